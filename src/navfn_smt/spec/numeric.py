"""The concrete numeric domain: C++ float/double/int arithmetic as NavFn's binary computes it.

Values are Python objects:

* a C++ ``float`` is a Python ``float`` whose value is exactly representable in
  IEEE-754 binary32 (every float32 operation rounds its exact result to nearest-even);
* a C++ ``double`` is a Python ``float`` (Python floats are binary64);
* a C++ ``int`` is a Python ``int``.

Rounding a binary64 result of ``+ - * /`` on two binary32 operands to binary32 gives
the correctly rounded binary32 result (53 >= 2*24 + 2, so double rounding is
innocuous), which is how :meth:`ConcreteDomain.add` and friends work.

The library functions are the ones the compiled original calls, taken from the C
library: ``hypot`` (double, for the integer distance terms of A*) and ``hypotf``
(float, for gradients and the path step).  ``roundf`` has an exact definition (half
away from zero) and is computed exactly here.  Python's ``round`` (half to even) and
``math.hypot`` (CPython's own algorithm) are *not* these functions.

The same method names are implemented by the symbolic domains of :mod:`navfn_smt.smt`,
so one kernel (:mod:`navfn_smt.spec.kernels`) serves all interpretations.
"""

from __future__ import annotations

import copy
import ctypes
import ctypes.util
import math
import struct

from .constants import INT_MAX, INT_MIN

_F32 = struct.Struct("<f")
_pack = _F32.pack
_unpack = _F32.unpack


def f32(x: float) -> float:
    """Round a binary64 value to the nearest binary32 value (ties to even), as C's ``(float)x``."""
    try:
        return _unpack(_pack(x))[0]
    except OverflowError:  # beyond float32 range: IEEE gives +-inf
        return math.copysign(math.inf, x)


def _load_libm():
    name = ctypes.util.find_library("m") or "libm.so.6"
    lib = ctypes.CDLL(name)
    hyp = lib.hypot
    hyp.restype = ctypes.c_double
    hyp.argtypes = [ctypes.c_double, ctypes.c_double]
    hypf = lib.hypotf
    hypf.restype = ctypes.c_float
    hypf.argtypes = [ctypes.c_float, ctypes.c_float]
    fma, fmaf = lib.fma, lib.fmaf
    fma.restype, fmaf.restype = ctypes.c_double, ctypes.c_float
    fma.argtypes, fmaf.argtypes = [ctypes.c_double] * 3, [ctypes.c_float] * 3
    return hyp, hypf, fma, fmaf


_c_hypot, _c_hypotf, _c_fma, _c_fmaf = _load_libm()


def c_fma(a: float, b: float, c: float) -> float:
    """C ``fma``: ``a * b + c`` in binary64, rounded once (libm's, correctly rounded)."""
    return _c_fma(a, b, c)


def c_fmaf(a: float, b: float, c: float) -> float:
    """C ``fmaf``: ``a * b + c`` in binary32, rounded once; the arguments are float32 values."""
    return _c_fmaf(a, b, c)


def c_hypot(a: float, b: float) -> float:
    """C ``hypot`` (binary64) from the platform's libm."""
    return _c_hypot(a, b)


def c_hypotf(a: float, b: float) -> float:
    """C ``hypotf`` (binary32) from the platform's libm; arguments must be float32 values."""
    return _c_hypotf(a, b)


def c_roundf(a: float) -> float:
    """C ``roundf``: the nearest integer, halves away from zero; exact for every float32.

    For a float32 value ``|a| + 0.5`` is exact in binary64 (the sum needs at most 54
    significant bits only when ``|a| >= 2**52``, where ``a`` is already integral), so
    ``floor(|a| + 0.5)`` is the exact rounded magnitude.
    """
    if math.isnan(a) or math.isinf(a):
        return a
    m = abs(a)
    if m >= 2.0**23:  # every float32 of this magnitude is an integer
        return a
    return math.copysign(float(math.floor(m + 0.5)), a)


def cvt_to_int32(a: float) -> int:
    """C ``static_cast<int>`` of a float or double on x86-64 (cvttss2si / cvttsd2si).

    Truncates toward zero; NaN and values outside the int32 range give INT_MIN (the
    "integer indefinite" value), which is what the compiled original does.
    """
    if a != a:
        return INT_MIN
    if -2147483649.0 < a < 2147483648.0:
        return int(a)  # int() truncates toward zero
    return INT_MIN


def cvt_to_int32_saturating(a: float) -> int:
    """C ``static_cast<int>`` of a float or double on arm64 (``fcvtzs``): truncates toward zero,
    values out of range clamp to INT_MIN or INT_MAX, NaN gives 0."""
    if a != a:
        return 0
    if a >= 2147483648.0:
        return INT_MAX
    if a <= -2147483649.0:
        return INT_MIN
    return int(a)


# each float-to-int conversion a build may have (spec.arithmetic.CONVERSIONS), as computed here
CONVERTERS = {"indefinite": cvt_to_int32, "saturating": cvt_to_int32_saturating}


