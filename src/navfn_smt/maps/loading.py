"""Any map a command names, loaded as NavFn costs: a suite map directory, a map_server
YAML map, or a raw map file of a given size."""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path
from typing import Optional

import numpy as np

from ..errors import NavfnInputError
from ..distros import DEFAULT


def is_yaml(path) -> bool:
    """True for a map_server map (``.yaml`` or ``.yml``)."""
    return Path(path).suffix.lower() in (".yaml", ".yml")


def load_costs(path, size: Optional[tuple[int, int]] = None, allow_outside: bool = False,
               distro: str = DEFAULT) -> np.ndarray:
    """The NavFn costs of a map directory, a map_server YAML, or a raw map file of ``size`` (W, H)."""
    from .suite import load_map, read_map_bytes

    m = Path(path)
    if is_yaml(m):
        if size:
            raise NavfnInputError(f"{m}: --size is for a raw map file; a map_server map has its own size")
        from ..nav2.mapserver import load_map_yaml

        return load_map_yaml(m, allow_outside, distro=distro).navfn_costs
    if m.is_dir():
        if size:
            raise NavfnInputError(f"{m}: --size is for a raw map file; a map directory has its size in test.txt")
        return load_map(m).costs
    if not m.exists():
        raise NavfnInputError(f"{m}: no such map file or directory")
    if not size:
        raise NavfnInputError(f"{m}: a raw map file needs --size W H")
    w, h = size
    if w < 3 or h < 3:
        raise NavfnInputError(f"--size {w} {h}: NavFn needs at least 3x3 cells")
    return np.asarray(read_map_bytes(m, w, h))


@dataclass
class CaseMap:
    """A map with a name and its cases (none for a map_server map)."""

    name: str
    costs: np.ndarray
    cases: list = field(default_factory=list)


def load_case_map(path, allow_outside: bool = False) -> CaseMap:
    """A suite map directory with its cases, or a map_server YAML map without any."""
    from .suite import load_map

    m = Path(path)
    if is_yaml(m):
        from ..nav2.mapserver import load_map_yaml

        return CaseMap(m.stem, load_map_yaml(m, allow_outside).navfn_costs)
    if not m.is_dir():
        raise NavfnInputError(f"{m}: not a suite map directory or map_server YAML")
    smap = load_map(m)
    return CaseMap(smap.name, smap.costs, smap.cases)
