"""Path extraction: ``NavFn::calcPath(n)`` and ``gradCell``.

Follows the interpolated gradient of the potential from the start cell down to the
goal in steps of ``pathStep`` (0.5), falling back to the lowest of the eight
neighbouring cells near unreached cells or when the path oscillates.  Every exit of
the C++ is an :class:`ExtractionExit`; only ``NEAR_GOAL`` returns a path (C++ returns
its length; every other exit returns 0 and the caller sees no path).
"""

from __future__ import annotations

import enum
from dataclasses import dataclass
from typing import Optional, Protocol

from . import kernels as K
from .constants import COST_NEUTRAL, PATH_STEP
from .numeric import CONCRETE as _D, taken


class ExtractionExit(enum.Enum):
    NEAR_GOAL = "near_goal"  # success: the goal point was appended
    OUT_OF_BOUNDS = "out_of_bounds"  # stc in the first or last row
    HIGH_POTENTIAL = "high_potential"  # grid-following landed on an unreached cell
    ZERO_GRADIENT = "zero_gradient"  # interpolated gradient exactly (0, 0)
    EXHAUSTED = "exhausted"  # n iterations without reaching the goal


# calcPath's exit as a small int (in compiled code, symbolic terms and batch arrays): its
# place in EXIT_CODES, or EXIT_UNDEFINED for the reads outside the potential array that C++
# leaves undefined (the spec raises UndefinedBehaviour)
EXIT_CODES = tuple(ExtractionExit)
EXIT_UNDEFINED = len(EXIT_CODES)


def exit_code(e: ExtractionExit) -> int:
    """The int of an exit (:data:`EXIT_CODES`)."""
    return EXIT_CODES.index(e)


_NEAR_GOAL, _OUT_OF_BOUNDS = exit_code(ExtractionExit.NEAR_GOAL), exit_code(ExtractionExit.OUT_OF_BOUNDS)


def exit_name(code: int) -> str:
    """The exit an int stands for, by its value (``"near_goal"``, ...), or ``"undefined"``."""
    return EXIT_CODES[code].value if 0 <= code < EXIT_UNDEFINED else "undefined"


@dataclass
class Extraction:
    path: list  # [(x, y), ...] float32 values, empty unless exit is NEAR_GOAL
    exit: ExtractionExit
    points_written: int  # npath at the exit (C++ leaves them in pathx/pathy)
    cell: int = -1  # stc at the exit


class Watch(Protocol):
    """What an observer of :func:`calc_path` is told (it may raise to stop the run)."""

    def iteration(self, i: int, stc: int, dx, dy, xs: list, ys: list) -> None:
        """At the start of iteration ``i``: the cell, the offsets and the points so far (the
        lists themselves, which the run keeps appending to)."""

    def fallback(self, i: int, oscillation: bool) -> None:
        """Iteration ``i`` follows the grid (lowest of eight); ``oscillation``: the test fired."""


class UndefinedBehaviour(Exception):
    """The C++ would read outside its arrays here; the spec refuses to guess."""


def ring_of_eight(stc: int, nx: int) -> tuple[int, ...]:
    """The 8 neighbours of cell ``stc`` in the order calcPath's grid fallback reads them (and the
    fix's ``calcPathDescent``): up-left, up, up-right, left, right, down-left, down, down-right."""
    return (stc - nx - 1, stc - nx, stc - nx + 1, stc - 1, stc + 1, stc + nx - 1, stc + nx, stc + nx + 1)


def ring_potentials(pot, ring):
    """The potentials of the 8 cells of ``ring``, as a tuple (which the JIT compiles too)."""
    return (pot[ring[0]], pot[ring[1]], pot[ring[2]], pot[ring[3]], pot[ring[4]], pot[ring[5]], pot[ring[6]],
            pot[ring[7]])


ITERATION_GOES_ON = -1  # iteration_test's code when calcPath writes the point and steps


def off_the_rows(D, stc, nx, ns):
    """calcPath's bounds test ``stc < nx || stc > ns - nx`` (ints): exit ``OUT_OF_BOUNDS``."""
    return D.or_(D.lt(stc, nx), D.lt(ns - nx, stc))


def ring_leaves_the_array(D, stc, nx, ns):
    """``stc - nx - 1 < 0 || stc + nx + 1 >= ns`` (ints): the eight-cell ring of ``stc`` reaches
    outside potarr, a read C++ leaves undefined."""
    return D.or_(D.lt(D.add_int(stc, -nx - 1), 0), D.le(ns, D.add_int(stc, nx + 1)))


def near_goal_test(D, pot, inclusive=False):
    """calcPath's near-goal test (:func:`~.kernels.near_goal`), or with ``inclusive`` a candidate
    fix's ``potarr[...] <= COST_NEUTRAL`` (``spec/candidates.py``)."""
    return D.le(pot, D.f32const(COST_NEUTRAL)) if inclusive else K.near_goal(D, pot)


