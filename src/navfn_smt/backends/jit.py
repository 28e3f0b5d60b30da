"""The fast backend: the spec's planning call, compiled by numba on the state of :mod:`.jit_state`.

Nothing here states the planner.  ``initCost``, ``propNavFn*`` with a fix's further call
(:func:`navfn_smt.spec.planner.call`) and ``calcPath`` (:func:`navfn_smt.spec.extraction.follow`)
are the spec's functions, compiled against the numba domain (:mod:`.numba_domain`) and the
compiled array models (:mod:`.jit_state`); the kernels inside them are
:mod:`navfn_smt.spec.kernels`.  What is written here is the entry points: one case, a batch of
cases of one map, and the work arrays they reuse.  Compiled functions are cached on disk, keyed
by the sources.
"""

from __future__ import annotations

import functools

import numpy as np
from numba import njit

from ..spec import extraction as E
from ..spec import planner as PL
from ..spec import propagation as P
from ..spec.constants import PATH_STEP, PRIORITYBUFSIZE
from ..spec.extraction import EXIT_GRADIENT_UNDEFINED, EXIT_UNDEFINED, ExtractionExit, exit_code
from ..spec.planner import path_cycle_limit
from .jit_state import (CYCLES, DROPPED, NPATH, NTOUCHED, NX, NY, TLEN, UPDATES, TrailWork, Work, cells_of,
                        clear_gradients, new_trail_work, new_work, state_of, trail_of)
from .numba_domain import JIT_OPTIONS, jit, jit_inline, numba_domain

# calcPath's exits as the compiled code returns them (spec.extraction.exit_code)
EXIT_NEAR_GOAL = exit_code(ExtractionExit.NEAR_GOAL)
EXIT_UB = EXIT_UNDEFINED  # either read outside potarr


def no_further_call(D, start_pot, fill_cur, fill_next):
    """NavFn as shipped makes no further call."""
    return False


@functools.lru_cache(maxsize=None)
def compiled_test(test):
    """A fix's further-call test (``FurtherCall.test``, a function over a numeric domain), compiled."""
    return jit_inline(test)


NEVER = compiled_test(no_further_call)


def entry(test):
    """The compiled planning call with the further-call test ``test`` built in, taking the work
    arrays one by one: what Python calls per case.  numba types a function argument (several
    microseconds a call) by the function object, which differs from process to process, so a
    compilation taking one is never found in the disk cache: NavFn as shipped has an entry of its
    own, cached; a fix's further-call test compiles in each process (about 5 s)."""
    return plan_shipped if test is NEVER else _entry(test)


@functools.lru_cache(maxsize=None)
def _entry(test):
    def plan(D, costs, potential, pending, slots, ints, cur_t, trace, memo, watch, newly, sx, sy, gx, gy, astar,
             cycles, further_cycles, record_trace):
        st = state_of(D, Work(costs, potential, pending, slots, ints, cur_t, trace, memo, watch, newly))
        return call_on(st, sx, sy, gx, gy, astar, cycles, test, further_cycles, record_trace)

    return njit(**JIT_OPTIONS)(plan)  # not cached: see entry


@jit_inline
def start_call(st):
    """The counters of a planning call back to zero, no pause pending (``setupNavFn``'s arrays are
    :func:`navfn_smt.spec.propagation.init_cost`'s)."""
    st.cycles = 0
    st.updates = 0
    st.dropped = 0
    st.tlen = 0
    st.nnew = 0
    st.last_n = -1
    st.budget = -1
    st.paused = False


@jit_inline
def call_on(st, sx, sy, gx, gy, astar, cycles, further_test, further_cycles, record_trace):
    """``setupNavFn`` + ``initCost(goal)`` + the planning call with a fix's further call
    (:func:`navfn_smt.spec.planner.call`) on the state ``st``.  Returns (what the last
    ``propNavFn*`` returns, the further calls made)."""
    start_call(st)
    P.init_cost(st, gx + gy * st.nx)
    return PL.call(st, (sx, sy), (gx, gy), astar, cycles, further_test, further_cycles, True, None, record_trace)


@jit
def plan_shipped(D, costs, potential, pending, slots, ints, cur_t, trace, memo, watch, newly, sx, sy, gx, gy, astar,
                 cycles, further_cycles, record_trace):
    """:func:`call_on` a state of these arrays, no further call (NavFn as shipped)."""
    st = state_of(D, Work(costs, potential, pending, slots, ints, cur_t, trace, memo, watch, newly))
    return call_on(st, sx, sy, gx, gy, astar, cycles, NEVER, further_cycles, record_trace)


