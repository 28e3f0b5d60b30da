"""Scaling of a bounded check on the Dask engine: the same size checked on 1, 2, ... workers.

    python benchmarks/check_scaling.py [--size 3 7] [--workers 1 2] [--properties complete start-reached]
                                       [--serial] [--json FILE]

For each number of workers a fresh Dask ``LocalCluster`` of that many single-threaded worker
processes is started (by the engine's own ``client``, as ``--jobs N`` starts it) and ``check``
runs on it through its scheduler address, as with ``--scheduler`` (the cluster's start-up
is not timed, the check's scheduling is); ``--serial`` adds the run in this process without
Dask.  Each run must reach the same verdicts and the same counts (cases, representatives,
control paths, queries): the engine changes where the cases run, never what they find.  The
table gives each run's wall time and its speed-up over one worker.
"""

from __future__ import annotations

import argparse
import json
import sys
import time


def run(size, names, eng) -> tuple[float, list]:
    """Check ``size`` for ``names`` on ``eng``: (seconds, per property [status, cases, explored, paths, queries])."""
    from navfn_smt.check.runner import check_one_size
    from navfn_smt.maps.suite import modes_of

    t = time.perf_counter()
    got = check_one_size(names, size[0], size[1], modes_of("both"), 50, 253, jobs=eng)
    seconds = time.perf_counter() - t
    return seconds, [[n, got[n].status, got[n].cases, got[n].representatives, got[n].paths,
                      got[n].queries] for n in names]


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--size", nargs=2, type=int, default=[3, 7], metavar=("W", "H"))
    ap.add_argument("--workers", nargs="+", type=int, default=[1, 2])
    ap.add_argument("--properties", nargs="+", default=["complete", "start-reached"])
    ap.add_argument("--serial", action="store_true", help="also time the check in this process, without Dask")
    ap.add_argument("--json", help="write the rows here")
    a = ap.parse_args()
    from navfn_smt.engine import Engine, client

    rows = []
    if a.serial:
        s, res = run(a.size, a.properties, Engine(1))
        rows.append({"engine": "this process", "workers": 1, "seconds": round(s, 1), "results": res})
        print(f"this process: {s:.1f} s", flush=True)
    for n in a.workers:
        with client(Engine(n)) as c:
            s, res = run(a.size, a.properties, Engine(scheduler=c.scheduler.address))
        rows.append({"engine": "dask", "workers": n, "seconds": round(s, 1), "results": res})
        print(f"dask, {n} worker(s): {s:.1f} s", flush=True)
    base = next((r["seconds"] for r in rows if r["engine"] == "dask" and r["workers"] == 1), None)
    print(f"\ncheck {' '.join(a.properties)} --size {a.size[0]} {a.size[1]}")
    print("| engine | workers | wall time | speed-up over 1 worker |\n|---|---|---|---|")
    for r in rows:
        up = f"{base / r['seconds']:.2f}x" if base else ""
        print(f"| {r['engine']} | {r['workers']} | {r['seconds']:.1f} s | {up} |")
    same = all(r["results"] == rows[0]["results"] for r in rows)
    print("same verdicts and counts on every engine:", same)
    if a.json:
        with open(a.json, "w") as f:
            json.dump({"size": a.size, "properties": a.properties, "rows": rows, "same": same}, f, indent=1)
    return 0 if same else 1


if __name__ == "__main__":
    sys.exit(main())
