"""A reference decoder that interprets the model directly, over the hand-written Python runtime.

The generator uses it to check every example against its expected values, and to compute the
JSON that the generated tests of every language must reproduce. It is deliberately independent
of the runtimes: generated code that disagrees with it is wrong.
"""

from __future__ import annotations

import importlib.util
import sys
from dataclasses import dataclass, field
from decimal import InvalidOperation
from types import ModuleType
from typing import Any

from .field_types import Reading
from .model import Field, Group, Layout, Sentence, Spec
from .paths import ROOT


def _load_runtime() -> ModuleType:
    path = ROOT / "runtime" / "python" / "runtime.py"
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
    # For every item on the wire: (field or group id, value, wire texts). A group's value is a
    # list of entries, each a list of (field id, value, texts).
    values: list[tuple[str, Any, Any]]
    problems: list[Any] = field(default_factory=list)   # the runtime's NmeaError of each problem


class _EnumMember:
    """Stand-in for a generated enum member: the reference decoder has no generated classes."""

    def __init__(self, code: str, value_id: str) -> None:
        self.code = code
        self.id = value_id


def candidates(spec: Spec, line: str, strict: bool = False) -> tuple[Any, list[tuple[Sentence, Layout]]]:
    """The line's frame and the layouts that may parse it, in order (none: a generic sentence);
    `strict` refuses a checksum of one digit."""
    if line[:1] not in ("$", "!") and spec.text_command(rt.first_word(line)):
        frame = rt.text_frame(line)
        return frame, spec.text_command(frame.address)
    frame = rt.frame(line, strict=strict)
    found = spec.by_address(frame.address) if frame.start == "$" else []
    keyed = any(layout.selector is not None for _, layout in found)
    if not any(holds_selector(layout, frame.fields) if layout.selector is not None
               else not keyed or _reads_first(layout, frame)
               for _, layout in found):
        found = []  # a message of a known family the spec does not know: a generic sentence
    if not found and rt.is_standard_address(frame.start, frame.address):
        standard = spec.sentence(frame.address[2:])
        if standard is None and rt.is_query_address(frame.start, frame.address):
            standard = spec.sentence(rt.QUERY)
        if standard is not None and not standard.is_proprietary and standard.start == frame.start:
            found = [(standard, layout) for layout in standard.layouts]
    return frame, found


def decode(spec: Spec, line: str, lenient: bool = False, strict: bool = False) -> Decoded:
    """The line decoded as every runtime's parse does it with these options: a number outside its
    field's range is kept and listed as a problem unless `strict`; `lenient` leaves the other
    fields at fault empty (one at a time, each a problem)."""
    frame, candidates_ = candidates(spec, line, strict)
    if not candidates_:
        return Decoded(frame, None, None, [])
    try:
        return _first_fit(candidates_, frame)
    except rt.NmeaError as err:
        if err.kind != "bad_field" or (strict and not lenient) or line[:1] not in ("$", "!"):  # text commands: strict
            raise
        return _refit(candidates_, frame, err, lenient, strict)


def _first_fit(candidates_: list[tuple[Sentence, Layout]], frame: Any) -> Decoded:
    """The first layout that reads the line. A variant is passed over when the main layout of
    its sentence, tried last before it, refused the line at a field the variant reads the same
    way (Sentence.same_as_main): it is not what the variant is there for."""
    errors = []
    refused: tuple[Sentence, int] | None = None   # the main layout tried last: its bad field
    for sentence, layout in candidates_:
        if layout.id is not None and refused is not None and refused[0] is sentence \
                and refused[1] in sentence.same_as_main(layout):
            continue
        try:
            return Decoded(frame, sentence, layout, _decode_layout(sentence, layout, frame))
        except rt.NmeaError as err:
            errors.append((layout, err))
            if layout.id is None:
                refused = (sentence, err.field) if err.kind == "bad_field" and err.field is not None else None
    raise _best_error(errors, frame)


def _refit(candidates_: list[tuple[Sentence, Layout]], frame: Any, err: Any, lenient: bool, strict: bool) -> Decoded:
    """The runtimes' second reading of a line no layout fits: one field at fault at a time, a
    number outside its range kept (unless `strict`) or (`lenient`) any other field left empty,
    until a layout fits, a field cannot be helped, or there would be MAX_PROBLEMS + 1 problems."""
    fields = list(frame.fields)
    problems = []
    while err.kind == "bad_field" and err.field is not None and fields[err.field - 1] \
            and len(problems) < rt.MAX_PROBLEMS:
        if err.out_of_range and not strict:
            fields[err.field - 1] = rt.RangeKept(fields[err.field - 1])
        elif lenient:
            fields[err.field - 1] = ""
            err.out_of_range = False  # its problem: a field left empty, not a value kept
        else:
            break
        problems.append(err)
        try:
            decoded = _first_fit(candidates_, rt.Frame(frame.start, frame.address, fields, frame.checksum))
        except rt.NmeaError as again:
            err = again
            continue
        decoded.frame = frame
        decoded.problems = problems
        return decoded
    raise err


