"""ROS map_server maps (YAML + image) loaded as Nav2 loads them: navfn_smt.nav2.mapserver.

Expected values are derived from Nav2's C++ by hand, not from the loader's output:

* nav2_map_server/src/map_io.cpp, two generations.  Legacy (Humble, Iron): with Debian's Q16
  GraphicsMagick an 8-bit sample v is the quantum v*257; shade = mean of the R, G, B quanta
  (and alpha, in trinary mode with a matte channel) / 65535 in double; occ = negate ? shade :
  1.0 - shade; trinary: occupied_thresh < occ -> 100, occ < free_thresh -> 0, else -1; scale:
  not opaque -> -1, else the same thresholds and rint((occ - free) / (occupied - free) * 100.0)
  in between; raw: round(shade * 255) if in 0..100 else -1.  Current (Jazzy >= 1.3.7, Kilted,
  Lyrical, Rolling; Eigen): 8-bit GraphicsMagick grey (Rec. 601 luma for colour), n = grey /
  255.0f, 1.0f - n unless negate, float comparisons n >= occupied -> 100, n <= free -> 0;
  scale: roundf((n - free) / (occupied - free) * 100.0f) strictly between; alpha < 255 -> -1.
  Image row y is grid row height - 1 - y in both.
* nav2_costmap_2d static_layer.cpp interpretValue (defaults: lethal 100, trinary_costmap true,
  unknown 255; track_unknown_space true as nav2_bringup's global costmap sets it; Lyrical and
  Rolling also map occupancy 99 to 253).
* NavFn::setCostmap (ROS branch): v < 253 -> int(50 + 0.8 v) capped at 253; 253, 254 -> 254;
  255 -> 253 with allow_unknown (the planner's default), else 254.

World coordinates and planning between world poses are tested in test_nav2_plan.py.
"""

from __future__ import annotations

import math
import os
import tempfile
from pathlib import Path

import numpy as np
import pytest
import yaml
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st
from PIL import Image

from navfn_smt.errors import NavfnInputError
from navfn_smt.nav2.mapserver import (
    MapServerMap,
    interpret_value,
    load_map_yaml,
)
from navfn_smt.spec.costs import add_border

HYP = settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.too_slow])
ROS_MAPS = ("empty_room", "keepout_mask", "map_circular", "speed_mask")
F32 = np.float32


# --------------------------------------------------------------------------------- helpers
def pgm_p5(pixels: np.ndarray) -> bytes:
    h, w = pixels.shape
    return b"P5\n# written by hand\n%d %d\n255\n" % (w, h) + np.asarray(pixels, np.uint8).tobytes()


def pgm_p2(pixels: np.ndarray) -> bytes:
    h, w = pixels.shape
    rows = "\n".join(" ".join(str(int(v)) for v in row) for row in pixels)
    return f"P2\n# written by hand\n{w} {h}\n255\n{rows}\n".encode()


def write_image(path: Path, pixels: np.ndarray, fmt: str) -> None:
    if fmt == "p5":
        path.write_bytes(pgm_p5(pixels))
    elif fmt == "p2":
        path.write_bytes(pgm_p2(pixels))
    else:
        Image.fromarray(np.asarray(pixels, np.uint8)).save(path, format=fmt)


BASE = {
    "image": "m.pgm",
    "resolution": 0.05,
    "origin": [-1.0, -2.0, 0.0],
    "negate": 0,
    "occupied_thresh": 0.65,
    "free_thresh": 0.196,
}


def write_yaml(folder: Path, name: str = "m.yaml", drop=(), **fields) -> Path:
    doc = {**BASE, **fields}
    for k in drop:
        doc.pop(k)
    p = folder / name
    p.write_text(yaml.safe_dump(doc))
    return p


def write_map(folder: Path, pixels, fmt: str = "p5", image: str | None = None, **fields) -> Path:
    ext = {"p5": "pgm", "p2": "pgm", "PNG": "png"}.get(fmt, fmt.lower())
    image = image or f"m.{ext}"
    write_image(folder / image, np.asarray(pixels, np.uint8), fmt)
    return write_yaml(folder, image=image, **fields)


def one_line_error(excinfo, *words):
    msg = str(excinfo.value)
    assert "\n" not in msg and msg.strip(), msg
    for w in words:
        assert w in msg, msg
    return msg


def ros_dir(shared_suite: Path, name: str) -> Path:
    return shared_suite / "ROS" / name


