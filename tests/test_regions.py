"""The passable regions and the reach test, stated once in maps/regions.py, against a plain
breadth-first walk of the wave's rule written here (a goal of any cost, passable cells only)."""

from collections import deque

import numpy as np

from navfn_smt.maps.regions import reaches, reaches_all, regions
from navfn_smt.spec.constants import COST_OBS


def _walk(costs, start, goal) -> bool:
    ny, nx = costs.shape
    seen, todo = {goal}, deque([goal])
    while todo:
        x, y = todo.popleft()
        if (x, y) == start:
            return True
        for n in ((x + 1, y), (x - 1, y), (x, y + 1), (x, y - 1)):
            if 0 <= n[0] < nx and 0 <= n[1] < ny and n not in seen and costs[n[1], n[0]] < COST_OBS:
                seen.add(n)
                todo.append(n)
    return False


def test_reaches_is_the_walk_of_the_wave():
    rng = np.random.default_rng(7)
    agree = {True: 0, False: 0}
    for _ in range(150):
        ny, nx = rng.integers(1, 8, size=2)
        costs = np.where(rng.random((ny, nx)) < 0.35, rng.choice([COST_OBS, 255], size=(ny, nx)),
                         rng.integers(0, COST_OBS, size=(ny, nx))).astype(np.uint8)
        cases = np.array([(sx, sy, gx, gy) for sx in range(nx) for sy in range(ny)
                          for gx in range(nx) for gy in range(ny)], np.int64)
        labels = regions(costs)
        assert ((labels > 0) == (costs < COST_OBS)).all()
        got = reaches_all(labels, cases)
        for (sx, sy, gx, gy), g in zip(cases.tolist(), got.tolist()):
            want = _walk(costs, (sx, sy), (gx, gy))
            assert g == want == reaches(labels, (sx, sy), (gx, gy)), (costs, (sx, sy), (gx, gy))
            agree[want] += 1
    assert agree[True] > 1000 and agree[False] > 1000  # both answers exercised


def test_regions_are_numbered_in_row_major_order_of_their_first_cell():
    costs = np.array([[0, 254, 0], [254, 254, 0], [0, 254, 254]], np.uint8)
    assert regions(costs).tolist() == [[1, 0, 2], [0, 0, 2], [3, 0, 0]]
