"""The registry of planners under test by their fix: NavFn as shipped and each candidate fix,
one :class:`~.planner.Fix` value each.  A new candidate is one module stating its hooks (and its
patches under ``patches/``), named here; the command line's ``--variant`` offers every name,
and nothing else in the package names one."""

from __future__ import annotations

from ..errors import NavfnInputError
from . import candidates, cycles_only, fix
from .planner import AS_SHIPPED, Fix

__all__ = ["AS_SHIPPED", "DEFAULT", "FIXES", "HELP", "NAMES", "PATCHED", "named"]

FIXES: dict[str, Fix] = {f.name: f for f in (AS_SHIPPED, fix.FIX, cycles_only.FIX, fix.PROPAGATION, fix.DESCENT,
                                              candidates.INCLUSIVE, candidates.RESUME)}
NAMES = tuple(FIXES)
PATCHED = tuple(f for f in FIXES.values() if f.patches is not None)  # those with a C++ patch
DEFAULT = AS_SHIPPED
HELP = "; ".join(f"{f.name}: {f.summary}" for f in FIXES.values()) + f"; default: {DEFAULT.name}"


def named(name) -> Fix:
    """The fix a command line or a report names (a :class:`Fix` is returned as it is); a clear
    error naming the choices otherwise."""
    if isinstance(name, Fix):
        return name
    if name not in FIXES:
        raise NavfnInputError(f"unknown variant {name!r} (choose from {', '.join(NAMES)})")
    return FIXES[name]
