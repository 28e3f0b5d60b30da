"""A corpus of malformed inputs for every command and loader, run through the real command line.

Each :class:`FuzzCase` builds its input files in a fresh directory and names the command line
that reads them.  :func:`run_corpus` runs every case as ``python -m navfn_smt ...`` in a
subprocess, one at a time, with a time limit, and classifies what happened:

``ok``          non-zero exit, one stderr line ``navfn-smt: error: ...``, no traceback
``usage``       non-zero exit from argparse (its usage line and one error line), no traceback
``refused-1``   exit 1 with a one-line diagnosis of a planning failure (a valid outcome)
``crash``       a traceback, or more than one line of error output
``hang``        the time limit was reached
``accepted``    exit 0: the input was not refused

``python tests/fuzz_corpus.py [--out docs/fuzz-table.md] [--only SUBSTRING] [--timeout S]`` writes
the table (docs/fuzz-table.md).  :func:`corpus` is also what ``tests/test_fuzz.py`` runs a fast
subset of, in process.
"""

from __future__ import annotations

import argparse
import io
import os
import shutil
import struct
import subprocess
import sys
import tempfile
import time
import zlib
from dataclasses import dataclass, field
from pathlib import Path
from typing import Callable, Optional

import numpy as np

import navfn_smt

PACKAGE = Path(navfn_smt.__file__).resolve().parent  # the package's example files are the inputs to corrupt
EXAMPLES = PACKAGE / "examples"
TEMPLATE_MAP = EXAMPLES / "suite" / "free" / "3x3_free"  # 5x5 cells, 81 cases, both goldens
ROOM_PGM = EXAMPLES / "mapserver" / "room.pgm"
NAV2_PARAMS = EXAMPLES / "nav2" / "nav2_params.yaml"
MAP_YAML = ("image: m.pgm\nresolution: 0.1\norigin: [0.0, 0.0, 0.0]\nnegate: 0\n"
            "occupied_thresh: 0.65\nfree_thresh: 0.196\n")


@dataclass
class FuzzCase:
    name: str  # what is malformed
    loader: str  # the loader or command group it targets
    argv: list  # the command line after ``navfn-smt``, run in the case's directory
    build: Callable[[Path], None] = lambda d: None
    fast: bool = False  # in the in-process subset of tests/test_fuzz.py
    allow: tuple = ()  # outcomes besides ok/usage that are correct for this input


@dataclass
class Outcome:
    case: FuzzCase
    code: Optional[int]
    stderr: str
    seconds: float
    verdict: str = field(default="")


# ------------------------------------------------------------------------ file builders
def _w(path: Path, data) -> None:
    path.parent.mkdir(parents=True, exist_ok=True)
    if isinstance(data, str):
        data = data.encode()
    path.write_bytes(data)


def _suite(d: Path, mutate: Optional[Callable[[Path], None]] = None) -> Path:
    """``d/s``: a suite with one copy of the 5x5 example map (``s/free/m``), then ``mutate(map dir)``."""
    m = d / "s" / "free" / "m"
    shutil.copytree(TEMPLATE_MAP, m)
    if mutate:
        mutate(m)
    return m


def _test_txt(text) -> Callable[[Path], None]:
    return lambda m: _w(m / "test.txt", text)


def _map_bytes(fn: Callable[[bytes], bytes]) -> Callable[[Path], None]:
    def mut(m: Path) -> None:
        f = m / "3x3_free.bin"
        f.write_bytes(fn(f.read_bytes()))
    return mut


def _golden(fn: Callable[[dict], dict], mode: str = "astar") -> Callable[[Path], None]:
    def mut(m: Path) -> None:
        f = m / f"golden_{mode}.npz"
        with np.load(f) as z:
            g = {k: z[k] for k in z.files}
        buf = io.BytesIO()
        np.savez(buf, **fn(g))
        f.write_bytes(buf.getvalue())
    return mut


def _golden_bytes(fn: Callable[[bytes], bytes], mode: str = "astar") -> Callable[[Path], None]:
    def mut(m: Path) -> None:
        f = m / f"golden_{mode}.npz"
        f.write_bytes(fn(f.read_bytes()))
    return mut


def _replace(g: dict, **kw) -> dict:
    return {**g, **kw}


def _drop(g: dict, *keys) -> dict:
    return {k: v for k, v in g.items() if k not in keys}


def _pgm(w: int, h: int, maxval: int = 255, data: Optional[bytes] = None) -> bytes:
    if data is None:
        data = bytes([254]) * (w * h * (2 if maxval > 255 else 1))
    return f"P5\n{w} {h}\n{maxval}\n".encode() + data


def _png_chunk(kind: bytes, data: bytes) -> bytes:
    return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)


def _png_header_only(w: int, h: int) -> bytes:
    """A PNG whose IHDR claims w x h 8-bit grey pixels, with a tiny (wrong) IDAT."""
    ihdr = struct.pack(">IIBBBBB", w, h, 8, 0, 0, 0, 0)
    return (b"\x89PNG\r\n\x1a\n" + _png_chunk(b"IHDR", ihdr) + _png_chunk(b"IDAT", zlib.compress(b"\0" * 16))
            + _png_chunk(b"IEND", b""))


def _pil_image(mode: str, size=(5, 5), fmt: str = "PNG", value=200) -> bytes:
    from PIL import Image

    im = Image.new(mode, size, value)
    if mode == "P":
        im.putpalette([i % 256 for i in range(768)])
    buf = io.BytesIO()
    im.save(buf, format=fmt)
    return buf.getvalue()


def _mapserver(d: Path, yaml_text: str = MAP_YAML, image: Optional[bytes] = None, image_name: str = "m.pgm") -> None:
    _w(d / "m.yaml", yaml_text)
    if image is not None:
        _w(d / image_name, image)


def _yaml_map(yaml_text: str, image: Optional[bytes] = None, image_name: str = "m.pgm"):
    if image is None:
        image = _pgm(5, 5)
    return lambda d: _mapserver(d, yaml_text, image, image_name)


def _image_map(image: bytes, image_name: str = "m.pgm", yaml_text: Optional[str] = None):
    text = yaml_text or MAP_YAML.replace("m.pgm", image_name)
    return lambda d: _mapserver(d, text, image, image_name)


