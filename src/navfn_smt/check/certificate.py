"""Certificates of bounded checks: what a proof explored and asked, re-checked without searching.

A certificate (gzipped JSON) holds, for one size: the arguments of the run, the hash of the
meaning of the code the queries are built from (:func:`code_hash`: the abstract syntax trees,
without docstrings, comments or layout, of the kernels, the encoding, the concolic and symbolic
domains, the properties as conditions of the run; not the search strategy, which a replay does
not use), the reduction's counts, the verdicts, and per explored case every
control path: the costs it was found with (its *seed*), the first branch it was free to flip
(its *bound*), how each property was judged on it (its *marks*), and how each flip was
answered.

:func:`replay` re-checks it and searches for nothing (docs/check.md has the table of what it
re-checks and what it trusts):

* the header: well formed, a cost box the intervals are sound on (:data:`~.bounded.MIN_COST`),
  a verdict for every property, each from the paths or from a named induction;
* coverage: the enumeration and the reduction are redone and give exactly the certificate's
  cases and weights; every case has one root path (bound 0), first; every other path has a
  parent, an earlier path whose flip ``bound - 1`` is recorded sat and whose first
  ``bound - 1`` branches and that branch negated are exactly the path's own (the path re-run
  from its seed); every sat flip has such a child; every path records as many flips as it has
  branches from its bound to the point the property rule stops at (:func:`~.bounded.flippable`);
* marks against verdicts: a property called proved is held on every path (on the box by the
  intervals, or by a query) and no flip is left undecided; one called refuted has a witness
  map that refutes it on the concrete spec;
* every unsat (a flip, a property's query; with ``check_intervals`` a property held on the box
  too) is asked again, of cvc5 first by default (the search asked bitwuzla), and must be unsat
  (a path's unsats asked as one query, their disjunction, which is unsat exactly when each is;
  each on its own only when it is not); every sat flip's query is evaluated true at its
  child's seed by Z3 (no solving).

What each decision rested on is counted in the result's ``evidence``: the unsats by the solver
that answered, the witnessed flips, and what is trusted (the intervals' verdicts, the paths
cut by QueuedStartReached, the cases decided by the reduction, the inductions).
"""

from __future__ import annotations

import ast
import gzip
import hashlib
import json
import re
import textwrap
from collections import Counter
from pathlib import Path
from typing import Optional

import z3

from ..errors import NavfnInputError
from ..smt import portfolio, smtlib, solvers
from . import bounded as B
from .common import BATCH, PARALLEL_FROM, carried_at, carried_status, outside_decided, symbolic_domain
from .common import replay as spec_replay

FORMAT = "navfn-smt check certificate 2"  # each path also records the branches its box decided
FORMAT_1 = "navfn-smt check certificate 1"  # written before: those branches not recorded, so trusted
FORMATS = (FORMAT, FORMAT_1)
SOURCES = ("spec/kernels.py", "spec/constants.py", "spec/numeric.py", "spec/extraction.py", "spec/fix.py",
           "spec/propagation.py", "spec/planner.py", "smt/domains.py", "check/encoding.py", "check/concolic.py")
# ... and of check/bounded.py the functions that build a path's terms and its properties
FUNCTIONS = ("Case", "_symbolic_run", "_reached", "property_value", "component", "representative", "reduce_cases",
             "SETTLED_BY_REACH", "flippable")
# ... and, for properties of the propagation alone, the run without calcPath
PROPAGATION_FUNCTIONS = ("_propagation_run", "PROPAGATION_ONLY", "run_of")


def _dump(node) -> str:
    """``ast.dump(node, annotate_fields=True, include_attributes=False)`` without the fields that
    are None (but a ``value``) or empty lists: the same text on Python 3.11, 3.12 and 3.13 for
    code they parse alike, where ``ast.dump``'s is not (3.12 adds ``type_params=[]`` to every
    function and class, 3.13 leaves out empty fields)."""
    if isinstance(node, ast.AST):
        fields = ((f, getattr(node, f, None)) for f in node._fields)
        shown = [f"{f}={_dump(v)}" for f, v in fields if not (v is None and f != "value" or v == [])]
        return f"{type(node).__name__}({', '.join(shown)})"
    if isinstance(node, list):
        return f"[{', '.join(_dump(x) for x in node)}]"
    return repr(node)


def meaning_of(text: str) -> bytes:
    """What :func:`code_hash` hashes of a source text (a module, or a function or class as
    ``inspect.getsource`` gives it, dedented when indented): its abstract syntax tree, parsed by
    the running Python, with every docstring (the first statement of a module, class or function
    body when it is a string constant) removed (``pass`` when the body would be empty), dumped
    without positions (:func:`_dump`).  Comments, blank lines and layout are not in the tree."""
    tree = ast.parse(textwrap.dedent(text) if text[:1] in (" ", "\t") else text)
    for node in ast.walk(tree):
        if isinstance(node, (ast.Module, ast.ClassDef, ast.FunctionDef, ast.AsyncFunctionDef)) and node.body:
            first = node.body[0]
            if isinstance(first, ast.Expr) and isinstance(first.value, ast.Constant) and isinstance(first.value.value, str):
                node.body = node.body[1:] or [ast.Pass()]
    return _dump(tree).encode()


