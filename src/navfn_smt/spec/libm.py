"""The C library's ``hypot`` as the build's libm computes it, for the costmap's footprint radii.

glibc 2.35 and later (Debian 12, Ubuntu 22.04 on) compute ``hypot(double, double)`` with one of
two kernels, chosen when glibc itself is compiled (``__FP_FAST_FMA``):

- ``"glibc"`` (x86-64, whose baseline has no fused multiply-add): ``h = sqrt(ax*ax + ay*ay)``,
  then one correction step ``h -= (t1 + t2) / (2h)`` from the rounding errors of the squares;
- ``"glibc-fma"`` (arm64): ``sqrt(fma(2ay, ax, (ax-ay)^2))`` when ``2ay >= ax``, else
  ``sqrt(fma(ax, ax, ay*ay))``, one rounding before the root.

Both are within an ulp of the true value but not always the same double: on 600,000 generated
pairs, Debian's arm64 glibc 2.36 (under qemu) and x86-64 glibc 2.36 differ on 35,050, and each
kernel here equals its build on all of them.  Before either kernel, glibc orders ``|x|, |y|``,
returns ``ax + ay`` when ``ay`` is negligible, and scales by 2^600 when ``ax`` is huge or ``ay``
tiny; :func:`glibc_hypot` does the same.  Which kernel a build's libm uses is found by running
it (``oracle/libm_probe.cpp``), not assumed from the target.

NavFn's own ``hypot`` (A*'s distance term, :mod:`.numeric`) is left on the host's libm: its
arguments are ints and its double is narrowed to float, where the two kernels agree (a test
holds this on every pair of ints below 400).
"""

from __future__ import annotations

import math

from .numeric import c_fma

SCALE = 2.0 ** -600
LARGE_VAL = 2.0 ** 511
TINY_VAL = 2.0 ** -459
EPS = 2.0 ** -54
HYPOTS = ("glibc", "glibc-fma")  # the kernels, by the name build.json records


def _kernel(ax: float, ay: float, fused: bool) -> float:
    """The kernel for ``ax >= ay >= 0`` whose squares neither overflow nor underflow."""
    if fused:
        t1, t2 = ay + ay, ax - ay
        return math.sqrt(c_fma(t1, ax, t2 * t2) if t1 >= ax else c_fma(ax, ax, ay * ay))
    h = math.sqrt(ax * ax + ay * ay)
    if h <= 2.0 * ay:
        delta = h - ay
        t1 = ax * (2.0 * delta - ax)
        t2 = (delta - 2.0 * (ax - ay)) * delta
    else:
        delta = h - ax
        t1 = 2.0 * delta * (ax - 2.0 * ay)
        t2 = (4.0 * delta - ay) * ay + delta * delta
    return h - (t1 + t2) / (2.0 * h)


def glibc_hypot(x: float, y: float, kernel: str = "glibc") -> float:
    """``hypot(x, y)`` (double) as glibc 2.35+ computes it with the kernel ``kernel`` of :data:`HYPOTS`."""
    if kernel not in HYPOTS:
        raise ValueError(f"no hypot kernel {kernel!r} (there are: {', '.join(HYPOTS)})")
    fused = kernel == "glibc-fma"
    if not (math.isfinite(x) and math.isfinite(y)):
        return math.inf if math.isinf(x) or math.isinf(y) else x + y
    x, y = abs(x), abs(y)
    ax, ay = (y, x) if x < y else (x, y)
    if ax > LARGE_VAL:
        return ax + ay if ay <= ax * EPS else _kernel(ax * SCALE, ay * SCALE, fused) / SCALE
    if ay < TINY_VAL:
        return ax + ay if ax >= ay / EPS else _kernel(ax / SCALE, ay / SCALE, fused) * SCALE
    return ax + ay if ay <= ax * EPS else _kernel(ax, ay, fused)


def kernel_of(inputs, outputs):
    """The kernel of :data:`HYPOTS` that gives every double of ``outputs`` (bit for bit) on the
    pairs ``inputs``, or None; and, per kernel, on how many pairs it differs."""
    import struct

    def bits(v):
        return struct.pack("<d", v)

    misses = {k: sum(bits(glibc_hypot(x, y, k)) != bits(want) for (x, y), want in zip(inputs, outputs))
              for k in HYPOTS}
    return next((k for k, n in misses.items() if n == 0), None), misses


def probe_inputs(n: int = 3000, seed: int = 0) -> list[tuple[float, float]]:
    """Pairs that tell the kernels apart, and reach every branch: footprint-like coordinates
    (within +-2 m), magnitudes from 1e-320 to 1e300, small ints, and the special values."""
    import numpy as np

    rng = np.random.default_rng(seed)
    k = n // 3
    near = rng.uniform(-2.0, 2.0, (k, 2))
    wide = np.exp(rng.uniform(math.log(1e-320), math.log(1e300), (k, 2))) * rng.choice([-1.0, 1.0], (k, 2))
    ints = rng.integers(-1000, 1000, (n - 2 * k, 2)).astype(np.float64)
    special = [(math.inf, math.nan), (math.nan, 1.0), (0.0, -0.0), (5e-324, 5e-324), (1e308, 1e308), (3.0, 4.0)]
    return [(float(a), float(b)) for a, b in np.concatenate([near, wide, ints])] + special
