"""The oracle's programs compiled one source at a time, each object kept once per content.

A program is its sources compiled one by one (``-c``) and linked.  An object is kept in a
cache folder under the SHA-256 of what decides it: the compiler (its name, ``--version`` and
target), its flags, and the source after preprocessing (``-E``: every header it includes and
every define in it) with the paths of the build's own folders (the Nav2 sources, this
package's drivers and stubs, the build folder) replaced by fixed names.  The compile maps the
same folders to the same names (``-ffile-prefix-map``, also the working directory it runs
in), so the object does not say where the folders were: two sources whose preprocessed text
agrees give the same object, and it is compiled once.  A build of a copy of a tree with one
file changed compiles that file and what includes it; building the same sources for another
target, or a second time, compiles nothing the first did not.

The cache folder is ``$NAVFN_SMT_OBJECT_CACHE``, else ``$XDG_CACHE_HOME/navfn-smt/objects``
(``~/.cache/navfn-smt/objects``); ``NAVFN_SMT_OBJECT_CACHE=off`` compiles everything afresh.
An object is written beside its place and renamed into it, so builds running side by side
(test processes, a user's two shells) never read half an object.
"""

from __future__ import annotations

import hashlib
import os
import shutil
import subprocess
import tempfile
from pathlib import Path
from typing import Optional

from ..errors import NavfnInputError

LINK_ONLY = ("-L", "-l", "-Wl,")  # flags of the link step alone
OFF = "off"


def cache_dir() -> Optional[Path]:
    """The object cache's folder, or None when ``NAVFN_SMT_OBJECT_CACHE=off``."""
    named = os.environ.get("NAVFN_SMT_OBJECT_CACHE")
    if named == OFF:
        return None
    if named:
        return Path(named)
    base = os.environ.get("XDG_CACHE_HOME") or str(Path.home() / ".cache")
    return Path(base) / "navfn-smt" / "objects"


class Compiler:
    """Compiles sources to objects for one build: ``tc``'s compiler and flags, the folders
    ``roots`` (``{folder: fixed name}``) mapped out of the objects, objects kept in ``cache``."""

    def __init__(self, tc, roots: dict, cache: Optional[Path]):
        self.tc = tc
        self.named = {name: str(Path(folder).absolute()) for folder, name in roots.items()}
        pairs = {}
        for folder, name in roots.items():  # as given and as resolved: a symlink's path is either
            pairs[str(Path(folder).absolute())] = pairs[str(Path(folder).resolve())] = name
        self.roots = sorted(pairs.items(), key=lambda r: -len(r[0]))  # the longest first: inner folders
        self.cache = cache
        self.version, self.machine = tc.version(), tc.machine()  # asked of the compiler once a build
        self.identity = f"{tc.cxx}\n{self.version}\n{self.machine}\n"
        self.compiled = 0
        self.reused = 0

    def unmap(self, path: Path) -> Path:
        """The file a path of the objects' debug information names, in this build's folders."""
        text = str(path)
        for name, folder in self.named.items():
            if text == name or text.startswith(name + "/"):
                return Path(folder + text[len(name):])
        return Path(path)

    def maps(self) -> list:
        # GCC takes the last option that matches a path, so the longest folder goes last
        return [f"-ffile-prefix-map={old}={new}" for old, new in reversed(self.roots)]

    def normal(self, text: str) -> str:
        for old, new in self.roots:
            text = text.replace(old, new)
        return text

    def _run(self, cmd, what: str, cwd: Path) -> subprocess.CompletedProcess:
        r = subprocess.run(cmd, capture_output=True, text=True, cwd=cwd)
        if r.returncode != 0:
            first = next((line for line in r.stderr.splitlines() if "error" in line), r.stderr.strip()[:300])
            raise NavfnInputError(f"the C++ build of {what} failed: {first}")
        return r

    def compile(self, source: Path, includes, defines, flags, out: Path, what: str) -> Path:
        """``source`` compiled to the object ``out`` (taken from the cache when it is there)."""
        source, out = Path(source).absolute(), Path(out).absolute()  # the compile runs in the objects' folder
        cmd = [self.tc.cxx, *self.tc.all_flags, *flags, *self.maps(), *(f"-I{Path(i).absolute()}" for i in includes),
               *(f"-D{d}" for d in defines)]
        cwd = out.parent
        if self.cache is None:
            self._run([*cmd, "-c", str(source), "-o", str(out)], what, cwd)
            self.compiled += 1
            return out
        pre = self._run([*cmd, "-E", str(source)], what, cwd).stdout
        key = hashlib.sha256("\0".join([self.identity, *self.tc.all_flags, *flags, self.normal(pre)])
                             .encode("utf-8", "surrogateescape")).hexdigest()
        kept = self.cache / key[:2] / f"{key}.o"
        if kept.is_file():
            shutil.copyfile(kept, out)
            self.reused += 1
            return out
        self._run([*cmd, "-c", str(source), "-o", str(out)], what, cwd)
        self.compiled += 1
        try:
            kept.parent.mkdir(parents=True, exist_ok=True)
            fd, part = tempfile.mkstemp(dir=kept.parent, suffix=".part")
            os.close(fd)
            shutil.copyfile(out, part)
            os.replace(part, kept)
        except OSError:  # a cache that cannot be written keeps nothing; the build goes on
            pass
        return out

    def link(self, objects, extra, out: Path) -> None:
        out = Path(out).absolute()
        self._run([self.tc.cxx, *self.tc.all_flags, *(str(Path(o).absolute()) for o in objects), *extra, "-o", str(out)],
                  out.name, out.parent)


def compile_flags(extra) -> list:
    """The flags of ``extra`` (a program's own) that the compile of each source takes."""
    return [f for f in extra if not f.startswith(LINK_ONLY)]
