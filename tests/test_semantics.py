"""Unit tests of NavFn's semantics, one test per piece of the C++ (nav2_navfn_planner/src/navfn.cpp).

Every expected value here is derived independently of the spec: by hand from the C++
source, from IEEE-754 facts, from numpy float32/float64 arithmetic used as an oracle
(numpy scalars round every operation to their own type), from struct bit patterns, or
from the platform's libm called directly through ctypes.  None is copied from the
spec's own output.  The comment next to a non-obvious expected value gives the reasoning.
"""

from __future__ import annotations

import collections
import ctypes
import ctypes.util
import math
import struct
from fractions import Fraction

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from navfn_smt.backends import get_backend
from navfn_smt.spec import kernels as K
from navfn_smt.spec import propagation as P
from navfn_smt.spec.costs import add_border, set_costmap, translate_cost
from navfn_smt.spec.extraction import ExtractionExit, UndefinedBehaviour, calc_path
from navfn_smt.spec.numeric import CONCRETE as D
from navfn_smt.spec.numeric import c_hypot, c_hypotf, c_roundf, cvt_to_int32, f32, f32_bits

pytestmark = pytest.mark.fast

F = np.float32
F64 = np.float64
INT_MIN = -(2**31)
HIGH = 1.0e10  # POT_HIGH
FLT_MAX = (2.0 - 2.0**-23) * 2.0**127
HYP = settings(max_examples=300, deadline=None, suppress_health_check=[HealthCheck.too_slow])


def bits(x: float) -> int:
    """binary32 bit pattern via struct (independent of navfn_smt.spec.numeric.f32_bits)."""
    return struct.unpack("<I", struct.pack("<f", x))[0]


def same_f32(a: float, b: float) -> bool:
    """Bit-identical as float32 (distinguishes -0.0 from 0.0, NaN equals NaN)."""
    if a != a and b != b:
        return True
    return bits(a) == bits(b)


_libm = ctypes.CDLL(ctypes.util.find_library("m") or "libm.so.6")
_libm.roundf.restype = ctypes.c_float
_libm.roundf.argtypes = [ctypes.c_float]


def libm_roundf(x: float) -> float:
    """The real C roundf, as an oracle for the spec's exact-arithmetic c_roundf."""
    return _libm.roundf(x)


float32s = st.floats(width=32, allow_nan=False, allow_infinity=False)


# ======================================================================================
# 1. Numeric primitives
# ======================================================================================
@pytest.mark.parametrize(
    "x, expected",
    [
        (16777217.0, 16777216.0),  # 2**24+1 is a tie between 2**24 and 2**24+2; even significand is 2**24
        (16777219.0, 16777220.0),  # tie between 2**24+2 (odd significand) and 2**24+4 (even)
        (16777218.0, 16777218.0),  # representable (spacing 2 above 2**24)
        (16777217.5, 16777218.0),  # above the tie: nearest is 2**24+2
        (-16777217.0, -16777216.0),  # ties-to-even is sign-symmetric
        (1.0 + 2.0**-24, 1.0),  # half an ulp of 1.0: tie, 1.0 has the even significand
        (1.0 + 3 * 2.0**-24, 1.0 + 2.0**-22),  # tie between 1+2**-23 (odd) and 1+2**-22 (even)
        (0.1, 0.100000001490116119384765625),  # float32(0.1) = 13421773 * 2**-27
        (2.0**-150, 0.0),  # half the smallest subnormal: tie, rounds to the even 0
        (3 * 2.0**-150, 2.0**-148),  # 1.5 subnormal units: tie between 1 and 2 units, 2 is even
    ],
)
def test_f32_rounds_to_nearest_even(x, expected):
    assert same_f32(f32(x), expected)
    assert f32(x) == expected


@pytest.mark.parametrize(
    "x, expected",
    [
        (3.5e38, math.inf),  # beyond FLT_MAX + half ulp
        (-3.5e38, -math.inf),
        (1e39, math.inf),
        (FLT_MAX, FLT_MAX),  # (2 - 2**-23) * 2**127 is the largest float32
        (FLT_MAX + 2.0**102, FLT_MAX),  # a quarter ulp (ulp = 2**104) above: rounds down
        (FLT_MAX + 2.0**103, math.inf),  # exact tie; FLT_MAX's significand is odd, so up to 2**128 = inf
        (math.inf, math.inf),
        (-math.inf, -math.inf),
    ],
)
def test_f32_overflows_to_infinity(x, expected):
    assert f32(x) == expected


def test_f32_bit_patterns_and_special_values():
    assert f32_bits(1.0) == 0x3F800000  # IEEE-754: sign 0, biased exponent 127, significand 0
    assert f32_bits(-0.0) == 0x80000000  # only the sign bit
    assert math.copysign(1.0, f32(-0.0)) == -1.0  # the sign of zero survives the narrowing
    # POT_HIGH: 1e10 = 9765625 * 2**10 with 9765625 < 2**24, so it is exact in float32;
    # exponent 33 (biased 160 = 0xA0), significand 9765625 - 2**23 = 1377017 = 0x1502F9.
    assert f32(1.0e10) == 1.0e10
    assert f32_bits(1.0e10) == (0xA0 << 23) | 0x1502F9 == 0x501502F9
    assert math.isnan(f32(math.nan))


@HYP
@given(st.floats(allow_nan=False))
def test_f32_agrees_with_numpy_narrowing(x):
    with np.errstate(over="ignore"):
        expected = float(F(x))  # numpy's float64 -> float32 cast rounds to nearest even, overflows to inf
    assert same_f32(f32(x), expected)


@pytest.mark.parametrize(
    "a, expected",
    [
        (2.9, 2),  # truncation toward zero
        (-2.9, -2),  # toward zero, not floor
        (0.99999994, 0),  # largest float32 below 1
        (-0.5, 0),
        (2147483520.0, 2147483520),  # largest float32 below 2**31 still fits
        (-2147483648.0, -(2**31)),  # -2**31 itself is in range
        (2147483648.0, INT_MIN),  # 2**31 overflows: cvttss2si gives the "integer indefinite" 0x80000000
        (-2147483904.0, INT_MIN),  # next float32 below -2**31
        (1e10, INT_MIN),
        (math.inf, INT_MIN),
        (-math.inf, INT_MIN),
        (math.nan, INT_MIN),  # NaN also gives the integer indefinite value
        (2147483647.9, 2147483647),  # a double (cvttsd2si): truncates into range
        (-2147483648.9, -(2**31)),  # a double just below -2**31 truncates to -2**31
        (-2147483649.0, INT_MIN),
    ],
)
def test_cvt_to_int32(a, expected):
    assert cvt_to_int32(a) == expected


@HYP
@given(st.floats(width=32))
def test_cvt_to_int32_is_truncation_or_indefinite(a):
    # independent formulation: truncate exactly; a result outside int32 (or NaN/inf) is 0x80000000
    if math.isnan(a) or math.isinf(a):
        expected = INT_MIN
    else:
        t = math.trunc(a)
        expected = t if -(2**31) <= t <= 2**31 - 1 else INT_MIN
    assert cvt_to_int32(a) == expected


