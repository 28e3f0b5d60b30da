"""Named predicates the obligations are stated with, after the paper's Dafny spec.

Each takes the numeric domain first, so a predicate reads the same in both semantics and
in the concrete replay of a counterexample.
"""

from __future__ import annotations

from ..spec.constants import COST_NEUTRAL, COST_OBS, POT_HIGH


def ValidPotential(D, p):
    """``0 <= p <= POT_HIGH``: a value the potential array can hold (never NaN)."""
    return D.and_(D.ge(p, D.f32const(0.0)), D.le(p, D.f32const(POT_HIGH)))


def Reached(D, p):
    """``p < POT_HIGH``: propagation has given the cell a finite potential."""
    return D.lt(p, D.f32const(POT_HIGH))


def Unreached(D, p):
    return D.ge(p, D.f32const(POT_HIGH))


def Lethal(D, c):
    """``cost >= COST_OBS`` (c is the cost as an int)."""
    return D.ge(c, COST_OBS)


def TranslatedCost(D, c):
    """A cost ``setCostmap`` can produce for a passable cell: COST_NEUTRAL..COST_OBS-1."""
    return D.and_(D.ge(c, COST_NEUTRAL), D.lt(c, COST_OBS))


def InUnitBox(D, dx, dy):
    """``-1 <= dx <= 1 and -1 <= dy <= 1``: an offset calcPath keeps after normalising."""
    one, mone = D.f32const(1.0), D.f32const(-1.0)
    return D.and_(D.and_(D.ge(dx, mone), D.le(dx, one)), D.and_(D.ge(dy, mone), D.le(dy, one)))


def GradDifference(D, v):
    """``v == 0`` or ``2**-25 <= |v| <= 2**35``: a component of gradCell's unnormalised vector on
    potentials NavFn produces (the claim of ``proofs/gradient.py:grad_differences_are_not_tiny``)."""
    zero, least, most = D.f32const(0.0), D.f32const(2.0**-25), D.f32const(2.0**35)
    not_tiny = D.or_(D.eq(v, zero), D.or_(D.ge(v, least), D.le(v, D.neg(least))))
    return D.and_(not_tiny, D.and_(D.le(v, most), D.ge(v, D.neg(most))))


def all_of(D, *conds):
    out = conds[0]
    for c in conds[1:]:
        out = D.and_(out, c)
    return out


def any_of(D, *conds):
    out = conds[0]
    for c in conds[1:]:
        out = D.or_(out, c)
    return out


def minimum(D, *xs):
    m = xs[0]
    for x in xs[1:]:
        m = D.ite(D.lt(x, m), x, m)
    return m
