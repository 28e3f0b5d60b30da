"""``navfn-smt``: one thin command layer over the parts of the toolkit.

Every user error (bad map, missing file, cell off the map, ...) is printed as one line
``navfn-smt: error: ...`` with exit status 2; disagreements found by ``difftest`` exit
with status 1.  No traceback reaches the user for bad input.
"""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

from .errors import NavfnInputError
from .fileio import atomic_write_text, check_writable

EXAMPLE_SUITE = Path(__file__).parent / "examples" / "suite"


# ----------------------------------------------------------------------------------- plan
def _is_yaml(path: Path) -> bool:
    return path.suffix.lower() in (".yaml", ".yml")


def _cell(what: str, v) -> tuple[int, int]:
    """A map cell from two command-line numbers (which must be integers)."""
    if any(not float(c).is_integer() for c in v):
        raise NavfnInputError(f"--{what} {v[0]:g} {v[1]:g}: a map cell needs integers (use --world for world coordinates)")
    return int(v[0]), int(v[1])


def _load_plan_map(args):
    import numpy as np

    from .maps.suite import load_map, read_map_bytes

    m = Path(args.map)
    if _is_yaml(m):
        if args.size:
            raise NavfnInputError(f"{m}: --size is for a raw map file; a map_server map has its own size")
        from .maps.mapserver import load_map_yaml

        return load_map_yaml(m, args.allow_outside, distro=args.distro).navfn_costs
    if m.is_dir():
        if args.size:
            raise NavfnInputError(f"{m}: --size is for a raw map file; a map directory has its size in test.txt")
        return load_map(m).costs
    if not m.exists():
        raise NavfnInputError(f"{m}: no such map file or directory")
    if not args.size:
        raise NavfnInputError(f"{m}: a raw map file needs --size W H")
    w, h = args.size
    if w < 3 or h < 3:
        raise NavfnInputError(f"--size {w} {h}: NavFn needs at least 3x3 cells")
    return np.asarray(read_map_bytes(m, w, h))


def _plan_world(args) -> int:
    from .maps.mapserver import plan_world

    if not _is_yaml(Path(args.map)):
        raise NavfnInputError(f"{args.map}: --world needs a map_server YAML map")
    wp = plan_world(args.map, tuple(args.start), tuple(args.goal), astar=not args.dijkstra,
                    backend=args.backend, allow_outside=args.allow_outside, distro=args.distro)
    res = wp.result
    path = [[float(x), float(y)] for x, y in wp.path_world]
    if args.json:
        out = {
            "mode": "dijkstra" if args.dijkstra else "astar", "backend": args.backend, "world": True,
            "start": list(args.start), "goal": list(args.goal),
            "start_cell": list(wp.start_cell), "goal_cell": list(wp.goal_cell),
            "start_reached": None if res is None else bool(res.start_reached),
            "start_potential": None if res is None else float(res.start_potential),
            "cycles": None if res is None else int(res.cycles),
            "exit": None if res is None or res.exit is None else res.exit.value,
            "path": path,
        }
        print(json.dumps(out))
        return 0
    print(f"map {wp.map.path} ({wp.map.width}x{wp.map.height} cells of {wp.map.resolution} m)")
    print(f"robot {tuple(args.start)} -> cell {wp.start_cell}; goal {tuple(args.goal)} -> cell {wp.goal_cell}")
    if res is None:
        print("start and goal poses are equal: Nav2 returns the pose without planning")
    else:
        print(f"NavFn runs from the goal cell back to the robot's (Nav2 swaps them); start reached: "
              f"{res.start_reached}; cycles: {res.cycles}")
    _print_path(path, "poses (world coordinates)", res)
    return 0


def cmd_plan(args) -> int:
    from .backends import get_backend

    if args.world:
        return _plan_world(args)
    start, goal = _cell("start", args.start), _cell("goal", args.goal)
    costs = _load_plan_map(args)
    runner = get_backend(args.backend).prepare(costs)
    res = runner.run(start, goal, astar=not args.dijkstra, trace=False)
    path = [[float(x), float(y)] for x, y in res.path]
    if args.json:
        out = {
            "mode": "dijkstra" if args.dijkstra else "astar",
            "backend": args.backend,
            "start": list(start),
            "goal": list(goal),
            "start_reached": bool(res.start_reached),
            "start_potential": float(res.start_potential),
            "cycles": int(res.cycles),
            "updates": int(res.updates),
            "dropped_pushes": int(res.dropped),
            "exit": res.exit.value if res.exit else None,
            "path": path,
        }
        print(json.dumps(out))
        return 0
    print(f"mode {'dijkstra' if args.dijkstra else 'astar'}, start {start}, goal {goal}")
    print(f"start reached: {res.start_reached}; start potential: {float(res.start_potential):.9g}; "
          f"cycles: {res.cycles}; updates: {res.updates}; dropped pushes: {res.dropped}")
    _print_path(path, "points", res)
    return 0