def holds_selector(layout: Layout, fields: list[str]) -> bool:
    """Whether the line's fields hold the layout's keyword in its place (ignoring case)."""
    at = layout.selector_at
    return layout.selector is not None and at < len(fields) and fields[at].upper() == layout.selector.upper()


def _best_error(errors: list[tuple[Layout, Any]], frame: Any) -> Any:
    """The error to report when no layout fits. The layouts whose keyword the line holds in its
    place (else all) are the contenders; of those, the first whose field count fitted (its error
    is a bad field) else the first."""
    contenders = [e for layout, e in errors if layout.selector is not None and holds_selector(layout, frame.fields)]
    contenders = contenders or [e for _, e in errors]
    return next((e for e in contenders if e.kind == "bad_field"), contenders[0])


def _decode_layout(sentence: Sentence, layout: Layout, frame: Any) -> list[tuple[str, Any, Any]]:
    fields = frame.fields
    count = len(fields)
    address = frame.address
    name = sentence.id if sentence.is_proprietary else sentence.id
    group = layout.group
    if group is not None:
        repeats, extra = rt.split_group(address, name, group.id, count, layout.fixed_count,
                                        group.width, group.min, group.max, layout.optional_count)
    else:
        if count < layout.fixed_count:
            raise rt.too_few(address, name, layout.fixed_count, count)
        if count > layout.max_fields:
            raise rt.too_many(address, name, layout.max_fields, count)
        repeats, extra = 0, count - layout.fixed_count
    ignore_case = sentence.framing == "text"
    values: list[tuple[str, Any, Any]] = []
    pos = 0
    optional_left = extra
    for item in layout.items:
        if isinstance(item, Group):
            entries = []
            for r in range(repeats):
                entry = []
                for f in item.fields:
                    value = _field(f, fields, pos, address, f"{item.id}[{r + 1}].{f.id}", ignore_case)
                    entry.append((f.id, value, fields[pos:pos + f.wire_width]))
                    pos += f.wire_width
                entries.append(entry)
            values.append((item.id, entries, None))
            continue
        if item.is_optional:
            if optional_left < item.wire_width:
                break
            optional_left -= item.wire_width
        value = _field(item, fields, pos, address, item.id, ignore_case)
        values.append((item.id, value, fields[pos:pos + item.wire_width]))
        pos += item.wire_width
    return values


def _reads_first(layout: Layout, frame: Any) -> bool:
    """Whether the line's first field reads as the first field of a keyword-less `layout` whose
    address has layouts with keywords (a number outside its range does; a layout without fields:
    whether the line has none; one that starts with a group: yes)."""
    if not layout.items:
        return not frame.fields
    first = layout.items[0]
    if isinstance(first, Group) or len(frame.fields) < first.wire_width:
        return True
    try:
        _field(first, frame.fields, 0, frame.address, first.id, False)
    except rt.NmeaError as err:
        return bool(err.out_of_range)
    return True


def _field(f: Field, fields: list[str], pos: int, address: str, name: str, ignore_case: bool) -> Any:
    at = Reading(rt, address, pos + 1, name, ignore_case, _EnumMember)
    return f.field_type.read(f, fields[pos:pos + f.wire_width], at)


def expect_json(layout: Layout, expect: dict[str, Any]) -> tuple[str, list[tuple[str, str]]]:
    """An example's `expect` in the decoded JSON form (`decode --values`), fields in wire order,
    and what is wrong with it: (key, message) for each value its field cannot hold and each key
    the layout lacks."""
    items = {i.id: i for i in layout.items}
    parts = []
    problems = []
    for item in layout.items:
        if item.id not in expect:
            continue
        try:
            parts.append(f'"{item.id}":{_expect_item(item, expect[item.id])}')
        except (TypeError, ValueError, KeyError, InvalidOperation) as exc:
            kind = "group" if isinstance(item, Group) else item.type
            problems.append((item.id, f"expect value of {item.id} does not fit its type {kind}: {exc}"))
    problems += [(key, f"expect names {key}, which the layout does not have") for key in expect if key not in items]
    return "{" + ",".join(parts) + "}", problems


