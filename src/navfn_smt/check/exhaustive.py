"""Decide a query over a small box of cost bytes by evaluating it at every point, with numpy.

The last resort of the bounded checks: a query no solver decides in time, whose box has few
enough points, is evaluated at all of them.  The evaluator interprets the query's Z3 terms
over numpy arrays, one element per point: float32 and float64 operations as numpy performs
them (IEEE-754, round to nearest even, like the C++ and the solvers), a fused multiply-add by
an exact vectorised ``fmaf`` and libm's correctly rounded ``fma`` point by point, so the answer is
exact.  An operator it does not know raises :class:`Unsupported`; the query then stays
unknown.  ``tests/test_check_bounded.py`` holds it equal to Z3's own evaluation.
"""

from __future__ import annotations

from typing import Optional

import numpy as np
import z3

from ..smt.codec import free_constants
from ..smt.evaluate import value
from ..smt.enumerate import fma_array, fmaf_array

CHUNK = 1 << 17
# the fused multiply-add of a build that contracts (spec.arithmetic), as the concrete spec computes it
_FMA = {np.float32: fmaf_array, np.float64: fma_array}


class Unsupported(Exception):
    pass


def _fp_dtype(sort):
    ebits, sbits = sort.ebits(), sort.sbits()
    if (ebits, sbits) == (8, 24):
        return np.float32
    if (ebits, sbits) == (11, 53):
        return np.float64
    raise Unsupported(f"floating-point sort {sort}")


def _rne(rm) -> None:
    if not z3.is_app_of(rm, z3.Z3_OP_FPA_RM_NEAREST_TIES_TO_EVEN):
        raise Unsupported(f"rounding mode {rm}")


def _signed(a, bits: int):
    a = a.astype(np.int64) & ((1 << bits) - 1)
    return np.where(a >= (1 << (bits - 1)), a - (1 << bits), a)


def evaluate(t, env: dict, n: int, memo: Optional[dict] = None):
    """The value of term ``t`` at ``n`` points; ``env`` maps constant names to int arrays."""
    memo = {} if memo is None else memo
    key = t.get_id()
    if key in memo:
        return memo[key]
    out = _eval(t, env, n, memo)
    memo[key] = out
    return out