def _print_path(path, unit: str, res) -> None:
    if path:
        print(f"path: {len(path)} {unit}")
        for x, y in path:
            print(f"  {x:.9g} {y:.9g}")
    else:
        print(f"no path (calcPath returned 0: {res.exit.value if res and res.exit else 'unknown'})")


# ------------------------------------------------------------------------------- difftest
def cmd_difftest(args) -> int:
    from .difftest.runner import plan_tasks, run_suite, summarize
    from .report.tables import difftest_table, progress_bar

    suite = Path(args.suite) if args.suite else EXAMPLE_SUITE
    modes = ("astar", "dijkstra") if args.mode == "both" else (args.mode,)
    if args.json:
        check_writable(args.json)  # fail early, before the run
    tasks = plan_tasks(suite, modes, args.backend)
    total = sum(t.hi - t.lo for t in tasks)
    jobs = args.jobs if args.jobs else 1
    with progress_bar(total, f"difftest {suite} ({args.backend})", enabled=not args.quiet) as advance:
        outcomes = run_suite(suite, modes, args.backend, jobs, progress=lambda o: advance(o.cases), tasks=tasks)
    summary = summarize(outcomes)
    difftest_table(summary)
    if args.json:
        doc = {"suite": str(suite), "backend": args.backend, "modes": list(modes), **summary}
        atomic_write_text(args.json, json.dumps(doc, indent=1))
    print(f"{summary['passed']} passed, {summary['failed']} failed")
    return 0 if summary["failed"] == 0 else 1


# --------------------------------------------------------------------------------- render
def cmd_render(args) -> int:
    from .backends import get_backend
    from .maps.pictures import render_case
    from .maps.suite import load_map

    m = Path(args.map)
    if _is_yaml(m):
        from types import SimpleNamespace

        from .maps.mapserver import load_map_yaml

        ms = load_map_yaml(m, args.allow_outside)
        smap = SimpleNamespace(name=m.stem, costs=ms.navfn_costs, cases=[])
        if not (args.start and args.goal):
            raise NavfnInputError(f"{m}: a map_server map has no cases; give --start X Y --goal X Y (cells)")
    elif not m.is_dir():
        raise NavfnInputError(f"{m}: not a suite map directory or map_server YAML")
    else:
        smap = load_map(m)
    if args.start or args.goal:
        if not (args.start and args.goal):
            raise NavfnInputError("--start and --goal go together")
        start, goal = tuple(args.start), tuple(args.goal)
    else:
        if not 0 <= args.case < len(smap.cases):
            raise NavfnInputError(f"--case {args.case}: {m} has cases 0..{len(smap.cases) - 1}")
        sx, sy, gx, gy = (int(v) for v in smap.cases[args.case])
        start, goal = (sx, sy), (gx, gy)
    res = get_backend(args.backend).prepare(smap.costs).run(start, goal, astar=not args.dijkstra, trace=False)
    hl = None
    if args.highlight:
        if len(args.highlight) not in (2, 4):
            raise NavfnInputError("--highlight takes X Y (a cell) or X1 Y1 X2 Y2 (a segment)")
        hl = [tuple(args.highlight[i:i + 2]) for i in range(0, len(args.highlight), 2)]
    mode = "Dijkstra" if args.dijkstra else "A*"
    render_case(smap.costs, res, start, goal, args.output, title=f"{smap.name} ({mode})", highlight=hl,
                arrows=None if args.arrows == "auto" else args.arrows == "on")
    print(f"wrote {args.output}")
    return 0


