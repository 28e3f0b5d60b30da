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


def _imports(path: Path):
    """``(target module parts, names)`` of every import of the package itself in ``path``."""
    here = _module_name(path)
    package = here if path.name == "__init__.py" else here[:-1]
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
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


def test_report_only_renders():
    """report/ renders what a part gives it: it imports nothing of diagnose/ (the sweep's
    summary and outcomes come with the result), and saves nothing (the commands and the
    parts write counterexamples and record decisions)."""
    edges, _ = _graph()
    assert "report" in edges and "diagnose" not in edges["report"]
    saving = [(str(p.relative_to(PACKAGE)), ".".join(t), n) for p in sorted((PACKAGE / "report").glob("*.py"))
              for t, names in _imports(p) for n in names
              if n.startswith("save_") or n in ("record", "record_decisions")]
    assert saving == []


def test_the_check_can_fail():
    """The cycle finder and the private-name reader see what they must."""
    assert _cycles({"a": {"b"}, "b": {"c"}, "c": {"a"}}) == [["a", "b", "c", "a"]]
    assert _cycles({"a": {"b"}, "b": set()}) == []
    src = PACKAGE / "commands" / "split.py"
    assert (["report", "split"], ["interval_text", "table", "write_json"]) in list(_imports(src))
