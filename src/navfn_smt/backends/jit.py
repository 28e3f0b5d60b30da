"""The fast backend: the planner's loops and memory, compiled by numba around the spec's kernels.

Every number this backend computes comes from :mod:`navfn_smt.spec.kernels`, the same
functions the reference spec runs and the SMT obligations reason about, compiled against
the numba domain (:mod:`.numba_domain`).  What is written here is only what is about loops
and memory: flat work arrays reused across the cases of a map, the three priority
buffers with their capacity and pending flags, the cycle and path loops, the trace.
Those loops are held equal to the reference spec's by difftest and by the conformance
test on generated maps.  Compiled functions are cached on disk, keyed by the sources.
"""

from __future__ import annotations

from collections import namedtuple

import numpy as np

from ..spec import extraction as E
from ..spec import fix as F
from ..spec import kernels as K
from ..spec import propagation as P
from ..spec.constants import COST_OBS, PATH_STEP, POT_HIGH, PRI_INC, PRIORITYBUFSIZE
from ..spec.extraction import EXIT_UNDEFINED, ITERATION_GOES_ON, ExtractionExit, exit_code
from ..spec.planner import path_cycle_limit
from .numba_domain import jit, jit_inline, numba_domain

# maps up to this many cells keep the A* heuristic of every (dx, dy) offset once computed
# (a float per offset: 4 * (2nx-1)(2ny-1) bytes, 16 MiB at the limit); larger maps call it
HEURISTIC_MEMO_CELLS = 1 << 20

# calcPath's exits as the compiled code returns them (spec.extraction.exit_code)
EXIT_NEAR_GOAL = exit_code(ExtractionExit.NEAR_GOAL)
EXIT_HIGH_POTENTIAL = exit_code(ExtractionExit.HIGH_POTENTIAL)
EXIT_ZERO_GRADIENT = exit_code(ExtractionExit.ZERO_GRADIENT)
EXIT_EXHAUSTED = exit_code(ExtractionExit.EXHAUSTED)
EXIT_UB = EXIT_UNDEFINED


# the propagation's state, one value through the compiled loops: the potentials ``pot``, the
# ``pending`` flags, the three priority buffers (rows of ``pb``), ``role`` = which of them is
# current, next and overflow, ``fill`` = how many cells each holds, ``curt`` = [curT], the
# threshold between the next and the overflow buffer (its arrays change in place)
Wave = namedtuple("Wave", "pot pending pb fill role curt")
CUR, NXT, OVER = range(3)
# ``counters``: C++'s loop variable ``cycle``, the cycles run, cells updated, pushes dropped
# for want of room, trace entries wanted (more than ``len(trace)`` when it was too short),
# watched cells newly reached
CYCLE, CYCLES, UPDATES, DROPPED, TRACE_LEN, NEWLY = range(6)
NCOUNTERS = 6

# the loop's tests, the spec's functions compiled (the obligations of proofs/loop.py are about them)
update_neighbours = jit_inline(P.update_neighbours)  # updateCell's l, r, u, d, in the order of its pushes
cycle_runs = jit_inline(P.cycle_runs)
call_ends_at_the_start = jit_inline(P.call_ends_at_the_start)
calls_again = jit_inline(F.calls_again)
# calcPath's tests and grid step, the spec's functions compiled (proofs/calcpath.py is about them)
iteration_test = jit_inline(E.iteration_test)
follows_the_grid = jit_inline(E.follows_the_grid)
grid_step = jit_inline(E.grid_step)
goal_point = jit_inline(E.goal_point)
oscillates = jit_inline(E.oscillates)
zero_gradient = jit_inline(E.zero_gradient)


@jit_inline
def start_propagation(D, costs, nx, ny, gx, gy, wave):
    """setupNavFn + initCost(goal) + the ``push_cur`` of the goal's four neighbours.

    Every potential POT_HIGH, nothing pending, the goal's potential 0, curT = COST_OBS
    (float), the buffers empty and in their first roles.  Returns the pushes the kernel
    ``push`` refused only for want of room (counted as dropped).
    """
    pot, pending, pb, fill, role, curt = wave
    ns = nx * ny
    high = D.f32const(POT_HIGH)
    for i in range(ns):
        pot[i] = high
        pending[i] = False
    for b in range(3):
        fill[b] = 0
        role[b] = b
    curt[0] = D.f32const(COST_OBS)
    cap = pb.shape[1]
    k = gx + gy * nx
    pot[k] = D.f32const(0.0)
    dropped = 0
    for n in (k + 1, k - 1, k - nx, k + nx):
        j = min(max(n, 0), ns - 1)  # a read inside the arrays: the guard tests n against the map
        admitted, lost, pending[j] = K.push(D, n, ns, pending[j], costs[j], fill[0], cap)
        if admitted:
            pb[0, fill[0]] = n
            fill[0] += 1
        dropped += lost
    return dropped


