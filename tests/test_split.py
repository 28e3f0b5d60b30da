"""Splits: parts that cover an obligation's input space, each decided; the cover proved.

The toy proof file (tests/data/split/toy_proofs.py) has one split per way a part is decided
(bit-precise query, enumeration, error model) and per verdict; each must reach its declared
verdict, in this process and on a real two-worker Dask cluster alike.  The array domain that
enumeration runs on is a second statement of the concrete arithmetic: the conformance harness
holds it equal to the scalar spec bit for bit (``tests/test_domain_conformance.py``).
"""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from hypothesis import given
from hypothesis import strategies as st

from navfn_smt.cli import main
from navfn_smt.engine import Engine
from navfn_smt.smt import split as S

TOY = Path(__file__).parent / "data" / "split" / "toy_proofs.py"
f32s = st.floats(width=32, allow_nan=False)


def _splits():
    return {s.obligation: s for s in S.load_splits([TOY])}


# ------------------------------------------------------------------------ the order of floats
@pytest.mark.fast
@given(f32s, f32s)
def test_ordinal_is_the_order_of_the_reals(a, b):
    assert S.from_ordinal(S.ordinal(a)) == a
    assert (S.ordinal(a) < S.ordinal(b)) == (a < b)


@pytest.mark.fast
@given(st.integers(-(2**31) + 1, 2**31 - 2), st.integers(0, 2**20))
def test_halves_partition_an_interval(lo, width):
    iv = S.Interval("x", lo, lo + width)
    if iv.width < 2:
        return
    a, b = iv.halves()
    assert (a.lo, b.hi) == (iv.lo, iv.hi) and a.hi + 1 == b.lo and a.width + b.width == iv.width


@pytest.mark.fast
def test_bisect_cuts_the_widest_variable_and_stops_at_single_values():
    box = (S.f32_interval("x", 1.0, 2.0), S.f32_interval("y", 1.0, 1.0))
    a, b = S.bisect(box, ("x", "y"))
    assert a[1] == b[1] == box[1] and a[0].hi + 1 == b[0].lo
    assert S.bisect((S.f32_interval("x", 0.0, 0.0),), ("x",)) is None


# ------------------------------------------------------------------------------ the verdicts
@pytest.mark.fast
@pytest.mark.parametrize("name", ["doubling_is_exact", "sum_minus_one_keeps_y", "square_root_of_square",
                                  "product_is_close"])
def test_each_toy_split_reaches_its_declared_verdict(name):
    s = _splits()[name]
    o = S.run_split(s, Engine(1))
    assert o.status == s.expect
    assert o.cover["status"] == "proved"
    if o.status == "refuted":
        witness = next(p["witness"] for p in o.parts if p["status"] == "refuted")
        assert witness["replayed_on_spec"] is True


@pytest.mark.parametrize("method", ["enumerate", "smt"])
def test_a_split_is_decided_in_a_builds_arithmetic(method):
    """``split --target``: the parts are decided in that build's float32 semantics, what is known
    judged there; a fused multiply-add is the product's rounding error where x86-64's rounded
    product gives zero, so the toy is proved in fp32 and refuted, by a witness the spec in that
    arithmetic replays, in each fused one."""
    from dataclasses import replace

    s = replace(_splits()["product_error_is_zero"], methods=(method,), solvers=("z3",), part_timeout=30.0)
    assert S.run_split(s, Engine(1)).status == "proved"
    for semantics in ("fp32@aarch64", "fp32@x86-64-v3"):
        o = S.run_split(s, Engine(1), semantics=semantics)
        assert (o.status, o.known, o.semantics, o.judgement) == ("refuted", "refuted", semantics, "confirmed")
        witness = next(p["witness"] for p in o.parts if p["status"] == "refuted")
        assert witness["replayed_on_spec"] is True


