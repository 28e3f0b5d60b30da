"""Symbolic numeric domains: the kernels of :mod:`navfn_smt.spec.kernels` as Z3 terms.

Two interpretations of the operations the concrete domain
(:class:`navfn_smt.spec.numeric.ConcreteDomain`) provides, under the same method names:

* :class:`FPDomain` (``fp32``): bit-precise IEEE-754.  C++ ``float`` is ``Float32``,
  ``double`` is ``Float64``, every operation rounds to nearest-even exactly where the C++
  rounds; C++ ``int`` is a 32-bit bit-vector.  Where the build contracts a multiply-add and
  how ``static_cast<int>`` converts are its arithmetic's (:mod:`navfn_smt.spec.arithmetic`;
  x86-64's by default: nothing fused, ``cvttss2si``'s INT_MIN for NaN and out of range).
* :class:`RealDomain` (``real``): the paper's abstraction.  Both ``float`` and ``double``
  are mathematical reals, no operation rounds, ``int`` is a mathematical integer.

Library functions are not IEEE basic operations:

* ``roundf`` has an exact definition (nearest integer, halves away from zero): the
  FP domain uses IEEE ``roundToIntegral`` with mode RNA, which is exactly that; the real
  domain defines it with ``floor``.
* ``hypot`` / ``hypotf`` have no exact definition.  Each call yields a fresh result
  constrained by a *model* recorded in :attr:`Domain.assumptions` (to be asserted with the
  obligation and named in its report): the result is non-negative, zero exactly when
  both arguments are zero, at least the larger magnitude and at most their sum, and (FP)
  within one unit in the last place of the exact value, which glibc documents for these
  functions on x86-64 (its ``libm-test-ulps``: at most 1 ulp).  In the real domain the
  result is the exact square root.

A domain also mints variables (:meth:`Domain.f32`, :meth:`Domain.cost`, ...), so an
obligation written against the domain can be evaluated symbolically or, with a model's
values, concretely (see :mod:`navfn_smt.smt.obligation`).
"""

from __future__ import annotations

import functools
import itertools
import operator
from typing import Optional

import z3

from ..spec.arithmetic import KNOWN, X86_64, Arithmetic
from ..spec.constants import INT_MAX, INT_MIN
from .codec import fp32_val, fp64_val

F32 = z3.FPSort(8, 24)
F64 = z3.FPSort(11, 53)
BV32 = z3.BitVecSort(32)
RNE = z3.RNE()


def _max_value(sort) -> float:
    return 3.4028234663852886e38 if sort == F32 else 1.7976931348623157e308


class Domain:
    """Common parts: logic, variables, the assumption list."""

    name = "?"
    _fresh = itertools.count()

    def __init__(self):
        self.assumptions: list = []  # constraints of library-function models
        self.assumption_notes: set = set()
        self.variables: dict = {}

    # logic
    @staticmethod
    def and_(a, b):
        return z3.And(a, b)

    @staticmethod
    def or_(a, b):
        return z3.Or(a, b)

    @staticmethod
    def not_(a):
        return z3.Not(a)

    def _var(self, name, sort):
        v = z3.Const(name, sort)
        self.variables[name] = v
        return v

    def _fresh_name(self, stem: str) -> str:
        return f"{stem}!{next(self._fresh)}"

    @staticmethod
    def fuses(site: str) -> bool:
        """Nothing fused (x86-64's arithmetic; :class:`FPDomain` takes a build's; over the reals
        a fused multiply-add equals the product and the sum)."""
        return False


