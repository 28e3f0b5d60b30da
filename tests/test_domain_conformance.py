"""Every numeric domain against the concrete one: the interface, then every kernel, bit for bit.

The interface is :class:`navfn_smt.spec.domain.NumericDomain`; the kernels, the inputs and
how each domain takes them in are the conformance harness (``tests/domain_harness.py``:
numba, concolic with its intervals, array, fp32, real where nothing rounds, real against
exact rationals).  Here every kernel runs in every domain that runs it, and each kind of
check is shown to fail on a domain with a seeded fault.  The bit-precise fp32 domain runs the
same table at length in ``tests/test_smt_equivalence.py`` (100,000 evaluations on two workers).
"""

from __future__ import annotations

import math
import re
from dataclasses import replace
from functools import partial
from pathlib import Path

import numpy as np
import pytest
import z3

import navfn_smt.spec.kernels as kernels
from navfn_smt.backends.numba_domain import OPERATIONS as NUMBA_OPERATIONS
from navfn_smt.check.concolic import ConcolicDomain
from navfn_smt.smt.enumerate import ArrayDomain
from domain_harness import RealEvalDomain
from navfn_smt.spec import conformance as T
from navfn_smt.spec.arithmetic import KNOWN, Arithmetic
from navfn_smt.spec.domain import OPERATIONS, NumericDomain
from navfn_smt.spec.numeric import CONCRETE as C
import domain_harness as H


# ------------------------------------------------------------------------ the interface
@pytest.mark.fast
@pytest.mark.parametrize("domain", H.DOMAIN_CLASSES, ids=lambda d: d.__name__)
def test_every_domain_has_every_operation(domain):
    assert H.missing(dir(domain)) == set()


def test_the_numba_domain_compiles_every_operation():
    assert H.missing(NUMBA_OPERATIONS) == set()


@pytest.mark.fast
def test_the_interface_lists_what_the_kernels_call():
    called = set(re.findall(r"\bD\.(\w+)\(", Path(kernels.__file__).read_text()))
    assert called and called <= set(OPERATIONS), sorted(called - set(OPERATIONS))


@pytest.mark.fast
def test_every_operation_says_what_it_stands_for():
    assert len(OPERATIONS) > 20
    assert [n for n in OPERATIONS if not (getattr(NumericDomain, n).__doc__ or "").strip()] == []


@pytest.mark.fast
def test_a_missing_operation_is_found():
    partial = type("Partial", (), {n: None for n in OPERATIONS if n != "hypotf"})
    assert H.missing(dir(partial)) == {"hypotf"}


# ------------------------------------------------------------------------ every kernel, every domain
PAIRS = [(run, case) for run in H.RUNS for case in T.CASES if case.name in run.kernels]


@pytest.mark.parametrize("run, case", PAIRS, ids=[f"{r.name}-{c.name}" for r, c in PAIRS])
def test_kernel_in_domain(run, case):
    assert H.mismatches(run, case) == []


@pytest.mark.fast
def test_every_domain_runs_every_kernel_it_can():
    """The runs leave out only what their domain cannot take: the array domain's conversions to
    int are scalar (heuristic, nearest, lowest); the real domain's hypot is a value the inputs do
    not determine (heuristic, grad_cell, step)."""
    left_out = {r.name: set(T.CASE) - set(r.kernels) for r in H.RUNS}
    assert left_out["numba"] == left_out["concolic"] == left_out["fp32"] == set()
    assert left_out["numba-aarch64"] == left_out["numba-x86-64-v3"] == set()
    assert left_out["array"] == {"heuristic", "nearest", "lowest"}
    assert left_out["real"] & left_out["real-exact"] == {"heuristic", "grad_cell", "step"}


def test_the_inputs_hold_every_edge_and_every_cost():
    """Each kernel's inputs carry NaN, both infinities, both zeros and subnormals, and a kernel
    of a cost sees every cost byte in every domain."""
    for case in T.CASES:
        floats = [v for a in H.rows(H.RUN["numba"], case) for v, k in zip(a, case.kinds) if k == T.F32]
        if floats:
            assert any(math.isnan(v) for v in floats) and {math.inf, -math.inf} <= set(floats), case.name
            assert {math.copysign(1, v) for v in floats if v == 0} == {1.0, -1.0}, case.name
            assert any(0 < abs(v) < 1.1754942e-38 for v in floats), case.name
    for run in H.RUNS:
        for case in T.CASES:
            at = [i for i, k in enumerate(case.kinds) if k in (T.COST, T.COST_F32)]
            if at and case.name in run.kernels:
                assert {int(a[i]) for a in H.rows(run, case) for i in at} == set(range(256)), (run.name, case.name)


# ------------------------------------------------------------------------ each check can fail
@pytest.mark.fast
def test_a_wrong_array_domain_is_caught():
    """A domain whose hypotf forgets C's rule for an infinite argument beside a NaN (the array
    domain's bug this harness found) differs from the concrete one."""

    class Forgetful(ArrayDomain):
        def hypotf(self, a, b):
            wa, wb = self.widen(a), self.widen(b)
            with np.errstate(all="ignore"):
                return self.narrow(np.sqrt(wa * wa + wb * wb))

    row = (-math.inf, 16.263456344604492, -1.4406818796870028e-31, 2.2537213648985461e+27, 30.40559196472168)
    case = T.CASE["grad_cell"]
    assert not T.agree(case.call(C, *row), H.array_results(case, [row], Forgetful)[0])
    assert T.agree(case.call(C, *row), H.array_results(case, [row])[0])
    assert H.mismatches(H.with_domain(H.RUN["array"], Forgetful, 4000), case) != []


@pytest.mark.parametrize("case, wrong", [
    ("cell_update", Arithmetic(KNOWN["aarch64"].fused - {"planar"}, "saturating")),
    ("step", Arithmetic(KNOWN["aarch64"].fused - {"path_step"}, "saturating")),
    ("nearest", KNOWN["x86-64-v3"]),
], ids=["planar", "path_step", "conversion"])
def test_the_compiled_domain_in_a_wrong_arithmetic_is_caught(case, wrong):
    """The compiled domain computes in the arithmetic it is given, not in x86-64's: in arm64's
    with one fused site dropped, or with x86-64's conversion, it differs from the concrete spec in
    arm64's on the kernel of that site.  (The double sites, quadratic and bilinear, are rounded
    to float after their multiply-add: fused or not, no drawn input tells them apart.)"""
    run = H.RUN["numba-aarch64"]
    assert H.mismatches(run, T.CASE[case]) == []
    assert H.mismatches(replace(run, results=partial(H.numba_results, arith=wrong), n=2000), T.CASE[case]) != []


@pytest.mark.fast
def test_an_unsound_interval_is_caught():
    """A concolic product that takes the interval from two corners of four (sound only for
    operands of one sign) misses values at the other corners."""

    class TwoCorners(ConcolicDomain):
        def mul(self, a, b):
            return self._binary("f32", C.mul, self.S.mul, a, b, False)

    assert H.mismatches(H.with_domain(H.RUN["concolic"], TwoCorners, 200), T.CASE["interpolate"]) != []


@pytest.mark.fast
def test_a_wrong_real_domain_is_caught():
    """A real roundf that rounds halves up (not away from zero) differs from the exact one."""

    class HalfUp(RealEvalDomain):
        @staticmethod
        def roundf(a):
            return z3.ToReal(z3.ToInt(a + z3.RealVal("1/2")))

    assert H.mismatches(H.with_domain(H.RUN["real-exact"], HalfUp, 300), T.CASE["nearest"]) != []
