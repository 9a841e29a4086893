"""Which tangential rule makes a DEM engine's oblique rebound differ from this toolkit's.

A DEM engine's Hertz-Mindlin contact hard-wires tangential rules its law's name does not
state (``docs/dem-conventions.md``): the lever arm, the history rule, the tangential
damping and the Coulomb cap, each a field of
:class:`~contactlab.solver.conventions.Conventions`. On Chung & Ooi's test 4 this module
runs :func:`contactlab.simulate_oblique` (exact, so every difference below is a rule, not
a step error) under:

* ``"contactlab default"``: this toolkit's rules (``DEM_CONVENTIONS["contactlab"]``);
* ``"only <rule>"``: the default with that one rule switched to the engine's;
* ``"all but <rule>"``: the engine's rules with that one switched back to the default;
* ``"<engine> rules"``: all of the engine's rules (its preset).

and compares each at every angle with the engine's own rebound: ``vt'`` and ``R w'``, both
over the incident ``vt``. A rule moves the curve onto the engine when ``"only <rule>"``
closes the gap, and is needed when ``"all but <rule>"`` opens it again. Rules in which the
engine's preset equals the default are not run.
"""

import math
from dataclasses import dataclass, fields, replace

import numpy as np

import contactlab as cl
from contactlab.benchmarks.chung_ooi.grading import engine_row
from contactlab.errors import ParameterError
from contactlab.solver.conventions import DEM_CONVENTIONS, Conventions

__all__ = [
    "BASE",
    "RULES",
    "Attribution",
    "attribute",
    "graded_rows",
    "markdown",
    "variants",
]

RULES = tuple(f.name for f in fields(Conventions))
"""The rules switched one at a time (the fields of :class:`Conventions`)."""

BASE = "contactlab default"
"""Label of this toolkit's own rules."""


def variants(target, base=DEM_CONVENTIONS["contactlab"], engine="engine"):
    """``{label: Conventions}``: ``base``, each differing rule switched alone both ways,
    and ``target`` (labelled ``"<engine> rules"``), in that order."""
    differing = [rule for rule in RULES if getattr(target, rule) != getattr(base, rule)]
    if not differing:  # the engine runs this toolkit's own rules
        return {f"{engine} rules": target}
    out = {BASE: base}
    for rule in differing:
        out[f"only {rule} = {getattr(target, rule)}"] = replace(
            base, **{rule: getattr(target, rule)}
        )
    if len(differing) > 1:  # with one rule, "all but" it is the default itself
        for rule in differing:
            out[f"all but {rule}"] = replace(target, **{rule: getattr(base, rule)})
    out[f"{engine} rules"] = target
    return out


@dataclass(frozen=True)
class Attribution:
    """One engine's test-4 rebounds against this toolkit under each variant of the rules.

    Attributes
    ----------
    engine : str
        The engine's label (e.g. ``"kratos"``, ``"lammps mindlin/force"``).
    material : str
        The sphere's material.
    angles : tuple of float
        Incidence angles [deg].
    engine_values : numpy.ndarray
        (n, 2): the engine's ``vt'/vt`` and ``R w'/vt`` [-] at each angle.
    values : dict
        ``{variant: (n, 2) array}``: the same for this toolkit under each variant.
    rules : dict
        ``{variant: Conventions}``.
    refused : dict
        ``{variant: reason}`` for variants this toolkit refuses (their values are NaN),
        e.g. ``history="total"`` with ``damping="tied"`` beside a damped normal law.
    """

    engine: str
    material: str
    angles: tuple
    engine_values: np.ndarray
    values: dict
    rules: dict
    refused: dict

    def differences(self, variant):
        """(n, 2): the variant's ``vt'/vt`` and ``R w'/vt`` minus the engine's [-]."""
        return self.values[variant] - self.engine_values

    def worst(self, variant):
        """Largest ``|difference|`` of ``vt'/vt`` and of ``R w'/vt`` over the angles [-]."""
        return tuple(np.abs(self.differences(variant)).max(axis=0))

    @property
    def preset(self):
        """Label of the variant with all of the engine's rules."""
        return next(reversed(self.values))

    def table(self):
        """Rows (dicts, one per variant and angle) for a CSV."""
        rows = []
        for variant, rules in self.rules.items():
            for i, degrees in enumerate(self.angles):
                ours, diff = self.values[variant][i], self.differences(variant)[i]
                rows.append(
                    {
                        "engine": self.engine,
                        "material": self.material,
                        "variant": variant,
                        **{rule: getattr(rules, rule) for rule in RULES},
                        "angle [deg]": degrees,
                        "vt'/vt [-]": ours[0],
                        "R w'/vt [-]": ours[1],
                        "engine vt'/vt [-]": self.engine_values[i, 0],
                        "engine R w'/vt [-]": self.engine_values[i, 1],
                        "vt'/vt minus engine's [-]": diff[0],
                        "R w'/vt minus engine's [-]": diff[1],
                    }
                )
        return rows


