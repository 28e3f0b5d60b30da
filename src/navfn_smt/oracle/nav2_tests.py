"""Nav2's own tests of ``nav2_navfn_planner``, built and run against the sources as they are and
as each fix's patch makes them, so that what a patch changes is shown by Nav2's tests, not ours.

Each ``nav2_add_gtest(NAME SOURCES...)`` (``ament_add_gtest`` in older versions) of
``nav2_navfn_planner/test/CMakeLists.txt`` is one program, compiled as the oracle's programs are
(:mod:`.objects`, one source at a time, each object kept once per content):

- the test's own sources, unchanged: those the sources declare, and those a fix's patch adds
  (each run as shipped and with that fix, to show that it fails as shipped and passes patched);
- NavFn: ``navfn.cpp`` as it is (``original``) or the copy a fix's patch makes (the variant
  named by the fix, e.g. ``fixed``, ``cycles-only``: :data:`navfn_smt.spec.fixes.PATCHED`,
  :func:`.build.patched_copy`); sources that carry a fix already (a contributor's branch) are
  that fix's variant as they are, and have no original;
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
from ..spec import fixes
from ..spec.fix import FIX as THE_FIX
from .build import (HERE, ROOT_NAMES, compile_all, program_jobs, sha256_of, carried_fix, cxx_standard, distribution,
                    find_sources, fix_patch, fix_skipped, patched_copy)
from .objects import Compiler, cache_dir
from .targets import Toolchain, toolchain

BOTH = (fixes.AS_SHIPPED.name, THE_FIX.name)  # as shipped, and with the fix of docs/fix.md
ALL = (fixes.AS_SHIPPED.name, *(f.name for f in fixes.PATCHED))  # as shipped, and every fix with a C++ patch
VARIANTS = BOTH  # the default
PATCH_TESTS = "the fix's patch"  # a test's "from" in the report when a fix's patch adds it
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


def _root(src: Path, fix, tmp: Path) -> Path:
    """The tree of ``fix``'s variant: the sources themselves as shipped or when they carry the
    fix, else a patched copy of the files its patch touches; a clear error when the fix cannot
    be built."""
    if fix.shipped or carried_fix(src) == fix:
        return src
    why = fix_skipped(src, fix)
    if why:
        raise NavfnInputError(f"the {fix.name} variant cannot be built: {why}")
    return patched_copy(src, tmp / fix.name, fix=fix)


def _variant_tests(src: Path, roots: dict) -> dict:
    """Each variant's tests: those of its tree (a patched copy's CMakeLists.txt declares the
    tests its patch adds), and, as shipped, also those every other variant's patch adds (each is
    run as shipped too, to show what its fix changes)."""
    # a patch that touches no test leaves its copy without test/CMakeLists.txt: the sources' tests
    per = {v: nav2_tests(root, src) if (root / "nav2_navfn_planner" / "test" / "CMakeLists.txt").is_file()
           else nav2_tests(src) for v, root in roots.items() if not fixes.named(v).shipped}
    for v in roots:
        if fixes.named(v).shipped:
            shipped = nav2_tests(src)
            names = {t.name for t in shipped}
            added = {t.name: t for ts in per.values() for t in ts if t.name not in names}
            per[v] = [*shipped, *added.values()]
    return {v: per[v] for v in roots}


def _programs(src: Path, roots: dict, tests: dict, tmp: Path) -> dict:
    """Each ``(test, variant)`` program's job, as :func:`.build.compile_all` takes them:
    ``roots`` and ``tests`` give each variant's tree and tests."""
    base = program_jobs(src, tmp / "oracle")
    gtest = googletest()
    gtest_job = [gtest / "src" / "gtest-all.cc"]
    gtest_inc = [gtest / "include", gtest]
    jobs, names = {}, {}
    for variant, root in roots.items():
        navfn_cpp, navfn_inc = root / "nav2_navfn_planner" / "src" / "navfn.cpp", root / "nav2_navfn_planner" / "include"
        for t in tests[variant]:
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


def _chosen(src: Path, variants) -> list:
    """The fixes ``variants`` (names or :class:`~navfn_smt.spec.planner.Fix` values) name, once
    each; on sources that carry a fix already only that fix, a clear error when it is not named."""
    chosen = list(dict.fromkeys(fixes.named(v) for v in variants))
    if not chosen:
        raise NavfnInputError("no variant to test")
    carried = carried_fix(src)
    if carried is None:
        return chosen
    # a contributor's branch: its NavFn as it is is the carried fix's
    if carried not in chosen:
        what = ("there is no NavFn as shipped to test" if all(f.shipped for f in chosen) else
                f"there is no NavFn as shipped to patch with {', '.join(f.name for f in chosen if not f.shipped)}")
        raise NavfnInputError(f"{src}: these sources carry the fix already ({fix_patch(src, carried).name} of "
                              f"patches/{carried.patches}/ applies to them in reverse): {what}; use --variant "
                              f"{carried.name}")
    return [carried]


