"""The reference decoder of the bit messages told by a number (spec/binary/rtcm3/messages): a
frame's payload, bit by bit from the spec's model, into the decoded JSON the runtimes must make
(the spec's examples are checked with it; generated/vectors hold its output). Independent of the
runtimes: a slow, plain walk of the model."""

from __future__ import annotations

from typing import Any

from .model import Ones, Payload, PayloadChoice, PayloadField, PayloadGroup, Spec


class FrameError(Exception):
    def __init__(self, kind: str, message: str) -> None:
        super().__init__(f"{kind}: {message}")
        self.kind = kind


def crc24q(data: bytes) -> int:
    """CRC-24Q (polynomial 0x1864CFB, initial value 0)."""
    crc = 0
    for byte in data:
        crc ^= byte << 16
        for _ in range(8):
            crc = (crc << 1) ^ 0x1864CFB if crc & 0x800000 else crc << 1
    return crc & 0xFFFFFF


def payload_of(frame: bytes) -> bytes:
    """The payload of a whole RTCM 3 frame (preamble, length, checksum checked)."""
    if len(frame) < 6 or frame[0] != 0xD3:
        raise FrameError("bad_frame", "no D3 preamble and header")
    length = (frame[1] & 0x03) << 8 | frame[2]
    if len(frame) != length + 6:
        raise FrameError("bad_frame", f"the header says {length} payload bytes, the frame has {len(frame) - 6}")
    if crc24q(frame[:-3]) != int.from_bytes(frame[-3:], "big"):
        raise FrameError("bad_checksum", "CRC-24Q does not match")
    return frame[3:-3]


def ones(value: Any) -> int:
    """The bits set in a mask member's decoded value (an integer, or data as '0'/'1' text)."""
    return value.count("1") if isinstance(value, str) else bin(value).count("1")


def count_of(count: Any, raws: dict[str, Any]) -> int:
    """The number a `count` gives from the raw values read so far."""
    if isinstance(count, int):
        return count
    if isinstance(count, Ones):
        total = 1
        for name in count.fields:
            total *= ones(raws[name])
        return total
    return int(raws[count])


class _Reader:
    def __init__(self, bits: str, where: str) -> None:
        self.bits, self.pos, self.where = bits, 0, where

    def take(self, width: int, name: str) -> str:
        if self.pos + width > len(self.bits):
            raise FrameError("short_payload", f"{self.where}: {name} needs {width} bits at bit {self.pos}, "
                             f"{len(self.bits) - self.pos} left")
        self.pos += width
        return self.bits[self.pos - width:self.pos]


def _field(f: PayloadField, reader: _Reader, raws: dict[str, Any], out: dict[str, Any]) -> None:
    width = f.bits if f.bits is not None else count_of(f.count, raws) * f.bit_type.char_bits
    raw = f.bit_type.raw(reader.take(width, f.id))
    raws[f.id] = raw
    out.update(f.bit_type.json(f, raw))


def _items(items: list, reader: _Reader, raws: dict[str, Any], out: dict[str, Any]) -> None:
    for item in items:
        if isinstance(item, PayloadField):
            _field(item, reader, raws, out)
        elif isinstance(item, PayloadGroup):
            n = count_of(item.count, raws)
            if n > item.max:
                raise FrameError("bad_value", f"{reader.where}: {item.id} has {n} entries, at most {item.max}")
            entries: list[dict[str, Any]] = [{} for _ in range(n)]
            if item.field_major:
                for f in item.fields:
                    for entry in entries:
                        _field(f, reader, {}, entry)
            else:
                for entry in entries:
                    for f in item.fields:
                        _field(f, reader, {}, entry)
            out[item.id] = entries
        elif isinstance(item, PayloadChoice):
            raw = raws[item.by]
            raw = int(raw) if not isinstance(raw, bool) else int(raw)
            case = next((c for c in item.cases if c.holds(raw)), None) or next(
                (c for c in item.cases if c.is_default), None)
            if case is not None:
                _items(case.items, reader, raws, out)


def decode_payload(spec: Spec, protocol: str, payload: bytes) -> tuple[Payload, dict[str, Any]]:
    """The message a payload is and its decoded JSON (the bits after the layout as `trailing`)."""
    bits = "".join(format(b, "08b") for b in payload)
    number = int(bits[:12], 2) if len(bits) >= 12 else None
    message = next((m for m in spec.bit_messages if m.protocol == protocol and number in m.types), None)
    if message is None:
        raise FrameError("unknown_message", f"message number {number} is not one the spec describes")
    reader = _Reader(bits, f"{protocol.upper()} {number}")
    out: dict[str, Any] = {}
    _items(message.items, reader, {}, out)
    out["trailing"] = bits[reader.pos:]
    return message, out


def decode(spec: Spec, frame: bytes, protocol: str = "rtcm3") -> dict[str, Any]:
    """The decoded JSON of a whole frame: its message's (`message`: the spec's id, its fields,
    `trailing`), or for a number no file describes {message: null, message_number, payload}."""
    payload = payload_of(frame)
    try:
        message, out = decode_payload(spec, protocol, payload)
    except FrameError as err:
        if err.kind != "unknown_message":
            raise
        number = payload[0] << 4 | payload[1] >> 4 if len(payload) >= 2 else None
        return {"message": None, "message_number": number, "payload": payload.hex()}
    return {"message": message.id, **out}
