"""Build Nav2's NavFn, planner plugin and costmap layers from a user's sources, unchanged, as
oracles the spec and the models are tested against.

The sources are the system under test: ``NAV2_SRC`` is a navigation2 checkout or a folder
holding ``nav2_navfn_planner``, ``nav2_core`` and ``nav2_costmap_2d``.  Nothing of them is
copied into the project and nothing in them is changed.  The build goes to a folder the user
names, the programs' sources compiled one at a time, side by side, each object kept once per
content (:mod:`.objects`):

- ``navfn-plain``: ``navfn.cpp`` as it is, with the driver ``navfn_driver.cpp`` and the rclcpp
  stub headers (``stubs/``, no ROS installation);
- ``navfn-traced``: the same, compiled from a copy of ``navfn.cpp`` in the build folder with
  ``NAVFN_SMT_CYCLE(curP, curPe);`` inserted before each anchor line of the two propagation
  loops (the white-box trace).  When a version moved an anchor the build stops, naming it;
- ``navfn-unbounded``: the traced build with priority buffers that never drop a push: a copy of
  ``navfn.hpp`` in the build folder whose ``#define PRIORITYBUFSIZE`` line names a variable the
  driver sets to ``nx * ny`` for each map (the pending flags keep a cell in one buffer at a time);
- ``navfn-plugin``: ``navfn_planner.cpp`` (the planner plugin), ``navfn.cpp``, ``costmap_2d.cpp``
  (and ``parameter_handler.cpp`` where the version has one) as they are, with the driver
  ``plugin_driver.cpp`` and the ROS stub headers of ``ros_stubs/``; the plugin's signature
  (``createPlan`` with a cancel checker, with via points; the node type) is read from
  ``nav2_core/global_planner.hpp``;
- ``costmap-layers``: the global costmap's sources and its static and inflation layers
  (:data:`LAYER_SOURCES`, those the version has) with ``layers_driver.cpp``, ``ros_stubs/``,
  ``-fopenmp`` and Eigen 3 where the version's inflation layer needs it;
- for each patched fix of :data:`navfn_smt.spec.fixes.PATCHED` (:func:`fix_programs`):
  ``navfn-<name>``, ``navfn-plugin-<name>`` and ``navfn-plain-<name>``, the traced NavFn, the
  plugin and the plain NavFn (to time the fix as Nav2 compiles it) with that fix: copies of
  ``navfn.cpp`` and ``navfn.hpp`` in the build folder, patched by ``patch -p1`` with the
  distribution's ``patches/<fix.patches>/<distribution>.patch``; the NavFn driver then calls
  the patched ``calcNavFnAstar`` / ``calcNavFnDijkstra`` (``NAVFN_SMT_CALC_NAVFN``).  So the
  fix of ``docs/fix.md`` gives ``navfn-fixed``, ``navfn-plugin-fixed`` and
  ``navfn-plain-fixed``.  A fix whose patch is missing or does not apply (without fuzz) is left
  out, its programs named in ``skipped`` with why.  Sources that carry a fix already (a
  contributor's branch: its patch applies in reverse) give that fix's programs from their own
  files, and ``build.json`` says ``sources_carry_fix``: the other NavFn programs are then
  patched too, the clients refuse to run them as NavFn as shipped, and the other fixes (whose
  patches are for NavFn as shipped) are left out;
- ``eigen-sqrt``: where the version's inflation layer uses Eigen, Eigen's square root built with
  the layers' flags (``eigen_sqrt.cpp``), to tell which one this machine takes.

Without Eigen the last two are left out of a version that needs it, and ``build.json`` says
why.  ``build.json`` records what was built: the compiler and its version, the flags and each
program's defines, the SHA-256 of every source file used, the git commit when the sources are
in a git checkout, and the distribution read from ``nav2_navfn_planner/package.xml``.  The
folder is written whole or not at all (built beside it, then renamed).
"""

from __future__ import annotations

import hashlib
import json
import os
import re
import shutil
import subprocess
from concurrent.futures import ThreadPoolExecutor
from dataclasses import replace
from pathlib import Path
from typing import Optional

