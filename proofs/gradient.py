"""Gradient: gradCell stores a unit vector or the zero vector.

Over the reals the normalised vector has length exactly 1.  In float32 its squared
length is within a few units of rounding of 1; the claim is stated with that tolerance
(2**-20).  Both rely on the model of ``hypotf``.
"""

from navfn_smt.smt.obligation import obligation
from navfn_smt.smt.predicates import ValidPotential, all_of
from navfn_smt.spec import kernels as K


@obligation("Gradient", expect={"real": "proved", "fp32": "proved"},
            scope="gradCell at any interior cell with any four neighbours: every map size")
def grad_is_unit_or_zero(D):
    """gradCell returns a unit or zero vector.

    valid potentials  ==>  (gx, gy) = (0, 0)  or  |gx*gx + gy*gy - 1| <= 2**-20 (computed in double)
    """
    cv, pl, pr, pu, pd = (D.f32(v) for v in ("cv", "l", "r", "u", "d"))
    gx, gy = K.grad_cell(D, cv, pl, pr, pu, pd)
    zero = D.f32const(0.0)
    wx, wy = D.widen(gx), D.widen(gy)
    n2 = D.add64(D.mul64(wx, wx), D.mul64(wy, wy))
    tol = D.f64const(2.0**-20)
    unit = D.and_(D.le(D.sub64(n2, D.f64const(1.0)), tol), D.ge(D.sub64(n2, D.f64const(1.0)), D.sub64(D.f64const(0.0), tol)))
    is_zero = D.and_(D.eq(gx, zero), D.eq(gy, zero))
    pre = all_of(D, *(ValidPotential(D, p) for p in (cv, pl, pr, pu, pd)))
    return pre, D.or_(is_zero, unit)
