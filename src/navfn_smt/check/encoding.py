"""The complete run of NavFn on a small map (propagation and path extraction), in the concolic domain.

The run is the spec's own: :func:`~navfn_smt.spec.propagation.init_cost`, the planning call
:func:`~navfn_smt.spec.planner.calc_navfn` with the fix's hooks, then
:func:`~navfn_smt.spec.planner.extract` (calcPath and the fix's fallback), each run unchanged
on the array model below, in a :class:`~.concolic.ConcolicDomain`.  The interior cells' costs
are domain values (symbolic bytes with a concrete value, or constants); the start and the goal
are fixed.  Every condition the control goes on with passes through
:func:`~navfn_smt.spec.numeric.taken`, where the concolic domain takes the branch of the
concrete map and records it when the cost box leaves it open (the kernels' own ``ite`` and the
``ite`` chains of calcPath's and the descent's exits decide the same way): the records are the
control path's condition, and every value the run computes carries its term.  So cells, slots
and fills stay plain ints; the costs and what is computed from them (potentials, gradients, path
points, the near-goal probe's cell) are terms.  A concolic value refuses ``bool()`` and ``==``,
so a test that reached Python's ``if`` without being taken raises.

What is written here is the array model (:class:`_Run`): the state of
:class:`~navfn_smt.spec.propagation.PropagationState` with the costs' terms, plus what the
check reads besides the potentials: every cell ever queued, and the branch count at which the
start's reach became certain (QueuedStartReached).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Optional

from ..spec import kernels as K
from ..spec.constants import COST_OBS, PRIORITYBUFSIZE
from ..spec.extraction import EXIT_UNDEFINED, UndefinedBehaviour, exit_code
from ..spec.planner import AS_SHIPPED, Fix, calc_navfn, extract as extract_path
from ..spec.propagation import Buffer, PropagationState, init_cost
from .concolic import concrete


@dataclass
class SymbolicPropagation:
    """The run after propagation: potentials per cell (terms or plain floats), the value the
    last ``propNavFn*`` call returned, the cycles that ran, every cell ever queued (in push
    order), the white-box trace, and ``start_certain``: the number of branches recorded when the
    start's reach became certain (None: never)."""

    nx: int
    ny: int
    potential: list
    start_reached: object
    cycles: int
    queued: list = field(default_factory=list)
    trace: list = field(default_factory=list)
    start_certain: Optional[int] = None


def interior(nx: int, ny: int) -> list[int]:
    """The cells off the map's lethal border, row by row."""
    return [y * nx + x for y in range(1, ny - 1) for x in range(1, nx - 1)]


class _Queue(Buffer):
    """A priority buffer of :class:`_Run`: tells the run of every cell it admits."""

    __slots__ = ("run",)

    def __init__(self, run: "_Run", cells=None):
        super().__init__(cells)
        self.run = run

    def append_if(self, admitted: bool, n: int) -> None:
        if admitted:
            self.cells.append(n)
            self.run.queue(self, n)

    def with_fill(self, fill: int) -> "_Queue":
        return _Queue(self.run, self.cells[:fill])

    def emptied(self) -> "_Queue":
        return _Queue(self.run)


@dataclass
class _Run(PropagationState):
    """The spec's concrete array model with costs that are domain values: ``costs[n]`` the
    cost as an int value, ``hf[n]`` as a float (``D.cost_int``, ``D.cost_as_f32`` of the byte).

    It notes when the start's reach becomes certain (QueuedStartReached): the start is in the
    current buffer of a cycle that runs, or pushed to the next buffer in a cycle that is not its
    call's last; the cycle after processes it, and nothing after can unreach it."""

    hf: list = field(default_factory=list)
    start_cell: int = -1
    queued: list = field(default_factory=list)
    certain: Optional[int] = None
    last_cycle: bool = False

    def cost_f32(self, n: int):
        return self.hf[n]

    def edge(self, n: int):
        return K.edge_weight(self.D, self.hf[n])

    @staticmethod
    def may(cond) -> bool:
        return cond if isinstance(cond, bool) else True  # a term: the step decides (spec.numeric.taken)

    def note_drop(self, dropped) -> None:
        self.dropped += bool(concrete(dropped))

    def record_cycle(self, cycle: int, cycles: int, trace_hook, record_trace: bool) -> None:
        self.last_cycle = cycle + 1 >= cycles
        if self.certain is None and self.start_cell in self.cur.cells:
            self.certain = len(self.D.branches)
        super().record_cycle(cycle, cycles, trace_hook, record_trace)

    def queue(self, buf: _Queue, n: int) -> None:
        self.queued.append(n)
        if self.certain is None and n == self.start_cell and buf is self.nxt and not self.last_cycle:
            self.certain = len(self.D.branches)


