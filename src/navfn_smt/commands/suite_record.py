"""``navfn-smt suite record``: the command that records golden files from the spec, or with
``--oracle DIR`` from the user's own C++ build of NavFn (``navfn-smt oracle build``).

    navfn-smt suite record SUITE [--mode astar|dijkstra|both] [--backend jit|reference]
                                 [--oracle DIR | --target NAME] [--full-first K] [--overwrite] [--quiet]

Wire it into the ``suite`` command with ``register(suite_subparsers)``; the handler raises
:class:`~navfn_smt.errors.NavfnInputError` on bad input, which ``main`` prints as one line.
"""

from __future__ import annotations

import argparse
import contextlib

from ..backends import BACKENDS
from ..errors import NavfnInputError
from ..maps.suite import MODE_CHOICES, modes_of
from .common import TARGET_HELP, planner_of


def cmd_suite_record(args) -> int:
    """Record every map of the suite in the chosen modes and print one summary line."""
    from ..maps.suite import discover, load_map
    from ..report.tables import progress_bar
    from ..difftest.record import record_suite
    from ..oracle.client import Oracle

    modes = modes_of(args.mode)
    if args.full_first < 0:
        raise NavfnInputError(f"--full-first {args.full_first}: expected a non-negative number of cases")
    planner = planner_of(args)  # with --oracle, the C++ records in its own arithmetic
    total = sum(len(load_map(d).cases) for d in discover(args.suite)) * len(modes)
    source = (f"the C++ of {args.oracle}" if args.oracle
              else f"backend {args.backend}{f', {planner.arithmetic.name} arithmetic' if args.target else ''}")
    with contextlib.ExitStack() as stack:
        oracle = stack.enter_context(Oracle(args.oracle)) if args.oracle else None
        advance = stack.enter_context(progress_bar(total, f"record {args.suite} ({source})", enabled=not args.quiet))
        recs = record_suite(args.suite, modes, args.backend, args.full_first, overwrite=args.overwrite,
                            progress=lambda r: advance(r.cases), oracle=oracle, planner=planner)
    maps = len({r.map for r in recs})
    cases = sum(r.cases for r in recs)
    secs = sum(r.seconds for r in recs)
    print(f"{len(recs)} golden files recorded for {maps} map{'s' if maps != 1 else ''} "
          f"({', '.join(modes)}; {source}), {cases} case runs in {secs:.1f} s")
    return 0


def register(suite_subparsers) -> argparse.ArgumentParser:
    """Add the ``record`` subcommand to the ``suite`` command's ``suite_subparsers``."""
    re_ = suite_subparsers.add_parser(
        "record", help="record golden files for every map of a suite from the spec",
        description="Plan every case of every map under SUITE and write golden_<mode>.npz in "
        "the shared suite's golden format. These goldens come from the spec, not the C++ "
        "original: existing golden files are kept unless --overwrite.")
    re_.add_argument("suite", metavar="SUITE", help="suite directory")
    re_.add_argument("--mode", choices=MODE_CHOICES, default="both", help="planner modes to record")
    re_.add_argument("--backend", choices=BACKENDS, default="jit", help="planner implementation that plans")
    re_.add_argument("--oracle", metavar="DIR", help="record from the C++ NavFn built in DIR (navfn-smt oracle "
                     "build) instead of the spec")
    re_.add_argument("--target", metavar="NAME", help=TARGET_HELP + "; it records from the spec in it")
    re_.add_argument("--full-first", type=int, default=50, metavar="K",
                     help="store full potentials and traces of the first K cases of each map "
                     "(the shared suite uses 5 on its ROS maps)")
    re_.add_argument("--overwrite", action="store_true", help="replace golden files that already exist")
    re_.add_argument("--quiet", action="store_true", help="no progress bar")
    re_.set_defaults(func=cmd_suite_record)
    return re_
