"""Semantic checks run after the schema: references resolve, layouts are parseable, and every
example of the manuals decodes to the values the spec expects. Each rule has an id that appears
in its messages; every message names the file, line and YAML path at fault."""

from __future__ import annotations

import json
import keyword
from typing import Any

from . import checks_binary, checks_payload, checks_rtcm3, names, names_c, names_rust, reference
from .resolve import checksum_ok
from .errors import SpecError
from .loader import Document
from .field_types import TYPES
from .model import QUERY, Example, Field, Group, Layout, Origin, Sentence, Spec
from .numbers import fixed_point

VERSION_ORDER = ["2.0", "2.1", "2.2", "2.3", "3.0", "3.01", "4.00", "4.10", "4.11"]


class _Reporter:
    def __init__(self, docs: dict[str, Document]) -> None:
        self.docs = docs
        self.errors: list[SpecError] = []

    def __call__(self, origin: Origin, rule: str, message: str, *more: str | int) -> None:
        doc = self.docs[origin.file]
        self.errors.append(doc.error(origin.path + tuple(more), message, rule))


def run(spec: Spec, docs: dict[str, Document]) -> list[SpecError]:
    report = _Reporter(docs)
    _unique(spec, report)
    _distinct_names(spec, report)
    manual_ids = {m.id for m in spec.manuals}
    for enum in spec.enums:
        _check_enum(enum, manual_ids, report)
    for bitfield in spec.bitfields:
        _check_bitfield(bitfield, manual_ids, report)
    for table in spec.tables:
        _check_table(spec, table, manual_ids, report)
    _check_facts(spec, report)
    _check_tag_codes(spec, manual_ids, report)
    for sentence in spec.sentences:
        _check_manuals(sentence.manuals, manual_ids, sentence.origin, report, "manuals")
        _check_proprietary(spec, sentence, manual_ids, report)
        for layout in sentence.layouts:
            _check_layout(spec, sentence, layout, manual_ids, report)
            _check_fix(sentence, layout, report)
    checks_payload.check(spec, manual_ids, report, _check_manuals)
    checks_binary.check(spec, report)
    checks_rtcm3.check(spec, report)
    if report.errors:
        return report.errors
    checks_payload.check_examples(spec, manual_ids, report)
    checks_binary.check_examples(spec, report)
    checks_rtcm3.check_examples(spec, report)
    _generated_names(spec, report)
    _check_generic(spec, report)
    _check_cli(spec, report)
    for sentence in spec.sentences:
        _check_replies(sentence, report)
    _check_fix_examples(spec, report)
    for sentence in spec.sentences:
        variant_ids = {v.id for v in sentence.variants}
        for example in sentence.examples:
            _check_example(spec, sentence, example, manual_ids, variant_ids, report)
    return report.errors


def _distinct_names(spec: Spec, report: _Reporter) -> None:
    """Enums, bitfields, tables and sentence layouts become types of one namespace in every
    language: their names must differ."""
    owners: dict[str, str] = {}
    for s in spec.sentences:
        for layout in s.layouts:
            owners[s.layout_snake(layout)] = f"sentence {s.id}"
    for kind, items in (("enum", spec.enums), ("bitfield", spec.bitfields), ("table", spec.tables)):
        for item in items:
            other = owners.get(item.id)
            if other is not None:
                report(item.origin, "S013", f"{kind} {item.id} has the name of {other}; rename it "
                       f"(e.g. {item.id}_code)", kind)
            owners[item.id] = f"{kind} {item.id}"


def _generated_names(spec: Spec, report: _Reporter) -> None:
    """The names each emitter builds from the spec's ids (C identifiers, Rust types, the command
    names of the `nmea` CLI) must not be shared by two things, nor taken from a runtime."""
    for clashes in (names_c.clashes, names_rust.clashes, names.command_clashes):
        for origin, message in clashes(spec):
            report(origin, "S016", f"{message}; rename one of them")


