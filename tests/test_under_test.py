"""The planner under test: one value, named the same way by every command (--variant, --target
NAME, --oracle DIR), read from a build's build.json when it comes from a build, and carried to
the spec that plans."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from navfn_smt.spec.fix import FIX
from navfn_smt.cli import main
from navfn_smt.errors import NavfnInputError
from navfn_smt.spec.arithmetic import KNOWN, X86_64
from navfn_smt.under_test import ORIGINAL, PlannerUnderTest

DATA = Path(__file__).parent / "data"
# the start is a lethal cell the wave never reaches: calcPath's (int) of an out-of-range float gives
# INT_MIN on x86-64, so no path; arm64's conversion saturates and the fallback walks (docs/toolchains.md)
LETHAL_START = DATA / "counterexamples" / "int-conversion-astar-4x3"


def _plan(capsys, *extra) -> tuple[int, dict]:
    rc = main(["plan", str(LETHAL_START), "--start", "1", "1", "--goal", "2", "1", "--json", *extra])
    return rc, json.loads(capsys.readouterr().out)


def _fake_build(tmp_path: Path, target: str = "aarch64", distribution: str = "jazzy", arithmetic=None) -> Path:
    """A build folder with no programs: what the planner is read from (build.json) and nothing else."""
    folder = tmp_path / f"build-{target}"
    folder.mkdir()
    entry = KNOWN.get(target, X86_64).as_dict() if arithmetic is None else arithmetic
    (folder / "build.json").write_text(json.dumps({"distribution": distribution, "target": target,
                                                   "programs": [], "arithmetic": entry}))
    return folder


@pytest.mark.parametrize("backend", ["reference", "jit"])
def test_plan_names_the_arithmetic_and_plans_in_it(backend, capsys):
    rc, doc = _plan(capsys, "--backend", backend)
    assert rc == 1 and doc["path"] == [] and doc["planner"] == {"variant": "original", "target": "x86-64",
                                                                "arithmetic": "x86-64"}
    rc, doc = _plan(capsys, "--backend", backend, "--target", "aarch64")
    assert rc == 0 and doc["path"][0] == [1.0, 1.0] and doc["planner"]["arithmetic"] == "aarch64"
    rc, doc = _plan(capsys, "--backend", backend, "--target", "x86-64-v3")  # fuses, but converts as x86-64
    assert rc == 1 and doc["path"] == []


def test_a_build_folder_gives_the_distribution_target_and_arithmetic(tmp_path, capsys):
    folder = _fake_build(tmp_path)
    p = PlannerUnderTest.of_build(folder)
    assert (p.arithmetic, p.distribution, p.target, p.build) == (KNOWN["aarch64"], "jazzy", "aarch64", folder)
    assert p.label == "original, the C++ of jazzy for aarch64, aarch64 arithmetic"
    rc, doc = _plan(capsys, "--oracle", str(folder))
    assert rc == 0 and doc["planner"] == {"variant": "original", "target": "aarch64", "arithmetic": "aarch64",
                                          "distribution": "jazzy", "build": str(folder)}
    x86 = PlannerUnderTest.of_build(_fake_build(tmp_path, "x86-64", "rolling"), FIX)
    assert x86.variant == "fixed" and x86.arithmetic == X86_64 and x86.distribution == "rolling"


def test_what_the_spec_cannot_compute_is_refused_naming_why(tmp_path):
    fixed = PlannerUnderTest.of_build(_fake_build(tmp_path), FIX)  # the fix computes in any arithmetic
    assert (fixed.variant, fixed.arithmetic.name) == ("fixed", "aarch64")
    with pytest.raises(NavfnInputError, match="--distro humble: .* a build of jazzy"):
        PlannerUnderTest.of_build(tmp_path / "build-aarch64", distribution="humble")
    odd = _fake_build(tmp_path, "riscv64", arithmetic={"fused": [], "conversion": "indefinite",
                                                       "unexpressible": ["a fused line no site names"]})
    p = PlannerUnderTest.of_build(odd)  # the layers may still be compared: refused only when NavFn's is used
    with pytest.raises(NavfnInputError, match="a fused line no site names"):
        p.backend("jit")
    with pytest.raises(NavfnInputError, match="give --oracle DIR"):
        ORIGINAL.plugin_arithmetic()
    with pytest.raises(NavfnInputError, match="no such arithmetic"):
        PlannerUnderTest.of_target("sparc")


@pytest.mark.parametrize("args, says", [
    (["plan", str(LETHAL_START), "--start", "1", "1", "--goal", "2", "1", "--target", "sparc"], "no such arithmetic"),
    (["plan", str(LETHAL_START), "--start", "1", "1", "--goal", "2", "1", "--target", "aarch64", "--oracle", "{b}"],
     "exclude each other"),
    (["difftest", "--target", "aarch64", "--oracle", "{b}"], "exclude each other"),
    (["suite", "record", "{tmp}", "--target", "aarch64", "--oracle", "{b}"], "exclude each other"),
])
def test_contradicting_options_are_one_line(args, says, tmp_path, capsys):
    b = _fake_build(tmp_path)
    assert main([a.format(b=b, tmp=tmp_path) for a in args]) == 2
    err = capsys.readouterr().err
    assert says in err and err.count("\n") == 1, err


def test_commands_make_the_planner_once_from_the_shared_options():
    """No command reads --variant or --target on its own to plan: each takes the planner from
    commands.common.planner_of (option checks aside), so every layer below gets one value."""
    commands = Path(__file__).parents[1] / "src" / "navfn_smt" / "commands"
    for f in commands.glob("*.py"):
        text = f.read_text()
        if f.name in ("common.py", "oracle.py", "ci.py", "plugin_check.py"):  # build toolchains; both variants
            continue
        if f.name == "fixes.py":  # every candidate in several arithmetics: commands.common.planners_of
            assert "planners_of(args" in text and "PlannerUnderTest" not in text
            continue
        planning = [line for line in text.splitlines() if ("get_backend(" in line or "variant=args." in line)]
        assert planning == [], (f.name, planning)
        if "--variant" in text or "planner_of" in text:
            assert "planner_of(args" in text, f.name


def test_a_build_without_layers_says_so_when_their_arithmetic_is_asked(tmp_path):
    p = PlannerUnderTest.of_build(_fake_build(tmp_path))
    with pytest.raises(NavfnInputError, match="has no costmap-layers .it has no program"):
        p.layers_arithmetic()
    with pytest.raises(NavfnInputError, match="has no navfn-plugin"):
        p.plugin_arithmetic()


def test_the_float32_semantics_of_each_arithmetic_is_the_symbolic_domains_name_for_it():
    """PlannerUnderTest.fp32_semantics names a build's arithmetic as smt.domains.FP32_SEMANTICS
    does (check and split look the domain up by it); an arithmetic the domains do not have is a
    clear error."""
    from navfn_smt.errors import NavfnInputError
    from navfn_smt.smt.domains import FP32_SEMANTICS
    from navfn_smt.spec.arithmetic import KNOWN, Arithmetic
    from navfn_smt.under_test import PlannerUnderTest

    for target, arith in KNOWN.items():
        semantics = PlannerUnderTest.of_target(target).fp32_semantics()
        assert FP32_SEMANTICS[semantics] == arith
    assert sorted(PlannerUnderTest.of_target(t).fp32_semantics() for t in KNOWN) == sorted(FP32_SEMANTICS)
    odd = PlannerUnderTest(arithmetic=Arithmetic(frozenset({"planar"})))
    with pytest.raises(NavfnInputError, match="none the symbolic encodings compute in"):
        odd.fp32_semantics()
