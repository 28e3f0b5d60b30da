"""What differs between the Nav2 distributions the toolkit models: one record each.

Every field is checked against the C++ of the distributions whose sources are at hand (Humble,
Jazzy, Kilted, Lyrical, Rolling: the live plugin, costmap and map_server difftests,
``docs/oracle.md``); Iron, not among them, takes its neighbours' code.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Optional

from .errors import NavfnInputError


@dataclass(frozen=True)
class Distro:
    """One Nav2 distribution: the planner plugin's behaviour (``navfn_planner.cpp``), map_server's
    and the costmap layers' rules, nav2_bringup's global costmap."""

    name: str
    version: Optional[tuple]  # Nav2's (major, minor) on its branch; None: Rolling, the main branch
    checked: bool  # its sources are among the checked ones
    throws: bool  # createPlan checks both poses with Costmap2D::worldToMap and throws (Jazzy on)
    same_position_smoothing: bool  # smoothApproachToGoal's second branch (Jazzy on)
    cycles_factor: bool  # the max_cycles_factor parameter, and calcPath's WARN when its cycles run out
    map_io: str  # map_server's map_io generation: "current" (Jazzy 1.3.7, May 2025, on) or "legacy"
    inscribed_cost: Optional[int]  # StaticLayer's inscribed_obstacle_cost_value, where it has one
    distance_transform_inflation: bool  # InflationLayer is the distance-transform layer (Nav2 1.5.0 on)
    bringup_inflation_radius: float  # nav2_bringup's global costmap
    bringup_filters: bool  # nav2_bringup's keepout and speed filters (Kilted on; not modelled)

    @property
    def exhausted_warning(self) -> bool:
        """navfn.cpp's calcPath warns when it runs out of cycles (with max_cycles_factor)."""
        return self.cycles_factor


DISTROS = {d.name: d for d in (
    #      name       version  checked throws smooth factor map_io   inscr new_infl radius filters
    Distro("humble", (1, 1), True, False, False, False, "legacy", None, False, 0.55, False),
    Distro("iron", (1, 2), False, True, False, False, "legacy", None, False, 0.55, False),
    Distro("jazzy", (1, 3), True, True, True, False, "current", None, False, 0.7, False),
    Distro("kilted", (1, 4), True, True, True, False, "current", None, False, 0.7, True),
    Distro("lyrical", (1, 5), True, True, True, True, "current", 99, True, 0.7, True),
    Distro("rolling", None, True, True, True, True, "current", 99, True, 0.7, True),
)}
CHECKED = tuple(name for name, d in DISTROS.items() if d.checked)  # the five whose sources are at hand
DEFAULT = "rolling"


def distro(name: str) -> Distro:
    """The record of the distribution ``name``; a clear error for one not modelled."""
    if name not in DISTROS:
        raise NavfnInputError(f"unknown Nav2 distro {name!r} (choose from {', '.join(DISTROS)})")
    return DISTROS[name]