# ---------------------------------------------------------------------------- metamorphic
def cmd_metamorphic(args) -> int:
    from rich.table import Table

    from .maps.suite import discover, load_map
    from .report.tables import console, progress_bar
    from .search.metamorphic import TRANSFORMS, run_metamorphic, save_counterexample

    suite = Path(args.suite) if args.suite else EXAMPLE_SUITE
    relations = args.relation or list(TRANSFORMS)
    modes = ("astar", "dijkstra") if args.mode == "both" else (args.mode,)
    if args.max_cases is not None and args.max_cases < 1:
        raise NavfnInputError("--max-cases must be at least 1")
    if args.json:
        check_writable(args.json)
    per_map = [len(load_map(d).cases) for d in discover(suite)]
    total = sum(min(n, args.max_cases or n) for n in per_map) * len(relations) * len(modes)
    with progress_bar(total, f"metamorphic {suite}") as advance:
        outcomes = run_metamorphic(suite, relations, modes, args.backend, args.max_cases, progress=advance)
    t = Table(title="metamorphic relations: result on the transformed map == transformed result")
    for c in ("relation", "mode", "cases", "potential", "path", "reached", "holds", "saved"):
        t.add_column(c, justify="left" if c in ("relation", "mode") else "right")
    rows = []
    for o in outcomes:
        tr = TRANSFORMS[o.relation]
        saved = [str(save_counterexample(Path(args.save), o.relation, cx, tr))
                 for cx in (o.counterexamples[: args.save_max] if args.save else [])]
        rows.append({
            "relation": o.relation, "mode": o.mode, "cases": o.cases, "holds": o.holds,
            "potential_equal": o.potential_equal if tr.same_potential else None,
            "path_equal": o.path_equal, "start_reached_equal": o.reached_equal, "saved": saved,
            "counterexamples": [{k: cx[k] for k in ("case_index", "case", "transformed_case", "mode",
                                                    "potential", "path", "reached")} | {"map": cx["map"].name}
                                for cx in o.counterexamples],
        })
        t.add_row(o.relation, o.mode, str(o.cases), str(o.potential_equal) if tr.same_potential else "n/a",
                  str(o.path_equal), str(o.reached_equal), str(o.holds), str(len(saved)))
    console.print(t)
    if args.json:
        atomic_write_text(args.json, json.dumps({"suite": str(suite), "relations": rows}, indent=1))
    if args.save:
        print(f"counterexamples saved under {args.save} (at most {args.save_max} per relation and mode)")
    return 0


# ------------------------------------------------------------------------------- coverage
def cmd_coverage(args) -> int:
    from rich.table import Table

    from .difftest.coverage import LIBRARY_FILES, measure, percent
    from .maps.suite import discover, load_map
    from .report.tables import console, progress_bar

    suites = [Path(s) for s in args.suite] if args.suite else [EXAMPLE_SUITE]
    modes = ("astar", "dijkstra") if args.mode == "both" else (args.mode,)
    if args.max_cases is not None and args.max_cases < 1:
        raise NavfnInputError("--max-cases must be at least 1")
    if args.json:
        check_writable(args.json)
    total = sum(min(len(load_map(d).cases), args.max_cases or 10**12) for s in suites for d in discover(s))
    with progress_bar(total * len(modes), "coverage") as advance:
        r = measure(suites, modes, args.max_cases, progress=advance)
    t = Table(title=f"coverage of the reference spec ({r['cases_run']} case runs)")
    for c in ("file", "lines", "covered", "branches", "covered ", "branch %"):
        t.add_column(c, justify="left" if c == "file" else "right")
    for f in r["files"]:
        name = f["file"] + (" (library)" if f["file"] in LIBRARY_FILES else "")
        t.add_row(name, str(f["lines"]), str(f["lines_covered"]), str(f["branches"]),
                  str(f["branches_covered"]), percent(f["branches_covered"], f["branches"]))
    t.add_row("spec (without library)", str(r["lines"]), str(r["lines_covered"]), str(r["branches"]),
              str(r["branches_covered"]), percent(r["branches_covered"], r["branches"]))
    console.print(t)
    print(f"kernel decisions (ite outcomes, per line): {r['ite_outcomes_covered']} of {r['ite_outcomes']} "
          f"({percent(r['ite_outcomes_covered'], r['ite_outcomes'])})")
    if r["uncovered"]:
        print("not covered:")
        for u in r["uncovered"]:
            why = u["reason"] or "no reason recorded: a suite case could reach it"
            print(f"  {u['kind']} {u['file']}:{u['line']} -> {u['to']}: {u['source']}\n      {why}")
    if args.json:
        atomic_write_text(args.json, json.dumps({"suites": [str(s) for s in suites], "modes": list(modes), **r},
                                                 indent=1))
    unexplained = [u for u in r["uncovered"] if not u["reason"]]
    print(f"spec branch coverage {percent(r['branches_covered'], r['branches'])}; "
          f"{len(r['uncovered'])} uncovered branches and decisions, {len(unexplained)} without a reason")
    if args.min_branch is not None and r["branch_percent"] < args.min_branch:
        return 1
    return 0


