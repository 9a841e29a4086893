"""What the command line prints: JSON dumps and aligned summaries."""

from contactlab.strict_json import dumps

__all__ = ["dump", "print_summary"]


def dump(data):
    """``data`` as indented strict JSON: NaN and infinity as ``null`` with the reason in
    ``"null_reasons"`` (:mod:`contactlab.strict_json`)."""
    return dumps(data)


def print_summary(summary):
    """Print the scalar entries of a summary dict, one per line, aligned."""
    for key, value in summary.items():
        if isinstance(value, float):
            print(f"{key:32s} {value:.6g}")
        elif not isinstance(value, dict):
            print(f"{key:32s} {value}")
