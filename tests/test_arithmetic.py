"""The arithmetic of a build as the oracle finds it: the object code's fused multiply-adds traced
to the spec's sites, the conversion probe's answers matched to the spec's converters, and the
checkers of both fed evidence that is wrong."""

from __future__ import annotations

import subprocess
from fractions import Fraction

import pytest

from navfn_smt.cli import main
from navfn_smt.errors import NavfnInputError
from navfn_smt.oracle.arithmetic import (EXPECTED, PROBE_INPUTS, conversion, fused_lines, fused_sites, of_build,
                                         plugin_of_build, plugin_record)
from navfn_smt.oracle.build import distribution, git_commit
from navfn_smt.oracle.targets import toolchain
from navfn_smt.spec.arithmetic import KNOWN, SITES, X86_64, Arithmetic, PluginArithmetic, site_of_line
from navfn_smt.spec.constants import COST_FACTOR, COST_NEUTRAL
from navfn_smt.spec.numeric import c_fma

# a navfn.cpp stand-in: one line per site as Nav2 writes it (the patterns of SITES), twice
SOURCE = """\
v = COST_NEUTRAL + COST_FACTOR * v;
v = COST_NEUTRAL + COST_FACTOR * v;
const float v = -0.2301 * div * div + 0.5307 * div + 0.7040;
pot = ta + hf * v;
const float v = -0.2301 * div * div + 0.5307 * div + 0.7040;
pot = ta + hf * v;
float x1 = (1.0 - dx) * gradx[stc] + dx * gradx[stc + 1];
float x = (1.0 - dy) * x1 + dy * x2;
dx += x * ss;
dy += y * ss;
float other = a * b + c;
"""


def _asm(lines, file="navfn.cpp", insn="fmadd\td0, d1, d2, d3"):
    body = [f'\t.file 1 "{file}"', '\t.file 2 "/usr/include/c++/12/cmath"']
    for n in lines:
        body += [f"\t.loc 1 {n} 7 view .LVU1", "\tfmul\td0, d1, d2", f"\t{insn}"]
    body += ["\t.loc 2 40 3", "\tfmadd\ts0, s1, s2, s3"]  # a library header's line is not navfn.cpp's
    return "\n".join(body) + "\n"


@pytest.mark.fast
def test_fused_lines_are_traced_to_their_source_lines_in_either_instruction_set():
    assert fused_lines(_asm([3, 9]), "navfn.cpp") == [3, 9]
    assert fused_lines(_asm([4], insn="vfmadd132ss\t%xmm1, %xmm2, %xmm0"), "navfn.cpp") == [4]
    assert fused_lines(_asm([4], insn="fmla\tv0.4s, v1.4s, v2.4s"), "navfn.cpp") == [4]
    assert fused_lines(_asm([4], insn="fmul\td0, d1, d2"), "navfn.cpp") == []  # not a multiply-add
    assert fused_lines(_asm([4]), "other.cpp") == []


@pytest.mark.fast
def test_sites_fused_on_every_line_are_the_arithmetic(tmp_path):
    src = tmp_path / "navfn.cpp"
    src.write_text(SOURCE)
    fused, at, problems = fused_sites(src, [1, 2, 3, 5, 4, 6, 7, 8, 9, 10])
    assert problems == [] and fused == set(SITES)
    assert at["planar"] == [4, 6] and at["path_step"] == [9, 10]
    assert fused_sites(src, []) == (set(), {}, [])


@pytest.mark.fast
def test_a_fused_line_the_spec_has_no_site_for_or_a_site_fused_in_part_is_unexpressible(tmp_path):
    src = tmp_path / "navfn.cpp"
    src.write_text(SOURCE)
    fused, _, problems = fused_sites(src, [11])
    assert fused == set() and problems and "navfn.cpp:11" in problems[0] and "a * b + c" in problems[0]
    fused, _, problems = fused_sites(src, [4])  # the planar site of one updateCell only
    assert "planar" not in fused and "planar fused on navfn.cpp lines [4] but not on [6]" in problems[0]


