"""The complete run of NavFn on a small map (propagation and path extraction), as domain terms.

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
from ..spec.constants import COST_OBS, PATH_STEP, POT_HIGH, PRI_INC, PRIORITYBUFSIZE
from ..spec import extraction as E
from ..spec.extraction import EXIT_UNDEFINED, ExtractionExit, exit_code
from ..spec.fix import DESCENT_GOES_ON
from ..spec.numeric import CONCRETE
from ..spec.planner import AS_SHIPPED, Fix
from ..spec.propagation import call_ends_at_the_start, cycle_runs, update_neighbours


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
    buffers: list = field(default_factory=list)  # every Buffer state the run passes through
    start_certain: object = None  # branches recorded when the start's reach became certain (see _queued)


def _interior(nx: int, ny: int) -> list[int]:
    return [y * nx + x for y in range(1, ny - 1) for x in range(1, nx - 1)]


def _push(D, buf: Buffer, guard, cell: int) -> Buffer:
    """``buf[fill] = cell; fill++`` under ``guard``."""
    slots = [D.ite(D.and_(guard, D.eq(buf.fill, j)), cell, s) for j, s in enumerate(buf.slots)]
    return Buffer(slots, D.ite(guard, D.add_int(buf.fill, 1), buf.fill))


def _fix(D, c):
    """A condition, or in a domain that follows one control path (``D.decide``, the concolic
    domain) the branch this run takes, as a plain bool: the encoding then builds only the
    terms of that branch.  Symbolic domains build both."""
    decide = getattr(D, "decide", None)
    return c if decide is None or isinstance(c, bool) else decide(c)


def _queued(D, buf: Buffer, cell: int) -> bool:
    """Whether ``cell`` is known to be in the buffer: in a domain that follows one control path,
    where fills and slots are plain ints.  A start in the current buffer of a cycle that runs,
    or pushed to the next buffer in a cycle followed by another, is reached in that cycle or
    the next (QueuedStartReached): what the run does after cannot unreach it."""
    return (getattr(D, "decide", None) is not None and isinstance(buf.fill, int)
            and any(isinstance(s, int) and s == cell for s in buf.slots[:buf.fill]))


def _choose(D, c, a: Buffer, b: Buffer) -> Buffer:
    return Buffer([D.ite(c, x, y) for x, y in zip(a.slots, b.slots)], D.ite(c, a.fill, b.fill))


def propagate(D, costs: dict, nx: int, ny: int, start, goal, astar: bool, fix: Fix = AS_SHIPPED) -> SymbolicPropagation:
    """Propagation on an ``nx`` x ``ny`` map; ``costs[k]`` is interior cell k's cost as a domain
    byte (``D.cost(...)``) or an int.  Border cells are COST_OBS.  ``fix``: its hooks of
    ``calcNavFn*`` (:func:`navfn_smt.spec.planner.calc_navfn`): the cycles of the first
    ``propNavFn*`` call, and a further call where its test holds, only in a domain that follows
    one control path (the concolic domain), which decides whether it calls.  The loop's tests are
    the spec's (``cycle_runs``, ``call_ends_at_the_start``, the fix's test)."""
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
            g = K.push_admitted(D, n, nx * ny, pending[n], cost_int[n], cur.fill, PRIORITYBUFSIZE)
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
    buffers = [cur]
    limit, calls, in_call = fix.cycles(nx, ny), 0, 0
    certain = None
    while True:
        if in_call == limit:  # propNavFn* returns; the fix calls it once more where it must
            if fix.further is None or calls:
                break
            again = _fix(D, fix.further.test(D, pot[start_cell], cur.fill, nxt.fill))
            if again is False:
                break
            if again is not True:
                raise ValueError(f"the {fix.name} planner's further call is encoded only in a domain that follows "
                                 f"one control path")
            calls, limit = 1, fix.further.cycles(nx, ny)
            if astar:  # curT += dist at the entry of propNavFnAstar
                cur_t = D.add(heuristic(goal[0] - start[0], goal[1] - start[1]), cur_t)
            running, in_call = True, 0
        running = D.and_(running, cycle_runs(D, in_call, limit, cur.fill, nxt.fill))
        in_call += 1
        if certain is None and running is True and _queued(D, cur, start_cell):
            certain = len(D.branches)
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
                if here is False:
                    continue  # a domain that follows one control path knows this slot is not cell n
                around = update_neighbours(n, nx)
                l, r, u, d = (pot[j] for j in around)
                new, changed = K.cell_update(D, pot[n], l, r, u, d, cost_int[n], hf[n])
                upd = _fix(D, D.and_(here, changed))
                if upd is False:
                    continue
                pot[n] = D.ite(upd, new, pot[n])
                key = D.add(new, heuristic(n % nx - start[0], n // nx - start[1])) if astar else new
                low = _fix(D, K.to_low_buffer(D, key, cur_t))
                for m, pm in zip(around, (l, r, u, d)):
                    if m not in cost_int:
                        continue  # the border: lethal, never pushed
                    fill = D.ite(low, new_nxt.fill, new_over.fill)
                    g = _fix(D, D.and_(D.and_(upd, K.push_wanted(D, pm, key, K.edge_weight(D, hf[m]))),
                                       K.push_admitted(D, m, nx * ny, pending[m], cost_int[m], fill,
                                                       PRIORITYBUFSIZE)))
                    new_nxt = _push(D, new_nxt, D.and_(g, low), m)
                    if certain is None and m == start_cell and in_call < limit and _queued(D, new_nxt, m):
                        certain = len(D.branches)
                    new_over = _push(D, new_over, D.and_(g, D.not_(low)), m)
                    pending[m] = D.or_(pending[m], g)
        # swap: next becomes current; an empty one pulls in the overflow and raises curT
        drained = D.eq(new_nxt.fill, 0)
        swapped_cur = _choose(D, drained, new_over, new_nxt)
        swapped_over = _choose(D, drained, empty, new_over)
        cur = _choose(D, running, swapped_cur, cur)
        over = _choose(D, running, swapped_over, over)
        nxt = _choose(D, running, empty, nxt)
        buffers += [new_nxt, new_over, cur, over]
        cur_t = D.ite(D.and_(running, drained), D.add(cur_t, inc), cur_t)
        running = _fix(D, D.and_(running, D.not_(call_ends_at_the_start(D, pot[start_cell]))))
    reached = D.lt(pot[start_cell], high)
    if not astar:  # Dijkstra returns cycle < cycles: true when it stopped early
        reached = D.not_(running)
    return SymbolicPropagation(nx, ny, pot, reached, cycles, pending, trace, buffers, certain)


# ---------------------------------------------------------------------------------------
# Path extraction: calcPath(n) over a symbolic potential
# ---------------------------------------------------------------------------------------
RUNNING = -1  # calcPath has not exited yet (beside the exits' ints, spec.extraction.EXIT_CODES)


@dataclass
class SymbolicExtraction:
    """Terms after ``calcPath(n)``: the exit code, and per iteration the point it appended.

    ``points[i] = (x, y, written)``: iteration ``i`` appended ``(x, y)`` when ``written``.
    The returned path (exit ``NEAR_GOAL``) is the written points followed by the goal."""

    exit: object
    points: list
    goal_point: tuple  # the (x, y) appended on success


def _mux(D, sel, value, keys):
    """``value(sel)`` for an int ``sel`` known to be one of ``keys``: a chain of ``ite`` over the
    keys, or the one value when ``sel`` is a plain int."""
    if isinstance(sel, int):
        return value(sel)
    keys = list(keys)
    out = value(keys[-1])
    for k in reversed(keys[:-1]):
        out = D.ite(D.eq(sel, k), value(k), out)
    return out


def extract(D, pot: list, nx: int, ny: int, start, goal, n: int) -> SymbolicExtraction:
    """``calcPath(n)`` from ``start`` on potentials ``pot`` (terms), as in
    :func:`navfn_smt.spec.extraction.calc_path`.

    The current cell ``stc`` is an int term; whatever depends on it (its potential, its
    eight-cell ring, the four gradients around the offset, the path point) is the kernel's
    value at every possible cell, selected by ``stc``.  gradCell's cache does not change
    what it returns (the potential is fixed during extraction), so each cell's gradient is
    one term, computed by ``K.grad_cell`` when first needed; rows 0 and ``ny - 1`` keep the
    zero ``setupNavFn`` wrote, and cell ``ns - nx`` is the C++'s out-of-bounds read."""
    ns = nx * ny
    cells = range(ns)
    zero = D.f32const(0.0)
    grads: dict = {}

    def grad(m):
        if m not in grads:
            if m < nx or m >= ns - nx:
                grads[m] = (zero, zero)
            else:
                grads[m] = K.grad_cell(D, pot[m], pot[m - 1], pot[m + 1], pot[m - nx], pot[m + nx])
        return grads[m]

    ring_offsets = (-nx - 1, -nx, -nx + 1, -1, 1, nx - 1, nx, nx + 1)
    inside = [c for c in cells if c - nx - 1 >= 0 and c + nx + 1 < ns]
    step = D.f32const(PATH_STEP)
    code = RUNNING
    stc = start[1] * nx + start[0]
    dx = dy = zero
    points: list = []
    for i in range(n):
        if isinstance(code, int) and code != RUNNING:
            break  # a plain exit code: this run has left the loop
        running = D.eq(code, RUNNING)
        near = K.nearest_cell(D, stc, dx, dy, nx, ns)
        at_goal = _fix(D, K.near_goal(D, _mux(D, near, pot.__getitem__, cells)))
        oob = _fix(D, E.off_the_rows(D, stc, nx, ns))
        ub_ring = _fix(D, E.ring_leaves_the_array(D, stc, nx, ns))
        x0, y0 = dx, dy
        px = _mux(D, stc, lambda c: K.path_point(D, c, nx, x0, y0)[0], cells)
        py = _mux(D, stc, lambda c: K.path_point(D, c, nx, x0, y0)[1], cells)
        written = D.and_(running, D.not_(D.or_(at_goal, D.or_(oob, ub_ring))))
        points.append((px, py, written))
        if written is False:
            new_code = D.ite(at_goal, exit_code(ExtractionExit.NEAR_GOAL),
                             D.ite(oob, exit_code(ExtractionExit.OUT_OF_BOUNDS), EXIT_UNDEFINED))
            code = D.ite(running, new_code, code)
            continue
        osc = False
        if i >= 2:
            qx, qy, _ = points[i - 2]
            osc = E.oscillates(D, px, py, qx, qy)
        centre = _mux(D, stc, pot.__getitem__, inside)
        ring = [_mux(D, stc, lambda c, o=o: pot[c + o], inside) for o in ring_offsets]
        fallback = _fix(D, E.grid_wanted(D, centre, ring, osc))
        stc_fb = stc_step = stuck = ub_grad = flat = False
        ndx = ndy = zero
        if fallback is not False:
            best = K.lowest_of_eight(D, centre, ring)
            moved = D.add_int(stc, _mux(D, best, ring_offsets.__getitem__, range(8)))
            stc_fb = D.ite(D.lt(best, 0), stc, moved)
            stuck = _fix(D, K.unreached(D, _mux(D, stc_fb, pot.__getitem__, cells)))
        if fallback is not True:
            down = D.add_int(stc, nx)
            for c in (stc, D.add_int(stc, 1), down, D.add_int(down, 1)):
                ub_grad = D.or_(ub_grad, D.eq(c, ns - nx))
            ub_grad = _fix(D, ub_grad)
            if ub_grad is not True:
                g = [[_mux(D, stc, lambda c, o=o, a=a: grad(c + o)[a], inside) for o in (0, 1, nx, nx + 1)]
                     for a in (0, 1)]
                x = K.interpolate_gradient(D, dx, dy, *g[0])
                y = K.interpolate_gradient(D, dx, dy, *g[1])
                flat = _fix(D, E.zero_gradient(D, x, y))
                if flat is not True:
                    ndx, ndy, cdx, cdy = K.step_offsets(D, dx, dy, x, y, step)
                    stc_step = D.add_int(D.add_int(stc, cdx), cdy * nx)
        # the outcome of the iteration, in the C++ order of its tests
        new_code = D.ite(at_goal, exit_code(ExtractionExit.NEAR_GOAL),
                   D.ite(oob, exit_code(ExtractionExit.OUT_OF_BOUNDS),
                   D.ite(ub_ring, EXIT_UNDEFINED,
                   D.ite(fallback, D.ite(stuck, exit_code(ExtractionExit.HIGH_POTENTIAL), RUNNING),
                   D.ite(ub_grad, EXIT_UNDEFINED,
                   D.ite(flat, exit_code(ExtractionExit.ZERO_GRADIENT), RUNNING))))))
        code = D.ite(running, new_code, code)
        keep = D.not_(running)
        stc = D.ite(keep, stc, D.ite(fallback, stc_fb, stc_step))
        dx = D.ite(keep, dx, D.ite(fallback, zero, ndx))
        dy = D.ite(keep, dy, D.ite(fallback, zero, ndy))
    code = D.ite(D.eq(code, RUNNING), exit_code(ExtractionExit.EXHAUSTED), code)
    return SymbolicExtraction(code, points, (D.int_to_f32(goal[0]), D.int_to_f32(goal[1])))


