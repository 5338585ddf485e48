"""A reference decoder that interprets the model directly, over the hand-written Python runtime.

The generator uses it to check every example against its expected values, and to compute the
JSON that the generated tests of every language must reproduce. It is deliberately independent
of the templates: generated code that disagrees with it is wrong.
"""

from __future__ import annotations

import importlib.util
import sys
from dataclasses import dataclass
from decimal import Decimal
from pathlib import Path
from types import ModuleType
from typing import Any

from .model import Field, Group, Layout, Sentence, Spec


def _load_runtime() -> ModuleType:
    path = Path(__file__).resolve().parent.parent / "templates" / "python" / "runtime.py"
    spec = importlib.util.spec_from_file_location("_nmea_reference_runtime", path)
    assert spec and spec.loader
    module = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = module
    spec.loader.exec_module(module)
    return module


rt = _load_runtime()


@dataclass
class Decoded:
    frame: Any
    sentence: Sentence | None
    layout: Layout | None
    values: list[tuple[str, Any]]  # (field or group id, value) for every item on the wire


class _EnumMember:
    """Stand-in for a generated enum member: the reference decoder has no generated classes."""

    def __init__(self, code: str, value_id: str) -> None:
        self.code = code
        self.id = value_id


def decode(spec: Spec, line: str) -> Decoded:
    frame = rt.frame(line)
    sentence = _find(spec, frame)
    if sentence is None:
        return Decoded(frame, None, None, [])
    first_error = None
    for layout in sentence.layouts:
        try:
            return Decoded(frame, sentence, layout, _decode_layout(sentence, layout, frame))
        except rt.NmeaError as err:
            first_error = first_error or err
    raise first_error


def _find(spec: Spec, frame: Any) -> Sentence | None:
    if not rt.is_standard_address(frame.start, frame.address):
        return None
    return spec.sentence(frame.address[2:])


def _decode_layout(sentence: Sentence, layout: Layout, frame: Any) -> list[tuple[str, Any]]:
    fields = frame.fields
    count = len(fields)
    address = frame.address
    group = layout.group
    if group is not None:
        repeats, extra = rt.split_group(address, sentence.id, group.id, count, layout.fixed_count,
                                        group.width, group.min, group.max, layout.optional_count)
    else:
        if count < layout.fixed_count:
            raise rt.too_few(address, sentence.id, layout.fixed_count, count)
        if count > layout.max_fields:
            raise rt.too_many(address, sentence.id, layout.max_fields, count)
        repeats, extra = 0, count - layout.fixed_count
    values: list[tuple[str, Any]] = []
    pos = 0
    optional_left = extra
    for item in layout.items:
        if isinstance(item, Group):
            entries = []
            for r in range(repeats):
                entry = []
                for f in item.fields:
                    entry.append((f.id, _field(f, fields, pos, address, f"{item.id}[{r + 1}].{f.id}")))
                    pos += f.wire_width
                entries.append(entry)
            values.append((item.id, entries))
            continue
        if item.is_optional:
            if optional_left < item.wire_width:
                break
            optional_left -= item.wire_width
        values.append((item.id, _field(item, fields, pos, address, item.id)))
        pos += item.wire_width
    return values


def _bound(value: float | None) -> Decimal | None:
    return None if value is None else Decimal(str(value))


def _field(f: Field, fields: list[str], pos: int, address: str, name: str) -> Any:
    text = fields[pos]
    index = pos + 1
    t = f.type
    if t == "integer":
        return rt.integer_field(text, address, index, name, f.expected, _bound(f.min), _bound(f.max))
    if t == "decimal":
        return rt.decimal_field(text, address, index, name, f.expected, _bound(f.min), _bound(f.max))
    if t == "hex":
        return rt.hex_field(text, address, index, name, f.expected)
    if t == "time":
        return rt.time_field(text, address, index, name, f.expected)
    if t == "date":
        return rt.date_field(text, address, index, name, f.expected)
    if t in ("latitude", "longitude"):
        return rt.coordinate_field(text, fields[pos + 1], address, index, name, f.expected,
                                   f.hemisphere_expected, f.hemispheres)
    if t == "char":
        return rt.char_field(text, address, index, name, f.expected)
    if t == "literal":
        return rt.literal_field(text, address, index, name, f.expected, f.value)
    if t == "text":
        return rt.text_field(text, address, index, name, f.expected, f.max_length)
    assert f.enum is not None
    by_code = {v.code: _EnumMember(v.code, v.id) for v in f.enum.values}
    if t == "enum":
        return rt.enum_field(text, address, index, name, f.expected, by_code, f.enum.code_class,
                             f.enum.min_len, f.enum.max_len)
    return rt.enum_chars_field(text, address, index, name, f.expected, by_code, f.enum.code_class,
                               f.max_length)


def _text(value: Any) -> str:
    if isinstance(value, _EnumMember):
        return rt.json_str(value.code)
    if isinstance(value, list):
        return rt.json_str("".join(v.code if isinstance(v, _EnumMember) else v for v in value))
    return rt.text_json(value)


def _value(value: Any) -> str:
    if isinstance(value, _EnumMember):
        return rt.json_str(value.id)
    if isinstance(value, list):
        return "[" + ",".join(rt.json_str(v.id if isinstance(v, _EnumMember) else v) for v in value) + "]"
    return rt.value_json(value)


def fields_json(decoded: Decoded, values: bool = False) -> str:
    """The `fields` object of a known sentence, in the lossless or the decoded (`values`) form."""
    show = _value if values else _text
    parts = []
    for item_id, value in decoded.values:
        if _is_group(decoded.layout, item_id):
            entries = []
            for entry in value:
                if len(entry) == 1:
                    entries.append(show(entry[0][1]))
                else:
                    entries.append("{" + ",".join(f'"{k}":{show(v)}' for k, v in entry) + "}")
            parts.append(f'"{item_id}":[' + ",".join(entries) + "]")
        else:
            parts.append(f'"{item_id}":{show(value)}')
    return "{" + ",".join(parts) + "}"


def to_json(decoded: Decoded, values: bool = False) -> str:
    """The JSON line that every language's `decode` (or `decode --values`) prints."""
    frame = decoded.frame
    head = f'{{"ok":true,"start":{rt.json_str(frame.start)},"address":{rt.json_str(frame.address)},'
    tail = f',"checksum":{rt.json_opt(frame.checksum)}}}'
    if decoded.sentence is None:
        fields = "[" + ",".join(rt.json_str(f) for f in frame.fields) + "]"
        return head + '"talker":null,"sentence":null,"variant":null,"fields":' + fields + tail
    variant = rt.json_opt(decoded.layout.id if decoded.layout else None)
    return (head + f'"talker":{rt.json_str(frame.address[:-3])},"sentence":{rt.json_str(decoded.sentence.id)},'
            f'"variant":{variant},"fields":{fields_json(decoded, values)}' + tail)


def _is_group(layout: Layout | None, item_id: str) -> bool:
    return layout is not None and layout.group is not None and layout.group.id == item_id


def decode_json(spec: Spec, line: str, values: bool = False) -> str:
    """decode's output line for `line`: the sentence or the error."""
    try:
        return to_json(decode(spec, line), values)
    except rt.NmeaError as err:
        return err.to_json()
