// navfn-smt: included by the static layer for map frames other than the global frame, which the
// oracle never gives it.
#pragma once
