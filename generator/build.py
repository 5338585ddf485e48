"""Turns the validated YAML documents into the intermediate model, resolves it (resolve.py) and
runs the semantic checks (checks.py)."""

from __future__ import annotations

import hashlib
from pathlib import Path
from typing import Any

from . import checks
from .errors import SpecError, SpecErrors
from .loader import Document, load_document, schema_errors
from .model import (BitfieldDef, Bits, BitValue, EnumDef, EnumValue, Example, Field, GenericMessage, Group, Item, Layout,
                    Manual, Note, Origin, Outcome, Parameter, ReplyRule, Sentence, Spec, TableDef)
from .resolve import resolve


def load_spec(spec_dir: Path) -> Spec:
    """Load, schema-check, build and semantically check the spec; raise SpecErrors listing
    every problem found."""
    errors: list[SpecError] = []
    root = spec_dir.parent
    docs: dict[str, list[Document]] = {"manuals": [], "enums": [], "bitfields": [], "tables": [], "sentences": []}
    files = [(spec_dir / "manuals.yaml", "manuals", "manuals.schema.json")]
    for folder, kind, schema in (("enums", "enums", "enum.schema.json"),
                                 ("bitfields", "bitfields", "bitfield.schema.json"),
                                 ("tables", "tables", "table.schema.json"),
                                 ("standard", "sentences", "sentence.schema.json"),
                                 ("proprietary", "sentences", "sentence.schema.json")):
        files += [(p, kind, schema) for p in sorted((spec_dir / folder).glob("*.yaml"))]
    digest = hashlib.sha256()
    file_digests: dict[str, str] = {}
    for path, kind, schema in files:
        try:
            doc = load_document(path)
        except SpecError as err:
            errors.append(err)
            continue
        doc.path = path.relative_to(root)
        digest.update(str(doc.path).encode() + b"\0" + path.read_bytes())
        file_digests[str(doc.path)] = hashlib.sha256(path.read_bytes()).hexdigest()
        found = schema_errors(doc, schema)
        errors += found
        if not found:
            docs[kind].append(doc)
    if errors:
        raise SpecErrors(errors)

    manuals_doc = docs["manuals"][0]
    manuals = [Manual(**m) for m in manuals_doc.data["manuals"]]
    generic = [GenericMessage(**g, origin=Origin(str(manuals_doc.path), ("generic", i)))
               for i, g in enumerate(manuals_doc.data.get("generic", []))]
    enums = [_enum(d) for d in docs["enums"]]
    sentences = [_sentence(d) for d in docs["sentences"]]
    spec = Spec(manuals, enums, sentences,
                sources=[str(d.path) for kind in ("enums", "bitfields", "tables", "sentences") for d in docs[kind]],
                digest=digest.hexdigest()[:16], file_digests=file_digests,
                bitfields=[_bitfield(d) for d in docs["bitfields"]], tables=[_table(d) for d in docs["tables"]],
                generic=generic)
    by_file = {str(d.path): d for kind in docs.values() for d in kind}
    resolve(spec)
    errors = checks.run(spec, by_file)
    if errors:
        raise SpecErrors(errors)
    return spec


def _enum(doc: Document) -> EnumDef:
    d = doc.data
    values = [EnumValue(v["code"], v["id"], v["doc"], v.get("manuals", []), v.get("since"),
                        Origin(str(doc.path), ("values", i)), v.get("cli"))
              for i, v in enumerate(d["values"])]
    return EnumDef(d["enum"], d["name"], d["doc"], values, Origin(str(doc.path), ()))


def _field(data: dict[str, Any], origin: Origin) -> Field:
    return Field(id=data["id"], name=data["name"], type=data["type"], doc=data["doc"],
                 manuals=data.get("manuals", []), origin=origin, format=data.get("format"),
                 unit=data.get("unit"), min=data.get("min"), max=data.get("max"),
                 max_length=data.get("max_length"), enum_id=data.get("enum"), value=data.get("value"),
                 since=data.get("since"), optional=bool(data.get("optional", False)),
                 bitfield_id=data.get("bitfield"))


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
    layout = Layout(None, d["name"], d["doc"], _items(d["fields"], file, ("fields",)), d["manuals"],
                    Origin(file, ("fields",)), outcome)
    variants = [Layout(v["id"], v["name"], v["doc"], _items(v["fields"], file, ("variants", i, "fields")),
                       v.get("manuals", d["manuals"]), Origin(file, ("variants", i)),
                       _outcome(v["outcome"], Origin(file, ("variants", i, "outcome"))) if "outcome" in v else outcome)
                for i, v in enumerate(d.get("variants", []))]
    rules = [ReplyRule(r, {}, Origin(file, ("replies", i))) if isinstance(r, str)
             else ReplyRule(r["sentence"], dict(r["when"]), Origin(file, ("replies", i)))
             for i, r in enumerate(d.get("replies", []))]
    examples = [Example(e["manual"], e.get("where"), e["raw"], e.get("corrected"), e.get("reason"),
                        e.get("unrecoverable"), e.get("variant"), e.get("expect"),
                        Origin(file, ("examples", i)))
                for i, e in enumerate(d.get("examples", []))]
    notes = [Note(n["manuals"], n["text"]) for n in d.get("notes", [])]
    return Sentence(d["sentence"], d["name"], d["doc"], d.get("talkers", []), d["manuals"], layout,
                    variants, notes, examples, Origin(file, ()), file, address=d.get("address"),
                    framing=d.get("framing", "sentence"), start=d.get("start", "$"), domain=d.get("domain"), kind=d.get("kind", "standard"), vendor=d.get("vendor"),
                    reply_rules=rules)


def _outcome(data: Any, origin: Origin) -> Outcome | None:
    """A reply's `outcome`: "ok", "error", or {field, ok: [values]}."""
    if data is None:
        return None
    if isinstance(data, str):
        return Outcome(fixed=data, origin=origin)
    return Outcome(field_id=data["field"], ok=list(data["ok"]), origin=origin)
