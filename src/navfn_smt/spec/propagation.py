"""Potential propagation: ``setupNavFn``, ``initCost``, ``propNavFnDijkstra`` and ``propNavFnAstar``.

Stated once, as steps over a state: :func:`init_cost`, :func:`push_cur` and :func:`push` (the
C++'s push macros, sharing :func:`admit`), :func:`update_cell`,
:func:`run_cycle` (the clearing loop, the update loop, :func:`end_of_cycle`) and the loop of
:func:`propagate`.  The state's few operations are its array model's: arrays filled with one
value, a buffer's conditional append, a choice between two buffers, the loops.  Here the model
is concrete (:class:`PropagationState`: flat lists indexed by ``n = y * nx + x`` like the C++
arrays); the proofs over arrays run the same functions on a state of SMT arrays
(``smt/program.py``), which turns each loop into the conditions of its invariant.  So no
condition depends on the data through Python's ``if``: the steps compute with the domain's
``ite``, ``and_`` and ``not_``; the one ``if`` on data, ``st.may``, skips steps that are no-ops
where its condition is false (the model may always answer yes: the proofs' does).  The conditions
the control goes on with (a cell changed, the buffer a push goes to, a push made, the loop's end
test) pass through :func:`~.numeric.taken`: a domain that follows one control path (``check``'s
concolic run, ``check/encoding.py``) takes its branch there, in this order.

Priority buffers are three bounded FIFO buffers (capacity PRIORITYBUFSIZE, or the ``capacity``
a caller gives ``setup``); a push to a full buffer is silently dropped, as in the C++ macros.
``curT`` is a float.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Callable, Optional

from ..errors import NavfnInputError
from . import kernels as K
from .constants import COST_OBS, POT_HIGH, PRI_INC, PRIORITYBUFSIZE
from .numeric import CONCRETE, taken

TraceHook = Callable[[int, list], None]

# Tables built by the kernels themselves (same code, evaluated once per cost value).
_HF = [CONCRETE.int_to_f32(c) for c in range(256)]
_EDGE = [K.edge_weight(CONCRETE, _HF[c]) for c in range(256)]


def cycle_limit(nx: int, ny: int) -> int:
    """``std::max(nx * ny / 20, nx + ny)`` (integer division), the cycle budget Nav2 uses."""
    return max((nx * ny) // 20, nx + ny)


def unbounded_capacity(nx: int, ny: int) -> int:
    """A buffer capacity that never drops a push on an ``nx`` by ``ny`` map: the pending flags
    keep every cell in at most one buffer at a time, so no buffer holds more than ``nx * ny``."""
    return nx * ny


class Buffer:
    """One priority buffer (``curP``, ``nextP`` or ``overP`` with its fill): its cells in slot order."""

    __slots__ = ("cells",)

    def __init__(self, cells=None):
        self.cells = [] if cells is None else cells

    @property
    def fill(self) -> int:
        return len(self.cells)

    def cell(self, k: int) -> int:
        return self.cells[k]

    def append_if(self, admitted: bool, n: int) -> None:
        """A push's write: ``n`` into slot ``fill``, the fill one up, when ``admitted``."""
        if admitted:
            self.cells.append(n)

    def with_fill(self, fill: int) -> "Buffer":
        return Buffer(self.cells[:fill])

    def emptied(self) -> "Buffer":
        return Buffer()

    def __len__(self) -> int:
        return len(self.cells)

    def __iter__(self):
        return iter(self.cells)


