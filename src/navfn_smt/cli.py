"""``navfn-smt``: the entry point.  It builds the command line from the command layer and runs
one command.

Each command is a module of :mod:`navfn_smt.commands` (its parser and its handler, listed in
:data:`navfn_smt.commands.COMMANDS`): the handler checks its arguments and output paths,
calls the part of the toolkit that does the work, and hands the results to a reporter in
:mod:`navfn_smt.report`.  Every user error (bad map, missing file, cell off the map,
unwritable output, ...) is printed here as one line ``navfn-smt: error: ...`` with exit
status 2, before any long work when it is about an output path; no traceback reaches the
user for bad input.
"""

from __future__ import annotations

import argparse
import importlib
import sys

from .commands import COMMANDS
from .commands.common import EXAMPLE_SUITE  # noqa: F401  (the example suite, as tests and users name it)
from .errors import NavfnInputError


def shown_default(value) -> str:
    """An option's default as its help shows it: ``30`` for 30.0, ``1e+07``, ``0 0`` for a pair."""
    if isinstance(value, (list, tuple)):
        return " ".join(shown_default(v) for v in value)
    if isinstance(value, float):
        return f"{value:g}"
    return str(value)


class _HelpFormatter(argparse.HelpFormatter):
    """Shows an option's default at the end of its help, unless the default is nothing (None,
    False) or the help already says what the default is."""

    def _get_help_string(self, action) -> str:
        text = action.help or ""
        if action.default in (None, False, argparse.SUPPRESS) or not action.option_strings:
            return text
        if "default" in text.lower():
            return text
        return f"{text} (default: {shown_default(action.default).replace('%', '%%')})"


class Parser(argparse.ArgumentParser):
    """An argument parser whose subcommands (and theirs) all show option defaults in their help."""

    def __init__(self, *args, formatter_class=_HelpFormatter, **kwargs):
        super().__init__(*args, formatter_class=formatter_class, **kwargs)


def _version() -> str:
    """The installed package's version."""
    from importlib.metadata import PackageNotFoundError, version

    try:
        return version("navfn-smt")
    except PackageNotFoundError:
        return "unknown (not installed)"


def _named(argv) -> tuple:
    """The command modules ``argv`` needs: the one it names (its first word that is not an
    option), so that one command's run imports what that command uses and no other's;
    every one when it names none (``--help``, ``--version``) or one that does not exist."""
    if argv is None:
        return COMMANDS
    word = next((a for a in argv if not a.startswith("-")), None)
    module = word.replace("-", "_") if word else None
    return (module,) if module in COMMANDS else COMMANDS


def build_parser(argv=None) -> argparse.ArgumentParser:
    """The command line: the parser of each command module ``argv`` needs (:func:`_named`; every
    one without ``argv``), in the order of :data:`COMMANDS`."""
    p = Parser(
        prog="navfn-smt",
        description="Executable specification of Nav2's NavFn planner, differential testing "
        "against the C++ original, and SMT proofs of its invariants.",
    )
    p.add_argument("--version", action="version", version=f"%(prog)s {_version()}")
    sub = p.add_subparsers(dest="command", required=True, metavar="COMMAND")
    for name in _named(argv):
        importlib.import_module(f".commands.{name}", __package__).register(sub)
    return p


def main(argv=None) -> int:
    """Run one command; its exit status (2 for bad input, 130 when interrupted, even while the
    command line is still being built)."""
    try:
        argv = sys.argv[1:] if argv is None else list(argv)
        parser = build_parser(argv)
        args = parser.parse_args(argv)
        if getattr(args, "jobs", 1) is not None and getattr(args, "jobs", 1) < 1:
            parser.error("--jobs must be at least 1")
        return args.func(args)
    except NavfnInputError as e:
        print(f"navfn-smt: error: {e}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        print("navfn-smt: interrupted", file=sys.stderr)
        return 130
    except BrokenPipeError:
        return 1


if __name__ == "__main__":
    sys.exit(main())
