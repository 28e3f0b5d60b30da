"""Where ``NavfnPlanner``'s own code (not NavFn's) misbehaves: the inputs, found and proved with
Z3 over IEEE binary64 (``Float64``, round-nearest-even), as :mod:`navfn_smt.smt` does for float32.

All the plugin's arithmetic is double; Python's ``float`` is the same IEEE binary64 with the same
rounding, so every number here is checked twice: by Z3 on the exact expression and by running
:mod:`navfn_smt.nav2.plugin` (which the findings then exercise end to end, see
``tests/data/plugin_cases``).

* :func:`offmap_interval`: the world coordinates that pass ``Costmap2D::worldToMap`` (the
  truncating one ``createPlan`` checks) but fail ``NavfnPlanner::worldToMap`` (the rounding one
  ``makePlan`` uses unchecked) form exactly ``[lo, hi)``; Z3 finds both ends (the one double where
  the property switches on/off: ``P(w) and not P(w-)``) and proves the characterisation with three
  unsat queries.
* :func:`stall_threshold`: the smallest positive double ``p`` from which the tolerance loop's
  ``p += resolution`` no longer moves (Nav2 then loops forever).
* :func:`loop_cells`: the cells the tolerance loop visits on one axis (20 points for Nav2's
  defaults, tolerance 0.5 and resolution float32(0.05): the window is one-sided).
* :func:`tolerance_gap`: a goal whose tolerance loop skips a map column (two consecutive points
  of the loop round two cells apart).
* :func:`write_case` / :func:`replay_case`: a finding as a directory a map_server and Nav2 could
  load (map YAML + PGM, params YAML) and ``case.json`` with the poses and ``create_plan``'s outcome.
"""

from __future__ import annotations

import json
import math
import struct
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Optional

import numpy as np

from .plugin import Costmap, Pose, costmap_axis_cell, create_plan, plugin_axis_cell

# --------------------------------------------------------------------------- doubles in order
MASK63 = (1 << 63) - 1


def ordinal(x: float) -> int:
    """The position of a double in the order of all doubles (monotone; -0.0 and 0.0 both 0)."""
    b = struct.unpack("<Q", struct.pack("<d", x))[0]
    return -(b & MASK63) if b >> 63 else b


def from_ordinal(i: int) -> float:
    b = (-i) | (1 << 63) if i < 0 else i
    return struct.unpack("<d", struct.pack("<Q", b))[0]


def next_up(x: float) -> float:
    return math.nextafter(x, math.inf)


def next_down(x: float) -> float:
    return math.nextafter(x, -math.inf)


def hexf(x: float) -> str:
    return float(x).hex()


# --------------------------------------------------------------------------- the two worldToMap
def passes_truncating(w: float, origin: float, res: float, size: int) -> bool:
    """``Costmap2D::worldToMap`` on one axis (the quotient below 2^32, where the cast is defined)."""
    return costmap_axis_cell(w, origin, res, size) is not None


def rounds_off(w: float, origin: float, res: float, size: int) -> bool:
    """``NavfnPlanner::worldToMap`` fails on this axis although ``w >= origin`` (std::round = half away)."""
    return plugin_axis_cell(w, origin, res) >= size


def offmap(w: float, origin: float, res: float, size: int) -> bool:
    """Passes createPlan's bounds check, rounds one past the edge in makePlan."""
    return passes_truncating(w, origin, res, size) and rounds_off(w, origin, res, size)


def _z3():
    import z3

    return z3


def _fp(v: float):
    z3 = _z3()
    return z3.FPVal(float(v), z3.Float64())


def z3_offmap(w, origin: float, res: float, size: int):
    """The property as Z3 terms: ``w >= o``, ``q = (w - o) / res`` (RNE), ``trunc(q) < size``
    (roundToIntegral RTZ) and ``round(q) >= size`` (roundToIntegral RNA = std::round)."""
    z3 = _z3()
    q = z3.fpDiv(z3.RNE(), z3.fpSub(z3.RNE(), w, _fp(origin)), _fp(res))
    n = _fp(float(size))
    return z3.And(z3.Not(z3.fpIsNaN(w)), z3.Not(z3.fpIsInf(w)), z3.fpGEQ(w, _fp(origin)),
                  z3.fpLT(z3.fpRoundToIntegral(z3.RTZ(), q), n),
                  z3.fpGEQ(z3.fpRoundToIntegral(z3.RNA(), q), n))


