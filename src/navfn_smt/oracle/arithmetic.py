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

import functools
import math
import re
import shutil
import struct
import subprocess
from collections import defaultdict
from pathlib import Path

from ..spec.arithmetic import (CONVERSIONS, LAYER_ORDERS, LAYER_SITES, LAYERS_X86_64, PLUGIN_SITES, X86_64,
                               Arithmetic, LayersArithmetic, PluginArithmetic, layer_site_of_line, plugin_site_of_line,
                               site_of_line, squared_call_of_line)
from ..spec.libm import HYPOTS, kernel_of, probe_inputs
from ..spec.numeric import CONVERTERS, c_hypot

HERE = Path(__file__).resolve().parent
FMA = re.compile(r"^\s*(v?fn?m(add|sub)[\w.]*|fml[as][\w.]*)\s")
LOC = re.compile(r"^\s*\.loc\s+(\d+)\s+(\d+)")
FILE = re.compile(r'^\s*\.file\s+(\d+)\s+"([^"]*)"(?:\s+"([^"]*)")?')
# objdump -d -l --inlines: a source line, a call it is inlined at, an instruction
LINE = re.compile(r"^(/?[^\s:]+):(\d+)(?:\s|$)")
INLINED = re.compile(r"^inlined by (/?[^\s:]+):(\d+)(?:\s|$)")
INSN = re.compile(r"^\s*[0-9a-f]+:\s+(\S.*)$")
PROBE_INPUTS = (math.nan, math.inf, -math.inf, 3.0e9, -3.0e9, 2147483648.0, -2147483904.0, 1.5e10)
# what each conversion the spec knows gives on the probe's inputs (the spec's own converters)
EXPECTED = {name: [convert(v) for v in PROBE_INPUTS] for name, convert in CONVERTERS.items()}


def _located(assembly: str):
    """Each line of ``assembly`` (``-S -g`` output) that is not a ``.file`` or ``.loc`` directive,
    with the source ``(path, line)`` its code comes from (``(None, None)`` before the first)."""
    files, current = {}, (None, None)
    for text in assembly.splitlines():
        m = FILE.match(text)
        if m:
            files[m.group(1)] = Path(m.group(2)) / m.group(3) if m.group(3) else Path(m.group(2))
            continue
        m = LOC.match(text)
        if m:
            current = (files.get(m.group(1)), int(m.group(2)))
            continue
        yield current, text


def fused_lines(assembly: str, source_name: str) -> list:
    """The source lines of ``source_name`` (a file name) that fused multiply-add instructions
    of ``assembly`` (``-S -g`` output) come from, in order, one entry per instruction."""
    return [n for (path, n), text in _located(assembly)
            if FMA.match(text) and path is not None and path.name == source_name]


def fused_lines_by_file(assembly: str) -> dict:
    """``{(source file path, line): fused instructions}`` of every fused multiply-add of
    ``assembly`` that has a source line, in any file (headers inlined into it too)."""
    found = defaultdict(int)
    for where, text in _located(assembly):
        if FMA.match(text) and where[0] is not None:
            found[where] += 1
    return dict(found)


def _source_lines(path: Path) -> tuple:
    """The lines of a source file the assembly names (empty when it is not there to read)."""
    return tuple(path.read_text(encoding="utf-8", errors="replace").splitlines()) if path.is_file() else ()


def _operands(text):
    """An instruction's mnemonic and its operands, as written."""
    parts = text.split(None, 1)
    return parts[0], [o.strip() for o in parts[1].split(",")] if len(parts) > 1 else []


def located_binary(disassembly: str):
    """Each instruction of ``objdump -d -l --inlines`` output as ``((path, line), calls, text)``:
    the source line its code comes from (``(None, None)`` when it has none) and the lines of the
    calls it is inlined at, innermost first."""
    where, calls = (None, None), []
    for text in disassembly.splitlines():
        m = LINE.match(text)
        if m:
            where, calls = (Path(m.group(1)), int(m.group(2))), []
            continue
        m = INLINED.match(text)
        if m:
            calls.append((Path(m.group(1)), int(m.group(2))))
            continue
        if text.endswith(">:"):  # a new function: its lines come after its label
            where, calls = (None, None), []
            continue
        m = INSN.match(text)
        if m:
            yield where, tuple(calls), m.group(1)


