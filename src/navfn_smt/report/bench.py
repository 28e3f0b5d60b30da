"""What ``bench`` reports: the timing tables and their JSON documents."""

from __future__ import annotations

import json

from rich.table import Table

from ..fileio import atomic_write_text
from .tables import console

SUITE_COLUMNS = ["backend", "mode", "cases", "seconds", "cases_per_second"]
SIZE_COLUMNS = ["backend", "size", "map", "mode", "seconds_per_plan", "path_points", "dropped_pushes", "work_bytes"]


def duration(seconds) -> str:
    """A time in a unit that shows it: ``850 ns``, ``42.1 µs``, ``3.20 ms``, ``1.53 s``."""
    if seconds is None:
        return "-"
    s = float(seconds)
    for unit, scale in (("s", 1.0), ("ms", 1e-3), ("µs", 1e-6)):
        if s >= scale:
            v = s / scale
            return f"{v:.3g} {unit}" if v < 100 else f"{v:.0f} {unit}"
    return f"{s / 1e-9:.3g} ns" if s > 0 else "0 s"


def size_in_bytes(b) -> str:
    """Bytes in a unit that shows them (``-`` for 0: not measured)."""
    if not b:
        return "-"
    for unit, scale in (("GiB", 2**30), ("MiB", 2**20), ("KiB", 2**10)):
        if b >= scale:
            return f"{b / scale:.3g} {unit}"
    return f"{b} B"


def _table(title: str, rows: list[dict], cols: list[str], headers=None, fmt=None, extra=None) -> None:
    """Print ``rows`` under ``title``: the given columns, renamed by ``headers``, formatted by ``fmt``;
    ``extra`` computes columns a row does not hold."""
    headers = headers or {}
    fmt = fmt or {}
    rows = [{**r, **{c: f(r) for c, f in (extra or {}).items()}} for r in rows]
    t = Table(title=title)
    for c in cols:
        t.add_column(headers.get(c, c), justify="right" if c not in ("backend", "mode", "map") else "left")
    for r in rows:
        t.add_row(*(fmt.get(c, str)(r[c]) for c in cols))
    console.print(t)


def suite_table(suite, rows: list[dict]) -> None:
    """Print cases per second per backend and mode on a whole suite."""
    _table("bench: whole suite " + str(suite), rows, SUITE_COLUMNS + ["per_case"],
           headers={"cases_per_second": "cases/s", "seconds": "time", "per_case": "per case"},
           fmt={"seconds": duration, "per_case": duration},
           extra={"per_case": lambda r: r["seconds"] / r["cases"] if r["cases"] else None})


def sizes_table(rows: list[dict]) -> None:
    """Print seconds per plan and working memory per backend, size, map and mode."""
    _table("bench: generated maps, time per plan", rows, SIZE_COLUMNS,
           headers={"seconds_per_plan": "time/plan", "path_points": "points", "dropped_pushes": "dropped",
                    "work_bytes": "work memory"},
           fmt={"work_bytes": size_in_bytes, "seconds_per_plan": duration})


def oracle_table(suite, distribution: str, rows: list[dict]) -> None:
    """Print the C++'s and the JIT's planning times on a suite and their ratio."""
    _table(f"bench: the JIT against the C++ NavFn ({distribution}), planning only, {suite}", rows,
           ["mode", "cases", "arithmetic", "cpp_seconds", "jit_seconds", "jit_over_cpp", "cpp_call_seconds"],
           headers={"cpp_seconds": "C++", "jit_seconds": "jit", "jit_over_cpp": "jit / C++",
                    "cpp_call_seconds": "C++ with transfer"},
           fmt={"cpp_seconds": duration, "jit_seconds": duration, "cpp_call_seconds": duration,
                "jit_over_cpp": lambda v: f"{v:.2f}x"})


