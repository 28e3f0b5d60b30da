"""The model codec (navfn_smt.smt.codec): bit patterns, entries and replay values."""

from __future__ import annotations

import math
from fractions import Fraction

import numpy as np
import pytest

z3 = pytest.importorskip("z3")

from navfn_smt.smt import codec  # noqa: E402

pytestmark = pytest.mark.fast

PATTERNS32 = [0x00000000, 0x80000000, 0x00000001, 0x807FFFFF, 0x3F800000, 0x7F7FFFFF, 0x7F800000, 0xFF800000,
              0x4B800000, 0xC0490FDB]


@pytest.mark.parametrize("bits", PATTERNS32)
def test_float32_bits_round_trip(bits):
    x = codec.f32_from_bits(bits)
    assert x == float(np.array([bits], dtype=np.uint32).view(np.float32)[0]) or math.isnan(x)
    assert codec.f32_to_bits(x) == bits
    assert codec.fp_value(bits, 8, 24) == x


def test_float64_bits_and_other_formats():
    for x in (0.0, -0.0, 1.0 / 3.0, 5e-324, -1.7976931348623157e308, math.inf):
        b = codec.f64_to_bits(x)
        assert codec.f64_from_bits(b) == x and codec.fp_value(b, 11, 53) == x
        assert str(codec.f64_from_bits(b)) == str(x)  # -0.0 keeps its sign
    assert codec.fp_value(0x3C00, 5, 11) == 1.0 and codec.fp_value(0x0001, 5, 11) == 2.0**-24
    assert codec.fp_value(0x7C00, 5, 11) == math.inf and math.isnan(codec.fp_value(0x7E00, 5, 11))
    assert codec.fp_sort_name(8, 24) == "FP32" and codec.fp_sort_name(3, 5) == "FP(3,5)"


def test_nan_patterns():
    assert codec.canonical_nan_bits(8, 24) == 0x7FC00000 and codec.canonical_nan_bits(11, 53) == 0x7FF8000000000000
    assert codec.is_nan_bits(0x7FC00000, 8, 24) and codec.is_nan_bits(0xFF800001, 8, 24)
    assert not codec.is_nan_bits(0x7F800000, 8, 24)
    model = {"x": codec.fp_entry(0x7FC00000, 8, 24), "y": codec.fp_entry(0x3F800000, 8, 24), "aux": 0x7FC00123}
    pinned = codec.pin_nan_patterns(model, {(8, 24): "aux"})
    assert pinned["x"]["bits"] == 0x7FC00123 and pinned["y"] == model["y"]
    assert model["x"]["bits"] == 0x7FC00000  # the argument is not changed


def test_z3_terms_have_exactly_the_bits():
    for bits in PATTERNS32:
        t = codec.fp32_val(codec.f32_from_bits(bits))
        if not math.isnan(codec.f32_from_bits(bits)):
            assert z3.simplify(z3.fpToIEEEBV(t)).as_long() == bits
    assert z3.simplify(z3.fpToIEEEBV(codec.fp64_val(-0.0))).as_long() == 1 << 63
    assert codec.fp_term(0x4B800000, z3.Float32()).eq(codec.fp32_val(2.0**24))


def test_z3_model_entries_and_replay_values():
    x, n, c, k = z3.FP("x", z3.Float32()), z3.BitVec("n", 32), z3.BitVec("c", 8), z3.Int("k")
    r = z3.Real("r")
    s = z3.Solver()
    s.add(x == codec.fp32_val(-1.5), n == -7, c == 200, k == -3, r == z3.RealVal("1/3"))
    assert s.check() == z3.sat
    variables = {"x": x, "n": n, "c": c, "k": k, "r": r}
    model = codec.z3_model(s.model(), variables.values())
    assert model["x"] == codec.fp_entry(0xBFC00000, 8, 24)
    assert model["n"] == 2**32 - 7 and model["c"] == 200 and model["k"] == -3 and model["r"] == Fraction(1, 3)
    assert codec.replay_values(model, variables) == {"x": -1.5, "n": -7, "c": 200, "k": -3, "r": Fraction(1, 3)}
    assert codec.replay_values({**model, "r": "(root-obj ...)"}, variables) is None
    assert codec.replay_values({k: v for k, v in model.items() if k != "x"}, variables) is None
    for name, v in variables.items():
        assert z3.is_true(z3.simplify(codec.entry_to_z3(model[name], v) == s.model().eval(v)))


def test_witness_values_are_json():
    w = codec.witness_values({"x": 1.0, "q": Fraction(1, 3), "n": -7})
    assert w == {"x": {"value": 1.0, "bits32": "0x3f800000"}, "q": {"value": "1/3"}, "n": {"value": -7}}


def test_rounding_mode_names():
    assert codec.rm_name("roundTowardZero") == "RTZ" and codec.rm_name("RoundingMode.RNA") == "RNA"
