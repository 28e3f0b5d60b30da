"""Map generators: every category generates valid maps with the shapes the paper's have,
deterministically, and a generated suite is written whole, refused over itself, and
records and difftests clean against its own recording."""

import math

import numpy as np
import pytest

from navfn_smt.difftest.record import record_suite
from navfn_smt.difftest.runner import run_suite, summarize
from navfn_smt.errors import NavfnInputError
from navfn_smt.maps import generators as G
from navfn_smt.maps.generators import (
    CATEGORIES, CATEGORY_INFO, choose_cases, generate_map, generate_maps, generate_suite,
    inflate, passable_cells,
)
from navfn_smt.maps.regions import regions as components
from navfn_smt.nav2.inflation import compute_cost as inflation_cost
from navfn_smt.maps.suite import discover, load_map

SMALL = {  # sizes that keep the whole file fast
    "circus": (5, 9), "columns": (11, 9), "free": (6, 5), "obstacle": (8, 7), "radial": (8, 8),
    "random": (7, 6), "spiral": (9, 9), "split": (8, 7), "walls": (10, 9), "inflated": (24, 20), "maze": (11, 9),
}
LETHAL = 254


def interior(a):
    return a[1:-1, 1:-1]


def neighbours(a, x, y):
    return [(x + dx, y + dy) for dx, dy in ((1, 0), (-1, 0), (0, 1), (0, -1)) if a[y + dy, x + dx] < LETHAL]


# ------------------------------------------------------------------------ every category
@pytest.mark.parametrize("category", CATEGORIES)
def test_category_generates_records_and_difftests_clean(tmp_path, category):
    maps = generate_suite(tmp_path, category, count=2, seed=3, size=SMALL[category], paths=60)
    assert len(maps) == 2 and all(m.directory.parent == tmp_path / category for m in maps)
    for m in maps:
        back = load_map(m.directory, tmp_path)
        assert back.category == category and (back.width, back.height) == SMALL[category]
        assert np.array_equal(back.costs, m.costs) and np.array_equal(back.cases, m.cases)
        assert 1 <= len(m.cases) <= 60
    recs = record_suite(tmp_path)
    assert len(recs) == 4
    summary = summarize(run_suite(tmp_path))
    n = sum(len(m.cases) for m in maps)
    assert summary["failed"] == 0, summary["disagreements"][:2]
    assert summary["passed"] == 2 * n


@pytest.mark.parametrize("category", CATEGORIES)
def test_lethal_border_and_valid_costs(category):
    lo = CATEGORY_INFO[category].min_size
    if max(lo) < CATEGORY_INFO[category].min_long:
        lo = (CATEGORY_INFO[category].min_long, lo[1])
    for size in (None, lo, SMALL[category]):
        if category == "inflated" and size is None:
            continue  # default sizes are large; covered by test_default_sizes
        for i in range(4):
            c = generate_map(category, seed=11, index=i, size=size, paths=10).costs
            assert c.dtype == np.uint8
            assert (c[0] == LETHAL).all() and (c[-1] == LETHAL).all()
            assert (c[:, 0] == LETHAL).all() and (c[:, -1] == LETHAL).all()
            assert ((c >= 50) & (c <= 254)).all()
            assert (interior(c) < LETHAL).any(), "at least one passable cell"


def test_default_sizes_lie_in_the_category_range():
    for category in CATEGORIES:
        (wl, wh), (hl, hh) = CATEGORY_INFO[category].default_sizes
        m = generate_map(category, seed=5, index=0, paths=5)
        assert wl <= m.width <= wh and hl <= m.height <= hh, (category, m.width, m.height)


# ------------------------------------------------------------------------ determinism
def _suite_bytes(root):
    return {str(p.relative_to(root)): p.read_bytes() for p in sorted(root.rglob("*")) if p.is_file()}


def test_same_seed_same_bytes(tmp_path):
    for out in (tmp_path / "a", tmp_path / "b"):
        for category in CATEGORIES:
            generate_suite(out, category, count=2, seed=42, size=SMALL[category], paths=50)
    a, b = _suite_bytes(tmp_path / "a"), _suite_bytes(tmp_path / "b")
    assert a.keys() == b.keys() and len(a) == 2 * 2 * len(CATEGORIES)
    assert a == b


