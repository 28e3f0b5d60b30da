"""What is known, and how a run is judged against it: a solver faster or slower than usual
never changes a run's exit status; only a decision against what is known fails it.

The solvers are replaced by fakes that answer faster (they decide every query) or slower
(they decide none) than the real ones, and by a real solver under a tiny time limit; the
exit status stays 0 in every case but a decision against what is known.
"""

from __future__ import annotations

import json
import shutil
from pathlib import Path

import pytest

from navfn_smt.cli import main
from navfn_smt.smt import knowledge as K
from navfn_smt.smt import runner
from navfn_smt.smt import split as S

pytestmark = pytest.mark.fast

TOY = Path(__file__).parent / "data" / "split" / "toy_proofs.py"

KNOWN_FILE = '''
from navfn_smt.smt.obligation import obligation
from navfn_smt.smt.predicates import ValidPotential


@obligation("Demo", expect={"fp32": "proved"}, scope="any finite x")
def subtracting_itself_gives_zero(D):
    """x - x = 0 for every valid potential."""
    x = D.f32("x")
    return ValidPotential(D, x), D.eq(D.sub(x, x), D.f32const(0.0))


@obligation("Demo", expect={"fp32": "refuted"}, scope="any valid potential")
def adding_one_increases(D):
    """x + 1 > x (false in float32: 1 is absorbed from 2**24 on)."""
    x = D.f32("x")
    return ValidPotential(D, x), D.gt(D.add(x, D.f32const(1.0)), x)


@obligation("Demo", expect={"fp32": "unknown"}, scope="any valid potential")
def doubling_is_not_smaller(D):
    """x + x >= x for every valid potential (true; declared with nothing known)."""
    x = D.f32("x")
    return ValidPotential(D, x), D.ge(D.add(x, x), x)
'''


# --------------------------------------------------------------------------- the judgements
@pytest.mark.parametrize("decision,known,judgement", [
    ("proved", "proved", K.CONFIRMED), ("refuted", "refuted", K.CONFIRMED),
    ("unknown", "proved", K.UNDECIDED), ("unknown", "refuted", K.UNDECIDED), ("unknown", "unknown", K.UNDECIDED),
    ("proved", "unknown", K.NEWLY_DECIDED), ("refuted", "unknown", K.NEWLY_DECIDED),
    ("proved", "refuted", K.CONTRADICTED), ("refuted", "proved", K.CONTRADICTED)])
def test_judge(decision, known, judgement):
    assert K.judge(decision, known) == judgement


def test_standing_is_the_decision_or_what_is_known():
    assert K.standing("proved", "unknown") == ("proved", K.UNDECIDED)
    assert K.standing("unknown", "unknown") == ("unknown", K.UNDECIDED)
    assert K.standing("unknown", "refuted") == ("refuted", K.NEWLY_DECIDED)
    assert K.standing("proved", "unknown", "proved") == ("proved", K.CONFIRMED)  # the whole query, then its split
    assert K.standing("unknown", "proved", "refuted") == ("refuted", K.CONTRADICTED)  # two runs disagree
    assert K.standing("proved", "refuted") == ("refuted", K.CONTRADICTED)


def test_a_split_gives_its_obligation_what_is_known_and_may_not_disagree():
    from navfn_smt.smt.obligation import load_obligations
    from navfn_smt.smt.runner import default_proof_files

    from navfn_smt.proofs import PREDICATES

    known = S.known_of_files(default_proof_files(), predicates=PREDICATES)
    assert known[("interpolated_gradient_is_zero_or_not_tiny", "fp32")] == K.Known("refuted", "split")
    assert known[("grad_is_unit_or_zero", "fp32")] == K.Known("proved", "split")
    assert known[("next_point_stays_near_the_cell", "fp32")].source == "chain FinitePotentialPath"
    # a declaration and a split that disagree are rejected at once
    ob = next(o for o in load_obligations([TOY]) if o.name == "doubling_is_exact")
    with pytest.raises(ValueError, match="the split states refuted"):
        S.split(ob, [(S.f32_interval("x", 0.0, 1.0),)], ("x",), expect="refuted")


# ------------------------------------------------------------------- prove, with fake solvers
@pytest.fixture
def proofs(tmp_path) -> Path:
    p = tmp_path / "p" / "known_demo.py"
    p.parent.mkdir()
    p.write_text(KNOWN_FILE)
    return p


def _prove(proofs, tmp_path, *extra) -> tuple[int, dict]:
    report = tmp_path / "r.json"
    rc = main(["prove", str(proofs), "--semantics", "fp32", "--jobs", "1", "--solver", "z3", "--report", str(report),
               *extra])
    doc = json.loads(report.read_text())
    return rc, {o["name"]: o for o in doc["obligations"]}


def _fake(answer):
    """A solver that answers ``answer(assertions)`` at once: ``(answer, values, solver, detail)``."""
    return lambda solvers: (lambda assertions, variables, timeout: answer(assertions, variables, timeout))