@jit_inline
def run_cycles(D, costs, nx, ny, sx, sy, astar, at_start, cycles, budget, wave, trace, counters, memo, watch, newly):
    """The loop of ``propNavFnAstar`` / ``propNavFnDijkstra(cycles, atStart)``, resumable.

    Runs from cycle ``counters[CYCLE]`` (0 after :func:`start_propagation`): each cycle is
    ``updateCell`` (A*: with the heuristic toward NavFn start ``(sx, sy)``) on every cell of
    the current buffer, then the swap (an empty next buffer pulls in the overflow, curT +=
    PRI_INC, float).  Returns True when the loop is over as in C++ (``cycle == cycles``,
    both buffers empty, or with ``at_start`` the start's potential below POT_HIGH), False
    when it paused: after ``budget`` cycles, or at the end of a cycle that ran with watched
    cells in ``newly[:counters[NEWLY]]`` (a cell ``n`` with ``watch[n] >= 0``, ``watch``
    empty: none, that leaves POT_HIGH appends ``watch[n]``).  The state is in ``wave`` and
    ``counters``.  ``trace`` receives the white-box trace while it has room (empty: none).
    """
    pot, pending, pb, fill, role, curt = wave
    ns = nx * ny
    high = D.f32const(POT_HIGH)
    cap = pb.shape[1]
    inc = D.int_to_f32(PRI_INC)
    cur = role[CUR]
    nxt = role[NXT]
    over = role[OVER]
    cur_t = curt[0]
    tcap = trace.shape[0]
    tlen = counters[TRACE_LEN]
    ncyc = counters[CYCLES]
    nupd = counters[UPDATES]
    ndrop = counters[DROPPED]
    nnew = counters[NEWLY]
    watching = watch.shape[0] > 0
    start_cell = sy * nx + sx
    cycle = counters[CYCLE]
    stop = cycle + budget
    finished = False
    while True:
        if not cycle_runs(D, cycle, cycles, fill[cur], fill[nxt]):
            finished = True
            break
        if cycle >= stop:
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
            if not K.is_passable(D, cost):
                continue
            around = update_neighbours(n, nx)
            l = pot[around[0]]
            r = pot[around[1]]
            u = pot[around[2]]
            d = pot[around[3]]
            old = pot[n]
            new, changed = K.cell_update(D, old, l, r, u, d, cost, D.int_to_f32(cost))
            pot[n] = new  # the old potential unless changed: cell_update is the `if (pot < potarr[n])`
            if not changed:
                continue
            if watching and watch[n] >= 0 and not D.lt(old, high):
                newly[nnew] = watch[n]
                nnew += 1
            key = new
            if astar:
                # the heuristic of this offset, remembered (NaN: not yet computed) when the map
                # keeps a memo; written out here, as the pushes below: a helper taking arrays
                # would pay reference-count updates on every call (7x slower in this loop)
                ddx = n % nx - sx
                ddy = n // nx - sy
                if memo.shape[0] == 0:
                    h = K.astar_heuristic(D, ddx, ddy)
                else:
                    mi = (ddy + ny - 1) * (2 * nx - 1) + ddx + nx - 1
                    h = memo[mi]
                    if h != h:
                        h = K.astar_heuristic(D, ddx, ddy)
                        memo[mi] = h
                key = D.add(new, h)
            dest = nxt if K.to_low_buffer(D, key, cur_t) else over
            for j in range(4):  # the four pushes, in updateCell's order (update_neighbours)
                if j == 0:
                    m = around[0]
                    pm = l
                elif j == 1:
                    m = around[1]
                    pm = r
                elif j == 2:
                    m = around[2]
                    pm = u
                else:
                    m = around[3]
                    pm = d
                if K.push_wanted(D, pm, key, K.edge_weight(D, D.int_to_f32(costs[m]))):
                    admitted, lost, pending[m] = K.push(D, m, ns, pending[m], costs[m], fill[dest], cap)
                    if admitted:
                        pb[dest, fill[dest]] = m
                        fill[dest] += 1
                    ndrop += lost
        # swap: the next buffer becomes current; an empty one pulls in the overflow (the
        # kernel gives the fills, the roles follow the C++'s pointer swaps)
        drained, fill_cur, fill_over, cur_t = K.end_of_cycle(D, fill[nxt], fill[over], cur_t, inc)
        t = cur
        cur = nxt
        nxt = t
        if drained:
            t = cur
            cur = over
            over = t
        fill[cur] = fill_cur
        fill[nxt] = 0
        fill[over] = fill_over
        if at_start and call_ends_at_the_start(D, pot[start_cell]):
            finished = True
            break
        cycle += 1
        if nnew > 0:  # a pause at the end of the cycle, for the caller to see the watched cells
            break
    role[CUR] = cur
    role[NXT] = nxt
    role[OVER] = over
    curt[0] = cur_t
    counters[CYCLE] = cycle
    counters[CYCLES] = ncyc
    counters[TRACE_LEN] = tlen
    counters[UPDATES] = nupd
    counters[DROPPED] = ndrop
    counters[NEWLY] = nnew
    return finished


