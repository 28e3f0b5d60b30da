"""The shape of the fix's paths beside NavFn's own: what a maintainer asks of a fallback path.

For every case of a suite, both modes, NavFn as shipped and with the fix run on the JIT backend
(held bit-exact to the C++ by the difftest).  The paths fall in three groups:

- ``gradient``: the paths NavFn as shipped returns (its gradient paths), the baseline;
- ``fix: propagate on``: cases the original fails and the fix plans by propagating on, the path
  then NavFn's own gradient path;
- ``fix: descent``: cases where the fix's descent gives the path (cell centres, 4-connected).

Measures, in cells (NavFn's path points are in cell units):

- length against the grid optimum: the shortest 8-connected path over passable cells from the
  start's cell to the goal's (a diagonal step only between two passable side cells), which no
  path through the passable cells can beat by more than the half cells at its ends;
- point spacing: the distances between consecutive points (NavFn's gradient steps half a cell);
- heading change: the sum of the turns between consecutive segments, per cell of length;
- the final heading, which Nav2's ``use_final_approach_orientation`` gives the goal pose (the
  direction of the last two points): how often it is one of the four axis directions.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import dijkstra

from ..spec.constants import COST_OBS, POT_HIGH

GROUPS = ("gradient", "fix: propagate on", "fix: descent")


def grid_distances(costs: np.ndarray, goals) -> np.ndarray:
    """The 8-connected shortest distance over passable cells from each goal cell to every cell:
    ``(len(goals), ny * nx)``, inf where unreachable."""
    ny, nx = costs.shape
    free = costs < COST_OBS
    y, x = np.mgrid[0:ny, 0:nx]
    rows, cols, w = [], [], []
    for dy, dx in ((0, 1), (1, 0), (1, 1), (1, -1)):
        y2, x2 = y + dy, x + dx
        inside = (y2 < ny) & (x2 >= 0) & (x2 < nx)
        ya, xa, yb, xb = y[inside], x[inside], y2[inside], x2[inside]
        ok = free[ya, xa] & free[yb, xb]
        if dx and dy:  # a diagonal only between two passable side cells
            ok &= free[yb, xa] & free[ya, xb]
        rows.append(ya[ok] * nx + xa[ok])
        cols.append(yb[ok] * nx + xb[ok])
        w.append(np.full(int(ok.sum()), math.sqrt(2.0) if dx and dy else 1.0))
    r, c, ww = np.concatenate(rows), np.concatenate(cols), np.concatenate(w)
    graph = coo_matrix((np.concatenate([ww, ww]), (np.concatenate([r, c]), np.concatenate([c, r]))),
                       shape=(ny * nx, ny * nx)).tocsr()
    return dijkstra(graph, indices=[gy * nx + gx for gx, gy in goals])


@dataclass
class PathShape:
    """One path's measures."""

    length: float
    optimum: float
    spacing_mean: float
    spacing_median: float
    spacing_max: float
    turn_per_cell: float
    final_axis: bool


def shape_of(path: np.ndarray, optimum: float) -> PathShape:
    p = np.asarray(path, np.float64)
    seg = np.diff(p, axis=0)
    d = np.hypot(seg[:, 0], seg[:, 1])
    moving = seg[d > 0]
    length = float(d.sum())
    heading = np.arctan2(moving[:, 1], moving[:, 0])
    turns = np.abs((np.diff(heading) + math.pi) % (2 * math.pi) - math.pi)
    last = heading[-1] if len(heading) else 0.0
    axis = min(abs((last / (math.pi / 2)) - round(last / (math.pi / 2))), 1.0) < 1e-6
    return PathShape(length, optimum, float(d.mean()) if len(d) else 0.0, float(np.median(d)) if len(d) else 0.0,
                     float(d.max()) if len(d) else 0.0,
                     float(turns.sum()) / length if length > 0 else 0.0, bool(axis))


@dataclass
class GroupSummary:
    """The measures of one group's paths."""

    paths: list = field(default_factory=list)

    def row(self) -> dict:
        if not self.paths:
            return {"paths": 0}
        ratio = np.array([s.length / s.optimum for s in self.paths if s.optimum > 0])
        return {
            "paths": len(self.paths),
            "length_over_optimum": {"median": float(np.median(ratio)), "p95": float(np.percentile(ratio, 95)),
                                    "max": float(ratio.max())} if len(ratio) else None,
            "spacing": {"mean": float(np.mean([s.spacing_mean for s in self.paths])),
                        "median": float(np.median([s.spacing_median for s in self.paths])),
                        "max": float(max(s.spacing_max for s in self.paths))},
            "turn_per_cell_median": float(np.median([s.turn_per_cell for s in self.paths])),
            "final_heading_on_an_axis": float(np.mean([s.final_axis for s in self.paths])),
        }


def measure_suite(maps, modes=("astar", "dijkstra"), backend: str = "jit") -> dict:
    """Every case of the suite maps ``maps`` (:class:`~navfn_smt.maps.suite.SuiteMap`), in each
    mode, as shipped and with the fix: the groups' summaries and how many cases fall in each."""
    from ..backends import EXIT_CODES, get_backend
    from ..spec.extraction import ExtractionExit
    from ..under_test import FIXED

    groups = {g: GroupSummary() for g in GROUPS}
    near = EXIT_CODES.index(ExtractionExit.NEAR_GOAL)
    counts = {"cases": 0, "original_fails": 0, "fixed_fails_too": 0, "fixed_fails_from_a_reached_start": 0}
    original, fixed = get_backend(backend), get_backend(backend, FIXED)
    for sm in maps:
        cases = np.asarray(sm.cases, dtype=np.int64).reshape(-1, 4)
        goals = sorted({(int(gx), int(gy)) for gx, gy in cases[:, 2:4].tolist()})
        where = {g: i for i, g in enumerate(goals)}
        dist = grid_distances(sm.costs, goals)
        ny, nx = sm.costs.shape
        plain, patched = original.prepare(sm.costs), fixed.prepare(sm.costs)
        for mode in modes:
            astar = mode == "astar"
            cols = plain.run_batch(cases, astar)
            off = cols["path_offsets"]
            for i, (sx, sy, gx, gy) in enumerate(cases.tolist()):
                counts["cases"] += 1
                opt = float(dist[where[gx, gy], sy * nx + sx])
                if cols["exit"][i] == near:
                    path = cols["path"][off[i]:off[i + 1]]
                    groups["gradient"].paths.append(shape_of(path, opt))
                    continue
                counts["original_fails"] += 1
                r = patched.run((sx, sy), (gx, gy), astar, trace=False)
                if not len(r.path):
                    counts["fixed_fails_too"] += 1
                    counts["fixed_fails_from_a_reached_start"] += bool(r.start_potential < POT_HIGH)
                    continue
                group = "fix: descent" if "descent" in r.extra.get("fix", []) else "fix: propagate on"
                groups[group].paths.append(shape_of(r.path, opt))
    return {"counts": counts, "groups": {g: s.row() for g, s in groups.items()}}
