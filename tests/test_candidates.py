"""The candidate fixes compared in docs/fix.md (spec/candidates.py, the fix's two halves in
spec/fix.py, ``navfn-smt fixes``): what each does on the committed far-from-goal gradient trap,
the inclusive near-goal test's change to paths the original returns, the resume fallback's
path, the comparison command, and each patched candidate's C++ against its spec."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from navfn_smt.check import properties as P
from navfn_smt.cli import main
from navfn_smt.maps.suite import discover, load_map
from navfn_smt.search.kinds import FAR, TRAP_FLOOR, KINDS
from navfn_smt.spec import candidates as C
from navfn_smt.spec import fixes
from navfn_smt.spec.extraction import ExtractionExit
from navfn_smt.spec.planner import plan
from navfn_smt.under_test import PlannerUnderTest


REPO = Path(__file__).resolve().parent.parent
EXAMPLE = REPO / "src" / "navfn_smt" / "examples" / "suite"
TRAP = REPO / "tests" / "data" / "counterexamples" / "far-trap-dijkstra-6x5"
SHIPPED_FAIL = ("original", "inclusive", "propagation", "cycles-only")  # the trap stays
PLANS = ("descent", "fixed", "resume")


def _trap():
    sm = load_map(TRAP)
    sx, sy, gx, gy = (int(v) for v in sm.cases[0])
    return sm.costs, (sx, sy), (gx, gy)


# --------------------------------------------------------------------------- the far-from-goal trap
@pytest.mark.fast
def test_the_far_trap_is_one_shipped_and_with_the_inclusive_test_and_the_descents_plan_it():
    costs, s, g = _trap()
    doc = json.loads((TRAP / "counterexample.json").read_text())
    assert doc["kind"] == "far-trap" and doc["variant"] == "inclusive" and doc["mode"] == "dijkstra"
    for name in SHIPPED_FAIL:
        r = P.run(costs, s, g, False, fix=fixes.named(name))
        detail = KINDS["far-trap"].judge(r)
        assert detail is not None, name
        assert detail["start_potential"] >= FAR and detail["lowest_potential"] >= TRAP_FLOOR
    for name in PLANS:
        r = plan(costs, s, g, False, fix=fixes.named(name))
        assert r.exit is ExtractionExit.NEAR_GOAL and tuple(r.path[-1].tolist()) == g, name
        assert tuple(r.path[0].tolist()) == s, name
        assert r.extra["fix"] == ["descent"], name


@pytest.mark.fast
def test_the_far_trap_judge_refuses_a_trap_near_the_goal_and_a_lethal_goal():
    """The committed 5x5 A* trap circles a cell of potential 50 beside the goal: incomplete, not
    far; the trap map with its goal made lethal is no far trap either."""
    sm = load_map(REPO / "tests" / "data" / "counterexamples" / "incomplete-astar-5x5")
    sx, sy, gx, gy = (int(v) for v in sm.cases[0])
    near = P.run(sm.costs, (sx, sy), (gx, gy), True)
    assert P.complete(near) is not None and KINDS["far-trap"].judge(near) is None
    costs, s, g = _trap()
    lethal = costs.copy()
    lethal[g[1], g[0]] = 254
    r = P.run(lethal, s, g, False)
    assert KINDS["far-trap"].judge(r) is None


# --------------------------------------------------------------------------- inclusive and resume
@pytest.mark.fast
def test_the_inclusive_test_cuts_paths_the_original_returns_at_a_potential_of_exactly_50():
    """Where the original plans, the inclusive test's path is the original's cut where it first
    reads a potential of exactly COST_NEUTRAL, then the goal: on the example suite it changes
    more than a third of the original's paths, each one that way."""
    inclusive = fixes.named("inclusive")
    planned = changed = 0
    for d in discover(EXAMPLE)[:6]:
        sm = load_map(d, EXAMPLE)
        for sx, sy, gx, gy in sm.cases[:60].tolist():
            o = plan(sm.costs, (sx, sy), (gx, gy), True)
            if not len(o.path):
                continue
            planned += 1
            i = plan(sm.costs, (sx, sy), (gx, gy), True, fix=inclusive)
            if i.path.tobytes() == o.path.tobytes():
                continue
            changed += 1
            assert len(i.path) < len(o.path)
            assert i.path[:-1].tobytes() == o.path[: len(i.path) - 1].tobytes()
            assert tuple(i.path[-1].tolist()) == (gx, gy)
    assert planned > 100 and changed * 3 > planned, (planned, changed)


