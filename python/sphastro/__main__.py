"""The ``sphastro`` command: ``sphastro render ...`` (see ``sphastro render --help``)."""

import argparse
import sys

from . import render


def main(argv=None):
    parser = argparse.ArgumentParser(prog="sphastro", description="SPH-ASTRO's Python tools")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND")
    sub.required = True
    commands = {"render": render.add_parser(sub)}
    args = parser.parse_args(argv)
    return args.func(args, commands[args.command])


if __name__ == "__main__":
    sys.exit(main())
