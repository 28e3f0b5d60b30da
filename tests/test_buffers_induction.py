"""The buffer and frontier invariants over arrays (proofs/buffers.py, proofs/frontier.py): their
obligations are not vacuous, and each notices a seeded bug in the step it states.

A proof of ``pre ==> claim`` says nothing when ``pre`` is unsatisfiable, so each precondition
is shown satisfiable; and a step stated wrongly (a push that forgets the pending flag or the
guard's pending test, a swap that drops the overflow buffer, an update that writes before its
test) must give a model of the negation."""

from pathlib import Path

import pytest
import z3

from navfn_smt.smt import portfolio
from navfn_smt.smt.domains import DOMAINS
from navfn_smt.smt.obligation import load_obligations
from navfn_smt.spec import kernels as K

PROOFS = Path(__file__).resolve().parents[1] / "src" / "navfn_smt" / "proofs"
OBLIGATIONS = {o.name: o for o in load_obligations([PROOFS / "buffers.py", PROOFS / "frontier.py"])}
PUSH = K.push  # the step as the spec runs it


def _decide(formula):
    """sat or unsat by the project's portfolio (z3 alone can take gigabytes on the float32 ones)."""
    got = portfolio.solve([formula], timeout=120.0).status
    assert got in ("sat", "unsat"), got
    return z3.sat if got == "sat" else z3.unsat


@pytest.mark.parametrize("semantics", ["real", "fp32"])
@pytest.mark.parametrize("name", sorted(OBLIGATIONS))
def test_each_precondition_is_satisfiable_and_each_claim_follows(name, semantics):
    """(the claims of the slow ones are left to `prove --all`, as the proof run leaves them)"""
    ob = OBLIGATIONS[name]
    D = DOMAINS[semantics]()
    pre, claim = ob.build(D)
    pre = z3.And(pre, *D.assumptions)  # the library functions' models, as the proof run takes them
    assert _decide(pre) == z3.sat
    if semantics not in ob.slow:
        assert _decide(z3.And(pre, z3.Not(claim))) == z3.unsat


def _forgets_pending(D, n, ns, pending, cost, fill, capacity):
    admitted, dropped, _ = PUSH(D, n, ns, pending, cost, fill, capacity)
    return admitted, dropped, pending


def _ignores_pending(D, n, ns, pending, cost, fill, capacity):
    return PUSH(D, n, ns, False, cost, fill, capacity)


def _writes_before_the_test(D, old, l, r, u, d, cost, hf):
    cand = K.planar_wave(D, l, r, u, d, hf)
    return cand, D.and_(K.is_passable(D, cost), D.lt(cand, old))


def _drops_overflow(D, nxt, over, drained):
    return nxt, D.ite(drained, 0, over)


WRONG_STEPS = [
    ("push", _forgets_pending, "update_keeps_each_pending_cell_in_one_slot"),
    ("push", _forgets_pending, "setup_puts_each_pending_cell_in_one_slot"),
    ("push", _ignores_pending, "astar_update_keeps_each_pending_cell_in_one_slot"),
    ("buffer_swap", _drops_overflow, "swap_keeps_each_pending_cell_in_one_slot"),
    ("cell_update", _writes_before_the_test, "update_and_its_pushes_reach_only_cells_of_the_component"),
    ("push", _forgets_pending, "update_and_its_pushes_keep_the_frontier"),
    ("push", _forgets_pending, "setup_leaves_no_unreached_neighbour_unbuffered"),
]


@pytest.mark.parametrize("kernel, wrong, name", WRONG_STEPS, ids=[f"{w.__name__}-{n}" for _, w, n in WRONG_STEPS])
def test_a_wrong_step_gives_a_model_of_the_negation(monkeypatch, kernel, wrong, name):
    """(in real arithmetic: each seeded bug is in the buffers' bookkeeping, which a float32
    model finds too, but a float32 query of the frontier's update takes a solver about a minute)"""
    monkeypatch.setattr(K, kernel, wrong)
    pre, claim = OBLIGATIONS[name].build(DOMAINS["real"]())
    assert _decide(z3.And(pre, z3.Not(claim))) == z3.sat
