"""A Nav2 planning set-up from files: the map, the global costmap built on it, the plugin's
parameters; what ``plan --world`` and ``diagnose`` start from.

The global costmap is the static layer of the map (:mod:`navfn_smt.maps.mapserver`), then the
params file's inflation layer when :mod:`.costmap` provides one; without a params file, the
static layer alone with Nav2's defaults.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path
from typing import Optional

from ..errors import NavfnInputError
from ..maps.mapserver import DEFAULT_DISTRO, MapServerMap, load_map_yaml
from .params import PlannerParams, planner_params
from .plugin import Costmap, costmap_from_map


# The plugin is Rolling's navfn_planner.cpp; its max_cycles_factor parameter exists only there
# (earlier distributions give calcPath 4 * max(size_x, size_y) cycles, the factor's default).
CYCLES_FACTOR_DISTROS = ("rolling",)


@dataclass
class Setup:
    map: MapServerMap
    costmap: Costmap  # the master costmap the plugin plans on
    params: PlannerParams
    layers: list = field(default_factory=list)  # the layers that ran, in order
    notes: list = field(default_factory=list)  # what was read or left out, for the report


def load_setup(map_yaml, params_file=None, distro: str = DEFAULT_DISTRO, allow_outside: bool = False,
               overrides: Optional[dict] = None) -> Setup:
    """Map + params file (optional) -> :class:`Setup`; ``overrides`` replace plugin parameters."""
    from dataclasses import replace

    params = planner_params(params_file) if params_file else PlannerParams()
    if overrides:
        params = replace(params, **{k: v for k, v in overrides.items() if v is not None})
    distro_notes = [] if distro == "rolling" else [
        f"the planner plugin is Rolling's navfn_planner.cpp (map loading and costmap layers follow {distro})"]
    if distro not in CYCLES_FACTOR_DISTROS and params.max_cycles_factor != 4:
        distro_notes.append(f"max_cycles_factor {params.max_cycles_factor} ignored: {distro} has no such parameter "
                            f"(Nav2 PR #6308, August 2026); calcPath gets 4 * max(size_x, size_y) cycles")
        params = replace(params, max_cycles_factor=4)
    costmap_params = None
    try:
        from . import costmap as layers
    except ImportError:  # the inflation layers are optional to this module
        layers = None
    if layers is not None and not all(hasattr(layers, f) for f in ("costmap_params", "static_layer_kwargs",
                                                                      "build_global_costmap")):
        layers = None
    if layers is not None and params_file:
        costmap_params = layers.costmap_params(params_file)
    m = load_map_yaml(Path(map_yaml), allow_outside, distro=distro,
                      **(layers.static_layer_kwargs(costmap_params) if costmap_params is not None else {}))
    if costmap_params is None:
        return Setup(m, costmap_from_map(m), params, ["static_layer"], distro_notes + (
            [] if params_file else ["no params file: Nav2's default plugin parameters, static layer only"]))
    gc = layers.build_global_costmap(m, costmap_params, distro)
    return Setup(m, costmap_from_map(m, gc.master), params, list(gc.layers), distro_notes + list(gc.notes))


def check_params_file(path) -> None:
    if path is not None and not Path(path).is_file():
        raise NavfnInputError(f"{path}: no such params file")
