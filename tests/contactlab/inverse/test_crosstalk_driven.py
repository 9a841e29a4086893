"""A structure mode driven by every impact of a record, tested with one shared coupling
(contactlab.inverse.crosstalk_driven) on ringing built here in closed form: each
impact's damped sinusoid, started at its onset, in proportion to its peak, on white and
1/f noise (``tests/support/plate_windows.py``'s generators, not the record model)."""

import math

import numpy as np
import pytest
from plate_windows import SENSOR, damped, flicker

from contactlab.errors import ParameterError
from contactlab.inverse import crosstalk_driven
from contactlab.inverse.crosstalk import _significant, structure_band
from contactlab.inverse.crosstalk_driven import (
    _block_covariance,
    _coloured_sandwich,
    _lag_covariance,
    driven_significance,
)

RATE = 2e6
MODE = (4100.0, 0.015)  # the record model's plate mode that the impulse feels most
GAPS = [1.4e-3, 3.5e-3, 1.3e-3, 3.9e-3, 1.5e-3, 2.6e-3, 1.4e-3, 4.6e-3]
"""Impact to next impact [s], hits and their bounces as in the realistic benchmark."""
PEAKS = np.array([2.6, 1.0, 1.1, 0.45, 3.4, 1.4, 0.8, 0.3])  # [N] hits, then bounces
WHITE = FLICKER = 0.03  # [N]: the benchmark's noise, 1/f as large as the white noise
DECAYED = 1.0e-3  # [s] a window starts where the sensor's ringing has decayed


def _record(coupling, seed):
    """Onsets [s], the windows of ringing after each impact (``(t, y)``) and the mode's
    ringing alone: ``coupling`` times each peak, a unit damped sine from its onset."""
    rng = np.random.default_rng(seed)
    onsets = 1e-3 + np.concatenate([[0.0], np.cumsum(GAPS[:-1])])
    t = np.arange(round((onsets[-1] + GAPS[-1]) * RATE)) / RATE
    ringing = sum(coupling * p * damped(t - o, *MODE) for o, p in zip(onsets, PEAKS, strict=True))
    y = 0.2 + 3.0 * t + ringing + WHITE * rng.normal(size=t.size)
    y = y + FLICKER * flicker(t.size, rng, 1.0 / RATE)
    windows = []
    for onset, gap in zip(onsets, GAPS, strict=True):
        inside = (t >= onset + DECAYED) & (t < onset + gap - 5e-5)
        windows.append((t[inside], y[inside]))
    return onsets, windows


@pytest.mark.parametrize("seed", [4, 5, 6])
def test_a_mode_each_window_cannot_show_is_found_by_its_shared_coupling(seed):
    # 1.5 % of each peak (the benchmark's 2 % crosstalk draws 1-2 %): 0.005-0.05 N
    # against 0.03 N of white and of 1/f noise
    onsets, windows = _record(0.015, seed)
    # window by window (the joint pencil's test, each window its own amplitude and phase)
    # the mode is significant after 2-3 of the 8 impacts: the record lost it
    hits = sum(
        _significant(*structure_band(t, y, SENSOR, 1, True)[:2], [(*MODE, _pole())], 1)[0]
        for t, y in windows
    )
    assert hits < len(windows) / 2
    _, z, significant = driven_significance(windows, onsets, PEAKS, [MODE], SENSOR)
    assert significant[0], z
    # the same noise without the mode: the shared coupling is not significant (noise is
    # neither locked to the onsets nor in proportion to the peaks)
    _, quiet = _record(0.0, seed)
    _, z0, none = driven_significance(quiet, onsets, PEAKS, [MODE], SENSOR)
    assert not none[0], z0


def test_the_shared_coupling_is_the_model_s():
    # with the mode strong enough to read (2 % of each peak), the fitted coupling per
    # newton of peak is the one the ringing was built with: z is its amplitude over its
    # standard error, so the error of the amplitude is about 1 / z of it; three such
    # errors, the white residual's error being optimistic under 1/f noise
    coupling = 0.02
    onsets, windows = _record(coupling, 4)
    amplitude, z, significant = driven_significance(windows, onsets, PEAKS, [MODE], SENSOR)
    assert significant[0]
    assert amplitude[0] == pytest.approx(coupling, rel=3.0 / z[0])


def test_onsets_and_drives_must_pair():
    t = np.arange(100) / RATE
    with pytest.raises(ParameterError, match="drives"):
        driven_significance([(t, np.sin(t))], [0.0, 1.0], [1.0], [MODE], SENSOR)


def _pole():
    frequency, zeta = MODE
    b = 2.0 * math.pi * frequency
    return complex(-zeta * b / math.sqrt(1.0 - zeta**2), b)


def test_block_means_covariance_is_the_double_sum_of_the_sample_covariance():
    # an AR(1) autocovariance r(k) = a**|k|: the covariance of two block means is the
    # mean of r over every pair of their samples (written out here), to rounding
    r = 0.9 ** np.arange(400)
    starts, size = np.array([0, 5, 40, 41, 200]), 7
    expected = np.array(
        [
            [
                np.mean([r[abs(a + i - b - j)] for i in range(size) for j in range(size)])
                for b in starts
            ]
            for a in starts
        ]
    )
    lags = _lag_covariance(int(np.ptp(starts)), size, r)
    assert _block_covariance(starts, starts, lags) == pytest.approx(expected, rel=1e-12)
    # white noise of variance 4: 4 / size on the diagonal, nothing between blocks that
    # do not overlap (0 and 5 overlap by 2 samples: 2 * 4 / 49)
    white = np.zeros(400)
    white[0] = 4.0
    blocked = _block_covariance(starts, starts, _lag_covariance(int(np.ptp(starts)), size, white))
    assert np.diag(blocked) == pytest.approx(4.0 / size)
    assert blocked[0, 1] == pytest.approx(2 * 4.0 / size**2)
    assert blocked[0, 4] == 0.0


def test_too_short_an_autocovariance_is_refused():
    with pytest.raises(ParameterError, match="autocovariance"):
        _lag_covariance(100, 10, np.ones(50))


def test_the_sandwich_summed_in_chunks_is_the_dense_one(monkeypatch):
    # X' R X over chunks of 7 rows (and of 3 entries: one row a chunk) against the dense
    # covariance's sandwich: the same sums in another order, rounding (1e-12 relative)
    rng = np.random.default_rng(4)
    starts, size = np.sort(rng.choice(3000, 40, replace=False)), 9
    design = rng.normal(size=(40, 5))
    r = 0.97 ** np.arange(3100) + 0.1 * 0.5 ** np.arange(3100)
    dense = _block_covariance(starts, starts, _lag_covariance(int(np.ptp(starts)), size, r))
    inverse = np.linalg.pinv(design.T @ design)
    expected = inverse @ (design.T @ dense @ design) @ inverse
    for entries in (7 * 40, 3):
        monkeypatch.setattr(crosstalk_driven, "CHUNK_ENTRIES", entries)
        chunked = _coloured_sandwich(design, starts, size, r)
        assert chunked == pytest.approx(expected, rel=1e-12, abs=1e-12 * np.abs(expected).max())
