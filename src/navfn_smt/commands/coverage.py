"""``navfn-smt coverage``: what a suite exercises of the reference spec."""

from __future__ import annotations

import sys
from pathlib import Path

from ..errors import NavfnInputError
from .common import EXAMPLE_SUITE, MODE_HELP, check_files, check_max_cases


def cmd_coverage(args) -> int:
    """Measure what a suite exercises of the reference spec; exit 1 below ``--min-branch``."""
    from ..difftest.coverage import measure
    from ..maps.suite import modes_of
    from ..maps.suite import discover, load_map
    from ..report import coverage as report
    from ..report.tables import progress_bar

    suites = [Path(s) for s in args.suite] if args.suite else [EXAMPLE_SUITE]
    modes = modes_of(args.mode)
    check_max_cases(args.max_cases)
    if args.min_branch is not None and not 0 <= args.min_branch <= 100:
        raise NavfnInputError(f"--min-branch {args.min_branch:g}: a percentage from 0 to 100")
    check_files(args.json)
    total = sum(min(len(load_map(d).cases), args.max_cases or 10**12) for s in suites for d in discover(s))
    with progress_bar(total * len(modes), "coverage") as advance:
        r = measure(suites, modes, args.max_cases, progress=advance)
    report.table(r)
    report.uncovered(r)
    if args.json:
        report.write_json(args.json, suites, modes, r)
    report.closing_line(r)
    if args.min_branch is not None and r["branch_percent"] < args.min_branch:
        print(f"navfn-smt: branch coverage {r['branch_percent']:.1f}% is below --min-branch {args.min_branch:g}%",
              file=sys.stderr)
        return 1
    return 0


def register(sub) -> None:
    """The command's parser, its options and its handler."""
    from ..maps.suite import MODE_CHOICES

    cv = sub.add_parser("coverage", help="line, branch and kernel-decision coverage of the reference spec under a suite")
    cv.add_argument("suite", nargs="*", help="suite directories, measured together (default: the example suite)")
    cv.add_argument("--mode", choices=MODE_CHOICES, default="both", help=MODE_HELP)
    cv.add_argument("--max-cases", type=int, metavar="N", help="at most this many cases per map (the spec runs traced: slow)")
    cv.add_argument("--min-branch", type=float, metavar="PERCENT",
                    help="exit 1, saying so, when branch coverage is below this percentage (0 to 100)")
    cv.add_argument("--json", metavar="FILE", help="write the figures and every uncovered branch as JSON")
    cv.set_defaults(func=cmd_coverage)