def test_a_solver_slower_than_usual_does_not_fail_the_run(proofs, tmp_path, monkeypatch, capsys):
    monkeypatch.setattr(runner, "solve_query", _fake(lambda a, v, t: ("unknown", None, "slow", "timeout")))
    rc, obs = _prove(proofs, tmp_path)
    assert rc == 0
    assert {o["judgement"] for o in obs.values()} == {"undecided"}
    # what is known stands: the report and the predicates show it, not the timeout
    assert obs["subtracting_itself_gives_zero"]["standing"] == "proved"
    assert obs["adding_one_increases"]["standing"] == "refuted"
    assert obs["doubling_is_not_smaller"]["standing"] == "unknown"
    assert "0 confirmed, 3 undecided, 0 newly decided, 0 contradicted (2 of the undecided known" in capsys.readouterr().out


def test_a_real_solver_under_a_tiny_time_limit_does_not_fail_the_run(proofs, tmp_path):
    rc, obs = _prove(proofs, tmp_path, "--timeout", "0.001")
    assert rc == 0
    assert all(o["judgement"] != "contradicted" for o in obs.values())


def test_a_solver_faster_than_usual_is_news_not_a_failure(proofs, tmp_path, capsys):
    """The real z3 decides the query nothing was known about: reported, recordable, exit 0."""
    rc, obs = _prove(proofs, tmp_path, "--timeout", "30")
    assert rc == 0
    assert obs["doubling_is_not_smaller"]["judgement"] == "newly decided"
    assert obs["doubling_is_not_smaller"]["standing"] == "proved"
    assert "newly decided: doubling_is_not_smaller[fp32] proved by z3" in capsys.readouterr().out


def test_a_decision_against_what_is_known_fails_the_run(proofs, tmp_path, monkeypatch, capsys):
    """A (lying) solver that proves everything proves the refuted obligation: a contradiction."""
    monkeypatch.setattr(runner, "solve_query", _fake(lambda a, v, t: ("unsat", None, "liar", "")))
    rc, obs = _prove(proofs, tmp_path)
    assert rc == 1
    assert obs["adding_one_increases"]["judgement"] == "contradicted"
    assert obs["subtracting_itself_gives_zero"]["judgement"] == "confirmed"
    assert obs["doubling_is_not_smaller"]["judgement"] == "newly decided"
    assert "CONTRADICTION: adding_one_increases[fp32] proved by liar, against the known refuted" in capsys.readouterr().out


def test_a_recorded_decision_becomes_what_is_known(proofs, tmp_path, monkeypatch):
    rc, obs = _prove(proofs, tmp_path, "--record")
    assert rc == 0 and obs["doubling_is_not_smaller"]["judgement"] == "newly decided"
    rec = json.loads((proofs.parent / K.RECORD_FILE).read_text())
    (entry,) = [v for k, v in rec.items() if k.startswith("doubling_is_not_smaller:")]
    assert entry["fp32"]["status"] == "proved" and entry["fp32"]["solver"] == "z3"
    # now known: a later run confirms it, a slower one leaves it standing, a contrary one fails
    rc, obs = _prove(proofs, tmp_path)
    assert rc == 0 and obs["doubling_is_not_smaller"]["judgement"] == "confirmed"
    assert obs["doubling_is_not_smaller"]["known"] == "proved"
    monkeypatch.setattr(runner, "solve_query", _fake(lambda a, v, t: ("unknown", None, "slow", "")))
    rc, obs = _prove(proofs, tmp_path)
    assert rc == 0 and obs["doubling_is_not_smaller"]["standing"] == "proved"
    # a record is for the code it was made for: an edited proof file drops it
    proofs.write_text(KNOWN_FILE + "\n# edited\n")
    rc, obs = _prove(proofs, tmp_path)
    assert obs["doubling_is_not_smaller"]["known"] == "unknown"


# ---------------------------------------------------------------------- split, with fake parts
def _toy_copy(tmp_path) -> Path:
    d = tmp_path / "toy"
    d.mkdir()
    shutil.copy(TOY, d / TOY.name)
    return d / TOY.name


def test_a_split_left_undecided_does_not_fail_the_run(tmp_path, monkeypatch, capsys):
    def slow(job):
        _, _, _, part, _, _, _ = job
        return S.Part(part.box, part.depth, detail="smt: timeout (fake)")

    monkeypatch.setattr(S, "check_part", slow)
    toy = _toy_copy(tmp_path)
    assert main(["split", "sum_minus_one_keeps_y", "--files", str(toy), "--jobs", "1", "--max-depth", "0",
                 "--quiet"]) == 0
    assert "1 splits: 0 confirmed, 1 undecided (sum_minus_one_keeps_y)" in capsys.readouterr().out


def test_a_split_against_what_is_known_fails_the_run(tmp_path, monkeypatch, capsys):
    def liar(job):
        _, _, _, part, _, _, _ = job
        return S.Part(part.box, part.depth, status="proved", solver="liar")

    monkeypatch.setattr(S, "check_part", liar)
    toy = _toy_copy(tmp_path)
    assert main(["split", "sum_minus_one_keeps_y", "--files", str(toy), "--jobs", "1", "--quiet"]) == 1
    assert "1 contradicted (sum_minus_one_keeps_y)" in capsys.readouterr().out
