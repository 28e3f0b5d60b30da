"""The paper's predicates as chains of obligations: the shipped chains agree with the
obligations' declarations, the check catches a chain that does not, and a predicate's
status follows from its links' verdicts."""

from types import SimpleNamespace as NS

import pytest

from navfn_smt.proofs import PREDICATES
from navfn_smt.smt.chains import Condition, Predicate, Verdict, check_chains, declared_verdicts, derive, qualified
from navfn_smt.smt.obligation import load_obligations
from navfn_smt.smt.runner import default_proof_files

pytestmark = pytest.mark.fast

# the status each predicate's chain gets from the verdicts its obligations are expected to get
BELOW = "potentials below 2^30"
COSTS = "costs as setCostmap makes them"
EXPECTED = {
    "PositionSafe": ("proved", f"conditional ({BELOW})"),
    "Monotone": ("proved", f"conditional ({BELOW})"),
    "Progress": (f"conditional ({COSTS})", f"conditional (bounded; {COSTS}; {BELOW})"),
    "ObstacleFreeQueue": ("proved", "proved"),
    "PendingMatchesBuffers": ("proved", "proved"),
    "NoPathWithoutFinitePotential": ("refuted", "proved"),
    "Gradient": ("refuted", "proved (1 trusted step)"),
    "FinitePotentialPath": ("refuted", "open"),
    "ValidPath": ("refuted", "open"),
    # complete on narrow maps: below Progress's bound 2**30 as well
    "FallbackPath": (f"conditional ({COSTS}; 2 trusted steps)", f"conditional (bounded; {COSTS}; {BELOW}; 2 trusted steps)"),
    # the fix: Progress's float32 bound 2**30 carries over
    "DescentPath": (f"conditional (the descent fits calcPath's budget; {COSTS}; 1 trusted step)",
                    f"conditional (bounded; {BELOW}; the descent fits calcPath's budget; {COSTS}; 1 trusted step)"),
    "ConnectedStartReached": (
        "conditional (no push dropped; the further call's nx*ny cycles suffice; push keys below 2^31; "
        f"{COSTS}; 1 trusted step)",
        f"conditional (no push dropped; {BELOW}; the further call's nx*ny cycles suffice; push keys below 2^31; "
        f"{COSTS}; 1 trusted step)"),
    "ReachedWithinComponent": ("proved (2 trusted steps)", f"conditional ({BELOW}; 2 trusted steps)"),
    "QueuedStartReached": ("proved (2 trusted steps)", f"conditional ({BELOW}; 2 trusted steps)"),
    "PositionSafeAndProgressInductive": ("proved", f"conditional ({BELOW})"),
    "BuffersInductive": ("proved", "proved"),
    "ReachedAndBufferedInductive": ("proved", f"conditional ({BELOW})"),
    "FrontierInductive": (f"conditional (push keys below 2^31; {COSTS})",
                          f"conditional (push keys below 2^31; {COSTS}; {BELOW})"),
    "DescentInductive": ("proved", f"conditional ({BELOW})"),
}


@pytest.fixture(scope="module")
def obligations():
    return load_obligations(default_proof_files())


def test_the_paper_predicates_are_there_by_name():
    names = [p.name for p in PREDICATES]
    assert {"PositionSafe", "Progress", "ValidPath", "FinitePotentialPath", "ObstacleFreeQueue",
            "NoPathWithoutFinitePotential"} <= set(names)
    assert all(p.statement and p.applies and p.links for p in PREDICATES)


def test_shipped_chains_agree_with_the_obligations(obligations):
    assert check_chains(PREDICATES, obligations) == []
    borrowed = {p.name for p in PREDICATES if all("." in link for link in p.links)}  # a chain of another's
    assert {o.predicate for o in obligations} | borrowed == {p.name for p in PREDICATES}
    assert borrowed == {"PendingMatchesBuffers"}


