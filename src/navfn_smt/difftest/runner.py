"""Differential testing: run every case of a suite and compare with the golden files.

Agreement is bit-exact, field by field, in this order (the first differing field is
the one reported): the path's float32 values, the potential's SHA-256, the trace's
SHA-256, ``start_reached``, ``cycles``, ``updates``.  Nothing is compared with a
tolerance.
"""

from __future__ import annotations

import functools
import time
from dataclasses import asdict, dataclass, field
from pathlib import Path
from typing import Callable, Iterable, Iterator, Optional, Union

import numpy as np

from ..backends import get_backend
from ..engine import Engine, engine, stream
from ..errors import NavfnInputError
from ..spec.extraction import UndefinedBehaviour
from ..spec.planner import PlanResult, sha256_f32, sha256_i32
from ..maps.suite import MODES, discover, golden_file, golden_path_of, is_case_line, load_golden, load_map

FIELDS = ("path", "potential", "trace", "start_reached", "cycles", "updates")
CHUNK = 2000  # cases per task, so that progress moves on large maps
AUTO_CASES = 50_000  # --jobs auto: local workers from this many case runs on (their start-up is ~3 s)
MAX_DISAGREEMENTS = 1000  # kept in a summary, the first by map, mode and case (all are counted)


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


def compare_case(res: PlanResult, g: dict, i: int, full_pos: dict,
                 white_box: bool = True) -> Optional[tuple[str, dict]]:
    """The first field in which ``res`` differs from golden case ``i``, with details;
    ``white_box=False``: path, potential and start_reached only (golden answers of a build
    without the trace hook)."""
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
    if not white_box:
        return None if bool(res.start_reached) == bool(g["start_reached"][i]) else (
            "start_reached", {"ours": bool(res.start_reached), "golden": bool(g["start_reached"][i])})
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
    counted: Optional[int] = None  # the map's cases as counted when the task was made
    planner: object = None  # the planner under test (under_test.PlannerUnderTest; None: NavFn as shipped, x86-64)


def _stamp(map_dir: str) -> tuple:
    """What the files of a map directory look like now (name, size, mtime, inode), to notice a change."""
    out = []
    for p in Path(map_dir).iterdir():
        try:
            st = p.stat()
        except OSError as e:  # a dangling link, a symlink loop: the map's own loader would say the same
            raise NavfnInputError(f"{p}: cannot read ({e.strerror})") from None
        out.append((p.name, st.st_size, st.st_mtime_ns, st.st_ino))
    return tuple(sorted(out))


@functools.lru_cache(maxsize=2)
def _inputs(map_dir: str, root: str, mode: str, stamp: tuple):
    """A task's map, golden file and full-potential positions; consecutive chunks of a map on
    one worker load them once (``stamp`` keys the cache to the files as they are)."""
    smap = load_map(map_dir, Path(root))
    g = load_golden(smap.golden_path(mode), smap)
    full_pos = {int(k): j for j, k in enumerate(g["full_index"])}
    rel = str(Path(map_dir).resolve().relative_to(Path(root).resolve()))
    return smap, g, full_pos, rel


def run_task(t: Task) -> TaskOutcome:
    """Cases ``lo..hi`` of one map in one mode, compared with the golden file."""
    smap, g, full_pos, rel = _inputs(t.map_dir, t.root, t.mode, _stamp(t.map_dir))
    if t.hi > len(smap.cases) or t.counted not in (None, len(smap.cases)):
        raise NavfnInputError(f"{smap.directory / 'test.txt'}: has {len(smap.cases)} cases, not the "
                              f"{t.counted or t.hi} counted (changed during the run?)")
    planner = get_backend(t.backend, t.planner).prepare(smap.costs)
    astar = t.mode == "astar"
    out = TaskOutcome(rel, smap.category, t.mode, t.hi - t.lo, 0, 0.0)
    t0 = time.perf_counter()
    for i in range(t.lo, t.hi):
        sx, sy, gx, gy = (int(v) for v in smap.cases[i])
        try:
            res = planner.run((sx, sy), (gx, gy), astar)
            verdict = compare_case(res, g, i, full_pos)
        except UndefinedBehaviour as e:
            verdict = ("undefined_behaviour", {"message": str(e)})
        if verdict is None:
            out.agreeing += 1
        elif len(out.disagreements) < t.max_details:
            out.disagreements.append(Disagreement(rel, smap.category, t.mode, i, [sx, sy, gx, gy], verdict[0], verdict[1]))
    out.seconds = time.perf_counter() - t0
    return out


def case_count(map_dir) -> int:
    """The cases of a map, counted in its ``test.txt`` without parsing them (the lines after
    the first two that :func:`is_case_line` accepts, as :func:`parse_test_txt` reads them);
    a malformed line is reported by the task that reads it."""
    path = Path(map_dir, "test.txt")
    try:
        with open(path, encoding="ascii") as f:  # line by line: a million cases are not held
            return sum(1 for no, line in enumerate(f) if no >= 2 and is_case_line(line))
    except (OSError, UnicodeDecodeError) as e:
        raise NavfnInputError(f"{path}: unreadable test file ({getattr(e, 'strerror', None) or type(e).__name__})") from None


def count_cases(root, modes: Iterable[str]) -> int:
    """Case runs of a difftest of ``root`` in ``modes``, with every golden file it needs checked to exist."""
    modes = tuple(modes)
    total = 0
    for d in discover(root):
        for mode in modes:
            if not golden_file(d, mode).exists():
                raise NavfnInputError(f"{golden_file(d, mode)}: no such golden file")
        total += case_count(d) * len(modes)
    return total


