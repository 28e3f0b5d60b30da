"""Build Nav2's NavFn from a user's sources, unchanged, as an oracle the spec is tested against.

The sources are the system under test: ``NAV2_SRC`` is a navigation2 checkout or a folder
holding ``nav2_navfn_planner`` and ``nav2_core``.  Nothing of them is copied into the project
and nothing in them is changed.  The build goes to a folder the user names:

- ``navfn-plain``: ``navfn.cpp`` as it is, with the driver ``navfn_driver.cpp`` and the rclcpp
  stub headers (``stubs/``, no ROS installation);
- ``navfn-traced``: the same, compiled from a copy of ``navfn.cpp`` in the build folder with
  ``NAVFN_SMT_CYCLE(curP, curPe);`` inserted before each anchor line of the two propagation
  loops (the white-box trace).  When a version moved an anchor the build stops, naming it.

``build.json`` records what was built: the compiler and its version, the flags, the SHA-256
of every source file used, the git commit when the sources are in a git checkout, and the
distribution read from ``nav2_navfn_planner/package.xml``.  The folder is written whole or not
at all (built beside it, then renamed).
"""

from __future__ import annotations

import hashlib
import json
import os
import re
import shutil
import subprocess
import tempfile
from pathlib import Path
from typing import Optional

from ..errors import NavfnInputError

HERE = Path(__file__).resolve().parent
ANCHOR = "// reset pending flags on current priority buffer"  # once in each propagation loop
ANCHORS_EXPECTED = 2
HOOK = "NAVFN_SMT_CYCLE(curP, curPe);"
FLAGS = ("-std=c++17", "-O2")
PROGRAMS = ("navfn-plain", "navfn-traced")
# package.xml's major.minor version -> the distribution it is released in
DISTRIBUTIONS = {(1, 1): "humble", (1, 2): "iron", (1, 3): "jazzy", (1, 4): "kilted"}
NEWEST = "rolling"


def find_sources(root) -> Path:
    """The folder holding ``nav2_navfn_planner`` and ``nav2_core`` under ``root`` (itself, or
    one level down as in a navigation2 checkout); a clear error otherwise."""
    root = Path(root)
    if not root.is_dir():
        raise NavfnInputError(f"{root}: no such directory (give a navigation2 checkout or a folder of its packages)")
    for cand in (root, *sorted(p for p in root.iterdir() if p.is_dir())):
        if (cand / "nav2_navfn_planner" / "src" / "navfn.cpp").is_file() and (cand / "nav2_core").is_dir():
            return cand
    raise NavfnInputError(f"{root}: no nav2_navfn_planner/src/navfn.cpp with nav2_core beside it")


def distribution(src: Path) -> str:
    """The distribution the sources are released in, from ``package.xml``'s version."""
    xml = src / "nav2_navfn_planner" / "package.xml"
    m = re.search(r"<version>\s*(\d+)\.(\d+)\.", xml.read_text(encoding="utf-8")) if xml.is_file() else None
    if m is None:
        raise NavfnInputError(f"{xml}: no <version> to tell the distribution by")
    major, minor = int(m.group(1)), int(m.group(2))
    return DISTRIBUTIONS.get((major, minor), NEWEST if (major, minor) > max(DISTRIBUTIONS) else "unknown")


def takes_cancel_checker(src: Path) -> bool:
    """Whether ``propNavFnDijkstra`` takes a ``cancelChecker`` (jazzy and later) or not (humble)."""
    hpp = (src / "nav2_navfn_planner" / "include" / "nav2_navfn_planner" / "navfn.hpp").read_text(encoding="utf-8")
    return bool(re.search(r"propNavFnDijkstra\s*\([^;]*cancelChecker", hpp))


def traced_copy(navfn_cpp: Path, out: Path) -> Path:
    """``navfn.cpp`` with the trace hook before each anchor line, written to ``out``."""
    lines = navfn_cpp.read_text(encoding="utf-8").splitlines(keepends=True)
    at = [i for i, line in enumerate(lines) if line.strip() == ANCHOR]
    if len(at) != ANCHORS_EXPECTED:
        raise NavfnInputError(f"{navfn_cpp}: the anchor line {ANCHOR!r} is there {len(at)} times, not "
                              f"{ANCHORS_EXPECTED} (once per propagation loop): this version moved it")
    for i in reversed(at):
        indent = lines[i][:len(lines[i]) - len(lines[i].lstrip())]
        lines.insert(i, f"{indent}{HOOK}\n")
    out.write_text('#include "trace_hook.hpp"\n' + "".join(lines), encoding="utf-8")
    return out


