"""``navfn-smt check``: a whole-planner property over every map of a size, or up to a size.

For one size the discrete choices are enumerated (:func:`.bounded.cases`: every layout of
lethal interior cells, every start and goal, each mode) and each is explored concolically
over the cost box (:func:`.bounded.explore`).  A property is ``proved`` for the size only
when every case is decided and holds; ``refuted`` when a case yields a map the reference
spec confirms; ``unknown`` otherwise (a solver timeout, never counted as proved).

Inductive properties also get their proof for every size: the obligations of the paper
predicate that carries the induction are checked (:data:`INDUCTION`).
"""

from __future__ import annotations

import math

import time
from dataclasses import dataclass, field, replace
from typing import Callable, Optional

from ..engine import Engine, as_engine, in_order, stream  # noqa: F401  (Engine: named in docstrings)
from ..errors import NavfnInputError
from ..under_test import ORIGINAL, PlannerUnderTest
from .bounded import CHECKABLE, Case, cases, check_cost_box, explore, reduce_cases  # noqa: F401  (CHECKABLE: re-exported)
from .certificate import case_key
from .common import BATCH, PARALLEL_FROM, carried_at, carried_status, outside_decided, replay, symbolic_domain
from .journal import Journal, header

# Properties that hold by induction over the run, and the predicate whose obligations carry it.
INDUCTION = {
    "queues-obstacle-free": ("ObstacleFreeQueue", "PendingMatchesBuffers"),
    "no-path-before-start-potential": ("NoPathWithoutFinitePotential",),
}
# ... and with a fix, those its value names (Fix.proved: with the fix of docs/fix.md, complete
# and start-reached become inductive too)
# ... each under the run-time conditions on its predicates' chains (proofs/__init__.py): said
# with the every-size verdict, which holds only where they do
def conditions(name: str, planner: PlannerUnderTest = ORIGINAL) -> list[str]:
    """The run-time conditions under which an inductive property's every-size verdict holds, in
    the float32 semantics of ``planner``: those on the chains of the predicates that carry it
    (their own and those of the predicates they rest on), each once, as ``name: text``."""
    return chain_conditions(inductive(planner).get(name, ()), planner.fp32_semantics())


def chain_conditions(carriers, semantics: str) -> list[str]:
    """The run-time conditions on the chains of the predicates named ``carriers`` in ``semantics``
    (:func:`~navfn_smt.smt.chains.beneath`), once each, as ``name: text``."""
    from ..proofs import PREDICATES
    from ..smt.chains import beneath

    _, conds = beneath([p for p in PREDICATES if p.name in carriers], semantics, PREDICATES)
    return [f"{c.name}: {c.text}" for c in conds]

# ... and on a narrow size, NavFn as shipped: complete, by FallbackPath (.common.INDUCTION_NARROW,
# carried_at: shared with a certificate's replay)

NOT_INDUCTIVE = {
    "valid-path": "its induction (FinitePotentialPath, ValidPath) has links that are open in float32 "
                  "(see `navfn-smt prove`); and a lethal goal cell breaks it at every size",
    "start-reached": "the cycle limit max(nx*ny/20, nx+ny) cuts long corridors off: refuted at larger sizes",
    "complete": "calcPath's budget of 4*nx iterations runs out on long paths: refuted at larger sizes",
}


@dataclass
class SizeResult:
    size: tuple
    property: str
    status: str  # proved | refuted | unknown
    cases: int = 0
    representatives: int = 0  # cases explored (one per layout of the goal's component, start, goal, mode)
    outside: int = 0  # cases whose start lies outside the goal's component: decided without exploring
    outside_explored: bool = False  # those starts explored instead (outside_decided: not in this arithmetic)
    cases_holding: int = 0
    cases_unknown: int = 0
    paths: int = 0
    queries: int = 0
    decided_by_intervals: int = 0
    flips_by_core: int = 0  # flips found unsat by an earlier flip's unsat core, not asked
    flips_by_sample: int = 0  # flips found sat at a sampled map, not asked
    slowest: list = field(default_factory=list)  # the explored cases that took longest, with their times
    case_seconds: float = 0.0  # the explored cases' own times, summed (those of a journal's cases too)
    from_journal: int = 0  # explored cases whose results a journal held: explored by an earlier, stopped run
    seconds: float = 0.0
    counterexample: Optional[dict] = None
    unknown_cases: list = field(default_factory=list)
    method: str = "exploration"  # or "induction: P (fp32 status)": decided for every map of the size without exploring
    # with a fix: of the explored control paths, those on which its further call ran and those
    # whose path its fallback gave (each path's seed map planned again on the spec)
    fix_paths: Optional[dict] = None


