"""``navfn-smt``: the command line, only argument parsing and calls.

Each ``cmd_*`` checks its arguments and output paths, calls the part of the toolkit that
does the work, and hands the results to a reporter in :mod:`navfn_smt.report`, which owns
every table, JSON document and file written.  Choice lists come from the code that owns
them.

Every user error (bad map, missing file, cell off the map, unwritable output, ...) is
printed as one line ``navfn-smt: error: ...`` with exit status 2, before any long work
when it is about an output path; disagreements found by ``difftest`` exit with status 1.
No traceback reaches the user for bad input.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from .errors import NavfnInputError
from .fileio import check_writable, check_writable_dir

EXAMPLE_SUITE = Path(__file__).parent / "examples" / "suite"


def _suite(arg) -> Path:
    """The suite a command names, or the example suite shipped with the package."""
    return Path(arg) if arg else EXAMPLE_SUITE


def _check_max_cases(n) -> None:
    """Reject a ``--max-cases`` below 1."""
    if n is not None and n < 1:
        raise NavfnInputError("--max-cases must be at least 1")


def _check_positive(option: str, value, allow_zero: bool = False) -> None:
    """Reject a number option that is not a positive finite number (NaN included)."""
    import math

    ok = value is None or (math.isfinite(value) and (value >= 0 if allow_zero else value > 0))
    if not ok:
        raise NavfnInputError(f"{option} {value:g}: must be a {'non-negative' if allow_zero else 'positive'} number")


def _check_files(*paths) -> None:
    """Fail early, before the run, on any output file that could not be written."""
    for p in paths:
        if p:
            check_writable(p)


# ----------------------------------------------------------------------------------- plan
def _cell(what: str, v) -> tuple[int, int]:
    """A map cell from two command-line numbers (which must be integers)."""
    if len(v) != 2:
        raise NavfnInputError(f"--{what} needs two cell coordinates X Y (a yaw is for --world poses)")
    if any(not float(c).is_integer() for c in v):
        raise NavfnInputError(f"--{what} {v[0]:g} {v[1]:g}: a map cell needs integers (use --world for world coordinates)")
    return int(v[0]), int(v[1])


def _plan_world(args) -> int:
    """Plan between world poses on a map_server map, as Nav2's NavfnPlanner plugin does."""
    from .maps.loading import is_yaml
    from .nav2.plugin import check_pose, create_plan
    from .nav2.setup import COSTMAP_FILES, check_params_file, load_setup
    from .report import plan as report

    if not is_yaml(args.map) and Path(args.map).suffix.lower() not in COSTMAP_FILES:
        raise NavfnInputError(f"{args.map}: --world needs a map_server YAML map or a costmap (.npy, .pgm)")
    if args.size:
        raise NavfnInputError("--size is for a raw map file, not a map_server map")
    start, goal = check_pose("start", args.start), check_pose("goal", args.goal)
    check_params_file(args.params)
    overrides = {"use_astar": True if args.astar else False if args.dijkstra else None}
    setup = load_setup(args.map, args.params, args.distro, args.allow_outside, overrides, args.resolution,
                       tuple(args.origin))
    run = create_plan(setup.costmap, start, goal, setup.params, args.backend)
    report.plugin_plan(setup, run, start, goal, args.backend, args.json)
    return 0 if run.ok else 1


def cmd_plan(args) -> int:
    """Plan on one map and print the path (NavFn itself, or Nav2's plugin with --world)."""
    from .backends import get_backend
    from .maps.loading import load_costs
    from .report import plan as report

    if args.world:
        return _plan_world(args)
    if args.params:
        raise NavfnInputError("--params is for --world planning (Nav2's plugin reads it)")
    if args.astar and args.dijkstra:
        raise NavfnInputError("--astar and --dijkstra exclude each other")
    mode = "dijkstra" if args.dijkstra else "astar"
    start, goal = _cell("start", args.start), _cell("goal", args.goal)
    costs = load_costs(args.map, args.size, args.allow_outside, args.distro)
    res = get_backend(args.backend).prepare(costs).run(start, goal, astar=not args.dijkstra, trace=False)
    report.cell_plan(res, mode, args.backend, start, goal, args.json, costs)
    return 0 if len(res.path) else 1


# ------------------------------------------------------------------------------- difftest
def cmd_difftest(args) -> int:
    """Compare every case of a suite with its golden files; exit 1 on any disagreement."""
    from .difftest.runner import count_cases, modes_of, run_suite
    from .engine import engine
    from .report import difftest as report
    from .report.tables import progress_bar

    suite, modes = _suite(args.suite), modes_of(args.mode)
    eng = engine(args.jobs, args.scheduler)
    _check_files(args.json)
    total = count_cases(suite, modes)
    with progress_bar(total, f"difftest {suite} ({args.backend})", enabled=not args.quiet) as advance:
        summary = run_suite(suite, modes, args.backend, eng=eng, total=total,
                            progress=lambda o: advance(o.cases)).as_dict()
    report.table(summary)
    if args.json:
        report.write_json(args.json, suite, args.backend, modes, summary)
    report.closing_line(summary)
    return 0 if summary["failed"] == 0 else 1


