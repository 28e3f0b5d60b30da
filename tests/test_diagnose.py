"""navfn-smt diagnose: the two reproductions (the U map of Nav2 PR #6308, the #4655 cycle),
hand-derived classifications on small maps, the unbudgeted calcPath against the spec, the command."""

import json
from pathlib import Path

import numpy as np
import pytest

from navfn_smt.cli import main
from navfn_smt.diagnose.core import diagnose, with_params
from navfn_smt.diagnose.inputs import load_inputs, parse_goals
from navfn_smt.diagnose.walk import walk_extraction
from navfn_smt.errors import NavfnInputError
from navfn_smt.nav2.params import PlannerParams
from navfn_smt.nav2.plugin import LEGAL_BUT_NO_PLAN, Costmap, Pose, create_plan

DATA = Path(__file__).parent / "data" / "diagnose"
U_MAP = DATA / "u_map" / "u_map.yaml"
U_START, U_GOAL = Pose.from_yaw(1.525, 17.575), Pose.from_yaw(22.825, 17.575)
LNP = DATA / "legal_no_plan"
LNP_START, LNP_GOAL = Pose.from_yaw(3.9125, 2.2125), Pose.from_yaw(1.5125, 0.7625)


def u_map_image() -> np.ndarray:
    """The recipe of u_map.pgm: a U corridor 40 cells wide in a 486x377 map, walls black, an
    8-cell unknown (grey 128) band along every wall, the corridor's middle free (254)."""
    W, H, band, arm = 486, 377, 8, 40
    img = np.zeros((H, W), np.uint8)
    L0, R1, top, B1 = 10, W - 10, 10, H - 10
    B0 = B1 - arm
    rects = ((L0, L0 + arm, top, B1), (L0, R1, B0, B1), (R1 - arm, R1, top, B1))
    for x0, x1, y0, y1 in rects:
        img[y0:y1, x0:x1] = 128
    for x0, x1, y0, y1 in rects:
        img[y0 + band:y1 - band, x0 + band:x1 - band] = 254
    return img


@pytest.fixture(scope="module")
def u_setup():
    return load_inputs(U_MAP)


@pytest.fixture(scope="module")
def u_diag(u_setup):
    return diagnose(u_setup.costmap, U_START, U_GOAL, u_setup.params)


def test_u_map_is_its_recipe():
    raw = (DATA / "u_map" / "u_map.pgm").read_bytes()
    head = b"P5\n486 377\n255\n"
    assert raw.startswith(head)
    assert np.array_equal(np.frombuffer(raw[len(head):], np.uint8).reshape(377, 486), u_map_image())


