"""Bounded checks of whole-planner properties over every map of one size.

The discrete choices (which interior cells are lethal, start, goal, mode) are enumerated;
the costs of the passable cells are symbolic, each anywhere in ``lo..hi``.  For one
discrete choice (a :class:`Case`) every control path of the complete run (propagation and
``calcPath``) is found by concolic exploration:

1. run the whole-planner encoding (:mod:`.encoding`) in the concolic domain on concrete
   costs: the run's path condition is the list of branches the cost box leaves open;
2. for every property, decide it on that path: from the intervals when they settle it, else
   by a solver query ``box & path condition & not property``;
3. flip each open branch after the point where this path was found
   (``box & branches[:j] & not branches[j]``); a model is a map that takes another control
   path, which is explored in turn.

Every control path that some map of the box takes diverges from an explored path at a
first branch, and that flip was asked: when every query is decided, the explored paths
cover every map of the case, and a property that held on each is proved for the case.  A
query the solver does not decide makes the case ``unknown``.  A refutation is a concrete
map, replayed on the spec (:mod:`.properties`) before it is reported.
"""

from __future__ import annotations

import itertools
import time
from dataclasses import dataclass, field
from typing import Callable, Optional

import numpy as np
import z3

from ..smt import smtlib, solvers
from ..maps.regions import reaches_all, regions
from ..spec.constants import COST_NEUTRAL, COST_OBS, POT_HIGH
from ..spec.planner import AS_SHIPPED, Fix, path_cycle_limit
from . import properties as P
from . import exhaustive
from .concolic import ConcolicDomain, V, concrete, term  # noqa: F401  (V: named in docstrings)
from ..spec.extraction import exit_code
from .encoding import RUNNING, SymbolicExtraction, extract, interior, propagate

NEAR_GOAL = exit_code(P.ExtractionExit.NEAR_GOAL)
CHECKABLE = tuple(P.PROPERTIES)


@dataclass(frozen=True)
class Case:
    """One discrete choice: the map's size, its lethal interior cells, start, goal and mode."""

    nx: int
    ny: int
    lethal: frozenset
    start: tuple
    goal: tuple
    astar: bool

    @property
    def mode(self) -> str:
        return "astar" if self.astar else "dijkstra"

    def costs_array(self, costs: dict) -> np.ndarray:
        """The (ny, nx) map with the given costs of the passable interior cells."""
        a = np.full((self.ny, self.nx), COST_OBS, np.uint8)
        for k in interior(self.nx, self.ny):
            if k not in self.lethal:
                a.flat[k] = costs[k]
        return a