# --------------------------------------------------------------------------------- render
def cmd_render(args) -> int:
    """Draw one planning case of a map into a picture file."""
    from .backends import get_backend
    from .maps.loading import is_yaml, load_case_map
    from .maps.pictures import FORMATS, render_case

    if Path(args.output).suffix.lower() not in FORMATS:
        raise NavfnInputError(f"{args.output}: the picture must be .png or .svg")
    _check_files(args.output)
    path = Path(args.map)
    m = load_case_map(path, args.allow_outside)
    if is_yaml(path) and not (args.start and args.goal):
        raise NavfnInputError(f"{path}: a map_server map has no cases; give --start X Y --goal X Y (cells)")
    if args.start or args.goal:
        if not (args.start and args.goal):
            raise NavfnInputError("--start and --goal go together")
        start, goal = tuple(args.start), tuple(args.goal)
    else:
        if not 0 <= args.case < len(m.cases):
            raise NavfnInputError(f"--case {args.case}: {path} has cases 0..{len(m.cases) - 1}")
        sx, sy, gx, gy = (int(v) for v in m.cases[args.case])
        start, goal = (sx, sy), (gx, gy)
    hl = None
    if args.highlight:
        if len(args.highlight) not in (2, 4):
            raise NavfnInputError("--highlight takes X Y (a cell) or X1 Y1 X2 Y2 (a segment)")
        hl = [tuple(args.highlight[i:i + 2]) for i in range(0, len(args.highlight), 2)]
    _check_files(args.output)
    res = get_backend(args.backend).prepare(m.costs).run(start, goal, astar=not args.dijkstra, trace=False)
    window = render_case(m.costs, res, start, goal, args.output,
                         title=f"{m.name} ({'Dijkstra' if args.dijkstra else 'A*'})", highlight=hl,
                         arrows=None if args.arrows == "auto" else args.arrows == "on", zoom=args.zoom)
    if window:
        x0, x1, y0, y1 = window
        ny, nx = m.costs.shape
        print(f"wrote {args.output} (showing x {x0}..{x1}, y {y0}..{y1} of the {nx}x{ny} map; "
              "--zoom full draws the whole map)")
    else:
        print(f"wrote {args.output}")
    return 0


# ---------------------------------------------------------------------------- metamorphic
def cmd_metamorphic(args) -> int:
    """Check map symmetries on a suite; counterexamples are saved only under ``--save``."""
    from .difftest.runner import modes_of
    from .maps.suite import discover, load_map
    from .report import metamorphic as report
    from .report.tables import progress_bar
    from .search.metamorphic import TRANSFORMS, run_metamorphic

    suite, modes = _suite(args.suite), modes_of(args.mode)
    relations = args.relation or list(TRANSFORMS)
    _check_max_cases(args.max_cases)
    if args.save_max < 0:
        raise NavfnInputError("--save-max must not be negative")
    _check_files(args.json)
    if args.save:
        check_writable_dir(args.save)
    per_map = [len(load_map(d).cases) for d in discover(suite)]
    total = sum(min(n, args.max_cases or n) for n in per_map) * len(relations) * len(modes)
    with progress_bar(total, f"metamorphic {suite}") as advance:
        outcomes = run_metamorphic(suite, relations, modes, args.backend, args.max_cases, progress=advance)
    rows = report.relation_rows(outcomes, report.save_counterexamples(outcomes, args.save, args.save_max))
    report.table(rows)
    if args.json:
        report.write_json(args.json, suite, rows)
    report.saved_note(args.save, args.save_max, rows)
    return 0


# ------------------------------------------------------------------------------- coverage
def cmd_coverage(args) -> int:
    """Measure what a suite exercises of the reference spec; exit 1 below ``--min-branch``."""
    from .difftest.coverage import measure
    from .difftest.runner import modes_of
    from .maps.suite import discover, load_map
    from .report import coverage as report
    from .report.tables import progress_bar

    suites = [Path(s) for s in args.suite] if args.suite else [EXAMPLE_SUITE]
    modes = modes_of(args.mode)
    _check_max_cases(args.max_cases)
    if args.min_branch is not None and not 0 <= args.min_branch <= 100:
        raise NavfnInputError(f"--min-branch {args.min_branch:g}: a percentage from 0 to 100")
    _check_files(args.json)
    total = sum(min(len(load_map(d).cases), args.max_cases or 10**12) for s in suites for d in discover(s))
    with progress_bar(total * len(modes), "coverage") as advance:
        r = measure(suites, modes, args.max_cases, progress=advance)
    report.table(r)
    report.uncovered(r)
    if args.json:
        report.write_json(args.json, suites, modes, r)
    report.closing_line(r)
    if args.min_branch is not None and r["branch_percent"] < args.min_branch:
        print(f"navfn-smt: branch coverage {r['branch_percent']:.1f}% is below --min-branch {args.min_branch:g}%",
              file=sys.stderr)
        return 1
    return 0


