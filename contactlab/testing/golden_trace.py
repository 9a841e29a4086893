"""Golden reference traces: store an impact once, compare every later run against it.

A reference is two files in one directory, named after it:

``<name>.npz``
    The signals, compressed: ``t [s]`` and one array per channel (``contact_force [N]``,
    ``sensor_force [N]``), at most :data:`DEFAULT_MAX_SAMPLES` samples (every k-th
    sample of the run's grid, so a rerun at the same sample rate lands on them exactly).
``<name>.json``
    Provenance, readable in a review: format and version, creation date (UTC),
    contactlab version, the set-up (law and its parameters, grain, sensor, impact speed,
    window, sample rate, solver) or the measured trace's origin, and the headline
    quantities with unit-bearing keys, computed from the full run.

:class:`GoldenStore` checks a run against a reference by name. References are written
only on request (``update=True``; in pytest, ``--contactlab-update-golden``), and every
write is recorded in :attr:`GoldenStore.log`; a missing reference fails with a message
saying how to create it. Nothing is rewritten silently.

This module holds the reference itself (:class:`GoldenTrace`: reading, writing, reading
a run on its grid); :mod:`contactlab.testing.golden` holds the store and the comparison.
Comparisons are :func:`contactlab.compare.compare`'s, quantity by quantity, at
:data:`REGRESSION_RTOL` unless told otherwise; a run is first read on the reference's
time grid (:meth:`GoldenTrace.on_grid`), so a rerun of the same set-up compares sample
for sample.
"""

import json
import math
import re
import zipfile
from dataclasses import dataclass
from datetime import UTC, datetime
from pathlib import Path

import numpy as np

import contactlab
from contactlab.compare import QUANTITIES
from contactlab.errors import ParameterError, TraceFormatError
from contactlab.quantities import column
from contactlab.result import ImpactResult
from contactlab.traces import Trace
from contactlab.validation import check_count

__all__ = [
    "CHANNELS",
    "DEFAULT_MAX_SAMPLES",
    "FORMAT",
    "FORMAT_VERSION",
    "REGRESSION_RTOL",
    "STORED_QUANTITIES",
    "UPDATE_FLAG",
    "GoldenMissingError",
    "GoldenTrace",
    "reference_paths",
]

FORMAT = "contactlab golden trace"
"""Value of the ``format`` key of every reference's JSON file."""

FORMAT_VERSION = 1
"""Version of the file layout; readers refuse other versions."""

DEFAULT_MAX_SAMPLES = 2001
"""Samples kept per reference: about 30 kB of files, and 0.25 us spacing over a 500 us
window, 200 samples per period of a 20 kHz sensor's ringing."""

REGRESSION_RTOL = 1e-6
"""Default tolerance of every compared quantity (relative, absolute for the restitution,
over the reference's peak for the waveforms). Reruns of one set-up differ by the solvers'
accuracy (exact method ~1e-12, adaptive DOP853 at rtol 1e-10 ~1e-9) across machines and
library versions; 1e-6 leaves three decades of margin and still catches any change of
physics (1 % more damping moves the numbers by ~1e-3)."""

STORED_QUANTITIES = tuple(name for name, q in QUANTITIES.items() if q.basis != "peak")
"""Headline quantities a reference keeps: the scalars :func:`contactlab.compare.compare`
compares (the waveform errors are computed from the stored signals)."""

CHANNELS = ("contact_force", "sensor_force")
"""Signals a reference keeps (a measured trace has ``sensor_force`` only)."""

UPDATE_FLAG = "--contactlab-update-golden"
"""Command-line flag of the pytest plugin that writes references."""

_NAME = re.compile(r"[A-Za-z0-9][A-Za-z0-9_.-]*")
_COLUMN = re.compile(r"(\w+) \[(.+)\]")


class GoldenMissingError(AssertionError):
    """A golden reference does not exist; the message says how to create it."""


def _json_default(obj):
    """JSON form of numpy values and paths found in set-ups and trace metadata."""
    if isinstance(obj, np.generic):
        return obj.item()
    if isinstance(obj, np.ndarray):
        return obj.tolist()
    return str(obj)


def _normalised(value):
    """``value`` as it reads back from JSON, so set-ups compare like for like."""
    return json.loads(json.dumps(value, default=_json_default))


