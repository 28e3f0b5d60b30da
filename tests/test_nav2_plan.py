"""Planning between world poses as Nav2's NavfnPlanner plugin does (navfn_smt.nav2.plugin),
end to end from map_server maps, and the two worldToMap functions.

Expected values are derived by hand from Nav2's C++: ``Costmap2D::worldToMap`` truncates
``(w - o) / r`` and refuses ``w < o`` or a cell past the size; ``NavfnPlanner::worldToMap``
rounds half away from zero and ``mapToWorld`` is ``o + p * r`` (no half cell); the costmap's
resolution is nav_msgs/MapMetaData's float32; ``makePlan`` clears the robot's cell, swaps the
poses for NavFn and gives ``calcPath`` ``max(size_x, size_y) * max_cycles_factor`` steps.
"""

from __future__ import annotations

import json
import subprocess
import sys

import numpy as np
import pytest
import yaml
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from PIL import Image

from navfn_smt.nav2.mapserver import load_map_yaml
from navfn_smt.nav2.params import PlannerParams
from navfn_smt.nav2.plugin import (
    Costmap,
    Pose,
    costmap_from_map,
    costmap_world_to_map,
    create_plan,
    plugin_map_to_world,
    plugin_world_to_map,
)
from navfn_smt.spec.extraction import ExtractionExit

from conftest import REPO

HYP = settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.too_slow])
F32 = np.float32
ROS_MAPS = ("empty_room", "keepout_mask", "map_circular", "speed_mask")
BASE = {"resolution": 1.0, "origin": [0.0, 0.0, 0.0], "negate": 0, "occupied_thresh": 0.65, "free_thresh": 0.196}


def write_map(folder, pixels, **fields):
    """A map_server YAML + PGM (pixels in image row order: row 0 is the top)."""
    pix = np.asarray(pixels, np.uint8)
    h, w = pix.shape
    (folder / "m.pgm").write_bytes(b"P5\n%d %d\n255\n" % (w, h) + pix.tobytes())
    p = folder / "m.yaml"
    p.write_text(yaml.safe_dump({**BASE, "image": "m.pgm", **fields}))
    return p


def grid(w, h, res, ox, oy) -> Costmap:
    return Costmap(np.zeros((h, w), np.uint8), ox, oy, float(F32(res)))


# -------------------------------------------------------------------------------- coordinates
def test_world_to_map_boundaries():
    c = grid(3, 4, 0.5, 0.0, 0.0)
    assert costmap_world_to_map(c, 0.0, 0.0) == (0, 0)
    assert costmap_world_to_map(c, 1.4999, 1.9999) == (2, 3)
    for wx, wy in ((1.5, 0.0), (0.0, 2.0), (-1e-12, 0.0), (0.0, -0.25)):
        assert costmap_world_to_map(c, wx, wy) is None
    # NavfnPlanner::worldToMap rounds half away from zero: 0.25 / 0.5 = 0.5 -> 1
    assert plugin_world_to_map(c, 0.25, 0.75) == (True, (1, 2))
    # 1.25 / 0.5 = 2.5 -> 3 == size_x: the call fails but has written the cell
    assert plugin_world_to_map(c, 1.25, 0.0) == (False, (3, 0))
    assert plugin_world_to_map(c, -0.1, 0.0) == (False, None)  # below the origin: nothing written
    assert plugin_map_to_world(c, 1.5, 2.0) == (0.75, 1.0)  # o + p r, no half cell


def test_float32_resolution_changes_the_cell():
    # MapMetaData.resolution is float32: 0.05 becomes 0.0500000007450580596923828125, so
    # (0.1 - 0) / r = 1.99999997 truncates to 1, where the YAML's double would give 2.
    c = grid(10, 10, 0.05, 0.0, 0.0)
    assert 0.1 / 0.05 == 2.0
    assert costmap_world_to_map(c, 0.1, 0.1) == (1, 1)


resolutions = st.one_of(st.integers(1, 2000).map(lambda k: k / 1000),
                        st.floats(0.001, 10.0, allow_nan=False, allow_infinity=False))
origins = st.floats(-1000.0, 1000.0, allow_nan=False, allow_infinity=False)


@HYP
@given(st.integers(3, 400), st.integers(3, 400), resolutions, origins, origins, st.data())
def test_plugin_world_map_round_trip(w, h, res, ox, oy, data):
    c = grid(w, h, res, ox, oy)
    mx, my = data.draw(st.integers(0, w - 1)), data.draw(st.integers(0, h - 1))
    assert plugin_world_to_map(c, *plugin_map_to_world(c, mx, my)) == (True, (mx, my))
    # the costmap's own cell centre o + (m + 0.5) r truncates back to m
    cx, cy = ox + (mx + 0.5) * c.resolution, oy + (my + 0.5) * c.resolution
    assert costmap_world_to_map(c, cx, cy) == (mx, my)


