// navfn-smt: the white-box trace hook of the traced oracle build.  The builder inserts
// NAVFN_SMT_CYCLE(curP, curPe); before each anchor line of a propagation loop in a copy of
// navfn.cpp (the sources themselves are never changed); the driver owns the recorder.
#ifndef NAVFN_SMT_TRACE_HOOK_HPP_
#define NAVFN_SMT_TRACE_HOOK_HPP_

void navfn_smt_cycle(const int * cells, int n);
#define NAVFN_SMT_CYCLE(cells, n) navfn_smt_cycle((cells), (n))

#endif  // NAVFN_SMT_TRACE_HOOK_HPP_
