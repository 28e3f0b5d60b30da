"""Shared fixtures, and the one marker policy of the tests.

The shared suites live beside the checkout (``../shared``) in CI; a fresh clone
elsewhere has none, and the tests that need them skip.  ``NAVFN_SHARED`` overrides
the location.

Markers (declared in ``pyproject.toml``) are given here, once, by what a test uses:
``shared`` and ``large`` for the shared suites' fixtures, ``dask`` for a Dask cluster
fixture, ``prove`` for a whole proof run; ``slow`` is written on the test itself and such a
test runs only with ``NAVFN_SLOW=1`` (:data:`SLOW`, read here and nowhere else).  So
``pytest -m "not dask and not prove"`` gives a quick run.  ``fast`` is written on a test or its
module (``pytestmark``): ``pytest -m fast`` is the development tier, of tests that have none of
the markers above and take a few seconds at most (tests/test_fast_tier.py checks its size and
that none of its tests has them).
"""

import os
from pathlib import Path

import pytest

from navfn_smt.distros import CHECKED

# the tests read reports as a pipe or a file gets them (a table row per line, as wide as it
# needs): a COLUMNS in the test processes' environment would fit them to its width
for _size in ("COLUMNS", "LINES"):
    os.environ.pop(_size, None)

REPO = Path(__file__).resolve().parent.parent
SHARED = Path(os.environ.get("NAVFN_SHARED", REPO.parent / "shared"))
SUITE = SHARED / "navfn-suite"
SUITE_LARGE = SHARED / "navfn-suite-large"
NAV2_SRC = SHARED / "nav2-src"
DATA = Path(__file__).resolve().parent / "data"
SLOW = bool(os.environ.get("NAVFN_SLOW"))  # the slow tests and guide commands run only then

# a test using one of these fixtures gets the marker
FIXTURE_MARKERS = {"shared_suite": "shared", "shared_suite_large": "large", "nav2_src": "shared", "cluster": "dask",
                   "local_cluster": "dask", "proof_run": "prove", "progress_run": "prove"}


def pytest_collection_modifyitems(config, items):
    skip_slow = pytest.mark.skip(reason="slow: set NAVFN_SLOW=1")
    for item in items:
        for fixture in getattr(item, "fixturenames", ()):
            if fixture in FIXTURE_MARKERS:
                item.add_marker(FIXTURE_MARKERS[fixture])
        if "slow" in item.keywords and not SLOW:
            item.add_marker(skip_slow)


@pytest.fixture
def shared_suite() -> Path:
    if not (SUITE / "README.md").exists():
        pytest.skip(f"shared suite not found at {SUITE}")
    return SUITE


@pytest.fixture(scope="session")
def nav2_src() -> Path:
    """The unmodified Nav2 sources of ../shared (a folder per distribution), and a C++ compiler."""
    import shutil

    if not (NAV2_SRC / "COMMITS.txt").exists():
        pytest.skip(f"Nav2 sources not found at {NAV2_SRC}")
    if shutil.which(os.environ.get("CXX") or "g++") is None:
        pytest.skip("no C++ compiler (g++ or $CXX)")
    return NAV2_SRC


DISTROS = CHECKED  # every distribution whose sources are at hand


def _session_root(tmp_path_factory) -> Path:
    """The test session's folder, shared by its test processes under ``pytest -n``."""
    root = tmp_path_factory.getbasetemp()
    return root.parent if os.environ.get("PYTEST_XDIST_WORKER") else root


@pytest.fixture(scope="session", autouse=True)
def object_cache(tmp_path_factory):
    """The oracle builds of one test run share one object cache (navfn_smt/oracle/objects.py),
    empty when the run starts: never the user's, so a run's time does not depend on the last."""
    before = os.environ.get("NAVFN_SMT_OBJECT_CACHE")
    os.environ["NAVFN_SMT_OBJECT_CACHE"] = str(_session_root(tmp_path_factory) / "objects")
    yield
    if before is None:
        os.environ.pop("NAVFN_SMT_OBJECT_CACHE", None)
    else:
        os.environ["NAVFN_SMT_OBJECT_CACHE"] = before


@pytest.fixture(scope="session")
def builds(nav2_src, tmp_path_factory) -> dict:
    """Every program of the oracle built from each distribution's sources: ``{distro: (build.json,
    folder)}``, once per test session (test_oracle.py, test_fix.py and test_nav2_benchmark.py
    share it).  Under ``pytest -n`` the test processes share one folder: the first to take its
    lock builds, the others wait for it and read each build.json."""
    import fcntl
    import json

    from navfn_smt.oracle.build import build

    root = _session_root(tmp_path_factory) / "oracle-builds"
    root.mkdir(exist_ok=True)
    out = {}
    with open(root / "lock", "w") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        for d in DISTROS:
            done = root / d / "build.json"
            out[d] = (json.loads(done.read_text()) if done.exists() else build(nav2_src / d, root / d, programs_for(d)),
                      root / d)
    return out


# the distributions whose session builds hold the candidate cycles-only's programs beside NavFn as
# shipped and the fix of docs/fix.md (tests/test_cycles_only.py tests that candidate's C++ on the
# oldest and the newest); Rolling's holds every registered fix's (tests/test_candidates.py tests
# the others' C++ there), the rest as shipped and with the fix, to keep the run's time
CANDIDATE_DISTROS = ("humble", "rolling")


def programs_for(distro: str) -> tuple:
    from navfn_smt.oracle.build import FIXED_PROGRAMS, PROGRAMS, SHIPPED_PROGRAMS, fix_programs
    from navfn_smt.spec import fixes

    if distro == "rolling":
        return PROGRAMS
    if distro in CANDIDATE_DISTROS:
        return (*SHIPPED_PROGRAMS, *FIXED_PROGRAMS, *fix_programs(fixes.named("cycles-only")))
    return (*SHIPPED_PROGRAMS, *FIXED_PROGRAMS)


@pytest.fixture
def shared_suite_large() -> Path:
    if not (SUITE_LARGE / "README.md").exists():
        pytest.skip(f"large shared suite not found at {SUITE_LARGE}")
    return SUITE_LARGE


def compare_golden_files(ours, theirs) -> list[str]:
    """Fields in which two golden files differ (dtype, shape or bytes); empty when identical."""
    import numpy as np

    from navfn_smt.maps.suite import GOLDEN_FIELDS

    diffs = []
    with np.load(ours, allow_pickle=False) as a, np.load(theirs, allow_pickle=False) as b:
        if list(a.files) != list(b.files):
            diffs.append(f"fields {a.files} vs {b.files}")
        for f in GOLDEN_FIELDS:
            if f not in a.files or f not in b.files:
                continue
            x, y = a[f], b[f]
            if x.dtype != y.dtype or x.shape != y.shape or x.tobytes() != y.tobytes():
                diffs.append(f"{f}: {x.dtype}{x.shape} vs {y.dtype}{y.shape}")
    return diffs


def discover_counterexamples(root) -> list[Path]:
    """Every directory holding a ``counterexample.json`` under ``root`` (sorted)."""
    from navfn_smt.search.counterexamples import JSON_NAME

    r = Path(root)
    return sorted(p.parent for p in r.rglob(JSON_NAME)) if r.is_dir() else []
