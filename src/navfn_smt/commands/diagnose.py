"""``navfn-smt diagnose``: the command (arguments and handler).

Wired into the command line by ``register(subparsers)``.  Exit status: 0 when every plan
succeeds, 1 when one fails (and is diagnosed), 2 on bad input.
"""

from __future__ import annotations

import sys
import time
from pathlib import Path

from ..errors import NavfnInputError
from .common import ORACLE_PLAN_HELP, add_planner_arguments, layers_arithmetic_of, planner_of, plugin_arithmetic_of


def _check_outputs(args) -> None:
    from ..fileio import check_writable
    from ..report.diagnose import check_picture_path

    for p in (args.json, args.picture):
        if p:
            check_writable(p)
    if args.picture:
        check_picture_path(args.picture)
    if args.json and args.picture and Path(args.json).resolve() == Path(args.picture).resolve():
        raise NavfnInputError("--json and --picture name the same file")


class _Progress:
    """A rich bar on a terminal; one plain line per goal otherwise (stderr)."""

    def __init__(self, total: int, label: str, quiet: bool):
        self.total, self.label, self.quiet, self.done = total, label, quiet, 0
        self.bar = None

    def __enter__(self):
        if not self.quiet and sys.stderr.isatty():
            from ..report.tables import progress_bar

            self.bar = progress_bar(self.total, self.label)
            self.advance = self.bar.__enter__()
        return self

    def step(self, d) -> None:
        self.done += 1
        if self.bar is not None:
            self.advance(1)
        elif not self.quiet:
            state = "ok" if d.ok else d.cause
            print(f"{self.label}: {self.done}/{self.total} ({d.goal.x:g}, {d.goal.y:g}) {state}", file=sys.stderr,
                  flush=True)

    def __exit__(self, *exc):
        if self.bar is not None:
            return self.bar.__exit__(*exc)
        return False


def cmd_diagnose(args) -> int:
    from ..report import diagnose as report
    from ..diagnose.core import diagnose
    from ..diagnose.inputs import load_inputs, parse_goals, pose_arg
    from ..distros import DEFAULT

    given = [o for o, v in (("--goal", args.goal), ("--goals", args.goals), ("--sweep", args.sweep)) if v]
    if len(given) != 1:
        raise NavfnInputError("give one of --goal X Y [YAW], --goals FILE or --sweep [N]" +
                              (f" (got {' and '.join(given)})" if given else ""))
    if args.max_steps is not None and args.max_steps < 1:
        raise NavfnInputError("--max-steps must be at least 1")
    start = pose_arg("start", args.start)
    _check_outputs(args)
    planner = planner_of(args)
    arith = plugin_arithmetic_of(planner, "diagnose")
    if args.sweep:
        return _sweep(args, start, planner, arith)
    goals = parse_goals(args.goals) if args.goals else [pose_arg("goal", args.goal)]
    setup = load_inputs(args.map, args.params, planner.distribution or DEFAULT, args.allow_outside,
                        args.resolution, tuple(args.origin), planner.fix, layers_arithmetic_of(planner, args.map))
    t0 = time.perf_counter()
    results = []
    batch = len(goals) > 1 or bool(args.goals)
    with _Progress(len(goals), "diagnose", quiet=not batch or args.quiet) as prog:
        for g in goals:
            d = diagnose(setup.costmap, start, g, setup.params, args.backend, what_ifs=not args.no_what_ifs,
                         max_steps=args.max_steps, arith=arith)
            results.append(d)
            prog.step(d)
    seconds = time.perf_counter() - t0
    report.print_text(args.map, setup, args.backend, results, planner)
    if args.json:
        report.write_json(args.json, report.report_doc(args.map, setup, args.backend, results, seconds, planner))
    if args.picture:
        title = f"{Path(args.map).name} ({'A*' if setup.params.use_astar else 'Dijkstra'})"
        if batch:
            report.write_batch_picture(args.picture, setup, results, title)
        else:
            report.write_picture(args.picture, results[0], title)
    return 0 if all(d.ok for d in results) else 1


