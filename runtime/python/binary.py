"""The frames of the binary protocols besides UBX whose messages the spec types (SkyTraq, SiRF,
CASIC, SBF: spec/binary/<protocol>/messages) and the base of their generated message classes
(nmeaspec.<protocol>_messages).

One framing for all of them, read from framings.FRAMINGS (spec/binary/<protocol>/protocol.yaml):
the sync bytes, the header (the length field, in the protocol's byte order, counting the payload or
the whole frame; CASIC's class and id, SBF's checksum and block number and revision), the payload,
the checksum (stream.CHECKSUMS; after the payload, or in the header: SBF) and the end bytes. A
message is told by its key: the class and id of the header (CASIC), the block number and revision
of the header (SBF), or the payload's first byte, the message id, and for some ids a second, the
sub-id (SkyTraq) or SID (SiRF); the layout's fields follow the key. A message is a
ubx.Message (one reader and one writer of byte layouts, in the protocol's byte order) that frames
itself with its protocol's framing.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cache
from typing import Any, ClassVar, Literal

from . import ubx
from .framings import FRAMINGS, Framing
from .runtime import NmeaError

__all__ = ["Frame", "Message", "Unknown", "decode", "decode_frame", "message"]


@cache
def framing(protocol: str) -> Framing:
    """The framing of a protocol by its name in the tools' JSON (skytraq, sirf, casic)."""
    return next(f for f in FRAMINGS if f.protocol == protocol)


