"""The table of docs/distributions.md, kept with the tests that check it: what the planner
plugin does differently in Humble, Jazzy, Kilted, Lyrical and Rolling, each difference with
the smallest case that shows it.

Every row (plugin rows, then the costmap layers' :data:`LAYER_DIFFERENCES`) is checked
against the C++ of all five distributions (built from their sources by
``navfn-smt oracle build``; ``tests/test_oracle.py``) and against the model of each
(:mod:`~navfn_smt.distros`); ``docs/distributions.md`` shows the same table.
NavFn itself (``navfn.cpp``'s arithmetic) is the same in all five: the live difftest of the
shared suite agrees with each distribution's build on every case.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from typing import Optional

import numpy as np

from navfn_smt.distros import CHECKED
from navfn_smt.nav2.costmap import INFLATION, LEGACY_INFLATION, STATIC, CostmapParams, InflationParams, LayerSpec
from navfn_smt.nav2.params import PlannerParams
from navfn_smt.nav2.plugin import EMPTY_PATH, Costmap, Pose

DISTROS = CHECKED  # the five whose sources are at hand


@dataclass(frozen=True)
class Difference:
    key: str
    what: str  # the difference, in the plugin's terms
    case: str  # the case, in words
    costs: tuple  # rows of the costmap (row 0 at the origin), 0.05 m cells, origin (0, 0)
    params: PlannerParams
    start: Pose
    goal: Pose


def _grid(w: int, h: int, lethal=()) -> tuple:
    g = np.zeros((h, w), dtype=np.uint8)
    for x, y in lethal:
        g[y, x] = 254
    return tuple(map(tuple, g.tolist()))


_U = np.zeros((12, 12), dtype=np.uint8)
_U[2:10, 5] = 254
_U[2, 2:10] = 254

DIFFERENCES = (
    Difference("pose-checks", "createPlan checks both poses with Costmap2D::worldToMap and throws (Jazzy on); "
               "Humble warns in makePlan and returns an empty path",
               "8x6 free map, start (-0.2, 0.1) below the origin, goal (0.2, 0.2)",
               _grid(8, 6), PlannerParams(), Pose(-0.2, 0.1), Pose(0.2, 0.2)),
    Difference("equal-positions-lethal", "equal start and goal positions: Humble first looks up the start's "
               "cost and returns an empty path on a lethal cell; later versions return the one pose",
               "8x6 map, cell (2, 2) lethal, start = goal = (0.125, 0.125), the goal turned 90 degrees",
               _grid(8, 6, [(2, 2)]), PlannerParams(), Pose(0.125, 0.125),
               Pose(0.125, 0.125, 0.0, 0.0, 0.7071067811865476, 0.7071067811865476)),
    Difference("same-position-smoothing", "smoothApproachToGoal replaces a last pose at the goal's position "
               "(Jazzy on); Humble appends the goal after it, publishing the position twice",
               "8x6 free map, start (0.1, 0.1), goal (0.25, 0.1) on a cell corner",
               _grid(8, 6), PlannerParams(), Pose(0.1, 0.1), Pose(0.25, 0.1)),
    Difference("max-cycles-factor", "max_cycles_factor (Lyrical, Rolling) sets calcPath's budget; the others always "
               "give it 4 * max(size_x, size_y) cycles, and Lyrical's and Rolling's calcPath warns when it "
               "runs out",
               "12x12 U-shaped wall, start (0.175, 0.175), goal (0.425, 0.175), max_cycles_factor 1",
               tuple(map(tuple, _U.tolist())), PlannerParams(max_cycles_factor=1), Pose(0.175, 0.175),
               Pose(0.425, 0.175)),
)


def costmap_of(d: Difference) -> Costmap:
    return Costmap(np.array(d.costs, dtype=np.uint8), 0.0, 0.0, 0.05)


def summary_of(error, poses: int, lines: list) -> str:
    """An outcome in a few words: the exception or the pose count, then the log's first words."""
    head = error if error not in (None, EMPTY_PATH) else f"{poses} pose" + ("" if poses == 1 else "s")
    return head + "".join(f"; {'WARN' if level == 30 else 'ERROR'} \"{line[:32]}...\"" for level, line in lines)


# ----------------------------------------------------------------------- the costmap layers
@dataclass(frozen=True)
class LayerDifference:
    key: str
    what: str
    case: str
    occupancy: tuple  # rows of the occupancy grid (row 0 at the origin), 0.05 m cells, origin (0, 0)
    layer_type: Optional[str]  # the inflation plugin type after the static layer, or None
    inflation: Optional[InflationParams] = None


LAYER_DIFFERENCES = (
    LayerDifference("inscribed-obstacle-cost", "the static layer turns occupancy 99 into INSCRIBED_INFLATED_OBSTACLE "
                    "(253) in Lyrical and Rolling; before, 99 is below the lethal threshold and trinary makes it free",
                    "3x1 grid of occupancy 0, 99, 100, the static layer alone", ((0, 99, 100),), None),
    LayerDifference("inflation-layer", "nav2_costmap_2d::InflationLayer is the breadth-first layer up to Kilted and "
                    "the distance-transform layer in Lyrical and Rolling (its cost table is sampled every 1/100 cell)",
                    "7x7 grid, one occupied cell in the middle, InflationLayer with inflation_radius 0.1, "
                    "cost_scaling_factor 5.0, robot_radius 0; the cell diagonal to the obstacle",
                    tuple(tuple(100 if (x, y) == (3, 3) else 0 for x in range(7)) for y in range(7)), INFLATION,
                    InflationParams(inflation_radius=0.1, cost_scaling_factor=5.0)),
    LayerDifference("legacy-inflation-layer", "nav2_costmap_2d::LegacyInflationLayer exists from Nav2 1.5 on "
                    "(Rolling): the breadth-first layer under its new name",
                    "the same 7x7 case with LegacyInflationLayer", tuple(tuple(100 if (x, y) == (3, 3) else 0
                                                                              for x in range(7)) for y in range(7)),
                    LEGACY_INFLATION, InflationParams(inflation_radius=0.1, cost_scaling_factor=5.0)),
)


def layer_params(d: LayerDifference) -> CostmapParams:
    layers = [LayerSpec("static_layer", STATIC)]
    if d.layer_type is not None:
        layers.append(LayerSpec("inflation_layer", d.layer_type, d.inflation))
    return replace(CostmapParams(), plugins=tuple(layers), robot_radius=0.0, footprint_padding=0.0)


def layer_summary(costmap) -> str:
    """A layer case's outcome in a few words: no such layer, the costs of a one-row grid, or the
    cost of the cell diagonal to the middle of a 7x7 grid."""
    if costmap is None:
        return "no such layer"
    if costmap.shape[0] == 1:
        return "costs " + " ".join(str(int(v)) for v in costmap[0])
    return f"cell (2, 2): {int(costmap[2, 2])}"
