"""The planning call is written once (spec/planner.py) and a fix is a value: every planner of the
package (the reference spec, the JIT, the check's encoding, the plugin model) runs a fix's own hook
functions, and no code outside argument parsing and report writing compares a fix's name."""

from __future__ import annotations

import json
import re
from collections import Counter
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from navfn_smt.check import properties as P
from navfn_smt.check.encoding import interior
from navfn_smt.maps.suite import load_map
from navfn_smt.spec import extraction as E
from navfn_smt.spec import fix as F
from navfn_smt.spec import fixes
from navfn_smt.spec import propagation as PR
from navfn_smt.spec.costs import add_border
from navfn_smt.spec.planner import Fallback, Fix, FurtherCall, plan
from navfn_smt.under_test import PlannerUnderTest

REPO = Path(__file__).resolve().parent.parent
SRC = REPO / "src" / "navfn_smt"
CX = REPO / "tests" / "data" / "counterexamples"


def _spy(calls: Counter, name: str, fn):
    def spied(*args, **kwargs):
        calls[name] += 1
        return fn(*args, **kwargs)
    return spied


def _spy_fix(calls: Counter, test=True) -> Fix:
    """The fix of docs/fix.md with every hook counted (``test=False``: its further call's test as
    it is, the one the JIT compiles)."""
    further = FurtherCall(_spy(calls, "test", F.calls_again) if test else F.calls_again,
                          _spy(calls, "further cycles", F.extra_cycles))
    return Fix("spy", "the fix of docs/fix.md, its hooks counted", patches="navfn-fix",
               cycles=_spy(calls, "cycles", F.FIX.cycles), further=further,
               fallback=Fallback(_spy(calls, "walk", F.descend)))


def _case(name: str):
    d = CX / name
    doc = json.loads((d / "counterexample.json").read_text())
    sm = load_map(d)
    sx, sy, gx, gy = (int(v) for v in sm.cases[0])
    return sm.costs, (sx, sy), (gx, gy), doc["mode"] == "astar"


# a map where the original leaves the start unreached (the further call acts) and one where
# calcPath fails from a reached start (the fallback acts)
UNREACHED, TRAPPED = "unreached-astar-7x8", "incomplete-astar-5x5"


def _checks_case(costs, s, g, astar):
    """The check's case of a map (its lethal interior cells fixed) and its other costs:
    ``(Case, {cell: cost})``, what ``bounded._symbolic_run`` takes."""
    from navfn_smt.check.bounded import Case
    from navfn_smt.spec.constants import COST_OBS

    arr = add_border(costs)
    ny, nx = arr.shape
    inner = interior(nx, ny)
    lethal = frozenset(k for k in inner if arr.flat[k] >= COST_OBS)
    return Case(nx, ny, lethal, s, g, astar), {k: int(arr.flat[k]) for k in inner if k not in lethal}


def _same(a, b) -> bool:
    return np.asarray(a).tobytes() == np.asarray(b).tobytes()


@pytest.mark.fast
@pytest.mark.parametrize("name,acted", [(UNREACHED, ("cycles", "test", "further cycles")),
                                        (TRAPPED, ("cycles", "test", "walk"))])
def test_the_spec_and_the_judges_run_the_fixs_hooks(name, acted):
    costs, s, g, astar = _case(name)
    for run in (lambda fx: plan(costs, s, g, astar, fix=fx), lambda fx: P.run(costs, s, g, astar, fix=fx)):
        calls = Counter()
        got, want = run(_spy_fix(calls)), run(F.FIX)
        assert all(calls[k] > 0 for k in acted), calls
        assert _same(got.potential, want.potential) and _same(got.path, want.path)


def _compiled_from(fn) -> list:
    """The Python functions numba compiled for calls of ``fn`` in this process (its overloads'
    implementations)."""
    from numba.core.registry import cpu_target

    fnty = cpu_target.typing_context.resolve_value_type(fn)
    return [disp.py_func for tmpl in fnty.templates for disp, _ in getattr(tmpl, "_impl_cache", {}).values()]


def _stricter_test(D, start_pot, fill_cur, fill_next):
    """A fix's own further-call test, new to the JIT: the start unreached and the current buffer
    holding cells (the fix's test also goes on from cells in the next buffer)."""
    return D.and_(D.not_(D.lt(start_pot, D.f32const(1e10))), D.lt(0, fill_cur))


