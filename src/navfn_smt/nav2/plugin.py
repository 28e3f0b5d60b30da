"""``nav2_navfn_planner::NavfnPlanner``, the planner plugin around NavFn, per distribution.

``createPlan`` (``navfn_planner.cpp``) as Jazzy, Kilted and Rolling run it, step by step, every
number as the C++ computes it (all plugin arithmetic is double; NavFn's is the spec's); what
Humble does differently follows the list (:mod:`navfn_smt.distros`):

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

Humble (``Distro.throws`` false) throws nothing: there is no ``Costmap2D::worldToMap``
check in ``createPlan``; ``makePlan`` returns false with a WARN when its own ``worldToMap`` fails
for the robot or the goal; the equal-positions case first looks up the start's cost (WARN and an
empty path when lethal); a failed plan is a WARN and an empty path (``error == "EmptyPath"``).
Its ``smoothApproachToGoal`` lacks the same-position branch.  ``max_cycles_factor`` is Rolling's
alone (the others run ``4 * max(size_x, size_y)`` cycles), and so is the WARN of Rolling's
``calcPath`` when it runs out of cycles (a fix's fallback keeps it: the gradient logs it, then
the fallback runs).  The log (:attr:`PluginRun.lines`)
holds every WARN and ERROR line in order, as Nav2 prints them.

Where the C++ has undefined behaviour (an index past an array, a signed overflow) the result
says so (``error == "UndefinedBehaviour"``) instead of guessing.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace
from typing import Optional

import numpy as np

from ..errors import NavfnInputError
from ..spec.planner import AS_SHIPPED, Fix
from ..spec.arithmetic import PLUGIN_X86_64, PluginArithmetic
from ..spec.constants import DBL_MAX, FREE_SPACE, INT_MAX, LETHAL_OBSTACLE, POT_HIGH
from ..spec.costs import add_border, set_costmap
from ..spec.extraction import ExtractionExit, UndefinedBehaviour
from ..spec.numeric import c_fma
from ..under_test import PlannerUnderTest
from ..distros import Distro, distro
from .params import PlannerParams

LEGAL_BUT_NO_PLAN = ("Failed to create a plan from potential when a legal potential was found. "
                     "This shouldn't happen.")
EXCEPTIONS = ("StartOutsideMapBounds", "GoalOutsideMapBounds", "GoalOccupied", "NoValidPathCouldBeFound")
EMPTY_PATH = "EmptyPath"  # Humble: createPlan returned no pose (it throws nothing)
WARN, ERROR = 30, 40  # rcutils' severity numbers
ROBOT_OFF_MAP = ("Cannot create a plan: the robot's start position is off the global costmap. Planning will "
                 "always fail, are you sure the robot has been properly localized?")
GOAL_OFF_MAP = "The goal sent to the planner is off the global costmap. Planning will always fail to this goal."
UNIQUE_POSE_LETHAL = "Failed to create a unique pose path because of obstacles"




def flavour_of(name: str) -> Distro:
    """What ``navfn_planner.cpp`` does in the distribution ``name`` (its :class:`~navfn_smt.distros.Distro`)."""
    return distro(name)


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
    n = max(cm.size_x, cm.size_y) * (params.max_cycles_factor if flavour_of(params.distro).cycles_factor else 4)
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


def plugin_map_to_world(cm: Costmap, px: float, py: float,
                        arith: PluginArithmetic = PLUGIN_X86_64) -> tuple[float, float]:
    """``NavfnPlanner::mapToWorld``: ``origin + p * resolution`` in double (p a float path point);
    one rounding where the build fused it (site ``map_to_world``)."""
    if arith.fuses("map_to_world"):
        return c_fma(float(px), cm.resolution, cm.origin_x), c_fma(float(py), cm.resolution, cm.origin_y)
    return cm.origin_x + float(px) * cm.resolution, cm.origin_y + float(py) * cm.resolution


def squared_distance(a: Pose, b: Pose, call: str, arith: PluginArithmetic = PLUGIN_X86_64) -> float:
    """``squared_distance`` of ``navfn_planner.hpp`` (double), as the build computes it in the
    call ``call`` of navfn_planner.cpp (:data:`~navfn_smt.spec.arithmetic.SQUARED_CALLS`)."""
    return squared_offset_in(arith, call)(a.x - b.x, a.y - b.y)


def squared_offset_in(arith: PluginArithmetic, call: str):
    """:func:`squared_offset`, or where the build fused the site, :func:`fused_squared_offset`
    with the square the build fused in the call ``call``."""
    if not arith.fuses("squared_distance"):
        return squared_offset
    if arith.squared_order(call) == "dy":
        return lambda dx, dy: fused_squared_offset(dy, dx)
    return fused_squared_offset


def squared_offset(dx, dy):
    """The arithmetic of :func:`squared_distance` on ``dx = a.x - b.x``, ``dy = a.y - b.y``:
    ``dx * dx + dy * dy`` in double (on floats, numpy arrays, or compiled)."""
    return dx * dx + dy * dy


_fma_array = np.frompyfunc(c_fma, 3, 1)  # C's fma elementwise (broadcast), as objects


def fused_squared_offset(dx, dy):
    """:func:`squared_offset` as a build that fuses it computes it: ``fma(dx, dx, dy * dy)``
    (on floats or numpy arrays)."""
    if np.ndim(dx) == 0 and np.ndim(dy) == 0:
        return c_fma(float(dx), float(dx), float(dy) * float(dy))
    dx, dy = np.broadcast_arrays(np.asarray(dx, np.float64), np.asarray(dy, np.float64))
    return np.asarray(_fma_array(dx, dx, dy * dy), dtype=np.float64)


def cpp_double(v: float) -> str:
    """``std::to_string(double)``: printf's ``%f``."""
    return f"{v:f}"


