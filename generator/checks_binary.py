"""Semantic checks of binary messages (spec/binary): the field checks of the bit payloads
(checks_payload, rules A002-A007) on each layout, then what binary frames add: where a message
lives and its class, bitfield parts, counted groups, layouts told apart, documents, replies and
examples; the keys of a configuration database (spec/binary/<protocol>/config_keys.yaml). Rule ids
B001-B010 (generator/rules.py)."""

from __future__ import annotations

from typing import Callable

from . import checks_payload, reference_binary
from .model import (CONFIG_TYPE_SIZE, BinaryMessage, BinaryProtocol, ConfigDatabase, Payload, PayloadField, PayloadGroup,
                    Spec)

Report = Callable[..., None]   # checks._Reporter: (origin, rule, message, *yaml path)


def _check_header_key(message: BinaryMessage, protocol: BinaryProtocol, report: Report) -> None:
    """A protocol without classes tells its messages by the payload's first bytes (SkyTraq, SiRF:
    an id of a byte, a sub_id), or by its header's number and revision (SBF) or id (Unicore): the message gives
    what its protocol tells them by, each within the header field's bits."""
    if protocol.identity:
        if message.revision is not None:
            report(message.origin, "B001", f"protocol {message.protocol} has no revisions: leave out revision",
                   "revision")
        if message.msg_id > 255:
            report(message.origin, "B001", f"id {message.msg_id} is over a byte", "id")
        return
    checksum = protocol.frame.get("checksum", {}).get("at")
    fields = [f for f in protocol.frame.get("header", [])
              if not f.get("counts") and "value" not in f and f["id"] != checksum and f.get("identity", True)]
    widths = [int(f["type"][1:]) * (8 if f["type"][0] == "u" else 1) for f in fields]
    if message.sub_id is not None:
        report(message.origin, "B001", f"protocol {message.protocol} has no sub-ids: leave out sub_id", "sub_id")
    if len(widths) == 1:   # Unicore: the header's message id alone
        if message.revision is not None:
            report(message.origin, "B001", f"protocol {message.protocol} has no revisions: leave out revision",
                   "revision")
        elif message.msg_id >= 1 << widths[0]:
            report(message.origin, "B001", f"id {message.msg_id} is over its {widths[0]} bits", "id")
    elif len(widths) != 2 or message.revision is None:
        report(message.origin, "B001", f"protocol {message.protocol} tells a message by its number and revision: "
               "give revision", "revision")
    elif message.msg_id >= 1 << widths[0] or message.revision >= 1 << widths[1]:
        report(message.origin, "B001", f"id {message.msg_id} or revision {message.revision} is over its "
               f"{widths[0]} or {widths[1]} bits", "id")


def check(spec: Spec, report: Report) -> None:
    """Everything but the examples (check_examples, once the spec holds together)."""
    protocols = {p.id: p for p in spec.protocols}
    owners: dict[tuple[str, int, int], str] = {}
    layout_ids = {layout.id for m in spec.binary for layout in m.layouts}
    for message in spec.binary:
        stem = message.origin.file.rsplit("/", 1)[-1].removesuffix(".yaml")
        if stem != message.id:
            report(message.origin, "S010", f"message {message.id} must live in {message.id}.yaml", "message")
        protocol = protocols.get(message.protocol)
        if protocol is not None and not protocol.classes:   # SkyTraq, SiRF: an id and perhaps a sub-id
            if message.msg_class:
                report(message.origin, "B001", f"protocol {message.protocol} has no classes: leave out class",
                       "class")
            _check_header_key(message, protocol, report)
        elif protocol is None or message.msg_class not in protocol.classes:
            report(message.origin, "B001", f"class {message.msg_class} is not a class of protocol {message.protocol}",
                   "class")
        elif not message.id.startswith(message.msg_class + "_"):
            report(message.origin, "B001", f"message {message.id} of class {message.msg_class} starts with "
                   f"{message.msg_class}_", "message")
        elif message.sub_id is not None or message.revision is not None:
            report(message.origin, "B001", f"a message of class {message.msg_class} has no sub_id or revision",
                   "sub_id" if message.sub_id is not None else "revision")
        if message.msg_class and message.msg_id > 255:
            report(message.origin, "B001", f"id {message.msg_id} is over a byte", "id")
        key = (message.protocol, *message.key)
        shorter = (message.protocol, message.msg_id)   # an id without sub-id takes every frame of that id
        if key in owners or message.sub_id is not None and shorter in owners and not message.msg_class:
            report(message.origin, "B001", f"{message.address} is also described by "
                   f"{owners.get(key) or owners[shorter]}", "id")
        owners.setdefault(key, message.id)
        for i, document in enumerate(message.documents):
            if protocol is not None and document not in protocol.documents:
                report(message.origin, "B005", f"{document} is not a document of protocol {message.protocol} "
                       f"({', '.join(protocol.documents)})", "documents", i)
        for layout in message.layouts:
            checks_payload.check_items(layout, report)
            _check_binary_items(layout, report)
            for i, reply in enumerate(layout.replies):
                if reply not in layout_ids:
                    report(layout.origin, "B006", f"reply {reply} is no layout of a binary message", "replies", i)
            if "poll" in layout.directions and not layout.replies:
                report(layout.origin, "B006", f"poll {layout.id} names the layout that answers it", "replies")
            for key, field_id in zip(("class", "id"), layout.acknowledges or ()):
                found = next((f for f in layout.fields if f.id == field_id), None)
                if found is None or found.type != "u1":
                    report(layout.origin, "B006", f"acknowledges.{key}: {field_id} is no u1 field of {layout.id}",
                           "acknowledges", key)
        _check_told_apart(message, report)
    for database in spec.config_keys:
        _check_config(database, protocols.get(database.protocol), report)


