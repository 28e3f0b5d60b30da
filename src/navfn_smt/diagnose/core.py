"""The diagnosis of one ``createPlan`` call: the step that failed, why, and what fixes it.

:func:`diagnose` runs :func:`navfn_smt.nav2.plugin.create_plan` and then explains its outcome
with the planner's own pieces:

* bounds: which check refused a pose (``Costmap2D::worldToMap`` in createPlan; the
  exception Nav2 throws);
* goal occupied: ``tolerance == 0`` and a lethal goal cell;
* no legal potential: the goal's cell is not 4-connected to the robot's through cells
  below COST_OBS (:mod:`.connectivity`, with the obstacle cells that cut it off), or it is
  connected but propagation stopped first, by its cycle limit or by pushes dropped from full
  priority buffers (told apart by propagating again with the limit or the buffers lifted);
* extraction: ``calcPath`` failed after a legal potential (Nav2 issue #4655).  calcPath is a
  pure function of the potential, so it is run without a budget (:mod:`.walk`): when it
  reaches the goal with a path of ``L`` points, the smallest ``max_cycles_factor`` that
  works is ``ceil(L / max(size_x, size_y))`` (checked by planning with it and with one less);
  when its state repeats, or it stops at another exit, no factor works;
* what-ifs: the plugin run again with ``use_astar``, ``tolerance`` and ``allow_unknown``
  changed one at a time.

Every step computes in one arithmetic, the plugin's of the build judged (``arith``: its
multiply-adds and conversions, NavFn's among them; x86-64's by default): the plan, the
propagations run again, calcPath walked without a budget, the factor's check and the what-ifs.
"""

from __future__ import annotations

import dataclasses
import time
from dataclasses import dataclass, field
from typing import Optional

import numpy as np

from ..nav2.params import PlannerParams
from ..spec.arithmetic import PLUGIN_X86_64, PluginArithmetic
from ..nav2.plugin import (
    INT_MAX,
    POT_HIGH,
    Costmap,
    Pose,
    PluginRun,
    create_plan,
)
from ..spec.extraction import ExtractionExit
from .connectivity import Connectivity, connectivity
from .walk import UB, UNDECIDED, Walk, walk_extraction

TOLERANCES = (0.0, 0.5, 1.0)

# cause codes (the JSON "cause"), each with the step ("stage") it belongs to
CAUSES = {
    "ok": "success",
    "start_outside_map": "bounds",
    "goal_outside_map": "bounds",
    "goal_occupied": "goal_check",
    "robot_cell_past_end": "make_plan",
    "navfn_cell_past_end": "propagation",
    "not_connected": "propagation",
    "propagation_cycle_limit": "propagation",
    "buffer_overflow": "propagation",
    "propagation_cycle_limit_and_buffer_overflow": "propagation",
    "goal_unreached": "propagation",
    "max_cycles_overflow": "extraction",
    "extraction_exhausted": "extraction",
    "extraction_cycle": "extraction",
    "extraction_zero_gradient": "extraction",
    "extraction_high_potential": "extraction",
    "extraction_out_of_bounds": "extraction",
    "extraction_undefined_behaviour": "extraction",
    "extraction_undecided": "extraction",
}


@dataclass
class WhatIf:
    """The plugin run again with one parameter changed."""

    change: str  # e.g. "use_astar=true"
    ok: bool
    error: Optional[str]
    legal_potential_no_plan: bool
    extraction: Optional[str]
    path_poses: int


@dataclass
class FactorFix:
    """The smallest ``max_cycles_factor`` that makes extraction succeed, or why there is none."""

    factor: Optional[int]  # None: no factor works (see reason)
    reason: str
    path_length: Optional[int] = None  # L, calcPath's return value without a budget
    max_dimension: int = 0
    factor_limit: int = 0  # the largest factor whose max_cycles fits an int
    verified_with: Optional[bool] = None  # the plugin succeeded with `factor`
    verified_one_less: Optional[bool] = None  # the plugin failed with `factor - 1`


@dataclass
class Diagnosis:
    ok: bool
    cause: str  # a key of CAUSES
    stage: str
    summary: str  # one line for a human
    details: list  # further lines
    run: PluginRun
    params: PlannerParams
    costmap: Costmap
    start: Pose
    goal: Pose
    walk: Optional[Walk] = None
    connectivity: Optional[Connectivity] = None
    fix: Optional[FactorFix] = None
    what_ifs: list = field(default_factory=list)
    failing_cell: Optional[tuple[int, int]] = None  # the cell to look at in the picture
    propagation_check: dict = field(default_factory=dict)  # what lifting the limits did
    timings: dict = field(default_factory=dict)  # seconds per step
    arith: PluginArithmetic = PLUGIN_X86_64  # the arithmetic every step computed in

    @property
    def legal_potential_no_plan(self) -> bool:
        return self.run.legal_potential_no_plan


