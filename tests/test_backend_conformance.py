"""Every backend agrees with the reference spec on every field, bit for bit, on generated maps.

The conformance check for alternative backends: hypothesis draws maps (sizes, every cost
byte 0..255, lethal blobs, uniform fields where potentials tie) and cases (starts and
goals anywhere on the map, in obstacles, on the border, equal to each other), plans with
the reference spec and with each other backend, and compares start_reached, the start
potential's bits, every potential's bits, the path's bits, the trace, cycles, updates,
dropped pushes and the extraction exit; a case the spec refuses as undefined behaviour
must be refused by the backend too.  The batch entry point is held to the same results.
Failing examples are kept by hypothesis and replayed first on the next run.
"""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import HealthCheck, example, given, settings
from hypothesis import strategies as st

from navfn_smt.backends import BACKENDS, get_backend
from navfn_smt.errors import NavfnInputError
from navfn_smt.spec.arithmetic import KNOWN
from navfn_smt.spec.extraction import ExtractionExit, UndefinedBehaviour
from navfn_smt.under_test import PlannerUnderTest

OTHERS = [b for b in BACKENDS if b != "reference"]


@st.composite
def cost_maps(draw):
    """A (height, width) uint8 map: random bytes, a uniform field, or blobs of one cost."""
    w = draw(st.integers(3, 14))
    h = draw(st.integers(3, 14))
    kind = draw(st.sampled_from(["bytes", "uniform", "blobs", "passable"]))
    if kind == "bytes":  # every cost byte, obstacles included
        cells = draw(st.lists(st.integers(0, 255), min_size=w * h, max_size=w * h))
        return np.array(cells, np.uint8).reshape(h, w)
    if kind == "passable":  # what setCostmap produces for free space: 50..253
        cells = draw(st.lists(st.integers(50, 253), min_size=w * h, max_size=w * h))
        return np.array(cells, np.uint8).reshape(h, w)
    base = draw(st.sampled_from([0, 1, 50, 128, 253]))
    arr = np.full((h, w), base, np.uint8)  # uniform: potentials tie everywhere
    if kind == "blobs":
        for _ in range(draw(st.integers(1, 4))):
            x, y = draw(st.integers(0, w - 1)), draw(st.integers(0, h - 1))
            rw, rh = draw(st.integers(1, 3)), draw(st.integers(1, 3))
            arr[y:y + rh, x:x + rw] = draw(st.sampled_from([254, 255, 253, 50]))
    return arr


@st.composite
def planning_cases(draw):
    costs = draw(cost_maps())
    h, w = costs.shape
    cell = st.tuples(st.integers(0, w - 1), st.integers(0, h - 1))
    start = draw(cell)
    goal = draw(st.one_of(cell, st.just(start)))
    return costs, start, goal, draw(st.booleans())


def _planner(arith) -> PlannerUnderTest:
    """NavFn as shipped, in the arithmetic ``arith`` (None: x86-64's)."""
    return PlannerUnderTest() if arith is None else PlannerUnderTest(arithmetic=arith)


def _plan(backend: str, costs, start, goal, astar, capacity=None, arith=None):
    try:
        return get_backend(backend, _planner(arith)).prepare(costs, capacity).run(start, goal, astar, trace=True)
    except UndefinedBehaviour:
        return "undefined"


def _bits(a) -> bytes:
    return np.ascontiguousarray(a, dtype="<f4").tobytes()


def assert_same(ours, ref, backend: str) -> None:
    if isinstance(ref, str) or isinstance(ours, str):
        assert ours == ref, f"{backend}: {ours!r} where the reference gives {ref!r}"
        return
    assert ours.start_reached == ref.start_reached, backend
    assert _bits(ours.start_potential) == _bits(ref.start_potential), backend
    assert _bits(ours.potential) == _bits(ref.potential), f"{backend}: potentials differ"
    assert ours.path.shape == ref.path.shape and _bits(ours.path) == _bits(ref.path), f"{backend}: paths differ"
    assert np.array_equal(ours.trace, ref.trace), f"{backend}: traces differ"
    assert (ours.cycles, ours.updates, ours.dropped) == (ref.cycles, ref.updates, ref.dropped), backend
    assert ours.exit == ref.exit, backend


