"""ObstacleFreeQueue: the priority buffers never hold an obstacle or a cell off the map;
PendingMatchesBuffers: a cell's pending flag says whether it is in the buffers.

Every push goes through the guard of the ``push_cur/push_next/push_over`` macros; a cell
is in a buffer only if that guard admitted it, and the guard sets its pending flag in the
same step.  The chains (base case and lemmas in order) are stated as data in
:data:`navfn_smt.proofs.ObstacleFreeQueue` and :data:`navfn_smt.proofs.PendingMatchesBuffers`.
"""

from navfn_smt.proofs import ObstacleFreeQueue, PendingMatchesBuffers
from navfn_smt.smt.obligation import obligation
from navfn_smt.smt.predicates import all_of
from navfn_smt.spec import kernels as K
from navfn_smt.spec.constants import COST_OBS, PRIORITYBUFSIZE


@obligation(ObstacleFreeQueue, expect={"real": "proved", "fp32": "proved",
                                       "fp32@x86-64-v3": "proved", "fp32@aarch64": "proved"},
            scope="one push, any cell index, map size, buffer fill: every map size")
def push_admits_only_passable_cells_on_the_map(D):
    """A push enqueues only a passable cell on the map, and only into a buffer with room.

    push_admitted(n)  ==>  0 <= n < ns  and  cost(n) < COST_OBS  and  fill < PRIORITYBUFSIZE
    """
    n, ns, fill = D.int32("n"), D.int32("ns"), D.int32("fill")
    c = D.cost("cost")
    pending = D.not_(D.eq(D.int32("pending_flag"), 0))
    admitted = K.push_admitted(D, n, ns, pending, D.cost_int(c), fill, PRIORITYBUFSIZE)
    claim = D.and_(D.and_(D.ge(n, 0), D.lt(n, ns)), D.and_(D.lt(D.cost_int(c), COST_OBS), D.lt(fill, PRIORITYBUFSIZE)))
    pre = D.ge(ns, 1)
    return pre, D.or_(D.not_(admitted), D.and_(claim, D.not_(pending)))


# --------------------------------------------------------------------------------------
# PendingMatchesBuffers: pending flags match buffer contents
#
# The state is abstracted to one arbitrary cell ``q``: its pending flag and how often it
# occurs in each buffer (``cur``, ``nxt``, ``over``), with each buffer's fill.  Since ``q``
# is arbitrary, what is proved for it holds for every cell.  Two invariants:
#
#   B (between cycles):  q occurs in cur + over exactly once if pending, else never;
#                        nxt is empty
#   P (while a cycle runs): q occurs in nxt + over exactly once if pending, else never
#
# setupNavFn + initCost establish B; a cycle's start (clear the flags of the cells in cur)
# turns B into P; every push keeps P; the cycle's end (cur <- nxt, and cur <- over when
# that is empty) turns P back into B.  These are all the changes propagation makes to
# flags and buffers (spec/propagation.py: setup, propagate, _push), so by induction over
# cycles the invariants hold on maps of every size and for every buffer capacity.  A
# consequence: no cell is ever twice in the buffers, so they never hold more than ns cells.
# --------------------------------------------------------------------------------------
def _flag(D, name):
    return D.not_(D.eq(D.int32(name), 0))


def _per_buffer(D, prefix):
    """A symbolic int per buffer (an occurrence count of q, or a fill)."""
    return {b: D.int32(f"{prefix}{b}") for b in ("cur", "nxt", "over")}


def _once_if(D, pending, total):
    return D.eq(total, D.ite(pending, 1, 0))


def _well_formed(D, cnt, fill):
    """0 <= count <= fill <= capacity for each buffer."""
    conds = []
    for b in cnt:
        conds += [D.ge(cnt[b], 0), D.le(cnt[b], fill[b]), D.le(fill[b], PRIORITYBUFSIZE)]
    return all_of(D, *conds)


def _between_cycles(D, pending, cnt, fill):
    return all_of(D, _once_if(D, pending, D.add_int(cnt["cur"], cnt["over"])), D.eq(fill["nxt"], 0),
                  _well_formed(D, cnt, fill))


def _during_cycle(D, pending, cnt, fill):
    return all_of(D, _once_if(D, pending, D.add_int(cnt["nxt"], cnt["over"])), _well_formed(D, cnt, fill))


def _push(D, q, pending_q, cnt, fill, target, m, pending_other, cost, wanted=True):
    """One ``push_*`` macro on cell ``m`` into ``target`` (a buffer name, or a symbolic choice
    ``(cond, name_if, name_else)``); returns the new (pending_q, counts, fills)."""
    is_q = D.eq(m, q)
    pending_m = D.ite(is_q, pending_q, pending_other)
    if isinstance(target, tuple):
        cond, yes, no = target
        fill_t = D.ite(cond, fill[yes], fill[no])
        chosen = {yes: cond, no: D.not_(cond)}
    else:
        fill_t = fill[target]
        chosen = {target: True}
    # the macro as the spec and the JIT run it (kernels.push), asked only when the update wants it
    pushed, _, pending_after = K.push(D, m, D.int32("ns"), pending_m, D.cost_int(cost), fill_t, PRIORITYBUFSIZE)
    admitted = D.and_(wanted, pushed)
    cnt, fill = dict(cnt), dict(fill)
    for b, sel in chosen.items():
        into_b = D.and_(admitted, sel) if sel is not True else admitted
        fill[b] = D.add_int(fill[b], D.ite(into_b, 1, 0))
        cnt[b] = D.add_int(cnt[b], D.ite(D.and_(into_b, is_q), 1, 0))
    return D.ite(D.and_(wanted, is_q), pending_after, pending_q), cnt, fill