@HYP
@given(st.integers(3, 400), st.integers(3, 400), resolutions, origins, origins, st.data())
def test_world_to_map_rejects_outside(w, h, res, ox, oy, data):
    c = grid(w, h, res, ox, oy)
    r = c.resolution
    frac = data.draw(st.floats(0.01, 0.99))
    inside_x = ox + (data.draw(st.integers(0, w - 1)) + 0.5) * r
    inside_y = oy + (data.draw(st.integers(0, h - 1)) + 0.5) * r
    k = data.draw(st.integers(0, 1000))
    side = data.draw(st.sampled_from(["left", "right", "below", "above"]))
    pt = {"left": (ox - (k + frac) * r, inside_y), "right": (ox + (w + k + frac) * r, inside_y),
          "below": (inside_x, oy - (k + frac) * r), "above": (inside_x, oy + (h + k + frac) * r)}[side]
    assert costmap_world_to_map(c, *pt) is None
    run = create_plan(c, Pose(*pt), Pose(inside_x, inside_y))
    assert run.error == "StartOutsideMapBounds" and not run.poses


# ------------------------------------------------------------------------------- planning
def free_cells(pix: np.ndarray) -> np.ndarray:
    """Grid (x, y) of pixels free in every setup (254, 255), away from edges, with all eight
    neighbours free too."""
    h, w = pix.shape
    free = pix >= 254
    ok = free.copy()
    for dr in (-1, 0, 1):
        for dc in (-1, 0, 1):
            ok &= np.roll(np.roll(free, dr, 0), dc, 1)
    ok[:2, :] = ok[-2:, :] = ok[:, :2] = ok[:, -2:] = False
    rows, cols = np.nonzero(ok)
    return np.stack([cols, h - 1 - rows], axis=1)  # grid y = h - 1 - image row


