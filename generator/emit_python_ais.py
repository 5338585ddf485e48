"""Python emitter of the bit-packed payloads (spec/ais/messages): the package
`nmeaspec.ais_messages`, a dataclass per message with its LAYOUT, the descriptor that the
runtime's one reader and one writer (runtime/python/ais.py) interpret."""

from __future__ import annotations

import json
import textwrap
from collections.abc import Callable

import jinja2

from .emit import header
from .emit_python import WIDTH, docstring
from .model import Payload, PayloadField, PayloadGroup, Spec
from .reference_ais import after

PACKAGE = "nmeaspec"


def member_type(f: PayloadField) -> str:
    """The Python type of a field's member: its type's, a float for a number with a divisor, a
    Special besides for one with special values."""
    base = f"{f.enum.camel} | int" if f.enum else f.bit_type.python_type
    if f.bit_type.numeric and (f.divisor or isinstance(f.base, float)):
        base = "float"
    return base + (" | ais.Special" if f.special and "ais.Special" not in base else "") + " | None"


def entry_class(payload: Payload, group: PayloadGroup) -> str:
    """The class of one entry of a group: BinaryAcknowledgeAck for binary_acknowledge's `acks`."""
    word = group.camel
    return payload.camel + (word[:-1] if word.endswith("s") else word + "Entry")


def _field_spec(f: PayloadField, following: list, indent: int) -> list[str]:
    """The descriptor of field `f` (the items `following` come after it) as lines of at most
    WIDTH characters at `indent`, with its trailing comma: on one line when it fits, else an
    argument a line (its special values a line each when they do not fit either)."""
    args = [json.dumps(f.id), str(f.bits)]
    if f.optional:
        args.append("optional=True")
    if f.bits is None and after(following):
        args.append(f"after={after(following)}")
    if f.divisor:
        args.append(f"divisor={f.divisor}")
    if f.base is not None:
        args.append(f"base={f.base}")
    specials = [f"ais.Special({json.dumps(s.id)}, {s.raw})" for s in f.special]
    if specials:
        args.append(f"special=({', '.join(specials)},)")
    if f.enum:
        args.append(f"enum={f.enum.camel}")
    if f.dispatch:
        args.append(f"dispatch=({', '.join(json.dumps(d) for d in f.dispatch)},)")
    if f.byte_order == "big" and f.type in ("ch", "bytes"):   # bytes as sent from a big-endian reader
        args.append("big=True")
    parts = [f"({p.low}, {' '.join(_field_spec(p, [], 0))[:-1]})" for p in f.parts]
    if parts:
        args.append(f"parts=({', '.join(parts)},)")
    # a field with an enum reads codes (an AIS enum, a UBX u1 with one); else its type's class
    call = "ais.Code(" if f.enum else f"{f.bit_type.module}.{f.bit_type.python_spec}("
    one = call + ", ".join(args) + "),"
    if indent + len(one) <= WIDTH:
        return [one]
    lines = [call]
    for arg in args:
        if arg.startswith("special=") and indent + 4 + len(arg) + 1 > WIDTH:
            lines += ["    special=(", *(f"        {s}," for s in specials), "    ),"]
        elif arg.startswith("parts=") and indent + 4 + len(arg) + 1 > WIDTH:
            lines += ["    parts=(", *(f"        {p}," for p in parts), "    ),"]
        else:
            lines.append(f"    {arg},")
    return lines + ["),"]


def group_extra(item: PayloadGroup, following: list) -> str:
    """The keyword arguments of an AIS group's descriptor after its bounds."""
    extra = f", after={after(following)}" if after(following) else ""
    extra += f", stride={json.dumps(item.stride)}" if item.stride else ""
    return extra + (f", count={json.dumps(item.count)}" if item.count else "")


def layout_lines(payload: Payload, items: list, rest: list, indent: int,
                 field_lines: Callable[[PayloadField, list, int], list[str]] = _field_spec,
                 group_args: Callable[[PayloadGroup, list], str] = group_extra) -> list[str]:
    """The descriptor entries of `items` (the items `rest` follow them), one or more lines each:
    a field's by `field_lines`, a group's keyword arguments by `group_args` (another protocol's
    bit layouts give their own)."""
    out: list[str] = []
    pad = " " * 4
    for i, item in enumerate(items):
        following = items[i + 1:] + rest
        if isinstance(item, PayloadField):
            out += field_lines(item, following, indent)
        elif isinstance(item, PayloadGroup):
            out.append(f"ais.Group({json.dumps(item.id)}, {entry_class(payload, item)}, (")
            out += [pad + line for line in layout_lines(payload, item.items, [], indent + 4, field_lines, group_args)]
            out.append(f"), {item.min}, {item.max}{group_args(item, following)}),")
        else:
            assert item.selector is not None and item.selector.offset is not None
            out.append(f"ais.Choice({json.dumps(item.by)}, {item.selector.offset}, {item.selector.bits}, (")
            for case in item.cases:
                values = "frozenset({" + ", ".join(map(str, case.values)) + "})" if case.values else "frozenset()"
                bounds = f"({case.range[0]}, {case.range[1]})" if case.range else "None"
                inner = layout_lines(payload, case.items, following, indent + 8, field_lines, group_args)
                if not inner:
                    out.append(f"{pad}ais.Case({values}, {bounds}, ()),")
                    continue
                out.append(f"{pad}ais.Case({values}, {bounds}, (")
                out += [pad * 2 + line for line in inner]
                out.append(f"{pad})),")
            out.append(")),")
    return out


