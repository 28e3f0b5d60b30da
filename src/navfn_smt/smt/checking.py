"""Checking proof obligations: each one's query in a semantics, solved, and its model replayed.

An obligation *holds* in a semantics when ``assumptions(D) and pre and not claim`` is
unsatisfiable in that domain (``proved``).  A model is a counterexample (``refuted``) only
once the concrete spec confirms it (:func:`navfn_smt.smt.replay.replay`); a model the spec
does not confirm, a solver that gives up or runs out of time gives ``unknown``, never
``proved``.  For a property that fails in float32 only for large values,
:func:`search_bound` finds the largest bound below which it still holds.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Optional

import z3

from ..errors import NavfnInputError
from . import codec
from .codec import f32_from_bits, f32_to_bits, fp32_val
from .domains import DOMAINS, arithmetic_of, is_fp32
from .obligation import Obligation
from .replay import replay


@dataclass
class Outcome:
    """The verdict on one obligation in one semantics, with what the report shows of it."""

    name: str
    predicate: str
    semantics: str
    status: str  # what this run decided: proved | refuted | unknown
    known: str  # what was known before the run (knowledge.Known.status): proved | refuted | unknown
    seconds: float
    solver: str
    scope: str
    statement: str
    assumptions: list = field(default_factory=list)
    bound: Optional[dict] = None
    witness: Optional[dict] = None  # values and replay verdict (refuted only)
    detail: str = ""
    known_source: str = "declared"  # where the knowledge comes from (knowledge.Known.source)
    standing: str = ""  # the one status the reports show (knowledge.standing)
    judgement: str = ""  # how this run stands to what is known (knowledge.JUDGEMENTS)

    def judge(self, known, *also: str) -> "Outcome":
        """Judge this run (and the decisions ``also`` made by others about the same query,
        such as its split's) against ``known`` (a :class:`~navfn_smt.smt.knowledge.Known`):
        set what is known, the standing and the judgement; a bound known from an earlier
        search stands where this run searched none."""
        from .knowledge import standing

        self.known, self.known_source = known.status, known.source
        self.standing, self.judgement = standing(known.status, self.status, *also)
        if self.standing == "refuted" and known.bound is not None and not (self.bound or {}).get("holds_below"):
            self.bound = {**known.bound, "source": "bound cache",
                          "note": "bound found by an earlier search (the bound cache); not searched in this run"}
        return self

    @property
    def fails(self) -> bool:
        """Only a decision against what is known fails a run."""
        from .knowledge import CONTRADICTED

        return self.judgement == CONTRADICTED


def domain_of(ob: Obligation, semantics: str):
    """A fresh domain of ``semantics`` for ``ob`` (float32, in a build's arithmetic, with the
    obligation's hypotf model)."""
    return DOMAINS[semantics](hypotf_model=ob.hypotf_model) if is_fp32(semantics) else DOMAINS[semantics]()


def query(ob: Obligation, semantics: str, extra=None):
    """The obligation's domain and the assertions whose unsatisfiability proves it:
    the domain's assumptions, the precondition (and ``extra(D)``) and the negated claim."""
    D = domain_of(ob, semantics)
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


def solve_query(solvers: tuple):
    """A ``solve(assertions, variables, timeout)`` for :func:`check` over ``solvers``."""
    if tuple(solvers) == ("z3",):
        return solve_z3

    def solve(assertions, variables, timeout):
        from .portfolio import solve as portfolio_solve

        res = portfolio_solve(assertions, timeout=timeout, solvers=solvers)
        if res.status == "error":
            raise RuntimeError("solvers disagree: " + "; ".join(f"{a.solver}={a.status}" for a in res.answers))
        if res.status == "sat":
            win = next(a for a in res.answers if a.solver == res.solver)
            values = codec.replay_values(win.model or {}, variables)
            if values is None:  # the winner gave no usable model: ask z3 for one
                return solve_z3(assertions, variables, timeout)
            return "sat", values, res.solver, ""
        if res.status == "unsat":
            return "unsat", None, res.solver, ""
        return "unknown", None, ",".join(solvers), "; ".join(f"{a.solver}: {a.status}" for a in res.answers)

    return solve


def check(ob: Obligation, semantics: str, timeout: float = 30.0, solve=solve_z3, bounds: bool = True,
          known=None) -> Outcome:
    """Check one obligation in one semantics, judged against ``known`` (default: its declaration)."""
    if ob.timeout is not None:
        timeout = min(timeout, ob.timeout)
    t0 = time.perf_counter()
    D, assertions = query(ob, semantics)
    answer, values, solver, detail = solve(assertions, D.variables, timeout)
    out = Outcome(ob.name, ob.predicate, semantics, "unknown", "unknown",
                  0.0, solver, ob.scope, ob.doc.strip(), sorted(D.assumption_notes), detail=detail)
    if answer == "unsat":
        out.status = "proved"
    elif answer == "sat":
        _judge_model(out, ob, values)
    if bounds and ob.bound is not None and is_fp32(semantics) and out.status == "refuted":
        out.bound = search_bound(ob, timeout, solve, semantics)
    out.seconds = round(time.perf_counter() - t0, 3)
    return out.judge(known if known is not None else declared(ob, semantics))


def declared(ob: Obligation, semantics: str):
    """What ``ob``'s declaration alone says is known in ``semantics`` (the runner judges
    against the whole knowledge: splits, chains and records too)."""
    from .knowledge import DECIDED, NOTHING, Known

    v = ob.expect.get(semantics, "unknown")
    return Known(v) if v in DECIDED else NOTHING


def _judge_model(out: Outcome, ob: Obligation, values: dict) -> None:
    """A solver's model, replayed on the concrete spec: ``refuted`` with its witness when
    the spec confirms it, else ``unknown``."""
    out.status, out.witness, detail = judge_model(ob, out.semantics, values)
    out.detail = detail or out.detail


def judge_model(ob: Obligation, semantics: str, values: dict) -> tuple[str, dict, str]:
    """``(status, witness, detail)`` of a model of ``ob``'s negation in ``semantics``, replayed
    on the concrete spec: ``refuted`` when the spec confirms it, ``unknown`` when it does not."""
    arith = arithmetic_of(semantics)
    if ob.arrays:  # no concrete array to replay the model on: never reported unreplayed
        return "unknown", {"values": codec.witness_values(values), "replayed_on_spec": None}, (
            "solver model over arrays, which the concrete spec cannot replay: not reported as a counterexample")
    confirmed = replay(ob, values, arithmetic=arith)
    if confirmed is None:  # a term the concrete spec cannot evaluate: never reported unreplayed
        return "unknown", {"values": codec.witness_values(values), "replayed_on_spec": None}, (
            "solver model of an obligation with a variable the concrete spec cannot evaluate (made with z3, "
            "not through the domain): not reported as a counterexample")
    witness = {"values": codec.witness_values(values), "replayed_on_spec": confirmed,
               "replayed_in": "rationals (real semantics)" if arith is None else
               "float32 spec" + ("" if semantics == "fp32" else f" in {arith.name}'s arithmetic")}
    if confirmed is False:
        # the model satisfies the library-function model but not the real libm: it is not
        # a counterexample of the compiled planner; the question stays open
        return "unknown", witness, "solver model not confirmed by the concrete spec (libm differs from its model)"
    return "refuted", witness, ""


def search_bound(ob: Obligation, timeout: float, solve=solve_z3, semantics: str = "fp32") -> dict:
    """The largest float32 X in [lo, hi] with ``var < X`` added to the precondition such
    that the obligation is proved, by bisection over positive float32 bit patterns (the
    property is monotone in X: a smaller X only strengthens the precondition)."""
    b = ob.bound
    lo, hi = f32_to_bits(b.lo), f32_to_bits(b.hi)  # invariant: proved at lo, refuted at hi

    witness_at: dict = {}

    def proved_below(bits_x: int) -> Optional[bool]:
        x = f32_from_bits(bits_x)
        extra = lambda D: z3.fpLT(D.variables[b.var], fp32_val(x))  # noqa: E731
        D, assertions = query(ob, semantics, extra)
        ans, values, _, _ = solve(assertions, D.variables, timeout)
        if ans == "unsat":
            return True
        if ans == "sat":
            if not replay(ob, values, lambda C: values[b.var] < x, arithmetic_of(semantics)):
                return None
            witness_at[bits_x] = values[b.var]
            return False
        return None

    cache = _BoundCache(ob, semantics)
    known = cache.get()
    if known is not None:
        kb = f32_to_bits(known)
        if proved_below(kb) is True and proved_below(kb + 1) is False:
            return {"var": b.var, "holds_below": known, "refuted_below": f32_from_bits(kb + 1), "solver_calls": 2,
                    "note": "bound from an earlier search, verified tight (proved below it, refuted one ulp above)"}
    first = proved_below(lo)
    if first is not True:
        return {"var": b.var, "holds_below": None, "note": f"not proved even for {b.var} < {b.lo}"}
    if proved_below(hi) is not False:
        return {"var": b.var, "holds_below": None, "note": f"no confirmed counterexample below {b.hi}"}
    calls = 2
    hi = min(hi, f32_to_bits(witness_at[hi]) + 1)  # refuted already below the counterexample's value + 1 ulp
    while hi - lo > 1:
        mid = (lo + hi) // 2
        r = proved_below(mid)
        calls += 1
        if r is None:
            return {"var": b.var, "holds_below": f32_from_bits(lo), "note": "search stopped on an unknown answer",
                    "solver_calls": calls}
        if r:
            lo = mid
        else:  # a confirmed counterexample with var = w < mid: refuted below w + 1 ulp as well
            hi = min(mid, f32_to_bits(witness_at[mid]) + 1)
    out = {"var": b.var, "holds_below": f32_from_bits(lo), "refuted_below": f32_from_bits(hi),
           "solver_calls": calls}
    not_cached = cache.put(f32_from_bits(lo))
    if not_cached:
        out["cache"] = not_cached
    return out


def cached_bound(ob: Obligation, semantics: str = "fp32") -> Optional[float]:
    """The bound an earlier search found for ``ob`` in ``semantics`` and the code as it is now, if cached."""
    return _BoundCache(ob, semantics).get() if ob.bound is not None else None


class _BoundCache:
    """Bounds found by search, kept beside the proof file (``.bounds.json``) and keyed by a
    hash of the proof file, the kernels and the domains (and the semantics, for a build
    arithmetic other than x86-64's): a later run only re-verifies that the bound is tight (two
    solver calls) instead of searching again."""

    def __init__(self, ob: Obligation, semantics: str = "fp32"):
        from .knowledge import content_key

        self.ob = ob
        self.path = Path(ob.source).parent / ".bounds.json" if ob.source else None
        self.key = content_key(ob) + ("" if semantics == "fp32" else f"@{semantics}")

    def _load(self) -> dict:
        import json

        try:
            return json.loads(self.path.read_text()) if self.path and self.path.exists() else {}
        except (OSError, ValueError):
            return {}

    def get(self) -> Optional[float]:
        return self._load().get(self.key)

    def put(self, value: float) -> Optional[str]:
        """Keep ``value``; when the file cannot be written (a read-only install), say why
        instead: the bound found stands, the next run searches again."""
        import json

        from ..fileio import atomic_write_text

        if self.path is None:
            return "not cached (the obligation has no proof file)"
        doc = {k: v for k, v in self._load().items()  # this obligation's older bound in this semantics goes
               if not (k.startswith(self.ob.name + ":") and k.partition("@")[2] == self.key.partition("@")[2])}
        doc[self.key] = value
        try:
            atomic_write_text(self.path, json.dumps(doc, indent=1, sort_keys=True) + "\n")
        except (NavfnInputError, OSError) as e:
            return f"not cached ({e}); the next run searches again"
        return None