def _z3_neighbour(bits, up: bool):
    """The double next to the one with these IEEE bits (toward +inf when ``up``), as bits."""
    z3 = _z3()
    one = z3.BitVecVal(1, 64)
    sign = z3.Extract(63, 63, bits) == z3.BitVecVal(1, 1)
    is_zero = (bits & z3.BitVecVal(MASK63, 64)) == z3.BitVecVal(0, 64)
    if up:  # -0/+0 -> smallest positive subnormal
        return z3.If(is_zero, one, z3.If(sign, bits - one, bits + one))
    return z3.If(is_zero, z3.BitVecVal((1 << 63) | 1, 64), z3.If(sign, bits + one, bits - one))


@dataclass
class Query:
    name: str
    verdict: str
    seconds: float
    model: Optional[float] = None


@dataclass
class Interval:
    """``{w : offmap(w)} == [lo, hi)`` on one axis of a map, with the queries that show it."""

    origin: float
    resolution: float
    size: int
    lo: float
    hi: float
    queries: list = field(default_factory=list)

    @property
    def proved(self) -> bool:
        want = {"lower end": "sat", "upper end": "sat",
                "none below lo": "unsat", "none at or above hi": "unsat", "all of [lo, hi)": "unsat"}
        got = {q.name: q.verdict for q in self.queries}
        return all(got.get(k, v) == v for k, v in want.items()) and all(k in got for k in list(want)[2:])

    def as_dict(self) -> dict:
        return {"origin": self.origin, "resolution": self.resolution, "size": self.size,
                "lo": hexf(self.lo), "hi": hexf(self.hi), "lo_decimal": repr(self.lo), "hi_decimal": repr(self.hi),
                "proved": self.proved,
                "queries": [{"name": q.name, "verdict": q.verdict, "seconds": round(q.seconds, 2),
                             **({"model": hexf(q.model)} if q.model is not None else {})} for q in self.queries]}


def _check(name: str, constraints, var=None, timeout: float = 120.0) -> Query:
    z3 = _z3()
    s = z3.Solver()
    s.set("timeout", int(timeout * 1000))
    s.add(*constraints)
    t = time.perf_counter()
    r = s.check()
    q = Query(name, str(r), time.perf_counter() - t)
    if r == z3.sat and var is not None:
        q.model = _model_double(s.model(), var)
    return q


def _model_double(model, var) -> float:
    z3 = _z3()
    v = model.eval(var, model_completion=True)
    if z3.is_bv(v):
        return struct.unpack("<d", struct.pack("<Q", v.as_long()))[0]
    bits = model.eval(z3.fpToIEEEBV(var), model_completion=True).as_long()
    return struct.unpack("<d", struct.pack("<Q", bits))[0]


def offmap_interval_numeric(origin: float, res: float, size: int) -> tuple[float, float]:
    """``[lo, hi)`` by walking the doubles around the real-number ends ``o + (size - 1/2) res`` and
    ``o + size res`` (exact: Python floats are binary64 with RNE)."""
    def first_true(x):  # smallest double >= some start where offmap holds, from an estimate
        while offmap(x, origin, res, size):
            x = next_down(x)
        while not offmap(x, origin, res, size):
            x = next_up(x)
        return x

    lo = first_true(origin + (size - 0.5) * res)
    hi = origin + size * res
    while offmap(hi, origin, res, size):
        hi = next_up(hi)
    while not offmap(next_down(hi), origin, res, size):
        hi = next_down(hi)
    return lo, hi


