"""The command line: results on the example suite, and bad input handled cleanly.

Bad input must give exit status 2, exactly one line on stderr naming the problem,
no traceback, and no partially written output file.
"""

import argparse
import json
import os
import shutil
import subprocess
import sys

import numpy as np
import pytest

from navfn_smt.cli import EXAMPLE_SUITE, main

FREE = EXAMPLE_SUITE / "free" / "3x3_free"
FREE_MAP = (FREE / "test.txt").read_text().splitlines()[1].strip()  # its map file name


def run(*args, cwd=None):
    p = subprocess.run([sys.executable, "-m", "navfn_smt", *map(str, args)], capture_output=True, text=True,
                       cwd=cwd, env={**os.environ, "COLUMNS": "200"})
    return p.returncode, p.stdout, p.stderr


def assert_clean_error(rc, err, *words):
    assert rc == 2, err
    assert "Traceback" not in err
    lines = [line for line in err.splitlines() if line.strip()]
    assert len(lines) == 1, err
    for w in words:
        assert w in lines[0], lines[0]


def test_plan_json_matches_golden():
    rc, out, err = run("plan", FREE, "--start", 1, 1, "--goal", 1, 3, "--json")
    assert rc == 0, err
    doc = json.loads(out)
    g = np.load(FREE / "golden_astar.npz")
    i = [tuple(c) for c in g["cases"].tolist()].index((1, 1, 1, 3))
    gp = g["path"][g["path_offsets"][i]: g["path_offsets"][i + 1]]
    assert np.array_equal(np.array(doc["path"], dtype=np.float32), gp)
    assert np.float32(doc["start_potential"]) == g["start_potential"][i]
    assert doc["cycles"] == int(g["cycles"][i]) and doc["start_reached"] == bool(g["start_reached"][i])


def test_plan_raw_map_with_size_and_dijkstra(tmp_path):
    raw = tmp_path / "m.bin"
    shutil.copy(FREE / FREE_MAP, raw)
    rc, out, err = run("plan", raw, "--size", 5, 5, "--start", 3, 3, "--goal", 1, 1, "--dijkstra", "--json")
    assert rc == 0, err
    doc = json.loads(out)
    assert doc["mode"] == "dijkstra" and doc["path"][0] == [3.0, 3.0] and doc["path"][-1] == [1.0, 1.0]


def test_plan_text_output_reports_no_path():
    """No path exits 1 (as --world and diagnose do) and says why."""
    rc, out, err = run("plan", EXAMPLE_SUITE / "split" / "3x3_wall_h", "--start", 1, 1, "--goal", 1, 3)
    assert rc == 1, err
    assert "no path" in out and "lethal cells separate it from the goal" in out


def test_difftest_default_example_and_json(tmp_path):
    report = tmp_path / "r.json"
    rc, out, err = run("difftest", "--mode", "astar", "--json", report)
    assert rc == 0, err
    assert out.strip().splitlines()[-1] == "2200 passed, 0 failed"
    doc = json.loads(report.read_text())
    assert doc["failed"] == 0 and doc["passed"] == 2200 and len(doc["maps"]) == 14


def test_difftest_disagreement_exits_1(tmp_path):
    suite = tmp_path / "s"
    shutil.copytree(FREE, suite / "free" / "3x3_free")
    g = dict(np.load(suite / "free" / "3x3_free" / "golden_dijkstra.npz"))
    g["cycles"] = g["cycles"] + (np.arange(len(g["cycles"])) == 7)
    np.savez(suite / "free" / "3x3_free" / "golden_dijkstra.npz", **g)
    report = tmp_path / "r.json"
    rc, out, err = run("difftest", suite, "--mode", "dijkstra", "--json", report)
    assert rc == 1
    assert out.strip().splitlines()[-1] == "80 passed, 1 failed"
    d = json.loads(report.read_text())["disagreements"]
    assert [(x["case_index"], x["field"]) for x in d] == [(7, "cycles")]


@pytest.mark.fast
def test_wrong_map_size(tmp_path):
    raw = tmp_path / "m.bin"
    raw.write_bytes(bytes(24))
    rc, out, err = run("plan", raw, "--size", 5, 5, "--start", 1, 1, "--goal", 2, 2)
    assert_clean_error(rc, err, "24 bytes", "5x5")


