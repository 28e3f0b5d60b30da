"""The search: its screens equal the definitions, it finds what it should on small budgets,
shrinks and confirms what it reports, saves whole directories, and its command line."""

import json

import numpy as np
import pytest

from navfn_smt.check import properties as P
from navfn_smt.cli import main
from navfn_smt.errors import NavfnInputError
from navfn_smt.search import kinds as KD
from navfn_smt.search.counterexamples import judge_kind, read_counterexample, replay, save_counterexample
from navfn_smt.search.hunt import hunt, hunt_smallest, parse_costs, shrink
from navfn_smt.spec.constants import COST_OBS


def _random_map(rng, w, h, lethal=0.2):
    c = rng.integers(50, 254, (h, w)).astype(np.uint8)
    c[rng.random((h, w)) < lethal] = COST_OBS
    c[0, :] = c[-1, :] = c[:, 0] = c[:, -1] = COST_OBS
    return c


def test_screens_equal_the_judges_on_random_maps():
    """Each kind's JIT screen flags exactly the cases its judge flags on the spec (cost: same gap)."""
    rng = np.random.default_rng(7)
    seen = {k: 0 for k in KD.KINDS}
    for _ in range(8):
        w, h = (int(v) for v in rng.integers(4, 8, 2))
        c = _random_map(rng, w, h)
        cells = [(x, y) for y in range(1, h - 1) for x in range(1, w - 1)]
        cases = np.array([(*s, *g) for s in cells for g in cells if s != g])[:30]
        for astar in (True, False):
            b = KD.plan_batch(c, cases, astar)
            scores = {k: KD.KINDS[k].screen(b) for k in KD.KINDS}
            for i, cs in enumerate(cases.tolist()):
                r = P.run(c, cs[:2], cs[2:], astar)
                for k, kind in KD.KINDS.items():
                    d = kind.judge(r)
                    assert (d is not None) == (scores[k][i] > 0), (k, cs, astar)
                    if d is not None:
                        seen[k] += 1
                        if k == "cost":
                            assert d["gap"] == scores[k][i]
    assert seen["cost"] and seen["int-conversion"]


def test_turn_and_oscillation_definitions():
    straight = np.array([[0, 0], [0.5, 0], [1, 0]], np.float32)
    back = np.array([[0, 0], [1, 0], [0.5, 0.1], [1, 0.1]], np.float32)
    assert KD.obtuse_turns(straight) == [] and KD.obtuse_turns(back) == [1, 2]
    right_angle = np.array([[0, 0], [1, 0], [1, 1]], np.float32)
    assert KD.obtuse_turns(right_angle) == []  # exactly 90 degrees is not "more than 90"
    osc = np.array([[0, 0], [1, 0], [0, 0], [2, 2]], np.float32)
    assert KD.oscillation_points(osc) == [2] and KD.oscillation_points(straight) == []


def test_int_conversion_is_observed_without_changing_the_spec():
    """An unreached start: the fallback converts 1e10; the spec's kernels are restored after."""
    from navfn_smt.spec import extraction, kernels

    c = np.full((5, 5), 50, np.uint8)
    c[0, :] = c[-1, :] = c[:, 0] = c[:, -1] = COST_OBS
    c[2, 1:4] = COST_OBS  # wall between start row 1 and goal row 3
    r = P.run(c, (2, 1), (2, 3), True)
    conv = KD.fallback_conversions(r)
    assert conv and conv[0][1] == pytest.approx(1e10)
    assert extraction.K is kernels
    assert KD.KINDS["int-conversion"].judge(r)["start_reached"] is False
    free = P.run(np.where(c == COST_OBS, 50, c) | 0, (2, 1), (2, 3), True)
    assert KD.fallback_conversions(free) == []


