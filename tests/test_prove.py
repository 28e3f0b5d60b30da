"""The proof run: no obligation in proofs/ gets a verdict against what is known of it, the
reports are complete, and a verdict that contradicts what is known fails the run."""

import json
import os
import subprocess
import sys
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import pytest

REPO = Path(__file__).resolve().parent.parent


def run(*args, cwd):
    p = subprocess.run([sys.executable, "-m", "navfn_smt", *map(str, args)], capture_output=True, text=True,
                       cwd=cwd, env={**os.environ, "COLUMNS": "200"})
    return p.returncode, p.stdout, p.stderr


@pytest.fixture(scope="module")
def proof_run(tmp_path_factory):
    out = tmp_path_factory.mktemp("prove")
    rc, stdout, stderr = run("prove", "--timeout", "30", "--report", out / "r.json",
                             "--junit", out / "j.xml", "--markdown", out / "inv.md", "--witness-dir", out / "w",
                             cwd=out)
    return rc, stdout, stderr, out


def test_no_obligation_contradicts_what_is_known(proof_run):
    """Each verdict is what is known or undecided (a solver slower than usual is no failure);
    a standing is never weaker than what is known, whatever the solvers managed today."""
    rc, stdout, stderr, out = proof_run
    assert rc == 0, stdout[-3000:] + stderr[-2000:]
    doc = json.loads((out / "r.json").read_text())
    obs = doc["obligations"]
    assert len(obs) >= 20
    for o in obs:
        for key in ("name", "property", "semantics", "status", "known", "standing", "judgement", "seconds", "solver",
                    "bound", "witness"):
            assert key in o
        assert o["semantics"] in ("real", "fp32") and o["status"] in (o["known"], "unknown"), o
        assert o["judgement"] in ("confirmed", "undecided") and (o["known"] == "unknown" or o["standing"] == o["known"]), o
        if o["status"] == "refuted":
            w = json.loads(Path(o["witness"]).read_text())
            assert w["replayed_on_spec"] is True and w["values"]
        else:
            assert o["witness"] is None
    props = {o["property"] for o in obs}
    assert {"PositionSafe", "Progress", "Monotone", "ObstacleFreeQueue",
            "FinitePotentialPath", "ValidPath", "NoPathWithoutFinitePotential", "Gradient"} <= props
    # PendingMatchesBuffers' chain is BuffersInductive's obligations: it has a status, no obligation of its own
    assert "PendingMatchesBuffers" not in props
    assert "PendingMatchesBuffers" in {p["name"] for p in doc["predicates"]}
    # every obligation in both semantics, but the slow queries the default run leaves to --all
    from navfn_smt.smt.obligation import load_obligations
    from navfn_smt.smt.runner import default_proof_files, wanted

    want = {(o.name, s) for o in load_obligations(default_proof_files()) for s in ("real", "fp32")
            if wanted(o, s, everything=False)}
    assert {(o["name"], o["semantics"]) for o in obs} == want
    assert "slow queries left to `navfn-smt prove --all`" in proof_run[1]


@pytest.fixture(scope="module")
def progress_run(tmp_path_factory):
    """`prove --all` on the Progress file in fp32: the bound search, which the default run leaves out."""
    out = tmp_path_factory.mktemp("progress")
    rc, stdout, stderr = run("prove", REPO / "src" / "navfn_smt" / "proofs" / "progress.py", "--all",
                             "--semantics", "fp32", "--report", out / "r.json", "--markdown", out / "inv.md", cwd=out)
    assert rc == 0, stdout[-3000:] + stderr[-2000:]
    return out


def test_progress_bound_is_found_and_tight(progress_run):
    doc = json.loads((progress_run / "r.json").read_text())
    o = next(o for o in doc["obligations"] if o["name"] == "update_keeps_a_lower_neighbour" and o["semantics"] == "fp32")
    b = o["bound"]
    # ta + 50 is absorbed once ulp(ta) > 100, i.e. from 2**30 on (ulp 128): the bound found must be that
    assert b["holds_below"] == 2.0**30 and b["refuted_below"] > b["holds_below"]
    assert "holds for `l < 1073741824.0`" in (progress_run / "inv.md").read_text()


def test_the_default_run_searches_no_bound_and_takes_the_cached_one(proof_run):
    """No solver call for the bound in the default run: the bound cache (for this code) gives it,
    so Progress is bounded there as in `prove --all` and on the page."""
    doc = json.loads((proof_run[3] / "r.json").read_text())
    o = next(o for o in doc["obligations"] if o["name"] == "update_keeps_a_lower_neighbour" and o["semantics"] == "fp32")
    assert o["status"] in ("refuted", "unknown") and o["standing"] == "refuted"
    assert o["bound"]["source"] == "bound cache" and o["bound"]["holds_below"] == 2.0**30
    assert "solver_calls" not in o["bound"]


