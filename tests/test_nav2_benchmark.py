"""Nav2's planner benchmark (navfn_smt.nav2.benchmark, ``navfn-smt nav2-benchmark``): the pairs
follow the protocol, the metrics are what docs/nav2-benchmark.md says, the fixed NavFn plans
every pair the original plans with the same path, and a model/C++ difference is reported.

Fast: a generated 200x200 map (10 m x 10 m) with a wall cutting off a strip, so some pairs
cannot be planned; the shared benchmark maps only for the drawing, skipped when absent."""

from __future__ import annotations

import json
import math
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest
import yaml

from navfn_smt.cli import main
from navfn_smt.nav2 import benchmark as B
from navfn_smt.nav2.plugin import Costmap, Pose
from navfn_smt.nav2.setup import load_setup

from conftest import REPO, SHARED

PARAMS = REPO / "src" / "navfn_smt" / "examples" / "nav2" / "nav2_params.yaml"
BENCH_MAPS = SHARED / "nav2-benchmark-maps"
WALL = 150  # the wall's column: cells right of it are cut off from the rest
MARGIN = 20


def write_map(folder: Path) -> Path:
    """A 200x200 map_server map of 0.05 m: random square obstacles and a full-height wall."""
    rng = np.random.default_rng(7)
    occ = np.zeros((200, 200), bool)  # row 0 = the grid's bottom row
    for _ in range(40):
        x, y, s = rng.integers(0, 190), rng.integers(0, 190), rng.integers(3, 10)
        occ[y:y + s, x:x + s] = True
    occ[:, WALL:WALL + 2] = True
    img = np.where(occ, 0, 254).astype(np.uint8)[::-1]  # image row 0 is the top
    (folder / "m.pgm").write_bytes(b"P5\n200 200\n255\n" + np.ascontiguousarray(img).tobytes())
    p = folder / "m.yaml"
    p.write_text(yaml.safe_dump({"image": "m.pgm", "resolution": 0.05, "origin": [-1.0, 2.0, 0.0], "negate": 0,
                                 "occupied_thresh": 0.65, "free_thresh": 0.196}))
    return p


@pytest.fixture(scope="module")
def small(tmp_path_factory):
    path = write_map(tmp_path_factory.mktemp("bench"))
    return path, load_setup(path, PARAMS)


@pytest.fixture(scope="module")
def small_run(small):
    _, setup = small
    draw = B.draw_pairs(setup.costmap, 16, margin=MARGIN)
    rows, diffs = B.run_benchmark(setup.costmap, setup.params, draw.pairs)
    return draw, rows, diffs


# ---------------------------------------------------------------------------------- the pairs
def check_protocol(cm: Costmap, pairs, margin: int, n: int) -> None:
    assert len(pairs) == n
    for q in pairs:
        for (col, row), pose in ((q.start_cell, q.start), (q.goal_cell, q.goal)):
            assert margin <= col <= cm.size_x - 1 - margin and margin <= row <= cm.size_y - 1 - margin
            assert cm.costs[row, col] < B.MAX_COST
            assert (pose.x, pose.y) == (cm.origin_x + col * cm.resolution, cm.origin_y + row * cm.resolution)
            assert math.isclose(math.hypot(pose.qz, pose.qw), 1.0) and pose.qx == pose.qy == 0.0
        assert math.hypot(q.goal.x - q.start.x, q.goal.y - q.start.y) > B.MIN_DISTANCE


def test_pairs_follow_the_protocol(small):
    _, setup = small
    cm = setup.costmap
    draw = B.draw_pairs(cm, 40, margin=MARGIN)
    check_protocol(cm, draw.pairs, MARGIN, 40)
    assert draw.cells_drawn > 80  # some cells were rejected (obstacles, too near)
    # the same seed gives the same pairs, another seed others
    assert B.draw_pairs(cm, 40, margin=MARGIN).pairs == draw.pairs
    assert B.draw_pairs(cm, 40, seed=34, margin=MARGIN).pairs != draw.pairs


