"""The hunt: random maps, then hill climbing of costs and obstacles, then shrinking.

Every candidate map is planned for all (or a seeded sample of) start/goal pairs of its
interior cells by the JIT in one ``run_batch`` call and scored by the kind's screen
(:mod:`.kinds`).  The climb keeps a mutated map when its best score is not worse (drifting
on plateaus), and restarts from a fresh random map when it has not improved for a while.
A kind that is not maximised stops at its first candidate; ``cost`` climbs until the time
is up.  The best candidate is then shrunk (rows and columns dropped, start and goal moved
with them, obstacles removed, costs lowered toward the cheapest) while the screen still
shows it (``cost``: while the gap does not fall), and finally replayed on the reference
spec, whose judge gives what is reported.  Nothing the spec does not confirm is reported.

Seeded: for a given seed and number of evaluations the hunt is deterministic; the time
budget only decides where it stops.
"""

from __future__ import annotations

import time
import zlib
from dataclasses import dataclass, field
from typing import Callable, Optional

import numpy as np

from ..check import properties as P
from ..errors import NavfnInputError
from ..spec.constants import COST_NEUTRAL, COST_OBS
from .kinds import KINDS, Batch, plan_batch

DEFAULT_COSTS = (COST_NEUTRAL, COST_OBS - 1)  # what setCostmap produces for passable cells
MAX_CASES = 256  # start/goal pairs planned per candidate map (all of them when fewer)
HEARTBEAT = 5.0  # seconds between progress lines when nothing improves


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
    variant: str = "original"  # the planner hunted: NavFn as shipped, or with the fix

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
                 variant: str = "original"):
        self.kind, self.astar, self.variant = KINDS[kind], astar, variant
        self.w, self.h = size
        self.lo, self.hi = costs_range
        self.rng = rng
        cells = [(x, y) for y in range(1, self.h - 1) for x in range(1, self.w - 1)]
        self.pairs = np.array([(s[0], s[1], g[0], g[1]) for s in cells for g in cells if s != g],
                              np.int64).reshape(-1, 4)
        self.evaluations = 0
        self.plans = 0

    def random_map(self) -> np.ndarray:
        iw, ih = self.w - 2, self.h - 2
        inner = self.rng.integers(self.lo, self.hi + 1, (ih, iw))
        style = self.rng.integers(3)
        if style == 1:  # mostly the extremes
            inner = np.where(self.rng.random((ih, iw)) < 0.5, self.lo, self.hi)
        lethal = self.rng.random((ih, iw)) < self.rng.choice((0.0, 0.1, 0.2, 0.3))
        inner = np.where(lethal, COST_OBS, inner)
        return _with_border(inner.astype(np.uint8))

    def mutate(self, costs: np.ndarray) -> np.ndarray:
        c = costs.copy()
        rng = self.rng
        for _ in range(int(rng.geometric(0.5)) + int(rng.random() < 0.3)):
            x, y = int(rng.integers(1, self.w - 1)), int(rng.integers(1, self.h - 1))
            op = rng.random()
            v = int(c[y, x])
            if op < 0.35:
                v = int(rng.integers(self.lo, self.hi + 1))
            elif op < 0.55:
                v = self.lo if rng.random() < 0.5 else self.hi
            elif op < 0.7:
                v = int(rng.integers(self.lo, self.hi + 1)) if v >= COST_OBS else COST_OBS
            elif op < 0.9:
                if v < COST_OBS:
                    v = int(np.clip(v + rng.integers(-20, 21), self.lo, self.hi))
            else:
                x2, y2 = int(rng.integers(1, self.w - 1)), int(rng.integers(1, self.h - 1))
                c[y, x], c[y2, x2] = c[y2, x2], c[y, x]
                continue
            c[y, x] = v
        return c

    def cases(self) -> np.ndarray:
        if len(self.pairs) <= MAX_CASES:
            return self.pairs
        return self.pairs[self.rng.choice(len(self.pairs), MAX_CASES, replace=False)]

    def score(self, costs: np.ndarray) -> tuple[float, int, Batch]:
        """The best screen score over the candidate's cases, and which case has it."""
        b = plan_batch(costs, self.cases(), self.astar, variant=self.variant)
        s = self.kind.screen(b)
        self.evaluations += 1
        self.plans += len(b.cases)
        i = int(np.argmax(s)) if len(s) else 0
        return (float(s[i]) if len(s) else 0.0), i, b


def screen_one(kind: str, costs: np.ndarray, start, goal, astar: bool, variant: str = "original") -> float:
    """The kind's screen score of one case (planned by the JIT)."""
    b = plan_batch(costs, [(start[0], start[1], goal[0], goal[1])], astar, variant=variant)
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
           costs_range=DEFAULT_COSTS, deadline: Optional[float] = None, variant: str = "original"):
    """The smallest, simplest map that still shows ``kind`` (by the screen): rows and columns
    dropped (unless ``keep_size``), then obstacles removed and costs lowered toward the
    cheapest.  ``cost`` keeps its gap at least as large as it was."""
    lo = costs_range[0]
    need = screen_one(kind, costs, start, goal, astar, variant)
    if need <= 0:
        return costs, tuple(start), tuple(goal)
    if not KINDS[kind].maximise:
        need = min(need, KINDS[kind].target)

    def holds(c, s, g) -> bool:
        h, w = c.shape
        if not (1 <= s[0] < w - 1 and 1 <= s[1] < h - 1 and 1 <= g[0] < w - 1 and 1 <= g[1] < h - 1) or s == g:
            return False
        return screen_one(kind, c, s, g, astar, variant) >= need

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


