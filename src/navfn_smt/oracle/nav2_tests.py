"""Nav2's own tests of ``nav2_navfn_planner``, built and run against the sources as they are and
as the fix patches them, so that what the patch changes is shown by Nav2's tests, not ours.

Each ``nav2_add_gtest(NAME SOURCES...)`` (``ament_add_gtest`` in older versions) of
``nav2_navfn_planner/test/CMakeLists.txt`` is one program, compiled as the oracle's programs are
(:mod:`.objects`, one source at a time, each object kept once per content):

- the test's own sources, unchanged: those the sources declare, and those the fix's patch adds
  (each run against both variants, to show that it fails as shipped and passes patched);
- NavFn: ``navfn.cpp`` as it is (``original``) or the copy the fix's patch makes (``fixed``,
  :func:`.build.patched_copy`); sources that carry the fix already (a contributor's branch) are
  the fixed variant as they are, and have no original;
- for a test that makes the planner plugin (it includes ``navfn_planner.hpp``): the plugin's
  sources with Nav2's ``costmap_2d.cpp``, and the project's ROS stub headers (``ros_stubs/``), in
  which a parameter request is answered as rclcpp's parameter service answers it;
- googletest compiled from its sources by the same toolchain (Debian's ``libgtest-dev`` installs
  them in ``/usr/src/googletest``), with ``gtest_main`` unless the test has its own ``main``.

Each program runs (under qemu-user for another machine) with ``--gtest_output=xml``; a result
is one gtest case: passed, failed (with gtest's message), or the program crashed.
"""

from __future__ import annotations

import json
import re
import shutil
import subprocess
import xml.etree.ElementTree as ET
from dataclasses import dataclass, replace
from pathlib import Path
from typing import Optional

from ..errors import NavfnInputError
from ..fileio import atomic_folder
from .build import (HERE, ROOT_NAMES, _compile_all, _jobs, _sha256, _skipped, carries_fix, cxx_standard, distribution,
                    find_sources, fix_patch, patched_copy)
from .objects import Compiler, cache_dir
from .targets import Toolchain, toolchain

VARIANTS = ("original", "fixed")
GTEST_ROOTS = (Path("/usr/src/googletest/googletest"), Path("/usr/src/gtest"))
GTEST_CALL = re.compile(r"\b(?:nav2|ament)_add_gtest\(\s*([A-Za-z0-9_]+)\s+([^)]*)\)")
TIMEOUT = 600  # seconds a test program may run (under qemu too)
PASSED, FAILED, CRASHED = "passed", "failed", "crashed"


@dataclass(frozen=True)
class Nav2Test:
    """One gtest program of nav2_navfn_planner/test: its name, its sources, and whether it makes
    the planner plugin (a ROS node) or runs NavFn alone."""

    name: str
    sources: tuple
    plugin: bool

    @property
    def has_main(self) -> bool:
        return any(re.search(r"^\s*int\s+main\s*\(", Path(s).read_text(encoding="utf-8"), re.M) for s in self.sources)


def nav2_tests(src: Path, beside: Optional[Path] = None) -> list[Nav2Test]:
    """The gtest programs ``nav2_navfn_planner/test/CMakeLists.txt`` of ``src`` declares, in its
    order; a source it names that ``src`` lacks is taken from the same folder of ``beside`` (a
    patched copy holds only the files its patch touches)."""
    folder = src / "nav2_navfn_planner" / "test"
    cmake = folder / "CMakeLists.txt"
    if not cmake.is_file():
        raise NavfnInputError(f"{src}: no nav2_navfn_planner/test/CMakeLists.txt (the sources' own tests)")
    other = beside / "nav2_navfn_planner" / "test" if beside is not None else folder
    out = []
    for name, args in GTEST_CALL.findall(cmake.read_text(encoding="utf-8")):
        sources = tuple(folder / a if (folder / a).is_file() else other / a for a in args.split() if a.endswith(".cpp"))
        missing = [s.name for s in sources if not s.is_file()]
        if missing:
            raise NavfnInputError(f"{cmake}: {name} names {missing[0]}, which is not in {folder}"
                                  + (f" nor in {other}" if other != folder else ""))
        text = "".join(s.read_text(encoding="utf-8") for s in sources)
        out.append(Nav2Test(name, sources, "navfn_planner.hpp" in text))
    if not out:
        raise NavfnInputError(f"{cmake}: declares no gtest")
    return out


