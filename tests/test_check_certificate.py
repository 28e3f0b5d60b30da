"""Certificates of bounded checks: written for a proved size, replayed without searching, and
refused when they do not re-check (a changed code hash, a path tree that does not close, a
case without its root path, marks that do not support the verdicts, a recorded unsat that is
not, cases that are not those of the size), and a seeded mutation run of the checker itself."""

import gzip
import json
import subprocess
import sys
from pathlib import Path

import pytest

from navfn_smt.check import certificate as C
from navfn_smt.errors import NavfnInputError
from navfn_smt.spec import fixes

REPORTS = Path(__file__).resolve().parents[1] / "docs" / "reports"
FAST = ("bitwuzla",)  # the tests ask bitwuzla (fast); which solver answers is not what they test


def _cli(*args):
    return subprocess.run([sys.executable, "-m", "navfn_smt", *args], capture_output=True, text=True)


@pytest.fixture(scope="module")
def cert(tmp_path_factory):
    d = tmp_path_factory.mktemp("certs")
    r = _cli("check", "complete", "start-reached", "--size", "3", "5", "--certificates", str(d))
    assert r.returncode == 0, r.stdout + r.stderr
    return d / "check-3x5.cert.json.gz"


def _edit(src, dst, change):
    doc = json.loads(gzip.decompress(src.read_bytes()))
    change(doc)
    dst.write_bytes(gzip.compress(json.dumps(doc).encode()))
    return dst


def test_a_proved_size_writes_a_certificate_that_replays(cert):
    got = C.replay(cert)
    assert got["status"] == "replayed", got["problems"]
    assert got["verdicts"] == {"complete": "proved", "start-reached": "proved"}
    doc = C.read(cert)  # 3x5 is narrow: complete by the induction, start-reached explored alone
    assert doc["properties"] == ["start-reached"] and doc["induction"]["complete"].startswith("induction: FallbackPath")
    assert got["paths"] >= got["cases"] > 0
    r = _cli("check", "--replay", str(cert))
    assert r.returncode == 0 and "replayed" in r.stdout


def test_start_reached_alone_records_flips_up_to_the_queued_start(cert):
    """Explored alone, start-reached flips a path's branches only up to the mark where the run
    queued the start for certain (QueuedStartReached): the certificate records that many flips,
    fewer than the path's branches on some paths, and the replay asks for exactly as many."""
    from navfn_smt.check import bounded as B
    from navfn_smt.smt.domains import FPDomain

    doc = C.read(cert)
    lo, hi = doc["costs"]
    cut = 0
    for key, _, log in doc["cases"]:
        case = C.case_of(key)
        inner = [k for k in B.interior(case.nx, case.ny) if k not in case.lethal]
        for seed, bound, _, flips, _ in log:
            D, _, sp, _ = B.run_of(doc["properties"])(case, dict(zip(inner, seed)), lo, hi, FPDomain)
            last = B.flippable(doc["properties"], D.branches, sp, lo)
            assert bound + len(flips) == last or (not flips and bound >= last)
            cut += last < len(D.branches)
    assert cut > 0


def test_a_changed_code_hash_is_refused(cert, tmp_path):
    bad = _edit(cert, tmp_path / "c.gz", lambda d: d.update(code_hash="0" * 64))
    got = C.replay(bad)
    assert got["status"] == "refused" and "changed" in got["problems"][0]
    assert _cli("check", "--replay", str(bad)).returncode == 1


def _first_with_flips(doc):
    return next(p for _, _, log in doc["cases"] for p in log if p[3])


def test_a_wrong_branch_count_is_refused(cert, tmp_path):
    bad = _edit(cert, tmp_path / "c.gz", lambda d: _first_with_flips(d).__setitem__(3, _first_with_flips(d)[3] + "u"))
    assert C.replay(bad, order=FAST)["status"] == "refused"


def test_a_sat_flip_recorded_unsat_is_refused(cert, tmp_path):
    def lie(doc):
        p = next(p for _, _, log in doc["cases"] for p in log if "s" in p[3])
        p[3] = p[3].replace("s", "u", 1)
    assert C.replay(_edit(cert, tmp_path / "c.gz", lie), order=FAST)["status"] == "refused"


