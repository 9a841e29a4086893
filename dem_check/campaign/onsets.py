"""The first touch of each impact of a record (:mod:`contactlab.inverse.lobe_onset`).

The detector's onset is the smoothed signal's crossing of five noise sigmas
(:mod:`dem_check.campaign.detection`, step 4), which lags the touch by the time the signal
takes to reach it. Here each analysed impact's whole first lobe is fitted with a contact
family's force pushed through the sensor; the family and its damping are chosen once per
record on its most significant impacts, since every impact of a record has the same
contact law (:func:`contactlab.inverse.lobe_onset.lobe_family`). Where an impact's fit
fails it keeps the crossing, and its ``reason`` says why.

Each fitted onset carries its uncertainty: the standard deviation of the fit's onset
under the record's white and 1/f noise (:func:`dem_check.campaign.local.record_noise`,
the covariance the local baselines use; :attr:`contactlab.inverse.lobe_onset.LobeFit.uncertainty`),
or under white noise of the baseline window's spread where the record has too few quiet
samples to estimate it; ``nan`` for a crossing.
"""

import dataclasses

import numpy as np

from contactlab.errors import ParameterError
from contactlab.inverse.lobe_onset import NoContact, fit_lobe, lobe_family
from contactlab.inverse.noise_colour import fit_ar_noise
from dem_check.campaign.local import record_noise

__all__ = [
    "CONFIRM_SIGMAS",
    "FAMILY_IMPACTS",
    "FAMILY_NOISE_MODEL",
    "LOBE_LEVEL",
    "LOBE_SPAN",
    "NOISE_MODEL",
    "NO_CONTACT",
    "SMOOTHING_REACH",
    "first_touches",
    "record_onsets",
]

CONFIRM_SIGMAS = 10.0
"""A candidate under this significance [-] is an impact only if its lobe fit finds a
contact: issue 22 asks for every impact of 10 noise sigmas and more; between the
detection threshold and this, a bump of 1/f noise can pass the threshold (seed 109 of
``benchmarks/bench_weak_impacts.py``: 7.25 local sigmas against 7.0, 0.6 ms before the
record's end, where the fit's best contact peaks at 0.031 N under a noise of 0.048 N)."""

NO_CONTACT = "no contact"
"""Status of a candidate under :data:`CONFIRM_SIGMAS` whose lobe fit found no contact:
listed with why (:attr:`dem_check.campaign.detection.Detection.unconfirmed`), not an
impact."""

FAMILY_IMPACTS = 4
"""The contact family is read on this many of a record's most significant impacts [-]
(18 fits each: 1.0-1.4 s of CPU per record)."""

LOBE_LEVEL = 0.3
"""The first guess of the contact's duration is the time the smoothed signal spends
above this fraction of its peak [-], over :data:`LOBE_SPAN`."""

LOBE_SPAN = 0.8
"""The fraction of a contact's duration its force spends above :data:`LOBE_LEVEL` of its
peak [-] (a half-sine: ``1 - 2 asin(0.3) / pi = 0.81``; the fit refines it)."""


NOISE_MODEL = "white"
"""The lobe fit's noise model, one of
:data:`contactlab.inverse.noise_colour.NOISE_MODELS`: ``"white"`` fits as if the noise
were white; ``"ar"``, an autoregressive model fitted on each impact's baseline window
(the quiet samples before it, less the running baseline), whitens the fit and gives the
bound under the coloured noise. Measured on ``bench_onsets.py``'s records (1/f noise as
large as the white noise) whitening changed the largest errors by -15 % to +9 %, within
their spread between records (docs/campaign.md, "Onsets"): white is kept, cheaper."""

FAMILY_NOISE_MODEL = "ar"
"""The noise model the contact family and damping are read under (whatever
:data:`NOISE_MODEL` the onsets are then fitted with): ``"ar"``, each impact's baseline
window's autoregressive model. A damping is kept by its chi-squared gain
(:func:`contactlab.inverse.lobe_onset.damping_resolved`), a likelihood argument that
holds where the residual is white: under white-noise weights the 1/f noise and the
plate's crosstalk ringing are not, and two undamped Hertz records under 2 % crosstalk
gained 7.5 and 12.1 with a damping of 0.019 and 0.024 (every onset 6-14 samples late);
whitened, 2.3 and 3.7 (docs/campaign.md, "Accuracy on realistic records with a Hertz
contact")."""

