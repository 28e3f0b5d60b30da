"""What ``plan`` prints: one planning result as text or as one JSON object."""

from __future__ import annotations

import json


def _points(path) -> list[list[float]]:
    """Path points as plain ``[x, y]`` floats."""
    return [[float(x), float(y)] for x, y in path]


def _exit_name(res) -> str:
    """How extraction ended, or ``unknown`` without a NavFn call."""
    return res.exit.value if res and res.exit else "unknown"


def print_path(path: list, unit: str, res) -> None:
    """The path's points one a line, or why there is none."""
    if path:
        print(f"path: {len(path)} {unit}")
        for x, y in path:
            print(f"  {x:.9g} {y:.9g}")
    else:
        print(f"no path (calcPath returned 0: {_exit_name(res)})")


EXIT_WHY = {
    "out_of_bounds": "calcPath stops when its cell is in the first or last row of the map (its bounds check)",
    "high_potential": "path extraction stepped onto a cell propagation never reached (potential 1e10)",
    "zero_gradient": "the interpolated gradient at the path's point was exactly (0, 0), so the path cannot move",
    "exhausted": "calcPath used its whole step budget (4 x the map width) without coming near the goal "
                 "(the path cycles)",
}


def why_no_path(costs, res, start, goal) -> list[str]:
    """Why NavFn returned no path between two cells: the start's cost and place, whether
    propagation reached it, and how calcPath ended (lines for a person to read)."""
    from ..spec.constants import COST_OBS, POT_HIGH
    from ..spec.propagation import cycle_limit

    ny, nx = costs.shape
    why = []

    def border(c) -> bool:
        return c[0] in (0, nx - 1) or c[1] in (0, ny - 1)

    sx, sy = start
    unreached = float(res.start_potential) >= POT_HIGH
    if border(start):
        why.append(f"the start cell {tuple(start)} is on the map's border: NavFn's setupNavFn makes the outermost "
                   f"rows and columns lethal (cost {COST_OBS}) even where the map is free, so no path can begin there")
    elif int(costs[sy, sx]) >= COST_OBS:
        why.append(f"the start cell {tuple(start)} has cost {int(costs[sy, sx])} (lethal, COST_OBS {COST_OBS}): "
                   "propagation never enters a lethal cell")
    if border(goal):
        why.append(f"the goal cell {tuple(goal)} is on the map's lethal border (propagation begins there but "
                   "spreads only into passable cells)")
    elif int(costs[goal[1], goal[0]]) >= COST_OBS:
        why.append(f"the goal cell {tuple(goal)} has cost {int(costs[goal[1], goal[0]])} (lethal): propagation "
                   "begins there but spreads only into passable cells")
    if unreached:
        line = "propagation never reached the start cell: its potential stayed 1e10 (POT_HIGH)"
        if not why:
            limit = cycle_limit(nx, ny)
            line += (f" after the cycle limit of {limit}" if res.cycles >= limit else
                     ": lethal cells separate it from the goal")
        why.append(line)
    exit_ = _exit_name(res)
    why.append(f"calcPath returned 0 ({exit_}): " + EXIT_WHY.get(exit_, "no path"))
    return why


def cell_plan_doc(res, mode: str, backend: str, start, goal) -> dict:
    """The JSON object of a plan between two cells."""
    return {
        "mode": mode,
        "backend": backend,
        "start": list(start),
        "goal": list(goal),
        "start_reached": bool(res.start_reached),
        "start_potential": float(res.start_potential),
        "cycles": int(res.cycles),
        "updates": int(res.updates),
        "dropped_pushes": int(res.dropped),
        "exit": res.exit.value if res.exit else None,
        "path": _points(res.path),
        **({"fix": res.extra["fix"]} if "fix" in res.extra else {}),
    }


