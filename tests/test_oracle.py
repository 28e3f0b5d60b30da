"""The user's own Nav2 NavFn in the loop: built unchanged from the shared sources of every
distribution, run live, and held equal to the spec (and to the recorded golden files)."""

from __future__ import annotations

import json
import shutil
from pathlib import Path

import pytest

from navfn_smt.cli import main
from navfn_smt.difftest.live import run_live
from conftest import compare_golden_files
from navfn_smt.maps.suite import MODES, discover
from navfn_smt.oracle.build import ANCHOR, build, distribution
from navfn_smt.oracle.client import Oracle, PluginOracle
from navfn_smt.under_test import PlannerUnderTest

EXAMPLE = Path(__file__).resolve().parent.parent / "src" / "navfn_smt" / "examples" / "suite"
DISTROS = ("humble", "jazzy", "kilted", "lyrical", "rolling")


@pytest.mark.parametrize("distro", DISTROS)
def test_every_distribution_builds_and_says_which_it_is(builds, nav2_src, distro):
    doc, folder = builds[distro]
    assert doc["distribution"] == distro == distribution(nav2_src / distro)
    assert set(doc["source_sha256"]) >= {"nav2_navfn_planner/src/navfn.cpp"}
    assert json.loads((folder / "build.json").read_text()) == doc
    # the sources are built as they are: the hook goes into a copy in the build folder only
    assert ANCHOR in (nav2_src / distro / "nav2_navfn_planner" / "src" / "navfn.cpp").read_text()
    assert "NAVFN_SMT_CYCLE" not in (nav2_src / distro / "nav2_navfn_planner" / "src" / "navfn.cpp").read_text()


@pytest.mark.parametrize("distro", DISTROS)
def test_the_spec_agrees_with_each_distributions_cpp_live(builds, distro):
    """Every case of the example suite, both modes, white-box (trace, cycles, updates)."""
    with Oracle(builds[distro][1]) as oracle:
        summary = run_live(EXAMPLE, MODES, "jit", oracle).as_dict()
    assert summary["failed"] == 0 and summary["passed"] == 4400, summary["disagreements"][:2]


def test_recording_from_the_cpp_reproduces_the_golden_files(builds, tmp_path):
    suite = tmp_path / "suite"
    shutil.copytree(EXAMPLE, suite)
    oracle = str(builds["rolling"][1])
    assert main(["suite", "record", str(suite), "--oracle", oracle, "--overwrite", "--quiet"]) == 0
    # the suite keeps whole potentials of the first 50 cases of a map, 5 on the ROS maps
    assert main(["suite", "record", str(suite / "ROS"), "--oracle", oracle, "--overwrite", "--quiet",
                 "--full-first", "5"]) == 0
    files = sorted(suite.rglob("golden_*.npz"))
    assert len(files) == 2 * len(discover(EXAMPLE))
    assert [f.name for f in files if compare_golden_files(f, EXAMPLE / f.relative_to(suite))] == []


# bugs seeded in a copy of the rolling sources: (file, the line as it is, the bug, the mode)
HPP = "nav2_navfn_planner/include/nav2_navfn_planner/navfn.hpp"
CPP = "nav2_navfn_planner/src/navfn.cpp"
SEEDED = {
    "cost constant": (HPP, "#define COST_OBS 254", "#define COST_OBS 253", "dijkstra"),
    "push guard": (CPP, "costarr[n] < COST_OBS && nextPe < PRIORITYBUFSIZE", "costarr[n] <= COST_OBS && nextPe < "
                   "PRIORITYBUFSIZE", "dijkstra"),
    "buffer size": (HPP, "#define PRIORITYBUFSIZE 10000", "#define PRIORITYBUFSIZE 100", "dijkstra"),
    "path step": (CPP, "pathStep = 0.5;", "pathStep = 0.25;", "dijkstra"),
    "A* heuristic": (CPP, "float dist = hypot(x - start[0], y - start[1]) * static_cast<float>(COST_NEUTRAL);",
                     "float dist = hypot(x - start[0], y - start[1]) * static_cast<float>(COST_NEUTRAL + 1);",
                     "astar"),
}
FIELDS = ("path", "potential", "trace", "start_reached", "cycles", "updates")


def seeded_copy(nav2_src: Path, tmp_path: Path, distro: str, rel: str, line: str, bug: str) -> Path:
    """A copy of a distribution's sources with ``line`` of file ``rel`` (there once) turned into ``bug``."""
    src = tmp_path / "src"
    shutil.copytree(nav2_src / distro, src)
    text = (src / rel).read_text()
    assert text.count(line) == 1, f"{rel} no longer has {line!r} once"
    (src / rel).write_text(text.replace(line, bug))
    return src


def test_an_object_from_the_cache_is_the_object_compiled_here(nav2_src, tmp_path, monkeypatch):
    """Rolling's plain program built with no object cache; then a copy of the sources in
    another folder, navfn.cpp's step changed, built into a fresh cache; then Rolling again from
    that cache: it compiles navfn.cpp and takes the driver's object, and its program equals the
    one built without the cache byte for byte (the objects say nothing of where the sources were)."""
    import hashlib

    def program(folder):
        return hashlib.sha256((folder / "navfn-plain").read_bytes()).hexdigest()

    monkeypatch.setenv("NAVFN_SMT_OBJECT_CACHE", "off")
    alone = build(nav2_src / "rolling", tmp_path / "alone", programs=("navfn-plain",))
    assert alone["objects"] == {"cache": None, "compiled": 2, "reused": 0}
    monkeypatch.setenv("NAVFN_SMT_OBJECT_CACHE", str(tmp_path / "objects"))
    src = seeded_copy(nav2_src, tmp_path, "rolling", "nav2_navfn_planner/src/navfn.cpp", "pathStep = 0.5;",
                      "pathStep = 0.25;")
    assert build(src, tmp_path / "copy", programs=("navfn-plain",))["objects"]["compiled"] == 2
    again = build(nav2_src / "rolling", tmp_path / "again", programs=("navfn-plain",))
    assert (again["objects"]["compiled"], again["objects"]["reused"]) == (1, 1)
    assert program(tmp_path / "again") == program(tmp_path / "alone") != program(tmp_path / "copy")
    assert again["path_maps"]["/nav2"] == str((nav2_src / "rolling").absolute())


