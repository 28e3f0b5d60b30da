"""The standard model of floating-point rounding: a sound over-approximation of float32.

Where no bit-precise solver decides a part of a split (:mod:`navfn_smt.smt.split`), its
claim can still be proved in the *error model*: every rounded operation of the kernels
becomes its exact real result times ``(1 + delta)`` with a fresh ``|delta| <= u``
(``u = 2**-24`` for a float result, ``2**-53`` for a double one).  The IEEE-754 standard
guarantees exactly this for every result in the normal range (Higham, *Accuracy and
Stability of Numerical Algorithms*, Theorem 2.2), so the true computation is one choice of
the deltas as long as every product, quotient, root and narrowing is zero or normal, and
every result finite (a sum below the normal range is exact).  That condition is
not assumed: each rounded operation adds a *side claim* (its exact result is 0, or between
the smallest normal and the largest finite value), proved together with the claim.

So a part proved here holds for every input of the part, in IEEE float32/float64 with
round-to-nearest, on the kernels the planner runs.  A model of the negated claim is not a
counterexample (the deltas need not be real rounding errors): it leaves the part
``unknown``.  The library functions follow the obligation's ``hypotf_model``: glibc's
definition (a double square root of a double sum, narrowed), the one-ulp bound, or only
the ordering facts.  Preconditions must be comparisons of the variables (no rounding), so
that they mean the same in every choice of the deltas.
"""

from __future__ import annotations

from fractions import Fraction

import z3

from ..spec.numeric import f32
from .codec import free_constants
from .domains import RealDomain

U32, U64 = Fraction(1, 2**24), Fraction(1, 2**53)  # half an ulp, relative: float and double
NORMAL32, MAX32 = Fraction(2) ** -126, Fraction((2**24 - 1) * 2**104)
NORMAL64, MAX64 = Fraction(2) ** -1022, Fraction((2**53 - 1) * 2**971)


