"""``navfn-smt path-quality [SUITE]``: the shape of the fix's paths beside NavFn's own gradient
paths, on every case of a suite (:mod:`navfn_smt.report.path_quality`, docs/fix.md)."""

from __future__ import annotations

import json

from .common import MODE_HELP, check_files, suite_or_example, vars_of

COLUMNS = ("paths", "length / optimum: median", "p95", "max", "spacing: mean", "median", "max", "turn per cell (rad, median)",
           "final heading on an axis")


def _cells(row: dict) -> list[str]:
    if not row["paths"]:
        return [f"{row['paths']:,}", *["-"] * (len(COLUMNS) - 1)]
    r = row["length_over_optimum"]
    return [f"{row['paths']:,}", *(f"{r[k]:.3f}" if r else "-" for k in ("median", "p95", "max")),
            f"{row['spacing']['mean']:.3f}", f"{row['spacing']['median']:.3f}", f"{row['spacing']['max']:.3f}", f"{row['turn_per_cell_median']:.3f}",
            f"{100 * row['final_heading_on_an_axis']:.1f} %"]


def cmd_path_quality(args) -> int:
    from ..fileio import atomic_write_text
    from ..maps.suite import discover, load_map, modes_of
    from ..report.path_quality import measure_suite

    check_files(args.json)
    root = suite_or_example(args.suite)
    maps = [load_map(d, root) for d in discover(root)]
    doc = measure_suite(maps, modes_of(args.mode))
    c = doc["counts"]
    print(f"{root}: {len(maps)} maps, {c['cases']:,} case runs; NavFn as shipped returns no path in "
          f"{c['original_fails']:,}, the fix still none in {c['fixed_fails_too']:,} "
          f"({c['fixed_fails_from_a_reached_start']:,} of them from a start the wave reached)")
    print("| group | " + " | ".join(COLUMNS) + " |")
    print("|---|" + "---|" * len(COLUMNS))
    for group, row in doc["groups"].items():
        print(f"| {group} | " + " | ".join(_cells(row)) + " |")
    if args.json:
        atomic_write_text(args.json, json.dumps({"command": "path-quality", "arguments": vars_of(args), **doc},
                                                indent=1) + "\n")
    return 0


def register(sub) -> None:
    """The command's parser, its options and its handler."""
    from ..maps.suite import MODE_CHOICES

    p = sub.add_parser("path-quality", help="the fix's paths beside NavFn's own: length against the grid optimum, "
                       "point spacing, turns, the final heading",
                       description="Plan every case of SUITE (default: the example suite) with NavFn as shipped and "
                       "with the fix (JIT backend) and measure the paths of three groups: NavFn's own gradient paths, "
                       "the fix's paths where it propagates on, and the fix's descent paths: length against the "
                       "shortest 8-connected path over passable cells, point spacing, heading change per cell, and "
                       "how often the final heading (use_final_approach_orientation) lies on an axis.")
    p.add_argument("suite", nargs="?", metavar="SUITE", help="a suite folder (default: the example suite)")
    p.add_argument("--mode", choices=MODE_CHOICES, default="both", help=MODE_HELP)
    p.add_argument("--json", metavar="FILE", help="write the counts and every group's figures as JSON")
    p.set_defaults(func=cmd_path_quality)
