"""dem_check: cross-checks of contactlab against a rigid-body engine and measured traces."""
