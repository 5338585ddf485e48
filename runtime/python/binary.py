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

from dataclasses import dataclass, fields
from functools import cache
from typing import Any, ClassVar, Literal, TypeVar

from . import ubx
from .framings import FRAMINGS, Framing
from .runtime import NmeaError

__all__ = ["Frame", "Header", "Message", "Unknown", "decode", "decode_frame", "message"]


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


H = TypeVar("H", bound="Header")


@dataclass
class Header:
    """The fields of a frame's header besides its sync, length, key and checksum (Unicore's CPU
    idle, time and status: the protocol.yaml header fields of `identity: false`, framings.Framing's
    `kept`), which a decoded message keeps and its frame is written with. Each protocol that has
    such fields has its subclass, generated (nmeaspec.unicore_messages.Header: a member per field,
    0 by default)."""

    PROTOCOL: ClassVar[str]
    """The protocol's name in the tools' JSON: unicore."""

    @classmethod
    def read(cls: type[H], header: bytes) -> H:
        """The fields of a frame's header (sync bytes to the payload), in the protocol's byte order."""
        f = framing(cls.PROTOCOL)
        order: Literal["big", "little"] = "big" if f.big_endian else "little"
        return cls(**{name: int.from_bytes(header[at:at + size], order) for name, at, size in f.kept})

    def write(self, header: bytearray, where: str) -> None:
        """Sets its fields in a frame's header; NmeaError bad_value names a field its bytes cannot hold."""
        from .ais import _bad_value

        f = framing(self.PROTOCOL)
        for name, at, size in f.kept:
            value = getattr(self, name)
            if not isinstance(value, int) or isinstance(value, bool) or not 0 <= value < 1 << 8 * size:
                raise _bad_value(where, f"header.{name}", value, f"a whole number of {size} bytes")
            header[at:at + size] = value.to_bytes(size, "big" if f.big_endian else "little")

    def to_dict(self) -> dict[str, Any]:
        """Its JSON object (`header` in a message's): each field by its id, in the header's order."""
        return {f.name: getattr(self, f.name) for f in fields(self)}


def header_of(message: object) -> Header | None:
    """The header fields a message or frame keeps (its `header`), None for a protocol with none."""
    found = getattr(message, "header", None)
    return found if isinstance(found, Header) else None


@dataclass(frozen=True)
class Frame:
    """One frame: its protocol, its key (class and id; id; id and sub-id), the payload after
    the key, and the header's other fields (Unicore's time and status; None: zeros)."""

    protocol: str
    key: tuple[int, ...]
    payload: bytes
    header: Header | None = None

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
        if self.header is not None:
            self.header.write(header, self.address)
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
        return Frame(self.NAME, self.KEY, self.payload(), header_of(self))

    def encode(self) -> bytes:
        header = header_of(self)
        if header is not None:   # checked first, so that an error names the message: UNICORE BESTNAVB
            header.write(bytearray(framing(self.NAME).header), f"{self.PROTOCOL} {self.ADDRESS}")
        return self.frame().encode()

    def to_dict(self) -> dict[str, Any]:
        """ubx.Message's JSON, with `header` after `message` where the protocol has header fields."""
        out = super().to_dict()
        header = header_of(self)
        return out if header is None else {"message": out.pop("message"), "header": header.to_dict(), **out}


@dataclass
class Unknown:
    """A frame of a key the spec does not describe, kept with its payload (and the header's other
    fields, where its protocol has some: Unicore's time and status)."""

    protocol: str
    key: tuple[int, ...]
    payload: bytes
    header: Header | None = None

    def encode(self) -> bytes:
        return Frame(self.protocol, self.key, self.payload, self.header).encode()

    def to_dict(self) -> dict[str, Any]:
        f = framing(self.protocol)
        keys = tuple(name for name, _, _ in f.identity) if len(self.key) == len(f.identity) and _header_key(f) \
            else ("id",)
        return {"message": None, **({"header": self.header.to_dict()} if self.header is not None else {}),
                **dict(zip(keys, self.key)), "payload": self.payload.hex()}


ByKey = dict[tuple[int, ...], tuple[type[Message], ...]]


def message(by_key: ByKey, protocol: str, header: bytes, payload: bytes,
            kept: type[Header] | None = None) -> Message | Unknown:
    """The message of a frame's header and payload: the layouts of its key (a header's class and
    id; the payload's id and sub-id, else its id), the one whose length and selector (type,
    version) the payload has, else the main one; an Unknown when the spec describes no such key.
    `kept`: the protocol's Header, whose fields the message keeps (Unicore's time and status)."""
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
        return Unknown(protocol, key if key else (), rest if key else b"", kept.read(header) if kept else None)
    found = ubx.layout_for(layouts, rest).from_payload(rest)
    assert isinstance(found, Message)
    if kept is not None:
        setattr(found, "header", kept.read(header))  # the layout class declares it (generated)
    return found


def decode(by_key: ByKey, protocol: str, data: bytes, kept: type[Header] | None = None) -> Message | Unknown:
    """The message of one whole frame, its sync bytes, length and checksum checked."""
    return message(by_key, protocol, *decode_frame(protocol, data), kept)
