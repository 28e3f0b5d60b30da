"""The fix's descent (``calcPathDescent``) proved inductive on a map of any size (issue #39): its
loop invariant, checked on the very iteration the spec runs (``spec/fix.py``:
``descent_iteration``) over SMT arrays.

The state is the potential array and the cost array of a map of ``ns`` cells, ``W`` wide, row
after row (both symbolic, the domain's ints), the goal ``g`` any cell, and the walk's cell
``stc`` with the number of points written.  setupNavFn makes the border lethal; the cells of it
the step needs are named by :meth:`Grid.on_border` (the first and the last row, and the two
border cells at the ends of the bound tests), assumed lethal at the cell the step stands on.  The potentials satisfy the
invariant :data:`~navfn_smt.proofs.PositionSafeAndProgressInductive` proves of propagation
(``proofs/induction.py``'s ``UnboundedMap.invariant``: valid potentials, PositionSafe, Progress
and, in float32, every reached potential below 2**30), assumed at the cells the step reads.

A ghost array ``visited`` holds the cells the walk has left.  The loop invariant: the walk's
cell is reached and every visited cell has a strictly higher potential (so the walk's cell is
not visited).  ``descent_begins_at_a_reached_start`` is its initiation; the step,
``descent_iteration_moves_strictly_down_or_stops_at_the_goal_or_the_budget``, shows that one
iteration stops only at the goal (the path) or at the budget, never by OUT_OF_BOUNDS or
ZERO_GRADIENT, and otherwise writes the point of a cell that is no obstacle and moves to a
reached 8-neighbour strictly lower and not visited, keeping the invariant.  What stays argued is
the count: distinct reached cells, so at most the map's passable cells and the goal, fit in the
budget ``n`` when the map has at most ``n - 1`` passable cells besides the goal.
"""

import z3

from navfn_smt.proofs import DescentInductive
from navfn_smt.proofs.buffers import cell_sort
from navfn_smt.proofs.induction import UnboundedMap
from navfn_smt.smt.obligation import obligation
from navfn_smt.smt.predicates import Lethal, Reached, all_of
from navfn_smt.spec import fix as F
from navfn_smt.spec.extraction import ExtractionExit, exit_code

STATED = dict(expect={"real": "proved", "fp32": "proved", "fp32@x86-64-v3": "proved", "fp32@aarch64": "proved"},
              arrays=True)


class Grid(UnboundedMap):
    """An ``UnboundedMap`` of ``ns`` cells of the domain's int, ``W`` wide, row after row, with
    setupNavFn's lethal border."""

    def __init__(self, D):
        super().__init__(D, cell=cell_sort(D))
        self.ns = D.int32("ns")

    def well_formed(self):
        """At least three rows of at least three cells, fewer than 2**30 cells (no cell number
        nor ``ns + W`` overflows an int)."""
        D = self.D
        return all_of(D, D.ge(self.W, 3), D.ge(self.ns, 3 * self.W), D.le(self.ns, 2 ** 30))

    def on_border(self, q):
        """Cells of the border, row after row: the first row (``q < W``), the last
        (``q >= ns - W``), and the first cell of the second row (``(0, 1)``, cell ``W``) and
        the last of the last but one (``(W-1, H-2)``, cell ``ns - W - 1``): the border cells
        calcPath's and the descent's bound tests name."""
        D = self.D
        return z3.Or(D.lt(q, self.W), D.ge(q, self.ns - self.W), q == self.W, q == self.ns - self.W - 1)

    def border_lethal(self, q):
        """setupNavFn's lethal border, at cell ``q``."""
        return z3.Implies(self.on_border(q), Lethal(self.D, self.cost_int(q)))


def walk_invariant(D, m: Grid, visited, stc, q):
    """The descent's loop invariant at cell ``q``: the walk's cell reached, and ``q``, if visited,
    strictly above it."""
    return z3.And(Reached(D, m.pot[stc]), z3.Implies(visited[q], D.lt(m.pot[stc], m.pot[q])))


@obligation(DescentInductive, scope="calcPathDescent's start on a map of any size", **STATED)
def descent_begins_at_a_reached_start(D):
    """The walk begins at the start when its potential is finite (descend's first test), where the
    invariant holds with nothing visited.

    pot[start] < POT_HIGH (else descend returns no path: HIGH_POTENTIAL)
    ==>  the loop invariant at stc = start, visited = {}, at any cell q
    """
    m = Grid(D)
    start, q = D.int32("start"), D.int32("q")
    visited = z3.K(cell_sort(D), z3.BoolVal(False))
    return Reached(D, m.pot[start]), walk_invariant(D, m, visited, start, q)


@obligation(DescentInductive, scope="one iteration of calcPathDescent at any cell of a map of any size, any goal",
            **STATED)
def descent_iteration_moves_strictly_down_or_stops_at_the_goal_or_the_budget(D):
    """One iteration of the descent (``descent_iteration``, as the spec runs it) from a state of
    the loop invariant.

    the loop invariant at q and at the 8 around stc; the propagation invariant at stc and the 8;
    the lethal border at stc, on the map
    ==>  the iteration ends EXHAUSTED only with points >= n, NEAR_GOAL only at the goal, never
         OUT_OF_BOUNDS or ZERO_GRADIENT; when it goes on, stc is no obstacle (its point is
         written), the next cell is one of the 8, reached, strictly lower, not visited, and the
         invariant holds at q with stc visited
    """
    m = Grid(D)
    stc, q = D.int32("stc"), D.int32("q")
    points, n = D.int32("points"), D.int32("n")
    visited = z3.Array("visited", cell_sort(D), z3.BoolSort())
    code, nxt = F.descent_iteration(D, m.pot, stc, points, n, m.W, m.ns, m.g)
    ring = F.descent_ring(stc, m.W)
    pre = all_of(D, m.well_formed(), D.ge(stc, 0), D.lt(stc, m.ns), m.border_lethal(stc), D.ge(points, 0),
                 m.goal_zero(m.pot), walk_invariant(D, m, visited, stc, q),
                 *(walk_invariant(D, m, visited, stc, c) for c in ring),
                 *(m.invariant(m.pot, c) for c in (stc, q, *ring)))
    after = z3.Store(visited, stc, True)
    goes_on = all_of(D, z3.Not(Lethal(D, m.cost_int(stc))), z3.Or([nxt == c for c in ring]),
                     D.lt(m.pot[nxt], m.pot[stc]), z3.Not(visited[nxt]), walk_invariant(D, m, after, nxt, q))
    claim = all_of(D,
                   z3.Implies(code == exit_code(ExtractionExit.EXHAUSTED), D.ge(points, n)),
                   z3.Implies(code == exit_code(ExtractionExit.NEAR_GOAL), stc == m.g),
                   z3.Or(code == exit_code(ExtractionExit.EXHAUSTED), code == exit_code(ExtractionExit.NEAR_GOAL),
                         code == F.DESCENT_GOES_ON),
                   z3.Implies(code == F.DESCENT_GOES_ON, goes_on))
    return pre, claim
