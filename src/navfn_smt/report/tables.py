"""The terminal both reports and progress bars go to, with rich: the shared consoles and
the progress of a long run.

On a terminal, tables fit its width and a long run shows a rich progress bar on stderr.
When the output is piped or redirected, tables are printed at their natural width (a
table never wraps in a file or a pager; ``COLUMNS`` still sets a width when given) and a
long run prints a plain heartbeat line on stderr every :data:`HEARTBEAT` seconds (or every
``NAVFN_HEARTBEAT`` seconds when that variable is set).
"""

from __future__ import annotations

import contextlib
import os
import sys
import time

from rich.console import Console
from rich.progress import BarColumn, MofNCompleteColumn, Progress, TextColumn, TimeElapsedColumn, TimeRemainingColumn

from ..errors import NavfnInputError

HEARTBEAT = 10.0  # seconds between two progress lines when stderr is not a terminal
WIDE = 10_000  # the width of a console that is not a terminal: wide enough that no table wraps


def make_console(stderr: bool = False) -> Console:
    """A rich console; when it does not write to a terminal and ``COLUMNS`` is unset, so wide
    that tables keep one line per row (they take only the width they need)."""
    stream = sys.stderr if stderr else sys.stdout
    tty = getattr(stream, "isatty", lambda: False)()
    width = None if tty or os.environ.get("COLUMNS") else WIDE
    return Console(stderr=stderr, width=width)


console = make_console()
err_console = make_console(stderr=True)


def duration(seconds: float) -> str:
    """``42 s``, ``3 min 20 s`` or ``1 h 05 min``."""
    s = int(round(seconds))
    if s < 60:
        return f"{s} s"
    if s < 3600:
        return f"{s // 60} min {s % 60:02d} s"
    return f"{s // 3600} h {s % 3600 // 60:02d} min"


def heartbeat_every(default: float = HEARTBEAT) -> float:
    """Seconds between two heartbeat lines: ``NAVFN_HEARTBEAT`` when set, else ``default``."""
    text = os.environ.get("NAVFN_HEARTBEAT", "").strip()
    if not text:
        return default
    try:
        every = float(text)
    except ValueError:
        every = -1.0
    if not every > 0 or every == float("inf"):
        raise NavfnInputError(f"NAVFN_HEARTBEAT={text!r}: give the seconds between two progress lines, a positive "
                              f"number")
    return every


def heartbeat(total: int, description: str, every: float | None = None, stream=None, clock=time.monotonic):
    """``advance(n)`` that prints ``description: done/total (p%), elapsed, about T left`` to
    ``stream`` (stderr) at most every ``every`` seconds, and a last line when the run ends
    after having printed any (a run shorter than ``every`` stays silent).  ``every`` defaults to
    :func:`heartbeat_every`."""
    every = heartbeat_every() if every is None else every
    t0 = clock()
    state = {"done": 0, "t0": t0, "last": t0, "printed": False}

    def line(now: float) -> str:
        done, elapsed = state["done"], now - state["t0"]
        pct = f" ({100 * done // total}%)" if total else ""
        left = ""
        if 0 < done < total:
            left = f", about {duration(elapsed * (total - done) / done)} left"
        return f"{description}: {done}/{total}{pct}, {duration(elapsed)}{left}"

    def advance(n: int) -> None:
        if state.get("finished"):
            return
        state["done"] += n
        now = clock()
        state["finished"] = finished = bool(total) and state["done"] >= total
        if now - state["last"] >= every or (finished and state["printed"]):
            state["last"] = now
            state["printed"] = True
            print(line(now), file=stream or sys.stderr, flush=True)

    return advance


def _rich_progress() -> Progress:
    """The terminal's bar: description, bar, done/total, elapsed, remaining (on stderr, cleared at the end)."""
    return Progress(TextColumn("{task.description}"), BarColumn(), MofNCompleteColumn(), TimeElapsedColumn(),
                    TimeRemainingColumn(), console=err_console, transient=True)


@contextlib.contextmanager
def progress_bar(total: int, description: str, enabled: bool = True, every: float | None = None):
    """Yields ``advance(n)``: a rich bar on stderr when it is a terminal, else a heartbeat
    line every ``every`` seconds (:func:`heartbeat`); nothing when not ``enabled``."""
    if not enabled:
        yield lambda n: None
        return
    if not sys.stderr.isatty():
        yield heartbeat(total, description, every)
        return
    with _rich_progress() as prog:
        task = prog.add_task(description, total=total)
        yield lambda n: prog.advance(task, n)


@contextlib.contextmanager
def progress_counts(description: str, enabled: bool = True, every: float | None = None):
    """Yields ``progress(done, total)`` for work that learns its total only once it runs
    (absolute counts rather than steps): a rich bar on a terminal, else heartbeat lines."""
    if not enabled:
        yield lambda done, total: None
        return
    if not sys.stderr.isatty():
        state: dict = {}

        def beat(done: int, total: int) -> None:
            if "advance" not in state:
                state["advance"], state["done"] = heartbeat(total, description, every), 0
            state["advance"](done - state["done"])
            state["done"] = done

        yield beat
        return
    with _rich_progress() as prog:
        task = prog.add_task(description, total=None)
        yield lambda done, total: prog.update(task, completed=done, total=total)