@pytest.mark.parametrize("bug", SEEDED)
def test_a_bug_seeded_in_the_cpp_is_caught_and_named(nav2_src, tmp_path, bug):
    """The live difftest of the example suite fails on the seeded copy, and each disagreement
    names the first field that differs."""
    rel, line, seeded, mode = SEEDED[bug]
    src = seeded_copy(nav2_src, tmp_path, "rolling", rel, line, seeded)
    build(src, tmp_path / "bug", programs=("navfn-traced",))
    with Oracle(tmp_path / "bug") as oracle:
        summary = run_live(EXAMPLE, (mode,), "jit", oracle).as_dict()
    assert summary["failed"] > 0
    assert summary["disagreements"] and {d["field"] for d in summary["disagreements"]} <= set(FIELDS)


def test_a_moved_anchor_stops_the_build_naming_it(nav2_src, tmp_path, capsys):
    src = tmp_path / "src"
    shutil.copytree(nav2_src / "rolling", src)
    cpp = src / "nav2_navfn_planner" / "src" / "navfn.cpp"
    cpp.write_text(cpp.read_text().replace(ANCHOR, "// (moved)", 1))
    assert main(["oracle", "build", str(src), "--out", str(tmp_path / "b")]) == 2
    err = capsys.readouterr().err
    assert ANCHOR in err and err.count("\n") == 1 and "Traceback" not in err
    assert not (tmp_path / "b").exists()  # nothing half-written


@pytest.mark.parametrize("args, says", [
    (["oracle", "build", "{tmp}/nowhere"], "no such directory"),
    (["oracle", "build", "{tmp}"], "no nav2_navfn_planner/src/navfn.cpp"),
    (["difftest", "--oracle", "{tmp}"], "not an oracle build folder"),
])
def test_bad_input_is_one_line(args, says, tmp_path, capsys):
    assert main([a.format(tmp=tmp_path) for a in args]) == 2
    err = capsys.readouterr().err
    assert says in err and err.count("\n") == 1


def test_a_corrupt_build_folder_is_one_line(builds, tmp_path, capsys):
    folder = tmp_path / "b"
    shutil.copytree(builds["rolling"][1], folder)
    (folder / "navfn-traced").unlink()
    assert main(["difftest", "--oracle", str(folder)]) == 2
    assert "incomplete" in capsys.readouterr().err


def test_the_cli_difftest_against_the_cpp(builds, capsys):
    assert main(["difftest", "--oracle", str(builds["humble"][1]), "--quiet"]) == 0
    assert "4400 passed, 0 failed" in capsys.readouterr().out


def test_a_build_folder_that_is_something_else_is_refused(nav2_src, tmp_path, capsys):
    (tmp_path / "mine").mkdir()
    (tmp_path / "mine" / "keep.txt").write_text("x")
    assert main(["oracle", "build", str(nav2_src / "rolling"), "--out", str(tmp_path / "mine")]) == 2
    assert "not an oracle build folder" in capsys.readouterr().err
    assert (tmp_path / "mine" / "keep.txt").exists()


def test_bench_times_the_cpp_and_the_jit_in_one_run(builds, tmp_path, capsys):
    out = tmp_path / "b.json"
    assert main(["bench", "--oracle", str(builds["kilted"][1]), "--json", str(out)]) == 0
    rows = json.loads(out.read_text())["results"]
    assert [r["mode"] for r in rows] == ["astar", "dijkstra"]
    for r in rows:
        assert r["cases"] == 2200 and r["cpp_seconds"] > 0 and r["jit_seconds"] > 0
        assert r["jit_over_cpp"] == round(r["jit_seconds"] / r["cpp_seconds"], 3)
    assert "jit / C++" in capsys.readouterr().out


# --------------------------------------------------------------------------- the plugin level
def test_the_plugin_model_of_each_distribution_agrees_with_its_cpp(builds):
    """Generated costmaps x poses x parameters: exceptions, messages, every published double and
    every WARN and ERROR line, for the five distributions; each outcome the version has occurs."""
    from navfn_smt.difftest.plugin_live import generated_configs, run_plugin_live

    for distro in DISTROS:
        with PluginOracle(builds[distro][1]) as oracle:
            s = run_plugin_live(generated_configs(distro, 120, seed=7), oracle).as_dict()
        assert s["failed"] == 0, (distro, s["disagreements"][:1])
        assert s["passed"] > 2000 and s["log_lines"] > 5000
        want = {"path", "empty path"} if distro == "humble" else {
            "path", "StartOutsideMapBounds", "GoalOutsideMapBounds", "GoalOccupied", "NoValidPathCouldBeFound"}
        assert want <= set(s["outcomes"]), (distro, s["outcomes"])


def test_the_tolerance_search_logs_a_line_per_point_past_the_edge_as_nav2_does(builds):
    """8x6 free map, tolerance 0.25, the goal in the right column's last half cell: the goal's
    cell rounds one past the edge, so getPointPotential and the tolerance points past the right
    edge log too (not only makePlan's line)."""
    import numpy as np

    from navfn_smt.nav2.params import PlannerParams
    from navfn_smt.nav2.plugin import Costmap, Pose, create_plan

    cm = Costmap(np.zeros((6, 8), np.uint8), 0.0, 0.0, 0.05)
    params = PlannerParams(tolerance=0.25)
    start, goal = Pose(0.11, 0.16), Pose(0.39, 0.11)
    with PluginOracle(builds["rolling"][1]) as oracle:
        (answer,) = oracle.create_plans(cm, params, [(start, goal)])
    run = create_plan(cm, start, goal, params)
    assert run.lines == answer.lines and len(answer.lines) == 60
    assert all(line.startswith("worldToMap failed: mx,my: ") for _, line in answer.lines)


def test_every_plugin_case_directory_replays_on_the_cpp(builds):
    """The committed findings of the plugin model (tests/data/plugin_cases), planned by Rolling's
    C++ plugin: the same exception, the same poses bit for bit, the same ERROR and WARN lines."""
    from plugin_cases import load_case, outcome, run_case
    from navfn_smt.difftest.plugin_live import first_difference

    cases = sorted(d for d in (Path(__file__).parent / "data" / "plugin_cases").iterdir() if d.is_dir())
    compared = 0
    with PluginOracle(builds["rolling"][1]) as oracle:
        for d in cases:
            run = run_case(d)
            if isinstance(run, dict) or run.error == "UndefinedBehaviour":
                continue
            cm, start, goal, params, case = load_case(d)
            assert outcome(run) == case["expected"], d.name
            (answer,) = oracle.create_plans(cm, params, [(start, goal)])
            assert first_difference(run, answer) is None, d.name
            compared += 1
    assert compared >= 10


