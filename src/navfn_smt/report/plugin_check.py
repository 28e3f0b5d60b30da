"""What ``navfn-smt plugin-check`` prints and writes: per property and variant, the cases
judged, the failures and the smallest failing case."""

from __future__ import annotations

import json

from rich.table import Table

from ..fileio import atomic_write_text
from .tables import make_console

console = make_console()


def first_case(first) -> str:
    """The smallest failing case in one line (empty when none)."""
    if first is None:
        return ""
    w, h = first["size"]
    return (f"{w}x{h} {first['mode']} robot {tuple(first['robot'])} goal {tuple(first['goal'])} tolerance "
            f"{first['tolerance']:g}: {first['reason']}")


def table(title: str, counts) -> None:
    t = Table(title=title)
    for c in ("property", "variant", "cases", "failing", "smallest failing case"):
        t.add_column(c, justify="right" if c in ("cases", "failing") else "left")
    for c in counts:
        t.add_row(c.property, c.variant, f"{c.judged:,}", f"{c.failed:,}", first_case(c.first))
    console.print(t)


def write_json(path, doc: dict) -> None:
    atomic_write_text(path, json.dumps(doc, indent=1))
