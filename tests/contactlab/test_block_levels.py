"""The running baseline from a record's levels computed once
(:func:`contactlab.signals.levels_baseline`, what the campaign's noise floor does) against
the baseline computed from the samples each time: the same arrays to the last bit, and
the shared levels left unchanged by a fit under a pulse at the record's start."""

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st
from levels_reference import numpy_residual

from contactlab import signals
from contactlab._block_levels import (
    LOCAL_MEAN_FRACTION,
    _block_medians,
    _edge_levels,
    block_levels,
)


def _record(seed):
    """A drifting noisy record with a pulse at its start, another later, and a step."""
    rng = np.random.default_rng(seed)
    n, width = 4096, 256
    t = np.arange(n) * 1e-6
    y = 0.02 * np.sin(2e3 * t) + rng.normal(0.0, 0.01, n) + np.where(t > 2.5e-3, 0.05, 0.0)
    y[:40] += np.hanning(80)[40:]  # a pulse's tail at the first sample
    y[1500:1540] += np.hanning(40)
    exclude = np.zeros(n, dtype=bool)
    exclude[:60] = exclude[1490:1600] = True
    return t, y, width, exclude


def test_levels_once_give_the_baseline_of_every_call_to_the_last_bit():
    t, y, width, exclude = _record(3)
    levels = block_levels(y, width)
    before = [array.copy() for array in (levels.level, levels.residual)]
    for exclude_, head in ((None, 0), (None, 60), (exclude, 60), (exclude, 0)):
        fresh = signals.running_baseline(y, width, exclude=exclude_, head=head)
        shared = signals.levels_baseline(levels, exclude=exclude_, head=head)
        for a, b in zip(fresh, shared, strict=True):
            assert np.array_equal(a, b)
    # the head fits changed copies: the shared levels are as computed
    assert np.array_equal(levels.level, before[0])
    assert np.array_equal(levels.residual, before[1])
    assert signals.levels_quiet_window(t, levels) == signals.quiet_window(t, y, width)


@settings(max_examples=60, deadline=None)
@given(
    blocks=st.integers(2, 12),
    width=st.integers(8, 64),
    extra=st.integers(0, 40),
    steps=st.lists(st.tuples(st.floats(0.0, 1.0), st.floats(-2.0, 2.0)), max_size=3),
    seed=st.integers(0, 2**32 - 1),
)
def test_the_compiled_residual_is_numpys_to_the_last_bit(blocks, width, extra, steps, seed):
    """``kernels.levels.nearest_residual`` against the numpy code it replaced
    (``tests/support/levels_reference.py``) on noise with level steps and a pulse, of
    any length and block width (the side means' short heads and tails included)."""
    rng = np.random.default_rng(seed)
    n = blocks * width + extra
    y = rng.normal(0.0, 0.05, n) + 3.0 * np.exp(-(((np.arange(n) - rng.uniform(0, n)) / 5) ** 2))
    for where, height in steps:
        y[int(where * n) :] += height
    levels = block_levels(y, width)
    span = max(2, width // LOCAL_MEAN_FRACTION)
    head, tail = _edge_levels(y, span, _block_medians(y, width)[1])
    medians = _block_medians(y, width)[1]
    reference = numpy_residual(y, levels.level, levels.block, medians, head, tail, span)
    assert np.array_equal(levels.residual, reference)  # same operations, same order: bitwise
