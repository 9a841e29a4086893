"""The ``contactlab`` command line: each command parses, calls one library function, reports."""

import argparse
import json
import sys
from pathlib import Path

import numpy as np

from contactlab.errors import ParameterError

__all__ = ["main"]


def _json_default(obj):
    if isinstance(obj, np.generic):
        return obj.item()
    raise TypeError(f"not JSON serialisable: {type(obj).__name__}")


def _dump(data):
    return json.dumps(data, indent=2, default=_json_default)


def _print_summary(summary):
    for key, value in summary.items():
        if isinstance(value, float):
            print(f"{key:32s} {value:.6g}")
        elif not isinstance(value, dict):
            print(f"{key:32s} {value}")


def _simulate(args):
    from contactlab.config import load_config, load_preset

    if (args.config is None) == (args.preset is None):
        raise ParameterError("give a CONFIG.toml file or --preset NAME (not both)")
    config = load_preset(args.preset) if args.preset else load_config(args.config)
    result = config.simulate()
    if args.plot:
        fig, _ = result.plot()
        fig.savefig(args.plot, dpi=150)
    print(_dump(result.summary()) if args.json else repr(result))


def _demo(args):
    from contactlab.demo import run_demo

    for path in run_demo(Path(args.out)):
        print(f"wrote {path}")


def _presets(args):
    from contactlab.config import list_presets

    print("\n".join(list_presets()))


def _build_parser():
    parser = argparse.ArgumentParser(
        prog="contactlab",
        description="Grain impacts on force sensors: contact laws, an exact two-mass solver "
        "and the Keska et al. (2021) error study. SI units throughout.",
    )
    sub = parser.add_subparsers(dest="command", required=True, metavar="COMMAND")

    p = sub.add_parser("simulate", help="simulate one impact from a TOML file or a preset")
    p.add_argument(
        "config", nargs="?", help="TOML file with [grain] [contact] [sensor] [simulation] tables"
    )
    p.add_argument("--preset", help="a named preset instead (see 'contactlab presets')")
    p.add_argument("--plot", metavar="PNG", help="write the force plot to this file")
    p.add_argument("--json", action="store_true", help="print a JSON summary")
    p.set_defaults(func=_simulate)

    p = sub.add_parser("presets", help="list the named presets (the paper's Figures 5-9)")
    p.set_defaults(func=_presets)

    p = sub.add_parser("demo", help="run the built-in demonstration into a results folder")
    p.add_argument("--out", default="results", help="output folder (default: results)")
    p.set_defaults(func=_demo)
    return parser


def main(argv=None):
    """Entry point of the ``contactlab`` console script."""
    args = _build_parser().parse_args(argv)
    try:
        args.func(args)
    except ParameterError as exc:
        print(f"contactlab: error: {exc}", file=sys.stderr)
        return 2
    return 0


if __name__ == "__main__":
    sys.exit(main())