def code_hash(names=None) -> str:
    """SHA-256 over the meaning of the sources the queries of a check of ``names`` are built
    from: the files of :data:`SOURCES` and the functions of :data:`FUNCTIONS`, in order, and when
    no property of ``names`` reads calcPath's result, those of :data:`PROPAGATION_FUNCTIONS` too.

    Each file and function is hashed as its abstract syntax tree without docstrings, comments or
    layout (:func:`meaning_of`), so editing those leaves the hash (and the certificates) as they
    are; a frozenset as its sorted members.  The tree is the running Python's parser's: an
    upgrade that parses the same code to another tree (new syntax, a renamed node) changes the
    hash, and a replay then says the code hash changed, which is safe."""
    import inspect

    root = Path(__file__).resolve().parents[1]
    h = hashlib.sha256()
    for rel in SOURCES:
        h.update(rel.encode() + b"\0" + meaning_of((root / rel).read_text(encoding="utf-8")) + b"\0")
    extra = () if names is None or B.reads_path(names) else PROPAGATION_FUNCTIONS
    for name in FUNCTIONS + extra:
        obj = getattr(B, name)
        text = repr(sorted(obj)).encode() if isinstance(obj, frozenset) else meaning_of(inspect.getsource(obj))
        h.update(name.encode() + b"\0" + text + b"\0")
    return h.hexdigest()


def planner_of(doc: dict):
    """The planner a certificate (or its header) is of: its variant, in the arithmetic of its
    float32 semantics (``semantics``, absent in the certificates written before there were
    others: x86-64's ``fp32``)."""
    from ..smt.domains import FP32_SEMANTICS
    from ..under_test import PlannerUnderTest

    from ..spec.fixes import named

    return PlannerUnderTest(named(doc["variant"]), FP32_SEMANTICS[doc.get("semantics", "fp32")])


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
    if not isinstance(doc, dict) or doc.get("format") not in FORMATS:
        raise NavfnInputError(f"{path}: not a check certificate (format {doc.get('format') if isinstance(doc, dict) else None!r})")
    return doc


def digest(path) -> str:
    """The SHA-256 of a certificate's file: a replay report names the certificate it re-checked."""
    return hashlib.sha256(Path(path).read_bytes()).hexdigest()


def _holds_at(assertions: list, variables: dict, seed: dict) -> bool:
    """Whether the costs ``seed`` satisfy every assertion (evaluated by Z3, no solving)."""
    sub = [(v, z3.BitVecVal(seed[k], v.size())) for k, v in variables.items()]
    return all(z3.is_true(z3.simplify(z3.substitute(a, *sub))) for a in assertions)


def _is_int(x) -> bool:
    return isinstance(x, int) and not isinstance(x, bool)


# ---------------------------------------------------------------------------------------
# Asking again
# ---------------------------------------------------------------------------------------
SOLVERS = ("cvc5", "bitwuzla", "z3")
# the search answers its flips with bitwuzla (an instance per path, cvc5 on what it leaves
# open), exact evaluation of small boxes, or an earlier bitwuzla core: a replay asks cvc5 first,
# and bitwuzla only what cvc5 leaves undecided (counted apart in the evidence)
DEFAULT_SOLVERS = ("cvc5", "bitwuzla")


def check_solvers(names) -> tuple:
    """``--solver`` checked: names of :data:`SOLVERS`, each at most once, in the order asked."""
    names = tuple(names)
    if not names or len(set(names)) != len(names) or any(n not in SOLVERS for n in names):
        raise NavfnInputError(f"--solver {','.join(names)}: name one or more of {', '.join(SOLVERS)}, each once, "
                              "in the order they are asked")
    return names


TRANSCRIBE = ("transcript",)  # the "solver" of a transcript (:func:`transcript`)
_ASKED: list = []  # the queries a transcript's case asked, by SHA-256 of their text


_DECLARED = re.compile(r"\(declare-(?:fun|const)\s+(\|[^|]*\||[^\s()]+)")
_TOKEN = re.compile(r"\|[^|]*\||[^\s()]+")


def canonical(smt2: str) -> str:
    """SMT-LIB text with its declared constants renamed ``v0, v1, ...`` in the order they are
    declared, and Z3's let names (``?x31``, ``$x53``, numbered by term ids) ``l0, l1, ...`` in
    the order they appear: the same query built twice in one process (whose fresh names and
    term ids count on) is the same text."""
    table = {n: f"v{i}" for i, n in enumerate(dict.fromkeys(_DECLARED.findall(smt2)))}

    def rename(m):
        tok = m.group(0)
        if tok not in table and tok[:2] in ("?x", "$x") and tok[2:].isdigit():
            table[tok] = f"l{len(table)}"
        return table.get(tok, tok)

    return _TOKEN.sub(rename, smt2)


