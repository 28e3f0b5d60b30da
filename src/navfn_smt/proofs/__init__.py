"""The proof obligations of NavFn's invariants, shipped with the package, and the paper's
predicates they establish.

Each module here is a proof file: obligations declared with
:func:`navfn_smt.smt.obligation.obligation` for one of the predicates below.
``navfn-smt prove`` checks every one of them by default
(:func:`navfn_smt.smt.runner.default_proof_files`), wherever the package is installed;
``.bounds.json`` beside them caches the bounds found by search.

Each predicate is a chain of obligations (:class:`navfn_smt.smt.chains.Predicate`): the
base case, then the lemmas of the inductive step, in order; ``Owner.name`` borrows a link
from another predicate's chain.  :func:`navfn_smt.smt.chains.check_chains` holds the chains
and the declarations consistent, and the proof run derives each predicate's status.
"""

from ..smt.chains import Condition, Predicate

# The run-time conditions: hypotheses of the claims below, each stated once, shown in a status as
# "conditional (NAME)" and in the fix's guarantee (spec/fixes.py GUARANTEE) where it rests on them
BELOW_2_30 = Condition(
    "potentials below 2^30",
    "every finite potential stays below 2**30 in float32: the largest finite potential of the run, which the "
    "spec reports; argued to hold on every map of fewer than 2**22 = 4,194,304 passable cells, every 2000 x 2000 "
    "map (FallbackPath's bound, a trusted step), and a longer way can exceed it", float32=True)
PUSH_KEY_BELOW_2_31 = Condition(
    "push keys below 2^31",
    "a changed cell's push key (its potential, plus A*'s heuristic) below 2**31, so that its (int) is the "
    "truncation: true when the potentials are below 2**30 and the heuristic below 2**30 (maps under 2**22 cells "
    "a side)")
PASSABLE_COSTS = Condition(
    "costs as setCostmap makes them",
    "every passable cell's cost in [COST_NEUTRAL, COST_OBS): what setCostmap's translation gives for every one "
    "of the 256 costmap values (tests/test_chains.py enumerates them on the spec's setCostmap, which difftest "
    "holds to the C++'s); a caller that writes costarr itself must keep it")
NO_DROP = Condition(
    "no push dropped",
    "no push dropped for want of room (PRIORITYBUFSIZE): the spec counts the drops (PlanResult.dropped), the C++ "
    "does not report them; overflow maps break it (docs/overflow.md); argued to hold on every map whose goal "
    "component has at most PRIORITYBUFSIZE = 10,000 cells (every 100 x 100 map): a push is of a cell in no buffer "
    "it may enter, and each buffer holds distinct cells of the component (BuffersInductive), so fewer than the "
    "component's count; tested with buffers the component's size (tests/test_invariants_runtime.py)")
CYCLES_SUFFICE = Condition(
    "the further call's nx*ny cycles suffice",
    "the wave empties its buffers or reaches the start within the further call's cap of nx*ny cycles: each cycle "
    "updates at least one buffered cell, but a cell can be buffered more than once, so nx*ny cycles are not shown "
    "to suffice; the bounded checks explore it on every map of their sizes, and benchmarks/further_call_cycles.py "
    "samples generated maps (tested, not proved: on 3,575 runs of 20x20, 60x60 and 120x120 maps of every category "
    "the further call used at most 42% of its cap, and never left a joined start unreached)")
DESCENT_FITS = Condition(
    "the descent fits calcPath's budget",
    "the descent's walk fits in calcPath's budget of n points (4 * nx, or max_cycles_factor times the larger side "
    "on Rolling and Lyrical): a longer descent fails, as the gradient does")
GRADIENT_NOT_TINY = Condition(
    "the interpolated gradient is zero or not tiny",
    "the interpolated gradient is exactly zero (calcPath then fails) or has a component of at least 2**-100: a "
    "precondition of step_keeps_offset_in_unit_box and of the step bound, refuted for one step "
    "(interpolated_gradient_is_zero_or_not_tiny: a subnormal offset beside a cell with a zero gradient); whether "
    "calcPath's own offsets get that small is not known", float32=True)

