"""Compiled screens of the search kinds over the columns of ``run_batch``.

The definitions live in :mod:`navfn_smt.check.properties` (path cost, optimum, gap) and
:mod:`.kinds` (turn, oscillation); these functions compute the same numbers for thousands
of planned cases at once so that the hunt can rank candidate maps.  They only *screen*:
every counterexample is replayed on the reference spec and judged by the definitions
before it is reported, and ``tests/test_search.py`` holds the screens equal to the
definitions on random maps.

Maps are flat uint8 arrays with the lethal border, cell ``(x, y)`` at ``y * nx + x``;
``path``/``offsets`` are ``run_batch``'s ``path`` and ``path_offsets``.
"""

from __future__ import annotations

import heapq
import math

import numpy as np
from numba import njit

from ..spec.constants import COST_OBS

_NONE = -1


@njit(cache=True)
def _cell_of(v):
    """``properties.nearest_cell`` of one coordinate: ``floor(v + 0.5)`` (in binary64)."""
    return int(math.floor(np.float64(v) + 0.5))


@njit(cache=True)
def path_costs(costs, nx, ny, path, offsets, out_first, out_last):
    """``properties.path_cost`` of every path (-1 for an empty path or a point off the map);
    the first and last cells of each path go to ``out_first``/``out_last`` (flat indices)."""
    n = offsets.shape[0] - 1
    out = np.full(n, _NONE, np.int64)
    for i in range(n):
        a, b = offsets[i], offsets[i + 1]
        if b == a:
            continue
        total = 0
        prev = -1
        ok = True
        for k in range(a, b):
            x = _cell_of(path[k, 0])
            y = _cell_of(path[k, 1])
            if not (0 <= x < nx and 0 <= y < ny):
                ok = False
                break
            c = y * nx + x
            if k == a:
                out_first[i] = c
            if c != prev:
                total += costs[c]
                prev = c
        if ok:
            out[i] = total
            out_last[i] = prev
    return out


@njit(cache=True)
def _dijkstra(costs, nx, ny, src, dist):
    """Cheapest 8-connected chains of passable cells from ``src`` (every cell's cost counted,
    ``src`` included), as ``properties.optimal_cost``; ``dist`` is -1 where none."""
    ns = nx * ny
    for i in range(ns):
        dist[i] = _NONE
    if costs[src] >= COST_OBS:
        return
    dist[src] = costs[src]
    heap = [(np.int64(costs[src]), np.int64(src))]
    done = np.zeros(ns, np.bool_)
    while len(heap) > 0:
        d, c = heapq.heappop(heap)
        if done[c]:
            continue
        done[c] = True
        x, y = c % nx, c // nx
        for ddy in (-1, 0, 1):
            for ddx in (-1, 0, 1):
                if ddx == 0 and ddy == 0:
                    continue
                xx, yy = x + ddx, y + ddy
                if not (0 <= xx < nx and 0 <= yy < ny):
                    continue
                m = yy * nx + xx
                if costs[m] >= COST_OBS or done[m]:
                    continue
                nd = d + costs[m]
                if dist[m] == _NONE or nd < dist[m]:
                    dist[m] = nd
                    heapq.heappush(heap, (nd, np.int64(m)))


@njit(cache=True)
def gaps(costs, nx, ny, path, offsets):
    """``properties.cost_gap`` of every case: path cost minus the optimum between the path's
    first and last cells; -1 where the gap is undefined (no path, no chain)."""
    n = offsets.shape[0] - 1
    first = np.full(n, _NONE, np.int64)
    last = np.full(n, _NONE, np.int64)
    pc = path_costs(costs, nx, ny, path, offsets, first, last)
    out = np.full(n, _NONE, np.int64)
    ns = nx * ny
    dist = np.empty(ns, np.int64)
    cur_src = -1
    order = np.argsort(first)
    for j in range(n):
        i = order[j]
        if pc[i] < 0 or costs[last[i]] >= COST_OBS:
            continue
        if first[i] != cur_src:
            _dijkstra(costs, nx, ny, first[i], dist)
            cur_src = first[i]
        opt = dist[last[i]]
        if opt != _NONE:
            out[i] = pc[i] - opt
    return out, pc


@njit(cache=True)
def _steps_at(path, k):
    """The steps into and out of point ``k`` (binary64 differences of the float32 points)."""
    ux = np.float64(path[k, 0]) - np.float64(path[k - 1, 0])
    uy = np.float64(path[k, 1]) - np.float64(path[k - 1, 1])
    vx = np.float64(path[k + 1, 0]) - np.float64(path[k, 0])
    vy = np.float64(path[k + 1, 1]) - np.float64(path[k, 1])
    return ux, uy, vx, vy


@njit(cache=True)
def turns(path, offsets):
    """Per path: the number of obtuse turns (consecutive step vectors with a negative dot
    product, binary64 from the float32 points) and the number of turn positions (steps - 1)."""
    n = offsets.shape[0] - 1
    bad = np.zeros(n, np.int64)
    slots = np.zeros(n, np.int64)
    for i in range(n):
        a, b = offsets[i], offsets[i + 1]
        for k in range(a + 1, b - 1):
            ux, uy, vx, vy = _steps_at(path, k)
            slots[i] += 1
            if ux * vx + uy * vy < 0.0:
                bad[i] += 1
    return bad, slots


@njit(cache=True)
def right_or_sharper(path, offsets):
    """Per path: turns of 90 degrees or more (dot product <= 0, both steps non-zero)."""
    n = offsets.shape[0] - 1
    out = np.zeros(n, np.int64)
    for i in range(n):
        a, b = offsets[i], offsets[i + 1]
        for k in range(a + 1, b - 1):
            ux, uy, vx, vy = _steps_at(path, k)
            if (ux != 0.0 or uy != 0.0) and (vx != 0.0 or vy != 0.0) and ux * vx + uy * vy <= 0.0:
                out[i] += 1
    return out


@njit(cache=True)
def oscillations(path, offsets):
    """Per path: the number of points equal (both float32 coordinates) to the point two before,
    and the number of points that have one two before (points - 2)."""
    n = offsets.shape[0] - 1
    bad = np.zeros(n, np.int64)
    slots = np.zeros(n, np.int64)
    for i in range(n):
        a, b = offsets[i], offsets[i + 1]
        for k in range(a + 2, b):
            slots[i] += 1
            if path[k, 0] == path[k - 2, 0] and path[k, 1] == path[k - 2, 1]:
                bad[i] += 1
    return bad, slots