# ---------------------------------------------------------------------- the shared ROS maps
# Per pixel value, Nav2's occupancy for the two YAML setups of the suite, worked out by hand:
# trinary, occupied 0.65, free 0.196: 0 -> occ 1.0 > 0.65 -> 100; 254 -> occ 1/255 < 0.196 -> 0;
# 255 -> 0; 205 -> occ 50/255 = 0.19608 (above 0.196, below 0.65) -> -1 (unknown).
TRINARY_OCC = {0: 100, 205: -1, 254: 0, 255: 0}
# scale, occupied 0.99, free 0.01 (speed_mask): 254 -> occ 0.0039 < 0.01 -> 0;
# 205 -> round((0.196078 - 0.01) / 0.98 * 100) = round(18.99) = 19;
# 128 -> round((0.498039 - 0.01) / 0.98 * 100) = round(49.80) = 50.
SCALE_OCC = {128: 50, 205: 19, 254: 0}
# interpretValue with trinary_costmap: -1 -> 255, 100 -> 254, everything else -> 0;
ROS_COST = {-1: 255, 100: 254, 0: 0, 19: 0, 50: 0}
# setCostmap with allow_unknown: 0 -> 50, 254 -> 254, 255 -> 253.
NAVFN_COST = {0: 50, 254: 254, 255: 253}


@pytest.mark.shared
@pytest.mark.parametrize("distro", ["humble", "jazzy", "rolling"])
@pytest.mark.parametrize("name", ROS_MAPS)
def test_ros_maps_load(shared_suite, name, distro):
    # The suite's pixel values and thresholds are far from every rounding difference between
    # the legacy and current loaders (205: occ 0.1960784 against free 0.196, in double and in
    # float alike), no image has alpha or colour, and no map yields occupancy 99: every
    # distribution gives the same grids.
    d = ros_dir(shared_suite, name)
    doc = yaml.safe_load((d / f"{name}.yaml").read_text())
    m = load_map_yaml(d / f"{name}.yaml", distro=distro)
    assert m.distro == distro
    w, h = map(int, (d / "test.txt").read_text().split()[:2])
    assert m.image_size == (w, h) and m.width == w and m.height == h
    assert m.resolution == doc["resolution"] and m.costmap_resolution == float(F32(doc["resolution"]))
    assert m.origin == tuple(float(v) for v in doc["origin"])
    assert m.mode == doc.get("mode", "trinary") and m.negate is False
    pix = np.array(Image.open(d / doc["image"]))
    table = SCALE_OCC if m.mode == "scale" else TRINARY_OCC
    assert set(np.unique(pix).tolist()) <= set(table)
    expected_occ = np.vectorize(table.get)(pix)[::-1]  # image row 0 is the top: grid row h-1
    assert m.occupancy.dtype == np.int8 and m.occupancy.shape == (h, w)
    assert np.array_equal(m.occupancy, expected_occ)
    expected_ros = np.vectorize(ROS_COST.get)(expected_occ)
    assert m.ros_costmap.dtype == np.uint8 and np.array_equal(m.ros_costmap, expected_ros)
    assert m.navfn_costs.dtype == np.uint8 and np.array_equal(m.navfn_costs, np.vectorize(NAVFN_COST.get)(expected_ros))


# What the suite's map.bin holds: a function of the pixel alone, in image row order, plus
# a one-cell lethal frame.  Found by comparing the files (see the report in the docstring of
# test_suite_map_bin_vs_nav2); it ignores the YAML's mode and thresholds.
MAP_BIN_OF_PIXEL = {0: 254, 128: 152, 205: 90, 254: 50, 255: 50}


@pytest.mark.shared
@pytest.mark.parametrize("name", ROS_MAPS)
def test_suite_map_bin_vs_nav2(shared_suite, name):
    """map.bin equals Nav2's chain only for empty_room; elsewhere it differs exactly where
    the image has grey 205 (Nav2: unknown -> 253; map.bin: 90) or 128 (speed_mask, scale
    mode: Nav2 occupancy 50 -> free -> 50; map.bin: 152), and map.bin's rows are in image
    order (row 0 = top), not in the OccupancyGrid's (row 0 = bottom)."""
    d = ros_dir(shared_suite, name)
    m = load_map_yaml(d / f"{name}.yaml")
    mb = np.fromfile(d / "map.bin", dtype=np.uint8).reshape(m.height, m.width)
    pix = np.array(Image.open(m.image_path))
    # map.bin's own structure: the frame, then the pixel function in image order
    assert np.all(add_border(mb) == mb)
    assert np.array_equal(mb, add_border(np.vectorize(MAP_BIN_OF_PIXEL.get)(pix).astype(np.uint8)))
    ours_image_order = add_border(m.navfn_costs[::-1])
    differ = ours_image_order != mb
    if name == "empty_room":
        assert np.array_equal(add_border(m.navfn_costs), mb)  # setupNavFn adds this frame anyway
        assert not differ.any()
    else:
        grey = (pix == 205) | (pix == 128)
        grey[[0, -1], :] = grey[:, [0, -1]] = False  # the frame is lethal in both
        assert np.array_equal(differ, grey)


