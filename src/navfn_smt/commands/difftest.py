"""``navfn-smt difftest``: every case of a suite against its golden files, bit for bit."""

from __future__ import annotations

from ..errors import NavfnInputError
from .common import BACKEND_HELP, MODE_HELP, add_planner_arguments, check_files, planner_of, suite_or_example, with_patch


def cmd_difftest(args) -> int:
    """Compare every case of a suite with its golden files; exit 1 on any disagreement."""
    from ..difftest.runner import count_cases, run_suite
    from ..maps.suite import modes_of
    from ..engine import engine
    from ..report import difftest as report
    from ..report.tables import progress_bar
    from ..spec import fixes

    check_files(args.json)
    fix = with_patch(fixes.named(args.variant), "difftest")
    if not fix.shipped and args.level == "costmap":
        raise NavfnInputError("--variant is for NavFn and the planner plugin; a fix does not touch the costmap")
    if args.level != "navfn":
        return _level(args)
    if args.unbounded and not args.oracle:
        raise NavfnInputError("--unbounded compares with the C++ built with unbounded buffers: give --oracle DIR")
    if not fix.shipped and not args.oracle:
        raise NavfnInputError(f"--variant {fix.name} compares with the C++ built with the fix's patch "
                              f"(patches/{fix.patches}/): give --oracle DIR (the golden files are the original's)")
    if not fix.shipped and args.unbounded:
        raise NavfnInputError(f"--variant {fix.name} and --unbounded exclude each other (no C++ build has both)")
    suite, modes = suite_or_example(args.suite), modes_of(args.mode)
    eng = engine(args.jobs, args.scheduler)
    planner = planner_of(args)
    if args.oracle:
        return _live(args, suite, modes, planner)
    total = count_cases(suite, modes)
    label = f"difftest {suite} ({args.backend}{f', {planner.arithmetic.name} arithmetic' if args.target else ''})"
    with progress_bar(total, label, enabled=not args.quiet) as advance:
        summary = run_suite(suite, modes, args.backend, eng=eng, total=total,
                            progress=lambda o: advance(o.cases), planner=planner).as_dict()
    report.table(summary)
    if args.json:
        report.write_json(args.json, suite, args.backend, modes, summary)
    report.closing_line(summary)
    return 0 if summary["failed"] == 0 else 1


def _live(args, suite, modes, planner) -> int:
    """``--oracle DIR``: the spec against the C++ NavFn built in DIR, live, every case."""
    from ..difftest.live import run_live
    from ..difftest.runner import case_count
    from ..maps.suite import discover
    from ..oracle.client import Oracle
    from ..report import difftest as report
    from ..report.tables import progress_bar

    total = sum(case_count(d) for d in discover(suite)) * len(modes)  # no golden files needed
    # the C++ of the planner's fix (navfn-traced as shipped, navfn-<fix> patched) or the unbounded one
    program = {"unbounded": True} if args.unbounded else {"fix": planner.fix}
    library = (planner.doc.get("library") or {}).get("file", "") if planner.fix.shipped and not args.unbounded else ""
    if library:
        program = {"traced": False}  # a library build: the library's own code, without the white-box trace
        print(f"{args.oracle} links a NavFn library ({library}): compared without the white-box trace (path, "
              f"potential, start reached)")
    planner.navfn_arithmetic()  # the spec computes in the build's arithmetic, found in the build
    with Oracle(args.oracle, **program) as oracle:
        label = f"difftest {suite} ({args.backend}, {planner.label})"
        with progress_bar(total, label, enabled=not args.quiet) as advance:
            summary = run_live(suite, modes, args.backend, oracle, progress=lambda o: advance(o.cases),
                               unbounded=args.unbounded, planner=planner).as_dict()
    report.table(summary)
    if args.json:
        report.write_json(args.json, suite, args.backend, modes, summary)
    report.closing_line(summary)
    return 0 if summary["failed"] == 0 else 1


def _level(args) -> int:
    """``--level plugin|costmap``: the model of that level against the C++ built in ``--oracle DIR``."""
    if not args.oracle:
        raise NavfnInputError(f"--level {args.level} runs against the C++: give --oracle DIR (navfn-smt oracle build)")
    if args.suite:
        raise NavfnInputError(f"--level {args.level} generates its own cases (or takes --map): no suite")
    planner = planner_of(args)
    if args.level == "plugin":
        return _plugin_level(args, planner)
    return _costmap_level(args, planner)


def _level_report(args, summary: dict, planner, arith) -> int:
    """The level's table, its JSON with ``--json`` (both name the build's target and the
    arithmetic ``arith`` the model computed in), exit 1 on any disagreement."""
    from ..report import difftest as report

    summary = {**summary, "target": planner.target, "arithmetic": arith.name}
    report.level_table(summary)
    if args.json:
        report.write_level_json(args.json, summary)
    return 0 if summary["failed"] == 0 else 1


