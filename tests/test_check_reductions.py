"""The reductions of the bounded checks, and the checks themselves, held against concrete runs.

* ReachedWithinComponent's use in ``check`` (:func:`navfn_smt.check.bounded.reduce_cases`):
  a layout and its representative (every cell outside the goal's component lethal) plan
  alike, potentials and path bit for bit, and a start outside the component is never
  reached and gets no path; each on every layout of the small sizes, both modes, both
  variants.
* The committed reports of ``check`` (docs/reports/check-*.json): every size proved there
  shows no failure in the concrete sweep over the reduced cost set
  (:mod:`navfn_smt.check.soundness`).
"""

import functools
import json
from pathlib import Path

import numpy as np
import pytest

from navfn_smt.spec import fixes
from navfn_smt.check import properties as P
from navfn_smt.check.bounded import Case, cases, component, reduce_cases, representative
from navfn_smt.check.soundness import COSTS, failing, sweep
from navfn_smt.spec.constants import POT_HIGH
from navfn_smt.spec.extraction import ExtractionExit, exit_code

REPORTS = Path(__file__).resolve().parents[1] / "docs" / "reports"
COUNTEREXAMPLES = Path(__file__).resolve().parent / "data" / "counterexamples"


def _costs(case: Case, rng) -> dict:
    return {k: int(rng.integers(50, 254)) for k in range(case.nx * case.ny)}


def _same_run(a: P.Run, b: P.Run) -> bool:
    return (a.potential.tobytes() == b.potential.tobytes() and a.exit == b.exit
            and a.path.tobytes() == b.path.tobytes())


@pytest.mark.parametrize("variant", fixes.NAMES)
@pytest.mark.parametrize("size", [(3, 6), (6, 3), (4, 4), (4, 5)])
def test_a_layout_plans_as_its_representative_does(size, variant):
    rng = np.random.default_rng(sum(size))
    red = reduce_cases(cases(*size, (True, False)))
    seen = outside = 0
    for case in cases(*size, (True, False)):
        if size == (4, 5) and rng.random() > 0.1:
            continue  # a tenth of the larger size's 4,608 cases
        costs = _costs(case, rng)
        run = P.run(case.costs_array(costs), case.start, case.goal, case.astar, fix=fixes.named(variant))
        comp = component(case.nx, case.ny, case.lethal, case.goal)
        if case.start[1] * case.nx + case.start[0] not in comp:
            outside += 1
            assert run.start_potential >= np.float32(POT_HIGH) and len(run.path) == 0, case
            continue
        rep = representative(case, comp)
        assert rep in red.representatives
        assert _same_run(run, P.run(rep.costs_array(costs), rep.start, rep.goal, rep.astar, fix=fixes.named(variant))), case
        seen += 1
    assert seen and outside


@pytest.mark.parametrize("size", [(3, 6), (4, 4)])
def test_in_aarch64s_arithmetic_an_outside_start_is_explored_by_its_representative(size):
    """In aarch64's arithmetic NoPathWithoutFinitePotential is refuted, so ``check`` explores a
    start outside the goal's component instead of deciding it (:func:`outside_decided`), by its
    representative; a layout and its representative plan alike there bit for bit, outside
    starts included, and some outside start gets a path (what the reduction would have hidden)."""
    from navfn_smt.check.runner import outside_decided
    from navfn_smt.under_test import PlannerUnderTest

    arm = PlannerUnderTest.of_target("aarch64")
    assert not outside_decided(arm)
    assert outside_decided(PlannerUnderTest.of_target("x86-64")) and outside_decided(
        PlannerUnderTest.of_target("x86-64-v3"))
    red = reduce_cases(cases(*size, (True, False)), decide_outside=False)
    assert red.outside == 0 and sum(red.representatives.values()) == red.total
    rng = np.random.default_rng(sum(size))
    outside = paths = 0
    for case in cases(*size, (True, False)):
        costs = _costs(case, rng)
        comp = component(case.nx, case.ny, case.lethal, case.goal)
        if case.start[1] * case.nx + case.start[0] in comp:
            continue
        outside += 1
        rep = representative(case, comp)
        assert rep in red.representatives
        run = P.run(case.costs_array(costs), case.start, case.goal, case.astar, arith=arm.arithmetic)
        assert _same_run(run, P.run(rep.costs_array(costs), rep.start, rep.goal, rep.astar,
                                    arith=arm.arithmetic)), case
        paths += len(run.path) > 0
    assert outside and paths


def test_the_reduction_counts_every_case_once():
    red = reduce_cases(cases(3, 7, (True, False)))
    assert red.total == 2 * 2**5 * 25
    assert sum(red.representatives.values()) + red.outside == red.total
    assert len(red.representatives) < red.total // 3


