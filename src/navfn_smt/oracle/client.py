"""The programs of an oracle build, running: one process serves every request (no process per case).

- :class:`Oracle` speaks ``navfn_driver.cpp``'s protocol: :meth:`Oracle.plan` gives every case
  of a map as the spec's :class:`~navfn_smt.spec.planner.PlanResult`, so the golden-file
  recorder and the live difftest take the C++'s answers where they take the spec's;
- :class:`PluginOracle` (``plugin_driver.cpp``): ``createPlan`` on a costmap;
- :class:`LayersOracle` (``layers_driver.cpp``): the global costmap's layers on a grid;
- :class:`EigenSqrt` (``eigen_sqrt.cpp``): this machine's Eigen square root.
"""

from __future__ import annotations

import os
import select
import struct
import subprocess
from dataclasses import dataclass
from pathlib import Path
from typing import Optional

import numpy as np

from ..errors import NavfnInputError
from ..spec import fixes
from ..spec.fix import FIX as THE_FIX
from ..spec.planner import PlanResult
from .build import fix_programs, load_build


AS_SHIPPED = ("navfn-plain", "navfn-traced", "navfn-unbounded", "navfn-plugin")  # NavFn as the sources have it


def navfn_program(fix=fixes.AS_SHIPPED, traced: bool = True) -> str:
    """The NavFn program of an oracle build that plans with ``fix`` (a
    :class:`~navfn_smt.spec.planner.Fix` or its name): ``navfn-traced`` / ``navfn-plain`` as
    shipped, else the fix's ``navfn-<name>`` (traced) / ``navfn-plain-<name>``."""
    fix = fixes.named(fix)
    if fix.shipped:
        return "navfn-traced" if traced else "navfn-plain"
    traced_name, _, plain_name = fix_programs(fix)
    return traced_name if traced else plain_name


def plugin_program(fix=fixes.AS_SHIPPED) -> str:
    """The planner plugin program of an oracle build that plans with ``fix`` (a Fix or its name):
    ``navfn-plugin`` as shipped, else the fix's ``navfn-plugin-<name>``."""
    fix = fixes.named(fix)
    return "navfn-plugin" if fix.shipped else fix_programs(fix)[1]


class _Program:
    """One program of an oracle build, running, answering requests on its pipes."""

    program = ""
    END = struct.pack("<4i", 0, 0, 0, 0)
    ENV: dict = {}
    # the longest wait for the next bytes of an answer: a program that loops (or a request a
    # machine cannot finish, as a 4 GB table under qemu once was) is stopped and named, not
    # waited for; far above the slowest answer measured (a 1000x1000 map, Dijkstra, under qemu)
    ANSWER_SECONDS = 600.0

    def __init__(self, folder):
        self.folder = Path(folder)
        self.build = load_build(self.folder)
        if self.build.get("sources_carry_fix") and self.program in AS_SHIPPED:
            # a build before ``sources_carry`` was recorded: its fix was the one of docs/fix.md
            carried = self.build.get("sources_carry") or {"fix": THE_FIX.name,
                                                          "patch": self.build.get("fix_patch", {}).get("file", "its patch")}
            raise NavfnInputError(f"{self.folder}: the sources of this build carry the fix already "
                                  f"({carried['patch']} applies to them in reverse), so its {self.program} is not "
                                  f"NavFn as shipped; compare it with --variant {carried['fix']}")
        if self.program not in self.build["programs"]:
            why = self.build.get("skipped", {}).get(self.program)
            raise NavfnInputError(f"{self.folder}: this build has no {self.program} ("
                                  + (f"left out: {why}" if why else f"it has {', '.join(self.build['programs'])}; "
                                     f"build it again with `navfn-smt oracle build`") + ")")
        env = {**os.environ, **self.ENV} if self.ENV else None
        # a program built for another machine runs under qemu-user (the build's runner)
        command = [*self.build.get("runner", []), str(self.folder / self.program)]
        self.proc = subprocess.Popen(command, stdin=subprocess.PIPE, stdout=subprocess.PIPE,
                                     env=env, bufsize=0)
        self._pending, self._at = b"", 0  # bytes read from the pipe, and how many of them are taken

    def close(self) -> None:
        if self.proc.poll() is None:
            try:
                self.proc.stdin.write(self.END)
                self.proc.stdin.close()
            except OSError:
                pass
        try:
            self.proc.wait(timeout=10)
        except subprocess.TimeoutExpired:
            self.proc.kill()

    def peak_memory_bytes(self) -> Optional[int]:
        """The program's peak resident memory so far (``VmHWM``), or None where it cannot be read
        (a program run under qemu-user: qemu's own memory is not the program's)."""
        if self.build.get("runner") or self.proc.poll() is not None:
            return None
        try:
            for line in Path(f"/proc/{self.proc.pid}/status").read_text().splitlines():
                if line.startswith("VmHWM:"):
                    return int(line.split()[1]) * 1024
        except (OSError, ValueError, IndexError):
            return None
        return None

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    def _stopped(self) -> NavfnInputError:
        """The error for a program that has ended (or closed its answers) mid-request."""
        try:
            self.proc.wait(timeout=10)
        except subprocess.TimeoutExpired:
            pass
        return NavfnInputError(f"{self.folder}: the C++ {self.program} stopped answering (exit status "
                               f"{self.proc.poll()}); is the build folder intact?")

    def _send(self, request: bytes) -> None:
        """One request to the program; a clear error when it has ended (a closed pipe)."""
        try:
            self.proc.stdin.write(request)
            self.proc.stdin.flush()
        except OSError:  # BrokenPipeError: the program is gone
            raise self._stopped() from None

    def _read(self, n: int) -> bytes:
        """The next ``n`` bytes of the program's answers; a clear error when it ends first, or
        sends nothing for :attr:`ANSWER_SECONDS` (then it is stopped)."""
        have = len(self._pending) - self._at
        if have >= n:
            self._at += n
            return self._pending[self._at - n:self._at]
        parts, fd = [self._pending[self._at:]], self.proc.stdout.fileno()
        while have < n:
            if not select.select([fd], [], [], self.ANSWER_SECONDS)[0]:
                self.proc.kill()
                raise NavfnInputError(f"{self.folder}: the C++ {self.program} sent nothing for "
                                      f"{self.ANSWER_SECONDS:g} s, so it was stopped (a request it cannot finish, or "
                                      f"a loop)")
            chunk = os.read(fd, max(n - have, 1 << 16))
            if not chunk:
                raise self._stopped()
            parts.append(chunk)
            have += len(chunk)
        self._pending, self._at = b"".join(parts), n
        return self._pending[:n]


