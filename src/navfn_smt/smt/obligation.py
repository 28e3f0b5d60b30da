"""Proof obligations: a property of the kernels, stated once, checked in each semantics.

An obligation is a function ``build(D) -> (pre, claim)`` written against a numeric domain
``D`` (:mod:`navfn_smt.smt.domains`): it mints its variables from ``D``, runs the spec
kernels on them and returns a precondition and a claim.  It *holds* when
``assumptions(D) and pre and not claim`` is unsatisfiable (``proved``); a model is a
counterexample (``refuted``), which is replayed on the concrete spec before it is
reported: the same ``build`` runs in a replay domain that hands out the model's values
and computes with the C++ arithmetic and the platform's libm.  A solver that gives up or
runs out of time gives ``unknown``, never ``proved``.

Obligations live in ``proofs/*.py``, declared with :func:`obligation`, each with the
verdict it is expected to get in each semantics; ``navfn-smt prove`` fails when a
verdict changes.
"""

from __future__ import annotations

import importlib.util
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Callable, Optional

import z3

from ..errors import NavfnInputError
from ..spec.numeric import ConcreteDomain, c_hypot, c_hypotf
from . import codec
from .domains import DOMAINS, ExactArithmetic

STATUSES = ("proved", "refuted", "unknown")


@dataclass(frozen=True)
class Bound:
    """For a property that fails in float32 only for large values: the variable to bound
    (``var < X``) and the range in which the largest X that still proves is searched."""

    var: str
    lo: float
    hi: float


@dataclass
class Obligation:
    name: str
    predicate: str  # the paper's predicate this obligation is part of
    build: Callable
    expect: dict  # semantics -> "proved" | "refuted" | "unknown" (an open question, documented as such)
    scope: str
    doc: str
    source: str = ""
    bound: Optional[Bound] = None
    timeout: Optional[float] = None  # a cap on the run's time limit (for questions known to be open)
    hypotf_model: str = "glibc"  # fp32: glibc's exact implementation, "ulp" (documented accuracy) or "bounds" (ordering only)

    @property
    def title(self) -> str:
        return self.doc.strip().splitlines()[0] if self.doc else self.name


def obligation(predicate: str, expect: dict, scope: str, bound: Optional[Bound] = None, hypotf_model: str = "glibc",
               timeout: Optional[float] = None):
    """Declare a proof obligation (a decorator for ``build(D) -> (pre, claim)``).

    ``timeout`` caps the run's time limit for this obligation: an open question (expected
    ``unknown``) need not spend the whole limit of every run on a known timeout."""

    def wrap(fn):
        for sem, verdict in expect.items():
            if sem not in DOMAINS or verdict not in STATUSES:
                raise ValueError(f"{fn.__name__}: bad expectation {sem}={verdict}")
        return Obligation(fn.__name__, predicate, fn, dict(expect), scope, fn.__doc__ or "", bound=bound,
                          hypotf_model=hypotf_model, timeout=timeout)

    return wrap


def load_obligations(paths) -> list[Obligation]:
    """Every :class:`Obligation` defined at module level in the given proof files."""
    found: list[Obligation] = []
    for p in paths:
        p = Path(p)
        if not p.is_file():
            raise NavfnInputError(f"{p}: no such proof file")
        spec = importlib.util.spec_from_file_location(f"navfn_proofs.{p.stem}", p)
        mod = importlib.util.module_from_spec(spec)
        try:
            spec.loader.exec_module(mod)
        except Exception as e:  # a broken proof file is the user's input
            raise NavfnInputError(f"{p}: cannot load ({type(e).__name__}: {e})") from None
        obs = [v for v in vars(mod).values() if isinstance(v, Obligation)]
        if not obs:
            raise NavfnInputError(f"{p}: defines no obligations")
        for o in obs:
            o.source = str(p)
        found.extend(obs)
    names = [o.name for o in found]
    dup = {n for n in names if names.count(n) > 1}
    if dup:
        raise NavfnInputError(f"obligations defined twice: {', '.join(sorted(dup))}")
    return found