def ask(assertions: list, order: tuple, timeout: float, memo: Optional[dict] = None) -> tuple:
    """``(status, who)``: the answer of the first solver of ``order`` that decides the query (sat
    or unsat) and its name; ``("unknown", reasons)`` when none does.  ``memo`` keeps the unsat
    answers by the query's text (an unsat is a proof: asking it again gives nothing new)."""
    q = smtlib.prepare(assertions)
    key = hashlib.sha256(q.smt2.encode()).hexdigest()
    if order == TRANSCRIBE:  # a transcript: the query's text is recorded, and taken as unsat
        _ASKED.append(hashlib.sha256(canonical(q.smt2).encode()).hexdigest())
        return "unsat", TRANSCRIBE[0]
    if memo is not None and key in memo:
        return "unsat", memo[key]
    reasons = []
    for who in order:  # each solver its dialect and options, as the portfolio sends them
        req = portfolio.request(q, who, timeout)
        r = solvers.RUNNERS[who](req["text"], timeout, req["names"], req["logic"], **req["options"])
        if r["status"] in ("sat", "unsat"):
            if r["status"] == "unsat" and memo is not None:
                memo[key] = who
            return r["status"], who
        reasons.append(f"{who}: {r.get('detail', r['status'])}")
    return "unknown", "; ".join(reasons)


def _all_unsat(box: list, unsat: dict, order: tuple, timeout: float, memo=None) -> tuple:
    """``(problems, answered)``: the ``(what, status)`` of the queries ``box & conditions`` that
    are not unsat, and how many unsats each solver confirmed.  First one query, their
    disjunction (unsat exactly when each is); only when it is not, each on its own."""
    answered: Counter = Counter()
    if not unsat:
        return [], answered

    def join(op, xs):  # SMT-LIB's and/or take two arguments or more
        return xs[0] if len(xs) == 1 else op(xs)

    either = join(z3.Or, [join(z3.And, c) for c in unsat.values()])
    st, who = ask(box + [either], order, timeout, memo)
    if st == "unsat":
        answered[who] += len(unsat)
        return [], answered
    problems = []
    for what, c in unsat.items():
        st, who = ask(box + c, order, timeout, memo)
        if st == "unsat":
            answered[who] += 1
        else:
            problems.append((what, st if st == "sat" else f"undecided ({who})"))
    return problems, answered


# ---------------------------------------------------------------------------------------
# One case
# ---------------------------------------------------------------------------------------
MARKS = {B.HELD_ON_BOX: "held on the box", B.HELD_BY_QUERY: "held by a query", B.REFUTED: "refuted",
         B.UNKNOWN: "unknown"}
FLIP_MARKS = {B.UNSAT: "unsat", B.SAT: "sat", B.UNKNOWN: "undecided"}


def new_evidence() -> dict:
    """The counts of what a replay's decisions rested on (see :func:`replay`)."""
    return {"unsat_reasked": {}, "sat_flips_witnessed": 0, "held_on_box_by_intervals": 0,
            "held_on_box_checked": 0, "paths_cut_by_queued_start": 0, "refutations_witnessed": 0}


def _add(total: dict, part: dict) -> None:
    for k, v in part.items():
        if isinstance(v, dict):
            for s, n in v.items():
                total[k][s] = total[k].get(s, 0) + n
        else:
            total[k] = total.get(k, 0) + v


def _log_problem(log, cells: int, properties: int, lo: int, hi: int, recorded: bool = True) -> Optional[str]:
    """What is wrong with the shape of a case's path log, if anything: each path ``[seed, bound,
    marks, flips, decided]`` (a cost in ``lo..hi`` per passable cell, a branch index, a mark per
    property, a mark per flip, the value ``t`` or ``f`` of each branch the box decided; without
    ``decided`` when not ``recorded``: format 1), one root (bound 0), first."""
    if not isinstance(log, list):
        return f"its path log {type(log).__name__} is not a list of paths"
    if not log:
        return "no control path is recorded (the case has no root path)"
    shape = "[seed, bound, marks, flips, decided]" if recorded else "[seed, bound, marks, flips]"
    for i, p in enumerate(log):
        if not (isinstance(p, list) and len(p) == 4 + recorded):
            return f"path {i} is not {shape}"
        seed, bound, marks, flips = p[:4]
        if recorded and not (isinstance(p[4], str) and set(p[4]) <= {"t", "f"}):
            return f"path {i}'s decided branches {p[4]!r} are not a value t or f per branch"
        if not (isinstance(seed, list) and len(seed) == cells and all(_is_int(c) and lo <= c <= hi for c in seed)):
            return f"path {i}'s seed {seed!r} is not {cells} costs in {lo}..{hi}"
        if not (_is_int(bound) and bound >= 0):
            return f"path {i}'s bound {bound!r} is not a branch index"
        if not (isinstance(marks, str) and len(marks) == properties and set(marks) <= set(MARKS)):
            return f"path {i}'s property marks {marks!r} are not one of {''.join(MARKS)} per property"
        if not (isinstance(flips, str) and set(flips) <= set(FLIP_MARKS)):
            return f"path {i}'s flips {flips!r} are not marks {''.join(FLIP_MARKS)}"
    roots = [i for i, p in enumerate(log) if p[1] == 0]
    if roots[:1] != [0]:
        return f"path 0 is not the root: its bound is {log[0][1]} (a case's first path has bound 0)"
    if len(roots) > 1:
        return f"paths {roots} all claim to be the root (bound 0)"
    return None


