"""Nav2's own tests of nav2_navfn_planner (``oracle nav2-tests``), built from ../shared/nav2-src
against NavFn as shipped and with the fix's patch, for every distribution."""

import json
import shutil

import pytest

from navfn_smt.cli import main
from navfn_smt.errors import NavfnInputError

from conftest import DISTROS

# what Nav2's tests say today, per distribution: (program, case) -> (original, fixed).  Rolling's
# and Lyrical's test_max_cycles (Nav2 #6308) expects calcPath(1) == 0 on a free 20x20 map: the
# descent keeps calcPath's budget, so it passes patched too.  The tests the two pull requests add
# (patches/navfn-propagation/: test_navfn_propagation_limit on NavFn and
# test_navfn_planner_propagation_limit on the planner plugin with a stubbed node;
# patches/navfn-descent/: test_navfn_descent) all fail as shipped and pass patched.
DYNAMIC = ("test_dynamic_parameters", "NavfnTest.testDynamicParameter")
MAX_CYCLES = ("test_max_cycles", "NavFnMaxCyclesTest.PathExtractionRespectsCycleLimit")
PROPAGATION = "test_navfn_propagation_limit"
PLUGIN = "test_navfn_planner_propagation_limit"
DESCENT = "test_navfn_descent"
FIX_TESTS = {(PROPAGATION, "NavFnPropagationLimitTest.DijkstraReachesTheStartAtTheEndOfALongCorridor"): ("failed", "passed"),
             (PROPAGATION, "NavFnPropagationLimitTest.AstarReachesTheStartAtTheEndOfALongCorridor"): ("failed", "passed"),
             (PLUGIN, "NavfnPlannerPropagationLimitTest.PlansTheLengthOfALongCorridor"): ("failed", "passed"),
             (PLUGIN, "NavfnPlannerPropagationLimitTest.PlanWithToleranceEndsAtTheGoalNotAcrossTheWall"): ("failed", "passed"),
             (DESCENT, "NavFnDescentTest.DijkstraPlansWhereTheGradientCirclesBesideTheGoal"): ("failed", "passed"),
             (DESCENT, "NavFnDescentTest.AstarPlansWhereTheGradientFailsNearTheGoal"): ("failed", "passed"),
             (DESCENT, "NavFnDescentTest.DescentKeepsCalcPathsBudget"): ("failed", "passed")}
# the further propagation call polls the cancel checker (Jazzy on: Humble's NavFn takes none)
CANCEL = {(PROPAGATION, "NavFnPropagationLimitTest.FurtherPropagationStopsWhenCancelled"): ("failed", "passed")}
KNOWN = {d: {DYNAMIC: ("passed", "passed"), **({MAX_CYCLES: ("passed", "passed")} if d in ("lyrical", "rolling") else {}),
             **FIX_TESTS, **(CANCEL if d != "humble" else {})} for d in DISTROS}


def _gtest():
    from navfn_smt.oracle.nav2_tests import googletest

    try:
        googletest()
    except NavfnInputError as e:
        pytest.skip(str(e))


@pytest.mark.parametrize("distro", DISTROS)
def test_nav2s_own_tests_pass_as_shipped_and_say_what_the_fix_changes(builds, tmp_path, distro, capsys):
    """Every gtest of the distribution's nav2_navfn_planner/test is built and run, as shipped and
    patched; each case's outcome is the one KNOWN states; the JSON report says the same."""
    _gtest()
    nav2_src = builds[distro][0]["sources"]
    rc = main(["oracle", "nav2-tests", nav2_src, "--out", str(tmp_path / "t"), "--json", str(tmp_path / "r.json")])
    doc = json.loads((tmp_path / "r.json").read_text())
    got = {}
    for r in doc["results"]:
        got.setdefault((r["program"], r["case"]), {})[r["variant"]] = r["status"]
    assert {k: (v["original"], v["fixed"]) for k, v in got.items()} == KNOWN[distro]
    assert doc["programs"][PROPAGATION]["from"] == doc["programs"][DESCENT]["from"] == "the fix's patch"
    # each added test is named after the pull request (the patched fix) whose patch adds it
    assert doc["programs"][PLUGIN] == {"sources": [f"{PLUGIN}.cpp"], "plugin": True, "from": "the fix's patch",
                                       "fix": "propagation"}
    assert doc["programs"][DESCENT]["fix"] == "descent"
    assert doc["programs"][DYNAMIC[0]]["from"] == "the sources"
    # a failure counts only where a pass is due: the patch's tests as shipped do not
    assert rc == 0
    assert doc["distribution"] == distro and doc["fix_patch"]["file"] == f"{distro}.patch"
    out = capsys.readouterr().out
    fixes = sum(1 for k in KNOWN[distro] if k[0].startswith("test_navfn"))
    assert f"the fix's own tests as shipped: {fixes} of {fixes} fail" in out
    if distro in ("lyrical", "rolling"):
        assert ("| test_max_cycles | the sources | NavFnMaxCyclesTest.PathExtractionRespectsCycleLimit | passed | passed |"
                in out)


