"""Solver portfolio for proof obligations: Z3, Bitwuzla and cvc5 on the same query.

An obligation is a Z3 query (a ``z3.Solver`` or a list of Boolean assertions)
whose satisfiability decides it: ``unsat`` proves the obligation, ``sat`` refutes
it with a counterexample, and anything else (unknown, timeout, error) leaves it
undecided -- never proved.

The query is exported once as SMT-LIB2.  Z3 gets its own dialect of it (parsed
back with ``Solver.from_string``, a ``z3.Solver`` cannot be pickled); Bitwuzla
and cvc5 get a standard SMT-LIB2 version with a ``set-logic`` (see
:func:`to_smt2`), in which Z3's non-standard operators are replaced by standard
equivalents.  Each solver runs in its own fresh Python process (``subprocess``:
no re-import of the caller's ``__main__``, no fork of a threaded caller), with
the solver's own time limit and a hard kill shortly after
it; a crash or a hang of one solver never blocks the caller.

:func:`solve` returns the first definitive answer (``confirm=False``) or waits
for every solver and compares (``confirm=True``).  How answers combine is the
pure function :func:`decide`: definitive answers that disagree give status
``"error"`` and ``disagreement=True``, never a silent choice.

Models of ``sat`` answers map the declared constants to Python values:
floating point as ``{"sort": "FP32", "bits": 0x3f800000, "value": 1.0,
"ebits": 8, "sbits": 24}`` (bits exact: NaN, -0.0, subnormals), bit-vectors as
unsigned ints, Bools as bools, Ints as ints, Reals as ``fractions.Fraction``
(irrational algebraic reals as their solver's text), rounding modes as
``"RNE"``/``"RNA"``/``"RTP"``/``"RTN"``/``"RTZ"``, anything else as the
solver's text.  Every model is re-evaluated against the original Z3 assertions
in the calling process; a model Z3 evaluates to false turns that answer into
an ``"error"`` (so it can never win), see ``SolverAnswer.model_checked``.
"""

from __future__ import annotations

import functools
import os
import pickle
import queue
import subprocess
import sys
import threading
import time
from dataclasses import dataclass, field
from typing import Any, Iterable

import z3  # lazily loaded in bitwuzla/cvc5 solver processes, see _WORKER_CODE

from . import codec

__all__ = [
    "SOLVERS",
    "SolverAnswer",
    "PortfolioResult",
    "Query",
    "prepare",
    "to_smt2",
    "solve",
    "decide",
    "check_model",
]

SOLVERS = ("z3", "bitwuzla", "cvc5")

DEFINITIVE = ("sat", "unsat")

# The parent kills a solver process this long after the solver's own time
# limit has passed (the solver normally stops itself first).
KILL_GRACE = 0.5

# cvc5 handles FP formats other than Float32/Float64 (e.g. the Float128 and
# (19, 237) brackets of the hypot models) only with its experimental FP solver
# (option fp-exp, "known issues ... use at your own risk").  Off: cvc5 is
# skipped on such queries.  On: cvc5 runs them with fp-exp.
CVC5_EXPERIMENTAL_FP = False


# --------------------------------------------------------------------------
# Results


@dataclass
class SolverAnswer:
    solver: str  # "z3" | "bitwuzla" | "cvc5"
    status: str  # "sat" | "unsat" | "unknown" | "timeout" | "error"
    seconds: float  # wall time from the start of the portfolio to this answer
    detail: str = ""  # error message / reason unknown / why skipped
    model: dict | None = None  # for sat: {const name: python value}
    # Time the solver itself spent parsing and checking (measured in its
    # process); None when it did not report (killed, crashed, skipped).
    solve_seconds: float | None = None
    # For sat: True when Z3 evaluated the original assertions under the model
    # to true, None when the evaluation was inconclusive (uninterpreted
    # functions, unspecified operations, ...).  False never survives: such an
    # answer is turned into status "error".
    model_checked: bool | None = None

    @property
    def definitive(self) -> bool:
        return self.status in DEFINITIVE


@dataclass
class PortfolioResult:
    status: str  # "sat" | "unsat" | "unknown"; "error" if definitive answers disagree
    solver: str | None  # the solver whose definitive answer won (first to finish)
    seconds: float  # wall time until the decision
    answers: list[SolverAnswer] = field(default_factory=list)
    disagreement: bool = False

    @property
    def winner(self) -> SolverAnswer | None:
        """The winning answer (None when there is none)."""
        for a in self.answers:
            if a.solver == self.solver and a.status == self.status:
                return a
        return None

    @property
    def model(self) -> dict | None:
        """The winning answer's model (sat only)."""
        w = self.winner
        return w.model if w is not None else None

    @property
    def proved(self) -> bool:
        return self.status == "unsat"


