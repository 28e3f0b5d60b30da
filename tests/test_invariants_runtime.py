"""The whole-state invariants the local obligations add up to, checked on real runs.

The obligations in ``proofs/queues.py`` and ``proofs/path_step.py`` model the state
changes of propagation and extraction one step at a time; these tests hold the
invariants they imply against the spec's actual loops (and against the C++ golden
outputs), so the hand-made step models cannot drift from the code they describe.
"""

from pathlib import Path

import numpy as np
import pytest

from navfn_smt.maps.suite import discover, golden_path_of, load_golden, load_map
from navfn_smt.spec import propagation as P
from navfn_smt.spec.constants import POT_HIGH
from navfn_smt.spec.costs import add_border
from navfn_smt.spec.extraction import ExtractionExit, calc_path

EXAMPLES = Path(__file__).resolve().parent.parent / "src" / "navfn_smt" / "examples" / "suite"


def _check_between_cycles(st, where):
    """Invariant B of proofs/queues.py on a concrete state."""
    held = list(st.cur) + list(st.over)
    assert st.nxt.fill == 0, where
    assert len(held) == len(set(held)), f"{where}: a cell is twice in the buffers"
    assert {n for n, p in enumerate(st.pending) if p} == set(held), f"{where}: flags differ from buffers"


def _propagate_checked(costs, start, goal, astar):
    ny, nx = costs.shape
    st = P.setup(add_border(costs).ravel().tolist(), nx, ny, goal)
    _check_between_cycles(st, "after setup")
    boundaries = []

    def hook(cycle, cells):
        _check_between_cycles(st, f"cycle {cycle}")
        boundaries.append(cycle)

    P.propagate(st, start, goal, astar, P.cycle_limit(nx, ny), trace_hook=hook, record_trace=False)
    _check_between_cycles(st, "at the end")
    return st, len(boundaries)


def _points_in_reached_cells(path, pot):
    """FinitePotentialPath: every point lies within 1/2 (each axis, closed) of a reached cell."""
    bad = []
    for x, y in np.asarray(path, dtype=np.float64):
        xs = {int(np.floor(x + 0.5)), int(np.ceil(x - 0.5))}
        ys = {int(np.floor(y + 0.5)), int(np.ceil(y - 0.5))}
        ok = any(0 <= cy < pot.shape[0] and 0 <= cx < pot.shape[1] and pot[cy, cx] < POT_HIGH
                 for cx in xs for cy in ys)
        if not ok:
            bad.append((x, y))
    return bad


@pytest.mark.parametrize("astar", [True, False], ids=["astar", "dijkstra"])
def test_pending_flags_match_buffers_on_example_maps(astar):
    runs = cycles = 0
    for d in discover(EXAMPLES):
        smap = load_map(d)
        for sx, sy, gx, gy in smap.cases[:20]:
            _, n = _propagate_checked(smap.costs, (int(sx), int(sy)), (int(gx), int(gy)), astar)
            runs += 1
            cycles += n
    assert runs >= 180 and cycles > 700


def test_pending_flags_match_buffers_when_pushes_are_dropped():
    from test_semantics import stub_comb_map  # the map whose buffer overflows

    costs = stub_comb_map(25, 405)
    ny, nx = costs.shape
    st, _ = _propagate_checked(costs, (nx - 2, ny - 2), (4, 1), False)
    assert st.dropped == 50


def test_check_between_cycles_can_fail():
    costs = np.full((5, 5), 50, np.uint8)
    st = P.setup(add_border(costs).ravel().tolist(), 5, 5, (2, 2))
    st.pending[st.cur.cell(0)] = False
    with pytest.raises(AssertionError, match="flags differ"):
        _check_between_cycles(st, "tampered")
    st.pending[st.cur.cell(0)] = True
    st.over.append_if(True, st.cur.cell(0))
    with pytest.raises(AssertionError, match="twice"):
        _check_between_cycles(st, "tampered")


def test_returned_paths_lie_in_reached_cells_on_example_maps():
    paths = 0
    for d in discover(EXAMPLES):
        smap = load_map(d)
        ny, nx = smap.costs.shape
        for sx, sy, gx, gy in smap.cases[:4]:
            st, _ = _propagate_checked(smap.costs, (int(sx), int(sy)), (int(gx), int(gy)), True)
            ext = calc_path(st.potential, nx, ny, (int(sx), int(sy)), (int(gx), int(gy)), 4 * nx)
            if ext.exit is ExtractionExit.NEAR_GOAL:
                pot = np.array(st.potential, dtype=np.float32).reshape(ny, nx)
                assert _points_in_reached_cells(ext.path, pot) == [], (d.name, sx, sy)
                paths += 1
    assert paths >= 30


