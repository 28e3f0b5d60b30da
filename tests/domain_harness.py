"""The conformance harness: every numeric domain run on the kernels' table, held to the concrete one.

The table (:mod:`navfn_smt.spec.conformance`) states the kernels and the one input mix (NaN,
infinities, zeros of both signs, subnormals, rounding ties, 2**24 and the largest float,
potentials, edge weights, offsets, arbitrary bit patterns, every cost byte).  Here each kind
of domain says only how it takes a plain input in and gives its results back, and
:func:`mismatches` compares them with the concrete domain's bit for bit (``agree``):

- ``numba``: the fast backend's domain, each kernel's call compiled and run on float32/int64;
- ``concolic``: every float input an interval two float32 steps either side of its value,
  every cost a box of five bytes; the concrete part must be the concrete result, and each
  result's interval must hold it and the concrete results at corners of the box (the low, the
  high and two drawn at random) that take the same branches;
- ``array``: numpy arrays, one call per kernel on every input at once, for the kernels whose
  arguments are arrays (the enumeration of :mod:`navfn_smt.smt.enumerate`);
- ``fp32``: the bit-precise domain on constants, its terms folded to values, and its library
  model admitting what the platform's libm returns (:mod:`navfn_smt.smt.evaluate`);
- ``real``: exact arithmetic, so equal to the concrete results only where nothing rounds
  (``push_admitted``); ``real-exact``: on the finite inputs of the kernels that round and call
  no ``hypot``, equal to the same kernel evaluated exactly on rationals (``ExactReplayDomain``).

:data:`RUNS` names each with its inputs; :data:`DOMAIN_CLASSES` and :func:`missing` hold every
domain to the interface (:class:`navfn_smt.spec.domain.NumericDomain`).  The tests run every
kernel in every domain (``tests/test_domain_conformance.py``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from functools import lru_cache, partial
from typing import Callable

import numpy as np
from numba import njit

from navfn_smt.backends.numba_domain import JIT_OPTIONS, numba_domain
from navfn_smt.check.concolic import ConcolicDomain, V, concrete
from navfn_smt.smt.domains import FPDomain, RealDomain
from navfn_smt.smt.enumerate import ArrayDomain
from navfn_smt.smt.errmodel import ErrorModelDomain
from navfn_smt.smt.evaluate import FPEvalDomain, NotConstant, fp32_result, lift, value
from navfn_smt.smt.replay import ExactReplayDomain, ReplayDomain
from navfn_smt.spec import conformance as T
from navfn_smt.spec.domain import OPERATIONS
from navfn_smt.spec.arithmetic import KNOWN
from navfn_smt.spec.numeric import CONCRETE as C
from navfn_smt.spec.numeric import ConcreteDomain

class RealEvalDomain(RealDomain):
    """The real domain on constants."""


# every class that runs the kernels (the numba domain's operations: its OPERATIONS table)
DOMAIN_CLASSES = (ConcreteDomain, ReplayDomain, ExactReplayDomain, ArrayDomain, FPDomain, FPEvalDomain,
                  RealDomain, RealEvalDomain, ErrorModelDomain, ConcolicDomain)


def missing(provided) -> set:
    """The operations of the interface that ``provided`` (a domain's attribute names) lacks."""
    return set(OPERATIONS) - set(provided)


# ------------------------------------------------------------------------ the domains
_COMPILED: dict = {}


def _numba_value(kind, v):
    if kind in (T.F32, T.COST_F32):
        return np.float32(v)
    return np.bool_(v) if kind == T.BOOL else np.int64(v)


def numba_results(case: T.KernelCase, rows: list, arith=None) -> list:
    """``case`` compiled against the numba domain in the arithmetic ``arith`` (None: x86-64's,
    :data:`~navfn_smt.backends.numba_domain.ND`), called on each row."""
    if case.name not in _COMPILED:
        _COMPILED[case.name] = njit(**JIT_OPTIONS)(case.call)
    f, D = _COMPILED[case.name], numba_domain(arith)
    return [tuple(f(D, *(_numba_value(k, v) for k, v in zip(case.kinds, args)))) for args in rows]


def _around(v: float, steps: int = 2) -> tuple:
    """The float32 interval ``steps`` float32 values either side of ``v`` (NaN: itself)."""
    lo = hi = np.float32(v)
    with np.errstate(over="ignore"):
        for _ in range(steps):
            lo, hi = np.nextafter(lo, np.float32(-np.inf)), np.nextafter(hi, np.float32(np.inf))
    return float(lo), float(hi)


def _box(kind, v) -> tuple:
    """The interval an input of ``kind`` ranges over in the concolic run: a float two float32
    steps either side, a cost two bytes either side (within 0..255), anything else itself."""
    if kind == T.F32:
        return _around(v)
    if kind in (T.COST, T.COST_F32):
        lo, hi = max(0, int(v) - 2), min(255, int(v) + 2)
        return (float(lo), float(hi)) if kind == T.COST_F32 else (lo, hi)
    return v, v


def _concolic_value(D, kind, v, box):
    if kind == T.F32:
        return V("f32", v, box[0], box[1], D.S.f32const(v))
    if kind in (T.COST, T.COST_F32):
        cost = D.cost(int(v), int(box[0]), int(box[1]), "c")  # one cost byte: both kinds name it "c"
        return D.cost_int(cost) if kind == T.COST else D.cost_as_f32(cost)
    return v


def _corners(case: T.KernelCase, boxes: list, rng) -> list:
    """The low and high corners of the boxes and two corners drawn at random (the cost
    arguments, one byte, take the same side)."""
    cost = np.array([k in (T.COST, T.COST_F32) for k in case.kinds])
    sides = [np.zeros(len(boxes), int), np.ones(len(boxes), int)] + [rng.integers(2, size=len(boxes)) for _ in "ab"]
    for side in sides[2:]:
        side[cost] = side[cost.argmax()]
    return [tuple(b[s] for b, s in zip(boxes, side)) for side in sides]


class _Path(ConcreteDomain):
    """The concrete domain, recording the branch every ``ite`` takes."""

    def __init__(self):
        self.taken: list = []

    def ite(self, c, a, b):
        self.taken.append(bool(c))
        return a if c else b


def _on_path(case: T.KernelCase, args: tuple) -> tuple:
    """``(results, branches taken)`` of the concrete kernel on ``args``."""
    P = _Path()
    return case.call(P, *args), P.taken


def holds(r, x) -> bool:
    """The interval of result ``r`` holds the value ``x`` (bools, NaN and plain results aside)."""
    if not isinstance(r, V) or r.kind == "bool" or (isinstance(x, float) and math.isnan(x)):
        return True
    return r.lo <= x <= r.hi or (isinstance(r.lo, float) and math.isnan(r.lo))


def concolic_results(case: T.KernelCase, rows: list, domain=ConcolicDomain) -> list:
    """``case`` in the concolic domain (terms in the bit-precise one) on a box around each row:
    the concrete parts; or a sentence when a result's interval misses its value, or the value
    at a corner of the box that takes the same branches (the intervals hold on the path)."""
    rng = np.random.default_rng(0)
    out = []
    for args in rows:
        D = domain(FPEvalDomain())
        boxes = [_box(k, v) for k, v in zip(case.kinds, args)]
        res = case.call(D, *(_concolic_value(D, k, v, b) for k, v, b in zip(case.kinds, args, boxes)))
        _, path = _on_path(case, args)
        values = [tuple(concrete(r) for r in res)]
        values += [got for got, taken in (_on_path(case, c) for c in _corners(case, boxes, rng)) if taken == path]
        missed = [(r, x) for xs in values for r, x in zip(res, xs) if not holds(r, x)]
        out.append(f"the interval misses a value: {missed[:2]}" if missed else values[0])
    return out


def array_results(case: T.KernelCase, rows: list, domain=ArrayDomain) -> list:
    """``case`` in the array domain, one call on the columns of every row at once."""
    cols = [np.array(c, np.float32 if k in (T.F32, T.COST_F32) else None) for k, c in zip(case.kinds, zip(*rows))]
    with np.errstate(all="ignore"):
        out = [np.broadcast_to(r, (len(rows),)) for r in case.call(domain({}), *cols)]
    return [tuple(r[i] for r in out) for i in range(len(rows))]


def fp32_results(case: T.KernelCase, rows: list) -> list:
    """``case`` in the bit-precise domain on each row (:func:`navfn_smt.smt.evaluate.fp32_result`)."""
    return [fp32_result(case, args) for args in rows]


def real_result(case: T.KernelCase, args: tuple, domain=RealEvalDomain):
    """``case``'s results on one finite input of the table in the real domain (Fractions, ints,
    bools), or a sentence saying why there are none."""
    D = domain()
    try:
        return tuple(value(v) for v in case.call(D, *(lift(D, k, v) for k, v in zip(case.kinds, args))))
    except NotConstant as e:
        return f"not determined: {str(e)[:200]}"


def real_results(case: T.KernelCase, rows: list, domain=RealEvalDomain) -> list:
    """``case`` in the real domain on each (finite) row."""
    return [real_result(case, args, domain) for args in rows]


# ------------------------------------------------------------------------ what they must equal
def concrete_results(case: T.KernelCase, rows: list, arith=None) -> list:
    """The concrete spec's results (in the arithmetic ``arith``; None: x86-64's): what every
    domain is held to."""
    D = C if arith is None else C.with_arithmetic(arith)
    return [case.call(D, *args) for args in rows]


def _exact_value(E, kind, v):
    if kind == T.F32:
        return E.f32const(v)
    if kind == T.COST_F32:
        return E.cost_as_f32(int(v))
    return v


def exact_results(case: T.KernelCase, rows: list) -> list:
    """The kernel evaluated exactly on rationals (no rounding anywhere): what the real domain
    computes where the concrete one rounds."""
    out = []
    for args in rows:
        E = ExactReplayDomain({})
        out.append(tuple(case.call(E, *(_exact_value(E, k, v) for k, v in zip(case.kinds, args)))))
    return out


# ------------------------------------------------------------------------ the runs
ALL = tuple(c.name for c in T.CASES)
ARRAY_KERNELS = ("cell_update", "edge_weight", "push", "push_admitted", "push_macro", "end_of_cycle", "grad_cell",
                 "interpolate", "step")
NOTHING_ROUNDS = ("push_admitted", "push_macro")
NO_HYPOT = ("cell_update", "edge_weight", "push", "push_macro", "end_of_cycle", "interpolate", "nearest", "lowest")  # the real domain's
# hypot is a fresh value the inputs do not determine


@dataclass(frozen=True)
class Run:
    """One domain on the table: ``results(case, rows)`` gives, per row, the results as a tuple
    (or a sentence saying why there are none), held to ``reference(case, rows)``; the rows are
    ``n`` drawn inputs (seed ``seed`` plus the kernel's place in the table) and every cost byte,
    only the finite ones when ``finite``; ``kernels``: the kernels this domain runs."""

    name: str
    results: Callable
    n: int
    seed: int
    kernels: tuple = ALL
    finite: bool = False
    reference: Callable = concrete_results


RUNS = (
    Run("numba", numba_results, 4000, 7),
    # the compiled domain in the fused arithmetics, each held to the concrete spec in the same
    *(Run(f"numba-{name}", partial(numba_results, arith=KNOWN[name]), 4000, 7,
          reference=partial(concrete_results, arith=KNOWN[name])) for name in ("x86-64-v3", "aarch64")),
    Run("concolic", concolic_results, 1000, 7),
    Run("array", array_results, 4000, 11, ARRAY_KERNELS),
    Run("fp32", fp32_results, 300, 5),
    Run("real", real_results, 1000, 7, NOTHING_ROUNDS, finite=True),
    Run("real-exact", real_results, 300, 7, NO_HYPOT, finite=True, reference=exact_results),
)
RUN = {r.name: r for r in RUNS}


def _finite(args) -> bool:
    return all(not isinstance(v, float) or math.isfinite(v) for v in args)


@lru_cache(maxsize=None)
def rows(run: Run, case: T.KernelCase) -> tuple:
    """The inputs ``run`` tries ``case`` on: drawn ones, then every cost byte (drawn once)."""
    seed = run.seed + T.CASES.index(case)
    out = T.inputs(case, seed, run.n) + T.every_cost(case, seed)
    return tuple(a for a in out if _finite(a) or not run.finite)


def mismatches(run: Run, case: T.KernelCase, first: int = 5) -> list:
    """``(input, wanted, got)`` of the first inputs on which ``run``'s domain differs from its
    reference on ``case``; empty when it agrees bit for bit on every input."""
    ins = list(rows(run, case))
    pairs = zip(ins, run.reference(case, ins), run.results(case, ins))
    return [(a, w, g) for a, w, g in pairs if not T.agree(w, g)][:first]


def with_domain(run: Run, domain, n: int) -> Run:
    """``run`` with another domain class in place of its own, on ``n`` drawn inputs (for showing
    that a check can fail)."""
    return replace(run, results=partial(run.results, domain=domain), n=n)
