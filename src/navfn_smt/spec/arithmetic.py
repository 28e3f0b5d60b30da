"""The arithmetic of a build: which multiply-adds the compiler fused, and how ``(int)`` converts.

The C++ standard lets a compiler contract ``a * b + c`` into one fused multiply-add (one
rounding instead of two), and leaves ``(int)`` of a float outside the int range undefined.
Compilers use both freedoms differently by target: GCC on x86-64 (SSE2) fuses nothing and its
``cvttss2si`` gives INT_MIN; GCC with ``-march=x86-64-v3`` and GCC on arm64 fuse every site
below, and arm64's ``fcvtzs`` saturates.  An :class:`Arithmetic` is that data, found from a
build (:mod:`navfn_smt.oracle.arithmetic`), never typed in; the kernels ask the numeric domain
``D.fuses(site)`` and ``D.to_int32`` converts as the domain's arithmetic says, so each kernel is
still stated once.

:data:`SITES` are the contractible expressions of NavFn's arithmetic, each with the source text
that names it in ``navfn.cpp`` (how the object code's fused lines are told apart).
"""

from __future__ import annotations

import re
from dataclasses import dataclass

from .libm import HYPOTS


# site -> (the C++, float or double, a pattern of its navfn.cpp line, lines expected in navfn.cpp)
SITES = {
    "cost_translation": ("setCostmap: COST_NEUTRAL + COST_FACTOR * v (double, truncated to int)",
                         r"COST_NEUTRAL\s*\+\s*COST_FACTOR\s*\*", 2),
    "quadratic": ("updateCell: -0.2301 * div * div + 0.5307 * div (double; the first product's "
                  "last multiplication fused with the sum)", r"-0\.2301\s*\*\s*\w+\s*\*", 2),
    "planar": ("updateCell: ta + hf * v (float)", r"ta\s*\+\s*hf\s*\*\s*v", 2),
    "bilinear": ("calcPath: (1.0 - t) * a + t * b (double; the left product fused, the float t * b added)",
                 r"\(1\.0\s*-\s*d[xy]\)\s*\*", 6),
    "path_step": ("calcPath: dx += x * ss, dy += y * ss (float)", r"d[xy]\s*\+=\s*[xy]\s*\*\s*ss", 2),
}
# how (int) of a float converts a NaN or a value outside the int range
CONVERSIONS = {
    "indefinite": "NaN and values out of range give INT_MIN (x86-64's cvttss2si, the 'integer indefinite')",
    "saturating": "values out of range clamp to INT_MIN or INT_MAX, NaN gives 0 (arm64's fcvtzs)",
}


@dataclass(frozen=True)
class Arithmetic:
    """The sites the build fused (a subset of :data:`SITES`) and its float-to-int conversion."""

    fused: frozenset = frozenset()
    conversion: str = "indefinite"

    def __post_init__(self):
        unknown = sorted(set(self.fused) - set(SITES))
        if unknown or self.conversion not in CONVERSIONS:
            raise ValueError(f"no such arithmetic: fused {sorted(self.fused)}, conversion {self.conversion!r}")

    def fuses(self, site: str) -> bool:
        return site in self.fused

    @property
    def name(self) -> str:
        """The known arithmetic's name (``x86-64``, ``x86-64-v3``, ``aarch64``), else a
        description of the data."""
        for name, a in KNOWN.items():
            if a == self:
                return name
        return f"fused[{'+'.join(sorted(self.fused)) or 'none'}]-{self.conversion}"

    @property
    def key(self) -> str:
        """A short identifier that differs for every distinct arithmetic (for compiled types)."""
        return "".join("1" if s in self.fused else "0" for s in SITES) + self.conversion[0]

    def as_dict(self) -> dict:
        return {"name": self.name, "fused": sorted(self.fused), "conversion": self.conversion}

    @staticmethod
    def from_dict(doc: dict) -> "Arithmetic":
        return Arithmetic(frozenset(doc.get("fused", ())), doc.get("conversion", "indefinite"))


X86_64 = Arithmetic()
KNOWN = {
    "x86-64": X86_64,
    "x86-64-v3": Arithmetic(frozenset(SITES), "indefinite"),
    "aarch64": Arithmetic(frozenset(SITES), "saturating"),
}


def site_of_line(text: str):
    """The site whose pattern a line of navfn.cpp matches, or None."""
    return next((s for s, (_, pattern, _) in SITES.items() if re.search(pattern, text)), None)


