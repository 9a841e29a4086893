"""Benchmark: the single-trace paths on realistic single-impact records (issue 22).

One impact of the hard test grain (k2 = 4e4 N/m, c2 = 0.5 N*s/m on the 40 kHz disc
sensor, contact 100 us) at 2 m/s in a 4 ms record at 2 MHz, white noise 1 % of the 3 N
peak signal, with one laboratory effect at a time at the levels of
``Effects.everything`` and a drift five times larger
(``dem_check.campaign.realistic_record``); the impact 1 ms into the record, or at its
first sample. Each record is read as a user would, with the
defaults:

- ``identify_sensor`` (default window): resonance and damping ratio against the
  sensor's, or the refusal's message;
- ``reconstruct_force`` (default baseline): peak and contact time against the model's
  truth, and the result's ``status``;
- ``compare_trace`` (the model of the same set-up): the peak sensor force's error and
  the comparison's baseline status.

Several noise seeds per line: the largest error over them is printed (``docs/campaign.md``,
"Single-trace paths").

``--no-crosstalk`` measures the paths without the crosstalk's removal (the default of
``contactlab.inverse.pulse.pulse_baseline``'s ``crosstalk`` option switched off for the
run, which the public functions do not expose).

``--noise-model white`` measures the reconstruction with the white-noise model it had
before the coloured-noise one (``contactlab.inverse.reconstruct.DEFAULT_NOISE_MODEL``);
``--effect NAME`` and ``--onset {1 ms,start}`` (repeatable) run those lines only.

Run: ``.venv/bin/python benchmarks/bench_single_trace.py [--seeds N] [--no-crosstalk]
[--noise-model white] [--effect NAME] [--onset start]``
"""

import argparse
import sys
from dataclasses import replace
from pathlib import Path

import numpy as np

import contactlab as cl
import contactlab.inverse.reconstruct as reconstruct_module
from contactlab.compare import compare_trace
from contactlab.config import load_config
from contactlab.errors import ParameterError
from contactlab.inverse import identify_sensor, reconstruct_force
from contactlab.inverse.pulse import pulse_baseline
from dem_check.campaign import Effects

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tests" / "dem_check" / "campaign"))
# the tests' record (white noise NOISE [N]), so that the benchmark measures their case
from test_realistic_single_trace import NOISE, _record  # noqa: E402

EFFECTS = {
    "white noise": Effects(),
    "1/f noise 0.3 sigma": Effects(pink=0.3 * NOISE),
    "1/f noise 1 sigma": Effects(pink=NOISE),
    "hum 1.5 sigma": Effects(hum=1.5 * NOISE),
    "drift 20 sigma": Effects(drift=20 * NOISE),
    "drift 100 sigma": Effects(drift=100 * NOISE),
    "crosstalk 2 %": Effects(crosstalk=0.02),
    "bounce 40 %, 2 ms later": Effects(bounce=0.4),
}
ONSETS = {"1 ms": 1e-3, "start": 0.0}


def setup():
    config = load_config(ROOT / "data" / "traces" / "model_hard.toml")
    law = cl.laws.LinearViscoelastic(stiffness=4e4, damping=0.5)
    return config, law


def _largest(values):
    """The signed value of largest magnitude."""
    return max(values, key=abs)


def identify(config, law, rec):
    t, y = np.asarray(rec.trace.t), np.asarray(rec.trace.values)
    try:
        found = identify_sensor(t, y)
    except ParameterError as exc:
        return None, str(exc)
    sensor = config.sensor
    return (
        found.resonance / sensor.resonance - 1.0,
        found.damping_ratio / sensor.damping_ratio - 1.0,
    ), getattr(found, "status", "")


def reconstruct(config, law, rec):
    t, y = np.asarray(rec.trace.t), np.asarray(rec.trace.values)
    truth = rec.truth.iloc[0]
    try:
        r = reconstruct_force(t, y, config.sensor)
    except ParameterError as exc:
        return None, str(exc)
    return (
        r.metrics.peak / truth["peak_contact_force [N]"] - 1.0,
        r.metrics.duration / truth["contact_time [s]"] - 1.0,
        r.metrics.impulse / truth["impulse [N*s]"] - 1.0,
    ), getattr(r, "status", "")


def compare(config, law, rec):
    try:
        c = compare_trace(rec.trace, replace(config, law=law))
    except ParameterError as exc:
        return None, str(exc)
    row = c.table.set_index("quantity").loc["peak_sensor_force"]
    return (row["rel_error"],), c.notes.get("baseline status", "")


def line(name, config, law, effects, onset, seeds):
    cells = []
    for method in (identify, reconstruct, compare):
        errors, statuses = [], set()
        for seed in range(seeds):
            value, status = method(
                config, law, _record((config.grain, config.sensor, law), effects, onset, seed)
            )
            statuses.add(status.split(":")[0] if value is not None else "refused")
            if value is not None:
                errors.append(value)
        if errors:
            text = ", ".join(f"{_largest(v) * 100:+.2f} %" for v in zip(*errors, strict=True))
        else:
            text = "refused"
        refused = seeds - len(errors)
        if refused and errors:
            text += f" ({refused} refused)"
        cells.append(f"{text} [{'; '.join(sorted(statuses))}]")
    print(f"| {name} | {' | '.join(cells)} |", flush=True)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seeds", type=int, default=4, help="noise seeds per line")
    parser.add_argument("--no-crosstalk", action="store_true", help="keep the crosstalk")
    parser.add_argument(
        "--noise-model",
        choices=["ar", "white"],
        default=reconstruct_module.DEFAULT_NOISE_MODEL,
        help="the reconstruction's noise model (white: before the coloured-noise model)",
    )
    parser.add_argument("--effect", action="append", choices=list(EFFECTS))
    parser.add_argument("--onset", action="append", choices=list(ONSETS))
    args = parser.parse_args()
    reconstruct_module.DEFAULT_NOISE_MODEL = args.noise_model
    if args.no_crosstalk:
        pulse_baseline.__kwdefaults__["crosstalk"] = False
    config, law = setup()
    print(
        f"noise model {args.noise_model}\n"
        "| effect, impact | identify-sensor: f1, zeta | reconstruct: peak, contact time, "
        "impulse "
        "| compare: peak signal |"
    )
    print("|---|---|---|---|")
    for onset_name, onset in ONSETS.items():
        if args.onset and onset_name not in args.onset:
            continue
        for name, effects in EFFECTS.items():
            if args.effect and name not in args.effect:
                continue
            line(f"{name}, {onset_name}", config, law, effects, onset, args.seeds)


if __name__ == "__main__":
    main()