SLOWEST = 10  # explored cases a size's report lists with their times
MAX_CELLS = 12  # interior cells a bounded check enumerates at most


def check_size(nx: int, ny: int) -> None:
    if nx < 3 or ny < 3:
        raise NavfnInputError(f"--size {nx} {ny}: NavFn needs at least 3x3 cells (the border is lethal)")
    if (nx - 2) * (ny - 2) > MAX_CELLS:
        raise NavfnInputError(f"--size {nx} {ny}: {(nx - 2) * (ny - 2)} interior cells; bounded checks enumerate "
                              f"2**cells layouts and cells**2 start/goal pairs (at most {MAX_CELLS} cells)")


@dataclass(frozen=True)
class CheckRequest:
    """What one bounded check asks, made once (by the command line, or a test) and carried to
    every size, every task of a worker and a journal's header: the properties ``names``, the
    ``modes`` (True: A*), the cost box ``lo..hi``, the planner under test, the limit of one query
    (``timeout``, seconds), the ``start`` and ``goal`` cells (None: every interior cell), which
    cells ``ends`` may be (any, or passable only) and the most points a box is evaluated at
    (``exhaustive_limit``)."""

    names: tuple
    modes: tuple = (True, False)
    lo: int = 50
    hi: int = 253
    planner: PlannerUnderTest = ORIGINAL
    timeout: float = 60.0
    start: Optional[tuple] = None
    goal: Optional[tuple] = None
    ends: str = "any"
    exhaustive_limit: int = 10_000_000

    def __post_init__(self):  # tuples and an int, whatever the caller gave
        for name, v in (("names", tuple(self.names)), ("modes", tuple(self.modes)),
                        ("exhaustive_limit", int(self.exhaustive_limit))):
            object.__setattr__(self, name, v)

    def header(self) -> dict:
        """What a certificate's and a journal's header say of the request."""
        return {"costs": [self.lo, self.hi], "modes": ["astar" if m else "dijkstra" for m in self.modes],
                "variant": self.planner.variant, "ends": self.ends}

    def check(self, nx: int, ny: int) -> None:
        """Refuse, naming the problem, what no run of the size could do."""
        check_size(nx, ny)
        symbolic_domain(self.planner.fp32_semantics())
        if not (self.timeout > 0 and math.isfinite(self.timeout)):
            raise NavfnInputError(f"--timeout {self.timeout!r}: must be a positive number of seconds")
        if not self.exhaustive_limit >= 0:
            raise NavfnInputError(f"--exhaustive {self.exhaustive_limit!r}: must be a non-negative number of points")
        for what, cell in (("start", self.start), ("goal", self.goal)):
            if cell is not None and not (1 <= cell[0] <= nx - 2 and 1 <= cell[1] <= ny - 2):
                raise NavfnInputError(f"--{what} {cell[0]} {cell[1]}: not an interior cell of the {nx}x{ny} map "
                                      f"(x in 1..{nx - 2}, y in 1..{ny - 2}; the border is lethal)")
        check_cost_box(self.lo, self.hi)

    def explore(self, case: Case, names) -> object:
        """One case explored for the properties ``names`` (a task's work, here or on a worker)."""
        return explore(case, names, self.lo, self.hi, symbolic_domain(self.planner.fp32_semantics()),
                       timeout=self.timeout, exhaustive_limit=self.exhaustive_limit, fix=self.planner.fix)


def _explore_job(args):
    """The exploration of each case of a batch (a task: run by a worker, or in this process)."""
    batch, names, request = args
    return [request.explore(case, names) for case in batch]


