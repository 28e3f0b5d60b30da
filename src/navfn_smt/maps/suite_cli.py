"""``navfn-smt suite``: generate map suites and record golden files from the spec.

    navfn-smt suite generate OUT --category C [--count K] [--seed S] [--size W H]
                                 [--paths P|all] [--overwrite]
    navfn-smt suite record SUITE [--mode astar|dijkstra|both] [--backend jit|reference]
                                 [--full-first K] [--overwrite] [--quiet]

Wire it into the command line with ``register(subparsers)``; the handlers raise
:class:`~navfn_smt.errors.NavfnInputError` on bad input, which ``main`` prints as one line.
"""

from __future__ import annotations

import argparse

from ..errors import NavfnInputError
from .generators import CATEGORIES, CATEGORY_INFO, DEFAULT_PATHS


def cmd_suite_generate(args) -> int:
    from .generators import generate_suite

    maps = generate_suite(args.out, args.category, count=args.count, seed=args.seed,
                          size=tuple(args.size) if args.size else None, paths=args.paths,
                          overwrite=args.overwrite)
    cases = sum(len(m.cases) for m in maps)
    sizes = sorted({f"{m.width}x{m.height}" for m in maps})
    shown = ", ".join(sizes[:4]) + (", ..." if len(sizes) > 4 else "")
    print(f"{len(maps)} {args.category} map{'s' if len(maps) != 1 else ''} written under {args.out}/{args.category} "
          f"({shown}), {cases} cases")
    return 0


def cmd_suite_record(args) -> int:
    from ..difftest.record import record_suite
    from ..maps.suite import discover, load_map
    from ..report.tables import progress_bar

    modes = ("astar", "dijkstra") if args.mode == "both" else (args.mode,)
    if args.full_first < 0:
        raise NavfnInputError(f"--full-first {args.full_first}: expected a non-negative number of cases")
    total = sum(len(load_map(d).cases) for d in discover(args.suite)) * len(modes)
    with progress_bar(total, f"record {args.suite} ({args.backend})", enabled=not args.quiet) as advance:
        recs = record_suite(args.suite, modes, args.backend, args.full_first, overwrite=args.overwrite,
                            progress=lambda r: advance(r.cases))
    maps = len({r.map for r in recs})
    cases = sum(r.cases for r in recs)
    secs = sum(r.seconds for r in recs)
    print(f"{len(recs)} golden files recorded for {maps} map{'s' if maps != 1 else ''} "
          f"({', '.join(modes)}; backend {args.backend}), {cases} case runs in {secs:.1f} s")
    return 0


def register(subparsers) -> argparse.ArgumentParser:
    """Add the ``suite`` command (subcommands ``generate`` and ``record``) to ``subparsers``."""
    su = subparsers.add_parser("suite", help="generate map suites and record golden files from the spec")
    sub = su.add_subparsers(dest="suite_command", required=True, metavar="SUBCOMMAND")

    ge = sub.add_parser(
        "generate", help="generate maps of one category with their cases (test.txt + map.bin)",
        description="Generate COUNT maps of one category into OUT/<category>/<map>/ in the suite format. "
        "Categories: " + "; ".join(f"{c}: {CATEGORY_INFO[c].summary}" for c in CATEGORIES) + ".",
    )
    ge.add_argument("out", metavar="OUT", help="suite directory (created; other categories in it are kept)")
    ge.add_argument("--category", required=True, metavar="C",
                    help=f"map category: {', '.join(CATEGORIES)}")
    ge.add_argument("--count", type=int, default=1, help="number of maps (default 1)")
    ge.add_argument("--seed", type=int, default=0, help="random seed (default 0); the same seed gives the same maps")
    ge.add_argument("--size", nargs=2, type=int, metavar=("W", "H"),
                    help="map size, border included (default: drawn per map from the category's usual range)")
    ge.add_argument("--paths", default=str(DEFAULT_PATHS), metavar="P|all",
                    help=f"cases per map: all ordered pairs of passable cells when at most P, else P sampled "
                    f"(default {DEFAULT_PATHS}); 'all' for every pair")
    ge.add_argument("--overwrite", action="store_true", help="replace map directories that already exist")
    ge.set_defaults(func=cmd_suite_generate)

    re_ = sub.add_parser("record", help="record golden files for every map of a suite from the spec",
                         description="Plan every case of every map under SUITE and write golden_<mode>.npz in "
                         "the shared suite's golden format. These goldens come from the spec, not the C++ "
                         "original: existing golden files are kept unless --overwrite.")
    re_.add_argument("suite", metavar="SUITE", help="suite directory")
    re_.add_argument("--mode", choices=("astar", "dijkstra", "both"), default="both")
    re_.add_argument("--backend", choices=("jit", "reference"), default="jit")
    re_.add_argument("--full-first", type=int, default=50, metavar="K",
                     help="store full potentials and traces of the first K cases of each map (default 50; "
                     "the shared suite uses 5 on its ROS maps)")
    re_.add_argument("--overwrite", action="store_true", help="replace golden files that already exist")
    re_.add_argument("--quiet", action="store_true", help="no progress bar")
    re_.set_defaults(func=cmd_suite_record)
    return su
