"""Nav2's inflation layers, footprint radii and global costmap parameters.

Golden values (tests/data/inflation, see its README) come from Nav2's own layer code compiled
into a harness; both Python layers must equal them bit for bit.  The small hand-derived
cases check the rules one at a time.
"""

import hashlib
import math
import time

import numpy as np
import pytest

from conftest import DATA
from navfn_smt.errors import NavfnInputError
from navfn_smt.nav2.mapserver import load_map_yaml
from navfn_smt.nav2 import costmap as cm
from navfn_smt.nav2.footprint import (
    c_hypot,
    decimal_to_float32,
    footprint_from_radius,
    min_max_distances,
    parse_vvf,
    robot_footprint,
)
from navfn_smt.nav2.inflation import (
    cell_distance,
    compute_cost,
    cost_lut,
    distance_map,
    eigen_sse_sqrt,
    inflate_current,
    inflate_legacy,
    legacy_tables,
)
from navfn_smt.nav2.rsqrt_tables import rsqrt_table

GOLD = DATA / "inflation"
RES = float(np.float32(0.05))  # a YAML's 0.05 as the costmap holds it
LAYERS = {"current": inflate_current, "legacy": inflate_legacy}


def sha(a) -> str:
    return hashlib.sha256(np.ascontiguousarray(a, dtype=np.uint8).tobytes()).hexdigest()


def load(name: str) -> dict:
    with np.load(GOLD / name) as z:
        return {k: z[k] for k in z.files}


def footprint_of(g: dict, n: int, kind_key: str = "footprint_kind"):
    text = str(g["footprint"][n]) if g[kind_key][n] == "string" else None
    return robot_footprint(float(g["robot_radius"][n]), text, float(g["footprint_padding"][n]))


def layer_args(g: dict, n: int, costmap, resolution: float):
    fp = footprint_of(g, n)
    return (costmap, resolution, fp.inscribed_radius, float(g["inflation_radius"][n]),
            float(g["cost_scaling_factor"][n]), bool(g["inflate_unknown"][n]), bool(g["inflate_around_unknown"][n]))


@pytest.fixture(scope="module")
def generated():
    g = load("generated.npz")
    offsets = np.concatenate([[0], np.cumsum(g["map_shapes"].prod(axis=1))])
    g["maps"] = [g["map_cells"][offsets[i]:offsets[i + 1]].reshape(s) for i, s in enumerate(g["map_shapes"])]
    return g


def gen_inputs(g: dict, n: int):
    return layer_args(g, n, g["maps"][g["map_index"][n]], float(np.float32(g["yaml_resolution"][n])))


# ------------------------------------------------------------------------------ goldens
@pytest.mark.parametrize("layer", sorted(LAYERS))
def test_generated_maps_equal_nav2(generated, layer):
    g = generated
    bad = [n for n in range(len(g["map_index"])) if sha(LAYERS[layer](*gen_inputs(g, n))) != g[f"sha_{layer}"][n]]
    assert not bad, f"{len(bad)} of {len(g['map_index'])} configurations differ from Nav2's {layer} layer: {bad[:10]}"


def test_generated_goldens_cover_the_ranges(generated):
    g = generated
    assert len(g["map_index"]) >= 300
    assert set(np.round(g["yaml_resolution"], 3)) >= {0.025, 0.05, 0.1}
    assert g["inflation_radius"].min() == 0.0 and g["inflation_radius"].max() == 1.5
    assert g["cost_scaling_factor"].min() == 0.5 and g["cost_scaling_factor"].max() == 10.0
    assert {"radius", "string"} == set(g["footprint_kind"])
    assert g["inflate_unknown"].any() and g["inflate_around_unknown"].any()
    assert any((m == 255).any() for m in g["maps"]) and (g["sha_current"] != g["sha_legacy"]).any()


def test_generated_full_costmaps(generated):
    g = generated
    for k, n in enumerate(g["full_index"]):
        for layer in LAYERS:
            want = g[f"full_{layer}_{k}"]
            assert sha(want) == g[f"sha_{layer}"][n]
            np.testing.assert_array_equal(LAYERS[layer](*gen_inputs(g, n)), want)


