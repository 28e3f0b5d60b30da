"""The one model codec: how values cross between the solvers and Python.

Its one job is the representation of values at the solver boundary, in both directions:

* IEEE-754 bit patterns and Python floats: :func:`f32_to_bits`, :func:`f32_from_bits`,
  their float64 twins, and :func:`fp_value` for any format (NaN, -0.0 and subnormals exact);
* Python floats and bit patterns as Z3 terms with exactly those bits (:func:`fp32_val`,
  :func:`fp64_val`, :func:`fp_term`);
* a solver's model as *entries*, the one form every solver's answer takes
  (:func:`z3_model`, :func:`bitwuzla_entry`, :func:`cvc5_entry`): floating point as
  ``{"sort": "FP32", "bits": 0x3f800000, "value": 1.0, "ebits": 8, "sbits": 24}``,
  bit-vectors as unsigned ints, Bools as bools, Ints as ints, Reals as
  ``fractions.Fraction`` (irrational algebraic reals as their solver's text), rounding
  modes as ``"RNE"``/``"RNA"``/``"RTP"``/``"RTN"``/``"RTZ"``, anything else as the
  solver's text;
* entries as the values an obligation is replayed with (:func:`replay_values`), replay
  values as JSON (:func:`witness_values`), and entries back as Z3 values
  (:func:`entry_to_z3`, for checking a model against the query).

In the bitwuzla and cvc5 worker processes ``z3`` is an empty stand-in module (see
:mod:`navfn_smt.smt.worker`): nothing here touches it at import time.
"""

from __future__ import annotations

import functools
import math
import struct
from fractions import Fraction
from typing import Any, Optional

import z3

_F32, _F64 = struct.Struct("<f"), struct.Struct("<d")
_U32, _U64 = struct.Struct("<I"), struct.Struct("<Q")


# ------------------------------------------------------------------ float bits
def f32_to_bits(x: float) -> int:
    """The binary32 bit pattern of a float32 value."""
    return _U32.unpack(_F32.pack(x))[0]


def f32_from_bits(bits: int) -> float:
    """The float32 value with binary32 bit pattern ``bits``."""
    return _F32.unpack(_U32.pack(bits))[0]


def f64_to_bits(x: float) -> int:
    """The binary64 bit pattern of a float."""
    return _U64.unpack(_F64.pack(x))[0]


def f64_from_bits(bits: int) -> float:
    """The float with binary64 bit pattern ``bits``."""
    return _F64.unpack(_U64.pack(bits))[0]


def fp_sort_name(eb: int, sb: int) -> str:
    """The name of an IEEE format in entries: FP16, FP32, FP64, FP128 or FP(eb,sb)."""
    return {(5, 11): "FP16", (8, 24): "FP32", (11, 53): "FP64", (15, 113): "FP128"}.get(
        (eb, sb), f"FP({eb},{sb})"
    )


def fp_value(bits: int, eb: int, sb: int) -> float:
    """The Python float of an IEEE bit pattern (exact for FP16/FP32/FP64)."""
    if (eb, sb) == (8, 24):
        return f32_from_bits(bits)
    if (eb, sb) == (11, 53):
        return f64_from_bits(bits)
    sign = -1.0 if bits >> (eb + sb - 1) & 1 else 1.0
    exp = (bits >> (sb - 1)) & ((1 << eb) - 1)
    man = bits & ((1 << (sb - 1)) - 1)
    bias = (1 << (eb - 1)) - 1
    if exp == (1 << eb) - 1:
        return math.nan if man else sign * math.inf
    if exp == 0:
        frac = Fraction(man) * Fraction(2) ** (1 - bias - (sb - 1))
    else:
        frac = Fraction((1 << (sb - 1)) | man) * Fraction(2) ** (exp - bias - (sb - 1))
    try:
        return sign * float(frac)
    except OverflowError:
        return sign * math.inf


def is_nan_bits(bits: int, eb: int, sb: int) -> bool:
    """Whether ``bits`` is a NaN pattern of the format (eb, sb)."""
    exp = (bits >> (sb - 1)) & ((1 << eb) - 1)
    return exp == (1 << eb) - 1 and bits & ((1 << (sb - 1)) - 1) != 0


def canonical_nan_bits(eb: int, sb: int) -> int:
    """The quiet NaN with an empty payload: the pattern reported when a model does not say."""
    return (((1 << eb) - 1) << (sb - 1)) | (1 << (sb - 2))


def fp_entry(bits: int, eb: int, sb: int) -> dict:
    """The entry of a floating-point model value: its format, exact bits and Python float."""
    return {"sort": fp_sort_name(eb, sb), "bits": bits, "value": fp_value(bits, eb, sb),
            "ebits": eb, "sbits": sb}


