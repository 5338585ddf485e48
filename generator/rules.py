"""Every rule a spec must keep, by the id its error messages carry: what it checks and how to fix a
break. The loader, the build and checks.py report only ids of this table; `nmeaspec-gen rules`
prints it and docs/rules.md is its Markdown form (`nmeaspec-gen rules --markdown`)."""

from __future__ import annotations

import textwrap
from typing import NamedTuple


class Rule(NamedTuple):
    id: str
    title: str
    checks: str
    fix: str


RULES: dict[str, Rule] = {rule.id: rule for rule in (
    Rule("yaml", "valid YAML",
         "The file parses as YAML.",
         "Fix the syntax at the line named (indentation, an unclosed quote or bracket, a tab)."),
    Rule("schema", "the shape of the file",
         "The file fits its JSON Schema (spec/schema/*.schema.json): required keys, known keys, value types.",
         "Add the missing key, remove the unknown one or correct the value; the message names the schema's complaint."),
    Rule("S001", "ids are unique",
         "An id is defined once in its scope: sentences, enums, bitfields, tables and manuals in the spec and "
         "its overlays, fields in a layout or a group, parameters in a table.",
         "Rename one of the two (the message names the other's file), or drop the copy."),
    Rule("S002", "enums and bitfields exist",
         "A field's or parameter's `enum` or `bitfield` names a file of enums/ or bitfields/.",
         "Correct the id, or add the enum or bitfield."),
    Rule("S003", "manuals exist",
         "Every `manuals`, example `manual` and proprietary `vendor` is an id of manuals.yaml.",
         "Correct the id, or add the manual to manuals.yaml (`nmeaspec-gen new manual`)."),
    Rule("S004", "optional fields are trailing",
         "No required field and no group follows an optional field (`optional: true` or `since`).",
         "Move the optional fields to the end, or make the later field optional too."),
    Rule("S005", "a group's count is unambiguous",
         "A group repeated a variable number of times is followed by fewer optional fields than its width.",
         "Fix the group's count (min = max), drop optional fields after it, or describe the other form as a variant."),
    Rule("S006", "enum values are unique",
         "No code and no value id appears twice in an enum.",
         "Remove the duplicate or give it its own code and id."),
    Rule("S007", "attributes fit the field's type",
         "`min`/`max` go with integer and decimal fields, `max_length` with text and enum_chars, `bitfield` "
         "with hex and integer; a keyword has its word in `value`; a decimal_list parameter has `count`.",
         "Remove the attribute, change the type, or add the attribute the type needs."),
    Rule("S008", "examples decode to their expect",
         "Every example decodes to exactly the values of its `expect`: every field on the wire is named, each "
         "with a value of its type, and no other field.",
         "Correct `expect` (the message shows the decoded value), or the field's type if the manual means another."),
    Rule("S009", "examples decode with their variant",
         "An example's `variant` exists and is the layout the line decodes with (none: the main layout).",
         "Name the variant the line matches, or correct the variant's fields."),
    Rule("S010", "files are named after their id",
         "An enum lives in <id>.yaml, a sentence in <id in lower case>.yaml.",
         "Rename the file (or the id)."),
    Rule("S011", "replies exist",
         "Every sentence a command's `replies` names is defined.",
         "Correct the id, or add the reply sentence."),
    Rule("S012", "bits fit their bitfield",
         "Each named run of bits (high:low) lies within the bitfield's width, and its values fit the run.",
         "Correct the bits or the width (write high:low), or the value."),
    Rule("S013", "type names are distinct",
         "Enums, bitfields, tables and sentence layouts become types of one namespace: their names differ.",
         "Rename the enum, bitfield or table (e.g. <id>_code)."),
    Rule("S014", "names the generated code keeps",
         "A field or group id is not a name the generated code uses itself (envelope attributes, methods, "
         "Python keywords, a group's <id>_count).",
         "Choose another id."),
    Rule("S015", "text commands are words",
         "The fields of a text command (framing: text) are single words: no group, no latitude or longitude.",
         "Describe the command with single-word fields."),
    Rule("S016", "generated names do not clash",
         "The names the emitters build from ids (C identifiers, Rust types, the tool's command names) are "
         "not shared by two things nor taken from a runtime.",
         "Rename one of the two things the message names."),
    Rule("S017", "generic examples are real lines",
         "A `generic` entry of manuals.yaml has an example that starts with its message and has a right checksum.",
         "Correct the example (its checksum is the XOR of the bytes between $ and *)."),
    Rule("S018", "enum_chars take one-character codes",
         "An enum_chars field's enum has only one-character codes.",
         "Use an enum of one-character codes, or type the field `enum`."),
    Rule("S019", "group fields are required",
         "No field inside a group is optional.",
         "Remove `optional`/`since` from the group's fields."),
    Rule("S020", "groups hold no keyword",
         "No group holds a keyword field (a keyword picks the layout).",
         "Move the keyword out of the group."),
    Rule("S021", "optional fields follow the NMEA versions",
         "Trailing fields with `since` come in the order of the versions that added them.",
         "Reorder the fields, or correct `since`."),
    Rule("S022", "a group's min is at most its max",
         "A group's `min` does not exceed its `max`.",
         "Swap or correct the bounds."),
    Rule("S023", "one group per layout",
         "A layout has at most one group.",
         "Merge the groups, or describe the other form as a variant."),
    Rule("S024", "enum codes fit a field",
         "An enum code holds none of , * $ ! and neither starts nor ends with a space.",
         "Correct the code."),
    Rule("S025", "cli shortcuts belong to commands",
         "A value with `cli` belongs to an enum that a command field takes.",
         "Remove `cli`, or use the enum in a command."),
    Rule("S026", "cli shortcuts are unique",
         "No `cli` shortcut appears twice in an enum.",
         "Give one of the values another shortcut."),
    Rule("S027", "cli shortcuts are not command names",
         "A `cli` shortcut's first word is not the name of a command of the vendors that take the enum.",
         "Choose another shortcut."),
    Rule("S028", "a field's min is at most its max",
         "A field's `min` does not exceed its `max`.",
         "Swap or correct the bounds."),
    Rule("S029", "bounds fit a number",
         "`min` and `max` fit the 18 digits a number holds in every runtime.",
         "Use fewer digits."),
    Rule("S030", "a damaged example says so",
         "An example whose checksum fails has `corrected` and `reason`, or `unrecoverable`.",
         "Add `corrected` (the line with the right checksum) and `reason`, or `unrecoverable: <why>`."),
    Rule("S031", "a correction corrects",
         "An example's `corrected` is not its `raw` text (a right checksum needs no correction).",
         "Remove `corrected` and `reason`."),
    Rule("S032", "a correction's checksum is right",
         "The checksum of `corrected` is right.",
         "Write the computed checksum the message names."),
    Rule("S033", "examples decode as their sentence",
         "An example decodes, and as the sentence whose file holds it.",
         "Correct the line, move the example to the sentence it is, or fix the layout (the message has the "
         "decoder's error)."),
    Rule("S034", "a standard id is its formatter",
         "A standard sentence's id is its 3-character formatter, or 4 characters for a formatter some receivers "
         "add to the standard ones (Unicore's GGAH).",
         "Use the formatter as id; a proprietary sentence goes to proprietary/ with `address`."),
    Rule("S035", "standard sentences are plain",
         "A standard sentence has no `kind`, `vendor`, `replies` or `framing`.",
         "Remove the key, or make it a proprietary sentence."),
    Rule("S036", "standard sentences have a domain",
         "A standard sentence has a `domain` (the docs index groups by it).",
         "Add `domain:` (gnss, navigation, heading, environment, ais_safety, alarms or system)."),
    Rule("S037", "proprietary sentences start with $",
         "A proprietary sentence has no `start` and no `domain`.",
         "Remove the key."),
    Rule("S038", "a text command's address is a word",
         "A text command's address (its command word) is letters only.",
         "Correct the address."),
    Rule("S039", "text command keywords are upper case",
         "A keyword of a text command is written in upper case (lines match it ignoring case).",
         "Write the word in upper case."),
    Rule("S040", "only commands have replies",
         "Only a sentence of `kind: command` lists `replies`.",
         "Set `kind: command`, or remove `replies`."),
    Rule("S041", "a reply's `when` fits the reply",
         "Each field a command's `when` names is a field of the reply, of a type a program compares exactly "
         "(integer, enum, text, char), with a value of that type.",
         "Correct the field id or the value."),
    Rule("S042", "a reply's `outcome` fits its layout",
         "An `outcome` names a field of each layout it applies to, of a comparable type, with values of that type.",
         "Correct the field id or the values."),
    Rule("S043", "only replies have an outcome",
         "Only a sentence of `kind: reply` says `outcome`.",
         "Set `kind: reply`, or remove `outcome`."),
    Rule("S044", "bits do not overlap",
         "No bit of a bitfield belongs to two named runs.",
         "Correct the bits."),
    Rule("S045", "generic messages stay generic",
         "A `generic` entry of manuals.yaml is a message no layout of the spec reads.",
         "Remove the entry: the spec now describes the message."),
    Rule("S046", "overlay extensions extend a sentence",
         "A file of an overlay's extensions/ names (`extends`) a sentence of the spec.",
         "Correct the id, or write the sentence in the overlay's standard/ or proprietary/."),
    Rule("S047", "fix facts fit their fields",
         "A field's `fix` names a fact of spec/fix.yaml that a field of its type, unit and enum can carry (the "
         "fact's `types`, `units`, `enums` or `from`), outside a group for an epoch fact and inside one for a "
         "satellite fact, and each epoch fact at most once per layout; a fact's `from` maps value ids of existing "
         "enums to its `values`.",
         "Correct the field's `fix` or the fact in spec/fix.yaml (add the unit with its factor, the enum to "
         "`enums` or `from`), or leave the field out of the fix."),
    Rule("S048", "fix examples are sentences that carry facts",
         "Every line of an example of spec/fix.yaml has a right checksum and decodes as a layout with fields that "
         "carry facts of a fix.",
         "Correct the line (the message has the decoder's error or the computed checksum), or tag the fields "
         "with `fix:`."),
    Rule("S049", "like names a standard sentence",
         "A sentence's `like` names a standard sentence of the spec that has fields of its own (not a `like` "
         "itself): its main layout is copied, without the facts of a fix.",
         "Correct the id, or give the sentence its own `fields`."),
    Rule("A001", "a fixed payload has its documented length",
         "The fields of a message (spec/ais/messages) with no variable or optional item take the bits its `length` "
         "says; a message with one has no `length`.",
         "Correct a field's `bits` or the length, from the manual's table."),
    Rule("A002", "bit fields fit their type",
         "A field's `bits` is within its type's widths (bool 1, text a multiple of 6, numbers 1-64; a binary "
         "frame's: its type's bytes or `size`); only text and data (ch, bytes) may leave it out; `divisor`, `unit` "
         "and `special` go with numbers, `enum` with enum or an unsigned byte type (an enum of decimal codes), "
         "`dispatch` with data.",
         "Correct the width or the type, or remove the attribute."),
    Rule("A003", "special values fit their field",
         "Each special value is a raw value the field's bits hold (two's complement for int), named once; "
         "a float field's (r4, r8) is a float (`value`), finite in the field's width, whose nearest float of "
         "that width the runtimes compare bit for bit, its id neither nan nor inf.",
         "Correct the raw value or the width."),
    Rule("A004", "ids are unique in a message",
         "No two fields, groups or choices of a message share an id, across the cases of its choices too; no two "
         "fields of a group entry.",
         "Rename one of them."),
    Rule("A005", "a variable item leaves bits it can count",
         "A repeated group or a field without `bits` is followed only by required fields of fixed width; group "
         "fields have fixed widths and are required; a group's min is at most its max.",
         "Give the field a width, or move the fixed fields before the variable item."),
    Rule("A006", "optional bit fields are trailing",
         "After an optional field (present when the payload has its bits) only optional fields follow.",
         "Make the later fields optional, or the earlier one required."),
    Rule("A007", "a choice finds its selector",
         "A choice's `by` names a top-level uint, bool or enum field (its raw value unsigned) at a fixed bit offset "
         "(when it follows the choice, the cases have one width; an application's choice follows it, a required "
         "field); its `when` and `range` values are raw values of it; at most one case has neither.",
         "Correct `by`, the cases' values or their widths."),
    Rule("A008", "message types are described once",
         "Each message type number belongs to one message file, each DAC and FI in a message type to one "
         "application file (one DAC and FI may name two layouts in two message types, as DAC 1 FI 16 does).",
         "Remove the number from one of the files."),
    Rule("A009", "payload examples decode to their expect",
         "Every example's payload decodes, with its fill bits, as a type of its message, to the values its `expect` "
         "names (the decoded JSON's form: a number in a unit beside <id>_raw, special values and enum values by id).",
         "Correct the payload, the fill bits or `expect` (the message shows the decoded value)."),
    Rule("A010", "an encapsulation names fields",
         "A sentence's `encapsulates` names fields of each of its layouts as its payload, fill bits, fragment "
         "count and number, sequential message id and channel.",
         "Correct the field ids."),
    Rule("A011", "an application's carriers dispatch",
         "The message types an application (spec/ais/applications) is carried `in` have a data field whose "
         "`dispatch` names their DAC and FI fields.",
         "Correct `in`, or add `dispatch: [dac, fid]` to the carrier's data field."),
    Rule("A012", "a count names fields before it",
         "A field's `count` (latin1 or utf8 characters, or data bits; no `bits`) or a group's names a top-level "
         "unsigned field before it, or (`{ones: [...]}`) unsigned or data mask fields before it whose set bits, "
         "multiplied, give the number; a field-major group has a `count`. AIS payloads have neither (their "
         "readers count groups by the bits left).",
         "Correct the field ids, move the count's fields before the item, or give the field a fixed width."),
    Rule("A013", "a group entry's choice has cases of one width",
         "A choice in a group's entry (an AIS payload's group counted by the bits left) names by `by` a uint or "
         "enum field of the entry before it; its cases hold required fields of fixed width, every case as wide "
         "as the others, so that every entry has one width (a default case keeps the bits of a value no case "
         "names, as sent).",
         "Move the selector before the choice, pad the shorter cases with spare bits, or give the default case "
         "a data field of the cases' width."),
    Rule("B001", "a binary message has one class and id",
         "A message of spec/binary/<protocol>/messages names a class of its protocol.yaml, its id starts with that "
         "class (nav_pvt), and no other message of the protocol has its class and id; a protocol without classes "
         "(SkyTraq, SiRF) tells a message by its id and `sub_id`, and one id without a sub-id takes every frame "
         "of that id; SBF tells a block by its header's number and `revision`, each within its bits.",
         "Correct `class`, `id`, `sub_id`, `revision` or `message`."),
    Rule("B002", "binary fields are byte fields",
         "The fields of a binary layout have byte types (u1..u8, i1..i8, r4, r8, x1..x4, ch, bytes, reserved); "
         "only a bitfield word (x1, x2, x4) has `parts`, each inside the word and overlapping no other; a 64-bit "
         "integer (u8, i8) takes no divisor or base, which a float would not give back byte-exact; a fixed text, "
         "bytes or reserved field has at most 255 bytes (the C descriptor's size byte).",
         "Correct the type, or the part's `bit` and `width`; split a longer run of bytes."),
    Rule("B003", "a counted group names its count",
         "A group's `count` names an unsigned field or bitfield part that comes before the group; its `stride` "
         "(the bytes of each entry: SBF's SBLength) names a u1, u2 or u4 field before it, of a group read entry "
         "by entry that has fields.",
         "Correct `count` or `stride`, or leave `count` out (the group then takes the bytes left)."),
    Rule("B004", "layouts of one message are told apart",
         "Layout ids (message id and `variant`) are unique; two layouts that share a direction differ in their "
         "fixed length or in the value of their selector (`select: {type: 0x10}`; `version: N` is short for "
         "`select: {version: N}`), layouts of one direction select by the same field, and a selector names a u1 "
         "field at a fixed offset.",
         "Give one layout a `variant`, a `select` (or `version`), or correct its fields."),
    Rule("B005", "binary messages name their protocol's documents",
         "Each of a message's `documents` is one of its protocol.yaml's documents.",
         "Correct the id, or add the document to protocol.yaml."),
    Rule("B006", "replies name layouts",
         "A layout's `replies` name layouts of binary messages (ack_ack, nav_pvt); every poll names the layout "
         "that answers it; an acknowledgement's `acknowledges` names its u1 fields of the answered class and id.",
         "Correct or add `replies`, or correct `acknowledges`."),
    Rule("B007", "binary examples decode to their expect",
         "Every example is a whole frame of its message (sync, length and checksum right) that the reference "
         "decoder reads, as the layout its length and version pick, to the values its `expect` names (the decoded "
         "JSON's form).",
         "Correct the frame or `expect` (the message shows the decoded value)."),
    Rule("B008", "configuration keys are unique and sized by their id",
         "In a configuration database (spec/binary/<protocol>/config_keys.yaml) no two keys share an id or a name "
         "(an item's aliases included), a group (name and id) is listed once, and each key id's bits 28-30 give "
         "its type's size (1 L, 2 one byte, 3 two, 4 four, 5 eight), its bits 16-23 its group's id, and its "
         "reserved bits (12-15, 24-27, 31) are 0.",
         "Correct the id, the type or the group, or make a second name of one key an `alias`."),
    Rule("B009", "configuration keys' enums, scales and documents resolve",
         "A key's `enum` is one of the file's enums, on an E or U type, whose values fit the type; a `scale` is on "
         "a number type (U, I, R) and is 1 over a whole number; a group's `documents` are its protocol.yaml's.",
         "Correct the enum, the scale or the document id."),
    Rule("B010", "a group in a group's entry is counted by the entry",
         "A group may end the entry of a group of a `stride` (SBF's Type-2 sub-blocks after each Type-1): it is "
         "the entry's last item, its `count` names an unsigned field of that entry, its `stride` an unsigned field "
         "(u1, u2, u4) before the outer group; its own entries hold fields only (one level).",
         "Move the group to the end of the entry, correct `count` or `stride`, or give the outer group a stride."),
)}


