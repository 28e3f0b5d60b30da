"""The whole-planner properties, judged on one concrete planning run of the reference spec.

These are the definitions: ``check`` proves or refutes them over symbolic maps, ``search``
hunts for maps that break them, and every counterexample either reports is replayed here
before it is shown.  Each judge takes a :class:`Run` (map, start, goal, mode and the spec's
result) and answers ``None`` when the property holds or a short reason when it does not.

Names follow the paper's predicates where it has one: ``queues-obstacle-free`` is its LTL
invariant over the queues, ``no-path-before-start-potential`` its
``~PathComputed W NonInfinitePotAtInit``, ``valid-path`` its ``ValidPath``.
"""

from __future__ import annotations

import heapq
import math
from dataclasses import dataclass, field
from typing import Callable, Optional

import numpy as np

from ..maps.regions import reaches, regions
from ..spec.constants import COST_OBS, POT_HIGH
from ..spec.costs import add_border
from ..spec.extraction import ExtractionExit, UndefinedBehaviour
from ..spec.planner import AS_SHIPPED, Fix, calc_navfn, extract, path_cycle_limit
from ..spec.propagation import setup

_HIGH = np.float32(POT_HIGH)


@dataclass
class Run:
    """One planning call of the reference spec, with what the judges need to see."""

    costs: np.ndarray  # (ny, nx) uint8, border lethal as NavFn writes it
    start: tuple[int, int]
    goal: tuple[int, int]
    astar: bool
    potential: np.ndarray  # (ny, nx) float32
    start_reached: bool
    path: np.ndarray  # (M, 2) float32, empty unless exit is NEAR_GOAL
    exit: str  # an ExtractionExit value, or "undefined" (the C++ reads outside its arrays)
    queued: set = field(default_factory=set)  # every cell that was ever in a buffer
    dropped: int = 0

    @property
    def mode(self) -> str:
        return "astar" if self.astar else "dijkstra"

    @property
    def start_potential(self) -> np.float32:
        return self.potential[self.start[1], self.start[0]]


def run(costs: np.ndarray, start, goal, astar: bool, capacity: Optional[int] = None, fix: Fix = AS_SHIPPED,
        arith=None) -> Run:
    """Plan like :func:`navfn_smt.spec.planner.plan` (its :func:`~navfn_smt.spec.planner.calc_navfn`
    and :func:`~navfn_smt.spec.planner.extract`), also noting every cell ever queued.

    ``capacity`` bounds each priority buffer (PRIORITYBUFSIZE, as in C++, when None); ``fix``:
    the planner's :class:`~navfn_smt.spec.planner.Fix`; ``arith``: the
    :class:`~navfn_smt.spec.arithmetic.Arithmetic` of the build to plan as (None: x86-64's)."""
    arr = add_border(np.asarray(costs, dtype=np.uint8))
    ny, nx = arr.shape
    start, goal = (int(start[0]), int(start[1])), (int(goal[0]), int(goal[1]))
    st = setup(arr.ravel().tolist(), nx, ny, goal, capacity, arith)
    queued = set(st.cur)
    hook = lambda cycle, cells: queued.update(cells)  # noqa: E731
    reached, _ = calc_navfn(st, start, goal, astar, fix, trace_hook=hook, record_trace=False)
    queued.update(st.cur, st.nxt, st.over)
    try:
        ext, _ = extract(st.potential, nx, ny, start, goal, path_cycle_limit(nx), fix, arith)
        path, exit_ = np.array(ext.path, np.float32).reshape(-1, 2), ext.exit.value
    except UndefinedBehaviour:
        path, exit_ = np.zeros((0, 2), np.float32), "undefined"
    pot = np.array(st.potential, np.float32).reshape(ny, nx)
    return Run(arr, start, goal, astar, pot, bool(reached), path, exit_, queued, st.dropped)


# ---------------------------------------------------------------------------------------
# Definitions shared by the judges
# ---------------------------------------------------------------------------------------
def passable(costs: np.ndarray, cell) -> bool:
    return int(costs[cell[1], cell[0]]) < COST_OBS


def connected(costs: np.ndarray, start, goal) -> bool:
    """The wave from the goal can reach the start (:func:`~navfn_smt.maps.regions.reaches`):
    exactly the condition under which the start can get a finite potential at all."""
    return reaches(regions(costs), start, goal)


def nearest_cell(x, y) -> tuple[int, int]:
    """The cell that contains a path point: ``floor(v + 0.5)`` per coordinate."""
    return int(math.floor(float(x) + 0.5)), int(math.floor(float(y) + 0.5))


def path_cells(path: np.ndarray) -> list[tuple[int, int]]:
    """The cells of the path's points, consecutive repeats counted once."""
    cells: list[tuple[int, int]] = []
    for x, y in np.asarray(path, np.float32).reshape(-1, 2).tolist():
        c = nearest_cell(x, y)
        if not cells or cells[-1] != c:
            cells.append(c)
    return cells


