"""What ``search`` reports: the findings table, saved counterexamples, JSON, the summary."""

from __future__ import annotations

import json
import sys
from typing import Optional

import numpy as np
from rich.table import Table

from ..fileio import atomic_write_text, jsonable
from ..search.counterexamples import field_of
from .tables import console


def progress_line(line: str) -> None:
    """A progress line on stderr (every improvement and a heartbeat, terminal or not)."""
    print(line, file=sys.stderr, flush=True)


def finding_row(f, saved: Optional[str] = None) -> dict:
    """One finding as a JSON row (works for the overflow search's finding-like results too)."""
    costs = field_of(f, "costs")
    size = list(field_of(f, "size", None) or (np.asarray(costs).shape[::-1] if costs is not None else []))
    row = {
        "kind": field_of(f, "kind"), "mode": field_of(f, "mode"), "size": [int(v) for v in size],
        "interior_cells": int(max(size[0] - 2, 0) * max(size[1] - 2, 0)) if len(size) == 2 else None,
        "start": list(field_of(f, "start") or []), "goal": list(field_of(f, "goal") or []),
        "detail": jsonable(field_of(f, "detail", {})),
        "seconds": field_of(f, "seconds"), "evaluations": field_of(f, "evaluations"), "plans": field_of(f, "plans"),
        "found_size": list(field_of(f, "found_size") or []) or None, "seed": field_of(f, "seed"),
        "history": jsonable(field_of(f, "history", [])),
        "saved": saved,
    }
    return row


def short(detail: dict) -> str:
    """A finding's detail in a few words."""
    if "gap" in detail:
        return f"gap {detail['gap']}: path {detail['path_cost']} / optimum {detail['optimum']} = {detail['ratio']:.2f}"
    return str(detail.get("reason", ""))


def table(kind: str, rows: list[dict], modes) -> None:
    t = Table(title=f"search {kind}")
    for c in ("mode", "size", "interior", "start", "goal", "found after", "maps", "what"):
        t.add_column(c)
    for r in rows:
        t.add_row(r["mode"], "x".join(map(str, r["size"])), str(r["interior_cells"]), str(tuple(r["start"])),
                  str(tuple(r["goal"])), f"{r['seconds']:.2f} s" if r["seconds"] is not None else "",
                  str(r["evaluations"] or ""), short(r["detail"]))
    console.print(t)
    missing = [m for m in modes if m not in {r["mode"] for r in rows}]
    for m in missing:
        console.print(f"{m}: no counterexample found within the budget")


def sizes_table(kind: str, tried: list) -> None:
    """Per mode, the sizes a ``--max-size`` hunt tried: each size with a counterexample (its
    best score: for ``cost`` the best gap of that size), then a count of the others."""
    if not tried:
        return
    t = Table(title=f"search {kind}: sizes hunted")
    for c in ("mode", "size", "interior", "maps", "seconds", "best"):
        t.add_column(c)
    quiet = {}
    for m in tried:
        for r in m["sizes"]:
            if r["found"]:
                t.add_row(m["mode"], "x".join(map(str, r["size"])), str(r["interior"]), str(r["evaluations"]),
                          f"{r['seconds']:.2f}", f"{r['best']:g}")
            else:
                quiet[m["mode"]] = quiet.get(m["mode"], 0) + 1
    console.print(t)
    for mode, n in quiet.items():
        console.print(f"{mode}: {n} more size(s) hunted without a counterexample (--json lists every size)")


def write_json(path, kind: str, args: dict, rows: list[dict], tried: list) -> None:
    doc = {"kind": kind, "arguments": jsonable(args), "findings": rows, "sizes_tried": tried}
    atomic_write_text(path, json.dumps(doc, indent=2) + "\n")


def saved_note(out_dir, rows) -> None:
    if out_dir:
        for r in rows:
            if r["saved"]:
                console.print(f"saved {r['saved']}")
    elif rows:
        console.print("counterexamples not saved (--out DIR keeps them as suite map directories)")


_SUMMARY_ROWS = (
    ("cases", "cases"), ("paths returned", "paths"),
    ("obtuse turn: paths %", "turn_per_path_percent"), ("obtuse turn: per step %", "turn_per_step_percent"),
    ("turn >= 90 degrees: per step %", "turn_ge90_per_step_percent"),
    ("oscillation: paths %", "oscillation_per_path_percent"),
    ("oscillation: per step %", "oscillation_per_step_percent"),
    ("incomplete", "incomplete"), ("unreached (connected)", "unreached"),
    ("int-conversion, start unreached", "int_conversion_start_unreached"),
    ("int-conversion, mid-path", "int_conversion_mid_path"), ("undefined (reads outside)", "undefined"),
    ("cost gap > 0: paths %", "gap_positive_percent"), ("cost gap: mean", "gap_mean"),
    ("cost gap: max", "gap_max"), ("ratio path/optimum: max", "ratio_max"),
)


def summary_table(s: dict) -> None:
    """Per mode, the whole suite; beside it the paper's figures."""
    t = Table(title=f"search --summary {s['suite']} ({s['maps']} maps, {s['seconds']} s)")
    t.add_column("measure")
    for m in s["modes"]:
        t.add_column(m, justify="right")
    t.add_column("paper", justify="right")
    paper = {"turn_per_step_percent": s["paper"]["turn_per_step_percent"],
             "oscillation_per_step_percent": s["paper"]["oscillation_per_step_percent"]}
    for label, key in _SUMMARY_ROWS:
        t.add_row(label, *[str(s["total"][m][key]) for m in s["modes"]], str(paper.get(key, "")))
    console.print(t)
    console.print("turn: (p[k]-p[k-1]).(p[k+1]-p[k]) < 0 over the M-2 inner points of a returned path "
                  "(right angle or more: <= 0 with both steps non-zero); oscillation: p[k] == p[k-2] over its "
                  "M-2 points from the third; paper: 1.91% obtuse turns, 0.13% oscillations", markup=False)


def write_summary_json(path, s: dict) -> None:
    atomic_write_text(path, json.dumps(jsonable(s), indent=2) + "\n")
