"""The whole-map sweep: plan from one fixed robot pose to every goal cell (or a sample), each
goal exactly as ``NavfnPlanner::createPlan`` (:func:`navfn_smt.nav2.plugin.create_plan`)
would plan it alone, in one pass.

Dijkstra: NavFn's propagation source is the robot's cell whatever the goal, and
``propNavFnDijkstra(atStart=true)`` only stops the same loop earlier, at the end of the cycle
in which the goal's cell gets a finite potential; so one propagation serves every goal, each
goal extracted at the end of its cycle (:mod:`navfn_smt.nav2.sweep_loops`).  A*: the
heuristic depends on the goal; each goal is propagated alone (compiled, no shortcut).

A goal cell ``(i, j)`` is planned with the goal pose the plugin's own ``mapToWorld`` gives
for it, ``(origin_x + i * res, origin_y + j * res)``: the plugin's rounding ``worldToMap``
maps it back to ``(i, j)`` (checked per goal; a goal for which it does not is planned by
``create_plan`` itself).  The costmap's cell centre ``origin + (i + 0.5) * res`` would not
do: it lies on the rounding boundary, and rounds to cell ``i + 1`` unless the division lands
just below the half (see :func:`goal_pose`).

Every plugin decision outside NavFn's loops (bounds checks, ``GoalOccupied``, equal
positions, the tolerance search's world points) is taken by the plugin's own functions.
"""

from __future__ import annotations

import time
from dataclasses import dataclass
from typing import Callable, Optional, Union

import numpy as np

from ..errors import NavfnInputError
from ..nav2.params import PlannerParams
from ..nav2.plugin import (
    EMPTY_PATH,
    GOAL_OFF_MAP,
    ROBOT_OFF_MAP,
    UNIQUE_POSE_LETHAL,
    Costmap,
    flavour_of,
    PluginRun,
    Pose,
    rounded_cells,
    costmap_world_to_map,
    create_plan,
    max_cycles,
    plugin_map_to_world,
    plugin_world_to_map,
    tolerance_steps,
)
from ..spec.constants import INSCRIBED_INFLATED_OBSTACLE, LETHAL_OBSTACLE, NO_INFORMATION
from ..spec.costs import add_border, set_costmap
from ..spec.extraction import EXIT_CODES
from ..spec.propagation import cycle_limit

# Per-goal outcomes; the error each stands for (None: a plan was published).
OUTCOMES = ("ok", "ok_tolerance", "same_pose", "no_legal", "legal_no_plan", "goal_occupied",
            "goal_outside", "start_outside", "undefined_behaviour")
OUTCOME_ERROR = {"ok": None, "ok_tolerance": None, "same_pose": None, "no_legal": "NoValidPathCouldBeFound",
                 "legal_no_plan": "NoValidPathCouldBeFound", "goal_occupied": "GoalOccupied",
                 "goal_outside": "GoalOutsideMapBounds", "start_outside": "StartOutsideMapBounds",
                 "undefined_behaviour": "UndefinedBehaviour"}
_CODE = {name: i for i, name in enumerate(OUTCOMES)}
EXIT_NAMES = tuple(e.name for e in EXIT_CODES)  # the sweep's exit ints are the spec's
FREE_BELOW = INSCRIBED_INFLATED_OBSTACLE  # goals by default: every known cell below it
DIJKSTRA_CYCLES_PER_CALL = 256
ASTAR_GOALS_PER_CALL = 32

Progress = Callable[[int, int], None]


