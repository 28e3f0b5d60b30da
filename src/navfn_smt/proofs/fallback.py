"""FallbackPath: calcPath returns a path on every map at most two interior cells wide or tall.

On such a map every interior cell has a lethal border cell, never reached, among its eight
neighbours, so calcPath takes the grid-following fallback at every iteration: ``int minp =
potarr[stc]`` and the first of the eight neighbours below ``(float)minp`` (then below the
truncation of each one taken) becomes the next cell (``kernels.lowest_of_eight``).  The walk
needs a neighbour below the *truncated* potential, a little more than Progress gives: an
update that changes a cell leaves its lowest neighbour below the new potential's truncation
(``update_keeps_a_neighbour_below_its_floor``; the cell is at least 0.704 * 50 above it),
so the fallback step moves (``fallback_step_moves_below_the_floor``), and only to a strictly
lower, reached neighbour (``fallback_step_goes_strictly_lower``).  The walk descends through
distinct cells to the goal, within the k - 1 moves a map of k passable cells allows.  The float32 link holds below
a bound found by search; ``update_raises_at_most_twice_its_cost`` keeps every potential of a
small map far below it.  The chain, its trusted steps and what it rests on are stated in
:data:`navfn_smt.proofs.FallbackPath`.
"""

from navfn_smt.proofs import FallbackPath
from navfn_smt.proofs.induction import UnboundedMap, frame_condition, invariant_condition
from navfn_smt.smt.obligation import Bound, obligation
from navfn_smt.smt.predicates import Reached, TranslatedCost, ValidPotential, all_of, any_of, minimum
from navfn_smt.spec import kernels as K
from navfn_smt.spec.constants import POT_HIGH

INT_RANGE = 2.0**31  # (int) of a float potential is the truncation below this
# the array inductions: proved in every semantics; a model of a negation is over arrays
FLOOR = dict(expect={"real": "proved", "fp32": "proved", "fp32@x86-64-v3": "proved", "fp32@aarch64": "proved"},
             arrays=True)


def one_update(D):
    """One update of a cell with any neighbours, ``l`` the lowest and reached: ``(pre, l, hf, new, changed)``."""
    old, l, r, u, d = (D.f32(v) for v in ("old", "l", "r", "u", "d"))
    c = D.cost("cost")
    hf = D.cost_as_f32(c)
    new, changed = K.cell_update(D, old, l, r, u, d, D.cost_int(c), hf)
    pre = all_of(D, TranslatedCost(D, D.cost_int(c)), *(ValidPotential(D, p) for p in (old, l, r, u, d)),
                 Reached(D, l), D.eq(minimum(D, l, r, u, d), l))
    return pre, l, hf, new, changed


@obligation(FallbackPath, expect={"real": "proved", "fp32": "refuted",
                                  "fp32@x86-64-v3": "refuted", "fp32@aarch64": "refuted"},
            scope="one update with any neighbours: every map size",
            bound=Bound(var="l", lo=1.0, hi=POT_HIGH))
def update_keeps_a_neighbour_below_its_floor(D):
    """A changed cell ends with its lowest neighbour below the truncation of its new potential.

    cost in [50, 253], valid potentials, l the lowest neighbour and reached
    ==>  updateCell(n) changes pot(n)  implies  l < (float)(int)pot'(n)
    """
    pre, l, _, new, changed = one_update(D)
    return pre, any_of(D, D.not_(changed), D.lt(l, D.int_to_f32(D.to_int32(new))))


@obligation(FallbackPath, expect={"real": "proved", "fp32": "proved",
                                  "fp32@x86-64-v3": "proved", "fp32@aarch64": "proved"},
            scope="one update with any neighbours: every map size")
def update_raises_at_most_twice_its_cost(D):
    """A changed cell ends at most twice its cost above its lowest neighbour (float32 sums).

    cost in [50, 253], valid potentials, l the lowest neighbour and reached
    ==>  updateCell(n) changes pot(n)  implies  pot'(n) <= l + (hf + hf)
    """
    pre, l, hf, new, changed = one_update(D)
    return pre, any_of(D, D.not_(changed), D.le(new, D.add(l, D.add(hf, hf))))


def _fallback_step(D):
    """One fallback step at a cell with any eight neighbours: ``(pre, centre, ring, best)``."""
    centre = D.f32("centre")
    ring = [D.f32(f"n{k}") for k in range(8)]
    pre = all_of(D, ValidPotential(D, centre), D.lt(centre, D.f32const(INT_RANGE)),
                 *(ValidPotential(D, p) for p in ring))
    return pre, centre, ring, K.lowest_of_eight(D, centre, ring)


