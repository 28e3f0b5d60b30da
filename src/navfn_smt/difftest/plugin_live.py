"""The plugin level of the live difftest: Nav2's ``NavfnPlanner::createPlan``, built from the
user's sources (``navfn-plugin`` of an oracle build), against the model of
:mod:`navfn_smt.nav2.plugin` for the distribution the sources were detected as.

A case is a costmap, the plugin's parameters and a (start, goal) pair of world poses.  The two
agree when they raise the same exception with the same message, or publish the same poses
(every double of position and orientation, bit for bit), and log the same WARN and ERROR
lines in the same order.  Where the model finds undefined behaviour in the C++ (an index past
an array), the C++'s answer means nothing and the case is counted apart, not compared.

:func:`generated_configs` gives the configurations: maps of 3..12 cells a side (NavFn needs 3x3), mixing free,
lethal, inscribed, unknown and intermediate costs; resolutions and origins that are exact and
that are float32 values widened; every parameter (tolerance, ``use_astar``, ``allow_unknown``,
``max_cycles_factor``, ``use_final_approach_orientation``); and for each, poses at cell centres,
on cell corners, on both sides of the half-cell boundaries where the plugin's rounding and
Costmap2D's truncation part, off the map on every side, on lethal cells, equal positions with
other headings, and random points.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field
from typing import Callable, Iterator, Optional

import numpy as np

from ..nav2.params import PlannerParams
from ..nav2.plugin import EMPTY_PATH, Costmap, Pose, create_plan, quaternion_from_yaw

MAX_DETAILS = 20
RESOLUTIONS = (0.05, 0.1, 0.25, 1.0, float(np.float32(0.05)), float(np.float32(0.03)))
COSTS = (0, 0, 0, 0, 254, 254, 253, 255, 1, 50, 128, 200, 252)


@dataclass
class PluginConfig:
    """One configured plugin on one costmap, and the pose pairs it is asked to plan."""

    costmap: Costmap
    params: PlannerParams
    pairs: list  # [(Pose, Pose)]
    name: str = ""


@dataclass
class PluginSummary:
    """Counts of a plugin-level run, and the first disagreements in detail."""

    distribution: str
    cases: int = 0
    agreeing: int = 0
    undefined: int = 0  # undefined behaviour in the C++ (model's verdict): not compared
    configs: int = 0
    outcomes: dict = field(default_factory=dict)  # the C++'s outcome -> count
    log_lines: int = 0  # WARN and ERROR lines compared
    disagreements: list = field(default_factory=list)
    cpp_seconds: float = 0.0
    model_seconds: float = 0.0

    @property
    def failed(self) -> int:
        return self.cases - self.agreeing - self.undefined

    def as_dict(self) -> dict:
        return {"level": "plugin", "distribution": self.distribution, "configs": self.configs, "cases": self.cases,
                "passed": self.agreeing, "failed": self.failed, "undefined_behaviour": self.undefined,
                "outcomes": dict(sorted(self.outcomes.items())), "log_lines": self.log_lines,
                "cpp_seconds": round(self.cpp_seconds, 3), "model_seconds": round(self.model_seconds, 3),
                "disagreements": self.disagreements}


def _poses_of(run) -> np.ndarray:
    return np.array([[p.x, p.y, *p.orientation] for p in run.poses], dtype=np.float64).reshape(-1, 6)


def first_difference(run, answer) -> Optional[tuple[str, object, object]]:
    """The first field in which the model's :class:`~navfn_smt.nav2.plugin.PluginRun` and the
    C++'s :class:`~navfn_smt.oracle.client.PluginAnswer` differ: (field, model, C++), or None."""
    error = None if run.error == EMPTY_PATH else run.error
    if error != answer.error:
        return "error", run.error, answer.error
    if error is not None and run.message != answer.message:
        return "message", run.message, answer.message
    mine = _poses_of(run)
    if mine.shape != answer.poses.shape:
        return "pose count", len(mine), len(answer.poses)
    same = (mine.view(np.uint64) == answer.poses.view(np.uint64)).all(axis=1)  # bit for bit
    if not same.all():
        k = int(np.argmin(same))
        return f"pose {k}", [v.hex() for v in mine[k].tolist()], [v.hex() for v in answer.poses[k].tolist()]
    if list(run.lines) != list(answer.lines):
        k = next((i for i, (a, b) in enumerate(zip(run.lines, answer.lines)) if a != b),
                 min(len(run.lines), len(answer.lines)))
        return (f"log line {k}", run.lines[k] if k < len(run.lines) else None,
                answer.lines[k] if k < len(answer.lines) else None)
    return None