def decide(answers: list[SolverAnswer], confirm: bool = False) -> PortfolioResult:
    """Combine solver answers into one result (pure function).

    The definitive (sat/unsat) answer with the smallest ``seconds`` wins (ties:
    list order).  Definitive answers that disagree give status ``"error"``,
    ``solver=None`` and ``disagreement=True``, whatever ``confirm`` is.  No
    definitive answer gives ``"unknown"``.  ``seconds`` is the winner's time
    when ``confirm`` is false, else (and when there is no winner) the time of
    the last answer.
    """
    answers = list(answers)
    definitive = [a for a in answers if a.status in DEFINITIVE]
    last = max((a.seconds for a in answers), default=0.0)
    if len({a.status for a in definitive}) > 1:
        return PortfolioResult("error", None, last, answers, True)
    if not definitive:
        return PortfolioResult("unknown", None, last, answers, False)
    win = min(definitive, key=lambda a: a.seconds)
    seconds = last if confirm else win.seconds
    return PortfolioResult(win.status, win.solver, seconds, answers, False)


# --------------------------------------------------------------------------
# Query analysis and SMT-LIB2 export

_AUX_PREFIX = "navfn_smt!"


@dataclass
class Query:
    """A query prepared for the portfolio: both SMT-LIB2 texts and what a
    solver process needs; ``assertions`` and ``consts`` (z3 objects) stay in
    the calling process for the model check."""

    assertions: list  # original z3 assertions (parent side only)
    z3_text: str  # Z3's own SMT-LIB2 of the original assertions
    smt2: str  # standard SMT-LIB2 (set-logic ... (check-sat)) for bitwuzla/cvc5
    logic: str
    consts: dict[str, Any]  # name -> z3 constant (original query)
    const_sorts: dict[str, str]  # name -> SMT-LIB sort text
    nan_consts: dict[tuple[int, int], str]  # (eb, sb) -> aux NaN-pattern constant
    skip: dict[str, str]  # solver -> why it cannot run this query (skipped)
    cvc5_fp_exp: bool  # cvc5 needs its experimental FP solver (CVC5_EXPERIMENTAL_FP)
    has_uf: bool
    rewritten: list[str]  # Z3 operators replaced in smt2


def _assertions_of(obj) -> list:
    if isinstance(obj, z3.Solver):
        return list(obj.assertions())
    if isinstance(obj, z3.Goal):
        return [obj[i] for i in range(len(obj))]
    if isinstance(obj, str):
        return list(z3.parse_smt2_string(obj))
    if isinstance(obj, z3.BoolRef):
        return [obj]
    if isinstance(obj, z3.AstVector):
        return list(obj)
    if isinstance(obj, Iterable):
        out = list(obj)
        for e in out:
            if not z3.is_bool(e):
                raise TypeError(f"not a Boolean z3 expression: {e!r}")
        return out
    raise TypeError(
        "expected a z3.Solver, z3.Goal, Boolean z3 expression(s) or SMT-LIB2 text, "
        f"got {type(obj).__name__}"
    )


@functools.cache
def _nonstd_ops() -> dict[int, str]:
    return {
        z3.Z3_OP_FPA_TO_IEEE_BV: "fp.to_ieee_bv",
        z3.Z3_OP_EXT_ROTATE_LEFT: "ext_rotate_left",
        z3.Z3_OP_EXT_ROTATE_RIGHT: "ext_rotate_right",
        z3.Z3_OP_BSMUL_NO_OVFL: "bvsmul_noovfl",
        z3.Z3_OP_BUMUL_NO_OVFL: "bvumul_noovfl",
        z3.Z3_OP_BSMUL_NO_UDFL: "bvsmul_noudfl",
    }


@functools.cache
def _arith_div_ops() -> tuple[int, ...]:
    return (z3.Z3_OP_DIV, z3.Z3_OP_IDIV, z3.Z3_OP_MOD, z3.Z3_OP_REM)


def _children(e) -> list:
    if z3.is_quantifier(e):
        return [e.body()]
    if z3.is_app(e):
        return [e.arg(i) for i in range(e.num_args())]
    return []


class _Analysis:
    def __init__(self) -> None:
        self.consts: dict[str, Any] = {}
        self.int = self.real = self.real_literal = self.nonlinear = False
        self.bv = self.fp = self.array = self.uf = self.quant = self.other = False
        self.fp_formats: set[tuple[int, int]] = set()
        self.nonstd: set[str] = set()
        self.nonstd_terms: list = []  # the applications of those operators


def _raw(fn):
    """The bare ctypes function behind a z3core wrapper (no per-call error check)."""
    try:
        return fn.__defaults__[-1].f
    except (AttributeError, IndexError, TypeError):
        return fn


