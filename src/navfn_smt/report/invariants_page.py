"""The invariants page, ``docs/invariants.md``: the one generator behind ``navfn-smt docs``
and ``navfn-smt prove --markdown``.

The page is built from three sources and nothing else:

* the proof obligations as declared now (``navfn_smt/proofs/*.py``): their statements in
  English and as formulas, their scopes, and the spec kernels they run, which name the
  C++ function each one is about;
* the paper's predicates as chains of obligations (``navfn_smt/proofs/__init__.py``);
* the latest reports, committed as data: a ``navfn-smt prove --report`` run
  (``docs/reports/prove.json``) for the obligations' verdicts, and ``navfn-smt check
  --json`` runs (``docs/reports/check*.json``) for the whole-planner properties.

No solver runs here: generating the page only reads, so it takes well under a second and
gives the same text for the same inputs (the only times on the page are the reports' own).
What no report covers is written as *not run*, never guessed.  Counterexamples of
``check`` link to a picture under ``images/`` beside the reports directory
(``images/check-<property>-<mode>-<W>x<H>.png``) when one is committed there; the
obligations' witnesses are kernel inputs, not maps, and are given as values.

This module renders what it is given (:func:`render`) and reads the reports' JSON (one-line
errors on a missing or malformed one); the commands gather the rest, the obligations and
what is known of them (:func:`navfn_smt.commands.common.page_sources`).
"""

from __future__ import annotations

import ast
import functools
import inspect
import json
import textwrap
from pathlib import Path
from typing import Optional

from ..errors import NavfnInputError
from ..smt.chains import outcome_verdicts
from . import predicates

DEFAULT_OUT = Path("docs") / "invariants.md"
REPORTS_DIR = Path("docs") / "reports"
DEFAULT_PROVE_REPORT = REPORTS_DIR / "prove.json"
CHECK_REPORT_GLOB = "check*.json"

# The C++ code each spec kernel (spec/kernels.py) is the arithmetic of, in navfn.cpp.
KERNEL_CODE = {
    "planar_wave": "`NavFn::updateCell` / `updateCellAstar`: the planar-wave candidate potential",
    "cell_update": "`NavFn::updateCell` / `updateCellAstar`: one update of a cell's potential",
    "edge_weight": "`NavFn::updateCell`: the neighbour's edge weight `INVSQRT2 * costarr[m]`",
    "astar_heuristic": "`NavFn::updateCellAstar`: the distance heuristic",
    "push_wanted": "`NavFn::updateCell`: the test that asks to enqueue a neighbour",
    "to_low_buffer": "`NavFn::updateCell`: `push_next` below `curT`, else `push_over`",
    "push_admitted": "the `push_cur` / `push_next` / `push_over` macros: their guard",
    "push": "the `push_cur` / `push_next` / `push_over` macros: the guard, the pending flag, a push dropped",
    "buffer_swap": "`NavFn::propNavFnDijkstra` / `propNavFnAstar`: the buffer swap at a cycle's end",
    "end_of_cycle": "`NavFn::propNavFnDijkstra` / `propNavFnAstar`: a cycle's end (the swap, `curT += priInc`)",
    "is_passable": "`NavFn::updateCell`: the obstacle test",
    "grad_cell": "`NavFn::gradCell`",
    "grad_vector": "`NavFn::gradCell`: the unnormalised difference vector",
    "normalise": "`NavFn::gradCell`: the normalisation by `hypotf`",
    "grad_cached": "`NavFn::gradCell`: the early return on a stored gradient",
    "bilinear": "`NavFn::calcPath`: one bilinear interpolation",
    "interpolate_gradient": "`NavFn::calcPath`: the interpolated gradient",
    "step_offsets": "`NavFn::calcPath`: the gradient step of the offsets",
    "wrap_offsets": "`NavFn::calcPath`: the offset wrapped back into the cell, moving the cell",
    "nearest_cell": "`NavFn::calcPath`: the near-goal probe",
    "path_point": "`NavFn::calcPath`: the point appended to the path",
    "lowest_of_eight": "`NavFn::calcPath`: the grid-following fallback",
    "near_goal": "`NavFn::calcPath`: the goal test",
    "lowest_neighbour": "`NavFn::calcPathDescent` (the fix, `patches/navfn-fix/`): the descent's step",
    "unreached": "`potarr[n] >= POT_HIGH` tests",
    "add_mul": "`NavFn::updateCell` (`ta + hf * v`) and `calcPath` (`dx += x * ss`): a float multiply-add a build "
               "may fuse",
    "mul_add64": "`NavFn::updateCell` (the quadratic) and `calcPath` (the interpolation): a double multiply-add a "
                 "build may fuse",
    # the loops' steps the spec and the JIT run, by module
    "propagation.cycle_runs": "`NavFn::propNavFnDijkstra` / `propNavFnAstar`: the loop's test at a cycle's top",
    "propagation.propagate": "`NavFn::setupNavFn`, `initCost` and `propNavFnDijkstra` / `propNavFnAstar`: the run "
                             "over arrays, its loops cut at their invariants (smt/program.py)",
    "propagation.call_ends_at_the_start": "`NavFn::propNavFnDijkstra` / `propNavFnAstar`: the start test at a "
                                          "cycle's end",
    "extraction.iteration_test": "`NavFn::calcPath`: the tests at an iteration's top (the near-goal probe, the "
                                 "bound tests)",
    "extraction.follows_the_grid": "`NavFn::calcPath`: the test for the grid-following fallback",
    "extraction.grid_step": "`NavFn::calcPath`: the grid-following step",
    "extraction.goal_point": "`NavFn::calcPath`: the goal point of the near-goal exit",
    "extraction.ring_of_eight": "`NavFn::calcPath`: the eight neighbours its fallback reads",
    "fix.calls_again": "`NavFn::calcNavFnAstar` / `calcNavFnDijkstra` (the fix, `patches/navfn-fix/`): the test "
                       "for the second `propNavFn*` call",
    "fix.descent_iteration": "`NavFn::calcPathDescent` (the fix, `patches/navfn-fix/`): one pass of its loop",
    "fix.descent_ring": "`NavFn::calcPathDescent` (the fix, `patches/navfn-fix/`): the eight neighbours it reads",
}
# the spec modules whose functions an obligation can run: the kernels (named bare) and the loops' steps
SPEC_MODULES = {"navfn_smt.spec.kernels": "", "navfn_smt.spec.propagation": "propagation.",
                "navfn_smt.spec.extraction": "extraction.", "navfn_smt.spec.fix": "fix."}

