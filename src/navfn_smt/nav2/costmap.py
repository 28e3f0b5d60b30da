"""The global costmap half of a Nav2 params file, and the costmap it builds on a static map.

``global_costmap: global_costmap: ros__parameters:`` holds the costmap node's parameters
(``Costmap2DROS::getParameters``) and one section per plugin, named in ``plugins``, whose
``plugin:`` gives the type.  Read here, with the **code defaults** when absent:

==========================  ========================  ===========================================
key                         code default              nav2_bringup's nav2_params.yaml
==========================  ========================  ===========================================
plugins                     static_layer,             the same three names
                            obstacle_layer,
                            inflation_layer
robot_radius                0.1 (double)              0.22
footprint                   "[]" (string)             absent
footprint_padding           0.01f (held as float)     absent
resolution                  0.1                       0.05 (the static map's resolution wins)
track_unknown_space         false                     true
lethal_cost_threshold       100 (int, clamped 0..100) absent
trinary_costmap             true                      absent
unknown_cost_value          255 (int)                 absent
inscribed_obstacle_cost_    99 (Lyrical, Rolling)     absent
value
use_maximum                 false                     absent
<inflation>.inflation_      0.55                      0.55 (Humble, Iron), 0.7 (Jazzy on)
radius
<inflation>.cost_scaling_   10.0                      3.0
factor
<inflation>.inflate_        false / false             absent
unknown / _around_unknown
<inflation>.custom_         -1.0 (Lyrical, Rolling;   absent
inscribed_radius            new layer only)
==========================  ========================  ===========================================

The static layer's settings are the costmap node's own keys, not the plugin section's (the
layer reads ``track_unknown_space``, ``lethal_cost_threshold``, ... from the node).
rclcpp refuses an override whose type differs from the declared default, so ``inflation_radius:
1`` is an error (write ``1.0``), as it is here.

Which inflation code a type names depends on the distro (see :data:`INFLATION_TYPES`):
``nav2_costmap_2d::InflationLayer`` is the breadth-first layer up to Kilted (Nav2 1.4.x) and
the distance-transform layer from Nav2 1.5.0 on (PR #5933, March 2026: Lyrical, Rolling),
where the old one is ``nav2_costmap_2d::LegacyInflationLayer``.

The costmap update (``LayeredCostmap::updateMap`` with full bounds, as after a new static
map): the master grid is reset to ``NO_INFORMATION`` (``track_unknown_space``) or
``FREE_SPACE``, then each plugin runs in ``plugins`` order.  Obstacle, voxel and range
layers need sensor data and are skipped with a note (with no observations they leave the
master unchanged, except that the obstacle layer's footprint clearing frees the cells under
the robot); costmap filters need filter masks and are skipped likewise.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import Mapping, Optional, Union

import numpy as np

from ..errors import NavfnInputError
from ..spec.arithmetic import LAYERS_X86_64, LayersArithmetic
from ..spec.constants import FREE_SPACE, NO_INFORMATION
from ..distros import distro as distro_record
from ..distros import DEFAULT, DISTROS
from .mapserver import MapServerMap, static_layer_costs
from .footprint import robot_footprint
from .params import load_params_yaml
from .inflation import inflate_current, inflate_legacy

STATIC = "nav2_costmap_2d::StaticLayer"
INFLATION = "nav2_costmap_2d::InflationLayer"
LEGACY_INFLATION = "nav2_costmap_2d::LegacyInflationLayer"
SENSOR_LAYERS = ("nav2_costmap_2d::ObstacleLayer", "nav2_costmap_2d::VoxelLayer", "nav2_costmap_2d::RangeSensorLayer")
UNMODELLED = ("nav2_costmap_2d::DenoiseLayer", "nav2_costmap_2d::PluginContainerLayer",
              "nav2_costmap_2d::AsymmetricInflationLayer")
DEFAULT_PLUGINS = (("static_layer", STATIC), ("obstacle_layer", SENSOR_LAYERS[0]), ("inflation_layer", INFLATION))


def inflation_types(distro: str) -> dict[str, str]:
    """Plugin type -> the inflation code it runs in ``distro`` ("current" or "legacy")."""
    if distro_record(distro).distance_transform_inflation:
        return {INFLATION: "current", LEGACY_INFLATION: "legacy"}
    return {INFLATION: "legacy"}


INFLATION_TYPES = {d: inflation_types(d) for d in DISTROS}


# ------------------------------------------------------------------------ the parameters
@dataclass(frozen=True)
class InflationParams:
    """One inflation plugin's parameters (``onInitialize``'s declarations and defaults)."""

    enabled: bool = True
    inflation_radius: float = 0.55
    cost_scaling_factor: float = 10.0
    inflate_unknown: bool = False
    inflate_around_unknown: bool = False
    custom_inscribed_radius: float = -1.0  # the new layer only (Lyrical, Rolling)


@dataclass(frozen=True)
class LayerSpec:
    name: str
    type: str
    inflation: Optional[InflationParams] = None  # for inflation types
    enabled: bool = True


@dataclass(frozen=True)
class CostmapParams:
    """The global costmap node's parameters that decide its costs on a static map."""

    plugins: tuple[LayerSpec, ...] = tuple(LayerSpec(n, t, InflationParams() if t == INFLATION else None)
                                           for n, t in DEFAULT_PLUGINS)
    robot_radius: float = 0.1
    footprint: str = "[]"
    footprint_padding: float = 0.01
    resolution: float = 0.1
    track_unknown_space: bool = False
    lethal_cost_threshold: int = 100
    trinary_costmap: bool = True
    unknown_cost_value: int = 255
    inscribed_obstacle_cost_value: int = 99
    use_maximum: bool = False
    filters: tuple[str, ...] = ()
    notes: tuple[str, ...] = ()


