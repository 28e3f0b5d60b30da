"""What ``check`` reports: per property and size the verdict, what was enumerated and what solved."""

from __future__ import annotations

import json
import sys

from rich.table import Table

from ..fileio import atomic_write_text
from .tables import console as _console


def progress(label: str, every: float = 20.0):
    """``(done, total, case_result)`` callback: a line on stderr every ``every`` seconds and at the end."""
    import time

    state = {"t": time.perf_counter(), "t0": time.perf_counter()}

    def tick(done: int, total: int, cr) -> None:
        now = time.perf_counter()
        if done == total or now - state["t"] >= every:
            state["t"] = now
            print(f"check {label}: {done}/{total} cases, {now - state['t0']:.0f} s", file=sys.stderr, flush=True)

    return tick


def row(r) -> dict:
    return {
        "property": r.property, "size": list(r.size), "status": r.status,
        "interior_cells": (r.size[0] - 2) * (r.size[1] - 2),
        "enumerated": {"cases": r.cases, "what": "every layout of lethal interior cells x every start x every goal "
                                                  "x each mode"},
        "solved": {"control_paths": r.paths, "solver_queries": r.queries,
                   "decided_by_intervals": r.decided_by_intervals},
        "cases_holding": r.cases_holding, "cases_unknown": r.cases_unknown,
        "unknown_cases": r.unknown_cases[:20],
        "counterexample": r.counterexample, "seconds": round(r.seconds, 2),
    }


def table(results: list) -> None:
    t = Table(title="check: whole-planner properties over every map of a size")
    for col in ("property", "size", "status", "cases", "paths", "queries", "time", "counterexample"):
        t.add_column(col)
    for r in results:
        cx = r.counterexample
        what = (f"{cx['mode']} start {tuple(cx['start'])} goal {tuple(cx['goal'])}: {cx['reason']}" if cx else "")
        t.add_row(r.property, f"{r.size[0]}x{r.size[1]}", r.status, str(r.cases), str(r.paths), str(r.queries),
                  f"{r.seconds:.1f} s", what)
    _console.print(t)


def write_json(path, doc: dict) -> None:
    atomic_write_text(path, json.dumps(doc, indent=2) + "\n")
