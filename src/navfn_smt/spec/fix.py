"""The fixed NavFn: a path where the original fails though the start is connected, within the
budgets the planner already has, and never another path where the original returns one.

The fix is two small changes to ``navfn.cpp`` (``patches/navfn-fix/``), stated here with
the kernels, each acting only where the original fails:

* **propagate on, once** (``calcNavFnAstar`` / ``calcNavFnDijkstra``): when the cycle limit
  ``max(nx*ny/20, nx+ny)`` stops the wave with the start still unreached and cells left in
  the buffers, call ``propNavFn*`` once more, with ``nx*ny`` cycles (:func:`extra_cycles`):
  the one explicit cap of the added work.  The original returns no path from an unreached
  start (the predicate ``NoPathWithoutFinitePotential``), so no path it returns changes.  The
  call is the C++ function unchanged, A*'s ``curT += dist`` at its entry included (so A*'s
  threshold is raised once more, not once per call of a loop), the cancel checker polled as
  in the first call.
* **descend** (``calcPath`` -> ``calcPathDescent``): when gradient following returns no
  path and the start has a finite potential, walk from the start to the lowest strictly lower
  of the 8 neighbours until the goal, within calcPath's own budget: at most ``n`` points (the
  ``n`` of ``calcPath(n)``, Nav2's ``max_cycles_factor`` times the map's larger side on
  Rolling), written to the ``n``-point buffers calcPath allocated.  Every reached cell but
  the goal has a strictly lower 4-neighbour (``Progress``, under the potential bound 2**30),
  so the lowest of the 8 is lower still, potentials strictly fall and no cell repeats; every
  cell it passes is reached, so passable (``PositionSafe``).  The walk reaches the goal when
  it fits in ``n`` points and otherwise fails (exit ``EXHAUSTED``), as the gradient does.
"""

from __future__ import annotations

from . import kernels as K
from .extraction import EXIT_CODES, Extraction, ExtractionExit, exit_code, ring_of_eight, ring_potentials
from .constants import POT_HIGH
from .numeric import CONCRETE, taken
from .planner import Fallback, Fix, FurtherCall
from .propagation import buffers_hold_cells

POT_BOUND = 2.0**30  # the potential bound the guarantees need: Progress's float32 link is proved below it


def extra_cycles(nx: int, ny: int) -> int:
    """The cap of the fix's one further ``propNavFn*`` call: ``nx * ny`` cycles."""
    return nx * ny


def reached(potential) -> bool:
    """A finite potential (``potarr[n] < POT_HIGH``)."""
    D = CONCRETE
    return bool(D.lt(D.f32const(float(potential)), D.f32const(POT_HIGH)))


def calls_again(D, start_pot, fill_cur, fill_next):
    """The fix's test after the first ``propNavFn*``: the start unreached (``potarr[startCell] >=
    POT_HIGH``, float) and a buffer holding cells (``curPe > 0 || nextPe > 0``, ints)."""
    return D.and_(K.unreached(D, start_pot), buffers_hold_cells(D, fill_cur, fill_next))


descent_ring = ring_of_eight  # calcPathDescent reads the ring of calcPath's grid fallback
DESCENT_GOES_ON = -1  # descent_iteration's code when the walk writes a point and moves on
_EXHAUSTED, _NEAR_GOAL, _OUT_OF_BOUNDS, _ZERO_GRADIENT = (
    exit_code(e) for e in (ExtractionExit.EXHAUSTED, ExtractionExit.NEAR_GOAL, ExtractionExit.OUT_OF_BOUNDS,
                           ExtractionExit.ZERO_GRADIENT))


