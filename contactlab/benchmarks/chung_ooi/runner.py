"""Run the nine Chung & Ooi tests: contactlab (and LAMMPS) against theory, figures, one table.

What each test grades and its tolerance: :mod:`~contactlab.benchmarks.chung_ooi.grading`
(tolerances), :mod:`~contactlab.benchmarks.chung_ooi.normal` (tests 1, 2, 3, 9),
:mod:`~contactlab.benchmarks.chung_ooi.oblique` (4, 5, 6),
:mod:`~contactlab.benchmarks.chung_ooi.pairs` (7, 8).

LAMMPS' column: pass ``lammps``, a callable with the signature of
:func:`dem_check.engines.lammps.oblique.lammps_oblique` (``contactlab benchmark chung-ooi
--lammps`` does). It runs the sphere-on-plane tests 4, 5 and 6, where LAMMPS holds the
same laws on a wall; the pair tests run through the exact reduction here only.
"""

from pathlib import Path

from contactlab.benchmarks.chung_ooi import normal, oblique, pairs
from contactlab.benchmarks.chung_ooi.cases import CASES, DISAGREEMENTS
from contactlab.benchmarks.chung_ooi.figures import DRAW, save_figure
from contactlab.plausibility import internal

__all__ = ["run_chung_ooi"]

_LAMMPS_TESTS = (4, 5, 6)
"""Tests LAMMPS runs (a sphere on a rigid wall)."""


def _run_case(case, material, lammps):
    number = case.number
    if number in (1, 2):
        return normal.hertz_test(case, material, pair=number == 1)
    if number in (3, 9):
        return normal.restitution_test(case, material, pair=number == 9)
    if number == 4:
        return oblique.oblique_test(case, material, lammps)
    if number == 5:
        return oblique.tangential_speed_test(case, material, lammps)
    if number == 6:
        return oblique.spin_test(case, material, lammps)
    if number == 7:
        return pairs.pair_spin_test(case, material)
    return pairs.unequal_pair_test(case, material)


def run_chung_ooi(out=None, lammps=None):
    """Run the tests; write one figure per test and ``chung_ooi.csv`` into ``out``.

    Parameters
    ----------
    out : str or path-like, optional
        Output folder (created); no files are written when None.
    lammps : callable, optional
        LAMMPS' oblique impact (:func:`dem_check.engines.lammps.oblique.lammps_oblique`);
        without it the LAMMPS column reads "not run".

    Returns
    -------
    dict
        ``rows`` (one per graded number: test, material, quantity, contactlab, theory,
        lammps, relative_error, lammps_error, tolerance, lammps_tolerance, passed),
        ``not_run`` ({test: reason}), ``disagreements`` ({test: what the sources say and
        what is used}), ``figures`` (paths) and ``markdown`` (the table).
    """
    rows, not_run, figures = [], {}, []
    if out is not None:
        Path(out).mkdir(parents=True, exist_ok=True)
    for case in CASES:
        if case.not_run:
            not_run[case.number] = case.not_run
            continue
        engine = lammps if case.number in _LAMMPS_TESTS else None
        curves = {}
        for material in case.materials:
            # the benchmark's spheres (0.1-0.2 m, up to 17 kg) are no grains: no warnings
            with internal():
                got, curves[material.name] = _run_case(case, material, engine)
            rows.extend(got)
        if out is not None:
            figures.append(save_figure(case, DRAW[case.number](case, curves), out))
    if out is not None:
        import pandas as pd

        pd.DataFrame(rows).to_csv(Path(out) / "chung_ooi.csv", index=False)
    return {
        "rows": rows,
        "not_run": not_run,
        "disagreements": dict(DISAGREEMENTS),
        "figures": figures,
        "markdown": _markdown(rows, not_run),
    }


def _number(value, missing="not run"):
    return missing if value is None else f"{value:.8g}"


def _error(value):
    return "" if value is None else f"{value:.1e}"


def _markdown(rows, not_run):
    lines = [
        "| test | material | quantity | contactlab | theory | LAMMPS | error | LAMMPS error "
        "| tol. | LAMMPS tol. | pass |",
        "|---|---|---|---|---|---|---|---|---|---|---|",
    ]
    for r in rows:
        lines.append(
            f"| {r['test']} | {r['material']} | {r['quantity']} | {_number(r['contactlab'])} | "
            f"{_number(r['theory'], 'no closed form')} | {_number(r['lammps'])} | "
            f"{_error(r['relative_error'])} | {_error(r['lammps_error'])} | {r['tolerance']:.0e} | "
            f"{r['lammps_tolerance']:.0e} | {'pass' if r['passed'] else 'FAIL'} |"
        )
    for number, reason in not_run.items():
        lines.append(f"| {number} | - | not run: {reason} | | | | | | | | |")
    return "\n".join(lines)
