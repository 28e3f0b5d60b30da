"""The compiled numeric domain: the kernels of :mod:`navfn_smt.spec.kernels`, run by numba.

The fast backend does not restate the planner's arithmetic.  It calls the very functions
the reference spec and the SMT obligations call, with ``D`` bound to :data:`ND`, an
instance of :class:`NumbaDomain`: a value numba types as a zero-size constant whose
methods (``ND.add``, ``ND.widen``, ``ND.ite``, ...) are compiled from the implementations
below (small functions LLVM inlines into their callers).  Every C++ ``float`` is a ``np.float32``, every ``double`` a
``np.float64``, every ``int`` a machine integer.

Float operations coerce their operands to float32 first, so an operand that arrives as a
double by mistake is still computed as C++ does (the coercion of a float32 is free).  The
library functions are the ones the other domains use: ``hypot``/``hypotf`` from the
platform's libm (numba calls the same C functions), and ``roundf``, the x86-64 float to
int conversion and the 32-bit int wrap compiled from :mod:`navfn_smt.spec.numeric`.

:func:`jit` compiles a function with the backend's options and an on-disk cache keyed by
the content of the sources it depends on, so an edited kernel is never run from a stale
cache (numba itself only notices changes to the file of the function it caches).
"""

from __future__ import annotations

import contextlib
import functools
import hashlib
import inspect
import math
import os
from pathlib import Path

import numpy as np
from llvmlite import ir as llvm_ir
from numba import config, njit, types
from numba.core.imputils import lower_constant
from numba.extending import (NativeValue, intrinsic, models, overload, overload_method, register_model, typeof_impl,
                             unbox)

from ..spec import extraction as E
from ..spec import kernels as K
from ..spec import numeric
from ..spec import propagation as P
from ..spec.arithmetic import X86_64

JIT_OPTIONS = {"error_model": "numpy"}  # float division by zero gives inf/nan, as in C++

_PACKAGE = Path(__file__).resolve().parents[1]
# every source compiled code is built from: the spec, the backends, and the plugin's sweep
# with the plugin's rules it compiles
_SOURCES = ("spec/*.py", "backends/*.py", "nav2/plugin.py", "nav2/sweep_loops.py")


def _source_digest() -> str:
    """SHA-256 over every source the compiled code is built from (:data:`_SOURCES`)."""
    h = hashlib.sha256()
    for pattern in _SOURCES:
        for p in sorted(_PACKAGE.glob(pattern)):
            h.update(p.relative_to(_PACKAGE).as_posix().encode())
            h.update(p.read_bytes())
    return h.hexdigest()[:16]


def _cache_root() -> Path:
    base = os.environ.get("NUMBA_CACHE_DIR") or os.environ.get("XDG_CACHE_HOME") or Path.home() / ".cache"
    sub = "navfn-smt" if not os.environ.get("NUMBA_CACHE_DIR") else ""
    return Path(base) / sub / f"jit-{_source_digest()}"


CACHE_DIR = _cache_root()
KEEP_CACHES = 6  # compiled caches of other source versions kept beside the current one (newest first)


def _prune_old_caches() -> None:
    """Remove the compiled caches of all but the most recently created source versions."""
    import shutil

    try:
        others = sorted((p for p in CACHE_DIR.parent.glob("jit-*") if p != CACHE_DIR),
                        key=lambda p: p.stat().st_mtime, reverse=True)
        for p in others[KEEP_CACHES:]:
            shutil.rmtree(p, ignore_errors=True)
    except OSError:
        pass  # a cache that cannot be tidied is still a cache


_prune_old_caches()


@contextlib.contextmanager
def _cache_dir():
    old = config.CACHE_DIR
    config.CACHE_DIR = str(CACHE_DIR)
    try:
        yield
    finally:
        config.CACHE_DIR = old


def jit(fn):
    """``njit(cache=True)`` with the backend's options and the source-keyed cache."""
    with _cache_dir():
        return njit(cache=True, **JIT_OPTIONS)(fn)


def jit_inline(fn):
    """:func:`jit`, its body inlined into every compiled caller (no call, no reference
    counting of its array arguments): for a loop that several compiled loops share."""
    with _cache_dir():
        return njit(cache=True, inline="always", **JIT_OPTIONS)(fn)


# --------------------------------------------------------------------------------------
# The domain value and its type
# --------------------------------------------------------------------------------------
class NumbaDomain:
    """The compiled domain in one build's arithmetic; use :data:`ND` (x86-64's) or
    :func:`numba_domain`.  Passed to compiled code as an argument, it costs nothing at run
    time: its type carries the arithmetic, so each arithmetic compiles its own code, in
    which ``D.fuses(site)`` is a constant and ``D.to_int32`` the build's conversion."""

    name = "numba"

    def __init__(self, arith=X86_64):
        self.arith = arith

    def __reduce__(self):  # sent to worker processes as the arithmetic it computes in
        return (numba_domain, (self.arith,))


class NumbaDomainType(types.Dummy):
    def __init__(self, arith):
        self.arith = arith
        super().__init__(name=f"NumbaDomain[{arith.key}]")


@functools.lru_cache(maxsize=None)
def _type_of(arith) -> NumbaDomainType:
    return NumbaDomainType(arith)


typeof_impl.register(NumbaDomain)(lambda val, c: _type_of(val.arith))
register_model(NumbaDomainType)(models.OpaqueModel)
lower_constant(NumbaDomainType)(lambda context, builder, ty, pyval: context.get_dummy_value())
unbox(NumbaDomainType)(lambda typ, obj, c: NativeValue(c.context.get_dummy_value()))

@functools.lru_cache(maxsize=None)
def _domain(arith) -> NumbaDomain:
    return NumbaDomain(arith)


