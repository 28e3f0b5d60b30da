"""What ``diagnose`` prints and writes: the explanation as text, the JSON report, the picture.

Every JSON field is documented in ``docs/diagnose.md``.  Pictures use the map's cell
coordinates with y up (grid row 0 at the bottom, as RViz shows the map); NavFn's path points
are in the same coordinates (a point ``(x, y)`` with integer part the cell).
"""

from __future__ import annotations

import json
import math
from pathlib import Path
from typing import Optional, Sequence

import numpy as np

from ..errors import NavfnInputError
from ..fileio import atomic_path, atomic_write_text
from ..nav2.plugin import LEGAL_BUT_NO_PLAN, yaw_of
from ..spec.constants import INSCRIBED_INFLATED_OBSTACLE, LETHAL_OBSTACLE, NO_INFORMATION, POT_HIGH

SCHEMA = "navfn-smt-diagnose/1"
PICTURE_FORMATS = (".png", ".svg")


# ----------------------------------------------------------------------------------- JSON
def _cell(c) -> Optional[list]:
    return None if c is None else [int(c[0]), int(c[1])]


def _num(v) -> Optional[float]:
    if v is None:
        return None
    v = float(v)
    return v if math.isfinite(v) else None


def _pose(p) -> dict:
    return {"x": p.x, "y": p.y, "yaw": yaw_of(p)}


def diagnosis_doc(d) -> dict:
    """One diagnosis as a JSON object."""
    run, w, c, f = d.run, d.walk, d.connectivity, d.fix
    return {
        "start": _pose(d.start),
        "goal": _pose(d.goal),
        "ok": bool(d.ok),
        "exception": run.error,
        "message": run.message,
        "log": list(run.log),
        "legal_potential_no_plan": bool(run.legal_potential_no_plan),
        "cause": d.cause,
        "stage": d.stage,
        "summary": d.summary,
        "details": list(d.details),
        "cells": {"start": _cell(run.start_cell), "goal": _cell(run.goal_cell), "robot": _cell(run.robot_cell),
                  "target": _cell(run.target_cell), "best": _cell(run.best_cell), "failing": _cell(d.failing_cell)},
        "propagation": None if run.potential is None else {
            "reached": None if run.reached is None else bool(run.reached),
            "cycles": int(run.cycles), "cycle_limit": int(run.cycle_limit), "dropped": int(run.dropped),
            "goal_potential": _num(run.goal_potential), "used_tolerance": bool(run.used_tolerance),
            "best_pose": None if run.best_pose is None else _pose(run.best_pose),
            "lifted": dict(d.propagation_check) or None,
        },
        "extraction": None if run.best_pose is None else {
            "exit": run.extraction.value if run.extraction is not None else None,
            "max_cycles": run.max_cycles,
            "path_points": None if run.path is None else int(len(run.path)),
            "unbudgeted": None if w is None else {
                "exit": w.exit, "iterations": int(w.iterations), "path_length": w.path_length,
                "cycle_start": w.cycle_start, "cycle_period": w.cycle_period,
                "fallbacks": len(w.fallbacks), "oscillations": len(w.oscillations),
                "exit_cell": _cell(w.exit_cell), "detail": w.detail,
            },
        },
        "connectivity": None if c is None else {
            "connected": c.connected, "robot_region_cells": c.robot_region_cells,
            "goal_region_cells": c.goal_region_cells, "goal_cell_passable": c.goal_cell_passable,
            "cut": [_cell(x) for x in c.cut], "goal_region_boundary": c.goal_region_boundary,
        },
        "fix": None if f is None else {
            "max_cycles_factor": f.factor, "reason": f.reason, "path_length": f.path_length,
            "max_dimension": f.max_dimension, "factor_limit": f.factor_limit,
            "verified_with": f.verified_with, "verified_one_less": f.verified_one_less,
        },
        "what_ifs": [{"change": x.change, "ok": x.ok, "exception": x.error,
                      "legal_potential_no_plan": x.legal_potential_no_plan, "extraction_exit": x.extraction,
                      "poses": x.path_poses} for x in d.what_ifs],
        "poses": len(run.poses),
        "timings": {k: round(v, 4) for k, v in d.timings.items()},
    }