PLANNER_CPP = """void NavfnPlanner::mapToWorld(double mx, double my, double & wx, double & wy)
{
  wx = costmap_->getOriginX() + mx * costmap_->getResolution();
  wy = costmap_->getOriginY() + my * costmap_->getResolution();
  double other = a * b + c;
        double sdist = squared_distance(p, goal);
      squared_distance(last_pose.pose, second_to_last_pose.pose) >
      squared_distance(goal, second_to_last_pose.pose))
    if (squared_distance(last_pose.pose, goal) < 1e-6) {
}
"""
CALLS = {"tolerance": 6, "smooth_last": 7, "smooth_goal": 8, "same_position": 9}  # their lines above
PLANNER_HPP = "    double dx = p1.x - p2.x;\n    double dy = p1.y - p2.y;\n    return dx * dx + dy * dy;\n"
GEOMETRY = """  q.x = sr * cp * cy - cr * sp * sy;
  q.y = cr * sp * cy + sr * cp * sy;
  q.z = cr * cp * sy - sr * sp * cy;
  q.w = cr * cp * cy + sr * sp * sy;
"""


FILES = {"navfn_planner.cpp": PLANNER_CPP, "navfn_planner.hpp": PLANNER_HPP, "geometry_utils.hpp": GEOMETRY,
         "navfn.cpp": SOURCE}


def _plugin_asm(tmp_path, fused) -> str:
    """Assembly whose fused instructions come from ``fused``: (file name, line[, instruction[, call
    line]]) items."""
    body = []
    for k, (name, text) in enumerate(FILES.items(), start=1):
        (tmp_path / name).write_text(text)
        body.append(f'\t.file {k} "{tmp_path}" "{name}"')
    number = {name: k for k, name in enumerate(FILES, start=1)}
    for item in fused:
        name, line, insn = item[:3] if len(item) >= 3 else (*item, "fmadd\td0, d1, d2, d3")
        body += [f"\t.loc {number[name]} {line} 3", f"\t{insn}"]
    return "\n".join(body) + "\n"


def _plugin_dis(tmp_path, items) -> str:
    """``objdump -d -l --inlines`` output of the same items: each instruction after its source line
    and, for an item with a call line, the line of navfn_planner.cpp it is inlined at."""
    body = ["0000000000000000 <_ZN18nav2_navfn_planner12NavfnPlanner8makePlanE>:"]
    for k, item in enumerate(items):
        name, line, insn = item[:3] if len(item) >= 3 else (*item, "fmadd\td0, d1, d2, d3")
        body.append(f"{tmp_path}/{name}:{line}")
        if len(item) > 3:
            body.append(f"inlined by {tmp_path}/navfn_planner.cpp:{item[3]} (_ZN18nav2_navfn_planner12NavfnPlanner)")
        body.append(f"    {4 * k:x}:\t{insn}")
    return "\n".join(body) + "\n"


def _record(tmp_path, items) -> dict:
    return plugin_record(_plugin_asm(tmp_path, items), lambda: _plugin_dis(tmp_path, items))


def _square(fused: str, x86: bool = False, call: str = "tolerance") -> list:
    """One copy of ``dx * dx + dy * dy`` (navfn_planner.hpp lines 1 to 3) inlined at the call
    ``call`` that fuses the square of ``fused``, as arm64's or x86-64-v3's code (AT&T) does it."""
    other = "dy" if fused == "dx" else "dx"
    line, at = {"dx": 1, "dy": 2}, CALLS[call]
    if x86:
        insns = [(line[fused], "vsubsd\t%xmm0, %xmm2, %xmm4"), (line[other], "vsubsd\t%xmm1, %xmm3, %xmm5"),
                 (3, "vmulsd\t%xmm5, %xmm5, %xmm5"), (3, "vfmadd132sd\t%xmm4, %xmm5, %xmm4")]
    else:
        insns = [(line[fused], "fsub\td4, d6, d0"), (line[other], "fsub\td5, d3, d1"), (3, "fmul\td5, d5, d5"),
                 (3, "fmadd\td4, d4, d4, d5")]
    return [("navfn_planner.hpp", n, insn, at) for n, insn in insns]


@pytest.mark.fast
def test_the_plugins_fused_lines_are_its_sites_wherever_they_are_inlined_from(tmp_path):
    both = [("navfn_planner.cpp", 3), ("navfn_planner.cpp", 4), *_square("dx"),
            *_square("dx", x86=True, call="smooth_last"), ("navfn.cpp", 4)]
    doc = _record(tmp_path, both + [("geometry_utils.hpp", 1), ("geometry_utils.hpp", 2)])
    assert doc["unexpressible"] == [] and doc["fused"] == ["map_to_world", "squared_distance", "yaw_quaternion"]
    assert doc["sites"]["map_to_world"] == ["navfn_planner.cpp:3", "navfn_planner.cpp:4"]
    assert doc["squared_distance_orders"] == {"smooth_last": "dx", "tolerance": "dx"}
    assert doc["fused_instructions"] == 6  # navfn.cpp's own line is NavFn's arithmetic, found apart

    def untouched():
        raise AssertionError("the disassembly is read only when squared_distance fuses")
    assert plugin_record(_plugin_asm(tmp_path, []), untouched) == {
        "fused": [], "squared_distance_orders": {}, "fused_instructions": 0, "sites": {}, "unexpressible": []}


