"""ReachedWithinComponent: only the goal's 4-connected component is ever reached.

The wave starts at the goal (``initCost`` pushes its passable 4-neighbours) and a cell is
pushed only as a passable 4-neighbour of a cell whose update lowered it.  An update of a cell
none of whose four neighbours is reached leaves it unreached
(``update_beside_no_reached_cell_stays_unreached``), an obstacle stays unreached
(``PositionSafe.update_keeps_obstacles_unreached``), and a push admits only a passable cell
(``ObstacleFreeQueue.push_admits_only_passable_cells_on_the_map``).  So by induction over the
updates, every reached or buffered cell lies in the goal's component, and a cost outside it is
read only by a push guard that fails either way.  The bounded checks rely on it
(:mod:`navfn_smt.check.bounded`: a start outside the component is decided without exploring,
and layouts that differ only outside it are explored once).
"""

from navfn_smt.proofs import ReachedWithinComponent
from navfn_smt.smt.obligation import obligation
from navfn_smt.smt.predicates import Unreached, ValidPotential, all_of
from navfn_smt.spec import kernels as K


@obligation(ReachedWithinComponent, expect={"real": "proved", "fp32": "proved",
                                            "fp32@x86-64-v3": "proved", "fp32@aarch64": "proved"},
            scope="one update of any cell, any cost, with four unreached neighbours: every map size")
def update_beside_no_reached_cell_stays_unreached(D):
    """An update of an unreached cell whose four neighbours are all unreached leaves it unreached
    and unchanged, whatever its cost.

    pot(n), l, r, u, d in [POT_HIGH, POT_HIGH]  ==>  updateCell(n) does not change pot(n)
    """
    old, l, r, u, d = (D.f32(v) for v in ("old", "l", "r", "u", "d"))
    c = D.cost("cost")
    new, changed = K.cell_update(D, old, l, r, u, d, D.cost_int(c), D.cost_as_f32(c))
    pre = all_of(D, *(D.and_(ValidPotential(D, p), Unreached(D, p)) for p in (old, l, r, u, d)))
    return pre, D.and_(D.not_(changed), Unreached(D, new))