UNTRACED = frozenset(navfn_program(f, traced=False) for f in fixes.FIXES.values())  # without the trace hook


class Oracle(_Program):
    """A running C++ NavFn of an oracle build folder, planning with ``fix`` (a
    :class:`~navfn_smt.spec.planner.Fix` or its name; as shipped by default): ``traced`` (with the
    white-box trace) or not (as Nav2 compiles it, to time and measure); ``unbounded``: as shipped,
    traced, with buffers that never drop a push (``navfn-unbounded``)."""

    def __init__(self, folder, fix=fixes.AS_SHIPPED, traced: bool = True, unbounded: bool = False):
        self.program = "navfn-unbounded" if unbounded else navfn_program(fix, traced)
        self.traced = self.program not in UNTRACED
        self.planning_seconds = 0.0  # the C++'s own time planning the last request's cases
        super().__init__(folder)

    def plan(self, costs: np.ndarray, cases, astar: bool) -> list[PlanResult]:
        """Every ``(sx, sy, gx, gy)`` of ``cases`` on the (ny, nx) NavFn cost array ``costs``."""
        costs = np.ascontiguousarray(costs, dtype=np.uint8)
        ny, nx = costs.shape
        cases = np.ascontiguousarray(cases, dtype="<i4").reshape(-1, 4)
        self._send(struct.pack("<4i", nx, ny, len(cases), int(astar)) + costs.tobytes() + cases.tobytes())
        out = []
        for sx, sy, _, _ in cases.tolist():
            reached, cycles, npath, ntrace = struct.unpack("<4i", self._read(16))
            (updates,) = struct.unpack("<q", self._read(8))
            pot = np.frombuffer(self._read(4 * nx * ny), dtype="<f4").reshape(ny, nx).copy()
            path = np.frombuffer(self._read(8 * npath), dtype="<f4").reshape(-1, 2).copy()
            trace = np.frombuffer(self._read(4 * ntrace), dtype="<i4").copy() if self.traced else None
            out.append(PlanResult(start_reached=bool(reached), start_potential=pot[sy, sx], path=path, potential=pot,
                                  trace=trace, cycles=cycles, updates=updates))
        (self.planning_seconds,) = struct.unpack("<d", self._read(8))
        return out


PLUGIN_OUTCOMES = (None, "StartOutsideMapBounds", "GoalOutsideMapBounds", "GoalOccupied", "NoValidPathCouldBeFound",
                   "OtherException")


@dataclass
class PluginAnswer:
    """What Nav2's ``createPlan`` did: the exception (None when it returned), its message, the
    published poses as (x, y, qx, qy, qz, qw) doubles, the (level, line) WARN and ERROR log."""

    error: Optional[str]
    message: str
    poses: np.ndarray  # float64 (n, 6)
    lines: list


