"""``check --journal``: a stopped bounded check resumes, exploring only what its journal lacks,
and gives the verdicts, counts and certificate of an uninterrupted run."""

from __future__ import annotations

import json

import pytest

from navfn_smt.check import runner as R
from navfn_smt.errors import NavfnInputError

SIZE = (3, 6)


def _run(journal, monkeypatch=None, explored=None, lo=50):
    if explored is not None:
        real = R.explore

        def counting(case, *a, **k):
            explored.append(case)
            return real(case, *a, **k)

        monkeypatch.setattr(R, "explore", counting)
    entries = []
    got = R.check_one_size(R.CheckRequest(("start-reached",), (True, False), lo, 253), *SIZE, certificate=entries,
                           journal=journal)
    return got["start-reached"], entries


def _summary(r):
    return (r.status, r.cases, r.representatives, r.outside, r.cases_holding, r.cases_unknown)


def test_a_stopped_check_resumes_where_it_stopped(tmp_path, monkeypatch):
    whole, entries = _run(tmp_path / "whole.jsonl")
    lines = (tmp_path / "whole.jsonl").read_text().splitlines()
    assert len(lines) == 1 + whole.representatives
    kept = 1 + whole.representatives // 2
    cut = tmp_path / "cut.jsonl"
    cut.write_text("\n".join(lines[:kept]) + "\n" + lines[kept][: len(lines[kept]) // 2])  # stopped mid-write
    explored = []
    resumed, again = _run(cut, monkeypatch, explored)
    assert len(explored) == whole.representatives - (kept - 1)  # the torn line's case is explored again
    assert _summary(resumed) == _summary(whole) and resumed.status == "proved"
    assert (resumed.paths, resumed.queries) == (whole.paths, whole.queries)  # counted once, journaled or not
    assert [e[:2] for e in again] == [e[:2] for e in entries]
    assert len(cut.read_text().splitlines()) == 1 + whole.representatives
    explored.clear()
    full, _ = _run(cut, monkeypatch, explored)
    assert explored == []  # a complete journal: nothing explored
    assert (whole.from_journal, resumed.from_journal, full.from_journal) == (0, kept - 1, whole.representatives)
    journaled = [json.loads(line)["seconds"] for line in cut.read_text().splitlines()[1:]]
    assert full.case_seconds == pytest.approx(sum(journaled))  # the report's case time spans every run


def test_a_journal_of_another_check_is_refused(tmp_path):
    path = tmp_path / "j.jsonl"
    _run(path)
    with pytest.raises(NavfnInputError, match="differs in costs"):
        _run(path, lo=60)


def test_a_damaged_journal_is_refused(tmp_path):
    path = tmp_path / "j.jsonl"
    _run(path)
    lines = path.read_text().splitlines()
    lines[2] = "{not json"
    path.write_text("\n".join(lines) + "\n")
    with pytest.raises(NavfnInputError, match="line 3 is not JSON"):
        _run(path)
    path.write_text(json.dumps({"format": "something else"}) + "\n")
    with pytest.raises(NavfnInputError, match="not a check journal"):
        _run(path)


def test_the_journal_needs_one_size(tmp_path, capsys):
    from navfn_smt.cli import main

    rc = main(["check", "start-reached", "--max-size", "3", "5", "--journal", str(tmp_path / "j.jsonl")])
    err = capsys.readouterr().err
    assert rc != 0 and "--journal" in err and "Traceback" not in err
    assert not (tmp_path / "j.jsonl").exists()
