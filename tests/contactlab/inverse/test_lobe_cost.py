"""The lobe fit's compiled residual (:mod:`contactlab.kernels.lobe_cost`) against the
numpy code of :meth:`contactlab.inverse.lobe_model.LobeModel.solve`: the whitening equal
to the last bit, the residual within the rounding of sums taken in another order, over
the families, dampings, rates, noise models and onsets the fits meet."""

import math

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy import optimize

from contactlab import Sensor
from contactlab.inverse.lobe_model import FAMILIES, LobeModel
from contactlab.inverse.noise_colour import ARNoise
from contactlab.kernels.lobe_cost import white_signal

SENSOR = Sensor.from_disc(10e-3, 2e-3, 40e3, damping_ratio=0.02)


@settings(max_examples=60, deadline=None)
@given(
    extra=st.integers(1, 400),
    order=st.integers(0, 30),
    fine=st.integers(1, 8),
    seed=st.integers(0, 2**32 - 1),
)
def test_whitening_is_numpys_slices_to_the_last_bit(extra, order, fine, seed):
    size = order * fine + extra  # the unit signal spans the window, longer than the filter
    rng = np.random.default_rng(seed)
    r, ar = rng.normal(size=size), rng.normal(scale=0.3, size=order)
    reference = r.copy()
    for k, a in enumerate(ar, start=1):  # LobeModel.white_unit's numpy code, before
        reference[k * fine :] -= a * r[: r.size - k * fine]
    assert np.array_equal(white_signal(r, ar, fine), reference)  # same operations: bitwise


def _model(family, damping, rate, order, seed, samples):
    rng = np.random.default_rng(seed)
    t = 1e-3 + np.arange(samples) / rate
    noise = None
    if order:  # a stable AR model: small coefficients
        noise = ARNoise(rng.uniform(-0.9, 0.9, order) / order, 0.01, 1000)
    y = rng.normal(scale=0.05, size=samples) + np.exp(-(((t - t.mean()) / 40e-6) ** 2))
    return LobeModel(t, y, SENSOR, family, damping, noise), t


LOBES = {
    "family": st.sampled_from(sorted(FAMILIES)),
    "damping": st.sampled_from([0.0, 0.1, 0.3]),
    "rate": st.sampled_from([1e6, 2e6, 5e6]),
    "seed": st.integers(0, 2**32 - 1),
}
"""The lobe models the fits meet: both families, three dampings, 1-5 MHz, any noise draw."""


@settings(max_examples=60, deadline=None)
@given(
    **LOBES,
    order=st.integers(0, 12),
    samples=st.integers(40, 800),
    where=st.floats(-0.2, 1.1),
    tau=st.floats(5e-6, 400e-6),
)
def test_the_residual_is_solves(family, damping, rate, order, seed, samples, where, tau):
    model, t = _model(family, damping, rate, order, seed, samples)
    t0 = t[0] + where * (t[-1] - t[0])
    _, reference = model.solve(t0, tau, coefficients=False)
    scanned = model.scan(np.array([t0, t0]), tau)
    fitted = model.rss(t0, tau)
    if math.isinf(reference):  # no force in the window: both say so
        assert math.isinf(fitted) and np.isinf(scanned).all()
        return
    # sums of up to 800 terms in another order than BLAS': rounding of the window's
    # total sum of squares (1e-16 a term, a margin of 100)
    tolerance = 1e-12 * model.y_rss
    assert abs(fitted - reference) <= tolerance
    assert np.all(np.abs(scanned - reference) <= tolerance)
    assert scanned[0] == scanned[1]  # one onset, one value


def test_a_duration_not_positive_has_no_fit():
    model, t = _model("linear", 0.0, 2e6, 3, 0, 200)
    assert model.rss(t[50], 0.0) == math.inf
    assert model.rss(t[50], -1e-6) == math.inf


@settings(max_examples=40, deadline=None)
@given(
    **LOBES,
    order=st.integers(0, 6),
    samples=st.integers(60, 500),
    where=st.floats(0.1, 0.6),
    tau=st.floats(20e-6, 200e-6),
    no_contact=st.booleans(),
)
def test_the_compiled_simplex_is_scipys_nelder_mead(
    family, damping, rate, order, seed, samples, where, tau, no_contact
):
    """``LobeModel.fit`` (Nelder-Mead compiled) against scipy.optimize.minimize's
    Nelder-Mead of ``LobeModel.rss`` from the same simplex, as fit_lobe called it: the
    same vertex to the last bit, a vertex without contact (an infinite residual) too."""
    model, t = _model(family, damping, rate, order, seed, samples)
    dt = float(t[1] - t[0])
    t0 = t[0] + where * (t[-1] - t[0])
    second = -tau if no_contact else tau
    simplex = [[t0, tau], [t0 + 3.0 * dt, second], [t0, 1.05 * tau]]
    reference = optimize.minimize(
        lambda x: model.rss(x[0], x[1]),
        simplex[0],
        method="Nelder-Mead",
        options={"initial_simplex": simplex, "xatol": 1e-3 * dt, "fatol": 1e-9},
    )
    assert model.fit(simplex, 1e-3 * dt, 1e-9) == (reference.x[0], reference.x[1])
