"""``navfn-smt search KIND``: one hunt per mode, at one size or growing up to a maximum.

The kind ``overflow`` is hunted by :mod:`navfn_smt.search.overflow` (imported only when
asked for); every other kind by :mod:`.hunt`.
"""

from __future__ import annotations

from typing import Optional

from ..errors import NavfnInputError
from .hunt import DEFAULT_COSTS, check_size, hunt, hunt_growing
from .kinds import KINDS, SEARCH_KINDS

DEFAULT_SIZE = {"cost": (5, 7)}
DEFAULT_HUNT_SIZE = (8, 8)  # the other kinds: hunted here, then shrunk


def modes_list(mode: str) -> tuple[str, ...]:
    return ("astar", "dijkstra") if mode == "both" else (mode,)


def _overflow(mode, size, max_size, timeout, seed, progress) -> list:
    try:
        from .overflow import search_overflow
    except ImportError as e:
        raise NavfnInputError(f"the overflow search is not available in this installation "
                              f"(navfn_smt.search.overflow: {e})") from None
    return list(search_overflow(mode, size=size, max_size=max_size, timeout=timeout, seed=seed, progress=progress))


def run_search(kind: str, mode: str = "both", size=None, max_size=None, timeout: float = 60.0, seed: int = 0,
               costs_range=DEFAULT_COSTS, progress=None) -> tuple[list, list]:
    """The findings of one search (per mode, at most one each), and per mode what sizes were
    tried with ``max_size`` (``[]`` otherwise)."""
    if kind not in SEARCH_KINDS:
        raise NavfnInputError(f"unknown search kind {kind!r} (choose from {', '.join(SEARCH_KINDS)})")
    if not (timeout > 0 and timeout < float("inf")):
        raise NavfnInputError("--timeout must be positive")
    if size is not None and max_size is not None:
        raise NavfnInputError("--size and --max-size exclude each other")
    if size is not None:
        check_size(*size)
    if max_size is not None:
        check_size(*max_size, what="--max-size")
    if kind == "overflow":
        return _overflow(mode, size, max_size, timeout, seed, progress), []
    modes = modes_list(mode)
    share = timeout / len(modes)
    findings, tried = [], []
    for m in modes:
        if max_size is not None:
            f, t = hunt_growing(kind, m, max_size, share, seed, costs_range, progress)
            tried.append({"mode": m, "sizes": t})
        else:
            f = hunt(kind, m, tuple(size or DEFAULT_SIZE.get(kind, DEFAULT_HUNT_SIZE)), share, seed, costs_range,
                     progress)
        if f is not None:
            findings.append(f)
    return findings, tried


def default_size(kind: str) -> Optional[tuple[int, int]]:
    return DEFAULT_SIZE.get(kind, DEFAULT_HUNT_SIZE) if kind in KINDS else None