@pytest.mark.fast
def test_fmaf_array_is_libms_fmaf():
    """The enumeration's vectorised fmaf (and the check's exhaustive evaluator's) is libm's, bit
    for bit: on random bit patterns and where rounding the double sum would break a float tie."""
    import numpy as np

    from navfn_smt.smt.enumerate import fmaf_array
    from navfn_smt.spec.numeric import c_fmaf

    rng = np.random.default_rng(7)
    n = 20000
    bits = rng.integers(0, 2**32, size=(3, n), dtype=np.uint64).astype(np.uint32).view(np.float32)
    m = rng.integers(1, 2**12, n)
    tie = (1 + m * 2.0**-12).astype(np.float32)
    tiny = (rng.choice([-1, 1], n) * 2.0 ** rng.integers(-80, -30, n)).astype(np.float32)
    for a, b, c in (bits, (tie, tie, tiny)):
        got = fmaf_array(a, b, c)
        want = np.array([c_fmaf(float(x), float(y), float(z)) for x, y, z in zip(a, b, c)], np.float32)
        same = (got.view(np.uint32) == want.view(np.uint32)) | (np.isnan(got) & np.isnan(want))
        assert same.all(), np.flatnonzero(~same)[:3]
    assert (fmaf_array(tie, tie, tiny) != (tie.astype(np.float64) ** 2 + tiny).astype(np.float32)).any()


@pytest.mark.fast
def test_a_part_the_cover_misses_makes_the_split_unknown():
    s = _splits()["doubling_is_exact"]
    gap = S.Split(s.obligation, [(S.f32_interval("x", -4.0, 0.0),)], ("x",), "proved", 0, 30.0, ("z3",),
                  source=s.source)
    o = S.run_split(gap, Engine(1))
    assert o.status == "unknown" and o.cover["status"] == "refuted"
    assert 0 < o.cover["uncovered_input"]["x"]["value"] <= 4.0


@pytest.mark.fast
def test_the_error_model_never_proves_a_false_claim():
    s = _splits()["sum_minus_one_keeps_y"]
    em = S.Split(s.obligation, s.boxes, s.bisect, "unknown", 0, 30.0, ("z3",), methods=("errmodel",),
                 source=s.source)
    o = S.run_split(em, Engine(1))
    assert o.status == "unknown" and all(p["status"] == "unknown" for p in o.parts)


@pytest.mark.fast
def test_an_undecided_part_is_cut_in_two_and_named():
    s = _splits()["doubling_is_exact"]
    tiny = S.Split(s.obligation, [(S.f32_interval("x", -4.0, 4.0),)], ("x",), "proved", 2, 1e-3, ("z3",),
                   source=s.source)
    o = S.run_split(tiny, Engine(1))
    if o.status == "unknown":  # a millisecond per part: the parts were cut down to the depth limit
        assert len(o.parts) == 4 and o.rounds == 3 and o.undecided
    else:
        assert o.status == "proved"


# --------------------------------------------------------------------------- on a cluster
@pytest.fixture(scope="module")
def cluster():
    distributed = pytest.importorskip("distributed")
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=":0",
                                  host="127.0.0.1") as c:
        yield c


def _result(o):
    return o.status, o.cover["status"], [(tuple((iv["var"], iv["lo"], iv["hi"]) for iv in p["box"]), p["status"])
                                         for p in o.parts]


@pytest.mark.parametrize("name", ["doubling_is_exact", "product_is_close", "square_root_of_square"])
def test_a_split_on_a_local_cluster_equals_the_local_run(cluster, name):
    s = _splits()[name]
    local = S.run_split(s, Engine(1))
    remote = S.run_split(s, Engine(scheduler=cluster.scheduler_address))
    assert _result(remote) == _result(local)


def test_a_refuted_split_is_refuted_on_the_cluster_too(cluster):
    s = _splits()["sum_minus_one_keeps_y"]
    o = S.run_split(s, Engine(scheduler=cluster.scheduler_address))
    assert o.status == "refuted" and o.cover["status"] == "proved"
    assert next(p for p in o.parts if p["status"] == "refuted")["witness"]["replayed_on_spec"] is True


# ------------------------------------------------------------------------------ the command
def test_split_command_reports_every_part(tmp_path, capsys):
    report = tmp_path / "split.json"
    assert main(["split", "doubling_is_exact", "product_is_close", "--files", str(TOY), "--jobs", "1",
                 "--report", str(report)]) == 0
    doc = json.loads(report.read_text())
    assert [s["obligation"] for s in doc["splits"]] == ["doubling_is_exact", "product_is_close"]
    assert all(s["status"] == "proved" and s["cover"]["status"] == "proved" for s in doc["splits"])
    assert "2 splits: 2 confirmed, 0 undecided, 0 newly decided, 0 contradicted" in capsys.readouterr().out


