"""``nav2_navfn_planner::NavfnPlanner``, the planner plugin around NavFn, as Nav2 Rolling runs it.

``createPlan`` (``navfn_planner.cpp``), step by step, every number as the C++ computes it
(all plugin arithmetic is double; NavFn's is the spec's):

1. ``Costmap2D::worldToMap`` (truncating) on both poses: off the map ->
   ``StartOutsideMapBounds`` / ``GoalOutsideMapBounds``; ``tolerance == 0`` and the goal's
   cell LETHAL_OBSTACLE (254) -> ``GoalOccupied``.
2. Equal start and goal positions: a one-pose path (the start pose; the goal's orientation
   unless ``use_final_approach_orientation``), no planning.
3. ``makePlan``: the plugin's own ``worldToMap`` *rounds* and its result is not checked, so a
   pose in the last half cell of the map's right column or top row becomes a cell one past the
   edge (see :func:`plugin_world_to_map`); ``clearRobotCell`` frees the robot's cell;
   ``setCostmap(..., isROS=true, allow_unknown)``; NavFn's start is the goal's cell and its
   goal the robot's cell (the swap); A* or Dijkstra (``atStart``).
4. The goal's potential (``getPointPotential``; DBL_MAX off the map); when not below
   POT_HIGH, the tolerance search: world points from ``goal - tolerance`` stepping by the
   resolution while ``<= goal + tolerance`` (accumulated in double), the legal one nearest the
   goal, first found on ties.
5. ``getPlanFromPotential``: ``setStart`` on that pose's cell, ``calcPath(max_cycles)`` with
   ``max_cycles = max(size_x, size_y) * max_cycles_factor`` (int), the points reversed and
   turned into world coordinates (``origin + p * resolution``: no half-cell offset); an empty
   result logs "Failed to create a plan from potential when a legal potential was found".
6. ``smoothApproachToGoal`` and ``use_final_approach_orientation``; no path ->
   ``NoValidPathCouldBeFound``.

Where the C++ has undefined behaviour (an index past an array, a signed overflow) the result
says so (``error == "UndefinedBehaviour"``) instead of guessing.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Optional

import numpy as np

from ..errors import NavfnInputError
from ..spec.constants import DBL_MAX, FREE_SPACE, INT_MAX, LETHAL_OBSTACLE, POT_HIGH
from ..spec.costs import add_border, set_costmap
from ..spec.extraction import ExtractionExit, UndefinedBehaviour
from .params import PlannerParams

LEGAL_BUT_NO_PLAN = ("Failed to create a plan from potential when a legal potential was found. "
                     "This shouldn't happen.")
EXCEPTIONS = ("StartOutsideMapBounds", "GoalOutsideMapBounds", "GoalOccupied", "NoValidPathCouldBeFound")


@dataclass(frozen=True)
class Pose:
    """``geometry_msgs/Pose`` in the plane: position (x, y) and an orientation quaternion."""

    x: float
    y: float
    qx: float = 0.0
    qy: float = 0.0
    qz: float = 0.0
    qw: float = 1.0

    @classmethod
    def from_yaw(cls, x: float, y: float, yaw: Optional[float] = None) -> "Pose":
        if yaw is None:
            return cls(float(x), float(y))
        return cls(float(x), float(y), *quaternion_from_yaw(float(yaw)))

    @property
    def orientation(self) -> tuple[float, float, float, float]:
        return (self.qx, self.qy, self.qz, self.qw)

    def with_position(self, x: float, y: float) -> "Pose":
        return Pose(x, y, self.qx, self.qy, self.qz, self.qw)


def quaternion_from_yaw(yaw: float) -> tuple[float, float, float, float]:
    """``orientationAroundZAxis``: tf2's ``setRPY(0, 0, yaw)``, its products as written (double)."""
    half_yaw, half_pitch, half_roll = yaw * 0.5, 0.0 * 0.5, 0.0 * 0.5
    cy, sy = math.cos(half_yaw), math.sin(half_yaw)
    cp, sp = math.cos(half_pitch), math.sin(half_pitch)
    cr, sr = math.cos(half_roll), math.sin(half_roll)
    return (sr * cp * cy - cr * sp * sy,
            cr * sp * cy + sr * cp * sy,
            cr * cp * sy - sr * sp * cy,
            cr * cp * cy + sr * sp * sy)


