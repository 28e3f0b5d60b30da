"""Whole-planner verification over symbolic small maps (in progress: the encoding of propagation)."""