def squared_operand_orders(disassembly: str, is_site, lines_of=_source_lines) -> list:
    """``[(call, order)]``, one per fused instruction of ``dx * dx + dy * dy`` (on a line
    ``is_site(path, line)`` says is it) in ``objdump -d -l --inlines`` output: the line
    ``(path, n)`` of the call the copy is inlined at (None when not inlined), and which square it
    fused: ``"dx"`` for ``fma(dx, dx, dy * dy)``, ``"dy"`` for ``fma(dy, dy, dx * dx)``, None when
    not found.  The multiplicand register is followed back to the instruction that last wrote it,
    and that instruction's line says ``dx =`` or ``dy =`` (arm64's ``fmadd d, n, m, a``; x86's
    ``vfmadd{132,213,231}sd`` in AT&T order).  Each inlined copy may choose differently.
    ``lines_of(path)``: a source file's lines."""
    body, orders = [], []
    for where, calls, text in located_binary(disassembly):
        body.append((where, text.strip()))
        if FMA.match(" " + text) and where[0] is not None and is_site(*where):
            orders.append((calls[0] if calls else None, _order(body, lines_of)))
    return orders


def _order(body, lines_of, names=("dx", "dy"), square=True) -> str:
    """Which variable of ``names`` the last instruction of ``body`` ((source line, text) pairs), a
    fused multiply-add, multiplies: the line that last wrote a multiplicand register assigns it.
    ``square``: the instruction must square one register (``dx * dx``), else either multiplicand
    register is followed (``A * C``)."""
    op, args = _operands(body[-1][1])
    if args and args[0].startswith("%"):  # AT&T: vfmadd{132,213,231}sd a, b, c (Intel c, b, a)
        if len(args) != 3:
            return None
        a, b, c = args
        mult = {"132": (c, a), "213": (b, c), "231": (b, a)}.get(re.sub(r"\D", "", op)[:3])
        dest_at = -1
    else:  # arm64: fmadd d, n, m, a
        mult = tuple(args[1:3]) if len(args) == 4 else None
        dest_at = 0
    if mult is None or (square and mult[0] != mult[1]):
        return None
    for reg in dict.fromkeys(r for r in mult if re.fullmatch(r"%?[a-z]+\d*", r)):  # registers, not memory
        for where, text in reversed(body[:-1]):
            _, ops = _operands(text)
            if ops and ops[dest_at] == reg:
                text = lines_of(where[0]) if where[0] is not None else ()
                m = re.search(rf"\b({'|'.join(names)})\s*=", text[where[1] - 1]) if 0 < where[1] <= len(text) else None
                if m:
                    return m.group(1)
                break
    return None


def _whole_sites(found: dict, source, site_of_line, any_part, problems: list) -> set:
    """The sites of ``found`` (site -> its fused ``(path, line)``) fused on every line of their file
    that ``site_of_line(file name, text)`` says is the site, or on any part of them where
    ``any_part(site)`` (the value is the same either way, or the driver cannot feel it); a site
    fused in part only is appended to ``problems``."""
    fused = set()
    for site, at in found.items():
        path = next(iter(at))[0]
        every = {(path, i + 1) for i, t in enumerate(source(path)) if site_of_line(path.name, t) == site}
        if at == every or any_part(site):
            fused.add(site)
        else:
            problems.append(f"{site} fused on {path.name} lines {sorted(n for _, n in at)} but not on "
                            f"{sorted(n for _, n in every - at)}")
    return fused


