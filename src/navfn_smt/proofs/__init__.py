"""The proof obligations of NavFn's invariants, shipped with the package.

Each module here is a proof file: obligations declared with
:func:`navfn_smt.smt.obligation.obligation`.  ``navfn-smt prove`` checks every one of them
by default (:func:`navfn_smt.smt.runner.default_proof_files`), wherever the package is
installed; ``.bounds.json`` beside them caches the bounds found by search.
"""