from ..distros import DISTROS
from ..errors import NavfnInputError
from ..fileio import atomic_folder
from ..spec import fixes
from ..spec.fix import FIX as THE_FIX
from ..spec.planner import Fix
from .arithmetic import find as find_arithmetic
from .arithmetic import layers_find, plugin_find
from .arithmetic import record as record_arithmetic
from .library import disassemble, elf_target, fused_lines_of_binary
from .objects import Compiler, cache_dir, compile_flags
from .targets import Toolchain, toolchain

HERE = Path(__file__).resolve().parent
ANCHOR = "// reset pending flags on current priority buffer"  # once in each propagation loop
ANCHORS_EXPECTED = 2
HOOK = "NAVFN_SMT_CYCLE(curP, curPe);"
PATCHES_ROOT = HERE.parent / "patches"  # a folder per patched fix (Fix.patches), one patch per distribution
CALC_NAVFN = "NAVFN_SMT_CALC_NAVFN"  # the NavFn driver calls calcNavFn*, where a fix's patch changes the planning


def fix_programs(fix: Fix) -> tuple[str, str, str]:
    """The programs of a patched fix: its traced NavFn, its planner plugin and its plain NavFn."""
    return f"navfn-{fix.name}", f"navfn-plugin-{fix.name}", f"navfn-plain-{fix.name}"


SHIPPED_PROGRAMS = ("navfn-plain", "navfn-traced", "navfn-unbounded", "navfn-plugin", "costmap-layers", "eigen-sqrt")
PATCHED_PROGRAMS = {p: f for f in fixes.PATCHED for p in fix_programs(f)}  # each left out, and named, without its patch
if len(PATCHED_PROGRAMS) != 3 * len(fixes.PATCHED) or set(PATCHED_PROGRAMS) & set(SHIPPED_PROGRAMS):
    raise RuntimeError(f"the fixes {', '.join(f.name for f in fixes.PATCHED)} name programs twice: rename one in "
                       f"spec/fixes.py (its programs are navfn-NAME, navfn-plugin-NAME, navfn-plain-NAME)")
PROGRAMS = (*SHIPPED_PROGRAMS, *PATCHED_PROGRAMS)
FIXED_PROGRAMS = fix_programs(THE_FIX)  # the fix of docs/fix.md: navfn-fixed, navfn-plugin-fixed, navfn-plain-fixed
PATCHES = PATCHES_ROOT / THE_FIX.patches  # the fix of docs/fix.md, one patch per distribution
NAVFN_FILES = ("nav2_navfn_planner/src/navfn.cpp", "nav2_navfn_planner/include/nav2_navfn_planner/navfn.hpp")
EIGEN_PROGRAMS = ("costmap-layers", "eigen-sqrt")  # left out, and named, when Eigen is missing
EIGEN_DIRS = ("/usr/include/eigen3", "/usr/local/include/eigen3")
LAYER_SOURCES = ("src/costmap_2d.cpp", "src/layer.cpp", "src/layered_costmap.cpp", "src/costmap_layer.cpp",
                 "src/footprint.cpp", "src/costmap_math.cpp", "src/array_parser.cpp", "plugins/static_layer.cpp",
                 "plugins/inflation_layer.cpp", "plugins/legacy_inflation_layer.cpp")
BUFFER_DEFINE = "#define PRIORITYBUFSIZE"  # once in navfn.hpp; the unbounded build replaces its line
# package.xml's major.minor version -> the distribution it is released in.  The newest one
# shares its minor version with Rolling (the main branch) until main moves on: main carries
# x.y.0, the distribution's branch releases x.y.1 and later (Lyrical 1.5.1 beside Rolling's 1.5.0)
DISTRIBUTIONS = {d.version: name for name, d in DISTROS.items() if d.version is not None}
SHARED_WITH_MAIN = (1, 5)
NEWEST = "rolling"


