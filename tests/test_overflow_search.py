"""The overflow counterexample: a push dropped by a full priority buffer changes the path.

The committed maps (``tests/data/counterexamples/overflow-dijkstra-*``, each in the arithmetic it
was hunted in) are replayed on the JIT with the C++ capacity (10,000) and with buffers that never drop; the reference spec's replay
is cheap on it too.  A short search at the committed size finds a counterexample again.
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from navfn_smt.backends import get_backend
from navfn_smt.maps.suite import load_golden, load_map
from navfn_smt.search.overflow import CAPACITY, first_difference, replay, search_overflow, verdict
from navfn_smt.search.counterexamples import planner_of
from navfn_smt.spec.propagation import unbounded_capacity

DATA = Path(__file__).parent / "data" / "counterexamples"
SAVED = sorted(DATA.glob("overflow-dijkstra-*"))


def _case(d: Path):
    doc = json.loads((d / "counterexample.json").read_text())
    smap = load_map(d)
    sx, sy, gx, gy = (int(v) for v in smap.cases[0])
    assert (doc["start"], doc["goal"]) == ([sx, sy], [gx, gy])
    return doc, smap.costs, (sx, sy), (gx, gy)


def _planner(doc: dict):
    """The planner the counterexample was hunted in (its ``arithmetic``; x86-64's when none)."""
    return planner_of(doc)


def test_a_dijkstra_counterexample_is_committed():
    assert SAVED, "no overflow-dijkstra-* counterexample under tests/data/counterexamples"
    doc, costs, _, _ = _case(SAVED[0])
    assert doc["kind"] == "overflow" and doc["mode"] == "dijkstra"
    assert doc["size"] == [costs.shape[1], costs.shape[0]] and costs.shape[0] == costs.shape[1]


@pytest.mark.parametrize("d", SAVED, ids=lambda d: d.name)
def test_jit_replay_drops_and_changes_the_path(d):
    doc, costs, start, goal = _case(d)
    h, w = costs.shape
    jit = get_backend("jit", _planner(doc))
    bounded = jit.prepare(costs, CAPACITY).run(start, goal, False, trace=False)
    unbounded = jit.prepare(costs, unbounded_capacity(w, h)).run(start, goal, False, trace=False)
    assert bounded.dropped > 0 and unbounded.dropped == 0
    assert first_difference(bounded.path, unbounded.path) is not None
    detail = verdict(bounded, unbounded)
    for k in ("dropped", "path_points", "path_points_unbounded", "first_difference"):
        assert detail[k] == doc["detail"][k], k
    # the default capacity is the C++ one: the plain planner gives the bounded result
    default = jit.prepare(costs).run(start, goal, False, trace=False)
    assert default.dropped == bounded.dropped and default.path.tobytes() == bounded.path.tobytes()


@pytest.mark.parametrize("d", SAVED, ids=lambda d: d.name)
def test_reference_replay_confirms(d):
    doc, costs, start, goal = _case(d)
    detail = replay(costs, start, goal, False, arith=_planner(doc).arithmetic)
    assert detail is not None
    for k in ("dropped", "path_points", "path_points_unbounded", "first_difference"):
        assert detail[k] == doc["detail"][k], k


@pytest.mark.parametrize("d", SAVED, ids=lambda d: d.name)
def test_golden_files_hold_the_dropping_planner(d):
    """The golden files were recorded with the C++ capacity: the JIT reproduces them."""
    from navfn_smt.difftest.record import golden_fields

    smap = load_map(d)
    planner = get_backend("jit", _planner(json.loads((d / "counterexample.json").read_text()))).prepare(smap.costs)
    for mode in ("astar", "dijkstra"):
        stored = load_golden(smap.golden_path(mode), smap)
        fresh = golden_fields(smap, planner, mode == "astar")
        for f, v in fresh.items():
            assert np.asarray(stored[f]).tobytes() == np.asarray(v).tobytes(), (mode, f)


def test_no_drop_no_counterexample():
    costs = np.full((20, 20), 50, np.uint8)
    r = get_backend("jit").prepare(costs).run((2, 2), (17, 17), False, trace=False)
    assert verdict(r, r) is None


@pytest.mark.slow
def test_search_finds_one_at_the_committed_size():
    doc, costs, _, _ = _case(SAVED[0])
    found = search_overflow("dijkstra", size=tuple(doc["size"]), timeout=120, seed=doc.get("seed", 0))
    assert found and found[0].detail["dropped"] > 0 and found[0].detail["replayed_on"] == "reference"


@pytest.mark.parametrize("d", SAVED, ids=lambda d: d.name)
def test_judge_of_a_spec_run(d):
    """``judge`` (what a counterexample replay calls for kind overflow) on the spec's run."""
    from navfn_smt.check.properties import run
    from navfn_smt.search.overflow import judge

    doc, costs, start, goal = _case(d)
    arith = _planner(doc).arithmetic
    detail = judge(run(costs, start, goal, False, arith=arith), arith=arith)
    assert detail is not None and detail["dropped"] == doc["detail"]["dropped"]
    assert judge(run(np.full((12, 12), 50, np.uint8), (2, 2), (9, 9), False)) is None



def test_an_overflow_counterexample_is_judged_in_each_arithmetic_with_its_unbounded_run_there(monkeypatch):
    """``is_one_in`` of an overflow map: in each arithmetic the bounded run and the unbounded one
    the judge compares it with are both planned in that arithmetic (the judge is told which)."""
    from navfn_smt.search import counterexamples as CX
    from navfn_smt.search import overflow as OV
    from navfn_smt.spec.arithmetic import KNOWN

    (d,) = [d for d in SAVED if d.name.endswith("-aarch64")]
    doc, costs, start, goal = _case(d)
    seen = []
    real = OV.judge
    monkeypatch.setattr(OV, "judge", lambda r, capacity=CAPACITY, arith=None: seen.append(arith) or real(r, capacity,
                                                                                                           arith))
    got = CX.judged_in_each(doc, costs, start, goal)
    assert seen == list(KNOWN.values()) and all(v is not None for v in got.values())
