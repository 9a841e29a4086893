"""A user's limits on the impacts found: ``min_force`` [N] and ``min_separation`` [s]
(step 3 of :mod:`dem_check.campaign.detection`): weaker or closer candidates keep a row
with status ``"below min_force"`` or ``"too close"`` and the reason, not analysed."""

import dataclasses

from contactlab.validation import check_number

__all__ = ["apply_limits", "check_limits"]


def check_limits(min_force, min_separation):
    """The user's ``min_force`` [N] and ``min_separation`` [s], checked (None: no limit)."""
    if min_force is not None:
        min_force = check_number("min_force", min_force, low=0.0, low_open=False, unit="N")
    if min_separation is not None:
        min_separation = check_number(
            "min_separation", min_separation, low=0.0, low_open=False, unit="s"
        )
    return min_force, min_separation


def apply_limits(windows, min_force, min_separation):
    """The user's limits: weaker or closer candidates keep a row with the reason."""
    out, previous = [], None
    for w in windows:
        if min_force is not None and not abs(w.peak) >= min_force:
            reason = f"peak {w.peak:.4g} N below min_force = {min_force:.4g} N"
            w = dataclasses.replace(w, status="below min_force", reason=reason)
        elif min_separation is not None and previous is not None:
            if w.onset - previous < min_separation:
                reason = (
                    f"onset {w.onset - previous:.4g} s after the impact at {previous:.6g} s, "
                    f"closer than min_separation = {min_separation:.4g} s"
                )
                w = dataclasses.replace(w, status="too close", reason=reason)
        if w.status not in ("below min_force", "too close"):
            previous = w.onset
        out.append(w)
    return out