def _orders_by_call(disassembly: str, lines: set, source) -> tuple:
    """``({call: order}, problems)``: the square fused in each call of squared_distance
    (:data:`~navfn_smt.spec.arithmetic.SQUARED_CALLS`), from the fused instructions on ``lines``
    (``(file name, line)``) of ``disassembly``; a copy whose call or order is not found, a call the
    model does not make, or a call whose copies differ is a problem."""
    by_call, problems = defaultdict(set), []
    for call, order in squared_operand_orders(disassembly, lambda path, n: (path.name, n) in lines, source):
        text = source(call[0]) if call is not None else ()
        name = squared_call_of_line(text[call[1] - 1]) if call is not None and 0 < call[1] <= len(text) else None
        where = f"{call[0].name}:{call[1]}" if call is not None else "a copy not inlined"
        if name is None:
            problems.append(f"squared_distance fused at {where}, which is no call of it the plugin model makes")
        elif order is None:
            problems.append(f"squared_distance fused at {where}: which square was fused could not be told")
        else:
            by_call[name].add(order)
    for name, found in sorted(by_call.items()):
        if len(found) > 1:
            problems.append(f"squared_distance's call {name} fused fma(dx, dx, dy * dy) in one inlined copy and "
                            f"fma(dy, dy, dx * dx) in another")
    return {name: found.pop() for name, found in sorted(by_call.items()) if len(found) == 1}, problems


def plugin_record(assembly_text: str, disassembly) -> dict:
    """build.json's ``plugin_arithmetic`` entry from the assembly of ``navfn_planner.cpp``: the
    plugin sites (:data:`~navfn_smt.spec.arithmetic.PLUGIN_SITES`) fused, every fused line by file,
    the square fused in each call of squared_distance (from ``disassembly()``, the ``objdump -d -l
    --inlines`` text of the assembled object, which names the call each inlined copy is at; asked
    only when that site fuses), and what the model cannot express (a fused line of the plugin's
    files that is no site, or a site fused on some of its lines only, unless its value is the
    same either way).  NavFn's own lines (navfn.cpp) are its arithmetic's, found apart."""
    found, problems = defaultdict(set), []
    source = functools.lru_cache(maxsize=None)(_source_lines)  # each file read once per record
    lines = fused_lines_by_file(assembly_text)
    for (path, n), _ in sorted(lines.items(), key=lambda kv: (str(kv[0][0]), kv[0][1])):
        if path.name == "navfn.cpp":
            continue
        text = source(path)
        line = text[n - 1] if 0 < n <= len(text) else ""
        site = plugin_site_of_line(path.name, line)
        if site is None:
            problems.append(f"{path.name}:{n} fused `{line.strip() or '?'}`, which is no multiply-add site of the "
                            f"plugin model")
        else:
            found[site].add((path, n))
    fused = _whole_sites(found, source, plugin_site_of_line, lambda site: PLUGIN_SITES[site][3], problems)
    orders = {}
    if "squared_distance" in fused:  # which square each call's inlined copies fused
        orders, why = _orders_by_call(disassembly(), {(p.name, n) for p, n in found["squared_distance"]}, source)
        if why:
            fused.discard("squared_distance")
            problems += why
    return {"fused": sorted(fused), "squared_distance_orders": orders,
            "fused_instructions": sum(v for (p, _), v in lines.items() if p.name != "navfn.cpp"),
            "sites": {s: [f"{p.name}:{n}" for p, n in sorted(v, key=lambda t: t[1])] for s, v in sorted(found.items())},
            "unexpressible": problems}


def plugin_find(tc, source: Path, includes, defines, folder: Path) -> dict:
    """The plugin's arithmetic as ``tc`` builds ``navfn_planner.cpp`` (:func:`plugin_record`)."""
    text = assembly(tc, source, includes, defines, folder)
    return plugin_record(text, lambda: disassemble(tc, folder / (source.stem + ".s")))


def disassemble(tc, asm: Path) -> str:
    """``objdump -d -l --inlines`` of the assembly ``asm`` assembled by ``tc``'s compiler."""
    obj = asm.with_suffix(".o")
    r = subprocess.run([tc.cxx, *tc.all_flags, "-c", str(asm), "-o", str(obj)], capture_output=True, text=True)
    if r.returncode != 0:
        raise RuntimeError(f"{asm.name} did not assemble: {r.stderr.strip()[:300]}")
    return objdump(tc.objdump(), obj, "--inlines")


def plugin_of_build(doc: dict):
    """The :class:`PluginArithmetic` a plugin build records, or None with why."""
    navfn, why = of_build(doc)
    if navfn is None:
        return None, why
    entry = doc.get("plugin_arithmetic")
    if entry is None:
        return None, "this build does not record its plugin's arithmetic (built before navfn-smt found it): build it again"
    if entry.get("unexpressible"):
        return None, "the plugin model cannot express this build's arithmetic: " + "; ".join(entry["unexpressible"])
    orders = entry.get("squared_distance_orders") or {}
    if not isinstance(orders, dict):  # by copy (older builds): unexpressible above unless every copy's was dx
        orders = {}
    return PluginArithmetic(navfn, frozenset(entry["fused"]),
                            frozenset(c for c, o in orders.items() if o == "dy")), None


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


