"""Planner backends: one declared interface, implemented by the reference spec and the JIT.

``get_backend(name).prepare(costs, capacity=None)`` checks a map (NavFn-internal costs, a
(height, width) uint8 array) and returns a :class:`MapPlanner` for it, whose priority buffers
hold ``capacity`` cells each (PRIORITYBUFSIZE, as in C++, when None; pass
:func:`~navfn_smt.spec.propagation.unbounded_capacity` of the map for buffers that never drop); ``planner.run(start, goal, astar,
trace=True, path_cycles=None, cycles=None)`` returns a :class:`~navfn_smt.spec.planner.PlanResult` that owns
its arrays (nothing in it changes when it plans again; ``path_cycles`` and ``cycles``
replace NavFn's budgets ``4 * nx`` and ``max(nx * ny / 20, nx + ny)``); ``planner.extract(potential,
start, goal, path_cycles)`` runs calcPath alone; ``planner.run_batch(cases, astar)``
plans many cases without traces and returns the columns of :func:`.jit.run_cases`.
``get_backend(name, planner)`` gives the backend planning as a planner under test
(:class:`~navfn_smt.under_test.PlannerUnderTest`): in its arithmetic, and with the fix of
:mod:`navfn_smt.spec.fix` (:class:`FixedMapPlanner`) when its variant is ``fixed``.
"""

from __future__ import annotations

from typing import Optional, Protocol

import numpy as np

from ..errors import NavfnInputError
from ..inputs import check_inputs
from ..spec.costs import add_border
from ..spec.extraction import EXIT_CODES, ExtractionExit, UndefinedBehaviour, calc_path
from ..spec.planner import PlanResult, path_cycle_limit, plan
from ..spec.constants import POT_HIGH, PRIORITYBUFSIZE
from ..spec.propagation import check_capacity, cycle_limit
from ..spec import fix as F


class MapPlanner(Protocol):
    """A backend's planner for one map, with the buffer capacity it was prepared with."""

    capacity: int

    def run(self, start, goal, astar: bool, trace: bool = True, path_cycles: Optional[int] = None,
            cycles: Optional[int] = None) -> PlanResult: ...

    def extract(self, potential: np.ndarray, start, goal, path_cycles: int) -> tuple[ExtractionExit, np.ndarray]: ...

    def run_batch(self, cases, astar: bool) -> dict: ...


class Backend(Protocol):
    name: str

    def prepare(self, costs: np.ndarray, capacity: Optional[int] = None) -> MapPlanner: ...


def _capacity(capacity: Optional[int]) -> int:
    return PRIORITYBUFSIZE if capacity is None else check_capacity(capacity)


class ReferenceMapPlanner:
    def __init__(self, costs: np.ndarray, capacity: Optional[int] = None, arith=None):
        self.costs = check_inputs(costs, (0, 0), (0, 0))
        self.capacity = _capacity(capacity)
        self.arith = arith

    def run(self, start, goal, astar: bool, trace: bool = True, path_cycles: Optional[int] = None,
            cycles: Optional[int] = None) -> PlanResult:
        return plan(self.costs, start, goal, astar=astar, record_trace=trace, capacity=self.capacity,
                    path_cycles=path_cycles, cycles=cycles, arith=self.arith)

    def run_fixed(self, start, goal, astar: bool, trace: bool = True, path_cycles: Optional[int] = None,
                  cycles: Optional[int] = None) -> PlanResult:
        """:meth:`run` with the fix's propagation (:func:`navfn_smt.spec.fix.propagate_on`), without
        its descent."""
        return plan(self.costs, start, goal, astar=astar, record_trace=trace, capacity=self.capacity,
                    path_cycles=path_cycles, cycles=cycles, variant="fixed", descent=False, arith=self.arith)

    def extract(self, potential: np.ndarray, start, goal, path_cycles: int) -> tuple[ExtractionExit, np.ndarray]:
        """``calcPath(path_cycles)`` alone on a given potential: (exit, path; empty unless NEAR_GOAL)."""
        ny, nx = self.costs.shape
        ext = calc_path([float(v) for v in np.asarray(potential, np.float32).ravel()], nx, ny,
                        (int(start[0]), int(start[1])), (int(goal[0]), int(goal[1])), int(path_cycles),
                        arith=self.arith)
        return ext.exit, np.array(ext.path, dtype=np.float32).reshape(-1, 2)

    def run_batch(self, cases, astar: bool) -> dict:
        """The columns of :func:`.jit.run_cases`, planned one case at a time by the spec."""
        return _columns([self.run((sx, sy), (gx, gy), astar, trace=False)
                         for sx, sy, gx, gy in np.asarray(cases).reshape(-1, 4).tolist()])