@dataclass
class PropagationState:
    """The arrays and counters of one propagation, in the concrete array model; what the trace
    and hashes are read from."""

    nx: int
    ny: int
    costs: list  # ints 0..255, border already lethal
    potential: list = field(default_factory=list)  # float32 values
    pending: list = field(default_factory=list)
    cur_t: float = 0.0
    cur: Buffer = field(default_factory=Buffer)
    nxt: Buffer = field(default_factory=Buffer)
    over: Buffer = field(default_factory=Buffer)
    cycles: int = 0  # cycles that processed at least one cell
    updates: int = 0
    dropped: int = 0  # pushes rejected because the buffer was full
    trace: list = field(default_factory=list)  # [n0, c, c, ..., n1, c, ...]
    capacity: int = PRIORITYBUFSIZE  # of each buffer; C++ fixes it at PRIORITYBUFSIZE
    domain: object = CONCRETE  # the concrete domain in the build's arithmetic (updateCell's multiply-adds)
    D = CONCRETE  # the domain of every other step

    @property
    def ns(self) -> int:
        return self.nx * self.ny

    # the concrete array model ------------------------------------------------------------
    def filled(self, array, value) -> list:
        """``array`` with every cell ``value`` (here a new list; a model may write it in place)."""
        return [value] * self.ns

    def index(self, n: int) -> int:
        """A read inside the arrays: the push's guard itself tests ``n`` against the map."""
        return min(max(n, 0), self.ns - 1)

    def cost_f32(self, n: int) -> float:
        return _HF[self.costs[n]]

    def edge(self, n: int) -> float:
        return _EDGE[self.costs[n]]

    def heuristic(self, n: int, start: tuple[int, int]) -> float:
        """A*'s heuristic from cell ``n`` to the start (:func:`kernels.astar_heuristic`)."""
        return _heuristic(n % self.nx - start[0], n // self.nx - start[1])

    @staticmethod
    def heuristic_between(goal: tuple[int, int], start: tuple[int, int]) -> float:
        """A*'s heuristic from the goal's coordinates to the start's, as they are (a cell one past
        the map's edge included)."""
        return _heuristic(goal[0] - start[0], goal[1] - start[1])

    @staticmethod
    def pick(cond: bool, a: Buffer, b: Buffer) -> Buffer:
        return a if cond else b

    @staticmethod
    def may(cond: bool) -> bool:
        """Whether steps guarded by ``cond`` can act: here, ``cond`` itself (they are skipped)."""
        return cond

    def note_drop(self, dropped: bool) -> None:
        self.dropped += bool(dropped)

    @staticmethod
    def loop(name: str, bound: int):
        return range(bound)

    @staticmethod
    def next_cycle(runs: bool) -> bool:
        """The cycle loop's test, at its top: whether another cycle runs (here ``runs`` itself)."""
        return runs

    def record_cycle(self, cycle: int, cycles: int, trace_hook: Optional[TraceHook], record_trace: bool) -> None:
        """A cycle of the ``cycles`` of this ``propNavFn*`` call starts (``cycle``, from 0) and
        processes the current buffer."""
        cells = self.cur.cells
        self.cycles += 1
        if record_trace:
            self.trace.append(len(cells))
            self.trace.extend(cells)
        if trace_hook is not None:
            trace_hook(cycle, list(cells))


_HEURISTIC_CACHE: dict = {}


def _heuristic(ddx: int, ddy: int) -> float:
    h = _HEURISTIC_CACHE.get((ddx, ddy))
    if h is None:
        h = _HEURISTIC_CACHE[(ddx, ddy)] = K.astar_heuristic(CONCRETE, ddx, ddy)
    return h


def check_capacity(capacity) -> int:
    """A buffer capacity as an int; refused when negative."""
    c = int(capacity)
    if c != capacity or c < 0:
        raise NavfnInputError(f"buffer capacity must be a non-negative integer, not {capacity!r}")
    return c


# ------------------------------------------------------------------------------ the steps
def setup(costs_with_border: list, nx: int, ny: int, goal: tuple[int, int],
          capacity: Optional[int] = None, arith=None) -> PropagationState:
    """``setupNavFn(true)`` and ``initCost(goal, 0)`` on a concrete state (:func:`init_cost`).

    ``capacity`` bounds each buffer (default PRIORITYBUFSIZE, as in C++; see
    :func:`unbounded_capacity` for one that never drops); ``arith``: the build's
    :class:`~.arithmetic.Arithmetic` (default x86-64's)."""
    st = PropagationState(nx=nx, ny=ny, costs=costs_with_border,
                          capacity=PRIORITYBUFSIZE if capacity is None else check_capacity(capacity),
                          domain=CONCRETE if arith is None else CONCRETE.with_arithmetic(arith))
    init_cost(st, goal[0] + goal[1] * nx)
    return st


def init_cost(st, k) -> None:
    """``setupNavFn(true)``: potentials to POT_HIGH, no cell pending, buffers empty,
    ``curT = COST_OBS``; then ``initCost(k, 0)``: the goal cell ``k`` gets potential 0 and its
    four neighbours are pushed onto the current buffer (right, left, up, down)."""
    D = st.D
    st.potential, st.pending = st.filled(st.potential, D.f32const(POT_HIGH)), st.filled(st.pending, False)
    st.cur, st.nxt, st.over = st.cur.emptied(), st.nxt.emptied(), st.over.emptied()
    st.cur_t = D.f32const(COST_OBS)
    st.potential[k] = D.f32const(0.0)
    for n in (k + 1, k - 1, k - st.nx, k + st.nx):
        push_cur(st, n)


def admit(st, n, wanted, fill):
    """What the push macros share: where the push is ``wanted``, the kernel :func:`kernels.push`
    admits the cell into a buffer of ``fill`` cells (capacity PRIORITYBUFSIZE unless the caller
    chose another) and gives its pending flag; a push refused only for want of room is counted as
    dropped (C++ drops it silently).  Returns whether the push is made."""
    D = st.D
    j = st.index(n)
    admitted, dropped, pending = K.push(D, n, st.ns, st.pending[j], st.costs[j], fill, st.capacity)
    pushed = taken(D, D.and_(wanted, admitted))
    st.pending[j] = D.ite(pushed, pending, st.pending[j])
    st.note_drop(D.and_(wanted, dropped))
    return pushed


def push_cur(st, n) -> None:
    """The ``push_cur`` macro (initCost's pushes): into the current buffer."""
    D = st.D
    pushed = admit(st, n, True, st.cur.fill)
    st.cur.append_if(D.and_(pushed, True), n)


def push(st, n, wanted, low) -> None:
    """An update's push where it is ``wanted``: ``push_next`` where ``low`` holds, ``push_over``
    where not."""
    D = st.D
    if not st.may(wanted):  # every write below wants `wanted`
        return
    pushed = admit(st, n, wanted, D.ite(low, st.nxt.fill, st.over.fill))
    st.nxt.append_if(D.and_(pushed, low), n)
    st.over.append_if(D.and_(pushed, D.not_(low)), n)


def update_neighbours(n, nx):
    """``updateCell(n)``'s four neighbours in the order it reads them (``l, r, u, d``) and pushes
    them: ``n-1, n+1, n-nx, n+nx`` (ints, or a domain's int terms)."""
    return n - 1, n + 1, n - nx, n + nx


def update_cell(st, n, astar: bool = False, start: tuple = (0, 0)) -> None:
    """``updateCell(n)`` (Dijkstra) or, with ``astar``, ``updateCellAstar(n)`` toward the start
    ``start``: the kernel :func:`kernels.cell_update` (``if (pot < potarr[n])``; an obstacle keeps
    its potential), then, when it changed the cell, the pushes of its neighbours the potential
    wants, into the buffer ``kernels.to_low_buffer`` picks by the key (the potential, plus A*'s
    heuristic)."""
    D = st.D
    st.updates += 1
    around = update_neighbours(n, st.nx)
    l, r, u, d = st.potential[around[0]], st.potential[around[1]], st.potential[around[2]], st.potential[around[3]]
    new, changed = K.cell_update(st.domain, st.potential[n], l, r, u, d, st.costs[n], st.cost_f32(n))
    changed = taken(D, changed)
    st.potential[n] = new  # the old potential unless changed
    if st.may(changed):  # the pushes want `changed`: where it is false they are no-ops
        key = D.add(new, st.heuristic(n, start)) if astar else new
        low = taken(D, K.to_low_buffer(D, key, st.cur_t))
        # updateCell's four pushes, written out as in the C++ (a loop over them is a loop, with a
        # jump table, in compiled code: a tenth of the JIT's planning time)
        push(st, around[0], D.and_(changed, K.push_wanted(D, l, key, st.edge(around[0]))), low)
        push(st, around[1], D.and_(changed, K.push_wanted(D, r, key, st.edge(around[1]))), low)
        push(st, around[2], D.and_(changed, K.push_wanted(D, u, key, st.edge(around[2]))), low)
        push(st, around[3], D.and_(changed, K.push_wanted(D, d, key, st.edge(around[3]))), low)


def end_of_cycle(st, inc) -> None:
    """The swap at a cycle's end (:func:`kernels.end_of_cycle`): the next buffer becomes current,
    or, when it is empty, the overflow buffer does (and ``curT += priInc``); the old current
    buffer's slots become the next buffer's, empty."""
    D = st.D
    drained, fill_cur, fill_over, st.cur_t = K.end_of_cycle(D, st.nxt.fill, st.over.fill, st.cur_t, inc)
    cur, over = st.pick(drained, st.over, st.nxt), st.pick(drained, st.nxt, st.over)
    st.cur, st.nxt, st.over = cur.with_fill(fill_cur), st.cur.emptied(), over.with_fill(fill_over)


def run_cycle(st, astar, start, inc) -> None:
    """One cycle of ``propNavFn*``: clear the pending flags of the current buffer's cells, update
    each of them in slot order (``updateCellAstar`` toward ``start`` with ``astar``), then
    :func:`end_of_cycle`."""
    for k in st.loop("clear", st.cur.fill):
        st.pending[st.cur.cell(k)] = False
    for k in st.loop("update", st.cur.fill):
        update_cell(st, st.cur.cell(k), astar, start)
    end_of_cycle(st, inc)


def buffers_hold_cells(D, fill_cur, fill_next):
    """``!(curPe == 0 && nextPe == 0)``: the current or the next buffer holds cells (ints)."""
    return D.not_(D.and_(D.eq(fill_cur, 0), D.eq(fill_next, 0)))


def cycle_runs(D, cycle, cycles, fill_cur, fill_next):
    """The test at the top of ``propNavFn*``'s loop: ``cycle < cycles`` (``for``) and the buffers
    holding cells (the ``break`` when ``curPe == 0 && nextPe == 0``): ints."""
    return D.and_(D.lt(cycle, cycles), buffers_hold_cells(D, fill_cur, fill_next))


def call_ends_at_the_start(D, start_pot):
    """The test at a cycle's end, after the swap: ``if (potarr[startCell] < POT_HIGH) break;``
    (``propNavFnAstar`` always; ``propNavFnDijkstra`` only when ``atStart``, which the loop tests
    first): a float comparison."""
    return D.lt(start_pot, D.f32const(POT_HIGH))


def propagate(
    st,
    start: tuple,
    goal: tuple,
    astar: bool,
    cycles: int,
    at_start: bool = True,
    pri_inc: int = PRI_INC,
    trace_hook: Optional[TraceHook] = None,
    record_trace: bool = True,
):
    """Run ``propNavFnAstar(cycles)`` or ``propNavFnDijkstra(cycles, atStart)``.

    Returns what the C++ returns: for A*, whether the start cell got a finite
    potential; for Dijkstra, ``cycle < cycles`` (true also when the buffers ran dry).
    ``trace_hook(cycle, cells)`` is called with the current buffer's contents, in
    processing order, for every cycle that processes cells.
    """
    D = st.D
    start_cell = start[1] * st.nx + start[0]
    if astar:
        st.cur_t = D.add(st.heuristic_between(goal, start), st.cur_t)
    inc = D.int_to_f32(pri_inc)
    check_start = astar or at_start
    cycle, going = 0, True
    while st.next_cycle(D.and_(going, cycle_runs(D, cycle, cycles, st.cur.fill, st.nxt.fill))):
        st.record_cycle(cycle, cycles, trace_hook, record_trace)
        run_cycle(st, astar, start, inc)
        going = taken(D, D.not_(D.and_(check_start, call_ends_at_the_start(D, st.potential[start_cell]))))
        cycle = cycle + D.ite(going, 1, 0)  # the `break` leaves the counter where it was
    if astar:
        return call_ends_at_the_start(D, st.potential[start_cell])
    return D.lt(cycle, cycles)
