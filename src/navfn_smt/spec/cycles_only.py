"""A candidate fix, for comparison: ``calcNavFnAstar`` / ``calcNavFnDijkstra`` give their one
``propNavFn*`` call ``nx * ny`` cycles instead of ``max(nx*ny/20, nx+ny)``; nothing else changes
(no further call, no fallback where calcPath fails).

Each cycle that runs processes a non-empty buffer and the pending flags keep a cell in one
buffer at a time, so the wave is not cut short by the cycle count on maps where a cell's
potential settles within ``nx * ny`` cycles; where the original's wave stops earlier (start
reached, buffers empty) the run is the original's, cycle for cycle.  calcPath is unchanged, so
its failures on a reached start (the gradient traps of ``docs/fix.md``) stay.
The patches: ``patches/navfn-cycles-only/<distribution>.patch``.
"""

from __future__ import annotations

from .planner import Fix


def cycles(nx: int, ny: int) -> int:
    """``propNavFn*(nx * ny)``: the one call's cycles."""
    return nx * ny


FIX = Fix("cycles-only", "one propNavFn* call of nx*ny cycles instead of max(nx*ny/20, nx+ny), no other change",
          patches="navfn-cycles-only", cycles=cycles)