_RM_NAMES = {
    "roundNearestTiesToEven": "RNE", "RNE": "RNE",
    "roundNearestTiesToAway": "RNA", "RNA": "RNA",
    "roundTowardPositive": "RTP", "RTP": "RTP",
    "roundTowardNegative": "RTN", "RTN": "RTN",
    "roundTowardZero": "RTZ", "RTZ": "RTZ",
    "ROUND_NEAREST_TIES_TO_EVEN": "RNE",
    "ROUND_NEAREST_TIES_TO_AWAY": "RNA",
    "ROUND_TOWARD_POSITIVE": "RTP",
    "ROUND_TOWARD_NEGATIVE": "RTN",
    "ROUND_TOWARD_ZERO": "RTZ",
}


def rm_name(x) -> str:
    """The entry of a rounding mode (any solver's spelling of it): RNE, RNA, RTP, RTN or RTZ."""
    s = getattr(x, "name", None) or str(x)
    s = s.split(".")[-1]
    return _RM_NAMES.get(s, s)


# ------------------------------------------------------------ floats as Z3 terms
@functools.cache
def _fp_sort(eb: int, sb: int):
    """The Z3 floating-point sort (eb, sb) of the main context, made once."""
    return z3.FPSort(eb, sb)


def fp_term(bits: int, sort):
    """The Z3 floating-point value of ``sort`` with exactly the bit pattern ``bits``."""
    ctx = sort.ctx
    return z3.fpBVToFP(z3.BitVecVal(bits, sort.ebits() + sort.sbits(), ctx), sort, ctx)


def fp32_val(x: float):
    """The Float32 value with exactly the bits of float32 ``x`` (NaN, -0.0 included)."""
    return fp_term(f32_to_bits(x), _fp_sort(8, 24))


def fp64_val(x: float):
    """The Float64 value with exactly the bits of ``x``."""
    return fp_term(f64_to_bits(x), _fp_sort(11, 53))


# ------------------------------------------------------------ models as entries
def z3_entry(model, c) -> Any:
    """The entry of constant ``c`` in a Z3 model (a NaN with the pattern the model gives
    ``fp.to_ieee_bv`` of it, when it says; else the canonical NaN)."""
    v = model.eval(c, model_completion=True)
    s = c.sort()
    if z3.is_fp_sort(s):
        eb, sb = s.ebits(), s.sbits()
        if isinstance(v, z3.FPNumRef) and v.isNaN():
            # Z3 maps all NaNs to one unspecified pattern; if the query used
            # fp.to_ieee_bv the model says which one.
            ieee = model.eval(z3.fpToIEEEBV(c), model_completion=True)
            if z3.is_bv_value(ieee) and is_nan_bits(ieee.as_long(), eb, sb):
                return fp_entry(ieee.as_long(), eb, sb)
            return fp_entry(canonical_nan_bits(eb, sb), eb, sb)
        b = z3.simplify(z3.fpToIEEEBV(v))
        return fp_entry(b.as_long(), eb, sb) if z3.is_bv_value(b) else v.sexpr()
    if z3.is_bv_sort(s):
        return v.as_long() if z3.is_bv_value(v) else v.sexpr()
    if s.kind() == z3.Z3_BOOL_SORT:
        return z3.is_true(v) if (z3.is_true(v) or z3.is_false(v)) else v.sexpr()
    if s.kind() == z3.Z3_INT_SORT:
        return v.as_long() if z3.is_int_value(v) else v.sexpr()
    if s.kind() == z3.Z3_REAL_SORT:
        if z3.is_rational_value(v):
            return Fraction(v.numerator_as_long(), v.denominator_as_long())
        return v.sexpr()
    if s.kind() == z3.Z3_ROUNDING_MODE_SORT:
        return rm_name(v.sexpr())
    return v.sexpr()


def z3_model(model, consts) -> dict:
    """The entries of the constants ``consts`` in a Z3 model, by name (a value that has
    no entry: the model's text of it)."""
    out = {}
    for c in consts:
        try:
            out[c.decl().name()] = z3_entry(model, c)
        except Exception:  # keep the answer; the value as text
            out[c.decl().name()] = model.eval(c, model_completion=True).sexpr()
    return out


def bitwuzla_entry(value, sort) -> Any:
    """The entry of a Bitwuzla value term of ``sort`` (its text when it has none)."""
    try:
        if sort.is_fp():
            return fp_entry(int(value.value(2, False), 2), sort.fp_exp_size(), sort.fp_sig_size())
        if sort.is_bv():
            return int(value.value(2), 2)
        if sort.is_bool():
            return bool(value.value())
        if sort.is_rm():
            return rm_name(value.value())
    except Exception:  # keep the answer; the value as text
        pass
    return str(value)


