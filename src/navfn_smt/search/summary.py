"""``navfn-smt search --summary SUITE``: how often each kind occurs on a suite.

Every case of every map is planned by the JIT (``run_batch``, held bit-equal to the spec by
difftest) and measured with the definitions of :mod:`.kinds` (through their compiled
screens in :mod:`.fast`):

* turn: a path with an obtuse turn; per step, obtuse turns over turn positions (a path of
  M points has M-2); also turns of 90 degrees or more (dot product <= 0, non-zero steps);
* oscillation: a path with a point equal to the one two before; per step, such points
  over the points that have one two before (M-2);
* incomplete: finite start potential, no path;
* unreached: start 4-connected to the goal, potential unreached;
* int-conversion: calcPath's fallback converts an unreached potential to int (exit
  high_potential), with the start unreached or mid-path;
* cost: the gap of every returned path (properties.cost_gap), its ratio path/optimum.

Each map is one task of the :mod:`~navfn_smt.engine`; the maps' counts are merged in suite
order whatever order they arrive in, so the summary is the same wherever they ran.
"""

from __future__ import annotations

import time
from pathlib import Path
from typing import Callable, Optional

import numpy as np

from ..engine import Engine, in_order, stream
from ..maps.suite import discover, load_map
from ..spec.extraction import EXIT_UNDEFINED, ExtractionExit, exit_code, exit_name
from . import fast
from .kinds import plan_batch

PAPER = {"turn_per_step_percent": 1.91, "oscillation_per_step_percent": 0.13}
_NEAR = exit_code(ExtractionExit.NEAR_GOAL)
_HIGH = exit_code(ExtractionExit.HIGH_POTENTIAL)
PARALLEL_FROM = 40  # --jobs auto: local workers from this many maps on


def _zero() -> dict:
    return {k: 0 for k in ("cases", "paths", "turn_paths", "turns", "turns_ge90", "turn_slots", "oscillation_paths",
                           "oscillations", "oscillation_slots", "incomplete", "unreached",
                           "int_conversion_start_unreached", "int_conversion_mid_path", "undefined",
                           "gap_defined", "gap_positive", "gap_sum")} | {"gap_max": 0, "ratio_max": 0.0,
                                                                         "gap_max_case": None, "exits": {}}


def _measure(smap, mode: str, acc: dict) -> None:
    b = plan_batch(smap.costs, smap.cases, mode == "astar")
    out = b.out
    off = out["path_offsets"]
    n = len(b.cases)
    acc["cases"] += n
    paths = (off[1:] - off[:-1]) > 0
    acc["paths"] += int(paths.sum())
    for code in np.unique(out["exit"]):
        name = exit_name(int(code))
        acc["exits"][name] = acc["exits"].get(name, 0) + int((out["exit"] == code).sum())
    acc["undefined"] += int((out["exit"] == EXIT_UNDEFINED).sum())
    t, ts = fast.turns(out["path"], off)
    o, os_ = fast.oscillations(out["path"], off)
    acc["turn_paths"] += int((t > 0).sum())
    acc["turns"] += int(t.sum())
    acc["turn_slots"] += int(ts.sum())
    acc["turns_ge90"] += int(fast.right_or_sharper(out["path"], off).sum())
    acc["oscillation_paths"] += int((o > 0).sum())
    acc["oscillations"] += int(o.sum())
    acc["oscillation_slots"] += int(os_.sum())
    finite = b.finite()
    acc["incomplete"] += int((finite & (out["exit"] != _NEAR)).sum())
    acc["unreached"] += int((~finite & b.connected()).sum())
    high = out["exit"] == _HIGH
    acc["int_conversion_start_unreached"] += int((high & ~finite).sum())
    acc["int_conversion_mid_path"] += int((high & finite).sum())
    g, pc = b.gaps()
    ok = g >= 0
    acc["gap_defined"] += int(ok.sum())
    acc["gap_positive"] += int((g > 0).sum())
    acc["gap_sum"] += int(g[ok].sum())
    if ok.any():
        i = int(np.argmax(np.where(ok, g, -1)))
        if g[i] > acc["gap_max"]:
            acc["gap_max"] = int(g[i])
            acc["gap_max_case"] = {"map": str(smap.directory), "case": [int(v) for v in b.cases[i]],
                                   "path_cost": int(pc[i]), "optimum": int(pc[i] - g[i])}
        opt = pc[ok] - g[ok]
        pos = opt > 0
        if pos.any():
            acc["ratio_max"] = max(acc["ratio_max"], float((pc[ok][pos] / opt[pos]).max()))


