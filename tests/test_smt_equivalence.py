"""The symbolic encodings and the concrete spec must not drift apart.

Every kernel is evaluated in the bit-precise domain on constant inputs and compared with
the concrete spec bit for bit, on the conformance table's inputs (zeros of both signs, 1e10
and other huge potentials, subnormals, infinities, NaN, rounding ties, bit patterns): about
26,000 kernel evaluations in all (a quarter of the table's count of each kernel: the
bit-precise domain folds each through Z3, about 4 ms an evaluation).  The library-function
model (hypot/hypotf) must admit the value the platform's libm returns on every input.  The
short runs of every domain, the real domain against exact rationals and every cost byte
included, are the conformance harness's (``tests/test_domain_conformance.py``).
"""

from multiprocessing import get_context

import pytest

from navfn_smt.smt.evaluate import KERNELS, FPEvalDomain, compare_kernel, f32_input, value


def _job(args):
    kernel, seed, n = args
    return compare_kernel(kernel, seed, n)


def test_fp_domain_equals_concrete_spec_bit_for_bit():
    jobs = []
    for i, (kernel, n) in enumerate(KERNELS.items()):
        for part in range(4):
            jobs.append((kernel, 1000 * i + part, n // 16))
    assert sum(j[2] for j in jobs) >= 25_000
    with get_context("spawn").Pool(2) as pool:
        results = pool.map(_job, jobs)
    bad = [b for r in results for b in r]
    assert not bad, bad[:5]


def test_mutated_kernel_is_caught():
    """The comparison can fail: a kernel computed in double where C++ narrows differs."""
    D = FPEvalDomain()
    wrong = D.add64(D.widen(f32_input(D, 16777216.0)), D.widen(f32_input(D, 1.0)))  # no narrowing
    assert value(wrong) != value(D.add(f32_input(D, 16777216.0), f32_input(D, 1.0)))


@pytest.mark.parametrize("target", ["x86-64-v3", "aarch64"])
def test_fp_domain_in_a_build_arithmetic_equals_the_concrete_spec_in_it(target):
    """The bit-precise domain in another build's arithmetic (fp.fma at the sites it fuses, its
    float-to-int conversion) equals the concrete spec in that arithmetic, bit for bit, on a
    sample of every kernel; and the comparison can fail: the domain left in x86-64's arithmetic
    differs from the concrete spec in this one on the kernels a fused site or a conversion changes
    (conformance table names: ``cell_update``, ``step``, and with arm64's conversion ``lowest``)."""
    from navfn_smt.spec.arithmetic import KNOWN, X86_64

    arith = KNOWN[target]
    jobs = [(kernel, 7000 + i, max(1, n // 200)) for i, (kernel, n) in enumerate(KERNELS.items())]
    bad = [b for kernel, seed, n in jobs for b in compare_kernel(kernel, seed, n, arith)]
    assert not bad, bad[:5]
    wrong = {b[0] for kernel, seed, n in jobs for b in compare_kernel(kernel, seed, n, arith, symbolic=X86_64)}
    assert {"cell_update", "step"} <= wrong, wrong  # the fused updateCell and path step
    assert ("lowest" in wrong) == (arith.conversion == "saturating"), wrong  # the fallback's (int) of 1e10
