"""Loading Kratos Multiphysics' DEM application quietly, on one thread.

Kratos comes from the ``kratos`` extra (``pip install 'contactlab[kratos]'``: the PyPI
wheels ``KratosMultiphysics`` and ``KratosDEMApplication`` 10.4.4). Importing them prints
a banner of about 15 lines on standard output from C++ (file descriptor 1), and the
kernel prints "Deregistering ..." lines when the process ends. :func:`load_kratos`
imports them with descriptor 1 pointed at ``/dev/null``, then sets Kratos' logger to
warnings and errors only (which also silences the lines at exit), and sets Kratos'
OpenMP threads to one (``ParallelUtilities.SetNumThreads(1)``): a one-grain drop test
gains nothing from threads, and on two cores two threads ran ten times slower (issue 27).

>>> from dem_check.engines.kratos.session import load_kratos
>>> kratos = load_kratos()  # doctest: +SKIP
>>> kratos.KM.ParallelUtilities.GetNumThreads()  # doctest: +SKIP
1
"""

import contextlib
import importlib
import importlib.metadata
import os
import sys
from dataclasses import dataclass

__all__ = ["EXTRA", "KratosModules", "kratos_version", "load_kratos", "quiet_stdout"]

EXTRA = "kratos"
"""Name of the optional dependency set that installs Kratos (``contactlab[kratos]``)."""

_INSTALL_HINT = f"install the extra: pip install 'contactlab[{EXTRA}]'"

_loaded = []
"""The :class:`KratosModules` once loaded (Kratos is imported once per process)."""


@dataclass(frozen=True)
class KratosModules:
    """The imported Kratos modules.

    Attributes
    ----------
    KM : module
        ``KratosMultiphysics`` (``Model``, ``Parameters``, ``VELOCITY_Z``, ...).
    DEM : module
        ``KratosMultiphysics.DEMApplication`` (``DAMPING_GAMMA``, ...).
    stage : type
        ``DEMAnalysisStage``, the class that reads a DEM case and steps it.
    """

    KM: object
    DEM: object
    stage: type


@contextlib.contextmanager
def quiet_stdout():
    """Point file descriptor 1 at ``/dev/null`` inside the block (C++ output included)."""
    sys.stdout.flush()
    saved = os.dup(1)
    null = os.open(os.devnull, os.O_WRONLY)
    try:
        os.dup2(null, 1)
        yield
    finally:
        sys.stdout.flush()
        os.dup2(saved, 1)
        os.close(saved)
        os.close(null)


def load_kratos():
    """Kratos and its DEM application, imported without output and set to one thread.

    Returns
    -------
    KratosModules

    Raises
    ------
    ImportError
        When Kratos is not installed; the message names the extra.
    """
    if _loaded:
        return _loaded[0]
    try:
        with quiet_stdout():
            km = importlib.import_module("KratosMultiphysics")
            dem = importlib.import_module("KratosMultiphysics.DEMApplication")
            stage = importlib.import_module(
                "KratosMultiphysics.DEMApplication.DEM_analysis_stage"
            ).DEMAnalysisStage
    except ImportError as exc:
        raise ImportError(f"Kratos DEM is not installed; {_INSTALL_HINT}") from exc
    km.Logger.GetDefaultOutput().SetSeverity(km.Logger.Severity.WARNING)
    km.ParallelUtilities.SetNumThreads(1)
    _loaded.append(KratosModules(km, dem, stage))
    return _loaded[0]


def kratos_version():
    """Installed ``KratosDEMApplication`` version (e.g. ``"10.4.4"``), or ``None``."""
    try:
        return importlib.metadata.version("KratosDEMApplication")
    except importlib.metadata.PackageNotFoundError:
        return None
