"""``check``'s verdicts held against exhaustive concrete runs of the reference spec.

Where the space of maps is small enough to enumerate (every layout, every start and goal,
every cost of a narrow range), the spec runs every map and judges every property; the
checker must then say ``proved`` exactly when no map breaks the property, and its
counterexample must be one of the maps that do.  A proof that a concrete map refutes is
the worst bug the checker can have: these tests are its guard.
"""

from __future__ import annotations

import itertools

import numpy as np
import pytest
import z3

from navfn_smt.check import properties as P
from navfn_smt.check.bounded import CHECKABLE, Case, _symbolic_run, cases, explore
from navfn_smt.check.concolic import V, concrete
from navfn_smt.check.encoding import interior
from navfn_smt.check.runner import CheckRequest, check_one_size
from navfn_smt.smt.domains import FPDomain
from navfn_smt.smt.evaluate import value
from navfn_smt.under_test import ORIGINAL


def _exhaustive(nx, ny, lo, hi, modes):
    """Per property, the set of cases (layout, start, goal, mode) some map of the range breaks."""
    broken = {n: set() for n in CHECKABLE}
    for case in cases(nx, ny, modes):
        free = [k for k in interior(nx, ny) if k not in case.lethal]
        for values in itertools.product(range(lo, hi + 1), repeat=len(free)):
            r = P.run(case.costs_array(dict(zip(free, values))), case.start, case.goal, case.astar)
            for n in CHECKABLE:
                if P.judge(n, r):
                    broken[n].add(case)
    return broken


@pytest.mark.parametrize("nx, ny, lo, hi", [(3, 4, 50, 90), (4, 3, 200, 253), (3, 5, 120, 128)])
def test_verdicts_match_exhaustive_runs(nx, ny, lo, hi):
    modes = (True, False)
    broken = _exhaustive(nx, ny, lo, hi, modes)
    got = check_one_size(CheckRequest(CHECKABLE, modes, lo, hi, timeout=60), nx, ny)
    for n in CHECKABLE:
        r = got[n]
        assert r.cases_unknown == 0
        assert r.status == ("refuted" if broken[n] else "proved"), n
        if broken[n]:
            cx = r.counterexample
            assert any(c.start == tuple(cx["start"]) and c.goal == tuple(cx["goal"]) and c.mode == cx["mode"]
                       for c in broken[n])


def test_4x4_cases_match_exhaustive_runs():
    """Each 4x4 case with three passable cells of four costs: per case, the checker's verdict
    per property equals the exhaustive one."""
    lo, hi = 100, 103
    for case in [Case(4, 4, frozenset({5}), (2, 2), (1, 2), True), Case(4, 4, frozenset({10}), (1, 1), (2, 1), False),
                 Case(4, 4, frozenset({6}), (1, 2), (2, 2), True), Case(4, 4, frozenset({9}), (2, 1), (1, 1), False)]:
        free = [k for k in interior(4, 4) if k not in case.lethal]
        broken = set()
        for values in itertools.product(range(lo, hi + 1), repeat=len(free)):
            r = P.run(case.costs_array(dict(zip(free, values))), case.start, case.goal, case.astar)
            broken |= {n for n in CHECKABLE if P.judge(n, r)}
        res = explore(case, CHECKABLE, lo, hi, FPDomain, timeout=60)
        for n in CHECKABLE:
            assert res.results[n].status == ("refuted" if n in broken else "holds"), (case, n)