def _marks_problem(names, marks: str, verdicts: dict, run: tuple, conc: dict, planner, unsat: dict,
                   out: dict, check_intervals: bool) -> Optional[str]:
    """A path's property marks against the verdicts (what is wrong, if anything): held on the box
    re-evaluated by the intervals (and asked of a solver with ``check_intervals``), held by a
    query added to ``unsat``, refuted only where the verdict is, its seed tried as a witness on
    the concrete spec (``out``'s witnesses and evidence), unknown never where proved."""
    D, case, costs, sp, ex = run
    ev = out["evidence"]
    for n, m in zip(names, marks):
        if m in (B.REFUTED, B.UNKNOWN):
            if verdicts[n] != "refuted":
                return f" marks {n} {MARKS[m]}; the certificate calls it {verdicts[n]}"
            if m == B.REFUTED and n not in out["witnesses"] and spec_replay(case, conc, n, planner)[2]:
                out["witnesses"].append(n)
                ev["refutations_witnessed"] += 1
            continue
        p = B.property_value(n, D, case, costs, sp, ex)
        truth, negated = D.truth(p), D.branches + [z3.Not(B.term(D, p))]
        if m == B.HELD_ON_BOX:
            if truth is not True:
                return f": {n} is marked held on the box, and the intervals do not decide it"
            ev["held_on_box_by_intervals"] += 1
            if check_intervals:
                unsat[f"{n} on the box"] = negated
                ev["held_on_box_checked"] += 1
        elif truth is True:
            return f": {n} is marked held by a query, and the intervals decide it (the search asks no query then)"
        else:
            unsat[f"{n}'s query"] = negated
    return None


def _decided_problem(by_intervals: list, record: str, unsat: dict) -> Optional[str]:
    """The branches the box decided on a path (``(condition, value)`` of the run) against the
    certificate's record of their values (what is wrong, if anything); the query that they hold
    on the whole box, as the record says, is added to ``unsat`` (its negation must be unsat)."""
    if len(record) != len(by_intervals):
        return f": it records {len(record)} branches decided by the box, and the run has {len(by_intervals)}"
    if record:
        held = [c if v == "t" else z3.Not(c) for (c, _), v in zip(by_intervals, record)]
        unsat["the branches the box decided"] = [z3.Not(z3.And(held) if len(held) > 1 else held[0])]
    return None


def check_case(case: B.Case, names, lo: int, hi: int, log, timeout: float, planner,
               verdicts: Optional[dict] = None, order: tuple = DEFAULT_SOLVERS, check_intervals: bool = False,
               memo: Optional[dict] = None, recorded: bool = True) -> dict:
    """One case's path log re-checked (the module docstring) as ``planner`` plans (a
    :class:`~navfn_smt.under_test.PlannerUnderTest`: its variant, in its arithmetic):
    ``{"problems": [...], "evidence": {...}, "witnesses": [properties refuted at some path's seed
    on the concrete spec]}``.
    ``verdicts``: the certificate's verdict of each of ``names`` (default: every one proved)."""
    verdicts = verdicts or {n: "proved" for n in names}
    proved = [n for n in names if verdicts.get(n) == "proved"]
    inner = [k for k in B.interior(case.nx, case.ny) if k not in case.lethal]
    where = json.dumps(case_key(case))
    ev = new_evidence()
    out = {"problems": [], "evidence": ev, "witnesses": []}

    def refuse(msg):
        out["problems"].append(f"case {where}: {msg}")
        return out

    wrong = _log_problem(log, len(inner), len(names), lo, hi, recorded)
    if wrong:
        return refuse(wrong)
    run = B.run_of(names)
    runs = []  # per path: (branches, box, variables)
    make = symbolic_domain(planner.fp32_semantics())
    make = B.recording(make) if recorded else make  # format 1: the run as it was when the certificate was written
    open_sat: dict = {}  # flip index -> paths whose flip there is recorded sat and has no child yet
    for i, (seed, bound, marks, flips, *decided) in enumerate(log):
        conc = dict(zip(inner, seed))
        D, costs, sp, ex = run(case, conc, lo, hi, make, planner.fix)
        variables = {k: costs[k].term for k in inner}
        box = [z3.And(z3.UGE(v, lo), z3.ULE(v, hi)) for v in variables.values()] + list(D.assumptions)
        pc = D.branches
        runs.append((pc, box, variables))
        at = f"path {i} (seed {seed}, bound {bound})"
        if i:
            j = bound - 1
            parent = next((k for k in open_sat.get(j, []) if B.takes_flip(pc, runs[k][0], j)), None)
            if parent is None:
                return refuse(f"{at} has no parent: no earlier path records flip {j} sat with this path's "
                              "branches on the other side")
            open_sat[j].remove(parent)
            ppc, pbox, pvars = runs[parent]
            if not _holds_at(pbox + ppc[:j] + [z3.Not(ppc[j])], pvars, conc):
                return refuse(f"{at}: its seed does not satisfy flip {j} of path {parent} (evaluated by Z3)")
            ev["sat_flips_witnessed"] += 1
        unsat = {}  # what the certificate says is unsat on this path: name -> conditions
        if recorded:  # every branch the box decided, with the value recorded: box => each, asked
            wrong = _decided_problem(D.by_intervals, decided[0], unsat)
            if wrong:
                return refuse(f"{at}{wrong}")
            ev["interval_decisions_asked"] = ev.get("interval_decisions_asked", 0) + len(decided[0])
        wrong = _marks_problem(names, marks, verdicts, (D, case, costs, sp, ex), conc, planner, unsat, out,
                               check_intervals)
        if wrong:
            return refuse(f"{at}{wrong}")
        last = B.flippable(names, pc, sp, lo)
        ev["paths_cut_by_queued_start"] += last < len(pc)
        settled = all(m == B.REFUTED for m in marks)  # every property refuted: the search flips nothing more
        want = 0 if settled else max(0, last - bound)
        if len(flips) != want:
            return refuse(f"{at} has {want} branches to flip, the certificate records {len(flips)}")
        for j, m in enumerate(flips, start=bound):
            if m == B.UNSAT:
                unsat[f"flip {j}"] = pc[:j] + [z3.Not(pc[j])]
            elif m == B.SAT:
                open_sat.setdefault(j, []).append(i)
            elif proved:
                return refuse(f"{at}: flip {j} was left undecided, and {proved[0]} is called proved")
        bad, answered = _all_unsat(box, unsat, order, timeout, memo)
        for what, st in bad:
            return refuse(f"{at}: {what} is recorded unsat and is {st}")
        _add(ev, {"unsat_reasked": dict(answered)})
    for j, parents in sorted(open_sat.items()):
        for k in parents:
            return refuse(f"path {k} (seed {log[k][0]}) records flip {j} sat, and no recorded path takes it")
    return out


