"""Python emitter of the binary messages (spec/binary/ubx): the package `nmeaspec.ubx_messages`,
a module per message with a dataclass per layout and its LAYOUT, the descriptor that the AIS
payloads' one reader and one writer (runtime/python/ais.py) interpret over little-endian bytes
(runtime/python/ubx.py). The descriptors are those of emit_python_ais: one model of payloads.
With a configuration database, also the runtime ubx_config.py and emit_ubx_config's files."""

from __future__ import annotations

import textwrap

import jinja2

from . import emit_ubx_config
from .emit import header, runtime_file
from .emit_python import WIDTH, docstring
from .emit_python_ais import entry_class, layout_lines, member
from .model import BinaryMessage, Payload, PayloadField, PayloadGroup, Spec

PACKAGE = "nmeaspec"


def _members(fields: list[PayloadField]) -> list[dict]:
    """A member per field, a bitfield's parts after its word."""
    return [member(m) for f in fields for m in (f, *f.parts)]


def title(message: BinaryMessage, layout: Payload) -> str:
    directions = ", ".join(layout.directions)
    return f"{message.name}: UBX {message.address} (class 0x{message.class_number:02X} id 0x{message.msg_id:02X}), " \
        f"{directions}."


def _tuple(words: list[str]) -> str:
    """A tuple of strings as Python source."""
    return "(" + ", ".join(f'"{w}"' for w in words) + ("," if len(words) == 1 else "") + ")"


def layout_view(message: BinaryMessage, layout: Payload) -> dict:
    members: list[dict] = []
    entries: list[dict] = []
    for item in layout.items:
        if isinstance(item, PayloadGroup):
            name = entry_class(layout, item)
            count = str(item.count) if item.count is not None else f"{item.min} to {item.max}"   # 6, num_svs
            members.append({"line": f"{item.id}: list[{name}] = field(default_factory=list)",
                            "doc": docstring(f"{item.name}: {count} entries.", 4)})
            entries.append({"class": name, "doc": docstring(f"One entry of {item.name.lower()}.", 4),
                            "members": _members(item.fields)})
        else:
            members += _members([item])
    doc = [*textwrap.wrap(title(message, layout), WIDTH - 7), "",
           *textwrap.wrap(" ".join(layout.doc.split()), WIDTH - 4)]
    return {
        "layout": layout, "class": layout.camel, "members": members, "entries": entries,
        "doc": [line.replace("\\", "\\\\").replace('"""', '\\"\\"\\"') for line in doc],
        "directions": _tuple(layout.directions),
        "replies": _tuple(layout.replies),
        "length": str(layout.fixed_width // 8) if layout.fixed_width is not None else "None",
        "acknowledges": "({!r}, {!r})".format(*layout.acknowledges).replace("'", '"') if layout.acknowledges
        else "None",
        "descriptor": layout_lines(layout, layout.items, [], 8),
        "raws": [{"name": f.id, "doc": docstring(f"The raw integer of {f.id}.", 8)}
                 for f in layout.fields if f.scaled],
    }


def emit(spec: Spec, env: jinja2.Environment) -> dict[str, str]:
    base = f"python/{PACKAGE}/ubx_messages"
    files: dict[str, str] = {}
    messages = [m for m in spec.binary if m.protocol == "ubx"]
    if not messages:
        return {}
    for message in messages:
        fields = [m for layout in message.layouts for f in layout.fields for m in (f, *f.parts)]
        enums = sorted({f.enum.camel for f in fields if f.enum})
        sources = [message.origin.file, *sorted({f.enum.origin.file for f in fields if f.enum})]
        modules = sorted({f.bit_type.module for f in fields} | {"ais", "ubx"})
        files[f"{base}/{message.id}.py"] = env.get_template("python/ubx_message.py.j2").render(
            header=header(spec, "#", sources), message=message, enums=enums, modules=", ".join(modules),
            uses_field=any(isinstance(i, PayloadGroup) for layout in message.layouts for i in layout.items),
            layouts=[layout_view(message, layout) for layout in message.layouts])
    files[f"{base}/__init__.py"] = env.get_template("python/ubx_init.py.j2").render(
        header=header(spec, "#", [m.origin.file for m in messages]), messages=messages)
    if spec.config_keys:   # the configuration database: its runtime, key table and docs page
        files[f"python/{PACKAGE}/ubx_config.py"] = runtime_file(spec, "#", "python/ubx_config.py")
        files[f"python/{PACKAGE}/apps/ubx_cli.py"] = runtime_file(spec, "#", "python/apps/ubx_cli.py")
        files.update(emit_ubx_config.emit(spec, env))
    return files
