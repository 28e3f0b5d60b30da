"""Certificates of bounded checks: what a proof explored and asked, re-checked without searching.

A certificate (gzipped JSON) holds, for one size: the arguments of the run, the hash of the
code the queries are built from (:func:`code_hash`: the kernels, the encoding, the concolic
and symbolic domains, the properties as conditions of the run; not the search strategy, which
a replay does not use), the reduction's counts, and per explored case every control path:
the costs it was found with (its *seed*), the first branch it was free to flip (its
*bound*), how each property was judged on it, and how each flip was answered.

:func:`replay` re-checks it: the enumeration and the reduction are redone and must give the
same cases; each path is re-run from its seed and must have as many branches as recorded;
every unsat (a flip, or a property's query) is asked again of a fresh solver and must be
unsat again (a path's unsats asked as one query, their disjunction, which is unsat exactly
when each of them is; each on its own only when it is not); every sat flip must be witnessed by the seed of a recorded path, evaluated on
the flip's query (no solver).  Nothing is searched for: a certificate whose path tree does
not close is refused.  A changed hash refuses the certificate before any of this.
"""

from __future__ import annotations

import gzip
import hashlib
import json
from pathlib import Path

import z3

from ..errors import NavfnInputError
from . import bounded as B

FORMAT = "navfn-smt check certificate 1"
SOURCES = ("spec/kernels.py", "spec/constants.py", "spec/numeric.py", "spec/extraction.py", "spec/fix.py",
           "spec/propagation.py", "smt/domains.py", "check/encoding.py", "check/concolic.py")
# ... and of check/bounded.py the functions that build a path's terms and its properties
FUNCTIONS = ("Case", "_symbolic_run", "_reached", "property_value", "component", "representative", "reduce_cases",
             "SETTLED_BY_REACH", "flippable")
# ... and, for properties of the propagation alone, the run without calcPath
PROPAGATION_FUNCTIONS = ("_propagation_run", "PROPAGATION_ONLY", "run_of")


def code_hash(names=None) -> str:
    """SHA-256 over the sources the queries of a check of ``names`` are built from: the files of
    :data:`SOURCES` and the functions of :data:`FUNCTIONS`, in order, and when no property of
    ``names`` reads calcPath's result, those of :data:`PROPAGATION_FUNCTIONS` too."""
    import inspect

    root = Path(__file__).resolve().parents[1]
    h = hashlib.sha256()
    for rel in SOURCES:
        h.update(rel.encode() + b"\0" + (root / rel).read_bytes() + b"\0")
    extra = () if names is None or B.reads_path(names) else PROPAGATION_FUNCTIONS
    for name in FUNCTIONS + extra:
        obj = getattr(B, name)
        text = repr(sorted(obj)) if isinstance(obj, frozenset) else inspect.getsource(obj)
        h.update(name.encode() + b"\0" + text.encode() + b"\0")
    return h.hexdigest()


def case_key(case: B.Case) -> list:
    return [case.nx, case.ny, sorted(case.lethal), list(case.start), list(case.goal), case.astar]


def case_of(key: list) -> B.Case:
    nx, ny, lethal, start, goal, astar = key
    return B.Case(nx, ny, frozenset(lethal), tuple(start), tuple(goal), bool(astar))


def write(path, header: dict, entries: list) -> None:
    """The certificate: ``header`` (size, properties, costs, modes, variant, reduction counts,
    verdicts) and ``entries`` ``[case key, weight, path log]`` of every explored case."""
    from ..fileio import atomic_write_bytes

    doc = {"format": FORMAT, "code_hash": code_hash(header["properties"]), **header, "cases": entries}
    atomic_write_bytes(path, gzip.compress(json.dumps(doc, separators=(",", ":")).encode(), mtime=0))


def read(path) -> dict:
    try:
        doc = json.loads(gzip.decompress(Path(path).read_bytes()))
    except FileNotFoundError:
        raise NavfnInputError(f"{path}: no such certificate") from None
    except (OSError, ValueError, EOFError) as e:
        raise NavfnInputError(f"{path}: not a check certificate ({e})") from None
    if not isinstance(doc, dict) or doc.get("format") != FORMAT:
        raise NavfnInputError(f"{path}: not a check certificate (format {doc.get('format') if isinstance(doc, dict) else None!r})")
    return doc


def _holds_at(assertions: list, variables: dict, seed: dict) -> bool:
    """Whether the costs ``seed`` satisfy every assertion (evaluated by Z3, no solving)."""
    sub = [(v, z3.BitVecVal(seed[k], v.size())) for k, v in variables.items()]
    return all(z3.is_true(z3.simplify(z3.substitute(a, *sub))) for a in assertions)