SMOOTHING_REACH = 4.0
"""The touch is sought up to this many standard deviations of the detector's Gaussian
kernel after the crossing [-]: the smoothed signal of a sharp rise leads it. The
smoothed ramp ``r (s - t0)`` is ``r sigma (phi(a) - a Q(a))`` at ``a`` kernel sigmas
before the touch: 4e-4 ``r sigma`` at 3, 7e-6 at 4; with ``r sigma`` about a quarter of
the peak (a 40 kHz sensor's rise of 6 us, a kernel of 1.66 us) a crossing of the
smoothed noise's five sigmas lies 4 kernel sigmas early only beyond 1e5 sigmas. At 5 MHz
with a linear contact's force step the crossing led the touch by up to 3.3 samples at
60-110 sigma, and a search that ended at it had the fit of the right family fail."""


def _lobe(detection, window, sensor, noise_model=NOISE_MODEL):
    """One impact as :func:`contactlab.inverse.lobe_onset.fit_lobe` takes it:
    ``(t, y, (latest touch, duration guess), noise, noise model)``, the latest touch the
    crossing plus :data:`SMOOTHING_REACH` kernel sigmas, the noise model
    ``noise_model`` (a name of :data:`contactlab.inverse.noise_colour.NOISE_MODELS`) on
    the baseline window (None: white)."""
    part = slice(window.first, window.stop)
    t = np.asarray(detection.record.t[part])
    y = np.asarray(detection.record.values[part], dtype=float)
    smooth = np.asarray(detection.smoothed.values[part])
    base = window.baseline_window
    in_base = (t >= base[0]) & (t < base[1])
    raw = np.asarray(detection.signal.values[part])
    noise = float(np.std(raw[in_base], ddof=1))
    model = None
    if noise_model == "ar":
        try:
            model = fit_ar_noise(raw[in_base])
        except ParameterError:  # too few quiet samples: white noise assumed
            model = None
    above = np.flatnonzero((t >= window.onset) & (smooth >= LOBE_LEVEL * window.peak))
    if above.size < 2:
        raise ParameterError(f"the impact at {window.onset:.6g} s does not rise to its peak")
    # the first run above the level, gaps shorter than a sensor period bridged (a damped
    # contact's force step rings the sensor down through the level): the first lobe
    period = round(sensor.period / float(t[1] - t[0]))
    gaps = np.flatnonzero(np.diff(above) > period)
    run = above[: gaps[0] + 1] if gaps.size else above
    length = float(t[run[-1]] - t[run[0]]) / LOBE_SPAN
    latest = window.onset + SMOOTHING_REACH * detection.floor.kernel
    return t, y, (latest, length), noise, model


def record_onsets(detection, windows, sensor, noise=None, family=None):
    """The fitted onsets of ``windows``, their uncertainties, and the contact family
    they share.

    Parameters
    ----------
    detection : Detection
    windows : list of ImpactWindow
    sensor : Sensor
    noise : ColouredNoise, optional
        The record's white and 1/f noise (:func:`dem_check.campaign.local.record_noise`):
        each onset's uncertainty under it; None: under white noise of the impact's
        baseline window's standard deviation.
    family : (str, float), optional
        The contact family and damping ratio read already on the record's other impacts
        (:attr:`Detection.contact_family`): not read again on ``windows``, and the
        uncertainties leave out the damping's error (it was read on other impacts).

    Returns
    -------
    onsets : list of float
        First touch [s] per window (its crossing where the fit failed).
    notes : list of str
        Empty where fitted; why not where the crossing was kept.
    family : str or None
        The family read on the :data:`FAMILY_IMPACTS` most significant impacts (None
        when none could be fitted: every impact keeps its crossing).
    damping : float or None
        Its damping ratio [-].
    uncertainties : list of float
        Standard deviation of each fitted onset [s] (``nan`` for a crossing).
    no_contact : list of bool
        Where the lobe fit found no contact
        (:class:`~contactlab.inverse.lobe_onset.NoContact`).
    """
    lobes, failed = [], {}
    for k, window in enumerate(windows):
        try:
            lobes.append(_lobe(detection, window, sensor))
        except ParameterError as error:
            lobes.append(None)
            failed[k] = str(error)
    strongest = sorted(
        (k for k, lobe in enumerate(lobes) if lobe is not None),
        key=lambda k: -windows[k].significance,
    )[:FAMILY_IMPACTS]
    try:
        if family is not None:
            (family, damping), strongest = family, []
        else:
            coloured = [_lobe(detection, windows[k], sensor, FAMILY_NOISE_MODEL) for k in strongest]
            family, damping = lobe_family(coloured, sensor)
    except ParameterError as error:  # no lobe could be fitted: every impact keeps its crossing
        note = f"onset: the 5-sigma crossing (no lobe of the record could be fitted: {error})"
        count = len(windows)
        crossings = [w.onset for w in windows]
        return crossings, [note] * count, None, None, [np.nan] * count, [False] * count
    onsets, notes, fits, no_contact = [], [], [], []
    for k, (window, lobe) in enumerate(zip(windows, lobes, strict=True)):
        try:
            if lobe is None:
                raise ParameterError(failed[k])
            t, y, guess, spread, noise_model = lobe
            if noise is None:  # white noise of the baseline window's spread
                covariance = np.zeros(t.size)
                covariance[0] = spread**2
            else:
                covariance = noise.autocovariance(t.size)
            fit = fit_lobe(
                t,
                y,
                sensor,
                guess,
                spread,
                family,
                damping,
                noise_model=noise_model,
                autocovariance=covariance,
            )
            onsets.append(fit.onset)
            notes.append("")
            fits.append(fit)
            no_contact.append(False)
        except ParameterError as error:
            no_contact.append(isinstance(error, NoContact))
            onsets.append(window.onset)
            notes.append(
                f"onset: the 5-sigma crossing (its lobe fit failed: {error}); no onset "
                "uncertainty is given for a crossing"
            )
            fits.append(None)
    return onsets, notes, family, damping, _uncertainties(fits, strongest), no_contact


