"""1/f noise drawn independently of ``dem_check.campaign.records`` (whose Gaussian real
and imaginary parts it does not share): the tests that check the campaign's readers and
bounds against noise the toolkit did not generate use it."""

import math

import numpy as np


def pink_by_phases(rng, count, sigma):
    """``count`` samples of 1/f noise of standard deviation ``sigma``: amplitudes
    ``k**-1/2`` exactly at the frequencies ``k / count`` (per sample), ``k = 1 ..
    count // 2``, phases uniform."""
    k = np.arange(1, count // 2 + 1)
    spectrum = np.zeros(count // 2 + 1, dtype=complex)
    spectrum[1:] = np.exp(2j * math.pi * rng.uniform(size=k.size)) / np.sqrt(k)
    noise = np.fft.irfft(spectrum, count)
    return sigma * noise / noise.std()
