"""A reference decoder of binary frames (spec/binary): the frame checked against its protocol's
framing, the layout of its class and id (or id and sub-id) picked, and its payload read by
reference_ais's walker over bytes in the protocol's byte order.

The checks decode every example with it and the vectors (generated/vectors/ubx.jsonl) hold what
it decodes, which every runtime must reproduce. It shares no code with the runtimes' readers
(runtime/python/ubx.py): a runtime that disagrees with it is wrong, or it is.
"""

from __future__ import annotations

from typing import Any

from .model import BinaryMessage, BinaryProtocol, Payload, Spec
from .reference_ais import PayloadError, _items

UBX_SYNC = b"\xb5\x62"


class _Bytes:
    """A cursor over a payload's bytes with _Bits' interface: widths in bits, whole bytes, each
    field's bits those of its integer in the protocol's byte order (characters and bytes: of
    their little-endian integer, as the field types read them: the bytes as sent)."""

    def __init__(self, data: bytes, payload: Payload, order: str = "little") -> None:
        self.data = data
        self.pos = 0   # bits
        self.payload = payload
        self.order = order
        self.as_sent = {f.id for f in payload.fields if f.type in ("ch", "bytes")} if order != "little" else set()

    @property
    def left(self) -> int:
        return 8 * len(self.data) - self.pos

    def take(self, width: int, name: str) -> str:
        if width > self.left:
            raise PayloadError("short_payload", f"{self.payload.id}: {name} needs bytes {self.pos // 8}-"
                               f"{(self.pos + width) // 8 - 1}, the payload has {len(self.data)}")
        start = self.pos // 8
        self.pos += width
        order = "little" if name in self.as_sent else self.order
        value = int.from_bytes(self.data[start:self.pos // 8], order)  # type: ignore[arg-type]
        return format(value, f"0{width}b") if width else ""


    def within(self, width: int) -> _Bytes:
        """A cursor over the next `width` bits alone (an entry of a stride), this one moved past them."""
        start = self.pos // 8
        self.pos += width
        inner = _Bytes(self.data[start:self.pos // 8], self.payload, self.order)
        return inner


def ubx_checksum(body: bytes) -> bytes:
    """Fletcher-8 over class, id, length and payload (UBX-13003221, "UBX checksum")."""
    a = b = 0
    for byte in body:
        a = (a + byte) % 256
        b = (b + a) % 256
    return bytes((a, b))


def _checksum(algorithm: str, data: bytes) -> bytes:
    """The checksum bytes of a frame (spec/schema/binary_protocol.schema.json, `algorithm`)."""
    if algorithm == "fletcher8":
        return ubx_checksum(data)
    if algorithm == "xor8":   # SkyTraq AN0028
        x = 0
        for byte in data:
            x ^= byte
        return bytes((x,))
    if algorithm == "sum15":   # SiRF binary
        return (sum(data) % (1 << 15)).to_bytes(2, "big")
    if algorithm == "sum32":   # CASIC: 32-bit little-endian words, a short last one padded with zeros
        padded = data + bytes(-len(data) % 4)
        total = sum(int.from_bytes(padded[i:i + 4], "little") for i in range(0, len(padded), 4))
        return (total % (1 << 32)).to_bytes(4, "little")
    if algorithm == "crc16_ccitt":   # SBF: CRC-CCITT (polynomial 0x1021, initial 0), little endian
        crc = 0
        for byte in data:
            crc ^= byte << 8
            for _ in range(8):
                crc = (crc << 1 ^ (0x1021 if crc & 0x8000 else 0)) & 0xFFFF
        return crc.to_bytes(2, "little")
    if algorithm == "crc32":   # Unicore: reflected 0xEDB88320, initial 0, no final inversion, little endian
        crc = 0
        for byte in data:
            crc ^= byte
            for _ in range(8):
                crc = crc >> 1 ^ (0xEDB88320 if crc & 1 else 0)
        return crc.to_bytes(4, "little")
    raise PayloadError("bad_frame", f"no reference checksum {algorithm}")


_CHECK_SIZE = {"fletcher8": 2, "xor8": 1, "sum15": 2, "sum32": 4, "crc16_ccitt": 2, "crc32": 4}


def protocol_frame(spec: Spec, data: bytes) -> tuple[BinaryProtocol, dict[str, int], bytes]:
    """The protocol of one whole frame (by its sync bytes), its header fields and its payload,
    read from protocol.yaml's `frame` facts: the sync, the header's fields (bytes or bits, in the
    protocol's byte order), the length, the checksum and the end bytes all checked."""
    protocol = next((p for p in spec.protocols if p.frame.get("sync") and data.startswith(bytes(p.frame["sync"]))
                     and p.id != "rtcm3"), None)
    if protocol is None:
        raise PayloadError("bad_frame", "the frame starts with no binary protocol's sync bytes")
    frame = protocol.frame
    order = protocol.byte_order
    name = protocol.id.upper()
    pos = 8 * len(frame["sync"])   # bits
    header: dict[str, int] = {}
    offsets: dict[str, int] = {"sync": 0}
    for f in frame["header"]:
        width = 8 * int(f["type"][1:]) if f["type"][0] == "u" else int(f["type"][1:])
        if (pos + width + 7) // 8 > len(data):
            raise PayloadError("bad_frame", f"a {name} frame is cut in its header")
        offsets[f["id"]] = pos // 8
        first, last = pos // 8, (pos + width + 7) // 8
        if width % 8 == 0 and pos % 8 == 0:
            header[f["id"]] = int.from_bytes(data[first:last], order)  # type: ignore[arg-type]
        elif order == "big":   # bits of a big-endian header, most significant first
            word = int.from_bytes(data[first:last], "big")
            header[f["id"]] = word >> (8 * last - pos - width) & ((1 << width) - 1)
        else:   # of a little-endian one, least significant first
            word = int.from_bytes(data[first:last], "little")
            header[f["id"]] = word >> (pos - 8 * first) & ((1 << width) - 1)
        pos += width
    start = pos // 8
    offsets["payload"] = start
    counted = next(f for f in frame["header"] if f.get("counts"))
    algorithm = frame["checksum"]["algorithm"]
    end = bytes(frame.get("end", []))
    at = frame["checksum"].get("at")   # SBF: in the header, before what it covers
    trailer = (0 if at else _CHECK_SIZE[algorithm]) + len(end)
    length = header[counted["id"]] - (start + trailer if counted["counts"] == "frame" else 0)
    size = start + length + trailer
    if len(data) != size or length < 0:
        raise PayloadError("bad_frame", f"the length field says {length} payload bytes, the {name} frame has "
                           f"{len(data) - size + length}")
    body = data[offsets[frame["checksum"]["over"][0]]:start + length]
    sent = data[offsets[at]:offsets[at] + _CHECK_SIZE[algorithm]] + data[start + length:] if at \
        else data[start + length:]
    if _checksum(algorithm, body) + end != sent:
        raise PayloadError("bad_checksum", f"the {name} checksum or end bytes do not match")
    return protocol, header, data[start:start + length]


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


def message_by_key(spec: Spec, protocol: str, payload: bytes) -> BinaryMessage | None:
    """A protocol without classes: the message of a payload's id and sub-id, else of its id alone."""
    found = {m.key: m for m in spec.binary if m.protocol == protocol}
    return found.get(tuple(payload[:2])) if len(payload) >= 2 and tuple(payload[:2]) in found \
        else found.get(tuple(payload[:1]))


def layout_for(message: BinaryMessage, payload: bytes) -> Payload:
    """The layout a payload is read as: the first, in spec order, whose fixed length (when it has
    one) is the payload's and whose selector's value (when it has one: a type or version byte) the
    payload's byte holds; else (a selector value no layout names) the first selected layout of the
    payload's fixed length, the byte kept as sent; else the message's main layout (the first output
    one, else the last), which then names the field a short payload cuts or keeps a long one's rest
    as trailing."""
    for layout in message.layouts:
        fixed = layout.fixed_width
        if fixed is not None and fixed != 8 * len(payload):
            continue
        if layout.select is not None:
            at = layout.select_at
            if at is None or at >= len(payload) or payload[at] != layout.select[1]:
                continue
        return layout
    for layout in message.layouts:   # a selector value no layout names: the selected layout of its length
        if layout.select is not None and layout.fixed_width == 8 * len(payload):
            return layout
    return next((layout for layout in message.layouts if "output" in layout.directions), message.layouts[-1])


def decode(spec: Spec, frame: bytes) -> dict[str, Any]:
    """The decoded JSON object of a whole frame (the form of generated/vectors/ubx.jsonl and
    binary.jsonl): the layout's id as `message`, its fields, and the bytes after its last field as
    hex `trailing`."""
    if frame[:2] == UBX_SYNC:
        msg_class, msg_id, payload = ubx_frame(frame)
        message = message_of(spec, "ubx", msg_class, msg_id)
        if message is None:
            return {"message": None, "class": msg_class, "id": msg_id, "payload": payload.hex()}
        return _decode_payload(message, payload)
    protocol, header, payload = protocol_frame(spec, frame)
    kept = {f["id"]: header[f["id"]] for f in protocol.frame["header"] if f.get("identity", True) is False}
    out = _decode_frame(spec, protocol, header, payload)
    # the header's fields of `identity: false` (Unicore's time and status), which a message keeps
    return out if not kept else {"message": out.pop("message"), "header": kept, **out}


def _decode_frame(spec: Spec, protocol: BinaryProtocol, header: dict[str, int], payload: bytes) -> dict[str, Any]:
    if protocol.classes:
        message = message_of(spec, protocol.id, header["class"], header["id"])
        if message is None:
            return {"message": None, "class": header["class"], "id": header["id"], "payload": payload.hex()}
        return _decode_payload(message, payload)
    if not protocol.identity:   # SBF, Unicore: the header's block number and revision (its id) tell the message
        names = [f["id"] for f in protocol.frame["header"]
                 if not f.get("counts") and "value" not in f and f["id"] != protocol.frame["checksum"].get("at")
                 and f.get("identity", True)]
        key = tuple(header[name] for name in names)
        message = next((m for m in spec.binary if m.protocol == protocol.id and m.key == key), None)
        if message is None:
            return {"message": None, **dict(zip(names, key)), "payload": payload.hex()}
        return _decode_payload(message, payload)
    message = message_by_key(spec, protocol.id, payload)
    if message is None:
        return {"message": None, "id": payload[0] if payload else None, "payload": payload[1:].hex()}
    return _decode_payload(message, payload[message.prefix:])


def _decode_payload(message: BinaryMessage, payload: bytes) -> dict[str, Any]:
    layout = layout_for(message, payload)
    cursor = _Bytes(payload, layout, message.byte_order)
    out: dict[str, Any] = {"message": layout.id}
    _items(layout.items, cursor, [], out)
    out["trailing"] = payload[cursor.pos // 8:].hex()
    return out
