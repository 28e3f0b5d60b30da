"""Scale: the difftest of ever larger suites on local Dask workers; wall time, cases per second
and the driver's peak resident memory per suite size.

    python benchmarks/scale_difftest.py [--cases 100000 300000 1000000] [--maps 10] [--size 30]
                                        [--jobs 2] [--mode astar] [--dir DIR] [--json FILE]

Every suite has the same maps (``--maps`` maps of ``--size`` x ``--size`` cells, half of the
``random`` category and half ``walls``, drawn by the package's generator with fixed seeds);
only the number of cases per map grows.  Golden files are recorded by our own spec
(``navfn-smt suite record``'s :func:`record_suite`): they say nothing about the C++ original,
but the difftest does exactly the same work on them (plan, hash, compare every field), which
is what is measured here.

Each difftest runs in a fresh subprocess, so that its peak resident memory is that of one
suite size; the worker processes are separate and not counted.  The figure is ``VmHWM`` of
``/proc/self/status`` (the peak of the process's own memory); ``ru_maxrss`` is printed beside
it, and is the same as long as the parent is small: Linux carries the parent's resident size
over a fork and exec into the child's ``ru_maxrss``, which is why generating and recording
(timed too, one CPU) also run in a subprocess of their own.
"""

from __future__ import annotations

import argparse
import json
import resource
import subprocess
import sys
import tempfile
import time
from pathlib import Path

CATEGORIES = ("random", "walls")  # at 30x30, at least 476 passable cells: 226,000 pairs a map


def make_suite(out: Path, cases: int, maps: int, size: int, mode: str) -> dict:
    """Generate ``maps`` maps with ``cases // maps`` cases each and record their golden files."""
    from navfn_smt.difftest.record import record_suite
    from navfn_smt.maps.generators import generate_suite

    per_map = cases // maps
    t0 = time.perf_counter()
    for k, category in enumerate(CATEGORIES):
        count = maps // len(CATEGORIES) + (k < maps % len(CATEGORIES))
        generate_suite(out, category, count=count, seed=7, size=(size, size), paths=per_map)
    t1 = time.perf_counter()
    record_suite(out, (mode,), full_first=5)
    t2 = time.perf_counter()
    return {"generate_s": round(t1 - t0, 1), "record_s": round(t2 - t1, 1)}


def peak_rss_mib() -> float:
    """The peak resident memory of this process's own address space (``VmHWM``), in MiB."""
    for line in Path("/proc/self/status").read_text().splitlines():
        if line.startswith("VmHWM:"):
            return int(line.split()[1]) / 1024
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024  # pragma: no cover - not Linux


def difftest_child(suite: str, jobs: int, mode: str) -> None:
    """In the fresh subprocess: one difftest on ``jobs`` local workers; its figures as JSON on stdout."""
    from navfn_smt.difftest.runner import count_cases, run_suite
    from navfn_smt.engine import Engine

    total = count_cases(suite, (mode,))
    up: list[float] = []
    t0 = time.perf_counter()
    s = run_suite(suite, (mode,), "jit", eng=Engine(jobs=jobs), total=total,
                  on_client=lambda c: up.append(time.perf_counter() - t0)).as_dict()
    wall = time.perf_counter() - t0
    print(json.dumps({"cases": total, "passed": s["passed"], "failed": s["failed"], "wall_s": round(wall, 1),
                      "startup_s": round(up[0], 1),
                      "cases_per_s": round(total / wall),
                      "driver_peak_rss_mib": round(peak_rss_mib(), 1),
                      "driver_ru_maxrss_mib": round(resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024, 1)}))


def run_size(work: Path, cases: int, a) -> dict:
    """Generate and record one suite, then difftest it in a fresh subprocess."""
    suite = work / f"suite-{cases}"
    row = {"maps": a.maps, "cases_per_map": cases // a.maps,
           **_subprocess("--make", str(suite), "--cases", str(cases), "--maps", str(a.maps), "--size", str(a.size),
                         "--mode", a.mode)}
    row.update(_subprocess("--child", str(suite), "--jobs", str(a.jobs), "--mode", a.mode))
    return row


def _subprocess(*args: str) -> dict:
    """This script run with ``args``; the JSON object it prints last."""
    p = subprocess.run([sys.executable, __file__, *args], capture_output=True, text=True)
    if p.returncode != 0:
        raise SystemExit(f"{' '.join(args)} failed:\n{p.stderr}")
    return json.loads(p.stdout.strip().splitlines()[-1])


def print_table(rows: list[dict], jobs: int) -> None:
    print(f"\n{'cases':>9} {'maps':>4} {'per map':>8} {'generate':>9} {'record':>8} {'difftest':>9} "
          f"{'(start-up)':>10} {'cases/s':>8} {'driver peak RSS':>16} {'(ru_maxrss)':>11}   (difftest on {jobs} local workers)")
    for r in rows:
        print(f"{r['cases']:>9,} {r['maps']:>4} {r['cases_per_map']:>8,} {r['generate_s']:>8.1f}s {r['record_s']:>7.1f}s "
              f"{r['wall_s']:>8.1f}s {r['startup_s']:>9.1f}s {r['cases_per_s']:>8,} {r['driver_peak_rss_mib']:>12.1f} MiB {r['driver_ru_maxrss_mib']:>7.1f} MiB"
              + ("" if r["failed"] == 0 else f"  ({r['failed']} disagree!)"))


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--cases", type=int, nargs="+", default=[100_000, 300_000, 1_000_000])
    ap.add_argument("--maps", type=int, default=10)
    ap.add_argument("--size", type=int, default=30, help="map side in cells, border included")
    ap.add_argument("--jobs", type=int, default=2, help="local worker processes of the difftest")
    ap.add_argument("--mode", choices=("astar", "dijkstra"), default="astar")
    ap.add_argument("--dir", type=Path, help="where the suites go (default: a temporary directory, removed)")
    ap.add_argument("--json", type=Path, help="also write the rows as JSON")
    ap.add_argument("--child", help=argparse.SUPPRESS)
    ap.add_argument("--make", help=argparse.SUPPRESS)
    a = ap.parse_args(argv)
    if a.make:
        print(json.dumps(make_suite(Path(a.make), a.cases[0], a.maps, a.size, a.mode)))
        return 0
    if a.child:
        difftest_child(a.child, a.jobs, a.mode)
        return 0
    with tempfile.TemporaryDirectory(prefix="navfn-scale-", dir=a.dir) as tmp:
        rows = []
        for n in a.cases:
            rows.append(run_size(Path(tmp), n, a))
            r = rows[-1]
            print(f"{n:,} cases: generated in {r['generate_s']} s, recorded in {r['record_s']} s, "
                  f"difftest {r['wall_s']} s, driver peak RSS {r['driver_peak_rss_mib']} MiB", flush=True)
    print_table(rows, a.jobs)
    if a.json:
        a.json.write_text(json.dumps(rows, indent=1))
    return 0 if all(r["failed"] == 0 for r in rows) else 1


if __name__ == "__main__":
    sys.exit(main())