def test_points_in_reached_cells_can_fail():
    pot = np.full((3, 3), POT_HIGH, np.float32)
    pot[1, 1] = 0.0
    assert _points_in_reached_cells([(1.5, 1.5), (1.0, 0.5)], pot) == []
    assert _points_in_reached_cells([(1.51, 1.0), (2.0, 2.0)], pot) == [(1.51, 1.0), (2.0, 2.0)]


def test_golden_paths_lie_in_reached_cells(shared_suite):
    """The C++ original's own outputs satisfy FinitePotentialPath (cases with stored potentials)."""
    checked = 0
    for d in discover(shared_suite):
        smap = load_map(d)
        for mode in ("astar", "dijkstra"):
            g = load_golden(smap.golden_path(mode))
            for k, i in enumerate(g["full_index"]):
                path = golden_path_of(g, int(i))
                if len(path):
                    assert _points_in_reached_cells(path, g["full_potential"][k]) == [], (d.name, mode, i)
                    checked += 1
    assert checked > 5000


def _goal_component_size(costs, goal):
    """Cells of the goal's component (the passable cells 4-connected to a passable neighbour of the
    goal, with the goal itself when passable): at most the cells the buffers can ever hold."""
    ny, nx = costs.shape
    passable = costs < 254
    seen, todo = set(), []
    gx, gy = goal
    for x, y in ((gx + 1, gy), (gx - 1, gy), (gx, gy - 1), (gx, gy + 1)):
        if 0 <= x < nx and 0 <= y < ny and passable[y, x]:
            todo.append((x, y))
    while todo:
        x, y = todo.pop()
        if (x, y) in seen:
            continue
        seen.add((x, y))
        for a, b in ((x + 1, y), (x - 1, y), (x, y - 1), (x, y + 1)):
            if 0 <= a < nx and 0 <= b < ny and passable[b, a] and (a, b) not in seen:
                todo.append((a, b))
    return len(seen)


def _small_maps(count=24):
    rng = np.random.default_rng(39)
    for _ in range(count):
        nx, ny = (int(v) for v in rng.integers(6, 15, size=2))
        costs = rng.integers(50, 254, size=(ny, nx)).astype(np.uint8)
        costs[rng.random((ny, nx)) < 0.3] = 254
        cells = [(x, y) for y in range(ny) for x in range(nx) if costs[y, x] < 254]
        if len(cells) < 2:
            continue
        i, j = rng.choice(len(cells), size=2, replace=False)
        yield costs, cells[i], cells[j]


def _dropped(costs, start, goal, astar, capacity, fixed):
    """Pushes dropped for want of room by propNavFn* (and the fix's second call when ``fixed``)."""
    from navfn_smt.spec import fix as F
    from navfn_smt.spec.planner import AS_SHIPPED, calc_navfn

    ny, nx = costs.shape
    st = P.setup(add_border(costs).ravel().tolist(), nx, ny, goal, capacity)
    calc_navfn(st, start, goal, astar, F.FIX if fixed else AS_SHIPPED, record_trace=False)
    return st.dropped


@pytest.mark.parametrize("fixed", [False, True], ids=["original", "fixed"])
def test_no_push_is_dropped_when_the_buffers_hold_the_goals_component(fixed):
    """ConnectedStartReached's no-drop condition on small buffers: with each buffer's capacity the
    size of the goal's component, no push is dropped (a push is of a cell in no buffer it may
    enter, which hold distinct cells of the component: BuffersInductive); with a quarter of it,
    some are, so the capacity is what the runs test."""
    dropped_when_small = 0
    for costs, start, goal in _small_maps():
        k = _goal_component_size(costs, goal)
        for astar in (True, False):
            assert _dropped(costs, start, goal, astar, k, fixed) == 0, (costs.shape, start, goal, astar, k)
            dropped_when_small += _dropped(costs, start, goal, astar, k // 4, fixed) > 0
    assert dropped_when_small > 0
