"""Semantic checks of the bit-packed payloads (spec/ais/messages): widths fit their types and sum
to the documented length, special values fit their fields, ids are unique, variable and optional
items come where a reader can size them, choices can find their selector, and every example
decodes to its `expect`. Rule ids A001-A013 (generator/rules.py)."""

from __future__ import annotations

from typing import Callable

from . import reference_ais
from .model import Ones, Origin, Payload, PayloadChoice, PayloadField, PayloadGroup, Spec, flat_fields

Report = Callable[..., None]   # checks._Reporter: (origin, rule, message, *yaml path)


def check(spec: Spec, manual_ids: set[str], report: Report, check_manuals: Callable[..., None]) -> None:
    """Everything but the examples (check_examples, once the spec holds together)."""
    owners: dict[int, str] = {}
    for payload in spec.payloads:
        stem = payload.origin.file.rsplit("/", 1)[-1].removesuffix(".yaml")
        if stem != payload.id:
            report(payload.origin, "S010", f"message {payload.id} must live in {payload.id}.yaml", "message")
        for i, number in enumerate(payload.types):
            if number in owners:
                report(payload.origin, "A008", f"message type {number} is also described by {owners[number]}", "types", i)
            owners.setdefault(number, payload.id)
        check_manuals(payload.manuals, manual_ids, payload.origin, report, "manuals")
        check_items(payload, report)
        for item in payload.items:   # the runtimes' AIS readers count groups by the bits left only
            counted = item.count if isinstance(item, (PayloadField, PayloadGroup)) else None
            if counted is not None or isinstance(item, PayloadGroup) and item.field_major:
                report(item.origin, "A012", f"{item.id}: counts and field-major groups are for the messages of "
                       "spec/binary (RTCM 3), not AIS payloads", "count")
    applications: dict[tuple[int, int, int], str] = {}   # by DAC, FI and the message type carrying them
    for application in spec.applications:
        stem = application.origin.file.rsplit("/", 1)[-1].removesuffix(".yaml")
        if stem != application.id:
            report(application.origin, "S010", f"message {application.id} must live in {application.id}.yaml", "message")
        for dac, fid in application.keys:
            for carrier in application.carriers_of((dac, fid)):
                if (dac, fid, carrier) in applications:
                    report(application.origin, "A008", f"DAC and FI {(dac, fid)} in a type {carrier} are also described "
                           f"by {applications[dac, fid, carrier]}", "application")
                applications.setdefault((dac, fid, carrier), application.id)
        for i, number in enumerate(application.carriers):
            carrier = owners.get(number)
            message = next((p for p in spec.payloads if p.id == carrier), None)
            if message is None or message.data_field is None or len(message.data_field.dispatch) != 2:
                report(application.origin, "A011", f"message type {number} has no data field dispatched by DAC and "
                       "FI", "application", "in", i)
        check_manuals(application.manuals, manual_ids, application.origin, report, "manuals")
        check_items(application, report)
    for sentence in spec.sentences:
        for role, field_id in (sentence.encapsulates or {}).items():
            if role != "protocol" and any(field_id not in {f.id for f in layout.fields} for layout in sentence.layouts):
                report(sentence.origin, "A010", f"encapsulates.{role}: {field_id} is not a field of every layout of "
                       f"{sentence.id}", "encapsulates", role)


def check_field(f: PayloadField, report: Report) -> None:
    t = f.bit_type
    if f.bits is None and not t.variable:
        report(f.origin, "A002", f"field {f.id}: a {f.type} field needs `{'size' if t.in_bytes else 'bits'}`", "bits")
    if f.bits is not None:
        if f.bits < t.min_bits or t.max_bits is not None and f.bits > t.max_bits or f.bits % t.char_bits:
            most = f"at most {t.max_bits}" if t.max_bits is not None else "any number of"
            whole = f", a multiple of {t.char_bits}" if t.char_bits > 1 else ""
            report(f.origin, "A002", f"field {f.id}: a {f.type} field takes at least {t.min_bits} and {most} bits{whole}, "
                   f"not {f.bits}", "bits")
    for key, given in (("divisor", f.divisor), ("unit", f.unit), ("special", f.special)):
        if given and not t.numeric:
            report(f.origin, "A002", f"field {f.id}: `{key}` goes with a number (uint, int), not {f.type}", key)
    if t.coded and f.enum_id is None or f.enum_id is not None and not t.enums:
        report(f.origin, "A002", f"field {f.id}: `enum` goes with type enum (or an unsigned byte type) and type "
               "enum needs one", "enum")
    elif f.enum_id is not None and f.enum is None:
        report(f.origin, "S002", f"field {f.id} refers to unknown enum {f.enum_id!r}", "enum")
    elif f.enum is not None and any(not v.code.isdigit() for v in f.enum.values):
        report(f.origin, "A002", f"field {f.id}: enum {f.enum.id} has codes that are no unsigned numbers", "enum")
    if f.dispatch and not t.dispatches:
        report(f.origin, "A002", f"field {f.id}: only data is dispatched", "dispatch")
    if f.bits is not None and t.numeric:
        low, high = t.raw_range(f.bits)
        raws: set[int] = set()
        ids: set[str] = set()
        for i, s in enumerate(f.special):
            if s.value is None and not low <= s.raw <= high:   # a float's: checks_binary
                report(f.origin, "A003", f"field {f.id}: special value {s.raw} is outside the {low}..{high} its "
                       f"{f.bits} bits hold", "special", i, "raw")
            if s.raw in raws or s.id in ids:
                report(f.origin, "A003", f"field {f.id}: special value {s.raw} ({s.id}) is named twice", "special", i)
            raws.add(s.raw)
            ids.add(s.id)


