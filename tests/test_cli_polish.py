"""The command line a new user meets: help, where output goes, messages that say what to do,
progress off a terminal, readable figures and pictures."""

import argparse
import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from navfn_smt.cli import EXAMPLE_SUITE, build_parser, main, shown_default

FREE = EXAMPLE_SUITE / "free" / "3x3_free"
WALL = EXAMPLE_SUITE / "split" / "3x3_wall_h"
ROS = EXAMPLE_SUITE / "ROS" / "400x400_ros"
EXAMPLES = EXAMPLE_SUITE.parent
ROOM = EXAMPLES / "mapserver" / "room.yaml"
PARAMS = EXAMPLES / "nav2" / "nav2_params.yaml"
PROOFS = Path(__file__).resolve().parents[1] / "src" / "navfn_smt" / "proofs"


def run(*args, cwd=None, env=None):
    """The console script as a user runs it, output piped (not a terminal), no COLUMNS set."""
    e = {k: v for k, v in os.environ.items() if k != "COLUMNS"}
    p = subprocess.run([sys.executable, "-m", "navfn_smt", *map(str, args)], capture_output=True, text=True,
                       cwd=cwd, env={**e, **(env or {})})
    return p.returncode, p.stdout, p.stderr


def one_line_error(rc, err, *words):
    assert rc == 2, err
    assert "Traceback" not in err
    lines = [line for line in err.splitlines() if line.strip()]
    assert len(lines) == 1 and lines[0].startswith("navfn-smt: error: "), err
    for w in words:
        assert w in lines[0], lines[0]


# ------------------------------------------------------------------------------------ help
def _parsers(p):
    yield p
    for a in p._actions:
        if isinstance(a, argparse._SubParsersAction):
            for sp in a.choices.values():
                yield from _parsers(sp)


def test_every_option_has_help_and_its_default_shown_once():
    for p in _parsers(build_parser()):
        text = "".join(p.format_help().split())
        for a in p._actions:
            if isinstance(a, argparse._SubParsersAction):
                continue
            assert a.help, f"{p.prog} {a.dest}: no help"
            if not a.option_strings or a.default in (None, False, argparse.SUPPRESS):
                continue
            shown = " ".join(p._get_formatter()._expand_help(a).split())
            assert "default" in shown.lower() and shown_default(a.default) in shown, f"{p.prog} {a.dest}: {shown}"
            assert shown.lower().count("default:") <= 1, f"{p.prog} {a.dest}: default shown twice: {shown}"
            assert "".join(shown.split()) in text


def test_defaults_are_shown_as_a_user_types_them():
    assert shown_default(30.0) == "30" and shown_default(1e7) == "1e+07"
    assert shown_default((0.0, 0.0)) == "0 0" and shown_default("both") == "both"
    text = " ".join(build_parser()._subparsers._group_actions[0].choices["prove"].format_help().split())
    assert "seconds per solver query (default: 30)" in text


def test_version(capsys):
    with pytest.raises(SystemExit) as e:
        main(["--version"])
    assert e.value.code == 0 and capsys.readouterr().out.startswith("navfn-smt ")


# ------------------------------------------------------------- nothing written unasked
def _cheap_runs(tmp: Path):
    """Every command with cheap arguments; outputs, where asked, go under ``tmp / 'out'``."""
    out = tmp / "out"
    out.mkdir()
    suite = out / "suite"
    shutil.copytree(FREE, suite / "free" / FREE.name)
    proofs = out / "proofs"
    proofs.mkdir()
    shutil.copy(PROOFS / "progress.py", proofs)
    return [
        ["plan", FREE, "--start", 1, 1, "--goal", 1, 3],
        ["plan", WALL, "--start", 1, 1, "--goal", 1, 3],
        ["plan", ROOM, "--world", "--start", -1.2, -0.9, "--goal", 1.0, 1.1, "--params", PARAMS],
        ["difftest", suite, "--mode", "astar"],
        ["render", FREE, "-o", out / "p.png"],
        ["metamorphic", suite, "--relation", "rot90", "--max-cases", 2, "--mode", "astar"],
        ["coverage", suite, "--max-cases", 1, "--mode", "astar"],
        ["prove", proofs, "--semantics", "real", "--timeout", 5, "--report", out / "r.json"],
        ["bench", suite, "--backend", "jit", "--mode", "astar"],
        ["bench", "--size", 12, "--backend", "jit", "--repeat", 1, "--mode", "astar"],
        ["check", "valid-path", "--size", 3, 3, "--mode", "astar"],
        ["search", "cost", "--timeout", 1, "--mode", "astar"],
        ["search", "--summary", suite, "--mode", "astar"],
        ["diagnose", ROOM, "--start", -1.2, -0.9, "--goal", 1.0, 1.1],
        ["suite", "generate", out / "gen", "--category", "free", "--count", 1, "--paths", 2],
        ["suite", "record", suite, "--mode", "astar", "--overwrite"],
    ]


