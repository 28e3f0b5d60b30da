"""The plugin's own misbehaviours (nav2/offmap.py, smt/offmap.py, docs/plugin.md): the Z3 characterisation of the
points createPlan accepts and makePlan rounds off the map, the tolerance loop's stall threshold,
one-sided window and skipped column, and every case directory replayed on both backends."""

import math
from pathlib import Path

import numpy as np
import pytest

from navfn_smt.nav2.offmap import RES, centre_cells, loop_cells, offmap, offmap_interval_numeric
from navfn_smt.smt.offmap import offmap_interval, stall_threshold
from plugin_cases import SKIP_GOAL_X, replay_case
from navfn_smt.nav2.plugin import Costmap, Pose, create_plan

CASES = Path(__file__).resolve().parent / "data" / "plugin_cases"
CASE_DIRS = sorted(p.parent for p in CASES.glob("*/case.json"))


def test_offmap_interval_proved_by_z3():
    # x of an 8-wide map at origin 0: [lo, hi) with lo the double nearest 7.5 * RES from above
    iv = offmap_interval(0.0, RES, 8, find=False, prove=True)
    assert iv.proved, iv.as_dict()
    assert (iv.lo.hex(), iv.hi.hex()) == ("0x1.8000006000000p-2", "0x1.99999a0000000p-2")
    assert iv.hi == 8 * RES  # exact: 8 * 13421773 * 2**-28
    assert offmap(iv.lo, 0.0, RES, 8) and not offmap(math.nextafter(iv.lo, 0), 0.0, RES, 8)
    assert offmap(math.nextafter(iv.hi, 0), 0.0, RES, 8) and not offmap(iv.hi, 0.0, RES, 8)


@pytest.mark.fast
def test_offmap_interval_of_a_realistic_map():
    # origin -10, 400 cells (the numbers of docs/plugin.md; the Z3 run is in the docs, minutes)
    lo, hi = offmap_interval_numeric(-10.0, RES, 400)
    assert (lo.hex(), hi.hex()) == ("0x1.3f3333d2fffffp+3", "0x1.4000009ffffffp+3")
    assert (lo, hi) == (9.975000297650693, 10.000000298023222)


def test_offmap_interval_through_create_plan():
    m = Costmap(np.zeros((6, 8), np.uint8), 0.0, 0.0, RES)
    lo, hi = offmap_interval_numeric(0.0, RES, 8)
    for x, cell in ((math.nextafter(lo, 0), 7), (lo, 8), (math.nextafter(hi, 0), 8)):
        r = create_plan(m, Pose(x, 0.11), Pose(0.11, 0.16))
        assert r.start_cell[0] == 7 and r.robot_cell[0] == cell
    assert create_plan(m, Pose(hi, 0.11), Pose(0.11, 0.16)).error == "StartOutsideMapBounds"


@pytest.mark.fast
def test_stall_threshold():
    st = stall_threshold(RES)
    assert st.threshold == 2.0 ** 49 == 562949953421312.0
    assert [q.verdict for q in st.queries] == ["sat", "unsat", "unsat"]
    p = 2.0 ** 49
    assert p + RES == p and math.nextafter(p, 0) + RES != math.nextafter(p, 0)


@pytest.mark.fast
def test_tolerance_window_is_one_sided():
    # tolerance 0.5, RES > 0.05: 0.5 / RES < 10, so g - 0.5 + 20 RES > g + 0.5: 20 points, not 21
    rng = np.random.default_rng(3)
    for g in np.concatenate([rng.uniform(-100, 100, 200), [0.0, 12 * RES, 5e5]]).tolist():
        cells = loop_cells(g, 0.5, g - 20.0, RES)
        assert len(cells) == 20


@pytest.mark.fast
def test_tolerance_skipped_column():
    assert SKIP_GOAL_X.hex() == "-0x1.8666646800003p+0"
    cells = loop_cells(SKIP_GOAL_X, 0.5, -10.0, RES)
    assert cells[:3] == [159, 161, 162] and 160 not in cells and len(cells) == 20
    assert loop_cells(math.nextafter(SKIP_GOAL_X, 0), 0.5, -10.0, RES)[:3] == [160, 161, 162]


