"""Grain streams on a sensor plate: many-grain DEM in LAMMPS with the sensor inside.

See ``docs/streams.md``.
"""