class ErrorModelDomain(RealDomain):
    """Reals with a relative rounding error per operation (``errmodel``); see the module docstring."""

    name = "errmodel"

    def __init__(self, hypotf_model: str = "glibc", arithmetic=None):
        super().__init__()
        self.hypotf_model = hypotf_model
        self.arith = arithmetic  # the build's (spec.arithmetic.Arithmetic; None: x86-64's, nothing fused)
        self.side: list = []  # the side claims: every rounded result zero or normal and finite
        self.rounded = 0

    def fuses(self, site: str) -> bool:
        """Whether the build fuses the multiply-add ``site`` (then rounded once, :meth:`fma`)."""
        return self.arith is not None and self.arith.fuses(site)

    def fma(self, a, b, c):
        """``a * b + c`` in float, rounded once (a fused multiply-add): one relative error, with the
        side claim of a product (zero or normal: unlike a sum of two floats, a fused result below
        the normal range may be inexact)."""
        return self._round(a * b + c, False)

    def fma64(self, a, b, c):
        return self._round(a * b + c, True)

    # --------------------------------------------------------------------------- rounding
    def _round(self, z, double: bool, sum_: bool = False):
        """``z * (1 + delta)``, ``|delta| <= u``, with the side claim that ``z`` is zero or normal
        and finite; for a sum (``sum_``) only finite: a sum that falls below the normal range is
        exact in IEEE arithmetic (no relative error at all)."""
        if z3.is_rational_value(z) and _representable(Fraction(z.as_fraction()), double):
            return z  # an exact constant needs no rounding
        d = self._delta(U64 if double else U32)
        lo, hi = (z3.RealVal(v) for v in ((NORMAL64, MAX64) if double else (NORMAL32, MAX32)))
        if sum_:
            self.side.append(z3.And(z <= hi, z >= -hi))
        else:
            self.side.append(z3.Or(z == 0, z3.And(z >= lo, z <= hi), z3.And(z <= -lo, z >= -hi)))
        return z * (1 + d)

    def _delta(self, u: Fraction):
        """A fresh relative error ``delta`` with ``|delta| <= u``."""
        self.rounded += 1
        d = z3.Real(f"delta!{self.rounded}")
        self.assumptions.append(z3.And(d >= -z3.RealVal(u), d <= z3.RealVal(u)))
        return d

    def _quotient(self, a, b):
        """``a / b`` as a fresh ``q`` with ``q * b == a``, and the side claim ``b != 0``."""
        self.rounded += 1
        q = z3.Real(f"quotient!{self.rounded}")
        self.assumptions.append(z3.Implies(b != 0, q * b == a))
        self.side.append(b != 0)
        return q

    def add(self, a, b):
        return self._round(a + b, False, sum_=True)

    def sub(self, a, b):
        return self._round(a - b, False, sum_=True)

    def mul(self, a, b):
        return self._round(a * b, False)

    def div(self, a, b):
        return self._round(self._quotient(a, b), False)

    def add64(self, a, b):
        return self._round(a + b, True, sum_=True)

    def sub64(self, a, b):
        return self._round(a - b, True, sum_=True)

    def mul64(self, a, b):
        return self._round(a * b, True)

    def div64(self, a, b):
        return self._round(self._quotient(a, b), True)

    def narrow(self, a):
        return self._round(a, False)

    def int_to_f32(self, n):
        """``(float)n``: exact below 2**24 in magnitude (a side claim)."""
        r = super().int_to_f32(n)
        self.side.append(z3.And(r <= 2**24, r >= -(2**24)))
        return r

    # ------------------------------------------------------------------ library functions
    def _sqrt(self, s):
        self.rounded += 1
        h = z3.Real(f"sqrt!{self.rounded}")
        self.assumptions.append(z3.And(h >= 0, h * h == s))
        return h

    def hypotf(self, a, b):
        if self.hypotf_model == "glibc":  # (float) sqrt((double) a * a + (double) b * b)
            s = self.add64(self.mul64(a, a), self.mul64(b, b))
            return self.narrow(self._round(self._sqrt(s), True))
        exact = self._sqrt(a * a + b * b)
        if self.hypotf_model == "ulp":  # within one ulp: a relative error of at most 2 * U32
            return exact * (1 + self._delta(2 * U32))
        # ordering facts only: between the larger magnitude and the sum of magnitudes
        self.rounded += 1
        h = z3.Real(f"hypotf!{self.rounded}")
        aa, ab = z3.If(a >= 0, a, -a), z3.If(b >= 0, b, -b)
        self.assumptions.append(z3.And(h >= aa, h >= ab, h <= aa + ab))
        return h

    def hypot64(self, a, b):
        raise NotImplementedError("the error model has no hypot (double)")

    def roundf(self, a):
        raise NotImplementedError("the error model has no roundf")

    def to_int32(self, a):
        raise NotImplementedError("the error model has no float to int conversion")


def _representable(x: Fraction, double: bool) -> bool:
    """Whether ``x`` is zero or a normal value of the format, exactly (rounding it changes nothing)."""
    lo, hi = (NORMAL64, MAX64) if double else (NORMAL32, MAX32)
    if x != 0 and not lo <= abs(x) <= hi:
        return False
    rounded = float(x) if double else f32(float(x))  # double rounding is innocuous for a float32 value
    return Fraction(rounded) == x


def query(ob, extra=None, arithmetic=None):
    """The error-model query of ``ob`` (``extra(D)`` added to the precondition) in the build's
    ``arithmetic`` (None: x86-64's): unsatisfiable when the claim and every side claim hold in
    every choice of the deltas."""
    D = ErrorModelDomain(ob.hypotf_model, arithmetic)
    pre, claim = ob.build(D)
    if extra is not None:
        pre = z3.And(pre, extra(D))
    rounding = set(free_constants([pre])) - set(D.variables)
    if rounding:
        raise NotImplementedError(f"{ob.name}: its precondition rounds ({', '.join(sorted(rounding))}); the error "
                                  f"model needs a precondition of plain comparisons")
    return D, [*D.assumptions, pre, z3.Not(z3.And(claim, *D.side))]
