"""``navfn-smt split``: decide the obligations no solver decides whole, part by part.

Every split declared in the proof files (:func:`navfn_smt.smt.split.split`) is run on the
engine: its parts, refined where undecided, then its cover; :mod:`navfn_smt.report.split`
prints the table and writes the report.  Exit 1 only when a verdict contradicts what is
known (:mod:`navfn_smt.smt.knowledge`): a split left undecided (a part out of time) is
reported, a decision where nothing was known is news (``--record`` keeps it).
"""

from __future__ import annotations

import time

from ..errors import NavfnInputError
from ..report.split import interval_text, table, write_json
from ..report.tables import duration


def register(sub) -> None:
    from ..engine import add_arguments
    from .common import TARGET_HELP

    sp = sub.add_parser("split", help="decide the obligations no solver decides whole: parts that cover the input "
                                      "space, each decided, and the cover proved")
    sp.add_argument("names", nargs="*", metavar="OBLIGATION",
                    help="the obligations whose splits to run (default: every split declared)")
    sp.add_argument("--files", nargs="+", metavar="FILE|DIR",
                    help="proof files declaring the splits (default: the package's navfn_smt/proofs)")
    add_arguments(sp, "parts")
    sp.add_argument("--target", metavar="NAME", help=TARGET_HELP + "; the parts are decided in its float32 "
                    "semantics (fp32@NAME), what is known of them judged there")
    sp.add_argument("--part-timeout", type=float, default=None, metavar="S",
                    help="seconds per part and method (default: what each split declares)")
    sp.add_argument("--max-depth", type=int, default=None, metavar="N",
                    help="how often an undecided part may be cut in two (default: what each split declares)")
    sp.add_argument("--report", metavar="FILE.json", help="machine-readable report: every part, the cover, times")
    sp.add_argument("--quiet", action="store_true", help="no line per decided part")
    sp.add_argument("--record", action="store_true",
                    help="record every verdict reached where nothing was known (known.json beside the proof file)")
    sp.set_defaults(func=cmd_split)


def cmd_split(args) -> int:
    import math

    from ..engine import engine
    from ..fileio import check_writable
    from ..smt.runner import default_proof_files, proof_files
    from ..smt.split import load_splits, run_split

    files = proof_files(args.files) if args.files else default_proof_files()
    if args.part_timeout is not None and not (math.isfinite(args.part_timeout) and args.part_timeout > 0):
        raise NavfnInputError(f"--part-timeout {args.part_timeout:g}: must be a positive number of seconds")
    if args.max_depth is not None and not 0 <= args.max_depth <= 64:
        raise NavfnInputError(f"--max-depth {args.max_depth}: must be between 0 and 64")
    if args.report:
        check_writable(args.report)
    from .common import planner_of

    semantics = planner_of(args).fp32_semantics()  # fp32: x86-64's arithmetic, the default
    eng = engine(args.jobs, args.scheduler)
    splits = load_splits(files)
    unknown = set(args.names) - {s.obligation for s in splits}
    if unknown:
        raise NavfnInputError(f"no split declared for {', '.join(sorted(unknown))} "
                              f"(declared: {', '.join(s.obligation for s in splits) or 'none'})")
    chosen = [s for s in splits if not args.names or s.obligation in args.names]
    if not chosen:
        raise NavfnInputError("no split declared in the proof files")
    t0 = time.perf_counter()
    outcomes = []
    for s in chosen:
        used = eng.for_work(len(s.boxes), 2)
        print(f"{s.obligation}: {len(s.boxes)} parts to start with, methods {', '.join(s.methods)}, in "
              f"{semantics}, on {used.describe()}", flush=True)
        outcomes.append(run_split(s, used, args.part_timeout, args.max_depth,
                                  progress=None if args.quiet else _part_line(time.perf_counter()),
                                  semantics=semantics))
    table(outcomes)
    if args.report:
        write_json(args.report, outcomes, time.perf_counter() - t0, eng.describe())
    from ..smt.knowledge import JUDGEMENTS, NEWLY_DECIDED

    n = {j: [o.obligation for o in outcomes if o.judgement == j] for j in JUDGEMENTS}
    print(f"{len(outcomes)} splits: " + ", ".join(f"{len(n[j])} {j}" + (f" ({', '.join(n[j])})" if n[j] and j != "confirmed" else "")
                                                   for j in JUDGEMENTS) + f"; {duration(time.perf_counter() - t0)}")
    if args.record:
        from ..smt.knowledge import record
        from ..smt.split import obligation_named

        for line in record((obligation_named(s.source, s.obligation), semantics, o.status,
                            {"by": "split", "seconds": o.seconds})
                           for s, o in zip(chosen, outcomes) if o.judgement == NEWLY_DECIDED):
            print(line)
    return 1 if any(o.fails for o in outcomes) else 0


def _part_line(t0: float):
    """``progress(done, total, part)``: a line per decided part with done/total, the time so far
    and an estimate of the time left for the parts known (refinement may add more)."""

    def line(done: int, total: int, part) -> None:
        box = ", ".join(interval_text(iv.as_json()) for iv in part.box)
        elapsed = time.perf_counter() - t0
        left = f", about {duration(elapsed * (total - done) / done)} left" if done < total else ""
        print(f"  part {done}/{total} {part.status} in {part.seconds:.1f} s by {part.solver or '-'} "
              f"({duration(elapsed)}{left}): {box}", flush=True)

    return line
