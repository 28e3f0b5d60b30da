"""Maps in ROS ``map_server`` format (a YAML file beside an image), loaded as Nav2 loads them.

The chain from pixels to the costs NavFn plans on, each step as Nav2 implements it.  Nav2's
distributions differ in step 1 and 2; ``distro`` selects which (default ``"rolling"``, the
main branch, which the golden suite's NavFn also follows; see :data:`navfn_smt.distros.DISTROS`).

1. ``nav2_map_server/src/map_io.cpp`` (``loadMapYaml``, ``loadMapFromFile``).  The YAML
   gives ``image``, ``resolution``, ``origin`` [x, y, yaw], ``negate``, ``occupied_thresh``,
   ``free_thresh`` and optionally ``mode`` (trinary when absent; case-insensitive).  The
   image is read with GraphicsMagick, which Debian/Ubuntu build with 16-bit quanta (Q16:
   an 8-bit sample ``v`` is the quantum ``v * 257``, MaxRGB 65535).  Two generations:

   ``"legacy"`` (Humble, Iron, Jazzy before 1.3.7), per pixel in double:
     shade = mean of the R, G, B quanta (plus ``MaxRGB - opacity``, the alpha, in trinary
     mode when the image has a matte channel) / 65535; ``occ = shade`` when ``negate``, else
     ``1.0 - shade``; trinary: ``occupied_thresh < occ`` -> 100, else ``occ < free_thresh``
     -> 0, else -1; scale: not fully opaque -> -1, else as trinary with
     ``rint((occ - free) / (occupied - free) * 100.0)`` (halves to even) in between; raw:
     ``round(shade * 255)`` when in 0..100, else -1.
   ``"current"`` (Nav2 #5071, April 2025: Jazzy from 1.3.7, Kilted, Lyrical, Rolling), with
   Eigen in float32:
     the image is converted to greyscale by GraphicsMagick (Rec. 601 luma from float
     tables, ``floor(0.299f R + 0.587f G + 0.114f B + 0.5)``, which is the sample itself
     for grey pixels) and exported as 8 bits (``quantum / 257``, truncated); ``n =
     grey / 255.0f``, ``1.0f - n`` unless ``negate``; the thresholds are compared as floats
     and *inclusively*: ``n >= occupied`` -> 100, ``n <= free`` -> 0, else -1; scale: values
     strictly between become ``roundf((n - free) / (occupied - free) * 100.0f)`` (halves
     away from zero); in trinary and scale alike a pixel whose 8-bit alpha is below 255 is
     -1 (alpha is never averaged in); raw: the 8-bit grey value when in 0..100, else -1.

   Both: raw ignores ``negate``; image row ``y`` becomes grid row ``height - 1 - y`` (grid
   row 0 is the image's bottom row).  ``nav_msgs/MapMetaData`` carries the resolution as
   float32, so the costmap works with the YAML's resolution narrowed to float32
   (``costmap_resolution``).
2. ``nav2_costmap_2d/plugins/static_layer.cpp`` (``interpretValue``): each occupancy value,
   read as an unsigned char (-1 is 255), becomes a costmap value: the unknown value (255)
   -> NO_INFORMATION (255) when ``track_unknown_space`` (true in nav2_bringup's global
   costmap; the code default is false) else FREE_SPACE (0); Lyrical and Rolling only: the
   value ``inscribed_obstacle_cost_value`` (99) -> INSCRIBED_INFLATED_OBSTACLE (253); values
   ``>= lethal_threshold`` (100) -> LETHAL_OBSTACLE (254); otherwise FREE_SPACE with
   ``trinary_costmap`` (default true) or ``(double)value / lethal_threshold * 254``
   truncated.
3. ``NavFn::setCostmap(costmap, isROS=true, allow_unknown)`` (:func:`..spec.costs.set_costmap`;
   the planner's ``allow_unknown`` defaults to true).

Only the static layer is modelled: a Nav2 global costmap normally also has an obstacle and
an inflation layer, which change the costs.

World coordinates, and planning between world poses as Nav2's NavFn planner plugin does, are
in :mod:`navfn_smt.nav2.plugin` (``Costmap2D::worldToMap`` truncates; the plugin's own
``worldToMap`` rounds).  The origin's yaw is read but, as in Nav2's costmap, not used.

Images are decoded with Pillow.  This matches GraphicsMagick for 8-bit grey, RGB, palette
and alpha images (PGM, PNG, BMP, ...) and for 16-bit grey; Pillow reduces 16-bit colour
PNGs to 8 bits, and rescales PGMs whose maxval is not 255 or 65535, where GraphicsMagick
keeps or scales the samples its own way.

The shared suite's ROS maps (``navfn-suite/ROS/*/map.bin``) were not made by this chain:
map.bin is a function of the pixel value alone (0 -> 254, 128 -> 152, 205 -> 90,
254 -> 50, 255 -> 50, whatever the YAML's mode and thresholds), stored in image row order
(row 0 = the image's top row, not the OccupancyGrid's bottom row), with a one-cell lethal
frame.  It equals this loader's ``add_border(navfn_costs)`` only for ``empty_room`` (no grey
pixels, vertically symmetric); see ``tests/test_mapserver.py``.
"""

