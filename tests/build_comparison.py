"""Two C++ builds of NavFn side by side: where the arithmetic of one toolchain parts from another's.

Every case of a suite is planned by both builds (oracles, :mod:`navfn_smt.oracle.client`) and
their answers are compared bit for bit: the potential field (float32 bits), the path (float32
bits), and whether each returned a plan.  No spec is involved: this measures what a change of
toolchain does to NavFn (``docs/toolchains.md``).
"""

from __future__ import annotations

from collections import Counter
from pathlib import Path
from typing import Iterable

import numpy as np

from navfn_smt.maps.suite import discover, load_map


def compare_builds(root, modes: Iterable[str], a, b, examples: int = 3) -> dict:
    """Counts over every case of ``root`` in ``modes``: ``runs``, ``potential`` (fields that
    differ), ``path`` (paths that differ), ``plan_a_only`` / ``plan_b_only`` (one build returned
    a path, the other none), ``pairs`` (map/mode pairs with a difference), and up to
    ``examples`` differing cases ``(map, mode, case index, start, goal)``."""
    root = Path(root)
    n, pairs, shown = Counter(), 0, []
    for d in discover(root):
        smap = load_map(d, root)
        rel = str(Path(d).resolve().relative_to(root.resolve()))
        for mode in modes:
            astar = mode == "astar"
            ra = a.plan(smap.costs, smap.cases, astar)
            rb = b.plan(smap.costs, smap.cases, astar)
            differs = False
            for i, (x, y) in enumerate(zip(ra, rb)):
                n["runs"] += 1
                pot = x.potential.tobytes() != y.potential.tobytes()
                path = x.path.tobytes() != y.path.tobytes()
                n["potential"] += pot
                n["path"] += path
                n["plan_a_only"] += len(x.path) > 0 and len(y.path) == 0
                n["plan_b_only"] += len(y.path) > 0 and len(x.path) == 0
                if pot or path:
                    differs = True
                    if len(shown) < examples:
                        sx, sy, gx, gy = np.asarray(smap.cases[i]).tolist()
                        shown.append((rel, mode, i, (sx, sy), (gx, gy)))
            pairs += differs
    return {**{k: n[k] for k in ("runs", "potential", "path", "plan_a_only", "plan_b_only")}, "pairs": pairs,
            "examples": shown}
