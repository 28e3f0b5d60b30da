"""docs/ci.md's workflow file: valid, and its own navfn-smt step run on the shared sources."""

from __future__ import annotations

import re
import shlex
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest
import yaml

from navfn_smt.cli import main

PAGE = Path(__file__).resolve().parent.parent / "docs" / "ci.md"


def workflow() -> dict:
    blocks = re.findall(r"```yaml\n(.*?)```", PAGE.read_text(), re.S)
    assert len(blocks) == 1, "docs/ci.md holds one workflow block"
    return yaml.safe_load(blocks[0])


def test_the_workflow_is_a_workflow():
    wf = workflow()
    steps = wf["jobs"]["navfn"]["steps"]
    assert wf["name"] == "navfn-smt" and "NAVFN_SMT" in wf["env"]
    assert steps[0]["uses"].startswith("actions/checkout@") and steps[0]["with"]["path"] == "navigation2"
    runs = [s["run"] for s in steps if "run" in s]
    assert any("libeigen3-dev" in r and "g++" in r for r in runs)
    assert any(r.startswith("pip install") and "$NAVFN_SMT" in r for r in runs)
    assert sum(r.startswith("navfn-smt ci ") for r in runs) == 1
    upload = steps[-1]
    assert upload["uses"].startswith("actions/upload-artifact@") and upload["if"] == "always()"


# one distribution (every one builds in tests/test_oracle.py; its seeded-bug run of `ci` is Rolling's)
@pytest.mark.parametrize("distro", ["jazzy"])
def test_the_workflows_navfn_smt_step_passes_on_the_sources(nav2_src, tmp_path, monkeypatch, distro):
    """The workflow's `navfn-smt ci` step as it is written: it builds, difftests every level and
    writes one JUnit suite with a test case per step and no failure."""
    steps = workflow()["jobs"]["navfn"]["steps"]
    (run,) = [s["run"] for s in steps if "run" in s and s["run"].startswith("navfn-smt ")]
    upload = Path(steps[-1]["with"]["path"])
    monkeypatch.chdir(tmp_path)
    (tmp_path / "navigation2").symlink_to(nav2_src / distro)
    argv = shlex.split(run)[1:] + ["--no-prove", "--configs", "20"]  # the proofs have a test of their own
    assert main(argv) == 0
    root = ET.parse(tmp_path / upload).getroot()
    suite = root.find("testsuite")
    assert root.tag == "testsuites" and suite.get("failures") == "0" and suite.get("name") == f"navfn-smt ci {distro}"
    names = [tc.get("name") for tc in suite.iter("testcase")]
    assert names[:5] == ["build", "difftest navfn", "difftest navfn unbounded", "difftest plugin", "difftest costmap"]
