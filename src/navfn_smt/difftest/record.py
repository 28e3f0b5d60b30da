"""Record golden files from our own specification, in exactly the shared suite's golden format.

``record_suite(SUITE)`` plans every case of every map under ``SUITE`` with one backend and
writes ``golden_astar.npz`` / ``golden_dijkstra.npz`` beside each ``test.txt``: the 15
fields of ``navfn-suite/README.md`` with the same dtypes and shapes, compressed the way the
shared files are.  ``full_index`` follows the suite's rule: the first ``full_first`` cases
plus every case whose start potential is finite (not the unreached 1e10) but whose path is
empty.  (The shared suite uses ``full_first`` 50, and 5 on its ROS maps.)

Such files let ``difftest`` guard generated suites against regressions of the spec; they
are not evidence about the C++ original.  Existing golden files are kept unless
``overwrite`` is given, so that a recording never silently replaces the C++ goldens.
"""

from __future__ import annotations

import os
import time
from dataclasses import dataclass
from pathlib import Path
from typing import Callable, Iterable, Optional

import numpy as np

from ..backends import BACKENDS, get_backend
from ..errors import NavfnInputError
from ..fileio import atomic_path
from ..maps.suite import GOLDEN_FIELDS, MODES, SuiteMap, discover, load_map
from ..spec.constants import POT_HIGH
from ..spec.extraction import UndefinedBehaviour
from ..spec.planner import sha256_f32, sha256_i32
from ..maps.suite import modes_of

_UNREACHED = np.float32(POT_HIGH)


@dataclass
class RecordedMap:
    map: str  # relative to the suite root
    category: str
    mode: str
    cases: int
    full: int  # cases whose full potential and trace are stored
    seconds: float
    path: Path  # the golden file written


def golden_fields(smap: SuiteMap, planner, astar: bool, full_first: int = 50) -> dict:
    """Plan every case of ``smap`` and build the golden arrays (in ``GOLDEN_FIELDS`` order)."""
    return fields_of_results(smap, _planned(smap, planner, astar), full_first)


def _planned(smap: SuiteMap, planner, astar: bool):
    for i, (sx, sy, gx, gy) in enumerate(smap.cases.tolist()):
        try:
            yield planner.run((sx, sy), (gx, gy), astar, trace=True)
        except UndefinedBehaviour as e:
            raise NavfnInputError(
                f"{smap.directory}: case {i} ({sx} {sy} {gx} {gy}): the C++ would read outside its arrays "
                f"({e}); nothing can be recorded for it") from None


def fields_of_results(smap: SuiteMap, results, full_first: int = 50) -> dict:
    """The golden arrays (in ``GOLDEN_FIELDS`` order) of ``results``, one per case of ``smap``
    in order, with their traces: the spec's (:func:`golden_fields`) or the C++'s (an oracle)."""
    n = len(smap.cases)
    start_reached = np.zeros(n, dtype=np.int8)
    start_potential = np.zeros(n, dtype=np.float32)
    path_offsets = np.zeros(n + 1, dtype=np.int64)
    pot_sha = np.zeros((n, 32), dtype=np.uint8)
    trace_sha = np.zeros((n, 32), dtype=np.uint8)
    cycles = np.zeros(n, dtype=np.int32)
    updates = np.zeros(n, dtype=np.int64)
    paths: list[np.ndarray] = []
    full_index: list[int] = []
    full_pot: list[np.ndarray] = []
    full_traces: list[np.ndarray] = []
    for i, res in enumerate(results):
        # a JIT result is a view into the planner's buffers: take what we keep before the next run
        pot = np.ascontiguousarray(res.potential, dtype="<f4")
        trace = np.ascontiguousarray(res.trace if res.trace is not None else (), dtype="<i4")  # none: untraced
        path = np.array(res.path, dtype=np.float32).reshape(-1, 2)
        sp = np.float32(res.start_potential)
        start_reached[i] = 1 if res.start_reached else 0
        start_potential[i] = sp
        paths.append(path)
        path_offsets[i + 1] = path_offsets[i] + len(path)
        pot_sha[i] = np.frombuffer(sha256_f32(pot), dtype=np.uint8)
        trace_sha[i] = np.frombuffer(sha256_i32(trace), dtype=np.uint8)
        cycles[i] = res.cycles
        updates[i] = res.updates
        if i < full_first or (len(path) == 0 and np.isfinite(sp) and sp != _UNREACHED):
            full_index.append(i)
            full_pot.append(pot.reshape(smap.height, smap.width).copy())
            full_traces.append(trace.copy())
    full_trace_offsets = np.zeros(len(full_traces) + 1, dtype=np.int64)
    if full_traces:
        full_trace_offsets[1:] = np.cumsum([len(t) for t in full_traces])
    fields = {
        "width": np.array(smap.width, dtype=np.int32),
        "height": np.array(smap.height, dtype=np.int32),
        "cases": np.ascontiguousarray(smap.cases, dtype=np.int32).reshape(-1, 4),
        "start_reached": start_reached,
        "start_potential": start_potential,
        "path_offsets": path_offsets,
        "path": np.concatenate(paths).astype(np.float32) if paths else np.zeros((0, 2), dtype=np.float32),
        "potential_sha256": pot_sha,
        "trace_sha256": trace_sha,
        "cycles": cycles,
        "updates": updates,
        "full_index": np.array(full_index, dtype=np.int64),
        "full_potential": (np.stack(full_pot).astype(np.float32) if full_pot
                           else np.zeros((0, smap.height, smap.width), dtype=np.float32)),
        "full_trace_offsets": full_trace_offsets,
        "full_trace": (np.concatenate(full_traces).astype(np.int32) if full_traces
                       else np.zeros(0, dtype=np.int32)),
    }
    assert tuple(fields) == GOLDEN_FIELDS
    return fields


