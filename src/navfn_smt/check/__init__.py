"""Whole-planner checks over symbolic small maps: the properties (judges of one spec run),
the whole run as domain terms, the concolic exploration of every map of a size, and the
runner that checks the sizes in turn."""