def _columns(results: list) -> dict:
    """Plan results as the columns of :func:`.jit.run_cases`."""
    offsets = np.cumsum([0] + [len(r.path) for r in results])
    return {
        "start_reached": np.array([r.start_reached for r in results], np.bool_),
        "start_potential": np.array([r.start_potential for r in results], np.float32),
        "cycles": np.array([r.cycles for r in results], np.int64),
        "updates": np.array([r.updates for r in results], np.int64),
        "dropped": np.array([r.dropped for r in results], np.int64),
        "exit": np.array([list(ExtractionExit).index(r.exit) for r in results], np.int64),
        "path_offsets": offsets.astype(np.int64),
        "path": np.concatenate([r.path for r in results] or [np.zeros((0, 2), np.float32)]).reshape(-1, 2),
    }


def _row(cols: dict, i: int) -> tuple:
    """Row ``i`` of the columns: its scalar fields and its path."""
    a, b = cols["path_offsets"][i], cols["path_offsets"][i + 1]
    return tuple(cols[k][i] for k in _SCALARS) + (cols["path"][a:b],)


_SCALARS = ("start_reached", "start_potential", "cycles", "updates", "dropped", "exit")


class FixedMapPlanner:
    """A backend's planner with the fix of :mod:`navfn_smt.spec.fix`: the backend plans as
    NavFn does, and where it returns no path, or the start is unreached, it plans the case again
    with the fix.  The fix never changes a path the original returns from a reached start, so
    this is the fixed planner, and the fix is stated once (in the spec, with the kernels).  (From
    an unreached start the original returns no path in x86-64's arithmetic, but it can where
    ``(int)`` saturates, as on arm64: the patched propagation goes on there all the same.)"""

    def __init__(self, inner: MapPlanner):
        self.inner = inner
        self.costs = inner.costs
        self.capacity = inner.capacity

    def run(self, start, goal, astar: bool, trace: bool = True, path_cycles: Optional[int] = None,
            cycles: Optional[int] = None) -> PlanResult:
        """The original's run where it returns a path from a reached start; from a reached start
        without one, the same run with the descent's path; from an unreached start (with a path
        or not), the fixed run again, then the descent where it has no path."""
        res = self.inner.run(start, goal, astar, trace, path_cycles, cycles)
        res.extra = {**res.extra, "fix": []}
        if not F.reached(res.start_potential):  # the fix propagates on
            res = self.inner.run_fixed(start, goal, astar, trace, path_cycles, cycles)
        elif len(res.path):
            return res
        n = path_cycle_limit(self.costs.shape[1]) if path_cycles is None else path_cycles
        return res if len(res.path) else F.with_descent(res, start, goal, n)

    def extract(self, potential: np.ndarray, start, goal, path_cycles: int) -> tuple[ExtractionExit, np.ndarray]:
        """calcPath and, where it returns no path, the fix's descent (``calcPathDescent``)."""
        exit_, path = self.inner.extract(potential, start, goal, path_cycles)
        if exit_ is ExtractionExit.NEAR_GOAL:
            return exit_, path
        ny, nx = self.costs.shape
        ext = F.descend([float(v) for v in np.asarray(potential, np.float32).ravel()], nx, ny,
                        (int(start[0]), int(start[1])), (int(goal[0]), int(goal[1])), int(path_cycles))
        return ext.exit, np.array(ext.path, dtype=np.float32).reshape(-1, 2)

    def run_batch(self, cases, astar: bool) -> dict:
        """The backend's columns, the cases it plans no path for, or from an unreached start,
        planned again with the fix."""
        cases = np.asarray(cases).reshape(-1, 4)
        cols = self.inner.run_batch(cases, astar)
        reached = np.asarray(cols["start_potential"], np.float32) < np.float32(POT_HIGH)  # F.reached, per case
        failed = np.flatnonzero((cols["exit"] != EXIT_CODES.index(ExtractionExit.NEAR_GOAL)) | ~reached)
        if not len(failed):
            return cols
        rows = [_row(cols, i) for i in range(len(cases))]
        for i in failed.tolist():
            sx, sy, gx, gy = cases[i].tolist()
            r = self.run((sx, sy), (gx, gy), astar, trace=False)
            rows[i] = (r.start_reached, r.start_potential, r.cycles, r.updates, r.dropped,
                       EXIT_CODES.index(r.exit), r.path)
        out = {k: np.array([row[j] for row in rows], cols[k].dtype) for j, k in enumerate(_SCALARS)}
        out["path_offsets"] = np.cumsum([0] + [len(row[-1]) for row in rows]).astype(np.int64)
        out["path"] = np.concatenate([row[-1] for row in rows] or [np.zeros((0, 2), np.float32)]).reshape(-1, 2)
        return out


