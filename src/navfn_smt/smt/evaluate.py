"""Evaluating the symbolic domains on concrete inputs (for holding them equal to the spec).

:class:`FPEvalDomain` is the bit-precise domain fed with constants; its library calls take
the platform libm's value (so the rest of the term is checked bit for bit) while the
library-function model is still asserted on that value, so evaluating
:attr:`~navfn_smt.smt.domains.Domain.assumptions` checks that the model admits what the
real libm returns.  :func:`value` folds a term to a Python value.
"""

from __future__ import annotations

import math
import struct

import z3

from ..spec.numeric import c_hypot, c_hypotf
from .domains import F32, F64, FPDomain, RealDomain, fp32_val, fp64_val


def value(t):
    """A constant term's value: float (exact bits) for FP, int for bit-vectors (signed),
    Fraction for reals, bool for Booleans."""
    from fractions import Fraction

    if isinstance(t, (bool, int, float)):
        return t
    t = z3.simplify(t)
    if z3.is_fp(t):
        if z3.is_true(z3.simplify(z3.fpIsNaN(t))):
            return math.nan  # SMT-LIB has one NaN, without a bit pattern
        b = z3.simplify(z3.fpToIEEEBV(t)).as_long()
        if t.sort() == F32:
            return struct.unpack("<f", struct.pack("<I", b))[0]
        if t.sort() == F64:
            return struct.unpack("<d", struct.pack("<Q", b))[0]
    if z3.is_bv(t):
        return t.as_signed_long()
    if z3.is_true(t):
        return True
    if z3.is_false(t):
        return False
    if z3.is_int_value(t):
        return t.as_long()
    if z3.is_rational_value(t):
        return Fraction(t.numerator_as_long(), t.denominator_as_long())
    if z3.is_algebraic_value(t):
        return t  # irrational (a square root): compared by the caller
    raise ValueError(f"not a constant: {t}")


class FPEvalDomain(FPDomain):
    """The fp32 domain on constants; library calls answer with the platform's libm."""

    def library_result(self, name, sort, a, b):
        av, bv = value(a), value(b)
        if sort == F32:
            return fp32_val(c_hypotf(av, bv))
        return fp64_val(c_hypot(av, bv))

    def model_admits_libm(self) -> bool:
        return all(z3.is_true(z3.simplify(a)) for a in self.assumptions)


class RealEvalDomain(RealDomain):
    """The real domain on constants."""


def f32_input(D, x: float):
    return fp32_val(x) if isinstance(D, FPDomain) else D.f32const(x)


def cost_input(D, c: int):
    return z3.BitVecVal(c, 8) if isinstance(D, FPDomain) else z3.IntVal(c)
