"""The path measures of ``navfn-smt path-quality`` (report/path_quality.py)."""

import json
import math
from pathlib import Path

import numpy as np

from navfn_smt.cli import main
from navfn_smt.maps.suite import load_map
from navfn_smt.report.path_quality import grid_distances, measure_suite, shape_of

CX = Path(__file__).resolve().parent / "data" / "counterexamples"


def test_the_grid_optimum_steps_diagonally_only_between_free_side_cells():
    costs = np.full((5, 6), 50, np.uint8)
    costs[:, 0] = costs[:, -1] = costs[0] = costs[-1] = 254
    costs[2, 3] = 254
    d = grid_distances(costs, [(1, 1)]).reshape(5, 6)
    assert d[1, 1] == 0 and d[1, 4] == 3 and d[2, 2] == math.sqrt(2)
    assert d[2, 4] == 4  # (3, 1) -> (4, 2) passes beside the wall cell (3, 2): no corner cut
    assert d[3, 4] == 3 + math.sqrt(2) and math.isinf(d[0, 0])


def test_a_staircase_has_unit_spacing_turns_and_an_axis_heading():
    s = shape_of(np.array([[0, 0], [1, 0], [1, 1], [2, 1], [2, 2]], np.float32), optimum=2 * math.sqrt(2))
    assert s.length == 4 and s.spacing_mean == s.spacing_max == 1
    assert math.isclose(s.turn_per_cell, 3 * (math.pi / 2) / 4) and s.final_axis
    diagonal = shape_of(np.array([[0, 0], [0.5, 0.5], [1, 1]], np.float32), optimum=math.sqrt(2))
    assert diagonal.turn_per_cell == 0 and not diagonal.final_axis


def test_the_descent_path_of_the_5x5_astar_map_is_in_its_group():
    sm = load_map(CX / "incomplete-astar-5x5")
    doc = measure_suite([sm], ("astar",))
    assert doc["counts"] == {"cases": 1, "original_fails": 1, "fixed_fails_too": 0, "fixed_fails_from_a_reached_start": 0}
    row = doc["groups"]["fix: descent"]
    # the descent's 8-connected steps: (3, 1) -> (2, 2) diagonally, then (1, 2), the grid optimum
    assert row["paths"] == 1 and row["spacing"]["max"] == math.sqrt(2) and row["length_over_optimum"]["max"] == 1.0
    assert row["final_heading_on_an_axis"] == 1.0
    assert doc["groups"]["gradient"]["paths"] == 0


def test_the_command_accounts_for_every_case_of_the_example_suite(tmp_path, capsys):
    assert main(["path-quality", "--json", str(tmp_path / "q.json")]) == 0
    doc = json.loads((tmp_path / "q.json").read_text())
    c, g = doc["counts"], doc["groups"]
    assert sum(row["paths"] for row in g.values()) + c["fixed_fails_too"] == c["cases"] == 4400
    assert g["gradient"]["paths"] == c["cases"] - c["original_fails"]
    assert "| fix: descent |" in capsys.readouterr().out
