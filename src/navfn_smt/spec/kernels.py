"""The numeric heart of NavFn, written once over a numeric domain ``D``.

Every function here takes the domain as its first argument and uses only its
operations (see :class:`navfn_smt.spec.numeric.ConcreteDomain`), so the same code
computes concrete float32 results for the reference spec and builds bit-precise or
real-valued terms for the SMT obligations.  Branches of the C++ become ``D.ite``.

Each kernel names the C++ it stands for and says which operations happen in
``float`` and which in ``double``.  The steps of the loops that touch the buffers (a push,
the end of a cycle) are kernels too; the loops around them (the order of the cells, the
buffers' slots, path iterations) live in :mod:`.propagation` and :mod:`.extraction`.
"""

from __future__ import annotations

from .constants import (
    COST_NEUTRAL,
    COST_OBS,
    INVSQRT2,
    POT_HIGH,
    QUAD_A,
    QUAD_B,
    QUAD_C,
)


# --------------------------------------------------------------------------------------
# Propagation: updateCell / updateCellAstar
# --------------------------------------------------------------------------------------
def planar_wave(D, l, r, u, d, hf):
    """Candidate potential of a passable cell (the arithmetic of ``updateCell``).

    ``l r u d`` are the float potentials of the left, right, up and down neighbours and
    ``hf`` is the cell's cost as a float.  In C++::

        tc = l < r ? l : r;  ta = u < d ? u : d;        // float
        dc = tc - ta;  if (dc < 0) { dc = -dc; ta = tc; }
        if (dc >= hf) pot = ta + hf;                      // float
        else { div = dc / hf;                             // float
               v = -0.2301*div*div + 0.5307*div + 0.7040; // double, narrowed to float
               pot = ta + hf * v; }                       // float

    Two multiply-adds a compiler may fuse (:func:`mul_add64`, :func:`add_mul`): the quadratic's
    ``(-0.2301*div)*div + 0.5307*div`` and ``ta + hf * v``.
    """
    zero = D.f32const(0.0)
    tc = D.ite(D.lt(l, r), l, r)
    ta0 = D.ite(D.lt(u, d), u, d)
    dc0 = D.sub(tc, ta0)
    swap = D.lt(dc0, zero)
    dc = D.ite(swap, D.neg(dc0), dc0)
    ta = D.ite(swap, tc, ta0)
    w = D.widen(D.div(dc, hf))
    aw, bw = D.mul64(D.f64const(QUAD_A), w), D.mul64(D.f64const(QUAD_B), w)
    quad = D.add64(mul_add64(D, "quadratic", aw, w, bw), D.f64const(QUAD_C))
    v = D.narrow(quad)
    return D.ite(D.ge(dc, hf), D.add(ta, hf), add_mul(D, "planar", ta, hf, v))


def mul_add64(D, site, a, b, c):
    """``a * b + c`` in double at the contractible ``site`` (:data:`~.arithmetic.SITES`): one
    rounding (``fma``) where the build fused it, the product rounded first otherwise."""
    return D.fma64(a, b, c) if D.fuses(site) else D.add64(D.mul64(a, b), c)


def add_mul(D, site, c, a, b):
    """``c + a * b`` in float at the contractible ``site``: one rounding (``fmaf``) where the
    build fused it, the product rounded first otherwise."""
    return D.fma(a, b, c) if D.fuses(site) else D.add(c, D.mul(a, b))


def cell_update(D, old, l, r, u, d, cost, hf):
    """One ``updateCell`` on a cell's potential: ``(new potential, changed)``.

    ``cost`` is the cell's cost as an int and ``hf`` the same as a float.  An obstacle
    (``cost >= COST_OBS``) is left alone; otherwise the planar-wave candidate replaces
    the old potential only when it is strictly lower (``if (pot < potarr[n])``).
    """
    cand = planar_wave(D, l, r, u, d, hf)
    changed = D.and_(is_passable(D, cost), D.lt(cand, old))
    return D.ite(changed, cand, old), changed


