"""What a whole-map sweep (:mod:`navfn_smt.diagnose.sweep`) reports, from the result it is given: a picture of every goal's
outcome over the costmap, a path-length heat map, and the JSON summary."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np

from ..errors import NavfnInputError
from ..fileio import atomic_path, atomic_write_text
from ..spec.constants import INSCRIBED_INFLATED_OBSTACLE, NO_INFORMATION

# outcome -> (colour, legend label); the costmap stays visible under the goals
COLOURS = {
    "ok": ("#2ca02c", "plan"),
    "ok_tolerance": ("#ffbf00", "plan, needs the tolerance search"),
    "same_pose": ("#1f77b4", "goal at the start (one pose)"),
    "no_legal": ("#d62728", "no path: nothing legal within tolerance"),
    "legal_no_plan": ("#ff00ff", "no path: legal potential, calcPath fails (#4655)"),
    "goal_occupied": ("#7f3f00", "GoalOccupied"),
    "goal_outside": ("#7f7f7f", "GoalOutsideMapBounds"),
    "start_outside": ("#404040", "StartOutsideMapBounds"),
    "undefined_behaviour": ("#00e5ff", "undefined behaviour"),
}


def _background(costs: np.ndarray) -> np.ndarray:
    """Costmap as RGB: free white, costs darker grey, lethal black, unknown pale blue."""
    c = costs.astype(np.float64)
    g = 1.0 - 0.55 * np.clip(c, 0, 252) / 252.0
    g = np.where(costs >= INSCRIBED_INFLATED_OBSTACLE, 0.0, g)
    rgb = np.repeat(g[..., None], 3, axis=2)
    rgb[costs == INSCRIBED_INFLATED_OBSTACLE] = (0.25, 0.25, 0.25)
    rgb[costs == NO_INFORMATION] = (0.75, 0.82, 0.95)
    return rgb


def render_sweep(res, costs: np.ndarray, origin: tuple, out, title: str = "") -> None:
    """Two panels over the costmap: each goal's outcome (colours, counts in the legend) and
    the path length of every planned goal; the robot's pose marked.  ``out`` .png or .svg.
    ``res`` is a sweep's result: its ``counts()`` name the outcomes in the order of their codes."""
    if Path(out).suffix.lower() not in (".png", ".svg"):
        raise NavfnInputError(f"{out}: the picture must be .png or .svg")
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.colors import to_rgb
    from matplotlib.lines import Line2D
    from matplotlib.patches import Patch

    ny, nx = costs.shape
    r = res.resolution
    ext = (origin[0], origin[0] + nx * r, origin[1], origin[1] + ny * r)  # cell i spans [o+i*r, o+(i+1)*r)
    bg = _background(costs)
    xs, ys = res.cells[:, 0], res.cells[:, 1]
    over = bg.copy()
    counts = res.counts()
    outcomes = list(counts)
    for k, name in enumerate(outcomes):
        sel = res.outcome == k
        if sel.any():
            over[ys[sel], xs[sel]] = 0.35 * bg[ys[sel], xs[sel]] + 0.65 * np.array(to_rgb(COLOURS[name][0]))
    length = np.full((ny, nx), np.nan)
    planned = np.isin(res.outcome, [outcomes.index("ok"), outcomes.index("ok_tolerance")])
    length[ys[planned], xs[planned]] = res.path_length[planned]

    side = 6.5 if max(nx, ny) >= 100 else 5.0
    fig, axes = plt.subplots(1, 2, figsize=(2 * side + 1.5, side + 2.2))
    fig.subplots_adjust(left=0.06, right=0.97, top=0.88, bottom=0.24, wspace=0.18)
    a0, a1 = axes
    a0.imshow(over, origin="lower", extent=ext, interpolation="nearest")
    a0.set_title("outcome per goal cell")
    handles = [Patch(color=COLOURS[n][0], label=f"{COLOURS[n][1]}: {counts[n]}") for n in outcomes if counts[n]]
    handles.append(Patch(facecolor="black", label="lethal / inscribed (costmap)"))
    if (costs == NO_INFORMATION).any():
        handles.append(Patch(facecolor=(0.75, 0.82, 0.95), label="unknown (costmap)"))
    handles.append(Line2D([], [], marker="*", markersize=14, color="white", markeredgecolor="black",
                          linestyle="none", label="robot (the start of every plan)"))
    fig.legend(handles=handles, loc="lower center", bbox_to_anchor=(0.5, 0.01), ncol=3, fontsize=9, frameon=False)
    a1.imshow(bg, origin="lower", extent=ext, interpolation="nearest")
    im = a1.imshow(length, origin="lower", extent=ext, interpolation="nearest", cmap="viridis")
    a1.set_title("path length of planned goals (m)")
    fig.colorbar(im, ax=a1, shrink=0.85, pad=0.02)
    for a in axes:
        a.plot([res.start.x], [res.start.y], marker="*", markersize=18, color="white", markeredgecolor="black",
               markeredgewidth=1.2, linestyle="none", label="robot")
        a.set_xlabel("x (m)")
        a.set_ylabel("y (m)")
    mode = "A*" if res.mode == "astar" else "Dijkstra"
    what = (f"sweep from the robot at ({res.start.x:.3f}, {res.start.y:.3f}), {mode}, "
            f"tolerance {res.params.tolerance:g}: {len(res)} goals")
    fig.suptitle(f"{title}: {what}" if title else what)
    with atomic_path(out, suffix=Path(out).suffix) as tmp:
        fig.savefig(tmp, dpi=110)
    plt.close(fig)


def write_summary_json(path, doc: dict) -> None:
    """A sweep's summary (:func:`navfn_smt.diagnose.sweep.summary`) as one JSON document."""
    atomic_write_text(path, json.dumps(doc, indent=1))
