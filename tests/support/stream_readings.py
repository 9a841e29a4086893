"""What the stream tests compare with contactlab's exact solver (imported by name:
``tests/conftest.py`` puts this folder on the path)."""


def impact_readings(result):
    """Contact time [s], peak contact and sensor forces [N] and restitution [-] of a
    stream's first contact, named as :class:`contactlab.ImpactResult`'s attributes."""
    truth = result.truth.iloc[0]
    return {
        "contact_time": truth["contact_time [s]"],
        "peak_contact_force": result.steps["contact_force [N]"].max(),
        "peak_sensor_force": result.steps["sensor_force [N]"].max(),
        "restitution": truth["rebound_normal_speed [m/s]"] / truth["normal_speed [m/s]"],
    }
