"""The symbolic encodings and the concrete spec must not drift apart.

Every kernel is evaluated in the bit-precise domain on constant inputs and compared with
the concrete spec bit for bit, on random and edge inputs (zeros of both signs, 1e10 and
other huge potentials, subnormals, infinities, NaN, every cost 0..255): about 100,000
kernel evaluations in all.  The library-function model (hypot/hypotf) must admit the
value the platform's libm returns on every input.  The real domain is compared with the
same kernels evaluated exactly on rationals.
"""

from multiprocessing import get_context

import numpy as np
import pytest
import z3

from navfn_smt.smt.evaluate import KERNELS, FPEvalDomain, RealEvalDomain, compare_kernel, cost_input, f32_input, same, value
from navfn_smt.smt.replay import ExactReplayDomain
from navfn_smt.spec import kernels as K
from navfn_smt.spec.numeric import CONCRETE as C


def _job(args):
    kernel, seed, n = args
    return compare_kernel(kernel, seed, n)


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
