"""Run proof obligations: every obligation of the given files in every requested semantics.

Each (obligation, semantics) pair is one task of the :mod:`~navfn_smt.engine` (this process,
local workers or a Dask cluster).  A task carries its proof file's path and contents, and the
worker loads the obligation itself (obligations hold functions, which do not travel between
processes): from the file, or from the contents where the file is not (a remote worker).
Solving goes through :func:`solve_query`: the solver portfolio when it is available, Z3 alone
otherwise.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Callable, Optional, Union

from ..engine import Engine, as_engine, default_jobs, stream
from ..errors import NavfnInputError
from .checking import Outcome, check, solve_query
from .domains import is_fp32
from .obligation import load_obligations, load_obligations_from

SEMANTICS = ("real", "fp32")
PARALLEL_FROM = 4  # --jobs auto: local workers from this many (obligation, semantics) tasks on, if the CPUs allow


@dataclass(frozen=True)
class Task:
    """One obligation in one semantics, with what a worker needs to check it: the proof
    file's path and contents, the time limit, the solvers and whether to search bounds."""

    path: str
    source: bytes
    name: str
    semantics: str
    timeout: float
    solvers: tuple
    bounds: bool = True


def _job(task: Task) -> Outcome:
    """The verdict of one task (run by a worker, or in this process)."""
    ob = next(o for o in load_obligations_from(task.path, task.source) if o.name == task.name)
    return check(ob, task.semantics, task.timeout, solve_query(task.solvers), bounds=task.bounds)


def tasks(paths, semantics=SEMANTICS, timeout: float = 30.0, solvers=("z3",), bounds: bool = True,
          everything: bool = True, slow_only: bool = False, skip: frozenset = frozenset()) -> list[Task]:
    """Every (obligation, semantics) of the proof files that has an expected verdict, in
    file, obligation and semantics order (the order of the results); without
    ``everything``, not the slow ones (:attr:`Obligation.slow`); with ``slow_only``, only what
    ``everything`` adds to the default run: the slow ones and, with ``bounds``, the fp32
    queries whose bound a refutation searches (:func:`wanted`); never the ``(name, semantics)``
    pairs of ``skip``."""
    sources = {}
    out = []
    for o in load_obligations(paths):
        if o.source not in sources:
            sources[o.source] = Path(o.source).read_bytes()
        out.extend(Task(o.source, sources[o.source], o.name, s, timeout, tuple(solvers), bounds)
                   for s in semantics if wanted(o, s, everything, slow_only, bounds) and (o.name, s) not in skip)
    return out


def wanted(o, semantics: str, everything: bool = True, slow_only: bool = False, bounds: bool = True) -> bool:
    """Whether a run asks ``o`` in ``semantics`` (:func:`tasks`): a float32 semantics of another
    build arithmetic as x86-64's ``fp32`` (what is slow there is slow in each)."""
    declared = "fp32" if is_fp32(semantics) else semantics
    if declared not in o.expect:
        return False
    if slow_only:
        return declared in o.slow or (bounds and o.bound is not None and declared == "fp32")
    return everything or declared not in o.slow


def split_decided(paths) -> frozenset:
    """The ``(name, "fp32")`` of every obligation of ``paths`` that a split of theirs decides part
    by part (:mod:`.split`): ``prove --skip-split`` leaves their whole queries to ``navfn-smt split``."""
    from .split import load_splits

    return frozenset((s.obligation, "fp32") for s in load_splits(paths))


def slow_queries(paths, semantics=SEMANTICS) -> list[str]:
    """The ``name (semantics)`` of the slow queries a default run leaves out."""
    return [f"{o.name} ({s})" for o in load_obligations(paths) for s in semantics
            if wanted(o, s, slow_only=True, bounds=False)]


def run(paths, semantics=SEMANTICS, timeout: float = 30.0, jobs: Union[Engine, int] = 1, solvers=("z3",),
        progress: Optional[Callable[[Outcome], None]] = None, bounds: bool = True,
        everything: bool = True, known: Optional[dict] = None, slow_only: bool = False,
        skip: frozenset = frozenset()) -> list[Outcome]:
    """The outcome of every obligation of ``paths`` in every semantics it declares, judged
    against what is ``known`` (:func:`navfn_smt.smt.split.known_of_files`; default: each
    obligation's declaration), in the order of :func:`tasks` whatever the order they finish in.  ``jobs``: an
    :class:`~navfn_smt.engine.Engine` (``auto`` resolved here), or a number of local workers;
    ``skip``: the ``(name, semantics)`` pairs left out (:func:`split_decided`)."""
    if not (timeout > 0 and timeout < float("inf")):
        raise NavfnInputError(f"--timeout {timeout!r}: must be a positive number of seconds")
    work = tasks(paths, semantics, timeout, solvers, bounds, everything, slow_only, skip)
    if not work:
        raise NavfnInputError("no obligation to check in the requested semantics")
    eng = as_engine(jobs)
    got: dict[int, Outcome] = {}
    for i, o in stream(_job, work, auto_engine(eng, len(work), solvers)):
        if known is not None:
            o.judge(known[(o.name, o.semantics)])
        got[i] = o
        if progress:
            progress(o)
    return [got[i] for i in range(len(work))]


def auto_engine(eng: Engine, tasks: int, solvers) -> Engine:
    """``--jobs auto`` for ``tasks`` queries: local workers only when every worker can have a
    CPU for each solver of the portfolio (each query already runs one process per solver, and
    their time limits are wall-clock: workers that share the CPUs with them turn proofs into
    timeouts), and at least two workers result; this process otherwise (on 2 CPUs, always)."""
    if eng.jobs is not None or eng.scheduler:
        return eng
    workers = default_jobs() // max(1, len(tuple(solvers)))
    return Engine(workers if workers >= 2 and tasks >= PARALLEL_FROM else 1)


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


def proof_files(names) -> list[Path]:
    """The proof files the command line names: Python files, or folders of them (every
    ``*.py`` not starting with ``_``, as in the package's own ``proofs/``)."""
    files: list[Path] = []
    for name in names:
        p = Path(name)
        if p.is_dir():
            try:
                files += default_proof_files(p)
            except NavfnInputError:
                raise NavfnInputError(f"{name}: no proof files in this folder (prove reads Python files "
                                      "declaring obligations, *.py not starting with _)") from None
        elif not p.exists():
            raise NavfnInputError(f"{name}: no such proof file or folder")
        elif p.suffix != ".py":
            raise NavfnInputError(f"{name}: not a proof file (prove reads Python files declaring obligations, "
                                  "or a folder of them)")
        else:
            files.append(p)
    return files
