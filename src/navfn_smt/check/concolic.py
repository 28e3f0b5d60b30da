"""A concolic domain: run the whole-planner encoding on one concrete map, keeping its path condition.

Every value derived from a symbolic cost carries three things at once:

* its concrete value (the C++ arithmetic, :data:`~navfn_smt.spec.numeric.CONCRETE`, in the
  build's arithmetic: the symbolic domain's, which fuses the same multiply-adds and converts
  to int the same way), which decides every branch the way the planner takes it on this map;
* an interval that holds its value for *every* cost in the box the check covers
  (float32/float64 rounding to nearest is monotone, so applying the C++ operation to the
  interval's ends gives sound bounds; no outward rounding is needed);
* its term in a symbolic domain (bit-precise float32, or the reals).

``ite(c, a, b)`` returns the branch the concrete value takes.  When the interval of ``c``
does not decide it for the whole box, the branch is recorded (its term, as taken): the
conjunction of the records is the *path condition*, the set of maps that follow the same
control path.  Terms therefore stay path-wise and small, and the intervals keep the
records to the branches the box really leaves open.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Optional

import z3

from ..spec.constants import INT_MAX, INT_MIN
from ..spec.numeric import CONCRETE as C

_INF = math.inf


@dataclass(eq=False)
class V:
    """A value: concrete, interval [lo, hi] over the box, and term.  ``kind``: f32, f64, int, bool.
    For bools ``lo``/``hi`` are the least and greatest truth value over the box."""

    kind: str
    conc: object
    lo: object
    hi: object
    term: object

    @property
    def decided(self) -> bool:
        return self.lo == self.hi

    def __bool__(self):
        """Refused: a branch on a value is taken by the domain (``ConcolicDomain.decide``, which
        the spec reaches through ``spec.numeric.taken``), never by Python's truth test, which
        would take one side silently for every map of the box."""
        raise TypeError(f"the truth of a concolic {self.kind} value is taken with decide(), not bool()")

    def __eq__(self, other):
        """Refused, as :meth:`__bool__`: ``==`` on a value is the domain's ``eq``, then taken."""
        raise TypeError(f"a concolic {self.kind} value is compared with the domain's eq(), not ==")

    __hash__ = object.__hash__


def _plain(x) -> bool:
    return not isinstance(x, V)