def _check_generic(spec: Spec, report: _Reporter) -> None:
    """What manuals.yaml says stays generic must: its example is a real line (checksum right, the
    message it names) that no layout of the spec reads."""
    for g in spec.generic:
        line = g.example
        if not line.startswith(g.message):
            report(g.origin, "S017", f"the example does not start with {g.message}", "example")
            continue
        try:
            frame, found = reference.candidates(spec, line)
        except reference.rt.NmeaError as err:
            report(g.origin, "S017", f"the example is not a sentence: {err.message}", "example")
            continue
        if frame.checksum is None or not checksum_ok(line):
            report(g.origin, "S017", "the example's checksum is missing or wrong", "example")
        elif found:
            names = ", ".join(sorted({s.id for s, _ in found}))
            report(g.origin, "S045", f"{g.message} is no longer generic ({names} reads it): remove it from the list",
                   "message")


def _unique(spec: Spec, report: _Reporter) -> None:
    seen: dict[str, Origin] = {}
    for s in spec.sentences:
        if s.id in seen:
            report(s.origin, "S001", f"sentence {s.id} is also defined in {seen[s.id].file}", "sentence")
        seen[s.id] = s.origin
    enums: dict[str, Origin] = {}
    for e in spec.enums:
        if e.id in enums:
            report(e.origin, "S001", f"enum {e.id} is also defined in {enums[e.id].file}", "enum")
        enums[e.id] = e.origin
        stem = e.origin.file.rsplit("/", 1)[-1].removesuffix(".yaml")
        if stem != e.id:
            report(e.origin, "S010", f"enum {e.id} must live in {e.id}.yaml", "enum")
    for s in spec.sentences:
        stem = s.origin.file.rsplit("/", 1)[-1].removesuffix(".yaml")
        if stem != s.id.lower():
            report(s.origin, "S010", f"sentence {s.id} must live in {s.id.lower()}.yaml", "sentence")


def _check_proprietary(spec: Spec, sentence: Sentence, manual_ids: set[str], report: _Reporter) -> None:
    if not sentence.is_proprietary:
        if (len(sentence.id) not in (3, 4) and sentence.id != QUERY) or not sentence.id.isalnum():
            report(sentence.origin, "S034", f"standard sentence {sentence.id}: the id is the 3-character formatter "
                   f"(or 4, a receiver's own formatter such as Unicore's GGAH, or {QUERY}, the query, whose talker is "
                   "two talker IDs); a proprietary sentence needs `address`", "sentence")
        for key, value in (("kind", sentence.kind != "standard"), ("vendor", sentence.vendor), ("replies", sentence.reply_rules),
                           ("framing", sentence.framing != "sentence")):
            if value:
                report(sentence.origin, "S035", f"standard sentence {sentence.id} cannot have `{key}`", key)
        if sentence.domain is None:
            report(sentence.origin, "S036", f"standard sentence {sentence.id} needs a `domain` (for the docs index)",
                   "sentence")
        return
    for key, value in (("start", sentence.start != "$"), ("domain", sentence.domain)):
        if value:
            report(sentence.origin, "S037", f"proprietary sentence {sentence.id} cannot have `{key}`", key)
    if sentence.vendor not in manual_ids:
        report(sentence.origin, "S003", f"vendor {sentence.vendor!r} is not a manual id", "vendor")
    if sentence.framing == "text" and not (sentence.address or "").isalpha():
        report(sentence.origin, "S038", "a text command's address is its command word: letters only", "address")
    if sentence.framing == "text":
        for layout in sentence.layouts:
            for item in layout.items:
                if isinstance(item, Group) or item.wire_width != 1:
                    report(item.origin, "S015", "a text command's fields are single words: no groups, no "
                           "latitude or longitude", "id")
                elif item.field_type.keyword and item.value and item.value != item.value.upper():
                    # Text commands match their words ignoring case, against the upper-case spelling.
                    report(item.origin, "S039", f"keyword field {item.id}: write the word in upper case", "value")
    if sentence.reply_ids and sentence.kind != "command":
        report(sentence.origin, "S040", "only commands have replies", "replies")
    for rule in sentence.reply_rules:
        if rule.sentence is None:
            report(rule.origin, "S011", f"unknown reply sentence {rule.sentence_id!r}")
    if any(layout.outcome for layout in sentence.layouts) and sentence.kind != "reply":
        report(sentence.origin, "S043", "only replies have an `outcome`", "sentence")


