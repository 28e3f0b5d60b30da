"""``navfn-smt plugin-check``: what a Nav2 user relies on of the planner plugin, on every small costmap."""

from __future__ import annotations

from ..spec import fixes
from ..spec.fix import FIX as THE_FIX
from ..errors import NavfnInputError
from .common import check_files, vars_of


def _values(text: str) -> tuple[int, ...]:
    try:
        vals = tuple(sorted({int(v) for v in text.split(",")}))
    except ValueError:
        raise NavfnInputError(f"--values {text}: costmap values 0..255, comma-separated") from None
    if not vals or not all(0 <= v <= 255 for v in vals):
        raise NavfnInputError(f"--values {text}: costmap values 0..255, comma-separated")
    return vals


def cmd_plugin_check(args) -> int:
    """Judge the plugin properties on every costmap up to a size; exit 1 when one fails."""
    import sys
    import time

    from ..check.runner import sizes_up_to
    from ..check.plugin import PLUGIN_PROPERTIES, check_plugin, induction_known
    from ..report import plugin_check as report

    check_files(args.json)
    names = tuple(PLUGIN_PROPERTIES) if args.property == "all" else (args.property,)
    w, h = args.max_size
    if args.sample < 0:
        raise NavfnInputError(f"--sample {args.sample}: a number of costmaps per size (0: every layout)")
    limit = 64 if args.sample else 9
    if w < 3 or h < 3 or (w - 2) * (h - 2) > limit:
        raise NavfnInputError(f"--max-size {w} {h}: at least 3x3 (the frame is NavFn's lethal border) and at most "
                              f"{limit} interior cells (every robot and goal cell are enumerated"
                              + (")" if args.sample else "; every layout too, unless --sample)"))
    values = _values(args.values)
    chosen = (fixes.AS_SHIPPED, THE_FIX) if args.variant == "both" else (fixes.named(args.variant),)
    sizes = [s for s in sizes_up_to(w, h) if (s[0] - 2) * (s[1] - 2) >= 2]
    t0 = time.perf_counter()

    def progress(size: str, done: int, total: int) -> None:
        if not args.quiet and (done == total or done % 64 == 0):
            print(f"plugin-check {size}: {done}/{total} costmaps, {time.perf_counter() - t0:.0f} s", file=sys.stderr)

    if args.sample:
        sizes = [tuple(args.max_size)]
    counts = check_plugin(names, sizes, values, chosen, tuple(args.tolerance), args.distro, args.backend,
                          progress, args.sample, args.seed)
    seconds = round(time.perf_counter() - t0, 1)
    what = (f"{args.sample} random {w}x{h} costmaps (seed {args.seed})" if args.sample
            else f"every costmap up to {w}x{h}")
    report.table(f"plugin-check: {what}, values {','.join(map(str, values))} ({seconds} s)", counts)
    induction = {n: ind for n in names if THE_FIX in chosen and (ind := induction_known(n))}
    for n, ind in induction.items():
        print(f"{n} (fixed): every costmap size by induction, under {len(ind['conditions'])} run-time conditions: "
              f"{ind['status']} (" + ", ".join(f"{p} {st}" for p, st in ind["predicates"].items()) + ")")
        for c in ind["conditions"]:
            print(f"  condition: {c}")
    if args.json:
        report.write_json(args.json, {
            "command": "plugin-check", "arguments": vars_of(args), "sizes": [list(s) for s in sizes],
            "values": list(values), "statements": {n: PLUGIN_PROPERTIES[n].statement for n in names},
            "results": [c.__dict__ for c in counts], "every_size_by_induction_fixed": induction,
            "seconds": seconds})
    return 0 if all(c.failed == 0 for c in counts) else 1


def register(sub) -> None:
    """The command's parser, its options and its handler."""
    from ..backends import BACKENDS
    from ..distros import DEFAULT, DISTROS
    from ..check.plugin import PLUGIN_PROPERTIES

    pc = sub.add_parser("plugin-check", help="judge what a Nav2 user relies on of the planner plugin (a plan when "
                        "the goal is reachable, poses in passable cells, the ends) on every small costmap")
    pc.add_argument("property", nargs="?", default="all", choices=(*PLUGIN_PROPERTIES, "all"), metavar="PROPERTY",
                    help=f"one of {', '.join(PLUGIN_PROPERTIES)}, or all (default)")
    pc.add_argument("--max-size", nargs=2, type=int, default=(5, 4), metavar=("W", "H"),
                    help="every costmap size up to W x H, frame included (default: 5 4; at most 9 interior cells)")
    pc.add_argument("--values", default="0,254", metavar="V,V,...",
                    help="the costmap values of the interior cells (default: 0,254, free and lethal; 253 is "
                    "inscribed, 255 unknown)")
    pc.add_argument("--sample", type=int, default=0, metavar="N",
                    help="instead of every layout, N random costmaps of --max-size exactly, each interior cell drawn "
                    "from --values (at most 64 interior cells; default: 0, every layout)")
    pc.add_argument("--seed", type=int, default=0, help="the seed of --sample")
    pc.add_argument("--variant", choices=(*fixes.NAMES, "both"), default="both",
                    help="the plugin as shipped, with a fix (" + fixes.HELP + "), or both: as shipped and with the fix of "
                    "docs/fix.md (default)")
    pc.add_argument("--tolerance", nargs="+", type=float, default=(0.0, 1.0), metavar="M",
                    help="the plugin's tolerance values, in cells (resolution 1; default: 0 1)")
    pc.add_argument("--distro", default=DEFAULT, choices=tuple(DISTROS),
                    help="whose navfn_planner.cpp (default: %(default)s)")
    pc.add_argument("--backend", choices=BACKENDS, default="jit", help="planner implementation (default: jit)")
    pc.add_argument("--json", metavar="FILE", help="write the counts and each first failing case as JSON")
    pc.add_argument("--quiet", action="store_true", help="no progress lines")
    pc.set_defaults(func=cmd_plugin_check)