def cvc5_entry(value, sort) -> Any:
    """The entry of a cvc5 value term of ``sort`` (its text when it has none)."""
    try:
        if sort.isFloatingPoint():
            eb, sb, bv = value.getFloatingPointValue()
            return fp_entry(int(bv.getBitVectorValue(2), 2), eb, sb)
        if sort.isBitVector():
            return int(value.getBitVectorValue(2), 2)
        if sort.isBoolean():
            return bool(value.getBooleanValue())
        if sort.isInteger():
            return int(value.getIntegerValue())
        if sort.isReal():
            return Fraction(value.getRealValue()) if value.isRealValue() else str(value)
        if sort.isRoundingMode():
            return rm_name(value.getRoundingModeValue())
    except Exception:  # keep the answer; the value as text
        pass
    return str(value)


def pin_nan_patterns(model: dict, nan_consts: dict) -> dict:
    """``model`` with each NaN of a format the query names a NaN-pattern constant for
    (``nan_consts``: (eb, sb) -> constant name) given that constant's bits: the pattern
    ``fp.to_ieee_bv`` gives NaN in this model."""
    model = dict(model)
    for key, aux in nan_consts.items():
        pattern = model.get(aux)
        if not isinstance(pattern, int):
            continue
        for name, v in model.items():
            if isinstance(v, dict) and (v.get("ebits"), v.get("sbits")) == key and \
                    is_nan_bits(v["bits"], *key):
                model[name] = fp_entry(pattern, *key)
    return model


# ------------------------------------------------------------ entries as values
def replay_value(entry, var) -> Any:
    """The value variable ``var`` takes in a concrete replay: floats by their exact bits,
    bit-vectors as ints (8-bit costs unsigned, other widths two's complement), Ints as ints,
    Reals as fractions; None for an entry that is no number (a solver's text)."""
    if isinstance(entry, dict) and "bits" in entry:
        return fp_value(int(entry["bits"]), entry["ebits"], entry["sbits"])
    if isinstance(entry, (bool, Fraction)):
        return entry
    if isinstance(entry, int):
        s = var.sort()
        if z3.is_bv_sort(s) and s.size() != 8 and entry >= 1 << (s.size() - 1):
            return entry - (1 << s.size())
        return entry
    return None


def replay_values(model: dict, variables: dict) -> Optional[dict]:
    """The obligation's variables (name -> Z3 constant) as replay values from a model of
    entries; None when the model lacks one or gives one that is no number."""
    out = {}
    for name, var in variables.items():
        value = replay_value(model.get(name), var)
        if value is None:
            return None
        out[name] = value
    return out


def witness_values(values: dict) -> dict:
    """Replay values as JSON: floats with their float32 bit pattern, fractions as text."""
    out = {}
    for k, v in values.items():
        if isinstance(v, float):
            out[k] = {"value": v, "bits32": f"0x{f32_to_bits(v):08x}"}
        elif isinstance(v, Fraction):
            out[k] = {"value": str(v)}
        else:
            out[k] = {"value": v}
    return out


def entry_to_z3(entry, c):
    """The Z3 value of an entry for constant ``c`` (None: it has none)."""
    s = c.sort()
    ctx = c.ctx
    if z3.is_fp_sort(s):
        return fp_term(entry["bits"], s) if isinstance(entry, dict) else None
    if z3.is_bv_sort(s):
        return z3.BitVecVal(entry, s.size(), ctx) if isinstance(entry, int) else None
    if s.kind() == z3.Z3_BOOL_SORT:
        return z3.BoolVal(entry, ctx) if isinstance(entry, bool) else None
    if s.kind() == z3.Z3_INT_SORT:
        return z3.IntVal(entry, ctx) if isinstance(entry, int) else None
    if s.kind() == z3.Z3_REAL_SORT:
        if isinstance(entry, (int, Fraction)):
            q = Fraction(entry)
            return z3.RealVal(f"{q.numerator}/{q.denominator}", ctx)
        return None
    if s.kind() == z3.Z3_ROUNDING_MODE_SORT:
        f = {"RNE": z3.RNE, "RNA": z3.RNA, "RTP": z3.RTP, "RTN": z3.RTN, "RTZ": z3.RTZ}.get(entry)
        return f(ctx) if f else None
    return None


def free_constants(terms) -> dict:
    """The uninterpreted constants (the variables) the Z3 ``terms`` mention, by name."""
    seen, out, todo = set(), {}, list(terms)
    while todo:
        t = todo.pop()
        if t.get_id() in seen:
            continue
        seen.add(t.get_id())
        if z3.is_const(t) and t.decl().kind() == z3.Z3_OP_UNINTERPRETED:
            out[t.decl().name()] = t
        todo.extend(t.children())
    return out
