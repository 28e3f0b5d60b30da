"""Search for the ``overflow`` counterexample: a push dropped by a full priority buffer
changes the path NavFn returns.

NavFn's three priority buffers hold ``PRIORITYBUFSIZE`` = 10,000 cells each and a push to a
full buffer is silently dropped.  A map is a counterexample when the planner with those
buffers returns a path that differs (bit for bit, or in length) from the path of the same
planner given buffers that never drop (:func:`~navfn_smt.spec.propagation.unbounded_capacity`).

How a buffer fills (see ``docs/overflow.md``): an updated cell whose new potential (its key;
plus the heuristic with A*) is at or above the threshold ``curT`` pushes its neighbours onto
the overflow buffer, and that buffer is only taken up when the next buffer runs dry.  While
a network of cheap cells keeps expanding below ``curT``, every dear cell it touches parks
its own neighbours in the overflow buffer, so one buffer can come to hold a large share of
the map.  The families searched here are built for that:

* ``comb`` (NavFn-internal costs 0..253): a cheap spine column with cheap teeth rows,
  the rows between them dear; the goal on the spine;
* ``stripes`` (also in the range ``setCostmap`` produces, 50..253): alternating cheap and
  dear rows;
* ``random``: uniform random costs in the range.

The search measures the largest buffer content of the unbounded run (from the JIT's trace:
every buffer's content is processed as one cycle), estimates the side at which a family
passes the capacity, grows the side until a map changes its path, then shrinks it while
maps (families, other starts, random mutations climbing the largest buffer) still do.
Every reported map is replayed on the reference spec (:func:`replay`) before it is returned.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field
from typing import Callable, Iterator, Optional

import numpy as np

from ..errors import NavfnInputError
from ..maps.suite import MODE_CHOICES, MODES, modes_of
from ..spec.constants import COST_OBS, PRIORITYBUFSIZE
from ..spec.propagation import unbounded_capacity

CAPACITY = PRIORITYBUFSIZE
COST_RANGES = {"internal": (0, 253), "nav2": (50, 253)}  # passable costs a map may use
CALIBRATION_SIDE = {"internal": 100, "nav2": 200}
MIN_SIDE = 12

Progress = Callable[[str], None]


@dataclass
class OverflowCounterexample:
    """A map on which a dropped push changes the path (the ``search`` finding interface)."""

    costs: np.ndarray  # (ny, nx) uint8, NavFn-internal
    start: tuple[int, int]
    goal: tuple[int, int]
    mode: str
    size: tuple[int, int]  # (width, height)
    detail: dict
    seconds: float = 0.0
    evaluations: int = 0
    plans: int = 0
    seed: int = 0
    found_size: tuple[int, int] = ()
    history: list = field(default_factory=list)
    kind: str = "overflow"
    planner: object = None  # the planner under test hunted (None: NavFn as shipped, x86-64's arithmetic)


# ---------------------------------------------------------------------------------------
# Judging one case: bounded (capacity 10,000) against unbounded buffers
# ---------------------------------------------------------------------------------------
def first_difference(a: np.ndarray, b: np.ndarray) -> Optional[int]:
    """Index of the first point where two paths differ (bits, or one ends); None if equal."""
    a = np.ascontiguousarray(a, np.float32).reshape(-1, 2)
    b = np.ascontiguousarray(b, np.float32).reshape(-1, 2)
    for i in range(min(len(a), len(b))):
        if a[i].tobytes() != b[i].tobytes():
            return i
    return None if len(a) == len(b) else min(len(a), len(b))


def _point(path: np.ndarray, i: Optional[int]):
    return None if i is None or i >= len(path) else [float(path[i, 0]), float(path[i, 1])]


def verdict(bounded, unbounded, capacity: int = CAPACITY, both_paths: bool = False) -> Optional[dict]:
    """The detail of a counterexample from two results (``PlanResult`` or ``properties.Run``,
    capacity first), or None when no push was dropped or the paths are the same (or, with
    ``both_paths``, when either planner returned no path)."""
    if bounded.dropped <= 0 or (both_paths and not (len(bounded.path) and len(unbounded.path))):
        return None
    i = first_difference(bounded.path, unbounded.path)
    if i is None:
        return None
    exit_of = lambda r: getattr(r.exit, "value", r.exit)  # noqa: E731
    return {
        "reason": f"{bounded.dropped} pushes dropped by full buffers (capacity {capacity}) change the path "
                  f"from point {i} on ({len(bounded.path)} points against {len(unbounded.path)} unbounded)",
        "capacity": capacity,
        "dropped": int(bounded.dropped),
        "dropped_unbounded": int(unbounded.dropped),
        "path_points": int(len(bounded.path)),
        "path_points_unbounded": int(len(unbounded.path)),
        "first_difference": {"index": i, "bounded": _point(bounded.path, i),
                             "unbounded": _point(unbounded.path, i)},
        "start_potential": float(bounded.start_potential),
        "start_potential_unbounded": float(unbounded.start_potential),
        "exit": exit_of(bounded),
        "exit_unbounded": exit_of(unbounded),
    }


class _Judge:
    """The JIT planners of one map (bounded and unbounded) and the counts of plans made."""

    def __init__(self, costs: np.ndarray, capacity: int = CAPACITY, both_paths: bool = False, planner=None):
        from ..backends import get_backend

        self.both_paths = both_paths
        ny, nx = costs.shape
        self.capacity = capacity
        self.bounded = get_backend("jit", planner).prepare(costs, capacity)
        self.unbounded = get_backend("jit", planner).prepare(costs, unbounded_capacity(nx, ny))
        self.plans = 0

    def largest_buffer(self, start, goal, astar: bool) -> tuple[int, object]:
        """The most cells any buffer held at once in the unbounded run (each buffer's content
        is processed as one cycle of the trace), and that run."""
        from ..spec.extraction import UndefinedBehaviour

        self.plans += 1
        try:
            r = self.unbounded.run(start, goal, astar, trace=True)
        except UndefinedBehaviour:
            return 0, None
        t = r.trace
        i, most = 0, 0
        while i < len(t):
            n = int(t[i])
            most = max(most, n)
            i += 1 + n
        return most, r

    def judge(self, start, goal, astar: bool, unbounded=None) -> tuple[Optional[dict], object]:
        from ..spec.extraction import UndefinedBehaviour

        try:
            self.plans += 1
            b = self.bounded.run(start, goal, astar, trace=False)
            if unbounded is None:
                self.plans += 1
                unbounded = self.unbounded.run(start, goal, astar, trace=False)
        except UndefinedBehaviour:
            return None, None
        return verdict(b, unbounded, self.capacity, self.both_paths), b


def replay(costs: np.ndarray, start, goal, astar: bool, capacity: int = CAPACITY,
           both_paths: bool = False, arith=None) -> Optional[dict]:
    """Replay a case on the reference spec (:func:`navfn_smt.check.properties.run`) with
    ``capacity`` and with unbounded buffers, both in the arithmetic ``arith`` (None: x86-64's):
    the counterexample's detail, or None when the spec does not confirm it."""
    from ..check.properties import run

    costs = np.asarray(costs, np.uint8)
    ny, nx = costs.shape
    t0 = time.perf_counter()
    bounded = run(costs, start, goal, astar, capacity=capacity, arith=arith)
    unbounded = run(costs, start, goal, astar, capacity=unbounded_capacity(nx, ny), arith=arith)
    d = verdict(bounded, unbounded, capacity, both_paths)
    if d is not None:
        d["replay_seconds"] = round(time.perf_counter() - t0, 2)
        d["replayed_on"] = "reference"
    return d


def judge(r, capacity: int = CAPACITY, arith=None) -> Optional[dict]:
    """The ``overflow`` kind's judge of one spec run (a :class:`navfn_smt.check.properties.Run`
    made with the C++ capacity, in the arithmetic ``arith``; None: x86-64's): the same case
    replanned by the spec with unbounded buffers in that arithmetic, and the detail when the run
    dropped pushes and its path differs (else None)."""
    from ..check.properties import run

    ny, nx = r.costs.shape
    unbounded = run(r.costs, r.start, r.goal, r.astar, capacity=unbounded_capacity(nx, ny), arith=arith)
    return verdict(r, unbounded, capacity)


# ---------------------------------------------------------------------------------------
# Map families
# ---------------------------------------------------------------------------------------
@dataclass(frozen=True)
class Candidate:
    family: str
    params: tuple
    costs: np.ndarray = field(compare=False, repr=False)
    start: tuple[int, int] = (0, 0)
    goal: tuple[int, int] = (0, 0)

    def describe(self) -> str:
        return f"{self.family}{self.params}"


def stripes(w: int, h: int, lo: int, hi: int, wl: int = 1, wh: int = 1) -> np.ndarray:
    """Rows of cost ``lo`` (``wl`` high) alternating with rows of cost ``hi`` (``wh`` high)."""
    rows = np.where(np.arange(h) % (wl + wh) < wl, lo, hi).astype(np.uint8)
    return np.repeat(rows[:, None], w, axis=1)


def comb(w: int, h: int, lo: int, hi: int, wl: int = 1, wh: int = 2, spine_x: int = 1) -> np.ndarray:
    """:func:`stripes` joined by a cheap spine column at ``spine_x``: cheap teeth, dear gaps."""
    c = stripes(w, h, lo, hi, wl, wh)
    c[:, spine_x] = lo
    return c


def _placements(w: int, h: int, spine_x: Optional[int] = None) -> dict:
    """Named (start, goal) pairs: goal where propagation begins, start far from it."""
    far_x = w - 2 if (spine_x or 1) < w // 2 else 1
    if spine_x is not None:
        return {"spine-mid/far-corner": ((far_x, h - 2), (spine_x, h // 2)),
                "spine-mid/near-corner": ((far_x, 1), (spine_x, h // 2)),
                "spine-top/far-corner": ((far_x, h - 2), (spine_x, 1))}
    return {"corner": ((w - 2, h - 2), (1, 1)), "corner2": ((1, h - 2), (w - 2, 1)),
            "edge": ((w - 2, h // 2), (1, h // 2)), "centre": ((1, 1), (w // 2, h // 2))}


def family_candidates(w: int, h: int, cost_range: str, rng: np.random.Generator) -> Iterator[Candidate]:
    """The structured maps of one size, most promising first, then a few random ones."""
    lo_cost, hi_cost = COST_RANGES[cost_range]
    if cost_range == "internal":
        for lo in (1, 0):
            for wl, wh in ((1, 2), (1, 1), (1, 3)):
                for sx in (1, w // 2):
                    c = comb(w, h, lo, hi_cost, wl, wh, sx)
                    for name, (s, g) in _placements(w, h, sx).items():
                        yield Candidate("comb", (lo, hi_cost, wl, wh, sx, name), c, s, g)
    for lo in sorted({max(lo_cost, 50), lo_cost}):
        for wl, wh in ((1, 1), (2, 2), (1, 2)):
            c = stripes(w, h, lo, hi_cost, wl, wh)
            for name, (s, g) in _placements(w, h).items():
                yield Candidate("stripes", (lo, hi_cost, wl, wh, name), c, s, g)
    for k in range(3):
        c = rng.integers(max(lo_cost, 50), hi_cost + 1, size=(h, w), dtype=np.uint8)
        for name, (s, g) in list(_placements(w, h).items())[:2]:
            yield Candidate("random", (max(lo_cost, 50), hi_cost, k, name), c, s, g)


# ---------------------------------------------------------------------------------------
# The search
# ---------------------------------------------------------------------------------------
class _Search:
    def __init__(self, astar: bool, cost_range: str, seed: int, deadline: float, say: Progress,
                 both_paths: bool = False, planner=None):
        self.astar = astar
        self.planner = planner
        self.both_paths = both_paths
        self.cost_range = cost_range
        self.rng = np.random.default_rng(seed)
        self.deadline = deadline
        self.say = say
        self.evaluations = 0
        self.plans = 0
        self.history: list = []
        self.palette = np.array([v for v in (0, 1, 2, 5, 20, 50, 100, 150, 200, 230, 252, 253, 254)
                                 if v >= COST_RANGES[cost_range][0]], np.uint8)

    def out_of_time(self, until: Optional[float] = None) -> bool:
        return time.monotonic() >= min(self.deadline, until or self.deadline)

    def evaluate(self, costs, start, goal, judge: Optional[_Judge] = None):
        """(largest buffer, detail or None, judge) of one case."""
        judge = judge or _Judge(costs, both_paths=self.both_paths, planner=self.planner)
        self.evaluations += 1
        before = judge.plans
        most, unb = judge.largest_buffer(start, goal, self.astar)
        detail = None
        if unb is not None and most > CAPACITY:
            detail, _ = judge.judge(start, goal, self.astar, unbounded=unb)
        self.plans += judge.plans - before
        return most, detail, judge

    def other_starts(self, cand: Candidate, judge: _Judge, tries: int = 12) -> Optional[tuple]:
        """Starts among the cells whose potential the drops changed (the goal kept)."""
        before = judge.plans
        _, b = judge.judge(cand.start, cand.goal, self.astar)
        u = judge.unbounded.run(cand.start, cand.goal, self.astar, trace=False)
        judge.plans += 1
        if b is None or b.dropped == 0:
            self.plans += judge.plans - before
            return None
        h, w = cand.costs.shape
        diff = (b.potential != u.potential)
        diff[:2, :] = diff[-2:, :] = diff[:, :2] = diff[:, -2:] = False
        diff &= cand.costs < COST_OBS
        cells = np.argwhere(diff)
        found = None
        for k in self.rng.permutation(len(cells))[:tries]:
            y, x = (int(v) for v in cells[k])
            self.evaluations += 1
            d, _ = judge.judge((x, y), cand.goal, self.astar)
            if d is not None:
                found = (x, y), d
                break
        self.plans += judge.plans - before
        return found

    def try_size(self, w: int, h: int, until: float) -> Optional[tuple[Candidate, dict, int]]:
        """A counterexample of size ``w`` x ``h``: the families first, then other starts on the
        fullest of them, then mutations climbing the largest buffer."""
        scored = []
        for cand in family_candidates(w, h, self.cost_range, self.rng):
            if self.out_of_time(until):
                return None
            most, detail, judge = self.evaluate(cand.costs, cand.start, cand.goal)
            if detail is not None:
                return cand, detail, most
            scored.append((most, len(scored), cand, judge))
        scored.sort(key=lambda s: -s[0])
        for most, _, cand, judge in scored[:4]:
            if most <= CAPACITY or self.out_of_time(until):
                break
            got = self.other_starts(cand, judge)
            if got is not None:
                s, d = got
                return Candidate(cand.family, cand.params + ("start moved",), cand.costs, s, cand.goal), d, most
        if not scored:
            return None
        return self.climb(scored[0][2], scored[0][0], until)

    def climb(self, cand: Candidate, most: int, until: float) -> Optional[tuple[Candidate, dict, int]]:
        """Hill climbing on the largest buffer: rectangles and cells set to a palette cost,
        the start or the goal moved; a map past the capacity is judged (and other starts tried)."""
        h, w = cand.costs.shape
        costs, start, goal = cand.costs.copy(), cand.start, cand.goal
        steps = 0
        while not self.out_of_time(until):
            steps += 1
            c2, s2, g2 = costs.copy(), start, goal
            k = self.rng.integers(5)
            if k <= 1:
                x, y = (int(v) for v in self.rng.integers(1, [w - 1, h - 1]))
                rw, rh = (int(v) for v in self.rng.integers(1, 6, 2)) if k == 0 else (1, 1)
                c2[y:y + rh, x:x + rw] = self.rng.choice(self.palette)
            elif k <= 3:
                s2 = tuple(int(v) for v in self.rng.integers(1, [w - 1, h - 1]))
            else:
                g2 = tuple(int(v) for v in self.rng.integers(1, [w - 1, h - 1]))
            m2, detail, judge = self.evaluate(c2, s2, g2)
            name = cand.params + (f"{steps} mutation steps",)
            if detail is not None:
                return Candidate(cand.family, name, c2, s2, g2), detail, m2
            if m2 >= most:
                costs, start, goal, most = c2, s2, g2, m2
                if m2 > CAPACITY:
                    got = self.other_starts(Candidate(cand.family, name, c2, s2, g2), judge, tries=4)
                    if got is not None:
                        return Candidate(cand.family, name + ("start moved",), c2, got[0], g2), got[1], m2
        return None

    def calibrate(self) -> int:
        """The side at which the fullest family should just pass the capacity (cells in the
        largest buffer grow with the area)."""
        n = CALIBRATION_SIDE[self.cost_range]
        best = 1
        for cand in family_candidates(n, n, self.cost_range, self.rng):
            most, _, _ = self.evaluate(cand.costs, cand.start, cand.goal)
            best = max(best, most)
        side = int(math.ceil(n * math.sqrt(CAPACITY / best)))
        self.say(f"overflow: largest buffer {best} cells at {n}x{n}; estimated side {side}")
        return max(side, MIN_SIDE)


def overflow_modes(mode: str) -> tuple[str, ...]:
    if mode not in MODE_CHOICES:
        raise NavfnInputError(f"unknown mode {mode!r} (choose {', '.join(MODES)} or both)")
    return tuple(reversed(modes_of(mode)))  # both: Dijkstra first, the order of its reports


def _side(v) -> tuple[int, int]:
    if v is None:
        return None
    if isinstance(v, (int, np.integer)):
        return int(v), int(v)
    w, h = (int(x) for x in v)
    return w, h


def search_overflow(mode: str, size=None, max_size=None, timeout: float = 60.0, seed: int = 0,
                    progress: Optional[Progress] = None, cost_range: str = "internal",
                    both_paths: bool = False, verify: bool = True, planner=None) -> list[OverflowCounterexample]:
    """Maps on which a push dropped by a full buffer (capacity 10,000) changes the path.

    ``mode``: ``dijkstra``, ``astar`` or ``both`` (the timeout is split).  With ``size``
    ((w, h) or an int side) only that size is searched; otherwise square sides are grown from
    an estimate until a map is found (up to ``max_size``, a side or (w, h)), then shrunk.
    ``cost_range``: ``internal`` (NavFn's costs 0..253) or ``nav2`` (50..253, what
    ``setCostmap`` produces).  With ``both_paths`` only maps where both planners return a
    path (and the paths differ) count.  The smallest map found per mode is replayed on the reference
    spec (``verify``) and returned; a mode without one is left out.  ``planner``: the planner
    under test whose arithmetic the hunt and the replay plan in (None: NavFn as shipped, x86-64's).
    """
    if cost_range not in COST_RANGES:
        raise NavfnInputError(f"unknown cost range {cost_range!r} (choose {', '.join(COST_RANGES)})")
    if timeout <= 0:
        raise NavfnInputError("timeout must be positive")
    modes = overflow_modes(mode)
    size, max_size = _side(size), _side(max_size)
    say = progress or (lambda line: None)
    results = []
    share = timeout / len(modes)
    for m in modes:
        t0 = time.monotonic()
        s = _Search(m == "astar", cost_range, seed, t0 + share, say, both_paths, planner)
        best = None
        if size is not None:
            got = s.try_size(*size, until=s.deadline)
            if got is not None:
                best = (size, got)
        else:
            cap = max(max_size) if max_size is not None else None
            n = s.calibrate()
            if cap is not None:
                n = min(n, cap)
            # grow until a side gives a counterexample
            while best is None and not s.out_of_time() and (cap is None or n <= cap):
                budget = time.monotonic() + max(2.0, (s.deadline - time.monotonic()) / 4)
                got = s.try_size(n, n, budget)
                s.history.append({"side": n, "found": got is not None, "seconds": round(time.monotonic() - t0, 1)})
                say(f"overflow {m}: {n}x{n} {'found' if got else 'none'} ({time.monotonic() - t0:.0f} s)")
                if got is not None:
                    best = ((n, n), got)
                else:
                    n += max(2, n // 20)
            # shrink while smaller sides still give one: steps doubling after each success,
            # back to one after a failure; a failure at one step ends the search
            step = 1
            while best is not None and not s.out_of_time() and best[0][0] - step >= MIN_SIDE:
                n = best[0][0] - step
                budget = time.monotonic() + max(2.0, (s.deadline - time.monotonic()) / 3)
                got = s.try_size(n, n, budget)
                s.history.append({"side": n, "found": got is not None, "seconds": round(time.monotonic() - t0, 1)})
                say(f"overflow {m}: {n}x{n} {'found' if got else 'none'} ({time.monotonic() - t0:.0f} s)")
                if got is not None:
                    best, step = ((n, n), got), step * 2
                elif step == 1:
                    break
                else:
                    step = 1
        if best is None:
            say(f"overflow {m}: none found ({s.evaluations} maps, {s.plans} plans, "
                f"sides {[h['side'] for h in s.history] or list(size or ())})")
            continue
        (w, h), (cand, detail, most) = best
        seconds = round(time.monotonic() - t0, 2)
        detail = dict(detail, largest_buffer=int(most), family=cand.describe(), cost_range=cost_range,
                      both_paths_required=both_paths, seconds=seconds, mode=m)
        if verify:
            say(f"overflow {m}: replaying {w}x{h} on the reference spec")
            ref = replay(cand.costs, cand.start, cand.goal, m == "astar", both_paths=both_paths,
                         arith=None if planner is None else planner.arithmetic)
            if ref is None:
                raise AssertionError(f"the reference spec does not confirm the JIT's overflow map {cand.describe()}")
            for k in ("dropped", "path_points", "path_points_unbounded", "first_difference"):
                if ref[k] != detail[k]:
                    raise AssertionError(f"reference and JIT disagree on {k}: {ref[k]} != {detail[k]}")
            detail.update(replayed_on="reference", replay_seconds=ref["replay_seconds"])
        results.append(OverflowCounterexample(
            costs=cand.costs, start=cand.start, goal=cand.goal, mode=m, size=(w, h), detail=detail,
            seconds=seconds, evaluations=s.evaluations, plans=s.plans, seed=seed, found_size=(w, h),
            history=s.history, planner=planner))
    return results


# ---------------------------------------------------------------------------------------
# Saving: a suite map directory with the one case, golden files, a picture, the detail
# ---------------------------------------------------------------------------------------
JSON_NAME = "counterexample.json"
PICTURE_NAME = "picture.png"


