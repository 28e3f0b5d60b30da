"""The passable regions of a NavFn cost array, and whether the wave can reach a start.

Stated once, for every part that asks: the generators (one region per map), the judges of
the whole-planner checks, the counterexample search's screen of unreached starts, and the
diagnosis of a failed plan.  A region is a 4-connected set of cells of cost below COST_OBS
(``updateCell`` and the ``push_*`` guards pass nothing else); the labelling is
``scipy.ndimage.label``'s.
"""

from __future__ import annotations

import numpy as np
from scipy import ndimage

from ..spec.constants import COST_OBS

# the four neighbours NavFn's wave moves to (n +- 1, n +- nx)
FOUR_NEIGHBOURS = np.array([[0, 1, 0], [1, 1, 1], [0, 1, 0]], dtype=bool)


def regions(costs) -> np.ndarray:
    """Label per cell of the (ny, nx) cost array: 1, 2, ... per region (numbered in row-major
    order of their first cell), 0 on cells of cost COST_OBS or more."""
    labels, _ = ndimage.label(np.asarray(costs) < COST_OBS, structure=FOUR_NEIGHBOURS)
    return labels.astype(np.int32)


def reaches(labels: np.ndarray, start, goal) -> bool:
    """Whether propagation from ``goal`` can reach ``start``: a 4-connected chain of cells from
    the goal to the start, every cell but the goal passable (``initCost`` does not look at the
    goal's cost).  ``labels`` from :func:`regions` of the same array."""
    return bool(reaches_all(labels, np.array([[start[0], start[1], goal[0], goal[1]]])).item())


def reaches_all(labels: np.ndarray, cases) -> np.ndarray:
    """:func:`reaches` for every ``(sx, sy, gx, gy)`` row of ``cases``."""
    cases = np.asarray(cases, dtype=np.int64).reshape(-1, 4)
    ny, nx = labels.shape
    sx, sy, gx, gy = cases.T
    own = labels[sy, sx]
    out = (sx == gx) & (sy == gy)
    for dx, dy in ((1, 0), (-1, 0), (0, 1), (0, -1)):
        x, y = gx + dx, gy + dy
        on = (x >= 0) & (x < nx) & (y >= 0) & (y < ny)
        out |= on & (own > 0) & (labels[np.where(on, y, 0), np.where(on, x, 0)] == own)
    return out