class FPDomain(Domain):
    """Bit-precise IEEE-754 semantics (``fp32``).

    ``hypotf_model``: ``"glibc"`` (default) defines ``hypotf`` as glibc computes it;
    ``"ulp"`` uses only the documented one-ulp accuracy; ``"bounds"`` only the ordering
    facts (between the larger magnitude and the sum of magnitudes), the weakest model: a
    proof under it holds for every hypotf that respects them.
    """

    name = "fp32"

    def __init__(self, hypotf_model: str = "glibc", arithmetic: Arithmetic = X86_64):
        super().__init__()
        self.hypotf_model = hypotf_model
        self.arith = arithmetic

    def fuses(self, site: str) -> bool:
        """Whether the build fuses the multiply-add ``site`` (its arithmetic's data: SMT-LIB's
        ``fp.fma`` where it does, a product and a sum rounded each where it does not)."""
        return self.arith.fuses(site)

    # ----------------------------------------------------------------- variables
    def f32(self, name: str):
        return self._var(name, F32)

    def f64(self, name: str):
        return self._var(name, F64)

    def int32(self, name: str):
        return self._var(name, BV32)

    def cost(self, name: str):
        """A cell cost (unsigned char) as the float ``static_cast<float>(costarr[n])``."""
        return self._var(name, z3.BitVecSort(8))

    def cost_as_f32(self, c):
        return z3.fpUnsignedToFP(RNE, c, F32) if z3.is_bv(c) else self.f32const(float(c))

    def cost_int(self, c):
        """The cost as a 32-bit int (for comparisons with COST_OBS)."""
        return z3.ZeroExt(24, c) if z3.is_bv(c) and c.size() == 8 else self._int(c)

    # ------------------------------------------------------- constants, conversions
    @staticmethod
    def f32const(x):
        from ..spec.numeric import f32

        return fp32_val(f32(float(x)))

    @staticmethod
    def f64const(x):
        return fp64_val(float(x))

    @staticmethod
    def widen(a):
        return z3.fpFPToFP(RNE, a, F64)

    @staticmethod
    def narrow(a):
        return z3.fpFPToFP(RNE, a, F32)

    def int_to_f32(self, n):
        if isinstance(n, int):
            return self.f32const(float(n))
        return z3.fpSignedToFP(RNE, n, F32)

    def int_to_f64(self, n):
        if isinstance(n, int):
            return self.f64const(float(n))
        return z3.fpSignedToFP(RNE, n, F64)

    def to_int32(self, a):
        """``(int)`` as the arithmetic converts: truncation toward zero; NaN or out of int32 range
        gives INT_MIN (x86-64's cvttss2si / cvttsd2si), or clamps with NaN giving 0 (arm64's fcvtzs)."""
        if a.sort() == F32:
            low, high = fp32_val(-2147483648.0), fp32_val(2147483648.0)
            in_range = z3.And(z3.fpGEQ(a, low), z3.fpLT(a, high))
        else:
            low, high = fp64_val(-2147483649.0), fp64_val(2147483648.0)
            in_range = z3.And(z3.fpGT(a, low), z3.fpLT(a, high))
        truncated = z3.fpToSBV(z3.RTZ(), a, BV32)
        if self.arith.conversion == "indefinite":
            return z3.If(in_range, truncated, z3.BitVecVal(INT_MIN, 32))
        return z3.If(z3.fpIsNaN(a), z3.BitVecVal(0, 32),
                     z3.If(z3.fpLT(a, low) if a.sort() == F32 else z3.fpLEQ(a, low), z3.BitVecVal(INT_MIN, 32),
                           z3.If(z3.fpGEQ(a, high), z3.BitVecVal(INT_MAX, 32), truncated)))

    # ------------------------------------------------------------- arithmetic
    def add_int(self, a, b):
        """32-bit int addition: bit-vector addition wraps like x86-64."""
        if isinstance(a, int) and isinstance(b, int):
            return a + b
        return self._int(a) + self._int(b)

    @staticmethod
    def add(a, b):
        return z3.fpAdd(RNE, a, b)

    @staticmethod
    def sub(a, b):
        return z3.fpSub(RNE, a, b)

    @staticmethod
    def mul(a, b):
        return z3.fpMul(RNE, a, b)

    @staticmethod
    def div(a, b):
        return z3.fpDiv(RNE, a, b)

    @staticmethod
    def neg(a):
        return z3.fpNeg(a)

    add64, sub64, mul64, div64 = add, sub, mul, div

    @staticmethod
    def fma(a, b, c):  # a * b + c, rounded once (SMT-LIB's fp.fma)
        return z3.fpFMA(RNE, a, b, c)

    fma64 = fma

    # ------------------------------------------------------- library functions
    def _hypot(self, a, b, sort, name, accurate=True):
        """A fresh result constrained by the documented accuracy (``accurate``), or only by the
        ordering facts every correct implementation satisfies (``accurate=False``: non-negative,
        zero iff both arguments are, between the larger magnitude and the sum of magnitudes)."""
        h = self.library_result(name, sort, a, b)
        aa, ab = z3.fpAbs(a), z3.fpAbs(b)
        zero = z3.FPVal(0.0, sort)
        big = z3.If(z3.fpGEQ(aa, ab), aa, ab)
        wide = F64 if sort == F32 else z3.FPSort(15, 113)
        W = lambda v: z3.fpFPToFP(RNE, v, wide)  # noqa: E731
        finite_args = z3.And(z3.Not(z3.fpIsInf(a)), z3.Not(z3.fpIsNaN(a)),
                             z3.Not(z3.fpIsInf(b)), z3.Not(z3.fpIsNaN(b)))
        top = W(z3.fpMaxValue(sort) if hasattr(z3, "fpMaxValue") else z3.FPVal(_max_value(sort), sort))
        sum_of_magnitudes = z3.fpAdd(RNE, W(aa), W(ab))
        facts = [z3.Not(z3.fpIsNaN(h)), z3.fpGEQ(h, zero),
                 z3.fpEQ(h, zero) == z3.And(z3.fpIsZero(a), z3.fpIsZero(b)),
                 z3.fpGEQ(h, big)]
        if not accurate:
            facts.append(z3.Implies(z3.fpLEQ(sum_of_magnitudes, top),
                                    z3.And(z3.Not(z3.fpIsInf(h)), z3.fpLEQ(W(h), sum_of_magnitudes))))
            note = (f"{name}: only non-negative, zero iff both arguments are, between the larger magnitude "
                    f"and the sum of magnitudes (no accuracy assumed)")
        else:
            # exact value bracketed in a wider format: (h - ulp)^2 <= a^2 + b^2 <= (h + ulp)^2,
            # with ulp = next(h) - h.  Squares of binary32 values (and of h +- ulp) are exact in
            # binary64, squares of binary64 values in binary128; only the sum of the two squares
            # rounds there (relative 2**-53, resp. 2**-113), far inside the one-ulp bracket.
            nxt = z3.fpBVToFP(z3.fpToIEEEBV(h) + 1, sort)
            ulp = z3.fpSub(RNE, W(nxt), W(h))
            s = z3.fpAdd(RNE, z3.fpMul(RNE, W(a), W(a)), z3.fpMul(RNE, W(b), W(b)))
            lo = z3.fpSub(RNE, W(h), ulp)
            hi = z3.fpAdd(RNE, W(h), ulp)
            lo0 = z3.If(z3.fpIsNegative(lo), z3.FPVal(0.0, wide), lo)
            # overflow: infinity only when the exact value is beyond the largest finite float
            facts.append(z3.If(z3.fpIsInf(h), z3.fpGT(s, z3.fpMul(RNE, top, top)), z3.And(
                z3.fpLEQ(W(h), sum_of_magnitudes),
                z3.Implies(z3.Not(z3.fpIsZero(h)), z3.And(
                    z3.fpLEQ(z3.fpMul(RNE, lo0, lo0), s),
                    z3.fpLEQ(s, z3.fpMul(RNE, hi, hi)))))))
            note = (f"{name}: non-negative, zero iff both arguments are, between the larger magnitude and "
                    f"the sum of magnitudes, infinite only beyond the largest float, and within 1 ulp of the "
                    f"exact sqrt(a*a + b*b) (glibc's documented accuracy on x86-64)")
        self.assumptions.append(z3.Implies(finite_args, z3.And(*facts)))
        self.assumption_notes.add(note)
        return h

    def library_result(self, name, sort, *args):
        """The result of a library call: a fresh constant (subclasses may supply a value)."""
        return z3.Const(self._fresh_name(name), sort)

    def hypot64(self, a, b):
        return self._hypot(a, b, F64, "hypot")

    def hypotf(self, a, b):
        """glibc's ``hypotf`` (2.35 and later, x86-64): ``(float) sqrt((double) a * a + (double) b * b)``.

        An exact definition of the implementation the original links against, rather than
        the one-ulp bound (:meth:`_hypot`) its documentation gives; the equality test holds it
        bit-equal to the platform's ``hypotf`` on every test input."""
        if self.hypotf_model in ("ulp", "bounds"):
            return self._hypot(a, b, F32, "hypotf", accurate=self.hypotf_model == "ulp")
        wa, wb = self.widen(a), self.widen(b)
        self.assumption_notes.add("hypotf: glibc's implementation, (float) sqrt((double) a * a + (double) b * b), "
                                  "held bit-equal to the platform libm by the equality test")
        core = self.narrow(z3.fpSqrt(RNE, z3.fpAdd(RNE, z3.fpMul(RNE, wa, wa), z3.fpMul(RNE, wb, wb))))
        # C99 Annex F (and glibc): an infinite argument gives +inf even when the other is NaN
        return z3.If(z3.Or(z3.fpIsInf(a), z3.fpIsInf(b)), z3.fpPlusInfinity(F32), core)

    @staticmethod
    def roundf(a):
        return z3.fpRoundToIntegral(z3.RNA(), a)

    # ------------------------------------------------------------ comparisons
    @staticmethod
    def _int(v):
        return z3.BitVecVal(v, 32) if isinstance(v, int) else v

    def _cmp(self, a, b, fp, bv):
        if isinstance(a, z3.FPRef) or isinstance(b, z3.FPRef):
            return fp(a, b)
        return bv(self._int(a), self._int(b))

    def lt(self, a, b):
        return self._cmp(a, b, z3.fpLT, lambda x, y: x < y)

    def le(self, a, b):
        return self._cmp(a, b, z3.fpLEQ, lambda x, y: x <= y)

    def gt(self, a, b):
        return self._cmp(a, b, z3.fpGT, lambda x, y: x > y)

    def ge(self, a, b):
        return self._cmp(a, b, z3.fpGEQ, lambda x, y: x >= y)

    def eq(self, a, b):
        return self._cmp(a, b, z3.fpEQ, lambda x, y: x == y)

    def ite(self, c, a, b):
        if isinstance(c, bool):
            return a if c else b
        if isinstance(a, int) and not isinstance(a, bool):
            a = self._int(a)
        if isinstance(b, int) and not isinstance(b, bool):
            b = self._int(b)
        return z3.If(c, a, b)