def yaw_of(pose: Pose) -> float:
    """The heading of a planar quaternion (for display)."""
    return math.atan2(2.0 * (pose.qw * pose.qz + pose.qx * pose.qy), 1.0 - 2.0 * (pose.qy ** 2 + pose.qz ** 2))


@dataclass
class Costmap:
    """What the plugin reads of ``Costmap2D``: the master grid (row ``my``, column ``mx``,
    index ``my * size_x + mx``), its origin and resolution (doubles; a map's resolution is the
    float32 of ``nav_msgs/MapMetaData`` widened)."""

    costs: np.ndarray  # uint8 (size_y, size_x)
    origin_x: float
    origin_y: float
    resolution: float

    @property
    def size_x(self) -> int:
        return int(self.costs.shape[1])

    @property
    def size_y(self) -> int:
        return int(self.costs.shape[0])


def costmap_axis_cell(w: float, origin: float, res: float, size: int) -> Optional[int]:
    """One axis of ``Costmap2D::worldToMap``: below the origin -> None; ``(w - o) / res``
    truncated; not below ``size`` -> None."""
    if w < origin:
        return None
    f = (w - origin) / res
    return int(f) if f < size else None  # the truncated value is below the size exactly when f is


def costmap_world_to_map(cm: Costmap, wx: float, wy: float) -> Optional[tuple[int, int]]:
    """``Costmap2D::worldToMap``: the cell containing (wx, wy), or None off the map."""
    mx = costmap_axis_cell(wx, cm.origin_x, cm.resolution, cm.size_x)
    my = costmap_axis_cell(wy, cm.origin_y, cm.resolution, cm.size_y)
    return None if mx is None or my is None else (mx, my)


def _cast_overflows(cm: Costmap, pose: Pose) -> bool:
    """``static_cast<unsigned int>`` of a quotient of 2^32 or more (or NaN) in ``Costmap2D::worldToMap``:
    undefined behaviour, reached when the point is not below the origin."""
    if pose.x < cm.origin_x or pose.y < cm.origin_y:
        return False
    fx, fy = (pose.x - cm.origin_x) / cm.resolution, (pose.y - cm.origin_y) / cm.resolution
    return not (fx < 2.0**32 and fy < 2.0**32)


def _round(v: float) -> int:
    """``std::round`` on a non-negative double (halves away from zero), exactly."""
    f = math.floor(v)
    return int(f) + (1 if v - f >= 0.5 else 0)


def plugin_axis_cell(w: float, origin: float, res: float) -> int:
    """One axis of ``NavfnPlanner::worldToMap`` for ``w >= origin``: ``std::round((w - o) / res)``,
    whatever the map's size (the value written before the bounds test)."""
    return _round((w - origin) / res)


def max_cycles(cm: Costmap, params: PlannerParams) -> Optional[int]:
    """``getPlanFromPotential``'s ``max(size_x, size_y) * max_cycles_factor`` (int); None when the
    product overflows int (undefined behaviour)."""
    n = max(cm.size_x, cm.size_y) * params.max_cycles_factor
    return n if -2**31 <= n <= INT_MAX else None


def plugin_world_to_map(cm: Costmap, wx: float, wy: float) -> tuple[bool, Optional[tuple[int, int]]]:
    """``NavfnPlanner::worldToMap``: (ok, cell).  Below the origin the cell is never written
    (None); otherwise ``round((w - o) / res)`` is written *before* the bounds test, so a failed
    call still leaves a cell one past the map's edge in ``mx``/``my``."""
    if wx < cm.origin_x or wy < cm.origin_y:
        return False, None
    mx = plugin_axis_cell(wx, cm.origin_x, cm.resolution)
    my = plugin_axis_cell(wy, cm.origin_y, cm.resolution)
    return (mx < cm.size_x and my < cm.size_y), (mx, my)


