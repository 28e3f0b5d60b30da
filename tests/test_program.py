"""The proofs over arrays run the spec's own propagation (smt/program.py): the run yields the
segments of its control graph, the predicates stated on it cover every one, and a step of the spec
broken on purpose breaks the condition built from it (the conditions read the spec's code, not a
copy)."""

import pytest
import z3

from navfn_smt.proofs import buffers, fallback, frontier, induction, queued
from navfn_smt.proofs.buffers import Map
from navfn_smt.smt import program
from navfn_smt.smt.domains import DOMAINS
from navfn_smt.spec import kernels as K
from navfn_smt.spec import propagation as P

pytestmark = pytest.mark.fast


def real():
    return DOMAINS["real"]()


def holds(D, built, seconds=60) -> str:
    """The verdict of the condition ``built`` = (pre, claim) of domain ``D`` (its assumptions too)."""
    pre, claim = built
    s = z3.Solver()
    s.set("timeout", seconds * 1000)
    s.add(pre, *D.assumptions, z3.Not(claim))
    r = s.check()
    return "proved" if r == z3.unsat else "refuted" if r == z3.sat else "unknown"


@pytest.mark.parametrize("astar", [False, True], ids=["dijkstra", "astar"])
def test_a_run_of_propagate_yields_the_segments_of_its_control_graph(astar):
    D = real()
    segs = program.segments(D, Map(D), astar)
    assert set(segs) == set(program.SEGMENTS)
    update = segs[("update", "update")]
    assert len(update.cells) >= 5 and update.slots  # the updated cell, its four neighbours, the slots pushed to




STATED_ON_THE_RUN = {  # predicate: the modules of its obligations
    "BuffersInductive": (buffers,), "PositionSafeAndProgressInductive": (induction,),
    "ReachedAndBufferedInductive": (buffers,), "FrontierInductive": (frontier,),
    "FallbackPath": (fallback,), "QueuedStartReached": (queued,),
}
WHOLE_RUN = ("BuffersInductive", "PositionSafeAndProgressInductive", "ReachedAndBufferedInductive",
             "FrontierInductive", "FallbackPath")  # invariants of the whole run (FallbackPath: its floor invariant)


@pytest.mark.parametrize("predicate", sorted(STATED_ON_THE_RUN))
def test_each_predicate_on_the_run_asks_every_segment_of_it_and_assumes_something_satisfiable(monkeypatch, predicate):
    """Each invariant of the whole run is asked of every segment (so its loops are machine-checked,
    none read off the code), and no condition's premises are contradictory (a proof of nothing)."""
    from navfn_smt.proofs import PREDICATES

    asked, premises = set(), []
    real_condition = program.condition

    def spy(D, m, seg, *args, **kw):
        asked.add((seg.source, seg.target))
        pre, claim = real_condition(D, m, seg, *args, **kw)
        premises.append((D, pre))
        return pre, claim

    modules = STATED_ON_THE_RUN[predicate]
    for module in (buffers, induction, frontier, queued, fallback):
        if hasattr(module, "condition"):
            monkeypatch.setattr(module, "condition", spy)
    links = next(p for p in PREDICATES if p.name == predicate).links
    built = 0
    for module in modules:
        for name in links:
            ob = getattr(module, name, None)
            if ob is not None and getattr(ob, "predicate", None) == predicate:
                ob.build(real())
                built += 1
    assert built and premises
    if predicate in WHOLE_RUN:
        assert asked == set(program.SEGMENTS)
    for D, pre in premises:
        s = z3.Solver()
        s.set("timeout", 60000)
        s.add(pre, *D.assumptions)
        assert s.check() == z3.sat


def test_the_conditions_hold_on_the_spec_as_it_is():
    D = real()
    for source, target in program.SEGMENTS:
        assert holds(D, buffers.buffer_condition(D, source, target)) == "proved", (source, target)


def test_a_push_that_forgets_its_flag_breaks_the_buffer_invariant(monkeypatch):
    real_push = K.push

    def forgetful(D, n, ns, pending, cost, fill, capacity):
        admitted, dropped, _ = real_push(D, n, ns, pending, cost, fill, capacity)
        return admitted, dropped, pending  # the flag is not set

    monkeypatch.setattr(K, "push", forgetful)
    D = real()
    assert holds(D, buffers.buffer_condition(D, "update", "update")) == "refuted"
    assert holds(D, buffers.buffer_condition(D, "setup", "cycle")) == "refuted"


