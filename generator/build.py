"""Turns the validated YAML documents into the intermediate model, resolves it (resolve.py) and
runs the semantic checks (checks.py)."""

from __future__ import annotations

import copy
import hashlib
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import yaml

from . import checks
from .errors import SpecError, SpecErrors
from .loader import Document, load_document, schema_errors
from .field_types import BIT_TYPES, float_bits
from .model import (BinaryExample, BinaryMessage, BinaryProtocol, BitfieldDef, Bits, BitValue, ConfigDatabase,
                    ConfigEnum, ConfigGroup, ConfigKey, EnumDef, EnumValue,
                    Example, Fact, Ones, Field, FixExample, GenericMessage, Group, Item, Layout, Manual, Note, Origin, Outcome, Parameter, Payload, PayloadCase,
                    PayloadChoice, PayloadExample, PayloadField, PayloadGroup, PayloadItem, ReplyRule, Route, Sentence, Spec,
                    Special, TableDef, TagCode)
from .resolve import resolve

MAX_ENTRIES = 65535   # a group with no `max`: as many entries as a frame's length allows
STRIDE_TRAILING = "trailing"   # the last field of a stride's entry: its bytes after the fields


# The folders of a spec tree, each with the kind of its files and their schema. An overlay
# (--spec-extra) has the same layout, its manuals.yaml optional, and may extend the sentences of
# the trees before it (extensions/: variants, notes and examples of a sentence defined elsewhere).
LAYOUT = (("enums", "enums", "enum.schema.json"),
          ("bitfields", "bitfields", "bitfield.schema.json"),
          ("tables", "tables", "table.schema.json"),
          ("standard", "sentences", "sentence.schema.json"),
          ("proprietary", "sentences", "sentence.schema.json"),
          ("extensions", "extensions", "extension.schema.json"),
          ("ais/messages", "payloads", "payload.schema.json"),
          ("ais/applications", "applications", "payload.schema.json"))