# The whole-planner properties of ``check``: formula and the planner code they are about
# (their English statements come from check/properties.py).
CHECK_DOCS = {
    "queues-obstacle-free": (
        "always (for every n in curP + nextP + overP:  costarr[n] < COST_OBS)",
        "`NavFn::propNavFnDijkstra` / `propNavFnAstar`: the three priority buffers over the whole run "
        "(`setupNavFn`, `initCost`, every cycle's `push_cur` / `push_next` / `push_over`); the paper's LTL "
        "invariant over the queues"),
    "no-path-before-start-potential": (
        "not PathComputed  W  potarr[start] < POT_HIGH   (calcPath returns npath > 0 only if potarr[start] "
        "< POT_HIGH)",
        "`NavFn::calcNavFnDijkstra` / `calcNavFnAstar`, then `NavFn::calcPath`: the paper's "
        "`~PathComputed W NonInfinitePotAtInit`"),
    "valid-path": (
        "for every point p of the returned path:  some cell c with |p - c| <= 1/2 per axis,  "
        "potarr[c] < POT_HIGH  and  costarr[c] < COST_OBS",
        "`NavFn::calcPath`: the path NavFn hands to Nav2; the paper's ValidPath over the whole run"),
    "start-reached": (
        "start and goal joined by a 4-connected chain of passable cells (the goal's cost aside)  "
        "==>  potarr[start] < POT_HIGH",
        "`NavFn::propNavFnDijkstra` / `propNavFnAstar`: the wave within the cycle limit "
        "`max(nx*ny/20, nx+ny)`"),
    "complete": (
        "potarr[start] < POT_HIGH  ==>  calcPath returns a path (exit near_goal)",
        "`NavFn::calcPath`: its `4*nx` iterations, fallback and near-goal test"),
}

INTRO = ("Each obligation below is a property of the specification's kernels, stated once and checked "
         "in two semantics: `real` (the paper's abstraction: no rounding) and `fp32` (bit-precise IEEE-754 "
         "binary32/binary64 as the compiled C++ computes on x86-64), and where the float32 columns "
         "`fp32@NAME` are shown, as a build for NAME computes (its multiply-adds fused, its conversions). `proved` means the solver showed the negation "
         "unsatisfiable; `refuted` means it found a counterexample, which was replayed on the concrete "
         "specification (*bounded* when a bound found by search still proves it below); `unknown` means nothing "
         "is known and no solver decided in time (never counted as proved); `not run` means the report has no "
         "verdict for it. Each verdict is the obligation's *standing*: the report's decision (or its split's) where "
         "one was made, otherwise what is known of it, its source named (`declared`, `split`, `chain P`, "
         "`recorded`: see [proofs.md](proofs.md)); a whole query left undecided is no failure, a decision against "
         "what is known is. "
         "The whole-planner properties of `navfn-smt check` are decided for every map of a size (a "
         "*bounded-size proof*), in fp32 only, and for every size when an induction carries them. An obligation's counterexample is a set of kernel "
         "inputs (a cell's and its neighbours' values), not a map, so it is given as values; a whole-planner "
         "counterexample is a map, drawn when its picture is committed under `images/`.")


# ------------------------------------------------------------------------------ reading
SPLIT_REPORT = "split.json"  # beside the prove report: a `navfn-smt split --report` run


def split_beside(reports_dir) -> Optional[tuple]:
    """The ``(label, doc)`` of the split report in ``reports_dir`` (:data:`SPLIT_REPORT`), if there is one."""
    path = Path(reports_dir) / SPLIT_REPORT
    return (report_label(path), _read_json(path, "split")) if path.is_file() else None


def default_check_reports(reports_dir: Path = REPORTS_DIR) -> list[Path]:
    """The committed ``check`` reports: every ``check*.json`` of the reports directory, by name."""
    return sorted(Path(reports_dir).glob(CHECK_REPORT_GLOB)) if Path(reports_dir).is_dir() else []


def _read_json(path, what: str) -> dict:
    p = Path(path)
    if not p.is_file():
        raise NavfnInputError(f"{path}: no such {what} report" + (" (it is a directory)" if p.is_dir() else ""))
    try:
        doc = json.loads(p.read_text(encoding="utf-8"))
    except UnicodeDecodeError:
        raise NavfnInputError(f"{path}: not a JSON {what} report (not UTF-8 text)") from None
    except json.JSONDecodeError as e:
        raise NavfnInputError(f"{path}: not a JSON {what} report ({e.msg} at line {e.lineno})") from None
    except OSError as e:
        raise NavfnInputError(f"{path}: cannot read ({e.strerror})") from None
    if not isinstance(doc, dict):
        raise NavfnInputError(f"{path}: not a {what} report (a JSON object expected)")
    return doc


