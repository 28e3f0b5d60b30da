"""Shared fixtures: where the shared suites are, when they are present at all.

The shared suites live beside the checkout (``../shared``) in CI; a fresh clone
elsewhere has none, and the tests that need them skip.  ``NAVFN_SHARED`` overrides
the location.
"""

import os
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parent.parent
SHARED = Path(os.environ.get("NAVFN_SHARED", REPO.parent / "shared"))
SUITE = SHARED / "navfn-suite"
SUITE_LARGE = SHARED / "navfn-suite-large"
DATA = Path(__file__).resolve().parent / "data"


@pytest.fixture
def shared_suite() -> Path:
    if not (SUITE / "README.md").exists():
        pytest.skip(f"shared suite not found at {SUITE}")
    return SUITE


@pytest.fixture
def shared_suite_large() -> Path:
    if not (SUITE_LARGE / "README.md").exists():
        pytest.skip(f"large shared suite not found at {SUITE_LARGE}")
    return SUITE_LARGE
