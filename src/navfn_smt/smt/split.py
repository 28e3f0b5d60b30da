"""Splitting an obligation no solver decides whole into parts that cover its input space.

An obligation states ``pre ==> claim`` over its variables.  A *split* of it is a set of
*parts*, each a box: an interval of values for some of the variables (float32 intervals
in the order of the reals, both ends included; integer intervals for int variables).
Part ``k`` is the obligation ``pre and box_k ==> claim``; the *cover* is the obligation
``pre ==> box_1 or ... or box_n``.  The obligation is

- ``proved`` when the cover and every part are proved;
- ``refuted`` when a part is refuted by a model the concrete spec confirms (the model
  satisfies ``pre``, so it refutes the whole obligation);
- ``unknown`` otherwise, naming the undecided parts.

The parts are found by refinement: a split declares its first boxes (sign cases, zero,
ranges of magnitudes); a part a solver leaves undecided within the part time limit is
bisected along its widest variable, in the order of float32 bit patterns, so that the
first cuts separate exponent ranges and later ones intervals of the significand, down to a
depth limit.  The cover is checked on the final parts, whatever their verdicts, as a
solver query of its own.  Each round of parts runs on the engine (:mod:`navfn_smt.engine`):
this process, local workers or a Dask cluster.
"""

from __future__ import annotations

import itertools
import math
import time
from dataclasses import asdict, dataclass, field
from fractions import Fraction
from pathlib import Path
from typing import Callable, Iterable, Optional

import z3

from .codec import f32_from_bits, f32_to_bits, fp32_val

# ------------------------------------------------------------------ float32 in real order

def ordinal(x: float) -> int:
    """The position of float32 ``x`` in the order of the reals: 0 for both zeros, n for the
    n-th float above zero, -n for the n-th below (NaN has none)."""
    if math.isnan(x):
        raise ValueError("NaN has no place in the order of the reals")
    bits = f32_to_bits(x)
    return bits if bits < 0x80000000 else -(bits & 0x7FFFFFFF)


def from_ordinal(k: int) -> float:
    """The float32 at position ``k`` (:func:`ordinal`'s inverse; 0 gives +0.0)."""
    return f32_from_bits(k) if k >= 0 else f32_from_bits(0x80000000 | -k)


@dataclass(frozen=True)
class Interval:
    """``lo <= v <= hi`` for variable ``var``: float32 ordinals (``kind="f32"``) or ints."""

    var: str
    lo: int
    hi: int
    kind: str = "f32"

    @property
    def width(self) -> int:
        return self.hi - self.lo + 1

    def halves(self) -> tuple["Interval", "Interval"]:
        mid = (self.lo + self.hi) // 2
        return Interval(self.var, self.lo, mid, self.kind), Interval(self.var, mid + 1, self.hi, self.kind)

    def formula(self, D):
        """The interval over the bit-precise domain's variable (ints: signed int32 comparisons)."""
        v = D.variables[self.var]
        if self.kind == "f32":
            lo, hi = fp32_val(from_ordinal(self.lo)), fp32_val(from_ordinal(self.hi))
            return z3.And(z3.fpGEQ(v, lo), z3.fpLEQ(v, hi))
        return z3.And(v >= self.lo, v <= self.hi)

    def real_formula(self, D):
        """The interval over the error model's real variable (a float interval by its values)."""
        v = D.variables[self.var]
        if self.kind == "f32":
            lo, hi = (z3.RealVal(Fraction(from_ordinal(k))) for k in (self.lo, self.hi))
        else:
            lo, hi = self.lo, self.hi
        return z3.And(v >= lo, v <= hi)

    def as_json(self) -> dict:
        if self.kind == "f32":
            lo, hi = from_ordinal(self.lo), from_ordinal(self.hi)
            return {"var": self.var, "lo": lo, "hi": hi, "lo_hex": lo.hex(), "hi_hex": hi.hex(), "floats": self.width}
        return {"var": self.var, "lo": self.lo, "hi": self.hi, "ints": self.width}


def f32_interval(var: str, lo: float, hi: float) -> Interval:
    """The float32 values from ``lo`` to ``hi``, both included (``-0.0`` and ``0.0`` are one place)."""
    return Interval(var, ordinal(lo), ordinal(hi))


Box = tuple  # of Interval, at most one per variable


def box_formula(D, box: Box, real: bool = False):
    """The box over ``D``'s variables (``real``: the error model's)."""
    return z3.And(*(iv.real_formula(D) if real else iv.formula(D) for iv in box)) if box else z3.BoolVal(True)


