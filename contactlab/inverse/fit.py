"""Fit a contact law to a sensor signal through the two-mass model.

The model is :func:`contactlab.simulate_impact` itself: grain and sensor are known (the
sensor from :func:`contactlab.inverse.identify_sensor`), the law's parameters, the impact
velocity (unless measured), the onset time and the baseline offset are adjusted until the
simulated signal S1 matches the trace in the least-squares sense
(``scipy.optimize.least_squares``, trust-region reflective with bounds). Parameters are
fitted as transformed values (``ln p`` for positive quantities, ``logit e`` for a
restitution coefficient, the onset in units of the contact time, the offset in noise
standard deviations) around a starting guess read from a Tikhonov
reconstruction of the force, so every fitted coordinate is of order one.
"""

import math
import warnings
from collections.abc import Mapping

import numpy as np
from scipy.optimize import least_squares

from contactlab import signals
from contactlab.blas import with_one_blas_thread
from contactlab.bodies import Grain, Sensor
from contactlab.errors import ContactlabWarning, ParameterError, ResolutionWarning, WindowWarning
from contactlab.inverse._signal import BASELINE_MIN_SAMPLES, check_window, uniform_signal
from contactlab.inverse.fit_models import FIT_MODELS, TRANSFORMS, FitModel
from contactlab.inverse.fit_quality import FitQuality, FitQualityWarning, judge_fit
from contactlab.inverse.fit_result import ContactFit, FittedParameter
from contactlab.inverse.noise_colour import ringing_residual
from contactlab.inverse.noise_window import clean_noise_window
from contactlab.inverse.pulse import pulse_baseline
from contactlab.inverse.reconstruct import reconstruct_force
from contactlab.solver import simulate_impact
from contactlab.validation import check_choice, check_count, check_number

__all__ = [
    "FIT_MODELS",
    "ContactFit",
    "FitModel",
    "FitQuality",
    "FitQualityWarning",
    "FittedParameter",
    "IdentifiabilityWarning",
    "fit_contact",
]

MAX_TRANSFORMED_STDERR = 0.25
"""Identifiability criterion: largest standard error of a transformed parameter (ln p,
logit e, onset / contact time). For ln p that is a relative error of about 25 %, a 95 %
confidence interval wider than a factor 2.7; well-determined parameters of a 1 % noise
trace have relative errors of 0.1-1 %, undetermined ones (the damping of a nearly
elastic contact) of 45 % and more."""

SINGULAR_RCOND = 1e-10
"""Singular values of the Jacobian (columns in transformed units) below this fraction of
the largest are treated as zero: their directions have unbounded variance."""

OVERSAMPLE = 4
"""The model is simulated at this multiple of the trace's sample rate and interpolated
linearly to the sample times (interpolation error ~ (w dt / 4)**2 / 8 of the amplitude:
8e-4 at 20 trace samples per period, a tenth of a 1 % noise)."""

NOISE_AFTER_PERIODS = 16.0
"""Sensor periods after the fit's window on which the noise of a record that starts at
its pulse is read [-] (as long as the post-contact window: 800 samples at 2 MHz for a
40 kHz sensor, the noise's variance to 5 %)."""

RINGING_TERMS = 4
"""Quantities :func:`~contactlab.inverse.noise_colour.ringing_residual` fits (a line and
the ringing's two amplitudes) [-]: the noise's degrees of freedom are the samples less
these."""

BOUND = math.log(100.0)
"""Fitted coordinates stay within +-ln(100) of the guess (a factor 100 for ln p)."""


class IdentifiabilityWarning(ContactlabWarning):
    """The trace does not determine a fitted parameter (or the optimiser did not
    converge); the message names the parameters and the fix."""


