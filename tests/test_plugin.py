"""NavfnPlanner::createPlan (nav2/plugin.py): every exception path and plugin rule with an
expectation derived by hand from navfn_planner.cpp, the params file, and conformance with the
core spec where no plugin-specific rule applies."""

import math
from pathlib import Path

import numpy as np
import pytest

from navfn_smt.errors import NavfnInputError
from navfn_smt.nav2.params import PlannerParams, planner_params
from navfn_smt.nav2.plugin import (LEGAL_BUT_NO_PLAN, POT_HIGH, Costmap, Pose, create_plan,
                                   quaternion_from_yaw, smooth_approach_to_goal)
from navfn_smt.spec.costs import set_costmap
from navfn_smt.spec.planner import plan as spec_plan

pytestmark = pytest.mark.fast

DATA = Path(__file__).resolve().parent / "data" / "plugin_cases"
RES = 0.05000000074505806  # float32(0.05) widened: 13421773 * 2**-28
assert RES == float(np.float32(0.05)) and RES == 13421773 * 2.0 ** -28


def cm(costs, ox=0.0, oy=0.0, res=RES):
    return Costmap(np.asarray(costs, dtype=np.uint8), ox, oy, res)


def free(w, h):
    return np.zeros((h, w), dtype=np.uint8)


P = PlannerParams()


# ------------------------------------------------------------------ StartOutsideMapBounds
def test_start_below_origin_in_x_and_y():
    m = cm(free(6, 5), 1.0, 2.0)
    r = create_plan(m, Pose(0.999, 2.1), Pose(1.1, 2.1), P)
    assert r.error == "StartOutsideMapBounds"
    assert r.message == "Start Coordinates of(0.999000, 2.100000) was outside bounds"
    r = create_plan(m, Pose(1.1, 1.9999999999999998), Pose(1.1, 2.1), P)
    assert r.error == "StartOutsideMapBounds"
    # %f rounds to six decimals: 1.9999999999999998 prints as 2.000000
    assert r.message == "Start Coordinates of(1.100000, 2.000000) was outside bounds"
    assert r.poses == []


def test_start_exactly_at_origin_plus_size_is_outside():
    # 6 * RES = 80530638 * 2**-28 exactly (27 significant bits), and 6*RES / RES == 6.0: trunc 6, not < 6
    x = 6 * RES
    assert x == 80530638 * 2.0 ** -28 and x / RES == 6.0
    m = cm(free(6, 5))
    assert create_plan(m, Pose(x, 0.1), Pose(0.1, 0.1), P).error == "StartOutsideMapBounds"
    # the double below is in column 5: the truncating check passes (and it rounds to column 6, see offmap)
    r = create_plan(m, Pose(math.nextafter(x, 0), 0.1), Pose(0.1, 0.1), P)
    assert r.start_cell == (5, 1) and r.error != "StartOutsideMapBounds"  # 0.1 / RES = 1.99999997


def test_float32_resolution_makes_a_point_that_looks_inside_outside():
    # "resolution: 0.01" is held as float32(0.01) = 10737418 * 2**-30 = 0.009999999776482582 < 0.01,
    # so a 10-cell map ends at 10 * res = 0.09999999776482582, below the 0.1 the YAML suggests
    res = float(np.float32(0.01))
    assert res == 10737418 * 2.0 ** -30 == 0.009999999776482582
    m = cm(free(10, 10), res=res)
    w = 0.099999999  # < 0.1, "inside" a 10 x 0.01 m map; w / res = 10.0000000224... -> trunc 10
    assert math.trunc(w / res) == 10
    r = create_plan(m, Pose(w, 0.05), Pose(0.05, 0.05), P)
    assert r.error == "StartOutsideMapBounds"
    assert r.message == "Start Coordinates of(0.100000, 0.050000) was outside bounds"
    # and the reverse for 0.05: float32(0.05) > 0.05 makes 0.3 (the nominal edge of 6 cells) inside
    assert create_plan(cm(free(6, 5)), Pose(0.3, 0.1), Pose(0.1, 0.1), P).start_cell == (5, 1)


