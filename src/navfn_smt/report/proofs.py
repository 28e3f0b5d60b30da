"""Reports of a proof run: the terminal table, JSON, JUnit XML and the markdown page
that becomes ``docs/invariants.md`` (generated from the obligations, never hand-edited)."""

from __future__ import annotations

import json
from dataclasses import asdict
from xml.sax.saxutils import escape, quoteattr

from rich.table import Table

from ..fileio import atomic_write_text
from . import predicates
from .tables import console


JUDGEMENT_COLOUR = {"confirmed": "green", "undecided": "dim", "newly decided": "yellow", "contradicted": "bold red"}


def _status_markup(o) -> str:
    return f"[{JUDGEMENT_COLOUR.get(o.judgement, 'red')}]{o.status}[/]"


def table(outcomes, known: dict) -> None:
    t = Table(title="proof obligations: this run's verdicts against what is known")
    for c in ("obligation", "property", "semantics", "this run", "known", "judgement", "seconds", "solver"):
        t.add_column(c, justify="right" if c == "seconds" else "left", overflow="fold")
    for o in outcomes:
        t.add_row(o.name, o.predicate, o.semantics, _status_markup(o),
                  o.known if o.known == "unknown" else f"{o.known} ({o.known_source})", o.judgement,
                  f"{o.seconds:.2f}", o.solver)
    console.print(t)
    for o in outcomes:
        if o.bound and o.bound.get("source") == "bound cache":
            console.print(f"  {o.name} [{o.semantics}]: holds for {o.bound['var']} < {o.bound['holds_below']!r} "
                          "(the bound cache: found by an earlier search for this code; not searched in this run)")
        elif o.bound and o.bound.get("holds_below") is not None:
            console.print(f"  {o.name} [{o.semantics}]: holds for {o.bound['var']} < {o.bound['holds_below']!r}"
                          f" (refuted below {o.bound.get('refuted_below')!r}; {o.bound.get('solver_calls')} solver calls)"
                          + (f"; bound {o.bound['cache']}" if o.bound.get("cache") else ""))
    predicates.table(outcomes, known)


def to_json(outcomes, witness_files: dict) -> list:
    rows = []
    for o in outcomes:
        d = asdict(o)
        d["property"] = d.pop("predicate")
        d["statement"] = o.statement
        d["witness"] = witness_files.get((o.name, o.semantics))
        d["witness_values"] = o.witness
        rows.append(d)
    return rows


def write_json(path, outcomes, witness_files: dict, meta: dict, known: dict) -> None:
    doc = {**meta, "obligations": to_json(outcomes, witness_files), **predicates.summary(outcomes, known)}
    atomic_write_text(path, json.dumps(doc, indent=1))


def write_junit(path, outcomes) -> None:
    failures = sum(o.fails for o in outcomes)
    total = sum(o.seconds for o in outcomes)
    skipped = sum(o.judgement == "undecided" for o in outcomes)
    lines = ['<?xml version="1.0" encoding="UTF-8"?>',
             f'<testsuite name="navfn-smt prove" tests="{len(outcomes)}" failures="{failures}" skipped="{skipped}" '
             f'time="{total:.3f}">']
    for o in outcomes:
        lines.append(f'  <testcase classname={quoteattr(o.predicate)} name={quoteattr(f"{o.name}[{o.semantics}]")} '
                     f'time="{o.seconds:.3f}">')
        if o.fails:
            msg = f"contradicts what is known: known {o.known} ({o.known_source}), this run {o.status}" + (
                f": {o.detail}" if o.detail else "")
            lines.append(f"    <failure message={quoteattr(msg)}>{escape(o.statement)}</failure>")
        elif o.judgement == "undecided":
            lines.append(f"    <skipped message={quoteattr(f'undecided in this run; known: {o.known}')}/>")
        lines.append(f"    <system-out>{escape(json.dumps({'status': o.status, 'known': o.known, 'standing': o.standing, 'judgement': o.judgement, 'solver': o.solver, 'bound': o.bound}))}"
                     "</system-out>")
        lines.append("  </testcase>")
    lines.append("</testsuite>")
    atomic_write_text(path, "\n".join(lines) + "\n")


def markdown(outcomes, meta: dict, sources: dict) -> str:
    """The invariants page of this run: the page ``navfn-smt docs`` generates
    (:func:`navfn_smt.report.invariants_page.render`, the one generator), read from this run's
    report instead of the committed one; ``sources`` is the rest the page is rendered from
    (:func:`navfn_smt.commands.common.page_sources`: the check reports, the split report, the
    obligations of the files the run checked and what is known of them)."""
    from . import invariants_page as page

    doc = json.loads(json.dumps({**meta, "obligations": to_json(outcomes, {})}))
    return page.render(doc, "the run's report", **sources)


def write_markdown(path, outcomes, meta: dict, sources: dict) -> None:
    """Write :func:`markdown` to ``path``."""
    atomic_write_text(path, markdown(outcomes, meta, sources))