def find_sources(root) -> Path:
    """The folder holding ``nav2_navfn_planner`` and ``nav2_core`` under ``root`` (itself, or
    one level down as in a navigation2 checkout); a clear error otherwise."""
    root = Path(root)
    if not root.is_dir():
        raise NavfnInputError(f"{root}: no such directory (give a navigation2 checkout or a folder of its packages)")
    for cand in (root, *sorted(p for p in root.iterdir() if p.is_dir())):
        if (cand / "nav2_navfn_planner" / "src" / "navfn.cpp").is_file() and (cand / "nav2_core").is_dir():
            if not (cand / "nav2_costmap_2d" / "src" / "costmap_2d.cpp").is_file():
                raise NavfnInputError(f"{cand}: no nav2_costmap_2d/src/costmap_2d.cpp beside nav2_navfn_planner "
                                      f"(the planner plugin is built with Nav2's Costmap2D)")
            return cand
    raise NavfnInputError(f"{root}: no nav2_navfn_planner/src/navfn.cpp with nav2_core beside it")


def distribution(src: Path) -> str:
    """The distribution the sources are released in, from ``package.xml``'s version."""
    xml = src / "nav2_navfn_planner" / "package.xml"
    m = re.search(r"<version>\s*(\d+)\.(\d+)\.(\d+)", xml.read_text(encoding="utf-8")) if xml.is_file() else None
    if m is None:
        raise NavfnInputError(f"{xml}: no <version> to tell the distribution by")
    major, minor, patch = int(m.group(1)), int(m.group(2)), int(m.group(3))
    if (major, minor) == SHARED_WITH_MAIN and patch == 0:
        return NEWEST
    return DISTRIBUTIONS.get((major, minor), NEWEST if (major, minor) > max(DISTRIBUTIONS) else "unknown")


def cxx_standard(src: Path) -> str:
    """The C++ standard the sources need: C++20 where the costmap holds a
    ``std::atomic<std::shared_ptr<...>>`` without Rolling's C++17 fallback (Lyrical's
    ``layered_costmap.hpp``), else C++17."""
    hpp = src / "nav2_costmap_2d" / "include" / "nav2_costmap_2d" / "layered_costmap.hpp"
    text = hpp.read_text(encoding="utf-8") if hpp.is_file() else ""
    return "c++20" if "std::atomic<std::shared_ptr" in text and "__cpp_lib_atomic_shared_ptr" not in text else "c++17"


def takes_cancel_checker(src: Path) -> bool:
    """Whether ``propNavFnDijkstra`` takes a ``cancelChecker`` (jazzy and later) or not (humble)."""
    hpp = (src / "nav2_navfn_planner" / "include" / "nav2_navfn_planner" / "navfn.hpp").read_text(encoding="utf-8")
    return bool(re.search(r"propNavFnDijkstra\s*\([^;]*cancelChecker", hpp))


def plugin_api(src: Path) -> list[str]:
    """The defines that fit the version's ``GlobalPlanner`` interface: ``createPlan`` with via
    points (3), with a cancel checker (2) or neither (1); ``nav2::LifecycleNode`` nodes."""
    hpp = (src / "nav2_core" / "include" / "nav2_core" / "global_planner.hpp").read_text(encoding="utf-8")
    api = 3 if "viapoints" in hpp else 2 if "cancel_checker" in hpp else 1
    return [f"NAVFN_SMT_PLUGIN_API={api}"] + (["NAVFN_SMT_NAV2_NODE"] if "nav2::LifecycleNode" in hpp else [])


def unbounded_header(navfn_hpp: Path, include_root: Path) -> Path:
    """A copy of ``navfn.hpp`` under ``include_root`` whose buffer size is the driver's variable."""
    lines = navfn_hpp.read_text(encoding="utf-8").splitlines(keepends=True)
    at = [i for i, line in enumerate(lines) if line.strip().startswith(BUFFER_DEFINE + " ")]
    if len(at) != 1:
        raise NavfnInputError(f"{navfn_hpp}: the line {BUFFER_DEFINE!r} is there {len(at)} times, not once: "
                              f"this version moved it")
    lines[at[0]] = f"{BUFFER_DEFINE} (::navfn_smt_buffer_size)\n"
    out = include_root / "nav2_navfn_planner" / "navfn.hpp"
    out.parent.mkdir(parents=True, exist_ok=True)
    out.write_text("extern int navfn_smt_buffer_size;  // navfn-smt: the unbounded build's buffer size\n"
                   + "".join(lines), encoding="utf-8")
    return out


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


