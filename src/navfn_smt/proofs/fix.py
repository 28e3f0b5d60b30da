"""The fix (``spec/fix.py``, ``patches/navfn-fix/``): why the fixed planner returns a path.

Two predicates, each for every map size:

* ``DescentPath``: the descent ``calcPathDescent(n)`` goes from a reached start to the goal
  when the walk fits in ``n`` points.  Each step moves to a strictly lower one of the 8
  neighbours, and moves whenever one is lower (``descent_step_goes_strictly_lower``);
  ``Progress`` gives every reached cell but the goal a lower 4-neighbour (below the potential
  bound 2**30, the bound its float32 link is proved under).  Potentials strictly fall along the
  walk, so no cell repeats and the walk ends at the goal after at most ``nx*ny - 1`` cells, or
  earlier at calcPath's budget ``n``; every cell it passes is below a reached one, so reached
  (the same obligation), so no obstacle (``PositionSafe``).
* ``ConnectedStartReached``: the fix's propagation (``propNavFn*`` once more, for ``nx*ny``
  cycles, when the start is unreached and a buffer holds cells) reaches a start joined to the
  goal by passable cells when the wave needs no more cycles than that.
  An update that lowers a cell below the bound asks to push each unreached neighbour
  (``update_wants_an_unreached_neighbour``); an unreached passable cell updated beside a
  reached one becomes reached (``unreached_cell_beside_a_reached_one_gets_reached``); the loop
  ends because every cycle consumes a buffered cell and every buffered cell was paid for by a
  strict fall of a float32 potential (``update_lowers_when_it_changes``).  Needs: no push
  dropped for want of room (the spec counts them: ``PlanResult.dropped``).
"""

from navfn_smt.proofs import ConnectedStartReached, DescentPath
from navfn_smt.smt.obligation import obligation
from navfn_smt.smt.predicates import Reached, TranslatedCost, ValidPotential, all_of, any_of
from navfn_smt.spec import kernels as K
from navfn_smt.spec.constants import POT_HIGH
from navfn_smt.spec.fix import POT_BOUND

KEY_BOUND = 2.0 * POT_BOUND  # a push key: a potential below POT_BOUND, plus A*'s heuristic below POT_BOUND


@obligation(DescentPath, expect={"real": "proved", "fp32": "proved",
                                 "fp32@x86-64-v3": "proved", "fp32@aarch64": "proved"},
            scope="one step of the descent at any cell with any four neighbours: every map size")
def descent_step_goes_strictly_lower(D):
    """The descent steps only to a strictly lower neighbour, which is then reached, and it steps
    whenever some neighbour is lower.

    valid potentials, k = lowest_neighbour(centre; the 8 neighbours in calcPathDescent's order)
    ==>  (k >= 0 implies n_k < centre, and n_k reached when the centre is)
         and (some n_j < centre implies k >= 0)

    Progress gives a lower 4-neighbour, one of the 8, so the step always moves.
    """
    centre = D.f32("centre")
    ring = [D.f32(f"n{k}") for k in range(8)]
    best = K.lowest_neighbour(D, centre, ring)
    moved_lower = any_of(D, *(all_of(D, D.eq(best, k), D.lt(p, centre),
                                     any_of(D, D.not_(Reached(D, centre)), Reached(D, p)))
                              for k, p in enumerate(ring)))
    some_lower = any_of(D, *(D.lt(p, centre) for p in ring))
    pre = all_of(D, ValidPotential(D, centre), *(ValidPotential(D, p) for p in ring))
    claim = D.and_(any_of(D, D.eq(best, -1), moved_lower), any_of(D, D.not_(some_lower), D.ge(best, 0)))
    return pre, claim


@obligation(ConnectedStartReached, expect={"real": "proved", "fp32": "proved",
                                           "fp32@x86-64-v3": "proved", "fp32@aarch64": "proved"},
            scope="the push test of any update, for any neighbour: every map size")
def update_wants_an_unreached_neighbour(D):
    """An update whose key is below the bound asks to push every unreached passable neighbour.

    cost(m) in [50, 253], 0 <= key < 2**31 (a potential below 2**30 plus A*'s heuristic)
    ==>  push_wanted(POT_HIGH, key, INVSQRT2 * cost(m))
    """
    key = D.f32("key")
    c = D.cost("cost")
    wanted = K.push_wanted(D, D.f32const(POT_HIGH), key, K.edge_weight(D, D.cost_as_f32(c)))
    pre = all_of(D, TranslatedCost(D, D.cost_int(c)), D.ge(key, D.f32const(0.0)), D.lt(key, D.f32const(KEY_BOUND)))
    return pre, wanted


@obligation(ConnectedStartReached, expect={"real": "proved", "fp32": "proved",
                                           "fp32@x86-64-v3": "proved", "fp32@aarch64": "proved"},
            scope="one update of an unreached cell with any neighbours: every map size")
def unreached_cell_beside_a_reached_one_gets_reached(D):
    """An update of an unreached passable cell beside a cell below the bound reaches it.

    cost in [50, 253], pot(n) = POT_HIGH, l < 2**30, neighbours valid
    ==>  updateCell(n) changes pot(n), and pot'(n) < POT_HIGH
    """
    l, r, u, d = (D.f32(v) for v in ("l", "r", "u", "d"))
    c = D.cost("cost")
    high = D.f32const(POT_HIGH)
    new, changed = K.cell_update(D, high, l, r, u, d, D.cost_int(c), D.cost_as_f32(c))
    pre = all_of(D, TranslatedCost(D, D.cost_int(c)), *(ValidPotential(D, p) for p in (l, r, u, d)),
                 D.lt(l, D.f32const(POT_BOUND)))
    return pre, D.and_(changed, Reached(D, new))


@obligation(ConnectedStartReached, expect={"real": "proved", "fp32": "proved",
                                           "fp32@x86-64-v3": "proved", "fp32@aarch64": "proved"},
            scope="one update of any cell with any neighbours: every map size")
def update_lowers_when_it_changes(D):
    """An update that changes a cell (and only such an update pushes) strictly lowers it.  In
    float32 that bounds how often a cell changes (its potential takes finitely many values), the
    measure behind the wave's emptying its buffers; over the reals a potential could fall by ever
    smaller steps, so it bounds nothing there, and propNavFn* ends only by its cycle count (at most
    ``cycles`` cycles, each over a buffer of at most PRIORITYBUFSIZE cells).

    valid potentials, any cost  ==>  updateCell(n) changes pot(n) implies pot'(n) < pot(n)
    """
    old, l, r, u, d = (D.f32(v) for v in ("old", "l", "r", "u", "d"))
    c = D.cost("cost")
    new, changed = K.cell_update(D, old, l, r, u, d, D.cost_int(c), D.cost_as_f32(c))
    pre = all_of(D, *(ValidPotential(D, p) for p in (old, l, r, u, d)))
    return pre, any_of(D, D.not_(changed), D.lt(new, old))
