"""Recording golden files from the spec: the shared suite's format exactly (the shared
goldens of the C++ are reproduced byte for byte), atomic writes, and a recording that
catches a tampered map."""

import shutil
import zipfile

import numpy as np
import pytest

from navfn_smt.difftest import record as R
from conftest import compare_golden_files
from navfn_smt.difftest.record import record_suite
from navfn_smt.difftest.runner import run_suite, summarize
from navfn_smt.errors import NavfnInputError
from navfn_smt.maps.generators import generate_suite
from navfn_smt.maps.suite import GOLDEN_FIELDS, load_golden, load_map

# the golden format of navfn-suite/README.md: dtype and shape (N cases, M points, K full, T trace)
FORMAT = {
    "width": ("int32", ()), "height": ("int32", ()), "cases": ("int32", ("N", 4)),
    "start_reached": ("int8", ("N",)), "start_potential": ("float32", ("N",)),
    "path_offsets": ("int64", ("N+1",)), "path": ("float32", ("M", 2)),
    "potential_sha256": ("uint8", ("N", 32)), "trace_sha256": ("uint8", ("N", 32)),
    "cycles": ("int32", ("N",)), "updates": ("int64", ("N",)), "full_index": ("int64", ("K",)),
    "full_potential": ("float32", ("K", "H", "W")), "full_trace_offsets": ("int64", ("K+1",)),
    "full_trace": ("int32", ("T",)),
}

SHARED_MAPS = [  # (map, full_first): small maps of several categories, one with finite-but-empty cases, a ROS map
    ("free/3x3_free", 50), ("spiral/5x5_spiral", 50), ("walls/5x5_2walls", 50), ("random/4x4_random", 50),
    ("split/7x7_split_v", 50), ("split/6x14_split_h", 50), ("circus/circus_5L", 50), ("radial/7x2_radial", 50),
    ("obstacle/5x7_obstacle30", 50), ("columns/7x7_column", 50), ("ROS/empty_room", 5), ("ROS/map_circular", 5),
]


def _copy_map(src, dst):
    shutil.copytree(src, dst, ignore=shutil.ignore_patterns("golden_*"))


@pytest.mark.shared
@pytest.mark.parametrize("name,full_first", SHARED_MAPS)
def test_record_reproduces_shared_golden_byte_for_byte(shared_suite, tmp_path, name, full_first):
    src = shared_suite / name
    _copy_map(src, tmp_path / name)
    recs = record_suite(tmp_path, full_first=full_first)
    assert [r.mode for r in recs] == ["astar", "dijkstra"]
    for mode in ("astar", "dijkstra"):
        ours, theirs = tmp_path / name / f"golden_{mode}.npz", src / f"golden_{mode}.npz"
        assert compare_golden_files(ours, theirs) == []
        with np.load(ours) as a, np.load(theirs) as b:
            assert a.files == b.files == list(GOLDEN_FIELDS)
            for f in GOLDEN_FIELDS:
                assert a[f].dtype == b[f].dtype and a[f].shape == b[f].shape and a[f].tobytes() == b[f].tobytes(), f
        assert ours.read_bytes() == theirs.read_bytes()  # even the zip container


@pytest.mark.shared
def test_reference_backend_records_the_same(shared_suite, tmp_path):
    _copy_map(shared_suite / "free/3x3_free", tmp_path / "free/3x3_free")
    record_suite(tmp_path, modes=("dijkstra",), backend="reference")
    got = tmp_path / "free/3x3_free/golden_dijkstra.npz"
    assert compare_golden_files(got, shared_suite / "free/3x3_free/golden_dijkstra.npz") == []
    assert not (tmp_path / "free/3x3_free/golden_astar.npz").exists()


@pytest.mark.shared
def test_full_index_rule_on_finite_but_empty_cases(shared_suite, tmp_path):
    _copy_map(shared_suite / "random/9x4_random", tmp_path / "random/9x4_random")
    record_suite(tmp_path, modes=("astar",), full_first=0)
    g = load_golden(tmp_path / "random/9x4_random/golden_astar.npz")
    empty = np.diff(g["path_offsets"]) == 0
    finite = g["start_potential"] < np.float32(1e10)
    assert g["full_index"].tolist() == np.nonzero(empty & finite)[0].tolist() == [180, 298, 409, 502, 658, 724, 1082]
    theirs = load_golden(shared_suite / "random/9x4_random/golden_astar.npz")
    for j, i in enumerate(g["full_index"]):
        k = theirs["full_index"].tolist().index(i)
        assert g["full_potential"][j].tobytes() == theirs["full_potential"][k].tobytes()