def _run_probe(tc, runner, folder: Path, name: str, count: int, payload: bytes, fmt_out: str, timeout: float) -> list:
    """``oracle/{name}_probe.cpp`` built in ``folder`` by the toolchain ``tc`` and run by ``runner``
    on ``count`` (an int32) then ``payload``; its ``count`` answers, each packed as ``fmt_out``."""
    exe = folder / f"{name}-probe"
    r = subprocess.run([tc.cxx, *tc.all_flags, str(HERE / f"{name}_probe.cpp"), "-o", str(exe)],
                       capture_output=True, text=True)
    if r.returncode != 0:
        raise RuntimeError(f"the {name} probe did not compile: {r.stderr.strip()[:300]}")
    r = subprocess.run([*runner, str(exe)], input=struct.pack("<i", count) + payload, capture_output=True,
                       timeout=timeout)
    if r.returncode != 0 or len(r.stdout) != struct.calcsize(f"<{count}{fmt_out}"):
        raise RuntimeError(f"the {name} probe failed (exit {r.returncode})")
    return list(struct.unpack(f"<{count}{fmt_out}", r.stdout))


def probe_conversion(tc, runner, folder: Path) -> list:
    """``static_cast<int>`` of :data:`PROBE_INPUTS` as the toolchain ``tc`` compiles it, run by
    ``runner``; the probe is built in ``folder``."""
    n = len(PROBE_INPUTS)
    return _run_probe(tc, runner, folder, "conversion", n, struct.pack(f"<{n}f", *PROBE_INPUTS), "i", 120)


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


def layers_record(disassembly: str, unmap=Path) -> dict:
    """build.json's ``layers_arithmetic`` entry from ``objdump -d -l`` of the costmap layers
    program (built with ``-g1`` or more): the modelled sites of
    :data:`~navfn_smt.spec.arithmetic.LAYER_SITES` fused, the other sites fused with why their
    value cannot change the result, which product each of distanceToLine's sums fused (a
    multiplicand followed back to the line that assigns ``A``, ``B``, ``C`` or ``D``), and what
    the model cannot express (a fused line that is no site or has no line, a modelled site fused
    on some of its lines only, a product that cannot be told).  A fused instruction of a
    compiler's intrinsics header (``fmaintrin.h``) is one the code asks for, not a contraction:
    Eigen's AVX square root, which the ``eigen-sqrt`` program measures; it is counted apart."""
    source = functools.lru_cache(maxsize=None)(lambda path: _source_lines(unmap(path)))
    found, problems, body, products, count, explicit = defaultdict(set), [], [], defaultdict(set), 0, 0
    for where, _, text in located_binary(disassembly):
        body.append((where, text.strip()))
        if not FMA.match(" " + text):
            continue
        count += 1
        if where[0] is None:
            problems.append("a fused multiply-add without a source line (build with -g)")
            continue
        if where[0].name.endswith("intrin.h"):  # an fma the code asks for (Eigen's AVX square root, which
            explicit += 1                       # the eigen-sqrt program measures), not a contraction
            continue
        lines = source(where[0])
        line = lines[where[1] - 1] if 0 < where[1] <= len(lines) else ""
        site = layer_site_of_line(where[0].name, line)
        if site is None:
            problems.append(f"{where[0].name}:{where[1]} fused `{line.strip() or '?'}`, which is no multiply-add "
                            f"site of the layers model")
            continue
        found[site].add(where)
        for name, product in LAYER_ORDERS.items():
            if site == "distance_to_line" and re.search(rf"\b{name}\s*=", line):
                products[name].add(product.get(_order(body, source, tuple(product), square=False)))
    fused = _whole_sites(found, source, layer_site_of_line, lambda site: LAYER_SITES[site][3] is not None, problems)
    orders = {}
    if "distance_to_line" in fused:
        for name in LAYER_ORDERS:
            if len(products[name]) != 1 or None in products[name]:
                problems.append(f"distanceToLine's {name}: which product was fused could not be told")
            else:
                orders[name] = next(iter(products[name]))
    return {"fused": sorted(s for s in fused if LAYER_SITES[s][3] is None), "orders": orders,
            "harmless": {s: LAYER_SITES[s][3] for s in sorted(fused) if LAYER_SITES[s][3] is not None},
            "fused_instructions": count, "intrinsics": explicit,
            "sites": {s: [f"{p.name}:{n}" for p, n in sorted(v, key=lambda t: t[1])] for s, v in sorted(found.items())},
            "unexpressible": list(dict.fromkeys(problems))}