def load_spec(spec_dir: Path, extras: Sequence[Path] = ()) -> Spec:
    """Load, schema-check, build and semantically check the spec, with the overlays `extras` laid
    over it in order; raise SpecErrors listing every problem found.

    A file is named in errors and in the generated files' headers by its path from the spec
    directory's parent (spec/standard/gga.yaml) or, for an overlay, as the overlay was given
    (my-nmea/proprietary/acme_pos.yaml)."""
    errors: list[SpecError] = []
    docs: dict[str, list[Document]] = {kind: [] for kind in ("manuals", "facts", "tag_block", "enums", "bitfields", "tables",
                                                             "sentences", "extensions", "payloads", "applications",
                                                             "protocols", "binary", "config_keys",
                                                             "bit_messages")}
    digest = hashlib.sha256()
    file_digests: dict[str, str] = {}
    for tree, names in [(spec_dir, spec_dir.parent), *((extra, None) for extra in extras)]:
        for path, kind, schema in _tree_files(tree, required_manuals=names is not None):
            name = path.relative_to(names) if names is not None else path
            if str(name) in file_digests:  # an overlay given under the name of the tree before it
                name = path.resolve()
            try:
                doc = load_document(path)
            except SpecError as err:
                errors.append(err)
                continue
            doc.path = name
            data = path.read_bytes()
            digest.update(str(name).encode() + b"\0" + data)
            file_digests[str(name)] = hashlib.sha256(data).hexdigest()
            found = schema_errors(doc, schema)
            errors += found
            if not found:
                docs[kind].append(doc)
    if errors:
        raise SpecErrors(errors)

    manuals = [Manual(**m) for d in docs["manuals"] for m in d.data["manuals"]]
    generic = [GenericMessage(**g, origin=Origin(str(d.path), ("generic", i)))
               for d in docs["manuals"] for i, g in enumerate(d.data.get("generic", []))]
    facts = [_fact(f, Origin(str(d.path), ("facts", i))) for d in docs["facts"] for i, f in enumerate(d.data["facts"])]
    enums = [_enum(d) for d in docs["enums"]]
    sentences = [_sentence(d) for d in docs["sentences"]]
    bitfields = [_bitfield(d) for d in docs["bitfields"]]
    tables = [_table(d) for d in docs["tables"]]
    payloads = [_payload(d) for d in docs["payloads"]]
    applications = [_payload(d) for d in docs["applications"]]
    protocols = [_protocol(d) for d in docs["protocols"]]
    binary = [_binary_message(d) for d in docs["binary"]]
    config_keys = [_config_database(d) for d in docs["config_keys"]]
    bit_messages = [_bit_message(d) for d in docs["bit_messages"]]
    errors = _clashes(docs, bitfields, tables) + _extend(sentences, docs["extensions"]) + _alike(sentences, docs["sentences"])
    if errors:
        raise SpecErrors(errors)
    spec = Spec(manuals, enums, sentences,
                sources=[str(d.path) for kind in ("enums", "bitfields", "tables", "sentences", "extensions", "payloads",
                                                  "applications", "protocols", "binary", "config_keys",
                                                  "bit_messages")
                         for d in docs[kind]],
                digest=digest.hexdigest()[:16], file_digests=file_digests,
                bitfields=bitfields, tables=tables, generic=generic, facts=facts,
                fix_sources=[str(d.path) for d in docs["facts"]],
                fix_examples=[FixExample(e["where"], e["lines"], e["expect"], Origin(str(d.path), ("examples", i)))
                              for d in docs["facts"] for i, e in enumerate(d.data.get("examples", []))],
                talker_systems={k: v for d in docs["facts"] for k, v in d.data.get("talkers", {}).items()},
                combined_talker=next((d.data["combined_talker"] for d in docs["facts"]
                                      if "combined_talker" in d.data), None),
                satellite_ids=[(r["system"], r["min"], r["max"]) for d in docs["facts"]
                               for r in d.data.get("satellite_ids", [])],
                tag_codes=[TagCode(c["code"], c["id"], c["name"], c["type"], c["doc"], Origin(str(d.path), ("codes", i)))
                           for d in docs["tag_block"] for i, c in enumerate(d.data["codes"])],
                tag_manuals=[m for d in docs["tag_block"] for m in d.data["manuals"]],
                tag_examples=[(e["where"], e["line"]) for d in docs["tag_block"] for e in d.data.get("examples", [])],
                tag_sources=[str(d.path) for d in docs["tag_block"]],
                payloads=payloads, applications=applications, protocols=protocols, binary=binary,
                config_keys=config_keys, bit_messages=bit_messages)
    by_file = {str(d.path): d for kind in docs.values() for d in kind}
    resolve(spec)
    errors = checks.run(spec, by_file)
    if errors:
        raise SpecErrors(errors)
    return spec


def _tree_files(tree: Path, required_manuals: bool) -> list[tuple[Path, str, str]]:
    """The YAML files of a spec tree, each with its kind and schema, in load order."""
    manuals = tree / "manuals.yaml"
    files = [(manuals, "manuals", "manuals.schema.json")] if required_manuals or manuals.exists() else []
    facts = tree / "fix.yaml"
    files += [(facts, "facts", "fix.schema.json")] if facts.exists() else []
    tag_block = tree / "tag_block.yaml"
    files += [(tag_block, "tag_block", "tag_block.schema.json")] if tag_block.exists() else []
    for folder, kind, schema in LAYOUT:
        files += [(p, kind, schema) for p in sorted((tree / folder).glob("*.yaml"))]
    for protocol in sorted((tree / "binary").glob("*/protocol.yaml")):   # a binary protocol, then its messages
        files.append((protocol, "protocols", "binary_protocol.schema.json"))
        messages = sorted((protocol.parent / "messages").glob("*.yaml"))
        # a protocol whose messages are told by a bit field (RTCM 3's 12-bit number) has bit layouts
        identity = (yaml.safe_load(protocol.read_text(encoding="utf-8")) or {}).get("identity") or []
        bits = bool(identity) and all(str(i.get("type", "")).startswith("b") for i in identity)
        files += [(p, "bit_messages", "bit_message.schema.json") if bits else (p, "binary", "binary_message.schema.json")
                  for p in messages]
        keys = protocol.parent / "config_keys.yaml"
        files += [(keys, "config_keys", "config_keys.schema.json")] if keys.exists() else []
    return files


