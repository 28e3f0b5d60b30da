"""What ``check`` reports: per property and size the verdict, what was enumerated and what solved."""

from __future__ import annotations

import json
import sys

from rich.table import Table

from ..fileio import atomic_write_text
from .tables import console as _console


_running: list = []  # the heartbeat of the size being checked (at most one)


def stop_progress() -> None:
    """Stop the heartbeat of the size being checked, if any (when the run ends or fails)."""
    while _running:
        _running.pop().set()


def progress(label: str, every: float | None = None):
    """``(done, total, case_result)`` callback for one size: a line on stderr every ``every``
    seconds (default 20, or ``NAVFN_HEARTBEAT``), whether or not a case finished in between (a
    hard case can take minutes), and one at the end, terminal or not.  The heartbeat of the
    previous size stops."""
    import threading
    import time

    from .tables import heartbeat_every

    every = heartbeat_every(20.0) if every is None else every

    stop_progress()
    stop = threading.Event()
    _running.append(stop)
    state = {"done": 0, "total": None, "t0": time.perf_counter()}

    def line() -> str:
        total = "?" if state["total"] is None else state["total"]
        return f"check {label}: {state['done']}/{total} cases, {time.perf_counter() - state['t0']:.0f} s"

    def beat() -> None:
        while not stop.wait(every):
            print(line(), file=sys.stderr, flush=True)

    threading.Thread(target=beat, daemon=True, name=f"check {label} heartbeat").start()

    def tick(done: int, total: int, cr) -> None:
        state["done"], state["total"] = done, total
        if done == total:
            stop.set()
            print(line(), file=sys.stderr, flush=True)

    return tick


def verdict_text(status: str, method: str = "exploration") -> str:
    """A size's verdict as tables show it: the status, and the induction that decided it if any."""
    return status if method == "exploration" else f"{status} ({method})"


def replay_evidence(got: dict) -> list[str]:
    """A replay's evidence as lines: what was re-checked, by what, and what was trusted."""
    ev, tr = got["evidence"], got["trusted"]
    asked = ", ".join(f"{n} by {s}" for s, n in sorted(ev["unsat_reasked"].items())) or "none"
    lines = [f"re-checked: unsats asked again: {asked}; sat flips witnessed by their child's run: "
             f"{ev['sat_flips_witnessed']}; held on the box, asked of a solver too: {ev['held_on_box_checked']}; "
             f"refutations replayed on the concrete spec: {ev['refutations_witnessed']}",
             f"trusted ({tr['count']}): held on the box by interval evaluation: {tr['held_on_box_by_intervals']}; "
             f"paths cut by QueuedStartReached: {tr['paths_cut_by_queued_start']}; cases decided by the reduction "
             f"(ReachedWithinComponent): {tr['cases_by_reduction']}"
             + (f"; by induction: {', '.join(tr['by_induction'])}" if tr["by_induction"] else "")]
    if got.get("interval_decisions_recorded") is False:
        lines.append("branches the box decided: not recorded (a certificate of format 1): trusted, not counted")
    elif "interval_decisions_asked" in ev:
        lines.append(f"branches the box decided: {ev['interval_decisions_asked']} recorded, each asked of the solver "
                     "(box => branch, with the path's other unsats)")
    return lines


REDUCTION = ("ReachedWithinComponent: a start outside the goal's component is never reached (decided without "
             "exploring); layouts that differ only outside the component run alike (one explored, every cell outside "
             "it lethal)")
REDUCTION_EXPLORING_OUTSIDE = (
    "ReachedWithinComponent: layouts that differ only outside the goal's component run alike (one explored, every "
    "cell outside it lethal); a start outside the component is explored too, by its representative "
    "(NoPathWithoutFinitePotential does not hold in this arithmetic: a start never reached may still get a path)")


def _reduction(r) -> str:
    """How the size's cases were reduced, in words."""
    if r.representatives >= r.cases:
        return "none"
    return REDUCTION_EXPLORING_OUTSIDE if getattr(r, "outside_explored", False) else REDUCTION


def row(r) -> dict:
    return {
        "property": r.property, "size": list(r.size), "status": r.status, "method": r.method,
        "interior_cells": (r.size[0] - 2) * (r.size[1] - 2),
        "enumerated": {"cases": r.cases, "what": "every layout of lethal interior cells x every start x every goal "
                                                  "x each mode",
                       "explored": r.representatives, "start_outside_component": r.outside,
                       "reduction": _reduction(r)},
        "solved": {"control_paths": r.paths, "solver_queries": r.queries,
                   "decided_by_intervals": r.decided_by_intervals,
                   "flips_by_earlier_unsat_core": r.flips_by_core, "flips_by_sampled_map": r.flips_by_sample},
        "slowest_cases": r.slowest,
        "cases_holding": r.cases_holding, "cases_unknown": r.cases_unknown,
        "unknown_cases": r.unknown_cases[:20],
        "counterexample": r.counterexample, "seconds": round(r.seconds, 2),
        "case_seconds": round(r.case_seconds, 2), "cases_from_journal": r.from_journal,
        **({"fix_branches": r.fix_paths} if r.fix_paths is not None else {}),
    }


def _acted(branches) -> str:
    """How many explored control paths took the fix's branches; none: the verdict is no evidence
    for the fix at that size."""
    if not branches:
        return "-"
    text = f"{branches['further_call']}, {branches['fallback_path']} of {branches['paths']} paths"
    if branches["further_call"] == branches["fallback_path"] == 0:
        text += ": never, so no evidence for the fix here"
    return text


def table(results: list) -> None:
    t = Table(title="check: whole-planner properties over every map of a size")
    fixed = any(r.fix_paths is not None for r in results)
    for col in ("property", "size", "status", "cases", "explored", "paths", "queries", "time", "counterexample",
                *(("the fix acted (further call, fallback path)",) if fixed else ())):
        t.add_column(col)
    for r in results:
        cx = r.counterexample
        what = (f"{cx['mode']} start {tuple(cx['start'])} goal {tuple(cx['goal'])}: {cx['reason']}" if cx else "")
        t.add_row(r.property, f"{r.size[0]}x{r.size[1]}", verdict_text(r.status, r.method), str(r.cases), str(r.representatives), str(r.paths), str(r.queries),
                  f"{r.seconds:.1f} s" + (f" ({r.from_journal} cases journaled before)" if r.from_journal else ""),
                  what, *((_acted(r.fix_paths),) if fixed else ()))
    _console.print(t)


def write_json(path, doc: dict) -> None:
    atomic_write_text(path, json.dumps(doc, indent=2) + "\n")
