"""PositionSafe and Progress as one invariant of the whole potential array, proved inductive on a
map of any width: the first of the loop inductions of issue #39, stated over arrays.

The state is the potential array ``pot`` and the cost array ``cost`` of an unbounded map: SMT
arrays indexed by 32-bit cell numbers, the width ``W`` symbolic (so every map size at once), the
goal ``g`` any cell.  The invariant holds at a cell ``n`` when

- ``pot[n]`` is a valid potential and ``cost[n]`` a cost setCostmap makes (50..253 passable,
  254 and up lethal);
- PositionSafe: a reached cell (``pot[n] < POT_HIGH``) other than the goal is passable;
- Progress: a reached cell other than the goal has a 4-neighbour (``n-1, n+1, n-W, n+W``) with a
  strictly lower potential;
- in float32, a reached cell's potential is below 2**30 (Progress's float32 bound, a run-time
  condition of every float32 claim here: the value each update writes is assumed below it);

and the goal keeps potential 0.  ``setup_and_init_cost_establish_the_invariant`` is the base
case: every cell POT_HIGH but the goal, 0 (what setupNavFn and initCost write).
The step is one ``updateCell`` (the project's ``cell_update`` kernel, as the spec and the C++
compute it) at any cell ``c``: it keeps the invariant at ``c``
(``update_keeps_the_invariant_at_the_updated_cell``) and at every other cell
(``update_keeps_the_invariant_at_every_other_cell``).  Both are quantifier-free: the claim is asked at an arbitrary cell ``n``, and the
invariant before the step is assumed at the cells the step reads (``n``, ``c``, their
neighbours and the goal), instances of "at every cell".

A real map embeds in this one: its cells outside the grid and its border are lethal and
unreached, where the invariant holds, and updateCell runs on interior cells only.  What stays
argued is that updateCell is the only write to the potential array after initCost.
"""

import z3

from navfn_smt.proofs import PositionSafeAndProgressInductive
from navfn_smt.smt.obligation import obligation
from navfn_smt.smt.predicates import Lethal, Reached, TranslatedCost, ValidPotential, all_of
from navfn_smt.spec import kernels as K
from navfn_smt.spec.constants import POT_HIGH

FP32_POTENTIAL_BOUND = 2.0 ** 30  # Progress's float32 bound (proofs/progress.py), a run-time condition
CELL = z3.BitVecSort(32)  # a cell number: int in the C++


class UnboundedMap:
    """The potential and cost arrays of a map of width ``W``, in the domain ``D``."""

    def __init__(self, D, cell=CELL):
        """``cell``: the sort of a cell number (32-bit by default; path extraction's proofs take the
        domain's int, as the spec's extraction functions compute with it)."""
        self.D = D
        self.pot = z3.Array("pot", cell, D.f32const(0.0).sort())
        self.cost = z3.Array("cost", cell, D.cost("cost_sort").sort())  # the domain's cost sort
        self.W, self.g = z3.Const("W", cell), z3.Const("g", cell)

    def neighbours(self, i):
        """``n-1, n+1, n-nx, n+nx``: the l, r, u, d of updateCell."""
        return i - 1, i + 1, i - self.W, i + self.W

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


@obligation(PositionSafeAndProgressInductive, expect={"real": "proved", "fp32": "proved",
                                                      "fp32@x86-64-v3": "proved", "fp32@aarch64": "proved"},
            scope="a map of any width (32-bit cell numbers), any goal", arrays=True)
def setup_and_init_cost_establish_the_invariant(D):
    """After setupNavFn and initCost (every potential POT_HIGH, the goal's 0) the invariant holds
    at every cell.

    costs as setCostmap makes them, the goal's passable or not
    ==>  pot = POT_HIGH everywhere but pot[g] = 0  satisfies the invariant at any cell n
    """
    return invariant_base(D)


def invariant_base(D, kind=UnboundedMap):
    """setupNavFn and initCost's potentials, the invariant of a map of class ``kind`` asked at a
    cell n: (pre, claim)."""
    m = kind(D)
    n = z3.BitVec("n", 32)
    pot = z3.Store(z3.K(CELL, D.f32const(POT_HIGH)), m.g, D.f32const(0.0))
    costs = [m.set_costmap_cost(i) for i in (n, *m.neighbours(n))]
    return all_of(D, m.W != 0, *costs), z3.And(m.invariant(pot, n), m.goal_zero(pot))


def invariant_step(D, where, kind=UnboundedMap):
    """One updateCell at cell c, the claim asked at cell n (``where``: "updated", n = c; "other",
    n != c), on a map of class ``kind`` (its invariant): (pre, claim)."""
    m = kind(D)
    n, c = z3.BitVec("n", 32), z3.BitVec("c", 32)
    new, changed = K.cell_update(D, m.pot[c], *(m.pot[j] for j in m.neighbours(c)), m.cost_int(c),
                                 D.cost_as_f32(m.cost[c]))
    after = z3.Store(m.pot, c, new)
    assumed = [m.invariant(m.pot, i) for i in (n, c, *m.neighbours(c), *m.neighbours(n), m.g)]
    pre = all_of(D, m.W != 0, m.goal_zero(m.pot), n == c if where == "updated" else n != c, *assumed)
    if D.name != "real":
        pre = D.and_(pre, z3.Implies(changed, D.lt(new, D.f32const(FP32_POTENTIAL_BOUND))))
    return pre, z3.And(m.invariant(after, n), m.goal_zero(after))


STEP = dict(expect={"real": "proved", "fp32": "proved", "fp32@x86-64-v3": "proved", "fp32@aarch64": "proved"},
            slow=("fp32", "fp32@x86-64-v3", "fp32@aarch64"), arrays=True)  # float32: about 25 s each, in `prove --all`


@obligation(PositionSafeAndProgressInductive, scope="one updateCell at any cell of a map of any width "
            "(32-bit cell numbers), any goal: the updated cell", **STEP)
def update_keeps_the_invariant_at_the_updated_cell(D):
    """One updateCell at any cell c keeps the invariant at c, and the goal's 0.

    the invariant at c, its neighbours and the goal; W != 0; in float32 the potential the update
    writes below 2**30
    ==>  after pot[c] := updateCell(c), the invariant at c and pot[g] = 0
    """
    return invariant_step(D, "updated")


@obligation(PositionSafeAndProgressInductive, scope="one updateCell at any cell of a map of any width "
            "(32-bit cell numbers), any goal: every other cell", **STEP)
def update_keeps_the_invariant_at_every_other_cell(D):
    """One updateCell at any cell c keeps the invariant at every other cell n (a neighbour of c
    included: its lower neighbour may be c, which only went down), and the goal's 0.

    the invariant at n, c, their neighbours and the goal; n != c; W != 0; in float32 the
    potential the update writes below 2**30
    ==>  after pot[c] := updateCell(c), the invariant at n and pot[g] = 0
    """
    return invariant_step(D, "other")
