"""The fix (spec/fix.py, patches/navfn-fix/): it never changes a path the original returns, it
returns a path from every reached start and reaches every connected start, its compiled and
symbolic forms equal the spec, and the patched C++ of every distribution equals the spec."""

from __future__ import annotations

import json
import subprocess
from pathlib import Path

import numpy as np
import pytest

from navfn_smt.backends import get_backend
from navfn_smt.check import properties as P
from navfn_smt.cli import main
from navfn_smt.errors import NavfnInputError
from navfn_smt.maps.regions import reaches, regions
from navfn_smt.maps.suite import load_map
from navfn_smt.under_test import FIXED, PlannerUnderTest
from navfn_smt.spec import fix as F
from navfn_smt.spec import fixes
from navfn_smt.spec.constants import COST_OBS, POT_HIGH
from navfn_smt.spec.costs import add_border
from navfn_smt.spec.extraction import ExtractionExit
from navfn_smt.spec.planner import path_cycle_limit, plan

REPO = Path(__file__).resolve().parent.parent
CX = REPO / "tests" / "data" / "counterexamples"
DIAG = REPO / "tests" / "data" / "diagnose"
EXAMPLE = REPO / "src" / "navfn_smt" / "examples" / "suite"
PATCHES = REPO / "src" / "navfn_smt" / "patches" / "navfn-fix"
DISTROS = ("humble", "jazzy", "kilted", "lyrical", "rolling")
FAILING = ("incomplete-astar-5x5", "incomplete-dijkstra-5x6", "start-reached-astar-7x7", "start-reached-dijkstra-7x7",
           "unreached-astar-7x8", "unreached-dijkstra-7x8", "far-trap-dijkstra-6x5")