def _check_binary_items(layout: Payload, report: Report) -> None:
    """Byte types only, bitfield parts inside their word, counted groups after their count."""
    seen: dict[str, PayloadField] = {}
    for item in layout.items:
        fields = item.all_fields if isinstance(item, PayloadGroup) else [item] if isinstance(item, PayloadField) else []
        for f in fields:
            if not f.bit_type.in_bytes:
                report(f.origin, "B002", f"field {f.id}: {f.type} is a type of bit payloads, not of binary frames",
                       "type")
            if f.type in ("u8", "i8") and (f.divisor is not None or f.base is not None):
                report(f.origin, "B002", f"field {f.id}: a 64-bit integer takes no divisor or base, as its value "
                       "would not come back byte-exact from a float", "divisor" if f.divisor is not None else "base")
            if f.bits is not None and f.bits > 8 * 255 and not f.bit_type.size:
                report(f.origin, "B002", f"field {f.id}: {f.bits // 8} bytes, a fixed text, bytes or reserved field "
                       "has at most 255 (the C descriptor's byte): split it", "size")
            _check_float_specials(f, report)
            if f.parts and not f.bit_type.has_parts:
                report(f.origin, "B002", f"field {f.id}: only a bitfield word (x1, x2, x4) has parts", "parts")
            _check_parts(f, report)
        if isinstance(item, PayloadGroup) and isinstance(item.count, str):
            count = seen.get(item.count)
            if count is None or count.bit_type.name not in ("u1", "u2", "u4", "uint"):
                report(item.origin, "B003", f"group {item.id}: count {item.count} names no unsigned field or part "
                       "before it", "count")
        if isinstance(item, PayloadGroup) and item.stride is not None:
            stride = seen.get(item.stride)
            if stride is None or stride.bit_type.name not in ("u1", "u2", "u4"):
                report(item.origin, "B003", f"group {item.id}: stride {item.stride} names no unsigned field (u1, u2, "
                       "u4) before it", "stride")
            if item.field_major:
                report(item.origin, "B003", f"group {item.id}: a stride's entries are read one after the other, "
                       "not field by field", "order")
            if len(item.fields) < 2:
                report(item.origin, "B003", f"group {item.id}: a stride's entry has at least one field", "fields")
        if isinstance(item, PayloadGroup):
            _check_nested(item, seen, report)
        if isinstance(item, PayloadField):
            seen.update({f.id: f for f in (item, *item.parts)})


