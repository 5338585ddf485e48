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
With `binary=True` the framer also takes the binary frames a receiver interleaves with its
sentences (spec/binary/*/protocol.yaml): outside a TAG block, a frame's sync bytes end the line
before them, and the frame is handed on whole (a BinaryFrame) once its checksum matches. A frame
whose checksum fails, that the stream cuts short or that is longer than MAX_FRAME is a BadFrame of
its sync bytes, and the bytes after them are read again, so that no sentence or frame it seemed to
hold is lost. Lines, frames and bad frames concatenate to the stream less the line endings.
Every line is then decoded like the `decode` verb does it, so NUL and other control bytes are
reported as not_a_sentence, and a text command is recognised as such.
"""

from __future__ import annotations

import re
import zlib
from collections.abc import Callable, Iterable, Iterator
from dataclasses import dataclass
from functools import cache
from importlib import import_module
from importlib.util import find_spec
from typing import Any, BinaryIO, Literal, overload

from .api import decode_json, parse
from .framings import FRAMINGS, Framing
from .runtime import MAX_LINE, NmeaError

# The longest binary frame the framer holds: an RTCM 3 frame's 1,029 bytes, and the long UBX
# frames of a multi-band receiver (a ZED-F9P's NAV-SAT or RXM-RAWX of 40 signals: 1,200 bytes).
MAX_FRAME = 2048
_STARTS = frozenset(b"$!")
_ENDS = frozenset(b"\r\n")
_TAG = ord("\\")
# The bytes that may do more than lengthen the line outside a TAG block: everything else is taken
# a run at a time. With binary frames, their first sync bytes too (_framings).
_SPECIAL = b"\r\n\\$!"
# Where the line is with respect to TAG blocks.
_OUTSIDE, _IN_TAG, _AFTER_TAG = 0, 1, 2


def crc24q(data: bytes) -> bytes:
    """The three checksum bytes of an RTCM 3 frame: CRC-24Q (polynomial 0x1864CFB, initial value
    0, no reflection), big endian."""
    crc = 0
    for byte in data:
        crc ^= byte << 16
        for _ in range(8):
            crc = (crc << 1) ^ 0x1864CFB if crc & 0x800000 else crc << 1
    return (crc & 0xFFFFFF).to_bytes(3, "big")


def _fletcher8(data: bytes) -> bytes:
    a = b = 0
    for byte in data:
        a = (a + byte) & 0xFF
        b = (b + a) & 0xFF
    return bytes((a, b))


def _xor8(data: bytes) -> bytes:
    x = 0
    for byte in data:
        x ^= byte
    return bytes((x,))


def _sum32(data: bytes) -> bytes:
    """The sum of little-endian 32-bit words (a short last word padded with zeros), little endian."""
    words = data + bytes(-len(data) % 4)
    total = sum(int.from_bytes(words[i:i + 4], "little") for i in range(0, len(words), 4))
    return (total & 0xFFFFFFFF).to_bytes(4, "little")


def _crc16_ccitt(data: bytes) -> bytes:
    """CRC-CCITT of SBF (polynomial 0x1021, initial value 0, no reflection), little endian."""
    crc = 0
    for byte in data:
        crc ^= byte << 8
        for _ in range(8):
            crc = (crc << 1) ^ 0x1021 if crc & 0x8000 else crc << 1
    return (crc & 0xFFFF).to_bytes(2, "little")


def _crc32(data: bytes) -> bytes:
    """CRC-32 of Unicore (reflected polynomial 0xEDB88320, initial value 0, no final inversion),
    little endian: zlib's CRC-32 started from all ones and inverted back."""
    return (zlib.crc32(data, 0xFFFFFFFF) ^ 0xFFFFFFFF).to_bytes(4, "little")


# The checksums of binary frames (spec/schema/binary_protocol.schema.json): the bytes sent.
CHECKSUMS: dict[str, Callable[[bytes], bytes]] = {
    "fletcher8": _fletcher8,
    "xor8": _xor8,
    "sum15": lambda data: (sum(data) & 0x7FFF).to_bytes(2, "big"),
    "sum32": _sum32,
    "crc24q": crc24q,
    "crc16_ccitt": _crc16_ccitt,
    "crc32": _crc32,
}


@dataclass(frozen=True, slots=True)
class _Framing:
    """How a binary protocol's frame is told from noise (framings.Framing, generated from
    spec/binary/<protocol>/protocol.yaml)."""

    spec: Framing
    checksum: Callable[[bytes], bytes]  # the checksum of the bytes it covers

    @property
    def protocol(self) -> str:
        return self.spec.protocol

    @property
    def sync(self) -> bytes:
        return self.spec.sync

    def follows_sync(self, byte: int) -> bool:
        """Whether the byte after the first sync byte may go on a frame of this protocol."""
        return byte & self.spec.follow_mask == self.spec.follow

    def size(self, header: bytearray) -> int:
        """The frame's bytes, sync to end, from its header."""
        f = self.spec
        length = int.from_bytes(header[f.length_at:f.length_at + f.length_size], "big" if f.big_endian else "little")
        return (length & f.length_mask) + f.length_adds

    def check(self, frame: bytes) -> tuple[bytes, bytes]:
        """A whole frame's checksum and end bytes as sent, and as they must be."""
        f = self.spec
        body = len(frame) - f.trailer
        at = f.check_at or body
        sent = frame[at:at + f.check_size] + frame[len(frame) - len(f.end):]
        return sent, self.checksum(frame[f.check_from:body]) + f.end


@cache
def _framings() -> dict[int, tuple[_Framing, ...]]:
    """The protocols by their first sync byte."""
    out: dict[int, tuple[_Framing, ...]] = {}
    for spec in FRAMINGS:
        out[spec.sync[0]] = out.get(spec.sync[0], ()) + (_Framing(spec, CHECKSUMS[spec.checksum]),)
    return out


def _framing(name: str) -> _Framing:
    return next(f for fs in _framings().values() for f in fs if f.protocol == name)


def _bits(data: bytes, at: int, bits: int, big_endian: bool = True) -> int:
    """The `bits` bits of `data` from bit `at`, numbered most significant first (big endian) or
    least significant first (little endian)."""
    first, last = at // 8, (at + bits + 7) // 8
    if not big_endian:
        return int.from_bytes(data[first:last], "little") >> (at - 8 * first) & ((1 << bits) - 1)
    return int.from_bytes(data[first:last], "big") >> (8 * last - at - bits) & ((1 << bits) - 1)


@dataclass(frozen=True, slots=True)
class BinaryFrame:
    """A binary frame whose checksum matched: its protocol ("ubx", "rtcm3") and its bytes, sync
    bytes to checksum."""

    protocol: str
    data: bytes

    @property
    def identity(self) -> dict[str, Any]:
        """What the frame is: the fields of its protocol that tell its message (UBX: class and id,
        with the message's name, null where the spec does not describe it; RTCM 3: the message
        number, null when its payload is shorter; framings.py), each null past the payload."""
        spec, data = _framing(self.protocol).spec, self.data
        body = 8 * (len(data) - spec.trailer)
        out: dict[str, Any] = {name: _bits(data, at, bits, spec.big_endian) if at + bits <= body else None
                               for name, at, bits in spec.identity}
        if self.protocol == "ubx":
            from . import ubx
            from .ubx_messages import BY_ID  # the generated layouts, imported when a frame needs them

            layouts = BY_ID.get((self.data[2], self.data[3]))
            out["name"] = ubx.main_layout(layouts).ADDRESS if layouts else None
        return out

    def to_json(self) -> str:
        """The `stream` verb's object of the frame (json.md, "Binary frames in stream")."""
        data, spec = self.data, _framing(self.protocol).spec
        body = 8 * (len(data) - spec.trailer)
        identity = "".join(f'"{name}":{_bits(data, at, bits, spec.big_endian) if at + bits <= body else "null"},'
                           for name, at, bits in spec.identity)
        return f'{{"ok":true,"protocol":"{self.protocol}",{identity}"length":{len(data)},"frame":"{data.hex()}"}}'

    def message(self) -> Any:
        """The frame's decoded message: a UBX frame's (nmeaspec.ubx_messages: a ubx.Message, or
        ubx.Unknown), a SkyTraq, SiRF or CASIC frame's (nmeaspec.<protocol>_messages: a
        binary.Message, or binary.Unknown), an RTCM 3 frame's (nmeaspec.rtcm3_messages: an
        rtcm3.Message, or rtcm3.Unknown). ValueError for a protocol whose messages are not typed."""
        if self.protocol == "ubx":
            from .ubx_messages import decode

            return decode(self.data)
        try:
            module = import_module(f"{__package__}.{self.protocol}_messages")
        except ImportError:
            raise ValueError(f"{self.protocol} messages are not decoded") from None
        return module.decode(self.data)


@cache
def typed(protocol: str) -> bool:
    """Whether the package types the messages of `protocol` (has nmeaspec.<protocol>_messages):
    not a protocol a subset made with `generate --only` leaves out."""
    return find_spec(f"{__package__}.{protocol}_messages") is not None


@dataclass(frozen=True, slots=True)
class BadFrame:
    """What looked like the start of a binary frame and is not one: its protocol, why (`bad_checksum`,
    `too_long`, `too_short` (a length that counts the whole frame, shorter than its header),
    `nul_header`, `cut`: the stream ended inside it), a message, and its sync bytes; the
    framer reads the bytes after them again."""

    protocol: str
    reason: str
    message: str
    data: bytes

    def to_json(self) -> str:
        """The `stream` verb's object of it (json.md, "Binary frames in stream")."""
        return (f'{{"ok":false,"protocol":"{self.protocol}","error":{{"kind":"{self.reason}",'
                f'"message":"{self.message}"}},"bytes":"{self.data.hex()}"}}')


Item = bytes | int | BinaryFrame | BadFrame


class Framer:
    """Cuts bytes fed in any chunks into lines (bytes) and overlong lines (their length, an int);
    with `binary`, also binary frames (BinaryFrame) and what failed to be one (BadFrame)."""

    def __init__(self, max_line: int = MAX_LINE, binary: bool = False, max_frame: int = MAX_FRAME) -> None:
        self.max_line = max_line
        self.max_frame = max_frame
        self._line = bytearray()
        self._length = 0
        self._tag = _OUTSIDE
        self._syncs = _framings() if binary else {}
        self._next_special = re.compile(b"[" + re.escape(_SPECIAL + bytes(self._syncs)) + b"]").search
        self._frame = bytearray()  # a binary frame under way, from its first sync byte
        self._framing: _Framing  # the protocol of the frame under way
        self._size = 0  # the frame's bytes, once its header is in

    def feed(self, data: bytes) -> list[Item]:
        out: list[Item] = []
        at, end = 0, len(data)
        while at < end:
            if self._tag == _OUTSIDE and not self._frame:  # the bytes up to the next special one
                found = self._next_special(data, at)
                stop = found.start() if found else end
                if stop > at:
                    room = self.max_line - self._length
                    if room > 0:
                        self._line += data[at : min(stop, at + room)]
                    self._length += stop - at
                    at = stop
                    continue
            byte = data[at]
            at += 1
            if not self._frame and byte not in self._syncs:  # a line's byte, without a frame's checks
                self._line_byte(byte, out)
                continue
            again = self._push(byte, out)
            while again:  # bytes after a rejected frame's sync, read once more (no recursion)
                replay, again = again, b""
                for i, byte in enumerate(replay):
                    if more := self._push(byte, out):
                        again = more + replay[i + 1:]
                        break
        return out

    def end(self) -> list[Item]:
        """The last line, when the stream ended without a line ending (or the bytes of a frame cut
        short by the end, read again)."""
        out: list[Item] = []
        while self._frame:
            if len(self._frame) == 1 or len(self._frame) < len(self._framing.sync):  # a sync cut short
                self._unstart(out)
            else:
                out.append(self._bad("cut", "the stream ends inside the frame"))
                out += self.feed(self._rest())
        self._finish(out)
        return out

    def _push(self, byte: int, out: list[Item]) -> bytes:
        """Takes one byte; what must be read again (bytes of a frame found wanting)."""
        if self._frame:
            return self._frame_byte(byte, out)
        if byte in self._syncs and self._tag == _OUTSIDE:
            self._frame.append(byte)
            return b""
        self._line_byte(byte, out)
        return b""

    def _frame_byte(self, byte: int, out: list[Item]) -> bytes:
        frame = self._frame
        if len(frame) == 1:
            for framing in self._syncs[frame[0]]:  # the protocol the next byte names
                if framing.follows_sync(byte):
                    self._framing = framing
                    break
            else:  # no frame: its first byte was one of the line
                self._line_byte(frame.pop(), out)
                return bytes((byte,))
        framing = self._framing
        if len(frame) < 3:  # the sync's bytes
            sync = framing.spec.sync
            if len(frame) == 2 < len(sync) and byte != sync[2]:  # a third sync byte, checked as it comes
                self._unstart(out)
                return bytes((byte,))
            if len(frame) + 1 == max(len(sync), 2):
                self._finish(out)  # the line before the frame, its sync whole
        frame.append(byte)
        if len(frame) == framing.spec.header:
            self._size = framing.size(frame)
            if not any(frame[len(framing.sync):]):  # what a break's NUL bytes after a sync make
                out.append(self._bad("nul_header", "the header after the sync is NUL bytes"))
                return self._rest()
            if self._size > self.max_frame:
                out.append(self._bad("too_long", f"frame is {self._size} bytes, the limit is {self.max_frame}"))
                return self._rest()
            if self._size < framing.spec.header + framing.spec.trailer:  # a length that counts the whole frame
                out.append(self._bad("too_short", f"frame is {self._size} bytes, the least is "
                                     f"{framing.spec.header + framing.spec.trailer}"))
                return self._rest()
        if len(frame) == self._size:
            sent, computed = framing.check(bytes(frame))
            if sent != computed:
                out.append(self._bad("bad_checksum", f"checksum {sent.hex(' ').upper()}, computed "
                                     f"{computed.hex(' ').upper()}"))
                return self._rest()
            out.append(BinaryFrame(framing.protocol, bytes(frame)))
            frame.clear()
            self._size = 0
        return b""

    def _unstart(self, out: list[Item]) -> None:
        """The sync bytes so far of what turns out to be no frame (a third sync byte that does not
        follow, or the stream's end): bytes of the line, as a first sync byte no second follows."""
        for byte in self._frame:
            self._line_byte(byte, out)
        self._frame.clear()

    def _bad(self, reason: str, message: str) -> BadFrame:
        return BadFrame(self._framing.protocol, reason, message, bytes(self._frame[:len(self._framing.sync)]))

    def _rest(self) -> bytes:
        """Drops the frame under way; the bytes after its sync, to be read again."""
        rest = bytes(self._frame[len(self._framing.sync):])
        self._frame.clear()
        self._size = 0
        return rest

    def _line_byte(self, byte: int, out: list[Item]) -> None:
        if byte in _ENDS:
            self._finish(out)
            return
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

    def _finish(self, out: list[Item]) -> None:
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


@overload
def lines(
    source: BinaryIO | Any | Iterable[bytes], chunk_size: int = 4096, binary: Literal[False] = False
) -> Iterator[bytes | int]: ...
@overload
def lines(
    source: BinaryIO | Any | Iterable[bytes], chunk_size: int = 4096, *, binary: Literal[True]
) -> Iterator[Item]: ...
def lines(
    source: BinaryIO | Any | Iterable[bytes], chunk_size: int = 4096, binary: bool = False
) -> Iterator[Item]:
    """The framed lines of a file, socket or iterable of byte chunks (an int for an overlong
    line); with `binary`, also its binary frames (see Framer)."""
    framer = Framer(binary=binary)
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
    """The `stream` verb without AIS messages: the JSON of `decode` for every framed line, and
    of every binary frame."""
    for item in lines(source, binary=True):
        if isinstance(item, int):
            yield too_long(item).to_json()
        elif isinstance(item, bytes):
            yield decode_json(item, values, **options)
        else:
            yield item.to_json()