def _analyze(assertions: list) -> _Analysis:
    """Sorts, operators and constants of a query: one pass over the term DAG.

    Walks the raw C API (z3py wrappers cost ~40 us a node; this ~5 us), with
    function declarations and sorts classified once each.
    """
    an = _Analysis()
    if not assertions:
        return an
    ctx = assertions[0].ctx
    c = ctx.ref()
    core = z3.z3core
    ast_id, ast_kind = _raw(core.Z3_get_ast_id), _raw(core.Z3_get_ast_kind)
    to_app, num_args, get_arg = _raw(core.Z3_to_app), _raw(core.Z3_get_app_num_args), \
        _raw(core.Z3_get_app_arg)
    app_decl, decl_id = _raw(core.Z3_get_app_decl), _raw(core.Z3_get_func_decl_id)
    get_sort, sort_id = _raw(core.Z3_get_sort), _raw(core.Z3_get_sort_id)
    sort_kind = _raw(core.Z3_get_sort_kind)
    q_body = _raw(core.Z3_get_quantifier_body)
    APP, NUMERAL, VAR, QUANT = z3.Z3_APP_AST, z3.Z3_NUMERAL_AST, z3.Z3_VAR_AST, \
        z3.Z3_QUANTIFIER_AST
    MUL, POWER, divs, nonstd = z3.Z3_OP_MUL, z3.Z3_OP_POWER, _arith_div_ops(), _nonstd_ops()
    decls: dict[int, int] = {}  # decl id -> its kind (classified on first sight)
    sorts: set[tuple[int, bool]] = set()

    def see_sort(a, numeral: bool) -> None:
        sp = get_sort(c, a)
        key = (sort_id(c, sp), numeral)
        if key not in sorts:
            sorts.add(key)
            _classify_sort(z3.z3._to_sort_ref(sp, ctx), an, numeral)

    seen: set[int] = set()
    stack = [a.as_ast() for a in assertions]
    while stack:
        a = stack.pop()
        i = ast_id(c, a)
        if i in seen:
            continue
        seen.add(i)
        kind = ast_kind(c, a)
        if kind == NUMERAL:
            see_sort(a, True)
            continue
        if kind == VAR:
            see_sort(a, False)
            continue
        if kind == QUANT:
            _classify(z3.QuantifierRef(a, ctx), an)
            stack.append(q_body(c, a))
            continue
        if kind != APP:
            an.other = True
            continue
        app = to_app(c, a)
        d = app_decl(c, app)
        di = decl_id(c, d)
        dk = decls.get(di)
        if dk is None:
            dk = decls[di] = _classify_decl(z3.FuncDeclRef(d, ctx), an)
        n = num_args(c, app)
        if dk == z3.Z3_OP_UNINTERPRETED and n == 0:
            _add_const(z3.z3._to_expr_ref(a, ctx), an)
            continue
        kids = [get_arg(c, app, j) for j in range(n)]
        if dk == MUL or dk in divs:
            if sort_kind(c, get_sort(c, a)) in (z3.Z3_INT_SORT, z3.Z3_REAL_SORT):
                args = kids if dk == MUL else kids[1:]
                if sum(1 for k in args if ast_kind(c, k) != NUMERAL) > (1 if dk == MUL else 0):
                    an.nonlinear = True
        elif dk == POWER:
            an.nonlinear = True
        elif dk in nonstd:
            an.nonstd.add(nonstd[dk])
            an.nonstd_terms.append(z3.z3._to_expr_ref(a, ctx))
        stack.extend(kids)
    return an


def _add_const(e, an: _Analysis) -> None:
    name = e.decl().name()
    old = an.consts.get(name)
    if old is None:
        an.consts[name] = e
    elif not old.eq(e):
        raise ValueError(
            f"two different constants are both named {name!r} "
            f"({old.sort()} and {e.sort()}): the SMT-LIB2 text would be ambiguous"
        )


def _classify_decl(d, an: _Analysis) -> int:
    k = d.kind()
    _classify_sort(d.range(), an, False)
    if k == z3.Z3_OP_UNINTERPRETED and d.arity() > 0:
        an.uf = True
        for i in range(d.arity()):
            _classify_sort(d.domain(i), an, False)
    return k


def _classify_sort(s, an: _Analysis, numeral: bool) -> None:
    k = s.kind()
    if k == z3.Z3_BOOL_SORT:
        return
    if k == z3.Z3_BV_SORT:
        an.bv = True
    elif k == z3.Z3_FLOATING_POINT_SORT:
        an.fp = True
        an.fp_formats.add((s.ebits(), s.sbits()))
    elif k == z3.Z3_ROUNDING_MODE_SORT:
        an.fp = True
    elif k == z3.Z3_INT_SORT:
        if not numeral:
            an.int = True
    elif k == z3.Z3_REAL_SORT:
        if numeral:
            an.real_literal = True
        else:
            an.real = True
    elif k == z3.Z3_ARRAY_SORT:
        an.array = True
        _classify_sort(s.domain(), an, False)
        _classify_sort(s.range(), an, False)
    elif k == z3.Z3_UNINTERPRETED_SORT:
        an.uf = True
    else:  # datatypes, sequences, strings, finite domains, ...
        an.other = True


