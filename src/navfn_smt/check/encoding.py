"""The complete propagation of NavFn on a small map, as terms of a symbolic domain.

``setupNavFn`` + ``propNavFn{Astar,Dijkstra}`` unrolled over a map whose interior cells have
costs given as domain values (symbolic bytes, or constants), with the start and goal fixed.
The arithmetic is the spec's kernels (:mod:`navfn_smt.spec.kernels`) in the domain; what is
written here is the C++ control flow made symbolic:

* a buffer is ``slots`` cell indices (terms over the interior cells) and a fill count; a
  push writes the slot at the fill count and increments it, under the push's guard.  No
  interior cell is twice in the buffers (the pending flags; proved in ``proofs/queues.py``),
  so each buffer needs as many slots as there are interior cells, and a push to a full
  buffer (``PRIORITYBUFSIZE``) cannot happen on such a map;
* a cycle processes slot i of the current buffer as the update of cell k under the guard
  ``i < fill and slot_i == k``, for every interior k, in the C++ order;
* the loop runs ``cycle_limit`` cycles, each under ``running`` (buffers not both empty, start
  not yet reached), so the terms describe every map of the size at once.

Only interior cells are ever pushed (the border is lethal), so slot values range over them.
The A* heuristic of a fixed cell and start is a constant: the kernel evaluated concretely.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from ..spec import kernels as K
from ..spec.constants import COST_OBS, POT_HIGH, PRI_INC
from ..spec.numeric import CONCRETE
from ..spec.propagation import cycle_limit


@dataclass
class Buffer:
    slots: list  # cell index per slot (int or term)
    fill: object  # int or term


@dataclass
class SymbolicPropagation:
    """Terms after propagation: potentials per cell, start_reached, processed cycles."""

    nx: int
    ny: int
    potential: list
    start_reached: object
    cycles: object
    pending: list = field(default_factory=list)
    trace: list = field(default_factory=list)  # per unrolled cycle: (processed?, fill, slots)


def _interior(nx: int, ny: int) -> list[int]:
    return [y * nx + x for y in range(1, ny - 1) for x in range(1, nx - 1)]


def _push(D, buf: Buffer, guard, cell: int) -> Buffer:
    """``buf[fill] = cell; fill++`` under ``guard``."""
    slots = [D.ite(D.and_(guard, D.eq(buf.fill, j)), cell, s) for j, s in enumerate(buf.slots)]
    return Buffer(slots, D.ite(guard, D.add_int(buf.fill, 1), buf.fill))


def _choose(D, c, a: Buffer, b: Buffer) -> Buffer:
    return Buffer([D.ite(c, x, y) for x, y in zip(a.slots, b.slots)], D.ite(c, a.fill, b.fill))


def propagate(D, costs: dict, nx: int, ny: int, start, goal, astar: bool) -> SymbolicPropagation:
    """Propagation on an ``nx`` x ``ny`` map; ``costs[k]`` is interior cell k's cost as a domain
    byte (``D.cost(...)``) or an int.  Border cells are COST_OBS."""
    inner = _interior(nx, ny)
    n_slots = len(inner)
    empty = Buffer([0] * n_slots, 0)
    cost_int = {k: D.cost_int(costs[k]) for k in inner}
    hf = {k: D.cost_as_f32(costs[k]) for k in inner}
    high = D.f32const(POT_HIGH)

    def heuristic(ddx, ddy):
        return D.f32const(K.astar_heuristic(CONCRETE, ddx, ddy))

    # setupNavFn + initCost(goal, 0)
    pot = [high] * (nx * ny)
    pending = [False] * (nx * ny)
    k = goal[0] + goal[1] * nx
    pot[k] = D.f32const(0.0)
    cur, nxt, over = empty, empty, empty
    for n in (k + 1, k - 1, k - nx, k + nx):
        if n in cost_int:
            g = D.and_(D.not_(pending[n]), D.lt(cost_int[n], COST_OBS))
            cur = _push(D, cur, g, n)
            pending[n] = D.or_(pending[n], g)
    cur_t = D.f32const(COST_OBS)
    start_cell = start[1] * nx + start[0]
    if astar:
        cur_t = D.add(heuristic(goal[0] - start[0], goal[1] - start[1]), cur_t)
    inc = D.int_to_f32(PRI_INC)
    cycles = 0
    running = True
    trace = []
    for _ in range(cycle_limit(nx, ny)):
        running = D.and_(running, D.not_(D.and_(D.eq(cur.fill, 0), D.eq(nxt.fill, 0))))
        cycles = D.ite(running, D.add_int(cycles, 1), cycles)
        trace.append((running, cur.fill, list(cur.slots)))
        active = [D.and_(running, D.lt(i, cur.fill)) for i in range(n_slots)]
        for i, s in enumerate(cur.slots):
            for m in inner:
                pending[m] = D.and_(pending[m], D.not_(D.and_(active[i], D.eq(s, m))))
        new_nxt, new_over = nxt, over
        for i, s in enumerate(cur.slots):
            for n in inner:
                here = D.and_(active[i], D.eq(s, n))
                l, r, u, d = pot[n - 1], pot[n + 1], pot[n - nx], pot[n + nx]
                new, changed = K.cell_update(D, pot[n], l, r, u, d, cost_int[n], hf[n])
                upd = D.and_(here, changed)
                pot[n] = D.ite(upd, new, pot[n])
                key = D.add(new, heuristic(n % nx - start[0], n // nx - start[1])) if astar else new
                low = K.to_low_buffer(D, key, cur_t)
                for m, pm in ((n - 1, l), (n + 1, r), (n - nx, u), (n + nx, d)):
                    if m not in cost_int:
                        continue  # the border: lethal, never pushed
                    g = D.and_(D.and_(upd, K.push_wanted(D, pm, key, K.edge_weight(D, hf[m]))),
                               D.and_(D.not_(pending[m]), D.lt(cost_int[m], COST_OBS)))
                    new_nxt = _push(D, new_nxt, D.and_(g, low), m)
                    new_over = _push(D, new_over, D.and_(g, D.not_(low)), m)
                    pending[m] = D.or_(pending[m], g)
        # swap: next becomes current; an empty one pulls in the overflow and raises curT
        drained = D.eq(new_nxt.fill, 0)
        swapped_cur = _choose(D, drained, new_over, new_nxt)
        swapped_over = _choose(D, drained, empty, new_over)
        cur = _choose(D, running, swapped_cur, cur)
        over = _choose(D, running, swapped_over, over)
        nxt = _choose(D, running, empty, nxt)
        cur_t = D.ite(D.and_(running, drained), D.add(cur_t, inc), cur_t)
        running = D.and_(running, D.not_(D.lt(pot[start_cell], high)))
    reached = D.lt(pot[start_cell], high)
    if not astar:  # Dijkstra returns cycle < cycles: true when it stopped early
        reached = D.not_(running)
    return SymbolicPropagation(nx, ny, pot, reached, cycles, pending, trace)
