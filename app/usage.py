"""The one error type of the command line: a bad argument, reported in one line with exit status 2."""


class UsageError(Exception):
    """A bad command-line argument; the message names the argument."""