@pytest.mark.fast
@pytest.mark.parametrize("x86", [False, True], ids=["arm64", "x86-64-v3"])
def test_each_call_of_squared_distance_computes_the_square_its_copy_fused(tmp_path, x86):
    """GCC fuses fma(dy, dy, dx * dx) in the tolerance search's copy of Jazzy's and Humble's
    squared_distance and fma(dx, dx, dy * dy) in the smoothing's: found per call, and the model
    computes each call as found."""
    from navfn_smt.nav2.plugin import Pose, squared_distance

    copies = [*_square("dy", x86), *_square("dx", x86, "smooth_last"), *_square("dx", x86, "same_position")]
    doc = _record(tmp_path, copies)
    assert doc["unexpressible"] == [] and "squared_distance" in doc["fused"]
    assert doc["squared_distance_orders"] == {"same_position": "dx", "smooth_last": "dx", "tolerance": "dy"}
    found = plugin_of_build({"arithmetic": KNOWN["aarch64"].as_dict(), "plugin_arithmetic": doc})[0]
    assert found.dy_first == {"tolerance"} and "fma(dy, dy, dx * dx) in tolerance" in found.name
    a, b = Pose(0.02, 0.36), Pose(0.0, 0.0)  # the two orders round differently here
    assert squared_distance(a, b, "tolerance", found) == c_fma(0.36, 0.36, 0.02 * 0.02)
    assert squared_distance(a, b, "smooth_last", found) == c_fma(0.02, 0.02, 0.36 * 0.36)
    assert c_fma(0.36, 0.36, 0.02 * 0.02) != c_fma(0.02, 0.02, 0.36 * 0.36)


@pytest.mark.fast
@pytest.mark.parametrize("x86", [False, True], ids=["arm64", "x86-64-v3"])
def test_copies_of_one_call_that_differ_or_a_call_the_model_does_not_make_are_unexpressible(tmp_path, x86):
    doc = _record(tmp_path, [*_square("dx", x86), *_square("dy", x86)])
    assert "squared_distance" not in doc["fused"]
    assert "call tolerance fused fma(dx, dx, dy * dy) in one inlined copy" in doc["unexpressible"][0]
    stray = [(n, line, insn, 5) for n, line, insn, _ in _square("dx", x86)]  # inlined at `other = a * b + c`
    doc = _record(tmp_path, stray)
    assert "navfn_planner.cpp:5, which is no call of it the plugin model makes" in doc["unexpressible"][0]
    untold = [*_square("dx", x86)[:3], ("navfn_planner.hpp", 3, "fmadd\td4, d4, d5, d5", 6)]  # not a square
    assert "could not be told" in _record(tmp_path, untold)["unexpressible"][0]


@pytest.mark.fast
def test_a_plugin_line_that_is_no_site_or_a_site_fused_in_part_is_unexpressible(tmp_path):
    doc = _record(tmp_path, [("navfn_planner.cpp", 5)])
    assert doc["fused"] == [] and "navfn_planner.cpp:5 fused `double other = a * b + c;`" in doc["unexpressible"][0]
    doc = _record(tmp_path, [("navfn_planner.cpp", 3)])
    assert "map_to_world fused on navfn_planner.cpp lines [3] but not on [4]" in doc["unexpressible"][0]
    bad = {"arithmetic": KNOWN["aarch64"].as_dict(), "plugin_arithmetic": doc}
    assert plugin_of_build(bad)[0] is None and "cannot express" in plugin_of_build(bad)[1]
    assert plugin_of_build({"arithmetic": KNOWN["aarch64"].as_dict()})[0] is None  # not recorded: built before
    good = {"arithmetic": KNOWN["aarch64"].as_dict(), "plugin_arithmetic": {"fused": ["map_to_world"]}}
    assert plugin_of_build(good)[0] == PluginArithmetic(KNOWN["aarch64"], frozenset({"map_to_world"}))


