"""Solver portfolio (navfn_smt.smt.portfolio, with its SMT-LIB export, solver adapters and worker
processes): Z3, Bitwuzla and cvc5 on one query."""

from __future__ import annotations

import glob
import os
import time
from fractions import Fraction

import numpy as np
import pytest

z3 = pytest.importorskip("z3")
bitwuzla = pytest.importorskip("bitwuzla")
cvc5 = pytest.importorskip("cvc5")

from navfn_smt.smt import codec, smtlib, solvers, worker  # noqa: E402
from navfn_smt.smt import portfolio as P  # noqa: E402
from navfn_smt.smt.portfolio import PortfolioResult, SolverAnswer, decide  # noqa: E402

F32 = z3.Float32()
RNE = z3.RNE()


def f32(bits: int) -> np.float32:
    return np.array([bits], dtype=np.uint32).view(np.float32)[0]


def bits_of(v: np.float32) -> int:
    return int(np.array([v], dtype=np.float32).view(np.uint32)[0])


def finite(v):
    return z3.And(z3.Not(z3.fpIsInf(v)), z3.Not(z3.fpIsNaN(v)))


def fp_bits(entry: dict) -> int:
    assert entry["sort"] == "FP32" and (entry["ebits"], entry["sbits"]) == (8, 24)
    return entry["bits"]


def sat_answers(res: PortfolioResult) -> list[SolverAnswer]:
    return [a for a in res.answers if a.status == "sat"]


def no_children_left() -> bool:
    """No child process (running or zombie) of this test process remains, but multiprocessing's
    resource tracker (one per process, started by the local Dask clusters of other tests)."""
    files = glob.glob(f"/proc/{os.getpid()}/task/*/children")
    if not files:  # not Linux: nothing to look at
        return True
    kids = []
    for f in files:
        try:
            kids += open(f).read().split()
        except FileNotFoundError:  # the thread ended between the listing and the read
            pass
    from multiprocessing import resource_tracker

    tracker = getattr(resource_tracker._resource_tracker, "_pid", None)
    return not [k for k in kids if int(k) != tracker]


X = z3.FP("x", F32)
Y = z3.FP("y", F32)
ONE = z3.FPVal(1.0, F32)

# x + 1.0f == x for a finite x: sat (any |x| >= 2^24).
Q_ABSORB = [finite(X), z3.fpAdd(RNE, X, ONE) == X]
# (x + y) - y == x for all finite x, y?  sat: a counterexample.
Q_CANCEL = [finite(X), finite(Y), z3.Not(z3.fpEQ(z3.fpSub(RNE, z3.fpAdd(RNE, X, Y), Y), X))]
# x * 1.0 == x (bit-exact) for every non-NaN x: unsat.
Q_MUL_ONE = [z3.Not(z3.fpIsNaN(X)), z3.Not(z3.fpMul(RNE, X, ONE) == X)]
B = z3.BitVec("b", 8)
Q_BV = [B * 3 == 7]  # unique solution b = 173 (3 * 173 = 519 = 2 * 256 + 7)
R = z3.Real("r")
Q_REAL = [R * 3 == 1, R > 0]
# 32 x 32 bit factoring of the largest prime below 2^63: unsat, hard for every solver.
BX, BY = z3.BitVec("p", 32), z3.BitVec("q", 32)
Q_HARD = [z3.ZeroExt(32, BX) * z3.ZeroExt(32, BY) == 9223372036854775783,
          z3.UGT(BX, 1), z3.UGT(BY, 1)]


# --------------------------------------------------------------------------
# decide(): the pure combination of answers


def test_decide_disagreement_is_an_error():
    answers = [SolverAnswer("bitwuzla", "sat", 0.1, model={}),
               SolverAnswer("cvc5", "unsat", 0.2)]
    for confirm in (False, True):
        res = decide(answers, confirm)
        assert res.status == "error" and res.disagreement and res.solver is None
        assert res.answers == answers
        assert not res.proved


def test_decide_first_definitive_wins_and_others_do_not_count():
    answers = [SolverAnswer("z3", "unknown", 0.05, detail="incomplete"),
               SolverAnswer("cvc5", "unsat", 0.4),
               SolverAnswer("bitwuzla", "unsat", 0.2),
               SolverAnswer("z3", "timeout", 1.0)]
    res = decide(answers, confirm=False)
    assert (res.status, res.solver, res.seconds, res.disagreement) == ("unsat", "bitwuzla", 0.2, False)
    assert res.proved
    res = decide(answers, confirm=True)
    assert (res.status, res.solver, res.seconds) == ("unsat", "bitwuzla", 1.0)


