"""The registry of planners under test by their fix: NavFn as shipped and each candidate fix,
one :class:`~.planner.Fix` value each.  A new candidate is one module stating its hooks (and its
patches under ``patches/``), named here; the command line's ``--variant`` offers every name,
and nothing else in the package names one."""

from __future__ import annotations

from ..errors import NavfnInputError
from . import candidates, cycles_only, fix
from .planner import AS_SHIPPED, Fix

__all__ = ["AS_SHIPPED", "DEFAULT", "FIXES", "GUARANTEE", "HELP", "NAMES", "PATCHED", "named"]

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


# What the fix of docs/fix.md guarantees, with every hypothesis: the one statement of it, which
# check --variant fixed prints and README.md and docs/fix.md quote word for word (a test holds them equal)
GUARANTEE = (
    "With both changes (the further propagation call and the descent), a start 4-connected to the goal "
    "through passable cells gets a path from the start to the goal, each point on a passable cell the wave "
    "reached, under these run-time conditions: no push dropped (argued to hold when the goal's component has at "
    "most 10,000 cells); potentials below 2^30 (argued to hold on every map of fewer than 2^22 passable "
    "cells); push keys below 2^31 (which the bound on potentials gives on maps under 2^22 cells a side); the "
    "further call's nx*ny cycles suffice; the descent fits calcPath's budget; costs as setCostmap makes them "
    "(true of every one of its 256 inputs); and a build that computes in IEEE float32 as the x86-64, x86-64-v3 "
    "and aarch64 builds checked here do. Strength: conditional, with 2 trusted steps (argued, not "
    "machine-checked: docs/invariants.md); the rest machine-checked steps and inductions over arrays of any "
    "size; tested on the suites; not bounded-checked where it acts: the bounded checks of the fixed planner "
    "reach 6 interior cells, and NavFn's smallest failing map found has 9.")