def _exit_name(run: PluginRun) -> Optional[str]:
    return run.extraction.value if run.extraction is not None else None


def with_params(params: PlannerParams, **changes) -> PlannerParams:
    return dataclasses.replace(params, **changes)


def diagnose(cm: Costmap, start: Pose, goal: Pose, params: PlannerParams = PlannerParams(), backend: str = "jit",
             what_ifs: bool = True, max_steps: Optional[int] = None,
             arith: Optional[PluginArithmetic] = None) -> Diagnosis:
    """Plan as Nav2 does and explain the outcome (never raises for planning outcomes), every
    step computed as a build of the plugin arithmetic ``arith`` does (None: x86-64's)."""
    arith = arith or PLUGIN_X86_64
    t0 = time.perf_counter()
    run = create_plan(cm, start, goal, params, backend, arith)
    timings = {"plan": time.perf_counter() - t0}
    d = Diagnosis(ok=run.ok, cause="ok", stage="success", summary="", details=[], run=run, params=params,
                  costmap=cm, start=start, goal=goal, timings=timings, arith=arith)
    t = time.perf_counter()
    _classify(d, cm, backend, max_steps)
    d.stage = CAUSES[d.cause]
    timings["explain"] = time.perf_counter() - t
    if what_ifs and d.cause not in ("start_outside_map", "goal_outside_map"):
        t = time.perf_counter()
        d.what_ifs = _what_ifs(cm, start, goal, params, backend, arith)
        timings["what_ifs"] = time.perf_counter() - t
    timings["total"] = time.perf_counter() - t0
    return d


# ------------------------------------------------------------------------------ classify
def _classify(d: Diagnosis, cm: Costmap, backend: str, max_steps: Optional[int]) -> None:
    run = d.run
    maxdim = max(cm.size_x, cm.size_y)
    for line in run.log:
        if line.startswith("worldToMap failed"):
            d.details.append(f"plugin log: {line} (a pose in the last half cell of the map rounds one cell past "
                             f"its edge in NavfnPlanner::worldToMap)")
    if run.error == "StartOutsideMapBounds":
        d.cause, d.summary = "start_outside_map", _outside("start", d.start, cm, run.message)
        return
    if run.error == "GoalOutsideMapBounds":
        d.cause, d.summary = "goal_outside_map", _outside("goal", d.goal, cm, run.message)
        return
    if run.error == "GoalOccupied":
        d.cause, d.failing_cell = "goal_occupied", run.goal_cell
        d.summary = (f"GoalOccupied: tolerance is 0 and the goal's cell {run.goal_cell} has cost 254 "
                     f"(LETHAL_OBSTACLE) in the costmap (createPlan's check, before planning)")
        return
    if run.error is None:
        _success(d, cm, maxdim)
        return
    if run.error == "UndefinedBehaviour" and run.costs is None:
        d.cause, d.failing_cell = "robot_cell_past_end", run.robot_cell
        d.summary = f"undefined behaviour in makePlan: {run.message}"
        return
    if run.error == "UndefinedBehaviour" and run.potential is None:
        d.cause, d.failing_cell = "navfn_cell_past_end", run.target_cell
        d.summary = f"undefined behaviour in propagation: {run.message}"
        return
    if run.best_pose is None:  # no legal potential at the goal nor in its tolerance window
        _no_legal_potential(d, cm, backend)
        return
    if run.error == "UndefinedBehaviour" and run.max_cycles is None:
        d.cause, d.failing_cell = "max_cycles_overflow", run.best_cell
        d.summary = f"undefined behaviour: {run.message}"
        d.fix = _factor_fix(d, cm, backend, max_steps)
        return
    _extraction(d, cm, backend, max_steps)