def _paths(items: list) -> list[list[PayloadField | PayloadGroup]]:
    """Every sequence of fields and groups a payload may have, one per combination of cases."""
    paths: list[list[PayloadField | PayloadGroup]] = [[]]
    for item in items:
        if isinstance(item, PayloadChoice):
            paths = [p + q for p in paths for case in item.cases for q in _paths(case.items)]
        else:
            paths = [p + [item] for p in paths]
    return paths


def _choices(items: list) -> list[PayloadChoice]:
    out: list[PayloadChoice] = []
    for item in items:
        if isinstance(item, PayloadChoice):
            out += [item, *(c for case in item.cases for c in _choices(case.items))]
    return out


def check_items(payload: Payload, report: Report) -> None:
    ids: dict[str, Origin] = {}
    for item in [*(i for i in payload.items if isinstance(i, PayloadGroup)), *_choices(payload.items)]:
        if item.id in ids:
            report(item.origin, "A004", f"id {item.id} is also used at {'.'.join(map(str, ids[item.id].path))}")
        ids.setdefault(item.id, item.origin)
    for f in flat_fields([i for i in payload.items if not isinstance(i, PayloadGroup)]):
        if f.id in ids:
            report(f.origin, "A004", f"id {f.id} is also used at {'.'.join(map(str, ids[f.id].path))}", "id")
        ids.setdefault(f.id, f.origin)
        check_field(f, report)
    groups = [i for i in payload.items if isinstance(i, PayloadGroup)]
    for group in groups + [g.nested for g in groups if g.nested is not None]:
        entry_ids: set[str] = set()
        for f in group.fields:
            check_field(f, report)
            if f.id in entry_ids:
                report(f.origin, "A004", f"id {f.id} appears twice in group {group.id}", "id")
            entry_ids.add(f.id)
            if (f.bits is None or f.optional) and not (group.stride is not None and f is group.fields[-1]):
                report(f.origin, "A005", f"field {f.id}: the fields of a group have fixed widths and are required", "bits")
        if group.min > group.max:
            report(group.origin, "A005", f"group {group.id}: min {group.min} is above max {group.max}", "min")
        _check_entry_choices(payload, group, report)
    for choice in _choices(payload.items):
        _check_choice(choice, report)
        selector = choice.selector
        if payload.application is not None and selector is not None and selector.offset is not None \
                and choice.offset is not None and (selector.offset > choice.offset or selector.optional):
            # the C and Rust readers of an application pick the case by the selector's value read before
            report(choice.origin, "A007", f"choice {choice.id}: an application's choice follows its selector, "
                   "a required field", "by")
    _check_counts(payload, report)
    reported: set[str] = set()
    for path in _paths(payload.items):
        variable: str | None = None
        optional: str | None = None
        for item in path:
            here = "/".join(map(str, item.origin.path))
            if variable is not None and (not isinstance(item, PayloadField) or item.bits is None or item.optional) \
                    and here not in reported:
                report(item.origin, "A005", f"{variable} takes the bits left: only required fields of fixed width "
                       "may follow it")
                reported.add(here)
            if optional is not None and not (isinstance(item, PayloadField) and item.optional) and here not in reported:
                report(item.origin, "A006", f"{optional} is optional: what follows it must be optional too")
                reported.add(here)
            if isinstance(item, PayloadGroup) and item.count is None \
                    or isinstance(item, PayloadField) and item.bits is None and item.count is None:
                variable = variable or item.id
            if isinstance(item, PayloadField) and item.optional:
                optional = optional or item.id
    fixed = payload.fixed_width
    if fixed is not None and payload.length != fixed and (payload.length is not None or payload.frame is None):
        report(payload.origin, "A001", f"the fields of message {payload.id} take {fixed} bits; `length` says "
               f"{payload.length}", "length")
    elif fixed is None and payload.length is not None:
        report(payload.origin, "A001", f"message {payload.id} has no fixed length: remove `length`", "length")