def patches_of(fix: Fix) -> Path:
    """The folder of a patched fix's patches (``patches/<fix.patches>/``)."""
    if fix.shipped:
        raise NavfnInputError(f"the {fix.name} planner is NavFn as shipped: it has no patch")
    return PATCHES_ROOT / fix.patches


def fix_patch(src: Path, fix: Fix = THE_FIX) -> Path:
    """``fix``'s patch (default: the fix of docs/fix.md) for the version of ``src``
    (``patches/<fix.patches>/<distribution>.patch``)."""
    return patches_of(fix) / f"{distribution(src)}.patch"


def _dry_run(src: Path, patch: Path, *extra) -> bool:
    """Whether ``patch -p1 -F0 --dry-run`` (with ``extra``) succeeds on the sources as they are."""
    r = subprocess.run(["patch", "-p1", "-F0", *extra, "--dry-run", "-d", str(src), "-i", str(patch)],
                       capture_output=True, text=True)
    return r.returncode == 0


def _patch_applies(src: Path, fix: Fix = THE_FIX) -> bool:
    """Whether ``fix``'s patch applies to the sources as they are (``patch --dry-run``, no fuzz)."""
    return _dry_run(src, fix_patch(src, fix))


def carries_fix(src: Path, fix: Fix = THE_FIX) -> bool:
    """Whether the sources already carry ``fix`` (a contributor's branch): its patch applies to
    them in reverse, without fuzz."""
    if not fix_patch(src, fix).is_file() or shutil.which("patch") is None:
        return False
    return _dry_run(src, fix_patch(src, fix), "-R")


def carried_fix(src: Path) -> Optional[Fix]:
    """The patched fix of :data:`~navfn_smt.spec.fixes.PATCHED` the sources carry already, if any."""
    return next((f for f in fixes.PATCHED if carries_fix(src, f)), None)


def patched_files(patch: Path) -> list[str]:
    """The files a patch changes or adds, relative to the sources' root (its ``+++ b/...`` lines)."""
    return [line.split()[1][2:] for line in patch.read_text(encoding="utf-8").splitlines() if line.startswith("+++ b/")]


def patched_copy(src: Path, root: Path, patch: Optional[Path] = None, fix: Fix = THE_FIX) -> Path:
    """Copies under ``root`` of the files ``fix``'s patch (or ``patch``) touches, with the patch
    applied by ``patch -p1`` (no fuzz): ``navfn.cpp``, ``navfn.hpp``, and the tests it adds to
    ``nav2_navfn_planner/test``; a clear error when the patch does not apply."""
    patch = Path(patch).absolute() if patch is not None else fix_patch(src, fix)
    for rel in dict.fromkeys([*NAVFN_FILES, *patched_files(patch)]):
        (root / rel).parent.mkdir(parents=True, exist_ok=True)
        if (src / rel).is_file():
            shutil.copyfile(src / rel, root / rel)
    r = subprocess.run(["patch", "-p1", "-F0", "--no-backup-if-mismatch", "-d", str(root), "-i", str(patch)],
                       capture_output=True, text=True)
    if r.returncode != 0:
        first = (r.stdout + r.stderr).strip().splitlines()[-1:] or ["no output"]
        raise NavfnInputError(f"{patch.name} does not apply to {src}: {first[0]}")
    return root


def sha256_of(p: Path) -> str:
    return hashlib.sha256(p.read_bytes()).hexdigest()


def _git(src: Path, *args) -> Optional[str]:
    try:
        r = subprocess.run(["git", "-C", str(src), *args], capture_output=True, text=True, timeout=10)
    except (OSError, subprocess.TimeoutExpired):
        return None
    return r.stdout.strip() if r.returncode == 0 else None


def git_commit(src: Path) -> tuple:
    """``(commit, note)``: the commit of the sources' own git checkout, or None with why: a
    folder inside another repository (as ``../shared/nav2-src/<distribution>`` is) has no
    commit of its own, and that repository's commit would say nothing about these sources."""
    top = _git(src, "rev-parse", "--show-toplevel")
    if top is None:
        return None, "not a git checkout"
    if Path(top).resolve() != src.resolve():
        return None, f"a folder inside the git repository {top}, not a checkout of its own"
    return _git(src, "rev-parse", "HEAD"), None