# Most digits a number field holds in every runtime (NMEA_MAX_DIGITS, runtime.MAX_DIGITS).
MAX_DIGITS = 18

def _check_facts(spec: Spec, report: _Reporter) -> None:
    """The facts of spec/fix.yaml: unique ids, and `enums` and `from` that name existing enums,
    their value ids and the fact's own values."""
    seen: set[str] = set()
    for fact in spec.facts:
        if fact.id in seen:
            report(fact.origin, "S001", f"fact {fact.id} appears twice", "id")
        seen.add(fact.id)
        for i, enum_id in enumerate(fact.enums):
            if enum_id not in spec.enum_by_id:
                report(fact.origin, "S047", f"fact {fact.id}: unknown enum {enum_id!r}", "enums", i)
        for enum_id, mapping in fact.mapping.items():
            enum = spec.enum_by_id.get(enum_id)
            if enum is None:
                report(fact.origin, "S047", f"fact {fact.id}: unknown enum {enum_id!r}", "from", enum_id)
                continue
            for value_id, value in mapping.items():
                if enum.by_id(value_id) is None:
                    report(fact.origin, "S047", f"fact {fact.id}: enum {enum_id} has no value {value_id!r}",
                           "from", enum_id)
                if value not in fact.values:
                    report(fact.origin, "S047", f"fact {fact.id}: {value!r} is not one of its values "
                           f"({', '.join(fact.values)})", "from", enum_id)


def _check_tag_codes(spec: Spec, manual_ids: set[str], report: _Reporter) -> None:
    """The codes of spec/tag_block.yaml: each code and id once, an id that can be a property of
    the Python TagBlock (not a keyword nor a member of the runtime's class), the manuals known."""
    codes: set[str] = set()
    ids: set[str] = set()
    taken = set(dir(reference.rt.TagBlock))
    for tag in spec.tag_codes:
        if keyword.iskeyword(tag.id) or tag.id in taken:
            report(tag.origin, "S014", f"TAG block code id {tag.id} is a name of Python's TagBlock itself", "id")
        if tag.code in codes:
            report(tag.origin, "S001", f"TAG block code {tag.code} appears twice", "code")
        if tag.id in ids:
            report(tag.origin, "S001", f"TAG block code id {tag.id} appears twice", "id")
        codes.add(tag.code)
        ids.add(tag.id)
    if spec.tag_codes:
        _check_manuals(spec.tag_manuals, manual_ids, Origin(spec.tag_codes[0].origin.file, ()), report, "manuals")


def _check_fix_examples(spec: Spec, report: _Reporter) -> None:
    """Each line of a fix example is an intact sentence of a layout that carries facts."""
    for example in spec.fix_examples:
        for i, line in enumerate(example.lines):
            if not checksum_ok(line):
                report(example.origin, "S048", f"the checksum fails (computed {_computed(line)})", "lines", i)
                continue
            try:
                decoded = reference.decode(spec, line)
            except reference.rt.NmeaError as err:
                report(example.origin, "S048", f"does not decode: {err}", "lines", i)
                continue
            if decoded.layout is None or not decoded.layout.fix_fields:
                report(example.origin, "S048", "no field of its layout carries a fact of a fix", "lines", i)


