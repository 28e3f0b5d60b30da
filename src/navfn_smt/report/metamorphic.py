"""What ``metamorphic`` reports: saved counterexamples, the relation table and the JSON document."""

from __future__ import annotations

import json

from rich.table import Table

from ..fileio import atomic_write_text
from ..search.metamorphic import TRANSFORMS
from .tables import console

_CX_FIELDS = ("case_index", "case", "transformed_case", "mode", "potential", "path", "reached")


def relation_rows(outcomes, saved: list[list[str]]) -> list[dict]:
    """One JSON row per relation and mode: the counts, the saved directories, every counterexample."""
    out = []
    for o, s in zip(outcomes, saved):
        same_potential = TRANSFORMS[o.relation].same_potential
        out.append({
            "relation": o.relation, "mode": o.mode, "cases": o.cases, "holds": o.holds,
            "potential_equal": o.potential_equal if same_potential else None,
            "path_equal": o.path_equal, "start_reached_equal": o.reached_equal, "saved": s,
            "counterexamples": [{k: cx[k] for k in _CX_FIELDS} | {"map": cx["map"].name}
                                for cx in o.counterexamples],
        })
    return out


def table(rows: list[dict]) -> None:
    """Print one line per relation and mode: how many cases agree in each respect."""
    t = Table(title="metamorphic relations: result on the transformed map == transformed result")
    for c in ("relation", "mode", "cases", "potential", "path", "reached", "holds", "saved"):
        t.add_column(c, justify="left" if c in ("relation", "mode") else "right")
    for r in rows:
        potential = "n/a" if r["potential_equal"] is None else str(r["potential_equal"])
        t.add_row(r["relation"], r["mode"], str(r["cases"]), potential, str(r["path_equal"]),
                  str(r["start_reached_equal"]), str(r["holds"]), str(len(r["saved"])))
    console.print(t)


def write_json(path, suite, rows: list[dict]) -> None:
    """Write the counts and counterexamples of every relation as one JSON document."""
    atomic_write_text(path, json.dumps({"suite": str(suite), "relations": rows}, indent=1))


def saved_note(save_dir, save_max: int, rows: list[dict]) -> None:
    """Print where counterexamples went, or (when there are some) how to keep them."""
    if save_dir:
        print(f"counterexamples saved under {save_dir} (at most {save_max} per relation and mode)")
    elif any(r["counterexamples"] for r in rows):
        print("counterexamples not saved (--save DIR keeps them as suite map directories)")
