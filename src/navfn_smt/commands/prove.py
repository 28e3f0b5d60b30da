"""``navfn-smt prove``: the proof obligations, each verdict judged against what is known."""

from __future__ import annotations

from pathlib import Path

from ..errors import NavfnInputError
from ..fileio import check_writable_dir
from .common import check_files, check_positive


def _proof_files(names) -> list[Path]:
    """The proof files the command line names (:func:`navfn_smt.smt.runner.proof_files`)."""
    from ..smt.runner import proof_files

    return proof_files(names)


def _page_sources(files) -> dict:
    """What ``--markdown``'s page is rendered from beside the run's verdicts: the committed
    check reports (``docs/reports/check*.json`` under the working directory) and the split
    report beside them, the obligations of the run's proof ``files`` and what is known of them."""
    from ..report import invariants_page as page
    from .common import page_sources

    paths = page.default_check_reports()
    return page_sources(paths, Path(paths[0]).parent if paths else page.REPORTS_DIR, files)


def _semantics(args, both: tuple) -> tuple:
    """The semantics the run asks: ``--semantics``; with ``--target NAME`` or ``--oracle DIR``,
    float32 in that build's arithmetic only (``fp32@NAME``; x86-64's is ``fp32``): the reals
    have no build arithmetic."""
    from ..smt.domains import FP32_SEMANTICS

    if not (args.target or args.oracle):
        return both if args.semantics == "both" else (args.semantics,)
    from .common import planner_of

    arith = planner_of(args).navfn_arithmetic()
    named = [s for s, a in FP32_SEMANTICS.items() if a == arith]
    if not named:
        raise NavfnInputError(f"the build's arithmetic {arith.name} is none the proofs compute in (they do in: "
                              f"{', '.join(a.name for a in FP32_SEMANTICS.values())})")
    if args.semantics == "real":
        raise NavfnInputError("--semantics real and --target/--oracle exclude each other: a build's arithmetic "
                              "is float32's (the reals round nowhere and fuse nothing)")
    return (named[0],)


def cmd_prove(args) -> int:
    """Check the proof obligations; exit 1 only when a verdict contradicts what is known."""
    from ..engine import engine
    from ..report import proof_run
    from ..report import proofs as report
    from ..report.tables import progress_bar
    from ..smt.knowledge import record_decisions
    from ..smt.obligation import load_obligations
    from ..smt.solvers import SOLVERS
    from ..smt.runner import SEMANTICS, default_proof_files, run, slow_queries, split_decided, wanted, write_smt2

    if args.slow_only and args.markdown:
        raise NavfnInputError("--slow-only leaves the default queries out: the invariants page (--markdown) needs "
                              "a whole run (--all)")
    if args.slow_only and args.all:
        raise NavfnInputError("--slow-only and --all exclude each other: --slow-only runs only what --all adds")
    files = _proof_files(args.files) if args.files else default_proof_files()
    semantics = _semantics(args, SEMANTICS)
    check_positive("--timeout", args.timeout)
    eng = engine(args.jobs, args.scheduler)
    check_files(args.report, args.junit, args.markdown)
    witnesses = proof_run.witness_dir(args.witness_dir, (args.report, args.junit, args.markdown))
    for d in (args.smt2, witnesses):
        if d:
            check_writable_dir(d)
    solvers = tuple(args.solver) if args.solver else SOLVERS
    from ..proofs import PREDICATES
    from ..smt.split import known_of_files

    obligations = load_obligations(files)
    known = known_of_files(files, obligations, PREDICATES)
    whole = args.all or args.slow_only
    bounds = whole and not args.no_bound_search
    skip = split_decided(files) if args.skip_split else frozenset()
    left_out = [f"{o.name} ({s})" for o in obligations for s in semantics
                if wanted(o, s, args.all, args.slow_only, bounds) and (o.name, s) in skip]
    n = sum(wanted(o, s, args.all, args.slow_only, bounds) for o in obligations for s in semantics) - len(left_out)
    with progress_bar(n, "prove") as advance:
        outcomes = run(files, semantics, args.timeout, eng, solvers, progress=lambda o: advance(1),
                       bounds=bounds, everything=args.all, known=known, slow_only=args.slow_only, skip=skip)
    witness_files = proof_run.write_witnesses(outcomes, witnesses)
    if args.smt2:
        write_smt2(files, semantics, Path(args.smt2))
    report.table(outcomes, known)
    meta = {**proof_run.meta(args.timeout, solvers, semantics, files),
            "queries": "all" if args.all else "slow only" if args.slow_only else "default",
            "left_to_splits": left_out}
    if args.report:
        report.write_json(args.report, outcomes, witness_files, meta, known)
    if args.junit:
        report.write_junit(args.junit, outcomes)
    if args.markdown:
        report.write_markdown(args.markdown, outcomes, meta, _page_sources(meta["files"]))
    proof_run.witness_note(outcomes, witnesses)
    if left_out:
        print(f"{len(left_out)} whole queries left to their splits (`navfn-smt split`, --skip-split): "
              f"{', '.join(left_out)}")
    left = [] if whole else slow_queries(files, semantics)
    if left:
        print(f"{len(left)} slow queries left to `navfn-smt prove --all` (splits: `navfn-smt split`): {', '.join(left)}")
    proof_run.closing_line(outcomes)
    if args.record:
        for line in record_decisions(outcomes, obligations, meta["when"]):
            print(line)
    return 1 if any(o.fails for o in outcomes) else 0