# ---------------------------------------------------------------------------
# The fit
# ---------------------------------------------------------------------------
class _Problem:
    """Residual function of the fit in transformed coordinates ``x`` (0 at the guess).

    ``fitted`` lists ``(name, transform)`` pairs; ``constants`` holds the values not
    fitted (parameters given in ``fixed``, a measured velocity).
    """

    def __init__(self, spec, grain, sensor, data, fitted, constants, start):
        self.spec, self.grain, self.sensor = spec, grain, sensor
        self.t, self.y, self.noise, self.dt = data
        self.names = [name for name, _ in fitted]
        self.kinds = [kind for _, kind in fitted]
        self.constants = constants
        self.start = start  # guesses: dict name -> value
        # coordinate units of the quantities fitted as they are (not transformed)
        self.scales = {"onset": start["contact_time"], "offset": self.noise}  # [s], [N]

    def values(self, x):
        """Natural values of every quantity (fitted and constant) at coordinate ``x``."""
        out = dict(self.constants)
        for name, kind, xi in zip(self.names, self.kinds, x, strict=True):
            if kind in self.scales:
                out[name] = self.start[name] + xi * self.scales[kind]
            else:
                to, back, _ = TRANSFORMS[kind]
                out[name] = back(to(self.start[name]) + xi)
        return out

    def slope(self, i, x):
        """d value / d coordinate of fitted quantity ``i`` at coordinate ``x``."""
        kind = self.kinds[i]
        if kind in self.scales:
            return self.scales[kind]
        to, _, derivative = TRANSFORMS[kind]
        return derivative(to(self.start[self.names[i]]) + x)

    def predict(self, values):
        """Model signal at the fitted samples [N] and the simulation behind it."""
        law = self.spec.build(values, self.grain)
        # two model steps beyond the last sample, so interpolation always has a bracket
        duration = max(self.t[-1] - values["onset"], 0.0) + 2.0 * self.dt / OVERSAMPLE
        with warnings.catch_warnings():
            # the model is read at the trace's sample times only: a window shorter than
            # a (trial) contact, or a grid coarser than a (trial) contact, is harmless
            warnings.simplefilter("ignore", WindowWarning)
            warnings.simplefilter("ignore", ResolutionWarning)
            sim = simulate_impact(
                self.grain,
                self.sensor,
                law,
                values["velocity"],
                duration=duration,
                sample_rate=OVERSAMPLE / self.dt,
            )
        model = np.interp(self.t - values["onset"], sim.t, sim.sensor_force, left=0.0)
        return model + values["offset"], sim

    def residuals(self, x):
        return (self.predict(self.values(x))[0] - self.y) / self.noise


def _pulse(t, y, sensor, baseline_window, crosstalk):
    """The pulse's local baseline (:func:`contactlab.inverse.pulse.pulse_baseline`) on
    the noise window (default: the clean one before the pulse, or in a record without
    a pre-trigger the samples before the pulse it finds), the noise [N], the noise
    window [s] and its samples less the baseline [N] (:func:`_noise_after`, after the
    fit's window, for a record that starts at its pulse)."""
    if baseline_window is None and np.count_nonzero(t < 0.0) >= BASELINE_MIN_SAMPLES:
        baseline_window = clean_noise_window(t, y)
    # the law's fit adjusts its own onset on the whole pulse: no first touch needed here
    pulse = pulse_baseline(t, y, sensor, baseline_window, crosstalk=crosstalk, first_touch=False)
    if pulse.status.startswith("short pre-trigger"):
        return (pulse, *_noise_after(t, y - pulse.values, pulse, sensor))
    samples = (y - pulse.values)[signals.in_window(t, pulse.window)]
    return pulse, pulse.noise, pulse.window, samples


def _noise_after(t, clean, pulse, sensor):
    """Noise [N], window [s] and samples [N] of a record that starts at its pulse: what
    a line and the sensor's free ringing leave
    (:func:`~contactlab.inverse.noise_colour.ringing_residual`) on the
    :data:`NOISE_AFTER_PERIODS` sensor periods after the fit's window (which ends with
    the post-contact window), so that the fit's residuals are judged against noise
    samples it was not fitted on, as against a pre-trigger."""
    length = NOISE_AFTER_PERIODS * sensor.period
    window = (pulse.post[1], min(pulse.post[1] + length, float(t[-1])))
    samples = ringing_residual(t, clean, window, sensor)
    if samples.size < BASELINE_MIN_SAMPLES + RINGING_TERMS:
        raise ParameterError(
            f"the pulse starts at {pulse.onset:.6g} s, with fewer than {BASELINE_MIN_SAMPLES} "
            f"samples before it, and the record ends at {t[-1]:.6g} s, leaving "
            f"{samples.size} samples after the fit's window to read the noise on (need "
            f"{BASELINE_MIN_SAMPLES + RINGING_TERMS}); record a pre-trigger or a longer "
            "tail, or pass baseline_window=(start, end) [s]"
        )
    noise = math.sqrt(float(samples @ samples) / (samples.size - RINGING_TERMS))
    return noise, window, samples