def edge_weight(D, hf_neighbour):
    """``INVSQRT2 * static_cast<float>(costarr[m])``: a double product narrowed to float."""
    return D.narrow(D.mul64(D.f64const(INVSQRT2), D.widen(hf_neighbour)))


def astar_heuristic(D, ddx, ddy):
    """``hypot(ddx, ddy) * static_cast<float>(COST_NEUTRAL)`` with int ``ddx, ddy``.

    ``hypot`` of two ints is the double ``hypot``; the product is double and is narrowed
    to float when it is stored (``float dist = ...``).
    """
    h = D.hypot64(D.int_to_f64(ddx), D.int_to_f64(ddy))
    return D.narrow(D.mul64(h, D.widen(D.f32const(COST_NEUTRAL))))


def push_wanted(D, neighbour_pot, key, weight):
    """``neighbour > key + weight`` (float): whether the update asks to enqueue a neighbour.

    ``key`` is the new potential (Dijkstra) or the new potential plus the A* heuristic.
    The push itself still requires the neighbour to be on the map, not pending, not an
    obstacle and the buffer not full (:func:`push_admitted`).
    """
    return D.gt(neighbour_pot, D.add(key, weight))


def to_low_buffer(D, key, cur_t):
    """``key < curT``: pushes go to the next buffer, otherwise to the overflow buffer."""
    return D.lt(key, cur_t)


def push_admitted(D, n, ns, pending, cost, fill, capacity):
    """The guard of the ``push_*`` macros: on the map, not pending, passable, room left."""
    return D.and_(
        D.and_(D.and_(D.ge(n, 0), D.lt(n, ns)), D.not_(pending)),
        D.and_(D.lt(cost, COST_OBS), D.lt(fill, capacity)),
    )


def push(D, n, ns, pending, cost, fill, capacity):
    """One ``push_cur/push_next/push_over`` macro on cell ``n`` into a buffer holding ``fill``
    cells of ``capacity`` (all ints): ``(admitted, dropped, pending after)``.

    An admitted cell goes into the buffer's slot ``fill`` and its pending flag is set in the
    same step (``pending[n] = true``); ``dropped``: the guard refused the cell only for want
    of room (the C++ drops it silently; the spec counts it).
    """
    admitted = push_admitted(D, n, ns, pending, cost, fill, capacity)
    dropped = D.and_(D.not_(admitted), push_admitted(D, n, ns, pending, cost, 0, 1))
    return admitted, dropped, D.or_(pending, admitted)


def buffer_swap(D, nxt, over, drained):
    """What the current and the overflow buffer hold after a cycle's swap, given what the next
    and the overflow buffer held (fills, or how often a cell occurs: ints): ``(cur, over)``.

    ``curPe = nextPe``, and when that is 0 (``drained``) ``curPe = overPe; overPe = 0``, each
    with its pointer swap; the next buffer is empty after.
    """
    return D.ite(drained, over, nxt), D.ite(drained, 0, over)


def end_of_cycle(D, fill_next, fill_over, cur_t, inc):
    """The end of a cycle of ``propNavFn*``: ``(drained, fill of cur, fill of over, curT)``.

    The next buffer becomes current (:func:`buffer_swap`); when it is empty the overflow
    buffer does, and ``curT += priInc`` (float).
    """
    drained = D.eq(fill_next, 0)
    cur, over = buffer_swap(D, fill_next, fill_over, drained)
    return drained, cur, over, D.ite(drained, D.add(cur_t, inc), cur_t)


def is_passable(D, cost):
    """``costarr[n] < COST_OBS``: updateCell changes nothing on an obstacle."""
    return D.lt(cost, COST_OBS)


# --------------------------------------------------------------------------------------
# Path extraction: gradCell and one step of calcPath
# --------------------------------------------------------------------------------------
def grad_cell(D, cv, pl, pr, pu, pd):
    """The gradient ``gradCell`` stores for a cell of potential ``cv`` (not on the border).

    Returns ``(gx, gy)``: the normalised vector when its norm is positive, otherwise
    ``(0, 0)`` (C++ then leaves ``gradx/grady`` at the zero ``setupNavFn`` wrote).
    """
    dx, dy = grad_vector(D, cv, pl, pr, pu, pd)
    return normalise(D, dx, dy)


