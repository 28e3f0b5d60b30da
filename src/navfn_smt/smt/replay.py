"""Concrete replay of a counterexample: does the spec itself confirm a solver's model?

A model refutes an obligation only if the concrete spec agrees: the obligation's ``build``
runs again in a replay domain that hands out the model's values for its variables and
computes with the C++ arithmetic and the platform's libm (float32 models), or evaluates
the same kernels exactly on rationals (real models).
"""

from __future__ import annotations

import math
from decimal import Decimal, getcontext
from fractions import Fraction
from typing import Optional

import z3

from ..spec.numeric import ConcreteDomain, c_hypot, c_hypotf, f32
from .domains import ExactArithmetic
from .obligation import Obligation


class ReplayDomain(ConcreteDomain):
    """The concrete domain, handing out a model's values for the obligation's variables."""

    name = "replay"

    def __init__(self, values: dict):
        self.values = values
        self.assumptions: list = []
        self.assumption_notes: set = set()
        self.variables: dict = {}

    def _get(self, name):
        if name not in self.values:
            raise KeyError(f"the model has no value for {name}")
        return self.values[name]

    def f32(self, name):
        return self._get(name)

    f64 = f32

    def int32(self, name):
        return self._get(name)

    def cost(self, name):
        return self._get(name)

    @staticmethod
    def cost_as_f32(c):
        return float(c)

    @staticmethod
    def cost_int(c):
        return int(c)

    hypot64 = staticmethod(c_hypot)
    hypotf = staticmethod(c_hypotf)


class ExactReplayDomain(ExactArithmetic, ReplayDomain):
    """The real semantics evaluated concretely on rationals: no rounding anywhere, ints
    without range, ``hypot`` as a 60-digit square root; for replaying ``real`` models."""

    name = "exact"

    @staticmethod
    def _q(x):
        return Fraction(x)

    def f32const(self, x):
        return self._q(f32(float(x)))

    def f64const(self, x):
        return self._q(float(x))

    def cost_as_f32(self, c):
        return self._q(int(c))

    @staticmethod
    def widen(a):
        return a

    narrow = widen

    def int_to_f32(self, n):
        return self._q(n)

    int_to_f64 = int_to_f32

    @staticmethod
    def to_int32(a):
        return math.trunc(a)

    @staticmethod
    def div(a, b):
        # the kernels compute both sides of a choice; a quotient by zero is never chosen
        # (in SMT-LIB real division by zero is an unspecified value as well)
        return a / b if b != 0 else a * 0

    div64 = div

    def _sqrt(self, a, b):
        getcontext().prec = 60
        s = Fraction(a) ** 2 + Fraction(b) ** 2
        return Fraction((Decimal(s.numerator) / Decimal(s.denominator)).sqrt())

    def hypot64(self, a, b):
        return self._sqrt(a, b)

    hypotf = hypot64

    @staticmethod
    def roundf(a):
        return (1 if a >= 0 else -1) * math.floor(abs(a) + Fraction(1, 2))


def replay(ob: Obligation, values: dict, extra_pre=None, arithmetic=None) -> Optional[bool]:
    """Does the concrete spec confirm the counterexample (pre true, claim false)?

    A float32 model is replayed with the C++ arithmetic of the build ``arithmetic``
    (:class:`~navfn_smt.spec.arithmetic.Arithmetic`; None: x86-64's) and the platform's libm; a
    real model (rationals) with the same kernels evaluated exactly on rationals.  None when the
    obligation builds a solver term the concrete spec cannot evaluate (a variable made with z3
    directly, not through the domain): the model is then not replayed."""
    exact = any(isinstance(v, Fraction) for v in values.values())
    D = ExactReplayDomain(values) if exact else ReplayDomain(values).with_arithmetic(arithmetic)
    pre, claim = ob.build(D)
    if extra_pre is not None:
        pre = pre and extra_pre(D)
    if isinstance(pre, z3.ExprRef) or isinstance(claim, z3.ExprRef):
        return None
    return bool(pre) and not bool(claim)