def _header_key(f: Framing) -> bool:
    """Whether the header carries the message's key (CASIC: class and id; SBF: number and revision)
    rather than the payload."""
    return all(at // 8 < f.header for _, at, _ in f.identity)


def _key_of(f: Framing, header: bytes) -> tuple[int, ...]:
    """The identity fields of a header, their bits numbered in the protocol's byte order."""
    from .stream import _bits

    return tuple(_bits(header, at, bits, f.big_endian) for _, at, bits in f.identity)


def _frame(f: Framing, header: bytearray, body: bytes) -> bytes:
    """A whole frame of a header (sync and key in place) and the body after it: its length field
    and checksum set, its end bytes added."""
    from .stream import CHECKSUMS  # the checksums of every framing

    size = len(header) + len(body) + f.trailer
    out = header + body
    out[f.length_at:f.length_at + f.length_size] = ((size - f.length_adds) & f.length_mask).to_bytes(
        f.length_size, "big" if f.big_endian else "little")
    checksum = CHECKSUMS[f.checksum](bytes(out[f.check_from:]))
    if f.check_at:
        out[f.check_at:f.check_at + f.check_size] = checksum
        return bytes(out) + f.end
    return bytes(out) + checksum + f.end


@dataclass(frozen=True)
class Frame:
    """One frame: its protocol, its key (class and id; id; id and sub-id) and the payload after
    the key."""

    protocol: str
    key: tuple[int, ...]
    payload: bytes

    @property
    def address(self) -> str:
        """Errors' address until a message layout names the frame: "SKYTRAQ 0xA8"."""
        return f"{self.protocol.upper()} " + " ".join(f"0x{k:02X}" for k in self.key)

    def encode(self) -> bytes:
        f = framing(self.protocol)
        in_header = _header_key(f)
        header = bytearray(f.sync) + bytearray(f.header - len(f.sync))
        if in_header:  # each identity field's bits, in the protocol's byte order
            for (_, at, bits), value in zip(f.identity, self.key):
                first, last = at // 8, (at + bits + 7) // 8
                order: Literal["big", "little"] = "big" if f.big_endian else "little"
                shift = 8 * last - at - bits if f.big_endian else at - 8 * first
                word = int.from_bytes(header[first:last], order) & ~(((1 << bits) - 1) << shift)
                header[first:last] = (word | (value & ((1 << bits) - 1)) << shift).to_bytes(last - first, order)
        return _frame(f, header, self.payload if in_header else bytes(self.key) + self.payload)


def decode_frame(protocol: str, data: bytes) -> tuple[bytes, bytes]:
    """The header and payload of the one frame of `protocol` that `data` holds, its sync bytes,
    length, checksum and end bytes checked."""
    f = framing(protocol)
    name = protocol.upper()
    if not f.sync.startswith(data[:len(f.sync)]):
        raise NmeaError("bad_sync", f"a {name} frame starts with {f.sync.hex(' ').upper()}, not "
                        f"{data[:len(f.sync)].hex(' ').upper()}", name)
    if len(data) < f.header:
        raise NmeaError("short_frame", f"a {name} header needs {f.header} bytes, there are {len(data)}", name)
    length = int.from_bytes(data[f.length_at:f.length_at + f.length_size], "big" if f.big_endian else "little")
    size = (length & f.length_mask) + f.length_adds
    if len(data) != size or size < f.header + f.trailer:
        kind = "short_frame" if len(data) < size or size < f.header + f.trailer else "long_frame"
        raise NmeaError(kind, f"the length field says {size} bytes, the frame has {len(data)}", name)
    from .stream import _framing

    sent, expected = _framing(protocol).check(data)
    if sent != expected:
        raise NmeaError("bad_checksum", f"checksum and end {sent.hex(' ').upper()}, computed "
                        f"{expected.hex(' ').upper()}", name)
    return data[:f.header], data[f.header:size - f.trailer]


@dataclass(kw_only=True)
class Message(ubx.Message):
    """A decoded message of SkyTraq, SiRF or CASIC (the generated classes of
    nmeaspec.<protocol>_messages): a ubx.Message that frames itself with its protocol's framing."""

    NAME: ClassVar[str]
    """The protocol's name in the tools' JSON: skytraq, sirf, casic."""
    KEY: ClassVar[tuple[int, ...]]
    """The bytes that tell the message: class and id (CASIC), id (and sub-id: SkyTraq, SiRF)."""

    def frame(self) -> Frame:  # type: ignore[override]
        return Frame(self.NAME, self.KEY, self.payload())

    def encode(self) -> bytes:
        return self.frame().encode()


@dataclass
class Unknown:
    """A frame of a key the spec does not describe, kept with its payload."""

    protocol: str
    key: tuple[int, ...]
    payload: bytes

    def encode(self) -> bytes:
        return Frame(self.protocol, self.key, self.payload).encode()

    def to_dict(self) -> dict[str, Any]:
        f = framing(self.protocol)
        keys = tuple(name for name, _, _ in f.identity) if len(self.key) == 2 and _header_key(f) else ("id",)
        return {"message": None, **dict(zip(keys, self.key)), "payload": self.payload.hex()}


ByKey = dict[tuple[int, ...], tuple[type[Message], ...]]


def message(by_key: ByKey, protocol: str, header: bytes, payload: bytes) -> Message | Unknown:
    """The message of a frame's header and payload: the layouts of its key (a header's class and
    id; the payload's id and sub-id, else its id), the one whose length and selector (type,
    version) the payload has, else the main one; an Unknown when the spec describes no such key."""
    f = framing(protocol)
    if _header_key(f):
        key = _key_of(f, header)
        rest = payload
    else:
        key = tuple(payload[:2])
        if key not in by_key:
            key = tuple(payload[:1])
        rest = payload[len(key):]
    layouts = by_key.get(key)
    if not layouts:
        return Unknown(protocol, key, rest) if key else Unknown(protocol, (), b"")
    found = ubx.layout_for(layouts, rest).from_payload(rest)
    assert isinstance(found, Message)
    return found


def decode(by_key: ByKey, protocol: str, data: bytes) -> Message | Unknown:
    """The message of one whole frame, its sync bytes, length and checksum checked."""
    return message(by_key, protocol, *decode_frame(protocol, data))
