"""The fixed NavFn: a path whenever the start has a finite potential, never another path
where the original returns one.

The fix is two small changes to ``navfn.cpp`` (``patches/navfn-fix/``), stated here with
the kernels, each acting only where the original fails:

* **propagate on** (``calcNavFnAstar`` / ``calcNavFnDijkstra``): when the cycle limit
  ``max(nx*ny/20, nx+ny)`` stops the wave with the start still unreached and cells left in
  the buffers, call ``propNavFn*`` again with the same limit until the start is reached or
  the buffers run dry.  The original returns no path from an unreached start (the predicate
  ``NoPathWithoutFinitePotential``), so no path it returns changes.  Each call is the C++
  function unchanged, A*'s ``curT += dist`` at its entry included.
* **descend** (``calcPath`` -> ``calcPathDescent``): when gradient following returns no
  path and the start has a finite potential, walk from the start to the lowest strictly lower
  4-neighbour until the goal.  Every reached cell but the goal has one (``Progress``, under
  the potential bound 2**30), potentials strictly fall, so no cell repeats and the walk ends
  at the goal within ``nx*ny`` steps; every cell it passes is reached, so passable
  (``PositionSafe``).
"""

from __future__ import annotations

from typing import Optional

import numpy as np

from ..errors import NavfnInputError
from . import kernels as K
from .extraction import Extraction, ExtractionExit, UndefinedBehaviour
from .constants import POT_HIGH
from .numeric import CONCRETE as D
from .propagation import PropagationState, TraceHook, propagate

VARIANTS = ("original", "fixed")
POT_BOUND = 2.0**30  # the potential bound the guarantees need: Progress's float32 link is proved below it
DEFAULT_VARIANT = "original"
VARIANT_HELP = ("original: NavFn as Nav2 ships it; fixed: with the fix of docs/fix.md (propagate on past the "
                "cycle limit, descend the potential where calcPath fails); default: original")


def check_variant(variant: str) -> str:
    """A variant's name, or a clear error naming the choices."""
    if variant not in VARIANTS:
        raise NavfnInputError(f"unknown variant {variant!r} (choose from {', '.join(VARIANTS)})")
    return variant


def check_cycles(cycles: int) -> int:
    """The fix calls ``propNavFn*(cycles)`` until done: a limit below 1 would never end."""
    if cycles < 1:
        raise NavfnInputError(f"the fixed planner needs a cycle limit of at least 1, not {cycles}")
    return cycles


def reached(potential) -> bool:
    """A finite potential (``potarr[n] < POT_HIGH``)."""
    return bool(D.lt(D.f32const(float(potential)), D.f32const(POT_HIGH)))


def propagate_on(st: PropagationState, start: tuple[int, int], goal: tuple[int, int], astar: bool, cycles: int,
                 at_start: bool = True, trace_hook: Optional[TraceHook] = None,
                 record_trace: bool = True) -> tuple[bool, int]:
    """The patched ``calcNavFn*`` after ``setupNavFn``: ``propNavFn*(cycles)``, then again while
    the start is unreached and a buffer holds cells.  Returns the last call's return value and
    how many calls the fix added (0 where the original's one call is all).

    Ends: every call that does not stop at once processes at least one buffered cell, a cell
    is buffered only when a potential strictly falls, and a float32 potential falls only
    finitely often."""
    check_cycles(cycles)
    start_cell = start[1] * st.nx + start[0]
    done = propagate(st, start, goal, astar, cycles, at_start, trace_hook=trace_hook, record_trace=record_trace)
    calls = 0
    while K.unreached(D, st.potential[start_cell]) and (st.cur or st.nxt):
        done = propagate(st, start, goal, astar, cycles, at_start, trace_hook=trace_hook, record_trace=record_trace)
        calls += 1
    return done, calls


def descend(potential: list, nx: int, ny: int, start: tuple[int, int], goal: tuple[int, int]) -> Extraction:
    """``calcPathDescent``: the cells from the start down the potential to the goal, then the goal.

    No path (exit ``HIGH_POTENTIAL``) from an unreached start; exit ``ZERO_GRADIENT`` at a
    cell with no lower neighbour other than the goal and ``EXHAUSTED`` after ``nx*ny - 1``
    cells, both impossible under the potential bound (``Progress``)."""
    ns = nx * ny
    stc = start[1] * nx + start[0]
    goal_cell = goal[1] * nx + goal[0]
    if K.unreached(D, potential[stc]):
        return Extraction([], ExtractionExit.HIGH_POTENTIAL, 0, stc)
    zero = D.f32const(0.0)
    points: list = []
    while stc != goal_cell:
        if len(points) >= ns - 1:
            return Extraction([], ExtractionExit.EXHAUSTED, len(points), stc)
        if stc < nx or stc >= ns - nx:
            raise UndefinedBehaviour(f"calcPathDescent reads outside the potential array around cell {stc}")
        points.append(K.path_point(D, stc, nx, zero, zero))
        ring = (stc - nx, stc - 1, stc + 1, stc + nx)
        best = K.lowest_of_four(D, potential[stc], [potential[m] for m in ring])
        if best < 0:
            return Extraction([], ExtractionExit.ZERO_GRADIENT, len(points), stc)
        stc = ring[best]
    points.append((D.int_to_f32(goal[0]), D.int_to_f32(goal[1])))
    return Extraction(points, ExtractionExit.NEAR_GOAL, len(points), stc)


def with_descent(res, start, goal):
    """A plan result without a path, given the descent's path where it finds one (``res.extra
    ["fix"]`` then names it); the potential and every other field stay."""
    ny, nx = res.potential.shape
    ext = descend([float(v) for v in res.potential.ravel()], nx, ny, (int(start[0]), int(start[1])),
                  (int(goal[0]), int(goal[1])))
    if ext.exit is ExtractionExit.NEAR_GOAL:
        res.path = np.array(ext.path, dtype=np.float32).reshape(-1, 2)
        res.exit = ext.exit
        res.extra = {**res.extra, "fix": [*res.extra.get("fix", []), "descent"]}
    return res
