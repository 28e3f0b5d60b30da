"""``navfn-smt fixes [SUITE]``: the candidate fixes side by side, in each arithmetic asked
(:mod:`navfn_smt.report.candidates`; the table that opens docs/fix.md)."""

from __future__ import annotations

import json
import sys

from ..errors import NavfnInputError
from .common import check_files, check_positive, planners_of, suite_or_example, vars_of

COLUMNS = ("candidate", "arithmetic", "search: kinds found (seeds)", "committed counterexamples still failing (of)",
           "paths changed where shipped plans", "planned where shipped fails", "still fails from a reached start",
           "added paths: length / optimum (median, max)", "plugin plans changed: tolerance 0, 2 cells")


def _row(name: str, arith: str, r: dict, seeds: int) -> list[str]:
    s = r["suite"]
    found = ", ".join(f"{k} {v}/{seeds}" for k, v in r["search"].items() if v) or "none"
    q = (s["added_paths"] or {}).get("length_over_optimum")
    p = r["plugin"]
    committed = ", ".join(f"{k} {a}/{b}" for k, (a, b) in sorted(r["committed"].items()))
    return [name, arith, found, committed or "-",
            f"{s['changed']:,} of {s['original_plans']:,}", f"{s['planned']:,} of {s['original_fails']:,}",
            f"{s['fails_from_a_reached_start']:,}", f"{q['median']:.3f}, {q['max']:.3f}" if q else "-",
            f"{p['0']['differ']:,}, {p['2 cells']['differ']:,} of {p['0']['plans']:,}"]


def _report(path) -> dict:
    """An ``oracle nav2-tests --json`` report; a clear error for anything else."""
    from pathlib import Path

    try:
        doc = json.loads(Path(path).read_text())
    except (OSError, ValueError) as e:
        raise NavfnInputError(f"--nav2-tests {path}: not a readable JSON report ({e})") from None
    if not isinstance(doc, dict) or not {"results", "programs", "variants", "distribution"} <= set(doc):
        raise NavfnInputError(f"--nav2-tests {path}: not a report of `navfn-smt oracle nav2-tests --json`")
    return doc


def _table(columns, rows) -> None:
    """A markdown table (docs/fix.md takes them as they are)."""
    print("| " + " | ".join(columns) + " |")
    print("|---" * len(columns) + "|")
    for row in rows:
        print("| " + " | ".join(str(c) for c in row) + " |")


def _worst_rows(rows):
    for r in rows:
        for w in r.get("worst") or ():
            o, f = w["original"], w["fixed"]
            yield (r["variant"], w["size"], w["case"], w["mode"], f"{1000 * o['seconds']:.0f} ms",
                   f"{1000 * f['seconds']:.0f} ms", f"{o['path_points']:,}, {f['path_points']:,}",
                   f"{o['peak_memory_bytes'] / 2**20:.1f}, {f['peak_memory_bytes'] / 2**20:.1f} MiB")


def _nav2_rows(rows):
    for r in rows:
        for distro, n in (r.get("nav2_tests") or {}).items():
            yield (r["variant"], distro, f"{n['own_passed_shipped']}, {n['own_passed_patched']} of {n['own']}",
                   f"{n['added_failed_shipped']}, {n['added_passed_patched']} of {n['added']}")


WORST_COLUMNS = ("candidate", "size", "case", "mode", "as shipped", "patched", "path points: shipped, patched",
                 "peak memory: shipped, patched")
NAV2_COLUMNS = ("candidate", "distribution", "Nav2's tests passed: shipped, patched",
                "its tests: failed shipped, passed patched")