def iter_tasks(root, modes: Iterable[str], backend: str, chunk: int = CHUNK, planner=None) -> Iterator[Task]:
    """The difftest's tasks, map by map as they are needed: chunks of ``chunk`` cases per mode.
    Only the cases are counted here; each task reads and checks the map it runs."""
    modes = tuple(modes)
    for d in discover(root):
        n = case_count(d)
        if n == 0:
            load_map(d, Path(root))  # no task reads a map without cases: check it here
        for mode in modes:
            for lo in range(0, n, chunk):
                yield Task(str(d), str(root), mode, backend, lo, min(lo + chunk, n), counted=n, planner=planner)


def plan_tasks(root, modes: Iterable[str], backend: str) -> list[Task]:
    """Every task of the difftest, built up front with every map checked (for callers that
    pick or reorder tasks)."""
    for d in discover(root):
        load_map(d, Path(root))
    count_cases(root, modes)
    return list(iter_tasks(root, modes, backend))


def _key(d: dict) -> tuple:
    return d["map"], d["mode"], d["case_index"]


class Summary:
    """A difftest's result, folded in one finished task at a time: counts per (category, mode)
    and per map, and the first ``MAX_DISAGREEMENTS`` disagreements by map, mode and case.  Its
    memory grows with the number of maps, not of cases; the order tasks finish in does not
    change it."""

    def __init__(self, max_disagreements: int = MAX_DISAGREEMENTS):
        self.cases = 0
        self.agreeing = 0
        self.max_disagreements = max_disagreements
        self._cats: dict = {}
        self._maps: dict = {}
        self._kept: list = []

    def add(self, o: TaskOutcome) -> None:
        """Count one task's outcome."""
        self.cases += o.cases
        self.agreeing += o.agreeing
        c = self._cats.setdefault((o.category, o.mode), {"category": o.category, "mode": o.mode, "cases": 0,
                                                         "agreeing": 0, "first_disagreement": None})
        c["cases"] += o.cases
        c["agreeing"] += o.agreeing
        m = self._maps.setdefault((o.map, o.mode), {"map": o.map, "category": o.category, "mode": o.mode,
                                                    "cases": 0, "agreeing": 0, "seconds": 0.0})
        m["cases"] += o.cases
        m["agreeing"] += o.agreeing
        m["seconds"] += o.seconds
        for d in map(asdict, o.disagreements):
            first = self._cats[(d["category"], d["mode"])]["first_disagreement"]
            if first is None or _key(d) < _key(first):
                self._cats[(d["category"], d["mode"])]["first_disagreement"] = d
            self._kept.append(d)
        if len(self._kept) > 2 * self.max_disagreements:
            self._trim()

    def _trim(self) -> None:
        self._kept.sort(key=_key)
        del self._kept[self.max_disagreements:]

    def as_dict(self) -> dict:
        """Per (category, mode) and per map counts, plus the disagreements kept, JSON-ready."""
        self._trim()
        return {
            "passed": self.agreeing,
            "failed": self.cases - self.agreeing,
            "categories": sorted(self._cats.values(), key=lambda c: (c["category"], c["mode"])),
            "maps": sorted(self._maps.values(), key=lambda m: (m["map"], m["mode"])),
            "disagreements": list(self._kept),
        }


def run_suite(
    root,
    modes: Iterable[str] = MODES,
    backend: str = "jit",
    jobs: Union[int, str, None] = 1,
    progress: Optional[Callable[[TaskOutcome], None]] = None,
    *,
    eng: Optional[Engine] = None,
    total: Optional[int] = None,
    chunk: int = CHUNK,
    on_client: Optional[Callable] = None,
    planner=None,
) -> Summary:
    """Run the difftest of ``root`` on ``eng`` (else ``engine(jobs)``; ``jobs`` None or
    ``auto`` takes local workers from ``AUTO_CASES`` case runs on) and fold the outcomes
    into a :class:`Summary`; ``progress`` is called after each finished task.  ``total``
    (the case runs, :func:`count_cases`) is counted when not given; ``planner``: the planner under
    test (:class:`~navfn_smt.under_test.PlannerUnderTest`) the golden files were recorded from."""
    modes = tuple(modes)
    total = count_cases(root, modes) if total is None else total
    eng = (eng or engine(jobs)).for_work(total, AUTO_CASES)
    summary = Summary()
    try:
        get_backend(backend, planner)  # refused here, once, when the backend cannot compute in it
        for _, o in stream(run_task, iter_tasks(root, modes, backend, chunk, planner), eng, on_client=on_client):
            summary.add(o)
            if progress:
                progress(o)
    except KeyboardInterrupt:
        _partial_note(summary, total)
        raise
    return summary


def _partial_note(summary: Summary, total: int) -> None:
    """What an interrupted run had compared, on stdout (no report file is written for it)."""
    done, agreeing = summary.cases, summary.agreeing
    try:
        print(f"interrupted after {done} of {total} cases: {agreeing} agreed, {done - agreeing} disagreed "
              f"(no report written; rerun to compare everything)", flush=True)
    except (OSError, ValueError):
        pass


def map_cells(map_dir: str) -> int:
    try:
        first = Path(map_dir, "test.txt").read_text().split("\n", 1)[0].split()
        return int(first[0]) * int(first[1])
    except (OSError, ValueError, IndexError):
        return 1


def summarize(outcomes: Union[Summary, Iterable[TaskOutcome]]) -> dict:
    """Per (category, mode) and per map counts, plus the disagreements, JSON-ready: of a
    :class:`Summary` (what :func:`run_suite` returns) or of task outcomes."""
    if not isinstance(outcomes, Summary):
        summary = Summary()
        for o in outcomes:
            summary.add(o)
        outcomes = summary
    return outcomes.as_dict()
