"""Map generators: the nine map categories of the JLAMP 2023 NavFn paper, plus two realistic ones.

Every generator returns NavFn-internal costs (a ``(height, width)`` uint8 array: 50..253
passable, 254 lethal) with a lethal border, the way the paper's suite stores its maps.
Sizes are whole-map sizes, border included, as in ``test.txt`` (the paper's names count
the interior only: its ``3x3_free`` is a 5x5 map).

Categories (``CATEGORIES``):

``free``      open interior, every cell neutral (50)
``random``    no obstacles, every interior cell a uniform random cost in 50..253
``obstacle``  a ratio of the interior cells lethal, picked at random (paper: 20..75 %)
``columns``   a periodic grid of rectangular lethal columns between corridors, clipped
              at the border
``radial``    a radial cost gradient ``50 + 203 * d / radius`` around a centre (a corner,
              the middle or any cell), lethal from ``radius`` on
``spiral``    a one-cell clockwise spiral corridor from (1, 1) inwards, one-cell walls
``split``     one straight lethal wall (horizontal or vertical, 1-2 cells thick) across
              the whole interior: two regions with no path between them
``walls``     random straight wall segments (horizontal, vertical, diagonal, any slope)
``circus``    a ring around a central lethal block: a neutral top row, two side corridors
              (one cheap, one at 253, entered through a 253 cell) and a neutral bottom
              row; the paper's circus maps are the 5-wide ones with the cheap side at 153
``inflated``  a Nav2 costmap: random lethal cores (rectangles, discs, points) and the walls
              inflated as ``nav2_costmap_2d``'s inflation layer does (253 within the
              inscribed radius, ``252 * exp(-k (d - r))`` truncated beyond, nothing past
              the inflation radius), then translated by ``NavFn::setCostmap``
``maze``      a maze of one-cell corridors (randomised depth-first search) with some walls
              knocked out so that it has loops

Categories that have both flavours in the paper (``columns``, ``obstacle``, ``spiral``,
``split``, ``walls``) and ``maze`` alternate in a suite: even-numbered maps have neutral
passable cells, odd-numbered ones random costs (name suffix ``_random``).

Cases are chosen like the paper's: all ordered pairs (start, goal) of passable interior
cells, start-major with cells in x-major order, when there are at most ``paths`` of them;
otherwise ``paths`` distinct pairs sampled at random (in the sampled order).

Everything is deterministic: map ``i`` of a category with seed ``s`` comes from
``numpy.random.default_rng([s, <category key>, i])``, so it does not depend on ``count``.
"""

from __future__ import annotations

import math
import os
import shutil
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Callable, Optional, Union

import numpy as np

from ..errors import NavfnInputError
from ..fileio import atomic_write_bytes
from ..spec.constants import COST_NEUTRAL, COST_OBS, LETHAL_OBSTACLE
from ..spec.costs import set_costmap

CATEGORIES = (
    "circus", "columns", "free", "obstacle", "radial", "random", "spiral", "split", "walls",
    "inflated", "maze",
)
# Stable stream keys (never hash(): it is salted per process).
_KEY = {c: i + 1 for i, c in enumerate(CATEGORIES)}

LETHAL = COST_OBS  # 254
FREE_COST = COST_NEUTRAL  # 50
MAX_COST = COST_OBS - 1  # 253, the dearest passable cost
DEFAULT_PATHS = 1000
MAX_CASES = 1_000_000  # per map; 'all' beyond this is refused

Size = tuple[int, int]


# ---------------------------------------------------------------------------------- helpers
def _frame(width: int, height: int, fill: int) -> np.ndarray:
    """A (height, width) map filled with ``fill`` inside a lethal border."""
    a = np.full((height, width), LETHAL, dtype=np.uint8)
    a[1:-1, 1:-1] = fill
    return a


def _random_costs(rng: np.random.Generator, shape) -> np.ndarray:
    return rng.integers(FREE_COST, MAX_COST + 1, size=shape, dtype=np.int64).astype(np.uint8)


def _paint_costs(a: np.ndarray, rng: np.random.Generator, random_costs: bool) -> np.ndarray:
    """Give every passable cell of ``a`` a random cost (or leave the map as it is)."""
    if random_costs:
        passable = a < LETHAL
        a[passable] = _random_costs(rng, int(passable.sum()))
    return a