def _clashes(docs: dict[str, list[Document]], bitfields: list[BitfieldDef], tables: list[TableDef]) -> list[SpecError]:
    """Manuals, bitfields and tables defined twice (checks.py finds the sentences and enums): with
    overlays, the second of two files that define one id, naming the first."""
    errors = []
    manuals: dict[str, str] = {}
    for d in docs["manuals"]:
        for i, m in enumerate(d.data["manuals"]):
            if m["id"] in manuals:
                errors.append(d.error(("manuals", i, "id"), f"manual {m['id']} is also defined in {manuals[m['id']]}",
                                      "S001"))
            manuals.setdefault(m["id"], str(d.path))
    for kind, items in (("bitfield", bitfields), ("table", tables)):
        seen: dict[str, str] = {}
        for item in items:
            if item.id in seen:
                doc = next(d for d in docs[f"{kind}s"] if str(d.path) == item.origin.file)
                errors.append(doc.error((kind,), f"{kind} {item.id} is also defined in {seen[item.id]}", "S001"))
            seen.setdefault(item.id, item.origin.file)
    return errors


def _extend(sentences: list[Sentence], extensions: list[Document]) -> list[SpecError]:
    """Add each extension's manuals, variants, notes and examples to the sentence it extends."""
    errors = []
    by_id = {s.id: s for s in sentences}
    for doc in extensions:
        d = doc.data
        sentence = by_id.get(d["extends"])
        if sentence is None:
            errors.append(doc.error(("extends",), f"no sentence {d['extends']} to extend", "S046"))
            continue
        file = str(doc.path)
        sentence.extensions.append(file)
        sentence.manuals += [m for m in d["manuals"] if m not in sentence.manuals]
        sentence.variants += _variants(d, file, sentence.layout.outcome)
        sentence.notes += _notes(d)
        sentence.examples += _examples(d, file)
    return errors


def _alike(sentences: list[Sentence], documents: list[Document]) -> list[SpecError]:
    """Give each sentence sent `like` another the other's main layout: its fields, without the
    facts of a fix (the other formatter says the values are not the receiver's fix: Unicore's
    GGAH is the second antenna's position)."""
    errors = []
    by_id = {s.id: s for s in sentences}
    by_file = {str(doc.path): doc for doc in documents}
    for sentence in sentences:
        if sentence.like is None:
            continue
        model = by_id.get(sentence.like)
        if model is None or model.is_proprietary or model.like is not None:
            errors.append(by_file[sentence.source].error(
                ("like",), f"`like: {sentence.like}` names no standard sentence with fields of its own", "S049"))
            continue
        sentence.like_source = model.source
        sentence.layout.items = [_unfixed(item) for item in copy.deepcopy(model.layout.items)]
    return errors


def _unfixed(item: Item) -> Item:
    """A copied item without the facts of a fix its fields carry."""
    for f in item.fields if isinstance(item, Group) else [item]:
        f.fix_id = None
    return item


def _enum(doc: Document) -> EnumDef:
    d = doc.data
    values = [EnumValue(v["code"], v["id"], v["doc"], v.get("manuals", []), v.get("since"),
                        Origin(str(doc.path), ("values", i)), v.get("cli"))
              for i, v in enumerate(d["values"])]
    return EnumDef(d["enum"], d["name"], d["doc"], values, Origin(str(doc.path), ()), d["codes"] == "closed")


def _field(data: dict[str, Any], origin: Origin) -> Field:
    return Field(id=data["id"], name=data["name"], type=data["type"], doc=data["doc"],
                 manuals=data.get("manuals", []), origin=origin, format=data.get("format"),
                 unit=data.get("unit"), min=data.get("min"), max=data.get("max"),
                 max_length=data.get("max_length"), enum_id=data.get("enum"), value=data.get("value"),
                 since=data.get("since"), optional=bool(data.get("optional", False)),
                 bitfield_id=data.get("bitfield"), fix_id=data.get("fix"))


def _fact(data: dict[str, Any], origin: Origin) -> Fact:
    return Fact(id=data["id"], name=data["name"], doc=data["doc"], types=data["types"], origin=origin,
                scope=data.get("scope", "epoch"), unit=data.get("unit"), units=data.get("units", {}),
                enums=data.get("enums", []), values=data.get("values", []), mapping=data.get("from", {}))


