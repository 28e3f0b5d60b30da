"""The spec's propagation run on SMT arrays: the conditions of its loop invariants, from its own code.

:mod:`navfn_smt.spec.propagation` states setupNavFn, initCost and propNavFn* once, as steps over
a state with a few operations of its own (arrays filled with one value, a buffer's conditional
append, a choice between two buffers, the loops).  :class:`Program` gives it a state of SMT arrays
(cells and slots the domain's int, the map's size and the buffers' capacity symbolic: every map
at once) and runs the
spec's :func:`~navfn_smt.spec.propagation.init_cost` and
:func:`~navfn_smt.spec.propagation.propagate` on it, unchanged: an array write becomes a store,
a conditional append a guarded store, a choice between buffers an ite.

The run cannot unroll a loop; Hoare's rule cuts it instead.  At a loop's entry the run records a
segment, the state since the last cut; then it replaces the state by a fresh one (the loop's
invariant will be assumed of it) and gives the body an arbitrary iteration ``k`` below the bound;
after the body it records the iteration's segment and starts afresh at the exit (the invariant
assumed at ``k`` = the bound).  The propagation's cycle loop is cut the same way, its test
ignored (the invariants hold whatever it decides).  So a run of ``propagate`` yields six segments,
one per edge of its control graph between cut points::

    setup -> cycle,  cycle -> clear,  clear -> clear,  clear exit -> update,
    update -> update,  update exit -> cycle

An obligation states an invariant per cut point and asks, for one segment, that the invariant at
its source (assumed at the cells and slots the segment read or wrote, instances of "at every
cell") gives the invariant at its target.  The segments are what the spec's code does; a
predicate whose obligations cover all six (``tests/test_program.py`` checks it) has its loops
machine-checked, with nothing read off the code.

Ghost state rides along: each buffer keeps ``inside`` (the cells it holds) and ``slot_of`` (at
which slot), written by its append and carried by the choice between buffers; the state keeps
``dropped`` (a push was refused for want of room).  A*'s heuristic is a fresh float at each use
(any value; the frontier's condition assumes it is not negative, which an obligation proves of
kernels.astar_heuristic).
"""

from __future__ import annotations

import itertools
from dataclasses import dataclass

import z3

from navfn_smt.spec import kernels as K
from navfn_smt.spec import propagation as P

# (source, target) of the segments a run of propagate yields
SEGMENTS = (("setup", "cycle"), ("cycle", "clear"), ("clear", "clear"), ("clear exit", "update"),
            ("update", "update"), ("update exit", "cycle"))
BUFFERS = ("cur", "nxt", "over")


def cell_sort(D):
    """The sort of a cell or slot number: the domain's int (32-bit bit-vector, or integer)."""
    return D.int32("i_sort_probe").sort()


def int_const(D, v: int):
    s = cell_sort(D)
    return z3.IntVal(v) if s == z3.IntSort() else z3.BitVecVal(v, s.size())


class Cells:
    """An SMT array written in place by the spec's steps (each write a store); every index it is
    read or written at is noted in ``seen``; ``view`` turns a read value into the step's type."""

    def __init__(self, array, seen: list, view=None):
        self.array, self.seen, self.view = array, seen, view

    def __getitem__(self, i):
        self.seen.append(i)
        return self.array[i] if self.view is None else self.view(self.array[i])

    def __setitem__(self, i, v):
        self.seen.append(i)
        self.array = z3.Store(self.array, i, v)


