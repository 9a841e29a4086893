"""Generate the synthetic sample traces in ``data/traces`` (deterministic, fixed seeds).

No public data set of measured grain-impact traces is known, so the sample traces are
simulated with the two-mass model (:func:`contactlab.simulate_impact`, set up by the
``model_*.toml`` files beside this script) and written by
:func:`contactlab.traces.write_trace` in the instruments' own export layouts, with the
features of a real acquisition:

- volts: the sensor signal S1 [N] times the sensitivity :data:`SENSITIVITY` [V/N], plus a
  DC offset [V] and white Gaussian noise [V];
- a trigger: t = 0 of the record is the first point of the simulation grid (1/8 of a
  sample interval) where the noise-free signal exceeds the trigger level, and 20 % of the
  record lies before it, so the pulse starts a few microseconds before t = 0, as on a scope;
- sampling at the record's own phase: the record's samples fall on every 8th point of
  the simulation grid counted from the trigger, not on the first touch;
- quantisation as an ADC does it: ``code = round(v / lsb)`` with
  ``lsb = (high - low) / 2**bits`` over the vertical range ``[low, high]`` [V]; a signal
  that would leave the range is an error here (the ranges are chosen so nothing clips).

Each file ``NAME`` gets a sidecar ``NAME.json`` labelled ``"synthetic": true`` with the
generating parameters, the model's truth (exact event times and peaks, in the file's time
base) and the noise-free reading of the sensor signal at the reading threshold; see
``README.md`` for the fields.

Usage::

    python data/traces/generate.py [--out DIR]
"""

import argparse
import json
import math
import sys
import tomllib
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from contactlab.config import load_config
from contactlab.metrics import impulse, pulse_metrics
from contactlab.traces import Trace, write_trace

__all__ = [
    "ACQUISITIONS",
    "OVERSAMPLING",
    "PRE_TRIGGER_FRACTION",
    "READING_K",
    "SENSITIVITY",
    "Acquisition",
    "acquire",
    "generate",
]

HERE = Path(__file__).resolve().parent
"""This folder: the model TOML files, and the default output folder."""

SENSITIVITY = 0.01124
"""Sensitivity of the simulated force sensor [V/N]: 11.24 mV/N (50 mV/lbf), a usual
value for quartz (ICP/IEPE) force sensors of some hundred newtons' range."""

PRE_TRIGGER_FRACTION = 0.2
"""Part of each record before the trigger [-]."""

OVERSAMPLING = 8
"""Simulation points per record sample interval [-]: the trigger's time resolution."""

READING_K = 5.0
"""Reading threshold in units of the effective noise (noise and quantisation) [-]."""

SIDECAR_DIGITS = 10
"""Significant digits of the sidecars' numbers: the truth is exact to ~1e-10 (the
adaptive solver's tolerance), and more digits would change the files with every change
in the last bits of the solvers' arithmetic."""


@dataclass(frozen=True)
class Acquisition:
    """How one sample file is simulated, acquired and written."""

    file: str
    """File name."""
    format: str
    """Registry name of the layout (a key of :data:`contactlab.traces.FORMATS`)."""
    description: str
    """What the file imitates."""
    model: str
    """Model TOML file in this folder."""
    samples: int
    """Record length [-]."""
    sample_interval: float
    """Sample interval [s]."""
    bits: int
    """ADC resolution [bit]."""
    vertical_range: tuple
    """ADC input range ``(low, high)`` [V]."""
    noise_std: float
    """Standard deviation of the white noise [V]."""
    dc_offset: float
    """DC offset of the signal [V]."""
    trigger_level: float
    """Trigger level [V] (offset included, as the instrument sees the signal)."""
    seed: int
    """Seed of the noise generator."""
    options: dict = field(default_factory=dict)
    """Writer options (see :func:`contactlab.traces.write_trace`)."""

    @property
    def lsb(self):
        """Quantisation step [V]."""
        low, high = self.vertical_range
        return (high - low) / 2**self.bits

    @property
    def pre_trigger_samples(self):
        """Samples before the trigger (t < 0) [-]."""
        return round(PRE_TRIGGER_FRACTION * self.samples)


def _acquisitions(path):
    """The acquisitions listed in ``path`` (``[[acquisition]]`` tables of the fields of
    :class:`Acquisition`); ``{sensitivity}`` in a comment is :data:`SENSITIVITY`."""
    rows = tomllib.loads(path.read_text(encoding="utf-8"))["acquisition"]
    for row in rows:
        row["vertical_range"] = tuple(row["vertical_range"])
        comments = row.get("options", {}).get("comments", {})
        for key, text in comments.items():
            comments[key] = text.format(sensitivity=SENSITIVITY)
    return tuple(Acquisition(**row) for row in rows)


ACQUISITIONS = _acquisitions(HERE / "acquisitions.toml")
"""The sample files, as ``acquisitions.toml`` beside this script lists them."""
"""The sample files: one per text layout, plus HDF5 and TDMS."""


def _quantise(volts, acquisition):
    """``code * lsb`` with ``code = round(v / lsb)``; an error if a code leaves the range."""
    lsb = acquisition.lsb
    codes = np.round(volts / lsb)
    lowest = round(acquisition.vertical_range[0] / lsb)
    if codes.min() < lowest or codes.max() > lowest + 2**acquisition.bits - 1:
        raise ValueError(
            f"{acquisition.file}: the signal ({volts.min():.4g} .. {volts.max():.4g} V) leaves the "
            f"vertical range {acquisition.vertical_range} V; widen it"
        )
    return codes * lsb