_KIND_NAMES = {bool: "a boolean", int: "an integer", float: "a double (write it with a decimal point)",
               str: "a string", list: "a list of strings"}


def _typed(where: str, key: str, value, kind):
    """An override as rclcpp accepts it: of the declared default's type only."""
    if kind is float:
        ok = isinstance(value, float)
    elif kind is int:
        ok = isinstance(value, int) and not isinstance(value, bool)
    elif kind is list:
        ok = isinstance(value, list) and all(isinstance(v, str) for v in value)
    else:
        ok = isinstance(value, kind)
    if not ok:
        raise NavfnInputError(f"{where}: '{key}' must be {_KIND_NAMES[kind]}, got {value!r} "
                              f"(Nav2 refuses a parameter of another type)")
    if kind is float and not math.isfinite(value):
        raise NavfnInputError(f"{where}: '{key}' must be finite, got {value!r}")
    if kind is int and not -2**63 <= value < 2**63:
        raise NavfnInputError(f"{where}: '{key}' {value} does not fit the int64 of a ROS parameter")
    return value


def _get(p: Mapping, where: str, key: str, kind, default, prefix: str = ""):
    """``p[key]`` checked against ``kind`` (named ``prefix + key`` in errors), else ``default``."""
    return _typed(where, prefix + key, p[key], kind) if key in p else default


def _non_negative(where: str, key: str, v: float) -> float:
    if v < 0.0:
        raise NavfnInputError(f"{where}: '{key}' must not be negative, got {v!r}")
    return v


def _inflation_params(sect: Mapping, name: str, where: str) -> InflationParams:
    d = InflationParams()
    g = lambda key, kind, default: _get(sect, where, key, kind, default, f"{name}.")  # noqa: E731
    return InflationParams(
        enabled=g("enabled", bool, d.enabled),
        inflation_radius=_non_negative(where, f"{name}.inflation_radius", g("inflation_radius", float, d.inflation_radius)),
        cost_scaling_factor=_non_negative(where, f"{name}.cost_scaling_factor",
                                          g("cost_scaling_factor", float, d.cost_scaling_factor)),
        inflate_unknown=g("inflate_unknown", bool, d.inflate_unknown),
        inflate_around_unknown=g("inflate_around_unknown", bool, d.inflate_around_unknown),
        custom_inscribed_radius=g("custom_inscribed_radius", float, d.custom_inscribed_radius),
    )


def _plugin_type(params: Mapping, name: str, where: str, default: Optional[str]) -> str:
    sect = params.get(name)
    if isinstance(sect, Mapping) and "plugin" in sect:
        return _typed(where, f"{name}.plugin", sect["plugin"], str)
    if default is not None:
        return default
    raise NavfnInputError(f"{where}: plugin '{name}' has no '{name}.plugin' parameter naming its type")