def test_cost_hunt_finds_and_keeps_a_gap():
    f = hunt("cost", "astar", (5, 7), timeout=30, seed=1, max_evaluations=300)
    assert f is not None and f.detail["gap"] >= 1000
    assert f.size == (5, 7)
    r = P.run(f.costs, f.start, f.goal, True)
    assert P.cost_gap(r) == f.detail["gap"] >= f.score  # shrinking never lost gap


def test_hunt_is_deterministic_for_a_seed_and_budget():
    a = hunt("cost", "dijkstra", (5, 6), timeout=30, seed=3, max_evaluations=60, shrink_result=False)
    b = hunt("cost", "dijkstra", (5, 6), timeout=30, seed=3, max_evaluations=60, shrink_result=False)
    assert a.detail == b.detail and (a.costs == b.costs).all() and (a.start, a.goal) == (b.start, b.goal)


@pytest.mark.parametrize("kind", ["incomplete", "unreached"])
def test_incomplete_and_unreached_are_found_and_shrunk(kind):
    f = hunt(kind, "astar", (8, 8), timeout=20, seed=0)
    assert f is not None, f"no {kind} counterexample in 20 s"
    assert f.interior <= 36
    r = P.run(f.costs, f.start, f.goal, True)
    assert KD.KINDS[kind].judge(r) is not None


def test_shrink_drops_what_is_not_needed():
    """A gap-free map is left alone; a big incomplete map shrinks."""
    c = np.full((6, 6), 50, np.uint8)
    c[0, :] = c[-1, :] = c[:, 0] = c[:, -1] = COST_OBS
    c2, s, g = shrink("incomplete", c, (1, 1), (4, 4), True, keep_size=False)
    assert (c2 == c).all() and (s, g) == ((1, 1), (4, 4))


def test_smallest_hunt_reports_the_smallest_size_found():
    f, tried = hunt_smallest("turn", "dijkstra", (6, 6), timeout=20, seed=0, max_evaluations=4000)
    assert f is not None and f.interior <= min(t["interior"] for t in tried if t["found"])
    assert tuple(f.found_size) in {tuple(t["size"]) for t in tried if t["found"]}
    assert tried[0]["size"] == [6, 6]  # the largest interior first


def test_save_and_replay(tmp_path):
    f = hunt("cost", "astar", (5, 5), timeout=20, seed=0, max_evaluations=50)
    d = save_counterexample(tmp_path, f.costs, f.start, f.goal, True, "cost", f.detail, extra={"seed": 0})
    assert d.name == "cost-astar-5x5" and (d / "picture.png").stat().st_size > 0
    assert not [p for p in tmp_path.iterdir() if p.name.startswith(".")]
    doc = read_counterexample(d)
    assert doc["kind"] == "cost" and doc["detail"]["gap"] == f.detail["gap"]
    r = replay(d)
    assert r["golden"] == {"reference": [], "jit": []} and r["detail"]["gap"] == f.detail["gap"]
    # a tampered golden file is caught bit for bit
    import numpy as np_
    g = dict(np_.load(d / "golden_astar.npz"))
    g["start_potential"] = np_.nextafter(g["start_potential"], np_.float32(np_.inf)).astype(np_.float32)
    np_.savez_compressed(d / "golden_astar.npz", **g)
    assert replay(d)["golden"]["jit"] == ["astar start_potential"]


def test_property_kinds_dispatch_to_properties():
    c = np.full((4, 4), 50, np.uint8)
    c[0, :] = c[-1, :] = c[:, 0] = c[:, -1] = COST_OBS
    r = P.run(c, (1, 1), (2, 2), True)
    assert judge_kind("complete", r) is None and judge_kind("valid-path", r) is None
    with pytest.raises(NavfnInputError):
        judge_kind("no-such-kind", r)


def test_parse_costs():
    assert parse_costs(None) == (50, 253) and parse_costs("60..200") == (60, 200)
    for bad in ("x", "10..300", "200..100"):
        with pytest.raises(NavfnInputError):
            parse_costs(bad)


