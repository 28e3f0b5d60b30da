"""render, metamorphic and coverage: the user-facing inspection tools."""

import json
import os
import shutil
import subprocess
import sys

import numpy as np
import pytest

from navfn_smt.backends import get_backend
from navfn_smt.cli import EXAMPLE_SUITE
from navfn_smt.maps.suite import load_map
from navfn_smt.search.metamorphic import TRANSFORMS, check_case

CIRCUS = EXAMPLE_SUITE / "circus" / "circus_5L"


def run(*args, cwd=None):
    p = subprocess.run([sys.executable, "-m", "navfn_smt", *map(str, args)], capture_output=True, text=True,
                       cwd=cwd, env={**os.environ, "COLUMNS": "200"})
    return p.returncode, p.stdout, p.stderr


@pytest.mark.parametrize("ext,magic", [(".png", b"\x89PNG"), (".svg", b"<?xml")])
def test_render_writes_picture(tmp_path, ext, magic):
    out = tmp_path / f"c{ext}"
    rc, o, e = run("render", CIRCUS, "--case", 1, "--highlight", 1, 3, "-o", out)
    assert rc == 0, e
    assert out.read_bytes()[:5].startswith(magic)
    assert not [p for p in tmp_path.iterdir() if p.name.startswith(".")]  # no temporary left behind


@pytest.mark.fast
@pytest.mark.parametrize("args,words", [
    (["--case", "9"], "cases 0..1"),
    (["-o", "x.gif"], ".png or .svg"),
    (["--start", "1", "1"], "--start and --goal"),
    (["--highlight", "1", "2", "3"], "--highlight"),
])
def test_render_bad_input(tmp_path, args, words):
    cmd = ["render", CIRCUS, *args]
    if "-o" not in args:
        cmd += ["-o", tmp_path / "p.png"]
    rc, o, e = run(*cmd, cwd=tmp_path)
    assert rc == 2 and "Traceback" not in e and words in e, e
    assert not any(tmp_path.iterdir())


@pytest.mark.parametrize("name", sorted(TRANSFORMS))
def test_transform_maps_cells_consistently(name):
    """The point map of each transform sends cell (x, y) to where the grid map puts its value."""
    t = TRANSFORMS[name]
    a = np.random.default_rng(1).integers(0, 254, size=(5, 7)).astype(np.uint8)
    b = t.grid(a)
    for y in range(5):
        for x in range(7):
            tx, ty = t.point(np.array([[x, y]]), 7, 5)[0].astype(int)
            if name == "cost_shift":
                assert b[ty, tx] == min(int(a[y, x]) + 10, 253)
            else:
                assert b[ty, tx] == a[y, x]


@pytest.mark.fast
def test_transpose_of_a_symmetric_case_breaks_the_path_by_rounding():
    """A finding of the metamorphic tool, kept as a regression test.

    On a uniform map, transposing a diagonal case (start and goal on the diagonal) gives the
    same map and case.  The potential comes out symmetric, yet the path is not: calcPath
    interpolates both gradient components along x first and along y second, so the two
    coordinates of a diagonal point round differently (here by a few ulps)."""
    costs = np.full((7, 7), 50, np.uint8)
    t = TRANSFORMS["transpose"]
    r = get_backend("reference").prepare(costs)
    v = check_case(t, costs, (1, 1, 5, 5), r, get_backend("reference").prepare(t.grid(costs)), True)
    assert v["potential"] and v["reached"] and not v["path"]
    res = r.run((1, 1), (5, 5), True)
    assert np.array_equal(res.potential, res.potential.T)
    p = res.path
    ulps = np.abs(p[:, 0].view(np.int32) - p[:, 1].view(np.int32))
    assert 0 < ulps.max() <= 8


def test_metamorphic_saves_replayable_counterexamples(tmp_path):
    suite = tmp_path / "suite"
    shutil.copytree(EXAMPLE_SUITE / "walls" / "5x5_2walls", suite / "walls" / "5x5_2walls")
    report = tmp_path / "m.json"
    rc, o, e = run("metamorphic", suite, "--relation", "rot90", "--relation", "flip_x", "--mode", "astar",
                   "--save", tmp_path / "cx", "--json", report)
    assert rc == 0, e
    rows = json.loads(report.read_text())["relations"]
    assert {r["relation"] for r in rows} == {"rot90", "flip_x"}
    for r in rows:
        assert r["holds"] <= min(r["path_equal"], r["start_reached_equal"]) <= r["cases"]
        for saved in r["saved"]:
            # replay on the reference spec: the relation really fails on the saved pair
            orig, tr = load_map(f"{saved}/original"), load_map(f"{saved}/transformed")
            t = TRANSFORMS[r["relation"]]
            assert np.array_equal(t.grid(orig.costs), tr.costs)
            ref = get_backend("reference")
            v = check_case(t, orig.costs, orig.cases[0], ref.prepare(orig.costs), ref.prepare(tr.costs), True)
            assert list(v["transformed_case"]) == tr.cases[0].tolist()
            assert not (v["potential"] and v["path"] and v["reached"])


def test_metamorphic_saves_nothing_unasked(tmp_path):
    suite, work = tmp_path / "suite", tmp_path / "work"
    shutil.copytree(EXAMPLE_SUITE / "walls" / "5x5_2walls", suite / "walls" / "5x5_2walls")
    work.mkdir()
    rc, o, e = run("metamorphic", suite, "--relation", "rot90", "--mode", "astar", cwd=work)
    assert rc == 0, e
    assert not any(work.iterdir())
    assert "counterexamples not saved" in o


def test_coverage_report(tmp_path):
    suite = tmp_path / "suite"
    shutil.copytree(EXAMPLE_SUITE / "free" / "3x3_free", suite / "free" / "3x3_free")
    report = tmp_path / "c.json"
    rc, o, e = run("coverage", suite, "--max-cases", 20, "--json", report)
    assert rc == 0, e
    doc = json.loads(report.read_text())
    assert doc["cases_run"] == 40
    assert 0 < doc["branches_covered"] < doc["branches"]
    assert {f["file"] for f in doc["files"]} == {"kernels.py", "numeric.py", "propagation.py", "extraction.py",
                                                "planner.py"}
    # from an interior start extraction never leaves the map: that branch is reported uncovered, with its reason
    out = [u for u in doc["uncovered"] if "OUT_OF_BOUNDS" in u["source"]]
    assert out and out[0]["reason"]
    rc, o, e = run("coverage", suite, "--max-cases", 2, "--min-branch", 100)
    assert rc == 1


def test_every_coverage_reason_names_a_line_of_the_spec():
    """Reasons are keyed by source line: a reworded line must take its reason along."""
    from navfn_smt.difftest.coverage import LIBRARY_FILES, REASONS, SPEC_DIR, SPEC_FILES

    lines = {ln.strip() for f in SPEC_FILES + LIBRARY_FILES for ln in (SPEC_DIR / f).read_text().splitlines()}
    stale = [k for k in REASONS if k not in lines]
    assert not stale, stale