def _starting_values(spec, grain, t, y, sensor, velocity, window):
    """Guesses from a Tikhonov reconstruction: onset, contact time, impulse."""
    rec = reconstruct_force(t, y, sensor, baseline_window=window)
    m = rec.metrics
    if not (m.duration > 0.0 and m.impulse > 0.0):
        raise ParameterError("no impact pulse found in the trace (the reconstruction is empty)")
    if velocity is None:
        restitution = 0.5
        v = m.impulse / (grain.mass * (1.0 + restitution))
    else:
        v = velocity
        restitution = min(max(m.impulse / (grain.mass * v) - 1.0, 0.05), 0.95)
    start = spec.guess(grain, v, m.duration, restitution)
    start.update({"velocity": v, "onset": m.start, "contact_time": m.duration})
    return start


def _covariance(jac, rss, dof):
    """Standard errors of the coordinates: pseudo-inverse of J^T J scaled by RSS/dof.

    A coordinate with weight above 1e-3 in a direction whose singular value is below
    :data:`SINGULAR_RCOND` times the largest gets an infinite standard error.
    """
    _, s, vt = np.linalg.svd(jac, full_matrices=False)
    keep = s > SINGULAR_RCOND * s[0]
    inv = np.where(keep, 1.0 / np.where(keep, s, 1.0) ** 2, 0.0)
    variance = np.diag((vt.T * inv) @ vt) * (rss / dof)
    loose = (np.abs(vt[~keep]) > 1e-3).any(axis=0)
    return np.where(loose, np.inf, np.sqrt(variance))


def _fitted_parameters(problem, x, stderr, units):
    """One :class:`FittedParameter` per fitted quantity."""
    values = problem.values(x)
    out = {}
    for i, name in enumerate(problem.names):
        se = stderr[i]
        with np.errstate(over="ignore", invalid="ignore"):
            low = problem.values(_shifted(x, i, -1.96 * se))[name]
            high = problem.values(_shifted(x, i, 1.96 * se))[name]
        out[name] = FittedParameter(
            value=float(values[name]),
            stderr=float(abs(problem.slope(i, x[i])) * se) if np.isfinite(se) else math.inf,
            ci95=(float(low), float(high)),
            unit=units[name],
            identifiable=bool(se <= MAX_TRANSFORMED_STDERR),
        )
    return out


def _shifted(x, i, delta):
    out = np.array(x, dtype=float)
    out[i] += delta
    return out


def _check_fixed(spec, fixed):
    if fixed is None:
        fixed = {}
    if not isinstance(fixed, Mapping):
        raise ParameterError(f"fixed must be a dict of law parameter -> value; got {fixed!r}")
    fixed = dict(fixed)
    unknown = sorted(set(fixed) - set(spec.parameters))
    if unknown:
        raise ParameterError(
            f"fixed: unknown parameter(s) {unknown} for law {spec.law!r}; its fitted "
            f"parameters are {list(spec.parameters)}"
        )
    if len(fixed) == len(spec.parameters):
        raise ParameterError(f"fixed: every parameter of {spec.law!r} is fixed; nothing to fit")
    units = dict(zip(spec.parameters, spec.units, strict=True))
    # a logit-transformed quantity is a restitution coefficient, in (0, 1]
    highs = {
        p: 1.0 for p, kind in zip(spec.parameters, spec.transforms, strict=True) if kind == "logit"
    }
    return {
        name: check_number(name, v, low=0.0, high=highs.get(name), unit=units[name])
        for name, v in fixed.items()
    }


