"""``complete`` on narrow maps, by the induction FallbackPath: decided without exploring.

On a map whose interior is at most two cells wide or tall, every interior cell has a lethal
border cell among its eight neighbours, so calcPath takes its grid-following fallback at
every step and descends to the goal (``proofs/fallback.py``).  ``check complete`` decides such
a size by the induction, also when another property is explored beside it.  The concrete runs
here hold the induction's conclusion against the spec beyond the sizes it is used for, and
show that its budget condition (at most 4*nx passable cells) is needed."""

import json

import pytest

from navfn_smt.check import common as CC
from navfn_smt.check.soundness import sample
from navfn_smt.cli import main
from navfn_smt.under_test import FIXED


@pytest.mark.fast
@pytest.mark.parametrize("size,narrow", [((4, 5), True), ((5, 4), True), ((4, 6), True), ((6, 4), True),
                                         ((3, 14), True), ((4, 10), True), ((4, 11), False), ((3, 15), False),
                                         ((5, 5), False), ((14, 3), True)])
def test_narrow_sizes_are_at_most_two_cells_wide_and_within_the_budget(size, narrow):
    assert CC.narrow(*size) is narrow
    assert bool(CC.carried_at(*size)) is narrow and not CC.carried_at(*size, planner=FIXED)


@pytest.mark.fast
def test_check_complete_on_a_narrow_size_is_decided_by_fallback_path(tmp_path, capsys):
    js = tmp_path / "c.json"
    assert main(["check", "complete", "--size", "4", "5", "--json", str(js)]) == 0
    row = json.loads(js.read_text())["results"][0]
    assert row["status"] == "proved" and row["method"].startswith("induction: FallbackPath")
    assert row["enumerated"]["explored"] == 0 and row["solved"]["control_paths"] == 0
    assert row["cases_holding"] == row["enumerated"]["cases"] == 4608
    assert "induction: FallbackPath" in capsys.readouterr().out


@pytest.mark.fast
def test_a_cost_box_below_cost_neutral_is_explored(tmp_path):
    """FallbackPath's obligations assume the costs setCostmap produces (50..253): with NavFn's
    raw range (down to 1: a box reaching 0 is refused, a NaN) the size is explored, not decided by it."""
    assert not CC.carried_at(3, 4, lo=0) and CC.carried_at(3, 4, lo=50, hi=253)
    js = tmp_path / "c.json"
    assert main(["check", "complete", "--size", "3", "4", "--costs", "1..253", "--json", str(js)]) == 0
    row = json.loads(js.read_text())["results"][0]
    assert row["method"] == "exploration" and row["solved"]["control_paths"] > 0


@pytest.mark.fast
def test_beside_another_property_complete_stays_decided_by_the_induction(tmp_path):
    """``check complete start-reached`` on a narrow size: complete by FallbackPath, start-reached
    explored alone (its control paths end with propagation)."""
    js = tmp_path / "c.json"
    assert main(["check", "complete", "start-reached", "--size", "3", "4", "--json", str(js)]) == 0
    rows = json.loads(js.read_text())["results"]
    assert [(r["property"], r["status"], r["method"].split(":")[0]) for r in rows] == [
        ("complete", "proved", "induction"), ("start-reached", "proved", "exploration")]
    assert rows[0]["solved"]["control_paths"] == 0 < rows[1]["solved"]["control_paths"]


@pytest.mark.parametrize("size", [(4, 10), (10, 4), (3, 14), (14, 3)])
def test_calcpath_returns_a_path_on_narrow_maps_concretely(size):
    """FallbackPath's conclusion on seeded random maps of narrow sizes larger than check
    enumerates (up to 16 cells): every reached start gets a path."""
    assert sample(*size, 1500, seed=1, lethal=0.1).failures["complete"] == 0


def test_past_the_budget_a_narrow_map_can_be_incomplete():
    """The budget condition is needed: a corridor of 14 cells on a 3-wide map (4*nx = 12
    iterations) is not narrow, and there calcPath runs out on reached starts."""
    assert not CC.narrow(3, 16)
    assert sample(3, 16, 1500, seed=1, lethal=0.1).failures["complete"] > 0
