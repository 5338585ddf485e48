"""RTCM 3 messages: a frame's payload read into the generated message class of its 12-bit
message number (nmeaspec.rtcm3_messages, from spec/binary/rtcm3/messages) by the bit layouts'
one reader and one writer (ais.py: fields most significant bit first), and written back to the
same bytes: reserved bits, the masks and cell order of MSM messages and the bits after the
layout (`trailing`, the padding to a whole byte) are kept as sent. The types RTCM 3 adds to the
bit layouts live here: sign-magnitude numbers, ISO 8859-1 and UTF-8 characters. Facts from the
public field lists named in spec/binary/rtcm3/protocol.yaml (pyrtcm, gpsd, RTKLIB)."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, ClassVar

from .ais import BitReader, BitWriter, Field, Record, Special, _bad_value, bits_text
from .runtime import NmeaError

PREAMBLE = 0xD3
HEADER_SIZE = 3  # the preamble, 6 reserved bits and the 10-bit length
CHECKSUM_SIZE = 3


def _crc_table() -> tuple[int, ...]:
    table = []
    for byte in range(256):
        crc = byte << 16
        for _ in range(8):
            crc = (crc << 1) ^ 0x1864CFB if crc & 0x800000 else crc << 1
        table.append(crc & 0xFFFFFF)
    return tuple(table)


_CRC_TABLE = _crc_table()


def crc24q(data: bytes) -> bytes:
    """The three checksum bytes of `data` (stream.crc24q's, a byte at a time by table)."""
    crc = 0
    for byte in data:
        crc = ((crc << 8) & 0xFFFFFF) ^ _CRC_TABLE[(crc >> 16) ^ byte]
    return crc.to_bytes(3, "big")


@dataclass(frozen=True, slots=True)
class SignMagnitude(Field):
    """smag: a sign bit (1: negative) and the magnitude, in a unit once divided by `divisor`. The
    negative zero a sender may send is Special("negative_zero", its bits), never a number."""

    divisor: int = 1
    special: tuple[Special, ...] = ()

    def from_raw(self, raw: int, width: int) -> Any:
        sign = 1 << (width - 1)
        if raw == sign:
            return Special("negative_zero", raw)
        number = -(raw & (sign - 1)) if raw & sign else raw
        for s in self.special:
            if s.raw == number:
                return s
        return number / self.divisor if self.divisor != 1 else number

    def raw_number(self, value: Any, where: str) -> int:
        if isinstance(value, Special):
            return value.raw
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            raise _bad_value(where, self.id, value, "a number")
        if self.divisor == 1:
            if isinstance(value, float) and not value.is_integer():
                raise _bad_value(where, self.id, value, "a whole number")
            return int(value)
        return round(value * self.divisor)

    def to_raw(self, value: Any, where: str) -> tuple[int, int]:
        assert self.width is not None
        sign = 1 << (self.width - 1)
        if isinstance(value, Special) and value.id == "negative_zero":
            return sign, self.width
        number = self.raw_number(value, where)
        if not -sign < number < sign:
            raise _bad_value(where, self.id, value, f"a raw value {1 - sign}..{sign - 1}")
        return (sign | -number) if number < 0 else number, self.width

    def put_json(self, out: dict[str, Any], value: Any) -> None:
        if isinstance(value, Special):
            out[self.id] = str(value)
            out[f"{self.id}_raw"] = value.raw
        elif self.divisor == 1 and not self.special:
            out[self.id] = value
        else:
            out[self.id] = value
            out[f"{self.id}_raw"] = self.raw_number(value, "")


@dataclass(frozen=True, slots=True)
class Latin1(Field):
    """latin1: characters of eight bits, ISO 8859-1, as sent; counted by a field before them."""

    def counted(self, number: int) -> int:
        return 8 * number

    def from_raw(self, raw: int, width: int) -> Any:
        return raw.to_bytes(width // 8, "big").decode("latin-1")

    def to_raw(self, value: Any, where: str) -> tuple[int, int]:
        try:
            data = value.encode("latin-1") if isinstance(value, str) else None
        except UnicodeEncodeError:
            data = None
        if data is None:
            raise _bad_value(where, self.id, value, "a text of ISO 8859-1 characters")
        return int.from_bytes(data, "big"), 8 * len(data)


@dataclass(frozen=True, slots=True)
class Utf8(Latin1):
    """utf8: text as its UTF-8 code units (bytes that are no UTF-8 kept as surrogate escapes)."""

    def from_raw(self, raw: int, width: int) -> Any:
        return raw.to_bytes(width // 8, "big").decode("utf-8", "surrogateescape")

    def to_raw(self, value: Any, where: str) -> tuple[int, int]:
        try:
            data = value.encode("utf-8", "surrogateescape") if isinstance(value, str) else None
        except UnicodeEncodeError:
            data = None
        if data is None:
            raise _bad_value(where, self.id, value, "a text")
        return int.from_bytes(data, "big"), 8 * len(data)


def frame(payload: bytes) -> bytes:
    """The frame of a payload: preamble, length, payload, CRC-24Q."""
    if len(payload) > 1023:
        raise NmeaError("bad_value", f"a payload takes at most 1023 bytes, not {len(payload)}", "RTCM3")
    head = bytes((PREAMBLE, len(payload) >> 8, len(payload) & 0xFF)) + payload
    return head + crc24q(head)


def payload_of(data: bytes) -> bytes:
    """The payload of the one frame `data` holds, its preamble, length and checksum checked."""
    if not data or data[0] != PREAMBLE:
        raise NmeaError("bad_sync", f"an RTCM 3 frame starts with D3, not {data[:1].hex().upper() or 'nothing'}",
                        "RTCM3")
    if len(data) < HEADER_SIZE + CHECKSUM_SIZE:
        raise NmeaError("short_frame", f"a frame takes at least 6 bytes, there are {len(data)}", "RTCM3")
    size = HEADER_SIZE + ((data[1] & 0x03) << 8 | data[2]) + CHECKSUM_SIZE
    if len(data) != size:
        kind = "short_frame" if len(data) < size else "long_frame"
        raise NmeaError(kind, f"the length field says {size} bytes, the frame has {len(data)}", "RTCM3")
    expected = crc24q(data[:-CHECKSUM_SIZE])
    if data[-CHECKSUM_SIZE:] != expected:
        raise NmeaError("bad_checksum", f"checksum {data[-3:].hex(' ').upper()}, computed "
                        f"{expected.hex(' ').upper()}", "RTCM3")
    return bytes(data[HEADER_SIZE:-CHECKSUM_SIZE])


@dataclass(kw_only=True)
class Message(Record):
    """What every decoded RTCM 3 message has besides its layout's fields: the bits after them
    (`trailing`: the padding to a whole byte, and anything a sender adds), as sent."""

    NUMBERS: ClassVar[tuple[int, ...]]
    """The message numbers the layout describes."""
    PROTOCOL: ClassVar[str] = "RTCM3"
    """How `nmea show` names the protocol of its rows (`RTCM3 1005`)."""

    @property
    def ADDRESS(self) -> str:  # noqa: N802 (the name the binary messages' rows share)
        """The message number, as `nmea show` names the row after the protocol."""
        return str(getattr(self, "message_number"))

    @property
    def where(self) -> str:
        return f"RTCM3 {getattr(self, 'message_number')}"

    @classmethod
    def from_payload(cls, payload: bytes) -> Message:
        """The message of a payload of this layout (a short one raises short_payload, naming the
        field it cuts)."""
        number = payload[0] << 4 | payload[1] >> 4 if len(payload) >= 2 else None
        reader = BitReader(int.from_bytes(payload, "big"), 8 * len(payload), f"RTCM3 {number}")
        values = cls.read(reader)
        return cls(**values, trailing=bits_text(reader.value & ((1 << reader.remaining) - 1), reader.remaining))

    def payload(self) -> bytes:
        """The payload bytes: the fields, then trailing (zeros to a whole byte when it falls short)."""
        writer = BitWriter()
        self.write(writer, self.where)
        if writer.length % 8:
            writer.put(0, -writer.length % 8)
        return writer.value.to_bytes(writer.length // 8, "big")

    def encode(self) -> bytes:
        """The whole frame."""
        return frame(self.payload())

    def to_dict(self) -> dict[str, Any]:
        """The decoded JSON (generated/vectors/rtcm3.jsonl): `message` (the spec's id), each field
        present by its id (a number in a unit beside its raw integer as <id>_raw, a special value
        by its id, a group as a list of its entries), then trailing."""
        return {"message": self.ID, **self._json(), "trailing": self.trailing}


@dataclass
class Unknown:
    """A frame of a message number the spec does not describe (proprietary 4001-4095, ...), kept
    with its payload."""

    message_number: int | None
    payload: bytes

    def encode(self) -> bytes:
        return frame(self.payload)

    def to_dict(self) -> dict[str, Any]:
        return {"message": None, "message_number": self.message_number, "payload": self.payload.hex()}


def message(by_number: dict[int, type[Message]], payload: bytes) -> Message | Unknown:
    """The message of a payload, as the class its number names in `by_number`; an Unknown for a
    number no class describes (or a payload too short to hold one)."""
    number = payload[0] << 4 | payload[1] >> 4 if len(payload) >= 2 else None
    cls = by_number.get(number) if number is not None else None
    if cls is None:
        return Unknown(number, bytes(payload))
    return cls.from_payload(payload)


def decode(by_number: dict[int, type[Message]], data: bytes) -> Message | Unknown:
    """message(by_number, payload_of(data)): the message of a whole frame."""
    return message(by_number, payload_of(data))