def passable_cells(costs: np.ndarray) -> np.ndarray:
    """(x, y) of every passable interior cell, x-major (x outer, y inner) like the paper."""
    inner = np.asarray(costs)[1:-1, 1:-1] < LETHAL
    ys, xs = np.nonzero(inner.T)  # transposed: rows of inner.T are x
    return np.stack([ys + 1, xs + 1], axis=1).astype(np.int32)


def _line(x0: int, y0: int, x1: int, y1: int) -> list[tuple[int, int]]:
    """Cells of a straight segment, one per step along the longer axis (rounded DDA)."""
    n = max(abs(x1 - x0), abs(y1 - y0))
    if n == 0:
        return [(x0, y0)]
    return [(int(math.floor(x0 + (x1 - x0) * t / n + 0.5)), int(math.floor(y0 + (y1 - y0) * t / n + 0.5)))
            for t in range(n + 1)]


# ------------------------------------------------------------------------------- categories
def free_map(rng: np.random.Generator, width: int, height: int) -> tuple[np.ndarray, dict]:
    return _frame(width, height, FREE_COST), {"desc": "free"}


def random_map(rng: np.random.Generator, width: int, height: int) -> tuple[np.ndarray, dict]:
    a = _frame(width, height, FREE_COST)
    a[1:-1, 1:-1] = _random_costs(rng, (height - 2, width - 2))
    return a, {"desc": "random"}


