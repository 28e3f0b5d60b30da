"""``navfn-smt fixes [SUITE]``: the candidate fixes side by side, in each arithmetic asked
(:mod:`navfn_smt.report.candidates`; the table that opens docs/fix.md)."""

from __future__ import annotations

import json
import sys

from ..errors import NavfnInputError
from .common import check_files, check_positive, suite_or_example, vars_of

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


def cmd_fixes(args) -> int:
    from ..fileio import atomic_write_text
    from ..maps.suite import discover, load_map
    from ..report import candidates as C
    from ..spec import fixes
    from ..under_test import PlannerUnderTest

    check_files(args.json)
    check_positive("--search-seconds", args.search_seconds, allow_zero=True)
    check_positive("--seeds", args.seeds)
    check_positive("--configs", args.configs)
    names = args.variant or [f.name for f in fixes.FIXES.values()]
    chosen = [fixes.named(n) for n in names]
    root = suite_or_example(args.suite)
    maps = [load_map(d, root) for d in discover(root)]
    if not maps:
        raise NavfnInputError(f"{root}: no suite map to plan on")
    seeds = list(range(args.seeds))

    def progress(text: str) -> None:
        if not args.quiet:
            print(f"[fixes] {text}", file=sys.stderr, flush=True)

    rows = []
    for target in args.targets:
        original = PlannerUnderTest.of_target(target)
        committed = [d for d in C.committed_counterexamples(C.FAILURE_KINDS)
                     if json.loads((d / "counterexample.json").read_text()).get("arithmetic", "x86-64") == target]
        for fix in chosen:
            planner = PlannerUnderTest.of_target(target, fix)
            progress(f"{planner.label}: the suite")
            r = {"variant": fix.name, "arithmetic": target, "summary": fix.summary,
                 "suite": C.suite_effects(maps, planner, original),
                 "committed": C.still_failing(planner, committed)}
            progress(f"{planner.label}: the plugin")
            r["plugin"] = C.plugin_effects(planner, args.configs)
            r["search"] = (C.search_counts(planner, C.FAILURE_KINDS, args.search_seconds, seeds, progress)
                           if args.search_seconds > 0 else {})
            rows.append(r)
    print(f"{root}: {len(maps)} maps, both modes; search: {args.search_seconds:g} s a kind and seed, "
          f"{len(seeds)} seed(s), maps up to 7x7; plugin: {args.configs} generated configurations of 12 pose pairs")
    print("| " + " | ".join(COLUMNS) + " |")
    print("|---" * len(COLUMNS) + "|")
    for r in rows:
        print("| " + " | ".join(_row(r["variant"], r["arithmetic"], r, len(seeds))) + " |")
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
    p.add_argument("--quiet", action="store_true", help="no progress lines")
    p.add_argument("--json", metavar="FILE", help="write every figure as JSON")
    p.set_defaults(func=cmd_fixes)
