"""Pictures of a planning case (``navfn-smt render``), in the spirit of the paper's figures.

One figure with two panels: the costmap (grey levels for costs, lethal cells black) and
the potential after propagation (a heat map, unreached cells blank), both with the path,
the start and goal cells, the gradient that path extraction follows (arrows, on maps small
enough to read them) and optionally a highlighted cell or segment (a counterexample).
Coordinates are NavFn's: x to the right, y down, cell (x, y) centred on integer (x, y).
"""

from __future__ import annotations

from pathlib import Path
from typing import Optional, Sequence

import numpy as np

from ..errors import NavfnInputError
from ..fileio import atomic_path
from ..spec import kernels as K
from ..spec.constants import COST_OBS, POT_HIGH
from ..spec.numeric import CONCRETE
from ..spec.planner import PlanResult

FORMATS = (".png", ".svg")
ARROW_LIMIT = 60  # draw gradient arrows when the picture shows up to this many cells a side


def gradient_field(potential: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """``gradCell`` of every interior cell (the vectors calcPath interpolates), via the spec kernel."""
    ny, nx = potential.shape
    p = potential.astype(np.float32)
    gx = np.zeros_like(p)
    gy = np.zeros_like(p)
    for y in range(1, ny - 1):
        for x in range(1, nx - 1):
            gx[y, x], gy[y, x] = K.grad_cell(
                CONCRETE, float(p[y, x]), float(p[y, x - 1]), float(p[y, x + 1]), float(p[y - 1, x]), float(p[y + 1, x])
            )
    return gx, gy


ZOOM_MIN_MAP = 80  # maps at most this many cells a side are always drawn whole
ZOOM_MARGIN = 12  # cells shown around the case's bounding box when zoomed


def view_window(nx: int, ny: int, points: np.ndarray, zoom: str = "auto") -> Optional[tuple[int, int, int, int]]:
    """The cells ``(x0, x1, y0, y1)`` (inclusive) a picture shows, or None for the whole map.

    ``zoom="auto"`` zooms to the neighbourhood of ``points`` (start, goal, path, highlight)
    when the map is larger than :data:`ZOOM_MIN_MAP` cells a side and that neighbourhood
    (the points' bounding box with a margin of :data:`ZOOM_MARGIN` cells or half its size)
    covers less than half the map either way; ``"full"`` never zooms."""
    if zoom == "full" or max(nx, ny) <= ZOOM_MIN_MAP or not len(points):
        return None
    lo, hi = np.floor(points.min(axis=0)), np.ceil(points.max(axis=0))
    margin = max(ZOOM_MARGIN, int(0.5 * max(hi - lo)))
    side = int(max(hi - lo)) + 2 * margin  # a square window, centred on the box
    cx, cy = (lo + hi) / 2
    if side >= 0.5 * nx and side >= 0.5 * ny:
        return None

    def span(c: float, n: int) -> tuple[int, int]:
        a = int(round(c - side / 2))
        a = min(max(a, 0), max(n - side - 1, 0))
        return a, min(a + side, n - 1)

    x0, x1 = span(cx, nx)
    y0, y1 = span(cy, ny)
    return x0, x1, y0, y1


def render_case(
    costs: np.ndarray,
    result: PlanResult,
    start: tuple[int, int],
    goal: tuple[int, int],
    out: str,
    title: str = "",
    highlight: Optional[Sequence[tuple[float, float]]] = None,
    arrows: Optional[bool] = None,
    zoom: str = "auto",
) -> Optional[tuple[int, int, int, int]]:
    """Draw the case and write ``out`` (.png or .svg) whole or not at all; the window of
    cells shown ``(x0, x1, y0, y1)``, or None when the whole map is.

    ``zoom``: ``auto`` draws only the neighbourhood of the case on a large map when the case
    is small against it (:func:`view_window`), ``full`` the whole map; ``arrows`` None draws
    gradient arrows when the cells shown are at most :data:`ARROW_LIMIT` a side."""
    ext = Path(out).suffix.lower()
    if ext not in FORMATS:
        raise NavfnInputError(f"{out}: the picture must be .png or .svg")
    if not Path(out).resolve().parent.is_dir():
        raise NavfnInputError(f"{out}: directory {Path(out).resolve().parent} does not exist")
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.colors import ListedColormap
    from matplotlib.lines import Line2D

    ny, nx = costs.shape
    pot = np.asarray(result.potential, dtype=np.float32).reshape(ny, nx)
    path = np.asarray(result.path, dtype=float).reshape(-1, 2)
    h = np.asarray(highlight, dtype=float).reshape(-1, 2) if highlight else np.zeros((0, 2))
    window = view_window(nx, ny, np.vstack([np.array([start, goal], dtype=float), path, h]), zoom)
    x0, x1, y0, y1 = window or (0, nx - 1, 0, ny - 1)
    wx, wy = x1 - x0 + 1, y1 - y0 + 1
    if arrows is None:
        arrows = max(wx, wy) <= ARROW_LIMIT
    scale = max(4.0, min(9.0, 9.0 * max(wx, wy) / 40))
    fig, axes = plt.subplots(1, 2, figsize=(2 * scale * wx / max(wx, wy) + 3.4, scale * wy / max(wx, wy) + 1.6))
    extent = (-0.5, nx - 0.5, ny - 0.5, -0.5)
    c = costs.astype(float)
    lethal = costs >= COST_OBS
    ax = axes[0]
    cim = ax.imshow(np.where(lethal, np.nan, c), cmap="Greys", vmin=0, vmax=300, extent=extent,
                    interpolation="nearest")
    ax.imshow(np.where(lethal, 1.0, np.nan), cmap=ListedColormap(["black"]), extent=extent, interpolation="nearest")
    cbar = fig.colorbar(cim, ax=ax, fraction=0.046, pad=0.04, label=f"cost (lethal {COST_OBS}: black)")
    cbar.ax.set_ylim(0, COST_OBS - 1)  # the passable costs; lethal ones are black on the map
    cbar.set_ticks([0, 50, 100, 150, 200, COST_OBS - 1])
    ax.set_title("costs")
    ax = axes[1]
    reached = pot < POT_HIGH
    shown = np.where(reached, pot, np.nan)
    inside = shown[y0:y1 + 1, x0:x1 + 1]
    finite = inside[np.isfinite(inside)]
    im = ax.imshow(shown, cmap="viridis", extent=extent, interpolation="nearest",
                   vmin=float(finite.min()) if len(finite) else None, vmax=float(finite.max()) if len(finite) else None)
    ax.imshow(np.where(lethal, 1.0, np.nan), cmap=ListedColormap(["black"]), extent=extent, interpolation="nearest")
    fig.colorbar(im, ax=ax, fraction=0.046, pad=0.04, label="potential")
    ax.set_title("potential (unreached: white)")
    if arrows:
        gx, gy = gradient_field(pot[max(y0 - 1, 0):y1 + 2, max(x0 - 1, 0):x1 + 2])
        ys, xs = np.nonzero((gx != 0) | (gy != 0))
        ox, oy = max(x0 - 1, 0), max(y0 - 1, 0)
        # gradCell's vector points downhill (positive = right and down), as extraction moves
        axes[1].quiver(xs + ox, ys + oy, gx[ys, xs], gy[ys, xs], angles="xy", scale_units="xy", scale=2.2,
                       color="white", width=0.004, alpha=0.8)
    handles = []
    for ax in axes:
        if len(path):
            ax.plot(path[:, 0], path[:, 1], "-", color="tab:red", lw=1.6, marker=".", ms=3)
        ax.plot([start[0]], [start[1]], "o", color="tab:orange", ms=8, mec="k")
        ax.plot([goal[0]], [goal[1]], "*", color="gold", ms=12, mec="k")
        if len(h) == 1:
            ax.add_patch(plt.Rectangle((h[0, 0] - 0.5, h[0, 1] - 0.5), 1, 1, fill=False, ec="magenta", lw=2.5))
        elif len(h):
            ax.plot(h[:, 0], h[:, 1], "-", color="magenta", lw=3)
        ax.set_xlim(x0 - 0.5, x1 + 0.5)
        ax.set_ylim(y1 + 0.5, y0 - 0.5)
        ax.set_xlabel("x")
        ax.set_ylabel("y")
        if max(wx, wy) <= 30:
            ax.set_xticks(range(x0, x1 + 1))
            ax.set_yticks(range(y0, y1 + 1))
            ax.tick_params(labelsize=7)
    if len(path):
        handles.append(Line2D([], [], color="tab:red", lw=1.6, marker=".", ms=3, label="path"))
    handles.append(Line2D([], [], ls="", marker="o", color="tab:orange", ms=8, mec="k", label="start"))
    handles.append(Line2D([], [], ls="", marker="*", color="gold", ms=12, mec="k", label="goal"))
    if len(h) == 1:
        handles.append(Line2D([], [], ls="", marker="s", mfc="none", mec="magenta", ms=10, mew=2.5,
                              label="highlight"))
    elif len(h):
        handles.append(Line2D([], [], color="magenta", lw=3, label="highlight"))
    # the legend sits under the panels, where it cannot hide a cell of the map
    fig.legend(handles=handles, loc="lower center", ncol=len(handles), fontsize=8, frameon=False)
    status = f"path: {len(path)} points" if len(path) else f"no path ({result.exit.value if result.exit else '?'})"
    where = (f"\nshowing x {x0}..{x1}, y {y0}..{y1} of the {nx}x{ny} map (--zoom full: the whole map)"
             if window else "")
    fig.suptitle(f"{title}  start {tuple(start)} goal {tuple(goal)}  {status}".strip() + where, fontsize=10)
    fig.tight_layout(rect=(0, 0.05, 1, 1))
    try:
        with atomic_path(out, suffix=ext) as tmp:
            fig.savefig(tmp, dpi=110)
    finally:
        plt.close(fig)
    return window