# ------------------------------------------------------------ pixel rules, by hand from map_io
def load_pixels(folder: Path, pixels, fmt="p5", distro="rolling", **fields) -> MapServerMap:
    """Write pixels and a YAML (``fields`` override BASE) and load them for ``distro``."""
    m = load_map_yaml(write_map(folder, pixels, fmt, **fields), distro=distro)
    assert m.distro == distro
    return m


@pytest.mark.fast
@pytest.mark.parametrize("distro", ["humble", "rolling"])
def test_vertical_flip(tmp_path, distro):
    pix = np.full((4, 3), 255, np.uint8)
    pix[0, 0] = 0  # top-left pixel
    m = load_pixels(tmp_path, pix, distro=distro)
    assert m.occupancy[3, 0] == 100 and (m.occupancy == 100).sum() == 1  # grid row h-1 = top


def write_rgba_205(tmp_path) -> str:
    rgba = np.zeros((3, 3, 4), np.uint8)
    rgba[..., :3] = 205
    rgba[..., 3] = 255
    rgba[0, 0, 3] = 254
    Image.fromarray(rgba, "RGBA").save(tmp_path / "a.png")
    return "a.png"


def test_legacy_trinary_averages_alpha_in(tmp_path):
    # RGBA 205 grey, opaque: trinary with a matte channel averages 4 channels:
    # (3 * 205 + 255) / 4 / 255 = 0.8529 -> occ 0.147 < 0.196 -> free, where the same
    # grey without alpha is unknown.  Scale mode: alpha 254 -> not opaque -> unknown.
    img = write_rgba_205(tmp_path)
    m = load_map_yaml(write_yaml(tmp_path, image=img), distro="humble")
    assert m.occupancy[2, 0] == 0  # alpha 254: (3*205 + 254) / 4 / 255 = 0.8520 -> occ 0.148 -> free
    assert np.all(m.occupancy == 0)
    grey = load_pixels(tmp_path, np.full((3, 3), 205, np.uint8), fmt="PNG", image="g.png", distro="humble")
    assert np.all(grey.occupancy == -1)
    s = load_map_yaml(write_yaml(tmp_path, "s.yaml", image=img, mode="scale"), distro="humble")
    # scale: opaque 205 -> occ 0.19608 between 0.196 and 0.65 -> rint(0.0784 / 45.4) = 0
    expected = np.zeros((3, 3), np.int8)
    expected[2, 0] = -1  # the alpha-254 pixel, image row 0
    assert np.array_equal(s.occupancy, expected)


def test_current_alpha_masks_in_trinary_and_scale(tmp_path):
    # current: the grey value is 205 whatever the alpha (no averaging) -> unknown in trinary;
    # alpha 254 < 255 -> unknown in both modes; scale: 205 -> n = 0.19607842f between
    # 0.196f and 0.65f -> roundf((0.19607842 - 0.196) / 0.454 * 100) = roundf(0.017) = 0.
    img = write_rgba_205(tmp_path)
    m = load_map_yaml(write_yaml(tmp_path, image=img), distro="rolling")
    assert np.all(m.occupancy == -1)
    s = load_map_yaml(write_yaml(tmp_path, "s.yaml", image=img, mode="scale"), distro="rolling")
    expected = np.zeros((3, 3), np.int8)
    expected[2, 0] = -1
    assert np.array_equal(s.occupancy, expected)


def write_colours(tmp_path) -> str:
    rgb = np.full((3, 3, 3), 255, np.uint8)
    rgb[0, 0] = (255, 0, 0)
    rgb[0, 1] = (255, 255, 0)
    Image.fromarray(rgb, "RGB").save(tmp_path / "c.png")
    return "c.png"


def test_legacy_rgb_channels_are_averaged(tmp_path):
    # (255, 0, 0): shade = 65535 / 3 / 65535 = 1/3, occ = 2/3 > 0.65 -> occupied;
    # (255, 255, 0): shade 2/3, occ 1/3 -> unknown; white -> free
    m = load_map_yaml(write_yaml(tmp_path, image=write_colours(tmp_path)), distro="humble")
    assert m.occupancy[2].tolist() == [100, -1, 0]


@pytest.mark.fast
def test_current_rgb_is_rec601_luma(tmp_path):
    # GraphicsMagick's GRAY transform in Q16: floor(0.299f*R + 0.587f*G + 0.114f*B + 0.5) from
    # float tables, then / 257 (truncated) for 8 bits.  (255,0,0): 0.299f * 65535 = 19594.96
    # -> 19595 -> 76 -> n = 1 - 76/255 = 0.702 >= 0.65 -> occupied.  (255,255,0): 19594.96 +
    # 38469.04 = 58064.0 -> 58064 -> 225 -> n = 0.1176 <= 0.196 -> free (legacy: unknown).
    red = F32(0.299) * F32(65535)
    yellow = red + F32(0.587) * F32(65535)
    assert math.floor(float(red) + 0.5) // 257 == 76 and math.floor(float(yellow) + 0.5) // 257 == 225
    m = load_map_yaml(write_yaml(tmp_path, image=write_colours(tmp_path)), distro="rolling")
    assert m.occupancy[2].tolist() == [100, 0, 0]


