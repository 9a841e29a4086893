"""The Coulomb cap in the oblique solver: the slides of ``Mindlin(coulomb_cap=...)``.

:class:`TotalCap` (``"total"``, LAMMPS): one slide of sign ``sigma`` (phase ``sigma``), the
force ``sigma mu N`` and the history slaved to it; it ends when sticking becomes
admissible, and the history is then set so that the trial force equals the cap.

:class:`ElasticCap` (``"elastic"``, Kratos), below.

Kratos (``DEM_D_Hertz_viscous_Coulomb_CL.cpp``, ``CalculateTangentialForceWithNeighbour``)
caps the elastic tangential force alone at ``mu N`` and cuts or drops the viscous force
``-eta s``; LAMMPS (and :func:`contactlab.simulate_oblique` by default) scales the total
and stores the rest as the elastic part. With no tangential damping the two are the same.
In the limit of a vanishing step, Kratos' four cases give these slides of sign ``sigma``
(the force is ``sigma mu N`` in each):

* the viscous force *along* the slide (``-sigma eta s > 0``): the elastic force held at
  ``sigma mu N`` and the viscous one dropped (:data:`ELASTIC_SLIDE`), or the elastic force
  below the cap and free, following the sticking rate, the viscous one cut to the rest
  (:data:`FREE_SLIDE`);
* the viscous force *against* the slide, with the elastic force above the cap: Kratos
  cuts the elastic force back to the cap, the total falls to ``mu N - eta |s|`` and the
  contact sticks until it climbs back to the cap: a saw tooth, each tooth a stick phase
  started by that cut; where the slip is at rest the teeth vanish and the slide is
  LAMMPS' (``|phase|`` 1), the limit of teeth whose length goes to zero.

The phase codes are those of :mod:`contactlab.solver.oblique` (0 sticking, ``sigma``
LAMMPS' slide) and ``2 sigma``, ``3 sigma`` here.
"""

__all__ = [
    "CUT",
    "ELASTIC_SLIDE",
    "FREE_SLIDE",
    "TEETH",
    "ElasticCap",
    "TotalCap",
    "cap_rules",
    "sign",
]

ELASTIC_SLIDE = 2
"""``|phase|`` of a slide whose elastic force is held at ``mu N`` (viscous force dropped)."""

FREE_SLIDE = 3
"""``|phase|`` of a slide whose elastic force is free below ``mu N`` (viscous force cut)."""

CUT = 1e-5
"""Smallest cut of the elastic force back to the cap, relative to the cap, that starts a
saw tooth: below it the slip is nearly at rest and the slide is LAMMPS' (the limit of
teeth whose length vanishes with the slip; its force is off the teeth's mean by less than
the cut), until the viscous force against it reaches twice this (then the teeth start)."""

TEETH = 200
"""Teeth in a row after which the smallest cut grows tenfold (teeth whose cut stays near
it are a slide at rest in the slip: LAMMPS' slide again, until the cut has grown)."""


def sign(phase):
    """The sign of a slide's force (``phase`` +-1, +-2 or +-3), 0 when sticking."""
    return (phase > 0) - (phase < 0)


def cap_rules(model):
    """The cap's rules for an :class:`~contactlab.solver.oblique.ObliqueModel`, by its
    law's ``coulomb_cap``."""
    return ElasticCap(model) if model.law.coulomb_cap == "elastic" else TotalCap(model)


class TotalCap:
    """Phase switches and events of LAMMPS' cap (see the module docstring)."""

    def __init__(self, model):
        self.model = model

    def _cap(self, y):
        d = y[2] - y[0]
        return d, self.model.law.friction * max(self.model.normal(d, y[3] - y[1]), 0.0)

    def slide_phase(self, sigma, y):
        """The phase once the trial force reaches ``sigma mu N`` in state ``y``."""
        return sigma

    def after_slide(self, phase, event, y):
        """The phase after event ``event`` of slide ``phase`` at state ``y``, whose
        history this sets to give the trial force the cap (LAMMPS' rescaling)."""
        d, cap = self._cap(y)
        y[6] = self.model.law.history_on_cap(sign(phase) * cap, d, self.model.slip(y.tolist()))
        return 0

    def events(self, phase, contact_value):
        """Event functions ``values(y) -> list`` and directions of slide ``phase``: the
        contact end (``contact_value(n, d)``) and the end of sliding."""
        model = self.model

        def values(y):
            x1, v1, x2, v2 = y[:4].tolist()
            n = model.normal(x2 - x1, v2 - v1)
            return [contact_value(n, x2 - x1), model.slide_exit(phase, y.tolist())]

        return values, [-1, -1]


