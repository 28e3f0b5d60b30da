"""One NavFn planning call, exactly as Nav2 (and the golden suite) runs it, with a fix's hooks.

For every case, on a fresh copy of the costs: ``setGoal``, ``setStart``,
``setupNavFn(true)``; then A* (``priInc = 2 * COST_NEUTRAL``,
``propNavFnAstar(max(nx*ny/20, nx+ny))``) or Dijkstra
(``propNavFnDijkstra(max(nx*ny/20, nx+ny), atStart=true)``); then ``calcPath(4 * nx)``.

A :class:`Fix` is a change to that call, stated as its hooks: the cycles ``calcNavFn*`` gives
``propNavFn*``, a further ``propNavFn*`` call after the first, and a fallback where calcPath
returns no path.  :data:`AS_SHIPPED` has none; the candidate fixes are registered in
:mod:`.fixes`.  :func:`calc_navfn` (the propagation) and :func:`extract` (calcPath with the
fix's fallback) are the call, written once; :func:`plan` and the models above the spec run them.
"""

from __future__ import annotations

import hashlib
from dataclasses import dataclass, field
from typing import Callable, Optional

import numpy as np

from ..errors import NavfnInputError
from ..inputs import check_inputs
from .costs import add_border
from .extraction import Extraction, ExtractionExit, calc_path
from .numeric import taken
from .propagation import PropagationState, TraceHook, cycle_limit, propagate, setup


@dataclass(frozen=True)
class FurtherCall:
    """A further ``propNavFn*`` call after the first one returns: made when ``test(D, start_pot,
    fill_cur, fill_next)`` holds (a function over a numeric domain, which the JIT compiles too),
    with ``cycles(nx, ny)`` cycles."""

    test: Callable
    cycles: Callable[[int, int], int]


@dataclass(frozen=True)
class Fallback:
    """What a patched calcPath does where following the gradient returns no path:
    ``walk(potential, nx, ny, start, goal, n, D)``, an :class:`~.extraction.Extraction` (``D``:
    the numeric domain it runs in, the concrete one by default; the check's encoding runs it in
    its concolic domain)."""

    walk: Callable


@dataclass(frozen=True)
class Fix:
    """NavFn as shipped (no hook) or changed by a patch of ``navfn.cpp``, stated as hooks of the
    planning call: ``cycles(nx, ny)``, the cycles ``calcNavFn*`` gives its ``propNavFn*`` call;
    ``further``, a :class:`FurtherCall`; ``fallback``, a :class:`Fallback` where ``calcPath(n)``
    returns no path; ``inclusive``, calcPath's near-goal test made ``<=``; ``proved``, the
    properties of ``check`` its proofs carry for every map size.  ``name`` is how the
    command line and reports name it; ``patches``: the folder of ``patches/`` holding its
    ``<distribution>.patch`` (None: no C++ patch, a candidate compared in the spec only)."""

    name: str
    summary: str
    patches: Optional[str] = None
    cycles: Callable[[int, int], int] = cycle_limit
    further: Optional[FurtherCall] = None
    fallback: Optional[Fallback] = None
    inclusive: bool = False  # calcPath's near-goal test reads potarr <= COST_NEUTRAL, not <
    proved: tuple = ()  # (property of check, the predicates of proofs/ that carry it for every map size) pairs

    @property
    def shipped(self) -> bool:
        """NavFn as Nav2 ships it (no hook)."""
        return self == AS_SHIPPED

    def first_cycles(self, nx: int, ny: int, cycles: Optional[int] = None) -> int:
        """The first call's cycles: ``cycles`` when a caller replaces the budget, else the fix's."""
        limit = self.cycles(nx, ny) if cycles is None else int(cycles)
        if self.further is not None and limit < 1:  # a further call after 0 cycles would never end
            raise NavfnInputError(f"the {self.name} planner needs a cycle limit of at least 1, not {limit}")
        return limit


AS_SHIPPED = Fix("original", "NavFn as Nav2 ships it")


def calc_navfn(st: PropagationState, start: tuple[int, int], goal: tuple[int, int], astar: bool,
               fix: Fix = AS_SHIPPED, cycles: Optional[int] = None, at_start: bool = True,
               trace_hook: Optional[TraceHook] = None, record_trace: bool = True) -> tuple[bool, int]:
    """``calcNavFnAstar`` / ``calcNavFnDijkstra(atStart)`` after ``setupNavFn``, with ``fix``'s
    hooks: :func:`call` with the fix's cycles (or ``cycles``) and its further call.  Returns the
    last call's return value and the further calls made (0 or 1)."""
    further = fix.further
    return call(st, start, goal, astar, fix.first_cycles(st.nx, st.ny, cycles),
                None if further is None else further.test, 0 if further is None else further.cycles(st.nx, st.ny),
                at_start, trace_hook, record_trace)


