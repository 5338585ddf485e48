"""Python emitter of the binary messages (spec/binary/<protocol>/messages): the packages
`nmeaspec.ubx_messages` (and skytraq_messages, sirf_messages, casic_messages), a module per
message with a dataclass per layout and its LAYOUT, the descriptor that the AIS payloads' one
reader and one writer (runtime/python/ais.py) interpret over bytes in the protocol's byte order
(runtime/python/ubx.py; the other protocols' framing: runtime/python/binary.py). The descriptors
are those of emit_python_ais: one model of payloads.
With a configuration database, also the runtime ubx_config.py and emit_ubx_config's files."""

from __future__ import annotations

import textwrap

import jinja2

from . import emit_ubx_config
from .emit import header, runtime_file
from .emit_framing import kept_fields
from .emit_python import WIDTH, docstring
from .emit_python_ais import entry_class, layout_lines, member
from .model import BinaryMessage, Payload, PayloadField, PayloadGroup, Spec

PACKAGE = "nmeaspec"


def _members(fields: list[PayloadField]) -> list[dict]:
    """A member per field, a bitfield's parts after its word."""
    return [member(m) for f in fields for m in (f, *f.parts)]


def identity(message: BinaryMessage) -> str:
    """What tells the message in a frame besides its address: class 0x01 id 0x07 (UBX, CASIC); the
    id (and sub-id) in the other base (SkyTraq: 168; SiRF: 0x5D 0x12)."""
    if message.msg_class:
        return f"class 0x{message.class_number:02X} id 0x{message.msg_id:02X}"
    if message.revision is not None:   # SBF: the header's id, revision and block number
        return f"id 0x{message.revision << 13 | message.msg_id:04X}"
    if message.protocol == "sirf":   # the address gives it in decimal, as SiRF does
        return f"0x{message.msg_id:02X}" + (f" 0x{message.sub_id:02X}" if message.sub_id is not None else "")
    return f"{message.msg_id}" + (f" {message.sub_id}" if message.sub_id is not None else "")


def title(message: BinaryMessage, layout: Payload) -> str:
    directions = ", ".join(layout.directions)
    return f"{message.name}: {message.protocol.upper()} {message.address} ({identity(message)}), {directions}."


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
            nested = item.nested
            inner = []
            if nested is not None:   # the group each entry ends with: a class of its own, a list of them
                inner_name = entry_class(layout, nested)
                entries.append({"class": inner_name, "doc": docstring(f"One entry of {nested.name.lower()}.", 4),
                                "members": _members(nested.fields)})
                inner = [{"line": f"{nested.id}: list[{inner_name}] = field(default_factory=list)",
                          "doc": docstring(f"{nested.name}: {nested.count} entries.", 4)}]
            entries.append({"class": name, "doc": docstring(f"One entry of {item.name.lower()}.", 4),
                            "members": _members(item.fields) + inner})
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
        "select": f'("{layout.select[0]}", {layout.select_at}, 0x{layout.select[1]:02X})' if layout.select else "None",
        "acknowledges": "({!r}, {!r})".format(*layout.acknowledges).replace("'", '"') if layout.acknowledges
        else "None",
        "descriptor": layout_lines(layout, layout.items, [], 8),
        # (a field of a group's entry and of its nested group's: one property, of the first)
        "raws": [{"name": name, "doc": docstring(f"The raw integer of {name}.", 8)}
                 for name in dict.fromkeys(f.id for f in layout.fields if f.scaled)],
    }


def _header_module(spec: Spec, protocol: str) -> str | None:
    """nmeaspec.<protocol>_messages.frame_header: the protocol's Header (binary.Header), a member
    per header field of `identity: false` (Unicore's time and status), None for a protocol with none."""
    p = next(p for p in spec.protocols if p.id == protocol)
    kept = kept_fields(p)
    if not kept:
        return None
    lines = [header(spec, "#", [p.origin.file]) + f'"""The header fields a {p.name} message keeps."""', "",
             "from __future__ import annotations", "", "from dataclasses import dataclass", "",
             "from typing import ClassVar", "", "from .. import binary", "", "", "@dataclass",
             "class Header(binary.Header):",
             *("    " + line for line in docstring(
                 f"The fields of a {p.name} frame's header besides its sync, message id and length, which a "
                 "decoded message keeps and its frame is written with (0 in a message built by hand, unless "
                 "set).", 4)), "",
             f'    PROTOCOL: ClassVar[str] = "{protocol}"', ""]
    for k in kept:
        lines += [f"    {k.id}: int = 0", *("    " + line for line in docstring(f"{k.doc}: u{k.size}.", 4))]
    return "\n".join(lines) + "\n"