def test_a_parameter_check_seeded_out_fails_nav2s_dynamic_parameter_test(nav2_src, tmp_path):
    """The stubbed parameter service runs the plugin's own validation: with Rolling's check of
    a tolerance above 0 weakened, Nav2's test sees -1.0 accepted and fails."""
    from navfn_smt.oracle.nav2_tests import run_nav2_tests

    _gtest()
    src = tmp_path / "src"
    for pkg in ("nav2_navfn_planner", "nav2_core", "nav2_costmap_2d"):
        shutil.copytree(nav2_src / "rolling" / pkg, src / pkg)
    handler = src / "nav2_navfn_planner" / "src" / "parameter_handler.cpp"
    text = handler.read_text()
    assert text.count("parameter.as_double() <= 0.0") == 1
    handler.write_text(text.replace("parameter.as_double() <= 0.0", "parameter.as_double() <= -10.0"))
    doc = run_nav2_tests(src, tmp_path / "t", ("original",))
    status = {(r["program"], r["case"]): (r["status"], r.get("message", "")) for r in doc["results"]}
    # the patches' tests ran (as shipped, every one of them fails) and Nav2's own passed
    assert status[MAX_CYCLES][0] == "passed" and {status[k][0] for k in FIX_TESTS} == {"failed"}
    assert status[DYNAMIC][0] == "failed" and "test.tolerance" in status[DYNAMIC][1], status


def test_sources_without_nav2s_tests_are_refused_clearly(nav2_src, tmp_path, capsys):
    src = tmp_path / "src"
    for pkg in ("nav2_navfn_planner", "nav2_core", "nav2_costmap_2d"):
        shutil.copytree(nav2_src / "rolling" / pkg, src / pkg)
    shutil.rmtree(src / "nav2_navfn_planner" / "test")
    assert main(["oracle", "nav2-tests", str(src), "--out", str(tmp_path / "t")]) == 2
    err = capsys.readouterr().err
    assert "nav2_navfn_planner/test/CMakeLists.txt" in err and "Traceback" not in err
    assert not (tmp_path / "t").exists()


# --------------------------------------------------------------------------- Nav2's lint
def _linters():
    from navfn_smt.oracle.lint import uncrustify_config

    try:
        uncrustify_config()
        import cpplint  # noqa: F401
    except (NavfnInputError, ImportError) as e:
        pytest.skip(str(e))


@pytest.mark.parametrize("distro", DISTROS)
def test_the_fix_adds_no_finding_of_nav2s_linters(nav2_src, distro):
    """ament's uncrustify configuration and ament_cpplint's arguments find nothing in the
    patched files that the shipped ones do not have, nor in the test file the patch adds."""
    from navfn_smt.oracle.lint import lint_fix

    _linters()
    doc = lint_fix(nav2_src / distro)
    assert [(r["file"].rsplit("/", 1)[1], r["tool"]) for r in doc["files"]] == [
        ("navfn.hpp", "uncrustify"), ("navfn.hpp", "cpplint"), ("navfn.cpp", "uncrustify"), ("navfn.cpp", "cpplint"),
        *((f"{t}.cpp", tool) for t in (DESCENT, PLUGIN, PROPAGATION) for tool in ("uncrustify", "cpplint"))]
    assert all(r["added"] == [] for r in doc["files"]), doc["files"]


def test_lint_names_what_a_patch_adds_and_fails(nav2_src, tmp_path, capsys):
    """The fix's patch with one line written against the style (``int next=stc;``): each linter
    finds it, on that line of the patched file, and the command exits 1."""
    from navfn_smt.oracle.build import PATCHES

    _linters()
    text = (PATCHES / "rolling.patch").read_text()
    assert text.count("+    int next = stc;\n") == 1
    seeded = tmp_path / "seeded.patch"
    seeded.write_text(text.replace("+    int next = stc;\n", "+    int next=stc;\n"))
    assert main(["oracle", "lint", str(nav2_src / "rolling"), "--patch", str(seeded), "--json", str(tmp_path / "r.json")]) == 1
    doc = json.loads((tmp_path / "r.json").read_text())
    added = {r["tool"]: r["added"] for r in doc["files"] if r["file"].endswith("navfn.cpp")}
    assert [f["message"] for f in added["cpplint"]] == ["Missing spaces around =  [whitespace/operators] [4]"]
    assert len(added["uncrustify"]) == 1 and "int next = stc;" in added["uncrustify"][0]["message"]
    assert added["cpplint"][0]["line"] == added["uncrustify"][0]["line"]
    assert "2 findings added by the patch" in capsys.readouterr().out
