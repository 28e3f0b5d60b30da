"""The code hash of a certificate is of the code's meaning: editing a docstring, a comment or
the layout of the sources it covers leaves it (and the recorded certificates) as it is; editing
a comparison, a constant or a frozenset it reads changes it."""

import inspect
import textwrap
from pathlib import Path

from navfn_smt.check import bounded as B
from navfn_smt.check import certificate as C

KERNELS = Path(C.__file__).resolve().parents[1] / "spec" / "kernels.py"


def _edit(text: str, old: str, new: str) -> str:
    assert old in text, old
    return text.replace(old, new, 1)


def test_kernels_docstrings_comments_and_layout_are_not_its_meaning():
    text = KERNELS.read_text(encoding="utf-8")
    same = C.meaning_of(text)
    first_doc = "Candidate potential of a passable cell (the arithmetic of ``updateCell``)."
    assert C.meaning_of(_edit(text, first_doc, "The candidate potential of a cell.")) == same
    assert C.meaning_of(_edit(text, "The numeric heart of NavFn", "The heart of NavFn")) == same  # the module's
    comment = "    zero = D.f32const(0.0)\n"
    assert C.meaning_of(_edit(text, comment, "    # the float zero\n\n" + comment)) == same
    assert C.meaning_of(_edit(text, comment, "    zero = D.f32const( 0.0 )  # zero\n")) == same


def test_kernels_comparisons_and_constants_are_its_meaning():
    text = KERNELS.read_text(encoding="utf-8")
    same = C.meaning_of(text)
    assert C.meaning_of(_edit(text, "tc = D.ite(D.lt(l, r), l, r)", "tc = D.ite(D.le(l, r), l, r)")) != same
    assert C.meaning_of(_edit(text, "zero = D.f32const(0.0)", "zero = D.f32const(1.0)")) != same
    assert C.meaning_of(_edit(text, '"quadratic"', '"planar"')) != same  # a string that is not a docstring


def test_a_bounded_function_is_hashed_by_its_meaning():
    src = inspect.getsource(B.flippable)
    same = C.meaning_of(src)
    assert C.meaning_of(_edit(src, "How many of a path's first branches", "How many branches")) == same
    assert C.meaning_of(_edit(src, "        return len(pc)\n", "        # all of them\n\n        return len(pc)\n")) == same
    assert C.meaning_of(textwrap.indent(src, "    ")) == same  # as a method's source: dedented
    assert C.meaning_of(_edit(src, "lo < COST_NEUTRAL", "lo <= COST_NEUTRAL")) != same
    assert C.meaning_of(_edit(src, "start_certain is None", "start_certain is False")) != same


def test_a_body_of_a_docstring_alone_is_pass():
    assert C.meaning_of('def f():\n    """Nothing."""\n') == C.meaning_of("def f():\n    pass\n")
    assert C.meaning_of('def f():\n    """Nothing."""\n') != C.meaning_of("def f():\n    return\n")
    assert C.meaning_of('def f():\n    """Doc."""\n    "data"\n') != C.meaning_of("def f():\n    pass\n")


def test_the_code_hash_is_stable_and_covers_the_frozensets(monkeypatch):
    full, alone = C.code_hash(), C.code_hash(["start-reached"])
    assert C.code_hash() == full and C.code_hash(["start-reached"]) == alone and alone != full
    monkeypatch.setattr(B, "PROPAGATION_ONLY", B.PROPAGATION_ONLY | {"another"})
    assert not B.reads_path(["start-reached"])
    assert C.code_hash(["start-reached"]) != alone  # PROPAGATION_ONLY is hashed for start-reached alone
    assert C.code_hash() == full  # ... and not when calcPath's result is read


def test_the_code_hash_ignores_a_docstring_of_a_hashed_function(monkeypatch):
    assert "flippable" in C.FUNCTIONS
    before = C.code_hash()
    getsource = inspect.getsource
    src = getsource(B.flippable)

    def patched(text):
        monkeypatch.setattr(inspect, "getsource", lambda obj: text if obj is B.flippable else getsource(obj))
        return C.code_hash()

    assert patched(_edit(src, "How many of a path's first branches", "How many branches")) == before
    assert patched(_edit(src, "lo < COST_NEUTRAL", "lo <= COST_NEUTRAL")) != before