def test_the_branches_the_box_decided_are_recorded_and_asked(cert):
    """Every path records the value of each branch its box decided (no flip was asked there), and
    the replay asks a solver that each holds on the whole box."""
    doc = C.read(cert)
    assert doc["format"] == C.FORMAT
    decided = [p[4] for _, _, log in doc["cases"] for p in log]
    assert sum(map(len, decided)) > 0 and all(set(d) <= {"t", "f"} for d in decided)
    got = C.replay(cert, order=FAST)
    assert got["status"] == "replayed" and got["evidence"]["interval_decisions_asked"] == sum(map(len, decided))


def _flip_a_decision(doc):
    p = next(p for _, _, log in doc["cases"] for p in log if p[4])
    p[4] = ("f" if p[4][0] == "t" else "t") + p[4][1:]


def test_a_flipped_interval_decision_is_refused(cert, tmp_path):
    """The mutation of #35's kind for the intervals: one recorded decision flipped, and the replay's
    solver finds a map of the box where the recorded value is false (the seed itself)."""
    got = C.replay(_edit(cert, tmp_path / "c.gz", _flip_a_decision), order=FAST)
    assert got["status"] == "refused" and "the branches the box decided" in got["problems"][0], got["problems"]


def test_a_missing_interval_decision_is_refused(cert, tmp_path):
    def drop(doc):
        p = next(p for _, _, log in doc["cases"] for p in log if p[4])
        p[4] = p[4][1:]
    got = C.replay(_edit(cert, tmp_path / "c.gz", drop), order=FAST)
    assert got["status"] == "refused" and "branches decided by the box" in got["problems"][0], got["problems"]


def test_a_certificate_of_format_1_replays_with_the_decisions_trusted(cert, tmp_path):
    """Certificates written before the decisions were recorded keep their paths of four entries:
    they replay as before, and the report says the box's decisions were not asked."""
    def old(doc):
        doc["format"] = C.FORMAT_1
        for _, _, log in doc["cases"]:
            for p in log:
                p.pop()
    got = C.replay(_edit(cert, tmp_path / "c.gz", old), order=FAST)
    assert got["status"] == "replayed" and got["interval_decisions_recorded"] is False
    assert "interval_decisions_asked" not in got["evidence"]
    mixed = _edit(cert, tmp_path / "m.gz", lambda d: d.update(format=C.FORMAT_1))  # five entries under format 1
    assert C.replay(mixed, order=FAST)["status"] == "refused"


def test_a_missing_path_is_refused(cert, tmp_path):
    def drop(doc):
        log = next(log for _, _, log in doc["cases"] if len(log) > 1)
        log.pop()
    assert C.replay(_edit(cert, tmp_path / "c.gz", drop), order=FAST)["status"] == "refused"


def test_a_missing_case_is_refused(cert, tmp_path):
    got = C.replay(_edit(cert, tmp_path / "c.gz", lambda d: d["cases"].pop()), order=FAST)
    assert got["status"] == "refused" and "has no entry" in got["problems"][0]


def test_an_unreadable_certificate_is_a_clear_error(tmp_path):
    p = tmp_path / "x.gz"
    p.write_text("not gzip")
    with pytest.raises(NavfnInputError):
        C.read(p)
    r = _cli("check", "--replay", str(p))
    assert r.returncode != 0 and "Traceback" not in r.stderr and "not a check certificate" in r.stderr


FLAVOURED = sorted(REPORTS.glob("aarch64/*/certificates/check-*.cert.json.gz"))  # check --target aarch64


@pytest.mark.parametrize("path", sorted((REPORTS / "certificates").glob("check-*.cert.json.gz")) + FLAVOURED,
                         ids=lambda p: p.name)
def test_every_committed_certificate_is_of_this_code(path):
    """The committed certificates were written by the code as it is, or are carried to it: the
    transcripts recorded under the code that wrote them and under this code are equal (a change
    to the kernels or the encoding that changes their queries must come with new certificates);
    the CI replays the four corridors of 7 and 8 cells, the others replay by hand (.ci/run)."""
    doc = C.read(path)
    now = C.code_hash(doc["properties"])
    assert doc["code_hash"] == now or C.carried(path.name, doc, C.digest(path), now)