@pytest.mark.fast
def test_format_of_a_generated_recording(tmp_path):
    maps = generate_suite(tmp_path, "split", count=2, seed=1, size=(9, 7), paths=300)
    recs = record_suite(tmp_path, full_first=7)
    assert len(recs) == 4 and {r.full for r in recs} >= {7}
    for m in maps:
        smap = load_map(m.directory)
        for mode in ("astar", "dijkstra"):
            path = m.directory / f"golden_{mode}.npz"
            with zipfile.ZipFile(path) as z:
                assert [i.filename for i in z.infolist()] == [f + ".npy" for f in GOLDEN_FIELDS]
                assert all(i.compress_type == zipfile.ZIP_DEFLATED for i in z.infolist())
            g = load_golden(path, smap)
            n = len(smap.cases)
            k = len(g["full_index"])
            dims = {"N": n, "N+1": n + 1, "M": int(g["path_offsets"][-1]), "K": k, "K+1": k + 1,
                    "T": int(g["full_trace_offsets"][-1]), "H": smap.height, "W": smap.width}
            for f, (dtype, shape) in FORMAT.items():
                assert g[f].dtype == np.dtype(dtype), f
                assert g[f].shape == tuple(dims.get(s, s) for s in shape), f
            assert g["full_index"][:7].tolist() == list(range(7))
            assert int(g["width"]) == smap.width and np.array_equal(g["cases"], smap.cases)
            # split maps: cases across the wall are unreached, with no path
            unreached = g["start_potential"] == np.float32(1e10)
            assert unreached.any() and (np.diff(g["path_offsets"])[unreached] == 0).all()


@pytest.mark.fast
def test_tampered_map_is_caught(tmp_path):
    maps = generate_suite(tmp_path, "random", count=1, seed=2, size=(8, 7), paths=200)
    record_suite(tmp_path)
    assert summarize(run_suite(tmp_path))["failed"] == 0
    m = maps[0]
    costs = m.costs.copy()
    sx, sy, gx, gy = m.cases[0]
    x, y = gx + (1 if gx < m.width - 2 else -1), gy  # a neighbour of case 0's goal
    costs[y, x] = 50 if costs[y, x] != 50 else 200
    (m.directory / "map.bin").write_bytes(costs.tobytes())
    s = summarize(run_suite(tmp_path))
    assert s["failed"] > 0
    first = [d for d in s["disagreements"] if d["case_index"] == 0]
    assert first and first[0]["field"] in ("path", "potential")


@pytest.mark.fast
def test_existing_goldens_are_kept_unless_overwrite(tmp_path):
    maps = generate_suite(tmp_path, "free", count=1, seed=1, size=(5, 5), paths=10)
    record_suite(tmp_path, modes="astar")
    g = maps[0].directory / "golden_astar.npz"
    before = g.read_bytes()
    with pytest.raises(NavfnInputError, match="exists.*--overwrite"):
        record_suite(tmp_path)
    assert not (maps[0].directory / "golden_dijkstra.npz").exists(), "refused before writing anything"
    recs = record_suite(tmp_path, overwrite=True)
    assert len(recs) == 2 and g.read_bytes() == before


@pytest.mark.fast
def test_failed_write_keeps_no_partial_golden(tmp_path, monkeypatch):
    maps = generate_suite(tmp_path, "free", count=1, seed=1, size=(5, 5), paths=10)

    def boom(f, **fields):
        f.write(b"PK\x03\x04 partial")
        raise OSError(28, "No space left on device")

    monkeypatch.setattr(R.np, "savez_compressed", boom)
    with pytest.raises(NavfnInputError, match="cannot write"):
        record_suite(tmp_path)
    assert sorted(p.name for p in maps[0].directory.iterdir()) == ["map.bin", "test.txt"]


def test_bad_input(tmp_path):
    generate_suite(tmp_path, "free", count=1, size=(5, 5), paths=4)
    for kwargs, words in [({"modes": ("astar", "bfs")}, "mode"), ({"backend": "gpu"}, "unknown backend"),
                          ({"full_first": -1}, "--full-first")]:
        with pytest.raises(NavfnInputError, match=words):
            record_suite(tmp_path, **kwargs)
    with pytest.raises(NavfnInputError, match="no such suite"):
        record_suite(tmp_path / "missing")


@pytest.mark.fast
def test_progress_callback(tmp_path):
    generate_suite(tmp_path, "maze", count=2, seed=1, size=(9, 9), paths=30)
    seen = []
    record_suite(tmp_path, progress=seen.append)
    assert [(r.mode, r.cases) for r in seen] == [("astar", 30), ("dijkstra", 30)] * 2
    assert all(r.category == "maze" and r.path.exists() and r.seconds >= 0 for r in seen)