@pytest.mark.fast
def test_cell_centres_round_up():
    # origin + (i + 0.5) * res lands on i + 0.5 or above for every cell of these maps: cell i + 1
    assert centre_cells(0.0, RES, 8).tolist() == list(range(1, 9))
    assert (centre_cells(-10.0, RES, 400) == np.arange(1, 401)).all()


@pytest.mark.fast
def test_case_directories_present():
    names = {d.name for d in CASE_DIRS}
    assert {"robot-right-half-cell", "robot-top-half-cell", "goal-right-half-cell", "goal-top-half-cell",
            "tolerance-window-right-edge", "tolerance-skipped-column", "tolerance-loop-never-ends",
            "max-cycles-overflow"} <= names


@pytest.mark.parametrize("backend", ["jit", "reference"])
@pytest.mark.parametrize("case", CASE_DIRS, ids=lambda d: d.name)
def test_case_replays(case, backend):
    expected, actual = replay_case(case, backend)
    assert actual == expected


@pytest.mark.fast
def test_robot_right_half_cell_path_crosses_the_map():
    expected, _ = replay_case(CASES / "robot-right-half-cell")
    xs = [float.fromhex(p[0]) / RES for p in expected["poses"]]
    assert expected["robot_cell"] == [8, 2] and xs[0] == 8.0 and xs[1] == 1.0  # from x = size_x to column 1


# ---------------------------------------------------------- Costmap2D::worldToMap's cast
@pytest.mark.fast
def test_costmap_world_to_map_cast_out_of_range_is_undefined():
    m = Costmap(np.zeros((6, 8), np.uint8), 0.0, 0.0, RES)
    far = 2.0 ** 32 * RES  # (w - o) / res = 2^32: static_cast<unsigned int> is undefined
    assert create_plan(m, Pose(far, 0.11), Pose(0.11, 0.16)).error == "UndefinedBehaviour"
    assert create_plan(m, Pose(math.inf, 0.11), Pose(0.11, 0.16)).error == "UndefinedBehaviour"
    assert create_plan(m, Pose(math.nan, 0.11), Pose(0.11, 0.16)).error == "UndefinedBehaviour"


def test_astar_from_one_past_the_edge_is_the_same_on_both_backends():
    # A* from a NavFn start one past the right edge (x = nx), on the JIT with the heuristic memo an
    # earlier plan of the map filled (a start in the first column), against the reference spec
    # (its own heuristic table, keyed by the signed offset): potentials, return value and trace
    # (the heuristic chooses each push's buffer).  A consistency test of the off-map path, which
    # the JIT's memo now serves; the lethal border keeps every updated cell's |dx| below nx
    from navfn_smt.backends.jit import JitPlanner
    from navfn_smt.spec.costs import add_border
    from navfn_smt.spec.planner import calc_navfn
    from navfn_smt.spec.propagation import cycle_limit, setup

    rng = np.random.default_rng(7)
    for _ in range(20):
        ny, nx = (int(v) for v in rng.integers(4, 14, size=2))
        costs = add_border(np.where(rng.random((ny, nx)) < 0.15, 254, rng.integers(0, 254, (ny, nx))).astype(np.uint8))
        jit = JitPlanner(costs)
        goal = (int(rng.integers(0, nx)), int(rng.integers(0, ny)))
        for start in ((0, int(rng.integers(0, ny))), (nx, int(rng.integers(0, ny - 1)))):
            st = setup(costs.ravel().tolist(), nx, ny, goal)
            reached, _ = calc_navfn(st, start, goal, True)
            got = jit.propagate(start, goal, True, cycle_limit(nx, ny), True)
            want = (np.float32(st.potential).tobytes(), bool(reached), st.trace)
            assert (jit.pot.tobytes(), got, jit.trace[:jit.counts()[3]].tolist()) == want, (nx, ny, start, goal)