def _check_nested(group: PayloadGroup, seen: dict[str, PayloadField], report: Report) -> None:
    """B010: a group in a group's entry (SBF's N2 Type-2 sub-blocks after each Type-1 of
    SB1Length): the last item of an entry of a stride, counted by an unsigned field of that entry,
    strided by an unsigned field before the outer group; one level only."""
    inner = [i for i in group.items if isinstance(i, PayloadGroup)]
    if not inner:
        return
    nested = inner[0]
    if len(inner) > 1 or group.items[-1] is not nested:
        report(nested.origin, "B010", f"group {nested.id}: a group in an entry of {group.id} is the entry's last "
               "item, and its only group", "group")
    if group.stride is None or group.field_major:
        report(nested.origin, "B010", f"group {nested.id}: a group in an entry needs the entry's bytes: {group.id} "
               "names a stride (and reads its entries one after the other)", "group")
    entry = {f.id: f for f in group.fields for f in (f, *f.parts)}
    count = entry.get(nested.count) if isinstance(nested.count, str) else None
    if count is None or count.bit_type.name not in ("u1", "u2", "u4", "uint"):
        report(nested.origin, "B010", f"group {nested.id}: count {nested.count} names no unsigned field of the "
               f"entry of {group.id} before it", "count")
    stride = seen.get(nested.stride) if nested.stride is not None else None
    if stride is None or stride.bit_type.name not in ("u1", "u2", "u4"):
        report(nested.origin, "B010", f"group {nested.id}: stride {nested.stride} names no unsigned field (u1, u2, "
               f"u4) before {group.id}", "stride")
    if len(nested.fields) < 2:
        report(nested.origin, "B003", f"group {nested.id}: a stride's entry has at least one field", "fields")
    if nested.nested is not None or nested.field_major or nested.choices:
        report(nested.origin, "B010", f"group {nested.id}: a nested group's entry holds fields only (no group, "
               "choice or field-major order)", "fields")


def _check_float_specials(f: PayloadField, report: Report) -> None:
    """A003 of floats: a float field's special value is a float (`value`), a finite one in the
    field's width (it stands for the float of that width nearest to it), and no id the runtimes
    give a NaN or an infinity; an integer's is a raw integer."""
    floating = f.type in ("r4", "r8")
    for i, s in enumerate(f.special):
        if floating and s.value is None:
            report(f.origin, "A003", f"field {f.id}: a special value of a {f.type} field is its float (`value`), "
                   "not a raw integer", "special", i, "raw")
        elif not floating and s.value is not None:
            report(f.origin, "A003", f"field {f.id}: a special value of a {f.type} field is its raw integer (`raw`), "
                   "not a float", "special", i, "value")
        elif floating and s.raw < 0:
            report(f.origin, "A003", f"field {f.id}: special value {s.value!r} is no finite {f.type} float",
                   "special", i, "value")
        if floating and s.id in ("nan", "inf"):
            report(f.origin, "A003", f"field {f.id}: special value id {s.id} is what a {s.id.upper()} reads as",
                   "special", i, "id")


def _check_parts(f: PayloadField, report: Report) -> None:
    used = 0
    ids = {f.id}
    for i, part in enumerate(f.parts):
        checks_payload.check_field(part, report)
        if f.bits is not None and part.low + (part.bits or 0) > f.bits:
            report(part.origin, "B002", f"part {part.id} of {f.id} takes bits {part.low}-"
                   f"{part.low + (part.bits or 1) - 1} of a {f.bits}-bit word", "bit")
        mask = ((1 << (part.bits or 1)) - 1) << part.low
        if used & mask:
            report(part.origin, "B002", f"part {part.id} of {f.id} overlaps an earlier part", "bit")
        used |= mask
        if part.id in ids:
            report(part.origin, "A004", f"id {part.id} appears twice in bitfield {f.id}", "id")
        ids.add(part.id)


def _check_told_apart(message: BinaryMessage, report: Report) -> None:
    """Two layouts of one direction differ in their fixed length or in their selector's value (the
    same field, a u1 at a fixed offset: a type, command or version byte)."""
    ids: set[str] = set()
    for i, layout in enumerate(message.layouts):
        if layout.id in ids:
            report(layout.origin, "B004", f"layout id {layout.id} is used twice: give one a `variant`", "variant")
        ids.add(layout.id)
        if layout.select is not None:
            chosen = layout.select_field
            if chosen is None or chosen.type != "u1" or layout.select_at is None or chosen.optional:
                report(layout.origin, "B004", f"layout {layout.id} is selected by {layout.select[0]}, which is no u1 "
                       "field at a fixed offset (not optional)", "select" if layout.select[0] != "version" else "version")
        for other in message.layouts[:i]:
            if not set(layout.directions) & set(other.directions):
                continue
            if layout.select is not None and other.select is not None:
                if layout.select[0] != other.select[0] or layout.select_at != other.select_at:
                    report(layout.origin, "B004", f"layouts {other.id} and {layout.id} share a direction and are "
                           f"selected by different fields ({other.select[0]}, {layout.select[0]}) or offsets", "select")
                    continue
                if layout.select[1] != other.select[1]:
                    continue
            widths = layout.fixed_width, other.fixed_width
            if None not in widths and widths[0] != widths[1]:
                continue
            report(layout.origin, "B004", f"layouts {other.id} and {layout.id} share a direction and are not told "
                   "apart by a fixed length or a selector's value", "direction")