def test_a_bug_seeded_in_the_plugin_is_caught(nav2_src, tmp_path):
    """navfn_planner.cpp's worldToMap truncating x instead of rounding it: the plugin level fails."""
    from navfn_smt.difftest.plugin_live import generated_configs, run_plugin_live

    rel = "nav2_navfn_planner/src/navfn_planner.cpp"
    src = seeded_copy(nav2_src, tmp_path, "rolling", rel, "mx = static_cast<int>(\n    std::round(",
                      "mx = static_cast<int>(\n    std::floor(")
    build(src, tmp_path / "bug", programs=("navfn-plugin",))
    with PluginOracle(tmp_path / "bug") as oracle:
        s = run_plugin_live(generated_configs("rolling", 40, seed=3), oracle).as_dict()
    assert s["failed"] > 0 and s["disagreements"][0]["field"].split()[0] in ("pose", "log", "error")


def test_the_cli_plugin_level(builds, tmp_path, capsys):
    out = tmp_path / "p.json"
    assert main(["difftest", "--level", "plugin", "--oracle", str(builds["humble"][1]), "--configs", "20",
                 "--quiet", "--json", str(out)]) == 0
    doc = json.loads(out.read_text())
    assert doc["distribution"] == "humble" and doc["failed"] == 0 and doc["passed"] > 0
    assert f"{doc['passed']} passed, 0 failed" in capsys.readouterr().out


@pytest.mark.parametrize("args, says", [
    (["difftest", "--level", "plugin"], "give --oracle DIR"),
    (["difftest", "--unbounded"], "give --oracle DIR"),
])
def test_levels_need_an_oracle(args, says, capsys):
    assert main(args) == 2
    err = capsys.readouterr().err
    assert says in err and err.count("\n") == 1


def test_a_build_without_the_plugin_says_so(nav2_src, tmp_path, capsys):
    build(nav2_src / "jazzy", tmp_path / "b", programs=("navfn-traced",))
    assert main(["difftest", "--level", "plugin", "--oracle", str(tmp_path / "b")]) == 2
    assert "has no navfn-plugin" in capsys.readouterr().err


# --------------------------------------------------------------------------- unbounded buffers
def test_the_unbounded_build_agrees_with_the_unbounded_spec_where_buffers_overflow(builds, shared_suite_large):
    """On the Nav2-sized map the bounded buffers drop pushes: the unbounded C++ plans other paths
    than the bounded one, and the spec with unbounded buffers follows it bit for bit."""
    import numpy as np

    from navfn_smt.maps.suite import load_map

    with Oracle(builds["rolling"][1], unbounded=True) as oracle:
        s = run_live(shared_suite_large, MODES, "jit", oracle, unbounded=True).as_dict()
    assert s["failed"] == 0 and s["passed"] == 8
    d = discover(shared_suite_large)[0]
    m = load_map(d, shared_suite_large)
    with Oracle(builds["rolling"][1], unbounded=True) as u, Oracle(builds["rolling"][1]) as b:
        differ = [not np.array_equal(x.path, y.path) for x, y in zip(u.plan(m.costs, m.cases, False),
                                                                     b.plan(m.costs, m.cases, False))]
    assert any(differ)


# --------------------------------------------------------------------------- navfn-smt ci
def test_ci_fails_on_a_seeded_bug_and_says_where(nav2_src, tmp_path, capsys):
    """``ci --target x86-64-v3`` on Rolling with calcPath's step halved: the NavFn steps fail and
    say so, and so does the plugin's, which runs that NavFn; the layers' step, computed in the
    arithmetic found in its own program, passes; the proofs (x86-64's arithmetic) are skipped
    with why."""
    import xml.etree.ElementTree as ET

    from navfn_smt.errors import NavfnInputError
    from navfn_smt.oracle.targets import toolchain

    try:
        toolchain("x86-64-v3").runner()
    except NavfnInputError as e:
        pytest.skip(str(e))
    src = tmp_path / "src"
    shutil.copytree(nav2_src / "rolling", src)
    cpp = src / "nav2_navfn_planner" / "src" / "navfn.cpp"
    cpp.write_text(cpp.read_text().replace("pathStep = 0.5;", "pathStep = 0.25;"))
    out = tmp_path / "ci"
    assert main(["ci", str(src), "--out", str(out), "--configs", "20", "--target", "x86-64-v3"]) == 1
    cases = {tc.get("name"): tc for tc in ET.parse(out / "junit.xml").getroot().iter("testcase")}
    failed = {name: tc.find("failure").get("message") for name, tc in cases.items() if tc.find("failure") is not None}
    assert "difftest navfn" in failed and "0 failed" not in failed["difftest navfn"]
    assert "difftest plugin" in failed and "difftest costmap" not in failed, failed
    assert "x86-64's arithmetic" in cases["prove"].find("skipped").get("message")
    assert "for x86-64-v3 (x86-64-v3)" in capsys.readouterr().out


# --------------------------------------------------------------------------- the distributions
def distribution_table() -> dict:
    """docs/distributions.md's case rows: key -> the humble, jazzy, kilted, lyrical and rolling cells."""
    page = (Path(__file__).resolve().parent.parent / "docs" / "distributions.md").read_text()
    return {line.split("|")[1].strip().strip("`"): [c.strip() for c in line.split("|")[4:9]]
            for line in page.splitlines() if line.startswith("| `")}


def test_each_distribution_difference_shows_on_the_cpp_as_the_table_says(builds):
    """Every row of tests/distribution_cases.py (and docs/distributions.md): the C++ of each
    distribution gives the outcome the docs table states, the model of each the same bit for
    bit, and the outcomes differ between distributions (the row shows a difference)."""
    from dataclasses import replace

    from navfn_smt.difftest.plugin_live import first_difference
    from distribution_cases import DIFFERENCES, costmap_of, summary_of
    from navfn_smt.nav2.plugin import create_plan

    rows = distribution_table()
    for d in DIFFERENCES:
        seen = []
        for distro in DISTROS:
            params = replace(d.params, distro=distro)
            with PluginOracle(builds[distro][1]) as oracle:
                (answer,) = oracle.create_plans(costmap_of(d), params, [(d.start, d.goal)])
            run = create_plan(costmap_of(d), d.start, d.goal, params)
            assert first_difference(run, answer) is None, (d.key, distro)
            seen.append(summary_of(answer.error, len(answer.poses), answer.lines))
        assert rows[d.key] == seen, d.key
        assert len(set(seen)) > 1, d.key