OBLIGATION_KEYS = ("name", "property", "semantics", "status", "seconds", "solver")


def read_prove_report(path) -> dict:
    """A ``navfn-smt prove --report`` document, checked to have what the page reads."""
    doc = _read_json(path, "prove")
    obs = doc.get("obligations")
    if not isinstance(obs, list) or not all(isinstance(o, dict) and all(k in o for k in OBLIGATION_KEYS)
                                            for o in obs):
        raise NavfnInputError(f"{path}: not a prove report (no list of obligations with "
                              f"{', '.join(OBLIGATION_KEYS)}; write one with `navfn-smt prove --report`)")
    return doc


def with_arithmetics(prove_doc: dict, prove_report) -> dict:
    """The prove report with the runs in other build arithmetics beside it joined in: each
    ``prove-NAME.json`` (``navfn-smt prove --target NAME --all --report``) whose semantics are
    float32 of another arithmetic (``fp32@NAME``) adds its verdicts and a column per semantics;
    ``arithmetics`` lists them, ``(label, when)``, for the page's opening lines."""
    from ..smt.domains import FP32_SEMANTICS

    doc = {**prove_doc, "obligations": list(prove_doc["obligations"]),
           "semantics": list(prove_doc.get("semantics") or []), "arithmetics": []}
    for sem in FP32_SEMANTICS:
        path = Path(prove_report).parent / f"prove-{sem.partition('@')[2]}.json"
        if sem == "fp32" or not path.is_file():
            continue
        other = read_prove_report(path)
        if list(other.get("semantics") or []) != [sem]:
            raise NavfnInputError(f"{path}: not a run in {sem} alone (its semantics: "
                                  f"{', '.join(other.get('semantics') or []) or 'none'}; write it with "
                                  f"`navfn-smt prove --target {sem.partition('@')[2]} --all --report {path}`)")
        doc["obligations"] += other["obligations"]
        doc["semantics"].append(sem)
        doc["arithmetics"].append((report_label(path), other.get("when", "?")))
    return doc


CHECK_KEYS = ("property", "size", "status", "enumerated", "solved", "seconds")


def read_check_report(path) -> dict:
    """A ``navfn-smt check --json`` document, checked to have what the page reads."""
    doc = _read_json(path, "check")
    res = doc.get("results")
    if doc.get("command") != "check" or not isinstance(res, list) or not all(
            isinstance(r, dict) and all(k in r for k in CHECK_KEYS) for r in res):
        raise NavfnInputError(f"{path}: not a check report (no \"command\": \"check\" with a list of results; "
                              f"write one with `navfn-smt check ... --json`)")
    return doc


def outcomes_of(prove_doc: dict) -> list:
    """The prove report's rows as the run's outcomes (what the predicates' summary derives from)."""
    from ..smt.checking import Outcome

    return [Outcome(name=r["name"], predicate=r["property"], semantics=r["semantics"], status=r["status"],
                    known=r.get("known", r.get("expected", "unknown")), seconds=float(r["seconds"]), solver=r["solver"],
                    scope=r.get("scope", ""), statement=r.get("statement", ""),
                    assumptions=list(r.get("assumptions") or []), bound=r.get("bound"),
                    witness=r.get("witness_values"), detail=r.get("detail", ""))
            for r in prove_doc["obligations"]]


# ------------------------------------------------------------------ obligations' texts
def statement_parts(doc: str) -> tuple[str, list[str], list[str]]:
    """An obligation's docstring as (English statement, notes, formula lines): the first
    paragraph, the paragraphs between, the last paragraph (the formula)."""
    paras = [p for p in inspect.cleandoc(doc or "").split("\n\n") if p.strip()]
    if not paras:
        return "", [], []
    english = " ".join(ln.strip() for ln in paras[0].splitlines())
    if len(paras) == 1:
        return english, [], []
    notes = [" ".join(ln.strip() for ln in p.splitlines()) for p in paras[1:-1]]
    return english, notes, [ln.rstrip() for ln in paras[-1].splitlines()]


RUN = "propagation.propagate"


def kernels_used(build) -> list[str]:
    """The spec functions an obligation's ``build`` calls, in order of first use: the kernels
    (``K.name``, named bare) and the loops' steps (``P.``, ``E.``, ``F.``: ``propagation.name``,
    ...), following the helper functions of its proof file and of the proof files it imports
    from."""
    proofs = Path(build.__code__.co_filename).parent
    seen_fns, found = set(), []

    def visit(fn) -> None:
        if fn in seen_fns:
            return
        seen_fns.add(fn)
        scope = fn.__globals__  # the proof file's names (it is not in sys.modules)
        try:
            tree = ast.parse(textwrap.dedent(inspect.getsource(fn)))
        except (OSError, TypeError, SyntaxError):
            return
        for node in ast.walk(tree):
            if isinstance(node, ast.Attribute) and isinstance(node.value, ast.Name):
                module = scope.get(node.value.id)
                prefix = SPEC_MODULES.get(getattr(module, "__name__", None))
                name = f"{prefix}{node.attr}"
                if prefix is not None and inspect.isfunction(getattr(module, node.attr, None)) and name not in found:
                    found.append(name)
            elif isinstance(node, ast.Call) and isinstance(node.func, ast.Name):
                helper = scope.get(node.func.id)
                if inspect.isfunction(helper) and Path(helper.__code__.co_filename).parent == proofs:
                    visit(helper)
                elif getattr(helper, "__module__", None) == "navfn_smt.smt.program" and RUN not in found:
                    found.append(RUN)  # a segment of the spec's run over arrays

    visit(build)
    return found


