"""QueuedStartReached: a start queued where the next cycle must update it is reached.

A buffered cell has a 4-neighbour that was reached when the cell was pushed (``initCost``
pushes the goal's neighbours; every later push happens in an update that changed its cell),
and potentials only fall (``Monotone.update_never_raises``).  So when a cycle updates a
queued, still unreached start, one of its four neighbours, whichever it is, lies below the
bound, and the update reaches it (``queued_cell_gets_reached``).  The loop over the current
buffer is checked with its invariant, its slot index and fill symbolic (the last two
obligations): a start waiting at any slot is reached by the time the cycle's updates end.
The bounded checks rely on it (:func:`navfn_smt.check.bounded.flippable`): explored alone,
``start-reached`` does not flip a control path's branches after the run queued the start so.
"""

import z3

from navfn_smt.proofs import QueuedStartReached
from navfn_smt.proofs.buffers import Buffers, Map, at_cell, at_slot, potentials
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


# ------------------------------------------------------------------------------------------
# The loop over the current buffer (issue #39): a cycle updates the cells of its current
# buffer's slots 0, 1, ..., curPe - 1 in turn, and its updates write the potentials (only the
# updated cell's) while their pushes write flags and the next and overflow buffers, never the
# current one (proofs/buffers.py: push).  The start waits in the current buffer at a ghost slot
# j (slots[j] = start); the loop invariant Q(k), k the next slot to update:
#     k > j  ==>  the start is reached;   and the start is reached or a 4-neighbour of it is
#     below the bound.
# Q(0) holds as the updates start (a buffered cell has a reached 4-neighbour:
# ReachedAndBufferedInductive; below the bound: the run-time condition), every update keeps it
# from k to k + 1, and Q(curPe) with j < curPe is the start reached.
# ------------------------------------------------------------------------------------------
def _waiting_start(D):
    """The map, the buffers, the potentials, the start's ghost slot ``j`` in the current buffer
    and the start (``slots[j]``)."""
    m, s = Map(D), Buffers(D)
    j = D.int32("j")
    return m, s, potentials(D), j, s.slots["cur"][j]


def _loop_invariant(D, m, s, pot, j, start, k):
    """Q(k): past its slot, the start is reached; else it is reached or beside a cell below the bound."""
    beside = any_of(D, *(D.lt(pot[q], D.f32const(POT_BOUND)) for q in m.neighbours(start)))
    return all_of(D, any_of(D, D.le(k, j), Reached(D, pot[start])), any_of(D, Reached(D, pot[start]), beside))


@obligation(QueuedStartReached, expect={"real": "proved", "fp32": "proved",
                                        "fp32@x86-64-v3": "proved", "fp32@aarch64": "proved"}, arrays=True,
            scope="the start of a cycle's updates and their end (k = 0 and k = curPe), any fill and any slot of "
                  "the start: every map size")
def queued_start_is_beside_a_reached_cell_as_the_updates_start_and_reached_when_they_end(D):
    """As a cycle's updates start (k = 0), a start waiting in the current buffer is beside a reached
    cell, which is below the bound: Q(0); when they end (k = curPe, past the start's slot), Q gives
    the start reached.

    the start at slot j < curPe of cur, a reached 4-neighbour of it (R2), reached cells below the bound
    ==>  Q(0), and (Q(curPe)  ==>  the start reached)
    """
    m, s, pot, j, start = _waiting_start(D)
    fill = s.fill["cur"]
    ring = m.neighbours(start)
    pre = all_of(D, m.well_formed(), D.ge(j, 0), D.lt(j, fill), at_slot(D, s, "cur", j),
                 any_of(D, *(Reached(D, pot[q]) for q in ring)),
                 *(any_of(D, D.not_(Reached(D, pot[q])), D.lt(pot[q], D.f32const(POT_BOUND))) for q in ring))
    ends = any_of(D, D.not_(_loop_invariant(D, m, s, pot, j, start, fill)), Reached(D, pot[start]))
    return pre, all_of(D, _loop_invariant(D, m, s, pot, j, start, 0), ends)


@obligation(QueuedStartReached, expect={"real": "proved", "fp32": "proved",
                                        "fp32@x86-64-v3": "proved", "fp32@aarch64": "proved"}, arrays=True,
            scope="updateCell or updateCellAstar at any slot k of the current buffer, any slot of the start, any "
                  "neighbours: every map size")
def update_of_any_slot_keeps_a_passed_queued_start_reached(D):
    """updateCell at slot k of the current buffer takes Q from k to k + 1: at the start's own slot
    the start, passable (the buffer invariant) and beside a cell below the bound, gets reached
    (queued_cell_gets_reached); at any other slot the write lowers one potential at most
    (Monotone), so a reached start stays reached and a neighbour below the bound stays below.

    Q(k), 0 <= k < curPe, the start at slot j of cur, P at the start and the updated cell, valid
    potentials at them and their neighbours, passable costs in [50, 253]
    ==>  Q(k + 1) after pot[n] := updateCell(n), n the cell of slot k
    """
    m, s, pot, j, start = _waiting_start(D)
    k = D.int32("k")
    n = s.slots["cur"][k]
    new, _ = K.cell_update(D, pot[n], *(pot[q] for q in m.updated(n)), m.cost_int(n), D.cost_as_f32(m.cost[n]))
    after = z3.Store(pot, n, new)
    cells = [start, n]
    read = [*cells, *m.neighbours(start), *m.neighbours(n)]
    pre = all_of(D, m.well_formed(), D.ge(k, 0), D.lt(k, s.fill["cur"]), D.ge(j, 0), D.lt(j, s.fill["cur"]),
                 at_slot(D, s, "cur", j), at_slot(D, s, "cur", k), *(at_cell(D, m, s, q, True) for q in cells),
                 *(ValidPotential(D, pot[q]) for q in read),
                 *(any_of(D, D.not_(m.passable(q)), TranslatedCost(D, m.cost_int(q))) for q in cells),
                 _loop_invariant(D, m, s, pot, j, start, k))
    return pre, _loop_invariant(D, m, s, after, j, start, D.add_int(k, 1))