def offmap_interval(origin: float, res: float, size: int, prove: bool = True, find: bool = True,
                    timeout: float = 120.0) -> Interval:
    """Z3 finds the ends (``find``): a double ``w`` with ``P(w)`` and not ``P`` of the double below
    (the lower end) or above (the upper end, ``hi`` is the double after it); then (``prove``) that
    ``P`` holds for no double below ``lo``, for none at or above ``hi``, and for every double in
    ``[lo, hi)``.  Without ``find`` the ends come from :func:`offmap_interval_numeric` and are only
    proved."""
    z3 = _z3()
    lo, hi = offmap_interval_numeric(origin, res, size)
    iv = Interval(origin, res, size, lo, hi)
    if find:
        bits = z3.BitVec("b", 64)
        w = z3.fpBVToFP(bits, z3.Float64())
        for name, up in (("lower end", False), ("upper end", True)):
            nb = z3.fpBVToFP(_z3_neighbour(bits, up), z3.Float64())
            q = _check(name, [z3_offmap(w, origin, res, size), z3.Not(z3_offmap(nb, origin, res, size))], bits, timeout)
            iv.queries.append(q)
            if q.model is None:
                continue
            end = q.model if not up else next_up(q.model)
            if up:
                iv.hi = end
            else:
                iv.lo = end
    if prove:
        w = z3.FP("w", z3.Float64())
        p = z3_offmap(w, origin, res, size)
        iv.queries.append(_check("none below lo", [p, z3.fpLT(w, _fp(iv.lo))], w, timeout))
        iv.queries.append(_check("none at or above hi", [p, z3.fpGEQ(w, _fp(iv.hi))], w, timeout))
        iv.queries.append(_check("all of [lo, hi)", [z3.Not(p), z3.fpGEQ(w, _fp(iv.lo)), z3.fpLT(w, _fp(iv.hi))],
                                 w, timeout))
    return iv


# --------------------------------------------------------------------------- cell centres
def centre_cells(origin: float, res: float, size: int) -> np.ndarray:
    """For each cell ``i``, the cell ``NavfnPlanner::worldToMap`` gives its centre
    ``origin + (i + 0.5) * res`` (computed in double): ``i + 1`` when the quotient comes out at
    ``i + 0.5`` or above, ``i`` when rounding made it fall below."""
    return np.array([plugin_axis_cell(origin + (i + 0.5) * res, origin, res) for i in range(size)], dtype=np.int64)


# --------------------------------------------------------------------------- the tolerance loop
@dataclass
class Stall:
    resolution: float
    threshold: float  # the smallest positive double p with p + res == p
    queries: list = field(default_factory=list)


def stall_threshold(res: float, timeout: float = 60.0) -> Stall:
    """The smallest positive ``p`` with ``fl(p + res) == p``: Z3 gives the only double ``p >= 0``
    where the loop stalls and the double below does not; then "a stalling ``p`` in ``[0, t)``" is
    unsat and "a ``p >= t`` that moves" is unsat (once the spacing of doubles exceeds ``2 res`` no
    addition of ``res`` moves)."""
    z3 = _z3()
    D = z3.Float64()
    bits = z3.BitVec("b", 64)
    p = z3.fpBVToFP(bits, D)
    below = z3.fpBVToFP(_z3_neighbour(bits, False), D)

    def stalls(x):
        return z3.And(z3.Not(z3.fpIsNaN(x)), z3.Not(z3.fpIsInf(x)), z3.fpEQ(z3.fpAdd(z3.RNE(), x, _fp(res)), x))

    st = Stall(res, math.nan)
    q = _check("first stalling double", [z3.fpGT(p, _fp(0.0)), stalls(p), z3.Not(stalls(below))], bits, timeout)
    st.queries.append(q)
    if q.model is None:
        return st
    st.threshold = q.model
    w = z3.FP("p", D)
    st.queries.append(_check("no stall in [0, t)", [z3.fpGEQ(w, _fp(0.0)), z3.fpLT(w, _fp(st.threshold)), stalls(w)],
                             w, timeout))
    st.queries.append(_check("every p >= t stalls", [z3.fpGEQ(w, _fp(st.threshold)), z3.Not(z3.fpIsInf(w)),
                                                    z3.Not(stalls(w))], w, timeout))
    return st


