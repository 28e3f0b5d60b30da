"""The toolchains an oracle is built with: the target machine, its compiler and flags, and how
this machine runs what they make.

A :class:`Toolchain` is one value, made once from ``--target NAME`` (or ``--cxx/--cxxflags``)
and carried into the build, which records it in ``build.json``; the client reads back the
command that runs a program (``runner``), so a program built for another machine runs under
Debian's ``qemu-user`` without the caller knowing.

- ``x86-64``: ``$CXX`` or ``g++`` for this machine, no extra flags (the build of the golden
  files: SSE2 arithmetic, no fused multiply-add);
- ``x86-64-v3``: the same compiler with ``-march=x86-64-v3`` (AVX2 and FMA: GCC contracts
  ``a * b + c`` into one rounding), run natively when this CPU has FMA and AVX2, else under
  ``qemu-x86_64 -cpu max``;
- ``aarch64``: Debian's cross compiler ``aarch64-linux-gnu-g++`` (arm64, as on a Raspberry Pi
  or a Jetson; GCC contracts there by default), run under ``qemu-aarch64`` with Debian's
  cross sysroot ``/usr/aarch64-linux-gnu``;
- a user's own: ``--cxx CXX --cxxflags FLAGS``; its machine is what the compiler says
  (``-dumpmachine``).
"""

from __future__ import annotations

import platform
import shlex
import shutil
import subprocess
from dataclasses import dataclass, field
from pathlib import Path
from typing import Optional

from ..errors import NavfnInputError

FLAGS = ("-O2",)  # every build's own flags after the C++ standard, as Nav2's release builds compile NavFn
DEFAULT_TARGET = "x86-64"


@dataclass(frozen=True)
class Toolchain:
    """A target and the compiler that builds for it: ``cxx`` with ``FLAGS + flags``."""

    target: str
    cxx: str
    flags: tuple = ()
    packages: tuple = field(default=(), compare=False)  # Debian packages that provide cxx and the runner
    std: str = "c++17"  # the sources' C++ standard (the build sets it: oracle.build.cxx_standard)

    @property
    def all_flags(self) -> list:
        return [f"-std={self.std}", *FLAGS, *self.flags]

    def check(self) -> None:
        """A clear error when the compiler is missing (naming the Debian packages)."""
        if shutil.which(self.cxx) is None:
            hint = f" (Debian: apt-get install {' '.join(self.packages)})" if self.packages else ""
            raise NavfnInputError(f"no C++ compiler for {self.target}: {self.cxx!r} is not on PATH{hint}")

    def machine(self) -> str:
        """The compiler's target triple (``-dumpmachine``), e.g. ``aarch64-linux-gnu``."""
        r = subprocess.run([self.cxx, *self.flags, "-dumpmachine"], capture_output=True, text=True)
        return r.stdout.strip()

    def version(self) -> str:
        r = subprocess.run([self.cxx, "--version"], capture_output=True, text=True)
        return (r.stdout.splitlines() or [""])[0]

    def objdump(self) -> str:
        """The objdump that reads this toolchain's objects: this machine's for its own
        architecture, ``<triple>-objdump`` (Debian's cross binutils) for another's."""
        machine = self.machine()
        return "objdump" if machine.split("-")[0] == platform.machine() else f"{machine}-objdump"

    def runner(self) -> list:
        """The command prefix that runs this toolchain's programs here: none for this machine's
        own, ``qemu-<arch>`` for another's (a clear error when it is not installed)."""
        arch = self.machine().split("-")[0]
        host = platform.machine()
        if arch == host and not _needs_cpu_features(self.flags):
            return []
        qemu = f"qemu-{arch}"
        if shutil.which(qemu) is None:
            raise NavfnInputError(f"the {self.target} build runs here under {qemu}, which is not installed "
                                  f"(Debian: apt-get install qemu-user)")
        if arch == host:  # this machine's architecture, but a CPU level it lacks
            return [qemu, "-cpu", "max"]
        sysroot = Path(f"/usr/{self.machine()}")
        return [qemu, "-L", str(sysroot)] if sysroot.is_dir() else [qemu]


def _needs_cpu_features(flags) -> bool:
    """Whether ``-march=x86-64-v3`` (or v4) code needs FMA/AVX2 this CPU does not have."""
    level = next((f.split("=", 1)[1] for f in flags if f.startswith("-march=")), None)
    if level not in ("x86-64-v3", "x86-64-v4"):
        return False
    try:
        cpu = Path("/proc/cpuinfo").read_text(encoding="utf-8").split()
    except OSError:
        return True
    wanted = {"fma", "avx2"} | ({"avx512f"} if level == "x86-64-v4" else set())
    return not wanted <= set(cpu)


TARGETS = {
    "x86-64": lambda cxx: Toolchain("x86-64", cxx or "g++", (), ("g++",)),
    "x86-64-v3": lambda cxx: Toolchain("x86-64-v3", cxx or "g++", ("-march=x86-64-v3",), ("g++", "qemu-user")),
    "aarch64": lambda cxx: Toolchain("aarch64", cxx or "aarch64-linux-gnu-g++", (),
                                     ("g++-aarch64-linux-gnu", "qemu-user")),
}


def toolchain(target: Optional[str] = None, cxx: Optional[str] = None, cxxflags: Optional[str] = None,
              env_cxx: Optional[str] = None) -> Toolchain:
    """The toolchain of ``--target NAME`` (default x86-64, whose compiler ``$CXX`` may name), or
    of a user's ``--cxx CXX [--cxxflags FLAGS]`` (its target named after the compiler's machine
    unless ``--target`` names it)."""
    if target is not None and target not in TARGETS and cxx is None:
        raise NavfnInputError(f"--target {target!r}: no such target (there are: {', '.join(TARGETS)}; or give "
                              f"your own compiler with --cxx)")
    if cxx is None and cxxflags is not None:
        raise NavfnInputError("--cxxflags goes with --cxx (the compiler those flags are for)")
    if cxx is not None:
        flags = tuple(shlex.split(cxxflags or ""))
        base = TARGETS.get(target or "", None)
        tc = Toolchain(target or "custom", cxx, ((base(cxx).flags if base else ()) + flags))
        if target is None:
            tc.check()
            tc = Toolchain(f"custom-{tc.machine().split('-')[0] or 'unknown'}", cxx, flags)
        return tc
    name = target or DEFAULT_TARGET
    return TARGETS[name](env_cxx if name != "aarch64" else None)
