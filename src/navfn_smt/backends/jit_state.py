"""The spec's array models, compiled: the state the JIT runs the spec's own steps on.

:mod:`navfn_smt.spec.propagation` states ``initCost`` and ``propNavFn*`` once, as steps over a
state with a few operations (arrays filled with one value, a buffer's conditional append, a
choice between two buffers, the loops); :mod:`navfn_smt.spec.extraction` states ``calcPath``
over a trail (the points written, gradCell's stored vectors).  Here those operations are
numba's, on flat arrays the caller owns (:class:`Work`, :class:`TrailWork`): a compiled entry
point makes a view of them (:func:`state_of`, :func:`trail_of`: raw pointers and sizes, a value
without reference counts, so the hot loops pay none) and runs the spec's step functions on it,
compiled as they are (registered below as numba sees the kernels).  So the JIT plans by the
same statement as the reference spec, the check's encoding and the proofs.

The view's fields are the spec's names (``st.potential``, ``st.cur.fill``, ``st.cur_t``, ...);
the counters, the buffers' fills and their roles live in one int array (``ints``), so that a
view written by the spec is read by the caller after the call.

What is only the JIT's: memory reused across cases, the A* heuristic of each offset kept once
computed, a trace array that the caller grows and runs again when it was too short, gradient
arrays zeroed cell by cell after a path, and, for the whole-map sweep, a pause at the end of a
cycle in which watched cells were first reached.
"""

from __future__ import annotations

import operator
from collections import namedtuple

import numpy as np
from llvmlite import ir
from numba import carray, types
from numba.core import cgutils
from numba.extending import (intrinsic, lower_setattr, make_attribute_wrapper, models, overload, overload_attribute,
                             overload_method, register_model)

from ..spec import extraction as E
from ..spec import kernels as K
from ..spec import numeric
from ..spec import planner as PL
from ..spec import propagation as P
from ..spec.constants import POT_HIGH
from .numba_domain import JIT_OPTIONS, NumbaDomainType, jit, jit_inline, returning

# the spec's steps, callable from compiled code as they are (their globals resolve to these)
SPEC_STEPS = (P.init_cost, P.admit, P.push_cur, P.push, P.update_neighbours, P.update_cell, P.end_of_cycle,
              P.run_cycle, P.cycle_runs, P.call_ends_at_the_start, P.propagate, PL.call, E.follow, E.gradient,
              E.near_goal_test, E.iteration_test, E.oscillates, E.follows_the_grid, E.zero_gradient, E.grid_step,
              E.goal_point)
# inlined where called: a call per update cost a quarter of the loop's time, one per gradCell about 15% of calcPath's
INLINED = (P.update_cell, E.gradient)
for _fn in SPEC_STEPS:
    overload(_fn, jit_options=JIT_OPTIONS, inline="always" if _fn in INLINED else "never")(returning(_fn))


@overload(numeric.taken, jit_options=JIT_OPTIONS)
def _taken(D, c):
    """The compiled domain follows every branch as its values say: the condition itself."""
    if isinstance(D, NumbaDomainType):
        return lambda D, c: c


# the entries of a state's ``ints``: the counters of the spec's state (cycles run, cells
# updated, pushes dropped), trace entries wanted, the sweep's pause (watched cells reported,
# cycles left: negative, no limit; whether the loop paused), the last cycle's buffer and cell
# count (-1: no cycle ended since the last test), the roles (the row of slots that is the current, next and overflow buffer), the fill
# of each row, the map's size and the buffers' capacity
(CYCLES, UPDATES, DROPPED, TLEN, NNEW, BUDGET, PAUSED, LAST_N, LAST_ROW, ROLE_CUR, ROLE_NXT, ROLE_OVER, FILL0, _FILL1,
 _FILL2, NX, NY, CAPACITY) = range(18)
NINTS = 18
INT_FIELDS = {"cycles": CYCLES, "updates": UPDATES, "dropped": DROPPED, "tlen": TLEN, "nnew": NNEW, "budget": BUDGET,
              "last_n": LAST_N}
