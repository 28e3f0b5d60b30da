"""Coverage of the reference specification under a suite (the paper's Table 2, for our spec).

Two measures:

* line and branch coverage of the spec's Python modules (coverage.py), and
* decision coverage of the kernels: the kernels turn every C++ branch into
  ``D.ite(cond, a, b)`` so that one code serves concrete and symbolic domains, which
  hides those branches from a line tracer.  A recording domain notes, for every ``ite``
  call site, which outcomes the suite produced; a site is covered when both were seen.

Branches that no NavFn run can take get a reason in :data:`REASONS`, keyed by the
stripped source line of the branch's origin.
"""

from __future__ import annotations

import json
import sys
import tempfile
from collections import defaultdict
from pathlib import Path
from typing import Optional


from ..maps.suite import MODES, discover, load_map

SPEC_DIR = Path(__file__).resolve().parent.parent / "spec"
# the modules of NavFn's behaviour that a planning call executes (costs.py's setCostmap is
# not part of a suite run: suite maps hold NavFn-internal costs already) ...
SPEC_FILES = ("kernels.py", "propagation.py", "extraction.py", "planner.py")
# ... and the arithmetic library under them (C++ operators, conversions, libm), reported
# apart: its IEEE corner cases (overflow, NaN) are part of the domain, not of NavFn
LIBRARY_FILES = ("numeric.py",)

REASONS = {
    # numeric.py: IEEE corner cases planning never produces
    "except OverflowError:  # beyond float32 range: IEEE gives +-inf":
        "no float operation of a plan overflows float32: potentials stay below POT_HIGH plus a few costs",
    "if math.isnan(a) or math.isinf(a):": "roundf is applied to path offsets, always finite",
    "if m >= 2.0**23:  # every float32 of this magnitude is an integer": "path offsets lie in (-2, 2)",
    "if a != a:": "the int conversions take finite values (potentials, rounded offsets)",
    "if -2147483649.0 < a < 2147483648.0:":
        "out-of-range conversion needs a potential >= 2**31, far above what suite maps reach "
        "(the 1e10 case is a separate, covered outcome)",
    "if a != a or a == 0.0:": "0/0 needs dc == 0 and hf == 0 in the same update; dc/hf is only "
                              "divided (eagerly, by the ite form) with hf = 0 on cost-0 cells",
    # extraction.py
    "if corner == 0 or corner == 1 or corner == nx or corner == nx + 1:":
        "gradCell(ns - nx) is undefined behaviour of the C++; a planned potential never has the "
        "nine reached cells around (0, ny-2) or (nx-1, ny-3) that lead there",
    "if code == EXIT_GRADIENT_UNDEFINED:":
        "gradCell(ns - nx) is undefined behaviour of the C++ (see follow's corner test)",
    "if taken(D, zero_gradient(D, x, y)):":
        "an exactly zero gradient needs a plateau of equal potentials (cost-0 cells), which the "
        "paper's maps lack; reached by tests/data/unseen-suite (zero/*)",
    "if code != ITERATION_GOES_ON:  # OUT_OF_BOUNDS, or the ring of (0, 1), (nx-1, ny-2), (0, ny-1)":
        "OUT_OF_BOUNDS: from an interior start, extraction moves only to reached cells (grid fallback) or "
        "by at most one cell from a cell whose eight neighbours are reached; the border rows are never "
        "reached; the ring's read outside potarr is undefined behaviour of the C++ at three border cells",
    # propagation.py
    # kernels.py (ite sites, decision coverage)
    "dx1 = D.ite(reached_l, D.add(zero, D.sub(pl, cv)), zero)":
        "the left neighbours of the four interpolation cells lie in the ring of nine reached cells",
    "dy1 = D.ite(reached_u, D.add(zero, D.sub(pu, cv)), zero)":
        "the upper neighbours of the four interpolation cells lie in the ring of nine reached cells",
    "return D.ite(unreached, dx_obs, dx2), D.ite(unreached, dy_obs, dy2)":
        "gradCell is applied to the interpolation square, whose cells are all reached (see above)",
    "idx = D.ite(D.lt(ns - 1, idx), ns - 1, idx)":
        "the probed cell is within one cell of an interior stc, never past the last cell",
    "return D.ite(D.lt(idx, 0), 0, idx)":
        "the probed cell is within one cell of an interior stc, never before the first cell",
    "if code == EXIT_UNDEFINED:":
        "undefined behaviour of the C++ at three border cells; suite starts are interior cells",
}


def _recording_domain():
    """The concrete domain, noting the outcome of every ``ite`` by call site."""
    from ..spec import numeric

    class RecordingDomain(numeric.ConcreteDomain):
        def __init__(self):
            self.seen: dict = defaultdict(set)

        def ite(self, c, a, b):
            f = sys._getframe(1)
            self.seen[(f.f_code.co_filename, f.f_lineno)].add(bool(c))
            return a if c else b

    return RecordingDomain()