def _eval(t, env, n, memo):  # noqa: C901 - one branch per operator
    ev = lambda c: evaluate(c, env, n, memo)  # noqa: E731
    k = t.decl().kind()
    if z3.is_const(t) and k == z3.Z3_OP_UNINTERPRETED:
        return env[t.decl().name()]
    if z3.is_true(t) or z3.is_false(t):
        return np.full(n, z3.is_true(t))
    if z3.is_fp_value(t):
        return np.full(n, value(t), dtype=_fp_dtype(t.sort()))
    if z3.is_bv_value(t):
        v = t.as_long()
        return np.full(n, v, dtype=np.uint64 if v >= 1 << 63 else np.int64)
    args = t.children()
    if k == z3.Z3_OP_AND:
        return np.logical_and.reduce([ev(a) for a in args])
    if k == z3.Z3_OP_OR:
        return np.logical_or.reduce([ev(a) for a in args])
    if k == z3.Z3_OP_NOT:
        return ~ev(args[0])
    if k == z3.Z3_OP_IMPLIES:
        return ~ev(args[0]) | ev(args[1])
    if k == z3.Z3_OP_ITE:
        return np.where(ev(args[0]), ev(args[1]), ev(args[2]))
    if k in (z3.Z3_OP_EQ, z3.Z3_OP_DISTINCT) and len(args) == 2:
        a, b = ev(args[0]), ev(args[1])
        if z3.is_bv(args[0]):
            mask = (1 << args[0].size()) - 1
            a, b = a & mask, b & mask
        return (a == b) if k == z3.Z3_OP_EQ else (a != b)
    # floating point
    fp_bin = {z3.Z3_OP_FPA_ADD: np.add, z3.Z3_OP_FPA_SUB: np.subtract, z3.Z3_OP_FPA_MUL: np.multiply,
              z3.Z3_OP_FPA_DIV: np.divide}
    if k in fp_bin:
        _rne(args[0])
        with np.errstate(all="ignore"):
            return fp_bin[k](ev(args[1]), ev(args[2])).astype(_fp_dtype(t.sort()))
    if k == z3.Z3_OP_FPA_FMA:  # a * b + c rounded once, exactly (the enumeration's fmaf and fma)
        _rne(args[0])
        dt = _fp_dtype(t.sort())
        a, b, c = (np.broadcast_to(ev(x), (n,)) for x in args[1:])
        return _FMA[dt](a, b, c).astype(dt)
    if k == z3.Z3_OP_FPA_SQRT:
        _rne(args[0])
        with np.errstate(all="ignore"):
            return np.sqrt(ev(args[1]))
    if k == z3.Z3_OP_FPA_NEG:
        return -ev(args[0])
    if k == z3.Z3_OP_FPA_ABS:
        return np.abs(ev(args[0]))
    fp_cmp = {z3.Z3_OP_FPA_LT: np.less, z3.Z3_OP_FPA_LE: np.less_equal, z3.Z3_OP_FPA_GT: np.greater,
              z3.Z3_OP_FPA_GE: np.greater_equal, z3.Z3_OP_FPA_EQ: np.equal}
    if k in fp_cmp:
        return fp_cmp[k](ev(args[0]), ev(args[1]))
    if k == z3.Z3_OP_FPA_IS_NAN:
        return np.isnan(ev(args[0]))
    if k == z3.Z3_OP_FPA_IS_INF:
        return np.isinf(ev(args[0]))
    if k == z3.Z3_OP_FPA_IS_ZERO:
        return ev(args[0]) == 0
    if k == z3.Z3_OP_FPA_IS_NEGATIVE:
        a = ev(args[0])
        return np.signbit(a) & ~np.isnan(a)
    if k == z3.Z3_OP_FPA_TO_FP_UNSIGNED:
        _rne(args[0])
        return ev(args[1]).astype(_fp_dtype(t.sort()))  # small unsigned ints convert exactly
    if k == z3.Z3_OP_FPA_TO_FP and len(args) == 1 and z3.is_bv(args[0]):  # reinterpret IEEE bits
        dt = _fp_dtype(t.sort())
        bits = ev(args[0]).astype(np.uint64)
        return (bits.astype(np.uint32).view(np.float32) if dt is np.float32 else bits.view(np.float64))
    if k == z3.Z3_OP_FPA_TO_FP and len(args) == 2 and z3.is_fp(args[1]):
        _rne(args[0])
        return ev(args[1]).astype(_fp_dtype(t.sort()))  # widening exact, narrowing rounds to nearest even
    if k == z3.Z3_OP_FPA_TO_FP and len(args) == 2 and z3.is_bv(args[1]):
        _rne(args[0])  # signed int to float
        return _signed(ev(args[1]), args[1].size()).astype(_fp_dtype(t.sort()))
    if k == z3.Z3_OP_FPA_ROUND_TO_INTEGRAL:
        a = ev(args[1]).astype(np.float64)
        if z3.is_app_of(args[0], z3.Z3_OP_FPA_RM_NEAREST_TIES_TO_AWAY):
            r = np.sign(a) * np.floor(np.abs(a) + 0.5)  # exact for float32 inputs in float64
        elif z3.is_app_of(args[0], z3.Z3_OP_FPA_RM_TOWARD_ZERO):
            r = np.trunc(a)
        else:
            raise Unsupported(f"roundToIntegral {args[0]}")
        return r.astype(_fp_dtype(t.sort()))
    if k == z3.Z3_OP_FPA_TO_SBV:
        if not z3.is_app_of(args[0], z3.Z3_OP_FPA_RM_TOWARD_ZERO):
            raise Unsupported(f"fp.to_sbv {args[0]}")
        a = ev(args[1]).astype(np.float64)
        ok = np.isfinite(a) & (np.abs(a) < 2.0 ** 62)
        return np.where(ok, np.trunc(np.where(ok, a, 0.0)), 0).astype(np.int64)  # guarded by the term's If
    # bit-vectors (values kept as unbounded int64 and wrapped where it matters)
    if k == z3.Z3_OP_ZERO_EXT:
        return ev(args[0])
    if k in (z3.Z3_OP_BADD, z3.Z3_OP_BSUB, z3.Z3_OP_BMUL):
        f = {z3.Z3_OP_BADD: np.add, z3.Z3_OP_BSUB: np.subtract, z3.Z3_OP_BMUL: np.multiply}[k]
        out = ev(args[0])
        for a in args[1:]:
            out = f(out, ev(a))
        return out & ((1 << t.size()) - 1)
    bv_cmp = {z3.Z3_OP_ULEQ: (np.less_equal, False), z3.Z3_OP_UGEQ: (np.greater_equal, False),
              z3.Z3_OP_ULT: (np.less, False), z3.Z3_OP_UGT: (np.greater, False),
              z3.Z3_OP_SLEQ: (np.less_equal, True), z3.Z3_OP_SGEQ: (np.greater_equal, True),
              z3.Z3_OP_SLT: (np.less, True), z3.Z3_OP_SGT: (np.greater, True)}
    if k in bv_cmp:
        f, signed = bv_cmp[k]
        bits = args[0].size()
        a, b = ev(args[0]), ev(args[1])
        if signed:
            a, b = _signed(a, bits), _signed(b, bits)
        else:
            a, b = a & ((1 << bits) - 1), b & ((1 << bits) - 1)
        return f(a, b)
    raise Unsupported(f"operator {t.decl()}")


