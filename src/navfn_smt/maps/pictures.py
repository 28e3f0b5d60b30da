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
ARROW_LIMIT = 60  # draw gradient arrows on maps up to this many cells a side


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


def render_case(
    costs: np.ndarray,
    result: PlanResult,
    start: tuple[int, int],
    goal: tuple[int, int],
    out: str,
    title: str = "",
    highlight: Optional[Sequence[tuple[float, float]]] = None,
    arrows: Optional[bool] = None,
) -> None:
    """Draw the case and write ``out`` (.png or .svg) whole or not at all."""
    ext = Path(out).suffix.lower()
    if ext not in FORMATS:
        raise NavfnInputError(f"{out}: the picture must be .png or .svg")
    if not Path(out).resolve().parent.is_dir():
        raise NavfnInputError(f"{out}: directory {Path(out).resolve().parent} does not exist")
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.colors import ListedColormap

    ny, nx = costs.shape
    pot = np.asarray(result.potential, dtype=np.float32).reshape(ny, nx)
    if arrows is None:
        arrows = max(nx, ny) <= ARROW_LIMIT
    scale = max(4.0, min(9.0, 9.0 * max(nx, ny) / 40))
    fig, axes = plt.subplots(1, 2, figsize=(2 * scale * nx / max(nx, ny) + 2.5, scale * ny / max(nx, ny) + 1.2))
    extent = (-0.5, nx - 0.5, ny - 0.5, -0.5)
    c = costs.astype(float)
    lethal = costs >= COST_OBS
    ax = axes[0]
    ax.imshow(np.where(lethal, np.nan, c), cmap="Greys", vmin=0, vmax=300, extent=extent, interpolation="nearest")
    ax.imshow(np.where(lethal, 1.0, np.nan), cmap=ListedColormap(["black"]), extent=extent, interpolation="nearest")
    ax.set_title("costs (lethal black)")
    ax = axes[1]
    reached = pot < POT_HIGH
    shown = np.where(reached, pot, np.nan)
    im = ax.imshow(shown, cmap="viridis", extent=extent, interpolation="nearest")
    ax.imshow(np.where(lethal, 1.0, np.nan), cmap=ListedColormap(["black"]), extent=extent, interpolation="nearest")
    fig.colorbar(im, ax=ax, fraction=0.046, pad=0.04, label="potential")
    ax.set_title("potential (unreached blank)")
    if arrows:
        gx, gy = gradient_field(pot)
        ys, xs = np.nonzero((gx != 0) | (gy != 0))
        # gradCell's vector points downhill (positive = right and down), as extraction moves
        axes[1].quiver(xs, ys, gx[ys, xs], gy[ys, xs], angles="xy", scale_units="xy", scale=2.2,
                       color="white", width=0.004, alpha=0.8)
    path = np.asarray(result.path, dtype=float).reshape(-1, 2)
    for ax in axes:
        if len(path):
            ax.plot(path[:, 0], path[:, 1], "-", color="tab:red", lw=1.6, marker=".", ms=3, label="path")
        ax.plot([start[0]], [start[1]], "o", color="tab:orange", ms=8, mec="k", label="start")
        ax.plot([goal[0]], [goal[1]], "*", color="gold", ms=12, mec="k", label="goal")
        if highlight:
            h = np.asarray(highlight, dtype=float).reshape(-1, 2)
            if len(h) == 1:
                ax.add_patch(plt.Rectangle((h[0, 0] - 0.5, h[0, 1] - 0.5), 1, 1, fill=False, ec="magenta", lw=2.5))
            else:
                ax.plot(h[:, 0], h[:, 1], "-", color="magenta", lw=3, label="highlight")
        ax.set_xlim(-0.5, nx - 0.5)
        ax.set_ylim(ny - 0.5, -0.5)
        ax.set_xlabel("x")
        ax.set_ylabel("y")
        if max(nx, ny) <= 30:
            ax.set_xticks(range(nx))
            ax.set_yticks(range(ny))
            ax.tick_params(labelsize=7)
    axes[0].legend(loc="upper right", fontsize=7, framealpha=0.8)
    status = f"path: {len(path)} points" if len(path) else f"no path ({result.exit.value if result.exit else '?'})"
    fig.suptitle(f"{title}  start {tuple(start)} goal {tuple(goal)}  {status}".strip(), fontsize=10)
    fig.tight_layout()
    try:
        with atomic_path(out, suffix=ext) as tmp:
            fig.savefig(tmp, dpi=110)
    finally:
        plt.close(fig)