COMMITTED = REPORTS / "certificates"


def _current(path):
    """A committed certificate as this code's: written by it, or carried to it by equal
    transcripts (then its code hash is set to this code's, in memory, as the carry allows), so
    a test of the other checks starts from a certificate that replays."""
    doc = C.read(path)
    now = C.code_hash(doc["properties"])
    if doc["code_hash"] != now:
        assert C.carried(Path(path).name, doc, C.digest(path), now), path
        doc["code_hash"] = now
    return doc


def _doc(name):
    return _current(COMMITTED / name)


def _refused(doc, first: str, memo=None):
    """The replay of ``doc`` refuses it, naming ``first`` in its first problem (with a memo the
    replay stops at that problem)."""
    got = C.replay(None, doc=doc, order=FAST, memo={} if memo is None else memo)
    assert got["status"] == "refused" and first in got["problems"][0], got["problems"][:1]
    return got


def _every_path(doc):
    return [p for _, _, log in doc["cases"] for p in log]


EDITS = {"empty": "no control path is recorded", "no-root": "root",
         "unknown": "marks start-reached unknown; the certificate calls it proved",
         "refuted": "marks start-reached refuted; the certificate calls it proved"}


def _edited(edit):
    """Issue 35's edits of 3x7's committed certificate: every path log emptied, every root
    path dropped, every property mark set to unknown, every one set to refuted."""
    doc = _doc("check-3x7.cert.json.gz")
    for _, _, log in doc["cases"]:
        if edit == "empty":
            log.clear()
        elif edit == "no-root":
            log[:] = [p for p in log if p[1] != 0]
        else:
            for p in log:
                p[2] = {"unknown": "?", "refuted": "r"}[edit] * len(p[2])
    return doc


def test_a_certificate_that_proves_nothing_is_refused(tmp_path):
    """Issue 35's four edits each replayed as a proof before; each is refused now, with the first
    problem named, by the checker and by the command (non-zero exit, no traceback)."""
    for edit, first in EDITS.items():
        _refused(_edited(edit), first)
    bad = tmp_path / "c.gz"
    bad.write_bytes(gzip.compress(json.dumps(_edited("refuted")).encode()))
    r = _cli("check", "--replay", str(bad), "--solver", "bitwuzla", "--jobs", "1")
    assert r.returncode == 1 and "Traceback" not in r.stderr and EDITS["refuted"] in r.stdout


def test_a_child_without_its_parent_and_a_flip_without_its_child_are_refused():
    doc = _doc("check-3x7.cert.json.gz")
    log = next(log for _, _, log in doc["cases"] if len(log) > 2)
    parent = next(p for p in log if "s" in p[3])
    j = parent[1] + parent[3].index("s")
    child = next(p for p in log if p[1] == j + 1)
    memo: dict = {}  # the cases before the corrupted one are re-checked once; a replay stops at a problem
    child[1] += 1  # the child claims another flip
    _refused(doc, "has no parent", memo)
    child[1] -= 1
    log.remove(child)  # the flip is recorded sat, its path is gone
    got = C.replay(None, doc=doc, order=FAST, memo=memo)
    assert got["status"] == "refused" and ("no recorded path takes it" in got["problems"][0]
                                           or "has no parent" in got["problems"][0])


def test_a_verdict_the_paths_do_not_give_is_refused(cert):
    doc = C.read(cert)
    doc["verdicts"]["start-reached"] = "refuted"  # every path holds it; nothing refutes it
    _refused(doc, "no recorded map refutes it")
    doc = C.read(cert)
    doc["verdicts"]["complete"] = "refuted"  # the induction that decides it says proved
    _refused(doc, "what is known today gives proved")
    doc = C.read(cert)
    doc["verdicts"]["valid-path"] = "proved"  # neither explored nor by an induction
    _refused(doc, "neither the paths nor a named induction")


