"""What ``navfn-smt ci`` writes: one JUnit file, a test case per step, the proofs' own suite beside it."""

from __future__ import annotations

import xml.etree.ElementTree as ET
from pathlib import Path
from typing import Optional

from ..fileio import atomic_write_text


def write_junit(path, name: str, cases: list, prove_junit: Optional[Path] = None) -> None:
    """``<testsuites>``: the steps as one ``<testsuite>``, then the suites of ``prove --junit``."""
    root = ET.Element("testsuites")
    suite = ET.SubElement(root, "testsuite", name=name, tests=str(len(cases)),
                          failures=str(sum(bool(c["failure"]) for c in cases)),
                          skipped=str(sum(bool(c["skipped"]) for c in cases)),
                          time=f"{sum(c['seconds'] for c in cases):.3f}")
    for c in cases:
        tc = ET.SubElement(suite, "testcase", classname="navfn-smt.ci", name=c["name"], time=f"{c['seconds']:.3f}")
        if c["failure"]:
            ET.SubElement(tc, "failure", message=c["failure"])
        elif c["skipped"]:
            ET.SubElement(tc, "skipped", message=c["skipped"])
        if c["out"]:
            ET.SubElement(tc, "system-out").text = c["out"]
    if prove_junit is not None and Path(prove_junit).is_file():
        proved = ET.parse(prove_junit).getroot()
        for s in ([proved] if proved.tag == "testsuite" else list(proved)):
            root.append(s)
    atomic_write_text(path, '<?xml version="1.0" encoding="UTF-8"?>\n' + ET.tostring(root, encoding="unicode") + "\n")