def test_reports_junit_and_markdown(proof_run):
    out = proof_run[3]
    suite = ET.parse(out / "j.xml").getroot()
    assert suite.tag == "testsuite" and int(suite.get("failures")) == 0 and int(suite.get("tests")) >= 20
    md = (out / "inv.md").read_text()
    assert md.startswith("# NavFn invariants") and "do not edit by hand" in md
    assert "update_keeps_a_lower_neighbour" in md


def test_predicates_in_the_reports(proof_run):
    """Per paper predicate: its chain with each link's verdicts, the derived status (as the
    expected verdicts derive it) and what is open, in the JSON, the terminal and the page."""
    from test_chains import EXPECTED

    rc, stdout, _, out = proof_run
    doc = json.loads((out / "r.json").read_text())
    assert doc["chain_problems"] == [] and doc["unchained_obligations"] == []
    preds = {p["name"]: p for p in doc["predicates"]}
    assert set(preds) == set(EXPECTED)
    # the one status per predicate: the same as what is known derives, slow queries left out or not
    for name, (real, fp32) in EXPECTED.items():
        p = preds[name]
        assert (p["status"]["real"]["status"], p["status"]["fp32"]["status"]) == (real, fp32), name
        assert p["changed"] == [] and p["chain"] and all(set(r["verdicts"]) == {"real", "fp32"} for r in p["chain"])
    assert preds["Progress"]["status"]["fp32"]["bounded"] == ["update_keeps_a_lower_neighbour (l < 1073741824.0)"]
    assert "interpolated_gradient_is_zero_or_not_tiny (assumed)" in preds["FinitePotentialPath"]["status"]["fp32"]["open"]
    assert "the paper's predicates" in stdout and "PendingMatchesBuffers" in stdout
    md = (out / "inv.md").read_text()
    assert "## The paper's predicates" in md
    assert "| 1 | base | `ValidPath.first_point_is_the_start` | proved | proved |" in md


def test_changed_verdict_fails_the_run(tmp_path):
    (tmp_path / "wrong.py").write_text('''
from navfn_smt.smt.obligation import obligation
from navfn_smt.smt.predicates import ValidPotential

@obligation("Demo", expect={"real": "proved", "fp32": "proved"}, scope="one addition")
def adding_one_always_increases(D):
    """x + 1 > x for every valid potential (false in float32: absorbed above 2**24)."""
    x = D.f32("x")
    return ValidPotential(D, x), D.gt(D.add(x, D.f32const(1.0)), x)
''')
    rc, stdout, stderr = run("prove", tmp_path / "wrong.py", "--report", tmp_path / "r.json",
                             "--witness-dir", tmp_path / "w", cwd=tmp_path)
    assert rc == 1, stdout + stderr
    assert "1 confirmed, 0 undecided, 0 newly decided, 1 contradicted" in stdout
    assert "CONTRADICTION: adding_one_always_increases[fp32] refuted" in stdout
    o = {x["semantics"]: x for x in json.loads((tmp_path / "r.json").read_text())["obligations"]}
    assert o["real"]["status"] == "proved" and o["fp32"]["status"] == "refuted"
    assert o["fp32"]["judgement"] == "contradicted"
    x = np.float32(o["fp32"]["witness_values"]["values"]["x"]["value"])
    assert x >= 2.0**24 and x + np.float32(1.0) == x  # the counterexample: 1 is absorbed


def test_a_model_with_a_variable_outside_the_domain_is_not_replayed_and_not_a_traceback(tmp_path):
    (tmp_path / "flag.py").write_text('''
import z3
from navfn_smt.smt.obligation import obligation

@obligation("Demo", expect={"real": "proved", "fp32": "proved"}, scope="one comparison")
def a_flag_made_with_z3(D):
    """A claim that fails, with a Bool made with z3 in its precondition."""
    x = D.f32("x")
    return z3.And(z3.Bool("flag"), D.lt(x, D.f32const(1.0))), D.lt(x, D.f32const(0.0))
''')
    rc, stdout, stderr = run("prove", tmp_path / "flag.py", "--report", tmp_path / "r.json", cwd=tmp_path)
    assert rc == 0 and "Traceback" not in stderr, stdout + stderr
    assert "0 confirmed, 2 undecided, 0 newly decided, 0 contradicted" in stdout
    assert "2 solver models not confirmed on the spec written under" in stdout and "counterexample" not in stdout
    for o in json.loads((tmp_path / "r.json").read_text())["obligations"]:
        assert o["status"] == "unknown" and "cannot evaluate" in o["detail"], o


