"""The test-suite format of ``navfn-suite`` (see the suite's README.md).

A map directory holds ``test.txt`` (``W H`` / map file name / blank / one case
``sx sy gx gy`` a line; lines starting with ``-1`` are comments), the map bytes
(NavFn-internal costs, row-major) and golden files ``golden_astar.npz`` and
``golden_dijkstra.npz``.  A suite is any directory tree of map directories; a map's
category is the first directory below the suite root.
"""

from __future__ import annotations

import os
import struct
import zipfile
import zlib
from dataclasses import dataclass
from pathlib import Path
from typing import Optional

import numpy as np

from ..errors import NavfnInputError
from ..fileio import atomic_write_bytes
from ..inputs import check_cells

MODES = ("astar", "dijkstra")  # the planner modes: calcNavFnAstar, calcNavFnDijkstra
MODE_CHOICES = (*MODES, "both")  # what a command's --mode accepts


def modes_of(choice: str) -> tuple[str, ...]:
    """The planner modes a ``--mode`` choice stands for: ``both`` is every mode in ``MODES``."""
    return tuple(MODES) if choice == "both" else (choice,)
GOLDEN_FIELDS = (
    "width",
    "height",
    "cases",
    "start_reached",
    "start_potential",
    "path_offsets",
    "path",
    "potential_sha256",
    "trace_sha256",
    "cycles",
    "updates",
    "full_index",
    "full_potential",
    "full_trace_offsets",
    "full_trace",
)


@dataclass
class SuiteMap:
    directory: Path
    name: str
    category: str
    width: int
    height: int
    map_file: str
    costs: np.ndarray  # (height, width) uint8
    cases: np.ndarray  # (N, 4) int32: sx sy gx gy

    def golden_path(self, mode: str) -> Path:
        return golden_file(self.directory, mode)


def golden_file(map_dir, mode: str) -> Path:
    """The golden file of a map directory for one planner mode."""
    return Path(map_dir) / f"golden_{mode}.npz"


def is_case_line(line: str) -> bool:
    """Whether a line of ``test.txt`` after the first two holds a case (not blank, not a ``-1`` comment)."""
    s = line.strip()
    return bool(s) and not s.startswith("-1")


def parse_test_txt(path: Path) -> tuple[int, int, str, np.ndarray]:
    """Read a ``test.txt``; returns (width, height, map file name, cases)."""
    try:
        text = Path(path).read_text(encoding="ascii")
    except FileNotFoundError:
        raise NavfnInputError(f"{path}: no such file") from None
    except (OSError, UnicodeDecodeError) as e:
        raise NavfnInputError(f"{path}: unreadable test file ({e.__class__.__name__})") from None
    lines = text.splitlines()
    if len(lines) < 2:
        raise NavfnInputError(f"{path}: expected 'W H' and a map file name on the first two lines")
    head = lines[0].split()
    try:
        width, height = int(head[0]), int(head[1])
        if len(head) != 2:
            raise ValueError
    except (ValueError, IndexError):
        raise NavfnInputError(f"{path}:1: expected 'W H', got {lines[0]!r}") from None
    if width < 3 or height < 3:
        raise NavfnInputError(f"{path}:1: map size {width}x{height} is below NavFn's 3x3 minimum")
    check_cells(width, height, f"{path}:1")
    map_file = lines[1].strip()
    if not map_file or os.path.basename(map_file) != map_file:
        raise NavfnInputError(f"{path}:2: expected a map file name in the same directory, got {lines[1]!r}")
    cases = []
    for no, line in enumerate(lines[2:], start=3):
        if not is_case_line(line):
            continue
        parts = line.split()
        try:
            vals = [int(p) for p in parts]
            if len(vals) != 4:
                raise ValueError
        except ValueError:
            raise NavfnInputError(f"{path}:{no}: expected a case 'sx sy gx gy', got {line!r}") from None
        sx, sy, gx, gy = vals
        for what, x, y in (("start", sx, sy), ("goal", gx, gy)):
            if not (0 <= x < width and 0 <= y < height):
                raise NavfnInputError(f"{path}:{no}: {what} ({x}, {y}) is off the {width}x{height} map")
        cases.append(vals)
    return width, height, map_file, np.array(cases, dtype=np.int32).reshape(-1, 4)


def read_map_bytes(path: Path, width: int, height: int) -> np.ndarray:
    """Raw map bytes of exactly ``width * height`` cells, as a (height, width) uint8 array."""
    check_cells(width, height, str(path))
    try:
        if Path(path).is_dir():
            raise NavfnInputError(f"{path}: is a directory, not a map file")
        size = Path(path).stat().st_size  # a wrong size is refused before anything is read
        if size != width * height:
            raise NavfnInputError(f"{path}: map has {size} bytes, expected {width}x{height} = {width * height}")
        data = Path(path).read_bytes()
    except FileNotFoundError:
        raise NavfnInputError(f"{path}: no such map file") from None
    except OSError as e:
        raise NavfnInputError(f"{path}: unreadable map file ({e.strerror or e.__class__.__name__})") from None
    if len(data) != width * height:
        raise NavfnInputError(
            f"{path}: map has {len(data)} bytes, expected {width}x{height} = {width * height}"
        )
    return np.frombuffer(data, dtype=np.uint8).reshape(height, width).copy()


def load_map(directory, root: Optional[Path] = None) -> SuiteMap:
    d = Path(directory)
    if not d.is_dir():
        raise NavfnInputError(f"{d}: not a map directory")
    width, height, map_file, cases = parse_test_txt(d / "test.txt")
    costs = read_map_bytes(d / map_file, width, height)
    category = d.parent.name
    if root is not None:
        rel = d.resolve().relative_to(Path(root).resolve())
        category = rel.parts[0] if len(rel.parts) > 1 else "."
    return SuiteMap(d, d.name, category, width, height, map_file, costs, cases)