def check_one_size(request: CheckRequest, nx: int, ny: int, jobs=1,
                   progress: Optional[Callable[[int, int, object], None]] = None,
                   certificate: Optional[list] = None, journal=None) -> dict:
    """Every case of the size as ``request.planner`` plans (its fix, in its arithmetic); returns
    ``{property: SizeResult}``, the same wherever the cases run.  ``jobs``: an
    :class:`~navfn_smt.engine.Engine` (``auto`` resolved here by the number of cases), or a
    number of local workers.  One representative per layout of the goal's component is
    explored, and a start outside it decided without exploring (:func:`~.bounded.reduce_cases`,
    by ReachedWithinComponent).
    ``certificate``: a list that gets ``[case key, weight, path log]`` of every explored case,
    in order (:mod:`.certificate`).  ``journal``: a file (:mod:`.journal`) that records each
    explored case as it is decided; the cases it already holds are not explored again."""
    request.check(nx, ny)
    names, planner = request.names, request.planner
    decide_outside = outside_decided(planner)
    red = reduce_cases(cases(nx, ny, request.modes, request.start, request.goal, request.ends), decide_outside)
    carried = carried_at(nx, ny, planner, request.lo, request.hi)
    t0 = time.perf_counter()
    out = {}
    for n in names:  # decided by an induction: not explored
        if n in carried:
            status, why = carried_status(carried[n], planner.fp32_semantics())
            out[n] = SizeResult((nx, ny), n, status, cases=red.total, outside=red.outside,
                                cases_holding=red.total if status == "proved" else 0,
                                cases_unknown=0 if status == "proved" else red.total, method=why,
                                seconds=time.perf_counter() - t0)
    explored = tuple(n for n in names if n not in carried)
    if explored:  # alone, a property of the propagation ends each control path where propagation does
        todo = list(red.representatives)
        got = {n: SizeResult((nx, ny), n, "proved", cases=red.total, representatives=len(todo), outside=red.outside,
                             cases_holding=red.outside, outside_explored=not decide_outside)
               for n in explored}
        eng = as_engine(jobs)
        book = None if journal is None else Journal(journal, header(request, explored, nx, ny))
        done = {} if book is None else book.known(todo)
        fresh = [c for c in todo if c not in done]
        if done and progress:  # resumed: the journal's cases count as arrived
            progress(len(done), len(todo), None)
        work = [(tuple(fresh[k:k + BATCH]), explored, request) for k in range(0, len(fresh), BATCH)]
        try:
            _collect(stream(_explore_job, work, eng.for_work(len(fresh), PARALLEL_FROM)), got, todo, progress,
                     planner, red.representatives, certificate, done, book)
        finally:
            if book is not None:
                book.close()
        for r in got.values():
            r.seconds = time.perf_counter() - t0
            r.from_journal = len(done)
            if r.counterexample is None and r.cases_unknown:
                r.status = "unknown"
        out.update(got)
    return {n: out[n] for n in names}


def _collect(batches, out: dict, todo: list, progress, planner: PlannerUnderTest = ORIGINAL, weight=None,
             certificate: Optional[list] = None, done: Optional[dict] = None, journal=None) -> None:
    """Fold the results of the cases ``todo`` into ``out`` in their order: counts, unknown cases
    and the counterexample (that of the first case refuting a property) are those of a run in
    order.  ``done``: the results already known (a journal's); ``batches``: ``(index, [case
    result, ...])`` of the others, arriving in any order, each recorded in ``journal`` as it
    arrives.  ``progress`` hears of every case as it arrives.  ``weight[case]``: how many
    enumerated cases the explored case stands for."""
    got = dict(done or {})
    count = len(got)

    def arrived(_, results) -> None:
        nonlocal count
        if journal is not None:
            journal.record(results)
        for cr in results:
            count += 1
            if progress:
                progress(count, len(todo), cr)

    for _, results in in_order(batches, arrived):
        for cr in results:
            got[cr.case] = cr
    for case in todo:
        cr = got[case]
        w = 1 if weight is None else weight[cr.case]
        _fold(cr, out, planner, w)
        if certificate is not None:
            certificate.append([case_key(cr.case), w, cr.log])


def fix_branches(cr, planner: PlannerUnderTest) -> dict:
    """Of the explored case ``cr``'s control paths, how many took each branch of ``planner``'s
    fix: each path's seed map (its log's first entry, the passable interior cells' costs) planned
    on the spec, whose fix's parts that acted (:func:`~navfn_smt.spec.planner.acted`) are the
    path's, the branches being the same for every map of the path."""
    from ..spec.planner import plan
    from .encoding import interior

    case = cr.case
    inner = [k for k in interior(case.nx, case.ny) if k not in case.lethal]
    out = {"paths": 0, "further_call": 0, "fallback_path": 0}
    for seed, *_ in cr.log:
        run = plan(case.costs_array(dict(zip(inner, seed))), case.start, case.goal, case.astar, record_trace=False,
                   fix=planner.fix, arith=planner.navfn_arithmetic())
        parts = run.extra.get("fix", [])
        out["paths"] += 1
        out["further_call"] += "propagation" in parts
        out["fallback_path"] += "descent" in parts
    return out


