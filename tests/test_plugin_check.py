"""plugin-check: the properties a Nav2 user relies on of the planner plugin, judged on the
plugin model as shipped and fixed, on every small costmap."""

from __future__ import annotations

import json
from dataclasses import replace
from pathlib import Path

import numpy as np

from navfn_smt.spec import fixes
from navfn_smt.spec.fix import FIX
from navfn_smt.cli import main
from navfn_smt.diagnose.inputs import load_inputs
from navfn_smt.nav2.params import PlannerParams
from navfn_smt.nav2.plugin import Costmap, Pose, create_plan
from navfn_smt.check.plugin import PLUGIN_PROPERTIES, centre, check_plugin, layouts

LNP = Path(__file__).parent / "data" / "diagnose" / "legal_no_plan"


def judge(name, cm, start, goal, params):
    return PLUGIN_PROPERTIES[name].judge(cm, start, goal, params, create_plan(cm, start, goal, params))


def test_the_layouts_are_every_interior_assignment_with_a_free_frame():
    maps = layouts(4, 4, (0, 254))
    assert len(maps) == 16 and len({m.tobytes() for m in maps}) == 16
    assert all(m[0].sum() == m[-1].sum() == m[:, 0].sum() == m[:, -1].sum() == 0 for m in maps)


def test_a_legal_potential_without_a_plan_fails_plugin_complete_unless_fixed():
    s = load_inputs(LNP / "map.yaml", LNP / "nav2_params.yaml")
    start, goal = Pose.from_yaw(3.9125, 2.2125), Pose.from_yaw(1.5125, 0.7625)
    why = judge("plugin-complete", s.costmap, start, goal, s.params)
    assert why == ("cell (30, 15) is reachable from the robot's cell (78, 44), but no plan (NoValidPathCouldBeFound: "
                   "Failed to create plan with tolerance of: 0.500000)")
    assert judge("plugin-complete", s.costmap, start, goal, replace(s.params, fix=FIX)) is None


def test_the_robot_rounded_into_a_lethal_cell_gives_a_first_pose_in_it():
    """NavfnPlanner::worldToMap rounds where Costmap2D::worldToMap floors: a robot at the centre of
    cell (1, 1) is NavFn's cell (2, 2); clearRobotCell clears that cell, the path starts at its
    corner (2.0, 2.0), which the costmap puts in the lethal cell (2, 2)."""
    c = np.zeros((4, 4), np.uint8)
    c[2, 2] = 254
    cm = Costmap(c, 0.0, 0.0, 1.0)
    params = PlannerParams(tolerance=1.0)
    why = judge("plugin-poses-passable", cm, centre(cm, 1, 1), centre(cm, 2, 1), params)
    assert why == "pose 0 (2.0, 2.0) lies in cell (2, 2) of cost 254"
    assert judge("plugin-poses-passable", cm, centre(cm, 1, 1), centre(cm, 2, 1), replace(params, fix=FIX))
    c[2, 2] = 0  # the same plan on a free cell is fine
    assert judge("plugin-poses-passable", Costmap(c, 0.0, 0.0, 1.0), centre(cm, 1, 1), centre(cm, 2, 1), params) is None
    why = judge("plugin-ends", cm, centre(cm, 1, 1), centre(cm, 2, 1), params)
    assert why.startswith("the first pose (2.0, 2.0) is not the robot's position (1.5, 1.5)")


def test_the_enumeration_counts_and_finds_the_smallest_case_first():
    counts = {(c.property, c.variant): c for c in check_plugin(tuple(PLUGIN_PROPERTIES), [(4, 3), (4, 4)], (0, 254),
                                                               (fixes.AS_SHIPPED, FIX), (0.0, 1.0))}
    # 4x3: 4 layouts x 2 pairs; 4x4: 16 layouts x 12 pairs; x 2 modes x 2 tolerances
    assert all(c.judged == (4 * 2 + 16 * 12) * 4 for c in counts.values())
    assert counts[("plugin-complete", "original")].failed == counts[("plugin-complete", "fixed")].failed == 0
    first = counts[("plugin-poses-passable", "original")].first
    assert first["size"] == [4, 4] and first["robot"] == [1, 1] and first["costs"][2][2] == 254


def test_the_command_reports_and_exits_1_on_a_failure(tmp_path, capsys):
    out = tmp_path / "p.json"
    assert main(["plugin-check", "--max-size", "4", "4", "--quiet", "--json", str(out)]) == 1
    doc = json.loads(out.read_text())
    assert {r["property"] for r in doc["results"]} == set(PLUGIN_PROPERTIES)
    assert "plugin-poses-passable" in capsys.readouterr().out
    assert main(["plugin-check", "plugin-complete", "--max-size", "4", "4", "--quiet"]) == 0
    # with the fix, plugin-complete holds for every size by the two predicates, under their run-time
    # conditions (below Progress's bound, the descent within calcPath's budget, ...), each said
    out = capsys.readouterr().out
    assert ("plugin-complete (fixed): every costmap size by induction, under 6 run-time conditions: conditional "
            "(bounded; potentials below 2^30; the descent fits calcPath's budget;") in out
    assert "; 5 trusted steps) (DescentPath conditional (bounded;" in out  # 2 of the predicates', 3 of the plugin's
    assert "  condition: the descent fits calcPath's budget: " in out
    got = doc["every_size_by_induction_fixed"]["plugin-complete"]
    assert got["status"].startswith("conditional (bounded; ") and len(got["trusted"]) == 5
    assert main(["plugin-check", "--values", "0,300"]) == 2
    assert "costmap values 0..255" in capsys.readouterr().err
    assert main(["plugin-check", "--max-size", "6", "6"]) == 2


def test_sampled_costmaps_are_drawn_from_the_values_and_reproducible():
    from navfn_smt.check.plugin import sampled_layouts

    a = sampled_layouts(6, 5, (0, 100, 254), 20, seed=3)
    b = sampled_layouts(6, 5, (0, 100, 254), 20, seed=3)
    assert [m.tobytes() for m in a] == [m.tobytes() for m in b] and len(a) == 20
    assert set(np.unique(np.concatenate([m[1:-1, 1:-1].ravel() for m in a]))) == {0, 100, 254}
    assert all(m[0].sum() == m[-1].sum() == m[:, 0].sum() == m[:, -1].sum() == 0 for m in a)
    assert main(["plugin-check", "--max-size", "6", "6", "--sample", "-1"]) == 2
