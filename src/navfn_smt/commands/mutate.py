"""``navfn-smt mutate``: seeded bugs, and which check catches each, per backend."""

from __future__ import annotations

from ..errors import NavfnInputError
from .common import check_files, check_positive, suite_or_example


def cmd_mutate(args) -> int:
    """Seed bugs in the kernels and domains and report which checks catch them, per backend."""
    import time

    from ..report import mutation as report
    from ..search.mutation import MUTANTS, run_mutants
    from ..smt.runner import default_proof_files

    unknown = set(args.mutant or []) - {m.name for m in MUTANTS}
    if unknown:
        raise NavfnInputError(f"unknown mutant(s): {', '.join(sorted(unknown))}")
    if args.jobs < 1:
        raise NavfnInputError("--jobs must be at least 1")
    check_positive("--timeout", args.timeout)
    check_files(args.json)
    chosen = [m for m in MUTANTS if not args.mutant or m.name in args.mutant]
    files = default_proof_files()
    t0 = time.perf_counter()
    done: list = []
    results = run_mutants(chosen, files, suite_or_example(args.suite), args.timeout, args.jobs,
                          progress=report.progress_line(done, len(chosen)), on_done=done.append)
    report.table(results)
    if args.json:
        report.write_json(args.json, results, time.perf_counter() - t0)
    report.score_line(results, time.perf_counter() - t0)
    return 1 if any(r.errors for r in results) else 0


def register(sub) -> None:
    """The command's parser, its options and its handler."""
    mu = sub.add_parser("mutate", help="seed bugs in the kernels and domains; report which checks catch them")
    mu.add_argument("--mutant", action="append", metavar="NAME", help="run only this mutant (repeatable)")
    mu.add_argument("--suite", help="suite for the difftest detector (default: the example suite)")
    mu.add_argument("--timeout", type=float, default=30.0, metavar="S", help="seconds per solver query")
    mu.add_argument("--jobs", type=int, default=2, metavar="N", help="mutants checked at the same time")
    mu.add_argument("--json", metavar="FILE", help="write every mutant's result as JSON")
    mu.set_defaults(func=cmd_mutate)