def _layer_specs(params: Mapping, where: str, distro: str) -> tuple[tuple[LayerSpec, ...], list[str]]:
    defaults = dict(DEFAULT_PLUGINS)
    names = _get(params, where, "plugins", list, [n for n, _ in DEFAULT_PLUGINS])
    use_defaults = names == [n for n, _ in DEFAULT_PLUGINS]  # Nav2 declares the default types only then
    specs, notes = [], []
    known = (STATIC, *inflation_types(distro), *SENSOR_LAYERS)
    for name in names:
        sect = params.get(name, {})
        if not isinstance(sect, Mapping):
            raise NavfnInputError(f"{where}: '{name}' must be a mapping of the plugin's parameters, got {sect!r}")
        ptype = _plugin_type(params, name, where, defaults.get(name) if use_defaults else None)
        if ptype in UNMODELLED:
            raise NavfnInputError(f"{where}: '{name}.plugin' {ptype} is not modelled")
        if ptype not in known:
            raise NavfnInputError(f"{where}: '{name}.plugin' {ptype!r} is not a costmap layer of Nav2 {distro} "
                                  f"(known: {', '.join(known)})")
        enabled = _get(sect, where, "enabled", bool, True, f"{name}.")
        infl = _inflation_params(sect, name, where) if ptype in inflation_types(distro) else None
        if infl is not None and infl.custom_inscribed_radius >= 0.0 and not (
                ptype == INFLATION and distro_record(distro).distance_transform_inflation):
            notes.append(f"{name}: custom_inscribed_radius is not a parameter of this layer in {distro}; ignored")
            infl = InflationParams(**{**infl.__dict__, "custom_inscribed_radius": -1.0})
        static_keys = [k for k in ("track_unknown_space", "lethal_cost_threshold", "trinary_costmap",
                                   "unknown_cost_value", "use_maximum") if k in sect]
        if ptype == STATIC and static_keys:
            notes.append(f"{name}: {', '.join(static_keys)} in the plugin section are not read "
                         f"(the static layer reads the costmap node's own keys)")
        specs.append(LayerSpec(name, ptype, infl, enabled))
    return tuple(specs), notes


def costmap_params(params: Mapping, distro: str = DEFAULT, where: str = "global_costmap") -> CostmapParams:
    """:class:`CostmapParams` from a ``ros__parameters`` mapping, Nav2's code defaults where absent."""
    _check_distro(distro)
    if not isinstance(params, Mapping):
        raise NavfnInputError(f"{where}: ros__parameters must be a mapping, got {params!r}")
    d = CostmapParams()
    plugins, notes = _layer_specs(params, where, distro)
    g = lambda key, kind, default: _get(params, where, key, kind, default)  # noqa: E731
    out = CostmapParams(
        plugins=plugins,
        robot_radius=_non_negative(where, "robot_radius", g("robot_radius", float, d.robot_radius)),
        footprint=g("footprint", str, d.footprint),
        footprint_padding=g("footprint_padding", float, d.footprint_padding),
        resolution=g("resolution", float, d.resolution),
        track_unknown_space=g("track_unknown_space", bool, d.track_unknown_space),
        lethal_cost_threshold=g("lethal_cost_threshold", int, d.lethal_cost_threshold),
        trinary_costmap=g("trinary_costmap", bool, d.trinary_costmap),
        unknown_cost_value=g("unknown_cost_value", int, d.unknown_cost_value),
        inscribed_obstacle_cost_value=g("inscribed_obstacle_cost_value", int, d.inscribed_obstacle_cost_value),
        use_maximum=g("use_maximum", bool, d.use_maximum),
        filters=tuple(g("filters", list, [])),
        notes=tuple(notes),
    )
    if out.resolution <= 0.0:
        raise NavfnInputError(f"{where}: 'resolution' must be positive, got {out.resolution!r}")
    if not 0 <= out.unknown_cost_value <= 255:
        raise NavfnInputError(f"{where}: 'unknown_cost_value' must be in 0..255, got {out.unknown_cost_value!r}")
    robot_footprint(out.robot_radius, out.footprint, out.footprint_padding)  # a bad footprint string fails here
    return out


