"""Gross-sliding closed forms: impulse balance and the sliding condition."""

import pytest

from contactlab import analytic
from contactlab.errors import ParameterError


def test_gross_sliding_conserves_contact_angular_momentum():
    vt, w = analytic.gross_sliding_rebound(analytic.ObliqueImpact(2.0, 5.0, 10.0, 0.01, 0.8, 0.3))
    assert vt == pytest.approx(5.0 - 0.3 * 1.8 * 2.0, rel=1e-15)  # round-off only
    # I w + m R vt (per m R) is unchanged by any force at the contact point
    assert 0.4 * 0.01 * w + vt == pytest.approx(0.4 * 0.01 * 10.0 + 5.0, rel=1e-15)


def test_sliding_condition_boundary():
    # slip 3.5 mu (1 + e) vn exactly: slides to rest at the end (boundary included)
    assert analytic.slides_throughout(
        analytic.ObliqueImpact(1.0, 3.5 * 0.2 * 2.0, 0.0, 0.01, 1.0, 0.2)
    )
    assert not analytic.slides_throughout(
        analytic.ObliqueImpact(1.0, 3.4 * 0.2 * 2.0, 0.0, 0.01, 1.0, 0.2)
    )
    with pytest.raises(ParameterError, match="slide throughout"):
        analytic.gross_sliding_rebound(analytic.ObliqueImpact(1.0, 0.1, 0.0, 0.01, 1.0, 0.2))
    with pytest.raises(ParameterError, match="friction"):
        analytic.slides_throughout(analytic.ObliqueImpact(1.0, 1.0, 0.0, 0.01, 1.0, -0.2))
