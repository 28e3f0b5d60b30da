"""``NavFn::calcPath`` run without a cycle budget, to its exit or to a repeated state.

calcPath is a pure function of the potential: the gradients it caches (``gradCell``) are
recomputed to the same values, so what one iteration does depends only on

    (stc, dx, dy)                      the cell and the float offsets in it,
    the last two points written        the oscillation test compares the new point with
                                       the point two before it (``pathx[npath - 3]``).

When that state repeats, every later iteration repeats too: the extraction cycles forever
and no ``max_cycles`` makes it reach the goal.  When it stops instead, it stops at the same
iteration whatever the budget, so the budget decides only whether it gets there: a path of
``L`` points (the goal point included) needs ``calcPath(n)`` with ``n >= L``.

The iteration is :func:`navfn_smt.spec.extraction.calc_path` itself, with a watch that keeps
the points, the grid-following steps and the states seen.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Optional

import numpy as np

from ..spec.extraction import ExtractionExit, UndefinedBehaviour, calc_path

UB = "undefined_behaviour"  # the exit the spec refuses (a read outside potarr)
UNDECIDED = "undecided"  # neither an exit nor a repeated state within the step cap
DEFAULT_MAX_STEPS = 400_000


@dataclass
class Walk:
    """calcPath iterated without a budget (``max_steps`` iterations at most)."""

    exit: str  # an ExtractionExit value, "cycle", UB or UNDECIDED
    iterations: int  # iterations started before the exit (the exiting one included)
    points: np.ndarray  # (M, 2) float32: every point written, in order (the goal point last on success)
    path_length: Optional[int] = None  # calcPath's return value on success (npath, goal point included)
    cycle_start: Optional[int] = None  # first iteration of the repeating stretch (0-based)
    cycle_period: Optional[int] = None  # iterations per repetition
    fallbacks: list = field(default_factory=list)  # iterations that followed the grid (lowest of eight)
    oscillations: list = field(default_factory=list)  # iterations whose oscillation test fired
    exit_cell: Optional[tuple[int, int]] = None  # stc at the exit (the cell the exit is about)
    detail: str = ""

    @property
    def cycles(self) -> bool:
        return self.exit == "cycle"


class _Repeat(Exception):
    """The state of iteration ``i`` is the state of iteration ``first``."""


class _Watch:
    """Keeps the walk's record and stops the run when a state repeats."""

    def __init__(self):
        self.seen: dict = {}
        self.fallbacks: list = []
        self.oscillations: list = []
        self.i, self.stc, self.xs, self.ys = -1, -1, [], []

    def iteration(self, i, stc, dx, dy, xs, ys):
        self.i, self.stc, self.xs, self.ys = i, stc, xs, ys
        if len(xs) >= 2:
            key = (stc, dx, dy, xs[-2], ys[-2], xs[-1], ys[-1])
            first = self.seen.setdefault(key, i)
            if first != i:
                raise _Repeat(first, i)

    def fallback(self, i, oscillation):
        self.fallbacks.append(i)
        if oscillation:
            self.oscillations.append(i)


_DETAILS = {
    "out_of_bounds": "the path reached the first or last row",
    "high_potential": "grid-following landed on an unreached cell",
    "zero_gradient": "the interpolated gradient is exactly (0, 0)",
}


def walk_extraction(potential: np.ndarray, start: tuple[int, int], goal: tuple[int, int],
                    max_steps: int = DEFAULT_MAX_STEPS, arith=None) -> Walk:
    """``calcPath(infinity)`` from NavFn's start cell ``start`` towards its goal ``goal`` on a
    (ny, nx) float32 potential: the exit it takes, or the cycle it enters.  The iteration is the
    spec's own :func:`~navfn_smt.spec.extraction.calc_path`, watched, in the NavFn arithmetic
    ``arith`` (None: x86-64's)."""
    pot_arr = np.asarray(potential, dtype=np.float32)
    ny, nx = pot_arr.shape
    watch = _Watch()
    w = Walk(exit=UNDECIDED, iterations=max_steps, points=np.zeros((0, 2), np.float32))
    try:
        ext = calc_path(pot_arr.ravel().tolist(), nx, ny, tuple(start), tuple(goal), max_steps, watch=watch,
                        arith=arith)
    except _Repeat as r:
        first, i = r.args
        w.exit, w.iterations, w.cycle_start, w.cycle_period = "cycle", i, first, i - first
        w.detail, cell = f"iteration {i} repeats the state of iteration {first}", watch.stc
    except UndefinedBehaviour as e:
        w.exit, w.iterations, w.detail, cell = UB, watch.i + 1, str(e), watch.stc
    else:
        cell = ext.cell
        if ext.exit is ExtractionExit.EXHAUSTED:
            w.detail = f"no exit and no repeated state in {max_steps} iterations"
        else:
            w.exit, w.iterations, w.detail = ext.exit.value, watch.i + 1, _DETAILS.get(ext.exit.value, "")
            if ext.exit is ExtractionExit.NEAR_GOAL:
                w.path_length = len(ext.path)
    w.exit_cell = (cell % nx, cell // nx)
    w.points = np.array(list(zip(watch.xs, watch.ys)), dtype=np.float32).reshape(-1, 2)
    w.fallbacks, w.oscillations = watch.fallbacks, watch.oscillations
    return w
