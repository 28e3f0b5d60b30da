"""The candidate fix cycles-only (spec/cycles_only.py, patches/navfn-cycles-only/) on the C++
side: its patches change the two cycle limits of calcNavFn* and nothing else, an oracle build
gives its three programs (navfn-cycles-only, navfn-plugin-cycles-only, navfn-plain-cycles-only)
as it gives the fixed fix's, the patched C++ equals the spec with that fix on every case (where
the raised limit acts too), Nav2's own tests pass patched, and the patched plugin equals the model."""

from __future__ import annotations

import json
import re
import shutil
import subprocess
from dataclasses import replace
from pathlib import Path

import pytest

from navfn_smt.cli import main
from navfn_smt.errors import NavfnInputError
from navfn_smt.maps.suite import discover, load_map
from navfn_smt.spec import fixes
from navfn_smt.spec.planner import cycle_limit
from navfn_smt.under_test import PlannerUnderTest

from conftest import CANDIDATE_DISTROS, DISTROS

REPO = Path(__file__).resolve().parent.parent
PACKAGE = REPO / "src" / "navfn_smt"
EXAMPLE = PACKAGE / "examples" / "suite"
CX = REPO / "tests" / "data" / "counterexamples"
CYCLES = fixes.named("cycles-only")
PATCHES = PACKAGE / "patches" / CYCLES.patches
NAVFN_CPP = "nav2_navfn_planner/src/navfn.cpp"
LIMIT = "std::max(nx * ny / 20, nx + ny)"


# --------------------------------------------------------------------------- the registry's programs
def test_every_patched_fix_gives_three_programs_and_the_fix_of_docs_keeps_its_names():
    from navfn_smt.oracle import build as B
    from navfn_smt.oracle.client import navfn_program, plugin_program

    assert B.FIXED_PROGRAMS == ("navfn-fixed", "navfn-plugin-fixed", "navfn-plain-fixed")
    assert B.fix_programs(CYCLES) == ("navfn-cycles-only", "navfn-plugin-cycles-only", "navfn-plain-cycles-only")
    assert {p for f in fixes.PATCHED for p in B.fix_programs(f)} <= set(B.PROGRAMS)
    assert B.PATCHES == PACKAGE / "patches" / "navfn-fix" and B.patches_of(CYCLES) == PATCHES
    assert (navfn_program("fixed"), navfn_program("fixed", traced=False)) == ("navfn-fixed", "navfn-plain-fixed")
    assert (navfn_program(CYCLES), navfn_program(CYCLES, traced=False), plugin_program(CYCLES)) == (
        "navfn-cycles-only", "navfn-plain-cycles-only", "navfn-plugin-cycles-only")
    assert (navfn_program(fixes.AS_SHIPPED), plugin_program("original")) == ("navfn-traced", "navfn-plugin")


def test_no_command_compares_a_variant_name():
    """The rule: a variant's name is parsed (fixes.named) or written, never compared: the code asks
    the Fix value (shipped, patches, fallback) or iterates fixes.PATCHED."""
    compared = re.compile(r"""(==|!=)\s*["'](fixed|original|cycles-only)["']|["'](fixed|original|cycles-only)["']\s*(==|!=)""")
    files = [*(PACKAGE / "oracle").glob("*.py"), *(PACKAGE / "commands").glob("*.py"), PACKAGE / "bench.py"]
    found = [f"{f.name}:{n}: {line.strip()}" for f in files
             for n, line in enumerate(f.read_text().splitlines(), 1) if compared.search(line)]
    assert found == []


# --------------------------------------------------------------------------- (a) the patches
def test_there_is_one_patch_per_distribution_touching_navfn_cpp_only():
    assert sorted(p.stem for p in PATCHES.glob("*.patch")) == sorted(DISTROS)
    for p in PATCHES.glob("*.patch"):
        text = p.read_text()
        assert [line for line in text.splitlines() if line.startswith(("--- ", "+++ "))] == [
            f"--- a/{NAVFN_CPP}", f"+++ b/{NAVFN_CPP}"], p.name
        assert "navfn-smt" not in text.lower() and "navfn_smt" not in text.lower(), p.name


