"""The package's structure, read from its imports (every import, at module level or inside a
function): no two parts (the folders and top-level modules of ``src/navfn_smt``) import each
other, directly or round a loop; no two files either (but the command layer, ``commands/`` and
``cli.py``, which may import anything lazily); and no file imports a private name (``_x``) of
another, nor reads one as an attribute of a module it imports."""

from __future__ import annotations

import ast
from pathlib import Path

PACKAGE = Path(__file__).resolve().parent.parent / "src" / "navfn_smt"


def _module_name(path: Path) -> list[str]:
    rel = path.relative_to(PACKAGE).with_suffix("")
    parts = list(rel.parts)
    return parts[:-1] if parts[-1] == "__init__" else parts


def _from_target(node: ast.ImportFrom, path: Path):
    """The module parts a ``from ... import`` in ``path`` imports from (None: not the package)."""
    here = _module_name(path)
    package = here if path.name == "__init__.py" else here[:-1]
    if node.level:
        base = package[:len(package) - (node.level - 1)] if node.level > 1 else package
        return base + (node.module.split(".") if node.module else [])
    if node.module and node.module.split(".")[0] == "navfn_smt":
        return node.module.split(".")[1:]
    return None


def _imports(path: Path, source: str | None = None):
    """``(target module parts, names)`` of every import of the package itself in ``path``
    (read from ``source`` when given: a module as it would be at that place)."""
    text = path.read_text(encoding="utf-8") if source is None else source
    for node in ast.walk(ast.parse(text)):
        if isinstance(node, ast.ImportFrom):
            target = _from_target(node, path)
            if target is None:
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


# ---------------------------------------------------------------------------- files
MODULES = {tuple(_module_name(p)): p for p in PACKAGE.rglob("*.py")}
# the command layer may import every part, lazily: its imports are not edges of the file graph
COMMAND_LAYER = ("commands/", "cli.py")
def _rel(parts: tuple) -> str:
    return str(MODULES[parts].relative_to(PACKAGE))


def _module_of(parts) -> tuple:
    """The module (a file) an import of ``parts`` names: the longest prefix of it that is a
    module of the package (``from .pkg import name``: ``pkg/__init__.py`` when ``name`` is not
    a submodule; ``()`` is the package's own ``__init__.py``)."""
    parts = tuple(parts)
    while parts not in MODULES:
        parts = parts[:-1]
    return parts


def _file_imports(path: Path, source: str | None = None) -> set:
    """The modules (parts) ``path`` imports anywhere in it: ``from pkg import name`` imports the
    submodule ``pkg.name`` when there is one, ``pkg`` itself otherwise."""
    out = set()
    for target, names in _imports(path, source):
        subs = [tuple(target) + (n,) for n in names]
        out |= {s if s in MODULES else _module_of(target) for s in subs} if names else {_module_of(target)}
    return out


def _file_graph(sources: dict | None = None) -> dict:
    """``{file: {file it imports}}`` over ``src/navfn_smt`` (paths relative to it), the command
    layer's imports left out; ``sources``: ``{relative path: text}`` read instead of the files."""
    sources = sources or {}
    edges: dict = {}
    for parts, path in sorted(MODULES.items()):
        me = _rel(parts)
        if me.startswith(COMMAND_LAYER):
            continue
        for target in _file_imports(path, sources.get(me)):
            if target != parts:
                edges.setdefault(me, set()).add(_rel(target))
    return edges


def _file_cycles(edges: dict) -> list:
    """One cycle (``[a, b, ..., a]``) through each strongly connected component of ``edges``
    of more than one file: none when the graph has no cycle (linear in its size, unlike
    :func:`_cycles`, which lists every cycle)."""
    index: dict = {}
    low: dict = {}
    stack: list = []
    on_stack: set = set()
    components = []

    def connect(v) -> None:  # Tarjan's algorithm
        index[v] = low[v] = len(index)
        stack.append(v)
        on_stack.add(v)
        for w in sorted(edges.get(v, ())):
            if w not in index:
                connect(w)
                low[v] = min(low[v], low[w])
            elif w in on_stack:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = set()
            while True:
                w = stack.pop()
                on_stack.discard(w)
                comp.add(w)
                if w == v:
                    break
            if len(comp) > 1:
                components.append(comp)

    for v in sorted(edges):
        if v not in index:
            connect(v)
    cycles = []
    for comp in components:  # the shortest way round from its first file, inside the component
        start = min(comp)
        came = {start: None}
        frontier = [start]
        while not any(start in edges.get(v, ()) for v in frontier):  # breadth first
            nxt = []
            for v in frontier:
                for w in sorted(edges.get(v, ())):
                    if w in comp and w not in came:
                        came[w] = v
                        nxt.append(w)
            frontier = nxt
        last, way = min(v for v in frontier if start in edges.get(v, ())), []
        while last is not None:
            way.append(last)
            last = came[last]
        cycles.append(way[::-1] + [start])
    return sorted(cycles)


