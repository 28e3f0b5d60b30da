"""``navfn-smt docs``: the committed invariants page is what the generator makes of the
obligations, the predicates' chains and the committed reports; ``--check`` names the first
differing line; bad inputs are one line with exit 2."""

import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parent.parent
PAGE = REPO / "docs" / "invariants.md"
REPORTS = REPO / "docs" / "reports"


def run(*args, cwd=REPO):
    p = subprocess.run([sys.executable, "-m", "navfn_smt", "docs", *map(str, args)], capture_output=True,
                       text=True, cwd=cwd, env={**os.environ, "COLUMNS": "200"})
    return p.returncode, p.stdout, p.stderr


@pytest.mark.fast
def test_committed_page_is_up_to_date():
    rc, out, err = run("--check")
    assert rc == 0, out + err
    assert "up to date" in out


def test_generated_page_is_the_committed_one_byte_for_byte(tmp_path):
    rc, out, err = run("--out", tmp_path / "inv.md")
    assert rc == 0, err
    assert (tmp_path / "inv.md").read_bytes() == PAGE.read_bytes()
    assert not [p for p in tmp_path.iterdir() if p.name.startswith(".")]  # no temporary file left


def test_an_edited_line_fails_the_check_naming_it(tmp_path):
    lines = PAGE.read_text().splitlines(keepends=True)
    n = next(i for i, ln in enumerate(lines) if "`update_keeps_a_lower_neighbour` |" in ln)
    lines[n] = lines[n].replace("refuted", "proved")
    copy = tmp_path / "invariants.md"
    copy.write_text("".join(lines))
    rc, out, err = run("--check", "--out", copy)
    assert rc == 1, out + err
    assert len(out.strip().splitlines()) == 1 and f"{copy}:{n + 1}:" in out, out
    assert copy.read_text() == "".join(lines)  # --check writes nothing


def test_a_missing_or_extra_line_fails_the_check(tmp_path):
    text = PAGE.read_text()
    copy = tmp_path / "invariants.md"
    copy.write_text(text + "one more line\n")
    rc, out, _ = run("--check", "--out", copy)
    n = len(text.splitlines()) + 1
    assert rc == 1 and f":{n}:" in out and "<end of file>" in out, out
    copy.write_text(text.rstrip("\n"))
    rc, out, _ = run("--check", "--out", copy)
    assert rc == 1 and "final newline" in out, out


@pytest.mark.fast
def test_the_page_lists_every_obligation_predicate_and_check_property():
    from navfn_smt.check.runner import CHECKABLE
    from navfn_smt.proofs import PREDICATES
    from navfn_smt.smt.obligation import load_obligations
    from navfn_smt.smt.runner import default_proof_files

    text = PAGE.read_text()
    for o in load_obligations(default_proof_files()):
        assert f"### `{o.name}`" in text and f"| {o.predicate} | `{o.name}` |" in text, o.name
    for p in PREDICATES:
        assert f"\n## {p.name}\n" in text and f"\n| {p.name} | " in text, p.name
    for name in CHECKABLE:
        assert f"### `{name}`" in text and f"| `{name}` | " in text, name


def test_every_trusted_step_is_on_the_page_and_the_docs_count_them_as_the_code_does():
    import re

    from navfn_smt.proofs import PREDICATES

    text = PAGE.read_text()
    steps = [t for p in PREDICATES for t in p.trusted]
    for t in steps:
        assert f"- {t}" in text, t[:80]
    fix = re.findall(r"every trusted step \((\d+) in all", (REPO / "docs" / "fix.md").read_text())
    proofs = re.findall(r"steps still trusted \((\d+)\)", (REPO / "docs" / "proofs.md").read_text())
    assert fix and proofs and {int(n) for n in fix + proofs} == {len(steps)}
    # the page's count line: trusted steps and run-time conditions, each condition once, as the code has them
    conditions = {c.name: c for p in PREDICATES for c in p.conditions}
    counts = re.findall(r"The chains take (\d+) trusted steps .*? and (\d+) run-time conditions", text)
    assert counts == [(str(len(steps)), str(len(conditions)))]
    for name in conditions:
        assert f"- *{name}* (" in text, name


