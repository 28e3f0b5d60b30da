"""What is known about each obligation, and how a run is judged against it.

An obligation's declared verdict (``expect=`` in its proof file) states what is *known*
about it in each semantics: ``proved`` or ``refuted`` (a proof, or a refutation replayed
on the concrete spec, that some earlier run produced), or ``unknown``: nothing is known
yet.  Knowledge comes from four places, one :class:`Known` per (obligation, semantics):

* the declaration itself;
* a split (:mod:`.split`) of the obligation: its verdict is the whole obligation's in fp32;
* a predicate's chain that decides an obligation stated whole through finer links
  (:attr:`~navfn_smt.smt.chains.Predicate.whole`);
* a decision recorded by ``prove --record`` / ``split --record`` where nothing was known,
  kept in ``known.json`` beside the proof file and keyed by a hash of the proof file, the
  kernels and the domains (a record made for other code is stale and ignored).

A run is judged by :func:`judge`: a decision in the direction of the knowledge
*confirms* it; no decision (a timeout, a solver that gave up) leaves it *undecided*, never
a failure, whatever was known; a decision where nothing was known is *newly decided*,
news to report and record, never a failure; only a decision **against** what is known
(a proof of a claim with a replayed refutation, or the reverse) is *contradicted*, and
fails the run.  So a run's exit status never depends on how fast a solver was that day.

:func:`standing` gives the one status every report shows for an obligation (``prove``,
``split``, ``check``'s induction and the invariants page): this run's decision where it
made one, what is known otherwise.
"""

from __future__ import annotations

import hashlib
import json
from dataclasses import dataclass
from pathlib import Path
from typing import Iterable, Optional

from ..errors import NavfnInputError
from .domains import FP32_SEMANTICS, is_fp32

DECIDED = ("proved", "refuted")

# how a run stands to what is known; only CONTRADICTED fails a run
CONFIRMED, UNDECIDED, NEWLY_DECIDED, CONTRADICTED = "confirmed", "undecided", "newly decided", "contradicted"
JUDGEMENTS = (CONFIRMED, UNDECIDED, NEWLY_DECIDED, CONTRADICTED)

RECORD_FILE = "known.json"  # beside the proof files: decisions recorded where nothing was declared


@dataclass(frozen=True)
class Known:
    """What is known of one obligation in one semantics, and where it is known from."""

    status: str  # proved | refuted | unknown (nothing known)
    source: str = "declared"  # declared | split | chain <Predicate> | recorded | none
    bound: Optional[dict] = None  # fp32, refuted: {"var", "holds_below"} from the bound cache


NOTHING = Known("unknown", "none")


def judge(decision: str, known: str) -> str:
    """How a run's ``decision`` (proved | refuted | unknown) stands to what is ``known``."""
    if decision not in DECIDED:
        return UNDECIDED
    if known not in DECIDED:
        return NEWLY_DECIDED
    return CONFIRMED if decision == known else CONTRADICTED


def standing(known: str, *decisions: str) -> tuple[str, str]:
    """``(status, judgement)`` of an obligation from what is known and the decisions of the
    runs that checked it (a whole query, a split): the one status the reports show.  Two
    runs that decide opposite ways contradict each other, whatever was known."""
    made = [d for d in decisions if d in DECIDED]
    if len(set(made)) > 1:
        return "refuted", CONTRADICTED  # a replayed refutation stands; the proof is the bug to find
    if not made:
        return known if known in DECIDED else "unknown", UNDECIDED
    verdict = judge(made[0], known)
    if verdict == CONTRADICTED:
        return "refuted", CONTRADICTED
    return made[0], verdict


# ------------------------------------------------------------------------- the knowledge
def content_key(ob) -> str:
    """A hash of what an obligation's verdict depends on: its proof file, the spec kernels
    and the symbolic domains (a record or a cached bound for other code does not apply)."""
    h = hashlib.sha256()
    here = Path(__file__).resolve().parent
    src = Path(ob.source) if ob.source else None
    for f in (src, here.parent / "spec" / "kernels.py", here / "domains.py"):
        if f is not None and f.exists():
            h.update(f.read_bytes())
    return f"{ob.name}:{h.hexdigest()[:16]}"