# --------------------------------------------------------------------------- the costmap level
def _layers(builds, distro):
    doc, folder = builds[distro]
    if "costmap-layers" not in doc["programs"]:
        pytest.skip(doc.get("skipped", {}).get("costmap-layers", "costmap-layers not built"))
    return folder


def test_the_costmap_model_of_each_distribution_agrees_with_its_layers(builds):
    """Generated occupancy grids x costmap parameters x layer lists (every inflation layer the
    version has): the master costmap byte for byte and the footprint's radii bit for bit."""
    from navfn_smt.difftest.layers_live import generated_configs, run_layers_live
    from navfn_smt.oracle.client import LayersOracle

    for distro in DISTROS:
        with LayersOracle(_layers(builds, distro)) as oracle:
            s = run_layers_live(generated_configs(distro, 150, seed=5), oracle).as_dict()
        assert s["failed"] == 0 and s["passed"] == 150, (distro, s["disagreements"][:1])
        kinds = {"legacy"} if distro not in ("lyrical", "rolling") else {"legacy", "current"}
        assert kinds == {k for o in s["outcomes"] for k in o.split(" + ")[1:]}, (distro, s["outcomes"])


def test_the_costmap_level_says_which_square_root_this_cpu_takes(builds):
    """The probe's 12 cells differ between the model's two square roots; the build's own Eigen
    square root is compared with both on 2^20 integers; when it equals one of them, the probe's
    C++ costmap is that one's (which one, or neither, is a fact about the CPU, reported)."""
    from navfn_smt.difftest.layers_live import cpu_sqrt, model_costmap, sqrt_probe
    from navfn_smt.nav2.inflation import SQRT_MODES
    from navfn_smt.oracle.client import LayersOracle

    cfg = sqrt_probe()
    models = {m: model_costmap(cfg, "rolling", m).costmap for m in SQRT_MODES}
    assert int((models["eigen-sse-amd"] != models["exact"]).sum()) == 12
    folder = _layers(builds, "rolling")
    with LayersOracle(folder) as oracle:
        cpp = oracle.costmap(cfg.occupancy, cfg.resolution, cfg.origin, cfg.params).costmap
    c = cpu_sqrt(folder)
    assert c["values"] == 1 << 20 and set(c["differ"]) == set(SQRT_MODES)
    if c["matches"]:
        assert c["differ"][c["matches"]] == 0 and (cpp == models[c["matches"]]).all()
    else:
        assert min(c["differ"].values()) > 0


def test_a_bug_seeded_in_a_layer_is_caught(nav2_src, tmp_path, builds):
    """The static layer's lethal test '>=' turned into '>': the costmap level fails."""
    from navfn_smt.difftest.layers_live import generated_configs, run_layers_live
    from navfn_smt.oracle.client import LayersOracle

    _layers(builds, "kilted")
    src = seeded_copy(nav2_src, tmp_path, "kilted", "nav2_costmap_2d/plugins/static_layer.cpp",
                      "value >= lethal_threshold_", "value > lethal_threshold_")
    build(src, tmp_path / "bug", programs=("costmap-layers",))
    with LayersOracle(tmp_path / "bug") as oracle:
        s = run_layers_live(generated_configs("kilted", 60, seed=3), oracle).as_dict()
    assert s["failed"] > 0 and s["disagreements"][0]["field"].startswith("cell")


def test_the_cli_costmap_level(builds, capsys):
    folder = _layers(builds, "rolling")
    assert main(["difftest", "--level", "costmap", "--oracle", str(folder), "--configs", "40", "--quiet"]) == 0
    out = capsys.readouterr().out
    assert "40 passed, 0 failed" in out and "square root" in out


def test_each_costmap_difference_shows_on_the_cpp_as_the_table_says(builds):
    """Every row of tests/distribution_cases.py's LAYER_DIFFERENCES (and docs/distributions.md): each
    distribution's compiled layers give the costmap the table states, its model the same bytes
    (or, where the version lacks the layer type, an error), and the rows differ between versions."""
    import numpy as np

    from navfn_smt.difftest.layers_live import LayersConfig, model_costmap
    from navfn_smt.errors import NavfnInputError
    from distribution_cases import LAYER_DIFFERENCES, layer_params, layer_summary
    from navfn_smt.oracle.client import LayersOracle

    rows = distribution_table()
    for d in LAYER_DIFFERENCES:
        seen = []
        for distro in DISTROS:
            cfg = LayersConfig(np.array(d.occupancy, np.int8), 0.05, (0.0, 0.0), layer_params(d))
            with LayersOracle(_layers(builds, distro)) as oracle:
                cpp = oracle.costmap(cfg.occupancy, cfg.resolution, cfg.origin, cfg.params).costmap
            if cpp is None:
                with pytest.raises(NavfnInputError, match="does not exist"):
                    model_costmap(cfg, distro)
            else:
                assert (model_costmap(cfg, distro).costmap == cpp).all(), (d.key, distro)
            seen.append(layer_summary(cpp))
        assert rows[d.key] == seen, d.key
        assert len(set(seen)) > 1, d.key


def test_the_costmap_level_on_a_users_map_and_what_it_refuses(builds, tmp_path, capsys):
    from conftest import REPO

    folder = str(_layers(builds, "jazzy"))
    room = str(REPO / "src/navfn_smt/examples/mapserver/room.yaml")
    params = str(REPO / "src/navfn_smt/examples/nav2/nav2_params.yaml")
    assert main(["difftest", "--level", "costmap", "--oracle", folder, "--map", room, "--params", params,
                 "--quiet"]) == 0
    out = capsys.readouterr().out
    assert "1 passed, 0 failed" in out and "obstacle_layer" in out  # the layer left out is named
    fp = tmp_path / "fp.yaml"
    fp.write_text('global_costmap:\n  global_costmap:\n    ros__parameters:\n'
                  '      footprint: "[[0.1, 0.1], [0.1, -0.1], [-0.1, -0.1], [-0.1, 0.1]]"\n')
    assert main(["difftest", "--level", "costmap", "--oracle", folder, "--map", room, "--params", str(fp)]) == 2
    err = capsys.readouterr().err
    assert "footprint polygon" in err and err.count("\n") == 1


