"""The report of ``navfn-smt split`` (:mod:`navfn_smt.commands.split`): the table gives per split the
verdict against what is known of it (:mod:`navfn_smt.smt.knowledge`), the parts by verdict,
the slowest part, the cover and the wall time; ``--report`` writes all of it with every
part's box, method and time as JSON.  Exit 1 only when a verdict contradicts what is known:
a split left undecided (a part out of time) is reported, a decision where nothing was known
is news (``--record`` keeps it).
"""

from __future__ import annotations

import json

from .tables import console, duration


def interval_text(iv: dict) -> str:
    """One variable's interval of a part's box, as the terminal shows it."""
    if "lo_hex" in iv:
        lo, hi = iv["lo"], iv["hi"]
        return f"{iv['var']} = {lo:g}" if lo == hi else f"{iv['var']} in [{lo:g}, {hi:g}]"
    return f"{iv['var']} = {iv['lo']}" if iv["lo"] == iv["hi"] else f"{iv['var']} in [{iv['lo']}, {iv['hi']}]"


def table(outcomes) -> None:
    from rich.table import Table

    t = Table(title="splits")
    for col in ("obligation", "verdict", "known", "judgement", "parts", "proved", "refuted", "unknown", "slowest part",
                "cover", "wall time"):
        t.add_column(col)
    for o in outcomes:
        c, slow = o.counts(), o.slowest()
        t.add_row(o.obligation, o.status, o.known, o.judgement, str(len(o.parts)), str(c["proved"]), str(c["refuted"]),
                  str(c["unknown"]), f"{slow['seconds']:.1f} s" if slow else "-",
                  f"{o.cover['status']} ({o.cover['seconds']:.1f} s)", duration(o.seconds))
    console.print(t)
    for o in outcomes:
        if o.undecided:
            print(f"{o.obligation}: undecided parts:")
            for p in o.undecided[:10]:
                print(f"  {', '.join(interval_text(iv) for iv in p['box'])} ({p['detail']})")
        for p in o.parts:
            if p["status"] == "refuted" and p.get("witness"):
                vals = ", ".join(f"{k}={v['value'] if isinstance(v, dict) else v!r}"
                                 for k, v in p["witness"]["values"].items())
                print(f"{o.obligation}: refuted, witness replayed on the float32 spec: {vals}")
                break


def write_json(path: str, outcomes, seconds: float, where: str) -> None:
    from ..fileio import atomic_write_text
    from ..smt.split import outcome_json

    doc = {"engine": where, "seconds": round(seconds, 3), "splits": [outcome_json(o) for o in outcomes]}
    atomic_write_text(path, json.dumps(doc, indent=1) + "\n")