@dataclass
class SweepResult:
    """One sweep: arrays per goal, in the order of ``cells``."""

    mode: str  # "dijkstra" or "astar"
    start: Pose
    params: PlannerParams
    shape: tuple  # (size_y, size_x) of the costmap
    resolution: float
    cells: np.ndarray  # (G, 2) int64 goal cells (x, y)
    goal_xy: np.ndarray  # (G, 2) float64 goal poses (mapToWorld of the cell)
    outcome: np.ndarray  # (G,) int8 index into OUTCOMES
    exit: np.ndarray  # (G,) int8 index of the calcPath exit in ExtractionExit, -1 when not extracted
    used_tolerance: np.ndarray  # (G,) bool
    best_cell: np.ndarray  # (G, 2) int64, the cell the path was extracted from (-1 when none)
    cycles: np.ndarray  # (G,) int64 propagation cycles of the goal's own run (-1 when not planned)
    goal_potential: np.ndarray  # (G,) float64 getPointPotential(goal) (nan when not planned)
    path_points: np.ndarray  # (G,) int64 NavFn path points (0 unless a plan)
    path_length: np.ndarray  # (G,) float64 metres along NavFn's path points (the polyline)
    robot_cell: Optional[tuple] = None
    seconds: float = 0.0
    fallback: int = 0  # goals planned by create_plan itself (see the module doc)
    path_offsets: Optional[np.ndarray] = None  # (G,) start of each kept path in ``paths``
    paths: Optional[np.ndarray] = None  # (P, 2) float32 NavFn points, when kept

    def __len__(self) -> int:
        return int(len(self.cells))

    def outcome_name(self, k: int) -> str:
        return OUTCOMES[int(self.outcome[k])]

    def error(self, k: int) -> Optional[str]:
        return OUTCOME_ERROR[self.outcome_name(k)]

    def path(self, k: int) -> np.ndarray:
        """Goal ``k``'s NavFn path (float32 (x, y) points from the goal's cell to the robot's),
        as ``PluginRun.path``; needs ``keep_paths``."""
        if self.paths is None:
            raise ValueError("paths were not kept (sweep(..., keep_paths=True))")
        n = int(self.path_points[k])
        o = int(self.path_offsets[k])
        return self.paths[o:o + n] if n else np.zeros((0, 2), np.float32)

    def counts(self) -> dict:
        c = np.bincount(self.outcome.astype(np.int64), minlength=len(OUTCOMES))
        return {name: int(c[i]) for i, name in enumerate(OUTCOMES)}


def goal_pose(cm: Costmap, cell) -> Pose:
    """The goal pose of a cell: the plugin's ``mapToWorld`` of the cell, ``origin + i * res``.

    The plugin's ``worldToMap`` rounds ``(w - origin) / res``, so this pose (``i`` up to a
    rounding error) maps back to ``(i, j)``, while the costmap's cell centre ``origin +
    (i + 0.5) * res`` (what ``Costmap2D::mapToWorld`` gives) lands on the half and rounds to
    ``i + 1`` whenever the division does not fall just below it."""
    return Pose(*plugin_map_to_world(cm, float(cell[0]), float(cell[1])))