@with_one_blas_thread
def fit_contact(
    t,
    signal,
    grain,
    sensor,
    law="linear",
    velocity=None,
    *,
    fixed=None,
    baseline_window=None,
    window=None,
    max_nfev=200,
    crosstalk=True,
):
    """Fit a contact law (plus onset, baseline offset and, unless measured, impact
    velocity) to a trace.

    Parameters
    ----------
    t : array_like
        Time [s], uniformly sampled, with a pre-trigger baseline.
    signal : array_like
        Sensor signal [N] of one impact.
    grain : Grain
        The grain (its mass and radius enter).
    sensor : Sensor
        The sensor (e.g. ``identify_sensor(...).to_sensor(mass)``).
    law : str, default "linear"
        A key of :data:`FIT_MODELS`: ``"linear"`` (stiffness [N/m], damping [N*s/m]),
        ``"hertz"`` (effective_modulus [Pa]), ``"hertz_damped"`` (effective_modulus
        [Pa], restitution [-]), ``"walton_braun"`` (loading_stiffness [N/m],
        restitution [-]).
    velocity : float, optional
        Measured impact velocity [m/s]; fixed when given, fitted otherwise.
    fixed : dict, optional
        Law parameters held at given values (SI units), e.g. ``{"damping": 1.0}``.
    baseline_window : (float, float), optional
        Noise window [s]. Default: from the record's start to one onset-to-peak time
        before the pulse's detected onset
        (:func:`~contactlab.inverse.noise_window.clean_noise_window`), so that the start
        of the pulse, which an oscilloscope records before its trigger, is not taken for
        noise; in a record without samples before ``t = 0``, the samples before the
        pulse it finds. The baseline removed is the pulse's local one
        (:func:`contactlab.inverse.pulse.pulse_baseline`: a line on the window's last 8
        sensor periods and on the free ringing after the contact; its noise is read
        there); a record that starts at the pulse takes the head level
        (:func:`~contactlab.inverse.local_baseline.head_baseline`) and its noise is read
        after the fit's window, on what a line and the sensor's free ringing leave
        (:data:`NOISE_AFTER_PERIODS` sensor periods; the fit's quality is judged against
        those samples, reported as its noise window).
    window : (float, float), optional
        Samples fitted [s]. Default: from half a contact time before the
        reconstructed onset to the end of the pulse's post-contact window (16 sensor
        periods of free ringing after the contact, where the local baseline was fitted;
        a drift beyond it is not known).
    max_nfev : int, default 200
        Largest number of residual evaluations (each one simulation; the
        finite-difference Jacobian costs one more per fitted quantity).
    crosstalk : bool, default True
        Remove the structure's crosstalk with the baseline
        (:func:`contactlab.inverse.pulse.pulse_baseline`); off for a record already rid
        of it (a campaign's).

    Returns
    -------
    ContactFit
        With ``quality`` (:class:`~contactlab.inverse.fit_quality.FitQuality`): the
        reduced chi-squared, its p-value, the residuals' whiteness and whether the law is
        consistent with the trace.

    Raises
    ------
    ParameterError
        Bad arguments, no pulse in the trace, or a record that starts at its pulse and
        ends fewer than 20 samples after the fit's window (no noise to judge it on).

    Warns
    -----
    IdentifiabilityWarning
        When a parameter is not identifiable (its flag in the result is False), or the
        optimiser stopped at ``max_nfev`` before converging.
    FitQualityWarning
        When the law is not consistent with the trace (``quality.consistent`` is False);
        the message gives ``quality.reasons``.

    Notes
    -----
    Residuals are ``(S1_model - S1) / sigma`` with ``sigma`` the baseline noise, so
    the reduced chi-squared is 1 for a correct model and white noise. The covariance of
    the transformed coordinates is ``pinv(J^T J) * RSS / (n - p)`` (scaled by the
    reduced chi-squared, as ``scipy.optimize.curve_fit`` does by default), with ``J``
    the finite-difference Jacobian at the solution. A parameter is flagged not
    identifiable when the standard error of its coordinate exceeds
    :data:`MAX_TRANSFORMED_STDERR`, or when it lies along a direction in which the
    Jacobian is singular (:data:`SINGULAR_RCOND`); the confidence interval of a
    flagged parameter is not meaningful (the linearisation fails). Typical cases: the
    damping of a nearly elastic contact, or stiffness and velocity together when the
    sensor is much slower than the contact (its signal then measures the impulse only).

    References
    ----------
    Branch M.A., Coleman T.F., Li Y. (1999) A subspace, interior, and conjugate gradient
    method for large-scale bound-constrained minimization problems. SIAM J. Sci.
    Comput. 21, 1-23. DOI 10.1137/S1064827595289108 (the ``trf`` method).
    Bates D.M., Watts D.G. (1988) Nonlinear Regression Analysis and Its Applications.
    Wiley. DOI 10.1002/9780470316757 (linearised confidence intervals).
    """
    spec = FIT_MODELS[check_choice("law", law, tuple(FIT_MODELS))]
    if not isinstance(grain, Grain):
        raise ParameterError(f"grain must be a contactlab.Grain; got {type(grain).__name__}")
    if not isinstance(sensor, Sensor):
        raise ParameterError(f"sensor must be a contactlab.Sensor; got {type(sensor).__name__}")
    if velocity is not None:
        velocity = check_number("velocity", velocity, low=0.0, unit="m/s")
    fixed = _check_fixed(spec, fixed)
    max_nfev = check_count("max_nfev", max_nfev)
    if window is not None:
        window = check_window("window", window)
    t, y, dt = uniform_signal(t, signal)
    pulse, noise, baseline_window, noise_samples = _pulse(t, y, sensor, baseline_window, crosstalk)
    y = y - pulse.values
    # a record that starts at its pulse: the reconstruction finds the pulse (and its
    # noise after the contact) itself
    before = None if pulse.status.startswith("short pre-trigger") else baseline_window
    start = _starting_values(spec, grain, t, y, sensor, velocity, before)
    start.update(fixed)
    if window is None:
        window = (start["onset"] - 0.5 * start["contact_time"], pulse.post[1])
    rows = (t >= window[0]) & (t <= window[1])
    fitted = [
        (name, kind)
        for name, kind in zip(spec.parameters, spec.transforms, strict=True)
        if name not in fixed
    ]
    fitted += [("velocity", "log")] if velocity is None else []
    # the baseline's offset is fitted too: the noise window's mean is known only to
    # sigma / sqrt(m), and a fixed error of that size over a long record shifts the
    # impulse, hence the velocity, by several standard errors (0.5 % for 57 samples)
    fitted += [("onset", "onset"), ("offset", "offset")]
    start["offset"] = 0.0
    constants = {**fixed, **({} if velocity is None else {"velocity": velocity})}
    data = (t[rows], y[rows], noise, dt)
    problem = _Problem(spec, grain, sensor, data, fitted, constants, start)
    n_rows, n_par = int(rows.sum()), len(fitted)
    if n_rows <= n_par:
        raise ParameterError(
            f"window {tuple(window)} s holds {n_rows} samples; the fit needs more than "
            f"{n_par} (one per fitted quantity)"
        )
    solution = least_squares(
        problem.residuals,
        np.zeros(n_par),
        bounds=(-BOUND, BOUND),
        method="trf",
        diff_step=1e-6,
        max_nfev=max_nfev,
    )
    rss = float(solution.fun @ solution.fun)
    stderr = _covariance(solution.jac, rss, n_rows - n_par)
    units = {
        **dict(zip(spec.parameters, spec.units, strict=True)),
        "velocity": "m/s",
        "onset": "s",
        "offset": "N",
    }
    values = problem.values(solution.x)
    model, simulation = problem.predict(values)
    residual = model - problem.y
    goodness = {
        "rms_residual [N]": float(np.sqrt(np.mean(residual**2))),
        "noise [N]": float(noise),
        "r_squared [-]": float(
            1.0 - residual @ residual / np.sum((problem.y - problem.y.mean()) ** 2)
        ),
        "reduced_chi_squared [-]": rss / (n_rows - n_par),
        "samples": n_rows,
        "function_evaluations": int(solution.nfev),
        "converged": bool(solution.status > 0),
    }
    parameters = _fitted_parameters(problem, solution.x, stderr, units)
    quality = judge_fit(
        residual / noise,
        n_par,
        noise_samples,
        baseline_window,
        goodness["converged"],
    )
    fit = ContactFit(
        law=simulation.law,
        law_name=spec.law,
        parameters=parameters,
        baseline_offset=parameters.pop("offset"),
        fixed=fixed,
        velocity=float(values["velocity"]),
        velocity_measured=velocity is not None,
        onset=float(values["onset"]),
        grain=grain,
        sensor=sensor,
        t=problem.t,
        signal=problem.y,
        model=model,
        goodness=goodness,
        quality=quality,
        simulation=simulation,
        baseline_status=pulse.status,
        baseline_notes=pulse.notes,
    )
    _warn(fit, max_nfev)
    return fit


def _warn(fit, max_nfev):
    problems = []
    if fit.not_identifiable:
        problems.append(
            f"not identifiable from this trace: {', '.join(fit.not_identifiable)} (standard "
            f"error of the fitted coordinate above {MAX_TRANSFORMED_STDERR}, or a singular "
            "direction); fix them (fixed=, velocity=) from other data"
        )
    if not fit.goodness["converged"]:
        problems.append(f"the optimiser stopped after max_nfev={max_nfev} evaluations")
    if problems:
        warnings.warn("; ".join(problems), IdentifiabilityWarning, stacklevel=3)
    if not fit.quality.consistent:
        warnings.warn(
            f"the {fit.law_name} law is not consistent with this trace: "
            + "; ".join(fit.quality.reasons),
            FitQualityWarning,
            stacklevel=3,
        )