def loop_cells(g: float, tolerance: float, origin: float, res: float) -> list:
    """The cells (one axis, std::round, off-map ones included) the tolerance loop's points round to."""
    from .plugin import tolerance_steps

    return [plugin_axis_cell(p, origin, res) for p in tolerance_steps(g - tolerance, g + tolerance, res).tolist()]


def tolerance_gap(origin: float, res: float, tolerance: float, lo: float, hi: float,
                  timeout: float = 300.0) -> Optional[dict]:
    """Z3: a goal ``g`` in ``[lo, hi]`` whose tolerance loop's first two points round to cells two
    apart (``round((p1 - o)/res) - round((p0 - o)/res) == 2`` with ``p0 = g - tol``,
    ``p1 = p0 + res``): the column between them is never examined.  Returns the goal and the cells
    the loop visits, or None (unsat or unknown)."""
    z3 = _z3()
    D = z3.Float64()
    rne = z3.RNE()
    g = z3.FP("g", D)
    p0 = z3.fpSub(rne, g, _fp(tolerance))
    p1 = z3.fpAdd(rne, p0, _fp(res))

    def cell(p):
        return z3.fpRoundToIntegral(z3.RNA(), z3.fpDiv(rne, z3.fpSub(rne, p, _fp(origin)), _fp(res)))

    q = _check("skipped column", [z3.fpGEQ(g, _fp(lo)), z3.fpLEQ(g, _fp(hi)), z3.fpGEQ(p0, _fp(origin)),
                                  z3.fpEQ(z3.fpSub(rne, cell(p1), cell(p0)), _fp(2.0))], g, timeout)
    if q.model is None:
        return {"goal": None, "query": q}
    return {"goal": q.model, "cells": loop_cells(q.model, tolerance, origin, res), "query": q}


# --------------------------------------------------------------------------- case directories
PIXEL = {0: 254, 254: 0, 255: 205}  # trinary map_server image values for free, lethal, unknown


def write_case(root, name: str, ros: np.ndarray, origin: tuple, resolution: str, start: Pose, goal: Pose,
               params: dict, note: str, backend: str = "jit") -> dict:
    """Write ``root/name``: ``map.yaml`` + ``map.pgm`` (trinary, row 0 of ``ros`` at the image's
    bottom), ``params.yaml`` (a ``planner_server`` section), ``case.json`` (poses, the note, and the
    outcome of :func:`create_plan` on the loaded files).  ``ros`` holds costmap values 0/254/255."""
    d = Path(root) / name
    d.mkdir(parents=True, exist_ok=True)
    ros = np.asarray(ros, dtype=np.uint8)
    h, w = ros.shape
    img = np.vectorize(PIXEL.__getitem__, otypes=[np.uint8])(ros)[::-1]
    (d / "map.pgm").write_bytes(b"P5\n%d %d\n255\n" % (w, h) + np.ascontiguousarray(img).tobytes())
    (d / "map.yaml").write_text(f"image: map.pgm\nmode: trinary\nresolution: {resolution}\n"
                                f"origin: [{origin[0]!r}, {origin[1]!r}, 0.0]\nnegate: 0\n"
                                f"occupied_thresh: 0.65\nfree_thresh: 0.196\n")
    lines = ["planner_server:", "  ros__parameters:", "    expected_planner_frequency: 20.0",
             "    planner_plugins: [\"GridBased\"]", "    GridBased:",
             "      plugin: \"nav2_navfn_planner::NavfnPlanner\""]
    for k, v in params.items():
        lines.append(f"      {k}: {_yaml_scalar(v)}")
    (d / "params.yaml").write_text("\n".join(lines) + "\n")
    case = {"note": note, "start": _pose_json(start), "goal": _pose_json(goal)}
    (d / "case.json").write_text(json.dumps(case, indent=1) + "\n")
    case["expected"] = outcome(run_case(d, backend))
    (d / "case.json").write_text(json.dumps(case, indent=1) + "\n")
    return case


def _yaml_scalar(v) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    return repr(v)


def _pose_json(p: Pose) -> dict:
    return {"x": p.x, "y": p.y, "x_hex": hexf(p.x), "y_hex": hexf(p.y), "orientation": list(p.orientation)}