class ReferenceBackend:
    """The executable specification itself (plain Python over the concrete domain)."""

    name = "reference"

    def __init__(self, arith=None):
        self.arith = arith  # the build's arithmetic (spec.arithmetic; None: x86-64's)

    def prepare(self, costs: np.ndarray, capacity: Optional[int] = None) -> ReferenceMapPlanner:
        return ReferenceMapPlanner(costs, capacity, self.arith)


class JitMapPlanner:
    def __init__(self, costs: np.ndarray, capacity: Optional[int] = None, arith=None):
        from .jit import JitPlanner

        self.costs = check_inputs(costs, (0, 0), (0, 0))
        self.capacity = _capacity(capacity)
        self.ny, self.nx = self.costs.shape
        self.work = JitPlanner(add_border(self.costs), self.capacity, arith)
        self.cycles = cycle_limit(self.nx, self.ny)
        self.path_cycles = path_cycle_limit(self.nx)

    def run(self, start, goal, astar: bool, trace: bool = True, path_cycles: Optional[int] = None,
            cycles: Optional[int] = None, fixed: bool = False) -> PlanResult:
        from . import jit as J

        check_inputs(self.costs, start, goal)
        p = self.work
        start = (int(start[0]), int(start[1]))
        goal = (int(goal[0]), int(goal[1]))
        n = self.path_cycles if path_cycles is None else int(path_cycles)
        limit = self.cycles if cycles is None else int(cycles)
        if fixed:
            F.check_cycles(limit)
        reached, code, npath = p.run(start, goal, astar, limit, n, trace, fixed)
        if code == J.EXIT_UB:
            raise UndefinedBehaviour("calcPath reads outside the potential array")
        pot = p.pot.reshape(self.ny, self.nx).copy()
        exit_ = EXIT_CODES[code]
        return PlanResult(
            start_reached=reached,
            start_potential=pot[start[1], start[0]],
            path=p.path[:npath].copy() if exit_ is ExtractionExit.NEAR_GOAL else np.zeros((0, 2), np.float32),
            potential=pot,
            trace=p.trace[: p.counters[J.TRACE_LEN]].copy() if trace else None,
            cycles=int(p.counters[J.CYCLES]),
            updates=int(p.counters[J.UPDATES]),
            dropped=int(p.counters[J.DROPPED]),
            exit=exit_,
        )

    def run_fixed(self, start, goal, astar: bool, trace: bool = True, path_cycles: Optional[int] = None,
                  cycles: Optional[int] = None) -> PlanResult:
        """:meth:`run` with the fix's propagation, compiled (:func:`.jit.propagate_on`), without its
        descent."""
        res = self.run(start, goal, astar, trace, path_cycles, cycles, fixed=True)
        res.extra = {"fix": ["propagation"] if self.work.calls else []}
        return res

    def extract(self, potential: np.ndarray, start, goal, path_cycles: int) -> tuple[ExtractionExit, np.ndarray]:
        """``calcPath(path_cycles)`` alone on a given potential, compiled."""
        from .jit import EXIT_UB, calc_path_zeroed

        pot = np.ascontiguousarray(potential, dtype=np.float32).ravel()
        n = int(path_cycles)
        path = np.empty((max(n, 0) + 1, 2), np.float32)
        p = self.work
        code, npath = calc_path_zeroed(p.D, pot, self.nx, self.ny, int(start[0]), int(start[1]), int(goal[0]), int(goal[1]),
                                 n, p.gradx, p.grady, path)
        if code == EXIT_UB:
            raise UndefinedBehaviour("calcPath reads outside the potential array")
        exit_ = EXIT_CODES[code]
        return exit_, path[:npath].copy() if exit_ is ExtractionExit.NEAR_GOAL else np.zeros((0, 2), np.float32)

    def run_batch(self, cases, astar: bool) -> dict:
        """Plan many cases in one compiled call (no traces); see :func:`.jit.run_cases`.  The
        cells are checked in one vectorised test (a hunt plans hundreds of cases a map, and a
        Python check per case took half of its time); the first case off the map is refused
        as :func:`~navfn_smt.inputs.check_inputs` refuses it."""
        from .jit import run_cases

        cases = np.asarray(cases, np.int64).reshape(-1, 4)
        xs, ys = cases[:, 0::2], cases[:, 1::2]
        off = ~((xs >= 0) & (xs < self.nx) & (ys >= 0) & (ys < self.ny)).all(axis=1)
        if off.any():
            sx, sy, gx, gy = cases[int(np.argmax(off))].tolist()
            check_inputs(self.costs, (sx, sy), (gx, gy))
        return run_cases(self.work, cases, astar, self.cycles, self.path_cycles)