@pytest.mark.fast
def test_every_kernel_names_its_cpp_code():
    """Where an obligation applies comes from the spec functions it runs: each needs its C++ place."""
    import inspect

    from navfn_smt.report.invariants_page import KERNEL_CODE, kernels_used
    from navfn_smt.smt.obligation import load_obligations
    from navfn_smt.smt.runner import default_proof_files
    from navfn_smt.spec import kernels

    public = {n for n, f in vars(kernels).items() if inspect.isfunction(f) and f.__module__ == kernels.__name__
              and not n.startswith("_")}
    assert public <= set(KERNEL_CODE), public - set(KERNEL_CODE)
    used = {o.name: kernels_used(o.build) for o in load_obligations(default_proof_files())}
    assert used["update_keeps_a_lower_neighbour"] == ["cell_update"]
    assert "step_offsets" in used["step_keeps_offset_in_unit_box"]  # through the proof file's helper
    # through a helper of another proof file (induction.py's update step): a segment of the spec's run
    assert used["update_keeps_a_neighbour_below_the_floor_at_the_updated_cell"] == ["propagation.propagate"]
    # the loops' steps the spec runs, named by their module
    assert "fix.descent_iteration" in used["descent_iteration_moves_strictly_down_or_stops_at_the_goal_or_the_budget"]
    assert "propagation.cycle_runs" in used["next_buffer_becomes_current_and_its_cycle_runs"]
    assert set(KERNEL_CODE) >= {k for ks in used.values() for k in ks}


@pytest.mark.fast
def test_statuses_come_from_the_reports():
    """Refuted with a witness, bounded with its bound, check sizes with their verdicts; the
    committed check reports are what the page's check rows say."""
    text = PAGE.read_text()
    assert "holds for `l < 1073741824.0`" in text
    refuted = [o for o in json.loads((REPORTS / "prove.json").read_text())["obligations"] if o["witness_values"]]
    assert refuted  # the report has replayed witnesses, and the page gives each one's values
    for o in refuted:
        first, v = next(iter(o["witness_values"]["values"].items()))
        assert f"counterexample: {first} = {v['value']!r}" in text, o["name"]
    for f in sorted(REPORTS.glob("check*.json")):
        for r in json.loads(f.read_text())["results"]:
            # the verdict, and after it the method when an induction decided the size
            assert f"| {r['size'][0]}x{r['size'][1]} | {r['interior_cells']} | {r['status']}" in text


@pytest.mark.fast
def test_a_certificate_is_linked_where_it_certifies_the_property():
    """A size's row links its committed certificate under exactly the properties the certificate
    gives a verdict for: 4x6's certificate covers start-reached, not complete (an induction's)."""
    import re

    from navfn_smt.check import certificate

    certified = {f.name: set(certificate.read(f)["verdicts"])
                 for f in (REPORTS / "certificates").glob("check-*.cert.json.gz")}
    assert certified
    linked, section = set(), None
    for line in PAGE.read_text().splitlines():
        if m := re.match(r"### `([a-z-]+)`", line):
            section = m.group(1)
        elif line.startswith("#"):  # another section (the checks in other arithmetics link no certificate)
            section = None
        elif line.startswith("| ") and section and (m := re.match(r"\| (\d+x\d+) \| \d+ \| proved", line)):
            link = re.search(r"\[(check-\d+x\d+\.cert\.json\.gz)\]", line)
            name = f"check-{m.group(1)}.cert.json.gz"
            assert (link is not None) == (name in certified and section in certified[name]), (section, line)
            if link:
                linked.add((section, name))
    assert ("start-reached", "check-4x6.cert.json.gz") in linked
    assert ("complete", "check-4x6.cert.json.gz") not in linked