@pytest.mark.parametrize("name", [UNREACHED, TRAPPED])
def test_the_jit_compiles_the_specs_call_and_runs_the_fixs_hooks(name):
    import numba

    from navfn_smt.backends import get_backend
    from navfn_smt.backends import jit as J
    from navfn_smt.spec import planner as PL

    costs, s, g, astar = _case(name)
    # a fresh compilation of the JIT's entry points: every step of the call it compiles is the
    # spec's own function (numba's overload of it has the function itself as implementation)
    planner = J.JitPlanner(add_border(costs))
    numba.njit(J.plan_shipped.py_func)(planner.D, *planner.work, *s, *g, astar, 100, 10, True)
    numba.njit(J.extract_path.py_func)(planner.D, planner.pot, planner.nx, planner.ny, *s, *g, 20, planner.trail, False)
    steps = (PR.init_cost, PR.push_cur, PR.push, PR.admit, PR.update_cell, PR.run_cycle, PR.end_of_cycle,
             PR.propagate, PR.cycle_runs, PR.call_ends_at_the_start, PL.call, E.follow, E.gradient,
             E.iteration_test, E.follows_the_grid, E.grid_step, E.zero_gradient)
    for step in steps:
        compiled = _compiled_from(step)
        assert compiled and all(c is step for c in compiled), step.__qualname__
    assert J.compiled_test(F.calls_again).py_func is F.calls_again  # a fix's test is compiled as it is
    # the fix's hooks run, its further test compiled as it is (a new one too), bit-exact with the spec
    for test in (F.calls_again, _stricter_test):
        calls = Counter()
        fix = replace(_spy_fix(calls, test=False), further=FurtherCall(test, _spy(calls, "further cycles",
                                                                                   F.extra_cycles)))
        got = get_backend("jit", PlannerUnderTest(fix)).prepare(costs).run(s, g, astar)
        want = plan(costs, s, g, astar, fix=fix)
        assert calls["cycles"] > 0 and calls["further cycles"] > 0
        assert (calls["walk"] > 0) == (name == TRAPPED)
        for field in ("potential", "path", "trace"):
            assert _same(getattr(got, field), getattr(want, field)), field
        assert got.extra == want.extra and got.extra["fix"]


@pytest.mark.parametrize("name", [UNREACHED, TRAPPED])
def test_the_checks_encoding_runs_the_fixs_hooks(name, monkeypatch):
    from navfn_smt.check.bounded import _symbolic_run
    from navfn_smt.check.concolic import concrete
    from navfn_smt.smt.domains import FPDomain
    from navfn_smt.spec import planner as PL

    costs, s, g, astar = _case(name)
    case, conc = _checks_case(costs, s, g, astar)
    calls = Counter()
    # the spec's steps themselves, counted where the spec calls them
    for module, step in ((PR, "update_cell"), (PR, "push"), (PR, "end_of_cycle"), (PL, "calc_path")):
        monkeypatch.setattr(module, step, _spy(calls, step, getattr(module, step)))
    _, _, sp, ex = _symbolic_run(case, conc, 50, 253, FPDomain, _spy_fix(calls))
    want = plan(costs, s, g, astar, fix=F.FIX)
    assert calls["cycles"] > 0 and calls["test"] > 0
    assert (calls["walk"] > 0) == (name == TRAPPED)  # the spec's walk, on terms
    assert all(calls[step] > 0 for step in ("update_cell", "push", "end_of_cycle", "calc_path")), calls
    assert [float(concrete(p)) for p in sp.potential] == [float(v) for v in want.potential.ravel()]
    assert concrete(ex.exit) == E.exit_code(want.exit)


@pytest.mark.parametrize("name", [UNREACHED, TRAPPED])
def test_the_plugin_model_runs_the_fixs_hooks(name):
    from navfn_smt.nav2.params import PlannerParams
    from navfn_smt.nav2.plugin import Costmap, create_plan
    from navfn_smt.check.plugin import centre

    costs, s, g, astar = _case(name)
    ros = np.where(costs >= 254, 254, 0).astype(np.uint8)  # the counterexample's walls, the rest free
    cm = Costmap(ros, 0.0, 0.0, 1.0)
    runs = {}
    for key, fx in (("spy", None), ("fixed", F.FIX)):
        calls = Counter()
        params = replace(PlannerParams(), use_astar=astar, tolerance=0.0, fix=fx or _spy_fix(calls, test=False))
        runs[key] = create_plan(cm, centre(cm, *s), centre(cm, *g), params, "reference")
        if fx is None:
            assert calls["cycles"] > 0  # the plugin's calcNavFn* runs the fix's cycles hook
    assert _same(runs["spy"].potential, runs["fixed"].potential)
    assert runs["spy"].error == runs["fixed"].error