def descent_iteration(D, pot, stc, points, n, nx, ns, goal_cell):
    """One pass of ``calcPathDescent``'s loop at cell ``stc`` with ``points`` points written:
    ``(code, next cell)``, the code an exit's :func:`~.extraction.exit_code` or
    :data:`DESCENT_GOES_ON` (write the point of ``stc``, go on at the next cell).  ``pot[i]`` is
    ``potarr[i]``.  The tests, in the C++ order: no room for a point (``EXHAUSTED``), the goal
    (``NEAR_GOAL``), a ring read leaving the array (``OUT_OF_BOUNDS``), no lower one of the 8
    (``ZERO_GRADIENT``); the step is :func:`~.kernels.lowest_neighbour` (float comparisons).
    Cells are the domain's ints, so the same function runs on a concrete potential and, over an
    SMT array, in ``proofs/descent.py``; a ring read the bounds test refuses is never used."""
    ring = descent_ring(stc, nx)
    best = K.lowest_neighbour(D, pot[stc], ring_potentials(pot, ring))
    nxt = stc
    for k, m in enumerate(ring):
        nxt = D.ite(D.eq(best, k), m, nxt)
    outside = D.or_(D.le(stc, nx), D.ge(stc, ns - nx - 1))
    code = D.ite(D.lt(best, 0), _ZERO_GRADIENT, DESCENT_GOES_ON)
    code = D.ite(outside, _OUT_OF_BOUNDS, code)
    code = D.ite(D.eq(stc, goal_cell), _NEAR_GOAL, code)
    return D.ite(D.ge(points, n), _EXHAUSTED, code), nxt


class _HighOffTheArray:
    """``potarr[i]``, POT_HIGH outside the array: the descent reads its ring before the bounds
    test, which refuses such a read before it counts."""

    def __init__(self, potential: list):
        self.potential, self.ns = potential, len(potential)

    def __getitem__(self, i: int):
        return self.potential[i] if 0 <= i < self.ns else CONCRETE.f32const(POT_HIGH)


def descend(potential: list, nx: int, ny: int, start: tuple[int, int], goal: tuple[int, int], n: int,
            D=CONCRETE) -> Extraction:
    """``calcPathDescent(n)``: the cells from the start down the potential to the goal, then the
    goal, at most ``n`` points (:func:`descent_iteration` until it stops).

    No path (exit ``HIGH_POTENTIAL``) from an unreached start; exit ``EXHAUSTED`` when the goal
    is not reached within ``n`` points; exits ``ZERO_GRADIENT`` at a cell with no lower neighbour
    other than the goal and ``OUT_OF_BOUNDS`` at a cell whose ring leaves the array, both
    impossible under the potential bound (``Progress``, ``PositionSafe``: a reached cell other
    than the goal is passable, so off the lethal border).  ``D``: the numeric domain it runs in
    (the check's encoding runs it in its concolic domain)."""
    ns = nx * ny
    stc = start[1] * nx + start[0]
    goal_cell = goal[1] * nx + goal[0]
    if taken(D, K.unreached(D, potential[stc])):
        return Extraction([], ExtractionExit.HIGH_POTENTIAL, 0, stc)
    zero = D.f32const(0.0)
    points: list = []

    pot = _HighOffTheArray(potential)
    while True:
        code, nxt = descent_iteration(D, pot, stc, len(points), n, nx, ns, goal_cell)
        if code == _NEAR_GOAL:
            points.append((D.int_to_f32(goal[0]), D.int_to_f32(goal[1])))
            return Extraction(points, ExtractionExit.NEAR_GOAL, len(points), stc)
        if code != DESCENT_GOES_ON:
            return Extraction([], EXIT_CODES[code], len(points), stc)
        points.append(K.path_point(D, stc, nx, zero, zero))
        stc = nxt


PROPAGATION = Fix("propagation", "the fix's first half alone (the first pull request): propagate on once past the "
                  "cycle limit while the start is unreached", patches="navfn-propagation",
                  further=FurtherCall(calls_again, extra_cycles),
                  proved=(("start-reached", ("ConnectedStartReached",)),))
DESCENT = Fix("descent", "the fix's second half alone (the second pull request): descend the potential where "
              "calcPath fails", patches="navfn-descent", fallback=Fallback(descend),
              proved=(("complete", ("DescentPath",)),))
FIX = Fix("fixed", "with the fix of docs/fix.md, both pull requests: propagate on once past the cycle limit, "
          "descend the potential where calcPath fails", patches="navfn-fix", further=FurtherCall(calls_again, extra_cycles),
          fallback=Fallback(descend),
          proved=(("complete", ("DescentPath",)), ("start-reached", ("ConnectedStartReached",))))
