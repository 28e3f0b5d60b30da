"""Run proof obligations: every obligation of the given files in every requested semantics.

Each (obligation, semantics) pair is one job; ``jobs`` worker processes take them, each
loading the proof file itself (obligations hold functions, which do not travel between
processes).  Solving goes through :func:`solve_query`: the solver portfolio when it is
available, Z3 alone otherwise.
"""

from __future__ import annotations

from concurrent.futures import ProcessPoolExecutor, as_completed
from pathlib import Path
from typing import Callable, Optional

from ..errors import NavfnInputError
from . import codec
from .checking import Outcome, check, solve_z3
from .obligation import load_obligations

SEMANTICS = ("real", "fp32")


def solve_query(solvers: tuple):
    """A ``solve(assertions, variables, timeout)`` for :func:`check` over ``solvers``."""
    if tuple(solvers) == ("z3",):
        return solve_z3

    def solve(assertions, variables, timeout):
        from .portfolio import solve as portfolio_solve

        res = portfolio_solve(assertions, timeout=timeout, solvers=solvers)
        if res.status == "error":
            raise RuntimeError("solvers disagree: " + "; ".join(f"{a.solver}={a.status}" for a in res.answers))
        if res.status == "sat":
            win = next(a for a in res.answers if a.solver == res.solver)
            values = codec.replay_values(win.model or {}, variables)
            if values is None:  # the winner gave no usable model: ask z3 for one
                return solve_z3(assertions, variables, timeout)
            return "sat", values, res.solver, ""
        if res.status == "unsat":
            return "unsat", None, res.solver, ""
        return "unknown", None, ",".join(solvers), "; ".join(f"{a.solver}: {a.status}" for a in res.answers)

    return solve


def _job(path: str, name: str, semantics: str, timeout: float, solvers: tuple, bounds: bool = True) -> Outcome:
    ob = next(o for o in load_obligations([path]) if o.name == name)
    return check(ob, semantics, timeout, solve_query(solvers), bounds=bounds)


def run(paths, semantics=SEMANTICS, timeout: float = 30.0, jobs: int = 1, solvers=("z3",),
        progress: Optional[Callable[[Outcome], None]] = None, bounds: bool = True) -> list[Outcome]:
    if not (timeout > 0 and timeout < float("inf")):
        raise NavfnInputError(f"--timeout {timeout!r}: must be a positive number of seconds")
    obligations = load_obligations(paths)
    work = [(o.source, o.name, s) for o in obligations for s in semantics if s in o.expect]
    if not work:
        raise NavfnInputError("no obligation to check in the requested semantics")
    outcomes = []
    if jobs <= 1:
        for w in work:
            o = _job(*w, timeout, tuple(solvers), bounds)
            outcomes.append(o)
            if progress:
                progress(o)
    else:
        with ProcessPoolExecutor(max_workers=jobs) as ex:
            futs = [ex.submit(_job, *w, timeout, tuple(solvers), bounds) for w in work]
            for f in as_completed(futs):
                o = f.result()
                outcomes.append(o)
                if progress:
                    progress(o)
    order = {(w[1], w[2]): i for i, w in enumerate(work)}
    outcomes.sort(key=lambda o: order[(o.name, o.semantics)])
    return outcomes


def proofs_dir() -> Path:
    """The folder of the proof files shipped in the package (``navfn_smt/proofs``), found
    through the package itself: the same in a source checkout and in any install."""
    from importlib.resources import files

    root = files("navfn_smt.proofs")
    if not isinstance(root, Path):  # e.g. a zipped install: the proofs need real files
        raise NavfnInputError(f"{root}: the proof files are not on the file system")
    return root


def default_proof_files(root: Optional[Path] = None) -> list[Path]:
    """Every proof file in ``root`` (default: the package's own, :func:`proofs_dir`)."""
    root = proofs_dir() if root is None else Path(root)
    files = sorted(p for p in root.glob("*.py") if not p.name.startswith("_"))
    if not files:
        raise NavfnInputError(f"{root}: no proof files (*.py)")
    return files


def write_smt2(paths, semantics, out_dir: Path) -> list[Path]:
    """Every query (assumptions, precondition and negated claim) as an SMT-LIB2 file."""
    import z3

    from ..fileio import atomic_write_text
    from .checking import query

    try:
        out_dir.mkdir(parents=True, exist_ok=True)
    except OSError as e:
        raise NavfnInputError(f"{out_dir}: cannot create directory ({e.strerror})") from None
    written = []
    for ob in load_obligations(paths):
        for sem in semantics:
            if sem not in ob.expect:
                continue
            _, assertions = query(ob, sem)
            s = z3.Solver()
            s.add(*assertions)
            p = out_dir / f"{ob.name}.{sem}.smt2"
            atomic_write_text(p, s.to_smt2())
            written.append(p)
    return written
