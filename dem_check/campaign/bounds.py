"""How well an impact's numbers can be read under a realistic record's noise: the peak
signal and the impulse, and the contact's peak force and contact time.

The best linear unbiased estimator (BLUE) of a linear function ``c' beta`` of the
parameters of a linear model ``y = X beta + e``, ``Cov(e) = Sigma``, is generalised least
squares; its variance ``c' (X' Sigma^-1 X)^-1 c`` is the Cramer-Rao bound when the noise
is Gaussian (for a nonlinear model, of the model linearised at the truth). No unbiased
estimator that uses the same samples and the same model does better, so these
variances say which accuracy targets are reachable at all (``docs/campaign.md``,
"What accuracy is possible").

The noise is that of :func:`dem_check.campaign.realistic_record` (white, 1/f and mains
hum with random phases; :func:`noise_autocovariance`); drift is slow enough over the
~1 ms read to be a line (two parameters in every model). Three models of the impact's
signal, from the most to the least informed:

- ``"law"``: the signal of the true contact law with unknown velocity, parameters
  (a linear contact's stiffness and damping, Hertz's stiffness) and first touch
  (:func:`law_design`): the bound for an estimator that knows the law's family (the
  fit); the only model here that bounds the contact time, and the lowest bound of the
  peak contact force;
- ``"band"``: any signal whose spectrum over the contact window lies below a cutoff
  (a cosine series, :func:`band_design`), then the sensor's free ringing: the bound for
  an unbiased reading of the low-passed record;
- ``"free"``: any signal in the contact window (:func:`free_variance`): the bound for an
  estimator that assumes nothing of the pulse (the impulse only: a peak read on one
  free sample averages nothing).

For the contact force, ``"force band"`` (:func:`force_band_design`): any contact force
below a cutoff in the contact window (a cosine series), its signal that force through
the sensor: the bound for an unbiased reading of the peak force by a deconvolution of
that bandwidth that does not know the law.

References
----------
Kay S.M. (1993) Fundamentals of Statistical Signal Processing: Estimation Theory.
Prentice Hall, ch. 3 (Cramer-Rao bound) and 6 (BLUE, Gauss-Markov theorem).
"""

import math

import numpy as np
from scipy.linalg import cho_factor, cho_solve, solve_toeplitz, toeplitz

from contactlab.inverse.local_baseline import _ringing
from contactlab.inverse.noise_prediction import pink_autocovariance
from contactlab.laws.linear import LinearViscoelastic
from contactlab.solver.impact import simulate_impact

__all__ = [
    "LAW_READINGS",
    "band_design",
    "blue_variance",
    "force_band_design",
    "free_variance",
    "law_design",
    "noise_autocovariance",
]


LAW_READINGS = ("peak_sensor_force", "impulse", "peak_contact_force", "contact_time")
"""The readings whose gradients :func:`law_design` returns, in its columns' order."""


def noise_autocovariance(count, dt, white, effects, record_length):
    """Autocovariance of a realistic record's random noise at lags ``0 .. count-1``.

    Parameters
    ----------
    count, dt
        Lags [samples] and sample interval [s], as for
        :func:`contactlab.inverse.noise_prediction.pink_autocovariance`.
    white : float
        White noise standard deviation [N].
    effects : Effects
        Its ``pink`` [N] (1/f noise: power ``1/f`` from ``1/record_length`` to the
        Nyquist frequency, as :func:`dem_check.campaign.realistic_record` draws it),
        ``hum`` [N], ``mains`` [Hz] and ``harmonics`` (each a sine of random phase,
        autocovariance ``a**2 / 2 cos(w tau)``) are used; the other effects are not
        random noise.
    record_length : float
        Length of the record the 1/f noise was drawn on [s] (its lowest frequency).

    Returns
    -------
    numpy.ndarray
        ``count`` values [N**2].
    """
    lags = np.arange(count) * dt
    out = effects.pink**2 * pink_autocovariance(count, dt, record_length)
    out[0] += white**2
    for order, relative in enumerate((1.0, *effects.harmonics), start=1):
        amplitude = effects.hum * relative
        out += 0.5 * amplitude**2 * np.cos(2.0 * math.pi * order * effects.mains * lags)
    return out