@pytest.mark.parametrize("seed", range(6))
def test_intervals_hold_every_value_of_the_box(seed):
    """The concolic domain's values are the spec's, and its intervals are sound: each value's
    path-wise term, evaluated at other maps of the cost box, stays inside the interval."""
    rng = np.random.default_rng(seed)
    nx, ny = 4, 4
    inner = interior(nx, ny)
    lo, hi = sorted(int(v) for v in rng.integers(50, 254, 2))
    case = Case(nx, ny, frozenset(), (1 + seed % 2, 2), (2, 1), bool(seed % 2))
    conc = {k: int(rng.integers(lo, hi + 1)) for k in inner}
    D, costs, sp, ex = _symbolic_run(case, conc, lo, hi, FPDomain)
    ref = P.run(case.costs_array(conc), case.start, case.goal, case.astar)
    symbolic = [(k, p) for k, p in enumerate(sp.potential) if isinstance(p, V)]
    assert symbolic
    for k, p in enumerate(sp.potential):
        v = p.conc if isinstance(p, V) else p
        assert np.float32(v).tobytes() == ref.potential.ravel()[k].tobytes()
    for _ in range(20):
        point = {costs[k].term: z3.BitVecVal(int(rng.integers(lo, hi + 1)), 8) for k in inner}
        for k, p in symbolic:
            got = value(z3.simplify(z3.substitute(p.term, *point.items())))
            assert p.lo <= got <= p.hi, (k, p.lo, got, p.hi)


def test_exhaustive_evaluation_equals_z3():
    """The numpy evaluator of the last-resort exhaustive decision gives Z3's value on every query
    an exploration asks, at random maps of the box; and decides small boxes as the solver does."""
    from navfn_smt.check import bounded as B
    from navfn_smt.check import exhaustive as X

    asked = []

    def recording(a, v, t):
        asked.append((a, v))
        return B.solve_bitwuzla(a, v, t)

    # every query through ``solve``: no incremental solver, no exhaustive evaluation first
    explore(Case(4, 4, frozenset({10}), (2, 1), (1, 2), True), CHECKABLE, 50, 253, FPDomain, timeout=30,
            solve=recording, incremental=False, exhaustive_limit=0)
    assert asked
    rng = np.random.default_rng(0)
    for a, v in asked:
        pts = [{k: int(rng.integers(50, 254)) for k in v} for _ in range(10)]
        env = {str(v[k]): np.array([p[k] for p in pts]) for k in v}
        memo = {}
        for t in a:
            got = X.evaluate(t, env, len(pts), memo)
            for i, p in enumerate(pts):
                want = z3.is_true(z3.simplify(z3.substitute(t, *[(v[k], z3.BitVecVal(p[k], 8)) for k in v])))
                assert bool(got[i]) == want
    for a, v in asked[:6]:
        small = {k: (100, 111) for k in v}
        box = [z3.And(z3.UGE(x, 100), z3.ULE(x, 111)) for x in v.values()]
        assert X.solve(a + box, v, small)[0] == B.solve_bitwuzla(a + box, v, 30)[0]


def test_the_exhaustive_fused_multiply_add_is_rounded_once():
    """The evaluator's fp.fma (the builds that contract, ``check --target aarch64``) is Z3's, float
    and double: on random operands, and where a product and a sum each rounded in double would
    land on a float tie and round it the wrong way (``(1 + 2**-12)**2 + 2**-60``)."""
    from navfn_smt.check import exhaustive as X
    from navfn_smt.smt.domains import F32, F64, RNE

    rng = np.random.default_rng(1)
    for sort, dt in ((F32, np.float32), (F64, np.float64)):
        a, b, c = (rng.normal(0, 1e3, 40).astype(dt) for _ in range(3))
        a[0], b[0], c[0] = 1 + 2.0 ** -12, 1 + 2.0 ** -12, 2.0 ** -60
        names = [z3.FP(n, sort) for n in "abc"]
        env = {"a": a, "b": b, "c": c}
        got = X.evaluate(z3.fpFMA(RNE, *names), env, 40, {})
        for i in range(40):
            vals = [z3.FPVal(float(x[i]), sort) for x in (a, b, c)]
            assert got[i].tobytes() == dt(value(z3.simplify(z3.fpFMA(RNE, *vals)))).tobytes(), (dt, i)
    tie = np.float32(1 + 2.0 ** -12)
    assert np.float32(np.float64(tie) * np.float64(tie) + 2.0 ** -60) != X.evaluate(
        z3.fpFMA(RNE, *[z3.FP(n, F32) for n in "abc"]), {"a": np.array([tie]), "b": np.array([tie]),
                                                          "c": np.array([np.float32(2.0 ** -60)])}, 1, {})[0]