def write_golden(path: Path, fields: dict) -> None:
    """``numpy.savez_compressed``, written whole or not at all."""
    with atomic_path(path) as tmp:
        with open(tmp, "wb") as f:
            np.savez_compressed(f, **fields)
            f.flush()
            os.fsync(f.fileno())


def _modes(modes: Iterable[str]) -> tuple[str, ...]:
    if isinstance(modes, str):
        modes = modes_of(modes)
    out = tuple(modes)
    bad = [m for m in out if m not in MODES]
    if bad or not out:
        raise NavfnInputError(f"mode {bad[0] if bad else ''!r}: choose astar, dijkstra or both")
    return out


def record_suite(
    suite_dir,
    modes: Iterable[str] = MODES,
    backend: str = "jit",
    full_first: int = 50,
    overwrite: bool = False,
    progress: Optional[Callable[[RecordedMap], None]] = None,
    oracle=None,
    planner=None,
) -> list[RecordedMap]:
    """Write ``golden_<mode>.npz`` for every map under ``suite_dir`` from our spec (planning as
    the planner under test ``planner``; None: NavFn as shipped, in x86-64's arithmetic), or with ``oracle`` (a running
    :class:`~navfn_smt.oracle.client.Oracle`) from the C++ NavFn.

    Every map is loaded and every target checked before anything is written; an existing
    golden file is an error unless ``overwrite``.  ``progress`` is called after each map and
    mode with its :class:`RecordedMap`.
    """
    modes = _modes(modes)
    if backend not in BACKENDS:
        raise NavfnInputError(f"unknown backend {backend!r} (choose from {', '.join(BACKENDS)})")
    if isinstance(full_first, bool) or not isinstance(full_first, (int, np.integer)) or full_first < 0:
        raise NavfnInputError(f"--full-first {full_first!r}: expected a non-negative number of cases")
    root = Path(suite_dir)
    maps = [load_map(d, root) for d in discover(root)]
    if not overwrite:
        existing = [m.golden_path(mode) for m in maps for mode in modes if m.golden_path(mode).exists()]
        if existing:
            what = (f"{existing[0]} exists" if len(existing) == 1
                    else f"{existing[0]} and {len(existing) - 1} more golden files exist")
            raise NavfnInputError(f"{what} (pass --overwrite to replace)")
    be = get_backend(backend, planner)
    done: list[RecordedMap] = []
    for smap in maps:
        planner = be.prepare(smap.costs) if oracle is None else None
        rel = str(smap.directory.resolve().relative_to(root.resolve()))
        for mode in modes:
            t0 = time.perf_counter()
            astar = mode == "astar"
            results = (_planned(smap, planner, astar) if oracle is None
                       else oracle.plan(smap.costs, smap.cases, astar))
            fields = fields_of_results(smap, results, int(full_first))
            write_golden(smap.golden_path(mode), fields)
            r = RecordedMap(rel, smap.category, mode, len(smap.cases), len(fields["full_index"]),
                            time.perf_counter() - t0, smap.golden_path(mode))
            done.append(r)
            if progress:
                progress(r)
    return done