def test_the_plugin_calls_none_of_costmap2ds_fused_functions(nav2_src):
    """Costmap2D's own multiply-adds (mapToWorld, mapToWorldNoBounds, worldToMapEnforceBounds,
    updateOrigin) fuse on arm64 too, but neither the plugin of any distribution nor our driver calls
    them, so they are no sites of the plugin model."""
    import re

    from navfn_smt.oracle import build as B

    called = re.compile(r"(costmap_?\w*(->|\.)|Costmap2D::)(mapToWorld|mapToWorldNoBounds|worldToMapEnforceBounds|"
                        r"updateOrigin)\b")
    files = [B.HERE / "plugin_driver.cpp",
             *sorted(nav2_src.glob("*/nav2_navfn_planner/src/navfn_planner.cpp")),
             *sorted(nav2_src.glob("*/nav2_navfn_planner/include/nav2_navfn_planner/navfn_planner.hpp"))]
    assert len(files) == 11
    assert [f for f in files if called.search(f.read_text())] == []
    assert called.search("costmap_->mapToWorld(mx, my, wx, wy);")


@pytest.mark.fast
def test_the_probe_names_a_conversion_only_when_the_spec_computes_the_same_ints():
    assert conversion(EXPECTED["indefinite"]) == "indefinite"
    assert conversion(EXPECTED["saturating"]) == "saturating"
    wrong = list(EXPECTED["saturating"])
    wrong[0] = -2147483648  # NaN gives INT_MIN but the rest saturates: neither
    assert conversion(wrong) is None
    assert len(PROBE_INPUTS) == len(EXPECTED["indefinite"])


@pytest.mark.fast
def test_a_build_whose_arithmetic_is_unknown_or_unexpressible_is_never_compared():
    assert of_build({})[0] is None and "build it again" in of_build({})[1]
    bad = {"arithmetic": {**KNOWN["aarch64"].as_dict(), "unexpressible": ["navfn.cpp:11 fused ..."]}}
    assert of_build(bad)[0] is None and "cannot express" in of_build(bad)[1]
    assert of_build({"arithmetic": KNOWN["aarch64"].as_dict()}) == (KNOWN["aarch64"], None)


@pytest.mark.fast
def test_arithmetics_are_data_named_when_known():
    for name, a in KNOWN.items():
        assert a.name == name and Arithmetic.from_dict(a.as_dict()) == a
    assert Arithmetic(frozenset(), "saturating").name == "fused[none]-saturating"
    assert len({a.key for a in KNOWN.values()}) == len(KNOWN) and X86_64 == KNOWN["x86-64"]
    with pytest.raises(ValueError):
        Arithmetic(frozenset({"nowhere"}))
    with pytest.raises(ValueError):
        Arithmetic(conversion="rounding")
    assert site_of_line("pot = ta + hf * v;") == "planar" and site_of_line("pot = ta + hf;") is None
    # Humble names the quotient d, later versions div
    for line in ("float v = -0.2301 * d * d + 0.5307 * d + 0.7040;",
                 "const float v = -0.2301 * div * div + 0.5307 * div + 0.7040;"):
        assert site_of_line(line) == "quadratic"


@pytest.mark.fast
def test_the_cost_translation_gives_the_same_ints_fused_or_not():
    """setCostmap's ``COST_NEUTRAL + COST_FACTOR * v`` (double, then int) for every cost below
    253: the fused value (the exact sum rounded once) truncates as the twice-rounded one does,
    so the site is recorded but the spec's translation needs no fused form."""
    for v in range(253):
        fused = float(Fraction(COST_FACTOR) * v + COST_NEUTRAL)
        assert int(fused) == int(COST_NEUTRAL + COST_FACTOR * v), v


@pytest.mark.fast
@pytest.mark.parametrize("version, distro", [("1.1.20", "humble"), ("1.3.13", "jazzy"), ("1.4.2", "kilted"),
                                              ("1.5.1", "lyrical"), ("1.5.0", "rolling"), ("1.6.0", "rolling")])
def test_the_distribution_is_read_from_the_version(tmp_path, version, distro):
    pkg = tmp_path / "nav2_navfn_planner"
    pkg.mkdir()
    (pkg / "package.xml").write_text(f"<package><version>{version}</version></package>")
    assert distribution(tmp_path) == distro