PositionSafe = Predicate(
    "PositionSafe",
    statement="A cell with a finite potential is no obstacle: potarr[n] < POT_HIGH implies "
              "costarr[n] < COST_OBS, the goal excepted.",
    applies="propagation: the potential array after setupNavFn, initCost and every updateCell / "
            "updateCellAstar; the paper's PositionSafe",
    lemmas=("update_keeps_obstacles_unreached",),
    rests_on=("PositionSafeAndProgressInductive",),  # the base case, and the step at every cell
)

Monotone = Predicate(
    "Monotone",
    statement="Potentials only go down, and the goal keeps potential 0.",
    applies="propagation: every updateCell / updateCellAstar; Progress relies on it (a lower neighbour "
            "stays lower)",
    lemmas=("update_never_raises", "goal_stays_zero"),
    rests_on=("PositionSafeAndProgressInductive",),  # the base case: the goal's 0, POT_HIGH elsewhere
)

Progress = Predicate(
    "Progress",
    statement="A reached cell other than the goal has a 4-neighbour with a strictly lower potential.",
    applies="propagation, for path extraction, which descends the potential; the paper's Progress",
    lemmas=("update_keeps_a_lower_neighbour", "Monotone.update_never_raises"),
    # the base case, and the step at every cell with all four neighbours read as the kernel reads them
    rests_on=("PositionSafeAndProgressInductive",),
    conditions=(PASSABLE_COSTS,),  # the precondition of update_keeps_a_lower_neighbour
)

ObstacleFreeQueue = Predicate(
    "ObstacleFreeQueue",
    statement="The priority buffers never hold an obstacle or a cell off the map, and a push never writes "
              "past a buffer's capacity.",
    applies="propagation: the three priority buffers (current, next, overflow) and every push_cur / "
            "push_next / push_over",
    lemmas=("push_admits_only_passable_cells_on_the_map",),
    # the base case (setup empties the buffers, initCost pushes through the guard) and the step at
    # every push, clearing loop and swap: every buffered cell passable and on the map, every fill
    # within its capacity
    rests_on=("BuffersInductive",),
)

PendingMatchesBuffers = Predicate(
    "PendingMatchesBuffers",
    statement="A cell's pending flag is set exactly when the cell is in the buffers, and then once: between "
              "cycles (B) once in current + overflow with next empty, during a cycle (P) once in next + "
              "overflow. So no cell is twice in the buffers, which never hold more cells than the map.",
    applies="propagation: the pending array and the buffers, for every map size and buffer capacity: "
            "BuffersInductive's invariant (on the spec's own run over arrays) read at one cell",
    base=("BuffersInductive.setup_puts_each_pending_cell_in_one_slot",),
    lemmas=("BuffersInductive.a_cycle_starts_with_every_flag_to_clear",
            "BuffersInductive.clearing_a_flag_keeps_the_clearing_invariant",
            "BuffersInductive.cleared_flags_give_the_cycle_invariant",
            "BuffersInductive.update_keeps_each_pending_cell_in_one_slot",
            "BuffersInductive.astar_update_keeps_each_pending_cell_in_one_slot",
            "BuffersInductive.swap_keeps_each_pending_cell_in_one_slot"),
)

NoPathWithoutFinitePotential = Predicate(
    "NoPathWithoutFinitePotential",
    statement="From a start cell without a finite potential, calcPath returns no path.",
    applies="path extraction (calcPath) at an unreached start: its first iteration",
    base=("unreached_cell_stays_put",),
    lemmas=("calc_path_stops_at_once_at_an_unreached_start",),
)

Gradient = Predicate(
    "Gradient",
    statement="gradCell stores a unit vector (squared length within 2**-20 of 1) or the zero vector, on "
              "every potential NavFn produces.",
    applies="path extraction: the gradient gradCell caches per cell, which calcPath interpolates; in float32 only "
            "(over the reals differences of potentials can be arbitrarily small, and no obligation normalises an "
            "arbitrary real vector: grad_is_unit_or_zero_any_float only one along an axis)",
    # potentials 0 or at least 1/2: the goal's 0 and POT_HIGH from setup, then every update (as Monotone)
    lemmas=("update_keeps_potentials_zero_or_at_least_half", "grad_differences_are_not_tiny",
            "grad_is_unit_or_zero"),
    limits=("grad_is_unit_or_zero_any_float",),
    trusted=("grad_is_unit_or_zero is decided by its split (navfn-smt split): nine sign cases whose cover is "
             "proved, the zero vector bit-precisely, every other part in the standard rounding-error model "
             "(IEEE 754 rounds each operation to within half an ulp, relative, when the result is normal, which "
             "the same queries prove); not machine-checked: no solver decides those parts bit-precisely",),
)

