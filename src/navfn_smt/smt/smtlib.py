"""SMT-LIB analysis and rewriting: a Z3 query as the texts the solvers read.

:func:`prepare` analyses a query (a ``z3.Solver``, a ``z3.Goal``, Boolean Z3 terms or
SMT-LIB2 text) in one pass over its term DAG -- its constants, sorts, operators and the
logic they make -- and exports it twice: in Z3's own dialect (for Z3, which reads it back
with ``Solver.from_string``; a ``z3.Solver`` cannot be pickled) and as standard SMT-LIB2
with a ``set-logic`` for Bitwuzla and cvc5, in which Z3's non-standard operators are
replaced by standard equivalents (:func:`to_smt2`).  It also says which solver cannot
take the query and why (Int/Real for Bitwuzla, FP formats a solver lacks).
"""

from __future__ import annotations

import functools
from dataclasses import dataclass
from typing import Any, Iterable

import z3

from . import solvers

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
    cvc5_fp_exp: bool  # cvc5 needs its experimental FP solver (solvers.CVC5_EXPERIMENTAL_FP)
    has_uf: bool
    rewritten: list[str]  # Z3 operators replaced in smt2


def _assertions_of(obj) -> list:
    """The Boolean assertions of a query given in any of the accepted forms."""
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
    """Z3's operators that standard SMT-LIB lacks (operator kind -> name)."""
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
    """Arithmetic division operators (nonlinear unless the divisor is a numeral)."""
    return (z3.Z3_OP_DIV, z3.Z3_OP_IDIV, z3.Z3_OP_MOD, z3.Z3_OP_REM)


def _children(e) -> list:
    """The direct subterms of ``e`` (a quantifier's body)."""
    if z3.is_quantifier(e):
        return [e.body()]
    if z3.is_app(e):
        return [e.arg(i) for i in range(e.num_args())]
    return []


class _Analysis:
    """What a query uses: constants, sorts, operators, FP formats."""

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
    """Record an uninterpreted constant; two different ones with one name are an error."""
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
    """Record what a function declaration uses; its kind."""
    k = d.kind()
    _classify_sort(d.range(), an, False)
    if k == z3.Z3_OP_UNINTERPRETED and d.arity() > 0:
        an.uf = True
        for i in range(d.arity()):
            _classify_sort(d.domain(i), an, False)
    return k


def _classify_sort(s, an: _Analysis, numeral: bool) -> None:
    """Record what a sort adds to the logic (a numeral's Int/Real sort: only a literal)."""
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
    """The SMT-LIB logic of the analysed query (``ALL`` beyond the standard logics)."""
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


def _skip_reasons(an: _Analysis) -> dict[str, str]:
    """Why a solver cannot take the query (solver -> reason), for those that cannot."""
    skip = {}
    if an.int or an.real:
        skip["bitwuzla"] = "bitwuzla has no Int/Real arithmetic"
    elif an.other:
        skip["bitwuzla"] = "bitwuzla supports only Bool/BV/FP/RoundingMode/arrays/uninterpreted sorts"
    for solver, formats in solvers.FP_FORMATS.items():
        odd = sorted(an.fp_formats - formats)
        if solver == "cvc5" and solvers.CVC5_EXPERIMENTAL_FP:
            continue
        if odd and solver not in skip:
            skip[solver] = f"{solver} does not support FP formats {odd} (only {sorted(formats)})"
    return skip


def _fp_sort_key(s) -> tuple[int, int]:
    """A floating-point sort's format (eb, sb)."""
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
    """Z3's SMT-LIB2 text of the assertions with the given ``set-logic`` (none for empty)."""
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
        cvc5_fp_exp=bool(an.fp_formats - solvers.FP_FORMATS["cvc5"]),
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
