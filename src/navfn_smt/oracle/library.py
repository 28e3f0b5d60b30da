"""The user's own NavFn binary in the loop: the driver linked against a shared library of NavFn.

A robot loads ``libnav2_navfn_planner.so`` as its package build made it (``-fPIC -O2 -g``,
shared).  ``oracle build NAV2_SRC --library FILE.so`` links ``navfn_driver.cpp`` (compiled
with the headers of ``NAV2_SRC``) against a copy of that file in the build folder, so the
program ``navfn-plain`` runs the library's own machine code.  Only the plain program is made:
the traced and the other programs need NavFn's source.

The library's target is read from its ELF header, and its arithmetic from its own machine
code: ``objdump -d -l`` traces every fused multiply-add instruction to a line of
``navfn.cpp`` through the library's debug information (matched to the sites of
:data:`~navfn_smt.spec.arithmetic.SITES` by the text of that line in ``NAV2_SRC``, so the
sources must be the library's).  A library with fused multiply-adds and no line information
is reported as unexpressible: the sites cannot be told.
"""

from __future__ import annotations

from pathlib import Path

from ..errors import NavfnInputError
from .arithmetic import FMA, located_binary, objdump

ELF_MACHINES = {62: "x86-64", 183: "aarch64"}  # e_machine -> the target of oracle.targets
OBJDUMP = {"x86-64": "objdump", "aarch64": "aarch64-linux-gnu-objdump"}


def elf_target(path: Path) -> str:
    """The target a shared library is built for, from its ELF header (a clear error otherwise)."""
    try:
        head = path.read_bytes()[:20]
    except OSError as e:
        raise NavfnInputError(f"--library {path}: {e.strerror}") from None
    if head[:4] != b"\x7fELF" or len(head) < 20:
        raise NavfnInputError(f"--library {path}: not an ELF shared library")
    machine = int.from_bytes(head[18:20], "little" if head[5] == 1 else "big")
    if machine not in ELF_MACHINES:
        raise NavfnInputError(f"--library {path}: built for ELF machine {machine}, not one of "
                              f"{', '.join(ELF_MACHINES.values())}")
    return ELF_MACHINES[machine]


def fused_lines_of_binary(disassembly: str, source_name: str) -> tuple:
    """``(lines, untraced)``: the ``source_name`` lines that fused multiply-add instructions of
    ``objdump -d -l`` output come from, and how many such instructions have no line at all."""
    lines, untraced = [], 0
    for (path, n), _, text in located_binary(disassembly):
        if FMA.match(" " + text):
            if path is None:
                untraced += 1
            elif path.name == source_name:
                lines.append(n)
    return lines, untraced


def disassemble(lib: Path, target: str) -> str:
    try:
        return objdump(OBJDUMP.get(target, "objdump"), lib)
    except RuntimeError as e:
        raise NavfnInputError(f"--library {lib}: {e}") from None