@pytest.mark.parametrize(
    "a, expected",
    [
        (0.5, 1.0),  # halves go away from zero
        (-0.5, -1.0),
        (2.5, 3.0),  # Python's round(2.5) would give 2
        (-2.5, -3.0),
        (1.5, 2.0),
        (-1.5, -2.0),
        (0.5 - 2.0**-25, 0.0),  # float32(0.49999997): below one half, rounds to 0
        (8388609.0, 8388609.0),  # 2**23 + 1: already an integer
        (-0.3, -0.0),  # C roundf keeps the sign of zero
        (0.0, 0.0),
        (-0.0, -0.0),
    ],
)
def test_c_roundf_halves_away_from_zero(a, expected):
    assert same_f32(c_roundf(a), expected)


def test_c_roundf_is_not_python_round_nor_naive_floor():
    assert f32(0.49999997) == 0.5 - 2.0**-25  # the float32 just below 0.5
    assert round(2.5) == 2 and c_roundf(2.5) == 3.0  # Python rounds half to even, C away from zero
    assert round(-0.5) == 0 and c_roundf(-0.5) == -1.0
    # the classic wrong roundf, floorf(x + 0.5f): 0.49999997f + 0.5f = 1 - 2**-25 is a tie in
    # float32 and rounds to 1.0, so it would give 1; the real roundf gives 0.
    assert float(np.floor(F(0.49999997) + F(0.5))) == 1.0
    assert c_roundf(f32(0.49999997)) == 0.0


@HYP
@given(st.floats(width=32))
def test_c_roundf_agrees_with_libm_roundf(a):
    assert same_f32(c_roundf(a), libm_roundf(a))


def test_c_hypotf_hand_values():
    assert c_hypotf(3.0, 4.0) == 5.0  # Pythagorean triple, exact
    assert c_hypotf(-254.0, 254.0) == float(np.hypot(F(-254), F(254)))
    # hypotf must not overflow where the naive float32 formula does: (1e30f)**2 is inf in float32
    with np.errstate(over="ignore"):
        assert math.isinf(float(F(1e30) * F(1e30)))
    h = c_hypotf(f32(1e30), f32(1e30))
    assert math.isfinite(h) and h == float(np.hypot(F(1e30), F(1e30)))
    assert c_hypotf(math.inf, math.nan) == math.inf  # C99 Annex F: hypot(inf, NaN) = +inf
    assert c_hypot(3.0, 4.0) == 5.0
    assert c_hypot(1.0, 1.0) == float(np.hypot(F64(1.0), F64(1.0)))


@HYP
@given(float32s, float32s)
def test_c_hypotf_agrees_with_numpy_float32(a, b):
    with np.errstate(over="ignore"):  # hypot of two values near FLT_MAX overflows to inf
        expected = float(np.hypot(F(a), F(b)))  # numpy's float32 hypot
    got = c_hypotf(a, b)
    assert same_f32(got, expected)
    assert f32(got) == got or math.isinf(got)  # a float32 value


# ======================================================================================
# 2. Cost translation (setCostmap) and the lethal border (setupNavFn)
# ======================================================================================
@pytest.mark.parametrize(
    "v, allow_unknown, expected",
    [
        (0, True, 50),  # 50 + 0.8*0
        (1, True, 50),  # 50.8 truncated by the int assignment
        (5, True, 54),  # 0.8*5 = 4.000000000000000222 in double: no drop below 4
        (100, True, 130),  # 50 + 80
        (127, True, 151),  # 50 + 101.6 -> 151
        (250, True, 250),  # 50 + 200
        (252, True, 251),  # 50 + 201.6 = 251.6 -> 251 (the COST_OBS-1 cap never triggers)
        (253, True, 254),  # COST_OBS_ROS -> COST_OBS
        (254, True, 254),
        (255, True, 253),  # unknown allowed -> COST_OBS - 1
        (255, False, 254),  # unknown forbidden -> COST_OBS
        (253, False, 254),
        (100, False, 130),  # allow_unknown only affects 255
    ],
)
def test_translate_cost_hand_values(v, allow_unknown, expected):
    assert translate_cost(v, allow_unknown) == expected


def test_translate_cost_closed_form_for_all_free_values():
    # double(0.8) > 4/5, so for multiples of 5 the double result is >= the integer and never
    # below it; for other v the fraction is >= 0.2. Hence int(...) == floor(50 + 4v/5) exactly.
    for v in range(253):
        expected = math.floor(50 + Fraction(4 * v, 5))
        assert translate_cost(v) == expected
        assert translate_cost(v) < 254
    with pytest.raises(ValueError):
        translate_cost(256)
    with pytest.raises(ValueError):
        translate_cost(-1)


def test_set_costmap_ros_branch():
    cmap = np.arange(256, dtype=np.uint8).reshape(16, 16)
    out = set_costmap(cmap, is_ros=True, allow_unknown=True)
    expected = [math.floor(50 + Fraction(4 * v, 5)) for v in range(253)] + [254, 254, 253]
    assert out.dtype == np.uint8
    assert out.ravel().tolist() == expected
    out2 = set_costmap(cmap, is_ros=True, allow_unknown=False)
    assert out2.ravel().tolist() == expected[:255] + [254]  # 255 becomes lethal


def test_set_costmap_pgm_branch_has_a_seven_cell_lethal_frame():
    ny, nx = 17, 20
    cmap = np.zeros((ny, nx), np.uint8)
    cmap[7, 7], cmap[7, 8], cmap[8, 8], cmap[9, 12] = 255, 253, 252, 100
    out = set_costmap(cmap, is_ros=False, allow_unknown=False)
    # C++: i < 7 || i > ny - 8 (= 9) || j < 7 || j > nx - 8 (= 12) -> COST_OBS
    for i in range(ny):
        for j in range(nx):
            frame = i < 7 or i > 9 or j < 7 or j > 12
            if frame:
                assert out[i, j] == 254, (i, j)
    assert out[7, 7] == 253  # PGM: 255 -> COST_OBS - 1 whatever allow_unknown says
    assert translate_cost(255, allow_unknown=False, ros=False) == 253
    assert translate_cost(253, allow_unknown=True, ros=False) == 254
    assert out[7, 8] == 254  # 253 -> COST_OBS
    assert out[8, 8] == 251  # 252 -> 251
    assert out[9, 12] == 130  # 100 -> 130, the last interior row and column
    assert out[8, 9] == 50  # 0 -> 50
    # a map of at most 14 rows has no interior at all
    assert (set_costmap(np.zeros((14, 30), np.uint8), is_ros=False) == 254).all()


def test_add_border():
    costs = np.full((4, 5), 7, np.uint8)
    out = add_border(costs)
    assert (costs == 7).all()  # input untouched: a new array is returned
    assert out.dtype == np.uint8
    assert (out[0, :] == 254).all() and (out[-1, :] == 254).all()
    assert (out[:, 0] == 254).all() and (out[:, -1] == 254).all()
    assert (out[1:-1, 1:-1] == 7).all()