@pytest.mark.shared
@pytest.mark.parametrize("astar", [True, False], ids=["astar", "dijkstra"])
@pytest.mark.parametrize("name", ROS_MAPS)
def test_plan_end_to_end_on_ros_maps(shared_suite, name, astar):
    d = shared_suite / "ROS" / name
    doc = yaml.safe_load((d / f"{name}.yaml").read_text())
    pix = np.array(Image.open(d / doc["image"]))
    cells = free_cells(pix)
    assert len(cells) > 100
    (sx, sy), (gx, gy) = cells[len(cells) // 7], cells[6 * len(cells) // 7]
    c = costmap_from_map(load_map_yaml(d / f"{name}.yaml"))
    r32 = float(F32(float(doc["resolution"])))
    assert c.resolution == r32
    start, goal = Pose(*plugin_map_to_world(c, sx, sy)), Pose(*plugin_map_to_world(c, gx, gy))
    run = create_plan(c, start, goal, PlannerParams(use_astar=astar))
    assert run.ok and run.robot_cell == (sx, sy) and run.target_cell == (gx, gy)
    assert run.extraction == ExtractionExit.NEAR_GOAL and not run.used_tolerance
    # NavFn's path runs from the goal cell to the robot's; Nav2 reverses it into world poses
    assert tuple(run.path[0]) == (gx, gy) and tuple(run.path[-1]) == (sx, sy)
    assert (run.poses[0].x, run.poses[0].y) == (start.x, start.y)
    assert run.poses[-1] == goal  # smoothApproachToGoal: the goal pose itself ends the path
    assert len(run.poses) == len(run.path)  # the last point was the goal's position: replaced, not appended
    assert all(p.orientation == (0.0, 0.0, 0.0, 1.0) for p in run.poses)


def test_plan_clears_robot_cell_and_swaps(tmp_path):
    # A 7x7 free room; the robot stands on an obstacle pixel.  clearRobotCell frees it before
    # setCostmap; NavFn never reads its goal cell's cost, so the plan equals NavFn's on either.
    pix = np.full((7, 7), 255, np.uint8)
    pix[3, 2] = 0  # image row 3 -> grid row 7 - 1 - 3 = 3
    m = load_map_yaml(write_map(tmp_path, pix))
    assert m.navfn_costs[3, 2] == 254
    c = costmap_from_map(m)
    run = create_plan(c, Pose(2.0, 3.0), Pose(4.0, 5.0), PlannerParams(use_astar=True), backend="reference")
    assert run.robot_cell == (2, 3) and run.target_cell == (4, 5) and run.costs[3, 2] == 50
    assert run.extraction == ExtractionExit.NEAR_GOAL
    from navfn_smt.backends import get_backend

    cleared = np.full((7, 7), 50, np.uint8)
    uncleared = cleared.copy()
    uncleared[3, 2] = 254
    for costs in (cleared, uncleared):
        want = get_backend("reference").prepare(costs).run((4, 5), (2, 3), True, path_cycles=7 * 4)
        assert run.cycles == want.cycles and np.array_equal(run.potential, want.potential)
        assert np.array_equal(run.path, want.path)
    assert (run.poses[0].x, run.poses[0].y) == (2.0, 3.0) and run.poses[-1] == Pose(4.0, 5.0)


def test_calc_path_budget_is_max_side_times_factor(tmp_path):
    # A 5x80 corridor: the path needs about two points per cell over 72 cells, more than
    # 4 * nx = 20 (NavFn's own budget), fewer than 4 * ny = 320 (the plugin's).
    c = costmap_from_map(load_map_yaml(write_map(tmp_path, np.full((80, 5), 255, np.uint8))))
    for backend in ("jit", "reference"):
        run = create_plan(c, Pose(2.0, 3.0), Pose(2.0, 75.0), backend=backend)
        assert run.ok and run.max_cycles == 320 and len(run.path) > 20
        assert (run.poses[0].x, run.poses[0].y) == (2.0, 3.0) and run.poses[-1] == Pose(2.0, 75.0)
        short = create_plan(c, Pose(2.0, 3.0), Pose(2.0, 75.0), PlannerParams(max_cycles_factor=1), backend=backend)
        assert short.error == "NoValidPathCouldBeFound" and short.extraction == ExtractionExit.EXHAUSTED
        assert short.legal_potential_no_plan


def test_goal_rounding_off_the_map_takes_the_tolerance_search(tmp_path):
    c = costmap_from_map(load_map_yaml(write_map(tmp_path, np.full((5, 5), 255, np.uint8))))
    # inside for Costmap2D::worldToMap (trunc(4.6) = 4), but the plugin rounds to 5: off the
    # map, so getPointPotential is DBL_MAX and the tolerance search runs
    run = create_plan(c, Pose(1.0, 1.0), Pose(4.6, 2.0))
    assert run.target_cell == (5, 2) and run.used_tolerance
    assert run.log and run.log[0].startswith("worldToMap failed: mx,my: 5,2")
    # x from 4.1 by 1.0: 4.1 -> cell 4 (border, unreached), 5.1 > 5.1? no: 4.1, 5.1 rounds off;
    # y 1.5 -> 2 (rounds half away), 2.5 -> 3: no legal point; the search finds nothing
    assert run.error == "NoValidPathCouldBeFound"
    assert create_plan(c, Pose(1.0, 1.0), Pose(4.6, 2.0), PlannerParams(tolerance=0.0)).error == \
        "NoValidPathCouldBeFound"
    ok = create_plan(c, Pose(1.0, 1.0), Pose(4.6, 2.0), PlannerParams(tolerance=1.0))
    # x: 3.6 -> cell 4 (lethal border), 4.6, 5.6 off; nothing legal either: the border is lethal
    assert ok.error == "NoValidPathCouldBeFound"
    near = create_plan(c, Pose(1.0, 1.0), Pose(4.6, 2.0), PlannerParams(tolerance=1.5))
    # x: 3.1 -> cell 3 (interior, reached); y: 0.5 -> 1, 1.5 -> 2, 2.5 -> 3, 3.5 -> 4 (border);
    # nearest to (4.6, 2.0) among legal points: (3.1, 1.5) and (3.1, 2.5) tie at 1.5^2 + 0.5^2; y
    # runs outer from below, so (3.1, 1.5) is found first and kept (strict <)
    assert near.ok and near.best_pose == Pose(4.6 - 1.5, 2.0 - 1.5 + 1.0)
    assert near.poses[-1] == near.best_pose


def test_plan_command_prints_poses_or_the_exception(tmp_path):
    pix = np.full((9, 9), 255, np.uint8)
    pix[9 - 1 - 4, 4] = 0  # grid cell (4, 4) occupied: costmap value 254
    y = write_map(tmp_path, pix)
    params = tmp_path / "nav2_params.yaml"
    params.write_text(yaml.safe_dump({"planner_server": {"ros__parameters": {
        "planner_plugins": ["GridBased"],
        "GridBased": {"plugin": "nav2_navfn_planner::NavfnPlanner", "tolerance": 0.0, "use_astar": True}}}}))

    def run(*args):
        p = subprocess.run([sys.executable, "-m", "navfn_smt", "plan", str(y), "--world", *map(str, args)],
                           capture_output=True, text=True)
        return p.returncode, p.stdout, p.stderr

    rc, out, err = run("--start", 2, 2, "--goal", 6, 6, 1.5707963267948966, "--params", params, "--json")
    assert rc == 0, err
    doc = json.loads(out)
    assert doc["ok"] and doc["params"]["use_astar"] and doc["params"]["tolerance"] == 0.0
    assert doc["poses"][0]["position"] == {"x": 2.0, "y": 2.0, "z": 0.0}
    last = doc["poses"][-1]
    assert last["position"]["x"] == 6.0 and last["orientation"]["z"] == np.sin(np.pi / 4)
    rc, out, err = run("--start", 2, 2, "--goal", 4.9, 4.5, "--params", params)  # trunc -> (4, 4), tolerance 0
    assert rc == 1 and err.strip() == "navfn-smt: GoalOccupied: Goal Coordinates of(4.900000, 4.500000) " \
                                      "was in lethal cost"
    # the map's edge is free in the costmap (NavFn's own border is internal): no GoalOccupied there
    rc, out, err = run("--start", 2, 2, "--goal", 0, 0, "--params", params)
    assert rc == 1 and "NoValidPathCouldBeFound: Failed to create plan with tolerance of: 0.000000" in err
    rc, out, err = run("--start", 2, 2, "--goal", 9.5, 0)
    assert rc == 1 and "GoalOutsideMapBounds: Goal Coordinates of(9.500000, 0.000000) was outside bounds" in err
    rc, out, err = run("--start", 2, 2, 1, 1, "--goal", 3, 3)
    assert rc == 2 and "X Y or X Y YAW" in err and "Traceback" not in err
    rc, out, err = run("--start", 2, 2, "--goal", 3, 3, "--params", tmp_path / "missing.yaml")
    assert rc == 2 and "no such params file" in err


def test_setup_builds_the_global_costmap_from_the_params_file(tmp_path):
    from navfn_smt.nav2 import costmap as layers
    from navfn_smt.nav2.setup import load_setup

    room = REPO / "src/navfn_smt/examples/mapserver/room.yaml"
    example = REPO / "src/navfn_smt/examples/nav2/nav2_params.yaml"
    m = load_map_yaml(room)
    default = load_setup(room)  # no params file: the static layer alone
    assert np.array_equal(default.costmap.costs, m.ros_costmap)
    given = load_setup(room, example)  # inflation 0.55 m, scaling 3.0
    want = layers.build_global_costmap(m, layers.load_costmap_params(example), "rolling").costmap
    assert np.array_equal(given.costmap.costs, want) and not np.array_equal(given.costmap.costs, m.ros_costmap)
    assert given.params.tolerance == 0.5 and not given.params.use_astar
    humble = load_setup(room, example, distro="humble", overrides={"max_cycles_factor": 9})
    assert humble.params.max_cycles_factor == 4 and any("PR #6308" in n for n in humble.notes)


def test_costmap_given_directly(tmp_path):
    from navfn_smt.nav2.setup import load_setup

    costs = np.zeros((12, 16), np.uint8)
    costs[2:10, 8] = 254  # a wall at x = 8, rows 2..9 (grid rows: row 0 at the bottom)
    np.save(tmp_path / "c.npy", costs)
    pgm = tmp_path / "c.pgm"  # the same values as an image: its top row is the grid's last row
    pgm.write_bytes(b"P5\n16 12\n255\n" + costs[::-1].tobytes())
    a = load_setup(tmp_path / "c.npy", resolution=0.05, origin=(1.0, 2.0))
    b = load_setup(pgm, resolution=0.05, origin=(1.0, 2.0))
    assert np.array_equal(a.costmap.costs, costs) and np.array_equal(b.costmap.costs, costs)
    assert a.costmap.resolution == float(F32(0.05)) and (a.costmap.origin_x, a.costmap.origin_y) == (1.0, 2.0)
    run = create_plan(a.costmap, Pose(1.0 + 3 * a.costmap.resolution, 2.0 + 5 * a.costmap.resolution),
                      Pose(1.0 + 12 * a.costmap.resolution, 2.0 + 5 * a.costmap.resolution))
    assert run.ok and run.robot_cell == (3, 5) and run.target_cell == (12, 5)
    assert all(costs[int(round(y)), int(round(x))] != 254 for x, y in run.path.tolist())
    for bad, words in (((tmp_path / "c.npy", None), "give --resolution"), ((tmp_path / "no.npy", 0.05), "no such")):
        with pytest.raises(Exception) as e:
            load_setup(bad[0], resolution=bad[1])
        assert words in str(e.value) and "\n" not in str(e.value)
    np.save(tmp_path / "f.npy", np.zeros((4, 4), np.float32) + 0.5)
    with pytest.raises(Exception) as e:
        load_setup(tmp_path / "f.npy", resolution=0.05)
    assert "integers 0..255" in str(e.value)
