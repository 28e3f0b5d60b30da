"""Differential tests against golden outputs of the C++ original.

* the example suite shipped with the package (a real subset of the shared suite),
  both backends, both modes: runs on every clone;
* an overflow subset of the large suite (two Dijkstra cases whose priority buffers
  overflow), committed under tests/data: runs on every clone;
* the whole shared suite with the JIT backend, and a deterministic sample of it with the
  reference backend, when ../shared is present.
"""


import numpy as np
import pytest

from navfn_smt.backends import get_backend
from navfn_smt.cli import EXAMPLE_SUITE
from navfn_smt.difftest.runner import Summary, Task, plan_tasks, run_suite, run_task, summarize
from navfn_smt.maps.suite import discover, load_golden, load_map

from conftest import DATA


def _assert_clean(outcomes):
    s = summarize(outcomes)
    cases = outcomes.cases if isinstance(outcomes, Summary) else sum(o.cases for o in outcomes)
    assert s["failed"] == 0, s["disagreements"][:3]
    assert s["passed"] == cases > 0
    return s


@pytest.mark.parametrize("backend", ["jit", "reference"])
def test_example_suite_agrees(backend):
    s = _assert_clean(run_suite(EXAMPLE_SUITE, ("astar", "dijkstra"), backend))
    # every category of the shared suite is represented
    assert {c["category"] for c in s["categories"]} == {
        "ROS", "circus", "columns", "free", "obstacle", "radial", "random", "spiral", "split", "walls"}


def test_overflow_subset_agrees_and_drops_pushes():
    suite = DATA / "overflow-subset"
    _assert_clean(run_suite(suite, ("astar", "dijkstra"), "jit"))
    smap = load_map(discover(suite)[0], suite)
    planner = get_backend("jit").prepare(smap.costs)
    dropped = [planner.run(tuple(c[:2]), tuple(c[2:]), False).dropped for c in smap.cases.tolist()]
    # the large suite's README: Dijkstra drops pushes on this map; these two cases drop some
    assert all(d > 0 for d in dropped), dropped


def test_overflow_subset_reference_backend():
    """The reference spec where the buffers drop pushes on a Nav2-sized map (1000x1000, Dijkstra):
    the case that drops pushes, about 25 s of pure Python (the whole subset, both cases, is
    `navfn-smt difftest tests/data/overflow-subset --backend reference --mode dijkstra`)."""
    suite = DATA / "overflow-subset"
    # case 1 (821 387 621 74) drops pushes
    tasks = plan_tasks(suite, ("dijkstra",), "reference")
    _assert_clean([run_task(Task(t.map_dir, t.root, t.mode, t.backend, 1, 2)) for t in tasks])


def test_shared_suite_reference_sample(shared_suite):
    """Every 601st case of every map, plus the cases whose full potential is stored (the JIT runs
    every case: tests/test_engine_difftest.py; the backends agree bit for bit on generated maps:
    tests/test_backend_conformance.py)."""
    outcomes = []
    for t in plan_tasks(shared_suite, ("astar", "dijkstra"), "reference"):
        if t.lo != 0:  # one pass per map and mode
            continue
        smap = load_map(t.map_dir, shared_suite)
        idx = set(range(0, len(smap.cases), 601))
        idx |= set(load_golden(smap.golden_path(t.mode))["full_index"][:3].tolist())
        for i in sorted(idx):
            outcomes.append(run_task(Task(t.map_dir, t.root, t.mode, "reference", i, i + 1)))
    s = _assert_clean(outcomes)
    assert s["passed"] > 500


def test_large_suite_jit(shared_suite_large):
    s = _assert_clean(run_suite(shared_suite_large, ("astar", "dijkstra"), "jit"))
    assert s["passed"] == 8


def test_tampered_golden_is_reported(tmp_path):
    """The difftest can fail: one path coordinate moved by one ulp is caught and located."""
    import shutil

    src = EXAMPLE_SUITE / "free" / "3x3_free"
    dst = tmp_path / "suite" / "free" / "3x3_free"
    shutil.copytree(src, dst)
    g = dict(np.load(dst / "golden_astar.npz"))
    p = g["path"].copy()
    k = int(g["path_offsets"][5])
    p[k, 0] = np.nextafter(p[k, 0], np.float32(np.inf))
    g["path"] = p
    np.savez(dst / "golden_astar.npz", **g)
    s = summarize(run_suite(tmp_path / "suite", ("astar",), "jit"))
    assert s["failed"] >= 1
    first = s["disagreements"][0]
    assert (first["case_index"], first["field"], first["detail"]["point"]) == (5, "path", 0)


@pytest.mark.parametrize("suite,cases,backend", [("unseen-suite", 2101, "jit"), ("edge-suite", 109, "jit"),
                                                ("edge-suite", 109, "reference")])
def test_suites_recorded_after_the_spec_agree(backend, suite, cases):
    """Suites recorded from the C++ after the spec was written (tests/data): new maps, and
    starts and goals on the lethal border.  The reference spec runs the edge suite whole (the
    unseen suite's 4,202 cases take it a minute; the shared suite's sample below and the backend
    conformance hold it to the same answers)."""
    s = _assert_clean(run_suite(DATA / suite, ("astar", "dijkstra"), backend, jobs=2))
    assert s["passed"] == 2 * cases


@pytest.mark.parametrize("mode", ["astar", "dijkstra"])
def test_jit_batch_equals_golden(mode):
    """The benchmark's batch entry point plans exactly what the C++ planned."""
    for d in discover(EXAMPLE_SUITE):
        smap = load_map(d, EXAMPLE_SUITE)
        g = load_golden(smap.golden_path(mode), smap)
        out = get_backend("jit").prepare(smap.costs).run_batch(smap.cases, mode == "astar")
        assert np.array_equal(out["path_offsets"], g["path_offsets"]), d
        assert np.array_equal(out["path"].view(np.uint32), g["path"].view(np.uint32)), d
        assert np.array_equal(out["start_potential"].view(np.uint32), g["start_potential"].view(np.uint32)), d
        assert np.array_equal(out["start_reached"], g["start_reached"].astype(bool)), d
        assert np.array_equal(out["cycles"], g["cycles"]) and np.array_equal(out["updates"], g["updates"]), d