class Slots:
    """A priority buffer over arrays: its slots and fill, and the ghosts ``inside`` and ``slot_of``."""

    def __init__(self, run: "Program", slots, fill, inside, slot_of):
        self.run, self.slots, self.fill, self.inside, self.slot_of = run, slots, fill, inside, slot_of

    def cell(self, k):
        self.run.slot_seen.append((self, k))
        return self.slots[k]

    def append_if(self, admitted, n):
        D, f = self.run.D, self.fill
        self.run.slot_seen.append((self, f))
        self.run.cell_seen.append(n)
        self.slots = z3.If(admitted, z3.Store(self.slots, f, n), self.slots)
        self.inside = z3.If(admitted, z3.Store(self.inside, n, True), self.inside)
        self.slot_of = z3.If(admitted, z3.Store(self.slot_of, n, f), self.slot_of)
        self.fill = D.ite(admitted, D.add_int(f, 1), f)

    def with_fill(self, fill) -> "Slots":
        return Slots(self.run, self.slots, fill, self.inside, self.slot_of)

    def emptied(self) -> "Slots":
        """No cell held (the ghost says so too); the slots stay as they were."""
        D = self.run.D
        return Slots(self.run, self.slots, int_const(D, 0), z3.K(cell_sort(D), False), self.slot_of)


_OVER = object()  # the end of a loop's rule


class ArrayState:
    """The spec's propagation state over SMT arrays: the array model :class:`Program` runs the
    spec's steps on (the methods are :class:`~navfn_smt.spec.propagation.PropagationState`'s)."""

    def __init__(self, run: "Program"):
        D, m = run.D, run.m
        self.run, self.D, self.domain = run, D, D
        self.nx, self.ns, self.capacity = m.nx, m.ns, m.capacity
        self.costs = Cells(m.cost, run.cell_seen, D.cost_int)
        self.cycles = self.updates = 0
        self.dropped = z3.BoolVal(False)
        self.cur = self.nxt = self.over = None
        self.potential = self.pending = None
        self.cur_t = None
        self._cycle = None  # the cycle loop's rule while it runs (next_cycle)

    def filled(self, array, value) -> Cells:
        return Cells(z3.K(cell_sort(self.D), value), self.run.cell_seen)

    @staticmethod
    def index(n):
        return n

    def cost_f32(self, n):
        self.run.cell_seen.append(n)
        return self.D.cost_as_f32(self.run.m.cost[n])

    def edge(self, n):
        return K.edge_weight(self.D, self.cost_f32(n))

    def heuristic_between(self, goal, start):
        return self.heuristic(None, start)

    def heuristic(self, n, start):
        h = self.D.f32(f"heuristic~{next(self.run._heuristics)}")  # its own count: A*'s run names the rest as Dijkstra's
        self.run.heuristics_seen.append(h)
        return h

    def pick(self, cond, a: Slots, b: Slots) -> Slots:
        D = self.D
        return Slots(self.run, z3.If(cond, a.slots, b.slots), D.ite(cond, a.fill, b.fill),
                     z3.If(cond, a.inside, b.inside), z3.If(cond, a.slot_of, b.slot_of))

    @staticmethod
    def may(cond) -> bool:
        return True  # every step runs, guarded by its own condition

    def note_drop(self, dropped) -> None:
        self.dropped = z3.Or(self.dropped, dropped)

    def loop(self, name: str, bound):
        return self.run.loop(name, bound)

    def next_cycle(self, runs) -> bool:
        """Hoare's rule at the cycle loop: true once (the body runs on the invariant's state), then
        false (the state after the loop); ``runs`` is what the invariant's conditions say."""
        if self._cycle is None:
            self._cycle = self.run.loop("cycle", None)
        if next(self._cycle, _OVER) is _OVER:
            self._cycle = None
            return False
        return True

    def record_cycle(self, cycle, cycles, trace_hook, record_trace) -> None:
        pass


@dataclass
class Snapshot:
    """The state at a cut point, as the invariants read it (arrays and fills by buffer name)."""

    pending: object
    potential: object
    slots: dict
    fill: dict
    inside: dict
    slot_of: dict
    dropped: object


@dataclass
class Segment:
    """The state from one cut point to the next: where it starts (``source``, the loop's ``k`` and
    bound there, what holds of ``k``), its state there and at its end, and the cells and slots
    it read or wrote."""

    source: str
    target: str
    k: object
    bound: object
    given: list
    before: Snapshot
    k_after: object
    bound_after: object
    after: Snapshot
    cells: list
    slots: list  # (the buffer's role at the segment's end, the slot)
    heuristics: list  # A*'s heuristic at each use (fresh floats)


