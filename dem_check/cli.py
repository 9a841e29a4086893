"""The ``dem-check`` command line: cross-checks of the reduced model."""

import argparse
import sys

__all__ = ["main"]


def _build_parser():
    parser = argparse.ArgumentParser(
        prog="dem-check",
        description="Cross-check contactlab's reduced grain/sensor model against a rigid-body "
        "engine (pybullet) and against measured oscilloscope traces. SI units throughout.",
    )
    parser.add_subparsers(dest="command", metavar="COMMAND")
    return parser


def main(argv=None):
    """Entry point of the ``dem-check`` console script."""
    parser = _build_parser()
    args = parser.parse_args(argv)
    if args.command is None:
        parser.print_help()
    return 0


if __name__ == "__main__":
    sys.exit(main())