def check_examples(spec: Spec, report: Report) -> None:
    """Every example is a whole frame of its message that decodes to the values of its `expect`."""
    for message in spec.binary:
        for example in message.examples:
            try:
                decoded = reference_binary.decode(spec, example.frame)
            except reference_binary.PayloadError as err:
                report(example.origin, "B007", f"the example does not decode: {err}", "frame")
                continue
            if decoded["message"] not in {layout.id for layout in message.layouts}:
                report(example.origin, "B007", f"the example is not a frame of {message.address}", "frame")
                continue
            for key, value in (example.expect or {}).items():
                if key not in decoded:
                    report(example.origin, "B007", f"expect names {key}, which the example does not have", "expect",
                           key)
                elif decoded[key] != value or type(decoded[key]) is not type(value):
                    report(example.origin, "B007", f"{key} decodes to {decoded[key]!r}, not {value!r}", "expect", key)


_RESERVED_KEY_BITS = 0x8F00F000   # bits 12-15, 24-27 and 31 of a key id


def _check_config(database: ConfigDatabase, protocol: object, report: Report) -> None:
    """B008: ids and names unique, each id's group and size bits its group's and its type's; B009:
    enums named exist and fit, scales only on numbers, documents those of the protocol."""
    documents = getattr(protocol, "documents", None)
    if documents is None:
        report(database.origin, "B009", f"protocol {database.protocol} has no protocol.yaml", "config_keys")
        documents = {}
    names: dict[str, str] = {}
    ids: dict[int, str] = {}
    groups: dict[tuple[str, int], int] = {}
    for group in database.groups:
        if (group.name, group.id) in groups:
            report(group.origin, "B008", f"group {group.name} 0x{group.id:02X} is listed twice", "group")
        groups[(group.name, group.id)] = 1
        for i, document in enumerate(group.documents):
            if document not in documents:
                report(group.origin, "B009", f"{document} is not a document of protocol {database.protocol}",
                       "documents", i)
    for key in database.keys:
        for j, name in enumerate([key.item, *key.aliases]):
            full = f"CFG-{key.group}-{name}"
            if full in names:
                report(key.origin, "B008", f"{full} is also the name of key {names[full]}", *(("aliases", j - 1) if j
                                                                                             else ("item",)))
            names.setdefault(full, key.name)
        if key.id in ids:
            report(key.origin, "B008", f"{key.name}: id 0x{key.id:08X} is also the id of {ids[key.id]} (an other "
                   "name of one key is an alias)", "id")
        ids.setdefault(key.id, key.name)
        size = key.id >> 28 & 7
        if size != CONFIG_TYPE_SIZE[key.type]:
            report(key.origin, "B008", f"{key.name}: id 0x{key.id:08X} has size bits {size}, a {key.type} value has "
                   f"{CONFIG_TYPE_SIZE[key.type]}", "id")
        if key.id >> 16 & 0xFF != key.group_id:
            report(key.origin, "B008", f"{key.name}: id 0x{key.id:08X} is of group 0x{key.id >> 16 & 0xFF:02X}, not "
                   f"of its group's 0x{key.group_id:02X}", "id")
        if key.id & _RESERVED_KEY_BITS:
            report(key.origin, "B008", f"{key.name}: id 0x{key.id:08X} sets reserved bits", "id")
        if key.enum_id is not None:
            if key.enum is None:
                report(key.origin, "B009", f"{key.name}: enum {key.enum_id} is not in the file's enums", "enum")
            elif key.type[0] not in "EU":
                report(key.origin, "B009", f"{key.name}: a {key.type} value has no enum", "enum")
            else:
                bits = 8 * int(key.type[1])
                for value_id, value in key.enum.values.items():
                    if not 0 <= value < 1 << bits:
                        report(key.origin, "B009", f"{key.name}: enum {key.enum_id}'s {value_id} = {value} does not "
                               f"fit a {key.type} value", "enum")
        if key.scale is not None:
            if key.type[0] not in "UIR":
                report(key.origin, "B009", f"{key.name}: a {key.type} value has no scale", "scale")
            elif abs(1 / key.scale - round(1 / key.scale)) > 1e-6 * (1 / key.scale):
                report(key.origin, "B009", f"{key.name}: scale {key.scale} is not 1 over a whole number", "scale")
