"""FinitePotentialPath and ValidPath: every point extraction emits lies in a reached cell.

The paper's FinitePotentialPath: each point of the path lies within 1/2 (each axis, ends
included) of a cell whose potential is finite; with PositionSafe that cell is no obstacle,
so the path is a ValidPath.  The argument is an induction over calcPath's iterations: the
first point is the start cell exactly (or calcPath fails at an unreached start); a
fallback step lands on a reached cell exactly; a gradient step, taken only when the nine
cells around are reached, keeps the offset in [-1, 1] with a bounded gradient and puts the
next point within 3/2 of the old cell, hence within 1/2 of one of those nine.  Its chain
(base case, lemmas in order, the steps taken from calcPath's control flow, what is open) is
stated as data in :data:`navfn_smt.proofs.FinitePotentialPath` and
:data:`navfn_smt.proofs.ValidPath`, and checked against the obligations below.

Each obligation is about one step over a symbolic neighbourhood, so the induction holds
for maps of every size (up to the stated coordinate bounds).

One precondition is not discharged: the interpolated gradient is either exactly zero
(calcPath then fails) or has a component of at least 2**-100.  In float32 a nonzero
gradient below that can make ``pathStep / hypotf(x, y)`` overflow, and the offset becomes
infinite (``step_keeps_offset_in_unit_box_any_gradient`` is refuted).  The precondition
itself is refuted for one step (``interpolated_gradient_is_zero_or_not_tiny``): a subnormal
offset next to a cell whose stored gradient is zero interpolates to a gradient of about
2**-130.  Whether calcPath's own offsets, which start at 0 and move by about half a cell,
can become that small is open.
"""

from navfn_smt.proofs import FinitePotentialPath, ValidPath
from navfn_smt.smt.obligation import obligation
from navfn_smt.smt.predicates import GradDifference, InUnitBox, all_of
from navfn_smt.smt.split import f32_interval, product, split
from navfn_smt.spec import kernels as K
from navfn_smt.spec.constants import PATH_STEP


def _within(D, v, m):
    return D.and_(D.ge(v, D.f32const(-m)), D.le(v, D.f32const(m)))


# bound on a stored gradient component (stored_gradient_is_bounded); loose on purpose: the
# chain needs only some bound, and a loose one is decided in seconds (a tight one is not)
UNIT_SLACK = 2.0
# bound on the interpolated gradient (interpolated_gradient_is_bounded): 3 * 3 * UNIT_SLACK
GRAD_BOUND = 20.0


# the interpolated gradient's larger component is at least this (the undischarged precondition)
LEAST_GRADIENT = 2.0**-100


def _gradient_step(D, least=LEAST_GRADIENT):
    """One gradient step from a symbolic offset: ``(pre, (dx', dy', cdx, cdy))``; ``pre`` holds
    the offset in the unit box and the gradient bounded and, if ``least`` is given, with a
    component of at least ``least`` (otherwise only not both zero)."""
    dx, dy, x, y = (D.f32(v) for v in ("dx", "dy", "x", "y"))
    zero = D.f32const(0.0)
    big_enough = D.not_(D.and_(D.eq(x, zero), D.eq(y, zero)))
    if least is not None:
        m = D.f32const(least)
        big_enough = D.or_(D.or_(D.ge(x, m), D.le(x, D.neg(m))), D.or_(D.ge(y, m), D.le(y, D.neg(m))))
    pre = all_of(D, InUnitBox(D, dx, dy), _within(D, x, GRAD_BOUND), _within(D, y, GRAD_BOUND), big_enough)
    return pre, K.step_offsets(D, dx, dy, x, y, D.f32const(PATH_STEP))


def _step(D, least):
    pre, (ndx, ndy, cdx, cdy) = _gradient_step(D, least)
    moves = all_of(D, D.ge(cdx, -1), D.le(cdx, 1), D.ge(cdy, -1), D.le(cdy, 1))
    return pre, D.and_(InUnitBox(D, ndx, ndy), moves)


@obligation(FinitePotentialPath, expect={"real": "proved", "fp32": "proved",
                                         "fp32@x86-64-v3": "proved", "fp32@aarch64": "proved"},
            scope="one gradient step from any offset in the unit box: every map size")