def plugin_map_to_world(cm: Costmap, px: float, py: float) -> tuple[float, float]:
    """``NavfnPlanner::mapToWorld``: ``origin + p * resolution`` in double (p a float path point)."""
    return cm.origin_x + float(px) * cm.resolution, cm.origin_y + float(py) * cm.resolution


def squared_distance(a: Pose, b: Pose) -> float:
    """``squared_distance`` of ``navfn_planner.hpp`` (double)."""
    return squared_offset(a.x - b.x, a.y - b.y)


def squared_offset(dx, dy):
    """The arithmetic of :func:`squared_distance` on ``dx = a.x - b.x``, ``dy = a.y - b.y``:
    ``dx * dx + dy * dy`` in double (on floats, numpy arrays, or compiled)."""
    return dx * dx + dy * dy


def cpp_double(v: float) -> str:
    """``std::to_string(double)``: printf's ``%f``."""
    return f"{v:f}"


@dataclass
class PluginRun:
    """One ``createPlan`` call: the published path or the exception, and what happened inside."""

    poses: list  # [Pose] from start to goal, as Nav2 publishes them; empty on failure
    error: Optional[str] = None  # one of EXCEPTIONS, or "UndefinedBehaviour"
    message: str = ""
    log: list = field(default_factory=list)  # the plugin's ERROR lines, in order
    start_cell: Optional[tuple[int, int]] = None  # Costmap2D::worldToMap of the poses
    goal_cell: Optional[tuple[int, int]] = None
    robot_cell: Optional[tuple[int, int]] = None  # NavfnPlanner::worldToMap: NavFn's goal
    target_cell: Optional[tuple[int, int]] = None  # ... of the goal: NavFn's start
    costs: Optional[np.ndarray] = None  # NavFn's internal costs after setCostmap
    potential: Optional[np.ndarray] = None  # (size_y, size_x) float32 after propagation
    reached: Optional[bool] = None  # the propagation call's return value
    cycles: int = 0  # propagation cycles
    cycle_limit: int = 0
    dropped: int = 0  # pushes lost to full priority buffers
    goal_potential: Optional[float] = None  # getPointPotential(goal), double
    used_tolerance: bool = False
    best_pose: Optional[Pose] = None  # the pose the path was extracted from
    best_cell: Optional[tuple[int, int]] = None
    max_cycles: Optional[int] = None
    extraction: Optional[ExtractionExit] = None
    path: Optional[np.ndarray] = None  # NavFn's float32 points (start -> robot), when found

    @property
    def ok(self) -> bool:
        return self.error is None

    @property
    def legal_potential_no_plan(self) -> bool:
        """The case Nav2 issue #4655 reports: a legal potential, then no path from it."""
        return LEGAL_BUT_NO_PLAN in self.log


def _fail(run: PluginRun, error: str, message: str) -> PluginRun:
    run.error, run.message, run.poses = error, message, []
    return run


def create_plan(cm: Costmap, start: Pose, goal: Pose, params: PlannerParams = PlannerParams(),
                backend: str = "jit") -> PluginRun:
    """``NavfnPlanner::createPlan(start, goal)`` on a costmap; never raises for planning outcomes."""
    run = PluginRun(poses=[])
    for what, pose in (("start", start), ("goal", goal)):
        if _cast_overflows(cm, pose):
            return _fail(run, "UndefinedBehaviour", f"Costmap2D::worldToMap casts ({cpp_double(pose.x)} - origin) / "
                                                    f"resolution to unsigned int for the {what}: the quotient is not "
                                                    f"below 2^32 (or not a number)")
    run.start_cell = costmap_world_to_map(cm, start.x, start.y)
    if run.start_cell is None:
        return _fail(run, "StartOutsideMapBounds", f"Start Coordinates of({cpp_double(start.x)}, "
                                                   f"{cpp_double(start.y)}) was outside bounds")
    run.goal_cell = costmap_world_to_map(cm, goal.x, goal.y)
    if run.goal_cell is None:
        return _fail(run, "GoalOutsideMapBounds", f"Goal Coordinates of({cpp_double(goal.x)}, "
                                                  f"{cpp_double(goal.y)}) was outside bounds")
    gx, gy = run.goal_cell
    if params.tolerance == 0 and int(cm.costs[gy, gx]) == LETHAL_OBSTACLE:
        return _fail(run, "GoalOccupied", f"Goal Coordinates of({cpp_double(goal.x)}, "
                                          f"{cpp_double(goal.y)}) was in lethal cost")
    if start.x == goal.x and start.y == goal.y:
        keep = start.orientation == goal.orientation or params.use_final_approach_orientation
        run.poses = [start if keep else Pose(start.x, start.y, *goal.orientation)]
        return run
    make_plan(cm, start, goal, params, run, backend)
    if run.error is None and not run.poses:
        _fail(run, "NoValidPathCouldBeFound", f"Failed to create plan with tolerance of: {cpp_double(params.tolerance)}")
    return run