def _private_uses(path: Path, source: str | None = None) -> list:
    """``(file, module, name)`` of every private name ``path`` takes from another module of the
    package: ``from module import _name``, or ``module._name`` of a module it imported (``from .
    import bounded as B``, ``import navfn_smt.x as y``).  Between a package's ``__init__.py``
    and its own modules a private name may pass."""
    me = tuple(_module_name(path))
    text = path.read_text(encoding="utf-8") if source is None else source
    tree = ast.parse(text)
    bound: dict = {}  # local name -> module parts
    found = []

    def private(name: str) -> bool:
        return name.startswith("_") and not name.startswith("__")

    def own_package(home: tuple) -> bool:
        init_of_me = path.name == "__init__.py"
        return (home == me[:-1] and not init_of_me) or (init_of_me and home[:-1] == me)

    def add(home: tuple, name: str) -> None:
        if home != me and not own_package(home):
            found.append((str(path.relative_to(PACKAGE)), ".".join(home), name))

    for node in ast.walk(tree):
        if isinstance(node, ast.ImportFrom):
            target = _from_target(node, path)
            if target is None:
                continue
            for a in node.names:
                sub = tuple(target) + (a.name,)
                if sub in MODULES:
                    bound[a.asname or a.name] = sub
                elif private(a.name):
                    add(_module_of(target), a.name)
        elif isinstance(node, ast.Import):
            for a in node.names:
                parts = tuple(a.name.split("."))
                if parts[0] == "navfn_smt" and a.asname and parts[1:] in MODULES:
                    bound[a.asname] = parts[1:]
    for node in ast.walk(tree):
        if (isinstance(node, ast.Attribute) and isinstance(node.value, ast.Name) and node.value.id in bound
                and private(node.attr)):
            add(bound[node.value.id], node.attr)
    return found


def _private_imports(sources: dict | None = None) -> list:
    sources = sources or {}
    return sorted({u for parts, path in MODULES.items() for u in _private_uses(path, sources.get(_rel(parts)))})


def test_no_file_imports_another_round_a_loop():
    """No two files import each other, directly or round a loop, counting the imports inside
    functions (kept there for start-up time: z3, numba, distributed): a piece both need lives
    in the lower one (the command layer, which imports every part, is left out)."""
    edges = _file_graph()
    assert sum(map(len, edges.values())) > 300, "no imports read: the reader is broken"
    cycles = _file_cycles(edges)
    assert cycles == [], "files importing each other round a loop:\n" + "\n".join(" -> ".join(c) for c in cycles)


def test_no_file_imports_a_private_name_of_another():
    """A name two files share is public in its home module (``from .runner import _domain``,
    ``B._interior`` are not)."""
    assert _private_imports() == []


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


def test_the_file_checks_can_fail():
    """A cycle between two files made by an import inside a function is found, and named by
    its files; one through the command layer is not; a private name taken by import or as an
    attribute of an imported module is found, in any spelling."""
    assert _file_cycles({"a.py": {"b.py"}, "b.py": {"c.py"}, "c.py": {"a.py", "d.py"}, "d.py": set()}) == [
        ["a.py", "b.py", "c.py", "a.py"]]
    assert _file_cycles({"a.py": {"b.py"}, "b.py": {"c.py"}, "c.py": set()}) == []
    split = PACKAGE / "smt" / "split.py"
    injected = {"smt/split.py": split.read_text(encoding="utf-8") + "\n\ndef f():\n    from .runner import run\n"}
    assert ["smt/runner.py", "smt/split.py", "smt/runner.py"] in _file_cycles(_file_graph(injected))
    assert ("smt", "runner") in _file_imports(split, "from navfn_smt.smt import runner\n")
    assert _file_imports(split, "from . import checking, runner\n") == {("smt", "checking"), ("smt", "runner")}
    assert _file_imports(split, "from ..proofs import PREDICATES\n") == {("proofs",)}
    through_commands = {"smt/runner.py": "from ..commands import prove\n"}  # commands/prove.py imports it
    assert "commands/prove.py" in _file_graph(through_commands)["smt/runner.py"]
    assert not any("commands/prove.py" in c for c in _file_cycles(_file_graph(through_commands)))
    here = PACKAGE / "check" / "certificate.py"
    for source in ("def f():\n    from .runner import _domain\n", "from navfn_smt.check.runner import _domain\n",
                   "from . import runner as R\nR._domain('fp32')\n", "import navfn_smt.check.runner as R\nR._domain\n",
                   "from navfn_smt.check import runner\nrunner._domain\n"):
        assert _private_uses(here, source) == [("check/certificate.py", "check.runner", "_domain")], source
    assert _private_uses(here, "from .runner import __doc__, domain\nimport json\njson._x\n") == []
    assert ("check/certificate.py", "check.runner", "_domain") in _private_imports(
        {"check/certificate.py": here.read_text(encoding="utf-8") + "\nfrom .runner import _domain\n"})


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
