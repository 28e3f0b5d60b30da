"""``navfn-smt search``: counterexample hunts, or the count of every kind on a suite."""

from __future__ import annotations

from pathlib import Path

from ..errors import NavfnInputError
from ..fileio import check_writable_dir
from .common import MODE_HELP, add_planner_arguments, check_files, check_positive, planner_of, vars_of


def cmd_search(args) -> int:
    """Hunt counterexamples of one kind (``--summary SUITE``: count every kind on a suite)."""
    from ..engine import engine
    from ..report import search as report
    from ..search.counterexamples import save_findings
    from ..maps.suite import modes_of
    from ..search.runner import run_search
    from ..spec.arithmetic import X86_64

    eng = engine(args.jobs, args.scheduler)
    check_files(args.json)
    planner = planner_of(args)
    if args.summary:
        if not planner.fix.shipped or planner.arithmetic != X86_64:
            raise NavfnInputError("--summary counts on NavFn as shipped, in the golden files' arithmetic: no "
                                  "--variant, no --target")
        if args.kind:
            raise NavfnInputError("give either a KIND or --summary SUITE, not both")
        from ..search.summary import summarize

        s = summarize(Path(args.summary), modes_of(args.mode), progress=report.progress_line, eng=eng)
        report.summary_table(s)
        if args.json:
            report.write_summary_json(args.json, s)
        return 0
    if not args.kind:
        raise NavfnInputError("give a KIND to search for (or --summary SUITE)")
    from ..search.hunt import parse_costs

    costs_range = parse_costs(args.costs)
    check_positive("--timeout", args.timeout)
    if args.out:
        check_writable_dir(args.out)
    findings, tried = run_search(args.kind, args.mode, args.size, args.max_size, args.timeout, args.seed,
                                 costs_range, progress=report.progress_line, eng=eng, planner=planner)
    rows = [report.finding_row(f, s) for f, s in zip(findings, save_findings(findings, args.out))]
    report.table(args.kind, rows, modes_of(args.mode))
    report.sizes_table(args.kind, tried)
    if args.json:
        report.write_json(args.json, args.kind, vars_of(args), rows, tried)
    report.saved_note(args.out, rows)
    return 0


def register(sub) -> None:
    """The command's parser, its options and its handler."""
    from ..maps.suite import MODE_CHOICES
    from ..engine import add_arguments as add_engine_arguments
    from ..search.kinds import SEARCH_KINDS

    se = sub.add_parser("search", help="hunt counterexamples (random maps, hill climbing, shrinking; replayed "
                        "on the spec), or count each kind on a suite with --summary")
    se.add_argument("kind", nargs="?", choices=SEARCH_KINDS, metavar="KIND",
                    help=f"what to hunt: {', '.join(SEARCH_KINDS)}")
    sz = se.add_mutually_exclusive_group()
    sz.add_argument("--size", nargs=2, type=int, metavar=("W", "H"),
                    help="map size, lethal border included (default: 5 7 for cost, --max-size 9 9 for "
                    "unreached, else hunt on 8 8 and shrink)")
    sz.add_argument("--max-size", nargs=2, type=int, metavar=("W", "H"),
                    help="hunt the smallest map up to W x H: one climb per size, largest interior first, "
                    "resumed in rounds of doubling budgets, sizes not below the smallest counterexample "
                    "dropped (cost: every size alike, the largest gap reported, the best gap per size listed)")
    se.add_argument("--mode", choices=MODE_CHOICES, default="both", help=MODE_HELP)
    add_planner_arguments(se)
    se.add_argument("--timeout", type=float, default=60.0, metavar="S",
                    help="seconds for the whole search, split between modes (counted once the planner is compiled)")
    se.add_argument("--seed", type=int, default=0, metavar="S", help="random seed (same seed and budget: same hunt)")
    se.add_argument("--costs", metavar="LO..HI", help="passable costs of the maps (default 50..253, what "
                    "setCostmap produces); lethal 254 is always allowed")
    se.add_argument("--out", metavar="DIR", help="save each counterexample as a suite map directory under DIR "
                    "(default: nothing written)")
    se.add_argument("--json", metavar="FILE", help="write the findings (or the summary) as JSON")
    se.add_argument("--summary", metavar="SUITE",
                    help="instead of hunting, count how often each kind occurs on a suite (JIT backend)")
    add_engine_arguments(se, "the modes' hunts (the maps of --summary)")
    se.set_defaults(func=cmd_search)
