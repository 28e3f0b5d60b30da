"""``navfn-smt check``: whole-planner properties proved or refuted on every map of a size."""

from __future__ import annotations

from pathlib import Path

from ..errors import NavfnInputError
from ..fileio import check_writable_dir
from .common import MODE_HELP, add_planner_arguments, check_files, check_positive, planner_of, vars_of

SEARCH_TIMEOUT = 60.0  # seconds per query of a search: what stays undecided is split, then unknown
# seconds per query of a replay, ten times a search's: each query was decided once, and the
# slowest recorded unsat measured (4x4's, a control path's seventh flip) took bitwuzla 75 s on a
# 2-core machine under a test run's load, past the search's limit; a loaded machine's verdict
# stays the quiet one's
REPLAY_TIMEOUT = 600.0


def cmd_check(args) -> int:
    """Bounded whole-planner checks; exit 0 only when every property is proved for every size asked."""
    import time

    from ..check import runner as CR
    from ..check.common import symbolic_domain
    from ..engine import engine
    from ..report import check as report
    from ..maps.suite import modes_of

    if args.timeout is None:  # a replay re-asks what a search decided: a limit no load reaches
        args.timeout = REPLAY_TIMEOUT if args.replay else SEARCH_TIMEOUT
    if args.transcript:
        return _transcript(args)
    if args.replay:
        return _replay(args)
    if not args.property:
        raise NavfnInputError("check: name a PROPERTY (or all), or give --replay CERT")
    unknown = [p for p in args.property if p not in (*CR.CHECKABLE, "all")]
    if unknown:
        raise NavfnInputError(f"check: unknown property {unknown[0]!r} (choose from {', '.join(CR.CHECKABLE)}, all)")
    names = CR.CHECKABLE if "all" in args.property else tuple(dict.fromkeys(args.property))
    planner = planner_of(args)  # NavFn as shipped or fixed, in the arithmetic of --target (x86-64's by default)
    semantics = planner.fp32_semantics()  # float32 in the planner's arithmetic (--semantics real is refused below)
    from ..search.hunt import parse_costs

    lo, hi = parse_costs(args.costs)
    check_positive("--timeout", args.timeout)
    check_positive("--exhaustive", args.exhaustive, allow_zero=True)
    check_positive("--budget", args.budget, allow_zero=True)
    eng = engine(args.jobs, args.scheduler)
    check_files(args.json)
    if args.out:
        check_writable_dir(args.out)
    if args.certificates:
        check_writable_dir(args.certificates)
    if args.certificates and (args.start or args.goal):
        raise NavfnInputError("--certificates: a certificate covers every start and goal of a size (no --start/--goal)")
    if args.journal:
        check_files(args.journal)
    modes = [m == "astar" for m in modes_of(args.mode)]
    if args.max_cells is not None and not args.max_size:
        raise NavfnInputError("--max-cells N: give --max-size W H too (the sizes up to W x H of at most N interior cells)")
    if args.max_size:
        check_positive("--max-cells", args.max_cells, allow_zero=True)
        sizes = [(w, h) for w, h in CR.sizes_up_to(*args.max_size)
                 if args.max_cells is None or (w - 2) * (h - 2) <= args.max_cells]
    else:
        sizes = [tuple(args.size or (4, 4))]
    symbolic_domain(args.semantics)  # --semantics real: offered by the parser, refused here (no bounded check over the reals)
    request = CR.CheckRequest(names, modes, lo, hi, planner, args.timeout, args.start, args.goal, args.ends,
                              args.exhaustive)
    t0 = time.perf_counter()
    try:
        results, skipped = CR.check_sizes(request, sizes, eng, args.budget, smallest_only=bool(args.max_size),
                                          progress_of=report.progress, t0=t0, certify=_certify(args, request),
                                          journal=args.journal)
    finally:
        report.stop_progress()
    print(f"planner: {planner.label} (float32 semantics {semantics})")
    report.table(results)
    saved = {}
    if args.out:
        from ..search.counterexamples import save_counterexample
        import numpy as np

        for r in results:
            cx = r.counterexample
            if cx and r.property not in saved:
                saved[r.property] = str(save_counterexample(
                    args.out, np.array(cx["costs"], np.uint8), tuple(cx["start"]), tuple(cx["goal"]),
                    cx["mode"] == "astar", r.property, {"reason": cx["reason"], "exit": cx["exit"]},
                    extra={"found_by": "check", "size_proved_below": CR.proved_sizes(results, r.property),
                           "variant": planner.variant, "semantics": semantics}))
    induction = {n: CR.induction(n, timeout=args.timeout, planner=planner)
                 for n in names if n in CR.inductive(planner)}
    if args.json:
        report.write_json(args.json, {
            "command": "check", "arguments": vars_of(args), "costs": [lo, hi], "semantics": semantics,
            "variant": planner.variant, "planner": planner.as_dict(),
            "ends": args.ends,
            "results": [report.row(r) for r in results], "sizes_not_reached": skipped,
            "largest_size_proved": {n: CR.largest_proved(results, n) for n in names},
            "smallest_counterexample": {n: CR.smallest_counterexample(results, n) for n in names},
            "every_size_by_induction": induction,
            "not_inductive": {n: CR.NOT_INDUCTIVE[n] for n in names
                              if n in CR.NOT_INDUCTIVE and n not in CR.inductive(planner)},
            "saved": saved, "seconds": round(time.perf_counter() - t0, 1)})
    for n, ind in induction.items():
        says = ("every map size by induction" + (f", under {len(ind['conditions'])} run-time conditions"
                                                  if ind.get("conditions") else "") if ind["status"] != "refuted" else
                f"no induction in {ind['semantics']}: a link of it is refuted, so it proves nothing there; status")
        print(f"{n}: {says}: {ind['status']} ("
              + ", ".join(f"{k} {v}" + ("" if ind["this_run"][k] == v else f" [this run: {ind['this_run'][k]}]")
                          for k, v in ind["obligations"].items()) + ")")
        for c in ind.get("conditions", []) if ind["status"] != "refuted" else []:
            print(f"  condition: {c}")
        if ind.get("trusted") and ind["status"] != "refuted":
            n = len(ind["trusted"])
            print(f"  trusted: {n} step{'s' if n != 1 else ''} argued or tested, not machine-checked "
                  "(docs/invariants.md lists them): " + "; ".join(t.split(": ", 1)[0] for t in ind["trusted"]))
        for k in ind["contradicted"]:
            print(f"CONTRADICTION: {k} decided against what is known")
    from ..spec.fix import FIX
    from ..spec.fixes import GUARANTEE

    if planner.fix == FIX and induction:
        print(f"the guarantee (docs/fix.md): {GUARANTEE}")
    if skipped:
        print(f"sizes not reached within --budget {args.budget:g} s: " + ", ".join(f"{w}x{h}" for w, h in skipped))
    for n, path in saved.items():
        print(f"{n}: counterexample saved in {path}")
    if any(ind["contradicted"] for ind in induction.values()):
        return 1
    return 0 if all(r.status == "proved" for r in results) else 1