# ======================================================================================
# 3. Kernels (concrete domain)
# ======================================================================================
def np_planar_wave(l, r, u, d, hf):
    """updateCell's arithmetic transcribed from the C++ with explicit numpy types."""
    l, r, u, d, hf = F(l), F(r), F(u), F(d), F(hf)
    tc = l if l < r else r
    ta = u if u < d else d
    dc = F(tc - ta)
    if dc < 0:
        dc = -dc
        ta = tc
    if dc >= hf:
        return float(F(ta + hf))
    div = F(dc / hf)
    w = F64(div)
    v = F(F64(-0.2301) * w * w + F64(0.5307) * w + F64(0.7040))
    return float(F(ta + F(hf * v)))


def test_planar_wave_single_reached_neighbour():
    # l = 0, r = u = d = 1e10: tc = 0, ta = 1e10, dc = -1e10 -> swap: dc = 1e10 >= 50, pot = 0 + 50
    assert K.planar_wave(D, 0.0, HIGH, HIGH, HIGH, 50.0) == 50.0
    # the reached neighbour below: tc = 1e10, ta = 0, dc = 1e10 >= 50 -> 0 + 50
    assert K.planar_wave(D, HIGH, HIGH, HIGH, 0.0, 50.0) == 50.0
    assert K.planar_wave(D, 100.0, HIGH, HIGH, HIGH, 253.0) == 353.0


def test_planar_wave_two_neighbours_at_zero():
    # dc = 0 < hf: div = 0, v = (float)(-0.2301*0*0 + 0.5307*0 + 0.7040) = float32(0.704)
    expected = float(F(0) + F(F(50) * F(0.7040)))
    got = K.planar_wave(D, 0.0, HIGH, 0.0, HIGH, 50.0)
    assert got == expected == float(F(35.2))  # 50 * 0.70399999618f = 35.1999998 -> float32(35.2)


def test_planar_wave_swap_when_dc_negative():
    # tc = min(l, r) = 10, ta = min(u, d) = 30: dc = -20 < 0 -> dc = 20, ta = 10
    div = F(F(20) / F(50))  # 0.4f
    w = F64(div)
    v = F(F64(-0.2301) * w * w + F64(0.5307) * w + F64(0.7040))  # double, narrowed
    expected = float(F(F(10) + F(F(50) * v)))  # ~ 10 + 50 * 0.87907
    got = K.planar_wave(D, 10.0, HIGH, 30.0, HIGH, 50.0)
    assert got == expected
    assert 53.9 < got < 54.0
    # the mirror image needs no swap (tc = 30, ta = 10, dc = 20) and must agree
    assert K.planar_wave(D, 30.0, HIGH, 10.0, HIGH, 50.0) == expected


def test_planar_wave_branch_boundary_dc_equal_hf():
    # dc = 50 >= hf = 50 -> the one-neighbour update 0 + 50, not the quadratic (which gives ~50.23)
    assert K.planar_wave(D, 0.0, HIGH, 50.0, HIGH, 50.0) == 50.0
    # dc = 49 < 50 -> quadratic: v(0.98) = -0.2301*0.9604 + 0.5307*0.98 + 0.704 ~ 1.0031 > 1,
    # so a smaller dc gives a LARGER potential (a quirk of the approximation)
    got = K.planar_wave(D, 0.0, HIGH, 49.0, HIGH, 50.0)
    assert got == np_planar_wave(0.0, HIGH, 49.0, HIGH, 50.0)
    assert got > 50.0


def test_planar_wave_zero_cost_cell_copies_its_lowest_neighbour():
    # hf = 0: dc >= 0 always, so pot = ta + 0 (no division by zero happens)
    assert K.planar_wave(D, 7.0, HIGH, 9.0, HIGH, 0.0) == 7.0


pot_values = st.one_of(st.just(HIGH), st.floats(0, 1e4, width=32))


@HYP
@given(pot_values, pot_values, pot_values, pot_values, st.integers(0, 253))
def test_planar_wave_agrees_with_numpy_transcription(l, r, u, d, cost):
    assert same_f32(K.planar_wave(D, l, r, u, d, float(cost)), np_planar_wave(l, r, u, d, cost))


def test_edge_weight_is_a_double_product_narrowed():
    assert K.edge_weight(D, 50.0) == float(F(0.707106781 * 50.0))  # double product, then (float)
    # for cost 52 the double product narrowed differs from an all-float product:
    assert K.edge_weight(D, 52.0) == float(F(F64(0.707106781) * F64(52)))  # 36.769554
    assert K.edge_weight(D, 52.0) != float(F(F(0.707106781) * F(52)))  # 36.76955
    assert K.edge_weight(D, 0.0) == 0.0


def test_astar_heuristic():
    assert K.astar_heuristic(D, 3, 4) == 250.0  # hypot(3, 4) = 5 exactly, 5 * 50.0f
    assert K.astar_heuristic(D, -3, 4) == 250.0
    assert K.astar_heuristic(D, 0, 0) == 0.0
    assert K.astar_heuristic(D, 1, 1) == float(F(math.sqrt(2.0) * 50.0))  # 70.71067811865476 -> float


def test_grad_cell_reached_cell_central_difference():
    # dx = (l - cv) + (cv - r) = 10 + 10 = 20, dy = (u - cv) + (cv - d) = 0;
    # norm = 20, 1.0/20 -> 0.05f, 0.05f * 20 = 1.0000000149 -> 1.0f
    assert K.grad_cell(D, 100.0, 110.0, 90.0, 100.0, 100.0) == (1.0, 0.0)
    # dy = (90 - 100) + (100 - 110) = -20 -> pointing up
    assert K.grad_cell(D, 100.0, 100.0, 100.0, 90.0, 110.0) == (0.0, -1.0)
    # only reached neighbours count: l unreached, so dx = 0 + (100 - 90) = 10 -> (1, 0)
    assert K.grad_cell(D, 100.0, HIGH, 90.0, 100.0, 100.0) == (1.0, 0.0)


def test_grad_cell_zero_vector_on_a_plateau():
    assert K.grad_cell(D, 100.0, 100.0, 100.0, 100.0, 100.0) == (0.0, 0.0)
    assert K.grad_cell(D, 100.0, HIGH, HIGH, HIGH, HIGH) == (0.0, 0.0)  # no reached neighbour
    assert K.grad_cell(D, HIGH, HIGH, HIGH, HIGH, HIGH) == (0.0, 0.0)  # obstacle branch, nothing reached


def test_grad_cell_obstacle_branch_directions():
    # cv unreached: dx = -COST_OBS because l is reached (r ignored: else-if), dy = +COST_OBS
    # because u is unreached and d is reached; the neighbours' values do not matter
    norm = np.hypot(F(-254), F(254))  # hypotf
    inv = F(1.0 / F64(norm))  # 1.0 / norm is double, narrowed
    expected = (float(F(inv * F(-254))), float(F(inv * F(254))))
    got = K.grad_cell(D, HIGH, 60.0, 70.0, HIGH, 80.0)
    assert got == expected
    assert got[0] == -got[1] and abs(abs(got[0]) - 1 / math.sqrt(2)) < 1e-6
    assert K.grad_cell(D, HIGH, 1.0, 2.0, HIGH, 3e9) == expected  # values irrelevant
    # only r reached: dx = +254, dy = 0
    inv1 = F(1.0 / F64(254))
    assert K.grad_cell(D, HIGH, HIGH, 5.0, HIGH, HIGH) == (float(F(inv1 * F(254))), 0.0)
    # u reached: dy = -254
    assert K.grad_cell(D, HIGH, HIGH, HIGH, 5.0, 7.0) == (0.0, float(F(inv1 * F(-254))))