WRONG = '''
from navfn_smt.smt.obligation import obligation
from navfn_smt.smt.predicates import ValidPotential

@obligation("Demo", expect={"real": "proved", "fp32": "proved"}, scope="one addition")
def adding_one_always_increases(D):
    """x + 1 > x for every valid potential (false in float32: absorbed above 2**24)."""
    x = D.f32("x")
    return ValidPotential(D, x), D.gt(D.add(x, D.f32const(1.0)), x)
'''


def test_witnesses_go_next_to_the_report_and_never_into_the_working_directory(tmp_path):
    proofs, work = tmp_path / "proofs", tmp_path / "work"
    proofs.mkdir()
    work.mkdir()
    (proofs / "wrong.py").write_text(WRONG)
    # no report asked: no witness file anywhere, and the run says so
    rc, stdout, stderr = run("prove", proofs / "wrong.py", "--no-bound-search", cwd=work)
    assert rc == 1, stdout + stderr
    assert "1 counterexample not written to files" in stdout
    assert not any(work.iterdir())
    # a report asked: witnesses in a folder next to it, named after it
    (tmp_path / "out").mkdir()
    rc, stdout, stderr = run("prove", proofs / "wrong.py", "--no-bound-search", "--report", tmp_path / "out" / "r.json",
                             cwd=work)
    assert rc == 1, stdout + stderr
    w = tmp_path / "out" / "r-witnesses" / "adding_one_always_increases.fp32.json"
    assert f"1 counterexample written under {w.parent}" in stdout
    assert json.loads(w.read_text())["replayed_on_spec"] is True
    o = {x["semantics"]: x for x in json.loads((tmp_path / "out" / "r.json").read_text())["obligations"]}
    assert o["fp32"]["witness"] == str(w) and o["real"]["witness"] is None
    assert not any(work.iterdir())


@pytest.mark.parametrize("content,words", [(None, "no such proof file"), ("this is not python(", "cannot load"),
                                           ("x = 1\n", "defines no obligations")])
def test_bad_proof_files(tmp_path, content, words):
    f = tmp_path / "p.py"
    if content is not None:
        f.write_text(content)
    rc, stdout, stderr = run("prove", f, cwd=tmp_path)
    assert rc == 2 and "Traceback" not in stderr and words in stderr, stderr


def test_committed_invariants_page_matches_the_obligations():
    """docs/invariants.md is generated from the proof run's report; it must list every
    obligation with what is known of it now (regenerate it with `navfn-smt docs`)."""
    from navfn_smt.proofs import PREDICATES
    from navfn_smt.smt.obligation import load_obligations
    from navfn_smt.smt.runner import default_proof_files

    lines = (REPO / "docs" / "invariants.md").read_text().splitlines()
    head = next(line for line in lines if line.startswith("| property | obligation |"))
    sems = [p.strip() for p in head.strip().strip("|").split("|")][2:]
    assert sems == ["real", "fp32", "fp32@x86-64-v3", "fp32@aarch64"]  # a column per build arithmetic
    rows = {}
    for line in lines:
        parts = [p.strip() for p in line.strip().strip("|").split("|")]
        if len(parts) == 2 + len(sems) and parts[1].startswith("`"):
            rows[parts[1].strip("`")] = {s: v.split()[0] for s, v in zip(sems, parts[2:])}
    obs = load_obligations(default_proof_files())
    from navfn_smt.smt.split import known_of_files

    known = known_of_files(default_proof_files(), obs, PREDICATES)
    assert set(rows) == {o.name for o in obs}
    for o in obs:  # a split decides its obligation's fp32 verdict: the knowledge says so
        # a semantics the obligation declares nothing in is not run ("not run")
        assert rows[o.name] == {s: known[(o.name, s)].status if (o.name, s) in known else "not" for s in sems}, o.name


def test_committed_invariants_page_shows_the_predicates():
    """The page's table of predicates has every predicate with the status its chain derives
    from the expected verdicts, and every link of its chain."""
    from navfn_smt.proofs import PREDICATES
    from navfn_smt.smt.chains import declared_verdicts, derive
    from navfn_smt.smt.obligation import load_obligations
    from navfn_smt.smt.runner import default_proof_files

    from navfn_smt.smt.split import load_splits

    verdict_of = declared_verdicts(load_obligations(default_proof_files()), load_splits(default_proof_files()))
    lines = (REPO / "docs" / "invariants.md").read_text().splitlines()
    head = next(line for line in lines if line.startswith("| predicate |"))
    sems = [p.strip() for p in head.strip().strip("|").split("|")][1:-2]
    rows = {}
    for line in lines:
        parts = [p.strip() for p in line.strip().strip("|").split("|")]
        if len(parts) == 3 + len(sems) and parts[0] in {p.name for p in PREDICATES}:
            rows[parts[0]] = parts
    assert set(rows) == {p.name for p in PREDICATES}
    for p in PREDICATES:
        statuses, (base, step) = rows[p.name][1:1 + len(sems)], rows[p.name][-2:]
        assert statuses == [derive(p, s, verdict_of, PREDICATES)["status"] for s in sems], p.name
        assert all(f"`{x}`" in base for x in p.base) and all(f"`{x}`" in step for x in p.lemmas), p.name


