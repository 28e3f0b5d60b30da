"""The extraction and loop-control obligations over arrays and fills (proofs/descent.py,
proofs/calcpath.py, proofs/loop.py, proofs/queued.py, proofs/potential_bound.py, and the floor
invariant of proofs/fallback.py): none is vacuous, and each notices a seeded bug in the function
it runs.

A proof of ``pre ==> claim`` says nothing when ``pre`` is unsatisfiable, so each precondition
is shown satisfiable (the claims themselves are the proof run's: tests/test_prove.py); and a
step stated wrongly (a descent that takes the first neighbour, a grid step that never stops,
a loop test that forgets a buffer, a swap that drops the overflow buffer, an update that writes
before its test or never writes) must give a model of the negation."""

from pathlib import Path

import pytest
import z3

from navfn_smt.smt import portfolio
from navfn_smt.smt.domains import DOMAINS
from navfn_smt.smt.obligation import load_obligations
from navfn_smt.spec import extraction as E
from navfn_smt.spec import fix as F
from navfn_smt.spec import kernels as K
from navfn_smt.spec import propagation as P

PROOFS = Path(__file__).resolve().parents[1] / "src" / "navfn_smt" / "proofs"
FILES = ("descent.py", "calcpath.py", "loop.py", "queued.py", "potential_bound.py")
FLOOR = ("setup_gives_every_reached_cell_a_neighbour_below_its_floor",
         "update_keeps_a_neighbour_below_the_floor_at_the_updated_cell",
         "update_keeps_a_neighbour_below_the_floor_at_every_other_cell")
OBLIGATIONS = {o.name: o for o in load_obligations([PROOFS / f for f in FILES] + [PROOFS / "fallback.py"])
               if o.source.endswith(FILES) or o.name in FLOOR}


def _decide(formula):
    """sat or unsat by the project's portfolio (z3 alone can blow up on float32 array queries)."""
    got = portfolio.solve([formula], timeout=120.0).status
    assert got in ("sat", "unsat"), got
    return z3.sat if got == "sat" else z3.unsat


def test_the_files_hold_the_obligations_named_here():
    assert set(FLOOR) <= set(OBLIGATIONS) and len(OBLIGATIONS) >= 14


@pytest.mark.parametrize("semantics", ["real", "fp32"])
@pytest.mark.parametrize("name", sorted(OBLIGATIONS))
def test_each_precondition_is_satisfiable(name, semantics):
    ob = OBLIGATIONS[name]
    if semantics not in ob.expect:
        pytest.skip(f"{name} declares nothing in {semantics}")
    pre, _ = ob.build(DOMAINS[semantics]())
    assert _decide(pre) == z3.sat


def _first_neighbour(D, centre, ring):
    return 0


def _never_stops(D, pot, stc, nx):
    nxt, dx, dy, _ = GRID_STEP(D, pot, stc, nx)
    return nxt, dx, dy, False


def _runs_on_the_next_fill_only(D, cycle, cycles, fill_cur, fill_next):
    return D.and_(D.lt(cycle, cycles), D.not_(D.eq(fill_next, 0)))


def _ends_at_pot_high(D, start_pot):
    return D.le(start_pot, D.f32const(1.0e10))


def _calls_again_on_the_next_fill_only(D, start_pot, fill_cur, fill_next):
    return D.and_(K.unreached(D, start_pot), D.not_(D.eq(fill_next, 0)))


def _drops_overflow(D, nxt, over, drained):
    return D.ite(drained, over, nxt), 0


def _writes_before_the_test(D, old, l, r, u, d, cost, hf):
    cand = K.planar_wave(D, l, r, u, d, hf)
    return D.ite(K.is_passable(D, cost), cand, old), D.and_(K.is_passable(D, cost), D.lt(cand, old))


def _never_writes(D, old, l, r, u, d, cost, hf):
    return old, D.lt(old, old)


GRID_STEP = E.grid_step
WRONG_STEPS = [
    (K, "lowest_neighbour", _first_neighbour,
     "descent_iteration_moves_strictly_down_or_stops_at_the_goal_or_the_budget"),
    (E, "grid_step", _never_stops, "calc_path_stops_at_once_at_an_unreached_start"),
    (P, "cycle_runs", _runs_on_the_next_fill_only,
     "propagation_stops_only_at_a_reached_start_with_empty_buffers_or_its_cycles_spent"),
    (P, "call_ends_at_the_start", _ends_at_pot_high,
     "propagation_stops_only_at_a_reached_start_with_empty_buffers_or_its_cycles_spent"),
    (F, "calls_again", _calls_again_on_the_next_fill_only,
     "propagation_stops_only_at_a_reached_start_with_empty_buffers_or_its_cycles_spent"),
    (K, "buffer_swap", _drops_overflow, "next_buffer_becomes_current_and_its_cycle_runs"),
    (K, "cell_update", _writes_before_the_test, "update_of_any_slot_keeps_a_passed_queued_start_reached"),
    (K, "cell_update", _never_writes, "update_of_any_slot_keeps_a_passed_queued_start_reached"),
]


@pytest.mark.parametrize("module, name, wrong, obligation", WRONG_STEPS,
                         ids=[f"{w.__name__}-{o}" for _, _, w, o in WRONG_STEPS])
def test_a_wrong_step_gives_a_model_of_the_negation(monkeypatch, module, name, wrong, obligation):
    monkeypatch.setattr(module, name, wrong)
    pre, claim = OBLIGATIONS[obligation].build(DOMAINS["fp32"]())
    assert _decide(z3.And(pre, z3.Not(claim))) == z3.sat



def test_the_rise_of_one_update_is_nearly_tight_over_the_reals(monkeypatch):
    """254.2 above the lowest neighbour is reachable over the reals (v tends to 1.0046 as dc nears
    hf = 253), so a rise of 254 is refuted: the bound 256 is not loose by much."""
    ob = OBLIGATIONS["update_raises_at_most_256_above_its_lowest_neighbour"]
    monkeypatch.setitem(ob.build.__globals__, "RISE", 254.0)
    pre, claim = ob.build(DOMAINS["real"]())
    assert _decide(z3.And(pre, z3.Not(claim))) == z3.sat
