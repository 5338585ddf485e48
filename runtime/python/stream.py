"""Reading sentences from a byte stream: a serial port, a socket, a file, in chunks of any size.

The framer cuts the stream into lines the way a receiver's output is meant to be cut, and keeps
going whatever arrives:
- CR LF, LF and a bare CR all end a line; empty lines are skipped;
- a '$' or '!' always starts a new sentence: whatever came before it on the line (garbage, or a
  sentence cut short) is handed on as a line of its own, and is reported by the decoder;
- but a '\\' at the start of a line opens a TAG block, which keeps its sentence: until the
  block's closing '\\' every byte but a line ending belongs to it, and a '$', '!' or '\\' right
  after that continues the line;
- a line longer than MAX_LINE is not kept: its bytes are only counted, and it is reported as
  too_long with its length;
- a last line without an ending still counts.
Every line is then decoded like the `decode` verb does it, so NUL and other control bytes are
reported as not_a_sentence, and a text command is recognised as such.
"""

from __future__ import annotations

from collections.abc import Iterable, Iterator
from typing import Any, BinaryIO

from .api import decode_json, parse
from .runtime import MAX_LINE, NmeaError

_STARTS = frozenset(b"$!")
_ENDS = frozenset(b"\r\n")
_TAG = ord("\\")
# Where the line is with respect to TAG blocks.
_OUTSIDE, _IN_TAG, _AFTER_TAG = 0, 1, 2


class Framer:
    """Cuts bytes fed in any chunks into lines (bytes) and overlong lines (their length, an int)."""

    def __init__(self, max_line: int = MAX_LINE) -> None:
        self.max_line = max_line
        self._line = bytearray()
        self._length = 0
        self._tag = _OUTSIDE

    def feed(self, data: bytes) -> list[bytes | int]:
        out: list[bytes | int] = []
        for byte in data:
            if byte in _ENDS:
                self._finish(out)
                continue
            if byte == _TAG and (self._length == 0 or self._tag != _OUTSIDE):
                # opens a block (at the start, or right after one), or closes the open one
                self._tag = _AFTER_TAG if self._tag == _IN_TAG else _IN_TAG
            elif byte in _STARTS and self._tag == _OUTSIDE:
                self._finish(out)
            elif self._tag == _AFTER_TAG:
                self._tag = _OUTSIDE  # the sentence after the blocks, or whatever else follows
            self._length += 1
            if self._length <= self.max_line:
                self._line.append(byte)
        return out

    def end(self) -> list[bytes | int]:
        """The last line, when the stream ended without a line ending."""
        out: list[bytes | int] = []
        self._finish(out)
        return out

    def _finish(self, out: list[bytes | int]) -> None:
        if self._length:
            out.append(bytes(self._line) if self._length <= self.max_line else self._length)
        self._line.clear()
        self._length = 0
        self._tag = _OUTSIDE


def _chunks(source: BinaryIO | Any | Iterable[bytes], size: int) -> Iterator[bytes]:
    if hasattr(source, "recv"):  # a socket
        while chunk := source.recv(size):
            yield chunk
    elif hasattr(source, "read"):  # a file, a serial port
        read = getattr(source, "read1", source.read)
        while chunk := read(size):
            yield chunk
    else:
        yield from source


def lines(
    source: BinaryIO | Any | Iterable[bytes], chunk_size: int = 4096
) -> Iterator[bytes | int]:
    """The framed lines of a file, socket or iterable of byte chunks (an int for an overlong
    line)."""
    framer = Framer()
    for chunk in _chunks(source, chunk_size):
        yield from framer.feed(chunk)
    yield from framer.end()


def too_long(length: int) -> NmeaError:
    return NmeaError("too_long", f"line is {length} bytes, the limit is {MAX_LINE}")


def sentences(source: BinaryIO | Any | Iterable[bytes], **options: bool) -> Iterator[Any]:
    """Every item of the stream: a decoded sentence, or the NmeaError that says what was wrong.
    `options` are parse()'s (lenient, require_checksum, strict)."""
    for item in lines(source):
        if isinstance(item, int):
            yield too_long(item)
            continue
        try:
            yield parse(item, **options)
        except NmeaError as err:
            yield err


def json_lines(
    source: BinaryIO | Any | Iterable[bytes], values: bool = False, **options: bool
) -> Iterator[str]:
    """The `stream` verb: the JSON of `decode` for every framed item."""
    for item in lines(source):
        yield (
            too_long(item).to_json()
            if isinstance(item, int)
            else decode_json(item, values, **options)
        )
