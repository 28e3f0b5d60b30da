"""Compiled loops of the whole-map sweep (:mod:`navfn_smt.diagnose.sweep`): one robot cell,
every goal cell planned as ``NavfnPlanner::createPlan`` would plan it alone.

Dijkstra: ``propNavFnDijkstra(cycles, atStart=true)`` for NavFn start ``t`` (a goal's cell)
runs the very same cycles as the loop with ``atStart=false``, up to the end of the cycle in
which ``potarr[t]`` first drops below POT_HIGH; it then stops.  So one loop serves every goal:
at the end of each cycle the goals whose potential became finite in that cycle see exactly
their single-goal potential, and are extracted there (``calcPath``, in the middle of the
propagation).  A goal never reached sees the loop's final state: the single-goal run ends
for the same reason the full loop does (buffers empty, or the cycle limit with ``cycle ==
cycles``), after the same cycles.  The robot's own cell is finite before the first cycle, so
its run stops at the end of cycle 0 (or never starts when the buffers are empty).

A*: the heuristic depends on the goal, so every goal is planned alone (:func:`.jit._propagate`).

``calcPath`` here is :func:`.jit._calc_path_touched`, the body of :func:`.jit._calc_path`
without its reset of the whole gradient arrays: the cells it writes are recorded and zeroed
after the call, which leaves the arrays as the reset would (all zero) at the next call;
``gradCell``'s cache is a pure function of the potential, so the results are bit-identical at
O(path) instead of O(cells) per goal.

The tolerance search is ``_legal_pose`` of the plugin over tables of its own world points:
the plugin's ``tolerance_steps`` and rounding ``worldToMap`` computed once per goal column and
row (they depend only on the goal's x, resp. y), scanned here in the loop's (y, x) order,
first strict minimum of the double squared distance.
"""

from __future__ import annotations

import numpy as np

from ..spec import kernels as K
from ..spec.constants import COST_OBS, POT_HIGH, PRI_INC
from .jit import EXIT_NEAR_GOAL, EXIT_UB, _calc_path_touched, _propagate
from .numba_domain import ND, jit

# per-goal integer columns of the compiled result (``out_i``); CYCLE: the cycles the goal's
# own propagation runs (``PluginRun.cycles``)
ST, EXIT, CYCLE, BEST_X, BEST_Y, NPATH, PATH_OFF, USED_TOL = range(8)
NI = 8
# per-goal float columns (``out_f``): the NavFn path's polyline length in cells, the goal's potential
LENGTH, GOAL_POT = range(2)
NF = 2
# statuses written by the compiled loops (0: not planned yet)
S_PENDING, S_PATH, S_NO_LEGAL, S_NO_PLAN, S_UB = range(5)
# the resumable Dijkstra loop's integer state (``st``)
CUR, NXT, OVER, CYC, DONE, NPTS, NNEW = range(7)
NSTATE = 7


@jit
def _legal_cell(pot, nx, g, out_i, col_of, row_of, xs, xcells, xlen, ys, ycells, ylen, wx, wy):
    """The tolerance search of ``_legal_pose`` for goal ``g``: the legal cell nearest the goal
    (first strict minimum in (y, x) order), or (-1, -1)."""
    high = ND.f32const(POT_HIGH)
    a = col_of[g]
    b = row_of[g]
    best = np.inf
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
            if ND.lt(pot[r * nx + c], high):
                dx = xs[a, xi] - wx[g]
                d = dx * dx + dy * dy
                if d < best:
                    best = d
                    bx = c
                    by = r
    return bx, by


