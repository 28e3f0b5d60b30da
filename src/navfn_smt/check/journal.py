"""The journal of a long bounded check: each explored case written down as it is decided, so a
run that stops (killed, out of time, the machine rebooted) resumes where it stopped.

A journal is a text file of JSON lines.  The first line is its header: the arguments that
decide what a case's exploration gives (size, properties, cost box, modes, variant, ends, start,
goal, solver timeout, exhaustive limit) and the hash of the code the queries are built from
(:func:`.certificate.code_hash`).  Every further line is one explored case's result, its
control paths' log included, appended and flushed to disk when its batch arrives.  A rerun with
the same journal takes the cases it holds as decided and explores the others; one whose header
differs is refused (the journal then describes another check).  A line cut short by a stop in
mid-write is the last one, and is dropped: its case is explored again.
"""

from __future__ import annotations

import json
import os
from pathlib import Path

from ..errors import NavfnInputError
from .bounded import CaseResult, PropertyResult
from .certificate import case_key, case_of, code_hash

FORMAT = "navfn-smt check journal 1"


def header(request, names, nx: int, ny: int) -> dict:
    """What a journal's cases depend on (``request``: the
    :class:`~navfn_smt.check.runner.CheckRequest` of the check, exploring ``names``): a rerun
    must give the same header to reuse them."""
    r = request
    return {"format": FORMAT, "code_hash": code_hash(names), "size": [nx, ny], "properties": list(names),
            **r.header(), "semantics": r.planner.fp32_semantics(), "start": list(r.start) if r.start else None,
            "goal": list(r.goal) if r.goal else None, "timeout": r.timeout, "exhaustive": r.exhaustive_limit}


def _encode(cr: CaseResult) -> dict:
    return {"case": case_key(cr.case), "paths": cr.paths, "flip_queries": cr.flip_queries,
            "decided_by_intervals": cr.decided_by_intervals, "seconds": round(cr.seconds, 3),
            "unknown_flips": cr.unknown_flips, "cached_unsat": cr.cached_unsat, "sampled_sat": cr.sampled_sat,
            "log": cr.log,
            "results": {n: {"status": r.status, "reason": r.reason, "queries": r.queries,
                            "counterexample": None if r.counterexample is None else
                            [[k, v] for k, v in r.counterexample.items()]}
                        for n, r in cr.results.items()}}


def _decode(doc: dict) -> CaseResult:
    results = {n: PropertyResult(n, r["status"], None if r["counterexample"] is None else
                                 {int(k): int(v) for k, v in r["counterexample"]}, r["reason"], r["queries"])
               for n, r in doc["results"].items()}
    counts = ("paths", "flip_queries", "decided_by_intervals", "seconds", "unknown_flips", "log", "cached_unsat",
              "sampled_sat")
    return CaseResult(case_of(doc["case"]), results, **{k: doc[k] for k in counts})


class Journal:
    """An open journal: :attr:`done` (case key as JSON -> its :class:`CaseResult`) read from the
    file, and :meth:`record` appending each case decided from now on."""

    def __init__(self, path, head: dict):
        self.path = Path(path)
        self.done: dict = {}
        lines = self._read()
        if lines:
            if lines[0] != head:
                differ = sorted(k for k in set(head) | set(lines[0]) if head.get(k) != lines[0].get(k))
                raise NavfnInputError(f"--journal {path}: written by another check (it differs in "
                                      f"{', '.join(differ)}); name a new file, or delete this one")
            for doc in lines[1:]:
                cr = _decode(doc)
                self.done[json.dumps(case_key(cr.case))] = cr
        self._file = open(self.path, "a", encoding="utf-8")
        if not lines:
            self._write([head])

    def _read(self) -> list:
        try:
            text = self.path.read_text(encoding="utf-8")
        except FileNotFoundError:
            return []
        except (OSError, UnicodeDecodeError) as e:
            raise NavfnInputError(f"--journal {self.path}: unreadable ({e})") from None
        docs = []
        rows = text.split("\n")
        for i, line in enumerate(rows):
            if not line:
                continue
            try:
                docs.append(json.loads(line))
            except ValueError:
                if any(rows[i + 1:]):  # only the last line may be cut short
                    raise NavfnInputError(f"--journal {self.path}: line {i + 1} is not JSON") from None
                text = "\n".join(rows[:i]) + ("\n" if i else "")
                self.path.write_text(text, encoding="utf-8")  # drop the torn line before appending
        if docs and (not isinstance(docs[0], dict) or docs[0].get("format") != FORMAT):
            raise NavfnInputError(f"--journal {self.path}: not a check journal")
        return docs

    def _write(self, docs: list) -> None:
        self._file.write("".join(json.dumps(d, separators=(",", ":")) + "\n" for d in docs))
        self._file.flush()
        os.fsync(self._file.fileno())

    def known(self, cases) -> dict:
        """The results this journal holds of ``cases`` (case -> :class:`CaseResult`)."""
        keyed = ((c, json.dumps(case_key(c))) for c in cases)
        return {c: self.done[k] for c, k in keyed if k in self.done}

    def record(self, results: list) -> None:
        """Append these explored cases' results."""
        self._write([_encode(cr) for cr in results])

    def close(self) -> None:
        self._file.close()
