"""The paper's predicates in the reports of a proof run: per predicate, its chain of
obligations with each link's verdict in each semantics, the status derived from them and
what is still open (for the JSON report, the terminal and the invariants page)."""

from __future__ import annotations

from rich.table import Table

from ..smt.chains import (
    STATUS_RANK,
    check_chains,
    derive,
    known_verdicts,
    link_owner,
    outcome_verdicts,
    split_link,
)
from .tables import console


def registry() -> tuple:
    """The predicates shipped with the proofs."""
    from ..proofs import PREDICATES

    return PREDICATES


def run_semantics(outcomes) -> list:
    """The semantics of the run, in the order the outcomes have them."""
    return list(dict.fromkeys(o.semantics for o in outcomes))


def in_run(outcomes, predicates=None) -> list:
    """The predicates that have an obligation of their own in the run, or whose chain is made of
    those of such predicates (``Other.name`` links), in registry order."""
    declared = {o.predicate for o in outcomes}
    borrowed = lambda p: p.links and all(link.split(".")[0] in declared for link in p.links if "." in link) \
        and all("." in link for link in p.links)  # noqa: E731
    return [p for p in (predicates or registry()) if p.name in declared or borrowed(p)]


def standing_text(o) -> str:
    """An outcome's standing as the reports show it: the status, its bound, where it is
    known from when this run did not decide it, and a decision that is news or contradicts."""
    text = o.standing
    if o.standing == "refuted" and o.bound and o.bound.get("holds_below") is not None:
        text += f" (holds for {o.bound['var']} < {o.bound['holds_below']!r})"
    if o.judgement == "undecided" and o.standing in ("proved", "refuted"):
        text += f" (known: {o.known_source}; the whole query: {o.status})"
    elif o.judgement == "newly decided":
        text += " (newly decided)"
    elif o.judgement == "contradicted":
        text += f" (CONTRADICTS the known {o.known}: this run {o.status})"
    return text


def link_verdict(outcomes_by_key: dict, name: str, semantics: str, known: dict) -> str:
    """One link's standing as the reports show it (:func:`standing_text`); for an obligation
    this run did not check, what is known of it."""
    o = outcomes_by_key.get((name, semantics))
    if o is not None:
        return standing_text(o)
    k = known.get((name, semantics))
    if k is None or k.status not in ("proved", "refuted"):
        return "not checked"
    return f"{k.status} (known: {k.source}; not checked in this run)"


def _chain_rows(p, by_key: dict, sems: list, known: dict) -> list:
    """The chain of ``p`` as rows: base case, step, assumptions, limits, then the obligations
    stated whole that the chain decides through finer links."""
    rows = ([("base", x) for x in p.base] + [("step", x) for x in p.lemmas] + [("assumed", x) for x in p.assumes]
            + [("limit", x) for x in p.limits] + [("whole", x) for x in p.whole])
    return [{"role": role, "link": x, "obligation": split_link(x)[1], "declared_for": link_owner(p, x),
             "verdicts": {s: link_verdict(by_key, split_link(x)[1], s, known) for s in sems}} for role, x in rows]


def summary(outcomes, known: dict, predicates=None) -> dict:
    """The ``predicates`` section of the JSON report: every predicate of the run with its
    chain, its status per semantics (derived from the obligations' standings: what is known
    with the decisions of this run), the status what was known
    alone derives (``known_status``), the steps it takes from control flow and what is still
    open; the obligations of predicates without a chain (``unchained_obligations``: those of
    proof files given by hand); and any inconsistency between chains and obligations
    (``chain_problems``).  ``known`` (``(name, semantics) -> Known``): what the outcomes were
    judged against; obligations this run did not check count with what is known of them."""
    preds = tuple(predicates or registry())
    names = {p.name for p in preds}
    sems = run_semantics(outcomes)
    by_key = {(o.name, o.semantics): o for o in outcomes}
    got = outcome_verdicts(outcomes, known)
    wanted = known_verdicts(known)
    out = []
    for p in in_run(outcomes, preds):
        status = {s: derive(p, s, got, preds) for s in sems}
        before = {s: derive(p, s, wanted, preds)["status"] for s in sems}
        out.append({"name": p.name, "statement": p.statement, "applies": p.applies,
                    "chain": _chain_rows(p, by_key, sems, known), "rests_on": list(p.rests_on),
                    "trusted": list(p.trusted),
                    "conditions": [{"name": c.name, "text": c.text} for c in p.conditions], "status": status,
                    "known_status": before,
                    "changed": [s for s in sems if status[s]["status"] != before[s]]})
    chained = [o for o in outcomes if o.predicate in names]
    return {"predicates": out,
            "unchained_obligations": sorted({o.name for o in outcomes if o.predicate not in names}),
            "chain_problems": check_chains(preds, chained, complete=False)}