def _costmap_level(args, planner) -> int:
    from ..difftest.layers_live import generated_configs, map_config, run_layers_live
    from ..oracle.client import LayersOracle
    from ..report.tables import progress_bar

    if args.sweep:
        raise NavfnInputError("--sweep is for --level plugin")
    if args.params and not args.map:
        raise NavfnInputError("--params goes with --map")
    arith = planner.layers_arithmetic()  # the model computes as the build was found to
    distro = planner.distribution
    with LayersOracle(args.oracle) as oracle:
        if args.map:
            cfg, notes = map_config(args.map, args.params, distro)
            configs = [cfg]
            for note in notes:
                print(note)
        else:
            configs = generated_configs(distro, args.configs, args.seed)
        label = (f"difftest --level costmap (the layer models against the C++ layers of {distro}, "
                 f"{planner.target}, {arith.name})")
        with progress_bar(1 if args.map else args.configs, label, enabled=not args.quiet) as advance:
            summary = run_layers_live(configs, oracle, progress=advance, arith=arith).as_dict()
    return _level_report(args, summary, planner, arith)


def _plugin_level(args, planner) -> int:
    from ..difftest.plugin_live import generated_configs, map_configs, run_plugin_live
    from ..oracle.client import PluginOracle
    from ..report.tables import progress_bar

    from dataclasses import replace

    arith = planner.plugin_arithmetic()  # the model computes as the build was found to
    distro = planner.distribution
    with PluginOracle(args.oracle, planner.fix) as oracle:
        if args.map:
            configs = list(map_configs(args.map, args.params, distro, args.configs, args.seed, args.pairs, args.sweep))
        else:
            configs = list(generated_configs(distro, args.configs, args.seed, args.pairs))
        configs = [replace(c, params=replace(c.params, fix=planner.fix)) for c in configs]
        total = sum(len(c.pairs) for c in configs)
        label = (f"difftest --level plugin ({args.backend} model, {planner.variant}, against the C++ plugin of "
                 f"{distro} for {planner.target}: {arith.name})")
        with progress_bar(total, label, enabled=not args.quiet) as advance:
            summary = run_plugin_live(configs, oracle, args.backend, progress=advance, arith=arith).as_dict()
    return _level_report(args, summary, planner, arith)


def register(sub) -> None:
    """The command's parser, its options and its handler."""
    from ..backends import BACKENDS
    from ..maps.suite import MODE_CHOICES
    from ..engine import add_arguments as add_engine_arguments

    dt = sub.add_parser("difftest", help="compare every case of a suite with its golden files")
    dt.add_argument("suite", nargs="?", help="suite directory (default: the example suite shipped with the package)")
    dt.add_argument("--mode", choices=MODE_CHOICES, default="both", help=MODE_HELP)
    dt.add_argument("--backend", choices=BACKENDS, default="jit", help=BACKEND_HELP)
    dt.add_argument("--oracle", metavar="DIR", help="compare with the C++ NavFn built in DIR (navfn-smt oracle "
                    "build), run live on every case, instead of the golden files")
    dt.add_argument("--unbounded", action="store_true", help="with --oracle: the C++ and the spec both with "
                    "priority buffers that never drop a push")
    add_planner_arguments(dt, variant_help="; a fix with patches needs --oracle (the build's C++ with its patch: "
                          "navfn-<fix>, navfn-plugin-<fix>); --target: the golden files were recorded from a build "
                          "in this arithmetic")
    dt.add_argument("--level", choices=("navfn", "plugin", "costmap"), default="navfn",
                    help="navfn: NavFn on a suite (default); plugin: Nav2's createPlan on generated costmaps, poses "
                    "and parameters (or --map); costmap: the static and inflation layers on generated grids and "
                    "parameters; plugin and costmap need --oracle")
    dt.add_argument("--configs", type=int, default=200, metavar="N",
                    help="--level plugin|costmap: generated configurations (default: %(default)s)")
    dt.add_argument("--pairs", type=int, default=24, metavar="N",
                    help="--level plugin: pose pairs per configuration (default: %(default)s)")
    dt.add_argument("--seed", type=int, default=0, help="--level plugin|costmap: the generator's seed")
    dt.add_argument("--map", metavar="YAML", help="--level plugin|costmap: a map_server map (with --params, its "
                    "global costmap and planner parameters) instead of generated costmaps")
    dt.add_argument("--params", metavar="FILE", help="--level plugin|costmap --map: a Nav2 params file")
    dt.add_argument("--sweep", nargs="+", type=float, metavar="X", help="--level plugin --map: from the start "
                    "pose X Y [YAW] to the centre of every cell of the map")
    add_engine_arguments(dt, what="difftest chunks")
    dt.add_argument("--json", metavar="FILE", help="write per-map counts and every disagreement as JSON")
    dt.add_argument("--quiet", action="store_true", help="no progress bar")
    dt.set_defaults(func=cmd_difftest)