def layers_find(tc, program: Path, runner, folder: Path, unmap=Path) -> dict:
    """The costmap layers' arithmetic in the program ``program`` (built with ``-g1`` or more) as ``tc``
    built it (:func:`layers_record`; ``unmap``: the file a path of its debug information names),
    and the kernel of its libm's ``hypot`` (:func:`probe_hypot`)."""
    doc = layers_record(objdump(tc.objdump(), program), unmap)
    pairs = probe_inputs()
    kernel, misses = kernel_of(pairs, probe_hypot(tc, runner, folder, pairs))
    if kernel is None:
        doc["unexpressible"].append(f"the C library's hypot is neither of glibc's kernels ({', '.join(HYPOTS)}): "
                                    f"they differ from it on {misses} of {len(pairs)} probe pairs")
    return {**doc, "hypot": kernel, "hypot_probe": {"pairs": len(pairs), "differing": misses}}


def probe_hypot(tc, runner, folder: Path, pairs) -> list:
    """``std::hypot`` of each pair of ``pairs`` as the toolchain ``tc`` links it, run by
    ``runner`` (under qemu, the target's own C library); the probe is built in ``folder``."""
    payload = struct.pack(f"<{2 * len(pairs)}d", *(v for pair in pairs for v in pair))
    return _run_probe(tc, runner, folder, "libm", len(pairs), payload, "d", 300)


def objdump(tool: str, path: Path, *options) -> str:
    """``tool -d -l`` of ``path``: its machine code with the source line of each instruction
    (``options``: more of objdump's); a RuntimeError naming what is missing or wrong."""
    if shutil.which(tool) is None:
        raise RuntimeError(f"{tool} is needed to read the machine code of {path.name} (Debian: binutils for its "
                           f"target, e.g. binutils-aarch64-linux-gnu)")
    r = subprocess.run([tool, "-d", "-l", "--no-show-raw-insn", *options, str(path)], capture_output=True, text=True)
    if r.returncode != 0:
        raise RuntimeError(f"{tool} could not read {path.name}: {r.stderr.strip()[:300]}")
    return r.stdout


def layers_of_build(doc: dict):
    """The :class:`LayersArithmetic` a layers build records, or None with why."""
    entry = doc.get("layers_arithmetic")
    if entry is None:
        navfn, _ = of_build(doc)
        if navfn == X86_64 and not doc.get("runner") and host_hypot() == LAYERS_X86_64.hypot:
            return LAYERS_X86_64, None  # built before the layers' arithmetic was found: x86-64's fuses nothing
        return None, "this build does not record its layers' arithmetic (built before navfn-smt found it): build it again"
    if entry.get("unexpressible"):
        return None, "the layers model cannot express this build's arithmetic: " + "; ".join(entry["unexpressible"])
    hypot = entry.get("hypot")
    if hypot is None:
        if doc.get("runner"):
            return None, ("this build does not record its C library's hypot (built before navfn-smt found it): "
                          "build it again")
        hypot = host_hypot()  # built before: a native program calls this machine's libm
        if hypot is None:
            return None, "this machine's C library's hypot is neither of glibc's kernels: the model cannot express it"
    return LayersArithmetic(frozenset(entry["fused"]), hypot=hypot, **entry.get("orders", {})), None


@functools.lru_cache(maxsize=None)
def host_hypot():
    """The kernel of this machine's libm ``hypot`` (through ctypes), or None when neither."""
    pairs = probe_inputs()
    return kernel_of(pairs, [c_hypot(x, y) for x, y in pairs])[0]
