"""The climb's mutations and the cost climb's plateau steps, compiled by numba.

The mutations draw from the climb's own ``numpy.random.Generator`` (numba draws the same
stream NumPy does), so a seed gives the same maps whether a step runs here or in Python.
:func:`mutate` and :func:`nudge` are the only statement of the climb's mutations.

:class:`FocusSteps` runs the steps of a ``cost`` climb that do not improve it: a mutant of
the current map, planned on the focus pairs (NavFn as shipped, by the fast backend's
``plan_cases_into``) and scored by ``fast.gaps``, replaces the current map when its gap is equal
and is dropped when it is lower.  It stops before a step that is due to restart and after a
step whose mutant beats the current map; the Python climb (``hunt.Climb``) takes both.
``tests/test_search_small.py`` holds its climbs equal, map for map, to the Python step.
"""

from __future__ import annotations

import numpy as np
from numba import njit

from ..backends.jit import JitPlanner, case_columns, plan_cases_into
from ..backends.jit_state import NX, NY
from ..backends.numba_domain import jit
from ..spec.constants import COST_OBS
from .fast import gaps

FINE = 0.3  # a maximised kind's mutations: share of single small nudges (:func:`nudge`)
_NUDGES = np.array([-3, -2, -1, 1, 2, 3], np.int64)


@njit(cache=True)
def nudge(rng, c, lo, hi):
    """One passable interior cell of ``c`` (in place) moved by 1 to 3 within ``lo..hi``: a
    maximised kind's best maps sit where tiny changes of the float arithmetic decide."""
    h, w = c.shape
    free = 0
    for y in range(1, h - 1):
        for x in range(1, w - 1):
            if c[y, x] < COST_OBS:
                free += 1
    if free == 0:
        return
    k = rng.integers(0, free)
    for y in range(1, h - 1):
        for x in range(1, w - 1):
            if c[y, x] < COST_OBS:
                if k == 0:
                    c[y, x] = min(max(np.int64(c[y, x]) + _NUDGES[rng.integers(0, 6)], lo), hi)
                    return
                k -= 1


@njit(cache=True)
def mutate(rng, c, lo, hi, maximise):
    """A mutation of the interior of ``c`` (in place): a few cells set to random costs or the
    extremes ``lo``/``hi``, obstacles toggled, costs moved by up to 20, cells swapped; for a
    maximised kind a share FINE of the mutations is one :func:`nudge`."""
    h, w = c.shape
    if maximise and rng.random() < FINE:
        nudge(rng, c, lo, hi)
        return
    n = rng.geometric(0.5)
    n += 1 if rng.random() < 0.3 else 0
    for _ in range(n):
        x = rng.integers(1, w - 1)
        y = rng.integers(1, h - 1)
        op = rng.random()
        v = np.int64(c[y, x])
        if op < 0.35:
            v = rng.integers(lo, hi + 1)
        elif op < 0.55:
            v = lo if rng.random() < 0.5 else hi
        elif op < 0.7:
            v = rng.integers(lo, hi + 1) if v >= COST_OBS else COST_OBS
        elif op < 0.9:
            if v < COST_OBS:
                v = min(max(v + rng.integers(-20, 21), lo), hi)
        else:
            x2 = rng.integers(1, w - 1)
            y2 = rng.integers(1, h - 1)
            t = c[y, x]
            c[y, x] = c[y2, x2]
            c[y2, x2] = t
            continue
        c[y, x] = v


@jit  # cached by the sources of the compiled planner it calls
def _best_gap(D, work, trail, cases, astar, cycles, path_cycles, reached, start_pot, ncycles, nupdates, ndropped,
              exits, path_off, path_pts):
    """The cost screen of the map ``work`` plans on (its costs view the candidate) on ``cases``:
    the largest gap (0 when none is positive) and the first case that has it, as ``np.argmax``
    of ``kinds._screen_cost`` picks it."""
    plan_cases_into(D, work, trail, cases, astar, cycles, path_cycles, False, reached, start_pot, ncycles, nupdates,
                    ndropped, exits, path_off, path_pts)
    n = cases.shape[0]
    g, _ = gaps(work.costs, work.ints[NX], work.ints[NY], path_pts[: path_off[n]], path_off[: n + 1])
    best, at = 0, 0
    for i in range(g.shape[0]):
        if g[i] > best:
            best, at = g[i], i
    return float(best), at


@jit
def _focus_steps(D, rng, cur, cur_score, cand, lo, hi, cases, astar, cycles, path_cycles, stale, patience, steps,
                 work, trail, reached, start_pot, ncycles, nupdates, ndropped, exits, path_off, path_pts):
    for k in range(steps):
        if stale > patience:
            return k, stale, -1.0, -1
        cand[:, :] = cur
        mutate(rng, cand, lo, hi, True)
        sc, at = _best_gap(D, work, trail, cases, astar, cycles, path_cycles, reached, start_pot, ncycles, nupdates,
                           ndropped, exits, path_off, path_pts)
        if sc > cur_score:
            return k + 1, stale, sc, at
        if sc == cur_score:
            cur[:, :] = cand
        stale += 1
    return steps, stale, -1.0, -1


class FocusSteps:
    """Work arrays for the compiled plateau steps on maps of one size and one number of focus pairs."""

    def __init__(self, nx: int, ny: int, pairs: int, cycles: int, path_cycles: int):
        self.cycles, self.path_cycles = int(cycles), int(path_cycles)
        self.cand = np.full((ny, nx), COST_OBS, np.uint8)
        planner = JitPlanner(self.cand)  # its costs view the candidate, which the steps change in place
        planner.fit_path(self.path_cycles)
        self.D, self.work = planner.D, (planner.work, planner.trail)
        self.out = tuple(case_columns(pairs, self.path_cycles).values())

    def run(self, rng, cur: np.ndarray, cur_score: float, lo: int, hi: int, cases: np.ndarray, astar: bool,
            stale: int, patience: int, steps: int) -> tuple[int, int, float, int]:
        """Up to ``steps`` steps from ``cur`` (changed in place on a plateau): the steps taken,
        the stale count, and the score and best case of the last mutant (in :attr:`cand`)
        when it beat ``cur_score`` (else ``-1.0, -1``; fewer steps: a restart is due)."""
        taken, stale, sc, at = _focus_steps(self.D, rng, cur, float(cur_score), self.cand, lo, hi, cases, astar, self.cycles,
                                            self.path_cycles, stale, patience, steps, *self.work, *self.out)
        return int(taken), int(stale), float(sc), int(at)
