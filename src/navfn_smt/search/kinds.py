"""The kinds of misbehaviour ``navfn-smt search`` hunts for: a definition, a judge, a screen.

Each :class:`Kind` states its definition precisely (``statement``), judges one concrete run
of the reference spec (``judge(run) -> dict | None``: ``None`` when the run does not show
it, else the detail of what it shows, with a one-line ``reason``), and screens a batch of
cases planned by the JIT (``screen(batch) -> scores``: a score > 0 marks a candidate, the
larger the better for the hunt).  Screens only rank candidates; nothing is reported
unless the judge confirms it on the spec (:mod:`.counterexamples`).

The judges reuse :mod:`navfn_smt.check.properties` where a property says the same thing
(``cost`` is its path-cost gap, ``incomplete`` its ``complete``, ``unreached`` its
``start-reached``).
"""

from __future__ import annotations

import contextlib
import math
from dataclasses import dataclass, field
from typing import Callable, Optional

import numpy as np

from ..check import properties as P
from ..maps.regions import reaches_all, regions
from ..spec import extraction as _extraction
from ..spec import kernels as _kernels
from ..spec.candidates import CellWatch
from ..spec.constants import COST_NEUTRAL, INT_MAX, INT_MIN, POT_HIGH
from ..spec.extraction import ExtractionExit, UndefinedBehaviour, exit_code
from ..spec.planner import path_cycle_limit
from ..spec.propagation import cycle_limit
from . import fast

_HIGH = np.float32(POT_HIGH)


# ---------------------------------------------------------------------------------------
# A batch of cases planned by the JIT on one map
# ---------------------------------------------------------------------------------------
@dataclass
class Batch:
    """One map (with its lethal border), its cases and the columns of ``run_batch``."""

    costs: np.ndarray  # (ny, nx) uint8
    cases: np.ndarray  # (N, 4) int64
    astar: bool
    out: dict
    _cache: dict = field(default_factory=dict)

    @property
    def flat(self) -> np.ndarray:
        return np.ascontiguousarray(self.costs, np.uint8).ravel()

    def gaps(self) -> np.ndarray:
        if "gaps" not in self._cache:
            ny, nx = self.costs.shape
            self._cache["gaps"] = fast.gaps(self.flat, nx, ny, self.out["path"], self.out["path_offsets"])
        return self._cache["gaps"]

    def connected(self) -> np.ndarray:
        if "connected" not in self._cache:
            self._cache["connected"] = reaches_all(regions(self.costs), self.cases)
        return self._cache["connected"]

    def finite(self) -> np.ndarray:
        return self.out["start_potential"] < _HIGH


def plan_batch(costs: np.ndarray, cases, astar: bool, backend: str = "jit", planner=None) -> Batch:
    """Plan ``cases`` (rows ``sx sy gx gy``) on ``costs`` with one backend planning as the
    planner under test ``planner`` (None: NavFn as shipped), as a :class:`Batch`."""
    from ..backends import get_backend

    cases = np.asarray(cases, np.int64).reshape(-1, 4)
    out = get_backend(backend, planner).prepare(costs).run_batch(cases, astar)
    return Batch(np.asarray(costs, np.uint8), cases, astar, out)


# ---------------------------------------------------------------------------------------
# Definitions on one path (the returned path: float32 points, goal point included)
# ---------------------------------------------------------------------------------------
def obtuse_turns(path: np.ndarray) -> list[int]:
    """Indices ``k`` (1 <= k <= M-2) where the path turns back by more than 90 degrees:
    ``(p[k] - p[k-1]) . (p[k+1] - p[k]) < 0``, computed in binary64 from the float32 points
    (a zero step has dot product 0 and is never a turn)."""
    p = np.asarray(path, np.float64).reshape(-1, 2)
    if len(p) < 3:
        return []
    u, v = p[1:-1] - p[:-2], p[2:] - p[1:-1]
    return [int(k) + 1 for k in np.nonzero((u * v).sum(axis=1) < 0.0)[0]]


def turn_angle(path: np.ndarray, k: int) -> float:
    """The turn at point ``k`` in degrees (0 = straight on, 180 = straight back)."""
    p = np.asarray(path, np.float64).reshape(-1, 2)
    u, v = p[k] - p[k - 1], p[k + 1] - p[k]
    return math.degrees(math.atan2(u[0] * v[1] - u[1] * v[0], u @ v)).__abs__()


