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
from navfn_smt.proofs.buffers import Map, buffer_invariant
from navfn_smt.smt.program import as_one, both_modes, condition
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
# The spec's update loop over the current buffer (smt/program.py), cut at its invariant.  The start
# waits in the current buffer at a ghost slot j (slots[j] = start); the invariant Q(k), k the next
# slot to update:
#     k > j  ==>  the start is reached;   and the start is reached or a 4-neighbour of it is
#     below the bound.
# Q(0) holds as the updates start (a buffered cell has a reached 4-neighbour:
# ReachedAndBufferedInductive; below the bound: the run-time condition), every update keeps it
# from k to k + 1, and Q(curPe) with j < curPe is the start reached after the swap.
# ------------------------------------------------------------------------------------------
def _loop_invariant(D, m, pot, j, start, k):
    """Q(k): past its slot, the start is reached; else it is reached or beside a cell below the bound."""
    beside = any_of(D, *(D.lt(pot[q], D.f32const(POT_BOUND)) for q in m.neighbours(start)))
    return all_of(D, any_of(D, D.le(k, j), Reached(D, pot[start])), any_of(D, Reached(D, pot[start]), beside))


def queued_condition(D, source: str, target: str):
    """The condition of the spec's segment from ``source`` to ``target`` (Dijkstra's run and A*'s)
    for a start waiting at slot j of the current buffer: as the updates start, beside a reached
    cell below the bound; Q(k) through the updates; reached after the swap.  Assumed: the buffer
    invariant at the start and where the segment reads, valid potentials there and beside the
    start, passable costs in [50, 253] there: (pre, claim)."""
    m = Map(D)
    j, start = D.int32("j"), D.int32("start")
    ring = m.neighbours(start)

    def at(loop, s, k, bound):
        pot = s.potential
        waits = all_of(D, s.slots["cur"][j] == start, D.ge(j, 0), D.lt(j, s.fill["cur"]))
        if loop == "clear":  # queued: beside a reached cell (R2), reached cells below the bound
            whole = all_of(D, waits, any_of(D, *(Reached(D, pot[q]) for q in ring)),
                           *(any_of(D, D.not_(Reached(D, pot[q])), D.lt(pot[q], D.f32const(POT_BOUND)))
                             for q in ring))
        elif loop == "update":
            whole = all_of(D, waits, D.eq(s.fill["cur"], bound), _loop_invariant(D, m, pot, j, start, k))
        else:
            whole = Reached(D, pot[start])
        return whole, (lambda c: z3.BoolVal(True)), (lambda b, i: z3.BoolVal(True))

    def facts(loop, s, k, bound):
        return (z3.BoolVal(True), lambda c: z3.And(ValidPotential(D, s.potential[c]),
                                                  z3.Implies(m.passable(c), TranslatedCost(D, m.cost_int(c)))),
                lambda b, i: z3.BoolVal(True))

    return both_modes(D, m, lambda segs: condition(D, m, segs[(source, target)], at, start, j,
                                                   near=(start, *ring), assumed=(buffer_invariant(D, m), facts)))


@obligation(QueuedStartReached, expect={"real": "proved", "fp32": "proved",
                                        "fp32@x86-64-v3": "proved", "fp32@aarch64": "proved"}, arrays=True,
            scope="the start of the spec's update loop and its end with the swap, any fill and any slot of the "
                  "start: every map size")
def queued_start_is_beside_a_reached_cell_as_the_updates_start_and_reached_when_they_end(D):
    """As a cycle's updates start (k = 0), a start waiting in the current buffer is beside a reached
    cell, which is below the bound: Q(0); when they end (k = curPe, past the start's slot), Q gives
    the start reached, which the swap keeps.

    the start at slot j < curPe of cur, a reached 4-neighbour of it (R2), reached cells below the bound
    ==>  Q(0);   Q(curPe)  ==>  the start reached after the swap
    """
    return as_one(queued_condition(D, s, t) for s, t in (("clear exit", "update"), ("update exit", "cycle")))


@obligation(QueuedStartReached, expect={"real": "proved", "fp32": "proved",
                                        "fp32@x86-64-v3": "proved", "fp32@aarch64": "proved"}, arrays=True,
            slow=("fp32", "fp32@x86-64-v3", "fp32@aarch64"),
            scope="one iteration of the spec's update loop (updateCell or updateCellAstar at any slot k of the "
                  "current buffer, with its pushes), any slot of the start: every map size")
def update_of_any_slot_keeps_a_passed_queued_start_reached(D):
    """The update of slot k of the current buffer takes Q from k to k + 1: at the start's own slot
    the start, passable (the buffer invariant) and beside a cell below the bound, gets reached
    (queued_cell_gets_reached); at any other slot the write lowers one potential at most
    (Monotone), so a reached start stays reached and a neighbour below the bound stays below.

    Q(k), 0 <= k < curPe, the start at slot j of cur, P at the start and the cells the update reads,
    valid potentials there and beside the start, passable costs in [50, 253]
    ==>  Q(k + 1) after the update
    """
    return queued_condition(D, "update", "update")