FinitePotentialPath = Predicate(
    "FinitePotentialPath",
    statement="Every point calcPath emits lies within 1/2 (each axis, ends included) of a cell with a finite "
              "potential.",
    applies="path extraction (calcPath), by induction over its iterations, for every map size up to the "
            "coordinate bounds of the links; the paper's FinitePotentialPath",
    base=("ValidPath.first_point_is_the_start", "NoPathWithoutFinitePotential.unreached_cell_stays_put"),
    lemmas=("Gradient.update_keeps_potentials_zero_or_at_least_half", "Gradient.grad_differences_are_not_tiny",
            "stored_gradient_is_bounded", "interpolated_gradient_is_bounded",
            "step_keeps_offset_in_unit_box", "step_along_an_axis_moves_at_most_half",
            "half_step_keeps_the_point_near_the_cell", "near_goal_probe_reads_a_neighbour",
            "grid_step_goes_on_only_at_a_reached_cell_with_offsets_zero", "gradient_step_runs_only_among_nine_reached_cells",
            "near_goal_exit_ends_at_the_goal_cell"),
    limits=("step_keeps_offset_in_unit_box_any_gradient",),
    whole=("next_point_stays_near_the_cell",),
    assumes=("interpolated_gradient_is_zero_or_not_tiny",),
    trusted=("rounding is monotone (IEEE 754: each operation rounds its exact result, and rounding to nearest is "
             "monotone), so for hypotf(x, y) >= max(|x|, 2**-100) the move |x * (0.5f / hypotf)| is at most the "
             "move along the axis, |x * (0.5f / |x|)| (step_along_an_axis_moves_at_most_half), or for "
             "|x| < 2**-100 at most |x| * 2**99 <= 1/2; with half_step_keeps_the_point_near_the_cell this gives "
             "next_point_stays_near_the_cell; not machine-checked: the monotonicity of float32 division and "
             "multiplication in two free operands is left undecided by bitwuzla, cvc5 and z3 at 300 s",),
    conditions=(GRADIENT_NOT_TINY,),
)

ValidPath = Predicate(
    "ValidPath",
    statement="The path calcPath returns begins at the start cell, and every point of it lies within 1/2 of "
              "a cell that is no obstacle (the goal excepted, where the path ends).",
    applies="path extraction (calcPath): the path NavFn hands to Nav2; the paper's ValidPath",
    base=("first_point_is_the_start",),
    lemmas=("point_near_a_reached_cell_is_near_a_passable_cell_or_the_goal",),
    rests_on=("FinitePotentialPath", "PositionSafeAndProgressInductive"),
)

DescentPath = Predicate(
    "DescentPath",
    statement="From a start with a finite potential, the fix's descent (calcPathDescent(n)) returns a path when "
              "the walk fits in calcPath's budget of n points: the centres of reached cells, each one of the 8 "
              "neighbours of the one before and strictly lower, ending at the goal; no point is an obstacle but "
              "the goal. Needs every potential below 2**30.",
    applies="the fix: calcPath's fallback calcPathDescent (spec/fix.py: descend), by induction over its steps, "
            "for every map size, within calcPath's budget n",
    lemmas=("descent_step_goes_strictly_lower", "Progress.update_keeps_a_lower_neighbour",
            "Monotone.update_never_raises"),
    rests_on=("DescentInductive", "Progress", "PositionSafe"),
    trusted=("the count: the walk's cells are distinct (DescentInductive: each is strictly below every cell "
             "before it) and reached, so passable or the goal, and calcPath's budget n holds them all on a map "
             "with at most n - 1 passable cells besides the goal (every map of up to 6 interior cells, whose "
             "n = 4*nx is at least 12); a counting (pigeonhole) step, which the quantifier-free obligations "
             "over arrays cannot state",),
    conditions=(BELOW_2_30, DESCENT_FITS),
)