def _normalised(tangential_velocity, angular_velocity, radius, vt):
    """``(vt'/vt, R w'/vt)`` [-] of a rebound."""
    return tangential_velocity / vt, radius * angular_velocity / vt


def attribute(body, material, normal, mindlin, speed, angles, engine, engine_rebounds, target):
    """Run this toolkit under each of :func:`variants` and compare with an engine.

    Parameters
    ----------
    body : contactlab.Grain
        The sphere.
    material : str
        Its material's name.
    normal : contactlab.laws.SmoothLaw
        Normal contact law.
    mindlin : contactlab.laws.Mindlin
        Tangential law; its stiffness and friction are kept, its rules set per variant.
    speed : float
        Impact speed [m/s].
    angles : sequence of float
        Incidence angles [deg].
    engine : str
        The engine's label.
    engine_rebounds : sequence
        The engine's rebound at each angle: ``(normal speed away [m/s], vt' [m/s], w'
        [rad/s])``.
    target : Conventions
        The engine's rules.

    Returns
    -------
    Attribution
    """
    rules = variants(target, engine=engine)
    values, refused = {}, {}
    for variant, chosen in rules.items():
        law = chosen.mindlin(mindlin)
        try:
            law.for_contact(normal, body.mass)
        except ParameterError as error:  # a combination this toolkit refuses, and why
            refused[variant] = str(error)
            values[variant] = np.full((len(angles), 2), np.nan)
            continue
        out = []
        for degrees in angles:
            angle = math.radians(degrees)
            result = cl.simulate_oblique(
                body, cl.Sensor.rigid(), normal, law, speed, angle, lever_arm=chosen.lever_arm
            )
            vt = speed * math.sin(angle)
            out.append(
                _normalised(result.tangential_velocity, result.angular_velocity, body.radius, vt)
            )
        values[variant] = np.array(out)
    theirs = np.array(
        [
            _normalised(r[1], r[2], body.radius, speed * math.sin(math.radians(degrees)))
            for degrees, r in zip(angles, engine_rebounds, strict=True)
        ]
    )
    return Attribution(engine, material, tuple(angles), theirs, values, rules, refused)


def markdown(attributions):
    """A Markdown table: per engine and variant, the worst difference from the engine and
    the angle where it is, for ``vt'/vt`` and ``R w'/vt``."""
    lines = [
        "| engine | material | variant | worst vt'/vt diff. | at [deg] | worst R w'/vt diff. "
        "| at [deg] |",
        "|---|---|---|---|---|---|---|",
    ]
    for item in attributions:
        for variant in item.values:
            if variant in item.refused:
                lines.append(
                    f"| {item.engine} | {item.material} | {variant} | not run: "
                    f"{item.refused[variant].split(':')[0]} | | | |"
                )
                continue
            diff = np.abs(item.differences(variant))
            where = diff.argmax(axis=0)
            lines.append(
                f"| {item.engine} | {item.material} | {variant} | {diff[where[0], 0]:.1e} | "
                f"{item.angles[where[0]]:g} | {diff[where[1], 1]:.1e} | {item.angles[where[1]]:g} |"
            )
    return "\n".join(lines)


def graded_rows(case, material, attribution, column):
    """Graded rows: this toolkit with all of the engine's rules against the engine at every
    angle, ``vt'/vt`` and ``R w'/vt`` (:func:`~contactlab.benchmarks.chung_ooi.grading.
    engine_row`, the engines' tolerance); ``column`` names the engine's column."""
    preset, rows = attribution.preset, []
    ours, theirs = attribution.values[preset], attribution.engine_values
    for i, degrees in enumerate(attribution.angles):
        label = f"at {degrees:g} deg, {attribution.engine} conventions [-]"
        for j, quantity in enumerate(("vt'/vt", "R w'/vt")):
            rows.append(
                engine_row(
                    case, material, f"{quantity} {label}", ours[i, j], theirs[i, j], 1.0, column
                )
            )
    return rows