@jit
def propagate(D, costs, nx, ny, sx, sy, gx, gy, astar, cycles, wave, trace, counters, memo):
    """setupNavFn + propNavFn{Astar,Dijkstra}(cycles, atStart=true).

    ``wave.pb`` is a (3, capacity) int array for the three buffers (its width is the capacity
    of each: PRIORITYBUFSIZE as in C++, or what the planner was given); ``trace`` receives the
    white-box trace (stops recording when full; ``counters[TRACE_LEN]`` then exceeds ``len(trace)``).  ``counters``
    has NCOUNTERS entries (CYCLE ... NEWLY); returns start_reached.
    """
    for i in range(counters.shape[0]):
        counters[i] = 0
    counters[DROPPED] = start_propagation(D, costs, nx, ny, gx, gy, wave)
    if astar:
        wave.curt[0] = D.add(K.astar_heuristic(D, gx - sx, gy - sy), wave.curt[0])
    no_watch = wave.pb[0, :0]
    run_cycles(D, costs, nx, ny, sx, sy, astar, True, cycles, cycles, wave, trace, counters, memo, no_watch, no_watch)
    if astar:
        return D.lt(wave.pot[sy * nx + sx], D.f32const(POT_HIGH))
    return counters[CYCLE] < cycles


@jit
def propagate_on(D, costs, nx, ny, sx, sy, gx, gy, astar, cycles, extra, wave, trace, counters, memo):
    """:func:`navfn_smt.spec.planner.calc_navfn` with the further call of the fix of docs/fix.md,
    compiled: :func:`propagate`, then, when its test holds (the start unreached and a buffer holding
    cells: ``spec.fix.calls_again``), ``propNavFn*(extra)`` once (A*: ``curT += dist`` at its entry,
    a cycle count from 0).  Returns what the last call returns and the further calls made (0 or
    1); ``tests/test_fix.py`` holds it equal to the spec."""
    done = propagate(D, costs, nx, ny, sx, sy, gx, gy, astar, cycles, wave, trace, counters, memo)
    pot, fill, role = wave.pot, wave.fill, wave.role
    start_cell = sy * nx + sx
    no_watch = wave.pb[0, :0]
    calls = 0
    if calls_again(D, pot[start_cell], fill[role[CUR]], fill[role[NXT]]):
        if astar:
            wave.curt[0] = D.add(K.astar_heuristic(D, gx - sx, gy - sy), wave.curt[0])
        counters[CYCLE] = 0
        run_cycles(D, costs, nx, ny, sx, sy, astar, True, extra, extra, wave, trace, counters, memo, no_watch, no_watch)
        done = D.lt(pot[start_cell], D.f32const(POT_HIGH)) if astar else counters[CYCLE] < extra
        calls = 1
    return done, calls