@dataclass
class PluginRun:
    """One ``createPlan`` call: the published path or the exception, and what happened inside."""

    poses: list  # [Pose] from start to goal, as Nav2 publishes them; empty on failure
    error: Optional[str] = None  # one of EXCEPTIONS, or "UndefinedBehaviour"
    message: str = ""
    lines: list = field(default_factory=list)  # the plugin's (level, line) WARN and ERROR lines, in order
    start_cell: Optional[tuple[int, int]] = None  # Costmap2D::worldToMap of the poses
    goal_cell: Optional[tuple[int, int]] = None
    robot_cell: Optional[tuple[int, int]] = None  # NavfnPlanner::worldToMap: NavFn's goal
    target_cell: Optional[tuple[int, int]] = None  # ... of the goal: NavFn's start
    costs: Optional[np.ndarray] = None  # NavFn's internal costs after setCostmap
    potential: Optional[np.ndarray] = None  # (size_y, size_x) float32 after propagation
    arith: PluginArithmetic = PLUGIN_X86_64  # the arithmetic of the build this run computes as
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
    def log(self) -> list:
        """The ERROR lines, in order."""
        return [line for level, line in self.lines if level == ERROR]

    @property
    def warnings(self) -> list:
        """The WARN lines, in order."""
        return [line for level, line in self.lines if level == WARN]

    @property
    def legal_potential_no_plan(self) -> bool:
        """The case Nav2 issue #4655 reports: a legal potential, then no path from it."""
        return LEGAL_BUT_NO_PLAN in self.log


def _fail(run: PluginRun, error: str, message: str) -> PluginRun:
    run.error, run.message, run.poses = error, message, []
    return run


