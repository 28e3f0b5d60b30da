"""``navfn-smt nav2-benchmark``: Nav2's planner benchmark (its three 100 m x 100 m maps, seed 33,
100 random start/goal pairs) for NavFn original and fixed, Dijkstra and A*; the protocol and
the metrics are :mod:`navfn_smt.nav2.benchmark`'s (docs/nav2-benchmark.md)."""

from __future__ import annotations

import json
import os
import sys
import time
from pathlib import Path

from ..errors import NavfnInputError
from .common import MODE_HELP, check_files, vars_of

# the repository's sibling folder of shared data (NAVFN_SHARED overrides it, as for the tests)
REPO = Path(__file__).resolve().parents[3]
MAPS_FOLDER = "nav2-benchmark-maps"
DEFAULT_MAPS = ("100by100_10.yaml", "100by100_15.yaml", "100by100_20.yaml")
EXAMPLE_PARAMS = Path(__file__).resolve().parent.parent / "examples" / "nav2" / "nav2_params.yaml"


def default_maps() -> list[Path]:
    """Nav2's three benchmark maps in ``../shared/nav2-benchmark-maps``; a clear error when absent."""
    folder = Path(os.environ.get("NAVFN_SHARED", REPO.parent / "shared")) / MAPS_FOLDER
    missing = [m for m in DEFAULT_MAPS if not (folder / m).is_file()]
    if missing:
        raise NavfnInputError(f"Nav2's benchmark maps are not in {folder} (missing {', '.join(missing)}): give the "
                              f"map YAML files on the command line (tools/planner_benchmarking/100by100_*.yaml of "
                              f"navigation2), or set NAVFN_SHARED to the folder holding {MAPS_FOLDER}/")
    return [folder / m for m in DEFAULT_MAPS]


def _check_args(args) -> list[Path]:
    from ..nav2.setup import check_params_file

    maps = [Path(m) for m in args.maps] if args.maps else default_maps()
    for m in maps:
        if not m.is_file():
            raise NavfnInputError(f"{m}: no such map YAML file")
    if args.pairs < 1:
        raise NavfnInputError(f"--pairs {args.pairs}: at least 1 pair")
    if args.margin < 0:
        raise NavfnInputError(f"--margin {args.margin}: a number of cells, at least 0")
    if not args.min_distance >= 0:
        raise NavfnInputError(f"--min-distance {args.min_distance:g}: a distance in metres, at least 0")
    check_params_file(args.params)
    if args.oracle and not Path(args.oracle).is_dir():
        raise NavfnInputError(f"--oracle {args.oracle}: no such build folder (navfn-smt oracle build SRC --out DIR)")
    check_files(args.json)
    return maps


def benchmark_map(map_yaml: Path, args, planners, oracles, distro: str, timing: str, arith=None, layers_arith=None):
    """The benchmark on one map: build its global costmap, draw the pairs, plan them; the model
    in the plugin's arithmetic ``arith`` and the layers' ``layers_arith`` (None: x86-64's)."""
    from ..nav2 import benchmark as B
    from ..nav2.setup import load_setup
    from ..report.tables import progress_bar

    t0 = time.perf_counter()
    print(f"nav2-benchmark: building the global costmap of {map_yaml} ...", file=sys.stderr, flush=True)
    setup = load_setup(map_yaml, args.params or EXAMPLE_PARAMS, distro, layers_arith=layers_arith)
    costmap_seconds = time.perf_counter() - t0
    draw = B.draw_pairs(setup.costmap, args.pairs, args.seed, args.max_cost, args.min_distance, args.margin)
    with progress_bar(len(planners) * len(draw.pairs), f"nav2-benchmark {map_yaml.name}") as advance:
        rows, diffs = B.run_benchmark(setup.costmap, setup.params, draw.pairs, planners, oracles, progress=advance,
                                      arith=arith)
    cm = setup.costmap
    return B.MapResult(str(map_yaml), (cm.size_x, cm.size_y), cm.resolution, setup.params, draw, rows, diffs,
                       timing, costmap_seconds, time.perf_counter() - t0)


