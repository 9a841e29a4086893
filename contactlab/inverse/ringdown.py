"""Ringing after a contact: the sensor's free ringing taken out, and damped modes shared
by several windows refined.

- :func:`free_ringing_residual`: a window after a contact less a polynomial and the
  sensor's free ringing fitted together (the noise floor of a record that starts at its
  pulse, :mod:`contactlab.inverse.noise_colour`; the structure's modes,
  :mod:`contactlab.inverse.crosstalk`).
- :func:`refine_poles`: poles shared by several windows (a structure rings at the same
  frequencies after every hit, with amplitudes that differ from hit to hit) refined by
  nonlinear least squares on all windows at once, each window's amplitudes eliminated
  (variable projection). A matrix pencil's poles are biased where the noise is coloured
  or the windows are short (one or two periods); least squares on the samples is not.

References
----------
Golub G., Pereyra V. (2003) Separable nonlinear least squares: the variable projection
method and its applications. Inverse Problems 19, R1-R26. DOI 10.1088/0266-5611/19/2/201
Kaufman L. (1975) A variable projection method for solving separable nonlinear least
squares problems. BIT 15, 49-57. DOI 10.1007/BF01932995
"""

import numpy as np
from scipy import optimize

from contactlab.errors import ParameterError
from contactlab.inverse.local_baseline import _ringing
from contactlab.validation import check_number

__all__ = ["MIN_DAMPING", "free_ringing_residual", "refine_poles", "refine_unheld"]

MIN_DAMPING = 1e-4
"""Smallest damping ratio a refined pole takes by default [-]: a window of one or two
periods hardly tells a mode's decay, and without a bound the refinement let such a pole
grow (``contactlab.inverse.crosstalk.joint_structure_modes``)."""


def free_ringing_residual(t, y, sensor, degree=1):
    """The record less a polynomial and the sensor's free ringing, fitted together.

    After a contact the sensor rings freely (its resonance and damping ratio known); what
    its ringing and a polynomial of ``degree`` (drift, as the baseline window's line
    before a pulse), fitted together by least squares, leave is the noise and whatever
    else rings there (the structure's modes).

    Parameters
    ----------
    t, y : numpy.ndarray
        Times [s] after the contact and the record (any unit); the ringing is referred to
        ``t[0]``.
    sensor : Sensor
        Its resonance and damping ratio give the ringing.
    degree : int, default 1
        Degree of the polynomial (0: a constant, 1: a line, 2: a quadratic) [-].

    Returns
    -------
    numpy.ndarray
        The residual on the samples (unit of ``y``).
    """
    s = t - t[0]
    scaled = s / max(float(s[-1]), 1e-300) - 0.5
    ringing, _, _ = _ringing(s, sensor)
    design = np.concatenate([np.vander(scaled, degree + 1, increasing=True), ringing], axis=1)
    coefficients, *_ = np.linalg.lstsq(design, y, rcond=None)
    return y - design @ coefficients


