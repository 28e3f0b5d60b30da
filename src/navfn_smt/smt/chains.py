"""The paper's predicates as chains of obligations.

A :class:`Predicate` (PositionSafe, Progress, ValidPath, FinitePotentialPath, ...) names
its English statement, where in the planner it applies, and the obligations that
establish it, in order: the base case, then the lemmas of the inductive step (for a
predicate that is not an induction, the lemmas that give it).  A link is the name of an
obligation declared for the predicate itself, or ``Owner.name`` for one borrowed from
another predicate's chain.  What the argument takes from the planner's control flow
without a solver (argued or tested, not machine-checked) is listed as *trusted*; what must
hold of the run for the argument to apply is a *condition* (:class:`Condition`: a hypothesis
of the claim, checked at run time where it can be, never proved); stronger variants expected
to fail, which show why a precondition is needed, are its *limits*.

The chains are data, checked (:func:`check_chains`): every link names an obligation
declared for the predicate it says, every obligation belongs to some chain.  A predicate's
status in a semantics is derived from its links' verdicts (:func:`derive`) and carries the
trusted steps and conditions that lie on its chain: ``proved`` alone means neither does.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Callable, Iterable, Optional

# a predicate's status, best first; a chain takes the worst of its links
STATUS_RANK = ("proved", "bounded", "open", "refuted")


@dataclass(frozen=True)
class Condition:
    """A run-time condition: a hypothesis under which a chain's claim holds, stated where the
    claim is; one object shared by every predicate that needs it."""

    name: str  # short, as a status shows it: "conditional (potentials below 2^30)"
    text: str  # what it says, where it is checked, and when it is argued to hold
    float32: bool = False  # a hypothesis of the float32 semantics only (the reals need no bound)

    def applies(self, semantics: str) -> bool:
        return not self.float32 or semantics != "real"


@dataclass(frozen=True)
class Predicate:
    """One of the paper's predicates and the chain of obligations that establishes it."""

    name: str  # the paper's name, exactly
    statement: str  # what it says, in English
    applies: str  # where in the paper and the planner it applies
    base: tuple = ()  # links of the base case, in order
    lemmas: tuple = ()  # links of the inductive step (or the lemmas that give it), in order
    limits: tuple = ()  # own obligations expected to fail: where the chain's preconditions are needed
    rests_on: tuple = ()  # other predicates the argument needs whole
    trusted: tuple = ()  # steps argued or tested, not checked by a solver
    conditions: tuple = ()  # Condition objects: run-time hypotheses of the claim
    whole: tuple = ()  # own obligations no solver decides whole, which finer links of the chain decide instead
    assumes: tuple = ()  # own obligations stating a precondition the links assume: unless proved, the chain is open

    @property
    def links(self) -> tuple:
        """The chain in order: base case, then the step."""
        return tuple(self.base) + tuple(self.lemmas)


@dataclass(frozen=True)
class Verdict:
    """An obligation's verdict in one semantics; ``bound`` when refuted but proved below a
    bound found by search (``"l < 1073741824.0"``)."""

    status: str  # proved | refuted | unknown
    bound: Optional[str] = None


def split_link(link: str) -> tuple[Optional[str], str]:
    """``"Owner.name"`` -> ``("Owner", "name")``; an own link -> ``(None, name)``."""
    owner, _, name = link.rpartition(".")
    return (owner or None), name


def link_owner(pred: Predicate, link: str) -> str:
    """The predicate a link's obligation is declared for."""
    owner, _ = split_link(link)
    return owner or pred.name


def own_obligations(predicates: Iterable[Predicate]) -> set:
    """Every obligation some predicate's chain holds as its own (not borrowed) link or limit."""
    out = set()
    for p in predicates:
        out |= ({split_link(x)[1] for x in p.links if split_link(x)[0] is None} | set(p.limits) | set(p.whole)
                | set(p.assumes))
    return out


# ----------------------------------------------------------------------------- the check
def check_chains(predicates, obligations, complete: bool = True) -> list[str]:
    """What is inconsistent between the chains and the obligations (empty when nothing).

    ``obligations`` are anything with ``name`` and ``predicate`` (declarations or outcomes).
    Every link must name an obligation declared for the predicate it says (its own, or the
    owner of a borrowed link, which must hold it as a link); every obligation must belong to
    the chain of the predicate it is declared for.  With ``complete=False`` (a run of some
    proof files only) links to obligations that were not loaded are not problems."""
    preds = {}
    problems = []
    for p in predicates:
        if p.name in preds:
            problems.append(f"{p.name}: defined twice")
        preds[p.name] = p
    declared = {o.name: o.predicate for o in obligations}
    for p in preds.values():
        problems += _check_links(p, preds, declared, complete)
        problems += [f"{p.name}: rests on {r}, which is not a predicate" for r in p.rests_on if r not in preds]
    problems += _check_cycles(preds)
    own = own_obligations(preds.values())
    for name, pred in declared.items():
        if name not in own:
            problems.append(f"{name} (declared for {pred}) is in no predicate's chain")
    return problems


