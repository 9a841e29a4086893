"""Measurement campaigns: long records with many impacts, per-impact results, population
statistics and a self-contained HTML report (see ``docs/campaign.md``).

>>> from dem_check.campaign import run_campaign
>>> result = run_campaign("day1/", sensor, grain, sensitivity=0.01124, out="rep")  # doctest: +SKIP
>>> result.impacts  # one row per impact found  # doctest: +SKIP
>>> result.files  # one row per file, with its status  # doctest: +SKIP

* :func:`run_campaign` (:mod:`.api`) runs it all;
* :func:`find_impacts` (:mod:`.detection`) finds the impacts of one record;
* :func:`synthetic_record` (:mod:`.synthetic`) builds a long record with a known truth;
* :func:`realistic_record` and :class:`Effects` (:mod:`.records`) add what a laboratory
  adds: 1/f noise, drift, hum, crosstalk, ADC quantisation and clipping, offset steps,
  bounces, short pre-triggers.
"""

from dem_check.campaign.api import run_campaign
from dem_check.campaign.detection import find_impacts
from dem_check.campaign.records import Effects, realistic_record
from dem_check.campaign.result import CampaignResult
from dem_check.campaign.synthetic import synthetic_record

__all__ = [
    "CampaignResult",
    "Effects",
    "find_impacts",
    "realistic_record",
    "run_campaign",
    "synthetic_record",
]
