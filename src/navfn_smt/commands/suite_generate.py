"""``navfn-smt suite generate``: the command that generates map suites.

    navfn-smt suite generate OUT --category C [--count K] [--seed S] [--size W H]
                                 [--paths P|all] [--overwrite]

Wire it into the ``suite`` command with ``register(suite_subparsers)``; the handler raises
:class:`~navfn_smt.errors.NavfnInputError` on bad input, which ``main`` prints as one line.
(``suite record``: :mod:`navfn_smt.commands.suite_record`; the ``suite`` command: :mod:`navfn_smt.commands.suite`.)
"""

from __future__ import annotations

import argparse

from ..maps.generators import CATEGORIES, CATEGORY_INFO, DEFAULT_PATHS


def cmd_suite_generate(args) -> int:
    """Generate the maps of one category and print one summary line."""
    from ..maps.generators import generate_suite

    maps = generate_suite(args.out, args.category, count=args.count, seed=args.seed,
                          size=tuple(args.size) if args.size else None, paths=args.paths,
                          overwrite=args.overwrite)
    cases = sum(len(m.cases) for m in maps)
    sizes = sorted({f"{m.width}x{m.height}" for m in maps})
    shown = ", ".join(sizes[:4]) + (", ..." if len(sizes) > 4 else "")
    print(f"{len(maps)} {args.category} map{'s' if len(maps) != 1 else ''} written under {args.out}/{args.category} "
          f"({shown}), {cases} cases")
    return 0


def register(suite_subparsers) -> argparse.ArgumentParser:
    """Add the ``generate`` subcommand to the ``suite`` command's ``suite_subparsers``."""
    ge = suite_subparsers.add_parser(
        "generate", help="generate maps of one category with their cases (test.txt + map.bin)",
        description="Generate COUNT maps of one category into OUT/<category>/<map>/ in the suite format. "
        "Categories: " + "; ".join(f"{c}: {CATEGORY_INFO[c].summary}" for c in CATEGORIES) + ".",
    )
    ge.add_argument("out", metavar="OUT", help="suite directory (created; other categories in it are kept)")
    ge.add_argument("--category", required=True, metavar="C",
                    help=f"map category: {', '.join(CATEGORIES)}")
    ge.add_argument("--count", type=int, default=1, help="number of maps")
    ge.add_argument("--seed", type=int, default=0, help="random seed; the same seed gives the same maps")
    ge.add_argument("--size", nargs=2, type=int, metavar=("W", "H"),
                    help="map size, border included (default: drawn per map from the category's usual range)")
    ge.add_argument("--paths", default=str(DEFAULT_PATHS), metavar="P|all",
                    help="cases per map: all ordered pairs of passable cells when at most P, else P sampled; "
                    "'all' for every pair")
    ge.add_argument("--overwrite", action="store_true", help="replace map directories that already exist")
    ge.set_defaults(func=cmd_suite_generate)
    return ge
