"""The resolve pass: the facts of the model derived from what the YAML says, before any check.

Loading (build.py) turns each document into model objects holding what the file says; this pass
links them (a field's enum, bitfield and fact of a fix, a table parameter's, a command's reply sentences) and
works out where each field is on the wire (its 1-based index, its group) and whether each
example's checksum holds. The checks (checks.py)
then only judge: a reference left unlinked here is an error they report, with its file and line.
"""

from __future__ import annotations

from . import reference
from .model import Group, Layout, Payload, PayloadChoice, PayloadField, PayloadGroup, Spec


def resolve(spec: Spec) -> None:
    spec.enum_by_id = {e.id: e for e in spec.enums}
    bitfields = {b.id: b for b in spec.bitfields}
    for table in spec.tables:
        for p in table.parameters:
            p.enum = spec.enum_by_id.get(p.enum_id) if p.enum_id is not None else None
            p.bitfield = bitfields.get(p.bitfield_id) if p.bitfield_id is not None else None
    facts = {fact.id: fact for fact in spec.facts}
    sentences = {s.id: s for s in spec.sentences}
    for sentence in spec.sentences:
        sentence.replies = []
        for rule in sentence.reply_rules:
            rule.sentence = sentences.get(rule.sentence_id)
            if rule.sentence is not None and rule.sentence not in sentence.replies:
                sentence.replies.append(rule.sentence)
        for example in sentence.examples:
            example.checksum_ok = (sentence.framing == "text" or "*" not in example.raw and example.raw.startswith("$")
                                   or checksum_ok(example.raw))
        for layout in sentence.layouts:
            _place(layout)
            for f in layout.all_fields:
                f.enum = spec.enum_by_id.get(f.enum_id) if f.enum_id is not None else None
                f.bitfield = bitfields.get(f.bitfield_id) if f.bitfield_id is not None else None
                f.fact = facts.get(f.fix_id) if f.fix_id is not None else None
    for payload in [*spec.payloads, *spec.applications, *spec.bit_messages]:
        _place_bits(payload)
        for f in payload.fields:
            f.enum = spec.enum_by_id.get(f.enum_id) if f.enum_id is not None else None
    for payload in spec.payloads:
        payload.applications = [a for a in spec.applications if set(a.carriers) & set(payload.types)]
    classes = {p.id: p.classes for p in spec.protocols}
    orders = {p.id: p.byte_order for p in spec.protocols}
    in_payload = {p.id for p in spec.protocols if p.identity}   # SkyTraq, SiRF: the id opens the payload
    for message in spec.binary:
        message.class_number = classes.get(message.protocol, {}).get(message.msg_class, 0)
        message.byte_order = orders.get(message.protocol, "little")
        message.header_key = message.protocol not in in_payload
        for layout in message.layouts:
            _place_bits(layout)
            for f in layout.fields + [part for f in layout.fields for part in f.parts]:
                f.enum = spec.enum_by_id.get(f.enum_id) if f.enum_id is not None else None
                f.byte_order = message.byte_order


def checksum_ok(line: str) -> bool:
    """Whether a `$` line's checksum holds; a bare '*' (checksum left out, as ST's manual writes
    its commands) holds too."""
    if line.startswith("$") and line.endswith("*") and line.count("*") == 1:
        return True
    star = line.rfind("*")
    if not line or line[0] not in "$!" or star < 0 or len(line) != star + 3:
        return False
    try:
        return int(line[star + 1:], 16) == reference.rt.checksum(line[1:star])
    except ValueError:
        return False


def _place(layout: Layout) -> None:
    """Each item's 1-based wire index (a group's first entry at its place, its fields' within an
    entry) and each grouped field's group."""
    index = 1
    for item in layout.items:
        item.wire_index = index
        if isinstance(item, Group):
            offset = 1
            for f in item.fields:
                f.group = item
                f.wire_index = offset
                offset += f.wire_width
            index += item.min * item.width
        else:
            index += item.wire_width




def _place_bits(payload: Payload) -> None:
    """Each item's first bit while no variable item comes before it (None after one), and each
    choice's selector (a top-level field; a group entry's choice: a field of the entry before
    it, its offsets counted from the entry's first bit)."""
    top = {f.id: f for f in payload.items if isinstance(f, PayloadField)}

    def place(items: list, offset: int | None, fields: dict[str, PayloadField]) -> None:
        for item in items:
            item.offset = offset
            if isinstance(item, PayloadChoice):
                item.selector = fields.get(item.by)
                for case in item.cases:
                    place(case.items, offset, fields)
            elif isinstance(item, PayloadGroup) and item.choices:
                entry: dict[str, PayloadField] = {}
                at: int | None = 0
                for part in item.items:   # an entry's selector comes before its choice (rule A013)
                    part.offset = at
                    if isinstance(part, PayloadChoice):
                        part.selector = entry.get(part.by)
                        for case in part.cases:
                            place(case.items, at, {})
                    else:
                        entry[part.id] = part
                    width = part.bits if isinstance(part, PayloadField) else part.width
                    at = None if at is None or width is None else at + width
            width = item.width
            offset = None if offset is None or width is None else offset + width

    place(payload.items, 0, top)
