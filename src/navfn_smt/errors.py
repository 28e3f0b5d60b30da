"""Errors a user can cause; the command line prints them as one line and exits non-zero."""


class NavfnInputError(Exception):
    """Bad input: a malformed or missing map, a wrong size, a cell off the map, ..."""
