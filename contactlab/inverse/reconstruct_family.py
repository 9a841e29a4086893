"""The contact's peak force and duration read with its contact family.

The largest value of a regularised solution is a biased reader of the peak force: the
regularisation rounds the top down, the noise left in the solution pushes its largest
value up, and neither is known for one record (``docs/campaign.md``, "Both traced
causes, followed up": 1 MHz records read 5-6.5 % off at 30-100 sigma where the law's
Cramer-Rao bound allows about a third of that). Where the contact's family is known (a
campaign reads it on each record's strongest impacts,
:attr:`dem_check.campaign.detection.Detection.contact_family`), the force is
``A h((t - t0) / tau)`` with the family's unit shape ``h``
(:func:`contactlab.inverse.lobe_model.force_shape`): fitted through the sensor to the
signal by :func:`contactlab.inverse.lobe_onset.fit_lobe` (generalised least squares
under an autoregressive model of the quiet samples, a line for what the baseline left),
its peak is ``A`` and its contact time ``tau``, both efficient estimates when the family
is right. The fit starts from the reconstruction's own reading (its start and duration),
so it costs one simplex, not a scan.

References
----------
Kay S.M. (1993) Fundamentals of Statistical Signal Processing: Estimation Theory.
Prentice Hall, ch. 7 (the maximum-likelihood estimate is asymptotically efficient).
"""

import dataclasses

import numpy as np

from contactlab.errors import ParameterError
from contactlab.inverse.lobe_onset import fit_lobe, force_shape
from contactlab.inverse.noise_colour import fit_ar_noise

__all__ = ["family_metrics", "family_reading"]


def family_metrics(t, y, sensor, family, metrics, noise, quiet):
    """The reconstruction's pulse metrics with the peak, the edges and the contact time
    of the contact family fitted to the signal.

    Parameters
    ----------
    t, y : numpy.ndarray
        Time [s] (uniform) and the signal [N] less its baseline.
    sensor : Sensor
        The moving sensor.
    family : (str, float)
        The family's name (:data:`contactlab.inverse.lobe_onset.FAMILIES`) and damping
        ratio [-].
    metrics : PulseMetrics
        The reconstruction's (its start, peak time and duration start the fit).
    noise : float
        The signal's noise standard deviation [N].
    quiet : numpy.ndarray
        Consecutive quiet samples [N]: the noise's autoregressive model (white when
        they are too few to fit one).

    Returns
    -------
    metrics : PulseMetrics
        ``metrics`` with ``peak`` = ``A`` [N], ``start`` = ``t0``, ``end`` = ``t0 +
        tau``, ``duration`` = ``tau`` [s] and ``peak_time`` the shape's top [s]; the
        impulse and rise time stay the reconstruction's.
    fit : LobeFit
        The fit (its chi-squared and samples say how well the family holds).

    Raises
    ------
    ParameterError
        If the fit fails (:func:`contactlab.inverse.lobe_onset.fit_lobe`).
    """
    name, damping = family
    try:
        model = fit_ar_noise(quiet)
    except ParameterError:  # too few quiet samples: white noise
        model = None
    # the touch cannot follow the force's top; the fit starts at the reconstruction's
    guess = (metrics.peak_time, metrics.duration)
    fit = fit_lobe(
        t,
        y,
        sensor,
        guess,
        noise,
        name,
        damping,
        noise_model=model,
        start=(metrics.start, metrics.duration),
    )
    u, h = force_shape(name, float(damping))
    read = dataclasses.replace(
        metrics,
        start=fit.onset,
        end=fit.onset + fit.duration,
        duration=fit.duration,
        peak=fit.amplitude,
        peak_time=fit.onset + fit.duration * float(u[int(np.argmax(h))]),
    )
    return read, fit


def family_reading(t, y, sensor, family, metrics, noise, quiet):
    """:func:`family_metrics`, or the reconstruction's ``metrics`` where the fit fails;
    with what :func:`contactlab.inverse.reconstruct_force` reports of it.

    Returns
    -------
    metrics : PulseMetrics
    parameters : dict
        ``peak_reading`` (``"family fit"``, or ``"largest value"`` with the reason the
        fit failed), ``largest_value [N]`` (the regularised force's largest value), and
        for a fit ``regularised_contact [s]`` (the regularised force's own contact,
        ``[start, end]``), its ``family_chi_squared [-]`` and ``family_samples [-]``.
    """
    out = {"largest_value [N]": float(metrics.peak)}
    try:
        read, fit = family_metrics(t, y, sensor, family, metrics, noise, quiet)
    except ParameterError as exc:
        return metrics, {**out, "peak_reading": f"largest value (the family's fit failed: {exc})"}
    return read, {
        **out,
        "regularised_contact [s]": [float(metrics.start), float(metrics.end)],
        "peak_reading": "family fit",
        "family_chi_squared [-]": fit.chi_squared,
        "family_samples [-]": fit.samples,
    }