def refine_poles(windows, poles, damping=(MIN_DAMPING, 0.06), factor=2.0):
    """Damped modes shared by several windows, refined by variable projection.

    Each window ``(tau, y)`` is modelled as a line plus, for each pole ``s = -a + ib``,
    ``exp(-a tau) (c cos(b tau) + d sin(b tau))``, its own amplitudes ``c, d`` for each
    pole. For given poles the model is linear in the amplitudes; the residual of all
    windows stacked, each window's amplitudes eliminated by least squares, is minimised
    over the poles' damping ratios and frequencies (``scipy.optimize.least_squares``,
    trust-region reflective, within the bounds; Kaufman's Jacobian of the projected
    residual).

    Parameters
    ----------
    windows : sequence of (numpy.ndarray, numpy.ndarray)
        ``(tau [s], y)`` of each window, ``tau`` from any origin (the amplitudes absorb
        it); windows with no more samples than the model's columns are not used.
    poles : sequence of complex
        Starting poles [1/s], oscillating (``b > 0``), e.g. a matrix pencil's.
    damping : (float, float), default (:data:`MIN_DAMPING`, 0.06)
        Bounds of each damping ratio ``a / |s|`` [-] (a start outside is moved inside).
    factor : float, default 2
        Each frequency stays within this factor of its start [-].

    Returns
    -------
    numpy.ndarray of complex
        The refined poles [1/s], in the order given; the starting ones when the windows
        hold no more samples than unknowns or the minimisation fails.

    Raises
    ------
    ParameterError
        A pole that does not oscillate, or bad bounds.
    """
    poles = np.asarray(poles, dtype=complex).ravel()
    if np.any(~np.isfinite(poles)) or np.any(poles.imag <= 0.0):
        raise ParameterError(f"poles must be finite with a positive imaginary part; got {poles}")
    factor = check_number("factor", factor, low=1.0, low_open=True)
    low_zeta = check_number("damping low", damping[0], low=0.0, high=1.0)
    high_zeta = check_number("damping high", damping[1], low=low_zeta, high=1.0, high_open=True)
    columns = 2 + 2 * poles.size
    used = [(np.asarray(tau, float), np.asarray(y, float)) for tau, y in windows]
    used = [(tau - tau.mean(), y) for tau, y in used if y.size > columns]
    if not poles.size or sum(y.size for _, y in used) <= columns * len(used) + 2 * poles.size:
        return poles
    scale = poles.imag
    low = np.tile([low_zeta, 1.0 / factor], poles.size)
    high = np.tile([high_zeta, factor], poles.size)
    start = np.clip(np.ravel([(-p.real / abs(p), 1.0) for p in poles]), low, high)
    problem = _Projection(used, scale)
    fit = optimize.least_squares(
        problem.residual, start, jac=problem.jacobian, bounds=(low, high), x_scale="jac"
    )
    return problem.poles(fit.x) if fit.success else poles


def refine_unheld(windows, poles, damping=(MIN_DAMPING, 0.06)):
    """Poles refined by :func:`refine_poles`, those held at the largest damping ratio
    dropped and the rest refined again without them, until none is held.

    A pole held at the upper bound wanted more damping: noise, not a mode. Refined with
    the others it takes part of a mode and pushes that mode's pole away: on a 1 MHz
    record (1/f noise 0.3 sigma, 2 % crosstalk) the pencil's 807 and 503 Hz poles became
    744 Hz held and 440 Hz at the smallest damping ratio, where the plate rings at 730
    Hz; refined again without the held one, 722 Hz (``docs/campaign.md``, "Accuracy on
    realistic records, current"). It can push the mode's pole to the bound too: where
    some held poles started above the largest damping ratio (moved inside to start;
    noise by their start too), only those are dropped first. On a 2 MHz Hertz record
    (2 % crosstalk, seed 3 of ``bench_realistic.py``) the pencil's 1903 Hz (damping
    0.035) and 2850 Hz (0.097) poles were both held, at 1821 and 2514 Hz, and the plate's
    1890 Hz mode was lost with them; without the 2850 Hz pole, 1841 Hz, damping 0.022.

    Parameters
    ----------
    windows, poles, damping
        As for :func:`refine_poles`.

    Returns
    -------
    numpy.ndarray of complex
        The refined poles none of which is held [1/s], in the order given less those
        dropped (empty when every pole was held).
    """
    poles = np.asarray(poles, dtype=complex).ravel()
    while poles.size:
        refined = refine_poles(windows, poles, damping)
        held = np.isclose(-refined.real / np.abs(refined), damping[1], rtol=1e-6, atol=0.0)
        noise = held & (-poles.real / np.abs(poles) > damping[1])  # started outside
        poles = refined[~noise] if noise.any() else refined[~held]
        if not held.any():
            break
    return poles


PAD_RATIO = 1.25
"""Windows are stacked with others at most this many times their length [-] (the zero
rows a stack pads them with cost work; the stacks' count costs numpy calls)."""


def _stack(windows):
    """``(tau, y, inside)`` of windows padded with zero rows to the longest: times [s]
    and values, ``(windows, samples)``, and which entries are samples."""
    longest = max(y.size for _, y in windows)
    tau, y = np.zeros((len(windows), longest)), np.zeros((len(windows), longest))
    inside = np.zeros((len(windows), longest), dtype=bool)
    for k, (times, values) in enumerate(windows):
        tau[k, : values.size], y[k, : values.size], inside[k, : values.size] = times, values, True
    return tau, y, inside


