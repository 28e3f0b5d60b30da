"""PositionSafe: a cell with a finite potential is never an obstacle.

Propagation starts with every potential at POT_HIGH and changes potentials only through
``updateCell``; so it suffices that an update never gives an obstacle a finite potential
(the inductive step, for any map size).  The goal itself is the one exception NavFn
makes: ``initCost`` sets its potential to 0 whatever its cost.
"""

from navfn_smt.proofs import PositionSafe
from navfn_smt.smt.obligation import obligation
from navfn_smt.smt.predicates import Lethal, Unreached, ValidPotential, all_of
from navfn_smt.spec import kernels as K


@obligation(PositionSafe, expect={"real": "proved", "fp32": "proved",
                                  "fp32@x86-64-v3": "proved", "fp32@aarch64": "proved"},
            scope="one update of any cell with any neighbours: inductive, every map size")
def update_keeps_obstacles_unreached(D):
    """An update never gives an obstacle a finite potential.

    cost(n) >= COST_OBS and pot(n) >= POT_HIGH  ==>  updateCell(n) leaves pot(n) >= POT_HIGH
    """
    old, l, r, u, d = (D.f32(v) for v in ("old", "l", "r", "u", "d"))
    c = D.cost("cost")
    new, _ = K.cell_update(D, old, l, r, u, d, D.cost_int(c), D.cost_as_f32(c))
    pre = all_of(D, Lethal(D, D.cost_int(c)), Unreached(D, old),
                 *(ValidPotential(D, p) for p in (old, l, r, u, d)))
    return pre, Unreached(D, new)
