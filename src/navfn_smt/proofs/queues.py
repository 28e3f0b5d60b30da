"""ObstacleFreeQueue: the priority buffers never hold an obstacle or a cell off the map.

Every push goes through the guard of the ``push_cur/push_next/push_over`` macros; a cell is in
a buffer only if that guard admitted it (BuffersInductive, on the spec's own run, carries this
over every step).  PendingMatchesBuffers is BuffersInductive's invariant read at one cell: its
chain is that predicate's obligations (:data:`navfn_smt.proofs.PendingMatchesBuffers`).
"""

from navfn_smt.proofs import ObstacleFreeQueue
from navfn_smt.smt.obligation import obligation
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
