"""``navfn-smt docs``: the command (arguments and handler); wired by ``register(subparsers)``.

Prints (or with ``--out`` writes) the invariants page (:mod:`navfn_smt.report.invariants_page`) from the obligations,
the paper's predicates and the committed reports, or with ``--check`` compares it with the
committed page and fails (exit 1, one line naming the first differing line) when they
differ.  No solver runs: the command only reads.
"""

from __future__ import annotations

from pathlib import Path

from ..errors import NavfnInputError
from ..fileio import atomic_write_text, check_writable
from ..report import invariants_page as page
from .common import page_sources


def generate(prove_report, check_reports) -> str:
    """The page from a prove report and check reports: read them (one-line errors on a missing
    or malformed one), with the split report beside the prove report, the shipped obligations
    and what is known of them (:func:`~navfn_smt.commands.common.page_sources`), and render it."""
    prove_doc = page.with_arithmetics(page.read_prove_report(prove_report), prove_report)
    sources = page_sources(check_reports, Path(prove_report).parent)
    return page.render(prove_doc, page.report_label(prove_report), **sources)


def _excerpt(line: str, col: int, width: int = 60) -> str:
    """``line`` around column ``col`` (0-based), at most ``width`` characters, quoted."""
    lo = max(0, col - 20)
    text = line[lo:lo + width]
    return repr(("..." if lo else "") + text + ("..." if lo + width < len(line) else ""))


def cmd_docs(args) -> int:
    """Print, write or check the invariants page; exit 1 only when ``--check`` finds it differs."""
    check_reports = (args.check_report if args.check_report is not None
                     else page.default_check_reports(Path(args.prove_report).parent))
    if args.out is None and not args.check:  # nothing named: the page goes to stdout, no file is written
        print(generate(args.prove_report, check_reports), end="")
        return 0
    out = Path(args.out if args.out is not None else page.DEFAULT_OUT)
    if args.check:
        if not out.is_file():
            raise NavfnInputError(f"{out}: no such page to check" + (" (it is a directory)" if out.is_dir() else ""))
    else:
        check_writable(out)
    text = generate(args.prove_report, check_reports)
    if not args.check:
        atomic_write_text(out, text)
        print(f"wrote {out}")
        return 0
    try:
        committed = out.read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError) as e:
        raise NavfnInputError(f"{out}: cannot read ({getattr(e, 'strerror', None) or e})") from None
    diff = page.first_difference(committed, text)
    if diff is None:
        print(f"{out} is up to date")
        return 0
    line, was, want = diff
    col = next((i for i, (a, b) in enumerate(zip(was, want)) if a != b), min(len(was), len(want)))
    print(f"{out}:{line}: differs from the generated page at column {col + 1}: has {_excerpt(was, col)}, "
          f"generated {_excerpt(want, col)} (regenerate with `navfn-smt docs --out {out}`)")
    return 1


def register(sub) -> None:
    d = sub.add_parser(
        "docs", help="generate docs/invariants.md from the obligations and the latest reports "
                     "(--check: fail when the committed page differs)",
        description="Generate the invariants page from the proof obligations, the paper's predicates and the "
                    "committed reports of `prove` and `check` (no solver runs). Paths are relative to the "
                    "working directory: run it from the repository's root.")
    d.add_argument("--out", metavar="FILE",
                   help=f"the page to write (default: print it on stdout, write nothing), or with --check the page "
                        f"to compare (default with --check: {page.DEFAULT_OUT})")
    d.add_argument("--check", action="store_true",
                   help="write nothing; exit 1 with one line naming the first differing line when FILE differs "
                        "from the generated page")
    d.add_argument("--prove-report", default=str(page.DEFAULT_PROVE_REPORT), metavar="FILE",
                   help="the `navfn-smt prove --report` JSON the obligations' verdicts come from "
                        "(default: %(default)s)")
    d.add_argument("--check-report", nargs="+", metavar="FILE",
                   help="`navfn-smt check --json` reports the whole-planner properties come from; a later one's "
                        "row for a property and size replaces an earlier one's (default: every check*.json in the "
                        "prove report's directory, by name)")
    d.set_defaults(func=cmd_docs)