def _suffix(planner) -> str:
    """What a certificate's file name adds for a planner other than NavFn as shipped in x86-64's
    arithmetic (``-fixed``, ``-aarch64``, ``-fixed-aarch64``): the names stay apart in one folder
    and in the record of transcripts, which is by file name."""
    arith = planner.navfn_arithmetic().name
    return ("" if planner.fix.shipped else f"-{planner.variant}") + ("" if arith == "x86-64" else f"-{arith}")


def _certify(args, request):
    """The callback that writes a proved size's certificate under ``--certificates DIR``."""
    if not args.certificates:
        return None
    from pathlib import Path

    from ..check import certificate

    def write(nx: int, ny: int, got: dict, entries: list) -> None:
        # the folder is made when the first certificate is written (check_writable_dir said it can be)
        Path(args.certificates).mkdir(parents=True, exist_ok=True)
        planner = request.planner
        path = Path(args.certificates) / f"check-{nx}x{ny}{_suffix(planner)}.cert.json.gz"
        r = next(iter(got.values()))
        explored = [n for n, g in got.items() if g.method == "exploration"]  # what the path logs judge
        certificate.write(path, {
            "size": [nx, ny], "properties": explored, **request.header(),
            **({} if planner.fp32_semantics() == "fp32" else {"semantics": planner.fp32_semantics()}),
            "total": r.cases, "outside": r.outside,
            "verdicts": {n: g.status for n, g in got.items()},
            "witnesses": {n: g.counterexample for n, g in got.items() if g.status == "refuted"},
            "induction": {n: g.method for n, g in got.items() if g.method != "exploration"}}, entries)
        print(f"{nx}x{ny}: certificate written to {path}")

    return write


