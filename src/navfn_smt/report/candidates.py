"""The candidate fixes side by side (``navfn-smt fixes``): what each removes, what it changes where
NavFn as shipped plans, the paths it gives, and what it costs.

Every measure plans with the spec (the JIT where it is compiled), in one arithmetic of a build
at a time, NavFn as shipped beside each candidate of :data:`navfn_smt.spec.fixes.FIXES`:

- ``search``: for each failure kind of :mod:`navfn_smt.search.kinds`, on how many of the seeds a
  search of the candidate found a counterexample within the budget (a kind not found is not
  shown absent: a search is not a proof);
- ``committed``: the committed counterexamples of those kinds (``tests/data/counterexamples``)
  that the candidate still fails, judged by their kind's judge on the spec;
- ``suite``: every case of a suite, both modes: where NavFn as shipped returns a path, how many
  the candidate changes (path, potential or start potential, bit for bit); where it returns
  none, how many the candidate plans, and how many it still fails from a start the wave reached;
- ``quality``: the candidate's paths where it plans and NavFn as shipped does not, their length
  over the grid optimum (:mod:`.path_quality`);
- ``plugin``: the planner plugin's model on generated configurations, tolerance 0 and 2 cells:
  plans that differ from the shipped plugin's, and plans where it threw;
- with a build of the C++ (``--oracle DIR``): ``worst``, the fix's worst cases
  (:func:`navfn_smt.bench.bench_worst_cases`: time, path points, peak memory, as shipped and
  patched, each case in a fresh process, the best of two runs); with reports of
  ``oracle nav2-tests``: ``nav2_tests``, per distribution the sources' own tests and the tests
  the candidate's patch adds, as shipped and patched.
"""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

import numpy as np

FAILURE_KINDS = ("incomplete", "unreached", "far-trap", "path-without-potential", "cost")
COMMITTED = Path(__file__).resolve().parents[3] / "tests" / "data" / "counterexamples"


def _same(a, b) -> bool:
    return np.asarray(a).tobytes() == np.asarray(b).tobytes()


def search_counts(planner, kinds, seconds: float, seeds, progress=None) -> dict:
    """``{kind: seeds (of len(seeds)) on which a search found a counterexample}``; both modes
    share each search's ``seconds``; maps hunted up to 7x7."""
    from ..search.runner import run_search

    out = {}
    for kind in kinds:
        found = 0
        for seed in seeds:
            if progress:
                progress(f"search {kind} seed {seed} ({planner.label})")
            findings, _ = run_search(kind, "both", max_size=(7, 7) if kind != "cost" else None, timeout=seconds,
                                     seed=seed, planner=planner)
            found += bool(findings)
        out[kind] = found
    return out


def committed_counterexamples(kinds, arithmetic: str, root: Path = COMMITTED) -> list[tuple[Path, dict]]:
    """The committed counterexample directories of ``kinds`` found in ``arithmetic`` (NavFn as
    shipped or any variant), each with its counterexample.json."""
    import json

    if not root.is_dir():
        return []
    out = []
    for d in sorted(root.iterdir()):
        f = d / "counterexample.json"
        if not f.is_file():
            continue
        doc = json.loads(f.read_text())
        if doc.get("kind") in kinds and doc.get("arithmetic", "x86-64") == arithmetic:
            out.append((d, doc))
    return out


def still_failing(planner, committed) -> dict:
    """``{kind: [still failing, of]}``: the counterexamples of ``committed`` (:func:`committed_counterexamples`)
    whose kind's judge still holds with ``planner``, by kind."""
    from ..check import properties as P
    from ..maps.suite import load_map
    from ..search.counterexamples import judge_kind

    out: dict = {}
    for d, doc in committed:
        counts = out.setdefault(doc["kind"], [0, 0])
        counts[1] += 1
        sm = load_map(d)
        sx, sy, gx, gy = (int(v) for v in sm.cases[0])
        r = P.run(sm.costs, (sx, sy), (gx, gy), doc["mode"] == "astar", fix=planner.fix,
                  arith=planner.navfn_arithmetic())
        counts[0] += judge_kind(doc["kind"], r, doc, planner.navfn_arithmetic()) is not None
    return out


