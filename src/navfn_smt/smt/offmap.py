"""Z3 over IEEE binary64 (``Float64``, round-nearest-even) on the planner plugin's own double
arithmetic (:mod:`navfn_smt.nav2.offmap`), as the obligations do for NavFn's float32.

These are searches, not obligations: each first asks Z3 for a particular double (an end of
the interval of off-map points, the first double where the tolerance loop stalls, a goal
whose loop skips a column) and then proves, with unsat queries, that the double it found is
the one the claim is about.  An obligation states a fixed claim over its inputs; here the
claim is only known once the first query answers, so they live in a module of their own.

* :func:`offmap_interval`: the off-map points form exactly ``[lo, hi)``: Z3 finds both ends
  (the one double where the property switches on/off: ``P(w) and not P(w-)``) and proves the
  characterisation with three unsat queries.
* :func:`stall_threshold`: the smallest positive double ``p`` from which the tolerance loop's
  ``p += resolution`` no longer moves (Nav2 then loops forever).
* :func:`tolerance_gap`: a goal whose tolerance loop skips a map column (two consecutive points
  of the loop round two cells apart).

``python -m navfn_smt.smt.offmap REPORT.json`` runs every query of docs/plugin.md (minutes).
"""

from __future__ import annotations

import json
import math
import struct
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Optional

import numpy as np

from ..nav2.offmap import RES, centre_cells, hexf, loop_cells, next_up, offmap_interval_numeric

MASK63 = (1 << 63) - 1  # every bit of a double but its sign


def _z3():
    import z3

    return z3


def _fp(v: float):
    z3 = _z3()
    return z3.FPVal(float(v), z3.Float64())


def z3_offmap(w, origin: float, res: float, size: int):
    """The property as Z3 terms: ``w >= o``, ``q = (w - o) / res`` (RNE), ``trunc(q) < size``
    (roundToIntegral RTZ) and ``round(q) >= size`` (roundToIntegral RNA = std::round)."""
    z3 = _z3()
    q = z3.fpDiv(z3.RNE(), z3.fpSub(z3.RNE(), w, _fp(origin)), _fp(res))
    n = _fp(float(size))
    return z3.And(z3.Not(z3.fpIsNaN(w)), z3.Not(z3.fpIsInf(w)), z3.fpGEQ(w, _fp(origin)),
                  z3.fpLT(z3.fpRoundToIntegral(z3.RTZ(), q), n),
                  z3.fpGEQ(z3.fpRoundToIntegral(z3.RNA(), q), n))


def _z3_neighbour(bits, up: bool):
    """The double next to the one with these IEEE bits (toward +inf when ``up``), as bits."""
    z3 = _z3()
    one = z3.BitVecVal(1, 64)
    sign = z3.Extract(63, 63, bits) == z3.BitVecVal(1, 1)
    is_zero = (bits & z3.BitVecVal(MASK63, 64)) == z3.BitVecVal(0, 64)
    if up:  # -0/+0 -> smallest positive subnormal
        return z3.If(is_zero, one, z3.If(sign, bits - one, bits + one))
    return z3.If(is_zero, z3.BitVecVal((1 << 63) | 1, 64), z3.If(sign, bits + one, bits - one))


@dataclass
class Query:
    name: str
    verdict: str
    seconds: float
    model: Optional[float] = None


@dataclass
class Interval:
    """``{w : offmap(w)} == [lo, hi)`` on one axis of a map, with the queries that show it."""

    origin: float
    resolution: float
    size: int
    lo: float
    hi: float
    queries: list = field(default_factory=list)

    @property
    def proved(self) -> bool:
        want = {"lower end": "sat", "upper end": "sat",
                "none below lo": "unsat", "none at or above hi": "unsat", "all of [lo, hi)": "unsat"}
        got = {q.name: q.verdict for q in self.queries}
        return all(got.get(k, v) == v for k, v in want.items()) and all(k in got for k in list(want)[2:])

    def as_dict(self) -> dict:
        return {"origin": self.origin, "resolution": self.resolution, "size": self.size,
                "lo": hexf(self.lo), "hi": hexf(self.hi), "lo_decimal": repr(self.lo), "hi_decimal": repr(self.hi),
                "proved": self.proved,
                "queries": [{"name": q.name, "verdict": q.verdict, "seconds": round(q.seconds, 2),
                             **({"model": hexf(q.model)} if q.model is not None else {})} for q in self.queries]}