def test_generated_footprint_radii(generated):
    g = generated
    for n in range(len(g["map_index"])):
        fp = footprint_of(g, n)
        assert (fp.inscribed_radius, fp.circumscribed_radius) == (g["inscribed_radius"][n], g["circumscribed_radius"][n])


@pytest.mark.fast
def test_footprint_goldens():
    g = load("footprints.npz")
    for n in range(len(g["kind"])):
        fp = footprint_of(g, n, "kind")
        assert fp.inscribed_radius == g["inscribed_radius"][n], (n, g["footprint"][n], g["footprint_padding"][n])
        assert fp.circumscribed_radius == g["circumscribed_radius"][n]


@pytest.mark.shared
def test_ros_maps_equal_nav2(shared_suite):
    g = load("ros.npz")
    maps = {}
    for n in range(len(g["map_index"])):
        i = int(g["map_index"][n])
        if i not in maps:
            m = load_map_yaml(shared_suite / str(g["map_names"][i]), track_unknown_space=bool(g["track_unknown_space"][i]))
            assert sha(m.ros_costmap) == g["static_sha"][i], "the suite's map changed"
            maps[i] = m
        m = maps[i]
        args = layer_args(g, n, m.ros_costmap, m.costmap_resolution)
        for layer, fn in LAYERS.items():
            assert sha(fn(*args)) == g[f"sha_{layer}"][n], (str(g["map_names"][i]), n, layer)


@pytest.mark.shared
def test_build_global_costmap_on_a_ros_map_equals_nav2(shared_suite):
    g = load("ros.npz")
    i = list(g["map_names"]).index("ROS/map_circular/map_circular.yaml")
    rows = [n for n in range(len(g["map_index"])) if g["map_index"][n] == i]  # track_unknown_space true first
    m = load_map_yaml(shared_suite / "ROS/map_circular/map_circular.yaml")
    humble = cm.build_global_costmap(m, cm.bringup_params("humble"), "humble")  # 0.22 m, 0.55 m, 3.0
    assert sha(humble.costmap) == g["sha_legacy"][rows[0]]
    rolling = cm.build_global_costmap(m, cm.bringup_params("rolling"), "rolling")  # 0.22 m, 0.7 m, 3.0
    assert sha(rolling.costmap) == g["sha_current"][rows[1]]
    assert rolling.layers_run == ("static_layer (static)", "inflation_layer (current)")


