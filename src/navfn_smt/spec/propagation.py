"""Potential propagation: ``setupNavFn``, ``propNavFnDijkstra`` and ``propNavFnAstar``.

The reference implementation: plain Python loops around the kernels of
:mod:`.kernels`, evaluated in the concrete domain.  State is kept in flat lists indexed
by ``n = y * nx + x`` like the C++ arrays.

Priority buffers are three bounded FIFO lists (capacity PRIORITYBUFSIZE, or the
``capacity`` a caller gives ``setup``); a push to a full buffer is silently dropped, as in
the C++ macros.  ``curT`` is a float.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Callable, Optional

from ..errors import NavfnInputError
from . import kernels as K
from .constants import COST_OBS, POT_HIGH, PRI_INC, PRIORITYBUFSIZE
from .numeric import CONCRETE as D

TraceHook = Callable[[int, list], None]

# Tables built by the kernels themselves (same code, evaluated once per cost value).
_HF = [D.int_to_f32(c) for c in range(256)]
_EDGE = [K.edge_weight(D, _HF[c]) for c in range(256)]
_POT_HIGH = D.f32const(POT_HIGH)


def cycle_limit(nx: int, ny: int) -> int:
    """``std::max(nx * ny / 20, nx + ny)`` (integer division), the cycle budget Nav2 uses."""
    return max((nx * ny) // 20, nx + ny)


def unbounded_capacity(nx: int, ny: int) -> int:
    """A buffer capacity that never drops a push on an ``nx`` by ``ny`` map: the pending flags
    keep every cell in at most one buffer at a time, so no buffer holds more than ``nx * ny``."""
    return nx * ny


@dataclass
class PropagationState:
    """The arrays and counters of one propagation; what the trace and hashes are read from."""

    nx: int
    ny: int
    costs: list  # ints 0..255, border already lethal
    potential: list  # float32 values
    pending: list
    cur_t: float
    cur: list = field(default_factory=list)
    nxt: list = field(default_factory=list)
    over: list = field(default_factory=list)
    cycles: int = 0  # cycles that processed at least one cell
    updates: int = 0
    dropped: int = 0  # pushes rejected because the buffer was full
    trace: list = field(default_factory=list)  # [n0, c, c, ..., n1, c, ...]
    capacity: int = PRIORITYBUFSIZE  # of each buffer; C++ fixes it at PRIORITYBUFSIZE
    domain: object = D  # the concrete domain in the build's arithmetic (updateCell's multiply-adds)

    @property
    def ns(self) -> int:
        return self.nx * self.ny


def check_capacity(capacity) -> int:
    """A buffer capacity as an int; refused when negative."""
    c = int(capacity)
    if c != capacity or c < 0:
        raise NavfnInputError(f"buffer capacity must be a non-negative integer, not {capacity!r}")
    return c


def _push(st: PropagationState, buf: list, n: int) -> None:
    """The ``push_cur/push_next/push_over`` macros: the kernel :func:`kernels.push` (capacity
    PRIORITYBUFSIZE unless the caller chose another) decides the push and the pending flag; a
    push refused only for want of room is counted as dropped (C++ drops it silently)."""
    ns = st.nx * st.ny
    j = min(max(n, 0), ns - 1)  # a read inside the arrays: the guard itself tests n against the map
    admitted, dropped, st.pending[j] = K.push(D, n, ns, st.pending[j], st.costs[j], len(buf), st.capacity)
    if admitted:
        buf.append(n)
    elif dropped:  # admitted but for the full buffer (PRIORITYBUFSIZE)
        st.dropped += 1


def setup(costs_with_border: list, nx: int, ny: int, goal: tuple[int, int],
          capacity: Optional[int] = None, arith=None) -> PropagationState:
    """``setupNavFn(true)``: potentials to POT_HIGH, buffers empty, ``curT = COST_OBS``,
    then ``initCost(goal, 0)``: the goal gets potential 0 and its four neighbours are
    pushed onto the current buffer (right, left, up, down).

    ``capacity`` bounds each buffer (default PRIORITYBUFSIZE, as in C++; see
    :func:`unbounded_capacity` for one that never drops); ``arith``: the build's
    :class:`~.arithmetic.Arithmetic` (default x86-64's)."""
    ns = nx * ny
    st = PropagationState(
        nx=nx,
        ny=ny,
        costs=costs_with_border,
        potential=[_POT_HIGH] * ns,
        pending=[False] * ns,
        cur_t=D.f32const(COST_OBS),
        capacity=PRIORITYBUFSIZE if capacity is None else check_capacity(capacity),
        domain=D if arith is None else D.with_arithmetic(arith),
    )
    k = goal[0] + goal[1] * nx
    st.potential[k] = D.f32const(0.0)
    for n in (k + 1, k - 1, k - nx, k + nx):
        _push(st, st.cur, n)
    return st


def update_neighbours(n, nx):
    """``updateCell(n)``'s four neighbours in the order it reads them (``l, r, u, d``) and pushes
    them: ``n-1, n+1, n-nx, n+nx`` (ints, or a domain's int terms: the proofs over arrays take
    them from here too)."""
    return n - 1, n + 1, n - nx, n + nx


def _update_cell(st: PropagationState, n: int, astar_start: Optional[tuple[int, int]]) -> None:
    """``updateCell(n)`` (Dijkstra) or ``updateCellAstar(n)`` when ``astar_start`` is given."""
    st.updates += 1
    nx = st.nx
    pot = st.potential
    cost = st.costs[n]
    if not K.is_passable(D, cost):  # skip the arithmetic on obstacles (cell_update keeps them)
        return
    around = update_neighbours(n, nx)
    l, r, u, d = (pot[m] for m in around)
    new, changed = K.cell_update(st.domain, pot[n], l, r, u, d, cost, _HF[cost])
    pot[n] = new  # the old potential unless changed: cell_update is the `if (pot < potarr[n])`
    if not changed:
        return
    key = new
    if astar_start is not None:
        x, y = n % nx, n // nx
        key = D.add(new, _heuristic(x - astar_start[0], y - astar_start[1]))
    buf = st.nxt if K.to_low_buffer(D, key, st.cur_t) else st.over
    costs = st.costs
    for m, pm in zip(around, (l, r, u, d)):
        if K.push_wanted(D, pm, key, _EDGE[costs[m]]):
            _push(st, buf, m)


_HEURISTIC_CACHE: dict = {}


def _heuristic(ddx: int, ddy: int) -> float:
    h = _HEURISTIC_CACHE.get((ddx, ddy))
    if h is None:
        h = _HEURISTIC_CACHE[(ddx, ddy)] = K.astar_heuristic(D, ddx, ddy)
    return h


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
    st: PropagationState,
    start: tuple[int, int],
    goal: tuple[int, int],
    astar: bool,
    cycles: int,
    at_start: bool = True,
    pri_inc: int = PRI_INC,
    trace_hook: Optional[TraceHook] = None,
    record_trace: bool = True,
) -> bool:
    """Run ``propNavFnAstar(cycles)`` or ``propNavFnDijkstra(cycles, atStart)``.

    Returns what the C++ returns: for A*, whether the start cell got a finite
    potential; for Dijkstra, ``cycle < cycles`` (true also when the buffers ran dry).
    ``trace_hook(cycle, cells)`` is called with the current buffer's contents, in
    processing order, for every cycle that processes cells.
    """
    nx = st.nx
    start_cell = start[1] * nx + start[0]
    astar_start = start if astar else None
    if astar:
        st.cur_t = D.add(_heuristic(goal[0] - start[0], goal[1] - start[1]), st.cur_t)
    inc = D.int_to_f32(pri_inc)
    check_start = astar or at_start
    cycle = 0
    while cycle_runs(D, cycle, cycles, len(st.cur), len(st.nxt)):
        cells = st.cur
        st.cycles += 1
        if record_trace:
            st.trace.append(len(cells))
            st.trace.extend(cells)
        if trace_hook is not None:
            trace_hook(cycle, list(cells))
        pending = st.pending
        for c in cells:
            pending[c] = False
        for c in cells:
            _update_cell(st, c, astar_start)
        # swap: the next buffer becomes current; an empty one pulls in the overflow (the
        # kernel gives the fills, a buffer's cells are its first `fill` slots)
        drained, fill_cur, fill_over, st.cur_t = K.end_of_cycle(D, len(st.nxt), len(st.over), st.cur_t, inc)
        cur, over = (st.over, st.nxt) if drained else (st.nxt, st.over)
        st.cur, st.nxt, st.over = cur[:fill_cur], [], over[:fill_over]
        if check_start and call_ends_at_the_start(D, st.potential[start_cell]):
            break
        cycle += 1
    if astar:
        return D.lt(st.potential[start_cell], _POT_HIGH)
    return cycle < cycles
