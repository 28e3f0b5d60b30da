"""``navfn-smt render``: a picture of one planning case."""

from __future__ import annotations

from pathlib import Path

from ..errors import NavfnInputError
from .common import BACKEND_HELP, ORACLE_PLAN_HELP, add_planner_arguments, check_files, planner_of


def cmd_render(args) -> int:
    """Draw one planning case of a map into a picture file."""
    from ..maps.loading import is_yaml, load_case_map
    from ..maps.pictures import FORMATS, render_case

    if Path(args.output).suffix.lower() not in FORMATS:
        raise NavfnInputError(f"{args.output}: the picture must be .png or .svg")
    check_files(args.output)
    path = Path(args.map)
    m = load_case_map(path, args.allow_outside)
    if is_yaml(path) and not (args.start and args.goal):
        raise NavfnInputError(f"{path}: a map_server map has no cases; give --start X Y --goal X Y (cells)")
    if args.start or args.goal:
        if not (args.start and args.goal):
            raise NavfnInputError("--start and --goal go together")
        start, goal = tuple(args.start), tuple(args.goal)
    else:
        if not 0 <= args.case < len(m.cases):
            raise NavfnInputError(f"--case {args.case}: {path} has cases 0..{len(m.cases) - 1}")
        sx, sy, gx, gy = (int(v) for v in m.cases[args.case])
        start, goal = (sx, sy), (gx, gy)
    hl = None
    if args.highlight:
        if len(args.highlight) not in (2, 4):
            raise NavfnInputError("--highlight takes X Y (a cell) or X1 Y1 X2 Y2 (a segment)")
        hl = [tuple(args.highlight[i:i + 2]) for i in range(0, len(args.highlight), 2)]
    check_files(args.output)
    res = planner_of(args).backend(args.backend).prepare(m.costs).run(start, goal, astar=not args.dijkstra,
                                                                    trace=False)
    window = render_case(m.costs, res, start, goal, args.output,
                         title=f"{m.name} ({'Dijkstra' if args.dijkstra else 'A*'})", highlight=hl,
                         arrows=None if args.arrows == "auto" else args.arrows == "on", zoom=args.zoom)
    if window:
        x0, x1, y0, y1 = window
        ny, nx = m.costs.shape
        print(f"wrote {args.output} (showing x {x0}..{x1}, y {y0}..{y1} of the {nx}x{ny} map; "
              "--zoom full draws the whole map)")
    else:
        print(f"wrote {args.output}")
    return 0


def register(sub) -> None:
    """The command's parser, its options and its handler."""
    from ..backends import BACKENDS

    rd = sub.add_parser("render", help="draw a planning case: costmap, potential, path, gradient")
    rd.add_argument("map", help="a suite map directory or a map_server YAML")
    rd.add_argument("--allow-outside", action="store_true",
                    help="let a map_server YAML name an image outside its own folder")
    rd.add_argument("--case", type=int, default=0, metavar="I", help="case index in test.txt")
    rd.add_argument("--start", nargs=2, type=int, metavar=("X", "Y"), help="plan this start cell instead of a case")
    rd.add_argument("--goal", nargs=2, type=int, metavar=("X", "Y"), help="plan this goal cell instead of a case")
    rd.add_argument("--dijkstra", action="store_true", help="Dijkstra propagation (default: A*)")
    rd.add_argument("--backend", choices=BACKENDS, default="jit", help=BACKEND_HELP)
    add_planner_arguments(rd, oracle_help=ORACLE_PLAN_HELP)
    rd.add_argument("--highlight", nargs="+", type=float, metavar="V",
                    help="mark a cell (X Y) or a segment (X1 Y1 X2 Y2), e.g. a counterexample")
    rd.add_argument("--arrows", choices=("auto", "on", "off"), default="auto",
                    help="gradient arrows (auto: when the picture shows up to 60 cells a side)")
    rd.add_argument("--zoom", choices=("auto", "full"), default="auto",
                    help="auto: on a map over 80 cells a side, show only the neighbourhood of the start, goal and "
                    "path when they fill less than half of it; full: always the whole map")
    rd.add_argument("-o", "--output", required=True, metavar="FILE", help="a .png or .svg file")
    rd.set_defaults(func=cmd_render)