def _plugin_cell(cm: Costmap, pose: Pose, run: PluginRun) -> tuple[int, int]:
    ok, cell = plugin_world_to_map(cm, pose.x, pose.y)
    if not ok:  # createPlan's check passed, so only the rounding can fail here
        run.log.append(f"worldToMap failed: mx,my: {cell[0]},{cell[1]}, size_x,size_y: {cm.size_x},{cm.size_y}")
    return cell


def make_plan(cm: Costmap, start: Pose, goal: Pose, params: PlannerParams, run: PluginRun, backend: str) -> None:
    """``NavfnPlanner::makePlan``; fills ``run`` (poses empty when no plan)."""
    nx, ny = cm.size_x, cm.size_y
    robot = run.robot_cell = _plugin_cell(cm, start, run)
    ros = np.array(cm.costs, dtype=np.uint8, copy=True)
    if robot[1] * nx + robot[0] >= nx * ny:
        _fail(run, "UndefinedBehaviour", f"clearRobotCell writes costmap index {robot[1] * nx + robot[0]}, past the "
                                         f"end of the {nx}x{ny} costmap (the robot's position rounds to cell {robot})")
        return
    ros.ravel()[robot[1] * nx + robot[0]] = FREE_SPACE  # clearRobotCell: setCost(mx, my) = costmap_[my*nx + mx]
    run.costs = set_costmap(ros, is_ros=True, allow_unknown=params.allow_unknown)
    target = run.target_cell = _plugin_cell(cm, goal, run)
    try:
        _propagate(run, target, robot, params.use_astar, backend)
    except UndefinedBehaviour as e:
        _fail(run, "UndefinedBehaviour", str(e))
        return
    best = _legal_pose(cm, goal, params.tolerance, run)
    if best is None:
        return
    run.best_pose = best
    poses = get_plan_from_potential(cm, best, params, run, backend)
    if run.error is not None:
        return
    if not poses:
        run.log.append(LEGAL_BUT_NO_PLAN)
        return
    poses = smooth_approach_to_goal(best, poses)
    if params.use_final_approach_orientation:
        poses = _final_approach_orientation(poses, start)
    run.poses = poses


def get_point_potential(cm: Costmap, run: PluginRun, wx: float, wy: float) -> float:
    """``getPointPotential``: DBL_MAX when the plugin's worldToMap fails, else the float potential."""
    ok, cell = plugin_world_to_map(cm, wx, wy)
    if not ok:
        return DBL_MAX
    return float(run.potential[cell[1], cell[0]])