def _npy(arr: np.ndarray) -> bytes:
    buf = io.BytesIO()
    np.save(buf, arr, allow_pickle=False)
    return buf.getvalue()


def _npy_header_claiming(shape, dtype="|u1") -> bytes:
    """A .npy header claiming ``shape`` with almost no data behind it."""
    header = repr({"descr": dtype, "fortran_order": False, "shape": tuple(shape)}).encode()
    header += b" " * (63 - (len(header) + 10) % 64) + b"\n"
    return b"\x93NUMPY\x01\x00" + struct.pack("<H", len(header)) + header + b"\0" * 64


def _with_map(extra: Callable[[Path], None]):
    """A good map_server map plus ``extra`` (params or goals files)."""
    def build(d: Path) -> None:
        _mapserver(d, MAP_YAML.replace("m.pgm", "room.pgm"), ROOM_PGM.read_bytes(), "room.pgm")
        extra(d)
    return build


def _file(name: str, data) -> Callable[[Path], None]:
    return lambda d: _w(d / name, data)


def _params(text: str):
    return _with_map(_file("p.yaml", text))


def _goals(name: str, data):
    return _with_map(_file(name, data))


def _symlink_loop(name: str) -> Callable[[Path], None]:
    def build(d: Path) -> None:
        os.symlink(name + ".b", d / name)
        os.symlink(name, d / (name + ".b"))
    return build


def _unreadable(name: str, data) -> Callable[[Path], None]:
    def build(d: Path) -> None:
        _w(d / name, data)
        os.chmod(d / name, 0)
    return build


PLANNER = "planner_server:\n  ros__parameters:\n    planner_plugins: [GridBased]\n    GridBased:\n"
NAVFN = "      plugin: nav2_navfn_planner::NavfnPlanner\n"
COSTMAP = "global_costmap:\n  global_costmap:\n    ros__parameters:\n"
WORLD = ["plan", "m.yaml", "--world", "--start", "0.5", "0.5", "--goal", "3.5", "3.5"]
WORLD_P = ["plan", "m.yaml", "--world", "--params", "p.yaml", "--start", "0.5", "0.5", "--goal", "3.5", "3.5"]
DIAG = ["diagnose", "m.yaml", "--start", "0.5", "0.5", "--goals", "g.txt", "--quiet", "--no-what-ifs"]