def _classify(q, an: _Analysis) -> None:
    """A quantifier node (its body is walked separately)."""
    an.quant = True
    if q.is_lambda():
        an.other = True
    for i in range(q.num_vars()):
        _classify_sort(q.var_sort(i), an, False)


def _logic_name(an: _Analysis) -> str:
    if an.other:
        return "ALL"
    arith = ""
    if an.int or an.real or an.real_literal:
        kind = "N" if an.nonlinear else "L"
        if an.int and (an.real or an.real_literal):
            arith = kind + "IRA"
        elif an.int:
            arith = kind + "IA"
        else:
            arith = kind + "RA"
    body = ("A" if an.array else "") + ("UF" if an.uf else "") + ("BV" if an.bv else "")
    body += ("FP" if an.fp else "") + arith
    if not body:
        body = "UF"  # pure propositional
    return body if an.quant else "QF_" + body


# Floating-point formats each solver supports without experimental options.
_FP_FORMATS = {
    "bitwuzla": {(5, 11), (8, 24), (11, 53), (15, 113)},
    "cvc5": {(8, 24), (11, 53)},
}


def _skip_reasons(an: _Analysis) -> dict[str, str]:
    skip = {}
    if an.int or an.real:
        skip["bitwuzla"] = "bitwuzla has no Int/Real arithmetic"
    elif an.other:
        skip["bitwuzla"] = "bitwuzla supports only Bool/BV/FP/RoundingMode/arrays/uninterpreted sorts"
    for solver, formats in _FP_FORMATS.items():
        odd = sorted(an.fp_formats - formats)
        if solver == "cvc5" and CVC5_EXPERIMENTAL_FP:
            continue
        if odd and solver not in skip:
            skip[solver] = f"{solver} does not support FP formats {odd} (only {sorted(formats)})"
    return skip


def _fp_sort_key(s) -> tuple[int, int]:
    return (s.ebits(), s.sbits())


def _has_var(e) -> bool:
    """Whether ``e`` contains a bound variable (de Bruijn index)."""
    seen: set[int] = set()
    stack = [e]
    while stack:
        t = stack.pop()
        if z3.is_var(t):
            return True
        if t.get_id() in seen:
            continue
        seen.add(t.get_id())
        stack.extend(_children(t))
    return False


def _replacement(t, ctx, side: list, nan_const, fresh, quantified: bool):
    """A standard SMT-LIB term for the non-standard application ``t`` (None: keep)."""
    k = t.decl().kind()
    if k == z3.Z3_OP_FPA_TO_IEEE_BV:
        x = t.arg(0)
        if quantified and _has_var(x):
            return None  # cannot name it outside its quantifier
        eb, sb = _fp_sort_key(x.sort())
        bits = fresh(eb + sb)
        side.append(z3.fpBVToFP(bits, x.sort(), ctx) == x)
        side.append(z3.Implies(z3.fpIsNaN(x, ctx), bits == nan_const(eb, sb), ctx))
        return bits
    a, b = t.arg(0), t.arg(1)
    w = a.size()
    if k in (z3.Z3_OP_EXT_ROTATE_LEFT, z3.Z3_OP_EXT_ROTATE_RIGHT):
        left = k == z3.Z3_OP_EXT_ROTATE_LEFT
        if z3.is_bv_value(b):
            mk = z3.Z3_mk_rotate_left if left else z3.Z3_mk_rotate_right
            return z3.BitVecRef(mk(ctx.ref(), b.as_long() % w, a.as_ast()), ctx)
        n = z3.URem(b, z3.BitVecVal(w, w, ctx))
        m = z3.BitVecVal(w, w, ctx) - n  # shifts by >= w give 0
        return (a << n) | z3.LShR(a, m) if left else z3.LShR(a, n) | (a << m)
    if k in (z3.Z3_OP_BSMUL_NO_OVFL, z3.Z3_OP_BSMUL_NO_UDFL):
        p = z3.SignExt(w, a) * z3.SignExt(w, b)
        if k == z3.Z3_OP_BSMUL_NO_OVFL:
            return p <= z3.BitVecVal((1 << (w - 1)) - 1, 2 * w, ctx)
        return p >= z3.BitVecVal(-(1 << (w - 1)), 2 * w, ctx)
    if k == z3.Z3_OP_BUMUL_NO_OVFL:
        p = z3.ZeroExt(w, a) * z3.ZeroExt(w, b)
        return z3.Extract(2 * w - 1, w, p) == z3.BitVecVal(0, w, ctx)
    return None


