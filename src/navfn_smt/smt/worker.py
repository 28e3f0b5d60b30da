"""The worker-process protocol: one solver run in a fresh Python process the caller can always kill.

A :class:`Worker` starts ``python -c BOOTSTRAP solver`` (``subprocess``: no re-import of
the caller's ``__main__``, no fork of a threaded caller) with the package first on its
path, writes the pickled request ``{"solver", "text", "timeout", "names", "logic",
"options", "parent"}`` to its stdin and, from a thread, posts
``(solver, when, stdout, stderr, exit code)`` to the caller's queue once the process ends.
In the process, :func:`main` runs the solver's adapter
(:data:`navfn_smt.smt.solvers.RUNNERS`) and writes its pickled answer dict to stdout.  The
process dies with its caller, stops itself some seconds after its time limit if the
caller is gone, and keeps the solver's chatter off the answer channel; the caller kills
it :data:`KILL_GRACE` after the solver's own time limit.  A process that dies without
answering gives an ``"error"`` answer (:func:`answer`): a crash or a hang of one solver
never blocks the caller.
"""

from __future__ import annotations

import os
import pickle
import queue
import subprocess
import sys
import threading
import time

from .solvers import RUNNERS

# The parent kills a solver process this long after the solver's own time
# limit has passed (the solver normally stops itself first).
KILL_GRACE = 0.5


# --------------------------------------------------------------- in the process
def main() -> None:
    """Entry point of a solver process: request on stdin, answer on stdout (pickles)."""
    req = pickle.load(sys.stdin.buffer)
    _tie_to_caller(req["parent"], req["timeout"])
    _limit_memory()
    out = _answer_channel()
    out.write(_pickled(_run(req)))
    out.flush()
    os._exit(0)  # skip solver teardown (can be slow on large states)


def _tie_to_caller(parent: int, timeout: float) -> None:
    """Die with the caller (Linux), and by SIGALRM in any case some seconds after the limit."""
    import signal

    try:
        import ctypes

        ctypes.CDLL(None, use_errno=True).prctl(1, signal.SIGKILL)  # PR_SET_PDEATHSIG
        if os.getppid() != parent:
            os._exit(3)
    except Exception:
        pass
    if hasattr(signal, "setitimer"):  # last resort if the caller is gone: SIGALRM kills
        signal.setitimer(signal.ITIMER_REAL, timeout + KILL_GRACE + 5.0)