ROLES = {"cur": ROLE_CUR, "nxt": ROLE_NXT, "over": ROLE_OVER}

# what a state views, owned by the caller: the costs (border included), potentials, pending
# flags, the three rows of slots (3, capacity), ``ints``, [curT], the trace, A*'s heuristic per
# offset |dx|, |dy| ((nx + 1) * (ny + 1); NaN: not computed), the watched cells (empty: none) and
# the cells reported
Work = namedtuple("Work", "costs potential pending slots ints cur_t trace memo watch newly")
# what a trail views: the points (rows of x, y), gradCell's vectors, the cells whose vector was
# written, and [npath, cells written]
TrailWork = namedtuple("TrailWork", "path gradx grady touched ints")
NPATH, NTOUCHED = range(2)


def new_work(costs: np.ndarray, nx: int, ny: int, capacity: int, trace: np.ndarray, memo: np.ndarray) -> Work:
    """The arrays of a state for an ``nx`` x ``ny`` map of ``costs`` (flat, border included), its
    buffers ``capacity`` slots wide (at most ``nx * ny`` kept: the pending flags keep a buffer from
    holding more)."""
    ns = nx * ny
    width = min(capacity, ns)
    ints = np.zeros(NINTS, np.int64)
    ints[NX], ints[NY], ints[CAPACITY], ints[BUDGET], ints[LAST_N] = nx, ny, width, -1, -1
    ints[ROLE_CUR], ints[ROLE_NXT], ints[ROLE_OVER] = 0, 1, 2
    none = np.empty(0, np.int64)
    return Work(costs, np.empty(ns, np.float32), np.zeros(ns, np.bool_), np.zeros((3, width), np.int64), ints,
                np.zeros(1, np.float32), trace, memo, none, none)


def new_trail_work(ns: int, nmax: int) -> TrailWork:
    """The arrays of a trail for up to ``nmax`` iterations of calcPath on a map of ``ns`` cells."""
    n = max(int(nmax), 0)
    return TrailWork(np.empty((n + 1, 2), np.float32), np.zeros(ns, np.float32), np.zeros(ns, np.float32),
                     np.empty(4 * n + 4, np.int64), np.zeros(2, np.int64))


# ------------------------------------------------------------------------------- the views
class ViewType(types.Type):
    """A view of a namedtuple of arrays (``work``'s type): each array ``a`` as its data pointer
    ``p_a`` and length ``n_a``, the map's size and the buffers' capacity as ints."""

    def __init__(self, domain, work):
        self.domain, self.work = domain, work
        super().__init__(name=f"{type(self).__name__}[{domain}, {work}]")


class StateType(ViewType):
    pass


class TrailType(ViewType):
    pass


class BufferType(types.Type):
    def __init__(self):
        super().__init__(name="JitBuffer")


BUFFER = BufferType()
_I64 = types.CPointer(types.int64)


class CellsType(ViewType):
    """A view of one array (:class:`Cells`) read by index, ``cells[i]``: what calcPath reads the
    potentials through (an array passed to a step pays a reference-count update per call, and
    gradCell is four calls a point)."""


Cells = namedtuple("Cells", "a")


@register_model(StateType)
@register_model(TrailType)
@register_model(CellsType)
class _ViewModel(models.StructModel):
    def __init__(self, dmm, fe_type):
        arrays = zip(fe_type.work.instance_class._fields, fe_type.work.types)
        super().__init__(dmm, fe_type, [("D", fe_type.domain), ("nx", types.int64), ("ny", types.int64),
                                        ("capacity", types.int64)]
                         + [m for name, t in arrays for m in ((f"p_{name}", types.CPointer(t.dtype)),
                                                              (f"n_{name}", types.int64))])


register_model(BufferType)(lambda dmm, fe_type: models.StructModel(dmm, fe_type, [
    ("p_slots", _I64), ("capacity", types.int64), ("p_ints", _I64), ("row", types.int64)]))