class Program:
    """One run of the spec's initCost and propNavFn* over SMT arrays, on the map ``m`` (the
    proofs' :class:`~navfn_smt.proofs.buffers.Map`): :attr:`segments` by (source, target)."""

    def __init__(self, D, m, astar: bool):
        self.D, self.m = D, m
        self._names, self._heuristics = itertools.count(), itertools.count()
        self.cell_seen, self.slot_seen, self.heuristics_seen = [], [], []
        self.segments: dict = {}
        st = self.state = ArrayState(self)
        empty = Slots(self, z3.Array(self.fresh("slots"), cell_sort(D), cell_sort(D)), int_const(D, 0),
                      z3.K(cell_sort(D), False), z3.Array(self.fresh("slot_of"), cell_sort(D), cell_sort(D)))
        st.cur = st.nxt = st.over = empty
        self._origin = ("setup", None, None, [], None)
        P.init_cost(st, m.g)
        start, goal = (D.int32("start_x"), D.int32("start_y")), (D.int32("goal_x"), D.int32("goal_y"))
        P.propagate(st, start, goal, astar, D.int32("cycles"), record_trace=False)

    def fresh(self, stem: str) -> str:
        return f"{stem}~{next(self._names)}"

    def snapshot(self) -> Snapshot:
        st = self.state
        bufs = {b: getattr(st, b) for b in BUFFERS}
        return Snapshot(st.pending.array, st.potential.array, {b: s.slots for b, s in bufs.items()},
                        {b: s.fill for b, s in bufs.items()}, {b: s.inside for b, s in bufs.items()},
                        {b: s.slot_of for b, s in bufs.items()}, st.dropped)

    def havoc(self) -> None:
        """A fresh state: what the loop's invariant will be assumed of."""
        D, st, cell = self.D, self.state, cell_sort(self.D)
        st.pending = Cells(z3.Array(self.fresh("pending"), cell, z3.BoolSort()), self.cell_seen)
        st.potential = Cells(z3.Array(self.fresh("pot"), cell, D.f32const(0.0).sort()), self.cell_seen)
        for b in BUFFERS:
            setattr(st, b, Slots(self, z3.Array(self.fresh(f"slots_{b}"), cell, cell), D.int32(self.fresh(f"fill_{b}")),
                                 z3.Array(self.fresh(f"inside_{b}"), cell, z3.BoolSort()),
                                 z3.Array(self.fresh(f"slot_of_{b}"), cell, cell)))
        st.cur_t, st.dropped = D.f32(self.fresh("curT")), z3.Bool(self.fresh("dropped"))

    def cut(self, target: str, k, bound) -> None:
        source, k0, bound0, given, before = self._origin
        roles = {id(getattr(self.state, b)): b for b in BUFFERS}
        slots = [(roles.get(id(buf)), k) for buf, k in self.slot_seen]  # a buffer's role, None if it has none now
        self.segments[(source, target)] = Segment(source, target, k0, bound0, given, before, k, bound,
                                                  self.snapshot(), self.cell_seen[:], slots, self.heuristics_seen[:])
        for seen in (self.cell_seen, self.slot_seen, self.heuristics_seen):
            seen.clear()

    def restart(self, source: str, k, bound, given: list) -> None:
        self.havoc()
        self._origin = (source, k, bound, given, self.snapshot())

    def loop(self, name: str, bound):
        """Hoare's rule at the loop ``name`` (``bound`` None: the cycle loop, no counter)."""
        D = self.D
        self.cut(name, int_const(D, 0) if bound is not None else None, bound)
        k = D.int32(self.fresh(f"k_{name}")) if bound is not None else None
        self.restart(name, k, bound, [] if bound is None else [D.ge(k, 0), D.lt(k, bound)])
        yield k
        self.cut(name, None if bound is None else D.add_int(k, 1), bound)
        self.restart(f"{name} exit", bound, bound, [])


