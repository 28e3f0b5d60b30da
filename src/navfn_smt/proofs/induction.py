"""PositionSafe and Progress as one invariant of the whole potential array, proved inductive on a
map of any size: the first of the loop inductions of issue #39, stated over arrays.

The state is the potential array ``pot`` and the cost array ``cost`` of an unbounded map: SMT
arrays indexed by the domain's int, the width symbolic, the goal ``g`` any cell on the map.  The
invariant holds at a cell ``n`` when

- ``pot[n]`` is a valid potential and ``cost[n]`` a cost setCostmap makes (50..253 passable,
  254 and up lethal);
- PositionSafe: a reached cell (``pot[n] < POT_HIGH``) other than the goal is passable;
- Progress: a reached cell other than the goal has a 4-neighbour (``n-1, n+1, n-W, n+W``) with a
  strictly lower potential;
- in float32, a reached cell's potential is below 2**30 (Progress's float32 bound, a run-time
  condition of every float32 claim here: the value each update writes is assumed below it);

and the goal keeps potential 0.  The run is the spec's: :mod:`navfn_smt.smt.program` runs
setupNavFn, initCost and propNavFn* over these arrays (the map's size symbolic, every map at once),
their loops cut at the invariant.  ``setup_and_init_cost_establish_the_invariant`` is the segment
from the start to the cycle loop; the updates keep it at the updated cell
(``update_keeps_the_invariant_at_the_updated_cell``) and at every other cell
(``update_keeps_the_invariant_at_every_other_cell``); the other segments write no potential
(``the_steps_around_the_updates_keep_the_invariant``).  The conditions are quantifier-free: the
claim is asked at an arbitrary cell ``q``, and the invariant before a segment is assumed at the
cells it reads, their neighbours and the goal, instances of "at every cell".

A real map embeds in this one: its cells outside the grid and its border are lethal and
unreached, where the invariant holds, and the goal is on the map.
"""

import z3

from navfn_smt.proofs import PositionSafeAndProgressInductive
from navfn_smt.smt.obligation import obligation
from navfn_smt.smt.predicates import Lethal, Reached, TranslatedCost, ValidPotential
from navfn_smt.proofs.buffers import Map
from navfn_smt.smt.program import SEGMENTS, as_one, cell_sort, condition, segments
from navfn_smt.spec.propagation import update_neighbours

FP32_POTENTIAL_BOUND = 2.0 ** 30  # Progress's float32 bound (proofs/progress.py), a run-time condition
CELL = z3.BitVecSort(32)  # a cell number: int in the C++


class UnboundedMap:
    """The potential and cost arrays of a map of width ``W``, in the domain ``D``."""

    def __init__(self, D, cell=CELL, on=None):
        """``cell``: the sort of a cell number (32-bit by default; path extraction's proofs take the
        domain's int, as the spec's extraction functions compute with it); ``on``: the width, goal
        and costs of the map the spec's run is over (a :class:`~navfn_smt.proofs.buffers.Map`)."""
        self.D = D
        self.pot = z3.Array("pot", cell, D.f32const(0.0).sort())
        if on is None:
            self.cost = z3.Array("cost", cell, D.cost("cost_sort").sort())  # the domain's cost sort
            self.W, self.g = z3.Const("W", cell), z3.Const("g", cell)
        else:
            self.cost, self.W, self.g = on.cost, on.nx, on.g

    def neighbours(self, i):
        """``n-1, n+1, n-nx, n+nx``: the l, r, u, d of updateCell (the spec's order)."""
        return update_neighbours(i, self.W)

    def cost_int(self, i):
        return self.D.cost_int(self.cost[i])

    def set_costmap_cost(self, i):
        """The cost at ``i`` is one setCostmap makes: 50..253 passable, 254 and up lethal."""
        return z3.Or(TranslatedCost(self.D, self.cost_int(i)), Lethal(self.D, self.cost_int(i)))

    def below(self, p):
        """What Progress asks of a lower neighbour of a cell of potential ``p``: the potential it
        must be strictly below (``p`` itself; FallbackPath's stronger invariant takes its truncation)."""
        return p

    def invariant(self, pot, i):
        """The invariant at cell ``i`` of the potential array ``pot``."""
        D = self.D
        p = pot[i]
        lower = z3.Or([D.lt(pot[j], self.below(p)) for j in self.neighbours(i)])
        parts = [ValidPotential(D, p), self.set_costmap_cost(i),
                 z3.Implies(z3.And(Reached(D, p), i != self.g), z3.And(z3.Not(Lethal(D, self.cost_int(i))), lower))]
        if D.name != "real":
            parts.append(z3.Implies(Reached(D, p), D.lt(p, D.f32const(FP32_POTENTIAL_BOUND))))
        return z3.And(parts)

    def goal_zero(self, pot):
        return pot[self.g] == self.D.f32const(0.0)