def report_doc(map_path, setup, backend: str, diagnoses: Sequence, seconds: float, planner=None) -> dict:
    """The whole report: the set-up once (with the planner judged and the arithmetic every step
    computed in), then one object per diagnosed plan."""
    cm, p = setup.costmap, setup.params
    causes: dict = {}
    for d in diagnoses:
        causes[d.cause] = causes.get(d.cause, 0) + 1
    return {
        "schema": SCHEMA,
        "map": str(map_path),
        "size": [cm.size_x, cm.size_y],
        "resolution": cm.resolution,
        "origin": [cm.origin_x, cm.origin_y],
        "costmap": {"layers": list(setup.layers), "notes": list(setup.notes)},
        "params": {"plugin": p.plugin, "tolerance": p.tolerance, "use_astar": p.use_astar,
                   "allow_unknown": p.allow_unknown, "max_cycles_factor": p.max_cycles_factor,
                   "use_final_approach_orientation": p.use_final_approach_orientation},
        "backend": backend,
        **({"planner": planner.as_dict()} if planner is not None else {}),
        "arithmetic": _arithmetic(diagnoses),
        "summary": {"plans": len(diagnoses), "ok": sum(d.ok for d in diagnoses),
                    "failed": sum(not d.ok for d in diagnoses), "causes": causes,
                    "legal_potential_no_plan": sum(d.legal_potential_no_plan for d in diagnoses),
                    "seconds": round(seconds, 3)},
        "results": [diagnosis_doc(d) for d in diagnoses],
    }


def write_json(path, doc: dict) -> None:
    atomic_write_text(path, json.dumps(doc, indent=1) + "\n")


# ----------------------------------------------------------------------------------- text
def _what_if_line(x) -> str:
    if x.ok:
        return f"{x.change}: plans ({x.poses} poses)" if hasattr(x, "poses") else f"{x.change}: plans"
    why = x.error or "fails"
    if x.legal_potential_no_plan:
        why += f", #4655 ({x.extraction})"
    return f"{x.change}: fails ({why})"


def text_lines(d) -> list[str]:
    """The explanation of one plan, a few lines."""
    run = d.run
    lines = [f"plan     ({d.start.x:g}, {d.start.y:g}) -> ({d.goal.x:g}, {d.goal.y:g})"]
    if d.ok:
        lines.append(f"result   OK: {d.summary}")
    else:
        lines.append(f"result   FAILED: {run.error}: {run.message}")
    for line in run.log:
        lines.append(f"log      {line}" + ("  (Nav2 issue #4655)" if line == LEGAL_BUT_NO_PLAN else ""))
    if not d.ok:
        lines.append(f"cause    {d.cause} ({d.stage}): {d.summary}")
    for line in d.details:
        lines.append(f"         {line}")
    f = d.fix
    if f is not None and not d.ok:
        if f.factor is not None:
            check = ""
            if f.verified_with is not None:
                check = (f"; checked: the plugin plans with {f.factor}: {'yes' if f.verified_with else 'NO'}, "
                         f"fails with {f.factor - 1}: {'yes' if f.verified_one_less else 'NO'}")
            lines.append(f"fix      max_cycles_factor: {f.factor} ({f.reason}{check})")
        else:
            lines.append(f"fix      max_cycles_factor: none ({f.reason}; int limit {f.factor_limit})")
    elif f is not None and f.factor is not None:
        lines.append(f"margin   the path needs max_cycles_factor >= {f.factor} (calcPath({f.path_length}) of "
                     f"{f.max_dimension} * factor)")
    if d.what_ifs:
        lines.append("what if  " + "; ".join(
            (f"{x.change}: plans ({x.path_poses} poses)" if x.ok else _what_if_line(x)) for x in d.what_ifs))
    return lines


def _arithmetic(diagnoses: Sequence) -> str:
    """The plugin arithmetic the diagnoses computed in (one for a report)."""
    from ..spec.arithmetic import PLUGIN_X86_64

    return (diagnoses[0].arith if diagnoses else PLUGIN_X86_64).name


