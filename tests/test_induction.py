"""The array induction of PositionSafe and Progress (proofs/induction.py): its queries can fail.
Each is asked here with the planner or the invariant broken on purpose, and the solver finds the
counterexample the proof run would (pre and not claim satisfiable), in both semantics."""

import pytest
import z3

from navfn_smt.smt.domains import FPDomain, RealDomain
from navfn_smt.smt.obligation import load_obligations
from navfn_smt.smt.runner import default_proof_files
from navfn_smt.spec import kernels as K

INDUCTION = {o.name: o for o in load_obligations(default_proof_files()) if o.source.endswith("induction.py")}
STEPS = ("update_keeps_the_invariant_at_the_updated_cell", "update_keeps_the_invariant_at_every_other_cell")


def _answer(name, D):
    """The proof run's question (pre and not claim) asked of the solver portfolio: "sat" (a
    counterexample), "unsat" (proved) or "unknown"."""
    from navfn_smt.smt.portfolio import solve

    pre, claim = INDUCTION[name].build(D)
    return solve([*D.assumptions, pre, z3.Not(claim)], timeout=120.0).status


def test_the_induction_has_a_base_and_two_steps_proved_in_the_real_domain():
    assert set(INDUCTION) == {"setup_and_init_cost_establish_the_invariant",
                              "the_steps_around_the_updates_keep_the_invariant", *STEPS}
    for name in INDUCTION:
        assert _answer(name, RealDomain()) == "unsat", name


def _flat_wave(D, l, r, u, d, hf):
    """planar_wave's candidate cut to the lowest neighbour itself: no cost added."""
    lo, hi = D.ite(D.lt(l, r), l, r), D.ite(D.lt(u, d), u, d)
    return D.ite(D.lt(lo, hi), lo, hi)


def _write_untested(D, old, l, r, u, d, cost, hf):
    """updateCell writing the candidate before (without) the ``pot < potarr[n]`` test."""
    cand = K.planar_wave(D, l, r, u, d, hf)
    return D.ite(K.is_passable(D, cost), cand, old), K.is_passable(D, cost)


@pytest.mark.parametrize("name, mutant, kernel", [
    # an updated cell may tie its lowest neighbour: Progress fails at it
    (STEPS[0], "planar_wave", _flat_wave),
    # a cell may rise above the cell it was the lower neighbour of: Progress fails there
    (STEPS[1], "cell_update", _write_untested)])
@pytest.mark.parametrize("domain", (RealDomain, FPDomain), ids=("real", "fp32"))
def test_a_broken_update_breaks_the_step(monkeypatch, name, mutant, kernel, domain):
    monkeypatch.setattr(K, mutant, kernel)
    assert _answer(name, domain()) == "sat"


@pytest.mark.fast
def test_a_setup_that_reaches_a_lethal_cell_breaks_the_base(monkeypatch):
    """The spec's setupNavFn with every cell at 0 instead of POT_HIGH: a lethal cell is reached."""
    from navfn_smt.spec import propagation as P

    ob = INDUCTION["setup_and_init_cost_establish_the_invariant"]
    monkeypatch.setattr(P, "POT_HIGH", 0.0)
    assert _answer(ob.name, RealDomain()) == "sat"