def test_a_smaller_component_would_be_caught():
    """The comparison above fails for a reduction that drops a cell of the component."""
    case = Case(3, 6, frozenset(), (1, 1), (1, 4), False)
    costs = {k: 100 for k in range(18)}
    wrong = Case(3, 6, frozenset({1 * 3 + 1 + 3}), case.start, case.goal, False)  # (1, 2) made lethal
    a = P.run(case.costs_array(costs), case.start, case.goal, False)
    b = P.run(wrong.costs_array(costs), wrong.start, wrong.goal, False)
    assert not _same_run(a, b)


def test_the_sweep_judges_a_known_incomplete_map():
    from navfn_smt.maps.suite import load_map
    from navfn_smt.search.kinds import plan_batch

    smap = load_map(COUNTEREXAMPLES / "incomplete-astar-5x5")
    b = plan_batch(smap.costs, smap.cases[:1], True)
    finite = b.out["start_potential"] < np.float32(POT_HIGH)
    returned = b.out["exit"] == exit_code(ExtractionExit.NEAR_GOAL)
    assert failing("complete", finite, returned, b.connected()).all()
    assert not failing("start-reached", finite, returned, b.connected()).any()


def test_the_random_sample_reports_failures_the_spec_confirms():
    """``soundness.sample`` (``check_soundness.py --open W H --random MAPS``): on 7x7, where
    NavFn is known to fail, its first failure of each property is a map the reference spec
    judges the same way; the same seed gives the same count."""
    from navfn_smt.check.soundness import sample

    got = sample(7, 7, 1500, seed=3)
    assert got.maps == 1500 and got.cases == 1500 * 25 * 25 * 2
    assert got.failures["complete"] > 0
    for name in ("complete", "start-reached"):
        if name in got.first:
            f = got.first[name]
            r = P.run(np.array(f["costs"], np.uint8), tuple(f["start"]), tuple(f["goal"]), f["mode"] == "astar")
            assert P.judge(name, r) is not None
    assert sample(7, 7, 1500, seed=3).failures == got.failures


def _proved_sizes():
    """(size, property, variant, float32 semantics) of every size a committed check report proves."""
    out = []
    for f in sorted(REPORTS.glob("check-*.json")) + sorted(REPORTS.glob("aarch64/*/check-*.json")):
        doc = json.loads(f.read_text())
        for r in doc["results"]:
            if r["status"] == "proved" and r["property"] in ("complete", "start-reached"):
                out.append((tuple(r["size"]), r["property"], doc.get("variant", "original"), doc.get("semantics", "fp32")))
    return sorted(set(out))


@functools.lru_cache(maxsize=None)  # one sweep judges every property: run once per size and planner
def _sweep(size: tuple, variant: str, semantics: str):
    from navfn_smt.smt.domains import FP32_SEMANTICS
    from navfn_smt.under_test import PlannerUnderTest

    return sweep(*size, planner=PlannerUnderTest(fixes.named(variant), FP32_SEMANTICS[semantics]))


@pytest.mark.parametrize("size,name,variant,semantics",
                         [s for s in _proved_sizes() if (s[0][0] - 2) * (s[0][1] - 2) <= 5])
def test_a_proved_size_shows_no_failure_in_the_concrete_sweep(size, name, variant, semantics):
    """Every map of the size over a reduced cost set, planned in the report's arithmetic."""
    got = _sweep(tuple(size), variant, semantics)
    assert got.cases == 6 ** ((size[0] - 2) * (size[1] - 2)) * 2 * ((size[0] - 2) * (size[1] - 2)) ** 2
    assert got.failures[name] == 0, got.first.get(name)
    assert got.costs == COSTS


def test_every_proved_size_shows_no_failure_on_random_maps_over_the_whole_cost_range():
    """The reduced set tries 5 of the 204 passable costs per cell; 300 seeded maps of each proved
    size of up to 5 cells draw each cost from the whole range 50..253, in the report's arithmetic."""
    from navfn_smt.check.soundness import sample
    from navfn_smt.smt.domains import FP32_SEMANTICS
    from navfn_smt.under_test import PlannerUnderTest

    proved = [s for s in _proved_sizes() if (s[0][0] - 2) * (s[0][1] - 2) <= 5]
    assert len(proved) > 10
    for size, name, variant, semantics in proved:
        planner = PlannerUnderTest(fixes.named(variant), FP32_SEMANTICS[semantics])
        got = sample(*size, 300, seed=1, planner=planner)
        assert got.maps == 300 and got.costs == (50, 253)
        assert got.failures[name] == 0, (size, name, variant, semantics, got.first.get(name))