@pytest.fixture(scope="module")
def refuting(tmp_path_factory):
    """A certificate with a refuted property beside a proved one (3x3: valid-path fails there)."""
    d = tmp_path_factory.mktemp("refuting")
    r = _cli("check", "valid-path", "start-reached", "--size", "3", "3", "--certificates", str(d))
    assert r.returncode == 1 and "refuted" in r.stdout, r.stdout + r.stderr
    return d / "check-3x3.cert.json.gz"


def test_a_refuted_verdict_needs_a_map_that_refutes_it_on_the_spec(refuting):
    from navfn_smt.check.certificate import _witness_problems

    doc = C.read(refuting)
    got = C.replay(None, doc=doc, order=FAST)
    assert got["status"] == "replayed" and got["verdicts"]["valid-path"] == "refuted", got["problems"]
    assert got["evidence"]["refutations_witnessed"] >= 1
    assert _witness_problems(doc, set()) == []  # the header's witness refutes it on its own
    w = doc["witnesses"]["valid-path"]
    w["costs"] = [[254, 254, 254], [254, 50, 254], [254, 254, 254]]  # a passable cell: the path is valid
    assert "no recorded map refutes it" in _witness_problems(doc, set())[0]
    for _, _, log in doc["cases"]:  # and no path's seed is said to refute it either
        for p in log:
            p[2] = p[2].replace("r", "?")
    _refused(doc, "no recorded map refutes it")


def test_costs_below_one_are_refused_where_nan_would_make_the_intervals_unsound(cert):
    """At cost 0 updateCell divides 0 by 0: a NaN, for which the concolic same-term shortcut
    (``x <= x`` decided true) is wrong; a check and a replay refuse such a box."""
    import math

    from navfn_smt.check.concolic import ConcolicDomain
    from navfn_smt.smt.domains import FPDomain
    from navfn_smt.spec.kernels import planar_wave
    from navfn_smt.spec.numeric import CONCRETE as N

    zero = N.f32const(0.0)  # planar_wave's div = dc / hf (built on both sides of its branch): 0/0 at cost 0
    assert math.isnan(N.div(zero, zero)) and planar_wave(N, *(N.f32const(100.0),) * 4, zero) == 100.0
    D = ConcolicDomain(FPDomain())
    x = D.cost_as_f32(D.cost(1, 0, 253, "c"))
    q = D.div(D.sub(x, x), x)  # 0/0 at cost 0, 0 elsewhere: the box holds a NaN
    assert D.truth(D.le(q, q)) is True  # decided for the whole box, false at cost 0
    r = _cli("check", "start-reached", "--size", "3", "4", "--costs", "0..253")
    assert r.returncode != 0 and "at least 1" in r.stderr and "Traceback" not in r.stderr
    doc = C.read(cert)
    doc["costs"] = [0, 253]
    _refused(doc, "costs below 1")


# ---------------------------------------------------------------------------------------
# The checker's own mutation test
# ---------------------------------------------------------------------------------------
MUTATIONS = 200  # at least 200 (issue 35)