ROOT_NAMES = {"src": "/nav2", "package": "/navfn-smt-oracle", "build": "/oracle-build"}  # in the objects


def compile_all(compiler: Compiler, jobs: dict, programs, tmp: Path) -> None:
    """Every program of ``programs``: each of its sources compiled to an object (one per core,
    side by side, :mod:`.objects`), then linked into ``tmp / name``."""
    objects = tmp / ".objects"
    objects.mkdir()
    work = [(name, i, Path(source)) for name in programs for i, source in enumerate(jobs[name][0])]
    with ThreadPoolExecutor(max_workers=os.cpu_count() or 1) as pool:
        done = {(name, i): pool.submit(compiler.compile, source, jobs[name][1], jobs[name][2],
                                       compile_flags(jobs[name][3] if len(jobs[name]) > 3 else ()),
                                       objects / f"{name}.{i}.{source.stem}.o", name)
                for name, i, source in work}
        linked = [pool.submit(compiler.link, [done[name, i].result() for i in range(len(jobs[name][0]))],
                              jobs[name][3] if len(jobs[name]) > 3 else (), tmp / name) for name in programs]
        for job in linked:
            job.result()
    shutil.rmtree(objects)


def program_jobs(src: Path, tmp: Path) -> dict:
    """Each program's (sources, include folders, defines[, extra flags]); the traced and
    unbounded copies are written into ``tmp``."""
    pkg = src / "nav2_navfn_planner"
    navfn_cpp = pkg / "src" / "navfn.cpp"
    includes = [HERE / "stubs", pkg / "include", src / "nav2_core" / "include", HERE]
    defines = ["NAVFN_SMT_CANCEL_CHECKER"] if takes_cancel_checker(src) else []
    driver = HERE / "navfn_driver.cpp"
    traced = traced_copy(navfn_cpp, tmp / "navfn_traced.cpp")
    unbounded_header(pkg / "include" / "nav2_navfn_planner" / "navfn.hpp", tmp / "unbounded")
    plugin = [HERE / "plugin_driver.cpp", pkg / "src" / "navfn_planner.cpp", navfn_cpp,
              src / "nav2_costmap_2d" / "src" / "costmap_2d.cpp",
              *[f for f in [pkg / "src" / "parameter_handler.cpp"] if f.is_file()]]
    plugin_includes = [HERE / "ros_stubs", pkg / "include", src / "nav2_core" / "include",
                       src / "nav2_costmap_2d" / "include"]
    costmap = src / "nav2_costmap_2d"
    layers = [HERE / "layers_driver.cpp", *[costmap / f for f in LAYER_SOURCES if (costmap / f).is_file()]]
    plugin_defines = plugin_api(src)
    patched = {}
    for fix in fixes.PATCHED:  # each fix's three programs, from its patched copy of navfn.cpp and navfn.hpp
        traced_name, plugin_name, plain_name = fix_programs(fix)
        if _skipped(src, traced_name) is not None:
            continue
        root = src if carries_fix(src, fix) else patched_copy(src, tmp / fix.name, fix=fix)
        fix_pkg = root / "nav2_navfn_planner"
        fix_cpp = traced_copy(fix_pkg / "src" / "navfn.cpp", tmp / f"navfn_{fix.name}_traced.cpp")
        fix_includes = [HERE / "stubs", fix_pkg / "include", *includes[1:]]
        patched.update({
            traced_name: ([driver, fix_cpp], fix_includes, [*defines, "NAVFN_SMT_TRACED", CALC_NAVFN]),
            plugin_name: ([plugin[0], plugin[1], fix_pkg / "src" / "navfn.cpp", *plugin[3:]],
                          [plugin_includes[0], fix_pkg / "include", *plugin_includes[1:]], plugin_defines),
            plain_name: ([driver, fix_pkg / "src" / "navfn.cpp"], fix_includes, [*defines, CALC_NAVFN]),
        })
    layer_defines = [d for d in plugin_defines if d == "NAVFN_SMT_NAV2_NODE"] + (
        ["NAVFN_SMT_LEGACY_LAYER"] if (costmap / "plugins" / "legacy_inflation_layer.cpp").is_file() else [])
    return {
        "costmap-layers": (layers, [HERE / "ros_stubs", costmap / "include", *eigen_include()], layer_defines,
                           ["-fopenmp", "-g1"]),  # -g1 (line tables): its arithmetic is read from its machine code
        "eigen-sqrt": ([HERE / "eigen_sqrt.cpp"], eigen_include(), [], ["-fopenmp"]),
        "navfn-plain": ([driver, navfn_cpp], includes, defines),
        "navfn-traced": ([driver, traced], includes, [*defines, "NAVFN_SMT_TRACED"]),
        "navfn-unbounded": ([driver, traced], [tmp / "unbounded", *includes],
                            [*defines, "NAVFN_SMT_TRACED", "NAVFN_SMT_UNBOUNDED"]),
        "navfn-plugin": (plugin, plugin_includes, plugin_defines),
        **patched,
    }


