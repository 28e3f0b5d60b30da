"""Mutation check: do the proofs and tests notice a seeded bug?

Each mutant is one textual change to the kernels or to a numeric domain, of the kind a
specification writer could make (drop the obstacle test, flip a comparison, forget the
pending flag, compute in double where C++ narrows, ...).  A mutant runs in a subprocess
on a copy of the package with the change applied, against three detectors:

* ``prove``: the proof obligations (a verdict that changes catches it);
* ``equality``: the symbolic domains compared with the concrete spec on kernel inputs;
* ``difftest``: the reference spec against C++ golden outputs on a few example maps.

The score is the share of mutants caught by at least one detector.
"""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass, field
from pathlib import Path

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
    Mutant("pot_in_double", KERNELS, "return D.ite(D.ge(dc, hf), D.add(ta, hf), D.add(ta, D.mul(hf, v)))",
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
    Mutant("narrow_toward_zero", DOMAINS, "return z3.fpFPToFP(RNE, a, F32)", "return z3.fpFPToFP(z3.RTZ(), a, F32)",
           "fp32 domain narrows double to float toward zero"),
    Mutant("roundf_half_even", DOMAINS, "return z3.fpRoundToIntegral(z3.RNA(), a)",
           "return z3.fpRoundToIntegral(z3.RNE(), a)", "fp32 domain rounds halves to even"),
    Mutant("no_int_min", DOMAINS, "return z3.If(in_range, z3.fpToSBV(z3.RTZ(), a, BV32), z3.BitVecVal(INT_MIN, 32))",
           "return z3.fpToSBV(z3.RTZ(), a, BV32)", "fp32 domain forgets cvttss2si's INT_MIN"),
)

EQUALITY_SCRIPT = """
import json
from navfn_smt.smt.evaluate import KERNELS, compare_kernel
bad = {k: len(compare_kernel(k, 77, 150)) for k in KERNELS}
print(json.dumps(bad))
"""


@dataclass
class MutantResult:
    name: str
    what: str
    caught_by: list = field(default_factory=list)
    details: dict = field(default_factory=dict)
    seconds: float = 0.0

    @property
    def caught(self) -> bool:
        return bool(self.caught_by)


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


def run_mutant(m: Mutant, proof_files, suite, timeout: float = 20.0, solvers=("bitwuzla", "z3", "cvc5")) -> MutantResult:
    t0 = time.perf_counter()
    res = MutantResult(m.name, m.what)
    with tempfile.TemporaryDirectory(prefix=f"mutant-{m.name}-") as tmp:
        root = Path(tmp)
        shutil.copytree(PACKAGE, root / "navfn_smt", ignore=shutil.ignore_patterns("__pycache__", "*.nbi", "*.nbc"))
        _apply(root, m)
        files = [_in_copy(Path(f), root) for f in proof_files]
        env = {**os.environ, "PYTHONPATH": str(root), "NUMBA_CACHE_DIR": str(root / "numba-cache")}
        py = [sys.executable]
        # 1. proofs
        report = root / "prove.json"
        cmd = py + ["-m", "navfn_smt", "prove", *map(str, files), "--timeout", str(timeout),
                    "--report", str(report), "--witness-dir", str(root / "witnesses"), "--no-bound-search", "--jobs", "2"]
        for s in solvers:
            cmd += ["--solver", s]
        p = subprocess.run(cmd, env=env, capture_output=True, text=True, cwd=tmp)
        if p.returncode == 1 and report.exists():
            doc = json.loads(report.read_text())
            # a verdict that changes to another definitive verdict catches the mutant, and so
            # does a solver model the concrete spec refuses (the domain no longer matches the
            # spec); a timeout does not: it says nothing about the mutant
            changed = [f"{o['name']}[{o['semantics']}]: {o['status']}" for o in doc["obligations"]
                       if o["status"] != o["expected"]
                       and (o["status"] != "unknown" or "not confirmed" in (o.get("detail") or ""))]
            timeouts = [f"{o['name']}[{o['semantics']}]" for o in doc["obligations"]
                        if o["status"] != o["expected"] and o["name"] + "[" + o["semantics"] + "]: unknown"
                        not in changed and o["status"] == "unknown"]
            if changed:
                res.caught_by.append("prove")
                res.details["prove"] = changed
            if timeouts:
                res.details["prove_timeouts"] = timeouts
        elif p.returncode not in (0, 1):
            res.details["prove_error"] = (p.stderr or p.stdout).strip().splitlines()[-1:]
        # 2. equality of the symbolic domains with the concrete spec
        p = subprocess.run(py + ["-c", EQUALITY_SCRIPT], env=env, capture_output=True, text=True, cwd=tmp)
        if p.returncode == 0:
            bad = json.loads(p.stdout.strip().splitlines()[-1])
            if any(bad.values()):
                res.caught_by.append("equality")
                res.details["equality"] = {k: v for k, v in bad.items() if v}
        else:
            res.details["equality_error"] = (p.stderr or "").strip().splitlines()[-1:]
        # 3. difftest of the reference spec against C++ golden outputs
        p = subprocess.run(py + ["-m", "navfn_smt", "difftest", str(suite), "--backend", "reference", "--quiet"],
                           env=env, capture_output=True, text=True, cwd=tmp)
        if p.returncode == 1:
            res.caught_by.append("difftest")
            res.details["difftest"] = p.stdout.strip().splitlines()[-1]
        elif p.returncode != 0:
            res.details["difftest_error"] = (p.stderr or p.stdout).strip().splitlines()[-1:]
    res.seconds = round(time.perf_counter() - t0, 1)
    return res