@jit
def _finish_goal(pot, nx, ny, g, tx, ty, rx, ry, nmax, gradx, grady, buf, touched, out_i, out_f, pts, st,
                 keep, col_of, row_of, xs, xcells, xlen, ys, ycells, ylen, wx, wy, memo_cell):
    """``_legal_pose`` + ``getPlanFromPotential`` for goal ``g`` (NavFn start ``(tx, ty)``) on
    ``pot`` as it is now; results into row ``g``.  ``memo_cell`` (length ns, or empty) maps a
    start cell to the goal whose extraction from it on this same potential is reused.
    Returns ``pts`` (grown when a kept path does not fit)."""
    high = ND.f32const(POT_HIGH)
    out_f[g, GOAL_POT] = ND.widen(pot[ty * nx + tx])
    if ND.lt(pot[ty * nx + tx], high):
        bx = tx
        by = ty
    else:
        out_i[g, USED_TOL] = 1
        bx, by = _legal_cell(pot, nx, g, out_i, col_of, row_of, xs, xcells, xlen, ys, ycells, ylen, wx, wy)
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
    code, npath, nt = _calc_path_touched(pot, nx, ny, bx, by, rx, ry, nmax, gradx, grady, buf, touched)
    zero = ND.f32const(0.0)
    for i in range(nt):
        gradx[touched[i]] = zero
        grady[touched[i]] = zero
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
def _sweep_dijkstra(costs, nx, ny, rx, ry, cycles, budget, pot, pending, pb, fill, st, curt, goal_of, newly,
                    tcell, nmax, gradx, grady, buf, touched, out_i, out_f, pts, keep,
                    col_of, row_of, xs, xcells, xlen, ys, ycells, ylen, wx, wy, memo_cell):
    """Up to ``budget`` cycles of ``propNavFnDijkstra(cycles, atStart=false)`` from the robot
    cell, resumable (state in ``pot, pending, pb, fill, st, curt``; ``st[CYC] < 0`` before the
    first call runs ``setupNavFn`` + ``initCost``).  At the end of each cycle every goal whose
    NavFn start became finite in it is finished on the potential as it is then; when the loop
    is over (``st[DONE]``), every goal still pending is finished on the final potential.
    ``goal_of[n]`` is the goal planned from cell ``n`` (-1: none), ``tcell[g]`` its cell.
    Returns ``pts``."""
    ns = nx * ny
    high = ND.f32const(POT_HIGH)
    cap = pb.shape[1]
    if st[CYC] < 0:
        for i in range(ns):
            pot[i] = high
            pending[i] = False
        fill[0] = 0
        fill[1] = 0
        fill[2] = 0
        st[CUR] = 0
        st[NXT] = 1
        st[OVER] = 2
        st[CYC] = 0
        st[NNEW] = 0
        curt[0] = ND.f32const(COST_OBS)
        k = rx + ry * nx
        pot[k] = ND.f32const(0.0)
        cur = 0
        for n in (k + 1, k - 1, k - nx, k + nx):  # push_cur, its guard the kernel push_admitted
            j = min(max(n, 0), ns - 1)  # a read inside the arrays: the guard tests n against the map
            if K.push_admitted(ND, n, ns, pending[j], costs[j], fill[cur], cap):
                pb[cur, fill[cur]] = n
                fill[cur] += 1
                pending[n] = True
        if goal_of[k] >= 0:  # the robot's own cell: finite before the first cycle
            newly[0] = goal_of[k]
            st[NNEW] = 1
    cur = st[CUR]
    nxt = st[NXT]
    over = st[OVER]
    cur_t = curt[0]
    inc = ND.int_to_f32(PRI_INC)
    cycle = st[CYC]
    done = False
    stop = cycle + budget
    while True:
        if cycle >= cycles or (fill[cur] == 0 and fill[nxt] == 0):
            done = True
            break
        if cycle >= stop:
            break
        ncur = fill[cur]
        for i in range(ncur):
            pending[pb[cur, i]] = False
        for i in range(ncur):
            n = pb[cur, i]
            cost = costs[n]
            if not K.is_passable(ND, cost):
                continue
            l = pot[n - 1]
            r = pot[n + 1]
            u = pot[n - nx]
            d = pot[n + nx]
            old = pot[n]
            new, changed = K.cell_update(ND, old, l, r, u, d, cost, ND.int_to_f32(cost))
            if not changed:
                continue
            pot[n] = new
            if not ND.lt(old, high) and goal_of[n] >= 0:
                newly[st[NNEW]] = goal_of[n]
                st[NNEW] += 1
            key = new
            dest = nxt if K.to_low_buffer(ND, key, cur_t) else over
            for j in range(4):
                if j == 0:
                    m = n - 1
                    pm = l
                elif j == 1:
                    m = n + 1
                    pm = r
                elif j == 2:
                    m = n - nx
                    pm = u
                else:
                    m = n + nx
                    pm = d
                if K.push_wanted(ND, pm, key, K.edge_weight(ND, ND.int_to_f32(costs[m]))):
                    if K.push_admitted(ND, m, ns, pending[m], costs[m], fill[dest], cap):
                        pb[dest, fill[dest]] = m
                        fill[dest] += 1
                        pending[m] = True
        fill[cur] = 0
        t = cur
        cur = nxt
        nxt = t
        if fill[cur] == 0:
            cur_t = ND.add(cur_t, inc)
            t = cur
            cur = over
            over = t
        # the end of the cycle: here a single-goal run of each newly reached goal stops
        for i in range(st[NNEW]):
            g = newly[i]
            out_i[g, CYCLE] = cycle + 1
            pts = _finish_goal(pot, nx, ny, g, tcell[g, 0], tcell[g, 1], rx, ry, nmax, gradx, grady, buf, touched,
                               out_i, out_f, pts, st, keep, col_of, row_of, xs, xcells, xlen, ys, ycells, ylen,
                               wx, wy, np.empty(0, np.int64))
        st[NNEW] = 0
        cycle += 1
    st[CUR] = cur
    st[NXT] = nxt
    st[OVER] = over
    st[CYC] = cycle
    curt[0] = cur_t
    if done:
        st[DONE] = 1
        for g in range(out_i.shape[0]):
            if out_i[g, ST] == S_PENDING and goal_of[tcell[g, 1] * nx + tcell[g, 0]] == g:
                out_i[g, CYCLE] = cycle
                pts = _finish_goal(pot, nx, ny, g, tcell[g, 0], tcell[g, 1], rx, ry, nmax, gradx, grady, buf,
                                   touched, out_i, out_f, pts, st, keep, col_of, row_of, xs, xcells, xlen, ys,
                                   ycells, ylen, wx, wy, memo_cell)
    return pts


@jit
def _sweep_astar(costs, nx, ny, rx, ry, cycles, goals, pot, pending, pb, memo, tcell, nmax, gradx, grady, buf,
                 touched, out_i, out_f, pts, st, keep, col_of, row_of, xs, xcells, xlen, ys, ycells, ylen, wx, wy):
    """``calcNavFnAstar`` + ``_legal_pose`` + ``getPlanFromPotential`` for each goal in ``goals``
    alone (NavFn start its cell, NavFn goal the robot's).  Returns ``pts``."""
    no_trace = np.empty(0, np.int32)
    counters = np.zeros(4, np.int64)
    no_memo = np.empty(0, np.int64)
    for i in range(goals.shape[0]):
        g = goals[i]
        tx = tcell[g, 0]
        ty = tcell[g, 1]
        _propagate(costs, nx, ny, tx, ty, rx, ry, True, cycles, pot, pending, pb, no_trace, counters, memo)
        out_i[g, CYCLE] = counters[0]
        pts = _finish_goal(pot, nx, ny, g, tx, ty, rx, ry, nmax, gradx, grady, buf, touched, out_i, out_f, pts,
                           st, keep, col_of, row_of, xs, xcells, xlen, ys, ycells, ylen, wx, wy, no_memo)
    return pts
