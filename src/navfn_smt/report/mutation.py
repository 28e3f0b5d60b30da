"""Reports of a mutation run: a progress line per finished detector, the table, JSON."""

from __future__ import annotations

import json
import sys

from rich.table import Table

from ..fileio import atomic_write_text
from ..search.mutation import BACKENDS
from .tables import console


def progress_line(done: list, total: int):
    """A ``progress(mutant, detector, result)`` that prints one plain line per finished
    detector to stderr (terminal or not), counting finished mutants in ``done``."""

    def show(mutant: str, detector: str, d: dict) -> None:
        verdict = "error: " + d["error"] if d.get("error") else ("caught" if d["caught"] else "not caught")
        detail = d.get("detail")
        if detector == "prove" and isinstance(detail, list) and detail:
            detail = detail[-1]
        more = f" ({detail})" if detail and isinstance(detail, str) and d["caught"] else ""
        print(f"[{len(done)}/{total} mutants done] {mutant}: {detector} {verdict}{more} in {d['seconds']} s",
              file=sys.stderr, flush=True)

    return show


def table(results) -> None:
    t = Table(title="mutation check: seeded bugs and what caught them")
    for c in ("mutant", "seeded bug", "caught by", *BACKENDS, "not run (cannot catch)", "seconds"):
        t.add_column(c, overflow="fold")
    for r in results:
        t.add_row(r.name, r.what, ", ".join(r.caught_by) or "[red]survived[/]",
                  *("[green]caught[/]" if r.caught_with(b) else "[red]survived[/]" for b in BACKENDS),
                  ", ".join(r.skipped) or "-", f"{r.seconds:.0f}")
    console.print(t)
    for r in results:
        for det, err in r.errors.items():
            console.print(f"[red]{r.name}: {det} failed to run: {err}[/]")


def score_line(results, seconds: float) -> None:
    """Print how many seeded bugs were caught, in all and per backend."""
    per = scores(results)
    each = ", ".join(f"{b} {per[b]}" for b in BACKENDS)
    print(f"mutation score: {sum(r.caught for r in results)} of {len(results)} seeded bugs caught "
          f"({each}) in {seconds:.0f} s")


def scores(results) -> dict:
    return {b: f"{sum(r.caught_with(b) for r in results)}/{len(results)}" for b in BACKENDS}


def write_json(path, results, seconds: float) -> None:
    atomic_write_text(path, json.dumps({
        "score": f"{sum(r.caught for r in results)}/{len(results)}",
        "score_per_backend": scores(results),
        "seconds": round(seconds, 1),
        "mutants": [{"name": r.name, "what": r.what, "caught_by": r.caught_by,
                     "caught_with": {b: r.caught_with(b) for b in BACKENDS}, "not_run": r.skipped,
                     "details": r.details, "errors": r.errors, "seconds": r.seconds} for r in results],
    }, indent=1, default=str))
