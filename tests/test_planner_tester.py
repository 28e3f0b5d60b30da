"""The NavFn checks of Nav2's planning system tests (nav2_system_tests/src/planning) carried over
to the plugin (``navfn-smt planner-tester``): the checks themselves against answers that are
wrong, the model as shipped and fixed, and the C++ plugin of every distribution against it."""

import json
import math

import numpy as np
import pytest

from navfn_smt.bench import serpentine
from navfn_smt.cli import main
from navfn_smt.nav2 import planner_tester as T
from navfn_smt.spec import fixes
from navfn_smt.nav2.params import PlannerParams
from navfn_smt.nav2.plugin import Pose, quaternion_from_yaw
from navfn_smt.spec.constants import COST_OBS

from conftest import DISTROS

START, GOAL = Pose.from_yaw(0.5, 0.5, math.pi / 2), Pose.from_yaw(0.5, 1.0, -math.pi)


def _answer(*xy_yaw, error=None):
    return T.Answer(error, np.array([[x, y, *quaternion_from_yaw(yaw)] for x, y, yaw in xy_yaw]).reshape(-1, 6))


def test_the_plugin_case_checks_refuse_wrong_headings_and_missing_paths():
    assert T.plugin_case_checks(_answer((0.5, 0.5, 0.0), (0.5, 1.0, -math.pi)), START, GOAL, False) == ""
    assert "goal's heading" in T.plugin_case_checks(_answer((0.5, 0.5, 0.0), (0.5, 1.0, 0.0)), START, GOAL, False)
    # with use_final_approach_orientation: the heading from the first pose to the last (+y here)
    assert T.plugin_case_checks(_answer((0.5, 0.5, 0.0), (0.5, 1.0, math.pi / 2)), START, GOAL, True) == ""
    assert "first pose to the last" in T.plugin_case_checks(_answer((0.5, 0.5, 0.0), (0.5, 1.0, 0.02 + math.pi / 2)),
                                                            START, GOAL, True)
    assert "start's heading" in T.plugin_case_checks(_answer((0.5, 0.5, 0.0)), START, GOAL, True)
    assert T.plugin_case_checks(_answer(error="NoValidPathCouldBeFound"), START, GOAL, False).startswith("createPlan threw")
    assert T.plugin_case_checks(_answer(), START, GOAL, False) == "no pose"


def test_the_random_pair_checks_refuse_collisions_and_wrong_ends():
    costs = np.zeros((5, 5), dtype=np.uint8)
    costs[2, 2] = 254
    cm = T.Costmap(costs, 0.0, 0.0, 1.0)
    s, g = Pose(1.0, 1.0), Pose(3.0, 3.0)
    assert T.random_pair_checks(cm, _answer((1, 1, 0), (1.4, 2.4, 0), (3, 3, 0)), s, g) == ""
    assert "collision at (2.40, 1.60)" in T.random_pair_checks(cm, _answer((1, 1, 0), (2.4, 1.6, 0), (3, 3, 0)), s, g)
    assert "not from the start to the goal" in T.random_pair_checks(cm, _answer((1, 1, 0), (3, 3.01, 0)), s, g)
    assert "not from the start" in T.random_pair_checks(cm, _answer((1.0000001, 1, 0), (3, 3, 0)), s, g)
    assert T.random_pair_checks(cm, _answer(error="GoalOccupied"), s, g) == "createPlan threw GoalOccupied"


def test_the_tester_reads_a_map_as_planner_tester_does_and_draws_free_cells():
    occ = np.array([[0, 100, -1], [99, 0, 101], [0, 0, 0]], dtype=np.int8)
    cm = T.tester_costmap(occ)
    assert cm.costs.tolist() == [[0, 254, 0], [0, 0, 254], [0, 0, 0]] and cm.resolution == 1.0
    pairs = T.draw_end_points(cm, 50, np.random.default_rng(0))
    cells = {(int(p.x), int(p.y)) for pair in pairs for p in pair}
    assert cells <= {(1, 1), (2, 2), (1, 2)} and len(cells) == 3  # 1..size-1 on each axis, free only
    with pytest.raises(ValueError, match="no free cell"):
        T.draw_end_points(T.tester_costmap(np.full((3, 3), 100, dtype=np.int8)), 1, np.random.default_rng(0))