class PluginOracle(_Program):
    """A running C++ planner plugin: ``createPlan`` on a costmap, as Nav2's planner server calls
    it, many pose pairs per configured plugin.  ``fix``: the planner's fix, a
    :class:`~navfn_smt.spec.planner.Fix` or its name (:func:`plugin_program`: ``navfn-plugin``
    as shipped, ``navfn-plugin-fixed`` with the fix of docs/fix.md, ``navfn-plugin-<name>``)."""

    END = struct.pack("<3i", 0, 0, 0)

    def __init__(self, folder, fix=fixes.AS_SHIPPED):
        self.program = plugin_program(fix)
        self.planning_seconds = 0.0
        super().__init__(folder)

    def create_plans(self, cm, params, pairs) -> list[PluginAnswer]:
        """``createPlan(start, goal)`` for every (start, goal) :class:`~navfn_smt.nav2.plugin.Pose`
        pair of ``pairs`` on the :class:`~navfn_smt.nav2.plugin.Costmap` ``cm``, by a plugin
        configured with the :class:`~navfn_smt.nav2.params.PlannerParams` ``params``."""
        costs = np.ascontiguousarray(cm.costs, dtype=np.uint8)
        poses = np.array([[s.x, s.y, *s.orientation, g.x, g.y, *g.orientation] for s, g in pairs], dtype="<f8")
        head = struct.pack("<3i4d4i", cm.size_x, cm.size_y, len(pairs), cm.origin_x, cm.origin_y, cm.resolution,
                           params.tolerance, int(params.use_astar), int(params.allow_unknown),
                           int(params.max_cycles_factor), int(params.use_final_approach_orientation))
        self._send(head + costs.tobytes() + poses.tobytes())
        out = []
        for _ in pairs:
            outcome, npose, nlog, nmsg = struct.unpack("<4i", self._read(16))
            message = self._read(nmsg).decode("utf-8", "replace")
            got = np.frombuffer(self._read(48 * npose), dtype="<f8").reshape(npose, 6).copy()
            lines = []
            for _ in range(nlog):
                level, n = struct.unpack("<2i", self._read(8))
                lines.append((level, self._read(n).decode("utf-8", "replace")))
            out.append(PluginAnswer(PLUGIN_OUTCOMES[outcome], message, got, lines))
        (self.planning_seconds,) = struct.unpack("<d", self._read(8))
        return out


LAYER_KINDS = {"nav2_costmap_2d::StaticLayer": 0, "nav2_costmap_2d::InflationLayer": 1,
               "nav2_costmap_2d::LegacyInflationLayer": 2}


@dataclass
class LayersAnswer:
    """The master costmap after Nav2's layers ran (None when the version lacks a layer type),
    and the footprint's radii as LayeredCostmap computed them."""

    costmap: Optional[np.ndarray]  # uint8 (size_y, size_x)
    inscribed_radius: float
    circumscribed_radius: float


class LayersOracle(_Program):
    """A running C++ global costmap (``costmap-layers``): Nav2's static and inflation layers on
    an occupancy grid, one full update per request."""

    program = "costmap-layers"
    END = struct.pack("<3i", 0, 0, 0)
    # OpenMP threads that spin between requests take the CPU the model needs meanwhile
    ENV = {"OMP_WAIT_POLICY": "passive"}

    def costmap(self, occupancy: np.ndarray, resolution: float, origin, params) -> LayersAnswer:
        """The layers of the :class:`~navfn_smt.nav2.costmap.CostmapParams` ``params`` (in order;
        only static and inflation types) on the int8 (height, width) ``occupancy`` grid of a map
        with the float32 ``resolution`` and ``origin`` (x, y)."""
        occ = np.ascontiguousarray(occupancy, dtype=np.int8)
        h, w = occ.shape
        out = [struct.pack("<3if2d6qdf", w, h, len(params.plugins), np.float32(resolution), float(origin[0]),
                           float(origin[1]), int(params.track_unknown_space), int(params.use_maximum),
                           int(params.lethal_cost_threshold), int(params.unknown_cost_value),
                           int(params.trinary_costmap), int(params.inscribed_obstacle_cost_value),
                           float(params.robot_radius), np.float32(params.footprint_padding))]
        for layer in params.plugins:
            ip = layer.inflation
            kind = LAYER_KINDS.get(layer.type, -1)
            enabled = layer.enabled and (ip is None or ip.enabled)
            out.append(struct.pack("<4i3d", kind, int(enabled), int(bool(ip and ip.inflate_unknown)),
                                   int(bool(ip and ip.inflate_around_unknown)), ip.inflation_radius if ip else 0.0,
                                   ip.cost_scaling_factor if ip else 0.0, ip.custom_inscribed_radius if ip else -1.0))
        self._send(b"".join(out) + occ.tobytes())
        sx, sy, status = struct.unpack("<3i", self._read(12))
        costs = np.frombuffer(self._read(sx * sy), dtype=np.uint8).reshape(sy, sx).copy()
        radii = struct.unpack("<2d", self._read(16))
        return LayersAnswer(None if status else costs, *radii)


class EigenSqrt(_Program):
    """This machine's Eigen ``cwiseSqrt`` (``eigen-sqrt``), as the distance-transform layer takes it."""

    program = "eigen-sqrt"
    END = struct.pack("<i", 0)

    def sqrt(self, values: np.ndarray) -> np.ndarray:
        x = np.ascontiguousarray(values, dtype="<f4").ravel()
        self._send(struct.pack("<i", len(x)) + x.tobytes())
        return np.frombuffer(self._read(4 * len(x)), dtype="<f4").copy()
