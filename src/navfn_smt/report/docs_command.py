"""``navfn-smt docs``: the command (arguments and handler); wired by ``register(subparsers)``."""

from __future__ import annotations

from ..errors import NavfnInputError


def cmd_docs(args) -> int:
    raise NavfnInputError("docs is not built yet")


def register(sub) -> None:
    d = sub.add_parser("docs", help="generate docs/invariants.md from the obligations and the latest reports "
                       "(--check: fail when the committed page differs)")
    d.set_defaults(func=cmd_docs)