def _check(name: str, constraints, var=None, timeout: float = 120.0) -> Query:
    z3 = _z3()
    s = z3.Solver()
    s.set("timeout", int(timeout * 1000))
    s.add(*constraints)
    t = time.perf_counter()
    r = s.check()
    q = Query(name, str(r), time.perf_counter() - t)
    if r == z3.sat and var is not None:
        q.model = _model_double(s.model(), var)
    return q


def _model_double(model, var) -> float:
    z3 = _z3()
    v = model.eval(var, model_completion=True)
    if z3.is_bv(v):
        return struct.unpack("<d", struct.pack("<Q", v.as_long()))[0]
    bits = model.eval(z3.fpToIEEEBV(var), model_completion=True).as_long()
    return struct.unpack("<d", struct.pack("<Q", bits))[0]


def offmap_interval(origin: float, res: float, size: int, prove: bool = True, find: bool = True,
                    timeout: float = 120.0) -> Interval:
    """Z3 finds the ends (``find``): a double ``w`` with ``P(w)`` and not ``P`` of the double below
    (the lower end) or above (the upper end, ``hi`` is the double after it); then (``prove``) that
    ``P`` holds for no double below ``lo``, for none at or above ``hi``, and for every double in
    ``[lo, hi)``.  Without ``find`` the ends come from :func:`offmap_interval_numeric` and are only
    proved."""
    z3 = _z3()
    lo, hi = offmap_interval_numeric(origin, res, size)
    iv = Interval(origin, res, size, lo, hi)
    if find:
        bits = z3.BitVec("b", 64)
        w = z3.fpBVToFP(bits, z3.Float64())
        for name, up in (("lower end", False), ("upper end", True)):
            nb = z3.fpBVToFP(_z3_neighbour(bits, up), z3.Float64())
            q = _check(name, [z3_offmap(w, origin, res, size), z3.Not(z3_offmap(nb, origin, res, size))], bits, timeout)
            iv.queries.append(q)
            if q.model is None:
                continue
            end = q.model if not up else next_up(q.model)
            if up:
                iv.hi = end
            else:
                iv.lo = end
    if prove:
        w = z3.FP("w", z3.Float64())
        p = z3_offmap(w, origin, res, size)
        iv.queries.append(_check("none below lo", [p, z3.fpLT(w, _fp(iv.lo))], w, timeout))
        iv.queries.append(_check("none at or above hi", [p, z3.fpGEQ(w, _fp(iv.hi))], w, timeout))
        iv.queries.append(_check("all of [lo, hi)", [z3.Not(p), z3.fpGEQ(w, _fp(iv.lo)), z3.fpLT(w, _fp(iv.hi))],
                                 w, timeout))
    return iv


# --------------------------------------------------------------------------- the tolerance loop
@dataclass
class Stall:
    resolution: float
    threshold: float  # the smallest positive double p with p + res == p
    queries: list = field(default_factory=list)


