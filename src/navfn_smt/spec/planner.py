"""One NavFn planning call, exactly as Nav2 (and the golden suite) runs it.

For every case, on a fresh copy of the costs: ``setGoal``, ``setStart``,
``setupNavFn(true)``; then A* (``priInc = 2 * COST_NEUTRAL``,
``propNavFnAstar(max(nx*ny/20, nx+ny))``) or Dijkstra
(``propNavFnDijkstra(max(nx*ny/20, nx+ny), atStart=true)``); then ``calcPath(4 * nx)``.
"""

from __future__ import annotations

import hashlib
from dataclasses import dataclass, field
from typing import Optional

import numpy as np

from ..inputs import check_inputs
from .costs import add_border
from .extraction import ExtractionExit, calc_path
from .propagation import TraceHook, cycle_limit, propagate, setup
from . import fix as F


def path_cycle_limit(nx: int) -> int:
    """``calcPath(nx * 4)``: the extraction budget ``calcNavFnAstar``/``calcNavFnDijkstra`` give."""
    return 4 * nx


@dataclass
class PlanResult:
    start_reached: bool
    start_potential: np.float32
    path: np.ndarray  # (M, 2) float32, empty when calcPath returned 0
    potential: np.ndarray  # (ny, nx) float32 after propagation
    trace: Optional[np.ndarray]  # int32 [n0, c..., n1, c...]; None when not recorded
    cycles: int
    updates: int
    dropped: int = 0
    exit: Optional[ExtractionExit] = None
    extra: dict = field(default_factory=dict)

    @property
    def potential_sha256(self) -> bytes:
        return sha256_f32(self.potential)

    @property
    def trace_sha256(self) -> bytes:
        return sha256_i32(self.trace)


def sha256_f32(a: np.ndarray) -> bytes:
    return hashlib.sha256(np.ascontiguousarray(a, dtype="<f4").tobytes()).digest()


def sha256_i32(a: np.ndarray) -> bytes:
    return hashlib.sha256(np.ascontiguousarray(a, dtype="<i4").tobytes()).digest()


def plan(
    costs: np.ndarray,
    start: tuple[int, int],
    goal: tuple[int, int],
    astar: bool = True,
    trace_hook: Optional[TraceHook] = None,
    cycles: Optional[int] = None,
    path_cycles: Optional[int] = None,
    record_trace: bool = True,
    capacity: Optional[int] = None,
    variant: str = F.DEFAULT_VARIANT,
    descent: bool = True,
    arith=None,
) -> PlanResult:
    """Plan on NavFn-internal costs (a (height, width) uint8 array) with the reference spec.

    ``start`` is NavFn's start (where extraction begins), ``goal`` where propagation begins.
    ``capacity`` bounds each priority buffer (default PRIORITYBUFSIZE, as in C++).
    ``variant="fixed"`` plans with the fix (:mod:`.fix`); ``extra["fix"]`` then lists the
    parts that acted (``"propagation"``, ``"descent"``), empty where the original plans;
    ``descent=False`` leaves the descent out (the fixed propagation and calcPath only).
    ``arith``: the :class:`~.arithmetic.Arithmetic` of the build to plan as (default x86-64's).
    """
    fixed = F.check_variant(variant) == "fixed"
    arr = check_inputs(costs, start, goal)
    ny, nx = arr.shape
    start = (int(start[0]), int(start[1]))
    goal = (int(goal[0]), int(goal[1]))
    cost_list = add_border(arr).ravel().tolist()
    st = setup(cost_list, nx, ny, goal, capacity, arith)
    limit = cycle_limit(nx, ny) if cycles is None else cycles
    acted = []
    if fixed:
        reached, calls = F.propagate_on(st, start, goal, astar, limit, True, trace_hook, record_trace)
        if calls:
            acted.append("propagation")
    else:
        reached = propagate(st, start, goal, astar, limit, at_start=True, trace_hook=trace_hook,
                            record_trace=record_trace)
    n = path_cycle_limit(nx) if path_cycles is None else path_cycles
    ext = calc_path(st.potential, nx, ny, start, goal, n, arith=arith)
    if fixed and descent and ext.exit is not ExtractionExit.NEAR_GOAL:
        ext = F.descend(st.potential, nx, ny, start, goal, n)
        if ext.exit is ExtractionExit.NEAR_GOAL:
            acted.append("descent")
    pot = np.array(st.potential, dtype=np.float32).reshape(ny, nx)
    path = np.array(ext.path, dtype=np.float32).reshape(-1, 2)
    return PlanResult(
        start_reached=bool(reached),
        start_potential=pot[start[1], start[0]],
        path=path,
        potential=pot,
        trace=np.array(st.trace, dtype=np.int32) if record_trace else None,
        cycles=st.cycles,
        updates=st.updates,
        dropped=st.dropped,
        exit=ext.exit,
        extra={"fix": acted} if fixed else {},
    )
