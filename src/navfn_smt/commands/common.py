"""What every command shares: the example suite, the checks of numbers and output paths,
a cell from the command line, the arguments as JSON, and what the invariants page is
rendered from (``docs`` and ``prove --markdown``)."""

from __future__ import annotations

import math
from pathlib import Path

from ..errors import NavfnInputError
from ..fileio import check_writable

EXAMPLE_SUITE = Path(__file__).resolve().parent.parent / "examples" / "suite"
BACKEND_HELP = "planner implementation: the numba JIT or the reference spec"
MODE_HELP = "planner modes: A*, Dijkstra or both"


def suite_or_example(arg) -> Path:
    """The suite a command names, or the example suite shipped with the package."""
    return Path(arg) if arg else EXAMPLE_SUITE


def check_max_cases(n) -> None:
    """Reject a ``--max-cases`` below 1."""
    if n is not None and n < 1:
        raise NavfnInputError("--max-cases must be at least 1")


def check_positive(option: str, value, allow_zero: bool = False) -> None:
    """Reject a number option that is not a positive finite number (NaN included)."""
    ok = value is None or (math.isfinite(value) and (value >= 0 if allow_zero else value > 0))
    if not ok:
        raise NavfnInputError(f"{option} {value:g}: must be a {'non-negative' if allow_zero else 'positive'} number")


def check_files(*paths) -> None:
    """Fail early, before the run, on any output file that could not be written."""
    for p in paths:
        if p:
            check_writable(p)


def cell(what: str, v) -> tuple[int, int]:
    """A map cell from two command-line numbers (which must be integers)."""
    if len(v) != 2:
        raise NavfnInputError(f"--{what} needs two cell coordinates X Y (a yaw is for --world poses)")
    if any(not float(c).is_integer() for c in v):
        raise NavfnInputError(f"--{what} {v[0]:g} {v[1]:g}: a map cell needs integers (use --world for world coordinates)")
    return int(v[0]), int(v[1])


def vars_of(args) -> dict:
    """The arguments of a command as plain JSON values (no handler)."""
    return {k: v for k, v in vars(args).items() if k != "func"}


def page_sources(check_reports, split_dir, files=None) -> dict:
    """What the invariants page (:func:`navfn_smt.report.invariants_page.render`) is rendered
    from beside a prove report, as its keyword arguments: the ``check_reports`` read (one-line
    errors on a missing or malformed one) and where their pictures are, the split report in
    ``split_dir`` if there is one, the obligations of the proof ``files`` (default: those shipped
    in the package) and what is known of them (their declarations, the splits of their files
    and the shipped chains).  It only reads: no solver runs."""
    from ..proofs import PREDICATES
    from ..report import invariants_page as page
    from ..smt.obligation import load_obligations
    from ..smt.runner import default_proof_files
    from ..smt.split import known_of_files

    checks = [(page.report_label(p), page.read_check_report(p)) for p in check_reports]
    flavoured = [(page.report_label(p), page.read_check_report(p)) for p in page.flavoured_check_reports(check_reports)]
    split = page.split_beside(split_dir)
    declared = load_obligations(files if files else default_proof_files())
    known = known_of_files(sorted({ob.source for ob in declared if ob.source}), declared, PREDICATES)
    return {"checks": checks, "images": page.images_dir(check_reports), "split": split,
            "declared": declared, "known": known, "flavoured": flavoured}


TARGET_HELP = ("the arithmetic of a build for this machine, in which the spec computes: x86-64 (default: the "
               "golden files'), x86-64-v3 or aarch64 (docs/toolchains.md)")


ORACLE_PLAN_HELP = ("plan as the build in DIR computes (navfn-smt oracle build): its distribution and the "
                    "arithmetic found in it")


def add_planner_arguments(parser, arithmetic: bool = True, variant_help: str = "", oracle_help: str = "") -> None:
    """The options that name the planner under test: ``--variant``, and with ``arithmetic``
    ``--target NAME``, and with ``oracle_help`` ``--oracle DIR`` (commands that compare with a
    build add their own ``--oracle``, which names the planner the same way)."""
    from ..spec import fixes

    parser.add_argument("--variant", choices=fixes.NAMES, default=fixes.DEFAULT.name, help=fixes.HELP + variant_help)
    if arithmetic:
        parser.add_argument("--target", metavar="NAME", help=TARGET_HELP)
    if oracle_help:
        parser.add_argument("--oracle", metavar="DIR", help=oracle_help)