def _pose_from_json(d: dict) -> Pose:
    return Pose(float.fromhex(d["x_hex"]), float.fromhex(d["y_hex"]), *map(float, d["orientation"]))


def load_case(d) -> tuple[Costmap, Pose, Pose, object, dict]:
    from .mapserver import load_map_yaml
    from .params import planner_params
    from .plugin import costmap_from_map

    d = Path(d)
    case = json.loads((d / "case.json").read_text())
    cm = costmap_from_map(load_map_yaml(d / "map.yaml"))
    return cm, _pose_from_json(case["start"]), _pose_from_json(case["goal"]), planner_params(d / "params.yaml"), case


def run_case(d, backend: str = "jit"):
    """``create_plan`` on a case directory; a NavfnInputError (a loop the plugin model refuses to
    run because Nav2's would not end) comes back as the outcome ``{"raises": ..., "message": ...}``."""
    from ..errors import NavfnInputError

    cm, start, goal, params, _ = load_case(d)
    try:
        return create_plan(cm, start, goal, params, backend=backend)
    except NavfnInputError as e:
        return {"raises": "NavfnInputError", "message": str(e)}


def outcome(run) -> dict:
    """What a replay compares: the published poses (hex, exact), the exception and its message,
    the cells the plugin's two worldToMap gave, the tolerance search's result, the log."""
    if isinstance(run, dict):
        return run
    cell = (lambda c: None if c is None else [int(c[0]), int(c[1])])
    return {
        "error": run.error,
        "message": run.message,
        "poses": [[hexf(p.x), hexf(p.y)] + [hexf(v) for v in p.orientation] for p in run.poses],
        "start_cell": cell(run.start_cell), "goal_cell": cell(run.goal_cell),
        "robot_cell": cell(run.robot_cell), "target_cell": cell(run.target_cell),
        "reached": run.reached,
        "goal_potential": None if run.goal_potential is None else hexf(run.goal_potential),
        "used_tolerance": run.used_tolerance,
        "best_pose": None if run.best_pose is None else [hexf(run.best_pose.x), hexf(run.best_pose.y)],
        "best_cell": cell(run.best_cell),
        "max_cycles": run.max_cycles,
        "log": list(run.log),
    }


def replay_case(d, backend: str = "jit") -> tuple[dict, dict]:
    """(expected, actual) outcomes of a case directory."""
    case = json.loads((Path(d) / "case.json").read_text())
    return case["expected"], outcome(run_case(d, backend))


# --------------------------------------------------------------------------- the findings as cases
RES = float(np.float32(0.05))  # "resolution: 0.05" in a map YAML, as the costmap holds it
SKIP_GOAL_X = -1.5249998811632401  # found by tolerance_gap(-10.0, RES, 0.5, -9.5, 0.0): column 160 skipped


def _free(w: int, h: int) -> np.ndarray:
    return np.zeros((h, w), dtype=np.uint8)


