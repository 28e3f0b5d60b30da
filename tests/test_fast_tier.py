"""The quick development tier, ``python -m pytest -m fast`` (README): it keeps more than a hundred
tests from at least eight test files, so that it cannot shrink unnoticed, and none of them uses
``../shared``, a Dask cluster, the whole proof run or waits for NAVFN_SLOW (the markers
tests/conftest.py gives by fixture).  Collected once, in a subprocess without test processes, with
a probe plugin that writes down each selected test and its markers."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parent.parent
HEAVY = ("shared", "large", "dask", "prove", "slow")

PROBE = f'''
import json, os


def pytest_collection_finish(session):
    rows = [[item.nodeid, sorted({{m.name for m in item.iter_markers()}} & set({HEAVY!r}))] for item in session.items]
    with open(os.environ["FAST_TIER_OUT"], "w") as f:
        json.dump(rows, f)
'''


@pytest.fixture(scope="module")
def fast_tier(tmp_path_factory) -> list:
    """``[[test id, its markers of HEAVY], ...]`` of the tests ``-m fast`` selects."""
    probe = tmp_path_factory.mktemp("probe")
    (probe / "fast_tier_probe.py").write_text(PROBE)
    env = {k: v for k, v in os.environ.items() if not k.startswith("PYTEST_")}
    env["PYTHONPATH"] = os.pathsep.join(p for p in (str(probe), env.get("PYTHONPATH")) if p)
    env["FAST_TIER_OUT"] = str(probe / "tier.json")
    run = subprocess.run([sys.executable, "-m", "pytest", "--collect-only", "-q", "-n", "0", "-p", "no:cacheprovider",
                          "-p", "fast_tier_probe", "-m", "fast"], cwd=REPO, env=env, capture_output=True, text=True,
                         timeout=300)
    assert run.returncode == 0, run.stdout + run.stderr
    return json.loads((probe / "tier.json").read_text())


def test_the_fast_tier_keeps_over_a_hundred_tests_from_eight_files(fast_tier):
    files = {nodeid.split("::")[0] for nodeid, _ in fast_tier}
    assert len(fast_tier) > 100, f"the fast tier has {len(fast_tier)} tests"
    assert len(files) >= 8, f"the fast tier comes from {len(files)} test files: {sorted(files)}"


def test_no_fast_test_uses_the_shared_suites_a_cluster_or_the_proof_run(fast_tier):
    assert [(nodeid, heavy) for nodeid, heavy in fast_tier if heavy] == []