# ------------------------------------------------------------------ GoalOutsideMapBounds
def test_goal_outside_bounds():
    m = cm(free(6, 5), 1.0, 2.0)
    r = create_plan(m, Pose(1.1, 2.1), Pose(1.1, 1.5), P)
    assert r.error == "GoalOutsideMapBounds"
    assert r.message == "Goal Coordinates of(1.100000, 1.500000) was outside bounds"
    r = create_plan(m, Pose(1.1, 2.1), Pose(0.5, 2.1), P)
    assert r.error == "GoalOutsideMapBounds"
    r = create_plan(m, Pose(1.1, 2.1), Pose(1.0 + 6 * RES, 2.1), P)  # the far edge, as for the start
    assert r.error == "GoalOutsideMapBounds"
    assert r.message == "Goal Coordinates of(1.300000, 2.100000) was outside bounds"
    # the start is checked first
    assert create_plan(m, Pose(0.0, 0.0), Pose(0.0, 0.0), P).error == "StartOutsideMapBounds"


# ------------------------------------------------------------------ GoalOccupied
@pytest.mark.parametrize("cost,tolerance,error", [
    (254, 0.0, "GoalOccupied"),
    (253, 0.0, "NoValidPathCouldBeFound"),  # inscribed: not the check's value; NavFn's COST_OBS, unreachable
    (254, 0.5, None),  # with a tolerance the nearest legal point is planned to
])
def test_goal_occupied_only_lethal_and_zero_tolerance(cost, tolerance, error):
    c = free(8, 6)
    c[3, 4] = cost
    p = PlannerParams(tolerance=tolerance)
    r = create_plan(cm(c), Pose(0.11, 0.11), Pose(4.25 * RES, 3.25 * RES), p)
    assert r.error == error
    if error == "GoalOccupied":
        assert r.message == "Goal Coordinates of(0.212500, 0.162500) was in lethal cost"
    elif error:
        assert r.message == "Failed to create plan with tolerance of: 0.000000"
    else:
        assert r.used_tolerance and r.best_cell != (4, 3)


def test_goal_occupied_uses_the_truncated_cell():
    # x = 4.75 cells: truncation gives column 4, std::round column 5
    c = free(8, 6)
    c[3, 4] = 254
    r = create_plan(cm(c), Pose(0.11, 0.11), Pose(4.75 * RES, 3.25 * RES), PlannerParams(tolerance=0.0))
    assert r.error == "GoalOccupied"
    c = free(8, 6)
    c[3, 5] = 254
    r = create_plan(cm(c), Pose(0.11, 0.11), Pose(4.75 * RES, 3.25 * RES), PlannerParams(tolerance=0.0))
    assert r.error == "NoValidPathCouldBeFound" and r.target_cell == (5, 3)


# ------------------------------------------------------------------ NoValidPathCouldBeFound / tolerance
def test_disconnected_goal():
    c = free(12, 6)
    c[:, 6] = 254  # a wall: columns 7..10 unreachable from column 2
    r = create_plan(cm(c), Pose(2.25 * RES, 2.25 * RES), Pose(9.25 * RES, 2.25 * RES), PlannerParams(tolerance=0.1))
    # window: 9.25 cells - 2 .. +1 (the loop's last point falls short, see offmap): columns 7..10, all unreachable
    assert r.error == "NoValidPathCouldBeFound" and r.used_tolerance
    assert r.message == "Failed to create plan with tolerance of: 0.100000"
    assert r.goal_potential >= POT_HIGH


HALF = 0.5  # a resolution with exact sums: the tolerance loop's points are exact


def test_tolerance_best_pose_and_tie_breaking():
    # 7x7, res 0.5: goal (1.5, 1.5) is the corner of cell (3, 3), lethal; tolerance 1.0:
    # the loop visits x, y in {0.5, 1.0, 1.5, 2.0, 2.5} (exact), y outer, x inner.
    # Legal nearest: the four neighbours at squared distance 0.25; first in (y, x) order is
    # (1.5, 1.0) (row y = 1.0 comes before row 1.5); the later equal ones lose on strict '<'.
    c = free(7, 7)
    c[3, 3] = 254
    goal = Pose.from_yaw(1.5, 1.5, 0.7)
    r = create_plan(cm(c, res=HALF), Pose(0.5, 0.5), goal, PlannerParams(tolerance=1.0))
    assert r.ok and r.used_tolerance
    assert (r.best_pose.x, r.best_pose.y) == (1.5, 1.0) and r.best_cell == (3, 2)
    assert (r.poses[-1].x, r.poses[-1].y) == (1.5, 1.0)  # the path ends at the best pose ...
    assert r.poses[-1].orientation == goal.orientation  # ... with the goal's orientation
    assert (r.poses[0].x, r.poses[0].y) == (0.5, 0.5)  # NavFn's last point: the robot's cell corner
    # block (3, 2) as well: next in order at 0.25 is (1.0, 1.5) (row 1.5, x = 1.0 before 2.0)
    c[2, 3] = 254
    r = create_plan(cm(c, res=HALF), Pose(0.5, 0.5), goal, PlannerParams(tolerance=1.0))
    assert (r.best_pose.x, r.best_pose.y) == (1.0, 1.5)


