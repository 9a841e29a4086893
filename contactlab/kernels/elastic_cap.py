"""The oblique impact's contact under Kratos' elastic Coulomb cap, compiled: its phase loop.

The phases are those of :mod:`contactlab.kernels.elastic_cap_rhs` (sticking, and slides
of three kinds, each phase code the kind times the slide's sign), each one a piece of
:func:`contactlab.kernels.oblique_kernel._piece` (the compiled DOP853 stepper and the
event location of LAMMPS' cap). Between pieces this loop applies Kratos' rules in the
limit of a vanishing step: :func:`slide_phase` when the trial force reaches the cap
(a saw tooth where the elastic force is cut back to it), :func:`after_slide` when a
slide's event ends it. A saw tooth's count and the smallest cut that starts one
(:data:`~contactlab.kernels.elastic_cap_rhs.CUT`, grown tenfold after
:data:`~contactlab.kernels.elastic_cap_rhs.TEETH` teeth in a row: a slide at rest in the
slip is LAMMPS' slide) travel in the packed parameters' ``cut`` field and a counter.
"""

import math

import numpy as np

from contactlab.compiled import njit
from contactlab.kernels import elastic_cap_rhs as cap
from contactlab.kernels import oblique_kernel as ok
from contactlab.kernels import oblique_rhs as ob

__all__ = ["after_slide", "slide_phase", "solve_contact"]


@njit(cache=True, error_model="numpy")
def _sign(phase):
    """The sign of a slide's force (phase code +-1, +-2 or +-3), 0 when sticking."""
    return 1 if phase > 0 else (-1 if phase < 0 else 0)


@njit(cache=True, error_model="numpy")
def slide_phase(sigma, y, par, teeth):
    """The phase once the trial force reaches ``sigma mu N`` in state ``y``, whose history
    this sets for a saw tooth; returns (phase, teeth in a row). ``par[CUT_FIELD]`` grows
    tenfold after :data:`~contactlab.kernels.elastic_cap_rhs.TEETH` teeth in a row."""
    while True:
        viscous = cap.along(sigma, y, par)
        if viscous == 0.0:
            return sigma, teeth
        d = y[2] - y[0]
        limit = ok._cap(y, par, 1.0)
        elastic = sigma * cap.elastic_force(y[6], d, par)
        if viscous > 0.0:
            kind = cap.ELASTIC_SLIDE if elastic >= limit else cap.FREE_SLIDE
            return kind * sigma, teeth
        if elastic - limit <= par[cap.CUT_FIELD] * limit:
            return sigma, teeth
        teeth += 1
        if teeth > cap.TEETH:
            par[cap.CUT_FIELD] *= 10.0
            return sigma, 0
        y[6] = cap.history_of(sigma * limit, d, par)
        if viscous >= -2.0 * limit:
            return ob.STICK, teeth
        # a viscous force over twice the cap leaves the trial force beyond the other cap
        sigma = -sigma


@njit(cache=True, error_model="numpy")
def after_slide(phase, event, y, par, teeth):
    """The phase after event ``event`` of slide ``phase`` at state ``y``, whose history
    this sets when it was slaved to the cap; returns (phase, teeth in a row)."""
    sigma, kind = _sign(phase), abs(phase)
    if event != 3:  # a slide ended: the teeth in a row start again
        teeth = 0
    d = y[2] - y[0]
    limit = ok._cap(y, par, 1.0)
    if kind == cap.LAMMPS_SLIDE:  # its history (LAMMPS' rescaling)
        y[6] = ob.history_on_cap(sigma * limit, d, ob.slip(y, par), par)
        if event == 3:  # the viscous force against the slide grown: a saw tooth starts
            y[6] = cap.history_of(sigma * limit, d, par)
            if cap.along(sigma, y, par) >= -2.0 * limit:
                return ob.STICK, teeth
            return slide_phase(-sigma, y, par, teeth)
        # event 2: the viscous force turned along the slide
        return (ob.STICK if event == 1 else cap.ELASTIC_SLIDE * sigma), teeth
    if kind == cap.FREE_SLIDE:  # the trial force back under the cap, or the elastic one at it
        return (ob.STICK if event == 1 else cap.ELASTIC_SLIDE * sigma), teeth
    y[6] = cap.history_of(sigma * limit, d, par)
    if event == 1:  # the elastic force turns back under the cap
        return (cap.FREE_SLIDE * sigma if cap.along(sigma, y, par) > 0.0 else ob.STICK), teeth
    # the viscous force turns against the slide: LAMMPS' slide, if it goes on
    return (sigma if ob.slide_exit(sigma, y, par) > 0.0 else ob.STICK), teeth


@njit(cache=True, error_model="numpy")
def solve_contact(par, y0, rtol, atol, keep):
    """The contact from the touch (``y0``, zero overlap) to the separation.

    Parameters and returns as :func:`contactlab.kernels.oblique_kernel.solve_contact`;
    ``par`` is :func:`contactlab.kernels.elastic_cap_rhs.pack`'s (not modified), and the
    phase column of the pieces holds each phase's sign (0 sticking, +-1 sliding).
    """
    par = par.copy()
    par[ob.PHASE], par[cap.SLIDE], par[cap.CUT_FIELD] = ob.STICK, 0.0, cap.CUT
    n = y0.size
    capacity = ok._FIRST_CAPACITY if keep else 1
    warp, steps = ok._empty_store(n + 1, capacity), ok._empty_store(n, capacity)
    pieces = np.zeros((ok.MAX_PHASES, 8))
    sigma, probe = ok._touch_phase(y0, rtol, atol, par)
    phase, teeth = ob.STICK, 0
    if sigma != ob.STICK:  # the probe's history is not kept: the touch's state goes on
        phase, teeth = slide_phase(sigma, probe.copy(), par, teeth)
    t, y, touch = 0.0, y0.copy(), True
    for k in range(ok.MAX_PHASES):
        par[ob.PHASE], par[cap.SLIDE] = _sign(phase), abs(phase)
        w0, s0 = warp[0], steps[0]
        status, switch, hit, hit_j, y_hit, warp, steps, failed = ok._piece(
            t, y, touch, rtol, atol, par, warp, steps, keep
        )
        if status != ok.STATUS_OK:
            return status, failed, y, pieces, k, warp, steps
        if hit_j < 0:
            return ok.STATUS_OPEN, t + ok.PIECE_LENGTH, y, pieces, k, warp, steps
        pieces[k, 0], pieces[k, 1], pieces[k, 2], pieces[k, 3] = t, hit, _sign(phase), switch
        pieces[k, 4], pieces[k, 5], pieces[k, 6], pieces[k, 7] = w0, warp[0], s0, steps[0]
        y, t, touch = y_hit, hit, False
        if hit_j == 0:
            return ok.STATUS_OK, math.nan, y, pieces, k + 1, warp, steps
        if phase == ob.STICK:
            phase, teeth = slide_phase(1 if hit_j == 1 else -1, y, par, teeth)
        else:
            phase, teeth = after_slide(phase, hit_j, y, par, teeth)
    return ok.STATUS_CHATTER, t, y, pieces, ok.MAX_PHASES, warp, steps
