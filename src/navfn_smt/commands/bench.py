"""``navfn-smt bench``: timing of a suite, of generated maps, of the whole-map sweep or of the cost climb."""

from __future__ import annotations

from ..errors import NavfnInputError
from .common import MODE_HELP, TARGET_HELP, check_files, planner_of, suite_or_example, with_patch


def cmd_bench(args) -> int:
    """Time the planner on a whole suite, or on generated maps with ``--size``."""
    from ..bench import SEED, bench_sizes, bench_suite, check_sizes
    from ..report import bench as report

    if args.climb is not None:  # the cost climb
        from ..bench import bench_climb

        check_files(args.json)
        rows = bench_climb(args.climb, args.mode)  # refuses --climb below 1 before any work
        report.climb_table(rows)
        if args.json:
            report.write_climb_json(args.json, 0, rows)
        return 0
    if args.sweep is not None:  # whole-map sweep benchmark
        from ..bench import bench_sweep

        goals = args.sweep_astar_goals
        if goals != "all":
            try:
                goals = int(goals)
            except ValueError:
                goals = 0
            if goals < 1:
                raise NavfnInputError(f"--sweep-astar-goals {args.sweep_astar_goals}: a number of goals "
                                      "(at least 1) or 'all'")
        check_files(args.json)
        rows = bench_sweep(args.sweep, args.mode, goals)
        report.sweep_table(rows)
        if args.json:
            report.write_sweep_json(args.json, 0, rows)
        return 0
    fix = _fix_of(args)
    if args.worst_cases:
        if not args.oracle:
            raise NavfnInputError("bench --worst-cases times the C++ as shipped and as patched: give --oracle DIR")
        from ..bench import bench_worst_cases
        from ..oracle.build import load_build
        from ..oracle.client import navfn_program
        from ..spec.fix import FIX as THE_FIX

        check_sizes(args.worst_cases, 1)
        check_files(args.json)
        build = load_build(args.oracle)
        worst = THE_FIX if fix.shipped else fix  # the fix of docs/fix.md unless --variant names another
        program = navfn_program(worst, traced=False)
        if program not in build["programs"]:
            why = build.get("skipped", {}).get(program, "build it again with `navfn-smt oracle build`")
            raise NavfnInputError(f"{args.oracle}: this build has no {program} ({why})")
        rows = bench_worst_cases(args.worst_cases, args.oracle, worst)
        report.worst_cases_table(args.oracle, rows, program)
        if args.json:
            report.write_worst_cases_json(args.json, args.oracle, build, rows)
        return 0
    if args.size:
        check_sizes(args.size, args.repeat)
        check_files(args.json)
        rows = bench_sizes(args.size, args.backend, args.repeat, args.mode)
        report.sizes_table(rows)
        if args.json:
            report.write_sizes_json(args.json, SEED, rows)
        return 0
    suite = suite_or_example(args.suite)
    check_files(args.json)
    planner = planner_of(args)
    if not fix.shipped:
        if not args.oracle:
            raise NavfnInputError(f"bench --variant {fix.name} times the C++ as shipped and as patched: give "
                                  f"--oracle DIR")
        from ..bench import bench_fix

        rows = bench_fix(suite, args.oracle, args.mode, args.repeat, fix)
        report.fix_table(suite, rows, fix.name)
        if args.json:
            report.write_suite_json(args.json, suite, rows)
        return 0
    if args.oracle:
        from ..bench import bench_oracle
        from ..oracle.client import Oracle

        with Oracle(args.oracle, traced=False) as oracle:
            rows = bench_oracle(suite, oracle, args.mode, planner)
            report.oracle_table(suite, planner.distribution, rows)
        if args.json:
            report.write_suite_json(args.json, suite, rows)
        return 0
    rows = bench_suite(suite, args.backend, args.mode, planner)
    report.suite_table(suite, rows)
    if args.json:
        report.write_suite_json(args.json, suite, rows)
    return 0


def _fix_of(args):
    """The fix ``--variant`` names (:mod:`navfn_smt.spec.fixes`)."""
    from ..spec import fixes

    return with_patch(fixes.named(args.variant), "bench")


def register(sub) -> None:
    """The command's parser, its options and its handler."""
    from ..backends import BACKENDS
    from ..maps.suite import MODE_CHOICES
    from ..spec import fixes

    be = sub.add_parser("bench", help="time the planner: a whole suite, or generated maps with --size")
    be.add_argument("suite", nargs="?", help="suite directory (default: the example suite)")
    be.add_argument("--size", nargs="+", type=int, metavar="N",
                    help="instead of a suite, plan on generated NxN open and random-cost maps")
    be.add_argument("--worst-cases", nargs="+", type=int, metavar="N",
                    help="with --oracle: the fix's worst cases on generated NxN maps (a serpentine, a start on a "
                         "wall, Nav2 #4655's room), on the C++ as shipped and as patched (the fix of docs/fix.md, "
                         "or the one --variant names), each case in a fresh process: time, path points, peak memory")
    be.add_argument("--backend", choices=(*BACKENDS, "all"), default="all", help="planner implementations timed")
    be.add_argument("--mode", choices=MODE_CHOICES, default="both", help=MODE_HELP)
    be.add_argument("--repeat", type=int, default=3, metavar="K", help="plans per map and mode with --size (best is kept)")
    be.add_argument("--oracle", metavar="DIR", help="time the C++ NavFn built in DIR (navfn-smt oracle build) and "
                    "the JIT on the suite in the same run, and print their ratio")
    be.add_argument("--variant", choices=fixes.NAMES, default=fixes.DEFAULT.name,
                    help=fixes.HELP + "; a fix with patches: with --oracle, time the cases the original plans on "
                    "the C++ as shipped and as patched with the fix (navfn-<fix>), and on the JIT without and with "
                    "it (--repeat times, best kept)")
    be.add_argument("--target", metavar="NAME", help=TARGET_HELP + " (a suite's timing)")
    be.add_argument("--json", metavar="FILE", help="write the figures as JSON")
    be.add_argument("--sweep", nargs="?", type=int, const=400, metavar="N",
                    help="instead, time the whole-map sweep (every free cell a goal of one robot pose) on a "
                         "generated NxN rooms costmap (default 400)")
    be.add_argument("--sweep-astar-goals", default="2000", metavar="K|all",
                    help="goals sampled for the A* sweep (one propagation each; default 2000)")
    be.add_argument("--climb", nargs="?", type=int, const=50_000, metavar="MAPS",
                    help="instead, time the cost climb of search cost on 5x7 maps: MAPS maps per mode "
                         "(default 50000) with the compiled steps and with the Python step")
    be.set_defaults(func=cmd_bench)
