"""Validation of what a user hands the planner (kept apart from the specification itself,
which states NavFn's behaviour on valid input only)."""

from __future__ import annotations

import numpy as np

from .errors import NavfnInputError


def check_inputs(costs: np.ndarray, start, goal) -> np.ndarray:
    """Validate a (height, width) cost array and two cells; returns the array as uint8."""
    arr = np.asarray(costs)
    if arr.ndim != 2:
        raise NavfnInputError(f"the cost map must be two-dimensional, got shape {arr.shape}")
    ny, nx = arr.shape
    if nx < 3 or ny < 3:
        raise NavfnInputError(f"the map is {nx}x{ny}; NavFn needs at least 3x3 cells")
    if arr.dtype != np.uint8:
        if not np.issubdtype(arr.dtype, np.integer) or arr.min() < 0 or arr.max() > 255:
            raise NavfnInputError("costs must be integers 0..255")
        arr = arr.astype(np.uint8)
    for name, cell in (("start", start), ("goal", goal)):
        x, y = int(cell[0]), int(cell[1])
        if not (0 <= x < nx and 0 <= y < ny):
            raise NavfnInputError(f"{name} ({x}, {y}) is off the {nx}x{ny} map")
    return arr


# The largest map any loader accepts, in cells: refused with one line before anything of that
# size is allocated (a header or a test.txt claiming 100000x100000 is refused from its numbers).
# NavFn itself keeps about 30 bytes a cell (costs, potentials, queues, the gradient), and the
# loaders a few arrays more, so 100 M cells is some gigabytes: larger maps are not planned here.
MAX_CELLS = 100_000_000


def check_cells(width: int, height: int, where: str) -> None:
    """Refuse a map of more than :data:`MAX_CELLS` cells (``where`` names the input)."""
    if width * height > MAX_CELLS:
        raise NavfnInputError(f"{where}: a {width}x{height} map has {width * height} cells; the limit is "
                              f"{MAX_CELLS} cells (100 M)")
