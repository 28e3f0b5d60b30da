"""Small obligations and splits for the split tests (each part decided in about a second)."""

from navfn_smt.smt.obligation import obligation
from navfn_smt.smt.split import f32_interval, product, split


@obligation("Toy", expect={"real": "proved", "fp32": "proved"}, scope="x in [-4, 4]")
def doubling_is_exact(D):
    """x + x == 2 * x for x in [-4, 4]."""
    x = D.f32("x")
    pre = D.and_(D.ge(x, D.f32const(-4.0)), D.le(x, D.f32const(4.0)))
    return pre, D.eq(D.add(x, x), D.mul(D.f32const(2.0), x))


doubling_is_exact_split = split(doubling_is_exact, product((f32_interval("x", -4.0, 0.0), f32_interval("x", 0.0, 4.0))),
                                bisect_along=("x",), expect="proved", max_depth=1, part_timeout=30.0,
                                solvers=("z3",))


@obligation("Toy", expect={"real": "proved", "fp32": "refuted"}, scope="x, y in [1, 2]")
def sum_minus_one_keeps_y(D):
    """(x + y) - x == y for x, y in [1, 2] (false in float32: y's low bits are lost)."""
    x, y = D.f32("x"), D.f32("y")
    one, two = D.f32const(1.0), D.f32const(2.0)
    pre = D.and_(D.and_(D.ge(x, one), D.le(x, two)), D.and_(D.ge(y, one), D.le(y, two)))
    return pre, D.eq(D.sub(D.add(x, y), x), y)


sum_minus_one_keeps_y_split = split(
    sum_minus_one_keeps_y, product((f32_interval("x", 1.0, 1.5), f32_interval("x", 1.5, 2.0)),
                                   (f32_interval("y", 1.0, 1.5), f32_interval("y", 1.5, 2.0))),
    bisect_along=("x", "y"), expect="refuted", max_depth=1, part_timeout=30.0, solvers=("z3",))


@obligation("Toy", expect={"real": "proved", "fp32": "refuted"}, scope="x in [1, 2]")
def square_root_of_square(D):
    """(x * x) / x == x for x in [1, 2] (float32: refuted by some x, found by enumeration)."""
    x = D.f32("x")
    pre = D.and_(D.ge(x, D.f32const(1.0)), D.le(x, D.f32const(2.0)))
    return pre, D.eq(D.div(D.mul(x, x), x), x)


square_root_of_square_split = split(square_root_of_square, [(f32_interval("x", 1.0, 2.0),)], bisect_along=("x",),
                                    expect="refuted", methods=("enumerate",), max_depth=0)


@obligation("Toy", expect={"real": "proved", "fp32": "proved"}, scope="a, b in [1, 2]")
def product_is_close(D):
    """|a * b - a * b (double)| <= 2**-23 * a * b: one float rounding, in the error model."""
    a, b = D.f32("a"), D.f32("b")
    one, two = D.f32const(1.0), D.f32const(2.0)
    pre = D.and_(D.and_(D.ge(a, one), D.le(a, two)), D.and_(D.ge(b, one), D.le(b, two)))
    exact = D.mul64(D.widen(a), D.widen(b))
    err = D.sub64(D.widen(D.mul(a, b)), exact)
    tol = D.mul64(D.f64const(2.0**-23), exact)
    return pre, D.and_(D.le(err, tol), D.ge(err, D.neg(tol)))


product_is_close_split = split(product_is_close, [(f32_interval("a", 1.0, 2.0), f32_interval("b", 1.0, 2.0))],
                               bisect_along=("a", "b"), expect="proved", methods=("errmodel",), max_depth=0,
                               part_timeout=30.0)


@obligation("Toy", expect={"real": "proved", "fp32": "proved", "fp32@x86-64-v3": "refuted", "fp32@aarch64": "refuted"},
            scope="x in [1, 2]")
def product_error_is_zero(D):
    """c + x * x with c = -(x * x rounded), at the site ``planar``: zero where the product is
    rounded first (x86-64), the product's rounding error where the build fuses the site."""
    from navfn_smt.spec.kernels import add_mul

    x = D.f32("x")
    pre = D.and_(D.ge(x, D.f32const(1.0)), D.le(x, D.f32const(2.0)))
    return pre, D.eq(add_mul(D, "planar", D.neg(D.mul(x, x)), x, x), D.f32const(0.0))


product_error_is_zero_split = split(product_error_is_zero, [(f32_interval("x", 1.0, 2.0),)], bisect_along=("x",),
                                    methods=("enumerate",), max_depth=0)