def measure(suites, modes=MODES, max_cases: Optional[int] = None, progress=None) -> dict:
    """Run the reference spec on the suites under coverage.py and the recording domain.

    The run happens in a fresh interpreter that starts measuring before the spec is
    imported, so definitions count as covered lines.  A* runs record the white-box trace
    through a hook; Dijkstra runs record nothing, so both sides of the instrumentation
    switches are exercised.
    """
    import multiprocessing as mp

    if isinstance(suites, (str, Path)):
        suites = [suites]
    suites = [str(s) for s in suites]
    for s in suites:
        discover(s)  # bad input fails here, with a clear message, before the child starts
    ctx = mp.get_context("spawn")
    queue = ctx.Queue()
    proc = ctx.Process(target=_child, args=(suites, tuple(modes), max_cases, queue))
    proc.start()
    result = None
    while result is None:
        kind, value = queue.get()
        if kind == "progress":
            if progress:
                progress(value)
        elif kind == "error":
            proc.join()
            raise RuntimeError(f"coverage run failed: {value}")
        else:
            result = value
    proc.join()
    return result


def _child(suites, modes, max_cases, queue) -> None:
    try:
        queue.put(("done", _measure_here(suites, modes, max_cases, lambda n: queue.put(("progress", n)))))
    except BaseException as e:  # report, do not hang the parent
        queue.put(("error", f"{type(e).__name__}: {e}"))


def _measure_here(suites, modes, max_cases, progress) -> dict:
    import coverage

    files = [str(SPEC_DIR / f) for f in SPEC_FILES + LIBRARY_FILES]
    cov = coverage.Coverage(branch=True, data_file=None, include=files)
    cases_run = 0
    cov.start()
    try:
        from ..spec import extraction, kernels, propagation
        from ..spec.planner import plan

        rec = _recording_domain()
        propagation.D = extraction.D = rec
        for suite in suites:
            for d in discover(suite):
                smap = load_map(d, Path(suite))
                cases = smap.cases if max_cases is None else smap.cases[:max_cases]
                for mode in modes:
                    astar = mode == "astar"
                    for sx, sy, gx, gy in cases.tolist():
                        try:
                            plan(smap.costs, (sx, sy), (gx, gy), astar=astar,
                                 trace_hook=_no_hook if astar else None, record_trace=astar)
                        except extraction.UndefinedBehaviour:
                            pass
                        cases_run += 1
                    progress(len(cases))
    finally:
        cov.stop()
    with tempfile.TemporaryDirectory() as tmp:
        out = Path(tmp) / "cov.json"
        cov.json_report(outfile=str(out))
        data = json.loads(out.read_text())
    return _summarize(data, rec, kernels, cases_run)


def _no_hook(cycle, cells) -> None:
    """A trace hook that does nothing (so the hook's code path is measured too)."""


def _line(path: str, no: int) -> str:
    try:
        return Path(path).read_text().splitlines()[no - 1].strip()
    except (OSError, IndexError):
        return ""


def _summarize(data: dict, rec, kernels_mod, cases_run: int) -> dict:
    files = []
    uncovered = []
    for path, f in sorted(data["files"].items()):
        s = f["summary"]
        files.append({"file": Path(path).name, "lines": s["num_statements"], "lines_covered": s["covered_lines"],
                      "branches": s["num_branches"], "branches_covered": s["covered_branches"]})
        for src, dst in f.get("missing_branches", []):
            text = _line(path, src)
            uncovered.append({"kind": "branch", "file": Path(path).name, "line": src,
                              "to": dst if dst > 0 else "exit", "source": text, "reason": REASONS.get(text)})
    # decision coverage of ite sites in the kernels (both outcomes seen?)
    import inspect

    kpath = inspect.getsourcefile(kernels_mod)
    src_lines = Path(kpath).read_text().splitlines()
    sites = [i + 1 for i, line in enumerate(src_lines) if "D.ite(" in line]
    ite_total = 0
    ite_covered = 0
    for no in sites:
        n_ite = src_lines[no - 1].count("D.ite(")
        outcomes = rec.seen.get((kpath, no), set())
        ite_total += 2 * n_ite
        ite_covered += min(len(outcomes), 2) * n_ite if outcomes else 0
        if len(outcomes) < 2:
            missing = sorted({True, False} - outcomes)
            text = src_lines[no - 1].strip()
            uncovered.append({"kind": "ite", "file": Path(kpath).name, "line": no,
                              "to": "/".join("true" if m else "false" for m in missing),
                              "source": text, "reason": REASONS.get(text)})
    spec = [f for f in files if f["file"] in SPEC_FILES]
    lib = [f for f in files if f["file"] in LIBRARY_FILES]

    def total(fs, key):
        return sum(f[key] for f in fs)

    nb, cb = total(spec, "branches"), total(spec, "branches_covered")
    return {
        "cases_run": cases_run,
        "files": files,
        "lines": total(spec, "lines"), "lines_covered": total(spec, "lines_covered"),
        "branches": nb, "branches_covered": cb,
        "branch_percent": round(100.0 * cb / nb, 2) if nb else 100.0,
        "library_branches": total(lib, "branches"), "library_branches_covered": total(lib, "branches_covered"),
        "ite_outcomes": ite_total, "ite_outcomes_covered": ite_covered,
        "uncovered": uncovered,
    }


def percent(a: int, b: int) -> str:
    return f"{100.0 * a / b:.1f}%" if b else "-"