def _replay(args) -> int:
    """``check --replay CERT``: exit 0 only when the certificate re-checks."""
    import time

    from ..check import certificate
    from ..engine import engine
    from ..report import check as report

    order = certificate.check_solvers(args.solver.split(",")) if args.solver else certificate.DEFAULT_SOLVERS
    check_positive("--timeout", args.timeout)
    eng = engine(args.jobs, args.scheduler)
    check_files(args.json)
    part = _part(args.part)
    if args.combine and args.part:
        raise NavfnInputError("--combine joins the reports of parts already replayed: no --part with it")
    doc = certificate.read(args.replay)
    sha = certificate.digest(args.replay)
    t0 = time.perf_counter()
    if args.combine:
        got = certificate.combine(doc, sha, [_part_report(f) for f in args.combine])
    else:
        try:
            got = certificate.replay(args.replay, eng, args.timeout, progress=report.progress(f"replay {args.replay}"),
                                     order=order, check_intervals=args.check_intervals, doc=doc, part=part)
        finally:
            report.stop_progress()
        got["seconds"] = round(time.perf_counter() - t0, 1)
    if args.json:
        report.write_json(args.json, {"command": "check --replay", "certificate": args.replay,
                                      "certificate_sha256": sha,
                                      "check_intervals": got.get("check_intervals", args.check_intervals), **got})
    size = "x".join(map(str, got.get("size", [])))
    if got["status"] == "replayed":
        if part != (1, 1):
            lo, hi = got["case_range"]
            print(f"{args.replay}: part {part[0]}/{part[1]} replayed: cases {lo} to {hi - 1} of the explored, "
                  f"{got['paths']} control paths re-checked, {got['seconds']} s (the whole certificate once every "
                  f"part is: --combine)")
        else:
            ind = got.get("induction", {})  # decided by an induction, not by the certificate's paths
            verdicts = ", ".join(f"{n} {report.verdict_text(v, ind.get(n, 'exploration'))}"
                                 for n, v in got["verdicts"].items())
            print(f"{args.replay}: replayed: {verdicts} on every "
                  f"{size} map ({got['cases']} cases explored, {got['paths']} control paths re-checked, "
                  f"{got['seconds']} s)")
        for line in report.replay_evidence(got):
            print(f"  {line}")
        if got.get("carried"):
            print(f"  carried: written by code {got['carried']['from'][:12]}, replayed with code "
                  f"{got['carried']['to'][:12]}; their recorded transcripts are equal (check --transcript)")
        return 0
    for p in got["problems"][:20]:
        print(f"problem: {p}")
    print(f"{args.replay}: refused ({len(got['problems'])} problems; the first: {got['problems'][0]})")
    return 1


def _transcript(args) -> int:
    """``check --transcript CERT [--record]``: the replay's queries and decisions under this code,
    and whether they are those of the code that wrote the certificate (it then carries)."""
    import json
    import time

    from ..check import certificate as C
    from ..engine import engine
    from ..report import check as report

    eng = engine(args.jobs, args.scheduler)
    doc = C.read(args.transcript)
    name, sha = Path(args.transcript).name, C.digest(args.transcript)
    t0 = time.perf_counter()
    try:
        got = C.transcript(doc, eng, progress=report.progress(f"transcript {args.transcript}"))
    finally:
        report.stop_progress()
    record = C.recorded_transcripts()
    entry = record.get(name) if (record.get(name) or {}).get("certificate_sha256") == sha else None
    entry = entry or {"certificate_sha256": sha, "transcripts": {}}
    entry["transcripts"][got["code_hash"]] = {k: got[k] for k in ("sha256", "cases", "queries")}
    print(f"{args.transcript}: transcript under code {got['code_hash'][:12]}: {got['sha256'][:16]} "
          f"({got['cases']} cases, {got['queries']} queries, {time.perf_counter() - t0:.1f} s)")
    if args.record:
        record[name] = entry
        C.TRANSCRIPTS.write_text(json.dumps(record, indent=1, sort_keys=True) + "\n", encoding="utf-8")
        print(f"recorded in {C.TRANSCRIPTS}")
    written = doc.get("code_hash")
    if written == got["code_hash"]:
        print("this is the code that wrote the certificate")
        return 0
    if C.carried(name, doc, sha, got["code_hash"], {name: entry}):
        print(f"the same as under the code that wrote it ({written[:12]}): the certificate carries to this code")
        return 0
    then = entry["transcripts"].get(written)
    print(f"no transcript of the code that wrote it ({written[:12]}) is recorded" if then is None else
          f"it differs from the transcript under the code that wrote it ({written[:12]}: {then['sha256'][:16]}): "
          "the certificate does not carry; run the check again")
    return 1


def _part(text):
    """``--part K/N`` as ``(k, n)`` (default ``(1, 1)``: the whole certificate)."""
    if not text:
        return (1, 1)
    try:
        k, n = (int(x) for x in text.split("/"))
    except ValueError:
        raise NavfnInputError(f"--part {text!r}: give K/N, the K-th of N parts (e.g. 3/8)") from None
    if not 1 <= k <= n:
        raise NavfnInputError(f"--part {text}: K must be 1 to N")
    return (k, n)


