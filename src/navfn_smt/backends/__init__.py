"""Planner backends with one interface: the reference spec and the numba JIT.

``get_backend(name).prepare(costs)`` returns a runner for one map (NavFn-internal
costs, a (height, width) uint8 array); ``runner.run(start, goal, astar, trace=True)`` returns a
:class:`~navfn_smt.spec.planner.PlanResult` (its ``trace`` is None when ``trace`` is False).  A JIT result's arrays are views into the
runner's work buffers and stay valid until its next ``run``.
"""

from __future__ import annotations

import numpy as np

from ..errors import NavfnInputError
from ..spec.costs import add_border
from ..spec.extraction import ExtractionExit
from ..inputs import check_inputs
from ..spec.planner import PlanResult, plan
from ..spec.propagation import cycle_limit

BACKENDS = ("jit", "reference")


class ReferenceRunner:
    def __init__(self, costs: np.ndarray):
        self.costs = costs

    def run(self, start, goal, astar: bool, trace: bool = True) -> PlanResult:
        return plan(self.costs, start, goal, astar=astar, record_trace=trace)


class ReferenceBackend:
    name = "reference"

    def prepare(self, costs: np.ndarray) -> ReferenceRunner:
        return ReferenceRunner(check_inputs(costs, (0, 0), (0, 0)))


class JitRunner:
    def __init__(self, costs: np.ndarray):
        from .jit import JitPlanner

        self.costs = check_inputs(costs, (0, 0), (0, 0))
        self.ny, self.nx = self.costs.shape
        self.planner = JitPlanner(add_border(self.costs))
        self.cycles = cycle_limit(self.nx, self.ny)

    def run(self, start, goal, astar: bool, trace: bool = True) -> PlanResult:
        from .jit import EXIT_NAMES, EXIT_UB

        check_inputs(self.costs, start, goal)
        p = self.planner
        start = (int(start[0]), int(start[1]))
        goal = (int(goal[0]), int(goal[1]))
        reached, code, npath = p.run(start, goal, astar, self.cycles, 4 * self.nx, trace)
        if code == EXIT_UB:
            from ..spec.extraction import UndefinedBehaviour

            raise UndefinedBehaviour("calcPath reads outside the potential array")
        pot = p.pot.reshape(self.ny, self.nx)
        path = p.path[:npath] if code == 0 else p.path[:0]
        return PlanResult(
            start_reached=reached,
            start_potential=pot[start[1], start[0]],
            path=path,
            potential=pot,
            trace=p.trace[: p.counters[3]] if trace else None,
            cycles=int(p.counters[0]),
            updates=int(p.counters[1]),
            dropped=int(p.counters[2]),
            exit=ExtractionExit(EXIT_NAMES[code]),
        )


    def run_batch(self, cases, astar: bool) -> dict:
        """Plan many cases in one compiled call (no traces); see :func:`.jit.run_cases`."""
        from .jit import run_cases

        for sx, sy, gx, gy in np.asarray(cases).reshape(-1, 4).tolist():
            check_inputs(self.costs, (sx, sy), (gx, gy))
        return run_cases(self.planner, cases, astar, self.cycles, 4 * self.nx)


class JitBackend:
    name = "jit"

    def prepare(self, costs: np.ndarray) -> JitRunner:
        return JitRunner(costs)


def get_backend(name: str):
    if name == "reference":
        return ReferenceBackend()
    if name == "jit":
        return JitBackend()
    raise NavfnInputError(f"unknown backend {name!r} (choose from {', '.join(BACKENDS)})")