@pytest.mark.fast
def test_split_command_errors_are_one_line(capsys):
    assert main(["split", "no_such_obligation", "--files", str(TOY)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "no split declared for no_such_obligation" in err[0]


@pytest.mark.fast
def test_the_shipped_splits_name_declared_obligations():
    from navfn_smt.smt.obligation import load_obligations
    from navfn_smt.smt.runner import default_proof_files

    names = {o.name for o in load_obligations(default_proof_files())}
    splits = S.load_splits(default_proof_files())
    assert {s.obligation for s in splits} >= {"grad_is_unit_or_zero", "interpolated_gradient_is_zero_or_not_tiny",
                                              "step_along_an_axis_moves_at_most_half"}
    assert all(s.obligation in names for s in splits)


@pytest.mark.fast
def test_a_worker_without_the_proof_file_decides_a_part_from_its_contents(tmp_path):
    """A remote worker: the driver's path does not exist there, the file's contents travel with the part."""
    s = _splits()["doubling_is_exact"]
    gone = str(tmp_path / "elsewhere" / "toy_proofs.py")
    part = S.check_part((gone, TOY.read_bytes(), s.obligation, S.Part(s.boxes[0], 0), (("smt", 30.0),), ("z3",), "fp32"))
    assert part.status == "proved"


def test_split_command_with_the_default_jobs_writes_its_report(tmp_path):
    """--jobs auto (the default): the report names the engine as asked, each split where it ran."""
    report = tmp_path / "split.json"
    assert main(["split", "doubling_is_exact", "--files", str(TOY), "--quiet", "--report", str(report)]) == 0
    doc = json.loads(report.read_text())
    assert doc["engine"].startswith("auto") and doc["splits"][0]["status"] == "proved"


@pytest.mark.fast
def test_ci_runs_every_shipped_split_once():
    """.ci/run names the splits in two runs (the solver-decided ones, then the enumerated one, on
    the lane beside the slow proof run): together they are every shipped split, each once, and
    the enumerated run holds only splits without a time limit."""
    import re
    import shlex
    from pathlib import Path

    from navfn_smt.smt.runner import default_proof_files

    script = (Path(__file__).resolve().parents[1] / ".ci" / "run").read_text().replace("\\\n", " ")
    named = []
    for line in script.splitlines():
        if re.match(r"\s*navfn-smt split ", line):
            words = shlex.split(line.split(">")[0].split("||")[0])
            named.append([w for w in words[2:] if re.fullmatch(r"[a-z_]+", w) and w != "split"])
    splits = {s.obligation: s for s in S.load_splits(default_proof_files())}
    flat = [n for lane in named for n in lane]
    assert len(named) == 2 and sorted(flat) == sorted(splits), named
    # so the slow proof run leaves those obligations' whole queries to them
    slow = [line for line in script.splitlines() if re.match(r"\s*navfn-smt prove --slow-only ", line)]
    assert len(slow) == 1 and "--skip-split" in shlex.split(slow[0].split("||")[0]), slow
    assert all(splits[n].methods == ("enumerate",) for n in named[1])


def test_prove_leaves_the_whole_queries_of_split_obligations_to_their_splits(tmp_path):
    """``prove --skip-split`` asks no fp32 whole query of an obligation a split decides, and says
    which it left out (on the terminal and in the report); the others it asks as before."""
    from navfn_smt.smt.runner import tasks

    left = tmp_path / "left.json"
    assert main(["prove", str(TOY), "--solver", "z3", "--skip-split", "--report", str(left)]) == 0
    asked = {(t.name, t.semantics) for t in tasks([TOY], everything=False)}  # what a run without it asks
    doc = json.loads(left.read_text())
    kept = {(o["name"], o["semantics"]) for o in doc["obligations"]}
    split_fp32 = {(s.obligation, "fp32") for s in S.load_splits([TOY])}
    assert split_fp32 <= asked and not split_fp32 & kept and kept == asked - split_fp32
    assert sorted(doc["left_to_splits"]) == sorted(f"{n} (fp32)" for n, _ in split_fp32)
