"""A text file's head: its first 64 KiB as decoded lines with byte offsets.

Layouts are detected and their headers read from :class:`Head`. Files are read as UTF-8,
falling back to Latin-1 (which decodes any byte). A file that starts with a UTF-16 or
UTF-32 byte-order mark (as some Windows instrument software writes it) is decoded whole
and re-encoded as UTF-8 in memory, and both the header and the data are read from that
copy; such files are small, and without the mark the encoding would be a guess.
"""

import codecs
import io
from dataclasses import dataclass

import numpy as np

from contactlab.traces.checks import fail

__all__ = ["HEAD_BYTES", "Head", "read_head"]

HEAD_BYTES = 1 << 16
"""Bytes read for detection and headers [B]; every supported header is far shorter."""

_WIDE_BOMS = (
    (codecs.BOM_UTF32_LE, "utf-32"),  # before UTF-16 LE, whose mark it starts with
    (codecs.BOM_UTF32_BE, "utf-32"),
    (codecs.BOM_UTF16_LE, "utf-16"),
    (codecs.BOM_UTF16_BE, "utf-16"),
)
"""Byte-order marks of the wide Unicode encodings, and the codec that reads each."""


@dataclass(frozen=True)
class Head:
    """The first :data:`HEAD_BYTES` of a file, split into complete lines."""

    path: str
    raw: bytes
    lines: tuple
    """Decoded lines without their line ends (the partial last line is dropped)."""
    offsets: tuple
    """Byte offset where each line starts, plus one entry past the last line."""
    encoding: str
    """Encoding of the file (``"utf-8"``, ``"latin-1"``, ``"utf-16"`` or ``"utf-32"``)."""
    at_eof: bool
    """Whether the head holds the whole file."""
    transcoded: bytes | None = None
    """The whole file re-encoded as UTF-8 when it is UTF-16 or UTF-32 (``raw``, ``lines``
    and ``offsets`` then describe this copy); ``None`` for files read as they are."""

    @property
    def data_encoding(self):
        """Encoding of the bytes :meth:`open_data` returns."""
        return self.encoding if self.transcoded is None else "utf-8"

    def open_data(self):
        """A binary file object over the content: the file, or its UTF-8 copy."""
        return open(self.path, "rb") if self.transcoded is None else io.BytesIO(self.transcoded)

    def ends_with_line_end(self):
        """Whether the content's last byte is ``\\n`` (a last line cut short has none)."""
        if self.transcoded is not None:
            return self.transcoded.endswith(b"\n")
        with open(self.path, "rb") as fh:
            if fh.seek(0, io.SEEK_END) == 0:
                return False
            fh.seek(-1, io.SEEK_END)
            return fh.read(1) == b"\n"

    @property
    def is_text(self):
        """Whether the head looks like text (no NUL byte)."""
        return b"\x00" not in self.raw

    def cells(self, index, delimiter=","):
        """Stripped cells of the 0-based line ``index`` (``[]`` beyond the head)."""
        if index >= len(self.lines):
            return []
        return [cell.strip() for cell in self.lines[index].split(delimiter)]

    def fail(self, line, message):
        """A TraceFormatError at the 1-based ``line`` of this file."""
        return fail(self.path, f"line {line}", message)


def read_head(path):
    """Read a file's head: its first 64 KiB as complete lines, with byte offsets.

    A UTF-16 or UTF-32 file (recognised by its byte-order mark) is read whole and
    re-encoded as UTF-8 (:attr:`Head.transcoded`); the head is then that copy's.

    Raises
    ------
    TraceFormatError
        A byte-order mark followed by bytes that are not valid in its encoding.
    """
    with open(path, "rb") as fh:
        raw = fh.read(HEAD_BYTES + 1)
        wide = next((codec for bom, codec in _WIDE_BOMS if raw.startswith(bom)), None)
        if wide is not None:
            raw += fh.read()
    transcoded = None
    if wide is not None:
        try:
            transcoded = raw.decode(wide).encode("utf-8")
        except UnicodeDecodeError as exc:
            raise fail(
                path,
                f"byte {exc.start}",
                f"starts with a {wide.upper()} byte-order mark but "
                f"is not valid {wide.upper()} ({exc.reason})",
            ) from None
        raw = transcoded[: HEAD_BYTES + 1]
    at_eof = len(raw) <= HEAD_BYTES
    raw = raw[:HEAD_BYTES]
    pieces = raw.split(b"\n")
    if not at_eof or pieces[-1] == b"":
        pieces.pop()
    offsets = np.cumsum([0] + [len(p) + 1 for p in pieces]).tolist()
    try:
        b"\n".join(pieces).decode("utf-8")
        encoding = "utf-8"
    except UnicodeDecodeError:
        encoding = "latin-1"  # decodes any byte; cells that matter are ASCII numbers
    lines = [p.rstrip(b"\r").decode(encoding) for p in pieces]
    if lines and lines[0].startswith("\ufeff"):
        lines[0] = lines[0][1:]
    return Head(str(path), raw, tuple(lines), tuple(offsets), wide or encoding, at_eof, transcoded)
