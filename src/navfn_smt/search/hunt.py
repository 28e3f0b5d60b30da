"""The hunt: random maps, then hill climbing of costs and obstacles, then shrinking.

Every candidate map is planned for all (or a seeded sample of) start/goal pairs of its
interior cells by the JIT in one ``run_batch`` call and scored by the kind's screen
(:mod:`.kinds`); a kind with a *guide* (``unreached``) is also given a graded score of the
whole map, which the climb follows while the screen is still 0.  The climb keeps a mutated
map when its score is not worse (drifting on plateaus), and restarts when it has not
improved for a while: from a fresh random map, or (``cost``) every other time from a kick
of the best map so far.  ``cost`` plans its mutants on the current map's best 32 pairs only,
and a mutant that beats it there on every pair again: about twice the maps in the same
time.  A kind that is not maximised stops at its first candidate; ``cost`` climbs until the
budget is spent.  The best candidate is then shrunk (rows and columns
dropped, start and goal moved with them, obstacles removed, costs lowered toward the
cheapest) while the screen still shows it (``cost``: while the gap does not fall), and
finally replayed on the reference spec, whose judge gives what is reported.  Nothing the
spec does not confirm is reported.

:func:`hunt_smallest` looks for the smallest map up to a maximum size: one climb per size,
resumed in rounds of doubling evaluation budgets, largest interior first, and every size at
least as large as the smallest counterexample so far dropped.

Seeded: for a given seed and number of evaluations the hunt is deterministic; the time
budget only decides where it stops.
"""

from __future__ import annotations

import functools
import sys
import time
import zlib
from dataclasses import dataclass, field
from typing import Callable, Optional

import numpy as np

from ..check import properties as P
from ..errors import NavfnInputError
from ..spec.arithmetic import X86_64
from ..spec.constants import COST_NEUTRAL, COST_OBS
from ..spec.planner import path_cycle_limit
from ..spec.propagation import cycle_limit
from . import steps
from ..under_test import ORIGINAL, PlannerUnderTest
from .kinds import KINDS, Batch, plan_batch

DEFAULT_COSTS = (COST_NEUTRAL, COST_OBS - 1)  # what setCostmap produces for passable cells
MAX_CASES = 256  # start/goal pairs planned per candidate map (all of them when fewer)
HEARTBEAT = 5.0  # seconds between progress lines when nothing improves
PATIENCE = 400  # evaluations without improvement before a climb restarts
MAXIMISE_PATIENCE = 1500  # the same for a maximised kind: its climbs go deeper
EXTREMES = 0.5  # a maximised kind's restarts: extra share of maps of the cheapest and dearest costs only
KICK = (2, 6)  # a restart from the best map mutates it this many times (at least, at most)
FOCUS = 32  # a maximised kind's mutants are planned on the current map's best start/goal pairs only
CHUNK = 256  # cost: compiled steps between two looks at the clock
FIRST_ROUND = 250  # evaluations per size in the first round of hunt_smallest (doubling per round)


@dataclass
class Finding:
    """A counterexample confirmed on the reference spec."""

    kind: str
    mode: str
    costs: np.ndarray  # (H, W) uint8, lethal border included
    start: tuple[int, int]
    goal: tuple[int, int]
    detail: dict  # the kind's judge on the spec's run
    score: float  # the screen's score (cost: the gap)
    seconds: float  # from the start of the hunt to the first candidate with this score
    evaluations: int  # maps planned until then
    plans: int  # cases planned until then
    found_size: tuple[int, int]  # the map size the hunt found it on (before shrinking)
    seed: int
    history: list = field(default_factory=list)  # (seconds, score) at every improvement
    planner: PlannerUnderTest = ORIGINAL  # the planner hunted: NavFn as shipped, or with the fix

    @property
    def variant(self) -> str:
        return self.planner.variant

    @property
    def size(self) -> tuple[int, int]:
        return int(self.costs.shape[1]), int(self.costs.shape[0])

    @property
    def interior(self) -> int:
        return max(self.size[0] - 2, 0) * max(self.size[1] - 2, 0)

    @property
    def astar(self) -> bool:
        return self.mode == "astar"