# ---------------------------------------------------------------------------------- prove
def _proof_files(names) -> list[Path]:
    """The proof files the command line names (:func:`navfn_smt.smt.runner.proof_files`)."""
    from .smt.runner import proof_files

    return proof_files(names)


def cmd_prove(args) -> int:
    """Check the proof obligations; exit 1 only when a verdict contradicts what is known."""
    from .engine import engine
    from .report import proof_run
    from .report import proofs as report
    from .report.tables import progress_bar
    from .smt.obligation import load_obligations
    from .smt.solvers import SOLVERS
    from .smt.runner import SEMANTICS, default_proof_files, run, slow_queries, write_smt2

    files = _proof_files(args.files) if args.files else default_proof_files()
    semantics = SEMANTICS if args.semantics == "both" else (args.semantics,)
    _check_positive("--timeout", args.timeout)
    eng = engine(args.jobs, args.scheduler)
    _check_files(args.report, args.junit, args.markdown)
    witnesses = proof_run.witness_dir(args.witness_dir, (args.report, args.junit, args.markdown))
    for d in (args.smt2, witnesses):
        if d:
            check_writable_dir(d)
    solvers = tuple(args.solver) if args.solver else SOLVERS
    n = sum(len([s for s in semantics if s in o.expect and (args.all or s not in o.slow)])
            for o in load_obligations(files))
    with progress_bar(n, "prove") as advance:
        outcomes = run(files, semantics, args.timeout, eng, solvers, progress=lambda o: advance(1),
                       bounds=args.all and not args.no_bound_search, everything=args.all)
    witness_files = proof_run.write_witnesses(outcomes, witnesses)
    if args.smt2:
        write_smt2(files, semantics, Path(args.smt2))
    from .smt.knowledge import of_files

    known = of_files(files)
    report.table(outcomes, known)
    meta = proof_run.meta(args.timeout, solvers, semantics, files)
    if args.report:
        report.write_json(args.report, outcomes, witness_files, meta, known)
    if args.junit:
        report.write_junit(args.junit, outcomes)
    if args.markdown:
        report.write_markdown(args.markdown, outcomes, meta)
    proof_run.witness_note(outcomes, witnesses)
    left = [] if args.all else slow_queries(files, semantics)
    if left:
        print(f"{len(left)} slow queries left to `navfn-smt prove --all` (splits: `navfn-smt split`): {', '.join(left)}")
    proof_run.closing_line(outcomes)
    if args.record:
        for line in proof_run.record_decisions(outcomes, files):
            print(line)
    return 1 if any(o.fails for o in outcomes) else 0


# --------------------------------------------------------------------------------- mutate
def cmd_mutate(args) -> int:
    """Seed bugs in the kernels and domains and report which checks catch them, per backend."""
    import time

    from .report import mutation as report
    from .search.mutation import MUTANTS, run_mutants
    from .smt.runner import default_proof_files

    unknown = set(args.mutant or []) - {m.name for m in MUTANTS}
    if unknown:
        raise NavfnInputError(f"unknown mutant(s): {', '.join(sorted(unknown))}")
    if args.jobs < 1:
        raise NavfnInputError("--jobs must be at least 1")
    _check_positive("--timeout", args.timeout)
    _check_files(args.json)
    chosen = [m for m in MUTANTS if not args.mutant or m.name in args.mutant]
    files = default_proof_files()
    t0 = time.perf_counter()
    done: list = []
    results = run_mutants(chosen, files, _suite(args.suite), args.timeout, args.jobs,
                          progress=report.progress_line(done, len(chosen)), on_done=done.append)
    report.table(results)
    if args.json:
        report.write_json(args.json, results, time.perf_counter() - t0)
    report.score_line(results, time.perf_counter() - t0)
    return 1 if any(r.errors for r in results) else 0


# ---------------------------------------------------------------------------------- bench
def cmd_bench(args) -> int:
    """Time the planner on a whole suite, or on generated maps with ``--size``."""
    from .bench import SEED, bench_sizes, bench_suite, check_sizes
    from .report import bench as report

    if args.sweep is not None:  # whole-map sweep benchmark
        from .bench import bench_sweep

        goals = args.sweep_astar_goals
        if goals != "all":
            try:
                goals = int(goals)
            except ValueError:
                goals = 0
            if goals < 1:
                raise NavfnInputError(f"--sweep-astar-goals {args.sweep_astar_goals}: a number of goals "
                                      "(at least 1) or 'all'")
        _check_files(args.json)
        rows = bench_sweep(args.sweep, args.mode, goals)
        report.sweep_table(rows)
        if args.json:
            report.write_sweep_json(args.json, 0, rows)
        return 0
    if args.size:
        check_sizes(args.size, args.repeat)
        _check_files(args.json)
        rows = bench_sizes(args.size, args.backend, args.repeat, args.mode)
        report.sizes_table(rows)
        if args.json:
            report.write_sizes_json(args.json, SEED, rows)
        return 0
    suite = _suite(args.suite)
    _check_files(args.json)
    rows = bench_suite(suite, args.backend, args.mode)
    report.suite_table(suite, rows)
    if args.json:
        report.write_suite_json(args.json, suite, rows)
    return 0


