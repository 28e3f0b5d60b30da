"""calcPath's control flow, checked on the functions the spec runs (``spec/extraction.py``:
``iteration_test``, ``follows_the_grid``, ``grid_step``, ``goal_point``) over SMT arrays, on a
map of any size (issue #39).

The map is :class:`~navfn_smt.proofs.descent.Grid`: ``ns`` cells ``W`` wide, row after row, a
lethal border, and potentials satisfying the invariant PositionSafeAndProgressInductive proves of
propagation (assumed at the cells a step reads).  These obligations are the steps of the
extraction inductions that were argued from reading calcPath:

- from an unreached start, the first iteration stops with no path (x86-64's truncation of
  POT_HIGH; on arm64 and over the reals the fallback walks, see ``no_path.py``);
- the grid-following step leaves the offsets 0 and goes on only at a reached cell, one of the nine;
- the gradient step runs only when the cell and its eight neighbours are reached;
- the near-goal exit's last point is the goal cell exactly;
- from a reached cell other than the goal, calcPath's bound tests pass (no OUT_OF_BOUNDS exit,
  no read outside potarr);
- on a map at most two interior cells tall (``ns <= 4*W``) or wide (``W <= 4``), every passable
  cell has an unreached one among its eight, so calcPath follows the grid at every iteration;
- a point near a reached cell is near a passable cell or the goal (ValidPath from
  FinitePotentialPath and PositionSafe).
"""

import z3

from navfn_smt.proofs import FallbackPath, FinitePotentialPath, NoPathWithoutFinitePotential, ValidPath
from navfn_smt.proofs.descent import STATED, Grid
from navfn_smt.smt.predicates import Lethal, Reached, Unreached, ValidPotential, all_of
from navfn_smt.smt.obligation import obligation
from navfn_smt.spec import extraction as E
from navfn_smt.spec.extraction import ExtractionExit, exit_code

NEAR_GOAL, OUT_OF_BOUNDS = exit_code(ExtractionExit.NEAR_GOAL), exit_code(ExtractionExit.OUT_OF_BOUNDS)
EXACT_INT = 2 ** 24  # every int below this converts to float32 exactly


def _cell(D, m: Grid, name="stc"):
    """A cell of the map, with its 8-ring and the propagation invariant at the nine."""
    stc = D.int32(name)
    ring = E.ring_of_eight(stc, m.W)
    pre = all_of(D, m.well_formed(), D.gt(stc, m.W), D.lt(stc, m.ns - m.W - 1), m.goal_zero(m.pot),
                 *(m.invariant(m.pot, c) for c in (stc, *ring)))
    return stc, ring, pre


@obligation(NoPathWithoutFinitePotential, expect={"fp32": "proved", "fp32@x86-64-v3": "proved"},
            scope="calcPath's first iteration at any start of a map of any size", arrays=True)
def calc_path_stops_at_once_at_an_unreached_start(D):
    """From an unreached start (offsets 0, no point yet) calcPath's first iteration returns no
    path: the near-goal probe reads the start, which is no goal; then the start is outside the
    bound tests, or it follows the grid, keeps the cell and stops (HIGH_POTENTIAL).

    pot[start] >= POT_HIGH, valid potentials at the nine cells, any map
    ==>  iteration_test != NEAR_GOAL, and it goes on only to a grid step that stops

    Over the reals and with arm64's saturating conversion the grid step moves instead
    (``unreached_cell_stays_put`` is refuted there), so only x86-64's float32 is declared.
    """
    m = Grid(D)
    stc = D.int32("start")
    ring = E.ring_of_eight(stc, m.W)
    zero = D.f32const(0.0)
    code = E.iteration_test(D, m.pot, stc, zero, zero, m.W, m.ns)
    nxt, _, _, stops = E.grid_step(D, m.pot, stc, m.W)
    pre = all_of(D, m.well_formed(), D.ge(stc, 0), D.lt(stc, m.ns), Unreached(D, m.pot[stc]),
                 *(ValidPotential(D, m.pot[c]) for c in (stc, *ring)))
    goes_on = code == E.ITERATION_GOES_ON
    return pre, z3.And(code != NEAR_GOAL,
                       z3.Implies(goes_on, z3.And(E.follows_the_grid(D, m.pot, stc, m.W, False), stops)))


@obligation(FinitePotentialPath, scope="calcPath's grid step at any cell of a map of any size", **STATED)
def grid_step_goes_on_only_at_a_reached_cell_with_offsets_zero(D):
    """calcPath's grid-following step moves to one of the nine cells, sets the offsets to 0, and
    goes on only when that cell is reached.

    any cell of the map, valid potentials at the nine
    ==>  grid_step = (next, 0, 0, stops): next one of the nine, and not stops implies next reached
    """
    m = Grid(D)
    stc, ring, pre = _cell(D, m)
    nxt, dx, dy, stops = E.grid_step(D, m.pot, stc, m.W)
    zero = D.f32const(0.0)
    return pre, z3.And(z3.Or([nxt == c for c in (stc, *ring)]), D.eq(dx, zero), D.eq(dy, zero),
                       z3.Implies(z3.Not(stops), Reached(D, m.pot[nxt])))


