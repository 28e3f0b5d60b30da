"""The user guide stays true: every command of docs/guide.md marked for testing is run again
and its output compared with the text the guide shows.

A block is marked by an HTML comment just before its fence (invisible on the site):

    <!-- guide: run -->            run it here (a command of under ~20 s)
    <!-- guide: slow -->           run it only with NAVFN_SLOW=1
    <!-- guide: run rc=1 -->       the command's expected exit status (default 0)

The fenced block holds ``$ COMMAND`` (continued with a trailing backslash) and then its standard
output. A line ``...`` in the guide stands for any number of lines. Before comparing, both
sides are normalised: durations (``2.1 s``, ``0.7s``, a proof's seconds column) become ``<t>``,
solver names (which solver of the portfolio answers first varies) become ``<solver>``,
runs of spaces and of table rules collapse, trailing spaces go.  ``/tmp/cx`` in a command
is a fresh temporary directory.  The commands run from the repository root with
``COLUMNS=120``, as the guide's outputs were captured.
"""

from __future__ import annotations

import os
import re
import shlex
import shutil
import subprocess
import sys
import tempfile
from dataclasses import dataclass
from pathlib import Path

import pytest
from conftest import SLOW

REPO = Path(__file__).resolve().parent.parent
GUIDE = REPO / "docs" / "guide.md"
MARK = re.compile(r"<!--\s*guide:\s*(run|slow)((?:\s+\w+=\S+)*)\s*-->")


@dataclass
class Block:
    line: int
    kind: str
    rc: int
    command: str
    output: list[str]


def guide_blocks() -> list[Block]:
    lines = GUIDE.read_text().splitlines()
    blocks = []
    for i, line in enumerate(lines):
        m = MARK.fullmatch(line.strip())
        if not m:
            continue
        opts = dict(o.split("=", 1) for o in m.group(2).split())
        j = i + 1
        assert lines[j].startswith("```"), f"guide.md:{i + 1}: the marker must be followed by a fence"
        j += 1
        assert lines[j].startswith("$ "), f"guide.md:{j + 1}: the block must start with '$ command'"
        command = lines[j][2:]
        while command.endswith("\\"):
            j += 1
            command = command[:-1] + " " + lines[j].strip()
        j += 1
        out = []
        while not lines[j].startswith("```"):
            out.append(lines[j])
            j += 1
        blocks.append(Block(i + 1, m.group(1), int(opts.get("rc", 0)), command, out))
    return blocks


SOLVERS = re.compile(r"\b(?:z3|bitwuzla|cvc5)(?:,(?:z3|bitwuzla|cvc5|bitwuz|la))*\b")
TIME = re.compile(r"(?<![\w.])\d+(?:\.\d+)?\s?s\b|(?<=│)\s*\d+\.\d\d\s*(?=│)")


def normalise(text_lines: list[str]) -> list[str]:
    out = []
    for line in text_lines:
        line = TIME.sub("<t>", line)
        line = SOLVERS.sub("<solver>", line)
        line = re.sub(r"[─━═]+", "─", line)
        line = re.sub(r" +", " ", line).rstrip()
        out.append(line)
    return out


def matches(expected: list[str], actual: list[str]) -> bool:
    """``expected`` with ``...`` lines standing for any run of lines, against ``actual``."""
    parts: list[list[str]] = [[]]
    for line in expected:
        if line.strip() == "...":
            parts.append([])
        else:
            parts[-1].append(line)
    if len(parts) == 1:
        return expected == actual
    head, *middle, tail = parts
    if actual[:len(head)] != head or (tail and actual[len(actual) - len(tail):] != tail):
        return False
    pos, end = len(head), len(actual) - len(tail)
    for part in middle:
        for k in range(pos, end - len(part) + 1):
            if actual[k:k + len(part)] == part:
                pos = k + len(part)
                break
        else:
            return False
    return pos <= end


BLOCKS = guide_blocks()


@pytest.fixture(scope="module")
def scratch():
    d = Path(tempfile.mkdtemp(prefix="guide"))
    yield d
    shutil.rmtree(d, ignore_errors=True)


def test_the_guide_has_tested_commands():
    kinds = [b.kind for b in BLOCKS]
    assert kinds.count("run") >= 6 and "slow" in kinds


def test_matches_handles_ellipses():
    assert matches(["a", "...", "d"], ["a", "b", "c", "d"])
    assert matches(["a", "...", "c", "...", "e"], ["a", "b", "c", "d", "e"])
    assert not matches(["a", "...", "x"], ["a", "b"])
    assert matches(["a"], ["a"]) and not matches(["a"], ["a", "b"])


@pytest.mark.parametrize("block", BLOCKS, ids=[f"line{b.line}-{b.command.split()[1]}" for b in BLOCKS])
def test_guide_command(block: Block, scratch: Path):
    if block.kind == "slow" and not SLOW:
        pytest.skip("a slow guide command (NAVFN_SLOW=1 runs it)")
    cx = scratch / "cx"
    argv = shlex.split(block.command.replace("/tmp/cx", str(cx)))
    assert argv[0] == "navfn-smt"
    env = dict(os.environ, COLUMNS="120")
    env.pop("FORCE_COLOR", None)
    done = subprocess.run([sys.executable, "-m", "navfn_smt", *argv[1:]], cwd=REPO, env=env,
                          capture_output=True, text=True, timeout=900)
    assert done.returncode == block.rc, done.stderr
    actual = normalise(done.stdout.replace(str(cx), "/tmp/cx").splitlines())
    expected = normalise(block.output)
    assert matches(expected, actual), (
        f"docs/guide.md:{block.line}: the output of `{block.command}` no longer matches the guide\n"
        + "--- guide\n" + "\n".join(block.output) + "\n--- now\n" + done.stdout)
