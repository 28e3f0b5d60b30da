"""The priority buffers as arrays, proved inductive on a map of any size (issue #39): each
pending cell is in exactly one buffer slot, no slot repeats a cell, and every buffered cell is
a passable cell of the goal's component, on the map.

The state is what propagation keeps, as SMT arrays over cell numbers and slot numbers (the
domain's int: a 32-bit bit-vector in float32 semantics, an integer over the reals): the
``pending`` flags, and per buffer (current, next, overflow) its slots and its fill.  Ghost
arrays the C++ has not say where each cell is: ``inside[b][q]`` (cell ``q`` is in buffer
``b``) and ``slot_of[b][q]`` (at which slot).  The invariant, asked at an arbitrary cell ``q``
and an arbitrary slot ``i`` of each buffer (so at every cell and slot):

- a cell inside a buffer sits in a filled slot of it: ``0 <= slot_of[b][q] < fill[b]`` and
  ``slots[b][slot_of[b][q]] = q``; a filled slot's cell is inside its buffer at that slot (so
  no two slots of a buffer hold the same cell);
- a cell inside a buffer is on the map (``0 <= q < ns``), passable and in the component;
- between cycles (B): ``pending[q]`` exactly when ``q`` is in the current or the overflow
  buffer, never in both, and the next buffer is empty; while a cycle runs (P): ``pending[q]``
  exactly when ``q`` is in the next or the overflow buffer, never in both (the cells of the
  current buffer have had their flags cleared and may be pushed again).

The component is any set of cells closed as the goal's component is: the goal's passable
4-neighbours are in it, and a passable 4-neighbour of a cell in it is in it (each obligation
assumes these at the cells it reads); the least such set is the goal's component.

The steps are the spec's own: :mod:`navfn_smt.smt.program` runs
:func:`~navfn_smt.spec.propagation.init_cost` and :func:`~navfn_smt.spec.propagation.propagate`
over these arrays, their loops (the cycles; the clearing of the current buffer's flags; the
updates, each with its four pushes) cut at the invariants B, C(k) and P, and each obligation is
one segment of that run.  Every segment has its obligation; the chain is the data of
:data:`navfn_smt.proofs.BuffersInductive`.  ReachedAndBufferedInductive's obligations (below)
are stated on the same run.
"""

import copy

import z3

from navfn_smt.proofs import BuffersInductive, ReachedAndBufferedInductive
from navfn_smt.smt.obligation import obligation
from navfn_smt.smt.predicates import Reached, ValidPotential, all_of
from navfn_smt.spec import kernels as K
from navfn_smt.spec.propagation import update_neighbours
from navfn_smt.smt.program import SEGMENTS, as_one, both_modes, cell_sort, condition

BUFFERS = ("cur", "nxt", "over")
# proved in every semantics; a model of a negation is over arrays, which the concrete spec cannot replay
STATED = dict(expect={"real": "proved", "fp32": "proved", "fp32@x86-64-v3": "proved", "fp32@aarch64": "proved"},
              arrays=True)


class Buffers:
    """Propagation's flags and buffers, with the ghost positions, in the domain ``D``."""

    def __init__(self, D):
        self.D = D
        cell = cell_sort(D)
        self.pending = z3.Array("pending", cell, z3.BoolSort())
        self.slots = {b: z3.Array(f"slots_{b}", cell, cell) for b in BUFFERS}
        self.fill = {b: D.int32(f"fill_{b}") for b in BUFFERS}
        self.inside = {b: z3.Array(f"inside_{b}", cell, z3.BoolSort()) for b in BUFFERS}
        self.slot_of = {b: z3.Array(f"slot_of_{b}", cell, cell) for b in BUFFERS}

    def copy(self, **changes):
        """The same state with some arrays or fills replaced."""
        new = copy.copy(self)
        new.__dict__.update(changes)
        return new