class _HighOffTheArray:
    """``potarr[i]`` of a list of terms, POT_HIGH outside it (the descent reads its ring before its
    bounds test, which refuses such a read before it counts)."""

    def __init__(self, D, pot: list):
        self.pot, self.high = pot, D.f32const(POT_HIGH)

    def __getitem__(self, i: int):
        return self.pot[i] if 0 <= i < len(self.pot) else self.high


def descend(D, pot: list, nx: int, ny: int, start, goal, n: int, fix: Fix) -> SymbolicExtraction:
    """The fallback of ``fix`` (the fix of docs/fix.md's ``calcPathDescent(n)``) on potentials
    ``pot`` (terms): the spec's loop iteration (``fix.fallback.iteration``) run until it stops, only
    in a domain that follows one control path (each step's choice, the kernel
    ``lowest_neighbour``, is decided, so the cell stays a plain int)."""
    iteration = fix.fallback.iteration
    ns = nx * ny
    zero = D.f32const(0.0)
    stc, goal_cell = start[1] * nx + start[0], goal[1] * nx + goal[0]
    points: list = []
    reader = _HighOffTheArray(D, pot)

    def end(code) -> SymbolicExtraction:
        return SymbolicExtraction(code, points, (D.int_to_f32(goal[0]), D.int_to_f32(goal[1])))

    if _decided(D, K.unreached(D, pot[stc])):
        return end(exit_code(ExtractionExit.HIGH_POTENTIAL))
    while True:
        code, nxt = iteration(D, reader, stc, len(points), n, nx, ns, goal_cell)
        if not isinstance(code, int) or not isinstance(nxt, int):
            raise ValueError("the fallback is encoded only in a domain that follows one control path")
        if code != DESCENT_GOES_ON:  # the goal point is the extraction's own last point (SymbolicExtraction)
            return end(code)
        px, py = K.path_point(D, stc, nx, zero, zero)
        points.append((px, py, True))
        stc = nxt
def _decided(D, c) -> bool:
    """A condition as the plain bool of this control path (recorded as a branch when open)."""
    c = _fix(D, c)
    if not isinstance(c, bool):
        raise ValueError("the fix's descent is encoded only in a domain that follows one control path")
    return c
