"""The difftest on the engine: local Dask workers, a Dask cluster given by address, a worker
killed mid-run, and the one-line errors of a bad ``--scheduler``.

Each parallel run must give the serial run's summary exactly: the same counts per category,
mode and map, and the same disagreements (a copy of the example suite with a tampered golden
file makes sure there are some), every case counted once.
"""

import logging
import os
import shutil
import signal

import numpy as np
import pytest

from navfn_smt import engine as engine_mod
from navfn_smt.cli import EXAMPLE_SUITE, main
from navfn_smt.difftest.runner import Summary, count_cases, run_suite, summarize
from navfn_smt.engine import Engine
from navfn_smt.maps.suite import MODES

TAMPERED = "random/3x3_random"  # every 5th case of its A* golden file claims one cycle more


@pytest.fixture(scope="module")
def suite(tmp_path_factory):
    """The example suite, one golden file of it tampered: a suite with disagreements."""
    root = tmp_path_factory.mktemp("engine") / "suite"
    shutil.copytree(EXAMPLE_SUITE, root)
    path = root / TAMPERED / "golden_astar.npz"
    g = dict(np.load(path))
    g["cycles"] = g["cycles"].copy()
    g["cycles"][::5] += 1
    np.savez(path, **g)
    return root


@pytest.fixture(scope="module")
def serial(suite):
    return comparable(run_suite(suite, MODES, "jit"))


def comparable(summary: Summary) -> dict:
    """A summary without the seconds each map took (the only field that varies between runs)."""
    s = summarize(summary)
    s["maps"] = [{k: v for k, v in m.items() if k != "seconds"} for m in s["maps"]]
    return s


def local_cluster():
    from distributed import LocalCluster

    return LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None,
                        scheduler_kwargs={"dashboard": False, "dashboard_address": "127.0.0.1:0"},
                        silence_logs=logging.CRITICAL, memory_limit=0, host="127.0.0.1")


def test_serial_summary_counts_every_case(suite, serial):
    assert serial["passed"] + serial["failed"] == count_cases(suite, MODES) == 4400  # both modes
    assert serial["failed"] > 0 and len(serial["disagreements"]) == serial["failed"]
    assert {d["map"] for d in serial["disagreements"]} == {TAMPERED}
    assert [d["field"] for d in serial["disagreements"]] == ["cycles"] * serial["failed"]


def test_local_workers_equal_serial(suite, serial):
    assert comparable(run_suite(suite, MODES, "jit", jobs=2, chunk=200)) == serial


def test_cluster_by_address_equals_serial(suite, serial):
    with local_cluster() as cluster:
        eng = Engine(scheduler=cluster.scheduler_address)
        assert comparable(run_suite(suite, MODES, "jit", eng=eng, chunk=200)) == serial


def test_worker_killed_mid_run_loses_no_case(suite, serial):
    """SIGKILL to one of two workers after a few tasks: its tasks run again elsewhere, and
    every case is still counted exactly once."""
    from distributed import Client

    state = {"done": 0}

    def on_client(client):
        state["pids"] = client.run(os.getpid)

    def progress(outcome):
        state["done"] += 1
        if state["done"] == 5:
            os.kill(min(state["pids"].values()), signal.SIGKILL)

    with local_cluster() as cluster:
        eng = Engine(scheduler=cluster.scheduler_address)
        s = comparable(run_suite(suite, MODES, "jit", eng=eng, chunk=40, progress=progress, on_client=on_client))
        with Client(cluster, set_as_default=False) as c:
            c.wait_for_workers(2, timeout=60)
            after = set(c.run(os.getpid).values())
    assert state["done"] > 100  # many tasks: the kill came early in the run
    assert min(state["pids"].values()) not in after  # the nanny replaced the killed worker
    assert s == serial


def test_auto_stays_in_this_process_below_the_threshold(suite, serial, monkeypatch):
    def no_cluster(eng):
        raise AssertionError("a small suite started workers")

    monkeypatch.setattr(engine_mod, "client", no_cluster)
    assert comparable(run_suite(suite, MODES, "jit", jobs="auto")) == serial


@pytest.mark.shared
def test_shared_suite_on_local_workers_equals_serial(shared_suite, tmp_path):
    """The whole shared suite, both modes, by the JIT on two local workers: every case passes
    (the suite's only whole run in the tests), and every seventh map's rows equal those of a run
    in this process (a serial run of the whole suite doubled the test's time)."""
    import shutil

    from navfn_smt.maps.suite import discover

    workers = comparable(run_suite(shared_suite, MODES, "jit", jobs=2))
    assert workers["passed"] == 2 * 121404 and workers["failed"] == 0
    sample = tmp_path / "sample"
    for d in discover(shared_suite)[::7]:
        shutil.copytree(d, sample / d.parent.name / d.name)  # the discovery follows no symbolic link
    serial = comparable(run_suite(sample, MODES, "jit"))
    names = {m["map"] for m in serial["maps"]}
    assert len(names) == len(discover(shared_suite)[::7]) >= 14
    assert serial["maps"] == [m for m in workers["maps"] if m["map"] in names] and serial["failed"] == 0


@pytest.mark.parametrize("address,words", [
    ("nonsense", ["--scheduler 'nonsense'", "HOST:PORT"]),
    ("tcp://127.0.0.1:1", ["--scheduler tcp://127.0.0.1:1", "cannot reach"]),
])
def test_bad_scheduler_is_one_line_exit_2(address, words, capsys, monkeypatch):
    monkeypatch.setattr(engine_mod, "CONNECT_TIMEOUT", 2.0)
    rc = main(["difftest", "--quiet", "--scheduler", address])
    err = capsys.readouterr().err
    assert rc == 2, err
    lines = [line for line in err.splitlines() if line.strip()]
    assert len(lines) == 1 and "Traceback" not in err, err
    assert lines[0].startswith("navfn-smt: error: ")
    for w in words:
        assert w in lines[0], lines[0]
