"""The whole-map sweep is create_plan run per goal, bit for bit (NavFn path float32 points,
calcPath exits, errors, tolerance, the cell extracted from, the propagation's cycles)."""

import json

import numpy as np
import pytest

from navfn_smt.diagnose.sweep import (EXIT_NAMES, OUTCOMES, goal_pose, outcome_of_run, rooms_costmap,
                                      select_goals, summary, sweep)
from navfn_smt.nav2.mapserver import load_map_yaml
from navfn_smt.nav2.params import PlannerParams
from navfn_smt.nav2.plugin import Costmap, Pose, costmap_from_map, create_plan, plugin_world_to_map
from navfn_smt.spec.propagation import cycle_limit

from conftest import REPO

ROOM = REPO / "src/navfn_smt/examples/mapserver/room.yaml"


def expected(cm, start, params, cell):
    run = create_plan(cm, start, goal_pose(cm, cell), params)
    path = run.path if run.ok and run.path is not None else np.zeros((0, 2), np.float32)
    return {
        "outcome": outcome_of_run(run),
        "exit": -1 if run.extraction is None else EXIT_NAMES.index(run.extraction.name),
        "used_tolerance": bool(run.used_tolerance),
        "best_cell": tuple(run.best_cell) if run.best_cell is not None and run.extraction is not None else (-1, -1),
        "cycles": run.cycles if run.potential is not None else -1,
        "path": path.astype(np.float32).tobytes(),
    }


def got(res, k):
    return {
        "outcome": res.outcome_name(k),
        "exit": int(res.exit[k]),
        "used_tolerance": bool(res.used_tolerance[k]),
        "best_cell": tuple(int(v) for v in res.best_cell[k]),
        "cycles": int(res.cycles[k]),
        "path": res.path(k).astype(np.float32).tobytes(),
    }


def assert_equal_per_goal(cm, start, params, goals=None, seed=0):
    res = sweep(cm, start, params, goals=goals, seed=seed, keep_paths=True)
    assert len(res) > 0
    bad = []
    for k, cell in enumerate(res.cells.tolist()):
        e, g = expected(cm, start, params, cell), got(res, k)
        if e != g:
            bad.append((cell, {key: (e[key], g[key]) for key in e if e[key] != g[key] and key != "path"},
                        e["path"] != g["path"]))
    assert not bad, f"{len(bad)} of {len(res)} goals differ, first: {bad[:3]}"
    return res


def small_map(seed, nx=17, ny=14):
    rng = np.random.default_rng(seed)
    c = np.zeros((ny, nx), np.uint8)
    c[rng.random(c.shape) < 0.1] = rng.integers(1, 253)
    c[rng.random(c.shape) < 0.2] = 254
    c[rng.random(c.shape) < 0.06] = 255
    c[rng.random(c.shape) < 0.04] = 253
    return Costmap(c, -1.0, 2.0, float(np.float32(0.05)))


def pose_in_cell(cm, x, y, fx=0.3, fy=0.2):
    return Pose(cm.origin_x + (x + fx) * cm.resolution, cm.origin_y + (y + fy) * cm.resolution)


@pytest.mark.parametrize("astar", [False, True])
@pytest.mark.parametrize("tolerance", [0.5, 0.0, 0.12])
def test_small_maps_every_cell(astar, tolerance):
    for seed in range(3):
        cm = small_map(seed)
        start = pose_in_cell(cm, 5 + seed, 6)
        assert_equal_per_goal(cm, start, PlannerParams(use_astar=astar, tolerance=tolerance,
                                                       allow_unknown=seed != 1), goals="all")


@pytest.mark.parametrize("astar", [False, True])
def test_room_map(astar):
    cm = costmap_from_map(load_map_yaml(ROOM))
    start = pose_in_cell(cm, 8, 9, 0.6, 0.45)
    res = assert_equal_per_goal(cm, start, PlannerParams(use_astar=astar), goals=None if not astar else 400, seed=3)
    assert res.counts()["ok"] > 0


def maze_costmap():
    """A serpentine corridor on a 23x23 map: its far end needs more cycles than the limit."""
    c = np.full((23, 23), 254, np.uint8)
    for y in range(1, 22, 2):
        c[y, 1:22] = 0
    for i, y in enumerate(range(2, 21, 2)):
        c[y, 21 if i % 2 == 0 else 1] = 0
    return Costmap(c, 0.0, 0.0, 0.1)


@pytest.mark.parametrize("astar", [False, True])
def test_cycle_limited(astar):
    cm = maze_costmap()
    start = pose_in_cell(cm, 2, 1)
    res = assert_equal_per_goal(cm, start, PlannerParams(use_astar=astar), goals=None)
    limit = cycle_limit(23, 23)
    assert (res.cycles == limit).any()  # the limit stopped propagation before some goals
    assert res.counts()["no_legal"] > 0


@pytest.mark.parametrize("astar", [False, True])
def test_legal_potential_no_plan(astar):
    """#4655's outcome: a legal potential, and calcPath runs out of its max_cycles budget."""
    cm = maze_costmap()
    start = pose_in_cell(cm, 2, 1)
    res = assert_equal_per_goal(cm, start, PlannerParams(use_astar=astar, max_cycles_factor=1), goals=None)
    assert res.counts()["legal_no_plan"] > 0
    assert summary(res)["issue_4655"] == res.counts()["legal_no_plan"]