def _library_toolchain(lib: Path, tc: Optional[Toolchain]) -> Toolchain:
    """The toolchain that builds the driver for a library: the library's target (its ELF
    header), with the compiler ``tc`` names when it is for that target."""
    target = elf_target(lib)
    if tc is None:
        return toolchain(target, env_cxx=os.environ.get("CXX") if target == "x86-64" else None)
    machine = tc.machine().split("-")[0].replace("_", "-")
    if machine != target:
        raise NavfnInputError(f"--library {lib} is built for {target}, the compiler {tc.cxx} for {machine}")
    return tc


def _plain_job(src: Path, jobs: dict) -> tuple:
    """``(navfn.cpp, include folders, defines)`` as the plain program compiles them."""
    return src / "nav2_navfn_planner" / "src" / "navfn.cpp", jobs["navfn-plain"][1], jobs["navfn-plain"][2]


def eigen_include() -> list[Path]:
    """Eigen 3's include folder (Rolling's inflation layer needs it), or none."""
    return [Path(d) for d in EIGEN_DIRS if (Path(d) / "Eigen" / "Core").is_file()][:1]


def uses_eigen(src: Path) -> bool:
    """The version's inflation layer includes Eigen (Rolling's distance-transform layer)."""
    hpp = src / "nav2_costmap_2d" / "include" / "nav2_costmap_2d" / "inflation_layer.hpp"
    return hpp.is_file() and "<Eigen/" in hpp.read_text(encoding="utf-8")


HEADERS = ("nav2_navfn_planner/include/nav2_navfn_planner/navfn.hpp",
           "nav2_navfn_planner/include/nav2_navfn_planner/navfn_planner.hpp",
           "nav2_navfn_planner/include/nav2_navfn_planner/parameter_handler.hpp",
           "nav2_core/include/nav2_core/global_planner.hpp", "nav2_core/include/nav2_core/planner_exceptions.hpp",
           *(f"nav2_costmap_2d/include/nav2_costmap_2d/{n}.hpp" for n in (
               "costmap_2d", "cost_values", "layer", "layered_costmap", "costmap_layer", "footprint", "costmap_math",
               "static_layer", "inflation_layer", "legacy_inflation_layer", "inflation_layer_interface",
               "distance_transform")))


def _used(src: Path, jobs: dict) -> list[Path]:
    """The Nav2 files a build reads (hashed into build.json): every program's sources from
    ``src`` and the headers of :data:`HEADERS` the version has."""
    sources = {f for job in jobs.values() for f in job[0] if src in f.parents}
    return sorted(sources | {src / h for h in HEADERS if (src / h).is_file()})