def planner_code(build) -> str:
    """Where in the C++ an obligation applies, from the kernels it runs."""
    ks = kernels_used(build)
    if not ks:
        return ""
    return "; ".join(f"{KERNEL_CODE.get(k, 'spec function')} (spec `{k if '.' in k else 'kernels.' + k}`)"
                     for k in ks)


# ---------------------------------------------------------------------------- helpers
def report_label(path) -> str:
    """A report as the page names it: ``reports/NAME`` (a link from docs/) or its file name."""
    p = Path(path)
    for up in p.parents:
        if up.name == "reports":  # reports/NAME, or reports/ARITHMETIC/VARIANT/NAME
            return f"reports/{p.relative_to(up).as_posix()}"
    return p.name


def _fmt_seconds(s) -> str:
    s = float(s)
    return f"{s:.2f} s" if s < 60 else f"{s:.0f} s ({int(s // 60)} min {s % 60:.0f} s)"


def _witness_text(r) -> str:
    vals = ", ".join(f"{k} = {v['value']!r}" for k, v in r.witness["values"].items())
    text = f"counterexample: {vals}"
    if r.witness.get("replayed_on_spec"):
        text += " (replayed on the concrete spec)"
    return text


def _not_run(known: dict, name: str, semantics: str) -> str:
    """An obligation the report has no verdict for: not run, and what is known of it."""
    k = known.get((name, semantics))
    return "not run" + (f" (known {k.status}: {k.source})" if k is not None and k.status != "unknown" else "")


def _obligation_lines(ob, rows: dict, sems: list, known: dict) -> list[str]:
    """One obligation's subsection: statement, formula, where it applies, verdict per semantics."""
    english, notes, formula = statement_parts(ob.doc)
    out = [f"### `{ob.name}`", "", english or ob.name, ""]
    if notes:
        out += [*notes, ""]
    if formula:
        out += ["    " + ln for ln in formula] + [""]
    where = planner_code(ob.build)
    out.append(f"*Planner code:* {where}." if where else
               f"*Planner code:* written out in the obligation, no spec kernel: {ob.predicate}'s part of the "
               f"planner (*Applies to* above).")
    out += ["", f"*Scope:* {ob.scope}."]
    notes_lib = sorted({n for r in rows.values() for n in r.assumptions})
    if notes_lib:
        out += ["", "*Library models assumed:* " + "; ".join(notes_lib) + "."]
    out.append("")
    for s in sems:
        r = rows.get(s)
        if r is None:
            out.append(f"- **{s}**: {_not_run(known, ob.name, s)}")
            continue
        line = f"- **{s}**: {predicates.standing_text(r)}; the whole query: {r.status} in {r.seconds:.2f} s ({r.solver})"
        if r.bound and r.bound.get("holds_below") is not None and r.standing == "refuted":
            line += (f"; bounded: holds for `{r.bound['var']} < {r.bound['holds_below']!r}`, found by search "
                     f"(refuted below {r.bound.get('refuted_below')!r})")
        if r.witness:
            line += "; " + _witness_text(r)
        if r.detail:
            line += f"; {r.detail}"
        if r.fails:
            line += f"; **contradicts the known {r.known} ({r.known_source})**"
        out.append(line)
    out.append("")
    return out


# ------------------------------------------------------------------ the check section
def _size(s) -> str:
    return f"{s[0]}x{s[1]}"


def _check_command(doc: dict) -> str:
    a = doc.get("arguments") or {}
    prop = a.get("property", "?")
    parts = ["navfn-smt check", " ".join(prop) if isinstance(prop, list) else str(prop)]
    if a.get("max_size"):
        parts.append("--max-size " + " ".join(map(str, a["max_size"])))
    elif a.get("size"):
        parts.append("--size " + " ".join(map(str, a["size"])))
    for opt in ("mode", "costs", "ends", "timeout", "jobs"):
        if a.get(opt) is not None:
            parts.append(f"--{opt} {a[opt]}")
    return " ".join(parts)


OPEN_UP_TO = 8  # the page names the sizes up to this many interior cells that no report decides


def _open_sizes(by_size: dict) -> list:
    """The sizes of at most :data:`OPEN_UP_TO` interior cells, below the smallest refuted one,
    that no report decides (proved or refuted)."""
    decided = {s for s, (r, _) in by_size.items() if r["status"] in ("proved", "refuted")}
    refuted = [(s[0] - 2) * (s[1] - 2) for s, (r, _) in by_size.items() if r["status"] == "refuted"]
    most = min([OPEN_UP_TO] + [c - 1 for c in refuted])
    sizes = [(w, h) for w in range(3, most + 3) for h in range(3, most + 3) if (w - 2) * (h - 2) <= most]
    return [s for s in _sorted_sizes(dict.fromkeys(sizes)) if s not in decided]


REPLAY_LINK = "reports/certificates/"


def _certificate(certs: Optional[Path], s, prop: str) -> str:
    """The size's committed certificate, as a link from docs/, when it certifies ``prop`` (its
    header's verdicts name the properties it covers); else a dash."""
    name = f"check-{s[0]}x{s[1]}.cert.json.gz"
    if certs is None or not (certs / name).is_file():
        return "-"
    if prop not in _certified(certs / name):
        return "-"
    return f"[{name}](reports/certificates/{name}){_replayed(certs / f'check-{s[0]}x{s[1]}.replay.json')}"


