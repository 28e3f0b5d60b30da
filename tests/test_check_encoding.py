"""The check's run of NavFn (``check.encoding``) is the spec's run, and its terms hold at the map.

``check.encoding`` runs the spec's own initCost, planning call and calcPath in the concolic
domain: each value carries its concrete value and its term over the symbolic cost bytes, and
each branch the cost box leaves open is recorded.  On generated maps the concrete side must be
the reference spec's run bit for bit (potentials, trace, cycles, the exit, every path point);
and the symbolic side must be right at the map: every recorded branch holds there, and every
potential's and path point's term, evaluated at the map's costs, is the concrete value bit for
bit.  A solver finds no map on the path's condition with these costs and another potential.
"""

from __future__ import annotations

import numpy as np
import pytest
import z3

from navfn_smt.check.concolic import ConcolicDomain, V, concrete
from navfn_smt.check.encoding import extract, interior, propagate
from navfn_smt.smt.domains import FPDomain
from navfn_smt.smt.evaluate import value
from navfn_smt.spec.costs import add_border
from navfn_smt.spec.constants import COST_OBS
from navfn_smt.spec.extraction import exit_name
from navfn_smt.spec.planner import path_cycle_limit, plan


def _bits(v) -> bytes:
    return np.float32(v).tobytes()


def _run(arr, start, goal, astar, lo=50, hi=253):
    """The check's run on ``arr`` with every passable interior cost symbolic over ``lo..hi``:
    ``(D, {cell: cost term}, propagation, extraction)``."""
    ny, nx = arr.shape
    D = ConcolicDomain(FPDomain())
    costs, terms = {}, {}
    for k in interior(nx, ny):
        c = int(arr.flat[k])
        if c >= COST_OBS:
            costs[k] = c
        else:
            costs[k] = D.cost(c, min(lo, c), max(hi, c), f"c{k}")
            terms[k] = costs[k].term
    sp = propagate(D, costs, nx, ny, start, goal, astar)
    ex = extract(D, sp.potential, nx, ny, start, goal, path_cycle_limit(nx))
    return D, terms, sp, ex


def _at_map(arr, terms: dict, t):
    """A term evaluated at the map's costs."""
    return value(z3.simplify(z3.substitute(t, *[(c, z3.BitVecVal(int(arr.flat[k]), 8)) for k, c in terms.items()])))


def _terms_hold(arr, D, terms, values) -> None:
    """Every recorded branch is true at the map, and each value's term is its concrete value there."""
    for b in D.branches:
        assert _at_map(arr, terms, b) is True, b
    for v in values:
        if isinstance(v, V):
            assert _bits(_at_map(arr, terms, v.term)) == _bits(v.conc), v.term


