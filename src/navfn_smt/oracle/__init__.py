"""The original in the loop: the user's own Nav2 NavFn, built from source unchanged
(:mod:`.build`) and run as a planner that serves many cases per process (:mod:`.client`)."""
