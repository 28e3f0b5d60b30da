"""Compiled loops of the whole-map sweep (:mod:`navfn_smt.diagnose.sweep`): one robot cell,
every goal cell planned as ``NavfnPlanner::createPlan`` would plan it alone, by the backend's
compiled NavFn (:mod:`navfn_smt.backends.jit`) and the plugin's own rules.

Dijkstra: ``propNavFnDijkstra(cycles, atStart=true)`` for NavFn start ``t`` (a goal's cell)
runs the very same cycles as the loop with ``atStart=false``, up to the end of the cycle in
which ``potarr[t]`` first drops below POT_HIGH; it then stops.  So one loop serves every goal:
the spec's propagation (:func:`~navfn_smt.spec.propagation.propagate`) compiled on the JIT's
state, which watches the goals' cells and pauses at the end of a cycle that reached some
(:mod:`navfn_smt.backends.jit_state`).  There the goals whose potential became finite in that
cycle see exactly their single-goal potential, and are extracted (``calcPath``, in the middle
of the propagation).  A goal never reached sees the loop's final state: the single-goal run
ends for the same reason the full loop does (buffers empty, or the cycle limit with ``cycle ==
cycles``), after the same cycles.  The robot's own cell is finite before the first cycle, so
its run stops at the end of cycle 0 (or never starts when the buffers are empty).

A*: the heuristic depends on the goal, so every goal is planned alone (the JIT's planning call).

``calcPath`` here is the JIT's (:func:`~navfn_smt.backends.jit.extract_path`), which zeroes the
gradient cells it wrote after the call, as the reset of the whole arrays would (all zero) at the
next call; ``gradCell``'s cache is a pure function of the potential, so the results are
bit-identical at O(path) instead of O(cells) per goal.

The tolerance search is ``_legal_pose`` of the plugin over tables of its world points (the
plugin's ``tolerance_steps`` and rounding ``worldToMap`` computed once per goal column and
row: they depend only on the goal's x, resp. y), scanned here in the loop's (y, x) order with
the plugin's own choice (:func:`.plugin.tolerance_prefers`).
"""

from __future__ import annotations

from collections import namedtuple

import numpy as np

from ..backends.jit import EXIT_NEAR_GOAL, EXIT_UB, NEVER, call_on, extract_path, start_call
from ..backends.jit_state import BUDGET as BUDGET_AT
from ..backends.jit_state import NPATH as POINTS
from ..backends.jit_state import CYCLES, NNEW, NX, NY, PAUSED, poke, state_of
from ..backends.numba_domain import jit
from ..spec import propagation as P
from ..spec.constants import DBL_MAX, POT_HIGH
from .plugin import squared_offset, tolerance_prefers

_squared_offset = jit(squared_offset)  # the plugin's rule, compiled
_tolerance_prefers = jit(tolerance_prefers)

# per-goal integer columns of the compiled result (``out_i``); CYCLE: the cycles the goal's
# own propagation runs (``PluginRun.cycles``)
ST, EXIT, CYCLE, BEST_X, BEST_Y, NPATH, PATH_OFF, USED_TOL = range(8)
NI = 8
# per-goal float columns (``out_f``): the NavFn path's polyline length in cells, the goal's potential
LENGTH, GOAL_POT = range(2)
NF = 2
# statuses written by the compiled loops (0: not planned yet)
S_PENDING, S_PATH, S_NO_LEGAL, S_NO_PLAN, S_UB = range(5)
# the sweep's integer state (``st``): whether the Dijkstra loop has started and is over; the
# points kept so far
STARTED, DONE, NPTS = range(3)
NSTATE = 3
# the goals' tolerance tables (built by diagnose/sweep.py): goal g's world point (wx[g], wy[g]), the
# columns of its tolerance search (xs, xcells: xlen[col_of[g]] of them) and its rows likewise
Tolerance = namedtuple("Tolerance", "col_of row_of xs xcells xlen ys ycells ylen wx wy")


@jit
def _legal_cell(D, pot, nx, g, tables):
    """The tolerance search of ``_legal_pose`` for goal ``g`` by the plugin's rule
    (:func:`.plugin.tolerance_prefers`): the cell of the point it chooses, or (-1, -1)."""
    col_of, row_of, xs, xcells, xlen, ys, ycells, ylen, wx, wy = tables
    a = col_of[g]
    b = row_of[g]
    best = DBL_MAX
    bx = -1
    by = -1
    for yi in range(ylen[b]):
        r = ycells[b, yi]
        if r < 0:
            continue
        dy = ys[b, yi] - wy[g]
        for xi in range(xlen[a]):
            c = xcells[a, xi]
            if c < 0:
                continue
            d = _squared_offset(xs[a, xi] - wx[g], dy)
            if _tolerance_prefers(D.widen(pot[r * nx + c]), d, best):
                best = d
                bx = c
                by = r
    return bx, by