def _rewrite(assertions: list, an: _Analysis):
    """Replace Z3's non-standard operators by standard SMT-LIB ones.

    ``fp.to_ieee_bv t`` becomes a fresh bit-vector ``k`` with ``(to_fp k) = t``
    (structural equality: for a NaN ``t`` any NaN pattern), and, to keep it a
    function as in Z3, ``k`` equals one per-format NaN pattern constant whenever
    ``t`` is NaN (Z3 maps every NaN to one unspecified NaN pattern).  Rounds of
    simultaneous substitution, until no replaceable operator is left (nested
    ones surface in the next round).
    """
    ctx = assertions[0].ctx
    nan_consts: dict[tuple[int, int], Any] = {}
    counter = [0]
    side: list = []

    def nan_const(eb: int, sb: int):
        if (eb, sb) not in nan_consts:
            c = z3.BitVec(f"{_AUX_PREFIX}nan!{eb}!{sb}", eb + sb, ctx)
            nan_consts[(eb, sb)] = c
            side.append(z3.fpIsNaN(z3.fpBVToFP(c, z3.FPSort(eb, sb, ctx), ctx), ctx))
        return nan_consts[(eb, sb)]

    def fresh(width: int):
        counter[0] += 1
        return z3.BitVec(f"{_AUX_PREFIX}ieee!{counter[0]}", width, ctx)

    current = list(assertions)
    kept: set[int] = set()
    while True:
        pairs = []
        for t in an.nonstd_terms:
            if t.get_id() in kept:
                continue
            r = _replacement(t, ctx, side, nan_const, fresh, an.quant)
            if r is None:
                kept.add(t.get_id())
            else:
                pairs.append((t, r))
        if not pairs and not side:
            break
        if pairs:
            current = [z3.substitute(a, *pairs) for a in current]
        current += side
        side = []
        an = _analyze(current)
    return current, {key: c.decl().name() for key, c in nan_consts.items()}


def _benchmark(assertions: list, logic: str, ctx) -> str:
    if not assertions:
        assertions = [z3.BoolVal(True, ctx)]
    n = len(assertions) - 1
    v = (z3.Ast * n)()
    for i in range(n):
        v[i] = assertions[i].as_ast()
    return z3.Z3_benchmark_to_smtlib_string(
        ctx.ref(), "navfn_smt portfolio query", logic, "unknown", "", n, v,
        assertions[-1].as_ast(),
    )


def prepare(solver_or_assertions, logic: str | None = None) -> Query:
    """Analyse a query and export it (see :func:`to_smt2`)."""
    assertions = _assertions_of(solver_or_assertions)
    ctx = assertions[0].ctx if assertions else z3.main_ctx()
    an = _analyze(assertions)
    chosen = logic or _logic_name(an)
    z3_text = _benchmark(assertions, "", ctx)
    std = assertions
    nan_names: dict[tuple[int, int], str] = {}
    if an.nonstd:
        std, nan_names = _rewrite(assertions, an)
    smt2 = _benchmark(std, chosen, ctx)
    return Query(
        assertions=assertions,
        z3_text=z3_text,
        smt2=smt2,
        logic=chosen,
        consts=an.consts,
        const_sorts={n: c.sort().sexpr() for n, c in an.consts.items()},
        nan_consts=nan_names,
        skip=_skip_reasons(an),
        cvc5_fp_exp=bool(an.fp_formats - _FP_FORMATS["cvc5"]),
        has_uf=an.uf,
        rewritten=sorted(an.nonstd),
    )


def to_smt2(solver_or_assertions, logic: str | None = None) -> str:
    """Standard SMT-LIB2 text of the query, ending with ``(check-sat)``.

    ``solver_or_assertions``: a ``z3.Solver``, a ``z3.Goal``, a Boolean z3
    expression, an iterable of them, or SMT-LIB2 text (parsed with Z3).
    The ``set-logic`` is chosen from the sorts and operators used when
    ``logic`` is None (``QF_FP``, ``QF_BVFP``, ``QF_UFBV``, ``QF_FPLRA``,
    ``QF_NIA``, ...; ``ALL`` for datatypes, strings, lambdas ...).  Z3's
    non-standard ``fp.to_ieee_bv``, ``ext_rotate_left/right`` and
    ``bvsmul_noovfl``/``bvsmul_noudfl``/``bvumul_noovfl`` are replaced by
    standard equivalents (fresh ``navfn_smt!...`` constants and side
    assertions for ``fp.to_ieee_bv``).
    """
    return prepare(solver_or_assertions, logic).smt2


# --------------------------------------------------------------------------
# Model check


def check_model(query: Query, model: dict) -> bool | None:
    """Evaluate the original assertions under ``model`` with Z3.

    True: all evaluate to true; False: one evaluates to false; None: cannot
    tell (missing or non-scalar values, uninterpreted functions, unspecified
    operations left unsimplified).
    """
    pairs = []
    for name, c in query.consts.items():
        if name not in model:
            return None
        v = codec.entry_to_z3(model[name], c)
        if v is None:
            return None
        pairs.append((c, v))
    verdict: bool | None = True
    for a in query.assertions:
        r = z3.simplify(z3.substitute(a, *pairs) if pairs else a)
        if z3.is_false(r):
            return False
        if not z3.is_true(r):
            verdict = None
    return verdict