def test_not_run_without_a_report(tmp_path):
    """An obligation missing from the prove report and a property no check report covers are
    listed as not run; the report's own time is the only one on the page (deterministic)."""
    doc = json.loads((REPORTS / "prove.json").read_text())
    doc["obligations"] = [o for o in doc["obligations"] if o["name"] != "goal_stays_zero"]
    (tmp_path / "prove.json").write_text(json.dumps(doc))
    check = json.loads(sorted(REPORTS.glob("check*.json"))[0].read_text())
    check["results"] = [r for r in check["results"] if r["property"] != "complete"]
    (tmp_path / "check-a.json").write_text(json.dumps(check))
    rc, out, err = run("--prove-report", tmp_path / "prove.json", "--out", tmp_path / "a.md")
    assert rc == 0, err
    text = (tmp_path / "a.md").read_text()
    assert ("| Monotone | `goal_stays_zero` | not run (known proved: declared) | not run (known proved: declared) |"
            in text)
    assert "| `complete` | not run |" in text
    rc, _, _ = run("--prove-report", tmp_path / "prove.json", "--out", tmp_path / "b.md")
    assert (tmp_path / "b.md").read_text() == text


def test_prove_markdown_is_the_same_generator(tmp_path):
    """`prove --markdown` renders through the docs generator: from the same verdicts it gives
    the same page but for the line naming the report (the prove report and the split report
    beside it, without the runs in other arithmetics, which only the docs generator joins in)."""
    import shutil

    from navfn_smt.commands.common import page_sources
    from navfn_smt.commands.docs import generate
    from navfn_smt.report import invariants_page as page
    from navfn_smt.report.proofs import markdown

    doc = json.loads((REPORTS / "prove.json").read_text())
    checks = sorted(REPORTS.glob("check*.json"))
    meta = {k: v for k, v in doc.items() if k in ("when", "timeout", "solvers", "semantics")}
    a = markdown(page.outcomes_of(doc), meta, page_sources(checks, REPORTS)).splitlines()
    alone = tmp_path / "reports"
    alone.mkdir()
    for name in ("prove.json", "split.json"):
        shutil.copy(REPORTS / name, alone / name)
    b = generate(alone / "prove.json", checks).splitlines()
    assert len(a) == len(b)
    differ = [(x, y) for x, y in zip(a, b) if x != y]
    assert len(differ) == 1 and differ[0][1].startswith("Proofs: [reports/prove.json]"), differ


@pytest.mark.fast
def test_the_page_joins_the_runs_in_other_arithmetics_beside_the_report(tmp_path):
    """The committed runs in x86-64-v3's and aarch64's arithmetic (prove-NAME.json beside
    prove.json) each add a column; a file there that is no run in its arithmetic alone is refused."""
    from navfn_smt.errors import NavfnInputError
    from navfn_smt.report import invariants_page as page

    doc = page.with_arithmetics(page.read_prove_report(REPORTS / "prove.json"), REPORTS / "prove.json")
    assert doc["semantics"] == ["real", "fp32", "fp32@x86-64-v3", "fp32@aarch64"]
    assert {o["semantics"] for o in doc["obligations"]} == set(doc["semantics"])
    bad = json.loads((REPORTS / "prove.json").read_text())
    (tmp_path / "prove.json").write_text(json.dumps(bad))
    (tmp_path / "prove-aarch64.json").write_text(json.dumps(bad))  # real and fp32, not fp32@aarch64
    with pytest.raises(NavfnInputError, match="not a run in fp32@aarch64 alone"):
        page.with_arithmetics(bad, tmp_path / "prove.json")


@pytest.mark.fast
@pytest.mark.parametrize("what", ["missing", "malformed", "not-a-report", "check-missing", "check-malformed",
                                  "check-not-a-report", "out-dir-missing", "check-page-missing"])
