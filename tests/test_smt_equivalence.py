"""The symbolic encodings and the concrete spec must not drift apart.

Every kernel is evaluated in the bit-precise domain on constant inputs and compared with
the concrete spec bit for bit, on random and edge inputs (zeros of both signs, 1e10 and
other huge potentials, subnormals, infinities, NaN, every cost 0..255): about 100,000
kernel evaluations in all.  The library-function model (hypot/hypotf) must admit the
value the platform's libm returns on every input.  The real domain is compared with the
same kernels evaluated exactly on rationals.
"""

import math
import struct
from multiprocessing import get_context

import numpy as np
import pytest
import z3

from navfn_smt.smt.evaluate import FPEvalDomain, RealEvalDomain, cost_input, f32_input, value
from navfn_smt.smt.obligation import ExactReplayDomain
from navfn_smt.spec import kernels as K
from navfn_smt.spec.numeric import CONCRETE as C

EDGE = [float(np.float32(v)) for v in (
    0.0, -0.0, 1.0, -1.0, 0.5, -0.5, 1.5, 49.999996, 50.0, 100.0, 253.0, 254.0, 1e10, 9999999488.0,
    2.0**24, 2.0**24 + 2, 2.0**30, 3.4028235e38, 1.4e-45, 1.1754942e-38, -1.4e-45, math.inf, -math.inf,
    math.nan, 0.70710677, 0.99999994, 1.0000001, -0.99999994)]


def same(a, b) -> bool:
    if isinstance(a, float) and isinstance(b, float):
        if math.isnan(a) and math.isnan(b):
            return True  # NaN payloads are not observable in NavFn
        return struct.pack("<d", a) == struct.pack("<d", b)
    return a == b


def f32s(rng, n, potentials=False):
    out = []
    for _ in range(n):
        k = rng.integers(10)
        if k < 3:
            out.append(float(EDGE[rng.integers(len(EDGE))]))
        elif k < 6 and potentials:
            out.append(float(np.float32(rng.uniform(0, 20000))))
        elif k < 8:
            out.append(float(np.float32(rng.uniform(-2, 2))))
        else:
            b = int(rng.integers(0, 2**32))
            out.append(struct.unpack("<f", struct.pack("<I", b))[0])
    return out


def _kernel_cases(kernel: str, seed: int, n: int) -> list:
    """Evaluate ``kernel`` on n inputs in both domains; return the mismatches."""
    rng = np.random.default_rng(seed)
    bad = []
    for _ in range(n):
        D = FPEvalDomain()
        if kernel == "cell_update":
            old, l, r, u, d = f32s(rng, 5, True)
            c = int(rng.integers(0, 256))
            conc = K.cell_update(C, old, l, r, u, d, c, float(c))
            sym = K.cell_update(D, *(f32_input(D, v) for v in (old, l, r, u, d)), D.cost_int(cost_input(D, c)),
                                D.cost_as_f32(cost_input(D, c)))
            got = (value(sym[0]), value(sym[1]))
            args = (old, l, r, u, d, c)
        elif kernel == "edge_weight":
            c = int(rng.integers(0, 256))
            conc = (K.edge_weight(C, float(c)),)
            got = (value(K.edge_weight(D, D.cost_as_f32(cost_input(D, c)))),)
            args = (c,)
        elif kernel == "push":
            p, key, w, t = f32s(rng, 4, True)
            conc = (K.push_wanted(C, p, key, w), K.to_low_buffer(C, key, t))
            fp = [f32_input(D, v) for v in (p, key, w, t)]
            got = (value(K.push_wanted(D, fp[0], fp[1], fp[2])), value(K.to_low_buffer(D, fp[1], fp[3])))
            args = (p, key, w, t)
        elif kernel == "heuristic":
            ddx, ddy = (int(v) for v in rng.integers(-3000, 3000, size=2))
            conc = (K.astar_heuristic(C, ddx, ddy),)
            got = (value(K.astar_heuristic(D, ddx, ddy)),)
            args = (ddx, ddy)
        elif kernel == "grad_cell":
            vals = f32s(rng, 5, True)
            conc = K.grad_cell(C, *vals)
            got = tuple(value(v) for v in K.grad_cell(D, *(f32_input(D, v) for v in vals)))
            args = tuple(vals)
        elif kernel == "interpolate":
            vals = f32s(rng, 6)
            conc = (K.interpolate_gradient(C, *vals),)
            got = (value(K.interpolate_gradient(D, *(f32_input(D, v) for v in vals))),)
            args = tuple(vals)
        elif kernel == "step":
            vals = f32s(rng, 4)
            conc = K.step_offsets(C, *vals, 0.5)
            sym = K.step_offsets(D, *(f32_input(D, v) for v in vals), D.f32const(0.5))
            got = tuple(value(v) for v in sym)
            args = tuple(vals)
        elif kernel == "nearest":
            dx, dy = f32s(rng, 2)
            nx = int(rng.integers(3, 5000))
            ns = nx * int(rng.integers(3, 5000))
            stc = int(rng.integers(0, ns))
            conc = (K.nearest_cell(C, stc, dx, dy, nx, ns),)
            got = (value(K.nearest_cell(D, stc, f32_input(D, dx), f32_input(D, dy), nx, ns)),)
            args = (stc, dx, dy, nx, ns)
        elif kernel == "lowest":
            vals = f32s(rng, 9, True)
            conc = (K.lowest_of_eight(C, vals[0], vals[1:]),)
            got = (value(K.lowest_of_eight(D, f32_input(D, vals[0]), [f32_input(D, v) for v in vals[1:]])),)
            args = tuple(vals)
        else:
            raise ValueError(kernel)
        if not all(same(a, b) for a, b in zip(conc, got)) or not D.model_admits_libm():
            bad.append((kernel, args, conc, got, D.model_admits_libm()))
    return bad