@jit
def _finish_goal(D, pot, nx, ny, g, tx, ty, rx, ry, nmax, trail, out_i, out_f, pts, st, keep, tables, memo_cell):
    """``_legal_pose`` + ``getPlanFromPotential`` for goal ``g`` (NavFn start ``(tx, ty)``) on
    ``pot`` as it is now; results into row ``g``.  ``memo_cell`` (length ns, or empty) maps a
    start cell to the goal whose extraction from it on this same potential is reused.
    Returns ``pts`` (grown when a kept path does not fit)."""
    high = D.f32const(POT_HIGH)
    out_f[g, GOAL_POT] = D.widen(pot[ty * nx + tx])
    if D.lt(pot[ty * nx + tx], high):
        bx = tx
        by = ty
    else:
        out_i[g, USED_TOL] = 1
        bx, by = _legal_cell(D, pot, nx, g, tables)
        if bx < 0:
            out_i[g, ST] = S_NO_LEGAL
            out_i[g, EXIT] = -1
            return pts
    out_i[g, BEST_X] = bx
    out_i[g, BEST_Y] = by
    if memo_cell.shape[0] > 0:
        h = memo_cell[by * nx + bx]
        if h >= 0:
            for j in (ST, EXIT, NPATH, PATH_OFF):
                out_i[g, j] = out_i[h, j]
            out_f[g, LENGTH] = out_f[h, LENGTH]
            return pts
        memo_cell[by * nx + bx] = g
    code = extract_path(D, pot, nx, ny, bx, by, rx, ry, nmax, trail, False)
    npath = trail.ints[POINTS]
    buf = trail.path
    out_i[g, EXIT] = code
    if code == EXIT_UB:
        out_i[g, ST] = S_UB
        return pts
    if code != EXIT_NEAR_GOAL:
        out_i[g, ST] = S_NO_PLAN
        return pts
    out_i[g, ST] = S_PATH
    out_i[g, NPATH] = npath
    length = 0.0
    for i in range(1, npath):
        ddx = np.float64(buf[i, 0]) - np.float64(buf[i - 1, 0])
        ddy = np.float64(buf[i, 1]) - np.float64(buf[i - 1, 1])
        length += np.sqrt(ddx * ddx + ddy * ddy)
    out_f[g, LENGTH] = length
    if keep:
        off = st[NPTS]
        if off + npath > pts.shape[0]:
            grown = np.empty((max(2 * pts.shape[0], off + npath), 2), np.float32)
            grown[:off] = pts[:off]
            pts = grown
        for i in range(npath):
            pts[off + i, 0] = buf[i, 0]
            pts[off + i, 1] = buf[i, 1]
        out_i[g, PATH_OFF] = off
        st[NPTS] = off + npath
    return pts


@jit
def sweep_dijkstra(D, work, rx, ry, cycles, budget, sw, goal_of, tcell, nmax, trail, out_i, out_f, pts, keep, tables,
                   memo_cell):
    """Up to ``budget`` cycles of ``propNavFnDijkstra(cycles, atStart=false)`` from the robot
    cell: the spec's :func:`~navfn_smt.spec.propagation.propagate` on the state of ``work``
    (:mod:`navfn_smt.backends.jit_state`), which watches the goals' cells (``work.watch``, a copy
    of ``goal_of`` that the loop marks as it reports them) and pauses at the end of a cycle that
    reached some.  Before the first call (``sw[STARTED]`` 0) it runs ``initCost``.  At each pause
    every goal whose NavFn start became finite in that cycle is finished on the potential as it
    is then; when the loop is over (``sw[DONE]``), every goal still pending is finished on the
    final potential.  ``goal_of[n]`` is the goal planned from cell ``n`` (-1: none), ``tcell[g]``
    its cell.  Returns ``pts``."""
    st = state_of(D, work)
    ints = work.ints
    pot = work.potential
    nx = st.nx
    ny = st.ny
    if not sw[STARTED]:
        start_call(st)
        k = rx + ry * nx
        P.init_cost(st, k)
        sw[STARTED] = 1
        if goal_of[k] >= 0:  # the robot's own cell: finite before the first cycle, reported at its end
            work.newly[0] = goal_of[k]
            work.watch[k] = -1
            poke(st.p_ints, NNEW, 1)
    poke(st.p_ints, BUDGET_AT, budget)
    while True:
        P.propagate(st, (rx, ry), (rx, ry), False, cycles - ints[CYCLES], False, record_trace=False)
        if not ints[PAUSED]:
            sw[DONE] = 1
            break
        # the end of a cycle: here a single-goal run of each newly reached goal stops
        for i in range(ints[NNEW]):
            g = work.newly[i]
            out_i[g, CYCLE] = ints[CYCLES]
            pts = _finish_goal(D, pot, nx, ny, g, tcell[g, 0], tcell[g, 1], rx, ry, nmax, trail, out_i, out_f, pts, sw,
                               keep, tables, memo_cell[:0])
        poke(st.p_ints, NNEW, 0)
        if ints[BUDGET_AT] == 0:
            return pts
    for g in range(out_i.shape[0]):
        if out_i[g, ST] == S_PENDING and goal_of[tcell[g, 1] * nx + tcell[g, 0]] == g:
            out_i[g, CYCLE] = ints[CYCLES]
            pts = _finish_goal(D, pot, nx, ny, g, tcell[g, 0], tcell[g, 1], rx, ry, nmax, trail, out_i, out_f, pts, sw,
                               keep, tables, memo_cell)
    return pts


@jit
def sweep_astar(D, work, rx, ry, cycles, goals, tcell, nmax, trail, out_i, out_f, pts, sw, keep, tables):
    """``calcNavFnAstar`` + ``_legal_pose`` + ``getPlanFromPotential`` for each goal in ``goals``
    alone (NavFn start its cell, NavFn goal the robot's): the spec's planning call on the state of
    ``work``.  Returns ``pts``."""
    no_memo = np.empty(0, np.int64)
    st = state_of(D, work)
    pot = work.potential
    nx = work.ints[NX]
    ny = work.ints[NY]
    for i in range(goals.shape[0]):
        g = goals[i]
        tx = tcell[g, 0]
        ty = tcell[g, 1]
        call_on(st, tx, ty, rx, ry, True, cycles, NEVER, 0, False)
        out_i[g, CYCLE] = work.ints[CYCLES]
        pts = _finish_goal(D, pot, nx, ny, g, tx, ty, rx, ry, nmax, trail, out_i, out_f, pts, sw, keep, tables, no_memo)
    return pts
