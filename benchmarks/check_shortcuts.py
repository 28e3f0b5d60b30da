"""The exploration of some cases with and without the flips decided before a solver is asked.

    python benchmarks/check_shortcuts.py [--case 4 6 1 1 2 3 astar ...] [--json FILE]

Each ``--case W H SX SY GX GY MODE`` (open layout: every interior cell passable) is explored
for ``start-reached`` over costs 50..253 twice in this process: every flip asked of the solvers
(``shortcuts=False``), then with unsat cores and sampled maps first (``shortcuts=True``, what
``check`` does).  Both must reach the same verdict; the table gives each run's control paths,
flips, the flips decided by a core or a sample, and its time.
"""

from __future__ import annotations

import argparse
import json
import sys
import time

DEFAULT = [["4", "5", "1", "1", "2", "3", "dijkstra"], ["4", "5", "1", "1", "2", "3", "astar"],
           ["4", "6", "1", "1", "2", "3", "astar"]]


def explore_both(spec: list) -> dict:
    from navfn_smt.check.bounded import Case, explore
    from navfn_smt.smt.domains import FPDomain

    w, h, sx, sy, gx, gy = map(int, spec[:6])
    case = Case(w, h, frozenset(), (sx, sy), (gx, gy), spec[6] == "astar")
    row = {"case": f"{w}x{h} {spec[6]} ({sx}, {sy}) -> ({gx}, {gy})"}
    for on in (False, True):
        t = time.perf_counter()
        r = explore(case, ["start-reached"], 50, 253, FPDomain, shortcuts=on)
        row["with" if on else "without"] = {
            "status": r.results["start-reached"].status, "paths": r.paths, "flips": r.flip_queries,
            "by_core": r.cached_unsat, "by_sample": r.sampled_sat, "seconds": round(time.perf_counter() - t, 1)}
    return row


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--case", nargs=7, action="append", metavar=("W", "H", "SX", "SY", "GX", "GY", "MODE"))
    ap.add_argument("--json", metavar="FILE")
    args = ap.parse_args()
    rows = []
    for spec in args.case or DEFAULT:
        row = explore_both(spec)
        rows.append(row)
        a, b = row["without"], row["with"]
        print(f"{row['case']}: without {a['paths']} paths, {a['flips']} flips, {a['seconds']} s; "
              f"with {b['paths']} paths, {b['flips']} flips ({b['by_core']} by a core, {b['by_sample']} by a "
              f"sample), {b['seconds']} s; {a['status']} / {b['status']}", flush=True)
    if args.json:
        with open(args.json, "w") as f:
            json.dump(rows, f, indent=2)
    return 0 if all(r["with"]["status"] == r["without"]["status"] for r in rows) else 1


if __name__ == "__main__":
    sys.exit(main())
