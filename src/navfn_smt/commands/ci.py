"""``navfn-smt ci NAV2_SRC``: the whole chain of trust for a Nav2 checkout in one command.

For a Nav2 fork's CI (the workflow file is in ``docs/ci.md``): build the checkout's NavFn,
planner plugin and costmap layers (``oracle build``), difftest every level live against the
specification and the models (NavFn on a suite, white-box, with Nav2's buffers and with
unbounded ones; the plugin on generated costmaps, poses and parameters; the costmap layers on
generated maps), prove the obligations, and write one JUnit file of every step.  Exit 0 when
every step agrees; 1 when one disagrees (or a proof contradicts what is known); a step the
sources cannot run (no Eigen for Rolling's inflation layer, say) is skipped and named.

``--target`` (``--cxx``, ``--cxxflags``) builds for another machine, as ``oracle build`` does; every
difftest step then computes in the arithmetic found in the build (NavFn's, the plugin's and the
layers'), and the proofs, which are about x86-64's arithmetic, are skipped and say so.
"""

from __future__ import annotations

import time
from pathlib import Path

from ..errors import NavfnInputError
from .common import check_files

DEFAULT_OUT = "build/nav2-ci"


class _Steps:
    """The steps run so far, as JUnit test cases, and what is printed of each."""

    def __init__(self):
        self.cases = []

    def add(self, name: str, seconds: float, failure=None, skipped=None, out: str = "") -> None:
        self.cases.append({"name": name, "seconds": seconds, "failure": failure, "skipped": skipped, "out": out})
        state = "FAILED" if failure else "skipped" if skipped else "ok"
        print(f"{name:<28} {state:<8} {seconds:7.1f} s  {failure or skipped or out}")

    @property
    def failed(self) -> bool:
        return any(c["failure"] for c in self.cases)


def _summary_step(steps: _Steps, name: str, run) -> None:
    """Run one difftest step; a step that cannot finish (the C++ stopped answering, say) fails."""
    t0 = time.perf_counter()
    try:
        s = run()
    except NavfnInputError as e:
        steps.add(name, time.perf_counter() - t0, failure=str(e))
        return
    text = f"{s['passed']} passed, {s['failed']} failed"
    steps.add(name, time.perf_counter() - t0, failure=text if s["failed"] else None, out=text)


def _navfn(args, planner, unbounded: bool):
    from ..difftest.live import run_live
    from ..maps.suite import MODES
    from ..oracle.client import Oracle
    from .common import suite_or_example

    planner.navfn_arithmetic()  # a clear failure of the step when the spec cannot express it
    with Oracle(planner.build, **({"unbounded": True} if unbounded else {"fix": planner.fix})) as oracle:
        return run_live(suite_or_example(args.suite), MODES, "jit", oracle, unbounded=unbounded,
                        planner=planner).as_dict()


def _plugin(args, planner):
    from ..difftest.plugin_live import generated_configs, run_plugin_live
    from ..oracle.client import PluginOracle

    arith = planner.plugin_arithmetic()
    with PluginOracle(planner.build, planner.fix) as oracle:
        return run_plugin_live(generated_configs(planner.distribution, args.configs, args.seed),
                               oracle, arith=arith).as_dict()


def _costmap(args, planner):
    from ..difftest.layers_live import generated_configs, run_layers_live
    from ..oracle.client import LayersOracle
    from ..report.difftest import cpu_sqrt_line

    arith = planner.layers_arithmetic()
    with LayersOracle(planner.build) as oracle:
        s = run_layers_live(generated_configs(planner.distribution, args.configs, args.seed),
                            oracle, arith=arith).as_dict()
    if s["cpu_sqrt"]:
        print("  " + cpu_sqrt_line(s["cpu_sqrt"]))
    return s


def _prove(args, steps: _Steps, junit: Path) -> None:
    """``navfn-smt prove --timeout T --junit FILE``, parsed by prove's own parser."""
    import argparse

    from . import prove

    parser = argparse.ArgumentParser(prog="navfn-smt")
    prove.register(parser.add_subparsers())
    pargs = parser.parse_args(["prove", "--timeout", str(args.timeout), "--junit", str(junit)])
    t0 = time.perf_counter()
    rc = pargs.func(pargs)
    steps.add("prove", time.perf_counter() - t0, failure="a verdict contradicts what is known" if rc else None,
              out=f"JUnit of every obligation: {junit}")