def _bitfield(doc: Document) -> BitfieldDef:
    d = doc.data
    bits = []
    for i, b in enumerate(d["bits"]):
        high, _, low = b["bits"].partition(":")
        bits.append(Bits(int(high), int(low or high), b["id"], b["doc"],
                         [BitValue(v["value"], v["id"], v["doc"]) for v in b.get("values", [])],
                         Origin(str(doc.path), ("bits", i))))
    return BitfieldDef(d["bitfield"], d["name"], d["doc"], d["width"], d.get("manuals", []), bits,
                       Origin(str(doc.path), ()))


def _table(doc: Document) -> TableDef:
    d = doc.data
    params = [Parameter(number=p["number"], id=p["id"], name=p["name"], doc=p["doc"], encoding=p["encoding"],
                        origin=Origin(str(doc.path), ("parameters", i)), size=p.get("size"), count=p.get("count"),
                        min=p.get("min"), max=p.get("max"), max_length=p.get("max_length"),
                        default=p.get("default"), unit=p.get("unit"), enum_id=p.get("enum"),
                        bitfield_id=p.get("bitfield"), takes_effect=p.get("takes_effect"))
              for i, p in enumerate(d["parameters"])]
    return TableDef(d["table"], d["name"], d["doc"], d["manuals"], params, Origin(str(doc.path), ()))


def _items(data: list[dict[str, Any]], file: str, where: tuple[str | int, ...]) -> list[Item]:
    items: list[Item] = []
    for i, item in enumerate(data):
        origin = Origin(file, where + (i,))
        if "group" in item:
            fields = [_field(f, Origin(file, where + (i, "fields", j))) for j, f in enumerate(item["fields"])]
            items.append(Group(item["group"], item["name"], item.get("doc", item["name"]), item["min"],
                               item["max"], fields, origin))
        else:
            items.append(_field(item, origin))
    return items


def _sentence(doc: Document) -> Sentence:
    d = doc.data
    file = str(doc.path)
    outcome = _outcome(d.get("outcome"), Origin(file, ("outcome",)))
    layout = Layout(None, d["name"], d["doc"], _items(d.get("fields", []), file, ("fields",)), d["manuals"],
                    Origin(file, ("fields",)), outcome)
    rules = [ReplyRule(r, {}, Origin(file, ("replies", i))) if isinstance(r, str)
             else ReplyRule(r["sentence"], dict(r["when"]), Origin(file, ("replies", i)))
             for i, r in enumerate(d.get("replies", []))]
    return Sentence(d["sentence"], d["name"], d["doc"], d.get("talkers", []), d["manuals"], layout,
                    _variants(d, file, outcome), _notes(d), _examples(d, file), Origin(file, ()), file,
                    address=d.get("address"), framing=d.get("framing", "sentence"), start=d.get("start", "$"),
                    domain=d.get("domain"), kind=d.get("kind", "standard"), vendor=d.get("vendor"),
                    reply_rules=rules, encapsulates=d.get("encapsulates"), like=d.get("like"))


def _variants(d: dict[str, Any], file: str, outcome: Outcome | None) -> list[Layout]:
    """The `variants` of a sentence or an extension (a variant's manuals default to the file's)."""
    return [Layout(v["id"], v["name"], v["doc"], _items(v["fields"], file, ("variants", i, "fields")),
                   v.get("manuals", d["manuals"]), Origin(file, ("variants", i)),
                   _outcome(v["outcome"], Origin(file, ("variants", i, "outcome"))) if "outcome" in v else outcome)
            for i, v in enumerate(d.get("variants", []))]


def _notes(d: dict[str, Any]) -> list[Note]:
    return [Note(n["manuals"], n["text"]) for n in d.get("notes", [])]


def _examples(d: dict[str, Any], file: str) -> list[Example]:
    return [Example(e["manual"], e.get("where"), e["raw"], e.get("corrected"), e.get("reason"),
                    e.get("unrecoverable"), e.get("variant"), e.get("expect"), Origin(file, ("examples", i)))
            for i, e in enumerate(d.get("examples", []))]


def _outcome(data: Any, origin: Origin) -> Outcome | None:
    """A reply's `outcome`: "ok", "error", or {field, ok: [values]}."""
    if data is None:
        return None
    if isinstance(data, str):
        return Outcome(fixed=data, origin=origin)
    return Outcome(field_id=data["field"], ok=list(data["ok"]), origin=origin)


