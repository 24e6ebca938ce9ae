"""Subcommands of the ``assur`` command line, one module each (see :mod:`synthesis.cli`)."""
