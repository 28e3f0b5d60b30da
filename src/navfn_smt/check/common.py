"""What a bounded check of one size (:mod:`.runner`) and the replay of its certificate
(:mod:`.certificate`) share, so that each decides as the other does: the symbolic domain of a
float32 semantics, the sizes an induction decides without exploring and its status from what is
known of its predicates, whether a start outside the goal's component is decided without
exploring, the spec's replay of a counterexample, and how cases are batched into tasks.

It imports neither of them (the run imports the certificate and its journal, the certificate
this): the check's layers are :mod:`.bounded`, this, :mod:`.certificate` and :mod:`.journal`,
then :mod:`.runner`.
"""

from __future__ import annotations

import functools

from ..errors import NavfnInputError
from ..spec.constants import COST_NEUTRAL, COST_OBS
from ..under_test import ORIGINAL, PlannerUnderTest
from . import properties as P
from .bounded import Case

PARALLEL_FROM = 200  # --jobs auto: local workers from this many cases of a size on
BATCH = 4  # cases per task: a case of a small size takes milliseconds, a task's round trip about as much

# On a narrow size (interior at most two cells wide or tall, at most 4*nx cells), NavFn as
# shipped: calcPath takes its fallback at every step there (every cell has a border neighbour)
INDUCTION_NARROW = {"complete": ("FallbackPath",)}
BOUND_CELLS = 2_000_000  # FallbackPath's bound 2**30 holds below this many passable cells (506 * cells)


def symbolic_domain(semantics: str):
    """The symbolic domain of a float32 ``semantics`` (``fp32``, or ``fp32@NAME`` in a build's
    arithmetic: :data:`~navfn_smt.smt.domains.FP32_SEMANTICS`)."""
    from ..smt.domains import DOMAINS, is_fp32

    if not is_fp32(semantics):
        raise NavfnInputError("check: only --semantics fp32 is implemented for whole-planner checks "
                              "(the concolic exploration follows float32 control paths)")
    return DOMAINS[semantics]


def replay(case: Case, costs: dict, name: str, planner: PlannerUnderTest = ORIGINAL):
    """The counterexample map run by the reference spec as ``planner`` plans (its variant, in its
    arithmetic); the judge's reason, or None if it holds."""
    arr = case.costs_array(costs)
    r = P.run(arr, case.start, case.goal, case.astar, fix=planner.fix, arith=planner.navfn_arithmetic())
    return arr, r, P.judge(name, r)


def narrow(nx: int, ny: int) -> bool:
    """An interior at most two cells wide or tall, of at most 4*nx cells: where FallbackPath carries complete."""
    w, h = nx - 2, ny - 2
    return min(w, h) <= 2 and w * h <= 4 * nx and w * h < BOUND_CELLS


def carried_at(nx: int, ny: int, planner: PlannerUnderTest = ORIGINAL, lo: int = COST_NEUTRAL,
               hi: int = COST_OBS - 1) -> dict:
    """The properties an induction decides on every map of this size without exploring, and
    the predicates that carry each.  The inductions' obligations assume the costs setCostmap
    produces (COST_NEUTRAL..COST_OBS-1): a wider cost box (``--costs 0..253``) is explored.
    Whether the induction decides is :func:`carried_status`'s, in the planner's arithmetic."""
    if not planner.fix.shipped or not narrow(nx, ny) or lo < COST_NEUTRAL or hi >= COST_OBS:
        return {}
    return INDUCTION_NARROW


@functools.lru_cache(maxsize=None)  # the proof files are read once a run, not once a size
def _verdict_of():
    """What is known of every obligation (declarations, splits, the bound cache), as
    :func:`~navfn_smt.smt.chains.known_verdicts` gives it."""
    from ..proofs import PREDICATES
    from ..smt.chains import known_verdicts
    from ..smt.runner import default_proof_files
    from ..smt.split import known_of_files

    return known_verdicts(known_of_files(default_proof_files(), None, PREDICATES))


def _derived(name: str, semantics: str) -> str:
    """The rank of the predicate ``name``'s status in ``semantics`` (proved, bounded, open or
    refuted, without the trusted steps and conditions that qualify it), derived from what is known:
    what a bounded check may decide by (its report names the induction, whose status says the rest)."""
    from ..proofs import PREDICATES
    from ..smt.chains import derive

    return derive(next(p for p in PREDICATES if p.name == name), semantics, _verdict_of(), PREDICATES)["rank"]


def outside_decided(planner: PlannerUnderTest = ORIGINAL) -> bool:
    """Whether a start outside the goal's component is decided without exploring
    (:func:`~.bounded.reduce_cases`): ReachedWithinComponent gives it no finite potential, and
    NoPathWithoutFinitePotential then no path, which holds only where its links are proved in the
    planner's arithmetic (not in aarch64's, whose saturating ``(int)`` lets calcPath's fallback
    walk from a cell never reached).  Elsewhere those starts are explored like any other."""
    semantics = planner.fp32_semantics()
    return all(_derived(p, semantics) == "proved" for p in ("ReachedWithinComponent", "NoPathWithoutFinitePotential"))


@functools.lru_cache(maxsize=None)
def carried_status(carriers: tuple, semantics: str = "fp32") -> tuple[str, str]:
    """``(status, why)`` of a size decided by the predicates ``carriers``: their status in the
    float32 ``semantics`` (``fp32``: x86-64's arithmetic), derived from what is known of their
    links (declarations, splits, the bound cache: what ``navfn-smt prove`` checks and CI
    re-checks), ``proved`` for the size when that status is proved or bounded (the bound,
    potentials below 2**30, holds on a map below BOUND_CELLS passable cells: see FallbackPath),
    ``unknown`` otherwise."""
    from ..smt.chains import STATUS_RANK

    statuses = [_derived(name, semantics) for name in carriers]
    worst = max(statuses, key=STATUS_RANK.index) if statuses else "open"
    why = f"induction: {', '.join(carriers)} ({semantics} {worst})"
    return ("proved" if worst in ("proved", "bounded") else "unknown"), why