def select_goals(cm: Costmap, goals: Union[None, str, int, np.ndarray] = None, seed: int = 0) -> np.ndarray:
    """The goal cells, (G, 2) int64 (x, y) in index order: None -> every free cell (cost below
    253: not lethal, inscribed nor unknown), ``"all"`` -> every cell, an int -> that many free
    cells drawn without replacement (``numpy.random.default_rng(seed)``), or given cells."""
    ny, nx = cm.costs.shape
    if goals is None or isinstance(goals, (int, np.integer)) and not isinstance(goals, bool):
        idx = np.flatnonzero(np.asarray(cm.costs).ravel() < FREE_BELOW)
        if goals is not None:
            k = int(goals)
            if k < 1:
                raise NavfnInputError(f"a goal sample needs at least one goal, got {k}")
            if k < len(idx):
                idx = np.sort(np.random.default_rng(seed).choice(idx, size=k, replace=False))
    elif isinstance(goals, str):
        if goals != "all":
            raise NavfnInputError(f"goals must be None, 'all', a sample size or cells, got {goals!r}")
        idx = np.arange(nx * ny)
    else:
        c = np.asarray(goals, dtype=np.int64).reshape(-1, 2)
        if len(c) and (c[:, 0].min() < 0 or c[:, 1].min() < 0 or c[:, 0].max() >= nx or c[:, 1].max() >= ny):
            raise NavfnInputError(f"a goal cell is off the {nx}x{ny} map")
        idx = np.unique(c[:, 1] * nx + c[:, 0])
    return np.stack([idx % nx, idx // nx], axis=1).astype(np.int64)


def outcome_of_run(run: PluginRun) -> str:
    """The sweep's outcome name of one ``create_plan`` result."""
    if run.error is None:
        if run.robot_cell is None:
            return "same_pose"
        return "ok_tolerance" if run.used_tolerance else "ok"
    if run.error in ("NoValidPathCouldBeFound", EMPTY_PATH):  # Humble: no exception, an empty path
        if run.legal_potential_no_plan:
            return "legal_no_plan"
        warned = run.warnings
        return ("start_outside" if ROBOT_OFF_MAP in warned else "goal_outside" if GOAL_OFF_MAP in warned
                else "goal_occupied" if UNIQUE_POSE_LETHAL in warned else "no_legal")
    return {"GoalOccupied": "goal_occupied", "GoalOutsideMapBounds": "goal_outside",
            "StartOutsideMapBounds": "start_outside", "UndefinedBehaviour": "undefined_behaviour"}[run.error]


def _tolerance_tables(values: np.ndarray, tolerance: float, origin: float, res: float, size: int):
    """Per distinct goal coordinate: the tolerance search's world points (``tolerance_steps``)
    and their rounded cells (-1 where worldToMap fails), padded; (index per goal, points,
    cells, lengths, refused per coordinate)."""
    uniq, index = np.unique(values, return_inverse=True)
    rows, refused = [], np.zeros(len(uniq), bool)
    for k, v in enumerate(uniq.tolist()):
        try:
            w = tolerance_steps(v - tolerance, v + tolerance, res)
        except NavfnInputError as e:
            refused[k] = True
            rows.append((np.zeros(0), np.zeros(0, np.int64), e))
            continue
        rows.append((w, rounded_cells(w, origin, res, size), None))
    width = max([len(r[0]) for r in rows] + [1])
    pts = np.zeros((len(uniq), width))
    cells = np.full((len(uniq), width), -1, np.int64)
    lens = np.zeros(len(uniq), np.int64)
    for k, (w, c, _) in enumerate(rows):
        pts[k, :len(w)], cells[k, :len(c)], lens[k] = w, c, len(w)
    errors = [r[2] for r in rows]
    return index.astype(np.int64), pts, cells, lens, errors


def sweep(cm: Costmap, start: Pose, params: PlannerParams = PlannerParams(),
          goals: Union[None, str, int, np.ndarray] = None, seed: int = 0, progress: Optional[Progress] = None,
          keep_paths: bool = False) -> SweepResult:
    """Plan from ``start`` to every goal of :func:`select_goals` as ``create_plan(cm, start,
    goal_pose(cm, cell), params)`` would, one propagation for Dijkstra (``params.use_astar``
    false), one per goal for A*.  ``progress(done, total)`` is called as goals finish.
    ``keep_paths`` keeps every NavFn path (:meth:`SweepResult.path`)."""
    from ..nav2 import sweep_loops as S
    from ..backends.jit import JitPlanner

    t0 = time.perf_counter()
    cells = select_goals(cm, goals, seed)
    ny, nx = cm.costs.shape
    G = len(cells)
    gxy = np.array([plugin_map_to_world(cm, float(x), float(y)) for x, y in cells.tolist()], np.float64).reshape(-1, 2)
    res = SweepResult(
        mode="astar" if params.use_astar else "dijkstra", start=start, params=params, shape=(ny, nx),
        resolution=cm.resolution, cells=cells, goal_xy=gxy, outcome=np.full(G, -1, np.int8),
        exit=np.full(G, -1, np.int8), used_tolerance=np.zeros(G, bool), best_cell=np.full((G, 2), -1, np.int64),
        cycles=np.full(G, -1, np.int64), goal_potential=np.full(G, np.nan), path_points=np.zeros(G, np.int64),
        path_length=np.zeros(G))
    report = progress or (lambda d, t: None)

    # createPlan's checks before makePlan, by the plugin's own functions (Jazzy on; Humble's
    # plugin has none, and its goals that would meet them are planned by create_plan alone)
    throws = flavour_of(params.distro).throws
    if throws and costmap_world_to_map(cm, start.x, start.y) is None:
        res.outcome[:] = _CODE["start_outside"]
        return _finish(res, t0, report)
    planned = []  # goals for the compiled loops
    fallback = []  # goals create_plan plans alone
    robot_ok, robot = plugin_world_to_map(cm, start.x, start.y)
    n_cycles = max_cycles(cm, params)  # None: the int product overflows
    exotic = not robot_ok or n_cycles is None or n_cycles < 0
    for k, ((x, y), (wx, wy)) in enumerate(zip(cells.tolist(), gxy.tolist())):
        gc = costmap_world_to_map(cm, wx, wy)
        if not throws and (gc is None or start.x == wx and start.y == wy):
            fallback.append(k)
        elif gc is None:
            res.outcome[k] = _CODE["goal_outside"]
        elif throws and params.tolerance == 0 and int(cm.costs[gc[1], gc[0]]) == LETHAL_OBSTACLE:
            res.outcome[k] = _CODE["goal_occupied"]
        elif start.x == wx and start.y == wy:
            res.outcome[k] = _CODE["same_pose"]
        elif exotic or plugin_world_to_map(cm, wx, wy) != (True, (x, y)):
            fallback.append(k)
        else:
            planned.append(k)
    done = G - len(planned) - len(fallback)
    report(done, G)
    res.robot_cell = robot
    planned = np.array(planned, np.int64)
    pts = np.zeros((1024 if keep_paths else 0, 2), np.float32)
    out_i = np.zeros((G, S.NI), np.int64)
    out_f = np.zeros((G, S.NF))
    st = np.zeros(S.NSTATE, np.int64)
    if len(planned):
        ros = np.array(cm.costs, dtype=np.uint8, copy=True)
        ros[robot[1], robot[0]] = 0  # clearRobotCell
        navfn = add_border(set_costmap(ros, is_ros=True, allow_unknown=params.allow_unknown))
        planner = JitPlanner(navfn)  # work arrays (PRIORITYBUFSIZE buffers, as the plugin's)
        cycles = cycle_limit(nx, ny)
        tol = params.tolerance
        col_of, xs, xcells, xlen, xerr = _tolerance_tables(gxy[:, 0], tol, cm.origin_x, cm.resolution, nx)
        row_of, ys, ycells, ylen, yerr = _tolerance_tables(gxy[:, 1], tol, cm.origin_y, cm.resolution, ny)
        tcell = np.ascontiguousarray(cells)
        out_i[:, S.ST] = -1  # not for the compiled loops
        out_i[planned, S.ST] = S.S_PENDING
        wx, wy = np.ascontiguousarray(gxy[:, 0]), np.ascontiguousarray(gxy[:, 1])
        tables = S.Tolerance(col_of, row_of, xs, xcells, xlen, ys, ycells, ylen, wx, wy)
        planner.fit_path(n_cycles)
        if params.use_astar:
            for lo in range(0, len(planned), ASTAR_GOALS_PER_CALL):
                chunk = planned[lo:lo + ASTAR_GOALS_PER_CALL]
                pts = S.sweep_astar(planner.D, planner.work, robot[0], robot[1], cycles, chunk, tcell, n_cycles,
                                    planner.trail, out_i, out_f, pts, st, keep_paths, tables)
                report(done + lo + len(chunk), G)
        else:
            goal_of = np.full(nx * ny, -1, np.int64)
            goal_of[tcell[planned, 1] * nx + tcell[planned, 0]] = planned
            work = planner.work._replace(watch=goal_of.copy(), newly=np.empty(G + 1, np.int64))
            memo_cell = np.full(nx * ny, -1, np.int64)
            while not st[S.DONE]:
                pts = S.sweep_dijkstra(planner.D, work, robot[0], robot[1], cycles, DIJKSTRA_CYCLES_PER_CALL, st, goal_of,
                                       tcell, n_cycles, planner.trail, out_i, out_f, pts, keep_paths, tables, memo_cell)
                report(done + int(np.count_nonzero(out_i[planned, S.ST] != S.S_PENDING)), G)
        _refused(out_i, planned, col_of, row_of, xerr, yerr)
        p = planned
        stc = out_i[p, S.ST]
        used = out_i[p, S.USED_TOL].astype(bool)
        res.outcome[p] = np.select(
            [stc == S.S_PATH, stc == S.S_NO_LEGAL, stc == S.S_NO_PLAN, stc == S.S_UB],
            [np.where(used, _CODE["ok_tolerance"], _CODE["ok"]), _CODE["no_legal"], _CODE["legal_no_plan"],
             _CODE["undefined_behaviour"]], -1)
        res.exit[p] = np.where(stc == S.S_NO_LEGAL, -1, out_i[p, S.EXIT])
        res.exit[p] = np.where(stc == S.S_UB, -1, res.exit[p])
        res.used_tolerance[p] = used
        res.best_cell[p, 0], res.best_cell[p, 1] = out_i[p, S.BEST_X], out_i[p, S.BEST_Y]
        res.best_cell[p] = np.where((stc == S.S_NO_LEGAL)[:, None], -1, res.best_cell[p])
        res.cycles[p] = out_i[p, S.CYCLE]
        res.goal_potential[p] = out_f[p, S.GOAL_POT]
        res.path_points[p] = np.where(stc == S.S_PATH, out_i[p, S.NPATH], 0)
        res.path_length[p] = out_f[p, S.LENGTH] * cm.resolution
    offsets = out_i[:, S.PATH_OFF].copy()
    pts = pts[:st[S.NPTS]] if keep_paths else None
    if not params.fix.shipped:  # the compiled loops plan as the original
        # a fix's further call and fallback act only where the first call leaves the start
        # unreached with cells buffered and where calcPath returns no path; an inclusive
        # near-goal test may change any path, so then every goal is planned alone
        failed = [_CODE[o] for o in ("ok_tolerance", "no_legal", "legal_no_plan")]
        fallback += [k for k in planned.tolist() if params.fix.inclusive or res.outcome[k] in failed]
    if fallback:
        pts, offsets = _plan_alone(cm, start, params, res, fallback, pts, offsets, keep_paths, report, G - len(fallback))
    if keep_paths:
        res.paths, res.path_offsets = pts, offsets
    res.fallback = len(fallback)
    return _finish(res, t0, report)


def _refused(out_i, planned, col_of, row_of, xerr, yerr) -> None:
    """A goal that needed a tolerance search the plugin refuses (``tolerance_steps`` raised)
    raises the same error here."""
    from ..nav2.sweep_loops import USED_TOL

    for g in planned[out_i[planned, USED_TOL] == 1].tolist():
        e = xerr[col_of[g]] or yerr[row_of[g]]
        if e is not None:
            raise e


def _plan_alone(cm, start, params, res, ks, pts, offsets, keep, report, done):
    """Goals ``ks`` planned by ``create_plan`` itself (reference for the exotic cases)."""
    extra = []
    n0 = 0 if pts is None else len(pts)
    for j, k in enumerate(ks):
        run = create_plan(cm, start, goal_pose(cm, res.cells[k]), params)
        res.outcome[k] = _CODE[outcome_of_run(run)]
        res.exit[k] = -1 if run.extraction is None else EXIT_NAMES.index(run.extraction.name)
        res.used_tolerance[k] = run.used_tolerance
        if run.best_cell is not None:
            res.best_cell[k] = run.best_cell
        res.cycles[k] = run.cycles if run.potential is not None else -1
        res.goal_potential[k] = np.nan if run.goal_potential is None else run.goal_potential
        if run.ok and run.path is not None:
            res.path_points[k] = len(run.path)
            d = np.diff(run.path.astype(np.float64), axis=0)
            res.path_length[k] = float(np.sqrt((d * d).sum(axis=1)).sum()) * cm.resolution
            if keep:
                offsets[k] = n0 + sum(len(e) for e in extra)
                extra.append(run.path)
        report(done + j + 1, len(res))
    if keep and extra:
        pts = np.concatenate([pts] + extra)
    return pts, offsets


def _finish(res: SweepResult, t0: float, report) -> SweepResult:
    res.seconds = time.perf_counter() - t0
    report(len(res), len(res))
    return res


def summary(res: SweepResult) -> dict:
    """The JSON summary of a sweep: counts per outcome, extraction exits, timing."""
    counts = res.counts()
    exits = {}
    for e in res.exit[res.exit >= 0].tolist():
        exits[EXIT_NAMES[e]] = exits.get(EXIT_NAMES[e], 0) + 1
    ok = np.isin(res.outcome, [_CODE["ok"], _CODE["ok_tolerance"]])
    return {
        "mode": res.mode,
        "start": {"x": res.start.x, "y": res.start.y},
        "robot_cell": None if res.robot_cell is None else list(map(int, res.robot_cell)),
        "map": {"size_x": res.shape[1], "size_y": res.shape[0], "resolution": res.resolution},
        "params": {"tolerance": res.params.tolerance, "use_astar": res.params.use_astar,
                   "allow_unknown": res.params.allow_unknown, "max_cycles_factor": res.params.max_cycles_factor},
        "goals": len(res),
        "outcomes": counts,
        "errors": _error_counts(counts),
        "extraction_exits": exits,
        "used_tolerance": int(res.used_tolerance.sum()),
        "issue_4655": counts["legal_no_plan"],
        "mean_path_length_m": float(res.path_length[ok].mean()) if ok.any() else None,
        "seconds": round(res.seconds, 3),
        "goals_per_second": None if not res.seconds else round(len(res) / res.seconds, 1),
        "planned_alone": res.fallback,
    }


def _error_counts(counts: dict) -> dict:
    out: dict = {}
    for name, n in counts.items():
        e = OUTCOME_ERROR[name]
        if e is not None and n:
            out[e] = out.get(e, 0) + n
    return out


def rooms_costmap(n: int, seed: int = 0, room: int = 40, resolution: float = 0.05,
                  inflation: bool = True) -> Costmap:
    """A generated n x n ROS costmap of rooms: a lethal frame, 2-cell walls every ``room``
    cells with one door (10 cells) per wall segment, about one segment in eight closed (rooms
    that may be sealed off), lethal furniture blocks, unknown (255) patches, then Nav2's
    inflation (inscribed radius 0.1 m, inflation radius 0.5 m, scaling 3) when ``inflation``.
    Origin (-n*res/2, -n*res/2)."""
    from ..maps.generators import inflate

    rng = np.random.default_rng(seed)
    c = np.zeros((n, n), np.uint8)
    c[0, :] = c[-1, :] = c[:, 0] = c[:, -1] = LETHAL_OBSTACLE
    lines = list(range(room, n - 2, room))
    for k in lines:
        c[k:k + 2, :] = LETHAL_OBSTACLE
        c[:, k:k + 2] = LETHAL_OBSTACLE
    bounds = [1] + [k + 2 for k in lines]
    ends = [k for k in lines] + [n - 1]
    for k in lines:  # a door in each wall segment between two crossings, both directions
        for lo, hi in zip(bounds, ends):
            for horizontal in (True, False):
                if hi - lo < 12 or rng.random() < 0.125:
                    continue
                d = int(rng.integers(lo + 1, hi - 11))
                if horizontal:
                    c[k:k + 2, d:d + 10] = 0
                else:
                    c[d:d + 10, k:k + 2] = 0
    for _ in range(max(1, n * n // 2000)):  # furniture
        w, h = int(rng.integers(2, 8)), int(rng.integers(2, 8))
        x, y = int(rng.integers(1, n - w - 1)), int(rng.integers(1, n - h - 1))
        c[y:y + h, x:x + w] = LETHAL_OBSTACLE
    for _ in range(max(1, n * n // 20000)):  # unknown patches
        w, h = int(rng.integers(3, 12)), int(rng.integers(3, 12))
        x, y = int(rng.integers(1, n - w - 1)), int(rng.integers(1, n - h - 1))
        c[y:y + h, x:x + w] = NO_INFORMATION
    if inflation:
        known = c != NO_INFORMATION
        inflated = inflate(np.where(known, c, 0).astype(np.uint8), resolution, 0.1, 0.5, 3.0)
        c = np.where(known, inflated, NO_INFORMATION).astype(np.uint8)
    half = -n * resolution / 2
    return Costmap(np.ascontiguousarray(c), half, half, resolution)