def _check_links(p: Predicate, preds: dict, declared: dict, complete: bool) -> list[str]:
    """The links and limits of one predicate against the declarations."""
    problems = []
    entries = ([(x, "link") for x in p.links] + [(x, "limit") for x in p.limits] + [(x, "whole") for x in p.whole]
               + [(x, "assumption") for x in p.assumes])
    seen = [split_link(x)[1] for x, _ in entries]
    problems += [f"{p.name}: {n} appears twice in the chain" for n in sorted(set(seen)) if seen.count(n) > 1]
    for x, role in entries:
        owner, name = split_link(x)
        want = owner or p.name
        if role in ("limit", "whole", "assumption") and owner is not None:
            problems.append(f"{p.name}: {role} {x} is borrowed (it must be the predicate's own)")
        elif owner == p.name:
            problems.append(f"{p.name}: link {x} borrows from the predicate itself")
        elif owner is not None and owner not in preds:
            problems.append(f"{p.name}: link {x} borrows from {owner}, which is not a predicate")
        elif owner is not None and name not in {split_link(y)[1] for y in preds[owner].links
                                                if split_link(y)[0] is None}:
            problems.append(f"{p.name}: link {x} is not a link of {owner}'s chain")
        if name not in declared:
            if complete:
                problems.append(f"{p.name}: {role} {x} names no obligation")
        elif declared[name] != want:
            problems.append(f"{p.name}: {role} {x} is declared for {declared[name]}, not {want}")
    return problems


def _check_cycles(preds: dict) -> list[str]:
    """A predicate may not rest on itself, directly or through others."""
    problems = []

    def reach(name, path):
        for r in preds[name].rests_on:
            if r == path[0]:
                problems.append(f"{path[0]}: rests on itself ({' -> '.join(path + (r,))})")
            elif r in preds and r not in path:
                reach(r, path + (r,))

    for name in preds:
        reach(name, (name,))
    return problems


# ---------------------------------------------------------------------------- the status
def link_status(v: Optional[Verdict]) -> str:
    """A link's part in its chain: proved, bounded (refuted, proved below a bound),
    refuted, or open (unknown, or not checked)."""
    if v is None or v.status == "unknown":
        return "open"
    if v.status == "refuted":
        return "bounded" if v.bound else "refuted"
    return "proved"


def qualified(rank: str, trusted: int, conditions) -> str:
    """A status as it is shown: ``proved`` or ``bounded`` only when no trusted step and no
    condition lies on the chain; else ``proved (2 trusted steps)``, or ``conditional (bounded;
    no push dropped; 1 trusted step)`` when a run-time condition does.  ``open`` and ``refuted``
    are shown as they are."""
    if rank not in ("proved", "bounded"):
        return rank
    steps = [f"{trusted} trusted step{'s' if trusted != 1 else ''}"] if trusted else []
    if conditions:
        return "conditional (" + "; ".join([rank] * (rank == "bounded") + list(conditions) + steps) + ")"
    return f"{rank} ({steps[0]})" if steps else rank


def beneath(preds: Iterable[Predicate], semantics: str, predicates: Iterable[Predicate] = ()) -> tuple[list, list]:
    """What lies on the chains of ``preds`` beside their links: ``(trusted, conditions)``, the
    trusted steps as ``(owner, step)`` and the :class:`Condition` objects that apply in
    ``semantics``, of each predicate and of those it rests on (among ``predicates``), depth
    first, each once."""
    by_name = {p.name: p for p in predicates}
    trusted: dict = {}
    conditions: dict = {}

    def visit(p):
        trusted.update(dict.fromkeys((p.name, t) for t in p.trusted))
        for c in p.conditions:
            if c.applies(semantics):
                conditions.setdefault(c.name, c)
        for r in p.rests_on:
            if r in by_name:
                visit(by_name[r])

    for p in preds:
        visit(p)
    return list(trusted), list(conditions.values())