for _typ, _work in ((StateType, Work), (TrailType, TrailWork), (CellsType, Cells)):
    for _name in ("D", "nx", "ny", "capacity", *(f"{k}_{f}" for f in _work._fields for k in "pn")):
        make_attribute_wrapper(_typ, _name, _name)
for _name in ("p_slots", "capacity", "p_ints", "row"):
    make_attribute_wrapper(BufferType, _name, _name)


def _view(view_class):
    """The intrinsic ``view(D, work, nx, ny, capacity)`` making a ``view_class`` of ``work``."""

    def typer(typingctx, D, work, nx, ny, capacity):
        def codegen(context, builder, sig, args):
            v = cgutils.create_struct_proxy(sig.return_type)(context, builder)
            v.D = context.get_dummy_value()
            for k, name in ((2, "nx"), (3, "ny"), (4, "capacity")):
                setattr(v, name, context.cast(builder, args[k], sig.args[k], types.int64))
            for i, (name, arrty) in enumerate(zip(work.instance_class._fields, work.types)):
                arr = cgutils.create_struct_proxy(arrty)(context, builder, value=builder.extract_value(args[1], i))
                setattr(v, f"p_{name}", arr.data)
                setattr(v, f"n_{name}", builder.extract_value(arr.shape, 0))
            return v._getvalue()

        return view_class(D, work)(D, work, nx, ny, capacity), codegen

    return intrinsic(typer)


_state, _trail, _cells = _view(StateType), _view(TrailType), _view(CellsType)
overload(operator.getitem, jit_options=JIT_OPTIONS)(
    lambda cells, i: (lambda cells, i: cells.p_a[i]) if isinstance(cells, CellsType) else None)


@intrinsic
def _buffer(typingctx, slots, capacity, ints, row):
    def codegen(context, builder, sig, args):
        b = cgutils.create_struct_proxy(BUFFER)(context, builder)
        b.p_slots, b.capacity, b.p_ints, b.row = args
        return b._getvalue()

    return BUFFER(slots, capacity, ints, row), codegen


@jit_inline
def state_of(D, work):
    """The state viewing ``work`` (a :class:`Work`), computing in the domain ``D``; the arrays must
    outlive it (a compiled entry point makes it from its arguments)."""
    return _state(D, work, work.ints[NX], work.ints[NY], work.ints[CAPACITY])


@jit_inline
def cells_of(D, array):
    """The cells of a one-dimensional ``array``, which must outlive them."""
    return _cells(D, Cells(array), 0, 0, 0)


@jit_inline
def trail_of(D, trail):
    """The trail viewing ``trail`` (a :class:`TrailWork`), computing in the domain ``D``."""
    return _trail(D, trail, 0, 0, 0)


@intrinsic
def poke(typingctx, pointer, index, value):
    """``pointer[index] = value``, as a call: numba's dead-code removal does not see that a
    store through a raw pointer is a write to memory others read, and drops a ``p[i] = v``."""

    def codegen(context, builder, sig, args):
        p, i, v = args
        builder.store(context.cast(builder, v, sig.args[2], sig.args[0].dtype), builder.gep(p, [i]))

    return types.void(pointer, index, value), codegen


def _setter(pointer: str, index: int, of_role: bool = False):
    """Lowering of ``x.attr = v``: ``v`` (a buffer: its row) stored at ``x.<pointer>[index]``."""

    def impl(context, builder, sig, args):
        typ, valty = sig.args
        at = getattr(cgutils.create_struct_proxy(typ)(context, builder, value=args[0]), pointer)
        value = (cgutils.create_struct_proxy(valty)(context, builder, value=args[1]).row if of_role else
                 context.cast(builder, args[1], valty, typ.work.types[typ.work.instance_class._fields.index(
                     pointer[2:])].dtype))
        builder.store(value, builder.gep(at, [ir.Constant(ir.IntType(64), index)]))

    return impl


def _in_place(context, builder, sig, args):
    """``st.potential = st.filled(st.potential, v)``: filled wrote the array itself."""


def _attribute(typ, name, impl, setter=None) -> None:
    """``typ.name`` in compiled code: ``impl(x)``; ``setter`` lowers ``typ.name = v``."""
    overload_attribute(typ, name, jit_options=JIT_OPTIONS)(returning(impl))
    if setter is not None:
        lower_setattr(typ, name)(setter)