def cmd_ci(args) -> int:
    """Build, difftest every level, prove; one JUnit file; exit 1 on any disagreement."""
    from ..oracle.build import SHIPPED_PROGRAMS, build
    from ..under_test import PlannerUnderTest
    from ..report.ci import write_junit
    from ..spec.arithmetic import X86_64
    from .common import toolchain_of

    out = Path(args.out)
    if out.exists() and not out.is_dir():
        raise NavfnInputError(f"{out}: not a folder (--out names the build and report folder)")
    out.mkdir(parents=True, exist_ok=True)
    check_files(args.junit)
    steps = _Steps()
    t0 = time.perf_counter()
    # the programs of NavFn as the sources are: ci difftests and proves no fix's patch
    doc = build(args.nav2_src, out / "oracle", programs=SHIPPED_PROGRAMS, tc=toolchain_of(args))
    planner = PlannerUnderTest.of_build(out / "oracle")  # the build's, its arithmetic as found in it
    arith = planner.arithmetic
    steps.add("build", time.perf_counter() - t0, out=f"{planner.distribution} for {planner.target} "
              f"({arith.name if arith else planner.unexpressible}): {', '.join(doc['programs'])}")
    _summary_step(steps, "difftest navfn", lambda: _navfn(args, planner, False))
    _summary_step(steps, "difftest navfn unbounded", lambda: _navfn(args, planner, True))
    _summary_step(steps, "difftest plugin", lambda: _plugin(args, planner))
    if "costmap-layers" in doc["programs"]:
        _summary_step(steps, "difftest costmap", lambda: _costmap(args, planner))
    else:
        steps.add("difftest costmap", 0.0, skipped=doc.get("skipped", {}).get("costmap-layers", "not built"))
    prove_junit = out / "prove-junit.xml" if not args.no_prove and arith == X86_64 else None
    if prove_junit is not None:
        _prove(args, steps, prove_junit)
    elif not args.no_prove:
        steps.add("prove", 0.0, skipped=f"the obligations are stated in x86-64's arithmetic; this build computes in "
                  f"{arith.name if arith else 'one the spec cannot express'} (docs/toolchains.md)")
    write_junit(args.junit or out / "junit.xml", f"navfn-smt ci {doc['distribution']}", steps.cases, prove_junit)
    print(f"JUnit: {args.junit or out / 'junit.xml'}")
    return 1 if steps.failed else 0


def register(sub) -> None:
    """The command's parser, its options and its handler."""
    from .common import add_toolchain_arguments

    c = sub.add_parser("ci", help="build a Nav2 checkout, difftest every level against it, prove; write JUnit",
                       description="The chain of trust for a Nav2 checkout in one command: oracle build, the live "
                       "difftest of NavFn (white-box, Nav2's buffers and unbounded ones), of the planner plugin and of "
                       "the costmap layers, then prove; one JUnit file.  See docs/ci.md for a workflow file.")
    c.add_argument("nav2_src", metavar="NAV2_SRC", help="a navigation2 checkout, or a folder of its packages")
    c.add_argument("--out", metavar="DIR", default=DEFAULT_OUT, help="build and report folder (default: %(default)s)")
    add_toolchain_arguments(c)
    c.add_argument("--suite", help="the NavFn suite (default: the example suite shipped with the package)")
    c.add_argument("--configs", type=int, default=200, metavar="N",
                   help="generated plugin and costmap configurations (default: %(default)s)")
    c.add_argument("--seed", type=int, default=0, help="the generators' seed (default: %(default)s)")
    c.add_argument("--timeout", type=float, default=60.0, help="prove: seconds per query (default: %(default)s)")
    c.add_argument("--no-prove", action="store_true", help="skip the proofs (they do not depend on NAV2_SRC)")
    c.add_argument("--junit", metavar="FILE", help="the JUnit file (default: DIR/junit.xml)")
    c.set_defaults(func=cmd_ci)