class Map:
    """The costs, the map's size, the goal, the component and the buffers' capacity (any: the C++'s
    PRIORITYBUFSIZE, or the spec's unbounded one): shared by every state."""

    def __init__(self, D):
        self.D = D
        self.ns, self.nx, self.g = D.int32("ns"), D.int32("nx"), D.int32("goal")
        self.capacity = D.int32("capacity")
        self.cost = z3.Array("cost", cell_sort(D), D.cost("cost_sort").sort())
        self.comp = z3.Array("component", cell_sort(D), z3.BoolSort())

    def cost_int(self, q):
        return self.D.cost_int(self.cost[q])

    def neighbours(self, q):
        """``n+1, n-1, n-nx, n+nx``: the order of initCost's pushes."""
        return q + 1, q - 1, q - self.nx, q + self.nx

    def updated(self, q):
        """``n-1, n+1, n-nx, n+nx``: the order updateCell reads its neighbours (``l, r, u, d``) and
        pushes them, the spec's (:func:`~navfn_smt.spec.propagation.update_neighbours`)."""
        return update_neighbours(q, self.nx)

    def neighbour(self, q, e):
        """The 4-neighbour of ``q`` in direction ``e`` (0..3, as :meth:`neighbours`)."""
        nb = self.neighbours(q)
        return z3.If(e == 0, nb[0], z3.If(e == 1, nb[1], z3.If(e == 2, nb[2], nb[3])))

    def passable(self, q):
        return K.is_passable(self.D, self.cost_int(q))

    def on_map(self, q):
        D = self.D
        return D.and_(D.ge(q, 0), D.lt(q, self.ns))

    def closed_at(self, q):
        """The component's closure, at cell ``q``: a passable 4-neighbour of the goal or of a
        cell of the component is in it."""
        near_goal = z3.Or([q == m for m in self.neighbours(self.g)])
        beside = z3.Or([self.comp[m] for m in self.neighbours(q)])
        return z3.Implies(z3.And(self.passable(q), z3.Or(near_goal, beside)), self.comp[q])

    def well_formed(self):
        D = self.D
        return all_of(D, D.ge(self.nx, 1), D.ge(self.ns, self.nx), D.le(self.ns, 2 ** 30), D.ge(self.capacity, 0))


def at_cell(D, m: Map, s: Buffers, q, during, clearing=None):
    """The invariant at cell ``q``: B (between cycles) or P (``during`` a cycle); with
    ``clearing`` = k, the clearing loop's C(k): B but that a cell of the current buffer is
    pending exactly when its slot is k or more."""
    parts = []
    for b in BUFFERS:
        k = s.slot_of[b][q]
        parts.append(z3.Implies(s.inside[b][q], z3.And(D.ge(k, 0), D.lt(k, s.fill[b]), s.slots[b][k] == q,
                                                       m.on_map(q), m.passable(q), m.comp[q])))
    a, c = ("nxt", "over") if during else ("cur", "over")
    first = s.inside[a][q]
    if clearing is not None:
        first = z3.And(first, D.ge(s.slot_of["cur"][q], clearing))
    parts += [s.pending[q] == z3.Or(first, s.inside[c][q]), z3.Not(z3.And(s.inside[a][q], s.inside[c][q]))]
    return z3.And(parts)


def at_slot(D, s: Buffers, b: str, i):
    """The invariant at slot ``i`` of buffer ``b``: a filled slot's cell is inside ``b`` there."""
    c = s.slots[b][i]
    return z3.Implies(z3.And(D.ge(i, 0), D.lt(i, s.fill[b])), z3.And(s.inside[b][c], s.slot_of[b][c] == i))


def fills(D, m: "Map", s: Buffers, during: bool):
    """Each fill within the buffers' capacity; between cycles the next buffer is empty."""
    parts = [z3.And(D.ge(s.fill[b], 0), D.le(s.fill[b], m.capacity)) for b in BUFFERS]
    if not during:
        parts.append(D.eq(s.fill["nxt"], 0))
    return z3.And(parts)


# ---------------------------------------------------- the spec's loops, cut at their invariants
def buffer_invariant(D, m: Map):
    """B at the cycle loop, C(k) at the clearing loop, P at the update loop (the bound: the
    current buffer's fill, which neither loop changes): ``(whole, at_cell, at_slot)``."""
    def at(loop, s, k, bound):
        during = loop == "update"
        whole = [fills(D, m, s, during)]
        if loop != "cycle":
            whole += [D.eq(s.fill["cur"], bound), D.ge(k, 0), D.le(k, bound)]
        clearing = k if loop == "clear" else None
        return (z3.And(whole), lambda q: at_cell(D, m, s, q, during, clearing),
                lambda b, i: at_slot(D, s, b, i))
    return at


