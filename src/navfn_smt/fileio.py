"""Writing files whole or not at all: a temporary name in the same directory, then a rename.

Every file the toolkit writes for a user (reports, pictures, maps, golden files) goes
through here, so a failure or an interruption never leaves a half-written file behind.
"""

from __future__ import annotations

import contextlib
import os
from pathlib import Path

import numpy as np

from .errors import NavfnInputError


@contextlib.contextmanager
def atomic_path(path, suffix: str = ""):
    """Yield a temporary path beside ``path``; on success it replaces ``path``.

    ``suffix`` keeps an extension on the temporary name (for writers that choose the format
    by extension).  OS errors become one-line :class:`NavfnInputError`.
    """
    p = Path(path)
    if not p.parent.is_dir():
        raise NavfnInputError(f"{path}: directory {p.parent} does not exist")
    tmp = p.with_name(f".{p.name}.tmp{os.getpid()}{suffix}")
    try:
        yield tmp
        os.replace(tmp, p)
    except OSError as e:
        tmp.unlink(missing_ok=True)
        raise NavfnInputError(f"{path}: cannot write ({e.strerror or e})") from None
    except BaseException:
        tmp.unlink(missing_ok=True)
        raise


@contextlib.contextmanager
def atomic_folder(path):
    """Yield a new temporary folder beside the folder ``path``; on success it replaces ``path``
    (which, when it exists, the caller has judged replaceable); on failure it is removed."""
    import shutil
    import tempfile

    p = Path(path)
    p.parent.mkdir(parents=True, exist_ok=True)
    tmp = Path(tempfile.mkdtemp(prefix=f".{p.name}.", dir=p.parent)).absolute()
    try:
        yield tmp
        if p.exists():
            shutil.rmtree(p)
        tmp.rename(p)
    finally:
        if tmp.exists():
            shutil.rmtree(tmp, ignore_errors=True)


def atomic_write_bytes(path, data: bytes) -> None:
    with atomic_path(path) as tmp:
        with open(tmp, "wb") as f:
            f.write(data)
            f.flush()
            os.fsync(f.fileno())


def atomic_write_text(path, text: str) -> None:
    atomic_write_bytes(path, text.encode("utf-8"))


def check_writable(path) -> None:
    """Fail before a long run when its report could not be written at the end.

    Probes with a temporary file beside ``path``, so an existing file at ``path`` is left
    as it is until the run replaces it.
    """
    p = Path(path)
    if not p.parent.is_dir():
        raise NavfnInputError(f"{path}: directory {p.parent} does not exist")
    if p.is_dir():
        raise NavfnInputError(f"{path}: is a directory")
    probe = p.with_name(f".{p.name}.probe{os.getpid()}")
    try:
        probe.write_bytes(b"")
        probe.unlink()
    except OSError as e:
        raise NavfnInputError(f"{path}: cannot write ({e.strerror or e})") from None


def check_writable_dir(path) -> None:
    """Fail before a long run when the directory it writes into could not be created or written.

    Nothing is created: the nearest existing ancestor of ``path`` must be a writable directory.
    """
    p = Path(path)
    if p.exists() and not p.is_dir():
        raise NavfnInputError(f"{path}: not a directory")
    existing = p
    while not existing.exists():
        existing = existing.parent
    if not existing.is_dir():
        raise NavfnInputError(f"{path}: {existing} is not a directory")
    if not os.access(existing, os.W_OK | os.X_OK):
        raise NavfnInputError(f"{path}: cannot write into {existing}")


def jsonable(v):
    """``v`` with numpy values and arrays as plain Python ones, keys as strings: what
    ``json.dumps`` takes."""
    if isinstance(v, dict):
        return {str(k): jsonable(x) for k, x in v.items()}
    if isinstance(v, (list, tuple)):
        return [jsonable(x) for x in v]
    if isinstance(v, np.generic):
        return v.item()
    if isinstance(v, np.ndarray):
        return v.tolist()
    return v
