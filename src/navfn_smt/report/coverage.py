"""What ``coverage`` reports: the per-file table, the uncovered branches with their
reasons, the JSON document and the closing line."""

from __future__ import annotations

import json

from rich.table import Table

from ..difftest.coverage import LIBRARY_FILES, percent
from ..fileio import atomic_write_text
from .tables import console


def table(r: dict) -> None:
    """Print lines and branches covered per spec file, and the spec's total without the library."""
    t = Table(title=f"coverage of the reference spec ({r['cases_run']} case runs)")
    for c in ("file", "lines", "covered", "branches", "covered ", "branch %"):
        t.add_column(c, justify="left" if c == "file" else "right")
    for f in r["files"]:
        name = f["file"] + (" (library)" if f["file"] in LIBRARY_FILES else "")
        t.add_row(name, str(f["lines"]), str(f["lines_covered"]), str(f["branches"]),
                  str(f["branches_covered"]), percent(f["branches_covered"], f["branches"]))
    t.add_row("spec (without library)", str(r["lines"]), str(r["lines_covered"]), str(r["branches"]),
              str(r["branches_covered"]), percent(r["branches_covered"], r["branches"]))
    console.print(t)


def uncovered(r: dict) -> None:
    """Print the kernel decisions covered, then every uncovered branch with its reason."""
    print(f"kernel decisions (ite outcomes, per line): {r['ite_outcomes_covered']} of {r['ite_outcomes']} "
          f"({percent(r['ite_outcomes_covered'], r['ite_outcomes'])})")
    if r["uncovered"]:
        print("not covered:")
        for u in r["uncovered"]:
            why = u["reason"] or "no reason recorded: a suite case could reach it"
            print(f"  {u['kind']} {u['file']}:{u['line']} -> {u['to']}: {u['source']}\n      {why}")


def write_json(path, suites, modes, r: dict) -> None:
    """Write the figures and every uncovered branch as one JSON document."""
    atomic_write_text(path, json.dumps({"suites": [str(s) for s in suites], "modes": list(modes), **r}, indent=1))


def closing_line(r: dict) -> None:
    """Print the branch coverage and how many uncovered branches lack a reason."""
    unexplained = [u for u in r["uncovered"] if not u["reason"]]
    print(f"spec branch coverage {percent(r['branches_covered'], r['branches'])}; "
          f"{len(r['uncovered'])} uncovered branches and decisions, {len(unexplained)} without a reason")