@pytest.mark.parametrize("distro", DISTROS)
def test_each_patch_applies_without_fuzz_and_changes_exactly_the_two_cycle_limits(nav2_src, tmp_path, distro):
    tree = tmp_path / distro
    shutil.copytree(nav2_src / distro / "nav2_navfn_planner", tree / "nav2_navfn_planner")
    r = subprocess.run(["patch", "-p1", "-F0", "-i", str(PATCHES / f"{distro}.patch")], cwd=tree,
                       capture_output=True, text=True)
    assert r.returncode == 0 and "fuzz" not in r.stdout and "offset" not in r.stdout, r.stdout + r.stderr
    shipped = (nav2_src / distro / NAVFN_CPP).read_text().splitlines()
    patched = (tree / NAVFN_CPP).read_text().splitlines()
    # the patched file is the shipped one with the two limits replaced and comment lines added
    code = [line for line in patched if not line.strip().startswith("//")]
    changed = [(a, b) for a, b in zip([line for line in shipped if not line.strip().startswith("//")], code) if a != b]
    assert len(code) == len([line for line in shipped if not line.strip().startswith("//")])
    assert [a.split("(", 1)[0].strip() for a, _ in changed] == ["return propNavFnDijkstra", "return propNavFnAstar"]
    assert [b for _, b in changed] == [a.replace(LIMIT, "nx * ny") for a, _ in changed]
    assert all(LIMIT in a for a, _ in changed)
    # the static create_nav_plan_astar keeps Nav2's limit: only calcNavFn* change
    assert sum(LIMIT in line for line in patched) == sum(LIMIT in line for line in shipped) - 2 == 1


# --------------------------------------------------------------------------- the builds
def test_a_build_gives_the_cycles_only_programs_and_records_each_fixs_patch(builds):
    for distro in CANDIDATE_DISTROS:
        doc, folder = builds[distro]
        assert {"navfn-cycles-only", "navfn-plugin-cycles-only", "navfn-plain-cycles-only",
                "navfn-fixed", "navfn-plugin-fixed", "navfn-plain-fixed"} <= set(doc["programs"]), distro
        record = doc["patches"]["cycles-only"]
        assert record["file"] == f"{distro}.patch" and record["folder"] == "patches/navfn-cycles-only"
        assert record["applied_by"] == "this build" and len(record["programs"]) == 3
        assert doc["fix_patch"]["file"] == f"{distro}.patch" == doc["patches"]["fixed"]["file"]
        # the NavFn driver calls the patched calcNavFn*, traced or not; the plugin needs no define
        assert "NAVFN_SMT_CALC_NAVFN" in doc["defines"]["navfn-cycles-only"]
        assert "NAVFN_SMT_TRACED" in doc["defines"]["navfn-cycles-only"]
        assert "NAVFN_SMT_CALC_NAVFN" in doc["defines"]["navfn-plain-cycles-only"]
        assert "NAVFN_SMT_CALC_NAVFN" not in doc["defines"]["navfn-plain"]


def _patches_without(tmp_path, text=None) -> Path:
    """A patches folder with the fixed fix's patches, and for cycles-only Rolling's patch
    replaced by ``text`` (None: none at all)."""
    root = tmp_path / "patches"
    shutil.copytree(PACKAGE / "patches" / "navfn-fix", root / "navfn-fix")
    (root / CYCLES.patches).mkdir()
    if text is not None:
        (root / CYCLES.patches / "rolling.patch").write_text(text)
    return root