def _methods(typ, **impls) -> None:
    """``typ``'s methods in compiled code, each ``impl(x, *args)``."""
    for name, impl in impls.items():
        overload_method(typ, name, jit_options=JIT_OPTIONS)(returning(impl))


for _name, _index in INT_FIELDS.items():
    _attribute(StateType, _name, eval(f"lambda st: st.p_ints[{_index}]"), _setter("p_ints", _index))  # noqa: S307
for _name, _index in ROLES.items():
    _attribute(StateType, _name, eval(f"lambda st: _buffer(st.p_slots, st.capacity, st.p_ints, "  # noqa: S307
                                      f"st.p_ints[{_index}])"), _setter("p_ints", _index, of_role=True))
_attribute(StateType, "paused", lambda st: st.p_ints[PAUSED] != 0, _setter("p_ints", PAUSED))
_attribute(StateType, "cur_t", lambda st: st.p_cur_t[0], _setter("p_cur_t", 0))
_attribute(StateType, "domain", lambda st: st.D)
_attribute(StateType, "ns", lambda st: st.n_potential)
_attribute(StateType, "potential", lambda st: carray(st.p_potential, st.n_potential), _in_place)
_attribute(StateType, "pending", lambda st: carray(st.p_pending, st.n_potential), _in_place)
_attribute(StateType, "costs", lambda st: carray(st.p_costs, st.n_potential))


# --------------------------------------------------------------------------------- buffers
def _append_if(b, admitted, n):
    if admitted:  # kernels.push admits a cell only below the capacity (the row's width)
        f = b.p_ints[FILL0 + b.row]
        poke(b.p_slots, b.row * b.capacity + f, n)
        poke(b.p_ints, FILL0 + b.row, f + 1)


def _with_fill(b, fill):
    """Its first ``fill`` cells (in place: the swap gives each row one new role)."""
    poke(b.p_ints, FILL0 + b.row, fill)
    return b


def _emptied(b):
    poke(b.p_ints, FILL0 + b.row, 0)
    return b


_attribute(BufferType, "fill", lambda b: b.p_ints[FILL0 + b.row])
_methods(BufferType, cell=lambda b, k: b.p_slots[b.row * b.capacity + k], append_if=_append_if, with_fill=_with_fill,
         emptied=_emptied)


# -------------------------------------------------------------------------- state's methods
def _filled(st, array, value):
    """``array`` with every cell ``value``, written in place."""
    array[:] = value
    return array