def cmd_fixes(args) -> int:
    from ..fileio import atomic_write_text
    from ..maps.suite import discover, load_map
    from ..report import candidates as C
    check_files(args.json)
    check_positive("--search-seconds", args.search_seconds, allow_zero=True)
    check_positive("--seeds", args.seeds)
    check_positive("--configs", args.configs)
    if args.worst_cases and not args.oracle:
        raise NavfnInputError("--worst-cases times the C++ as shipped and patched: give --oracle DIR")
    if args.worst_cases:
        from ..bench import check_sizes

        check_sizes(args.worst_cases, 1)
    reports = [_report(f) for f in args.nav2_tests or ()]
    root = suite_or_example(args.suite)
    maps = [load_map(d, root) for d in discover(root)]
    if not maps:
        raise NavfnInputError(f"{root}: no suite map to plan on")
    seeds = list(range(args.seeds))

    def progress(text: str) -> None:
        if not args.quiet:
            print(f"[fixes] {text}", file=sys.stderr, flush=True)

    rows = []
    for target, original, planners in planners_of(args):
        committed = C.committed_counterexamples(C.FAILURE_KINDS, target)
        for planner in planners:
            fix = planner.fix
            progress(f"{planner.label}: the suite")
            r = {"variant": fix.name, "arithmetic": target, "summary": fix.summary,
                 "suite": C.suite_effects(maps, planner, original),
                 "committed": C.still_failing(planner, committed)}
            progress(f"{planner.label}: the plugin")
            r["plugin"] = C.plugin_effects(planner, args.configs)
            r["search"] = (C.search_counts(planner, C.FAILURE_KINDS, args.search_seconds, seeds, progress)
                           if args.search_seconds > 0 else {})
            if args.worst_cases and fix.patches is not None and target == args.targets[0]:
                from ..bench import bench_worst_cases

                progress(f"{fix.name}: the worst cases on {args.oracle}")
                r["worst"] = bench_worst_cases(args.worst_cases, args.oracle, fix, repeat=2)
            if reports and fix.patches is not None:
                r["nav2_tests"] = C.nav2_tests(reports, fix)
            rows.append(r)
    print(f"{root}: {len(maps)} maps, both modes; search: {args.search_seconds:g} s a kind and seed, "
          f"{len(seeds)} seed(s), maps up to 7x7; plugin: {args.configs} generated configurations of 12 pose pairs")
    _table(COLUMNS, [_row(r["variant"], r["arithmetic"], r, len(seeds)) for r in rows])
    for columns, extra in ((WORST_COLUMNS, list(_worst_rows(rows))), (NAV2_COLUMNS, list(_nav2_rows(rows)))):
        if extra:
            print()
            _table(columns, extra)
    if args.json:
        atomic_write_text(args.json, json.dumps({"command": "fixes", "arguments": vars_of(args),
                                                 "suite": str(root), "rows": rows}, indent=1) + "\n")
    return 0


def register(sub) -> None:
    """The command's parser, its options and its handler."""
    from ..spec import fixes
    from ..spec.arithmetic import KNOWN

    p = sub.add_parser("fixes", help="the candidate fixes side by side: the failures each removes, what each changes "
                       "where NavFn as shipped plans, the paths each adds",
                       description="For each candidate fix (every --variant but the original by default, the "
                       "original as the baseline) in each arithmetic: searches for each failure kind on a few seeds, "
                       "the committed counterexamples it still fails, every case of SUITE (default: the example "
                       "suite) in both modes against NavFn as shipped, and the planner plugin's model on generated "
                       "configurations with tolerance 0 and 2 cells.")
    p.add_argument("suite", nargs="?", metavar="SUITE", help="a suite folder (default: the example suite)")
    p.add_argument("--variant", nargs="+", choices=fixes.NAMES, metavar="NAME",
                   help=f"the candidates (default: all: {', '.join(fixes.NAMES)})")
    p.add_argument("--targets", nargs="+", choices=tuple(KNOWN), default=["x86-64", "aarch64"], metavar="NAME",
                   help="the arithmetics to plan in (default: x86-64 aarch64)")
    p.add_argument("--search-seconds", type=float, default=60.0, metavar="S",
                   help="seconds of each search (a kind, a seed; both modes share them); 0: no search (default 60)")
    p.add_argument("--seeds", type=int, default=3, metavar="N", help="searches per kind, seeds 0..N-1 (default 3)")
    p.add_argument("--configs", type=int, default=300, metavar="N",
                   help="generated plugin configurations (12 pose pairs each; default 300)")
    p.add_argument("--oracle", metavar="DIR", help="a build of the C++ (navfn-smt oracle build) with each "
                   "candidate's patch, for --worst-cases")
    p.add_argument("--worst-cases", nargs="+", type=int, metavar="N",
                   help="with --oracle: each patched candidate's worst cases on generated NxN maps, as in bench "
                   "--worst-cases, the best time of two runs")
    p.add_argument("--nav2-tests", nargs="+", metavar="REPORT",
                   help="reports of `oracle nav2-tests --variant all --json` to read each candidate's Nav2 tests from")
    p.add_argument("--quiet", action="store_true", help="no progress lines")
    p.add_argument("--json", metavar="FILE", help="write every figure as JSON")
    p.set_defaults(func=cmd_fixes)