OPEN = "open"  # an 8x8 map of cost 50: A* stops at the start with cells left in the buffers


@pytest.mark.parametrize("where,name", [("propagation", OPEN), ("planner", OPEN), ("extraction", OPEN),
                                        ("fix", TRAPPED)])
def test_a_test_the_spec_does_not_take_fails_the_checks_run(where, name, monkeypatch):
    """The spec's tests on domain values go through ``taken``; one that did not (its module's
    ``taken`` replaced by the identity) would branch by Python's truth test, on one side for
    every map of the box: in the check's run it raises instead."""
    import importlib

    from navfn_smt.check.bounded import _symbolic_run
    from navfn_smt.smt.domains import FPDomain

    costs, s, g, astar = (np.full((8, 8), 50, np.uint8), (2, 2), (4, 4), True) if name == OPEN else _case(name)
    case, conc = _checks_case(costs, s, g, astar)
    _symbolic_run(case, conc, 50, 253, FPDomain, F.FIX)  # as the spec states it: it runs
    monkeypatch.setattr(importlib.import_module(f"navfn_smt.spec.{where}"), "taken", lambda D, c: c)
    with pytest.raises(TypeError, match="concolic"):
        _symbolic_run(case, conc, 50, 253, FPDomain, F.FIX)


@pytest.mark.fast
def test_the_checks_encoding_states_no_step_of_the_planner():
    """check/encoding.py is an array model: it calls the spec's initCost, planning call and
    extraction, and names no kernel or test of the steps (updateCell, the pushes, the loop's
    tests, calcPath's tests and steps, the descent), so it cannot restate one."""
    import ast
    import inspect

    tree = ast.parse((SRC / "check" / "encoding.py").read_text(encoding="utf-8"))
    names = {n.id for n in ast.walk(tree) if isinstance(n, ast.Name)}
    names |= {n.attr for n in ast.walk(tree) if isinstance(n, ast.Attribute)}
    assert {"init_cost", "calc_navfn", "extract_path"} <= names
    steps = {name for module in (PR, E, F) for name, f in vars(module).items()
             if inspect.isfunction(f) and f.__module__ == module.__name__}
    steps |= {"cell_update", "push_admitted", "push_wanted", "to_low_buffer", "end_of_cycle", "grad_cell",
              "lowest_of_eight", "lowest_neighbour", "nearest_cell", "step_offsets", "interpolate_gradient"}
    used = (names & steps) - {"init_cost", "propagate", "exit_code"}  # the encoding's own propagate; an exit as an int
    assert used == set(), used


NAME_TEST = re.compile(r"""(==|!=)\s*["'](original|fixed|cycles-only)["']|["'](original|fixed|cycles-only)["']\s*(==|!=)"""
                       r"""|\bin\s*\(\s*["'](original|fixed)["']""")


@pytest.mark.fast
def test_no_code_compares_a_fixs_name_outside_argument_parsing_and_reports():
    """Names of fixes live in argument parsing (commands/) and in what reports write (report/);
    everywhere else a fix is its value (spec.planner.Fix)."""
    found = []
    for path in sorted(SRC.rglob("*.py")):
        rel = path.relative_to(SRC).as_posix()
        if rel.startswith(("commands/", "report/")):
            continue
        for i, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1):
            if NAME_TEST.search(line.split("#")[0]):
                found.append(f"{rel}:{i}: {line.strip()}")
    assert found == []


@pytest.mark.fast
def test_the_registry_names_each_fix_once_and_parses_names():
    assert fixes.NAMES == tuple(f.name for f in fixes.FIXES.values()) and len(set(fixes.NAMES)) == len(fixes.NAMES)
    assert fixes.DEFAULT.shipped and all(not f.shipped for f in fixes.PATCHED)
    assert {f.name for f in fixes.PATCHED} >= {"fixed", "cycles-only"}
    assert all((SRC / "patches" / f.patches).is_dir() for f in fixes.PATCHED)
    for name in fixes.NAMES:
        assert fixes.named(name).name == name and fixes.named(fixes.named(name)) is fixes.named(name)
    with pytest.raises(Exception, match="unknown variant 'patched'"):
        fixes.named("patched")
