"""The arithmetic of an oracle build, found from the build itself (:class:`~navfn_smt.spec.arithmetic.Arithmetic`).

- **Fused multiply-adds**, from the object code: ``navfn.cpp`` is compiled again with the
  build's compiler and flags plus ``-S -g`` (debug information does not change GCC's code), and
  every fused multiply-add instruction (x86's ``vfmadd...``/``vfnmadd...``, arm64's
  ``fmadd``/``fmsub``/``fnmadd``/``fnmsub``/``fmla``/``fmls``, RISC-V's ``fmadd.s`` ...) is
  traced to its source line through the ``.loc`` directives.  Each line is a site of
  :data:`~navfn_smt.spec.arithmetic.SITES` by its text; a site is fused when every line of it
  has one.  A fused line that is no site, or a site fused on some of its lines only, is
  arithmetic the spec cannot express: named in ``unexpressible``.
- **Conversions**, by running the build's own code: ``conversion_probe.cpp``, compiled with the
  same compiler and flags and run as the build's programs run (under qemu for another
  machine), converts NaN, the infinities and out-of-range values with ``static_cast<int>``;
  the conversion is the one of the spec's converters (``CONVERTERS``) that gives the same ints.

Both are recorded in ``build.json`` (``arithmetic``); the difftest then holds the spec in that
arithmetic to the build, which is the evidence that what was found is right.
"""

from __future__ import annotations

import math
import re
import struct
import subprocess
from collections import defaultdict
from pathlib import Path

from ..spec.arithmetic import CONVERSIONS, Arithmetic, site_of_line
from ..spec.numeric import CONVERTERS

HERE = Path(__file__).resolve().parent
FMA = re.compile(r"^\s*(v?fn?m(add|sub)[\w.]*|fml[as][\w.]*)\s")
LOC = re.compile(r"^\s*\.loc\s+(\d+)\s+(\d+)")
FILE = re.compile(r'^\s*\.file\s+(\d+)\s+"([^"]*)"(?:\s+"([^"]*)")?')
PROBE_INPUTS = (math.nan, math.inf, -math.inf, 3.0e9, -3.0e9, 2147483648.0, -2147483904.0, 1.5e10)
# what each conversion the spec knows gives on the probe's inputs (the spec's own converters)
EXPECTED = {name: [convert(v) for v in PROBE_INPUTS] for name, convert in CONVERTERS.items()}


def fused_lines(assembly: str, source_name: str) -> list:
    """The source lines of ``source_name`` (a file name) that fused multiply-add instructions
    of ``assembly`` (``-S -g`` output) come from, in order, one entry per instruction."""
    files, current, lines = {}, None, []
    for text in assembly.splitlines():
        m = FILE.match(text)
        if m:
            files[m.group(1)] = m.group(3) or m.group(2)
            continue
        m = LOC.match(text)
        if m:
            current = (m.group(1), int(m.group(2)))
            continue
        if FMA.match(text) and current and Path(files.get(current[0], "")).name == source_name:
            lines.append(current[1])
    return lines


def fused_sites(source: Path, lines) -> tuple:
    """``(fused sites, {site: lines}, unexpressible)`` from the fused ``lines`` of ``source``."""
    text = source.read_text(encoding="utf-8").splitlines()
    found, problems = defaultdict(set), []
    for n in sorted(set(lines)):
        site = site_of_line(text[n - 1]) if 0 < n <= len(text) else None
        if site is None:
            problems.append(f"{source.name}:{n} fused `{text[n - 1].strip() if 0 < n <= len(text) else '?'}`, "
                            f"which is no multiply-add site of the spec")
        else:
            found[site].add(n)
    fused = set()
    for site, at in found.items():
        every = {i + 1 for i, t in enumerate(text) if site_of_line(t) == site}
        if at == every:
            fused.add(site)
        else:
            problems.append(f"{site} fused on {source.name} lines {sorted(at)} but not on {sorted(every - at)}")
    return fused, {s: sorted(v) for s, v in sorted(found.items())}, problems