def compare_config(cfg: PluginConfig, oracle, backend: str, summary: PluginSummary, arith=None) -> None:
    """Plan every pair of ``cfg`` with the model, then the pairs without undefined behaviour with
    the C++ (one request); count and keep the differences."""
    runs = []
    t0 = time.perf_counter()
    for start, goal in cfg.pairs:
        runs.append(create_plan(cfg.costmap, start, goal, cfg.params, backend, arith))
    summary.model_seconds += time.perf_counter() - t0
    summary.configs += 1
    summary.cases += len(runs)
    defined = [k for k, run in enumerate(runs) if run.error != "UndefinedBehaviour"]
    summary.undefined += len(runs) - len(defined)
    if not defined:
        return
    t1 = time.perf_counter()
    answers = oracle.create_plans(cfg.costmap, cfg.params, [cfg.pairs[k] for k in defined])
    summary.cpp_seconds += time.perf_counter() - t1
    for k, answer in zip(defined, answers):
        key = answer.error or ("path" if len(answer.poses) else "empty path")
        summary.outcomes[key] = summary.outcomes.get(key, 0) + 1
        summary.log_lines += len(answer.lines)
        diff = first_difference(runs[k], answer)
        if diff is None:
            summary.agreeing += 1
        elif len(summary.disagreements) < MAX_DETAILS:
            summary.disagreements.append(_describe(cfg, k, *cfg.pairs[k], diff))


def _describe(cfg: PluginConfig, k: int, start: Pose, goal: Pose, diff) -> dict:
    cm, p = cfg.costmap, cfg.params
    return {"config": cfg.name, "case": k, "field": diff[0], "model": diff[1], "cpp": diff[2],
            "start": [start.x.hex(), start.y.hex(), *start.orientation],
            "goal": [goal.x.hex(), goal.y.hex(), *goal.orientation],
            "size": [cm.size_x, cm.size_y], "origin": [cm.origin_x.hex(), cm.origin_y.hex()],
            "resolution": cm.resolution.hex(), "costs": cm.costs.tolist(),
            "params": {"tolerance": p.tolerance, "use_astar": p.use_astar, "allow_unknown": p.allow_unknown,
                       "max_cycles_factor": p.max_cycles_factor,
                       "use_final_approach_orientation": p.use_final_approach_orientation}}


def run_plugin_live(configs, oracle, backend: str = "jit",
                    progress: Optional[Callable[[int], None]] = None, arith=None) -> PluginSummary:
    """Every configuration of ``configs`` against the running plugin ``oracle``, the model in the
    arithmetic ``arith`` (a :class:`~navfn_smt.spec.arithmetic.PluginArithmetic`; None: x86-64's)."""
    summary = PluginSummary(oracle.build["distribution"])
    for cfg in configs:
        compare_config(cfg, oracle, backend, summary, arith)
        if progress:
            progress(len(cfg.pairs))
    return summary


# --------------------------------------------------------------------------- generated cases
def _axis_points(rng, origin: float, res: float, n: int) -> list[float]:
    """World coordinates along one axis: centres, corners, the half-cell boundaries and their
    neighbouring doubles, the last double of the map and one past it, below the origin, random."""
    k = int(rng.integers(0, n))
    half = origin + (k + 0.5) * res
    edge = origin + n * res
    last_half = origin + (n - 0.5) * res
    special = [origin + k * res, half, math.nextafter(half, -math.inf), math.nextafter(half, math.inf), last_half,
               math.nextafter(last_half, math.inf), math.nextafter(edge, -math.inf), edge, origin,
               math.nextafter(origin, -math.inf), origin - res]
    inside = [origin + (int(rng.integers(0, n)) + 0.5) * res for _ in range(6)]
    inside += [origin + float(rng.uniform(0, n)) * res for _ in range(len(special) - len(inside))]
    return special + inside  # half of the points on the map's interior