def test_cli_search_writes_only_with_out(tmp_path, capsys, monkeypatch):
    monkeypatch.chdir(tmp_path)
    js = tmp_path / "r.json"
    assert main(["search", "oscillation", "--size", "6", "6", "--mode", "dijkstra", "--timeout", "10",
                 "--json", str(js)]) == 0
    assert [p.name for p in tmp_path.iterdir()] == ["r.json"]
    doc = json.loads(js.read_text())
    assert doc["kind"] == "oscillation" and doc["findings"][0]["detail"]["oscillations"] >= 1
    err = capsys.readouterr().err
    assert "[search oscillation dijkstra" in err


def test_cli_search_errors(tmp_path, capsys):
    assert main(["search", "cost", "--size", "2", "5"]) == 2
    assert main(["search", "cost", "--costs", "1..999"]) == 2
    (tmp_path / "f").write_text("")
    assert main(["search", "cost", "--out", str(tmp_path / "f"), "--timeout", "1"]) == 2
    assert main(["search"]) == 2
    err = capsys.readouterr().err
    assert err.count("navfn-smt: error:") == 4


def test_overflow_dispatch_reports_a_missing_module(monkeypatch, capsys):
    import sys

    monkeypatch.setitem(sys.modules, "navfn_smt.search.overflow", None)
    assert main(["search", "overflow", "--timeout", "1"]) == 2
    assert "overflow search is not available" in capsys.readouterr().err


def test_summary_of_the_circus_maps():
    """The paper's hand-made circus maps: two of five paths cost 850 more than the optimum."""
    from navfn_smt.cli import EXAMPLE_SUITE
    from navfn_smt.search.summary import summarize

    s = summarize(EXAMPLE_SUITE / "circus", ("astar", "dijkstra"))
    for m in ("astar", "dijkstra"):
        t = s["total"][m]
        assert t["cases"] == t["paths"] == 5 and t["gap_positive"] == 2 and t["gap_max"] == 850
        assert t["incomplete"] == t["unreached"] == t["int_conversion_start_unreached"] == 0


def test_summary_of_the_shared_random_maps(shared_suite):
    """Counts on the shared suite's random category (9,182 cases), as in docs/search.md."""
    from navfn_smt.search.summary import summarize

    s = summarize(shared_suite / "random", ("astar", "dijkstra"))
    a, d = s["total"]["astar"], s["total"]["dijkstra"]
    assert a["cases"] == d["cases"] == 9182
    assert (a["paths"], a["incomplete"], a["oscillation_paths"], a["turn_paths"], a["gap_max"]) == (9161, 21, 21, 998, 5070)
    assert (d["paths"], d["incomplete"], d["oscillation_paths"], d["turn_paths"], d["gap_max"]) == (9165, 17, 25, 1003, 3845)
    assert a["int_conversion_mid_path"] == d["int_conversion_mid_path"] == 0


def test_a_hunts_clock_starts_once_its_planner_is_compiled(monkeypatch):
    """Compiling the planner (about 20 s with a cold JIT cache) is not taken from --timeout: with
    a compile slower than the whole budget the hunt still evaluates maps and finds its map."""
    import time

    from navfn_smt.search import hunt as H

    compile_ = H._compile
    seen = []

    def slow(*args):
        compile_(*args)
        seen.append(args)
        time.sleep(3.0)

    monkeypatch.setattr(H, "_compile", slow)
    f = H.hunt("incomplete", "dijkstra", (8, 8), 2.0, seed=0, shrink_result=False)
    assert seen == [("incomplete", "dijkstra", H.DEFAULT_COSTS, H.ORIGINAL)]
    assert f is not None and f.evaluations > 0
    f, tried = H.hunt_smallest("incomplete", "dijkstra", (6, 6), 2.0, seed=0)
    assert len(seen) == 2 and sum(t["evaluations"] for t in tried) > 0