def _check_fix(sentence: Sentence, layout: Layout, report: _Reporter) -> None:
    """Each field's `fix` names a fact that a field of its type, unit and enum can carry, in the
    right place (an epoch fact outside a group, once per layout; a satellite fact in a group)."""
    seen: set[str] = set()
    for item in layout.items:
        grouped = isinstance(item, Group)
        for f in item.fields if isinstance(item, Group) else [item]:
            if f.fix_id is None:
                continue
            fact = f.fact
            if fact is None:
                report(f.origin, "S047", f"field {f.id}: unknown fact {f.fix_id!r} (spec/fix.yaml)", "fix")
                continue
            problem = None
            if f.type not in fact.types:
                problem = f"a {f.type} field cannot carry fact {fact.id} ({' or '.join(fact.types)})"
            elif (f.unit or fact.units) and f.unit not in fact.units:
                problem = f"fact {fact.id} takes units {', '.join(fact.units) or 'none'}, the field is in {f.unit}"
            elif f.enum is not None and f.enum.id not in fact.enums and f.enum.id not in fact.mapping:
                problem = f"fact {fact.id} takes no values of enum {f.enum.id} (its `enums` or `from`)"
            elif grouped != (fact.scope == "satellite"):
                problem = (f"fact {fact.id} is of one satellite: it belongs to a group's field" if not grouped else
                           f"fact {fact.id} is of the epoch: it cannot be a group's field")
            elif not grouped and fact.id in seen:
                problem = f"fact {fact.id} is carried twice in {sentence.id}{f' ({layout.id})' if layout.id else ''}"
            if problem:
                report(f.origin, "S047", f"field {f.id}: {problem}", "fix")
            seen.add(fact.id)


def _check_replies(sentence: Sentence, report: _Reporter) -> None:
    """A command's `when` names fields of its reply with values they can hold; a reply's `outcome`
    names a field of each layout it applies to."""
    for rule in sentence.reply_rules:
        if rule.sentence is None:
            continue
        for field_id, value in rule.when.items():
            found = [f for layout in rule.sentence.layouts for f in layout.fields if f.id == field_id]
            if not found:
                report(rule.origin, "S041", f"reply {rule.sentence_id} has no field {field_id!r}", "when", field_id)
            elif (problem := found[0].field_type.pairing_problem(found[0], value)) is not None:
                report(rule.origin, "S041", problem, "when", field_id)
    for layout in sentence.layouts:
        outcome = layout.outcome
        if outcome is None or outcome.field_id is None or outcome.origin is None:
            continue
        found = [f for f in layout.fields if f.id == outcome.field_id]
        if not found:
            name = f"variant {layout.id}" if layout.id else "the main layout"
            report(outcome.origin, "S042", f"{name} of {sentence.id} has no field {outcome.field_id!r}", "field")
            continue
        for i, value in enumerate(outcome.ok):
            if (problem := found[0].field_type.pairing_problem(found[0], value)) is not None:
                report(outcome.origin, "S042", problem, "ok", i)


def _check_bitfield(bitfield: Any, manual_ids: set[str], report: _Reporter) -> None:
    _check_manuals(bitfield.manuals, manual_ids, bitfield.origin, report, "manuals")
    used = 0
    ids: set[str] = set()
    for b in bitfield.bits:
        if b.low > b.high or b.high >= bitfield.width:
            report(b.origin, "S012", f"bits {b.label} do not fit a {bitfield.width}-bit value (write high:low)", "bits")
            continue
        if used & b.mask:
            report(b.origin, "S044", f"bits {b.label} overlap bits named before", "bits")
        used |= b.mask
        if b.id in ids:
            report(b.origin, "S001", f"{b.id!r} appears twice in bitfield {bitfield.id}", "id")
        ids.add(b.id)
        for j, v in enumerate(b.values):
            if v.value >= 1 << b.width:
                report(b.origin, "S012", f"value {v.value} does not fit bits {b.label}", "values", j)


