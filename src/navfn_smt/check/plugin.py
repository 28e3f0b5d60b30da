"""What a Nav2 user relies on of the planner plugin, judged on one ``createPlan`` of the plugin
model (:func:`navfn_smt.nav2.plugin.create_plan`), as shipped or with the fix, and checked on
every small costmap by ``navfn-smt plugin-check``.

Each judge takes the costmap, the poses, the parameters and the run, and answers ``None`` when
the property holds or a short reason when it does not.  A run that is undefined behaviour in
the C++ (``UndefinedBehaviour``) is not judged.

* ``plugin-complete``: a plan is returned whenever the goal, or a point the tolerance search
  admits, is reachable from the robot: its cell (``NavfnPlanner::worldToMap``) joined to the
  robot's cell by a 4-connected chain of cells NavFn treats as passable (after
  ``clearRobotCell`` and ``setCostmap``: inscribed and lethal costs are obstacles, unknown is
  passable with ``allow_unknown``; the robot's own cell is where the wave starts).
* ``plugin-poses-passable``: every pose Nav2 publishes lies in a cell the costmap's own
  ``Costmap2D::worldToMap`` (what a controller or a collision checker uses) finds, and whose cost
  is below ``INSCRIBED_INFLATED_OBSTACLE`` (253; unknown, 255, only with ``allow_unknown``); the
  robot's own cell excepted (where the robot stands is not the plan's choice).
* ``plugin-ends``: the first pose is at the robot's position and the last at the goal's (at the
  point the tolerance search chose, when it ran).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Callable, Optional

import numpy as np

from ..maps.regions import reaches, regions
from ..spec.costs import add_border
from ..nav2.params import PlannerParams
from ..nav2.plugin import (Costmap, Pose, PluginRun, costmap_world_to_map, plugin_world_to_map, rounded_cells,
                     tolerance_steps)

INSCRIBED = 253
UNKNOWN = 255
NOT_JUDGED = ("UndefinedBehaviour",)


@dataclass(frozen=True)
class PluginProperty:
    name: str
    statement: str
    judge: Callable[[Costmap, Pose, Pose, PlannerParams, PluginRun], Optional[str]]


def _candidate_cells(cm: Costmap, goal: Pose, params: PlannerParams) -> list:
    """The goal's cell and the cells of the points the tolerance search looks at (NavfnPlanner's
    own worldToMap), those on the map."""
    ok, cell = plugin_world_to_map(cm, goal.x, goal.y)
    out = [cell] if ok else []
    if params.tolerance > 0:
        xs = tolerance_steps(goal.x - params.tolerance, goal.x + params.tolerance, cm.resolution)
        ys = tolerance_steps(goal.y - params.tolerance, goal.y + params.tolerance, cm.resolution)
        cols = rounded_cells(xs, cm.origin_x, cm.resolution, cm.size_x)
        rows = rounded_cells(ys, cm.origin_y, cm.resolution, cm.size_y)
        out += [(int(c), int(r)) for r in rows if r >= 0 for c in cols if c >= 0]
    return out


def plan_when_reachable(cm, start, goal, params, run: PluginRun) -> Optional[str]:
    if run.error in NOT_JUDGED or run.costs is None or run.robot_cell is None:
        return None  # undefined behaviour, or no NavFn run (poses off the map, equal poses)
    if run.poses:
        return None
    labels = regions(add_border(run.costs))
    for cell in _candidate_cells(cm, goal, params):
        if reaches(labels, cell, run.robot_cell):
            return (f"cell {cell} is reachable from the robot's cell {run.robot_cell}, but no plan "
                    f"({run.error or 'empty path'}: {run.message or ', '.join(run.log) or 'no message'})")
    return None


def poses_in_passable_cells(cm, start, goal, params, run: PluginRun) -> Optional[str]:
    if run.error in NOT_JUDGED:
        return None
    robot = costmap_world_to_map(cm, start.x, start.y)  # where the robot stands is not the plan's choice
    for i, p in enumerate(run.poses):
        cell = costmap_world_to_map(cm, p.x, p.y)
        if cell is None:
            return f"pose {i} ({p.x!r}, {p.y!r}) is off the costmap"
        if cell == robot:
            continue
        cost = int(cm.costs[cell[1], cell[0]])
        if cost >= INSCRIBED and not (cost == UNKNOWN and params.allow_unknown):
            return f"pose {i} ({p.x!r}, {p.y!r}) lies in cell {cell} of cost {cost}"
    return None


def ends_at_robot_and_goal(cm, start, goal, params, run: PluginRun) -> Optional[str]:
    if run.error in NOT_JUDGED or not run.poses:
        return None
    first, last = run.poses[0], run.poses[-1]
    target = run.best_pose if run.best_pose is not None else goal
    if (first.x, first.y) != (start.x, start.y):
        return f"the first pose ({first.x!r}, {first.y!r}) is not the robot's position ({start.x!r}, {start.y!r})"
    if (last.x, last.y) != (target.x, target.y):
        return f"the last pose ({last.x!r}, {last.y!r}) is not the goal's position ({target.x!r}, {target.y!r})"
    return None


# plugin-complete with the fix holds for every costmap size by induction, under its predicates'
# run-time conditions (the descent within max_cycles points among them): the plugin's NavFn run
# is NavFn's on the costs setCostmap makes (COST_NEUTRAL..COST_OBS-1 for passable cells: the
# range the predicates assume), from the robot's cell to each candidate cell
FIXED_PLUGIN_INDUCTION = {
    "plugin-complete": {
        "predicates": ("ConnectedStartReached", "DescentPath"),
        "trusted": (
            "the plugin propagates from the robot's cell (NavfnPlanner::worldToMap, frame cells included: "
            "initCost ignores the cell's cost) with the fixed calcNavFn*, so a candidate cell joined to it by "
            "passable cells gets a finite potential (ConnectedStartReached, when no push is dropped)",
            "the goal is used when its potential is finite, else the tolerance search takes a candidate with a "
            "finite potential when there is one (makePlan's loop, `potential < POT_HIGH`)",
            "getPlanFromPotential runs the fixed calcPath from that point's cell, which returns a path from a "
            "finite potential (DescentPath); a path of at least one point gives poses",
        ),
    },
}


def induction_known(name: str) -> Optional[dict]:
    """The every-size status of a property of the fixed plugin, from what is known of its
    predicates (no solver runs: the declared verdicts, splits and bound cache), with the steps
    it trusts; None for a property no induction carries."""
    if name not in FIXED_PLUGIN_INDUCTION:
        return None
    from ..proofs import PREDICATES
    from ..smt.chains import combined, declared_verdicts, derive, qualified
    from .runner import chain_conditions
    from ..smt.obligation import load_obligations
    from ..smt.runner import default_proof_files
    from ..smt.split import load_splits

    files = default_proof_files()
    verdict_of = declared_verdicts(load_obligations(files), load_splits(files), PREDICATES)
    carriers = FIXED_PLUGIN_INDUCTION[name]["predicates"]
    derived = {p.name: derive(p, "fp32", verdict_of, PREDICATES) for p in PREDICATES if p.name in carriers}
    whole = combined(list(derived.values()))
    trusted = list(FIXED_PLUGIN_INDUCTION[name]["trusted"])
    return {"status": qualified(whole["rank"], len(whole["trusted"]) + len(trusted), whole["conditions"]),
            "predicates": {n: d["status"] for n, d in derived.items()},
            "trusted": whole["trusted"] + trusted,
            "conditions": chain_conditions(carriers, "fp32")}


PLUGIN_PROPERTIES = {p.name: p for p in (
    PluginProperty("plugin-complete", "a plan is returned whenever the goal, or a point the tolerance search "
                   "admits, is reachable from the robot through cells NavFn treats as passable",
                   plan_when_reachable),
    PluginProperty("plugin-poses-passable", "every published pose lies in a costmap cell (Costmap2D::worldToMap) "
                   "of cost below 253 (inscribed), unknown only with allow_unknown; the robot's own cell excepted",
                   poses_in_passable_cells),
    PluginProperty("plugin-ends", "the first pose is at the robot's position, the last at the goal's (or at the "
                   "point the tolerance search chose)", ends_at_robot_and_goal),
)}


# ----------------------------------------------------------------------------- the enumeration
def layouts(w: int, h: int, values) -> list[np.ndarray]:
    """Every costmap of ``w`` x ``h`` cells whose interior cells take each of ``values`` and whose
    border cells (NavFn's lethal frame) are free, in lexicographic order."""
    import itertools

    inner = [(x, y) for y in range(1, h - 1) for x in range(1, w - 1)]
    out = []
    for vals in itertools.product(values, repeat=len(inner)):
        c = np.zeros((h, w), np.uint8)
        for (x, y), v in zip(inner, vals):
            c[y, x] = v
        out.append(c)
    return out


def centre(cm: Costmap, x: int, y: int) -> Pose:
    """The world position of a cell's centre."""
    return Pose(cm.origin_x + (x + 0.5) * cm.resolution, cm.origin_y + (y + 0.5) * cm.resolution)


@dataclass
class PropertyCount:
    """One property for one planner over an enumeration (``variant``: its fix's name): cases judged,
    failures, the first failure."""

    property: str
    variant: str
    judged: int = 0
    failed: int = 0
    first: Optional[dict] = None


def sampled_layouts(w: int, h: int, values, count: int, seed: int) -> list[np.ndarray]:
    """``count`` costmaps of ``w`` x ``h`` cells, each interior cell drawn uniformly from ``values``
    (``numpy.random.default_rng([seed, w, h])``), the frame free."""
    rng = np.random.default_rng([seed, w, h])
    out = []
    for _ in range(count):
        c = np.zeros((h, w), np.uint8)
        c[1:h - 1, 1:w - 1] = rng.choice(np.asarray(values, np.uint8), (h - 2, w - 2))
        out.append(c)
    return out


def check_plugin(names, sizes, values, fixes, tolerances, distro: str = "rolling", backend: str = "jit",
                 progress: Optional[Callable[[str, int, int], None]] = None, sample: int = 0,
                 seed: int = 0) -> list[PropertyCount]:
    """Every costmap of :func:`layouts` for each size of ``sizes`` (smallest first), or ``sample``
    random ones (:func:`sampled_layouts`), every robot and goal at distinct interior cell
    centres, both modes, each tolerance, each fix of ``fixes`` (:class:`~navfn_smt.spec.planner.Fix`
    values): each property judged on the plugin
    model's run.  The first failure of a property is the one of the smallest size, then the
    first layout in lexicographic (or drawing) order."""
    from dataclasses import replace

    from ..nav2.plugin import create_plan

    counts = {(n, f): PropertyCount(n, f.name) for n in names for f in fixes}
    for w, h in sizes:
        maps = sampled_layouts(w, h, values, sample, seed) if sample else layouts(w, h, values)
        for i, costs in enumerate(maps):
            cm = Costmap(costs, 0.0, 0.0, 1.0)
            cells = [(x, y) for y in range(1, h - 1) for x in range(1, w - 1)]
            for astar in (False, True):
                for tol in tolerances:
                    for fix in fixes:
                        params = replace(PlannerParams(), use_astar=astar, tolerance=tol, distro=distro, fix=fix)
                        for r in cells:
                            for g in cells:
                                if r == g:
                                    continue
                                start, goal = centre(cm, *r), centre(cm, *g)
                                run = create_plan(cm, start, goal, params, backend)
                                for n in names:
                                    c = counts[(n, fix)]
                                    why = PLUGIN_PROPERTIES[n].judge(cm, start, goal, params, run)
                                    c.judged += 1
                                    if why is not None:
                                        c.failed += 1
                                        if c.first is None:
                                            c.first = {"size": [w, h], "costs": costs.tolist(), "robot": list(r),
                                                       "goal": list(g), "mode": "astar" if astar else "dijkstra",
                                                       "tolerance": tol, "reason": why}
            if progress:
                progress(f"{w}x{h}", i + 1, len(maps))
    return list(counts.values())
