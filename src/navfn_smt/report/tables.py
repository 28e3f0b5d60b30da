"""Human-readable output with rich: progress bars and result tables."""

from __future__ import annotations

import contextlib
import sys

from rich.console import Console
from rich.progress import BarColumn, MofNCompleteColumn, Progress, TextColumn, TimeElapsedColumn, TimeRemainingColumn
from rich.table import Table

console = Console()
err_console = Console(stderr=True)


@contextlib.contextmanager
def progress_bar(total: int, description: str, enabled: bool = True):
    """Yields ``advance(n)``; the bar goes to stderr and only when it is a terminal."""
    if not enabled or not sys.stderr.isatty():
        yield lambda n: None
        return
    with Progress(
        TextColumn("{task.description}"),
        BarColumn(),
        MofNCompleteColumn(),
        TimeElapsedColumn(),
        TimeRemainingColumn(),
        console=err_console,
        transient=True,
    ) as prog:
        task = prog.add_task(description, total=total)
        yield lambda n: prog.advance(task, n)


def _describe(d) -> str:
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


def difftest_table(summary: dict) -> None:
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
                  _describe(c["first_disagreement"]))
    console.print(t)