def _payload_field(data: dict[str, Any], origin: Origin) -> PayloadField:
    """A field of a bit payload (`bits`: its width) or of a binary frame (its type's bytes, or
    `size` bytes)."""
    size = BIT_TYPES[data["type"]].size if data["type"] in BIT_TYPES else None
    bits = data["bits"] if "bits" in data else 8 * data["size"] if "size" in data else 8 * size if size else None
    return PayloadField(id=data["id"], name=data["name"], type=data["type"], bits=bits,
                        doc=data.get("doc", data["name"]), origin=origin, unit=data.get("unit"),
                        divisor=data.get("divisor"), base=data.get("base"), enum_id=data.get("enum"),
                        optional=bool(data.get("optional", False)),
                        special=[_special(s, bits) for s in data.get("special", [])],
                        dispatch=data.get("dispatch", []),
                        parts=[_part(p, Origin(origin.file, origin.path + ("parts", i)))
                               for i, p in enumerate(data.get("parts", []))],
                        count=_count(data.get("count")), ref=data.get("ref"))


def _special(data: dict[str, Any], bits: int | None) -> Special:
    """A special value: a raw integer, or (a float field's) the float `value`, whose raw is its
    bit pattern in the field's width (-1 when that width has no such finite float: B002 says so)."""
    if "value" not in data:
        return Special(data["raw"], data["id"], data["doc"])
    raw = float_bits(data["value"], bits or 64)
    return Special(-1 if raw is None else raw, data["id"], data["doc"], float(data["value"]))


def _count(data: Any) -> Any:
    """A `count`: a field's id, a number, or {ones: [mask ids]}."""
    return Ones(tuple(data["ones"])) if isinstance(data, dict) else data


def _part(data: dict[str, Any], origin: Origin) -> PayloadField:
    """A named bit range of a bitfield word: a flag, or an unsigned (signed, enum) number."""
    width = data.get("width", 1)
    return PayloadField(id=data["id"], name=data["name"], type=data.get("type", "bool" if width == 1 else "uint"),
                        bits=width, doc=data.get("doc", data["name"]), origin=origin, unit=data.get("unit"),
                        divisor=data.get("divisor"), enum_id=data.get("enum"), low=data["bit"])


def _payload_items(data: list[dict[str, Any]], file: str, where: tuple[str | int, ...]) -> list[PayloadItem]:
    items: list[PayloadItem] = []
    for i, item in enumerate(data):
        at = where + (i,)
        if "group" in item:
            fields = _payload_items(item["fields"], file, at + ("fields",))
            if "stride" in item:   # an entry of the stride's bytes: the bytes after its fields, as sent
                # (before a nested group, whose entries follow the stride's bytes)
                fields.insert(len(fields) - (1 if fields and isinstance(fields[-1], PayloadGroup) else 0), PayloadField(id=STRIDE_TRAILING, name="Bytes after the entry's fields, as sent", type="bytes",
                                           bits=None, doc="The entry's bytes after its fields, as sent (a newer "
                                           "firmware's additions, the stride's padding)", origin=Origin(file, at + ("stride",))))
            items.append(PayloadGroup(item["group"], item["name"], item.get("doc", item["name"]),
                                      item.get("min", 0 if "count" in item else 1), item.get("max", MAX_ENTRIES),
                                      fields, Origin(file, at), count=_count(item.get("count")),
                                      field_major=item.get("order") == "field_major", stride=item.get("stride")))
        elif "choice" in item:
            cases = [PayloadCase(c.get("when", []), tuple(c["range"]) if "range" in c else None,
                                 _payload_items(c["fields"], file, at + ("cases", k, "fields")))  # type: ignore[arg-type]
                     for k, c in enumerate(item["cases"])]
            items.append(PayloadChoice(item["choice"], item["by"], item.get("doc", ""), cases, Origin(file, at)))
        else:
            items.append(_payload_field(item, Origin(file, at)))
    return items


def _protocol(doc: Document) -> BinaryProtocol:
    d = doc.data
    return BinaryProtocol(d["protocol"], d["name"], {m["id"]: m["title"] for m in d["documents"]}, d.get("classes", {}),
                          Origin(str(doc.path), ()), d["frame"], d.get("identity", []))