ConnectedStartReached = Predicate(
    "ConnectedStartReached",
    statement="With the fix's propagation, a start joined to the goal by a 4-connected chain of passable cells "
              "gets a finite potential, when no push is dropped for want of room, every potential stays below "
              "2**30 and the wave empties its buffers within the fix's cap (nx*ny more cycles).",
    applies="the fix: calcNavFnAstar / calcNavFnDijkstra call propNavFn* once more, for nx*ny cycles, when the "
            "start is unreached and a buffer holds cells (spec/planner.py: calc_navfn with spec/fix.py's further call), for every map size",
    lemmas=("update_wants_an_unreached_neighbour", "unreached_cell_beside_a_reached_one_gets_reached",
            "update_lowers_when_it_changes", "Monotone.update_never_raises",
            "propagation_stops_only_at_a_reached_start_with_empty_buffers_or_its_cycles_spent"),
    # the induction over the run: the frontier (FrontierInductive) and, under it, the buffers
    rests_on=("PendingMatchesBuffers", "FrontierInductive"),
    trusted=("the component is the least set of cells holding the goal's passable 4-neighbours and closed under "
             "passable 4-neighbours; when the buffers are empty and no push was dropped, the reached cells below "
             "the bound hold the goal (potential 0) and are so closed "
             "(empty_buffers_without_a_drop_leave_no_reached_cell_beside_an_unreached_one), so they include the "
             "component and the start, in it, is reached (an induction over the chain of cells from the goal to the "
             "start, which the quantifier-free obligations over arrays cannot state)",),
    conditions=(NO_DROP, BELOW_2_30, CYCLES_SUFFICE),
)

FallbackPath = Predicate(
    "FallbackPath",
    statement="On a map whose interior is at most two cells wide or at most two cells tall, calcPath returns a "
              "path from every start with a finite potential when the map has at most 4*nx passable cells: every "
              "step is the grid-following fallback, which moves to a strictly lower reached neighbour until a cell "
              "below COST_NEUTRAL. Needs every potential below 2**30.",
    applies="path extraction (calcPath, NavFn as shipped), by induction over its iterations, on every map at most "
            "two interior cells wide or tall (any length up to 4*nx passable cells); navfn-smt check decides "
            "complete on such sizes by it",
    lemmas=("update_keeps_a_neighbour_below_its_floor", "fallback_step_moves_below_the_floor",
            "fallback_step_goes_strictly_lower", "update_raises_at_most_twice_its_cost",
            "update_raises_at_most_256_above_its_lowest_neighbour",
            "Monotone.update_never_raises", "short_map_follows_the_grid_at_every_passable_cell",
            "thin_map_follows_the_grid_at_every_passable_cell", "bound_tests_pass_at_a_reached_cell",
            "FinitePotentialPath.grid_step_goes_on_only_at_a_reached_cell_with_offsets_zero",
            "setup_gives_every_reached_cell_a_neighbour_below_its_floor",
            "update_keeps_a_neighbour_below_the_floor_at_the_updated_cell",
            "update_keeps_a_neighbour_below_the_floor_at_every_other_cell",
            "the_steps_around_the_updates_keep_a_neighbour_below_the_floor"),
    rests_on=("Progress", "PositionSafeAndProgressInductive"),
    trusted=("potentials strictly fall along the walk (each cell but the goal has a 4-neighbour below its "
             "potential's truncation: setup_gives_every_reached_cell_a_neighbour_below_its_floor and the two "
             "update_keeps_a_neighbour_below_the_floor_* obligations, where the fallback moves: "
             "fallback_step_moves_below_the_floor), so no cell repeats: from a start among k passable cells the "
             "walk meets a cell below COST_NEUTRAL (the goal, potential 0, at the latest) within k - 1 moves, "
             "inside calcPath's 4*nx iterations when k <= 4*nx; a counting (pigeonhole) step, "
             "which the quantifier-free obligations over arrays cannot state",
             "the bound: the i-th cell to become reached (the goal first, potential 0) gets at most 256 above "
             "its lowest neighbour, reached, while that one is below 2**30 "
             "(update_raises_at_most_256_above_its_lowest_neighbour) and only falls after, so every finite "
             "potential is at most 256 * (k - 1), k the number of cells reached (at most the passable ones and "
             "the goal): below 2**30 on every map of fewer than 2**22 = 4,194,304 passable cells, every Nav2 map "
             "of 2000 x 2000 cells (the planner benchmark's); an induction over the order in which cells become "
             "reached, counting them, which the quantifier-free obligations over arrays cannot state",),
)