def path_cost(costs: np.ndarray, path: np.ndarray) -> int:
    """The sum of the costs of the cells that contain the path's points (repeats once)."""
    return sum(int(costs[y, x]) for x, y in path_cells(path))


def optimal_cost(costs: np.ndarray, a, b) -> Optional[int]:
    """The cheapest 8-connected chain of passable cells from ``a`` to ``b`` under the same measure
    (every cell's cost counted, ``a`` and ``b`` included): exact Dijkstra over integers.
    ``None`` when no chain exists."""
    ny, nx = costs.shape
    a, b = tuple(a), tuple(b)
    if not (passable(costs, a) and passable(costs, b)):
        return None
    best = {a: int(costs[a[1], a[0]])}
    heap = [(best[a], a)]
    while heap:
        d, (x, y) = heapq.heappop(heap)
        if (x, y) == b:
            return d
        if d > best[(x, y)]:
            continue
        for ddx in (-1, 0, 1):
            for ddy in (-1, 0, 1):
                n = (x + ddx, y + ddy)
                if n == (x, y) or not (0 <= n[0] < nx and 0 <= n[1] < ny) or not passable(costs, n):
                    continue
                nd = d + int(costs[n[1], n[0]])
                if nd < best.get(n, 1 << 62):
                    best[n] = nd
                    heapq.heappush(heap, (nd, n))
    return None


def cost_gap(r: Run) -> Optional[int]:
    """Path cost minus the optimum between the path's first and last cells (``None`` without a
    path, or when the path touches a cell no passable chain joins)."""
    if not len(r.path):
        return None
    cells = path_cells(r.path)
    if any(not (0 <= x < r.costs.shape[1] and 0 <= y < r.costs.shape[0]) for x, y in cells):
        return None
    opt = optimal_cost(r.costs, cells[0], cells[-1])
    return None if opt is None else path_cost(r.costs, r.path) - opt


# ---------------------------------------------------------------------------------------
# The judges: None when the property holds on the run, else why not
# ---------------------------------------------------------------------------------------
def queues_obstacle_free(r: Run) -> Optional[str]:
    bad = sorted(c for c in r.queued if int(r.costs.flat[c]) >= COST_OBS)
    if bad:
        nx = r.costs.shape[1]
        return f"lethal cell {(bad[0] % nx, bad[0] // nx)} was queued"
    return None


def no_path_before_start_potential(r: Run) -> Optional[str]:
    if len(r.path) and not r.start_potential < _HIGH:
        return f"a path of {len(r.path)} points was returned although the start's potential is {r.start_potential:g}"
    return None


def valid_path(r: Run) -> Optional[str]:
    ny, nx = r.costs.shape
    for i, (x, y) in enumerate(r.path.tolist()):
        ok = False
        for cx in (math.floor(x), math.ceil(x)):
            for cy in (math.floor(y), math.ceil(y)):
                if (abs(x - cx) <= 0.5 and abs(y - cy) <= 0.5 and 0 <= cx < nx and 0 <= cy < ny
                        and passable(r.costs, (cx, cy)) and r.potential[cy, cx] < _HIGH):
                    ok = True
        if not ok:
            return f"path point {i} ({x:g}, {y:g}) is not within 1/2 of a reached passable cell"
    return None


def start_reached(r: Run) -> Optional[str]:
    if connected(r.costs, r.start, r.goal) and not r.start_potential < _HIGH:
        return "the start is connected to the goal but its potential stayed unreached"
    return None


def complete(r: Run) -> Optional[str]:
    if r.start_potential < _HIGH and r.exit != ExtractionExit.NEAR_GOAL.value:
        return f"the start's potential is {r.start_potential:g} but calcPath returned no path (exit {r.exit})"
    return None


def optimal(gap: int) -> Callable[[Run], Optional[str]]:
    def judge(r: Run) -> Optional[str]:
        g = cost_gap(r)
        if g is not None and g > gap:
            return f"the path costs {g} more than the optimum (allowed {gap})"
        return None

    return judge


@dataclass(frozen=True)
class Property:
    name: str
    statement: str
    judge: Callable[[Run], Optional[str]]


PROPERTIES = {p.name: p for p in (
    Property("queues-obstacle-free", "no buffer ever holds a lethal cell, over the whole run",
             queues_obstacle_free),
    Property("no-path-before-start-potential",
             "a path is returned only when the start's potential is finite (~PathComputed W NonInfinitePotAtInit)",
             no_path_before_start_potential),
    Property("valid-path", "every point of the returned path lies within 1/2 of a reached, passable cell",
             valid_path),
    Property("start-reached",
             "a start 4-connected to the goal through passable cells gets a finite potential", start_reached),
    Property("complete", "a finite start potential implies a returned path", complete),
)}


def judge(name: str, r: Run, gap: int = 0) -> Optional[str]:
    """Judge property ``name`` (``optimal`` takes ``gap``) on a run."""
    if name == "optimal":
        return optimal(gap)(r)
    return PROPERTIES[name].judge(r)
