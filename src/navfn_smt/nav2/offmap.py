"""Where ``NavfnPlanner``'s own code (not NavFn's) misbehaves: the plugin's double arithmetic
about points on and off the map, and about the tolerance loop.

All the plugin's arithmetic is double; Python's ``float`` is the same IEEE binary64 with the same
rounding, so what is computed here is exact.  Z3 finds and proves the same facts over ``Float64``
(:mod:`navfn_smt.smt.offmap`); the findings are exercised end to end by the case directories
of ``tests/data/plugin_cases`` (built by ``tests/plugin_cases.py``).

* :func:`offmap`: a world coordinate that passes ``Costmap2D::worldToMap`` (the truncating one
  ``createPlan`` checks) but fails ``NavfnPlanner::worldToMap`` (the rounding one ``makePlan``
  uses unchecked); :func:`offmap_interval_numeric` the exact interval ``[lo, hi)`` of them.
* :func:`centre_cells`: the cell the plugin rounds each cell's centre to.
* :func:`loop_cells`: the cells the tolerance loop visits on one axis (20 points for Nav2's
  defaults, tolerance 0.5 and resolution float32(0.05): the window is one-sided).
"""

from __future__ import annotations

import math

import numpy as np

from .plugin import costmap_axis_cell, plugin_axis_cell

RES = float(np.float32(0.05))  # "resolution: 0.05" in a map YAML, as the costmap holds it


# --------------------------------------------------------------------------- doubles in order
def next_up(x: float) -> float:
    return math.nextafter(x, math.inf)


def next_down(x: float) -> float:
    return math.nextafter(x, -math.inf)


def hexf(x: float) -> str:
    return float(x).hex()


# --------------------------------------------------------------------------- the two worldToMap
def passes_truncating(w: float, origin: float, res: float, size: int) -> bool:
    """``Costmap2D::worldToMap`` on one axis (the quotient below 2^32, where the cast is defined)."""
    return costmap_axis_cell(w, origin, res, size) is not None


def rounds_off(w: float, origin: float, res: float, size: int) -> bool:
    """``NavfnPlanner::worldToMap`` fails on this axis although ``w >= origin`` (std::round = half away)."""
    return plugin_axis_cell(w, origin, res) >= size


def offmap(w: float, origin: float, res: float, size: int) -> bool:
    """Passes createPlan's bounds check, rounds one past the edge in makePlan."""
    return passes_truncating(w, origin, res, size) and rounds_off(w, origin, res, size)


def offmap_interval_numeric(origin: float, res: float, size: int) -> tuple[float, float]:
    """``[lo, hi)`` by walking the doubles around the real-number ends ``o + (size - 1/2) res`` and
    ``o + size res`` (exact: Python floats are binary64 with RNE)."""
    def first_true(x):  # smallest double >= some start where offmap holds, from an estimate
        while offmap(x, origin, res, size):
            x = next_down(x)
        while not offmap(x, origin, res, size):
            x = next_up(x)
        return x

    lo = first_true(origin + (size - 0.5) * res)
    hi = origin + size * res
    while offmap(hi, origin, res, size):
        hi = next_up(hi)
    while not offmap(next_down(hi), origin, res, size):
        hi = next_down(hi)
    return lo, hi


# --------------------------------------------------------------------------- cell centres
def centre_cells(origin: float, res: float, size: int) -> np.ndarray:
    """For each cell ``i``, the cell ``NavfnPlanner::worldToMap`` gives its centre
    ``origin + (i + 0.5) * res`` (computed in double): ``i + 1`` when the quotient comes out at
    ``i + 0.5`` or above, ``i`` when rounding made it fall below."""
    return np.array([plugin_axis_cell(origin + (i + 0.5) * res, origin, res) for i in range(size)], dtype=np.int64)


# --------------------------------------------------------------------------- the tolerance loop
def loop_cells(g: float, tolerance: float, origin: float, res: float) -> list:
    """The cells (one axis, std::round, off-map ones included) the tolerance loop's points round to."""
    from .plugin import tolerance_steps

    return [plugin_axis_cell(p, origin, res) for p in tolerance_steps(g - tolerance, g + tolerance, res).tolist()]