def stall_threshold(res: float, timeout: float = 60.0) -> Stall:
    """The smallest positive ``p`` with ``fl(p + res) == p``: Z3 gives the only double ``p >= 0``
    where the loop stalls and the double below does not; then "a stalling ``p`` in ``[0, t)``" is
    unsat and "a ``p >= t`` that moves" is unsat (once the spacing of doubles exceeds ``2 res`` no
    addition of ``res`` moves)."""
    z3 = _z3()
    D = z3.Float64()
    bits = z3.BitVec("b", 64)
    p = z3.fpBVToFP(bits, D)
    below = z3.fpBVToFP(_z3_neighbour(bits, False), D)

    def stalls(x):
        return z3.And(z3.Not(z3.fpIsNaN(x)), z3.Not(z3.fpIsInf(x)), z3.fpEQ(z3.fpAdd(z3.RNE(), x, _fp(res)), x))

    st = Stall(res, math.nan)
    q = _check("first stalling double", [z3.fpGT(p, _fp(0.0)), stalls(p), z3.Not(stalls(below))], bits, timeout)
    st.queries.append(q)
    if q.model is None:
        return st
    st.threshold = q.model
    w = z3.FP("p", D)
    st.queries.append(_check("no stall in [0, t)", [z3.fpGEQ(w, _fp(0.0)), z3.fpLT(w, _fp(st.threshold)), stalls(w)],
                             w, timeout))
    st.queries.append(_check("every p >= t stalls", [z3.fpGEQ(w, _fp(st.threshold)), z3.Not(z3.fpIsInf(w)),
                                                    z3.Not(stalls(w))], w, timeout))
    return st


def tolerance_gap(origin: float, res: float, tolerance: float, lo: float, hi: float,
                  timeout: float = 300.0) -> Optional[dict]:
    """Z3: a goal ``g`` in ``[lo, hi]`` whose tolerance loop's first two points round to cells two
    apart (``round((p1 - o)/res) - round((p0 - o)/res) == 2`` with ``p0 = g - tol``,
    ``p1 = p0 + res``): the column between them is never examined.  Returns the goal and the cells
    the loop visits, or None (unsat or unknown)."""
    z3 = _z3()
    D = z3.Float64()
    rne = z3.RNE()
    g = z3.FP("g", D)
    p0 = z3.fpSub(rne, g, _fp(tolerance))
    p1 = z3.fpAdd(rne, p0, _fp(res))

    def cell(p):
        return z3.fpRoundToIntegral(z3.RNA(), z3.fpDiv(rne, z3.fpSub(rne, p, _fp(origin)), _fp(res)))

    q = _check("skipped column", [z3.fpGEQ(g, _fp(lo)), z3.fpLEQ(g, _fp(hi)), z3.fpGEQ(p0, _fp(origin)),
                                  z3.fpEQ(z3.fpSub(rne, cell(p1), cell(p0)), _fp(2.0))], g, timeout)
    if q.model is None:
        return {"goal": None, "query": q}
    return {"goal": q.model, "cells": loop_cells(q.model, tolerance, origin, res), "query": q}


def main(argv=None) -> int:
    """``python -m navfn_smt.smt.offmap REPORT.json``: every Z3 query of docs/plugin.md, the
    verdicts and the doubles found written to REPORT.json (minutes)."""
    import argparse

    ap = argparse.ArgumentParser(prog="python -m navfn_smt.smt.offmap")
    ap.add_argument("report")
    a = ap.parse_args(argv)
    rep = {}
    for what, o, n in (("x of an 8x6 map at 0, 0", 0.0, 8), ("y of an 8x6 map at 0, 0", 0.0, 6),
                       ("x of a 400-wide map at -10", -10.0, 400)):
        iv = offmap_interval(o, RES, n)
        rep[what] = iv.as_dict()
        print(what, rep[what])
    st = stall_threshold(RES)
    rep["stall"] = {"threshold": hexf(st.threshold), "decimal": repr(st.threshold),
                    "queries": [(q.name, q.verdict, round(q.seconds, 2)) for q in st.queries]}
    print(rep["stall"])
    gap = tolerance_gap(-10.0, RES, 0.5, -9.5, 0.0)
    rep["gap"] = {"goal": None if gap["goal"] is None else hexf(gap["goal"]), "cells": gap.get("cells"),
                  "verdict": gap["query"].verdict, "seconds": round(gap["query"].seconds, 2)}
    print(rep["gap"])
    rep["centre_cells_8_at_0"] = centre_cells(0.0, RES, 8).tolist()
    rep["centre_cells_400_at_-10"] = int((centre_cells(-10.0, RES, 400) == np.arange(1, 401)).sum())
    Path(a.report).write_text(json.dumps(rep, indent=1) + "\n")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