@pytest.mark.fast
@pytest.mark.parametrize("distro", ["humble", "rolling"])
def test_raw_mode(tmp_path, distro):
    # raw: the pixel value (legacy: round(shade * 255); current: the 8-bit grey cast to int8);
    # kept when in 0..100, else -1; negate and thresholds play no part.
    pix = np.array([[0, 1, 50], [99, 100, 101], [200, 254, 255]], np.uint8)
    for negate in (0, 1):
        m = load_pixels(tmp_path, pix, mode="RAW", negate=negate, distro=distro)  # mode is case-insensitive
        assert m.mode == "raw"
        assert m.occupancy[::-1].tolist() == [[0, 1, 50], [99, 100, -1], [-1, -1, -1]]


@pytest.mark.fast
@pytest.mark.parametrize("distro", ["humble", "jazzy"])
def test_scale_mode_values(tmp_path, distro):
    # occupied 0.99, free 0.01 (speed_mask's): occ = 1 - p/255 (in double or float alike here)
    # p=128: round(49.80) = 50; p=205: round(18.99) = 19; p=0: occ 1.0 -> 100;
    # p=3: occ 0.98824 -> round(99.82) = 100 (between, not above 0.99); p=254: below 0.01 -> 0
    pix = np.array([[128, 205, 0], [3, 254, 255], [255, 255, 255]], np.uint8)
    m = load_pixels(tmp_path, pix, mode="scale", occupied_thresh=0.99, free_thresh=0.01, distro=distro)
    assert m.occupancy[::-1].tolist() == [[50, 19, 100], [100, 0, 0], [0, 0, 0]]
    # interpretValue, trinary_costmap: < 100 -> free; 100 -> lethal
    assert m.ros_costmap[::-1].tolist() == [[0, 0, 254], [254, 0, 0], [0, 0, 0]]
    m2 = load_map_yaml(m.path, trinary_costmap=False, distro=distro)
    # (double)v / 100 * 254 truncated: 50 -> 127, 19 -> 48 (48.26)
    assert m2.ros_costmap[2].tolist() == [127, 48, 254]
    # setCostmap: int(50 + 0.8 * 127) = 151, int(50 + 0.8 * 48) = 88
    assert m2.navfn_costs[2].tolist() == [151, 88, 254]


def test_inscribed_value_only_in_lyrical_and_rolling(tmp_path):
    # scale 0.99 / 0.01, p = 5: occ = 0.98039 -> round((0.97039 / 0.98) * 100) = round(99.02) = 99.
    # Lyrical/Rolling interpretValue: 99 == inscribed_obstacle_cost_value -> 253 -> NavFn 254;
    # Kilted/Jazzy/Humble: 99 < 100 with trinary_costmap -> 0 -> NavFn 50.
    y = write_map(tmp_path, np.full((3, 3), 5, np.uint8), mode="scale", occupied_thresh=0.99, free_thresh=0.01)
    for distro, ros, navfn in (("rolling", 253, 254), ("lyrical", 253, 254), ("kilted", 0, 50),
                               ("jazzy", 0, 50), ("humble", 0, 50)):
        m = load_map_yaml(y, distro=distro)
        assert np.all(m.occupancy == 99) and np.all(m.ros_costmap == ros) and np.all(m.navfn_costs == navfn)
    assert np.all(load_map_yaml(y, distro="rolling", inscribed_cost_value=None).ros_costmap == 0)
    assert np.all(load_map_yaml(y, distro="jazzy", inscribed_cost_value=99).ros_costmap == 253)
    with pytest.raises(NavfnInputError) as e:
        load_map_yaml(y, distro="foxy")
    one_line_error(e, "unknown Nav2 distro", "foxy")


def test_scale_rounding_of_halves(tmp_path):
    # free 0, occupied 0.64, p = 153.  Legacy: occ = 1.0 - 153*257/65535 = 1.0 - 0.6 = 0.4,
    # 0.4 / 0.64 * 100.0 = 62.5 exactly in double; std::rint ties to even -> 62.
    # Current: n = 1.0f - 153/255.0f, (n - 0.0f) / 0.64f * 100.0f = 62.5 exactly in float;
    # Eigen's round is std::round, ties away from zero -> 63.
    assert (1.0 - 0.6 - 0.0) / (0.64 - 0.0) * 100.0 == 62.5
    n = F32(1.0) - F32(153) / F32(255.0)
    assert float(((n - F32(0.0)) / F32(0.64)) * F32(100.0)) == 62.5
    for distro, want in (("humble", 62), ("rolling", 63)):
        a = load_pixels(tmp_path, np.full((3, 3), 153, np.uint8), mode="scale", free_thresh=0.0,
                        occupied_thresh=0.64, distro=distro)
        assert np.all(a.occupancy == want), distro