class JitBackend:
    """The kernels compiled by numba, with loops and buffers of its own (:mod:`.jit`)."""

    name = "jit"

    def __init__(self, arith=None):
        self.arith = arith  # the build's arithmetic (spec.arithmetic; None: x86-64's)

    def prepare(self, costs: np.ndarray, capacity: Optional[int] = None) -> JitMapPlanner:
        return JitMapPlanner(costs, capacity, self.arith)


_BACKENDS: dict[str, type] = {b.name: b for b in (JitBackend, ReferenceBackend)}
BACKENDS = tuple(_BACKENDS)


class _Fixed:
    """A backend whose planners carry the fix (:class:`FixedMapPlanner`)."""

    def __init__(self, inner: Backend):
        self.inner = inner
        self.name = inner.name

    def prepare(self, costs: np.ndarray, capacity: Optional[int] = None) -> FixedMapPlanner:
        return FixedMapPlanner(self.inner.prepare(costs, capacity))


def get_backend(name: str, planner=None) -> Backend:
    """The backend ``name`` planning as the planner under test ``planner`` does
    (:class:`~navfn_smt.under_test.PlannerUnderTest`; None: NavFn as shipped, in x86-64's
    arithmetic): in its arithmetic, with the fix when its variant is ``fixed``."""
    if name not in _BACKENDS:
        raise NavfnInputError(f"unknown backend {name!r} (choose from {', '.join(BACKENDS)})")
    if planner is None:
        return _BACKENDS[name](None)
    backend = _BACKENDS[name](planner.navfn_arithmetic())
    return _Fixed(backend) if planner.variant == "fixed" else backend
