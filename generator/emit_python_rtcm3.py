"""Python emitter of the bit messages told by a number (spec/binary/rtcm3/messages): the package
`nmeaspec.rtcm3_messages`, a module per message with its dataclass and LAYOUT, the descriptor
that the bit layouts' one reader and one writer (runtime/python/ais.py) interpret, with RTCM 3's
frames and types (runtime/python/rtcm3.py). The descriptors are emit_python_ais's, with counts
(a member's value, or the bits set in mask members) and field-major groups."""

from __future__ import annotations

import dataclasses
import json
import textwrap

import jinja2

from .emit import header
from .emit_python import WIDTH, docstring
from . import emit_python_ais
from .emit_python_ais import _field_spec, entry_class, member
from .model import Ones, Payload, PayloadField, PayloadGroup, Spec

PACKAGE = "nmeaspec"


def _count(count: str | int | Ones) -> str:
    """A count as Python source: a number, a member's name, or a tuple of mask members."""
    if isinstance(count, Ones):
        return "(" + ", ".join(json.dumps(name) for name in count.fields) + ("," if len(count.fields) == 1 else "") + ")"
    return json.dumps(count)


def _field_lines(f: PayloadField, following: list, indent: int) -> list[str]:
    """emit_python_ais's descriptor of a field, with its `count` when it has one."""
    lines = _field_spec(f, [] if f.count is not None else following, indent)
    if f.count is None:
        return lines
    if len(lines) == 1:
        one = lines[0][:-2] + f", count={_count(f.count)}),"
        if indent + len(one) <= WIDTH:
            return [one]
        lines = [lines[0][:lines[0].index("(") + 1], *(f"    {a}," for a in lines[0][lines[0].index("(") + 1:-2]
                                                          .split(", ")), "),"]
    return lines[:-1] + [f"    count={_count(f.count)},", lines[-1]]


def _group_args(item: PayloadGroup, following: list) -> str:
    """A group's count (a field, or mask bits) and its order, after its bounds."""
    extra = f", count={_count(item.count)}" if item.count is not None else ""
    return extra + (", field_major=True" if item.field_major else "")


def layout_lines(payload: Payload, items: list, rest: list, indent: int) -> list[str]:
    """The descriptor entries of `items` (the items `rest` follow them), one or more lines each."""
    return emit_python_ais.layout_lines(payload, items, rest, indent, _field_lines, _group_args)


def _member(f: PayloadField) -> dict:
    """emit_python_ais's member, its data field number after its name; a sign-magnitude number
    may also be the special negative_zero."""
    named = f"{f.name} ({f.ref})" if f.ref else f.name
    found = member(dataclasses.replace(f, name=named, doc=named if f.doc == f.name else f.doc))
    if f.type == "smag" and "ais.Special" not in found["line"]:
        found["line"] = found["line"].replace(" | None = None", " | ais.Special | None = None")
    return found


def title(payload: Payload) -> str:
    numbers = ", ".join(map(str, payload.types))
    return f"{payload.name}: RTCM 3 message{'s' if len(payload.types) > 1 else ''} {numbers}."


def message_view(payload: Payload) -> dict:
    members: list[dict] = []
    entries: list[dict] = []
    for item in payload.items:
        if isinstance(item, PayloadGroup):
            name = entry_class(payload, item)
            count = (" x ".join(f"bits set in {n}" for n in item.count.fields) if isinstance(item.count, Ones)
                     else str(item.count))
            members.append({"line": f"{item.id}: list[{name}] = field(default_factory=list)",
                             "doc": docstring(f"{item.name}: {count} entries"
                                              f"{', sent field by field' if item.field_major else ''}.", 4)})
            entries.append({"class": name, "doc": docstring(f"One entry of {item.name.lower()}.", 4),
                            "members": [_member(f) for f in item.fields]})
        else:
            members += [_member(f) for f in ([item] if isinstance(item, PayloadField) else item.fields)]
    lines = [*textwrap.wrap(title(payload), WIDTH - 7), "", *textwrap.wrap(" ".join(payload.doc.split()), WIDTH - 4)]
    return {
        "payload": payload, "class": payload.camel, "members": members, "entries": entries,
        "doc": [line.replace("\\", "\\\\").replace('"""', '\\"\\"\\"') for line in lines],
        "numbers": "(" + ", ".join(map(str, payload.types)) + ("," if len(payload.types) == 1 else "") + ")",
        "title": title(payload),
        "layout": layout_lines(payload, payload.items, [], 8),
        "raws": [{"name": f.id, "doc": docstring(f"The raw integer of {f.id}.", 8)}
                 for f in payload.fields if f.scaled or f.type == "smag"],
        "modules": ", ".join(sorted({f.bit_type.module for f in payload.fields} | {"ais", "rtcm3"})),
        "uses_field": any(isinstance(i, PayloadGroup) for i in payload.items),
    }


def emit(spec: Spec, env: jinja2.Environment) -> dict[str, str]:
    messages = [m for m in spec.bit_messages if m.protocol == "rtcm3"]
    if not messages:
        return {}
    base = f"python/{PACKAGE}/rtcm3_messages"
    files: dict[str, str] = {}
    for message in messages:
        files[f"{base}/{message.id}.py"] = env.get_template("python/rtcm3_message.py.j2").render(
            header=header(spec, "#", [message.origin.file]), **message_view(message))
    by_number = sorted((number, m) for m in messages for number in m.types)
    imports = []
    for m in messages:
        one = f"from .{m.id} import {m.camel} as {m.camel}"
        imports += [one] if len(one) <= WIDTH else [f"from .{m.id} import (", f"    {m.camel} as {m.camel},", ")"]
    files[f"{base}/__init__.py"] = env.get_template("python/rtcm3_init.py.j2").render(
        header=header(spec, "#", [m.origin.file for m in messages]), messages=messages, by_number=by_number, imports=imports)
    return files