def _print_map(res, args) -> None:
    from rich.table import Table

    from ..report.tables import console, duration

    def num(v, f):
        return "-" if v is None else format(v, f)

    t = Table(title=f"nav2-benchmark: {Path(res.map).name} ({res.size[0]}x{res.size[1]} cells of "
                    f"{res.resolution:.6g} m), {len(res.draw.pairs)} pairs, seed {args.seed}",
              caption=f"planning time: {res.timing}", caption_justify="left")
    t.add_column("planner")
    for c in ("pairs planned", "pairs failed", "average path length (m)", "average planning time (s)",
              "average cost", "maximum cost"):
        t.add_column(c, justify="right")
    for r in res.rows:
        t.add_row(r.planner.name, str(len(r.planned)), str(r.failed), num(r.mean_length, ".3f"),
                  num(r.mean_seconds, ".5f"), num(r.mean_cost, ".2f"), num(r.max_cost, "d"),
                  style="red" if r.failed else None)
    console.print(t)
    for c in res.fix:
        mode = "A*" if c.mode == "astar" else "Dijkstra"
        console.print(f"fixed against original, {mode}: the same path bit for bit on {c.same_path} of the "
                      f"{c.original_planned} pairs the original plans"
                      + (f"; a different path or none on pairs {c.changed}" if c.changed else "")
                      + (f"; pairs only the fixed plans: {c.fixed_only}" if c.fixed_only else ""),
                      style="bold red" if c.changed else None)
    for r in res.rows:
        errors = sorted({p.error for p in r.pairs if p.error is not None})
        if r.failed:
            console.print(f"{r.planner.name} fails {r.failed} pair(s): "
                          f"{[k for k, p in enumerate(r.pairs) if not p.ok]} ({', '.join(errors) or 'no pose'})")
    if res.differences:
        console.print(f"MODEL AND C++ DIFFER on {len(res.differences)} plan(s) of {Path(res.map).name}:",
                      style="bold red")
        for d in res.differences[:20]:
            console.print(f"  {d.planner}, pair {d.pair}: {d.what}: model {d.model}, C++ {d.cpp}", style="bold red")
    elif args.oracle:
        console.print(f"model and C++: every one of the {sum(len(r.pairs) for r in res.rows)} plans the same, "
                      f"poses bit for bit")
    console.print(f"{Path(res.map).name}: {res.draw.cells_drawn} cells drawn for {len(res.draw.pairs)} pairs; "
                  f"global costmap built in {duration(res.costmap_seconds)}, whole map {duration(res.seconds)}")


def _layers_arithmetic(planner):
    """The layers' arithmetic of the planner under test's build, for the global costmap both
    planners plan on (None, x86-64's, with a note, when the build has no layers program or its
    arithmetic is not one the model expresses: the C++ plugin is given the model's costmap
    either way)."""
    from ..errors import NavfnInputError
    from ..report.tables import console

    try:
        return planner.layers_arithmetic()  # refused without a layers program, or in an arithmetic not modelled
    except NavfnInputError as e:
        console.print(f"the global costmap is computed in x86-64's layers arithmetic ({e}); both planners plan on it")
        return None