@pytest.mark.fast
def test_the_git_commit_is_the_sources_own(tmp_path):
    repo = tmp_path / "repo"
    (repo / "inner").mkdir(parents=True)
    (repo / "inner" / "f").write_text("x")
    git = ["git", "-C", str(repo), "-c", "user.name=t", "-c", "user.email=t@t"]
    subprocess.run([*git, "init", "-q"], check=True)
    subprocess.run([*git, "add", "."], check=True)
    subprocess.run([*git, "commit", "-qm", "x"], check=True)
    head = subprocess.run([*git, "rev-parse", "HEAD"], capture_output=True, text=True).stdout.strip()
    assert git_commit(repo) == (head, None)
    commit, why = git_commit(repo / "inner")
    assert commit is None and "inside the git repository" in why
    assert git_commit(tmp_path) == (None, "not a git checkout")


@pytest.mark.fast
def test_toolchains_are_checked_before_anything_is_built(tmp_path, capsys):
    with pytest.raises(NavfnInputError, match="no such target"):
        toolchain("sparc")
    with pytest.raises(NavfnInputError, match="goes with --cxx"):
        toolchain(cxxflags="-O3")
    assert toolchain("x86-64-v3").all_flags == ["-std=c++17", "-O2", "-march=x86-64-v3"]
    with pytest.raises(NavfnInputError, match="not on PATH"):
        toolchain(cxx="no-such-g++").check()
    assert main(["oracle", "build", str(tmp_path), "--target", "sparc", "--out", str(tmp_path / "o")]) == 2
    err = capsys.readouterr().err
    assert "no such target" in err and err.count("\n") == 1 and not (tmp_path / "o").exists()


@pytest.mark.fast
def test_fused_instructions_of_a_library_are_traced_through_its_line_information():
    from navfn_smt.oracle.library import fused_lines_of_binary

    dump = """
0000000000001a40 <_ZN18nav2_navfn_planner5NavFn10updateCellEi>:
/src/nav2_navfn_planner/src/navfn.cpp:452
    1a40:\tfmul\td16, d2, d16
    1a44:\tfmadd\td2, d2, d16, d3
/src/nav2_navfn_planner/src/navfn.cpp:453 (discriminator 2)
    1a48:\tfmadd\ts0, s1, s2, s0
/usr/include/c++/12/cmath:40
    1a4c:\tfmadd\ts0, s1, s2, s0

0000000000001b00 <other>:
    1b00:\tvfmadd132ss %xmm1,%xmm2,%xmm0
"""
    assert fused_lines_of_binary(dump, "navfn.cpp") == ([452, 453], 1)


def _nearest(x: Fraction, bits: int) -> float:
    """The binary32 (bits 32) or binary64 value nearest the rational ``x``, ties to even."""
    import numpy as np

    t = np.float32 if bits == 32 else np.float64
    f = t(float(x))  # within an ulp of the nearest
    cands = [f, np.nextafter(f, t(np.inf)), np.nextafter(f, t(-np.inf))]
    best = min(cands, key=lambda v: (abs(Fraction(float(v)) - x), int(np.asarray(v).view(
        np.uint32 if bits == 32 else np.uint64)) & 1))
    return float(best)


@pytest.mark.fast
def test_the_concrete_fused_multiply_add_rounds_once():
    """``D.fma`` and ``D.fma64`` are the exact ``a * b + c`` rounded once (to float, to double),
    on random and on cancelling inputs; the unfused sum rounds twice and differs on some."""
    import random

    import numpy as np

    from navfn_smt.spec.numeric import CONCRETE as C, f32

    rng = random.Random(36)
    differs = 0
    for i in range(3000):
        a, b = f32(rng.uniform(-1e3, 1e3)), f32(rng.uniform(-1e3, 1e3))
        c = f32(-a * b) if i % 3 == 0 else f32(rng.uniform(-1e6, 1e6))  # cancelling: the residual shows
        exact = Fraction(a) * Fraction(b) + Fraction(c)
        assert C.fma(a, b, c) == _nearest(exact, 32), (a, b, c)
        differs += C.fma(a, b, c) != C.add(c, C.mul(a, b))
        a64, b64, c64 = rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1)
        assert C.fma64(a64, b64, c64) == _nearest(Fraction(a64) * Fraction(b64) + Fraction(c64), 64)
    assert differs > 500
    assert np.float32(C.fma(1.0000001, 1.0000001, -1.0000002)) != 0.0


