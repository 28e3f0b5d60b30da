"""Solver adapters: one SMT-LIB query run in Z3, Bitwuzla or cvc5, answered as a plain dict.

:data:`SOLVERS` is the table of solvers (the command line's ``--solver`` choices) and
:data:`RUNNERS` their adapters.  An adapter ``run(text, timeout, names, logic, **options)``
parses the query text, checks it under the solver's own time limit and answers
``{"status": "sat" | "unsat" | "unknown" | "timeout", "model": {name: entry},
"detail": str, "solve_seconds": float}``, the model giving the constants of ``names`` as
:mod:`navfn_smt.smt.codec` entries.  Adapters run in worker processes
(:mod:`navfn_smt.smt.worker`); each imports its solver library and the codec only when it
runs, so this module is cheap to import.
"""

from __future__ import annotations

import os
import time

SOLVERS = ("z3", "bitwuzla", "cvc5")

# Floating-point formats each solver supports without experimental options.
FP_FORMATS = {
    "bitwuzla": {(5, 11), (8, 24), (11, 53), (15, 113)},
    "cvc5": {(8, 24), (11, 53)},
}

# cvc5 handles FP formats other than Float32/Float64 (e.g. the Float128 and
# (19, 237) brackets of the hypot models) only with its experimental FP solver
# (option fp-exp, "known issues ... use at your own risk").  Off: cvc5 is
# skipped on such queries.  On: cvc5 runs them with fp-exp.
CVC5_EXPERIMENTAL_FP = False


def check_names(solvers) -> tuple[str, ...]:
    """The solvers named (one name or several, duplicates dropped), all of them known."""
    if isinstance(solvers, str):
        solvers = (solvers,)
    names = tuple(dict.fromkeys(solvers))
    unknown = [s for s in names if s not in SOLVERS]
    if unknown:
        raise ValueError(f"unknown solver(s) {unknown}; known: {list(SOLVERS)}")
    if not names:
        raise ValueError("no solver given")
    return names


_Z3_LOGICS = frozenset({
    "QF_FP", "QF_BVFP", "QF_FPLRA", "QF_BV", "QF_UFBV", "QF_ABV", "QF_AUFBV",
    "QF_LIA", "QF_LRA", "QF_NIA", "QF_NRA", "QF_UFLIA", "QF_UF",
})


def run_z3(text: str, timeout: float, names: dict[str, str], logic: str) -> dict:
    """Z3 on its own dialect of the query (with its logic-specific solver where it has one)."""
    import z3

    from . import codec

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


def strip_bars(name: str) -> str:
    """A symbol's name without its SMT-LIB quoting bars."""
    if len(name) >= 2 and name[0] == "|" and name[-1] == "|":
        return name[1:-1]
    return name


def run_bitwuzla(text: str, timeout: float, names: dict[str, str], logic: str) -> dict:
    """Bitwuzla on the standard SMT-LIB2 query."""
    import bitwuzla as bw

    from . import codec

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
            name = strip_bars(f.symbol() or "")
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


def run_cvc5(text: str, timeout: float, names: dict[str, str], logic: str,
             fp_exp: bool = False) -> dict:
    """cvc5 on the standard SMT-LIB2 query (``fp_exp``: with its experimental FP solver)."""
    import cvc5

    from . import codec

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
            name = strip_bars(t.getSymbol())
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


RUNNERS = {
    "z3": run_z3,
    "bitwuzla": run_bitwuzla,
    "cvc5": run_cvc5,
    # Test doubles, reachable only through portfolio._solve (check_names rejects them).
    "_selftest_crash": _run_selftest_crash,
    "_selftest_hang": _run_selftest_hang,
}
