"""``navfn-smt oracle build NAV2_SRC``: build the user's own Nav2 NavFn as an oracle;
``navfn-smt oracle nav2-tests NAV2_SRC``: build and run Nav2's own NavFn tests against it, as it
is and with a fix's patch (each fix of ``spec/fixes.py`` that has patches).

The sources are compiled unchanged (:mod:`navfn_smt.oracle.build`); ``difftest --oracle DIR``
and ``suite record --oracle DIR`` then run them live.  Nav2's tests: :mod:`navfn_smt.oracle.nav2_tests`.
"""

from __future__ import annotations

DEFAULT_OUT = "build/nav2-oracle"
DEFAULT_TESTS_OUT = "build/nav2-tests"


def cmd_oracle_build(args) -> int:
    from ..oracle.build import build
    from .common import toolchain_of

    tc = toolchain_of(args)
    tc = None if args.library and not (args.target or args.cxx) else tc
    doc = build(args.nav2_src, args.out, tc=tc, library=args.library)
    commit = f", commit {doc['git_commit'][:12]}" if doc.get("git_commit") else ""
    runs = f", run under {' '.join(doc['runner'])}" if doc["runner"] else ""
    print(f"built the NavFn oracle of {doc['sources']} ({doc['distribution']}{commit}) for {doc['target']} "
          f"({doc['machine']}{runs}) into {args.out} with {doc['compiler_version'] or doc['compiler']} "
          f"{' '.join(doc['flags'])}: {', '.join(doc['programs'])}")
    for name, why in doc.get("skipped", {}).items():
        print(f"  left out {name}: {why}")
    return 0


def cmd_oracle_nav2_tests(args) -> int:
    from ..oracle.nav2_tests import PASSED, failed, run_nav2_tests, without_fix
    from .common import toolchain_of

    doc = run_nav2_tests(args.nav2_src, args.out, _variant_groups().get(args.variant, (args.variant,)),
                         tc=toolchain_of(args))
    variants = doc["variants"]
    runs = f", run under {' '.join(doc['runner'])}" if doc["runner"] else ""
    patches = "".join(f"; {name}: {p['folder']}/{p['file']}" for name, p in doc.get("patches", {}).items())
    print(f"Nav2's own tests of nav2_navfn_planner, {doc['distribution']} ({doc['sources']}), built for "
          f"{doc['target']}{runs} with {doc['compiler_version'] or doc['compiler']} {' '.join(doc['flags'])} into "
          f"{args.out}{patches}:")
    rows = {}
    for r in doc["results"]:
        rows.setdefault((r["program"], r["case"] or "(the program)"), {})[r["variant"]] = r["status"]
    print("| program | from | test | " + " | ".join(variants) + " |")
    print("|---|---|---|" + "---|" * len(variants))
    for (program, case), status in rows.items():
        print(f"| {program} | {doc['programs'][program]['from']} | {case} | "
              + " | ".join(status.get(v, "-") for v in variants) + " |")
    bad = failed(doc)
    for r in bad:
        print(f"{r['variant']}: {r['program']} {r['case'] or ''} {r['status']}: {r.get('message', '')}")
    shown = [r for r in doc["results"] if without_fix(doc, r)]
    fix_line = (f"; the fix's own tests as shipped: {sum(r['status'] != PASSED for r in shown)} of {len(shown)} fail "
                f"(they show what the fix changes)") if shown else ""
    print(f"{sum(r['status'] == PASSED for r in doc['results'] if not without_fix(doc, r))} passed, {len(bad)} failed "
          f"or crashed{fix_line}")
    if args.json:
        import json

        from ..fileio import atomic_write_text

        atomic_write_text(args.json, json.dumps(doc, indent=1) + "\n")
    return 1 if bad else 0


def cmd_oracle_lint(args) -> int:
    from ..oracle.lint import lint_fix

    doc = lint_fix(args.nav2_src, args.patch, args.variant)
    print(f"Nav2's lint on {doc['patch']} for {doc['distribution']} ({doc['sources']}): {doc['uncrustify']['version']} "
          f"with ament's {doc['uncrustify']['config']}, cpplint with ament_cpplint's arguments:")
    print("| file | linter | findings as shipped | patched | added by the patch |")
    print("|---|---|---|---|---|")
    for r in doc["files"]:
        print(f"| {r['file']} | {r['tool']} | {r['shipped']} | {r['patched']} | {len(r['added'])} |")
    added = [(r, f) for r in doc["files"] for f in r["added"]]
    for r, f in added:
        print(f"{r['file']}:{f['line']}: {r['tool']}: {f['message']}")
    print(f"{len(added)} findings added by the patch")
    if args.json:
        import json

        from ..fileio import atomic_write_text

        atomic_write_text(args.json, json.dumps(doc, indent=1) + "\n")
    return 1 if added else 0