def _config_database(doc: Document) -> ConfigDatabase:
    """A configuration database: its enums and its groups of keys, each key given its group's id
    and documents."""
    d = doc.data
    file = str(doc.path)
    enums = {e: ConfigEnum(e, v["doc"], dict(v["values"]), Origin(file, ("enums", e))) for e, v in d["enums"].items()}
    groups = []
    for i, g in enumerate(d["groups"]):
        documents = list(g.get("documents", []))
        keys = [ConfigKey(g["group"], k["item"], k["id"], k["type"], Origin(file, ("groups", i, "keys", j)),
                          group_id=g["id"], scale=k.get("scale"), unit=k.get("unit"), enum_id=k.get("enum"),
                          aliases=list(k.get("aliases", [])), doc=k.get("doc", ""), documents=documents,
                          enum=enums.get(k.get("enum", "")))
                for j, k in enumerate(g["keys"])]
        groups.append(ConfigGroup(g["id"], g["group"], g["name"], documents, keys, Origin(file, ("groups", i))))
    return ConfigDatabase(d["config_keys"], d["library"], d["not_found"], enums, groups, Origin(file, ()))


def _select(layout: dict[str, Any]) -> tuple[str, int] | None:
    """A layout's selector: `select: {type: 0x10}`, or `version: 1` (short for `select: {version: 1}`)."""
    if "version" in layout:
        return ("version", layout["version"])
    return next(iter(layout["select"].items())) if "select" in layout else None


def _binary_message(doc: Document) -> BinaryMessage:
    """A binary message and its layouts, each a Payload named by the message's id and its variant
    (a poll's default: poll)."""
    d = doc.data
    file = str(doc.path)
    protocol = doc.path.parent.parent.name
    layouts = []
    for i, lay in enumerate(d["layouts"]):
        variant = lay.get("variant", "poll" if lay["direction"] == ["poll"] else "")
        at: tuple[str | int, ...] = ("layouts", i)
        layouts.append(Payload(d["message"] + (f"_{variant}" if variant else ""), d["name"], lay.get("doc", d["doc"]),
                               [], d["documents"], 8 * lay["length"] if "length" in lay else None,
                               _payload_items(lay["fields"], file, at + ("fields",)), [], [], Origin(file, at),
                               protocol=protocol, directions=lay["direction"], select=_select(lay),
                               replies=lay.get("replies", []),
                               acknowledges=(lay["acknowledges"]["class"], lay["acknowledges"]["id"])
                               if "acknowledges" in lay else None))
    message = BinaryMessage(d["message"], d["name"], d["doc"], protocol, d.get("class", ""), d["id"], d["documents"],
                            layouts, Origin(file, ()), sub_id=d.get("sub_id"),
                            revision=d.get("revision"),
                            examples=[BinaryExample(e["where"], bytes.fromhex(e["frame"]), e.get("expect"),
                                                    Origin(file, ("examples", i)))
                                      for i, e in enumerate(d.get("examples", []))])
    for layout in layouts:
        layout.frame = message
    return message


def _bit_message(doc: Document) -> Payload:
    """A message of bit fields told by its number (spec/binary/rtcm3/messages): a Payload of its
    protocol, its examples whole frames."""
    d = doc.data
    file = str(doc.path)
    return Payload(d["message"], d["name"], d["doc"], d["numbers"], d["documents"], d.get("length"),
                   _payload_items(d["fields"], file, ("fields",)), [], [], Origin(file, ()),
                   protocol=doc.path.parent.parent.name,
                   frame_examples=[BinaryExample(e["where"], bytes.fromhex(e["frame"]), e.get("expect"),
                                                 Origin(file, ("examples", i)))
                                   for i, e in enumerate(d.get("examples", []))])


def _payload(doc: Document) -> Payload:
    d = doc.data
    file = str(doc.path)
    examples = [PayloadExample(e["manual"], e["where"], e["payload"], e["fill_bits"], e.get("expect"),
                               Origin(file, ("examples", i))) for i, e in enumerate(d.get("examples", []))]
    application = d.get("application")
    routes = [Route(a["dac"] if isinstance(a["dac"], list) else [a["dac"]], a["fid"], a["in"])
              for a in (application if isinstance(application, list) else [application] if application else [])]
    return Payload(d["message"], d["name"], d["doc"], d.get("types", []), d["manuals"], d.get("length"),
                   _payload_items(d["fields"], file, ("fields",)), _notes(d), examples, Origin(file, ()),
                   application=(routes[0].dacs[0], routes[0].fid) if routes else None, routes=routes)
