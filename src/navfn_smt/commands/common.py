"""What every command shares: the example suite, the checks of numbers and output paths,
a cell from the command line, and the arguments as JSON."""

from __future__ import annotations

import math
from pathlib import Path

from ..errors import NavfnInputError
from ..fileio import check_writable

EXAMPLE_SUITE = Path(__file__).resolve().parent.parent / "examples" / "suite"
BACKEND_HELP = "planner implementation: the numba JIT or the reference spec"
MODE_HELP = "planner modes: A*, Dijkstra or both"


def suite_or_example(arg) -> Path:
    """The suite a command names, or the example suite shipped with the package."""
    return Path(arg) if arg else EXAMPLE_SUITE


def check_max_cases(n) -> None:
    """Reject a ``--max-cases`` below 1."""
    if n is not None and n < 1:
        raise NavfnInputError("--max-cases must be at least 1")


def check_positive(option: str, value, allow_zero: bool = False) -> None:
    """Reject a number option that is not a positive finite number (NaN included)."""
    ok = value is None or (math.isfinite(value) and (value >= 0 if allow_zero else value > 0))
    if not ok:
        raise NavfnInputError(f"{option} {value:g}: must be a {'non-negative' if allow_zero else 'positive'} number")


def check_files(*paths) -> None:
    """Fail early, before the run, on any output file that could not be written."""
    for p in paths:
        if p:
            check_writable(p)


def cell(what: str, v) -> tuple[int, int]:
    """A map cell from two command-line numbers (which must be integers)."""
    if len(v) != 2:
        raise NavfnInputError(f"--{what} needs two cell coordinates X Y (a yaw is for --world poses)")
    if any(not float(c).is_integer() for c in v):
        raise NavfnInputError(f"--{what} {v[0]:g} {v[1]:g}: a map cell needs integers (use --world for world coordinates)")
    return int(v[0]), int(v[1])


def vars_of(args) -> dict:
    """The arguments of a command as plain JSON values (no handler)."""
    return {k: v for k, v in vars(args).items() if k != "func"}
