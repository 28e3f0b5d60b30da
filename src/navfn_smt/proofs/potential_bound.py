"""The potential bound: how far above its lowest neighbour an update can put a cell.

``updateCell`` puts a changed cell at ``ta + hf`` or ``ta + hf * v`` above the lowest of its four
neighbours ``ta``, with ``v = -0.2301 d^2 + 0.5307 d + 0.7040`` for ``d = dc / hf`` in [0, 1),
so ``v < 1.0046``, and ``hf`` a passable cost of at most 253: at most 254.2 above it over the
reals, and at most 256 in float32 while the neighbour is below 2**30 (a float32 there has a
spacing of at most 64, and 256 is a multiple of it).  Each cell becomes reached in an update
beside a reached cell (the goal first, at 0) and only falls after, so the k-th cell to become
reached is at most 256 * (k - 1) while that is below 2**30; the cells reached are the passable
ones and the goal at most, so every potential stays below 2**30 on a map of fewer than
2**22 = 4,194,304 passable cells, which holds every Nav2 map of 2000 x 2000 cells (the planner
benchmark's, 1998 x 1998 inside its lethal border).  That count over the order in which cells
become reached is a trusted step of :data:`navfn_smt.proofs.FallbackPath`; this file checks the
step of one update.
"""

from navfn_smt.proofs import FallbackPath
from navfn_smt.proofs.fallback import one_update  # one update, its lowest neighbour reached
from navfn_smt.smt.obligation import obligation
from navfn_smt.smt.predicates import all_of, any_of
from navfn_smt.spec.fix import POT_BOUND

RISE = 256.0  # the most one update puts a changed cell above its lowest neighbour below POT_BOUND


@obligation(FallbackPath, expect={"real": "proved", "fp32": "proved",
                                  "fp32@x86-64-v3": "proved", "fp32@aarch64": "proved"},
            scope="one update with any neighbours, the lowest below 2**30: every map size",
            slow=("fp32", "fp32@x86-64-v3", "fp32@aarch64"))  # float32: 15-20 s with cvc5
def update_raises_at_most_256_above_its_lowest_neighbour(D):
    """A changed cell ends at most 256 above its lowest neighbour, when that one is below 2**30.

    cost in [50, 253], valid potentials, l the lowest neighbour, l < 2**30
    ==>  updateCell(n) changes pot(n)  implies  pot'(n) <= l + 256
    """
    pre, l, _, new, changed = one_update(D)
    pre = all_of(D, pre, D.lt(l, D.f32const(POT_BOUND)))
    return pre, any_of(D, D.not_(changed), D.le(new, D.add(l, D.f32const(RISE))))
