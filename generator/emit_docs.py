"""Markdown reference docs: an index, a page per sentence and per enum, the manuals' errata, the
tools' JSON form."""

from __future__ import annotations

import json
from collections import Counter
from typing import Any

import jinja2

from . import emit_vectors
from .emit import RUNTIME, markdown_banner
from .emit_framing import kept_fields
from .model import Field, Group, Layout, Manual, Ones, Payload, PayloadCase, PayloadField, PayloadGroup, ReplyRule, Sentence, Spec


def cell(text: str | None) -> str:
    """Text safe inside a Markdown table cell."""
    if not text:
        return ""
    return " ".join(text.split()).replace("|", "\\|")


def type_cell(f: Field) -> str:
    name = f.field_type.doc_name
    if f.enum is not None:
        return f"{name} [{f.enum.id}](../enums/{f.enum.id}.md)"
    if f.bitfield is not None:
        return f"{name} [{f.bitfield.id}](../bitfields/{f.bitfield.id}.md)"
    if "word" in f.field_type.args:
        return f"{name} `{f.value}`"
    if f.min is not None or f.max is not None:
        low = "" if f.min is None else _num(f.min)
        high = "" if f.max is None else _num(f.max)
        return f"{name} {low}..{high}"
    if f.max_length:
        return f"{name} (≤ {f.max_length})"
    return name


def _num(value: float) -> str:
    return str(int(value)) if float(value).is_integer() else str(value)


def position(f: Field, layout: Layout) -> str:
    """Where the field is on the wire, 1-based after the address."""
    group = layout.group
    if f.group is not None:
        g = f.group
        first = g.wire_index + f.wire_index - 1
        return f"{first} + {g.width}·k" if not g.single else f"{first}…"
    if group is not None and layout.items.index(f) > layout.items.index(group):
        after = [i for i in layout.items[layout.items.index(group) + 1:] if isinstance(i, Field)]
        offset = sum(x.wire_width for x in after[:after.index(f)])
        return f"after {group.id}" + (f" + {offset}" if offset else "")
    width = f.wire_width
    return f"{f.wire_index}" if width == 1 else f"{f.wire_index}–{f.wire_index + width - 1}"


def rows(layout: Layout) -> list[dict]:
    out = []
    for item in layout.items:
        fields = item.fields if isinstance(item, Group) else [item]
        for f in fields:
            out.append({
                "pos": position(f, layout),
                "id": f"{item.id}[k].{f.id}" if isinstance(item, Group) else f.id,
                "name": cell(f.name), "type": type_cell(f), "unit": cell(f.unit), "format": cell(f.format),
                "doc": cell(f.doc) + (f" Fix: [`{f.fact.id}`](../fix.md#{f.fact.id})." if f.fact else ""),
                "manuals": ", ".join(f.manuals),
                "since": ("v" + f.since) if f.since else ("optional" if f.optional else ""),
            })
    return out


def layout_summary(layout: Layout) -> str:
    g = layout.group
    if g is None:
        if layout.min_fields == layout.max_fields:
            return f"{layout.min_fields} fields"
        return f"{layout.min_fields} to {layout.max_fields} fields"
    return (f"{layout.fixed_count} fields, plus {g.min} to {g.max} × {g.width} fields of {g.id}"
            + (f", plus up to {layout.optional_count} optional trailing" if layout.optional_count else ""))


def example_view(vector: dict) -> dict:
    status = "intact" if vector["checksum_ok"] and vector["line"] == vector["raw"] else (
        "unrecoverable" if vector["line"] is None else "corrected")
    values = json.loads(vector["decode_values"])["fields"] if vector.get("decode_values") else None
    return {**vector, "status": status,
            "decoded": [(k, json.dumps(v, ensure_ascii=False)) for k, v in values.items()] if values else []}