def iteration_test(D, pot, stc, dx, dy, nx, ns, inclusive=False):
    """calcPath's tests at the top of an iteration, before it writes a point: the exit's
    :func:`exit_code` (``NEAR_GOAL``: the near-goal probe reads a potential below
    COST_NEUTRAL; ``OUT_OF_BOUNDS``: :func:`off_the_rows`), :data:`EXIT_UNDEFINED`
    (:func:`ring_leaves_the_array`) or :data:`ITERATION_GOES_ON`.  ``pot[i]`` is
    ``potarr[i]`` (a list, the JIT's array, or an SMT array in ``proofs/calcpath.py``); cells are
    the domain's ints; ``inclusive``: :func:`near_goal_test`'s."""
    near = K.nearest_cell(D, stc, dx, dy, nx, ns)
    code = D.ite(ring_leaves_the_array(D, stc, nx, ns), EXIT_UNDEFINED, ITERATION_GOES_ON)
    code = D.ite(off_the_rows(D, stc, nx, ns), _OUT_OF_BOUNDS, code)
    return D.ite(near_goal_test(D, pot[near], inclusive), _NEAR_GOAL, code)


def oscillates(D, px, py, qx, qy):
    """calcPath's oscillation test: the point just written equals the one two before (floats)."""
    return D.and_(D.eq(px, qx), D.eq(py, qy))


def grid_wanted(D, centre, ring, oscillation):
    """calcPath's fallback test on the potentials it reads: the path oscillates, or the cell
    (``centre``) or one of its eight (``ring``, in :func:`ring_of_eight`'s order) is unreached."""
    test = D.or_(oscillation, K.unreached(D, centre))
    for p in ring:
        test = D.or_(test, K.unreached(D, p))
    return test


def follows_the_grid(D, pot, stc, nx, oscillation):
    """:func:`grid_wanted` at ``stc``, reading ``pot``."""
    return grid_wanted(D, pot[stc], ring_potentials(pot, ring_of_eight(stc, nx)), oscillation)


def zero_gradient(D, x, y):
    """calcPath's test of the interpolated gradient: exactly ``(0, 0)`` (floats): exit ``ZERO_GRADIENT``."""
    zero = D.f32const(0.0)
    return D.and_(D.eq(x, zero), D.eq(y, zero))


def grid_step(D, pot, stc, nx):
    """calcPath's grid-following step: ``(next cell, dx, dy, stops)``.  The next cell is the
    one :func:`~.kernels.lowest_of_eight` picks (``stc`` when none), the offsets become 0, and
    calcPath stops (``HIGH_POTENTIAL``) when the next cell is unreached."""
    ring = ring_of_eight(stc, nx)
    best = K.lowest_of_eight(D, pot[stc], ring_potentials(pot, ring))
    nxt = stc
    for k, m in enumerate(ring):
        nxt = D.ite(D.eq(best, k), m, nxt)
    zero = D.f32const(0.0)
    return nxt, zero, zero, K.unreached(D, pot[nxt])


def goal_point(D, goal):
    """The point calcPath appends at the near-goal exit: the goal cell, int converted to float."""
    return D.int_to_f32(goal[0]), D.int_to_f32(goal[1])


class Trail:
    """calcPath's writes in the concrete array model: the points (``xs``, ``ys``) and gradCell's
    stored vectors by cell; a :class:`Watch`, when given, is told each iteration and each
    grid-following step.  The JIT's trail holds the same in arrays (``backends/jit_state.py``)."""

    def __init__(self, watch: Optional[Watch] = None):
        self.xs: list = []
        self.ys: list = []
        self.grads: dict = {}
        self.watch = watch

    def append(self, x, y) -> None:
        self.xs.append(x)
        self.ys.append(y)

    @property
    def count(self) -> int:
        return len(self.xs)

    def point(self, i: int) -> tuple:
        return self.xs[i], self.ys[i]

    def knows(self, m: int) -> bool:
        return m in self.grads

    def keep(self, m: int, gx, gy) -> None:
        self.grads[m] = (gx, gy)

    def vector(self, m: int) -> tuple:
        return self.grads[m]

    def iteration(self, i: int, stc: int, dx, dy) -> None:
        if self.watch is not None:
            self.watch.iteration(i, stc, dx, dy, self.xs, self.ys)

    def fallback(self, i: int, oscillation: bool) -> None:
        if self.watch is not None:
            self.watch.fallback(i, oscillation)


# follow's code for the read past potarr of gradCell(ns - nx), undefined in C++ as the ring's
EXIT_GRADIENT_UNDEFINED = EXIT_UNDEFINED + 1
_HIGH_POTENTIAL = exit_code(ExtractionExit.HIGH_POTENTIAL)
_ZERO_GRADIENT = exit_code(ExtractionExit.ZERO_GRADIENT)
_EXHAUSTED = exit_code(ExtractionExit.EXHAUSTED)


