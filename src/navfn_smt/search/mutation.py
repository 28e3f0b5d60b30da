"""Mutation check: do the proofs and tests notice a seeded bug?

Each mutant is one textual change to the kernels or to a numeric domain, of the kind a
specification writer could make (drop the obstacle test, flip a comparison, forget the
pending flag, compute in double where C++ narrows, ...).  The change is made in the one
source of the arithmetic, so a kernel mutant reaches the reference spec, the compiled
backend and the SMT encodings alike.  A mutant runs in a subprocess on a copy of the
package with the change applied, against these detectors:

* ``prove``: the proof obligations (a verdict that contradicts what is known catches it);
* ``equality``: the symbolic domains compared with the concrete spec on kernel inputs;
* ``difftest-reference``, ``difftest-jit``: each backend against the C++ golden outputs
  of the example suite.

A mutant meets only the detectors that can catch it: the obligations and kernel
comparisons that execute the mutated function (found by tracing them once, unmutated),
and the difftests when planning calls it (the kernels the planner's loops name, and
what those call).  Within ``prove``, the first changed verdict ends the detector.
The score is given per backend: caught by ``prove``, ``equality`` or that backend's
difftest.
"""

from __future__ import annotations

import ast
import json
import os
import shutil
import subprocess
import sys
import tempfile
import time
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass, field
from pathlib import Path
from typing import Callable, Optional

from ..backends import BACKENDS as ALL_BACKENDS

PACKAGE = Path(__file__).resolve().parents[1]
KERNELS = "spec/kernels.py"
DOMAINS = "smt/domains.py"


@dataclass(frozen=True)
class Mutant:
    name: str
    file: str  # relative to the package
    old: str
    new: str
    what: str


MUTANTS = (
    Mutant("drop_obstacle_test", KERNELS, "changed = D.and_(is_passable(D, cost), D.lt(cand, old))",
           "changed = D.lt(cand, old)", "updateCell no longer skips obstacles"),
    Mutant("update_when_higher", KERNELS, "changed = D.and_(is_passable(D, cost), D.lt(cand, old))",
           "changed = D.and_(is_passable(D, cost), D.gt(cand, old))", "flipped comparison: keep the higher potential"),
    Mutant("push_ignores_pending", KERNELS, "D.and_(D.and_(D.ge(n, 0), D.lt(n, ns)), D.not_(pending)),",
           "D.and_(D.ge(n, 0), D.lt(n, ns)),", "push before checking the pending flag"),
    Mutant("push_admits_obstacles", KERNELS, "D.and_(D.lt(cost, COST_OBS), D.lt(fill, capacity)),",
           "D.lt(fill, capacity),", "push without the obstacle test"),
    Mutant("pot_in_double", KERNELS, 'return D.ite(D.ge(dc, hf), D.add(ta, hf), add_mul(D, "planar", ta, hf, v))',
           "return D.ite(D.ge(dc, hf), D.add(ta, hf), "
           "D.narrow(D.add64(D.widen(ta), D.mul64(D.widen(hf), quad))))",
           "compute the interpolated potential in double where C++ narrows to float"),
    Mutant("swap_flipped", KERNELS, "swap = D.lt(dc0, zero)", "swap = D.gt(dc0, zero)",
           "flipped comparison: take the higher pair in the planar wave"),
    Mutant("no_int_truncation", KERNELS, "better = D.lt(p, D.int_to_f32(minp))", "better = D.lt(p, centre)",
           "grid fallback compares floats, not the truncated int minp"),
    Mutant("no_offset_normalisation", KERNELS, "right = D.gt(D.widen(ndx), one)",
           "right = D.gt(D.widen(ndx), D.f64const(2.0))", "offset normalisation only beyond 2"),
    Mutant("gradient_not_normalised", KERNELS, "inv = D.narrow(D.div64(D.f64const(1.0), D.widen(norm)))",
           "inv = D.narrow(D.div64(D.f64const(2.0), D.widen(norm)))", "gradient scaled to length 2"),
    Mutant("near_goal_inclusive", KERNELS, "return D.lt(pot, D.f32const(COST_NEUTRAL))",
           "return D.le(pot, D.f32const(COST_NEUTRAL))", "near-goal test with <= COST_NEUTRAL"),
    Mutant("push_threshold_inclusive", KERNELS, "return D.gt(neighbour_pot, D.add(key, weight))",
           "return D.ge(neighbour_pot, D.add(key, weight))", "push also when equal"),
    Mutant("obstacle_gradient_sign", KERNELS, "dx_obs = D.ite(reached_l, mobs, D.ite(reached_r, obs, zero))",
           "dx_obs = D.ite(reached_l, obs, D.ite(reached_r, mobs, zero))",
           "gradCell in an obstacle points the wrong way"),
    Mutant("push_forgets_pending", KERNELS, "return admitted, dropped, D.or_(pending, admitted)",
           "return admitted, dropped, pending", "a push enqueues the cell without setting its pending flag"),
    Mutant("swap_drops_overflow", KERNELS, "return D.ite(drained, over, nxt), D.ite(drained, 0, over)",
           "return nxt, D.ite(drained, 0, over)",
           "the end-of-cycle swap empties the overflow buffer instead of making it current"),
    Mutant("write_before_the_test", KERNELS, "return D.ite(changed, cand, old), changed", "return cand, changed",
           "updateCell writes the candidate potential before its `pot < potarr[n]` test, whatever the test says"),
    Mutant("narrow_toward_zero", DOMAINS, "return z3.fpFPToFP(RNE, a, F32)", "return z3.fpFPToFP(z3.RTZ(), a, F32)",
           "fp32 domain narrows double to float toward zero"),
    Mutant("roundf_half_even", DOMAINS, "return z3.fpRoundToIntegral(z3.RNA(), a)",
           "return z3.fpRoundToIntegral(z3.RNE(), a)", "fp32 domain rounds halves to even"),
    Mutant("no_int_min", DOMAINS, "return z3.If(in_range, truncated, z3.BitVecVal(INT_MIN, 32))",
           "return truncated", "fp32 domain forgets cvttss2si's INT_MIN"),
)


