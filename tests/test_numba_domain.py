"""The numba domain computes every kernel bit for bit as the concrete domain does.

The fast backend runs :mod:`navfn_smt.spec.kernels` compiled against the numba domain; the
reference spec runs them in the concrete domain.  Here each kernel is evaluated in both
on many generated inputs (potentials, edge weights, small offsets and arbitrary float32
bit patterns: NaN, infinities, subnormals, values beyond the int range) and the results
are compared bit for bit (NaN payloads aside: NavFn cannot observe them).
"""

from __future__ import annotations

import math
import struct

import numpy as np
import pytest
from numba import njit

from navfn_smt.backends.numba_domain import ND, OPERATIONS
from navfn_smt.spec import kernels as K
from navfn_smt.spec.numeric import CONCRETE as C
from navfn_smt.spec.numeric import ConcreteDomain

N = 4000


def f32_inputs(rng, n, potentials=True) -> np.ndarray:
    """Potentials, edge weights, offsets in [-2, 2] and arbitrary bit patterns, mixed."""
    kind = rng.integers(10, size=n)
    out = np.empty(n, np.float32)
    pot = rng.uniform(0, 20000, n).astype(np.float32) if potentials else rng.uniform(-2, 2, n).astype(np.float32)
    small = rng.uniform(-2, 2, n).astype(np.float32)
    raw = rng.integers(0, 2**32, n, dtype=np.uint64).astype(np.uint32).view(np.float32)
    edge = (np.float32(0.707106781) * rng.integers(0, 256, n)).astype(np.float32)
    out[:] = np.where(kind < 3, edge, np.where(kind < 6, pot, np.where(kind < 8, small, raw)))
    return out


def same(a, b) -> bool:
    a, b = float(a), float(b)
    if math.isnan(a) and math.isnan(b):
        return True
    return struct.pack("<d", a) == struct.pack("<d", b)


@njit(error_model="numpy")
def _cell_update(x, costs):
    out = np.empty((x.shape[0], 2), np.float32)
    for i in range(x.shape[0]):
        new, changed = K.cell_update(ND, x[i, 0], x[i, 1], x[i, 2], x[i, 3], x[i, 4], costs[i],
                                     ND.int_to_f32(costs[i]))
        out[i, 0] = new
        out[i, 1] = 1.0 if changed else 0.0
    return out


@njit(error_model="numpy")
def _grad_cell(x):
    out = np.empty((x.shape[0], 2), np.float32)
    for i in range(x.shape[0]):
        out[i, 0], out[i, 1] = K.grad_cell(ND, x[i, 0], x[i, 1], x[i, 2], x[i, 3], x[i, 4])
    return out


@njit(error_model="numpy")
def _interpolate(x):
    out = np.empty(x.shape[0], np.float32)
    for i in range(x.shape[0]):
        out[i] = K.interpolate_gradient(ND, x[i, 0], x[i, 1], x[i, 2], x[i, 3], x[i, 4], x[i, 5])
    return out


@njit(error_model="numpy")
def _step(x):
    out = np.empty((x.shape[0], 4), np.float64)
    for i in range(x.shape[0]):
        a, b, c, d = K.step_offsets(ND, x[i, 0], x[i, 1], x[i, 2], x[i, 3], ND.f32const(0.5))
        out[i, 0], out[i, 1], out[i, 2], out[i, 3] = a, b, c, d
    return out


@njit(error_model="numpy")
def _nearest(x, ints):
    out = np.empty(x.shape[0], np.int64)
    for i in range(x.shape[0]):
        out[i] = K.nearest_cell(ND, ints[i, 0], x[i, 0], x[i, 1], ints[i, 1], ints[i, 2])
    return out


@njit(error_model="numpy")
def _lowest(x):
    out = np.empty(x.shape[0], np.int64)
    for i in range(x.shape[0]):
        out[i] = K.lowest_of_eight(ND, x[i, 0], (x[i, 1], x[i, 2], x[i, 3], x[i, 4], x[i, 5], x[i, 6], x[i, 7], x[i, 8]))
    return out


@njit(error_model="numpy")
def _push_and_heuristic(x, ints):
    out = np.empty((x.shape[0], 4), np.float32)
    for i in range(x.shape[0]):
        out[i, 0] = 1.0 if K.push_wanted(ND, x[i, 0], x[i, 1], x[i, 2]) else 0.0
        out[i, 1] = 1.0 if K.to_low_buffer(ND, x[i, 1], x[i, 3]) else 0.0
        out[i, 2] = K.astar_heuristic(ND, ints[i, 0], ints[i, 1])
        out[i, 3] = K.edge_weight(ND, ND.int_to_f32(ints[i, 2]))
    return out