def derive(pred: Predicate, semantics: str, verdict_of: Callable[[str, str], Optional[Verdict]],
           predicates: Iterable[Predicate] = ()) -> dict:
    """The predicate's status in one semantics from its links' verdicts (and those of the
    predicates it rests on).  Its ``rank``: ``proved`` only when every link is; ``bounded`` when
    the only failures are refutations below which a bound holds; ``open`` when a link is unknown
    (or was not checked) and none is refuted, or an assumption is not proved (``x (assumed)``);
    ``refuted`` when a link has a counterexample.  Its ``status``: the rank :func:`qualified` by
    the trusted steps and conditions on the chain (its own and those of the predicates it rests
    on, each once), listed as ``trusted`` (``Owner: step``) and ``conditions`` (names).
    Returns those and, for each rank but proved, the links behind it (``link (via Owner)`` for
    those of a predicate it rests on)."""
    preds = {p.name: p for p in predicates}
    by_status: dict = {s: [] for s in STATUS_RANK}
    for x in pred.links:
        v = verdict_of(split_link(x)[1], semantics)
        by_status[link_status(v)].append(x if v is None or not v.bound else f"{x} ({v.bound})")
    for x in pred.assumes:  # a precondition of the links: where it fails, the chain says nothing
        if link_status(verdict_of(x, semantics)) != "proved":
            by_status["open"].append(f"{x} (assumed)")
    for r in pred.rests_on:
        if r in preds:
            sub = derive(preds[r], semantics, verdict_of, predicates)
            for s in STATUS_RANK[1:]:
                by_status[s] += [f"{y} (via {r})" for y in sub[s]]
    rank = max((s for s in STATUS_RANK if by_status[s] or s == "proved"), key=STATUS_RANK.index)
    trusted, conditions = beneath([pred], semantics, preds.values())
    return {"status": qualified(rank, len(trusted), [c.name for c in conditions]), "rank": rank,
            "trusted": [f"{o}: {t}" for o, t in trusted], "conditions": [c.name for c in conditions],
            **{s: by_status[s] for s in STATUS_RANK[1:]}}


def combined(derived: list) -> dict:
    """Several predicates' derivations (:func:`derive`) as one status: the worst rank, qualified
    by every trusted step and condition of any of them, each once (what an induction carried by
    those predicates rests on)."""
    if not derived:
        return {"status": "open", "rank": "open", "trusted": [], "conditions": []}
    rank = max((d["rank"] for d in derived), key=STATUS_RANK.index)
    trusted = list(dict.fromkeys(t for d in derived for t in d["trusted"]))
    conditions = list(dict.fromkeys(c for d in derived for c in d["conditions"]))
    return {"status": qualified(rank, len(trusted), conditions), "rank": rank, "trusted": trusted,
            "conditions": conditions}


def declared_verdicts(obligations, splits=(), predicates=()) -> Callable[[str, str], Optional[Verdict]]:
    """``verdict_of`` from what is known alone (:func:`navfn_smt.smt.knowledge.knowledge` of
    the declarations, the splits, the chains and the bound cache), no run's decisions."""
    from .checking import cached_bound
    from .knowledge import knowledge

    return known_verdicts(knowledge(obligations, splits, predicates, bound_of=cached_bound))


def _bound_text(status: str, bound: Optional[dict]) -> Optional[str]:
    """``"l < 1073741824.0"`` for a refutation below which a bound holds (a verdict's bound)."""
    found = status == "refuted" and bound and bound.get("holds_below") is not None
    return f"{bound['var']} < {bound['holds_below']!r}" if found else None


def known_verdicts(known: dict) -> Callable[[str, str], Optional[Verdict]]:
    """``verdict_of`` from what is known alone (``known``: ``(name, semantics) -> Known``,
    :func:`navfn_smt.smt.knowledge.knowledge`), a bound counting when the bound cache holds one."""

    def verdict_of(name, semantics):
        k = known.get((name, semantics))
        if k is None:
            return None
        status = k.status if k.status in ("proved", "refuted") else "unknown"
        return Verdict(status, _bound_text(status, k.bound))

    return verdict_of


def outcome_verdicts(outcomes, known: dict) -> Callable[[str, str], Optional[Verdict]]:
    """``verdict_of`` from the standings of a run's judged outcomes
    (:meth:`~navfn_smt.smt.checking.Outcome.judge`), and for an obligation no outcome is about,
    from what is ``known`` of it (:func:`known_verdicts`)."""
    by_key = {(o.name, o.semantics): o for o in outcomes}
    otherwise = known_verdicts(known)

    def verdict_of(name, semantics):
        o = by_key.get((name, semantics))
        if o is None:
            return otherwise(name, semantics)
        k = known.get((name, semantics))  # a run without the bound search keeps the cached bound
        return Verdict(o.standing, _bound_text(o.standing, o.bound or (k.bound if k is not None else None)))

    return verdict_of