def test_interpolation_mixes_double_and_float_products():
    # (1.0 - t) * a is double, t * b is float, the sum double narrowed to float
    t, a, b = F(0.72529393), F(0.30773202), F(-0.13754651)
    expected = float(F((F64(1.0) - F64(t)) * F64(a) + F64(F(t * b))))
    all_float = float(F(F(F(1) - t) * a + F(t * b)))
    all_double = float(F((1.0 - F64(t)) * F64(a) + F64(t) * F64(b)))
    got = K.bilinear(D, float(t), float(a), float(b))
    assert got == expected
    assert got != all_float and got != all_double  # the mixed precision is observable here
    # dx = dy = 0: the interpolation returns exactly the upper-left cell's component
    assert K.interpolate_gradient(D, 0.0, 0.0, -0.25, 9.0, 9.0, 9.0) == -0.25


def test_lowest_of_eight_truncates_to_int():
    rest = [HIGH] * 8
    # minp = (int)10.9 = 10; 10.5 < 10.0 is false, so nothing beats the centre
    nb = rest.copy()
    nb[3] = 10.5
    assert K.lowest_of_eight(D, 10.9, nb) == -1
    nb[3] = 10.0  # 10.0 < 10.0 false too
    assert K.lowest_of_eight(D, 10.9, nb) == -1
    # 9.99 < 10 wins (minp becomes 9); a later 9.5 < 9 is false; a later 8.99 < 9 wins
    nb = rest.copy()
    nb[1], nb[4] = 9.99, 9.5
    assert K.lowest_of_eight(D, 10.9, nb) == 1
    nb[6] = 8.99
    assert K.lowest_of_eight(D, 10.9, nb) == 6
    # ties keep the first in C++ order (strict <)
    nb = rest.copy()
    nb[2], nb[5] = 5.0, 5.0
    assert K.lowest_of_eight(D, 10.9, nb) == 2
    # a centre at 1e10 (or any value >= 2**31) gives minp = INT_MIN: no neighbour beats it
    nb = rest.copy()
    nb[0] = 5.0
    assert K.lowest_of_eight(D, HIGH, nb) == -1
    assert K.lowest_of_eight(D, 3e9, [0.0] * 8) == -1


@pytest.mark.parametrize(
    "stc, dx, dy, nx, ns, expected",
    [
        (10, 0.0, 0.0, 7, 35, 10),
        (10, 0.5, 0.0, 7, 35, 11),  # roundf(0.5) = 1 (Python round would give 0)
        (10, 2.5, 0.0, 7, 35, 13),  # roundf(2.5) = 3 (Python round would give 2)
        (10, -0.5, 0.0, 7, 35, 9),  # away from zero: -1
        (10, 0.49999997, 0.0, 7, 35, 10),  # below one half: 0
        (10, 0.0, 0.5, 7, 35, 17),  # one row down: + (int)(7.0f * 1.0f)
        (10, 0.0, -0.5, 7, 35, 3),  # one row up
        (10, -0.6, 0.6, 7, 35, 16),  # -1 + 7
        (0, -0.5, 0.0, 7, 35, 0),  # -1 clamped to 0
        (2, 0.0, -1.0, 7, 35, 0),  # 2 - 7 = -5 clamped to 0
        (34, 0.5, 0.0, 7, 35, 34),  # 35 clamped to ns - 1
        (30, 0.0, 0.5, 7, 35, 34),  # 37 clamped to ns - 1
    ],
)
def test_nearest_cell(stc, dx, dy, nx, ns, expected):
    assert K.nearest_cell(D, stc, f32(dx), f32(dy), nx, ns) == expected


def np_step(dx, dy, x, y):
    """calcPath's step and overflow tests, with numpy types, from the C++."""
    dx, dy, x, y = F(dx), F(dy), F(x), F(y)
    ss = F(F(0.5) / np.hypot(x, y))
    dx = F(dx + F(x * ss))
    dy = F(dy + F(y * ss))
    cdx = cdy = 0
    if F64(dx) > 1.0:
        cdx, dx = 1, F(F64(dx) - 1.0)
    if F64(dx) < -1.0:
        cdx, dx = -1, F(F64(dx) + 1.0)
    if F64(dy) > 1.0:
        cdy, dy = 1, F(F64(dy) - 1.0)
    if F64(dy) < -1.0:
        cdy, dy = -1, F(F64(dy) + 1.0)
    return float(dx), float(dy), cdx, cdy


def test_step_offsets_overflow_moves_the_cell():
    # 0.75 + 0.5 = 1.25 > 1 -> one cell right, dx = 0.25 (all exact)
    assert K.step_offsets(D, 0.75, 0.0, 1.0, 0.0, 0.5) == (0.25, 0.0, 1, 0)
    # -0.75 - 0.5 = -1.25 < -1 in y -> one row up, dy = -0.25
    assert K.step_offsets(D, 0.0, -0.75, 0.0, -1.0, 0.5) == (0.0, -0.25, 0, -1)
    # exactly 1.0 is not > 1.0: no move
    assert K.step_offsets(D, 0.5, 0.0, 1.0, 0.0, 0.5) == (1.0, 0.0, 0, 0)
    # inexact values: 0.9f + 0.5f, minus 1.0 in double, narrowed
    dx = f32(0.9)
    got = K.step_offsets(D, dx, f32(0.7), 3.0, 4.0, 0.5)  # ss = 0.5/5 = 0.1f; step (0.3, 0.4)
    assert got == np_step(dx, f32(0.7), 3.0, 4.0)
    assert got[2:] == (1, 1)  # 1.2 > 1 and 1.1 > 1: diagonal move
    g = K.step_offsets(D, f32(-0.8), 0.0, -1.0, 0.0, 0.5)
    assert g == np_step(f32(-0.8), 0.0, -1.0, 0.0) and g[2] == -1


grad_component = st.one_of(st.floats(-1, -2.0**-10, width=32), st.floats(2.0**-10, 1, width=32))


@HYP
@given(
    st.floats(-1, 1, width=32),
    st.floats(-1, 1, width=32),
    grad_component,
    st.one_of(st.just(0.0), grad_component),
)
def test_step_offsets_agree_with_numpy(dx, dy, x, y):
    assert K.step_offsets(D, dx, dy, x, y, 0.5) == np_step(dx, dy, x, y)


# ======================================================================================
# 4. Priority buffers: bounded at PRIORITYBUFSIZE = 10000, pushes to a full buffer dropped
# ======================================================================================
def open_5x5_costs():
    c = np.full((5, 5), 50, np.uint8)
    return add_border(c).ravel().tolist()


