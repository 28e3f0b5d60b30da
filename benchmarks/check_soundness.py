"""Soundness of the committed bounded checks: every size a report proves, swept concretely.

    python benchmarks/check_soundness.py [--reports docs/reports] [--max-cells 8] [--json FILE]

For each size and property that a committed ``check`` report (``docs/reports/check-*.json``)
proves, every map of the size whose passable cells cost one of 50, 51, 100, 200, 253 (and
every lethal layout), every start and goal, both modes, is planned by the compiled spec and
judged (``navfn_smt.check.soundness``).  Exit 1 when a proved size shows a failure: a
``proved`` that a concrete map refutes.  6 ** cells maps a size: about 20 s at 6 cells, 2 min
at 7, 12 min at 8 on one core.  The test run sweeps the sizes of up to 5 cells
(``tests/test_check_reductions.py``).
"""

from __future__ import annotations

import argparse
import json
import sys
import time
from pathlib import Path

from navfn_smt.check.soundness import COSTS, SWEPT, sweep

REPORTS = Path(__file__).resolve().parent.parent / "docs" / "reports"


def proved(reports: Path, max_cells: int) -> dict:
    """``{(size, variant): [property, ...]}`` of what the reports prove, swept properties only."""
    out: dict = {}
    for f in sorted(reports.glob("check-*.json")):
        doc = json.loads(f.read_text())
        for r in doc["results"]:
            size = tuple(r["size"])
            if r["status"] == "proved" and r["property"] in SWEPT and (size[0] - 2) * (size[1] - 2) <= max_cells:
                out.setdefault((size, doc.get("variant", "original")), set()).add(r["property"])
    return {k: sorted(v) for k, v in sorted(out.items())}


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--reports", type=Path, default=REPORTS)
    ap.add_argument("--max-cells", type=int, default=8)
    ap.add_argument("--json", type=Path)
    a = ap.parse_args()
    rows, bad = [], 0
    for (size, variant), names in proved(a.reports, a.max_cells).items():
        t0 = time.perf_counter()
        got = sweep(*size, variant=variant)
        row = {"size": list(size), "variant": variant, "proved": names, "costs": list(COSTS), "maps": got.maps,
               "cases": got.cases, "failures": {n: got.failures[n] for n in names},
               "seconds": round(time.perf_counter() - t0, 1)}
        fails = sum(row["failures"].values())
        bad += fails
        rows.append(row)
        print(f"{size[0]}x{size[1]} {variant}: {got.maps:,} maps, {got.cases:,} cases, "
              + ", ".join(f"{n} {row['failures'][n]} failures" for n in names) + f" ({row['seconds']} s)",
              flush=True)
        for n in names:
            if got.failures[n]:
                print(f"  UNSOUND: {n} proved, refuted by {got.first[n]}")
    if a.json:
        a.json.write_text(json.dumps({"costs": list(COSTS), "sizes": rows}, indent=1) + "\n")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
