"""Reconstruct the true contact force S2(t) from a sensor signal S1(t).

The sensor is the linear filter ``S1/S2 = (c1 s + k1) / (m1 s**2 + c1 s + k1)``, which
depends only on its resonance ``f1`` and damping ratio ``zeta1``. Two estimates of S2:

``"tikhonov"`` (default)
    Regularised deconvolution. The force is piecewise linear on a grid inside the
    contact window and zero outside it; the signal is exactly (first-order hold) the
    sensor's response to it, a Toeplitz matrix ``H``. The estimate minimises
    ``||H f - s||**2 + lambda**2 ||D f||**2`` with ``D`` the first difference, subject to
    ``f >= 0``. ``lambda`` is chosen on the unconstrained problem by generalised
    cross-validation or by the discrepancy principle, then the non-negative problem is
    solved once.
``"inverse"``
    Band-limited exact inverse: ``S2 = S1 + m1 x1''`` with ``x1 = S1 / (c1 s + k1)``,
    after a zero-phase Butterworth low-pass of the signal.

The contact window, the baseline and the noise are read from the signal (see
:func:`reconstruct_force`).
"""

import math

import numpy as np
from scipy import linalg
from scipy.optimize import nnls

from contactlab import signals
from contactlab.blas import with_one_blas_thread
from contactlab.bodies import Sensor
from contactlab.entry_checks import check_flag
from contactlab.errors import ParameterError
from contactlab.inverse._signal import BASELINE_MIN_SAMPLES, check_window, uniform_signal
from contactlab.inverse.contact_edges import (
    SIGNIFICANCE_SIGMAS,
    THRESHOLD_FRACTION,
    THRESHOLD_SIGMAS,
    flank_shapes,
    level_edges,
    significant_edges,
    tikhonov_std,
)
from contactlab.inverse.noise_colour import (
    NOISE_MODELS,
    block_noise_model,
    describe_model,
    ringing_residual,
    whiten_problem,
)
from contactlab.inverse.pulse import pulse_baseline
from contactlab.inverse.reconstruct_family import family_reading
from contactlab.inverse.reconstruct_inverse import band_limited_inverse
from contactlab.inverse.reconstruction import ForceReconstruction
from contactlab.inverse.regularization import CRITERIA, StandardForm
from contactlab.inverse.sampling import check_samples_per_lobe
from contactlab.validation import check_choice, check_count, check_number

__all__ = ["CONTACT_EDGES", "CRITERIA", "METHODS", "ForceReconstruction", "reconstruct_force"]

DEFAULT_MAX_UNKNOWNS = 400
"""Default largest number of force values in the Tikhonov problem (sets the grid step)."""

DEFAULT_NOISE_MODEL = "ar"
"""Default noise model of the Tikhonov reconstruction (:data:`NOISE_MODELS`): an
autoregressive model fitted on the baseline window, the problem whitened with it
(generalised least squares; :mod:`contactlab.inverse.noise_colour`)."""

ROWS_AFTER_WINDOW = 3.0
"""Sensor periods of free ringing after the window used as data. The ringing is fixed
by the sensor state at the window's end (two numbers), so a few periods carry its
information; more only enlarge the matrix."""

ONSET_SIGMAS = 5.0
"""Onset threshold in baseline standard deviations (a baseline sample exceeds 5 sigma
with probability 6e-7)."""


# ---------------------------------------------------------------------------
# The sensor as a discrete linear operator
# ---------------------------------------------------------------------------
def _state_space(sensor):
    """Sensor in force units: state (k1 x1, k1 v1), input S2, output S1."""
    w, zeta = sensor.angular_frequency, sensor.damping_ratio
    a = np.array([[0.0, 1.0], [-(w**2), -2.0 * zeta * w]])
    return a, np.array([[0.0], [w**2]]), np.array([[1.0, 2.0 * zeta / w]]), np.zeros((1, 1))


def _powers(matrix, vector, count):
    """``[matrix**k @ vector for k in range(count)]`` as rows, by doubling (vectorised)."""
    out = vector[None, :]
    power = matrix
    while out.shape[0] < count:
        out = np.vstack([out, out @ power.T])
        power = power @ power
    return out[:count]


