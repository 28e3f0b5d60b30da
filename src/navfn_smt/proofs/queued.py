"""QueuedStartReached: a start queued where the next cycle must update it is reached.

A buffered cell has a 4-neighbour that was reached when the cell was pushed (``initCost``
pushes the goal's neighbours; every later push happens in an update that changed its cell),
and potentials only fall (``Monotone.update_never_raises``).  So when a cycle updates a
queued, still unreached start, one of its four neighbours, whichever it is, lies below the
bound, and the update reaches it (``queued_cell_gets_reached``).  The bounded checks rely on
it (:func:`navfn_smt.check.bounded.flippable`): explored alone, ``start-reached`` does not
flip a control path's branches after the run queued the start so.
"""

from navfn_smt.proofs import QueuedStartReached
from navfn_smt.smt.obligation import obligation
from navfn_smt.smt.predicates import Reached, TranslatedCost, ValidPotential, all_of, any_of
from navfn_smt.spec import kernels as K
from navfn_smt.spec.constants import POT_HIGH
from navfn_smt.spec.fix import POT_BOUND


@obligation(QueuedStartReached, expect={"real": "proved", "fp32": "proved",
                                        "fp32@x86-64-v3": "proved", "fp32@aarch64": "proved"},
            scope="one update of an unreached cell with any neighbours: every map size")
def queued_cell_gets_reached(D):
    """An update of an unreached passable cell some 4-neighbour of which, any of the four, is
    below the bound reaches it.

    cost in [50, 253], pot(n) = POT_HIGH, min(l, r, u, d) < 2**30, neighbours valid
    ==>  updateCell(n) changes pot(n), and pot'(n) < POT_HIGH
    """
    ring = [D.f32(v) for v in ("l", "r", "u", "d")]
    c = D.cost("cost")
    new, changed = K.cell_update(D, D.f32const(POT_HIGH), *ring, D.cost_int(c), D.cost_as_f32(c))
    pre = all_of(D, TranslatedCost(D, D.cost_int(c)), *(ValidPotential(D, p) for p in ring),
                 any_of(D, *(D.lt(p, D.f32const(POT_BOUND)) for p in ring)))
    return pre, D.and_(changed, Reached(D, new))