def test_no_command_writes_into_the_working_directory(tmp_path, monkeypatch, capsys):
    """Each command runs in an empty working directory, which stays empty."""
    cwd = tmp_path / "cwd"
    cwd.mkdir()
    runs = _cheap_runs(tmp_path)
    monkeypatch.chdir(cwd)
    for argv in runs:
        if argv[0] == "coverage":  # its process pool's resource tracker would outlive the call: not in process
            rc, _, err = run(*argv, cwd=cwd)
        else:
            rc = main([str(a) for a in argv])
            err = capsys.readouterr().err
        assert rc in (0, 1), f"{argv}: {err}"
        assert sorted(os.listdir(cwd)) == [], f"{argv[0]} wrote {os.listdir(cwd)}"
    assert (tmp_path / "out" / "p.png").exists() and (tmp_path / "out" / "r.json").exists()


@pytest.mark.fast
def test_render_output_checked_before_the_map_is_read(tmp_path, capsys):
    assert main(["render", str(tmp_path / "no-such-map"), "-o", str(tmp_path / "p.jpg")]) == 2
    assert "p.jpg: the picture must be .png or .svg" in capsys.readouterr().err
    assert main(["render", str(tmp_path / "no-such-map"), "-o", str(tmp_path / "missing" / "p.png")]) == 2
    assert "missing" in capsys.readouterr().err


# ------------------------------------------------------------------------------- prove
def test_prove_refuses_a_file_that_is_not_python(tmp_path):
    notes = tmp_path / "notes.yaml"
    notes.write_text("a: 1\n")
    rc, out, err = run("prove", notes)
    one_line_error(rc, err, "notes.yaml", "not a proof file")


def test_prove_reads_a_folder_or_says_what_it_expects(tmp_path, capsys):
    empty = tmp_path / "empty"
    empty.mkdir()
    (empty / "notes.txt").write_text("x")
    assert main(["prove", str(empty)]) == 2
    err = capsys.readouterr().err
    assert "no proof files in this folder" in err and "*.py" in err
    folder = tmp_path / "proofs"
    folder.mkdir()
    shutil.copy(PROOFS / "progress.py", folder)
    assert main(["prove", str(folder) + "/", "--semantics", "real", "--timeout", "5"]) == 0
    out = capsys.readouterr().out  # the one obligation read and judged (confirmed, or undecided on a busy machine)
    assert "update_keeps_a_lower_neighbour" in out and ", 0 newly decided, 0 contradicted" in out
    assert main(["prove", str(tmp_path / "nothing")]) == 2
    assert "no such proof file or folder" in capsys.readouterr().err


# ------------------------------------------------------------------ messages that name flags
@pytest.mark.fast
def test_image_outside_the_yaml_folder_names_the_flag(tmp_path, capsys):
    inner = tmp_path / "maps"
    inner.mkdir()
    shutil.copy(ROOM.with_suffix(".pgm"), tmp_path / "room.pgm")
    y = inner / "room.yaml"
    y.write_text(ROOM.read_text().replace("image: room.pgm", "image: ../room.pgm"))
    assert main(["plan", str(y), "--start", "5", "5", "--goal", "8", "8"]) == 2
    err = capsys.readouterr().err
    assert "--allow-outside" in err and "allow_outside" not in err
    assert main(["plan", str(y), "--start", "5", "5", "--goal", "8", "8", "--allow-outside"]) == 0


@pytest.mark.fast
@pytest.mark.parametrize("value", ["-1", "101", "nan"])
def test_min_branch_out_of_range_is_an_error(value, capsys):
    assert main(["coverage", "--min-branch", value]) == 2
    assert "--min-branch" in capsys.readouterr().err


