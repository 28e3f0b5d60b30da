"""Deciding a part by exhaustion: the obligation run on every input of the part at once.

:class:`ArrayDomain` is the concrete float32 domain on numpy arrays: a variable is the
array of every float32 in the part's interval (a chunk of them at a time), and each
operation is numpy's elementwise IEEE-754 operation in the C++ type: float ops on
``float32`` arrays (numpy rounds each to nearest-even, as the SSE instructions do), double
ops on ``float64``, ``(float)`` of a double by ``astype``.  ``hypotf`` is glibc's definition,
``(float) sqrt((double) a * a + (double) b * b)`` (the same definition the bit-precise
domain uses, held equal to the platform's libm by the equality test).  So a part is
``proved`` when ``pre ==> claim`` holds on every element, and ``refuted`` by the first
element where it fails, which is then replayed on the scalar spec like any model.
"""

from __future__ import annotations

import numpy as np

from ..spec.numeric import c_fma
from .replay import ReplayDomain

# inputs per evaluation: each operation's temporaries (a few hundred KiB) stay in the CPU's cache;
# a part of 2**25 inputs took 7.4 s in chunks of 2**24 and 1.0 s in chunks of 2**16 (2**14: 1.3 s)
CHUNK = 1 << 16
_FMA64 = np.frompyfunc(c_fma, 3, 1)


def fma_array(a, b, c) -> np.ndarray:
    """``fma`` elementwise (``a * b + c`` rounded once to double): libm's, point by point (exact, slow)."""
    return _FMA64(*np.broadcast_arrays(a, b, c)).astype(np.float64)


def fmaf_array(a, b, c) -> np.ndarray:
    """``fmaf`` elementwise, exactly (``a * b + c`` rounded once to float32), vectorised: the
    product of two floats is exact in double; the double sum ``t`` and its error ``e`` (TwoSum,
    exact) give the exact result ``t + e``; rounding ``t`` to float is then right unless ``t`` is
    a midpoint of two floats and ``e`` is not zero, where the next double from ``t`` towards the
    exact result (no midpoint) rounds right instead.  Held to libm's ``fmaf`` by a test."""
    with np.errstate(all="ignore"):
        a, b, c = (np.asarray(x, dtype=np.float32).astype(np.float64) for x in np.broadcast_arrays(a, b, c))
        s = a * b
        t = s + c
        bp = t - s
        e = (s - (t - bp)) + (c - bp)
        f = t.astype(np.float32)
        up = t > f.astype(np.float64)
        g = np.nextafter(f, np.where(up, np.float32(np.inf), np.float32(-np.inf)))
        mid = np.isfinite(t) & np.isfinite(f) & (f.astype(np.float64) != t) & (
            (f.astype(np.float64) + g.astype(np.float64)) * 0.5 == t) & (e != 0)
        fixed = np.nextafter(t, np.where(e > 0, np.inf, -np.inf)).astype(np.float32)
    return np.where(mid, fixed, f)
LIMIT = 1 << 33  # the most inputs a part may have to be enumerated


def _elementwise(fn, dtype):
    """``fn(a, b)`` computed in ``dtype``, with infinities and NaN as in C++ (no warning)."""

    def op(a, b):
        with np.errstate(all="ignore"):
            return fn(a, b, dtype=dtype)

    return staticmethod(op)


class ArrayDomain(ReplayDomain):
    """C++ float and double arithmetic, elementwise on numpy arrays: the replay domain whose
    values are arrays of inputs (one variable enumerated, the others repeated)."""

    name = "array"

    # comparisons, logic and choice: numpy's elementwise functions
    lt = staticmethod(np.less)
    le = staticmethod(np.less_equal)
    gt = staticmethod(np.greater)
    ge = staticmethod(np.greater_equal)
    eq = staticmethod(np.equal)
    and_ = staticmethod(np.logical_and)
    or_ = staticmethod(np.logical_or)
    not_ = staticmethod(np.logical_not)
    ite = staticmethod(np.where)
    neg = staticmethod(np.negative)
    f32const = staticmethod(np.float32)
    f64const = staticmethod(np.float64)

    @staticmethod
    def widen(a):
        return np.asarray(a, dtype=np.float32).astype(np.float64)

    @staticmethod
    def narrow(a):
        with np.errstate(all="ignore"):
            return np.asarray(a, dtype=np.float64).astype(np.float32)

    # float ops in float32, double ops in float64 (numpy rounds each result to nearest-even)
    add, sub, mul, div = (_elementwise(f, np.float32) for f in (np.add, np.subtract, np.multiply, np.divide))
    add64, sub64, mul64, div64 = (_elementwise(f, np.float64) for f in (np.add, np.subtract, np.multiply, np.divide))

    def fma(self, a, b, c):
        """``a * b + c`` in float rounded once, elementwise (:func:`fmaf_array`, exact)."""
        return fmaf_array(a, b, c)

    def fma64(self, a, b, c):
        return fma_array(a, b, c)

    def hypotf(self, a, b):
        """glibc's ``hypotf``: the square root in double, rounded once to float; an infinite
        argument gives +inf even beside a NaN (IEEE 754 and C's hypot)."""
        wa, wb = self.widen(a), self.widen(b)
        with np.errstate(all="ignore"):
            return np.where(np.isinf(wa) | np.isinf(wb), np.float32(np.inf), self.narrow(np.sqrt(wa * wa + wb * wb)))


def _floats(lo: int, hi: int) -> np.ndarray:
    """The float32 values at real-order positions ``lo..hi`` (:func:`.split.ordinal`)."""
    k = np.arange(lo, hi + 1, dtype=np.int64)
    bits = np.where(k >= 0, k, (-k) | 0x80000000).astype(np.uint32)
    return bits.view(np.float32)


def decide(ob, box, semantics: str = "fp32") -> tuple:
    """``(status, detail, witness)`` of ``ob`` on every input of ``box`` in the float32
    ``semantics`` (a build's arithmetic: smt.domains.FP32_SEMANTICS): one float32 variable,
    every other variable of the obligation fixed to one value by the box."""
    from .domains import arithmetic_of

    from .checking import judge_model

    free = [iv for iv in box if iv.width > 1]
    if any(iv.kind != "f32" for iv in box) or len(free) > 1:
        return "unknown", "enumeration takes float32 intervals with at most one of more than one value", None
    if free and free[0].width > LIMIT:
        return "unknown", f"{free[0].width} inputs: more than the {LIMIT} enumeration takes", None
    fixed = {iv.var: _floats(iv.lo, iv.lo)[0] for iv in box if iv.width == 1}
    var = free[0] if free else box[0]
    count = 0
    for lo in range(var.lo, var.hi + 1, CHUNK):
        xs = _floats(lo, min(var.hi, lo + CHUNK - 1))
        values = {**{k: np.full(len(xs), v, dtype=np.float32) for k, v in fixed.items()}, var.var: xs}
        pre, claim = ob.build(ArrayDomain(values).with_arithmetic(arithmetic_of(semantics)))
        bad = np.nonzero(np.broadcast_to(np.logical_and(pre, np.logical_not(claim)), xs.shape))[0]
        count += len(xs)
        if len(bad):
            status, witness, _ = judge_model(ob, semantics, {k: float(v[bad[0]]) for k, v in values.items()})
            if status != "refuted":
                return "unknown", "the array domain and the scalar spec disagree on an input", witness
            return "refuted", f"input {count - len(xs) + int(bad[0]) + 1} of {var.width}", witness
    return "proved", f"all {count} inputs", None