def _case(seed: int):
    """Seeds below 16: mixed costs; from 16 on: dear cells (200, 253) whose potentials pass the
    priority threshold, so the overflow buffer and the threshold increment take part."""
    rng = np.random.default_rng(seed)
    nx, ny = int(rng.integers(3, 6)), int(rng.integers(3, 5))
    palette = [50, 51, 80, 120, 200, 253, 254, 255] if seed < 16 else [200, 253, 253, 253, 254]
    arr = add_border(rng.choice(palette, size=(ny, nx)).astype(np.uint8))
    inner = interior(nx, ny)
    start = (int(rng.choice(inner)) % nx, int(rng.choice(inner)) // nx)
    goal = (int(rng.choice(inner)) % nx, int(rng.choice(inner)) // nx)
    return arr, start, goal, bool(rng.integers(2))


def _propagation_is_the_specs(arr, start, goal, astar) -> None:
    D, terms, sp, _ = _run(arr, start, goal, astar)
    ref = plan(arr, start, goal, astar=astar, record_trace=True)
    assert [_bits(concrete(p)) for p in sp.potential] == [_bits(v) for v in ref.potential.ravel()]
    assert bool(concrete(sp.start_reached)) == ref.start_reached
    assert sp.cycles == ref.cycles and sp.trace == ref.trace.tolist()
    _terms_hold(arr, D, terms, sp.potential)


@pytest.mark.parametrize("seed", range(28))
def test_the_checks_propagation_is_the_specs_and_its_terms_hold(seed):
    _propagation_is_the_specs(*_case(seed))


@pytest.mark.parametrize("seed", [5, 6])
def test_the_checks_propagation_on_a_5x5_map(seed):
    """A 3x3 interior: longer traces, several pushes per update, both buffers in use."""
    rng = np.random.default_rng(seed)
    arr = add_border(rng.choice([50, 51, 120, 200, 253], size=(5, 5)).astype(np.uint8))
    arr[1, 1] = arr[2, 2] = 60
    _propagation_is_the_specs(arr, (1, 1), (2, 2), bool(seed % 2))


# 5x5 maps on which sending every push to the next buffer changes the spec's trace, so the
# choice between the next and the overflow buffer is exercised (found by search over seeds)
SPLIT_MAPS = [
    ([[200, 120, 120], [200, 120, 200], [200, 200, 120]], (1, 1), (3, 3), True),
    ([[50, 120, 200], [50, 120, 253], [253, 50, 200]], (1, 3), (3, 1), False),
]


@pytest.mark.parametrize("inner, start, goal, astar", SPLIT_MAPS)
def test_the_checks_propagation_where_pushes_split_between_buffers(inner, start, goal, astar):
    arr = np.full((5, 5), 254, np.uint8)
    arr[1:4, 1:4] = inner
    _propagation_is_the_specs(arr, start, goal, astar)


@pytest.mark.fast
def test_the_path_condition_admits_no_other_potential():
    """Costs as symbolic bytes over 50..253: the run's path condition holds at its map, and with
    the costs fixed to the map's, no model gives a potential other than the spec's."""
    arr = add_border(np.full((4, 4), 60, np.uint8))
    arr[1, 2], arr[2, 1] = 90, 254
    D, terms, sp, _ = _run(arr, (1, 1), (2, 2), True)
    ref = plan(arr, (1, 1), (2, 2), astar=True, record_trace=False).potential.ravel()
    assert D.branches, "the box leaves no branch open: the test would not test the path condition"
    fixed = [terms[k] == int(arr.flat[k]) for k in terms]
    s = z3.Solver()
    s.add(*D.branches, *fixed)
    assert s.check() == z3.sat
    S = D.S
    s.add(z3.Or(*[z3.Not(z3.fpEQ(p.term, S.f32const(float(ref[k])))) for k, p in enumerate(sp.potential)
                  if isinstance(p, V)]))
    assert s.check() == z3.unsat


def _extraction_case(seed: int):
    rng = np.random.default_rng(1000 + seed)
    nx, ny = int(rng.integers(3, 5)), int(rng.integers(3, 5))
    if seed % 3 == 0:
        nx, ny = 5, 4  # room for gradient steps (an interior cell whose ring is all reached)
    arr = add_border(rng.choice([50, 60, 120, 200, 253, 254], size=(ny, nx)).astype(np.uint8))
    inner = interior(nx, ny)
    s, g = int(rng.choice(inner)), int(rng.choice(inner))
    return arr, (s % nx, s // nx), (g % nx, g // nx), bool(seed % 2)


def _whole_run_is_the_specs(arr, start, goal, astar):
    from navfn_smt.check import properties as P

    D, terms, sp, ex = _run(arr, start, goal, astar)
    ref = P.run(arr, start, goal, astar)
    assert exit_name(ex.exit) == ref.exit
    assert [(_bits(concrete(x)), _bits(concrete(y))) for x, y in ex.path] == \
        [(_bits(x), _bits(y)) for x, y in ref.path.tolist()]
    _terms_hold(arr, D, terms, [v for point in ex.path for v in point])
    return ref


@pytest.mark.parametrize("seed", range(16))
def test_the_checks_whole_run_is_the_specs_and_its_terms_hold(seed):
    """Propagation and calcPath: the exit and every path point bit for bit, terms included."""
    _whole_run_is_the_specs(*_extraction_case(seed))


GRADIENT_MAPS = [  # 6x5 maps on which calcPath takes a gradient step (a point off the cell centres)
    ([[50, 50, 120, 80], [80, 120, 80, 80], [120, 60, 120, 80]], True),
]


@pytest.mark.parametrize("inner, astar", GRADIENT_MAPS)
def test_the_checks_whole_run_with_gradient_steps(inner, astar):
    """calcPath's gradient step as terms (interpolation, normalisation, offset overflow) between
    grid-following steps: the exit and every path point bit for bit, terms included."""
    arr = np.full((5, 6), 254, np.uint8)
    arr[1:4, 1:5] = inner
    ref = _whole_run_is_the_specs(arr, (2, 3), (3, 1), astar)
    assert ref.exit == "near_goal" and any(x % 1 for x, _ in ref.path.tolist())  # a gradient step


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
    inner = interior(nx, ny)
    case = Case(nx, ny, frozenset(k for k in inner if arr.flat[k] >= COST_OBS), start, goal, astar)
    conc = {k: int(arr.flat[k]) for k in inner if k not in case.lethal}
    runs = {}
    for semantics, arith in FP32_SEMANTICS.items():
        D, _, sp, ex = _symbolic_run(case, conc, 50, 253, DOMAINS[semantics])
        ref = P.run(arr, start, goal, astar, arith=arith)
        pot = [_bits(concrete(p)) for p in sp.potential]
        assert pot == [_bits(v) for v in ref.potential.ravel()], semantics
        assert exit_name(concrete(ex.exit)) == ref.exit, semantics
        pts = [(concrete(x), concrete(y)) for x, y in ex.path]
        assert [(_bits(x), _bits(y)) for x, y in pts] == [(_bits(x), _bits(y)) for x, y in ref.path.tolist()]
        runs[semantics] = (pot, ref.exit, ref.path.tobytes())
    assert any(r != runs["fp32"] for r in runs.values()), "the arithmetics plan this map alike"