def test_pairs_are_drawn_as_documented(small):
    """The drawing, written again from the module's docstring: row, column, keep or draw again,
    yaw; start then goal."""
    _, setup = small
    cm = setup.costmap
    rng = np.random.default_rng(B.SEED)
    lo, hi = MARGIN, 199 - MARGIN

    def one(ok):
        while True:
            row, col = rng.integers(lo, hi, endpoint=True), rng.integers(lo, hi, endpoint=True)
            x, y = cm.origin_x + col * cm.resolution, cm.origin_y + row * cm.resolution
            if cm.costs[row, col] < 210 and ok(x, y):
                return (int(col), int(row)), rng.uniform(0, 2 * math.pi)

    want = []
    for _ in range(10):
        s, syaw = one(lambda x, y: True)
        sx, sy = cm.origin_x + s[0] * cm.resolution, cm.origin_y + s[1] * cm.resolution
        g, gyaw = one(lambda x, y: math.dist((x, y), (sx, sy)) > 3.0)
        want.append((s, g, Pose.from_yaw(sx, sy, syaw).orientation))
    got = B.draw_pairs(cm, 10, margin=MARGIN).pairs
    assert [(q.start_cell, q.goal_cell, q.start.orientation) for q in got] == want


def test_a_map_that_does_not_suit_the_protocol_is_refused(small):
    from navfn_smt.errors import NavfnInputError

    _, setup = small
    with pytest.raises(NavfnInputError, match="margin of 100 cells"):
        B.draw_pairs(setup.costmap, 5)  # 200 cells: no cell 100 from both borders
    blocked = replace(setup.costmap, costs=np.full((200, 200), 254, np.uint8))
    with pytest.raises(NavfnInputError, match="no cell of cost below 210"):
        B.draw_pairs(blocked, 5, margin=MARGIN)
    with pytest.raises(NavfnInputError, match="does not suit"):
        B.draw_pairs(setup.costmap, 2, margin=MARGIN, min_distance=100.0)  # the map is 10 m wide


@pytest.mark.skipif(not (BENCH_MAPS / "100by100_20.yaml").exists(), reason=f"no benchmark maps in {BENCH_MAPS}")
def test_pairs_on_nav2s_benchmark_map():
    setup = load_setup(BENCH_MAPS / "100by100_20.yaml", PARAMS)
    cm = setup.costmap
    assert (cm.size_x, cm.size_y) == (2000, 2000) and cm.resolution == float(np.float32(0.05))
    draw = B.draw_pairs(cm)
    check_protocol(cm, draw.pairs, B.MARGIN, B.PAIRS)
    assert len({(q.start_cell, q.goal_cell) for q in draw.pairs}) == B.PAIRS


# -------------------------------------------------------------------------------- the metrics
def test_metrics_on_a_hand_made_path():
    costs = np.zeros((4, 5), np.uint8)  # (row y, column x)
    costs[0, 0], costs[0, 3], costs[1, 3], costs[3, 3], costs[2, 3] = 10, 30, 50, 200, 99
    cm = Costmap(costs, -1.0, 0.5, 0.5)
    # the map spans x -1..1.5, y 0.5..2.5: (-1, 0.5) is cell (0, 0), (0.5, 0.5) is (3, 0), (0.5, 2.49) is (3, 3)
    path = np.array([[-1.0, 0.5, 0, 0, 0, 1], [0.5, 0.5, 0, 0, 0, 1], [0.5, 2.49, 0, 0, 0, 1]])
    assert B.path_length(path) == pytest.approx(1.5 + 1.99)
    mx, my = B.path_cells(cm, path)
    assert mx.tolist() == [0, 3, 3] and my.tolist() == [0, 0, 3]
    assert B.path_costs(cm, path).tolist() == [10, 30, 200]
    # floor, not round (NavfnPlanner's own worldToMap rounds): 2.998 and 0.98 cells are cells 2 and 0
    mx, my = B.path_cells(cm, np.array([[0.499, 0.99]]))
    assert (mx.tolist(), my.tolist()) == ([2], [0])
    assert B.path_costs(cm, np.array([[0.5, 1.0]])).tolist() == [50]  # exactly on the boundary: (3, 1)
    with pytest.raises(ValueError, match="off the costmap"):
        B.path_costs(cm, np.array([[0.5, 2.5]]))
    with pytest.raises(ValueError, match="off the costmap"):
        B.path_costs(cm, np.array([[-1.0000001, 0.5]]))
    assert B.path_length(path[:1]) == 0.0


