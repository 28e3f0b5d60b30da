"""Candidate fixes compared with the fix of docs/fix.md (``navfn-smt fix compare``), each a
:class:`~.planner.Fix` of its hooks; the registry is :mod:`.fixes`.

* ``inclusive``: calcPath's near-goal test ``potarr[...] < COST_NEUTRAL`` made ``<=``.  The
  gradient can circle a cell whose potential is exactly ``COST_NEUTRAL`` (50, the goal's
  4-neighbours on free space) without reading a potential below it; this stops there.  A one
  character patch (``patches/navfn-inclusive/``); it does nothing for a trap away from the goal.
* ``resume``: where the gradient fails, keep its points up to the cell where it got stuck (the
  last cell it had not visited before: from there it only circles cells it knows) and descend the
  potential from there (:func:`.fix.descend`), the whole path within calcPath's ``n`` points.  No
  C++ patch: compared in the spec only.
"""

from __future__ import annotations

from .extraction import Extraction, ExtractionExit, calc_path
from .fix import descend
from .numeric import CONCRETE
from .planner import Fallback, Fix


class CellWatch:
    """The cell ``stc`` of each iteration of a calcPath, and its points (a
    :class:`~.extraction.Watch`); iteration ``i`` writes point ``i``."""

    def __init__(self):
        self.cells: list[int] = []
        self.xs: list = []
        self.ys: list = []

    def iteration(self, i, stc, dx, dy, xs, ys) -> None:
        self.cells.append(int(stc))
        self.xs, self.ys = xs, ys

    def fallback(self, i, oscillation) -> None:
        pass


def stuck_at(cells: list[int]) -> int:
    """The iteration at which the gradient entered the last cell it had not visited before: from
    there on it only comes back to cells it knows (-1 for no iteration)."""
    seen: set[int] = set()
    last = -1
    for i, c in enumerate(cells):
        if c not in seen:
            seen.add(c)
            last = i
    return last


def resume(potential: list, nx: int, ny: int, start: tuple[int, int], goal: tuple[int, int], n: int,
           D=CONCRETE) -> Extraction:
    """The ``resume`` candidate's fallback: the gradient's points before the iteration
    :func:`stuck_at` names, then :func:`.fix.descend` from that iteration's cell with the points
    left of ``n``."""
    watch = CellWatch()
    ext = calc_path(potential, nx, ny, start, goal, n, watch=watch, domain=D)
    at = stuck_at(watch.cells)
    if at < 0 or ext.exit is ExtractionExit.HIGH_POTENTIAL:
        return ext
    kept = list(zip(watch.xs, watch.ys))[:at]
    cell = watch.cells[at]
    rest = descend(potential, nx, ny, (cell % nx, cell // nx), goal, n - len(kept), D)
    if rest.exit is not ExtractionExit.NEAR_GOAL:
        return Extraction([], rest.exit, len(kept) + rest.points_written, rest.cell)
    return Extraction(kept + rest.path, rest.exit, len(kept) + rest.points_written, rest.cell)


INCLUSIVE = Fix("inclusive", "calcPath's near-goal test potarr <= COST_NEUTRAL instead of <, no other change",
                patches="navfn-inclusive", inclusive=True)
RESUME = Fix("resume", "where calcPath fails, its points up to where the gradient got stuck, then the descent of "
             "the fix from there, n points in all (spec only, no patch)", fallback=Fallback(resume))