def _heuristic(st, n, start):
    """A*'s heuristic from cell ``n`` to the start, kept per offset ``|dx|, |dy|`` (hypot(x, y) is
    hypot(|x|, |y|), C11 F.10.4.3) up to a start one past the map's edge."""
    nx = st.nx
    y = np.int64(np.uint64(n) // np.uint64(nx))  # one unsigned division: a cell of the map
    ddx, ddy = n - y * nx - start[0], y - start[1]
    if abs(ddx) > nx or abs(ddy) > st.ny:
        return K.astar_heuristic(st.D, ddx, ddy)
    i = abs(ddy) * (nx + 1) + abs(ddx)
    h = st.p_memo[i]
    if h != h:
        h = K.astar_heuristic(st.D, ddx, ddy)
        poke(st.p_memo, i, h)
    return h


def _note_drop(st, dropped):
    if dropped:
        poke(st.p_ints, DROPPED, st.p_ints[DROPPED] + 1)


def _record_cycle(st, cycle, cycles, trace_hook, record_trace):
    """A cycle starts: counted, and the current buffer's cells traced while the trace has room."""
    ints = st.p_ints
    poke(ints, CYCLES, ints[CYCLES] + 1)
    row = ints[ROLE_CUR]
    n = ints[FILL0 + row]
    poke(ints, LAST_ROW, row)
    poke(ints, LAST_N, n)
    if record_trace:
        t = ints[TLEN]
        if t < st.n_trace:
            poke(st.p_trace, t, n)
        for k in range(n):
            if t + 1 + k < st.n_trace:
                poke(st.p_trace, t + 1 + k, st.p_slots[row * st.capacity + k])
        poke(ints, TLEN, t + 1 + n)


def _next_cycle(st, runs):
    """The cycle loop's test.  With watched cells, at the end of a cycle (``last_n`` not -1) the
    cells it processed that are watched and now reached go to ``newly`` (in processing order:
    only a processed cell changes), and the loop pauses when ``newly`` holds cells, as when
    ``budget`` cycles have run (``paused``: 1)."""
    ints = st.p_ints
    if st.n_watch > 0 and ints[LAST_N] >= 0:  # a cycle of this loop ended
        high = st.D.f32const(POT_HIGH)
        row = ints[LAST_ROW]
        for k in range(ints[LAST_N]):
            n = st.p_slots[row * st.capacity + k]
            if st.p_watch[n] >= 0 and st.D.lt(st.p_potential[n], high):
                poke(st.p_newly, ints[NNEW], st.p_watch[n])
                poke(ints, NNEW, ints[NNEW] + 1)
                poke(st.p_watch, n, -1)
        poke(ints, LAST_N, -1)
        if ints[NNEW] > 0:
            poke(ints, PAUSED, 1)
            return False
    if not runs:
        poke(ints, PAUSED, 0)
        return False
    if ints[BUDGET] == 0:
        poke(ints, PAUSED, 1)
        return False
    if ints[BUDGET] > 0:
        poke(ints, BUDGET, ints[BUDGET] - 1)
    return True


_methods(StateType, filled=_filled, heuristic=_heuristic, note_drop=_note_drop, record_cycle=_record_cycle,
         next_cycle=_next_cycle,
         index=lambda st, n: min(max(n, 0), st.n_potential - 1),  # a read inside the arrays: the push's guard tests n
         cost_f32=lambda st, n: st.D.int_to_f32(st.p_costs[n]),
         edge=lambda st, n: K.edge_weight(st.D, st.D.int_to_f32(st.p_costs[n])),
         heuristic_between=lambda st, goal, start: K.astar_heuristic(st.D, goal[0] - start[0], goal[1] - start[1]),
         pick=lambda st, cond, a, b: a if cond else b, may=lambda st, cond: cond,
         loop=lambda st, name, bound: range(bound))


# ----------------------------------------------------------------------------------- trail
def _append(tr, x, y):
    k = tr.p_ints[NPATH]
    poke(tr.p_path, 2 * k, x)
    poke(tr.p_path, 2 * k + 1, y)
    poke(tr.p_ints, NPATH, k + 1)


def _point(tr, i):  # i < 0: from the end
    k = tr.p_ints[NPATH] + i
    return tr.p_path[2 * k], tr.p_path[2 * k + 1]


def _keep(tr, m, gx, gy):
    poke(tr.p_gradx, m, gx)
    poke(tr.p_grady, m, gy)
    t = tr.p_ints[NTOUCHED]
    if t < tr.n_touched:
        poke(tr.p_touched, t, m)
        poke(tr.p_ints, NTOUCHED, t + 1)


_attribute(TrailType, "count", lambda tr: tr.p_ints[NPATH])
_methods(TrailType, append=_append, point=_point, keep=_keep,
         knows=lambda tr, m: K.grad_cached(tr.D, tr.p_gradx[m], tr.p_grady[m]),
         vector=lambda tr, m: (tr.p_gradx[m], tr.p_grady[m]),
         iteration=lambda tr, i, stc, dx, dy: None, fallback=lambda tr, i, oscillation: None)


@jit
def clear_gradients(D, trail):
    """Zero the gradient vectors the last calcPath wrote (``setupNavFn`` leaves them all zero)."""
    zero = D.f32const(0.0)
    gradx, grady, touched = trail.gradx, trail.grady, trail.touched
    for i in range(trail.ints[NTOUCHED]):
        gradx[touched[i]] = zero
        grady[touched[i]] = zero
