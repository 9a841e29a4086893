"""The particles of a stream, drawn before the simulation: who arrives where, when, how fast.

Arrival times at the plate follow a Poisson process whose rate is the case's flow
profile (thinning, Lewis & Shedler 1979); a mass flow is turned into a count rate with
the mix's mean particle mass. Each particle's kind follows the shares, its class is
uniform among the kind's classes (they are equal-probability bins), its speed and
incidence are normal draws and its azimuth uniform; it aims at a uniform point of the
feed spot. Its path is ballistic under the case's gravity (in the plate's frame), run
backwards from the touch: the particle is inserted at the last insertion slot at least
``release`` of travel before its touch, on that very path, so slots change no
trajectory. Everything is drawn from the case's seed on every MPI rank alike, so 1 or
N processes simulate the same particles.

A straw (a kind with ``spheres > 1``) also draws its axis (uniform azimuth, tilt from
the plate's plane uniform in ``[0, tilt_deg]``); its centre of mass follows the path,
aimed so that its lowest sphere touches at the aim point, and it is kept clear of the
others as the capsule round its spheres' centres (:mod:`dem_check.stream.clearance`).
"""

import math

import numpy as np
import pandas as pd

from contactlab.bodies import Grain, Sensor
from contactlab.errors import ParameterError
from contactlab.solver import simulate_impact
from dem_check.stream.clearance import Placed

__all__ = ["LEAD_SLOTS", "Schedule", "gravity_vector", "schedule"]

LEAD_SLOTS = 2
"""Insertion slots before the first possible touch (the stream needs time to arrive)."""

_TRIES = 50
"""Aim points drawn for a particle before the feed is declared too dense."""


def gravity_vector(case):
    """Gravity in the plate's frame [m/s**2]: the plate tilted by its inclination about y,
    so the down-slope direction is +x."""
    a = math.radians(case.plate.inclination_deg)
    return np.array([case.gravity * math.sin(a), 0.0, -case.gravity * math.cos(a)])


class Schedule:
    """The drawn particles (:attr:`table`) and the classes they belong to.

    Attributes
    ----------
    table : pandas.DataFrame
        One row per particle, in insertion order (its index is the particle id ``pid``):
        ``kind``, ``cls`` (class index), ``diameter [m]``, ``density [kg/m^3]``, ``mass
        [kg]``, ``aim_time [s]`` (touch time of the free path), ``slot`` (insertion
        slot), ``x, y, z [m]`` and ``vx, vy, vz [m/s]`` at insertion, ``speed [m/s]``
        and ``incidence [deg]`` at the aim.
        Straws add ``spheres`` (1 for a single sphere) and their axis ``axis_x, axis_y,
        axis_z [-]`` (a unit vector; zeros for a sphere); their ``diameter`` is a
        sphere's and ``mass`` the clump's.
    classes : list
        ``(kind name, grain, law, tangential law)`` per class; class ``k`` is LAMMPS
        atom type ``k + 1``.
    clumps : list
        Per class: None for single spheres, else the sphere centres along a straw's axis
        from its centre of mass [m] (:meth:`~dem_check.stream.case.ParticleKind.offsets`).
    time_step, slot_steps, lead : float, int, float
        Step [s], steps per insertion slot, time before the first touch [s].
    gravity : numpy.ndarray
        Gravity in the plate's frame [m/s**2].
    """

    def __init__(self, table, classes, time_step, slot_steps, lead, gravity, clumps):
        self.table, self.classes, self.gravity = table, classes, gravity
        self.time_step, self.slot_steps, self.lead = time_step, slot_steps, lead
        self.clumps = clumps

    def extent(self, cls):
        """Bounding radius of class ``cls``'s particles about their centre of mass [m]."""
        return _extent(self.classes[cls][1].radius, self.clumps[cls])


def _extent(radius, offsets):
    return radius if offsets is None else radius + max(abs(o) for o in offsets)


def _time_step(case, classes, clumps):
    """The case's step, or the shortest wall contact over ``steps_per_contact``; a
    straw's is that of one sphere carrying its share of the clump (a flat straw: all
    its spheres press at once)."""
    if case.time_step is not None:
        return case.time_step
    fastest = case.feed.speed + 3.0 * case.feed.speed_sd
    times = []
    for (_, grain, law, _), offsets in zip(classes, clumps, strict=True):
        if offsets is not None:
            share = grain.mass / len(offsets)
            grain = Grain(diameter=grain.diameter, mass=share, **_material(grain))
        times.append(simulate_impact(grain, Sensor.rigid(), law, fastest, audit=False))
    return min(r.contact_time for r in times) / case.steps_per_contact


def _material(grain):
    return {"youngs_modulus": grain.youngs_modulus, "poisson_ratio": grain.poisson_ratio}


def _arrivals(case, rng, mean_mass, start):
    """Touch times [s] of a Poisson process with the flow's rate, in [start, start+duration)."""
    flow, duration = case.flow, case.duration
    scale = 1.0 if flow.kind == "count" else 1.0 / mean_mass
    peak = flow.peak() * scale
    if peak <= 0.0:
        return np.zeros(0)
    if flow.arrivals == "regular":
        grid = np.linspace(0.0, duration, 100_001)
        rate = flow.at(grid, duration) * scale
        cumulative = np.concatenate(
            [[0.0], np.cumsum(0.5 * (rate[1:] + rate[:-1]) * np.diff(grid))]
        )
        wanted = np.arange(0.5, cumulative[-1], 1.0)
        return start + np.interp(wanted, cumulative, grid)
    count = rng.poisson(peak * duration * 1.2 + 20)
    times = np.cumsum(rng.exponential(1.0 / peak, count))
    while times.size and times[-1] < duration:
        more = np.cumsum(rng.exponential(1.0 / peak, count)) + times[-1]
        times = np.concatenate([times, more])
    times = times[times < duration]
    keep = rng.uniform(0.0, peak, times.size) < flow.at(times, duration) * scale
    return start + times[keep]