def buffer_condition(D, source: str, target: str, modes=(False, True)):
    """The condition of the spec's segment from ``source`` to ``target``, for A* and for Dijkstra
    (their keys differ), the invariant asked at any cell q and slot i: (pre, claim).  The buffers
    read no float: the run leaves every float result free (:class:`~.program.FreeFloats`), which
    covers every arithmetic."""
    m = Map(D)
    q, i = D.int32("q"), D.int32("i")
    return both_modes(D, m, lambda segs: condition(D, m, segs[(source, target)], buffer_invariant(D, m), q, i),
                      free_floats=True, modes=modes)


@obligation(BuffersInductive, **STATED,
            scope="the spec's setupNavFn and initCost at any goal of a map of any size (the domain's int cell numbers)")
def setup_puts_each_pending_cell_in_one_slot(D):
    """After setupNavFn (no flag set, every buffer empty) and initCost's four ``push_cur`` of the
    goal's neighbours, the buffer invariant B holds at every cell and slot.

    the component closed at the cells initCost reads  ==>  B at any cell q and slot i of every buffer
    """
    return buffer_condition(D, "setup", "cycle")


@obligation(BuffersInductive, **STATED,
            scope="the start of any cycle of the spec's propNavFn*, on a map of any size")
def a_cycle_starts_with_every_flag_to_clear(D):
    """A cycle starts the clearing loop in its invariant C(0): B.

    B at q, slot i  ==>  C(0) at q and slot i, the bound the current buffer's fill
    """
    return buffer_condition(D, "cycle", "clear")


@obligation(BuffersInductive, **STATED,
            scope="one iteration of the spec's loop clearing the current buffer's flags, on a map of any size")
def clearing_a_flag_keeps_the_clearing_invariant(D):
    """One iteration ``pending[curP[k]] = false`` keeps the clearing loop's invariant C(k): B but
    that a cell of the current buffer is pending exactly when its slot is at least ``k``.

    C(k) at q, at the cell and slot read, 0 <= k < fill of cur  ==>  C(k + 1) at q and slot i
    """
    return buffer_condition(D, "clear", "clear")


@obligation(BuffersInductive, **STATED,
            scope="the end of the spec's clearing loop and the start of its update loop, on a map of any size")
def cleared_flags_give_the_cycle_invariant(D):
    """When the clearing loop is done (k = fill of cur), its invariant is P, the update loop's.

    C(fill of cur) at q, slot i  ==>  P at q and slot i
    """
    return buffer_condition(D, "clear exit", "update")


# one iteration of the update loop, a query per mode: as one condition the two take a solver ten
# times longer than apart (96 s against 9 and 9 in float32, x86-64); float32's in `prove --all`
SLOW = ("fp32", "fp32@x86-64-v3", "fp32@aarch64")


@obligation(BuffersInductive, slow=SLOW, **STATED,
            scope="one iteration of the spec's update loop (updateCell on slot k of the current buffer, with its "
                  "four pushes), on a map of any size")
def update_keeps_each_pending_cell_in_one_slot(D):
    """An update (Dijkstra's) of the cell in slot k of cur keeps P: each push puts its cell in one
    slot (the next free one of the buffer to_low_buffer picks), its flag set, and only a passable
    cell of the component on the map enters.

    P at q, slot i, and at the cells and slots the update touches; the component closed at them;
    k < fill of cur  ==>  P at q and slot i after the update
    """
    return buffer_condition(D, "update", "update", modes=(False,))


@obligation(BuffersInductive, slow=SLOW, **STATED,
            scope="one iteration of the spec's update loop (updateCellAstar on slot k of the current buffer, with "
                  "its four pushes), on a map of any size")
def astar_update_keeps_each_pending_cell_in_one_slot(D):
    """An update of A* (its key the potential plus the heuristic) of the cell in slot k of cur
    keeps P, as Dijkstra's does.

    P at q, slot i, and at the cells and slots the update touches; the component closed at them;
    k < fill of cur  ==>  P at q and slot i after the update
    """
    return buffer_condition(D, "update", "update", modes=(True,))


@obligation(BuffersInductive, **STATED,
            scope="the end of the spec's update loop and of the cycle (kernels.end_of_cycle: the fills and the "
                  "buffers' roles), on a map of any size")
def swap_keeps_each_pending_cell_in_one_slot(D):
    """The swap at a cycle's end turns P into B: the next buffer becomes current (when it is
    empty, the overflow buffer does), the buffer left behind is empty.

    P at q and slot i  ==>  B at q and slot i after the swap
    """
    return buffer_condition(D, "update exit", "cycle")