def _legal_pose(cm: Costmap, goal: Pose, tolerance: float, run: PluginRun) -> Optional[Pose]:
    """The goal when its potential is legal, else the tolerance search's nearest legal point
    (None when there is none)."""
    run.goal_potential = get_point_potential(cm, run, goal.x, goal.y)
    if run.goal_potential < POT_HIGH:
        return goal
    run.used_tolerance = True
    xs = tolerance_steps(goal.x - tolerance, goal.x + tolerance, cm.resolution)
    ys = tolerance_steps(goal.y - tolerance, goal.y + tolerance, cm.resolution)
    cols, rows = rounded_cells(xs, cm.origin_x, cm.resolution, cm.size_x), rounded_cells(ys, cm.origin_y,
                                                                                             cm.resolution, cm.size_y)
    xi, yi = np.nonzero(cols >= 0)[0], np.nonzero(rows >= 0)[0]
    if len(xi) == 0 or len(yi) == 0:
        return None
    pot = run.potential[rows[yi][:, None], cols[xi][None, :]].astype(np.float64)  # (y, x): the loop's order
    sdist = squared_offset((xs[xi] - goal.x)[None, :], (ys[yi] - goal.y)[:, None])
    taken = tolerance_prefers(pot, sdist, DBL_MAX)  # the points the loop could take at all
    if not taken.any():
        return None
    # the loop's strict '<' keeps the first of the nearest it could take
    k = int(np.argmin(np.where(taken, sdist, np.inf)))
    return goal.with_position(float(xs[xi[k % len(xi)]]), float(ys[yi[k // len(xi)]]))


def tolerance_prefers(potential, sdist, best_sdist):
    """The choice of makePlan's tolerance loop at one point: ``potential < POT_HIGH && sdist <
    best_sdist`` (double compares).  ``best_sdist`` starts at DBL_MAX and becomes each chosen
    point's distance, so the first of the nearest legal points in the loop's (y, x) order wins,
    and a point at DBL_MAX never does.  Operators only: the same rule runs on floats, on numpy
    arrays (elementwise, here) and compiled in the sweep's loop (:mod:`.sweep_loops`)."""
    return (potential < POT_HIGH) & (sdist < best_sdist)


MAX_TOLERANCE_STEPS = 10**8


def tolerance_steps(lo: float, hi: float, step: float) -> np.ndarray:
    """The values ``p = lo; while (p <= hi) { ...; p += step; }`` visits, accumulated in double
    one addition at a time (``np.add.accumulate`` adds sequentially, as the loop does)."""
    if not lo <= hi:
        return np.zeros(0)
    n = int((hi - lo) / step) + 2  # the loop's trip count is at most this (one addition error aside)
    if n > MAX_TOLERANCE_STEPS:
        raise NavfnInputError(f"tolerance search of {n} points per axis: Nav2 would loop for about {n}^2 "
                              f"iterations; use a smaller tolerance")
    for extra in (0, 64):
        v = np.add.accumulate(np.concatenate(([lo], np.full(n + extra, step))))
        if v[-1] > hi:
            return v[v <= hi] if np.all(np.diff(v) > 0) else _stalled(lo, step)
    return _stalled(lo, step)


def _stalled(lo: float, step: float):
    raise NavfnInputError(f"tolerance search never ends: adding the resolution {step!r} to {lo!r} does not "
                          f"move it past the goal (Nav2's loop would not terminate)")


def rounded_cells(w: np.ndarray, origin: float, res: float, size: int) -> np.ndarray:
    """``NavfnPlanner::worldToMap`` per axis on many points: the rounded cell, or -1 when the call fails."""
    f = (w - origin) / res
    fl = np.floor(f)
    cell = fl + (f - fl >= 0.5)
    return np.where((w >= origin) & (cell < size), cell, -1).astype(np.int64)


def get_plan_from_potential(cm: Costmap, pose: Pose, params: PlannerParams, run: PluginRun, backend: str) -> list:
    """``getPlanFromPotential``: calcPath from ``pose``'s cell, reversed into world poses."""
    from ..backends import get_backend

    _, cell = plugin_world_to_map(cm, pose.x, pose.y)  # legal, so on the map
    run.best_cell = cell
    n = max_cycles(cm, params)
    if n is None:
        _fail(run, "UndefinedBehaviour", f"max_cycles = {max(cm.size_x, cm.size_y)} * {params.max_cycles_factor} "
                                         f"overflows int")
        return []
    run.max_cycles = n
    try:
        planner = get_backend(backend).prepare(run.costs)
        run.extraction, path = planner.extract(run.potential, cell, run.robot_cell, n)
    except UndefinedBehaviour as e:
        _fail(run, "UndefinedBehaviour", str(e))
        return []
    run.path = path
    return [Pose(*plugin_map_to_world(cm, px, py)) for px, py in path[::-1].tolist()]


def smooth_approach_to_goal(goal: Pose, poses: list) -> list:
    """``smoothApproachToGoal``: replace the last pose by the goal when it lies farther from the
    one before than the goal does, or (same position) to take its orientation; else append it."""
    if len(poses) >= 2:
        before, last = poses[-2], poses[-1]
        if squared_distance(last, before) > squared_distance(goal, before):
            return poses[:-1] + [goal]
        if squared_distance(last, goal) < 1e-6:
            return poses[:-1] + [goal]
    return poses + [goal]


def _final_approach_orientation(poses: list, start: Pose) -> list:
    """``use_final_approach_orientation``: the last pose faces along the final approach."""
    if len(poses) == 1:
        return [Pose(poses[0].x, poses[0].y, *start.orientation)]
    last, approach = poses[-1], poses[-2]
    if abs(last.x - approach.x) < 0.0001 and abs(last.y - approach.y) < 0.0001 and len(poses) > 2:
        approach = poses[-3]
    theta = math.atan2(last.y - approach.y, last.x - approach.x)
    return poses[:-1] + [Pose(last.x, last.y, *quaternion_from_yaw(theta))]


def _propagate(run: PluginRun, navfn_start: tuple[int, int], navfn_goal: tuple[int, int], astar: bool,
               backend: str) -> None:
    """``setStart``/``setGoal`` then ``calcNavFnAstar`` or ``calcNavFnDijkstra(atStart=true)``.

    Cells one past the edge (see :func:`plugin_world_to_map`) reach NavFn unchecked; their index
    ``y * nx + x`` then names cell (0, y + 1), and their coordinates enter the A* heuristic
    and the path's last point: that case runs on the reference spec with the raw coordinates.
    """
    from ..backends import get_backend
    from ..spec.propagation import cycle_limit

    ny, nx = run.costs.shape
    run.cycle_limit = cycle_limit(nx, ny)
    on_map = all(0 <= c[0] < nx and 0 <= c[1] < ny for c in (navfn_start, navfn_goal))
    if on_map:
        # calcNavFn* only propagate; calcPath comes later, from the chosen pose's cell
        r = get_backend(backend).prepare(run.costs).run(navfn_start, navfn_goal, astar, trace=False, path_cycles=0)
        run.potential, run.reached, run.cycles, run.dropped = r.potential, r.start_reached, r.cycles, r.dropped
        return
    for what, c in (("start", navfn_start), ("goal", navfn_goal)):
        if c[1] * nx + c[0] >= nx * ny:
            raise UndefinedBehaviour(f"NavFn's {what} cell {c} indexes {c[1] * nx + c[0]}, past the end of potarr "
                                     f"({nx * ny} cells)")
    _propagate_raw(run, navfn_start, navfn_goal, astar)


def _propagate_raw(run: PluginRun, navfn_start, navfn_goal, astar: bool) -> None:
    from ..spec.propagation import propagate, setup

    ny, nx = run.costs.shape
    st = setup(add_border(run.costs).ravel().tolist(), nx, ny, navfn_goal)
    run.reached = bool(propagate(st, navfn_start, navfn_goal, astar, run.cycle_limit, at_start=True,
                                 record_trace=False))
    run.potential = np.array(st.potential, dtype=np.float32).reshape(ny, nx)
    run.cycles, run.dropped = st.cycles, st.dropped


def costmap_from_map(m, inflated: Optional[np.ndarray] = None) -> Costmap:
    """The plugin's view of a :class:`~navfn_smt.nav2.mapserver.MapServerMap` (its static layer, or
    ``inflated`` when an inflation layer ran)."""
    costs = m.ros_costmap if inflated is None else inflated
    return Costmap(np.ascontiguousarray(costs, dtype=np.uint8), float(m.origin[0]), float(m.origin[1]),
                   float(m.costmap_resolution))


def check_pose(what: str, values) -> Pose:
    """A pose from the command line: x y [yaw], finite numbers."""
    vals = list(values)
    if len(vals) not in (2, 3):
        raise NavfnInputError(f"--{what} needs X Y or X Y YAW, got {len(vals)} numbers")
    for v in vals:
        if not math.isfinite(v):
            raise NavfnInputError(f"--{what}: coordinates must be finite, got {v!r}")
    return Pose.from_yaw(*vals)