def test_a_swap_that_keeps_the_old_next_buffer_breaks_the_buffer_invariant(monkeypatch):
    monkeypatch.setattr(program.Slots, "emptied", lambda self: self)
    D = real()
    assert holds(D, buffers.buffer_condition(D, "update exit", "cycle")) == "refuted"


def test_an_update_that_writes_a_neighbour_breaks_the_potential_invariant(monkeypatch):
    real_update = P.update_cell

    def stray(st, n, astar=False, start=(0, 0)):
        real_update(st, n, astar, start)
        st.potential[n + 1] = st.D.f32const(0.0)  # a second write, to a cell the invariant does not allow

    monkeypatch.setattr(P, "update_cell", stray)
    D = real()
    assert holds(D, induction.invariant_condition(D, "update", "update", where="other")) == "refuted"


def test_free_floats_leave_every_float_result_open():
    D = DOMAINS["fp32"]()
    F = program.FreeFloats(D)
    x, y = D.f32("x"), D.f32("y")
    s = z3.Solver()
    s.add(x == D.f32const(1.0), y == D.f32const(2.0), z3.Not(F.add(x, y) == D.add(x, y)))
    assert s.check() == z3.sat  # the sum is free: a run in F covers every rounding
    assert F.add_int(D.int32("a"), 1).sort() == D.int32("a").sort()  # ints are computed as in D


def test_the_two_array_models_agree_on_concrete_values():
    """The operations the spec's steps use mean the same in the concrete model (lists) and in the
    proofs' (SMT arrays): filled arrays, writes, a buffer's conditional append, the choice between
    two buffers, a new fill, emptying; compared value by value (fills, filled slots, flags; the
    ghosts are the invariants' business) after a random sequence."""
    import random

    D = real()
    m = Map(D)
    run = program.Program(D, m, astar=False)
    rng = random.Random(7)
    for trial in range(20):
        conc = P.PropagationState(nx=3, ny=3, costs=[50] * 9)
        conc.pending, conc.cur, conc.nxt = conc.filled(conc.pending, False), P.Buffer(), P.Buffer()
        sym = program.ArrayState(run)
        sym.pending = sym.filled(sym.pending, False)
        empty = program.Slots(run, z3.K(program.cell_sort(D), program.int_const(D, 0)), program.int_const(D, 0),
                              z3.K(program.cell_sort(D), False), z3.K(program.cell_sort(D), program.int_const(D, 0)))
        sym.cur, sym.nxt = empty, empty.emptied()
        for _ in range(12):
            op, n, flag = rng.choice("awpfe"), rng.randrange(9), rng.random() < 0.6
            if op == "a":
                conc.cur.append_if(flag, n)
                sym.cur.append_if(z3.BoolVal(flag), program.int_const(D, n))
            elif op == "w":
                conc.pending[n] = flag
                sym.pending[program.int_const(D, n)] = z3.BoolVal(flag)
            elif op == "p":
                conc.cur, conc.nxt = conc.pick(flag, conc.nxt, conc.cur), conc.pick(flag, conc.cur, conc.nxt)
                sym.cur, sym.nxt = sym.pick(z3.BoolVal(flag), sym.nxt, sym.cur), sym.pick(z3.BoolVal(flag), sym.cur, sym.nxt)
            elif op == "f":
                f = rng.randrange(conc.cur.fill + 1)
                conc.cur, sym.cur = conc.cur.with_fill(f), sym.cur.with_fill(program.int_const(D, f))
            else:
                conc.cur, sym.cur = conc.cur.emptied(), sym.cur.emptied()
        value = lambda t: z3.simplify(t)  # noqa: E731
        for c, s in ((conc.cur, sym.cur), (conc.nxt, sym.nxt)):
            assert value(s.fill).as_long() == c.fill
            assert [value(s.slots[program.int_const(D, k)]).as_long() for k in range(c.fill)] == c.cells
        assert [z3.is_true(value(sym.pending[program.int_const(D, q)])) for q in range(9)] == conc.pending