def suite_effects(maps, planner, original, modes=("astar", "dijkstra")) -> dict:
    """Every case of ``maps`` in each mode, ``original`` (NavFn as shipped) beside ``planner``:
    the counts of :mod:`this module <.candidates>` and the length over the optimum of the paths
    the candidate adds."""
    from ..backends import EXIT_CODES, get_backend
    from ..spec.constants import POT_HIGH
    from ..spec.extraction import ExtractionExit
    from .path_quality import GroupSummary, grid_distances, shape_of

    near = EXIT_CODES.index(ExtractionExit.NEAR_GOAL)
    high = np.float32(POT_HIGH)
    c = {"cases": 0, "original_plans": 0, "changed": 0, "original_fails": 0, "planned": 0, "fails": 0,
         "fails_from_a_reached_start": 0}
    added = GroupSummary()
    ours, theirs = get_backend("jit", planner), get_backend("jit", original)
    for sm in maps:
        cases = np.asarray(sm.cases, np.int64).reshape(-1, 4)
        goals = sorted({(int(gx), int(gy)) for gx, gy in cases[:, 2:4].tolist()})
        where = {g: i for i, g in enumerate(goals)}
        dist = None
        ny, nx = sm.costs.shape
        a, b = theirs.prepare(sm.costs), ours.prepare(sm.costs)
        for mode in modes:
            astar = mode == "astar"
            o, f = a.run_batch(cases, astar), b.run_batch(cases, astar)
            oo, fo = o["path_offsets"], f["path_offsets"]
            for i, (sx, sy, gx, gy) in enumerate(cases.tolist()):
                c["cases"] += 1
                op, fp = o["path"][oo[i]:oo[i + 1]], f["path"][fo[i]:fo[i + 1]]
                fixed_plans = f["exit"][i] == near
                if o["exit"][i] == near:
                    c["original_plans"] += 1
                    c["changed"] += not (fixed_plans and _same(op, fp)
                                         and _same(o["start_potential"][i], f["start_potential"][i]))
                    continue
                c["original_fails"] += 1
                if not fixed_plans:
                    c["fails"] += 1
                    c["fails_from_a_reached_start"] += bool(f["start_potential"][i] < high)
                    continue
                c["planned"] += 1
                if dist is None:
                    dist = grid_distances(sm.costs, goals)
                added.paths.append(shape_of(fp, float(dist[where[gx, gy], sy * nx + sx])))
    c["added_paths"] = added.row()
    return c


def plugin_effects(planner, configs: int = 60, seed: int = 0, distro: str = "rolling") -> dict:
    """The plugin's model on ``configs`` generated configurations (12 pose pairs each), with
    tolerance 0 and 2 cells, as shipped and with ``planner``'s fix: ``{tolerance: counts}``, the
    plans that differ (poses, bit for bit) and those where only one of them threw."""
    from ..difftest.plugin_live import generated_configs
    from ..nav2.plugin import create_plan

    out = {}
    for label, cells in (("0", 0.0), ("2 cells", 2.0)):
        n = {"plans": 0, "differ": 0, "planned_where_shipped_threw": 0, "threw_where_shipped_planned": 0}
        for cfg in generated_configs(distro, configs, seed, 12):
            base = replace(cfg.params, tolerance=cells * cfg.costmap.resolution)
            for start, goal in cfg.pairs:
                a = create_plan(cfg.costmap, start, goal, base, arith=None)
                b = create_plan(cfg.costmap, start, goal, replace(base, fix=planner.fix), arith=None)
                n["plans"] += 1
                pa = [(p.x, p.y) for p in a.poses]
                pb = [(p.x, p.y) for p in b.poses]
                n["differ"] += pa != pb or a.error != b.error
                n["planned_where_shipped_threw"] += a.error is not None and b.error is None
                n["threw_where_shipped_planned"] += a.error is None and b.error is not None
        out[label] = n
    return out


def nav2_tests(reports: list[dict], fix) -> dict:
    """From ``oracle nav2-tests`` reports (their JSON), per distribution: the sources' own tests
    passed as shipped and with ``fix``, and the tests ``fix``'s patch adds (or, for a fix made of
    several, those of any patch), failed as shipped and passed with ``fix``; {} where a report
    did not run ``fix``."""
    out = {}
    for doc in reports:
        if fix.name not in doc.get("variants", ()):
            continue
        res: dict = {}
        for r in doc["results"]:
            res.setdefault((r["program"], r["case"]), {})[r["variant"]] = r["status"]
        progs = doc["programs"]
        own = [k for k in res if progs[k[0]]["from"] == "the sources"]
        added = [k for k in res if progs[k[0]]["from"] != "the sources" and
                 (progs[k[0]].get("fix") == fix.name or fix.further is not None and fix.fallback is not None)]
        out[doc["distribution"]] = {
            "own": len(own), "own_passed_shipped": sum(res[k].get("original") == "passed" for k in own),
            "own_passed_patched": sum(res[k].get(fix.name) == "passed" for k in own),
            "added": len(added), "added_failed_shipped": sum(res[k].get("original") == "failed" for k in added),
            "added_passed_patched": sum(res[k].get(fix.name) == "passed" for k in added)}
    return out
