"""A reference decoder of bit-packed payloads (spec/ais/messages) that interprets the model
directly, over the payload's bits as a text of '0' and '1'.

The checks decode every example with it and the vectors (generated/vectors/ais.jsonl) hold what
it decodes, which every runtime must reproduce. It shares no code with the runtimes' readers
(runtime/python/ais.py): a runtime that disagrees with it is wrong, or it is.
"""

from __future__ import annotations

from typing import Any

from .field_types import BIT_TYPES
from .model import Payload, PayloadChoice, PayloadField, PayloadGroup, PayloadItem, Spec


class PayloadError(ValueError):
    """A payload the reference decoder cannot read, with the kind of error every runtime reports
    (runtime/contract.yaml's payload_kinds)."""

    def __init__(self, kind: str, message: str) -> None:
        super().__init__(message)
        self.kind = kind


def armor_bits(payload: str, fill_bits: int) -> tuple[str, str]:
    """The message bits of an armored payload and the values of its fill bits."""
    if not 0 <= fill_bits <= 5 or fill_bits and not payload:
        raise PayloadError("bad_armor", f"fill bits are 0-5 (none for an empty payload), not {fill_bits}")
    bits = ""
    for ch in payload:
        value = ord(ch) - 48
        value -= 8 if value > 40 else 0
        if not 0 <= value < 64 or "W" < ch < "`":
            raise PayloadError("bad_armor", f"{ch!r} is not six-bit armoring")
        bits += f"{value:06b}"
    cut = len(bits) - fill_bits
    return bits[:cut], bits[cut:]


def payload_of(spec: Spec, message_type: int) -> Payload | None:
    return next((p for p in spec.payloads if message_type in p.types), None)


def after(items: list[PayloadItem]) -> int:
    """The bits the required fields after a variable item take (it leaves them these bits)."""
    return sum(i.bits or 0 for i in items if isinstance(i, PayloadField) and not i.optional)


class _Bits:
    def __init__(self, bits: str, payload: Payload) -> None:
        self.bits = bits
        self.pos = 0
        self.payload = payload

    @property
    def left(self) -> int:
        return len(self.bits) - self.pos

    def take(self, width: int, name: str) -> str:
        if width > self.left:
            raise PayloadError("short_payload",
                               f"{self.payload.id}: {name} needs {width} bits at bit {self.pos}, {self.left} left")
        self.pos += width
        return self.bits[self.pos - width:self.pos]


def _items(items: list, bits: Any, rest: list, out: dict[str, Any], start: int = 0) -> bool:
    """Decode `items` (followed by the items `rest`) into `out`; False when an optional field is
    missing (nothing after it is read). `bits` is a cursor over the payload: _Bits here, or
    reference_binary's over little-endian bytes (both give a field's bits as '0'/'1' text).
    `start`: the first bit of the record (a group's entry) whose bits a choice's offsets count."""
    for i, item in enumerate(items):
        following = items[i + 1:] + rest
        if isinstance(item, PayloadGroup) and item.stride is not None:
            _strided(item, bits, following, out)
        elif isinstance(item, PayloadGroup):
            count = item.count if isinstance(item.count, int) else out[item.count] if item.count else \
                min(item.max, max(bits.left - after(following), 0) // item.entry_width)
            if count < item.min or count * item.entry_width > bits.left:
                raise PayloadError("short_payload",
                                   f"{bits.payload.id}: {item.id} needs {max(count, item.min)} entries")
            entries = []
            for _ in range(count):
                entry: dict[str, Any] = {}
                _items(item.items, bits, [], entry, bits.pos)
                entries.append(entry)
            out[item.id] = entries
        elif isinstance(item, PayloadChoice):
            assert item.selector is not None and item.selector.offset is not None
            at, width = start + item.selector.offset, item.selector.bits or 0
            if at + width > len(bits.bits):
                raise PayloadError("short_payload", f"{bits.payload.id}: {item.by} needs bits {at}..{at + width - 1}")
            raw = int(bits.bits[at:at + width], 2)
            case = next((c for c in item.cases if c.holds(raw)), None) or \
                next((c for c in item.cases if c.is_default), None)
            if case is not None and not _items(case.items, bits, following, out, start):
                return False
        else:
            t = BIT_TYPES[item.type]
            width = item.bits
            if width is None:
                width = max(bits.left - after(following), 0)
                width -= width % t.char_bits
            if item.optional and bits.left < width:
                return False
            out.update(t.json(item, t.raw(bits.take(width, item.id))))
    return True


def _strided(item: PayloadGroup, bits: Any, following: list, out: dict[str, Any],
             block: dict[str, Any] | None = None) -> None:
    """A group whose entries are as many bytes as its `stride` field says: each entry's fields
    read from a cursor over its own bytes (the last, `trailing`, takes what they leave), then the
    entries of the group it ends with, if any (counted by the entry, strided by `block`, the
    message's values)."""
    stride = (out if block is None else block)[str(item.stride)]
    count = 1 if item.count is None else item.count if isinstance(item.count, int) else out[str(item.count)]
    if count and 8 * stride < item.entry_width:
        raise PayloadError("bad_value", f"{bits.payload.id}: {item.stride} {stride} is less than the "
                           f"{item.entry_width // 8} bytes of {item.id}'s fields")
    if item.count is None:
        count = min(item.max, max(bits.left - after(following), 0) // (8 * stride))
    if count < item.min or 8 * count * stride > bits.left:
        raise PayloadError("short_payload", f"{bits.payload.id}: {item.id} needs {max(count, item.min)} entries")
    entries = []
    for k in range(count):
        if 8 * stride > bits.left:   # (after a nested group's entries: the next entry cut)
            raise PayloadError("short_payload", f"{bits.payload.id}: {item.id} needs {count - k} more entries")
        entry: dict[str, Any] = {}
        _items(item.fields, bits.within(8 * stride), [], entry)
        if item.nested is not None:
            _strided(item.nested, bits, [], entry, out if block is None else block)
        entries.append(entry)
    out[item.id] = entries


def decode(spec: Spec, payload: str, fill_bits: int) -> dict[str, Any]:
    """The decoded JSON object of an armored payload (the form of generated/vectors/ais.jsonl)."""
    bits_text, padding = armor_bits(payload, fill_bits)
    if len(bits_text) < 6:
        raise PayloadError("short_payload", "a payload has at least 6 bits")
    message = payload_of(spec, int(bits_text[:6], 2))
    if message is None:
        raise PayloadError("unknown_message", f"message type {int(bits_text[:6], 2)} is not described")
    bits = _Bits(bits_text, message)
    out: dict[str, Any] = {}
    _items(message.items, bits, [], out)
    application = _application(message, out)
    if application is not None:
        out["application"] = application
    out["trailing"] = bits.bits[bits.pos:]
    out["padding"] = padding
    return out


def _application(message: Payload, out: dict[str, Any]) -> dict[str, Any] | None:
    """The decoded application of the message's data bits (its DAC and FI name one the spec
    describes, carried by its type, that reads them); the data member then leaves `out`."""
    data = message.data_field
    if data is None or data.id not in out:
        return None
    key = tuple(out.get(name) for name in data.dispatch)
    application = next((a for a in message.applications
                        if out["message_type"] in a.carriers_of(key)), None)
    if application is None:
        return None
    bits = _Bits(out[data.id], application)
    decoded: dict[str, Any] = {}
    try:
        _items(application.items, bits, [], decoded)
    except PayloadError:
        return None
    del out[data.id]
    return {**decoded, "trailing": bits.bits[bits.pos:]}
