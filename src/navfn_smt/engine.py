"""Where the work of a long run goes: this process, local worker processes, or a Dask cluster.

``difftest``, ``prove``, ``check`` and ``search`` cut their work into independent tasks (a
chunk of a suite's cases, one obligation or part of one, one case of a size, one seed) and
hand them to :func:`stream`, which yields each result once, as it arrives:

- ``Engine(jobs=1)``: in this process, in order (no worker, no start-up cost);
- ``Engine(jobs=N)``: a Dask ``LocalCluster`` of N single-threaded worker processes on loopback;
- ``Engine(scheduler="tcp://host:8786")``: the Dask cluster at that address.  Its workers need
  this package installed (the same version) and the files the tasks name (suites, proof files)
  at the same paths.

Scheduling is Dask's: a worker that dies takes no task with it, the scheduler gives its tasks to
another worker (``distributed.scheduler.allowed-failures`` times at most, then the run fails
naming the task).  At most ``window`` tasks are in flight, and a task's result is dropped once
the caller has folded it in, so the driver's memory does not grow with the number of tasks.
Results are keyed by the task's position, so a result reaches the caller exactly once.
"""

from __future__ import annotations

import contextlib
import logging
import os
import signal
import threading
import uuid
from dataclasses import dataclass
from typing import Callable, Iterable, Iterator, Optional, TypeVar

from .errors import NavfnInputError

T = TypeVar("T")
R = TypeVar("R")

CONNECT_TIMEOUT = 10.0  # seconds to reach a scheduler before giving up with an error


@dataclass(frozen=True)
class Engine:
    """Where tasks run: ``jobs`` local worker processes, or the cluster at ``scheduler``.

    ``jobs=None`` is ``--jobs auto``: one worker per CPU when the run is large enough to pay
    for starting them (about 3 s), in this process otherwise (:meth:`for_work`)."""

    jobs: Optional[int] = 1
    scheduler: Optional[str] = None

    @property
    def serial(self) -> bool:
        return self.scheduler is None and (self.jobs or 1) <= 1

    def for_work(self, units: int, enough: int) -> "Engine":
        """The engine to use for ``units`` of work: ``auto`` becomes local workers when
        ``units >= enough`` and this process otherwise; an explicit choice stays."""
        if self.jobs is not None or self.scheduler:
            return self
        return Engine(default_jobs() if units >= enough else 1)

    def describe(self) -> str:
        if self.scheduler:
            return f"Dask cluster at {self.scheduler}"
        if self.jobs is None:
            return "auto (local workers where the run pays for them)"
        return "this process" if self.jobs <= 1 else f"{self.jobs} local worker processes"


def as_engine(jobs) -> Engine:
    """An :class:`Engine` as given, or the engine of a number of local workers (1: this process)."""
    return jobs if isinstance(jobs, Engine) else Engine(max(1, int(jobs)))


def engine(jobs: Optional[int] = 1, scheduler: Optional[str] = None) -> Engine:
    """The engine of ``--jobs N|auto`` / ``--scheduler ADDRESS``, checked (a one-line error otherwise)."""
    if jobs == "auto":
        jobs = None
    if jobs is not None and (not isinstance(jobs, int) or jobs < 1):
        raise NavfnInputError(f"--jobs {jobs!r}: must be a whole number of worker processes, at least 1")
    if jobs is not None and jobs > 256:
        raise NavfnInputError(f"--jobs {jobs}: at most 256 local worker processes (use --scheduler for a cluster)")
    if scheduler is not None:
        scheduler = scheduler.strip()
        host = scheduler.split("://", 1)[-1]
        if not host or ":" not in host or not host.rsplit(":", 1)[1].isdigit():
            raise NavfnInputError(f"--scheduler {scheduler!r}: expected a Dask scheduler address HOST:PORT "
                                  f"(for example tcp://127.0.0.1:8786)")
    return Engine(jobs, scheduler or None)


def _jobs(text: str):
    if text == "auto":
        return None
    try:
        return int(text)
    except ValueError:
        import argparse

        raise argparse.ArgumentTypeError(f"expected a number of worker processes or 'auto', not {text!r}") from None


def add_arguments(parser, what: str = "tasks") -> None:
    """``--jobs N|auto`` and ``--scheduler ADDRESS`` on a subcommand's parser."""
    parser.add_argument("--jobs", type=_jobs, default=None, metavar="N",
                        help=f"{what} run on N local worker processes (a Dask LocalCluster); 1 runs in this "
                             f"process; auto: one per CPU when the run is large enough to pay their start-up")
    parser.add_argument("--scheduler", default=None, metavar="ADDRESS",
                        help="run on the Dask cluster whose scheduler is at ADDRESS (e.g. tcp://10.0.0.5:8786) "
                             "instead of local processes; its workers need navfn-smt installed and the same files")