@jit_inline
def follow_on(D, pot, nx, ny, sx, sy, gx, gy, nmax, trail, tr, inclusive):
    """``calcPath(nmax)`` (:func:`navfn_smt.spec.extraction.follow`) into the trail ``tr`` viewing
    ``trail`` (a :class:`~.jit_state.TrailWork` of ``nmax + 1`` points at least); the gradient
    arrays are left all zero again.  Returns the exit code (:data:`EXIT_UB` for a read outside
    potarr); ``inclusive``: the near-goal test reads ``<=`` (a candidate fix's)."""
    trail.ints[NPATH] = 0
    trail.ints[NTOUCHED] = 0
    code, _ = E.follow(D, cells_of(D, pot), nx, ny, (sx, sy), (gx, gy), nmax, PATH_STEP, tr, inclusive)
    clear_gradients(D, trail)
    if code == EXIT_GRADIENT_UNDEFINED:
        return EXIT_UB
    return code


@jit
def extract_path(D, pot, nx, ny, sx, sy, gx, gy, nmax, trail, inclusive):
    """:func:`follow_on` a trail viewing ``trail``."""
    return follow_on(D, pot, nx, ny, sx, sy, gx, gy, nmax, trail, trail_of(D, trail), inclusive)


@jit
def extract_into(D, pot, nx, ny, sx, sy, gx, gy, nmax, inclusive, path, gradx, grady, touched, ints):
    """:func:`extract_path` with the trail's arrays one by one (as Python calls it: numba types a
    tuple of arrays on every call, at a microsecond)."""
    return extract_path(D, pot, nx, ny, sx, sy, gx, gy, nmax, TrailWork(path, gradx, grady, touched, ints),
                        inclusive)


class JitPlanner:
    """Work arrays for one map size, reused across the cases of a map; ``capacity`` bounds
    each priority buffer (PRIORITYBUFSIZE, as in C++, unless given); ``arith``: the build's
    :class:`~navfn_smt.spec.arithmetic.Arithmetic` it computes in (None: x86-64's), carried to the
    compiled code as its numeric domain ``D``; A*'s heuristic is kept per offset once computed."""

    def __init__(self, costs_with_border: np.ndarray, capacity: int = PRIORITYBUFSIZE, arith=None):
        self.D = numba_domain(arith)
        c = np.ascontiguousarray(costs_with_border, dtype=np.uint8)
        self.ny, self.nx = c.shape
        self.costs = c.ravel()
        ns = self.nx * self.ny
        self.capacity = int(capacity)
        self.work = new_work(self.costs, self.nx, self.ny, self.capacity, np.empty(max(4 * ns, 1 << 12), np.int32),
                             np.full((self.nx + 1) * (self.ny + 1), np.nan, np.float32))
        self.pot = self.work.potential  # the potentials, as callers read them after a run
        self.calls = 0
        self.trail = new_trail_work(ns, path_cycle_limit(self.nx))

    @property
    def trace(self) -> np.ndarray:
        return self.work.trace

    @property
    def path(self) -> np.ndarray:
        """The points of the last calcPath (:meth:`extract`)."""
        return self.trail.path

    def fit_path(self, nmax: int) -> None:
        """A trail for up to ``nmax`` iterations of calcPath."""
        if self.trail.path.shape[0] < nmax + 1:
            self.trail = new_trail_work(self.nx * self.ny, nmax)

    def nbytes(self) -> int:
        """Bytes of the arrays it plans in (the state's, with the trace, and the trail's)."""
        return int(sum(a.nbytes for a in (*self.work, *self.trail)))

    def counts(self) -> tuple[int, int, int, int]:
        """(cycles run, cells updated, pushes dropped, trace entries) of the last planning call."""
        ints = self.work.ints
        return int(ints[CYCLES]), int(ints[UPDATES]), int(ints[DROPPED]), int(ints[TLEN])

    def propagate(self, start, goal, astar: bool, cycles: int, record_trace: bool = True, further=None) -> bool:
        """initCost and the planning call; with ``record_trace`` False no trace is kept (memory stays
        linear in the map size: the trace grows with the number of updates).  ``further``: a fix's
        :class:`~navfn_smt.spec.planner.FurtherCall` (None: none); ``self.calls`` is then the
        further calls made."""
        test = NEVER if further is None else compiled_test(further.test)
        extra = 0 if further is None else further.cycles(self.nx, self.ny)
        while True:
            reached, self.calls = entry(test)(self.D, *self.work, start[0], start[1], goal[0], goal[1], astar, cycles,
                                              extra, record_trace)
            wanted = int(self.work.ints[TLEN])
            if not record_trace or wanted <= self.work.trace.shape[0]:
                return bool(reached)
            self.work = self.work._replace(trace=np.empty(wanted * 2, np.int32))

    def extract(self, start, goal, nmax: int, pot=None, inclusive: bool = False) -> tuple[int, int]:
        """calcPath(nmax) on ``pot`` (default: the state's potentials): (exit code, points in
        :attr:`path`); ``inclusive``: the near-goal test reads ``<=``."""
        self.fit_path(nmax)
        code = extract_into(self.D, self.pot if pot is None else pot, self.nx, self.ny, start[0], start[1], goal[0],
                            goal[1], nmax, inclusive, *self.trail)
        return int(code), int(self.trail.ints[NPATH])