def test_a_rows_figures():
    """Averages over the planned pairs; the maximum over every pose of every path; failures counted."""
    def pair(length, mean, mx, seconds, error=None):
        poses = np.zeros((0 if error else 3, 6))
        return B.PairResult(error, poses, seconds, seconds, None, length, mean, mx)

    row = B.PlannerResult(B.PLANNERS[0], [pair(10.0, 2.0, 100, 0.1), pair(20.0, 4.0, 30, 0.3),
                                          pair(None, None, None, 5.0, "NoValidPathCouldBeFound")])
    assert (len(row.planned), row.failed) == (2, 1)
    assert row.mean_length == 15.0 and row.mean_cost == 3.0 and row.max_cost == 100
    assert row.mean_seconds == pytest.approx(0.2) and row.mean_path_max_cost == 65.0
    empty = B.PlannerResult(B.PLANNERS[0], [pair(None, None, None, 1.0, "GoalOccupied")])
    assert empty.failed == 1 and empty.mean_length is None and empty.max_cost is None


def test_the_run_measures_each_path(small, small_run):
    _, setup = small
    draw, rows, diffs = small_run
    assert diffs == [] and [r.planner for r in rows] == list(B.PLANNERS)
    for row in rows:
        assert len(row.pairs) == len(draw.pairs)
        for q, r in zip(draw.pairs, row.pairs):
            if not r.ok:
                assert r.length is None
                continue
            xy = r.poses[:, :2]
            assert r.length == pytest.approx(sum(math.dist(a, b) for a, b in zip(xy[:-1], xy[1:])))
            costs = [int(setup.costmap.costs[int((y - setup.costmap.origin_y) // setup.costmap.resolution),
                                             int((x - setup.costmap.origin_x) // setup.costmap.resolution)])
                     for x, y in xy]
            assert r.mean_cost == pytest.approx(np.mean(costs)) and r.max_cost == max(costs)
            assert r.length >= q.distance - 1.0  # the tolerance (0.5 m) may end it short of the goal
            assert r.seconds == r.model_seconds > 0 and r.cpp_seconds is None


# ------------------------------------------------------------------------- original and fixed
def test_fixed_plans_what_the_original_plans_with_the_same_path(small_run):
    draw, rows, _ = small_run
    by = {(r.planner.variant, r.planner.mode): r for r in rows}
    crossing = [k for k, q in enumerate(draw.pairs) if (q.start_cell[0] > WALL) != (q.goal_cell[0] > WALL)]
    assert crossing, "no pair crosses the wall: the map no longer tests failures"
    for mode in ("dijkstra", "astar"):
        orig, fixed = by["original", mode], by["fixed", mode]
        for k, (a, b) in enumerate(zip(orig.pairs, fixed.pairs)):
            if a.ok:
                assert b.ok and B.same_bits(a.poses, b.poses), (mode, k)
        assert {k for k, p in enumerate(fixed.pairs) if p.ok} >= {k for k, p in enumerate(orig.pairs) if p.ok}
        # pairs across the wall cannot be planned, and are counted as failures
        assert all(not orig.pairs[k].ok and not fixed.pairs[k].ok for k in crossing)
        assert orig.failed >= len(crossing) and len(orig.planned) + orig.failed == len(draw.pairs)
        assert orig.planned, "no pair planned"
    (dij, ast) = B.compare_fix(rows)
    assert dij.changed == [] == ast.changed and dij.same_path == len(by["original", "dijkstra"].planned)


def test_compare_fix_sees_a_changed_path(small_run):
    _, rows, _ = small_run
    orig = rows[0]
    k = next(i for i, p in enumerate(orig.pairs) if p.ok)
    fixed = B.PlannerResult(rows[1].planner, list(rows[1].pairs))
    moved = fixed.pairs[k].poses.copy()
    moved[1, 0] = np.nextafter(moved[1, 0], np.inf)  # one bit of one coordinate
    fixed.pairs[k] = replace(fixed.pairs[k], poses=moved)
    (c,) = B.compare_fix([orig, fixed])
    assert c.changed == [k] and c.same_path == len(orig.planned) - 1


# ------------------------------------------------------------------------------- the C++ side
class FakeOracle:
    """A C++ plugin that answers with the model's poses, one coordinate nudged on the pair whose
    start is ``bad`` (None: never)."""

    def __init__(self, bad, variant: str):
        self.bad, self.variant, self.planning_seconds = bad, variant, 0.0

    def create_plans(self, cm, params, pairs):
        from navfn_smt.nav2.plugin import create_plan
        from navfn_smt.oracle.client import PluginAnswer

        assert len(pairs) == 1 and params.fix.name == self.variant  # one request per pair, for its time
        run = create_plan(cm, *pairs[0], params)
        poses = B.poses_array(run.poses)
        if pairs[0][0] == self.bad and len(poses):
            poses[-1, 1] = np.nextafter(poses[-1, 1], -np.inf)
        self.planning_seconds = 0.25
        return [PluginAnswer(run.error, run.message, poses, run.lines)]


def test_a_cpp_difference_is_reported_and_cpp_times_are_used(small, small_run):
    _, setup = small
    draw, rows, _ = small_run
    k = next(i for i, p in enumerate(rows[0].pairs) if p.ok and i > 0)
    oracles = {"original": FakeOracle(draw.pairs[k].start, "original"), "fixed": FakeOracle(None, "fixed")}
    got, diffs = B.run_benchmark(setup.costmap, setup.params, draw.pairs[:k + 1], B.PLANNERS[:2], oracles)
    assert [(d.planner, d.pair, d.what.split()[0]) for d in diffs] == [("NavFn original Dijkstra", k, "pose")]
    assert all(p.seconds == p.cpp_seconds == 0.25 for r in got for p in r.pairs)
    assert got[1].pairs[k].length == rows[1].pairs[k].length  # the fixed's answers were the model's
    assert got[0].pairs[k].poses[-1, 1] < rows[0].pairs[k].poses[-1, 1]  # the C++'s poses are the result


# ------------------------------------------------------------------------------------ command
def test_the_command_on_a_small_map(small, tmp_path, capsys):
    path, _ = small
    out = tmp_path / "r.json"
    assert main(["nav2-benchmark", str(path), "--pairs", "6", "--margin", str(MARGIN), "--mode", "astar",
                 "--json", str(out)]) == 0
    text = capsys.readouterr().out
    assert "NavFn original A*" in text and "NavFn fixed A*" in text and "Dijkstra" not in text.split("planner")[1]
    assert "the model's create_plan" in text
    doc = json.loads(out.read_text())
    (m,) = doc["maps"]
    assert len(m["pairs"]) == 6 and [r["planner"] for r in m["rows"]] == ["NavFn original A*", "NavFn fixed A*"]
    assert all(r["planned"] + r["failed"] == 6 for r in m["rows"]) and m["differences"] == []


def test_the_command_refuses_bad_input(small, tmp_path, monkeypatch, capsys):
    path, _ = small
    assert main(["nav2-benchmark", str(path), "--pairs", "2"]) == 2  # margin 100 on a 200-cell map
    assert "margin of 100 cells" in capsys.readouterr().err
    assert main(["nav2-benchmark", str(tmp_path / "none.yaml")]) == 2
    assert "no such map YAML file" in capsys.readouterr().err
    monkeypatch.setenv("NAVFN_SHARED", str(tmp_path))
    assert main(["nav2-benchmark"]) == 2
    assert "benchmark maps are not in" in capsys.readouterr().err


def test_the_cpp_plugin_agrees(small, builds):
    """With the C++ plugin (Rolling's build the oracle tests share): every pose bit for bit, and
    the planning time is the C++'s."""
    from navfn_smt.oracle.client import PluginOracle

    _, setup = small
    folder = builds["rolling"][1]
    draw = B.draw_pairs(setup.costmap, 6, margin=MARGIN)
    with PluginOracle(folder, "original") as o, PluginOracle(folder, "fixed") as f:
        rows, diffs = B.run_benchmark(setup.costmap, setup.params, draw.pairs, B.PLANNERS,
                                      {"original": o, "fixed": f})
    assert diffs == []
    assert all(p.seconds == p.cpp_seconds for r in rows for p in r.pairs)
