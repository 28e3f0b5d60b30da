"""Resource limits: maps too large are refused from their headers, solvers out of memory give
``unknown``, and an interrupted run exits 130 with no traceback and no half-written report."""

import os
import signal
import subprocess
import sys
from pathlib import Path

import pytest

from navfn_smt.errors import NavfnInputError
from fuzz_corpus import _npy_header_claiming, _pgm, _png_header_only, MAP_YAML
from navfn_smt.inputs import MAX_CELLS, check_cells

EXAMPLE = Path(__file__).resolve().parent.parent / "src" / "navfn_smt" / "examples" / "suite"


def test_limit_is_100m_cells():
    assert MAX_CELLS == 100_000_000
    check_cells(10_000, 10_000, "x")
    with pytest.raises(NavfnInputError, match="limit is 100000000 cells"):
        check_cells(10_001, 10_000, "x")


def test_test_txt_claiming_a_huge_map(tmp_path):
    from navfn_smt.maps.suite import load_map

    (tmp_path / "test.txt").write_text("100000 100000\nmap.bin\n\n1 1 2 2\n")
    (tmp_path / "map.bin").write_bytes(b"\0" * 25)
    with pytest.raises(NavfnInputError, match="100 M"):
        load_map(tmp_path)


@pytest.mark.fast
@pytest.mark.parametrize("name,data", [("m.pgm", _pgm(100000, 100000, data=b"\0" * 10)),
                                       ("m.pgm", _pgm(12000, 10000, data=b"\0" * 10)),
                                       ("m.png", _png_header_only(100000, 100000))])
def test_image_header_claiming_a_huge_map(tmp_path, name, data):
    from navfn_smt.nav2.mapserver import load_map_yaml

    (tmp_path / "m.yaml").write_text(MAP_YAML.replace("m.pgm", name))
    (tmp_path / name).write_bytes(data)
    with pytest.raises(NavfnInputError, match="100 M"):
        load_map_yaml(tmp_path / "m.yaml")


def test_npy_header_claiming_a_huge_map(tmp_path):
    from navfn_smt.nav2.setup import load_costmap_file

    (tmp_path / "c.npy").write_bytes(_npy_header_claiming((100000, 100000)))
    with pytest.raises(NavfnInputError, match="100 M"):
        load_costmap_file(tmp_path / "c.npy", 0.1)


@pytest.mark.fast
def test_solver_out_of_memory_is_unknown(monkeypatch):
    import z3

    from navfn_smt.smt import portfolio

    monkeypatch.setenv("NAVFN_SOLVER_MEMORY_MB", "1")  # no solver can even load
    x = z3.BitVec("x", 32)
    r = portfolio.solve([x * x == 49], timeout=5)
    assert r.status == "unknown"


def test_worker_memory_limit_default():
    from navfn_smt.smt.worker import memory_limit_bytes

    assert 0 < memory_limit_bytes() <= 8 * 2**30


@pytest.mark.parametrize("jobs", ["1", "2"])
def test_sigint_in_difftest(tmp_path, jobs):
    """Ctrl-C (to the whole process group) in a running difftest: exit 130, one line on stderr
    after the progress lines, the partial count on stdout, no report file (not even a temporary
    one).  The signal goes once the run reports progress, however loaded the machine is."""
    suite = tmp_path / "suite"
    import shutil

    for k in range(6):  # six copies of every category: the run lasts far longer than the first progress line
        for cat in EXAMPLE.iterdir():
            if cat.is_dir():
                shutil.copytree(cat, suite / f"{cat.name}{k}")
    code = ("import signal, sys; signal.signal(signal.SIGINT, signal.default_int_handler); "
            "from navfn_smt.cli import main; sys.exit(main())")
    env = {**os.environ, "NAVFN_HEARTBEAT": "0.05"}  # stderr is a pipe: progress lines, 20 a second
    p = subprocess.Popen([sys.executable, "-c", code, "difftest", str(suite), "--json", "r.json",
                          "--jobs", jobs, "--backend", "reference"], cwd=tmp_path, stdout=subprocess.PIPE,
                         stderr=subprocess.PIPE, start_new_session=True, env=env)
    first = p.stderr.readline().decode()  # blocks until the run has compared cases
    assert first.startswith(f"difftest {suite}") and " 0/" not in first, first
    os.killpg(p.pid, signal.SIGINT)
    out, err = p.communicate(timeout=60)
    lines = (first + err.decode()).splitlines()
    assert p.returncode == 130, "\n".join(lines)
    assert lines[-1] == "navfn-smt: interrupted"
    assert all(line.startswith(f"difftest {suite}") for line in lines[:-1]), lines  # no traceback
    assert "interrupted after" in out.decode()
    assert [f.name for f in tmp_path.iterdir()] == ["suite"]


def test_sigint_while_the_command_line_is_built(monkeypatch, capsys):
    """Ctrl-C before the command runs (while its modules are imported): exit 130, one line."""
    from navfn_smt import cli

    def interrupted(argv=None):
        raise KeyboardInterrupt

    monkeypatch.setattr(cli, "build_parser", interrupted)
    assert cli.main(["difftest"]) == 130
    assert capsys.readouterr().err == "navfn-smt: interrupted\n"


@pytest.mark.fast
@pytest.mark.parametrize("value", ["fast", "0", "-1", "nan", "inf"])
def test_a_bad_heartbeat_interval_is_named(monkeypatch, capsys, value):
    from navfn_smt.cli import main

    monkeypatch.setenv("NAVFN_HEARTBEAT", value)
    assert main(["difftest"]) == 2
    assert capsys.readouterr().err.strip() == (f"navfn-smt: error: NAVFN_HEARTBEAT={value!r}: give the seconds "
                                               f"between two progress lines, a positive number")
