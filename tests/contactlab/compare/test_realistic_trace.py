"""dem-check compare on a realistic record without a pre-trigger (issue 22): the
baseline comes from the samples after the contact, not refused and not kept."""

from pathlib import Path

import numpy as np
import pytest

from contactlab.compare import compare_trace
from contactlab.config import load_config
from dem_check.campaign import Effects, realistic_record

ROOT = Path(__file__).resolve().parents[3]


def test_a_record_that_starts_at_the_impact_is_compared():
    config = load_config(ROOT / "data" / "traces" / "model_hard.toml")
    velocity = config.simulation["velocity"]
    record = realistic_record(
        config.grain,
        config.sensor,
        config.law,
        [velocity],
        [0.0],
        length=1e-3,
        sample_rate=5e6,
        noise=0.02,
        effects=Effects(pink=0.01, hum=0.01),
        seed=5,
    )
    offset = 0.3  # [N] a DC offset the baseline must remove
    trace = record.trace.derive({"step": "offset"}, values=np.asarray(record.trace.values) + offset)
    result = compare_trace(trace, config)
    # no sample before the impact: the head level fitted with the ringing after the contact
    assert result.notes["baseline status"] == "short pre-trigger"
    assert "no pre-trigger" in result.notes["baseline"]
    measured = float(np.max(result.a.values))
    # 0.02 N noise on a 4 N peak, 5 MHz: the offset removed to the quiet stretch's
    # standard error (a few mN), the peak to 1 %
    assert measured == pytest.approx(record.truth["peak_sensor_force [N]"][0], rel=0.01)