def test_statuses_derived_from_the_expected_verdicts(obligations):
    verdict_of = declared_verdicts(obligations)
    got = {p.name: tuple(derive(p, s, verdict_of, PREDICATES)["status"] for s in ("real", "fp32"))
           for p in PREDICATES}
    assert got == EXPECTED
    fpp = next(p for p in PREDICATES if p.name == "FinitePotentialPath")
    # the axis step bound is known from its split; the step's precondition is assumed, and refuted
    assert derive(fpp, "fp32", verdict_of, PREDICATES)["open"] == ["interpolated_gradient_is_zero_or_not_tiny (assumed)"]
    assert set(derive(fpp, "real", verdict_of, PREDICATES)["refuted"]) == {
        "NoPathWithoutFinitePotential.unreached_cell_stays_put", "Gradient.grad_differences_are_not_tiny"}


def _ob(name, predicate):
    return NS(name=name, predicate=predicate)


A = Predicate("A", "a", "here", base=("a0",), lemmas=("a1",), limits=("a2",))
B = Predicate("B", "b", "here", lemmas=("b0", "A.a1"), rests_on=("A",))
OBS = [_ob("a0", "A"), _ob("a1", "A"), _ob("a2", "A"), _ob("b0", "B")]


def test_check_passes_a_consistent_chain():
    assert check_chains([A, B], OBS) == []


@pytest.mark.parametrize("preds,obs,words", [
    ([A, B], OBS + [_ob("b1", "B")], "b1 (declared for B) is in no predicate's chain"),
    ([A, B], OBS[:-1], "B: link b0 names no obligation"),
    ([A, B], OBS[:-1] + [_ob("b0", "A")], "B: link b0 is declared for A, not B"),
    ([A, Predicate("B", "b", "here", lemmas=("b0", "a1"))], OBS, "B: link a1 is declared for A, not B"),
    ([A, Predicate("B", "b", "here", lemmas=("b0", "A.a2"))], OBS, "B: link A.a2 is not a link of A's chain"),
    ([A, Predicate("B", "b", "here", lemmas=("b0", "C.a1"))], OBS, "borrows from C, which is not a predicate"),
    ([A, Predicate("B", "b", "here", lemmas=("b0",), rests_on=("B",))], OBS, "B: rests on itself"),
    ([A, Predicate("B", "b", "here", lemmas=("b0", "b0"))], OBS, "B: b0 appears twice"),
    ([A, B, A], OBS, "A: defined twice"),
])
def test_check_finds_an_inconsistent_chain(preds, obs, words):
    assert any(words in p for p in check_chains(preds, obs)), check_chains(preds, obs)


def test_partial_run_is_no_problem():
    assert check_chains([A, B], OBS[:2], complete=False) == []


def _verdicts(table):
    return lambda name, sem: table.get(name)


@pytest.mark.parametrize("table,status", [
    ({"a0": Verdict("proved"), "a1": Verdict("proved")}, "proved"),
    ({"a0": Verdict("proved"), "a1": Verdict("refuted", "x < 2.0")}, "bounded"),
    ({"a0": Verdict("unknown"), "a1": Verdict("refuted", "x < 2.0")}, "open"),
    ({"a0": Verdict("proved")}, "open"),  # a link not checked is not proved
    ({"a0": Verdict("unknown"), "a1": Verdict("refuted")}, "refuted"),
])
def test_status_is_the_worst_link(table, status):
    # the limit a2 is expected to fail and never counts
    full = {**table, "a2": Verdict("refuted")}
    assert derive(A, "fp32", _verdicts(full), [A, B])["status"] == status


def test_status_takes_the_predicates_it_rests_on():
    table = {"a0": Verdict("unknown"), "a1": Verdict("proved"), "b0": Verdict("proved")}
    got = derive(B, "fp32", _verdicts(table), [A, B])
    assert got["status"] == "open" and got["open"] == ["a0 (via A)"]