def member(f: PayloadField) -> dict:
    unit = f" [{f.unit}]" if f.unit else ""
    scale = f" (raw / {f.divisor}{f' + {f.base}' if f.base is not None else ''})" if f.divisor else \
        f" (raw + {f.base})" if f.base is not None else ""
    special = f" Special: {', '.join(f'{s.id} ({s.shown})' for s in f.special)}." \
        if f.special else ""
    return {"line": f"{f.id}: {member_type(f)} = None",
            "doc": docstring(f"{f.name}{unit}{scale}{'' if f.doc == f.name else ': ' + f.doc}.{special}"
                             .replace("..", "."), 4)}


def title(payload: Payload) -> str:
    """What a message is: its name and its type numbers, or (an application) its DAC and FI."""
    if payload.application is not None:
        by_carriers: dict[tuple[int, ...], list[str]] = {}   # routes of the same types named once
        for r in payload.routes:
            by_carriers.setdefault(tuple(r.carriers), []).append(r.text)
        routes = " or ".join(f"{' or '.join(texts)} (in type {', '.join(map(str, carriers))})"
                             for carriers, texts in by_carriers.items())
        return f"{payload.name}: AIS application {routes}."
    numbers = ", ".join(map(str, payload.types))
    return f"{payload.name}: AIS message type{'s' if len(payload.types) > 1 else ''} {numbers}."


def _doc_lines(payload: Payload) -> list[str]:
    """A message class's docstring, line by line (the template adds the quotes and the indent)."""
    lines = [*textwrap.wrap(title(payload), WIDTH - 7), "", *textwrap.wrap(" ".join(payload.doc.split()), WIDTH - 4)]
    if payload.examples:
        example = payload.examples[0]
        lines += ["", f"Example ({example.manual}), {example.fill_bits} fill bits:", example.payload]
    return [line.replace("\\", "\\\\").replace('"""', '\\"\\"\\"') for line in lines]


def message_view(payload: Payload) -> dict:
    members: list[dict] = []
    entries: list[dict] = []
    for item in payload.items:
        if isinstance(item, PayloadGroup):
            name = entry_class(payload, item)
            members.append({"line": f"{item.id}: list[{name}] = field(default_factory=list)",
                            "doc": docstring(f"{item.name}: {item.min} to {item.max} entries.", 4)})
            entries.append({"class": name, "doc": docstring(f"One entry of {item.name.lower()}.", 4),
                            "members": [member(f) for f in item.fields]})
        else:
            members += [member(f) for f in ([item] if isinstance(item, PayloadField) else item.fields)]
    types = ", ".join(map(str, payload.types))
    return {
        "payload": payload, "class": payload.camel, "members": members, "entries": entries,
        "doc": _doc_lines(payload),
        "types": f"({types},)" if len(payload.types) == 1 else f"({types})",
        "title": "\n".join(textwrap.wrap(title(payload), WIDTH - 6)),
        "carriers": ", ".join(f"{key}: ({', '.join(map(str, payload.carriers_of(key)))}{',' if len(payload.carriers_of(key)) == 1 else ''})"
                              for key in payload.keys),
        "layout": layout_lines(payload, payload.items, [], 8),
        "raws": [{"name": f.id, "doc": docstring(f"The raw integer of {f.id}.", 8)}
                 for f in payload.fields if f.scaled],
        "enums": sorted({f.enum.camel for f in payload.fields if f.enum}),
        "uses_field": any(isinstance(i, PayloadGroup) for i in payload.items),
    }


def emit(spec: Spec, env: jinja2.Environment) -> dict[str, str]:
    base = f"python/{PACKAGE}/ais_messages"
    files: dict[str, str] = {}
    for payload in [*spec.payloads, *spec.applications]:
        sources = [payload.origin.file, *sorted({f.enum.origin.file for f in payload.fields if f.enum})]
        files[f"{base}/{payload.id}.py"] = env.get_template("python/ais_message.py.j2").render(
            header=header(spec, "#", sources), **message_view(payload))
    by_type = sorted((number, p) for p in spec.payloads for number in p.types)
    files[f"{base}/__init__.py"] = env.get_template("python/ais_init.py.j2").render(
        header=header(spec, "#", [p.origin.file for p in [*spec.payloads, *spec.applications]]),
        payloads=spec.payloads, applications=spec.applications, by_type=by_type)
    return files