def _maps(seed: int, count: int):
    """Random maps with corridors, obstacles and cost mixes, and every pair of a sample of cells."""
    rng = np.random.default_rng(seed)
    for _ in range(count):
        w, h = (int(v) for v in rng.integers(4, 16, 2))
        costs = rng.integers(50, 254, (h, w)).astype(np.uint8)
        if rng.random() < 0.4:  # a snake of walls: a corridor that outlasts the cycle limit
            for y in range(2, h - 1, 2):
                costs[y, :] = COST_OBS
                costs[y, 1 if (y // 2) % 2 else w - 2] = 50
        else:
            costs[rng.random((h, w)) < rng.choice((0.0, 0.2, 0.4))] = COST_OBS
        cells = [(x, y) for y in range(1, h - 1) for x in range(1, w - 1)]  # the border is lethal
        pick = rng.choice(len(cells), min(len(cells), 8), replace=False)
        yield costs, [(cells[a], cells[b]) for a in pick for b in pick if a != b]


def _cases():
    """Random maps, then the failing counterexamples' maps with every pair of interior cells."""
    for costs, pairs in _maps(0, 40):
        for s, g in pairs:
            yield costs, s, g
    for name in FAILING[:2]:
        costs = load_map(CX / name).costs
        h, w = costs.shape
        cells = [(x, y) for y in range(1, h - 1) for x in range(1, w - 1)]
        for s in cells:
            for g in cells:
                if s != g:
                    yield costs, s, g


def _same(a, b) -> bool:
    return np.asarray(a).tobytes() == np.asarray(b).tobytes()


# --------------------------------------------------------------------------- the specification
@pytest.mark.parametrize("name", FAILING)
def test_every_failing_counterexample_plans_when_fixed(name):
    d = CX / name
    doc = json.loads((d / "counterexample.json").read_text())
    sm = load_map(d)
    sx, sy, gx, gy = (int(v) for v in sm.cases[0])
    astar = doc["mode"] == "astar"
    original = P.run(sm.costs, (sx, sy), (gx, gy), astar)
    fixed = P.run(sm.costs, (sx, sy), (gx, gy), astar, fix=F.FIX)
    assert not len(original.path)  # the original fails: no path
    assert fixed.exit == "near_goal" and P.complete(fixed) is None and P.start_reached(fixed) is None
    assert tuple(fixed.path[-1].tolist()) == (gx, gy) and tuple(fixed.path[0].tolist()) == (sx, sy)


def test_the_fix_never_changes_what_the_original_plans_and_plans_every_connected_start():
    acted = {"propagation": 0, "descent": 0, "over budget": 0}
    for costs, s, g in _cases():
        for astar in (True, False):
            o = plan(costs, s, g, astar)
            f = plan(costs, s, g, astar, fix=F.FIX)
            if len(o.path):
                assert f.extra["fix"] == []
                for field in ("path", "potential", "trace"):
                    assert _same(getattr(o, field), getattr(f, field)), (field, s, g)
                assert (o.cycles, o.updates, o.start_reached) == (f.cycles, f.updates, f.start_reached)
                continue
            for part in f.extra["fix"]:
                acted[part] += 1
            connected = reaches(regions(add_border(costs)), s, g)
            if connected and f.dropped == 0:  # ConnectedStartReached: no push dropped on maps this small
                assert f.start_potential < POT_HIGH, (s, g)
            if f.start_potential < POT_HIGH:  # DescentPath, within calcPath's budget of 4 * nx points
                walk = F.descend([float(v) for v in f.potential.ravel()], costs.shape[1], costs.shape[0], s, g,
                                 costs.size)
                assert walk.exit is ExtractionExit.NEAR_GOAL, (s, g)
                fits = len(walk.path) <= path_cycle_limit(costs.shape[1])
                acted["over budget"] += not fits
                assert bool(len(f.path)) == fits and (f.exit is ExtractionExit.NEAR_GOAL) == fits, (s, g)
    # the cases exercise both parts, and descents longer than the budget
    assert acted["propagation"] > 20 and acted["descent"] > 5 and acted["over budget"] > 0, acted


def test_descent_steps_strictly_down_to_the_goal():
    seen = 0
    for costs, s, g in _cases():
        r = P.run(costs, s, g, True, fix=F.FIX)
        ext = F.descend([float(v) for v in r.potential.ravel()], costs.shape[1], costs.shape[0], s, g, costs.size)
        if not r.start_potential < POT_HIGH:
            assert ext.exit is ExtractionExit.HIGH_POTENTIAL and not ext.path
            continue
        seen += 1
        pts = [tuple(int(v) for v in p) for p in ext.path]
        assert ext.exit is ExtractionExit.NEAR_GOAL and pts[0] == s and pts[-1] == g and len(pts) <= costs.size
        for a, b in zip(pts, pts[1:]):
            assert max(abs(a[0] - b[0]), abs(a[1] - b[1])) == 1 and r.potential[b[1], b[0]] < r.potential[a[1], a[0]]
        assert all(costs[y, x] < COST_OBS for x, y in pts[:-1])  # PositionSafe: the goal alone may be lethal
    assert seen > 100


@pytest.mark.parametrize("backend", ["jit", "reference"])
def test_every_backend_with_the_fix_equals_the_spec_bit_for_bit(backend):
    """The conformance test of the fixed variant: the backend's planner with the fix (the JIT's
    compiled further call) against spec.planner.plan(fix=F.FIX), every field."""
    for costs, pairs in _maps(1, 25):
        planner = get_backend(backend, FIXED).prepare(costs)
        cols = planner.run_batch(np.array([(*s, *g) for s, g in pairs]), True)
        for i, (s, g) in enumerate(pairs):
            want = plan(costs, s, g, True, fix=F.FIX)
            got = planner.run(s, g, True)
            for field in ("path", "potential", "trace"):
                assert _same(getattr(want, field), getattr(got, field)), (backend, field, s, g)
            assert (want.cycles, want.updates, want.dropped, want.exit, want.extra["fix"]) == \
                (got.cycles, got.updates, got.dropped, got.exit, got.extra["fix"])
            a, b = cols["path_offsets"][i], cols["path_offsets"][i + 1]
            assert _same(cols["path"][a:b], want.path) and cols["cycles"][i] == want.cycles


def test_the_symbolic_encoding_with_the_fix_equals_the_spec():
    """check's whole-planner encoding of each registered fix (the fix of docs/fix.md: propagate on,
    descend; cycles-only), run on concrete costs in the concolic domain, against the spec on the
    failing counterexamples."""
    from navfn_smt.check.bounded import Case, _symbolic_run
    from navfn_smt.check.concolic import concrete
    from navfn_smt.check.encoding import interior
    from navfn_smt.smt.domains import FPDomain
    from navfn_smt.spec.extraction import exit_code

    for name in FAILING[:4]:
        d = CX / name
        doc = json.loads((d / "counterexample.json").read_text())
        sm = load_map(d)
        arr = add_border(sm.costs)
        ny, nx = arr.shape
        sx, sy, gx, gy = (int(v) for v in sm.cases[0])
        inner = interior(nx, ny)
        lethal = frozenset(k for k in inner if arr.flat[k] >= COST_OBS)
        case = Case(nx, ny, lethal, (sx, sy), (gx, gy), doc["mode"] == "astar")
        conc = {k: int(arr.flat[k]) for k in inner if k not in lethal}
        for fix in fixes.PATCHED:  # each registered fix, through the same encoding
            _, _, sp, ex = _symbolic_run(case, conc, 50, 253, FPDomain, fix)
            r = P.run(sm.costs, (sx, sy), (gx, gy), case.astar, fix=fix)
            assert concrete(ex.exit) == exit_code(ExtractionExit(r.exit)), (name, fix.name)
            pts = [(float(concrete(x)), float(concrete(y))) for x, y in ex.path]
            assert pts == [tuple(p) for p in r.path.tolist()], (name, fix.name)
            assert [float(concrete(p)) for p in sp.potential] == [float(v) for v in r.potential.ravel()], (name, fix.name)


def test_a_variant_that_is_not_one_is_refused():
    with pytest.raises(NavfnInputError, match="unknown variant 'patched'"):
        fixes.named("patched")
    with pytest.raises(TypeError, match="takes a Fix"):
        PlannerUnderTest("fixed")  # a name is parsed once, at the command line
    with pytest.raises(NavfnInputError, match="cycle limit of at least 1"):
        plan(np.full((3, 3), 50, np.uint8), (0, 0), (2, 2), True, cycles=0, fix=F.FIX)


# --------------------------------------------------------------------------- the commands
def test_plan_check_and_difftest_take_the_variant(capsys):
    d = CX / "incomplete-astar-5x5"
    assert main(["plan", str(d), "--start", "3", "1", "--goal", "1", "2"]) == 1
    assert main(["plan", str(d), "--start", "3", "1", "--goal", "1", "2", "--variant", "fixed", "--json"]) == 0
    doc = json.loads(capsys.readouterr().out.strip().splitlines()[-1])
    assert doc["fix"] == ["descent"] and doc["path"][-1] == [1.0, 2.0]
    assert main(["difftest", "--variant", "fixed"]) == 2
    assert "give --oracle DIR" in capsys.readouterr().err
    assert main(["check", "complete", "--size", "3", "4", "--variant", "fixed", "--mode", "astar"]) == 0
    assert "bounded" in capsys.readouterr().out  # complete, every size: DescentPath, below Progress's bound


def test_the_4655_room_sweeps_without_a_failure_when_fixed():
    from navfn_smt.diagnose.inputs import load_inputs
    from navfn_smt.diagnose.sweep import sweep

    lnp = DIAG / "legal_no_plan"
    start = __import__("navfn_smt.nav2.plugin", fromlist=["Pose"]).Pose.from_yaw(3.9125, 2.2125)
    counts = {}
    for fix in (fixes.AS_SHIPPED, F.FIX):
        s = load_inputs(lnp / "map.yaml", lnp / "nav2_params.yaml", fix=fix)
        counts[fix.name] = sweep(s.costmap, start, s.params).counts()
    assert counts["original"]["legal_no_plan"] > 0
    assert counts["fixed"]["ok"] == sum(counts["fixed"].values()) == sum(counts["original"].values())


def test_the_u_map_plans_when_fixed():
    from navfn_smt.diagnose.inputs import load_inputs
    from navfn_smt.nav2.plugin import Pose, create_plan

    s = load_inputs(DIAG / "u_map" / "u_map.yaml", fix=F.FIX)
    start, goal = Pose.from_yaw(1.525, 17.575), Pose.from_yaw(22.825, 17.575)
    run = create_plan(s.costmap, start, goal, s.params)
    assert run.ok and len(run.poses) > 2 and not run.log
    assert (run.poses[-1].x, run.poses[-1].y) == (goal.x, goal.y)  # smoothApproachToGoal sets the last pose
    # the first pose is the robot's cell as NavFn's path point maps back, within half a cell of the robot
    assert max(abs(run.poses[0].x - start.x), abs(run.poses[0].y - start.y)) <= s.costmap.resolution / 2 + 1e-9


# --------------------------------------------------------------------------- the patches and the C++
def test_there_is_one_patch_per_distribution_touching_navfn_and_adding_its_tests_only():
    assert sorted(p.stem for p in PATCHES.glob("*.patch")) == sorted(DISTROS)
    for p in PATCHES.glob("*.patch"):
        files = [line.split()[1] for line in p.read_text().splitlines() if line.startswith("+++ ")]
        assert files == ["b/nav2_navfn_planner/include/nav2_navfn_planner/navfn.hpp",
                         "b/nav2_navfn_planner/src/navfn.cpp", "b/nav2_navfn_planner/test/CMakeLists.txt",
                         "b/nav2_navfn_planner/test/test_navfn_descent.cpp",
                         "b/nav2_navfn_planner/test/test_navfn_planner_propagation_limit.cpp",
                         "b/nav2_navfn_planner/test/test_navfn_propagation_limit.cpp"], p.name


@pytest.mark.parametrize("distro", DISTROS)
def test_each_patch_applies_cleanly_with_patch_p1(nav2_src, tmp_path, distro):
    import shutil

    tree = tmp_path / distro
    shutil.copytree(nav2_src / distro / "nav2_navfn_planner", tree / "nav2_navfn_planner")
    r = subprocess.run(["patch", "-p1", "-F0", "--dry-run", "-i", str(PATCHES / f"{distro}.patch")], cwd=tree,
                       capture_output=True, text=True)
    assert r.returncode == 0 and "FAILED" not in r.stdout and "fuzz" not in r.stdout, r.stdout + r.stderr


@pytest.mark.parametrize("distro", DISTROS)
def test_the_patched_cpp_equals_the_fixed_spec_and_the_original_where_it_plans(builds, distro):
    from navfn_smt.difftest.live import run_live
    from navfn_smt.oracle.client import Oracle

    doc, folder = builds[distro]
    assert {"navfn-fixed", "navfn-plugin-fixed"} <= set(doc["programs"])
    assert doc["fix_patch"]["file"] == f"{distro}.patch"
    for suite in (EXAMPLE, CX):
        with Oracle(folder, fix="fixed") as oracle:
            s = run_live(suite, ("astar", "dijkstra"), "jit", oracle, planner=FIXED).as_dict()
        assert s["failed"] == 0 and s["passed"] > 0, s
    # where the original C++ plans, the patched C++ returns the same path, potential and trace
    sm = load_map(CX / "cost-astar-7x7")
    with Oracle(folder) as original, Oracle(folder, fix="fixed") as fixed:
        for astar in (True, False):
            cases = [(s[0], s[1], g[0], g[1]) for s in [(1, 1), (3, 3), (5, 2)] for g in [(2, 5), (4, 4)]]
            for a, b in zip(original.plan(sm.costs, cases, astar), fixed.plan(sm.costs, cases, astar)):
                if len(a.path):
                    assert _same(a.path, b.path) and _same(a.potential, b.potential) and _same(a.trace, b.trace)


def test_the_patched_plugin_equals_the_fixed_model(builds):
    from navfn_smt.difftest.plugin_live import generated_configs, run_plugin_live
    from navfn_smt.oracle.client import PluginOracle
    from dataclasses import replace

    for distro in ("humble", "rolling"):
        _, folder = builds[distro]
        configs = [replace(c, params=replace(c.params, fix=F.FIX)) for c in generated_configs(distro, 60, 3, 12)]
        with PluginOracle(folder, "fixed") as oracle:
            s = run_plugin_live(configs, oracle, "jit").as_dict()
        assert s["failed"] == 0 and s["passed"] > 500, (distro, s)


def test_a_contributors_branch_that_carries_the_fix_is_difftested_as_the_fixed_planner(nav2_src, tmp_path, capsys):
    """A navigation2 checkout with the patch applied (a pull request's branch): its own NavFn is
    built as the fixed programs, without patching twice; ``difftest --variant fixed`` compares it
    with the fixed spec and passes; running it as NavFn as shipped is refused, naming why, and so is
    running Nav2's own tests on it as shipped."""
    import shutil

    from navfn_smt.oracle.build import build
    from navfn_smt.oracle.client import Oracle

    src = tmp_path / "src"
    for pkg in ("nav2_navfn_planner", "nav2_core", "nav2_costmap_2d"):
        shutil.copytree(nav2_src / "rolling" / pkg, src / pkg)
    subprocess.run(["patch", "-p1", "-i", str(PATCHES / "rolling.patch")], cwd=src, check=True, capture_output=True)
    out = tmp_path / "out"
    doc = build(src, out, programs=("navfn-plain", "navfn-fixed"))
    assert doc["programs"] == ["navfn-plain", "navfn-fixed"] and not doc["skipped"]
    assert doc["sources_carry_fix"] and doc["fix_patch"]["applied_by"] == "the sources"
    assert main(["difftest", str(EXAMPLE), "--oracle", str(out), "--variant", "fixed"]) == 0
    assert " 0 failed" in capsys.readouterr().out
    with pytest.raises(NavfnInputError, match="carry the fix already.*--variant fixed"):
        Oracle(out, traced=False)
    assert main(["difftest", str(EXAMPLE), "--oracle", str(out)]) == 2
    assert "carry the fix already" in capsys.readouterr().err
    assert main(["oracle", "nav2-tests", str(src), "--variant", "original", "--out", str(tmp_path / "t")]) == 2
    assert "no NavFn as shipped to test" in capsys.readouterr().err and not (tmp_path / "t").exists()


# --------------------------------------------------------------------------- in arm64's arithmetic
def _arm64_cases(kind: str):
    for d in sorted(CX.glob(f"{kind}-*")):
        doc = json.loads((d / "counterexample.json").read_text())
        sm = load_map(d)
        sx, sy, gx, gy = (int(v) for v in sm.cases[0])
        yield d.name, sm.costs, (sx, sy), (gx, gy), doc["mode"] == "astar"


@pytest.mark.parametrize("backend", ["jit", "reference"])
def test_in_arm64s_arithmetic_the_fix_propagates_on_where_the_original_plans_from_an_unreached_start(backend):
    """Where ``(int)`` saturates (arm64), the original returns a path from a start the wave never
    reached on the committed unreached maps; the patched propagation goes on there all the same
    (it loops while the start is unreached), so the fixed backends plan as
    spec.planner.plan(fix=F.FIX) in that arithmetic, bit for bit: the start reached, the
    fixed propagation named.  (The backends once kept the original's path there, as they may in
    x86-64's arithmetic, where no path comes from an unreached start.)"""
    from navfn_smt.spec.arithmetic import KNOWN

    arm, fixed = KNOWN["aarch64"], PlannerUnderTest.of_target("aarch64", F.FIX)
    seen = 0
    for name, costs, s, g, astar in _arm64_cases("unreached"):
        o = plan(costs, s, g, astar, arith=arm)
        want = plan(costs, s, g, astar, fix=F.FIX, arith=arm)
        planner = get_backend(backend, fixed).prepare(costs)
        got = planner.run(s, g, astar)
        for field in ("path", "potential", "trace"):
            assert _same(getattr(want, field), getattr(got, field)), (name, field)
        assert (want.cycles, want.exit, want.extra["fix"]) == (got.cycles, got.exit, got.extra["fix"]), name
        cols = planner.run_batch(np.array([(*s, *g)]), astar)
        assert _same(cols["path"], want.path) and cols["cycles"][0] == want.cycles, name
        if len(o.path) and not o.start_potential < POT_HIGH:  # a path from the unreached start
            seen += 1
            assert want.start_potential < POT_HIGH and "propagation" in want.extra["fix"], name
    assert seen >= 2, seen


def test_in_arm64s_arithmetic_the_fix_still_returns_a_path_from_a_lethal_start():
    """The patch leaves calcPath as it is: where ``(int)`` saturates, the fixed planner returns
    the path-without-potential maps' path from the lethal start, as the original does (and as
    the patched arm64 C++ does: tests/test_oracle.py); x86-64's returns none there."""
    from navfn_smt.spec.arithmetic import KNOWN

    for name, costs, s, g, astar in _arm64_cases("path-without-potential"):
        arm = plan(costs, s, g, astar, fix=F.FIX, arith=KNOWN["aarch64"])
        x86 = plan(costs, s, g, astar, fix=F.FIX)
        assert len(arm.path) and not arm.start_potential < POT_HIGH and costs[s[1], s[0]] == COST_OBS, name
        assert not len(x86.path), name


def test_the_fixed_plugin_keeps_the_exhaustion_warning_and_plans(builds):
    """Rolling's calcPath warns "Path extraction exhausted" and the plugin throws; patched, the
    gradient still warns so (Nav2 #6308's WARN, kept) and the descent plans, in the C++ and in the
    model alike (generated configuration 33, pair 18: the first of its kind)."""
    from dataclasses import replace

    from navfn_smt.difftest.plugin_live import generated_configs
    from navfn_smt.nav2.plugin import create_plan
    from navfn_smt.oracle.client import PluginOracle

    cfg = next(c for k, c in enumerate(generated_configs("rolling", 34, 0)) if k == 33)
    start, goal = cfg.pairs[18]
    _, folder = builds["rolling"]
    for fix in (fixes.AS_SHIPPED, F.FIX):
        params = replace(cfg.params, fix=fix)
        model = create_plan(cfg.costmap, start, goal, params)
        with PluginOracle(folder, fix.name) as oracle:
            (cpp,) = oracle.create_plans(cfg.costmap, params, [(start, goal)])
        warns = [text for level, text in cpp.lines]
        assert warns == [text for level, text in model.lines]
        exhausted = [w for w in warns if w.startswith("[PathCalc] Path extraction exhausted: npath = ")]
        assert len(exhausted) == 1 and exhausted[0].endswith(f", max_cycles = {model.max_cycles}")
        if fix.shipped:
            assert cpp.error == "NoValidPathCouldBeFound"
        else:
            assert cpp.error is None and len(cpp.poses) > 0 and warns == exhausted


def test_the_worst_cases_bench_measures_what_the_fix_changes(builds):
    """bench --worst-cases on a small size: the fix reaches the serpentine's far start where the
    original's cycle limit stops, its descent keeps calcPath's budget there (no path, as the
    original), it floods without reaching a start on a wall, and it plans #4655's room; each
    case's C++ reports a peak memory. The spec agrees on each."""
    from navfn_smt.bench import bench_worst_cases, worst_case_maps

    _, folder = builds["rolling"]
    rows = bench_worst_cases([41], folder)
    assert [r["case"] for r in rows] == [m[0] for m in worst_case_maps(41)]
    for r, (_, costs, case, astar) in zip(rows, worst_case_maps(41)):
        f = plan(costs, case[:2], case[2:], astar, fix=F.FIX)
        o = plan(costs, case[:2], case[2:], astar)
        assert (r["fixed"]["start_reached"], r["fixed"]["path_points"]) == (bool(f.start_reached), len(f.path))
        assert (r["original"]["start_reached"], r["original"]["path_points"]) == (bool(o.start_reached), len(o.path))
        assert all(r[v]["peak_memory_bytes"] > 0 for v in ("original", "fixed"))
    serpentine, _, wall, room = rows
    assert not serpentine["original"]["start_reached"] and serpentine["fixed"]["start_reached"]
    assert serpentine["fixed"]["path_points"] == 0  # about 41*41/2 cells: more than 4 * 41 points
    assert not wall["fixed"]["start_reached"] and room["fixed"]["path_points"] == 3 == room["original"]["path_points"] + 3


def test_bench_worst_cases_needs_a_build_and_sizes_it_can_make():
    for argv, says in ((["bench", "--worst-cases", "2000"], "give --oracle DIR"),
                       (["bench", "--worst-cases", "5", "--oracle", "nowhere"], "at least 12 cells")):
        r = subprocess.run(["navfn-smt", *argv], capture_output=True, text=True)
        assert r.returncode == 2 and says in r.stderr and "Traceback" not in r.stderr, r.stderr