# A solver process may take this much address space (NAVFN_SOLVER_MEMORY_MB overrides it):
# half the machine's memory, at most 8 GiB.  A solver that needs more fails to allocate and
# its answer is "unknown" (out of memory) or, if it dies of it, "error": the portfolio then
# reports the query as unknown, never as a crash of the caller.
def memory_limit_bytes() -> int:
    env = os.environ.get("NAVFN_SOLVER_MEMORY_MB")
    if env:
        try:
            return max(1, int(env)) * 2**20
        except ValueError:
            pass
    try:
        phys = os.sysconf("SC_PAGE_SIZE") * os.sysconf("SC_PHYS_PAGES")
    except (ValueError, OSError, AttributeError):
        phys = 16 * 2**30
    return min(8 * 2**30, phys // 2)


def _limit_memory() -> None:
    try:
        import resource

        limit = memory_limit_bytes()
        soft, hard = resource.getrlimit(resource.RLIMIT_AS)
        if hard != resource.RLIM_INFINITY:
            limit = min(limit, hard)
        resource.setrlimit(resource.RLIMIT_AS, (limit, hard))
    except (ImportError, ValueError, OSError):
        pass


def _answer_channel():
    """The original stdout, for the answer only; file descriptor 1 goes to /dev/null."""
    out = os.fdopen(os.dup(1), "wb")
    devnull = os.open(os.devnull, os.O_WRONLY)
    os.dup2(devnull, 1)  # keep solver chatter out of the answer channel
    os.close(devnull)
    return out


def _run(req: dict) -> dict:
    """The adapter's answer to the request, or an error answer (never an exception)."""
    try:
        return RUNNERS[req["solver"]](req["text"], req["timeout"], req["names"], req["logic"],
                                      **req.get("options", {}))
    except MemoryError:
        return {"status": "unknown", "detail": f"out of memory (solver limit {memory_limit_bytes() // 2**20} MiB; "
                                                 f"NAVFN_SOLVER_MEMORY_MB)"}
    except BaseException as exc:  # report, never hang the caller
        return {"status": "error", "detail": f"{type(exc).__name__}: {exc}".strip()}


def _pickled(ans: dict) -> bytes:
    """The answer as bytes (an error answer if it cannot be pickled)."""
    try:
        return pickle.dumps(ans)
    except Exception as exc:
        return pickle.dumps({"status": "error", "detail": f"unpicklable answer: {exc}"})


# Solver process bootstrap.  Processes for bitwuzla and cvc5 never touch Z3; its
# import (~0.1 s of CPU for libz3) is skipped there with an empty stand-in
# module (nothing they import uses z3's attributes at import time).
BOOTSTRAP = """\
import sys
stub = None
if sys.argv[1] != "z3":
    import types
    stub = sys.modules["z3"] = types.ModuleType("z3", "stand-in: not loaded here")
try:
    from navfn_smt.smt.worker import main
except Exception:  # something on the import path needs the real z3
    if stub is None:
        raise
    for mod in [m for m in sys.modules if m == "z3" or m.startswith("navfn_smt")]:
        del sys.modules[mod]
    from navfn_smt.smt.worker import main
main()
"""


# --------------------------------------------------------------- in the caller
def command(solver: str) -> tuple[list[str], dict[str, str]]:
    """The command line and environment of a process for ``solver``."""
    env = dict(os.environ)
    # the directory holding the navfn_smt package, first on the path
    root = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    env["PYTHONPATH"] = root + (os.pathsep + env["PYTHONPATH"] if env.get("PYTHONPATH") else "")
    return [sys.executable, "-c", BOOTSTRAP, solver], env


class Worker:
    """One solver process, and the thread that hands it its request and posts its reply
    ``(solver, when, stdout, stderr, exit code)`` to ``replies`` when it ends."""

    def __init__(self, solver: str, request: dict, replies: "queue.Queue"):
        payload = pickle.dumps({**request, "solver": solver, "parent": os.getpid()})
        cmd, env = command(solver)
        self.proc = subprocess.Popen(cmd, env=env, stdin=subprocess.PIPE,
                                     stdout=subprocess.PIPE, stderr=subprocess.PIPE)
        self.thread = threading.Thread(target=_communicate, args=(solver, self.proc, payload, replies),
                                       name=f"portfolio-{solver}", daemon=True)
        try:
            self.thread.start()
        except BaseException:
            self.kill()
            raise

    def kill(self) -> None:
        """Kill the process (its reply thread then ends)."""
        try:
            self.proc.kill()
        except Exception:
            pass

    def join(self, timeout: float) -> None:
        """Wait for the reply thread (it ends once the process is gone)."""
        self.thread.join(timeout)


def _communicate(name: str, proc, payload: bytes, q: "queue.Queue") -> None:
    """Feed the process its request, wait for it to end, post its reply."""
    try:
        out, err = proc.communicate(payload)
    except Exception as exc:
        out, err = b"", f"{type(exc).__name__}: {exc}".encode()
    q.put((name, time.monotonic(), out, err, proc.returncode))


def answer(out: bytes, err: bytes, code) -> dict:
    """The answer dict a process wrote, or an ``"error"`` answer for one that died without."""
    try:
        msg = pickle.loads(out) if out else None
    except Exception:
        msg = None
    if isinstance(msg, dict):
        return msg
    tail = err.decode(errors="replace").strip().splitlines()[-3:]
    return {"status": "error",
            "detail": f"solver process died (exit code {code})" + (": " + " | ".join(tail) if tail else "")}