def test_a_ci_step_that_cannot_finish_fails(capsys):
    """The C++ stopping mid-run (a NavfnInputError from its client) fails the step, never skips it."""
    from navfn_smt.commands.ci import _Steps, _summary_step
    from navfn_smt.errors import NavfnInputError

    def crashed():
        raise NavfnInputError("the C++ navfn-traced stopped answering (exit status -6)")

    steps = _Steps()
    _summary_step(steps, "difftest navfn", crashed)
    assert steps.failed and "stopped answering" in steps.cases[0]["failure"] and not steps.cases[0]["skipped"]


# --------------------------------------------------------------------------- other targets
# (target, --cxxflags, the arithmetic the build must be found to have)
TARGET_BUILDS = {
    "aarch64": ("aarch64", None, "aarch64"),
    "x86-64-v3": ("x86-64-v3", None, "x86-64-v3"),
    "aarch64-no-contract": ("aarch64", "-ffp-contract=off", "fused[none]-saturating"),
}


@pytest.fixture(scope="module")
def target_builds(nav2_src, tmp_path_factory) -> dict:
    """Rolling's NavFn (plain and traced) built for each of :data:`TARGET_BUILDS`; skipped where
    the cross compiler or qemu-user is missing (.ci/run installs them)."""
    from navfn_smt.errors import NavfnInputError
    from navfn_smt.oracle.targets import toolchain

    root = tmp_path_factory.mktemp("targets")
    out = {}
    for name, (target, flags, _) in TARGET_BUILDS.items():
        tc = toolchain(target, cxx=("aarch64-linux-gnu-g++" if flags else None), cxxflags=flags)
        try:
            tc.check()
            tc.runner()
        except NavfnInputError as e:
            pytest.skip(str(e))
        programs = ("navfn-plain", "navfn-traced",
                    *(("navfn-plugin", "navfn-fixed", "navfn-plugin-fixed") if name == "aarch64" else ()),
                    *(("costmap-layers",) if name == "x86-64-v3" else ()))
        out[name] = (build(nav2_src / "rolling", root / name, programs=programs, tc=tc), root / name)
    return out


@pytest.mark.parametrize("name", TARGET_BUILDS)
def test_each_target_records_its_toolchain_and_the_arithmetic_found_in_it(target_builds, name):
    doc, _ = target_builds[name]
    target, flags, arith = TARGET_BUILDS[name]
    extra = [flags] if flags else ["-march=x86-64-v3"] if target == "x86-64-v3" else []
    assert doc["target"] == target and doc["flags"] == ["-std=c++17", "-O2", *extra]
    assert doc["machine"].split("-")[0] == ("aarch64" if target == "aarch64" else "x86_64")
    assert (doc["runner"][:1] == ["qemu-aarch64"]) == (target == "aarch64")
    found = doc["arithmetic"]
    assert found["name"] == arith and found["unexpressible"] == []
    # every site in both updateCells, the six bilinear lines, both path steps (14 instructions)
    assert found["fused_instructions"] == (0 if flags else 14)
    assert doc["git_commit"] is None and doc["git_commit_note"]  # ../shared is no checkout of Nav2


def test_the_builds_differ_as_their_arithmetic_says(builds, target_builds):
    """On the example suite: arm64 parts from x86-64 in potentials and paths; x86-64-v3 (fused,
    x86 conversions) gives arm64's potentials bit for bit and its paths except where the
    conversion of an unreached potential decides; arm64 without contraction keeps x86-64's
    potentials and differs only there, and there arm64 returns a path where x86-64 returns none."""
    from build_comparison import compare_builds

    def compare(a, b):
        with Oracle(a, traced=False) as x, Oracle(b, traced=False) as y:
            return compare_builds(EXAMPLE, MODES, x, y)

    x86, a64 = builds["rolling"][1], target_builds["aarch64"][1]
    fused = compare(x86, a64)
    assert fused["potential"] > 1000 and fused["path"] > 500 and fused["plan_a_only"] == 0
    v3 = compare(target_builds["x86-64-v3"][1], a64)
    loose = compare(x86, target_builds["aarch64-no-contract"][1])
    assert v3["potential"] == 0 == loose["potential"]
    assert v3["path"] == v3["plan_b_only"] == loose["path"] == loose["plan_b_only"] == fused["plan_b_only"] > 0


def test_a_build_in_another_arithmetic_runs_under_qemu_and_is_compared_in_its_own(target_builds, capsys):
    import numpy as np

    from navfn_smt.spec.costs import add_border

    folder = target_builds["aarch64"][1]
    with Oracle(folder) as oracle:  # runs through the build's runner, unnoticed
        (res,) = oracle.plan(add_border(np.full((6, 6), 50, np.uint8)), [(1, 1, 4, 4)], True)
    assert res.start_reached and len(res.path) > 0
    # the compiled backend computes in the build's arithmetic (the fix too: the next test but one)
    assert main(["difftest", "--oracle", str(folder), "--quiet"]) == 0
    assert "4400 passed, 0 failed" in capsys.readouterr().out


@pytest.mark.parametrize("name", TARGET_BUILDS)
def test_the_spec_in_the_arithmetic_found_agrees_with_each_build_live(target_builds, name):
    """The spec in the arithmetic each build was found to have: every case of the example suite,
    both modes, white-box (path, potential, trace, cycles, updates), bit for bit; the reference
    spec itself for arm64, the compiled backend (held to it by tests/test_backend_conformance.py
    in each arithmetic) for the others."""
    from navfn_smt.under_test import PlannerUnderTest

    doc, folder = target_builds[name]
    backend = "reference" if name == "aarch64" else "jit"
    with Oracle(folder) as oracle:
        s = run_live(EXAMPLE, MODES, backend, oracle, planner=PlannerUnderTest.of_build(folder)).as_dict()
    assert s["failed"] == 0 and s["passed"] == 4400, s["disagreements"][:1]


@pytest.mark.parametrize("name", ["aarch64", "x86-64-v3"])
def test_the_committed_counterexamples_plan_on_each_build_as_the_spec_in_its_arithmetic(target_builds, name):
    """Every committed counterexample's map, every case, both modes, on the C++ built for arm64
    and for x86-64-v3, against the spec in the arithmetic found in each build, white-box and bit
    for bit: so which of them is a counterexample in that arithmetic (``is_one_in`` of each
    counterexample.json, held to the spec by tests/test_counterexamples.py) is what that C++ does."""
    from navfn_smt.under_test import PlannerUnderTest

    doc, folder = target_builds[name]
    root = Path(__file__).resolve().parent / "data" / "counterexamples"
    with Oracle(folder) as oracle:
        s = run_live(root, MODES, "jit", oracle, planner=PlannerUnderTest.of_build(folder)).as_dict()
    assert s["failed"] == 0 and s["passed"] == 2 * len(discover(root)), s["disagreements"][:1]