def _modules(spec: Spec, env: jinja2.Environment, protocol: str, messages: list[BinaryMessage]) -> dict[str, str]:
    """A module per message of `protocol` in nmeaspec.<protocol>_messages."""
    files: dict[str, str] = {}
    base = "ubx.Message" if protocol == "ubx" else "binary.Message"
    kept = _header_module(spec, protocol)
    if kept:
        files[f"python/{PACKAGE}/{protocol}_messages/frame_header.py"] = kept
    for message in messages:
        fields = [m for layout in message.layouts for f in layout.fields for m in (f, *f.parts)]
        enums = sorted({f.enum.camel for f in fields if f.enum})
        sources = [message.origin.file, *sorted({f.enum.origin.file for f in fields if f.enum})]
        modules = sorted({f.bit_type.module for f in fields} | {"ais", "ubx"} | ({"binary"} if protocol != "ubx"
                                                                               else set()))
        heading = "\n".join(docstring(f"{message.name}: {protocol.upper()} {message.address}, {identity(message)}.", 0))
        key = "(" + ", ".join(f"0x{k:02X}" for k in message.key) + ("," if len(message.key) == 1 else "") + ")"
        files[f"python/{PACKAGE}/{protocol}_messages/{message.id}.py"] = env.get_template(
            "python/ubx_message.py.j2").render(
            header=header(spec, "#", sources), message=message, enums=enums, modules=", ".join(modules),
            uses_field=bool(kept) or any(isinstance(i, PayloadGroup) for layout in message.layouts
                                         for i in layout.items), kept=bool(kept),
            layouts=[layout_view(message, layout) for layout in message.layouts], heading=heading, base=base,
            protocol=protocol, key=key)
    return files


def emit(spec: Spec, env: jinja2.Environment) -> dict[str, str]:
    base = f"python/{PACKAGE}/ubx_messages"
    files: dict[str, str] = {}
    for protocol in sorted({m.protocol for m in spec.binary} - {"ubx"}):   # SkyTraq, SiRF, CASIC
        others = [m for m in spec.binary if m.protocol == protocol]
        files.update(_modules(spec, env, protocol, others))
        name = next((p.name for p in spec.protocols if p.id == protocol), protocol)
        rows = []
        for m in sorted(others, key=lambda m: m.key):
            key = ", ".join(f"0x{k:02X}" for k in m.key)
            rows.append({"key": key, "layouts": [layout.camel for layout in m.layouts], "indent": len(key) + 9})
        files[f"python/{PACKAGE}/{protocol}_messages/__init__.py"] = env.get_template("python/binary_init.py.j2").render(
            header=header(spec, "#", [m.origin.file for m in others]), messages=others, rows=rows, name=name,
            protocol=protocol, kept=any(kept_fields(p) for p in spec.protocols if p.id == protocol),
            told="class and id" if others[0].msg_class else "block number and revision"
            if others[0].revision is not None else "id, and sub-id where the message has one",
            told_short="class and id" if others[0].msg_class else "block number and revision"
            if others[0].revision is not None else "id (and sub-id)")
    messages = [m for m in spec.binary if m.protocol == "ubx"]
    if not messages:
        return files
    files.update(_modules(spec, env, "ubx", messages))
    files[f"{base}/__init__.py"] = env.get_template("python/ubx_init.py.j2").render(
        header=header(spec, "#", [m.origin.file for m in messages]), messages=messages)
    if spec.config_keys:   # the configuration database: its runtime, key table and docs page
        files[f"python/{PACKAGE}/ubx_config.py"] = runtime_file(spec, "#", "python/ubx_config.py")
        files[f"python/{PACKAGE}/apps/ubx_cli.py"] = runtime_file(spec, "#", "python/apps/ubx_cli.py")
        files.update(emit_ubx_config.emit(spec, env))
    return files
