"""Every committed counterexample still stands: replayed on the reference spec and the JIT.

Each directory under ``tests/data/counterexamples`` (written by ``search --out`` or
``check``) holds one case, golden files recorded from the spec and ``counterexample.json``
naming its kind.  Both backends must reproduce the golden files bit for bit (every field's
bytes, float32 included: no tolerance), and the judge of the kind (a search kind of
:mod:`navfn_smt.search.kinds` or a property of :mod:`navfn_smt.check.properties`) must still
report the violation on the spec.
"""

import pytest

from conftest import DATA
from navfn_smt.search.counterexamples import discover_counterexamples, replay

DIRS = discover_counterexamples(DATA / "counterexamples")


def test_there_are_counterexamples():
    assert DIRS, "no committed counterexamples found"


@pytest.mark.parametrize("directory", DIRS, ids=[d.name for d in DIRS])
def test_counterexample_replays(directory):
    r = replay(directory)
    assert r["golden"] == {"reference": [], "jit": []}, f"golden files not reproduced: {r['golden']}"
    assert r["detail"] is not None, f"the {r['kind']} judge no longer reports the violation"
