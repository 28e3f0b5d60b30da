"""The propagation loop's control flow (issue #39): when ``propNavFn*`` runs a cycle, when it
stops, and when the fix calls it again, checked on the very tests the spec and the JIT run
(``spec/propagation.py``: ``cycle_runs``, ``call_ends_at_the_start``; ``spec/fix.py``:
``calls_again``) and on the swap between cycles (``kernels.end_of_cycle``).

The state between two cycles is the buffers' fills: after initCost the current buffer holds
the goal's pushes and the other two are empty; after a swap, what ``end_of_cycle`` makes of any
next and overflow fills (the next buffer is then empty).  The loop stops at its top when its
cycles are spent or the current and the next buffer are both empty, and at a cycle's end when
the start is reached (A* always, Dijkstra with ``atStart``).  The fix calls ``propNavFn*`` once
more when the start is unreached and the current or the next buffer holds cells.

The start's potential is a valid one (a float32 in [0, POT_HIGH]: PositionSafeAndProgressInductive).
These obligations are about fills and one potential: they hold on a map of any size.
ConnectedStartReached takes the first (a run that ends leaves the start reached, every buffer
empty or the cycles spent), QueuedStartReached the second (a non-empty next buffer is the next
cycle's current buffer, and that cycle runs while cycles are left and the start is unreached).
"""

from navfn_smt.proofs import ConnectedStartReached, QueuedStartReached
from navfn_smt.smt.obligation import obligation
from navfn_smt.smt.predicates import Reached, ValidPotential, all_of, any_of
from navfn_smt.spec import fix as F
from navfn_smt.spec import kernels as K
from navfn_smt.spec import propagation as P

# fills and cycle numbers are ints; the one float is the start's potential, compared with POT_HIGH
LOOP = dict(expect={"real": "proved", "fp32": "proved", "fp32@x86-64-v3": "proved", "fp32@aarch64": "proved"})


def _between_cycles(D):
    """The fills between two cycles, ``(pre, cur, nxt, over)``: after initCost (``first``: the goal's
    pushes in the current buffer, the others empty) or after the swap of any next and overflow
    fills (``end_of_cycle``)."""
    first = D.not_(D.eq(D.int32("first"), 0))
    pushed, fill_next, fill_over = D.int32("pushed"), D.int32("fill_next"), D.int32("fill_over")
    _, cur, over, _ = K.end_of_cycle(D, fill_next, fill_over, D.f32("curT"), D.f32("priInc"))
    pre = all_of(D, D.ge(pushed, 0), D.le(pushed, 4), D.ge(fill_next, 0), D.ge(fill_over, 0))
    return pre, D.ite(first, pushed, cur), 0, D.ite(first, 0, over)


def _end_of_cycle_test(D):
    """The break at a cycle's end, as the loop runs it: ``(start_pot, ends)``, ``ends`` the start
    test (``call_ends_at_the_start``) when the call checks the start (``check_start``: A*, or
    Dijkstra with ``atStart``)."""
    start_pot = D.f32("start_pot")
    check = D.not_(D.eq(D.int32("check_start"), 0))
    return start_pot, D.and_(check, P.call_ends_at_the_start(D, start_pot))


@obligation(ConnectedStartReached, scope="the fills between any two cycles of propNavFn*, any cycle count, any "
            "start potential: every map size", **LOOP)
def propagation_stops_only_at_a_reached_start_with_empty_buffers_or_its_cycles_spent(D):
    """A ``propNavFn*`` call that stops (at its top: ``cycle_runs`` false; at a cycle's end:
    ``call_ends_at_the_start``), and the fix that then does not call it again (``calls_again``
    false), leave the start reached, all three buffers empty, or the call's cycles spent.

    fills between cycles, 0 <= cycle, a valid start potential  ==>  (not cycle_runs  ==>  cycle >= cycles or all three fills 0),
    (call_ends_at_the_start  ==>  the start reached), (not calls_again  ==>  reached or all empty)
    """
    pre, cur, nxt, over = _between_cycles(D)
    cycle, cycles = D.int32("cycle"), D.int32("cycles")
    start_pot, ends = _end_of_cycle_test(D)
    empty = all_of(D, D.eq(cur, 0), D.eq(nxt, 0), D.eq(over, 0))
    reached = Reached(D, start_pot)
    claim = all_of(D,
                   any_of(D, P.cycle_runs(D, cycle, cycles, cur, nxt), D.ge(cycle, cycles), empty),
                   any_of(D, D.not_(ends), reached),
                   any_of(D, F.calls_again(D, start_pot, cur, nxt), reached, empty))
    return all_of(D, pre, D.ge(cycle, 0), ValidPotential(D, start_pot)), claim


@obligation(QueuedStartReached, scope="the swap at the end of any cycle of propNavFn*, any cycle count, any start "
            "potential: every map size", **LOOP)
def next_buffer_becomes_current_and_its_cycle_runs(D):
    """A cycle that ends with cells in its next buffer makes that buffer the following cycle's current
    one, whole (``end_of_cycle``: not drained, the current fill is the next fill), and when the call
    does not end at the start (``call_ends_at_the_start`` false) and has cycles left, that cycle
    runs (``cycle_runs``).

    fill_next > 0, fill_over >= 0, 0 <= cycle < cycle + 1 < cycles  ==>  not drained, cur' = fill_next,
    over' = fill_over, and (not call_ends_at_the_start  ==>  cycle_runs(cycle + 1, cycles, cur', 0))
    """
    fill_next, fill_over = D.int32("fill_next"), D.int32("fill_over")
    cycle, cycles = D.int32("cycle"), D.int32("cycles")
    _, ends = _end_of_cycle_test(D)
    drained, cur, over, _ = K.end_of_cycle(D, fill_next, fill_over, D.f32("curT"), D.f32("priInc"))
    pre = all_of(D, D.gt(fill_next, 0), D.ge(fill_over, 0), D.ge(cycle, 0), D.lt(cycle, cycles),
                  D.lt(cycle + 1, cycles))
    runs = P.cycle_runs(D, cycle + 1, cycles, cur, 0)
    claim = all_of(D, D.not_(drained), D.eq(cur, fill_next), D.eq(over, fill_over),
                   any_of(D, ends, runs))
    return pre, claim