def points(ranges: dict, variables: dict, assertions) -> int:
    """How many points the box has over the variables the assertions mention."""
    used = set(free_constants(assertions))
    return int(np.prod([hi - lo + 1 for k, (lo, hi) in ranges.items() if str(variables[k]) in used] or [1]))


def solve(assertions: list, variables: dict, ranges: dict):
    """``("sat", {cell: cost})`` at the first point satisfying every assertion, or ``("unsat", None)``."""
    used = free_constants(assertions)
    unknown = set(used) - {str(v) for v in variables.values()}
    if unknown:
        raise Unsupported(f"constants other than costs: {sorted(unknown)}")
    cells = [k for k in ranges if str(variables[k]) in used]
    axes = [np.arange(ranges[k][0], ranges[k][1] + 1) for k in cells]
    total = int(np.prod([len(a) for a in axes] or [1]))
    for start in range(0, total, CHUNK):
        idx = np.arange(start, min(total, start + CHUNK))
        env, rest = {}, idx
        for k, axis in zip(reversed(cells), reversed(axes)):
            env[str(variables[k])] = axis[rest % len(axis)]
            rest = rest // len(axis)
        for a in reversed(assertions):  # each on the points that passed the ones after it (the flip first)
            keep = evaluate(a, env, len(idx), {})
            if not keep.all():
                idx = idx[keep]
                env = {name: v[keep] for name, v in env.items()}
            if not len(idx):
                break
        if len(idx):
            model = {k: int(env[str(variables[k])][0]) if str(variables[k]) in env else ranges[k][0]
                     for k in ranges}
            return "sat", model
    return "unsat", None


def truths(terms: list, variables: dict, costs: np.ndarray) -> Optional[np.ndarray]:
    """Each Boolean term's value at each of the given points (``costs``: one row per point, one
    column per cell of ``variables``, in its order), exact like :func:`solve`: a (terms, points)
    array, or None when a term needs a constant other than a cost or an operator not known."""
    names = {str(v): i for i, v in enumerate(variables.values())}
    if set(free_constants(terms)) - set(names):
        return None
    env = {name: costs[:, i].astype(np.int64) for name, i in names.items()}
    memo: dict = {}
    try:
        return np.array([evaluate(t, env, len(costs), memo) for t in terms], dtype=bool).reshape(len(terms), -1)
    except Unsupported:
        return None
