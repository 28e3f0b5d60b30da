"""NoPathWithoutFinitePotential: extraction from an unreached start returns no path.

An unreached start cell triggers the grid-following fallback (one of the nine cells is
unreached).  The fallback compares the neighbours with ``int minp = potarr[stc]``; on
x86-64 the conversion of POT_HIGH = 1e10 (beyond INT_MAX) yields INT_MIN, so no neighbour
compares lower, the cell stays put, and calcPath returns 0 at once ("high potential").
Over the reals, where the conversion has no range, the fallback would move to any
reached neighbour instead: the paper's abstraction does not capture this behaviour.  Nor
does arm64: its ``fcvtzs`` saturates 1e10 to INT_MAX, every reached neighbour compares lower,
and the fallback walks from the unreached start (``fp32@aarch64`` refuted; the committed
``path-without-potential-*-aarch64`` counterexamples are such walks on the C++).
"""

from navfn_smt.proofs import NoPathWithoutFinitePotential
from navfn_smt.smt.obligation import obligation
from navfn_smt.smt.predicates import Unreached, ValidPotential, all_of
from navfn_smt.spec import kernels as K


@obligation(NoPathWithoutFinitePotential, expect={"real": "refuted", "fp32": "proved", "fp32@aarch64": "refuted",
                                                  "fp32@x86-64-v3": "proved"},
            scope="the fallback step at any cell with any eight neighbours: every map size")
def unreached_cell_stays_put(D):
    """From an unreached cell the fallback keeps the cell (so calcPath fails at once).

    pot(stc) >= POT_HIGH, neighbours valid  ==>  lowest_of_eight(stc) = -1 (stay)
    """
    centre = D.f32("centre")
    ring = [D.f32(f"n{k}") for k in range(8)]
    best = K.lowest_of_eight(D, centre, ring)
    pre = all_of(D, ValidPotential(D, centre), Unreached(D, centre), *(ValidPotential(D, p) for p in ring))
    return pre, D.eq(best, -1)