def test_check_command(tmp_path, capsys):
    """The command: verdicts, what was enumerated and solved, the induction, the saved
    counterexample (replayed) in JSON; exit 1 because valid-path is refuted; bad input exits 2."""
    import json

    from navfn_smt.cli import main
    from navfn_smt.search.counterexamples import replay

    out, rep = tmp_path / "cx", tmp_path / "r.json"
    assert main(["check", "all", "--size", "3", "4", "--out", str(out), "--json", str(rep)]) == 1
    doc = json.loads(rep.read_text())
    status = {r["property"]: r["status"] for r in doc["results"]}
    assert status == {"queues-obstacle-free": "proved", "no-path-before-start-potential": "proved",
                      "valid-path": "refuted", "start-reached": "proved", "complete": "proved"}
    assert doc["results"][0]["enumerated"]["cases"] == 32
    assert doc["every_size_by_induction"]["queues-obstacle-free"]["status"] == "proved"
    saved = list(out.iterdir())
    assert [d.name for d in saved] == ["valid-path-astar-3x4"]
    again = replay(saved[0])
    assert again["detail"] and not any(again["golden"].values())  # still violated; goldens bit-equal
    for bad in (["--costs", "9"], ["--size", "2", "4"], ["--start", "0", "1"], ["--semantics", "real"]):
        assert main(["check", "complete", "--size", "3", "4", *bad]) == 2


def test_the_propagation_run_is_the_whole_runs_propagation():
    """Alone, start-reached and queues-obstacle-free are judged on the run without calcPath
    (``run_of``): its path condition must be the whole run's up to calcPath's first branch, term
    for term, and the properties' values the same, on seeded cost vectors of several cases."""
    from navfn_smt.check.bounded import _propagation_run, property_value, run_of

    assert run_of(["start-reached", "queues-obstacle-free"]) is _propagation_run
    assert run_of(["start-reached", "complete"]) is _symbolic_run
    rng = np.random.default_rng(3)
    for case in [Case(4, 5, frozenset(), (1, 1), (2, 3), False), Case(5, 4, frozenset({11}), (3, 2), (1, 1), True),
                 Case(4, 4, frozenset(), (2, 2), (1, 1), True), Case(3, 6, frozenset({10}), (1, 1), (1, 4), False)]:
        free = [k for k in interior(case.nx, case.ny) if k not in case.lethal]
        for _ in range(5):
            conc = {k: int(rng.integers(50, 254)) for k in free}
            Dp, costs_p, sp_p, ex_p = _propagation_run(case, conc, 50, 253, FPDomain)
            Dw, costs_w, sp_w, ex_w = _symbolic_run(case, conc, 50, 253, FPDomain)
            n = len(Dp.branches)
            assert n <= len(Dw.branches)
            assert all(a.eq(b) for a, b in zip(Dp.branches, Dw.branches[:n])), (case, conc)
            for name in ("start-reached", "queues-obstacle-free"):
                vp = property_value(name, Dp, case, costs_p, sp_p, ex_p)
                vw = property_value(name, Dw, case, costs_w, sp_w, ex_w)
                assert bool(concrete(vp)) == bool(concrete(vw))


def test_the_propagation_run_refutes_a_known_unreached_start():
    """The 14-cell Dijkstra map whose connected start stays unreached: explored alone from its
    costs, start-reached is refuted on the first control path."""
    case, conc = _case_of_map("unreached-dijkstra-9x4", "dijkstra")
    res = explore(case, ["start-reached"], 50, 253, FPDomain, timeout=30, initial=conc)
    assert res.results["start-reached"].status == "refuted"
    assert res.results["start-reached"].counterexample == conc


