"""What ``mutate`` reports: which check caught each seeded bug, as a table, JSON and a score."""

from __future__ import annotations

import json

from rich.table import Table

from ..fileio import atomic_write_text
from .tables import console


def table(results) -> None:
    """Print one row per mutant: the seeded bug, the checks that caught it, the time taken."""
    t = Table(title="mutation check: seeded bugs and what caught them")
    for c in ("mutant", "seeded bug", "caught by", "seconds"):
        t.add_column(c, overflow="fold")
    for r in results:
        t.add_row(r.name, r.what, ", ".join(r.caught_by) or "[red]survived[/]", f"{r.seconds:.0f}")
    console.print(t)


def write_json(path, results) -> None:
    """Write the score and every mutant's result as one JSON document."""
    caught = sum(r.caught for r in results)
    atomic_write_text(path, json.dumps({"score": f"{caught}/{len(results)}", "mutants": [
        {"name": r.name, "what": r.what, "caught_by": r.caught_by, "details": r.details, "seconds": r.seconds}
        for r in results]}, indent=1, default=str))


def score_line(results) -> None:
    """Print how many seeded bugs were caught."""
    print(f"mutation score: {sum(r.caught for r in results)} of {len(results)} seeded bugs caught")