def create_plan(cm: Costmap, start: Pose, goal: Pose, params: PlannerParams = PlannerParams(),
                backend: str = "jit", arith: Optional[PluginArithmetic] = None) -> PluginRun:
    """``NavfnPlanner::createPlan(start, goal)`` of ``params.distro`` on a costmap, computed as a
    build of the arithmetic ``arith`` does (None: x86-64's); never raises for planning outcomes."""
    flavour = flavour_of(params.distro)
    run = PluginRun(poses=[], arith=arith or PLUGIN_X86_64)
    if flavour.throws and _checked_poses(cm, start, goal, params, run) is not None:
        return run
    if start.x == goal.x and start.y == goal.y:
        if not flavour.throws and _unique_pose_lethal(cm, start, run):
            return run
        keep = start.orientation == goal.orientation or params.use_final_approach_orientation
        run.poses = [start if keep else Pose(start.x, start.y, *goal.orientation)]
        return run
    make_plan(cm, start, goal, params, run, backend)
    if run.error is None and not run.poses:
        if flavour.throws:
            _fail(run, "NoValidPathCouldBeFound", f"Failed to create plan with tolerance of: "
                                                  f"{cpp_double(params.tolerance)}")
        else:
            run.lines.append((WARN, f"{params.plugin}: failed to create plan with tolerance {params.tolerance:.2f}."))
            _fail(run, EMPTY_PATH, "createPlan returned an empty path")
    return run


def _checked_poses(cm: Costmap, start: Pose, goal: Pose, params: PlannerParams, run: PluginRun) -> Optional[str]:
    """createPlan's checks (Jazzy on): both poses on the map (``Costmap2D::worldToMap``) and, with
    no tolerance, the goal's cell not lethal; the error raised, or None."""
    for what, pose in (("start", start), ("goal", goal)):
        if _cast_overflows(cm, pose):
            return _fail(run, "UndefinedBehaviour", f"Costmap2D::worldToMap casts ({cpp_double(pose.x)} - origin) / "
                                                    f"resolution to unsigned int for the {what}: the quotient is not "
                                                    f"below 2^32 (or not a number)").error
    run.start_cell = costmap_world_to_map(cm, start.x, start.y)
    if run.start_cell is None:
        return _fail(run, "StartOutsideMapBounds", f"Start Coordinates of({cpp_double(start.x)}, "
                                                   f"{cpp_double(start.y)}) was outside bounds").error
    run.goal_cell = costmap_world_to_map(cm, goal.x, goal.y)
    if run.goal_cell is None:
        return _fail(run, "GoalOutsideMapBounds", f"Goal Coordinates of({cpp_double(goal.x)}, "
                                                  f"{cpp_double(goal.y)}) was outside bounds").error
    gx, gy = run.goal_cell
    if params.tolerance == 0 and int(cm.costs[gy, gx]) == LETHAL_OBSTACLE:
        return _fail(run, "GoalOccupied", f"Goal Coordinates of({cpp_double(goal.x)}, "
                                          f"{cpp_double(goal.y)}) was in lethal cost").error
    return None


def _unique_pose_lethal(cm: Costmap, start: Pose, run: PluginRun) -> bool:
    """Humble's equal-positions case: ``Costmap2D::worldToMap`` on the start, its result not
    checked, then ``getCost(mx, my)``; lethal -> a WARN and an empty path (True)."""
    if start.x < cm.origin_x or start.y < cm.origin_y:
        _fail(run, "UndefinedBehaviour", "Costmap2D::worldToMap leaves mx, my unset below the origin and "
                                         "getCost reads them (the start equals the goal, off the map)")
        return True
    if _cast_overflows(cm, start):
        _fail(run, "UndefinedBehaviour", f"Costmap2D::worldToMap casts ({cpp_double(start.x)} - origin) / resolution "
                                         f"to unsigned int: the quotient is not below 2^32")
        return True
    mx = int((start.x - cm.origin_x) / cm.resolution)
    my = int((start.y - cm.origin_y) / cm.resolution)
    index = my * cm.size_x + mx
    if index >= cm.size_x * cm.size_y:
        _fail(run, "UndefinedBehaviour", f"getCost reads costmap index {index}, past the end of the "
                                         f"{cm.size_x}x{cm.size_y} costmap (the start equals the goal, off the map)")
        return True
    if int(cm.costs.ravel()[index]) != LETHAL_OBSTACLE:
        return False
    run.lines.append((WARN, UNIQUE_POSE_LETHAL))
    _fail(run, EMPTY_PATH, "createPlan returned an empty path")
    return True


