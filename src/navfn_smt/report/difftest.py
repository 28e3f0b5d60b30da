"""What ``difftest`` reports: the agreement table, the JSON document and the closing line."""

from __future__ import annotations

import json

from rich.table import Table

from ..fileio import atomic_write_text
from .tables import console


def _value(v, bits: bool = False) -> str:
    """A value as the detail holds it; a float32 ``{value, bits}`` with its bit pattern if ``bits``."""
    if isinstance(v, dict) and "value" in v:
        return f"{v['value']!r} ({v['bits']})" if bits else repr(v["value"])
    if isinstance(v, list):
        return "(" + ", ".join(_value(x, bits) for x in v) + ")"
    return str(v)


def _ours_golden(ours, golden) -> str:
    """``ours A, golden B``; float32 bit patterns too when the printed values are equal (NaNs)."""
    bits = _value(ours) == _value(golden)
    return f"ours {_value(ours, bits)}, golden {_value(golden, bits)}"


def describe(d) -> str:
    """A disagreement in one line: where, which field, and our value against the golden file's."""
    if d is None:
        return "-"
    det = d["detail"]
    where = f"{d['map']} case {d['case_index']} {tuple(d['case'])}: {d['field']}"
    if d["field"] == "potential" and "cell" in det:
        where += (f" at cell {tuple(det['cell'])}: {_ours_golden(det['ours'], det['golden'])}"
                  f" ({det['cells_differing']} cells differ)")
    elif d["field"] == "potential":
        where += (f" hash differs; start potential: "
                  f"{_ours_golden(det['start_potential'], det['golden_start_potential'])}")
        if "note" in det:
            where += f" ({det['note']})"
    elif d["field"] == "path" and "point" in det:
        where += f" at point {det['point']}: {_ours_golden(det['ours'], det['golden'])}"
        if det["length"] != det["golden_length"]:
            where += f"; length: ours {det['length']}, golden {det['golden_length']}"
    elif d["field"] == "path":
        where += f" length: ours {det['length']}, golden {det['golden_length']}"
    elif d["field"] == "trace" and "position" in det:
        where += f" at position {det['position']}: {_ours_golden(det['ours'], det['golden'])}"
    elif d["field"] == "trace":
        where += f" hash differs; length: ours {det['length']}"
        if "golden_length" in det:
            where += f", golden {det['golden_length']}"
    elif "ours" in det:
        where += f": {_ours_golden(det['ours'], det['golden'])}"
    return where


def table(summary: dict) -> None:
    """Print one row per category and mode: cases, agreeing cases, the first disagreement."""
    t = Table(title="difftest: agreement with the golden outputs")
    t.add_column("category")
    t.add_column("mode")
    t.add_column("cases", justify="right")
    t.add_column("agreeing", justify="right")
    t.add_column("first disagreement (ours vs golden file)", overflow="fold")
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


def level_table(summary: dict) -> None:
    """The plugin or costmap level: counts by the C++'s outcome, then the first disagreements."""
    build = f" for {summary['target']} ({summary['arithmetic']})" if summary.get("target") else ""
    t = Table(title=f"difftest --level {summary['level']}: the model against the C++ of {summary['distribution']}"
                    f"{build}")
    t.add_column("C++ outcome")
    t.add_column("cases", justify="right")
    for outcome, n in summary["outcomes"].items():
        t.add_row(str(outcome), str(n))
    console.print(t)
    if summary.get("sqrt_match"):
        print("the distance-transform layer's square roots, per configuration that has one: " + ", ".join(
            f"{k}: {v}" for k, v in summary["sqrt_match"].items()))
    if summary.get("cpu_sqrt"):
        print(cpu_sqrt_line(summary["cpu_sqrt"]))
    for d in summary["disagreements"][:5]:
        print(f"{d['config']} case {d['case']}: {d['field']}: model {d['model']!r}, C++ {d['cpp']!r}")
    extra = [f"{summary[k]} {k.replace('_', ' ')}" for k in ("undefined_behaviour", "log_lines") if k in summary]
    print(f"{summary['passed']} passed, {summary['failed']} failed" + (f" ({', '.join(extra)})" if extra else ""))


def write_level_json(path, summary: dict) -> None:
    atomic_write_text(path, json.dumps(summary, indent=1))


def cpu_sqrt_line(c: dict) -> str:
    """What this machine's Eigen square root is, against the model's (docs/distributions.md)."""
    counts = ", ".join(f"{k} {v}" for k, v in c["differ"].items())
    head = f"this machine's Eigen sqrt on the integers below {c['values']}: differs from the model's {counts}; "
    if c["matches"] == "eigen-sse-amd":
        return head + "it is the emulated AMD Zen rsqrtps: the model's default reproduces it"
    if c["matches"] == "exact":
        return head + "it is correctly rounded: the model reproduces it with sqrt='exact'"
    if c["matches"]:
        return head + f"it is the model's {c['matches']} (the model's default is eigen-sse-amd)"
    return head + (f"sqrt(49) = {c['sqrt_49']!r}: this CPU's rsqrtps is not modelled, so the distance-transform "
                   f"layer may differ where a distance rounds across a cost-table step or the cut-off")
