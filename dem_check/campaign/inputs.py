"""The campaign's files: which files ``paths`` names, and each record read in newtons.

Nothing is skipped silently: a folder without files, a glob without a match, a missing
path and a file that cannot be read or converted each become a row of the files table
with the reason (:class:`InputProblem`).
"""

import glob
import os
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path

from contactlab.errors import ParameterError, TraceFormatError
from dem_check.traces import read_trace, to_force

__all__ = ["InputProblem", "expand_paths", "for_file", "read_record"]

_GLOB_CHARACTERS = frozenset("*?[")


@dataclass(frozen=True)
class InputProblem:
    """A path that gave no record: the files table's row for it."""

    file: str
    status: str
    reason: str


def _one(path, skip):
    """Files named by one path (folder, glob or file), or the problem with it."""
    text = os.fspath(path)
    if any(c in _GLOB_CHARACTERS for c in text) and not os.path.exists(text):
        found = sorted(p for p in glob.glob(text) if os.path.isfile(p))
        if not found:
            return [], [InputProblem(text, "no match", f"the pattern {text!r} matches no file")]
        return [p for p in found if Path(p).resolve() not in skip], []
    if os.path.isdir(text):
        found = sorted(
            str(p)
            for p in Path(text).iterdir()
            if p.is_file() and not p.name.startswith(".") and p.resolve() not in skip
        )
        if not found:
            return [], [InputProblem(text, "empty folder", f"the folder {text!r} holds no file")]
        return found, []
    if not os.path.exists(text):
        return [], [InputProblem(text, "missing", f"no such file or folder: {text!r}")]
    return [text], []


def expand_paths(paths, skip=()):
    """The files of a campaign, in order, and the paths that named none.

    Parameters
    ----------
    paths : str, os.PathLike or sequence of them
        Files, folders (their files, sorted by name, hidden files excepted) or glob
        patterns (``"day1/*.csv"``).
    skip : iterable of str or os.PathLike
        Files never taken as records (the metadata CSV when it lies among them).

    Returns
    -------
    files : list of str
    problems : list of InputProblem

    Raises
    ------
    ParameterError
        ``paths`` is empty, or names no file at all (the message lists why).
    """
    if isinstance(paths, str | os.PathLike):
        paths = [paths]
    try:
        paths = list(paths)
    except TypeError:
        raise ParameterError(
            f"paths must be a folder, a glob or a list of files; got {paths!r}"
        ) from None
    if not paths:
        raise ParameterError("paths is empty: give a folder, a glob or a list of files")
    skip = {Path(p).resolve() for p in skip}
    files, problems = [], []
    for path in paths:
        if not isinstance(path, str | os.PathLike):
            raise ParameterError(f"paths must hold file names; got {path!r}")
        found, trouble = _one(path, skip)
        files += [f for f in found if f not in files]
        problems += trouble
    if not files:
        raise ParameterError(
            "paths names no file to analyse: " + "; ".join(p.reason for p in problems)
        )
    return files, problems


def for_file(name, option, path):
    """A per-file option: the value itself, or a mapping's entry for ``path``.

    A mapping is looked up by the path as given, then by its file name.
    """
    if not isinstance(option, Mapping):
        return option
    for key in (path, os.path.basename(path)):
        if key in option:
            return option[key]
    return None


def read_record(path, channel=None, sensitivity=None):
    """One record in newtons, or why it cannot be had.

    Parameters
    ----------
    path : str
    channel : str or int, optional
        As for :func:`dem_check.read_trace`.
    sensitivity : float, optional
        Sensor sensitivity [V/N] for a record in volts. A record already in newtons is
        taken as it is (and the files table says the sensitivity was not applied).

    Returns
    -------
    trace : Trace or None
    status : str
        ``"ok"``, ``"unreadable"``, ``"no sensitivity"`` or ``"not a force"``.
    reason : str
        The reader's message, or what to do.
    """
    try:
        trace = read_trace(path, channel=channel)
    except (TraceFormatError, OSError, ImportError) as exc:
        return None, "unreadable", str(exc)
    except ParameterError as exc:  # e.g. a channel that does not exist
        return None, "unreadable", f"{path}: {exc}"
    if trace.unit == "V":
        if sensitivity is None:
            return (
                None,
                "no sensitivity",
                f"{path} is in volts: give the sensor's sensitivity [V/N] (sensitivity=, "
                "--sensitivity) to convert it to newtons",
            )
        try:
            trace = to_force(trace, sensitivity)
        except ParameterError as exc:
            return None, "no sensitivity", f"{path}: {exc}"
    elif trace.unit != "N":
        return (
            None,
            "not a force",
            f"{path} is in {trace.unit!r}; a campaign reads force sensors (V or N)",
        )
    return trace, "ok", ""
