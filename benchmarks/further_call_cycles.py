"""How much of the fix's further call's cap of nx*ny cycles the wave uses, on generated maps.

    python benchmarks/further_call_cycles.py [--size N] [--maps M] [--pairs P] [--seed S] [--json FILE]

For each map category of ``navfn-smt suite generate`` (M maps of N x N each) and P random
passable start/goal pairs per map, both modes in turn, the fixed planner's reference spec plans
once and reports its cycles. The further call runs only where the first call (``max(nx*ny/20,
nx+ny)`` cycles) left the start unreached with a buffer holding cells; what it used is the
cycles past the first call's cap, as a share of nx*ny. The condition "the further call's nx*ny
cycles suffice" (proofs/__init__.py) fails on a run where the start stays unreached although it is
joined to the goal: counted as ``capped_unreached``. Evidence, not a proof: it samples maps.
"""

from __future__ import annotations

import argparse
import json
import sys
import time
from pathlib import Path

import numpy as np

from navfn_smt.maps.generators import CATEGORIES, generate_map
from navfn_smt.maps.regions import reaches_all, regions
from navfn_smt.spec.constants import COST_OBS
from navfn_smt.spec.fix import FIX, extra_cycles
from navfn_smt.spec.planner import plan
from navfn_smt.spec.propagation import cycle_limit


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--size", type=int, default=30)
    ap.add_argument("--maps", type=int, default=20)
    ap.add_argument("--pairs", type=int, default=5)
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--json", type=Path)
    a = ap.parse_args()
    rng = np.random.default_rng(a.seed)
    t0 = time.perf_counter()
    runs = further = capped_unreached = 0
    worst = {"share": 0.0}
    for cat in CATEGORIES:
        for idx in range(a.maps):
            costs = np.asarray(generate_map(cat, seed=a.seed, index=idx, size=(a.size, a.size)).costs)
            ny, nx = costs.shape
            free = np.argwhere(costs < COST_OBS)
            if len(free) < 2:
                continue
            for k in range(a.pairs):
                (gy, gx), (sy, sx) = free[rng.integers(len(free), size=2)]
                start, goal, astar = (int(sx), int(sy)), (int(gx), int(gy)), bool(k % 2)
                r = plan(costs, start, goal, astar, fix=FIX, record_trace=False)
                runs += 1
                used = r.cycles - cycle_limit(nx, ny)  # past the first call's cap
                further += "propagation" in r.extra.get("fix", [])
                joined = bool(reaches_all(regions(costs), np.array([[*start, *goal]]))[0])
                capped_unreached += joined and not r.start_reached
                share = max(used, 0) / extra_cycles(nx, ny)
                if share > worst["share"]:
                    worst = {"share": round(share, 4), "category": cat, "index": idx, "start": list(start),
                             "goal": list(goal), "mode": "astar" if astar else "dijkstra", "cycles": r.cycles}
    doc = {"size": a.size, "maps_per_category": a.maps, "pairs": a.pairs, "seed": a.seed, "runs": runs,
           "further_call_ran": further, "capped_unreached": capped_unreached, "worst": worst,
           "seconds": round(time.perf_counter() - t0, 1)}
    print(json.dumps(doc))
    if not runs:
        print("further_call_cycles: no map was planned (--maps 0, or no generated map with two passable cells)", file=sys.stderr)
        return 1
    if a.json:
        a.json.write_text(json.dumps(doc, indent=1) + "\n")
    return 1 if capped_unreached else 0


if __name__ == "__main__":
    sys.exit(main())
