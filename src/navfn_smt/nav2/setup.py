"""A Nav2 planning set-up from files: the map, the global costmap built on it, the plugin's
parameters; what ``plan --world`` and ``diagnose`` start from.

The global costmap is built by :mod:`.costmap` from the map (static layer) and the params
file's ``global_costmap`` section (its inflation layer); without a params file, the static
layer alone.
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Optional

import numpy as np

from ..errors import NavfnInputError
from ..distros import DEFAULT
from .mapserver import MapServerMap, load_map_yaml
from .params import PlannerParams, load_params_yaml, planner_params
from .plugin import Costmap, costmap_from_map


# The plugin is Rolling's navfn_planner.cpp; its max_cycles_factor parameter exists there and in
# Lyrical, released from it (earlier distributions give calcPath 4 * max(size_x, size_y) cycles, the factor's default).


@dataclass
class Setup:
    map: MapServerMap
    costmap: Costmap  # the master costmap the plugin plans on
    params: PlannerParams
    layers: list = field(default_factory=list)  # the layers that ran, in order
    notes: list = field(default_factory=list)  # what was read or left out, for the report


COSTMAP_FILES = (".npy", ".pgm")


def load_costmap_file(path, resolution: Optional[float], origin=(0.0, 0.0), distro: str = DEFAULT) -> MapServerMap:
    """A costmap given directly: a ``.npy`` array of costmap values (uint8, (height, width), row 0
    the grid's bottom row, as ``Costmap2D`` indexes it) or an 8-bit PGM whose pixels are the values
    (image row 0 at the top, as map_server images are).  ``resolution`` (metres per cell) is
    narrowed to float32 as a map message would carry it."""
    from .mapserver import read_image_quanta
    from ..spec.costs import set_costmap

    p = Path(path)
    if resolution is None:
        raise NavfnInputError(f"{p}: a costmap file has no resolution; give --resolution")
    if not (resolution > 0 and np.isfinite(np.float32(resolution)) and np.float32(resolution) > 0):
        raise NavfnInputError(f"--resolution must be a positive float32 number, got {resolution!r}")
    if not all(np.isfinite(v) for v in origin):
        raise NavfnInputError(f"--origin must be finite, got {origin!r}")
    if p.suffix.lower() == ".npy":
        a = _read_npy(p)
        if a.ndim != 2 or not (np.issubdtype(a.dtype, np.integer) and a.size and 0 <= a.min() and a.max() <= 255):
            raise NavfnInputError(f"{p}: a costmap must be a 2-D array of integers 0..255, got {a.dtype} {a.shape}")
        costs = np.ascontiguousarray(a, dtype=np.uint8)
    else:
        q = read_image_quanta(p)
        if q.channels.ndim != 2:
            raise NavfnInputError(f"{p}: a costmap image must be greyscale")
        costs = np.ascontiguousarray((q.channels // 257)[::-1], dtype=np.uint8)
    h, w = costs.shape
    if w < 3 or h < 3:
        raise NavfnInputError(f"{p}: the costmap is {w}x{h}; NavFn needs at least 3x3 cells")
    return MapServerMap(p, p, float(resolution), float(np.float32(resolution)), (float(origin[0]), float(origin[1]), 0.0),
                        w, h, "costmap", False, distro, 0.0, 0.0, np.zeros((h, w), np.int8), costs,
                        set_costmap(costs, is_ros=True))


def _read_npy(p: Path) -> np.ndarray:
    """A ``.npy`` array, its header checked (2-D, at most ``MAX_CELLS`` cells) before the data is read."""
    from ..inputs import check_cells

    try:
        with open(p, "rb") as f:
            version = np.lib.format.read_magic(f)
            if version == (1, 0):
                shape, _, dtype = np.lib.format.read_array_header_1_0(f)
            elif version in ((2, 0), (3, 0)):
                shape, _, dtype = np.lib.format.read_array_header_2_0(f)
            else:
                raise ValueError(f"unknown .npy version {version}")
            if len(shape) != 2:
                raise NavfnInputError(f"{p}: a costmap must be a 2-D array, got shape {shape}")
            check_cells(shape[1], shape[0], str(p))
            f.seek(0)
            a = np.load(f, allow_pickle=False)
    except FileNotFoundError:
        raise NavfnInputError(f"{p}: no such costmap file") from None
    except NavfnInputError:
        raise
    except (OSError, ValueError, EOFError, TypeError, SyntaxError) as e:
        raise NavfnInputError(f"{p}: not a readable .npy array ({' '.join(str(e).split()) or type(e).__name__})") from None
    if not isinstance(a, np.ndarray):
        raise NavfnInputError(f"{p}: not a .npy array")
    return a


def load_setup(map_yaml, params_file=None, distro: str = DEFAULT, allow_outside: bool = False,
               overrides: Optional[dict] = None, resolution: Optional[float] = None, origin=(0.0, 0.0),
               layers_arith=None) -> Setup:
    """Map + params file -> :class:`Setup`; ``overrides`` replace plugin parameters.

    ``map_yaml`` may also be a costmap given directly (:data:`COSTMAP_FILES`, with ``resolution``
    and ``origin``): the plugin plans on it as it is, no layer runs.

    Without a params file the plugin has Nav2's default parameters and the costmap is the map's
    static layer alone; a params file without a ``global_costmap`` section gives Nav2's code
    defaults for the costmap (static, obstacle and inflation layers; the obstacle layer is
    skipped).  ``layers_arith``: the layers compute as a build of that
    :class:`~navfn_smt.spec.arithmetic.LayersArithmetic` does (None: x86-64's).
    """
    from ..spec.arithmetic import LAYERS_X86_64
    from . import costmap as layers

    params = planner_params(params_file) if params_file else PlannerParams()
    if overrides:
        params = replace(params, **{k: v for k, v in overrides.items() if v is not None})
    from ..distros import distro as distro_record

    record = distro_record(distro)
    params = replace(params, distro=distro)
    notes = [] if record.checked else [
        f"{distro}'s navfn_planner.cpp is not among the sources this model was checked against: the plugin "
        f"is modelled as its neighbours' (distros.py)"]
    if not record.cycles_factor and params.max_cycles_factor != 4:
        notes.append(f"max_cycles_factor {params.max_cycles_factor} ignored: {distro} has no such parameter "
                     f"(Nav2 PR #6308, August 2026); calcPath gets 4 * max(size_x, size_y) cycles")
        params = replace(params, max_cycles_factor=4)
    if Path(map_yaml).suffix.lower() in COSTMAP_FILES:
        m = load_costmap_file(map_yaml, resolution, origin, distro)
        notes.append("a costmap given directly: no costmap layer ran")
        return Setup(m, costmap_from_map(m), params, [], notes)
    if params_file and not any(k in load_params_yaml(params_file) for k in ("global_costmap", "/global_costmap")):
        cparams = layers.CostmapParams()
        notes.append(f"{params_file} has no global_costmap section: Nav2's code defaults for the global costmap")
    elif params_file:
        cparams = layers.load_costmap_params(params_file, distro)
    else:
        m = load_map_yaml(Path(map_yaml), allow_outside, distro=distro)
        notes.append("no params file: Nav2's default planner parameters, the map's static layer only "
                     "(nav2_bringup's track_unknown_space: true; pass --params for the inflation layer)")
        return Setup(m, costmap_from_map(m), params, ["static_layer (static)"], notes)
    m = load_map_yaml(Path(map_yaml), allow_outside, distro=distro)
    gc = layers.build_global_costmap(m, cparams, distro, arith=layers_arith or LAYERS_X86_64)
    return Setup(m, costmap_from_map(m, gc.costmap), params, list(gc.layers_run), notes + list(gc.notes))


def check_params_file(path) -> None:
    if path is not None and not Path(path).is_file():
        raise NavfnInputError(f"{path}: no such params file")