# The domains of the standard sentences (the spec's `domain` key), in the order the index shows them.
DOMAINS = {
    "gnss": "GNSS: position, satellites, integrity, time",
    "navigation": "Navigation: waypoints, routes, bearings, cross-track, autopilot",
    "heading": "Heading, attitude, rate of turn, steering and propulsion",
    "environment": "Wind, water, depth, speed through water, transducers",
    "ais_safety": "AIS, radar targets, DSC, man overboard, safety messages",
    "alarms": "Alarms, alerts and detection systems",
    "system": "Text, equipment, configuration and communication",
}


def _bits_cell(f: PayloadField, after: str) -> str:
    """Where a payload field is: its bits (0 is the first bit sent), or what it follows."""
    if f.offset is None:
        return f"after `{after}`"
    if f.bits == 1:
        return str(f.offset)
    return f"{f.offset}–{f.offset + f.bits - 1}" if f.bits else f"{f.offset}–"


def binary_rows(layout: Payload) -> list[dict]:
    """The docs table of a binary layout: a row per field (a group's: where its k-th entry's is),
    a bitfield's parts below it."""
    out: list[dict] = []

    def row(f: PayloadField, offset: str, prefix: str = "") -> None:
        kind = f"{f.bit_type.doc_name}" + (f" [{f.enum.id}](../enums/{f.enum.id}.md)" if f.enum else "")
        size = " (the bytes left)" if not f.bits else f" ({f.bits // 8} bytes)" if not f.bit_type.size else ""
        out.append({"offset": offset, "type": kind + size + (" (optional)" if f.optional else ""),
                    "id": prefix + f.id, "name": cell(f.name), "scale": f"÷ {f.divisor}" if f.divisor else "",
                    "unit": cell(f.unit), "doc": cell(f.doc if f.doc != f.name else "")})
        for part in f.parts:
            bits = str(part.low) if part.bits == 1 else f"{part.low}–{part.low + (part.bits or 1) - 1}"
            out.append({"offset": f"bit {bits}", "type": part.bit_type.doc_name, "id": prefix + part.id,
                        "name": cell(part.name), "scale": f"÷ {part.divisor}" if part.divisor else "",
                        "unit": cell(part.unit), "doc": cell(part.doc if part.doc != part.name else "")})

    for item in layout.items:
        if isinstance(item, PayloadField):
            row(item, str(item.offset // 8) if item.offset is not None else "after the group")
        elif isinstance(item, PayloadGroup):
            at = 0
            for f in item.fields:
                start = f"{item.offset // 8} + " if item.offset is not None else ""
                # a stride's entries: as many bytes as its field says (the fields' and the entry's trailing bytes)
                step = f"`{item.stride}`" if item.stride is not None else str(item.entry_width // 8)
                row(f, f"{start}{at // 8} + {step}·k", f"{item.id}[k].")
                at += f.bits or 0
            if item.nested is not None:   # after each entry's stride bytes, its own entries (rule B010)
                inner, at = item.nested, 0
                for f in inner.fields:
                    row(f, f"after {item.id}[k]'s `{item.stride}`: {at // 8} + `{inner.stride}`·j",
                        f"{item.id}[k].{inner.id}[j].")
                    at += f.bits or 0
    return out


def _case_text(by: str, case: PayloadCase) -> str:
    """When a case of a choice by the field `by` holds, as the docs' tables say it."""
    values = ", ".join(map(str, case.values))
    return (f"{by} = {values}" if len(case.values) == 1 else f"{by} in {values}" if case.values else
            f"{by} in {case.range[0]}..{case.range[1]}" if case.range else f"{by}: otherwise")


def payload_rows(payload: Payload) -> list[dict]:
    """The docs table of a payload: a row per field, in order, with the case of a choice it
    belongs to and, for a group's fields, where the k-th entry's is."""
    out: list[dict] = []

    def row(f: PayloadField, where: str, when: str, prefix: str = "") -> dict:
        t = f.bit_type
        kind = f"{t.doc_name} [{f.enum.id}](../enums/{f.enum.id}.md)" if f.enum else t.doc_name
        special = "; ".join(f"{s.shown} `{s.id}`: {s.doc}" for s in f.special)
        return {"bits": where, "width": str(f.bits) if f.bits else "rest", "id": prefix + f.id, "name": cell(f.name),
                "type": kind + (" (optional)" if f.optional else ""), "when": when,
                "scale": " ".join([f"÷ {f.divisor}"] * bool(f.divisor) + [f"+ {f.base}"] * (f.base is not None)),
                "unit": cell(f.unit),
                "special": cell(special), "doc": cell(f.doc if f.doc != f.name else "")}

    def walk(items: list, when: str, previous: str) -> str:
        for item in items:
            if isinstance(item, PayloadField):
                out.append(row(item, _bits_cell(item, previous), when))
                previous = item.id
            elif isinstance(item, PayloadGroup):
                at = 0
                entries = f"{item.min} to {item.max} entries"
                for part in item.items:   # an entry's fields; a choice's, case by case from one bit
                    cases = [(entries, [part])] if isinstance(part, PayloadField) else \
                        [(f"{entries}; {_case_text(part.by, case)}", case.items) for case in part.cases]
                    for when_, fields in cases:
                        here = at
                        for f in fields:
                            where = (f"{item.offset + here} + {item.entry_width}·k" if item.offset is not None
                                     else f"after `{previous}`")
                            out.append(row(f, where, when_, f"{item.id}[k]."))
                            here += f.bits or 0
                    at += (part.bits or 0) if isinstance(part, PayloadField) else (part.width or 0)
                previous = item.id
            else:
                for case in item.cases:
                    cond = _case_text(item.by, case)
                    walk(case.items, f"{when}; {cond}" if when else cond, previous)
                previous = item.id
        return previous

    walk(payload.items, "", "")
    return out


def bit_message_rows(payload: Payload) -> list[dict]:
    """payload_rows of a bit message told by a number (RTCM 3), with each field's `ref`, a counted
    field's width and a counted group's entries."""
    def count(c: Any) -> str:
        return " × ".join(f"bits set in `{n}`" for n in c.fields) if isinstance(c, Ones) else f"`{c}`"

    fields = {f.id: f for f in payload.fields}
    groups = {g.id: g for g in payload.items if isinstance(g, PayloadGroup)}
    out = payload_rows(payload)
    for r in out:
        group = groups.get(r["id"].split("[k].")[0]) if "[k]." in r["id"] else None
        f = next((x for x in group.fields if f"{group.id}[k].{x.id}" == r["id"]), None) if group else fields[r["id"]]
        assert f is not None
        r["ref"] = f.ref or ""
        if f.count is not None:
            r["width"] = f"{count(f.count)}{' × 8' if f.bit_type.char_bits == 8 else ''}"
        if group is not None and group.count is not None:
            r["when"] = f"{count(group.count)} entries" + (", field by field" if group.field_major else "")
            if group.field_major:
                r["bits"] = f"after `{group.id}`'s earlier fields"
    return out


def emit(spec: Spec, env: jinja2.Environment) -> dict[str, str]:
    env.filters["cell"] = cell
    env.globals["replied_by"] = lambda s: replied_by(spec, s)
    env.globals["reply_link"] = reply_link
    env.globals["outcome_text"] = outcome_text
    vectors = [example_view(v) for v in emit_vectors.example_vectors(spec)]
    by_sentence: dict[str, list[dict]] = {}
    for v in vectors:
        by_sentence.setdefault(v["sentence"], []).append(v)
    counts: dict[str, Counter] = {m.id: Counter() for m in spec.manuals}
    for v in vectors:
        counts[v["manual_id"]][v["status"]] += 1
    enum_users: dict[str, list[str]] = {e.id: [] for e in spec.enums}
    for s in spec.sentences:
        for lay in s.layouts:
            for item in lay.items:
                for f in (item.fields if isinstance(item, Group) else [item]):
                    link = f"[{s.id}](../sentences/{s.id.lower()}.md)"
                    if f.enum and link not in enum_users[f.enum.id]:
                        enum_users[f.enum.id].append(link)
    # The support matrix: the receiver manuals (and the standard) against what they document.
    matrix_manuals = [spec.manual("nmea0183"), *receiver_manuals(spec)]
    matrix = [(s, [m.id in s.manuals or m.id == s.vendor for m in matrix_manuals])
              for s in [*spec.standard, *spec.proprietary]
              if any(m.id != "nmea0183" and (m.id in s.manuals or m.id == s.vendor) for m in matrix_manuals)]
    domains = [{"title": title, "sentences": [s for s in spec.standard if s.domain == domain]}
               for domain, title in DOMAINS.items()]
    env.globals["domain_titles"] = DOMAINS
    files: dict[str, str] = {}
    # A page about one item names the files it is made from in its banner, so that editing one
    # YAML file does not rewrite every page's banner.
    def banner_of(sources: list[str] | None) -> str:
        return markdown_banner(spec, sources)

    banner = banner_of(None)
    files["docs/README.md"] = env.get_template("docs/index.md.j2").render(
        banner=banner, spec=spec, matrix=matrix, matrix_manuals=matrix_manuals, counts=counts, vectors=vectors,
        domains=[d for d in domains if d["sentences"]])
    for s in spec.sentences:
        files[f"docs/sentences/{s.id.lower()}.md"] = env.get_template("docs/sentence.md.j2").render(
            banner=banner_of([*s.files, *sorted({e.origin.file for e in _enums_of(s)}), "spec/manuals.yaml"]),
            s=s, spec=spec, layouts=[(lay, rows(lay), layout_summary(lay)) for lay in s.layouts],
            examples=by_sentence.get(s.id, []), enums=_enums_of(s))
    for payload in [*spec.payloads, *spec.applications]:
        for f in payload.fields:
            link = f"[{payload.id}](../ais/{payload.id}.md)"
            if f.enum and link not in enum_users[f.enum.id]:
                enum_users[f.enum.id].append(link)
        files[f"docs/ais/{payload.id}.md"] = env.get_template("docs/ais_message.md.j2").render(
            banner=banner_of([payload.origin.file, "spec/manuals.yaml"]), p=payload, spec=spec,
            rows=payload_rows(payload),
            examples=[{**v, "json": json.dumps(v["decode"], separators=(",", ":"))}
                      for v in emit_vectors.ais_vectors(spec) if v["message"] == payload.id])
    documents = {d: title for p in spec.protocols for d, title in p.documents.items()}
    ubx_vectors = emit_vectors.ubx_vectors(spec) + emit_vectors.binary_vectors(spec)
    for m in spec.binary:
        link = f"[{m.address}](../{m.protocol}/{m.id}.md)"
        for f in (part for lay in m.layouts for f in lay.fields for part in (f, *f.parts)):
            if f.enum and link not in enum_users[f.enum.id]:
                enum_users[f.enum.id].append(link)
        identity = (f"Class 0x{m.class_number:02X}, id 0x{m.msg_id:02X}" if m.msg_class
                    else f"Block number {m.msg_id}, revision {m.revision}" if m.revision is not None
                    else f"{'MID' if m.protocol == 'sirf' else 'Id'} 0x{m.msg_id:02X} ({m.msg_id})"
                    + (f", {'SID' if m.protocol == 'sirf' else 'sub-id'} 0x{m.sub_id:02X} ({m.sub_id})"
                       if m.sub_id is not None else ""))
        prefix = "" if not m.prefix else " after the id" if m.sub_id is None else " after the id and sub-id"
        kept = ", ".join(f"`{k.id}` (u{k.size} at byte {k.at})" for p in spec.protocols if p.id == m.protocol
                         for k in kept_fields(p))
        files[f"docs/{m.protocol}/{m.id}.md"] = env.get_template("docs/ubx_message.md.j2").render(
            banner=banner_of([m.origin.file]), m=m, documents=documents, identity=identity, prefix=prefix, kept=kept,
            layouts=[{"layout": lay, "rows": binary_rows(lay),
                      "length": lay.fixed_width // 8 if lay.fixed_width is not None else None} for lay in m.layouts],
            examples=[{**v, "json": json.dumps(v["decode"], separators=(",", ":"))}
                      for v in ubx_vectors if v["message"] == m.id and v.get("protocol", "ubx") == m.protocol])
    rtcm3_vectors = emit_vectors.rtcm3_vectors(spec) if spec.bit_messages else []
    for p in spec.bit_messages:
        files[f"docs/{p.protocol}/{p.id}.md"] = env.get_template("docs/rtcm3_message.md.j2").render(
            banner=banner_of([p.origin.file]), p=p, documents=documents, rows=bit_message_rows(p),
            examples=[{**v, "json": json.dumps(v["decode"], separators=(",", ":"))}
                      for v in rtcm3_vectors if v["message"] == p.id])
    for e in spec.enums:
        files[f"docs/enums/{e.id}.md"] = env.get_template("docs/enum.md.j2").render(
            banner=banner_of([e.origin.file]), e=e, users=enum_users[e.id])
    for b in spec.bitfields:
        files[f"docs/bitfields/{b.id}.md"] = env.get_template("docs/bitfield.md.j2").render(
            banner=banner_of([b.origin.file]), b=b, users=_bitfield_users(spec, b.id))
    for t in spec.tables:
        files[f"docs/tables/{t.id}.md"] = env.get_template("docs/table.md.j2").render(banner=banner_of([t.origin.file]), t=t)
    for m in receiver_manuals(spec):
        files[f"docs/vendors/{m.id}.md"] = env.get_template("docs/vendor.md.j2").render(
            banner=banner, m=m, spec=spec, counts=counts[m.id],
            standard=[(s, [n for n in s.notes if m.id in n.manuals]) for s in spec.standard if m.id in s.manuals],
            proprietary=[s for s in spec.proprietary if s.vendor == m.id],
            tables=[t for t in spec.tables if m.id in t.manuals],
            bitfields=[b for b in spec.bitfields if m.id in b.manuals],
            errata=[v for v in vectors if v["manual_id"] == m.id and v["status"] != "intact"])
    files.update(_indexes(spec, env, banner))
    files["docs/errata.md"] = env.get_template("docs/errata.md.j2").render(
        banner=banner, spec=spec, vectors=[v for v in vectors if v["status"] != "intact"], counts=counts)
    files["docs/fix.md"] = env.get_template("docs/fix.md.j2").render(
        banner=banner_of([*spec.fix_sources, "templates/docs/fix.md.j2"]), spec=spec)
    files["docs/tag_block.md"] = env.get_template("docs/tag_block.md.j2").render(
        banner=banner_of([*spec.tag_sources, "templates/docs/tag_block.md.j2"]), spec=spec,
        examples=[{**v, "outcome": _tag_outcome(json.loads(v["decode"]))} for v in emit_vectors.tag_block_vectors(spec)])
    files["docs/json.md"] = banner_of(["runtime/json.md"]) + (RUNTIME / "json.md").read_text(encoding="utf-8")
    return files


def _tag_outcome(decoded: dict) -> str:
    """What decode made of a TAG block example: its sentence and blocks, or its error."""
    if not decoded["ok"]:
        return f"{decoded['error']['kind']}: {decoded['error']['message']}"
    blocks = "; ".join(", ".join(f"{p['code']}={p['value']}" for p in b["params"]) for b in decoded["tag_blocks"])
    sentence = decoded.get("sentence") or decoded.get("address")
    return f"{sentence} behind {blocks}" if sentence else f"TAG blocks only: {blocks}"


def receiver_manuals(spec: Spec) -> list[Manual]:
    """The manuals that get a receiver page: the receiver manuals of ../shared/seeds (`file`) and
    the protocol document of each family with sentences of its own (a `vendor` id)."""
    vendors = {s.vendor for s in spec.proprietary}
    return [m for m in spec.manuals if m.file is not None or m.id in vendors]


def _indexes(spec: Spec, env: jinja2.Environment, banner: str) -> dict[str, str]:
    """The index pages: sentences A to Z, receivers, commands."""
    from .emit_python_apps import command_views, usage

    commands, shortcuts = command_views(spec)
    sentences = [{"id": s.id, "name": s.name, "kind": s.kind, "vendor": s.vendor,
                  "wire": (s.address if s.framing == "text" else f"${s.address}") if s.address
                  else f"$--{s.id}"} for s in sorted(spec.sentences, key=lambda s: s.id)]
    manuals = receiver_manuals(spec)
    vendors = [{"manual": m,
                "standard": sum(1 for s in spec.standard if m.id in s.manuals),
                "own": sum(1 for s in spec.proprietary if s.vendor == m.id and s.kind != "command"),
                "commands": sum(1 for s in spec.proprietary if s.vendor == m.id and s.kind == "command")}
               for m in manuals]
    by_vendor = []
    for m in manuals:
        mine = [{**c, "usage": usage(c)} for c in commands if c["vendor"] == m.id]
        if mine:
            by_vendor.append({"manual": m, "commands": mine, "shortcuts": [
                (" ".join(x["words"]), x["command"], ", ".join(f"{k} `{v}`" for k, v in x["settings"]))
                for x in shortcuts if x["vendor"] == m.id]})
    return {
        "docs/sentences.md": env.get_template("docs/sentences.md.j2").render(banner=banner, sentences=sentences),
        "docs/vendors.md": env.get_template("docs/vendors.md.j2").render(banner=banner, vendors=vendors,
                                                                            generic=spec.generic),
        "docs/commands.md": env.get_template("docs/commands.md.j2").render(banner=banner, vendors=by_vendor),
    }


def _bitfield_users(spec: Spec, bitfield_id: str) -> list[str]:
    users = []
    for s in spec.sentences:
        for lay in s.layouts:
            for item in lay.items:
                for f in (item.fields if isinstance(item, Group) else [item]):
                    if f.bitfield and f.bitfield.id == bitfield_id and s.id not in users:
                        users.append(s.id)
    for t in spec.tables:
        for p in t.parameters:
            if p.bitfield and p.bitfield.id == bitfield_id and t.id not in users:
                users.append(t.id)
    return users


def _value_text(value: object) -> str:
    return f"`{value}`"


def reply_link(rule: ReplyRule, prefix: str = "") -> str:
    """A reply of a command, linked, with the field values that pair it with the command."""
    link = f"[{rule.sentence_id}]({prefix}{rule.sentence_id.lower()}.md)"
    if not rule.when:
        return link
    return link + " with " + " and ".join(f"`{k}` = {_value_text(v)}" for k, v in rule.when.items())


def outcome_text(sentence: Sentence) -> str:
    """What a reply reports, per layout: success, an error, or success when a field says so."""
    parts = []
    for layout in sentence.layouts:
        o = layout.outcome
        text = ("success (it carries what the command asked for)" if o is None else
                "success" if o.fixed == "ok" else "an error" if o.fixed == "error" else
                f"success when `{o.field_id}` is " + " or ".join(_value_text(v) for v in o.ok) + ", else an error")
        parts.append((f"variant `{layout.id}`: " if layout.id else "", text))
    if len({text for _, text in parts}) == 1:
        return parts[0][1]
    return "; ".join(label + text for label, text in parts)


def replied_by(spec: Spec, sentence: Sentence) -> list[Sentence]:
    """The commands a reply answers."""
    return [s for s in spec.sentences if sentence in s.replies]


def _enums_of(s: Sentence) -> list:
    seen = []
    for lay in s.layouts:
        for item in lay.items:
            for f in (item.fields if isinstance(item, Group) else [item]):
                if f.enum and f.enum not in seen:
                    seen.append(f.enum)
    return seen
