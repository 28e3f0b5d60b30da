"""The built C++ NavFn as a planner: one process serves every case (no process per case).

:class:`Oracle` speaks the driver's protocol (``navfn_driver.cpp``); :meth:`Oracle.prepare`
gives a planner for one map with the same ``run`` as the backends' (:class:`MapPlanner`), so
the golden-file recorder and the difftest's comparison take the C++ where they take the spec.
"""

from __future__ import annotations

import struct
import subprocess
from pathlib import Path
from typing import Optional

import numpy as np

from ..errors import NavfnInputError
from ..spec.planner import PlanResult
from .build import load_build


class Oracle:
    """A running C++ NavFn of an oracle build folder (``traced``: with the white-box trace)."""

    def __init__(self, folder, traced: bool = True):
        self.folder = Path(folder)
        self.build = load_build(self.folder)
        self.traced = traced
        self.planning_seconds = 0.0  # the C++'s own time planning the last request's cases
        program = self.folder / ("navfn-traced" if traced else "navfn-plain")
        self.proc = subprocess.Popen([str(program)], stdin=subprocess.PIPE, stdout=subprocess.PIPE)

    def close(self) -> None:
        if self.proc.poll() is None:
            try:
                self.proc.stdin.write(struct.pack("<4i", 0, 0, 0, 0))
                self.proc.stdin.close()
            except OSError:
                pass
        try:
            self.proc.wait(timeout=10)
        except subprocess.TimeoutExpired:
            self.proc.kill()

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    def _read(self, n: int) -> bytes:
        data = self.proc.stdout.read(n) if n else b""
        if len(data) != n:
            raise NavfnInputError(f"{self.folder}: the C++ NavFn stopped answering (exit status "
                                  f"{self.proc.poll()}); is the build folder intact?")
        return data

    def plan(self, costs: np.ndarray, cases, astar: bool) -> list[PlanResult]:
        """Every ``(sx, sy, gx, gy)`` of ``cases`` on the (ny, nx) NavFn cost array ``costs``."""
        costs = np.ascontiguousarray(costs, dtype=np.uint8)
        ny, nx = costs.shape
        cases = np.ascontiguousarray(cases, dtype="<i4").reshape(-1, 4)
        self.proc.stdin.write(struct.pack("<4i", nx, ny, len(cases), int(astar)) + costs.tobytes() + cases.tobytes())
        self.proc.stdin.flush()
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

    def prepare(self, costs: np.ndarray, capacity: Optional[int] = None) -> "OracleMapPlanner":
        if capacity is not None:
            raise NavfnInputError("the C++ NavFn's buffers hold PRIORITYBUFSIZE cells: no other capacity")
        return OracleMapPlanner(self, costs)


class OracleMapPlanner:
    """The C++ NavFn on one map, planning one case per :meth:`run` (as a backend's planner)."""

    def __init__(self, oracle: Oracle, costs: np.ndarray):
        self.oracle = oracle
        self.costs = np.ascontiguousarray(costs, dtype=np.uint8)

    def run(self, start, goal, astar: bool, trace: bool = True) -> PlanResult:
        return self.oracle.plan(self.costs, [(*start, *goal)], astar)[0]
