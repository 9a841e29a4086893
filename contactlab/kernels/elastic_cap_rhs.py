"""Kratos' elastic Coulomb cap, compiled: the right-hand side and events of its slides.

Kratos (``DEM_D_Hertz_viscous_Coulomb_CL.cpp``, ``CalculateTangentialForceWithNeighbour``)
caps the elastic tangential force alone at ``mu N`` and cuts or drops the viscous force
``-eta s``; LAMMPS (:mod:`contactlab.kernels.oblique_rhs`, ``coulomb_cap="total"``) scales
the total and stores the rest as the elastic part. In the limit of a vanishing step,
Kratos' four cases give slides of sign ``sigma`` whose force is ``sigma mu N`` in each:

* the viscous force *along* the slide (``-sigma eta s > 0``): the elastic force held at
  ``sigma mu N`` and the viscous one dropped (:data:`ELASTIC_SLIDE`), or the elastic force
  below the cap and free, following the sticking rate, the viscous one cut to the rest
  (:data:`FREE_SLIDE`);
* the viscous force *against* the slide, with the elastic force above the cap: Kratos
  cuts the elastic force back to the cap, the total falls to ``mu N - eta |s|`` and the
  contact sticks until it climbs back to the cap: a saw tooth, each tooth a stick phase
  started by that cut (:mod:`contactlab.kernels.elastic_cap`); where the slip is at rest
  the teeth vanish and the slide is LAMMPS' (:data:`LAMMPS_SLIDE`), the limit of teeth
  whose length goes to zero.

The packed parameters (:func:`pack`) are the oblique impact's with the ``model`` field
:data:`ELASTIC_CAP_MODEL` and two more fields: the kind of slide (:data:`SLIDE`, one of
the three above; the ``phase`` field keeps the slide's sign, so that the oblique
right-hand side applies ``sigma mu N``) and the smallest cut that starts a saw tooth
(:data:`CUT_FIELD`). :func:`rhs` is the oblique right-hand side with the history running
in a free slide; :func:`events` is the oblique impact's events with the slides' own. Every
slide event falls (the rising ones are written negated), so the crossing directions of
:func:`contactlab.kernels.oblique_rhs.direction` hold for them all, and
:mod:`contactlab.kernels.oblique_kernel` and :mod:`contactlab.kernels.oblique_events` run
both caps through these two functions.
"""

import numpy as np

from contactlab.compiled import njit
from contactlab.kernels import oblique_rhs as ob
from contactlab.kernels.power import MODEL, force

__all__ = [
    "CUT",
    "CUT_FIELD",
    "ELASTIC_CAP_MODEL",
    "ELASTIC_SLIDE",
    "EVENTS",
    "FREE_SLIDE",
    "LAMMPS_SLIDE",
    "SLIDE",
    "TEETH",
    "along",
    "elastic_force",
    "events",
    "history_of",
    "pack",
    "rhs",
]

ELASTIC_CAP_MODEL = 2.0
"""Value of the ``model`` field (:data:`contactlab.kernels.power.MODEL`): the oblique
impact with Kratos' cap."""

LAMMPS_SLIDE, ELASTIC_SLIDE, FREE_SLIDE = 1, 2, 3
"""Kinds of slide: LAMMPS' (the history slaved to the trial force at the cap), the elastic
force held at ``mu N`` (viscous force dropped), the elastic force free below ``mu N``
(viscous force cut). A phase code of the phase loop is the kind times the slide's sign."""

SLIDE, CUT_FIELD = len(ob.OBLIQUE_PARAMETERS), len(ob.OBLIQUE_PARAMETERS) + 1
"""Indices of the kind of slide and of the smallest cut in :func:`pack`'s array."""

EVENTS = 4
"""Most events of a phase (LAMMPS' slide under Kratos' cap)."""

CUT = 1e-5
"""Smallest cut of the elastic force back to the cap, relative to the cap, that starts a
saw tooth: below it the slip is nearly at rest and the slide is LAMMPS' (the limit of
teeth whose length vanishes with the slip; its force is off the teeth's mean by less than
the cut), until the viscous force against it reaches twice this (then the teeth start)."""

TEETH = 200
"""Teeth in a row after which the smallest cut grows tenfold (teeth whose cut stays near
it are a slide at rest in the slip: LAMMPS' slide again, until the cut has grown)."""