def googletest() -> Path:
    """googletest's source folder (``src/gtest-all.cc``), or a clear error."""
    for root in GTEST_ROOTS:
        if (root / "src" / "gtest-all.cc").is_file():
            return root
    raise NavfnInputError("googletest's sources were not found (in " + ", ".join(map(str, GTEST_ROOTS))
                          + "); Debian: apt-get install libgtest-dev")


def _fixed_root(src: Path, tmp: Path) -> Optional[Path]:
    """The tree of the fixed variant: the sources themselves when they carry the fix, else a
    patched copy of the files the patch touches; None when the fix cannot be built."""
    if carries_fix(src):
        return src
    if _skipped(src, "navfn-fixed"):
        return None
    return patched_copy(src, tmp / "fixed")


def _programs(src: Path, fixed: Optional[Path], tests, variants, tmp: Path) -> dict:
    """Each ``(test, variant)`` program's job, as :func:`.build._compile_all` takes them."""
    base = _jobs(src, tmp / "oracle")
    gtest = googletest()
    gtest_job = [gtest / "src" / "gtest-all.cc"]
    gtest_inc = [gtest / "include", gtest]
    jobs, names = {}, {}
    for variant in variants:
        root = fixed if variant == "fixed" else src
        navfn_cpp, navfn_inc = root / "nav2_navfn_planner" / "src" / "navfn.cpp", root / "nav2_navfn_planner" / "include"
        for t in tests:
            main = [] if t.has_main else [gtest / "src" / "gtest_main.cc"]
            if t.plugin:
                sources, includes, defines = base["navfn-plugin"][:3]
                others = [s for s in sources[1:] if Path(s).name != "navfn.cpp"]  # the plugin, costmap_2d, ...
                job = ([*t.sources, navfn_cpp, *others, *gtest_job, *main], [includes[0], navfn_inc, *includes[1:], *gtest_inc],
                       defines, ["-lpthread"])
            else:
                includes = base["navfn-plain"][1]
                job = ([*t.sources, navfn_cpp, *gtest_job, *main], [includes[0], navfn_inc, *includes[1:], *gtest_inc], [],
                       ["-lpthread"])
            name = f"{t.name}-{variant}"
            jobs[name], names[name] = job, (t, variant)
    return jobs, names


def _results(xml: Path, run: subprocess.CompletedProcess) -> list[dict]:
    """The cases of gtest's XML report; one crashed result when the program left none whole."""
    try:
        root = ET.parse(xml).getroot()
    except (OSError, ET.ParseError):
        tail = (run.stderr or run.stdout or "").strip().splitlines()[-1:] or ["no output"]
        return [{"case": None, "status": CRASHED, "message": f"exit status {run.returncode}: {tail[0]}"}]
    out = []
    for case in root.iter("testcase"):
        failures = [f.get("message", "") for f in case.findall("failure")]
        out.append({"case": f"{case.get('classname')}.{case.get('name')}", "status": FAILED if failures else PASSED,
                    **({"message": "\n".join(failures)} if failures else {})})
    if run.returncode != 0 and not any(r["status"] == FAILED for r in out):
        out.append({"case": None, "status": CRASHED, "message": f"exit status {run.returncode} with no failed case"})
    return out