def test_push_to_full_buffer_is_dropped_and_not_pending():
    stt = P.PropagationState(
        nx=5, ny=5, costs=open_5x5_costs(), potential=[HIGH] * 25, pending=[False] * 25, cur_t=254.0
    )
    stt.nxt = P.Buffer([7] * 10000)  # full (contents irrelevant)
    into_next, into_over = True, False  # push_next and push_over: the update's `low` picks the buffer
    P.push(stt, 12, True, into_next)
    assert stt.dropped == 1 and not stt.pending[12] and len(stt.nxt) == 10000
    P.push(stt, 12, True, into_next)  # not pending, so a second attempt is a second drop
    assert stt.dropped == 2
    P.push(stt, 12, False, into_next)  # not wanted by the update: no push, no drop
    assert stt.dropped == 2
    # the other guards come first and are not drops: lethal, pending, off the map
    P.push(stt, 0, True, into_next)
    stt.pending[6] = True
    P.push(stt, 6, True, into_next)
    P.push(stt, -1, True, into_next)
    P.push(stt, 25, True, into_next)
    assert stt.dropped == 2 and len(stt.nxt) == 10000
    # a buffer with room admits and marks pending
    P.push(stt, 12, True, into_over)
    assert list(stt.over) == [12] and stt.pending[12]
    P.push(stt, 12, True, into_next)  # now pending: silently skipped, no drop
    assert stt.dropped == 2
    # 9999 entries: one more fits exactly (push_cur)
    stt.cur = P.Buffer([7] * 9999)
    P.push_cur(stt, 13)
    assert len(stt.cur) == 10000 and stt.cur.cell(9999) == 13 and stt.pending[13] and stt.dropped == 2


def stub_comb_map(K_cols: int, ny: int) -> np.ndarray:
    """A comb of zero-cost columns with 1-D stubs [Z, D1, D2, D3] on both sides.

    Columns (period 8): D3 D2 D1 Z D1 D2 D3 W; row 1 is all zero (connects the Z columns);
    stubs (cost 253) on odd rows 3..ny-2, lethal everywhere else.
    """
    nx = 8 * K_cols + 1
    c = np.full((ny, nx), 254, np.uint8)
    c[1, 1 : nx - 1] = 0
    for k in range(K_cols):
        z = 8 * k + 4
        c[1 : ny - 1, z] = 0
        for y in range(3, ny - 1, 2):
            c[y, z - 3 : z] = 253
            c[y, z + 1 : z + 4] = 253
    return c


def cycle_sizes(trace: np.ndarray) -> list:
    sizes, i = [], 0
    while i < len(trace):
        sizes.append(int(trace[i]))
        i += int(trace[i]) + 1
    return sizes


def test_buffer_overflow_drops_on_a_comb_map_in_both_backends():
    # Reasoning (Dijkstra, curT = 254): zero cells get potential 0 and D1 cells 0 + 253 = 253,
    # both keys < 254, so they push into the next buffer; D2 cells get 253 + 253 = 506 >= curT and
    # push their D3 into the overflow buffer. The next buffer never runs dry while the zero
    # cells are being swept, so every stub's single D3 push lands in the overflow buffer before
    # it is ever swapped in: S = 25 columns * 2 sides * 201 stub rows = 10050 pushes into a
    # buffer of 10000, hence exactly 50 drops, and those 50 D3 cells are never processed.
    Kc, ny = 25, 405
    costs = stub_comb_map(Kc, ny)
    nx = costs.shape[1]
    stubs = Kc * (ny - 3)
    assert stubs == 10050
    start, goal = (nx - 2, ny - 2), (4, 1)  # start: the D3 of the very last stub -> pushed last
    results = {}
    for name in ("reference", "jit"):
        r = get_backend(name).prepare(costs).run(start, goal, False)
        assert r.dropped == stubs - 10000 == 50
        sizes = cycle_sizes(r.trace)
        assert sizes[-1] == 10000 == max(sizes)  # the overflow buffer, swapped in once, full
        # Zero cell (x, y) is processed in cycle x + y - 6 (its Manhattan distance to the goal
        # minus 1); the last, (196, 403), in cycle 593; its D1s in 594, D2s in 595; the full
        # overflow buffer in 596: 597 cycles.
        assert r.cycles == 597
        # each passable cell is updated once: 198 zero cells in row 1 (the goal is never
        # pushed), 25 * 402 in the Z columns, 2 per stub for D1/D2, 10000 admitted D3 cells
        assert r.updates == 198 + 25 * 402 + 2 * stubs + 10000 == 40348
        pot = r.potential
        d3 = np.zeros_like(costs, dtype=bool)
        for k in range(Kc):
            d3[3 : ny - 1 : 2, 8 * k + 1] = True
            d3[3 : ny - 1 : 2, 8 * k + 7] = True
        assert d3.sum() == stubs
        assert int((pot[d3] == HIGH).sum()) == 50  # the dropped cells never got a potential
        assert set(pot[d3].tolist()) == {759.0, HIGH}  # admitted ones: 506 + 253
        assert set(pot[costs == 0].tolist()) == {0.0}
        # The start was dropped: Dijkstra still returns true (buffers ran dry before the
        # cycle limit, 201*405//20 = 4070), with the start unreached.
        assert r.start_reached is True and r.start_potential == HIGH
        assert r.exit == ExtractionExit.HIGH_POTENTIAL and len(r.path) == 0
        results[name] = (
            r.potential.tobytes(), r.trace.tobytes(), r.cycles, r.updates, r.dropped, r.exit
        )
    assert results["reference"] == results["jit"]


def test_dropped_cell_is_not_pending_during_propagation():
    # the same comb, spec propagation observed cycle by cycle: the 50 dropped D3 cells are
    # not pending when the overflow buffer is swapped in, and never appear in the trace
    Kc, ny = 25, 405
    costs = stub_comb_map(Kc, ny)
    nx = costs.shape[1]
    stt = P.setup(add_border(costs).ravel().tolist(), nx, ny, (4, 1))
    seen = []

    def hook(cycle, cells):
        if len(cells) == 10000:
            seen.append((set(cells), list(stt.pending)))

    P.propagate(stt, (nx - 2, ny - 2), (4, 1), False, P.cycle_limit(nx, ny), trace_hook=hook)
    assert stt.dropped == 50 and len(seen) == 1
    cells, pending = seen[0]
    d3 = [y * nx + x for y in range(3, ny - 1, 2) for k in range(Kc) for x in (8 * k + 1, 8 * k + 7)]
    dropped = [n for n in d3 if n not in cells]
    assert len(dropped) == 50
    assert not any(pending[n] for n in dropped)
    assert all(pending[n] for n in cells)  # admitted ones were pending until their cycle
    assert (nx - 2) + (ny - 2) * nx in dropped


# ======================================================================================
# 5. Propagation
# ======================================================================================
def test_cycle_limit():
    assert P.cycle_limit(5, 5) == 10  # max(25 // 20 = 1, 10)
    assert P.cycle_limit(100, 100) == 500  # max(500, 200)
    assert P.cycle_limit(21, 20) == 41  # max(21, 41)
    assert P.cycle_limit(40, 41) == 82  # 1640 // 20 = 82 vs 81
    assert P.cycle_limit(201, 405) == 4070  # 81405 // 20 (integer division)