# --------------------------------------------------------------------------
# Solver runners (executed in the child processes)


_Z3_LOGICS = frozenset({
    "QF_FP", "QF_BVFP", "QF_FPLRA", "QF_BV", "QF_UFBV", "QF_ABV", "QF_AUFBV",
    "QF_LIA", "QF_LRA", "QF_NIA", "QF_NRA", "QF_UFLIA", "QF_UF",
})


def _run_z3(text: str, timeout: float, names: dict[str, str], logic: str) -> dict:
    t0 = time.monotonic()
    # Z3's logic-specific solvers are much faster on FP than its default
    # (e.g. 0.07 s vs 1.3 s on (x + y) - y != x).
    s = z3.SolverFor(logic) if logic in _Z3_LOGICS else z3.Solver()
    s.set("timeout", max(1, int(timeout * 1000)))
    s.from_string(text)
    r = s.check()
    dt = time.monotonic() - t0
    if r == z3.sat:
        m = s.model()
        model = {}
        if names:
            # The constants themselves, rebuilt from their declarations.
            decls = "".join(
                f"(declare-fun {_smt_quote(n)} () {srt})" for n, srt in names.items()
            )
            eqs = "".join(f"(assert (= {_smt_quote(n)} {_smt_quote(n)}))" for n in names)
            model = codec.z3_model(m, [eq.arg(0) for eq in z3.parse_smt2_string(decls + eqs)])
        return {"status": "sat", "model": model, "solve_seconds": dt}
    if r == z3.unsat:
        return {"status": "unsat", "solve_seconds": dt}
    reason = s.reason_unknown()
    timed_out = "timeout" in reason or "canceled" in reason or dt >= 0.95 * timeout
    return {"status": "timeout" if timed_out else "unknown", "detail": reason,
            "solve_seconds": dt}


def _smt_quote(name: str) -> str:
    """SMT-LIB symbol for ``name``: always quoted (``|x|`` is the symbol ``x``)."""
    if "|" in name or "\\" in name:
        raise ValueError(f"constant name {name!r} cannot be written in SMT-LIB2")
    return f"|{name}|"


def _strip_bars(name: str) -> str:
    if len(name) >= 2 and name[0] == "|" and name[-1] == "|":
        return name[1:-1]
    return name


def _run_bitwuzla(text: str, timeout: float, names: dict[str, str], logic: str) -> dict:
    import bitwuzla as bw

    t0 = time.monotonic()
    opts = bw.Options()
    opts.set(bw.Option.PRODUCE_MODELS, True)
    opts.set(bw.Option.TIME_LIMIT_PER, max(1, int(timeout * 1000)))
    tm = bw.TermManager()
    parser = bw.Parser(tm, opts)
    parser.parse(text, True, False)  # parse only: assert, do not run check-sat
    solver = parser.bitwuzla()
    r = solver.check_sat()
    dt = time.monotonic() - t0
    if r == bw.Result.SAT:
        model = {}
        for f in parser.get_declared_funs():
            name = _strip_bars(f.symbol() or "")
            if name not in names:
                continue
            srt = f.sort()
            if srt.is_fun():
                continue
            model[name] = codec.bitwuzla_entry(solver.get_value(f), srt)
        return {"status": "sat", "model": model, "solve_seconds": dt}
    if r == bw.Result.UNSAT:
        return {"status": "unsat", "solve_seconds": dt}
    timed_out = dt >= 0.95 * timeout
    return {"status": "timeout" if timed_out else "unknown",
            "detail": "time limit" if timed_out else "bitwuzla: unknown", "solve_seconds": dt}


def _run_cvc5(text: str, timeout: float, names: dict[str, str], logic: str,
              fp_exp: bool = False) -> dict:
    import cvc5

    t0 = time.monotonic()
    tm = cvc5.TermManager()
    solver = cvc5.Solver(tm)
    solver.setOption("produce-models", "true")
    solver.setOption("tlimit-per", str(max(1, int(timeout * 1000))))
    if fp_exp:
        solver.setOption("fp-exp", "true")
    sm = cvc5.SymbolManager(tm)
    parser = cvc5.InputParser(solver, sm)
    parser.setStringInput(cvc5.InputLanguage.SMT_LIB_2_6, text, "query")
    while True:
        cmd = parser.nextCommand()
        if cmd.isNull():
            break
        if cmd.getCommandName() in ("check-sat", "exit"):
            continue
        cmd.invoke(solver, sm)
    r = solver.checkSat()
    dt = time.monotonic() - t0
    if r.isSat():
        model = {}
        for t in sm.getDeclaredTerms():
            name = _strip_bars(t.getSymbol())
            if name not in names:
                continue
            srt = t.getSort()
            if srt.isFunction():
                continue
            model[name] = codec.cvc5_entry(solver.getValue(t), srt)
        return {"status": "sat", "model": model, "solve_seconds": dt}
    if r.isUnsat():
        return {"status": "unsat", "solve_seconds": dt}
    why = r.getUnknownExplanation()
    timed_out = why in (cvc5.UnknownExplanation.TIMEOUT, cvc5.UnknownExplanation.RESOURCEOUT)
    return {"status": "timeout" if timed_out else "unknown", "detail": str(why),
            "solve_seconds": dt}