def grad_vector(D, cv, pl, pr, pu, pd):
    """gradCell's unnormalised vector (float).  In an unreached cell (``cv >= POT_HIGH``)
    it points by +-COST_OBS towards a reached neighbour; otherwise it is the central
    difference over the reached neighbours (``dx += l - cv; dx += cv - r``)."""
    high = D.f32const(POT_HIGH)
    zero = D.f32const(0.0)
    obs = D.f32const(COST_OBS)
    mobs = D.f32const(-COST_OBS)
    reached_l, reached_r = D.lt(pl, high), D.lt(pr, high)
    reached_u, reached_d = D.lt(pu, high), D.lt(pd, high)
    # cell in an obstacle (unreached)
    dx_obs = D.ite(reached_l, mobs, D.ite(reached_r, obs, zero))
    dy_obs = D.ite(reached_u, mobs, D.ite(reached_d, obs, zero))
    # reached cell: dx += l - cv; dx += cv - r (each only for reached neighbours)
    dx1 = D.ite(reached_l, D.add(zero, D.sub(pl, cv)), zero)
    dx2 = D.ite(reached_r, D.add(dx1, D.sub(cv, pr)), dx1)
    dy1 = D.ite(reached_u, D.add(zero, D.sub(pu, cv)), zero)
    dy2 = D.ite(reached_d, D.add(dy1, D.sub(cv, pd)), dy1)
    unreached = D.ge(cv, high)
    return D.ite(unreached, dx_obs, dx2), D.ite(unreached, dy_obs, dy2)


def normalise(D, dx, dy):
    """gradCell's normalisation: ``norm = hypot(dx, dy)`` (``hypotf``); when positive,
    ``norm = 1.0 / norm`` (double, narrowed) and the stored vector is ``norm * (dx, dy)``
    (float); otherwise the stored vector stays (0, 0)."""
    zero = D.f32const(0.0)
    norm = D.hypotf(dx, dy)
    inv = D.narrow(D.div64(D.f64const(1.0), D.widen(norm)))
    positive = D.gt(norm, zero)
    return D.ite(positive, D.mul(inv, dx), zero), D.ite(positive, D.mul(inv, dy), zero)


def grad_cached(D, gx, gy):
    """``gradx[n] + grady[n] > 0.0``: gradCell returns early, keeping the stored vector."""
    return D.gt(D.add(gx, gy), D.f32const(0.0))


def bilinear(D, t, a, b):
    """``(1.0 - t) * a + t * b`` with float ``t a b``: the left product is double, the
    right product float (``t * b`` are both floats), the sum double, narrowed to float.  A
    build that contracts fuses the left product with the sum (site ``bilinear``)."""
    right = D.widen(D.mul(t, b))
    return D.narrow(mul_add64(D, "bilinear", D.sub64(D.f64const(1.0), D.widen(t)), D.widen(a), right))


def interpolate_gradient(D, dx, dy, g00, g10, g01, g11):
    """Bilinear interpolation of one gradient component over the four cells
    ``stc, stc+1, stc+nx, stc+nx+1`` at offset ``(dx, dy)`` (calcPath's x1, x2, x)."""
    top = bilinear(D, dx, g00, g10)
    bottom = bilinear(D, dx, g01, g11)
    return bilinear(D, dy, top, bottom)


def step_offsets(D, dx, dy, x, y, path_step):
    """Advance the offset by ``path_step`` along ``(x, y)`` and normalise it.

    ``ss = pathStep / hypotf(x, y); dx += x*ss; dy += y*ss`` (all float; each a
    multiply-add a build may fuse, site ``path_step``), then :func:`wrap_offsets`.  Returns
    ``(dx, dy, cell_dx, cell_dy)``.
    """
    ss = D.div(path_step, D.hypotf(x, y))
    return wrap_offsets(D, add_mul(D, "path_step", dx, x, ss), add_mul(D, "path_step", dy, y, ss))