class FreeFloats:
    """The domain ``D`` with every float operation's result left free: a fresh float (or, for a
    comparison of floats, a fresh truth value) at each use; ints, truth values and constants as
    in ``D``.  A run in it has every behaviour a run in ``D`` has (each float outcome is one
    choice of the fresh values), so a condition that reads no float and holds here holds in every
    arithmetic; it spares the solver the float circuits of updateCell."""

    def __init__(self, D, comparisons: bool = False):
        """``comparisons``: compare floats as ``D`` does (their operands free where computed)."""
        self._D, self._float, self._compare = D, D.f32const(0.0).sort(), comparisons
        self._names = itertools.count()

    def _is_float(self, v) -> bool:
        return isinstance(v, z3.ExprRef) and v.sort() == self._float

    def __getattr__(self, name):
        op = getattr(self._D, name)
        if not callable(op) or name in ("f32const", "f32", "f64", "int32", "cost", "ite", "and_", "or_", "not_"):
            return op

        def free(*args):
            if not any(self._is_float(a) for a in args):
                return op(*args)
            out = op(*args)
            if not isinstance(out, z3.ExprRef) or (self._compare and z3.is_bool(out)):
                return out
            return z3.Const(f"free_{name}~{next(self._names)}", out.sort())
        return free


def segments(D, m, astar: bool, free_floats=False) -> dict:
    """The segments of a run of initCost and propNavFn* (A* or Dijkstra) on the map ``m``
    (``free_floats``: in :class:`FreeFloats` of ``D``; "arithmetic": its comparisons kept)."""
    if free_floats:
        D = FreeFloats(D, comparisons=free_floats == "arithmetic")
    return Program(D, m, astar).segments


def _unique(terms) -> list:
    out = []
    for t in terms:
        if not any(t.eq(u) for u in out):
            out.append(t)
    return out


def loop_of(point: str) -> str:
    """The loop whose invariant holds at a cut point (its exit included)."""
    return point.removesuffix(" exit")


def condition(D, m, seg: Segment, invariant, q, i, given=(), assumed=(), near=()):
    """The condition of ``seg`` for ``invariant(loop, snapshot, k, bound) -> (whole, at_cell,
    at_slot)``: (pre, claim).  The source's invariant (none at setup), and the invariants
    ``assumed`` (proved elsewhere), are assumed at ``q``, ``i`` and at the cells and slots the
    segment touched and at the cells ``near``, the component's closure at the touched cells; the
    claim is the target's invariant at ``q`` and ``i``."""
    touched = _unique([q, *near, *seg.cells])
    slots = [(b, i) for b in BUFFERS]  # the claim's slot in every buffer, and each slot touched in its buffer
    for b, j in seg.slots:
        for role in ([b] if b else BUFFERS):
            if not any(r == role and j.eq(x) for r, x in slots):
                slots.append((role, j))
    pre = [m.well_formed(), m.on_map(m.g), *(m.closed_at(c) for c in seg.cells), *seg.given, *given]
    held = [*assumed, invariant] if seg.source != "setup" else []
    for inv in held:
        whole, at_cell, at_slot = inv(loop_of(seg.source), seg.before, seg.k, seg.bound)
        pre += [whole, *(at_cell(c) for c in touched), *(at_slot(b, j) for b, j in slots)]
    whole, at_cell, at_slot = invariant(seg.target, seg.after, seg.k_after, seg.bound_after)
    return z3.And(pre), z3.And(whole, at_cell(q), *(at_slot(b, i) for b in BUFFERS))


def as_one(parts):
    """Conditions ``(pre, claim)`` as one: (True, each pre implying its claim)."""
    return z3.BoolVal(True), z3.And([z3.Implies(pre, claim) for pre, claim in parts])


def both_modes(D, m, build, free_floats: bool = False, modes=(False, True)):
    """``build(segments)`` for Dijkstra's run and A*'s (their keys differ; ``modes``: which), as
    one condition (:func:`as_one`)."""
    return as_one(build(segments(D, m, astar, free_floats)) for astar in modes)