def _log_world_to_map_failed(cm: Costmap, run: PluginRun, mx: int, my: int) -> None:
    run.lines.append((ERROR, f"worldToMap failed: mx,my: {mx},{my}, size_x,size_y: {cm.size_x},{cm.size_y}"))


def _plugin_cell(cm: Costmap, pose: Pose, run: PluginRun) -> tuple[bool, Optional[tuple[int, int]]]:
    """``NavfnPlanner::worldToMap`` on a pose, its ERROR line logged when the rounded cell is off
    the map (below the origin it returns false without a line)."""
    ok, cell = plugin_world_to_map(cm, pose.x, pose.y)
    if not ok and cell is not None:
        _log_world_to_map_failed(cm, run, *cell)
    return ok, cell


def _int_cast_overflows(cm: Costmap, pose: Pose) -> bool:
    """``static_cast<int>(std::round(q))`` in ``NavfnPlanner::worldToMap`` with q not below 2^31
    (undefined behaviour; only reachable where createPlan does not check the poses first)."""
    if pose.x < cm.origin_x or pose.y < cm.origin_y:
        return False
    # round(q) < 2^31 exactly when q < 2^31 - 0.5 (halves away from zero; q >= 0); NaN is not below
    return not all(q < 2.0**31 - 0.5
                   for q in ((pose.x - cm.origin_x) / cm.resolution, (pose.y - cm.origin_y) / cm.resolution))


def make_plan(cm: Costmap, start: Pose, goal: Pose, params: PlannerParams, run: PluginRun, backend: str) -> None:
    """``NavfnPlanner::makePlan``; fills ``run`` (poses empty when no plan)."""
    flavour = flavour_of(params.distro)
    nx, ny = cm.size_x, cm.size_y
    if not flavour.throws and (_int_cast_overflows(cm, start) or _int_cast_overflows(cm, goal)):
        _fail(run, "UndefinedBehaviour", "NavfnPlanner::worldToMap casts std::round((w - origin) / resolution) "
                                         "to int: the value is not below 2^31")
        return
    ok, robot = _plugin_cell(cm, start, run)
    if not ok and not flavour.throws:
        run.lines.append((WARN, ROBOT_OFF_MAP))
        return
    run.robot_cell = robot
    ros = np.array(cm.costs, dtype=np.uint8, copy=True)
    if robot[1] * nx + robot[0] >= nx * ny:
        _fail(run, "UndefinedBehaviour", f"clearRobotCell writes costmap index {robot[1] * nx + robot[0]}, past the "
                                         f"end of the {nx}x{ny} costmap (the robot's position rounds to cell {robot})")
        return
    ros.ravel()[robot[1] * nx + robot[0]] = FREE_SPACE  # clearRobotCell: setCost(mx, my) = costmap_[my*nx + mx]
    run.costs = set_costmap(ros, is_ros=True, allow_unknown=params.allow_unknown)
    ok, target = _plugin_cell(cm, goal, run)
    if not ok and not flavour.throws:
        run.lines.append((WARN, GOAL_OFF_MAP))
        return
    run.target_cell = target
    try:
        _propagate(run, target, robot, params.use_astar, backend, params.fix)
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
        run.lines.append((ERROR, LEGAL_BUT_NO_PLAN))
        return
    poses = smooth_approach_to_goal(best, poses, flavour.same_position_smoothing, run.arith)
    if params.use_final_approach_orientation:
        poses = _final_approach_orientation(poses, start)
    run.poses = poses


