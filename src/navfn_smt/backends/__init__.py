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
(:class:`~navfn_smt.under_test.PlannerUnderTest`): in its arithmetic, with its fix's hooks
(:class:`~navfn_smt.spec.planner.Fix`; the spec runs them, the JIT compiles the spec's planning
call with its further call, and runs the spec's fallback where calcPath fails).
"""

from __future__ import annotations

from typing import Optional, Protocol

import numpy as np

from ..errors import NavfnInputError
from ..inputs import check_inputs
from ..spec.costs import add_border
from ..spec.extraction import EXIT_CODES, ExtractionExit, UndefinedBehaviour
from ..spec.planner import AS_SHIPPED, Fix, PlanResult, acted, extract, path_cycle_limit, plan
from ..spec.constants import POT_HIGH, PRIORITYBUFSIZE
from ..spec.propagation import check_capacity


class MapPlanner(Protocol):
    """A backend's planner for one map, with the buffer capacity it was prepared with."""

    capacity: int

    def run(self, start, goal, astar: bool, trace: bool = True, path_cycles: Optional[int] = None,
            cycles: Optional[int] = None) -> PlanResult: ...

    def extract(self, potential: np.ndarray, start, goal, path_cycles: int) -> tuple[ExtractionExit, np.ndarray]: ...

    def run_batch(self, cases, astar: bool) -> dict: ...


class Backend:
    """A planner implementation, registered by its ``name``: :meth:`prepare` gives its
    ``map_planner`` for one map, computing in the build's arithmetic ``arith``
    (spec.arithmetic; None: x86-64's) with the fix ``fix``."""

    name: str
    map_planner: type

    def __init__(self, arith=None, fix: Fix = AS_SHIPPED):
        self.arith, self.fix = arith, fix

    def prepare(self, costs: np.ndarray, capacity: Optional[int] = None) -> MapPlanner:
        return self.map_planner(costs, capacity, self.arith, self.fix)


def _capacity(capacity: Optional[int]) -> int:
    return PRIORITYBUFSIZE if capacity is None else check_capacity(capacity)


class ReferenceMapPlanner:
    def __init__(self, costs: np.ndarray, capacity: Optional[int] = None, arith=None, fix: Fix = AS_SHIPPED):
        self.costs = check_inputs(costs, (0, 0), (0, 0))
        self.capacity = _capacity(capacity)
        self.arith = arith
        self.fix = fix

    def run(self, start, goal, astar: bool, trace: bool = True, path_cycles: Optional[int] = None,
            cycles: Optional[int] = None) -> PlanResult:
        return plan(self.costs, start, goal, astar=astar, record_trace=trace, capacity=self.capacity,
                    path_cycles=path_cycles, cycles=cycles, fix=self.fix, arith=self.arith)

    def extract(self, potential: np.ndarray, start, goal, path_cycles: int) -> tuple[ExtractionExit, np.ndarray]:
        """``calcPath(path_cycles)`` alone on a given potential, with the fix's fallback where it
        returns no path: (exit, path; empty unless NEAR_GOAL)."""
        ny, nx = self.costs.shape
        ext, _ = extract([float(v) for v in np.asarray(potential, np.float32).ravel()], nx, ny,
                         (int(start[0]), int(start[1])), (int(goal[0]), int(goal[1])), int(path_cycles), self.fix,
                         self.arith)
        return ext.exit, np.array(ext.path, dtype=np.float32).reshape(-1, 2)

    def run_batch(self, cases, astar: bool) -> dict:
        """The columns of :func:`.jit.run_cases`, planned one case at a time by the spec."""
        return _columns([_row_of(self.run((sx, sy), (gx, gy), astar, trace=False))
                         for sx, sy, gx, gy in np.asarray(cases).reshape(-1, 4).tolist()])


# the scalar columns of a batch (as jit.case_columns makes them), one entry a case
_SCALARS = {"start_reached": np.bool_, "start_potential": np.float32, "cycles": np.int64, "updates": np.int64,
            "dropped": np.int64, "exit": np.int64}


def _row_of(r: PlanResult) -> tuple:
    """A plan's row: its scalar fields, then its path."""
    return r.start_reached, r.start_potential, r.cycles, r.updates, r.dropped, EXIT_CODES.index(r.exit), r.path


def _row(cols: dict, i: int) -> tuple:
    """Row ``i`` of the columns."""
    a, b = cols["path_offsets"][i], cols["path_offsets"][i + 1]
    return tuple(cols[k][i] for k in _SCALARS) + (cols["path"][a:b],)


def _columns(rows: list) -> dict:
    """Rows as the columns of :func:`.jit.run_cases`."""
    out = {k: np.array([row[j] for row in rows], t) for j, (k, t) in enumerate(_SCALARS.items())}
    out["path_offsets"] = np.cumsum([0] + [len(row[-1]) for row in rows]).astype(np.int64)
    out["path"] = np.concatenate([row[-1] for row in rows] or [np.zeros((0, 2), np.float32)]).reshape(-1, 2)
    return out


class ReferenceBackend(Backend):
    """The executable specification itself (plain Python over the concrete domain)."""

    name, map_planner = "reference", ReferenceMapPlanner


class JitMapPlanner:
    def __init__(self, costs: np.ndarray, capacity: Optional[int] = None, arith=None, fix: Fix = AS_SHIPPED):
        from .jit import JitPlanner

        self.costs = check_inputs(costs, (0, 0), (0, 0))
        self.capacity = _capacity(capacity)
        self.ny, self.nx = self.costs.shape
        self.work = JitPlanner(add_border(self.costs), self.capacity, arith)
        self.fix = fix
        self.path_cycles = path_cycle_limit(self.nx)

    def run(self, start, goal, astar: bool, trace: bool = True, path_cycles: Optional[int] = None,
            cycles: Optional[int] = None) -> PlanResult:
        """One case as :func:`~navfn_smt.spec.planner.plan` plans it: the compiled propagation with
        the fix's cycles and further call, compiled calcPath, and the fix's fallback (the spec's,
        in Python) where calcPath returns no path."""
        check_inputs(self.costs, start, goal)
        p, fix = self.work, self.fix
        start = (int(start[0]), int(start[1]))
        goal = (int(goal[0]), int(goal[1]))
        n = self.path_cycles if path_cycles is None else int(path_cycles)
        reached = p.propagate(start, goal, astar, fix.first_cycles(self.nx, self.ny, cycles), trace, fix.further)
        ran, updates, dropped, traced = p.counts()
        pot = p.pot.reshape(self.ny, self.nx).copy()
        exit_, path, descended = self._extract(p.pot, start, goal, n)
        res = PlanResult(
            start_reached=reached,
            start_potential=pot[start[1], start[0]],
            path=path,
            potential=pot,
            trace=p.trace[:traced].copy() if trace else None,
            cycles=ran,
            updates=updates,
            dropped=dropped,
            exit=exit_,
        )
        if not fix.shipped:
            res.extra = {"fix": acted(self.nx, self.ny, res.cycles, p.calls, cycles, descended)}
        return res

    def _extract(self, pot: np.ndarray, start, goal, n: int) -> tuple[ExtractionExit, np.ndarray, bool]:
        """Compiled calcPath(n) on ``pot`` and the fix's fallback (the spec's, in Python) where it
        returns no path: (exit, path, whether the fallback gave it)."""
        from . import jit as J

        code, npath = self.work.extract(start, goal, n, pot, self.fix.inclusive)
        if code == J.EXIT_UB:
            raise UndefinedBehaviour("calcPath reads outside the potential array")
        exit_ = EXIT_CODES[code]
        if exit_ is ExtractionExit.NEAR_GOAL:
            return exit_, self.work.path[:npath].copy(), False
        if self.fix.fallback is None:
            return exit_, np.zeros((0, 2), np.float32), False
        ext = self.fix.fallback.walk([float(v) for v in pot], self.nx, self.ny, start, goal, n)
        return ext.exit, np.array(ext.path, dtype=np.float32).reshape(-1, 2), ext.exit is ExtractionExit.NEAR_GOAL

    def extract(self, potential: np.ndarray, start, goal, path_cycles: int) -> tuple[ExtractionExit, np.ndarray]:
        """``calcPath(path_cycles)`` alone on a given potential, compiled, with the fix's fallback."""
        pot = np.ascontiguousarray(potential, dtype=np.float32).ravel()
        exit_, path, _ = self._extract(pot, (int(start[0]), int(start[1])), (int(goal[0]), int(goal[1])),
                                       int(path_cycles))
        return exit_, path

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
        cols = run_cases(self.work, cases, astar, self.fix.first_cycles(self.nx, self.ny), self.path_cycles,
                         self.fix.inclusive)
        if self.fix.further is None and self.fix.fallback is None:
            return cols
        return _again_where_failed(self, cols, cases, astar)


class JitBackend(Backend):
    """The spec's planning call compiled by numba (:mod:`.jit`), with any fix's further call; a
    fix's fallback runs in Python (the spec's) where calcPath returns no path."""

    name, map_planner = "jit", JitMapPlanner


_BACKENDS: dict[str, type] = {b.name: b for b in (JitBackend, ReferenceBackend)}
BACKENDS = tuple(_BACKENDS)


def _again_where_failed(planner, cols: dict, cases: np.ndarray, astar: bool) -> dict:
    """Columns planned without a fix's further call and fallback, with the cases where those can
    act (no path, or the start unreached) planned again by ``planner.run``: the further call is
    made only from an unreached start and the fallback only where calcPath returns no path, so
    every other case is planned as the fix plans it."""
    reached = np.asarray(cols["start_potential"], np.float32) < np.float32(POT_HIGH)  # potarr[startCell] < POT_HIGH
    failed = np.flatnonzero((cols["exit"] != EXIT_CODES.index(ExtractionExit.NEAR_GOAL)) | ~reached)
    if not len(failed):
        return cols
    rows = [_row(cols, i) for i in range(len(cases))]
    for i in failed.tolist():
        sx, sy, gx, gy = cases[i].tolist()
        rows[i] = _row_of(planner.run((sx, sy), (gx, gy), astar, trace=False))
    return _columns(rows)


def get_backend(name: str, planner=None) -> Backend:
    """The backend ``name`` planning as the planner under test ``planner`` does
    (:class:`~navfn_smt.under_test.PlannerUnderTest`; None: NavFn as shipped, in x86-64's
    arithmetic): in its arithmetic, with its fix."""
    if name not in _BACKENDS:
        raise NavfnInputError(f"unknown backend {name!r} (choose from {', '.join(BACKENDS)})")
    if planner is None:
        return _BACKENDS[name](None)
    return _BACKENDS[name](planner.navfn_arithmetic(), planner.fix)