KERNELS = {"cell_update": 16000, "edge_weight": 3000, "push": 12000, "heuristic": 8000, "grad_cell": 12000,
           "interpolate": 14000, "step": 12000, "nearest": 12000, "lowest": 12000}


def _job(args):
    kernel, seed, n = args
    return _kernel_cases(kernel, seed, n)


def test_fp_domain_equals_concrete_spec_bit_for_bit():
    jobs = []
    for i, (kernel, n) in enumerate(KERNELS.items()):
        for part in range(4):
            jobs.append((kernel, 1000 * i + part, n // 4))
    assert sum(j[2] for j in jobs) >= 100_000
    with get_context("spawn").Pool(2) as pool:
        results = pool.map(_job, jobs)
    bad = [b for r in results for b in r]
    assert not bad, bad[:5]


def test_every_cost_value():
    for c in range(256):
        D = FPEvalDomain()
        assert same(value(K.edge_weight(D, D.cost_as_f32(cost_input(D, c)))), K.edge_weight(C, float(c)))
        for pots in ([0.0, 1e10, 1e10, 1e10, 1e10], [1e10, 0.0, 30.0, 1e10, 12.5], [9.0, 100.0, 120.0, 105.0, 99.0]):
            conc = K.cell_update(C, *pots, c, float(c))
            sym = K.cell_update(D, *(f32_input(D, v) for v in pots), D.cost_int(cost_input(D, c)),
                                D.cost_as_f32(cost_input(D, c)))
            assert (same(value(sym[0]), conc[0]), value(sym[1])) == (True, conc[1]), (c, pots)


def test_mutated_kernel_is_caught():
    """The comparison can fail: a kernel computed in double where C++ narrows differs."""
    D = FPEvalDomain()
    wrong = D.add64(D.widen(f32_input(D, 16777216.0)), D.widen(f32_input(D, 1.0)))  # no narrowing
    assert value(wrong) != value(D.add(f32_input(D, 16777216.0), f32_input(D, 1.0)))


@pytest.mark.parametrize("seed", range(3))
def test_real_domain_equals_exact_evaluation(seed):
    rng = np.random.default_rng(100 + seed)
    for _ in range(400):
        old, l, r, u, d = (float(np.float32(v)) for v in rng.uniform(0, 5000, size=5))
        c = int(rng.integers(0, 254))
        E = ExactReplayDomain({})
        exact = K.cell_update(E, *(E.f32const(v) for v in (old, l, r, u, d)), c, E.cost_as_f32(c))
        R = RealEvalDomain()
        sym = K.cell_update(R, *(R.f32const(v) for v in (old, l, r, u, d)), z3.IntVal(c), R.cost_as_f32(z3.IntVal(c)))
        assert value(sym[0]) == exact[0] and value(sym[1]) == exact[1]