def _section(doc: Mapping, node: str, path) -> Mapping:
    """``<node>: <node>: ros__parameters:`` (namespace and node), or ``<node>: ros__parameters:``."""
    for outer in (node, f"/{node}"):
        sect = doc.get(outer)
        if not isinstance(sect, Mapping):
            continue
        for inner in (sect.get(node), sect.get(f"/{node}"), sect):
            if isinstance(inner, Mapping) and isinstance(inner.get("ros__parameters"), Mapping):
                return inner["ros__parameters"]
    raise NavfnInputError(f"{path}: no '{node}: {node}: ros__parameters' section")


def load_costmap_params(path, distro: str = DEFAULT, node: str = "global_costmap") -> CostmapParams:
    """Read a Nav2 params YAML's global costmap section; every problem raises NavfnInputError."""
    p = Path(path)
    doc = load_params_yaml(p)
    return costmap_params(_section(doc, node, p), distro, where=f"{p}: {node}")


def bringup_params(distro: str = DEFAULT) -> CostmapParams:
    """nav2_bringup's shipped global costmap (``nav2_params.yaml``) for ``distro``, static and
    inflation layers as they are there (robot_radius 0.22, resolution 0.05, track_unknown_space
    true, cost_scaling_factor 3.0, inflation_radius 0.55 in Humble and Iron, else 0.7; the
    keepout and speed filters from Kilted on, which are not modelled)."""
    record = distro_record(distro)
    radius = record.bringup_inflation_radius
    return costmap_params({
        "robot_radius": 0.22, "resolution": 0.05, "track_unknown_space": True,
        "plugins": ["static_layer", "obstacle_layer", "inflation_layer"],
        "static_layer": {"plugin": STATIC, "map_subscribe_transient_local": True},
        "obstacle_layer": {"plugin": SENSOR_LAYERS[0]},
        "inflation_layer": {"plugin": INFLATION, "cost_scaling_factor": 3.0, "inflation_radius": radius},
        **({"filters": ["keepout_filter", "speed_filter"]} if record.bringup_filters else {}),
    }, distro, where=f"nav2_bringup ({distro})")


# ------------------------------------------------------------------------ the costmap
@dataclass
class GlobalCostmap:
    """The global costmap after one full update; arrays are (height, width), row 0 = grid row 0 (bottom)."""

    static: np.ndarray  # uint8, the static layer's costs (a costmap array given as source, copied)
    costmap: np.ndarray  # uint8, the master grid after every modelled layer
    resolution: float  # double, as the costmap holds it
    origin: tuple[float, float]
    distro: str
    inscribed_radius: float
    circumscribed_radius: float
    layers_run: tuple[str, ...]  # "name (type: static|current|legacy)" in order
    notes: tuple[str, ...] = field(default_factory=tuple)


def _check_distro(distro: str) -> None:
    distro_record(distro)


def as_int(v: int) -> int:
    """An int64 parameter read into an ``int`` (the low 32 bits, two's complement)."""
    return ((int(v) + 2**31) % 2**32) - 2**31


def as_unsigned_char(v: int) -> int:
    """An int64 parameter read into an ``unsigned char`` (modulo 256)."""
    return int(v) % 256


def _static_costs(source, params: CostmapParams, distro: str) -> np.ndarray:
    """The static layer's costs: its parameters as ``StaticLayer::getParameters`` holds them
    (``lethal_cost_threshold`` read into an int, then clamped; ``unknown_cost_value`` and
    ``inscribed_obstacle_cost_value`` into unsigned chars), then ``interpretValue`` per cell."""
    if isinstance(source, MapServerMap):
        inscribed = as_unsigned_char(params.inscribed_obstacle_cost_value) if distro_record(distro).inscribed_cost is not None else None
        return static_layer_costs(source.occupancy, track_unknown_space=params.track_unknown_space,
                                  lethal_threshold=as_int(params.lethal_cost_threshold),
                                  trinary_costmap=params.trinary_costmap,
                                  unknown_cost_value=as_unsigned_char(params.unknown_cost_value),
                                  inscribed_cost_value=inscribed)
    a = np.asarray(source)
    if a.ndim != 2 or a.dtype != np.uint8 or a.size == 0:
        raise NavfnInputError(f"costmap must be a non-empty 2-D uint8 array, got {a.dtype} with shape {a.shape}")
    return a.copy()


