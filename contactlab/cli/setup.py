"""Commands that set a user up: presets, a template case, the compiled solvers.

* ``contactlab presets [--show NAME]``: list the named cases, or print one;
* ``contactlab init CASE.toml``: write a commented template case to edit;
* ``contactlab warm-up``: compile the numba solvers once (``make demo`` and ``make test``
  run it), so that no timed command pays the compile.
"""

import sys
from pathlib import Path

from contactlab.errors import ParameterError

__all__ = ["TEMPLATE", "add_setup_parsers", "announce_compile"]

TEMPLATE = Path(__file__).resolve().parent.parent / "data" / "template.toml"
"""The commented case ``contactlab init`` writes."""

COMPILE_NOTICE = (
    "compiling solvers once, 1-2 minutes (cached afterwards; 'contactlab warm-up' does it ahead)"
)


def announce_compile(prog):
    """Say on stderr that the compiled solvers are not cached yet and will compile.

    Returns
    -------
    bool
        Whether the notice was printed (the cache was cold).
    """
    from contactlab.batch.warm_up import cache_is_warm

    if cache_is_warm():
        return False
    print(f"{prog}: {COMPILE_NOTICE}", file=sys.stderr, flush=True)
    return True


def _presets(args):
    from contactlab.config import PRESET_DIR, list_presets
    from contactlab.validation import check_choice

    if args.show is None:
        print("\n".join(list_presets()))
        return
    check_choice("--show", args.show, tuple(list_presets()))
    print((PRESET_DIR / f"{args.show}.toml").read_text(encoding="utf-8"), end="")


def _init(args):
    path = Path(args.case)
    if path.suffix != ".toml":
        raise ParameterError(f"{path}: give a file name ending in .toml")
    if path.exists() and not args.force:
        raise ParameterError(f"{path} exists; give --force to overwrite it")
    path.write_text(TEMPLATE.read_text(encoding="utf-8"), encoding="utf-8")
    print(f"wrote {path}: edit it, then run 'contactlab simulate {path}'", file=sys.stderr)


def _warm_up(args):
    from contactlab.batch.warm_up import warm_up

    announce_compile("contactlab")
    print(f"solvers ready in {warm_up():.1f} s (compiled or loaded from the cache)")


def add_setup_parsers(sub):
    """The ``presets``, ``init`` and ``warm-up`` commands."""
    p = sub.add_parser("presets", help="list the named presets (the paper's Figures 5-9)")
    p.add_argument("--show", metavar="NAME", help="print this preset's TOML file")
    p.set_defaults(func=_presets, compiles=False)

    p = sub.add_parser("init", help="write a commented template case CASE.toml to edit")
    p.add_argument("case", metavar="CASE.toml", help="file to write")
    p.add_argument("--force", action="store_true", help="overwrite an existing file")
    p.set_defaults(func=_init, compiles=False)

    p = sub.add_parser(
        "warm-up",
        help="compile the numba solvers once (1-2 min; make demo and make test do it)",
    )
    p.set_defaults(func=_warm_up, compiles=False)