@obligation(FinitePotentialPath, scope="calcPath's fallback test at any cell of a map of any size", **STATED)
def gradient_step_runs_only_among_nine_reached_cells(D):
    """calcPath takes the gradient step only when the path does not oscillate and the cell and
    its eight neighbours are all reached.

    any cell of the map, any oscillation flag
    ==>  not follows_the_grid implies no oscillation and the nine cells reached
    """
    m = Grid(D)
    stc, ring, pre = _cell(D, m)
    osc = z3.Bool("oscillation")
    nine = z3.And([Reached(D, m.pot[c]) for c in (stc, *ring)])
    return pre, z3.Implies(z3.Not(E.follows_the_grid(D, m.pot, stc, m.W, osc)), z3.And(z3.Not(osc), nine))


@obligation(FinitePotentialPath, scope="calcPath's near-goal exit, any goal of a map below 2**24 cells a side",
            **STATED)
def near_goal_exit_ends_at_the_goal_cell(D):
    """The point the near-goal exit appends is the goal cell exactly, whose potential is 0.

    0 <= gx, gy < 2**24  ==>  goal_point(gx, gy) converts back to (gx, gy), with no fraction
    """
    gx, gy = D.int32("gx"), D.int32("gy")
    px, py = E.goal_point(D, (gx, gy))
    pre = all_of(D, D.ge(gx, 0), D.lt(gx, EXACT_INT), D.ge(gy, 0), D.lt(gy, EXACT_INT))
    exact = all_of(D, *(z3.And(D.to_int32(p) == g, D.eq(D.int_to_f32(D.to_int32(p)), p)) for p, g in ((px, gx),
                                                                                                     (py, gy))))
    return pre, exact


@obligation(FallbackPath, scope="calcPath's bound tests at any reached cell of a map of any size", **STATED)
def bound_tests_pass_at_a_reached_cell(D):
    """At a reached cell other than the goal calcPath's bound tests pass, whatever the offsets:
    it is no obstacle (PositionSafe), so off the lethal border.

    stc on the map, reached, not the goal; the border lethal at stc; the invariant at stc
    ==>  iteration_test is NEAR_GOAL or goes on (never OUT_OF_BOUNDS, never a read outside potarr)
    """
    m = Grid(D)
    stc = D.int32("stc")
    dx, dy = D.f32("dx"), D.f32("dy")
    code = E.iteration_test(D, m.pot, stc, dx, dy, m.W, m.ns)
    one = D.f32const(1.0)
    pre = all_of(D, m.well_formed(), D.ge(stc, 0), D.lt(stc, m.ns), stc != m.g, Reached(D, m.pot[stc]),
                 m.border_lethal(stc), m.invariant(m.pot, stc), m.goal_zero(m.pot),
                 *(all_of(D, D.ge(v, D.neg(one)), D.le(v, one)) for v in (dx, dy)))
    return pre, z3.Or(code == NEAR_GOAL, code == E.ITERATION_GOES_ON)


def _narrow(D, m: Grid, wide: bool):
    """A passable cell of a map two interior cells short (``ns`` is 3 or 4 rows of ``W``) or,
    ``wide`` False, thin (``W`` is 3 or 4, the columns 0 and W-1 lethal as well): (pre, stc, ring)."""
    stc, ring, pre = _cell(D, m)
    if wide:
        shape = z3.Or(m.ns == 3 * m.W, m.ns == 4 * m.W)
        border = [m.border_lethal(c) for c in ring]
    else:
        shape = z3.Or(m.W == 3, m.W == 4)
        column = [z3.Implies(z3.Or(c % m.W == 0, c % m.W == m.W - 1), Lethal(D, m.cost_int(c))) for c in (stc, *ring)]
        border = [*(m.border_lethal(c) for c in ring), *column]
    return all_of(D, pre, shape, z3.Not(Lethal(D, m.cost_int(stc))), m.border_lethal(stc), *border), stc, ring


def _takes_the_grid(D, wide):
    m = Grid(D)
    pre, stc, ring = _narrow(D, m, wide)
    return pre, E.follows_the_grid(D, m.pot, stc, m.W, z3.Bool("oscillation"))


@obligation(FallbackPath, scope="calcPath's fallback test at any passable cell of a map at most two interior "
            "cells tall, any width", **STATED)
def short_map_follows_the_grid_at_every_passable_cell(D):
    """On a map of at most two interior rows, a passable cell has two border cells among its
    eight (the row above or the row below); at most one is the goal, the other is lethal, so
    unreached (PositionSafe): calcPath follows the grid there.

    ns = 3*W or 4*W, stc passable, off the border rows; the border and the invariant at the nine
    ==>  follows_the_grid(stc)
    """
    return _takes_the_grid(D, wide=True)


@obligation(FallbackPath, scope="calcPath's fallback test at any passable cell of a map at most two interior "
            "cells wide, any height", **STATED)
def thin_map_follows_the_grid_at_every_passable_cell(D):
    """The same on a map of at most two interior columns (W = 3 or 4): the column to the left or
    to the right is border.

    W = 3 or 4, stc passable, off the border; the border and the invariant at the nine
    ==>  follows_the_grid(stc)
    """
    return _takes_the_grid(D, wide=False)


@obligation(ValidPath, scope="any cell of a map of any size", **STATED)
def point_near_a_reached_cell_is_near_a_passable_cell_or_the_goal(D):
    """FinitePotentialPath puts every point within 1/2 of a reached cell; PositionSafe (the
    propagation invariant) makes that cell passable unless it is the goal.

    the invariant at c, c reached  ==>  c is the goal or not lethal
    """
    m = Grid(D)
    c = D.int32("c")
    return all_of(D, m.invariant(m.pot, c), Reached(D, m.pot[c])), z3.Or(c == m.g,
                                                                         z3.Not(Lethal(D, m.cost_int(c))))
