"""The numeric domain: what the kernels (:mod:`.kernels`) ask of the ``D`` they are given.

Stated once, as a :class:`typing.Protocol`.  The concrete domain (:mod:`.numeric`) computes
with Python floats as C++ does; the numba domain compiles the same operations; the
bit-precise and real domains build solver terms; the concolic domain carries intervals and
terms beside the concrete value; the array domain computes on numpy arrays.  Each operation
below says what it stands for in C++ (``float`` is binary32, ``double`` binary64, every
operation rounds to nearest-even unless it says otherwise).  The conformance harness
(``tests/domain_harness.py``, run by ``tests/test_domain_conformance.py``) holds every domain to this list and to the concrete
domain's results, bit for bit, on the inputs of :mod:`.conformance`.
"""

from __future__ import annotations

from typing import Protocol


class NumericDomain(Protocol):
    """The operations every numeric domain provides (values are the domain's own)."""

    # constants and conversions
    def f32const(self, x: float):
        """A ``float`` literal: the value rounded to binary32."""

    def f64const(self, x: float):
        """A ``double`` literal."""

    def widen(self, a):
        """``(double) a`` for a ``float``: exact."""

    def narrow(self, a):
        """``(float) a`` for a ``double``: rounded to nearest-even."""

    def int_to_f32(self, n):
        """``(float) n`` for an ``int``: rounded above 2**24."""

    def int_to_f64(self, n):
        """``(double) n`` for an ``int``: exact."""

    def to_int32(self, a):
        """``(int) a``: truncation toward zero; out of range or NaN as the domain's arithmetic
        converts (x86-64's cvttss2si/cvttsd2si: INT_MIN; arm64's fcvtzs: saturated, NaN 0)."""

    def add_int(self, a, b):
        """``a + b`` on ``int``: wrapping at 32 bits as x86-64 does."""

    # float arithmetic (binary32)
    def add(self, a, b):
        """``float + float``."""

    def sub(self, a, b):
        """``float - float``."""

    def mul(self, a, b):
        """``float * float``."""

    def div(self, a, b):
        """``float / float`` (IEEE: inf or NaN on a zero divisor)."""

    def neg(self, a):
        """``-a`` (a sign flip, exact)."""

    def fma(self, a, b, c):
        """``a * b + c`` on ``float`` contracted into one fused multiply-add: rounded once."""

    def fuses(self, site):
        """Whether the build contracts the multiply-add at ``site`` (spec.arithmetic.SITES): the
        domain's arithmetic (x86-64's fuses none)."""

    # double arithmetic (binary64)
    def add64(self, a, b):
        """``double + double``."""

    def sub64(self, a, b):
        """``double - double``."""

    def mul64(self, a, b):
        """``double * double``."""

    def div64(self, a, b):
        """``double / double``."""

    def fma64(self, a, b, c):
        """``a * b + c`` on ``double`` contracted into one fused multiply-add: rounded once."""

    # the C library
    def hypot64(self, a, b):
        """glibc's ``hypot`` (double)."""

    def hypotf(self, a, b):
        """glibc's ``hypotf`` (float): an infinite argument gives +inf, even beside a NaN."""

    def roundf(self, a):
        """C's ``roundf``: to the nearest integer, halves away from zero."""

    # comparisons (IEEE: false with a NaN), logic and choice
    def lt(self, a, b):
        """``a < b``."""

    def le(self, a, b):
        """``a <= b``."""

    def gt(self, a, b):
        """``a > b``."""

    def ge(self, a, b):
        """``a >= b``."""

    def eq(self, a, b):
        """``a == b``."""

    def and_(self, a, b):
        """``a && b`` (both sides evaluated: the kernels' operands have no side effects)."""

    def or_(self, a, b):
        """``a || b``."""

    def not_(self, a):
        """``!a``."""

    def ite(self, c, a, b):
        """``c ? a : b``."""


OPERATIONS = tuple(n for n, v in vars(NumericDomain).items() if callable(v) and not n.startswith("_"))
