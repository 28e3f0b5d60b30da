"""The documentation builds as a site: ``mkdocs build --strict`` (broken links, missing
images and unknown anchors fail the build)."""

import subprocess
import sys
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parent.parent


def test_mkdocs_build_strict(tmp_path):
    reason = "mkdocs and mdx_truly_sane_lists are not installed (pip install -e '.[test]' installs them)"
    pytest.importorskip("mkdocs", reason=reason)
    pytest.importorskip("mdx_truly_sane_lists", reason=reason)
    site = tmp_path / "site"
    done = subprocess.run(
        [sys.executable, "-m", "mkdocs", "build", "--strict", "-f", str(REPO / "mkdocs.yml"), "-d", str(site)],
        cwd=REPO, capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, f"mkdocs build --strict failed:\n{done.stdout}\n{done.stderr}"
    for page in ("index", "guide", "method", "architecture", "gallery", "invariants"):
        assert (site / page / "index.html").exists() or (site / f"{page}.html").exists(), page