def blue_variance(autocovariance, design, functionals):
    """Variances of the BLUE of ``c' beta`` for each column ``c`` of ``functionals``.

    Parameters
    ----------
    autocovariance : numpy.ndarray
        The stationary noise's autocovariance at lags ``0 .. n-1`` [signal unit**2].
    design : numpy.ndarray
        ``(n, m)`` model matrix on ``n`` consecutive samples.
    functionals : numpy.ndarray
        ``(m, k)``: the functions of the parameters estimated.

    Returns
    -------
    numpy.ndarray
        ``k`` variances.
    """
    whitened = solve_toeplitz(autocovariance, design)
    information = design.T @ whitened
    inverse = np.linalg.solve(information, functionals)
    return np.einsum("ij,ij->j", functionals, inverse)


def free_variance(autocovariance, outside, free, design, weights, tail):
    """Variance of the BLUE of ``weights' s + tail' beta`` when the signal ``s`` is free
    on the samples ``free`` and the model ``design beta`` holds on ``outside``.

    With ``s`` free, the samples in ``free`` say nothing of ``beta``: it is the GLS
    estimate on ``outside``, and the noise in ``free`` is predicted from the residual
    there (its conditional mean). The two errors are uncorrelated, so the variance is
    ``w' (S_ff - S_fo S_oo^-1 S_of) w + u' (X_o' S_oo^-1 X_o)^-1 u`` with
    ``u = X_f' w - X_o' S_oo^-1 S_of w - tail``.

    Parameters
    ----------
    autocovariance : numpy.ndarray
        At lags ``0 .. n-1`` of the ``n`` samples of ``design``.
    outside, free : numpy.ndarray of bool
        Samples where the model holds and where the signal is free (disjoint).
    design : numpy.ndarray
        ``(n, m)``: the baseline (and ringing) columns, on every sample.
    weights : numpy.ndarray
        ``n`` weights of the signal (zero outside ``free``).
    tail : numpy.ndarray
        ``m`` weights of the parameters.

    Returns
    -------
    float
    """
    sigma = toeplitz(autocovariance)
    factor = cho_factor(sigma[np.ix_(outside, outside)])
    w = weights[free]
    cross = sigma[np.ix_(outside, free)] @ w
    predicted = cho_solve(factor, cross)
    conditional = w @ sigma[np.ix_(free, free)] @ w - cross @ predicted
    x_out = design[outside]
    u = design[free].T @ w - x_out.T @ predicted - tail
    information = x_out.T @ cho_solve(factor, x_out)
    return float(conditional + u @ np.linalg.solve(information, u))


def _signal(grain, sensor, law, velocity, t, onset):
    """The sensor signal at ``t`` [s] of an impact touching at ``onset`` [s] (linear
    interpolation on a grid 32 times finer than ``t``) and its :data:`LAW_READINGS`
    (peak signal [N], impulse [N*s], peak contact force [N], contact time [s]: the
    exact solver's readings, not the grid's)."""
    dt = float(t[1] - t[0])
    window = float(t[-1] - onset) + dt
    result = simulate_impact(grain, sensor, law, velocity, duration=window, sample_rate=32.0 / dt)
    values = np.interp(t - onset, result.t, result.sensor_force, left=0.0, right=0.0)
    return values, np.array([getattr(result, name) for name in LAW_READINGS])