Progress = Callable[[str], None]


def hunt(kind: str, mode: str, size, timeout: float, seed: int = 0, costs_range=DEFAULT_COSTS,
         progress: Optional[Progress] = None, shrink_result: bool = True,
         max_evaluations: Optional[int] = None, variant: str = "original") -> Optional[Finding]:
    """Hunt ``kind`` on maps of ``size`` (W, H, lethal border included) in ``mode`` (of the
    planner ``variant``: ``fixed`` hunts the planner with the fix).

    Returns the best counterexample found, shrunk and confirmed on the spec, or ``None``."""
    if kind not in KINDS:
        raise NavfnInputError(f"unknown search kind {kind!r} (choose from {', '.join(KINDS)})")
    w, h = size
    check_size(w, h)
    astar = mode == "astar"
    spec = KINDS[kind]
    rng = np.random.default_rng([seed, zlib.crc32(kind.encode()), int(astar), w, h])
    cl = _Climber(kind, astar, (w, h), costs_range, rng, variant)
    t0 = time.perf_counter()
    deadline = t0 + timeout
    say = progress or (lambda line: None)
    tag = f"search {kind} {mode} {w}x{h}"
    best = None  # (score, costs, start, goal, seconds, evaluations, plans)
    history: list = []
    last_say = t0
    patience = 400
    cur, (cur_s, _, _) = None, (0.0, 0, None)
    stale = 0
    while True:
        now = time.perf_counter()
        if now > deadline or (max_evaluations is not None and cl.evaluations >= max_evaluations):
            break
        if cur is None or stale > patience:
            cand = cl.random_map()
            stale = 0
            fresh = True
        else:
            cand = cl.mutate(cur)
            fresh = False
        sc, i, b = cl.score(cand)
        if fresh or sc >= cur_s:
            if not fresh and sc > cur_s:
                stale = 0
            cur, cur_s = cand, sc
        stale += 1
        if sc > 0 and (best is None or sc > best[0]):
            t = time.perf_counter() - t0
            case = b.cases[i]
            best = (sc, cand, (int(case[0]), int(case[1])), (int(case[2]), int(case[3])), t, cl.evaluations, cl.plans)
            history.append((round(t, 3), sc))
            say(f"[{tag}] {t:6.1f}s {cl.evaluations} maps {cl.plans} plans: score {sc:g}")
            last_say = time.perf_counter()
            if not spec.maximise and sc >= spec.target:
                break
        elif time.perf_counter() - last_say > HEARTBEAT:
            say(f"[{tag}] {time.perf_counter() - t0:6.1f}s {cl.evaluations} maps {cl.plans} plans: "
                f"best {best[0] if best else 0:g}")
            last_say = time.perf_counter()
    if best is None:
        return None
    sc, costs, start, goal, t, ev, pl = best
    if shrink_result:
        costs, start, goal = shrink(kind, costs, start, goal, astar, keep_size=spec.maximise,
                                    costs_range=costs_range, deadline=time.perf_counter() + max(5.0, timeout / 4),
                                    variant=variant)
    r = P.run(costs, start, goal, astar, variant=variant)
    detail = spec.judge(r)
    if detail is None:
        say(f"[{tag}] the reference spec does not confirm the candidate; nothing reported")
        return None
    return Finding(kind, mode, costs, start, goal, detail, sc, t, ev, pl, (w, h), seed, history, variant)


def sizes_upto(max_size) -> list[tuple[int, int]]:
    """Every size up to ``max_size`` with at least two interior cells (a start and a goal),
    smallest interior first (then width, height)."""
    mw, mh = max_size
    out = [(w, h) for w in range(3, mw + 1) for h in range(3, mh + 1) if (w - 2) * (h - 2) >= 2]
    return sorted(out, key=lambda s: ((s[0] - 2) * (s[1] - 2), s[0], s[1]))


def hunt_growing(kind: str, mode: str, max_size, timeout: float, seed: int = 0, costs_range=DEFAULT_COSTS,
                 progress: Optional[Progress] = None, variant: str = "original") -> tuple[Optional[Finding], list[dict]]:
    """Hunt on growing sizes (smallest interior first) up to ``max_size``; the first size with a
    counterexample ends it.  Returns the finding and what each size tried."""
    check_size(*max_size, what="--max-size")
    sizes = sizes_upto(max_size)
    t0 = time.perf_counter()
    tried = []
    for n, sz in enumerate(sizes):
        left = timeout - (time.perf_counter() - t0)
        if left <= 0:
            break
        share = left / (len(sizes) - n)
        ts = time.perf_counter()
        f = hunt(kind, mode, sz, share, seed, costs_range, progress, shrink_result=False, variant=variant)
        tried.append({"size": list(sz), "seconds": round(time.perf_counter() - ts, 3), "found": f is not None})
        if f is not None:
            if KINDS[kind].maximise:
                return f, tried
            c, s, g = shrink(kind, f.costs, f.start, f.goal, f.astar, keep_size=True, costs_range=costs_range,
                             variant=variant)
            r = P.run(c, s, g, f.astar, variant=variant)
            d = KINDS[kind].judge(r)
            if d is not None:
                f.costs, f.start, f.goal, f.detail = c, s, g, d
            return f, tried
    return None, tried