def _mutate(doc, rng):
    """One random single-field corruption of ``doc`` (in place): ``(what, where)``; ``where`` is
    ``("seed", case index, path index)`` for a seed's cost, ``("mark", property, new mark)`` for
    a property's mark, else None."""
    import random  # noqa: F401  (rng is a random.Random)

    cases = doc["cases"]
    ci = rng.randrange(len(cases))
    key, _, log = cases[ci]
    pi = rng.randrange(len(log))
    path = log[pi]
    kind = rng.choice(["seed"] * 6 + ["bound"] * 2 + ["mark"] * 2 + ["flip"] * 2
                      + ["flip count", "case", "weight", "hash", "header", "path"])
    if kind == "seed" and path[0]:
        k = rng.randrange(len(path[0]))
        lo, hi = doc["costs"]
        path[0][k] = rng.choice([rng.randint(lo, hi), lo, hi, hi + 1, lo - 1])
        return f"case {ci} path {pi}: seed cost {k} -> {path[0][k]}", ("seed", ci, pi)
    if kind in ("seed", "bound"):
        path[1] = rng.choice([path[1] + 1, max(0, path[1] - 1), rng.randint(0, 12)])
        return f"case {ci} path {pi}: bound -> {path[1]}", None
    if kind == "mark":
        k = rng.randrange(len(path[2]))
        path[2] = path[2][:k] + rng.choice([m for m in "iqr?" if m != path[2][k]]) + path[2][k + 1:]
        return f"case {ci} path {pi}: mark {k} -> {path[2]}", ("mark", doc["properties"][k], path[2][k])
    if kind == "flip" and path[3]:
        k = rng.randrange(len(path[3]))
        path[3] = path[3][:k] + rng.choice([m for m in "us?" if m != path[3][k]]) + path[3][k + 1:]
        return f"case {ci} path {pi}: flip {k} -> {path[3]}", None
    if kind in ("flip", "flip count"):
        path[3] = path[3][:-1] if path[3] and rng.random() < 0.5 else path[3] + rng.choice("us")
        return f"case {ci} path {pi}: flips -> {path[3]!r}", None
    if kind == "case":
        field = rng.randrange(6)
        nx, ny = key[0], key[1]
        cells = [x for x in range(nx * ny) if 0 < x % nx < nx - 1 and 0 < x // nx < ny - 1]
        if field == 2:
            key[2] = sorted(set(key[2]) ^ {rng.choice(cells)})
        elif field in (3, 4):
            c = rng.choice(cells)
            key[field] = [c % nx, c // nx]
        elif field == 5:
            key[5] = not key[5]
        else:
            key[field] += rng.choice([-1, 1])
        return f"case {ci}: key field {field} -> {key}", None
    if kind == "weight":
        cases[ci][1] += rng.choice([-1, 1, 2])
        return f"case {ci}: weight -> {cases[ci][1]}", None
    if kind == "hash":
        h = doc["code_hash"]
        k = rng.randrange(len(h))
        doc["code_hash"] = h[:k] + ("0" if h[k] != "0" else "1") + h[k + 1:]
        return "code hash", None
    if kind == "path":
        if rng.random() < 0.5 and len(log) > 1:
            log.pop(pi)
            return f"case {ci}: path {pi} dropped", None
        log.insert(pi, json.loads(json.dumps(path)))
        return f"case {ci}: path {pi} doubled", None
    field = rng.choice(["total", "outside", "costs", "size", "modes", "verdicts", "properties"])
    if field in ("total", "outside"):
        doc[field] += rng.choice([-1, 1])
    elif field == "costs":
        doc["costs"] = rng.choice([[0, doc["costs"][1]], [doc["costs"][0], 254], [doc["costs"][0] - 1, 253]])
    elif field == "size":
        doc["size"] = [doc["size"][1], doc["size"][0]]
    elif field == "modes":
        doc["modes"] = doc["modes"][:1]
    elif field == "verdicts":
        n = rng.choice(sorted(doc["verdicts"]))
        doc["verdicts"][n] = {"proved": "refuted", "refuted": "proved"}[doc["verdicts"][n]]
    else:
        doc["properties"] = doc["properties"] + ["valid-path"] if "valid-path" not in doc["properties"] else []
    return f"header {field}", None


def _harmless(doc, original, where) -> bool:
    """Whether a corruption leaves what the certificate proves as it was: a seed's cost changed
    where the run from the new seed records the same branch terms as from the old one, up to the
    point the search stops flipping (the same flips, so the same queries), or a mark of a refuted property turned refuted or
    unknown (such marks are not evidence: the verdict rests on a map replayed on the spec)."""
    from navfn_smt.check import bounded as B
    from navfn_smt.smt.domains import FPDomain

    if where is None:
        return False
    if where[0] == "mark":
        return doc["verdicts"][where[1]] == "refuted" and where[2] in "r?"
    _, ci, pi = where
    key, _, log = doc["cases"][ci]
    case = C.case_of(key)
    inner = [k for k in B.interior(case.nx, case.ny) if k not in case.lethal]
    lo, hi = doc["costs"]
    run, names = B.run_of(doc["properties"]), doc["properties"]

    def flipped(seed):  # the branches the rule lets the search flip (flippable), as terms
        D, _, sp, _ = run(case, dict(zip(inner, seed)), lo, hi, FPDomain, fixes.named(doc["variant"]))
        return D.branches[:B.flippable(names, D.branches, sp, lo)]

    new, old = flipped(log[pi][0]), flipped(original["cases"][ci][2][pi][0])
    return len(new) == len(old) and all(a.eq(b) for a, b in zip(new, old))


def test_the_checker_refuses_every_harmful_corruption_of_a_committed_certificate(refuting, capsys):
    """A seeded run of single-field corruptions (a seed's cost, a bound, a property mark, a flip
    mark, a branch count, a case key, a weight, the hash, a header field, a path dropped or
    doubled) of 3x7's and 7x3's committed certificates and of a 3x3 certificate with a refuted
    property: each is refused, or shown harmless here (:func:`_harmless`: the certificate still
    proves exactly what it did).  Replays share answers
    (a memo of each case's result by its entry, and of unsats by their query), so only what a
    corruption changed is re-checked."""
    import random

    rng = random.Random(35)
    sources = [COMMITTED / "check-3x7.cert.json.gz", COMMITTED / "check-7x3.cert.json.gz", refuting]
    memo: dict = {}
    for src in sources:
        assert C.replay(None, doc=_current(src), order=FAST, memo=memo)["status"] == "replayed", src
    tried = refused = harmless = 0
    for i in range(MUTATIONS):
        src = sources[i % len(sources)]
        original = _current(src)
        doc = _current(src)
        what, where = _mutate(doc, rng)
        while doc == original:  # a draw that changed nothing (a bound already 0 lowered) is drawn again
            what, where = _mutate(doc, rng)
        tried += 1
        got = C.replay(None, doc=doc, order=FAST, memo=memo)
        if got["status"] == "refused":
            refused += 1
            continue
        assert _harmless(doc, original, where), f"{src.name}: {what} replays as a proof"
        harmless += 1
    with capsys.disabled():
        print(f"\ncertificate mutations: {tried} tried, {refused} refused, {harmless} harmless")
    assert tried >= 200 and refused + harmless == tried and refused > harmless


@pytest.mark.parametrize("path", sorted((REPORTS / "certificates").glob("check-*.replay.json"))
                         + sorted((REPORTS / "certificates" / "parts").glob("check-*.replay-*of*.json")),
                         ids=lambda p: p.name)
def test_a_committed_replay_report_is_of_its_committed_certificate(path):
    """The invariants page shows each certified size's trusted count from its replay report (or
    the parts replayed so far): the report re-checked the certificate committed beside it (the
    same bytes), and it replayed."""
    doc = json.loads(path.read_text())
    name = path.name.split(".replay")[0] + ".cert.json.gz"
    cert = REPORTS / "certificates" / name
    assert doc["certificate_sha256"] == C.digest(cert) and doc["status"] == "replayed"
    t = doc["trusted"]
    assert t["count"] == t["held_on_box_by_intervals"] + t["paths_cut_by_queued_start"] + t["cases_by_reduction"]


def test_the_invariants_page_shows_a_replays_trusted_count(tmp_path):
    from navfn_smt.report.invariants_page import _replayed

    assert _replayed(tmp_path / "none.replay.json") == "; not replayed"
    report = tmp_path / "check-3x3.replay.json"
    report.write_text(json.dumps({"status": "replayed", "evidence": {"unsat_reasked": {"cvc5": 3}},
                                  "trusted": {"count": 7, "held_on_box_by_intervals": 4,
                                              "paths_cut_by_queued_start": 1, "cases_by_reduction": 2}}))
    text = _replayed(report)
    assert "3 by cvc5" in text and "trusted 7: 4 held on the box" in text


def _parts(doc, n, sha="x"):
    """The reports of the n parts of ``doc``'s replay, as ``check --replay --part --json`` writes them."""
    out = []
    for k in range(1, n + 1):
        got = C.replay(None, doc=doc, order=FAST, part=(k, n))
        out.append({"command": "check --replay", "certificate_sha256": sha, "check_intervals": False, **got})
    return out


def test_a_replay_in_parts_is_the_whole_replay_once_every_part_is(refuting):
    """3x3 (a refuted property, witnessed by some part's seeds): three parts tile the cases, and
    combined they give the whole replay's counts; a part refused, missing, twice, of another
    certificate or asked of other solvers refuses the whole."""
    doc = C.read(refuting)
    whole = C.replay(None, doc=doc, order=FAST)
    parts = _parts(doc, 3)
    assert [p["case_range"] for p in parts] == [list(C.part_range(len(doc["cases"]), (k, 3))) for k in (1, 2, 3)]
    assert parts[0]["case_range"][0] == 0 and parts[-1]["case_range"][1] == len(doc["cases"])
    got = C.combine(doc, "x", parts)
    assert got["status"] == "replayed" and got["parts"] == 3, got["problems"]
    for key in ("cases", "paths", "evidence", "trusted", "verdicts"):
        assert got[key] == whole[key], key
    for parts_now, says in [
        (parts[:2], "not each of 1/3 to 3/3 once"),
        (parts + parts[:1], "not each of 1/3 to 3/3 once"),
        ([parts[0], {**parts[1], "certificate_sha256": "y"}, parts[2]], "part 2/3 is the replay of another"),
        ([parts[0], {**parts[1], "status": "refused", "problems": ["p"]}, parts[2]], "part 2/3 did not replay: p"),
        ([parts[0], {**parts[1], "solvers": ["cvc5"]}, parts[2]], "part 2/3 was replayed with solvers"),
        ([parts[0], {**parts[1], "case_range": [0, 1]}, parts[2]], "part 2/3 covers cases [0, 1]"),
        (parts[:1] + _parts(doc, 2)[1:], "different splits"),
    ]:
        bad = C.combine(doc, "x", parts_now)
        assert bad["status"] == "refused" and any(says in p for p in bad["problems"]), (says, bad["problems"])
    # the witness of the refuted property is judged over all parts: with it gone, refused
    no_witness = {k: v for k, v in doc.items() if k != "witnesses"}
    forged = [{**p, "witnessed": []} for p in parts]
    assert "no recorded map refutes it" in C.combine(no_witness, "x", forged)["problems"][0]


def test_parts_on_the_command_line(cert, tmp_path):
    reports = []
    for k in (1, 2):
        out = tmp_path / f"p{k}.json"
        r = _cli("check", "--replay", str(cert), "--part", f"{k}/2", "--solver", "bitwuzla", "--json", str(out))
        assert r.returncode == 0 and f"part {k}/2 replayed" in r.stdout, r.stdout + r.stderr
        reports.append(str(out))
    r = _cli("check", "--replay", str(cert), "--combine", *reports, "--json", str(tmp_path / "whole.json"))
    assert r.returncode == 0 and "replayed: complete proved" in r.stdout, r.stdout + r.stderr
    assert json.loads((tmp_path / "whole.json").read_text())["parts"] == 2
    r = _cli("check", "--replay", str(cert), "--combine", reports[0])
    assert r.returncode == 1 and "not each of 1/2 to 2/2 once" in r.stdout
    for bad, says in [("3/2", "K must be 1 to N"), ("x", "give K/N")]:
        r = _cli("check", "--replay", str(cert), "--part", bad)
        assert r.returncode == 2 and says in r.stderr and "Traceback" not in r.stderr


def test_the_invariants_page_shows_a_replay_done_in_parts_so_far(tmp_path):
    from navfn_smt.report.invariants_page import _replayed

    (tmp_path / "parts").mkdir()
    for k, status in ((1, "replayed"), (2, "refused")):
        (tmp_path / "parts" / f"check-4x6.replay-{k}of12.json").write_text(json.dumps(
            {"status": status, "part": [k, 12], "paths": 1234}))
    text = _replayed(tmp_path / "check-4x6.replay.json")
    assert "in parts so far: 1 of 12" in text and "1,234 control paths" in text


def test_a_certificate_carries_to_changed_code_only_when_its_transcript_is_the_same(tmp_path, monkeypatch):
    """The transcript (every query a replay asks, by its text, and every decision) is the same
    in every run; a certificate whose code hash is not this code's replays only when the
    transcripts recorded under both codes are equal, and a recorded transcript that differs,
    or none at all, refuses it."""
    cert = REPORTS / "certificates" / "check-3x7.cert.json.gz"  # 82 queries
    doc = C.read(cert)
    first, again = C.transcript(doc), C.transcript(doc)
    assert first == again and first["queries"] == 82 and first["code_hash"] == C.code_hash(doc["properties"])
    old = _edit(cert, tmp_path / "check-3x7.cert.json.gz", lambda d: d.update(code_hash="0" * 64))
    sha, now = C.digest(old), first["code_hash"]
    record = tmp_path / "transcripts.json"
    monkeypatch.setattr(C, "TRANSCRIPTS", record)

    def write(then_sha):
        record.write_text(json.dumps({old.name: {"certificate_sha256": sha, "transcripts": {
            "0" * 64: {"sha256": then_sha}, now: {"sha256": first["sha256"]}}}}))

    assert "no recorded transcript carries it" in C.replay(old, order=FAST)["problems"][0]
    write(first["sha256"])
    got = C.replay(old, order=FAST)
    assert got["status"] == "replayed" and got["carried"] == {"from": "0" * 64, "to": now}, got["problems"]
    write("f" * 64)  # the code that wrote it asked something else
    assert C.replay(old, order=FAST)["status"] == "refused"
    assert not C.carried(old.name, C.read(old), "another sha", now)


@pytest.mark.parametrize("path", sorted((REPORTS / "certificates").glob("check-*.cert.json.gz")), ids=lambda p: p.name)
def test_every_recorded_transcript_is_of_its_committed_certificate(path):
    """docs/reports/certificates/transcripts.json: each entry names the bytes of the certificate
    committed under its name, and holds the transcript under the code that wrote it."""
    record = C.recorded_transcripts().get(path.name)
    if record is None:
        pytest.skip(f"no transcript recorded for {path.name}")
    assert record["certificate_sha256"] == C.digest(path)
    assert C.read(path)["code_hash"] in record["transcripts"]


def test_the_aarch64_certificates_are_its_reports_and_the_small_ones_replay():
    """docs/reports/aarch64/VARIANT/: each size's report and its certificate are of aarch64's
    float32 semantics, name the same verdicts, and the certificate's file name says its
    arithmetic and variant; those of at most 3 interior cells replay here (seconds; the others
    replayed by hand, figures in the session's note)."""
    assert len(FLAVOURED) >= 12  # every size of at most 6 interior cells but 4x5 and 5x4, NavFn as shipped
    for path in FLAVOURED:
        doc = C.read(path)
        variant = path.parent.parent.name
        nx, ny = doc["size"]
        assert doc["semantics"] == "fp32@aarch64" and doc["variant"] == variant
        assert path.name == f"check-{nx}x{ny}" + ("" if variant == "original" else "-fixed") + "-aarch64.cert.json.gz"
        reports = [json.loads(f.read_text()) for f in sorted(path.parent.parent.glob("check-*.json"))]
        assert reports and all(r["semantics"] == "fp32@aarch64" and r["variant"] == variant for r in reports)
        got = {r["property"]: r["status"] for rep in reports for r in rep["results"] if r["size"] == [nx, ny]}
        assert got, f"no report of {nx}x{ny} beside {path.name}"
        assert {n: v for n, v in doc["verdicts"].items() if n in got} == {n: got[n] for n in doc["verdicts"] if n in got}
        if (nx - 2) * (ny - 2) <= 3:
            r = _cli("check", "--replay", str(path), "--solver", "bitwuzla")
            assert r.returncode == 0 and "replayed" in r.stdout, r.stdout + r.stderr


def test_certificates_go_into_a_folder_made_for_them(tmp_path):
    """--certificates DIR names a folder that may not exist yet: it is made when the first
    certificate is written, not refused at the end of a long run (a 4x4 run once lost 20 minutes
    so)."""
    out = tmp_path / "new" / "certificates"
    r = _cli("check", "start-reached", "--size", "3", "4", "--jobs", "1", "--certificates", str(out))
    assert r.returncode == 0 and (out / "check-3x4.cert.json.gz").is_file(), r.stdout + r.stderr
