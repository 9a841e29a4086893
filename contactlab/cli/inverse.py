"""The inverse-method commands: identify-sensor, reconstruct, fit, export-dem."""

import sys
from pathlib import Path

from contactlab.cli.output import dump
from contactlab.cli.running import add_crosstalk_flag, add_outputs, same_named
from contactlab.errors import ParameterError

__all__ = ["add_inverse_parsers"]


def _read_trace(args, force=True):
    """The trace named on the command line, in newtons unless ``force`` is False."""
    from contactlab.traces import TraceFormatError, read_trace

    try:
        trace = read_trace(args.trace, channel=args.channel, sensitivity=args.sensitivity)
    except FileNotFoundError:
        raise ParameterError(f"trace file not found: {args.trace}") from None
    except TraceFormatError as exc:
        raise ParameterError(str(exc)) from None
    if force and trace.unit != "N":
        raise ParameterError(
            f"{args.trace} is in {trace.unit}, not N: give --sensitivity [V/N] to convert it"
        )
    return trace


def _save_plot(fig, path):
    import matplotlib.pyplot as plt

    fig.savefig(path, dpi=150)
    plt.close(fig)
    print(f"wrote {path}", file=sys.stderr)


def _identify_sensor(args):
    from contactlab.inverse import identify_sensor, plot_identification

    trace = _read_trace(args, force=False)
    ident = identify_sensor(trace.t, trace.values, window=args.window)
    if args.plot:
        _save_plot(plot_identification(trace.t, trace.values, ident)[0], args.plot)
    print(dump(ident.to_dict(unit=trace.unit)) if args.json else repr(ident))


def _inverse_sensor(args):
    from contactlab.bodies import Sensor
    from contactlab.config import load_config

    if (args.sensor_config is None) == (args.resonance is None):
        raise ParameterError("give --resonance F --damping-ratio Z or --sensor-config CONFIG.toml")
    if args.sensor_config is not None:
        return load_config(args.sensor_config).sensor
    if args.sensor_mass is None or args.damping_ratio is None:
        raise ParameterError("--resonance needs --sensor-mass M [kg] and --damping-ratio Z [-]")
    return Sensor.from_resonance(
        args.resonance, mass=args.sensor_mass, damping_ratio=args.damping_ratio
    )


def _reconstruct(args):
    from contactlab.inverse import reconstruct_force

    sensor = _inverse_sensor(args)
    trace = _read_trace(args)
    rec = reconstruct_force(
        trace.t,
        trace.values,
        sensor,
        args.method,
        baseline_window=args.baseline,
        crosstalk=not args.no_crosstalk,
        **same_named(
            args, "regularization", "cutoff", "noise_model", "contact_edges", "flank_exponent"
        ),
    )
    if args.plot:
        _save_plot(rec.plot()[0], args.plot)
    print(dump(rec.summary()) if args.json else repr(rec))


def _fit(args):
    from contactlab.config import load_config
    from contactlab.inverse import compare_laws, fit_contact

    model = load_config(args.model)
    trace = _read_trace(args)
    fitter = compare_laws if args.law == "auto" else fit_contact
    result = fitter(
        trace.t,
        trace.values,
        model.grain,
        model.sensor,
        None if args.law == "auto" else args.law,
        velocity=args.velocity,
        baseline_window=args.baseline,
        crosstalk=not args.no_crosstalk,
    )
    fit = result.best if args.law == "auto" else result
    if args.out:
        fit.to_json(args.out)
        print(f"wrote {args.out} ({fit.law_name})", file=sys.stderr)
    if args.plot:
        _save_plot(fit.plot()[0], args.plot)
    print(dump(result.to_dict()) if args.json else result.summary())


def _export_dem(args):
    from contactlab.inverse import export_dem, read_fit

    text = export_dem(
        read_fit(args.fit),
        args.to,
        source=str(args.fit),
        poisson_ratio=args.poisson_ratio,
        friction=args.friction,
    )
    if args.out:
        Path(args.out).write_text(text, encoding="utf-8")
        print(f"wrote {args.out}", file=sys.stderr)
    else:
        print(text, end="")