def product(*axes: Iterable[Interval]) -> list[Box]:
    """Every box taking one interval from each axis (sign cases times ranges, and so on)."""
    return [tuple(choice) for choice in itertools.product(*axes)]


def bisect(box: Box, along: tuple[str, ...]) -> Optional[tuple[Box, Box]]:
    """The box cut in two along its widest interval among the variables ``along`` (the first
    of them on a tie); None when each of them is a single value."""
    cands = [(iv.width, -along.index(iv.var), k) for k, iv in enumerate(box) if iv.var in along and iv.width > 1]
    if not cands:
        return None
    _, _, k = max(cands)
    a, b = box[k].halves()
    return box[:k] + (a,) + box[k + 1:], box[:k] + (b,) + box[k + 1:]


# ------------------------------------------------------------------------- declaration

@dataclass
class Split:
    """A declared split of ``obligation`` (its name) in float32: the first boxes, the
    variables refinement may cut, how deep, and what is known of the verdict it reaches
    (the whole obligation's fp32 verdict: :mod:`.knowledge`)."""

    obligation: str
    boxes: list
    bisect: tuple
    expect: str  # known: proved | refuted | unknown (nothing known yet)
    max_depth: int = 12
    part_timeout: float = 60.0
    solvers: tuple = ("bitwuzla",)
    note: str = ""
    methods: tuple = ("smt",)
    timeouts: dict = field(default_factory=dict)  # seconds per method, where not part_timeout
    source: str = ""

    def timeout_of(self, method: str, part_timeout: float) -> float:
        return min(self.timeouts.get(method, part_timeout), part_timeout)

    @property
    def name(self) -> str:
        return f"{self.obligation}/split"


METHODS = ("smt", "errmodel", "enumerate")
ERRMODEL_SEEDS = 4  # random seeds the error model's time is shared among


def split(obligation, boxes, bisect_along, expect: Optional[str] = None, max_depth: int = 12,
          part_timeout: float = 60.0, solvers=("bitwuzla",), note: str = "", methods=("smt",), timeouts=None) -> Split:
    """Declare a split of ``obligation`` (the declared obligation itself) in a proof file.

    What is known of the split's verdict is the obligation's declared fp32 verdict, stated
    once there; ``expect`` states it here instead, for an obligation that declares nothing
    known in fp32 (the two may not disagree).

    ``methods`` are tried on each part in order until one decides it: ``smt``, the
    bit-precise query (:mod:`.checking`) with ``solvers``; ``errmodel``, the standard
    rounding-error model (:mod:`.errmodel`, proofs only) with Z3's nonlinear real arithmetic;
    ``enumerate``, every input of a part with one float variable (:mod:`.enumerate`)."""
    declared = obligation.expect.get("fp32", "unknown")
    if expect is None:
        expect = declared
    if expect not in ("proved", "refuted", "unknown"):
        raise ValueError(f"{obligation.name}: bad expectation {expect}")
    if declared != "unknown" and expect != declared:
        raise ValueError(f"{obligation.name}: the split states {expect}, the obligation {declared} in fp32")
    if not methods or any(m not in METHODS for m in methods):
        raise ValueError(f"{obligation.name}: methods must be among {METHODS}")
    return Split(obligation.name, list(boxes), tuple(bisect_along), expect, max_depth, part_timeout,
                 tuple(solvers), note, tuple(methods), dict(timeouts or {}))


def known_of_files(paths, obligations=None, predicates=()) -> dict:
    """What is known (:func:`navfn_smt.smt.knowledge.knowledge`) of the obligations of the proof
    files ``paths`` (or ``obligations`` already loaded from them): their declarations, the
    splits of those files, the chains of ``predicates`` and the bound cache."""
    from .checking import cached_bound
    from .knowledge import knowledge
    from .obligation import load_obligations

    obs = load_obligations(paths) if obligations is None else obligations
    return knowledge(obs, load_splits(paths), predicates, bound_of=cached_bound)


def load_splits(paths) -> list[Split]:
    """Every :class:`Split` defined at module level in the given proof files."""
    from .obligation import load_proof_module

    found = []
    for p in paths:
        for v in vars(load_proof_module(p)).values():
            if isinstance(v, Split):
                v.source = str(p)
                found.append(v)
    return found


# ------------------------------------------------------------------------------ checking

@dataclass
class Part:
    box: Box
    depth: int
    status: str = "unknown"  # proved | refuted | unknown
    seconds: float = 0.0
    solver: str = ""
    detail: str = ""
    witness: Optional[dict] = None

    def as_json(self) -> dict:
        return {"box": [iv.as_json() for iv in self.box], "depth": self.depth, "status": self.status,
                "seconds": self.seconds, "solver": self.solver, "detail": self.detail, "witness": self.witness}


