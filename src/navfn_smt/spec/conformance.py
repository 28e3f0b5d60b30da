"""The kernels' conformance table: every kernel with the inputs it is tried on, stated once.

Every numeric domain that runs :mod:`.kernels` (concrete, numba, bit-precise, real, concolic
intervals, numpy arrays) is held equal to the concrete one, bit for bit, on these cases: the
symbolic equality of ``smt/evaluate.py`` (also the mutation check's domain detector) and the
harness that runs every domain on them (``tests/domain_harness.py``) both draw from here.

A case names its kernel, the kind of each argument (so a domain knows how to take it in:
a float32 value, a cost byte as int or as float, a plain int or bool), how inputs are drawn,
and how the kernel is called (its results always a tuple).  Floats are drawn from one mix:
edge values (zeros, ones, halves, the cost values, POT_HIGH, 2**24 and its neighbours, the
largest float, subnormals, infinities, NaN, rounding ties near 1), potentials, edge weights,
small offsets, and arbitrary float32 bit patterns.  A kernel that takes a cost is also tried
on every cost byte (:func:`every_cost`).
"""

from __future__ import annotations

import math
import struct
from dataclasses import dataclass
from typing import Callable

import numpy as np

from . import kernels as K

# the kinds of a kernel's arguments
F32 = "f32"  # a float32 value
COST = "cost"  # a cost byte (0..255) as the int the kernels compare
COST_F32 = "cost_f32"  # the same byte as the float ``(float) cost``
INT = "int"  # a plain int (cell indices, sizes, buffer fills, offsets)
BOOL = "bool"  # a plain bool (a pending flag)

EDGE = tuple(float(np.float32(v)) for v in (
    0.0, -0.0, 1.0, -1.0, 0.5, -0.5, 1.5, 49.999996, 50.0, 100.0, 253.0, 254.0, 1e10, 9999999488.0,
    2.0**24, 2.0**24 + 2, 2.0**30, 3.4028235e38, 1.4e-45, 1.1754942e-38, -1.4e-45, math.inf, -math.inf,
    math.nan, 0.70710677, 0.99999994, 1.0000001, -0.99999994))


def f32_values(rng: np.random.Generator, n: int, potentials: bool = True) -> list[float]:
    """``n`` float32 values (as Python floats) from the one mix: a fifth edge values, a fifth
    edge weights (``COST * INVSQRT2``-like multiples), potentials in [0, 20000] (or offsets in
    [-2, 2] without ``potentials``), offsets in [-2, 2], and arbitrary bit patterns."""
    kind = rng.integers(5, size=n)
    edge = np.array(EDGE, np.float32)[rng.integers(len(EDGE), size=n)]
    weight = (np.float32(0.707106781) * rng.integers(0, 256, n)).astype(np.float32)
    pot = (rng.uniform(0, 20000, n) if potentials else rng.uniform(-2, 2, n)).astype(np.float32)
    small = rng.uniform(-2, 2, n).astype(np.float32)
    raw = rng.integers(0, 2**32, n, dtype=np.uint64).astype(np.uint32).view(np.float32)
    out = np.select([kind == 0, kind == 1, kind == 2, kind == 3], [edge, weight, pot, small], raw)
    return [float(v) for v in out]


def same(a, b) -> bool:
    """Bit for bit (as doubles: every float32 is one), NaN payloads aside (NavFn cannot see them)."""
    if isinstance(a, (bool, np.bool_)) or isinstance(b, (bool, np.bool_)):
        return bool(a) == bool(b)
    if isinstance(a, (float, np.floating)) or isinstance(b, (float, np.floating)):
        a, b = float(a), float(b)
        if math.isnan(a) and math.isnan(b):
            return True
        return struct.pack("<d", a) == struct.pack("<d", b)
    return a == b


def agree(want: tuple, got) -> bool:
    """``got`` (a domain's results, or a sentence saying why it has none) is ``want``, bit for bit."""
    return isinstance(got, tuple) and len(got) == len(want) and all(same(w, g) for w, g in zip(want, got))


@dataclass(frozen=True)
class KernelCase:
    """One kernel under test: ``draw(rng)`` one input (a tuple of plain values, of ``kinds``),
    ``call(D, *args)`` the kernel's results as a tuple; ``count`` inputs in the symbolic test;
    ``stated``: inputs chosen by hand, tried on every cost byte (:func:`every_cost`)."""

    name: str
    kinds: tuple
    draw: Callable
    call: Callable
    count: int
    stated: tuple = ()


def _floats(k, potentials=True):
    return lambda rng: tuple(f32_values(rng, k, potentials))


def _cost(rng):
    return int(rng.integers(0, 256))


def _cell_update(rng):
    c = _cost(rng)
    return (*f32_values(rng, 5), c, float(c))


# updateCell's branches for every cost: the cell already lower than any candidate, a
# neighbour difference of 12.5 (dc >= hf up to cost 12, the quadratic above), and of 1
_HUGE = float(np.float32(1e10))
_CELL_UPDATE_STATED = ((0.0, _HUGE, _HUGE, _HUGE, _HUGE, 0, 0.0), (_HUGE, 0.0, 30.0, _HUGE, 12.5, 0, 0.0),
                       (9.0, 100.0, 120.0, 105.0, 99.0, 0, 0.0))