def _significant(value):
    """``value`` with every float in it rounded to :data:`SIDECAR_DIGITS` digits."""
    if isinstance(value, dict):
        return {key: _significant(item) for key, item in value.items()}
    if isinstance(value, list | tuple):
        return [_significant(item) for item in value]
    if isinstance(value, float):
        return float(f"{value:.{SIDECAR_DIGITS}g}")
    return value


def acquire(acquisition):
    """Simulate one impact and acquire it as the instrument would.

    Parameters
    ----------
    acquisition : Acquisition

    Returns
    -------
    trace : Trace
        The record in volts, t = 0 at the trigger.
    sidecar : dict
        Generating parameters, the truth and the noise-free reading (JSON-ready, floats
        to :data:`SIDECAR_DIGITS` significant digits).
    """
    acq = acquisition
    config = load_config(HERE / acq.model)
    dt, n, pre = acq.sample_interval, acq.samples, acq.pre_trigger_samples
    result = config.simulate(duration=n * dt, sample_rate=OVERSAMPLING / dt)
    force = result.sensor_force  # S1 [N] on the simulation grid, t = 0 at first touch
    above = force > (acq.trigger_level - acq.dc_offset) / SENSITIVITY
    if not above.any() or np.argmax(above) > pre * OVERSAMPLING:
        raise ValueError(f"{acq.file}: the signal does not reach the trigger level in time")
    trigger = int(np.argmax(above))
    grid = (np.arange(n) - pre) * OVERSAMPLING + trigger
    sampled = np.where(grid >= 0, force[np.maximum(grid, 0)], 0.0)  # at rest before touch
    rng = np.random.default_rng(acq.seed)
    volts = sampled * SENSITIVITY + acq.dc_offset + rng.normal(0.0, acq.noise_std, n)
    t = np.arange(n) * dt
    t += -pre * dt  # as the readers build start + n * increment
    trace = Trace(
        t,
        _quantise(volts, acq),
        "V",
        {"sample_interval": dt, "trigger_time": 0.0},
    )

    onset = -float(result.t[trigger])  # first touch in the record's time base [s]
    t_model = result.t + onset
    inside = t_model <= t[-1]
    noise = math.sqrt(acq.noise_std**2 + acq.lsb**2 / 12.0) / SENSITIVITY
    threshold = READING_K * noise
    reading = pulse_metrics(t_model[inside], force[inside], threshold)
    slope = np.gradient(force, result.t)
    law = config.law
    sidecar = {
        "synthetic": True,
        "description": acq.description,
        "file": acq.file,
        "format": acq.format,
        "writer_options": acq.options,
        "generator": "data/traces/generate.py",
        "model": acq.model,
        "seed": acq.seed,
        "grain": config.grain.to_dict(),
        "sensor": config.sensor.to_dict(),
        "law": {"name": law.name, "parameters": law.parameters()},
        "velocity [m/s]": result.velocity,
        "sensitivity [V/N]": SENSITIVITY,
        "noise_std [V]": acq.noise_std,
        "bits": acq.bits,
        "vertical_range [V]": list(acq.vertical_range),
        "lsb [V]": acq.lsb,
        "dc_offset [V]": acq.dc_offset,
        "trigger_level [V]": acq.trigger_level,
        "pre_trigger [s]": pre * dt,
        "samples": n,
        "sample_interval [s]": dt,
        "first_time [s]": t[0],
        "last_time [s]": t[-1],
        "simulation_sample_rate [Hz]": OVERSAMPLING / dt,
        "truth": {
            "onset_time [s]": onset,
            "contact_time [s]": result.contact_time,
            "peak_contact_force [N]": result.peak_contact_force,
            "peak_sensor_force [N]": result.peak_sensor_force,
            "sensor_response_time [s]": result.sensor_response_time,
            "restitution [-]": result.restitution,
            "impulse [N*s]": result.impulse,
        },
        "noise_free_reading": {
            "noise [N]": noise,
            "threshold [N]": threshold,
            "start [s]": reading.start,
            "end [s]": reading.end,
            "duration [s]": reading.duration,
            "peak [N]": reading.peak,
            "start_slope [N/s]": float(np.interp(reading.start, t_model, slope)),
            "end_slope [N/s]": float(np.interp(reading.end, t_model, slope)),
            "record_impulse [N*s]": impulse(t_model[inside], force[inside]),
        },
    }
    return trace, _significant(sidecar)


def generate(out_dir=HERE):
    """Write every sample file of :data:`ACQUISITIONS` and its JSON sidecar.

    Parameters
    ----------
    out_dir : str or os.PathLike, default this folder
        Output folder (created if missing).

    Returns
    -------
    list of pathlib.Path
        The files written, each trace followed by its sidecar.
    """
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    written = []
    for acq in ACQUISITIONS:
        trace, sidecar = acquire(acq)
        path = out / acq.file
        write_trace(path, trace, acq.format, **acq.options)
        side = out / f"{acq.file}.json"
        side.write_text(json.dumps(sidecar, indent=2) + "\n", encoding="utf-8")
        written += [path, side]
    return written


def main(argv=None):
    """Command line: ``python data/traces/generate.py [--out DIR]``."""
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--out", default=HERE, type=Path, help="output folder (default: here)")
    args = parser.parse_args(argv)
    written = generate(args.out)
    for path in written:
        print(f"{path.stat().st_size:>9} B  {path}")
    print(f"{sum(p.stat().st_size for p in written):>9} B  total")
    return 0


if __name__ == "__main__":
    sys.exit(main())