def numba_domain(arith=None) -> NumbaDomain:
    """The compiled domain computing as a build of ``arith`` does (None: x86-64's), one per arithmetic."""
    return _domain(X86_64 if arith is None else arith)


ND = numba_domain(X86_64)

# --------------------------------------------------------------------------------------
# The operations (names and meaning as in navfn_smt.spec.numeric.ConcreteDomain)
# --------------------------------------------------------------------------------------
_CONVERTERS = {name: njit(**JIT_OPTIONS)(fn) for name, fn in numeric.CONVERTERS.items()}
_roundf = njit(**JIT_OPTIONS)(numeric.c_roundf)
_wrap_int32 = njit(**JIT_OPTIONS)(numeric.wrap_int32)
F32, F64 = np.float32, np.float64


def _to_int32(self, a):  # the build's conversion: cvttss2si / cvttsd2si, or fcvtzs
    convert = _CONVERTERS[self.arith.conversion]

    def impl(self, a):
        return convert(a)

    return impl


@intrinsic
def fma_llvm(typingctx, a, b, c):
    """LLVM's ``llvm.fma`` on three floats of one type: ``a * b + c`` rounded once."""
    if not (a == b == c and isinstance(a, types.Float)):
        return None
    sig = a(a, b, c)

    def codegen(context, builder, signature, args):
        ty = args[0].type
        fn = builder.module.declare_intrinsic("llvm.fma", [ty], llvm_ir.FunctionType(ty, [ty, ty, ty]))
        return builder.call(fn, args)

    return sig, codegen


def _fuses(self, site):  # a constant of the compiled code: whether the build fused ``site``
    if not isinstance(site, types.StringLiteral):
        return None  # asked again with the site's literal value
    fused = self.arith.fuses(site.literal_value)

    def impl(self, site):
        return fused

    return impl


# every operation but the two typed by the arithmetic: float operands coerced to float32 (C++
# float) or float64 (double) first
OPERATIONS = {
    "f32const": lambda self, x: F32(x), "f64const": lambda self, x: F64(x),
    "widen": lambda self, a: F64(F32(a)),  # float -> double, exact
    "narrow": lambda self, a: F32(F64(a)),  # double -> float, round to nearest even
    "int_to_f32": lambda self, n: F32(n), "int_to_f64": lambda self, n: F64(n), "to_int32": _to_int32,
    "add_int": lambda self, a, b: _wrap_int32(a + b),
    "add": lambda self, a, b: F32(F32(a) + F32(b)), "sub": lambda self, a, b: F32(F32(a) - F32(b)),
    "mul": lambda self, a, b: F32(F32(a) * F32(b)), "div": lambda self, a, b: F32(F32(a) / F32(b)),
    "neg": lambda self, a: -F32(a),
    "add64": lambda self, a, b: F64(a) + F64(b), "sub64": lambda self, a, b: F64(a) - F64(b),
    "mul64": lambda self, a, b: F64(a) * F64(b), "div64": lambda self, a, b: F64(a) / F64(b),
    "fma": lambda self, a, b, c: fma_llvm(F32(a), F32(b), F32(c)),
    "fma64": lambda self, a, b, c: fma_llvm(F64(a), F64(b), F64(c)),
    "fuses": _fuses,
    "hypot64": lambda self, a, b: math.hypot(F64(a), F64(b)),  # libm hypot
    "hypotf": lambda self, a, b: F32(math.hypot(F32(a), F32(b))),  # libm hypotf
    "roundf": lambda self, a: F32(_roundf(F32(a))),
    "lt": lambda self, a, b: a < b, "le": lambda self, a, b: a <= b, "gt": lambda self, a, b: a > b,
    "ge": lambda self, a, b: a >= b, "eq": lambda self, a, b: a == b,
    "and_": lambda self, a, b: a and b, "or_": lambda self, a, b: a or b, "not_": lambda self, a: not a,
    "ite": lambda self, c, a, b: a if c else b,
}


def returning(impl):
    """A typing function with ``impl``'s signature that always answers ``impl``."""

    @functools.wraps(impl)
    def typer(*args, **kwargs):
        return impl

    return typer


# operations whose code depends on the domain's arithmetic: their typing functions choose it
TYPED_BY_ARITHMETIC = {"fuses": _fuses, "to_int32": _to_int32}


def _register(name, impl):
    if name in TYPED_BY_ARITHMETIC:
        overload_method(NumbaDomainType, name, jit_options=JIT_OPTIONS, prefer_literal=True)(impl)
    else:
        overload_method(NumbaDomainType, name, jit_options=JIT_OPTIONS)(returning(impl))


for _name, _impl in OPERATIONS.items():
    _register(_name, _impl)


# --------------------------------------------------------------------------------------
# The kernels become callable from compiled code, unchanged
# --------------------------------------------------------------------------------------
KERNELS = tuple(
    name for name, fn in vars(K).items()
    if callable(fn) and getattr(fn, "__module__", None) == K.__name__
)
for _name in KERNELS:
    _fn = getattr(K, _name)
    # a kernel that names a multiply-add site is typed with the site's literal value, so that
    # ``D.fuses(site)`` inside it is a constant
    _literal = "site" in inspect.signature(_fn).parameters
    overload(_fn, jit_options=JIT_OPTIONS, prefer_literal=_literal)(returning(_fn))

# the helpers of the spec's loop steps the compiled loops run (calcPath's ring of eight, its
# potentials and its tests, spec/extraction.py; the buffers' emptiness test, spec/propagation.py),
# callable the same way
for _fn in (E.ring_of_eight, E.ring_potentials, E.off_the_rows, E.ring_leaves_the_array, E.grid_wanted,
            P.buffers_hold_cells):
    overload(_fn, jit_options=JIT_OPTIONS)(returning(_fn))