def _merge(into: dict, acc: dict) -> None:
    for k, v in acc.items():
        if k == "exits":
            for e, n in v.items():
                into["exits"][e] = into["exits"].get(e, 0) + n
        elif k == "gap_max":
            if v > into["gap_max"]:
                into["gap_max"], into["gap_max_case"] = v, acc["gap_max_case"]
        elif k == "ratio_max":
            into[k] = max(into[k], v)
        elif k != "gap_max_case":
            into[k] += v


def _pct(a: int, b: int) -> Optional[float]:
    return round(100.0 * a / b, 4) if b else None


def finish(acc: dict) -> dict:
    """The counts with their percentages."""
    r = dict(acc)
    r["turn_per_path_percent"] = _pct(acc["turn_paths"], acc["paths"])
    r["turn_per_step_percent"] = _pct(acc["turns"], acc["turn_slots"])
    r["turn_ge90_per_step_percent"] = _pct(acc["turns_ge90"], acc["turn_slots"])
    r["oscillation_per_path_percent"] = _pct(acc["oscillation_paths"], acc["paths"])
    r["oscillation_per_step_percent"] = _pct(acc["oscillations"], acc["oscillation_slots"])
    r["gap_positive_percent"] = _pct(acc["gap_positive"], acc["gap_defined"])
    r["gap_mean"] = round(acc["gap_sum"] / acc["gap_defined"], 3) if acc["gap_defined"] else None
    r["ratio_max"] = round(acc["ratio_max"], 4)
    return r


def _map_counts(task) -> tuple[str, dict]:
    """One map's category and counts per mode (a task: run by a worker, or in this process)."""
    directory, root, modes = task
    smap = load_map(directory, root)
    per_mode = {}
    for m in modes:
        per_mode[m] = _zero()
        _measure(smap, m, per_mode[m])
    return smap.category, per_mode


def summarize(suite: Path, modes, progress: Optional[Callable[[str], None]] = None,
              eng: Engine = Engine(1)) -> dict:
    """Per mode and per category, and over the whole suite per mode; the maps measured on
    ``eng`` (``auto``: local workers for a large suite)."""
    root = Path(suite)
    dirs = discover(root)
    t0 = time.perf_counter()
    per_mode = {m: _zero() for m in modes}
    per_cat: dict = {}
    last = t0
    tasks = [(d, root, tuple(modes)) for d in dirs]
    # merged in suite order: ties (the largest gap's case) as in a run in order
    for k, (_, (category, counts)) in enumerate(in_order(stream(_map_counts, tasks,
                                                                 eng.for_work(len(dirs), PARALLEL_FROM))), 1):
        for m in modes:
            _merge(per_mode[m], counts[m])
            _merge(per_cat.setdefault((category, m), _zero()), counts[m])
        if progress and (time.perf_counter() - last > 5.0 or k == len(dirs)):
            progress(f"[search --summary] {k}/{len(dirs)} maps, {time.perf_counter() - t0:.1f} s")
            last = time.perf_counter()
    return {
        "suite": str(root), "maps": len(dirs), "modes": list(modes), "seconds": round(time.perf_counter() - t0, 2),
        "paper": PAPER,
        "total": {m: finish(a) for m, a in per_mode.items()},
        "categories": [{"category": c, "mode": m, **finish(a)} for (c, m), a in sorted(per_cat.items())],
    }