def obstacle_map(rng: np.random.Generator, width: int, height: int, ratio: Optional[float] = None,
                 random_costs: bool = True) -> tuple[np.ndarray, dict]:
    """``int(interior * ratio)`` distinct interior cells lethal (at least one passable cell kept)."""
    if ratio is None:
        ratio = int(rng.integers(2, 15)) * 5 / 100  # 10 % .. 70 %
    a = _frame(width, height, FREE_COST)
    iw, ih = width - 2, height - 2
    n = iw * ih
    k = min(int(n * ratio), n - 1)
    picked = rng.choice(n, size=k, replace=False)
    a[1 + picked // iw, 1 + picked % iw] = LETHAL
    _paint_costs(a, rng, random_costs)
    pct = int(round(ratio * 100))
    return a, {"desc": f"obstacle{pct}" + ("_random" if random_costs else ""), "ratio": ratio,
               "random_costs": random_costs}


def columns_map(rng: np.random.Generator, width: int, height: int, random_costs: bool = False
                ) -> tuple[np.ndarray, dict]:
    """Lethal ``bw x bh`` blocks every ``bw + gx`` / ``bh + gy`` cells, corridors between them.

    Every free cell lies on a corridor row or column that crosses the whole interior, so the
    free space is connected.
    """
    iw, ih = width - 2, height - 2
    bw = int(rng.integers(1, max(1, min(4, iw - 1)) + 1))
    bh = int(rng.integers(1, max(1, min(4, ih - 1)) + 1))
    gx = int(rng.integers(1, 4))
    gy = int(rng.integers(1, 4))
    ox = 1 + int(rng.integers(1, gx + 1))  # first block column: a corridor of 1..gx before it
    oy = 1 + int(rng.integers(1, gy + 1))
    ox = min(ox, width - 2)  # a block must start inside the interior
    oy = min(oy, height - 2)
    a = _frame(width, height, FREE_COST)
    xs = np.arange(width)
    ys = np.arange(height)
    colx = (xs >= ox) & ((xs - ox) % (bw + gx) < bw)
    coly = (ys >= oy) & ((ys - oy) % (bh + gy) < bh)
    block = coly[:, None] & colx[None, :]
    block[0, :] = block[-1, :] = False
    block[:, 0] = block[:, -1] = False
    a[block] = LETHAL
    _paint_costs(a, rng, random_costs)
    return a, {"desc": "column" + ("_random" if random_costs else ""), "block": [bw, bh], "gap": [gx, gy],
               "origin": [ox, oy], "random_costs": random_costs}


def radial_map(rng: np.random.Generator, width: int, height: int, center: Optional[tuple[int, int]] = None,
               radius: Optional[float] = None) -> tuple[np.ndarray, dict]:
    """Cost ``int(50 + 203 * d / radius)`` at Euclidean distance ``d < radius`` from the centre."""
    iw, ih = width - 2, height - 2
    if center is None:
        kind = int(rng.integers(0, 3))
        if kind == 0:  # a corner
            center = (1 if rng.integers(0, 2) == 0 else iw, 1 if rng.integers(0, 2) == 0 else ih)
        elif kind == 1:  # the middle
            center = ((iw + 1) // 2, (ih + 1) // 2)
        else:
            center = (int(rng.integers(1, iw + 1)), int(rng.integers(1, ih + 1)))
    cx, cy = center
    if radius is None:
        diag = math.hypot(iw, ih)
        radius = float(rng.integers(max(2, int(diag * 0.4)), max(3, int(diag * 1.2)) + 1))
    a = _frame(width, height, FREE_COST)
    y, x = np.mgrid[0:height, 0:width]
    d = np.sqrt((x - cx) ** 2.0 + (y - cy) ** 2.0)
    inside = d < radius
    vals = np.where(inside, np.floor(d / radius * (MAX_COST - FREE_COST) + FREE_COST), LETHAL)
    a[1:-1, 1:-1] = np.minimum(vals, LETHAL).astype(np.uint8)[1:-1, 1:-1]
    where = "corner" if (cx in (1, iw) and cy in (1, ih)) else "center" if (cx, cy) == ((iw + 1) // 2, (ih + 1) // 2) else "cell"
    return a, {"desc": f"radial_{where}", "center": [int(cx), int(cy)], "radius": radius}


def spiral_map(rng: np.random.Generator, width: int, height: int, random_costs: bool = False
               ) -> tuple[np.ndarray, dict]:
    """A clockwise spiral corridor from (1, 1): walk straight while the next cell is free and
    touches no corridor cell but the current one, otherwise turn right; stop when neither works."""
    a = np.full((height, width), LETHAL, dtype=np.uint8)
    carved = np.zeros((height, width), dtype=bool)

    def can_enter(px, py, nx_, ny_):
        if not (1 <= nx_ <= width - 2 and 1 <= ny_ <= height - 2) or carved[ny_, nx_]:
            return False
        for qx, qy in ((nx_ + 1, ny_), (nx_ - 1, ny_), (nx_, ny_ + 1), (nx_, ny_ - 1)):
            if (qx, qy) != (px, py) and carved[qy, qx]:
                return False
        return True

    x, y, dx, dy = 1, 1, 1, 0
    carved[y, x] = True
    while True:
        if can_enter(x, y, x + dx, y + dy):
            x, y = x + dx, y + dy
        else:
            dx, dy = -dy, dx  # turn right (y grows downwards)
            if not can_enter(x, y, x + dx, y + dy):
                break
            x, y = x + dx, y + dy
        carved[y, x] = True
    a[carved] = FREE_COST
    _paint_costs(a, rng, random_costs)
    return a, {"desc": "spiral" + ("_random" if random_costs else ""), "random_costs": random_costs,
               "end": [int(x), int(y)]}


def split_map(rng: np.random.Generator, width: int, height: int, orientation: Optional[str] = None,
              random_costs: bool = True) -> tuple[np.ndarray, dict]:
    """A straight lethal wall across the interior, leaving at least one row/column each side."""
    iw, ih = width - 2, height - 2
    options = [o for o, n in (("h", ih), ("v", iw)) if n >= 3]
    if not options:
        raise NavfnInputError(f"a split map needs an interior at least 3 cells long one way, got {width}x{height}")
    if orientation is None:
        orientation = options[int(rng.integers(0, len(options)))]
    elif orientation not in options:
        raise NavfnInputError(f"cannot split a {width}x{height} map {orientation!r}")
    n = ih if orientation == "h" else iw
    thick = int(rng.integers(1, min(2, n - 2) + 1))
    at = int(rng.integers(2, n - thick + 1))  # first wall row/column; >= 1 free line each side
    a = _frame(width, height, FREE_COST)
    if orientation == "h":
        a[at:at + thick, :] = LETHAL
    else:
        a[:, at:at + thick] = LETHAL
    _paint_costs(a, rng, random_costs)
    return a, {"desc": f"split_{orientation}" + ("_random" if random_costs else ""), "orientation": orientation,
               "at": at, "thickness": thick, "random_costs": random_costs}


def walls_map(rng: np.random.Generator, width: int, height: int, walls: Optional[int] = None,
              random_costs: bool = False) -> tuple[np.ndarray, dict]:
    """``walls`` straight segments of random direction and length (clipped to the interior)."""
    iw, ih = width - 2, height - 2
    if walls is None:
        walls = int(rng.integers(1, max(1, iw * ih // 12) + 1))
    a = _frame(width, height, FREE_COST)
    longest = max(2, int(max(iw, ih) * 0.6))
    for _ in range(walls):
        x0 = int(rng.integers(1, iw + 1))
        y0 = int(rng.integers(1, ih + 1))
        ang = rng.integers(0, 16) * (math.pi / 8) if rng.random() < 0.75 else rng.random() * 2 * math.pi
        length = int(rng.integers(1, longest + 1))
        x1 = int(round(x0 + length * math.cos(ang)))
        y1 = int(round(y0 + length * math.sin(ang)))
        for x, y in _line(x0, y0, x1, y1):
            if 1 <= x <= iw and 1 <= y <= ih:
                a[y, x] = LETHAL
    if not (a < LETHAL).any():  # keep one cell open
        a[1 + int(rng.integers(0, ih)), 1 + int(rng.integers(0, iw))] = FREE_COST
    _paint_costs(a, rng, random_costs)
    return a, {"desc": f"{walls}walls" + ("_random" if random_costs else ""), "walls": walls,
               "random_costs": random_costs}


def circus_map(rng: np.random.Generator, width: int, height: int, side: Optional[str] = None,
               cheap: Optional[int] = None) -> tuple[np.ndarray, dict]:
    """The paper's circus: a ring round a lethal block; one side corridor cheap, the other 253.

    Row 1 is neutral; x = 1 and x = width-2 are the side corridors (their first cell below
    row 1 costs 253 on both sides); the block covers x = 2..width-3, y = 2..height-3; the
    bottom row between the corridors is neutral.  With width 5 and ``cheap`` = 153 this is
    exactly the paper's ``circus_<h>L`` / ``circus_<h>R``.
    """
    if side is None:
        side = "L" if rng.integers(0, 2) == 0 else "R"
    if cheap is None:
        cheap = int(rng.integers(60, 221))
    a = np.full((height, width), LETHAL, dtype=np.uint8)
    lo, hi = 1, width - 2
    a[1, lo:hi + 1] = FREE_COST
    a[height - 2, lo + 1:hi] = FREE_COST
    left, right = (cheap, MAX_COST) if side == "L" else (MAX_COST, cheap)
    a[2:height - 1, lo] = left
    a[2:height - 1, hi] = right
    a[2, lo] = a[2, hi] = MAX_COST
    return a, {"desc": f"circus_{side}", "side": side, "cheap": cheap}


# ---- inflated: Nav2's inflation layer (nav2_costmap_2d InflationLayer::updateCosts / computeCost)


def inflate(ros: np.ndarray, resolution: float, inscribed_radius: float, inflation_radius: float,
            cost_scaling_factor: float) -> np.ndarray:
    """Inflate a ROS costmap (0 free, 254 lethal) over the whole map with Nav2's breadth-first
    layer (:func:`navfn_smt.nav2.inflation.inflate_legacy`, ``InflationLayer`` up to Kilted)."""
    from ..nav2.inflation import inflate_legacy

    return inflate_legacy(np.asarray(ros, dtype=np.uint8), resolution, inscribed_radius, inflation_radius,
                          cost_scaling_factor)


def inflated_map(rng: np.random.Generator, width: int, height: int, resolution: float = 0.05,
                 inscribed_radius: Optional[float] = None, inflation_radius: Optional[float] = None,
                 cost_scaling_factor: Optional[float] = None, cores: Optional[int] = None,
                 walls: bool = True) -> tuple[np.ndarray, dict]:
    """A Nav2 global costmap: lethal cores (and the map's outer walls) inflated, then
    ``NavFn::setCostmap``'s translation (253 and 254 lethal, ``50 + 0.8 v`` below)."""
    small = min(width, height)
    if inscribed_radius is None:  # robot radius: 1..5 cells, at most an eighth of the map
        cells = int(rng.integers(1, max(1, min(5, (small - 2) // 8)) + 1))
        inscribed_radius = round((cells + int(rng.integers(0, 10)) / 10) * resolution, 4)
    if inflation_radius is None:
        inflation_radius = round(inscribed_radius + float(rng.integers(2, 13)) * resolution, 4)
    if cost_scaling_factor is None:
        cost_scaling_factor = float(rng.integers(10, 101)) / 10.0  # 1.0 .. 10.0
    ros = np.zeros((height, width), dtype=np.uint8)
    if walls:
        ros[0, :] = ros[-1, :] = ros[:, 0] = ros[:, -1] = LETHAL_OBSTACLE
    if cores is None:
        cores = int(rng.integers(1, max(2, width * height // 250) + 1))
    y, x = np.mgrid[0:height, 0:width]
    for _ in range(cores):
        cx, cy = int(rng.integers(1, width - 1)), int(rng.integers(1, height - 1))
        kind = int(rng.integers(0, 3))
        if kind == 0:  # rectangle
            rw = int(rng.integers(1, max(1, width // 6) + 1))
            rh = int(rng.integers(1, max(1, height // 6) + 1))
            ros[cy:cy + rh, cx:cx + rw] = LETHAL_OBSTACLE
        elif kind == 1:  # disc
            rad = float(rng.integers(1, max(1, small // 10) + 1))
            ros[(x - cx) ** 2 + (y - cy) ** 2 <= rad * rad] = LETHAL_OBSTACLE
        else:  # a single cell (a post, a sensor speck)
            ros[cy, cx] = LETHAL_OBSTACLE
    inflated = inflate(ros, resolution, inscribed_radius, inflation_radius, cost_scaling_factor)
    a = set_costmap(inflated, is_ros=True, allow_unknown=True)
    a[0, :] = a[-1, :] = a[:, 0] = a[:, -1] = LETHAL
    return a, {"desc": "inflated", "resolution": resolution, "inscribed_radius": inscribed_radius,
               "inflation_radius": inflation_radius, "cost_scaling_factor": cost_scaling_factor, "cores": cores}


def maze_map(rng: np.random.Generator, width: int, height: int, loops: Optional[float] = None,
             random_costs: bool = False) -> tuple[np.ndarray, dict]:
    """A maze on the odd cells (randomised depth-first search), then each remaining wall
    between two maze cells knocked out with probability ``loops`` (at least one when any)."""
    if loops is None:
        loops = float(rng.integers(5, 21)) / 100.0
    a = np.full((height, width), LETHAL, dtype=np.uint8)
    cols = list(range(1, width - 1, 2))
    rows = list(range(1, height - 1, 2))
    visited = np.zeros((len(rows), len(cols)), dtype=bool)
    start = (int(rng.integers(0, len(cols))), int(rng.integers(0, len(rows))))
    stack = [start]
    visited[start[1], start[0]] = True
    a[rows[start[1]], cols[start[0]]] = FREE_COST
    while stack:
        i, j = stack[-1]
        nbrs = [(i + di, j + dj) for di, dj in ((1, 0), (-1, 0), (0, 1), (0, -1))
                if 0 <= i + di < len(cols) and 0 <= j + dj < len(rows) and not visited[j + dj, i + di]]
        if not nbrs:
            stack.pop()
            continue
        ni, nj = nbrs[int(rng.integers(0, len(nbrs)))]
        visited[nj, ni] = True
        a[rows[nj], cols[ni]] = FREE_COST
        a[(rows[j] + rows[nj]) // 2, (cols[i] + cols[ni]) // 2] = FREE_COST
        stack.append((ni, nj))
    # walls between two maze cells that are still closed
    closed = [(x, y) for y in rows for x in range(2, width - 2, 2) if x + 1 <= width - 2 and a[y, x] == LETHAL]
    closed += [(x, y) for y in range(2, height - 2, 2) for x in cols if y + 1 <= height - 2 and a[y, x] == LETHAL]
    opened = 0
    for x, y in closed:
        if rng.random() < loops:
            a[y, x] = FREE_COST
            opened += 1
    if closed and not opened:
        x, y = closed[int(rng.integers(0, len(closed)))]
        a[y, x] = FREE_COST
        opened = 1
    _paint_costs(a, rng, random_costs)
    return a, {"desc": "maze" + ("_random" if random_costs else ""), "loops": loops, "opened": opened,
               "random_costs": random_costs}


@dataclass(frozen=True)
class Category:
    name: str
    make: Callable[..., tuple[np.ndarray, dict]]
    min_size: Size  # whole map, border included
    default_sizes: tuple[Size, Size]  # ranges of W and H drawn when no size is given: (lo, hi) each
    alternates: bool  # even maps neutral, odd maps random costs
    summary: str
    min_long: int = 3  # the longer side must have at least this many cells


CATEGORY_INFO: dict[str, Category] = {
    c.name: c for c in (
        Category("circus", circus_map, (5, 5), ((5, 9), (7, 16)), False,
                 "a ring round a lethal block, one side corridor cheap and one at 253"),
        Category("columns", columns_map, (5, 5), ((7, 23), (7, 23)), True,
                 "a periodic grid of lethal rectangular columns between corridors"),
        Category("free", free_map, (3, 3), ((5, 14), (5, 14)), False, "open, every cell neutral"),
        Category("obstacle", obstacle_map, (3, 3), ((5, 17), (5, 17)), True,
                 "10-70 % of the cells lethal, at random"),
        Category("radial", radial_map, (3, 3), ((5, 22), (4, 22)), False,
                 "a radial cost gradient round a corner, the middle or a cell; lethal beyond its radius"),
        Category("random", random_map, (3, 3), ((5, 17), (4, 17)), False, "no obstacles, random costs"),
        Category("spiral", spiral_map, (3, 3), ((7, 26), (7, 26)), True,
                 "a one-cell clockwise spiral corridor from (1, 1) inwards"),
        Category("split", split_map, (3, 3), ((5, 22), (5, 22)), True,
                 "a straight lethal wall across the map: two regions, no path between them", min_long=5),
        Category("walls", walls_map, (5, 5), ((7, 32), (7, 27)), True,
                 "random straight wall segments of any direction"),
        Category("inflated", inflated_map, (5, 5), ((40, 100), (40, 100)), False,
                 "a Nav2 costmap: lethal cores and walls inflated by the inflation layer, translated by NavFn"),
        Category("maze", maze_map, (5, 5), ((11, 41), (11, 41)), True,
                 "a maze of one-cell corridors with loops"),
    )
}


# ------------------------------------------------------------------------------------ cases
def parse_paths(paths: Union[int, str, None]) -> Optional[int]:
    """``paths`` as given to the generator or the CLI: a positive number, or 'all' (None)."""
    if paths is None:
        return None
    if isinstance(paths, str):
        s = paths.strip().lower()
        if s == "all":
            return None
        try:
            paths = int(s)
        except ValueError:
            raise NavfnInputError(f"--paths {paths!r}: expected a positive number or 'all'") from None
    if isinstance(paths, bool) or not isinstance(paths, (int, np.integer)) or paths < 1:
        raise NavfnInputError(f"--paths {paths!r}: expected a positive number or 'all'")
    return int(paths)


def choose_cases(costs: np.ndarray, paths: Union[int, str, None], rng: np.random.Generator) -> np.ndarray:
    """Cases ``sx sy gx gy`` (int32, (N, 4)) as the paper chose them: every ordered pair of
    passable interior cells (start-major, cells x-major) when there are at most ``paths``,
    otherwise ``paths`` distinct pairs drawn at random, in the order drawn."""
    limit = parse_paths(paths)
    cells = passable_cells(costs)
    n = len(cells)
    total = n * n
    if limit is None or total <= limit:
        if total > MAX_CASES:
            raise NavfnInputError(
                f"all ordered pairs of the {n} passable cells are {total} cases per map, more than {MAX_CASES}; "
                "give a number of paths")
        idx = np.arange(total, dtype=np.int64)
    else:
        idx = rng.choice(total, size=limit, replace=False).astype(np.int64)
    return np.concatenate([cells[idx // n], cells[idx % n]], axis=1).astype(np.int32).reshape(-1, 4)


# ------------------------------------------------------------------------------------- maps
@dataclass
class GeneratedMap:
    name: str
    category: str
    costs: np.ndarray  # (height, width) uint8, NavFn-internal
    cases: np.ndarray  # (N, 4) int32
    params: dict = field(default_factory=dict)
    directory: Optional[Path] = None  # set once written

    @property
    def width(self) -> int:
        return int(self.costs.shape[1])

    @property
    def height(self) -> int:
        return int(self.costs.shape[0])


def _check_category(category: str) -> Category:
    info = CATEGORY_INFO.get(category)
    if info is None:
        raise NavfnInputError(f"unknown map category {category!r} (choose from {', '.join(CATEGORIES)})")
    return info


def _check_size(info: Category, size) -> Optional[Size]:
    if size is None:
        return None
    try:
        w, h = (int(v) for v in size)
    except (TypeError, ValueError):
        raise NavfnInputError(f"--size {size!r}: expected two numbers W H") from None
    mw, mh = info.min_size
    if w < mw or h < mh:
        raise NavfnInputError(f"--size {w} {h}: {info.name} maps need at least {mw}x{mh} cells (border included)")
    if max(w, h) < info.min_long:
        raise NavfnInputError(f"--size {w} {h}: {info.name} maps need {info.min_long} cells one way (border included)")
    if w * h > 4096 * 4096:
        raise NavfnInputError(f"--size {w} {h}: too large (at most 4096x4096 cells)")
    return w, h


def _check_seed(seed) -> int:
    if isinstance(seed, bool) or not isinstance(seed, (int, np.integer)) or seed < 0:
        raise NavfnInputError(f"--seed {seed!r}: expected a non-negative integer")
    return int(seed)


def map_rng(category: str, seed: int, index: int) -> np.random.Generator:
    """The random stream of map ``index`` of ``category`` in a suite generated with ``seed``."""
    return np.random.default_rng([_check_seed(seed), _KEY[_check_category(category).name], int(index)])


def generate_map(category: str, seed: int = 0, index: int = 0, size: Optional[Size] = None,
                 paths: Union[int, str, None] = DEFAULT_PATHS) -> GeneratedMap:
    """Map ``index`` of ``category`` for ``seed``: costs, cases and the generator's parameters."""
    info = _check_category(category)
    size = _check_size(info, size)
    parse_paths(paths)
    rng = map_rng(category, seed, index)
    if size is None:
        (wl, wh), (hl, hh) = info.default_sizes
        size = (int(rng.integers(wl, wh + 1)), int(rng.integers(hl, hh + 1)))
    w, h = size
    kwargs = {"random_costs": index % 2 == 1} if info.alternates else {}
    for _attempt in range(100):
        costs, params = info.make(rng, w, h, **kwargs)
        if (costs[1:-1, 1:-1] < LETHAL).any():
            break
    else:
        raise NavfnInputError(f"--size {w} {h}: {category} maps of this size leave no passable cell")
    _validate(costs)
    cases = choose_cases(costs, paths, rng)
    desc = params.pop("desc")
    name = f"{w}x{h}_{desc}_s{int(seed)}_{index:03d}"
    return GeneratedMap(name, category, costs, cases, {"category": category, "seed": int(seed), "index": int(index),
                                                        "size": [w, h], **params})


def _validate(costs: np.ndarray) -> None:
    """Every generated map: uint8, a lethal border, passable costs 50..253 (internal error otherwise)."""
    assert costs.dtype == np.uint8 and costs.ndim == 2
    assert (costs[0, :] == LETHAL).all() and (costs[-1, :] == LETHAL).all()
    assert (costs[:, 0] == LETHAL).all() and (costs[:, -1] == LETHAL).all()
    assert ((costs >= FREE_COST) & (costs <= LETHAL)).all()


def generate_maps(category: str, count: int = 1, seed: int = 0, size: Optional[Size] = None,
                  paths: Union[int, str, None] = DEFAULT_PATHS) -> list[GeneratedMap]:
    _check_category(category)
    _check_seed(seed)
    if isinstance(count, bool) or not isinstance(count, (int, np.integer)) or count < 1:
        raise NavfnInputError(f"--count {count!r}: expected a positive number of maps")
    return [generate_map(category, seed, i, size, paths) for i in range(int(count))]


# ---------------------------------------------------------------------------------- writing
def format_test_txt(m: GeneratedMap, map_file: str = "map.bin") -> str:
    """``test.txt`` of a generated map: size, map file, blank line, a provenance comment, cases."""
    p = m.params
    extras = ", ".join(f"{k} {v}" for k, v in p.items() if k not in ("category", "seed", "index", "size"))
    lines = [f"{m.width} {m.height}", map_file, "",
             f"-1 navfn-smt suite generate: category {m.category}, seed {p.get('seed')}, map {p.get('index')}"
             + (f"; {extras}" if extras else "")]
    lines += [f"{sx} {sy} {gx} {gy}" for sx, sy, gx, gy in m.cases.tolist()]
    return "\n".join(lines) + "\n"


def _write_file(path: Path, data: bytes) -> None:
    """Write a whole file or nothing (see :mod:`navfn_smt.fileio`)."""
    atomic_write_bytes(path, data)


def write_map(m: GeneratedMap, category_dir: Path, overwrite: bool = False) -> Path:
    """Write one map directory ``category_dir/<name>`` (test.txt + map.bin) all or nothing.

    The files are written into a hidden temporary directory beside it, which is then renamed
    into place; an existing directory is only replaced with ``overwrite`` (it is moved aside
    first and removed once the new one is in place).
    """
    target = category_dir / m.name
    if target.exists() and not overwrite:
        raise NavfnInputError(f"{target}: already exists (pass --overwrite to replace it)")
    tmp = category_dir / f".{m.name}.tmp{os.getpid()}"
    old = category_dir / f".{m.name}.old{os.getpid()}"
    shutil.rmtree(tmp, ignore_errors=True)
    try:
        tmp.mkdir()
        _write_file(tmp / "map.bin", np.ascontiguousarray(m.costs, dtype=np.uint8).tobytes())
        _write_file(tmp / "test.txt", format_test_txt(m).encode("ascii"))
        if target.exists():
            os.replace(target, old)
        os.replace(tmp, target)
    except BaseException:
        shutil.rmtree(tmp, ignore_errors=True)
        if old.exists() and not target.exists():
            os.replace(old, target)  # put the previous map back
        raise
    shutil.rmtree(old, ignore_errors=True)
    return target


def generate_suite(out_dir, category: str, count: int = 1, seed: int = 0, size: Optional[Size] = None,
                   paths: Union[int, str, None] = DEFAULT_PATHS, overwrite: bool = False,
                   progress: Optional[Callable[[GeneratedMap], None]] = None) -> list[GeneratedMap]:
    """Generate ``count`` maps of ``category`` into ``out_dir/<category>/<name>/``.

    Another category goes beside the ones already there; maps whose directories exist are
    refused (before anything is written) unless ``overwrite``.  Each map directory appears
    whole or not at all.  Returns the maps, with ``directory`` set.
    """
    out = Path(out_dir)
    if out.exists() and not out.is_dir():
        raise NavfnInputError(f"{out}: not a directory")
    maps = generate_maps(category, count, seed, size, paths)
    cat_dir = out / category
    if not overwrite:
        clash = [m.name for m in maps if (cat_dir / m.name).exists()]
        if clash:
            what = (f"{cat_dir / clash[0]} already exists" if len(clash) == 1
                    else f"{cat_dir / clash[0]} and {len(clash) - 1} more maps already exist")
            raise NavfnInputError(f"{what} (pass --overwrite to replace)")
    try:
        cat_dir.mkdir(parents=True, exist_ok=True)
    except OSError as e:
        raise NavfnInputError(f"{cat_dir}: cannot create ({e.strerror})") from None
    written = []
    for m in maps:
        try:
            d = write_map(m, cat_dir, overwrite)
        except OSError as e:
            raise NavfnInputError(f"{cat_dir / m.name}: cannot write ({e.strerror})") from None
        m = replace(m, directory=d)
        written.append(m)
        if progress:
            progress(m)
    return written