def step_keeps_offset_in_unit_box(D):
    """One step of calcPath keeps the offset in [-1, 1] and moves at most one cell per axis.

    |dx|, |dy| <= 1, |x|, |y| <= 20, max(|x|, |y|) >= 2**-100
    ==>  new |dx|, |dy| <= 1  and  cell moves in {-1, 0, 1}
    """
    return _step(D, LEAST_GRADIENT)


# the counterexample needs only hypotf's documented accuracy (much faster for the solvers than
# glibc's exact definition); it is replayed with the real libm
@obligation(FinitePotentialPath, expect={"real": "proved", "fp32": "refuted",
                                         "fp32@x86-64-v3": "refuted", "fp32@aarch64": "refuted"},
            scope="one gradient step from any offset in the unit box, any non-zero gradient: every map size",
            hypotf_model="ulp")
def step_keeps_offset_in_unit_box_any_gradient(D):
    """The same for any non-zero gradient, subnormal ones included (fails in float32).

    |dx|, |dy| <= 1, |x|, |y| <= 20, not both zero  ==>  new |dx|, |dy| <= 1
    """
    return _step(D, None)


def _near(D, s, cell_move, offset):
    """The next point's coordinate, as calcPath computes it (int to float, float add), is within
    3/2 of cell ``s``: its distance from ``s`` is computed in double, where it is exact."""
    point = D.add(D.int_to_f32(D.add_int(s, cell_move)), offset)
    dist = D.sub64(D.widen(point), D.int_to_f64(s))
    return D.and_(D.le(dist, D.f64const(1.5)), D.ge(dist, D.f64const(-1.5)))