def _check_table(spec: Spec, table: Any, manual_ids: set[str], report: _Reporter) -> None:
    _check_manuals(table.manuals, manual_ids, table.origin, report, "manuals")
    numbers: set[int] = set()
    ids: set[str] = set()
    for p in table.parameters:
        if p.number in numbers or p.id in ids:
            report(p.origin, "S001", f"parameter {p.number} ({p.id}) appears twice in table {table.id}", "number")
        numbers.add(p.number)
        ids.add(p.id)
        if p.enum_id is not None and p.enum is None:
            report(p.origin, "S002", f"parameter {p.id} refers to unknown enum {p.enum_id!r}", "enum")
        if p.bitfield_id is not None and p.bitfield is None:
            report(p.origin, "S002", f"parameter {p.id} refers to unknown bitfield {p.bitfield_id!r}", "bitfield")
        if p.encoding == "decimal_list" and not p.count:
            report(p.origin, "S007", f"parameter {p.id}: a decimal_list needs `count`", "encoding")


def _check_manuals(manuals: list[str], known: set[str], origin: Origin, report: _Reporter, *where: str | int) -> None:
    for i, m in enumerate(manuals):
        if m not in known:
            report(origin, "S003", f"unknown manual {m!r} (spec/manuals.yaml lists {', '.join(sorted(known))})",
                   *where, i)


def _check_enum(enum: Any, manual_ids: set[str], report: _Reporter) -> None:
    codes: set[str] = set()
    ids: set[str] = set()
    for v in enum.values:
        if v.code in codes:
            report(v.origin, "S006", f"code {v.code!r} appears twice in enum {enum.id}", "code")
        if v.id in ids:
            report(v.origin, "S006", f"value id {v.id!r} appears twice in enum {enum.id}", "id")
        if any(ch in ",*$!" for ch in v.code) or v.code != v.code.strip():
            report(v.origin, "S024", f"code {v.code!r} cannot hold ',', '*', '$', '!' or start or end with a space",
                   "code")
        codes.add(v.code)
        ids.add(v.id)
        _check_manuals(v.manuals, manual_ids, v.origin, report, "manuals")


def _check_cli(spec: Spec, report: _Reporter) -> None:
    """`cli` shortcuts: on values of an enum that a command field takes, unique in their enum, and
    not named like a command of the vendors that take the enum."""
    takers: dict[str, list[Sentence]] = {}
    for s in spec.sentences:
        if s.kind == "command":
            for layout in s.layouts:
                for f in layout.fields:
                    if f.enum is not None:
                        takers.setdefault(f.enum.id, []).append(s)
    for enum in spec.enums:
        seen: set[str] = set()
        commands = {t.command_name(layout) for s in takers.get(enum.id, []) for t in spec.sentences
                    if t.kind == "command" and t.vendor == s.vendor for layout in t.layouts}
        for v in enum.values:
            if v.cli is None:
                continue
            if enum.id not in takers:
                report(v.origin, "S025", f"cli {v.cli!r}: no command takes enum {enum.id}", "cli")
            if v.cli in seen:
                report(v.origin, "S026", f"cli {v.cli!r} appears twice in enum {enum.id}", "cli")
            if v.cli.split()[0] in commands:
                report(v.origin, "S027", f"cli {v.cli!r} is named like a command", "cli")
            seen.add(v.cli)


# Names the generated code of every language gives to other things in a sentence's type:
# envelope attributes, methods, the C tagged union. A field or group may not take them.
RESERVED_FIELD_IDS = frozenset({
    "address", "as", "as_received", "checksum", "fields", "fields_from_json", "fields_json", "id", "kind",
    "optional_count", "parse", "parse_fields", "problems", "replies", "selector", "sentence", "start", "talker",
    "to_bytes", "to_json", "to_sentence", "trailing", "variant",
    # names the generated Python module itself uses
    "Any", "ClassVar", "Decimal", "dataclass", "field", "list", "rt",
}) | frozenset(keyword.kwlist)