def test_min_branch_not_met_says_so():
    rc, out, err = run("coverage", "--max-cases", 1, "--mode", "astar", "--min-branch", 100)
    assert rc == 1 and err.strip().splitlines()[-1].endswith("is below --min-branch 100%"), err


# --------------------------------------------------------------------------- plan: no path
@pytest.mark.fast
@pytest.mark.parametrize("start, words", [
    ((0, 0), ["on the map's border", "lethal"]),
    ((0, 2), ["on the map's border"]),
    ((1, 1), ["lethal cells separate it from the goal"]),
])
def test_plan_without_path_says_why(start, words, capsys):
    m = FREE if start[0] == 0 else WALL
    assert main(["plan", str(m), "--start", *map(str, start), "--goal", "1", "3"]) == 1
    out = capsys.readouterr().out
    assert "no path" in out and "why: calcPath returned 0" in out
    for w in words:
        assert w in out


def test_plan_start_on_an_obstacle_gives_its_cost(tmp_path, capsys):
    costs = np.full((5, 5), 50, np.uint8)
    costs[2, 2] = 254
    raw = tmp_path / "m.bin"
    raw.write_bytes(costs.tobytes())
    assert main(["plan", str(raw), "--size", "5", "5", "--start", "2", "2", "--goal", "1", "1", "--json"]) == 1
    doc = json.loads(capsys.readouterr().out)
    assert doc["path"] == [] and any("has cost 254 (lethal" in w for w in doc["why"])


# -------------------------------------------------------------------- progress off a terminal
def test_heartbeat_lines_when_not_a_terminal(capsys):
    from navfn_smt.report.tables import heartbeat, progress_bar

    t = iter(range(0, 1000, 5))
    advance = heartbeat(4, "work", every=10, clock=lambda: next(t))  # 5 s per step
    for _ in range(4):
        advance(1)
    advance(0)  # a caller reporting the end twice: one last line
    lines = capsys.readouterr().err.splitlines()
    assert lines == ["work: 2/4 (50%), 10 s, about 10 s left", "work: 4/4 (100%), 20 s"]
    t = iter(range(0, 1000, 20))
    advance = heartbeat(1000, "many", every=10, clock=lambda: next(t))
    advance(999)
    assert capsys.readouterr().err.strip() == "many: 999/1000 (99%), 20 s, about 0 s left"  # never 100% early
    with progress_bar(3, "quick") as advance:  # stderr is not a terminal here; a short run stays silent
        advance(3)
    assert capsys.readouterr().err == ""
    with progress_bar(2, "slow", every=0) as advance:
        advance(1)
        advance(1)
    assert capsys.readouterr().err.splitlines()[-1].startswith("slow: 2/2 (100%)")


# ------------------------------------------------------------ difftest: ours vs golden
def test_difftest_disagreement_names_ours_and_golden_on_one_line(tmp_path):
    suite = tmp_path / "s"
    shutil.copytree(FREE, suite / "free" / FREE.name)
    g = dict(np.load(suite / "free" / FREE.name / "golden_dijkstra.npz"))
    g["cycles"] = g["cycles"] + (np.arange(len(g["cycles"])) == 7)
    np.savez(suite / "free" / FREE.name / "golden_dijkstra.npz", **g)
    rc, out, err = run("difftest", suite, "--mode", "dijkstra")
    assert rc == 1
    row = [line for line in out.splitlines() if "case 7" in line]
    assert len(row) == 1 and "cycles: ours" in row[0] and ", golden" in row[0], out  # not wrapped when piped