C = Predicate("C", "c", "here", lemmas=("c0",), assumes=("c1",), whole=("c2",))


@pytest.mark.parametrize("assumption,status", [("proved", "proved"), ("refuted", "open"), ("unknown", "open")])
def test_an_assumption_not_proved_leaves_the_chain_open(assumption, status):
    """A precondition the links assume: refuted or unknown, the chain holds only where it does
    (open, never refuted by it); the obligation stated whole never counts."""
    table = {"c0": Verdict("proved"), "c1": Verdict(assumption), "c2": Verdict("unknown")}
    got = derive(C, "fp32", _verdicts(table), [C])
    assert got["status"] == status and got["open"] == ([] if status == "proved" else ["c1 (assumed)"])


def test_assumptions_and_whole_obligations_are_the_predicates_own():
    obs = [_ob("c0", "C"), _ob("c1", "C"), _ob("c2", "C")]
    assert check_chains([C], obs) == []
    bad = Predicate("D", "d", "here", lemmas=("d0",), assumes=("C.c1",))
    assert any("assumption C.c1 is borrowed" in p for p in check_chains([C, bad], obs + [_ob("d0", "D")]))


# --------------------------------------------------------------------------- statuses that carry their trust
T = Predicate("T", "t", "here", lemmas=("t0",), trusted=("a counting step, argued",))
U = Predicate("U", "u", "here", lemmas=("u0",), rests_on=("T",),
              conditions=(Condition("no push dropped", "a run-time condition"),))
R = Predicate("R", "r", "here", lemmas=("r0",), conditions=(Condition("below 2**30", "float32's", float32=True),))


def test_a_trusted_step_or_a_condition_on_the_chain_qualifies_proved():
    every = _verdicts({"t0": Verdict("proved"), "u0": Verdict("proved"), "r0": Verdict("proved")})
    t = derive(T, "fp32", every, [T, U])
    assert (t["rank"], t["status"], t["trusted"]) == ("proved", "proved (1 trusted step)", ["T: a counting step, argued"])
    u = derive(U, "fp32", every, [T, U])  # the trusted step beneath, through rests_on, and its own condition
    assert u["status"] == "conditional (no push dropped; 1 trusted step)" and u["conditions"] == ["no push dropped"]
    assert derive(R, "fp32", every, [R])["status"] == "conditional (below 2**30)"
    assert derive(R, "real", every, [R])["status"] == "proved"  # a float32 condition is not the reals'
    # a chain that is not proved says so, whatever lies beneath
    assert derive(U, "fp32", _verdicts({"t0": Verdict("proved"), "u0": Verdict("unknown")}), [T, U])["status"] == "open"
    assert qualified("bounded", 2, ["c"]) == "conditional (bounded; c; 2 trusted steps)"


def test_no_shipped_status_says_proved_over_a_trusted_step_or_a_condition(obligations):
    verdict_of = declared_verdicts(obligations)
    for p in PREDICATES:
        for s in ("real", "fp32"):
            d = derive(p, s, verdict_of, PREDICATES)
            if d["status"] == "proved":
                assert not d["trusted"] and not d["conditions"], p.name
            if d["trusted"] or d["conditions"]:
                assert d["status"] not in ("proved", "bounded"), (p.name, s)


def test_the_setcostmap_condition_holds_for_every_costmap_value():
    """costs as setCostmap makes them: every one of the 256 values, with unknown allowed or not,
    translates to COST_OBS or a passable cost in [COST_NEUTRAL, COST_OBS)."""
    from navfn_smt.spec.constants import COST_NEUTRAL, COST_OBS
    from navfn_smt.spec.costs import translate_cost

    got = {translate_cost(v, unknown, ros) for v in range(256) for unknown in (True, False) for ros in (True, False)}
    assert COST_OBS in got and min(got) == COST_NEUTRAL
    assert all(c == COST_OBS or COST_NEUTRAL <= c < COST_OBS for c in got)
