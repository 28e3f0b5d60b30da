"""Nav2's planner benchmark (``tools/planner_benchmarking`` of navigation2), for NavFn as shipped
("original") and NavFn with the fix ("fixed", :mod:`navfn_smt.spec.fix`), in both modes.

What ``navfn-smt nav2-benchmark`` runs (docs/nav2-benchmark.md).  Nav2's benchmark drives a
live planner server; here the planner is the bit-exact model of ``NavfnPlanner::createPlan``
(:func:`navfn_smt.nav2.plugin.create_plan`) on the global costmap the model builds from the
map and a params file, and optionally the C++ plugin itself (an oracle build), whose poses
must then equal the model's bit for bit.

**The pairs** (:func:`draw_pairs`).  One ``numpy.random.default_rng(seed)`` generator (seed 33
by default) draws every number, in this order, until ``n`` pairs (100 by default) are drawn:

1. the start: a row ``rng.integers(lo, hi_y, endpoint=True)``, then a column
   ``rng.integers(lo, hi_x, endpoint=True)``, where ``lo = margin`` and ``hi = size - 1 - margin``
   (a margin of 100 cells: at least 100 cells between the cell and each edge of the map); the
   cell is kept when its costmap cost is below ``max_cost`` (210), else a new row and column are
   drawn; then a yaw ``rng.uniform(0, 2 pi)``;
2. the goal: a row and a column drawn the same way, kept when the cell's cost is below 210
   *and* its position is more than ``min_distance`` (3 m) from the start's (Euclidean, in
   metres), else drawn again; then its yaw.

A cell (col, row) becomes the pose ``(origin_x + col * resolution, origin_y + row * resolution)``
(the cell's corner, as Nav2's script places it; the resolution is the costmap's, the float32 of
the map YAML widened to double) with the drawn yaw.  Every pair drawn is kept and planned: a
planner that fails a pair counts a failure (Nav2's script instead drops a pair some planner
fails and draws another, so its table never shows a failure).  Nav2's script draws with
Python's ``random`` seeded 33 and its window includes row and column ``size - margin``: the
rules are the same, the pairs are not Nav2's.

**The planners** (:data:`PLANNERS`): NavFn original and fixed, Dijkstra and A*, each planning
every pair with the params file's plugin parameters (``use_astar`` and ``variant`` replaced).

**The metrics**, per planner, over the pairs it planned (a plan is a ``createPlan`` that
returned poses):

* path length (m): the sum, over consecutive poses of the path, of the Euclidean distance
  ``sqrt(dx**2 + dy**2)`` between them (:func:`path_length`); averaged over the pairs;
* planning time (s): the C++'s own time in ``createPlan`` for the pair when an oracle is given
  (one request per pair), else the wall time of the model's :func:`create_plan`; averaged over
  the pairs;
* path cost: for every pose of the path, the costmap cost of the cell ``Costmap2D::worldToMap``
  gives, ``(floor((x - origin_x) / resolution), floor((y - origin_y) / resolution))``
  (:func:`path_costs`); a path's *average cost* is the mean over its poses, and the table's
  average cost is the mean of that over the pairs; the table's *maximum cost* is the maximum
  over every pose of every path.  (Nav2's ``process_data.py`` prints as "Max cost" the mean over
  pairs of each path's maximum: :attr:`PlannerResult.mean_path_max_cost` keeps that one.)
* failures: the pairs with no plan (``createPlan`` threw, or returned no pose).
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field, replace
from typing import Callable, Optional

import numpy as np

from ..spec.fix import FIX as THE_FIX
from ..spec.planner import AS_SHIPPED, Fix
from ..errors import NavfnInputError
from .params import PlannerParams
from .plugin import EMPTY_PATH, Costmap, Pose, create_plan

SEED = 33
PAIRS = 100
MAX_COST = 210  # a start or goal cell's costmap cost is below this
MIN_DISTANCE = 3.0  # metres between start and goal, strictly more
MARGIN = 100  # cells between a drawn cell and each edge of the map, at least
DRAWS_PER_PAIR = 10_000  # cells drawn per pair at most before the map is declared unsuitable


@dataclass(frozen=True)
class Planner:
    """One row of the table: NavFn with ``fix`` (as shipped, or patched) in one mode."""

    fix: Fix
    use_astar: bool

    @property
    def variant(self) -> str:
        return self.fix.name

    @property
    def mode(self) -> str:
        return "astar" if self.use_astar else "dijkstra"

    @property
    def name(self) -> str:
        return f"NavFn {self.variant} {'A*' if self.use_astar else 'Dijkstra'}"


PLANNERS = tuple(Planner(f, astar) for astar in (False, True) for f in (AS_SHIPPED, THE_FIX))


def planners_for(modes) -> tuple[Planner, ...]:
    """The rows for the modes ``modes`` ("dijkstra", "astar"), in the order of :data:`PLANNERS`."""
    return tuple(p for p in PLANNERS if p.mode in modes)


@dataclass(frozen=True)
class Pair:
    """A start and a goal: their drawn cells (col, row) and poses."""

    start_cell: tuple[int, int]
    goal_cell: tuple[int, int]
    start: Pose
    goal: Pose

    @property
    def distance(self) -> float:
        return math.hypot(self.goal.x - self.start.x, self.goal.y - self.start.y)


@dataclass
class Draw:
    """The drawn pairs and how many cells were drawn to get them."""

    pairs: list
    cells_drawn: int


def _window(size: int, margin: int, axis: str) -> tuple[int, int]:
    lo, hi = margin, size - 1 - margin
    if hi < lo:
        raise NavfnInputError(f"the map is {size} cells along {axis}: a margin of {margin} cells from the border "
                              f"leaves no cell to draw")
    return lo, hi


def draw_pairs(cm: Costmap, n: int = PAIRS, seed: int = SEED, max_cost: int = MAX_COST,
               min_distance: float = MIN_DISTANCE, margin: int = MARGIN) -> Draw:
    """``n`` start/goal pairs on ``cm`` by the protocol of the module's docstring."""
    if n < 1:
        raise NavfnInputError(f"--pairs {n}: at least 1 pair")
    if margin < 0:
        raise NavfnInputError(f"--margin {margin}: a number of cells, at least 0")
    lo_x, hi_x = _window(cm.size_x, margin, "x")
    lo_y, hi_y = _window(cm.size_y, margin, "y")
    window = cm.costs[lo_y:hi_y + 1, lo_x:hi_x + 1]
    if not (window < max_cost).any():
        raise NavfnInputError(f"no cell of cost below {max_cost} at least {margin} cells from the border")
    rng = np.random.default_rng(seed)
    res = cm.resolution
    budget = DRAWS_PER_PAIR * n
    drawn = 0

    def cell(accept) -> tuple[tuple[int, int], Pose]:
        nonlocal drawn
        while True:
            if drawn >= budget:
                raise NavfnInputError(f"{drawn} cells drawn without finding {n} pairs of cells of cost below "
                                      f"{max_cost} more than {min_distance:g} m apart: the map does not suit "
                                      f"the protocol")
            drawn += 1
            row = int(rng.integers(lo_y, hi_y, endpoint=True))
            col = int(rng.integers(lo_x, hi_x, endpoint=True))
            x, y = cm.origin_x + col * res, cm.origin_y + row * res
            if int(cm.costs[row, col]) < max_cost and accept(x, y):
                return (col, row), Pose.from_yaw(x, y, float(rng.uniform(0.0, 2.0 * math.pi)))

    pairs = []
    while len(pairs) < n:
        s_cell, start = cell(lambda x, y: True)
        g_cell, goal = cell(lambda x, y: math.sqrt((x - start.x) ** 2 + (y - start.y) ** 2) > min_distance)
        pairs.append(Pair(s_cell, g_cell, start, goal))
    return Draw(pairs, drawn)


