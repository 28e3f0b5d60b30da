"""The fast backend: the whole planner re-implemented for numba's JIT.

Trusted only because ``difftest`` holds it bit-equal to the reference spec (and to the
C++ golden files) on every suite.  Written to mirror :mod:`navfn_smt.spec` statement by
statement, with explicit float32/float64 types: numba follows NumPy's promotion rules,
so every float constant is a typed global and every double intermediate is spelled out.
Compiled functions are cached on disk (``cache=True``), so only the first run compiles.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from ..spec.constants import (
    COST_NEUTRAL,
    COST_OBS,
    INT_MIN,
    INVSQRT2,
    PATH_STEP,
    POT_HIGH,
    PRI_INC,
    PRIORITYBUFSIZE,
    QUAD_A,
    QUAD_B,
    QUAD_C,
)

F0 = np.float32(0.0)
F_POT_HIGH = np.float32(POT_HIGH)
F_COST_OBS = np.float32(COST_OBS)
F_MCOST_OBS = np.float32(-COST_OBS)
F_NEUTRAL = np.float32(COST_NEUTRAL)
F_PRI_INC = np.float32(PRI_INC)
F_STEP = np.float32(PATH_STEP)
D_NEUTRAL = np.float64(np.float32(COST_NEUTRAL))
D_INVSQRT2 = np.float64(INVSQRT2)
D_QA = np.float64(QUAD_A)
D_QB = np.float64(QUAD_B)
D_QC = np.float64(QUAD_C)
D_ONE = np.float64(1.0)
BUF = PRIORITYBUFSIZE
I_INT_MIN = INT_MIN

# exit codes of calc_path (match ExtractionExit order in :data:`EXIT_NAMES`)
EXIT_NEAR_GOAL, EXIT_OUT_OF_BOUNDS, EXIT_HIGH_POTENTIAL, EXIT_ZERO_GRADIENT, EXIT_EXHAUSTED, EXIT_UB = range(6)
EXIT_NAMES = ("near_goal", "out_of_bounds", "high_potential", "zero_gradient", "exhausted", "undefined")


@njit(cache=True, error_model="numpy")
def _f2i(a):
    """cvttss2si: truncation, INT_MIN for NaN and out of range."""
    d = np.float64(a)
    if d != d or not (-2147483649.0 < d < 2147483648.0):
        return I_INT_MIN
    return int(d)


@njit(cache=True, error_model="numpy")
def _roundf(a):
    """roundf: halves away from zero (exact for float32 inputs, see spec.numeric)."""
    d = np.float64(a)
    if d != d or math.isinf(d):
        return a
    m = abs(d)
    if m >= 8388608.0:
        return a
    r = math.floor(m + 0.5)
    if d < 0.0:
        r = -r
    return np.float32(r)


@njit(cache=True, error_model="numpy")
def _heuristic(ddx, ddy):
    return np.float32(math.hypot(np.float64(ddx), np.float64(ddy)) * D_NEUTRAL)


@njit(cache=True, error_model="numpy")
def _edge(c):
    return np.float32(D_INVSQRT2 * np.float64(np.float32(c)))


@njit(cache=True, error_model="numpy")
def _propagate(costs, nx, ny, sx, sy, gx, gy, astar, cycles, pot, pending, pb, trace, counters):
    """setupNavFn + propNavFn{Astar,Dijkstra}(cycles, atStart=true).

    ``pb`` is a (3, BUF) int array for the three buffers; ``trace`` receives the white-box
    trace (stops recording when full; ``counters[3]`` then exceeds ``len(trace)``).
    ``counters`` = [cycles, updates, dropped, trace_len]; returns start_reached.
    """
    ns = nx * ny
    for i in range(ns):
        pot[i] = F_POT_HIGH
        pending[i] = False
    cur = 0
    nxt = 1
    over = 2
    fill = np.zeros(3, np.int64)
    ncyc = 0
    nupd = 0
    ndrop = 0
    tlen = 0
    tcap = trace.shape[0]
    cur_t = F_COST_OBS
    k = gx + gy * nx
    pot[k] = F0
    # push_cur; the push is written out at both sites: a helper taking arrays would pay
    # reference-count updates on every call (7x slower in the update loop)
    for n in (k + 1, k - 1, k - nx, k + nx):
        if n >= 0 and n < ns and not pending[n] and costs[n] < COST_OBS:
            if fill[cur] < BUF:
                pb[cur, fill[cur]] = n
                fill[cur] += 1
                pending[n] = True
            else:
                ndrop += 1
    start_cell = sy * nx + sx
    if astar:
        cur_t = _heuristic(gx - sx, gy - sy) + cur_t
    cycle = 0
    while cycle < cycles:
        if fill[cur] == 0 and fill[nxt] == 0:
            break
        ncur = fill[cur]
        ncyc += 1
        if tlen < tcap:
            trace[tlen] = ncur
        tlen += 1
        for i in range(ncur):
            c = pb[cur, i]
            pending[c] = False
            if tlen < tcap:
                trace[tlen] = c
            tlen += 1
        for i in range(ncur):
            n = pb[cur, i]
            nupd += 1
            cost = costs[n]
            if cost >= COST_OBS:
                continue
            l = pot[n - 1]
            r = pot[n + 1]
            u = pot[n - nx]
            d = pot[n + nx]
            tc = l if l < r else r
            ta = u if u < d else d
            hf = np.float32(cost)
            dc = np.float32(tc - ta)
            if dc < F0:
                dc = -dc
                ta = tc
            if dc >= hf:
                new = np.float32(ta + hf)
            else:
                w = np.float64(np.float32(dc / hf))
                v = np.float32(D_QA * w * w + D_QB * w + D_QC)
                new = np.float32(ta + np.float32(hf * v))
            if not (new < pot[n]):
                continue
            pot[n] = new
            key = new
            if astar:
                key = np.float32(new + _heuristic(n % nx - sx, n // nx - sy))
            dest = nxt if key < cur_t else over
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
                if pm > np.float32(key + _edge(costs[m])):
                    if m >= 0 and m < ns and not pending[m] and costs[m] < COST_OBS:
                        if fill[dest] < BUF:
                            pb[dest, fill[dest]] = m
                            fill[dest] += 1
                            pending[m] = True
                        else:
                            ndrop += 1
        # swap buffers
        fill[cur] = 0
        t = cur
        cur = nxt
        nxt = t
        if fill[cur] == 0:
            cur_t = np.float32(cur_t + F_PRI_INC)
            t = cur
            cur = over
            over = t
        if pot[start_cell] < F_POT_HIGH:
            break
        cycle += 1
    counters[0] = ncyc
    counters[1] = nupd
    counters[2] = ndrop
    counters[3] = tlen
    if astar:
        return pot[start_cell] < F_POT_HIGH
    return cycle < cycles


@njit(cache=True, error_model="numpy")
def _bilinear(t, a, b):
    return np.float32((D_ONE - np.float64(t)) * np.float64(a) + np.float64(np.float32(t * b)))


@njit(cache=True, error_model="numpy")
def _calc_path(pot, nx, ny, sx, sy, gx, gy, nmax, gradx, grady, path):
    """calcPath(nmax); ``path`` is (nmax, 2) float32.  Returns (exit code, npath)."""
    ns = nx * ny
    for i in range(ns):
        gradx[i] = F0
        grady[i] = F0
    stc = sy * nx + sx
    dx = F0
    dy = F0
    npath = 0
    fnx = np.float32(nx)
    for _ in range(nmax):
        ox = _f2i(_roundf(dx))
        oy = _f2i(np.float32(fnx * _roundf(dy)))
        near = stc + ox + oy
        near = ((near + 2147483648) & 0xFFFFFFFF) - 2147483648  # int32 wrap-around, as on x86-64
        if near > ns - 1:
            near = ns - 1
        if near < 0:
            near = 0
        if pot[near] < F_NEUTRAL:
            path[npath, 0] = np.float32(gx)
            path[npath, 1] = np.float32(gy)
            npath += 1
            return EXIT_NEAR_GOAL, npath
        if stc < nx or stc > ns - nx:
            return EXIT_OUT_OF_BOUNDS, npath
        if stc - nx - 1 < 0 or stc + nx + 1 >= ns:
            return EXIT_UB, npath
        path[npath, 0] = np.float32(np.float32(stc % nx) + dx)
        path[npath, 1] = np.float32(np.float32(stc // nx) + dy)
        npath += 1
        osc = (
            npath > 2
            and path[npath - 1, 0] == path[npath - 3, 0]
            and path[npath - 1, 1] == path[npath - 3, 1]
        )
        up = stc - nx
        down = stc + nx
        if (
            pot[stc] >= F_POT_HIGH
            or pot[stc + 1] >= F_POT_HIGH
            or pot[stc - 1] >= F_POT_HIGH
            or pot[down] >= F_POT_HIGH
            or pot[down + 1] >= F_POT_HIGH
            or pot[down - 1] >= F_POT_HIGH
            or pot[up] >= F_POT_HIGH
            or pot[up + 1] >= F_POT_HIGH
            or pot[up - 1] >= F_POT_HIGH
            or osc
        ):
            minc = stc
            minp = _f2i(pot[stc])
            for m in (up - 1, up, up + 1, stc - 1, stc + 1, down - 1, down, down + 1):
                if pot[m] < np.float32(minp):
                    minp = _f2i(pot[m])
                    minc = m
            stc = minc
            dx = F0
            dy = F0
            if pot[stc] >= F_POT_HIGH:
                return EXIT_HIGH_POTENTIAL, npath
        else:
            # gradCell for the four cells of the interpolation square (inlined: array
            # arguments to a helper cost reference-count updates on every call)
            for n in (stc, stc + 1, down, down + 1):
                if np.float32(gradx[n] + grady[n]) > F0:
                    continue
                if n < nx or n > ns - nx:
                    continue
                if n + nx >= ns:  # n == ns - nx: the C++ reads potarr[ns]
                    return EXIT_UB, npath
                cv = pot[n]
                gdx = F0
                gdy = F0
                if cv >= F_POT_HIGH:
                    if pot[n - 1] < F_POT_HIGH:
                        gdx = F_MCOST_OBS
                    elif pot[n + 1] < F_POT_HIGH:
                        gdx = F_COST_OBS
                    if pot[n - nx] < F_POT_HIGH:
                        gdy = F_MCOST_OBS
                    elif pot[n + nx] < F_POT_HIGH:
                        gdy = F_COST_OBS
                else:
                    if pot[n - 1] < F_POT_HIGH:
                        gdx = np.float32(gdx + np.float32(pot[n - 1] - cv))
                    if pot[n + 1] < F_POT_HIGH:
                        gdx = np.float32(gdx + np.float32(cv - pot[n + 1]))
                    if pot[n - nx] < F_POT_HIGH:
                        gdy = np.float32(gdy + np.float32(pot[n - nx] - cv))
                    if pot[n + nx] < F_POT_HIGH:
                        gdy = np.float32(gdy + np.float32(cv - pot[n + nx]))
                norm = np.float32(math.hypot(gdx, gdy))
                if norm > F0:
                    inv = np.float32(D_ONE / np.float64(norm))
                    gradx[n] = np.float32(inv * gdx)
                    grady[n] = np.float32(inv * gdy)
            x1 = _bilinear(dx, gradx[stc], gradx[stc + 1])
            x2 = _bilinear(dx, gradx[down], gradx[down + 1])
            x = _bilinear(dy, x1, x2)
            y1 = _bilinear(dx, grady[stc], grady[stc + 1])
            y2 = _bilinear(dx, grady[down], grady[down + 1])
            y = _bilinear(dy, y1, y2)
            if x == F0 and y == F0:
                return EXIT_ZERO_GRADIENT, npath
            ss = np.float32(F_STEP / np.float32(math.hypot(x, y)))
            dx = np.float32(dx + np.float32(x * ss))
            dy = np.float32(dy + np.float32(y * ss))
            if np.float64(dx) > D_ONE:
                stc += 1
                dx = np.float32(np.float64(dx) - D_ONE)
            if np.float64(dx) < -D_ONE:
                stc -= 1
                dx = np.float32(np.float64(dx) + D_ONE)
            if np.float64(dy) > D_ONE:
                stc += nx
                dy = np.float32(np.float64(dy) - D_ONE)
            if np.float64(dy) < -D_ONE:
                stc -= nx
                dy = np.float32(np.float64(dy) + D_ONE)
    return EXIT_EXHAUSTED, npath


class JitPlanner:
    """Work arrays for one map size, reused across the cases of a map."""

    def __init__(self, costs_with_border: np.ndarray):
        c = np.ascontiguousarray(costs_with_border, dtype=np.uint8)
        self.ny, self.nx = c.shape
        self.costs = c.ravel()
        ns = self.nx * self.ny
        self.pot = np.empty(ns, np.float32)
        self.pending = np.zeros(ns, np.bool_)
        self.pb = np.zeros((3, BUF), np.int64)
        self.gradx = np.zeros(ns, np.float32)
        self.grady = np.zeros(ns, np.float32)
        self.trace = np.empty(max(4 * ns, 1 << 12), np.int32)
        self.no_trace = np.empty(0, np.int32)
        self.counters = np.zeros(4, np.int64)
        self.path = np.empty((4 * self.nx + 1, 2), np.float32)

    def run(self, start, goal, astar: bool, cycles: int, path_cycles: int, record_trace: bool = True):
        """Plan one case; with ``record_trace`` False no trace is kept (memory stays linear
        in the map size: the trace grows with the number of updates)."""
        sx, sy = start
        gx, gy = goal
        while True:
            reached = _propagate(
                self.costs, self.nx, self.ny, sx, sy, gx, gy, astar, cycles,
                self.pot, self.pending, self.pb, self.trace if record_trace else self.no_trace, self.counters,
            )
            if not record_trace or self.counters[3] <= self.trace.shape[0]:
                break
            self.trace = np.empty(int(self.counters[3]) * 2, np.int32)
        if self.path.shape[0] < path_cycles + 1:
            self.path = np.empty((path_cycles + 1, 2), np.float32)
        code, npath = _calc_path(
            self.pot, self.nx, self.ny, sx, sy, gx, gy, path_cycles, self.gradx, self.grady, self.path
        )
        return bool(reached), int(code), int(npath)


@njit(cache=True, error_model="numpy")
def _run_cases(costs, nx, ny, cases, astar, cycles, path_cycles, pot, pending, pb, gradx, grady,
               reached, start_pot, ncycles, nupdates, ndropped, exits, path_off, path_pts):
    """Plan every case of one map in one call (no trace); results go to the output arrays.

    ``path_pts`` must hold ``len(cases) * (path_cycles + 1)`` points; case ``i``'s path is
    ``path_pts[path_off[i]:path_off[i + 1]]`` (empty unless the exit is NEAR_GOAL).
    """
    no_trace = np.empty(0, np.int32)
    counters = np.zeros(4, np.int64)
    buf = np.empty((path_cycles + 1, 2), np.float32)
    off = 0
    path_off[0] = 0
    for i in range(cases.shape[0]):
        sx, sy, gx, gy = cases[i, 0], cases[i, 1], cases[i, 2], cases[i, 3]
        reached[i] = _propagate(costs, nx, ny, sx, sy, gx, gy, astar, cycles, pot, pending, pb, no_trace, counters)
        start_pot[i] = pot[sy * nx + sx]
        ncycles[i] = counters[0]
        nupdates[i] = counters[1]
        ndropped[i] = counters[2]
        code, npath = _calc_path(pot, nx, ny, sx, sy, gx, gy, path_cycles, gradx, grady, buf)
        exits[i] = code
        if code == EXIT_NEAR_GOAL:
            for k in range(npath):
                path_pts[off + k, 0] = buf[k, 0]
                path_pts[off + k, 1] = buf[k, 1]
            off += npath
        path_off[i + 1] = off


def run_cases(planner: "JitPlanner", cases: np.ndarray, astar: bool, cycles: int, path_cycles: int) -> dict:
    """Batch form of :meth:`JitPlanner.run` for benchmarks and bulk planning (no traces)."""
    cases = np.ascontiguousarray(cases, dtype=np.int64).reshape(-1, 4)
    n = cases.shape[0]
    out = {
        "start_reached": np.zeros(n, np.bool_),
        "start_potential": np.zeros(n, np.float32),
        "cycles": np.zeros(n, np.int64),
        "updates": np.zeros(n, np.int64),
        "dropped": np.zeros(n, np.int64),
        "exit": np.zeros(n, np.int64),
        "path_offsets": np.zeros(n + 1, np.int64),
        "path": np.zeros((n * (path_cycles + 1), 2), np.float32),
    }
    _run_cases(planner.costs, planner.nx, planner.ny, cases, astar, cycles, path_cycles, planner.pot,
               planner.pending, planner.pb, planner.gradx, planner.grady, out["start_reached"],
               out["start_potential"], out["cycles"], out["updates"], out["dropped"], out["exit"],
               out["path_offsets"], out["path"])
    out["path"] = out["path"][: out["path_offsets"][-1]]
    return out