def _replayed(path: Path) -> str:
    """What the certificate's committed replay report says: the solvers that re-asked its unsats
    and what it trusted (``check --replay``; docs/check.md has the table), or that it has none."""
    if not path.is_file():
        return _replayed_parts(path)
    doc = _read_json(path, "replay")
    if doc.get("status") != "replayed":
        return f"; [replay]({REPLAY_LINK}{path.name}): {doc.get('status')}"
    asked = ", ".join(f"{n:,} by {who}" for who, n in sorted(doc["evidence"]["unsat_reasked"].items())) or "none"
    t = doc["trusted"]
    return (f"; [replayed]({REPLAY_LINK}{path.name}) (unsats asked again: {asked}); trusted {t['count']:,}: "
            f"{t['held_on_box_by_intervals']:,} held on the box by intervals, {t['paths_cut_by_queued_start']:,} "
            f"paths cut by QueuedStartReached, {t['cases_by_reduction']:,} cases by the reduction")


def _replayed_parts(path: Path) -> str:
    """A replay done in parts so far (``check --replay --part K/N``, reports in ``parts/``): how
    many of the N parts replayed, or that none has."""
    stem = path.name.replace(".replay.json", "")
    files = sorted((path.parent / "parts").glob(f"{stem}.replay-*of*.json"))
    done = sorted(((f, r) for f in files if (r := _read_json(f, "replay")).get("status") == "replayed"),
                  key=lambda fr: fr[1]["part"][0])  # in the parts' order: 1, 2, ..., 10, not 1, 10, 11, ...
    if not done:
        return "; not replayed"
    n = done[0][1]["part"][1]
    paths = sum(r["paths"] for _, r in done)
    links = ", ".join(f"[{r['part'][0]}]({REPLAY_LINK}parts/{f.name})" for f, r in done)
    return (f"; replayed in parts so far: {len(done)} of {n} (parts {links}; {paths:,} control "
            f"paths re-checked); the whole replay once every part is (`check --replay --combine`)")


@functools.lru_cache(maxsize=None)
def _certified(path: Path) -> frozenset:
    """The properties a certificate gives a verdict for."""
    from ..check import certificate

    return frozenset(certificate.read(path)["verdicts"])


def _size_time(r: dict) -> str:
    """A size's time; a run resumed from a journal adds the journaled cases and the case time
    of every run."""
    t = _fmt_seconds(r["seconds"])
    if r.get("cases_from_journal"):
        t += (f" (resumed: {r['cases_from_journal']} cases journaled by earlier runs; "
              f"{_fmt_seconds(r['case_seconds'])} of case time in all)")
    return t


def _merge_checks(checks: list) -> tuple[dict, dict, dict]:
    """Per property: its rows by size (a later report replaces an earlier one's row), its
    induction result and the reason it is not inductive, with the report each came from."""
    rows: dict = {}
    induction: dict = {}
    not_inductive: dict = {}
    for label, doc in checks:
        for r in doc["results"]:
            rows.setdefault(r["property"], {})[tuple(r["size"])] = (r, label)
        for n, ind in (doc.get("every_size_by_induction") or {}).items():
            if ind:
                induction[n] = ind
        not_inductive.update(doc.get("not_inductive") or {})
    return rows, induction, not_inductive


def _sorted_sizes(by_size: dict) -> list:
    return sorted(by_size, key=lambda s: ((s[0] - 2) * (s[1] - 2), s))


def _picture(images: Optional[Path], prop: str, cx: dict) -> Optional[str]:
    if images is None or not cx or "size" not in cx and "costs" not in cx:
        return None
    if "costs" in cx:
        h, w = len(cx["costs"]), len(cx["costs"][0])
    else:
        w, h = cx["size"]
    name = f"check-{prop}-{cx.get('mode', '')}-{w}x{h}.png"
    return f"images/{name}" if (images / name).is_file() else None


def _cx_text(cx: dict) -> str:
    return (f"{cx.get('mode', '?')}, start {tuple(cx.get('start', ()))}, goal {tuple(cx.get('goal', ()))}: "
            f"{cx.get('reason', '')}")


def check_status(prop: str, by_size: dict, induction: dict) -> str:
    """One line: the fp32 status of a whole-planner property from the reports."""
    if not by_size:
        return "not run"
    sizes = _sorted_sizes(by_size)
    refuted = [s for s in sizes if by_size[s][0]["status"] == "refuted"]
    proved = [s for s in sizes if by_size[s][0]["status"] == "proved"]
    unknown = [s for s in sizes if by_size[s][0]["status"] not in ("proved", "refuted")]
    parts = []
    ind = induction.get(prop)
    if ind and ind.get("rank", ind.get("status")) == "proved":
        parts.append(f"{ind['status']} for every size (induction)")
    if refuted:
        parts.append(f"refuted at {_size(refuted[0])}")
    if proved:
        parts.append("bounded-size proof: " + ", ".join(_size(s) for s in proved))
    if unknown:
        parts.append("unknown at " + ", ".join(_size(s) for s in unknown))
    return "; ".join(parts)


