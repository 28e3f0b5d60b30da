"""The NavFn planner plugin's parameters, read from a Nav2 params file as the planner server does.

``nav2_navfn_planner/src/parameter_handler.cpp`` declares five parameters under the plugin's
name, each with a default whose type fixes the parameter's type (rclcpp refuses an override of
another type, so ``tolerance: 1`` is an error in Nav2, not 1.0):

    tolerance 0.5 (double), use_astar false, max_cycles_factor 4 (int, from Nav2 PR #6308),
    allow_unknown true, use_final_approach_orientation false.

The plugin's name comes from ``planner_server``'s ``planner_plugins`` (default
``["GridBased"]``); its section's ``plugin`` names the type, ``nav2_navfn_planner::NavfnPlanner``
(``nav2_navfn_planner/NavfnPlanner`` in older files).
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Optional

from ..errors import NavfnInputError
from ..spec.planner import AS_SHIPPED, Fix

NAVFN_TYPES = ("nav2_navfn_planner::NavfnPlanner", "nav2_navfn_planner/NavfnPlanner")
DEFAULT_PLUGINS = ("GridBased",)


@dataclass(frozen=True)
class PlannerParams:
    """``nav2_navfn_planner::Parameters`` with Nav2's defaults."""

    tolerance: float = 0.5
    use_astar: bool = False
    allow_unknown: bool = True
    max_cycles_factor: int = 4
    use_final_approach_orientation: bool = False
    plugin: str = "GridBased"  # the plugin's name in planner_server (where the values were read)
    distro: str = "rolling"  # whose navfn_planner.cpp reads them (see distros.py)
    fix: Fix = AS_SHIPPED  # NavFn as shipped, or with a fix (navfn_smt.spec.fixes)


_TYPES = {"tolerance": float, "use_astar": bool, "allow_unknown": bool, "max_cycles_factor": int,
          "use_final_approach_orientation": bool}


def load_params_yaml(path) -> dict:
    """A params file as a mapping; unreadable or malformed files raise NavfnInputError."""
    from .mapserver import load_yaml

    p = Path(path)
    try:
        doc = load_yaml(p)
    except NavfnInputError as e:
        raise NavfnInputError(str(e).replace("map YAML file", "params file")) from None
    if not isinstance(doc, dict):
        raise NavfnInputError(f"{p}: a Nav2 params file must be a mapping of node names to parameters")
    return doc


def node_parameters(doc: dict, node: str, path) -> Optional[dict]:
    """``<node>: ros__parameters:`` at the top level or under a namespace key (``/**``, ``/ns``)."""
    for key in (node, f"/{node}"):
        if key in doc:
            sect = doc[key]
            params = sect.get("ros__parameters") if isinstance(sect, dict) else None
            if not isinstance(params, dict):
                raise NavfnInputError(f"{path}: '{key}' has no 'ros__parameters' mapping")
            return params
    for key, sect in doc.items():
        if isinstance(key, str) and key.startswith("/") and isinstance(sect, dict) and node in sect:
            return node_parameters(sect, node, path)
    return None


def _typed(path, name: str, key: str, value, kind):
    """An override of a declared parameter: rclcpp accepts only the declared type."""
    ok = (isinstance(value, bool) if kind is bool else
          isinstance(value, int) and not isinstance(value, bool) if kind is int else
          isinstance(value, float))
    if not ok:
        want = {bool: "a boolean", int: "an integer", float: "a double (write it with a decimal point)"}[kind]
        raise NavfnInputError(f"{path}: '{name}.{key}' must be {want}, got {value!r} "
                              f"(Nav2 refuses a parameter of another type)")
    if kind is float and value != value:
        raise NavfnInputError(f"{path}: '{name}.{key}' is not a number")
    if kind is int and not -2**63 <= value < 2**63:
        raise NavfnInputError(f"{path}: '{name}.{key}' {value} does not fit the int64 of a ROS parameter")
    return value


def planner_params(path, plugin: Optional[str] = None) -> PlannerParams:
    """The NavFn plugin's parameters from a params file (``planner_server`` section).

    ``plugin`` picks a plugin name when several are configured; by default the first one whose
    type is NavFn's.  A file without a ``planner_server`` section gives Nav2's defaults.
    """
    doc = load_params_yaml(path)
    params = node_parameters(doc, "planner_server", path)
    if params is None:
        return PlannerParams()
    names = params.get("planner_plugins", list(DEFAULT_PLUGINS))
    if not isinstance(names, list) or not all(isinstance(n, str) for n in names):
        raise NavfnInputError(f"{path}: 'planner_server.planner_plugins' must be a list of names, got {names!r}")
    def plugin_type(n):
        sect = params.get(n)
        kind = sect.get("plugin") if isinstance(sect, dict) else None
        # planner_server's default plugin "GridBased" is NavFn when its type is not given
        return kind if kind is not None or names != list(DEFAULT_PLUGINS) else NAVFN_TYPES[0]

    navfn = [n for n in names if plugin_type(n) in NAVFN_TYPES]
    if plugin is not None:
        if plugin not in names:
            raise NavfnInputError(f"{path}: no planner plugin named {plugin!r} (planner_plugins: {names})")
        if plugin not in navfn:
            raise NavfnInputError(f"{path}: planner plugin {plugin!r} is not a NavfnPlanner")
        name = plugin
    elif navfn:
        name = navfn[0]
    else:
        raise NavfnInputError(f"{path}: no planner plugin of type nav2_navfn_planner::NavfnPlanner "
                              f"(planner_plugins: {names})")
    sect = params.get(name)
    if sect is None:
        sect = {}
    if not isinstance(sect, dict):
        raise NavfnInputError(f"{path}: 'planner_server.{name}' must be a mapping of the plugin's parameters, "
                              f"got {sect!r}")
    values = {key: _typed(path, name, key, sect[key], kind) for key, kind in _TYPES.items() if key in sect}
    return PlannerParams(plugin=name, **values)
