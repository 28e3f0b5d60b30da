"""Soak: the difftest run again and again in one process; resident memory after each round.

    python benchmarks/soak.py [--rounds-example 5] [--rounds-shared 2] [--shared DIR]

Reads RSS from /proc/self/statm (Linux).  A leak shows as RSS rising round after round on the
same suite; the first round of each suite includes compiling (or loading) the JIT and the
suite's maps.
"""

from __future__ import annotations

import argparse
import gc
import os
import sys
import time
from pathlib import Path

from navfn_smt.difftest.runner import run_suite, summarize

EXAMPLE = Path(__file__).resolve().parent.parent / "src" / "navfn_smt" / "examples" / "suite"
SHARED = Path(os.environ.get("NAVFN_SHARED", Path(__file__).resolve().parent.parent.parent / "shared")) / "navfn-suite"


def rss_mib() -> float:
    with open("/proc/self/statm") as f:
        return int(f.read().split()[1]) * os.sysconf("SC_PAGE_SIZE") / 2**20


def soak(suite: Path, rounds: int, label: str) -> list[float]:
    out = []
    for r in range(1, rounds + 1):
        t0 = time.perf_counter()
        s = summarize(run_suite(suite, ("astar", "dijkstra"), "jit", 1))
        gc.collect()
        out.append(rss_mib())
        print(f"{label} round {r}: {s['passed'] + s['failed']} cases, {s['failed']} failed, {time.perf_counter() - t0:.1f} s, "
              f"RSS {out[-1]:.1f} MiB", flush=True)
    return out


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--rounds-example", type=int, default=5)
    ap.add_argument("--rounds-shared", type=int, default=2)
    ap.add_argument("--shared", type=Path, default=SHARED)
    a = ap.parse_args(argv)
    print(f"start: RSS {rss_mib():.1f} MiB", flush=True)
    ex = soak(EXAMPLE, a.rounds_example, "example suite")
    sh = []
    if a.rounds_shared and a.shared.is_dir():
        sh = soak(a.shared, a.rounds_shared, "shared suite")
    elif a.rounds_shared:
        print(f"shared suite not found at {a.shared}; skipped")
    # growth after the first round of each suite (the first loads code and data)
    growth = max([ex[-1] - ex[1]] if len(ex) > 1 else [0.0]) + (sh[-1] - sh[0] if len(sh) > 1 else 0.0)
    print(f"growth after warm-up: {growth:+.1f} MiB")
    return 0


if __name__ == "__main__":
    sys.exit(main())