def check_section(checks: list, images: Optional[Path], verdict_of=None) -> list[str]:
    """The whole-planner properties: a summary table, then one subsection per property.  An
    induction's status is derived from its predicates' standings (``verdict_of``, the page's
    one status per obligation), not copied from the check report that ran it."""
    from ..check.common import INDUCTION_NARROW
    from ..check.properties import PROPERTIES
    from ..check.runner import CHECKABLE, INDUCTION, NOT_INDUCTIVE, induction_status
    from .check import verdict_text

    rows, induction, not_inductive = _merge_checks(checks)
    if verdict_of is not None:
        induction = {n: {**ind, **induction_status(n, verdict_of)} for n, ind in induction.items()}
    out = ["## Whole-planner properties (`navfn-smt check`)", "",
           "Each property below is about the whole planner (setup, propagation with its bounded buffers, "
           "cycle limit, then `calcPath` with every exit) and is decided for every map of a size: lethal "
           "layouts, start and goal enumerated, costs symbolic, float32 control paths explored (see "
           "[check.md](check.md)). The real semantics does not apply (the exploration follows float32 "
           "control paths). A size without a row here has no committed report.", ""]
    if checks:
        out += ["Reports read:", ""]
        for label, doc in checks:
            out.append(f"- [{label}]({label}): `{_check_command(doc)}`; costs "
                       f"{'..'.join(map(str, doc.get('costs', []))) or '?'}, ends {doc.get('ends', '?')}, "
                       f"{doc.get('semantics', '?')}; {_fmt_seconds(doc.get('seconds', 0))} in all"
                       + (", resumed from a journal" if any(r.get("cases_from_journal") for r in doc["results"])
                          else ""))
        out.append("")
    else:
        out += ["No check report was given: every property is *not run*.", ""]
    out += ["| property | fp32 status (from the reports) | every size |", "|---|---|---|"]
    for n in CHECKABLE:
        if n in INDUCTION:
            ind = induction.get(n)
            every = (f"by induction: {ind['status']}" if ind else "inductive (" + ", ".join(INDUCTION[n])
                     + "); not run")
        else:
            every = "not inductive"
        out.append(f"| `{n}` | {check_status(n, rows.get(n, {}), induction)} | {every} |")
    out.append("")
    for n in CHECKABLE:
        formula, applies = CHECK_DOCS.get(n, ("", ""))
        out += [f"### `{n}`", "", PROPERTIES[n].statement[0].upper() + PROPERTIES[n].statement[1:] + ".", ""]
        if formula:
            out += ["    " + formula, ""]
        if applies:
            out += [f"*Planner code:* {applies}.", ""]
        out += [f"*Judge:* `check/properties.py`, `{PROPERTIES[n].judge.__name__}`.", ""]
        ind = induction.get(n)
        if ind:
            obs = ", ".join(f"`{k}`" for k in ind.get("obligations", {}))
            out += [f"*Every size:* by induction over {', '.join(ind.get('predicates', []))}: **{ind['status']}** "
                    f"(fp32, the predicates' status above; their links: {obs}).", ""]
        elif n in INDUCTION:
            out += [f"*Every size:* carried by {', '.join(INDUCTION[n])}; no report of the induction.", ""]
        else:
            out += [f"*Every size:* not inductive: {not_inductive.get(n, NOT_INDUCTIVE.get(n, ''))}.", ""]
        if n in INDUCTION_NARROW:
            out += [f"*Narrow sizes* (interior at most two cells wide or tall, at most 4*nx cells): by induction over "
                    f"{', '.join(INDUCTION_NARROW[n])}; `check {n}` alone decides them without exploring.", ""]
        by_size = rows.get(n, {})
        if not by_size:
            out += ["*Bounded sizes:* not run (no report).", ""]
            continue
        certs = images.parent / "reports" / "certificates" if images is not None else None
        out += ["| size | interior cells | verdict | cases | explored | control paths | solver queries | time (the size, every property) | report | certificate |",
                "|---|---|---|---|---|---|---|---|---|---|"]
        for s in _sorted_sizes(by_size):
            r, label = by_size[s]
            verdict = verdict_text(r["status"], r.get("method", "exploration"))
            out.append(f"| {_size(s)} | {r.get('interior_cells', (s[0] - 2) * (s[1] - 2))} | {verdict} | "
                       f"{r['enumerated'].get('cases', '?')} | {r['enumerated'].get('explored', '-')} | "
                       f"{r['solved'].get('control_paths', '?')} | "
                       f"{r['solved'].get('solver_queries', '?')} | {_size_time(r)} | {label} | "
                       f"{_certificate(certs, s, n) if r['status'] == 'proved' else '-'} |")
        out.append("")
        still = [] if ind and ind.get("status") == "proved" else _open_sizes(by_size)
        if still:
            out += [f"*Open sizes* (at most {OPEN_UP_TO} interior cells, below any counterexample, no report "
                    "decides them): " + ", ".join(_size(s) for s in still) + ".", ""]
        out += [f"*Status:* fp32 **{check_status(n, by_size, induction)}**.", ""]
        refuted = [s for s in _sorted_sizes(by_size) if by_size[s][0]["status"] == "refuted"]
        if refuted:
            cx = by_size[refuted[0]][0].get("counterexample") or {}
            out += [f"*Counterexample* ({_size(refuted[0])}, replayed on the spec): {_cx_text(cx)}.", ""]
            pic = _picture(images, n, cx)
            if pic:
                out += [f"![{n}, {cx.get('mode', '')}, {_size(refuted[0])}]({pic})", ""]
            elif cx.get("costs"):
                out += ["Its costs (rows, lethal border included):", ""]
                out += ["    " + " ".join(f"{c:3d}" for c in row) for row in cx["costs"]] + [""]
        unknown = [s for s in _sorted_sizes(by_size) if by_size[s][0]["status"] not in ("proved", "refuted")]
        for s in unknown:
            r = by_size[s][0]
            out += [f"*Unknown at {_size(s)}:* {r.get('cases_unknown', '?')} cases undecided.", ""]
    return out


