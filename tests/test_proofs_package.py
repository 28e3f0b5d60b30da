"""The proofs ship in the package: the proof files and the bound cache resolve through
``navfn_smt.proofs`` wherever the package lives, whatever the current directory, and a
bound cache that cannot be written never fails a run."""

import json
import os
import subprocess
import sys
import tomllib
from importlib.resources import files
from pathlib import Path

import navfn_smt

REPO = Path(__file__).resolve().parent.parent
PROOF_FILES = {"gradient.py", "monotonicity.py", "no_path.py", "path_step.py", "position_safe.py", "progress.py",
               "queues.py", "fix.py", "component.py", "fallback.py", "queued.py", "potential_bound.py", "induction.py",
               "buffers.py", "frontier.py", "descent.py", "calcpath.py", "loop.py"}


def test_proofs_and_bound_cache_are_inside_the_package():
    root = files("navfn_smt.proofs")
    names = {p.name for p in root.iterdir()}
    assert PROOF_FILES <= names and ".bounds.json" in names
    assert Path(str(root)).resolve() == (Path(navfn_smt.__file__).parent / "proofs").resolve()
    assert isinstance(json.loads(root.joinpath(".bounds.json").read_text()), dict)


def test_the_wheel_takes_the_bound_cache():
    """A dot file is package data only when named: the wheel must carry it."""
    doc = tomllib.loads((REPO / "pyproject.toml").read_text())
    assert "proofs/.bounds.json" in doc["tool"]["setuptools"]["package-data"]["navfn_smt"]


def test_default_proof_files_with_cwd_elsewhere(tmp_path):
    script = ("import json; from navfn_smt.smt.runner import default_proof_files; "
              "print(json.dumps([str(p) for p in default_proof_files()]))")
    p = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, cwd=tmp_path)
    assert p.returncode == 0, p.stderr
    found = [Path(f) for f in json.loads(p.stdout)]
    package = Path(navfn_smt.__file__).resolve().parent
    assert {f.name for f in found} == PROOF_FILES
    assert all(f.resolve().parent == package / "proofs" for f in found)
    assert list(tmp_path.iterdir()) == []


BOUNDED = '''
from navfn_smt.smt.obligation import Bound, obligation
from navfn_smt.smt.predicates import ValidPotential

@obligation("Demo", expect={"fp32": "refuted"}, scope="one addition", bound=Bound(var="x", lo=1.0, hi=1e10))
def adding_one_increases(D):
    """x + 1 > x (false in float32 from 2**24 on)."""
    x = D.f32("x")
    return ValidPotential(D, x), D.gt(D.add(x, D.f32const(1.0)), x)
'''


def test_unwritable_bound_cache_keeps_the_bound_and_says_so(tmp_path):
    (tmp_path / "p.py").write_text(BOUNDED)
    (tmp_path / ".bounds.json").mkdir()  # the cache cannot be written (as if installed read-only)
    work = tmp_path / "cwd"
    work.mkdir()
    p = subprocess.run([sys.executable, "-m", "navfn_smt", "prove", tmp_path / "p.py", "--all", "--semantics", "fp32",
                        "--solver", "z3", "--report", tmp_path / "r.json"], capture_output=True, text=True,
                       cwd=work, env={**os.environ, "COLUMNS": "200"})
    assert p.returncode == 0, p.stdout + p.stderr
    (o,) = json.loads((tmp_path / "r.json").read_text())["obligations"]
    assert o["bound"]["holds_below"] == 2.0**24
    assert "not cached" in o["bound"]["cache"] and "not cached" in p.stdout
    assert list(work.iterdir()) == []  # nothing written into the current directory unasked


def test_a_mutant_proves_the_proofs_of_its_own_copy(tmp_path):
    """The mutation check copies the package: the shipped proof files are taken from the copy."""
    from navfn_smt.search.mutation import _in_copy
    from navfn_smt.smt.runner import default_proof_files

    for f in default_proof_files():
        assert _in_copy(f, tmp_path) == tmp_path / "navfn_smt" / "proofs" / f.name
    other = tmp_path / "mine.py"
    assert _in_copy(other, tmp_path) == other