@jit
def plan_cases_into(D, work, trail, cases, astar, cycles, path_cycles, inclusive, reached, start_pot, ncycles, nupdates,
                    ndropped, exits, path_off, path_pts):
    """Plan every case of one map (``work.costs``) in one call, as shipped (no trace); results go
    to the output arrays.  ``trail`` holds ``path_cycles + 1`` points at least; ``path_pts`` must
    hold ``len(cases) * (path_cycles + 1)``; case ``i``'s path is
    ``path_pts[path_off[i]:path_off[i + 1]]`` (empty unless the exit is NEAR_GOAL)."""
    nx = work.ints[NX]
    ny = work.ints[NY]
    st = state_of(D, work)
    tr = trail_of(D, trail)
    off = 0
    path_off[0] = 0
    for i in range(cases.shape[0]):
        sx, sy, gx, gy = cases[i, 0], cases[i, 1], cases[i, 2], cases[i, 3]
        done, _ = call_on(st, sx, sy, gx, gy, astar, cycles, NEVER, 0, False)
        reached[i] = done
        start_pot[i] = work.potential[sy * nx + sx]
        ncycles[i] = work.ints[CYCLES]
        nupdates[i] = work.ints[UPDATES]
        ndropped[i] = work.ints[DROPPED]
        code = follow_on(D, work.potential, nx, ny, sx, sy, gx, gy, path_cycles, trail, tr, inclusive)
        exits[i] = code
        if code == EXIT_NEAR_GOAL:
            npath = trail.ints[NPATH]
            for k in range(npath):
                path_pts[off + k, 0] = trail.path[k, 0]
                path_pts[off + k, 1] = trail.path[k, 1]
            off += npath
        path_off[i + 1] = off


# the scalar output columns of plan_cases_into, one entry a case (backends._SCALARS names them too)
CASE_SCALARS = {"start_reached": np.bool_, "start_potential": np.float32, "cycles": np.int64, "updates": np.int64,
                "dropped": np.int64, "exit": np.int64}


def case_columns(n: int, path_cycles: int) -> dict:
    """Zeroed output columns of :func:`plan_cases_into` for ``n`` cases, in its argument order."""
    return {**{k: np.zeros(n, t) for k, t in CASE_SCALARS.items()}, "path_offsets": np.zeros(n + 1, np.int64),
            "path": np.zeros((n * (path_cycles + 1), 2), np.float32)}


def run_cases(planner: "JitPlanner", cases: np.ndarray, astar: bool, cycles: int, path_cycles: int,
              inclusive: bool = False) -> dict:
    """Plan ``cases`` (rows of sx, sy, gx, gy) on the planner's map in one call, no further call
    nor fallback (no traces; ``inclusive``: calcPath's near-goal test reads ``<=``): the columns
    of :func:`case_columns`, the path cut to its points."""
    cases = np.ascontiguousarray(cases, dtype=np.int64).reshape(-1, 4)
    out = case_columns(cases.shape[0], path_cycles)
    planner.fit_path(path_cycles)
    plan_cases_into(planner.D, planner.work, planner.trail, cases, astar, cycles, path_cycles, inclusive, *out.values())
    out["path"] = out["path"][: out["path_offsets"][-1]]
    return out
