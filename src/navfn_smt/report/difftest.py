"""What ``difftest`` reports: the agreement table, the JSON document and the closing line."""

from __future__ import annotations

import json

from rich.table import Table

from ..fileio import atomic_write_text
from .tables import console


def describe(d) -> str:
    """A disagreement in one line: where, which field, and how the values differ."""
    if d is None:
        return "-"
    det = d["detail"]
    where = f"{d['map']} case {d['case_index']} {tuple(d['case'])}: {d['field']}"
    if d["field"] == "potential" and "cell" in det:
        where += f" at cell {tuple(det['cell'])} ({det['ours']['value']!r} vs {det['golden']['value']!r})"
    elif d["field"] == "path" and "point" in det:
        where += f" at point {det['point']}"
    elif d["field"] == "path":
        where += f" length {det['length']} vs {det['golden_length']}"
    elif "ours" in det and not isinstance(det["ours"], dict):
        where += f" {det['ours']} vs {det['golden']}"
    return where


def table(summary: dict) -> None:
    """Print one row per category and mode: cases, agreeing cases, the first disagreement."""
    t = Table(title="difftest: agreement with the golden outputs")
    t.add_column("category")
    t.add_column("mode")
    t.add_column("cases", justify="right")
    t.add_column("agreeing", justify="right")
    t.add_column("first disagreement", overflow="fold")
    for c in summary["categories"]:
        ok = c["agreeing"] == c["cases"]
        t.add_row(c["category"], c["mode"], str(c["cases"]),
                  f"[green]{c['agreeing']}[/]" if ok else f"[red]{c['agreeing']}[/]",
                  describe(c["first_disagreement"]))
    console.print(t)


def write_json(path, suite, backend: str, modes, summary: dict) -> None:
    """Write the run's per-map counts and every disagreement as one JSON document."""
    doc = {"suite": str(suite), "backend": backend, "modes": list(modes), **summary}
    atomic_write_text(path, json.dumps(doc, indent=1))


def closing_line(summary: dict) -> None:
    """Print ``N passed, M failed``."""
    print(f"{summary['passed']} passed, {summary['failed']} failed")