# every backend, the reference first; each has a difftest detector of its own
BACKENDS = ("reference", *(b for b in ALL_BACKENDS if b != "reference"))
DETECTORS = ("equality", *(f"difftest-{b}" for b in BACKENDS), "prove")
BACKEND_DETECTORS = {b: ("prove", "equality", f"difftest-{b}") for b in BACKENDS}
PLANNING_SOURCES = ("spec/propagation.py", "spec/extraction.py", "backends/jit.py")


@dataclass
class MutantResult:
    name: str
    what: str
    caught_by: list = field(default_factory=list)
    skipped: dict = field(default_factory=dict)  # detector -> why it cannot catch this mutant
    details: dict = field(default_factory=dict)
    errors: dict = field(default_factory=dict)  # detector -> error (a broken detector is no catch)
    seconds: float = 0.0

    @property
    def caught(self) -> bool:
        return bool(self.caught_by)

    def caught_with(self, backend: str) -> bool:
        """Caught by a check that speaks for ``backend`` (the proofs, the equality test, its difftest)."""
        return any(d in self.caught_by for d in BACKEND_DETECTORS[backend])


# --------------------------------------------------------------------------------------
# Which detectors can catch a mutant: the functions each one executes
# --------------------------------------------------------------------------------------
def mutated_function(m: Mutant) -> Optional[str]:
    """``file:qualname`` of the function whose body the mutant changes (None: module level)."""
    text = (PACKAGE / m.file).read_text()
    line = text[: text.index(m.old)].count("\n") + 1
    for node in ast.parse(text).body:
        if isinstance(node, ast.ClassDef):
            for f in node.body:
                if isinstance(f, ast.FunctionDef) and f.lineno <= line <= f.end_lineno:
                    return f"{m.file}:{node.name}.{f.name}"
        elif isinstance(node, ast.FunctionDef) and node.lineno <= line <= node.end_lineno:
            return f"{m.file}:{node.name}"
    return None


def _traced(fn: Callable) -> set:
    """The ``file:qualname`` of every kernel or domain function that runs during ``fn()``."""
    watched = {str(PACKAGE / f): f for f in (KERNELS, DOMAINS)}
    seen: set = set()

    def prof(frame, event, arg):
        if event == "call":
            rel = watched.get(frame.f_code.co_filename)
            if rel:
                seen.add(f"{rel}:{frame.f_code.co_qualname}")

    old = sys.getprofile()
    sys.setprofile(prof)
    try:
        fn()
    finally:
        sys.setprofile(old)
    return seen


def planning_kernels() -> set:
    """Kernels the planner's loops name (``K.name``), closed over the kernels' own calls."""
    kernel_tree = ast.parse((PACKAGE / KERNELS).read_text())
    calls = {f.name: {n.id for n in ast.walk(f) if isinstance(n, ast.Name)}
             for f in kernel_tree.body if isinstance(f, ast.FunctionDef)}
    todo = set()
    for src in PLANNING_SOURCES:
        tree = ast.parse((PACKAGE / src).read_text())
        todo |= {n.attr for n in ast.walk(tree)
                 if isinstance(n, ast.Attribute) and isinstance(n.value, ast.Name) and n.value.id == "K"}
    found: set = set()
    while todo:
        k = todo.pop()
        if k in calls and k not in found:
            found.add(k)
            todo |= calls[k] & set(calls)
    return {f"{KERNELS}:{k}" for k in found}