def test_the_patched_arm64_cpp_equals_the_fixed_spec_in_its_arithmetic(target_builds, capsys):
    """Rolling patched by the fix and built for arm64 (navfn-fixed, under qemu-user): the fixed
    spec in the arithmetic found in that build agrees with it on the example suite and on every
    committed counterexample, white-box and bit for bit, both modes (among them the unreached
    starts the original leaves with a path on arm64, which the patched propagation reaches)."""
    _, folder = target_builds["aarch64"]
    root = Path(__file__).resolve().parent / "data" / "counterexamples"
    for suite in ([], [str(root)]):
        assert main(["difftest", *suite, "--variant", "fixed", "--oracle", str(folder)]) == 0
        assert ", 0 failed" in capsys.readouterr().out


@pytest.mark.parametrize("wrong", ["path_step", "planar", "conversion"])
def test_an_arithmetic_wrong_on_purpose_is_caught_by_the_difftest(target_builds, wrong):
    """arm64's arithmetic with one of its float sites unfused, or with x86-64's conversion: the
    live difftest against the arm64 build fails.  (The double sites, quadratic and bilinear, are
    narrowed to float after the multiply-add: unfused, they changed no result of the example
    suite, nor the quadratic's on 2,000,000 random quotients; docs/toolchains.md.)"""
    from dataclasses import replace

    from navfn_smt.spec.arithmetic import KNOWN
    from navfn_smt.under_test import PlannerUnderTest

    arm = KNOWN["aarch64"]
    bad = (replace(arm, conversion="indefinite") if wrong == "conversion"
           else replace(arm, fused=arm.fused - {wrong}))
    with Oracle(target_builds["aarch64"][1]) as oracle:
        s = run_live(EXAMPLE, MODES, "jit", oracle, planner=PlannerUnderTest(arithmetic=bad)).as_dict()
    assert s["failed"] > 0, wrong


def test_the_plugin_model_in_the_arithmetic_found_agrees_with_the_arm64_plugin(target_builds, capsys):
    """The planner plugin built for arm64: its own multiply-adds (mapToWorld, squared_distance,
    the yaw quaternion) are found fused; the model computing as found agrees with it on generated
    costmaps, poses and parameters; with mapToWorld or NavFn's arithmetic left as x86-64's it
    does not."""
    from navfn_smt.difftest.plugin_live import generated_configs, run_plugin_live
    from navfn_smt.oracle.client import PluginOracle
    from navfn_smt.spec.arithmetic import KNOWN, PluginArithmetic

    doc, folder = target_builds["aarch64"]
    assert doc["plugin_arithmetic"]["fused"] == ["map_to_world", "squared_distance", "yaw_quaternion"]
    assert main(["difftest", "--level", "plugin", "--oracle", str(folder), "--configs", "25", "--quiet"]) == 0
    assert ", 0 failed" in capsys.readouterr().out
    configs = list(generated_configs("rolling", 25, 0, 24))
    found = PlannerUnderTest.of_build(folder).plugin_arithmetic()
    with PluginOracle(folder) as oracle:
        for wrong in (PluginArithmetic(found.navfn, found.fused - {"map_to_world"}),
                      PluginArithmetic(KNOWN["x86-64"], found.fused)):
            assert run_plugin_live(configs, oracle, arith=wrong).as_dict()["failed"] > 0, wrong.name


def test_the_fixed_plugin_model_agrees_with_the_patched_arm64_plugin(target_builds, capsys):
    """The patched plugin built for arm64 and the fixed model in the arithmetic found in it
    agree on generated configurations, among them starts one cell past the map's edge (configuration
    15 of seed 0, a 12x9 map with the start at x = 12), whose propagation the model runs on the
    spec: it ran in x86-64's arithmetic there, and a path pose differed by a float32 ulp."""
    _, folder = target_builds["aarch64"]
    assert main(["difftest", "--level", "plugin", "--variant", "fixed", "--oracle", str(folder),
                 "--configs", "20", "--quiet"]) == 0
    out = capsys.readouterr().out
    assert ", 0 failed" in out and " passed" in out, out[-500:]


def test_diagnose_judges_a_plan_as_the_arm64_build_computes_it(target_builds, tmp_path, capsys):
    """A Nav2 plan the arm64 plugin makes otherwise than x86-64's (30 poses against 29: generated
    configuration 387, pair 2): ``diagnose`` in the arithmetic found in that build gives the C++'s
    plan and says which arithmetic it judged; in x86-64's it gives the other.  The CLI names it,
    refuses ``--target aarch64`` without a build and a sweep in that arithmetic."""
    import itertools

    import numpy as np

    from navfn_smt.diagnose.core import diagnose
    from navfn_smt.difftest.plugin_live import PluginConfig, generated_configs, run_plugin_live

    doc, folder = target_builds["aarch64"]
    found = PlannerUnderTest.of_build(folder).plugin_arithmetic()
    cfg = next(itertools.islice(generated_configs("rolling", 388, 0, 24), 387, 388))
    start, goal = cfg.pairs[2]
    arm, x86 = (diagnose(cfg.costmap, start, goal, cfg.params, arith=a) for a in (found, None))
    assert arm.ok and x86.ok and (len(arm.run.poses), len(x86.run.poses)) == (30, 29)
    assert arm.arith == found and "aarch64" in arm.arith.name and "aarch64" not in x86.arith.name
    one = [PluginConfig(cfg.costmap, cfg.params, [(start, goal)], cfg.name)]
    with PluginOracle(folder) as oracle:  # the arm64 C++ plans as the arm64 diagnosis, not as x86-64's
        assert run_plugin_live(one, oracle, arith=found).as_dict()["failed"] == 0
        assert run_plugin_live(one, oracle).as_dict()["failed"] == 1
    costs = tmp_path / "costs.npy"
    np.save(costs, cfg.costmap.costs)
    params = tmp_path / "params.yaml"  # the configuration's planner parameters (no global_costmap: none runs)
    params.write_text("planner_server:\n  ros__parameters:\n    planner_plugins: [GridBased]\n    GridBased:\n"
                      f"      plugin: nav2_navfn_planner::NavfnPlanner\n      tolerance: {cfg.params.tolerance}\n"
                      f"      use_astar: {str(cfg.params.use_astar).lower()}\n")
    where = ["--params", str(params), "--resolution", str(cfg.costmap.resolution), "--origin", str(cfg.costmap.origin_x),
             str(cfg.costmap.origin_y), "--start", str(start.x), str(start.y), "--goal", str(goal.x), str(goal.y)]
    report = tmp_path / "d.json"
    assert main(["diagnose", str(costs), *where, "--oracle", str(folder), "--json", str(report)]) == 0
    out = capsys.readouterr().out
    assert "judged   original, the C++ of rolling for aarch64, aarch64 arithmetic" in out, out
    got = json.loads(report.read_text())
    assert got["planner"]["arithmetic"] == "aarch64" and got["arithmetic"] == found.name
    assert got["results"][0]["poses"] == 30
    assert main(["diagnose", str(costs), *where, "--target", "aarch64"]) == 2
    assert "give --oracle DIR" in capsys.readouterr().err
    assert main(["diagnose", str(costs), *where[:-3], "--sweep", "5", "--oracle", str(folder)]) == 2
    assert "--sweep computes in x86-64's arithmetic only" in capsys.readouterr().err


