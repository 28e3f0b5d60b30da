"""Nav2's lint on a fix: what its patch adds to the findings of ament's two C++ linters.

Nav2 runs ``ament_uncrustify`` and ``ament_cpplint`` on its packages.  Here each file the
distribution's patch touches is linted twice, as shipped and patched:

- uncrustify with ament's configuration for the installed version (``lint/``: the
  ``ament_code_style_0_XX.cfg`` files of ament_lint, Apache-2.0), formatting the file; a finding is
  a run of lines uncrustify would change;
- cpplint (PyPI ``cpplint``) with the arguments ``ament_cpplint`` passes (line length 100, its
  filters, ``--root`` the package's ``include`` folder), run from the package's folder.

A finding counts against the patch only when the patched file has more of it than the shipped
one (the same message, line numbers aside; every finding in a file the patch adds): a linter's version may find things in Nav2's own
code that Nav2's CI does not, and those are not the patch's.
"""

from __future__ import annotations

import difflib
import re
import shutil
import subprocess
import sys
import tempfile
from collections import Counter
from pathlib import Path

from ..errors import NavfnInputError
from ..spec import fixes
from ..spec.fix import FIX as THE_FIX
from .build import distribution, find_sources, fix_patch, patched_copy, patched_files, patches_of

CONFIGS = Path(__file__).resolve().parent / "lint"
CPPLINT_ARGS = ("--linelength=100", "--extensions=c,cc,cpp,cxx", "--headers=h,hh,hpp,hxx",
                "--filter=-build/c++11,-runtime/references,-whitespace/braces,-whitespace/indent,"
                "-whitespace/parens,-whitespace/semicolon")
CXX_FILES = (".cpp", ".hpp", ".h", ".cc")  # the files of a patch the two linters read
CPPLINT_LINE = re.compile(r"^(?P<file>[^:]+):(?P<line>\d+):\s+(?P<message>.*)$")


def uncrustify_config() -> tuple[Path, str]:
    """ament's configuration for the installed uncrustify, and its version; a clear error when
    uncrustify is missing or of a version ament has no configuration for."""
    exe = shutil.which("uncrustify")
    if exe is None:
        raise NavfnInputError("uncrustify is not installed (Debian: apt-get install uncrustify)")
    out = subprocess.run([exe, "--version"], capture_output=True, text=True).stdout.strip()
    m = re.search(r"(\d+)\.(\d+)", out)
    cfg = CONFIGS / f"ament_code_style_{m.group(1)}_{m.group(2)}.cfg" if m else None
    if cfg is None or not cfg.is_file():
        have = ", ".join(sorted(p.name for p in CONFIGS.glob("*.cfg")))
        raise NavfnInputError(f"no ament configuration for {out or 'this uncrustify'} (there are: {have})")
    return cfg, out


def uncrustify_findings(path: Path, cfg: Path) -> list[dict]:
    """Each run of lines uncrustify would change in ``path``: its first line and the lines
    as they are and as the style wants them."""
    r = subprocess.run(["uncrustify", "-q", "-c", str(cfg), "-f", str(path)], capture_output=True, text=True)
    if r.returncode != 0:
        raise NavfnInputError(f"uncrustify could not read {path}: {(r.stderr.strip().splitlines() or ['no output'])[-1]}")
    have, want = path.read_text(encoding="utf-8").splitlines(), r.stdout.splitlines()
    out = []
    for tag, i1, i2, j1, j2 in difflib.SequenceMatcher(None, have, want, autojunk=False).get_opcodes():
        if tag != "equal":
            out.append({"line": i1 + 1, "message": "uncrustify would write " + " / ".join(want[j1:j2]).strip()
                        + " for " + " / ".join(have[i1:i2]).strip()})
    return out


def cpplint_findings(package: Path, rel: str) -> list[dict]:
    """cpplint's findings on ``package / rel`` as ``ament_cpplint`` runs it."""
    r = subprocess.run([sys.executable, "-m", "cpplint", *CPPLINT_ARGS, "--root=include", rel], capture_output=True,
                       text=True, cwd=package)
    if "No module named cpplint" in r.stderr:
        raise NavfnInputError("cpplint is not installed (pip install cpplint)")
    out = []
    for line in r.stderr.splitlines():
        m = CPPLINT_LINE.match(line)
        if m and m.group("file") == rel:
            out.append({"line": int(m.group("line")), "message": m.group("message").strip()})
    return out


def added(shipped: list[dict], patched: list[dict]) -> list[dict]:
    """The findings of ``patched`` beyond those of ``shipped``, the same message counted."""
    left = Counter(f["message"] for f in shipped)
    out = []
    for f in patched:
        if left[f["message"]] > 0:
            left[f["message"]] -= 1
        else:
            out.append(f)
    return out


def lint_fix(nav2_src, patch=None, fix=THE_FIX) -> dict:
    """The two linters on each file ``fix``'s patch (a patched :class:`~navfn_smt.spec.planner.Fix`
    or its name; default: the fix of docs/fix.md), or ``patch``, touches, as shipped and
    patched: the counts and the findings the patch adds."""
    src = find_sources(nav2_src)
    fix = fixes.named(fix)
    patch = Path(patch) if patch is not None else fix_patch(src, fix)
    if not patch.is_file():
        raise NavfnInputError(f"no patch {patch.name} of the {fix.name} fix for {distribution(src)} "
                              f"(patches/{patches_of(fix).name}/)")
    cfg, version = uncrustify_config()
    files = [f for f in patched_files(patch) if f.endswith(CXX_FILES)]
    with tempfile.TemporaryDirectory() as tmp:
        fixed = patched_copy(src, Path(tmp), patch)
        rows = []
        for rel in files:
            package, inner = rel.split("/", 1)
            for tool in ("uncrustify", "cpplint"):
                new = not (src / rel).is_file()  # a file the patch adds: all its findings are the patch's
                if tool == "uncrustify":
                    before, after = [] if new else uncrustify_findings(src / rel, cfg), uncrustify_findings(fixed / rel, cfg)
                else:
                    before = [] if new else cpplint_findings(src / package, inner)
                    after = cpplint_findings(fixed / package, inner)
                rows.append({"file": rel, "tool": tool, "shipped": len(before), "patched": len(after),
                             "added": added(before, after)})
    return {"sources": str(src.resolve()), "distribution": distribution(src), "patch": patch.name, "fix": fix.name,
            "uncrustify": {"version": version, "config": cfg.name}, "cpplint": {"arguments": list(CPPLINT_ARGS)},
            "files": rows}
