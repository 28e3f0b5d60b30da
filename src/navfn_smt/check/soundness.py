"""The bounded checks held against concrete runs: every map of a size over a reduced cost set.

A ``proved`` that a concrete map refutes is the worst bug a verifier can have.  This sweep
plans every map of a size whose passable interior cells take costs from a small set
(:data:`COSTS`, lethal added), every start and goal, each mode, with the compiled spec, and
judges the properties on each case the way :mod:`.properties` does.  It shares nothing with
the symbolic side but the spec: not the reductions, not the encoding, not the solvers.  A
size the check proved must show no failure here (``benchmarks/check_soundness.py`` and
``tests/test_check_reductions.py`` hold the committed reports to it).
"""

from __future__ import annotations

import itertools
from dataclasses import dataclass, field

import numpy as np

from ..spec.constants import COST_OBS, POT_HIGH
from ..spec.extraction import ExtractionExit, exit_code
from ..under_test import ORIGINAL, PlannerUnderTest

COSTS = (50, 51, 100, 200, 253)  # the reduced set: the ends of 50..253, a neighbour of the low end, two between
SWEPT = ("complete", "start-reached", "no-path-before-start-potential")
_NEAR_GOAL = exit_code(ExtractionExit.NEAR_GOAL)


@dataclass
class Sweep:
    """What the sweep of one size found: cases run, failures per property, the first failure of each."""

    size: tuple
    costs: tuple
    planner: PlannerUnderTest
    maps: int = 0
    cases: int = 0
    failures: dict = field(default_factory=lambda: {n: 0 for n in SWEPT})
    first: dict = field(default_factory=dict)


def failing(name: str, finite: np.ndarray, returned: np.ndarray, connected: np.ndarray) -> np.ndarray:
    """Per case, whether ``name`` fails (the judges of :mod:`.properties`, vectorised)."""
    if name == "complete":
        return finite & ~returned
    if name == "start-reached":
        return connected & ~finite
    if name == "no-path-before-start-potential":
        return returned & ~finite
    raise ValueError(f"the sweep does not judge {name!r}")


def _judge(out: Sweep, backend, arr: np.ndarray, pairs: np.ndarray, modes) -> None:
    """Plan every pair of ``pairs`` on the map ``arr`` in each mode, judged into ``out``."""
    from ..maps.regions import reaches_all, regions

    high = np.float32(POT_HIGH)
    out.maps += 1
    connected = reaches_all(regions(arr), pairs)
    for astar in modes:
        got = backend.prepare(arr).run_batch(pairs, astar)
        finite = got["start_potential"] < high
        returned = got["exit"] == _NEAR_GOAL
        out.cases += len(pairs)
        for n in SWEPT:
            f = failing(n, finite, returned, connected)
            if f.any():
                out.failures[n] += int(f.sum())
                if n not in out.first:
                    i = int(np.argmax(f))
                    out.first[n] = {"costs": arr.tolist(), "start": pairs[i, :2].tolist(),
                                    "goal": pairs[i, 2:].tolist(), "mode": "astar" if astar else "dijkstra"}


def _cells(nx: int, ny: int):
    """The interior cells of the size, and every ordered start/goal pair of them."""
    inner = [(x, y) for y in range(1, ny - 1) for x in range(1, nx - 1)]
    return inner, np.array([(sx, sy, gx, gy) for sx, sy in inner for gx, gy in inner], np.int64)


def _map(nx: int, ny: int, inner, combo) -> np.ndarray:
    arr = np.full((ny, nx), COST_OBS, np.uint8)
    for (x, y), c in zip(inner, combo):
        arr[y, x] = c
    return arr


def sweep(nx: int, ny: int, costs=COSTS, modes=(True, False), planner: PlannerUnderTest = ORIGINAL,
          progress=None) -> Sweep:
    """Every map of ``nx`` x ``ny`` whose interior cells take a cost of ``costs`` or COST_OBS,
    every interior start and goal, each mode (``True``: A*), planned as ``planner`` plans (its
    variant, in its arithmetic)."""
    from ..backends import get_backend

    backend = get_backend("jit", planner)
    inner, pairs = _cells(nx, ny)
    out = Sweep((nx, ny), tuple(costs), planner)
    for k, combo in enumerate(itertools.product(tuple(costs) + (COST_OBS,), repeat=len(inner))):
        _judge(out, backend, _map(nx, ny, inner, combo), pairs, modes)
        if progress and k % 1000 == 0:
            progress(out)
    return out


def sample(nx: int, ny: int, maps: int, seed: int = 0, lo: int = 50, hi: int = COST_OBS - 1, lethal: float = 0.15,
           modes=(True, False), planner: PlannerUnderTest = ORIGINAL, progress=None) -> Sweep:
    """``maps`` random maps of ``nx`` x ``ny`` (``numpy.random.default_rng(seed)``): each interior
    cell lethal with probability ``lethal``, else a cost uniform in ``lo..hi``; every interior
    start and goal, each mode.  Evidence, not a proof: the product of :func:`sweep` is exhaustive
    over its cost set, this covers the whole cost range thinly."""
    from ..backends import get_backend

    backend = get_backend("jit", planner)
    inner, pairs = _cells(nx, ny)
    rng = np.random.default_rng(seed)
    out = Sweep((nx, ny), (lo, hi), planner)
    for k in range(maps):
        combo = np.where(rng.random(len(inner)) < lethal, COST_OBS, rng.integers(lo, hi + 1, len(inner)))
        _judge(out, backend, _map(nx, ny, inner, combo), pairs, modes)
        if progress and k % 1000 == 0:
            progress(out)
    return out
