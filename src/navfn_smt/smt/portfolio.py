"""Solver portfolio for proof obligations: Z3, Bitwuzla and cvc5 on the same query.

An obligation is a Z3 query (a ``z3.Solver`` or a list of Boolean assertions)
whose satisfiability decides it: ``unsat`` proves the obligation, ``sat`` refutes
it with a counterexample, and anything else (unknown, timeout, error) leaves it
undecided -- never proved.

This module orchestrates: the query is exported once (:mod:`navfn_smt.smt.smtlib`),
each solver (:mod:`navfn_smt.smt.solvers`) runs on it in its own worker process
(:mod:`navfn_smt.smt.worker`) with its own time limit and a hard kill shortly after
it, and the answers are combined.  :func:`solve` returns the first definitive answer
(``confirm=False``) or waits for every solver and compares (``confirm=True``).  How
answers combine is the pure function :func:`decide`: definitive answers that disagree
give status ``"error"`` and ``disagreement=True``, never a silent choice.

Models of ``sat`` answers map the declared constants to the entries of
:mod:`navfn_smt.smt.codec`.  Every model is re-evaluated against the original Z3
assertions in the calling process (:func:`check_model`); a model Z3 evaluates to false
turns that answer into an ``"error"`` (so it can never win), see
``SolverAnswer.model_checked``.
"""

from __future__ import annotations

import queue
import time
from dataclasses import dataclass, field

import z3

from . import codec
from .smtlib import Query, prepare
from .solvers import SOLVERS, check_names
from .worker import KILL_GRACE, Worker, answer

__all__ = ["SolverAnswer", "PortfolioResult", "solve", "decide", "check_model"]

DEFINITIVE = ("sat", "unsat")


# --------------------------------------------------------------------------
# Results


@dataclass
class SolverAnswer:
    """One solver's answer to the query, as the portfolio received (or gave) it."""

    solver: str  # "z3" | "bitwuzla" | "cvc5"
    status: str  # "sat" | "unsat" | "unknown" | "timeout" | "error"
    seconds: float  # wall time from the start of the portfolio to this answer
    detail: str = ""  # error message / reason unknown / why skipped
    model: dict | None = None  # for sat: {const name: codec entry}
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
    """The portfolio's decision on a query, with every answer it rests on."""

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


def _finish_sat(query: Query, ans: SolverAnswer) -> SolverAnswer:
    """A sat answer with its model reduced to the query's constants (NaNs with the pattern
    the model gives them) and checked by Z3: a model Z3 rejects turns it into ``"error"``."""
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


# --------------------------------------------------------------------------
# Running the solvers


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
    Float32/64.  ``solver_or_assertions`` may also be a
    :class:`~navfn_smt.smt.smtlib.Query` from :func:`~navfn_smt.smt.smtlib.prepare`
    (to export once and solve several times).

    Each ``SolverAnswer.seconds`` counts from the call (so it includes the
    export and the solver process start-up, ~0.05-0.15 s); ``solve_seconds``
    is the solver's own parse-and-check time.
    """
    t0 = time.monotonic()
    names = check_names(solvers)
    if not timeout > 0:
        raise ValueError("timeout must be positive")
    query = solver_or_assertions if isinstance(solver_or_assertions, Query) \
        else prepare(solver_or_assertions)
    return _solve(query, names, timeout, confirm, t0)


def _solve(query: Query, names: tuple[str, ...], timeout: float, confirm: bool,
           t0: float | None = None) -> PortfolioResult:
    """The portfolio on a prepared query with checked solver names (test doubles allowed)."""
    if t0 is None:
        t0 = time.monotonic()
    answers: list[SolverAnswer] = []
    running: dict[str, Worker] = {}  # the workers not yet answered
    started: list[Worker] = []
    replies: queue.Queue = queue.Queue()
    try:
        for name in names:
            w = _start(query, name, timeout, replies, answers, t0)
            if w is not None:
                running[name] = w
                started.append(w)
        _collect(query, running, replies, answers, t0 + timeout + KILL_GRACE, confirm, t0)
        if running and (confirm or not _decided(answers)):
            now = time.monotonic() - t0
            for name in running:
                answers.append(SolverAnswer(name, "timeout", now, detail=f"killed after {timeout:g} s"))
    finally:
        for w in running.values():
            w.kill()
        for w in started:  # a reply thread ends once its process is gone
            w.join(5.0)
    return decide(answers, confirm)


def _start(query: Query, name: str, timeout: float, replies: queue.Queue, answers: list,
           t0: float) -> Worker | None:
    """A worker for solver ``name``; None, with its answer recorded, when it is skipped
    (it cannot take the query) or cannot start."""
    if name in query.skip:
        answers.append(SolverAnswer(name, "unknown", time.monotonic() - t0, detail="skipped: " + query.skip[name]))
        return None
    try:
        return Worker(name, request(query, name, timeout), replies)
    except Exception as exc:
        answers.append(SolverAnswer(name, "error", time.monotonic() - t0, detail=f"could not start: {exc}"))
        return None


def request(query: Query, name: str, timeout: float) -> dict:
    """What solver ``name`` is sent: Z3 its own dialect, the others the standard text, in
    which the NaN-pattern constants are reported too."""
    if name == "z3":
        return {"text": query.z3_text, "timeout": timeout, "names": query.const_sorts, "logic": query.logic,
                "options": {}}
    names = {**query.const_sorts, **{aux: "" for aux in query.nan_consts.values()}}
    options = {"fp_exp": True} if name == "cvc5" and query.cvc5_fp_exp else {}
    return {"text": query.smt2, "timeout": timeout, "names": names, "logic": query.logic, "options": options}


def _collect(query: Query, running: dict, replies: queue.Queue, answers: list, deadline: float,
             confirm: bool, t0: float) -> None:
    """Answers as the workers end, until none is left or the deadline passes, or (without
    ``confirm``) the first definitive one."""
    while running:
        left = deadline - time.monotonic()
        if left <= 0:
            break
        try:
            name, when, out, err, code = replies.get(timeout=left)
        except queue.Empty:
            break
        running.pop(name, None)
        answers.append(_answer(query, name, when - t0, answer(out, err, code)))
        if not confirm and _decided(answers):
            break


def _answer(query: Query, name: str, seconds: float, msg: dict) -> SolverAnswer:
    """A worker's answer dict as a :class:`SolverAnswer` (a sat one with its model checked)."""
    ans = SolverAnswer(name, str(msg.get("status", "error")), seconds, detail=str(msg.get("detail", "")),
                       model=msg.get("model"), solve_seconds=msg.get("solve_seconds"))
    return _finish_sat(query, ans) if ans.status == "sat" else ans


def _decided(answers: list) -> bool:
    """Whether some answer is definitive (sat or unsat)."""
    return any(a.status in DEFINITIVE for a in answers)