def _hat_response(sensor, dt, steps, count):
    """Sensor signal [N] at ``dt`` spacing after a unit triangular force pulse.

    The pulse rises linearly from 0 at ``-steps*dt`` to 1 N at 0 and falls back to 0 at
    ``steps*dt`` (a hat basis function of a piecewise-linear force); the response is
    exact (first-order-hold discretisation, scipy ``cont2discrete(method="foh")``).

    Parameters
    ----------
    sensor : Sensor
        A moving (not rigid) sensor; only its resonance and damping ratio matter.
    dt : float
        Sample interval [s].
    steps : int
        Half-width of the hat in samples.
    count : int
        Number of samples returned.

    Returns
    -------
    numpy.ndarray
        Response at offsets ``m = -steps, ..., count - steps - 1`` samples from the
        hat's centre.
    """
    from scipy.signal import cont2discrete  # scipy.signal is slow to import: only here

    ad, bd, cd, dd, _ = cont2discrete(_state_space(sensor), dt, method="foh")
    states = _powers(ad, bd[:, 0], count)
    # response to the one-sample hat: D at k = 0, C A^(k-1) B after
    unit = np.concatenate([dd[0], states[:-1] @ cd[0]])
    weights = 1.0 - np.abs(np.arange(-steps + 1, steps)) / steps
    return np.concatenate([[0.0], np.convolve(unit, weights)[: count - 1]])


def _toeplitz(sensor, dt, q, rows, columns):
    """Block-mean signal of each hat: ``H[i, j]`` for blocks of q samples, knots q apart."""
    g = _hat_response(sensor, dt, q, (rows + 2) * q)
    sums = np.concatenate([[0.0], np.cumsum(g)])
    # block k rows after the knot starts k*q samples after the hat centre, index k*q + q
    lag = np.arange(-1, rows)
    means = (sums[(lag + 2) * q] - sums[(lag + 1) * q]) / q
    first_row = np.zeros(columns)
    first_row[: min(2, columns)] = means[1::-1][: min(2, columns)]
    return linalg.toeplitz(means[1:], first_row)