def cases(nx: int, ny: int, modes, start=None, goal=None, ends: str = "any"):
    """Every layout of the interior (each cell lethal or passable), every start and goal
    (``ends="passable"``: only passable start and goal cells)."""
    inner = interior(nx, ny)
    cells = [(k % nx, k // nx) for k in inner]
    for astar in modes:
        for bits in itertools.product((False, True), repeat=len(inner)):
            lethal = frozenset(k for k, b in zip(inner, bits) if b)
            for s in ([start] if start else cells):
                for g in ([goal] if goal else cells):
                    if ends == "passable" and {s[1] * nx + s[0], g[1] * nx + g[0]} & lethal:
                        continue
                    yield Case(nx, ny, lethal, tuple(s), tuple(g), astar)


# ---------------------------------------------------------------------------------------
# Reductions (ReachedWithinComponent): what lies outside the goal's component never matters
# ---------------------------------------------------------------------------------------
def component(nx: int, ny: int, lethal: frozenset, goal) -> frozenset:
    """The goal's component: the cells the wave from the goal can ever reach
    (:func:`~navfn_smt.maps.regions.reaches`): the goal, and the passable cells 4-connected to a
    passable neighbour of it.  No other cell is ever pushed, updated or reached, and no other
    cost is read but as the guard of a push that fails (a passable cell next to the component
    would be in it)."""
    arr = np.full((ny, nx), COST_OBS, np.uint8)
    inner = interior(nx, ny)
    for k in inner:
        if k not in lethal:
            arr.flat[k] = COST_NEUTRAL
    ok = reaches_all(regions(arr), [(k % nx, k // nx, goal[0], goal[1]) for k in inner])
    return frozenset(k for k, o in zip(inner, ok) if o)


def representative(case: Case, comp: Optional[frozenset] = None) -> Case:
    """The case with every interior cell outside the goal's component made lethal: by
    ReachedWithinComponent it runs exactly as ``case`` does, for a start in the component."""
    nx, ny = case.nx, case.ny
    comp = component(nx, ny, case.lethal, case.goal) if comp is None else comp
    return Case(nx, ny, frozenset(k for k in interior(nx, ny) if k not in comp or k in case.lethal),
                case.start, case.goal, case.astar)


@dataclass
class Reduced:
    """The enumerated cases of a size, reduced: the representatives to explore, with the number
    of enumerated cases each stands for (in order of first appearance), and the number of cases
    whose start lies outside the goal's component (never reached: decided without exploring)."""

    total: int
    representatives: dict  # Case -> enumerated cases it stands for
    outside: int


def reduce_cases(todo, decide_outside: bool = True) -> Reduced:
    """:class:`Reduced` of the enumerated cases ``todo`` (see :func:`representative`); with
    ``decide_outside`` False (an arithmetic where a start never reached may get a path), a
    start outside the goal's component is explored too, by its representative."""
    comps: dict = {}
    reps: dict = {}
    outside = total = 0
    for case in todo:
        total += 1
        key = (case.nx, case.ny, case.lethal, case.goal)
        if key not in comps:
            comps[key] = component(*key)
        comp = comps[key]
        if decide_outside and case.start[1] * case.nx + case.start[0] not in comp:
            outside += 1
            continue
        rep = representative(case, comp)
        reps[rep] = reps.get(rep, 0) + 1
    return Reduced(total, reps, outside)


# ---------------------------------------------------------------------------------------
# The properties on the encoded run
# ---------------------------------------------------------------------------------------
def _reached(D, pot):
    return D.lt(pot, D.f32const(POT_HIGH))


def property_value(name: str, D, case: Case, costs: dict, sp, ex):
    """The property as a condition of the encoded run (a :class:`V` or a plain bool)."""
    nx = case.nx
    sc = case.start[1] * nx + case.start[0]
    start_finite = _reached(D, sp.potential[sc])
    code = concrete(ex.exit)  # path-wise: the exit of this control path
    returned = code == NEAR_GOAL
    if name == "complete":
        return D.or_(D.not_(start_finite), returned)
    if name == "no-path-before-start-potential":
        return D.or_(not returned, start_finite)
    if name == "start-reached":
        arr = case.costs_array({k: 100 for k in costs})
        return D.or_(not P.connected(arr, case.start, case.goal), start_finite)
    if name == "queues-obstacle-free":
        ok = True
        for c in sp.queued:
            ok = D.and_(ok, D.lt(D.cost_int(costs.get(c, COST_OBS)), COST_OBS))
        return ok
    if name == "valid-path":
        if not returned:
            return True
        ok = True
        for x, y in ex.path:
            near_any = False
            for c in range(nx * case.ny):
                cx, cy = c % nx, c // nx
                good = D.and_(D.lt(D.cost_int(costs.get(c, COST_OBS)), COST_OBS), _reached(D, sp.potential[c]))
                inside = D.and_(D.and_(D.ge(x, D.f32const(cx - 0.5)), D.le(x, D.f32const(cx + 0.5))),
                                D.and_(D.ge(y, D.f32const(cy - 0.5)), D.le(y, D.f32const(cy + 0.5))))
                near_any = D.or_(near_any, D.and_(inside, good))
            ok = D.and_(ok, near_any)
        return ok
    raise ValueError(f"unknown property {name!r}")


# ---------------------------------------------------------------------------------------
# Solving
# ---------------------------------------------------------------------------------------
def solve_bitwuzla(assertions: list, variables: dict, timeout: float):
    """``("sat", {cell: cost})``, ``("unsat", None)`` or ``("unknown", reason)`` (a timeout is
    unknown): bitwuzla, and cvc5 on what bitwuzla leaves undecided."""
    q = smtlib.prepare(assertions)
    names = {n: n for n in q.consts}
    reasons = []
    for solver, run in (("bitwuzla", solvers.run_bitwuzla), ("cvc5", solvers.run_cvc5)):
        r = run(q.smt2, timeout, names, q.logic)
        if r["status"] == "sat":
            return "sat", {k: int(r["model"][str(v)]) for k, v in variables.items()}
        if r["status"] == "unsat":
            return "unsat", None
        reasons.append(f"{solver}: {r.get('detail', r['status'])}")
    return "unknown", "; ".join(reasons)


def relevant(conditions: list, variables: dict, ranges: dict, lo: int, hi: int, assumptions: list):
    """The query's box cut down to the costs ``conditions`` mention: ``(box assertions,
    variables, ranges)``.  A cost no condition mentions only has to lie in ``lo..hi``, which it
    can on its own, so leaving it out changes no verdict (its model value is ``lo``), and the
    exhaustive evaluator counts only the points of the costs that matter."""
    from ..smt.codec import free_constants

    used = set(free_constants(conditions + list(assumptions))) if conditions or assumptions else set()
    keep = {k: v for k, v in variables.items() if str(v) in used}
    return ([z3.And(z3.UGE(v, lo), z3.ULE(v, hi)) for v in keep.values()] + list(assumptions), keep,
            {k: ranges[k] for k in keep})


# the least cost a check's box may hold.  With a cost of 0 updateCell computes 0/0 (dc = hf = 0):
# a NaN, which the concolic intervals do not track (their same-term shortcut decides ``x <= x``
# true where a NaN makes it false).  From 1 up, every division of the propagation has a divisor
# of at least 1 and every value is finite (argued in docs/check.md; tests/test_check_certificate.py
# shows the NaN at 0), so the intervals are sound on every box a check accepts
MIN_COST = 1


def check_cost_box(lo: int, hi: int) -> None:
    """A check's cost box ``lo..hi``, refused with a clear error below :data:`MIN_COST`."""
    if lo < MIN_COST:
        from ..errors import NavfnInputError

        raise NavfnInputError(f"--costs {lo}..{hi}: a check needs costs of at least {MIN_COST}: with a cost of 0 "
                              "updateCell divides 0 by 0 (NaN), where the concolic intervals are not sound "
                              "(docs/check.md)")


QUICK = 5.0  # seconds the incremental solver gets per flip before the flip is asked on its own


class PathSolver:
    """The flips of one control path in one bitwuzla instance: the box and every branch of the
    path condition are parsed (and bit-blasted) once, each branch ``j`` named by a Boolean
    ``a_j == branch_j``; flip ``j`` is the check under the assumptions ``a_0 .. a_{j-1}, not a_j``
    (the same query :func:`solve_bitwuzla` asks from scratch, ``box & pc[:j] & not pc[j]``)."""

    def __init__(self, box: list, pc: list, variables: dict, timeout: float):
        import bitwuzla as bw

        self.bw = bw
        names = [z3.Bool(f"navfn_smt!flip{j}") for j in range(len(pc))]
        q = smtlib.prepare(box + [n == b for n, b in zip(names, pc)])
        opts = bw.Options()
        opts.set(bw.Option.PRODUCE_MODELS, True)
        opts.set(bw.Option.PRODUCE_UNSAT_ASSUMPTIONS, True)
        opts.set(bw.Option.TIME_LIMIT_PER, max(1, int(min(timeout, QUICK) * 1000)))
        self.tm = bw.TermManager()
        parser = bw.Parser(self.tm, opts)
        parser.parse(q.smt2, True, False)
        self.solver = parser.bitwuzla()
        funs = {solvers.strip_bars(f.symbol() or ""): f for f in parser.get_declared_funs()}
        self.flags = [funs[str(n)] for n in names]
        self.costs = {k: funs.get(str(v)) for k, v in variables.items()}

    def flip(self, j: int):
        """``("sat", {cell: cost})``, ``("unsat", core)`` or ``("unknown", reason)``; the core is
        the indices of the branches before ``j`` that bitwuzla's unsat assumptions name (with
        ``not branch_j`` they are unsat on the box)."""
        bw = self.bw
        r = self.solver.check_sat(*self.flags[:j], self.tm.mk_term(bw.Kind.NOT, [self.flags[j]]))
        if r == bw.Result.SAT:
            return "sat", {k: int(self.solver.get_value(f).value(2), 2) for k, f in self.costs.items()
                           if f is not None}
        if r == bw.Result.UNSAT:
            used = set(map(str, self.solver.get_unsat_assumptions()))
            return "unsat", [i for i in range(j) if str(self.flags[i]) in used]
        return "unknown", f"bitwuzla (incremental): no answer within {QUICK:g} s"


class UnsatCores:
    """The unsat flips of one case, remembered by their cores.  A flip ``box & pc[:j] & not
    pc[j]`` found unsat with core ``C`` (branches of ``pc[:j]``) proves every flip of the same
    case that negates the same branch term while its prefix holds every branch of ``C``: that
    query implies ``box & C & not pc[j]``.  Terms are z3's hash-consed ASTs, compared by id
    and kept alive here so that no id is reused.  The model constraints of the domain
    (``D.assumptions``) are part of a query: a core counts only on a path whose constraints
    include those it was found under."""

    def __init__(self):
        self.cores: dict = {}  # id of the flipped branch -> [(branch ids, assumption ids)]
        self.alive: list = []

    def path(self, pc: list, assumptions: list) -> "_PathCores":
        return _PathCores(self, pc, assumptions)


class _PathCores:
    def __init__(self, cache: UnsatCores, pc: list, assumptions: list):
        self.cache, self.pc = cache, pc
        self.ids = [t.get_id() for t in pc]
        self.assumed = frozenset(a.get_id() for a in assumptions)
        cache.alive += list(pc) + list(assumptions)

    def implied(self, j: int) -> bool:
        """Whether an earlier core proves flip ``j`` of this path unsat."""
        known = self.cache.cores.get(self.ids[j], ())
        prefix = None
        for core, assumed in known:
            prefix = set(self.ids[:j]) if prefix is None else prefix
            if core <= prefix and assumed <= self.assumed:
                return True
        return False

    def learn(self, j: int, core) -> None:
        """Flip ``j`` is unsat with the branches ``core`` (indices below ``j``)."""
        entry = (frozenset(self.ids[i] for i in core), self.assumed)
        self.cache.cores.setdefault(self.ids[j], []).append(entry)


class Samples:
    """Maps tried on every flip of a path before a solver is asked: a map of the box that takes
    the path's first ``j`` branches and not branch ``j`` is a model of flip ``j`` (the terms
    evaluated exactly, :func:`exhaustive.truths`).  The points are the path's seed changed in
    one or two costs, the seeds of the case's paths, and uniform draws from the box (a fixed
    random stream, so a run is repeatable)."""

    UNIFORM, NEAR = 2048, 2048

    def __init__(self, lo: int, hi: int, seed: int = 0):
        self.lo, self.hi = lo, hi
        self.rng = np.random.default_rng(seed)
        self.seeds: list = []

    def points(self, conc: dict, cells: list) -> np.ndarray:
        base = np.array([conc[k] for k in cells], dtype=np.int64)
        self.seeds.append(base)
        n = len(cells)
        uniform = self.rng.integers(self.lo, self.hi + 1, size=(self.UNIFORM, n))
        near = np.repeat(base[None, :], self.NEAR, axis=0)
        for _ in range(2):
            col = self.rng.integers(0, n, size=self.NEAR)
            near[np.arange(self.NEAR), col] = self.rng.integers(self.lo, self.hi + 1, size=self.NEAR)
        return np.vstack([near, np.array(self.seeds), uniform])


EXHAUSTIVE_LIMIT = 10_000_000  # points of a box worth evaluating one by one (numpy: about a minute)


def solve_split(assertions: list, variables: dict, timeout: float, solve, ranges: dict, depth: int = 2,
                limit: int = EXHAUSTIVE_LIMIT):
    """A box of at most ``limit`` points is decided by evaluating the query at every point
    (:mod:`.exhaustive`, exact); a larger one by ``solve``, and when that does not decide, cut in
    four along its widest cost range, each part solved the same way (``depth`` levels).  Every
    part unsat: unsat; a part sat: its model; otherwise unknown.  The parts cover the box, so this
    is sound."""
    status, model = "unknown", "not asked"
    small = exhaustive.points(ranges, variables, assertions) <= limit
    if small:  # exact, and at most a few seconds: before the solvers' long time limits
        try:
            return exhaustive.solve(assertions, variables, ranges)
        except exhaustive.Unsupported as e:
            model = f"exhaustive: {e}"
    status, model = solve(assertions, variables, timeout)
    if status != "unknown":
        return status, model
    if depth == 0:
        return status, model
    k = max(ranges, key=lambda c: (ranges[c][1] - ranges[c][0], c))
    lo, hi = ranges[k]
    if lo == hi:
        return status, model
    step = -(-(hi - lo + 1) // 4)
    for a in range(lo, hi + 1, step):
        b = min(hi, a + step - 1)
        part = assertions + [z3.UGE(variables[k], a), z3.ULE(variables[k], b)]
        st, m = solve_split(part, variables, timeout, solve, {**ranges, k: (a, b)}, depth - 1, limit)
        if st == "sat":
            return st, m
        if st != "unsat":
            return st, m
    return "unsat", None


@dataclass
class PropertyResult:
    name: str
    status: str = "holds"  # holds | refuted | unknown
    counterexample: Optional[dict] = None  # cell -> cost
    reason: str = ""
    queries: int = 0


@dataclass
class CaseResult:
    case: Case
    results: dict  # name -> PropertyResult
    paths: int = 0
    flip_queries: int = 0
    decided_by_intervals: int = 0
    seconds: float = 0.0
    unknown_flips: list = field(default_factory=list)
    cached_unsat: int = 0  # flips found unsat by an earlier flip's core (UnsatCores), not asked
    sampled_sat: int = 0  # flips found sat at a sampled map (Samples), not asked
    log: list = field(default_factory=list)  # per control path: [seed costs, bound, property marks, flip marks]


# the marks of a certificate (:mod:`.certificate`): how each property was judged on a path,
# and how each flip was answered
HELD_ON_BOX, HELD_BY_QUERY, REFUTED, UNKNOWN = "i", "q", "r", "?"
UNSAT, SAT = "u", "s"


def _symbolic_run(case: Case, conc: dict, lo: int, hi: int, make_domain: Callable, fix: Fix = AS_SHIPPED):
    """The case's run as terms in the concolic domain (``D, costs, propagation, extraction``):
    propagation, then calcPath and the fix's fallback where it returns no path."""
    D, costs, sp, _ = _propagation_run(case, conc, lo, hi, make_domain, fix)
    ex = extract(D, sp.potential, case.nx, case.ny, case.start, case.goal, path_cycle_limit(case.nx), fix)
    return D, costs, sp, ex


# properties whose value on the encoded run reads the propagation only (property_value never
# looks at calcPath's exit or points for them): explored alone, a case's control paths end
# where propagation does, and calcPath's branches (the hardest queries) are never flipped
PROPAGATION_ONLY = frozenset({"start-reached", "queues-obstacle-free"})
NOT_EXTRACTED = SymbolicExtraction(RUNNING, [])  # calcPath not run: no exit, no path


def reads_path(names) -> bool:
    """Whether some property of ``names`` reads calcPath's result."""
    return not set(names) <= PROPAGATION_ONLY


def _propagation_run(case: Case, conc: dict, lo: int, hi: int, make_domain: Callable, fix: Fix = AS_SHIPPED):
    """:func:`_symbolic_run` without calcPath (the same propagation, the same domains): for the
    properties of :data:`PROPAGATION_ONLY`, which judge the potentials and the buffers alone."""
    D = ConcolicDomain(make_domain())
    inner = interior(case.nx, case.ny)
    costs = {k: (COST_OBS if k in case.lethal else D.cost(conc[k], lo, hi, f"c{k}")) for k in inner}
    sp = propagate(D, costs, case.nx, case.ny, case.start, case.goal, case.astar, fix)
    return D, costs, sp, NOT_EXTRACTED


# properties settled on a control path once the start's reach is certain (encoding._Run's mark,
# QueuedStartReached): explored alone, a path's branches after that point are never flipped
SETTLED_BY_REACH = frozenset({"start-reached"})


def flippable(names, pc: list, sp, lo: int) -> int:
    """How many of a path's first branches are flipped: all of them, or for properties of
    :data:`SETTLED_BY_REACH` alone those recorded before the start's reach became certain
    (QueuedStartReached: every path sharing that prefix reaches the start; its lemma needs
    costs from COST_NEUTRAL up, what setCostmap gives)."""
    if sp.start_certain is None or not set(names) <= SETTLED_BY_REACH or lo < COST_NEUTRAL:
        return len(pc)
    return min(len(pc), sp.start_certain)


def run_of(names) -> Callable:
    """The encoded run that judging ``names`` needs: with calcPath when a property reads it."""
    return _symbolic_run if reads_path(names) else _propagation_run


def _ask(conditions: list, variables: dict, ranges: dict, lo: int, hi: int, D, timeout: float, solve,
         limit: int):
    """:func:`solve_split` on the box of the costs the conditions mention (:func:`relevant`);
    a model gives every other cost ``lo``."""
    box, keep, rng = relevant(conditions, variables, ranges, lo, hi, D.assumptions)
    status, model = solve_split(box + conditions, keep, timeout, solve, rng, limit=limit)
    if status == "sat":
        model = {k: model.get(k, lo) for k in variables}
    return status, model


def takes_flip(branches: list, parent: list, j: int) -> bool:
    """Whether a path's branches are its parent's first ``j`` and then branch ``j`` negated: what
    the map found for flip ``j`` (by a solver or a sample) must give, the run being exact."""
    if len(branches) <= j or any(not a.eq(b) for a, b in zip(branches[:j], parent[:j])):
        return False
    a, b = branches[j], parent[j]
    return (z3.is_not(a) and a.arg(0).eq(b)) or (z3.is_not(b) and b.arg(0).eq(a))


def recording(make_domain: Callable) -> Callable:
    """``make_domain`` whose domains have the concolic run keep the branches the box decided
    (:attr:`~.concolic.ConcolicDomain.by_intervals`): what a path's log records, and a replay of
    a certificate that records them asks again."""
    def make():
        S = make_domain()
        S.record_intervals = True
        return S
    return make


def explore(case: Case, names, lo: int, hi: int, make_domain: Callable, timeout: float = 60.0,
            solve=solve_bitwuzla, initial: Optional[dict] = None,
            exhaustive_limit: int = EXHAUSTIVE_LIMIT, fix: Fix = AS_SHIPPED,
            incremental: bool = True, shortcuts: bool = True) -> CaseResult:
    """Every control path of ``case`` over the cost box ``lo..hi``; each property judged on each
    (of the planner with ``fix``).  The run ends with propagation when no
    property reads calcPath's result (:func:`run_of`).  ``incremental``: a path's flips are
    asked of one solver instance (:class:`PathSolver`), what it leaves undecided of ``solve``.
    ``shortcuts``: before a flip is asked, an earlier flip's unsat core (:class:`UnsatCores`)
    or a sampled map (:class:`Samples`, exact evaluation) may decide it; a certificate
    re-checks those answers like any other."""
    check_cost_box(lo, hi)
    t0 = time.perf_counter()
    inner = [k for k in interior(case.nx, case.ny) if k not in case.lethal]
    results = {n: PropertyResult(n) for n in names}
    out = CaseResult(case, results)
    todo = [(initial or {k: lo for k in inner}, 0, None)]
    run = run_of(names)
    make_domain = recording(make_domain)
    cores = UnsatCores()
    sampled = Samples(lo, hi)
    while todo:
        conc, bound, parent = todo.pop()
        D, costs, sp, ex = run(case, conc, lo, hi, make_domain, fix)
        if parent is not None and not takes_flip(D.branches, parent, bound - 1):
            raise RuntimeError(f"{case}: the map {conc} found for flip {bound - 1} does not take that flip")
        out.paths += 1
        variables = {k: costs[k].term for k in inner}
        ranges = {k: (lo, hi) for k in inner}
        box = [z3.And(z3.UGE(v, lo), z3.ULE(v, hi)) for v in variables.values()] + list(D.assumptions)
        pc = D.branches
        marks, flips = "", ""
        for n in names:
            r = results[n]
            if r.status == "refuted":
                marks += REFUTED
                continue
            p = property_value(n, D, case, costs, sp, ex)
            if not concrete(p):
                r.status, r.counterexample = "refuted", dict(conc)
                marks += REFUTED
                continue
            if D.truth(p) is True:
                out.decided_by_intervals += 1
                marks += HELD_ON_BOX
                continue
            r.queries += 1
            status, model = _ask(pc + [z3.Not(term(D, p))], variables, ranges, lo, hi, D, timeout, solve,
                                 exhaustive_limit)
            marks += {"sat": REFUTED, "unsat": HELD_BY_QUERY}.get(status, UNKNOWN)
            if status == "sat":
                r.status, r.counterexample = "refuted", model
            elif status != "unsat" and r.status == "holds":
                r.status, r.reason = "unknown", f"solver: {model}"
        out.log.append([[conc[k] for k in inner], bound, marks, flips,
                        "".join("t" if v else "f" for _, v in D.by_intervals)])
        if all(r.status == "refuted" for r in results.values()):
            break  # nothing left to prove in this case
        last = flippable(names, pc, sp, lo)
        inc = None
        held = cores.path(pc, D.assumptions) if shortcuts else None
        pts = tv = None
        if shortcuts and last > bound and inner and not D.assumptions:
            pts = sampled.points(conc, inner)
            tv = exhaustive.truths(pc[:last], variables, pts)
        for j in range(bound, last):
            out.flip_queries += 1
            if held is not None and held.implied(j):
                out.cached_unsat += 1
                flips += UNSAT
                continue
            hit = None if tv is None else np.flatnonzero(tv[:j].all(axis=0) & ~tv[j])
            if hit is not None and len(hit):
                out.sampled_sat += 1
                flips += SAT
                todo.append(({k: int(c) for k, c in zip(inner, pts[hit[0]])}, j + 1, pc))
                continue
            if inc is None and incremental:
                inc = PathSolver(box, pc[:last], variables, timeout)
            status, model = inc.flip(j) if inc else ("unknown", "")
            if status == "sat":
                model = {k: model.get(k, lo) for k in inner}
            elif status == "unknown":
                status, model = _ask(pc[:j] + [z3.Not(pc[j])], variables, ranges, lo, hi, D, timeout, solve,
                                     exhaustive_limit)
            if status == "unsat" and held is not None:
                held.learn(j, model if isinstance(model, list) else range(j))
            flips += {"sat": SAT, "unsat": UNSAT}.get(status, UNKNOWN)
            if status == "sat":
                todo.append((model, j + 1, pc))
            elif status != "unsat":
                out.unknown_flips.append(j)
                for r in results.values():
                    if r.status == "holds":
                        r.status, r.reason = "unknown", f"a branch the solver did not decide ({model})"
        out.log[-1][3] = flips
    out.seconds = time.perf_counter() - t0
    return out