def test_different_seed_different_maps():
    for category in CATEGORIES:
        if category == "free":  # every free map of a size is the same map; only its cases are drawn
            continue
        maps1 = generate_maps(category, count=2, seed=1, size=SMALL[category], paths=10)
        maps2 = generate_maps(category, count=2, seed=2, size=SMALL[category], paths=10)
        assert any(not np.array_equal(x.costs, y.costs) for x, y in zip(maps1, maps2)), category
    # default sizes are drawn too, so even free suites differ
    f1 = generate_maps("free", 3, seed=1)
    f2 = generate_maps("free", 3, seed=2)
    assert [m.costs.shape for m in f1] != [m.costs.shape for m in f2]


def test_map_does_not_depend_on_count_and_names_carry_seed_and_index():
    one = generate_maps("walls", count=1, seed=9, paths=30)
    three = generate_maps("walls", count=3, seed=9, paths=30)
    assert np.array_equal(one[0].costs, three[0].costs) and np.array_equal(one[0].cases, three[0].cases)
    assert [m.name.endswith(f"_s9_{i:03d}") for i, m in enumerate(three)] == [True] * 3
    assert len({m.name for m in three}) == 3
    assert three[1].name.split("_")[-3] == "random"  # odd maps get random costs


# ------------------------------------------------------------------------ cases
@pytest.mark.fast
def test_cases_all_pairs_in_paper_order_when_few():
    c = generate_map("free", size=(5, 5), paths="all").costs
    cases = choose_cases(c, 1000, np.random.default_rng(0))
    cells = [(x, y) for x in range(1, 4) for y in range(1, 4)]  # x-major like the paper's 3x3_free
    assert cases.tolist() == [[*s, *g] for s in cells for g in cells]
    assert cases.dtype == np.int32 and cases.shape == (81, 4)


@pytest.mark.fast
def test_cases_sampled_when_many_and_all_allowed():
    c = generate_map("random", seed=1, size=(12, 12), paths=10).costs
    rng = np.random.default_rng(0)
    cases = choose_cases(c, 1000, rng)
    assert cases.shape == (1000, 4)
    assert len({tuple(r) for r in cases.tolist()}) == 1000  # distinct pairs
    assert all(c[y, x] < LETHAL for sx, sy, gx, gy in cases for x, y in ((sx, sy), (gx, gy)))
    assert len(choose_cases(c, "all", rng)) == 100 ** 2
    assert len(choose_cases(c, 10_000, rng)) == 100 ** 2  # exactly P pairs: all of them
    m = generate_map("obstacle", seed=2, size=(9, 9), paths="all")
    n = len(passable_cells(m.costs))
    assert len(m.cases) == n * n
    for bad in (0, -3, "x", "1.5", True):
        with pytest.raises(NavfnInputError):
            choose_cases(c, bad, rng)
    with pytest.raises(NavfnInputError, match="give a number"):
        generate_map("free", size=(40, 40), paths="all")


# ------------------------------------------------------------------------ shapes
def test_free_maps_have_no_interior_obstacles():
    for i in range(3):
        assert (interior(generate_map("free", seed=i, index=i, paths=5).costs) == 50).all()


def test_random_maps_have_random_costs_and_no_obstacles():
    c = generate_map("random", seed=4, size=(20, 20), paths=5).costs
    assert (interior(c) < LETHAL).all() and len(np.unique(interior(c))) > 50


@pytest.mark.fast
def test_obstacle_ratio():
    m = generate_map("obstacle", seed=6, index=1, size=(12, 12), paths=5)
    n = 10 * 10
    assert (interior(m.costs) == LETHAL).sum() == int(n * m.params["ratio"])
    assert 0.1 <= m.params["ratio"] <= 0.7 and m.params["random_costs"]
    m0 = generate_map("obstacle", seed=6, index=0, size=(12, 12), paths=5)
    assert set(np.unique(m0.costs)) <= {50, 254}


@pytest.mark.fast
def test_split_maps_have_two_disconnected_regions():
    for i in range(8):
        m = generate_map("split", seed=8, index=i, size=(9 + i % 3, 7 + i % 2), paths=200)
        lab = components(m.costs)
        assert lab.max() == 2, m.name
        o, at, t = m.params["orientation"], m.params["at"], m.params["thickness"]
        band = m.costs[at:at + t, :] if o == "h" else m.costs[:, at:at + t]
        assert (band == LETHAL).all()
        # cases across the wall have no path: the planner cannot reach the start
        labels = [(lab[sy, sx], lab[gy, gx]) for sx, sy, gx, gy in m.cases]
        assert any(a != b for a, b in labels) and any(a == b for a, b in labels)