def fix_skipped(src: Path, fix: Fix) -> Optional[str]:
    """Why the programs of the patched ``fix`` are left out of a build of ``src`` (None: they are
    built): no patch for the version, no ``patch`` program, a patch that does not apply without
    fuzz, or sources that carry another fix already."""
    carried = carried_fix(src)
    if carried == fix:
        return None  # built from the sources as they are
    folder, patch = patches_of(fix), fix_patch(src, fix)
    if carried is not None:
        return (f"these sources carry the {carried.name} fix already ({fix_patch(src, carried).name} of "
                f"patches/{carried.patches}/ applies to them in reverse), and the {fix.name} patch is for NavFn as "
                f"shipped")
    if not patch.is_file():
        have = ", ".join(sorted(p.stem for p in folder.glob("*.patch"))) or "none"
        return f"no patch of the {fix.name} fix for {distribution(src)} (patches/{fix.patches}/ has {have})"
    if shutil.which("patch") is None:
        return f"the {fix.name} fix is applied with the patch program, which is not installed"
    if not _patch_applies(src, fix):
        return (f"patches/{fix.patches}/{patch.name} does not apply to these sources without fuzz, nor in reverse "
                f"(the sources changed where it patches)")
    return None


def _skipped(src: Path, name: str) -> Optional[str]:
    """Why ``name`` is left out of this build (None: it is built): the Eigen programs without
    Eigen, ``eigen-sqrt`` for a version whose inflation layer does not use it, a patched fix's
    programs as :func:`fix_skipped` says."""
    if name in PATCHED_PROGRAMS:
        return fix_skipped(src, PATCHED_PROGRAMS[name])
    if name not in EIGEN_PROGRAMS:
        return None
    if not uses_eigen(src):
        return None if name == "costmap-layers" else "this version's inflation layer does not use Eigen"
    if not eigen_include():
        return "this version's inflation layer needs Eigen 3, which is not installed (libeigen3-dev)"
    return None


def build(nav2_src, out, programs=PROGRAMS, tc: Optional[Toolchain] = None, library=None) -> dict:
    """Build the oracle ``programs`` (all by default) from ``nav2_src`` into the folder ``out``
    with the toolchain ``tc`` (default: x86-64 with ``$CXX`` or g++), compiling their sources
    side by side, one per core, from the object cache where it has them; returns build.json.  ``library``: a shared library of NavFn built from
    ``nav2_src``, which ``navfn-plain`` (the only program then) links (:mod:`.library`)."""
    src = find_sources(nav2_src)
    out = Path(out)
    if library is not None:
        tc, programs = _library_toolchain(Path(library), tc), ("navfn-plain",)
    if out.exists() and not (out / "build.json").is_file():
        raise NavfnInputError(f"{out}: exists and is not an oracle build folder (no build.json); name a new folder")
    unknown = [p for p in programs if p not in PROGRAMS]
    if unknown:
        raise NavfnInputError(f"no oracle program {unknown[0]!r} (there are: {', '.join(PROGRAMS)})")
    tc = replace(tc or toolchain(env_cxx=os.environ.get("CXX")), std=cxx_standard(src))
    tc.check()
    runner = tc.runner()
    skipped = {name: why for name in programs if (why := _skipped(src, name))}
    programs = tuple(p for p in programs if p not in skipped)
    with atomic_folder(out) as tmp:
        jobs = program_jobs(src, tmp)
        if library is not None:  # the driver alone, linked with a copy of the library beside it
            lib = tmp / Path(library).name
            shutil.copyfile(library, lib)
            driver, includes, defines = jobs["navfn-plain"][0][0], *jobs["navfn-plain"][1:3]
            # by name (-l:), so the program needs the file name, found beside it ($ORIGIN)
            jobs["navfn-plain"] = ([driver], includes, defines, [f"-L{tmp}", f"-l:{lib.name}", "-Wl,-rpath,$ORIGIN"])
        compiler = Compiler(tc, {src: ROOT_NAMES["src"], HERE: ROOT_NAMES["package"], tmp: ROOT_NAMES["build"]},
                            cache_dir())
        compile_all(compiler, jobs, programs, tmp)
        try:
            (tmp / "arithmetic").mkdir()
            if library is None:
                arith = find_arithmetic(tc, runner, *_plain_job(src, jobs), tmp / "arithmetic")
            else:
                navfn_cpp = _plain_job(src, jobs)[0]
                lines, untraced = fused_lines_of_binary(disassemble(lib, tc.target), navfn_cpp.name)
                arith = record_arithmetic(lines, navfn_cpp, tc, runner, tmp / "arithmetic", untraced)
            plugin_arith = None
            if "navfn-plugin" in programs:
                sources, includes, defines = jobs["navfn-plugin"][:3]
                planner_cpp = next(f for f in sources if Path(f).name == "navfn_planner.cpp")
                plugin_arith = plugin_find(tc, planner_cpp, includes, defines, tmp / "arithmetic")
            layers_arith = layers_find(tc, tmp / "costmap-layers", runner, tmp / "arithmetic", compiler.unmap) if "costmap-layers" in programs else None
        except RuntimeError as e:
            raise NavfnInputError(f"the arithmetic of the {tc.target} build could not be found: {e}") from None
        commit, why = git_commit(src)
        doc = {
            "sources": str(src.resolve()), "distribution": distribution(src), "git_commit": commit,
            **({"git_commit_note": why} if why else {}),
            "target": tc.target, "machine": compiler.machine, "compiler": tc.cxx, "compiler_version": compiler.version,
            "flags": tc.all_flags, "path_maps": dict(compiler.named),
            "objects": {"cache": str(compiler.cache) if compiler.cache else None, "compiled": compiler.compiled,
                        "reused": compiler.reused},
            "runner": runner, "arithmetic": arith,
            **({"plugin_arithmetic": plugin_arith} if plugin_arith is not None else {}),
            **({"layers_arithmetic": layers_arith} if layers_arith is not None else {}),
            "defines": {name: jobs[name][2] for name in programs}, "programs": list(programs), "skipped": skipped,
            "source_sha256": {str(p.relative_to(src)): sha256_of(p) for p in _used(src, jobs)},
            "anchor": ANCHOR,
        }
        if library is not None:
            doc["library"] = {"file": str(Path(library).resolve()), "sha256": sha256_of(Path(library)),
                              "target": tc.target}
            doc["source_sha256"] = {k: v for k, v in doc["source_sha256"].items() if k.endswith(".hpp")}
        doc.update(_patches_record(src, programs))
        (tmp / "build.json").write_text(json.dumps(doc, indent=1) + "\n", encoding="utf-8")
    return doc