def _variant_groups() -> dict:
    """``oracle nav2-tests --variant``'s groups: ``both`` (as shipped and the fix of docs/fix.md)
    and ``all`` (as shipped and every patched fix); a fix's name stands for itself."""
    from ..oracle.nav2_tests import ALL, BOTH

    return {"both": BOTH, "all": ALL}


def _sources_argument(parser) -> None:
    parser.add_argument("nav2_src", metavar="NAV2_SRC",
                        help="a navigation2 checkout, or a folder holding nav2_navfn_planner, nav2_core and nav2_costmap_2d")


def register(sub) -> None:
    """The ``oracle`` command and its ``build`` subcommand."""
    from ..spec import fixes
    from ..spec.fix import FIX as THE_FIX
    from .common import add_toolchain_arguments

    orc = sub.add_parser("oracle", help="build the user's own Nav2 NavFn (unchanged) to test the spec against")
    osub = orc.add_subparsers(dest="oracle_command", required=True, metavar="SUBCOMMAND")
    b = osub.add_parser("build", help="compile nav2_navfn_planner's NavFn from a navigation2 checkout",
                        description="Compile NavFn (navfn.cpp) from NAV2_SRC unchanged, with the project's "
                        "drivers and ROS stub headers: plain; with a white-box trace hook inserted at an anchor "
                        "line in a copy; with priority buffers that never drop (a copy of navfn.hpp); and the "
                        "planner plugin (navfn_planner.cpp with Nav2's costmap_2d.cpp); and for each fix with patches "
                        "(patches/<fix>/<distribution>.patch) its traced NavFn, plugin and plain NavFn, "
                        "navfn-<fix>, navfn-plugin-<fix>, navfn-plain-<fix>.  Record the compiler, "
                        "flags, source hashes, patches, git commit and distribution in DIR/build.json.")
    _sources_argument(b)
    b.add_argument("--out", metavar="DIR", default=DEFAULT_OUT, help="the build folder (default: %(default)s)")
    add_toolchain_arguments(b)
    b.add_argument("--library", metavar="FILE.so", help="your own NavFn binary: link the driver against this shared "
                   "library (as a package build makes it, -fPIC -O2 -g), built from NAV2_SRC; its target is read from "
                   "the file and its arithmetic from its machine code; only navfn-plain is built")
    b.set_defaults(func=cmd_oracle_build)
    t = osub.add_parser("nav2-tests", help="build and run nav2_navfn_planner's own gtests, as shipped and with a fix",
                        description="Build every gtest that nav2_navfn_planner/test/CMakeLists.txt of NAV2_SRC declares "
                        "against NavFn as it is (original) and as a fix's patch makes it (fixed, cycles-only, ...), "
                        "with googletest from its sources (Debian: libgtest-dev) and, for the tests that make the "
                        "planner plugin, the project's ROS stub headers; the tests a fix's patch adds are run as "
                        "shipped and with that fix.  Report every gtest "
                        "case; exit 1 when one fails where it should pass (every test patched, the sources' own as "
                        "shipped).")
    _sources_argument(t)
    t.add_argument("--out", metavar="DIR", default=DEFAULT_TESTS_OUT, help="the build folder (default: %(default)s)")
    t.add_argument("--variant", choices=(fixes.AS_SHIPPED.name, *(f.name for f in fixes.PATCHED), *_variant_groups()),
                   default="both",
                   help=f"NavFn as shipped ({fixes.AS_SHIPPED.name}), with one fix's patch (patches/<fix>/: "
                   f"{', '.join(f'{f.name}: patches/{f.patches}/' for f in fixes.PATCHED)}), both ({fixes.AS_SHIPPED.name} "
                   f"and {THE_FIX.name}) or all (default: %(default)s)")
    t.add_argument("--json", metavar="FILE", help="write the report (every case, its status and message) as JSON")
    add_toolchain_arguments(t)
    t.set_defaults(func=cmd_oracle_nav2_tests)
    lint = osub.add_parser("lint", help="Nav2's lint (ament's uncrustify and cpplint) on a fix's patch",
                           description="Run uncrustify with ament's configuration and cpplint with ament_cpplint's "
                           "arguments on each file a fix's patch touches, as shipped and patched, and report the "
                           "findings the patch adds (the same message, line numbers aside).  Exit 1 when it adds one.")
    _sources_argument(lint)
    lint.add_argument("--variant", choices=tuple(f.name for f in fixes.PATCHED), default=THE_FIX.name,
                      help="the fix whose patch is judged: the distribution's patches/<fix>/ patch (default: "
                      "%(default)s)")
    lint.add_argument("--patch", metavar="FILE", help="another patch to judge (default: the --variant fix's patch "
                      "for the distribution)")
    lint.add_argument("--json", metavar="FILE", help="write the report (counts and added findings) as JSON")
    lint.set_defaults(func=cmd_oracle_lint)