def conversion(values) -> str:
    """The conversion the probe's answers show, or None when it is neither known one."""
    return next((name for name, want in EXPECTED.items() if list(values) == want), None)


def probe_conversion(tc, runner, folder: Path) -> list:
    """``static_cast<int>`` of :data:`PROBE_INPUTS` as the toolchain ``tc`` compiles it, run by
    ``runner``; the probe is built in ``folder``."""
    exe = folder / "conversion-probe"
    cmd = [tc.cxx, *tc.all_flags, str(HERE / "conversion_probe.cpp"), "-o", str(exe)]
    r = subprocess.run(cmd, capture_output=True, text=True)
    if r.returncode != 0:
        raise RuntimeError(f"the conversion probe did not compile: {r.stderr.strip()[:300]}")
    data = struct.pack(f"<i{len(PROBE_INPUTS)}f", len(PROBE_INPUTS), *PROBE_INPUTS)
    r = subprocess.run([*runner, str(exe)], input=data, capture_output=True, timeout=120)
    if r.returncode != 0 or len(r.stdout) != 4 * len(PROBE_INPUTS):
        raise RuntimeError(f"the conversion probe failed (exit {r.returncode})")
    return list(struct.unpack(f"<{len(PROBE_INPUTS)}i", r.stdout))


def assembly(tc, source: Path, includes, defines, folder: Path) -> str:
    """``source`` compiled by ``tc`` with ``-S -g``, as text."""
    out = folder / (source.stem + ".s")
    cmd = [tc.cxx, *tc.all_flags, "-S", "-g", *(f"-I{i}" for i in includes), *(f"-D{d}" for d in defines),
           str(source), "-o", str(out)]
    r = subprocess.run(cmd, capture_output=True, text=True)
    if r.returncode != 0:
        raise RuntimeError(f"{source.name} did not compile to assembly: {r.stderr.strip()[:300]}")
    return out.read_text(encoding="utf-8", errors="replace")


def find(tc, runner, navfn_cpp: Path, includes, defines, folder: Path) -> dict:
    """The arithmetic of NavFn built by ``tc``: build.json's ``arithmetic`` entry."""
    lines = fused_lines(assembly(tc, navfn_cpp, includes, defines, folder), navfn_cpp.name)
    return record(lines, navfn_cpp, tc, runner, folder)


def record(lines, navfn_cpp: Path, tc, runner, folder: Path, untraced: int = 0) -> dict:
    """build.json's ``arithmetic`` entry from the fused ``lines`` of ``navfn_cpp`` (and
    ``untraced`` fused instructions without a source line) and the conversion probe of ``tc``."""
    fused, at, problems = fused_sites(navfn_cpp, lines)
    if untraced:
        problems.append(f"{untraced} fused multiply-add instructions have no source line (no debug information: "
                        f"build with -g), so their sites cannot be told")
    values = probe_conversion(tc, runner, folder)
    conv = conversion(values)
    if conv is None:
        problems.append(f"static_cast<int> of {list(PROBE_INPUTS)} gives {values}: neither "
                        f"{' nor '.join(CONVERSIONS)}")
    arith = Arithmetic(frozenset(fused), conv or "indefinite")
    return {**arith.as_dict(), "fused_instructions": len(lines) + untraced, "sites": at,
            "conversion_probe": {"inputs": [repr(v) for v in PROBE_INPUTS], "outputs": values},
            "unexpressible": problems}


def of_build(doc: dict):
    """The :class:`Arithmetic` a build.json records, or None with why when the spec cannot
    express it (or the build predates the record)."""
    entry = doc.get("arithmetic")
    if entry is None:
        return None, "this build does not record its arithmetic (built before navfn-smt found it): build it again"
    if entry.get("unexpressible"):
        return None, "the spec cannot express this build's arithmetic: " + "; ".join(entry["unexpressible"])
    return Arithmetic.from_dict(entry), None
