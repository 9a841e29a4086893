"""What the command line prints: JSON dumps and aligned summaries."""

import json

import numpy as np

__all__ = ["dump", "print_summary"]


def _json_default(obj):
    if isinstance(obj, np.generic):
        return obj.item()
    raise TypeError(f"not JSON serialisable: {type(obj).__name__}")


def dump(data):
    """``data`` as indented JSON (numpy scalars as Python numbers)."""
    return json.dumps(data, indent=2, default=_json_default)


def print_summary(summary):
    """Print the scalar entries of a summary dict, one per line, aligned."""
    for key, value in summary.items():
        if isinstance(value, float):
            print(f"{key:32s} {value:.6g}")
        elif not isinstance(value, dict):
            print(f"{key:32s} {value}")