@pytest.mark.fast
@pytest.mark.parametrize("backend", OTHERS)
@settings(max_examples=300, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(case=planning_cases())
@example(case=(np.full((5, 5), 50, np.uint8), (2, 2), (2, 2), True))  # start == goal
@example(case=(np.full((3, 3), 0, np.uint8), (1, 1), (0, 0), False))  # cost 0, goal on the border
@example(case=(np.full((6, 4), 50, np.uint8), (0, 1), (2, 3), True))  # undefined behaviour at (0, 1)
def test_backend_agrees_with_reference(backend, case):
    costs, start, goal, astar = case
    assert_same(_plan(backend, costs, start, goal, astar), _plan("reference", costs, start, goal, astar), backend)


@pytest.mark.parametrize("backend", OTHERS)
@pytest.mark.parametrize("arith", ["x86-64-v3", "aarch64"])
@settings(max_examples=150, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(case=planning_cases(), data=st.data())
@example(case=(np.full((7, 7), 50, np.uint8), (3, 3), (1, 1), True), data=None)  # potentials differ from x86-64's
def test_backend_agrees_with_reference_in_each_arithmetic(backend, arith, case, data):
    """In a fused arithmetic (and arm64's conversion) too: planning, and extraction alone from any
    cell (where the conversion of an unreached potential decides)."""
    costs, start, goal, astar = case
    a = KNOWN[arith]
    ref = _plan("reference", costs, start, goal, astar, arith=a)
    assert_same(_plan(backend, costs, start, goal, astar, arith=a), ref, f"{backend} in {arith}")
    if isinstance(ref, str) or data is None:
        return
    h, w = costs.shape
    other = data.draw(st.tuples(st.integers(0, w - 1), st.integers(0, h - 1)), label="extraction start")
    n = data.draw(st.integers(-1, 6 * max(w, h)), label="path cycles")
    assert _extract(backend, costs, ref.potential, other, goal, n, a) == \
        _extract("reference", costs, ref.potential, other, goal, n, a)


@pytest.mark.fast
@pytest.mark.parametrize("backend", OTHERS)
@settings(max_examples=200, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(case=planning_cases(), capacity=st.integers(0, 8))
@example(case=(np.full((9, 9), 50, np.uint8), (2, 2), (6, 6), False), capacity=3)
@example(case=(np.full((9, 9), 50, np.uint8), (2, 2), (6, 6), True), capacity=1)
def test_backend_agrees_with_reference_at_small_capacity(backend, case, capacity):
    """Buffers of 0..8 cells: pushes drop on every map, and the backend drops the same ones."""
    costs, start, goal, astar = case
    ref = _plan("reference", costs, start, goal, astar, capacity)
    assert_same(_plan(backend, costs, start, goal, astar, capacity), ref, backend)


def _extract(backend: str, costs, potential, start, goal, n, arith=None):
    try:
        exit_, path = get_backend(backend, _planner(arith)).prepare(costs).extract(potential, start, goal, n)
        return exit_, _bits(path)
    except UndefinedBehaviour:
        return "undefined"


@pytest.mark.fast
@pytest.mark.parametrize("backend", OTHERS)
@settings(max_examples=200, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(case=planning_cases(), data=st.data())
def test_extraction_alone_agrees_with_reference(backend, case, data):
    """``extract`` (calcPath on a given potential, from any cell, with any budget, as the Nav2
    plugin calls it after its tolerance search) agrees bit for bit; so does ``run`` with a budget."""
    costs, start, goal, astar = case
    h, w = costs.shape
    ref = _plan("reference", costs, start, goal, astar)
    if isinstance(ref, str):
        return
    other = data.draw(st.tuples(st.integers(0, w - 1), st.integers(0, h - 1)), label="extraction start")
    n = data.draw(st.integers(-1, 6 * max(w, h)), label="path cycles")
    assert _extract(backend, costs, ref.potential, other, goal, n) == \
        _extract("reference", costs, ref.potential, other, goal, n)

    cycles = data.draw(st.one_of(st.none(), st.integers(0, 2 * w * h)), label="propagation cycles")

    def budgeted(b):
        try:
            return get_backend(b).prepare(costs).run(start, goal, astar, trace=True, path_cycles=n, cycles=cycles)
        except UndefinedBehaviour:
            return "undefined"

    assert_same(budgeted(backend), budgeted("reference"), backend)


@pytest.mark.fast
def test_small_capacity_drops_and_default_does_not():
    """The capacity reaches both planners: 3 cells drop pushes on an open 9x9 map, the default
    (PRIORITYBUFSIZE) and an unbounded capacity do not, and give the same result."""
    from navfn_smt.spec.propagation import unbounded_capacity

    costs = np.full((9, 9), 50, np.uint8)
    for backend in ("reference", *OTHERS):
        small = _plan(backend, costs, (2, 2), (6, 6), False, 3)
        default = _plan(backend, costs, (2, 2), (6, 6), False)
        unbounded = _plan(backend, costs, (2, 2), (6, 6), False, unbounded_capacity(9, 9))
        assert small.dropped > 0 and default.dropped == 0, backend
        assert_same(unbounded, default, backend)
    with pytest.raises(NavfnInputError):
        get_backend("reference").prepare(costs, -1)
    with pytest.raises(NavfnInputError):
        get_backend("jit").prepare(costs, -1)


@pytest.mark.fast
@pytest.mark.parametrize("backend", OTHERS)
@settings(max_examples=60, deadline=None)
@given(costs=cost_maps(), data=st.data())
def test_batch_agrees_with_single_runs(backend, costs, data):
    """``run_batch`` (one compiled call for many cases) gives each case's ``run`` result."""
    h, w = costs.shape
    interior = st.tuples(st.integers(1, max(1, w - 2)), st.integers(1, max(1, h - 2)))
    cases = data.draw(st.lists(st.tuples(interior, interior), min_size=1, max_size=6))
    astar = data.draw(st.booleans())
    flat = np.array([[s[0], s[1], g[0], g[1]] for s, g in cases], np.int64)
    try:
        singles = [get_backend("reference").prepare(costs).run(s, g, astar, trace=False) for s, g in cases]
    except UndefinedBehaviour:
        return  # an interior start next to a lethal corner can still be undefined; covered above
    batch = get_backend(backend).prepare(costs).run_batch(flat, astar)
    _assert_batch(batch, singles)
    # the batch keeps the planner's capacity too
    capacity = data.draw(st.integers(1, 6))
    try:
        singles = [get_backend("reference").prepare(costs, capacity).run(s, g, astar, trace=False) for s, g in cases]
    except UndefinedBehaviour:
        return
    _assert_batch(get_backend(backend).prepare(costs, capacity).run_batch(flat, astar), singles)


def _assert_batch(batch, singles):
    for i, ref in enumerate(singles):
        assert batch["start_reached"][i] == ref.start_reached
        assert _bits(batch["start_potential"][i]) == _bits(ref.start_potential)
        assert (batch["cycles"][i], batch["updates"][i], batch["dropped"][i]) == (ref.cycles, ref.updates, ref.dropped)
        assert list(ExtractionExit)[batch["exit"][i]] == ref.exit
        lo, hi = batch["path_offsets"][i], batch["path_offsets"][i + 1]
        assert _bits(batch["path"][lo:hi]) == _bits(ref.path)


@pytest.mark.fast
def test_results_do_not_alias_the_runner():
    """A result keeps its values when the same planner plans another case."""
    costs = np.full((8, 8), 50, np.uint8)
    planner = get_backend("jit").prepare(costs)
    first = planner.run((2, 2), (5, 5), True)
    kept = (first.potential.copy(), first.path.copy(), first.trace.copy())
    planner.run((5, 2), (2, 6), False)
    assert np.array_equal(first.potential, kept[0])
    assert np.array_equal(first.path, kept[1]) and np.array_equal(first.trace, kept[2])


@pytest.mark.fast
def test_conformance_check_can_fail():
    """The comparison notices a single flipped potential bit."""
    costs = np.full((6, 6), 60, np.uint8)
    ref = _plan("reference", costs, (1, 1), (4, 4), True)
    other = _plan("reference", costs, (1, 1), (4, 4), True)
    other.potential[2, 2] = np.nextafter(other.potential[2, 2], np.float32(np.inf))
    with pytest.raises(AssertionError):
        assert_same(other, ref, "doctored")