def recheck_case(case: B.Case, names, lo: int, hi: int, log: list, timeout: float, variant: str) -> list[str]:
    """The problems of one case's path log (empty: it re-checks)."""
    from .runner import _domain

    inner = [k for k in B._interior(case.nx, case.ny) if k not in case.lethal]
    problems = []
    seeds = {}  # bound -> seeds of the paths recorded with it
    for seed, bound, _, _ in log:
        seeds.setdefault(bound, []).append(dict(zip(inner, seed)))
    run = B.run_of(names)
    for seed, bound, marks, flips in log:
        conc = dict(zip(inner, seed))
        D, costs, sp, ex = run(case, conc, lo, hi, _domain("fp32"), variant)
        variables = {k: costs[k].term for k in inner}
        box = [z3.And(z3.UGE(v, lo), z3.ULE(v, hi)) for v in variables.values()] + list(D.assumptions)
        pc = D.branches
        last = B.flippable(names, pc, sp, lo)
        if flips and bound + len(flips) != last:
            return [f"{case_key(case)}: a path from {seed} has {last} branches to flip, the certificate "
                    f"{bound + len(flips)}"]
        unsat = {}  # what the certificate says is unsat on this path: name -> conditions
        for n, m in zip(names, marks):
            p = B.property_value(n, D, case, costs, sp, ex)
            if m == B.HELD_ON_BOX and D.truth(p) is not True:
                problems.append(f"{case_key(case)}: {n} not decided on the box from {seed}")
            elif m == B.HELD_BY_QUERY:
                unsat[f"{n}'s query"] = pc + [z3.Not(B.term(D, p))]
        for j, m in enumerate(flips, start=bound):
            if m == B.UNSAT:
                unsat[f"flip {j}"] = pc[:j] + [z3.Not(pc[j])]
            elif m == B.SAT:
                flip = box + pc[:j] + [z3.Not(pc[j])]
                if not any(_holds_at(flip, variables, s) for s in seeds.get(j + 1, [])):
                    problems.append(f"{case_key(case)}: flip {j} of the path from {seed} has no recorded witness")
            else:
                problems.append(f"{case_key(case)}: flip {j} of the path from {seed} was left undecided")
        problems += [f"{case_key(case)}: {what} of the path from {seed} is {st}, recorded unsat"
                     for what, st in _all_unsat(box, unsat, variables, timeout)]
    return problems


def _all_unsat(box: list, unsat: dict, variables: dict, timeout: float) -> list:
    """The ``(what, status)`` of the queries ``box & conditions`` not unsat.  First one query,
    their disjunction (unsat exactly when each is); only when it is not, each on its own."""
    if not unsat:
        return []
    def join(op, xs):  # SMT-LIB's and/or take two arguments or more
        return xs[0] if len(xs) == 1 else op(xs)

    either = join(z3.Or, [join(z3.And, c) for c in unsat.values()])
    if B.solve_bitwuzla(box + [either], variables, timeout)[0] == "unsat":
        return []
    got = [(what, B.solve_bitwuzla(box + c, variables, timeout)[0]) for what, c in unsat.items()]
    return [(what, st) for what, st in got if st != "unsat"]


def _replay_job(args):
    entries, names, lo, hi, timeout, variant = args
    return [(key, recheck_case(case_of(key), names, lo, hi, log, timeout, variant)) for key, _, log in entries]


def replay(path, jobs=1, timeout: float = 60.0, progress=None) -> dict:
    """Re-check a certificate (see the module docstring): ``{"status": "replayed" | "refused",
    "problems": [...], ...}``."""
    from ..engine import as_engine, in_order, stream
    from .runner import BATCH, PARALLEL_FROM

    doc = read(path)
    head = {k: doc[k] for k in ("size", "properties", "costs", "modes", "variant", "verdicts", "induction")
            if k in doc}
    now = code_hash(doc["properties"])
    if doc["code_hash"] != now:
        return {**head, "status": "refused", "problems": [
            "the kernels or the encoding changed since the certificate was written (code hash "
            f"{doc['code_hash'][:12]}, now {now[:12]}): run the check again"]}
    nx, ny = doc["size"]
    red = B.reduce_cases(B.cases(nx, ny, [m == "astar" for m in doc["modes"]], None, None, doc.get("ends", "any")))
    want = {json.dumps(case_key(c)): w for c, w in red.representatives.items()}
    got = {json.dumps(k): w for k, w, _ in doc["cases"]}
    problems = []
    if want != got or red.outside != doc["outside"] or red.total != doc["total"]:
        problems.append("the enumeration and reduction of this size do not give the certificate's cases")
    lo, hi = doc["costs"]
    names = doc["properties"]
    work = [(tuple(doc["cases"][k:k + BATCH]), names, lo, hi, timeout, doc["variant"])
            for k in range(0, len(doc["cases"]), BATCH)]
    done = 0
    for _, results in in_order(stream(_replay_job, work, as_engine(jobs).for_work(len(doc["cases"]), PARALLEL_FROM))):
        for _, p in results:
            problems += p
            done += 1
            if progress:
                progress(done, len(doc["cases"]), None)
    return {**head, "status": "refused" if problems else "replayed", "problems": problems,
            "cases": len(doc["cases"]), "paths": sum(len(log) for _, _, log in doc["cases"])}

