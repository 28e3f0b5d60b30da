"""What ``diagnose`` reads: the map and its global costmap, the plugin's parameters, the goals.

The map, costmap and parameters are read as ``plan --world`` reads them
(:func:`navfn_smt.nav2.setup.load_setup`).
"""

from __future__ import annotations

import json
import math
from pathlib import Path
from typing import Optional

from ..errors import NavfnInputError
from ..distros import DEFAULT
from ..nav2.plugin import Pose, check_pose
from ..nav2.setup import Setup, check_params_file, load_setup
from ..spec.planner import AS_SHIPPED, Fix




def load_inputs(map_yaml, params_file=None, distro: str = DEFAULT, allow_outside: bool = False,
                resolution=None, origin=(0.0, 0.0), fix: Fix = AS_SHIPPED, layers_arith=None) -> Setup:
    """Map (or costmap file) + optional params file -> the costmap and the plugin's parameters
    (:func:`load_setup`), for NavFn as shipped or with a fix (``fix``), the layers computing
    in ``layers_arith`` (None: x86-64's)."""
    check_params_file(params_file)
    return load_setup(map_yaml, params_file, distro, allow_outside, {"fix": fix}, resolution=resolution,
                      origin=origin, layers_arith=layers_arith)


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
            try:
                vals = [float(v) for v in it]
            except OverflowError:
                raise NavfnInputError(f"{path}: goal {n} has a number too large for a double: {it!r}"[:300]) from None
            goals.append(_goal(f"{path}: goal {n}", vals))
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
    except Exception as e:  # yaml's errors are many classes (and RecursionError on deep nesting)
        first = (str(e).splitlines() or [type(e).__name__])[0]
        raise NavfnInputError(f"{p}: malformed goals file ({first})") from None
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