def run_nav2_tests(nav2_src, out, variants=VARIANTS, tc: Optional[Toolchain] = None) -> dict:
    """Build each of Nav2's NavFn tests for each variant (a fix's name or
    :class:`~navfn_smt.spec.planner.Fix`: as shipped, or a patched fix of
    :data:`navfn_smt.spec.fixes.PATCHED`) into ``out`` and run it; returns the report (also
    ``out/nav2-tests.json``).  The folder is written whole or not at all."""
    src = find_sources(nav2_src)
    out = Path(out)
    if out.exists() and not (out / "nav2-tests.json").is_file():
        raise NavfnInputError(f"{out}: exists and is not a folder of Nav2's tests (no nav2-tests.json); name a new folder")
    shipped = {t.name for t in nav2_tests(src)}
    chosen = _chosen(src, variants)
    carried = carried_fix(src)
    variants = tuple(f.name for f in chosen)
    tc = replace(tc or toolchain(), std=cxx_standard(src))
    tc.check()
    runner = tc.runner()
    with atomic_folder(out) as tmp:
        (tmp / "oracle").mkdir()
        roots = {f.name: _root(src, f, tmp) for f in chosen}
        # the shipped tests and those each fix's patch adds: a test of a patch runs as shipped
        # and patched, where it should fail as shipped and pass patched; as shipped, the tests of
        # every fix's patch run (those of the fixes not chosen too, where their patch applies)
        others = {f.name: _root(src, f, tmp) for f in fixes.PATCHED
                  if any(c.shipped for c in chosen) and f not in chosen and fix_skipped(src, f) is None}
        found = _variant_tests(src, {**roots, **others})
        tests = {v: found[v] for v in roots}
        jobs, names = _programs(src, roots, tests, tmp)
        compiler = Compiler(tc, {src: ROOT_NAMES["src"], HERE: ROOT_NAMES["package"], tmp: ROOT_NAMES["build"],
                                 googletest(): "/googletest"}, cache_dir())
        compile_all(compiler, jobs, list(jobs), tmp)
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
            "programs": _programs_record(tests, found, shipped),
            "source_sha256": {str(s.relative_to(s.parents[2])): sha256_of(s) for ts in tests.values() for t in ts
                              for s in t.sources},
            "variants": list(variants), "results": results,
            **({"sources_carry_fix": True, "sources_carry": carried.name} if carried is not None else {}),
            **_patches(src, chosen),
        }
        for stale in (tmp / "oracle", *(tmp / f.name for f in fixes.PATCHED)):
            shutil.rmtree(stale, ignore_errors=True)
        (tmp / "nav2-tests.json").write_text(json.dumps(doc, indent=1) + "\n", encoding="utf-8")
    return doc


def _programs_record(tests: dict, found: dict, shipped: set) -> dict:
    """The report's ``programs``: each test run (``tests``, by variant), its sources, whether it
    makes the plugin, and where it is from: the sources, or a fix's patch (``fix`` then names
    the fix whose tree declares it in ``found``)."""
    origin = {t.name: v for v in found if not fixes.named(v).shipped for t in found[v]}
    out = {}
    for ts in tests.values():
        for t in ts:
            if t.name not in out:
                out[t.name] = {"sources": [s.name for s in t.sources], "plugin": t.plugin,
                               "from": "the sources" if t.name in shipped else PATCH_TESTS,
                               **({} if t.name in shipped else {"fix": origin[t.name]})}
    return out


def _patches(src: Path, chosen) -> dict:
    """What the report records of the patches: ``patches`` by fix name; ``fix_patch``, the one of
    the fix of docs/fix.md (the key its readers know)."""
    patched = [f for f in chosen if not f.shipped]
    if not patched:
        return {}
    out = {"patches": {f.name: {"folder": f"patches/{f.patches}", "file": fix_patch(src, f).name,
                                "sha256": sha256_of(fix_patch(src, f))} for f in patched}}
    if THE_FIX in patched:
        out["fix_patch"] = {k: out["patches"][THE_FIX.name][k] for k in ("file", "sha256")}
    return out


def without_fix(doc: dict, r: dict) -> bool:
    """Whether the result ``r`` is of a test a fix's patch adds, run as shipped (where it is
    meant to fail: it shows what the fix changes)."""
    return fixes.named(r["variant"]).shipped and doc["programs"][r["program"]]["from"] == PATCH_TESTS


def failed(doc: dict) -> list[dict]:
    """The results of a report that are not passes where a pass is due: every test patched,
    and the sources' own tests as shipped."""
    return [r for r in doc["results"] if r["status"] != PASSED and not without_fix(doc, r)]