@njit(error_model="numpy")
def _push_admitted(ints):
    out = np.empty(ints.shape[0], np.bool_)
    for i in range(ints.shape[0]):
        out[i] = K.push_admitted(ND, ints[i, 0], ints[i, 1], ints[i, 2] != 0, ints[i, 3], ints[i, 4], ints[i, 5])
    return out


def _columns(rng, n, k, potentials=True):
    return np.stack([f32_inputs(rng, n, potentials) for _ in range(k)], axis=1)


def _py(a) -> list:
    return [float(v) for v in a]


def test_numba_domain_has_every_operation():
    ops = {n for n in vars(ConcreteDomain) if not n.startswith("_") and callable(getattr(C, n))}
    assert ops <= set(OPERATIONS), f"not compiled: {sorted(ops - set(OPERATIONS))}"


@pytest.mark.parametrize("kernel", ["cell_update", "grad_cell", "interpolate", "step", "nearest", "lowest", "push",
                                    "push_admitted"])
def test_kernel_bit_equal_to_concrete(kernel):
    rng = np.random.default_rng(hash(kernel) % 2**32)
    bad = []
    if kernel == "cell_update":
        x, costs = _columns(rng, N, 5), rng.integers(0, 256, N)
        got = _cell_update(x, costs)
        for i in range(N):
            want = K.cell_update(C, *_py(x[i]), int(costs[i]), C.int_to_f32(int(costs[i])))
            if not (same(got[i, 0], want[0]) and bool(got[i, 1]) == want[1]):
                bad.append((x[i], costs[i], got[i], want))
    elif kernel == "grad_cell":
        x = _columns(rng, N, 5)
        got = _grad_cell(x)
        bad = [(x[i], got[i]) for i in range(N)
               if not all(map(same, got[i], K.grad_cell(C, *_py(x[i]))))]
    elif kernel == "interpolate":
        x = _columns(rng, N, 6, potentials=False)
        got = _interpolate(x)
        bad = [(x[i], got[i]) for i in range(N) if not same(got[i], K.interpolate_gradient(C, *_py(x[i])))]
    elif kernel == "step":
        x = _columns(rng, N, 4, potentials=False)
        got = _step(x)
        bad = [(x[i], got[i]) for i in range(N)
               if not all(map(same, got[i], K.step_offsets(C, *_py(x[i]), 0.5)))]
    elif kernel == "nearest":
        x = _columns(rng, N, 2, potentials=False)
        nx = rng.integers(3, 5000, N)
        ns = nx * rng.integers(3, 5000, N)
        ints = np.stack([rng.integers(0, ns), nx, ns], axis=1)
        got = _nearest(x, ints)
        bad = [(x[i], ints[i], got[i]) for i in range(N)
               if got[i] != K.nearest_cell(C, int(ints[i, 0]), *_py(x[i]), int(ints[i, 1]), int(ints[i, 2]))]
    elif kernel == "lowest":
        x = _columns(rng, N, 9)
        got = _lowest(x)
        bad = [(x[i], got[i]) for i in range(N) if got[i] != K.lowest_of_eight(C, float(x[i, 0]), _py(x[i, 1:]))]
    elif kernel == "push_admitted":  # cell n of ns, pending, cost, fill, capacity: on and off the map, full and not
        ns = rng.integers(1, 40000, N)
        ints = np.stack([rng.integers(-3, ns + 3), ns, rng.integers(0, 2, N), rng.integers(0, 256, N),
                         rng.integers(0, 12, N), rng.integers(0, 12, N)], axis=1)
        got = _push_admitted(ints)
        bad = [(ints[i], got[i]) for i in range(N)
               if bool(got[i]) != K.push_admitted(C, *(int(v) for v in ints[i, :2]), bool(ints[i, 2]),
                                                  *(int(v) for v in ints[i, 3:]))]
    elif kernel == "push":
        x = _columns(rng, N, 4)
        ints = np.stack([rng.integers(-3000, 3000, N), rng.integers(-3000, 3000, N), rng.integers(0, 256, N)], axis=1)
        got = _push_and_heuristic(x, ints)
        for i in range(N):
            p, key, w, t = _py(x[i])
            want = (K.push_wanted(C, p, key, w), K.to_low_buffer(C, key, t),
                    K.astar_heuristic(C, int(ints[i, 0]), int(ints[i, 1])),
                    K.edge_weight(C, C.int_to_f32(int(ints[i, 2]))))
            if not (bool(got[i, 0]) == want[0] and bool(got[i, 1]) == want[1]
                    and same(got[i, 2], want[2]) and same(got[i, 3], want[3])):
                bad.append((x[i], ints[i], got[i], want))
    assert not bad, f"{len(bad)} of {N} differ, first: {bad[0]}"
