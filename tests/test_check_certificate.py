"""Certificates of bounded checks: written for a proved size, replayed without searching, and
refused when they do not re-check (a changed code hash, a path tree that does not close, a
recorded unsat that is not, cases that are not those of the size)."""

import gzip
import json
import subprocess
import sys
from pathlib import Path

import pytest

from navfn_smt.check import certificate as C
from navfn_smt.errors import NavfnInputError

REPORTS = Path(__file__).resolve().parents[1] / "docs" / "reports"


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
        inner = [k for k in B._interior(case.nx, case.ny) if k not in case.lethal]
        for seed, bound, _, flips in log:
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
    assert C.replay(bad)["status"] == "refused"


def test_a_sat_flip_recorded_unsat_is_refused(cert, tmp_path):
    def lie(doc):
        p = next(p for _, _, log in doc["cases"] for p in log if "s" in p[3])
        p[3] = p[3].replace("s", "u", 1)
    assert C.replay(_edit(cert, tmp_path / "c.gz", lie))["status"] == "refused"


def test_a_missing_path_is_refused(cert, tmp_path):
    def drop(doc):
        log = next(log for _, _, log in doc["cases"] if len(log) > 1)
        log.pop()
    assert C.replay(_edit(cert, tmp_path / "c.gz", drop))["status"] == "refused"


def test_a_missing_case_is_refused(cert, tmp_path):
    got = C.replay(_edit(cert, tmp_path / "c.gz", lambda d: d["cases"].pop()))
    assert got["status"] == "refused" and "enumeration" in got["problems"][0]


def test_an_unreadable_certificate_is_a_clear_error(tmp_path):
    p = tmp_path / "x.gz"
    p.write_text("not gzip")
    with pytest.raises(NavfnInputError):
        C.read(p)
    r = _cli("check", "--replay", str(p))
    assert r.returncode != 0 and "Traceback" not in r.stderr and "not a check certificate" in r.stderr


@pytest.mark.parametrize("path", sorted((REPORTS / "certificates").glob("check-*.cert.json.gz")), ids=lambda p: p.name)
def test_every_committed_certificate_is_of_this_code(path):
    """The committed certificates were written by the code as it is (a change to the kernels or
    the encoding must come with new certificates); the CI replays them (.ci/run)."""
    doc = C.read(path)
    assert doc["code_hash"] == C.code_hash(doc["properties"])