def flavoured_check_reports(check_reports) -> list[Path]:
    """The check reports of other build arithmetics beside the first x86-64 one:
    ``NAME/VARIANT/check-*.json`` under its folder, NAME an arithmetic of spec.arithmetic.KNOWN."""
    from ..spec.arithmetic import KNOWN

    first = next(iter(check_reports), None)
    if first is None:
        return []
    root = Path(first).parent
    return [f for name in KNOWN if name != "x86-64" for f in sorted((root / name).glob("*/check-*.json"))]


def flavoured_section(flavoured: list, checks: list) -> list[str]:
    """The bounded checks in other build arithmetics (``check --target NAME``): per arithmetic
    and variant, each size's verdict of each property, x86-64's beside it where it differs (NavFn
    as shipped), and the smallest counterexample of each property refuted there."""
    from ..check.runner import CHECKABLE
    from .check import verdict_text

    if not flavoured:
        return []
    x86, _, _ = _merge_checks(checks)
    groups: dict = {}
    for label, doc in flavoured:
        planner = doc.get("planner") or {}
        key = (planner.get("arithmetic", "?"), doc.get("variant", "original"))
        groups.setdefault(key, []).append((label, doc))
    out = ["## Whole-planner properties in other build arithmetics (`navfn-smt check --target NAME`)", "",
           "The bounded checks again, computing as a build for NAME does (docs/toolchains.md): the concolic "
           "exploration's concrete side, its intervals and its terms in that arithmetic, every counterexample "
           "replayed on the spec in it, every certificate replayable (`check --replay`). Where a verdict differs "
           "from x86-64's at the same size, x86-64's is given after it. A dash: not checked at that size (a "
           "`--max-size` run leaves a property at its smallest counterexample).", ""]
    for (arith, variant), docs in sorted(groups.items()):
        rows, _, _ = _merge_checks(docs)
        sizes = sorted({s for by_size in rows.values() for s in by_size}, key=lambda s: ((s[0] - 2) * (s[1] - 2), s))
        names = [n for n in CHECKABLE if n in rows]
        out += [f"### {arith}, {variant}", "", "Reports read: " + ", ".join(
            f"[{label}]({label})" for label, _ in docs) + ".", "",
                "| size | interior cells | " + " | ".join(f"`{n}`" for n in names) + " |",
                "|---|---|" + "---|" * len(names)]
        for s in sizes:
            cells = []
            for n in names:
                r = rows[n].get(s)
                if r is None:
                    cells.append("-")
                    continue
                text = verdict_text(r[0]["status"], r[0].get("method", "exploration"))
                other = x86.get(n, {}).get(s) if variant == "original" else None
                if other is not None and other[0]["status"] != r[0]["status"]:
                    text += f" (x86-64: {other[0]['status']})"
                cells.append(text)
            out.append(f"| {_size(s)} | {(s[0] - 2) * (s[1] - 2)} | " + " | ".join(cells) + " |")
        out.append("")
        for n in names:
            refuted = [s for s in sizes if s in rows[n] and rows[n][s][0]["status"] == "refuted"]
            if refuted:
                cx = rows[n][refuted[0]][0].get("counterexample") or {}
                out += [f"*`{n}`, smallest counterexample* ({_size(refuted[0])}, replayed on the spec in {arith}'s "
                        f"arithmetic): {_cx_text(cx)}.", ""]
    return out


# --------------------------------------------------------------------------- the page
def judged(outcomes: list, split_doc: Optional[dict], known: dict) -> list:
    """The report's outcomes judged against what is known now, the fp32 verdict of an
    obligation its split decides joining the whole query's (from the split report): each
    outcome's standing is the one status the page shows."""
    from ..smt.knowledge import NOTHING

    decided = {sp["obligation"]: sp for sp in (split_doc or {}).get("splits", [])}
    out = []
    for o in outcomes:
        sp = decided.get(o.name) if o.semantics == "fp32" else None
        if sp is None:
            out.append(o.judge(known.get((o.name, o.semantics), NOTHING)))
            continue
        o.judge(known.get((o.name, o.semantics), NOTHING), sp["status"])
        o.detail = (f"split: {sp['status']} ({len(sp['parts'])} parts, cover {sp['cover']['status']}, "
                    f"{_fmt_seconds(sp['seconds'])}); whole query: {o.status} in {o.seconds:.2f} s ({o.solver})"
                    + (f"; {o.detail}" if o.detail else ""))
        out.append(o)
    return out


def split_section(split_doc: Optional[dict], label: str) -> list[str]:
    """The splits: verdict, parts, slowest part, cover and time of each (from ``navfn-smt split --report``)."""
    if not split_doc:
        return []
    out = ["## Splits", "",
           f"Obligations no solver decides whole, decided part by part ([{label}]({label}), a `navfn-smt split` "
           f"run on {split_doc.get('engine', '?')}): the parts cover the input space (the cover is itself a "
           "solver query) and each part is decided bit-precisely, in the standard rounding-error model (proofs "
           "only) or by enumerating every input.", "",
           "| obligation | verdict | known before | parts | proved / refuted / unknown | slowest part | cover | wall time |",
           "|---|---|---|---|---|---|---|---|"]
    for sp in split_doc.get("splits", []):
        c = sp.get("counts", {})
        slow = sp.get("slowest_part") or {}
        out.append(f"| `{sp['obligation']}` | {sp['status']} | {sp.get('known', sp.get('expected', '?'))} | {len(sp['parts'])} | "
                   f"{c.get('proved', 0)} / {c.get('refuted', 0)} / {c.get('unknown', 0)} | "
                   f"{_fmt_seconds(slow.get('seconds', 0))} ({slow.get('solver', '-')}) | "
                   f"{sp['cover']['status']} | {_fmt_seconds(sp['seconds'])} |")
    out.append("")
    for sp in split_doc.get("splits", []):
        if sp.get("note"):
            out.append(f"- `{sp['obligation']}`: {sp['note']}.")
        for p in sp.get("undecided", [])[:10]:
            box = ", ".join(f"{iv['var']} in [{iv['lo']!r}, {iv['hi']!r}]" for iv in p["box"])
            out.append(f"  - undecided part: {box} ({p['detail']})")
    out.append("")
    return out