def test_each_call_of_the_plugins_squared_distance_is_compared_with_the_square_it_fused(nav2_src, tmp_path):
    """Jazzy's plugin for x86-64-v3 fuses fma(dy, dy, dx * dx) in the tolerance search's copy of
    squared_distance and fma(dx, dx, dy * dy) in the smoothing's: found per call, and the model
    computing so agrees with the build on the two generated configurations (of the first 41) where
    the order changes a plan; with dx's square in every call it does not."""
    from dataclasses import replace

    from navfn_smt.difftest.plugin_live import generated_configs, run_plugin_live
    from navfn_smt.errors import NavfnInputError
    from navfn_smt.oracle.targets import toolchain

    tc = toolchain("x86-64-v3")
    try:
        tc.runner()
    except NavfnInputError as e:
        pytest.skip(str(e))
    doc = build(nav2_src / "jazzy", tmp_path / "b", programs=("navfn-plugin",), tc=tc)
    assert doc["plugin_arithmetic"]["squared_distance_orders"] == {
        "same_position": "dx", "smooth_goal": "dx", "smooth_last": "dx", "tolerance": "dy"}
    configs = [c for k, c in enumerate(generated_configs("jazzy", 41, 0, 24)) if k in (39, 40)]
    found = PlannerUnderTest.of_build(tmp_path / "b").plugin_arithmetic()
    with PluginOracle(tmp_path / "b") as oracle:
        assert found.dy_first == {"tolerance"}
        assert run_plugin_live(configs, oracle, arith=found).as_dict()["failed"] == 0
        assert run_plugin_live(configs, oracle, arith=replace(found, dy_first=frozenset())).as_dict()["failed"] == 2


def test_the_layers_model_in_the_arithmetic_found_agrees_with_the_fused_layers(target_builds):
    """Rolling's costmap layers built for x86-64-v3: distanceToLine (the inscribed radius) and the
    cost table's index are found fused, with A * C and C * C the products rounded once; the model
    computing so agrees with the layers on generated maps and parameters; computing as x86-64's
    layers do, it does not."""
    from navfn_smt.difftest.layers_live import generated_configs, run_layers_live
    from navfn_smt.oracle.client import LayersOracle
    from navfn_smt.spec.arithmetic import LAYERS_X86_64

    doc, folder = target_builds["x86-64-v3"]
    assert doc["layers_arithmetic"]["fused"] == ["distance_to_line", "lut_index"]
    assert doc["layers_arithmetic"]["orders"] == {"dot": "A", "len_sq": "C"}
    found = PlannerUnderTest.of_build(folder).layers_arithmetic()
    with LayersOracle(folder) as oracle:
        assert run_layers_live(generated_configs("rolling", 40, 0), oracle, arith=found).as_dict()["failed"] == 0
        assert run_layers_live(generated_configs("rolling", 40, 0), oracle, arith=LAYERS_X86_64).as_dict()["failed"] > 0


def test_the_conversion_probe_answers_as_the_spec_converts(target_builds):
    from navfn_smt.oracle.arithmetic import EXPECTED

    for name, (doc, _) in target_builds.items():
        probe = doc["arithmetic"]["conversion_probe"]["outputs"]
        assert probe == EXPECTED[doc["arithmetic"]["conversion"]], name
    assert target_builds["aarch64"][0]["arithmetic"]["conversion"] == "saturating"
    assert target_builds["x86-64-v3"][0]["arithmetic"]["conversion"] == "indefinite"


# --------------------------------------------------------------------------- the user's own binary
def _navfn_library(nav2_src, out: Path, cxx: str, flags=("-g",)) -> Path:
    """navfn.cpp of Rolling as a package build makes it: a shared library, -fPIC -O2 (-g)."""
    import subprocess

    from navfn_smt.oracle import build as B

    pkg = nav2_src / "rolling" / "nav2_navfn_planner"
    cmd = [cxx, "-std=c++17", "-fPIC", "-O2", *flags, "-shared", f"-I{B.HERE / 'stubs'}", f"-I{pkg / 'include'}",
           f"-I{nav2_src / 'rolling' / 'nav2_core' / 'include'}", f"-I{B.HERE}", "-DNAVFN_SMT_CANCEL_CHECKER",
           str(pkg / "src" / "navfn.cpp"), "-o", str(out)]
    subprocess.run(cmd, check=True)
    return out


@pytest.fixture(scope="module")
def library_builds(nav2_src, target_builds, tmp_path_factory) -> dict:
    """Oracle builds linking a NavFn library built here for x86-64 and for aarch64."""
    root = tmp_path_factory.mktemp("libraries")
    out = {}
    for target, cxx in (("x86-64", "g++"), ("aarch64", "aarch64-linux-gnu-g++")):
        lib = _navfn_library(nav2_src, root / f"libnavfn_{target}.so", cxx)
        out[target] = (build(nav2_src / "rolling", root / target, library=lib), root / target)
    return out


