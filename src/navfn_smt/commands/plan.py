"""``navfn-smt plan``: NavFn between two cells, or Nav2's planner plugin between world poses."""

from __future__ import annotations

from pathlib import Path

from ..errors import NavfnInputError
from ..distros import DEFAULT
from .common import (BACKEND_HELP, ORACLE_PLAN_HELP, add_planner_arguments, cell, layers_arithmetic_of,
                     planner_of, plugin_arithmetic_of)


def _plan_world(args) -> int:
    """Plan between world poses on a map_server map, as Nav2's NavfnPlanner plugin does."""
    from ..maps.loading import is_yaml
    from ..nav2.plugin import check_pose, create_plan
    from ..nav2.setup import COSTMAP_FILES, check_params_file, load_setup
    from ..report import plan as report

    if not is_yaml(args.map) and Path(args.map).suffix.lower() not in COSTMAP_FILES:
        raise NavfnInputError(f"{args.map}: --world needs a map_server YAML map or a costmap (.npy, .pgm)")
    if args.size:
        raise NavfnInputError("--size is for a raw map file, not a map_server map")
    start, goal = check_pose("start", args.start), check_pose("goal", args.goal)
    check_params_file(args.params)
    planner = planner_of(args)
    arith = plugin_arithmetic_of(planner, "--world")
    overrides = {"use_astar": True if args.astar else False if args.dijkstra else None, "fix": planner.fix}
    setup = load_setup(args.map, args.params, planner.distribution or DEFAULT, args.allow_outside, overrides,
                       args.resolution, tuple(args.origin), layers_arithmetic_of(planner, args.map))
    run = create_plan(setup.costmap, start, goal, setup.params, args.backend, arith)
    report.plugin_plan(setup, run, start, goal, args.backend, args.json)
    return 0 if run.ok else 1


def cmd_plan(args) -> int:
    """Plan on one map and print the path (NavFn itself, or Nav2's plugin with --world)."""
    from ..maps.loading import load_costs
    from ..report import plan as report

    if args.world:
        return _plan_world(args)
    if args.params:
        raise NavfnInputError("--params is for --world planning (Nav2's plugin reads it)")
    if args.astar and args.dijkstra:
        raise NavfnInputError("--astar and --dijkstra exclude each other")
    mode = "dijkstra" if args.dijkstra else "astar"
    start, goal = cell("start", args.start), cell("goal", args.goal)
    planner = planner_of(args)
    costs = load_costs(args.map, args.size, args.allow_outside, planner.distribution or DEFAULT)
    res = planner.backend(args.backend).prepare(costs).run(start, goal, astar=not args.dijkstra, trace=False)
    report.cell_plan(res, mode, args.backend, start, goal, args.json, costs, planner)
    return 0 if len(res.path) else 1


def register(sub) -> None:
    """The command's parser, its options and its handler."""
    from ..backends import BACKENDS
    from ..distros import DISTROS

    pl = sub.add_parser("plan", help="plan on one map and print the path")
    pl.add_argument("map", help="a suite map directory (test.txt gives the size), a map_server YAML, "
                    "or a raw map file with --size")
    pl.add_argument("--size", nargs=2, type=int, metavar=("W", "H"), help="size of a raw map file")
    pl.add_argument("--start", nargs="+", type=float, required=True, metavar=("X Y", "YAW"),
                    help="NavFn's start cell X Y (where the path begins); with --world the robot's pose X Y [YAW] "
                    "in metres and radians")
    pl.add_argument("--goal", nargs="+", type=float, required=True, metavar=("X Y", "YAW"),
                    help="NavFn's goal cell X Y (where propagation begins); with --world the goal pose X Y [YAW]")
    pl.add_argument("--world", action="store_true",
                    help="plan between world poses on a map_server YAML map exactly as Nav2's NavfnPlanner plugin "
                    "(createPlan) does: prints the poses Nav2 publishes, or the exception it throws (exit 1)")
    pl.add_argument("--params", metavar="FILE",
                    help="with --world: a Nav2 params file; the planner_server's NavfnPlanner parameters and the "
                    "global_costmap's layers are read from it (default: Nav2's defaults, static layer only)")
    pl.add_argument("--resolution", type=float, metavar="M",
                    help="with --world on a costmap file (.npy of costmap values, row 0 at the bottom; or an 8-bit "
                    "PGM of them): metres per cell")
    pl.add_argument("--origin", nargs=2, type=float, default=(0.0, 0.0), metavar=("X", "Y"),
                    help="with --world on a costmap file: the world position of its lower-left corner "
                    "(default: 0 0)")
    pl.add_argument("--allow-outside", action="store_true",
                    help="let a map_server YAML name an image outside its own folder")
    pl.add_argument("--distro", choices=tuple(DISTROS),
                    help=f"Nav2 distribution whose map loading and costmap rules apply (default: {DEFAULT}, "
                    "or with --oracle the build's)")
    alg = pl.add_mutually_exclusive_group()
    alg.add_argument("--dijkstra", action="store_true",
                     help="Dijkstra propagation (default: A* on cells; with --world the params file's use_astar, "
                     "whose Nav2 default is Dijkstra)")
    alg.add_argument("--astar", action="store_true", help="A* propagation (with --world: overrides use_astar)")
    pl.add_argument("--backend", choices=BACKENDS, default="jit", help=BACKEND_HELP)
    add_planner_arguments(pl, oracle_help=ORACLE_PLAN_HELP + " (with --world, the plugin's and the layers')")
    pl.add_argument("--json", action="store_true", help="print a JSON object")
    pl.set_defaults(func=cmd_plan)
