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

from ..spec.numeric import c_hypot, c_hypotf
from .codec import f32_from_bits, f64_from_bits, f64_to_bits, fp32_val, fp64_val
from .domains import F32, F64, FPDomain, RealDomain


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


class RealEvalDomain(RealDomain):
    """The real domain on constants."""


def f32_input(D, x: float):
    return fp32_val(x) if isinstance(D, FPDomain) else D.f32const(x)


def cost_input(D, c: int):
    return z3.BitVecVal(c, 8) if isinstance(D, FPDomain) else z3.IntVal(c)


# ------------------------------------------------------------- equality with the spec
import numpy as np  # noqa: E402

from ..spec import kernels as K  # noqa: E402
from ..spec.numeric import CONCRETE as C  # noqa: E402

EDGE = [float(np.float32(v)) for v in (
    0.0, -0.0, 1.0, -1.0, 0.5, -0.5, 1.5, 49.999996, 50.0, 100.0, 253.0, 254.0, 1e10, 9999999488.0,
    2.0**24, 2.0**24 + 2, 2.0**30, 3.4028235e38, 1.4e-45, 1.1754942e-38, -1.4e-45, math.inf, -math.inf,
    math.nan, 0.70710677, 0.99999994, 1.0000001, -0.99999994)]


def same(a, b) -> bool:
    if isinstance(a, float) and isinstance(b, float):
        if math.isnan(a) and math.isnan(b):
            return True  # NaN payloads are not observable in NavFn
        return f64_to_bits(a) == f64_to_bits(b)
    return a == b


def f32s(rng, n, potentials=False):
    out = []
    for _ in range(n):
        k = rng.integers(10)
        if k < 3:
            out.append(float(EDGE[rng.integers(len(EDGE))]))
        elif k < 6 and potentials:
            out.append(float(np.float32(rng.uniform(0, 20000))))
        elif k < 8:
            out.append(float(np.float32(rng.uniform(-2, 2))))
        else:
            b = int(rng.integers(0, 2**32))
            out.append(f32_from_bits(b))
    return out


def compare_kernel(kernel: str, seed: int, n: int) -> list:
    """Evaluate ``kernel`` on n inputs in both domains; return the mismatches."""
    rng = np.random.default_rng(seed)
    bad = []
    for _ in range(n):
        try:
            D = FPEvalDomain()
            if kernel == "cell_update":
                old, l, r, u, d = f32s(rng, 5, True)
                c = int(rng.integers(0, 256))
                conc = K.cell_update(C, old, l, r, u, d, c, float(c))
                sym = K.cell_update(D, *(f32_input(D, v) for v in (old, l, r, u, d)), D.cost_int(cost_input(D, c)),
                                    D.cost_as_f32(cost_input(D, c)))
                got = (value(sym[0]), value(sym[1]))
                args = (old, l, r, u, d, c)
            elif kernel == "edge_weight":
                c = int(rng.integers(0, 256))
                conc = (K.edge_weight(C, float(c)),)
                got = (value(K.edge_weight(D, D.cost_as_f32(cost_input(D, c)))),)
                args = (c,)
            elif kernel == "push":
                p, key, w, t = f32s(rng, 4, True)
                conc = (K.push_wanted(C, p, key, w), K.to_low_buffer(C, key, t))
                fp = [f32_input(D, v) for v in (p, key, w, t)]
                got = (value(K.push_wanted(D, fp[0], fp[1], fp[2])), value(K.to_low_buffer(D, fp[1], fp[3])))
                args = (p, key, w, t)
            elif kernel == "push_admitted":
                ns = int(rng.integers(1, 40000))
                n, fill, cap = int(rng.integers(-3, ns + 3)), int(rng.integers(0, 12)), int(rng.integers(0, 12))
                pend, c = bool(rng.integers(2)), int(rng.integers(0, 256))
                conc = (K.push_admitted(C, n, ns, pend, c, fill, cap),)
                got = (value(K.push_admitted(D, n, ns, pend, D.cost_int(cost_input(D, c)), fill, cap)),)
                args = (n, ns, pend, c, fill, cap)
            elif kernel == "heuristic":
                ddx, ddy = (int(v) for v in rng.integers(-3000, 3000, size=2))
                conc = (K.astar_heuristic(C, ddx, ddy),)
                got = (value(K.astar_heuristic(D, ddx, ddy)),)
                args = (ddx, ddy)
            elif kernel == "grad_cell":
                vals = f32s(rng, 5, True)
                conc = K.grad_cell(C, *vals)
                got = tuple(value(v) for v in K.grad_cell(D, *(f32_input(D, v) for v in vals)))
                args = tuple(vals)
            elif kernel == "interpolate":
                vals = f32s(rng, 6)
                conc = (K.interpolate_gradient(C, *vals),)
                got = (value(K.interpolate_gradient(D, *(f32_input(D, v) for v in vals))),)
                args = tuple(vals)
            elif kernel == "step":
                vals = f32s(rng, 4)
                conc = K.step_offsets(C, *vals, 0.5)
                sym = K.step_offsets(D, *(f32_input(D, v) for v in vals), D.f32const(0.5))
                got = tuple(value(v) for v in sym)
                args = tuple(vals)
            elif kernel == "nearest":
                dx, dy = f32s(rng, 2)
                nx = int(rng.integers(3, 5000))
                ns = nx * int(rng.integers(3, 5000))
                stc = int(rng.integers(0, ns))
                conc = (K.nearest_cell(C, stc, dx, dy, nx, ns),)
                got = (value(K.nearest_cell(D, stc, f32_input(D, dx), f32_input(D, dy), nx, ns)),)
                args = (stc, dx, dy, nx, ns)
            elif kernel == "lowest":
                vals = f32s(rng, 9, True)
                conc = (K.lowest_of_eight(C, vals[0], vals[1:]),)
                got = (value(K.lowest_of_eight(D, f32_input(D, vals[0]), [f32_input(D, v) for v in vals[1:]])),)
                args = tuple(vals)
            else:
                raise ValueError(kernel)
            if not all(same(a, b) for a, b in zip(conc, got)) or not D.model_admits_libm():
                bad.append((kernel, args, conc, got, D.model_admits_libm()))
        except NotConstant as e:  # the inputs do not determine the symbolic result
            bad.append((kernel, "not determined", str(e)[:200]))
    return bad


# evaluations per kernel in the equality test (about 100,000 in all)
KERNELS = {"cell_update": 16000, "edge_weight": 3000, "push": 12000, "push_admitted": 3000, "heuristic": 8000, "grad_cell": 12000,
           "interpolate": 14000, "step": 12000, "nearest": 12000, "lowest": 12000}