def test_bad_inputs_are_one_line_with_exit_2(tmp_path, what):
    prove = REPORTS / "prove.json"
    args = ["--out", tmp_path / "inv.md"]
    bad = tmp_path / "bad.json"
    if what == "missing":
        args += ["--prove-report", tmp_path / "nope.json"]
    elif what == "malformed":
        bad.write_text('{"obligations": [')
        args += ["--prove-report", bad]
    elif what == "not-a-report":
        bad.write_text('{"results": []}')
        args += ["--prove-report", bad]
    elif what == "check-missing":
        args += ["--check-report", tmp_path / "nope.json"]
    elif what == "check-malformed":
        bad.write_text("not json")
        args += ["--check-report", bad]
    elif what == "check-not-a-report":
        shutil.copy(prove, bad)
        args += ["--check-report", bad]
    elif what == "out-dir-missing":
        args = ["--out", tmp_path / "no" / "inv.md"]
    elif what == "check-page-missing":
        args = ["--check", "--out", tmp_path / "inv.md"]
    rc, out, err = run(*args)
    assert rc == 2, out + err
    assert "Traceback" not in err and len(err.strip().splitlines()) == 1 and err.startswith("navfn-smt: error:"), err
    assert not (tmp_path / "inv.md").exists()


@pytest.mark.fast
def test_help_lists_every_option():
    rc, out, _ = run("--help")
    assert rc == 0
    for opt in ("--out", "--check", "--prove-report", "--check-report"):
        assert opt in out


def test_docs_without_out_prints_the_page_and_writes_nothing(tmp_path):
    rc, out, err = run("--prove-report", REPORTS / "prove.json", cwd=tmp_path)
    assert rc == 0, err
    assert out == PAGE.read_text(encoding="utf-8")
    assert list(tmp_path.iterdir()) == []


def test_parts_replayed_so_far_are_listed_in_their_order():
    """A size replayed in parts lists its parts by number (1, 2, ..., 10), not as text sorts them."""
    import re

    rows = [line for line in PAGE.read_text().splitlines() if "replayed in parts so far" in line]
    for row in rows:
        numbers = [int(k) for k in re.findall(r"\[(\d+)\]\(reports/certificates/parts/", row)]
        assert numbers == sorted(numbers) and len(numbers) == len(set(numbers)), row[:200]


def test_the_checks_in_other_arithmetics_have_their_section_with_x86s_verdict_beside():
    """The committed aarch64 check reports (docs/reports/aarch64/VARIANT/) are read apart from
    x86-64's (they never replace its rows) and shown per arithmetic and variant; a verdict that
    differs from x86-64's at the same size has x86-64's beside it, and a refuted property its
    smallest counterexample; a made-up report that differs shows so."""
    from navfn_smt.report import invariants_page as page

    x86 = sorted(REPORTS.glob("check*.json"))
    flavoured = page.flavoured_check_reports(x86)
    assert flavoured and all(f.parent.parent.name == "aarch64" for f in flavoured)
    assert "original" in {f.parent.name for f in flavoured} <= {"original", "fixed"}
    text = PAGE.read_text()
    assert "## Whole-planner properties in other build arithmetics" in text and "### aarch64, original" in text
    checks = [(page.report_label(p), page.read_check_report(p)) for p in x86]
    doc = json.loads(flavoured[0].read_text())
    size = next(r["size"] for r in doc["results"])
    mine = {**doc, "planner": {"arithmetic": "aarch64"}, "variant": "original",
            "results": [{**r, "status": "refuted", "counterexample": {"mode": "astar", "start": [1, 1], "goal": [1, 1],
                                                                        "reason": "made up"}}
                        for r in doc["results"] if r["property"] == "start-reached"]}
    lines = page.flavoured_section([("made-up.json", mine)], checks)
    row = next(line for line in lines if line.startswith(f"| {size[0]}x{size[1]} |"))
    assert "refuted (x86-64: proved)" in row
    assert any("smallest counterexample" in line and "made up" in line for line in lines)
