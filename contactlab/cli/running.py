"""How both command lines run a command: bad input and warnings as one line on stderr.

* Bad input (:class:`~contactlab.errors.ParameterError`, a trace file that cannot be
  read, a missing file) ends with ``PROG: error: MESSAGE`` and exit code 2, never a
  traceback.
* A warning is one line, ``PROG: warning: MESSAGE``, printed once, without the source
  line Python prints; ``--strict`` turns the toolkit's warnings (a value outside what real grains
  and sensors span, a window too short, ...) into errors (exit code 2).
* Messages speak in flags: a Python parameter name the library used (``damping_ratio``,
  ``window=``) is shown as the command's flag (``--damping-ratio``, ``--window``).
* Output piped into ``head`` ends quietly when ``head`` stops reading.
* Negative numbers are values, not flags: ``--baseline -1e-4 -5e-5``.
* A command that may compile the numba solvers says so first when their cache is cold
  (:func:`contactlab.cli.setup.announce_compile`); commands that never do set
  ``compiles=False``.
"""

import argparse
import os
import re
import sys
import warnings

from contactlab.cli.setup import announce_compile
from contactlab.errors import ContactlabWarning, ParameterError, TraceFormatError

__all__ = [
    "INPUT_ERRORS",
    "Parser",
    "add_crosstalk_flag",
    "add_outputs",
    "add_strict",
    "run",
    "same_named",
]

INPUT_ERRORS = (ParameterError, TraceFormatError, OSError, ImportError)
"""What bad input raises: a parameter, a file's content, a missing file, an extra not
installed. Anything else is a bug and keeps its traceback."""

STRICT_HELP = "treat warnings (a value outside what real grains and sensors span...) as errors"

ALIASES = {"baseline_window": "--baseline"}
"""Library parameter names whose flag has another name."""


class Parser(argparse.ArgumentParser):
    """An argument parser that reads ``-1e-4`` as a number, not as an unknown flag.

    argparse takes ``-1e-4`` for an option because its number pattern has no exponent;
    no flag of these commands starts with a digit, so every such word is a value.
    """

    def __init__(self, *args, **kwargs):
        super().__init__(*args, **kwargs)
        self._negative_number_matcher = re.compile(r"^-(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?$")


def add_outputs(parser, func, plot=None, json="print a JSON summary"):
    """A command's last options and its function: ``--plot PNG`` where ``plot`` says what
    the figure shows, then ``--json`` with its help ``json``."""
    if plot is not None:
        parser.add_argument("--plot", metavar="PNG", help=plot)
    parser.add_argument("--json", action="store_true", help=json)
    parser.set_defaults(func=func)


def add_strict(parser):
    """``--strict`` on the main parser and on every command (``prog --strict cmd`` or
    ``prog cmd --strict``)."""
    parser.add_argument("--strict", action="store_true", help=STRICT_HELP)
    for action in parser._actions:
        if isinstance(action, argparse._SubParsersAction):
            for sub in action.choices.values():
                sub.add_argument(
                    "--strict", action="store_true", default=argparse.SUPPRESS, help=STRICT_HELP
                )


def _flags(parser, command):
    """``{python name: flag}`` for the options of ``command``."""
    flags = {}
    for action in parser._actions:
        if isinstance(action, argparse._SubParsersAction) and command in action.choices:
            for option in action.choices[command]._actions:
                longs = [s for s in option.option_strings if s.startswith("--")]
                if longs:
                    flags[option.dest] = longs[0]
    flags.update({name: flag for name, flag in ALIASES.items() if flag in flags.values()})
    return flags


def in_flags(message, flags):
    """``message`` with the Python names of ``flags`` written as the flags.

    Parameters
    ----------
    message : str
        A library message, e.g. ``"give window= after the pulse"``.
    flags : dict
        ``{python name: flag}``.

    Returns
    -------
    str
        E.g. ``"give --window after the pulse"``: ``name=`` becomes the flag wherever it
        appears, a bare name only when it holds an underscore (``damping_ratio``), so that
        ordinary words are left alone.
    """
    for name in sorted(flags, key=len, reverse=True):
        flag = flags[name]
        message = re.sub(rf"(?<![\w-]){re.escape(name)}=", f"{flag} ", message)
        if "_" in name:
            message = re.sub(rf"(?<![\w-]){re.escape(name)}\b", flag, message)
    return re.sub(r" +([,;.)])", r"\1", re.sub(r"  +", " ", message))


def _quiet_broken_pipe():
    """The reader of stdout has gone (``| head``): send the rest nowhere, quietly."""
    devnull = os.open(os.devnull, os.O_WRONLY)
    os.dup2(devnull, sys.stdout.fileno())
    return 1


def run(prog, parser, argv=None):
    """Parse ``argv``, run the command, report bad input and warnings as lines on stderr.

    Parameters
    ----------
    prog : str
        The program's name in messages.
    parser : argparse.ArgumentParser
        Its parser; each command sets ``func(args) -> int or None``.
    argv : list of str, optional
        Arguments (default: ``sys.argv[1:]``).

    Returns
    -------
    int
        The command's exit code (None counts as 0), 2 for bad input or a warning under
        ``--strict``, 1 when stdout was closed early.
    """
    args = parser.parse_args(argv)
    flags = _flags(parser, getattr(args, "command", None))

    shown = set()  # once each: code that catches warnings resets Python's own registry

    def one_line(message, category, filename, lineno, file=None, line=None):
        kind = "warning" if issubclass(category, ContactlabWarning) else category.__name__
        text = f"{prog}: {kind}: {in_flags(str(message), flags)}"
        if text not in shown:
            shown.add(text)
            print(text, file=sys.stderr)

    with warnings.catch_warnings():
        warnings.simplefilter("default")
        if args.strict:
            warnings.simplefilter("error", ContactlabWarning)
        warnings.showwarning = one_line
        if getattr(args, "compiles", True):
            announce_compile(prog)
        try:
            code = args.func(args)
            sys.stdout.flush()
        except BrokenPipeError:
            return _quiet_broken_pipe()
        except ContactlabWarning as exc:  # raised by --strict
            print(f"{prog}: error: {in_flags(str(exc), flags)} (--strict)", file=sys.stderr)
            return 2
        except INPUT_ERRORS as exc:
            print(f"{prog}: error: {in_flags(str(exc), flags)}", file=sys.stderr)
            return 2
    return 0 if code is None else code


def add_crosstalk_flag(parser):
    """``--no-crosstalk``: keep the structure's crosstalk (its modes ringing after a hit,
    found on the record and removed with the baseline by default)."""
    parser.add_argument(
        "--no-crosstalk",
        action="store_true",
        help="keep the structure's modes ringing after a hit (removed by default)",
    )


def same_named(args, *names):
    """``{name: args.name}`` for the options whose flag has the name of the keyword it
    fills (``--min-force`` fills ``min_force``), to hand on to the command's function."""
    return {name: getattr(args, name) for name in names}