def with_patch(fix, command: str):
    """``fix`` when the C++ can be built with it (NavFn as shipped, or a fix with patches); a
    clear error for a candidate stated in the spec alone."""
    if not fix.shipped and fix.patches is None:
        raise NavfnInputError(f"{command} --variant {fix.name}: this candidate has no C++ patch, so no build plans "
                              f"as it does (it is compared in the spec alone: navfn-smt fixes)")
    return fix


def planners_of(args) -> list:
    """The planners under test a comparison's options name: ``(target, NavFn as shipped there,
    [a planner per --variant])`` for each of ``--targets``, every registered fix when no
    --variant is given."""
    from ..spec import fixes
    from ..under_test import PlannerUnderTest

    chosen = [fixes.named(n) for n in (args.variant or fixes.NAMES)]
    return [(t, PlannerUnderTest.of_target(t), [PlannerUnderTest.of_target(t, f) for f in chosen])
            for t in args.targets]


def planner_of(args, variant=None):
    """The planner under test (:class:`~navfn_smt.under_test.PlannerUnderTest`) a command's
    options name, made once: ``--variant`` (or ``variant``), ``--target NAME`` or ``--oracle DIR``
    (whose build.json gives its distribution and arithmetic), ``--distro`` where the command
    has it; contradicting options are a clear error."""
    from ..spec import fixes
    from ..under_test import PlannerUnderTest

    variant = fixes.named(variant or getattr(args, "variant", None) or fixes.DEFAULT)
    target, oracle = getattr(args, "target", None), getattr(args, "oracle", None)
    distro = getattr(args, "distro", None)
    if oracle:
        if target:
            raise NavfnInputError(f"--target {target} and --oracle DIR exclude each other: a build's arithmetic "
                                  f"is found in the build (its build.json names its target)")
        return PlannerUnderTest.of_build(oracle, variant, distro)
    return PlannerUnderTest.of_target(target, variant, distro)


def plugin_arithmetic_of(planner, command: str):
    """The plugin arithmetic the planner under test computes in for ``command`` (its name in
    errors): the one found in its build (``--oracle DIR``), None for x86-64's; a clear error
    for ``--target NAME`` of another machine, whose plugin arithmetic is found only in a build."""
    from ..spec.arithmetic import X86_64

    if planner.build is not None:
        return planner.plugin_arithmetic()
    if planner.arithmetic != X86_64:
        name = planner.arithmetic.name
        raise NavfnInputError(f"{command} --target {name}: the plugin's arithmetic is found in a build; give "
                              f"--oracle DIR (navfn-smt oracle build --target {name})")
    return None


def layers_arithmetic_of(planner, map_path):
    """The costmap layers' arithmetic of the planner's build for a map_server map (None: x86-64's,
    or a costmap given directly, on which no layer runs)."""
    from ..maps.loading import is_yaml

    return planner.layers_arithmetic() if planner.build is not None and is_yaml(map_path) else None


def add_toolchain_arguments(parser) -> None:
    """``--target``, ``--cxx`` and ``--cxxflags``: the toolchain a command builds Nav2's C++ with."""
    parser.add_argument("--target", metavar="NAME", help="the machine to build for: x86-64 (default; $CXX or g++), "
                        "x86-64-v3 (-march=x86-64-v3: FMA), aarch64 (Debian's aarch64-linux-gnu-g++, run under "
                        "qemu-aarch64); a program for another machine runs under qemu-user")
    parser.add_argument("--cxx", metavar="CXX", help="your own C++ compiler (its target machine is what it says "
                        "with -dumpmachine, unless --target names one)")
    parser.add_argument("--cxxflags", metavar="FLAGS", help="with --cxx: flags after -std=c++17 -O2")


def toolchain_of(args):
    """The :class:`~navfn_smt.oracle.targets.Toolchain` of :func:`add_toolchain_arguments`' options."""
    import os

    from ..oracle.targets import toolchain

    return toolchain(args.target, args.cxx, args.cxxflags, env_cxx=os.environ.get("CXX"))