@pytest.mark.fast
def test_u_map_fails_with_factor_4_and_diagnose_finds_5(u_setup, u_diag):
    d = u_diag
    assert u_setup.params.max_cycles_factor == 4 and u_setup.costmap.size_x == 486
    assert not d.ok and d.run.error == "NoValidPathCouldBeFound"
    assert LEGAL_BUT_NO_PLAN in d.run.log
    assert d.cause == "extraction_exhausted" and d.stage == "extraction"
    assert d.run.extraction.value == "exhausted" and d.run.max_cycles == 1944
    f = d.fix
    assert f.path_length == 2056 and f.factor == 5 == -(-2056 // 486)
    assert f.verified_with is True and f.verified_one_less is True
    # the plugin itself: plans with 5, fails with 4
    ok = create_plan(u_setup.costmap, U_START, U_GOAL, with_params(u_setup.params, max_cycles_factor=5))
    bad = create_plan(u_setup.costmap, U_START, U_GOAL, with_params(u_setup.params, max_cycles_factor=4))
    assert ok.ok and len(ok.path) == 2056
    assert not bad.ok and bad.legal_potential_no_plan
    # what-ifs: A* and allow_unknown=false shorten the path enough, tolerance does not
    w = {x.change: x.ok for x in d.what_ifs}
    assert w == {"use_astar=true": True, "tolerance=0": False, "tolerance=1": False, "allow_unknown=false": True}


@pytest.mark.fast
def test_legal_potential_no_plan_is_a_cycle_no_factor_fixes():
    s = load_inputs(LNP / "map.yaml", LNP / "nav2_params.yaml")
    assert s.params.use_astar and s.layers == ["static_layer (static)"]
    run = create_plan(s.costmap, LNP_START, LNP_GOAL, s.params)
    assert run.log == [LEGAL_BUT_NO_PLAN] and run.error == "NoValidPathCouldBeFound"
    assert run.goal_potential < 1e10 and run.extraction.value == "exhausted"
    d = diagnose(s.costmap, LNP_START, LNP_GOAL, s.params)
    assert d.cause == "extraction_cycle"
    assert (d.walk.cycle_start, d.walk.cycle_period) == (51, 19)
    assert d.fix.factor is None and "repeats" in d.fix.reason
    # the state repeats: any budget exhausts, e.g. 1000 * max side
    assert not create_plan(s.costmap, LNP_START, LNP_GOAL, with_params(s.params, max_cycles_factor=1000)).ok
    assert {x.change: x.ok for x in d.what_ifs}["use_astar=true" if not s.params.use_astar else "use_astar=false"]


# ------------------------------------------------------------------ hand-derived classifications
def _open(n=12, res=1.0):
    c = np.zeros((n, n), np.uint8)
    return Costmap(c, 0.0, 0.0, res)


def _at(x, y):  # a pose in cell (x, y) for both worldToMaps (truncating and rounding) at resolution 1
    return Pose.from_yaw(x + 0.25, y + 0.25)


def test_start_outside_below_origin():
    d = diagnose(_open(), Pose.from_yaw(-0.5, 3.0), _at(5, 5), what_ifs=False)
    assert (d.ok, d.cause, d.stage, d.run.error) == (False, "start_outside_map", "bounds", "StartOutsideMapBounds")
    assert "x -0.5 < origin x 0" in d.summary


def test_goal_outside_beyond_size():
    d = diagnose(_open(), _at(2, 2), Pose.from_yaw(5.0, 12.0), what_ifs=False)
    assert (d.cause, d.run.error) == ("goal_outside_map", "GoalOutsideMapBounds")
    assert "y 12 >= 12" in d.summary


def test_goal_occupied_only_with_tolerance_0():
    cm = _open()
    cm.costs[5, 5] = 254
    d = diagnose(cm, _at(2, 2), _at(5, 5), PlannerParams(tolerance=0.0))
    assert (d.cause, d.failing_cell, d.run.error) == ("goal_occupied", (5, 5), "GoalOccupied")
    # tolerance 0.5 lets the search plan to a neighbour; the what-if says so
    assert {x.change: x.ok for x in d.what_ifs}["tolerance=0.5"]


def test_not_connected_with_the_wall_as_cut():
    cm = _open()
    cm.costs[:, 6] = 254  # a wall one cell thick at x = 6 splits the map
    d = diagnose(cm, _at(2, 5), _at(9, 5), PlannerParams(tolerance=0.0), what_ifs=False)
    assert d.cause == "not_connected" and d.run.best_pose is None
    c = d.connectivity
    assert not c.connected and len(c.cut) == 1 and c.cut[0][0] == 6  # clearing one wall cell joins them
    # the regions: the interior is 10x10 (the frame is lethal); x 1..5 and x 7..10
    assert (c.robot_region_cells, c.goal_region_cells) == (50, 40)


def test_propagation_cycle_limit_on_a_serpentine():
    # 9x9: the cycle limit is max(81 // 20, 9 + 9) = 18; the goal lies 30 corridor cells from the
    # robot, 4-connected: propagation stops before it, and lifting the limit (not the buffers) reaches it
    c = np.full((9, 9), 254, np.uint8)
    c[1, 1:8] = 0
    c[1:4, 7] = 0
    c[3, 1:8] = 0
    c[3:6, 1] = 0
    c[5, 1:8] = 0
    c[5:8, 7] = 0
    c[7, 1:8] = 0
    d = diagnose(Costmap(c, 0.0, 0.0, 1.0), _at(1, 1), _at(1, 7), what_ifs=False)
    assert d.cause == "propagation_cycle_limit" and d.stage == "propagation"
    assert (d.run.cycles, d.run.cycle_limit, d.run.dropped) == (18, 18, 0)
    assert d.connectivity.connected
    assert d.propagation_check == {"cycles_lifted": True, "buffers_lifted": False, "both_lifted": True}


@pytest.mark.fast
def test_extraction_exhausted_on_a_small_u():
    # 60x60 U corridor 6 cells wide: the path (219 points) is longer than 60 * factor 1
    n = 60
    c = np.full((n, n), 254, np.uint8)
    c[2:n - 2, 2:8] = 0
    c[2:8, 2:n - 2] = 0
    c[2:n - 2, n - 8:n - 2] = 0
    cm = Costmap(c, 0.0, 0.0, 1.0)
    d = diagnose(cm, _at(5, n - 4), _at(n - 5, n - 4), PlannerParams(max_cycles_factor=1), what_ifs=False)
    assert d.cause == "extraction_exhausted" and d.run.max_cycles == 60
    assert d.fix.path_length == 219 and d.fix.factor == 4 == -(-219 // 60)
    assert d.fix.verified_with and d.fix.verified_one_less
    assert len(create_plan(cm, _at(5, n - 4), _at(n - 5, n - 4), PlannerParams(max_cycles_factor=4)).path) == 219


# ------------------------------------------------------------------ the unbudgeted calcPath
@pytest.mark.fast
@pytest.mark.parametrize("name", ["incomplete-dijkstra-5x6", "oscillation-astar-6x5", "unreached-astar-7x8",
                                  "cost-dijkstra-7x7", "int-conversion-astar-4x3"])
def test_walk_equals_spec_calc_path(name):
    from navfn_smt.maps.suite import load_map
    from navfn_smt.spec.extraction import calc_path
    from navfn_smt.spec.planner import plan

    m = load_map(Path(__file__).parent / "data" / "counterexamples" / name)
    sx, sy, gx, gy = (int(v) for v in m.cases[0])
    for astar in (True, False):
        r = plan(m.costs, (sx, sy), (gx, gy), astar=astar, record_trace=False)
        w = walk_extraction(r.potential, (sx, sy), (gx, gy))
        ny, nx = r.potential.shape
        flat = [float(v) for v in r.potential.ravel()]
        n = w.iterations
        e = calc_path(flat, nx, ny, (sx, sy), (gx, gy), n)
        assert e.exit.value == w.exit and e.points_written == len(w.points)
        if w.exit == "near_goal":
            assert np.array_equal(np.array(e.path, np.float32), w.points)
            assert calc_path(flat, nx, ny, (sx, sy), (gx, gy), n - 1).exit.value == "exhausted"


@pytest.mark.fast
def test_walk_cycle_on_a_two_cell_bowl():
    # a potential where grid-following and the gradient send the path back and forth forever
    s = load_inputs(LNP / "map.yaml", LNP / "nav2_params.yaml")
    run = create_plan(s.costmap, LNP_START, LNP_GOAL, s.params)
    w = walk_extraction(run.potential, run.best_cell, run.robot_cell)
    assert w.exit == "cycle"
    p = w.points
    # the repeated stretch: points cycle_start.. equal the points one period later
    a, k = w.cycle_start, w.cycle_period
    assert np.array_equal(p[a:a + 1], p[a + k:a + k + 1]) or len(p) == a + k


# ------------------------------------------------------------------ inputs and the command
def test_parse_goals_formats(tmp_path):
    t = tmp_path / "g.txt"
    t.write_text("# goals\n1 2\n3 4 1.57\n")
    y = tmp_path / "g.yaml"
    y.write_text("- [1, 2]\n- {x: 3, y: 4, yaw: 1.57}\n")
    j = tmp_path / "g.json"
    j.write_text("[[1, 2], [3, 4, 1.57]]")
    for f in (t, y, j):
        g = parse_goals(f)
        assert [(p.x, p.y) for p in g] == [(1.0, 2.0), (3.0, 4.0)] and g[1].qz != 0
    bad = tmp_path / "b.txt"
    bad.write_text("1 two\n")
    with pytest.raises(NavfnInputError, match="b.txt:1"):
        parse_goals(bad)


def test_cli_exit_codes_and_json(tmp_path, capsys):
    lnp = ["diagnose", str(LNP / "map.yaml"), "--params", str(LNP / "nav2_params.yaml"), "--start", "3.9125", "2.2125"]
    out = tmp_path / "r.json"
    pic = tmp_path / "r.png"
    assert main(lnp + ["--goal", "1.5125", "0.7625", "--json", str(out), "--picture", str(pic)]) == 1
    doc = json.loads(out.read_text())
    r = doc["results"][0]
    assert r["cause"] == "extraction_cycle" and r["legal_potential_no_plan"] and r["fix"]["max_cycles_factor"] is None
    assert r["extraction"]["unbudgeted"]["cycle_period"] == 19 and doc["params"]["use_astar"] is True
    assert pic.stat().st_size > 10000
    assert "Nav2 issue #4655" in capsys.readouterr().out
    # a goal that plans: exit 0
    assert main(lnp + ["--goal", "4.0", "3.0", "--no-what-ifs"]) == 0
    # batch: one JSON for all, exit 1 when any fails
    goals = tmp_path / "goals.txt"
    goals.write_text("1.5125 0.7625\n4.0 3.0\n")
    assert main(lnp + ["--goals", str(goals), "--json", str(out), "--no-what-ifs", "--quiet",
                       "--picture", str(pic)]) == 1
    doc = json.loads(out.read_text())
    assert doc["summary"]["plans"] == 2 and doc["summary"]["ok"] == 1 and doc["summary"]["legal_potential_no_plan"] == 1


@pytest.mark.fast
def test_cli_bad_input_exits_2(tmp_path, capsys):
    m = str(LNP / "map.yaml")
    cases = [
        [m, "--start", "1", "1", "--goal", "2", "2", "--json", str(tmp_path / "no" / "r.json")],
        [m, "--start", "1", "1", "--goal", "2", "2", "--picture", str(tmp_path / "r.gif")],
        [m, "--start", "1", "1"],
        [m, "--start", "1", "1", "--goal", "2"],
        [m, "--start", "1", "1", "--goal", "2", "2", "--params", str(tmp_path / "missing.yaml")],
        [str(tmp_path / "nomap.yaml"), "--start", "1", "1", "--goal", "2", "2"],
    ]
    for c in cases:
        assert main(["diagnose", *c]) == 2, c
        err = capsys.readouterr().err
        assert err.startswith("navfn-smt: error: ") and err.count("\n") == 1 and "Traceback" not in err


def test_cli_sweep(tmp_path):
    out = tmp_path / "s.json"
    rc = main(["diagnose", str(LNP / "map.yaml"), "--params", str(LNP / "nav2_params.yaml"), "--start", "3.9125",
               "2.2125", "--sweep", "300", "--json", str(out)])
    doc = json.loads(out.read_text())
    assert doc["goals"] == 300 and rc == (0 if doc["issue_4655"] == 0 and doc["outcomes"]["ok"] == 300 else 1)