def test_tolerance_loop_values_are_accumulated_doubles():
    # res = float32(0.05), goal (0.15000000223517418, ...) = 3 * RES, cell (3, 3) lethal, tolerance 0.1.
    # g = 3 * RES = 40265319 * 2**-28 = 0x1.3333338p-3 exactly; the loop's x: p0 = fl(g - 0.1), then
    # p += RES one rounding at a time (0.1 is not a multiple of RES: p2 misses g by 0x0.0000000333333p-3).
    g = 3 * RES
    p0 = g - 0.1
    p1 = p0 + RES
    p2 = p1 + RES
    p3 = p2 + RES
    p4 = p3 + RES
    assert p4 > g + 0.1 >= p3  # four points: the loop stops short of g + 0.1
    assert p2 != g  # the accumulated point at the goal's column is not the goal's coordinate
    assert (p0.hex(), p1.hex(), p2.hex(), p3.hex()) == (
        "0x1.99999acccccccp-5", "0x1.99999a6666666p-4", "0x1.333333b333333p-3", "0x1.99999a3333333p-3")
    assert g.hex() == "0x1.3333338000000p-3"
    c = free(7, 7)
    c[3, 3] = 254
    r = create_plan(cm(c), Pose(1.25 * RES, 1.25 * RES), Pose(g, g), PlannerParams(tolerance=0.1))
    # candidates at squared distance min: (g, p1), (p1, g)... with x = p2 != g: the nearest four are
    # (p2, p1) [row p1], (p1, p2), (p3, p2) [row p2], (p2, p3); |p1 - g| vs |p3 - g| decides
    d1, d2, d3 = p1 - g, p2 - g, p3 - g
    cands = [(d2 * d2 + d1 * d1, (p2, p1)), (d1 * d1 + d2 * d2, (p1, p2)), (d3 * d3 + d2 * d2, (p3, p2)),
             (d2 * d2 + d3 * d3, (p2, p3))]
    best = min(cands, key=lambda t: t[0])  # min keeps the first of equals: the loop's strict '<'
    assert (r.best_pose.x, r.best_pose.y) == best[1]
    assert (r.best_pose.x, r.best_pose.y) == (p2, p1)


def test_unreachable_goal_no_legal_point_within_tolerance():
    c = free(12, 6)
    c[1:5, 5:10] = 254  # the goal at column 7 amid a 5-wide lethal block, tolerance 1 cell
    r = create_plan(cm(c), Pose(1.25 * RES, 1.25 * RES), Pose(7.25 * RES, 2.25 * RES),
                    PlannerParams(tolerance=RES))
    assert r.error == "NoValidPathCouldBeFound" and r.used_tolerance
    assert r.message == "Failed to create plan with tolerance of: 0.050000"


# ------------------------------------------------------------------ start == goal
def test_start_equals_goal_orientation_rules():
    m = cm(free(6, 6))
    a, b = Pose.from_yaw(0.12, 0.12, 0.0), Pose.from_yaw(0.12, 0.12, 1.0)
    assert create_plan(m, a, a, P).poses == [a]
    r = create_plan(m, a, b, P)
    assert r.poses == [Pose(0.12, 0.12, *b.orientation)]  # the goal's orientation
    r = create_plan(m, a, b, PlannerParams(use_final_approach_orientation=True))
    assert r.poses == [a]  # the start's: no rotation in place
    # no planning at all: even a start on a lethal cell, and a goal on a lethal cell with tolerance > 0
    c = free(6, 6)
    c[2, 2] = 254
    assert create_plan(cm(c), a, b, P).poses == [Pose(0.12, 0.12, *b.orientation)]
    # ... but GoalOccupied is checked first
    assert create_plan(cm(c), a, b, PlannerParams(tolerance=0.0)).error == "GoalOccupied"
    # exact equality: one double apart is a plan
    r = create_plan(m, a, Pose(0.12, math.nextafter(0.12, 1)), P)
    assert r.ok and r.target_cell == r.robot_cell and len(r.poses) >= 2


