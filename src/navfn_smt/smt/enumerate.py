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

from ..spec.numeric import ConcreteDomain

CHUNK = 1 << 24  # inputs per evaluation (a few hundred MiB of temporaries at most)
LIMIT = 1 << 33  # the most inputs a part may have to be enumerated


class ArrayDomain(ConcreteDomain):
    """C++ float and double arithmetic, elementwise on numpy arrays (one variable enumerated)."""

    name = "array"

    def __init__(self, values: dict):
        self.values = values
        self.assumptions: list = []
        self.assumption_notes: set = set()
        self.variables: dict = {}

    def f32(self, name):
        if name not in self.values:
            raise KeyError(f"{name}: not enumerated by the part")
        return self.values[name]

    @staticmethod
    def f32const(x):
        return np.float32(x)

    @staticmethod
    def f64const(x):
        return np.float64(x)

    @staticmethod
    def widen(a):
        return np.asarray(a, dtype=np.float32).astype(np.float64)

    @staticmethod
    def narrow(a):
        with np.errstate(all="ignore"):
            return np.asarray(a, dtype=np.float64).astype(np.float32)

    @staticmethod
    def add(a, b):
        with np.errstate(all="ignore"):  # inf and NaN as in C++, silently
            return np.add(a, b, dtype=np.float32)

    @staticmethod
    def sub(a, b):
        with np.errstate(all="ignore"):  # inf and NaN as in C++, silently
            return np.subtract(a, b, dtype=np.float32)

    @staticmethod
    def mul(a, b):
        with np.errstate(all="ignore"):  # inf and NaN as in C++, silently
            return np.multiply(a, b, dtype=np.float32)

    @staticmethod
    def div(a, b):
        with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
            return np.divide(a, b, dtype=np.float32)

    @staticmethod
    def neg(a):
        return np.negative(a)

    @staticmethod
    def add64(a, b):
        with np.errstate(all="ignore"):  # inf and NaN as in C++, silently
            return np.add(a, b, dtype=np.float64)

    @staticmethod
    def sub64(a, b):
        with np.errstate(all="ignore"):  # inf and NaN as in C++, silently
            return np.subtract(a, b, dtype=np.float64)

    @staticmethod
    def mul64(a, b):
        with np.errstate(all="ignore"):  # inf and NaN as in C++, silently
            return np.multiply(a, b, dtype=np.float64)

    @staticmethod
    def div64(a, b):
        with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
            return np.divide(a, b, dtype=np.float64)

    def hypotf(self, a, b):
        wa, wb = self.widen(a), self.widen(b)
        with np.errstate(all="ignore"):
            return self.narrow(np.sqrt(wa * wa + wb * wb))

    @staticmethod
    def lt(a, b):
        return np.less(a, b)

    @staticmethod
    def le(a, b):
        return np.less_equal(a, b)

    @staticmethod
    def gt(a, b):
        return np.greater(a, b)

    @staticmethod
    def ge(a, b):
        return np.greater_equal(a, b)

    @staticmethod
    def eq(a, b):
        return np.equal(a, b)

    @staticmethod
    def and_(a, b):
        return np.logical_and(a, b)

    @staticmethod
    def or_(a, b):
        return np.logical_or(a, b)

    @staticmethod
    def not_(a):
        return np.logical_not(a)

    @staticmethod
    def ite(c, a, b):
        return np.where(c, a, b)


def _floats(lo: int, hi: int) -> np.ndarray:
    """The float32 values at real-order positions ``lo..hi`` (:func:`.split.ordinal`)."""
    k = np.arange(lo, hi + 1, dtype=np.int64)
    bits = np.where(k >= 0, k, (-k) | 0x80000000).astype(np.uint32)
    return bits.view(np.float32)


def decide(ob, box) -> tuple:
    """``(status, detail, witness)`` of ``ob`` on every input of ``box``: one float32
    variable, every other variable of the obligation fixed to one value by the box."""
    from .codec import witness_values
    from .replay import replay

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
        pre, claim = ob.build(ArrayDomain(values))
        bad = np.nonzero(np.broadcast_to(np.logical_and(pre, np.logical_not(claim)), xs.shape))[0]
        count += len(xs)
        if len(bad):
            w = {k: float(v[bad[0]]) for k, v in values.items()}
            confirmed = replay(ob, w)
            witness = {"values": witness_values(w), "replayed_on_spec": confirmed, "replayed_in": "float32 spec"}
            if confirmed is False:
                return "unknown", "the array domain and the scalar spec disagree on an input", witness
            return "refuted", f"input {count - len(xs) + int(bad[0]) + 1} of {var.width}", witness
    return "proved", f"all {count} inputs", None
