"""``navfn-smt suite``: generate map suites (:mod:`.suite_generate`) and record golden files
from the spec (:mod:`.suite_record`)."""

from __future__ import annotations

from . import suite_generate, suite_record


def register(sub) -> None:
    """The ``suite`` command and its two subcommands."""
    su = sub.add_parser("suite", help="generate map suites and record golden files from the spec")
    suite_sub = su.add_subparsers(dest="suite_command", required=True, metavar="SUBCOMMAND")
    suite_generate.register(suite_sub)
    suite_record.register(suite_sub)