# ---------------------------------------------------------------------------- the metrics
def poses_array(poses) -> np.ndarray:
    """:class:`Pose` objects as a float64 (n, 6) array of x, y, qx, qy, qz, qw (the C++'s layout)."""
    return np.array([[p.x, p.y, p.qx, p.qy, p.qz, p.qw] for p in poses], dtype=np.float64).reshape(-1, 6)


def path_length(xy: np.ndarray) -> float:
    """The sum of the Euclidean distances between consecutive points of ``xy`` ((n, >=2): x, y first)."""
    xy = np.asarray(xy, dtype=np.float64)
    if len(xy) < 2:
        return 0.0
    d = np.diff(xy[:, :2], axis=0)
    return float(np.sqrt(d[:, 0] ** 2 + d[:, 1] ** 2).sum())


def path_cells(cm: Costmap, xy: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The cells (mx, my) of the points of ``xy`` as ``Costmap2D::worldToMap`` gives them:
    ``floor((w - origin) / resolution)`` on each axis; a point off the map raises ValueError."""
    xy = np.asarray(xy, dtype=np.float64)
    mx = np.floor((xy[:, 0] - cm.origin_x) / cm.resolution)
    my = np.floor((xy[:, 1] - cm.origin_y) / cm.resolution)
    off = (mx < 0) | (my < 0) | (mx >= cm.size_x) | (my >= cm.size_y)
    if off.any():
        k = int(np.argmax(off))
        raise ValueError(f"path point {k} ({xy[k, 0]!r}, {xy[k, 1]!r}) is off the costmap")
    return mx.astype(np.int64), my.astype(np.int64)


def path_costs(cm: Costmap, xy: np.ndarray) -> np.ndarray:
    """The costmap cost of the cell of every point of ``xy`` (:func:`path_cells`), as int64."""
    mx, my = path_cells(cm, xy)
    return cm.costs[my, mx].astype(np.int64)


# ---------------------------------------------------------------------------- the results
@dataclass
class PairResult:
    """One planner on one pair."""

    error: Optional[str]  # None: planned
    poses: np.ndarray  # float64 (n, 6): the path (the C++'s when an oracle ran), empty on failure
    seconds: float  # the planning time of the table (the C++'s with an oracle, else the model's)
    model_seconds: float
    cpp_seconds: Optional[float] = None
    length: Optional[float] = None
    mean_cost: Optional[float] = None
    max_cost: Optional[int] = None

    @property
    def ok(self) -> bool:
        return self.error is None and len(self.poses) > 0

    def summary(self) -> dict:
        return {"ok": self.ok, "error": self.error, "poses": len(self.poses), "seconds": self.seconds,
                "model_seconds": self.model_seconds, "cpp_seconds": self.cpp_seconds, "length": self.length,
                "mean_cost": self.mean_cost, "max_cost": self.max_cost}


def _mean(values) -> Optional[float]:
    values = list(values)
    return float(np.mean(values)) if values else None


@dataclass
class PlannerResult:
    """One row of the table: a planner over every pair."""

    planner: Planner
    pairs: list = field(default_factory=list)  # [PairResult], in the order of the pairs

    @property
    def planned(self) -> list:
        return [r for r in self.pairs if r.ok]

    @property
    def failed(self) -> int:
        return len(self.pairs) - len(self.planned)

    @property
    def mean_length(self) -> Optional[float]:
        return _mean(r.length for r in self.planned)

    @property
    def mean_seconds(self) -> Optional[float]:
        return _mean(r.seconds for r in self.planned)

    @property
    def mean_cost(self) -> Optional[float]:
        return _mean(r.mean_cost for r in self.planned)

    @property
    def max_cost(self) -> Optional[int]:
        planned = self.planned
        return max(r.max_cost for r in planned) if planned else None

    @property
    def mean_path_max_cost(self) -> Optional[float]:
        """Nav2's own "Max cost" column: the mean over pairs of each path's maximum cost."""
        return _mean(r.max_cost for r in self.planned)

    def summary(self) -> dict:
        return {"planner": self.planner.name, "variant": self.planner.variant, "mode": self.planner.mode,
                "pairs": len(self.pairs), "planned": len(self.planned), "failed": self.failed,
                "mean_length_m": self.mean_length, "mean_seconds": self.mean_seconds, "mean_cost": self.mean_cost,
                "max_cost": self.max_cost, "mean_path_max_cost": self.mean_path_max_cost,
                "errors": sorted({r.error for r in self.pairs if r.error is not None}),
                "per_pair": [r.summary() for r in self.pairs]}


@dataclass
class Difference:
    """The model and the C++ disagreeing on one pair."""

    planner: str
    pair: int
    what: str  # "error", "pose count" or "pose k"
    model: object
    cpp: object


@dataclass
class FixComparison:
    """The fixed planner against the original in one mode."""

    mode: str
    original_planned: int  # pairs the original planned
    same_path: int  # ... on which the fixed gives the same poses, bit for bit
    changed: list  # pair indices the original planned where the fixed differs (or fails)
    fixed_only: list  # pair indices only the fixed planned


def compare_fix(rows: list) -> list:
    """:class:`FixComparison` per mode where both variants ran."""
    by = {(r.planner.fix.shipped, r.planner.mode): r for r in rows}
    out = []
    for mode in ("dijkstra", "astar"):
        o, f = by.get((True, mode)), by.get((False, mode))
        if o is None or f is None:
            continue
        changed, fixed_only, same, planned = [], [], 0, 0
        for k, (a, b) in enumerate(zip(o.pairs, f.pairs)):
            if a.ok:
                planned += 1
                if b.ok and same_bits(a.poses, b.poses):
                    same += 1
                else:
                    changed.append(k)
            elif b.ok:
                fixed_only.append(k)
        out.append(FixComparison(mode, planned, same, changed, fixed_only))
    return out


def same_bits(a: np.ndarray, b: np.ndarray) -> bool:
    """Two float64 arrays equal bit for bit (shape included)."""
    a, b = np.ascontiguousarray(a, dtype=np.float64), np.ascontiguousarray(b, dtype=np.float64)
    return a.shape == b.shape and bool((a.view(np.uint64) == b.view(np.uint64)).all())


def first_difference(model_error: Optional[str], model: np.ndarray, cpp_error: Optional[str],
                     cpp: np.ndarray) -> Optional[tuple[str, object, object]]:
    """Where the model's outcome and the C++'s differ: (what, model, C++), or None."""
    if model_error != cpp_error:
        return "error", model_error, cpp_error
    if model.shape != cpp.shape:
        return "pose count", len(model), len(cpp)
    same = (np.ascontiguousarray(model).view(np.uint64) == np.ascontiguousarray(cpp).view(np.uint64)).all(axis=1)
    if not same.all():
        k = int(np.argmin(same))
        return f"pose {k}", [v.hex() for v in model[k].tolist()], [v.hex() for v in cpp[k].tolist()]
    return None


def _measured(cm: Costmap, poses: np.ndarray, error: Optional[str], seconds: float, model_seconds: float,
              cpp_seconds: Optional[float]) -> PairResult:
    r = PairResult(error, poses, seconds, model_seconds, cpp_seconds)
    if r.ok:
        costs = path_costs(cm, poses)
        r.length, r.mean_cost, r.max_cost = path_length(poses), float(costs.mean()), int(costs.max())
    return r


def run_benchmark(cm: Costmap, params: PlannerParams, pairs: list, planners=PLANNERS, oracles: Optional[dict] = None,
                  backend: str = "jit", progress: Optional[Callable[[int], None]] = None, arith=None
                  ) -> tuple[list, list]:
    """Every planner of ``planners`` on every pair of ``pairs``: (``[PlannerResult]``,
    ``[Difference]``).  Pair by pair, each planner in turn on the pair (so a change of the
    machine's load during the run weighs on every planner alike), after one untimed plan per
    planner (the JIT compiles or loads its cache, the C++ touches its memory).

    ``oracles`` maps a variant to a running C++ plugin (``PluginOracle``) of that variant: each
    pair is then planned by the model and by the C++ (one request per pair, whose
    ``planning_seconds`` is the pair's planning time), the C++'s poses are the result and every
    difference from the model's is returned.  ``progress(1)`` after every plan.  ``arith``: the
    model plans as a build of that :class:`~navfn_smt.spec.arithmetic.PluginArithmetic` (None:
    x86-64's), the oracles' own."""
    configured = []
    for planner in planners:
        oracle = (oracles or {}).get(planner.variant)
        if oracles is not None and oracle is None:
            raise ValueError(f"no oracle for the {planner.variant} variant")
        p = replace(params, fix=planner.fix, use_astar=planner.use_astar)
        configured.append((planner, p, oracle))
        if pairs:  # warm-up, untimed
            create_plan(cm, pairs[0].start, pairs[0].goal, p, backend, arith)
            if oracle is not None:
                oracle.create_plans(cm, p, [(pairs[0].start, pairs[0].goal)])
    rows = [PlannerResult(planner) for planner in planners]
    differences = []
    for k, pair in enumerate(pairs):
        for row, (planner, p, oracle) in zip(rows, configured):
            t0 = time.perf_counter()
            run = create_plan(cm, pair.start, pair.goal, p, backend, arith)
            model_seconds = time.perf_counter() - t0
            mine = poses_array(run.poses)
            if oracle is None:
                row.pairs.append(_measured(cm, mine, run.error, model_seconds, model_seconds, None))
            else:
                (answer,) = oracle.create_plans(cm, p, [(pair.start, pair.goal)])
                cpp_seconds = float(oracle.planning_seconds)
                model_error = None if run.error == EMPTY_PATH else run.error  # Humble throws nothing
                diff = first_difference(model_error, mine, answer.error, answer.poses)
                if diff is not None:
                    differences.append(Difference(planner.name, k, *diff))
                row.pairs.append(_measured(cm, answer.poses, answer.error, cpp_seconds, model_seconds, cpp_seconds))
            if progress:
                progress(1)
    return rows, differences


@dataclass
class MapResult:
    """The benchmark on one map: its pairs, the table's rows, the fix's effect, the model's
    differences from the C++."""

    map: str
    size: tuple[int, int]
    resolution: float
    params: PlannerParams
    draw: Draw
    rows: list
    differences: list
    timing: str  # what the planning-time column measured
    costmap_seconds: float = 0.0  # building the global costmap
    seconds: float = 0.0  # the whole map, drawing and planning

    @property
    def fix(self) -> list:
        return compare_fix(self.rows)

    def to_json(self) -> dict:
        p = self.params
        return {"map": self.map, "size": list(self.size), "resolution": self.resolution, "timing": self.timing,
                "params": {"tolerance": p.tolerance, "allow_unknown": p.allow_unknown,
                           "max_cycles_factor": p.max_cycles_factor,
                           "use_final_approach_orientation": p.use_final_approach_orientation,
                           "distro": p.distro},
                "cells_drawn": self.draw.cells_drawn,
                "pairs": [{"start_cell": list(q.start_cell), "goal_cell": list(q.goal_cell),
                           "start": [q.start.x, q.start.y, *q.start.orientation],
                           "goal": [q.goal.x, q.goal.y, *q.goal.orientation], "distance_m": q.distance}
                          for q in self.draw.pairs],
                "rows": [r.summary() for r in self.rows],
                "fix": [vars(c) for c in self.fix],
                "differences": [vars(d) for d in self.differences],
                "costmap_seconds": self.costmap_seconds, "seconds": self.seconds}
