"""Grain streams on a sensor plate: many-grain DEM in LAMMPS with the sensor inside.

>>> from dem_check.stream import DEFAULT_CASE, run_stream, score
>>> result = run_stream(DEFAULT_CASE)  # doctest: +SKIP
>>> score(result).counts  # doctest: +SKIP

See ``docs/streams.md``.
"""

from dem_check.stream.calibration import Calibration, calibration_curve, plate_output
from dem_check.stream.case import (
    DEFAULT_CASE,
    STRAW,
    Feed,
    Flow,
    ParticleKind,
    Plate,
    StreamCase,
    read_case,
)
from dem_check.stream.result import StreamResult, run_stream
from dem_check.stream.scoring import (
    FEATURES,
    Score,
    campaign_detector,
    discrimination,
    hit_features,
    pileup_curve,
    score,
)
from dem_check.stream.study import stream_study

__all__ = [
    "DEFAULT_CASE",
    "FEATURES",
    "STRAW",
    "Calibration",
    "Feed",
    "Flow",
    "ParticleKind",
    "Plate",
    "Score",
    "StreamCase",
    "StreamResult",
    "calibration_curve",
    "campaign_detector",
    "discrimination",
    "hit_features",
    "pileup_curve",
    "plate_output",
    "read_case",
    "run_stream",
    "score",
    "stream_study",
]