def _check_layout(spec: Spec, sentence: Sentence, layout: Layout, manual_ids: set[str],
                  report: _Reporter) -> None:
    ids: set[str] = set()
    seen_optional = False
    groups = 0
    for item in layout.items:
        if item.id in ids:
            report(item.origin, "S001", f"{item.id!r} appears twice in {sentence.id}", "id")
        ids.add(item.id)
        names = [item.id] + ([f.id for f in item.fields] if isinstance(item, Group) else [])
        for name in names:
            if name in RESERVED_FIELD_IDS:
                report(item.origin, "S014", f"{name!r} is a name the generated code uses itself; choose another id",
                       "group" if isinstance(item, Group) and name == item.id else "id")
        if isinstance(item, Group):
            groups += 1
            if item.min > item.max:
                report(item.origin, "S022", f"group {item.id}: min {item.min} exceeds max {item.max}", "min")
            if seen_optional:
                report(item.origin, "S004", f"group {item.id} follows an optional field", "group")
            inner: set[str] = set()
            count_id = f"{item.id}_count"  # the C member that counts the entries
            if any(other.id == count_id for other in layout.items):
                report(item.origin, "S014", f"{count_id!r} is the name of the count of group {item.id}; choose "
                       "another id", "group")
            for f in item.fields:
                if f.id in inner:
                    report(f.origin, "S001", f"{f.id!r} appears twice in group {item.id}", "id")
                inner.add(f.id)
                if f.is_optional:
                    report(f.origin, "S019", "a field inside a group cannot be optional", "id")
                if f.field_type.keyword:
                    report(f.origin, "S020", "a group cannot hold a keyword (a keyword picks the layout)", "type")
                _check_field(f, manual_ids, report)
            continue
        if item.is_optional:
            seen_optional = True
        elif seen_optional:
            report(item.origin, "S004", f"required field {item.id} follows an optional field; optional "
                   "fields must be trailing", "id")
        _check_field(item, manual_ids, report)
    if groups > 1:
        report(layout.origin, "S023", f"{sentence.id} has {groups} groups; a layout takes at most one")
    group = layout.group
    if group is not None and not group.is_fixed and layout.optional_count >= group.width:
        report(group.origin, "S005", f"group {group.id} repeats a variable number of times and is followed by "
               f"{layout.optional_count} optional fields; fewer than its width ({group.width}) keep the "
               "field count unambiguous (or use a variant)", "group")
    versions = [f.since for f in layout.optional_fields if f.since]
    if versions != sorted(versions, key=VERSION_ORDER.index):
        report(layout.origin, "S021", f"{sentence.id}: optional fields must be in the order of the NMEA "
               "versions that added them")


def _check_field(f: Field, manual_ids: set[str], report: _Reporter) -> None:
    _check_manuals(f.manuals, manual_ids, f.origin, report, "manuals")
    if f.bitfield_id is not None:
        if f.bitfield is None:
            report(f.origin, "S002", f"field {f.id} refers to unknown bitfield {f.bitfield_id!r}", "bitfield")
        elif not f.field_type.bits:
            report(f.origin, "S007", f"field {f.id}: a bitfield applies to {_types_that('bits')} fields", "bitfield")
    if f.field_type.keyword and not (f.value or "").strip():
        report(f.origin, "S007", f"keyword field {f.id} needs its word in `value`", "value")
    if f.enum_id is not None:
        if f.enum is None:
            report(f.origin, "S002", f"field {f.id} refers to unknown enum {f.enum_id!r}", "enum")
        elif f.field_type.per_char and f.enum.max_len != 1:
            report(f.origin, "S018", f"{f.type} field {f.id} needs an enum of one-character codes", "enum")
    if f.min is not None and f.max is not None and f.min > f.max:
        report(f.origin, "S028", f"field {f.id}: min {f.min} exceeds max {f.max}", "min")
    for key, bound in (("min", f.min), ("max", f.max)):
        if bound is not None:
            digits, scale = fixed_point(bound)
            if scale > MAX_DIGITS or abs(digits) >= 10**MAX_DIGITS:
                report(f.origin, "S029", f"field {f.id}: {key} {bound} needs more than the {MAX_DIGITS} digits "
                       "a number holds", key)
    if (f.min is not None or f.max is not None) and not f.field_type.numeric:
        report(f.origin, "S007", f"field {f.id}: min/max apply to {_types_that('numeric')} fields only", "min")
    if f.max_length is not None and not f.field_type.has_length:
        report(f.origin, "S007", f"field {f.id}: max_length applies to {_types_that('has_length')} only",
               "max_length")