def _case_of_map(name: str, mode: str):
    """The case and costs of a saved counterexample map (its first start/goal pair), in ``mode``."""
    from conftest import DATA
    from navfn_smt.maps.suite import load_map
    from navfn_smt.spec.constants import COST_OBS

    smap = load_map(DATA / "counterexamples" / name)
    sx, sy, gx, gy = (int(v) for v in smap.cases[0])
    ny, nx = smap.costs.shape
    lethal = frozenset(k for k in interior(nx, ny) if smap.costs.flat[k] >= COST_OBS)
    return Case(nx, ny, lethal, (sx, sy), (gx, gy), mode == "astar"), \
        {k: int(smap.costs.flat[k]) for k in interior(nx, ny) if k not in lethal}


UNREACHED_MAPS = [("unreached-astar-5x7", "astar"), ("unreached-astar-7x8", "astar"),
                  ("unreached-dijkstra-7x8", "dijkstra"), ("unreached-dijkstra-9x4", "dijkstra"),
                  ("start-reached-astar-7x7", "astar"), ("start-reached-dijkstra-7x7", "dijkstra")]


@pytest.mark.parametrize("name, mode", UNREACHED_MAPS)
def test_an_unreached_start_is_never_queued_for_certain(name, mode):
    """QueuedStartReached: on every saved map whose connected start stays unreached (the spec
    says so), the encoded run never marks the start's reach certain; a mark there would let
    the exploration skip the very branches that lead to such a map."""
    from navfn_smt.check.bounded import _propagation_run

    case, conc = _case_of_map(name, mode)
    r = P.run(case.costs_array(conc), case.start, case.goal, case.astar)
    assert P.judge("start-reached", r)  # the map is a counterexample
    sp = _propagation_run(case, conc, 50, 253, FPDomain)[2]
    assert sp.start_certain is None