def test_slow_only_is_what_all_adds_to_the_default_run():
    """``prove --slow-only`` (CI, after a test run that checked the default queries): the slow
    queries and the fp32 queries whose refutation searches a bound, and with the default run
    every query of ``--all``."""
    from navfn_smt.smt.runner import default_proof_files, tasks

    files = default_proof_files()

    def keys(**kw):
        return [(t.name, t.semantics) for t in tasks(files, **kw)]

    whole, default, slow = keys(everything=True), keys(everything=False), keys(slow_only=True)
    assert set(default) | set(slow) == set(whole) and len(whole) == len(set(whole))
    both = set(default) & set(slow)
    assert both and all(s == "fp32" for _, s in both)  # the bound searches, which only --all runs
    assert ("update_keeps_a_lower_neighbour", "fp32") in both
    assert not set(default) & set(keys(slow_only=True, bounds=False))
    assert set(slow) - set(default) == set(whole) - set(default) != set()


@pytest.mark.parametrize("extra, message", [
    (["--all"], "--slow-only and --all exclude each other"),
    (["--markdown", "p.md"], "--slow-only leaves the default queries out"),
])
def test_slow_only_refuses_what_needs_a_whole_run(tmp_path, monkeypatch, capsys, extra, message):
    from navfn_smt.cli import main

    monkeypatch.chdir(tmp_path)
    assert main(["prove", "--slow-only", *extra]) == 2
    assert capsys.readouterr().err.startswith(f"navfn-smt: error: {message}")
    assert list(tmp_path.iterdir()) == []


def test_a_build_arithmetic_has_verdicts_of_its_own(tmp_path):
    """NoPathWithoutFinitePotential's step is proved in x86-64's fp32, where ``(int)1e10`` is
    INT_MIN, and refuted in aarch64's, where it saturates to INT_MAX: ``prove --target aarch64``
    judges it in ``fp32@aarch64`` against what is declared there, with a witness the concrete
    spec confirms in that arithmetic, and which is no counterexample in x86-64's."""
    from navfn_smt.cli import main
    from navfn_smt.smt.obligation import load_obligations
    from navfn_smt.smt.replay import replay
    from navfn_smt.spec.arithmetic import KNOWN

    proof = REPO / "src" / "navfn_smt" / "proofs" / "no_path.py"
    for target, want in (("aarch64", "refuted"), ("x86-64", "proved")):
        assert main(["prove", str(proof), "--target", target, "--report", str(tmp_path / f"{target}.json")]) == 0
        (row,) = json.loads((tmp_path / f"{target}.json").read_text())["obligations"]
        assert row["semantics"] == ("fp32@aarch64" if target == "aarch64" else "fp32"), row
        assert (row["status"], row["known"], row["judgement"]) == (want, want, "confirmed"), row
    (row,) = json.loads((tmp_path / "aarch64.json").read_text())["obligations"]
    w = json.loads(Path(row["witness"]).read_text())
    assert w["replayed_on_spec"] is True and "aarch64" in w["replayed_in"]
    (ob,) = load_obligations([proof])
    values = {k: float(v["value"]) for k, v in w["values"].items()}
    assert replay(ob, values, arithmetic=KNOWN["aarch64"]) is True
    assert replay(ob, values) is False and replay(ob, values, arithmetic=KNOWN["x86-64-v3"]) is False


@pytest.mark.parametrize("extra, message", [
    (["--target", "sparc"], "--target 'sparc': no such arithmetic"),
    (["--target", "aarch64", "--semantics", "real"], "--semantics real and --target/--oracle exclude each other"),
    (["--target", "aarch64", "--oracle", "nowhere"], "--target aarch64 and --oracle DIR exclude each other"),
])
def test_prove_in_a_build_arithmetic_refuses_what_names_none(tmp_path, monkeypatch, capsys, extra, message):
    from navfn_smt.cli import main

    monkeypatch.chdir(tmp_path)
    assert main(["prove", "--report", "r.json", *extra]) == 2
    assert capsys.readouterr().err.startswith(f"navfn-smt: error: {message}")
    assert list(tmp_path.iterdir()) == []