@dataclass
class SplitOutcome:
    name: str
    obligation: str
    status: str
    known: str  # what was known before the run (knowledge.Known.status)
    parts: list
    cover: dict
    rounds: int
    seconds: float
    engine: str
    note: str = ""
    undecided: list = field(default_factory=list)
    known_source: str = "split"  # where the knowledge comes from (knowledge.Known.source)
    semantics: str = "fp32"  # the float32 semantics the parts were decided in (a build's arithmetic)

    @property
    def judgement(self) -> str:
        """How this run stands to what is known (:func:`~navfn_smt.smt.knowledge.judge`)."""
        from .knowledge import judge

        return judge(self.status, self.known)

    @property
    def fails(self) -> bool:
        """Only a decision against what is known fails a run."""
        from .knowledge import CONTRADICTED

        return self.judgement == CONTRADICTED

    def counts(self) -> dict:
        out = {"proved": 0, "refuted": 0, "unknown": 0}
        for p in self.parts:
            out[p["status"]] += 1
        return out

    def slowest(self) -> Optional[dict]:
        return max(self.parts, key=lambda p: p["seconds"], default=None)


def obligation_named(source: str, name: str, code: Optional[bytes] = None):
    """The obligation ``name`` of proof file ``source``; with ``code`` (the file's contents, sent
    with a task) loaded from those where the file is missing or differs (a remote worker)."""
    from .obligation import load_obligations, load_obligations_from

    found = load_obligations_from(source, code) if code is not None else load_obligations([source])
    return next(o for o in found if o.name == name)


def check_part(job: tuple) -> Part:
    """One part, decided in float32 (a worker's task): ``(source, code, name, part, timeouts,
    solvers, semantics)`` with ``code`` the proof file's contents, ``timeouts`` the seconds of each
    method, tried in turn until one decides the part, and ``semantics`` the float32 semantics
    (``fp32``, or ``fp32@NAME`` in a build's arithmetic)."""
    source, code, name, part, timeouts, solvers, semantics = job
    ob = obligation_named(source, name, code)
    t0 = time.perf_counter()
    out = Part(part.box, part.depth)
    notes = []
    for method, timeout in timeouts:
        status, solver, detail, witness = _METHOD[method](ob, part.box, timeout, solvers, semantics)
        notes.append(f"{method}: {detail or status}")
        if status != "unknown":
            out.status, out.solver, out.witness = status, solver, witness
            break
        out.solver = solver
    out.detail = "; ".join(notes)
    out.seconds = round(time.perf_counter() - t0, 3)
    return out


def _smt(ob, box: Box, timeout: float, solvers, semantics: str = "fp32") -> tuple:
    """The bit-precise query on the part; a model counts only once the concrete spec confirms it."""
    from .checking import judge_model, query, solve_query

    D, assertions = query(ob, semantics, lambda D: box_formula(D, box))
    answer, values, solver, detail = solve_query(tuple(solvers))(assertions, D.variables, timeout)
    if answer == "unsat":
        return "proved", solver, "", None
    if answer == "sat":
        status, witness, detail = judge_model(ob, semantics, values)
        return status, solver, detail, witness
    return "unknown", solver, detail or "unknown", None


def _errmodel(ob, box: Box, timeout: float, solvers, semantics: str = "fp32") -> tuple:
    """The error-model query on the part (:mod:`.errmodel`, in the arithmetic of ``semantics``:
    a fused multiply-add rounds once): proves or leaves unknown, never refutes."""
    from . import errmodel
    from .domains import arithmetic_of

    try:
        D, assertions = errmodel.query(ob, lambda D: box_formula(D, box, real=True), arithmetic_of(semantics))
    except NotImplementedError as e:
        return "unknown", "z3 (error model)", str(e), None
    # nonlinear real arithmetic is sensitive to the order it explores: a query that takes 6 s with
    # one seed can time out with another, so the time is shared among a few seeds, tried in turn
    why = ""
    for seed in range(ERRMODEL_SEEDS):
        s = z3.SolverFor("QF_NRA")
        s.set(timeout=max(1, int(timeout * 1000 / ERRMODEL_SEEDS)), random_seed=seed)
        s.add(*assertions)
        r = s.check()
        if r == z3.unsat:
            return "proved", f"z3 (error model, seed {seed})", "", None
        if r == z3.sat:
            return "unknown", "z3 (error model)", "a choice of rounding errors breaks the claim", None
        why = s.reason_unknown()
    return "unknown", "z3 (error model)", why, None