def not_proved(st: dict) -> str:
    """The links behind a status other than proved: ``open at x; refuted at y``."""
    parts = [f"{s} at " + ", ".join(st[s]) for s in reversed(STATUS_RANK[1:]) if st[s]]
    return "; ".join(parts)


def table(outcomes, known: dict) -> None:
    """The terminal summary: one row per predicate, its status per semantics and the links
    that keep it from proved."""
    doc = summary(outcomes, known)
    if not doc["predicates"]:
        return
    sems = run_semantics(outcomes)
    t = Table(title="the paper's predicates: status derived from their chains of obligations")
    for c in ("predicate", *sems, "links", "not proved"):
        t.add_column(c, overflow="fold")
    for p in doc["predicates"]:
        cells = [p["status"][s]["status"] + ("" if s not in p["changed"] else f" (known: {p['known_status'][s]})")
                 for s in sems]
        gaps = "\n".join(f"{s}: {not_proved(p['status'][s])}" for s in sems if not_proved(p["status"][s]))
        colour = "green" if not p["changed"] else "yellow"
        t.add_row(f"[{colour}]{p['name']}[/]", *cells, str(sum(r["role"] != "limit" for r in p["chain"])), gaps)
    console.print(t)
    for problem in doc["chain_problems"]:
        console.print(f"  [red]chain problem:[/] {problem}")


# ------------------------------------------------------------------------------ markdown
STATUS_NOTE = ("A predicate's status in a semantics is derived from its chain: **proved** when every link is "
               "proved (and every predicate it rests on is); **bounded** when the only failures are refutations "
               "below which a bound found by search holds; **open** when a link is unknown and none is refuted; "
               "**refuted** when a link has a confirmed counterexample, so that the chain does not establish the "
               "predicate in that semantics. A link written `Owner.name` is borrowed from another predicate's "
               "chain; a *limit* is a stronger variant expected to fail, which shows why a precondition is "
               "needed. A status carries what lies beneath it: **proved** alone means every link is machine-checked "
               "and no trusted step and no run-time condition lies on the chain (its own or that of a predicate it "
               "rests on); **proved (N trusted steps)** counts the argued or tested steps beneath it; "
               "**conditional (C; ...)** names the run-time conditions it holds under (hypotheses, listed once in "
               "the section on conditions below), and its trusted steps.")


def markdown_summary(outcomes, known: dict) -> list:
    """The table of predicates at the top of the invariants page."""
    doc = summary(outcomes, known)
    if not doc["predicates"]:
        return []
    sems = run_semantics(outcomes)
    lines = ["## The paper's predicates", "", STATUS_NOTE, "",
             "| predicate | " + " | ".join(sems) + " | base case | step |",
             "|---" * (len(sems) + 3) + "|"]
    for p in doc["predicates"]:
        base = ", ".join(f"`{r['link']}`" for r in p["chain"] if r["role"] == "base") or "-"
        step = ", ".join(f"`{r['link']}`" for r in p["chain"] if r["role"] == "step")
        if p["rests_on"]:
            step += ("; " if step else "") + "rests on " + ", ".join(p["rests_on"])
        statuses = " | ".join(p["status"][s]["status"] for s in sems)
        lines.append(f"| {p['name']} | {statuses} | {base} | {step or '-'} |")
    lines.append("")
    lines += trust_lines(preds_of(doc))
    if doc["unchained_obligations"]:
        lines += ["Obligations of no chain: " + ", ".join(f"`{n}`" for n in doc["unchained_obligations"]) + ".", ""]
    if doc["chain_problems"]:
        lines += ["Chain problems:", ""] + [f"- {x}" for x in doc["chain_problems"]] + [""]
    return lines


