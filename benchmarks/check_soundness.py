"""Soundness of the committed bounded checks: every size a report proves, swept concretely.

    python benchmarks/check_soundness.py [--reports docs/reports] [--max-cells 8] [--json FILE]
    python benchmarks/check_soundness.py --open W H [--open W H ...] [--random MAPS --seed S]

For each size and property that a committed ``check`` report (``docs/reports/check-*.json``)
proves, every map of the size whose passable cells cost one of 50, 51, 100, 200, 253 (and
every lethal layout), every start and goal, both modes, is planned by the compiled spec and
judged (``navfn_smt.check.soundness``); then ``--random MAPS`` (default 1000) seeded random
maps of the size whose passable costs are drawn from the whole range 50..253, so that every cost
value, not only the five, meets the proved verdict.  Exit 1 when a proved size shows a failure:
a ``proved`` that a concrete map refutes.  6 ** cells maps a size: about 20 s at 6 cells, 2 min
at 7, 12 min at 8 on one core.  The test run sweeps the sizes of up to 5 cells
(``tests/test_check_reductions.py``).

``--open W H`` sweeps a size no report proves (an open size) the same way and reports what
fails there: a failure is then a counterexample (replay it with ``navfn-smt plan``), and none
is evidence, not a proof.  ``--random MAPS`` replaces the product over the reduced set by MAPS
seeded random maps over the whole range 50..253 (each cell lethal with probability 0.15).
"""

from __future__ import annotations

import argparse
import json
import sys
import time
from pathlib import Path

from navfn_smt.check.soundness import COSTS, SWEPT, sample, sweep
from navfn_smt.spec import fixes
from navfn_smt.under_test import PlannerUnderTest

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
    ap.add_argument("--open", nargs=2, type=int, action="append", metavar=("W", "H"),
                    help="sweep this size (no report proves it): failures are counterexamples")
    ap.add_argument("--random", type=int, metavar="MAPS", default=None,
                    help="MAPS random maps per size, each passable cost drawn from the whole range 50..253 (with "
                         "--open: instead of the reduced product; else: besides it, default 1000)")
    ap.add_argument("--seed", type=int, default=0)
    a = ap.parse_args()
    if a.open:
        return open_sizes(a)
    rows, bad = [], 0
    maps = 1000 if a.random is None else a.random
    for (size, variant), names in proved(a.reports, a.max_cells).items():
        planner = PlannerUnderTest(fix=fixes.named(variant))
        for how, run in (("reduced product", lambda: sweep(*size, planner=planner)),
                         (f"{maps} random maps, costs 50..253, seed {a.seed}",
                          lambda: sample(*size, maps, a.seed, planner=planner))):
            t0 = time.perf_counter()
            got = run()
            row = {"size": list(size), "variant": variant, "proved": names, "sweep": how, "maps": got.maps,
                   "cases": got.cases, "failures": {n: got.failures[n] for n in names},
                   "seconds": round(time.perf_counter() - t0, 1)}
            bad += sum(row["failures"].values())
            rows.append(row)
            print(f"{size[0]}x{size[1]} {variant}, {how}: {got.maps:,} maps, {got.cases:,} cases, "
                  + ", ".join(f"{n} {row['failures'][n]} failures" for n in names) + f" ({row['seconds']} s)",
                  flush=True)
            for n in names:
                if got.failures[n]:
                    print(f"  UNSOUND: {n} proved, refuted by {got.first[n]}")
    if not rows:
        print(f"check_soundness: no size of at most {a.max_cells} cells is proved by a report in {a.reports}: "
              "nothing swept", file=sys.stderr)
        return 1
    if a.json:
        a.json.write_text(json.dumps({"costs": list(COSTS), "sizes": rows}, indent=1) + "\n")
    return 1 if bad else 0


def open_sizes(a) -> int:
    """Sweep the ``--open`` sizes (the reduced product, or ``--random`` maps); exit 1 when a
    property fails on one of them (a counterexample, printed)."""
    rows, bad = [], 0
    for nx, ny in a.open:
        t0 = time.perf_counter()
        got = sample(nx, ny, a.random, a.seed) if a.random else sweep(nx, ny)
        row = {"size": [nx, ny], "maps": got.maps, "cases": got.cases, "failures": dict(got.failures),
               "first": got.first, "seconds": round(time.perf_counter() - t0, 1),
               **({"random": a.random, "seed": a.seed} if a.random else {"costs": list(COSTS)})}
        rows.append(row)
        bad += sum(got.failures.values())
        print(f"{nx}x{ny} (open): {got.maps:,} maps, {got.cases:,} cases, "
              + ", ".join(f"{n} {got.failures[n]} failures" for n in SWEPT) + f" ({row['seconds']} s)", flush=True)
        for n, first in got.first.items():
            print(f"  counterexample to {n}: {first}")
    if a.json:
        a.json.write_text(json.dumps({"open": rows}, indent=1) + "\n")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