# ------------------------------------------------------------------------------ replay
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
        from fractions import Fraction

        return Fraction(x)

    def f32const(self, x):
        from ..spec.numeric import f32

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
        import math

        return math.trunc(a)

    @staticmethod
    def div(a, b):
        # the kernels compute both sides of a choice; a quotient by zero is never chosen
        # (in SMT-LIB real division by zero is an unspecified value as well)
        return a / b if b != 0 else a * 0

    div64 = div

    def _sqrt(self, a, b):
        from decimal import Decimal, getcontext
        from fractions import Fraction

        getcontext().prec = 60
        s = Fraction(a) ** 2 + Fraction(b) ** 2
        return Fraction((Decimal(s.numerator) / Decimal(s.denominator)).sqrt())

    def hypot64(self, a, b):
        return self._sqrt(a, b)

    hypotf = hypot64

    @staticmethod
    def roundf(a):
        import math
        from fractions import Fraction

        return (1 if a >= 0 else -1) * math.floor(abs(a) + Fraction(1, 2))


def replay(ob: Obligation, values: dict, extra_pre=None) -> Optional[bool]:
    """Does the concrete spec confirm the counterexample (pre true, claim false)?

    A float32 model is replayed with the C++ arithmetic and the platform's libm; a real
    model (rationals) with the same kernels evaluated exactly on rationals."""
    from fractions import Fraction

    exact = any(isinstance(v, Fraction) for v in values.values())
    D = ExactReplayDomain(values) if exact else ReplayDomain(values)
    pre, claim = ob.build(D)
    if extra_pre is not None:
        pre = pre and extra_pre(D)
    return bool(pre) and not bool(claim)


# ------------------------------------------------------------------------------- check
@dataclass
class Outcome:
    name: str
    predicate: str
    semantics: str
    status: str  # proved | refuted | unknown
    expected: str
    seconds: float
    solver: str
    scope: str
    statement: str
    assumptions: list = field(default_factory=list)
    bound: Optional[dict] = None
    witness: Optional[dict] = None  # values and replay verdict (refuted only)
    detail: str = ""

    @property
    def as_expected(self) -> bool:
        return self.status == self.expected


def _query(ob: Obligation, semantics: str, extra=None):
    D = DOMAINS[semantics](hypotf_model=ob.hypotf_model) if semantics == "fp32" else DOMAINS[semantics]()
    pre, claim = ob.build(D)
    if extra is not None:
        pre = z3.And(pre, extra(D))
    return D, [*D.assumptions, pre, z3.Not(claim)]


def solve_z3(assertions, variables: dict, timeout: float):
    """Z3 alone: ``(answer, values, solver, detail)`` with answer sat/unsat/unknown."""
    s = z3.Solver()
    s.set(timeout=max(1, int(timeout * 1000)))
    s.add(*assertions)
    r = s.check()
    if r == z3.unsat:
        return "unsat", None, "z3", ""
    if r == z3.sat:
        values = codec.replay_values(codec.z3_model(s.model(), variables.values()), variables)
        if values is None:
            return "unknown", None, "z3", "the model gives a variable no number"
        return "sat", values, "z3", ""
    return "unknown", None, "z3", s.reason_unknown()


def check(ob: Obligation, semantics: str, timeout: float = 30.0, solve=solve_z3, bounds: bool = True) -> Outcome:
    """Check one obligation in one semantics."""
    if ob.timeout is not None:
        timeout = min(timeout, ob.timeout)
    t0 = time.perf_counter()
    D, assertions = _query(ob, semantics)
    answer, values, solver, detail = solve(assertions, D.variables, timeout)
    out = Outcome(ob.name, ob.predicate, semantics, "unknown", ob.expect.get(semantics, "proved"),
                  0.0, solver, ob.scope, ob.doc.strip(), sorted(D.assumption_notes), detail=detail)
    if answer == "unsat":
        out.status = "proved"
    elif answer == "sat":
        confirmed = replay(ob, values)
        out.witness = {"values": codec.witness_values(values), "replayed_on_spec": confirmed,
                       "replayed_in": "rationals (real semantics)" if semantics == "real" else "float32 spec"}
        if confirmed is False:
            # the model satisfies the library-function model but not the real libm: it is not
            # a counterexample of the compiled planner; the question stays open
            out.status = "unknown"
            out.detail = "solver model not confirmed by the concrete spec (libm differs from its model)"
        else:
            out.status = "refuted"
    if bounds and ob.bound is not None and semantics == "fp32" and out.status == "refuted":
        out.bound = search_bound(ob, timeout, solve)
    out.seconds = round(time.perf_counter() - t0, 3)
    return out


