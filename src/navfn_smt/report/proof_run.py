"""What a ``prove`` run leaves besides its report pages: where witness files go, the
witness files themselves, the run's metadata and its closing lines.

A witness (the values of a refuted obligation's counterexample) is written only where the
user asked for output: into ``--witness-dir``, or else into a folder next to the first
report file asked for (``r.json`` -> ``r-witnesses/``); with neither, none is written.
"""

from __future__ import annotations

import datetime
import json
from pathlib import Path
from typing import Optional

from ..errors import NavfnInputError
from ..fileio import atomic_write_text


def witness_dir(explicit, reports) -> Optional[Path]:
    """``explicit`` if given, else ``<stem>-witnesses`` next to the first report in ``reports``, else None."""
    if explicit:
        return Path(explicit)
    first = next((Path(r) for r in reports if r), None)
    return None if first is None else first.with_name(f"{first.stem}-witnesses")


def write_witnesses(outcomes, directory: Optional[Path]) -> dict:
    """Write one JSON file per refuted outcome into ``directory`` (created when needed);
    the files written, keyed by (obligation, semantics).  Nothing without a directory."""
    files = {}
    if directory is None:
        return files
    for o in outcomes:
        if not o.witness:
            continue
        try:
            directory.mkdir(parents=True, exist_ok=True)
        except OSError as e:
            raise NavfnInputError(f"{directory}: cannot create directory ({e.strerror})") from None
        w = directory / f"{o.name}.{o.semantics}.json"
        atomic_write_text(w, json.dumps({"obligation": o.name, "property": o.predicate, "semantics": o.semantics,
                                         "statement": o.statement, **o.witness}, indent=1))
        files[(o.name, o.semantics)] = str(w)
    return files


def meta(timeout: float, solvers, semantics, files) -> dict:
    """The run's settings, stamped with the time, for the JSON report and the markdown page."""
    return {"when": datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC"),
            "timeout": timeout, "solvers": list(solvers), "semantics": list(semantics),
            "files": [str(f) for f in files]}


def witness_note(outcomes, directory: Optional[Path]) -> None:
    """Print where the witness files went (of counterexamples, and of solver models the concrete
    spec did not confirm or could not replay), or that they were not written."""
    refuted = sum(1 for o in outcomes if o.witness and o.status == "refuted")
    other = sum(1 for o in outcomes if o.witness and o.status != "refuted")
    if not refuted + other:
        return
    parts = [f"{refuted} counterexample{'s' if refuted != 1 else ''}"] if refuted else []
    parts += [f"{other} solver model{'s' if other != 1 else ''} not confirmed on the spec"] if other else []
    what = " and ".join(parts)
    if directory is None:
        print(f"{what} not written to files (give --report or --witness-dir to keep them)")
    else:
        print(f"{what} written under {directory}")


def closing_line(outcomes) -> None:
    """Print how the run stands to what is known: ``N confirmed, M undecided, K newly decided,
    J contradicted``, then every newly decided query (news to record) and every contradiction
    (the only failure), each named."""
    from ..smt.knowledge import CONTRADICTED, JUDGEMENTS, NEWLY_DECIDED, UNDECIDED

    n = {j: [o for o in outcomes if o.judgement == j] for j in JUDGEMENTS}
    known_left = sum(o.known in ("proved", "refuted") for o in n[UNDECIDED])
    print(", ".join(f"{len(n[j])} {j}" for j in JUDGEMENTS)
          + (f" ({known_left} of the undecided known from elsewhere)" if known_left else ""))
    for o in n[NEWLY_DECIDED]:
        print(f"newly decided: {o.name}[{o.semantics}] {o.status} by {o.solver} in {o.seconds:.1f} s"
              + (" (witness replayed on the spec)" if o.witness and o.witness.get("replayed_on_spec") else "")
              + "; nothing was known: record it with --record, or state it in the proof file")
    for o in n[CONTRADICTED]:
        print(f"CONTRADICTION: {o.name}[{o.semantics}] {o.status} by {o.solver}, against the known {o.known} "
              f"({o.known_source})" + (f": {o.detail}" if o.detail else ""))