def _types_that(attribute: str) -> str:
    """The field types with `attribute`, for a message: "text and enum_chars"."""
    names = [t.name for t in TYPES.values() if getattr(t, attribute)]
    return ", ".join(names[:-1]) + " and " + names[-1] if len(names) > 1 else names[0]


def _check_example(spec: Spec, sentence: Sentence, example: Example, manual_ids: set[str],
                   variant_ids: set[str | None], report: _Reporter) -> None:
    o = example.origin
    if example.manual not in manual_ids:
        report(o, "S003", f"unknown manual {example.manual!r}", "manual")
    if example.checksum_ok and example.corrected and example.corrected == example.raw:
        report(o, "S031", "the correction is the manual's text itself", "corrected")
        return
    if not example.checksum_ok and not (example.corrected or example.unrecoverable):
        report(o, "S030", f"raw's checksum fails (computed {_computed(example.raw)}); give `corrected` and "
               "`reason`, or `unrecoverable`", "raw")
        return
    if example.unrecoverable:
        return
    if example.corrected and sentence.framing != "text" and "*" in example.corrected \
            and not checksum_ok(example.corrected):
        report(o, "S032", f"the correction's checksum fails too (computed {_computed(example.corrected)})",
               "corrected")
        return
    if example.variant is not None and example.variant not in variant_ids:
        report(o, "S009", f"unknown variant {example.variant!r}", "variant")
        return
    line = example.line
    assert line is not None
    try:
        decoded = reference.decode(spec, line, strict=True)  # within every range the spec gives
    except reference.rt.NmeaError as err:
        report(o, "S033", f"does not decode: {err}", "corrected" if example.corrected else "raw")
        return
    if decoded.sentence is not sentence:
        report(o, "S033", f"decodes as {decoded.sentence.id if decoded.sentence else 'an unknown sentence'}, "
               f"not {sentence.id}", "raw")
        return
    if decoded.layout is None or decoded.layout.id != example.variant:
        found = decoded.layout.id if decoded.layout else None
        report(o, "S009", f"decodes with layout {found or 'main'}, the example says "
               f"{example.variant or 'main'}", "variant")
        return
    expected, problems = reference.expect_json(decoded.layout, example.expect or {})
    for key, problem in problems:
        report(o, "S008", problem, "expect", key)
    if problems:
        return
    got = json.loads(reference.fields_json(decoded, values=True))
    want = json.loads(expected)
    for key in got:
        if key not in want:
            report(o, "S008", f"field {key} is on the wire but not in expect (decoded: {json.dumps(got[key])})",
                   "expect")
    for key in want:
        if key not in got:
            report(o, "S008", f"expect names {key}, which is not on the wire", "expect", key)
        elif got[key] != want[key]:
            report(o, "S008", f"{key} decodes to {json.dumps(got[key])}, expect says {json.dumps(want[key])}",
                   "expect", key)


def _computed(line: str) -> str:
    star = line.find("*")
    body = line[1:star] if star >= 0 else line[1:]
    return f"{reference.rt.checksum(body):02X}"
