"""``navfn-smt search KIND``: one hunt per mode, at one size or for the smallest map up to a maximum.

The kind ``overflow`` is hunted by :mod:`navfn_smt.search.overflow` (imported only when
asked for); every other kind by :mod:`.hunt`.  Each mode's hunt is one task of the
:mod:`~navfn_smt.engine` with its share of the time budget: the modes run side by side when
there are workers, one after the other in this process otherwise; findings come in mode order.
"""

from __future__ import annotations

from typing import Optional

from ..engine import Engine, stream
from ..errors import NavfnInputError
from ..maps.suite import modes_of
from ..under_test import ORIGINAL
from .hunt import DEFAULT_COSTS, check_size, hunt, hunt_smallest
from .kinds import SEARCH_KINDS

DEFAULT_SIZE = {"cost": (5, 7)}
DEFAULT_MAX_SIZE = {"unreached": (9, 9)}  # hunted for the smallest map up to this size
DEFAULT_HUNT_SIZE = (8, 8)  # the other kinds: hunted here, then shrunk
PARALLEL_SHARE = 10.0  # --jobs auto: modes side by side when each has this many seconds (workers start in ~3 s)


def _overflow_search():
    """The overflow search and its modes (imported only when asked for)."""
    try:
        from .overflow import overflow_modes, search_overflow
    except ImportError as e:
        raise NavfnInputError(f"the overflow search is not available in this installation "
                              f"(navfn_smt.search.overflow: {e})") from None
    return overflow_modes, search_overflow


def _overflow(mode, size, max_size, timeout, seed, progress, planner) -> list:
    search_overflow = _overflow_search()[1]
    return list(search_overflow(mode, size=size, max_size=max_size, timeout=timeout, seed=seed, progress=progress,
                                planner=planner))


def _hunt_mode(task) -> tuple[list, Optional[dict]]:
    """One mode's hunt (a task): its findings (none or one) and, with ``max_size``, the sizes tried."""
    kind, m, size, max_size, share, seed, costs_range, progress, planner = task
    if kind == "overflow":
        return _overflow(m, size, max_size, share, seed, progress, planner), None
    if size is None and max_size is None:
        max_size = DEFAULT_MAX_SIZE.get(kind)
    if max_size is not None:
        f, t = hunt_smallest(kind, m, max_size, share, seed, costs_range, progress, planner)
        return [f] if f is not None else [], {"mode": m, "sizes": t}
    f = hunt(kind, m, tuple(size or DEFAULT_SIZE.get(kind, DEFAULT_HUNT_SIZE)), share, seed, costs_range, progress,
             planner=planner)
    return [f] if f is not None else [], None


def run_search(kind: str, mode: str = "both", size=None, max_size=None, timeout: float = 60.0, seed: int = 0,
               costs_range=DEFAULT_COSTS, progress=None, eng: Engine = Engine(1),
               planner=None) -> tuple[list, list]:
    """The findings of one search (per mode, at most one each), and per mode what sizes were
    tried with ``max_size`` (``[]`` otherwise, and for ``overflow``).  Each mode hunts for its
    share of ``timeout`` on ``eng`` (``auto``: side by side when the share pays for workers)."""
    if kind not in SEARCH_KINDS:
        raise NavfnInputError(f"unknown search kind {kind!r} (choose from {', '.join(SEARCH_KINDS)})")
    if not (timeout > 0 and timeout < float("inf")):
        raise NavfnInputError("--timeout must be positive")
    if size is not None and max_size is not None:
        raise NavfnInputError("--size and --max-size exclude each other")
    planner = ORIGINAL if planner is None else planner
    if not planner.fix.shipped and kind == "overflow":
        raise NavfnInputError("search overflow hunts the C++ buffers' overflow, which the fix does not touch: "
                              "no --variant")
    if size is not None:
        check_size(*size)
    if max_size is not None:
        check_size(*max_size, what="--max-size")
    modes = _overflow_search()[0](mode) if kind == "overflow" else modes_of(mode)
    share = timeout / len(modes)
    tasks = [(kind, m, size, max_size, share, seed, costs_range, progress, planner) for m in modes]
    eng = eng.for_work(len(modes) if share >= PARALLEL_SHARE else 1, 2)
    got = dict(stream(_hunt_mode, tasks, eng))
    findings = [f for i in range(len(modes)) for f in got[i][0]]
    tried = [got[i][1] for i in range(len(modes)) if got[i][1] is not None]
    return findings, tried

