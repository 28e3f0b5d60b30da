"""The difftest against the C++ live: every case of a suite planned by the user's own build of
NavFn (an oracle, :mod:`navfn_smt.oracle`) and by the spec, compared field by field.

The C++'s answers take the place of the golden files: for each map and mode they are folded
into the golden arrays in memory (:func:`~.record.fields_of_results`, the first 50 cases with
their whole potential and trace, as recorded suites keep them), and the spec's results are
compared with them exactly as with golden files (:func:`~.runner.compare_case`): the path's
float32 values, the potential's and the trace's SHA-256, ``start_reached``, cycles, updates.
The C++ serves a map's cases in one request, so the run costs about what planning costs.
"""

from __future__ import annotations

import time
from pathlib import Path
from typing import Callable, Iterable, Optional

from ..backends import get_backend
from ..maps.suite import discover, load_map
from ..spec.extraction import UndefinedBehaviour
from ..spec.propagation import unbounded_capacity
from .record import fields_of_results
from .runner import Disagreement, Summary, TaskOutcome, compare_case

MAX_DETAILS = 20  # disagreements kept per map and mode (every one is counted)


def run_live(root, modes: Iterable[str], backend: str, oracle,
             progress: Optional[Callable[[TaskOutcome], None]] = None, unbounded: bool = False,
             planner=None) -> Summary:
    """Every case of ``root`` in ``modes``: ``backend`` against the running ``oracle``
    (``unbounded``: the spec's buffers never drop a push, as the C++ of ``navfn-unbounded``;
    ``planner``: the planner under test, :class:`~navfn_smt.under_test.PlannerUnderTest`, read
    from the build: the spec in the build's arithmetic, with the fix as the C++ of ``navfn-fixed``)."""
    root = Path(root)
    summary = Summary()
    be = get_backend(backend, planner)
    for d in discover(root):
        smap = load_map(d, root)
        ny, nx = smap.costs.shape
        planner = be.prepare(smap.costs, capacity=unbounded_capacity(nx, ny) if unbounded else None)
        rel = str(Path(d).resolve().relative_to(root.resolve()))
        for mode in modes:
            o = _compare_map(smap, rel, mode, planner, oracle)
            summary.add(o)
            if progress:
                progress(o)
    return summary


def _compare_map(smap, rel: str, mode: str, planner, oracle) -> TaskOutcome:
    astar = mode == "astar"
    g = fields_of_results(smap, oracle.plan(smap.costs, smap.cases, astar))
    full_pos = {int(k): j for j, k in enumerate(g["full_index"])}
    out = TaskOutcome(rel, smap.category, mode, len(smap.cases), 0, 0.0)
    t0 = time.perf_counter()
    for i, (sx, sy, gx, gy) in enumerate(smap.cases.tolist()):
        try:
            verdict = compare_case(planner.run((sx, sy), (gx, gy), astar), g, i, full_pos, white_box=oracle.traced)
        except UndefinedBehaviour as e:
            verdict = ("undefined_behaviour", {"message": str(e)})
        if verdict is None:
            out.agreeing += 1
        elif len(out.disagreements) < MAX_DETAILS:
            out.disagreements.append(Disagreement(rel, smap.category, mode, i, [sx, sy, gx, gy], *verdict))
    out.seconds = time.perf_counter() - t0
    return out