def _coefficients(q, r, y):
    """``numpy.linalg.lstsq(r, q' y)`` of each stacked window: a triangular solve where
    every window's ``r`` has a diagonal above ``eps * columns`` of its largest (full
    rank), lstsq one window after the other otherwise."""
    qty = np.einsum("knm,kn->km", q, y)
    diagonal = np.abs(np.diagonal(r, axis1=1, axis2=2))
    if np.all(diagonal > np.finfo(float).eps * r.shape[-1] * diagonal.max(axis=1, keepdims=True)):
        return np.linalg.solve(r, qty[..., None])[..., 0]
    return np.stack([np.linalg.lstsq(rk, qk, rcond=None)[0] for rk, qk in zip(r, qty, strict=True)])


class _Projection:
    """The projected residual of :func:`refine_poles` and its Jacobian at ``x`` (damping
    ratio and frequency over its start for each pole), computed once per ``x``.

    Windows of similar lengths are stacked (:data:`PAD_RATIO`), each padded with zero
    rows to the longest of its stack: a zero row of the model and the data changes
    neither a window's QR factor nor its projection, and its residual and Jacobian rows
    are dropped. One batched QR and product then serve a stack: a record's windows are
    40 and more, of 30-150 samples each, and a loop over them spent most of its time in
    numpy's call overheads (``benchmarks/bench_joint_poles.py``). The rows come stack
    after stack, not window after window: least squares does not depend on their order.
    """

    def __init__(self, windows, scale):
        self.scale, self.x, self.parts = scale, None, None
        groups = []
        for k in sorted(range(len(windows)), key=lambda k: windows[k][1].size):
            size = windows[k][1].size
            if groups and size <= PAD_RATIO * windows[groups[-1][0]][1].size:
                groups[-1].append(k)
            else:
                groups.append([k])
        self.stacks = [_stack([windows[k] for k in group]) for group in groups]

    def poles(self, x):
        zeta, b = x[0::2], x[1::2] * self.scale
        return b * (-zeta / np.sqrt(1.0 - zeta**2) + 1j)

    def rates(self, x):
        """Each pole's frequency ``b`` and decay rate ``sigma`` [1/s] at ``x``, and the
        derivatives of ``sigma`` by the damping ratio and by the frequency ratio."""
        zeta, ratio = x[0::2], x[1::2]
        root = np.sqrt(1.0 - zeta**2)
        b = ratio * self.scale
        return b, -b * zeta / root, np.stack([-b / root**3, -self.scale * zeta / root], axis=1)

    def _update(self, x):
        if self.x is not None and np.array_equal(x, self.x):
            return
        b, sigma, dsigma = self.rates(x)
        residuals, jacobians = [], []
        for times, y, inside in self.stacks:
            tau, rows = times[:, :, None], inside[:, :, None]
            decay = np.where(rows, np.exp(tau * sigma), 0.0)  # zero on the padding rows
            cos, sin = decay * np.cos(tau * b), decay * np.sin(tau * b)
            design = np.concatenate([rows.astype(float), tau, cos, sin], axis=2)
            q, r = np.linalg.qr(design)
            coefficients = _coefficients(q, r, y)
            residual = y - np.einsum("knm,km->kn", design, coefficients)
            c, d = coefficients[:, None, 2 : 2 + b.size], coefficients[:, None, 2 + b.size :]
            model = cos * c + sin * d  # each pole's part of the model, one column each
            turned = cos * d - sin * c  # its derivative along b over tau
            derivative = np.empty((*times.shape, x.size))
            derivative[..., 0::2] = tau * model * dsigma[:, 0]
            derivative[..., 1::2] = tau * (model * dsigma[:, 1] + turned * self.scale)
            # Kaufman: the residual's Jacobian less the term of the amplitudes' change
            jacobian = -(derivative - q @ (np.swapaxes(q, 1, 2) @ derivative))
            residuals.append(residual[inside])
            jacobians.append(jacobian[inside])
        self.x, self.parts = x.copy(), (np.concatenate(residuals), np.concatenate(jacobians))

    def residual(self, x):
        self._update(x)
        return self.parts[0]

    def jacobian(self, x):
        self._update(x)
        return self.parts[1]