def _add_trace_arguments(p):
    p.add_argument("trace", help="trace file (any format dem_check.read_trace reads)")
    p.add_argument("--channel", help="channel name or 0-based index (multi-channel files)")
    p.add_argument("--sensitivity", type=float, help="sensor sensitivity [V/N] for a volt trace")


def add_inverse_parsers(sub):
    """The inverse-method commands: identify-sensor, reconstruct, fit, export-dem."""
    from contactlab.inverse.export import DEM_CODES
    from contactlab.inverse.fit_models import FIT_MODELS
    from contactlab.inverse.noise_colour import NOISE_MODELS
    from contactlab.inverse.reconstruct import CONTACT_EDGES, CRITERIA, METHODS

    window = {"nargs": 2, "type": float, "metavar": ("T0", "T1")}
    p = sub.add_parser(
        "identify-sensor", help="sensor resonance and damping ratio from free ringing"
    )
    _add_trace_arguments(p)
    p.add_argument("--window", **window, help="ringing window [s] (default: automatic)")
    add_outputs(p, _identify_sensor, plot="write the trace and fitted ringing")

    p = sub.add_parser("reconstruct", help="the true contact force from a sensor trace")
    _add_trace_arguments(p)
    p.add_argument("--sensor-mass", type=float, help="sensor moving mass [kg]")
    p.add_argument("--resonance", type=float, help="sensor resonance [Hz]")
    p.add_argument("--damping-ratio", type=float, help="sensor damping ratio [-]")
    p.add_argument("--sensor-config", help="TOML impact config whose [sensor] is used")
    p.add_argument(
        "--method", choices=tuple(METHODS), default="tikhonov", help="(default tikhonov)"
    )
    p.add_argument("--regularization", choices=tuple(CRITERIA), help="tikhonov (default gcv)")
    p.add_argument(
        "--noise-model",
        choices=NOISE_MODELS,
        help="tikhonov: ar (default; the noise's AR model, read on the baseline, whitens "
        "the problem) or white",
    )
    p.add_argument(
        "--contact-edges",
        choices=CONTACT_EDGES,
        help="significance (default; where the force is significantly above its noise, "
        "the edges extrapolated along the flanks) or level (2 %% of the peak)",
    )
    p.add_argument(
        "--flank-exponent",
        type=float,
        default=1.0,
        help="power law of the force at the contact's edges [-] (default 1; 1.5 for Hertz)",
    )
    p.add_argument("--cutoff", type=float, help="inverse filter cutoff [Hz] (default 2 f1)")
    p.add_argument("--baseline", **window, help="pre-trigger window [s] (default t < 0)")
    add_crosstalk_flag(p)
    add_outputs(p, _reconstruct, plot="write signal and reconstructed force")

    p = sub.add_parser("fit", help="fit a contact law to a trace through the two-mass model")
    _add_trace_arguments(p)
    p.add_argument(
        "--law",
        required=True,
        choices=(*FIT_MODELS, "auto"),
        help="law to fit; auto fits every law, ranks them by BIC and says which the data "
        "reject (--out then writes the best)",
    )
    p.add_argument("--model", required=True, help="TOML impact config: its grain and sensor")
    p.add_argument("--velocity", type=float, help="measured impact velocity [m/s] (fixed)")
    p.add_argument("--baseline", **window, help="pre-trigger window [s] (default t < 0)")
    p.add_argument("--out", metavar="FIT.json", help="write the fit as JSON")
    add_crosstalk_flag(p)
    add_outputs(p, _fit, plot="write trace, fitted signal and force", json="print the fit as JSON")

    p = sub.add_parser(
        "export-dem", help="a fitted law as LAMMPS/LIGGGHTS/MercuryDPM/YADE/EDEM input"
    )
    p.add_argument("fit", help="FIT.json written by 'contactlab fit --out'")
    p.add_argument("--to", required=True, choices=tuple(DEM_CODES), help="target code")
    p.add_argument("--out", metavar="FILE", help="write the snippet here (default: print)")
    p.add_argument("--poisson-ratio", type=float, help="grain Poisson ratio [-] (Hertz laws)")
    p.add_argument("--friction", type=float, help="friction coefficient [-] (not fitted)")
    p.set_defaults(func=_export_dem)
