"""Differential testing: run every case of a suite and compare with the golden files.

Agreement is bit-exact, field by field, in this order (the first differing field is
the one reported): the path's float32 values, the potential's SHA-256, the trace's
SHA-256, ``start_reached``, ``cycles``, ``updates``.  Nothing is compared with a
tolerance.
"""

from __future__ import annotations

import time
from concurrent.futures import ProcessPoolExecutor, as_completed
from dataclasses import asdict, dataclass, field
from pathlib import Path
from typing import Callable, Iterable, Optional

import numpy as np

from ..backends import get_backend
from ..spec.extraction import UndefinedBehaviour
from ..spec.planner import PlanResult, sha256_f32, sha256_i32
from ..maps.suite import MODES, discover, golden_path_of, load_golden, load_map

FIELDS = ("path", "potential", "trace", "start_reached", "cycles", "updates")
CHUNK = 2000  # cases per task, so that progress moves on large maps
MODE_CHOICES = (*MODES, "both")  # what a command's --mode accepts


def modes_of(choice: str) -> tuple[str, ...]:
    """The planner modes a ``--mode`` choice stands for: ``both`` is every mode in ``MODES``."""
    return tuple(MODES) if choice == "both" else (choice,)


@dataclass
class Disagreement:
    map: str
    category: str
    mode: str
    case_index: int
    case: list  # [sx, sy, gx, gy]
    field: str
    detail: dict


@dataclass
class TaskOutcome:
    map: str
    category: str
    mode: str
    cases: int
    agreeing: int
    seconds: float
    disagreements: list = field(default_factory=list)


def _f32_repr(v) -> dict:
    v = np.float32(v)
    return {"value": float(v), "bits": f"0x{int(v.view(np.uint32)):08x}"}


def compare_case(res: PlanResult, g: dict, i: int, full_pos: dict) -> Optional[tuple[str, dict]]:
    """The first field in which ``res`` differs from golden case ``i``, with details."""
    gp = golden_path_of(g, i)
    ours = np.asarray(res.path, dtype=np.float32).reshape(-1, 2)
    if ours.shape != gp.shape or not np.array_equal(ours.view(np.uint32), gp.view(np.uint32)):
        detail: dict = {"length": len(ours), "golden_length": len(gp)}
        n = min(len(ours), len(gp))
        diff = np.nonzero((ours[:n].view(np.uint32) != gp[:n].view(np.uint32)).any(axis=1))[0]
        if len(diff):
            k = int(diff[0])
            detail.update(
                point=k,
                ours=[_f32_repr(ours[k, 0]), _f32_repr(ours[k, 1])],
                golden=[_f32_repr(gp[k, 0]), _f32_repr(gp[k, 1])],
            )
        return "path", detail
    if sha256_f32(res.potential) != bytes(g["potential_sha256"][i]):
        detail = {"start_potential": _f32_repr(res.start_potential),
                  "golden_start_potential": _f32_repr(g["start_potential"][i])}
        j = full_pos.get(i)
        if j is None:
            detail["note"] = "golden stores only the hash of this case's potential"
        else:
            gpot = g["full_potential"][j]
            ours_pot = np.asarray(res.potential, dtype=np.float32).reshape(gpot.shape)
            cells = np.argwhere(ours_pot.view(np.uint32) != gpot.view(np.uint32))
            if len(cells) == 0:
                detail["note"] = "the golden file's potential equals ours but not its own hash (corrupt golden file)"
            else:
                y, x = (int(c) for c in cells[0])
                detail.update(cell=[x, y], ours=_f32_repr(ours_pot[y, x]), golden=_f32_repr(gpot[y, x]),
                              cells_differing=int(len(cells)))
        return "potential", detail
    if sha256_i32(res.trace) != bytes(g["trace_sha256"][i]):
        detail = {"length": int(len(res.trace))}
        j = full_pos.get(i)
        if j is not None:
            off = g["full_trace_offsets"]
            gt = g["full_trace"][off[j] : off[j + 1]]
            n = min(len(gt), len(res.trace))
            d = np.nonzero(np.asarray(res.trace[:n]) != gt[:n])[0]
            detail["golden_length"] = int(len(gt))
            if len(d):
                k = int(d[0])
                detail.update(position=k, ours=int(res.trace[k]), golden=int(gt[k]))
        return "trace", detail
    for name, ours_v, gold_v in (
        ("start_reached", bool(res.start_reached), bool(g["start_reached"][i])),
        ("cycles", int(res.cycles), int(g["cycles"][i])),
        ("updates", int(res.updates), int(g["updates"][i])),
    ):
        if ours_v != gold_v:
            return name, {"ours": ours_v, "golden": gold_v}
    return None


@dataclass
class Task:
    map_dir: str
    root: str
    mode: str
    backend: str
    lo: int
    hi: int
    max_details: int = 20


