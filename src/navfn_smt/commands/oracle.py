"""``navfn-smt oracle build NAV2_SRC``: build the user's own Nav2 NavFn as an oracle.

The sources are compiled unchanged (:mod:`navfn_smt.oracle.build`); ``difftest --oracle DIR``
and ``suite record --oracle DIR`` then run them live.
"""

from __future__ import annotations

DEFAULT_OUT = "build/nav2-oracle"


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


def register(sub) -> None:
    """The ``oracle`` command and its ``build`` subcommand."""
    from .common import add_toolchain_arguments

    orc = sub.add_parser("oracle", help="build the user's own Nav2 NavFn (unchanged) to test the spec against")
    osub = orc.add_subparsers(dest="oracle_command", required=True, metavar="SUBCOMMAND")
    b = osub.add_parser("build", help="compile nav2_navfn_planner's NavFn from a navigation2 checkout",
                        description="Compile NavFn (navfn.cpp) from NAV2_SRC unchanged, with the project's "
                        "drivers and ROS stub headers: plain; with a white-box trace hook inserted at an anchor "
                        "line in a copy; with priority buffers that never drop (a copy of navfn.hpp); and the "
                        "planner plugin (navfn_planner.cpp with Nav2's costmap_2d.cpp).  Record the compiler, "
                        "flags, source hashes, git commit and distribution in DIR/build.json.")
    b.add_argument("nav2_src", metavar="NAV2_SRC",
                   help="a navigation2 checkout, or a folder holding nav2_navfn_planner, nav2_core and nav2_costmap_2d")
    b.add_argument("--out", metavar="DIR", default=DEFAULT_OUT, help="the build folder (default: %(default)s)")
    add_toolchain_arguments(b)
    b.add_argument("--library", metavar="FILE.so", help="your own NavFn binary: link the driver against this shared "
                   "library (as a package build makes it, -fPIC -O2 -g), built from NAV2_SRC; its target is read from "
                   "the file and its arithmetic from its machine code; only navfn-plain is built")
    b.set_defaults(func=cmd_oracle_build)
