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

The steps are the ones the spec and the JIT run: setupNavFn and initCost's four
``push_cur`` (:func:`~navfn_smt.spec.kernels.push`), the loop clearing the current buffer's
flags (one iteration, with its loop invariant), one push of an update (``kernels.push`` into
the buffer ``kernels.to_low_buffer`` picks, of a 4-neighbour of a cell of the current
buffer), and the end of the cycle (``kernels.end_of_cycle``: the fills, the buffers' roles).
The chain is the data of :data:`navfn_smt.proofs.BuffersInductive`.
"""

import copy

import z3

from navfn_smt.proofs import BuffersInductive, ReachedAndBufferedInductive
from navfn_smt.smt.obligation import obligation
from navfn_smt.smt.predicates import Reached, ValidPotential, all_of
from navfn_smt.spec import kernels as K
from navfn_smt.spec.constants import POT_HIGH, PRIORITYBUFSIZE
from navfn_smt.spec.propagation import update_neighbours

BUFFERS = ("cur", "nxt", "over")
# proved in every semantics; a model of a negation is over arrays, which the concrete spec cannot replay
STATED = dict(expect={"real": "proved", "fp32": "proved", "fp32@x86-64-v3": "proved", "fp32@aarch64": "proved"},
              arrays=True)


def cell_sort(D):
    """The sort of a cell or slot number: the domain's int (32-bit bit-vector, or integer)."""
    return D.int32("i_sort_probe").sort()


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
    """The costs, the map's size, the goal and the component: shared by every state."""

    def __init__(self, D):
        self.D = D
        self.ns, self.nx, self.g = D.int32("ns"), D.int32("nx"), D.int32("goal")
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
        return all_of(D, D.ge(self.nx, 1), D.ge(self.ns, self.nx), D.le(self.ns, 2 ** 30))


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


def fills(D, s: Buffers, during: bool):
    """Each fill within the capacity; between cycles the next buffer is empty."""
    parts = [z3.And(D.ge(s.fill[b], 0), D.le(s.fill[b], PRIORITYBUFSIZE)) for b in BUFFERS]
    if not during:
        parts.append(D.eq(s.fill["nxt"], 0))
    return z3.And(parts)


def invariant(D, m: Map, s: Buffers, cells, slots, during: bool):
    """The invariant at the given cells and at the given slot of every buffer."""
    return z3.And(fills(D, s, during), *(at_cell(D, m, s, q, during) for q in cells),
                  *(at_slot(D, s, b, i) for i in slots for b in BUFFERS))


def push(D, m: Map, s: Buffers, target, n, wanted):
    """One ``push_*`` macro on cell ``n`` into ``target`` (a buffer's name, or ``(cond, if, else)``
    for the one ``to_low_buffer`` picks), when the update ``wanted`` it: (state after, admitted)."""
    if isinstance(target, tuple):
        cond, yes, no = target
        fill_t = D.ite(cond, s.fill[yes], s.fill[no])
        into = {yes: cond, no: z3.Not(cond)}
    else:
        fill_t = s.fill[target]
        into = {target: True}
    pushed, _, pending_after = K.push(D, n, m.ns, s.pending[n], m.cost_int(n), fill_t, PRIORITYBUFSIZE)
    admitted = D.and_(wanted, pushed)
    slots, fill, inside, slot_of = dict(s.slots), dict(s.fill), dict(s.inside), dict(s.slot_of)
    for b, sel in into.items():
        here = D.and_(admitted, sel)
        slots[b] = z3.If(here, z3.Store(s.slots[b], s.fill[b], n), s.slots[b])
        inside[b] = z3.If(here, z3.Store(s.inside[b], n, True), s.inside[b])
        slot_of[b] = z3.If(here, z3.Store(s.slot_of[b], n, s.fill[b]), s.slot_of[b])
        fill[b] = D.ite(here, D.add_int(s.fill[b], 1), s.fill[b])
    pending = z3.Store(s.pending, n, D.ite(wanted, pending_after, s.pending[n]))
    return s.copy(slots=slots, fill=fill, inside=inside, slot_of=slot_of, pending=pending), admitted


def swapped(D, m: Map, s: Buffers) -> Buffers:
    """The state after the swap at a cycle's end (``kernels.end_of_cycle``: the fills, and the
    buffers' roles as the C++'s pointer swaps give them)."""
    drained, fill_cur, fill_over, _ = K.end_of_cycle(D, s.fill["nxt"], s.fill["over"], D.f32("curT"), D.f32("inc"))
    nothing = z3.K(cell_sort(D), False)
    role = {"cur": lambda a: z3.If(drained, a["over"], a["nxt"]),
            "nxt": lambda a: a["cur"],
            "over": lambda a: z3.If(drained, a["nxt"], a["over"])}
    return s.copy(slots={b: role[b](s.slots) for b in BUFFERS}, slot_of={b: role[b](s.slot_of) for b in BUFFERS},
                   # the ghost: a buffer left behind empty holds no cell
                   inside={"cur": role["cur"](s.inside), "nxt": nothing, "over": z3.If(drained, nothing, s.inside["over"])},
                   fill={"cur": fill_cur, "nxt": D.int32("zero_nxt"), "over": fill_over})


def after_init_cost(D, m: Map):
    """setupNavFn (no flag set, every buffer empty) then initCost's four ``push_cur`` of the
    goal's neighbours: (the state, the fills' zeros to assume)."""
    nothing = z3.K(cell_sort(D), False)
    s = Buffers(D).copy(pending=nothing, fill={b: D.int32(f"zero_{b}") for b in BUFFERS},
                        inside={b: nothing for b in BUFFERS})
    zeros = [D.eq(s.fill[b], 0) for b in BUFFERS]
    for n in m.neighbours(m.g):
        s, _ = push(D, m, s, "cur", n, True)
    return s, zeros


# ------------------------------------------------------------------------------ the base case
@obligation(BuffersInductive, **STATED,
            scope="setupNavFn and initCost at any goal of a map of any size (the domain's int cell numbers)")
def setup_puts_each_pending_cell_in_one_slot(D):
    """After setupNavFn (no flag set, every buffer empty) and initCost's four ``push_cur`` of the
    goal's neighbours, the buffer invariant B holds at every cell and slot.

    costs any, the component closed at the four neighbours
    ==>  B at any cell q and at slot i of every buffer
    """
    m = Map(D)
    q, i = D.int32("q"), D.int32("i")
    s, zeros = after_init_cost(D, m)
    closed = [m.closed_at(n) for n in m.neighbours(m.g)]
    pre = all_of(D, m.well_formed(), m.on_map(m.g), *zeros, *closed)
    return pre, invariant(D, m, s, [q], [i], during=False)


# ------------------------------------------------------------------ the start of a cycle
@obligation(BuffersInductive, **STATED,
            scope="one iteration of the loop clearing the current buffer's flags, on a map of any size")
def clearing_a_flag_keeps_the_clearing_invariant(D):
    """One iteration ``pending[curP[j]] = false`` of the loop at a cycle's start keeps its loop
    invariant C(j): B but that a cell of the current buffer is pending exactly when its slot is
    at least ``j``.  C(0) is B; C(fill of cur) is P (the next buffer being empty).

    C(j) at q, at slot j of cur and at the cells and slots read, 0 <= j < fill of cur
    ==>  C(j + 1) at q and at slot i of every buffer
    """
    m = Map(D)
    q, i, j = D.int32("q"), D.int32("i"), D.int32("j")
    s = Buffers(D)
    c = s.slots["cur"][j]
    after = s.copy(pending=z3.Store(s.pending, c, False))
    pre = all_of(D, m.well_formed(), fills(D, s, False), D.ge(j, 0), D.lt(j, s.fill["cur"]),
                 at_cell(D, m, s, q, False, j), at_cell(D, m, s, c, False, j), at_slot(D, s, "cur", j),
                 *(at_slot(D, s, b, i) for b in BUFFERS))
    claim = z3.And(at_cell(D, m, after, q, False, D.add_int(j, 1)), *(at_slot(D, after, b, i) for b in BUFFERS))
    return pre, claim


@obligation(BuffersInductive, **STATED,
            scope="the end of the loop clearing the current buffer's flags, on a map of any size")
def cleared_flags_give_the_cycle_invariant(D):
    """When the clearing loop is done (j = fill of cur), its invariant is P; at its start
    (j = 0) it is B.

    C(fill of cur) at q  ==>  P at q;   B at q  ==>  C(0) at q
    """
    m = Map(D)
    q = D.int32("q")
    s = Buffers(D)
    pre = all_of(D, m.well_formed(), fills(D, s, False))
    claim = z3.And(z3.Implies(at_cell(D, m, s, q, False, s.fill["cur"]), at_cell(D, m, s, q, True)),
                   z3.Implies(at_cell(D, m, s, q, False), at_cell(D, m, s, q, False, 0)))
    return pre, claim


# --------------------------------------------------------------------- a push of an update
@obligation(BuffersInductive, **STATED,
            scope="one push of updateCell or updateCellAstar, of a 4-neighbour of a cell of the current buffer, "
                  "into the buffer to_low_buffer picks, on a map of any size")
def push_keeps_each_pending_cell_in_one_slot(D):
    """A push of an update keeps P: the cell enters one slot (the next free one of its buffer),
    its flag set, and only a passable cell of the component on the map enters.

    P at q, at the pushed cell, at slot i and slot fill of every buffer, at the updated cell's
    slot k of cur; the component closed at the pushed cell; the pushed cell a 4-neighbour of
    the cell in slot k of cur, k < fill of cur; any wanted, key and curT
    ==>  P at q and at slot i of every buffer after the push
    """
    m = Map(D)
    q, i, k, d = D.int32("q"), D.int32("i"), D.int32("k"), D.int32("direction")
    s = Buffers(D)
    n = s.slots["cur"][k]  # the updated cell
    pushed = m.neighbour(n, d)
    wanted = z3.Bool("wanted")
    low = K.to_low_buffer(D, D.f32("key"), D.f32("curT"))
    after, _ = push(D, m, s, (low, "nxt", "over"), pushed, wanted)
    cells, slots = [q, pushed, n], [i, *(s.fill[b] for b in BUFFERS)]
    pre = all_of(D, m.well_formed(), invariant(D, m, s, cells, slots, True), at_slot(D, s, "cur", k),
                 D.ge(k, 0), D.lt(k, s.fill["cur"]), m.closed_at(pushed))
    return pre, invariant(D, m, after, [q], [i], True)


# ------------------------------------------------------------------------ the end of a cycle
@obligation(BuffersInductive, **STATED,
            scope="the end of any cycle (kernels.end_of_cycle: the fills and the buffers' roles), on a map of any "
                  "size")
def swap_keeps_each_pending_cell_in_one_slot(D):
    """The swap at a cycle's end turns P into B: the next buffer becomes current (when it is
    empty, the overflow buffer does), the buffer left behind is empty.

    P at q and at slot i of every buffer  ==>  B at q and at slot i of every buffer after the swap
    """
    m = Map(D)
    q, i = D.int32("q"), D.int32("i")
    s = Buffers(D)
    after = swapped(D, m, s)
    pre = all_of(D, m.well_formed(), D.eq(after.fill["nxt"], 0), invariant(D, m, s, [q], [i], True))
    return pre, invariant(D, m, after, [q], [i], False)


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


@obligation(ReachedAndBufferedInductive, **STATED,
            scope="setupNavFn and initCost at any goal of a map of any size (the domain's int cell numbers)")
def setup_reaches_the_goal_alone_and_buffers_its_neighbours(D):
    """After setupNavFn and initCost (every potential POT_HIGH but the goal's 0, the goal's four
    neighbours pushed), R1 and R2 hold at every cell.

    ==>  R1 and R2 at any cell q
    """
    m = Map(D)
    q = D.int32("q")
    s, zeros = after_init_cost(D, m)
    pot = z3.Store(z3.K(cell_sort(D), D.f32const(POT_HIGH)), m.g, D.f32const(0.0))
    pre = all_of(D, m.well_formed(), *zeros)
    return pre, reach(D, m, s, pot, q)


@obligation(ReachedAndBufferedInductive, **STATED,
            scope="updateCell's write at any cell of the current buffer, on a map of any size")
def update_reaches_only_cells_of_the_component(D):
    """updateCell at a cell n of the current buffer (a cell of the component, by the buffer
    invariant) keeps R1 and R2: it writes only pot[n], never higher; and when it changes n,
    n is reached after (the pushes that follow are of a reached cell's neighbours).

    P at n and at its slot k of cur, R1 and R2 at q, valid potentials at n
    ==>  after pot[n] := updateCell(n): R1 and R2 at q, and n reached if changed
    """
    m = Map(D)
    q, k = D.int32("q"), D.int32("k")
    s = Buffers(D)
    pot = potentials(D)
    n = s.slots["cur"][k]
    new, changed = K.cell_update(D, pot[n], *(pot[j] for j in m.updated(n)), m.cost_int(n),
                                 D.cost_as_f32(m.cost[n]))
    after = z3.Store(pot, n, new)
    pre = all_of(D, m.well_formed(), D.ge(k, 0), D.lt(k, s.fill["cur"]), at_slot(D, s, "cur", k),
                 at_cell(D, m, s, n, True), ValidPotential(D, pot[n]), reach(D, m, s, pot, q))
    return pre, z3.And(reach(D, m, s, after, q), z3.Implies(changed, Reached(D, after[n])))


@obligation(ReachedAndBufferedInductive, **STATED,
            scope="one push of updateCell or updateCellAstar from a reached cell, into the buffer to_low_buffer "
                  "picks, on a map of any size")
def push_buffers_only_a_neighbour_of_a_reached_cell(D):
    """A push of a 4-neighbour of the updated cell n, reached (the update changed it), keeps R1
    and R2: the pushed cell is beside n.

    R1 and R2 at q, pot[n] < POT_HIGH, the pushed cell a 4-neighbour of n, any wanted, key, curT
    ==>  R1 and R2 at q after the push
    """
    m = Map(D)
    q, n, d = D.int32("q"), D.int32("n"), D.int32("direction")
    s = Buffers(D)
    pot = potentials(D)
    pushed = m.neighbour(n, d)
    low = K.to_low_buffer(D, D.f32("key"), D.f32("curT"))
    after, _ = push(D, m, s, (low, "nxt", "over"), pushed, z3.Bool("wanted"))
    pre = all_of(D, m.well_formed(), Reached(D, pot[n]), reach(D, m, s, pot, q))
    return pre, reach(D, m, after, pot, q)


@obligation(ReachedAndBufferedInductive, **STATED,
            scope="the end of any cycle (kernels.end_of_cycle), on a map of any size")
def swap_keeps_every_buffered_cell_beside_a_reached_one(D):
    """The swap moves cells between the buffers' roles and empties one: R1 and R2 stay.

    R1 and R2 at q  ==>  R1 and R2 at q after the swap
    """
    m = Map(D)
    q = D.int32("q")
    s = Buffers(D)
    pot = potentials(D)
    after = swapped(D, m, s)
    pre = all_of(D, m.well_formed(), D.eq(after.fill["nxt"], 0), reach(D, m, s, pot, q))
    return pre, reach(D, m, after, pot, q)