def fix_table(suite, rows: list[dict], name: str = "fixed") -> None:
    """Print what a fix (``name``) costs where it does not act: the C++ and the JIT, as shipped and
    with the fix (the ``*_fixed`` figures)."""
    ratio = lambda v: f"{v:.3f}x"  # noqa: E731
    _table(f"bench: the {name} fix where the original plans (C++ as shipped and patched, JIT without and with it), "
           f"{suite}",
           rows, ["mode", "cases_the_original_plans", "cpp_original", "cpp_fixed", "cpp_fixed_over_original",
                  "jit_original", "jit_fixed", "jit_fixed_over_original"],
           headers={"cases_the_original_plans": "cases", "cpp_original": "C++", "cpp_fixed": f"C++ {name}",
                    "cpp_fixed_over_original": f"{name} / original", "jit_original": "jit", "jit_fixed": f"jit {name}",
                    "jit_fixed_over_original": f"{name} / original"},
           fmt={"cpp_original": duration, "cpp_fixed": duration, "jit_original": duration, "jit_fixed": duration,
                "cpp_fixed_over_original": ratio, "jit_fixed_over_original": ratio})


def worst_cases_table(folder, rows: list[dict], program: str = "navfn-plain-fixed") -> None:
    """Print a fix's worst cases: time, path points and peak memory, as shipped and patched
    (``program``; the ``fixed`` figures)."""
    _table(f"bench: the fix's worst cases, C++ of {folder} as shipped (navfn-plain) and patched ({program})",
           rows, ["size", "case", "mode", "t_original", "t_fixed", "points_original", "points_fixed", "mem_original",
                  "mem_fixed"],
           headers={"t_original": "time", "t_fixed": "time fixed", "points_original": "path points",
                    "points_fixed": "path points fixed", "mem_original": "peak memory", "mem_fixed": "peak memory fixed"},
           fmt={"t_original": duration, "t_fixed": duration, "mem_original": size_in_bytes, "mem_fixed": size_in_bytes},
           extra={f"{k}_{v}": (lambda r, key=key, v=v: r[v][key]) for k, key in (
               ("t", "seconds"), ("points", "path_points"), ("mem", "peak_memory_bytes")) for v in ("original", "fixed")})


def write_worst_cases_json(path, folder, build: dict, rows: list[dict]) -> None:
    """Write the worst cases with the build they ran on (its compiler, flags and patch)."""
    atomic_write_text(path, json.dumps({"oracle": str(folder), "build": build, "results": rows}, indent=1))


def write_suite_json(path, suite, rows: list[dict]) -> None:
    """Write a suite benchmark as one JSON document."""
    atomic_write_text(path, json.dumps({"suite": str(suite), "results": rows}, indent=1))


def write_sizes_json(path, seed: int, rows: list[dict]) -> None:
    """Write a generated-map benchmark (with the maps' random seed) as one JSON document."""
    atomic_write_text(path, json.dumps({"seed": seed, "results": rows}, indent=1))


# ------------------------------------------------------------------------- whole-map sweep
SWEEP_COLUMNS = ["mode", "size", "goals", "seconds", "goals_per_second", "first_call_seconds", "planned",
                 "issue_4655", "no_path"]


def sweep_table(rows: list[dict]) -> None:
    """Print goals per second of the whole-map sweep per mode."""
    _table("bench: whole-map sweep (one robot pose, every free cell a goal)", rows, SWEEP_COLUMNS,
           headers={"seconds": "time", "goals_per_second": "goals/s", "first_call_seconds": "1st call",
                    "issue_4655": "#4655", "no_path": "no path", "mode": "mode"},
           fmt={"seconds": duration, "first_call_seconds": duration})


def write_sweep_json(path, seed: int, rows: list[dict]) -> None:
    """Write a sweep benchmark (with its map's seed) as one JSON document."""
    atomic_write_text(path, json.dumps({"seed": seed, "sweep": rows}, indent=1))


CLIMB_COLUMNS = ["mode", "steps", "maps", "plans", "seconds", "maps_per_second", "best_gap"]


def climb_table(rows: list[dict]) -> None:
    """Print maps per second of the cost climb per mode and kind of step."""
    _table("bench: the cost climb on 5x7 maps (same seed, same climb)", rows, CLIMB_COLUMNS,
           headers={"seconds": "time", "maps_per_second": "maps/s", "best_gap": "best gap"},
           fmt={"seconds": duration, "best_gap": lambda g: f"{g:g}"})


def write_climb_json(path, seed: int, rows: list[dict]) -> None:
    """Write a climb benchmark (with its seed) as one JSON document."""
    atomic_write_text(path, json.dumps({"seed": seed, "climb": rows}, indent=1))
