"""Nav2's two inflation layers, bit-exact, on a whole-map update.

Both layers take the master costmap (uint8, ``(size_y, size_x)``, row ``j`` the grid row)
and raise the cost of every cell within ``inflation_radius`` of an obstacle cell
(``LETHAL_OBSTACLE``, and ``NO_INFORMATION`` too with ``inflate_around_unknown``) to a cost
that falls with the distance.  They differ in how they find that distance:

``inflate_current``: ``nav2_costmap_2d::InflationLayer`` from Nav2 1.5.0 on (#5933, March
  2026: Lyrical, Rolling).  A Euclidean distance transform (Felzenszwalb and Huttenlocher's
  lower envelope of parabolas, columns then rows, all in **float32**, then Eigen's
  ``cwiseSqrt``, which on x86 with Eigen 3.4 is *not* the correctly rounded square root but
  ``rsqrtps`` plus one Newton step, CPU-dependent: see :func:`matrix_sqrt`), and a cost table
  sampled every 1/100 cell, indexed by ``(unsigned)(distance * 100 + 0.5f)`` in float.
``inflate_legacy``: the breadth-first layer (``InflationLayer`` up to Kilted,
  ``LegacyInflationLayer`` from 1.5.0 on).  Cells are visited in bins of increasing integer
  squared distance to the obstacle cell that reached them first, spreading to the four
  neighbours; a cell keeps the first source that pops it, which need not be its nearest
  obstacle.  Distances and costs come from tables indexed by ``(|dx|, |dy|)``, in double.

Shared: ``Costmap2D::cellDistance`` (the cut-off in cells), ``computeCost`` (double: 254 at
distance 0, 253 up to the inscribed radius, else ``(unsigned char)(252 * exp(-csf * (d *
res - inscribed)))``), and the write rule (an unknown cell takes the cost only when it is >=
253, or > 0 with ``inflate_unknown``; any other cell takes ``max(old, cost)``).

The update window is the whole map, as when the global costmap inflates a static map
(``need_reinflation_`` after ``onFootprintChanged`` gives infinite bounds).  ``resolution``
is the costmap's double, i.e. the map's float32 resolution widened (``MapServerMap.
costmap_resolution``).  ``exp`` is the C library's (``math.exp`` calls it).
"""

from __future__ import annotations

import math
from functools import lru_cache

import numpy as np
from numba import njit

from ..backends.numba_domain import fma_llvm
from ..errors import NavfnInputError
from ..spec.arithmetic import LAYERS_X86_64, LayersArithmetic
from ..spec.constants import FREE_SPACE, INSCRIBED_INFLATED_OBSTACLE, LETHAL_OBSTACLE, NO_INFORMATION
COST_LUT_PRECISION = 100  # InflationLayer: samples of the cost table per cell
FLT_MAX = np.float32(np.finfo(np.float32).max)  # DistanceTransform::DT_INF


# ------------------------------------------------------------------------------ shared
def cell_distance(world_dist: float, resolution: float) -> int:
    """``Costmap2D::cellDistance``: ``(unsigned int) max(0.0, ceil(world_dist / resolution))``, double."""
    cells = max(0.0, math.ceil(world_dist / resolution)) if math.isfinite(world_dist / resolution) else None
    if cells is None or cells >= 2.0 ** 32:
        raise NavfnInputError(f"inflation radius {world_dist!r} m is not a usable number of cells at "
                              f"resolution {resolution!r}")
    return int(cells)


def compute_cost(distance: float, resolution: float, inscribed_radius: float, cost_scaling_factor: float) -> int:
    """``computeCost(double distance)`` (both layers): the cost at ``distance`` cells, double.

    0 -> LETHAL; ``distance * resolution <= inscribed_radius`` -> INSCRIBED; else
    ``(unsigned char)((INSCRIBED - 1) * exp(-1.0 * csf * (distance * resolution - inscribed)))``.
    """
    if distance == 0:
        return LETHAL_OBSTACLE
    if distance * resolution <= inscribed_radius:
        return INSCRIBED_INFLATED_OBSTACLE
    factor = math.exp(-1.0 * cost_scaling_factor * (distance * resolution - inscribed_radius))
    return int((INSCRIBED_INFLATED_OBSTACLE - 1) * factor)  # truncation; always in 0..252


