"""What ``diagnose`` reads: the map and its global costmap, the plugin's parameters, the goals.

The costmap: the map's static layer, then, when a params file has a ``global_costmap``
section, its layers as :func:`navfn_smt.nav2.costmap.build_global_costmap` runs them
(static and inflation; sensor layers skipped).  Without a params file, or without that
section, the static layer alone (nav2_bringup's ``track_unknown_space: true``).
"""

from __future__ import annotations

import json
import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import Optional

from ..errors import NavfnInputError
from ..maps.mapserver import DEFAULT_DISTRO, MapServerMap, load_map_yaml
from ..nav2.params import PlannerParams, planner_params
from ..nav2.plugin import Costmap, Pose, check_pose, costmap_from_map


@dataclass
class DiagnoseSetup:
    map: MapServerMap
    costmap: Costmap  # the master costmap the plugin plans on
    params: PlannerParams
    layers: list = field(default_factory=list)  # the costmap layers that ran, in order
    notes: list = field(default_factory=list)


def load_inputs(map_yaml, params_file=None, distro: str = DEFAULT_DISTRO, allow_outside: bool = False) -> DiagnoseSetup:
    """Map + optional params file -> the costmap and the plugin's parameters."""
    if params_file is not None and not Path(params_file).is_file():
        raise NavfnInputError(f"{params_file}: no such params file")
    params = planner_params(params_file) if params_file else PlannerParams()
    m = load_map_yaml(Path(map_yaml), allow_outside, distro=distro)
    if params_file is None:
        return DiagnoseSetup(m, costmap_from_map(m), params, ["static_layer"],
                             ["no params file: Nav2's default planner parameters, static layer only"])
    try:
        from ..nav2 import costmap as layers
    except ImportError:
        layers = None
    if layers is None or not all(hasattr(layers, f) for f in ("load_costmap_params", "build_global_costmap")):
        return DiagnoseSetup(m, costmap_from_map(m), params, ["static_layer"],
                             ["global costmap layers not available: static layer only"])
    try:
        cp = layers.load_costmap_params(params_file, distro)
    except NavfnInputError as e:
        if "no 'global_costmap" not in str(e):
            raise
        return DiagnoseSetup(m, costmap_from_map(m), params, ["static_layer"],
                             [f"{params_file} has no global_costmap section: static layer only"])
    gc = layers.build_global_costmap(m, cp, distro)
    return DiagnoseSetup(m, costmap_from_map(m, gc.costmap), params, list(gc.layers_run), list(gc.notes))


def parse_goals(path) -> list[Pose]:
    """A batch of goals: a YAML or JSON list (of ``[x, y]``, ``[x, y, yaw]`` or mappings with
    x, y and optionally yaw), or plain text with one ``x y [yaw]`` a line (``#`` comments)."""
    p = Path(path)
    try:
        text = p.read_text()
    except FileNotFoundError:
        raise NavfnInputError(f"{path}: no such goals file") from None
    except (OSError, UnicodeDecodeError) as e:
        raise NavfnInputError(f"{path}: cannot read goals ({e})") from None
    items = _structured(p, text)
    goals = []
    if items is None:
        for n, line in enumerate(text.splitlines(), 1):
            line = line.split("#", 1)[0].strip()
            if not line:
                continue
            try:
                vals = [float(v) for v in line.replace(",", " ").split()]
            except ValueError:
                raise NavfnInputError(f"{path}:{n}: a goal is 'x y [yaw]', got {line!r}") from None
            goals.append(_goal(f"{path}:{n}", vals))
    else:
        for n, it in enumerate(items):
            if isinstance(it, dict):
                if not {"x", "y"} <= set(it):
                    raise NavfnInputError(f"{path}: goal {n} needs keys x and y, got {sorted(it)}")
                it = [it["x"], it["y"]] + ([it["yaw"]] if it.get("yaw") is not None else [])
            if not isinstance(it, (list, tuple)) or not all(isinstance(v, (int, float)) and not isinstance(v, bool)
                                                             for v in it):
                raise NavfnInputError(f"{path}: goal {n} must be [x, y] or [x, y, yaw], got {it!r}")
            goals.append(_goal(f"{path}: goal {n}", [float(v) for v in it]))
    if not goals:
        raise NavfnInputError(f"{path}: no goals")
    return goals


def _structured(p: Path, text: str) -> Optional[list]:
    s = text.lstrip()
    if not (s.startswith("[") or s.startswith("-") or p.suffix.lower() in (".yaml", ".yml", ".json")):
        return None
    try:
        if p.suffix.lower() == ".json" or s.startswith("["):
            try:
                doc = json.loads(text)
            except json.JSONDecodeError:
                import yaml

                doc = yaml.safe_load(text)
        else:
            import yaml

            doc = yaml.safe_load(text)
    except Exception as e:  # yaml's errors are many classes
        raise NavfnInputError(f"{p}: malformed goals file ({str(e).splitlines()[0]})") from None
    if isinstance(doc, dict) and "goals" in doc:
        doc = doc["goals"]
    if not isinstance(doc, list):
        raise NavfnInputError(f"{p}: goals must be a list")
    return doc


def _goal(where: str, vals: list) -> Pose:
    if len(vals) not in (2, 3) or not all(math.isfinite(v) for v in vals):
        raise NavfnInputError(f"{where}: a goal is x y [yaw] with finite numbers, got {vals}")
    return Pose.from_yaw(*vals)


def pose_arg(what: str, values) -> Pose:
    return check_pose(what, values)