def search_bound(ob: Obligation, timeout: float, solve=solve_z3) -> dict:
    """The largest float32 X in [lo, hi] with ``var < X`` added to the precondition such
    that the obligation is proved, by bisection over positive float32 bit patterns (the
    property is monotone in X: a smaller X only strengthens the precondition)."""
    b = ob.bound
    lo, hi = codec.f32_to_bits(b.lo), codec.f32_to_bits(b.hi)  # invariant: proved at lo, refuted at hi

    witness_at: dict = {}

    def proved_below(bits_x: int) -> Optional[bool]:
        x = codec.f32_from_bits(bits_x)
        extra = lambda D: z3.fpLT(D.variables[b.var], codec.fp32_val(x))  # noqa: E731
        D, assertions = _query(ob, "fp32", extra)
        ans, values, _, _ = solve(assertions, D.variables, timeout)
        if ans == "unsat":
            return True
        if ans == "sat":
            if not replay(ob, values, lambda C: values[b.var] < x):
                return None
            witness_at[bits_x] = values[b.var]
            return False
        return None

    cache = _BoundCache(ob)
    known = cache.get()
    if known is not None:
        kb = codec.f32_to_bits(known)
        if proved_below(kb) is True and proved_below(kb + 1) is False:
            return {"var": b.var, "holds_below": known, "refuted_below": codec.f32_from_bits(kb + 1), "solver_calls": 2,
                    "note": "bound from an earlier search, verified tight (proved below it, refuted one ulp above)"}
    first = proved_below(lo)
    if first is not True:
        return {"var": b.var, "holds_below": None, "note": f"not proved even for {b.var} < {b.lo}"}
    if proved_below(hi) is not False:
        return {"var": b.var, "holds_below": None, "note": f"no confirmed counterexample below {b.hi}"}
    calls = 2
    hi = min(hi, codec.f32_to_bits(witness_at[hi]) + 1)  # refuted already below the counterexample's value + 1 ulp
    while hi - lo > 1:
        mid = (lo + hi) // 2
        r = proved_below(mid)
        calls += 1
        if r is None:
            return {"var": b.var, "holds_below": codec.f32_from_bits(lo), "note": "search stopped on an unknown answer",
                    "solver_calls": calls}
        if r:
            lo = mid
        else:  # a confirmed counterexample with var = w < mid: refuted below w + 1 ulp as well
            hi = min(mid, codec.f32_to_bits(witness_at[mid]) + 1)
    cache.put(codec.f32_from_bits(lo))
    return {"var": b.var, "holds_below": codec.f32_from_bits(lo), "refuted_below": codec.f32_from_bits(hi),
            "solver_calls": calls}


class _BoundCache:
    """Bounds found by search, kept beside the proof file (``.bounds.json``) and keyed by a
    hash of the proof file, the kernels and the domains: a later run only re-verifies that
    the bound is tight (two solver calls) instead of searching again."""

    def __init__(self, ob: Obligation):
        import hashlib

        self.ob = ob
        src = Path(ob.source) if ob.source else None
        self.path = src.parent / ".bounds.json" if src else None
        h = hashlib.sha256()
        here = Path(__file__).resolve().parent
        for f in (src, here.parent / "spec" / "kernels.py", here / "domains.py"):
            if f is not None and f.exists():
                h.update(f.read_bytes())
        self.key = f"{ob.name}:{h.hexdigest()[:16]}"

    def _load(self) -> dict:
        import json

        try:
            return json.loads(self.path.read_text()) if self.path and self.path.exists() else {}
        except (OSError, ValueError):
            return {}

    def get(self) -> Optional[float]:
        return self._load().get(self.key)

    def put(self, value: float) -> None:
        import json

        from ..fileio import atomic_write_text

        if self.path is None:
            return
        doc = {k: v for k, v in self._load().items() if not k.startswith(self.ob.name + ":")}
        doc[self.key] = value
        try:
            atomic_write_text(self.path, json.dumps(doc, indent=1, sort_keys=True) + "\n")
        except NavfnInputError:
            pass  # a read-only checkout: the next run searches again