def print_text(map_path, setup, backend: str, diagnoses: Sequence, planner=None, console=None) -> None:
    out = console.print if console is not None else print
    cm, p = setup.costmap, setup.params
    out(f"map      {map_path}: {cm.size_x}x{cm.size_y} cells, {cm.resolution:g} m, costmap layers: "
        f"{', '.join(setup.layers) or 'none'}")
    for n in setup.notes:
        out(f"note     {n}")
    out(f"params   {'A*' if p.use_astar else 'Dijkstra'}, tolerance {p.tolerance:g}, allow_unknown "
        f"{str(p.allow_unknown).lower()}, max_cycles_factor {p.max_cycles_factor} ({backend} backend)")
    judged = f"{planner.label}; " if planner is not None else ""
    out(f"judged   {judged}every step computed in the plugin arithmetic {_arithmetic(diagnoses)}")
    if len(diagnoses) == 1:
        for line in text_lines(diagnoses[0]):
            out(line)
        return
    for i, d in enumerate(diagnoses):
        state = "ok" if d.ok else f"FAILED {d.cause}"
        fix = ""
        if not d.ok and d.fix is not None:
            fix = f"  fix: max_cycles_factor {d.fix.factor}" if d.fix.factor is not None else "  no factor fixes it"
        out(f"{i:4d}  ({d.goal.x:g}, {d.goal.y:g})  {state}{fix}")
    failed = sum(not d.ok for d in diagnoses)
    out(f"{len(diagnoses)} plans, {len(diagnoses) - failed} ok, {failed} failed, "
        f"{sum(d.legal_potential_no_plan for d in diagnoses)} with the #4655 message")


# -------------------------------------------------------------------------------- picture
def check_picture_path(path) -> None:
    if Path(path).suffix.lower() not in PICTURE_FORMATS:
        raise NavfnInputError(f"{path}: the picture must be .png or .svg")


def _costmap_image(costs: np.ndarray) -> np.ndarray:
    """RGB of the master costmap: free white, inflation yellow to red, inscribed purple,
    lethal black, unknown pale blue."""
    c = costs.astype(float)
    rgb = np.ones(costs.shape + (3,))
    mid = (costs > 0) & (costs < 253)
    t = c[mid] / 252.0
    rgb[mid] = np.stack([1.0 - 0.15 * t, 0.95 - 0.75 * t, 0.6 - 0.6 * t], axis=-1)
    rgb[costs == INSCRIBED_INFLATED_OBSTACLE] = (0.55, 0.2, 0.6)
    rgb[costs == LETHAL_OBSTACLE] = (0.0, 0.0, 0.0)
    rgb[costs == NO_INFORMATION] = (0.75, 0.85, 0.95)
    return rgb


def _trap(d):
    """(points up to the exit, the repeating stretch or None) of the unbudgeted extraction."""
    w = d.walk
    if w is None or len(w.points) == 0:
        return None, None
    pts = w.points.astype(float)
    if w.cycle_start is not None:
        return pts[: w.cycle_start + 1], pts[w.cycle_start: w.cycle_start + w.cycle_period + 1]
    return pts, None


def _overlay(ax, d, zoom: bool = False) -> None:
    run = d.run
    path = None if run.path is None or not d.ok else np.asarray(run.path, float)
    if path is not None and len(path):
        ax.plot(path[:, 0], path[:, 1], "-", color="tab:blue", lw=1.4 if not zoom else 1.8, label="path")
    if not d.ok:
        lead, cyc = _trap(d)
        budget = run.max_cycles or 0
        if lead is not None:
            if d.cause == "extraction_exhausted" and d.fix is not None and d.fix.factor is not None:
                ax.plot(lead[:budget, 0], lead[:budget, 1], "-", color="tab:orange", lw=1.6,
                        label=f"calcPath's {budget} points")
                ax.plot(lead[budget - 1:, 0], lead[budget - 1:, 1], "--", color="tab:blue", lw=1.2,
                        label=f"the rest ({len(lead)} in all)")
            else:
                ax.plot(lead[:, 0], lead[:, 1], "-", color="tab:orange", lw=1.4, marker="." if zoom else None,
                        ms=4, label="extraction")
        if cyc is not None:
            ax.plot(cyc[:, 0], cyc[:, 1], "-", color="red", lw=2.2 if not zoom else 1.4, marker="o" if zoom else None,
                    ms=3, label=f"cycle (every {d.walk.cycle_period} iterations)")
            if zoom:
                ax.annotate("", xy=cyc[1], xytext=cyc[0],
                            arrowprops=dict(arrowstyle="->", color="red", lw=2))
    con = d.connectivity
    if con is not None and con.cut:
        cut = np.asarray(con.cut, float)
        ax.plot(cut[:, 0], cut[:, 1], "x", color="red", ms=6 if not zoom else 9, mew=2, label="obstacle cut")
    for cell, style, label in ((run.robot_cell, dict(marker="o", color="limegreen", ms=9), "start (robot)"),
                               (run.target_cell, dict(marker="*", color="gold", ms=14), "goal")):
        if cell is not None:
            ax.plot([cell[0]], [cell[1]], linestyle="none", mec="k", label=label, **style)
    if run.best_cell is not None and run.used_tolerance:
        ax.plot([run.best_cell[0]], [run.best_cell[1]], "D", color="cyan", mec="k", ms=7, label="tolerance pick")
    if d.failing_cell is not None and not d.ok:
        import matplotlib.pyplot as plt

        fx, fy = d.failing_cell
        ax.add_patch(plt.Rectangle((fx - 0.5, fy - 0.5), 1, 1, fill=False, ec="magenta", lw=2.5))
        ax.plot([], [], "s", mfc="none", mec="magenta", mew=2, label="failing cell")