def _apply_static(master: np.ndarray, static: np.ndarray, use_maximum: bool) -> None:
    """``StaticLayer::updateCosts`` on a non-rolling costmap: ``updateWithTrueOverwrite``, or
    ``updateWithMax`` (skip the layer's unknown cells; an unknown or lower master cell takes the value)."""
    if not use_maximum:
        master[...] = static
        return
    take = (static != NO_INFORMATION) & ((master == NO_INFORMATION) | (master < static))
    master[take] = static[take]


def build_global_costmap(
    source: Union[MapServerMap, np.ndarray],
    params: Optional[CostmapParams] = None,
    distro: Optional[str] = None,
    resolution: Optional[float] = None,
    origin: tuple[float, float] = (0.0, 0.0),
    sqrt: str = "eigen-sse-amd",
    arith: LayersArithmetic = LAYERS_X86_64,
) -> GlobalCostmap:
    """The global costmap's costs after one full update on a static map, in the arithmetic of
    the layers build ``arith`` (x86-64's by default).

    ``source``: a :class:`MapServerMap` (its occupancy goes through the static layer with
    ``params``; resolution and origin are the map's) or a uint8 costmap array taken as the
    static layer's output (resolution: ``resolution`` if given, else ``params.resolution``).
    ``params`` default: :class:`CostmapParams` (Nav2's code defaults); see
    :func:`bringup_params`.  ``distro`` default: the map's, else ``"rolling"``.  ``sqrt``: how
    the distance-transform layer takes its square root (:func:`~.inflation.matrix_sqrt`).
    """
    params = params if params is not None else CostmapParams()
    distro = distro or (source.distro if isinstance(source, MapServerMap) else DEFAULT)
    _check_distro(distro)
    static = _static_costs(source, params, distro)
    if isinstance(source, MapServerMap):
        res, org = source.costmap_resolution, (source.origin[0], source.origin[1])
    else:
        res, org = float(resolution if resolution is not None else params.resolution), origin
    fp = robot_footprint(params.robot_radius, params.footprint, params.footprint_padding, arith=arith)
    master = np.full(static.shape, NO_INFORMATION if params.track_unknown_space else FREE_SPACE, np.uint8)
    ran, notes = [], list(params.notes)
    for layer in params.plugins:
        ran.append(_run_layer(layer, master, static, params, distro, res, fp.inscribed_radius, notes, sqrt, arith))
    notes += [f"filter '{f}' not modelled (needs a filter mask); skipped" for f in params.filters]
    return GlobalCostmap(static, master, res, org, distro, fp.inscribed_radius, fp.circumscribed_radius,
                         tuple(r for r in ran if r), tuple(notes))


def _run_layer(layer: LayerSpec, master, static, params: CostmapParams, distro: str, res: float,
               inscribed: float, notes: list, sqrt: str = "eigen-sse-amd",
               arith: LayersArithmetic = LAYERS_X86_64) -> Optional[str]:
    if layer.type in SENSOR_LAYERS:
        notes.append(f"{layer.name} ({layer.type}) needs sensor data; skipped")
        return None
    if not layer.enabled or (layer.inflation is not None and not layer.inflation.enabled):
        notes.append(f"{layer.name} is disabled")
        return None
    if layer.type == STATIC:
        _apply_static(master, static, params.use_maximum)
        return f"{layer.name} (static)"
    kind = inflation_types(distro).get(layer.type)
    if kind is None:
        raise NavfnInputError(f"'{layer.name}.plugin' {layer.type} does not exist in Nav2 {distro}")
    ip = layer.inflation or InflationParams()
    radius = ip.custom_inscribed_radius if ip.custom_inscribed_radius >= 0.0 else inscribed
    args = (master, res, radius, ip.inflation_radius, ip.cost_scaling_factor, ip.inflate_unknown,
            ip.inflate_around_unknown)
    master[...] = inflate_current(*args, sqrt=sqrt, arith=arith) if kind == "current" else inflate_legacy(*args)
    return f"{layer.name} ({kind})"