def test_negate_at_a_decimal_threshold(tmp_path):
    # Legacy, free 0.2: negate=1, p=51: occ = shade = 13107/65535 = the double 0.2, not < 0.2
    # -> unknown; negate=0, p=204: occ = 1.0 - (the double 0.8) = 0.19999999999999996 < 0.2
    # -> free.  Current: n = 51/255.0f = 0.2f <= 0.2f -> free; 1.0f - 0.8f = 0.19999999f <= 0.2f
    # -> free: the inclusive float comparison makes the two agree.
    for distro, want51 in (("humble", -1), ("rolling", 0)):
        a = load_pixels(tmp_path, np.full((3, 3), 51, np.uint8), negate=1, free_thresh=0.2, distro=distro)
        b = load_pixels(tmp_path, np.full((3, 3), 204, np.uint8), negate=0, free_thresh=0.2, distro=distro)
        assert np.all(a.occupancy == want51) and np.all(b.occupancy == 0), distro


@pytest.mark.fast
def test_thresholds_inclusive_only_in_current(tmp_path):
    # occupied 0.2 with negate=1, p = 51: legacy 0.2 < 0.2 is false -> unknown (free 0.1);
    # current 0.2f >= 0.2f -> occupied.
    for distro, want in (("humble", -1), ("rolling", 100)):
        a = load_pixels(tmp_path, np.full((3, 3), 51, np.uint8), negate=1, occupied_thresh=0.2, free_thresh=0.1,
                        distro=distro)
        assert np.all(a.occupancy == want), distro


@pytest.mark.fast
def test_16_bit_grey(tmp_path):
    # Legacy keeps 16-bit samples: occ = 1 - v/65535.  v = 52690: occ 0.1960021 (not < 0.196)
    # -> unknown; v = 52691: occ 0.1959869 -> free; v = 52885: occ 0.19303 -> free.  Current
    # exports 8 bits with ScaleQuantumToChar, a truncating / 257: 52690, 52691 and 52885
    # (= 205 * 257 + 200) all give 205 -> unknown.
    a = np.full((3, 3), 65535, np.uint16)
    a[0, 0], a[0, 1], a[0, 2] = 52690, 52691, 0
    a[1, 0] = 52885
    Image.fromarray(a).save(tmp_path / "w.png")
    y = write_yaml(tmp_path, image="w.png")
    for distro, row, mid in (("humble", [-1, 0, 100], 0), ("rolling", [-1, -1, 100], -1)):
        m = load_map_yaml(y, distro=distro)
        assert m.occupancy[2].tolist() == row and m.occupancy[1].tolist() == [mid, 0, 0], distro
        assert np.all(m.occupancy[0] == 0)


def test_palette_with_transparency_is_matte(tmp_path):
    # A palette PNG with a tRNS chunk has a matte channel.  Index 0 = black, alpha 0; index 1 =
    # grey 205, opaque; index 2 = grey 128, opaque.  Legacy trinary averages alpha in:
    # black (0 + 0)/4 -> occ 1 -> occupied; 205: (3*205 + 255)/4 = 217.5 -> occ 0.147 -> free;
    # 128: (384 + 255)/4/255 = 0.6265 -> occ 0.3735 -> unknown.  Current: alpha 0 -> unknown,
    # 205 -> unknown, 128 -> n = 0.498 -> unknown.
    im = Image.new("P", (3, 3), 1)
    im.putpalette([0, 0, 0, 205, 205, 205, 128, 128, 128] + [0] * (256 * 3 - 9))
    im.putpixel((0, 0), 0)
    im.putpixel((1, 0), 2)
    im.save(tmp_path / "p.png", transparency=bytes([0, 255, 255]))
    y = write_yaml(tmp_path, image="p.png")
    m = load_map_yaml(y, distro="humble")
    assert m.occupancy[2].tolist() == [100, -1, 0] and np.all(m.occupancy[:2] == 0)
    assert np.all(load_map_yaml(y, distro="rolling").occupancy == -1)