def _sweep(args, start, planner, arith) -> int:
    """Every free cell (or a sample of N) as a goal from one robot pose: outcome counts, JSON, picture."""
    from ..report.sweep import render_sweep, write_summary_json
    from ..diagnose.inputs import load_inputs
    from ..diagnose.sweep import summary, sweep

    from ..distros import DEFAULT
    from ..spec.arithmetic import PLUGIN_X86_64

    if arith not in (None, PLUGIN_X86_64):
        raise NavfnInputError(f"--sweep computes in x86-64's arithmetic only so far (its compiled loops), not as "
                              f"{planner.label} does: diagnose the goals one by one there (--goals FILE)")
    n = None if args.sweep == "all" else _sample_size(args.sweep)
    setup = load_inputs(args.map, args.params, planner.distribution or DEFAULT, args.allow_outside,
                        args.resolution, tuple(args.origin), planner.fix, layers_arithmetic_of(planner, args.map))
    cm = setup.costmap
    from ..report.tables import progress_bar
    from ..diagnose.sweep import select_goals

    goals = select_goals(cm, n, args.seed)
    seen = [0]
    with progress_bar(len(goals), "sweep", enabled=not args.quiet) as advance:
        def progress(done: int, total: int) -> None:  # sweep reports how many are done; the bar counts steps
            advance(done - seen[0])
            seen[0] = done

        res = sweep(cm, start, setup.params, goals=goals, seed=args.seed, progress=progress)
    doc = summary(res)
    print(f"map      {args.map}: {cm.size_x}x{cm.size_y} cells, costmap layers: {', '.join(setup.layers)}")
    print(f"sweep    {doc['goals']} goals from ({start.x:g}, {start.y:g}), {doc['mode']}, {doc['seconds']} s")
    for name, k in doc["outcomes"].items():
        if k:
            print(f"  {name:20s} {k}")
    if args.json:
        write_summary_json(args.json, doc)
    if args.picture:
        render_sweep(res, cm.costs, (cm.origin_x, cm.origin_y), args.picture, title=Path(args.map).name)
    ok = doc["outcomes"].get("ok", 0) + doc["outcomes"].get("ok_tolerance", 0) + doc["outcomes"].get("same_pose", 0)
    return 0 if ok == doc["goals"] else 1


def _sample_size(v) -> int:
    try:
        n = int(v)
    except ValueError:
        raise NavfnInputError(f"--sweep takes a number of goals or 'all', got {v!r}") from None
    if n < 1:
        raise NavfnInputError("--sweep needs at least one goal")
    return n


def register(sub) -> None:
    from ..backends import BACKENDS
    from ..distros import DEFAULT, DISTROS

    d = sub.add_parser("diagnose", help="explain why a Nav2 NavFn plan fails and what fixes it")
    d.add_argument("map", help="a map_server YAML map, or a costmap file (.npy, .pgm) with --resolution")
    d.add_argument("--resolution", type=float, metavar="M",
                   help="for a costmap file (.npy of costmap values, row 0 at the bottom; or an 8-bit PGM of them): "
                   "metres per cell")
    d.add_argument("--origin", nargs=2, type=float, default=(0.0, 0.0), metavar=("X", "Y"),
                   help="for a costmap file: the world position of its lower-left corner (default: 0 0)")
    d.add_argument("--start", nargs="+", type=float, required=True, metavar="V",
                   help="the robot's pose: X Y [YAW] (world coordinates, metres, radians)")
    d.add_argument("--goal", nargs="+", type=float, metavar="V", help="the goal pose: X Y [YAW]")
    d.add_argument("--goals", metavar="FILE",
                   help="a batch of goals: one 'x y [yaw]' a line, or a YAML/JSON list (one report for all)")
    d.add_argument("--sweep", nargs="?", const="all", metavar="N",
                   help="instead of one goal, every free cell of the map as a goal (or a random sample of N): "
                   "counts of each outcome, --json summary, --picture of the outcomes")
    d.add_argument("--seed", type=int, default=0, help="random seed of the --sweep sample")
    d.add_argument("--params", metavar="FILE",
                   help="a Nav2 params file: the NavfnPlanner plugin's parameters (planner_server) and the global "
                   "costmap's layers (global_costmap); default: Nav2's defaults, static layer only")
    d.add_argument("--distro", default=None,
                   help=f"Nav2 distribution whose map loading and costmap rules apply ({', '.join(DISTROS)}; default "
                        f"{DEFAULT}, or the --oracle build's)")
    d.add_argument("--allow-outside", action="store_true",
                   help="let the map YAML name an image outside its own folder")
    add_planner_arguments(d, oracle_help=ORACLE_PLAN_HELP + ": the plugin's, NavFn's and the layers'; every step "
                          "of the diagnosis computes in it")
    d.add_argument("--backend", choices=BACKENDS, default="jit",
                   help="planner implementation: the numba JIT or the reference spec")
    d.add_argument("--json", metavar="FILE", help="write the machine-readable report (docs/diagnose.md)")
    d.add_argument("--picture", metavar="FILE",
                   help="a .png or .svg: costmap, potential, the path or the trap, the failing cell (with --goals: "
                   "every goal marked by its outcome)")
    d.add_argument("--no-what-ifs", action="store_true",
                   help="do not re-plan with use_astar, tolerance and allow_unknown changed")
    d.add_argument("--max-steps", type=int, metavar="N",
                   help="iterations of the unbudgeted calcPath before a trap is called undecided (default 400000)")
    d.add_argument("--quiet", action="store_true", help="no progress bar or progress lines")
    d.set_defaults(func=cmd_diagnose)