def law_design(grain, sensor, law, velocity, t, onset, step=1e-4):
    """Columns of the linearised law model at the truth, and the gradients of the
    :data:`LAW_READINGS` (``"law"`` model of the module docstring).

    Parameters
    ----------
    grain, sensor : Grain, Sensor
    law : contactlab.laws.ContactLaw
        Each of its positive parameters (``law.parameters()``: a
        :class:`~contactlab.laws.LinearViscoelastic`'s ``stiffness`` [N/m] and
        ``damping`` [N*s/m], an undamped :class:`~contactlab.laws.Hertz`'s ``k_hertz``
        [N/m**1.5]) is unknown (central differences of relative ``step``; a parameter
        at zero, such as a damping switched off, is held: it has no relative step).
    velocity : float
        Impact velocity [m/s]. A ``LinearViscoelastic`` law is linear: its signal, peak
        signal, impulse and peak contact force are proportional to the velocity, its
        contact time does not depend on it (the velocity's column is exact). Any other
        law's velocity column and gradients are central differences of relative
        ``step``.
    t : numpy.ndarray
        Sample times [s] of the segment read.
    onset : float
        First touch [s].
    step : float, default 1e-4
        Relative step of the differences [-].

    Returns
    -------
    design : numpy.ndarray
        ``(n, p + 4)``: d/dvelocity, d/d each of the law's ``p`` unknown parameters,
        d/donset, then a line (a linear law: ``(n, 6)``).
    functionals : numpy.ndarray
        ``(p + 4, 4)``: gradients of the peak signal [N], impulse [N*s], peak contact
        force [N] and contact time [s].
    truth : numpy.ndarray
        The four readings.
    """
    values, truth = _signal(grain, sensor, law, velocity, t, onset)
    if isinstance(law, LinearViscoelastic):
        columns = [values / velocity]
        gradients = [truth * np.array([1.0, 1.0, 1.0, 0.0]) / velocity]
    else:
        size = step * velocity
        faster = _signal(grain, sensor, law, velocity + size, t, onset)
        slower = _signal(grain, sensor, law, velocity - size, t, onset)
        columns = [(faster[0] - slower[0]) / (2.0 * size)]
        gradients = [(faster[1] - slower[1]) / (2.0 * size)]
    parameters = law.parameters()
    for name, value in parameters.items():
        if value == 0.0:
            continue
        size = step * value
        shifted = []
        for sign in (1.0, -1.0):
            changed = type(law)(**{**parameters, name: value + sign * size})
            shifted.append(_signal(grain, sensor, changed, velocity, t, onset))
        columns.append((shifted[0][0] - shifted[1][0]) / (2.0 * size))
        gradients.append((shifted[0][1] - shifted[1][1]) / (2.0 * size))
    dt = float(t[1] - t[0])
    later = _signal(grain, sensor, law, velocity, t, onset + 0.5 * step * dt)[0]
    earlier = _signal(grain, sensor, law, velocity, t, onset - 0.5 * step * dt)[0]
    columns.append((later - earlier) / (step * dt))
    gradients.append(np.zeros(len(LAW_READINGS)))
    design = np.column_stack([*columns, _line(t)])
    functionals = np.vstack([np.array(gradients), np.zeros((2, len(LAW_READINGS)))])
    return design, functionals, truth


def band_design(t, window, cutoff, sensor):
    """Columns of the ``"band"`` model: a cosine series up to ``cutoff`` [Hz] on
    ``window`` ``[start, end)`` [s] (zero elsewhere), the sensor's free ringing from
    ``end`` on, and a line.

    Returns
    -------
    design : numpy.ndarray
        ``(n, terms + 4)``: the cosines, the ringing's two columns, the line.
    terms : int
        Number of cosines.
    """
    cosines = _cosines(t, window, cutoff)
    ringing, _, _ = _ringing(np.maximum(t - window[1], 0.0), sensor)
    ringing[t < window[1]] = 0.0
    return np.column_stack([cosines, ringing, _line(t)]), cosines.shape[1]


def _cosines(t, window, cutoff):
    """A cosine series up to ``cutoff`` [Hz] on ``window`` ``[start, end)`` [s], zero
    elsewhere: ``(n, terms)``."""
    span = window[1] - window[0]
    terms = math.ceil(2.0 * cutoff * span) + 1
    cosines = np.cos(math.pi * np.outer((t - window[0]) / span, np.arange(terms)))
    cosines[(t < window[0]) | (t >= window[1])] = 0.0
    return cosines


def _line(t):
    """The baseline's two columns: a constant and a slope over the segment."""
    return np.column_stack([np.ones(t.size), (t - t.mean()) / np.ptp(t)])


def force_band_design(t, window, cutoff, sensor):
    """Columns of the ``"force band"`` model: the sensor's signal of each contact force of
    a cosine series up to ``cutoff`` [Hz] on ``window`` ``[start, end)`` [s] (zero
    elsewhere; through the sensor's transfer function ``(c1 p + k1) / (m1 p**2 + c1 p +
    k1)`` by :func:`scipy.signal.lsim`, the force linear between samples), and a line.

    Returns
    -------
    design : numpy.ndarray
        ``(n, terms + 2)``: the signals of the cosine forces, the line.
    forces : numpy.ndarray
        ``(n, terms)``: the cosine forces themselves (the peak force's functional is
        their row at the force's top).
    """
    from scipy.signal import lsim  # scipy.signal is slow to import: only here

    forces = _cosines(t, window, cutoff)
    w, zeta = sensor.angular_frequency, sensor.damping_ratio
    system = ([2.0 * zeta * w, w**2], [1.0, 2.0 * zeta * w, w**2])
    start = int(np.argmax(t >= window[0]))
    signals = np.zeros_like(forces)
    for k in range(forces.shape[1]):
        signals[start:, k] = lsim(system, forces[start:, k], t[start:] - t[start])[1]
    return np.column_stack([signals, _line(t)]), forces