def _outside(what: str, pose: Pose, cm: Costmap, message: str) -> str:
    exc = "StartOutsideMapBounds" if what == "start" else "GoalOutsideMapBounds"
    x_hi = cm.origin_x + cm.size_x * cm.resolution
    y_hi = cm.origin_y + cm.size_y * cm.resolution
    why = []
    if pose.x < cm.origin_x:
        why.append(f"x {pose.x:g} < origin x {cm.origin_x:g}")
    if pose.y < cm.origin_y:
        why.append(f"y {pose.y:g} < origin y {cm.origin_y:g}")
    if not why:
        if (pose.x - cm.origin_x) / cm.resolution >= cm.size_x:
            why.append(f"x {pose.x:g} >= {x_hi:g} (origin + size_x * resolution)")
        if (pose.y - cm.origin_y) / cm.resolution >= cm.size_y:
            why.append(f"y {pose.y:g} >= {y_hi:g} (origin + size_y * resolution)")
    return (f"{exc}: Costmap2D::worldToMap refused the {what} ({'; '.join(why)}); createPlan threw before "
            f"planning: \"{message}\"")


def _success(d: Diagnosis, cm: Costmap, maxdim: int) -> None:
    run = d.run
    d.cause = "ok"
    if run.path is None:
        d.summary = "plan found: start and goal are the same position, a one-pose path (no planning)"
        return
    L = len(run.path)
    d.summary = f"plan found: {len(run.poses)} poses ({L} calcPath points, max_cycles {run.max_cycles})"
    need = -(-L // maxdim)
    d.fix = FactorFix(need, f"the path needs calcPath({L}); max_cycles_factor {need} is the smallest that gives it",
                      path_length=L, max_dimension=maxdim, factor_limit=INT_MAX // maxdim)
    if run.used_tolerance:
        d.details.append(f"the goal's cell {run.target_cell} has no legal potential (potential "
                         f"{run.goal_potential:g}); the tolerance search planned to {_pose_str(run.best_pose)} "
                         f"(cell {run.best_cell}) instead")


def _pose_str(p: Pose) -> str:
    return f"({p.x:.6g}, {p.y:.6g})"


def _no_legal_potential(d: Diagnosis, cm: Costmap, backend: str) -> None:
    run = d.run
    target, robot = run.target_cell, run.robot_cell
    d.failing_cell = target
    on_map = all(0 <= c[0] < cm.size_x and 0 <= c[1] < cm.size_y for c in (target, robot))
    window = (f"; no cell within the tolerance {d.params.tolerance:g} m of the goal has one either"
              if d.params.tolerance > 0 else "; tolerance is 0")
    if not on_map:
        d.cause = "goal_unreached"
        d.summary = (f"no legal potential at the goal: NavFn's cells {target} (goal) / {robot} (robot) lie "
                     f"one past the map's edge (plugin worldToMap rounds){window}")
        return
    con = d.connectivity = connectivity(run.costs, robot, target)
    if not con.connected:
        d.cause = "not_connected"
        what = ("the goal's cell is an obstacle for NavFn (cost 254 after setCostmap)" if not con.goal_cell_passable
                else f"the goal's region ({con.goal_region_cells} cells) is not 4-connected to the robot's "
                     f"({con.robot_region_cells} cells) through cells of cost < 254")
        d.summary = f"not connected: {what}{window}"
        if con.cut:
            d.details.append(f"clearing {len(con.cut)} obstacle cell(s) would connect them, e.g. "
                             f"{', '.join(map(str, con.cut[:6]))}{' ...' if len(con.cut) > 6 else ''}")
        return
    # connected but unreached: what stopped propagation?
    lifted = _repropagate(run, d.params.use_astar, backend, d.arith)
    d.propagation_check = lifted
    cyc = run.cycles >= run.cycle_limit
    drops = run.dropped > 0
    by_cycles, by_buffers = lifted.get("cycles_lifted"), lifted.get("buffers_lifted")
    if by_cycles and (not drops or not by_buffers):
        d.cause = "propagation_cycle_limit"
    elif by_buffers and not cyc:
        d.cause = "buffer_overflow"
    elif lifted.get("both_lifted") and (cyc or drops):
        d.cause = "propagation_cycle_limit_and_buffer_overflow"
    else:
        d.cause = "goal_unreached"
    stop = {"propagation_cycle_limit": f"propagation stopped at its cycle limit ({run.cycles} of "
                                       f"max(nx*ny/20, nx+ny) = {run.cycle_limit} cycles)",
            "buffer_overflow": f"{run.dropped} push(es) were dropped by full priority buffers "
                               f"(PRIORITYBUFSIZE 10000)",
            "propagation_cycle_limit_and_buffer_overflow":
                f"propagation hit its cycle limit ({run.cycle_limit}) and dropped {run.dropped} push(es)",
            "goal_unreached": f"propagation ended after {run.cycles} cycles without reaching it"}[d.cause]
    d.summary = f"goal connected but unreached: {stop}{window}"
    d.details.append("propagating again: " + ", ".join(f"{k.replace('_', ' ')}: "
                                                       f"{'reaches the goal' if v else 'does not'}"
                                                       for k, v in lifted.items()))


def _repropagate(run: PluginRun, astar: bool, backend: str, arith: PluginArithmetic) -> dict:
    """Whether the goal's cell gets a potential with the cycle limit lifted, the buffers made
    unbounded, or both (same costs, cells, mode and arithmetic)."""
    from ..spec.propagation import unbounded_capacity

    ny, nx = run.costs.shape
    big = 4 * nx * ny + 16
    out = {}
    for name, cycles, cap in (("cycles_lifted", big, None), ("buffers_lifted", None, unbounded_capacity(nx, ny)),
                              ("both_lifted", big, unbounded_capacity(nx, ny))):
        pot = _propagate(run.costs, run.target_cell, run.robot_cell, astar, backend, cycles, cap, arith)
        out[name] = bool(pot[run.target_cell[1], run.target_cell[0]] < POT_HIGH)
    return out


def _propagate(costs, start, goal, astar, backend, cycles, capacity, arith: PluginArithmetic) -> np.ndarray:
    planner = _navfn(backend, arith).prepare(costs, capacity)
    return planner.run(start, goal, astar, trace=False, path_cycles=0, cycles=cycles).potential


# ---------------------------------------------------------------------------- extraction
_EXIT_CAUSE = {
    "exhausted": "extraction_exhausted",
    "zero_gradient": "extraction_zero_gradient",
    "high_potential": "extraction_high_potential",
    "out_of_bounds": "extraction_out_of_bounds",
}


def _extraction(d: Diagnosis, cm: Costmap, backend: str, max_steps: Optional[int]) -> None:
    run = d.run
    fix = d.fix = _factor_fix(d, cm, backend, max_steps)
    w = d.walk
    legal = "legal potential at " + ("the goal" if not run.used_tolerance else
                                     f"{_pose_str(run.best_pose)} (tolerance search)")
    if run.error == "UndefinedBehaviour":
        d.cause = "extraction_undefined_behaviour"
        d.failing_cell = w.exit_cell if w is not None else run.best_cell
        d.summary = f"{legal}, then calcPath would read outside the potential array (undefined behaviour): " \
                    f"{run.message}"
        return
    exit_ = _exit_name(run)
    d.failing_cell = w.exit_cell
    if exit_ == "exhausted":
        if fix.factor is not None:
            d.cause = "extraction_exhausted"
            d.summary = (f"{legal}, then calcPath exhausted its max_cycles ({run.max_cycles} = {fix.max_dimension} "
                         f"* max_cycles_factor {d.params.max_cycles_factor}): the path needs {fix.path_length} "
                         f"points; max_cycles_factor {fix.factor} is the smallest that works")
            d.failing_cell = tuple(int(round(v)) for v in w.points[run.max_cycles - 1]) if run.max_cycles else None
            return
        if w.exit == "cycle":
            d.cause = "extraction_cycle"
            d.summary = (f"{legal}, then calcPath entered a cycle: from iteration {w.cycle_start} its state "
                         f"repeats every {w.cycle_period} iterations, so it exhausts any max_cycles; no "
                         f"max_cycles_factor works")
            pts = w.points[w.cycle_start:w.cycle_start + w.cycle_period]
            d.failing_cell = _cell_of(pts[0]) if len(pts) else w.exit_cell
            return
        if w.exit == UNDECIDED:
            d.cause = "extraction_undecided"
            d.summary = (f"{legal}, then calcPath exhausted its max_cycles ({run.max_cycles}); run without a "
                         f"budget it neither reached the goal, stopped nor repeated a state in {w.iterations} "
                         f"iterations (undecided)")
            d.failing_cell = _cell_of(w.points[-1]) if len(w.points) else run.best_cell
            return
        d.cause = _EXIT_CAUSE.get(w.exit, "extraction_undefined_behaviour")
        d.summary = (f"{legal}, then calcPath exhausted its max_cycles ({run.max_cycles}); a larger budget "
                     f"does not help: at iteration {w.iterations} it would stop with '{w.exit}' "
                     f"({w.detail}); no max_cycles_factor works")
        return
    d.cause = _EXIT_CAUSE[exit_]
    what = {"zero_gradient": "the interpolated gradient was exactly (0, 0)",
            "high_potential": "grid-following moved to an unreached cell (potential >= POT_HIGH)",
            "out_of_bounds": "the path reached the map's first or last row"}[exit_]
    d.summary = (f"{legal}, then calcPath stopped at iteration {w.iterations} of {run.max_cycles}: {what} "
                 f"(exit '{exit_}'); no max_cycles_factor works")


def _cell_of(p) -> tuple[int, int]:
    return int(round(float(p[0]))), int(round(float(p[1])))


def _navfn(backend: str, arith: PluginArithmetic):
    """The NavFn ``backend`` computing in the NavFn arithmetic of ``arith``."""
    from ..under_test import PlannerUnderTest

    return PlannerUnderTest(arithmetic=arith.navfn).backend(backend)


def _factor_fix(d: Diagnosis, cm: Costmap, backend: str, max_steps: Optional[int]) -> FactorFix:
    """The smallest factor, computed from the unbudgeted extraction and checked on the plugin."""
    run = d.run
    maxdim = max(cm.size_x, cm.size_y)
    limit = INT_MAX // maxdim
    if not (0 <= run.robot_cell[0] < cm.size_x and 0 <= run.robot_cell[1] < cm.size_y):
        return FactorFix(None, "the robot's cell lies past the map's edge", max_dimension=maxdim, factor_limit=limit)
    w = d.walk = walk_extraction(run.potential, run.best_cell, run.robot_cell,
                                 **({"max_steps": max_steps} if max_steps else {}), arith=d.arith.navfn)
    if w.exit != "near_goal":
        why = {"cycle": f"calcPath's state repeats (period {w.cycle_period} from iteration {w.cycle_start})",
               UNDECIDED: f"undecided: no exit and no repeated state in {w.iterations} iterations",
               UB: w.detail}.get(w.exit, f"calcPath stops with '{w.exit}' at iteration {w.iterations}")
        return FactorFix(None, f"no factor works: {why}", max_dimension=maxdim, factor_limit=limit)
    L = w.path_length
    need = -(-L // maxdim)
    if need > limit:
        return FactorFix(None, f"the path needs calcPath({L}) but max_cycles = {maxdim} * factor overflows int "
                               f"above factor {limit}", path_length=L, max_dimension=maxdim, factor_limit=limit)
    # the budget boundary on the backend itself: calcPath(L) succeeds, calcPath(L - 1) does not
    planner = _navfn(backend, d.arith).prepare(run.costs)
    at_l = planner.extract(run.potential, run.best_cell, run.robot_cell, L)[0] is ExtractionExit.NEAR_GOAL
    below = planner.extract(run.potential, run.best_cell, run.robot_cell, L - 1)[0] is ExtractionExit.NEAR_GOAL
    if not at_l or below:
        raise AssertionError(f"the unbudgeted extraction (L = {L}) disagrees with the {backend} backend's calcPath")
    fix = FactorFix(need, f"the path needs calcPath({L}): max_cycles_factor >= ceil({L} / {maxdim}) = {need}",
                    path_length=L, max_dimension=maxdim, factor_limit=limit)
    ok = create_plan(d.costmap, d.start, d.goal, with_params(d.params, max_cycles_factor=need), backend, d.arith)
    fix.verified_with = ok.ok
    if need - 1 >= 0:
        less = create_plan(d.costmap, d.start, d.goal, with_params(d.params, max_cycles_factor=need - 1), backend,
                           d.arith)
        fix.verified_one_less = not less.ok
    return fix


# ------------------------------------------------------------------------------ what-ifs
def _what_ifs(cm: Costmap, start: Pose, goal: Pose, params: PlannerParams, backend: str,
              arith: PluginArithmetic) -> list:
    changes = [("use_astar", not params.use_astar)]
    changes += [("tolerance", t) for t in TOLERANCES if t != params.tolerance]
    changes += [("allow_unknown", not params.allow_unknown)]
    out = []
    for key, value in changes:
        r = create_plan(cm, start, goal, with_params(params, **{key: value}), backend, arith)
        shown = str(value).lower() if isinstance(value, bool) else f"{value:g}"
        out.append(WhatIf(f"{key}={shown}", r.ok, r.error, r.legal_potential_no_plan, _exit_name(r), len(r.poses)))
    return out