def _walk_spiral(c):
    """Follow the corridor from (1, 1); returns the cells in order."""
    path = [(1, 1)]
    prev = None
    while True:
        x, y = path[-1]
        nxt = [p for p in neighbours(c, x, y) if p != prev]
        assert len(nxt) <= 1, f"corridor branches at {(x, y)}"
        if not nxt:
            return path
        prev = (x, y)
        path.append(nxt[0])


@pytest.mark.parametrize("size", [(3, 3), (7, 7), (9, 13), (17, 8), (26, 7), (13, 19)])
def test_spiral_is_one_clockwise_corridor_from_the_corner(size):
    c = generate_map("spiral", size=size, paths=5).costs
    path = _walk_spiral(c)
    assert len(path) == int((c < LETHAL).sum()), "every passable cell is on the corridor"
    assert len(neighbours(c, 1, 1)) <= 1  # the corridor starts at (1, 1)
    for (x0, y0), (x1, y1), (x2, y2) in zip(path, path[1:], path[2:]):
        cross = (x1 - x0) * (y2 - y1) - (y1 - y0) * (x2 - x1)
        assert cross >= 0, "turns are right turns only (clockwise, y down)"
    # corridors are one cell wide: no 2x2 open block
    open_ = c < LETHAL
    assert not (open_[:-1, :-1] & open_[1:, :-1] & open_[:-1, 1:] & open_[1:, 1:]).any()


def test_spiral_and_circus_equal_the_papers_maps(shared_suite):
    spirals = [d for d in discover(shared_suite / "spiral")]
    assert len(spirals) == 10
    for d in spirals:
        m = load_map(d)
        c = generate_map("spiral", size=(m.width, m.height), paths=1).costs
        assert np.array_equal(c == LETHAL, m.costs == LETHAL), d.name
        if "random" not in d.name:
            assert np.array_equal(c, m.costs), d.name
    for d in discover(shared_suite / "circus"):
        m = load_map(d)
        c, _ = G.circus_map(None, m.width, m.height, side=d.name[-1], cheap=153)
        assert np.array_equal(c, m.costs), d.name


def test_circus_is_a_ring_with_a_cheap_and_a_dear_side():
    for i, size in enumerate([(5, 7), (5, 14), (7, 10), (9, 16)]):
        m = generate_map("circus", seed=2, index=i, size=size, paths=5)
        c = m.costs
        w, h = size
        open_cells = list(zip(*np.nonzero(c < LETHAL)))
        assert all(len(neighbours(c, x, y)) == 2 for y, x in open_cells), "a ring: every cell has two neighbours"
        assert components(c).max() == 1
        assert (c[1, 1:w - 1] == 50).all() and (c[h - 2, 2:w - 2] == 50).all()
        assert (c[2:h - 2, 2:w - 2] == LETHAL).all()
        left, right = c[3:h - 1, 1], c[3:h - 1, w - 2]
        cheap, dear = (left, right) if m.params["side"] == "L" else (right, left)
        assert (dear == 253).all() and (cheap == m.params["cheap"]).all() and m.params["cheap"] < 253
        assert c[2, 1] == c[2, w - 2] == 253


def test_radial_gradient():
    for i in range(6):
        m = generate_map("radial", seed=3, index=i, size=(12, 9), paths=5)
        c = m.costs
        cx, cy = m.params["center"]
        r = m.params["radius"]
        assert c[cy, cx] == 50
        for y in range(1, 8):
            for x in range(1, 11):
                d = math.hypot(x - cx, y - cy)
                assert (c[y, x] == LETHAL) == (d >= r)
                if d < r:
                    assert c[y, x] == int(50 + 203 * d / r)