def test_interpret_value_table():
    assert interpret_value(-1) == 255 and interpret_value(255) == 255
    assert interpret_value(-1, track_unknown_space=False) == 0
    assert interpret_value(100) == 254 and interpret_value(127) == 254 and interpret_value(-2) == 254
    assert interpret_value(99) == 0 and interpret_value(0) == 0
    assert interpret_value(99, trinary_costmap=False) == 251  # 0.99 * 254 = 251.46
    assert interpret_value(20, trinary_costmap=False) == 50  # 0.2 * 254 = 50.8
    assert interpret_value(99, inscribed_cost_value=99) == 253  # Nav2 rolling (#5781)
    assert interpret_value(60, lethal_threshold=50) == 254
    assert interpret_value(25, lethal_threshold=50, trinary_costmap=False) == 127


@pytest.mark.fast
def test_defaults(tmp_path):
    # the default distribution is Rolling (Nav2's main branch, like the golden suite's NavFn)
    m = load_map_yaml(write_map(tmp_path, np.full((3, 3), 255, np.uint8)))
    assert m.distro == "rolling" and m.mode == "trinary" and m.negate is False


def test_unknown_without_allow_unknown(tmp_path):
    m = load_pixels(tmp_path, np.full((3, 3), 205, np.uint8))
    assert np.all(m.navfn_costs == 253)
    assert np.all(load_map_yaml(m.path, allow_unknown=False).navfn_costs == 254)
    assert np.all(load_map_yaml(m.path, track_unknown_space=False).navfn_costs == 50)


def test_number_forms_yaml_cpp_accepts(tmp_path):
    # yaml-cpp's as<double> reads "5e-2"; PyYAML leaves it a string; negate may be a bool
    write_image(tmp_path / "m.pgm", np.full((3, 3), 255, np.uint8), "p5")
    (tmp_path / "m.yaml").write_text(
        "image: m.pgm\nresolution: 5e-2\norigin: [0, 0, 0]\nnegate: false\noccupied_thresh: 0.65\nfree_thresh: 0.196\n"
    )
    m = load_map_yaml(tmp_path / "m.yaml")
    assert m.resolution == 0.05 and m.negate is False and m.mode == "trinary"


# -------------------------------------------------------------------------------- bad input
def bad(path, *words, **kw):
    with pytest.raises(NavfnInputError) as e:
        load_map_yaml(path, **kw)
    return one_line_error(e, *words)


@pytest.mark.fast
def test_bad_yaml_files(tmp_path):
    bad(tmp_path / "none.yaml", "no such map YAML file")
    bad(tmp_path, "is a directory")
    (tmp_path / "a.yaml").write_text("image: [unclosed\nresolution: 0.05\n")
    bad(tmp_path / "a.yaml", "malformed YAML", "line")
    (tmp_path / "b.yaml").write_text("- 1\n- 2\n")
    bad(tmp_path / "b.yaml", "must be a mapping")
    (tmp_path / "c.yaml").write_text("")
    bad(tmp_path / "c.yaml", "must be a mapping")
    (tmp_path / "d.yaml").write_bytes(b"image: \xff\xfe\x00bad\n")
    bad(tmp_path / "d.yaml", "malformed YAML")
    (tmp_path / "e.yaml").write_text("image: !!python/object:os.system x\n")
    bad(tmp_path / "e.yaml", "malformed YAML")


@pytest.mark.fast
@pytest.mark.parametrize("key", ["image", "resolution", "origin", "negate", "occupied_thresh", "free_thresh"])
def test_missing_required_key(tmp_path, key):
    write_image(tmp_path / "m.pgm", np.full((3, 3), 255, np.uint8), "p5")
    bad(write_yaml(tmp_path, drop=(key,)), "missing required key", repr(key))


@pytest.mark.parametrize(
    "field,value,words",
    [
        ("image", 5, ["'image'", "file name"]),
        ("image", "", ["'image'", "empty"]),
        ("resolution", "abc", ["'resolution'", "number"]),
        ("resolution", True, ["'resolution'", "number"]),
        ("resolution", [0.05], ["'resolution'", "number"]),
        ("resolution", 0, ["'resolution'", "positive"]),
        ("resolution", -0.05, ["'resolution'", "positive"]),
        ("resolution", float("nan"), ["'resolution'", "finite"]),
        ("resolution", float("inf"), ["'resolution'", "finite"]),
        ("resolution", 1e-60, ["'resolution'", "float32"]),
        ("origin", "0 0 0", ["'origin'", "list"]),
        ("origin", [0.0, 0.0], ["'origin'", "3 elements"]),
        ("origin", [0.0, "x", 0.0], ["origin[1]", "number"]),
        ("negate", 0.5, ["'negate'"]),
        ("negate", "maybe", ["'negate'"]),
        ("occupied_thresh", [1], ["'occupied_thresh'", "number"]),
        ("occupied_thresh", 1.5, ["'occupied_thresh'", "[0, 1]"]),
        ("free_thresh", -0.1, ["'free_thresh'", "[0, 1]"]),
        ("free_thresh", 0.7, ["'free_thresh'", "below", "'occupied_thresh'"]),
        ("free_thresh", 0.65, ["'free_thresh'", "below"]),
        ("mode", "binary", ["unknown 'mode'", "binary"]),
        ("mode", 3, ["'mode'"]),
        ("mode", None, ["'mode'"]),
    ],
)
def test_bad_fields(tmp_path, field, value, words):
    write_image(tmp_path / "m.pgm", np.full((3, 3), 255, np.uint8), "p5")
    bad(write_yaml(tmp_path, **{field: value}), *words)