def pack(par):
    """The parameters of :func:`contactlab.kernels.oblique_rhs.pack` with Kratos' cap
    (sticking, the smallest cut :data:`CUT`)."""
    par = np.append(par, [0.0, CUT])
    par[MODEL] = ELASTIC_CAP_MODEL
    return par


@njit(cache=True, error_model="numpy")
def elastic_force(h, d, par):
    """The elastic part of the tangential force [N] (:func:`~contactlab.kernels.oblique_rhs.
    trial_force` at zero slip)."""
    return ob.trial_force(h, d, 0.0, par)


@njit(cache=True, error_model="numpy")
def history_of(elastic, d, par):
    """The history whose elastic force is ``elastic`` [N] at overlap ``d`` [m]
    (:func:`~contactlab.kernels.oblique_rhs.history_on_cap` at zero slip)."""
    return ob.history_on_cap(elastic, d, 0.0, par)


@njit(cache=True, error_model="numpy")
def along(sigma, z, par):
    """``-sigma eta s`` [N]: the viscous force along a slide of sign ``sigma`` (> 0), or
    against it (< 0)."""
    d = z[2] - z[0]
    return -sigma * ob._graded(d, par[ob.ETA], par[ob.ETA_EXPONENT]) * ob.slip(z, par)


@njit(cache=True, error_model="numpy")
def rhs(z, par, warped, out):
    """``y' = f(y)`` (or ``dz/ds`` warped) into ``out``: the oblique impact's, the history
    following its sticking rate in a free slide."""
    ob.rhs(z, par, warped, out)
    if par[ob.PHASE] != ob.STICK and par[SLIDE] == FREE_SLIDE:
        d, r = z[2] - z[0], z[3] - z[1]
        out[6] = ob.history_rate(z[6], d, r, ob.slip(z, par), par)
        if warped:
            out[6] *= 4.0 * z[7] ** 3


@njit(cache=True, error_model="numpy")
def _elastic_slide_exit(sigma, z, par):
    """``sigma dF_elastic/dt - mu dN/dt`` [N/s] in an elastic slide, along a sticking path
    from the elastic force at the cap: the slide goes on while >= 0."""
    x1, v1, x2, v2 = z[0], z[1], z[2], z[3]
    d, r = x2 - x1, v2 - v1
    n = force(d, r, par)
    mu = par[ob.FRICTION]
    h = history_of(sigma * mu * max(n, 0.0), d, par)
    a1, a2 = ob._accelerations(x1, v1, n, par)
    rate = ob.elastic_force_rate(h, d, r, ob.slip(z, par), par)
    return sigma * rate - mu * ob._normal_force_rate(d, r, a2 - a1, par)


@njit(cache=True, error_model="numpy")
def events(z, par, phase, out):
    """Event values into ``out`` (at least :data:`EVENTS`); returns how many ``phase`` has.

    Sticking, and with LAMMPS' cap, those of :func:`contactlab.kernels.oblique_rhs.events`.
    Event 0 is the contact's end; the slides of Kratos' cap add, all falling:

    * LAMMPS' slide: 1 the end of sliding, 2 the viscous force turning along the slide,
      3 the viscous force against it grown to twice the smallest cut (a saw tooth starts);
    * elastic slide: 1 the elastic force turning back under the cap, 2 the viscous force
      turning against the slide;
    * free slide: 1 the trial force falling back to ``mu N``, 2 the elastic force reaching
      it.
    """
    kind = par[SLIDE]
    if phase == ob.STICK or par[MODEL] != ELASTIC_CAP_MODEL or kind == LAMMPS_SLIDE:
        count = ob.events(z, par, phase, out)
        if phase == ob.STICK or par[MODEL] != ELASTIC_CAP_MODEL:
            return count
        against = -along(phase, z, par)
        mu_n = par[ob.FRICTION] * force(z[2] - z[0], z[3] - z[1], par)
        out[2], out[3] = against, 2.0 * par[CUT_FIELD] * mu_n - against
        return 4
    d = z[2] - z[0]
    n = force(d, z[3] - z[1], par)
    out[0] = ob.contact_value(n, d)
    mu_n = par[ob.FRICTION] * n
    if kind == FREE_SLIDE:
        out[1] = phase * ob.trial_force(z[6], d, ob.slip(z, par), par) - mu_n
        out[2] = mu_n - phase * elastic_force(z[6], d, par)
    else:
        out[1] = _elastic_slide_exit(phase, z, par)
        out[2] = along(phase, z, par)
    return 3