def test_describe_every_field():
    from navfn_smt.report.difftest import describe

    f = lambda v: {"value": v, "bits": "0x0"}  # noqa: E731
    base = {"map": "m", "case_index": 3, "case": [1, 1, 2, 2]}
    path = describe({**base, "field": "path", "detail": {"length": 4, "golden_length": 5, "point": 2,
                                                         "ours": [f(1.0), f(2.0)], "golden": [f(1.5), f(2.0)]}})
    assert "ours (1.0, 2.0), golden (1.5, 2.0)" in path and "length: ours 4, golden 5" in path
    pot = describe({**base, "field": "potential", "detail": {"cell": [1, 2], "ours": f(3.0), "golden": f(4.0),
                                                             "cells_differing": 7, "start_potential": f(1.0),
                                                             "golden_start_potential": f(1.0)}})
    assert "at cell (1, 2): ours 3.0, golden 4.0" in pot
    same = describe({**base, "field": "potential", "detail": {"start_potential": {"value": 1.0, "bits": "0x1"},
                                                              "golden_start_potential": {"value": 1.0, "bits": "0x2"},
                                                              "note": "n"}})
    assert "ours 1.0 (0x1), golden 1.0 (0x2)" in same  # equal printed values: the bits tell them apart
    assert "start_reached: ours True, golden False" in describe(
        {**base, "field": "start_reached", "detail": {"ours": True, "golden": False}})


# ---------------------------------------------------------------------- bench units
def test_bench_times_in_fitting_units(capsys):
    from navfn_smt.report.bench import duration, size_in_bytes, sizes_table

    assert [duration(x) for x in (2.5, 0.0123, 4.2e-5, 3e-8, 0)] == ["2.5 s", "12.3 ms", "42 µs", "30 ns", "0 s"]
    assert size_in_bytes(0) == "-" and size_in_bytes(24400) == "23.8 KiB"
    sizes_table([{"backend": "jit", "size": 12, "map": "open", "mode": "astar", "seconds_per_plan": 1.8e-5,
                  "path_points": 2, "dropped_pushes": 0, "work_bytes": 24400}])
    out = capsys.readouterr().out
    assert "18 µs" in out and " 0.0 " not in out


# ----------------------------------------------------------------------------- render
def test_render_zooms_on_a_short_case_of_a_large_map(tmp_path, capsys):
    from navfn_smt.maps.pictures import view_window

    assert view_window(7, 7, np.array([[1.0, 1.0], [5.0, 5.0]])) is None
    w = view_window(400, 400, np.array([[188.0, 198.0], [188.0, 203.0]]))
    assert w is not None and w[0] <= 188 <= w[1] and w[2] <= 198 and 203 <= w[3] and w[1] - w[0] < 60
    assert view_window(400, 400, np.array([[188.0, 198.0], [188.0, 203.0]]), "full") is None
    assert view_window(400, 400, np.array([[5.0, 5.0], [390.0, 390.0]])) is None  # a long case: whole map
    assert main(["render", str(ROS), "-o", str(tmp_path / "z.png")]) == 0
    out = capsys.readouterr().out
    assert "showing x" in out and "of the 400x400 map" in out and "--zoom full" in out
    assert (tmp_path / "z.png").stat().st_size > 0


def test_check_heartbeat_does_not_wait_for_a_case(capsys, monkeypatch):
    import time

    from navfn_smt.report import check as report

    monkeypatch.setenv("NAVFN_HEARTBEAT", "0.05")  # its own default is 20 s
    tick = report.progress("4x4")
    time.sleep(0.3)  # no case finished yet: the heartbeat still prints
    tick(1, 2, None)
    tick(2, 2, None)
    report.stop_progress()
    lines = capsys.readouterr().err.splitlines()
    assert lines[0].startswith("check 4x4: 0/? cases") and lines[-1].startswith("check 4x4: 2/2 cases")
    time.sleep(0.15)
    assert capsys.readouterr().err == ""  # stopped


@pytest.mark.fast
@pytest.mark.parametrize("argv, words", [
    (["check", "valid-path", "--exhaustive", "nan"], "--exhaustive nan"),
    (["check", "valid-path", "--budget", "-1"], "--budget -1"),
    (["check", "valid-path", "--timeout", "nan"], "--timeout nan"),
    (["bench", "--sweep", "40", "--sweep-astar-goals", "many"], "--sweep-astar-goals many"),
    (["bench", "--climb", "0"], "--climb 0"),
    (["prove", "--timeout", "inf"], "--timeout inf"),
    (["search", "cost", "--timeout", "-1"], "--timeout -1"),
    (["mutate", "--timeout", "0"], "--timeout 0"),
])
def test_bad_numbers_are_one_line_errors(argv, words, capsys):
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert err.startswith("navfn-smt: error: ") and words in err and len(err.splitlines()) == 1
