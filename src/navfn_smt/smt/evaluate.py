"""Evaluating the symbolic domains on concrete inputs (for holding them equal to the spec).

:class:`FPEvalDomain` is the bit-precise domain fed with constants; its library calls take
the platform libm's value (so the rest of the term is checked bit for bit) while the
library-function model is still asserted on that value, so evaluating
:attr:`~navfn_smt.smt.domains.Domain.assumptions` checks that the model admits what the
real libm returns.  :func:`value` folds a term to a Python value.
"""

from __future__ import annotations

import math

import z3

from ..spec.arithmetic import X86_64
from ..spec.numeric import c_hypot, c_hypotf
from .codec import f32_from_bits, f64_from_bits, fp32_val, fp64_val
from .domains import F32, F64, FPDomain


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
            return f32_from_bits(b)
        if t.sort() == F64:
            return f64_from_bits(b)
    if z3.is_bv_value(t):
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
    raise NotConstant(f"not a constant: {t}")


class NotConstant(ValueError):
    """A symbolic result the inputs do not determine (an unspecified SMT-LIB operation)."""


class FPEvalDomain(FPDomain):
    """The fp32 domain on constants; library calls answer with the platform's libm."""

    def library_result(self, name, sort, a, b):
        av, bv = value(a), value(b)
        if sort == F32:
            return fp32_val(c_hypotf(av, bv))
        return fp64_val(c_hypot(av, bv))

    def model_admits_libm(self) -> bool:
        return all(z3.is_true(z3.simplify(a)) for a in self.assumptions)


def f32_input(D, x: float):
    return fp32_val(x) if isinstance(D, FPDomain) else D.f32const(x)


def cost_input(D, c: int):
    return z3.BitVecVal(c, 8) if isinstance(D, FPDomain) else z3.IntVal(c)


# ------------------------------------------------------------- equality with the spec
from ..spec import conformance as T  # noqa: E402
from ..spec.numeric import CONCRETE as C  # noqa: E402

same = T.same


def lift(D, kind: str, v):
    """A plain input of the conformance table as the fp32 or real domain takes it."""
    if kind == T.F32:
        return f32_input(D, v)
    if kind == T.COST:
        return D.cost_int(cost_input(D, v))
    if kind == T.COST_F32:
        return D.cost_as_f32(cost_input(D, int(v)))
    return v  # plain ints and bools stay plain, as the kernels take them


def _results(D, case: T.KernelCase, args: tuple):
    return tuple(value(v) for v in case.call(D, *(lift(D, k, v) for k, v in zip(case.kinds, args))))


def fp32_result(case: T.KernelCase, args: tuple, arithmetic=None):
    """``case``'s results on one input of the table in the bit-precise domain (in the build
    arithmetic ``arithmetic``; None: x86-64's), or a sentence saying why there are none (a result
    the inputs do not determine, the library model refusing what the platform's libm returns)."""
    D = FPEvalDomain(arithmetic=arithmetic or X86_64)
    try:
        got = _results(D, case, args)
    except NotConstant as e:  # the inputs do not determine the symbolic result
        return f"not determined: {str(e)[:200]}"
    return got if D.model_admits_libm() else f"the library model refuses libm's {got}"


def compare_kernel(kernel: str, seed: int, n: int, arithmetic=None, symbolic=None) -> list:
    """Evaluate ``kernel`` on ``n`` inputs of the conformance table in the bit-precise domain and
    concretely, both in the build arithmetic ``arithmetic`` (None: x86-64's; ``symbolic``: the
    bit-precise domain's, when it is to differ); return the mismatches (and the inputs where the
    library model refuses libm)."""
    case = T.CASE[kernel]
    conc = C.with_arithmetic(arithmetic)
    symbolic = arithmetic if symbolic is None else symbolic
    bad = []
    for args in T.inputs(case, seed, n):
        want, got = case.call(conc, *args), fp32_result(case, args, symbolic)
        if not T.agree(want, got):
            bad.append((kernel, args, want, got))
    return bad


# evaluations per kernel in the equality test (about 100,000 in all)
KERNELS = {c.name: c.count for c in T.CASES}