def _records(path: Path) -> dict:
    try:
        doc = json.loads(path.read_text()) if path.is_file() else {}
    except (OSError, ValueError):
        return {}
    return doc if isinstance(doc, dict) else {}


def recorded(ob, semantics: str) -> Optional[dict]:
    """The decision recorded for ``ob`` in ``semantics`` for the code as it is now, if any."""
    if not ob.source:
        return None
    rec = _records(Path(ob.source).parent / RECORD_FILE).get(content_key(ob), {}).get(semantics)
    return rec if isinstance(rec, dict) and rec.get("status") in DECIDED else None


def expectations(ob) -> dict:
    """``semantics -> declared verdict`` of ``ob``: its declaration, and for an obligation with a
    float32 verdict, the float32 semantics of every other build arithmetic too (``unknown``
    where the declaration names none: what is known there is recorded, or nothing)."""
    out = dict(ob.expect)
    if "fp32" in out:
        out.update({s: ob.expect.get(s, "unknown") for s in FP32_SEMANTICS})
    return out


def knowledge(obligations, splits=(), predicates=(), bound_of=None) -> dict:
    """``(name, semantics) -> Known`` for every obligation and semantics it declares, from the
    declarations, the ``splits``, the ``predicates``' chains and the recorded decisions;
    ``bound_of(ob, semantics)`` gives the bound cached for an obligation refuted in a float32
    semantics (none without it); a split and a chain decide x86-64's ``fp32`` only."""
    by_split = {}
    for s in splits:
        if s.expect in DECIDED:
            by_split[s.obligation] = s.expect
    whole = {name: p.name for p in predicates for name in getattr(p, "whole", ())}
    out = {}
    for ob in obligations:
        for sem, declared in expectations(ob).items():
            k = Known(declared, "declared") if declared in DECIDED else NOTHING
            if sem == "fp32" and ob.name in by_split:  # split() refuses a verdict the declaration contradicts
                k = Known(by_split[ob.name], "split")
            elif declared in DECIDED and sem == "fp32" and ob.name in whole:
                k = Known(declared, f"chain {whole[ob.name]}")
            elif k is NOTHING:
                rec = recorded(ob, sem)
                if rec:
                    k = Known(rec["status"], "recorded")
            cached = bound_of(ob, sem) if bound_of is not None and k.status == "refuted" and is_fp32(sem) else None
            if cached is not None:
                k = Known(k.status, k.source, {"var": ob.bound.var, "holds_below": cached})
            out[(ob.name, sem)] = k
    return out


def record(decisions: Iterable[tuple]) -> list[str]:
    """Record ``(obligation, semantics, status, evidence)`` decisions made where nothing was
    known into ``known.json`` beside each proof file; what was written, one line each (or
    why it could not be)."""
    from ..fileio import atomic_write_text

    lines = []
    by_file: dict = {}
    for ob, sem, status, evidence in decisions:
        if status in DECIDED and ob.source:
            by_file.setdefault(Path(ob.source).parent / RECORD_FILE, []).append((ob, sem, status, evidence))
    for path, items in by_file.items():
        doc = _records(path)
        for ob, sem, status, evidence in items:
            key = content_key(ob)
            for old in [k for k in doc if k.startswith(ob.name + ":") and k != key]:
                del doc[old]  # a record for older code
            doc.setdefault(key, {})[sem] = {"status": status, **evidence}
            lines.append(f"recorded {ob.name} [{sem}] {status} in {path}")
        try:
            atomic_write_text(path, json.dumps(doc, indent=1, sort_keys=True) + "\n")
        except (NavfnInputError, OSError) as e:
            lines = [ln for ln in lines if not ln.endswith(str(path))]
            lines.append(f"not recorded: {path}: {e}")
    return lines


def record_decisions(outcomes, obligations, when: str) -> list[str]:
    """Record this run's new decisions (where nothing was known) beside their proof files, with
    the solver, its time and the run's time stamp ``when`` (and the witness of a refutation)."""
    obs = {o.name: o for o in obligations}
    return record((obs[o.name], o.semantics, o.status,
                   {"solver": o.solver, "seconds": o.seconds, "when": when,
                    **({"witness": o.witness} if o.witness else {})})
                  for o in outcomes if o.judgement == NEWLY_DECIDED)
