"""``navfn-smt difftest``: every case of a suite against its golden files, bit for bit."""

from __future__ import annotations

from .common import BACKEND_HELP, MODE_HELP, check_files, suite_or_example


def cmd_difftest(args) -> int:
    """Compare every case of a suite with its golden files; exit 1 on any disagreement."""
    from ..difftest.runner import count_cases, run_suite
    from ..maps.suite import modes_of
    from ..engine import engine
    from ..report import difftest as report
    from ..report.tables import progress_bar

    suite, modes = suite_or_example(args.suite), modes_of(args.mode)
    eng = engine(args.jobs, args.scheduler)
    check_files(args.json)
    if args.oracle:
        return _live(args, suite, modes)
    total = count_cases(suite, modes)
    with progress_bar(total, f"difftest {suite} ({args.backend})", enabled=not args.quiet) as advance:
        summary = run_suite(suite, modes, args.backend, eng=eng, total=total,
                            progress=lambda o: advance(o.cases)).as_dict()
    report.table(summary)
    if args.json:
        report.write_json(args.json, suite, args.backend, modes, summary)
    report.closing_line(summary)
    return 0 if summary["failed"] == 0 else 1


def _live(args, suite, modes) -> int:
    """``--oracle DIR``: the spec against the C++ NavFn built in DIR, live, every case."""
    from ..difftest.live import run_live
    from ..difftest.runner import case_count
    from ..maps.suite import discover
    from ..oracle.client import Oracle
    from ..report import difftest as report
    from ..report.tables import progress_bar

    total = sum(case_count(d) for d in discover(suite)) * len(modes)  # no golden files needed
    with Oracle(args.oracle) as oracle:
        label = f"difftest {suite} ({args.backend} against the C++ of {oracle.build['distribution']})"
        with progress_bar(total, label, enabled=not args.quiet) as advance:
            summary = run_live(suite, modes, args.backend, oracle, progress=lambda o: advance(o.cases)).as_dict()
    report.table(summary)
    if args.json:
        report.write_json(args.json, suite, args.backend, modes, summary)
    report.closing_line(summary)
    return 0 if summary["failed"] == 0 else 1


def register(sub) -> None:
    """The command's parser, its options and its handler."""
    from ..backends import BACKENDS
    from ..maps.suite import MODE_CHOICES
    from ..engine import add_arguments as add_engine_arguments

    dt = sub.add_parser("difftest", help="compare every case of a suite with its golden files")
    dt.add_argument("suite", nargs="?", help="suite directory (default: the example suite shipped with the package)")
    dt.add_argument("--mode", choices=MODE_CHOICES, default="both", help=MODE_HELP)
    dt.add_argument("--backend", choices=BACKENDS, default="jit", help=BACKEND_HELP)
    dt.add_argument("--oracle", metavar="DIR", help="compare with the C++ NavFn built in DIR (navfn-smt oracle "
                    "build), run live on every case, instead of the golden files")
    add_engine_arguments(dt, what="difftest chunks")
    dt.add_argument("--json", metavar="FILE", help="write per-map counts and every disagreement as JSON")
    dt.add_argument("--quiet", action="store_true", help="no progress bar")
    dt.set_defaults(func=cmd_difftest)