def build_cases(root, backend: str = "jit") -> dict:
    """Every finding of ``docs/plugin.md`` as a case directory under ``root``; returns the cases."""
    out = {}
    o8 = offmap_interval_numeric(0.0, RES, 8)  # x: the right column's last half cell of an 8-wide map
    o6 = offmap_interval_numeric(0.0, RES, 6)  # y: the top row's of a 6-high map
    y2, y3 = 2 * RES + 0.01, 3 * RES + 0.01  # rows 2 and 3 under both worldToMap
    x2 = 2 * RES + 0.01
    defaults = {"tolerance": 0.5, "use_astar": False, "allow_unknown": True}

    def case(name, ros, origin, start, goal, params, note):
        out[name] = write_case(root, name, ros, origin, "0.05", start, goal, params, note, backend)

    case("robot-right-half-cell", _free(8, 6), (0.0, 0.0), Pose(o8[0], y2), Pose(x2, y3), defaults,
         f"robot at x = lo = {hexf(o8[0])}: createPlan's truncating check gives column 7, the plugin's "
         f"rounding gives column 8 = size_x; NavFn's propagation starts at index 2*8+8 = cell (0, 3); "
         f"the path runs from x = 8 (one past the edge) straight to column 1")
    case("robot-top-half-cell", _free(8, 6), (0.0, 0.0), Pose(x2, o6[0]), Pose(x2, y3), defaults,
         f"robot at y = lo = {hexf(o6[0])}: row 6 = size_y; clearRobotCell writes index 6*8+2 = 50, past "
         f"the 48-cell costmap (undefined behaviour)")
    case("goal-right-half-cell", _free(8, 6), (0.0, 0.0), Pose(x2, y3), Pose(next_down(o8[1]), y2), defaults,
         f"goal at x = hi- = {hexf(next_down(o8[1]))}, the last double of column 7: rounds to column 8, "
         f"getPointPotential is DBL_MAX, the tolerance search picks the nearest point of column 6 "
         f"(column 7 is NavFn's lethal border)")
    case("goal-right-half-cell-tolerance-0", _free(8, 6), (0.0, 0.0), Pose(x2, y3), Pose(o8[0], y2),
         {**defaults, "tolerance": 0.0},
         "the same with tolerance 0: the goal's free, reachable cell (7, 2) gives NoValidPathCouldBeFound")
    case("goal-top-half-cell", _free(8, 6), (0.0, 0.0), Pose(x2, y2), Pose(x2, o6[0]), defaults,
         "goal in the top row's last half cell: NavFn's start is (2, 6), index 50 past potarr (48 cells); "
         "the propagation reads it (undefined behaviour)")
    i = 4
    case("goal-at-cell-centre", _free(8, 6), (0.0, 0.0), Pose(x2, y2), Pose((i + 0.5) * RES, y3), defaults,
         f"goal at the centre of cell {i}, origin + ({i} + 0.5) * res: the plugin plans to cell {i + 1} "
         f"(std::round, half away from zero); the path's last point is the corner of cell {i + 1}, then the goal")
    occ = _free(8, 6)
    occ[3, 4] = 254
    case("goal-occupied-truncated-only", occ, (0.0, 0.0), Pose(x2, y2), Pose(4.75 * RES, y3),
         {**defaults, "tolerance": 0.0},
         "tolerance 0, the goal's truncated cell (4, 3) is lethal, its rounded cell (5, 3) free: "
         "GoalOccupied, although NavFn would plan to (5, 3)")
    occ = _free(8, 6)
    occ[3, 5] = 254
    case("goal-lethal-rounded-only", occ, (0.0, 0.0), Pose(x2, y2), Pose(4.75 * RES, y3),
         {**defaults, "tolerance": 0.0},
         "tolerance 0, the truncated cell (4, 3) free passes the GoalOccupied check; the rounded cell "
         "(5, 3) is lethal: no potential there, NoValidPathCouldBeFound")
    # the one-sided tolerance window: 20 points from g - 0.5 to g + 0.45000001415610313
    ros = np.full((7, 26), 254, np.uint8)
    ros[1:6, 22:25] = 0
    case("tolerance-window-right-edge", ros, (0.0, 0.0), Pose(23.25 * RES, 3.25 * RES),
         Pose(12 * RES, 3 * RES), defaults,
         "goal at the corner of cell (12, 3) (lethal), tolerance 0.5 = 10 cells: the loop visits x = g - 0.5 "
         "... g + 0.45000001415610313 (20 points, columns 2..21); the free cell (22, 3), 10 cells right "
         "of the goal, is never examined: NoValidPathCouldBeFound")
    ros = np.full((7, 26), 254, np.uint8)
    ros[1:6, 1:4] = 0
    case("tolerance-window-left-edge", ros, (0.0, 0.0), Pose(1.25 * RES, 3.25 * RES),
         Pose(13 * RES, 3 * RES), defaults,
         "the mirror image: the free cell (3, 3) 10 cells left of the goal's (13, 3) is examined "
         "(the loop's first column) and planned to")
    # a column the accumulated loop skips
    ros = np.full((7, 182), 254, np.uint8)
    ros[1:6, 160] = 0
    case("tolerance-skipped-column", ros, (-10.0, 0.0), Pose(-10.0 + 160.25 * RES, 1.25 * RES),
         Pose(SKIP_GOAL_X, 3 * RES + 0.01), defaults,
         f"origin x -10, goal x = {hexf(SKIP_GOAL_X)} (Z3): the loop's first point rounds to column 159, "
         f"the second ({hexf(SKIP_GOAL_X - 0.5 + RES)}) to 161; the free column 160 (distance < 0.5 from "
         f"the goal) is never examined: NoValidPathCouldBeFound")
    ros = np.full((7, 182), 254, np.uint8)
    ros[1:6, 160] = 0
    case("tolerance-skipped-column-control", ros, (-10.0, 0.0), Pose(-10.0 + 160.25 * RES, 1.25 * RES),
         Pose(next_up(SKIP_GOAL_X), 3 * RES + 0.01), defaults,
         "the goal one double higher: the loop visits column 160 and plans to it")
    # the loop that never ends
    big = 2.0 ** 49
    ros = _free(8, 6)
    ros[3, 4:6] = 254  # the goal's truncated (4) and rounded (5) cells
    case("tolerance-loop-never-ends", ros, (big, 0.0), Pose(big + 2 * RES, y2), Pose(big + 4 * RES, 3 * RES),
         defaults,
         "origin x = 2^49 = 562949953421312 (the first positive double where p + 0.05f == p), the goal "
         "(2^49 + 0.25: 4 * res rounds to the double spacing 0.125) on a lethal cell: the tolerance loop's x reaches 2^49 and stays there; Nav2 never returns")
    case("max-cycles-overflow", _free(8, 6), (0.0, 0.0), Pose(x2, y2), Pose(5 * RES + 0.01, y3),
         {**defaults, "max_cycles_factor": 268435456},
         "max_cycles = 8 * 268435456 = 2^31 overflows int (undefined behaviour)")
    case("max-cycles-zero", _free(8, 6), (0.0, 0.0), Pose(x2, y2), Pose(5 * RES + 0.01, y3),
         {**defaults, "max_cycles_factor": 0},
         "max_cycles_factor 0: calcPath(0) returns 0, 'Failed to create a plan from potential when a legal "
         "potential was found' then NoValidPathCouldBeFound")
    return out


