"""u-blox UBX frames: the framing layer (spec/binary/ubx/protocol.yaml) that the message layouts
will sit on.

A frame is the sync bytes B5 62, a class and an id byte, the payload's length (two bytes, little
endian, the payload alone) and the payload, closed by a Fletcher-8 checksum over class..payload.
A frame decodes to its class, id and payload and encodes back to the same bytes; a frame of a
class/id nobody describes is kept with its payload. A payload is read and written by the field
classes and item walkers of the AIS payloads (ais.py: one model of payloads) through ByteReader and
ByteWriter, which hold the little-endian byte order: offsets and widths stay in bits, whole bytes
here. Facts from u-blox UBX-13003221 (u-blox 8 / M8
Receiver description, "UBX protocol": frame structure and checksum).
"""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass

from .runtime import NmeaError

SYNC = b"\xb5\x62"
HEADER_SIZE = 6  # sync, class, id, length
CHECKSUM_SIZE = 2


def fletcher8(data: bytes) -> bytes:
    """The two checksum bytes (CK_A, CK_B) of `data`: 8-bit Fletcher, both sums modulo 256."""
    ck_a = ck_b = 0
    for byte in data:
        ck_a = (ck_a + byte) & 0xFF
        ck_b = (ck_b + ck_a) & 0xFF
    return bytes((ck_a, ck_b))


@dataclass(frozen=True)
class Frame:
    msg_class: int
    msg_id: int
    payload: bytes

    @property
    def address(self) -> str:
        """Errors' address until the message layouts name the frame: "UBX 0x01 0x07"."""
        return f"UBX 0x{self.msg_class:02X} 0x{self.msg_id:02X}"

    def encode(self) -> bytes:
        body = bytes((self.msg_class, self.msg_id)) + len(self.payload).to_bytes(2, "little") + self.payload
        return SYNC + body + fletcher8(body)


class ByteReader:
    """A payload's little-endian fields, with BitReader's interface (ais.read_items walks either):
    offsets and widths in bits, each a whole number of bytes."""

    __slots__ = ("payload", "length", "pos", "where")

    def __init__(self, payload: bytes, where: str) -> None:
        self.payload = payload
        self.length = 8 * len(payload)
        self.pos = 0
        self.where = where  # errors' address: "UBX NAV-PVT"

    @property
    def remaining(self) -> int:
        return self.length - self.pos

    def peek(self, offset: int, width: int, name: str) -> int:
        first, last = offset // 8, (offset + width) // 8 - 1
        if offset + width > self.length:
            raise NmeaError("short_payload", f"{name} needs bytes {first}-{last}, the payload has "
                            f"{len(self.payload)}", self.where, name=name)
        return int.from_bytes(self.payload[first:last + 1], "little")

    def take(self, width: int, name: str) -> int:
        raw = self.peek(self.pos, width, name)
        self.pos += width
        return raw


class ByteWriter:
    """A payload's fields written little endian, with BitWriter's interface (ais.write_items)."""

    __slots__ = ("payload",)

    def __init__(self) -> None:
        self.payload = bytearray()

    def put(self, raw: int, width: int) -> None:
        self.payload += raw.to_bytes(width // 8, "little")


def frame_size(data: bytes | memoryview, start: int = 0) -> int:
    """The size of the frame whose sync bytes are at `start`, read from its length field."""
    if len(data) - start < HEADER_SIZE:
        raise NmeaError("short_frame", f"a UBX header needs {HEADER_SIZE} bytes, there are {len(data) - start}", "UBX")
    return HEADER_SIZE + int.from_bytes(data[start + 4:start + 6], "little") + CHECKSUM_SIZE


def decode_frame(data: bytes) -> Frame:
    """The one frame `data` holds, its sync bytes, length and checksum checked."""
    if not SYNC.startswith(data[:2]):  # a cut-off start is short_frame below
        raise NmeaError("bad_sync", f"a UBX frame starts with B5 62, not {data[:2].hex(' ').upper()}", "UBX")
    size = frame_size(data)
    frame = Frame(data[2], data[3], bytes(data[HEADER_SIZE:size - CHECKSUM_SIZE]))
    if len(data) < size:
        raise NmeaError("short_frame", f"the length field says {size} bytes, the frame has {len(data)}", frame.address)
    if len(data) > size:
        raise NmeaError("long_frame", f"the length field says {size} bytes, the frame has {len(data)}", frame.address)
    expected = fletcher8(data[2:size - CHECKSUM_SIZE])
    if data[size - CHECKSUM_SIZE:size] != expected:
        raise NmeaError("bad_checksum", f"checksum {data[-2:].hex(' ').upper()}, computed "
                        f"{expected.hex(' ').upper()}", frame.address)
    return frame


def split_frames(data: bytes) -> Iterator[tuple[int, Frame]]:
    """The valid frames in a stream that mixes them with text (NMEA) and noise, each with its
    offset. A sync pair whose frame is cut short or fails its checksum is skipped byte by byte, as
    a receiver resynchronizes."""
    pos = data.find(SYNC)
    while pos >= 0:
        try:
            size = frame_size(data, pos)
            frame = decode_frame(data[pos:pos + size])
        except NmeaError:
            pos = data.find(SYNC, pos + 1)
            continue
        yield pos, frame
        pos = data.find(SYNC, pos + size)