def parse_costs(text: Optional[str]) -> tuple[int, int]:
    """``LO..HI`` (passable costs, 0 <= LO <= HI <= 253) or the default 50..253."""
    if not text:
        return DEFAULT_COSTS
    try:
        lo, hi = (int(v) for v in text.split(".."))
    except ValueError:
        raise NavfnInputError(f"--costs {text!r}: expected LO..HI, e.g. 50..253") from None
    if not 0 <= lo <= hi < COST_OBS:
        raise NavfnInputError(f"--costs {text!r}: need 0 <= LO <= HI <= {COST_OBS - 1}")
    return lo, hi


def check_size(w: int, h: int, what: str = "--size") -> None:
    if w < 3 or h < 3:
        raise NavfnInputError(f"{what} {w} {h}: NavFn needs at least 3x3 (the lethal border included)")
    if w * h > 4096:
        raise NavfnInputError(f"{what} {w} {h}: the search is for small maps (at most 4096 cells)")


def _with_border(interior: np.ndarray) -> np.ndarray:
    h, w = interior.shape
    c = np.full((h + 2, w + 2), COST_OBS, np.uint8)
    c[1:-1, 1:-1] = interior
    return c


class _Climber:
    """Scores candidate maps of one size for one kind and mode."""

    def __init__(self, kind: str, astar: bool, size, costs_range, rng: np.random.Generator,
                 planner: PlannerUnderTest = ORIGINAL):
        self.kind, self.astar, self.planner = KINDS[kind], astar, planner
        self.w, self.h = size
        self.lo, self.hi = costs_range
        self.rng = rng
        cells = [(x, y) for y in range(1, self.h - 1) for x in range(1, self.w - 1)]
        self.pairs = np.array([(s[0], s[1], g[0], g[1]) for s in cells for g in cells if s != g],
                              np.int64).reshape(-1, 4)
        self.evaluations = 0
        self.plans = 0

    def random_map(self) -> np.ndarray:
        """A random interior: uniform costs, or (a third of the maps, and for a maximised kind
        another EXTREMES of them) only the cheapest and dearest cost, with some lethal cells."""
        iw, ih = self.w - 2, self.h - 2
        inner = self.rng.integers(self.lo, self.hi + 1, (ih, iw))
        style = self.rng.integers(3)
        if self.kind.maximise and self.rng.random() < EXTREMES:
            style = 1
        if style == 1:  # mostly the extremes
            inner = np.where(self.rng.random((ih, iw)) < 0.5, self.lo, self.hi)
        lethal = self.rng.random((ih, iw)) < self.rng.choice((0.0, 0.1, 0.2, 0.3))
        inner = np.where(lethal, COST_OBS, inner)
        return _with_border(inner.astype(np.uint8))

    def mutate(self, costs: np.ndarray) -> np.ndarray:
        """A mutant of ``costs`` (a copy), by :func:`.steps.mutate`."""
        c = costs.copy()
        steps.mutate(self.rng, c, self.lo, self.hi, self.kind.maximise)
        return c

    def cases(self) -> np.ndarray:
        if len(self.pairs) <= MAX_CASES:
            return self.pairs
        return self.pairs[self.rng.choice(len(self.pairs), MAX_CASES, replace=False)]

    def score(self, costs: np.ndarray, focus: Optional[np.ndarray] = None) -> tuple[float, int, Batch, float]:
        """The best screen score over the candidate's cases (``focus``: those pairs only), which
        case has it, the batch, and the kind's guide of the map (0 without a guide)."""
        b = plan_batch(costs, self.cases() if focus is None else focus, self.astar, planner=self.planner)
        s = self.kind.screen(b)
        self.evaluations += 1
        self.plans += len(b.cases)
        i = int(np.argmax(s)) if len(s) else 0
        sc = float(s[i]) if len(s) else 0.0
        guide = self.kind.guide(b) if self.kind.guide is not None else 0.0
        return sc, i, b, guide


Progress = Callable[[str], None]


def _quiet(line: str) -> None:
    """A progress callback that says nothing."""