class ElasticCap(TotalCap):
    """Phase switches and events of Kratos' cap (see the module docstring)."""

    def __init__(self, model):
        super().__init__(model)
        self.cut, self.teeth = CUT, 0  # the smallest cut now, teeth in a row

    def along(self, sigma, y):
        """``-sigma eta s`` [N]: the viscous force along a slide of sign ``sigma`` (> 0),
        or against it (< 0)."""
        model = self.model
        return -sigma * model.law.damping_coefficient(y[2] - y[0]) * model.slip(list(y[:7]))

    def slide_phase(self, sigma, y):
        """The phase once the trial force reaches ``sigma mu N`` in state ``y`` (a list or
        an array, whose history this sets for a saw tooth); see the module docstring."""
        along = self.along(sigma, y)
        if along == 0.0:
            return sigma
        law = self.model.law
        d, cap = self._cap(y)
        elastic = sigma * law.elastic_force(y[6], d)
        if along < 0.0:
            if elastic - cap <= self.cut * cap:
                return sigma
            self.teeth += 1
            if self.teeth > TEETH:
                self.cut, self.teeth = 10.0 * self.cut, 0
                return sigma
            y[6] = law.history_of(sigma * cap, d)
            # a viscous force over twice the cap leaves the trial force beyond the other cap
            return 0 if along >= -2.0 * cap else self.slide_phase(-sigma, y)
        return ELASTIC_SLIDE * sigma if elastic >= cap else FREE_SLIDE * sigma

    def after_slide(self, phase, event, y):
        """The phase after event ``event`` of slide ``phase`` at state ``y``, whose history
        this sets when it was slaved to the cap."""
        sigma, kind = sign(phase), abs(phase)
        if event != 3:  # a slide ended: the teeth in a row start again
            self.teeth = 0
        if kind == 1:  # LAMMPS' slide: its history; event 2, the viscous force turned along
            stick = super().after_slide(phase, event, y)
            if event == 3:  # the viscous force against the slide grown: a saw tooth starts
                d, cap = self._cap(y)
                y[6] = self.model.law.history_of(sigma * cap, d)
                along = self.along(sigma, y)
                return 0 if along >= -2.0 * cap else self.slide_phase(-sigma, y)
            return stick if event == 1 else ELASTIC_SLIDE * sigma
        if kind == FREE_SLIDE:  # the trial force back under the cap, or the elastic one at it
            return 0 if event == 1 else ELASTIC_SLIDE * sigma
        d, cap = self._cap(y)
        y[6] = self.model.law.history_of(sigma * cap, d)
        if event == 1:  # the elastic force turns back under the cap
            return FREE_SLIDE * sigma if self.along(sigma, y) > 0.0 else 0
        # the viscous force turns against the slide: LAMMPS' slide, if it goes on
        return sigma if self.model.slide_exit(sigma, y.tolist()) > 0.0 else 0

    def events(self, phase, contact_value):
        """Event functions and directions of slide ``phase``: the contact end; in LAMMPS'
        slide the end of sliding and the viscous force turning along it; in a free slide
        the trial force falling back to ``mu N`` and the elastic force reaching it; in an
        elastic slide the elastic force turning back and the viscous force turning against
        the slide."""
        model, sigma, kind = self.model, sign(phase), abs(phase)
        normal, law, mu = model.normal, model.law, model.law.friction

        def values(y):
            x1, v1, x2, v2, *_, h = y[:7].tolist()
            d = x2 - x1
            n = normal(d, v2 - v1)
            if kind == FREE_SLIDE:
                trial = sigma * model.tangential_force(0, y[:7].tolist())
                elastic = sigma * law.elastic_force(h, d)
                return [contact_value(n, d), trial - mu * n, elastic - mu * n]
            ends = [contact_value(n, d), model.slide_exit(phase, y.tolist())]
            if kind == ELASTIC_SLIDE:  # the viscous force turning against the slide
                return [*ends, self.along(sigma, y)]
            # LAMMPS' slide: the viscous force turning along it, or grown against it
            against = -self.along(sigma, y)
            return [*ends, against, against - 2.0 * self.cut * mu * n]

        if kind == FREE_SLIDE:
            return values, [-1, -1, +1]
        return values, ([-1, -1, -1] if kind == ELASTIC_SLIDE else [-1, -1, -1, +1])