@jit
def calc_path_touched(D, pot, nx, ny, sx, sy, gx, gy, nmax, gradx, grady, path, touched):
    """calcPath(nmax); ``path`` is (nmax + 1, 2) float32.  Returns (exit code, npath, ntouched).

    The gradient arrays must be all zero on entry (``setupNavFn`` leaves them so; gradCell's
    cache is a pure function of the potential): no reset here.  Every cell whose gradient is
    written goes to ``touched`` while it has room (4 * nmax entries suffice), so a caller can
    zero just those afterwards.
    """
    ns = nx * ny
    zero = D.f32const(0.0)
    step = D.f32const(PATH_STEP)
    nt = 0
    stc = sy * nx + sx
    dx = zero
    dy = zero
    npath = 0
    for _ in range(nmax):
        code = iteration_test(D, pot, stc, dx, dy, nx, ns)
        if code == EXIT_NEAR_GOAL:
            path[npath, 0], path[npath, 1] = goal_point(D, (gx, gy))
            npath += 1
            return EXIT_NEAR_GOAL, npath, nt
        if code != ITERATION_GOES_ON:  # OUT_OF_BOUNDS, or a ring read outside potarr
            return code, npath, nt
        px, py = K.path_point(D, stc, nx, dx, dy)
        path[npath, 0] = px
        path[npath, 1] = py
        npath += 1
        osc = npath > 2 and oscillates(D, path[npath - 1, 0], path[npath - 1, 1], path[npath - 3, 0], path[npath - 3, 1])
        down = stc + nx
        if follows_the_grid(D, pot, stc, nx, osc):
            stc, dx, dy, stops = grid_step(D, pot, stc, nx)
            if stops:
                return EXIT_HIGH_POTENTIAL, npath, nt
        else:
            for n in (stc, stc + 1, down, down + 1):
                if K.grad_cached(D, gradx[n], grady[n]):
                    continue
                if n < nx or n > ns - nx:
                    continue
                if n + nx >= ns:
                    return EXIT_UB, npath, nt
                gradx[n], grady[n] = K.grad_cell(D, pot[n], pot[n - 1], pot[n + 1], pot[n - nx], pot[n + nx])
                if nt < touched.shape[0]:
                    touched[nt] = n
                    nt += 1
            x = K.interpolate_gradient(D, dx, dy, gradx[stc], gradx[stc + 1], gradx[down], gradx[down + 1])
            y = K.interpolate_gradient(D, dx, dy, grady[stc], grady[stc + 1], grady[down], grady[down + 1])
            if zero_gradient(D, x, y):
                return EXIT_ZERO_GRADIENT, npath, nt
            dx, dy, cdx, cdy = K.step_offsets(D, dx, dy, x, y, step)
            stc += cdx + cdy * nx
    return EXIT_EXHAUSTED, npath, nt


@jit
def calc_path_zeroed(D, pot, nx, ny, sx, sy, gx, gy, nmax, gradx, grady, path):
    """calcPath(nmax) on gradient arrays in any state (zeroed first, O(cells)).  Returns (exit code, npath)."""
    zero = D.f32const(0.0)
    for i in range(nx * ny):
        gradx[i] = zero
        grady[i] = zero
    code, npath, _ = calc_path_touched(D, pot, nx, ny, sx, sy, gx, gy, nmax, gradx, grady, path, np.empty(0, np.int64))
    return code, npath


class JitPlanner:
    """Work arrays for one map size, reused across the cases of a map; ``capacity`` bounds
    each priority buffer (PRIORITYBUFSIZE, as in C++, unless given); ``arith``: the build's
    :class:`~navfn_smt.spec.arithmetic.Arithmetic` it computes in (None: x86-64's), carried to the
    compiled loops as their numeric domain ``D``."""

    def __init__(self, costs_with_border: np.ndarray, capacity: int = PRIORITYBUFSIZE, arith=None):
        self.D = numba_domain(arith)
        c = np.ascontiguousarray(costs_with_border, dtype=np.uint8)
        self.ny, self.nx = c.shape
        self.costs = c.ravel()
        ns = self.nx * self.ny
        self.capacity = int(capacity)
        # the propagation's state (start_propagation); a buffer never holds more than ns cells
        # (pending flags), so a width of ns drops exactly what any larger capacity drops: nothing
        self.wave = Wave(np.empty(ns, np.float32), np.zeros(ns, np.bool_), np.zeros((3, min(self.capacity, ns)), np.int64),
                         np.zeros(3, np.int64), np.zeros(3, np.int64), np.zeros(1, np.float32))
        self.pot = self.wave.pot  # the potentials, as callers read them after a run
        self.gradx = np.zeros(ns, np.float32)
        self.grady = np.zeros(ns, np.float32)
        self.trace = np.empty(max(4 * ns, 1 << 12), np.int32)
        self.no_trace = np.empty(0, np.int32)
        self.counters = np.zeros(NCOUNTERS, np.int64)
        memo = (2 * self.nx - 1) * (2 * self.ny - 1) if ns <= HEURISTIC_MEMO_CELLS else 0
        self.memo = np.full(memo, np.nan, np.float32)
        self.path = np.empty((path_cycle_limit(self.nx) + 1, 2), np.float32)

    def work_arrays(self) -> tuple:
        """What :func:`plan_cases_into` works in, in its argument order (wave to grady)."""
        return (self.wave, self.memo, self.gradx, self.grady)

    def run(self, start, goal, astar: bool, cycles: int, path_cycles: int, record_trace: bool = True,
            further: int = 0):
        """Plan one case; with ``record_trace`` False no trace is kept (memory stays linear
        in the map size: the trace grows with the number of updates).  ``further`` > 0: the
        further call of ``further`` cycles of the fix of docs/fix.md (:func:`propagate_on`);
        ``self.calls`` is then the further calls made."""
        sx, sy = start
        gx, gy = goal
        self.calls = 0
        while True:
            if further:
                reached, self.calls = propagate_on(
                    self.D, self.costs, self.nx, self.ny, sx, sy, gx, gy, astar, cycles, further, self.wave,
                    self.trace if record_trace else self.no_trace, self.counters, self.memo,
                )
            else:
                reached = propagate(
                    self.D, self.costs, self.nx, self.ny, sx, sy, gx, gy, astar, cycles, self.wave,
                    self.trace if record_trace else self.no_trace, self.counters, self.memo,
                )
            if not record_trace or self.counters[TRACE_LEN] <= self.trace.shape[0]:
                break
            self.trace = np.empty(int(self.counters[TRACE_LEN]) * 2, np.int32)
        if self.path.shape[0] < path_cycles + 1:
            self.path = np.empty((path_cycles + 1, 2), np.float32)
        code, npath = calc_path_zeroed(
            self.D, self.pot, self.nx, self.ny, sx, sy, gx, gy, path_cycles, self.gradx, self.grady, self.path
        )
        return bool(reached), int(code), int(npath)