@pytest.mark.parametrize("nx, ny", [(4, 5), (5, 4), (3, 10), (9, 4), (5, 7), (7, 8)])
def test_a_start_queued_for_certain_is_reached(nx, ny):
    """QueuedStartReached on seeded maps (random lethal cells and costs, both modes): when the
    encoded run marks the start's reach certain, the mark lies within its branches and the
    spec reaches the start; at least 10 of the 60 seeded runs of each size are marked."""
    from navfn_smt.check.bounded import _propagation_run
    from navfn_smt.check.runner import replay
    from navfn_smt.spec.constants import POT_HIGH

    rng = np.random.default_rng(nx * 100 + ny)
    inner = interior(nx, ny)
    marked = 0
    for i in range(60):
        lethal = frozenset(k for k in inner if rng.random() < 0.2)
        free = [k for k in inner if k not in lethal]
        if len(free) < 2:
            continue
        s, g = rng.choice(free, 2, replace=False)
        case = Case(nx, ny, lethal, (int(s) % nx, int(s) // nx), (int(g) % nx, int(g) // nx), bool(i % 2))
        conc = {k: int(rng.choice([50, 51, 100, 200, 253]) if i % 3 else rng.integers(50, 254)) for k in free}
        D, _, sp, _ = _propagation_run(case, conc, 50, 253, FPDomain)
        if sp.start_certain is None:
            continue
        marked += 1
        assert 0 <= sp.start_certain <= len(D.branches)
        _, run, why = replay(case, conc, "start-reached")
        assert run.start_potential < POT_HIGH and why is None, (case, conc)
    assert marked >= 10


def test_shortcut_answers_recheck_and_change_no_verdict(monkeypatch):
    """The flips the exploration decides without asking: each unsat core it learns is unsat on
    the box with its flipped branch negated (asked again of bitwuzla), each path it finds by a
    sampled map re-checks as a certificate's path (the flip's witness is a recorded seed), and
    the verdict is that of the exploration that asks every flip."""
    from navfn_smt.check import bounded as B
    from navfn_smt.check.certificate import check_case
    from navfn_smt.smt.codec import free_constants

    learned = []
    learn = B._PathCores.learn

    def recording(self, j, core):
        core = list(core)
        learned.append((self.pc, j, core))
        learn(self, j, core)

    monkeypatch.setattr(B._PathCores, "learn", recording)
    case, names = Case(4, 5, frozenset(), (1, 1), (2, 3), True), ["start-reached"]
    fast = explore(case, names, 50, 253, FPDomain, timeout=60)
    plain = explore(case, names, 50, 253, FPDomain, timeout=60, shortcuts=False)
    assert fast.cached_unsat and fast.sampled_sat and not plain.cached_unsat and not plain.sampled_sat
    assert fast.results["start-reached"].status == plain.results["start-reached"].status == "holds"
    assert check_case(case, names, 50, 253, fast.log, 60, ORIGINAL, order=("bitwuzla",))["problems"] == []  # cvc5: 8x slower
    assert learned
    for pc, j, core in learned:
        query = [pc[i] for i in core] + [z3.Not(pc[j])]
        variables = {name: z3.BitVec(name, 8) for name in free_constants(query)}
        box = [z3.And(z3.UGE(v, 50), z3.ULE(v, 253)) for v in variables.values()]
        assert B.solve_bitwuzla(box + query, variables, 60)[0] == "unsat", (j, core)


def test_check_in_aarch64s_arithmetic_finds_the_path_from_an_unreached_start(tmp_path, capsys):
    """``check --target aarch64`` on 4x3: no-path-before-start-potential, proved in x86-64's
    arithmetic, is refuted in arm64's by a map on which the spec in that arithmetic returns a
    path from a start it never reached (the committed path-without-potential-*-4x3-aarch64 are
    such maps); start-reached holds there, and the certificate of the size says its semantics, replays, and an edit of that
    semantics is refused."""
    import gzip
    import json

    from navfn_smt.cli import main
    from navfn_smt.spec.arithmetic import KNOWN
    from navfn_smt.spec.constants import POT_HIGH

    name = "no-path-before-start-potential"
    assert main(["check", name, "--size", "4", "3"]) == 0  # x86-64: proved
    rep, certs = tmp_path / "r.json", tmp_path / "certs"
    certs.mkdir()
    assert main(["check", name, "--size", "4", "3", "--target", "aarch64", "--json", str(rep)]) == 1
    assert "aarch64 arithmetic" in capsys.readouterr().out
    doc = json.loads(rep.read_text())
    assert doc["semantics"] == "fp32@aarch64" and doc["planner"]["arithmetic"] == "aarch64"
    got = {r["property"]: r for r in doc["results"]}
    assert got[name]["status"] == "refuted"
    enumerated = got[name]["enumerated"]  # every case explored: x86-64 decides 8 of 32 by their outside start
    assert enumerated["start_outside_component"] == 0 and enumerated["explored"] == enumerated["cases"] == 32
    cx = got[name]["counterexample"]
    r = P.run(np.array(cx["costs"], np.uint8), tuple(cx["start"]), tuple(cx["goal"]), cx["mode"] == "astar",
              arith=KNOWN["aarch64"])
    assert len(r.path) and r.start_potential >= np.float32(POT_HIGH)
    # a certificate is written for a size whose explored properties hold: start-reached's
    assert main(["check", "start-reached", "--size", "4", "3", "--target", "aarch64", "--certificates", str(certs)]) == 0
    cert = certs / "check-4x3-aarch64.cert.json.gz"
    assert main(["check", "--replay", str(cert), "--solver", "bitwuzla"]) == 0
    header = json.loads(gzip.decompress(cert.read_bytes()))
    assert header["semantics"] == "fp32@aarch64" and header["outside"] == 0
    for other in ("fp32", "fp32@x86-64-v3", "fp32@nowhere"):
        edited = tmp_path / f"edited-{other}.cert.json.gz"
        edited.write_bytes(gzip.compress(json.dumps({**header, "semantics": other}).encode()))
        capsys.readouterr()
        assert main(["check", "--replay", str(edited), "--solver", "bitwuzla"]) == 1, other
        assert "refused" in capsys.readouterr().out