def _truncated(rng, mean, sd, low, high):
    value = rng.normal(mean, sd)
    while not low <= value <= high:
        value = rng.normal(mean, sd)
    return value


def schedule(case):
    """Draw the particles of ``case`` (a :class:`Schedule`), reproducibly from its seed.

    Raises
    ------
    ParameterError
        When no aim point keeps a particle clear of the others at insertion (the feed is
        too dense for its spot: widen ``feed.spot`` or lower the flow).
    """
    classes, owner, clumps = [], [], []
    for k, kind in enumerate(case.particles):
        for grain, law, tangential in kind.classes():
            classes.append((kind.name, grain, law, tangential))
            owner.append(k)
            clumps.append(None if kind.spheres == 1 else kind.offsets(grain.diameter))
    owner = np.array(owner)
    dt = _time_step(case, classes, clumps)
    slot_steps = max(1, round(case.slot / dt))
    slot = slot_steps * dt
    feed, g = case.feed, gravity_vector(case)
    slowest = max(0.1 * feed.speed, feed.speed - 3.0 * feed.speed_sd)
    lead = (math.ceil(feed.release / slowest / slot) + LEAD_SLOTS) * slot
    shares = np.array([kind.share for kind in case.particles], dtype=float)
    shares /= shares.sum()
    masses = np.array([c[1].mass for c in classes])
    mean_mass = sum(shares[k] * masses[owner == k].mean() for k in range(shares.size))
    rng = np.random.default_rng(case.seed)
    times = _arrivals(case, rng, mean_mass, lead)
    rows, placed = [], Placed(times.size, g)
    for t_aim in times:
        k = rng.choice(shares.size, p=shares)
        cls = int(rng.choice(np.flatnonzero(owner == k)))
        grain = classes[cls][1]
        speed = _truncated(rng, feed.speed, feed.speed_sd, 0.1 * feed.speed, np.inf)
        theta = math.radians(_truncated(rng, feed.incidence_deg, feed.incidence_sd_deg, 0.0, 89.0))
        phi = rng.uniform(0.0, 2.0 * math.pi)
        v = speed * np.array(
            [math.sin(theta) * math.cos(phi), math.sin(theta) * math.sin(phi), -math.cos(theta)]
        )
        fly = feed.release / speed
        slot_index = math.floor((t_aim - fly) / slot)
        back = t_aim - slot_index * slot
        axis, height = _axis(rng, case.particles[k], clumps[cls], grain.radius)
        shape = (grain.radius, np.array(axis), _extent(grain.radius, clumps[cls]) - grain.radius)
        for _ in range(_TRIES):
            radius, angle = feed.spot * math.sqrt(rng.uniform()), rng.uniform(0.0, 2 * math.pi)
            touch = np.array([radius * math.cos(angle), radius * math.sin(angle), height])
            start = touch - v * back + 0.5 * g * back**2
            if placed.clear(start, v - g * back, shape, slot_index * slot):
                break
        else:
            raise ParameterError(
                f"feed: no aim point in the spot of radius {feed.spot!r} m keeps particle "
                f"{len(rows)} clear of the others at insertion; widen feed.spot or lower "
                "the flow rate"
            )
        velocity = v - g * back
        placed.add(slot_index * slot, start, velocity, shape, t_aim)
        spheres = 1 if clumps[cls] is None else len(clumps[cls])
        rows.append(
            {
                "kind": case.particles[k].name,
                "cls": cls,
                "diameter [m]": grain.diameter,
                "density [kg/m^3]": grain.mass / (spheres * math.pi / 6.0 * grain.diameter**3),
                "mass [kg]": grain.mass,
                "spheres": spheres,
                "axis_x [-]": axis[0],
                "axis_y [-]": axis[1],
                "axis_z [-]": axis[2],
                "aim_time [s]": t_aim,
                "slot": slot_index,
                "x [m]": start[0],
                "y [m]": start[1],
                "z [m]": start[2],
                "vx [m/s]": velocity[0],
                "vy [m/s]": velocity[1],
                "vz [m/s]": velocity[2],
                "speed [m/s]": speed,
                "incidence [deg]": math.degrees(theta),
            }
        )
    order = np.argsort([row["slot"] for row in rows], kind="stable")
    table = pd.DataFrame([rows[i] for i in order]).reset_index(drop=True)
    table.index.name = "pid"
    return Schedule(table, classes, dt, slot_steps, lead, g, clumps)


def _axis(rng, kind, offsets, radius):
    """A straw's axis (a unit vector; uniform azimuth, tilt from the plate's plane uniform
    in ``[0, kind.tilt_deg]``) and the height of its centre of mass over the plate when
    its lowest sphere touches [m]; zeros and the radius for a sphere (no draws, so a
    stream without straws draws what it drew before straws existed)."""
    if offsets is None:
        return (0.0, 0.0, 0.0), radius
    azimuth = rng.uniform(0.0, 2.0 * math.pi)
    tilt = math.radians(rng.uniform(0.0, kind.tilt_deg))
    axis = (math.cos(tilt) * math.cos(azimuth), math.cos(tilt) * math.sin(azimuth), math.sin(tilt))
    return axis, radius + (_extent(radius, offsets) - radius) * math.sin(tilt)