def test_init_cost_pushes_right_left_up_down():
    # 5x5, 3x3 interior of cost 50; goal (1, 2) = cell 11: pushes 12 (right), 10 (left: the
    # lethal border, refused), 6 (up), 16 (down)
    stt = P.setup(open_5x5_costs(), 5, 5, (1, 2))
    assert list(stt.cur) == [12, 6, 16]
    assert stt.potential[11] == 0.0
    assert [i for i, p in enumerate(stt.pending) if p] == [6, 12, 16]
    assert stt.cur_t == 254.0 and stt.nxt.fill == 0 and stt.over.fill == 0


@pytest.mark.parametrize("astar", [True, False])
@pytest.mark.parametrize("backend", ["reference", "jit"])
def test_first_cycle_on_5x5(backend, astar):
    costs = np.full((5, 5), 50, np.uint8)
    r = get_backend(backend).prepare(costs).run((1, 1), (1, 2), astar)
    # cycle 0 processes 12, 6, 16 in push order; each has exactly one reached neighbour
    # (the goal at 0), so each gets 0 + 50; the start (cell 6) is then reached and both
    # modes stop after one cycle.
    assert r.trace.tolist() == [3, 12, 6, 16]
    assert r.cycles == 1 and r.updates == 3 and r.dropped == 0
    pot = r.potential.ravel()
    assert pot[11] == 0.0 and pot[12] == 50.0 and pot[6] == 50.0 and pot[16] == 50.0
    assert all(pot[i] == HIGH for i in range(25) if i not in (6, 11, 12, 16))
    assert r.start_reached is True and r.start_potential == 50.0
    # calcPath: 50 is not < 50; the ring of cell 6 holds unreached cells -> lowest of eight:
    # minp = 50, the down neighbour 11 (potential 0) wins; then potential 0 < 50 -> near goal
    assert r.exit == ExtractionExit.NEAR_GOAL
    assert r.path.tolist() == [[1.0, 1.0], [1.0, 2.0]]


def walled_map():
    # 7x5, interior cost 50 with a lethal column at x = 3: goal (1, 2) cannot reach start (5, 2)
    c = np.full((5, 7), 50, np.uint8)
    c[:, 3] = 254
    return c


@pytest.mark.parametrize("backend", ["reference", "jit"])
def test_unreachable_start_dijkstra_true_astar_false(backend):
    planner = get_backend(backend).prepare(walled_map())
    dj = planner.run((5, 2), (1, 2), False)
    # Dijkstra returns cycle < cycles: the buffers ran dry long before max(35//20, 12) = 12
    assert dj.start_reached is True and dj.start_potential == HIGH
    assert dj.exit == ExtractionExit.HIGH_POTENTIAL
    assert dj.cycles < 12
    astar = planner.run((5, 2), (1, 2), True)
    # A* returns whether the start potential is finite
    assert astar.start_reached is False and astar.start_potential == HIGH
    assert astar.exit == ExtractionExit.HIGH_POTENTIAL


def serpentine():
    """9x9 map: a 1-cell corridor of cost 50, rows 1, 3, 5, 7 joined at alternating ends."""
    c = np.full((9, 9), 254, np.uint8)
    for y in (1, 3, 5, 7):
        c[y, 1:8] = 50
    c[2, 7] = c[4, 1] = c[6, 7] = 50
    order = [(x, 1) for x in range(1, 8)] + [(7, 2)] + [(x, 3) for x in range(7, 0, -1)] + [(1, 4)]
    order += [(x, 5) for x in range(1, 8)] + [(7, 6)] + [(x, 7) for x in range(7, 0, -1)]
    return c, order  # order[k] is at corridor distance k from (1, 1)


@pytest.mark.parametrize("backend", ["reference", "jit"])
@pytest.mark.parametrize("astar", [True, False])
def test_cycle_limit_exhausted_returns_false(backend, astar):
    costs, order = serpentine()
    start = order[-1]  # corridor distance 30 > cycle_limit(9, 9) = max(81 // 20, 18) = 18
    r = get_backend(backend).prepare(costs).run(start, order[0], astar)
    # one corridor cell per cycle; cell k gets 50 * k (one reached neighbour: ta + hf)
    assert r.cycles == 18 and r.updates == 18
    expected_trace = []
    for k in range(1, 19):
        expected_trace += [1, order[k][1] * 9 + order[k][0]]
    assert r.trace.tolist() == expected_trace
    for k in range(0, 19):
        assert r.potential[order[k][1], order[k][0]] == 50.0 * k
    assert r.potential[order[19][1], order[19][0]] == HIGH
    assert r.start_reached is False  # Dijkstra: cycle == cycles; A*: start unreached
    # the same map with the start 9 cells away: both modes reach it and return true
    r2 = get_backend(backend).prepare(costs).run(order[9], order[0], astar)
    assert r2.start_reached is True and r2.start_potential == 450.0 and r2.cycles == 9


def test_priority_threshold_increments_when_next_runs_dry():
    # Dijkstra in the serpentine: cycle c processes the cell at distance c+1 (potential
    # 50(c+1)); a key >= curT goes to the overflow buffer, the next buffer is then empty and
    # curT += 100. Keys 300 (c=5), 400, 500, ..., 900 (c=17) overflow: 7 increments, 254 -> 954.
    costs, order = serpentine()
    stt = P.setup(add_border(costs).ravel().tolist(), 9, 9, order[0])
    ret = P.propagate(stt, order[-1], order[0], False, 18)
    assert ret is False and stt.cur_t == 954.0
    # A*: curT starts at hypot(goal - start) * 50 + 254 = 250 + 254 for a (3, 4) offset; with
    # zero cycles nothing runs: A* returns false, Dijkstra returns 0 < 0 = false
    c = np.full((8, 7), 50, np.uint8)
    stt = P.setup(add_border(c).ravel().tolist(), 7, 8, (1, 1))
    assert P.propagate(stt, (4, 5), (1, 1), True, 0) is False and stt.cur_t == 504.0
    stt = P.setup(add_border(c).ravel().tolist(), 7, 8, (1, 1))
    assert P.propagate(stt, (4, 5), (1, 1), False, 0) is False and stt.cur_t == 254.0


def test_astar_key_includes_heuristic():
    # A* on a 7x3 strip (interior row y = 1, x = 1..5), goal (1, 1), start (5, 1): cell (2, 1)
    # gets potential 50 and key 50 + hypot(2 - 5, 0) * 50 = 200 < curT = 200 + 254, so it
    # pushes into next; every cell's key is 50k + 50(4 - k) = 200, and the start is reached in
    # cycle 3, whose cell pushes nothing: next is empty, so curT += 100 -> 554 before the break
    c = np.full((3, 7), 50, np.uint8)
    stt = P.setup(add_border(c).ravel().tolist(), 7, 3, (1, 1))
    assert P.propagate(stt, (5, 1), (1, 1), True, 100) is True
    assert stt.cur_t == 554.0 and stt.cycles == 4
    assert stt.trace == [1, 9, 1, 10, 1, 11, 1, 12]
    assert stt.potential[7 + 1 : 7 + 6] == [0.0, 50.0, 100.0, 150.0, 200.0]


# ======================================================================================
# 6. calcPath
# ======================================================================================
def field(nx, ny, fn):
    return [float(fn(x, y)) for y in range(ny) for x in range(nx)]