from __future__ import annotations

import math
import os
import re
import warnings
from dataclasses import dataclass
from pathlib import Path
from typing import Optional

import numpy as np

from ..errors import NavfnInputError
from ..spec.constants import FREE_SPACE, INSCRIBED_INFLATED_OBSTACLE, LETHAL_OBSTACLE, NO_INFORMATION
from ..spec.costs import set_costmap
from ..distros import DEFAULT
from ..distros import distro as distro_record

MODES = ("trinary", "scale", "raw")
MAP_IO = ("current", "legacy")
_FROM_DISTRO = "distro"  # default of inscribed_cost_value: whatever the distro does
REQUIRED_KEYS = ("image", "resolution", "origin", "negate", "occupied_thresh", "free_thresh")

QUANTUM_MAX = 65535.0  # MaxRGB of a Q16 GraphicsMagick
OCC_UNKNOWN, OCC_FREE, OCC_OCCUPIED = -1, 0, 100  # nav2_util/occ_grid_values.hpp

# yaml-cpp reads "5e-2" as a double; PyYAML (YAML 1.1) only resolves floats that have a dot
# and leaves such scalars as strings.  Plain decimal numbers in a string are accepted.
_DECIMAL = re.compile(r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?")


@dataclass
class MapServerMap:
    """A map as Nav2's map server, static layer and NavFn planner see it.

    All three arrays are (height, width) with row ``y`` the *grid* row (0 = the image's
    bottom row), i.e. NavFn's cell ``(x, y)`` at index ``y * width + x``.
    """

    path: Path  # the YAML file
    image_path: Path  # the image, as the YAML names it (joined to the YAML's folder)
    resolution: float  # metres per cell, as written in the YAML (double)
    costmap_resolution: float  # the same narrowed to float32, as the costmap uses it
    origin: tuple[float, float, float]  # x, y, yaw of the grid's lower-left corner
    width: int
    height: int
    mode: str
    negate: bool
    distro: str  # the Nav2 distribution whose loading rules were applied
    occupied_thresh: float
    free_thresh: float
    occupancy: np.ndarray  # int8, nav_msgs/OccupancyGrid values (-1, 0..100)
    ros_costmap: np.ndarray  # uint8, the static layer's costmap values
    navfn_costs: np.ndarray  # uint8, NavFn's internal costs (setCostmap, no border)

    @property
    def image_size(self) -> tuple[int, int]:
        return (self.width, self.height)


# ------------------------------------------------------------------------------ the YAML
def load_yaml(path: Path):
    import yaml

    try:
        data = path.read_bytes()
    except FileNotFoundError:
        raise NavfnInputError(f"{path}: no such map YAML file") from None
    except IsADirectoryError:
        raise NavfnInputError(f"{path}: is a directory, not a map YAML file") from None
    except OSError as e:
        raise NavfnInputError(f"{path}: unreadable map YAML file ({e.strerror or e.__class__.__name__})") from None
    try:
        return yaml.safe_load(data)
    except yaml.MarkedYAMLError as e:
        mark = e.problem_mark or e.context_mark
        where = f" at line {mark.line + 1}, column {mark.column + 1}" if mark else ""
        what = (e.problem or e.context or "syntax error").strip()
        raise NavfnInputError(f"{path}: malformed YAML{where}: {what}") from None
    except yaml.YAMLError as e:
        raise NavfnInputError(f"{path}: malformed YAML ({' '.join(str(e).split())})") from None
    except (RecursionError, ValueError, TypeError) as e:
        raise NavfnInputError(f"{path}: malformed YAML ({e.__class__.__name__})") from None


def _type_name(v) -> str:
    if v is None:
        return "null"
    return {bool: "a boolean", str: "a string", list: "a list", dict: "a mapping"}.get(type(v), type(v).__name__)


def _number(path: Path, key: str, v) -> float:
    """A YAML scalar that yaml-cpp's ``as<double>()`` would read, as a finite float."""
    x = None
    if isinstance(v, (int, float)) and not isinstance(v, bool):
        try:
            x = float(v)
        except OverflowError:
            raise NavfnInputError(f"{path}: '{key}' is out of range ({v})") from None
    elif isinstance(v, str) and _DECIMAL.fullmatch(v.strip()):
        x = float(v.strip())
    if x is None:
        raise NavfnInputError(f"{path}: '{key}' must be a number, got {_type_name(v)} ({v!r})")
    if not math.isfinite(x):
        raise NavfnInputError(f"{path}: '{key}' must be a finite number, got {v!r}")
    return x


@dataclass
class _YamlParams:
    image: str
    image_path: Path
    resolution: float
    origin: tuple[float, float, float]
    negate: bool
    occupied_thresh: float
    free_thresh: float
    mode: str


def read_map_yaml(yaml_path, allow_outside: bool = False) -> _YamlParams:
    """Parse and validate a map_server YAML (``loadMapYaml``); the image is not read."""
    path = Path(yaml_path)
    doc = load_yaml(path)
    if not isinstance(doc, dict):
        raise NavfnInputError(f"{path}: a map YAML must be a mapping of keys to values, got {_type_name(doc)}")
    missing = [k for k in REQUIRED_KEYS if k not in doc]
    if missing:
        raise NavfnInputError(f"{path}: missing required key{'s' if len(missing) > 1 else ''} "
                              f"{', '.join(repr(k) for k in missing)}")

    image = doc["image"]
    if not isinstance(image, str):
        raise NavfnInputError(f"{path}: 'image' must be a file name, got {_type_name(image)} ({image!r})")
    if not image.strip():
        raise NavfnInputError(f"{path}: 'image' is empty")
    if "\x00" in image:
        raise NavfnInputError(f"{path}: 'image' contains a NUL character")

    resolution = _number(path, "resolution", doc["resolution"])
    if resolution <= 0.0:
        raise NavfnInputError(f"{path}: 'resolution' must be positive, got {doc['resolution']!r}")
    with np.errstate(over="ignore", under="ignore"):
        narrowed = np.float32(resolution)
    if not np.isfinite(narrowed) or narrowed <= 0:
        raise NavfnInputError(f"{path}: 'resolution' {doc['resolution']!r} does not fit the float32 of nav_msgs/MapMetaData")

    origin = doc["origin"]
    if not isinstance(origin, (list, tuple)):
        raise NavfnInputError(f"{path}: 'origin' must be a list [x, y, yaw], got {_type_name(origin)} ({origin!r})")
    if len(origin) != 3:
        raise NavfnInputError(f"{path}: 'origin' must have 3 elements [x, y, yaw], not {len(origin)}")
    ox, oy, oyaw = (_number(path, f"origin[{i}]", v) for i, v in enumerate(origin))

    occupied = _number(path, "occupied_thresh", doc["occupied_thresh"])
    free = _number(path, "free_thresh", doc["free_thresh"])
    for key, t in (("occupied_thresh", occupied), ("free_thresh", free)):
        if not 0.0 <= t <= 1.0:
            raise NavfnInputError(f"{path}: '{key}' must be in [0, 1], got {doc[key]!r}")
    if free >= occupied:
        raise NavfnInputError(f"{path}: 'free_thresh' ({doc['free_thresh']!r}) must be below "
                              f"'occupied_thresh' ({doc['occupied_thresh']!r})")

    negate = doc["negate"]
    if isinstance(negate, bool):
        pass
    elif isinstance(negate, int):
        negate = negate != 0  # yaml-cpp as<int>, used as a truth value
    else:
        raise NavfnInputError(f"{path}: 'negate' must be 0, 1, true or false, got {_type_name(negate)} ({negate!r})")

    mode = doc.get("mode", "trinary")
    if "mode" in doc and not isinstance(mode, str):
        raise NavfnInputError(f"{path}: 'mode' must be one of {', '.join(MODES)}, got {_type_name(mode)} ({mode!r})")
    if mode.lower() not in MODES:
        raise NavfnInputError(f"{path}: unknown 'mode' {mode!r} (choose from {', '.join(MODES)})")
    mode = mode.lower()

    # map_io joins a relative image name to dirname() of the YAML path as given.
    folder = os.path.dirname(str(path)) or "."
    image_path = Path(image if image.startswith("/") else folder + "/" + image)
    if not allow_outside:
        real_folder = Path(os.path.realpath(folder))
        real_image = Path(os.path.realpath(image_path))
        if not real_image.is_relative_to(real_folder):
            raise NavfnInputError(f"{path}: image {image!r} resolves to {real_image}, outside the YAML's folder "
                                  f"{real_folder} (--allow-outside permits it)")
    return _YamlParams(image, image_path, resolution, (ox, oy, oyaw), bool(negate), occupied, free, mode)


# ----------------------------------------------------------------------------- the image
@dataclass
class ImageQuanta:
    """An image as GraphicsMagick Q16 holds it, image row 0 at the top.

    ``channels`` is (height, width) for a grey image or (height, width, 3) for an RGB one,
    int32 quanta in 0..65535 (8-bit samples ``v`` are ``v * 257``; 16-bit grey samples are
    kept).  ``alpha`` is ``MaxRGB - opacity`` (65535 = opaque) when the image has a matte
    channel (an alpha band, or transparency such as a PNG tRNS chunk), else None.
    """

    channels: np.ndarray
    alpha: Optional[np.ndarray]

    @property
    def shape(self) -> tuple[int, int]:
        return self.channels.shape[:2]


def read_image_quanta(image_path) -> ImageQuanta:
    """Decode an image with Pillow into :class:`ImageQuanta`; bad files raise NavfnInputError."""
    from PIL import Image

    p = Path(image_path)
    if not p.exists():
        raise NavfnInputError(f"{p}: image file does not exist")
    if p.is_dir():
        raise NavfnInputError(f"{p}: image is a directory, not an image file")
    from ..inputs import check_cells

    try:
        with warnings.catch_warnings():
            # the size is checked against MAX_CELLS below; Pillow's own bomb warning would be a second line
            warnings.simplefilter("ignore", Image.DecompressionBombWarning)
            with Image.open(p) as im:
                check_cells(im.size[0], im.size[1], f"{p}: image")  # from the header, before any pixel
                im.load()
                return _quanta(im, p)
    except NavfnInputError:
        raise
    except Image.DecompressionBombError:
        raise NavfnInputError(f"{p}: image header claims more than {2 * Image.MAX_IMAGE_PIXELS} pixels; the limit "
                              f"is 100000000 cells (100 M)") from None
    except MemoryError:
        raise NavfnInputError(f"{p}: image too large to load") from None
    except Exception as e:  # Pillow raises many types for bad bytes (OSError, SyntaxError, ValueError, ...)
        msg = " ".join(str(e).split()) or e.__class__.__name__
        raise NavfnInputError(f"{p}: unreadable or corrupt image ({msg})") from None


def _quanta(im, p: Path) -> ImageQuanta:
    mode = im.mode
    if mode in ("I;16", "I;16L", "I;16B", "I;16N", "I"):  # 16-bit grey (PNG, PGM with maxval > 255)
        a = np.asarray(im).astype(np.int64)
        if a.size and (a.min() < 0 or a.max() > 65535):
            raise NavfnInputError(f"{p}: {mode} image with samples outside 0..65535 is not supported")
        alpha = None
        t = im.info.get("transparency")
        if isinstance(t, int) and not isinstance(t, bool):
            alpha = np.where(a == t, 0, 65535).astype(np.int32)
        return ImageQuanta(a.astype(np.int32), alpha)
    bands = im.getbands()
    has_alpha = "A" in bands or "a" in bands or "transparency" in im.info
    grey = mode in ("1", "L", "LA", "La", "F")
    if grey:
        conv = im.convert("LA" if has_alpha else "L") if mode != "L" or has_alpha else im
    else:
        conv = im.convert("RGBA" if has_alpha else "RGB")
    a = np.asarray(conv).astype(np.int32) * 257
    if has_alpha:
        return ImageQuanta(np.ascontiguousarray(a[..., :-1].squeeze(-1) if grey else a[..., :3]), a[..., -1])
    return ImageQuanta(a, None)


def _trinary_classes(occ, occupied, free, inclusive: bool) -> np.ndarray:
    out = np.full(occ.shape, OCC_UNKNOWN, dtype=np.int8)
    if inclusive:  # current: occ >= occupied, then occ <= free overrides
        out[occ >= occupied] = OCC_OCCUPIED
        out[occ <= free] = OCC_FREE
    else:  # legacy: occupied < occ first, else occ < free
        out[occ < free] = OCC_FREE
        out[occupied < occ] = OCC_OCCUPIED
    return out


def _round_half_away_array(x: np.ndarray) -> np.ndarray:
    """C ``round`` / ``roundf`` on non-negative values (halves away from zero), exactly."""
    x = np.asarray(x, dtype=np.float64)  # float32 values are exact in double
    fl = np.floor(x)
    return fl + (x - fl >= 0.5)


def gm_grey8(q: ImageQuanta) -> np.ndarray:
    """GraphicsMagick's ``type(GrayscaleType)`` then ``write(..., "I", CharPixel)``: 8-bit grey values.

    RGB -> GRAY uses float tables (``0.299f * i`` ...), a float sum, then ``floor(sum + 0.5)``
    in double (clamped to MaxRGB); the 8-bit export is ``quantum / 257`` truncated.
    """
    c = q.channels
    if c.ndim == 2:
        quantum = c
    else:
        f = np.float32
        r, g, b = (c[..., i].astype(f) for i in range(3))
        total = ((f(0.299) * r + f(0.587) * g) + f(0.114) * b) + f(0.0)
        t = total.astype(np.float64)
        quantum = np.floor(np.where(t > 65535.0, 65535.0, np.where(t < 0.0, 0.0, t + 0.5))).astype(np.int64)
    return quantum // 257


def occupancy_from_quanta(
    q: ImageQuanta, mode: str, negate: bool, occupied_thresh: float, free_thresh: float, map_io: str = "current"
) -> np.ndarray:
    """``loadMapFromFile``'s per-pixel rule; int8 in image row order (row 0 = top)."""
    if mode not in MODES:
        raise NavfnInputError(f"unknown mode {mode!r} (choose from {', '.join(MODES)})")
    if map_io not in MAP_IO:
        raise NavfnInputError(f"unknown map_io {map_io!r} (choose from {', '.join(MAP_IO)})")
    if map_io == "current":
        return _occupancy_current(q, mode, negate, occupied_thresh, free_thresh)
    return _occupancy_legacy(q, mode, negate, occupied_thresh, free_thresh)


def _occupancy_current(q: ImageQuanta, mode, negate, occupied_thresh, free_thresh) -> np.ndarray:
    grey = gm_grey8(q)
    if mode == "raw":  # cast to int8: 128..255 turn negative; only 0..100 survive
        return np.where(grey <= OCC_OCCUPIED, grey, OCC_UNKNOWN).astype(np.int8)
    f = np.float32
    n = grey.astype(f) / f(255.0)
    if not negate:
        n = f(1.0) - n
    occupied, free = f(occupied_thresh), f(free_thresh)  # Eigen converts the double scalars
    out = _trinary_classes(n, occupied, free, inclusive=True)
    if mode == "scale":
        between = (n > free) & (n < occupied)
        scaled = ((n[between] - free) / f(occupied_thresh - free_thresh)) * f(100.0)
        out[between] = _round_half_away_array(scaled).astype(np.int8)
    if q.alpha is not None:
        out[q.alpha // 257 < 255] = OCC_UNKNOWN
    return out


def _occupancy_legacy(q: ImageQuanta, mode, negate, occupied_thresh, free_thresh) -> np.ndarray:
    c = q.channels
    total = (3 * c if c.ndim == 2 else c[..., 0] + c[..., 1] + c[..., 2]).astype(np.float64)  # exact
    n = 3.0
    if mode == "trinary" and q.alpha is not None:
        total = total + q.alpha
        n = 4.0
    shade = (total / n) / QUANTUM_MAX  # sum / channels.size(), then scaleQuantumToDouble
    if mode == "raw":
        pct = _round_half_away_array(shade * 255.0)
        return np.where(pct <= OCC_OCCUPIED, pct, OCC_UNKNOWN).astype(np.int8)
    occ = shade if negate else 1.0 - shade
    out = _trinary_classes(occ, occupied_thresh, free_thresh, inclusive=False)
    if mode == "scale":
        between = ~((occupied_thresh < occ) | (occ < free_thresh))
        mid = np.rint((occ[between] - free_thresh) / (occupied_thresh - free_thresh) * 100.0)
        out[between] = mid.astype(np.int8)
        if q.alpha is not None:
            out[q.alpha != 65535] = OCC_UNKNOWN
    return out


# ------------------------------------------------------------------------------ costmaps
def interpret_value(
    value: int,
    track_unknown_space: bool = True,
    lethal_threshold: int = 100,
    trinary_costmap: bool = True,
    unknown_cost_value: int = 255,
    inscribed_cost_value: Optional[int] = None,
) -> int:
    """``StaticLayer::interpretValue`` on one occupancy value read as an unsigned char."""
    v = int(value) & 0xFF
    lethal = max(min(int(lethal_threshold), 100), 0)  # getParameters clamps it to 0..100
    if v == unknown_cost_value:
        return NO_INFORMATION if track_unknown_space else FREE_SPACE
    if inscribed_cost_value is not None and v == inscribed_cost_value:
        return INSCRIBED_INFLATED_OBSTACLE
    if v >= lethal:
        return LETHAL_OBSTACLE
    if trinary_costmap:
        return FREE_SPACE
    return int((float(v) / lethal) * LETHAL_OBSTACLE)  # double, truncated to unsigned char


def static_layer_costs(occupancy: np.ndarray, **params) -> np.ndarray:
    """The static layer's costmap for an int8 occupancy grid (``interpret_value`` per cell)."""
    lut = np.array([interpret_value(v, **params) for v in range(256)], dtype=np.uint8)
    return lut[np.asarray(occupancy, dtype=np.int8).view(np.uint8)]


# ------------------------------------------------------------------------------- loading
def load_map_yaml(
    path,
    allow_outside: bool = False,
    *,
    distro: str = DEFAULT,
    track_unknown_space: bool = True,
    lethal_threshold: int = 100,
    trinary_costmap: bool = True,
    unknown_cost_value: int = 255,
    inscribed_cost_value=_FROM_DISTRO,
    allow_unknown: bool = True,
) -> MapServerMap:
    """Load a map_server YAML and its image; every problem raises :class:`NavfnInputError`.

    ``distro`` (a key of :data:`navfn_smt.distros.DISTROS`) selects the map_io generation and the static
    layer's inscribed-value rule; ``inscribed_cost_value`` (an int or None) overrides the
    latter.  The other keyword arguments are the static layer's parameters (defaults:
    Nav2's, with ``track_unknown_space`` true as nav2_bringup's global costmap sets it) and
    the NavFn planner's ``allow_unknown`` (default true).  ``allow_outside`` permits an
    image path that resolves (through symlinks and ``..``) outside the YAML's folder.
    """
    record = distro_record(distro)
    map_io, inscribed = record.map_io, record.inscribed_cost
    if inscribed_cost_value != _FROM_DISTRO:
        inscribed = inscribed_cost_value
    y = read_map_yaml(path, allow_outside)
    quanta = read_image_quanta(y.image_path)
    height, width = quanta.shape
    if width < 3 or height < 3:
        raise NavfnInputError(f"{y.image_path}: image is {width}x{height} pixels; NavFn needs at least 3x3")
    occ_img = occupancy_from_quanta(quanta, y.mode, y.negate, y.occupied_thresh, y.free_thresh, map_io)
    occupancy = np.ascontiguousarray(occ_img[::-1])  # image row 0 (top) is grid row height-1
    ros = static_layer_costs(
        occupancy,
        track_unknown_space=track_unknown_space,
        lethal_threshold=lethal_threshold,
        trinary_costmap=trinary_costmap,
        unknown_cost_value=unknown_cost_value,
        inscribed_cost_value=inscribed,
    )
    navfn = set_costmap(ros, is_ros=True, allow_unknown=allow_unknown)
    return MapServerMap(
        path=Path(path),
        image_path=y.image_path,
        resolution=y.resolution,
        costmap_resolution=float(np.float32(y.resolution)),
        origin=y.origin,
        width=int(width),
        height=int(height),
        mode=y.mode,
        negate=y.negate,
        distro=distro,
        occupied_thresh=y.occupied_thresh,
        free_thresh=y.free_thresh,
        occupancy=occupancy,
        ros_costmap=ros,
        navfn_costs=navfn,
    )