@pytest.mark.fast
def test_resume_keeps_the_gradients_points_before_it_got_stuck():
    costs, s, g = _trap()
    ny, nx = costs.shape
    r = plan(costs, s, g, False)
    watch = C.CellWatch()
    from navfn_smt.spec.extraction import calc_path

    calc_path(r.potential.ravel().tolist(), nx, ny, s, g, 4 * nx, watch=watch)
    at = C.stuck_at(watch.cells)
    assert 0 < at < 4 * nx
    resumed = plan(costs, s, g, False, fix=fixes.named("resume"))
    kept = np.array(list(zip(watch.xs, watch.ys)), np.float32)[:at]
    assert resumed.path[:at].tobytes() == kept.tobytes()
    cell = watch.cells[at]
    assert tuple(resumed.path[at].tolist()) == (cell % nx, cell // nx)
    assert C.stuck_at([]) == -1 and C.stuck_at([5, 5, 6, 5, 6]) == 2


# --------------------------------------------------------------------------- the comparison command
@pytest.mark.fast
def test_the_comparison_command_counts_what_each_candidate_changes(tmp_path, capsys):
    out = tmp_path / "fixes.json"
    assert main(["fixes", "--variant", "fixed", "inclusive", "--targets", "x86-64", "--search-seconds", "0",
                 "--configs", "3", "--quiet", "--json", str(out)]) == 0
    rows = {r["variant"]: r for r in json.loads(out.read_text())["rows"]}
    assert rows["fixed"]["suite"]["changed"] == 0 and rows["fixed"]["suite"]["planned"] > 0
    assert rows["inclusive"]["suite"]["changed"] > 0
    assert rows["fixed"]["committed"]["far-trap"] == [0, 1] and rows["inclusive"]["committed"]["far-trap"] == [1, 1]
    assert "| fixed | x86-64 |" in capsys.readouterr().out


@pytest.mark.fast
@pytest.mark.parametrize("argv, says", [(["--seeds", "0"], "--seeds"), (["--variant", "nope"], "invalid choice"),
                                        (["--configs", "-1"], "--configs")])
def test_the_comparison_command_refuses_bad_input(argv, says, capsys):
    with pytest.raises(SystemExit) if says == "invalid choice" else _no_raise():
        assert main(["fixes", *argv]) == 2
    assert says in capsys.readouterr().err


class _no_raise:
    def __enter__(self):
        return self

    def __exit__(self, *exc):
        return False


# --------------------------------------------------------------------------- the C++ of each candidate
@pytest.mark.parametrize("name", ["propagation", "descent", "inclusive"])
def test_each_patched_candidates_cpp_equals_its_spec(builds, name):
    """Rolling's C++ with each candidate's patch equals the spec with that candidate, bit for bit,
    on the committed counterexamples (the failures the candidates act on); the whole fix is
    compared on every distribution by tests/test_fix.py, and the shared suite by hand
    (docs/fix.md)."""
    from navfn_smt.difftest.live import run_live
    from navfn_smt.oracle.client import Oracle

    fix = fixes.named(name)
    _, folder = builds["rolling"]
    planner = PlannerUnderTest.of_build(folder, fix)
    for suite in (TRAP.parent,):
        with Oracle(folder, fix=fix) as oracle:
            s = run_live(suite, ("astar", "dijkstra"), "jit", oracle, planner=planner).as_dict()
        assert s["failed"] == 0 and s["passed"] > 0, (name, s)


def test_the_far_trap_fails_in_the_shipped_and_inclusive_cpp_and_the_descents_plan_it(builds):
    from navfn_smt.oracle.client import Oracle

    costs, s, g = _trap()
    _, folder = builds["rolling"]
    for name in ("original", "inclusive", "descent", "fixed"):
        with Oracle(folder, fix=name) as oracle:
            (r,) = oracle.plan(costs, [(*s, *g)], False)
        assert r.potential.ravel()[s[1] * costs.shape[1] + s[0]] >= FAR
        assert bool(len(r.path)) == (name in PLANS), name


# --------------------------------------------------------------------------- one statement of the guarantee
@pytest.mark.fast
def test_the_guarantee_is_stated_once_in_the_same_words_everywhere():
    """README.md and docs/fix.md quote the guarantee check prints word for word, and no page keeps
    the shorter headline without its hypotheses."""
    from navfn_smt.spec.fixes import GUARANTEE

    def words(text: str) -> str:
        return " ".join(text.replace("> ", " ").split())

    for page in (REPO / "README.md", REPO / "docs" / "fix.md"):
        assert words(GUARANTEE) in words(page.read_text()), page.name
    # every run-time condition on the chains of the predicates that carry the fix's properties is named in
    # it, and its count of trusted steps is theirs
    from navfn_smt.check.runner import conditions, induction_status, inductive
    from navfn_smt.check.common import _verdict_of
    from navfn_smt.under_test import PlannerUnderTest

    from navfn_smt.spec.fix import FIX

    fixed = PlannerUnderTest(fix=FIX)
    for name in inductive(fixed):
        if name in dict(FIX.proved):
            for c in conditions(name, fixed):
                assert c.split(": ", 1)[0] in GUARANTEE, c[:60]
    both = induction_status("complete", _verdict_of(), fixed)["trusted"] + \
        induction_status("start-reached", _verdict_of(), fixed)["trusted"]
    assert f"conditional, with {len(set(both))} trusted steps" in GUARANTEE
    assert "IEEE float32" in GUARANTEE
    pages = [REPO / "README.md", *(REPO / "docs").rglob("*.md")]
    shorter = "a start 4-connected to the goal gets a path, for every map size"
    assert [p.name for p in pages if shorter in words(p.read_text())] == []


# --------------------------------------------------------------------------- the two pull requests
PATCHES = REPO / "src" / "navfn_smt" / "patches"
WARN_6308 = '"[PathCalc] Path extraction exhausted: npath = %d, max_cycles = %d",'


def _apply(tree: Path, *patches: Path) -> None:
    import subprocess

    for patch in patches:
        r = subprocess.run(["patch", "-p1", "-F0", "-i", str(patch)], cwd=tree, capture_output=True, text=True)
        assert r.returncode == 0 and "fuzz" not in r.stdout, r.stdout + r.stderr


@pytest.mark.parametrize("distro", ["humble", "jazzy", "kilted", "lyrical", "rolling"])
def test_the_two_pull_requests_apply_alone_and_in_turn_and_make_the_fix(nav2_src, tmp_path, distro):
    """Each pull request's patch applies to the sources as shipped; the second applies after the
    first; the two in turn give exactly the files the fix's patch gives; #6308's WARN and its
    level stay as shipped; no patch names this project."""
    import shutil

    one, two, both = (PATCHES / f / f"{distro}.patch" for f in ("navfn-propagation", "navfn-descent", "navfn-fix"))
    trees = {}
    for name, patches in (("one", (one,)), ("two", (two,)), ("turn", (one, two)), ("both", (both,))):
        tree = tmp_path / name
        shutil.copytree(nav2_src / distro / "nav2_navfn_planner", tree / "nav2_navfn_planner")
        _apply(tree, *patches)
        trees[name] = tree
    for f in sorted(p.relative_to(trees["both"]) for p in trees["both"].rglob("*") if p.is_file()):
        assert (trees["turn"] / f).read_bytes() == (trees["both"] / f).read_bytes(), f
    cpp = "nav2_navfn_planner/src/navfn.cpp"
    shipped = (nav2_src / distro / cpp).read_text()
    for tree in trees.values():
        patched = (tree / cpp).read_text()
        assert patched.count(WARN_6308) == shipped.count(WARN_6308)
        level = shipped.split(WARN_6308)[0].rsplit("RCLCPP_", 1)[1].split("(")[0] if WARN_6308 in shipped else None
        if level is not None:
            assert patched.split(WARN_6308)[0].rsplit("RCLCPP_", 1)[1].split("(")[0] == level
    for patch in (one, two, both):
        text = patch.read_text().lower()
        assert "navfn-smt" not in text and "navfn_smt" not in text and "generated with the assistance of ai" in text


# --------------------------------------------------------------------------- evidence where the fix acts
@pytest.mark.fast
def test_the_check_counts_the_control_paths_that_take_each_branch_of_the_fix():
    """fix_branches plans each explored path's seed map again: on the far trap's map the fallback
    gives the path, on a corridor the further call runs, and NavFn as shipped takes neither."""
    from types import SimpleNamespace

    from navfn_smt.check.bounded import Case
    from navfn_smt.check.encoding import interior
    from navfn_smt.check.runner import fix_branches
    from navfn_smt.under_test import FIXED

    costs, s, g = _trap()
    ny, nx = costs.shape
    lethal = frozenset(k for k in interior(nx, ny) if costs.flat[k] == 254)
    case = Case(nx, ny, lethal, s, g, False)
    seed = [int(costs.flat[k]) for k in interior(nx, ny) if k not in lethal]
    cr = SimpleNamespace(case=case, log=[[seed, None, "", ""], [seed, None, "", ""]])
    assert fix_branches(cr, FIXED) == {"paths": 2, "further_call": 0, "fallback_path": 2}
    # a U-shaped corridor of 27 cells on a 15x5 map: the wave needs 26 cycles, the limit is 20
    w, h = 15, 5
    maze = np.full((h, w), 254, np.uint8)
    maze[1, 1:w - 1] = 50
    maze[2, w - 2] = 50
    maze[3, 1:w - 1] = 50
    lethal = frozenset(k for k in interior(w, h) if maze.flat[k] == 254)
    case = Case(w, h, lethal, (1, 3), (1, 1), False)
    seed = [50] * (len(interior(w, h)) - len(lethal))
    got = fix_branches(SimpleNamespace(case=case, log=[[seed, None, "", ""]]), FIXED)
    assert got["further_call"] == 1, got
    shipped = fix_branches(SimpleNamespace(case=case, log=[[seed, None, "", ""]]), PlannerUnderTest())
    assert shipped == {"paths": 1, "further_call": 0, "fallback_path": 0}


@pytest.mark.fast
def test_the_comparison_reads_nav2s_test_reports_and_refuses_what_is_not_one(tmp_path, capsys):
    report = {"distribution": "rolling", "variants": ["original", "propagation"],
              "programs": {"own": {"from": "the sources"}, "added": {"from": "the fix's patch", "fix": "propagation"}},
              "results": [{"program": "own", "case": "A.a", "variant": "original", "status": "passed"},
                          {"program": "own", "case": "A.a", "variant": "propagation", "status": "passed"},
                          {"program": "added", "case": "B.b", "variant": "original", "status": "failed"},
                          {"program": "added", "case": "B.b", "variant": "propagation", "status": "failed"}]}
    good = tmp_path / "r.json"
    good.write_text(json.dumps(report))
    out = tmp_path / "f.json"
    assert main(["fixes", "--variant", "propagation", "--targets", "x86-64", "--search-seconds", "0", "--configs", "1",
                 "--quiet", "--nav2-tests", str(good), "--json", str(out)]) == 0
    (row,) = json.loads(out.read_text())["rows"]
    assert row["nav2_tests"]["rolling"] == {"own": 1, "own_passed_shipped": 1, "own_passed_patched": 1, "added": 1,
                                            "added_failed_shipped": 1, "added_passed_patched": 0}
    bad = tmp_path / "bad.json"
    bad.write_text(json.dumps({"results": []}))
    assert main(["fixes", "--nav2-tests", str(bad)]) == 2
    assert main(["fixes", "--worst-cases", "100"]) == 2
    err = capsys.readouterr().err
    assert "not a report of" in err and "give --oracle DIR" in err and "Traceback" not in err