# ------------------------------------------------------------------ smoothApproachToGoal
def test_smooth_approach_three_branches():
    before, last = Pose(0.0, 0.0), Pose(1.0, 0.0)
    goal = Pose.from_yaw(0.5, 0.0, 1.0)
    # 1. last farther from before (1.0) than the goal (0.25): replaced
    assert smooth_approach_to_goal(goal, [before, last]) == [before, goal]
    # 2. not farther, but within 1e-3 (squared 1e-6) of the goal: replaced (orientation)
    g2 = Pose.from_yaw(1.0, 0.0009, 2.0)
    assert smooth_approach_to_goal(g2, [before, last]) == [before, g2]
    # 3. otherwise appended
    g3 = Pose(1.5, 0.0)
    assert smooth_approach_to_goal(g3, [before, last]) == [before, last, g3]
    # boundary of 2: squared distance exactly 1e-6 is not < 1e-6 -> appended ... (0.001**2 rounds above 1e-6)
    g4 = Pose(1.0, 0.001)
    assert 0.001 * 0.001 > 1e-6 or smooth_approach_to_goal(g4, [before, last])[-1] == g4
    # one pose: appended
    assert smooth_approach_to_goal(g3, [last]) == [last, g3]


def test_smooth_approach_through_create_plan():
    # res 0.5, a 1-wide corridor (row 1 of a 9x3 map): NavFn's points are cell corners (k, 1) -> (k/2, 0.5)
    m = cm(free(9, 3), res=HALF)
    # goal (3.6, 0.5): cell (7, 1); last point (3.5, 0.5), before it (3.0, 0.5): 0.25 > 0.36? no;
    # |last - goal|^2 = 0.01 >= 1e-6 -> appended
    r = create_plan(m, Pose(0.5, 0.5), Pose(3.6, 0.5), P)
    xs = [p.x for p in r.poses]
    assert xs[-3:] == [3.0, 3.5, 3.6]
    # goal (3.4, 0.5): rounds to cell 7 too; last (3.5) is 0.25 from before (3.0), goal 0.16: replaced
    r = create_plan(m, Pose(0.5, 0.5), Pose(3.4, 0.5), P)
    assert [p.x for p in r.poses][-2:] == [3.0, 3.4]
    # goal (3.5, 0.5) itself: squared distance 0 < 1e-6: replaced (same position, the goal's orientation)
    g = Pose.from_yaw(3.5, 0.5, 1.0)
    r = create_plan(m, Pose(0.5, 0.5), g, P)
    assert r.poses[-1] == g and [p.x for p in r.poses][-2:] == [3.0, 3.5]


# ------------------------------------------------------------------ use_final_approach_orientation
def test_quaternion_hand_values():
    assert quaternion_from_yaw(0.0) == (0.0, 0.0, 0.0, 1.0)
    # setRPY(0, 0, y): (0, 0, sin(y/2), cos(y/2)) (the roll/pitch products are exact zeros)
    assert quaternion_from_yaw(math.pi / 2) == (0.0, 0.0, 0.7071067811865475, 0.7071067811865476)
    assert quaternion_from_yaw(math.pi) == (0.0, 0.0, 1.0, 6.123233995736766e-17)


@pytest.mark.parametrize("start,goal,q", [
    ((0.5, 0.5), (3.5, 0.5), (0.0, 0.0, 0.0, 1.0)),  # eastward: atan2(0, +) = 0
    ((3.5, 0.5), (0.5, 0.5), (0.0, 0.0, 1.0, 6.123233995736766e-17)),  # westward: atan2(0, -) = pi
])
def test_final_approach_orientation_along_corridor(start, goal, q):
    m = cm(free(9, 3), res=HALF)
    p = PlannerParams(use_final_approach_orientation=True)
    r = create_plan(m, Pose.from_yaw(*start, 2.0), Pose.from_yaw(*goal, -2.0), p)
    assert r.poses[-1].orientation == q
    assert all(pose.orientation == (0.0, 0.0, 0.0, 1.0) for pose in r.poses[:-1])


def test_final_approach_orientation_northward():
    m = cm(free(3, 9), res=HALF)
    r = create_plan(m, Pose(0.5, 0.5), Pose(0.5, 3.5), PlannerParams(use_final_approach_orientation=True))
    assert r.poses[-1].orientation == (0.0, 0.0, 0.7071067811865475, 0.7071067811865476)