def _check_costmap(costmap) -> np.ndarray:
    a = np.asarray(costmap)
    if a.ndim != 2 or a.dtype != np.uint8:
        raise NavfnInputError(f"costmap must be a 2-D uint8 array, got {a.dtype} with shape {a.shape}")
    return np.ascontiguousarray(a)


def _check_numbers(**values) -> None:
    for key, v in values.items():
        if isinstance(v, bool) or not isinstance(v, (int, float, np.integer, np.floating)) or not math.isfinite(v):
            raise NavfnInputError(f"'{key}' must be a finite number, got {v!r}")
    if values["resolution"] <= 0:
        raise NavfnInputError(f"'resolution' must be positive, got {values['resolution']!r}")


@njit(cache=True)
def _write_cost(old, cost, inflate_unknown):
    """The write rule both layers share (``updateCosts`` / ``applyInflation``)."""
    if old == NO_INFORMATION and ((cost > FREE_SPACE) if inflate_unknown else (cost >= INSCRIBED_INFLATED_OBSTACLE)):
        return cost
    return max(old, cost)


# ------------------------------------------------------------- the current InflationLayer
@lru_cache(maxsize=64)
def cost_lut(cell_inflation_radius: int, resolution: float, inscribed_radius: float,
             cost_scaling_factor: float) -> np.ndarray:
    """``InflationLayer::computeCaches``: ``computeCost(d / 100.0)`` for d = 0 .. cir * 100 + 1.

    ``static_cast<double>(d_scaled) / COST_LUT_PRECISION``: a double division by the int 100.
    Read-only (cached).
    """
    n = cell_inflation_radius * COST_LUT_PRECISION + 1
    lut = np.array([compute_cost(d / float(COST_LUT_PRECISION), resolution, inscribed_radius, cost_scaling_factor)
                    for d in range(n + 1)], dtype=np.uint8)
    lut.setflags(write=False)
    return lut


@njit(cache=True)
def _dt_1d(f, d, n, v, z):
    """``DistanceTransform::distanceTransform1D``, float32 throughout (ints converted to float).

    ``s = (f[q] - f[v[k]] + (float)(q*q - v[k]*v[k])) / (2.0f * (float)(q - v[k]))``; the
    envelope is popped while ``s <= z[k]``; then ``d[q] = (float)(diff*diff) + f[v[k]]``.
    """
    two = np.float32(2.0)
    k = 0
    v[0] = 0
    z[0] = -FLT_MAX
    z[1] = FLT_MAX
    for q in range(1, n):
        s = (f[q] - f[v[k]] + np.float32(q * q - v[k] * v[k])) / (two * np.float32(q - v[k]))
        while s <= z[k]:
            k -= 1
            s = (f[q] - f[v[k]] + np.float32(q * q - v[k] * v[k])) / (two * np.float32(q - v[k]))
        k += 1
        v[k] = q
        z[k] = s
        z[k + 1] = FLT_MAX
    k = 0
    for q in range(n):
        while z[k + 1] < np.float32(q):
            k += 1
        diff = q - v[k]
        d[q] = np.float32(diff * diff) + f[v[k]]


@njit(cache=True)
def _dt_2d(img):
    """``DistanceTransform::distanceTransform2D`` up to its square root: the column pass, then
    the row pass, leaving squared distances (float32) in ``img``."""
    h, w = img.shape
    n = max(h, w)
    f = np.empty(n, np.float32)
    d = np.empty(n, np.float32)
    v = np.empty(n, np.int64)
    z = np.empty(n + 1, np.float32)
    for x in range(w):
        for y in range(h):
            f[y] = img[y, x]
        _dt_1d(f, d, h, v, z)
        for y in range(h):
            img[y, x] = d[y]
    for y in range(h):
        for x in range(w):
            f[x] = img[y, x]
        _dt_1d(f, d, w, v, z)
        for x in range(w):
            img[y, x] = d[x]