def compiler() -> str:
    """The C++ compiler: ``$CXX``, else g++ (a clear error when there is none)."""
    cxx = os.environ.get("CXX") or "g++"
    if shutil.which(cxx) is None:
        raise NavfnInputError(f"no C++ compiler: {cxx!r} is not on PATH (install g++ or set CXX)")
    return cxx


def _sha256(p: Path) -> str:
    return hashlib.sha256(p.read_bytes()).hexdigest()


def _git_commit(src: Path) -> Optional[str]:
    try:
        r = subprocess.run(["git", "-C", str(src), "rev-parse", "HEAD"], capture_output=True, text=True, timeout=10)
    except (OSError, subprocess.TimeoutExpired):
        return None
    return r.stdout.strip() if r.returncode == 0 else None


def _compile(cxx: str, sources, includes, defines, out: Path) -> None:
    cmd = [cxx, *FLAGS, *(f"-I{i}" for i in includes), *(f"-D{d}" for d in defines), *map(str, sources),
           "-o", str(out)]
    r = subprocess.run(cmd, capture_output=True, text=True)
    if r.returncode != 0:
        first = next((line for line in r.stderr.splitlines() if "error" in line), r.stderr.strip()[:300])
        raise NavfnInputError(f"the C++ build of {out.name} failed: {first}")


def build(nav2_src, out) -> dict:
    """Build the oracle programs from ``nav2_src`` into the folder ``out``; returns build.json."""
    src = find_sources(nav2_src)
    out = Path(out)
    if out.exists() and not (out / "build.json").is_file():
        raise NavfnInputError(f"{out}: exists and is not an oracle build folder (no build.json); name a new folder")
    cxx = compiler()
    version = subprocess.run([cxx, "--version"], capture_output=True, text=True).stdout.splitlines()[:1]
    pkg = src / "nav2_navfn_planner"
    navfn_cpp = pkg / "src" / "navfn.cpp"
    includes = [HERE / "stubs", pkg / "include", src / "nav2_core" / "include", HERE]
    defines = ["NAVFN_SMT_CANCEL_CHECKER"] if takes_cancel_checker(src) else []
    out.parent.mkdir(parents=True, exist_ok=True)
    tmp = Path(tempfile.mkdtemp(prefix=f".{out.name}.", dir=out.parent))
    try:
        driver = HERE / "navfn_driver.cpp"
        _compile(cxx, [driver, navfn_cpp], includes, defines, tmp / "navfn-plain")
        traced = traced_copy(navfn_cpp, tmp / "navfn_traced.cpp")
        _compile(cxx, [driver, traced], includes, [*defines, "NAVFN_SMT_TRACED"], tmp / "navfn-traced")
        used = [navfn_cpp, pkg / "include" / "nav2_navfn_planner" / "navfn.hpp",
                src / "nav2_core" / "include" / "nav2_core" / "planner_exceptions.hpp"]
        doc = {
            "sources": str(src.resolve()), "distribution": distribution(src), "git_commit": _git_commit(src),
            "compiler": cxx, "compiler_version": version[0] if version else "", "flags": list(FLAGS),
            "defines": defines, "programs": list(PROGRAMS),
            "source_sha256": {str(p.relative_to(src)): _sha256(p) for p in used if p.is_file()},
            "anchor": ANCHOR,
        }
        (tmp / "build.json").write_text(json.dumps(doc, indent=1) + "\n", encoding="utf-8")
        if out.exists():
            shutil.rmtree(out)
        tmp.rename(out)
    finally:
        if tmp.exists():
            shutil.rmtree(tmp, ignore_errors=True)
    return doc


def load_build(folder) -> dict:
    """build.json of an oracle build folder, its programs present; a clear error otherwise."""
    folder = Path(folder)
    try:
        doc = json.loads((folder / "build.json").read_text(encoding="utf-8"))
    except (OSError, ValueError) as e:
        raise NavfnInputError(f"{folder}: not an oracle build folder (build.json: "
                              f"{getattr(e, 'strerror', None) or e}); run `navfn-smt oracle build`") from None
    missing = [p for p in PROGRAMS if not os.access(folder / p, os.X_OK)]
    if missing:
        raise NavfnInputError(f"{folder}: the build is incomplete ({', '.join(missing)} missing); build it again")
    return doc