def invariant_condition(D, source: str, target: str, kind=UnboundedMap, where=None):
    """The condition of the spec's segment from ``source`` to ``target`` for the invariant of a
    map of class ``kind``, asked at any cell q (``where``, for an update: "updated", q is the
    updated cell; "other", it is not): (pre, claim).  The invariant is assumed at the cells the
    segment touches, at q's neighbours and at the goal; in float32 the potential an update writes,
    when reached, below 2**30 (the run-time condition).  Dijkstra's and A*'s runs write the same
    potentials (the key only picks the pushes' buffer): one run, Dijkstra's."""
    m = Map(D)
    u = kind(D, cell_sort(D), on=m)
    q = D.int32("q")

    def at(loop, s, k, bound):
        return u.goal_zero(s.potential), (lambda c: u.invariant(s.potential, c)), (lambda b, i: z3.BoolVal(True))

    seg = segments(D, m, astar=False)[(source, target)]
    given = [u.set_costmap_cost(c) for c in (q, *u.neighbours(q))] if source == "setup" else []
    if where is not None:
        c = seg.before.slots["cur"][seg.k]  # the updated cell
        new = seg.after.potential[c]
        given.append(q == c if where == "updated" else q != c)
        if D.name != "real":
            given.append(z3.Implies(Reached(D, new), D.lt(new, D.f32const(FP32_POTENTIAL_BOUND))))
    return condition(D, m, seg, at, q, D.int32("i"), near=(*u.neighbours(q), m.g), given=given)


def frame_condition(D, kind=UnboundedMap):
    """The segments of the spec's run that write no potential (a cycle's start, the clearing loop,
    its end, the swap): each keeps the invariant of a map of class ``kind``."""
    return as_one(invariant_condition(D, s, t, kind) for s, t in SEGMENTS if s not in ("setup", "update"))


STEP = dict(expect={"real": "proved", "fp32": "proved", "fp32@x86-64-v3": "proved", "fp32@aarch64": "proved"},
            slow=("fp32", "fp32@x86-64-v3", "fp32@aarch64"), arrays=True)  # float32: about 25 s each, in `prove --all`
EVERY = dict(expect=STEP["expect"], arrays=True)


@obligation(PositionSafeAndProgressInductive, scope="the spec's setupNavFn and initCost on a map of any size "
            "(the domain's int cell numbers), any goal on it", **EVERY)
def setup_and_init_cost_establish_the_invariant(D):
    """After the spec's setupNavFn and initCost (every potential POT_HIGH, the goal's 0) the
    invariant holds at every cell.

    costs as setCostmap makes them at the cells asked  ==>  the invariant at any cell q, pot[g] = 0
    """
    return invariant_condition(D, "setup", "cycle")


@obligation(PositionSafeAndProgressInductive, scope="the steps of the spec's propNavFn* that write no potential, on "
            "a map of any size, any goal", **EVERY)
def the_steps_around_the_updates_keep_the_invariant(D):
    """A cycle's start, the loop clearing the flags, its end and the swap write no potential: each
    keeps the invariant.

    the invariant at q  ==>  the invariant at q after the step
    """
    return frame_condition(D)


@obligation(PositionSafeAndProgressInductive, scope="one iteration of the spec's update loop (updateCell on the "
            "cell in slot k of the current buffer) on a map of any size, any goal: the updated cell", **STEP)
def update_keeps_the_invariant_at_the_updated_cell(D):
    """One updateCell at the cell c in slot k of the current buffer keeps the invariant at c, and
    the goal's 0.

    the invariant at c, its neighbours and the goal; in float32 the potential the update writes
    below 2**30
    ==>  after pot[c] := updateCell(c), the invariant at c and pot[g] = 0
    """
    return invariant_condition(D, "update", "update", where="updated")


@obligation(PositionSafeAndProgressInductive, scope="one iteration of the spec's update loop (updateCell on the "
            "cell in slot k of the current buffer) on a map of any size, any goal: every other cell", **STEP)
def update_keeps_the_invariant_at_every_other_cell(D):
    """One updateCell at the cell c in slot k of the current buffer keeps the invariant at every
    other cell n (a neighbour of c included: its lower neighbour may be c, which only went down),
    and the goal's 0.

    the invariant at n, c, their neighbours and the goal; n != c; in float32 the potential the
    update writes below 2**30
    ==>  after pot[c] := updateCell(c), the invariant at n and pot[g] = 0
    """
    return invariant_condition(D, "update", "update", where="other")