def oscillation_points(path: np.ndarray) -> list[int]:
    """Indices ``k >= 2`` where point ``k`` equals point ``k-2`` (both float32 coordinates,
    exactly calcPath's own oscillation test, here applied to the returned path)."""
    p = np.asarray(path, np.float32).reshape(-1, 2)
    if len(p) < 3:
        return []
    return [int(k) + 2 for k in np.nonzero((p[2:] == p[:-2]).all(axis=1))[0]]


# ---------------------------------------------------------------------------------------
# int-conversion: calcPath's grid-following fallback on an out-of-range potential
# ---------------------------------------------------------------------------------------
class _ObservedKernels:
    """The spec's kernels, with ``lowest_of_eight`` noting every centre potential it converts.

    ``int minp = potarr[stc]`` is the only float-to-int conversion of the fallback whose
    argument can leave the int32 range: a neighbour replaces ``minp`` only when it is below
    ``(float)minp``, so below 2**31 (and potentials are never negative).  The conversions of
    ``nearest_cell`` take ``roundf`` of offsets within (-1, 1) times ``nx``."""

    def __init__(self):
        self.centres: list[float] = []

    def __getattr__(self, name):
        return getattr(_kernels, name)

    def lowest_of_eight(self, D, centre, neighbours):
        self.centres.append(centre)
        return _kernels.lowest_of_eight(D, centre, neighbours)


@contextlib.contextmanager
def observed_fallback():
    """Run the spec's ``calcPath`` with :class:`_ObservedKernels` (behaviour unchanged)."""
    obs = _ObservedKernels()
    saved = _extraction.K
    _extraction.K = obs
    try:
        yield obs
    finally:
        _extraction.K = saved


def fallback_conversions(r: P.Run) -> list[tuple[int, float]]:
    """``(fallback number, centre potential)`` of every grid-following fallback of ``r``'s
    extraction whose ``int minp = potarr[stc]`` converts a value outside the int32 range
    (undefined behaviour in C++; x86-64 gives INT_MIN).  Replays the spec's ``calcPath`` on
    the run's potential."""
    ny, nx = r.potential.shape
    with observed_fallback() as obs:
        try:
            _extraction.calc_path(r.potential.ravel().tolist(), nx, ny, r.start, r.goal, path_cycle_limit(nx))
        except UndefinedBehaviour:
            pass
    return [(i, float(c)) for i, c in enumerate(obs.centres)
            if not (INT_MIN - 1.0 < float(c) < INT_MAX + 1.0)]


# ---------------------------------------------------------------------------------------
# The judges (on the spec) and screens (on a JIT batch)
# ---------------------------------------------------------------------------------------
def _judge_cost(r: P.Run) -> Optional[dict]:
    g = P.cost_gap(r)
    if g is None or g <= 0:
        return None
    pc = P.path_cost(r.costs, r.path)
    opt = pc - g
    return {"reason": f"the path costs {pc}, the optimum {opt}: gap {g} (ratio {pc / opt:.2f})",
            "gap": g, "path_cost": pc, "optimum": opt, "ratio": round(pc / opt, 4), "points": len(r.path)}


def _judge_incomplete(r: P.Run) -> Optional[dict]:
    why = P.complete(r)
    if why is None:
        return None
    return {"reason": why, "exit": r.exit, "start_potential": float(r.start_potential)}


FAR = 500.0  # far-trap: the least start potential, ten free cells from the goal
TRAP_FLOOR = 4 * COST_NEUTRAL  # far-trap: the gradient stays four free cells or more from the goal


