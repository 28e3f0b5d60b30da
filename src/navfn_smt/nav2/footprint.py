"""The robot's inscribed and circumscribed radius, as Nav2's costmap derives them.

The chain (``Costmap2DROS::getParameters`` / ``on_configure`` / ``setRobotFootprint``, the
same in Humble through Rolling):

1. the ``footprint`` parameter (a *string*) is used when it is neither ``""`` nor ``"[]"``
   and parses (``makeFootprintFromString``: ``nav2_util::parseVVF`` reads every number with
   ``std::istream >> float``, i.e. the decimal rounded once to **float32**; at least three
   points of exactly two numbers); otherwise ``makeFootprintFromRadius(robot_radius)``: 16
   points ``(cos(a) * r, sin(a) * r)``, ``a = i * 2 * M_PI / 16``, all in **double**.  A
   footprint that arrives as a ``geometry_msgs/Polygon`` (the ``footprint`` topic) has
   ``Point32`` coordinates, float32 as well;
2. ``padFootprint`` with ``footprint_padding``, a **float** member (the double parameter
   narrowed): ``x += sign0(x) * padding`` per coordinate, in double (``sign0`` is 0 only
   for an exact 0, so ``cos(pi/2) * r = 6e-18 * r`` is padded like a positive x);
3. ``LayeredCostmap::setFootprint`` -> ``calculateMinAndMaxDistances`` (double): over every
   vertex and every edge (closing edge included), the minimum and maximum of the vertex's
   distance to the origin and the edge's ``distanceToLine`` to the origin.  Fewer than three
   points give ``(DBL_MAX, 0.0)``.

``cos`` and ``sin`` are the C library's (glibc), called through ``math``; they agree between
x86-64's and arm64's glibc 2.36 on the 16 angles of step 1.  ``hypot`` is glibc's as the
build's libm computes it, with the kernel the layers build was found to use
(:mod:`~navfn_smt.spec.libm`, ``LayersArithmetic.hypot``): arm64's differs by an ulp.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass
from fractions import Fraction
from typing import Optional, Sequence

import numpy as np

from ..errors import NavfnInputError
from ..spec.arithmetic import LAYERS_X86_64, LayersArithmetic
from ..spec.constants import DBL_MAX
from ..spec.libm import glibc_hypot
from ..spec.numeric import c_fma

DEFAULT_ROBOT_RADIUS = 0.1  # Costmap2DROS: robot_radius (double); nav2_bringup sets 0.22
DEFAULT_FOOTPRINT_PADDING = 0.01  # Costmap2DROS: footprint_padding, held as float
RADIUS_POINTS = 16  # makeFootprintFromRadius: N

def c_hypot(x: float, y: float, arith: LayersArithmetic = LAYERS_X86_64) -> float:
    """C's ``hypot(double, double)`` as the build's libm computes it (glibc's, with the kernel of
    ``arith``; not Python's own ``math.hypot``)."""
    return glibc_hypot(x, y, arith.hypot)


def _std_min(a: float, b: float) -> float:
    return b if b < a else a  # std::min(a, b)


def _std_max(a: float, b: float) -> float:
    return b if a < b else a  # std::max(a, b)


@dataclass(frozen=True)
class RobotFootprint:
    """The padded footprint and its radii as ``LayeredCostmap`` stores them (all double)."""

    points: tuple[tuple[float, float], ...]  # padded, as handed to LayeredCostmap::setFootprint
    inscribed_radius: float
    circumscribed_radius: float
    source: str  # "robot_radius" or "footprint"
    padding: float  # the float32 padding, as a double


# ---------------------------------------------------------------------------- the points
def footprint_from_radius(radius: float) -> list[tuple[float, float]]:
    """``makeFootprintFromRadius(double radius)``: 16 points on the circle, double.

    ``angle = i * 2 * M_PI / N``: ``i * 2`` is an int, the product with ``M_PI`` and the
    division by ``N`` are double; ``cos(angle) * radius`` and ``sin(angle) * radius``.
    """
    pts = []
    for i in range(RADIUS_POINTS):
        angle = float(i * 2) * math.pi / float(RADIUS_POINTS)
        pts.append((math.cos(angle) * radius, math.sin(angle) * radius))
    return pts


def decimal_to_float32(token: str) -> float:
    """``std::istream >> float`` on one number token: the decimal rounded once to float32.

    (libstdc++ hands the token to ``strtof``: correctly rounded, ties to even.)  Going through
    a double first could round twice; here the nearest float32 is chosen exactly.
    """
    exact = Fraction(token)
    with np.errstate(over="ignore"):
        guess = np.float32(float(token))
    if not np.isfinite(guess):
        raise ValueError(f"{token!r} is out of the float range")
    best = guess
    for cand in (np.nextafter(guess, np.float32(-np.inf)), np.nextafter(guess, np.float32(np.inf))):
        if not np.isfinite(cand):
            continue
        d_best, d_cand = abs(Fraction(float(best)) - exact), abs(Fraction(float(cand)) - exact)
        if d_cand < d_best or (d_cand == d_best and int(cand.view(np.uint32)) % 2 == 0):
            best = cand
    return float(best)


def _scan_number(s: str, i: int) -> tuple[str, int]:
    """The characters libstdc++'s ``num_get`` collects for a float from position ``i``.

    An optional sign, digits with at most one decimal point, then optionally ``e``/``E``, a
    sign and digits.  Returns the token and the position after it.
    """
    j = i
    if j < len(s) and s[j] in "+-":
        j += 1
    seen_dot = False
    while j < len(s) and (s[j].isdigit() and s[j].isascii() or (s[j] == "." and not seen_dot)):
        seen_dot = seen_dot or s[j] == "."
        j += 1
    if j < len(s) and s[j] in "eE":
        j += 1
        if j < len(s) and s[j] in "+-":
            j += 1
        while j < len(s) and s[j].isdigit() and s[j].isascii():
            j += 1
    return s[i:j], j


_NUMBER = re.compile(r"[+-]?(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?", re.ASCII)


def parse_vvf(text: str) -> list[list[float]]:
    """``nav2_util::parseVVF``: ``[[1.0, 2.0], [3.3, 4.4, 5.5], ...]`` into float32 values.

    Raises ValueError with parseVVF's message when it would set its error string (depth
    above 2, more ``]`` than ``[``, a number outside depth 2, a token ``>> float`` rejects,
    which ends the loop and so leaves the string "unterminated").
    """
    result: list[list[float]] = []
    current: list[float] = []
    depth, i = 0, 0
    while i < len(text):
        c = text[i]
        if c == "[":
            depth += 1
            if depth > 2:
                raise ValueError("Array depth greater than 2")
            current = []
            i += 1
        elif c == "]":
            depth -= 1
            if depth < 0:
                raise ValueError("More close ] than open [")
            if depth == 1:
                result.append(current)
            i += 1
        elif c in ", \t":
            i += 1
        else:
            if depth != 2:
                raise ValueError(f"Numbers at depth other than 2. Char was '{c}'.")
            token, i = _scan_number(text, i)
            if not _NUMBER.fullmatch(token):
                raise ValueError("Unterminated vector string.")  # failbit ends the loop
            current.append(decimal_to_float32(token))
    if depth != 0:
        raise ValueError("Unterminated vector string.")
    return result


def footprint_from_string(text: str) -> list[tuple[float, float]]:
    """``makeFootprintFromString``: at least three points of two float32 numbers each."""
    vvf = parse_vvf(text)
    if len(vvf) < 3:
        raise ValueError("You must specify at least three points for the robot footprint")
    for v in vvf:
        if len(v) != 2:
            raise ValueError(f"Points in the footprint specification must be pairs of numbers. "
                             f"Found a point with {len(v)} numbers.")
    return [(v[0], v[1]) for v in vvf]


def footprint_from_points(points: Sequence[Sequence[float]]) -> list[tuple[float, float]]:
    """A footprint given as ``geometry_msgs/Point32`` pairs: each coordinate narrowed to float32."""
    out = []
    for p in points:
        if len(p) != 2:
            raise ValueError(f"footprint points must be pairs (x, y), got {p!r}")
        out.append((float(np.float32(p[0])), float(np.float32(p[1]))))
    if len(out) < 3:
        raise ValueError("You must specify at least three points for the robot footprint")
    return out


# ---------------------------------------------------------------------- padding and radii
def sign0(x: float) -> float:
    """``sign0(double)``: -1, 0 or 1 (0 only for +-0.0)."""
    return -1.0 if x < 0.0 else (1.0 if x > 0.0 else 0.0)


def pad_footprint(points, padding: float) -> list[tuple[float, float]]:
    """``padFootprint(footprint, double padding)``: ``x += sign0(x) * padding``, double."""
    return [(x + sign0(x) * padding, y + sign0(y) * padding) for x, y in points]


def distance_to_line(px, py, x0, y0, x1, y1, arith: LayersArithmetic = LAYERS_X86_64) -> float:
    """``distanceToLine`` (costmap_math.cpp), double: the distance to the segment's nearest point;
    its four multiply-adds rounded once where the build fused them (site ``distance_to_line``),
    each sum with the product the build fused."""
    a, b = px - x0, py - y0
    c, d = x1 - x0, y1 - y0
    fused = arith.fuses("distance_to_line")
    if fused:
        dot = c_fma(a, c, b * d) if arith.dot == "A" else c_fma(b, d, a * c)
        len_sq = c_fma(c, c, d * d) if arith.len_sq == "C" else c_fma(d, d, c * c)
    else:
        dot = a * c + b * d
        len_sq = c * c + d * d
    try:
        param = dot / len_sq
    except ZeroDivisionError:  # C: x/0 -> +-inf, 0/0 -> nan
        param = math.nan if dot == 0 or dot != dot else math.copysign(math.inf, dot)
    if param < 0:
        xx, yy = x0, y0
    elif param > 1:
        xx, yy = x1, y1
    elif fused:  # also for a NaN param, as in C
        xx, yy = c_fma(param, c, x0), c_fma(param, d, y0)
    else:
        xx, yy = x0 + param * c, y0 + param * d
    return c_hypot(xx - px, yy - py, arith)  # distance(pX, pY, xx, yy) = hypot(x1 - x0, y1 - y0)


def min_max_distances(points, arith: LayersArithmetic = LAYERS_X86_64) -> tuple[float, float]:
    """``calculateMinAndMaxDistances``: (inscribed, circumscribed) radius, double, in the layers
    build's arithmetic ``arith``."""
    min_dist, max_dist = DBL_MAX, 0.0
    if len(points) <= 2:
        return min_dist, max_dist
    n = len(points)
    for i in range(n):  # the last iteration is the closing edge (back -> front)
        (x0, y0), (x1, y1) = points[i], points[(i + 1) % n]
        vertex = c_hypot(x0 - 0.0, y0 - 0.0, arith)
        edge = distance_to_line(0.0, 0.0, x0, y0, x1, y1, arith)
        min_dist = _std_min(min_dist, _std_min(vertex, edge))
        max_dist = _std_max(max_dist, _std_max(vertex, edge))
    return min_dist, max_dist


def float32_padding(footprint_padding: float) -> float:
    """``float footprint_padding_``: the parameter narrowed to float32, returned as a double.  As
    the C++ conversion (``cvtsd2ss``), a double beyond float's range becomes infinite, silently."""
    with np.errstate(over="ignore"):
        return float(np.float32(footprint_padding))


def robot_footprint(
    robot_radius: float = DEFAULT_ROBOT_RADIUS,
    footprint=None,
    footprint_padding: float = DEFAULT_FOOTPRINT_PADDING,
    strict: bool = True,
    arith: LayersArithmetic = LAYERS_X86_64,
) -> RobotFootprint:
    """The padded footprint and its radii for the costmap parameters, as ``Costmap2DROS`` sets them.

    ``footprint``: None, a string (the ROS parameter; ``""`` and ``"[]"`` mean "use the
    radius"), or a sequence of (x, y) pairs taken as ``Point32`` (float32).  A string Nav2
    cannot parse makes Nav2 log an error and use ``robot_radius``; with ``strict`` (the
    default) it raises :class:`NavfnInputError` instead.  The radii are computed in the layers
    build's arithmetic ``arith``.
    """
    source = "robot_radius"
    points = None
    if isinstance(footprint, str):
        if footprint not in ("", "[]"):
            try:
                points = footprint_from_string(footprint)
                source = "footprint"
            except ValueError as e:
                if strict:
                    raise NavfnInputError(f"'footprint': cannot parse {footprint!r}: {e} "
                                          f"(Nav2 would log this and fall back to robot_radius)") from None
    elif footprint is not None:
        try:
            points = footprint_from_points(footprint)
        except (TypeError, ValueError) as e:
            raise NavfnInputError(f"'footprint': {e}") from None
        source = "footprint"
    if points is None:
        points = footprint_from_radius(float(robot_radius))
    padding = float32_padding(footprint_padding)
    padded = pad_footprint(points, padding)
    inscribed, circumscribed = min_max_distances(padded, arith)
    return RobotFootprint(tuple(padded), inscribed, circumscribed, source, padding)


def inscribed_radius(robot_radius: float = DEFAULT_ROBOT_RADIUS, footprint=None,
                     footprint_padding: float = DEFAULT_FOOTPRINT_PADDING,
                     custom_inscribed_radius: Optional[float] = None) -> float:
    """The inscribed radius an inflation layer uses (``LayeredCostmap::getInscribedRadius``).

    ``custom_inscribed_radius`` >= 0 replaces it (the new InflationLayer's parameter,
    Lyrical/Rolling; a negative value, the default -1.0, means "use the footprint's").
    """
    if custom_inscribed_radius is not None and custom_inscribed_radius >= 0.0:
        return float(custom_inscribed_radius)
    return robot_footprint(robot_radius, footprint, footprint_padding).inscribed_radius
