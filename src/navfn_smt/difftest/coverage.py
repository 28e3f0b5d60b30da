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


from ..maps.suite import discover, load_map
from ..spec import numeric

SPEC_DIR = Path(__file__).resolve().parent.parent / "spec"
# the modules a planning call executes (costs.py's setCostmap is not part of a suite run:
# suite maps hold NavFn-internal costs already)
SPEC_FILES = ("kernels.py", "numeric.py", "propagation.py", "extraction.py", "planner.py")

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
    "if m < nx or m > ns - nx:":
        "gradCell runs only on the interpolation square of a cell whose eight neighbours are all "
        "reached, so none of the four cells is in the first or last row",
    "if stc < nx or stc > ns - nx:":
        "from an interior start, extraction moves only to reached cells (grid fallback) or by at most "
        "one cell from a cell whose eight neighbours are reached; the border rows are never reached",
    # propagation.py
    "if not K.is_passable(D, cost):":
        "pushes admit only passable cells, so an updated cell is never an obstacle (obstacle-free queues)",
    "if len(buf) < PRIORITYBUFSIZE:":
        "a full buffer needs a wavefront of more than 10,000 cells: reached by navfn-suite-large "
        "and tests/data/overflow-subset, not by the paper's maps",
    # kernels.py (ite sites, decision coverage)
    "dx = D.ite(unreached, dx_obs, dx2)":
        "gradCell is applied to the interpolation square, whose cells are all reached (see above)",
    "dy = D.ite(unreached, dy_obs, dy2)":
        "gradCell is applied to the interpolation square, whose cells are all reached (see above)",
    "idx = D.ite(D.lt(ns - 1, idx), ns - 1, idx)":
        "the probed cell is within one cell of an interior stc, never past the last cell",
    "return D.ite(D.lt(idx, 0), 0, idx)":
        "the probed cell is within one cell of an interior stc, never before the first cell",
    "if stc - nx - 1 < 0 or stc + nx + 1 >= ns:":
        "undefined behaviour of the C++ at three border cells; suite starts are interior cells",
    # planner.py input checks (the command line and tests exercise them)
    "if arr.ndim != 2:": "input validation; exercised by tests/test_cli.py, not by suite runs",
    "if nx < 3 or ny < 3:": "input validation; exercised by tests/test_cli.py, not by suite runs",
    "if arr.dtype != np.uint8:": "suite maps are read as uint8",
    "if not np.issubdtype(arr.dtype, np.integer) or arr.min() < 0 or arr.max() > 255:":
        "suite maps are read as uint8",
    "if not (0 <= x < nx and 0 <= y < ny):": "suite cases are on their maps (checked when test.txt is read)",
}


class RecordingDomain(numeric.ConcreteDomain):
    """The concrete domain, noting the outcome of every ``ite`` by call site."""

    def __init__(self):
        self.seen: dict = defaultdict(set)

    def ite(self, c, a, b):
        f = sys._getframe(1)
        self.seen[(f.f_code.co_filename, f.f_lineno)].add(bool(c))
        return a if c else b


def measure(suite, modes=("astar", "dijkstra"), max_cases: Optional[int] = None, progress=None) -> dict:
    """Run the reference spec on the suite under coverage.py and the recording domain."""
    import coverage

    from ..spec import extraction, kernels, propagation
    from ..spec.planner import plan

    rec = RecordingDomain()
    saved = (propagation.D, extraction.D)
    propagation.D = extraction.D = rec
    cov = coverage.Coverage(branch=True, data_file=None, include=[str(SPEC_DIR / f) for f in SPEC_FILES])
    cases_run = 0
    try:
        cov.start()
        for d in discover(suite):
            smap = load_map(d, Path(suite))
            cases = smap.cases if max_cases is None else smap.cases[:max_cases]
            for mode in modes:
                for sx, sy, gx, gy in cases.tolist():
                    try:
                        plan(smap.costs, (sx, sy), (gx, gy), astar=mode == "astar", trace_hook=_no_hook)
                    except extraction.UndefinedBehaviour:
                        pass
                    cases_run += 1
                if progress:
                    progress(len(cases))
    finally:
        cov.stop()
        propagation.D, extraction.D = saved
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


def _summarize(data: dict, rec: RecordingDomain, kernels_mod, cases_run: int) -> dict:
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
    nb = sum(f["branches"] for f in files)
    cb = sum(f["branches_covered"] for f in files)
    nl = sum(f["lines"] for f in files)
    cl = sum(f["lines_covered"] for f in files)
    return {
        "cases_run": cases_run,
        "files": files,
        "lines": nl, "lines_covered": cl,
        "branches": nb, "branches_covered": cb,
        "branch_percent": round(100.0 * cb / nb, 2) if nb else 100.0,
        "ite_outcomes": ite_total, "ite_outcomes_covered": ite_covered,
        "uncovered": uncovered,
    }


def percent(a: int, b: int) -> str:
    return f"{100.0 * a / b:.1f}%" if b else "-"


