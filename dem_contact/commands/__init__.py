"""Subcommands of the ``dem-contact`` command line (one module each)."""
