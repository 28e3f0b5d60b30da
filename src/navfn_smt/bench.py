"""Benchmarks (``navfn-smt bench``): speed goals live here, not in timed tests.

* suite mode: plans every case of a suite per backend and mode, and reports cases per
  second (planning only: loading files and comparing with golden outputs excluded; the
  JIT plans a map's cases in one compiled call, the reference one call per case);
* size mode (``--size N ...``): plans on generated NxN maps, an open one (cost 50) and
  a random-cost one (costs 50..253 from ``numpy.random.default_rng(12345)``), both with
  a lethal border, from start (5, 5) to goal (N-6, N-6), and reports seconds per plan
  and the planner's working memory (its arrays; no trace is recorded when timing);
* worst-case mode (``--worst-cases N ... --oracle DIR``): a fix's added work and memory on
  generated NxN maps where it acts or floods (:func:`worst_case_maps`), on the C++ of a build as
  shipped (``navfn-plain``) and as patched (``navfn-plain-fixed``, or ``navfn-plain-<fix>``),
  each case in a fresh process: planning seconds, path points and peak memory;
* climb mode (``--climb [MAPS]``): the cost climb of ``search cost`` on 5x7 maps, MAPS maps
  per mode with the compiled plateau steps and again with the Python step, from the same
  seed: maps per second of each, and a check that both made the same climb.
"""

from __future__ import annotations

import time
from pathlib import Path

import numpy as np

from .backends import BACKENDS, get_backend
from .errors import NavfnInputError
from .inputs import check_cells
from .maps.suite import discover, load_map, modes_of
from .spec.constants import COST_OBS
from .spec.fix import FIX as THE_FIX
from .under_test import ORIGINAL, PlannerUnderTest
from .report.tables import progress_bar, progress_counts

SEED = 12345


def generated_map(kind: str, n: int) -> np.ndarray:
    """The benchmark maps: ``open`` (all cost 50) or ``random`` (50..253), lethal border."""
    if kind == "open":
        c = np.full((n, n), 50, dtype=np.uint8)
    elif kind == "random":
        c = np.random.default_rng(SEED).integers(50, 254, size=(n, n), dtype=np.uint8)
    else:
        raise ValueError(kind)
    c[0, :] = c[-1, :] = c[:, 0] = c[:, -1] = COST_OBS
    return c


def serpentine(n: int) -> np.ndarray:
    """An NxN map of one-cell corridors joined at alternate ends (a wall row between corridor
    rows, its gap at the right, then the left end), lethal border: the longest path an NxN
    map can force, about N*N/2 cells."""
    c = np.full((n, n), COST_OBS, dtype=np.uint8)
    c[1:n - 1:2, 1:n - 1] = 50
    for k, y in enumerate(range(2, n - 2, 2)):
        c[y, n - 2 if k % 2 == 0 else 1] = 50
    c[0, :] = c[-1, :] = c[:, 0] = c[:, -1] = COST_OBS
    return c


def _gradient_trap_room(n: int) -> np.ndarray:
    """A 3x3 room where the gradient fails from a reached start and the descent plans (found by
    search: the failure Nav2 #4655 reports, not the reporter's map) walled off in the
    corner of an otherwise open NxN map: the map's size is what a map-sized buffer would cost."""
    c = generated_map("open", n)
    c[0:5, 0:5] = np.array([[254] * 5, [254, 50, 240, 121, 254], [254, 253, 50, 50, 254],
                            [254, 252, 51, 50, 254], [254] * 5], dtype=np.uint8)
    return c