@obligation(FallbackPath, expect={"real": "proved", "fp32": "proved",
                                  "fp32@x86-64-v3": "proved", "fp32@aarch64": "proved"},
            scope="one fallback step at any cell with any eight neighbours: every map size", slow=("fp32",))
def fallback_step_goes_strictly_lower(D):
    """The fallback moves only to a strictly lower, reached neighbour.

    0 <= centre < 2**31, valid potentials, k = lowest_of_eight(centre; n0 .. n7)
    ==>  k >= 0 implies n_k < centre and n_k reached
    """
    pre, centre, ring, best = _fallback_step(D)
    moved_lower = any_of(D, *(all_of(D, D.eq(best, k), D.lt(p, centre), Reached(D, p)) for k, p in enumerate(ring)))
    return pre, any_of(D, D.eq(best, -1), moved_lower)


@obligation(FallbackPath, expect={"real": "proved", "fp32": "proved",
                                  "fp32@x86-64-v3": "proved", "fp32@aarch64": "proved"},
            scope="one fallback step at any cell with any eight neighbours: every map size")
def fallback_step_moves_below_the_floor(D):
    """The fallback moves whenever a neighbour is below the truncation of the centre's potential.

    0 <= centre < 2**31, valid potentials, k = lowest_of_eight(centre; n0 .. n7)
    ==>  some n_j < (float)(int)centre implies k >= 0
    """
    pre, centre, ring, best = _fallback_step(D)
    floor = D.int_to_f32(D.to_int32(centre))
    return pre, any_of(D, D.not_(any_of(D, *(D.lt(p, floor) for p in ring))), D.ge(best, 0))


# ---------------------------------------------------------------------------------------------
# The walk's invariant over the whole run: a lower neighbour below the truncation, at every cell
# ---------------------------------------------------------------------------------------------
class FloorMap(UnboundedMap):
    """PositionSafeAndProgressInductive's map and invariant, with Progress strengthened as the
    fallback needs it: a reached cell other than the goal has a 4-neighbour strictly below the
    truncation of its potential, ``(float)(int)potarr[n]`` (kernels.lowest_of_eight's ``minp``)."""

    def below(self, p):
        return self.D.int_to_f32(self.D.to_int32(p))


@obligation(FallbackPath, scope="setupNavFn and initCost on a map of any width (32-bit cell numbers), any goal",
            **FLOOR)
def setup_gives_every_reached_cell_a_neighbour_below_its_floor(D):
    """After setupNavFn and initCost the strengthened invariant holds at every cell (only the goal
    is reached).

    costs as setCostmap makes them  ==>  the invariant of FloorMap at any cell n, pot[g] = 0
    """
    return invariant_condition(D, "setup", "cycle", FloorMap)


@obligation(FallbackPath, scope="one updateCell at any cell of a map of any width (32-bit cell numbers), any "
            "goal: the updated cell", slow=("fp32", "fp32@x86-64-v3", "fp32@aarch64"), **FLOOR)
def update_keeps_a_neighbour_below_the_floor_at_the_updated_cell(D):
    """One updateCell at any cell c keeps the strengthened invariant at c: a changed cell's lowest
    neighbour is below its new potential's truncation (update_keeps_a_neighbour_below_its_floor,
    here with the neighbours read from the array).

    the invariant at c, its neighbours and the goal; in float32 the potential the update writes
    below 2**30  ==>  after pot[c] := updateCell(c), the invariant at c and pot[g] = 0
    """
    return invariant_condition(D, "update", "update", FloorMap, "updated")


@obligation(FallbackPath, scope="one updateCell at any cell of a map of any width (32-bit cell numbers), any "
            "goal: every other cell", slow=("fp32", "fp32@x86-64-v3", "fp32@aarch64"), **FLOOR)
def update_keeps_a_neighbour_below_the_floor_at_every_other_cell(D):
    """One updateCell at c keeps the strengthened invariant at every other cell n: n's potential is
    unchanged, and a lower neighbour that is c only went down.

    the invariant at n, c, their neighbours and the goal; n != c  ==>  after the update, the
    invariant at n and pot[g] = 0
    """
    return invariant_condition(D, "update", "update", FloorMap, "other")


@obligation(FallbackPath, scope="the steps of the spec's propNavFn* that write no potential, on a map of any size, "
            "any goal", expect=FLOOR["expect"], arrays=True)
def the_steps_around_the_updates_keep_a_neighbour_below_the_floor(D):
    """A cycle's start, the loop clearing the flags, its end and the swap write no potential: each
    keeps the strengthened invariant.

    the invariant at q  ==>  the invariant at q after the step
    """
    return frame_condition(D, FloorMap)