class Climb:
    """The climb on one size, resumable: :meth:`advance` evaluates maps until a total number of
    evaluations, the deadline or (a kind that is not maximised) its first candidate."""

    def __init__(self, kind: str, mode: str, size, costs_range, seed: int, planner: PlannerUnderTest, t0: float,
                 compiled: bool = True):
        w, h = size
        astar = mode == "astar"
        rng = np.random.default_rng([seed, zlib.crc32(kind.encode()), int(astar), w, h])
        self.spec = KINDS[kind]
        self.cl = _Climber(kind, astar, (w, h), costs_range, rng, planner)
        self.size, self.t0 = (w, h), t0
        self.tag = f"search {kind} {mode} {w}x{h}"
        self.patience = MAXIMISE_PATIENCE if self.spec.maximise else PATIENCE
        self.cur, self.cur_v, self.stale = None, (0.0, 0.0), 0
        self.focus: Optional[np.ndarray] = None  # a maximised kind: the pairs its mutants are planned on
        self.kicks = 0  # restarts so far (cost: every other one starts from the best map)
        self.best = None  # (score, costs, start, goal, seconds, evaluations, plans)
        self.history: list = []  # (seconds, score) at every improvement
        self.closest = 0.0  # the highest guide seen
        self.seconds = 0.0  # time spent in this climb
        self.compiled = (steps.FocusSteps(w, h, FOCUS, cycle_limit(w, h), path_cycle_limit(w))
                         if compiled and kind == "cost" and planner.fix.shipped
                         and planner.arithmetic == X86_64 else None)  # the compiled steps plan as x86-64 does

    @property
    def evaluations(self) -> int:
        return self.cl.evaluations

    @property
    def done(self) -> bool:
        """A kind that is not maximised is done at its first candidate."""
        return self.best is not None and not self.spec.maximise and self.best[0] >= self.spec.target

    def restart_map(self) -> np.ndarray:
        """A fresh random map; for a maximised kind every other restart kicks the best map
        instead (a few mutations of it), to climb again from near the best basin found."""
        self.kicks += 1
        if self.spec.maximise and self.best is not None and self.kicks % 2 == 0:
            c = self.best[1]
            for _ in range(int(self.cl.rng.integers(KICK[0], KICK[1] + 1))):
                c = self.cl.mutate(c)
            return c
        return self.cl.random_map()

    def step(self) -> bool:
        """Evaluate one map: a restart map first and after ``patience`` evaluations without
        improvement, else a mutant of the current map, kept when (screen, guide) is not worse.
        A maximised kind plans a mutant on the current map's FOCUS best start/goal pairs only,
        and a mutant that beats the current map on them again on every pair (one more
        evaluation), which renews the focus.  True when it raised the best screen score."""
        fresh = self.cur is None or self.stale > self.patience
        cand = self.restart_map() if fresh else self.cl.mutate(self.cur)
        focus = self.focus if self.spec.maximise and not fresh else None
        sc, i, b, guide = self.cl.score(cand, focus)
        return self._take(cand, fresh, focus is None, sc, i, b, guide)

    def _take(self, cand: np.ndarray, fresh: bool, every_pair: bool, sc: float, i: int, b: Optional[Batch],
              guide: float) -> bool:
        """The rest of :meth:`step` once ``cand`` is scored (``every_pair``: ``b`` holds every
        pair, or MAX_CASES of them, not the focus; ``b`` may be None for a focus mutant that
        beats the current map, which is planned again here)."""
        v = (sc, guide)
        if fresh:
            self.stale = 0
        if fresh or v >= self.cur_v:
            if not fresh and v > self.cur_v:
                self.stale = 0
                if not every_pair:
                    sc, i, b, guide = self.cl.score(cand)
                    v, every_pair = (sc, guide), True
            self.cur, self.cur_v = cand, v
            if self.spec.maximise and every_pair:
                self.focus = b.cases[np.argsort(-self.spec.screen(b), kind="stable")[:FOCUS]]
        self.stale += 1
        self.closest = max(self.closest, float(guide))
        if sc > 0 and (self.best is None or sc > self.best[0]):
            t = time.perf_counter() - self.t0
            sx, sy, gx, gy = (int(n) for n in b.cases[i])
            self.best = (sc, cand, (sx, sy), (gx, gy), t, self.evaluations, self.cl.plans)
            self.history.append((round(t, 3), sc))
            return True
        return False

    def next_steps(self, until: int) -> bool:
        """One :meth:`step`, or (``cost`` of NavFn as shipped, between restarts) up to CHUNK
        steps compiled (:class:`.steps.FocusSteps`): the plateau steps there, and the one
        whose mutant beats the current map finished here.  True when the best score rose."""
        if self.compiled is None or self.focus is None or self.stale > self.patience:
            return self.step()
        cur = self.cur.copy()  # changed in place on plateaus; the old map may be the best one
        taken, self.stale, sc, at = self.compiled.run(
            self.cl.rng, cur, self.cur_v[0], self.cl.lo, self.cl.hi, self.focus, self.cl.astar, self.stale,
            self.patience, min(CHUNK, until - self.evaluations))
        self.cur = cur
        self.cl.evaluations += taken
        self.cl.plans += taken * len(self.focus)
        if at < 0:
            return False
        return self._take(self.compiled.cand.copy(), False, False, sc, at, None, 0.0)

    def advance(self, until: int, deadline: float, say: Progress) -> None:
        """Evaluate maps until ``until`` evaluations in all, the deadline, or :attr:`done`;
        a progress line at every improvement and a heartbeat every HEARTBEAT seconds."""
        began = last = time.perf_counter()
        while self.evaluations < until and not self.done:
            now = time.perf_counter()
            if now > deadline:
                break
            if self.next_steps(until):
                say(f"[{self.tag}] {now - self.t0:6.1f}s {self.evaluations} maps {self.cl.plans} plans: "
                    f"score {self.best[0]:g}")
                last = time.perf_counter()
            elif now - last > HEARTBEAT:
                guide = f" (guide {self.closest:.3f})" if self.spec.guide is not None and self.best is None else ""
                say(f"[{self.tag}] {now - self.t0:6.1f}s {self.evaluations} maps {self.cl.plans} plans: "
                    f"best {self.best[0] if self.best else 0:g}{guide}")
                last = now
        self.seconds += time.perf_counter() - began