def _patches_record(src: Path, programs) -> dict:
    """What build.json records of the patches: ``patches``, each built fix's patch by its name;
    ``fix_patch``, the fix of docs/fix.md's (the key its readers know); ``sources_carry_fix``
    (and ``sources_carry``, which fix and patch) when the sources carry a fix already: every NavFn
    program of the build is then patched with it."""
    carried = carried_fix(src)
    out = {}
    built = [f for f in fixes.PATCHED if any(p in programs for p in fix_programs(f))]
    if built:
        out["patches"] = {f.name: {"folder": f"patches/{f.patches}", "file": fix_patch(src, f).name,
                                   "sha256": sha256_of(fix_patch(src, f)),
                                   "applied_by": "the sources" if carried == f else "this build",
                                   "programs": [p for p in fix_programs(f) if p in programs]} for f in built}
    if THE_FIX in built:
        out["fix_patch"] = {k: v for k, v in out["patches"][THE_FIX.name].items() if k in ("file", "sha256", "applied_by")}
    if carried is not None:
        out["sources_carry_fix"] = True
        out["sources_carry"] = {"fix": carried.name, "patch": f"patches/{carried.patches}/{fix_patch(src, carried).name}"}
    return out


def load_build(folder) -> dict:
    """build.json of an oracle build folder, its programs present; a clear error otherwise."""
    folder = Path(folder)
    try:
        doc = json.loads((folder / "build.json").read_text(encoding="utf-8"))
    except (OSError, ValueError) as e:
        raise NavfnInputError(f"{folder}: not an oracle build folder (build.json: "
                              f"{getattr(e, 'strerror', None) or e}); run `navfn-smt oracle build`") from None
    missing = [p for p in doc.get("programs", PROGRAMS) if not os.access(folder / p, os.X_OK)]
    if missing:
        raise NavfnInputError(f"{folder}: the build is incomplete ({', '.join(missing)} missing); build it again")
    return doc