def _fold(cr, out: dict, planner: PlannerUnderTest = ORIGINAL, weight: int = 1) -> None:
    """One explored case's results added to ``out``, counting the ``weight`` enumerated cases it
    stands for (the counterexample replayed on the spec first); with a fix, the control paths
    that took its branches (:func:`fix_branches`)."""
    case = cr.case
    branches = None if planner.fix.shipped else fix_branches(cr, planner)
    for name, pr in cr.results.items():
        r = out[name]
        if branches is not None:
            r.fix_paths = {k: (r.fix_paths or {}).get(k, 0) + v for k, v in branches.items()}
        r.paths += cr.paths
        r.case_seconds += cr.seconds
        r.queries += pr.queries + cr.flip_queries - cr.cached_unsat - cr.sampled_sat
        r.decided_by_intervals += cr.decided_by_intervals
        r.flips_by_core += cr.cached_unsat
        r.flips_by_sample += cr.sampled_sat
        r.slowest = sorted(r.slowest + [_case_json(case) | {"seconds": round(cr.seconds, 2), "paths": cr.paths}],
                           key=lambda c: -c["seconds"])[:SLOWEST]
        if pr.status == "holds":
            r.cases_holding += weight
        elif pr.status == "unknown":
            r.cases_unknown += weight
            r.unknown_cases.append(_case_json(case) | {"reason": pr.reason})
        elif pr.status == "refuted" and r.counterexample is None:
            arr, run, why = replay(case, pr.counterexample, name, planner)
            if why is None:  # the spec does not confirm it: the encoding is wrong, never report it
                raise RuntimeError(f"{name}: the solver's counterexample {_case_json(case)} costs "
                                   f"{pr.counterexample} does not replay on the spec")
            r.status = "refuted"
            r.counterexample = _case_json(case) | {"costs": arr.tolist(), "reason": why, "exit": run.exit,
                                                   "start_potential": float(run.start_potential)}