# ---------------------------------------------------------------------------------- prove
PROOFS_DIR = Path(__file__).resolve().parents[2] / "proofs"


def cmd_prove(args) -> int:
    import datetime

    from .report import proofs as rp
    from .report.tables import progress_bar
    from .smt.runner import SEMANTICS, default_proof_files, run
    from .smt.solvers import SOLVERS

    files = [Path(f) for f in args.files] if args.files else default_proof_files(PROOFS_DIR)
    semantics = SEMANTICS if args.semantics == "both" else (args.semantics,)
    if args.timeout <= 0:
        raise NavfnInputError("--timeout must be positive")
    if args.jobs < 1:
        raise NavfnInputError("--jobs must be at least 1")
    for f in (args.report, args.junit, args.markdown):
        if f:
            check_writable(f)
    solvers = tuple(args.solver) if args.solver else SOLVERS
    from .smt.obligation import load_obligations

    n = sum(len([s for s in semantics if s in o.expect]) for o in load_obligations(files))
    with progress_bar(n, "prove") as advance:
        outcomes = run(files, semantics, args.timeout, args.jobs, solvers, progress=lambda o: advance(1),
                       bounds=not args.no_bound_search)
    witness_files = {}
    for o in outcomes:
        if o.witness:
            wdir = Path(args.witness_dir)
            wdir.mkdir(parents=True, exist_ok=True)
            w = wdir / f"{o.name}.{o.semantics}.json"
            atomic_write_text(w, json.dumps({"obligation": o.name, "property": o.predicate, "semantics": o.semantics,
                                             "statement": o.statement, **o.witness}, indent=1))
            witness_files[(o.name, o.semantics)] = str(w)
    if args.smt2:
        from .smt.runner import write_smt2

        write_smt2(files, semantics, Path(args.smt2))
    rp.table(outcomes)
    meta = {"when": datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC"),
            "timeout": args.timeout, "solvers": list(solvers), "semantics": list(semantics),
            "files": [str(f) for f in files]}
    if args.report:
        rp.write_json(args.report, outcomes, witness_files, meta)
    if args.junit:
        rp.write_junit(args.junit, outcomes)
    if args.markdown:
        rp.write_markdown(args.markdown, outcomes, meta)
    bad = [o for o in outcomes if not o.as_expected]
    print(f"{len(outcomes) - len(bad)} passed, {len(bad)} failed"
          + (": " + ", ".join(f"{o.name}[{o.semantics}] {o.status} (expected {o.expected})" for o in bad) if bad else ""))
    return 1 if bad else 0


# --------------------------------------------------------------------------------- mutate
def cmd_mutate(args) -> int:
    from rich.table import Table

    from .report.tables import console, progress_bar
    from .search.mutation import MUTANTS, run_mutant
    from .smt.runner import default_proof_files

    chosen = [m for m in MUTANTS if not args.mutant or m.name in args.mutant]
    unknown = set(args.mutant or []) - {m.name for m in MUTANTS}
    if unknown:
        raise NavfnInputError(f"unknown mutant(s): {', '.join(sorted(unknown))}")
    if args.json:
        check_writable(args.json)
    files = default_proof_files(PROOFS_DIR)
    suite = Path(args.suite) if args.suite else EXAMPLE_SUITE
    results = []
    with progress_bar(len(chosen), "mutants") as advance:
        for m in chosen:
            results.append(run_mutant(m, files, suite, args.timeout))
            advance(1)
    t = Table(title="mutation check: seeded bugs and what caught them")
    for c in ("mutant", "seeded bug", "caught by", "seconds"):
        t.add_column(c, overflow="fold")
    for r in results:
        t.add_row(r.name, r.what, ", ".join(r.caught_by) or "[red]survived[/]", f"{r.seconds:.0f}")
    console.print(t)
    caught = sum(r.caught for r in results)
    if args.json:
        atomic_write_text(args.json, json.dumps({"score": f"{caught}/{len(results)}", "mutants": [
            {"name": r.name, "what": r.what, "caught_by": r.caught_by, "details": r.details, "seconds": r.seconds}
            for r in results]}, indent=1, default=str))
    print(f"mutation score: {caught} of {len(results)} seeded bugs caught")
    return 0