@pytest.mark.parametrize("kind", ["missing", "does not apply"])
def test_a_fix_whose_patch_is_missing_or_does_not_apply_is_left_out_and_named(nav2_src, tmp_path, monkeypatch,
                                                                                kind, capsys):
    from navfn_smt.oracle import build as B
    from navfn_smt.oracle.client import Oracle, PluginOracle

    text = None if kind == "missing" else (PATCHES / "rolling.patch").read_text().replace(
        "setupNavFn(true);", "setupNavFn(false);")
    monkeypatch.setattr(B, "PATCHES_ROOT", _patches_without(tmp_path, text))
    out = tmp_path / "b"
    doc = B.build(nav2_src / "rolling", out, programs=("navfn-plain", "navfn-cycles-only", "navfn-plugin-cycles-only"))
    assert doc["programs"] == ["navfn-plain"]
    why = doc["skipped"]["navfn-cycles-only"]
    says = "no patch of the cycles-only fix for rolling" if kind == "missing" else "does not apply"
    assert says in why and doc["skipped"]["navfn-plugin-cycles-only"] == why and "patches" not in doc
    with pytest.raises(NavfnInputError, match=f"no navfn-cycles-only \\(left out: .*{says}"):
        Oracle(out, fix=CYCLES)
    with pytest.raises(NavfnInputError, match="no navfn-plugin-cycles-only \\(left out"):
        PluginOracle(out, CYCLES)
    assert main(["difftest", str(EXAMPLE), "--oracle", str(out), "--variant", "cycles-only"]) == 2
    assert says in capsys.readouterr().err


def test_the_commands_refuse_what_a_patched_fix_cannot_do(capsys):
    for argv, says in ((["difftest", "--variant", "cycles-only"], "give --oracle DIR"),
                       (["difftest", "--variant", "cycles-only", "--level", "costmap", "--oracle", "x"],
                        "does not touch the costmap"),
                       (["difftest", "--variant", "cycles-only", "--unbounded", "--oracle", "x"], "exclude each other"),
                       (["bench", "--variant", "cycles-only"], "give --oracle DIR")):
        assert main(argv) == 2, argv
        assert says in capsys.readouterr().err, argv


# --------------------------------------------------------------------------- (b) live, every distribution
def _acted(folder, suite) -> tuple[int, int]:
    """How many of the suite's case runs (both modes) the patched C++ ran past Nav2's cycle limit
    max(nx*ny/20, nx+ny), and how many the spec with the fix says its propagation acted on."""
    from navfn_smt.oracle.client import Oracle

    be = PlannerUnderTest(CYCLES).backend("jit")
    cpp = spec = 0
    with Oracle(folder, fix=CYCLES) as oracle:
        for d in discover(suite):
            m = load_map(d, suite)
            ny, nx = m.costs.shape
            planner = be.prepare(m.costs)
            for astar in (True, False):
                cpp += sum(r.cycles > cycle_limit(nx, ny) for r in oracle.plan(m.costs, m.cases, astar))
                spec += sum("propagation" in planner.run((sx, sy), (gx, gy), astar, trace=False).extra.get("fix", [])
                            for sx, sy, gx, gy in m.cases.tolist())
    return cpp, spec


@pytest.mark.parametrize("distro", CANDIDATE_DISTROS)
def test_the_patched_cpp_equals_the_cycles_only_spec_where_the_limit_acts_too(builds, distro, tmp_path, capsys):
    from navfn_smt.difftest.live import run_live
    from navfn_smt.oracle.client import Oracle

    doc, folder = builds[distro]
    planner = PlannerUnderTest.of_build(folder, CYCLES)
    for suite in (CX,):  # the example suite through the command line below
        with Oracle(folder, fix=CYCLES) as oracle:
            assert oracle.program == "navfn-cycles-only" and oracle.traced
            s = run_live(suite, ("astar", "dijkstra"), "jit", oracle, planner=planner).as_dict()
        assert s["failed"] == 0 and s["passed"] > 0, s
    cpp, spec = _acted(folder, EXAMPLE)
    assert cpp == spec > 0, (cpp, spec)  # 12 of the example suite's 4,400 case runs go past Nav2's limit
    assert main(["difftest", str(EXAMPLE), "--oracle", str(folder), "--variant", "cycles-only", "--quiet",
                 "--json", str(tmp_path / "r.json")]) == 0
    summary = json.loads((tmp_path / "r.json").read_text())
    assert summary["failed"] == 0 and summary["passed"] == 4400, summary


