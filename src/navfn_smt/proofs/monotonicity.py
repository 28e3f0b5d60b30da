"""Monotonicity: potentials only go down, and the goal keeps potential 0."""

from navfn_smt.proofs import Monotone
from navfn_smt.smt.obligation import obligation
from navfn_smt.smt.predicates import ValidPotential, all_of
from navfn_smt.spec import kernels as K


@obligation(Monotone, expect={"real": "proved", "fp32": "proved",
                              "fp32@x86-64-v3": "proved", "fp32@aarch64": "proved"},
            scope="one update of any cell with any neighbours: every map size")
def update_never_raises(D):
    """An update never raises a potential.

    valid potentials  ==>  updateCell(n) <= pot(n)
    """
    old, l, r, u, d = (D.f32(v) for v in ("old", "l", "r", "u", "d"))
    c = D.cost("cost")
    new, _ = K.cell_update(D, old, l, r, u, d, D.cost_int(c), D.cost_as_f32(c))
    return all_of(D, *(ValidPotential(D, p) for p in (old, l, r, u, d))), D.le(new, old)


@obligation(Monotone, expect={"real": "proved", "fp32": "proved",
                              "fp32@x86-64-v3": "proved", "fp32@aarch64": "proved"},
            scope="one update of the goal cell with any neighbours: every map size")
def goal_stays_zero(D):
    """The goal keeps potential 0: an update of a cell at 0 leaves it at 0.

    pot(n) = 0 and neighbours valid  ==>  updateCell(n) = 0
    """
    l, r, u, d = (D.f32(v) for v in ("l", "r", "u", "d"))
    c = D.cost("cost")
    zero = D.f32const(0.0)
    new, _ = K.cell_update(D, zero, l, r, u, d, D.cost_int(c), D.cost_as_f32(c))
    return all_of(D, *(ValidPotential(D, p) for p in (l, r, u, d))), D.eq(new, zero)