def run_nav2_tests(nav2_src, out, variants=VARIANTS, tc: Optional[Toolchain] = None) -> dict:
    """Build each of Nav2's NavFn tests for each variant into ``out`` and run it; returns the
    report (also ``out/nav2-tests.json``).  The folder is written whole or not at all."""
    src = find_sources(nav2_src)
    out = Path(out)
    if out.exists() and not (out / "nav2-tests.json").is_file():
        raise NavfnInputError(f"{out}: exists and is not a folder of Nav2's tests (no nav2-tests.json); name a new folder")
    shipped = {t.name for t in nav2_tests(src)}
    if carries_fix(src):  # a contributor's branch: its NavFn as it is is the fixed one
        if "original" in variants and len(variants) == 1:
            raise NavfnInputError(f"{src}: these sources carry the fix already ({fix_patch(src).name} applies to them "
                                  "in reverse): there is no NavFn as shipped to test; use --variant fixed")
        variants = ("fixed",)
    tc = replace(tc or toolchain(), std=cxx_standard(src))
    tc.check()
    runner = tc.runner()
    with atomic_folder(out) as tmp:
        (tmp / "oracle").mkdir()
        fixed = _fixed_root(src, tmp)
        if fixed is None and "fixed" in variants:
            raise NavfnInputError(f"the fixed variant cannot be built: {_skipped(src, 'navfn-fixed')}")
        # the shipped tests and those the fix's patch adds, each run against every variant: a
        # test of the patch should fail as shipped and pass patched
        tests = nav2_tests(fixed, src) if fixed is not None else nav2_tests(src)
        jobs, names = _programs(src, fixed, tests, variants, tmp)
        compiler = Compiler(tc, {src: ROOT_NAMES["src"], HERE: ROOT_NAMES["package"], tmp: ROOT_NAMES["build"],
                                 googletest(): "/googletest"}, cache_dir())
        _compile_all(compiler, jobs, list(jobs), tmp)
        results = []
        for name, (t, variant) in names.items():
            xml = tmp / f"{name}.xml"
            try:
                run = subprocess.run([*runner, str(tmp / name), f"--gtest_output=xml:{xml}"], capture_output=True,
                                     text=True, timeout=TIMEOUT, cwd=tmp)
            except subprocess.TimeoutExpired:
                results.append({"program": t.name, "variant": variant, "case": None, "status": CRASHED,
                                "message": f"still running after {TIMEOUT} s"})
                continue
            (tmp / f"{name}.log").write_text(run.stdout + run.stderr, encoding="utf-8")
            results += [{"program": t.name, "variant": variant, **r} for r in _results(xml, run)]
        doc = {
            "sources": str(src.resolve()), "distribution": distribution(src), "target": tc.target,
            "compiler": tc.cxx, "compiler_version": compiler.version, "flags": tc.all_flags, "runner": runner,
            "googletest": str(googletest()),
            "objects": {"cache": str(compiler.cache) if compiler.cache else None, "compiled": compiler.compiled,
                        "reused": compiler.reused},
            "programs": {t.name: {"sources": [s.name for s in t.sources], "plugin": t.plugin,
                                  "from": "the sources" if t.name in shipped else "the fix's patch"} for t in tests},
            "source_sha256": {str(s.relative_to(s.parents[2])): _sha256(s) for t in tests for s in t.sources},
            "variants": list(variants), "results": results, **({"sources_carry_fix": True} if carries_fix(src) else {}),
            **({"fix_patch": {"file": fix_patch(src).name, "sha256": _sha256(fix_patch(src))}} if "fixed" in variants else {}),
        }
        for stale in (tmp / "oracle", tmp / "fixed"):
            shutil.rmtree(stale, ignore_errors=True)
        (tmp / "nav2-tests.json").write_text(json.dumps(doc, indent=1) + "\n", encoding="utf-8")
    return doc


def without_fix(doc: dict, r: dict) -> bool:
    """Whether the result ``r`` is of a test the fix's patch adds, run as shipped (where it is
    meant to fail: it shows what the fix changes)."""
    return r["variant"] == "original" and doc["programs"][r["program"]]["from"] == "the fix's patch"


def failed(doc: dict) -> list[dict]:
    """The results of a report that are not passes where a pass is due: every test patched,
    and the sources' own tests as shipped."""
    return [r for r in doc["results"] if r["status"] != PASSED and not without_fix(doc, r)]