@pytest.mark.fast
def test_missing_map():
    rc, out, err = run("plan", "/nonexistent/map.bin", "--size", 5, 5, "--start", 1, 1, "--goal", 2, 2)
    assert_clean_error(rc, err, "no such")


@pytest.mark.fast
def test_raw_map_without_size(tmp_path):
    raw = tmp_path / "m.bin"
    raw.write_bytes(bytes(25))
    rc, out, err = run("plan", raw, "--start", 1, 1, "--goal", 2, 2)
    assert_clean_error(rc, err, "--size")


@pytest.mark.parametrize("which,cell", [("--start", (5, 1)), ("--goal", (1, -1)), ("--start", (0, 99))])
def test_cell_off_the_map(which, cell):
    other = "--goal" if which == "--start" else "--start"
    rc, out, err = run("plan", FREE, which, *cell, other, 1, 1)
    assert_clean_error(rc, err, which.strip("-"), "off the 5x5 map")


@pytest.mark.fast
def test_not_a_map_directory(tmp_path):
    d = tmp_path / "bad"
    d.mkdir()
    (d / "test.txt").write_bytes(b"\x89PNG\r\n\x1a\n\x00\x00garbage")
    rc, out, err = run("plan", d, "--start", 1, 1, "--goal", 2, 2)
    assert_clean_error(rc, err, "test.txt")


@pytest.mark.fast
def test_malformed_case_line(tmp_path):
    d = tmp_path / "suite" / "c" / "m"
    shutil.copytree(FREE, d)
    (d / "test.txt").write_text("5 5\nmap.bin\n\n1 1 2\n")
    rc, out, err = run("difftest", tmp_path / "suite")
    assert_clean_error(rc, err, "test.txt:4", "sx sy gx gy")


@pytest.mark.fast
def test_truncated_map_bytes_in_suite(tmp_path):
    d = tmp_path / "suite" / "c" / "m"
    shutil.copytree(FREE, d)
    (d / FREE_MAP).write_bytes(bytes(7))
    rc, out, err = run("difftest", tmp_path / "suite")
    assert_clean_error(rc, err, "7 bytes")


@pytest.mark.fast
def test_corrupt_golden_file(tmp_path):
    d = tmp_path / "suite" / "c" / "m"
    shutil.copytree(FREE, d)
    (d / "golden_astar.npz").write_bytes(b"not a zip")
    report = tmp_path / "r.json"
    rc, out, err = run("difftest", tmp_path / "suite", "--json", report)
    assert_clean_error(rc, err, "golden_astar.npz")
    assert not report.exists()  # nothing half-written


@pytest.mark.fast
def test_missing_suite_and_empty_suite(tmp_path):
    rc, out, err = run("difftest", tmp_path / "nope")
    assert_clean_error(rc, err, "no such suite")
    rc, out, err = run("difftest", tmp_path)
    assert_clean_error(rc, err, "no map directories")


@pytest.mark.fast
def test_unwritable_json_report(tmp_path):
    rc, out, err = run("difftest", "--json", tmp_path / "missing-dir" / "r.json")
    assert_clean_error(rc, err, "does not exist")


@pytest.mark.fast
def test_main_returns_status_in_process(capsys):
    assert main(["plan", str(FREE), "--start", "9", "9", "--goal", "1", "1"]) == 2
    assert "off the 5x5 map" in capsys.readouterr().err


ROOM = EXAMPLE_SUITE.parent / "mapserver" / "room.yaml"


def test_plan_world_on_map_server_yaml():
    rc, out, err = run("plan", ROOM, "--world", "--start", -1.2, -0.9, "--goal", 1.0, 1.1, "--json")
    assert rc == 0, err
    doc = json.loads(out)
    assert doc["ok"] and doc["extraction_exit"] == "near_goal" and doc["poses"]
    # Nav2 returns the path from the robot to the goal, converted with origin + p * resolution
    res = doc["resolution"]
    assert res == float(np.float32(0.1))
    sx, sy = doc["robot_cell"]
    assert [doc["poses"][0]["position"][k] for k in "xy"] == [-2.0 + sx * res, -2.0 + sy * res]
    assert [doc["poses"][-1]["position"][k] for k in "xy"] == [1.0, 1.1]  # smoothApproachToGoal: the goal pose