def wrap_int32(n: int) -> int:
    """Two's-complement wrap of an int to 32 bits (what x86-64 does on overflow)."""
    return ((n + 2**31) & 0xFFFFFFFF) - 2**31


class ConcreteDomain:
    """C++ arithmetic on concrete values; see the module docstring for representation.

    Method families: ``*32`` helpers act on floats, ``*64`` on doubles; comparisons take
    two values of the same kind; ``ite`` chooses between two already computed values.
    ``arith`` is the build's :class:`~navfn_smt.spec.arithmetic.Arithmetic` (None: x86-64's,
    nothing fused, conversions indefinite); :meth:`with_arithmetic` gives the domain in another.
    """

    name = "concrete"
    arith = None

    def with_arithmetic(self, arith):
        """This domain computing as a build of the arithmetic ``arith`` does."""
        other = copy.copy(self)
        other.arith = arith
        return other

    def fuses(self, site: str) -> bool:
        """Whether the build computes the multiply-add at ``site`` with one rounding."""
        return self.arith is not None and self.arith.fuses(site)

    # --- constants and conversions ------------------------------------------------
    @staticmethod
    def f32const(x: float) -> float:
        return f32(float(x))

    @staticmethod
    def f64const(x: float) -> float:
        return float(x)

    @staticmethod
    def widen(a: float) -> float:  # float -> double, exact
        return a

    narrow = staticmethod(f32)  # double -> float, round to nearest even

    @staticmethod
    def int_to_f32(n: int) -> float:  # (float)n, rounds for |n| > 2**24
        return f32(float(n))

    @staticmethod
    def int_to_f64(n: int) -> float:  # (double)n, exact for int32
        return float(n)

    def to_int32(self, a: float) -> int:  # (int) of a float or double, as the build's target converts
        return CONVERTERS[self.arith.conversion if self.arith is not None else "indefinite"](a)

    @staticmethod
    def add_int(a: int, b: int) -> int:  # int + int, wrapping at 32 bits
        return wrap_int32(a + b)

    # --- float arithmetic (binary32) ------------------------------------------------
    @staticmethod
    def add(a: float, b: float) -> float:
        return f32(a + b)

    @staticmethod
    def sub(a: float, b: float) -> float:
        return f32(a - b)

    @staticmethod
    def mul(a: float, b: float) -> float:
        return f32(a * b)

    @staticmethod
    def div(a: float, b: float) -> float:
        return f32(_ieee_div(a, b))

    @staticmethod
    def neg(a: float) -> float:
        return -a

    fma = staticmethod(c_fmaf)  # a * b + c in float, rounded once

    # --- double arithmetic (binary64) -----------------------------------------------
    @staticmethod
    def add64(a: float, b: float) -> float:
        return a + b

    @staticmethod
    def sub64(a: float, b: float) -> float:
        return a - b

    @staticmethod
    def mul64(a: float, b: float) -> float:
        return a * b

    @staticmethod
    def div64(a: float, b: float) -> float:
        return _ieee_div(a, b)

    fma64 = staticmethod(c_fma)  # a * b + c in double, rounded once

    # --- library functions ----------------------------------------------------------
    hypot64 = staticmethod(c_hypot)
    hypotf = staticmethod(c_hypotf)
    roundf = staticmethod(c_roundf)

    # --- comparisons and choice -----------------------------------------------------
    @staticmethod
    def lt(a, b) -> bool:
        return a < b

    @staticmethod
    def le(a, b) -> bool:
        return a <= b

    @staticmethod
    def gt(a, b) -> bool:
        return a > b

    @staticmethod
    def ge(a, b) -> bool:
        return a >= b

    @staticmethod
    def eq(a, b) -> bool:
        return a == b

    @staticmethod
    def and_(a: bool, b: bool) -> bool:
        return a and b

    @staticmethod
    def or_(a: bool, b: bool) -> bool:
        return a or b

    @staticmethod
    def not_(a: bool) -> bool:
        return not a

    @staticmethod
    def ite(c: bool, a, b):
        return a if c else b


def _ieee_div(a: float, b: float) -> float:
    try:
        return a / b
    except ZeroDivisionError:
        if a != a or a == 0.0:
            return math.nan
        return math.copysign(math.inf, a) * math.copysign(1.0, b)


CONCRETE = ConcreteDomain()


def taken(D, c):
    """A condition the control flow goes on with, as the domain ``D`` runs it: in a domain that
    follows one control path (``D.decide``: the concolic domain of ``check``), the branch this
    run takes, as a plain bool (the domain records it where its box leaves it open); in every
    other domain ``c`` itself (a bool of the concrete domain; a term of a symbolic one, whose
    run guards each step by it)."""
    decide = getattr(D, "decide", None)
    return c if decide is None or isinstance(c, bool) else decide(c)


def f32_bits(x: float) -> int:
    """The binary32 bit pattern of a float32 value (for bit-exact comparisons)."""
    return int.from_bytes(_pack(x), "little")
