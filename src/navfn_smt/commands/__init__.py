"""The command layer: one module per command, each with ``register(sub)`` (its parser, its
options and its handler) and the handler itself.  :mod:`navfn_smt.cli` builds the command
line from :data:`COMMANDS`, in this order (the order ``navfn-smt --help`` lists them);
:mod:`.common` holds what every command shares.  A new command is a new module here and a
name below, never a longer ``cli.py``.
"""

COMMANDS = ("plan", "difftest", "render", "metamorphic", "coverage", "suite", "prove", "mutate", "bench", "check",
            "search", "diagnose", "docs", "split", "oracle", "ci", "nav2_benchmark", "plugin_check", "path_quality",
            "planner_tester", "fixes")