@dataclass
class Relevance:
    """What each detector executes, traced once on the unmutated package."""

    obligations: dict  # (file, name, semantics) -> functions run while building its query
    kernels: dict  # equality kernel -> functions run while comparing it
    planning: set

    @classmethod
    def trace(cls, proof_files) -> "Relevance":
        from ..smt.evaluate import KERNELS as EQ_KERNELS
        from ..smt.evaluate import compare_kernel
        from ..smt.checking import query
        from ..smt.obligation import load_obligations

        obs = {}
        for ob in load_obligations(proof_files):
            for sem in ob.expect:
                obs[(str(Path(ob.source).resolve()), ob.name, sem)] = _traced(lambda: query(ob, sem))
        kernels = {k: _traced(lambda: compare_kernel(k, 0, 2)) for k in EQ_KERNELS}
        return cls(obs, kernels, planning_kernels())

    def plan(self, m: Mutant) -> tuple[dict, dict]:
        """``(work, skipped)``: what to run for ``m`` and why the rest cannot catch it."""
        fn = mutated_function(m)
        runs = (lambda calls: True) if fn is None else (lambda calls: fn in calls)
        work, skipped = {}, {}
        obs = [list(k) for k, calls in self.obligations.items() if runs(calls)]
        obs.sort(key=lambda k: k[2] != "real")  # real semantics first: they decide fastest
        kernels = [k for k, calls in self.kernels.items() if runs(calls)]
        planning = runs(self.planning)
        for det, todo in (("prove", obs), ("equality", kernels)):
            if todo:
                work[det] = todo
            else:
                skipped[det] = f"no {'obligation' if det == 'prove' else 'kernel comparison'} runs {fn}"
        for backend in BACKENDS:
            if planning:
                work[f"difftest-{backend}"] = backend
            else:
                skipped[f"difftest-{backend}"] = f"planning does not run {fn}"
        return work, skipped


# --------------------------------------------------------------------------------------
# Running a mutant: a subprocess on a mutated copy of the package
# --------------------------------------------------------------------------------------
def _apply(root: Path, m: Mutant) -> None:
    p = root / "navfn_smt" / m.file
    text = p.read_text()
    if text.count(m.old) != 1:
        raise RuntimeError(f"mutant {m.name}: the text to change occurs {text.count(m.old)} times in {m.file}")
    p.write_text(text.replace(m.old, m.new))


def _in_copy(path: Path, root: Path) -> Path:
    """A proof file shipped in the package, taken from the mutant's copy of the package (so
    the mutant's proofs, bound cache included, are the copy's); any other file as it is."""
    try:
        return root / "navfn_smt" / path.resolve().relative_to(PACKAGE)
    except ValueError:
        return path