def _run_selftest_crash(text: str, timeout: float, names: dict, logic: str) -> dict:
    os.abort()  # test double: a solver process that dies without answering


def _run_selftest_hang(text: str, timeout: float, names: dict, logic: str) -> dict:
    time.sleep(3600)  # test double: a solver that ignores its time limit
    return {"status": "unknown"}


_RUNNERS = {
    "z3": _run_z3,
    "bitwuzla": _run_bitwuzla,
    "cvc5": _run_cvc5,
    # Test doubles, reachable only through _solve (solve() rejects them).
    "_selftest_crash": _run_selftest_crash,
    "_selftest_hang": _run_selftest_hang,
}


def _worker_main() -> None:
    """Entry point of a solver process: request on stdin, answer on stdout (pickles)."""
    import signal

    req = pickle.load(sys.stdin.buffer)
    try:  # Linux: die with the caller
        import ctypes

        ctypes.CDLL(None, use_errno=True).prctl(1, signal.SIGKILL)  # PR_SET_PDEATHSIG
        if os.getppid() != req["parent"]:
            os._exit(3)
    except Exception:
        pass
    if hasattr(signal, "setitimer"):  # last resort if the caller is gone: SIGALRM kills
        signal.setitimer(signal.ITIMER_REAL, req["timeout"] + KILL_GRACE + 5.0)
    out = os.fdopen(os.dup(1), "wb")
    devnull = os.open(os.devnull, os.O_WRONLY)
    os.dup2(devnull, 1)  # keep solver chatter out of the answer channel
    os.close(devnull)
    try:
        ans = _RUNNERS[req["solver"]](req["text"], req["timeout"], req["names"], req["logic"],
                                      **req.get("options", {}))
    except BaseException as exc:  # report, never hang the caller
        ans = {"status": "error", "detail": f"{type(exc).__name__}: {exc}".strip()}
    try:
        data = pickle.dumps(ans)
    except Exception as exc:
        data = pickle.dumps({"status": "error", "detail": f"unpicklable answer: {exc}"})
    out.write(data)
    out.flush()
    os._exit(0)  # skip solver teardown (can be slow on large states)


# Solver process bootstrap.  Processes for bitwuzla and cvc5 never touch Z3; its
# import (~0.1 s of CPU for libz3) is skipped there with an empty stand-in
# module (nothing at this module's top level uses z3's attributes).
_WORKER_CODE = """\
import sys
stub = None
if sys.argv[1] != "z3":
    import types
    stub = sys.modules["z3"] = types.ModuleType("z3", "stand-in: not loaded here")
try:
    from navfn_smt.smt.portfolio import _worker_main
except Exception:  # something on the import path needs the real z3
    if stub is None:
        raise
    for mod in [m for m in sys.modules if m == "z3" or m.startswith("navfn_smt")]:
        del sys.modules[mod]
    from navfn_smt.smt.portfolio import _worker_main
_worker_main()
"""


def _worker_command(solver: str) -> tuple[list[str], dict[str, str]]:
    env = dict(os.environ)
    # the directory holding the navfn_smt package, first on the path
    root = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    env["PYTHONPATH"] = root + (os.pathsep + env["PYTHONPATH"] if env.get("PYTHONPATH") else "")
    return [sys.executable, "-c", _WORKER_CODE, solver], env


def _communicate(name: str, proc, payload: bytes, q: "queue.Queue") -> None:
    try:
        out, err = proc.communicate(payload)
    except Exception as exc:
        out, err = b"", f"{type(exc).__name__}: {exc}".encode()
    q.put((name, time.monotonic(), out, err, proc.returncode))


def _check_solvers(solvers) -> tuple[str, ...]:
    if isinstance(solvers, str):
        solvers = (solvers,)
    names = tuple(dict.fromkeys(solvers))
    unknown = [s for s in names if s not in SOLVERS]
    if unknown:
        raise ValueError(f"unknown solver(s) {unknown}; known: {list(SOLVERS)}")
    if not names:
        raise ValueError("no solver given")
    return names


def _finish_sat(query: Query, ans: SolverAnswer) -> SolverAnswer:
    model = codec.pin_nan_patterns(ans.model or {}, query.nan_consts)
    model = {n: v for n, v in model.items() if n in query.consts}
    ans.model = model
    try:
        ok = check_model(query, model)
    except Exception as exc:  # evaluation problems never decide anything
        ok = None
        ans.detail = (ans.detail + "; " if ans.detail else "") + f"model check failed: {exc}"
    ans.model_checked = ok
    if ok is False:
        ans.status = "error"
        ans.detail = (ans.detail + "; " if ans.detail else "") + \
            "model does not satisfy the query when evaluated by z3"
    return ans