def test_a_library_build_links_the_users_binary_and_finds_its_arithmetic_in_its_machine_code(library_builds,
                                                                                             target_builds, capsys):
    from build_comparison import compare_builds

    for target, (doc, folder) in library_builds.items():
        assert doc["programs"] == ["navfn-plain"] and doc["library"]["target"] == doc["target"] == target
        assert doc["arithmetic"]["name"] == target and doc["arithmetic"]["unexpressible"] == []
    # the x86-64 library agrees with the spec (path, potential, start reached: no trace in a library)
    assert main(["difftest", "--oracle", str(library_builds["x86-64"][1]), "--quiet"]) == 0
    assert "4400 passed, 0 failed" in capsys.readouterr().out
    # the arm64 library's code is the arm64 program's: the same answers bit for bit
    assert library_builds["aarch64"][0]["arithmetic"]["fused_instructions"] == 14
    with Oracle(library_builds["aarch64"][1], traced=False) as a, \
            Oracle(target_builds["aarch64"][1], traced=False) as b:
        same = compare_builds(EXAMPLE, MODES, a, b)
    assert same["runs"] == 4400 and same["potential"] == same["path"] == 0


def test_a_library_without_line_information_or_of_another_machine_is_named(nav2_src, target_builds, tmp_path,
                                                                          capsys):
    lib = _navfn_library(nav2_src, tmp_path / "libnavfn.so", "aarch64-linux-gnu-g++", flags=())
    doc = build(nav2_src / "rolling", tmp_path / "nodebug", library=lib)
    assert "no source line" in doc["arithmetic"]["unexpressible"][0]  # 14 fused, none traceable
    assert main(["difftest", "--oracle", str(tmp_path / "nodebug")]) == 2
    assert "cannot express" in capsys.readouterr().err
    args = ["oracle", "build", str(nav2_src / "rolling"), "--library", str(lib), "--target", "x86-64",
            "--out", str(tmp_path / "o")]
    assert main(args) == 2
    err = capsys.readouterr().err
    assert "built for aarch64" in err and err.count("\n") == 1 and not (tmp_path / "o").exists()
    (tmp_path / "not.so").write_text("text")
    assert main(["oracle", "build", str(nav2_src / "rolling"), "--library", str(tmp_path / "not.so"),
                 "--out", str(tmp_path / "o")]) == 2
    assert "not an ELF shared library" in capsys.readouterr().err


def test_golden_files_recorded_from_arm64_replay_on_the_spec_in_its_arithmetic(target_builds, tmp_path, capsys):
    """``suite record --oracle`` from the arm64 build, then ``difftest SUITE --target aarch64``
    without the build: bit for bit; in x86-64's arithmetic the same files fail; the compiled
    backend computes in it too."""
    suite = tmp_path / "suite"
    shutil.copytree(EXAMPLE, suite)
    oracle = str(target_builds["aarch64"][1])
    assert main(["suite", "record", str(suite), "--oracle", oracle, "--overwrite", "--quiet"]) == 0
    assert main(["difftest", str(suite), "--target", "aarch64", "--quiet"]) == 0
    assert "4400 passed, 0 failed" in capsys.readouterr().out
    assert main(["difftest", str(suite), "--quiet"]) == 1
    capsys.readouterr()
    assert main(["difftest", str(suite), "--target", "sparc", "--quiet"]) == 2
    assert "no such arithmetic" in capsys.readouterr().err
    # the spec in arm64's arithmetic records the arm64 build's golden files byte for byte
    from conftest import compare_golden_files

    ours = tmp_path / "spec"
    shutil.copytree(EXAMPLE, ours)
    assert main(["suite", "record", str(ours), "--target", "aarch64", "--overwrite", "--quiet"]) == 0
    pairs = [(d / f"golden_{m}.npz", suite / d.relative_to(ours) / f"golden_{m}.npz")
             for d in discover(ours) for m in MODES]
    assert len(pairs) == 28 and [compare_golden_files(a, b) for a, b in pairs] == [[]] * 28
    assert main(["suite", "record", str(ours), "--target", "aarch64", "--oracle", oracle, "--overwrite"]) == 2


def test_nav2_benchmark_plans_with_an_arm64_plugin_in_its_arithmetic(target_builds, tmp_path, capsys):
    """Rolling's plugin built for arm64: the benchmark's model plans in the arithmetic found in it
    and agrees with it on every pose, NavFn as shipped and fixed (the arm64 build of the patched
    sources), each in the arithmetic found in that build."""
    from test_nav2_benchmark import MARGIN, write_map

    _, folder = target_builds["aarch64"]
    out = tmp_path / "r.json"
    assert main(["nav2-benchmark", str(write_map(tmp_path)), "--pairs", "4", "--margin", str(MARGIN), "--mode",
                 "astar", "--oracle", str(folder), "--json", str(out)]) == 0
    text = capsys.readouterr().out
    assert "the model in aarch64" in text
    (m,) = json.loads(out.read_text())["maps"]
    assert [r["planner"] for r in m["rows"]] == ["NavFn original A*", "NavFn fixed A*"] and m["differences"] == []


@pytest.mark.parametrize("behaviour", ["silent", "gone", "ends"])
def test_a_program_that_does_not_answer_is_stopped_and_named(tmp_path, monkeypatch, behaviour):
    """A build's program that sends nothing (a loop, or a request it cannot finish under qemu) is
    stopped after ``ANSWER_SECONDS`` with an error naming it; one that has ended before the
    request (a closed pipe) or ends after reading it is named too, never a traceback."""
    import time

    import numpy as np

    from navfn_smt.errors import NavfnInputError
    from navfn_smt.oracle.client import _Program

    (tmp_path / "build.json").write_text(json.dumps({"programs": ["navfn-traced"]}))
    program = tmp_path / "navfn-traced"
    # the request below is 41 bytes: 4 ints, 9 costs, one case of 4 ints
    body = {"silent": "sleep 60", "gone": "exit 3", "ends": "head -c 41 > /dev/null; exit 3"}[behaviour]
    program.write_text(f"#!/bin/sh\n{body}\n")
    program.chmod(0o755)
    monkeypatch.setattr(_Program, "ANSWER_SECONDS", 1.0)
    t0 = time.monotonic()
    with Oracle(tmp_path) as oracle:
        if behaviour == "gone":
            oracle.proc.wait(timeout=30)  # its end of the pipe closed before the request is written
        says = "sent nothing for 1 s" if behaviour == "silent" else r"stopped answering \(exit status 3\)"
        with pytest.raises(NavfnInputError, match=says):
            oracle.plan(np.full((3, 3), 50, np.uint8), [(0, 0, 2, 2)], True)
    assert time.monotonic() - t0 < 30