def test_columns_are_periodic_blocks_in_connected_corridors():
    for i in range(6):
        m = generate_map("columns", seed=4, index=i, size=(15, 13), paths=5)
        c = m.costs
        assert components(c).max() == 1
        (bw, bh), (gx, gy), (ox, oy) = m.params["block"], m.params["gap"], m.params["origin"]
        assert c[oy, ox] == LETHAL and (interior(c) == LETHAL).any()
        for y in range(1, 12):
            for x in range(1, 14):
                inside = x >= ox and y >= oy and (x - ox) % (bw + gx) < bw and (y - oy) % (bh + gy) < bh
                assert (c[y, x] == LETHAL) == inside


def test_walls_are_segments():
    m = generate_map("walls", seed=1, index=0, size=(20, 16), paths=5)
    assert (interior(m.costs) == LETHAL).sum() >= m.params["walls"]
    assert set(np.unique(m.costs)) <= {50, 254}


def test_maze_is_connected_with_loops_and_one_cell_corridors():
    for i in range(4):
        c = generate_map("maze", seed=5, index=i, size=(15 + 2 * i, 13), paths=5).costs
        open_ = c < LETHAL
        assert components(c).max() == 1
        v = int(open_.sum())
        e = int((open_[:, 1:] & open_[:, :-1]).sum() + (open_[1:, :] & open_[:-1, :]).sum())
        assert e - v + 1 >= 1, "at least one loop"
        assert not (open_[:-1, :-1] & open_[1:, :-1] & open_[:-1, 1:] & open_[1:, 1:]).any()


# ------------------------------------------------------------------------ inflated
def test_compute_cost_gives_nav2s_inflation_costs():
    # resolution 0.05, inscribed radius 0.22, cost_scaling_factor 3.0 (Nav2's defaults)
    assert inflation_cost(0, 0.05, 0.22, 3.0) == 254
    assert inflation_cost(4, 0.05, 0.22, 3.0) == 253  # 0.2 m <= 0.22
    assert inflation_cost(5, 0.05, 0.22, 3.0) == int(252 * math.exp(-3.0 * (5 * 0.05 - 0.22)))
    assert inflation_cost(10, 0.05, 0.22, 3.0) == 108  # 252 * exp(-0.84) = 108.9, truncated
    assert inflation_cost(math.hypot(3, 4), 0.05, 0.22, 3.0) == 230  # 252 * exp(-0.09) = 230.3


def test_inflate_one_obstacle_is_the_cost_of_its_distance():
    ros = np.zeros((31, 31), dtype=np.uint8)
    ros[15, 15] = 254
    res, ins, infl, k = 0.05, 0.12, 0.42, 4.0
    out = inflate(ros, res, ins, infl, k)
    cir = math.ceil(infl / res)
    for y in range(31):
        for x in range(31):
            d = math.hypot(x - 15, y - 15)
            want = 0 if d > cir else inflation_cost(d, res, ins, k)
            assert out[y, x] == want, (x, y)


def test_inflated_map_is_navfn_translation_of_ros_costs():
    ros_values = {min(int(50 + 0.8 * v), 253) for v in range(253)}
    for i in range(3):
        m = generate_map("inflated", seed=2, index=i, size=(40, 32), paths=5)
        c = interior(m.costs)
        assert set(np.unique(c)) - {254} <= ros_values
        assert (c == LETHAL).any() and ((c > 50) & (c < 254)).any()
        assert 0.05 <= m.params["inscribed_radius"] < m.params["inflation_radius"]
        # walls are inflated: the cells next to the border cost more than neutral
        assert (m.costs[1, 1:-1] > 50).all()
    # with a small robot, open space far from obstacles stays neutral
    c, p = G.inflated_map(np.random.default_rng(1), 60, 50, inscribed_radius=0.1, inflation_radius=0.3,
                          cost_scaling_factor=3.0, cores=2)
    assert (c == 50).any() and p["cores"] == 2
    assert (c[2, 2:-2] == LETHAL).all() and (c[3, 3:-3] < LETHAL).any()  # 2 cells (0.1 m) inscribed


