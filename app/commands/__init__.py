"""Subcommands of ``python -m app``: each answers headless, prints its result and exits."""