def main(argv=None) -> int:
    """``python -m navfn_smt.nav2.offmap [CASES_DIR] [--report FILE.json]``: rebuild the case
    directories and (with ``--report``) run every Z3 query of docs/plugin.md (minutes)."""
    import argparse

    ap = argparse.ArgumentParser(prog="python -m navfn_smt.nav2.offmap")
    ap.add_argument("cases", nargs="?")
    ap.add_argument("--report")
    a = ap.parse_args(argv)
    if a.cases:
        for name, c in build_cases(a.cases).items():
            e = c["expected"]
            print(name, e.get("error") or e.get("raises") or f"{len(e['poses'])} poses")
    if a.report:
        rep = {}
        for what, o, n in (("x of an 8x6 map at 0, 0", 0.0, 8), ("y of an 8x6 map at 0, 0", 0.0, 6),
                           ("x of a 400-wide map at -10", -10.0, 400)):
            iv = offmap_interval(o, RES, n)
            rep[what] = iv.as_dict()
            print(what, rep[what])
        st = stall_threshold(RES)
        rep["stall"] = {"threshold": hexf(st.threshold), "decimal": repr(st.threshold),
                        "queries": [(q.name, q.verdict, round(q.seconds, 2)) for q in st.queries]}
        print(rep["stall"])
        gap = tolerance_gap(-10.0, RES, 0.5, -9.5, 0.0)
        rep["gap"] = {"goal": None if gap["goal"] is None else hexf(gap["goal"]), "cells": gap.get("cells"),
                      "verdict": gap["query"].verdict, "seconds": round(gap["query"].seconds, 2)}
        print(rep["gap"])
        rep["centre_cells_8_at_0"] = centre_cells(0.0, RES, 8).tolist()
        rep["centre_cells_400_at_-10"] = int((centre_cells(-10.0, RES, 400) == np.arange(1, 401)).sum())
        Path(a.report).write_text(json.dumps(rep, indent=1) + "\n")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