def _expect_item(item: Field | Group, value: Any) -> str:
    if isinstance(item, Group):
        if not isinstance(value, list):
            raise TypeError("a group expects a list")
        if item.single:
            return "[" + ",".join(_expect_value(item.fields[0], v) for v in value) + "]"
        out = []
        for entry in value:
            if set(entry) != {f.id for f in item.fields}:
                raise KeyError(f"entry keys {sorted(entry)} differ from the group's fields")
            out.append("{" + ",".join(f'"{f.id}":{_expect_value(f, entry[f.id])}' for f in item.fields) + "}")
        return "[" + ",".join(out) + "]"
    return _expect_value(item, value)


def _expect_value(f: Field, value: Any) -> str:
    return "null" if value is None else f.field_type.expect_json(f, value, rt)


def _texts_json(texts: list[str]) -> str:
    """The lossless JSON of a field: its wire text(s), null when empty."""
    if len(texts) == 2:
        return "null" if texts == ["", ""] else f"[{rt.json_str(texts[0])},{rt.json_str(texts[1])}]"
    return "null" if not texts[0] else rt.json_str(texts[0])


def _value(value: Any) -> str:
    if isinstance(value, _EnumMember):
        return rt.json_str(value.id)
    if isinstance(value, list):
        return "[" + ",".join(rt.json_str(v.id if isinstance(v, _EnumMember) else v) for v in value) + "]"
    return rt.value_json(value)


def fields_json(decoded: Decoded, values: bool = False) -> str:
    """The `fields` object of a known sentence, in the lossless or the decoded (`values`) form."""
    def show(value: Any, texts: list[str]) -> str:
        return _value(value) if values else _texts_json(texts)

    parts = []
    for item_id, value, texts in decoded.values:
        if texts is None:  # a group
            entries = []
            for entry in value:
                if len(entry) == 1:
                    entries.append(show(entry[0][1], entry[0][2]))
                else:
                    entries.append("{" + ",".join(f'"{k}":{show(v, t)}' for k, v, t in entry) + "}")
            parts.append(f'"{item_id}":[' + ",".join(entries) + "]")
        else:
            parts.append(f'"{item_id}":{show(value, texts)}')
    return "{" + ",".join(parts) + "}"


def to_json(decoded: Decoded, values: bool = False) -> str:
    """The JSON line that every language's `decode` (or `decode --values`) prints."""
    frame = decoded.frame
    head = f'{{"ok":true,"start":{rt.json_str(frame.start)},"address":{rt.json_str(frame.address)},'
    tail = f',"checksum":{rt.json_opt(frame.checksum)}}}'
    short = rt.short_checksum_json(frame.checksum)  # a checksum of one digit: the first problem
    problem_items = ([short] if short else []) + [rt.problem_json(p) for p in decoded.problems]
    problems = ',"problems":[' + ",".join(problem_items) + "]" if problem_items else ""
    if decoded.sentence is None:
        fields = "[" + ",".join(rt.json_str(f) for f in frame.fields) + "]"
        return head + '"talker":null,"sentence":null,"variant":null,"fields":' + fields + problems + tail
    variant = rt.json_opt(decoded.layout.id if decoded.layout else None)
    # a standard sentence's talker: the address but the formatter (a query's: two talker IDs)
    talker = "null" if decoded.sentence.is_proprietary else rt.json_str(frame.address[:-len(decoded.sentence.id)])
    return (head + f'"talker":{talker},"sentence":{rt.json_str(decoded.sentence.id)},'
            f'"variant":{variant},"fields":{fields_json(decoded, values)}{problems}' + tail)


def decode_json(spec: Spec, line: str, values: bool = False, lenient: bool = False, strict: bool = False) -> str:
    """decode's output line for `line` (with decode's --lenient, --strict): the sentence (after
    its TAG blocks, which come last in the JSON) or the error."""
    try:
        if line[:1] != "\\":
            return to_json(decode(spec, line, lenient, strict), values)
        if len(line) > rt.MAX_LINE:
            raise rt.NmeaError("too_long", f"line is {len(line)} bytes, the limit is {rt.MAX_LINE}")
        blocks, rest = rt.read_tag_blocks(tag_block_class(spec), line)
        tags = '"tag_blocks":[' + ",".join(b.to_json() for b in blocks) + "]}"
        if not rest:
            return '{"ok":true,' + tags
        return to_json(decode(spec, rest, lenient, strict), values)[:-1] + "," + tags
    except rt.NmeaError as err:
        return err.to_json()


def tag_block_class(spec: Spec) -> type:
    """The runtime's TagBlock with the spec's codes, as the generated subclass has them."""
    codes = {c.code: rt.TagCode(c.code, c.id, c.type) for c in spec.tag_codes}
    return type("TagBlock", (rt.TagBlock,), {"__slots__": (), "CODES": codes})