def test_decide_without_definitive_answer_is_unknown_never_proved():
    for answers in ([], [SolverAnswer("z3", "timeout", 1.0)],
                    [SolverAnswer("z3", "error", 0.1), SolverAnswer("cvc5", "unknown", 0.3)]):
        res = decide(answers)
        assert res.status == "unknown" and res.solver is None and not res.disagreement
        assert not res.proved


# --------------------------------------------------------------------------
# SMT-LIB2 export


def _parse_bitwuzla(text: str) -> None:
    tm = bitwuzla.TermManager()
    parser = bitwuzla.Parser(tm, bitwuzla.Options())
    parser.parse(text, True, False)


def _parse_cvc5(text: str) -> None:
    tm = cvc5.TermManager()
    solver = cvc5.Solver(tm)
    sm = cvc5.SymbolManager(tm)
    parser = cvc5.InputParser(solver, sm)
    parser.setStringInput(cvc5.InputLanguage.SMT_LIB_2_6, text, "query")
    while not (cmd := parser.nextCommand()).isNull():
        if cmd.getCommandName() != "check-sat":
            cmd.invoke(solver, sm)


@pytest.mark.parametrize("name, query, logic, bitwuzla_ok", [
    ("absorb", Q_ABSORB, "QF_FP", True),
    ("cancel", Q_CANCEL, "QF_FP", True),
    ("bv", Q_BV, "QF_BV", True),
    ("bool", [z3.Or(z3.Bool("p"), z3.Not(z3.Bool("p")))], "QF_UF", True),
    ("bvfp", [z3.fpToIEEEBV(X) == z3.BitVec("k", 32), z3.RotateLeft(B, z3.BitVec("c", 8)) == 1],
     "QF_BVFP", True),
    ("real", Q_REAL, "QF_LRA", False),
    ("fp-real", [z3.fpToReal(X) == R], "QF_FPLRA", False),
    ("uf", [z3.Function("f", F32, F32)(X) == Y], "QF_UFFP", True),
])
def test_to_smt2_is_parsed_by_every_solver(name, query, logic, bitwuzla_ok):
    text = smtlib.to_smt2(query)
    assert f"(set-logic {logic})" in text
    assert text.rstrip().endswith("(check-sat)")
    z3.Solver().from_string(text)
    _parse_cvc5(text)
    if bitwuzla_ok:
        _parse_bitwuzla(text)
    else:
        assert "bitwuzla" in smtlib.prepare(query).skip
    # a z3.Solver gives the same query as its assertions (the let-sharing may differ)
    s = z3.Solver()
    s.add(*query)
    text2 = smtlib.to_smt2(s)
    assert text2.splitlines()[:3] == text.splitlines()[:3]
    check = z3.Solver()
    check.add(z3.And(*z3.parse_smt2_string(text)) != z3.And(*z3.parse_smt2_string(text2)))
    assert check.check() == z3.unsat


@pytest.mark.fast
def test_nonstandard_z3_operators_are_rewritten_equivalently():
    b, c = z3.BitVec("b", 8), z3.BitVec("c", 8)
    for e in (z3.RotateLeft(b, c) == 0x81, z3.RotateRight(b, c) == 0x81,
              z3.RotateLeft(b, 3) == 0x81, z3.BVMulNoOverflow(b, c, True),
              z3.BVMulNoOverflow(b, c, False), z3.BVMulNoUnderflow(b, c)):
        text = smtlib.to_smt2([e])
        for op in ("ext_rotate", "mul_noovfl", "mul_noudfl"):
            assert op not in text
        s = z3.Solver()
        s.add(z3.And(*z3.parse_smt2_string(text)) != e)
        assert s.check() == z3.unsat, e