# ---------------------------------------------------------------------------------------
# The whole certificate
# ---------------------------------------------------------------------------------------
def header_problems(doc: dict) -> list[str]:
    """What is wrong with a certificate's header (empty: it is well formed)."""
    from ..smt.domains import FP32_SEMANTICS
    from ..spec.constants import COST_OBS
    from ..spec.fixes import NAMES

    size, names, costs, modes = doc.get("size"), doc.get("properties"), doc.get("costs"), doc.get("modes")
    if not (isinstance(size, list) and len(size) == 2 and all(_is_int(v) and 3 <= v <= 64 for v in size)):
        return [f"size {size!r} is not a map size [W, H]"]
    if not (isinstance(names, list) and names and len(set(map(str, names))) == len(names)
            and all(n in B.CHECKABLE for n in names)):
        return [f"properties {names!r} are not distinct properties of check ({', '.join(B.CHECKABLE)})"]
    if not (isinstance(costs, list) and len(costs) == 2 and all(_is_int(v) for v in costs)
            and 0 <= costs[0] <= costs[1] < COST_OBS):
        return [f"costs {costs!r} are not a cost box [LO, HI] with 0 <= LO <= HI < {COST_OBS}"]
    if costs[0] < B.MIN_COST:
        return [f"costs {costs[0]}..{costs[1]}: costs below {B.MIN_COST} make NaN possible (0/0 in updateCell), where "
                "the concolic intervals are not sound; such a certificate proves nothing"]
    if not (isinstance(modes, list) and modes and len(set(modes)) == len(modes)
            and all(m in ("astar", "dijkstra") for m in modes)):
        return [f"modes {modes!r} are not distinct modes (astar, dijkstra)"]
    if doc.get("variant") not in NAMES:
        return [f"variant {doc.get('variant')!r} is not one of {', '.join(NAMES)}"]
    if doc.get("semantics", "fp32") not in FP32_SEMANTICS:
        return [f"semantics {doc.get('semantics')!r} is not one of {', '.join(FP32_SEMANTICS)}"]
    if doc.get("ends", "any") not in ("any", "passable"):
        return [f"ends {doc.get('ends')!r} is not any or passable"]
    if not all(_is_int(doc.get(k)) and doc.get(k) >= 0 for k in ("total", "outside")):
        return ["total and outside are not counts of cases"]
    verdicts, induction = doc.get("verdicts"), doc.get("induction", {})
    if not isinstance(verdicts, dict) or not isinstance(induction, dict):
        return ["verdicts and induction are not tables of properties"]
    for n in names:
        if verdicts.get(n) not in ("proved", "refuted"):
            return [f"{n} is explored and its verdict is {verdicts.get(n)!r}, not proved or refuted"]
    for n, v in verdicts.items():
        if n not in names and not (isinstance(induction.get(n), str) and induction[n].startswith("induction")):
            return [f"{n} is called {v!r} and neither the paths nor a named induction decide it"]
    if not isinstance(doc.get("cases"), list):
        return ["cases is not a list"]
    return []


