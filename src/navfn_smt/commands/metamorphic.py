"""``navfn-smt metamorphic``: how often planning commutes with map symmetries."""

from __future__ import annotations

from ..errors import NavfnInputError
from ..fileio import check_writable_dir
from .common import BACKEND_HELP, MODE_HELP, check_files, check_max_cases, suite_or_example


def cmd_metamorphic(args) -> int:
    """Check map symmetries on a suite; counterexamples are saved only under ``--save``."""
    from ..maps.suite import discover, load_map, modes_of
    from ..report import metamorphic as report
    from ..report.tables import progress_bar
    from ..search.metamorphic import TRANSFORMS, run_metamorphic, save_counterexamples

    suite, modes = suite_or_example(args.suite), modes_of(args.mode)
    relations = args.relation or list(TRANSFORMS)
    check_max_cases(args.max_cases)
    if args.save_max < 0:
        raise NavfnInputError("--save-max must not be negative")
    check_files(args.json)
    if args.save:
        check_writable_dir(args.save)
    per_map = [len(load_map(d).cases) for d in discover(suite)]
    total = sum(min(n, args.max_cases or n) for n in per_map) * len(relations) * len(modes)
    with progress_bar(total, f"metamorphic {suite}") as advance:
        outcomes = run_metamorphic(suite, relations, modes, args.backend, args.max_cases, progress=advance)
    rows = report.relation_rows(outcomes, save_counterexamples(outcomes, args.save, args.save_max))
    report.table(rows)
    if args.json:
        report.write_json(args.json, suite, rows)
    report.saved_note(args.save, args.save_max, rows)
    return 0


def register(sub) -> None:
    """The command's parser, its options and its handler."""
    from ..backends import BACKENDS
    from ..maps.suite import MODE_CHOICES
    from ..search.metamorphic import TRANSFORMS

    mm = sub.add_parser("metamorphic", help="check map symmetries: transposes, flips, rotations, padding, cost shifts")
    mm.add_argument("suite", nargs="?", help="suite directory (default: the example suite)")
    mm.add_argument("--relation", action="append", choices=tuple(TRANSFORMS),
                    help="check only this relation (repeatable; default: all)")
    mm.add_argument("--mode", choices=MODE_CHOICES, default="both", help=MODE_HELP)
    mm.add_argument("--backend", choices=BACKENDS, default="jit", help=BACKEND_HELP)
    mm.add_argument("--max-cases", type=int, metavar="N", help="at most this many cases per map (default: all)")
    mm.add_argument("--save", metavar="DIR",
                    help="save counterexamples under DIR as suite map directories (default: not saved)")
    mm.add_argument("--save-max", type=int, default=3, metavar="N", help="counterexamples saved per relation and mode")
    mm.add_argument("--json", metavar="FILE", help="write the counts and counterexamples as JSON")
    mm.set_defaults(func=cmd_metamorphic)