def worst_case_maps(n: int) -> list[tuple[str, np.ndarray, tuple, bool]]:
    """The worst cases of the fix at size ``n``: (name, costs, (sx, sy, gx, gy), astar).

    * ``serpentine``: NavFn's start at the far end of :func:`serpentine` from the goal (A* and
      Dijkstra): the cycle limit stops the original's wave; the fix propagates on, and its
      descent meets calcPath's budget of 4*N points;
    * ``serpentine, start on a wall``: the same with the start on a wall cell (the plugin's
      goal pose on a lethal cell): never reached, so the fix's one further call floods the
      goal's component;
    * ``gradient-trap room``: the gradient fails from a reached start and the descent plans, on an
      NxN map (a room found by search, of the kind Nav2 #4655 reports).
    """
    s = serpentine(n)
    last = n - 2 if (n - 2) % 2 == 1 else n - 3  # the last corridor row
    gap = n - 2 if ((last - 1) // 2 - 1) % 2 == 0 else 1  # where the wall row above it opens
    far = (1 if gap == n - 2 else n - 2, last)  # that corridor's other end
    wall = (far[0], last - 1)
    return [("serpentine", s, (*far, 1, 1), True), ("serpentine", s, (*far, 1, 1), False),
            ("serpentine, start on a wall", s, (*wall, 1, 1), True),
            ("gradient-trap room", _gradient_trap_room(n), (3, 1, 1, 2), True)]


def bench_worst_cases(sizes, folder, fix=THE_FIX, repeat: int = 1) -> list[dict]:
    """Each of :func:`worst_case_maps` at each size on the build ``folder``'s C++, as shipped and
    patched with ``fix`` (a patched :class:`~navfn_smt.spec.planner.Fix`; default: the fix of
    docs/fix.md), each case in a fresh program (its peak memory is that case's), ``repeat`` times
    (the time the best of them, the other figures the first run's).  Each row holds the figures
    as shipped under ``original`` and as patched under ``fixed``; ``variant`` names the fix."""
    from .oracle.client import Oracle
    from .spec.planner import AS_SHIPPED

    rows = []
    for n in sizes:
        for name, costs, case, astar in worst_case_maps(n):
            row = {"size": n, "case": name, "mode": "astar" if astar else "dijkstra", "start": case[:2],
                   "goal": case[2:], "variant": fix.name}
            for key, planned in (("original", AS_SHIPPED), ("fixed", fix)):
                for _ in range(repeat):
                    with Oracle(folder, traced=False, fix=planned) as o:
                        res = o.plan(costs, [case], astar)[0]
                        seconds = round(o.planning_seconds, 4)
                        row.setdefault(key, {"path_points": len(res.path), "start_reached": res.start_reached,
                                             "peak_memory_bytes": o.peak_memory_bytes(), "seconds": seconds})
                        row[key]["seconds"] = min(row[key]["seconds"], seconds)
            rows.append(row)
    return rows


def backends_of(choice: str) -> tuple[str, ...]:
    """The backends a ``--backend`` choice stands for: ``all`` is every one in ``BACKENDS``."""
    return tuple(BACKENDS) if choice == "all" else (choice,)


def bench_suite(suite: Path, backend: str, mode: str, planner=None) -> list[dict]:
    """Time every case of ``suite`` per backend and mode, planning as the planner under test
    ``planner`` (None: NavFn as shipped, in x86-64's arithmetic); one row of figures each."""
    maps = [load_map(d, suite) for d in discover(suite)]
    ncases = sum(len(m.cases) for m in maps)
    rows = []
    for b in backends_of(backend):
        for md in modes_of(mode):
            astar = md == "astar"
            runners = [get_backend(b, planner).prepare(m.costs) for m in maps]
            if b == "jit":  # warm-up: compile or load the cache before timing
                runners[0].run_batch(maps[0].cases[:1], astar)
            elapsed = 0.0
            with progress_bar(ncases, f"bench {b} {md}") as advance:
                for m, r in zip(maps, runners):
                    if b == "jit":  # one compiled call per map, as a C++ harness would loop
                        t0 = time.perf_counter()
                        r.run_batch(m.cases, astar)
                    else:
                        t0 = time.perf_counter()
                        for sx, sy, gx, gy in m.cases.tolist():
                            r.run((sx, sy), (gx, gy), astar, trace=False)
                    elapsed += time.perf_counter() - t0
                    advance(len(m.cases))
            rows.append({"backend": b, "mode": md, "cases": ncases, "seconds": round(elapsed, 3),
                         "cases_per_second": round(ncases / elapsed, 1) if elapsed else None})
    return rows


def bench_oracle(suite: Path, oracle, mode: str, planner) -> list[dict]:
    """The C++ NavFn (``oracle``: a running plain build) and the JIT on every case of ``suite``,
    map by map in the same run: the C++'s own planning time (its driver's clock, pipes aside),
    the whole calls (planning and the answers' transfer) and the JIT's batch time, the JIT
    planning as ``planner``, the planner under test read from the build (as ``difftest --oracle``
    compares them)."""
    maps = [load_map(d, suite) for d in discover(suite)]
    ncases = sum(len(m.cases) for m in maps)
    arith = planner.navfn_arithmetic()
    planners = [planner.backend("jit").prepare(m.costs) for m in maps]
    rows = []
    for md in modes_of(mode):
        astar = md == "astar"
        planners[0].run_batch(maps[0].cases[:1], astar)  # compile or load the cache before timing
        cpp = wall = jit = 0.0
        for m, p in zip(maps, planners):
            t0 = time.perf_counter()
            oracle.plan(m.costs, m.cases, astar)
            wall += time.perf_counter() - t0
            cpp += oracle.planning_seconds
            t0 = time.perf_counter()
            p.run_batch(m.cases, astar)
            jit += time.perf_counter() - t0
        rows.append({"mode": md, "cases": ncases, "arithmetic": arith.name, "cpp_seconds": cpp, "jit_seconds": jit,
                     "jit_over_cpp": round(jit / cpp, 3) if cpp else None, "cpp_call_seconds": wall})
    return rows


def bench_fix(suite: Path, folder, mode: str, repeat: int = 3, fix=THE_FIX) -> list[dict]:
    """A fix's cost where it does not act: the cases of ``suite`` the original plans, timed on
    the C++ of the build ``folder`` as shipped and as patched with ``fix`` (default: the fix of
    docs/fix.md; ``navfn-traced``, ``navfn-fixed`` or ``navfn-<fix>``: the same trace hook in
    both) and on the JIT without and with the fix, each ``repeat`` times in alternation; the
    best time of each is kept.  The figures with the fix are under the ``*_fixed`` keys; each
    row's ``variant`` names the fix."""
    from .oracle.client import Oracle

    maps = [load_map(d, suite) for d in discover(suite)]
    rows = []
    with Oracle(folder) as original, Oracle(folder, fix=fix) as fixed:
        for md in modes_of(mode):
            astar = md == "astar"
            work = []
            for m in maps:
                plans = get_backend("jit").prepare(m.costs).run_batch(m.cases, astar)["exit"] == 0
                work.append((m, m.cases[plans]))
            jit = {key: [p.backend("jit").prepare(m.costs) for m, _ in work]
                   for key, p in (("original", ORIGINAL), ("fixed", PlannerUnderTest(fix)))}
            for v in jit:
                jit[v][0].run_batch(work[0][1][:1], astar)  # compile or load the cache before timing
            best = {k: float("inf") for k in ("cpp_original", "cpp_fixed", "jit_original", "jit_fixed")}
            for _ in range(repeat):
                t = dict.fromkeys(best, 0.0)
                for i, (m, cases) in enumerate(work):
                    for key, oracle in (("cpp_original", original), ("cpp_fixed", fixed)):
                        oracle.plan(m.costs, cases, astar)
                        t[key] += oracle.planning_seconds
                    for v in jit:
                        t0 = time.perf_counter()
                        jit[v][i].run_batch(cases, astar)
                        t[f"jit_{v}"] += time.perf_counter() - t0
                best = {k: min(best[k], t[k]) for k in best}
            n = sum(len(c) for _, c in work)
            rows.append({"mode": md, "variant": fix.name, "cases_the_original_plans": n,
                         **{k: round(v, 4) for k, v in best.items()},
                         "cpp_fixed_over_original": round(best["cpp_fixed"] / best["cpp_original"], 3),
                         "jit_fixed_over_original": round(best["jit_fixed"] / best["jit_original"], 3)})
    return rows


def check_sizes(sizes, repeat: int) -> None:
    """Reject benchmark sizes below 12 cells a side and fewer than one plan per map."""
    for n in sizes:
        if n < 12:
            raise NavfnInputError(f"--size {n}: benchmark maps must be at least 12 cells a side")
        check_cells(n, n, f"--size {n}")
    if repeat < 1:
        raise NavfnInputError("--repeat must be at least 1")


def bench_sizes(sizes, backend: str, repeat: int, modes: str = "both") -> list[dict]:
    """Time plans on generated open and random NxN maps per backend and mode; one row each."""
    check_sizes(sizes, repeat)
    rows = []
    steps = len(backends_of(backend)) * len(sizes) * 2 * len(modes_of(modes))
    with progress_bar(steps, "bench sizes") as advance:
        for b in backends_of(backend):
            rows += _bench_sizes_of(b, sizes, repeat, modes, advance)
    return rows


def _bench_sizes_of(b: str, sizes, repeat: int, modes: str, advance) -> list[dict]:
    """The rows of :func:`bench_sizes` for one backend; ``advance(1)`` after each map and mode."""
    rows = []
    if b == "jit":  # warm-up: load the compiled code before timing
        get_backend(b).prepare(generated_map("open", 12)).run((5, 5), (6, 6), True, trace=False)
    for n in sizes:
        for kind in ("open", "random"):
            costs = generated_map(kind, n)
            planner = get_backend(b).prepare(costs)
            for md in modes_of(modes):
                astar = md == "astar"
                best = None
                res = None
                for _ in range(repeat if b == "jit" else 1):
                    t0 = time.perf_counter()
                    res = planner.run((5, 5), (n - 6, n - 6), astar, trace=False)
                    dt = time.perf_counter() - t0
                    best = dt if best is None else min(best, dt)
                rows.append({
                    "backend": b, "size": n, "map": kind, "mode": md,
                    "seconds_per_plan": float(f"{best:.4g}"),
                    "path_points": int(len(res.path)), "dropped_pushes": int(res.dropped),
                    "work_bytes": _work_bytes(planner),
                })
                advance(1)
    return rows


def _work_bytes(planner) -> int:
    """Bytes of the planner's own arrays (JIT backend, trace off); 0 where not measured."""
    p = getattr(planner, "work", None)
    return 0 if p is None else p.nbytes()



# ------------------------------------------------------------------------- whole-map sweep
SWEEP_SIZE = 400
SWEEP_ASTAR_GOALS = 2000


def bench_sweep(n: int = SWEEP_SIZE, modes: str = "both", astar_goals=SWEEP_ASTAR_GOALS, seed: int = 0) -> list[dict]:
    """Time :func:`~navfn_smt.diagnose.sweep.sweep` on a generated n x n rooms costmap
    (:func:`~navfn_smt.diagnose.sweep.rooms_costmap`), robot in the first room, every free cell
    a goal (A*: ``astar_goals`` sampled ones unless ``"all"``: one propagation per goal); one
    row per mode, with the first call's time (compiling, or loading the on-disk cache) apart."""
    from .diagnose.sweep import rooms_costmap, sweep
    from .nav2.params import PlannerParams
    from .nav2.plugin import Pose

    if n < 30:
        raise NavfnInputError(f"--sweep {n}: the sweep map must be at least 30 cells a side")
    check_cells(n, n, f"--sweep {n}")
    cm = rooms_costmap(n, seed=seed)
    res = cm.resolution
    start = Pose(cm.origin_x + 20.3 * res, cm.origin_y + 20.7 * res)
    tiny = rooms_costmap(30, seed=seed, room=12)
    tiny_start = Pose(tiny.origin_x + 5.3 * res, tiny.origin_y + 5.7 * res)
    rows = []
    for md in modes_of(modes):
        params = PlannerParams(use_astar=md == "astar")
        t0 = time.perf_counter()
        sweep(tiny, tiny_start, params, goals=20)
        warm = time.perf_counter() - t0
        goals = None if md == "dijkstra" or astar_goals == "all" else int(astar_goals)
        with progress_counts(f"sweep {md} (goals)") as progress:
            r = sweep(cm, start, params, goals=goals, seed=seed, progress=progress)
        counts = r.counts()
        rows.append({"mode": md, "size": n, "goals": len(r), "seconds": round(r.seconds, 3),
                     "goals_per_second": round(len(r) / r.seconds, 1), "first_call_seconds": round(warm, 3),
                     "planned": counts["ok"] + counts["ok_tolerance"], "issue_4655": counts["legal_no_plan"],
                     "no_path": counts["no_legal"]})
    return rows


# ------------------------------------------------------------------------- the cost climb
CLIMB_MAPS = 50_000
CLIMB_SIZE = (5, 7)


def bench_climb(maps: int = CLIMB_MAPS, modes: str = "both", seed: int = 0) -> list[dict]:
    """Time ``maps`` evaluations of the cost climb per mode on CLIMB_SIZE maps, with the
    compiled plateau steps (:mod:`.search.steps`) and with the Python step (one row each, the
    first call's compilation excluded); refuses to report when the two climbs differ."""
    import math

    from .search.hunt import Climb

    if maps < 1:
        raise NavfnInputError(f"--climb {maps}: at least one map")
    rows = []
    for md in modes_of(modes):
        Climb("cost", md, CLIMB_SIZE, (50, 253), seed, ORIGINAL, 0.0).advance(300, math.inf, lambda line: None)
        ends = []
        for compiled in (True, False):
            c = Climb("cost", md, CLIMB_SIZE, (50, 253), seed, ORIGINAL, 0.0, compiled=compiled)
            t0 = time.perf_counter()
            c.advance(maps, math.inf, lambda line: None)
            sec = time.perf_counter() - t0
            best = c.best[0] if c.best is not None else 0.0
            ends.append((c.cl.plans, best, c.cur.tobytes()))
            rows.append({"mode": md, "steps": "compiled" if compiled else "python", "maps": c.evaluations,
                         "plans": c.cl.plans, "seconds": round(sec, 3), "maps_per_second": round(c.evaluations / sec),
                         "best_gap": best})
        if ends[0] != ends[1]:
            raise RuntimeError(f"bench --climb, {md}: the compiled steps and the Python step made different climbs")
    return rows