def induction_problems(doc: dict) -> list[str]:
    """A verdict the paths do not decide must be the one an induction gives at this size today
    (:func:`~.common.carried_at`, its status from what is known of its predicates)."""
    nx, ny = doc["size"]
    carried = carried_at(nx, ny, planner_of(doc), *doc["costs"])
    for n, v in doc["verdicts"].items():
        if n in doc["properties"]:
            continue
        if n not in carried:
            return [f"{n} is called {v} by induction, and no induction decides it at {nx}x{ny}"]
        status, why = carried_status(carried[n], planner_of(doc).fp32_semantics())
        if (v, doc["induction"][n]) != (status, why):
            return [f"{n} is called {v} ({doc['induction'][n]}); what is known today gives {status} ({why})"]
    return []


def _case_entries(doc: dict, memo: Optional[dict] = None) -> tuple[list, list]:
    """``(problems, [(case, weight, log)])`` of the certificate's case entries, against the
    enumeration and reduction of its size (redone here)."""
    nx, ny = doc["size"]
    entries = []
    for i, e in enumerate(doc["cases"]):
        try:
            key, weight, log = e
            nx_, ny_, lethal, start, goal, astar = key
            ok = (nx_, ny_) == (nx, ny) and isinstance(astar, bool) and _is_int(weight) and all(
                _is_int(c) for c in [*lethal, *start, *goal]) and len(start) == len(goal) == 2
        except (TypeError, ValueError):
            ok = False
        if not ok:
            return [f"case entry {i} is not [[W, H, lethal, start, goal, astar], weight, paths] of this size"], []
        entries.append((case_of(key), weight, log))
    how = (nx, ny, tuple(doc["modes"]), doc.get("ends", "any"), doc.get("semantics", "fp32"))
    red = None if memo is None else memo.setdefault("reductions", {}).get(how)
    if red is None:
        red = B.reduce_cases(B.cases(nx, ny, [m == "astar" for m in doc["modes"]], None, None, how[3]),
                             outside_decided(planner_of(doc)))
        if memo is not None:
            memo["reductions"][how] = red
    if red.total != doc["total"] or red.outside != doc["outside"]:
        return [f"the size has {red.total} cases, {red.outside} with the start outside the goal's component; the "
                f"certificate says {doc['total']} and {doc['outside']}"], []
    seen = set()
    for case, weight, _ in entries:
        if case in seen:
            return [f"case {json.dumps(case_key(case))} is listed twice"], []
        seen.add(case)
        want = red.representatives.get(case)
        if want is None:
            return [f"case {json.dumps(case_key(case))} is not a case the reduction explores"], []
        if want != weight:
            return [f"case {json.dumps(case_key(case))} stands for {want} cases; the certificate says {weight}"], []
    missing = [c for c in red.representatives if c not in seen]
    if missing:
        return [f"case {json.dumps(case_key(missing[0]))} of the size has no entry "
                f"({len(missing)} cases missing)"], []
    return [], entries


def _replay_job(args):
    entries, names, verdicts, lo, hi, timeout, planner, order, check_intervals, recorded = args
    return [check_case(case_of(key), names, lo, hi, log, timeout, planner, verdicts, order, check_intervals,
                       recorded=recorded) for key, _, log in entries]


def _transcript_job(args):
    entries, names, verdicts, lo, hi, planner, recorded = args
    out = []
    for key, _, log in entries:
        _ASKED.clear()
        got = check_case(case_of(key), names, lo, hi, log, 1.0, planner, verdicts, TRANSCRIBE, recorded=recorded)
        out.append([key, list(_ASKED), got])
    return out


# ---------------------------------------------------------------------------------------
# Transcripts: a certificate carried to changed code
# ---------------------------------------------------------------------------------------
TRANSCRIPTS = Path(__file__).resolve().parents[3] / "docs" / "reports" / "certificates" / "transcripts.json"


def transcript(doc: dict, jobs=1, progress=None) -> dict:
    """What a replay of ``doc`` does under this code, without a solver: the cases the
    enumeration and the reduction give, the inductions' problems, and for every case each
    query the replay would ask (the SHA-256 of its SMT-LIB text, in order) and every decision
    it makes (problems, evidence, witnesses), each query taken as unsat.  Two codes with the
    same transcript replay the certificate alike: the same queries to the solvers, the same
    decisions.  ``{"sha256", "code_hash", "cases", "queries"}``."""
    from ..engine import as_engine, in_order, stream

    problems = header_problems(doc)
    if problems:
        raise NavfnInputError(f"not a certificate: {problems[0]}")
    h = hashlib.sha256()
    problems, entries = _case_entries(doc, None)
    h.update(json.dumps([problems, induction_problems(doc),
                         [[case_key(c), w] for c, w, _ in entries]]).encode())
    lo, hi = doc["costs"]
    args = (doc["properties"], doc["verdicts"], lo, hi, planner_of(doc), doc["format"] == FORMAT)
    work = [(tuple([case_key(c), w, log] for c, w, log in entries[k:k + BATCH]), *args)
            for k in range(0, len(entries), BATCH)]
    done = queries = 0
    for _, results in in_order(stream(_transcript_job, work, as_engine(jobs).for_work(len(entries), PARALLEL_FROM))):
        for key, asked, got in results:
            h.update(json.dumps([key, asked, got], sort_keys=True).encode())
            done += 1
            queries += len(asked)
            if progress:
                progress(done, len(entries), None)
    return {"sha256": h.hexdigest(), "code_hash": code_hash(doc["properties"]), "cases": len(entries),
            "queries": queries}