def _enumerate(ob, box: Box, timeout: float, solvers, semantics: str = "fp32") -> tuple:
    """Every input of the part on the concrete float32 arithmetic of ``semantics`` (:mod:`.enumerate`)."""
    from .enumerate import decide

    status, detail, witness = decide(ob, box, semantics)
    return status, "enumeration", detail, witness


_METHOD = {"smt": _smt, "errmodel": _errmodel, "enumerate": _enumerate}


def check_cover(source: str, name: str, boxes: list, timeout: float, solvers=("z3",), semantics: str = "fp32") -> dict:
    """The cover obligation: ``pre ==> box_1 or ... or box_n`` (``pre`` in ``semantics``);
    ``proved`` when unsatisfiable."""
    from .checking import domain_of, solve_query

    ob = obligation_named(source, name)
    t0 = time.perf_counter()
    D = domain_of(ob, semantics)
    pre, _ = ob.build(D)
    cover = z3.Or(*(box_formula(D, b) for b in boxes))
    answer, values, solver, detail = solve_query(tuple(solvers))([pre, z3.Not(cover)], D.variables, timeout)
    status = {"unsat": "proved", "sat": "refuted"}.get(answer, "unknown")
    out = {"status": status, "parts": len(boxes), "seconds": round(time.perf_counter() - t0, 3), "solver": solver}
    if status == "refuted":
        from .codec import witness_values

        out["uncovered_input"] = witness_values(values)
    return out


def run_split(s: Split, eng, part_timeout: Optional[float] = None, max_depth: Optional[int] = None,
              progress: Optional[Callable[[int, int, Part], None]] = None, stop_at_refutation: bool = True,
              semantics: str = "fp32") -> SplitOutcome:
    """Decide the split's parts round by round on ``eng``, then its cover, in the float32
    ``semantics`` (``fp32``: x86-64's arithmetic; ``fp32@NAME``: a build's, ``split --target``)."""
    from ..engine import session

    timeout = s.part_timeout if part_timeout is None else part_timeout
    depth_limit = s.max_depth if max_depth is None else max_depth
    t0 = time.perf_counter()
    todo = [Part(tuple(b), 0) for b in s.boxes]
    final: list[Part] = []
    rounds, done = 0, 0
    per_method = tuple((m, s.timeout_of(m, timeout)) for m in s.methods)
    code = Path(s.source).read_bytes()  # sent with every part: a remote worker needs no copy of the file
    with session(eng) as run:
        while todo:
            rounds += 1
            jobs = [(s.source, code, s.obligation, p, per_method, s.solvers, semantics) for p in todo]
            total = done + len(jobs)
            nxt: list[Part] = []
            returned: set = set()
            refuted = False
            for i, part in run(check_part, jobs):
                returned.add(i)
                done += 1
                if progress:
                    progress(done, total, part)
                halves = bisect(part.box, s.bisect) if part.status == "unknown" and part.depth < depth_limit else None
                if halves is None:
                    final.append(part)
                else:
                    nxt.extend(Part(h, part.depth + 1) for h in halves)
                if part.status == "refuted" and stop_at_refutation:
                    refuted = True
                    break  # the obligation is refuted: the parts still out are not needed
            if refuted:
                for i, p in enumerate(todo):
                    if i not in returned:
                        final.append(Part(p.box, p.depth, detail="not run: another part refuted the obligation"))
                final.extend(nxt)
                break
            todo = nxt
    final.sort(key=lambda p: tuple((iv.var, iv.lo) for iv in p.box))
    cover = check_cover(s.source, s.obligation, [p.box for p in final], max(timeout, 60.0), semantics=semantics)
    statuses = {p.status for p in final}
    if "refuted" in statuses:
        status = "refuted"
    elif statuses == {"proved"} and cover["status"] == "proved":
        status = "proved"
    else:
        status = "unknown"
    parts = [p.as_json() for p in final]
    known = known_of_files([s.source])[(s.obligation, semantics)]  # the declaration, or a recorded decision
    return SplitOutcome(s.name, s.obligation, status, known.status, parts, cover, rounds,
                        round(time.perf_counter() - t0, 3), eng.describe(), s.note,
                        [p for p in parts if p["status"] == "unknown"] if status != "refuted" else [],
                        known_source=known.source, semantics=semantics)


def outcome_json(o: SplitOutcome) -> dict:
    d = asdict(o)
    d["judgement"] = o.judgement
    d["counts"] = o.counts()
    d["slowest_part"] = o.slowest()
    return d
