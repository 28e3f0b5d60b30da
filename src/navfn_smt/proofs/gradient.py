"""Gradient: gradCell stores a unit vector or the zero vector.

Over the reals the normalised vector has length exactly 1.  In float32 its squared
length is within a few units of rounding of 1; the claim is stated with that tolerance
(2**-20).  Both rely on the model of ``hypotf``.

For arbitrary float potentials the float32 claim fails: when the neighbours differ by a
subnormal amount, ``1.0 / norm`` overflows when narrowed to float and the stored vector
is infinite or NaN.  Potentials that NavFn produces are 0 (the goal) or at least the
smallest candidate ``0 + 1 * 0.704`` above it, so their differences are never subnormal;
under that precondition the claim is proved.
"""

from navfn_smt.proofs import Gradient
from navfn_smt.smt.obligation import obligation
from navfn_smt.smt.predicates import GradDifference, TranslatedCost, ValidPotential, all_of
from navfn_smt.smt.split import f32_interval, product, split
from navfn_smt.spec import kernels as K


def _navfn_potential(D, p):
    """0, or at least 1/2: what propagation produces (the goal, or a cost times >= 0.704)."""
    return D.or_(D.eq(p, D.f32const(0.0)), D.ge(p, D.f32const(0.5)))


def _unit_or_zero_of(D, gx, gy):
    zero = D.f32const(0.0)
    wx, wy = D.widen(gx), D.widen(gy)
    err = D.sub64(D.add64(D.mul64(wx, wx), D.mul64(wy, wy)), D.f64const(1.0))
    tol = D.f64const(2.0**-20)
    unit = D.and_(D.le(err, tol), D.ge(err, D.sub64(D.f64const(0.0), tol)))
    return D.or_(D.and_(D.eq(gx, zero), D.eq(gy, zero)), unit)


@obligation(Gradient, expect={"real": "proved", "fp32": "proved",
                              "fp32@x86-64-v3": "proved", "fp32@aarch64": "proved"},
            scope="one update of any cell with any neighbours and a cost setCostmap makes: every map size")
def update_keeps_potentials_zero_or_at_least_half(D):
    """An update keeps every potential 0 or at least 1/2: the precondition of
    grad_differences_are_not_tiny, by induction over the run (setup writes the goal's 0 and
    POT_HIGH elsewhere; every later write to the potentials is an update, as for Monotone).

    cost in [50, 253], valid potentials each 0 or >= 1/2  ==>  updateCell(n) is 0 or >= 1/2
    """
    old, l, r, u, d = (D.f32(v) for v in ("old", "l", "r", "u", "d"))
    c = D.cost("cost")
    new, _ = K.cell_update(D, old, l, r, u, d, D.cost_int(c), D.cost_as_f32(c))
    pre = all_of(D, TranslatedCost(D, D.cost_int(c)),
                 *(D.and_(ValidPotential(D, p), _navfn_potential(D, p)) for p in (old, l, r, u, d)))
    return pre, _navfn_potential(D, new)


@obligation(Gradient, expect={"real": "refuted", "fp32": "proved",
                              "fp32@x86-64-v3": "proved", "fp32@aarch64": "proved"},
            scope="gradCell's difference step at any interior cell whose potentials NavFn can produce")
def grad_differences_are_not_tiny(D):
    """On the potentials NavFn produces, gradCell's unnormalised components are 0 or at least 2**-25.

    A float32 fact (differences of floats >= 1/2 are multiples of 2**-25); over the reals
    the differences can be arbitrarily small, so the real verdict is refuted.

    potentials valid and each 0 or >= 1/2  ==>  dx, dy each 0 or |.| >= 2**-25, and |.| <= 2**35
    """
    cv, pl, pr, pu, pd = (D.f32(v) for v in ("cv", "l", "r", "u", "d"))
    dx, dy = K.grad_vector(D, cv, pl, pr, pu, pd)
    pre = all_of(D, *(D.and_(ValidPotential(D, p), _navfn_potential(D, p)) for p in (cv, pl, pr, pu, pd)))
    return pre, D.and_(GradDifference(D, dx), GradDifference(D, dy))


# Known in fp32 from its split below (nine sign cases, the cover proved).  Whole, no solver of the
# portfolio decided it within 300 s on this machine (two binary64 squares, a square root and a
# division under the claim's binary64 squares), so `prove --all` gives the whole query only a
# short limit: undecided is the usual answer, and never a failure; a solver that refuted it
# would contradict the split and fail the run.
@obligation(Gradient, expect={"real": "proved", "fp32": "proved"},
            scope="gradCell's normalisation of any vector whose components are 0 or in [2**-25, 2**35]",
            timeout=10, slow=("fp32",))
def grad_is_unit_or_zero(D):
    """gradCell's normalisation returns a unit or zero vector; with the lemma above, gradCell
    stores a unit or zero vector on every potential NavFn produces.

    dx, dy each 0 or 2**-25 <= |.| <= 2**35  ==>  (gx, gy) = (0, 0)  or  |gx*gx + gy*gy - 1| <= 2**-20
    """
    dx, dy = D.f32("dx"), D.f32("dy")
    gx, gy = K.normalise(D, dx, dy)
    return D.and_(GradDifference(D, dx), GradDifference(D, dy)), _unit_or_zero_of(D, gx, gy)


# the counterexample only needs hypotf's documented accuracy (the exact glibc definition
# makes the query much harder for the solvers); it is replayed with the real libm
@obligation(Gradient, expect={"real": "proved", "fp32": "refuted",
                              "fp32@x86-64-v3": "refuted", "fp32@aarch64": "refuted"},
            scope="gradCell's normalisation of any finite vector: every map size", hypotf_model="ulp")
def grad_is_unit_or_zero_any_float(D):
    """gradCell's normalisation returns a unit or zero vector for any finite vector along an axis
    (fails in float32: a subnormal vector has a norm whose inverse overflows float).

    dx finite, |dx| <= 2**35, dy = 0  ==>  (gx, gy) = (0, 0)  or  |gx*gx + gy*gy - 1| <= 2**-20
    """
    dx, dy = D.f32("dx"), D.f32("dy")
    big = D.f32const(2.0**35)
    pre = all_of(D, D.le(dx, big), D.ge(dx, D.neg(big)), D.eq(dy, D.f32const(0.0)))
    return pre, _unit_or_zero_of(D, *K.normalise(D, dx, dy))


def _pieces(v):
    """A gradCell difference (GradDifference): negative, zero or positive, magnitudes 2**-25 to 2**35."""
    return (f32_interval(v, -(2.0**35), -(2.0**-25)), f32_interval(v, 0.0, 0.0), f32_interval(v, 2.0**-25, 2.0**35))


# Decided by splitting: the sign cases of the two differences (nine parts, the cover proved by a
# solver).  Both zero is decided bit-precisely; every other part in the error model, where each
# rounding is a relative error of at most half an ulp (sound because every intermediate of the
# part is zero or normal, which the same query proves).
grad_is_unit_or_zero_split = split(
    grad_is_unit_or_zero, product(_pieces("dx"), _pieces("dy")), bisect_along=("dx", "dy"),
    methods=("errmodel", "smt"), timeouts={"smt": 20.0}, part_timeout=240.0, max_depth=4,
    note="sign cases of the two differences; every part but (0, 0) in the error model")