def cell_plan(res, mode: str, backend: str, start, goal, as_json: bool, costs=None, planner=None) -> None:
    """Print a plan between two cells: its JSON object (with ``why`` when there is no path),
    or a summary and the path's points, or no path and why (from the map's ``costs``);
    ``planner``: the planner under test that planned it, named in both."""
    why = why_no_path(costs, res, start, goal) if costs is not None and not len(res.path) else None
    if as_json:
        doc = cell_plan_doc(res, mode, backend, start, goal)
        if planner is not None:
            doc["planner"] = planner.as_dict()
        if why:
            doc["why"] = why
        print(json.dumps(doc))
        return
    print(f"mode {mode}, start {start}, goal {goal}" + (f"; planner: {planner.label}" if planner is not None else ""))
    print(f"start reached: {res.start_reached}; start potential: {float(res.start_potential):.9g}; "
          f"cycles: {res.cycles}; updates: {res.updates}; dropped pushes: {res.dropped}")
    if "fix" in res.extra:
        print("fixed planner: " + (f"the fix acted ({', '.join(res.extra['fix'])})" if res.extra["fix"]
                                   else "the original's plan (the fix did not act)"))
    print_path(_points(res.path), "points", res)
    for line in why or ():
        print(f"  why: {line}")


def _pose(p) -> dict:
    """A ``geometry_msgs/Pose`` as Nav2 publishes it (doubles printed to round-trip exactly)."""
    return {"position": {"x": p.x, "y": p.y, "z": 0.0},
            "orientation": {"x": p.qx, "y": p.qy, "z": p.qz, "w": p.qw}}


def plugin_plan_doc(setup, run, start, goal, backend: str) -> dict:
    """The JSON object of one ``createPlan`` call: the path Nav2 publishes, or its exception."""
    from dataclasses import fields

    # the plugin's parameters, the fix by its name (as ``--variant`` gives it)
    params = {f.name: getattr(setup.params, f.name) for f in fields(setup.params) if f.name != "fix"}
    return {
        "map": str(setup.map.path),
        "size": [setup.costmap.size_x, setup.costmap.size_y],
        "resolution": setup.costmap.resolution,
        "origin": [setup.costmap.origin_x, setup.costmap.origin_y],
        "layers": setup.layers,
        "notes": setup.notes,
        "params": {**params, "variant": setup.params.fix.name},
        "backend": backend,
        "start": _pose(start), "goal": _pose(goal),
        "ok": run.ok,
        "exception": run.error,
        "message": run.message or None,
        "log": run.log,
        "start_cell": run.start_cell and list(run.start_cell),
        "goal_cell": run.goal_cell and list(run.goal_cell),
        "robot_cell": run.robot_cell and list(run.robot_cell),
        "target_cell": run.target_cell and list(run.target_cell),
        "goal_potential": run.goal_potential,
        "used_tolerance": run.used_tolerance,
        "best_pose": run.best_pose and _pose(run.best_pose),
        "propagation_cycles": run.cycles if run.potential is not None else None,
        "max_cycles": run.max_cycles,
        "extraction_exit": run.extraction.value if run.extraction else None,
        "header": {"frame_id": "map"},
        "poses": [_pose(p) for p in run.poses],
    }


def plugin_plan(setup, run, start, goal, backend: str, as_json: bool) -> None:
    """Print one ``createPlan`` call: its JSON object, or a summary and the poses (x y and the
    quaternion z w), or the exception as one line on stderr."""
    import sys

    if as_json:
        print(json.dumps(plugin_plan_doc(setup, run, start, goal, backend)))
    else:
        c = setup.costmap
        p = setup.params
        print(f"map {setup.map.path} ({c.size_x}x{c.size_y} cells of {c.resolution!r} m, layers: "
              f"{', '.join(setup.layers) or 'none'}); {'A*' if p.use_astar else 'Dijkstra'}, tolerance {p.tolerance!r}, "
              f"max_cycles_factor {p.max_cycles_factor}")
        for note in setup.notes:
            print(f"note: {note}")
        for line in run.log:
            print(f"[nav2 ERROR] {line}")
        if run.ok:
            how = f" (goal unreached: tolerance search chose ({run.best_pose.x!r}, {run.best_pose.y!r}))" \
                if run.used_tolerance else ""
            print(f"path: {len(run.poses)} poses in frame map{how}")
            print("  x y qz qw")
            for q in run.poses:
                print(f"  {q.x!r} {q.y!r} {q.qz!r} {q.qw!r}")
    if not run.ok:
        print(f"navfn-smt: {run.error}: {run.message}", file=sys.stderr)
