"""The symbolic whole-propagation encoding equals the concrete spec, bit for bit.

``check.encoding.propagate`` builds NavFn's complete propagation (setup, the three buffers,
pending flags, threshold, cycle limit, the stop at the start) as terms of the fp32 domain.
Fixing the map and folding the terms must give every potential, ``start_reached`` and the
cycle count exactly as the reference spec computes them; with symbolic cost bytes, a solver
must find no assignment of the map's costs under which a potential differs.
"""

from __future__ import annotations

import numpy as np
import pytest
import z3

from navfn_smt.check.encoding import _interior, propagate
from navfn_smt.smt.domains import FPDomain
from navfn_smt.smt.evaluate import value
from navfn_smt.spec.costs import add_border
from navfn_smt.spec.planner import plan


def _bits(v) -> bytes:
    return np.float32(v).tobytes()


def _case(seed: int):
    """Seeds below 16: mixed costs; from 16 on: dear cells (200, 253) whose potentials pass the
    priority threshold, so the overflow buffer and the threshold increment take part."""
    rng = np.random.default_rng(seed)
    nx, ny = int(rng.integers(3, 6)), int(rng.integers(3, 5))
    palette = [50, 51, 80, 120, 200, 253, 254, 255] if seed < 16 else [200, 253, 253, 253, 254]
    arr = add_border(rng.choice(palette, size=(ny, nx)).astype(np.uint8))
    inner = _interior(nx, ny)
    start = (int(rng.choice(inner)) % nx, int(rng.choice(inner)) // nx)
    goal = (int(rng.choice(inner)) % nx, int(rng.choice(inner)) // nx)
    return arr, start, goal, bool(rng.integers(2))


@pytest.mark.parametrize("seed", range(28))
def test_encoding_folds_to_the_spec(seed):
    arr, start, goal, astar = _case(seed)
    ny, nx = arr.shape
    sp = propagate(FPDomain(), {k: int(arr.ravel()[k]) for k in _interior(nx, ny)}, nx, ny, start, goal, astar)
    ref = plan(arr, start, goal, astar=astar, record_trace=True)
    got = [_fold(p) for p in sp.potential]
    assert [_bits(v) for v in got] == [_bits(v) for v in ref.potential.ravel()]
    assert _fold(sp.start_reached) == ref.start_reached
    assert _fold(sp.cycles) == ref.cycles
    assert _trace(sp) == ref.trace.tolist()


def _fold(t):
    return value(z3.simplify(t)) if z3.is_expr(t) else t


def _trace(sp) -> list:
    """The white-box trace the terms describe: per processed cycle, the count and the cells."""
    out = []
    for running, fill, slots in sp.trace:
        if _fold(running):
            n = _fold(fill)
            out += [n] + [_fold(s) for s in slots[:n]]
    return out


@pytest.mark.parametrize("seed", [5, 6])
def test_encoding_on_a_5x5_map(seed):
    """A 3x3 interior: longer traces, several pushes per update, both buffers in use."""
    rng = np.random.default_rng(seed)
    arr = add_border(rng.choice([50, 51, 120, 200, 253], size=(5, 5)).astype(np.uint8))
    arr[1, 1] = arr[2, 2] = 60
    sp = propagate(FPDomain(), {k: int(arr.ravel()[k]) for k in _interior(5, 5)}, 5, 5, (1, 1), (2, 2), bool(seed % 2))
    ref = plan(arr, (1, 1), (2, 2), astar=bool(seed % 2), record_trace=True)
    assert _trace(sp) == ref.trace.tolist()
    got = [_fold(p) for p in sp.potential]
    assert [_bits(v) for v in got] == [_bits(v) for v in ref.potential.ravel()]


# 5x5 maps on which sending every push to the next buffer changes the spec's trace, so the
# choice between the next and the overflow buffer is exercised (found by search over seeds)
SPLIT_MAPS = [
    ([[200, 120, 120], [200, 120, 200], [200, 200, 120]], (1, 1), (3, 3), True),
    ([[50, 120, 200], [50, 120, 253], [253, 50, 200]], (1, 3), (3, 1), False),
]


@pytest.mark.parametrize("inner, start, goal, astar", SPLIT_MAPS)
def test_encoding_where_pushes_split_between_buffers(inner, start, goal, astar):
    arr = np.full((5, 5), 254, np.uint8)
    arr[1:4, 1:4] = inner
    sp = propagate(FPDomain(), {k: int(arr.ravel()[k]) for k in _interior(5, 5)}, 5, 5, start, goal, astar)
    ref = plan(arr, start, goal, astar=astar, record_trace=True)
    assert _trace(sp) == ref.trace.tolist()
    got = [_fold(p) for p in sp.potential]
    assert [_bits(v) for v in got] == [_bits(v) for v in ref.potential.ravel()]


@pytest.mark.fast
def test_symbolic_costs_admit_no_other_potential():
    """Costs as symbolic bytes, fixed by constraints: no model gives a potential other than the spec's."""
    arr = add_border(np.full((4, 4), 60, np.uint8))
    arr[1, 2], arr[2, 1] = 90, 254
    ny, nx = arr.shape
    inner = _interior(nx, ny)
    D = FPDomain()
    costs = {k: D.cost(f"c{k}") for k in inner}
    sp = propagate(D, costs, nx, ny, (1, 1), (2, 2), True)
    ref = plan(arr, (1, 1), (2, 2), astar=True, record_trace=False).potential.ravel()
    s = z3.Solver()
    s.add(*[costs[k] == int(arr.ravel()[k]) for k in inner])
    s.add(z3.Or(*[z3.Not(z3.fpEQ(sp.potential[k], D.f32const(float(ref[k])))) for k in inner]))
    assert s.check() == z3.unsat


def _extraction_case(seed: int):
    rng = np.random.default_rng(1000 + seed)
    nx, ny = int(rng.integers(3, 5)), int(rng.integers(3, 5))
    if seed % 3 == 0:
        nx, ny = 5, 4  # room for gradient steps (an interior cell whose ring is all reached)
    arr = add_border(rng.choice([50, 60, 120, 200, 253, 254], size=(ny, nx)).astype(np.uint8))
    inner = _interior(nx, ny)
    s, g = int(rng.choice(inner)), int(rng.choice(inner))
    return arr, (s % nx, s // nx), (g % nx, g // nx), bool(seed % 2)


@pytest.mark.parametrize("seed", range(16))
def test_whole_run_folds_to_the_spec(seed):
    """Propagation and calcPath as terms: fixed map, folded: the exit and every path point bit for bit."""
    from navfn_smt.check import properties as P
    from navfn_smt.check.encoding import extract
    from navfn_smt.spec.extraction import exit_name
    from navfn_smt.spec.planner import path_cycle_limit

    arr, start, goal, astar = _extraction_case(seed)
    ny, nx = arr.shape
    D = FPDomain()
    sp = propagate(D, {k: int(arr.ravel()[k]) for k in _interior(nx, ny)}, nx, ny, start, goal, astar)
    ex = extract(D, sp.potential, nx, ny, start, goal, path_cycle_limit(nx))
    ref = P.run(arr, start, goal, astar)
    code = _fold(ex.exit)
    assert exit_name(code) == ref.exit
    pts = [(_fold(x), _fold(y)) for x, y, w in ex.points if _fold(w)] + [tuple(_fold(v) for v in ex.goal_point)]
    got = [(_bits(x), _bits(y)) for x, y in pts] if ref.exit == "near_goal" else []
    assert got == [(_bits(x), _bits(y)) for x, y in ref.path.tolist()]


GRADIENT_MAPS = [  # 6x5 maps on which calcPath takes a gradient step (a point off the cell centres)
    ([[50, 50, 120, 80], [80, 120, 80, 80], [120, 60, 120, 80]], True),
]


@pytest.mark.parametrize("inner, astar", GRADIENT_MAPS)
def test_whole_run_with_gradient_steps(inner, astar):
    """calcPath's gradient step as terms (interpolation, normalisation, offset overflow) between
    grid-following steps: the exit and every path point bit for bit, also in the concolic domain."""
    from navfn_smt.check import properties as P
    from navfn_smt.check.concolic import ConcolicDomain
    from navfn_smt.check.encoding import extract
    from navfn_smt.spec.extraction import exit_name
    from navfn_smt.spec.planner import path_cycle_limit

    arr = np.full((5, 6), 254, np.uint8)
    arr[1:4, 1:5] = inner
    start, goal = (2, 3), (3, 1)
    ref = P.run(arr, start, goal, astar)
    costs = {k: int(arr.ravel()[k]) for k in _interior(6, 5)}
    D = FPDomain()
    sp = propagate(D, costs, 6, 5, start, goal, astar)
    ex = extract(D, sp.potential, 6, 5, start, goal, path_cycle_limit(6))
    assert exit_name(_fold(ex.exit)) == ref.exit == "near_goal"
    pts = [(_fold(x), _fold(y)) for x, y, w in ex.points if _fold(w)] + [tuple(_fold(v) for v in ex.goal_point)]
    assert [(_bits(x), _bits(y)) for x, y in pts] == [(_bits(x), _bits(y)) for x, y in ref.path.tolist()]
    assert any(x % 1 for x, _ in ref.path.tolist())  # a point off the cell centres: a gradient step
    # the concolic domain follows the same run
    C = ConcolicDomain(FPDomain())
    box = {k: C.cost(v, v, v, f"c{k}") for k, v in costs.items()}
    sp2 = propagate(C, box, 6, 5, start, goal, astar)
    ex2 = extract(C, sp2.potential, 6, 5, start, goal, path_cycle_limit(6))
    assert exit_name(ex2.exit) == ref.exit
    pts2 = [(x.conc if hasattr(x, "conc") else x, y.conc if hasattr(y, "conc") else y)
            for x, y, w in ex2.points if (w.conc if hasattr(w, "conc") else w)] + [ex2.goal_point]
    assert [(_bits(x), _bits(y)) for x, y in pts2] == [(_bits(x), _bits(y)) for x, y in ref.path.tolist()]


def _counterexample_case(name: str):
    """The map, start, goal and mode of a committed counterexample (tests/data/counterexamples)."""
    from conftest import DATA
    from navfn_smt.maps.suite import load_map

    import json

    d = DATA / "counterexamples" / name
    doc = json.loads((d / "counterexample.json").read_text())
    return load_map(d).costs, tuple(doc["start"]), tuple(doc["goal"]), doc["mode"] == "astar"


# maps where the arithmetics part: a path on aarch64 only (its saturating (int)), a path on x86-64
# only (the fused multiply-adds' potentials), and a path with gradient steps that fuse
ARITHMETIC_MAPS = ["path-without-potential-astar-4x3-aarch64", "cost-astar-5x7", "turn-astar-5x5"]


@pytest.mark.fast
@pytest.mark.parametrize("name", ARITHMETIC_MAPS)
def test_the_concolic_run_in_each_arithmetic_is_the_specs_there(name):
    """The whole run in the concolic domain over a build's arithmetic (``check --target``):
    its concrete side, every potential, the exit and every path point, is the reference spec's
    run in that arithmetic bit for bit, for x86-64, x86-64-v3 and aarch64; and on each of these
    maps some arithmetic's run differs from x86-64's, so a concolic domain that ignored the
    arithmetic would fail here."""
    from navfn_smt.check import properties as P
    from navfn_smt.check.bounded import Case, _symbolic_run
    from navfn_smt.check.concolic import concrete
    from navfn_smt.smt.domains import DOMAINS, FP32_SEMANTICS
    from navfn_smt.spec.constants import COST_OBS
    from navfn_smt.spec.extraction import exit_name

    arr, start, goal, astar = _counterexample_case(name)
    ny, nx = arr.shape
    inner = _interior(nx, ny)
    case = Case(nx, ny, frozenset(k for k in inner if arr.flat[k] >= COST_OBS), start, goal, astar)
    conc = {k: int(arr.flat[k]) for k in inner if k not in case.lethal}
    runs = {}
    for semantics, arith in FP32_SEMANTICS.items():
        D, _, sp, ex = _symbolic_run(case, conc, 50, 253, DOMAINS[semantics])
        ref = P.run(arr, start, goal, astar, arith=arith)
        pot = [_bits(concrete(p)) for p in sp.potential]
        assert pot == [_bits(v) for v in ref.potential.ravel()], semantics
        assert exit_name(concrete(ex.exit)) == ref.exit, semantics
        pts = [(concrete(x), concrete(y)) for x, y, w in ex.points if concrete(w)]
        if ref.exit == "near_goal":
            pts.append(tuple(concrete(v) for v in ex.goal_point))
            assert [(_bits(x), _bits(y)) for x, y in pts] == [(_bits(x), _bits(y)) for x, y in ref.path.tolist()]
        runs[semantics] = (pot, ref.exit, ref.path.tobytes())
    assert any(r != runs["fp32"] for r in runs.values()), "the arithmetics plan this map alike"