class ConcolicDomain:
    """The operations of the concrete domain over :class:`V` values (see the module docstring).

    ``S`` is the symbolic domain that builds the terms.  ``branches`` collects the recorded
    branch terms of the run, in program order; ``by_intervals``, when ``S.record_intervals`` is
    set (None otherwise: no term is kept, so the run builds its queries exactly as before), the
    branches the box decided (no flip possible), each once, as ``(condition term, its value on
    the whole box)``, in program order: what a certificate records and its replay asks a solver
    again."""

    name = "concolic"

    def __init__(self, S):
        self.S = S
        self.branches: list = []
        self.by_intervals: Optional[list] = [] if getattr(S, "record_intervals", False) else None
        self._seen: set = set()
        self.assumptions = S.assumptions
        self._int32 = C.with_arithmetic(getattr(S, "arith", None)).to_int32  # the build's (int)

    def fuses(self, site: str) -> bool:
        """Whether the build fuses the multiply-add ``site``: as the symbolic domain's arithmetic
        says (x86-64's fuses none)."""
        return self.S.fuses(site)

    # ------------------------------------------------------------------ lifting
    def _lift(self, x, kind: str) -> V:
        if isinstance(x, V):
            return x
        if kind == "bool":
            return V("bool", x, x, x, z3.BoolVal(bool(x)))
        if kind == "int":
            return V("int", x, x, x, self.S._int(x) if hasattr(self.S, "_int") else z3.IntVal(x))
        const = self.S.f32const if kind == "f32" else self.S.f64const
        return V(kind, x, x, x, const(x))

    def cost(self, conc: int, lo: int, hi: int, name: str) -> V:
        """A cell's cost byte: concretely ``conc``, any of ``lo..hi`` over the box."""
        return V("cost", conc, lo, hi, self.S.cost(name))

    def cost_int(self, c):
        if _plain(c):
            return c
        return V("int", c.conc, c.lo, c.hi, self.S.cost_int(c.term))

    def cost_as_f32(self, c):
        if _plain(c):
            return C.int_to_f32(c)
        return V("f32", C.int_to_f32(c.conc), C.int_to_f32(c.lo), C.int_to_f32(c.hi), self.S.cost_as_f32(c.term))

    # ------------------------------------------------------- constants, conversions
    f32const = staticmethod(C.f32const)
    f64const = staticmethod(C.f64const)

    @staticmethod
    def _mono(kind, f, sf, a):
        """A conversion monotone non-decreasing in its argument."""
        if _plain(a):
            return f(a)
        return V(kind, f(a.conc), f(a.lo), f(a.hi), sf(a.term))

    def widen(self, a):
        return self._mono("f64", C.widen, self.S.widen, a)

    def narrow(self, a):
        return self._mono("f32", C.narrow, self.S.narrow, a)

    def int_to_f32(self, n):
        return self._mono("f32", C.int_to_f32, self.S.int_to_f32, n)

    def int_to_f64(self, n):
        return self._mono("f64", C.int_to_f64, self.S.int_to_f64, n)

    def roundf(self, a):
        return self._mono("f32", C.roundf, self.S.roundf, a)

    def to_int32(self, a):
        """Truncation is monotone inside the int range; outside it x86-64 gives INT_MIN, and a
        saturating conversion (arm64's) stays monotone, clamping, with NaN giving 0."""
        if _plain(a):
            return self._int32(a)
        term = self.S.to_int32(a.term)
        conc = self._int32(a.conc)
        if getattr(self.S, "arith", None) is not None and self.S.arith.conversion == "saturating":
            if math.isnan(a.lo) or math.isnan(a.hi):
                return V("int", conc, INT_MIN, INT_MAX, term)
            return V("int", conc, self._int32(a.lo), self._int32(a.hi), term)
        if a.lo >= -2.0**31 and a.hi < 2.0**31:
            return V("int", conc, self._int32(a.lo), self._int32(a.hi), term)
        if a.lo >= 2.0**31 or a.hi < -2.0**31:
            return V("int", conc, INT_MIN, INT_MIN, term)
        return V("int", conc, INT_MIN, INT_MAX, term)

    def add_int(self, a, b):
        if _plain(a) and _plain(b):
            return C.add_int(a, b)
        va, vb = self._lift(a, "int"), self._lift(b, "int")
        lo, hi = va.lo + vb.lo, va.hi + vb.hi
        if lo < INT_MIN or hi > INT_MAX:
            lo, hi = INT_MIN, INT_MAX
        return V("int", C.add_int(va.conc, vb.conc), lo, hi, self.S.add_int(va.term, vb.term))

    # ------------------------------------------------------------- arithmetic
    def _binary(self, kind, f, sf, a, b, corners: bool):
        if _plain(a) and _plain(b):
            return f(a, b)
        va, vb = self._lift(a, kind), self._lift(b, kind)
        conc = f(va.conc, vb.conc)
        if corners:
            ends = [f(x, y) for x in (va.lo, va.hi) for y in (vb.lo, vb.hi)]
            if f in (C.div, C.div64) and vb.lo <= 0 <= vb.hi:
                ends = [math.nan]
        else:
            ends = [f(va.lo, vb.lo), f(va.hi, vb.hi)]
        if any(math.isnan(e) for e in ends):
            lo, hi = -_INF, _INF
        else:
            lo, hi = min(ends), max(ends)
        return V(kind, conc, lo, hi, sf(va.term, vb.term))

    def add(self, a, b):
        return self._binary("f32", C.add, self.S.add, a, b, False)

    def add64(self, a, b):
        return self._binary("f64", C.add64, self.S.add64, a, b, False)

    def sub(self, a, b):
        return self.add(a, self.neg(b))

    def sub64(self, a, b):
        return self.add64(a, self.neg(b))

    def mul(self, a, b):
        return self._binary("f32", C.mul, self.S.mul, a, b, True)

    def mul64(self, a, b):
        return self._binary("f64", C.mul64, self.S.mul64, a, b, True)

    def div(self, a, b):
        return self._binary("f32", C.div, self.S.div, a, b, True)

    def div64(self, a, b):
        return self._binary("f64", C.div64, self.S.div64, a, b, True)

    def _fma(self, kind, f, sf, a, b, c):
        """``a * b + c`` rounded once: its extremes over a box are at its corners (bilinear in
        ``a, b``, increasing in ``c``; rounding is monotone)."""
        if _plain(a) and _plain(b) and _plain(c):
            return f(a, b, c)
        va, vb, vc = self._lift(a, kind), self._lift(b, kind), self._lift(c, kind)
        ends = [f(x, y, z) for x in (va.lo, va.hi) for y in (vb.lo, vb.hi) for z in (vc.lo, vc.hi)]
        lo, hi = (-_INF, _INF) if any(math.isnan(e) for e in ends) else (min(ends), max(ends))
        return V(kind, f(va.conc, vb.conc, vc.conc), lo, hi, sf(va.term, vb.term, vc.term))

    def fma(self, a, b, c):
        return self._fma("f32", C.fma, self.S.fma, a, b, c)

    def fma64(self, a, b, c):
        return self._fma("f64", C.fma64, self.S.fma64, a, b, c)

    def neg(self, a):
        if _plain(a):
            return C.neg(a)
        return V(a.kind, C.neg(a.conc), C.neg(a.hi), C.neg(a.lo), self.S.neg(a.term))

    def _hypot(self, f, sf, kind, a, b):
        """Monotone in each argument's magnitude."""
        if _plain(a) and _plain(b):
            return f(a, b)
        va, vb = self._lift(a, kind), self._lift(b, kind)

        def mag(v):
            if v.lo >= 0:
                return v.lo, v.hi
            if v.hi <= 0:
                return -v.hi, -v.lo
            return 0.0, max(-v.lo, v.hi)

        (alo, ahi), (blo, bhi) = mag(va), mag(vb)
        return V(kind, f(va.conc, vb.conc), f(alo, blo), f(ahi, bhi), sf(va.term, vb.term))

    def hypot64(self, a, b):
        return self._hypot(C.hypot64, self.S.hypot64, "f64", a, b)

    def hypotf(self, a, b):
        return self._hypot(C.hypotf, self.S.hypotf, "f32", a, b)

    # ------------------------------------------------------ comparisons, logic
    def _cmp(self, f, sf, always, never, a, b):
        """``always(a, b)``/``never(a, b)`` on intervals: the comparison holds on the whole box / nowhere."""
        if _plain(a) and _plain(b):
            return f(a, b)
        kind = a.kind if isinstance(a, V) else b.kind
        va, vb = self._lift(a, kind), self._lift(b, kind)
        conc = f(va.conc, vb.conc)
        if va.term.eq(vb.term) and not (isinstance(va.conc, float) and math.isnan(va.conc)):
            lo = hi = conc  # one value compared with itself (finite: its interval has no NaN)
        elif any(isinstance(x, float) and math.isnan(x) for x in (va.lo, va.hi, vb.lo, vb.hi)):
            lo, hi = False, True
        elif always(va, vb):
            lo = hi = True
        elif never(va, vb):
            lo = hi = False
        else:
            lo, hi = False, True
        return V("bool", conc, lo, hi, sf(va.term, vb.term))

    def lt(self, a, b):
        return self._cmp(C.lt, self.S.lt, lambda x, y: x.hi < y.lo, lambda x, y: x.lo >= y.hi, a, b)

    def le(self, a, b):
        return self._cmp(C.le, self.S.le, lambda x, y: x.hi <= y.lo, lambda x, y: x.lo > y.hi, a, b)

    def gt(self, a, b):
        return self.lt(b, a)

    def ge(self, a, b):
        return self.le(b, a)

    def eq(self, a, b):
        return self._cmp(C.eq, self.S.eq, lambda x, y: x.lo == x.hi == y.lo == y.hi,
                         lambda x, y: x.hi < y.lo or y.hi < x.lo, a, b)

    def and_(self, a, b):
        if _plain(a) and _plain(b):
            return a and b
        if _plain(a):
            return b if a else False
        if _plain(b):
            return a if b else False
        return V("bool", a.conc and b.conc, a.lo and b.lo, a.hi and b.hi, self.S.and_(a.term, b.term))

    def or_(self, a, b):
        if _plain(a) and _plain(b):
            return a or b
        if _plain(a):
            return True if a else b
        if _plain(b):
            return True if b else a
        return V("bool", a.conc or b.conc, a.lo or b.lo, a.hi or b.hi, self.S.or_(a.term, b.term))

    def not_(self, a):
        if _plain(a):
            return not a
        return V("bool", not a.conc, not a.hi, not a.lo, self.S.not_(a.term))

    def decide(self, c) -> bool:
        """The branch the concrete run takes, recorded (once) when the box leaves it open."""
        if _plain(c):
            return bool(c)
        if not c.decided:
            t = c.term if c.conc else self.S.not_(c.term)
            key = t.get_id()
            if key not in self._seen:
                self._seen.add(key)
                self.branches.append(t)
        elif self.by_intervals is not None and -c.term.get_id() - 1 not in self._seen:  # decided, once
            self._seen.add(-c.term.get_id() - 1)
            self.by_intervals.append((c.term, bool(c.lo)))
        return bool(c.conc)

    def ite(self, c, a, b):
        return a if self.decide(c) else b

    def truth(self, c) -> Optional[bool]:
        """A condition's value on the whole box, or None when the box leaves it open."""
        if _plain(c):
            return bool(c)
        return c.lo if c.decided else None


def concrete(v):
    """The concrete value of a :class:`V` or plain value."""
    return v.conc if isinstance(v, V) else v


def term(D: ConcolicDomain, v):
    """The term of a bool value (plain bools become constants)."""
    return v.term if isinstance(v, V) else z3.BoolVal(bool(v))