def gradient(D, pot, trail, m, nx, ns):
    """``gradCell(m)``: the vector it stored for ``m``, else the kernel's (rows 0 and ny-1 keep the
    zero ``setupNavFn`` wrote), stored.  gradCell tests its cache by the vector being nonzero; a
    vector computed again is the same (calcPath changes no potential), so a trail may store each
    cell's vector once."""
    if not trail.knows(m):
        if m < nx or m >= ns - nx:
            zero = D.f32const(0.0)
            trail.keep(m, zero, zero)
        else:
            gx, gy = K.grad_cell(D, pot[m], pot[m - 1], pot[m + 1], pot[m - nx], pot[m + nx])
            trail.keep(m, gx, gy)
    return trail.vector(m)


def follow(D, pot, nx, ny, start, goal, n, path_step, trail, inclusive=False):
    """The loop of ``calcPath(n)``: follow the gradient of ``pot`` from ``start``, writing the
    points to ``trail`` (``inclusive``: :func:`iteration_test`'s).  Returns (the exit's
    :func:`exit_code`, or :data:`EXIT_UNDEFINED` for a read outside potarr; the cell ``stc`` at
    the exit)."""
    ns = nx * ny
    zero = D.f32const(0.0)
    step = D.f32const(path_step)
    stc = start[1] * nx + start[0]
    dx = zero
    dy = zero
    for i in range(n):
        trail.iteration(i, stc, dx, dy)
        code = iteration_test(D, pot, stc, dx, dy, nx, ns, inclusive)
        if code == _NEAR_GOAL:
            gx, gy = goal_point(D, goal)
            trail.append(gx, gy)
            return _NEAR_GOAL, stc
        if code != ITERATION_GOES_ON:  # OUT_OF_BOUNDS, or the ring of (0, 1), (nx-1, ny-2), (0, ny-1)
            return code, stc
        px, py = K.path_point(D, stc, nx, dx, dy)
        trail.append(px, py)
        oscillation = False
        if trail.count > 2:
            qx, qy = trail.point(-3)
            oscillation = oscillates(D, px, py, qx, qy)
        if taken(D, follows_the_grid(D, pot, stc, nx, oscillation)):
            trail.fallback(i, oscillation)
            stc, dx, dy, stops = grid_step(D, pot, stc, nx)
            if taken(D, stops):
                return _HIGH_POTENTIAL, stc
        else:
            corner = ns - nx - stc  # cell (0, ny-1) passes gradCell's bound test, then potarr[ns] is read
            if corner == 0 or corner == 1 or corner == nx or corner == nx + 1:
                return EXIT_GRADIENT_UNDEFINED, stc
            g0x, g0y = gradient(D, pot, trail, stc, nx, ns)
            g1x, g1y = gradient(D, pot, trail, stc + 1, nx, ns)
            g2x, g2y = gradient(D, pot, trail, stc + nx, nx, ns)
            g3x, g3y = gradient(D, pot, trail, stc + nx + 1, nx, ns)
            x = K.interpolate_gradient(D, dx, dy, g0x, g1x, g2x, g3x)
            y = K.interpolate_gradient(D, dx, dy, g0y, g1y, g2y, g3y)
            if taken(D, zero_gradient(D, x, y)):
                return _ZERO_GRADIENT, stc
            dx, dy, cdx, cdy = K.step_offsets(D, dx, dy, x, y, step)
            stc += cdx + cdy * nx
    return _EXHAUSTED, stc


def calc_path(
    potential: list,
    nx: int,
    ny: int,
    start: tuple[int, int],
    goal: tuple[int, int],
    n: int,
    path_step: float = PATH_STEP,
    watch: Optional[Watch] = None,
    arith=None,
    domain=None,
    inclusive: bool = False,
) -> Extraction:
    """``calcPath(n)`` on a propagated potential (``potential[i]`` is ``potarr[i]``: float32
    values), by :func:`follow` on a :class:`Trail`; ``watch`` is told each iteration and each
    grid-following step; ``arith``: the build's :class:`~.arithmetic.Arithmetic` (default
    x86-64's); ``domain``: the numeric domain to run in instead (its tests go through
    :func:`~.numeric.taken`: the check's encoding runs this function in its concolic domain).
    ``inclusive``: the near-goal test reads ``<=`` (a candidate fix's).  A read outside potarr,
    which C++ leaves undefined, raises :class:`UndefinedBehaviour`."""
    D = domain if domain is not None else _D if arith is None else _D.with_arithmetic(arith)
    trail = Trail(watch)
    code, stc = follow(D, potential, nx, ny, start, goal, n, path_step, trail, inclusive)
    if code == EXIT_UNDEFINED:
        raise UndefinedBehaviour(f"calcPath reads outside the potential array around cell {stc}")
    if code == EXIT_GRADIENT_UNDEFINED:
        raise UndefinedBehaviour(f"gradCell reads past the potential array at cell {nx * ny - nx}")
    path = list(zip(trail.xs, trail.ys)) if code == _NEAR_GOAL else []
    return Extraction(path, EXIT_CODES[code], trail.count, stc)
