"""Metamorphic relations: does NavFn commute with symmetries of the map?

For a transform T of the map and its cells, a relation holds on a case when planning on
T(map) from T(start) to T(goal) gives T of the original result.  NavFn is not symmetric
(the order of pushes, float rounding, the cycle limit and ``calcPath(4 * nx)`` depend on
orientation and size), so the tool measures, per relation, on how many cases the
potential (bit for bit, transformed), the path (every point mapped exactly, compared as
binary64) and ``start_reached`` agree.  Nothing is assumed to hold.

Cell transforms act on NavFn coordinates (x right, y down) of a map of ``nx`` x ``ny``.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path
from typing import Callable

import numpy as np

from ..backends import get_backend
from ..maps.suite import discover, load_map
from ..spec.constants import COST_OBS


@dataclass(frozen=True)
class Transform:
    name: str
    grid: Callable[[np.ndarray], np.ndarray]  # (ny, nx) array -> transformed array
    point: Callable[[np.ndarray, int, int], np.ndarray]  # (M, 2) float64 points -> mapped
    same_potential: bool = True  # whether potentials are expected to map (False: cost shift)


def _pts(f):
    def g(p, nx, ny):
        p = np.asarray(p, dtype=np.float64).reshape(-1, 2)
        return f(p[:, 0], p[:, 1], nx, ny)

    return g


def _stack(x, y):
    return np.stack([x, y], axis=1)


PAD = 2
SHIFT = 10

TRANSFORMS = {
    "transpose": Transform("transpose", lambda a: a.T, _pts(lambda x, y, nx, ny: _stack(y, x))),
    "flip_x": Transform("flip_x", lambda a: a[:, ::-1], _pts(lambda x, y, nx, ny: _stack(nx - 1 - x, y))),
    "flip_y": Transform("flip_y", lambda a: a[::-1, :], _pts(lambda x, y, nx, ny: _stack(x, ny - 1 - y))),
    "rot90": Transform("rot90", lambda a: np.rot90(a, 1), _pts(lambda x, y, nx, ny: _stack(y, nx - 1 - x))),
    "rot180": Transform("rot180", lambda a: np.rot90(a, 2),
                        _pts(lambda x, y, nx, ny: _stack(nx - 1 - x, ny - 1 - y))),
    "rot270": Transform("rot270", lambda a: np.rot90(a, 3), _pts(lambda x, y, nx, ny: _stack(ny - 1 - y, x))),
    "pad": Transform("pad", lambda a: np.pad(a, PAD, constant_values=np.asarray(a).dtype.type(COST_OBS))
                     if a.dtype == np.uint8 else np.pad(a, PAD, constant_values=np.float32(1e10)),
                     _pts(lambda x, y, nx, ny: _stack(x + PAD, y + PAD))),
    "cost_shift": Transform(
        "cost_shift",
        lambda a: np.where(a < COST_OBS, np.minimum(a.astype(np.int32) + SHIFT, COST_OBS - 1), a).astype(np.uint8),
        _pts(lambda x, y, nx, ny: _stack(x, y)),
        same_potential=False,
    ),
}


@dataclass
class RelationOutcome:
    relation: str
    mode: str
    cases: int = 0
    potential_equal: int = 0
    path_equal: int = 0
    reached_equal: int = 0
    holds: int = 0
    counterexamples: list = field(default_factory=list)


def check_case(t: Transform, costs: np.ndarray, case, planner, tplanner, astar: bool) -> dict:
    """Compare one case with its transformed twin; returns which parts agree."""
    ny, nx = costs.shape
    sx, sy, gx, gy = (int(v) for v in case)
    r0 = planner.run((sx, sy), (gx, gy), astar, trace=False)
    pot0 = np.array(r0.potential, copy=True)
    path0 = np.array(r0.path, dtype=np.float64, copy=True)
    reached0 = r0.start_reached
    ts = t.point(np.array([[sx, sy]]), nx, ny)[0].astype(int)
    tg = t.point(np.array([[gx, gy]]), nx, ny)[0].astype(int)
    r1 = tplanner.run((int(ts[0]), int(ts[1])), (int(tg[0]), int(tg[1])), astar, trace=False)
    pot_ok = (not t.same_potential) or np.array_equal(
        t.grid(pot0).view(np.uint32), np.asarray(r1.potential).view(np.uint32))
    mapped = t.point(path0, nx, ny)
    path1 = np.asarray(r1.path, dtype=np.float64).reshape(-1, 2)
    path_ok = mapped.shape == path1.shape and np.array_equal(mapped, path1)
    return {"potential": bool(pot_ok), "path": bool(path_ok), "reached": reached0 == r1.start_reached,
            "transformed_case": [int(ts[0]), int(ts[1]), int(tg[0]), int(tg[1])]}


def run_metamorphic(suite, relations=None, modes=("astar",), backend="jit", max_cases=None, progress=None):
    """Check each relation on every case of every map (or the first ``max_cases`` per map)."""
    relations = list(relations or TRANSFORMS)
    outcomes = {(r, m): RelationOutcome(r, m) for r in relations for m in modes}
    for d in discover(suite):
        smap = load_map(d, Path(suite))
        cases = smap.cases if max_cases is None else smap.cases[:max_cases]
        planner = get_backend(backend).prepare(smap.costs)
        for rel in relations:
            t = TRANSFORMS[rel]
            tplanner = get_backend(backend).prepare(t.grid(smap.costs))
            for mode in modes:
                o = outcomes[(rel, mode)]
                for i, case in enumerate(cases):
                    v = check_case(t, smap.costs, case, planner, tplanner, mode == "astar")
                    o.cases += 1
                    o.potential_equal += v["potential"]
                    o.path_equal += v["path"]
                    o.reached_equal += v["reached"]
                    ok = v["potential"] and v["path"] and v["reached"]
                    o.holds += ok
                    if not ok:
                        o.counterexamples.append({"map": smap, "case_index": i, "case": [int(c) for c in case],
                                                  "mode": mode, **v})
                        del o.counterexamples[50:]  # keep memory bounded; counts stay complete
            if progress:
                progress(len(cases) * len(modes))
    return [outcomes[k] for k in sorted(outcomes)]


def save_counterexample(out_dir: Path, relation: str, cx: dict, transform: Transform) -> Path:
    """A counterexample as two suite map directories, ``original`` and ``transformed``,
    each with the one case, so ``suite record`` / ``difftest`` / ``render`` can replay it."""
    from ..maps.suite import write_map_dir

    smap = cx["map"]
    base = Path(out_dir) / relation / f"{smap.name}_case{cx['case_index']}_{cx['mode']}"
    write_map_dir(base / "original", smap.costs, [cx["case"]])
    write_map_dir(base / "transformed", transform.grid(smap.costs), [cx["transformed_case"]])
    return base


def save_counterexamples(outcomes, save_dir, save_max: int) -> list[list[str]]:
    """Save at most ``save_max`` counterexamples of each outcome under ``save_dir`` (none
    without a directory); the saved directories per outcome."""
    if not save_dir:
        return [[] for _ in outcomes]
    return [[str(save_counterexample(Path(save_dir), o.relation, cx, TRANSFORMS[o.relation]))
             for cx in o.counterexamples[:save_max]] for o in outcomes]