def test_to_ieee_bv_keeps_z3_semantics_on_every_solver():
    k = z3.BitVec("k", 32)
    # every NaN has one bit pattern in Z3 (an unspecified one): unsat everywhere
    q = [z3.fpIsNaN(X), z3.fpIsNaN(Y), z3.fpToIEEEBV(X) != z3.fpToIEEEBV(Y)]
    res = P.solve(q, timeout=20, confirm=True)
    assert res.status == "unsat" and len(res.answers) == 3 and not res.disagreement
    # a NaN's reported bits are the pattern fp.to_ieee_bv gives it in the model
    res = P.solve([z3.fpIsNaN(X), z3.fpToIEEEBV(X) == k], timeout=20, confirm=True)
    assert res.status == "sat" and len(sat_answers(res)) == 3
    for a in sat_answers(res):
        assert np.isnan(f32(fp_bits(a.model["x"]))) and a.model["x"]["bits"] == a.model["k"], a
    # -0.0 and a negative subnormal are distinct bit patterns
    res = P.solve([z3.fpToIEEEBV(X) == 0x80000001, z3.fpToIEEEBV(Y) == 0x80000000],
                  timeout=20, confirm=True)
    assert res.status == "sat" and len(sat_answers(res)) == 3
    for a in sat_answers(res):
        assert (a.model["x"]["bits"], a.model["y"]["bits"]) == (0x80000001, 0x80000000)
        assert a.model["y"]["value"] == 0.0 and str(a.model["y"]["value"]) == "-0.0"


def test_solvers_are_skipped_on_what_they_cannot_do():
    half = z3.FP("h", z3.FloatHalf())
    assert set(smtlib.prepare([z3.fpIsSubnormal(half)]).skip) == {"cvc5"}
    odd = z3.FP("o", z3.FPSort(3, 5))
    assert set(smtlib.prepare([z3.fpIsNaN(odd)]).skip) == {"cvc5", "bitwuzla"}
    assert set(smtlib.prepare(Q_REAL).skip) == {"bitwuzla"}
    assert smtlib.prepare(Q_CANCEL).skip == {}


@pytest.mark.fast
def test_queries_from_another_z3_context():
    ctx = z3.Context()
    b = z3.BitVec("b", 8, ctx)
    res = P.solve([b * 3 == 7, z3.RotateLeft(b, z3.BitVec("c", 8, ctx)) == 173], timeout=20,
                  confirm=True)
    assert res.status == "sat" and len(sat_answers(res)) == 3 and not res.disagreement
    for a in sat_answers(res):
        assert a.model["b"] == 173 and a.model_checked is True


@pytest.mark.fast
def test_ambiguous_constant_names_are_rejected():
    with pytest.raises(ValueError, match="named 'x'"):
        smtlib.to_smt2([z3.fpIsNaN(X), z3.BitVec("x", 8) == 1])


# --------------------------------------------------------------------------
# The portfolio on small FP32 queries, replayed with numpy


@pytest.mark.fast
def test_absorption_counterexample_replays_in_numpy():
    res = P.solve(Q_ABSORB, timeout=20, confirm=True)
    assert res.status == "sat" and not res.disagreement
    assert {a.solver for a in sat_answers(res)} == {"z3", "bitwuzla", "cvc5"}
    assert res.model is not None and res.winner.solver == res.solver
    for a in sat_answers(res):
        x = f32(fp_bits(a.model["x"]))
        assert a.model["x"]["value"] == float(x)
        assert np.isfinite(x) and abs(x) >= 2.0 ** 24
        assert bits_of(x + np.float32(1.0)) == bits_of(x)
        assert a.model_checked is True


def test_cancellation_counterexample_replays_in_numpy():
    res = P.solve(Q_CANCEL, timeout=20, confirm=True)
    assert res.status == "sat" and not res.disagreement
    assert len(sat_answers(res)) == 3
    with np.errstate(over="ignore", invalid="ignore"):
        for a in sat_answers(res):
            x, y = f32(fp_bits(a.model["x"])), f32(fp_bits(a.model["y"]))
            assert np.isfinite(x) and np.isfinite(y)
            assert (x + y) - y != x, a  # really a counterexample


@pytest.mark.fast
def test_first_answer_wins_without_confirm():
    t = time.monotonic()
    res = P.solve(Q_CANCEL, timeout=20)
    assert res.status == "sat" and res.solver in solvers.SOLVERS
    assert [a.solver for a in res.answers if a.status == "sat"] == [res.solver]
    assert res.seconds <= time.monotonic() - t
    assert no_children_left()


@pytest.mark.fast
def test_mul_by_one_is_proved():
    s = z3.Solver()  # a z3.Solver is taken as it is
    s.add(*Q_MUL_ONE)
    res = P.solve(s, timeout=20, confirm=True)
    assert res.status == "unsat" and res.proved and not res.disagreement
    assert [a.status for a in res.answers] == ["unsat"] * 3


@pytest.mark.fast
@pytest.mark.parametrize("name", solvers.SOLVERS)
def test_each_solver_alone_proves_the_unsat_query(name):
    res = P.solve(Q_MUL_ONE, timeout=20, solvers=(name,))
    assert (res.status, res.solver) == ("unsat", name)
    assert [a.solver for a in res.answers] == [name]
    assert res.answers[0].solve_seconds is not None