@contextlib.contextmanager
def client(eng: Engine):
    """A ``distributed.Client`` for ``eng`` (a fresh LocalCluster for ``jobs``), closed at the end."""
    try:
        from distributed import Client, LocalCluster
    except ImportError:  # pragma: no cover - a declared dependency
        raise NavfnInputError("Dask distributed is not installed (pip install distributed)") from None
    if eng.scheduler:
        try:
            c = Client(eng.scheduler, timeout=CONNECT_TIMEOUT, set_as_default=False)
        except (OSError, TimeoutError) as e:
            raise NavfnInputError(f"--scheduler {eng.scheduler}: cannot reach a Dask scheduler "
                                  f"({type(e).__name__}: {str(e).splitlines()[0] if str(e) else 'no answer'})") from None
        with c:
            yield c
        return
    if eng.jobs is None:
        eng = Engine(default_jobs())
    # one thread per worker: the tasks are CPU-bound Python, numba and solver code; the
    # scheduler's HTTP server on a free port (its default 8787 may be taken: a warning on stderr)
    # the scheduler and the nannies run on this process's event loop thread: a Ctrl-C cuts the
    # driver's waits, and their cancelled callbacks could log a traceback (tornado's "Exception
    # in callback") before the handler below quiets them; the loop's loggers say nothing while
    # the cluster lives (a task's error still reaches the driver as its exception)
    cluster, quiet = None, _quiet_shutdown(("tornado", "asyncio"))
    try:
        with _sigint_blocked():
            cluster = LocalCluster(n_workers=eng.jobs, threads_per_worker=1, processes=True,
                                   dashboard_address=None, silence_logs=logging.ERROR, memory_limit=0,
                                   scheduler_kwargs={"dashboard": False, "dashboard_address": "127.0.0.1:0"},
                                   host="127.0.0.1")
        with Client(cluster, set_as_default=False) as c:
            yield c
    except BaseException:
        quiet = {**_quiet_shutdown(), **quiet}  # the levels from before the cluster are the ones to put back
        raise
    finally:
        if cluster is not None:
            cluster.close()
        for name, level in quiet.items():
            logging.getLogger(name).setLevel(level)


def _quiet_shutdown(names=("distributed", "tornado", "asyncio")) -> dict:
    """A run that ends on an error or a Ctrl-C closes its cluster mid-flight: the scheduler and
    the nannies live in this process, and their comms, cut while reading, could log tracebacks
    at ERROR under the error the run reports.  So until the cluster is closed, this process's
    Dask, Tornado and asyncio loggers say nothing (the workers, which never see Ctrl-C, still log
    at ERROR); the levels they had are returned, to be put back."""
    before = {}
    for name in names:
        before[name] = logging.getLogger(name).level
        logging.getLogger(name).setLevel(logging.CRITICAL + 1)
    return before


@contextlib.contextmanager
def _sigint_blocked():
    """Ctrl-C held back while local worker processes start, and delivered after: the workers
    (and the cluster's thread) inherit the block, so a Ctrl-C to the terminal's process group
    stops only the driver, which closes the cluster, instead of every worker printing a
    traceback."""
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    from multiprocessing import resource_tracker

    resource_tracker.ensure_running()  # started later, it would unblock Ctrl-C in the spawning thread
    signal.pthread_sigmask(signal.SIG_BLOCK, {signal.SIGINT})
    try:
        yield
    finally:
        signal.pthread_sigmask(signal.SIG_UNBLOCK, {signal.SIGINT})


def stream(fn: Callable[[T], R], tasks: Iterable[T], eng: Engine, window: Optional[int] = None,
           on_client: Optional[Callable] = None) -> Iterator[tuple[int, R]]:
    """``(i, fn(task_i))`` for every task, each exactly once, in the order they finish.

    ``tasks`` may be a generator: it is read only as far as ``window`` tasks ahead of the
    results taken (default: four per worker).  ``on_client(client)`` is called once the
    cluster is up (the worker-loss test uses it)."""
    with session(eng, on_client) as run:
        yield from run(fn, tasks, window)


@contextlib.contextmanager
def session(eng: Engine, on_client: Optional[Callable] = None):
    """Yields ``run(fn, tasks, window=None)``, a :func:`stream` that keeps one cluster (or this
    process) for several batches: work whose later tasks depend on earlier results (a split's
    refinement rounds) starts its workers once."""
    if eng.serial:
        yield lambda fn, tasks, window=None: ((i, fn(t)) for i, t in enumerate(tasks))
        return
    with client(eng) as c:
        if on_client is not None:
            on_client(c)
        workers = max(1, len(c.scheduler_info().get("workers", {})) or eng.jobs or 1)
        yield lambda fn, tasks, window=None: _on_cluster(c, fn, tasks, window or 4 * workers)


def _on_cluster(c, fn, tasks, window: int):
    from distributed import as_completed

    run = uuid.uuid4().hex[:12]
    it = iter(enumerate(tasks))
    pending = as_completed(loop=c.loop)
    index = {}

    def submit_next() -> bool:
        for i, t in it:
            f = c.submit(fn, t, key=f"navfn-{run}-{i}", pure=False)
            index[f.key] = i
            pending.add(f)
            return True
        return False

    for _ in range(window):
        if not submit_next():
            break
    seen: set[int] = set()
    try:
        for f in pending:
            i = index.pop(f.key)
            result = f.result()  # a task's own exception is raised here, as in the serial run
            f.release()
            if i in seen:  # pragma: no cover - as_completed yields each future once
                raise RuntimeError(f"task {i} returned twice")
            seen.add(i)
            submit_next()
            yield i, result
    finally:
        for f in list(pending.futures):
            f.cancel()


def in_order(results: Iterable[tuple[int, R]],
             on_arrival: Optional[Callable[[int, R], None]] = None) -> Iterator[tuple[int, R]]:
    """The ``(i, result)`` pairs of :func:`stream`, which arrive in any order, handed on in task
    order (a result waits for those before it), so that what is folded from them does not depend
    on where the tasks ran; ``on_arrival(i, result)`` hears of each as it arrives."""
    waiting: dict = {}
    nxt = 0
    for i, r in results:
        if on_arrival is not None:
            on_arrival(i, r)
        waiting[i] = r
        while nxt in waiting:
            yield nxt, waiting.pop(nxt)
            nxt += 1


def default_jobs() -> int:
    """The number of CPUs this process may use (the default of ``--jobs`` where parallel runs pay)."""
    try:
        return max(1, len(os.sched_getaffinity(0)))
    except AttributeError:  # pragma: no cover - not Linux
        return max(1, os.cpu_count() or 1)
