"""Measured results of the x86 ``rsqrtps`` instruction, for Eigen's fast float square root.

Eigen 3.4 (``EIGEN_FAST_MATH``, on by default) computes ``cwiseSqrt()`` of float packets on
SSE as ``x * r``, ``r`` one Newton step from ``_mm_rsqrt_ps(x)`` (see
:func:`navfn_smt.nav2.inflation.eigen_sse_sqrt`).  ``rsqrtps`` is a table lookup whose
contents differ between CPU vendors.  On the machine measured here (an AMD EPYC, Zen) its
result for a positive normal float depends only on the exponent's parity and the top 12
mantissa bits, and scales exactly by powers of 4 (checked for every mantissa, exponents
-60..60, and end to end on every integer 0..2^24).

``amd-zen``: 8192 float32, entry ``p * 4096 + i`` = ``rsqrtps`` of the float with biased
exponent ``127 + p`` and mantissa ``i << 11`` (inputs in [1, 2) for p = 0, [2, 4) for p = 1).
Measured with a small C program calling ``_mm_rsqrt_ps`` (gcc 12, Debian 12).

``intel-xeon-6-167``: the same table measured on an Intel Xeon (CPU family 6, model 167), the
machine the live costmap difftest first ran on; the same structure holds there (checked for
every mantissa at every tenth exponent of -60..60 and every eighth elsewhere), and Eigen's
square root built from Nav2's layers' flags equals the emulation on every integer below 2^20.
"""

from functools import lru_cache
from pathlib import Path

import numpy as np

HERE = Path(__file__).parent / "rsqrt"  # the tables: NAME.npy, 8192 little-endian float32 each


@lru_cache(maxsize=None)
def rsqrt_table(name: str = "amd-zen") -> np.ndarray:
    """The measured ``rsqrtps`` table ``name`` (``amd-zen``, ``intel-xeon-6-167``: ``HERE/NAME.npy``)
    as a read-only float32 array of 8192 entries."""
    t = np.load(HERE / f"{name}.npy", allow_pickle=False).astype(np.float32)
    if t.shape != (8192,):
        raise ValueError(f"{HERE / name}.npy: {t.shape} entries, expected 8192")
    t.setflags(write=False)
    return t
