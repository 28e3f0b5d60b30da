"""Declaring proof obligations: a property of the kernels, stated once for every semantics.

An obligation is a function ``build(D) -> (pre, claim)`` written against a numeric domain
``D`` (:mod:`navfn_smt.smt.domains`): it mints its variables from ``D``, runs the spec
kernels on them and returns a precondition and a claim.  Obligations live in
``proofs/*.py``, declared with :func:`obligation`, each with the verdict it is expected
to get in each semantics (one of :data:`STATUSES`); :func:`load_obligations` collects
them.  Checking them is :mod:`navfn_smt.smt.checking`'s job; ``navfn-smt prove`` fails
when a verdict changes.
"""

from __future__ import annotations

import importlib.util
from dataclasses import dataclass
from pathlib import Path
from typing import Callable, Optional

from ..errors import NavfnInputError
from .domains import DOMAINS

STATUSES = ("proved", "refuted", "unknown")


@dataclass(frozen=True)
class Bound:
    """For a property that fails in float32 only for large values: the variable to bound
    (``var < X``) and the range in which the largest X that still proves is searched."""

    var: str
    lo: float
    hi: float


@dataclass
class Obligation:
    """One declared property: its ``build``, the paper predicate it belongs to, the verdict
    expected in each semantics and what it needs to be checked (bound, hypotf model, time cap)."""

    name: str
    predicate: str  # the paper's predicate this obligation is part of
    build: Callable
    expect: dict  # semantics -> "proved" | "refuted" | "unknown" (an open question, documented as such)
    scope: str
    doc: str
    source: str = ""
    bound: Optional[Bound] = None
    timeout: Optional[float] = None  # a cap on the run's time limit (for questions known to be open)
    hypotf_model: str = "glibc"  # fp32: glibc's exact implementation, "ulp" (documented accuracy) or "bounds" (ordering only)
    slow: tuple = ()  # semantics whose query belongs to the long run (`prove --all`), not the default one
    arrays: bool = False  # stated over SMT arrays (a map of any size): the concrete spec cannot replay a model

    @property
    def title(self) -> str:
        return self.doc.strip().splitlines()[0] if self.doc else self.name


def obligation(predicate, expect: dict, scope: str, bound: Optional[Bound] = None, hypotf_model: str = "glibc",
               timeout: Optional[float] = None, slow=(), arrays: bool = False):
    """Declare a proof obligation (a decorator for ``build(D) -> (pre, claim)``) as part of
    ``predicate`` (a :class:`~navfn_smt.smt.chains.Predicate`, or just a name).

    ``timeout`` caps the run's time limit for this obligation: an open question (expected
    ``unknown``) need not spend the whole limit of every run on a known timeout.  ``slow``
    names the semantics whose query is left to the long run (``prove --all``): a question a
    split decides, or a proof that takes longer than the default run may.  ``arrays``: the
    obligation is stated over SMT arrays, which the concrete spec has not, so a model of its
    negation cannot be replayed and is never reported as a counterexample (it stays unknown)."""

    def wrap(fn):
        for sem, verdict in expect.items():
            if sem not in DOMAINS or verdict not in STATUSES:
                raise ValueError(f"{fn.__name__}: bad expectation {sem}={verdict}")
        name = getattr(predicate, "name", predicate)
        return Obligation(fn.__name__, name, fn, dict(expect), scope, fn.__doc__ or "", bound=bound,
                          hypotf_model=hypotf_model, timeout=timeout, slow=tuple(slow), arrays=arrays)

    return wrap


def load_proof_module(path):
    """The proof file ``path`` run as a module (one-line errors for a missing or broken file)."""
    p = Path(path)
    if not p.is_file():
        raise NavfnInputError(f"{p}: no such proof file")
    spec = importlib.util.spec_from_file_location(f"navfn_proofs.{p.stem}", p)
    mod = importlib.util.module_from_spec(spec)
    try:
        spec.loader.exec_module(mod)
    except (Exception, SystemExit) as e:  # a broken proof file is the user's input
        raise NavfnInputError(f"{p}: cannot load ({type(e).__name__}: {e})") from None
    return mod


def load_obligations(paths) -> list[Obligation]:
    """Every :class:`Obligation` defined at module level in the given proof files."""
    found: list[Obligation] = []
    for p in paths:
        found.extend(_module_obligations(Path(p), load_proof_module(p)))
    names = [o.name for o in found]
    dup = {n for n in names if names.count(n) > 1}
    if dup:
        raise NavfnInputError(f"obligations defined twice: {', '.join(sorted(dup))}")
    return found


def load_obligations_from(path, source: bytes) -> list[Obligation]:
    """The obligations of the proof file ``path`` whose contents are ``source``: read from the
    file when it is there with those contents, run from ``source`` otherwise (a worker of a
    remote cluster, where the driver's file does not exist).  Either way their ``source`` is
    ``path``, the driver's name for the file."""
    p = Path(path)
    try:
        if p.is_file() and p.read_bytes() == source:
            return load_obligations([p])
    except OSError:
        pass
    mod = importlib.util.module_from_spec(importlib.util.spec_from_loader(f"navfn_proofs.{p.stem}", loader=None))
    mod.__file__ = str(p)
    try:
        exec(compile(source, str(p), "exec"), vars(mod))
    except (Exception, SystemExit) as e:  # as for a file: a broken proof file is the user's input
        raise NavfnInputError(f"{p}: cannot load ({type(e).__name__}: {e})") from None
    return _module_obligations(p, mod)


def _module_obligations(p: Path, mod) -> list[Obligation]:
    """The obligations defined at module level by ``mod``, the proof file ``p`` run."""
    obs = [v for v in vars(mod).values() if isinstance(v, Obligation)]
    if not obs:
        raise NavfnInputError(f"{p}: defines no obligations")
    for o in obs:
        o.source = str(p)
    return obs
