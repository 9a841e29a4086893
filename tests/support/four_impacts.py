"""The campaign tests' four-impact record (imported by name: ``tests/conftest.py`` puts this
folder on the path): four impacts 5 ms apart, each with its bounce, in a 22 ms realistic
record with white noise of 0.03 N (1 % of the hard grain's 3 N peak signal at 2 m/s)."""

from dem_check.campaign import realistic_record

NOISE = 0.03
"""White noise [N]."""

ONSETS = (1e-3, 6e-3, 11e-3, 16e-3)
"""The four impacts' onsets [s]."""


def four_impact_record(grain, sensor, law, velocities, effects, *, sample_rate, seed):
    """A :func:`dem_check.campaign.realistic_record` of four impacts at :data:`ONSETS`.

    Parameters
    ----------
    grain, sensor, law
        The bodies and the contact law.
    velocities : sequence of 4 float
        Impact velocities [m/s].
    effects : dem_check.campaign.Effects
        The laboratory effects.
    sample_rate : float
        Sample rate [Hz].
    seed : int
        Random seed of the noise.

    Returns
    -------
    dem_check.campaign.records.RealisticRecord
    """
    return realistic_record(
        grain,
        sensor,
        law,
        list(velocities),
        list(ONSETS),
        length=22e-3,
        sample_rate=sample_rate,
        noise=NOISE,
        effects=effects,
        seed=seed,
    )