# ---------------------------------------------------------------------------------- check
def cmd_check(args) -> int:
    """Bounded whole-planner checks; exit 0 only when every property is proved for every size asked."""
    import time

    from .check import runner as CR
    from .engine import engine
    from .report import check as report
    from .search.runner import modes_list

    names = CR.CHECKABLE if args.property == "all" else (args.property,)
    from .search.hunt import parse_costs

    lo, hi = parse_costs(args.costs)
    _check_positive("--timeout", args.timeout)
    _check_positive("--exhaustive", args.exhaustive, allow_zero=True)
    _check_positive("--budget", args.budget, allow_zero=True)
    eng = engine(args.jobs, args.scheduler)
    _check_files(args.json)
    if args.out:
        check_writable_dir(args.out)
    modes = [m == "astar" for m in modes_list(args.mode)]
    if args.max_size:
        sizes = CR.sizes_up_to(*args.max_size)
    else:
        sizes = [tuple(args.size or (4, 4))]
    t0 = time.perf_counter()
    try:
        results, skipped = _check_sizes(args, names, sizes, modes, lo, hi, t0, eng)
    finally:
        report.stop_progress()
    report.table(results)
    saved = {}
    if args.out:
        from .search.counterexamples import save_counterexample
        import numpy as np

        for r in results:
            cx = r.counterexample
            if cx and r.property not in saved:
                saved[r.property] = str(save_counterexample(
                    args.out, np.array(cx["costs"], np.uint8), tuple(cx["start"]), tuple(cx["goal"]),
                    cx["mode"] == "astar", r.property, {"reason": cx["reason"], "exit": cx["exit"]},
                    extra={"found_by": "check", "size_proved_below": _proved_sizes(results, r.property)}))
    induction = {n: CR.induction(n) for n in names if n in CR.INDUCTION}
    if args.json:
        report.write_json(args.json, {
            "command": "check", "arguments": vars_of(args), "costs": [lo, hi], "semantics": args.semantics,
            "ends": args.ends,
            "results": [report.row(r) for r in results], "sizes_not_reached": skipped,
            "largest_size_proved": {n: _largest(results, n) for n in names},
            "smallest_counterexample": {n: next((r.counterexample for r in results if r.property == n
                                                 and r.counterexample), None) for n in names},
            "every_size_by_induction": induction,
            "not_inductive": {n: CR.NOT_INDUCTIVE[n] for n in names if n in CR.NOT_INDUCTIVE},
            "saved": saved, "seconds": round(time.perf_counter() - t0, 1)})
    for n, ind in induction.items():
        print(f"{n}: every map size by induction: {ind['status']} ("
              + ", ".join(f"{k} {v}" + ("" if ind["this_run"][k] == v else f" [this run: {ind['this_run'][k]}]")
                          for k, v in ind["obligations"].items()) + ")")
        for k in ind["contradicted"]:
            print(f"CONTRADICTION: {k} decided against what is known")
    if skipped:
        print(f"sizes not reached within --budget {args.budget:g} s: " + ", ".join(f"{w}x{h}" for w, h in skipped))
    for n, path in saved.items():
        print(f"{n}: counterexample saved in {path}")
    if any(ind["contradicted"] for ind in induction.values()):
        return 1
    return 0 if all(r.status == "proved" for r in results) else 1


def _check_sizes(args, names, sizes, modes, lo, hi, t0, eng):
    """Check each size in turn on ``eng`` until --budget runs out; the results and the sizes skipped."""
    import time

    from .check import runner as CR
    from .report import check as report

    results, skipped = [], []
    open_names = list(names)
    for nx, ny in sizes:
        if args.budget and time.perf_counter() - t0 > args.budget:
            skipped.append([nx, ny])
            continue
        if not open_names:
            break
        got = CR.check_one_size(open_names, nx, ny, modes, lo, hi, args.semantics, args.timeout, eng,
                                args.start, args.goal, args.ends, int(args.exhaustive),
                                progress=report.progress(f"{nx}x{ny}"))
        for n in list(open_names):
            results.append(got[n])
            if got[n].status == "refuted" and args.max_size:
                open_names.remove(n)  # the smallest counterexample of this property is found
    return results, skipped


def _proved_sizes(results, name) -> list:
    return [list(r.size) for r in results if r.property == name and r.status == "proved"]