def recorded_transcripts(path: Optional[Path] = None) -> dict:
    """The committed transcripts (:data:`TRANSCRIPTS`): certificate file name ->
    {"certificate_sha256", "transcripts": {code hash: transcript}}."""
    path = path or TRANSCRIPTS
    try:
        return json.loads(path.read_text(encoding="utf-8"))
    except FileNotFoundError:
        return {}
    except (OSError, ValueError) as e:
        raise NavfnInputError(f"{path}: not a transcripts file ({e})") from None


def carried(name: str, doc: dict, sha256: str, now: str, record: Optional[dict] = None) -> bool:
    """Whether the certificate (file ``name``, SHA-256 ``sha256``) written by code ``doc
    ["code_hash"]`` carries to the code ``now``: its transcript recorded under ``now`` equals
    the one recorded under the code that wrote it."""
    entry = (recorded_transcripts() if record is None else record).get(name) or {}
    ts = entry.get("transcripts") or {}
    then = ts.get(doc.get("code_hash"))
    return (entry.get("certificate_sha256") == sha256 and then is not None and now in ts
            and ts[now]["sha256"] == then["sha256"])


def _witness_problems(doc: dict, witnessed: set) -> list[str]:
    """A refuted property needs a witness: a path's seed that refutes it on the concrete spec
    (found while the cases are re-checked), or the header's ``witnesses`` entry, replayed here."""
    from .properties import judge, run as run_spec
    import numpy as np

    out = []
    for n in doc["properties"]:
        if doc["verdicts"][n] != "refuted" or n in witnessed:
            continue
        w = (doc.get("witnesses") or {}).get(n)
        try:
            planner = planner_of(doc)
            r = run_spec(np.array(w["costs"], np.uint8), tuple(w["start"]), tuple(w["goal"]), w["mode"] == "astar",
                         fix=planner.fix, arith=planner.navfn_arithmetic())
            ok = np.array(w["costs"]).shape == (doc["size"][1], doc["size"][0]) and judge(n, r) is not None
        except (TypeError, KeyError, ValueError, IndexError):
            ok = False
        if not ok:
            out.append(f"{n} is called refuted, and no recorded map refutes it on the concrete spec")
        else:
            witnessed.add(n)
    return out


def part_range(explored: int, part: tuple) -> tuple:
    """The cases ``[lo, hi)`` (positions among the explored cases, in the certificate's order)
    that part ``k`` of ``n`` re-checks: the n parts tile them, in order."""
    k, n = part
    return (k - 1) * explored // n, k * explored // n


def replay(path, jobs=1, timeout: float = 60.0, progress=None, order: tuple = DEFAULT_SOLVERS,
           check_intervals: bool = False, memo: Optional[dict] = None, doc: Optional[dict] = None,
           part: tuple = (1, 1)) -> dict:
    """Re-check a certificate (the module docstring): ``{"status": "replayed" | "refused",
    "problems": [...], "evidence": {...}, "trusted": {...}, ...}``; the first problem refuses it.
    ``order``: the solvers asked, in turn; ``check_intervals``: the properties held on the box are
    asked of them too; ``memo`` (one process): answers kept across replays; ``doc``: the
    certificate already read.  ``part=(k, n)``: every check of the whole certificate (header,
    hash, inductions, coverage of the cases) but the paths of the k-th n-th of its cases only
    (:func:`part_range`); the n part reports together are a whole replay (:func:`combine`)."""
    from ..engine import as_engine, in_order, stream

    doc = read(path) if doc is None else doc
    head = {k: doc[k] for k in ("size", "properties", "costs", "modes", "variant", "semantics", "verdicts", "induction")
            if k in doc}
    order = check_solvers(order)

    def refused(problems):
        return {**head, "status": "refused", "problems": problems, "solvers": list(order)}

    problems = header_problems(doc)
    if problems:
        return refused(problems)
    now = code_hash(doc["properties"])
    if doc.get("code_hash") != now and not (path and carried(Path(path).name, doc, digest(path), now)):
        return refused(["the kernels or the encoding changed since the certificate was written (code hash "
                        f"{str(doc.get('code_hash'))[:12]}, now {now[:12]}), and no recorded transcript carries "
                        "it to this code (check --transcript): run the check again"])
    if doc.get("code_hash") != now:  # carried: the same queries and decisions as under the code that wrote it
        head["carried"] = {"from": doc["code_hash"], "to": now}
    problems = induction_problems(doc)
    if problems:
        return refused(problems)
    problems, entries = _case_entries(doc, memo)
    if problems:
        return refused(problems)
    whole = len(entries)
    first, last = part_range(whole, part)
    entries = entries[first:last]
    lo, hi = doc["costs"]
    names, verdicts = doc["properties"], doc["verdicts"]
    planner = planner_of(doc)
    recorded = doc["format"] == FORMAT
    args = (names, verdicts, lo, hi, timeout, planner, order, check_intervals, recorded)
    evidence = new_evidence()
    witnessed: set = set()
    problems = []
    done = 0
    if memo is not None:  # in this process, each case's result kept by its entry; stops at a problem
        results = []
        known, unsat = memo.setdefault("cases", {}), memo.setdefault("unsat", {})
        for case, w, log in entries:
            k = json.dumps([case_key(case), log, names, verdicts, lo, hi, doc["variant"], doc.get("semantics", "fp32"),
                            order, check_intervals])
            if k not in known:
                known[k] = check_case(case, names, lo, hi, log, timeout, planner, verdicts, order,
                                      check_intervals, unsat, recorded)
            results.append(known[k])
            if known[k]["problems"]:
                break
        batches = [(0, results)]
    else:
        work = [(tuple([case_key(c), w, log] for c, w, log in entries[k:k + BATCH]), *args)
                for k in range(0, len(entries), BATCH)]
        batches = in_order(stream(_replay_job, work, as_engine(jobs).for_work(len(entries), PARALLEL_FROM)))
    for _, results in batches:
        for got in results:
            problems += got["problems"]
            _add(evidence, got["evidence"])
            witnessed.update(got["witnesses"])
            done += 1
            if progress:
                progress(done, len(entries), None)
    if part == (1, 1):
        problems += _witness_problems(doc, witnessed)
    got = {**head, "status": "refused" if problems else "replayed", "problems": problems, "solvers": list(order),
           "cases": len(entries), "paths": sum(len(log) for _, _, log in entries), "evidence": evidence,
           "trusted": _trusted(doc, evidence, whole), "interval_decisions_recorded": recorded}
    if part != (1, 1):  # the witnesses are judged when the parts are combined
        got.update(part=list(part), case_range=[first, last], witnessed=sorted(witnessed))
    return got


