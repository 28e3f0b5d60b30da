"""The package's structure, read from its imports (every import, at module level or inside a
function): no two parts (the folders and top-level modules of ``src/navfn_smt``) import each
other, directly or round a loop, and no part imports a private name (``_x``) of another."""

from __future__ import annotations

import ast
from pathlib import Path

PACKAGE = Path(__file__).resolve().parent.parent / "src" / "navfn_smt"


def _module_name(path: Path) -> list[str]:
    rel = path.relative_to(PACKAGE).with_suffix("")
    parts = list(rel.parts)
    return parts[:-1] if parts[-1] == "__init__" else parts


def _imports(path: Path, source: str | None = None):
    """``(target module parts, names)`` of every import of the package itself in ``path``
    (read from ``source`` when given: a module as it would be at that place)."""
    here = _module_name(path)
    package = here if path.name == "__init__.py" else here[:-1]
    text = path.read_text(encoding="utf-8") if source is None else source
    for node in ast.walk(ast.parse(text)):
        if isinstance(node, ast.ImportFrom):
            if node.level:
                base = package[:len(package) - (node.level - 1)] if node.level > 1 else package
                target = base + (node.module.split(".") if node.module else [])
            elif node.module and node.module.split(".")[0] == "navfn_smt":
                target = node.module.split(".")[1:]
            else:
                continue
            names = [a.name for a in node.names]
            if not node.module:  # ``from . import x``: x is a module
                for n in names:
                    yield target + [n], []
            else:
                yield target, names
        elif isinstance(node, ast.Import):
            for a in node.names:
                if a.name.split(".")[0] == "navfn_smt":
                    yield a.name.split(".")[1:], []


def _part(parts: list[str]) -> str:
    return parts[0] if parts else "navfn_smt"


def _graph():
    edges: dict = {}
    private = []
    for path in sorted(PACKAGE.rglob("*.py")):
        me = _part(_module_name(path))
        for target, names in _imports(path):
            other = _part(target)
            if other != me and other != "navfn_smt":
                edges.setdefault(me, set()).add(other)
                private += [(str(path.relative_to(PACKAGE)), ".".join(target), n) for n in names
                            if n.startswith("_") and not n.startswith("__")]
    return edges, private


def _cycles(edges: dict) -> list:
    found = []

    def visit(node, path):
        for nxt in sorted(edges.get(node, ())):
            if nxt == path[0]:
                found.append(path + [nxt])
            elif nxt not in path and nxt > path[0]:  # each cycle once, from its smallest part
                visit(nxt, path + [nxt])

    for start in sorted(edges):
        visit(start, [start])
    return found


def test_no_part_imports_another_round_a_loop():
    edges, _ = _graph()
    assert edges, "no imports read: the reader is broken"
    assert _cycles(edges) == []


def test_no_part_imports_a_private_name_of_another():
    assert _graph()[1] == []


REPORT = PACKAGE / "report"
# What report/ must not call: saving and recording are actions, loading obligations and what
# is known of them is the gathering the commands do (report/ renders what it is given).
NOT_RENDERING = ("record", "record_decisions", "load_obligations", "load_splits", "known_of_files",
                 "default_proof_files")


def _diagnose_imports(modules) -> list:
    """``(module, imported module)`` of every import of diagnose/ in ``modules``, ``(path,
    source or None)`` pairs: absolute, relative (``..diagnose``) or the package itself."""
    return [(str(p.relative_to(PACKAGE)), ".".join(t)) for p, src in modules
            for t, _ in _imports(p, src) if _part(t) == "diagnose"]


def _not_rendering(modules) -> list:
    """``(module, imported module, name)`` of every saving, recording or loading name imported."""
    return [(str(p.relative_to(PACKAGE)), ".".join(t), n) for p, src in modules
            for t, names in _imports(p, src) for n in names
            if n.startswith("save_") or n in NOT_RENDERING]


def test_report_imports_nothing_of_diagnose():
    """report/ renders the diagnosis and the sweep from the result and summary it is given
    (the sweep's outcomes come with the result): no module of it imports diagnose/."""
    modules = [(p, None) for p in sorted(REPORT.glob("*.py"))]
    assert len(modules) > 5, "report/ not found: the check reads nothing"
    assert _diagnose_imports(modules) == []


def test_report_only_renders():
    """report/ renders what a part gives it: it saves nothing and records nothing (the
    commands and the parts write counterexamples and record decisions), and loads no
    obligations (the commands gather what the invariants page is rendered from)."""
    edges, _ = _graph()
    assert "report" in edges and "diagnose" not in edges["report"]
    assert _not_rendering([(p, None) for p in sorted(REPORT.glob("*.py"))]) == []


def test_the_check_can_fail():
    """The cycle finder and the private-name reader see what they must."""
    assert _cycles({"a": {"b"}, "b": {"c"}, "c": {"a"}}) == [["a", "b", "c", "a"]]
    assert _cycles({"a": {"b"}, "b": set()}) == []
    src = PACKAGE / "commands" / "split.py"
    assert (["report", "split"], ["interval_text", "table", "write_json"]) in list(_imports(src))


def test_the_report_checks_can_fail():
    """An import of diagnose/ added back to report/, in any spelling, is found; so is a
    saving or loading name."""
    here = REPORT / "sweep.py"
    for source, target in [("from ..diagnose.sweep import OUTCOMES, summary\n", "diagnose.sweep"),
                           ("from ..diagnose import core\n", "diagnose"),
                           ("from .. import diagnose\n", "diagnose"),
                           ("def f():\n    from navfn_smt.diagnose.sweep import summary\n", "diagnose.sweep"),
                           ("import navfn_smt.diagnose.walk\n", "diagnose.walk")]:
        assert _diagnose_imports([(here, source)]) == [("report/sweep.py", target)], source
    assert _diagnose_imports([(here, "from ..diagnose_notes import x\nfrom .diagnose import y\n")]) == []
    assert _not_rendering([(here, "from ..search.counterexamples import save_counterexample\n")]) == [
        ("report/sweep.py", "search.counterexamples", "save_counterexample")]
    assert _not_rendering([(here, "def f():\n    from ..smt.obligation import load_obligations\n")]) == [
        ("report/sweep.py", "smt.obligation", "load_obligations")]
