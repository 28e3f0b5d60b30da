"""Counterexamples as suite map directories: saved whole, replayed on the spec and the JIT.

A counterexample directory ``<kind>-<mode>-<W>x<H>`` holds

* ``map.bin`` and ``test.txt`` with the one case (a suite map directory, so ``difftest``,
  ``render`` and ``plan`` take it as it is),
* ``golden_astar.npz`` and ``golden_dijkstra.npz`` recorded from the reference spec,
* ``picture.png``: the case drawn in the counterexample's mode,
* ``counterexample.json``: kind, mode, size, start, goal and the judge's detail (plus what
  the finder adds: gap, time, seed, ...); ``arithmetic``, the arithmetic it was found and its
  golden files recorded in when not x86-64's; ``is_one_in``, for each known arithmetic of a
  build (:data:`~navfn_smt.spec.arithmetic.KNOWN`), whether the case is a counterexample of its
  kind when the spec plans in it (:func:`stands_in`).

Everything is written into a hidden sibling directory first and renamed into place, so an
interruption leaves no half-written counterexample.  ``search`` and ``check`` both save
through :func:`save_counterexample`; :func:`replay` is what the regression test runs.
"""

from __future__ import annotations

import json
import os
import shutil
from pathlib import Path
from typing import Optional

import numpy as np

from ..check import properties as P
from ..errors import NavfnInputError
from ..spec import fixes
from ..fileio import jsonable
from ..maps.suite import GOLDEN_FIELDS, MODES, load_golden, load_map, write_map_dir
from ..spec.arithmetic import KNOWN, X86_64
from ..under_test import PlannerUnderTest
from . import kinds as KD

JSON_NAME = "counterexample.json"
PICTURE_NAME = "picture.png"


def directory_name(kind: str, mode: str, costs: np.ndarray, arith=X86_64) -> str:
    """``<kind>-<mode>-<W>x<H>``, and ``-<arithmetic>`` for one found in another arithmetic
    than x86-64's (the golden files' and the committed ones')."""
    h, w = np.asarray(costs).shape
    return f"{kind}-{mode}-{w}x{h}" + ("" if arith == X86_64 else f"-{arith.name}")


def field_of(f, name, default=None):
    """A field of a finding: a hunt's :class:`~navfn_smt.search.hunt.Finding` or the overflow
    search's finding-like dict."""
    return f.get(name, default) if isinstance(f, dict) else getattr(f, name, default)


def save_findings(findings, out_dir) -> list[Optional[str]]:
    """Save every finding that carries a map under ``out_dir`` (nothing without one); the
    directories written, None where nothing was."""
    if not out_dir:
        return [None] * len(findings)
    saved = []
    for f in findings:
        costs = field_of(f, "costs")
        if costs is None:
            saved.append(None)
            continue
        extra = {k: field_of(f, k) for k in ("seconds", "evaluations", "plans", "seed")}
        extra["found_size"] = list(field_of(f, "found_size") or [])
        planner = field_of(f, "planner")
        if planner is not None and not planner.fix.shipped:
            extra["variant"] = planner.variant
        d = save_counterexample(out_dir, costs, field_of(f, "start"), field_of(f, "goal"),
                                field_of(f, "mode") == "astar", field_of(f, "kind"), field_of(f, "detail", {}),
                                extra=extra, planner=field_of(f, "planner"))
        saved.append(str(d))
    return saved


def save_counterexample(out_dir, costs: np.ndarray, start, goal, astar: bool, kind: str, detail: dict,
                        extra: Optional[dict] = None, name: Optional[str] = None,
                        planner: Optional[PlannerUnderTest] = None) -> Path:
    """Write the counterexample directory ``out_dir/<kind>-<mode>-<W>x<H>`` (or ``name``) whole,
    replacing an older one of the same name; returns its path.  Its golden files are recorded
    from the reference spec in the arithmetic of ``planner`` (None: x86-64's)."""
    arith = planner.arithmetic if planner is not None and planner.arithmetic is not None else X86_64
    from ..backends import get_backend
    from ..difftest.record import golden_fields, write_golden
    from ..maps.pictures import render_case

    costs = np.ascontiguousarray(costs, np.uint8)
    mode = "astar" if astar else "dijkstra"
    start, goal = (int(start[0]), int(start[1])), (int(goal[0]), int(goal[1]))
    out = Path(out_dir)
    try:
        out.mkdir(parents=True, exist_ok=True)
    except OSError as e:
        raise NavfnInputError(f"{out}: cannot create directory ({e.strerror})") from None
    final = out / (name or directory_name(kind, mode, costs, arith))
    tmp = out / f".{final.name}.tmp{os.getpid()}"
    old = out / f".{final.name}.old{os.getpid()}"
    shutil.rmtree(tmp, ignore_errors=True)
    try:
        write_map_dir(tmp, costs, [(*start, *goal)], comment=f"{kind} counterexample ({mode})")
        smap = load_map(tmp)
        ref = get_backend("reference", planner).prepare(costs)
        for m in MODES:
            write_golden(smap.golden_path(m), golden_fields(smap, ref, m == "astar"))
        res = ref.run(start, goal, astar, trace=False)
        h, w = costs.shape
        render_case(costs, res, start, goal, str(tmp / PICTURE_NAME),
                    title=_title(kind, astar, w, h, detail),
                    arrows=True)
        doc = {"kind": kind, "mode": mode, "size": [w, h], "start": list(start), "goal": list(goal),
               "detail": jsonable(detail), **jsonable(extra or {}),
               **({"arithmetic": arith.name} if arith != X86_64 else {})}
        doc["is_one_in"] = stands_in(doc, costs)
        (tmp / JSON_NAME).write_text(json.dumps(doc, indent=2) + "\n", encoding="utf-8")
        if final.exists():
            os.replace(final, old)
        os.replace(tmp, final)
        shutil.rmtree(old, ignore_errors=True)
    except OSError as e:
        shutil.rmtree(tmp, ignore_errors=True)
        raise NavfnInputError(f"{final}: cannot write ({e.strerror or e})") from None
    except BaseException:
        shutil.rmtree(tmp, ignore_errors=True)
        raise
    return final