def call(st, start, goal, astar, cycles, further_test, further_cycles, at_start=True, trace_hook=None,
         record_trace=True):
    """The propagation of one planning call: ``propNavFn*(cycles)``, then, where
    ``further_test(D, start_pot, fill_cur, fill_next)`` holds after it (None: never), a further
    ``propNavFn*(further_cycles)``.  Returns the last call's return value and the further calls
    made (0 or 1).  The JIT compiles this function with its state (``backends/jit_state.py``)."""
    D = st.D
    done = propagate(st, start, goal, astar, cycles, at_start, trace_hook=trace_hook, record_trace=record_trace)
    if further_test is not None:
        if taken(D, further_test(D, st.potential[start[1] * st.nx + start[0]], st.cur.fill, st.nxt.fill)):
            done = propagate(st, start, goal, astar, further_cycles, at_start, trace_hook=trace_hook,
                             record_trace=record_trace)
            return done, 1
    return done, 0


def extract(potential: list, nx: int, ny: int, start: tuple[int, int], goal: tuple[int, int], n: int,
            fix: Fix = AS_SHIPPED, arith=None, domain=None) -> tuple[Extraction, bool]:
    """``calcPath(n)`` and, where it returns no path, the fix's fallback: the extraction, and
    whether the fallback gave the path.  ``domain``: the numeric domain to run in (default: the
    concrete one in ``arith``, the build's arithmetic)."""
    ext = calc_path(potential, nx, ny, start, goal, n, arith=arith, domain=domain, inclusive=fix.inclusive)
    if fix.fallback is None or ext.exit is ExtractionExit.NEAR_GOAL:
        return ext, False
    ext = fix.fallback.walk(potential, nx, ny, start, goal, n, *(() if domain is None else (domain,)))
    return ext, ext.exit is ExtractionExit.NEAR_GOAL


def acted(nx: int, ny: int, ran: int, calls: int, cycles: Optional[int], descended: bool) -> list:
    """The parts of a fix that acted on a run of ``ran`` cycles on an ``nx`` by ``ny`` map
    (``PlanResult.extra["fix"]``): ``"propagation"`` when it propagated past Nav2's budget (a
    further call, or, the budget not replaced by ``cycles``, more cycles than
    ``max(nx*ny/20, nx+ny)``), ``"descent"`` when its fallback gave the path."""
    past = calls > 0 or (cycles is None and ran > cycle_limit(nx, ny))
    return ["propagation"] * past + ["descent"] * descended


def path_cycle_limit(nx: int) -> int:
    """``calcPath(nx * 4)``: the extraction budget ``calcNavFnAstar``/``calcNavFnDijkstra`` give."""
    return 4 * nx


@dataclass
class PlanResult:
    start_reached: bool
    start_potential: np.float32
    path: np.ndarray  # (M, 2) float32, empty when calcPath returned 0
    potential: np.ndarray  # (ny, nx) float32 after propagation
    trace: Optional[np.ndarray]  # int32 [n0, c..., n1, c...]; None when not recorded
    cycles: int
    updates: int
    dropped: int = 0
    exit: Optional[ExtractionExit] = None
    extra: dict = field(default_factory=dict)


def sha256_f32(a: np.ndarray) -> bytes:
    return hashlib.sha256(np.ascontiguousarray(a, dtype="<f4").tobytes()).digest()


def sha256_i32(a: np.ndarray) -> bytes:
    return hashlib.sha256(np.ascontiguousarray(a, dtype="<i4").tobytes()).digest()


def plan(
    costs: np.ndarray,
    start: tuple[int, int],
    goal: tuple[int, int],
    astar: bool = True,
    trace_hook: Optional[TraceHook] = None,
    cycles: Optional[int] = None,
    path_cycles: Optional[int] = None,
    record_trace: bool = True,
    capacity: Optional[int] = None,
    fix: Fix = AS_SHIPPED,
    arith=None,
) -> PlanResult:
    """Plan on NavFn-internal costs (a (height, width) uint8 array) with the reference spec.

    ``start`` is NavFn's start (where extraction begins), ``goal`` where propagation begins.
    ``capacity`` bounds each priority buffer (default PRIORITYBUFSIZE, as in C++).
    ``fix``: the planner's :class:`Fix` (default NavFn as shipped); for a patched planner
    ``extra["fix"]`` lists the parts that acted (:func:`acted`), empty where the original plans.
    ``arith``: the :class:`~.arithmetic.Arithmetic` of the build to plan as (default x86-64's).
    """
    arr = check_inputs(costs, start, goal)
    ny, nx = arr.shape
    start = (int(start[0]), int(start[1]))
    goal = (int(goal[0]), int(goal[1]))
    cost_list = add_border(arr).ravel().tolist()
    st = setup(cost_list, nx, ny, goal, capacity, arith)
    reached, calls = calc_navfn(st, start, goal, astar, fix, cycles, True, trace_hook, record_trace)
    n = path_cycle_limit(nx) if path_cycles is None else path_cycles
    ext, descended = extract(st.potential, nx, ny, start, goal, n, fix, arith)
    pot = np.array(st.potential, dtype=np.float32).reshape(ny, nx)
    path = np.array(ext.path, dtype=np.float32).reshape(-1, 2)
    return PlanResult(
        start_reached=bool(reached),
        start_potential=pot[start[1], start[0]],
        path=path,
        potential=pot,
        trace=np.array(st.trace, dtype=np.int32) if record_trace else None,
        cycles=st.cycles,
        updates=st.updates,
        dropped=st.dropped,
        exit=ext.exit,
        extra={} if fix.shipped else {"fix": acted(nx, ny, st.cycles, calls, cycles, descended)},
    )