@pytest.mark.fast
def test_the_concrete_domain_converts_as_its_arithmetic_says():
    from navfn_smt.spec.numeric import CONCRETE as C

    arm = C.with_arithmetic(KNOWN["aarch64"])
    assert [C.to_int32(v) for v in (3e9, -3e9, float("nan"), 7.9, -7.9)] == [-2**31, -2**31, -2**31, 7, -7]
    assert [arm.to_int32(v) for v in (3e9, -3e9, float("nan"), 7.9, -7.9)] == [2**31 - 1, -2**31, 0, 7, -7]
    assert C.arith is None and not C.fuses("planar") and arm.fuses("planar")
    assert not C.with_arithmetic(KNOWN["x86-64"]).fuses("planar")


@pytest.mark.fast
def test_a_kernel_is_stated_once_and_computes_in_each_arithmetic():
    """planar_wave in x86-64's and in arm64's arithmetic: the same code, values that differ
    where the fused ``ta + hf * v`` or quadratic rounds once."""
    import random

    from navfn_smt.spec import kernels as K
    from navfn_smt.spec.numeric import CONCRETE as C, f32

    arm = C.with_arithmetic(KNOWN["aarch64"])
    rng = random.Random(5)
    differ = 0
    for _ in range(2000):
        l, r, u, d = (f32(rng.uniform(0, 3000)) for _ in range(4))
        hf = f32(rng.randint(50, 253))
        differ += K.planar_wave(C, l, r, u, d, hf) != K.planar_wave(arm, l, r, u, d, hf)
    assert 0 < differ < 2000


# --------------------------------------------------------------------------- the costmap layers
MATH_CPP = """double distanceToLine(double pX, double pY, double x0, double y0, double x1, double y1)
{
  double A = pX - x0;
  double B = pY - y0;
  double C = x1 - x0;
  double D = y1 - y0;
  double dot = A * C + B * D;
  double len_sq = C * C + D * D;
    xx = x0 + param * C;
    yy = y0 + param * D;
  double other = a * b + c;
}
"""
LAYER_FILES = {"costmap_math.cpp": MATH_CPP,
               "inflation_layer.cpp": "        static_cast<unsigned int>(distance_cells * lut_precision + 0.5f));\n",
               "costmap_2d.cpp": "  } else if (wx > resolution_ * size_x_ + origin_x_) {\n",
               "fmaintrin.h": "  return (__m256)__builtin_ia32_vfmaddps256 ((__v8sf)__A, (__v8sf)__B,\n"}


def _distance_to_line_code(dot: str = "A", len_sq: str = "C") -> list:
    """arm64 code of distanceToLine (the lines of MATH_CPP) fusing the products named."""
    fused_dot = ("fmul\td6, d1, d3", "fmadd\td6, d0, d2, d6") if dot == "A" else ("fmul\td6, d0, d2",
                                                                                   "fmadd\td6, d1, d3, d6")
    fused_len = ("fmul\td7, d3, d3", "fmadd\td7, d2, d2, d7") if len_sq == "C" else ("fmul\td7, d2, d2",
                                                                                     "fmadd\td7, d3, d3, d7")
    return [("costmap_math.cpp", 3, "fsub\td0, d8, d4"), ("costmap_math.cpp", 4, "fsub\td1, d9, d5"),
            ("costmap_math.cpp", 5, "fsub\td2, d10, d4"), ("costmap_math.cpp", 6, "fsub\td3, d11, d5"),
            *(("costmap_math.cpp", 7, i) for i in fused_dot), *(("costmap_math.cpp", 8, i) for i in fused_len),
            ("costmap_math.cpp", 9, "fmadd\td12, d13, d2, d4"), ("costmap_math.cpp", 10, "fmadd\td14, d13, d3, d5")]


def _layers_dis(tmp_path, items, untraced: int = 0) -> str:
    for name, text in LAYER_FILES.items():
        (tmp_path / name).write_text(text)
    body = ["0000000000001000 <_Z14distanceToLinedddddd>:"]
    body += [f"    {4 * k:x}:\tfmadd\td0, d1, d2, d3" for k in range(untraced)]  # before any line
    for k, (name, line, insn) in enumerate(items):
        body += [f"{tmp_path}/{name}:{line}", f"    {0x100 + 4 * k:x}:\t{insn}"]
    return "\n".join(body) + "\n"


