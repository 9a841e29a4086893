"""The campaign's files: which files ``paths`` names, and each record read in newtons.

Nothing is skipped silently: a folder without files, a glob without a match, a missing
path, a sub-folder, a link that is broken or loops, a FIFO, a sidecar that is not a record,
a file named twice and a file that cannot be read or converted each become a row of the
files table with the reason (:class:`InputProblem`).
"""

import glob
import os
import stat
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path

from contactlab.errors import ParameterError, TraceFormatError
from contactlab.traces import read_trace, to_force

__all__ = [
    "SIDECAR_SUFFIXES",
    "SKIPPED_STATUSES",
    "InputProblem",
    "check_out_folder",
    "expand_paths",
    "for_file",
    "read_record",
]

_GLOB_CHARACTERS = frozenset("*?[")

SIDECAR_SUFFIXES = frozenset(
    {".json", ".toml", ".md", ".py", ".html", ".png", ".svg", ".pdf", ".yaml", ".yml"}
)
"""Files that are never records: sidecar metadata (``daq.h5.json``), set-ups (``.toml``),
notes, scripts, reports and figures. They are listed as ``skipped``, not read."""


SKIPPED_STATUSES = ("skipped", "sub-folder", "duplicate")
"""Rows that are no failure: a file that is not a record, a sub-folder not searched, a
file already read under another name. The others (missing, unreadable, ...) are."""


@dataclass(frozen=True)
class InputProblem:
    """A path that gave no record: the files table's row for it."""

    file: str
    status: str
    reason: str


def _not_a_record(path):
    """Why the folder entry ``path`` is not read as a record, or None if it is a candidate.

    Never follows a link blindly: a broken link, a link loop, a sub-folder, a FIFO, socket
    or device and a sidecar each get a row (status, reason).
    """
    text = os.fspath(path)
    if os.path.islink(text):
        try:
            Path(text).resolve(strict=True)
        except FileNotFoundError:
            return InputProblem(text, "broken link", f"{text!r} links to a missing file")
        except (RuntimeError, OSError) as exc:  # Python 3.11 raises RuntimeError on a loop
            return InputProblem(text, "link loop", f"{text!r} is a link loop ({exc})")
    try:
        mode = os.stat(text).st_mode
    except OSError as exc:
        return InputProblem(text, "unreadable", f"{text!r}: {exc.strerror}")
    if stat.S_ISDIR(mode):
        return InputProblem(
            text, "sub-folder", f"{text!r} is a sub-folder, not searched: name it to read it"
        )
    if not stat.S_ISREG(mode):
        return InputProblem(text, "not a file", f"{text!r} is a FIFO, socket or device")
    if Path(text).suffix.lower() in SIDECAR_SUFFIXES:
        return InputProblem(text, "skipped", f"{text!r} is not a record (a sidecar or note)")
    return None


def _listed(candidates, skip):
    """Split folder or glob entries into record candidates and problem rows."""
    files, problems = [], []
    for path in candidates:
        problem = _not_a_record(path)
        if problem is not None:
            problems.append(problem)
        elif Path(path).resolve() not in skip:
            files.append(path)
    return files, problems


def _one(path, skip):
    """Files named by one path (folder, glob or file), or the problem with it."""
    text = os.fspath(path)
    if any(c in _GLOB_CHARACTERS for c in text) and not os.path.lexists(text):
        found = sorted(glob.glob(text))
        if not found:
            return [], [InputProblem(text, "no match", f"the pattern {text!r} matches no file")]
        return _listed(found, skip)
    if os.path.isdir(text):
        try:
            entries = sorted(str(p) for p in Path(text).iterdir() if not p.name.startswith("."))
        except OSError as exc:
            return [], [InputProblem(text, "unreadable folder", f"{text!r}: {exc.strerror}")]
        if not entries:
            return [], [InputProblem(text, "empty folder", f"the folder {text!r} holds no file")]
        return _listed(entries, skip)
    if not os.path.lexists(text):
        return [], [InputProblem(text, "missing", f"no such file or folder: {text!r}")]
    problem = _not_a_record(text)
    return ([], [problem]) if problem is not None else ([text], [])


def _identity(path):
    """The file itself, however it is named: device and inode."""
    info = os.stat(path)
    return info.st_dev, info.st_ino


def expand_paths(paths, skip=()):
    """The files of a campaign, in order, and the paths that named none.

    Parameters
    ----------
    paths : str, os.PathLike or sequence of them
        Files, folders (their files, sorted by name, hidden files excepted; sub-folders
        are listed, not searched) or glob patterns (``"day1/*.csv"``).
    skip : iterable of str or os.PathLike
        Files never taken as records (the metadata CSV when it lies among them).

    Returns
    -------
    files : list of str
        Each file once: a file named again (another path, a link) is a ``duplicate`` row.
    problems : list of InputProblem
        Paths that named no record, with the reason: no match, missing, empty or
        unreadable folder, sub-folder, broken link, link loop, FIFO/socket/device,
        sidecar (``skipped``), duplicate.

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
    files, problems, seen = [], [], {}
    for path in paths:
        if not isinstance(path, str | os.PathLike):
            raise ParameterError(f"paths must hold file names; got {path!r}")
        found, trouble = _one(path, skip)
        problems += trouble
        for file in found:
            first = seen.setdefault(_identity(file), file)
            if first is file:
                files.append(file)
            else:
                problems.append(
                    InputProblem(file, "duplicate", f"{file!r} is the same file as {first!r}")
                )
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


def _read_failure(path, channel):
    """``"no channel"`` when the file reads without the channel asked for (the channel
    is what failed), else ``"unreadable"``."""
    if channel is None:
        return "unreadable"
    try:
        read_trace(path)
    except (TraceFormatError, OSError, ImportError, ParameterError):
        return "unreadable"
    return "no channel"


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
        ``"ok"``, ``"unreadable"``, ``"no channel"`` (the file has no such channel),
        ``"no sensitivity"`` or ``"not a force"``.
    reason : str
        The reader's message, or what to do.
    """
    try:
        trace = read_trace(path, channel=channel)
    except (TraceFormatError, OSError, ImportError, ParameterError) as exc:
        message = str(exc) if isinstance(exc, TraceFormatError) else f"{path}: {exc}"
        return None, _read_failure(path, channel), message
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


def check_out_folder(out, files):
    """Refuse an output folder that holds an input: writing there would overwrite records.

    Parameters
    ----------
    out : str or os.PathLike
        The folder for the tables and report.
    files : list of str
        The campaign's records.

    Raises
    ------
    ParameterError
        Naming ``out`` and the first record inside it.
    """
    folder = Path(out).resolve()
    for file in files:
        if folder in Path(file).resolve().parents:
            raise ParameterError(
                f"out = {os.fspath(out)!r} holds the input {file!r}: the tables and report "
                "would overwrite records there; choose another folder"
            )
