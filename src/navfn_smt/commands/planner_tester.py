"""``navfn-smt planner-tester``: what Nav2's planning system tests check of NavFn (the NavFn cases
of ``test_planner_plugins.cpp``, ``PlannerTester``'s random test), on the plugin as shipped and
fixed: the specification's model, and with ``--oracle DIR`` the C++ plugin of that build, whose
poses must equal the model's bit for bit (:mod:`navfn_smt.nav2.planner_tester`)."""

from __future__ import annotations

import json
import time
from pathlib import Path

from ..errors import NavfnInputError
from .common import check_files, check_positive, vars_of

EXAMPLE_MAP = Path(__file__).resolve().parent.parent / "examples" / "mapserver" / "room.yaml"


def _fixes() -> tuple:
    """The planners compared: NavFn as shipped and with the fix of docs/fix.md."""
    from ..spec import fixes
    from ..spec.fix import FIX as THE_FIX

    return fixes.AS_SHIPPED, THE_FIX


def _check_args(args) -> list[Path]:
    maps = [Path(m) for m in args.maps] or [EXAMPLE_MAP]
    for m in maps:
        if not m.is_file():
            raise NavfnInputError(f"{m}: no such map YAML file")
    check_positive("--pairs", args.pairs)
    if args.oracle and not Path(args.oracle).is_dir():
        raise NavfnInputError(f"--oracle {args.oracle}: no such build folder (navfn-smt oracle build SRC --out DIR)")
    check_files(args.json)
    return maps


def _planners(args, stack) -> tuple[dict, str]:
    """``{(who, variant): planner}``: the model of each variant, and with ``--oracle`` the C++'s;
    and the distribution they plan as."""
    from dataclasses import replace

    from ..nav2 import planner_tester as T

    planners, distro, arith = {}, args.distro or "rolling", None
    if args.oracle:
        from ..oracle.client import PluginOracle
        from .common import planner_of

        planner = planner_of(args, _fixes()[0])
        distro, arith = planner.distribution, planner.plugin_arithmetic()
        for fix in _fixes():
            planners[("C++", fix.name)] = T.oracle_planner(stack.enter_context(PluginOracle(args.oracle, fix)))
    for fix in _fixes():
        model = T.model_planner(fix, arith)
        planners[("model", fix.name)] = (lambda m: (lambda cm, p, pairs: m(cm, replace(p, distro=distro), pairs)))(model)
    return planners, distro


def _same(a, b) -> bool:
    """The model's answer and the C++'s: the same exception, the same poses bit for bit."""
    from ..nav2.benchmark import first_difference

    return first_difference(a.error, a.poses, b.error, b.poses) is None


def cmd_planner_tester(args) -> int:
    import contextlib

    from ..nav2 import planner_tester as T
    from ..nav2.mapserver import load_map_yaml
    from ..nav2.params import PlannerParams
    from ..report.tables import console, duration

    maps = _check_args(args)
    t0 = time.perf_counter()
    doc = {"arguments": vars_of(args), "plugin_cases": {}, "random": {}, "differences": []}
    with contextlib.ExitStack() as stack:
        planners, distro = _planners(args, stack)
        doc["distribution"] = distro
        answers = {}

        def recording(key, plan):
            def run(cm, params, pairs):
                out = plan(cm, params, pairs)
                answers.setdefault(key, []).extend(out)
                return out
            return run

        for key, plan in planners.items():
            doc["plugin_cases"][" ".join(key)] = [vars(c) for c in T.run_plugin_cases(recording(key, plan))]
        for m in maps:
            cm = T.tester_costmap(load_map_yaml(m).occupancy)
            for key, plan in planners.items():
                console.print(f"planner-tester: the random test on {m.name} ({cm.size_x}x{cm.size_y}), {' '.join(key)} ...")
                results = T.run_random_test(recording(key, plan), cm, args.seed, args.pairs,
                                            params=PlannerParams(use_astar=True))
                doc["random"].setdefault(str(m), {})[" ".join(key)] = [
                    {**vars(r), "passed": r.passed} for r in results]
        if args.oracle:  # the C++ and the model, answer by answer
            for v in (f.name for f in _fixes()):
                model, cpp = answers[("model", v)], answers[("C++", v)]
                bad = [k for k, (a, b) in enumerate(zip(model, cpp)) if not _same(a, b)]
                if len(model) != len(cpp) or bad:
                    doc["differences"].append({"variant": v, "answers": len(model), "differ": bad[:20]})
            doc["compared_answers"] = sum(len(answers[("model", f.name)]) for f in _fixes())
    doc["seconds"] = time.perf_counter() - t0
    _print(doc, console, duration)
    if args.json:
        from ..fileio import atomic_write_text, jsonable

        atomic_write_text(args.json, json.dumps(jsonable(doc), indent=1) + "\n")
    return 1 if doc["differences"] else 0


def _print(doc, console, duration) -> None:
    from rich.table import Table

    keys = list(doc["plugin_cases"])
    t = Table(title=f"Nav2's planning system tests, their NavFn checks on the plugin ({doc['distribution']})")
    t.add_column("test")
    for k in keys:
        t.add_column(k)
    cases = {k: {c["name"]: c for c in doc["plugin_cases"][k]} for k in keys}
    for name in cases[keys[0]]:
        t.add_row(f"testPluginMap.{name}", *[("passed" if cases[k][name]["ok"] else f"failed: {cases[k][name]['why']}")
                                            for k in keys])
    for m, by in doc["random"].items():
        cells = []
        for k in keys:
            rs = by[k]
            verdict = "passed" if any(r["passed"] for r in rs) else "failed"
            cells.append(f"{verdict}: " + ", ".join(f"{r['failed']}/{r['pairs']} failed" for r in rs))
        t.add_row(f"testWithHundredRandomEndPoints on {Path(m).name}", *cells)
    console.print(t)
    if "compared_answers" in doc:
        if doc["differences"]:
            console.print(f"MODEL AND C++ DIFFER: {doc['differences']}", style="bold red")
        else:
            console.print(f"model and C++: each of the {doc['compared_answers']} answers the same, poses bit for bit")
    console.print(f"planner-tester: {duration(doc['seconds'])}")


def register(sub) -> None:
    """The command's parser, its options and its handler."""
    from ..distros import CHECKED as DISTROS
    from ..nav2.planner_tester import RANDOM_PAIRS

    p = sub.add_parser("planner-tester", help="the NavFn checks of Nav2's planning system tests (test_planner_plugins, "
                       "PlannerTester's random test) on the plugin, as shipped and fixed")
    p.add_argument("maps", nargs="*", metavar="MAP_YAML",
                   help="map_server YAML maps for the random test, read as PlannerTester reads its map (1 m a cell; "
                   "default: the example room)")
    p.add_argument("--pairs", type=int, default=RANDOM_PAIRS, metavar="N", help="start/goal pairs per draw (default: 100)")
    p.add_argument("--seed", type=int, default=1, help="the seed of the first draw (default: 1; a further draw, "
                   "when one fails, takes the next seed)")
    p.add_argument("--distro", choices=tuple(DISTROS),
                   help="whose navfn_planner.cpp the model plans as (default: an --oracle build's own, else rolling)")
    p.add_argument("--oracle", metavar="DIR", help="also run the C++ plugin of the build in DIR, as shipped and "
                   "fixed; its answers must equal the model's bit for bit (exit status 1 otherwise)")
    p.add_argument("--json", metavar="FILE", help="write every verdict as JSON")
    p.set_defaults(func=cmd_planner_tester)