def wrap_offsets(D, ndx, ndy):
    """calcPath's four sequential overflow tests on the advanced offset: ``dx > 1.0`` moves
    one cell right and subtracts 1.0 (double, narrowed), and so on.  Returns
    ``(dx, dy, cell_dx, cell_dy)`` where the cell moves are ints in {-1, 0, 1}."""
    one = D.f64const(1.0)
    mone = D.f64const(-1.0)
    right = D.gt(D.widen(ndx), one)
    ndx = D.ite(right, D.narrow(D.sub64(D.widen(ndx), one)), ndx)
    left = D.lt(D.widen(ndx), mone)
    ndx = D.ite(left, D.narrow(D.add64(D.widen(ndx), one)), ndx)
    down = D.gt(D.widen(ndy), one)
    ndy = D.ite(down, D.narrow(D.sub64(D.widen(ndy), one)), ndy)
    up = D.lt(D.widen(ndy), mone)
    ndy = D.ite(up, D.narrow(D.add64(D.widen(ndy), one)), ndy)
    cdx = D.ite(right, 1, 0) + D.ite(left, -1, 0)
    cdy = D.ite(down, 1, 0) + D.ite(up, -1, 0)
    return ndx, ndy, cdx, cdy


def nearest_cell(D, stc, dx, dy, nx, ns):
    """calcPath's near-goal probe::

        max(0, min(nx*ny - 1, stc + (int)roundf(dx) + (int)(nx * roundf(dy))))

    ``nx * roundf(dy)`` is a float product (int ``nx`` converted to float) before the
    truncating conversion to int.  The sum overflows only for offsets no extraction
    produces (|dx| beyond 2**31); it then wraps, as the compiled x86-64 code does.
    """
    ox = D.to_int32(D.roundf(dx))
    oy = D.to_int32(D.mul(D.int_to_f32(nx), D.roundf(dy)))
    idx = D.add_int(D.add_int(stc, ox), oy)  # int additions wrap on overflow, as on x86-64
    idx = D.ite(D.lt(ns - 1, idx), ns - 1, idx)
    return D.ite(D.lt(idx, 0), 0, idx)


def path_point(D, stc, nx, dx, dy):
    """``pathx = stc % nx + dx; pathy = stc / nx + dy``: int converted to float, float add."""
    return D.add(D.int_to_f32(stc % nx), dx), D.add(D.int_to_f32(stc // nx), dy)


def lowest_of_eight(D, centre, neighbours):
    """The grid-following fallback: index into ``neighbours`` of the lowest, or -1.

    ``int minp = potarr[stc]`` truncates (x86-64: INT_MIN when out of range); each of
    the eight neighbours, in the C++ order (up-left, up, up-right, left, right,
    down-left, down, down-right), replaces the minimum when ``potarr[m] < minp``, a
    float comparison against ``(float)minp``, and ``minp`` becomes its truncation.
    """
    minp = D.to_int32(centre)
    best = -1
    for k, p in enumerate(neighbours):
        better = D.lt(p, D.int_to_f32(minp))
        minp = D.ite(better, D.to_int32(p), minp)
        best = D.ite(better, k, best)
    return best


def lowest_neighbour(D, centre, neighbours):
    """The fix's descent step (``calcPathDescent``): index into ``neighbours`` (the 8 around the
    cell in calcPath's order: up-left, up, up-right, left, right, down-left, down, down-right)
    of the lowest potential strictly below ``centre``, the first on ties; -1 when none is lower.
    Float comparisons only, no truncation (unlike :func:`lowest_of_eight`)::

        next = stc;  if (potarr[m] < potarr[next]) next = m;   // for each m in order
    """
    low = centre
    best = -1
    for k, p in enumerate(neighbours):
        better = D.lt(p, low)
        low = D.ite(better, p, low)
        best = D.ite(better, k, best)
    return best


def near_goal(D, pot):
    """``potarr[nearest_point] < COST_NEUTRAL`` (float compared with an int)."""
    return D.lt(pot, D.f32const(COST_NEUTRAL))


def unreached(D, pot):
    """``pot >= POT_HIGH``."""
    return D.ge(pot, D.f32const(POT_HIGH))
