"""Nav2's planning system tests (``nav2_system_tests/src/planning``), their NavFn checks stated on
one ``createPlan`` call of the planner plugin.

``test_planner_plugins.cpp`` and ``PlannerTester``'s random test (``test_planner_random``) make
``nav2_planner``'s ``PlannerServer`` on a ROS graph with a map server and a TF tree, which the
project does not stub (``nav2_planner`` and ``nav2_map_server`` are not in ``../shared``). What
they check of NavFn is carried over here, in our words, as properties of the plugin's answers,
so that any planner answering ``createPlan`` can be held to them: the C++ plugin of an oracle
build, as shipped and fixed (:class:`~navfn_smt.oracle.client.PluginOracle`), or the
specification's model of the plugin (:func:`~navfn_smt.nav2.plugin.create_plan`).

- **The plugin cases** (``testPluginMap.NavFn*``): on the planner server's global costmap with no
  map (5 m x 5 m at 0.1 m, free), from (0.5, 0.5) heading +y to a goal ``length`` metres ahead
  heading -pi, for five lengths (0 to 1.5 m), each without and with
  ``use_final_approach_orientation``: a path comes back, and its last heading is the goal's, or
  with the option the start's (one pose) or the direction from the first pose to the last,
  within 0.01 rad.  ``NavFnCancel`` (a checker that always cancels) is not carried: the oracle's
  driver passes a checker that never cancels.
- **The random test** (``testWithHundredRandomEndPoints``): ``PlannerTester`` reads its map at
  1 m a cell from the origin (occupancy at least 100 lethal, the rest, unknown included, free),
  draws 100 start/goal pairs of free cells (cost below 253) with both coordinates from 1 to the
  size less one, and plans each with A*; a pair fails unless a path comes back whose every pose
  rounds to a free cell (``isCollisionFree``) and which starts at the start and ends at the goal
  exactly (``isWithinTolerance``).  The test passes when at most 10 % fail, in one of three
  draws.  Its draws come from ``std::random_device``; ours from a seed, so a run can be repeated.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Callable, Optional

import numpy as np

from ..spec.constants import FREE_SPACE, INSCRIBED_INFLATED_OBSTACLE, LETHAL_OBSTACLE
from .params import PlannerParams
from .plugin import Costmap, Pose, yaw_of

# testPluginMap's NavFn cases: the goal's distance ahead of the start, in metres
PLUGIN_LENGTHS = (("EqualStartGoal", 0.0), ("VerySmallPath", 0.00001), ("BelowCostmapResolution", 0.09),
                  ("JustAboveCostmapResolution", 0.102), ("AboveCostmapResolution", 1.5))
HEADING_TOLERANCE = 0.01  # rad, the tests' EXPECT_NEAR
RANDOM_PAIRS, RANDOM_TRIES, ACCEPTABLE_FAIL_RATIO = 100, 3, 0.1
LETHAL_OCCUPANCY = 100  # PlannerTester's lethal_threshold_

# a planner under test: (costmap, params, [(start, goal)]) -> one answer per pair
Planner = Callable[[Costmap, PlannerParams, list], list]


@dataclass
class Answer:
    """What one ``createPlan`` gave: the exception's name (None when it returned) and the poses,
    a float64 (n, 6) array of x, y, qx, qy, qz, qw."""

    error: Optional[str]
    poses: np.ndarray


def model_planner(fix, arith=None) -> Planner:
    """The specification's model of the plugin, NavFn with ``fix`` (a :class:`~navfn_smt.spec.planner.Fix`),
    computing as a build of the plugin arithmetic ``arith`` does (None: x86-64's)."""
    from dataclasses import replace

    from .benchmark import poses_array
    from .plugin import EMPTY_PATH, create_plan

    def plan(cm, params, pairs):
        p = replace(params, fix=fix)
        out = []
        for s, g in pairs:
            run = create_plan(cm, s, g, p, arith=arith)
            # Humble's createPlan throws nothing: a failed plan is an empty path, as its C++ returns
            out.append(Answer(None if run.error == EMPTY_PATH else run.error, poses_array(run.poses)))
        return out

    return plan


def oracle_planner(oracle) -> Planner:
    """A running C++ plugin (:class:`~navfn_smt.oracle.client.PluginOracle`)."""

    def plan(cm, params, pairs):
        return [Answer(a.error, a.poses) for a in oracle.create_plans(cm, params, pairs)]

    return plan


def _yaw(row) -> float:
    return yaw_of(Pose(*map(float, row)))


# --------------------------------------------------------------------------- the plugin cases
def default_global_costmap() -> Costmap:
    """The planner server's global costmap when no map has come: 50 x 50 free cells of 0.1 m."""
    return Costmap(np.zeros((50, 50), dtype=np.uint8), 0.0, 0.0, 0.1)


@dataclass
class CaseResult:
    name: str
    ok: bool
    why: str = ""


def plugin_case_checks(answer: Answer, start: Pose, goal: Pose, final_approach: bool) -> str:
    """Why ``answer`` fails testSmallPathValidity(AndNo)Orientation's checks; "" when it passes."""
    if answer.error is not None:
        return f"createPlan threw {answer.error}"
    if len(answer.poses) == 0:
        return "no pose"
    last = _yaw(answer.poses[-1])
    if not final_approach:
        want, what = yaw_of(goal), "the goal's heading"
    elif len(answer.poses) == 1:
        want, what = yaw_of(start), "the start's heading (one pose)"
    else:
        d = answer.poses[-1, :2] - answer.poses[0, :2]
        want, what = math.atan2(d[1], d[0]), "the heading from the first pose to the last"
    if not abs(last - want) <= HEADING_TOLERANCE:
        return f"last heading {last:.4f} rad, not {what} {want:.4f} rad"
    return ""


def run_plugin_cases(planner: Planner, params: PlannerParams = PlannerParams()) -> list[CaseResult]:
    """testPluginMap's ten NavFn cases on ``planner`` (``params``: the planner's other values)."""
    from dataclasses import replace

    cm = default_global_costmap()
    out = []
    for final_approach in (False, True):
        p = replace(params, use_final_approach_orientation=final_approach)
        for name, length in PLUGIN_LENGTHS:
            start = Pose.from_yaw(0.5, 0.5, math.pi / 2)
            goal = Pose.from_yaw(0.5, 0.5 + length, -math.pi)
            (answer,) = planner(cm, p, [(start, goal)])
            why = plugin_case_checks(answer, start, goal, final_approach)
            out.append(CaseResult(f"NavFn{name}{'N' if final_approach else ''}", not why, why))
    return out


# --------------------------------------------------------------------------- the random test
def tester_costmap(occupancy: np.ndarray) -> Costmap:
    """PlannerTester's costmap of an occupancy grid (int8, row 0 the map's bottom): trinary,
    unknown space not tracked (unknown is free), occupancy at least 100 lethal; 1 m a cell at the
    origin, whatever the map's YAML says (``loadDefaultMap``)."""
    occ = np.asarray(occupancy, dtype=np.int16)
    costs = np.where(occ >= LETHAL_OCCUPANCY, LETHAL_OBSTACLE, FREE_SPACE).astype(np.uint8)
    costs[occ == -1] = FREE_SPACE
    return Costmap(costs, 0.0, 0.0, 1.0)


def is_free(cm: Costmap, x: int, y: int) -> bool:
    """``nav2_util::Costmap::is_free``: a cost below the inscribed value."""
    return int(cm.costs[y, x]) < INSCRIBED_INFLATED_OBSTACLE


def draw_end_points(cm: Costmap, n: int, rng: np.random.Generator) -> list[tuple[Pose, Pose]]:
    """``n`` start/goal pairs as PlannerTester draws them: each coordinate uniform from 1 to the
    size less one (both included), drawn again until the cell is free."""
    if not any(is_free(cm, x, y) for y in range(1, cm.size_y) for x in range(1, cm.size_x)):
        raise ValueError("the map has no free cell to draw end points from")

    def one() -> Pose:
        while True:
            x, y = int(rng.integers(1, cm.size_x)), int(rng.integers(1, cm.size_y))  # high excluded
            if is_free(cm, x, y):
                return Pose(float(x), float(y))

    return [(one(), one()) for _ in range(n)]


def random_pair_checks(cm: Costmap, answer: Answer, start: Pose, goal: Pose) -> str:
    """Why a random pair fails plannerTest; "" when it passes."""
    if answer.error is not None:
        return f"createPlan threw {answer.error}"
    if len(answer.poses) == 0:
        return "no pose"
    for x, y in answer.poses[:, :2]:
        mx, my = int(np.round(x)), int(np.round(y))  # std::round, then unsigned
        if not (0 <= mx < cm.size_x and 0 <= my < cm.size_y) or not is_free(cm, mx, my):
            return f"collision at ({x:.2f}, {y:.2f})"
    first, last = answer.poses[0], answer.poses[-1]
    if not (first[0] == start.x and first[1] == start.y and last[0] == goal.x and last[1] == goal.y):
        return (f"path from ({first[0]:.2f}, {first[1]:.2f}) to ({last[0]:.2f}, {last[1]:.2f}), not from the start "
                f"to the goal")
    return ""


@dataclass
class RandomResult:
    """One draw of the random test: its pairs, how many failed and why (the first few)."""

    seed: int
    pairs: int
    failed: int
    failures: list = field(default_factory=list)  # (start, goal, why), at most 5

    @property
    def passed(self) -> bool:
        return self.failed / self.pairs <= ACCEPTABLE_FAIL_RATIO


def run_random_test(planner: Planner, cm: Costmap, seed: int, pairs: int = RANDOM_PAIRS,
                    tries: int = RANDOM_TRIES, params: PlannerParams = PlannerParams(use_astar=True)) -> list[RandomResult]:
    """testWithHundredRandomEndPoints on ``planner``: up to ``tries`` draws (seeds ``seed``,
    ``seed + 1``, ...) until one passes; PlannerTester's planner uses A*."""
    out = []
    for k in range(tries):
        rng = np.random.default_rng(seed + k)
        drawn = draw_end_points(cm, pairs, rng)
        answers = planner(cm, params, drawn)
        failures = [(s, g, why) for (s, g), a in zip(drawn, answers) if (why := random_pair_checks(cm, a, s, g))]
        out.append(RandomResult(seed + k, pairs, len(failures), [(s.x, s.y, g.x, g.y, w) for s, g, w in failures[:5]]))
        if out[-1].passed:
            break
    return out