# ------------------------------------------------------------------------ writing
@pytest.mark.fast
def test_categories_add_up_and_same_names_are_refused(tmp_path):
    generate_suite(tmp_path, "free", count=2, seed=1, size=(5, 5), paths=20)
    generate_suite(tmp_path, "spiral", count=1, seed=1, size=(7, 7), paths=20)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["free", "spiral"]
    generate_suite(tmp_path, "free", count=1, seed=2, size=(5, 5), paths=20)  # new names: added
    assert len(discover(tmp_path)) == 4
    before = _suite_bytes(tmp_path)
    with pytest.raises(NavfnInputError, match="already exist.*--overwrite"):
        generate_suite(tmp_path, "free", count=3, seed=1, size=(5, 5), paths=20)
    assert _suite_bytes(tmp_path) == before, "a refusal writes nothing"
    # overwrite replaces the directory (a stale golden file goes with it)
    d = tmp_path / "free" / generate_maps("free", 1, 1, (5, 5), 20)[0].name
    (d / "golden_astar.npz").write_bytes(b"stale")
    generate_suite(tmp_path, "free", count=2, seed=1, size=(5, 5), paths=5, overwrite=True)
    assert not (d / "golden_astar.npz").exists() and len(load_map(d).cases) == 5
    assert not [p for p in tmp_path.rglob(".*")], "no temporary files left"


@pytest.mark.fast
def test_failed_write_leaves_no_map_directory(tmp_path, monkeypatch):
    real = G._write_file

    def failing(path, data):
        if path.name == "test.txt":
            raise OSError(28, "No space left on device")
        real(path, data)

    generate_suite(tmp_path, "walls", count=1, seed=1, size=(9, 9), paths=10)
    kept = _suite_bytes(tmp_path)
    monkeypatch.setattr(G, "_write_file", failing)
    with pytest.raises(NavfnInputError, match="cannot write"):
        generate_suite(tmp_path, "maze", count=2, seed=1, size=(9, 9), paths=10)
    assert not list((tmp_path / "maze").iterdir()), "no map directory, whole or partial"
    with pytest.raises(NavfnInputError, match="cannot write"):
        generate_suite(tmp_path, "walls", count=1, seed=1, size=(9, 9), paths=3, overwrite=True)
    assert _suite_bytes(tmp_path) == kept, "a failed overwrite keeps the old map"
    assert not [p for p in tmp_path.rglob(".*")]


def test_bad_input_is_one_navfn_input_error(tmp_path):
    for kwargs, words in [
        ({"category": "nope"}, "unknown map category"),
        ({"category": "free", "count": 0}, "--count"),
        ({"category": "free", "seed": -1}, "--seed"),
        ({"category": "circus", "size": (4, 9)}, "at least 5x5"),
        ({"category": "free", "size": (2, 5)}, "at least 3x3"),
        ({"category": "free", "paths": "many"}, "--paths"),
    ]:
        with pytest.raises(NavfnInputError, match=words):
            generate_suite(tmp_path / "s", **kwargs)
    (tmp_path / "file").write_text("x")
    with pytest.raises(NavfnInputError, match="not a directory"):
        generate_suite(tmp_path / "file", "free")
    assert not (tmp_path / "s").exists()


def test_cli_register_generate_and_record(tmp_path, capsys):
    from navfn_smt.cli import build_parser

    p = build_parser()
    out = tmp_path / "suite"
    args = p.parse_args(["suite", "generate", str(out), "--category", "radial", "--count", "2", "--seed", "7",
                         "--size", "7", "6", "--paths", "all"])
    assert args.func(args) == 0
    line = capsys.readouterr().out.strip()
    assert line.startswith("2 radial maps written") and "cases" in line
    assert all(len(load_map(d).cases) == len(passable_cells(load_map(d).costs)) ** 2 for d in discover(out))
    args = p.parse_args(["suite", "record", str(out), "--mode", "astar", "--full-first", "3", "--quiet"])
    assert args.func(args) == 0
    assert "2 golden files recorded for 2 maps" in capsys.readouterr().out
    for argv, words in [
        (["suite", "generate", str(out), "--category", "radial", "--count", "2", "--seed", "7", "--size", "7", "6"],
         "already exist"),
        (["suite", "generate", str(out), "--category", "mazes"], "unknown map category"),
        (["suite", "generate", str(out), "--category", "maze", "--paths", "0"], "--paths"),
        (["suite", "record", str(out), "--mode", "astar"], "exist"),
        (["suite", "record", str(tmp_path / "none")], "no such suite"),
        (["suite", "record", str(out), "--full-first", "-1"], "--full-first"),
    ]:
        a = p.parse_args(argv)
        with pytest.raises(NavfnInputError, match=words):
            a.func(a)