def _reading(impact):
    """``(t, channels, unit, quantities)`` of a simulated or measured impact."""
    if isinstance(impact, Trace):
        lobe = impact.metrics()
        quantities = {"sensor_response_time": lobe.duration, "peak_sensor_force": lobe.peak}
        return impact.t, {"sensor_force": impact.values}, impact.unit, quantities
    if isinstance(impact, ImpactResult):
        channels = {c: getattr(impact, c) for c in CHANNELS}
        return impact.t, channels, "N", {q: float(getattr(impact, q)) for q in STORED_QUANTITIES}
    raise ParameterError(
        "a golden trace is made from a contactlab ImpactResult or a dem_check Trace; got "
        f"{type(impact).__name__}"
    )


def _setup_of(impact):
    """What produced an impact: the simulation's set-up or the trace's origin."""
    if isinstance(impact, Trace):
        keys = ("source", "format", "instrument", "channel", "history")
        return "measured trace", _normalised({k: impact.metadata.get(k) for k in keys})
    return "contactlab.simulate_impact", _normalised(
        {
            "law": type(impact.law).__name__,
            "law_parameters": impact.law.parameters(),
            "grain": impact.grain.to_dict(),
            "sensor": impact.sensor.to_dict(),
            "velocity [m/s]": impact.velocity,
            "duration [s]": impact.duration,
            "sample_rate [Hz]": impact.sample_rate,
            "method": impact.method,
            "threshold [N]": impact.threshold,
        }
    )


def _check_name(name):
    if not isinstance(name, str) or not _NAME.fullmatch(name):
        raise ParameterError(
            "golden name must be a file name stem of letters, digits, '_', '-' and '.' "
            f"(no folders); got {name!r}"
        )
    return name


def reference_paths(directory, name):
    directory = Path(directory)
    return directory / f"{name}.json", directory / f"{name}.npz"


def _bad_file(path, problem):
    return TraceFormatError(f"{path}: {problem}; rewrite it with {UPDATE_FLAG}")