def _judge_far_trap(r: P.Run) -> Optional[dict]:
    if P.complete(r) is None or r.exit != ExtractionExit.EXHAUSTED.value or r.start_potential < FAR:
        return None
    if not (P.passable(r.costs, r.start) and P.passable(r.costs, r.goal)):
        return None
    ny, nx = r.costs.shape
    watch = CellWatch()
    _extraction.calc_path(r.potential.ravel().tolist(), nx, ny, r.start, r.goal, path_cycle_limit(nx), watch=watch)
    pot = r.potential.ravel()
    lowest = float(min(pot[c] for c in watch.cells))
    if lowest < TRAP_FLOOR:
        return None
    loop = sorted(set(watch.cells[len(watch.cells) // 2:]))
    return {"reason": f"the start's potential is {float(r.start_potential):g}, yet following the gradient circles "
            f"cells {loop} (potentials {float(min(pot[loop])):g} to {float(max(pot[loop])):g}) until calcPath's "
            f"{path_cycle_limit(nx)} iterations run out", "start_potential": float(r.start_potential),
            "lowest_potential": lowest, "loop": loop}


def _judge_unreached(r: P.Run) -> Optional[dict]:
    why = P.start_reached(r)
    if why is None:
        return None
    return {"reason": why, "start_potential": float(r.start_potential), "dropped": r.dropped}


def _judge_turn(r: P.Run) -> Optional[dict]:
    ks = obtuse_turns(r.path)
    if not ks:
        return None
    angles = [turn_angle(r.path, k) for k in ks]
    return {"reason": f"{len(ks)} turn(s) back by more than 90 degrees, the first at point {ks[0]} "
            f"({angles[0]:.1f} degrees)", "turns": len(ks), "points": ks, "angles": [round(a, 2) for a in angles],
            "path_points": len(r.path)}


def _judge_oscillation(r: P.Run) -> Optional[dict]:
    ks = oscillation_points(r.path)
    if not ks:
        return None
    return {"reason": f"{len(ks)} path point(s) equal to the point two before, the first at point {ks[0]}",
            "oscillations": len(ks), "points": ks, "path_points": len(r.path)}


def _judge_int_conversion(r: P.Run) -> Optional[dict]:
    conv = fallback_conversions(r)
    if not conv:
        return None
    i, v = conv[0]
    where = "the start is unreached" if not r.start_potential < _HIGH else "mid-path (the start was reached)"
    return {"reason": f"calcPath's fallback converts potential {v:g} to int (outside int32): {where}",
            "value": v, "fallback": i, "start_reached": bool(r.start_potential < _HIGH), "exit": r.exit}


def _judge_path_without_potential(r: P.Run) -> Optional[dict]:
    why = P.no_path_before_start_potential(r)
    if why is None:
        return None
    sx, sy = r.start
    return {"reason": why, "start_potential": float(r.start_potential), "start_cost": int(r.costs[sy, sx]),
            "start_passable": P.passable(r.costs, r.start), "points": len(r.path),
            "first_point": [float(v) for v in r.path[0]]}


def _screen_cost(b: Batch) -> np.ndarray:
    g, _ = b.gaps()
    return np.maximum(g, 0).astype(np.float64)


def _screen_incomplete(b: Batch) -> np.ndarray:
    return (b.finite() & (b.out["exit"] != exit_code(ExtractionExit.NEAR_GOAL))).astype(np.float64)


def _screen_far_trap(b: Batch) -> np.ndarray:
    far = b.finite() & (np.asarray(b.out["start_potential"], np.float32) >= np.float32(FAR))
    ny, nx = b.costs.shape
    cells = b.costs.ravel()
    ends = (cells[b.cases[:, 1] * nx + b.cases[:, 0]] < 254) & (cells[b.cases[:, 3] * nx + b.cases[:, 2]] < 254)
    return (far & ends & (b.out["exit"] == exit_code(ExtractionExit.EXHAUSTED))).astype(np.float64)


def _screen_unreached(b: Batch) -> np.ndarray:
    return (~b.finite() & b.connected()).astype(np.float64)


def _guide_unreached(b: Batch) -> float:
    """How close the map comes to an unreached start: among the connected cases whose start
    was reached, the most cycles propagation needed to reach it, plus the fraction of cases
    that needed that many (a tie-break below one cycle), over the cycle limit; about 1 when a
    start is reached only in the last cycle.

    The screen alone is 0 on every map until the first counterexample, which leaves the climb
    nothing to follow; a start reached only in the last cycles is one delay away from staying
    unreached (the delays come from cells waiting in the overflow buffer, and from cells whose
    pending flag blocks a cheaper push, so that the wave passes a corridor twice)."""
    cycles = np.where(b.connected() & b.finite(), b.out["cycles"], 0)
    if not len(cycles):
        return 0.0
    ny, nx = b.costs.shape
    limit = cycle_limit(nx, ny)
    most = int(cycles.max())
    share = np.count_nonzero(cycles == most) / (len(cycles) + 1)
    return (most + share) / limit


def _screen_path_without_potential(b: Batch) -> np.ndarray:
    return (~b.finite() & (b.out["exit"] == exit_code(ExtractionExit.NEAR_GOAL))).astype(np.float64)


def _screen_turn(b: Batch) -> np.ndarray:
    return fast.turns(b.out["path"], b.out["path_offsets"])[0].astype(np.float64)


def _screen_oscillation(b: Batch) -> np.ndarray:
    return fast.oscillations(b.out["path"], b.out["path_offsets"])[0].astype(np.float64)


def _screen_int_conversion(b: Batch) -> np.ndarray:
    # The fallback meets an unreached centre exactly when calcPath exits on a high potential:
    # a finite centre only moves to a lower, hence reached, neighbour, and a gradient step is
    # taken only when all eight neighbours are reached and moves to one of them, so after the
    # first point stc is always on a reached cell.  A finite potential >= 2**31 would need
    # millions of cells of path: that is the overflow search's ground, not this screen's.
    return (b.out["exit"] == exit_code(ExtractionExit.HIGH_POTENTIAL)).astype(np.float64)


@dataclass(frozen=True)
class Kind:
    name: str
    statement: str
    judge: Callable[[P.Run], Optional[dict]]
    screen: Callable[[Batch], np.ndarray]
    maximise: bool = False  # the hunt keeps improving the score until the time is up
    target: float = 1.0  # without maximise, a screen score at least this ends the hunt
    # a graded score of a whole map below the target (higher: closer), which the climb follows
    # while the screen is still 0; None: the screen alone
    guide: Optional[Callable[[Batch], float]] = None


KINDS = {k.name: k for k in (
    Kind("cost", "the returned path costs more than the optimum: properties.path_cost (costs of the cells "
         "containing the path's points, nearest cell floor(v+0.5), consecutive repeats once) minus "
         "properties.optimal_cost (cheapest 8-connected chain of passable cells between the path's first "
         "and last cells, both counted) is positive; the search maximises it",
         _judge_cost, _screen_cost, maximise=True),
    Kind("incomplete", "the start's potential is finite (< 1e10) but calcPath returns no path "
         "(properties 'complete'); the detail names calcPath's exit",
         _judge_incomplete, _screen_incomplete),
    Kind("far-trap", f"a gradient trap far from the goal (Nav2 #4655's shape): the start's potential is at least "
         f"{FAR:g} and finite, start and goal passable, calcPath runs out of its 4*nx iterations (exit exhausted), and the cells the "
         f"gradient visits all have potentials of at least {TRAP_FLOOR} (so it circles away from the goal's "
         f"neighbourhood, where an inclusive near-goal test could stop it)",
         _judge_far_trap, _screen_far_trap),
    Kind("unreached", "the start is 4-connected to the goal through passable cells (properties.connected) but "
         "its potential is still unreached (1e10) when propagation stops (properties 'start-reached')",
         _judge_unreached, _screen_unreached, guide=_guide_unreached),
    Kind("turn", "the returned path turns back by more than 90 degrees: for some point k (1 <= k <= M-2, "
         "goal point included) (p[k]-p[k-1]) . (p[k+1]-p[k]) < 0, in binary64 from the float32 points",
         _judge_turn, _screen_turn),
    Kind("oscillation", "a point of the returned path equals, in both float32 coordinates, the point two "
         "before it (p[k] == p[k-2], k >= 2)", _judge_oscillation, _screen_oscillation),
    Kind("int-conversion", "calcPath's grid-following fallback (int minp = potarr[stc]) converts a potential "
         "outside the int32 range to int (undefined behaviour in C++); on maps whose potentials stay below "
         "2**31 this happens exactly when the start is unreached (the first fallback converts 1e10)",
         _judge_int_conversion, _screen_int_conversion),
    Kind("path-without-potential", "calcPath returns a path although the start's potential is not finite "
         "(properties 'no-path-before-start-potential'): a lethal start, or one the wave never reached; proved "
         "impossible in x86-64's arithmetic (NoPathWithoutFinitePotential), where (int) of the unreached potential "
         "is INT_MIN; where the conversion saturates (arm64) the fallback can walk from such a start",
         _judge_path_without_potential, _screen_path_without_potential),
)}

SEARCH_KINDS = tuple(KINDS) + ("overflow",)

