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

from navfn_smt.spec import kernels as K

from navfn_smt.proofs import FrontierInductive
from navfn_smt.proofs.buffers import STATED, Buffers, Map, at_cell, buffer_invariant, fills, potentials
from navfn_smt.smt.program import SEGMENTS, as_one, condition, segments
from navfn_smt.smt.obligation import obligation
from navfn_smt.smt.predicates import Reached, TranslatedCost, ValidPotential, all_of
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


def frontier_condition(D, source: str, target: str, astar: bool):
    """The condition of the spec's segment from ``source`` to ``target`` (A*'s run or Dijkstra's)
    for F at any cell p and each of its four neighbours: (pre, claim).  Assumed where the segment
    reads, at p and at p's neighbours: the buffer invariant (BuffersInductive), valid potentials
    (PositionSafeAndProgressInductive), passable costs in [50, 253] (what setCostmap makes); at an
    update, A*'s heuristic not negative and a changed cell's key below 2**31 (run-time
    conditions)."""
    m = Map(D)
    p = D.int32("p")

    def at(loop, s, k, bound):
        k = {"cycle": None, "clear": 0}.get(loop, k)  # while the flags are cleared every cell of cur waits
        return (z3.BoolVal(True),
                lambda x: z3.And([frontier(D, m, s, s.potential, s.dropped, x, c, k) for c in m.neighbours(x)]),
                lambda b, j: z3.BoolVal(True))

    def facts(loop, s, k, bound):
        return (z3.BoolVal(True), lambda x: z3.And(ValidPotential(D, s.potential[x]),
                                                  z3.Implies(m.passable(x), TranslatedCost(D, m.cost_int(x)))),
                lambda b, j: z3.BoolVal(True))

    seg = segments(D, m, astar)[(source, target)]
    given = []
    if source == "update":
        n = seg.before.slots["cur"][seg.k]
        old, new = seg.before.potential[n], seg.after.potential[n]
        key = new
        for h in seg.heuristics:
            key = D.add(new, h)
            given.append(D.ge(h, D.f32const(0.0)))
        given.append(z3.Implies(D.lt(new, old), D.lt(key, D.f32const(KEY_BOUND))))
    return condition(D, m, seg, at, p, D.int32("i"), given=given, near=m.neighbours(p),
                     assumed=(buffer_invariant(D, m), facts))


def frontier_holds(D, pairs):
    """The conditions of ``pairs`` of segments, in both modes, as one: (True, their implications)."""
    return as_one(frontier_condition(D, s, t, astar) for s, t in pairs for astar in (False, True))


@obligation(FrontierInductive, expect=STATED["expect"], scope="A*'s heuristic between any two cells")
def astar_heuristic_is_not_negative(D):
    """The heuristic ``hypot(dx, dy) * COST_NEUTRAL`` of kernels.astar_heuristic is not negative,
    for any int offsets (what the update's condition assumes of it).

    any ints dx, dy  ==>  astar_heuristic(dx, dy) >= 0
    """
    return z3.BoolVal(True), D.ge(K.astar_heuristic(D, D.int32("dx"), D.int32("dy")), D.f32const(0.0))


@obligation(FrontierInductive, **STATED, scope="the spec's setupNavFn and initCost at any goal of a map of any size")
def setup_leaves_no_unreached_neighbour_unbuffered(D):
    """After setupNavFn and initCost (the goal alone reached, its four neighbours pushed) F holds.

    ==>  F at any cell p and each of its neighbours
    """
    return frontier_holds(D, [("setup", "cycle")])


@obligation(FrontierInductive, **STATED, scope="the steps of the spec's propNavFn* but the updates (a cycle's "
            "start, the clearing loop, its end, the swap), on a map of any size")
def the_steps_around_the_updates_keep_the_frontier(D):
    """A cycle starts with every cell of cur waiting (k = 0); clearing a flag leaves its cell
    waiting in cur; the updates start at k = 0; after the last (k = fill of cur) the swap changes
    no flag, potential or ``dropped``.

    F at (p, c), the buffer invariant  ==>  F at (p, c) after the step
    """
    return frontier_holds(D, [(s, t) for s, t in SEGMENTS if s not in ("setup", "update")])


@obligation(FrontierInductive, **STATED, slow=("fp32", "fp32@x86-64-v3", "fp32@aarch64"),
            scope="one iteration of the spec's update loop (updateCell or updateCellAstar on slot k of the current "
                  "buffer, with its four pushes), on a map of any size")
def update_and_its_pushes_keep_the_frontier(D):
    """updateCell on slot k of the current buffer, then its four pushes (only when it changed its
    cell), takes F from k to k + 1.

    P, valid potentials, passable costs in [50, 253] at p, its neighbours and the cells the update
    touches; a changed cell's key (its potential, plus A*'s heuristic, not negative) below 2**31;
    F(k) there  ==>  F(k + 1) at (p, c) after the write and the pushes (``dropped`` set by a push
    refused for want of room)
    """
    return frontier_holds(D, [("update", "update")])


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
    pre = all_of(D, m.well_formed(), fills(D, m, s, False), D.eq(s.fill["cur"], 0), D.eq(s.fill["over"], 0),
                 at_cell(D, m, s, c, False), frontier(D, m, s, pot, False, p, c))
    near = z3.And(Reached(D, pot[p]), D.lt(pot[p], D.f32const(POT_BOUND)), m.on_map(c), m.passable(c))
    return pre, z3.Implies(near, Reached(D, pot[c]))