# ------------------------------------------------------------------ max_cycles
def serpentine(width):
    """Interior 5x5 (cells 1..5) as a snake: rows 1, 3, 5 open, (5, 2) and (1, 4) the turns;
    columns 6.. lethal.  From (5, 5) the grid-following extraction (every cell touches a lethal
    one) visits (5,5) (4,5) (3,5) (2,5) (1,4) (2,3) (3,3) (4,3) (5,2) (4,1) (3,1) (2,1) -- diagonal
    steps cut each turn -- then at (1, 1) (potential 0 < COST_NEUTRAL) adds the goal: 13 cycles.
    The map must be at least 12 wide for the propagation itself: NavFn's cycle limit
    max(nx*ny/20, nx+ny) is 14 at 7x7, fewer than the corridor's 17 cells (the goal is then never
    reached: a different failure, tolerance search without a legal point)."""
    c = np.full((7, width), 254, np.uint8)
    c[1, 1:6] = c[3, 1:6] = c[5, 1:6] = 0
    c[2, 5] = c[4, 1] = 0
    return c


@pytest.mark.parametrize("width,factor,ok", [(12, 1, False), (13, 1, True), (12, 2, True), (13, 0, False),
                                             (13, -1, False)])
def test_max_cycles_budget(width, factor, ok):
    # max_cycles = max(size_x, 7) * factor; 13 cycles needed: 12 fails, 13 passes
    r = create_plan(cm(serpentine(width), res=HALF), Pose(0.5, 0.5), Pose(2.5, 2.5),
                    PlannerParams(max_cycles_factor=factor))
    assert r.max_cycles == max(width, 7) * factor
    if ok:
        assert r.ok and len(r.path) == 13
        assert [tuple(p) for p in r.path.tolist()] == [(5, 5), (4, 5), (3, 5), (2, 5), (1, 4), (2, 3), (3, 3),
                                                       (4, 3), (5, 2), (4, 1), (3, 1), (2, 1), (1, 1)]
    else:
        assert r.error == "NoValidPathCouldBeFound" and LEGAL_BUT_NO_PLAN in r.log and r.legal_potential_no_plan


# ------------------------------------------------------------------ clearRobotCell, allow_unknown, modes
def test_robot_on_lethal_cell_still_plans():
    c = free(8, 6)
    c[2, 2] = 254
    r = create_plan(cm(c), Pose(2.25 * RES, 2.25 * RES), Pose(5.25 * RES, 3.25 * RES), P)
    assert r.ok and r.robot_cell == (2, 2)
    # the costs NavFn saw have the robot's cell free (COST_NEUTRAL), the caller's costmap untouched here
    assert r.costs[2, 2] == 50 and c[2, 2] == 254


@pytest.mark.parametrize("allow", [True, False])
def test_allow_unknown_corridor(allow):
    c = np.full((3, 10), 255, np.uint8)  # all unknown: the corridor row 1 is the only way
    c[1, 1] = 0
    r = create_plan(cm(c, res=HALF), Pose(0.5, 0.5), Pose(4.0, 0.5),
                    PlannerParams(allow_unknown=allow, tolerance=0.0))
    if allow:  # unknown -> COST_OBS - 1 = 253: passable
        assert r.ok and (r.poses[-1].x, r.poses[-1].y) == (4.0, 0.5)
    else:  # unknown -> COST_OBS
        assert r.error == "NoValidPathCouldBeFound"


@pytest.mark.parametrize("astar", [True, False])
def test_astar_and_dijkstra_both_succeed(astar):
    c = free(12, 10)
    c[2:8, 5] = 254
    r = create_plan(cm(c), Pose(2.25 * RES, 4.25 * RES), Pose(9.25 * RES, 4.25 * RES), PlannerParams(use_astar=astar))
    assert r.ok and len(r.poses) > 3 and r.goal_potential < POT_HIGH


# ------------------------------------------------------------------ params
def test_params_from_bringup_like_file():
    p = planner_params(DATA / "nav2_params.yaml")
    assert p == PlannerParams(tolerance=0.5, use_astar=False, allow_unknown=True, max_cycles_factor=4,
                              use_final_approach_orientation=False, plugin="GridBased")