# The multiply-adds of the planner plugin's own code: navfn_planner.cpp and the headers it inlines
# (site -> (the C++, a pattern of its line, the file, whether its value is the same fused or not)).
# Costmap2D's own multiply-adds (mapToWorld, worldToMapEnforceBounds, updateOrigin) are in
# functions the plugin never calls (tests/test_arithmetic.py holds that against the sources).
PLUGIN_SITES = {
    "map_to_world": ("NavfnPlanner::mapToWorld: origin + m * resolution (double), each published position",
                     r"getOrigin[XY]\(\)\s*\+\s*m[xy]\s*\*", "navfn_planner.cpp", False),
    "squared_distance": ("squared_distance: dx * dx + dy * dy (double), the tolerance search and the smoothing",
                         r"dx\s*\*\s*dx\s*\+\s*dy\s*\*\s*dy", "navfn_planner.hpp", False),
    "yaw_quaternion": ("orientationAroundZAxis: setRPY(0, 0, yaw)'s products (double); every product with the "
                       "sine of the zero roll or pitch is an exact zero, so fused or not the quaternion is the same",
                       r"q\.[xyzw]\s*=\s*\w+\s*\*\s*\w+\s*\*\s*\w+\s*[-+]", "geometry_utils.hpp", True),
}


# The calls of squared_distance in navfn_planner.cpp (call -> a pattern of its line).  GCC
# inlines each call and may fuse either square in each copy: ``fma(dx, dx, dy * dy)`` (order
# "dx") or ``fma(dy, dy, dx * dx)`` (order "dy"), so a build's order is found per call.
SQUARED_CALLS = {
    "tolerance": r"sdist\s*=\s*squared_distance\(",
    "smooth_last": r"squared_distance\(\s*last_pose\.pose\s*,\s*second_to_last_pose",
    "smooth_goal": r"squared_distance\(\s*goal\s*,\s*second_to_last_pose",
    "same_position": r"squared_distance\(\s*last_pose\.pose\s*,\s*goal\s*\)",
}


def squared_call_of_line(text: str):
    """The call of squared_distance a line of navfn_planner.cpp makes, or None."""
    return next((c for c, pattern in SQUARED_CALLS.items() if re.search(pattern, text)), None)


def plugin_site_of_line(file_name: str, text: str):
    """The plugin site a line of ``file_name`` is, or None."""
    return next((s for s, (_, pattern, f, _) in PLUGIN_SITES.items()
                 if f == file_name and re.search(pattern, text)), None)


@dataclass(frozen=True)
class PluginArithmetic:
    """The arithmetic of a plugin build: NavFn's (:class:`Arithmetic`) and the plugin sites
    (:data:`PLUGIN_SITES`) its compiler fused."""

    navfn: Arithmetic = X86_64
    fused: frozenset = frozenset()
    dy_first: frozenset = frozenset()  # the calls (SQUARED_CALLS) whose fused square is dy's

    def __post_init__(self):
        unknown = sorted(set(self.fused) - set(PLUGIN_SITES)) + sorted(set(self.dy_first) - set(SQUARED_CALLS))
        if unknown:
            raise ValueError(f"no such plugin site or call: {unknown}")

    def fuses(self, site: str) -> bool:
        return site in self.fused

    def squared_order(self, call: str) -> str:
        """Which square the build fuses in the call ``call`` of squared_distance (when it fuses)."""
        if call not in SQUARED_CALLS:
            raise ValueError(f"no such call of squared_distance: {call}")
        return "dy" if call in self.dy_first else "dx"

    @property
    def name(self) -> str:
        plugin = "+".join(sorted(self.fused)) or "none"
        dy = f", fma(dy, dy, dx * dx) in {'+'.join(sorted(self.dy_first))}" if self.dy_first else ""
        return f"{self.navfn.name}, plugin fused[{plugin}]{dy}"


PLUGIN_X86_64 = PluginArithmetic()