def solve(solver_or_assertions, timeout: float = 30.0, solvers=SOLVERS,
          confirm: bool = False) -> PortfolioResult:
    """Run the solvers concurrently on the query; see :func:`decide`.

    ``confirm=False``: return at the first definitive answer and kill the
    others (``answers`` holds only answers actually received).  ``confirm=True``:
    wait for every solver up to ``timeout`` and compare.  Solvers still running
    at ``timeout`` (+ ``KILL_GRACE``) are killed and answer ``"timeout"``;
    a solver process that dies answers ``"error"``.  A solver that cannot take
    the query is skipped with an ``"unknown"`` answer whose detail says why:
    Bitwuzla on Int/Real (and datatype, string ...) queries, Bitwuzla on FP
    formats other than Float16/32/64/128, cvc5 on formats other than
    Float32/64.  ``solver_or_assertions`` may also be a :class:`Query` from
    :func:`prepare` (to export once and solve several times).

    Each ``SolverAnswer.seconds`` counts from the call (so it includes the
    export and the solver process start-up, ~0.05-0.15 s); ``solve_seconds``
    is the solver's own parse-and-check time.
    """
    t0 = time.monotonic()
    names = _check_solvers(solvers)
    if not timeout > 0:
        raise ValueError("timeout must be positive")
    query = solver_or_assertions if isinstance(solver_or_assertions, Query) \
        else prepare(solver_or_assertions)
    return _solve(query, names, timeout, confirm, t0)


def _solve(query: Query, names: tuple[str, ...], timeout: float, confirm: bool,
           t0: float | None = None) -> PortfolioResult:
    if t0 is None:
        t0 = time.monotonic()
    answers: list[SolverAnswer] = []
    running: dict[str, Any] = {}  # name -> subprocess.Popen
    threads: list[threading.Thread] = []
    q: queue.Queue = queue.Queue()
    std_names = dict(query.const_sorts)
    std_names.update({aux: "" for aux in query.nan_consts.values()})
    try:
        for name in names:
            if name in query.skip:
                answers.append(SolverAnswer(name, "unknown", time.monotonic() - t0,
                                            detail="skipped: " + query.skip[name]))
                continue
            payload = pickle.dumps({
                "solver": name,
                "text": query.z3_text if name == "z3" else query.smt2,
                "timeout": timeout,
                "names": query.const_sorts if name == "z3" else std_names,
                "logic": query.logic,
                "parent": os.getpid(),
                "options": {"fp_exp": True} if name == "cvc5" and query.cvc5_fp_exp else {},
            })
            cmd, env = _worker_command(name)
            try:
                proc = subprocess.Popen(cmd, env=env, stdin=subprocess.PIPE,
                                        stdout=subprocess.PIPE, stderr=subprocess.PIPE)
            except Exception as exc:
                answers.append(SolverAnswer(name, "error", time.monotonic() - t0,
                                            detail=f"could not start: {exc}"))
                continue
            running[name] = proc
            th = threading.Thread(target=_communicate, args=(name, proc, payload, q),
                                  name=f"portfolio-{name}", daemon=True)
            th.start()
            threads.append(th)

        deadline = t0 + timeout + KILL_GRACE
        while running:
            left = deadline - time.monotonic()
            if left <= 0:
                break
            try:
                name, when, out, err, code = q.get(timeout=left)
            except queue.Empty:
                break
            running.pop(name, None)
            now = when - t0
            try:
                msg = pickle.loads(out) if out else None
            except Exception:
                msg = None
            if not isinstance(msg, dict):
                tail = err.decode(errors="replace").strip().splitlines()[-3:]
                ans = SolverAnswer(name, "error", now,
                                   detail=f"solver process died (exit code {code})"
                                   + (": " + " | ".join(tail) if tail else ""))
            else:
                ans = SolverAnswer(name, str(msg.get("status", "error")), now,
                                   detail=str(msg.get("detail", "")), model=msg.get("model"),
                                   solve_seconds=msg.get("solve_seconds"))
                if ans.status == "sat":
                    ans = _finish_sat(query, ans)
            answers.append(ans)
            if not confirm and any(a.status in DEFINITIVE for a in answers):
                break
        if running and (confirm or not any(a.status in DEFINITIVE for a in answers)):
            now = time.monotonic() - t0
            for name in running:
                answers.append(SolverAnswer(name, "timeout", now,
                                            detail=f"killed after {timeout:g} s"))
    finally:
        for proc in running.values():
            try:
                proc.kill()
            except Exception:
                pass
        for th in threads:  # communicate() returns once its process is gone
            th.join(5.0)
    return decide(answers, confirm)