# ----------------------------------------------------------------------------- the corpus
def corpus() -> list[FuzzCase]:
    """Every malformed input with the command that reads it (more than a hundred)."""
    C: list[FuzzCase] = []

    def add(name, loader, argv, build=lambda d: None, fast=False, allow=()):
        C.append(FuzzCase(name, loader, list(argv), build, fast, tuple(allow)))

    # --- suite map directories, through each command that reads suites -----------------
    suite_muts = [
        ("map bytes truncated", _map_bytes(lambda b: b[:-3]), True),
        ("map bytes one too many", _map_bytes(lambda b: b + b"\0"), False),
        ("map file empty", _map_bytes(lambda b: b""), True),
        ("map file missing", lambda m: (m / "3x3_free.bin").unlink(), False),
        ("map file is a directory", lambda m: ((m / "3x3_free.bin").unlink(), (m / "3x3_free.bin").mkdir()), True),
        ("map file a symlink loop", lambda m: ((m / "3x3_free.bin").unlink(),
                                               os.symlink("3x3_free.bin", m / "3x3_free.bin")), True),
        ("map file chmod 000 (root reads it anyway)", lambda m: os.chmod(m / "3x3_free.bin", 0), False),
        ("test.txt empty", _test_txt(""), True),
        ("test.txt size line only", _test_txt("5 5\n"), False),
        ("test.txt size not numbers", _test_txt("five 5\n3x3_free.bin\n"), True),
        ("test.txt three numbers on the size line", _test_txt("5 5 5\n3x3_free.bin\n"), False),
        ("test.txt negative size", _test_txt("-5 5\n3x3_free.bin\n"), False),
        ("test.txt size below 3x3", _test_txt("2 2\n3x3_free.bin\n"), False),
        ("test.txt claims 100000x100000", _test_txt("100000 100000\n3x3_free.bin\n\n1 1 2 2\n"), True),
        ("test.txt size 1e3 (float)", _test_txt("1e3 5\n3x3_free.bin\n"), False),
        ("test.txt size a 40-digit number", _test_txt("9" * 40 + " 5\n3x3_free.bin\n"), False),
        ("test.txt map name with a path", _test_txt("5 5\n../x.bin\n"), False),
        ("test.txt map name empty", _test_txt("5 5\n\n"), False),
        ("test.txt case of 3 numbers", _test_txt("5 5\n3x3_free.bin\n\n1 1 2\n"), True),
        ("test.txt case with a float", _test_txt("5 5\n3x3_free.bin\n\n1 1 2.5 2\n"), False),
        ("test.txt case off the map", _test_txt("5 5\n3x3_free.bin\n\n1 1 9 2\n"), True),
        ("test.txt case negative", _test_txt("5 5\n3x3_free.bin\n\n-2 1 2 2\n"), False),
        ("test.txt non-ASCII bytes", _test_txt(b"5 5\n3x3_free.bin\n\n1 1 \xff\xfe 2\n"), True),
        ("test.txt NUL bytes", _test_txt(b"5 5\n3x3_free.bin\n\n1 1\x00 2 2\n"), False),
        ("test.txt is a directory", lambda m: ((m / "test.txt").unlink(), (m / "test.txt").mkdir()), False),
        ("test.txt a symlink loop", lambda m: ((m / "test.txt").unlink(), os.symlink("test.txt", m / "test.txt")),
         False),
        ("golden file missing", lambda m: (m / "golden_astar.npz").unlink(), False),
        ("golden file random bytes", _golden_bytes(lambda b: os.urandom(200)), True),
        ("golden file truncated", _golden_bytes(lambda b: b[: len(b) // 2]), True),
        ("golden file empty", _golden_bytes(lambda b: b""), False),
        ("golden lacks path_offsets", _golden(lambda g: _drop(g, "path_offsets")), True),
        ("golden width wrong", _golden(lambda g: _replace(g, width=np.int32(9))), False),
        ("golden width an array", _golden(lambda g: _replace(g, width=np.array([5, 5]))), True),
        ("golden width a string", _golden(lambda g: _replace(g, width=np.array("five"))), False),
        ("golden path_offsets too short", _golden(lambda g: _replace(g, path_offsets=g["path_offsets"][:3])), True),
        ("golden path_offsets out of range", _golden(lambda g: _replace(g, path_offsets=g["path_offsets"] * 1000)),
         False),
        ("golden path wrong shape", _golden(lambda g: _replace(g, path=g["path"].ravel())), True),
        ("golden sha256 wrong shape", _golden(lambda g: _replace(g, potential_sha256=g["potential_sha256"][:, :3])),
         False),
        ("golden start_reached too short", _golden(lambda g: _replace(g, start_reached=g["start_reached"][:2])),
         False),
        ("golden full_index out of range", _golden(lambda g: _replace(g, full_index=g["full_index"] + 10**6)),
         False),
        ("golden full_potential wrong shape", _golden(lambda g: _replace(g, full_potential=g["full_potential"][:, :2])),
         True),
        ("golden full_trace_offsets short", _golden(lambda g: _replace(g, full_trace_offsets=g["full_trace_offsets"][:2])),
         False),
        ("golden cycles as strings", _golden(lambda g: _replace(g, cycles=g["cycles"].astype(str))), True),
        ("golden object array (pickle)", _golden_bytes(lambda b: _npz_with_object(b)), False),
    ]
    suite_cmds = [
        ("difftest", lambda: ["difftest", "s", "--quiet", "--mode", "astar"]),
        ("plan", lambda: ["plan", "s/free/m", "--start", "1", "1", "--goal", "2", "2"]),
        ("render", lambda: ["render", "s/free/m", "-o", "out.png"]),
        ("suite record", lambda: ["suite", "record", "s", "--mode", "astar", "--overwrite", "--quiet"]),
        ("metamorphic", lambda: ["metamorphic", "s", "--mode", "astar", "--max-cases", "2"]),
        ("coverage", lambda: ["coverage", "s", "--mode", "astar", "--max-cases", "2"]),
        ("bench", lambda: ["bench", "s", "--backend", "reference", "--mode", "astar"]),
        ("search --summary", lambda: ["search", "--summary", "s", "--mode", "astar"]),
    ]
    golden_readers = {"difftest"}  # commands that read the golden files
    for i, (name, mut, fast) in enumerate(suite_muts):
        is_golden = name.startswith("golden")
        if is_golden:
            cmds = [c for c in suite_cmds if c[0] in golden_readers]
        else:  # every test.txt / map bytes problem through difftest, and one other command in turn
            others = [c for c in suite_cmds if c[0] != "difftest"]
            cmds = [suite_cmds[0], others[i % len(others)]]
        for cname, argv in cmds:
            add(name, f"suite ({cname})", argv(), lambda d, mut=mut: _suite(d, mut), fast=fast and cname == "difftest",
                allow=("accepted", "refused-1") if "chmod" in name else ())
    for cname, argv in suite_cmds:
        if cname in ("plan", "render"):
            continue
        add("suite directory does not exist", f"suite ({cname})", argv())
        add("suite is a file", f"suite ({cname})", argv(), _file("s", b"not a dir"), fast=cname == "difftest")
    add("suite without any test.txt", "suite (difftest)", ["difftest", "s", "--quiet"], lambda d: (d / "s").mkdir(),
        fast=True)
    add("suite with a directory symlink loop", "suite (difftest)", ["difftest", "s", "--quiet"],
        lambda d: (_suite(d), os.symlink("..", d / "s" / "free" / "m" / "loop")), allow=("refused-1", "accepted"))
    add("plan on a raw map file without --size", "plan", ["plan", "raw.bin", "--start", "1", "1", "--goal", "2", "2"],
        _file("raw.bin", b"\0" * 25))
    add("plan on a raw map with --size 100000 100000", "plan",
        ["plan", "raw.bin", "--size", "100000", "100000", "--start", "1", "1", "--goal", "2", "2"],
        _file("raw.bin", b"\0" * 25), fast=True)
    add("plan start off the map", "plan", ["plan", "s/free/m", "--start", "7", "1", "--goal", "2", "2"], _suite,
        fast=True)
    add("plan goal negative", "plan", ["plan", "s/free/m", "--start", "1", "1", "--goal", "-1", "2"], _suite)
    add("plan start not an integer cell", "plan", ["plan", "s/free/m", "--start", "1.5", "1", "--goal", "2", "2"],
        _suite)
    add("plan start NaN", "plan", ["plan", "s/free/m", "--start", "nan", "1", "--goal", "2", "2"], _suite, fast=True)
    add("plan start 1e300", "plan", ["plan", "s/free/m", "--start", "1e300", "1", "--goal", "2", "2"], _suite)
    add("render --case out of range", "render", ["render", "s/free/m", "--case", "100000", "-o", "o.png"], _suite)
    add("render --case negative", "render", ["render", "s/free/m", "--case", "-1", "-o", "o.png"], _suite)
    add("render start off the map", "render", ["render", "s/free/m", "--start", "9", "9", "--goal", "1", "1",
                                               "-o", "o.png"], _suite, fast=True)
    add("render output format unknown", "render", ["render", "s/free/m", "-o", "o.txt"], _suite)
    add("render output into a missing directory", "render", ["render", "s/free/m", "-o", "no/o.png"], _suite)

    # --- map_server YAML and images -----------------------------------------------------
    yaml_cases = [
        ("YAML syntax error", "image: [m.pgm\nresolution: 0.1\n", True),
        ("YAML tab indentation", "image: m.pgm\n\tresolution: 0.1\n", False),
        ("YAML empty file", "", True),
        ("YAML a list", "- 1\n- 2\n", False),
        ("YAML a scalar", "42\n", False),
        ("YAML missing resolution", MAP_YAML.replace("resolution: 0.1\n", ""), True),
        ("YAML negative resolution", MAP_YAML.replace("0.1", "-0.1"), True),
        ("YAML zero resolution", MAP_YAML.replace("0.1", "0"), False),
        ("YAML resolution a string", MAP_YAML.replace("0.1", "fine"), False),
        ("YAML resolution 1e400", MAP_YAML.replace("0.1", "1.0e400"), False),
        ("YAML resolution .nan", MAP_YAML.replace("0.1", ".nan"), False),
        ("YAML resolution below float32", MAP_YAML.replace("0.1", "1.0e-50"), False),
        ("YAML resolution a 400-digit integer", MAP_YAML.replace("0.1", "9" * 400), True),
        ("YAML origin 2 elements", MAP_YAML.replace("[0.0, 0.0, 0.0]", "[0.0, 0.0]"), False),
        ("YAML origin a string", MAP_YAML.replace("[0.0, 0.0, 0.0]", "here"), False),
        ("YAML origin .inf", MAP_YAML.replace("[0.0, 0.0, 0.0]", "[.inf, 0.0, 0.0]"), False),
        ("YAML origin huge", MAP_YAML.replace("[0.0, 0.0, 0.0]", "[1.0e300, -1.0e300, 0.0]"), True),
        ("YAML negate a word", MAP_YAML.replace("negate: 0", "negate: maybe"), False),
        ("YAML thresholds inverted", MAP_YAML.replace("0.65", "0.1"), False),
        ("YAML threshold above 1", MAP_YAML.replace("0.65", "1.5"), False),
        ("YAML unknown mode", MAP_YAML + "mode: fancy\n", False),
        ("YAML mode a number", MAP_YAML + "mode: 3\n", False),
        ("YAML image a list", MAP_YAML.replace("image: m.pgm", "image: [a, b]"), False),
        ("YAML image empty", MAP_YAML.replace("image: m.pgm", "image: ''"), False),
        ("YAML image outside its folder", MAP_YAML.replace("m.pgm", "../../etc/passwd"), False),
        ("YAML image missing", MAP_YAML.replace("m.pgm", "nothere.pgm"), True),
        ("YAML image a directory", MAP_YAML.replace("m.pgm", "."), False),
        ("YAML nested 10000 deep", "a: " + "[" * 10000 + "]" * 10000 + "\n", True),
        ("YAML billion laughs", "a: &a [x, x, x, x, x, x, x, x, x]\nb: &b [*a, *a, *a, *a, *a, *a, *a, *a, *a]\n"
         "c: &c [*b, *b, *b, *b, *b, *b, *b, *b, *b]\nd: &d [*c, *c, *c, *c, *c, *c, *c, *c, *c]\n"
         "origin: [*d, *d, *d]\n" + MAP_YAML.replace("origin: [0.0, 0.0, 0.0]\n", ""), False),
        ("YAML non-UTF-8 bytes", MAP_YAML.replace("m.pgm", "m\udcff.pgm"), True),
        ("YAML python tag", "!!python/object/apply:os.system ['true']\n", False),
        ("YAML duplicate keys", MAP_YAML + "resolution: -1.0\n", False),
    ]
    for i, (name, text, fast) in enumerate(yaml_cases):
        data = text.encode("utf-8", "surrogateescape")
        cmd = (["plan", "m.yaml", "--start", "1", "1", "--goal", "2", "2"] if i % 3 == 0 else
               WORLD if i % 3 == 1 else ["render", "m.yaml", "--start", "1", "1", "--goal", "2", "2", "-o", "o.png"])
        add(name, f"map_server YAML ({cmd[0]})", cmd, _yaml_map(data), fast=fast,
            allow=("refused-1",) if name == "YAML origin huge" else ())
    add("YAML file is a directory", "map_server YAML (plan)", WORLD, lambda d: (d / "m.yaml").mkdir())
    add("YAML file a symlink loop", "map_server YAML (plan)", WORLD, _symlink_loop("m.yaml"), fast=True)
    add("YAML file chmod 000 (root reads it anyway)", "map_server YAML (plan)", WORLD,
        lambda d: (_mapserver(d, MAP_YAML, _pgm(5, 5)), os.chmod(d / "m.yaml", 0)), allow=("refused-1", "accepted"))

    image_cases = [
        ("PGM truncated pixels", _pgm(5, 5, data=b"\xfe" * 7), "m.pgm", True),
        ("PGM zero-size file", b"", "m.pgm", True),
        ("PGM header only", b"P5\n5 5\n255\n", "m.pgm", False),
        ("PGM claims 100000x100000", _pgm(100000, 100000, data=b"\0" * 100), "m.pgm", True),
        ("PGM claims 20000x20000 (400 M pixels)", _pgm(20000, 20000, data=b"\0" * 100), "m.pgm", False),
        ("PGM 0x0", _pgm(0, 0, data=b""), "m.pgm", False),
        ("PGM 2x2 (below 3x3)", _pgm(2, 2), "m.pgm", False),
        ("PGM maxval 0", _pgm(5, 5, maxval=0), "m.pgm", False),
        ("PGM maxval 70000", _pgm(5, 5, maxval=70000), "m.pgm", False),
        ("PGM 16-bit (maxval 65535)", _pgm(5, 5, maxval=65535), "m.pgm", False),
        ("PGM negative width", b"P5\n-5 5\n255\n" + b"\0" * 25, "m.pgm", False),
        ("PGM garbage after magic", b"P5\nxx yy\n255\n" + b"\0" * 25, "m.pgm", False),
        ("text file named .pgm", b"hello, this is not an image\n", "m.pgm", True),
        ("PNG claims 100000x100000 (header only)", _png_header_only(100000, 100000), "m.png", True),
        ("PNG truncated", _pil_image("L")[:40], "m.png", False),
        ("PNG palette", _pil_image("P"), "m.png", False),
        ("PNG 16-bit grey", _pil_image("I;16", value=60000), "m.png", False),
        ("PNG RGBA", _pil_image("RGBA", value=(10, 20, 30, 100)), "m.png", False),
        ("PNG 1x1000 (a line)", _pil_image("L", size=(1, 1000)), "m.png", False),
        ("GIF", _pil_image("P", fmt="GIF"), "m.gif", False),
        ("TIFF float", _pil_image("F", fmt="TIFF", value=0.5), "m.tif", False),
        ("JPEG named .png", _pil_image("L", fmt="JPEG"), "m.png", False),
    ]
    for i, (name, data, iname, fast) in enumerate(image_cases):
        cmd = WORLD if i % 2 == 0 else ["plan", "m.yaml", "--start", "1", "1", "--goal", "2", "2"]
        add(name, f"map_server image ({cmd[0]}{' --world' if cmd is WORLD else ''})", cmd, _image_map(data, iname),
            fast=fast, allow=("refused-1", "accepted") if name in (
                "PNG palette", "PNG 16-bit grey", "PNG RGBA", "GIF", "TIFF float", "JPEG named .png",
                "PGM 16-bit (maxval 65535)", "PGM maxval 70000") else ())
    add("image a symlink loop", "map_server image (plan --world)", WORLD,
        lambda d: (_w(d / "m.yaml", MAP_YAML), _symlink_loop("m.pgm")(d)))

    # --- costmap files (.npy, .pgm) -------------------------------------------------------
    def npy_case(name, data, fast=False, extra=(), allow=()):
        add(name, "costmap .npy (plan --world)", ["plan", "c.npy", "--world", "--resolution", "0.1",
                                                  "--start", "0.15", "0.15", "--goal", "0.35", "0.35", *extra],
            _file("c.npy", data), fast=fast, allow=allow)

    npy_case("npy of NaN costs", _npy(np.full((5, 5), np.nan)), True)
    npy_case("npy of inf costs", _npy(np.full((5, 5), np.inf)))
    npy_case("npy of negative ints", _npy(np.full((5, 5), -3, np.int16)))
    npy_case("npy of ints above 255", _npy(np.full((5, 5), 300, np.int32)))
    npy_case("npy 3-D", _npy(np.zeros((2, 5, 5), np.uint8)))
    npy_case("npy empty", _npy(np.zeros((0, 5), np.uint8)))
    npy_case("npy 2x2", _npy(np.zeros((2, 2), np.uint8)))
    npy_case("npy header claims 100000x100000", _npy_header_claiming((100000, 100000)), True)
    npy_case("npy header claims (10**12, 10**12)", _npy_header_claiming((10**12, 10**12)))
    npy_case("npy header claims a negative shape", _npy_header_claiming((-5, 5)))
    npy_case("npy truncated", _npy(np.zeros((50, 50), np.uint8))[:200], True)
    npy_case("npy random bytes", os.urandom(300))
    npy_case("npy object dtype (pickle)", _npy_object())
    npy_case("npz named .npy", _npz_plain(), True)
    npy_case("npy of bools", _npy(np.ones((5, 5), bool)))
    npy_case("npy of strings", _npy(np.full((5, 5), "x")))
    npy_case("npy structured dtype", _npy(np.zeros((5, 5), dtype=[("a", "u1"), ("b", "u1")])))
    npy_case("npy fine, --resolution negative", _npy(np.zeros((5, 5), np.uint8)), extra=())
    C[-1].argv[C[-1].argv.index("0.1")] = "-0.1"
    npy_case("npy fine, --resolution nan", _npy(np.zeros((5, 5), np.uint8)))
    C[-1].argv[C[-1].argv.index("0.1")] = "nan"
    npy_case("npy fine, start off the map", _npy(np.zeros((5, 5), np.uint8)), allow=("refused-1",))
    C[-1].argv[C[-1].argv.index("0.15")] = "-40"
    add("npy without --resolution", "costmap .npy (plan --world)",
        ["plan", "c.npy", "--world", "--start", "0.15", "0.15", "--goal", "0.35", "0.35"],
        _file("c.npy", _npy(np.zeros((5, 5), np.uint8))))
    add("costmap .pgm in colour", "costmap .pgm (diagnose)",
        ["diagnose", "c.pgm", "--resolution", "0.1", "--start", "0.15", "0.15", "--goal", "0.35", "0.35"],
        _file("c.pgm", _pil_image("RGB", fmt="PPM", value=(1, 2, 3))))
    add("costmap .pgm claims 100000x100000", "costmap .pgm (diagnose)",
        ["diagnose", "c.pgm", "--resolution", "0.1", "--start", "0.15", "0.15", "--goal", "0.35", "0.35"],
        _file("c.pgm", _pgm(100000, 100000, data=b"\0" * 64)), fast=True)

    # --- Nav2 params files ------------------------------------------------------------------
    params_cases = [
        ("params YAML syntax error", "planner_server: [\n", True),
        ("params a list", "- a\n", False),
        ("params non-UTF-8", b"planner_server:\n  ros__parameters: \xff\xfe\n", True),
        ("params no ros__parameters", "planner_server:\n  x: 1\n", False),
        ("params planner_plugins not a list", "planner_server:\n  ros__parameters:\n    planner_plugins: 5\n", False),
        ("params unknown planner plugin type", PLANNER + "      plugin: my::Planner\n", True),
        ("params tolerance an int", PLANNER + NAVFN + "      tolerance: 1\n", False),
        ("params tolerance .inf", PLANNER + NAVFN + "      tolerance: .inf\n", True),
        ("params tolerance negative", PLANNER + NAVFN + "      tolerance: -1.0\n", False),
        ("params tolerance 1e300", PLANNER + NAVFN + "      tolerance: 1.0e300\n", False),
        ("params use_astar a string", PLANNER + NAVFN + "      use_astar: 'yes'\n", False),
        ("params max_cycles_factor 10**30", PLANNER + NAVFN + "      max_cycles_factor: " + "1" + "0" * 30 + "\n", True),
        ("params max_cycles_factor negative", PLANNER + NAVFN + "      max_cycles_factor: -4\n", False),
        ("params plugin section a string", "planner_server:\n  ros__parameters:\n    GridBased: use_astar\n", True),
        ("params plugin section a list", "planner_server:\n  ros__parameters:\n    GridBased: [tolerance]\n", False),
        ("costmap plugins not a list", COSTMAP + "      plugins: static_layer\n", False),
        ("costmap unknown layer plugin", COSTMAP + "      plugins: [x]\n      x:\n        plugin: my::Layer\n", True),
        ("costmap layer without a type", COSTMAP + "      plugins: [x]\n", False),
        ("costmap footprint not a polygon", COSTMAP + "      footprint: '[[1.0, 2.0]]'\n", True),
        ("costmap footprint garbage", COSTMAP + "      footprint: '[[a, b], [c'\n", False),
        ("costmap footprint huge numbers", COSTMAP + "      footprint: '[[1e39, 0], [0, 1e39], [-1e39, 0]]'\n", False),
        ("costmap footprint a list, not a string", COSTMAP + "      footprint: [[1.0, 0.0], [0.0, 1.0]]\n", False),
        ("costmap robot_radius 1e6", COSTMAP + "      robot_radius: 1.0e6\n", False),
        ("costmap robot_radius negative", COSTMAP + "      robot_radius: -0.5\n", False),
        ("costmap inflation_radius 1e9", COSTMAP + "      plugins: [static_layer, inflation_layer]\n"
         "      static_layer:\n        plugin: nav2_costmap_2d::StaticLayer\n"
         "      inflation_layer:\n        plugin: nav2_costmap_2d::InflationLayer\n"
         "        inflation_radius: 1.0e9\n", True),
        ("costmap inflation_radius an int", COSTMAP + "      plugins: [static_layer, inflation_layer]\n"
         "      static_layer:\n        plugin: nav2_costmap_2d::StaticLayer\n"
         "      inflation_layer:\n        plugin: nav2_costmap_2d::InflationLayer\n"
         "        inflation_radius: 1\n", False),
        ("costmap cost_scaling_factor .nan", COSTMAP + "      plugins: [inflation_layer]\n"
         "      inflation_layer:\n        plugin: nav2_costmap_2d::InflationLayer\n"
         "        cost_scaling_factor: .nan\n", False),
        ("costmap resolution 0", COSTMAP + "      resolution: 0.0\n", False),
        ("costmap unknown_cost_value 1000", COSTMAP + "      unknown_cost_value: 1000\n", False),
        ("costmap lethal_cost_threshold 10**30", COSTMAP + "      lethal_cost_threshold: " + "9" * 30 + "\n", True),
        ("costmap ros__parameters a list", "global_costmap:\n  global_costmap:\n    ros__parameters: [1]\n", False),
    ]
    for i, (name, text, fast) in enumerate(params_cases):
        argv = WORLD_P if i % 2 == 0 else ["diagnose", "m.yaml", "--params", "p.yaml", "--start", "0.5", "0.5",
                                           "--goal", "3.5", "3.5", "--no-what-ifs"]
        add(name, f"params ({argv[0]})", argv, _params(text), fast=fast,
            allow=("refused-1", "accepted") if "tolerance" in name else
            ("refused-1",) if "max_cycles_factor negative" in name else ())
    add("params file is a directory", "params (plan)", WORLD_P, _with_map(lambda d: (d / "p.yaml").mkdir()))
    add("params file a symlink loop", "params (plan)", WORLD_P, _with_map(_symlink_loop("p.yaml")))

    # --- goals files ------------------------------------------------------------------------
    goals_cases = [
        ("goals empty", "g.txt", "", True),
        ("goals only comments", "g.txt", "# nothing\n", False),
        ("goals a word", "g.txt", "one two\n", True),
        ("goals four numbers", "g.txt", "1 2 3 4\n", False),
        ("goals NaN", "g.txt", "nan 1\n", False),
        ("goals inf", "g.txt", "inf 1\n", False),
        ("goals 1e400", "g.txt", "1e400 1\n", False),
        ("goals non-UTF-8", "g.txt", b"1 1\n\xff\xfe 2\n", True),
        ("goals JSON malformed", "g.json", "[[1, 2], [3", True),
        ("goals JSON a number", "g.json", "42", False),
        ("goals JSON of strings", "g.json", '[["a", "b"]]', False),
        ("goals JSON a 400-digit integer", "g.json", "[[" + "9" * 400 + ", 1]]", True),
        ("goals JSON nested 100000 deep", "g.json", "[" * 100000 + "]" * 100000, True),
        ("goals YAML mapping without y", "g.yaml", "- {x: 1}\n", False),
        ("goals YAML mapping x a string", "g.yaml", "- {x: a, y: 1}\n", False),
        ("goals YAML syntax error", "g.yaml", "- [1, 2\n", False),
        ("goals YAML booleans", "g.yaml", "- [true, false]\n", False),
        ("goals YAML yaw .nan", "g.yaml", "- {x: 1.0, y: 1.0, yaw: .nan}\n", False),
        ("goals off the map", "g.txt", "1000 1000\n", False),
    ]
    for name, fname, data, fast in goals_cases:
        argv = [a if a != "g.txt" else fname for a in DIAG]
        add(name, "goals (diagnose)", argv, _goals(fname, data), fast=fast,
            allow=("refused-1",) if name == "goals off the map" else ())
    add("goals file is a directory", "goals (diagnose)", DIAG, _with_map(lambda d: (d / "g.txt").mkdir()))
    add("diagnose start off the map", "diagnose", ["diagnose", "m.yaml", "--start", "-50", "0.5", "--goal", "1", "1",
                                                   "--no-what-ifs"], _with_map(lambda d: None), allow=("refused-1",))
    add("diagnose start NaN", "diagnose", ["diagnose", "m.yaml", "--start", "nan", "0.5", "--goal", "1", "1"],
        _with_map(lambda d: None), fast=True)
    add("diagnose --sweep a word", "diagnose", ["diagnose", "m.yaml", "--start", "0.5", "0.5", "--sweep", "many"],
        _with_map(lambda d: None))
    add("diagnose --sweep 0", "diagnose", ["diagnose", "m.yaml", "--start", "0.5", "0.5", "--sweep", "0"],
        _with_map(lambda d: None))
    add("diagnose --sweep -5", "diagnose", ["diagnose", "m.yaml", "--start", "0.5", "0.5", "--sweep", "-5"],
        _with_map(lambda d: None))

    # --- prove --------------------------------------------------------------------------------
    add("proof file missing", "prove", ["prove", "nothere.py"], fast=True)
    add("proof file with a syntax error", "prove", ["prove", "p.py"], _file("p.py", "def (:\n"), fast=True)
    add("proof file non-UTF-8", "prove", ["prove", "p.py"], _file("p.py", b"x = '\xff'\n"))
    add("proof file without obligations", "prove", ["prove", "p.py"], _file("p.py", "x = 1\n"))
    add("proof file raising at import", "prove", ["prove", "p.py"], _file("p.py", "raise SystemExit(0)\n"))
    add("proof file is a directory", "prove", ["prove", "p.py"], lambda d: (d / "p.py").mkdir())
    add("prove --timeout nan", "prove", ["prove", "--timeout", "nan"], fast=True)
    add("prove --timeout -1", "prove", ["prove", "--timeout", "-1"])
    add("prove --timeout inf", "prove", ["prove", "p.py", "--timeout", "inf"], _file("p.py", "x = 1\n"))
    add("prove --jobs 0", "prove", ["prove", "--jobs", "0"])
    add("prove --report into a directory", "prove", ["prove", "--report", "."])

    # --- check, search ------------------------------------------------------------------------
    add("check --size 100000 100000", "check", ["check", "valid-path", "--size", "100000", "100000"], fast=True)
    add("check --size 2 2", "check", ["check", "valid-path", "--size", "2", "2"])
    add("check --size -3 4", "check", ["check", "valid-path", "--size", "-3", "4"])
    add("check --costs garbage", "check", ["check", "valid-path", "--costs", "a..b"], fast=True)
    add("check --costs reversed", "check", ["check", "valid-path", "--costs", "200..100"])
    add("check --costs above 255", "check", ["check", "valid-path", "--costs", "0..1000"])
    add("check --timeout nan", "check", ["check", "valid-path", "--timeout", "nan"], fast=True)
    add("check --start off the map", "check", ["check", "valid-path", "--start", "9", "9"])
    add("check --budget nan", "check", ["check", "valid-path", "--max-size", "4", "4", "--budget", "nan"],
        allow=("accepted", "refused-1"))
    add("check --exhaustive nan", "check", ["check", "valid-path", "--exhaustive", "nan"])
    add("check --max-size 100000 100000", "check", ["check", "valid-path", "--max-size", "100000", "100000",
                                                    "--budget", "0.001"], allow=("accepted", "refused-1"))
    add("search --size 100000 100000", "search", ["search", "turn", "--size", "100000", "100000", "--timeout", "1"],
        fast=True)
    add("search --size 1 1", "search", ["search", "turn", "--size", "1", "1", "--timeout", "1"])
    add("search --timeout nan", "search", ["search", "turn", "--timeout", "nan"], fast=True)
    add("search --timeout 0", "search", ["search", "turn", "--timeout", "0"])
    add("search --costs 300..400", "search", ["search", "turn", "--costs", "300..400", "--timeout", "1"])
    add("search --max-size 2 2", "search", ["search", "turn", "--max-size", "2", "2", "--timeout", "1"])
    add("search --out is a file", "search", ["search", "turn", "--out", "f", "--timeout", "1"], _file("f", "x"))
    add("search without a kind", "search", ["search"])

    # --- bench, suite generate, record, metamorphic, coverage, docs ---------------------------
    add("bench --size 5", "bench", ["bench", "--size", "5"])
    add("bench --size 100000", "bench", ["bench", "--size", "100000", "--backend", "reference"], fast=True)
    add("bench --repeat 0", "bench", ["bench", "--size", "12", "--repeat", "0"])
    add("bench --worst-cases without a build", "bench", ["bench", "--worst-cases", "100"])
    add("bench --sweep 0", "bench", ["bench", "--sweep", "0"])
    add("bench --sweep 100000", "bench", ["bench", "--sweep", "100000"], fast=True)
    add("bench --sweep-astar-goals many", "bench", ["bench", "--sweep", "20", "--sweep-astar-goals", "many"])
    add("generate --size 100000 100000", "suite generate", ["suite", "generate", "o", "--category", "free",
                                                            "--size", "100000", "100000"], fast=True)
    add("generate --size 2 2", "suite generate", ["suite", "generate", "o", "--category", "free", "--size", "2", "2"])
    add("generate --count -1", "suite generate", ["suite", "generate", "o", "--category", "free", "--count", "-1"])
    add("generate --count 10**9", "suite generate", ["suite", "generate", "o", "--category", "free",
                                                     "--count", "1000000000", "--size", "5", "5"],
        allow=("hang",))  # a valid, merely long request: ten seconds of writing maps is not a failure
    C[-1].allow = ("hang", "accepted")
    add("generate unknown category", "suite generate", ["suite", "generate", "o", "--category", "nope"])
    add("generate --paths zero", "suite generate", ["suite", "generate", "o", "--category", "free", "--paths", "0"])
    add("generate into a file", "suite generate", ["suite", "generate", "o", "--category", "free"], _file("o", "x"),
        fast=True)
    add("record --full-first -1", "suite record", ["suite", "record", "s", "--full-first", "-1"], _suite)
    add("metamorphic --max-cases 0", "metamorphic", ["metamorphic", "--max-cases", "0"])
    add("metamorphic --save into a file", "metamorphic", ["metamorphic", "--save", "f"], _file("f", "x"))
    add("coverage --max-cases -1", "coverage", ["coverage", "--max-cases", "-1"])
    add("coverage --min-branch nan", "coverage", ["coverage", "s", "--min-branch", "nan", "--max-cases", "1",
                                                  "--mode", "astar"], _suite, allow=("refused-1", "accepted"))
    add("difftest --jobs 0", "difftest", ["difftest", "--jobs", "0"])
    add("difftest --json into a missing directory", "difftest", ["difftest", "--json", "no/r.json"], fast=True)
    add("docs (not built yet)", "docs", ["docs"], fast=True)
    add("no command", "cli", [])
    add("unknown command", "cli", ["frobnicate"])
    return C


def _npz_with_object(_: bytes) -> bytes:
    buf = io.BytesIO()
    with np.load(TEMPLATE_MAP / "golden_astar.npz") as z:
        g = {k: z[k] for k in z.files}
    g["path"] = np.array([{"a": 1}], dtype=object)
    np.savez(buf, **g)
    return buf.getvalue()


def _npy_object() -> bytes:
    buf = io.BytesIO()
    np.save(buf, np.array([[{"a": 1}] * 5] * 5, dtype=object), allow_pickle=True)
    return buf.getvalue()


def _npz_plain() -> bytes:
    buf = io.BytesIO()
    np.savez(buf, a=np.zeros((5, 5), np.uint8))
    return buf.getvalue()


# ----------------------------------------------------------------------------- running
def classify(code: Optional[int], stderr: str, case: Optional[FuzzCase] = None) -> str:
    lines = [ln for ln in stderr.splitlines() if ln.strip()]
    allow = case.allow if case else ()
    if code is None:
        return "hang"
    if "Traceback" in stderr:
        return "crash"
    if code == 0:
        return "accepted"
    if code == 2 and len(lines) == 1 and lines[0].startswith("navfn-smt: error: "):
        return "ok"
    if code == 2 and len(lines) == 2 and lines[0].startswith("usage: ") and ": error: " in lines[1]:
        return "usage"
    if code == 1 and len(lines) <= 1 and "refused-1" in allow:
        return "refused-1"
    if code == 130:
        return "interrupted"
    return "crash"


def passed(o: Outcome) -> bool:
    return o.verdict in ("ok", "usage") or o.verdict in o.case.allow


def run_case(case: FuzzCase, timeout: float = 10.0, workdir: Optional[Path] = None) -> Outcome:
    """Build the case's files in a fresh directory and run its command line there."""
    with tempfile.TemporaryDirectory(prefix="navfn-fuzz-", dir=workdir) as tmp:
        d = Path(tmp)
        case.build(d)
        env = {**os.environ, "PYTHONWARNINGS": "default", "COLUMNS": "100"}
        t0 = time.perf_counter()
        proc = subprocess.Popen([sys.executable, "-m", "navfn_smt", *case.argv], cwd=d, env=env,
                                stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, start_new_session=True)
        try:
            _, err = proc.communicate(timeout=timeout)
            code = proc.returncode
        except subprocess.TimeoutExpired:
            os.killpg(proc.pid, 9)
            _, err = proc.communicate()
            code = None
        seconds = time.perf_counter() - t0
        for p in d.rglob("*"):  # let the temporary directory go (chmod 000 files, loops)
            try:
                if not p.is_symlink():
                    os.chmod(p, 0o700)
            except OSError:
                pass
    text = err.decode("utf-8", "replace")
    o = Outcome(case, code, text, seconds)
    o.verdict = classify(code, text, case)
    return o


def _cell(s: str) -> str:
    return s.replace("|", "\\|").replace("\n", " ")


def table(outcomes: list[Outcome]) -> str:
    """The markdown table of every outcome, with totals per loader and verdict."""
    rows = ["| # | input | loader / command | command line | exit | first line of stderr | s | verdict |",
            "|---|---|---|---|---|---|---|---|"]
    for i, o in enumerate(outcomes, 1):
        first = next((ln for ln in o.stderr.splitlines() if ln.strip() and not ln.startswith("usage: ")), "")
        if "Traceback" in o.stderr:
            first = "Traceback: " + (o.stderr.strip().splitlines() or [""])[-1]
        rows.append(f"| {i} | {_cell(o.case.name)} | {_cell(o.case.loader)} | `{_cell(' '.join(o.case.argv))}` | "
                    f"{'timeout' if o.code is None else o.code} | {_cell(first[:160])} | {o.seconds:.1f} | "
                    f"{o.verdict}{'' if passed(o) else ' **FAIL**'} |")
    by_loader: dict = {}
    for o in outcomes:
        key = o.case.loader.split(" (")[0]
        by_loader.setdefault(key, []).append(o)
    tot = ["| loader / command | inputs | ok | usage | other accepted outcome | failures |", "|---|---|---|---|---|---|"]
    for k, os_ in sorted(by_loader.items()):
        tot.append(f"| {k} | {len(os_)} | {sum(o.verdict == 'ok' for o in os_)} | "
                   f"{sum(o.verdict == 'usage' for o in os_)} | "
                   f"{sum(passed(o) and o.verdict not in ('ok', 'usage') for o in os_)} | "
                   f"{sum(not passed(o) for o in os_)} |")
    tot.append(f"| **all** | {len(outcomes)} | {sum(o.verdict == 'ok' for o in outcomes)} | "
               f"{sum(o.verdict == 'usage' for o in outcomes)} | "
               f"{sum(passed(o) and o.verdict not in ('ok', 'usage') for o in outcomes)} | "
               f"{sum(not passed(o) for o in outcomes)} |")
    return "\n".join(tot) + "\n\n" + "\n".join(rows) + "\n"


def run_corpus(cases: list[FuzzCase], timeout: float = 10.0, progress=None) -> list[Outcome]:
    out = []
    for c in cases:
        o = run_case(c, timeout)
        out.append(o)
        if progress:
            progress(o)
    return out


HEADER = """# Fuzz table

Every malformed input of `tests/fuzz_corpus.py`'s `corpus()` run through the real command line
(`python -m navfn_smt ...` in a subprocess, one at a time, {timeout:g} s limit), as
`python tests/fuzz_corpus.py --out docs/fuzz-table.md` writes it.  Verdicts: **ok** = exit 2 and
exactly one stderr line `navfn-smt: error: ...`; **usage** = argparse's refusal of the command
line (its `usage:` line and one error line, exit 2); **refused-1** = exit 1 with a one-line
planning failure, the right answer for that input; **accepted** = exit 0 where the input is
valid after all (listed per case in the corpus); **FAIL** marks anything else (a traceback,
several lines, a hang).  See docs/hardening.md for what was fixed.

Run as root: `chmod 000` does not stop root from reading a file, so the "chmod 000" inputs
read fine and are listed as what they do.

"""


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(prog="python tests/fuzz_corpus.py", description="run the malformed-input corpus")
    ap.add_argument("--out", help="write the markdown table here (default: print it)")
    ap.add_argument("--only", help="run only cases whose name or loader contains this")
    ap.add_argument("--timeout", type=float, default=10.0)
    ap.add_argument("--log", help="append the whole stderr of every failing case to this file")
    args = ap.parse_args(argv)
    cases = [c for c in corpus() if not args.only or args.only in c.name or args.only in c.loader]

    def progress(o: Outcome) -> None:
        mark = "  " if passed(o) else "!!"
        first = next((ln for ln in o.stderr.splitlines() if ln.strip()), "")
        print(f"{mark} {o.verdict:10} {o.seconds:5.1f}s {o.case.name} [{' '.join(o.case.argv[:2])}] {first[:100]}",
              flush=True)
        if args.log and not passed(o):
            with open(args.log, "a") as f:
                f.write(f"===== {o.case.name} | {' '.join(o.case.argv)} | exit {o.code}\n{o.stderr}\n")

    outcomes = run_corpus(cases, args.timeout, progress)
    text = HEADER.format(timeout=args.timeout) + table(outcomes)
    if args.out:
        from navfn_smt.fileio import atomic_write_text

        atomic_write_text(args.out, text)
    else:
        print(text)
    bad = [o for o in outcomes if not passed(o)]
    print(f"{len(outcomes)} inputs, {len(bad)} failures", file=sys.stderr)
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
