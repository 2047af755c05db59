"""Command-line interface: ``dem-contact SUBCOMMAND`` (also ``python -m dem_contact``).

Each subcommand lives in ``dem_contact.commands.<name>`` with ``add_parser(subparsers)`` and
``run(args) -> int``. Invalid input prints one line on stderr and exits with code 2.
"""
from __future__ import annotations

import argparse
import importlib
import sys

from .errors import InputError, NumericalError

#: Subcommand modules, in the order ``--help`` lists them.
COMMANDS = ["impact"]


class OneLineParser(argparse.ArgumentParser):
    """argparse that reports usage errors as one line and exit code 2."""

    def error(self, message):
        sys.stderr.write(f"{self.prog}: error: {message}\n")
        sys.exit(2)


def build_parser() -> argparse.ArgumentParser:
    parser = OneLineParser(
        prog="dem-contact",
        description="Validated, fast contact laws for spheres: Hertz, Thornton elastic-plastic and "
                    "Mindlin-Deresiewicz tangential traction; oblique sphere-wall impacts, sweeps and "
                    "fits. All quantities in SI units.")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND", parser_class=OneLineParser)
    for name in COMMANDS:
        importlib.import_module(f".commands.{name}", __package__).add_parser(sub)
    return parser


def main(argv=None) -> int:
    parser = build_parser()
    args = parser.parse_args(argv)
    if args.command is None:
        parser.print_help()
        return 0
    try:
        return int(args.run(args) or 0)
    except InputError as e:
        sys.stderr.write(f"dem-contact {args.command}: error: {e}\n")
        return 2
    except NumericalError as e:
        sys.stderr.write(f"dem-contact {args.command}: numerical failure: {e}\n")
        return 3


if __name__ == "__main__":
    sys.exit(main())