def test_params_values_and_defaults(tmp_path):
    f = tmp_path / "p.yaml"
    f.write_text("planner_server:\n  ros__parameters:\n    planner_plugins: [\"GridBased\"]\n    GridBased:\n"
                 "      plugin: \"nav2_navfn_planner::NavfnPlanner\"\n      tolerance: 0.25\n      use_astar: true\n")
    p = planner_params(f)
    assert (p.tolerance, p.use_astar, p.allow_unknown, p.max_cycles_factor, p.use_final_approach_orientation) == (
        0.25, True, True, 4, False)
    f.write_text("amcl:\n  ros__parameters:\n    alpha1: 0.2\n")
    assert planner_params(f) == PlannerParams()


def test_params_type_error(tmp_path):
    f = tmp_path / "p.yaml"
    f.write_text("planner_server:\n  ros__parameters:\n    planner_plugins: [\"GridBased\"]\n    GridBased:\n"
                 "      plugin: \"nav2_navfn_planner::NavfnPlanner\"\n      tolerance: 1\n")
    with pytest.raises(NavfnInputError, match=r"'GridBased.tolerance' must be a double.*got 1"):
        planner_params(f)


def test_params_unknown_plugin(tmp_path):
    with pytest.raises(NavfnInputError, match="no planner plugin named 'Nope'"):
        planner_params(DATA / "nav2_params.yaml", plugin="Nope")
    f = tmp_path / "p.yaml"
    f.write_text("planner_server:\n  ros__parameters:\n    planner_plugins: [\"GridBased\"]\n    GridBased:\n"
                 "      plugin: \"nav2_smac_planner::SmacPlanner2D\"\n")
    with pytest.raises(NavfnInputError, match="no planner plugin of type nav2_navfn_planner::NavfnPlanner"):
        planner_params(f)


# ------------------------------------------------------------------ conformance with the core spec
def _conformance_maps(n):
    rng = np.random.default_rng(7)
    for k in range(n):
        w, h = int(rng.integers(5, 13)), int(rng.integers(5, 13))
        c = rng.choice(np.array([0, 0, 0, 30, 100, 200, 252, 253, 254, 255], np.uint8), size=(h, w))
        sx, sy, gx, gy = (int(rng.integers(1, w - 1)), int(rng.integers(1, h - 1)),
                          int(rng.integers(1, w - 1)), int(rng.integers(1, h - 1)))
        yield k, c, (sx, sy), (gx, gy), bool(k % 2)


@pytest.mark.parametrize("backend", ["jit", "reference"])
def test_plugin_path_equals_core_spec(backend):
    """Where the goal is reached and both poses are at 0.25 of a cell (truncation and rounding
    agree): poses = spec path (start = goal cell, goal = robot cell, path_cycles = max * factor)
    reversed, origin + p * res, then smoothApproachToGoal."""
    compared = 0
    for k, c, (sx, sy), (gx, gy), astar in _conformance_maps(40):
        ox, oy = -3.0 + 0.1 * k, 1.7
        m = cm(c, ox, oy)
        start = Pose(ox + (sx + 0.25) * RES, oy + (sy + 0.25) * RES)
        goal = Pose(ox + (gx + 0.25) * RES, oy + (gy + 0.25) * RES)
        if (sx, sy) == (gx, gy):
            continue
        params = PlannerParams(use_astar=astar, max_cycles_factor=1 + k % 4)
        r = create_plan(m, start, goal, params, backend=backend)
        assert r.robot_cell == r.start_cell == (sx, sy) and r.target_cell == r.goal_cell == (gx, gy)
        if r.goal_potential is None or not r.goal_potential < POT_HIGH:
            continue
        ros = c.copy()
        ros[sy, sx] = 0
        costs = set_costmap(ros, is_ros=True, allow_unknown=True)
        s = spec_plan(costs, (gx, gy), (sx, sy), astar=astar, path_cycles=max(c.shape) * params.max_cycles_factor,
                      record_trace=False)
        if len(s.path) == 0:
            assert r.error == "NoValidPathCouldBeFound" and r.legal_potential_no_plan
            continue
        assert np.array_equal(s.path, r.path) and s.path.dtype == np.float32
        world = [(ox + float(px) * RES, oy + float(py) * RES) for px, py in s.path[::-1].tolist()]
        got = [(p.x, p.y) for p in r.poses]
        assert got[:len(world) - 1] == world[:-1]
        assert got[-1] == (goal.x, goal.y)
        assert len(got) in (len(world), len(world) + 1)
        if len(got) == len(world) + 1:
            assert got[-2] == world[-1]
        compared += 1
    assert compared >= 15
