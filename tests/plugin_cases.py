"""The plugin's findings (docs/plugin.md) as case directories a map_server and Nav2 could load,
and their replay: a test tool, not part of the package.

``python tests/plugin_cases.py tests/data/plugin_cases`` rebuilds the committed directories
(map YAML + PGM, params YAML, ``case.json`` with the poses and ``create_plan``'s outcome);
``tests/test_plugin_offmap.py`` replays every one on both backends (:func:`replay_case`).
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

import numpy as np

from navfn_smt.nav2.offmap import RES, hexf, next_down, next_up, offmap_interval_numeric
from navfn_smt.nav2.plugin import Costmap, Pose, create_plan

PIXEL = {0: 254, 254: 0, 255: 205}  # trinary map_server image values for free, lethal, unknown


def write_case(root, name: str, ros: np.ndarray, origin: tuple, resolution: str, start: Pose, goal: Pose,
               params: dict, note: str, backend: str = "jit") -> dict:
    """Write ``root/name``: ``map.yaml`` + ``map.pgm`` (trinary, row 0 of ``ros`` at the image's
    bottom), ``params.yaml`` (a ``planner_server`` section), ``case.json`` (poses, the note, and the
    outcome of :func:`create_plan` on the loaded files).  ``ros`` holds costmap values 0/254/255."""
    d = Path(root) / name
    d.mkdir(parents=True, exist_ok=True)
    ros = np.asarray(ros, dtype=np.uint8)
    h, w = ros.shape
    img = np.vectorize(PIXEL.__getitem__, otypes=[np.uint8])(ros)[::-1]
    (d / "map.pgm").write_bytes(b"P5\n%d %d\n255\n" % (w, h) + np.ascontiguousarray(img).tobytes())
    (d / "map.yaml").write_text(f"image: map.pgm\nmode: trinary\nresolution: {resolution}\n"
                                f"origin: [{origin[0]!r}, {origin[1]!r}, 0.0]\nnegate: 0\n"
                                f"occupied_thresh: 0.65\nfree_thresh: 0.196\n")
    lines = ["planner_server:", "  ros__parameters:", "    expected_planner_frequency: 20.0",
             "    planner_plugins: [\"GridBased\"]", "    GridBased:",
             "      plugin: \"nav2_navfn_planner::NavfnPlanner\""]
    for k, v in params.items():
        lines.append(f"      {k}: {_yaml_scalar(v)}")
    (d / "params.yaml").write_text("\n".join(lines) + "\n")
    case = {"note": note, "start": _pose_json(start), "goal": _pose_json(goal)}
    (d / "case.json").write_text(json.dumps(case, indent=1) + "\n")
    case["expected"] = outcome(run_case(d, backend))
    (d / "case.json").write_text(json.dumps(case, indent=1) + "\n")
    return case


def _yaml_scalar(v) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    return repr(v)


def _pose_json(p: Pose) -> dict:
    return {"x": p.x, "y": p.y, "x_hex": hexf(p.x), "y_hex": hexf(p.y), "orientation": list(p.orientation)}


def _pose_from_json(d: dict) -> Pose:
    return Pose(float.fromhex(d["x_hex"]), float.fromhex(d["y_hex"]), *map(float, d["orientation"]))


def load_case(d) -> tuple[Costmap, Pose, Pose, object, dict]:
    from navfn_smt.nav2.mapserver import load_map_yaml
    from navfn_smt.nav2.params import planner_params
    from navfn_smt.nav2.plugin import costmap_from_map

    d = Path(d)
    case = json.loads((d / "case.json").read_text())
    cm = costmap_from_map(load_map_yaml(d / "map.yaml"))
    return cm, _pose_from_json(case["start"]), _pose_from_json(case["goal"]), planner_params(d / "params.yaml"), case


def run_case(d, backend: str = "jit"):
    """``create_plan`` on a case directory; a NavfnInputError (a loop the plugin model refuses to
    run because Nav2's would not end) comes back as the outcome ``{"raises": ..., "message": ...}``."""
    from navfn_smt.errors import NavfnInputError

    cm, start, goal, params, _ = load_case(d)
    try:
        return create_plan(cm, start, goal, params, backend=backend)
    except NavfnInputError as e:
        return {"raises": "NavfnInputError", "message": str(e)}


def outcome(run) -> dict:
    """What a replay compares: the published poses (hex, exact), the exception and its message,
    the cells the plugin's two worldToMap gave, the tolerance search's result, the log."""
    if isinstance(run, dict):
        return run
    cell = (lambda c: None if c is None else [int(c[0]), int(c[1])])
    return {
        "error": run.error,
        "message": run.message,
        "poses": [[hexf(p.x), hexf(p.y)] + [hexf(v) for v in p.orientation] for p in run.poses],
        "start_cell": cell(run.start_cell), "goal_cell": cell(run.goal_cell),
        "robot_cell": cell(run.robot_cell), "target_cell": cell(run.target_cell),
        "reached": run.reached,
        "goal_potential": None if run.goal_potential is None else hexf(run.goal_potential),
        "used_tolerance": run.used_tolerance,
        "best_pose": None if run.best_pose is None else [hexf(run.best_pose.x), hexf(run.best_pose.y)],
        "best_cell": cell(run.best_cell),
        "max_cycles": run.max_cycles,
        "log": list(run.log),
        "warnings": list(run.warnings),
    }


def replay_case(d, backend: str = "jit") -> tuple[dict, dict]:
    """(expected, actual) outcomes of a case directory."""
    case = json.loads((Path(d) / "case.json").read_text())
    return case["expected"], outcome(run_case(d, backend))


# --------------------------------------------------------------------------- the findings as cases
SKIP_GOAL_X = -1.5249998811632401  # found by tolerance_gap(-10.0, RES, 0.5, -9.5, 0.0): column 160 skipped


def _free(w: int, h: int) -> np.ndarray:
    return np.zeros((h, w), dtype=np.uint8)


def build_cases(root, backend: str = "jit") -> dict:
    """Every finding of ``docs/plugin.md`` as a case directory under ``root``; returns the cases."""
    out = {}
    o8 = offmap_interval_numeric(0.0, RES, 8)  # x: the right column's last half cell of an 8-wide map
    o6 = offmap_interval_numeric(0.0, RES, 6)  # y: the top row's of a 6-high map
    y2, y3 = 2 * RES + 0.01, 3 * RES + 0.01  # rows 2 and 3 under both worldToMap
    x2 = 2 * RES + 0.01
    defaults = {"tolerance": 0.5, "use_astar": False, "allow_unknown": True}

    def case(name, ros, origin, start, goal, params, note):
        out[name] = write_case(root, name, ros, origin, "0.05", start, goal, params, note, backend)

    case("robot-right-half-cell", _free(8, 6), (0.0, 0.0), Pose(o8[0], y2), Pose(x2, y3), defaults,
         f"robot at x = lo = {hexf(o8[0])}: createPlan's truncating check gives column 7, the plugin's "
         f"rounding gives column 8 = size_x; NavFn's propagation starts at index 2*8+8 = cell (0, 3); "
         f"the path runs from x = 8 (one past the edge) straight to column 1")
    case("robot-top-half-cell", _free(8, 6), (0.0, 0.0), Pose(x2, o6[0]), Pose(x2, y3), defaults,
         f"robot at y = lo = {hexf(o6[0])}: row 6 = size_y; clearRobotCell writes index 6*8+2 = 50, past "
         f"the 48-cell costmap (undefined behaviour)")
    case("goal-right-half-cell", _free(8, 6), (0.0, 0.0), Pose(x2, y3), Pose(next_down(o8[1]), y2), defaults,
         f"goal at x = hi- = {hexf(next_down(o8[1]))}, the last double of column 7: rounds to column 8, "
         f"getPointPotential is DBL_MAX, the tolerance search picks the nearest point of column 6 "
         f"(column 7 is NavFn's lethal border)")
    case("goal-right-half-cell-tolerance-0", _free(8, 6), (0.0, 0.0), Pose(x2, y3), Pose(o8[0], y2),
         {**defaults, "tolerance": 0.0},
         "the same with tolerance 0: the goal's free, reachable cell (7, 2) gives NoValidPathCouldBeFound")
    case("goal-top-half-cell", _free(8, 6), (0.0, 0.0), Pose(x2, y2), Pose(x2, o6[0]), defaults,
         "goal in the top row's last half cell: NavFn's start is (2, 6), index 50 past potarr (48 cells); "
         "the propagation reads it (undefined behaviour)")
    i = 4
    case("goal-at-cell-centre", _free(8, 6), (0.0, 0.0), Pose(x2, y2), Pose((i + 0.5) * RES, y3), defaults,
         f"goal at the centre of cell {i}, origin + ({i} + 0.5) * res: the plugin plans to cell {i + 1} "
         f"(std::round, half away from zero); the path's last point is the corner of cell {i + 1}, then the goal")
    occ = _free(8, 6)
    occ[3, 4] = 254
    case("goal-occupied-truncated-only", occ, (0.0, 0.0), Pose(x2, y2), Pose(4.75 * RES, y3),
         {**defaults, "tolerance": 0.0},
         "tolerance 0, the goal's truncated cell (4, 3) is lethal, its rounded cell (5, 3) free: "
         "GoalOccupied, although NavFn would plan to (5, 3)")
    occ = _free(8, 6)
    occ[3, 5] = 254
    case("goal-lethal-rounded-only", occ, (0.0, 0.0), Pose(x2, y2), Pose(4.75 * RES, y3),
         {**defaults, "tolerance": 0.0},
         "tolerance 0, the truncated cell (4, 3) free passes the GoalOccupied check; the rounded cell "
         "(5, 3) is lethal: no potential there, NoValidPathCouldBeFound")
    # the one-sided tolerance window: 20 points from g - 0.5 to g + 0.45000001415610313
    ros = np.full((7, 26), 254, np.uint8)
    ros[1:6, 22:25] = 0
    case("tolerance-window-right-edge", ros, (0.0, 0.0), Pose(23.25 * RES, 3.25 * RES),
         Pose(12 * RES, 3 * RES), defaults,
         "goal at the corner of cell (12, 3) (lethal), tolerance 0.5 = 10 cells: the loop visits x = g - 0.5 "
         "... g + 0.45000001415610313 (20 points, columns 2..21); the free cell (22, 3), 10 cells right "
         "of the goal, is never examined: NoValidPathCouldBeFound")
    ros = np.full((7, 26), 254, np.uint8)
    ros[1:6, 1:4] = 0
    case("tolerance-window-left-edge", ros, (0.0, 0.0), Pose(1.25 * RES, 3.25 * RES),
         Pose(13 * RES, 3 * RES), defaults,
         "the mirror image: the free cell (3, 3) 10 cells left of the goal's (13, 3) is examined "
         "(the loop's first column) and planned to")
    # a column the accumulated loop skips
    ros = np.full((7, 182), 254, np.uint8)
    ros[1:6, 160] = 0
    case("tolerance-skipped-column", ros, (-10.0, 0.0), Pose(-10.0 + 160.25 * RES, 1.25 * RES),
         Pose(SKIP_GOAL_X, 3 * RES + 0.01), defaults,
         f"origin x -10, goal x = {hexf(SKIP_GOAL_X)} (Z3): the loop's first point rounds to column 159, "
         f"the second ({hexf(SKIP_GOAL_X - 0.5 + RES)}) to 161; the free column 160 (distance < 0.5 from "
         f"the goal) is never examined: NoValidPathCouldBeFound")
    ros = np.full((7, 182), 254, np.uint8)
    ros[1:6, 160] = 0
    case("tolerance-skipped-column-control", ros, (-10.0, 0.0), Pose(-10.0 + 160.25 * RES, 1.25 * RES),
         Pose(next_up(SKIP_GOAL_X), 3 * RES + 0.01), defaults,
         "the goal one double higher: the loop visits column 160 and plans to it")
    # the loop that never ends
    big = 2.0 ** 49
    ros = _free(8, 6)
    ros[3, 4:6] = 254  # the goal's truncated (4) and rounded (5) cells
    case("tolerance-loop-never-ends", ros, (big, 0.0), Pose(big + 2 * RES, y2), Pose(big + 4 * RES, 3 * RES),
         defaults,
         "origin x = 2^49 = 562949953421312 (the first positive double where p + 0.05f == p), the goal "
         "(2^49 + 0.25: 4 * res rounds to the double spacing 0.125) on a lethal cell: the tolerance loop's x reaches 2^49 and stays there; Nav2 never returns")
    case("max-cycles-overflow", _free(8, 6), (0.0, 0.0), Pose(x2, y2), Pose(5 * RES + 0.01, y3),
         {**defaults, "max_cycles_factor": 268435456},
         "max_cycles = 8 * 268435456 = 2^31 overflows int (undefined behaviour)")
    case("max-cycles-zero", _free(8, 6), (0.0, 0.0), Pose(x2, y2), Pose(5 * RES + 0.01, y3),
         {**defaults, "max_cycles_factor": 0},
         "max_cycles_factor 0: calcPath(0) returns 0, 'Failed to create a plan from potential when a legal "
         "potential was found' then NoValidPathCouldBeFound")
    return out


def main(argv=None) -> int:
    """``python tests/plugin_cases.py CASES_DIR``: rebuild the case directories."""
    import argparse

    ap = argparse.ArgumentParser(prog="python tests/plugin_cases.py")
    ap.add_argument("cases")
    a = ap.parse_args(argv)
    for name, c in build_cases(a.cases).items():
        e = c["expected"]
        print(name, e.get("error") or e.get("raises") or f"{len(e['poses'])} poses")
    return 0


if __name__ == "__main__":
    sys.exit(main())
