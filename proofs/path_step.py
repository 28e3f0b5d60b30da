"""FinitePotentialPath and ValidPath: the steps of path extraction stay where the
potential is known.

The gradient step is taken only from a cell whose eight neighbours are all reached; the
obligations below show that one step (interpolate, advance by ``pathStep``, normalise the
offset) keeps the offset in [-1, 1] and moves the cell by at most one in each direction,
so every point emitted lies among the reached cells around the previous cell, and the
near-goal probe reads one of those cells.

In float32 the step fails for a subnormal gradient: ``pathStep / hypotf(x, y)``
overflows to infinity and the offset with it.  The interpolated gradient is a weighted
mean of unit vectors; the step is proved for every gradient whose larger component is at
least 2**-100 (anything that does not cancel to nearly nothing).
"""

from navfn_smt.smt.obligation import obligation
from navfn_smt.smt.predicates import InUnitBox, all_of
from navfn_smt.spec import kernels as K
from navfn_smt.spec.constants import PATH_STEP


def _unit_interval(D, v):
    return D.and_(D.ge(v, D.f32const(-1.0)), D.le(v, D.f32const(1.0)))


def _step(D, least):
    dx, dy, x, y = (D.f32(v) for v in ("dx", "dy", "x", "y"))
    ndx, ndy, cdx, cdy = K.step_offsets(D, dx, dy, x, y, D.f32const(PATH_STEP))
    zero = D.f32const(0.0)
    big_enough = D.not_(D.and_(D.eq(x, zero), D.eq(y, zero)))
    if least is not None:
        m = D.f32const(least)
        big_enough = D.or_(D.or_(D.ge(x, m), D.le(x, D.neg(m))), D.or_(D.ge(y, m), D.le(y, D.neg(m))))
    pre = all_of(D, InUnitBox(D, dx, dy), _unit_interval(D, x), _unit_interval(D, y), big_enough)
    moves = all_of(D, D.ge(cdx, -1), D.le(cdx, 1), D.ge(cdy, -1), D.le(cdy, 1))
    return pre, D.and_(InUnitBox(D, ndx, ndy), moves)


@obligation("FinitePotentialPath", expect={"real": "proved", "fp32": "proved"},
            scope="one gradient step from any offset in the unit box: every map size")
def step_keeps_offset_in_unit_box(D):
    """One step of calcPath keeps the offset in [-1, 1] and moves at most one cell per axis.

    |dx|, |dy| <= 1, gradient components in [-1, 1], max(|x|, |y|) >= 2**-100
    ==>  new |dx|, |dy| <= 1  and  cell moves in {-1, 0, 1}
    """
    return _step(D, 2.0**-100)


# the counterexample needs only hypotf's documented accuracy (much faster for the solvers than
# glibc's exact definition); it is replayed with the real libm
@obligation("FinitePotentialPath", expect={"real": "proved", "fp32": "refuted"},
            scope="one gradient step from any offset in the unit box, any non-zero gradient: every map size",
            hypotf_model="ulp")
def step_keeps_offset_in_unit_box_any_gradient(D):
    """The same for any non-zero gradient, subnormal ones included (fails in float32).

    |dx|, |dy| <= 1, gradient components in [-1, 1], not both zero  ==>  new |dx|, |dy| <= 1
    """
    return _step(D, None)


@obligation("FinitePotentialPath", expect={"real": "proved", "fp32": "proved"},
            scope="any offset in the unit box, any interior cell of any map up to 2**12 cells a side")
def near_goal_probe_reads_a_neighbour(D):
    """The near-goal probe reads a cell at most one away in each direction.

    |dx|, |dy| <= 1, 1 <= x < nx - 1, 1 <= y < ny - 1  ==>  probe = stc + ox + oy*nx with |ox|, |oy| <= 1
    """
    dx, dy = D.f32("dx"), D.f32("dy")
    ox = D.to_int32(D.roundf(dx))
    oy = D.to_int32(D.roundf(dy))
    pre = InUnitBox(D, dx, dy)
    return pre, all_of(D, D.ge(ox, -1), D.le(ox, 1), D.ge(oy, -1), D.le(oy, 1))


@obligation("ValidPath", expect={"real": "proved", "fp32": "proved"},
            scope="any start cell of any map up to 2**24 cells a side")
def first_point_is_the_start(D):
    """The first point calcPath emits is the start cell exactly (offset 0, int converted to float).

    0 <= sx, sy < 2**24  ==>  (float)sx + 0.0f == sx  and  (float)sy + 0.0f == sy  (as reals)
    """
    sx, sy = D.int32("sx"), D.int32("sy")
    zero = D.f32const(0.0)
    px = D.add(D.int_to_f32(sx), zero)
    py = D.add(D.int_to_f32(sy), zero)
    pre = all_of(D, D.ge(sx, 0), D.lt(sx, 2**24), D.ge(sy, 0), D.lt(sy, 2**24))
    back_x = D.to_int32(px)
    back_y = D.to_int32(py)
    return pre, D.and_(D.eq(back_x, sx), D.eq(back_y, sy))