def _window(d, nx: int, ny: int):
    """The zoom window (x0, x1, y0, y1) around the failure, or None when the map is small."""
    if d.ok or d.failing_cell is None or max(nx, ny) <= 60 or d.cause == "extraction_exhausted":
        return None
    pts = []
    lead, cyc = _trap(d)
    least = 10.0
    if cyc is not None:
        pts, least = cyc, 3.0
    elif lead is not None:
        pts = lead[-30:]
    pts = np.vstack([np.asarray(pts, float).reshape(-1, 2), [d.failing_cell]])
    cx, cy = pts.mean(axis=0)
    half = max(least, 0.8 * float(np.ptp(pts[:, 0])), 0.8 * float(np.ptp(pts[:, 1])))
    x0, x1 = max(-0.5, cx - half), min(nx - 0.5, cx + half)
    y0, y1 = max(-0.5, cy - half), min(ny - 0.5, cy + half)
    return x0, x1, y0, y1


def write_picture(path, d, title: str = "") -> None:
    """Costmap, potential and (on large maps) a zoom on the failure, with the path or the trap."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    cm, run = d.costmap, d.run
    nx, ny = cm.size_x, cm.size_y
    win = _window(d, nx, ny)
    panels = 3 if win is not None else 2
    aspect = ny / nx
    w = 5.2
    fig, axes = plt.subplots(1, panels, figsize=(w * panels + 0.6, w * aspect + 1.6), squeeze=False)
    axes = axes[0]
    extent = (-0.5, nx - 0.5, -0.5, ny - 0.5)
    axes[0].imshow(_costmap_image(cm.costs), origin="lower", extent=extent, interpolation="nearest")
    axes[0].set_title("costmap (lethal black, inscribed purple,\nunknown blue, inflation yellow-red)", fontsize=9)
    pot = run.potential
    pot_ax = axes[1]
    if pot is not None:
        shown = np.where(pot < POT_HIGH, pot, np.nan)
        im = pot_ax.imshow(shown, origin="lower", extent=extent, interpolation="nearest", cmap="viridis")
        fig.colorbar(im, ax=pot_ax, fraction=0.046, pad=0.03)
        pot_ax.set_title("potential after propagation (unreached blank)", fontsize=9)
    else:
        pot_ax.imshow(_costmap_image(cm.costs), origin="lower", extent=extent, interpolation="nearest")
        pot_ax.set_title("no propagation ran", fontsize=9)
    for ax in axes[:2]:
        _overlay(ax, d)
        ax.set_xlim(-0.5, nx - 0.5)
        ax.set_ylim(-0.5, ny - 0.5)
    if win is not None:
        ax = axes[2]
        x0, x1, y0, y1 = win
        if pot is not None:
            ax.imshow(np.where(pot < POT_HIGH, pot, np.nan), origin="lower", extent=extent, interpolation="nearest",
                      cmap="viridis", vmin=np.nanmin(_sub(pot, win)), vmax=np.nanmax(_sub(pot, win)))
            ax.imshow(np.where(cm.costs >= LETHAL_OBSTACLE, 1.0, np.nan), origin="lower", extent=extent,
                      interpolation="nearest", cmap="Greys", vmin=0, vmax=1)
        if pot is not None and x1 - x0 <= 16:
            _label_cells(ax, pot, cm.costs, win)
        _overlay(ax, d, zoom=True)
        ax.set_xlim(x0, x1)
        ax.set_ylim(y0, y1)
        ax.set_title("zoom on the failure (potential, lethal black)", fontsize=9)
        for a in axes[:2]:
            a.add_patch(plt.Rectangle((x0, y0), x1 - x0, y1 - y0, fill=False, ec="magenta", lw=1, ls=":"))
    for ax in axes:
        ax.set_xlabel("cell x")
        ax.set_ylabel("cell y")
        ax.tick_params(labelsize=7)
    handles, labels = axes[-1].get_legend_handles_labels()
    uniq = dict(zip(labels, handles))
    fig.legend(uniq.values(), uniq.keys(), loc="lower center", ncol=min(len(uniq), 6), fontsize=8, frameon=False)
    status = "plan found" if d.ok else f"FAILED: {d.cause}"
    if not d.ok and d.fix is not None:
        status += (f"; smallest max_cycles_factor {d.fix.factor}" if d.fix.factor is not None
                   else "; no max_cycles_factor fixes it")
    if d.legal_potential_no_plan:
        status += "  [#4655: legal potential, no plan]"
    fig.suptitle(f"{title}\n{status}".strip(), fontsize=10)
    fig.tight_layout(rect=(0, 0.07, 1, 1))
    _save(fig, path)


def _label_cells(ax, pot: np.ndarray, costs: np.ndarray, win) -> None:
    """Each cell's potential (and cost) written in it, on small zoom windows."""
    x0, x1, y0, y1 = win
    for y in range(max(0, math.ceil(y0)), min(pot.shape[0] - 1, math.floor(y1)) + 1):
        for x in range(max(0, math.ceil(x0)), min(pot.shape[1] - 1, math.floor(x1)) + 1):
            p = float(pot[y, x])
            txt = f"{p:.1f}" if p < POT_HIGH else "unreached"
            ax.text(x, y + 0.12, txt, ha="center", va="center", fontsize=6, color="white")
            ax.text(x, y - 0.22, f"c{int(costs[y, x])}", ha="center", va="center", fontsize=5, color="0.85")