def _title(kind: str, astar: bool, w: int, h: int, detail: dict) -> str:
    t = f"{kind} ({'A*' if astar else 'Dijkstra'}) {w}x{h}"
    if "gap" in detail:
        return f"{t}: gap {detail['gap']}, ratio {detail['ratio']:.2f}"
    if "exit" in detail:
        return f"{t}: exit {detail['exit']}"
    return t


def read_counterexample(directory) -> dict:
    """``counterexample.json`` of a saved counterexample."""
    p = Path(directory) / JSON_NAME
    try:
        return json.loads(p.read_text(encoding="utf-8"))
    except FileNotFoundError:
        raise NavfnInputError(f"{p}: no such file") from None
    except (OSError, ValueError) as e:
        raise NavfnInputError(f"{p}: unreadable ({e})") from None


def judge_kind(kind: str, r: P.Run, doc: Optional[dict] = None, arith=None) -> Optional[dict]:
    """The judge of ``kind``: a search kind of :mod:`.kinds`, ``overflow`` (judged by
    :mod:`.overflow`, imported only then: ``r`` replanned with unbounded buffers in ``r``'s
    arithmetic ``arith``, None: x86-64's) or a property of :data:`properties.PROPERTIES`
    (``optimal`` takes the ``gap`` allowed from ``doc``'s ``allowed_gap``)."""
    if kind in KD.KINDS:
        return KD.KINDS[kind].judge(r)
    if kind == "overflow":
        try:
            from .overflow import judge as overflow_judge
        except ImportError as e:
            raise NavfnInputError(f"overflow counterexamples need navfn_smt.search.overflow ({e})") from None
        cap = (doc or {}).get("detail", {}).get("capacity")
        return overflow_judge(r, arith=arith) if cap is None else overflow_judge(r, capacity=int(cap), arith=arith)
    if kind == "optimal":
        why = P.judge(kind, r, gap=int((doc or {}).get("allowed_gap", 0)))
    elif kind in P.PROPERTIES:
        why = P.judge(kind, r)
    else:
        raise NavfnInputError(f"unknown counterexample kind {kind!r}")
    return None if why is None else {"reason": why}


def planner_of(doc: dict) -> PlannerUnderTest:
    """The planner a saved counterexample was found in: its variant, in the arithmetic its
    golden files were recorded in (``arithmetic``; x86-64's when it names none)."""
    return PlannerUnderTest.of_target(doc.get("arithmetic"), fixes.named(doc.get("variant", fixes.DEFAULT.name)))


def judged_in_each(doc: dict, costs: np.ndarray, start, goal) -> dict:
    """``{arithmetic: the detail of doc's kind's judge, None where the case is no counterexample}``,
    the spec planning ``start`` to ``goal`` on ``costs`` in each known arithmetic (the fixed
    variant in x86-64's only, the one it computes in so far)."""
    fix = planner_of(doc).fix
    return {name: judge_kind(doc["kind"], P.run(costs, start, goal, doc["mode"] == "astar", fix=fix,
                                                arith=arith), doc, arith)
            for name, arith in KNOWN.items() if fix.shipped or arith == X86_64}


def stands_in(doc: dict, costs: np.ndarray) -> dict:
    """``{arithmetic: whether the case of doc is a counterexample of its kind}`` (:func:`judged_in_each`)."""
    judged = judged_in_each(doc, costs, tuple(doc["start"]), tuple(doc["goal"]))
    return {name: detail is not None for name, detail in judged.items()}


def golden_differences(directory, backend: str, planner: Optional[PlannerUnderTest] = None) -> list[str]:
    """Fields of the stored golden files that ``backend`` (computing as ``planner``; None: NavFn
    as shipped, in x86-64's arithmetic) does not reproduce bit for bit."""
    from ..backends import get_backend
    from ..difftest.record import golden_fields

    smap = load_map(directory)
    prepared = get_backend(backend, planner).prepare(smap.costs)
    diffs = []
    for m in MODES:
        stored = load_golden(smap.golden_path(m), smap)
        fresh = golden_fields(smap, prepared, m == "astar")
        for f in GOLDEN_FIELDS:
            a, b = np.asarray(stored[f]), np.asarray(fresh[f])
            if a.dtype != b.dtype or a.shape != b.shape or a.tobytes() != b.tobytes():
                diffs.append(f"{m} {f}")
    return diffs


def replay(directory) -> dict:
    """Replay a saved counterexample: its golden files on the reference spec and the JIT (bit
    for bit, in the arithmetic it was found in), its kind's judge on the spec, and in which
    known arithmetics it is one (``is_one_in``, for the test to hold against the recorded one).
    Returns the problems found (empty lists and a detail when it still stands)."""
    doc = read_counterexample(directory)
    smap = load_map(directory)
    sx, sy, gx, gy = (int(v) for v in smap.cases[0])
    planner = planner_of(doc)
    judged = judged_in_each(doc, smap.costs, (sx, sy), (gx, gy))  # its own arithmetic among them
    return {
        "kind": doc["kind"],
        "golden": {b: golden_differences(directory, b, planner) for b in ("reference", "jit")},
        "detail": judged[planner.arithmetic.name],
        "is_one_in": {name: detail is not None for name, detail in judged.items()},
    }