def _check_counts(payload: Payload, report: Report) -> None:
    """A012: a counted field (characters, or data bits) or group names top-level fields before it:
    an unsigned field for a number, unsigned or data fields for masks whose set bits count; a
    field-major group has a count."""
    seen: dict[str, PayloadField] = {}

    def names(count: str | Ones, where: str, origin: Origin) -> None:
        for name in count.fields if isinstance(count, Ones) else (count,):
            f = seen.get(name)
            wanted = ("uint", "data") if isinstance(count, Ones) else ("uint",)
            if f is None or f.type not in wanted or f.count is not None and f.type != "data":
                kind = "unsigned or data mask field" if isinstance(count, Ones) else "unsigned field"
                report(origin, "A012", f"{where}: count {name} names no {kind} before it", "count")

    def walk(items: list) -> None:
        for item in items:
            if isinstance(item, PayloadField):
                if item.count is not None:
                    if item.bits is not None or item.bit_type.char_bits != 8 and item.type != "data":
                        report(item.origin, "A012", f"field {item.id}: `count` sizes characters (latin1, utf8) or "
                               "data, without `bits`", "count")
                    elif not isinstance(item.count, int):
                        names(item.count, f"field {item.id}", item.origin)
                seen[item.id] = item
            elif isinstance(item, PayloadGroup):
                if isinstance(item.count, Ones):
                    names(item.count, f"group {item.id}", item.origin)
                if item.field_major and item.count is None:
                    report(item.origin, "A012", f"group {item.id}: a field-major group needs a `count`", "order")
            else:
                for case in item.cases:
                    walk(case.items)

    walk(payload.items)


def _check_entry_choices(payload: Payload, group: PayloadGroup, report: Report) -> None:
    """A013: a choice in a group's entry picks its case by a uint or enum field of the entry before
    it; its cases hold fields only (a default case keeps the bits of values no case names) and are
    all as wide, so that every entry has one width; an AIS payload's group only (the runtimes of
    spec/binary read entries of fields)."""
    before: set[str] = set()
    for item in group.items:
        if isinstance(item, PayloadField):
            before.add(item.id)
            continue
        if isinstance(item, PayloadGroup):   # a group of the entry (B010)
            if payload.protocol == "ais":
                report(item.origin, "A013", f"group {group.id}: group {item.id} in an entry: a binary message's "
                       "group of a stride only (rule B010)")
            continue
        where = f"group {group.id}: choice {item.id}"
        selector = item.selector
        if payload.protocol != "ais" or group.count is not None or group.field_major:
            report(item.origin, "A013", f"{where}: only an AIS payload's group counted by the bits left has choices "
                   "in its entries")
        elif item.by not in before or selector is None or selector.bits is None or not selector.bit_type.selects \
                or selector.type == "bool":
            report(item.origin, "A013", f"{where}: `by` names no uint or enum field of the entry before the choice",
                   "by")
        else:
            _check_choice(item, report)
        widths = {case.width for case in item.cases}
        if any(not isinstance(i, PayloadField) for case in item.cases for i in case.items) or None in widths \
                or len(widths) > 1:
            shown = ", ".join(str(case.width) for case in item.cases)
            report(item.origin, "A013", f"{where}: every case holds required fields of fixed width and is as wide as "
                   f"the others (widths {shown}), so that every entry takes {group.entry_width} bits", "cases")


def _check_choice(choice: PayloadChoice, report: Report) -> None:
    selector = choice.selector
    if selector is None or selector.bits is None or selector.offset is None or not selector.bit_type.selects:
        report(choice.origin, "A007", f"choice {choice.id}: `by` names no top-level uint, flag or enum field at a "
               "fixed bit of the message (a choice after it must have cases of one width)", "by")
        return
    low, high = selector.bit_type.raw_range(selector.bits)
    defaults = [c for c in choice.cases if c.is_default]
    if len(defaults) > 1:
        report(choice.origin, "A007", f"choice {choice.id} has more than one case without `when` or `range`", "cases")
    for i, case in enumerate(choice.cases):
        for raw in case.values + list(case.range or ()):
            if not low <= raw <= high:
                report(choice.origin, "A007", f"choice {choice.id}: {raw} is not a raw value of {selector.id} "
                       f"({low}..{high})", "cases", i)


def check_examples(spec: Spec, manual_ids: set[str], report: Report) -> None:
    """Every example decodes, as a type of its message (an application's: with it), to the values
    of its `expect`."""
    for payload in [*spec.payloads, *spec.applications]:
        _check_examples(payload, spec, manual_ids, report)


def _check_examples(payload: Payload, spec: Spec, manual_ids: set[str], report: Report) -> None:
    for example in payload.examples:
        if example.manual not in manual_ids:
            report(example.origin, "S003", f"unknown manual {example.manual!r}", "manual")
        try:
            decoded = reference_ais.decode(spec, example.payload, example.fill_bits)
        except reference_ais.PayloadError as err:
            report(example.origin, "A009", f"the example does not decode: {err}", "payload")
            continue
        if payload.application is not None:
            decoded = decoded.get("application", {"message_type": decoded["message_type"]})
            if "trailing" not in decoded:
                report(example.origin, "A009", f"the example's data is not application {payload.id}", "payload")
                continue
        elif decoded["message_type"] not in payload.types:
            report(example.origin, "A009", f"the example is a message of type {decoded['message_type']}", "payload")
        for key, value in (example.expect or {}).items():
            if key not in decoded:
                report(example.origin, "A009", f"expect names {key}, which the example does not have", "expect", key)
            elif decoded[key] != value or type(decoded[key]) is not type(value):
                report(example.origin, "A009", f"{key} decodes to {decoded[key]!r}, not {value!r}", "expect", key)
