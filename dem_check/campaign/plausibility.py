"""Each analysed impact of a campaign against what its grain can physically produce.

An impact whose velocity change (impulse / grain mass) or reconstructed peak force lies
outside the bounds of :func:`contactlab.compare.physics.physics_problems` gets the status
``"implausible"`` with the reason, so it is listed in the report and left out of the
statistics, instead of counting as ``"ok"``. Without a grain nothing can be checked.
"""

from contactlab.compare.physics import physics_problems

__all__ = ["IMPLAUSIBLE", "physics_status"]

IMPLAUSIBLE = "implausible"
"""Status of an impact no impact of the grain can produce."""


def physics_status(row, grain):
    """The status columns an ``"ok"`` impact row takes after the physics check.

    Parameters
    ----------
    row : dict
        The impact's row, with ``peak_contact_force [N]`` and ``velocity_change [m/s]``.
    grain : contactlab.Grain or None

    Returns
    -------
    dict
        Empty when the row stays as it is (plausible, not ``"ok"``, or no grain), else
        ``{"status": "implausible", "reason": ...}``.
    """
    if grain is None or row["status"] != "ok":
        return {}
    problems = physics_problems(grain, row["peak_contact_force [N]"], row["velocity_change [m/s]"])
    if not problems:
        return {}
    reason = "; ".join([*problems, row["reason"]] if row["reason"] else problems)
    return {"status": IMPLAUSIBLE, "reason": reason}