def test_calc_path_near_goal_at_start():
    pot = field(5, 5, lambda x, y: 100.0)
    pot[2 * 5 + 2] = 49.5  # < COST_NEUTRAL
    e = calc_path(pot, 5, 5, (2, 2), (3, 1), 10)
    assert e.exit == ExtractionExit.NEAR_GOAL
    assert e.path == [(3.0, 1.0)] and e.points_written == 1  # only the goal point is appended
    pot[2 * 5 + 2] = 50.0  # 50 < 50 is false: not near the goal; a symmetric pit has
    # dx = (100 - 50) + (50 - 100) = 0 and dy = 0, so extraction stops on a zero gradient
    e = calc_path(pot, 5, 5, (2, 2), (3, 1), 10)
    assert e.exit == ExtractionExit.ZERO_GRADIENT and e.points_written == 1


def test_calc_path_near_goal_overrides_undefined_corner():
    # the near-goal probe comes before the bound and ring reads: no UB at (0, ny-1) then
    pot = field(5, 5, lambda x, y: 100.0)
    pot[20] = 10.0
    e = calc_path(pot, 5, 5, (0, 4), (1, 1), 5)
    assert e.exit == ExtractionExit.NEAR_GOAL and e.path == [(1.0, 1.0)]


@pytest.mark.parametrize("start", [(2, 0), (0, 0), (4, 0), (2, 4), (4, 4), (1, 4)])
def test_calc_path_out_of_bounds_in_first_or_last_row(start):
    pot = field(5, 5, lambda x, y: 100.0)
    e = calc_path(pot, 5, 5, start, (2, 2), 10)
    assert e.exit == ExtractionExit.OUT_OF_BOUNDS and e.points_written == 0 and e.path == []


def test_calc_path_high_potential_from_unreached_start():
    pot = [HIGH] * 25
    e = calc_path(pot, 5, 5, (2, 2), (1, 1), 10)
    # all eight unreached: the grid fallback stays put on 1e10 -> "high potential"
    assert e.exit == ExtractionExit.HIGH_POTENTIAL and e.points_written == 1
    # even with a reached neighbour, minp = (int)1e10 = INT_MIN and 60 < -2147483648.0 is
    # false: the fallback never leaves an unreached cell
    pot[2 * 5 + 3] = 60.0
    e = calc_path(pot, 5, 5, (2, 2), (1, 1), 10)
    assert e.exit == ExtractionExit.HIGH_POTENTIAL and e.points_written == 1


def test_calc_path_stuck_on_finite_cell_exhausts():
    # a finite start whose eight neighbours are unreached: the fallback never moves and the
    # potential 100 is not high, so every iteration appends the same point until n runs out
    pot = [HIGH] * 25
    pot[12] = 100.0
    e = calc_path(pot, 5, 5, (2, 2), (1, 1), 7)
    assert e.exit == ExtractionExit.EXHAUSTED and e.points_written == 7 and e.path == []


def test_calc_path_zero_gradient_on_plateau():
    # all finite and equal: every gradCell gives dx = dy = 0, norm 0 -> vectors stay (0, 0);
    # the interpolated gradient is exactly (0, 0)
    pot = field(5, 5, lambda x, y: 100.0)
    e = calc_path(pot, 5, 5, (2, 2), (1, 1), 10)
    assert e.exit == ExtractionExit.ZERO_GRADIENT and e.points_written == 1


def test_calc_path_exhausted():
    pot = field(9, 5, lambda x, y: 20.0 * x)
    e = calc_path(pot, 9, 5, (5, 2), (0, 2), 1)  # one step of 0.5 cannot reach potential < 50
    assert e.exit == ExtractionExit.EXHAUSTED and e.points_written == 1
    e = calc_path(pot, 9, 5, (5, 2), (0, 2), 0)  # n = 0: no iteration at all
    assert e.exit == ExtractionExit.EXHAUSTED and e.points_written == 0
    pot = field(5, 5, lambda x, y: 0.0)
    e = calc_path(pot, 5, 5, (2, 2), (2, 2), 0)  # even on the goal
    assert e.exit == ExtractionExit.EXHAUSTED


def test_calc_path_follows_gradient_with_roundf_probe():
    # potential 20x on 9x5 (all finite), start (5, 2): every gradCell used gives
    # dx = (l - cv) + (cv - r) = -20 + -20 = -40, dy = 0 -> (-1, 0) (0.025f * -40 rounds to
    # -1.0); with dy = 0 the lower row has weight 0; each step moves dx by -0.5:
    #   it1: append (5, 2),   dx -> -0.5
    #   it2: probe roundf(-0.5) = -1 -> (4,2) = 80; append (4.5, 2); dx -> -1.0 (not < -1)
    #   it3: probe (4,2) = 80; append (4, 2); dx -> -1.5 < -1: stc = (4,2), dx = -0.5
    #   it4: probe (3,2) = 60; append (3.5, 2); dx -> -1.0
    #   it5: probe (3,2) = 60; append (3, 2); stc = (3,2), dx = -0.5
    #   it6: probe roundf(-0.5) = -1 -> (2,2) = 40 < 50: append the goal, done
    # (Python's round(-0.5) = 0 would probe (3,2) = 60 at it6 and not stop there.)
    pot = field(9, 5, lambda x, y: 20.0 * x)
    e = calc_path(pot, 9, 5, (5, 2), (0, 2), 36)
    assert e.exit == ExtractionExit.NEAR_GOAL
    assert e.path == [(5.0, 2.0), (4.5, 2.0), (4.0, 2.0), (3.5, 2.0), (3.0, 2.0), (0.0, 2.0)]
    assert e.points_written == 6


def test_calc_path_oscillation_forces_grid_fallback():
    # Potential 100 + 20|x + y - 4.5| on 7x7 (a valley between x+y = 4 and x+y = 5), except
    # (1, 1) = 20, a cell no gradient below uses. Start A = (2, 2):
    #   gradCell(A): dx = (130-110) + (110-110) = 20 = dy -> (s, s), s = 0.70710677
    #   gradCell(3,2), (2,3), (3,3): (-s, -s) (the other side of the valley)
    #   it1: append (2, 2); step along (s, s): dx = dy = d = 0.35355338
    #   it2: append (2+d, 2+d); interpolated x = y ~ -0.116 s (< 0): step back by 0.5 along
    #        (-1, -1)/sqrt2, which lands on dx = dy = 0.0 exactly (checked below with numpy)
    #   it3: append (2, 2) == the point two steps back -> oscillation -> lowest of eight:
    #        (1, 1) = 20 < 110 is the first (up-left) and lowest -> stc = (1, 1)
    #   it4: probe (1, 1) = 20 < 50 -> goal appended.
    # Without the oscillation test it3 would follow the gradient again, forever bouncing.
    s_inv = F(1.0 / F64(np.hypot(F(20), F(20))))
    s = F(s_inv * F(20))
    d = F(F(0) + F(s * F(F(0.5) / np.hypot(s, s))))

    def bil(t, a, b):
        return F((F64(1.0) - F64(t)) * F64(a) + F64(F(t * b)))

    x = bil(d, bil(d, s, -s), bil(d, -s, -s))
    assert x < 0
    back = F(d + F(x * F(F(0.5) / np.hypot(x, x))))
    assert back == 0.0  # the return step is exact
    p1 = (2.0, 2.0)
    p2 = (float(F(F(2) + d)), float(F(F(2) + d)))
    p3 = (float(F(F(2) + back)), float(F(F(2) + back)))
    assert p3 == p1  # pathx[npath-1] == pathx[npath-3], same for y

    pot = field(7, 7, lambda x_, y_: 100.0 + 20.0 * abs(x_ + y_ - 4.5))
    pot[1 * 7 + 1] = 20.0
    e = calc_path(pot, 7, 7, (2, 2), (1, 1), 28)
    assert e.exit == ExtractionExit.NEAR_GOAL
    assert e.path == [p1, p2, p3, (1.0, 1.0)]
    assert e.points_written == 4


