"""The frontier, proved inductive over arrays on a map of any size (issue #39): every unreached
passable neighbour of a reached cell below the bound is pending, or a push was dropped.

Beside the buffers of :mod:`.buffers` (their slots, flags and ghost positions) the state has
the potential array and a ghost flag ``dropped``: some push of the run was refused for want of
room.  The invariant F, asked of an arbitrary cell p and its 4-neighbour c in direction e (so of
every such pair):

    p reached (pot[p] < POT_HIGH) and below the bound POT_BOUND = 2**30, c on the map, passable
    and unreached  ==>  c pending, or dropped, or (while the cycle's updates run, k the next slot
    of the current buffer) c waits in the current buffer at slot k or later.

The steps: setupNavFn and initCost; one iteration of the loop clearing the current buffer's
flags (a cleared cell waits in the current buffer); the updates' start and the cycle's end (the
swap changes no flag); one updateCell of slot k with its four pushes (an unreached cell beside a
reached one gets reached; a changed cell's unreached neighbours are wanted, then admitted,
already pending, or dropped).  At the exit, with both buffers empty and no push dropped, the
reached cells below the bound are closed: each one's passable 4-neighbours on the map are
reached (``empty_buffers_without_a_drop_leave_no_reached_cell_beside_an_unreached_one``).  The
chain is the data of :data:`navfn_smt.proofs.FrontierInductive`.
"""

import z3

from navfn_smt.proofs import FrontierInductive
from navfn_smt.proofs.buffers import (STATED, Buffers, Map, after_init_cost, at_cell, at_slot, cell_sort, fills,
                                      potentials, push, swapped)
from navfn_smt.smt.obligation import obligation
from navfn_smt.smt.predicates import Reached, TranslatedCost, ValidPotential, all_of
from navfn_smt.spec import kernels as K
from navfn_smt.spec.constants import POT_HIGH, PRIORITYBUFSIZE
from navfn_smt.proofs.fix import KEY_BOUND  # a push key: a potential below POT_BOUND plus A*'s heuristic
from navfn_smt.spec.fix import POT_BOUND


def pair_state(D, slot: str):
    """The state an obligation of F is asked in: the map, an arbitrary cell p and its neighbour c
    in direction e, the buffers, the potentials, the ghost ``dropped``, and the slot ``slot``."""
    m = Map(D)
    p, e = D.int32("p"), D.int32("e")
    return m, p, m.neighbour(p, e), Buffers(D), potentials(D), z3.Bool("dropped"), D.int32(slot)


def frontier(D, m, s, pot, dropped, p, c, k=None):
    """F at the pair (p, c), c a 4-neighbour of p: a reached p below the bound with c an unreached
    passable cell on the map has c pending, or a push was dropped, or (while the cycle's updates
    run, ``k`` the next slot of cur) c waits in cur at slot k or later."""
    lhs = z3.And(Reached(D, pot[p]), D.lt(pot[p], D.f32const(POT_BOUND)), m.on_map(c), m.passable(c),
                 z3.Not(Reached(D, pot[c])))
    rhs = [s.pending[c], dropped]
    if k is not None:
        rhs.append(z3.And(s.inside["cur"][c], D.ge(s.slot_of["cur"][c], k)))
    return z3.Implies(lhs, z3.Or(rhs))


@obligation(FrontierInductive, **STATED, scope="setupNavFn and initCost at any goal of a map of any size")
def setup_leaves_no_unreached_neighbour_unbuffered(D):
    """After setupNavFn and initCost (the goal alone reached, its four neighbours pushed) F holds.

    ==>  F at any cell p and its neighbour in any direction e
    """
    m = Map(D)
    p, e = D.int32("p"), D.int32("e")
    c = m.neighbour(p, e)
    s, zeros = after_init_cost(D, m)
    pot = z3.Store(z3.K(cell_sort(D), D.f32const(POT_HIGH)), m.g, D.f32const(0.0))
    pre = all_of(D, m.well_formed(), m.on_map(m.g), *zeros)
    return pre, frontier(D, m, s, pot, False, p, c)


@obligation(FrontierInductive, **STATED, scope="one iteration of the loop clearing the current buffer's flags, "
            "on a map of any size")
def clearing_a_flag_keeps_the_frontier(D):
    """One iteration ``pending[curP[j]] = false`` keeps F with every cell of the current buffer
    waiting (k = 0): the cleared cell is in the current buffer.

    F(k = 0) at (p, c), slot j of cur filled  ==>  F(k = 0) at (p, c) after
    """
    m, p, c, s, pot, dropped, j = pair_state(D, "j")
    x = s.slots["cur"][j]
    after = s.copy(pending=z3.Store(s.pending, x, False))
    pre = all_of(D, m.well_formed(), D.ge(j, 0), D.lt(j, s.fill["cur"]), at_slot(D, s, "cur", j),
                 frontier(D, m, s, pot, dropped, p, c, 0))
    return pre, frontier(D, m, after, pot, dropped, p, c, 0)


@obligation(FrontierInductive, **STATED, scope="the start of a cycle's updates and the end of the cycle (kernels."
            "end_of_cycle), on a map of any size")