def _part_report(path) -> dict:
    """A part's replay report (``check --replay --part K/N --json``), read whole."""
    import json

    try:
        doc = json.loads(Path(path).read_text(encoding="utf-8"))
    except (OSError, ValueError) as e:
        raise NavfnInputError(f"{path}: not a replay report ({getattr(e, 'strerror', None) or e})") from None
    if not isinstance(doc, dict) or doc.get("command") != "check --replay":
        raise NavfnInputError(f"{path}: not a replay report (no \"command\": \"check --replay\")")
    return doc


def register(sub) -> None:
    """The command's parser, its options and its handler."""
    from ..check.bounded import CHECKABLE as CHECK_PROPERTIES
    from ..maps.suite import MODE_CHOICES
    from ..engine import add_arguments as add_engine_arguments

    ck = sub.add_parser("check", help="prove or refute a whole-planner property on every map of a size "
                        "(bounded: symbolic costs, enumerated layouts, start and goal)")
    ck.add_argument("property", nargs="*", metavar="PROPERTY",
                    help=f"one or more of {', '.join(CHECK_PROPERTIES)}, or all (each case is explored once for "
                    "all the properties named)")
    csz = ck.add_mutually_exclusive_group()
    csz.add_argument("--size", nargs=2, type=int, metavar=("W", "H"),
                     help="map size, lethal border included (default: 4 4)")
    csz.add_argument("--max-size", nargs=2, type=int, metavar=("W", "H"),
                     help="every size up to W x H, smallest interior first, until --budget runs out; "
                     "a refuted property stops at its smallest counterexample")
    ck.add_argument("--max-cells", type=int, metavar="N", help="with --max-size: only the sizes of at most N "
                    "interior cells")
    ck.add_argument("--mode", choices=MODE_CHOICES, default="both", help=MODE_HELP)
    add_planner_arguments(ck)
    ck.add_argument("--costs", default="50..253", metavar="LO..HI",
                    help="range of every passable cell's cost (50..253: what setCostmap produces; at least 1: a cost "
                    "of 0 makes a NaN possible, where the intervals are unsound); lethal cells are enumerated")
    ck.add_argument("--semantics", choices=("fp32", "real"), default="fp32",
                    help="fp32: bit-precise float32 and float64, as the C++ computes (real: not available for check)")
    ck.add_argument("--timeout", type=float, metavar="S",
                    help=f"seconds per solver query (default {SEARCH_TIMEOUT:g}); a query bitwuzla and cvc5 leave "
                    "undecided is split (its cost box cut in four, twice) or evaluated at every point of its box "
                    f"(--exhaustive); what stays undecided is unknown.  With --replay (default {REPLAY_TIMEOUT:g}): "
                    "a recorded unsat no solver of --solver decides within it refuses the certificate")
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
    ck.add_argument("--certificates", metavar="DIR", help="write a certificate of each size whose properties are all "
                    "proved to DIR/check-WxH.cert.json.gz: every case, control path and query, with the code's hash")
    ck.add_argument("--journal", metavar="FILE", help="with --size: record each explored case in FILE as it is "
                    "decided; a rerun with the same FILE explores only the cases it does not hold (refused when "
                    "the arguments or the code differ), so a long check can be stopped and resumed")
    ck.add_argument("--replay", metavar="CERT", help="re-check a certificate without searching: its coverage (every "
                    "case, a root path each, every flip closed), its marks against its verdicts, every unsat asked "
                    "again, every sat flip witnessed; refused when the kernels or the encoding changed")
    ck.add_argument("--solver", metavar="S[,S...]", help="with --replay: the solvers asked, in turn, each only what "
                    "the ones before leave undecided (default: cvc5,bitwuzla; the search asked bitwuzla)")
    ck.add_argument("--transcript", metavar="CERT", help="what a replay of CERT asks and decides under this code, "
                    "without a solver (every query's SMT-LIB text by its SHA-256, every decision); equal to the "
                    "transcript under the code that wrote CERT, the certificate carries to this code")
    ck.add_argument("--record", action="store_true", help="with --transcript: record it in "
                    "docs/reports/certificates/transcripts.json")
    ck.add_argument("--part", metavar="K/N", help="with --replay: every check of the whole certificate but the "
                    "control paths of the K-th of N equal runs of its cases only, so a long replay can be done in "
                    "parts (the whole when every part is, by --combine)")
    ck.add_argument("--combine", metavar="REPORT", nargs="+", help="with --replay CERT: the whole replay from the "
                    "--json reports of its parts 1/N to N/N (refused unless each is of CERT, replayed, and they "
                    "tile its cases)")
    ck.add_argument("--check-intervals", action="store_true", help="with --replay: ask the solvers too where a "
                    "property held on the whole box by interval evaluation (default: counted as trusted)")
    ck.set_defaults(func=cmd_check)