def test_the_plain_cycles_only_program_plans_as_the_traced_one(builds):
    from navfn_smt.oracle.client import Oracle

    _, folder = builds["rolling"]
    sm = load_map(CX / "start-reached-dijkstra-7x7")
    with Oracle(folder, fix=CYCLES) as traced, Oracle(folder, traced=False, fix="cycles-only") as plain:
        assert (plain.program, plain.traced) == ("navfn-plain-cycles-only", False)
        for astar in (True, False):
            for a, b in zip(traced.plan(sm.costs, sm.cases, astar), plain.plan(sm.costs, sm.cases, astar)):
                assert a.path.tobytes() == b.path.tobytes() and a.potential.tobytes() == b.potential.tobytes()
                assert a.start_reached == b.start_reached and b.cycles == -1


# --------------------------------------------------------------------------- (c) Nav2's own tests
@pytest.mark.parametrize("distro", ["rolling"])
def test_nav2s_own_tests_pass_with_cycles_only(builds, tmp_path, distro, capsys):
    from navfn_smt.oracle.nav2_tests import googletest

    try:
        googletest()
    except NavfnInputError as e:
        pytest.skip(str(e))
    rc = main(["oracle", "nav2-tests", builds[distro][0]["sources"], "--variant", "cycles-only", "--out",
               str(tmp_path / "t"), "--json", str(tmp_path / "r.json")])
    doc = json.loads((tmp_path / "r.json").read_text())
    assert rc == 0 and doc["variants"] == ["cycles-only"]
    assert {r["variant"] for r in doc["results"]} == {"cycles-only"}
    assert doc["results"] and all(r["status"] == "passed" for r in doc["results"]), doc["results"]
    assert all(p["from"] == "the sources" for p in doc["programs"].values())  # the patch adds no test
    assert doc["patches"] == {"cycles-only": {"folder": "patches/navfn-cycles-only", "file": f"{distro}.patch",
                                              "sha256": doc["patches"]["cycles-only"]["sha256"]}}
    assert "fix_patch" not in doc
    assert "cycles-only: patches/navfn-cycles-only/" in capsys.readouterr().out


# --------------------------------------------------------------------------- (d) the plugin
def test_the_patched_plugin_equals_the_cycles_only_model(builds, capsys):
    from navfn_smt.difftest.plugin_live import generated_configs, run_plugin_live
    from navfn_smt.oracle.client import PluginOracle

    _, folder = builds["rolling"]
    configs = [replace(c, params=replace(c.params, fix=CYCLES)) for c in generated_configs("rolling", 12, 5, 12)]
    with PluginOracle(folder, CYCLES) as oracle:
        assert oracle.program == "navfn-plugin-cycles-only"
        s = run_plugin_live(configs, oracle, "jit").as_dict()
    assert s["failed"] == 0 and s["passed"] > 100, s
    assert main(["difftest", "--level", "plugin", "--variant", "cycles-only", "--oracle", str(folder),
                 "--configs", "6", "--pairs", "8", "--quiet"]) == 0


# --------------------------------------------------------------------------- Nav2's lint
@pytest.mark.parametrize("distro", ["rolling"])
def test_the_cycles_only_patch_adds_no_finding_of_nav2s_linters(nav2_src, distro):
    from navfn_smt.oracle.lint import lint_fix, uncrustify_config

    try:
        uncrustify_config()
        import cpplint  # noqa: F401
    except (NavfnInputError, ImportError) as e:
        pytest.skip(str(e))
    doc = lint_fix(nav2_src / distro, fix=CYCLES)
    assert doc["fix"] == "cycles-only" and doc["patch"] == f"{distro}.patch"
    assert [(r["file"], r["tool"]) for r in doc["files"]] == [(NAVFN_CPP, "uncrustify"), (NAVFN_CPP, "cpplint")]
    assert all(r["added"] == [] for r in doc["files"]), doc["files"]
