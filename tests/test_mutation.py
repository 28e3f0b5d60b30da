"""The mutation check on the loop's steps: a seeded bug in a push, the end-of-cycle swap or
updateCell's write is caught by the proofs and by the difftest of every backend (issue #39).

The steps are kernels (``kernels.push``, ``kernels.buffer_swap``, ``kernels.cell_update``) that
the reference spec and the JIT run and the buffer obligations state, so one textual change
reaches all of them."""

from navfn_smt.cli import EXAMPLE_SUITE
from navfn_smt.search.mutation import MUTANTS, PACKAGE, BACKENDS, run_mutants
from navfn_smt.smt.runner import default_proof_files

LOOP_MUTANTS = ("push_forgets_pending", "swap_drops_overflow", "write_before_the_test")


def test_every_loop_mutant_is_caught_by_the_proofs_and_by_each_backends_difftest():
    chosen = [m for m in MUTANTS if m.name in LOOP_MUTANTS]
    assert [m.name for m in chosen] == list(LOOP_MUTANTS)
    results = run_mutants(chosen, default_proof_files(), EXAMPLE_SUITE, timeout=20.0, jobs=2)
    for r in results:
        assert not r.errors, (r.name, r.errors)
        want = {"prove", *(f"difftest-{b}" for b in BACKENDS)}
        assert want <= set(r.caught_by), (r.name, r.caught_by, r.details)


def test_every_mutant_changes_one_place_of_the_code_as_it_is():
    """A mutant whose text the code no longer has would stop the whole mutation check."""
    for m in MUTANTS:
        assert (PACKAGE / m.file).read_text().count(m.old) == 1, m.name
