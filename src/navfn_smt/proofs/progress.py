"""Progress: a reached cell (other than the goal) has a strictly lower 4-neighbour.

After an update that changes a cell, its new potential exceeds the lowest of its four
neighbours, which is what lets path extraction always descend.  Over the reals this holds
for every cost ``setCostmap`` produces (50..253: the candidate is at least the lowest
neighbour plus 0.704 times the cost).  In float32 the addition ``ta + hf`` is absorbed by
rounding once the neighbour's potential is large enough; the toolkit reports the
counterexample and the largest bound below which the property still holds.
"""

from navfn_smt.proofs import Progress
from navfn_smt.smt.obligation import Bound, obligation
from navfn_smt.smt.predicates import Reached, TranslatedCost, ValidPotential, all_of, any_of, minimum
from navfn_smt.spec import kernels as K
from navfn_smt.spec.constants import POT_HIGH


@obligation(Progress, expect={"real": "proved", "fp32": "refuted",
                              "fp32@x86-64-v3": "refuted", "fp32@aarch64": "refuted"},
            scope="one update with any neighbours: every map size",
            bound=Bound(var="l", lo=1.0, hi=POT_HIGH))
def update_keeps_a_lower_neighbour(D):
    """A changed cell ends strictly above its lowest neighbour.

    cost in [50, 253], valid potentials, some neighbour reached, l the lowest neighbour
    ==>  updateCell(n) changes pot(n)  implies  pot'(n) > l
    """
    old, l, r, u, d = (D.f32(v) for v in ("old", "l", "r", "u", "d"))
    c = D.cost("cost")
    new, changed = K.cell_update(D, old, l, r, u, d, D.cost_int(c), D.cost_as_f32(c))
    low = minimum(D, l, r, u, d)
    pre = all_of(D, TranslatedCost(D, D.cost_int(c)), *(ValidPotential(D, p) for p in (old, l, r, u, d)),
                 Reached(D, l), D.eq(low, l))
    return pre, any_of(D, D.not_(changed), D.gt(new, l))