def test_plan_cells_on_map_server_yaml_and_bad_world_input(tmp_path):
    rc, out, err = run("plan", ROOM, "--start", 8, 8, "--goal", 30, 30, "--json")
    assert rc == 0, err and json.loads(out)["path"]
    rc, out, err = run("plan", ROOM, "--start", 8.5, 8, "--goal", 30, 30)
    assert_clean_error(rc, err, "integers")
    rc, out, err = run("plan", ROOM, "--world", "--start", 50, 0, "--goal", 0, 0)
    assert rc == 1 and "StartOutsideMapBounds: Start Coordinates of(50.000000, 0.000000) was outside bounds" in err
    bad = tmp_path / "bad.yaml"
    bad.write_text("image: [unclosed\n")
    rc, out, err = run("plan", bad, "--world", "--start", 0, 0, "--goal", 1, 1)
    assert_clean_error(rc, err, "bad.yaml")


def test_version():
    from importlib.metadata import version

    rc, out, err = run("--version")
    assert rc == 0, err
    assert out.strip() == f"navfn-smt {version('navfn-smt')}"


@pytest.mark.fast
def test_every_option_has_help_and_shows_its_default():
    from navfn_smt.cli import build_parser, shown_default

    def parsers(p):
        yield p
        for a in p._actions:
            if isinstance(a, argparse._SubParsersAction):
                for sp in a.choices.values():
                    yield from parsers(sp)

    for p in parsers(build_parser()):
        for a in p._actions:
            assert a.help or isinstance(a, argparse._SubParsersAction), f"{p.prog} {a.dest}: no help"
        text = "".join(p.format_help().split())  # no whitespace: wrapping may split at hyphens
        for a in p._actions:
            if a.option_strings and a.default not in (None, False, argparse.SUPPRESS):
                shown = " ".join(p._get_formatter()._expand_help(a).split())
                assert "default" in shown and shown_default(a.default) in shown, f"{p.prog} {a.dest}: {shown}"
                assert "".join(shown.split()) in text, f"{p.prog} {a.dest}"


@pytest.mark.parametrize("argv", [
    ["difftest", "--json", "{missing}/r.json"],
    ["bench", "--size", "12", "--backend", "reference", "--json", "{missing}/b.json"],
    ["bench", "--json", "{missing}/b.json"],
    ["metamorphic", "--relation", "rot90", "--json", "{missing}/m.json", "--save", "{tmp}/cx"],
    ["metamorphic", "--relation", "rot90", "--json", "{tmp}/m.json", "--save", "{tmp}/a-file"],
    ["coverage", "--max-cases", "1", "--json", "{missing}/c.json"],
    ["prove", "--junit", "{tmp}/j.xml", "--report", "{missing}/r.json"],
    ["prove", "--report", "{tmp}/r.json", "--markdown", "{tmp}/a-dir"],
    ["prove", "--report", "{tmp}/r.json", "--smt2", "{tmp}/a-file"],
    ["prove", "--report", "{tmp}/r.json", "--witness-dir", "{tmp}/a-file/w"],
    ["render", str(FREE), "-o", "{missing}/p.png"],
])
def test_unwritable_output_is_rejected_before_any_work(tmp_path, argv):
    """Exit 2 with one line, nothing printed on stdout (no run happened), nothing written,
    and an existing file at an output path left as it was."""
    work = tmp_path / "work"
    work.mkdir()
    (work / "a-dir").mkdir()
    (work / "a-file").write_text("kept")
    (work / "m.json").write_text("kept")
    args = [a.format(missing=tmp_path / "missing", tmp=work) for a in argv]
    rc, out, err = run(*args, cwd=work)
    assert_clean_error(rc, err)
    assert out == ""
    assert sorted(p.name for p in work.iterdir()) == ["a-dir", "a-file", "m.json"]
    assert (work / "a-file").read_text() == "kept" and (work / "m.json").read_text() == "kept"
    assert not any((work / "a-dir").iterdir()) and not (tmp_path / "missing").exists()