# The multiply-adds of the costmap layers as the layers driver runs them (a static map, a
# footprint from a radius, no rolling window): site -> (the C++, a pattern of its line, the
# file, None where the model computes it as found, else why its value cannot change the layers'
# result).  The reasons are argued; the difftest of fused builds against the model tests them.
LAYER_SITES = {
    "distance_to_line": ("distanceToLine: dot = A * C + B * D, len_sq = C * C + D * D, xx = x0 + param * C, "
                         "yy = y0 + param * D (double): the footprint's inscribed radius",
                         r"(dot|len_sq)\s*=\s*\w+\s*\*\s*\w+\s*\+|(xx|yy)\s*=\s*[xy]0\s*\+\s*param\s*\*",
                         "costmap_math.cpp", None),
    "lut_index": ("InflationLayer::updateCosts: distance_cells * lut_precision + 0.5f (float), the cost table's "
                  "index (Lyrical, Rolling)", r"distance_cells\s*\*\s*lut_precision\s*\+", "inflation_layer.cpp", None),
    "map_to_world": ("Costmap2D::mapToWorld: origin + (m + 0.5) * resolution (double)",
                     r"w[xy]\s*=\s*origin_[xy]_\s*\+\s*\(m[xy]\s*\+\s*0\.5\)\s*\*", "costmap_2d.cpp",
                     "the static layer's bounds are cell centres, which worldToMapEnforceBounds floors to the same "
                     "cells fused or not"),
    "enforce_bounds": ("Costmap2D::worldToMapEnforceBounds: resolution * size + origin (double)",
                       r"w[xy]\s*>\s*resolution_\s*\*\s*size_[xy]_\s*\+\s*origin_[xy]_", "costmap_2d.cpp",
                       "compared with bounds half a cell beyond the map or at DBL_MAX: the same outcome fused or not"),
    "update_origin": ("Costmap2D::updateOrigin: origin + cell * resolution (double)",
                      r"new_grid_o[xy]\s*=\s*origin_[xy]_\s*\+\s*cell_o[xy]\s*\*", "costmap_2d.cpp",
                      "a rolling window's: the driver's costmap does not roll"),
    "rolling_origin": ("LayeredCostmap::updateMap: robot - size / 2 (double)",
                       r"new_origin_[xy]\s*=\s*robot_[xy]\s*-", "layered_costmap.cpp",
                       "a rolling window's: the driver's costmap does not roll"),
    "raytrace_line": ("Costmap2D::raytraceLine: x0 + dx_full / dist * min_length (double), a shortened start",
                      r"min_[xy]0\s*=\s*\(unsigned int\)\([xy]0\s*\+\s*d[xy]_full\s*/\s*dist\s*\*",
                      "costmap_2d.hpp", "sensor rays and the static layer's footprint clearing (off by default, and "
                      "the driver leaves it off): the driver runs neither"),
    "transform_footprint": ("transformFootprint: x + (fx * cos - fy * sin) (double)",
                            r"new_(x|y|pt\.[xy])\s*=\s*[xy]\s*\+\s*\(footprint_spec", "footprint.cpp",
                            "the driver transforms no footprint"),
}
# which product distanceToLine's two sums fuse, by a variable it multiplies: dot's A * C ("A")
# or B * D ("B"), len_sq's C * C ("C") or D * D ("D")
LAYER_ORDERS = {"dot": {"A": "A", "C": "A", "B": "B", "D": "B"}, "len_sq": {"C": "C", "D": "D"}}


def layer_site_of_line(file_name: str, text: str):
    """The layer site a line of ``file_name`` is, or None."""
    return next((s for s, (_, pattern, f, _) in LAYER_SITES.items() if f == file_name and re.search(pattern, text)),
                None)


@dataclass(frozen=True)
class LayersArithmetic:
    """The arithmetic of a costmap layers build: the modelled sites of :data:`LAYER_SITES` it
    fused, and which product each of distanceToLine's two sums rounds once (``dot``: ``"A"``
    for ``fma(A, C, B * D)``, ``"B"`` for ``fma(B, D, A * C)``; ``len_sq``: ``"C"`` or ``"D"``); and
    the kernel of its libm's ``hypot`` (``hypot``: one of :data:`~navfn_smt.spec.libm.HYPOTS`)."""

    fused: frozenset = frozenset()
    dot: str = "A"
    len_sq: str = "C"
    hypot: str = "glibc"

    def __post_init__(self):
        modelled = {s for s, v in LAYER_SITES.items() if v[3] is None}
        if (set(self.fused) - modelled or self.dot not in ("A", "B") or self.len_sq not in ("C", "D")
                or self.hypot not in HYPOTS):
            raise ValueError(f"no such layers arithmetic: fused {sorted(self.fused)}, dot {self.dot}, len_sq "
                             f"{self.len_sq}, hypot {self.hypot}")

    def fuses(self, site: str) -> bool:
        return site in self.fused

    @property
    def name(self) -> str:
        fused = "+".join(sorted(self.fused)) or "none"
        orders = f", fma({self.dot}...) and fma({self.len_sq}...)" if "distance_to_line" in self.fused else ""
        libm = f", hypot {self.hypot}" if self.hypot != "glibc" else ""
        return f"layers fused[{fused}]{orders}{libm}"


LAYERS_X86_64 = LayersArithmetic()