# ---------------------------------------------------------------------------------- bench
def cmd_bench(args) -> int:
    from .bench import bench_sizes, bench_suite

    if args.size:
        bench_sizes(args.size, args.backend, args.repeat, args.json)
        return 0
    suite = Path(args.suite) if args.suite else EXAMPLE_SUITE
    bench_suite(suite, args.backend, args.mode, args.json)
    return 0


# ---------------------------------------------------------------------------------- main
def build_parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(
        prog="navfn-smt",
        description="Executable specification of Nav2's NavFn planner, differential testing "
        "against the C++ original, and SMT proofs of its invariants.",
    )
    sub = p.add_subparsers(dest="command", required=True, metavar="COMMAND")

    pl = sub.add_parser("plan", help="plan on one map and print the path")
    pl.add_argument("map", help="a suite map directory (test.txt gives the size), a map_server YAML, "
                    "or a raw map file with --size")
    pl.add_argument("--size", nargs=2, type=int, metavar=("W", "H"), help="size of a raw map file")
    pl.add_argument("--start", nargs=2, type=float, required=True, metavar=("X", "Y"),
                    help="NavFn's start cell (where the path begins); with --world the robot's position")
    pl.add_argument("--goal", nargs=2, type=float, required=True, metavar=("X", "Y"),
                    help="NavFn's goal cell (where propagation begins); with --world the goal position")
    pl.add_argument("--world", action="store_true",
                    help="start and goal are world coordinates on a map_server YAML map, planned as Nav2's "
                    "NavFn planner plugin does (it swaps them before calling NavFn)")
    pl.add_argument("--allow-outside", action="store_true",
                    help="let a map_server YAML name an image outside its own folder")
    pl.add_argument("--distro", default="rolling",
                    help="Nav2 distribution whose map loading rules apply (humble, iron, jazzy, kilted, "
                    "lyrical, rolling; default rolling)")
    pl.add_argument("--dijkstra", action="store_true", help="Dijkstra propagation (default: A*)")
    pl.add_argument("--backend", choices=("jit", "reference"), default="jit")
    pl.add_argument("--json", action="store_true", help="print a JSON object")
    pl.set_defaults(func=cmd_plan)

    dt = sub.add_parser("difftest", help="compare every case of a suite with its golden files")
    dt.add_argument("suite", nargs="?", help="suite directory (default: the example suite shipped with the package)")
    dt.add_argument("--mode", choices=("astar", "dijkstra", "both"), default="both")
    dt.add_argument("--backend", choices=("jit", "reference"), default="jit")
    dt.add_argument("--jobs", type=int, default=1, help="worker processes (default 1)")
    dt.add_argument("--json", metavar="FILE", help="write per-map counts and every disagreement as JSON")
    dt.add_argument("--quiet", action="store_true", help="no progress bar")
    dt.set_defaults(func=cmd_difftest)

    rd = sub.add_parser("render", help="draw a planning case: costmap, potential, path, gradient")
    rd.add_argument("map", help="a suite map directory or a map_server YAML")
    rd.add_argument("--allow-outside", action="store_true",
                    help="let a map_server YAML name an image outside its own folder")
    rd.add_argument("--case", type=int, default=0, help="case index in test.txt (default 0)")
    rd.add_argument("--start", nargs=2, type=int, metavar=("X", "Y"), help="plan this start instead of a case")
    rd.add_argument("--goal", nargs=2, type=int, metavar=("X", "Y"))
    rd.add_argument("--dijkstra", action="store_true")
    rd.add_argument("--backend", choices=("jit", "reference"), default="jit")
    rd.add_argument("--highlight", nargs="+", type=float, metavar="V",
                    help="mark a cell (X Y) or a segment (X1 Y1 X2 Y2), e.g. a counterexample")
    rd.add_argument("--arrows", choices=("auto", "on", "off"), default="auto",
                    help="gradient arrows (auto: on maps up to 60 cells a side)")
    rd.add_argument("-o", "--output", required=True, metavar="FILE", help="a .png or .svg file")
    rd.set_defaults(func=cmd_render)

    mm = sub.add_parser("metamorphic", help="check map symmetries: transposes, flips, rotations, padding, cost shifts")
    mm.add_argument("suite", nargs="?", help="suite directory (default: the example suite)")
    mm.add_argument("--relation", action="append", choices=("transpose", "flip_x", "flip_y", "rot90", "rot180",
                                                           "rot270", "pad", "cost_shift"),
                    help="check only this relation (repeatable; default: all)")
    mm.add_argument("--mode", choices=("astar", "dijkstra", "both"), default="both")
    mm.add_argument("--backend", choices=("jit", "reference"), default="jit")
    mm.add_argument("--max-cases", type=int, help="at most this many cases per map")
    mm.add_argument("--save", metavar="DIR", default="metamorphic-counterexamples",
                    help="where counterexamples are saved as suite map directories ('' to not save)")
    mm.add_argument("--save-max", type=int, default=3, help="counterexamples saved per relation and mode")
    mm.add_argument("--json", metavar="FILE", help="write the counts and counterexamples as JSON")
    mm.set_defaults(func=cmd_metamorphic)

    cv = sub.add_parser("coverage", help="line, branch and kernel-decision coverage of the reference spec under a suite")
    cv.add_argument("suite", nargs="*", help="suite directories, measured together (default: the example suite)")
    cv.add_argument("--mode", choices=("astar", "dijkstra", "both"), default="both")
    cv.add_argument("--max-cases", type=int, help="at most this many cases per map (the spec runs traced: slow)")
    cv.add_argument("--min-branch", type=float, help="exit 1 when branch coverage is below this percentage")
    cv.add_argument("--json", metavar="FILE", help="write the figures and every uncovered branch as JSON")
    cv.set_defaults(func=cmd_coverage)

    from .maps.suite_cli import register as register_suite

    register_suite(sub)

    from .smt.solvers import SOLVERS

    pr = sub.add_parser("prove", help="check the proof obligations in proofs/ (or the given files)")
    pr.add_argument("files", nargs="*", help="proof files (default: every proofs/*.py)")
    pr.add_argument("--semantics", choices=("real", "fp32", "both"), default="both")
    pr.add_argument("--timeout", type=float, default=30.0, help="seconds per solver query (default 30)")
    pr.add_argument("--jobs", type=int, default=1, help="obligations checked in parallel (default 1)")
    pr.add_argument("--solver", action="append", choices=SOLVERS,
                    help="solvers of the portfolio (repeatable; default all three)")
    pr.add_argument("--report", metavar="FILE.json", help="machine-readable report")
    pr.add_argument("--junit", metavar="FILE.xml", help="JUnit XML, one test case per obligation and semantics")
    pr.add_argument("--markdown", metavar="FILE.md", help="the invariants page (docs/invariants.md)")
    pr.add_argument("--smt2", metavar="DIR", help="also write every query as SMT-LIB2")
    pr.add_argument("--no-bound-search", action="store_true",
                    help="do not search bounds for properties refuted in fp32 (verdicts only)")
    pr.add_argument("--witness-dir", default="proof-witnesses", metavar="DIR",
                    help="where counterexamples are written (default proof-witnesses)")
    pr.set_defaults(func=cmd_prove)

    mu = sub.add_parser("mutate", help="seed bugs in the kernels and domains; report which checks catch them")
    mu.add_argument("--mutant", action="append", metavar="NAME", help="run only this mutant (repeatable)")
    mu.add_argument("--suite", help="suite for the difftest detector (default: the example suite)")
    mu.add_argument("--timeout", type=float, default=30.0, help="seconds per solver query")
    mu.add_argument("--json", metavar="FILE", help="write every mutant's result as JSON")
    mu.set_defaults(func=cmd_mutate)

    be = sub.add_parser("bench", help="time the planner: a whole suite, or generated maps with --size")
    be.add_argument("suite", nargs="?", help="suite directory (default: the example suite)")
    be.add_argument("--size", nargs="+", type=int, metavar="N",
                    help="instead of a suite, plan on generated NxN open and random-cost maps")
    be.add_argument("--backend", choices=("jit", "reference", "all"), default="all")
    be.add_argument("--mode", choices=("astar", "dijkstra", "both"), default="both")
    be.add_argument("--repeat", type=int, default=3, help="plans per map and mode with --size (best is kept)")
    be.add_argument("--json", metavar="FILE", help="write the figures as JSON")
    be.set_defaults(func=cmd_bench)
    return p


def main(argv=None) -> int:
    parser = build_parser()
    args = parser.parse_args(argv)
    if getattr(args, "jobs", 1) is not None and getattr(args, "jobs", 1) < 1:
        parser.error("--jobs must be at least 1")
    try:
        return args.func(args)
    except NavfnInputError as e:
        print(f"navfn-smt: error: {e}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        print("navfn-smt: interrupted", file=sys.stderr)
        return 130
    except BrokenPipeError:
        return 1


if __name__ == "__main__":
    sys.exit(main())
