// navfn-smt: included by the planner plugin; it uses nothing of it.
#pragma once