ReachedWithinComponent = Predicate(
    "ReachedWithinComponent",
    statement="Only the goal's component (the goal and the passable cells 4-connected to a passable neighbour of "
              "it) is ever pushed, updated or reached: a start outside it keeps POT_HIGH, and a cost outside it "
              "is read only by a push guard that fails whatever the cell is.",
    applies="propagation, for every map size; the bounded checks (navfn-smt check) decide a start outside the "
            "component without exploring, and explore one layout of those that differ only outside it",
    lemmas=("update_beside_no_reached_cell_stays_unreached", "PositionSafe.update_keeps_obstacles_unreached",
            "ObstacleFreeQueue.push_admits_only_passable_cells_on_the_map"),
    # the base case and the step: only cells of the component are ever buffered, updated (a cell of the
    # current buffer) or reached
    rests_on=("BuffersInductive", "ReachedAndBufferedInductive"),
    trusted=("calcPath and the fix's descent read potentials and gradients, never costs, and a cell outside the "
             "component has POT_HIGH in every layout (ReachedAndBufferedInductive); the first half is read off "
             "the code (the iterations of spec/extraction.py and spec/fix.py take a reader of potentials only), not "
             "checked by a solver",
             "tests/test_check_reductions.py runs every layout of the small sizes concretely: a layout and its "
             "representative give the same potentials, exit and path; tested, not proved: the reduction is about "
             "every layout at once, which no obligation states",),
)

QueuedStartReached = Predicate(
    "QueuedStartReached",
    statement="A start in the current buffer of a cycle that runs gets a finite potential in that cycle; so does "
              "a start pushed to the next buffer in a cycle that is not the last of its propNavFn* call (it is in "
              "the current buffer of the next cycle). Needs costs of at least COST_NEUTRAL and every potential "
              "below 2**30.",
    applies="propagation, for every map size; the bounded checks (navfn-smt check) stop flipping a control path's "
            "branches once it has queued the start so, when start-reached is explored alone: every path sharing "
            "that prefix reaches the start",
    base=("queued_start_is_beside_a_reached_cell_as_the_updates_start_and_reached_when_they_end",),
    lemmas=("update_of_any_slot_keeps_a_passed_queued_start_reached", "queued_cell_gets_reached",
            "Monotone.update_never_raises", "next_buffer_becomes_current_and_its_cycle_runs"),
    # a buffered cell has a reached 4-neighbour (below the bound: the run-time condition below); the
    # buffer invariant at the start's slot and the updated cell's; the cycle's loop over its current
    # buffer's slots is the spec's, cut at its invariant (smt/program.py)
    rests_on=("ReachedAndBufferedInductive", "BuffersInductive"),
    trusted=("the queueing is a fact of the control path up to the push (or the cycle's start): every run with "
             "the same branches that far queues the start the same way; argued: the soundness of symbolic "
             "execution (check/concolic.py), not an obligation",
             "tests/test_check_bounded.py: on every saved map whose connected start stays unreached the run never "
             "queues the start so, and on seeded maps of six sizes every run that does reaches it (the spec's "
             "run); tested, not proved",),
    conditions=(BELOW_2_30,),
)

PositionSafeAndProgressInductive = Predicate(
    "PositionSafeAndProgressInductive",
    statement="PositionSafe and Progress, with valid potentials and the goal's 0, hold of the whole potential "
              "array after setup and are kept by every step of propagation, on a map of any size.",
    applies="propagation, stated over arrays (proofs/induction.py): the spec's setupNavFn, initCost and "
            "propNavFn* run over SMT arrays, their loops cut at the invariant (smt/program.py), every segment "
            "of the run machine-checked",
    base=("setup_and_init_cost_establish_the_invariant",),
    lemmas=("the_steps_around_the_updates_keep_the_invariant", "update_keeps_the_invariant_at_the_updated_cell",
            "update_keeps_the_invariant_at_every_other_cell"),
    conditions=(BELOW_2_30,),
)