def test_same_pose_and_occupied_goal():
    cm = small_map(4)
    start = goal_pose(cm, (6, 7))  # the robot exactly on the pose of its cell's goal
    for astar in (False, True):
        res = assert_equal_per_goal(cm, start, PlannerParams(use_astar=astar, tolerance=0.0), goals="all")
        c = res.counts()
        assert c["same_pose"] == 1 and c["goal_occupied"] > 0


def test_robot_rounding_off_the_map_is_planned_alone():
    cm = small_map(5, 9, 8)
    start = Pose(cm.origin_x + 8.7 * cm.resolution, cm.origin_y + 3.2 * cm.resolution)  # rounds to x = 9
    assert not plugin_world_to_map(cm, start.x, start.y)[0]
    res = assert_equal_per_goal(cm, start, PlannerParams(), goals="all")
    assert res.fallback == len(res) - res.counts()["same_pose"] - res.counts()["goal_occupied"]


def test_start_outside():
    cm = small_map(0)
    res = sweep(cm, Pose(cm.origin_x - 1.0, cm.origin_y), PlannerParams(), goals=5)
    assert res.counts()["start_outside"] == 5
    run = create_plan(cm, Pose(cm.origin_x - 1.0, cm.origin_y), goal_pose(cm, res.cells[0]), PlannerParams())
    assert outcome_of_run(run) == "start_outside"


@pytest.mark.fast
@pytest.mark.parametrize("origin,res", [(-10.0, 0.05), (-51.224998, float(np.float32(0.05))),
                                        (3.3, float(np.float32(0.1))), (-2.0, 0.025)])
def test_goal_pose_rounds_back_to_its_cell(origin, res):
    n = 2000
    cm = Costmap(np.zeros((3, n), np.uint8), origin, origin, res)
    back = [plugin_world_to_map(cm, goal_pose(cm, (i, 0)).x, origin)[1][0] for i in range(n)]
    assert back == list(range(n))
    # the costmap's cell centre is on the rounding boundary: it rounds to the next cell
    centre = [plugin_world_to_map(cm, origin + (i + 0.5) * res, origin)[1][0] for i in range(n)]
    assert np.mean(np.array(centre) == np.arange(n) + 1) > 0.4


def test_goal_selection():
    cm = small_map(0)
    free = select_goals(cm)
    assert (cm.costs[free[:, 1], free[:, 0]] < 253).all()
    assert len(select_goals(cm, "all")) == cm.costs.size
    s = select_goals(cm, 10, seed=2)
    assert len(s) == 10 and np.array_equal(s, select_goals(cm, 10, seed=2))
    assert len(select_goals(cm, [[1, 1], [1, 1], [2, 3]])) == 2


def test_picture_and_summary(tmp_path):
    from navfn_smt.report.sweep import render_sweep, write_summary_json

    cm = rooms_costmap(60, seed=1, room=20)
    start = pose_in_cell(cm, 10, 10)
    seen = []
    res = sweep(cm, start, PlannerParams(), progress=lambda d, t: seen.append((d, t)))
    assert seen[-1] == (len(res), len(res))
    render_sweep(res, cm.costs, (cm.origin_x, cm.origin_y), tmp_path / "s.png")
    assert (tmp_path / "s.png").stat().st_size > 10000
    write_summary_json(tmp_path / "s.json", summary(res))
    doc = json.loads((tmp_path / "s.json").read_text())
    assert sum(doc["outcomes"].values()) == len(res) and set(doc["outcomes"]) == set(OUTCOMES)


def test_plugin_goal_in_first_column():
    """Nav2's calcNavFn* only propagate: NavFn's start in the first column (where calcPath from it
    would read before the array) is never extracted from; the tolerance search moves the goal."""
    cm = small_map(0)
    start = pose_in_cell(cm, 5, 6)
    run = create_plan(cm, start, goal_pose(cm, (0, 1)), PlannerParams())
    assert run.error != "UndefinedBehaviour"


def test_bench_sweep_command(tmp_path, capsys):
    from navfn_smt.cli import main

    out = tmp_path / "b.json"
    assert main(["bench", "--sweep", "40", "--sweep-astar-goals", "5", "--json", str(out)]) == 0
    rows = json.loads(out.read_text())["sweep"]
    assert [r["mode"] for r in rows] == ["astar", "dijkstra"]
    assert rows[0]["goals"] == 5 and rows[1]["goals"] > 100 and all(r["goals_per_second"] > 0 for r in rows)
    assert "goals/s" in capsys.readouterr().out
    assert main(["bench", "--sweep", "10"]) == 2


@pytest.mark.parametrize("distro", ["humble", "jazzy"])
def test_every_distributions_plugin_swept(distro):
    """Humble's plugin checks nothing before makePlan: its lethal goals with tolerance 0 and its
    equal-position goal are planned by create_plan itself; the sweep still equals it per goal."""
    cm = small_map(4)
    start = goal_pose(cm, (6, 7))
    for astar in (False, True):
        params = PlannerParams(use_astar=astar, tolerance=0.0, max_cycles_factor=1, distro=distro)
        c = assert_equal_per_goal(cm, start, params, goals="all").counts()
        assert (c["goal_occupied"] > 0) == (distro != "humble") and c["no_legal"] > 0
    off = sweep(cm, Pose(cm.origin_x - 1.0, cm.origin_y), PlannerParams(distro=distro), goals=5)
    assert off.counts()["start_outside"] == 5