def rule(rule_id: str) -> Rule:
    """The rule of `rule_id`; reporting an id the table does not have is a bug of the generator."""
    try:
        return RULES[rule_id]
    except KeyError:
        raise ValueError(f"rule {rule_id!r} is not in generator/rules.py") from None


def as_text() -> str:
    def wrapped(label: str, text: str) -> str:
        return textwrap.fill(text, 100, initial_indent=f"       {label:8}", subsequent_indent=" " * 15) + "\n"

    return "".join(f"{r.id:7}{r.title}\n" + wrapped("checks:", r.checks) + wrapped("fix:", r.fix) for r in RULES.values())


def as_markdown() -> str:
    def cell(text: str) -> str:
        return text.replace("|", "\\|")

    lines = ["# Spec rules", "",
             "Every error of `nmeaspec-gen validate` ends with the id of the rule it breaks, e.g.",
             "`spec/standard/gga.yaml:12: fields[3].enum: field quality refers to unknown enum 'x' [S002]`.",
             "This page is `nmeaspec-gen rules --markdown` (generator/rules.py).", "",
             "| id | rule | what it checks | how to fix |", "| --- | --- | --- | --- |"]
    lines += [f"| {r.id} | {cell(r.title)} | {cell(r.checks)} | {cell(r.fix)} |" for r in RULES.values()]
    return "\n".join(lines) + "\n"
