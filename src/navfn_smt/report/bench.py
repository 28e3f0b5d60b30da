"""What ``bench`` reports: the timing tables and their JSON documents."""

from __future__ import annotations

import json

from rich.table import Table

from ..fileio import atomic_write_text
from .tables import console

SUITE_COLUMNS = ["backend", "mode", "cases", "seconds", "cases_per_second"]
SIZE_COLUMNS = ["backend", "size", "map", "mode", "seconds_per_plan", "path_points", "dropped_pushes", "work_bytes"]


def _table(title: str, rows: list[dict], cols: list[str], headers=None, fmt=None) -> None:
    """Print ``rows`` under ``title``: the given columns, renamed by ``headers``, formatted by ``fmt``."""
    headers = headers or {}
    fmt = fmt or {}
    t = Table(title=title)
    for c in cols:
        t.add_column(headers.get(c, c), justify="right" if c not in ("backend", "mode", "map") else "left")
    for r in rows:
        t.add_row(*(fmt.get(c, str)(r[c]) for c in cols))
    console.print(t)


def suite_table(suite, rows: list[dict]) -> None:
    """Print cases per second per backend and mode on a whole suite."""
    _table("bench: whole suite " + str(suite), rows, SUITE_COLUMNS, headers={"cases_per_second": "cases/s"})


def sizes_table(rows: list[dict]) -> None:
    """Print seconds per plan and working memory per backend, size, map and mode."""
    _table("bench: generated maps, seconds per plan", rows, SIZE_COLUMNS,
           headers={"seconds_per_plan": "s/plan", "path_points": "points", "dropped_pushes": "dropped",
                    "work_bytes": "work MiB"},
           fmt={"work_bytes": lambda b: f"{b / 2**20:.1f}"})


def write_suite_json(path, suite, rows: list[dict]) -> None:
    """Write a suite benchmark as one JSON document."""
    atomic_write_text(path, json.dumps({"suite": str(suite), "results": rows}, indent=1))


def write_sizes_json(path, seed: int, rows: list[dict]) -> None:
    """Write a generated-map benchmark (with the maps' random seed) as one JSON document."""
    atomic_write_text(path, json.dumps({"seed": seed, "results": rows}, indent=1))


# ------------------------------------------------------------------------- whole-map sweep
SWEEP_COLUMNS = ["mode", "size", "goals", "seconds", "goals_per_second", "first_call_seconds", "planned",
                 "issue_4655", "no_path"]


def sweep_table(rows: list[dict]) -> None:
    """Print goals per second of the whole-map sweep per mode."""
    _table("bench: whole-map sweep (one robot pose, every free cell a goal)", rows, SWEEP_COLUMNS,
           headers={"seconds": "s", "goals_per_second": "goals/s", "first_call_seconds": "1st call s",
                    "issue_4655": "#4655", "no_path": "no path", "mode": "mode"})


def write_sweep_json(path, seed: int, rows: list[dict]) -> None:
    """Write a sweep benchmark (with its map's seed) as one JSON document."""
    atomic_write_text(path, json.dumps({"seed": seed, "sweep": rows}, indent=1))