def propagate(D, costs: dict, nx: int, ny: int, start, goal, astar: bool, fix: Fix = AS_SHIPPED) -> SymbolicPropagation:
    """initCost and the planning call (:func:`~navfn_smt.spec.planner.calc_navfn`, with ``fix``'s
    hooks) on an ``nx`` x ``ny`` map in the concolic domain ``D``; ``costs[k]`` is interior cell
    k's cost, a domain byte (``D.cost(...)``) or an int.  Border cells are COST_OBS."""
    byte = [COST_OBS] * (nx * ny)
    for k in interior(nx, ny):
        byte[k] = costs[k]
    st = _Run(nx=nx, ny=ny, costs=[D.cost_int(c) for c in byte], capacity=PRIORITYBUFSIZE, domain=D,
              hf=[D.cost_as_f32(c) for c in byte], start_cell=start[1] * nx + start[0])
    st.D = D
    st.cur = st.nxt = st.over = _Queue(st)
    init_cost(st, goal[1] * nx + goal[0])
    done, _ = calc_navfn(st, start, goal, astar, fix)
    # the buffers point back at the run: without them the run's terms go now, not at the next
    # garbage collection (Z3's SMT-LIB printer shares a subterm by its reference count, so what
    # stays alive changes a query's text, which transcripts compare)
    st.cur = st.nxt = st.over = None
    return SymbolicPropagation(nx, ny, st.potential, done, st.cycles, st.queued, st.trace, st.certain)


# ---------------------------------------------------------------------------------------
# Path extraction: calcPath(n) and the fix's fallback
# ---------------------------------------------------------------------------------------
RUNNING = -1  # calcPath was not run (beside the exits' ints, spec.extraction.EXIT_CODES)


@dataclass
class SymbolicExtraction:
    """The run after ``calcPath(n)`` (and the fix's fallback): the exit's int
    (:func:`~navfn_smt.spec.extraction.exit_code`, ``EXIT_UNDEFINED``) and the path it returned
    (points as terms or floats, the goal last; empty unless the exit is ``NEAR_GOAL``)."""

    exit: int
    path: list


class _Potentials:
    """``potarr`` as the run reads it: at a plain cell, that cell's potential; at a cell that is
    an int term (calcPath's near-goal probe, whose rounded offsets the box may leave open), every
    cell's potential selected by ``ite`` over the cells, from the last down, which the concolic
    domain resolves to the concrete cell (recording each test the box leaves open)."""

    def __init__(self, D, pot: list):
        self.D, self.pot = D, pot

    def __len__(self) -> int:
        return len(self.pot)

    def __getitem__(self, i):
        if isinstance(i, int):
            return self.pot[i]
        out = self.pot[-1]
        for k in reversed(range(len(self.pot) - 1)):
            out = self.D.ite(self.D.eq(i, k), self.pot[k], out)
        return out


def extract(D, pot: list, nx: int, ny: int, start, goal, n: int, fix: Fix = AS_SHIPPED) -> SymbolicExtraction:
    """``calcPath(n)`` from ``start`` on potentials ``pot`` (the propagation's), then ``fix``'s
    fallback where it returns no path (:func:`~navfn_smt.spec.planner.extract`), in the concolic
    domain ``D``; a read outside the arrays is exit ``EXIT_UNDEFINED``."""
    try:
        ext, _ = extract_path(_Potentials(D, pot), nx, ny, start, goal, n, fix, domain=D)
    except UndefinedBehaviour:
        return SymbolicExtraction(EXIT_UNDEFINED, [])
    return SymbolicExtraction(exit_code(ext.exit), ext.path)