def _case_json(case: Case) -> dict:
    return {"size": [case.nx, case.ny], "mode": case.mode, "start": list(case.start), "goal": list(case.goal),
            "lethal": sorted([k % case.nx, k // case.nx] for k in case.lethal)}


def sizes_up_to(max_nx: int, max_ny: int, min_nx: int = 3, min_ny: int = 3) -> list[tuple[int, int]]:
    """Sizes from ``min`` up to ``max``, smallest interior first (ties: wider first).

    A side is cut at 15 cells, and a size with more interior cells than :func:`check_size`
    accepts is left out (so ``--max-size 100000 100000`` lists some dozen sizes, not 10**10)."""
    max_nx, max_ny = min(max_nx, 15), min(max_ny, 15)
    out = [(w, h) for w in range(min_nx, max_nx + 1) for h in range(min_ny, max_ny + 1)
           if (w - 2) * (h - 2) <= MAX_CELLS]
    return sorted(out, key=lambda s: ((s[0] - 2) * (s[1] - 2), -s[0], s[1]))


def check_sizes(request: CheckRequest, sizes, jobs, budget: float = 0.0, smallest_only: bool = False,
                progress_of: Callable[[str], Optional[Callable]] = lambda size: None,
                t0: Optional[float] = None, certify: Optional[Callable] = None, journal=None) -> tuple[list, list]:
    """:func:`check_one_size` for each of ``sizes`` in turn until ``budget`` seconds (0: no
    budget) have passed since ``t0``; the results in size order and the sizes not reached.
    With ``smallest_only`` a property refuted at one size is not checked at larger ones (its
    smallest counterexample is found).  ``progress_of("WxH")`` gives each size's progress.
    ``certify(nx, ny, {property: SizeResult}, entries)`` hears of each size where some property
    was proved and none left unknown, with its certificate's entries (:mod:`.certificate`; a
    refuted property's verdict rests on its counterexample, replayed on the spec).  ``journal``:
    the journal file of a single size (:mod:`.journal`)."""
    if journal is not None and len(sizes) != 1:
        raise NavfnInputError("--journal: a journal records the cases of one size (use --size, not --max-size)")
    t0 = time.perf_counter() if t0 is None else t0
    results, skipped = [], []
    open_names = list(request.names)
    for nx, ny in sizes:
        if budget and time.perf_counter() - t0 > budget:
            skipped.append([nx, ny])
            continue
        if not open_names:
            break
        entries = [] if certify else None
        got = check_one_size(replace(request, names=tuple(open_names)), nx, ny, jobs,
                             progress=progress_of(f"{nx}x{ny}"), certificate=entries, journal=journal)
        if certify and all(r.status in ("proved", "refuted") for r in got.values()) and any(
                r.status == "proved" for r in got.values()) and any(r.method == "exploration" for r in got.values()):
            certify(nx, ny, got, entries)
        for n in list(open_names):
            results.append(got[n])
            if got[n].status == "refuted" and smallest_only:
                open_names.remove(n)
    return results, skipped


def proved_sizes(results, name: str) -> list:
    """The sizes at which ``name`` was proved, as [W, H] lists."""
    return [list(r.size) for r in results if r.property == name and r.status == "proved"]


def largest_proved(results, name: str) -> Optional[list]:
    """The proved size of ``name`` with the most interior cells (ties: the larger), or None."""
    proved = [r.size for r in results if r.property == name and r.status == "proved"]
    return list(max(proved, key=lambda s: ((s[0] - 2) * (s[1] - 2), s))) if proved else None


def smallest_counterexample(results, name: str) -> Optional[dict]:
    """The counterexample of ``name`` at the first size that has one (sizes run smallest
    interior first), or None."""
    return next((r.counterexample for r in results if r.property == name and r.counterexample), None)


def inductive(planner: PlannerUnderTest = ORIGINAL) -> dict:
    """The properties proved for every map size, and the predicates that carry them."""
    return {**INDUCTION, **dict(planner.fix.proved)}


def induction_status(name: str, verdict_of, planner: PlannerUnderTest = ORIGINAL) -> str:
    """The every-size status of an inductive property: the worst status, in the float32 semantics
    of ``planner``'s arithmetic, of the predicates that carry it (:func:`~navfn_smt.smt.chains.derive`,
    from ``verdict_of``), qualified by every trusted step and run-time condition on their chains
    (:func:`~navfn_smt.smt.chains.combined`): ``{"status", "rank", "trusted", "conditions"}``,
    the one status ``check``, ``prove`` and the invariants page give those predicates."""
    from ..proofs import PREDICATES
    from ..smt.chains import combined, derive

    carriers = inductive(planner)[name]
    semantics = planner.fp32_semantics()
    return combined([derive(p, semantics, verdict_of, PREDICATES) for p in PREDICATES if p.name in carriers])


def induction(name: str, timeout: float = 30.0, planner: PlannerUnderTest = ORIGINAL) -> Optional[dict]:
    """The every-size proof of an inductive property: its predicates' obligations checked in
    the float32 semantics of ``planner``'s arithmetic by the whole solver portfolio (as ``prove`` asks them, the
    slow ones left to ``prove --all`` and taken as known) and judged
    against what is known (:mod:`~navfn_smt.smt.knowledge`); the status is derived from their
    standings, so a solver slower today than when the proof was found leaves it as known, and
    only a decision against what is known changes it."""
    if name not in inductive(planner):
        return None
    from ..proofs import PREDICATES
    from ..smt.chains import outcome_verdicts, split_link
    from ..smt.checking import check
    from ..smt.obligation import load_obligations
    from ..smt.runner import default_proof_files, solve_query
    from ..smt.solvers import SOLVERS
    from ..smt.split import known_of_files

    preds = [p for p in PREDICATES if p.name in inductive(planner)[name]]
    semantics = planner.fp32_semantics()
    wanted = [split_link(x)[1] for p in preds for x in (*p.base, *p.lemmas)]
    files = default_proof_files()
    obligations = {o.name: o for o in load_obligations(files)}
    known = known_of_files(files, list(obligations.values()), PREDICATES)
    # a query marked slow in this semantics is left, as in prove's default run, to `prove --all`:
    # its standing is what is known of it
    slow = [w for w in wanted if semantics in obligations[w].slow]
    runs = [check(obligations[w], semantics, timeout, solve_query(SOLVERS), known=known[(w, semantics)])
            for w in wanted if w not in slow]
    status = induction_status(name, outcome_verdicts(runs, known), planner)
    return {"predicates": [p.name for p in preds],
            "status": status["status"], "rank": status["rank"], "semantics": semantics,
            "obligations": {**{o.name: o.standing for o in runs}, **{w: known[(w, semantics)].status for w in slow}},
            "this_run": {**{o.name: o.status for o in runs}, **{w: "slow, not asked (prove --all)" for w in slow}},
            "contradicted": [o.name for o in runs if o.fails],
            "trusted": status["trusted"],
            "conditions": conditions(name, planner)}
