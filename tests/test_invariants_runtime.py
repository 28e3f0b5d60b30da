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
    held = st.cur + st.over
    assert st.nxt == [], where
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
    st.pending[st.cur[0]] = False
    with pytest.raises(AssertionError, match="flags differ"):
        _check_between_cycles(st, "tampered")
    st.pending[st.cur[0]] = True
    st.over.append(st.cur[0])
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
