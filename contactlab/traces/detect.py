"""Recognise a trace file by its content, never by its extension."""

from contactlab.traces.formats import FORMATS
from contactlab.traces.texthead import read_head

__all__ = ["detect_format", "detect_head"]


def detect_head(head):
    """Name of the first registered format whose sniffer accepts ``head``.

    Every head is accepted by one: ``scope-binary`` takes any non-text content and
    ``generic`` any text (and reports what is wrong with it when read).
    """
    return next(name for name, fmt in FORMATS.items() if fmt.sniff(head))


def detect_format(path):
    """Name of the format of a trace file, from its first 64 KiB.

    Parameters
    ----------
    path : str or os.PathLike

    Returns
    -------
    str
        A key of :data:`~contactlab.traces.formats.FORMATS`, e.g. ``"rigol-sequence"``.
    """
    return detect_head(read_head(path))
