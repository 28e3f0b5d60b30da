"""The built C++ NavFn as a planner: one process serves every case (no process per case).

:class:`Oracle` speaks the driver's protocol (``navfn_driver.cpp``): :meth:`Oracle.plan` gives
every case of a map as the spec's :class:`~navfn_smt.spec.planner.PlanResult`, so the
golden-file recorder and the live difftest take the C++'s answers where they take the spec's.
"""

from __future__ import annotations

import struct
import subprocess
from pathlib import Path

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