def _largest(results, name):
    proved = [r.size for r in results if r.property == name and r.status == "proved"]
    return list(max(proved, key=lambda s: ((s[0] - 2) * (s[1] - 2), s))) if proved else None


# --------------------------------------------------------------------------------- search
def cmd_search(args) -> int:
    """Hunt counterexamples of one kind (``--summary SUITE``: count every kind on a suite)."""
    from .engine import engine
    from .report import search as report
    from .search.runner import modes_list, run_search

    eng = engine(args.jobs, args.scheduler)
    _check_files(args.json)
    if args.summary:
        if args.kind:
            raise NavfnInputError("give either a KIND or --summary SUITE, not both")
        from .search.summary import summarize

        s = summarize(Path(args.summary), modes_list(args.mode), progress=report.progress_line, eng=eng)
        report.summary_table(s)
        if args.json:
            report.write_summary_json(args.json, s)
        return 0
    if not args.kind:
        raise NavfnInputError("give a KIND to search for (or --summary SUITE)")
    from .search.hunt import parse_costs

    costs_range = parse_costs(args.costs)
    _check_positive("--timeout", args.timeout)
    if args.out:
        check_writable_dir(args.out)
    findings, tried = run_search(args.kind, args.mode, args.size, args.max_size, args.timeout, args.seed,
                                 costs_range, progress=report.progress_line, eng=eng)
    rows = [report.finding_row(f, s) for f, s in zip(findings, report.save_findings(findings, args.out))]
    report.table(args.kind, rows, modes_list(args.mode))
    if args.json:
        report.write_json(args.json, args.kind, vars_of(args), rows, tried)
    report.saved_note(args.out, rows)
    return 0


def vars_of(args) -> dict:
    """The arguments of a command as plain JSON values (no handler)."""
    return {k: v for k, v in vars(args).items() if k != "func"}


# ---------------------------------------------------------------------------------- main
def shown_default(value) -> str:
    """An option's default as its help shows it: ``30`` for 30.0, ``1e+07``, ``0 0`` for a pair."""
    if isinstance(value, (list, tuple)):
        return " ".join(shown_default(v) for v in value)
    if isinstance(value, float):
        return f"{value:g}"
    return str(value)


class _HelpFormatter(argparse.HelpFormatter):
    """Shows an option's default at the end of its help, unless the default is nothing (None,
    False) or the help already says what the default is."""

    def _get_help_string(self, action) -> str:
        text = action.help or ""
        if action.default in (None, False, argparse.SUPPRESS) or not action.option_strings:
            return text
        if "default" in text.lower():
            return text
        return f"{text} (default: {shown_default(action.default).replace('%', '%%')})"


class Parser(argparse.ArgumentParser):
    """An argument parser whose subcommands (and theirs) all show option defaults in their help."""

    def __init__(self, *args, formatter_class=_HelpFormatter, **kwargs):
        super().__init__(*args, formatter_class=formatter_class, **kwargs)


def _version() -> str:
    """The installed package's version."""
    from importlib.metadata import PackageNotFoundError, version

    try:
        return version("navfn-smt")
    except PackageNotFoundError:
        return "unknown (not installed)"