def _uncertainties(fits, read_on):
    """Each fitted onset's standard deviation [s] (``nan`` where not fitted): its own
    noise's (the damping known) and that of the damping ratio read on the impacts
    ``read_on`` (indices), which moves every onset of the record the same way
    (:meth:`contactlab.inverse.lobe_model.LobeModel.damping_terms`: ``var = s**2 +
    shift**2 var(d) - 2 shift cov``, ``var(d) = sum noise / (sum information)**2``,
    ``cov = cross / sum information`` for an impact the damping was read on)."""
    shared = [fits[k].damping_terms for k in read_on if fits[k] is not None]
    information = sum(terms[1] for terms in shared)
    if not information > 0.0:  # no impact the damping was read on was fitted
        shared = []
    damping_variance = sum(terms[2] for terms in shared) / information**2 if shared else 0.0
    out = []
    for k, fit in enumerate(fits):
        if fit is None:
            out.append(np.nan)
            continue
        shift, _, _, cross = fit.damping_terms
        together = cross / information if k in read_on and shared else 0.0
        variance = fit.uncertainty**2 + shift**2 * damping_variance - 2.0 * shift * together
        out.append(float(np.sqrt(max(variance, 0.0))))  # a variance: >= 0 but for rounding
    return out


def first_touches(detection, sensor, statuses):
    """The detection's impacts, those with a status of ``statuses`` with their onset
    fitted (:func:`record_onsets`) and its ``onset_uncertainty`` [s] under the record's
    noise (:func:`dem_check.campaign.local.record_noise`); where the fit failed, the
    crossing is kept and the impact's ``reason`` says so. Returned as the
    :class:`Detection` fields ``impacts``, ``unconfirmed`` (the candidates under
    :data:`CONFIRM_SIGMAS` whose fit found no contact, status :data:`NO_CONTACT`) and
    ``contact_family``: the record's family and damping ratio ``(name, zeta [-])`` (None
    where none was read), with which the reconstruction reads its contact's edges
    (:mod:`dem_check.campaign.analysis`)."""
    chosen = [k for k, w in enumerate(detection.impacts) if w.status in statuses]
    if not chosen:
        return {"impacts": list(detection.impacts), "contact_family": None}
    noise = record_noise(detection, sensor)
    onsets, notes, family, damping, uncertainties, no_contact = record_onsets(
        detection, [detection.impacts[k] for k in chosen], sensor, noise
    )
    if noise is None:
        white = (
            "onset uncertainty: under white noise of the baseline's spread (too few quiet "
            "samples in the record to estimate its 1/f noise)"
        )
        notes = [note or white for note in notes]
    impacts, unconfirmed = list(detection.impacts), {}  # index: its "no contact" row
    rows = zip(chosen, onsets, notes, uncertainties, no_contact, strict=True)
    for k, onset, note, spread, no_lobe in rows:
        reason = "; ".join(r for r in (impacts[k].reason, note) if r)
        impacts[k] = dataclasses.replace(
            impacts[k], onset=onset, reason=reason, onset_uncertainty=spread
        )
        if no_lobe and impacts[k].significance < CONFIRM_SIGMAS:
            why = (
                f"not an impact: {impacts[k].significance:.3g} sigma, under "
                f"{CONFIRM_SIGMAS:g}, and no contact lobe fits it ({reason})"
            )
            unconfirmed[k] = dataclasses.replace(impacts[k], status=NO_CONTACT, reason=why)
    return {
        "impacts": [w for k, w in enumerate(impacts) if k not in unconfirmed],
        "unconfirmed": list(unconfirmed.values()),
        "contact_family": None if family is None else (family, damping),
    }