def _pose(rng, x: float, y: float) -> Pose:
    if rng.random() < 0.5:
        return Pose(x, y)
    return Pose(x, y, *quaternion_from_yaw(float(rng.uniform(-math.pi, math.pi))))


def _costmap(rng, nx: int, ny: int) -> Costmap:
    costs = rng.choice(np.array(COSTS, dtype=np.uint8), size=(ny, nx))
    res = float(rng.choice(RESOLUTIONS))
    ox, oy = (float(rng.choice([0.0, -1.5, 0.3, float(np.float32(-2.7)), -res * nx / 2])) for _ in range(2))
    return Costmap(costs, ox, oy, res)


def _params(rng, res: float, distro: str) -> PlannerParams:
    tol = float(rng.choice([0.0, 0.0, 0.25, 0.5, 1.5 * res, 2 * res, 0.1]))
    return PlannerParams(tolerance=tol, use_astar=bool(rng.random() < 0.5), allow_unknown=bool(rng.random() < 0.7),
                         max_cycles_factor=int(rng.choice([1, 2, 4, 4, 8])),
                         use_final_approach_orientation=bool(rng.random() < 0.3), distro=distro)


def generated_configs(distro: str, count: int, seed: int = 0, pairs: int = 24) -> Iterator[PluginConfig]:
    """``count`` generated configurations of ``pairs`` pose pairs each (seeded: the same for the
    same arguments)."""
    rng = np.random.default_rng(seed)
    for c in range(count):
        nx, ny = (8, 6) if c == 0 else (int(rng.integers(3, 13)), int(rng.integers(3, 13)))
        cm = _costmap(rng, nx, ny)
        params = _params(rng, cm.resolution, distro)
        xs = _axis_points(rng, cm.origin_x, cm.resolution, nx)
        ys = _axis_points(rng, cm.origin_y, cm.resolution, ny)
        lethal = np.argwhere(cm.costs == 254)
        out = []
        for _ in range(pairs):
            start = _pose(rng, float(rng.choice(xs)), float(rng.choice(ys)))
            roll = rng.random()
            if roll < 0.1:
                goal = _pose(rng, start.x, start.y)
            elif roll < 0.25 and len(lethal):
                j, i = lethal[int(rng.integers(len(lethal)))]
                goal = _pose(rng, cm.origin_x + (i + 0.5) * cm.resolution, cm.origin_y + (j + 0.5) * cm.resolution)
            else:
                goal = _pose(rng, float(rng.choice(xs)), float(rng.choice(ys)))
            out.append((start, goal))
        yield PluginConfig(cm, params, out, name=f"seed {seed} config {c}")


def map_configs(map_yaml, params_file, distro: str, count: int, seed: int = 0, pairs: int = 24,
                sweep: Optional[list] = None) -> Iterator[PluginConfig]:
    """A user's map (and params file: its global costmap and planner parameters, as
    ``plan --world`` builds them for ``distro``): with ``sweep`` (X Y [YAW]) one configuration
    from that start to the centre of every cell; else ``count`` configurations of generated poses."""
    from ..nav2.plugin import check_pose
    from ..nav2.setup import check_params_file, load_setup

    check_params_file(params_file)
    setup = load_setup(map_yaml, params_file, distro)
    cm, params = setup.costmap, setup.params
    if sweep is not None:
        start = check_pose("sweep", sweep)
        goals = [Pose(cm.origin_x + (i + 0.5) * cm.resolution, cm.origin_y + (j + 0.5) * cm.resolution)
                 for j in range(cm.size_y) for i in range(cm.size_x)]
        yield PluginConfig(cm, params, [(start, g) for g in goals], name=f"sweep from ({start.x}, {start.y})")
        return
    rng = np.random.default_rng(seed)
    for c in range(count):
        xs = _axis_points(rng, cm.origin_x, cm.resolution, cm.size_x)
        ys = _axis_points(rng, cm.origin_y, cm.resolution, cm.size_y)
        out = [(_pose(rng, float(rng.choice(xs)), float(rng.choice(ys))),
                _pose(rng, float(rng.choice(xs)), float(rng.choice(ys)))) for _ in range(pairs)]
        yield PluginConfig(cm, params, out, name=f"{map_yaml} seed {seed} config {c}")