def build_parser() -> argparse.ArgumentParser:
    """The whole command line: every subcommand with its options and handler."""
    from .backends import BACKENDS
    from .diagnose.command import register as register_diagnose
    from .report.docs_command import register as register_docs
    from .report.split import register as register_split
    from .difftest.record_cli import register as register_record
    from .difftest.runner import MODE_CHOICES
    from .engine import add_arguments as add_engine_arguments
    from .maps.mapserver import DEFAULT_DISTRO, DISTROS
    from .maps.suite_cli import register as register_generate
    from .check.bounded import CHECKABLE as CHECK_PROPERTIES
    from .search.kinds import SEARCH_KINDS
    from .search.metamorphic import TRANSFORMS
    from .smt.solvers import SOLVERS
    from .smt.runner import SEMANTICS

    p = Parser(
        prog="navfn-smt",
        description="Executable specification of Nav2's NavFn planner, differential testing "
        "against the C++ original, and SMT proofs of its invariants.",
    )
    p.add_argument("--version", action="version", version=f"%(prog)s {_version()}")
    sub = p.add_subparsers(dest="command", required=True, metavar="COMMAND")
    backend_help = "planner implementation: the numba JIT or the reference spec"
    mode_help = "planner modes: A*, Dijkstra or both"

    pl = sub.add_parser("plan", help="plan on one map and print the path")
    pl.add_argument("map", help="a suite map directory (test.txt gives the size), a map_server YAML, "
                    "or a raw map file with --size")
    pl.add_argument("--size", nargs=2, type=int, metavar=("W", "H"), help="size of a raw map file")
    pl.add_argument("--start", nargs="+", type=float, required=True, metavar=("X Y", "YAW"),
                    help="NavFn's start cell X Y (where the path begins); with --world the robot's pose X Y [YAW] "
                    "in metres and radians")
    pl.add_argument("--goal", nargs="+", type=float, required=True, metavar=("X Y", "YAW"),
                    help="NavFn's goal cell X Y (where propagation begins); with --world the goal pose X Y [YAW]")
    pl.add_argument("--world", action="store_true",
                    help="plan between world poses on a map_server YAML map exactly as Nav2's NavfnPlanner plugin "
                    "(createPlan) does: prints the poses Nav2 publishes, or the exception it throws (exit 1)")
    pl.add_argument("--params", metavar="FILE",
                    help="with --world: a Nav2 params file; the planner_server's NavfnPlanner parameters and the "
                    "global_costmap's layers are read from it (default: Nav2's defaults, static layer only)")
    pl.add_argument("--resolution", type=float, metavar="M",
                    help="with --world on a costmap file (.npy of costmap values, row 0 at the bottom; or an 8-bit "
                    "PGM of them): metres per cell")
    pl.add_argument("--origin", nargs=2, type=float, default=(0.0, 0.0), metavar=("X", "Y"),
                    help="with --world on a costmap file: the world position of its lower-left corner "
                    "(default: 0 0)")
    pl.add_argument("--allow-outside", action="store_true",
                    help="let a map_server YAML name an image outside its own folder")
    pl.add_argument("--distro", default=DEFAULT_DISTRO, choices=tuple(DISTROS),
                    help="Nav2 distribution whose map loading and costmap rules apply (default: %(default)s)")
    alg = pl.add_mutually_exclusive_group()
    alg.add_argument("--dijkstra", action="store_true",
                     help="Dijkstra propagation (default: A* on cells; with --world the params file's use_astar, "
                     "whose Nav2 default is Dijkstra)")
    alg.add_argument("--astar", action="store_true", help="A* propagation (with --world: overrides use_astar)")
    pl.add_argument("--backend", choices=BACKENDS, default="jit", help=backend_help)
    pl.add_argument("--json", action="store_true", help="print a JSON object")
    pl.set_defaults(func=cmd_plan)

    dt = sub.add_parser("difftest", help="compare every case of a suite with its golden files")
    dt.add_argument("suite", nargs="?", help="suite directory (default: the example suite shipped with the package)")
    dt.add_argument("--mode", choices=MODE_CHOICES, default="both", help=mode_help)
    dt.add_argument("--backend", choices=BACKENDS, default="jit", help=backend_help)
    add_engine_arguments(dt, what="difftest chunks")
    dt.add_argument("--json", metavar="FILE", help="write per-map counts and every disagreement as JSON")
    dt.add_argument("--quiet", action="store_true", help="no progress bar")
    dt.set_defaults(func=cmd_difftest)

    rd = sub.add_parser("render", help="draw a planning case: costmap, potential, path, gradient")
    rd.add_argument("map", help="a suite map directory or a map_server YAML")
    rd.add_argument("--allow-outside", action="store_true",
                    help="let a map_server YAML name an image outside its own folder")
    rd.add_argument("--case", type=int, default=0, metavar="I", help="case index in test.txt")
    rd.add_argument("--start", nargs=2, type=int, metavar=("X", "Y"), help="plan this start cell instead of a case")
    rd.add_argument("--goal", nargs=2, type=int, metavar=("X", "Y"), help="plan this goal cell instead of a case")
    rd.add_argument("--dijkstra", action="store_true", help="Dijkstra propagation (default: A*)")
    rd.add_argument("--backend", choices=BACKENDS, default="jit", help=backend_help)
    rd.add_argument("--highlight", nargs="+", type=float, metavar="V",
                    help="mark a cell (X Y) or a segment (X1 Y1 X2 Y2), e.g. a counterexample")
    rd.add_argument("--arrows", choices=("auto", "on", "off"), default="auto",
                    help="gradient arrows (auto: when the picture shows up to 60 cells a side)")
    rd.add_argument("--zoom", choices=("auto", "full"), default="auto",
                    help="auto: on a map over 80 cells a side, show only the neighbourhood of the start, goal and "
                    "path when they fill less than half of it; full: always the whole map")
    rd.add_argument("-o", "--output", required=True, metavar="FILE", help="a .png or .svg file")
    rd.set_defaults(func=cmd_render)

    mm = sub.add_parser("metamorphic", help="check map symmetries: transposes, flips, rotations, padding, cost shifts")
    mm.add_argument("suite", nargs="?", help="suite directory (default: the example suite)")
    mm.add_argument("--relation", action="append", choices=tuple(TRANSFORMS),
                    help="check only this relation (repeatable; default: all)")
    mm.add_argument("--mode", choices=MODE_CHOICES, default="both", help=mode_help)
    mm.add_argument("--backend", choices=BACKENDS, default="jit", help=backend_help)
    mm.add_argument("--max-cases", type=int, metavar="N", help="at most this many cases per map (default: all)")
    mm.add_argument("--save", metavar="DIR",
                    help="save counterexamples under DIR as suite map directories (default: not saved)")
    mm.add_argument("--save-max", type=int, default=3, metavar="N", help="counterexamples saved per relation and mode")
    mm.add_argument("--json", metavar="FILE", help="write the counts and counterexamples as JSON")
    mm.set_defaults(func=cmd_metamorphic)

    cv = sub.add_parser("coverage", help="line, branch and kernel-decision coverage of the reference spec under a suite")
    cv.add_argument("suite", nargs="*", help="suite directories, measured together (default: the example suite)")
    cv.add_argument("--mode", choices=MODE_CHOICES, default="both", help=mode_help)
    cv.add_argument("--max-cases", type=int, metavar="N", help="at most this many cases per map (the spec runs traced: slow)")
    cv.add_argument("--min-branch", type=float, metavar="PERCENT",
                    help="exit 1, saying so, when branch coverage is below this percentage (0 to 100)")
    cv.add_argument("--json", metavar="FILE", help="write the figures and every uncovered branch as JSON")
    cv.set_defaults(func=cmd_coverage)

    su = sub.add_parser("suite", help="generate map suites and record golden files from the spec")
    suite_sub = su.add_subparsers(dest="suite_command", required=True, metavar="SUBCOMMAND")
    register_generate(suite_sub)
    register_record(suite_sub)

    pr = sub.add_parser("prove", help="check the proof obligations shipped in the package (or the given files)")
    pr.add_argument("files", nargs="*", metavar="FILE|DIR",
                    help="proof files (Python files declaring obligations) or folders of them "
                    "(default: every proof file of the package's navfn_smt/proofs)")
    pr.add_argument("--semantics", choices=(*SEMANTICS, "both"), default="both",
                    help="real (no rounding), fp32 (bit-precise IEEE-754) or both")
    pr.add_argument("--timeout", type=float, default=30.0, metavar="S", help="seconds per solver query")
    add_engine_arguments(pr, "obligations (each in each semantics)")
    pr.add_argument("--solver", action="append", choices=SOLVERS,
                    help="solvers of the portfolio (repeatable; default: all)")
    pr.add_argument("--report", metavar="FILE.json", help="machine-readable report")
    pr.add_argument("--junit", metavar="FILE.xml", help="JUnit XML, one test case per obligation and semantics")
    pr.add_argument("--markdown", metavar="FILE.md", help="the invariants page (docs/invariants.md)")
    pr.add_argument("--smt2", metavar="DIR", help="also write every query as SMT-LIB2")
    pr.add_argument("--all", action="store_true",
                    help="also the slow queries (whole queries a split decides, long proofs), which the default "
                         "run leaves out to stay within a minute")
    pr.add_argument("--record", action="store_true",
                    help="record every decision made where nothing was known (known.json beside the proof file, "
                         "keyed by a hash of the proof file, kernels and domains), so later runs judge against it")
    pr.add_argument("--no-bound-search", action="store_true",
                    help="with --all, do not search bounds for properties refuted in fp32 (the default run "
                         "gives verdicts only: the bound search re-verifies its cached bound with two queries)")
    pr.add_argument("--witness-dir", metavar="DIR",
                    help="where counterexamples are written (default: STEM-witnesses next to the first of "
                    "--report, --junit, --markdown given; none written without any of them)")
    pr.set_defaults(func=cmd_prove)

    mu = sub.add_parser("mutate", help="seed bugs in the kernels and domains; report which checks catch them")
    mu.add_argument("--mutant", action="append", metavar="NAME", help="run only this mutant (repeatable)")
    mu.add_argument("--suite", help="suite for the difftest detector (default: the example suite)")
    mu.add_argument("--timeout", type=float, default=30.0, metavar="S", help="seconds per solver query")
    mu.add_argument("--jobs", type=int, default=2, metavar="N", help="mutants checked at the same time")
    mu.add_argument("--json", metavar="FILE", help="write every mutant's result as JSON")
    mu.set_defaults(func=cmd_mutate)

    be = sub.add_parser("bench", help="time the planner: a whole suite, or generated maps with --size")
    be.add_argument("suite", nargs="?", help="suite directory (default: the example suite)")
    be.add_argument("--size", nargs="+", type=int, metavar="N",
                    help="instead of a suite, plan on generated NxN open and random-cost maps")
    be.add_argument("--backend", choices=(*BACKENDS, "all"), default="all", help="planner implementations timed")
    be.add_argument("--mode", choices=MODE_CHOICES, default="both", help=mode_help)
    be.add_argument("--repeat", type=int, default=3, metavar="K", help="plans per map and mode with --size (best is kept)")
    be.add_argument("--json", metavar="FILE", help="write the figures as JSON")
    be.add_argument("--sweep", nargs="?", type=int, const=400, metavar="N",
                    help="instead, time the whole-map sweep (every free cell a goal of one robot pose) on a "
                         "generated NxN rooms costmap (default 400)")
    be.add_argument("--sweep-astar-goals", default="2000", metavar="K|all",
                    help="goals sampled for the A* sweep (one propagation each; default 2000)")
    be.set_defaults(func=cmd_bench)

    ck = sub.add_parser("check", help="prove or refute a whole-planner property on every map of a size "
                        "(bounded: symbolic costs, enumerated layouts, start and goal)")
    ck.add_argument("property", choices=(*CHECK_PROPERTIES, "all"), metavar="PROPERTY",
                    help=f"one of {', '.join(CHECK_PROPERTIES)}, or all")
    csz = ck.add_mutually_exclusive_group()
    csz.add_argument("--size", nargs=2, type=int, metavar=("W", "H"),
                     help="map size, lethal border included (default: 4 4)")
    csz.add_argument("--max-size", nargs=2, type=int, metavar=("W", "H"),
                     help="every size up to W x H, smallest interior first, until --budget runs out; "
                     "a refuted property stops at its smallest counterexample")
    ck.add_argument("--mode", choices=MODE_CHOICES, default="both", help=mode_help)
    ck.add_argument("--costs", default="50..253", metavar="LO..HI",
                    help="range of every passable cell's cost (50..253: what setCostmap produces; 0..253 for "
                    "NavFn's raw API); lethal cells are enumerated")
    ck.add_argument("--semantics", choices=("fp32", "real"), default="fp32",
                    help="fp32: bit-precise float32 and float64, as the C++ computes (real: not available for check)")
    ck.add_argument("--timeout", type=float, default=60.0, metavar="S",
                    help="seconds per solver query; a query bitwuzla and cvc5 leave undecided is split (its cost box "
                    "cut in four, twice) or evaluated at every point of its box (--exhaustive); what stays "
                    "undecided is unknown")
    ck.add_argument("--exhaustive", type=float, default=1e7, metavar="POINTS",
                    help="evaluate an undecided query at every point of its cost box when the box has at most this "
                    "many points (numpy, about 5 million points a second)")
    ck.add_argument("--budget", type=float, metavar="S", help="with --max-size: stop starting new sizes after this many seconds")
    add_engine_arguments(ck, "cases")
    ck.add_argument("--start", nargs=2, type=int, metavar=("X", "Y"), help="fix the start cell (default: every one)")
    ck.add_argument("--goal", nargs=2, type=int, metavar=("X", "Y"), help="fix the goal cell (default: every one)")
    ck.add_argument("--ends", choices=("any", "passable"), default="any",
                    help="start and goal range over every interior cell, or only over passable ones (Nav2 clears "
                    "the robot's cell, NavFn's goal)")
    ck.add_argument("--out", metavar="DIR", help="save each property's smallest counterexample under DIR as a "
                    "suite map directory with goldens and picture (default: nothing written)")
    ck.add_argument("--json", metavar="FILE", help="write the verdicts, what was enumerated and solved, as JSON")
    ck.set_defaults(func=cmd_check)

    se = sub.add_parser("search", help="hunt counterexamples (random maps, hill climbing, shrinking; replayed "
                        "on the spec), or count each kind on a suite with --summary")
    se.add_argument("kind", nargs="?", choices=SEARCH_KINDS, metavar="KIND",
                    help=f"what to hunt: {', '.join(SEARCH_KINDS)}")
    sz = se.add_mutually_exclusive_group()
    sz.add_argument("--size", nargs=2, type=int, metavar=("W", "H"),
                    help="map size, lethal border included (default: 5 7 for cost, else hunt on 8 8 and shrink)")
    sz.add_argument("--max-size", nargs=2, type=int, metavar=("W", "H"),
                    help="grow the size from 3x3 to W x H (smallest interior first); report the first size "
                    "with a counterexample")
    se.add_argument("--mode", choices=MODE_CHOICES, default="both", help=mode_help)
    se.add_argument("--timeout", type=float, default=60.0, metavar="S", help="seconds for the whole search, split between modes")
    se.add_argument("--seed", type=int, default=0, metavar="S", help="random seed (same seed and budget: same hunt)")
    se.add_argument("--costs", metavar="LO..HI", help="passable costs of the maps (default 50..253, what "
                    "setCostmap produces); lethal 254 is always allowed")
    se.add_argument("--out", metavar="DIR", help="save each counterexample as a suite map directory under DIR "
                    "(default: nothing written)")
    se.add_argument("--json", metavar="FILE", help="write the findings (or the summary) as JSON")
    se.add_argument("--summary", metavar="SUITE",
                    help="instead of hunting, count how often each kind occurs on a suite (JIT backend)")
    add_engine_arguments(se, "the modes' hunts (the maps of --summary)")
    se.set_defaults(func=cmd_search)

    register_diagnose(sub)
    register_docs(sub)
    register_split(sub)
    return p


def main(argv=None) -> int:
    """Run one command; its exit status (2 for bad input, 130 when interrupted)."""
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