# ---------------------------------------------------------------------------
# The two methods
# ---------------------------------------------------------------------------
def _tikhonov(t, y, dt, sensor, noise, window, options):
    max_unknowns, criterion = options["max_unknowns"], options["regularization"]
    ta, tb = window
    ia = int(np.searchsorted(t, ta))
    span = (tb - t[ia]) / dt
    q = options.get("step") or max(1, math.ceil(span / (max_unknowns - 1)))
    columns = int(span // q) + 1
    last = min(t[-1], tb + ROWS_AFTER_WINDOW * sensor.period)
    rows = int((last - t[ia]) / dt + 1) // q
    if columns < 2 or rows <= columns:
        raise ParameterError(
            f"contact window ({ta:.6g}, {tb:.6g}) s leaves {columns} force values and "
            f"{rows} data blocks; the record must extend past the window"
        )
    h = _toeplitz(sensor, dt, q, rows, columns)
    data = y[ia : ia + rows * q].reshape(rows, q).mean(axis=1)
    model = block_noise_model(options["quiet"], q, options["noise_model"])
    h, data, block_noise = whiten_problem(model, h, data, y[:ia], q, noise / math.sqrt(q))
    coloured = model is not None and model.order > 0
    lam = CRITERIA[criterion](StandardForm(h, data, smoothest=coloured), block_noise)
    penalty = lam * np.diff(np.eye(columns), axis=0)
    values, _ = nnls(np.vstack([h, penalty]), np.concatenate([data, np.zeros(columns - 1)]))
    knots = t[ia] + np.arange(-1, columns + 1) * q * dt
    force = np.interp(t, knots, np.concatenate([[0.0], values, [0.0]]))
    # the unconstrained solution's spread, between the knots as the force is
    std = np.interp(t, knots, np.concatenate([[0.0], tikhonov_std(h, penalty, block_noise), [0.0]]))
    params = {
        "regularization": criterion,
        "lambda": float(lam),
        "grid_step [s]": q * dt,
        "unknowns": columns,
        "data_blocks": rows,
        **describe_model(model),
    }
    return force, params, std


METHODS = {"tikhonov": _tikhonov, "inverse": band_limited_inverse}
"""Reconstruction methods: name -> implementation."""

CONTACT_EDGES = ("significance", "level")
"""How the contact's start and end are read (``contact_edges`` of
:func:`reconstruct_force`)."""

DEFAULT_CONTACT_EDGES = "significance"
"""Default of ``contact_edges``: where the force is significantly above zero, the edges
extrapolated along the flanks (:mod:`contactlab.inverse.contact_edges`)."""


def _widened(t, y, dt, sensor, noise, window, options, solved):
    """The Tikhonov solution on a window started earlier, when the force is significant
    at the default window's first knot (its contact started before the window).

    The default window starts a quarter sensor period before the onset, the first
    crossing of 5 baseline standard deviations; at a peak of 20 standard deviations that
    is a quarter of the way up a smooth pulse, and the contact's start was cut (a
    half-sine of 100 us at 1 MHz, 5 % noise: the window started 3 us late and the
    contact came out 3 % short). The window is started once more, as far before its
    first knot as the peak is after it (not before the record), on the same grid step.
    ``solved`` is the first solution's ``(force, parameters, spread)``; returns the
    window start [s] and the solution on the window used.
    """
    force, params, std = solved
    ta, tb = window
    ia = int(np.searchsorted(t, ta))
    q = max(1, round(params["grid_step [s]"] / dt))
    head = slice(ia, ia + q + 1)  # the window's first grid step
    if ia == 0 or not np.any(force[head] > SIGNIFICANCE_SIGMAS * std[head]):
        return ta, solved  # the noise, not the window, ends the contact on the left
    top = int(np.argmax(force))
    earlier = max(float(t[0]), float(2.0 * t[ia] - t[top]))
    wider = {**options, "step": q}
    return earlier, METHODS["tikhonov"](t, y, dt, sensor, noise, (earlier, tb), wider)


def _check_sensor(sensor):
    if not isinstance(sensor, Sensor):
        raise ParameterError(f"sensor must be a contactlab.Sensor; got {type(sensor).__name__}")
    if sensor.is_rigid:
        raise ParameterError("sensor is rigid: its signal is the contact force (S1 == S2)")
    return sensor


@with_one_blas_thread
def reconstruct_force(
    t,
    signal,
    sensor,
    method="tikhonov",
    *,
    baseline_window=None,
    window=None,
    regularization=None,
    cutoff=None,
    max_unknowns=None,
    threshold=None,
    crosstalk=True,
    noise_model=None,
    contact_edges=None,
    flank_exponent=1.0,
    contact_family=None,
    first_touch=True,
    read_family=True,
):
    """Estimate the contact force S2(t) from the sensor signal S1(t).

    Parameters
    ----------
    t : array_like
        Time [s], uniformly sampled, with a pre-trigger baseline (see
        ``baseline_window``).
    signal : array_like
        Sensor signal [N] (convert volts with the sensitivity first).
    sensor : Sensor
        The sensor; only its resonance and damping ratio enter (identify them with
        :func:`contactlab.inverse.identify_sensor`).
    method : {"tikhonov", "inverse"}, default "tikhonov"
        Regularised deconvolution or band-limited inverse filter (module docstring).
    baseline_window : (float, float), optional
        Pre-trigger window ``[start, end)`` [s] giving the noise and the onset. Default:
        the samples before ``t = 0``, or in a record without them the samples before the
        pulse it finds (:func:`contactlab.inverse.pulse.pulse_baseline`). The baseline
        removed is a line fitted on the window's last 8 sensor periods before the pulse
        and, with the sensor's free ringing, on 16 periods after the contact (drift and
        wander removed; ``status`` and ``notes`` say when it cannot be trusted).
    window : (float, float), optional
        Contact window ``(ta, tb)`` [s] outside which the force is zero (Tikhonov),
        within the record. Default: from a quarter sensor period before the onset (the
        first crossing of 5 baseline standard deviations, which the sensor's rise delays
        by less than a quarter period; not before the record's first sample) to one
        lobe-length after the end of the signal's largest lobe (a contact cannot outlast
        that, see :func:`contactlab.inverse.identify_sensor`).
    regularization : {"gcv", "discrepancy"}, optional
        How lambda is chosen (Tikhonov only; default ``"gcv"``). ``"discrepancy"``
        sets the residual to the baseline noise. GCV is the default because the
        discrepancy principle is unstable for an impact: a smooth pulse has few
        effective parameters compared with the random spread ``sqrt(2 m)`` of the noise
        energy over ``m`` data, so a few per cent error in the noise moves lambda by
        decades (measured on the hard grain of ``docs/inverse.md``: peak errors up to
        62 % over 8 noise seeds, against at most 3.9 % with GCV).
    cutoff : float, optional
        Low-pass cutoff [Hz] of the inverse filter (inverse only); default twice the
        resonance (:data:`contactlab.inverse.reconstruct_inverse.DEFAULT_CUTOFF_FACTOR`).
        Zero-phase Butterworth of order 4.
    max_unknowns : int, optional
        Largest number of force values, >= 2 (Tikhonov only; default
        :data:`DEFAULT_MAX_UNKNOWNS` = 400); the signal is averaged over blocks of ``q``
        samples and the force grid step is ``q`` samples.
    threshold : float, optional
        Level [N] at which the metrics read the pulse (``contact_edges="level"``).
        Default: 2 % of the reconstructed peak, or five standard deviations of the
        reconstruction over the baseline window if that is larger.
    crosstalk : bool, default True
        Remove the structure's crosstalk with the baseline (modes found on the ringing
        after the contact; :func:`contactlab.inverse.pulse.pulse_baseline`), the modes
        removed named in ``notes``; off for a record already rid of it (a campaign's).
    first_touch : bool, default True
        Fit the pulse's first touch on its whole lobe
        (:func:`contactlab.inverse.lobe_onset.single_onset`; 0.6 s of CPU) and report it
        as ``first_touch [s]``, ``first_touch_bound [s]`` and ``first_touch_shape``; off
        where the onset is fitted elsewhere (a campaign's, per record).
    read_family : bool, default True
        With ``contact_family``: read the peak and the contact from the family's fit.
    noise_model : {"ar", "white"}, optional
        The noise the Tikhonov estimate assumes (default :data:`DEFAULT_NOISE_MODEL`,
        ``"ar"``). ``"ar"``: an autoregressive model of the block means over the
        baseline window (Burg, order by BIC, kept only if it differs from white noise
        at the 1 % level; :mod:`contactlab.inverse.noise_colour`) whitens the data and
        the sensor matrix before lambda is chosen and the force solved (generalised
        least squares); a record without a baseline before the pulse (a short
        pre-trigger) reads the model after the contact, on what the sensor's free
        ringing and a line leave; with white noise or fewer than 20 blocks of quiet
        samples it is the white model.
        ``parameters["noise_model"]`` says which was used (``"AR(p)"`` with its
        coefficients and innovation, or ``"white"``). ``"white"``: ordinary least
        squares, as before coloured noise was modelled.
    contact_edges : {"significance", "level"}, optional
        How the contact's start and end are read from the reconstructed force.
        ``"significance"``: the run of samples around the peak where the force is more
        than 3 of its own standard deviations above zero (the noise propagated through
        the Tikhonov solution, ``noise**2 G G^T``; the inverse filter's spread over the
        baseline), each edge where a line fitted to its flank between 10 % and 50 % of
        the peak reaches zero (:func:`contactlab.inverse.contact_edges.significant_edges`).
        ``"level"``: the first lobe above ``threshold``, ended at a dip under 5 % of the
        peak (as before; taken whenever ``threshold`` is given).
        ``parameters["contact_edges"]`` says which was used. Default
        :data:`DEFAULT_CONTACT_EDGES`, ``"significance"``.
    flank_exponent : float, default 1.0
        Power law of the force at the contact's edges, ``F ~ |t - t_edge|**p`` [-], in
        [1, 3] (``"significance"`` only): the flanks' lines are fitted to ``F**(1/p)``.
        1 for a linear or viscoelastic law, 1.5 for Hertz (with 1 a Hertz contact comes
        out 6-8 % short).
    contact_family : (str, float), optional
        The contact's family and damping ratio ``(name, zeta [-])``
        (:data:`contactlab.inverse.lobe_onset.FAMILIES`; a campaign reads it per record
        with its onsets) (``"significance"`` only): the flanks' power laws and the
        force's jump at the touch from the family's force
        (:func:`contactlab.inverse.contact_edges.family_flanks`), instead of
        ``flank_exponent``: a damped contact's start at half its force's jump. With
        ``read_family`` (default) the metrics' peak, edges and duration are then the
        family's force fitted to the signal (:mod:`contactlab.inverse.reconstruct_family`;
        ``parameters["peak_reading"]`` says which was used).

    Returns
    -------
    ForceReconstruction

    Raises
    ------
    ParameterError
        Bad arguments, a baseline with fewer than 16 samples or without noise, no
        onset, a window the record does not extend past (or a record that ends inside
        the pulse), a record too coarse to reconstruct (a first lobe under
        :data:`~contactlab.inverse.sampling.MIN_SAMPLES_PER_CONTACT` samples, the
        campaign's rule), or (discrepancy) a noise level the model cannot match.

    Notes
    -----
    Tikhonov: the force is ``sum_j f_j phi_j(t)`` with hat functions ``phi_j`` on a grid
    of step ``q dt`` inside the window; each column of ``H`` is the exact block-mean
    response to one hat. Lambda is chosen for the unconstrained problem (filter factors
    of one SVD), then ``f >= 0`` is imposed by ``scipy.optimize.nnls`` on the stacked
    system ``[H; lambda D] f = [s; 0]``. With an AR noise model ``A(z)`` both ``H`` and
    ``s`` are filtered by ``A(z)`` first (its first rows started on the baseline's block
    means before the window, where ``H`` is zero), so GCV and the discrepancy principle
    see white noise of the innovation's standard deviation. GCV assumes white noise:
    with 1/f noise as large as the white noise it took a lambda of 0.18 where the
    whitened problem takes 0.79, and the peak came out +7.0 % instead of +0.6 %
    (``docs/inverse.md``).
    Inverse: ``S2 = S1 + u'' / w1**2`` with ``u = S1 / (1 + 2 zeta1 s / w1)``; ``u''`` by
    the 3-point stencil, accurate to ``(w dt)**2 / 12`` below the cutoff.

    References
    ----------
    Hansen P.C. (1994) Regularization Tools. Numer. Algorithms 6, 1-35.
    DOI 10.1007/BF02149761 (GCV, discrepancy principle, standard form).
    Elden L. (1977) Algorithms for the regularization of ill-conditioned least squares
    problems. BIT 17, 134-145. DOI 10.1007/BF01932285
    Kariya T., Kurata H. (2004) Generalized Least Squares. Wiley (prewhitening).
    Eichstaedt S., Elster C., Esward T.J., Hessling J.P. (2010) Deconvolution filters
    for the analysis of dynamic measurement processes: a tutorial. Metrologia 47,
    522-533. DOI 10.1088/0026-1394/47/5/003
    """
    t, y, dt = uniform_signal(t, signal)
    sensor = _check_sensor(sensor)
    method = check_choice("method", method, tuple(METHODS))
    read_family = check_flag("read_family", read_family)
    for name, value, owner in (
        ("cutoff", cutoff, "inverse"),
        ("regularization", regularization, "tikhonov"),
        ("max_unknowns", max_unknowns, "tikhonov"),
        ("noise_model", noise_model, "tikhonov"),
    ):
        if value is not None and method != owner:
            raise ParameterError(f"{name} applies to method={owner!r}, not {method!r}")
    if cutoff is not None:
        cutoff = check_number("cutoff", cutoff, low=0.0, high=0.5 / dt, high_open=True, unit="Hz")
    options = {
        "regularization": check_choice("regularization", regularization or "gcv", tuple(CRITERIA)),
        "noise_model": check_choice(
            "noise_model", noise_model or DEFAULT_NOISE_MODEL, NOISE_MODELS
        ),
        "cutoff": cutoff,
        "max_unknowns": check_count(
            "max_unknowns", DEFAULT_MAX_UNKNOWNS if max_unknowns is None else max_unknowns, 2
        ),
    }
    flank_exponent = check_number(
        "flank_exponent", flank_exponent, low=1.0, high=3.0, low_open=False
    )
    flanks = flank_shapes(flank_exponent, contact_family)
    contact_edges = check_choice(
        "contact_edges", contact_edges or DEFAULT_CONTACT_EDGES, CONTACT_EDGES
    )
    if threshold is not None:
        threshold = check_number("threshold", threshold, low=0.0, unit="N")
        contact_edges = "level"  # a level the user gave is read as given
    pulse = pulse_baseline(
        t, y, sensor, baseline_window, ONSET_SIGMAS, crosstalk=crosstalk, first_touch=first_touch
    )
    y = y - pulse.values
    noise, onset, base = pulse.noise, pulse.onset, pulse.window
    quiet = y[signals.in_window(t, base)]
    if quiet.size < BASELINE_MIN_SAMPLES:  # a short pre-trigger: the noise after the contact
        quiet = ringing_residual(t, y, pulse.post, sensor)
    options["quiet"] = quiet
    check_samples_per_lobe(t, y, ONSET_SIGMAS * noise)
    ta, tb = check_window("window", pulse.contact if window is None else window)
    if not float(t[0]) <= ta < float(t[-1]):
        raise ParameterError(
            f"window start must lie within the record [{t[0]:.6g}, {t[-1]:.6g}) s; got {ta!r}"
        )
    force, params, std = METHODS[method](t, y, dt, sensor, noise, (ta, tb), options)
    if std is not None and window is None and contact_edges == "significance":
        solved = (force, params, std)
        ta, (force, params, std) = _widened(t, y, dt, sensor, noise, (ta, tb), options, solved)
    # the reconstruction's own noise, over the baseline before the contact window
    in_base = (t >= base[0]) & (t < min(base[1], ta))
    spread = float(np.std(force[in_base], ddof=1)) if in_base.sum() > 1 else 0.0
    if float(force.max()) <= 0.0:
        raise ParameterError("the reconstructed force is zero everywhere: no pulse found")
    if contact_edges == "significance":
        std = np.full(t.size, spread) if std is None else std
        metrics = significant_edges(t, force, std, **flanks)
        # the level the force's peak had to pass; the edges are the flanks' lines at zero
        threshold = SIGNIFICANCE_SIGMAS * float(std[np.argmax(force)])
        if contact_family is not None and read_family:
            metrics, read = family_reading(t, y, sensor, contact_family, metrics, noise, quiet)
            params.update(read)
    else:
        if threshold is None:
            threshold = max(THRESHOLD_FRACTION * float(force.max()), THRESHOLD_SIGMAS * spread)
        metrics = level_edges(t, force, threshold)
    params.update(
        {
            "window [s]": [ta, tb],
            "baseline_window [s]": list(base),
            "baseline [N]": float(np.interp(onset, t, pulse.values)),
            "baseline_drift [N]": pulse.drift,
            "post_window [s]": list(pulse.post),
            "noise [N]": noise,
            "onset [s]": onset,
            **(pulse.first_touch.parameters() if first_touch else {}),
            "contact_edges": contact_edges,
            "threshold [N]": threshold,
            "sensor_resonance [Hz]": sensor.resonance,
            "sensor_damping_ratio [-]": sensor.damping_ratio,
        }
    )
    return ForceReconstruction(
        t=t,
        signal=y,
        force=force,
        method=method,
        parameters=params,
        metrics=metrics,
        status=pulse.status,
        notes=pulse.notes,
    )