def run_mutant(m: Mutant, rel: Relevance, suite, timeout: float = 30.0, solvers=("bitwuzla", "z3", "cvc5"),
               progress: Optional[Callable[[str, str, dict], None]] = None) -> MutantResult:
    """Seed ``m`` in a copy of the package and run the detectors that can catch it.

    ``progress(mutant, detector, line)`` is called as each detector finishes."""
    t0 = time.perf_counter()
    res = MutantResult(m.name, m.what)
    work, res.skipped = rel.plan(m)
    with tempfile.TemporaryDirectory(prefix=f"mutant-{m.name}-") as tmp:
        root = Path(tmp)
        shutil.copytree(PACKAGE, root / "navfn_smt", ignore=shutil.ignore_patterns("__pycache__", "*.nbi", "*.nbc"))
        _apply(root, m)
        if "prove" in work:  # the proofs shipped in the package are taken from the mutant's copy
            work["prove"] = [[str(_in_copy(Path(f), root)), name, sem] for f, name, sem in work["prove"]]
        plan = root / "plan.json"
        plan.write_text(json.dumps({"work": work, "suite": str(Path(suite).resolve()), "timeout": timeout, "solvers": list(solvers)}))
        env = {**os.environ, "PYTHONPATH": str(root), "NUMBA_CACHE_DIR": str(root / "numba-cache")}
        proc = subprocess.Popen([sys.executable, "-m", "navfn_smt.search.mutation", str(plan)], env=env, cwd=tmp,
                                stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        for line in proc.stdout:
            if not line.startswith("{"):
                continue
            d = json.loads(line)
            if d.get("caught"):
                res.caught_by.append(d["detector"])
            if d.get("error"):
                res.errors[d["detector"]] = d["error"]
            elif d.get("detail"):
                res.details[d["detector"]] = d["detail"]
            if progress:
                progress(m.name, d["detector"], d)
        err = proc.stderr.read()
        if proc.wait() != 0:
            res.errors["worker"] = " | ".join(err.strip().splitlines()[-3:])
    res.caught_by.sort(key=DETECTORS.index)
    res.seconds = round(time.perf_counter() - t0, 1)
    return res


def run_mutants(mutants, proof_files, suite, timeout: float = 30.0, jobs: int = 2,
                progress: Optional[Callable[[str, str, dict], None]] = None,
                on_done: Optional[Callable[[MutantResult], None]] = None) -> list[MutantResult]:
    """Every mutant, ``jobs`` at a time; results in the order given."""
    rel = Relevance.trace(proof_files)

    def one(m: Mutant) -> MutantResult:
        r = run_mutant(m, rel, suite, timeout, progress=progress)
        if on_done:
            on_done(r)
        return r

    with ThreadPoolExecutor(max_workers=jobs) as ex:
        return list(ex.map(one, mutants))


# --------------------------------------------------------------------------------------
# Inside the mutated copy: the detectors
# --------------------------------------------------------------------------------------
def _emit(detector: str, caught: bool, detail, t0: float, error: Optional[str] = None) -> None:
    print(json.dumps({"detector": detector, "caught": caught, "detail": detail, "error": error,
                      "seconds": round(time.perf_counter() - t0, 1)}, default=str), flush=True)


def _detect_equality(kernels) -> tuple[bool, dict]:
    from navfn_smt.smt.evaluate import compare_kernel

    bad = {k: len(compare_kernel(k, 77, 150)) for k in kernels}
    bad = {k: v for k, v in bad.items() if v}
    return bool(bad), bad


def _detect_difftest(suite: str, backend: str) -> tuple[bool, str]:
    """The suite's cases, smallest maps first; the first disagreeing case catches the mutant."""
    from navfn_smt.difftest.runner import map_cells, plan_tasks, run_task
    from navfn_smt.maps.suite import MODES

    tasks = sorted(plan_tasks(Path(suite), MODES, backend), key=lambda t: map_cells(t.map_dir))
    runs = 0
    for t in tasks:
        o = run_task(t)
        runs += o.cases
        if o.disagreements:
            d = o.disagreements[0]
            return True, f"{d.map} {d.mode} case {d.case_index}: {d.field} differs (after {runs} case runs)"
    return False, f"all {runs} case runs agree"


def _detect_prove(obligations, timeout: float, solvers) -> tuple[bool, list]:
    """Check the obligations in order; the first verdict that contradicts what is known
    catches the mutant.  A timeout does not catch it (it says nothing about the mutant), nor
    does a decision where nothing was known, but a solver model the concrete spec refuses
    does (the domain no longer matches the spec)."""
    from navfn_smt.proofs import PREDICATES
    from navfn_smt.smt import knowledge
    from navfn_smt.smt.checking import check
    from navfn_smt.smt.split import known_of_files
    from navfn_smt.smt.obligation import load_obligations
    from navfn_smt.smt.runner import solve_query

    loaded, known = {}, {}
    notes = []
    for path, name, sem in obligations:
        if path not in loaded:
            loaded[path] = {o.name: o for o in load_obligations([Path(path)])}
            known.update(known_of_files([Path(path)], list(loaded[path].values()), PREDICATES))
        o = check(loaded[path][name], sem, timeout, solve_query(tuple(solvers)), bounds=False, known=known[(name, sem)])
        # a model the concrete spec refuses, or a model over arrays of an obligation known proved (the
        # mutant's spec breaks what the proof holds of the spec's own run: no concrete array replays it)
        over_arrays = o.status == "unknown" and "over arrays" in (o.detail or "") and o.known == "proved"
        if o.fails or over_arrays or (o.status == "unknown" and "not confirmed" in (o.detail or "")):
            return True, notes + [f"{name}[{sem}]: {o.status} (known {o.known})"]
        if o.judgement == knowledge.UNDECIDED and o.known != "unknown":
            notes.append(f"{name}[{sem}]: unknown (timeout, not counted)")
    return False, notes


def worker_main(plan_file: str) -> int:
    plan = json.loads(Path(plan_file).read_text())
    work = plan["work"]
    for det in DETECTORS:
        if det not in work:
            continue
        t0 = time.perf_counter()
        error = None
        try:
            if det == "equality":
                caught, detail = _detect_equality(work[det])
            elif det.startswith("difftest-"):
                caught, detail = _detect_difftest(plan["suite"], work[det])
            else:
                caught, detail = _detect_prove(work[det], plan["timeout"], plan["solvers"])
        except Exception as e:  # a detector that breaks is reported, and is not a catch
            caught, detail, error = False, None, f"{type(e).__name__}: {e}"[:300]
        _emit(det, caught, detail, t0, error)
    return 0


if __name__ == "__main__":
    sys.exit(worker_main(sys.argv[1]))