@functools.cache  # once per process: later hunts find the planner compiled
def _compile(kind: str, mode: str, costs_range, planner: PlannerUnderTest) -> None:
    """A few evaluations of a throwaway climb on a 4x4 map, before a hunt's clock starts: with
    a cold JIT cache (a fresh install, a new version) compiling the planner and the kind's
    steps takes tens of seconds, which would otherwise come out of ``--timeout``."""
    Climb(kind, mode, (4, 4), costs_range, 0, planner, time.perf_counter()).advance(3, float("inf"), _quiet)


def screen_one(kind: str, costs: np.ndarray, start, goal, astar: bool, planner: PlannerUnderTest = ORIGINAL) -> float:
    """The kind's screen score of one case (planned by the JIT)."""
    b = plan_batch(costs, [(start[0], start[1], goal[0], goal[1])], astar, planner=planner)
    return float(KINDS[kind].screen(b)[0])


def _drop(costs, start, goal, axis: int, k: int, shift_start: int, shift_goal: int):
    """Drop interior row (axis 0) or column (axis 1) ``k``; a start or goal on it moves to
    the neighbour on the side ``shift`` (-1 before, 0 after) before the indices close up."""
    c = np.delete(costs, k, axis=axis)
    i = 1 - axis  # coordinate index of a cell (x, y) that runs along this axis

    def move(p, shift):
        p = list(p)
        if p[i] == k:
            p[i] += shift
        elif p[i] > k:
            p[i] -= 1
        return tuple(p)

    return c, move(start, shift_start), move(goal, shift_goal)