def preds_of(doc: dict) -> list:
    """The predicates (:class:`~navfn_smt.smt.chains.Predicate`) a summary is about."""
    names = {p["name"] for p in doc["predicates"]}
    return [p for p in registry() if p.name in names]


def trust_lines(preds) -> list:
    """What the chains take without a machine check, counted: the trusted steps (argued or
    tested), and each run-time condition once, with the predicates that state it."""
    steps = sum(len(p.trusted) for p in preds)
    conds: dict = {}
    for p in preds:
        for c in p.conditions:
            conds.setdefault(c.name, (c, []))[1].append(p.name)
    lines = [f"The chains take {steps} trusted steps (argued or tested, not machine-checked; each is listed under "
             f"its predicate below) and {len(conds)} run-time conditions, hypotheses under which a conditional "
             "status holds:", ""]
    lines += [f"- *{c.name}* ({', '.join(names)}; float32 only)" if c.float32 else
              f"- *{c.name}* ({', '.join(names)})" for c, names in conds.values()]
    return lines + [""]


def markdown_chain(name: str, outcomes, known: dict) -> list:
    """The head of a predicate's section: statement, where it applies, its chain with each
    link's verdicts, its status and what is still open (nothing for a predicate without a
    chain)."""
    doc = summary(outcomes, known)
    p = next((x for x in doc["predicates"] if x["name"] == name), None)
    if p is None:
        return []
    sems = run_semantics(outcomes)
    lines = [p["statement"], "", f"*Applies to:* {p['applies']}.", "",
             "| # | role | link | " + " | ".join(sems) + " |", "|---" * (len(sems) + 3) + "|"]
    step = 0
    for r in p["chain"]:
        step += r["role"] != "limit"
        num = str(step) if r["role"] != "limit" else "-"
        lines.append(f"| {num} | {r['role']} | `{r['link']}` | " + " | ".join(r["verdicts"][s] for s in sems) + " |")
    lines.append("")
    if p["rests_on"]:
        statuses = {x["name"]: x["status"] for x in doc["predicates"]}
        rests = [f"{r} ({', '.join(f'{s}: ' + statuses[r][s]['status'] for s in sems)})" if r in statuses else r
                 for r in p["rests_on"]]
        lines += ["*Rests on:* " + ", ".join(rests) + ".", ""]
    if p["trusted"]:
        lines += ["*Trusted: argued from the planner's code or tested, not machine-checked (each says why):*", ""]
        lines += [f"- {t}" for t in p["trusted"]] + [""]
    if p["conditions"]:
        lines += ["*Conditions: run-time hypotheses of the claim, not proved:*", ""]
        lines += [f"- *{c['name']}*: {c['text']}" for c in p["conditions"]] + [""]
    lines.append("*Status:* " + "; ".join(
        f"{s} **{p['status'][s]['status']}**" + (f" ({not_proved(p['status'][s])})" if not_proved(p["status"][s]) else "")
        for s in sems) + ".")
    lines.append("")
    still = [f"{s}: " + ", ".join(f"`{x}`" for x in p["status"][s]["open"]) + " undecided"
             for s in sems if p["status"][s]["open"]]
    beneath = sorted({t for s in sems for t in p["status"][s]["trusted"]} - {f"{p['name']}: {t}" for t in p["trusted"]})
    if beneath:
        owners = sorted({x.split(": ", 1)[0] for x in beneath})
        lines += [f"*Trusted steps beneath it, of the predicates it rests on:* {len(beneath)} (of "
                  + ", ".join(owners) + ").", ""]
    lines += ["*Still open:*", ""] + ([f"- {x}" for x in still] if still else ["- no link undecided"]) + [""]
    return lines