@pytest.mark.fast
def test_bitvector_query():
    res = P.solve(Q_BV, timeout=20, confirm=True)
    assert res.status == "sat" and len(sat_answers(res)) == 3
    for a in sat_answers(res):
        assert a.model == {"b": 173} and a.model_checked is True


@pytest.mark.fast
def test_real_query_skips_bitwuzla():
    res = P.solve(Q_REAL, timeout=20, confirm=True)
    assert res.status == "sat" and res.solver in ("z3", "cvc5")
    skipped = [a for a in res.answers if a.solver == "bitwuzla"]
    assert len(skipped) == 1 and skipped[0].status == "unknown"
    assert "skipped" in skipped[0].detail
    for a in sat_answers(res):
        assert a.model == {"r": Fraction(1, 3)}
    res = P.solve(Q_REAL, timeout=20, solvers=("bitwuzla",))
    assert res.status == "unknown"


@pytest.mark.fast
def test_special_values_are_bit_exact():
    q = [z3.fpIsZero(X), z3.fpIsNegative(X), z3.fpIsSubnormal(Y), z3.fpIsNegative(Y),
         z3.fpIsNaN(z3.FP("n", F32))]
    res = P.solve(q, timeout=20, confirm=True)
    assert res.status == "sat" and len(sat_answers(res)) == 3
    for a in sat_answers(res):
        assert a.model["x"]["bits"] == 0x80000000
        y = f32(fp_bits(a.model["y"]))
        assert y < 0 and abs(y) < np.finfo(np.float32).tiny and y != 0
        assert np.isnan(f32(fp_bits(a.model["n"])))


# --------------------------------------------------------------------------
# Robustness: timeouts, hangs, crashes, bad input


@pytest.mark.fast
def test_timeout_is_unknown_never_unsat():
    t = time.monotonic()
    res = P.solve(Q_HARD, timeout=0.3, confirm=True)
    elapsed = time.monotonic() - t
    assert res.status == "unknown" and not res.proved
    assert {a.status for a in res.answers} <= {"timeout", "unknown"}
    assert len(res.answers) == 3
    assert elapsed < 0.3 + worker.KILL_GRACE + 20.0  # a guard against a hang, with room for a loaded machine
    assert no_children_left()


def test_hanging_and_crashing_solvers_do_not_block_the_caller():
    query = smtlib.prepare(Q_MUL_ONE)
    t = time.monotonic()
    # a limit z3 meets on this trivial query even on a loaded machine; the bound guards against a hang
    res = P._solve(query, ("_selftest_hang", "_selftest_crash", "z3"), 5.0, confirm=True)
    assert time.monotonic() - t < 5.0 + worker.KILL_GRACE + 20.0
    by = {a.solver: a for a in res.answers}
    assert by["_selftest_hang"].status == "timeout"
    assert by["_selftest_crash"].status == "error" and "died" in by["_selftest_crash"].detail
    assert by["z3"].status == "unsat" and res.status == "unsat"
    assert no_children_left()
    # without confirm the hanging solver is killed as soon as z3 has answered
    t = time.monotonic()
    res = P._solve(query, ("_selftest_hang", "z3"), 30.0, confirm=False)
    assert time.monotonic() - t < 25.0  # well before the hanging solver's 30 s limit
    assert (res.status, res.solver) == ("unsat", "z3")
    assert no_children_left()


def test_a_model_z3_rejects_never_wins():
    query = smtlib.prepare(Q_ABSORB)
    assert P.check_model(query, {"x": codec.fp_entry(0x3F800000, 8, 24)}) is False  # 1.0f
    assert P.check_model(query, {"x": codec.fp_entry(0x4B800000, 8, 24)}) is True  # 2^24
    ans = P._finish_sat(query, SolverAnswer("cvc5", "sat", 0.1,
                                            model={"x": codec.fp_entry(0x3F800000, 8, 24)}))
    assert ans.status == "error" and ans.model_checked is False


def test_bad_arguments():
    with pytest.raises(ValueError, match="unknown solver"):
        P.solve(Q_BV, solvers=("z3", "yices"))
    with pytest.raises(ValueError):
        P.solve(Q_BV, solvers=())
    with pytest.raises(ValueError, match="unknown solver"):
        P.solve(Q_BV, solvers=("_selftest_hang",))
    with pytest.raises(TypeError):
        smtlib.to_smt2([z3.BitVec("b", 8)])
