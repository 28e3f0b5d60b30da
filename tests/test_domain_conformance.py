"""Every numeric domain against the concrete one: the interface, then every kernel, bit for bit.

One table of kernels and inputs (:mod:`navfn_smt.spec.conformance`), one way to compare
(``same``: bit for bit, NaN payloads aside), and per domain only how it takes a plain input
in and gives a result back:

- numba: the fast backend's domain, each kernel compiled and called on float32/int64 values;
- concolic: point intervals whose concrete part must be the concrete result and whose
  interval must hold it;
- array: numpy arrays, one call per kernel on every input at once, for the kernels the
  splits enumerate (the others take Python ints and tuples the array domain does not);
- real: exact arithmetic, so only where no rounding happens (``push_admitted``).

The bit-precise fp32 domain runs the same table in ``tests/test_smt_equivalence.py`` (100,000
evaluations on two workers; here 300 per kernel).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from numba import njit

from navfn_smt.backends.numba_domain import ND, OPERATIONS as NUMBA_OPERATIONS
from navfn_smt.check.concolic import ConcolicDomain, V, concrete
from navfn_smt.smt.domains import FPDomain, RealDomain
from navfn_smt.smt.enumerate import ArrayDomain
from navfn_smt.smt.evaluate import FPEvalDomain, RealEvalDomain, compare_kernel, lift, value
from navfn_smt.spec import conformance as T
from navfn_smt.spec.domain import OPERATIONS
from navfn_smt.spec.numeric import CONCRETE as C
from navfn_smt.spec.numeric import ConcreteDomain

N = 4000  # inputs per kernel (numba, concolic, array)
ARRAY_KERNELS = ("cell_update", "edge_weight", "push", "push_admitted", "grad_cell", "interpolate", "step")


def _mismatches(case, got_of, n=N, seed=None):
    """The inputs on which ``got_of(args)`` differs from the concrete results (first 5)."""
    bad = []
    for args in T.inputs(case, seed if seed is not None else 7 + T.CASES.index(case), n):
        want, got = case.call(C, *args), got_of(args)
        if len(want) != len(got) or not all(T.same(w, g) for w, g in zip(want, got)):
            bad.append((args, want, got))
    return bad[:5]


# ------------------------------------------------------------------------ the interface
@pytest.mark.parametrize("domain", [ConcreteDomain, FPDomain, RealDomain, ConcolicDomain, ArrayDomain],
                         ids=lambda d: d.__name__)
def test_every_domain_has_every_operation(domain):
    assert set(OPERATIONS) - set(dir(domain)) == set()


def test_the_numba_domain_compiles_every_operation():
    assert set(OPERATIONS) - set(NUMBA_OPERATIONS) == set()


def test_the_interface_lists_what_the_kernels_call():
    import re
    from pathlib import Path

    import navfn_smt.spec.kernels as kernels

    called = set(re.findall(r"\bD\.(\w+)\(", Path(kernels.__file__).read_text()))
    assert called and called <= set(OPERATIONS), sorted(called - set(OPERATIONS))


# ------------------------------------------------------------------------ the kernels
_NUMBA = {}


def _numba_call(case):
    if case.name not in _NUMBA:
        _NUMBA[case.name] = njit(error_model="numpy")(case.call)
    return _NUMBA[case.name]


def _numba_value(kind, v):
    if kind in (T.F32, T.COST_F32):
        return np.float32(v)
    return np.bool_(v) if kind == T.BOOL else np.int64(v)


@pytest.mark.parametrize("case", T.CASES, ids=lambda c: c.name)
def test_numba(case):
    f = _numba_call(case)
    got = lambda args: tuple(f(ND, *(_numba_value(k, v) for k, v in zip(case.kinds, args))))  # noqa: E731
    assert _mismatches(case, got) == []


def _concolic_value(D, kind, v):
    if kind == T.F32:
        return V("f32", v, v, v, D.S.f32const(v))
    if kind == T.COST:
        return D.cost_int(D.cost(v, v, v, "c"))
    if kind == T.COST_F32:
        return D.cost_as_f32(D.cost(int(v), int(v), int(v), "c"))
    return v


def _holds(r) -> bool:
    """A result's interval holds its concrete value (bools: the truth value's range)."""
    if not isinstance(r, V) or r.kind == "bool" or (isinstance(r.conc, float) and math.isnan(r.conc)):
        return True
    return r.lo <= r.conc <= r.hi or (isinstance(r.lo, float) and math.isnan(r.lo))


@pytest.mark.parametrize("case", T.CASES, ids=lambda c: c.name)
def test_concolic(case):
    def got(args):
        D = ConcolicDomain(FPEvalDomain())
        res = case.call(D, *(_concolic_value(D, k, v) for k, v in zip(case.kinds, args)))
        assert all(_holds(r) for r in res), (args, res)
        return tuple(concrete(r) for r in res)

    assert _mismatches(case, got, n=N // 4) == []


@pytest.mark.parametrize("name", ARRAY_KERNELS)
def test_array(name):
    case = T.CASE[name]
    ins = T.inputs(case, 11, N)
    cols = [np.array(c, np.float32 if k in (T.F32, T.COST_F32) else None) for k, c in zip(case.kinds, zip(*ins))]
    with np.errstate(all="ignore"):
        out = [np.broadcast_to(r, (N,)) for r in case.call(ArrayDomain({}), *cols)]
    rows = iter(range(N))  # _mismatches draws the same inputs, in order

    def got(args):
        i = next(rows)
        return tuple(r[i] for r in out)

    assert _mismatches(case, got, seed=11) == []


def test_real_where_nothing_rounds():
    case = T.CASE["push_admitted"]

    def got(args):
        D = RealEvalDomain()
        return tuple(value(r) for r in case.call(D, *(lift(D, k, v) for k, v in zip(case.kinds, args))))

    assert _mismatches(case, got, n=1000) == []


@pytest.mark.parametrize("case", T.CASES, ids=lambda c: c.name)
def test_fp32(case):
    """A short run of the bit-precise comparison (the long one: test_smt_equivalence.py)."""
    assert compare_kernel(case.name, 5, 300) == []


# ------------------------------------------------------------------------ the harness can fail
def test_a_wrong_domain_is_caught():
    """A domain whose hypotf forgets C's rule for an infinite argument beside a NaN (the
    array domain's bug this harness found) differs from the concrete one."""

    class Forgetful(ArrayDomain):
        def hypotf(self, a, b):
            wa, wb = self.widen(a), self.widen(b)
            with np.errstate(all="ignore"):
                return self.narrow(np.sqrt(wa * wa + wb * wb))

    case = T.CASE["grad_cell"]
    ins = [(-math.inf, 16.263456344604492, -1.4406818796870028e-31, 2.2537213648985461e+27, 30.40559196472168)]
    cols = [np.array(c, np.float32) for c in zip(*ins)]
    with np.errstate(all="ignore"):
        out = case.call(Forgetful({}), *cols)
    assert not all(T.same(w, np.asarray(r)[0]) for w, r in zip(case.call(C, *ins[0]), out))
    with np.errstate(all="ignore"):
        fixed = case.call(ArrayDomain({}), *cols)
    assert all(T.same(w, np.asarray(r)[0]) for w, r in zip(case.call(C, *ins[0]), fixed))