def frontier_holds_as_the_updates_start_and_after_the_swap(D):
    """F between cycles gives F with k = 0; F with k = fill of cur (every update done) gives F
    after the swap, which changes no flag, potential or ``dropped``.

    P at c  ==>  (F at (p, c) ==> F(0) at (p, c)) and (F(fill of cur) at (p, c) ==> F after the swap)
    """
    m = Map(D)
    p, e = D.int32("p"), D.int32("e")
    c = m.neighbour(p, e)
    s = Buffers(D)
    pot = potentials(D)
    dropped = z3.Bool("dropped")
    after = swapped(D, m, s)
    pre = all_of(D, m.well_formed(), fills(D, s, True), at_cell(D, m, s, c, True))
    claim = z3.And(z3.Implies(frontier(D, m, s, pot, dropped, p, c), frontier(D, m, s, pot, dropped, p, c, 0)),
                   z3.Implies(frontier(D, m, s, pot, dropped, p, c, s.fill["cur"]),
                              frontier(D, m, after, pot, dropped, p, c)))
    return pre, claim


@obligation(FrontierInductive, **STATED, slow=("fp32", "fp32@x86-64-v3", "fp32@aarch64"),  # float32: 20-40 s
            scope="one updateCell or updateCellAstar of any slot of the current buffer "
            "with its four pushes, on a map of any size")
def update_and_its_pushes_keep_the_frontier(D):
    """updateCell on slot k of the current buffer, then its four pushes (in the update's
    `if (pot < potarr[n])` block: only when it changed its cell), takes F from k to k + 1.

    P at c, p, the updated cell n and its neighbours; valid potentials there; passable costs in
    [50, 253] at n and c (what setCostmap makes); a changed cell's key (its potential, plus A*'s
    heuristic) below 2**31; F(k) at (p, c) and at each neighbour of n with n
    ==>  F(k + 1) at (p, c) after the write and the pushes (``dropped`` set by a push refused
    for want of room)
    """
    m, p, c, s, pot, dropped, k = pair_state(D, "k")
    n = s.slots["cur"][k]
    nb = m.updated(n)
    new, changed = K.cell_update(D, pot[n], *(pot[j] for j in nb), m.cost_int(n), D.cost_as_f32(m.cost[n]))
    pot2 = z3.Store(pot, n, new)
    key = D.f32("key")  # new, or new plus A*'s heuristic
    low = K.to_low_buffer(D, key, D.f32("curT"))
    t = s
    drop = dropped
    for j in nb:
        wanted = D.and_(changed, K.push_wanted(D, pot[j], key, K.edge_weight(D, D.cost_as_f32(m.cost[j]))))
        fill_t = D.ite(low, t.fill["nxt"], t.fill["over"])
        _, lost, _ = K.push(D, j, m.ns, t.pending[j], m.cost_int(j), fill_t, PRIORITYBUFSIZE)
        drop = z3.Or(drop, D.and_(wanted, lost))
        t, _ = push(D, m, t, (low, "nxt", "over"), j, wanted)
    cells = [c, n, p, *nb]
    pre = all_of(D, m.well_formed(), fills(D, s, True), D.ge(k, 0), D.lt(k, s.fill["cur"]), at_slot(D, s, "cur", k),
                 *(at_cell(D, m, s, x, True) for x in cells), *(ValidPotential(D, pot[x]) for x in [n, *nb, p, c]),
                 z3.Implies(m.passable(n), TranslatedCost(D, m.cost_int(n))),
                 z3.Implies(m.passable(c), TranslatedCost(D, m.cost_int(c))),
                 z3.Implies(changed, z3.And(D.ge(key, new), D.lt(key, D.f32const(KEY_BOUND)))),
                 frontier(D, m, s, pot, dropped, p, c, k),
                 *(frontier(D, m, s, pot, dropped, x, n, k) for x in nb))
    return pre, frontier(D, m, t, pot2, drop, p, c, D.add_int(k, 1))


@obligation(FrontierInductive, **STATED, scope="the loop's exit with both buffers empty, on a map of any size")
def empty_buffers_without_a_drop_leave_no_reached_cell_beside_an_unreached_one(D):
    """When propagation stops with the current and the overflow buffer empty (the next one is,
    between cycles) and no push dropped, every passable 4-neighbour on the map of a reached cell
    below the bound is reached.

    B at c, F at (p, c), fills of cur and over 0, not dropped
    ==>  p reached below the bound and c passable on the map  ==>  c reached
    """
    m = Map(D)
    p, e = D.int32("p"), D.int32("e")
    c = m.neighbour(p, e)
    s = Buffers(D)
    pot = potentials(D)
    pre = all_of(D, m.well_formed(), fills(D, s, False), D.eq(s.fill["cur"], 0), D.eq(s.fill["over"], 0),
                 at_cell(D, m, s, c, False), frontier(D, m, s, pot, False, p, c))
    near = z3.And(Reached(D, pot[p]), D.lt(pot[p], D.f32const(POT_BOUND)), m.on_map(c), m.passable(c))
    return pre, z3.Implies(near, Reached(D, pot[c]))