@pytest.mark.fast
def test_the_layers_fused_lines_are_their_sites_and_distance_to_lines_products_are_found(tmp_path):
    from navfn_smt.oracle.arithmetic import layers_of_build, layers_record
    from navfn_smt.spec.arithmetic import LayersArithmetic

    items = [*_distance_to_line_code(), ("inflation_layer.cpp", 1, "fmadd\ts0, s1, s2, s3"),
             ("costmap_2d.cpp", 1, "fmadd\td0, d1, d2, d3"), ("fmaintrin.h", 1, "fmla\tv0.4s, v1.4s, v2.4s")]
    doc = layers_record(_layers_dis(tmp_path, items))
    assert doc["unexpressible"] == [] and doc["fused"] == ["distance_to_line", "lut_index"]
    assert doc["orders"] == {"dot": "A", "len_sq": "C"} and doc["intrinsics"] == 1
    assert list(doc["harmless"]) == ["enforce_bounds"] and doc["fused_instructions"] == 7
    doc = layers_record(_layers_dis(tmp_path, _distance_to_line_code("B", "D")))
    assert doc["orders"] == {"dot": "B", "len_sq": "D"} and doc["fused"] == ["distance_to_line"]
    found = layers_of_build({"arithmetic": KNOWN["aarch64"].as_dict(), "layers_arithmetic": doc})[0]
    assert found == LayersArithmetic(frozenset({"distance_to_line"}), "B", "D")
    assert layers_of_build({"arithmetic": X86_64.as_dict()})[0] == LayersArithmetic()  # recorded before: fuses none
    assert "build it again" in layers_of_build({"arithmetic": KNOWN["aarch64"].as_dict()})[1]


@pytest.mark.fast
def test_the_layers_model_computes_distance_to_line_with_the_products_found():
    from navfn_smt.nav2.footprint import c_hypot, distance_to_line
    from navfn_smt.spec.arithmetic import LayersArithmetic

    x0, y0, x1, y1 = -0.3, 0.7, 0.4, -0.1  # the point (0, 0): its nearest point is inside the segment
    a, b, c, d = 0.0 - x0, 0.0 - y0, x1 - x0, y1 - y0
    for dot, len_sq in (("A", "C"), ("B", "D")):
        s = c_fma(a, c, b * d) if dot == "A" else c_fma(b, d, a * c)
        n = c_fma(c, c, d * d) if len_sq == "C" else c_fma(d, d, c * c)
        assert 0 < s / n < 1
        want = c_hypot(c_fma(s / n, c, x0) - 0.0, c_fma(s / n, d, y0) - 0.0)
        arith = LayersArithmetic(frozenset({"distance_to_line"}), dot, len_sq)
        assert distance_to_line(0.0, 0.0, x0, y0, x1, y1, arith) == want
    assert distance_to_line(0.0, 0.0, x0, y0, x1, y1) == c_hypot(x0 + (a * c + b * d) / (c * c + d * d) * c,
                                                                 y0 + (a * c + b * d) / (c * c + d * d) * d)


@pytest.mark.fast
@pytest.mark.parametrize("drop", ["partial", "no site", "no line", "untold"])
def test_layer_arithmetic_the_model_cannot_express_is_named(tmp_path, drop):
    from navfn_smt.oracle.arithmetic import layers_of_build, layers_record

    items, untraced = _distance_to_line_code(), 0
    if drop == "partial":
        items = items[:-2]
    elif drop == "no site":
        items.append(("costmap_math.cpp", 11, "fmadd\td0, d1, d2, d3"))
    elif drop == "no line":
        untraced = 1
    else:  # the dot's multiplicands written by no line that assigns A, B, C or D
        items = [i for i in items if i[1] not in (3, 4, 5, 6)]
    doc = layers_record(_layers_dis(tmp_path, items, untraced))
    says = {"partial": "distance_to_line fused on costmap_math.cpp lines [7, 8] but not on [9, 10]",
            "no site": "costmap_math.cpp:11 fused `double other = a * b + c;`", "no line": "without a source line",
            "untold": "distanceToLine's dot: which product was fused could not be told"}[drop]
    assert any(says in p for p in doc["unexpressible"]), doc["unexpressible"]
    bad = {"arithmetic": KNOWN["aarch64"].as_dict(), "layers_arithmetic": doc}
    assert layers_of_build(bad)[0] is None and "cannot express" in layers_of_build(bad)[1]