def run_task(t: Task) -> TaskOutcome:
    smap = load_map(t.map_dir, Path(t.root))
    g = load_golden(smap.golden_path(t.mode), smap)
    full_pos = {int(k): j for j, k in enumerate(g["full_index"])}
    runner = get_backend(t.backend).prepare(smap.costs)
    astar = t.mode == "astar"
    rel = str(Path(t.map_dir).resolve().relative_to(Path(t.root).resolve()))
    out = TaskOutcome(rel, smap.category, t.mode, t.hi - t.lo, 0, 0.0)
    t0 = time.perf_counter()
    for i in range(t.lo, t.hi):
        sx, sy, gx, gy = (int(v) for v in smap.cases[i])
        try:
            res = runner.run((sx, sy), (gx, gy), astar)
            verdict = compare_case(res, g, i, full_pos)
        except UndefinedBehaviour as e:
            verdict = ("undefined_behaviour", {"message": str(e)})
        if verdict is None:
            out.agreeing += 1
        elif len(out.disagreements) < t.max_details:
            out.disagreements.append(Disagreement(rel, smap.category, t.mode, i, [sx, sy, gx, gy], verdict[0], verdict[1]))
    out.seconds = time.perf_counter() - t0
    return out


def plan_tasks(root, modes: Iterable[str], backend: str) -> list[Task]:
    tasks = []
    for d in discover(root):
        smap = load_map(d, Path(root))  # validates test.txt and map bytes up front
        for mode in modes:
            if not smap.golden_path(mode).exists():
                from ..errors import NavfnInputError

                raise NavfnInputError(f"{smap.golden_path(mode)}: no such golden file")
            for lo in range(0, len(smap.cases), CHUNK):
                tasks.append(Task(str(d), str(root), mode, backend, lo, min(lo + CHUNK, len(smap.cases))))
    return tasks


def _warm(backend: str) -> None:
    if backend == "jit":
        from ..backends.jit import JitPlanner  # noqa: F401  (import compiles from cache)


def run_suite(
    root,
    modes: Iterable[str] = MODES,
    backend: str = "jit",
    jobs: int = 1,
    progress: Optional[Callable[[TaskOutcome], None]] = None,
    tasks: Optional[list] = None,
) -> list[TaskOutcome]:
    """Run the difftest; ``progress`` is called after each finished task."""
    tasks = plan_tasks(root, modes, backend) if tasks is None else tasks
    outcomes: list[TaskOutcome] = []
    try:
        if jobs <= 1:
            for t in tasks:
                o = run_task(t)
                outcomes.append(o)
                if progress:
                    progress(o)
        else:
            # largest tasks first keeps both workers busy until the end
            order = sorted(tasks, key=lambda t: -(t.hi - t.lo) * _map_cells(t.map_dir))
            ex = ProcessPoolExecutor(max_workers=jobs, initializer=_warm, initargs=(backend,))
            try:
                futs = [ex.submit(run_task, t) for t in order]
                for f in as_completed(futs):
                    o = f.result()
                    outcomes.append(o)
                    if progress:
                        progress(o)
            finally:  # on Ctrl-C: drop the queued tasks instead of running them all first
                ex.shutdown(wait=True, cancel_futures=True)
    except KeyboardInterrupt:
        _partial_note(outcomes, sum(t.hi - t.lo for t in tasks))
        raise
    outcomes.sort(key=lambda o: (o.category, o.map, o.mode))
    return outcomes


def _partial_note(outcomes: list[TaskOutcome], total: int) -> None:
    """What an interrupted run had compared, on stdout (no report file is written for it)."""
    done = sum(o.cases for o in outcomes)
    agreeing = sum(o.agreeing for o in outcomes)
    try:
        print(f"interrupted after {done} of {total} cases: {agreeing} agreed, {done - agreeing} disagreed "
              f"(no report written; rerun to compare everything)", flush=True)
    except (OSError, ValueError):
        pass


def _map_cells(map_dir: str) -> int:
    try:
        first = Path(map_dir, "test.txt").read_text().split("\n", 1)[0].split()
        return int(first[0]) * int(first[1])
    except (OSError, ValueError, IndexError):
        return 1


def summarize(outcomes: list[TaskOutcome]) -> dict:
    """Per (category, mode) and per map counts, plus the disagreements, JSON-ready."""
    per_cat: dict = {}
    per_map: dict = {}
    disagreements = []
    for o in outcomes:
        c = per_cat.setdefault((o.category, o.mode), {"category": o.category, "mode": o.mode, "cases": 0,
                                                      "agreeing": 0, "first_disagreement": None})
        c["cases"] += o.cases
        c["agreeing"] += o.agreeing
        m = per_map.setdefault((o.map, o.mode), {"map": o.map, "category": o.category, "mode": o.mode,
                                                 "cases": 0, "agreeing": 0, "seconds": 0.0})
        m["cases"] += o.cases
        m["agreeing"] += o.agreeing
        m["seconds"] += o.seconds
        for d in o.disagreements:
            disagreements.append(asdict(d))
    disagreements.sort(key=lambda d: (d["map"], d["mode"], d["case_index"]))
    for d in disagreements:
        cat = per_cat[(d["category"], d["mode"])]
        if cat["first_disagreement"] is None:
            cat["first_disagreement"] = d
    passed = sum(o.agreeing for o in outcomes)
    total = sum(o.cases for o in outcomes)
    return {
        "passed": passed,
        "failed": total - passed,
        "categories": sorted(per_cat.values(), key=lambda c: (c["category"], c["mode"])),
        "maps": sorted(per_map.values(), key=lambda m: (m["map"], m["mode"])),
        "disagreements": disagreements,
    }
