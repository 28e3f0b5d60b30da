"""``navfn-smt diagnose``: the command (arguments and handler).

Wired into the command line by ``register(subparsers)``.
"""

from __future__ import annotations

from ..errors import NavfnInputError


def cmd_diagnose(args) -> int:
    raise NavfnInputError("diagnose is not built yet")


def register(sub) -> None:
    d = sub.add_parser("diagnose", help="explain why a Nav2 NavFn plan fails and what fixes it")
    d.add_argument("map", help="a map_server YAML map")
    d.set_defaults(func=cmd_diagnose)
