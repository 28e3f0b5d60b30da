"""NavFn's cost model: translation of ROS costmap values and the lethal border.

``set_costmap`` is ``NavFn::setCostmap``; ``add_border`` is the part of
``NavFn::setupNavFn`` that overwrites the outermost rows and columns with COST_OBS.
"""

from __future__ import annotations

import numpy as np

from .constants import COST_FACTOR, COST_NEUTRAL, COST_OBS, COST_OBS_ROS, COST_UNKNOWN_ROS


def translate_cost(v: int, allow_unknown: bool = True, ros: bool = True) -> int:
    """One cell of ``setCostmap``.

    ROS branch: values below 253 become ``COST_NEUTRAL + COST_FACTOR * v`` (double
    arithmetic, truncated to int by the assignment, capped at COST_OBS - 1); 253 and
    254 become COST_OBS; 255 (unknown) becomes COST_OBS - 1 when ``allow_unknown`` and
    COST_OBS otherwise.  The PGM branch (``ros=False``) treats 255 as COST_OBS - 1
    always (its border handling is in :func:`set_costmap`).
    """
    if not 0 <= v <= 255:
        raise ValueError(f"cost {v} is not an unsigned char")
    if v < COST_OBS_ROS:
        t = int(COST_NEUTRAL + COST_FACTOR * v)  # double, truncated toward zero
        return COST_OBS - 1 if t >= COST_OBS else t
    if v == COST_UNKNOWN_ROS and (allow_unknown or not ros):
        return COST_OBS - 1
    return COST_OBS


_LUT_ROS = np.array([translate_cost(v, True) for v in range(256)], dtype=np.uint8)
_LUT_ROS_NO_UNKNOWN = np.array([translate_cost(v, False) for v in range(256)], dtype=np.uint8)
_LUT_PGM = np.array([translate_cost(v, True, ros=False) for v in range(256)], dtype=np.uint8)


def set_costmap(cmap: np.ndarray, is_ros: bool = True, allow_unknown: bool = True) -> np.ndarray:
    """``NavFn::setCostmap`` on a (height, width) array of unsigned chars.

    The non-ROS (PGM) branch also makes a 7-cell frame lethal, as the C++ does
    (``i < 7 || i > ny - 8 || j < 7 || j > nx - 8``).
    """
    c = np.asarray(cmap, dtype=np.uint8)
    if c.ndim != 2:
        raise ValueError("costmap must be two-dimensional (height, width)")
    if is_ros:
        return (_LUT_ROS if allow_unknown else _LUT_ROS_NO_UNKNOWN)[c]
    out = _LUT_PGM[c]
    ny, nx = c.shape
    rows = np.arange(ny)[:, None]
    cols = np.arange(nx)[None, :]
    frame = (rows < 7) | (rows > ny - 8) | (cols < 7) | (cols > nx - 8)
    out[frame] = COST_OBS
    return out


def add_border(costs: np.ndarray) -> np.ndarray:
    """The lethal frame ``setupNavFn`` writes: first/last row and column become COST_OBS.

    ``costs`` is a (height, width) array; a new array is returned.
    """
    out = np.array(costs, dtype=np.uint8, copy=True)
    out[0, :] = COST_OBS
    out[-1, :] = COST_OBS
    out[:, 0] = COST_OBS
    out[:, -1] = COST_OBS
    return out