@pytest.mark.fast
def test_image_missing_or_outside(tmp_path):
    inner = tmp_path / "maps"
    inner.mkdir()
    bad(write_yaml(inner, image="nothere.pgm"), "does not exist")
    write_image(tmp_path / "outside.pgm", np.full((3, 3), 255, np.uint8), "p5")
    y = write_yaml(inner, image="../outside.pgm")
    bad(y, "outside the YAML's folder")
    assert load_map_yaml(y, allow_outside=True).image_size == (3, 3)
    bad(write_yaml(inner, image=str(tmp_path / "outside.pgm")), "outside the YAML's folder")
    os.symlink(tmp_path / "outside.pgm", inner / "link.pgm")
    bad(write_yaml(inner, image="link.pgm"), "outside the YAML's folder")
    # a symlink that stays inside is fine, and so is a '..' that comes back in
    write_image(inner / "real.pgm", np.full((3, 3), 255, np.uint8), "p5")
    os.symlink(inner / "real.pgm", inner / "inlink.pgm")
    assert load_map_yaml(write_yaml(inner, image="inlink.pgm")).image_size == (3, 3)
    assert load_map_yaml(write_yaml(inner, image="../maps/real.pgm")).image_size == (3, 3)
    bad(write_yaml(inner, image="."), "directory")