def _push_admitted(rng):
    ns = int(rng.integers(1, 40000))
    return (int(rng.integers(-3, ns + 3)), ns, bool(rng.integers(2)), _cost(rng), int(rng.integers(0, 12)),
            int(rng.integers(0, 12)))


def _end_of_cycle(rng):
    return (int(rng.integers(0, 3)) * int(rng.integers(0, 12)), int(rng.integers(0, 12)), *f32_values(rng, 1),
            float(np.float32(rng.integers(1, 4))))


def _nearest(rng):
    nx = int(rng.integers(3, 5000))
    ns = nx * int(rng.integers(3, 5000))
    return (int(rng.integers(0, ns)), *f32_values(rng, 2, False), nx, ns)


def _heuristic(rng):
    return tuple(int(v) for v in rng.integers(-3000, 3000, size=2))


# the calls: module-level functions, so that numba can compile them too
def call_cell_update(D, old, l, r, u, d, cost, hf):
    return K.cell_update(D, old, l, r, u, d, cost, hf)


def call_edge_weight(D, hf):
    return (K.edge_weight(D, hf),)


def call_push(D, pot, key, weight, cur_t):
    return K.push_wanted(D, pot, key, weight), K.to_low_buffer(D, key, cur_t)


def call_push_admitted(D, n, ns, pending, cost, fill, capacity):
    return (K.push_admitted(D, n, ns, pending, cost, fill, capacity),)


def call_push_macro(D, n, ns, pending, cost, fill, capacity):
    return K.push(D, n, ns, pending, cost, fill, capacity)


def call_end_of_cycle(D, fill_next, fill_over, cur_t, inc):
    return K.end_of_cycle(D, fill_next, fill_over, cur_t, inc)


def call_heuristic(D, ddx, ddy):
    return (K.astar_heuristic(D, ddx, ddy),)


def call_grad_cell(D, cv, pl, pr, pu, pd):
    return K.grad_cell(D, cv, pl, pr, pu, pd)


def call_interpolate(D, dx, dy, g00, g10, g01, g11):
    return (K.interpolate_gradient(D, dx, dy, g00, g10, g01, g11),)


def call_step(D, dx, dy, x, y):
    return K.step_offsets(D, dx, dy, x, y, D.f32const(0.5))


def call_nearest(D, stc, dx, dy, nx, ns):
    return (K.nearest_cell(D, stc, dx, dy, nx, ns),)


def call_lowest(D, c, n0, n1, n2, n3, n4, n5, n6, n7):
    return (K.lowest_of_eight(D, c, (n0, n1, n2, n3, n4, n5, n6, n7)),)


CASES = (
    KernelCase("cell_update", (F32,) * 5 + (COST, COST_F32), _cell_update, call_cell_update, 16000,
               _CELL_UPDATE_STATED),
    KernelCase("edge_weight", (COST_F32,), lambda rng: (float(_cost(rng)),), call_edge_weight, 3000),
    KernelCase("push", (F32,) * 4, _floats(4), call_push, 12000),
    KernelCase("push_admitted", (INT, INT, BOOL, COST, INT, INT), _push_admitted, call_push_admitted, 3000),
    KernelCase("push_macro", (INT, INT, BOOL, COST, INT, INT), _push_admitted, call_push_macro, 3000),
    KernelCase("end_of_cycle", (INT, INT, F32, F32), _end_of_cycle, call_end_of_cycle, 3000),
    KernelCase("heuristic", (INT, INT), _heuristic, call_heuristic, 8000),
    KernelCase("grad_cell", (F32,) * 5, _floats(5), call_grad_cell, 12000),
    KernelCase("interpolate", (F32,) * 6, _floats(6, False), call_interpolate, 14000),
    KernelCase("step", (F32,) * 4, _floats(4, False), call_step, 12000),
    KernelCase("nearest", (INT, F32, F32, INT, INT), _nearest, call_nearest, 12000),
    KernelCase("lowest", (F32,) * 9, _floats(9), call_lowest, 12000),
)
CASE = {c.name: c for c in CASES}


def inputs(case: KernelCase, seed: int, n: int) -> list[tuple]:
    """``n`` inputs of ``case``, the same for the same seed."""
    rng = np.random.default_rng(seed)
    return [case.draw(rng) for _ in range(n)]


def every_cost(case: KernelCase, seed: int, per_cost: int = 3) -> list[tuple]:
    """Inputs of ``case`` on every cost byte 0..255: its stated inputs and ``per_cost`` drawn
    ones (from a stream of their own), their cost arguments (``COST``, ``COST_F32``) set to the
    byte; an input that comes twice (a kernel of the cost alone) is kept once; none for a kernel
    without a cost."""
    at = [i for i, k in enumerate(case.kinds) if k in (COST, COST_F32)]
    if not at:
        return []
    rng = np.random.default_rng((seed, 256))
    rows = []
    for c in range(256):
        for args in [*case.stated, *(case.draw(rng) for _ in range(per_cost))]:
            args = list(args)
            for i in at:
                args[i] = c if case.kinds[i] == COST else float(c)
            rows.append(tuple(args))
    return list(dict.fromkeys(rows))