# ------------------------------------------------------------------------------------------
# Reached and buffered cells (ReachedAndBufferedInductive): with the potential array beside the
# buffers, two more facts of every cell q, on a map of any size:
#   R1  a reached cell (pot[q] < POT_HIGH) is the goal or a cell of the component;
#   R2  a buffered cell (inside any buffer) has a reached 4-neighbour.
# The steps: setup and initCost, updateCell's write at a cell of the current buffer, a push of
# a 4-neighbour of a cell the update changed (only such an update pushes), the swap.  The
# clearing loop changes only flags, which R1 and R2 do not read.
# ------------------------------------------------------------------------------------------
def reach(D, m: Map, s: Buffers, pot, q):
    """R1 and R2 at cell ``q``."""
    buffered = z3.Or([s.inside[b][q] for b in BUFFERS])
    beside = z3.Or([Reached(D, pot[j]) for j in m.neighbours(q)])
    return z3.And(z3.Implies(Reached(D, pot[q]), z3.Or(q == m.g, m.comp[q])), z3.Implies(buffered, beside))


def potentials(D):
    """The potential array, in the domain's float (its index the domain's int)."""
    return z3.Array("pot", cell_sort(D), D.f32const(0.0).sort())


def reach_condition(D, source: str, target: str):
    """The condition of the spec's segment from ``source`` to ``target`` for R1 and R2 at any cell
    q, with the buffer invariant and valid potentials (BuffersInductive,
    PositionSafeAndProgressInductive) assumed where the segment reads: (pre, claim).  R1 and R2
    read whether potentials are below POT_HIGH, not their values: the run leaves every float
    result free but its comparisons (:class:`~.program.FreeFloats`), which covers every
    arithmetic."""
    m = Map(D)
    q, i = D.int32("q"), D.int32("i")

    def at(loop, s, k, bound):
        return z3.BoolVal(True), (lambda c: reach(D, m, s, s.potential, c)), (lambda b, j: z3.BoolVal(True))

    def valid(loop, s, k, bound):
        return z3.BoolVal(True), (lambda c: ValidPotential(D, s.potential[c])), (lambda b, j: z3.BoolVal(True))

    return both_modes(D, m, lambda segs: condition(D, m, segs[(source, target)], at, q, i,
                                                   assumed=(buffer_invariant(D, m), valid)),
                      free_floats="arithmetic")


@obligation(ReachedAndBufferedInductive, **STATED,
            scope="the spec's setupNavFn and initCost at any goal of a map of any size (the domain's int cell numbers)")
def setup_reaches_the_goal_alone_and_buffers_its_neighbours(D):
    """After setupNavFn and initCost (every potential POT_HIGH but the goal's 0, the goal's four
    neighbours pushed), R1 and R2 hold at every cell.

    ==>  R1 and R2 at any cell q
    """
    return reach_condition(D, "setup", "cycle")


@obligation(ReachedAndBufferedInductive, **STATED,
            scope="the steps of the spec's propNavFn* but the updates (a cycle's start, the clearing loop, its end, "
                  "the swap), on a map of any size")
def the_steps_around_the_updates_keep_every_buffered_cell_beside_a_reached_one(D):
    """The clearing loop changes flags only, which R1 and R2 do not read; the swap moves cells
    between the buffers' roles and empties one: R1 and R2 stay.

    R1 and R2 at q  ==>  R1 and R2 at q after the step
    """
    return as_one(reach_condition(D, s, t) for s, t in SEGMENTS if s not in ("setup", "update"))


@obligation(ReachedAndBufferedInductive, **STATED,
            scope="one iteration of the spec's update loop (updateCell or updateCellAstar on slot k of the current "
                  "buffer, with its four pushes), on a map of any size")
def update_and_its_pushes_reach_only_cells_of_the_component(D):
    """An update of the cell n in slot k of cur (a cell of the component, by the buffer invariant)
    keeps R1 and R2: it writes only pot[n], never higher, and when it changes n, n is reached;
    its pushes, made only then, are of n's neighbours.

    P at the cells touched, R1 and R2 at q and there, valid potentials there
    ==>  R1 and R2 at q after the update and its pushes
    """
    return reach_condition(D, "update", "update")