@pytest.mark.fast
def test_corrupt_images(tmp_path):
    (tmp_path / "g.pgm").write_bytes(b"this is not an image at all")
    bad(write_yaml(tmp_path, image="g.pgm"), "unreadable or corrupt image")
    (tmp_path / "t.pgm").write_bytes(b"P5\n10 10\n255\n" + bytes(30))  # 100 bytes promised
    bad(write_yaml(tmp_path, image="t.pgm"), "unreadable or corrupt image")
    (tmp_path / "v.pgm").write_bytes(b"P2\n3 3\n255\n0 0 0 0 300 0 0 0 0\n")  # sample above maxval
    bad(write_yaml(tmp_path, image="v.pgm"), "unreadable or corrupt image")
    Image.fromarray(np.full((20, 20), 7, np.uint8)).save(tmp_path / "p.png")
    data = (tmp_path / "p.png").read_bytes()
    (tmp_path / "p.png").write_bytes(data[: len(data) // 2])
    bad(write_yaml(tmp_path, image="p.png"), "unreadable or corrupt image")


@pytest.mark.parametrize("shape", [(2, 5), (5, 2), (1, 1)])
def test_image_too_small(tmp_path, shape):
    bad(write_map(tmp_path, np.full(shape, 255, np.uint8)), "at least 3x3")


# ------------------------------------------------------------- pixel -> cost, as properties
ALL_SHADES = np.arange(256, dtype=np.uint8).reshape(16, 16)  # image (r, c) holds 16 r + c
thresholds = st.tuples(st.integers(1, 996), st.integers(1, 996)).filter(lambda t: t[0] != t[1]).map(
    lambda t: (min(t) / 997, max(t) / 997)  # free < occupied; never equal to any k/255
)


def by_pixel(grid: np.ndarray) -> np.ndarray:
    """Values of a grid loaded from ALL_SHADES, indexed by pixel value."""
    return grid[::-1].reshape(256)


distros = st.sampled_from(["humble", "jazzy", "rolling"])


@HYP
@given(
    mode=st.sampled_from(["trinary", "scale"]),
    negate=st.booleans(),
    thr=thresholds,
    distro=distros,
    track_unknown=st.booleans(),
    trinary_costmap=st.booleans(),
    allow_unknown=st.booleans(),
    inscribed=st.sampled_from([None, 99]),
)
def test_cost_monotone_in_shade(mode, negate, thr, distro, track_unknown, trinary_costmap, allow_unknown, inscribed):
    free, occupied = thr
    with tempfile.TemporaryDirectory() as d:
        y = write_map(Path(d), ALL_SHADES, mode=mode, negate=int(negate), free_thresh=free, occupied_thresh=occupied)
        m = load_map_yaml(y, distro=distro, track_unknown_space=track_unknown, trinary_costmap=trinary_costmap,
                          allow_unknown=allow_unknown, inscribed_cost_value=inscribed)
    cost = by_pixel(m.navfn_costs).astype(int)
    ros = by_pixel(m.ros_costmap).astype(int)
    occ = by_pixel(m.occupancy).astype(int)
    # brighter pixel = lower occ (negate: higher), and every later step keeps the order:
    # trinary free (0 -> 0 -> 50) <= unknown (-1 -> 255 or 0 -> 253, 254 or 50) <= occupied
    # (100 -> 254 -> 254); scale occupancy and interpretValue (with 99 -> 253 too) are
    # monotone on 0..100; double and float division, subtraction and rounding are monotone.
    step = np.diff(cost)
    assert np.all(step >= 0) if negate else np.all(step <= 0)
    if mode == "scale":
        d_occ = np.diff(occ)
        assert np.all(d_occ >= 0) if negate else np.all(d_occ <= 0)
    # black is occupied (white when negated) and white free (black when negated)
    lethal_px, free_px = (255, 0) if negate else (0, 255)
    assert occ[lethal_px] == 100 and ros[lethal_px] == 254 and cost[lethal_px] == 254
    assert occ[free_px] == 0 and ros[free_px] == 0 and cost[free_px] == 50


@HYP
@given(mode=st.sampled_from(["trinary", "scale"]), thr=thresholds, distro=distros)
def test_negate_symmetry(mode, thr, distro):
    # Pixel p negated equals pixel 255 - p plain: occ is p/255 on one side and 1 - (255-p)/255
    # on the other, equal up to a last-bit rounding (double, or float for current), which
    # only matters at a threshold (none is near a k/255 here: m/997) or on a rounding half.
    free, occupied = thr
    if mode == "scale":
        for p in range(256):
            v = (p / 255 - free) / (occupied - free) * 100
            assume(abs(v - math.floor(v) - 0.5) > 1e-4)
    with tempfile.TemporaryDirectory() as d:
        a = load_map_yaml(write_map(Path(d), ALL_SHADES, mode=mode, negate=1, free_thresh=free,
                                    occupied_thresh=occupied, image="a.pgm"), distro=distro)
        b = load_map_yaml(write_map(Path(d), 255 - ALL_SHADES, mode=mode, negate=0, free_thresh=free,
                                    occupied_thresh=occupied, image="b.pgm"), distro=distro)
    assert np.array_equal(a.occupancy, b.occupancy)
    assert np.array_equal(a.navfn_costs, b.navfn_costs)


def expected_occupancy(pixels: np.ndarray, mode: str, distro: str) -> np.ndarray:
    """map_io's rule for a grey 8-bit image, negate 0, thresholds 0.65 / 0.196, image order."""
    if mode == "raw":
        return np.where(pixels <= 100, pixels, -1)
    if distro == "humble":  # double; v*257/65535 == v/255 exactly, as doubles
        occ = 1.0 - pixels.astype(np.float64) / 255.0
        mid = np.rint((occ - 0.196) / (0.65 - 0.196) * 100.0)
        return np.where(0.65 < occ, 100, np.where(occ < 0.196, 0, mid if mode == "scale" else -1))
    n = F32(1.0) - pixels.astype(F32) / F32(255.0)  # Eigen, float; the thresholds become floats
    o, f = F32(0.65), F32(0.196)
    scaled = (((n - f) / F32(0.65 - 0.196)) * F32(100.0)).astype(np.float64)
    mid = np.floor(scaled) + (scaled - np.floor(scaled) >= 0.5)  # std::round, non-negative
    between = np.where(mid >= 0, mid, 0) if mode == "scale" else -1
    return np.where(n <= f, 0, np.where(n >= o, 100, between))


@HYP
@given(
    st.integers(3, 9).flatmap(lambda h: st.integers(3, 9).flatmap(
        lambda w: st.lists(st.integers(0, 255), min_size=h * w, max_size=h * w).map(
            lambda v: np.array(v, np.uint8).reshape(h, w)))),
    st.sampled_from(["trinary", "scale", "raw"]),
    distros,
)
def test_p2_p5_png_load_identically(pixels, mode, distro):
    with tempfile.TemporaryDirectory() as d:
        loaded = [load_map_yaml(write_map(Path(d), pixels, fmt, image=f"m_{fmt}.{'png' if fmt == 'PNG' else 'pgm'}",
                                          mode=mode), distro=distro)
                  for fmt in ("p2", "p5", "PNG")]
    first = loaded[0]
    assert first.image_size == (pixels.shape[1], pixels.shape[0])
    for m in loaded[1:]:
        assert m.image_size == first.image_size
        assert np.array_equal(m.occupancy, first.occupancy)
        assert np.array_equal(m.ros_costmap, first.ros_costmap)
        assert np.array_equal(m.navfn_costs, first.navfn_costs)
    # and each equals the rule worked out per pixel from map_io
    want = expected_occupancy(pixels, mode, distro)
    assert np.array_equal(first.occupancy, want[::-1].astype(np.int8))