def _serpentine(n):
    return T.tester_costmap(np.where(serpentine(n) == COST_OBS, 100, 0).astype(np.int8))


@pytest.mark.parametrize("distro", ("humble", "rolling"))
def test_the_model_passes_the_plugin_cases_as_shipped_and_fixed(distro):
    for variant in ("original", "fixed"):
        results = T.run_plugin_cases(T.model_planner(fixes.named(variant)), PlannerParams(distro=distro))
        assert len(results) == 10 and [c.why for c in results if not c.ok] == [], (variant, distro)


def test_the_random_test_fails_as_shipped_on_a_serpentine_and_passes_fixed():
    """On a 15x15 serpentine the cycle limit stops A*'s wave short of most goals: the test fails
    as shipped (each of its three draws above 10 %) and passes with the fix."""
    cm = _serpentine(15)
    original = T.run_random_test(T.model_planner(fixes.AS_SHIPPED), cm, 1)
    fixed = T.run_random_test(T.model_planner(fixes.named("fixed")), cm, 1)
    assert len(original) == 3 and not any(r.passed for r in original)
    assert all(r.failed > 10 and "NoValidPathCouldBeFound" in r.failures[0][4] for r in original)
    assert any(r.passed for r in fixed) and fixed[0].failed < original[0].failed


@pytest.mark.parametrize("distro", DISTROS)
def test_the_cpp_plugin_answers_the_system_tests_as_the_model_does(builds, tmp_path, distro, capsys):
    """Every answer of the C++ plugin (as shipped and fixed) equals the model's bit for bit, on the
    plugin cases and the random test of a serpentine; the verdicts are the ones above."""
    folder = builds[distro][1]
    occ = np.where(serpentine(15) == COST_OBS, 100, 0).astype(np.int8)
    _write_map(tmp_path / "serpentine.yaml", occ)
    rc = main(["planner-tester", str(tmp_path / "serpentine.yaml"), "--oracle", str(folder), "--json",
               str(tmp_path / "r.json")])
    doc = json.loads((tmp_path / "r.json").read_text())
    # per variant: the 10 plugin cases, 3 draws of 100 pairs as shipped (each fails), 1 fixed
    assert rc == 0 and doc["differences"] == [] and doc["compared_answers"] == 2 * 10 + 300 + 100
    assert doc["distribution"] == distro
    for who in ("model", "C++"):
        assert all(c["ok"] for v in ("original", "fixed") for c in doc["plugin_cases"][f"{who} {v}"])
        (by,) = doc["random"].values()
        assert not any(r["passed"] for r in by[f"{who} original"]) and by[f"{who} fixed"][-1]["passed"]
    assert "answers the same, poses bit for bit" in capsys.readouterr().out


def _write_map(path, occ):
    """A map_server trinary map of the occupancy ``occ`` (row 0 the bottom)."""
    from PIL import Image

    img = np.where(occ[::-1] >= 100, 0, 254).astype(np.uint8)
    Image.fromarray(img, "L").save(path.with_suffix(".pgm"))
    path.write_text(f"image: {path.with_suffix('.pgm').name}\nresolution: 1.0\norigin: [0.0, 0.0, 0.0]\n"
                    "negate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\n")


def test_planner_tester_refuses_bad_input_clearly(tmp_path, capsys):
    assert main(["planner-tester", str(tmp_path / "none.yaml")]) == 2
    assert main(["planner-tester", "--pairs", "0"]) == 2
    assert main(["planner-tester", "--oracle", str(tmp_path / "nothing")]) == 2
    err = capsys.readouterr().err
    assert "none.yaml: no such map YAML file" in err and "--pairs" in err and "no such build folder" in err
    assert "Traceback" not in err