def eigen_sse_sqrt(x: np.ndarray, table: np.ndarray) -> np.ndarray:
    """Eigen 3.4's ``psqrt<Packet4f>`` with ``EIGEN_FAST_MATH`` (its default) on SSE, float32.

    ``r = rsqrtps(x)`` (from ``table``, see :mod:`.rsqrt_tables`); one Newton step
    ``r = r * ((x * -0.5f) * (r * r) + 1.5f)`` (no FMA: two roundings); ``x * r``; inputs below
    FLT_MIN (0 here) give 0.  Not the correctly rounded square root: ``sqrt(49)`` is
    ``7.0000005`` on the measured CPU.
    """
    x = np.ascontiguousarray(x, dtype=np.float32)
    bits = x.view(np.uint32).astype(np.int64)
    e = ((bits >> 23) & 0xFF) - 127
    par = e & 1
    r = np.ldexp(table[par * 4096 + ((bits >> 11) & 0xFFF)], -((e - par) // 2)).astype(np.float32)
    f = np.float32
    with np.errstate(all="ignore"):
        r = r * (((x * f(-0.5)) * (r * r)) + f(1.5))
        y = x * r
    return np.where(x < np.finfo(np.float32).tiny, f(0.0), y).astype(np.float32)


SQRT_MODES = ("eigen-sse-amd", "exact", "eigen-sse-intel")
RSQRT_TABLE_OF = {"eigen-sse-amd": "amd-zen", "eigen-sse-intel": "intel-xeon-6-167"}


def matrix_sqrt(sq: np.ndarray, sqrt: str = "eigen-sse-amd") -> np.ndarray:
    """``img = img.cwiseSqrt()`` on the row-major ROI matrix (here: the whole map).

    ``"eigen-sse-amd"``: Eigen 3.4 on SSE vectorises the assignment over the flat storage in
    packets of 4 (:func:`eigen_sse_sqrt`, with the ``rsqrtps`` table measured on AMD Zen) and
    does the last ``size % 4`` elements with the scalar, correctly rounded ``std::sqrt``.
    ``"exact"``: the correctly rounded float square root everywhere (a build whose Eigen
    takes ``sqrtps``).  ``"eigen-sse-intel"``: as ``"eigen-sse-amd"`` with the ``rsqrtps``
    table measured on an Intel Xeon (family 6, model 167).
    """
    if sqrt not in SQRT_MODES:
        raise NavfnInputError(f"unknown sqrt mode {sqrt!r} (choose from {', '.join(SQRT_MODES)})")
    flat = np.ascontiguousarray(sq, dtype=np.float32).ravel()
    out = np.sqrt(flat)
    if sqrt in RSQRT_TABLE_OF:
        from .rsqrt_tables import rsqrt_table

        n = flat.size - flat.size % 4
        out[:n] = eigen_sse_sqrt(flat[:n], rsqrt_table(RSQRT_TABLE_OF[sqrt]))
    return out.reshape(sq.shape)


def distance_map(costmap: np.ndarray, inflate_around_unknown: bool = False, sqrt: str = "eigen-sse-amd") -> np.ndarray:
    """The float32 distance (in cells) of every cell to the nearest obstacle cell, as
    ``InflationLayer::updateCosts`` computes it: 0 at LETHAL (and NO_INFORMATION with
    ``inflate_around_unknown``), ``DT_INF`` (FLT_MAX) elsewhere, the transform, the square
    root (:func:`matrix_sqrt`).  A map without obstacle cells stays near ``sqrt(FLT_MAX)``."""
    c = _check_costmap(costmap)
    src = (c == LETHAL_OBSTACLE) | ((c == NO_INFORMATION) if inflate_around_unknown else False)
    img = np.where(src, np.float32(0.0), FLT_MAX).astype(np.float32)
    _dt_2d(img)
    return matrix_sqrt(img, sqrt)


@njit(cache=True)
def _apply_inflation(master, dist, cir, lut, inflate_unknown, fused_index):
    """``InflationLayer::applyInflation`` over the whole map, float32 index arithmetic.

    A cell farther than ``(float)cell_inflation_radius_`` is skipped; else its cost is
    ``lut[min(lut_max, (unsigned)(distance * 100 + 0.5f))]``, the index's multiply-add rounded
    once where the build fused it (``fused_index``, site ``lut_index``).
    """
    cir_f = np.float32(cir)
    lut_max = lut.shape[0] - 1
    prec = np.float32(COST_LUT_PRECISION)
    half = np.float32(0.5)
    h, w = master.shape
    for j in range(h):
        for i in range(w):
            dc = dist[j, i]
            if dc > cir_f:
                continue
            scaled = min(lut_max, int(fma_llvm(dc, prec, half) if fused_index else dc * prec + half))
            master[j, i] = _write_cost(master[j, i], lut[scaled], inflate_unknown)


def inflate_current(
    costmap,
    resolution: float,
    inscribed_radius: float,
    inflation_radius: float = 0.55,
    cost_scaling_factor: float = 10.0,
    inflate_unknown: bool = False,
    inflate_around_unknown: bool = False,
    enabled: bool = True,
    sqrt: str = "eigen-sse-amd",
    arith: LayersArithmetic = LAYERS_X86_64,
) -> np.ndarray:
    """``InflationLayer::updateCosts`` (Nav2 >= 1.5.0) over the whole map, in the layers build's
    arithmetic ``arith``; returns a new array.

    ``resolution``, ``inscribed_radius``, ``inflation_radius`` and ``cost_scaling_factor`` are
    the layer's doubles (defaults: the layer's own, 0.55 m and 10.0).  Nothing happens when
    the layer is disabled or ``cellDistance(inflation_radius)`` is 0.  ``sqrt`` selects how the
    distance transform's square root is taken (:func:`matrix_sqrt`): the default reproduces
    an x86-64 build with Eigen 3.4 on an AMD Zen CPU; other CPUs' ``rsqrtps`` differ.
    """
    master = _check_costmap(costmap).copy()
    _check_numbers(resolution=resolution, inscribed_radius=inscribed_radius,
                   inflation_radius=inflation_radius, cost_scaling_factor=cost_scaling_factor)
    cir = cell_distance(float(inflation_radius), float(resolution))
    if not enabled or cir == 0 or master.size == 0:
        return master
    lut = cost_lut(cir, float(resolution), float(inscribed_radius), float(cost_scaling_factor))
    dist = distance_map(master, inflate_around_unknown, sqrt)
    _apply_inflation(master, dist, cir, lut, bool(inflate_unknown), arith.fuses("lut_index"))
    return master


# -------------------------------------------------------------- the breadth-first layer
@lru_cache(maxsize=64)
def legacy_tables(cell_inflation_radius: int, resolution: float, inscribed_radius: float,
                  cost_scaling_factor: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """``LegacyInflationLayer::computeCaches`` and ``generateIntegerDistances``.

    Returns ``(distances, costs, levels)``, each indexed ``[|dx|, |dy|]``:
    ``distances`` = ``hypot(dx, dy)`` (C's, double, for dx, dy < cir + 2), ``costs`` =
    ``computeCost`` of those, and ``levels`` = the bin of an offset: the rank of
    ``dx^2 + dy^2`` among the distinct squared lengths ``<= r^2`` of integer offsets,
    ``r = cir + 2`` (offset (0, 0) is bin 0).  Read-only (cached).
    """
    n = cell_inflation_radius + 2  # cache_length_
    ij = np.arange(n, dtype=np.float64)
    distances = np.hypot.outer(ij, ij)  # numpy's hypot is the C library's
    costs = np.empty((n, n), np.uint8)
    for i in range(n):
        for j in range(i, n):  # hypot is symmetric, and so is the cost
            costs[i, j] = costs[j, i] = compute_cost(float(distances[i, j]), resolution, inscribed_radius,
                                                     cost_scaling_factor)
    r = n
    sq = np.add.outer(np.arange(r + 1) ** 2, np.arange(r + 1) ** 2)
    distinct = np.unique(sq[sq <= r * r])
    levels = np.searchsorted(distinct, sq).astype(np.int64)  # offsets beyond r are never looked up
    for a in (distances, costs, levels):
        a.setflags(write=False)
    return distances, costs, levels


@njit(cache=True)
def _grow(a, n):
    b = np.empty(max(2 * a.shape[0], n), a.dtype)
    b[: a.shape[0]] = a
    return b


@njit(cache=True)
def _legacy_update(master, cir, distances, costs, levels, inflate_unknown, inflate_around_unknown):
    """``LegacyInflationLayer::updateCosts`` with the whole map as its window.

    The bins ``inflation_cells_[level]`` are FIFO lists, here linked lists in one arena
    (``nx, ny, nsx, nsy, nxt``).  Bins are processed in increasing level; a cell enqueued
    into the bin being processed is processed in the same pass, one enqueued into an
    earlier bin never is (C++ appends it to a bin whose loop has finished).
    Neighbour order: ``x-1, y-1, x+1, y+1``.  ``enqueue`` skips seen cells and cells whose
    ``distances[|dx|, |dy|]`` (double) exceeds ``cir`` (as a double).
    """
    h, w = master.shape
    n_levels = int(levels.max()) + 1
    head = np.full(n_levels, -1, np.int64)
    tail = np.full(n_levels, -1, np.int64)
    cap = max(16, h * w // 2)
    nx = np.empty(cap, np.int64)
    ny = np.empty(cap, np.int64)
    nsx = np.empty(cap, np.int64)
    nsy = np.empty(cap, np.int64)
    nxt = np.empty(cap, np.int64)
    count = 0
    seen = np.zeros((h, w), np.bool_)
    cir_d = np.float64(cir)
    current = 0

    for j in range(h):  # the obstacle scan, row by row: bin 0, each cell its own source
        for i in range(w):
            c = master[j, i]
            if c == LETHAL_OBSTACLE or (inflate_around_unknown and c == NO_INFORMATION):
                if count == nx.shape[0]:
                    nx, ny, nsx, nsy, nxt = (_grow(nx, count + 1), _grow(ny, count + 1), _grow(nsx, count + 1),
                                             _grow(nsy, count + 1), _grow(nxt, count + 1))
                nx[count], ny[count], nsx[count], nsy[count], nxt[count] = i, j, i, j, -1
                if tail[0] == -1:
                    head[0] = count
                else:
                    nxt[tail[0]] = count
                tail[0] = count
                count += 1

    for current in range(n_levels):
        node = head[current]
        while node != -1:
            mx, my, sx, sy = nx[node], ny[node], nsx[node], nsy[node]
            if seen[my, mx]:
                node = nxt[node]
                continue
            seen[my, mx] = True
            master[my, mx] = _write_cost(master[my, mx], costs[abs(mx - sx), abs(my - sy)], inflate_unknown)
            for k in range(4):
                if k == 0:
                    if mx == 0:
                        continue
                    ex, ey = mx - 1, my
                elif k == 1:
                    if my == 0:
                        continue
                    ex, ey = mx, my - 1
                elif k == 2:
                    if mx >= w - 1:
                        continue
                    ex, ey = mx + 1, my
                else:
                    if my >= h - 1:
                        continue
                    ex, ey = mx, my + 1
                if seen[ey, ex]:
                    continue
                dx, dy = abs(ex - sx), abs(ey - sy)
                if distances[dx, dy] > cir_d:
                    continue
                lev = levels[dx, dy]
                if lev < current:
                    continue  # appended to a finished bin: never processed in this update
                if count == nx.shape[0]:
                    nx, ny, nsx, nsy, nxt = (_grow(nx, count + 1), _grow(ny, count + 1), _grow(nsx, count + 1),
                                             _grow(nsy, count + 1), _grow(nxt, count + 1))
                nx[count], ny[count], nsx[count], nsy[count], nxt[count] = ex, ey, sx, sy, -1
                if tail[lev] == -1:
                    head[lev] = count
                else:
                    nxt[tail[lev]] = count
                tail[lev] = count
                count += 1
            node = nxt[node]  # read after the appends: the bin may have grown past this cell


def inflate_legacy(
    costmap,
    resolution: float,
    inscribed_radius: float,
    inflation_radius: float = 0.55,
    cost_scaling_factor: float = 10.0,
    inflate_unknown: bool = False,
    inflate_around_unknown: bool = False,
    enabled: bool = True,
) -> np.ndarray:
    """``LegacyInflationLayer::updateCosts`` (``InflationLayer`` up to Kilted) over the whole map.

    Same parameters and defaults as :func:`inflate_current`; returns a new array.
    """
    master = _check_costmap(costmap).copy()
    _check_numbers(resolution=resolution, inscribed_radius=inscribed_radius,
                   inflation_radius=inflation_radius, cost_scaling_factor=cost_scaling_factor)
    cir = cell_distance(float(inflation_radius), float(resolution))
    if not enabled or cir == 0 or master.size == 0:
        return master
    distances, costs, levels = legacy_tables(cir, float(resolution), float(inscribed_radius),
                                             float(cost_scaling_factor))
    _legacy_update(master, cir, distances, costs, levels, bool(inflate_unknown), bool(inflate_around_unknown))
    return master
