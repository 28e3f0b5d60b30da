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

The iteration below is :func:`navfn_smt.spec.extraction.calc_path` (same kernels, same
concrete float32/double domain, same order of tests), with the points, the grid-following
steps and the state kept; the tests hold the two equal.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Optional

import numpy as np

from ..spec import kernels as K
from ..spec.constants import PATH_STEP
from ..spec.numeric import CONCRETE as D

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


def walk_extraction(potential: np.ndarray, start: tuple[int, int], goal: tuple[int, int],
                    max_steps: int = DEFAULT_MAX_STEPS) -> Walk:
    """``calcPath(infinity)`` from NavFn's start cell ``start`` towards its goal ``goal`` on a
    (ny, nx) float32 potential: the exit it takes, or the cycle it enters."""
    pot_arr = np.asarray(potential, dtype=np.float32)
    ny, nx = pot_arr.shape
    ns = nx * ny
    pot = pot_arr.ravel().tolist()
    grads: dict = {}  # gradCell's cache: a pure function of the potential
    step = D.f32const(PATH_STEP)
    stc = start[1] * nx + start[0]
    dx = dy = D.f32const(0.0)
    xs: list = []
    ys: list = []
    seen: dict = {}
    w = Walk(exit=UNDECIDED, iterations=0, points=np.zeros((0, 2), np.float32))

    def grad(m: int):
        # gradCell(m): rows 0 and ny-1 keep the zero setupNavFn wrote; m == ns - nx would read potarr[ns]
        g = grads.get(m)
        if g is None:
            if m < nx or m > ns - nx:
                g = (0.0, 0.0)
            elif m + nx >= ns:
                raise _Ub(m)
            else:
                g = K.grad_cell(D, pot[m], pot[m - 1], pot[m + 1], pot[m - nx], pot[m + nx])
            grads[m] = g
        return g

    def finish(exit_: str, i: int, detail: str = "") -> Walk:
        w.exit, w.iterations, w.detail = exit_, i + 1, detail
        w.exit_cell = (stc % nx, stc // nx)
        w.points = np.array(list(zip(xs, ys)), dtype=np.float32).reshape(-1, 2)
        return w

    for i in range(max_steps):
        if len(xs) >= 2:
            key = (stc, dx, dy, xs[-2], ys[-2], xs[-1], ys[-1])
            first = seen.get(key)
            if first is not None:
                w.cycle_start, w.cycle_period = first, i - first
                return finish("cycle", i - 1, f"iteration {i} repeats the state of iteration {first}")
            seen[key] = i
        near = K.nearest_cell(D, stc, dx, dy, nx, ns)
        if K.near_goal(D, pot[near]):
            xs.append(D.int_to_f32(goal[0]))
            ys.append(D.int_to_f32(goal[1]))
            w.path_length = len(xs)
            return finish("near_goal", i)
        if stc < nx or stc > ns - nx:
            return finish("out_of_bounds", i, "the path reached the first or last row")
        if stc - nx - 1 < 0 or stc + nx + 1 >= ns:
            return finish(UB, i, f"calcPath would read outside the potential array around cell {stc}")
        px, py = K.path_point(D, stc, nx, dx, dy)
        xs.append(px)
        ys.append(py)
        oscillation = len(xs) > 2 and xs[-1] == xs[-3] and ys[-1] == ys[-3]
        up, down = stc - nx, stc + nx
        ring = (up - 1, up, up + 1, stc - 1, stc + 1, down - 1, down, down + 1)
        if oscillation:
            w.oscillations.append(i)
        if oscillation or K.unreached(D, pot[stc]) or any(K.unreached(D, pot[m]) for m in ring):
            w.fallbacks.append(i)
            best = K.lowest_of_eight(D, pot[stc], [pot[m] for m in ring])
            if best >= 0:
                stc = ring[best]
            dx = dy = D.f32const(0.0)
            if K.unreached(D, pot[stc]):
                return finish("high_potential", i, "grid-following landed on an unreached cell")
        else:
            try:
                g = [grad(m) for m in (stc, stc + 1, down, down + 1)]
            except _Ub as e:
                return finish(UB, i, f"gradCell would read past the potential array at cell {e.args[0]}")
            x = K.interpolate_gradient(D, dx, dy, g[0][0], g[1][0], g[2][0], g[3][0])
            y = K.interpolate_gradient(D, dx, dy, g[0][1], g[1][1], g[2][1], g[3][1])
            if x == 0.0 and y == 0.0:
                return finish("zero_gradient", i, "the interpolated gradient is exactly (0, 0)")
            dx, dy, cdx, cdy = K.step_offsets(D, dx, dy, x, y, step)
            stc += cdx + cdy * nx
    w.exit, w.iterations = UNDECIDED, max_steps
    w.exit_cell = (stc % nx, stc // nx)
    w.points = np.array(list(zip(xs, ys)), dtype=np.float32).reshape(-1, 2)
    w.detail = f"no exit and no repeated state in {max_steps} iterations"
    return w


class _Ub(Exception):
    pass
