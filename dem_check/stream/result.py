"""A stream's result: the step series, the truth, the oscilloscope trace, the files.

:func:`run_stream` is the entry point: simulate (:mod:`dem_check.stream.engine`), read
the truth (:mod:`dem_check.stream.truth`) and return a :class:`StreamResult`. Its
:meth:`~StreamResult.trace` samples the sensor signal ``S1`` at an oscilloscope's rate
(point samples of the step series, linearly interpolated between steps, plus white noise
``noise`` [N] from the seed, and optionally a laboratory's effects:
:class:`dem_check.campaign.Effects`): a :class:`~contactlab.traces.Trace` in newtons that
:func:`dem_check.run_campaign` analyses. :meth:`~StreamResult.write` puts in a folder:

* ``trace.csv``: that trace (generic CSV, read by :func:`dem_check.read_trace`);
* ``steps.csv.gz``: every step's ``t [s]``, ``contact_force [N]``, ``sensor_force [N]``,
  ``x1 [m]``, ``v1 [m/s]``;
* ``truth.csv``: one row per contact, impacts and re-contacts
  (:data:`~dem_check.stream.truth.TRUTH_COLUMNS`);
* ``particles.csv``: the drawn particles; ``deck.lammps``: the LAMMPS input run.
"""

from pathlib import Path

import numpy as np
import pandas as pd

from contactlab.entry_checks import check_flag, check_instance
from contactlab.errors import ParameterError
from contactlab.tables import write_csv
from contactlab.traces.api import write_trace
from contactlab.validation import check_count, check_number, check_path
from dem_check.campaign.records import add_effects
from dem_check.stream.engine import simulate_stream
from dem_check.stream.truth import impacts_truth
from dem_check.traces import Trace

__all__ = ["StreamResult", "run_stream"]


STREAM_RESULT = "a StreamResult (from run_stream)"
"""What the stream functions' ``result`` is, for their messages."""


class StreamResult:
    """One simulated stream (see the module docstring).

    Attributes
    ----------
    case : StreamCase
    steps : pandas.DataFrame
        Per step (``t [s]``, ``contact_force [N]``, ``sensor_force [N]``, ``x1 [m]``,
        ``v1 [m/s]``).
    truth : pandas.DataFrame
        Per contact: impacts and re-contacts (:data:`~dem_check.stream.truth.TRUTH_COLUMNS`).
    particles : pandas.DataFrame
        The drawn particles (:class:`~dem_check.stream.feed.Schedule`'s table).
    time_step, slot_time, lead : float
        The step, the insertion slot and the time before the first touch [s].
    script : str
        The LAMMPS input run.
    rank, ranks : int
        This process's MPI rank and the number of processes it ran on.
    """

    def __init__(self, raw):
        self.case = raw.case
        self.steps = raw.steps
        self.truth = impacts_truth(raw.contacts, raw.schedule, raw.steps)
        self.particles = raw.schedule.table
        self.time_step = raw.schedule.time_step
        self.slot_time = raw.schedule.slot_steps * raw.schedule.time_step
        self.lead = raw.schedule.lead
        self.script = raw.script
        self.rank, self.ranks = raw.rank, raw.ranks

    def trace(self, sample_rate=None, noise=None, seed=None, effects=None):
        """The sensor signal S1 as an oscilloscope records it.

        Parameters
        ----------
        sample_rate : float, optional
            [Hz]; default the case's. Must not exceed the simulation's step rate.
        noise : float, optional
            Standard deviation of white noise added [N]; default the case's.
        seed : int, optional
            Noise seed; default the case's.
        effects : dem_check.campaign.Effects, optional
            A laboratory's coloured noise, drift, hum, crosstalk, ADC and offset steps
            (:func:`dem_check.campaign.records.add_effects`); the crosstalk rings after
            each impact's touch with the impact's peak contact force as its scale.
            Default the case's (``StreamCase.effects``; ``Effects()`` for none).

        Returns
        -------
        Trace
        """
        rate = check_number(
            "sample_rate",
            self.case.sample_rate if sample_rate is None else sample_rate,
            low=0.0,
            unit="Hz",
        )
        if rate * self.time_step > 1.0 + 1e-12:
            raise ParameterError(
                f"sample_rate = {rate!r} Hz is above the simulation's step rate "
                f"{1.0 / self.time_step:.6g} Hz; lower it or the case's time_step"
            )
        noise = check_number(
            "noise",
            self.case.noise if noise is None else noise,
            low=0.0,
            low_open=False,
            unit="N",
        )
        seed = check_count("seed", self.case.seed if seed is None else seed, low=0)
        t_steps = self.steps["t [s]"].to_numpy()
        t = np.arange(0.0, t_steps[-1], 1.0 / rate)
        values = np.interp(t, t_steps, self.steps["sensor_force [N]"].to_numpy())
        rng = np.random.default_rng(seed + 1)
        effects = self.case.effects if effects is None else effects
        if effects is not None:
            impacts = self.truth[self.truth["contact"] == 0]
            truth = pd.DataFrame(
                {
                    "onset [s]": impacts["touch [s]"],
                    "peak_sensor_force [N]": impacts["peak_force [N]"],
                }
            )
            values = add_effects(t, values, effects, truth, noise, rng)[0]
        elif noise > 0.0:
            values = values + rng.normal(0.0, noise, t.size)
        metadata = {
            "format": "stream",
            "instrument": "dem_check.stream (LAMMPS with the sensor inside)",
            "sample_interval": 1.0 / rate,
            "channel": "S1",
            "trigger_time": None,
        }
        return Trace(t, values, "N", metadata)

    def write(self, out, trace=None):
        """Write the files of the module docstring into folder ``out``; returns its path."""
        out = Path(check_path("out", out))
        check_instance("trace", trace, Trace, "StreamResult.trace", optional=True)
        out.mkdir(parents=True, exist_ok=True)
        trace = self.trace() if trace is None else trace
        write_trace(
            out / "trace.csv",
            trace,
            "generic",
            name="S1",
            comments={"source": "dem_check.stream", "time_step [s]": repr(self.time_step)},
        )
        write_csv(self.steps, out / "steps.csv.gz")
        # particle kinds are named in the user's case: no cell may run as a formula
        write_csv(self.truth, out / "truth.csv")
        write_csv(self.particles, out / "particles.csv", index=True)
        (out / "deck.lammps").write_text(self.script, encoding="utf-8")
        return out


def run_stream(case, *, progress=False):
    """Simulate a stream case in LAMMPS with the sensor inside; see ``docs/streams.md``.

    Parameters
    ----------
    case : StreamCase
    progress : bool, default False
        A progress bar (tqdm, stderr).

    Returns
    -------
    StreamResult

    Raises
    ------
    ParameterError
        For a law LAMMPS cannot hold exactly, or a feed too dense for its spot.
    ImportError
        Without the ``lammps`` extra.
    """
    from dem_check.stream.case import StreamCase

    check_instance("case", case, StreamCase, "read_case or DEFAULT_CASE.with_")
    progress = check_flag("progress", progress)
    return StreamResult(simulate_stream(case, progress=progress))