def discover(root) -> list[Path]:
    """All map directories (those holding a ``test.txt``) under ``root``, sorted."""
    r = Path(root)
    if not r.exists():
        raise NavfnInputError(f"{r}: no such suite directory")
    if not r.is_dir():
        raise NavfnInputError(f"{r}: a suite must be a directory")
    found = sorted(p.parent for p in r.rglob("test.txt"))
    if not found:
        raise NavfnInputError(f"{r}: no map directories (no test.txt) found")
    return found


def load_golden(path: Path, smap: Optional[SuiteMap] = None) -> dict:
    """All fields of a golden npz, loaded eagerly; checked for shape and type, and against the map if given."""
    try:
        with open(path, "rb") as f, np.load(f, allow_pickle=False) as z:
            missing = [f for f in GOLDEN_FIELDS if f not in z.files]
            if missing:
                raise NavfnInputError(f"{path}: golden file lacks {', '.join(missing)}")
            g = {f: z[f] for f in GOLDEN_FIELDS}
    except FileNotFoundError:
        raise NavfnInputError(f"{path}: no such golden file") from None
    except IsADirectoryError:
        raise NavfnInputError(f"{path}: is a directory, not a golden file") from None
    except (OSError, ValueError, zipfile.BadZipFile, EOFError, KeyError, RuntimeError, zlib.error, struct.error,
            NotImplementedError, OverflowError, MemoryError) as e:
        # (np.load raises many types on bad bytes; zipfile also KeyError and RuntimeError)
        raise NavfnInputError(f"{path}: unreadable golden file ({' '.join(str(e).split()) or type(e).__name__})") from None
    _check_golden(path, g)
    if smap is not None:
        if int(g["width"]) != smap.width or int(g["height"]) != smap.height:
            raise NavfnInputError(
                f"{path}: golden size {int(g['width'])}x{int(g['height'])} does not match test.txt's "
                f"{smap.width}x{smap.height}"
            )
        if not np.array_equal(g["cases"], smap.cases):
            raise NavfnInputError(f"{path}: golden cases differ from test.txt")
    return g


def _check_golden(path, g: dict) -> None:
    """Every field of a golden file with the shape and type the difftest reads, or NavfnInputError."""
    def bad(field: str, why: str):
        a = g[field]
        return NavfnInputError(f"{path}: golden field {field!r} {why} (got {a.dtype} {a.shape})")

    for f in GOLDEN_FIELDS:
        kind = g[f].dtype.kind
        if kind not in "biuf" or (kind == "f") != (f in ("start_potential", "path", "full_potential")):
            raise bad(f, "has the wrong type")
    for f in ("width", "height"):
        if g[f].shape != ():
            raise bad(f, "must be one number")
    w, h = int(g["width"]), int(g["height"])
    n = g["cases"].shape[0] if g["cases"].ndim == 2 else -1
    k = g["full_index"].shape[0] if g["full_index"].ndim == 1 else -1
    shapes = {"cases": (n, 4), "start_reached": (n,), "start_potential": (n,), "path_offsets": (n + 1,),
              "potential_sha256": (n, 32), "trace_sha256": (n, 32), "cycles": (n,), "updates": (n,),
              "full_index": (k,), "full_potential": (k, h, w), "full_trace_offsets": (k + 1,)}
    for f, want in shapes.items():
        if n < 0 or k < 0 or g[f].shape != want:
            raise bad(f, f"must have shape {want if n >= 0 and k >= 0 else '(N, 4)' if n < 0 else '(K,)'}")
    if g["path"].ndim != 2 or g["path"].shape[1:] != (2,):
        raise bad("path", "must have shape (P, 2)")
    if g["full_trace"].ndim != 1:
        raise bad("full_trace", "must be one-dimensional")
    for off, data in (("path_offsets", "path"), ("full_trace_offsets", "full_trace")):
        o = g[off]
        if o[0] != 0 or o[-1] != len(g[data]) or np.any(np.diff(o) < 0):
            raise bad(off, f"must rise from 0 to the length of {data!r} ({len(g[data])})")
    if k and (g["full_index"].min() < 0 or g["full_index"].max() >= n):
        raise bad("full_index", f"must hold case numbers 0..{n - 1}")


def golden_path_of(g: dict, i: int) -> np.ndarray:
    off = g["path_offsets"]
    return g["path"][off[i] : off[i + 1]]


def write_map_dir(directory, costs: np.ndarray, cases, map_file: str = "map.bin", comment: str = "") -> Path:
    """Write a map directory in the suite format (test.txt and the map bytes), file by file
    atomically; golden files are written separately (``suite record``)."""
    d = Path(directory)
    c = np.ascontiguousarray(costs, dtype=np.uint8)
    if c.ndim != 2:
        raise NavfnInputError("a map must be two-dimensional")
    ny, nx = c.shape
    lines = [f"{nx} {ny}", map_file, ""]
    if comment:
        lines.append(f"-1 {comment}")
    lines += [" ".join(str(int(v)) for v in case) for case in cases]
    try:
        d.mkdir(parents=True, exist_ok=True)
    except OSError as e:
        raise NavfnInputError(f"{d}: cannot create directory ({e.strerror})") from None
    atomic_write_bytes(d / map_file, c.tobytes())
    atomic_write_bytes(d / "test.txt", ("\n".join(lines) + "\n").encode("ascii"))
    return d