@obligation(PendingMatchesBuffers, expect={"real": "proved", "fp32": "proved",
                                           "fp32@x86-64-v3": "proved", "fp32@aarch64": "proved"},
            scope="setupNavFn and initCost at any goal of any map: base case of the induction")
def pending_matches_buffers_after_setup(D):
    """After setupNavFn and initCost's four pushes, pending flags match buffer contents (B).

    flags all false, buffers empty; push_cur(k+1), push_cur(k-1), push_cur(k-nx), push_cur(k+nx)
    ==>  for every cell q: q occurs once in cur + over if pending, else never; nxt is empty
    """
    q, k, nx = D.int32("q"), D.int32("goal"), D.int32("nx")
    pending = False
    cnt = {b: 0 for b in ("cur", "nxt", "over")}
    fill = dict(cnt)
    for i, m in enumerate((k + 1, k - 1, k - nx, k + nx)):
        # a cell other than q: its flag only decides whether the fill grows, so leave it free
        pending, cnt, fill = _push(D, q, pending, cnt, fill, "cur", m, _flag(D, f"pending_other{i}"), D.cost(f"cost{i}"))
    pre = all_of(D, D.ge(nx, 2), D.le(nx, 2**15), D.ge(k, 0), D.lt(k, 2**30))
    return pre, _between_cycles(D, pending, cnt, fill)


@obligation(PendingMatchesBuffers, expect={"real": "proved", "fp32": "proved",
                                           "fp32@x86-64-v3": "proved", "fp32@aarch64": "proved"},
            scope="the start of any cycle (flags of cur cleared): every map size, every capacity")
def pending_matches_buffers_at_cycle_start(D):
    """Clearing the flags of the current buffer's cells turns B into P.

    B(q), pending(q)' = pending(q) and q not in cur  ==>  P(q)
    """
    pending = _flag(D, "pending_q")
    cnt, fill = _per_buffer(D, "count_"), _per_buffer(D, "fill_")
    cleared = D.and_(pending, D.eq(cnt["cur"], 0))
    return _between_cycles(D, pending, cnt, fill), _during_cycle(D, cleared, cnt, fill)


@obligation(PendingMatchesBuffers, expect={"real": "proved", "fp32": "proved",
                                           "fp32@x86-64-v3": "proved", "fp32@aarch64": "proved"},
            scope="one push of updateCell or updateCellAstar, any potentials, key and threshold: every map size")
def pending_matches_buffers_after_push(D):
    """A push from an update keeps P: the flag is set exactly when the cell enters a buffer.

    P(q), push_wanted(neighbour, key, weight), target = nxt if key < curT else over  ==>  P(q) after the push
    """
    q, m = D.int32("q"), D.int32("m")
    pending = _flag(D, "pending_q")
    cnt, fill = _per_buffer(D, "count_"), _per_buffer(D, "fill_")
    key, cur_t, neighbour = D.f32("key"), D.f32("curT"), D.f32("neighbour")
    cost = D.cost("cost")
    wanted = K.push_wanted(D, neighbour, key, K.edge_weight(D, D.cost_as_f32(cost)))
    target = (K.to_low_buffer(D, key, cur_t), "nxt", "over")
    pending2, cnt2, fill2 = _push(D, q, pending, cnt, fill, target, m, _flag(D, "pending_m"), cost, wanted)
    return _during_cycle(D, pending, cnt, fill), _during_cycle(D, pending2, cnt2, fill2)


@obligation(PendingMatchesBuffers, expect={"real": "proved", "fp32": "proved",
                                           "fp32@x86-64-v3": "proved", "fp32@aarch64": "proved"},
            scope="the end of any cycle (buffer swap): every map size, every capacity")
def pending_matches_buffers_at_cycle_end(D):
    """The swap (cur <- nxt; when that is empty, cur <- over) turns P back into B.

    P(q)  ==>  B(q) after the swap
    """
    pending = _flag(D, "pending_q")
    cnt, fill = _per_buffer(D, "count_"), _per_buffer(D, "fill_")
    # the swap as the spec and the JIT run it (kernels.end_of_cycle), on the fills and, by the
    # same selection, on q's occurrences
    drained, fill_cur, fill_over, _ = K.end_of_cycle(D, fill["nxt"], fill["over"], D.f32("curT"), D.f32("priInc"))
    cnt_cur, cnt_over = K.buffer_swap(D, cnt["nxt"], cnt["over"], drained)
    cnt2 = {"cur": cnt_cur, "nxt": 0, "over": cnt_over}
    fill2 = {"cur": fill_cur, "nxt": 0, "over": fill_over}
    return _during_cycle(D, pending, cnt, fill), _between_cycles(D, pending, cnt2, fill2)
