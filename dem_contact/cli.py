"""Command-line interface: ``dem-contact SUBCOMMAND`` (also ``python -m dem_contact``).

Each subcommand lives in its own module ``dem_contact.commands.<name>`` (the command's name) and states what is
its own: ``HELP`` and ``DESCRIPTION`` (its --help), ``add_options(parser)`` and ``run(args) -> int``
(``commands.common.add_command`` builds its parser); modules are found automatically and listed by ``ORDER``.
Invalid input prints one line on stderr and exits with code 2,
a numerical failure with code 3; any other failure is one line too (code 1), never a traceback.
"""
from __future__ import annotations

import argparse
import importlib
import pkgutil
import sys

from .errors import InputError, NumericalError


def command_modules():
    """The subcommand modules of ``dem_contact.commands``, ordered by their ``ORDER``."""
    from . import commands

    mods = [importlib.import_module(f"{commands.__name__}.{m.name}")
            for m in pkgutil.iter_modules(commands.__path__) if m.name != "common"]
    return sorted(mods, key=lambda m: getattr(m, "ORDER", 100))


class OneLineParser(argparse.ArgumentParser):
    """argparse that reports usage errors as one line and exit code 2."""

    def error(self, message):
        sys.stderr.write(f"{self.prog}: error: {message}\n")
        sys.exit(2)


def build_parser() -> argparse.ArgumentParser:
    from .commands.common import add_command

    parser = OneLineParser(
        prog="dem-contact",
        description="Validated, fast contact laws for spheres: Hertz, Thornton elastic-plastic and "
                    "Mindlin-Deresiewicz tangential traction; oblique sphere-wall impacts, sweeps and "
                    "fits. All quantities in SI units.")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND", parser_class=OneLineParser)
    for mod in command_modules():
        add_command(sub, mod)
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
    except KeyboardInterrupt:
        sys.stderr.write(f"dem-contact {args.command}: interrupted\n")
        return 130
    except OSError as e:
        sys.stderr.write(f"dem-contact {args.command}: error: {e}\n")
        return 2
    except Exception as e:      # a defect of dem_contact: still one line, with what to report
        sys.stderr.write(f"dem-contact {args.command}: internal error ({type(e).__name__}: {e}); please report "
                         f"it with the command line\n")
        return 1


if __name__ == "__main__":
    sys.exit(main())