def render(prove_doc: dict, prove_label: str, checks: list, images: Optional[Path] = None, *,
           declared: list, known: dict, split: Optional[tuple] = None, flavoured: tuple = ()) -> str:
    """The page from a prove report (``prove_label`` names it), the ``(label, doc)`` check
    reports, and the directory where check counterexample pictures are looked up;
    ``declared``: the obligations to list, ``known``: what is known of them
    (:func:`navfn_smt.smt.split.known_of_files`); ``split``: the ``(label, doc)`` of a split
    report, whose verdicts replace the whole ones; ``flavoured``: the ``(label, doc)`` check
    reports of other build arithmetics (:func:`flavoured_section`).  The caller gathers all of it
    (:func:`navfn_smt.commands.common.page_sources`): the page only renders."""
    split_label, split_doc = split or (None, None)
    outcomes = judged(outcomes_of(prove_doc), split_doc, known)
    sems = list(prove_doc.get("semantics") or predicates.run_semantics(outcomes)) or ["real", "fp32"]
    by_name: dict = {}
    for o in outcomes:
        by_name.setdefault(o.name, {})[o.semantics] = o
    order = [p.name for p in predicates.registry()]
    props: dict = {}
    for ob in sorted(declared, key=lambda ob: order.index(ob.predicate) if ob.predicate in order else len(order)):
        props.setdefault(ob.predicate, []).append(ob)
    if declared:  # a predicate whose chain is another's obligations has none of its own: its section too
        props = {name: props.get(name, []) for name in [*order, *(n for n in props if n not in order)]}
    stale = sorted(set(by_name) - {ob.name for ob in declared})
    out = ["# NavFn invariants", "",
           "<!-- generated by `navfn-smt docs` from the proof obligations (src/navfn_smt/proofs/), the paper's "
           "predicates (proofs/__init__.py) and the reports under docs/reports/; do not edit by hand: "
           "`navfn-smt docs --check` fails when this page differs -->", "",
           INTRO, ""]
    prove_link = f"[{prove_label}]({prove_label})" if prove_label.endswith(".json") else prove_label
    out += [f"Proofs: {prove_link}, a `navfn-smt prove` run of {prove_doc.get('when', '?')}; "
           f"timeout {prove_doc.get('timeout', '?')} s per query; solvers: "
           f"{', '.join(prove_doc.get('solvers', [])) or '?'}; semantics: {', '.join(sems)}.", ""]
    if prove_doc.get("arithmetics"):
        out += ["`fp32` computes as the golden files' x86-64 build does (nothing fused, `(int)` out of range gives "
                "INT_MIN); `fp32@NAME` as a build for NAME does, its multiply-adds fused and its conversions "
                "(docs/toolchains.md); the reals have no build arithmetic. The runs in them: "
                + "; ".join(f"[{label}]({label}) of {when}" for label, when in prove_doc["arithmetics"])
                + ". A split and a chain of finer links decide `fp32` only (docs/toolchains.md says what "
                "is open in the others).", ""]
    if stale:
        out += ["Verdicts of obligations no longer declared (the report is older than the proofs): "
                + ", ".join(f"`{n}`" for n in stale) + ".", ""]
    out += predicates.markdown_summary(outcomes, known)
    out += ["## Obligations", "", "| property | obligation | " + " | ".join(sems) + " |",
            "|---" * (len(sems) + 2) + "|"]
    for prop, obs in props.items():
        for ob in obs:
            st = []
            for s in sems:
                r = by_name.get(ob.name, {}).get(s)
                st.append(_not_run(known, ob.name, s) if r is None else predicates.standing_text(r))
            out.append(f"| {prop} | `{ob.name}` | " + " | ".join(st) + " |")
    out.append("")
    for prop, obs in props.items():
        out += [f"## {prop}", "", *predicates.markdown_chain(prop, outcomes, known)]
        for ob in obs:
            out += _obligation_lines(ob, by_name.get(ob.name, {}), sems, known)
    out += split_section(split_doc, split_label)
    out += check_section(checks, images, outcome_verdicts(outcomes, known))
    out += flavoured_section(list(flavoured), checks)
    while out and out[-1] == "":
        out.pop()
    return "\n".join(out) + "\n"


def images_dir(check_paths) -> Optional[Path]:
    """Where check counterexample pictures are looked up: ``images/`` beside the first
    check report's directory (``docs/images`` for ``docs/reports``)."""
    first = next(iter(check_paths), None)
    return None if first is None else Path(first).resolve().parent.parent / "images"


def first_difference(committed: str, generated: str) -> Optional[tuple[int, str, str]]:
    """The first line (1-based) where two pages differ, with both lines (``<end of file>``
    past the end of one of them); None when they are equal."""
    a, b = committed.splitlines(), generated.splitlines()
    for i in range(max(len(a), len(b))):
        x = a[i] if i < len(a) else "<end of file>"
        y = b[i] if i < len(b) else "<end of file>"
        if x != y:
            return i + 1, x, y
    if committed != generated:  # only the final newline differs
        return max(len(a), 1), "(final newline)", "(final newline)"
    return None
