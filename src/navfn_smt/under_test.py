"""The planner under test: which NavFn a command plans with, verifies or compares, as one value.

A user names it once, on the command line, and every layer below reads it from this value:

- ``--variant``: NavFn as Nav2 ships it (``original``) or with a fix (``fixed``, docs/fix.md, or a
  candidate of :mod:`navfn_smt.spec.fixes`), carried as its :class:`~navfn_smt.spec.planner.Fix`;
- ``--target NAME``: the arithmetic of a build for that machine (``x86-64``, the golden files'
  and the default; ``x86-64-v3``; ``aarch64``: docs/toolchains.md);
- ``--oracle DIR``: a build of the user's own sources (``navfn-smt oracle build``); its
  distribution, target and arithmetic (NavFn's, the plugin's, the layers') are read from its
  build.json, where the build recorded what it found in its object code and probes.

:func:`navfn_smt.commands.common.planner_of` makes it from those options, once per command;
:meth:`PlannerUnderTest.backend` is the spec (or its compiled backend) computing as it does.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path
from typing import Optional

from .errors import NavfnInputError
from .spec.arithmetic import KNOWN, X86_64, Arithmetic
from .spec.fix import FIX as THE_FIX
from .spec.planner import AS_SHIPPED, Fix


@dataclass(frozen=True)
class PlannerUnderTest:
    """NavFn with ``fix`` (:data:`~navfn_smt.spec.planner.AS_SHIPPED`: as Nav2 ships it), computing in ``arithmetic`` (NavFn's own; None only for a build whose
    arithmetic the spec cannot express, ``unexpressible`` saying why), of the Nav2 ``distribution``
    (None: not named; NavFn's own code is the same in every distribution, the plugin's and the
    costmap's rules are not); ``build``: the oracle build folder it was read from (None when
    named by ``--target``), whose build.json is ``doc``."""

    fix: Fix = AS_SHIPPED
    arithmetic: Optional[Arithmetic] = X86_64
    distribution: Optional[str] = None
    build: Optional[Path] = None
    doc: Optional[dict] = field(default=None, compare=False, repr=False)
    unexpressible: str = ""

    def __post_init__(self):
        if not isinstance(self.fix, Fix):
            raise TypeError(f"a planner under test takes a Fix, not {self.fix!r} (spec.fixes.named parses a name)")

    @property
    def variant(self) -> str:
        """The fix's name, as the command line and reports name it."""
        return self.fix.name

    @property
    def _of_build(self) -> str:
        return f" of {self.build}" if self.build is not None else ""

    @staticmethod
    def of_target(target: Optional[str] = None, fix: Fix = AS_SHIPPED,
                  distribution: Optional[str] = None) -> "PlannerUnderTest":
        """The planner computing as a build for the machine ``target`` does (None: x86-64)."""
        if target is not None and target not in KNOWN:
            raise NavfnInputError(f"--target {target!r}: no such arithmetic (there are: {', '.join(KNOWN)})")
        return PlannerUnderTest(fix, KNOWN[target or "x86-64"], distribution)

    @staticmethod
    def of_build(folder, fix: Fix = AS_SHIPPED, distribution: Optional[str] = None) -> "PlannerUnderTest":
        """The planner an oracle build folder holds, its distribution and arithmetic as the build
        recorded them (``distribution``, when given, must be the build's)."""
        from .oracle.arithmetic import of_build
        from .oracle.build import load_build

        doc = load_build(folder)
        arith, why = of_build(doc)
        if distribution is not None and distribution != doc.get("distribution"):
            raise NavfnInputError(f"--distro {distribution}: {folder} is a build of {doc.get('distribution')}'s "
                                  f"sources (leave --distro out: the build names it)")
        return PlannerUnderTest(fix, arith, doc.get("distribution"), Path(folder), doc, why or "")

    @property
    def target(self) -> str:
        """The machine of the build (``build.json``'s target), or the arithmetic's name."""
        if self.doc is not None:
            return self.doc.get("target", "x86-64")
        return self.arithmetic.name

    def navfn_arithmetic(self) -> Arithmetic:
        """NavFn's arithmetic; a clear error when the spec cannot express the build's."""
        if self.arithmetic is None:
            raise NavfnInputError(f"{self.build}: {self.unexpressible}")
        return self.arithmetic

    def fp32_semantics(self) -> str:
        """The float32 semantics of the symbolic domains this planner computes in (a key of
        :data:`navfn_smt.smt.domains.FP32_SEMANTICS`: ``fp32`` for x86-64's arithmetic,
        ``fp32@aarch64``, ``fp32@x86-64-v3``); a clear error for an arithmetic they do not have."""
        arith = self.navfn_arithmetic()  # named as smt.domains names them (a test holds the two equal)
        found = next((name for name, a in KNOWN.items() if a == arith), None)
        if found is None:
            raise NavfnInputError(f"the arithmetic {arith.name}{self._of_build} is none the symbolic encodings "
                                  f"compute in ({', '.join(KNOWN)})")
        return "fp32" if arith == X86_64 else f"fp32@{found}"

    def _found(self, reader, what: str, program: str):
        """What ``reader`` (one of oracle.arithmetic's ``*of_build``) finds in the build for the
        program ``program``; a clear error when there is no build, no such program or nothing the
        models can compute in."""
        if self.doc is None:
            raise NavfnInputError(f"the {what} arithmetic is found in a build: give --oracle DIR (navfn-smt oracle build)")
        if program not in self.doc.get("programs", (program,)):
            why = self.doc.get("skipped", {}).get(program, "build it again with `navfn-smt oracle build`")
            raise NavfnInputError(f"{self.build}: this build has no {program} (it has "
                                  f"{', '.join(self.doc['programs']) or 'no program'}; {why})")
        value, why = reader(self.doc)
        if value is None:
            raise NavfnInputError(f"{self.build}: {why}")
        return value

    def plugin_arithmetic(self):
        """The :class:`~navfn_smt.spec.arithmetic.PluginArithmetic` the build's plugin was found
        to compute in; a clear error when there is none the model can compute in."""
        from .oracle.arithmetic import plugin_of_build

        return self._found(plugin_of_build, "plugin's", "navfn-plugin")

    def layers_arithmetic(self):
        """The :class:`~navfn_smt.spec.arithmetic.LayersArithmetic` of the build's costmap layers."""
        from .oracle.arithmetic import layers_of_build

        return self._found(layers_of_build, "layers'", "costmap-layers")

    def backend(self, name: str):
        """The backend ``name`` (``reference`` or ``jit``) planning as this planner does."""
        from .backends import get_backend

        return get_backend(name, self)

    @property
    def label(self) -> str:
        """How reports name it: ``original, aarch64 arithmetic``, or with the build
        ``fixed, the C++ of rolling for x86-64, x86-64 arithmetic``."""
        arith = self.arithmetic.name if self.arithmetic is not None else "unexpressible"
        if self.doc is None:
            return f"{self.variant}, {arith} arithmetic" + (f", {self.distribution}" if self.distribution else "")
        return f"{self.variant}, the C++ of {self.distribution} for {self.target}, {arith} arithmetic"

    def as_dict(self) -> dict:
        """What JSON reports record of it."""
        return {"variant": self.variant, "target": self.target,
                "arithmetic": self.arithmetic.name if self.arithmetic is not None else None,
                **({"distribution": self.distribution} if self.distribution else {}),
                **({"build": str(self.build)} if self.build is not None else {})}


ORIGINAL = PlannerUnderTest()  # NavFn as Nav2 ships it, in the golden files' arithmetic (x86-64)
FIXED = PlannerUnderTest(THE_FIX)  # with the fix of docs/fix.md