def cmd_nav2_benchmark(args) -> int:
    """Run Nav2's planner benchmark on each map and print one table per map."""
    import contextlib

    from ..maps.suite import modes_of
    from ..nav2.benchmark import planners_for
    from ..report.tables import console, duration

    maps = _check_args(args)
    planners = planners_for(modes_of(args.mode))
    t0 = time.perf_counter()
    results = []
    with contextlib.ExitStack() as stack:
        oracles, distro, arith, layers_arith = None, "rolling", None, None
        timing = "the model's create_plan (jit), wall time per pair; give --oracle DIR for the C++'s"
        if args.oracle:
            from ..oracle.client import PluginOracle
            from ..spec import fixes
            from .common import planner_of

            planner = planner_of(args, fixes.AS_SHIPPED)  # the build's; each planner of the benchmark plans as it
            arith = planner.plugin_arithmetic()  # the model plans as the build was found to compute
            # a running C++ plugin per fix of the benchmark's planners (as shipped, each patched one), by its name
            oracles = {f.name: stack.enter_context(PluginOracle(args.oracle, f))
                       for f in dict.fromkeys([fixes.AS_SHIPPED, *(p.fix for p in planners)])}
            build = planner.doc
            distro = planner.distribution
            layers_arith = _layers_arithmetic(planner)
            timing = (f"the C++ NavfnPlanner::createPlan ({distro}, {planner.target}, "
                      f"{build['compiler']} {' '.join(build['flags'])}, oracle build {args.oracle}), its own time "
                      f"per pair; the model in {arith.name}")
        for m in maps:
            res = benchmark_map(m, args, planners, oracles, distro, timing, arith, layers_arith)
            _print_map(res, args)
            results.append(res)
    total = time.perf_counter() - t0
    console.print(f"nav2-benchmark: {len(maps)} map(s) in {duration(total)}")
    if args.json:
        from ..fileio import atomic_write_text, jsonable
        from ..nav2.benchmark import MARGIN, MAX_COST, MIN_DISTANCE

        doc = {"arguments": vars_of(args), "protocol": {"pairs": args.pairs, "seed": args.seed, "max_cost": args.max_cost,
                                                 "min_distance_m": args.min_distance, "margin_cells": args.margin,
                                                 "nav2_defaults": {"max_cost": MAX_COST, "min_distance_m": MIN_DISTANCE,
                                                                   "margin_cells": MARGIN}},
               "params_file": str(args.params or EXAMPLE_PARAMS), "timing": timing, "seconds": total,
               "maps": [r.to_json() for r in results]}
        atomic_write_text(args.json, json.dumps(jsonable(doc), indent=1))
    differences = sum(len(r.differences) for r in results)
    if differences:
        console.print(f"nav2-benchmark: the model and the C++ differ on {differences} plan(s): the figures above are "
                      f"the C++'s", style="bold red")
        return 1
    return 0


def register(sub) -> None:
    """The command's parser, its options and its handler."""
    from ..maps.suite import MODE_CHOICES
    from ..nav2.benchmark import MARGIN, MAX_COST, MIN_DISTANCE, PAIRS, SEED

    nb = sub.add_parser("nav2-benchmark", help="Nav2's planner benchmark (tools/planner_benchmarking) for NavFn "
                        "original and fixed, Dijkstra and A*")
    nb.add_argument("maps", nargs="*", metavar="MAP_YAML",
                    help=f"map_server YAML maps (default: the three of ../shared/{MAPS_FOLDER})")
    nb.add_argument("--pairs", type=int, default=PAIRS, metavar="N", help="random start/goal pairs per map")
    nb.add_argument("--seed", type=int, default=SEED, metavar="S", help="seed of the random generator (numpy's) that draws the pairs")
    nb.add_argument("--params", metavar="FILE", help="Nav2 params file: the plugin's parameters and the global "
                    "costmap's layers (default: the example nav2_params.yaml, static and inflation layers)")
    nb.add_argument("--oracle", metavar="DIR", help="also plan with the C++ plugin built in DIR (navfn-smt oracle "
                    "build): its own createPlan time is the planning time, and its poses must equal the model's "
                    "bit for bit (exit status 1 otherwise)")
    nb.add_argument("--json", metavar="FILE", help="write every figure, pair and per-pair result as JSON")
    nb.add_argument("--mode", choices=MODE_CHOICES, default="both", help=MODE_HELP)
    nb.add_argument("--margin", type=int, default=MARGIN, metavar="CELLS",
                    help="cells between a start or goal and the map's border, at least")
    nb.add_argument("--min-distance", type=float, default=MIN_DISTANCE, metavar="M",
                    help="start and goal more than this many metres apart")
    nb.add_argument("--max-cost", type=int, default=MAX_COST, metavar="C",
                    help="start and goal cells of costmap cost below this")
    nb.set_defaults(func=cmd_nav2_benchmark)