def _sub(pot: np.ndarray, win) -> np.ndarray:
    x0, x1, y0, y1 = win
    s = pot[max(0, int(y0)): int(math.ceil(y1)) + 1, max(0, int(x0)): int(math.ceil(x1)) + 1]
    s = np.where(s < POT_HIGH, s, np.nan)
    return s if np.isfinite(s).any() else np.array([0.0, 1.0])


def write_batch_picture(path, setup, diagnoses: Sequence, title: str = "") -> None:
    """One costmap with every goal of a batch marked by its outcome."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    cm = setup.costmap
    nx, ny = cm.size_x, cm.size_y
    fig, ax = plt.subplots(figsize=(8, 8 * ny / nx + 1.2))
    ax.imshow(_costmap_image(cm.costs), origin="lower", extent=(-0.5, nx - 0.5, -0.5, ny - 0.5),
              interpolation="nearest")
    causes = sorted({d.cause for d in diagnoses})
    colours = plt.get_cmap("tab10")
    for i, cause in enumerate(causes):
        cells = [_goal_cell(cm, d) for d in diagnoses if d.cause == cause]
        pts = np.asarray([p for p in cells if p is not None], float).reshape(-1, 2)
        off = len(cells) - len(pts)
        style = dict(marker="o", color="limegreen") if cause == "ok" else dict(marker="X", color=colours(i % 10))
        ax.plot(pts[:, 0], pts[:, 1], linestyle="none", mec="k", ms=8,
                label=f"{cause} ({len(cells)}{f', {off} off the map' if off else ''})", **style)
    starts = {d.run.start_cell for d in diagnoses if d.run.start_cell is not None}
    for s in starts:
        ax.plot([s[0]], [s[1]], "o", color="white", mec="k", ms=11)
        ax.plot([s[0]], [s[1]], "+", color="k", ms=9)
    ax.plot([], [], "o", color="white", mec="k", label="start")
    ax.set_xlim(-0.5, nx - 0.5)
    ax.set_ylim(-0.5, ny - 0.5)
    ax.set_xlabel("cell x")
    ax.set_ylabel("cell y")
    ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.08), ncol=3, fontsize=8, frameon=False)
    failed = sum(not d.ok for d in diagnoses)
    fig.suptitle(f"{title}\n{len(diagnoses)} goals: {len(diagnoses) - failed} ok, {failed} failed".strip(), fontsize=10)
    fig.tight_layout()
    _save(fig, path)


def _goal_cell(cm, d):
    from ..nav2.plugin import costmap_world_to_map

    return costmap_world_to_map(cm, d.goal.x, d.goal.y)


def _save(fig, path) -> None:
    import matplotlib.pyplot as plt

    try:
        with atomic_path(path, suffix=Path(path).suffix.lower()) as tmp:
            fig.savefig(tmp, dpi=110)
    finally:
        plt.close(fig)