@pytest.mark.parametrize("start", [(0, 4), (0, 1), (4, 3)])
def test_calc_path_undefined_behaviour_at_ring_corners(start):
    # (0, ny-1) passes the bound test (stc = ns - nx is not > ns - nx) but stc + nx reads past
    # potarr; (0, 1) reads potarr[-1]; (nx-1, ny-2) reads potarr[ns]
    pot = field(5, 5, lambda x, y: 100.0)
    with pytest.raises(UndefinedBehaviour):
        calc_path(pot, 5, 5, start, (2, 2), 10)


@pytest.mark.parametrize("backend", ["reference", "jit"])
def test_undefined_behaviour_at_bottom_left_start_in_backends(backend):
    costs = np.full((5, 6), 50, np.uint8)
    with pytest.raises(UndefinedBehaviour):
        get_backend(backend).prepare(costs).run((0, 4), (2, 2), True)


@pytest.mark.parametrize("start", [(0, 3), (4, 2)])
def test_calc_path_gradcell_reads_past_potarr_is_undefined(start):
    # all nine ring cells finite, so the gradient branch runs; gradCell(ns - nx) = gradCell(20)
    # on 5x5 passes its bound test (20 > 25 - 5 is false) and the C++ reads potarr[25]
    pot = field(5, 5, lambda x, y: 100.0 + 10.0 * x)
    with pytest.raises(UndefinedBehaviour):
        calc_path(pot, 5, 5, start, (2, 2), 10)
    # the JIT backend's extraction reports the same exit instead of reading out of bounds
    from navfn_smt.backends import jit as J
    from navfn_smt.backends.jit_state import new_trail_work
    from navfn_smt.backends.numba_domain import ND

    code = J.extract_path(ND, np.array(pot, np.float32), 5, 5, start[0], start[1], 2, 2, 10, new_trail_work(25, 10), False)
    assert code == J.EXIT_UB


# ======================================================================================
# 7. The reference spec and the JIT backend agree bit for bit
# ======================================================================================
@pytest.mark.parametrize("astar", [True, False])
@pytest.mark.parametrize("backend", ["reference", "jit"])
def test_planned_path_uses_roundf_in_the_near_goal_probe(backend, astar):
    # 9x5, interior cost 30, goal (1, 2), start (5, 2). The middle row gets 30 per cell
    # (one reached neighbour each time): (2,2) = 30, (3,2) = 60, (4,2) = 90, (5,2) = 120, and
    # the propagation stops there, leaving (5,1) and (6,2) unreached. Rows 1 and 3 are mirror
    # images. calcPath:
    #   at (5,2): unreached in the ring -> lowest of eight: (4,1) ~103 < 120, then (4,2) = 90
    #   at (4,2): (5,1) unreached -> lowest of eight: (3,1) ~76 < 90, then (3,2) = 60
    #   at (3,2): ring all reached; gradCell: dx = (30-60) + (60-90) = -60, dy = (u-60) + (60-u)
    #      = 0, 1/60 -> float, times -60 = -1.0 exactly; step: dx = -0.5
    #   probe: roundf(-0.5) = -1 -> (2,2) = 30 < 50 -> goal appended
    # (a half-to-even round would probe (3,2) = 60 and append (2.5, 2) first)
    assert float(F(F(1.0 / F64(60)) * F(-60))) == -1.0
    costs = np.full((5, 9), 30, np.uint8)
    r = get_backend(backend).prepare(costs).run((5, 2), (1, 2), astar)
    pot = r.potential
    assert [float(v) for v in pot[2, 1:6]] == [0.0, 30.0, 60.0, 90.0, 120.0]
    assert pot[1, 5] == HIGH and pot[2, 6] == HIGH
    assert (pot[1] == pot[3]).all() and 76 < pot[1, 3] < 90 and pot[1, 4] < 120
    assert r.exit == ExtractionExit.NEAR_GOAL
    assert r.path.tolist() == [[5.0, 2.0], [4.0, 2.0], [3.0, 2.0], [1.0, 2.0]]


def _run(backend_runner, start, goal, astar):
    try:
        r = backend_runner.run(start, goal, astar)
    except UndefinedBehaviour:
        return "UB"
    return (
        np.ascontiguousarray(r.path, dtype=np.float32).view(np.uint32).tobytes(),
        r.path.shape,
        np.ascontiguousarray(r.potential, dtype="<f4").tobytes(),
        np.asarray(r.trace, dtype=np.int32).tobytes(),
        r.cycles,
        r.updates,
        r.dropped,
        bool(r.start_reached),
        r.exit,
        int(np.float32(r.start_potential).view(np.uint32)),
    )


def cell(rng, nx, ny):
    """Mostly interior cells (where paths are long), sometimes any cell (borders, corners)."""
    if rng.random() < 0.8:
        return int(rng.integers(1, max(nx - 1, 2))), int(rng.integers(1, max(ny - 1, 2)))
    return int(rng.integers(0, nx)), int(rng.integers(0, ny))


def test_backends_agree_on_random_small_maps():
    rng = np.random.default_rng(20240611)
    exits: collections.Counter = collections.Counter()
    for case in range(200):
        ny, nx = (int(v) for v in rng.integers(3, 13, size=2))
        kind = rng.random((ny, nx))
        costs = rng.integers(1, 254, size=(ny, nx))
        costs[kind < 0.15] = 0
        costs[(kind >= 0.15) & (kind < 0.3)] = 254
        costs[(kind >= 0.3) & (kind < 0.33)] = 255
        costs[(kind >= 0.33) & (kind < 0.6)] = 50
        costs = costs.astype(np.uint8)
        ref = get_backend("reference").prepare(costs)
        jit = get_backend("jit").prepare(costs)
        for _ in range(2):
            start, goal = cell(rng, nx, ny), cell(rng, nx, ny)
            astar = bool(rng.integers(0, 2))
            a = _run(ref, start, goal, astar)
            b = _run(jit, start, goal, astar)
            # an UndefinedBehaviour corner must make both raise (a == b == "UB")
            exits[a if a == "UB" else a[8]] += 1
            assert a == b, (case, nx, ny, start, goal, astar, costs.tolist())
    # sanity: the sample exercises successful paths and several failure exits
    assert exits[ExtractionExit.NEAR_GOAL] > 50
    assert exits[ExtractionExit.HIGH_POTENTIAL] > 10 and exits[ExtractionExit.OUT_OF_BOUNDS] > 10