@dataclass(frozen=True, eq=False)
class GoldenTrace:
    """A stored reference impact: signals on its grid, headline quantities, provenance.

    Attributes
    ----------
    name : str
        Name of the reference (the files' stem).
    t : numpy.ndarray
        Time grid [s].
    channels : dict
        ``"contact_force"`` and/or ``"sensor_force"`` -> samples on ``t`` (in ``unit``).
    unit : str
        Unit of the channels (``"N"``).
    quantities : dict
        Headline quantities (names from :data:`STORED_QUANTITIES`) in SI units.
    metadata : dict
        The JSON provenance (``created``, ``contactlab_version``, ``source``, ``setup``).

    Notes
    -----
    Quantities and channels also read as attributes, like an ImpactResult's
    (``golden.restitution``, ``golden.sensor_force``), which is what
    :func:`contactlab.compare.compare` reads; those a reference lacks (a measured trace has
    no contact force) raise AttributeError, which ``compare`` reports as not available.
    """

    name: str
    t: np.ndarray
    channels: dict
    unit: str
    quantities: dict
    metadata: dict

    def __getattr__(self, name):
        fields = self.__dict__
        if name in STORED_QUANTITIES and name in fields.get("quantities", {}):
            return fields["quantities"][name]
        if name in CHANNELS and name in fields.get("channels", {}):
            return fields["channels"][name]
        raise AttributeError(f"golden trace {fields.get('name')!r} has no {name!r}")

    @property
    def setup(self):
        """The set-up (or the trace's origin) the reference was made from."""
        return self.metadata["setup"]

    def on_grid(self, impact):
        """An impact read on this reference's time grid, for a sample-for-sample comparison.

        Parameters
        ----------
        impact : ImpactResult or dem_check Trace
            A run of the set-up the reference was made from.

        Returns
        -------
        GoldenTrace
            The impact's channels interpolated linearly at the reference's sample times
            inside its window (exactly its own samples when the reference was written
            from a run at the same sample rate), and its headline quantities, computed
            from the full run.
        """
        t, channels, unit, quantities = _reading(impact)
        slack = 1e-9 * (t[-1] - t[0])  # grids rebuilt from one sample rate agree to rounding
        grid = self.t[(self.t >= t[0] - slack) & (self.t <= t[-1] + slack)]
        on_grid = {c: np.interp(grid, t, y) for c, y in channels.items()}
        return GoldenTrace(self.name, grid, on_grid, unit, quantities, {"setup": None})

    @classmethod
    def of(cls, name, impact, max_samples=DEFAULT_MAX_SAMPLES):
        """A reference made from an impact, not yet written.

        Parameters
        ----------
        name : str
            Reference name: a file name stem (letters, digits, ``_``, ``-``, ``.``).
        impact : ImpactResult or dem_check Trace
            The simulated or measured impact.
        max_samples : int, default :data:`DEFAULT_MAX_SAMPLES`
            Largest number of samples kept (every k-th sample of the impact's grid).

        Returns
        -------
        GoldenTrace
        """
        _check_name(name)
        max_samples = check_count("max_samples", max_samples, low=2)
        t, channels, unit, quantities = _reading(impact)
        stride = max(1, math.ceil(t.size / max_samples))
        channels = {c: np.array(y[::stride]) for c, y in channels.items()}
        source, setup = _setup_of(impact)
        columns = ["t [s]", *(f"{c} [{unit}]" for c in channels)]
        metadata = {
            "format": FORMAT,
            "format_version": FORMAT_VERSION,
            "name": name,
            "created": datetime.now(UTC).isoformat(timespec="seconds"),
            "contactlab_version": contactlab.__version__,
            "source": source,
            "setup": setup,
            "quantities": {column(q): v for q, v in quantities.items()},
            "arrays": {"file": f"{name}.npz", "columns": columns, "stride": stride},
        }
        return cls(name, np.array(t[::stride]), channels, unit, quantities, metadata)

    def write(self, directory):
        """Write ``<name>.json`` and ``<name>.npz`` into ``directory`` (created if needed).

        Returns
        -------
        tuple of pathlib.Path
            The JSON and NPZ paths.
        """
        json_path, npz_path = reference_paths(directory, self.name)
        json_path.parent.mkdir(parents=True, exist_ok=True)
        columns = self.metadata["arrays"]["columns"]
        arrays = dict(zip(columns, (self.t, *self.channels.values()), strict=True))
        np.savez_compressed(npz_path, **arrays)
        text = json.dumps(self.metadata, indent=2, default=_json_default)
        json_path.write_text(text + "\n", encoding="utf-8")
        return json_path, npz_path

    @classmethod
    def read(cls, directory, name):
        """Read the reference ``name`` from ``directory``.

        Raises
        ------
        GoldenMissingError
            If either file is missing (the message says how to create them).
        TraceFormatError
            If a file is not a readable golden reference (the message names it).
        """
        json_path, npz_path = reference_paths(directory, _check_name(name))
        missing = [str(p) for p in (json_path, npz_path) if not p.is_file()]
        if missing:
            raise GoldenMissingError(
                f"golden reference {name!r} not found: {' and '.join(missing)} missing. Run "
                f"pytest with {UPDATE_FLAG} to create it (outside pytest: "
                "GoldenStore(directory, update=True)), then review and commit the files."
            )
        try:
            metadata = json.loads(json_path.read_text(encoding="utf-8"))
        except json.JSONDecodeError as exc:
            raise _bad_file(json_path, f"line {exc.lineno}: not valid JSON ({exc.msg})") from None
        except UnicodeDecodeError:
            raise _bad_file(json_path, "not UTF-8 text") from None
        found = (
            (metadata.get("format"), metadata.get("format_version"))
            if isinstance(metadata, dict)
            else type(metadata).__name__
        )
        if found != (FORMAT, FORMAT_VERSION):
            raise _bad_file(
                json_path, f"not a {FORMAT!r} version {FORMAT_VERSION} (found {found!r})"
            )
        try:
            columns = metadata["arrays"]["columns"]
            parsed = [_COLUMN.fullmatch(c).groups() for c in columns]
            quantities = {
                _COLUMN.fullmatch(k).group(1): float(v) for k, v in metadata["quantities"].items()
            }
            with np.load(npz_path, allow_pickle=False) as data:
                arrays = [np.array(data[c], dtype=float) for c in columns]
        except (KeyError, TypeError, AttributeError, ValueError) as exc:
            raise _bad_file(
                json_path, f"incomplete or inconsistent with {npz_path.name} ({exc!r})"
            ) from None
        except (OSError, zipfile.BadZipFile) as exc:
            raise _bad_file(npz_path, f"not a readable .npz archive ({exc})") from None
        units = {unit for _, unit in parsed[1:]}
        shapes = {a.shape for a in arrays}
        if parsed[0] != ("t", "s") or len(units) != 1 or len(shapes) != 1 or arrays[0].ndim != 1:
            raise _bad_file(
                npz_path, f"columns {columns} are not t [s] and equal-length 1-D channels"
            )
        channels = {c: a for (c, _), a in zip(parsed[1:], arrays[1:], strict=True)}
        return cls(name, arrays[0], channels, units.pop(), quantities, metadata)