# ----------------------------------------------------------------- hand-derived cases
def one_cell(size=21):
    m = np.zeros((size, size), np.uint8)
    m[size // 2, size // 2] = 254
    return m


def test_cell_distance_is_ceil_of_double_division():
    r01, r005 = float(np.float32(0.1)), RES
    assert cell_distance(0.7, r01) == 7  # 0.7 / 0.10000000149 = 6.99999990
    assert cell_distance(0.25, r005) == 5  # 4.99999993
    assert cell_distance(0.05, r005) == 1
    assert cell_distance(0.0, r005) == 0 and cell_distance(-1.0, r005) == 0
    assert cell_distance(0.2, 0.05) == 4 and cell_distance(0.2 + 1e-12, 0.05) == 5  # any excess is a cell


def test_compute_cost_rules():
    assert compute_cost(0.0, RES, 0.2, 3.0) == 254
    assert compute_cost(3.0, RES, 0.2, 3.0) == 253
    d = 5.0
    assert compute_cost(d, RES, 0.2, 3.0) == int(252 * math.exp(-3.0 * (d * RES - 0.2)))
    assert compute_cost(1000.0, RES, 0.2, 10.0) == 0


def test_inscribed_boundary_is_compared_in_double():
    # 4 cells at 0.05f are 0.20000000298 m: above an inscribed radius of 0.2, at or below 0.2000000030
    assert 4 * RES > 0.2
    assert compute_cost(4.0, RES, 0.2, 3.0) == int(252 * math.exp(-3.0 * (4 * RES - 0.2)))
    assert compute_cost(4.0, RES, 4 * RES, 3.0) == 253


def test_single_lethal_cell_legacy_is_compute_cost_of_hypot():
    m = one_cell()
    out = inflate_legacy(m, RES, 0.11, 0.4, 3.0)  # cir = 8
    c = 10
    for y in range(21):
        for x in range(21):
            d = c_hypot(x - c, y - c)
            want = compute_cost(d, RES, 0.11, 3.0) if d <= 8 else 0
            assert out[y, x] == want, (x, y)
    assert out[c, c] == 254 and out[c, c + 2] == 253 and out[c, c + 3] < 253  # 2 * 0.05f <= 0.11 < 3 * 0.05f
    assert inflate_legacy(m, RES, 0.1, 0.4, 3.0)[c, c + 2] < 253  # 2 * 0.05f = 0.1000000015 > 0.1


def test_single_lethal_cell_current_uses_the_hundredth_cell_table():
    m = one_cell()
    out = inflate_current(m, RES, 0.1, 0.4, 3.0, sqrt="exact")
    lut = cost_lut(8, RES, 0.1, 3.0)
    c = 10
    assert out[c + 4, c + 3] == lut[500] == compute_cost(5.0, RES, 0.1, 3.0)  # a 3-4-5 offset
    d = np.float32(math.sqrt(2.0))  # (1, 1): float sqrt(2) * 100 + 0.5 -> index 141
    assert int(d * np.float32(100) + np.float32(0.5)) == 141
    assert out[c + 1, c + 1] == lut[141] == compute_cost(1.41, RES, 0.1, 3.0)
    d = np.float32(math.sqrt(5.0))  # (1, 2): 2.236 -> table entry 224, not computeCost(sqrt(5))
    assert out[c + 2, c + 1] == compute_cost(2.24, RES, 0.1, 3.0)


def test_cut_off_cells():
    m = one_cell()
    c = 10
    legacy = inflate_legacy(m, RES, 0.0, 0.25, 1.0)  # cir = 5: distance 5 is in, 5.09 is out
    exact = inflate_current(m, RES, 0.0, 0.25, 1.0, sqrt="exact")
    for out in (legacy, exact):
        assert out[c, c + 5] > 0 and out[c + 4, c + 3] > 0  # exactly at the cut-off
        assert out[c + 1, c + 5] == 0 and out[c, c + 6] == 0  # sqrt(26), 6: beyond
    # Eigen's fast float sqrt (measured rsqrtps of AMD Zen) puts sqrt(49) above 7 (sqrt(25) is 5)
    fast = inflate_current(m, RES, 0.0, 0.35, 1.0)  # cir = 7
    exact = inflate_current(m, RES, 0.0, 0.35, 1.0, sqrt="exact")
    assert exact[c, c + 7] > 0 and fast[c, c + 7] == 0 and fast[c + 7, c] == 0
    assert (fast != exact).sum() == 4  # (+-7, 0), (0, +-7): 49 has no other sum of two squares
    assert (inflate_current(m, RES, 0.0, 0.25, 1.0) == legacy).all()


def test_eigen_sqrt_measured_values():
    x = np.array([0.0, 1.0, 49.0, 2.0, np.finfo(np.float32).max], np.float32)
    y = eigen_sse_sqrt(x, rsqrt_table())
    assert y[0] == 0.0 and y[1] == 1.0
    assert float(y[2]).hex() == "0x1.c000020000000p+2"  # 7.0000005, as Eigen 3.4 gave in the harness
    assert float(y[4]).hex() == "0x1.fffffe0000000p+63"
    sq = np.full((3, 3), 49.0, np.float32)  # 9 cells: 8 in packets of four, the last one by std::sqrt
    d = distance_map(np.where(np.arange(9).reshape(3, 3) == 0, 254, 0).astype(np.uint8))
    assert d.dtype == np.float32 and d[0, 0] == 0.0
    from navfn_smt.nav2.inflation import matrix_sqrt
    out = matrix_sqrt(sq)
    assert (out.ravel()[:8] > 7.0).all() and out.ravel()[8] == 7.0


def test_unknown_cells():
    m = np.full((9, 9), 255, np.uint8)
    m[4, 4] = 254
    m[4, 5] = 0
    keep = inflate_current(m, RES, 0.06, 0.2, 3.0, sqrt="exact")
    assert keep[4, 3] == 253 and keep[4, 2] == 255  # unknown takes only >= 253
    assert keep[4, 5] == 253
    take = inflate_legacy(m, RES, 0.06, 0.2, 3.0, inflate_unknown=True)
    assert take[4, 2] == compute_cost(2.0, RES, 0.06, 3.0) < 253  # unknown takes any cost > 0
    around = inflate_legacy(m, RES, 0.06, 0.2, 3.0, inflate_around_unknown=True)
    assert around[0, 0] == 254  # an unknown source gets LETHAL (>= 253 replaces 255)
    assert (inflate_current(m, RES, 0.06, 0.2, 3.0, inflate_around_unknown=True, sqrt="exact") == around).all()


def test_zero_radius_or_disabled_changes_nothing():
    m = one_cell()
    m[0, 0] = 255
    for fn in LAYERS.values():
        assert (fn(m, RES, 0.2, 0.0, 3.0) == m).all()
        assert (fn(m, RES, 0.2, 0.5, 3.0, enabled=False) == m).all()
        assert (fn(m, RES, 0.2, 0.5, 3.0, inflate_around_unknown=True) != m).any()


def test_existing_costs_are_kept_when_higher():
    m = one_cell()
    m[10, 15] = 200
    for fn in LAYERS.values():
        out = fn(m, RES, 0.05, 0.5, 3.0)
        assert out[10, 15] == 200 and out[10, 14] == max(compute_cost(4.0, RES, 0.05, 3.0), 0)


@pytest.mark.fast
def test_legacy_tables():
    dist, costs, levels = legacy_tables(3, RES, 0.1, 3.0)
    assert dist.shape == costs.shape == (5, 5) and dist[3, 4] == 5.0
    assert levels[0, 0] == 0 and levels[1, 0] == levels[0, 1] == 1 and levels[1, 1] == 2 and levels[2, 0] == 3
    assert levels[3, 4] == levels[5, 0]  # 25 = 9 + 16: one bin
    big, _, _ = legacy_tables(150, RES, 0.1, 3.0)  # numpy's hypot is the C library's hypot
    assert all(big[i, j] == c_hypot(float(i), float(j)) for i in range(152) for j in range(152))


def test_bad_input():
    with pytest.raises(NavfnInputError, match="uint8"):
        inflate_current(np.zeros((3, 3), np.int32), RES, 0.1)
    with pytest.raises(NavfnInputError, match="resolution"):
        inflate_legacy(np.zeros((3, 3), np.uint8), 0.0, 0.1)
    with pytest.raises(NavfnInputError, match="inflation_radius"):
        inflate_legacy(np.zeros((3, 3), np.uint8), RES, 0.1, math.nan)
    with pytest.raises(NavfnInputError, match="sqrt"):
        inflate_current(one_cell(), RES, 0.1, 0.5, sqrt="fast")


def test_speed_500x500():
    rng = np.random.default_rng(5)
    m = np.where(rng.random((500, 500)) < 0.01, 254, 0).astype(np.uint8)
    for fn in LAYERS.values():
        fn(m, RES, 0.22, 0.3, 3.0)  # compile / load
        t = time.perf_counter()
        fn(m, RES, 0.22, 1.5, 3.0)
        assert time.perf_counter() - t < 1.0


# ------------------------------------------------------------------------ footprint
def test_radius_footprint_and_padding_quirk():
    pts = footprint_from_radius(0.2)
    assert len(pts) == 16 and pts[0] == (0.2, 0.0)
    assert 0 < pts[4][0] < 1e-16  # cos(pi/2) * r is not 0 ...
    fp = robot_footprint(0.2, None, 0.01)
    assert fp.points[4][0] == pytest.approx(0.01, abs=1e-9)  # ... so padding moves it by the padding
    assert fp.padding == float(np.float32(0.01)) != 0.01
    inside, outside = min_max_distances(footprint_from_radius(0.2))
    assert inside == pytest.approx(0.2 * math.cos(math.pi / 16)) and outside == pytest.approx(0.2)


@pytest.mark.fast
def test_string_footprint_is_float32():
    fp = robot_footprint(0.5, "[[0.3, 0.2], [0.3, -0.2], [-0.3, -0.2], [-0.3, 0.2]]", 0.0)
    assert fp.source == "footprint" and fp.inscribed_radius == float(np.float32(0.2))
    assert fp.circumscribed_radius == c_hypot(float(np.float32(0.3)), float(np.float32(0.2)))
    assert robot_footprint(0.5, "[]", 0.0).source == "robot_radius"
    assert robot_footprint(0.5, "", 0.0).inscribed_radius == robot_footprint(0.5, None, 0.0).inscribed_radius


def test_parse_vvf():
    assert parse_vvf("[[1, 2.2], [.3, -4e4]]") == [[1.0, float(np.float32(2.2))], [float(np.float32(0.3)), -4e4]]
    for bad, msg in (("[[[1]]]", "depth"), ("[[1, 2]]]", "More close"), ("[1, 2]", "depth other than 2"),
                     ("[[1, 2], [3, x]]", "Unterminated"), ("[[1, 2]", "Unterminated"), ("[[1e, 2]]", "Unterminated")):
        with pytest.raises(ValueError, match=msg):
            parse_vvf(bad)


def test_decimal_to_float32_rounds_once():
    assert decimal_to_float32("0.1") == float(np.float32(0.1))
    # 1 + 2^-24 + 2^-60: a double rounds it to the halfway point 1 + 2^-24, then float ties to 1.0;
    # rounded once, it is above the halfway point and goes up to 1 + 2^-23
    s = "1.0000000596046447753906251"  # 1 + 2^-24 + 1e-25
    assert decimal_to_float32(s) == 1 + 2 ** -23
    assert float(np.float32(float(s))) == 1.0


def test_bad_footprint_strings():
    with pytest.raises(NavfnInputError, match="footprint"):
        robot_footprint(0.2, "[[0.1, 0.1], [0.2, 0.2]]")  # two points
    with pytest.raises(NavfnInputError, match="pairs"):
        robot_footprint(0.2, "[[0.1, 0.1, 0.0], [0.2, 0.2], [0.3, 0.1]]")
    fp = robot_footprint(0.2, "[[0.1, 0.1], [0.2, 0.2]]", strict=False)  # Nav2: error log, then the radius
    assert fp.source == "robot_radius"


# ------------------------------------------------------------------------ params YAML
PARAMS = """
global_costmap:
  global_costmap:
    ros__parameters:
      update_frequency: 1.0
      robot_radius: 0.22
      resolution: 0.05
      track_unknown_space: true
      plugins: ["static_layer", "obstacle_layer", "inflation_layer"]
      obstacle_layer:
        plugin: "nav2_costmap_2d::ObstacleLayer"
        observation_sources: scan
      static_layer:
        plugin: "nav2_costmap_2d::StaticLayer"
        map_subscribe_transient_local: true
      inflation_layer:
        plugin: "nav2_costmap_2d::InflationLayer"
        cost_scaling_factor: 3.0
        inflation_radius: 0.7
"""


def write(tmp_path, text):
    p = tmp_path / "nav2_params.yaml"
    p.write_text(text)
    return p


@pytest.mark.fast
def test_params_file(tmp_path):
    p = cm.load_costmap_params(write(tmp_path, PARAMS), "jazzy")
    assert p == cm.bringup_params("jazzy")
    assert p.robot_radius == 0.22 and p.track_unknown_space and p.footprint_padding == 0.01
    infl = p.plugins[-1].inflation
    assert infl.inflation_radius == 0.7 and infl.cost_scaling_factor == 3.0 and not infl.inflate_unknown
    d = cm.CostmapParams()
    assert d.robot_radius == 0.1 and not d.track_unknown_space and d.resolution == 0.1
    assert d.plugins[-1].inflation.inflation_radius == 0.55 and d.plugins[-1].inflation.cost_scaling_factor == 10.0


def test_distro_layer_mapping():
    assert cm.INFLATION_TYPES["humble"] == {cm.INFLATION: "legacy"}
    assert cm.INFLATION_TYPES["kilted"] == {cm.INFLATION: "legacy"}
    assert cm.INFLATION_TYPES["rolling"] == {cm.INFLATION: "current", cm.LEGACY_INFLATION: "legacy"}
    assert cm.INFLATION_TYPES["lyrical"] == cm.INFLATION_TYPES["rolling"]
    assert set(cm.INFLATION_TYPES) == {"humble", "iron", "jazzy", "kilted", "lyrical", "rolling"}


@pytest.mark.fast
@pytest.mark.parametrize("edit, key", [
    (("inflation_radius: 0.7", "inflation_radius: 1"), "inflation_layer.inflation_radius"),
    (("inflation_radius: 0.7", "inflation_radius: -0.5"), "inflation_layer.inflation_radius"),
    (("robot_radius: 0.22", "robot_radius: -0.22"), "robot_radius"),
    (("track_unknown_space: true", "track_unknown_space: 1"), "track_unknown_space"),
    (("nav2_costmap_2d::InflationLayer", "nav2_costmap_2d::Inflation"), "inflation_layer.plugin"),
    (("resolution: 0.05", "footprint: [[1.0, 1.0]]"), "footprint"),
    (('plugins: ["static_layer", "obstacle_layer", "inflation_layer"]', 'plugins: ["static_layer", "x"]'), "x.plugin"),
])
def test_bad_params_name_the_key(tmp_path, edit, key):
    with pytest.raises(NavfnInputError, match=f"'{key}'"):
        cm.load_costmap_params(write(tmp_path, PARAMS.replace(*edit)))


@pytest.mark.fast
def test_unreadable_params(tmp_path):
    with pytest.raises(NavfnInputError, match="no such"):
        cm.load_costmap_params(tmp_path / "absent.yaml")
    with pytest.raises(NavfnInputError, match="malformed"):
        cm.load_costmap_params(write(tmp_path, "global_costmap: [unclosed"))
    with pytest.raises(NavfnInputError, match="ros__parameters"):
        cm.load_costmap_params(write(tmp_path, "controller_server:\n  ros__parameters: {}\n"))


def test_legacy_layer_type_only_from_lyrical(tmp_path):
    text = PARAMS.replace('"nav2_costmap_2d::InflationLayer"', '"nav2_costmap_2d::LegacyInflationLayer"')
    assert cm.load_costmap_params(write(tmp_path, text), "rolling").plugins[-1].type == cm.LEGACY_INFLATION
    with pytest.raises(NavfnInputError, match="inflation_layer.plugin"):
        cm.load_costmap_params(write(tmp_path, text), "humble")


def test_build_on_an_array_runs_layers_in_order():
    m = one_cell()
    m[0, 0] = 255
    p = cm.bringup_params("rolling")
    out = cm.build_global_costmap(m, p, resolution=RES)
    assert out.layers_run == ("static_layer (static)", "inflation_layer (current)")
    assert any("obstacle_layer" in n for n in out.notes) and any("keepout_filter" in n for n in out.notes)
    fp = robot_footprint(0.22, None, 0.01)
    assert out.inscribed_radius == fp.inscribed_radius
    np.testing.assert_array_equal(out.costmap, inflate_current(m, RES, fp.inscribed_radius, 0.7, 3.0))
    legacy = cm.build_global_costmap(m, cm.bringup_params("humble"), "humble", resolution=RES)
    np.testing.assert_array_equal(legacy.costmap, inflate_legacy(m, RES, fp.inscribed_radius, 0.55, 3.0))
    static_last = cm.CostmapParams(plugins=tuple(reversed(p.plugins)), robot_radius=0.22, track_unknown_space=True)
    np.testing.assert_array_equal(cm.build_global_costmap(m, static_last, resolution=RES).costmap, m)


def test_build_on_a_packaged_map():
    from pathlib import Path

    import navfn_smt

    yaml = Path(navfn_smt.__file__).parent / "examples" / "mapserver" / "room.yaml"
    m = load_map_yaml(yaml, distro="humble")
    out = cm.build_global_costmap(m, cm.bringup_params("humble"))
    assert out.distro == "humble" and out.resolution == m.costmap_resolution
    assert out.costmap.shape == (m.height, m.width) and out.costmap.dtype == np.uint8
    no_track = cm.build_global_costmap(m, cm.CostmapParams())
    assert (no_track.static != 255).all()