@jit
def plan_cases_into(D, costs, nx, ny, cases, astar, cycles, path_cycles, wave, memo, gradx, grady, reached, start_pot,
                    ncycles, nupdates, ndropped, exits, path_off, path_pts):
    """Plan every case of one map in one call (no trace); results go to the output arrays.

    ``path_pts`` must hold ``len(cases) * (path_cycles + 1)`` points; case ``i``'s path is
    ``path_pts[path_off[i]:path_off[i + 1]]`` (empty unless the exit is NEAR_GOAL).
    """
    no_trace = np.empty(0, np.int32)
    counters = np.zeros(NCOUNTERS, np.int64)
    buf = np.empty((path_cycles + 1, 2), np.float32)
    off = 0
    path_off[0] = 0
    for i in range(cases.shape[0]):
        sx, sy, gx, gy = cases[i, 0], cases[i, 1], cases[i, 2], cases[i, 3]
        reached[i] = propagate(D, costs, nx, ny, sx, sy, gx, gy, astar, cycles, wave, no_trace, counters, memo)
        start_pot[i] = wave.pot[sy * nx + sx]
        ncycles[i] = counters[CYCLES]
        nupdates[i] = counters[UPDATES]
        ndropped[i] = counters[DROPPED]
        code, npath = calc_path_zeroed(D, wave.pot, nx, ny, sx, sy, gx, gy, path_cycles, gradx, grady, buf)
        exits[i] = code
        if code == EXIT_NEAR_GOAL:
            for k in range(npath):
                path_pts[off + k, 0] = buf[k, 0]
                path_pts[off + k, 1] = buf[k, 1]
            off += npath
        path_off[i + 1] = off


def case_columns(n: int, path_cycles: int) -> dict:
    """Zeroed output columns of :func:`plan_cases_into` for ``n`` cases, in its argument order."""
    return {
        "start_reached": np.zeros(n, np.bool_),
        "start_potential": np.zeros(n, np.float32),
        "cycles": np.zeros(n, np.int64),
        "updates": np.zeros(n, np.int64),
        "dropped": np.zeros(n, np.int64),
        "exit": np.zeros(n, np.int64),
        "path_offsets": np.zeros(n + 1, np.int64),
        "path": np.zeros((n * (path_cycles + 1), 2), np.float32),
    }


def run_cases(planner: "JitPlanner", cases: np.ndarray, astar: bool, cycles: int, path_cycles: int) -> dict:
    """Batch form of :meth:`JitPlanner.run` for benchmarks and bulk planning (no traces)."""
    cases = np.ascontiguousarray(cases, dtype=np.int64).reshape(-1, 4)
    out = case_columns(cases.shape[0], path_cycles)
    plan_cases_into(planner.D, planner.costs, planner.nx, planner.ny, cases, astar, cycles, path_cycles, *planner.work_arrays(),
                    *out.values())
    out["path"] = out["path"][: out["path_offsets"][-1]]
    return out