def get_point_potential(cm: Costmap, run: PluginRun, wx: float, wy: float) -> float:
    """``getPointPotential``: DBL_MAX when the plugin's worldToMap fails (its ERROR line logged
    when the point lies past the right or top edge), else the float potential."""
    ok, cell = plugin_world_to_map(cm, wx, wy)
    if not ok:
        if cell is not None:
            _log_world_to_map_failed(cm, run, *cell)
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
    _log_tolerance_points(cm, run, xs, ys)
    cols, rows = rounded_cells(xs, cm.origin_x, cm.resolution, cm.size_x), rounded_cells(ys, cm.origin_y,
                                                                                             cm.resolution, cm.size_y)
    xi, yi = np.nonzero(cols >= 0)[0], np.nonzero(rows >= 0)[0]
    if len(xi) == 0 or len(yi) == 0:
        return None
    pot = run.potential[rows[yi][:, None], cols[xi][None, :]].astype(np.float64)  # (y, x): the loop's order
    sdist = squared_offset_in(run.arith, "tolerance")((xs[xi] - goal.x)[None, :], (ys[yi] - goal.y)[:, None])
    taken = tolerance_prefers(pot, sdist, DBL_MAX)  # the points the loop could take at all
    if not taken.any():
        return None
    # the loop's strict '<' keeps the first of the nearest it could take
    k = int(np.argmin(np.where(taken, sdist, np.inf)))
    return goal.with_position(float(xs[xi[k % len(xi)]]), float(ys[yi[k // len(xi)]]))


def _log_tolerance_points(cm: Costmap, run: PluginRun, xs: np.ndarray, ys: np.ndarray) -> None:
    """The ERROR line ``getPointPotential``'s worldToMap logs for every tolerance point, in the
    loop's (y, x) order, that is not below the origin but rounds to a cell past an edge."""
    if len(xs) == 0 or len(ys) == 0:
        return
    mx, my = rounded_raw(xs, cm.origin_x, cm.resolution), rounded_raw(ys, cm.origin_y, cm.resolution)
    past = ((xs >= cm.origin_x)[None, :] & (ys >= cm.origin_y)[:, None]
            & ((mx >= cm.size_x)[None, :] | (my >= cm.size_y)[:, None]))
    for j, i in zip(*np.nonzero(past)):
        _log_world_to_map_failed(cm, run, int(mx[i]), int(my[j]))


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


def rounded_raw(w: np.ndarray, origin: float, res: float) -> np.ndarray:
    """``std::round((w - origin) / res)`` per point (the value ``NavfnPlanner::worldToMap`` writes
    when ``w >= origin``; meaningless below the origin)."""
    f = (w - origin) / res
    fl = np.floor(f)
    return np.where(np.isfinite(fl), fl + (f - fl >= 0.5), -1).astype(np.int64)


def rounded_cells(w: np.ndarray, origin: float, res: float, size: int) -> np.ndarray:
    """``NavfnPlanner::worldToMap`` per axis on many points: the rounded cell, or -1 when the call fails."""
    cell = rounded_raw(w, origin, res)
    return np.where((w >= origin) & (cell < size), cell, -1)


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
        planner = get_backend(backend, PlannerUnderTest(params.fix, run.arith.navfn)).prepare(run.costs)
        run.extraction, path = planner.extract(run.potential, cell, run.robot_cell, n)
        gradient = run.extraction
        if params.fix.fallback is not None:  # calcPath's gradient as shipped first, its log unchanged
            alone = PlannerUnderTest(replace(params.fix, fallback=None), run.arith.navfn)
            gradient, _ = get_backend(backend, alone).prepare(run.costs).extract(run.potential, cell, run.robot_cell, n)
        if gradient is ExtractionExit.EXHAUSTED and flavour_of(params.distro).exhausted_warning:
            run.lines.append((WARN, f"[PathCalc] Path extraction exhausted: npath = {max(n, 0)}, max_cycles = {n}"))
    except UndefinedBehaviour as e:
        _fail(run, "UndefinedBehaviour", str(e))
        return []
    run.path = path
    return [Pose(*plugin_map_to_world(cm, px, py, run.arith)) for px, py in path[::-1].tolist()]


def smooth_approach_to_goal(goal: Pose, poses: list, same_position: bool = True,
                            arith: PluginArithmetic = PLUGIN_X86_64) -> list:
    """``smoothApproachToGoal``: replace the last pose by the goal when it lies farther from the
    one before than the goal does, or (same position; Jazzy on) to take its orientation; else
    append it."""
    if len(poses) >= 2:
        before, last = poses[-2], poses[-1]
        farther = squared_distance(last, before, "smooth_last", arith)
        if farther > squared_distance(goal, before, "smooth_goal", arith):
            return poses[:-1] + [goal]
        if same_position and squared_distance(last, goal, "same_position", arith) < 1e-6:
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
               backend: str, fix: Fix = AS_SHIPPED) -> None:
    """``setStart``/``setGoal`` then ``calcNavFnAstar`` or ``calcNavFnDijkstra(atStart=true)``,
    as ``fix`` changes them (:func:`navfn_smt.spec.planner.calc_navfn`).

    Cells one past the edge (see :func:`plugin_world_to_map`) reach NavFn unchecked; their index
    ``y * nx + x`` then names cell (0, y + 1), and their coordinates enter the A* heuristic
    and the path's last point: that case runs with the raw coordinates (:func:`_propagate_raw`).
    """
    from ..backends import get_backend

    ny, nx = run.costs.shape
    run.cycle_limit = fix.first_cycles(nx, ny)  # the first call's: max(nx*ny/20, nx+ny) as shipped
    on_map = all(0 <= c[0] < nx and 0 <= c[1] < ny for c in (navfn_start, navfn_goal))
    if on_map:
        # calcNavFn* only propagate; calcPath comes later, from the chosen pose's cell (the
        # backend's calcPath of 0 points and the fix's fallback of 0 points cost nothing)
        planner = get_backend(backend, PlannerUnderTest(fix, run.arith.navfn)).prepare(run.costs)
        r = planner.run(navfn_start, navfn_goal, astar, trace=False, path_cycles=0)
        run.potential, run.reached, run.cycles, run.dropped = r.potential, r.start_reached, r.cycles, r.dropped
        return
    for what, c in (("start", navfn_start), ("goal", navfn_goal)):
        if c[1] * nx + c[0] >= nx * ny:
            raise UndefinedBehaviour(f"NavFn's {what} cell {c} indexes {c[1] * nx + c[0]}, past the end of potarr "
                                     f"({nx * ny} cells)")
    _propagate_raw(run, navfn_start, navfn_goal, astar, backend, fix)


def _propagate_raw(run: PluginRun, navfn_start, navfn_goal, astar: bool, backend: str = "jit",
                   fix: Fix = AS_SHIPPED) -> None:
    """Propagation with a cell one past the edge, its coordinates as they are: the spec's planning
    call (:func:`~navfn_smt.spec.planner.calc_navfn`), on the reference spec or compiled."""
    from ..spec.planner import calc_navfn
    from ..spec.propagation import setup

    ny, nx = run.costs.shape
    if backend == "jit":
        from ..backends.jit import JitPlanner

        planner = JitPlanner(add_border(run.costs), arith=run.arith.navfn)
        run.reached = planner.propagate(navfn_start, navfn_goal, astar, run.cycle_limit, False, fix.further)
        run.potential = planner.pot.reshape(ny, nx).copy()
        run.cycles, _, run.dropped, _ = planner.counts()
        return
    st = setup(add_border(run.costs).ravel().tolist(), nx, ny, navfn_goal, arith=run.arith.navfn)
    reached, _ = calc_navfn(st, navfn_start, navfn_goal, astar, fix, record_trace=False)
    run.reached = bool(reached)
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