def register(sub) -> None:
    """The command's parser, its options and its handler."""
    from ..engine import add_arguments as add_engine_arguments
    from ..smt.runner import SEMANTICS
    from ..smt.solvers import SOLVERS

    pr = sub.add_parser("prove", help="check the proof obligations shipped in the package (or the given files)")
    pr.add_argument("files", nargs="*", metavar="FILE|DIR",
                    help="proof files (Python files declaring obligations) or folders of them "
                    "(default: every proof file of the package's navfn_smt/proofs)")
    pr.add_argument("--semantics", choices=(*SEMANTICS, "both"), default="both",
                    help="real (no rounding), fp32 (bit-precise IEEE-754) or both")
    pr.add_argument("--target", metavar="NAME",
                    help="float32 in the arithmetic of a build for this machine: x86-64 (fp32, the default), "
                         "x86-64-v3 or aarch64 (fp32@NAME: multiply-adds fused as that build fuses them, its "
                         "float-to-int conversion; docs/toolchains.md)")
    pr.add_argument("--oracle", metavar="DIR", help="float32 in the arithmetic found in the build in DIR "
                    "(navfn-smt oracle build)")
    pr.add_argument("--timeout", type=float, default=30.0, metavar="S", help="seconds per solver query")
    add_engine_arguments(pr, "obligations (each in each semantics)")
    pr.add_argument("--solver", action="append", choices=SOLVERS,
                    help="solvers of the portfolio (repeatable; default: all)")
    pr.add_argument("--report", metavar="FILE.json", help="machine-readable report")
    pr.add_argument("--junit", metavar="FILE.xml", help="JUnit XML, one test case per obligation and semantics")
    pr.add_argument("--markdown", metavar="FILE.md", help="the invariants page (docs/invariants.md)")
    pr.add_argument("--smt2", metavar="DIR", help="also write every query as SMT-LIB2")
    pr.add_argument("--all", action="store_true",
                    help="also the slow queries (whole queries a split decides, long proofs), which the default "
                         "run leaves out to stay within a minute")
    pr.add_argument("--slow-only", action="store_true",
                    help="only what --all adds to the default run: the slow queries and the bound searches (for "
                         "a CI whose test run has checked the default queries already)")
    pr.add_argument("--skip-split", action="store_true",
                    help="leave out the whole fp32 queries of the obligations a split decides part by part (their "
                         "verdict is the split's: for a CI that runs `navfn-smt split` on them beside this run)")
    pr.add_argument("--record", action="store_true",
                    help="record every decision made where nothing was known (known.json beside the proof file, "
                         "keyed by a hash of the proof file, kernels and domains), so later runs judge against it")
    pr.add_argument("--no-bound-search", action="store_true",
                    help="with --all or --slow-only, do not search bounds for properties refuted in fp32 (the default run "
                         "gives verdicts only: the bound search re-verifies its cached bound with two queries)")
    pr.add_argument("--witness-dir", metavar="DIR",
                    help="where counterexamples are written (default: STEM-witnesses next to the first of "
                    "--report, --junit, --markdown given; none written without any of them)")
    pr.set_defaults(func=cmd_prove)