def shrink(kind: str, costs: np.ndarray, start, goal, astar: bool, keep_size: bool,
           costs_range=DEFAULT_COSTS, deadline: Optional[float] = None, planner: PlannerUnderTest = ORIGINAL):
    """The smallest, simplest map that still shows ``kind`` (by the screen): rows and columns
    dropped (unless ``keep_size``), then obstacles removed and costs lowered toward the
    cheapest.  ``cost`` keeps its gap at least as large as it was."""
    lo = costs_range[0]
    need = screen_one(kind, costs, start, goal, astar, planner)
    if need <= 0:
        return costs, tuple(start), tuple(goal)
    if not KINDS[kind].maximise:
        need = min(need, KINDS[kind].target)

    def holds(c, s, g) -> bool:
        h, w = c.shape
        if not (1 <= s[0] < w - 1 and 1 <= s[1] < h - 1 and 1 <= g[0] < w - 1 and 1 <= g[1] < h - 1) or s == g:
            return False
        return screen_one(kind, c, s, g, astar, planner) >= need

    def late() -> bool:
        return deadline is not None and time.perf_counter() > deadline

    c, s, g = costs.copy(), tuple(start), tuple(goal)
    changed = True
    while changed and not late():
        changed = False
        if not keep_size:
            for axis in (0, 1):
                k = 1
                while k < c.shape[axis] - 1 and c.shape[axis] > 3 and not late():
                    for ss in (0, -1):
                        for gs in (0, -1):
                            c2, s2, g2 = _drop(c, s, g, axis, k, ss, gs)
                            if holds(c2, s2, g2):
                                c, s, g = c2, s2, g2
                                changed = True
                                break
                        else:
                            continue
                        break
                    else:
                        k += 1
        for y in range(1, c.shape[0] - 1):
            for x in range(1, c.shape[1] - 1):
                if late() or int(c[y, x]) == lo or (x, y) in (s, g):
                    continue
                v = int(c[y, x])
                for nv in (lo, (lo + min(v, COST_OBS - 1)) // 2):
                    if nv >= v:
                        continue
                    c2 = c.copy()
                    c2[y, x] = nv
                    if holds(c2, s, g):
                        c, changed = c2, True
                        break
    return c, s, g


def _check_kind(kind: str) -> None:
    if kind not in KINDS:
        raise NavfnInputError(f"unknown search kind {kind!r} (choose from {', '.join(KINDS)})")


def _confirm(climb: Climb, kind: str, mode: str, seed: int, costs_range, shrink_result: bool, keep_size: bool,
             shrink_seconds: float, planner: PlannerUnderTest, say: Progress) -> Optional[Finding]:
    """The climb's best candidate, shrunk (``shrink_result``) and replayed on the reference spec:
    a :class:`Finding` when the kind's judge confirms it, else None."""
    if climb.best is None:
        return None
    sc, costs, start, goal, t, ev, pl = climb.best
    astar = mode == "astar"
    if shrink_result:
        costs, start, goal = shrink(kind, costs, start, goal, astar, keep_size=keep_size, costs_range=costs_range,
                                    deadline=time.perf_counter() + shrink_seconds, planner=planner)
    r = P.run(costs, start, goal, astar, fix=planner.fix, arith=planner.arithmetic)
    detail = KINDS[kind].judge(r)
    if detail is None:
        say(f"[{climb.tag}] the reference spec does not confirm the candidate; nothing reported")
        return None
    return Finding(kind, mode, costs, start, goal, detail, sc, t, ev, pl, climb.size, seed, list(climb.history),
                   planner)


def hunt(kind: str, mode: str, size, timeout: float, seed: int = 0, costs_range=DEFAULT_COSTS,
         progress: Optional[Progress] = None, shrink_result: bool = True,
         max_evaluations: Optional[int] = None, planner: PlannerUnderTest = ORIGINAL) -> Optional[Finding]:
    """Hunt ``kind`` on maps of ``size`` (W, H, lethal border included) in ``mode`` (of the
    planner ``variant``: ``fixed`` hunts the planner with the fix).

    Returns the best counterexample found, shrunk and confirmed on the spec, or ``None``."""
    _check_kind(kind)
    w, h = size
    check_size(w, h)
    _compile(kind, mode, costs_range, planner)
    t0 = time.perf_counter()
    climb = Climb(kind, mode, (w, h), costs_range, seed, planner, t0)
    say = progress or _quiet
    climb.advance(sys.maxsize if max_evaluations is None else max_evaluations, t0 + timeout, say)
    return _confirm(climb, kind, mode, seed, costs_range, shrink_result, KINDS[kind].maximise,
                    max(5.0, timeout / 4), planner, say)


def interior(size) -> int:
    """Interior cells of a size (W, H) with its lethal border."""
    return max(size[0] - 2, 0) * max(size[1] - 2, 0)


def sizes_upto(max_size) -> list[tuple[int, int]]:
    """Every size up to ``max_size`` with at least two interior cells (a start and a goal),
    smallest interior first (then width, height)."""
    mw, mh = max_size
    out = [(w, h) for w in range(3, mw + 1) for h in range(3, mh + 1) if interior((w, h)) >= 2]
    return sorted(out, key=lambda s: (interior(s), s[0], s[1]))


def _share(size, live: list, maximise: bool) -> float:
    """A size's share of a round's budget: 1 for a maximised kind (every size hunted alike);
    else its interior over the largest live interior, squared: smaller maps, less likely to
    hold the kind, get less, so that the rounds reach the sizes just below the smallest
    counterexample sooner.  (Weighting by the climbs' guides was tried and starved the sizes
    that hold counterexamples in favour of near misses that never become one.)"""
    if maximise:
        return 1.0
    return (interior(size) / max(interior(s) for s in live)) ** 2


def hunt_smallest(kind: str, mode: str, max_size, timeout: float, seed: int = 0, costs_range=DEFAULT_COSTS,
                  progress: Optional[Progress] = None, planner: PlannerUnderTest = ORIGINAL,
                  max_evaluations: Optional[int] = None) -> tuple[Optional[Finding], list[dict]]:
    """The smallest counterexample on sizes up to ``max_size`` (a maximised kind: the largest
    score over those sizes), and what each size tried.

    One climb per size, resumed in rounds: in round ``r`` every live size, largest interior
    first, climbs until it has evaluated ``FIRST_ROUND * 2**r`` maps times its
    :func:`_share`.  A counterexample is shrunk and confirmed on the spec at once; every size
    whose interior is not smaller is then dropped.  The hunt ends when no size is left, the
    time is up or ``max_evaluations`` maps were evaluated in all.  Budgets are counted in
    evaluations, so a seed and ``max_evaluations`` give the same hunt on any machine."""
    _check_kind(kind)
    check_size(*max_size, what="--max-size")
    spec = KINDS[kind]
    say = progress or _quiet
    _compile(kind, mode, costs_range, planner)
    t0 = time.perf_counter()
    deadline = t0 + timeout
    total = sys.maxsize if max_evaluations is None else max_evaluations
    climbs: dict = {}
    best: Optional[Finding] = None
    budget = FIRST_ROUND
    order = sorted(sizes_upto(max_size), key=lambda s: (-interior(s), s[0], s[1]))

    def live() -> list:
        return [s for s in order if spec.maximise or best is None or interior(s) < best.interior]

    def spent() -> int:
        return sum(c.evaluations for c in climbs.values())

    while live() and time.perf_counter() < deadline and spent() < total:
        before = spent()
        for sz in live():
            if sz not in live() or time.perf_counter() > deadline or spent() >= total:
                continue
            c = climbs.get(sz) or climbs.setdefault(sz, Climb(kind, mode, sz, costs_range, seed, planner, t0))
            if c.done:
                continue
            until = max(1, int(budget * _share(sz, live(), spec.maximise)))
            c.advance(min(until, c.evaluations + total - spent()), deadline, say)
            if c.done:
                f = _confirm(c, kind, mode, seed, costs_range, True, False, 5.0, planner, say)
                if f is not None and (best is None or f.interior < best.interior):
                    best = f
        if spent() == before:  # every live size is done (its candidate not confirmed)
            break
        budget *= 2
    if spec.maximise:
        top = max((c for c in climbs.values() if c.best is not None), key=lambda c: c.best[0], default=None)
        if top is not None:
            best = _confirm(top, kind, mode, seed, costs_range, True, True, max(5.0, timeout / 4), planner, say)
    tried = [{"size": list(sz), "interior": interior(sz), "evaluations": c.evaluations,
              "seconds": round(c.seconds, 3), "found": c.best is not None,
              "best": c.best[0] if c.best is not None else None,
              **({"guide": round(float(c.closest), 4)} if spec.guide is not None else {})}
             for sz, c in climbs.items()]
    return best, tried