class ExactArithmetic:
    """Rounding-free arithmetic through Python's operators: on Z3 reals it builds terms, on
    fractions it computes exactly.  Floats, doubles and ints alike (no range, no rounding)."""

    add = add64 = add_int = staticmethod(operator.add)
    sub = sub64 = staticmethod(operator.sub)
    mul = mul64 = staticmethod(operator.mul)
    div = div64 = staticmethod(operator.truediv)
    neg = staticmethod(operator.neg)

    @staticmethod
    def fma(a, b, c):  # a * b + c, exact
        return a * b + c

    fma64 = fma


class RealDomain(ExactArithmetic, Domain):
    """The paper's abstraction: float and double are reals, int is an integer, no rounding."""

    name = "real"

    def f32(self, name: str):
        return self._var(name, z3.RealSort())

    f64 = f32

    def int32(self, name: str):
        return self._var(name, z3.IntSort())

    def cost(self, name: str):
        c = self._var(name, z3.IntSort())
        self.assumptions.append(z3.And(c >= 0, c <= 255))
        return c

    def cost_as_f32(self, c):
        return z3.ToReal(c) if z3.is_int(c) else z3.RealVal(c)

    def cost_int(self, c):
        return c

    @staticmethod
    def f32const(x):
        from fractions import Fraction

        from ..spec.numeric import f32

        return z3.RealVal(Fraction(f32(float(x))))

    @staticmethod
    def f64const(x):
        from fractions import Fraction

        return z3.RealVal(Fraction(float(x)))

    @staticmethod
    def widen(a):
        return a

    narrow = widen

    @staticmethod
    def int_to_f32(n):
        return z3.RealVal(n) if isinstance(n, int) else z3.ToReal(n)

    int_to_f64 = int_to_f32

    @staticmethod
    def to_int32(a):
        """Truncation toward zero (the reals never leave the int range in this abstraction)."""
        return z3.If(a >= 0, z3.ToInt(a), -z3.ToInt(-a))

    def _hypot(self, a, b, name):
        h = z3.Real(self._fresh_name(name))
        self.assumptions.append(z3.And(h >= 0, h * h == a * a + b * b))
        self.assumption_notes.add(f"{name}: the exact square root sqrt(a*a + b*b)")
        return h

    def hypot64(self, a, b):
        return self._hypot(a, b, "hypot")

    def hypotf(self, a, b):
        return self._hypot(a, b, "hypotf")

    @staticmethod
    def roundf(a):
        """Nearest integer, halves away from zero: floor(|a| + 1/2) with a's sign."""
        up = z3.ToReal(z3.ToInt(a + z3.RealVal("1/2")))
        down = -z3.ToReal(z3.ToInt(-a + z3.RealVal("1/2")))
        return z3.If(a >= 0, up, down)

    @staticmethod
    def lt(a, b):
        return a < b

    @staticmethod
    def le(a, b):
        return a <= b

    @staticmethod
    def gt(a, b):
        return a > b

    @staticmethod
    def ge(a, b):
        return a >= b

    @staticmethod
    def eq(a, b):
        return a == b

    @staticmethod
    def ite(c, a, b):
        if isinstance(c, bool):
            return a if c else b
        return z3.If(c, a, b)


# the float32 semantics of each known build arithmetic (spec.arithmetic.KNOWN): ``fp32`` is
# x86-64's, the golden files' build; ``fp32@NAME`` computes as the build NAME does
FP32_SEMANTICS = {"fp32": X86_64, **{f"fp32@{n}": a for n, a in KNOWN.items() if a != X86_64}}
DOMAINS = {"real": RealDomain, **{s: functools.partial(FPDomain, arithmetic=a) for s, a in FP32_SEMANTICS.items()}}


def is_fp32(semantics: str) -> bool:
    """Whether ``semantics`` is float32 in some build's arithmetic."""
    return semantics in FP32_SEMANTICS


def fp32_of(target: str) -> str:
    """The float32 semantics of the build arithmetic ``target`` (a name of spec.arithmetic.KNOWN)."""
    return "fp32" if KNOWN[target] == X86_64 else f"fp32@{target}"


def arithmetic_of(semantics: str) -> Optional[Arithmetic]:
    """The build arithmetic a float32 ``semantics`` computes in; None over the reals."""
    return FP32_SEMANTICS.get(semantics)