BuffersInductive = Predicate(
    "BuffersInductive",
    statement="Each pending cell is in exactly one buffer slot (between cycles of the current or the overflow "
              "buffer, during a cycle of the next or the overflow one), no slot of a buffer repeats a cell, and "
              "every buffered cell is a passable cell of the goal's component on the map: true after setup and "
              "kept by every step of propagation, on a map of any size.",
    applies="propagation, stated over arrays with ghost positions (proofs/buffers.py): the spec's setupNavFn, "
            "initCost and propNavFn* run over SMT arrays, their loops (the cycles, the clearing of the flags, the "
            "updates with their pushes) cut at their invariants (smt/program.py), every segment of the run "
            "machine-checked, the component's closure assumed at the cells each segment touches",
    base=("setup_puts_each_pending_cell_in_one_slot",),
    lemmas=("a_cycle_starts_with_every_flag_to_clear", "clearing_a_flag_keeps_the_clearing_invariant",
            "cleared_flags_give_the_cycle_invariant", "update_keeps_each_pending_cell_in_one_slot",
            "astar_update_keeps_each_pending_cell_in_one_slot", "swap_keeps_each_pending_cell_in_one_slot"),
)

ReachedAndBufferedInductive = Predicate(
    "ReachedAndBufferedInductive",
    statement="A reached cell is the goal or a cell of the goal's component, and a buffered cell has a reached "
              "4-neighbour: true after setup and kept by every step of propagation, on a map of any size.",
    applies="propagation, stated over arrays beside the buffers (proofs/buffers.py): the loop induction of "
            "ReachedWithinComponent's and QueuedStartReached's facts about the run machine-checked (issue #39)",
    base=("setup_reaches_the_goal_alone_and_buffers_its_neighbours",),
    lemmas=("the_steps_around_the_updates_keep_every_buffered_cell_beside_a_reached_one",
            "update_and_its_pushes_reach_only_cells_of_the_component"),
    # the buffer invariant (an updated cell is a buffered cell of the component) and valid potentials
    rests_on=("BuffersInductive", "PositionSafeAndProgressInductive"),
)

FrontierInductive = Predicate(
    "FrontierInductive",
    statement="Every unreached passable neighbour on the map of a reached cell below 2**30 is pending (or, while "
              "a cycle's updates run, waits in the current buffer), or some push was dropped for want of room: "
              "true after setup and kept by every step, on a map of any size; so when propagation ends with its "
              "buffers empty and no push dropped, the reached cells below 2**30 are closed under passable "
              "4-neighbours.",
    applies="propagation, stated over arrays beside the buffers (proofs/frontier.py), with a ghost flag for a "
            "dropped push: the loop induction behind ConnectedStartReached machine-checked (issue #39)",
    base=("setup_leaves_no_unreached_neighbour_unbuffered",),
    lemmas=("the_steps_around_the_updates_keep_the_frontier", "update_and_its_pushes_keep_the_frontier",
            "astar_heuristic_is_not_negative",
            "empty_buffers_without_a_drop_leave_no_reached_cell_beside_an_unreached_one"),
    rests_on=("BuffersInductive", "PositionSafeAndProgressInductive"),
    conditions=(PUSH_KEY_BELOW_2_31, PASSABLE_COSTS),
)

DescentInductive = Predicate(
    "DescentInductive",
    statement="From a reached start, every iteration of the fix's descent stops at the goal (with the path) or at "
              "its budget, or writes the point of a cell that is no obstacle and moves to a reached 8-neighbour "
              "strictly lower than it and than no cell visited before: never OUT_OF_BOUNDS, never ZERO_GRADIENT, "
              "on a map of any size whose potentials satisfy PositionSafeAndProgressInductive.",
    applies="the fix: calcPathDescent's loop (spec/fix.py: descent_iteration, the iteration descend runs), "
            "stated over arrays with a ghost set of visited cells (proofs/descent.py): the descent's loop "
            "invariant machine-checked (issue #39)",
    base=("descent_begins_at_a_reached_start",),
    lemmas=("descent_iteration_moves_strictly_down_or_stops_at_the_goal_or_the_budget",),
    rests_on=("PositionSafeAndProgressInductive",),
    conditions=(BELOW_2_30,),
)

# in the order the invariants page lists them: propagation, then path extraction, then the fix
PREDICATES = (PositionSafe, Monotone, Progress, ObstacleFreeQueue, PendingMatchesBuffers,
              NoPathWithoutFinitePotential, Gradient, FinitePotentialPath, ValidPath, FallbackPath, DescentPath,
              ConnectedStartReached, ReachedWithinComponent, QueuedStartReached, PositionSafeAndProgressInductive,
              BuffersInductive, ReachedAndBufferedInductive, FrontierInductive,
              DescentInductive)