def _trusted(doc: dict, evidence: dict, explored: int) -> dict:
    trusted = {
        "held_on_box_by_intervals": evidence["held_on_box_by_intervals"] - evidence["held_on_box_checked"],
        "paths_cut_by_queued_start": evidence["paths_cut_by_queued_start"],
        "cases_by_reduction": doc["total"] - explored,
        "by_induction": sorted(n for n in doc["verdicts"] if n not in doc["properties"])}
    trusted["count"] = sum(v for v in trusted.values() if isinstance(v, int))
    return trusted


def combine(doc: dict, sha256: str, reports: list) -> dict:
    """The whole replay of the certificate ``doc`` (whose file has the SHA-256 ``sha256``) from
    the reports of its parts (``check --replay --part K/N --json``): refused unless every report
    is of this certificate, replayed, with the same solvers and options, and the parts are
    1..n of one n, each once, tiling the explored cases; the refuted verdicts' witnesses are
    judged over all parts."""
    head = {k: doc[k] for k in ("size", "properties", "costs", "modes", "variant", "semantics", "verdicts", "induction")
            if k in doc}
    problems = []
    n = {tuple(r.get("part", (1, 1)))[1] for r in reports}
    if len(n) != 1:
        problems.append(f"the parts are of different splits: {sorted(n)}")
    n = max(n) if n else 0
    explored = len(doc.get("cases", []))
    seen = sorted(tuple(r.get("part", (1, 1))) for r in reports)
    if seen != [(k, n) for k in range(1, n + 1)]:
        problems.append(f"the parts are {['%d/%d' % p for p in seen]}, not each of 1/{n} to {n}/{n} once")
    for r in reports:
        k = tuple(r.get("part", (1, 1)))
        name = "part %d/%d" % k
        if r.get("certificate_sha256") != sha256:
            problems.append(f"{name} is the replay of another certificate (SHA-256 "
                            f"{str(r.get('certificate_sha256'))[:12]}, this one {sha256[:12]})")
        if r.get("status") != "replayed":
            problems.append(f"{name} did not replay: {(r.get('problems') or [r.get('status')])[0]}")
        if list(r.get("case_range", part_range(explored, k))) != list(part_range(explored, k)):
            problems.append(f"{name} covers cases {r.get('case_range')}, not {list(part_range(explored, k))}")
        for key in ("solvers", "check_intervals"):
            if r.get(key) != reports[0].get(key):
                problems.append(f"{name} was replayed with {key} {r.get(key)}, part "
                                f"{'%d/%d' % tuple(reports[0].get('part', (1, 1)))} with {reports[0].get(key)}")
    if problems:
        return {**head, "status": "refused", "problems": problems}
    evidence, witnessed = new_evidence(), set()
    for r in reports:
        _add(evidence, r["evidence"])
        witnessed.update(r.get("witnessed", ()))
    problems = _witness_problems(doc, witnessed)
    return {**head, "status": "refused" if problems else "replayed", "problems": problems,
            "solvers": reports[0]["solvers"], "check_intervals": reports[0].get("check_intervals", False),
            "cases": sum(r["cases"] for r in reports), "paths": sum(r["paths"] for r in reports),
            "evidence": evidence, "trusted": _trusted(doc, evidence, explored), "parts": n,
            "seconds": round(sum(r.get("seconds", 0.0) for r in reports), 1)}