@obligation(FinitePotentialPath, expect={"real": "proved", "fp32": "proved",
                                         "fp32@x86-64-v3": "proved", "fp32@aarch64": "proved"},
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


@obligation(ValidPath, expect={"real": "proved", "fp32": "proved",
                               "fp32@x86-64-v3": "proved", "fp32@aarch64": "proved"},
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


# needs only that hypotf lies between the larger magnitude and the sum of magnitudes
@obligation(FinitePotentialPath, expect={"real": "proved", "fp32": "proved",
                                         "fp32@x86-64-v3": "proved", "fp32@aarch64": "proved"},
            scope="gradCell's normalisation of any vector whose components are 0 or in [2**-25, 2**35]",
            hypotf_model="bounds")
def stored_gradient_is_bounded(D):
    """gradCell stores components of magnitude at most 2 (with grad_differences_are_not_tiny, on
    every potential NavFn produces; the unit-length obligation gives 1 over the reals).

    dx, dy each 0 or 2**-25 <= |.| <= 2**35  ==>  |gx|, |gy| <= 2
    """
    dx, dy = D.f32("dx"), D.f32("dy")
    gx, gy = K.normalise(D, dx, dy)
    return D.and_(GradDifference(D, dx), GradDifference(D, dy)), D.and_(_within(D, gx, UNIT_SLACK), _within(D, gy, UNIT_SLACK))


# about 20 s in float32 (bitwuzla), so the proof belongs to the long run (prove --all)
@obligation(FinitePotentialPath, expect={"real": "proved", "fp32": "proved",
                                         "fp32@x86-64-v3": "proved", "fp32@aarch64": "proved"},
            scope="calcPath's bilinear interpolation at any offset in the unit box: every map size",
            slow=("fp32",))
def interpolated_gradient_is_bounded(D):
    """The interpolated gradient is at most 20 in each component (the offset may be negative, so
    the interpolation can extrapolate: up to 3 * 3 times the largest stored component).

    |dx|, |dy| <= 1, the four stored components |g| <= 2  ==>  |x| <= 20
    """
    dx, dy = D.f32("dx"), D.f32("dy")
    g = [D.f32(f"g{k}") for k in range(4)]
    x = K.interpolate_gradient(D, dx, dy, *g)
    pre = all_of(D, InUnitBox(D, dx, dy), *(_within(D, v, UNIT_SLACK) for v in g))
    return pre, _within(D, x, GRAD_BOUND)


# Known in fp32 through FinitePotentialPath's finer links (its `whole`): the axis step bound
# (decided by its split), half_step_keeps_the_point_near_the_cell and the monotonicity of
# rounding (trusted).  Whole, the bound 3/2 is tight (it rests on a tie rounding to even at 1.5)
# and no solver of the portfolio decided it on this machine: with glibc's hypotf all three time
# out at 120 s, and the offset before normalisation alone at 200 s.  A short limit, then: an
# undecided whole query is never a failure.
@obligation(FinitePotentialPath, expect={"real": "proved", "fp32": "proved"},
            scope="one gradient step at any interior cell of any map up to 2**23 cells a side",
            hypotf_model="bounds", timeout=10, slow=("fp32",))
def next_point_stays_near_the_cell(D):
    """After a gradient step from cell (sx, sy) the next point emitted lies within 3/2 of it in
    each axis, so within 1/2 of one of the nine cells around it, all reached when the step is taken.

    1 <= sx, sy < 2**23, |dx|, |dy| <= 1, |x|, |y| <= 20, max(|x|, |y|) >= 2**-100
    ==>  |((float)(sx + cdx) + dx') - sx| <= 3/2  and the same for y
    """
    sx, sy = D.int32("sx"), D.int32("sy")
    step_pre, (ndx, ndy, cdx, cdy) = _gradient_step(D)
    pre = all_of(D, D.ge(sx, 1), D.lt(sx, 2**23), D.ge(sy, 1), D.lt(sy, 2**23), step_pre)

    return pre, D.and_(_near(D, sx, cdx, ndx), _near(D, sy, cdy, ndy))


def _unit_or_zero(D, gx, gy):
    """A stored gradient as the Gradient predicate leaves it: (0, 0) or squared length within 2**-20 of 1."""
    wx, wy = D.widen(gx), D.widen(gy)
    err = D.sub64(D.add64(D.mul64(wx, wx), D.mul64(wy, wy)), D.f64const(1.0))
    tol = D.f64const(2.0**-20)
    zero = D.f32const(0.0)
    unit = D.and_(D.le(err, tol), D.ge(err, D.neg(tol)))
    return D.or_(D.and_(D.eq(gx, zero), D.eq(gy, zero)), unit)


# Known refuted in fp32 from the split below, which finds a witness in seconds (replayed on the
# spec).  Whole, bitwuzla finds one in 10 s to 2 minutes depending on the machine's load, z3 times
# out: either answer is fine, a proof would contradict the split and fail the run.
@obligation(FinitePotentialPath, expect={"real": "refuted", "fp32": "refuted"},
            scope="calcPath's interpolation at any offset in the unit box, of any four stored gradients that are "
                  "unit or zero: every map size", timeout=10, slow=("fp32",))
def interpolated_gradient_is_zero_or_not_tiny(D):
    """The interpolated gradient is exactly zero or has a component of at least 2**-100 (the
    precondition of step_keeps_offset_in_unit_box and next_point_stays_near_the_cell).

    |dx|, |dy| <= 1, the four stored gradients (gx_k, gy_k) zero or of unit length  ==>
    (x, y) = (0, 0)  or  max(|x|, |y|) >= 2**-100
    """
    dx, dy = D.f32("dx"), D.f32("dy")
    gx = [D.f32(f"gx{k}") for k in range(4)]
    gy = [D.f32(f"gy{k}") for k in range(4)]
    x = K.interpolate_gradient(D, dx, dy, *gx)
    y = K.interpolate_gradient(D, dx, dy, *gy)
    zero, least = D.f32const(0.0), D.f32const(LEAST_GRADIENT)
    big = D.or_(D.or_(D.ge(x, least), D.le(x, D.neg(least))), D.or_(D.ge(y, least), D.le(y, D.neg(least))))
    pre = all_of(D, InUnitBox(D, dx, dy), *(_unit_or_zero(D, a, b) for a, b in zip(gx, gy)))
    return pre, D.or_(D.and_(D.eq(x, zero), D.eq(y, zero)), big)


_SMALLEST_NORMAL = 2.0**-126
_LARGEST_SUBNORMAL = _SMALLEST_NORMAL - 2.0**-149


def _offset_pieces(v):
    """An offset in [-1, 1] by kind: subnormal (either sign) first, then zero, then normal."""
    return (f32_interval(v, 2.0**-149, _LARGEST_SUBNORMAL), f32_interval(v, -_LARGEST_SUBNORMAL, -(2.0**-149)),
            f32_interval(v, 0.0, 0.0), f32_interval(v, _SMALLEST_NORMAL, 1.0), f32_interval(v, -1.0, -_SMALLEST_NORMAL))


# Decided by splitting the offsets by kind (25 parts, the cover proved by a solver); the first
# refuted part ends the run, its witness replayed on the concrete spec.
interpolated_gradient_is_zero_or_not_tiny_split = split(
    interpolated_gradient_is_zero_or_not_tiny, product(_offset_pieces("dx"), _offset_pieces("dy")),
    bisect_along=("dx", "dy"), methods=("smt",), part_timeout=60.0, max_depth=2,
    note="the offsets by kind: subnormal, zero or normal, each sign")


# next_point_stays_near_the_cell in two links, each decided (see FinitePotentialPath's chain):
# the step moves the offset by at most 1/2 along each axis, and a move of at most 1/2 keeps the
# point within 3/2 of the cell.  The tie that makes the bound 3/2 tight sits in the second.

@obligation(FinitePotentialPath, expect={"real": "proved", "fp32": "proved",
                                         "fp32@x86-64-v3": "proved", "fp32@aarch64": "proved"},
            scope="one gradient step at any interior cell of any map up to 2**23 cells a side, any move of at "
                  "most 1/2 per axis", slow=("fp32",))
def half_step_keeps_the_point_near_the_cell(D):
    """A gradient step that moves the offset by at most 1/2 per axis puts the next point within
    3/2 of the cell in each axis (``dx += x*ss`` with ``|x*ss| <= 1/2``, then calcPath's wrap).

    1 <= sx, sy < 2**23, |dx|, |dy| <= 1, |tx|, |ty| <= 1/2  ==>
    |((float)(sx + cdx) + dx') - sx| <= 3/2  and the same for y
    """
    sx, sy = D.int32("sx"), D.int32("sy")
    dx, dy, tx, ty = (D.f32(v) for v in ("dx", "dy", "tx", "ty"))
    half = D.f32const(0.5)
    ndx, ndy, cdx, cdy = K.wrap_offsets(D, D.add(dx, tx), D.add(dy, ty))  # dx += x*ss, with tx = x*ss
    pre = all_of(D, D.ge(sx, 1), D.lt(sx, 2**23), D.ge(sy, 1), D.lt(sy, 2**23), InUnitBox(D, dx, dy),
                 _within(D, tx, 0.5), _within(D, ty, 0.5))
    del half
    return pre, D.and_(_near(D, sx, cdx, ndx), _near(D, sy, cdy, ndy))


# Known proved in fp32 from its split below (every float32 enumerated); whole, no solver decides it
# within the proof run's limit.
@obligation(FinitePotentialPath, expect={"real": "proved", "fp32": "proved"},
            scope="a gradient step along one axis, any component from 2**-100 to 20: the largest move the "
                  "step can make (hypotf equals |x| there)", timeout=10, slow=("fp32",))
def step_along_an_axis_moves_at_most_half(D):
    """A gradient step along the x axis moves the offset by at most 1/2: ``x * (pathStep / hypotf(x, 0))``
    rounds to at most 1/2 in magnitude.  With the monotonicity of rounding this bounds every
    step (a larger hypotf only shrinks ``ss``; see FinitePotentialPath).

    2**-100 <= |x| <= 20  ==>  |x * (0.5f / hypotf(x, 0))| <= 1/2 and no cell move
    """
    x = D.f32("x")
    zero = D.f32const(0.0)
    ndx, ndy, cdx, cdy = K.step_offsets(D, zero, zero, x, zero, D.f32const(PATH_STEP))
    pre = D.or_(D.and_(D.ge(x, D.f32const(LEAST_GRADIENT)), D.le(x, D.f32const(GRAD_BOUND))),
                D.and_(D.le(x, D.f32const(-LEAST_GRADIENT)), D.ge(x, D.f32const(-GRAD_BOUND))))
    return pre, D.and_(_within(D, ndx, 0.5), D.eq(cdx, 0))


# Decided by enumeration: each sign is one part of about 8.8e8 floats, every one run on the
# float32 arithmetic (the cover, both signs, proved by a solver).
step_along_an_axis_moves_at_most_half_split = split(
    step_along_an_axis_moves_at_most_half,
    [(f32_interval("x", LEAST_GRADIENT, GRAD_BOUND),), (f32_interval("x", -GRAD_BOUND, -LEAST_GRADIENT),)],
    bisect_along=("x",), methods=("enumerate",), max_depth=0,
    note="both signs, every float32 of each enumerated")