# --------------------------------------------------------------------------- the C library's hypot
@pytest.mark.fast
def test_the_hypot_kernels_differ_and_the_probe_names_only_the_one_that_gives_every_double():
    """glibc's two hypot kernels part on some probe pairs (so the probe can tell them apart);
    answers of either are named as it; answers one ulp off on one pair are neither."""
    import math

    from navfn_smt.spec.libm import HYPOTS, glibc_hypot, kernel_of, probe_inputs

    pairs = probe_inputs()
    for kernel in HYPOTS:
        answers = [glibc_hypot(x, y, kernel) for x, y in pairs]
        found, misses = kernel_of(pairs, answers)
        assert found == kernel and misses[kernel] == 0
        assert all(n > 20 for k, n in misses.items() if k != kernel), misses
        answers[0] = math.nextafter(answers[0], math.inf)
        assert kernel_of(pairs, answers)[0] is None
    with pytest.raises(ValueError, match="no hypot kernel"):
        glibc_hypot(3.0, 4.0, "musl")


@pytest.mark.fast
def test_this_machines_glibc_hypot_is_the_plain_kernel():
    """On x86-64 (whose glibc has no fused kernel) the C library's hypot is the ``glibc`` kernel
    on every probe pair; the legacy layers record of a native build takes it."""
    import platform

    from navfn_smt.oracle.arithmetic import host_hypot, layers_of_build
    from navfn_smt.spec.numeric import c_hypot
    from navfn_smt.spec.libm import kernel_of, probe_inputs

    if platform.machine() != "x86_64":
        pytest.skip("the plain kernel is x86-64 glibc's")
    pairs = probe_inputs(seed=1)
    assert kernel_of(pairs, [c_hypot(x, y) for x, y in pairs])[0] == "glibc" == host_hypot()
    entry = {"fused": [], "orders": {}, "unexpressible": []}
    assert layers_of_build({"arithmetic": X86_64.as_dict(), "runner": [], "layers_arithmetic": entry})[0].hypot == "glibc"
    why = layers_of_build({"arithmetic": X86_64.as_dict(), "runner": ["qemu-aarch64"], "layers_arithmetic": entry})[1]
    assert "hypot" in why and "build it again" in why
    found = layers_of_build({"arithmetic": X86_64.as_dict(), "layers_arithmetic": {**entry, "hypot": "glibc-fma"}})[0]
    assert found.hypot == "glibc-fma" and "hypot glibc-fma" in found.name


def test_the_aarch64_c_library_computes_hypot_with_the_fused_kernel(tmp_path):
    """Debian's arm64 glibc, run under qemu by the probe an oracle build runs: the ``glibc-fma``
    kernel on every probe pair, and not the plain one."""
    from navfn_smt.oracle.arithmetic import probe_hypot
    from navfn_smt.spec.libm import kernel_of, probe_inputs

    tc = toolchain("aarch64")
    try:
        tc.check()
        runner = tc.runner()
    except NavfnInputError as e:
        pytest.skip(str(e))
    pairs = probe_inputs()
    found, misses = kernel_of(pairs, probe_hypot(tc, runner, tmp_path, pairs))
    assert found == "glibc-fma" and misses["glibc"] > 0


@pytest.mark.fast
def test_the_footprint_radii_follow_the_hypot_kernel_and_astar_distances_do_not():
    """The footprint's radii are computed with the build's kernel: some generated robot radii give
    an inscribed radius one ulp apart under the two.  NavFn's A* distance term (``hypot`` of two
    ints times 50, narrowed to float) is the same float under both for every pair of ints below
    400, which is why NavFn's spec may keep the host's ``hypot``."""
    import numpy as np

    from navfn_smt.nav2.footprint import robot_footprint
    from navfn_smt.spec.arithmetic import LayersArithmetic
    from navfn_smt.spec.libm import glibc_hypot

    fma = LayersArithmetic(hypot="glibc-fma")
    radii = np.random.default_rng(0).uniform(0.05, 1.0, 60)
    apart = sum(robot_footprint(float(r)).inscribed_radius != robot_footprint(float(r), arith=fma).inscribed_radius
                for r in radii)
    assert apart > 0
    doubles = same = 0
    for i in range(400):
        for j in range(i + 1):
            a, b = glibc_hypot(float(i), float(j)), glibc_hypot(float(i), float(j), "glibc-fma")
            doubles += a != b
            same += np.float32(a * COST_NEUTRAL) == np.float32(b * COST_NEUTRAL)
    assert doubles > 0 and same == 400 * 401 // 2
