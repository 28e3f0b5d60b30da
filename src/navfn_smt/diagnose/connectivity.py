"""Which cells NavFn's propagation can reach at all, and the obstacles that cut a goal off.

After ``setCostmap`` (and the lethal frame ``setupNavFn`` writes) propagation spreads
4-connected (``updateCell`` pushes left, right, up, down) through cells whose cost is below
COST_OBS (254); an obstacle cell never gets a potential.  So a cell gets a finite potential
only when it lies in the robot's 4-connected region of passable cells (the robot's cell is
NavFn's goal, cleared by ``clearRobotCell``).  When the goal's cell lies outside it, the
*cut* is the smallest set of obstacle cells whose clearing would join the two regions
(a 0-1 shortest path over the grid: passable cells cost 0, obstacle cells 1; the frame
stays lethal, setupNavFn rewrites it).
"""

from __future__ import annotations

from collections import deque
from dataclasses import dataclass, field

import numpy as np

from ..maps.regions import FOUR_NEIGHBOURS, regions
from ..spec.constants import COST_OBS
from ..spec.costs import add_border


@dataclass
class Connectivity:
    connected: bool  # the goal's cell is in the robot's region
    robot_region_cells: int
    goal_region_cells: int  # 0 when the goal's cell is itself an obstacle
    goal_cell_passable: bool
    cut: list = field(default_factory=list)  # [(x, y)] obstacle cells to clear, fewest first found
    goal_region_boundary: int = 0  # obstacle cells 4-adjacent to the goal's region


def connectivity(costs: np.ndarray, robot: tuple[int, int], goal: tuple[int, int]) -> Connectivity:
    """The regions of NavFn's internal ``costs`` (after setCostmap, (ny, nx)) around the robot's
    and the goal's cells."""
    framed = add_border(costs)
    passable = framed < COST_OBS
    labels = regions(framed)
    rl = int(labels[robot[1], robot[0]])
    gl = int(labels[goal[1], goal[0]])
    robot_cells = int((labels == rl).sum()) if rl else 0
    goal_cells = int((labels == gl).sum()) if gl else 0
    if rl and rl == gl:
        return Connectivity(True, robot_cells, goal_cells, True)
    boundary = 0
    if gl:
        from scipy import ndimage

        grown = ndimage.binary_dilation(labels == gl, structure=FOUR_NEIGHBOURS)
        boundary = int((grown & ~passable).sum())
    return Connectivity(False, robot_cells, goal_cells, bool(gl), _cut(framed, labels, rl, goal), boundary)


def _cut(framed: np.ndarray, labels: np.ndarray, robot_label: int, goal: tuple[int, int]) -> list:
    """The fewest obstacle cells on a 4-connected way from the robot's region to the goal's cell."""
    ny, nx = framed.shape
    obstacle = (framed >= COST_OBS).ravel()
    inf = np.iinfo(np.int64).max
    dist = np.full(nx * ny, inf, np.int64)
    prev = np.full(nx * ny, -1, np.int64)
    dq = deque()
    if robot_label:
        for i in np.flatnonzero(labels.ravel() == robot_label).tolist():
            dist[i] = 0
            dq.append(i)
    target = goal[1] * nx + goal[0]
    while dq:
        i = dq.popleft()
        if i == target:
            break
        x, y = i % nx, i // nx
        for j, ok in ((i - 1, x > 1), (i + 1, x < nx - 2), (i - nx, y > 1), (i + nx, y < ny - 2)):
            if not ok:  # the frame stays lethal whatever the map says
                continue
            w = 1 if obstacle[j] else 0
            d = dist[i] + w
            if d < dist[j]:
                dist[j] = d
                prev[j] = i
                if w:
                    dq.append(j)
                else:
                    dq.appendleft(j)
    if dist[target] == inf:
        return []
    cells, i = [], target
    while i >= 0:
        if obstacle[i]:
            cells.append((int(i % nx), int(i // nx)))
        i = int(prev[i])
    return cells[::-1]


