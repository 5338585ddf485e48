"""A reference decoder of binary frames (spec/binary): the frame checked against its protocol's
framing, the layout of its class and id picked, and its payload read by reference_ais's walker
over little-endian bytes.

The checks decode every example with it and the vectors (generated/vectors/ubx.jsonl) hold what
it decodes, which every runtime must reproduce. It shares no code with the runtimes' readers
(runtime/python/ubx.py): a runtime that disagrees with it is wrong, or it is.
"""

from __future__ import annotations

from typing import Any

from .model import BinaryMessage, Payload, Spec
from .reference_ais import PayloadError, _items

UBX_SYNC = b"\xb5\x62"


class _Bytes:
    """A cursor over a payload's bytes with _Bits' interface: widths in bits, whole bytes, each
    field's bits those of its little-endian integer."""

    def __init__(self, data: bytes, payload: Payload) -> None:
        self.data = data
        self.pos = 0   # bits
        self.payload = payload

    @property
    def left(self) -> int:
        return 8 * len(self.data) - self.pos

    def take(self, width: int, name: str) -> str:
        if width > self.left:
            raise PayloadError("short_payload", f"{self.payload.id}: {name} needs bytes {self.pos // 8}-"
                               f"{(self.pos + width) // 8 - 1}, the payload has {len(self.data)}")
        start = self.pos // 8
        self.pos += width
        value = int.from_bytes(self.data[start:self.pos // 8], "little")
        return format(value, f"0{width}b") if width else ""


def ubx_checksum(body: bytes) -> bytes:
    """Fletcher-8 over class, id, length and payload (UBX-13003221, "UBX checksum")."""
    a = b = 0
    for byte in body:
        a = (a + byte) % 256
        b = (b + a) % 256
    return bytes((a, b))


def ubx_frame(data: bytes) -> tuple[int, int, bytes]:
    """Class, id and payload of one whole UBX frame."""
    if data[:2] != UBX_SYNC or len(data) < 8:
        raise PayloadError("bad_frame", "a UBX frame is B5 62, class, id, length, payload and two checksum bytes")
    length = int.from_bytes(data[4:6], "little")
    if len(data) != 8 + length:
        raise PayloadError("bad_frame", f"the length field says {length} payload bytes, the frame has {len(data) - 8}")
    if ubx_checksum(data[2:-2]) != data[-2:]:
        raise PayloadError("bad_checksum", "the Fletcher-8 checksum does not match")
    return data[2], data[3], data[6:-2]


def message_of(spec: Spec, protocol: str, msg_class: int, msg_id: int) -> BinaryMessage | None:
    return next((m for m in spec.binary
                 if m.protocol == protocol and (m.class_number, m.msg_id) == (msg_class, msg_id)), None)


def layout_for(message: BinaryMessage, payload: bytes) -> Payload:
    """The layout a payload is read as: the first, in spec order, whose fixed length (when it has
    one) is the payload's and whose version (when it has one) the payload's version field holds;
    else the message's main layout (the first output one, else the last), which then names the
    field a short payload cuts or keeps a long one's rest as trailing."""
    for layout in message.layouts:
        fixed = layout.fixed_width
        if fixed is not None and fixed != 8 * len(payload):
            continue
        if layout.version is not None:
            version = next(f for f in layout.fields if f.id == "version")
            if version.offset is None or version.offset // 8 >= len(payload) \
                    or payload[version.offset // 8] != layout.version:
                continue
        return layout
    return next((layout for layout in message.layouts if "output" in layout.directions), message.layouts[-1])


def decode(spec: Spec, frame: bytes) -> dict[str, Any]:
    """The decoded JSON object of a whole UBX frame (the form of generated/vectors/ubx.jsonl):
    the layout's id as `message`, its fields, and the bytes after its last field as hex
    `trailing`."""
    msg_class, msg_id, payload = ubx_frame(frame)
    message = message_of(spec, "ubx", msg_class, msg_id)
    if message is None:
        return {"message": None, "class": msg_class, "id": msg_id, "payload": payload.hex()}
    layout = layout_for(message, payload)
    cursor = _Bytes(payload, layout)
    out: dict[str, Any] = {"message": layout.id}
    _items(layout.items, cursor, [], out)
    out["trailing"] = payload[cursor.pos // 8:].hex()
    return out
