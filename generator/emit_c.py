"""C emitter: one nmea.h / nmea.c pair (the hand-written runtime of runtime/c, then per
sentence layout a struct and a descriptor table that the runtime's one reader, writer and JSON
form interpret, plus a fast reader and writer for the sentences on the fast path), the nmea-c
tool and the example tests.

Everything the templates print is worked out here: the descriptor rows, the fast path's call for
each field (its reader and arguments from the field-type registry), the value ranges, with the C
names of names_c.py; the templates only loop and print.
"""

from __future__ import annotations

import re
import textwrap

import jinja2

from . import emit_vectors, pairing
from .emit import CONTRACT, RUNTIME, RUNTIME_C, char_literal, header, runtime_file, runtime_source
from .emit_c_ais import carries_ais
from .emit_c_ubx import carries_ubx
from .model import QUERY, BitfieldDef, EnumDef, Field, Group, Layout, Sentence, Spec, TableDef
from .names_c import (bits_const, bits_function, bits_mask, entry_type, enum_const, enum_def, enum_type,
                      group_accessor, layout_const, layout_type, member, parameter_macro, table_count, table_name)
from .numbers import fixed_point, fmt_num

def runtime_header(name: str) -> str:
    """runtime/c/<name> as nmea.h holds it: the generated framing table's header (framings.h,
    generator/emit_framing.py) pasted in place of its #include."""
    text = (RUNTIME_C / name).read_text(encoding="utf-8")
    return text.replace('#include "framings.h"\n', (RUNTIME_C / "framings.h").read_text(encoding="utf-8"))


MAX_LINE = CONTRACT["limits"]["max_line"]  # NMEA_MAX_LINE
MAX_DIGITS = CONTRACT["limits"]["max_digits"]  # NMEA_MAX_DIGITS
MAX_PROBLEMS = CONTRACT["limits"]["max_problems"]  # NMEA_MAX_PROBLEMS


_PLAIN_C_TEXT = re.compile(r'[\x20\x21\x23-\x3E\x40-\x5B\x5D-\x7E]*')  # printable ASCII but " ? \\: as it stands


def c_str(text: str) -> str:
    """A C string literal of `text` (UTF-8 bytes; '?' escaped so that no trigraph can form)."""
    if _PLAIN_C_TEXT.fullmatch(text):
        return f'"{text}"'
    out = ['"']
    for byte in text.encode("utf-8"):
        ch = chr(byte)
        if ch in '"\\?':
            out.append("\\" + ch)
        elif 0x20 <= byte <= 0x7E:
            out.append(ch)
        else:
            out.append(f"\\{byte:03o}")
    out.append('"')
    return "".join(out)


def error_text(text: str) -> str:
    """A text that only errors use (a field's id, what it takes) as nmea.c writes it: in
    ERROR_TEXT, which -DNMEA_TERSE_ERRORS makes NULL (runtime/c/base.c)."""
    return f"ERROR_TEXT({c_str(text)})"


def c_comment(text: str) -> str:
    """Text that is safe inside a /* */ comment."""
    return text.replace("*/", "* /").replace("/*", "/ *").replace("??", "? ?")


def doc_lines(text: str, width: int = 92) -> list[str]:
    return textwrap.wrap(c_comment(" ".join(text.split())), width) or [""]


# ------------------------------------------------------------------------------------------------
# Value ranges


def _range_word(value: float) -> str:
    text = fmt_num(value)
    return text.replace("-", "minus_").replace(".", "p")


def range_init(low: float | None, high: float | None) -> str:
    """The initializer of an nmea_range."""
    parts = []
    if low is not None:
        digits, scale = fixed_point(low)  # (at most 18 digits: checks.py, S007)
        parts += [".has_min = true", f".min = {digits}"] + ([f".min_scale = {scale}"] if scale else [])
    if high is not None:
        digits, scale = fixed_point(high)
        parts += [".has_max = true", f".max = {digits}"] + ([f".max_scale = {scale}"] if scale else [])
    return "{" + ", ".join(parts) + "}" if parts else "{0}"


class Ranges:
    """The distinct value ranges of the spec, each a named static const nmea_range."""

    def __init__(self) -> None:
        self.by_bounds: dict[tuple, dict] = {}

    def ref(self, f: Field) -> str:
        if f.min is None and f.max is None:
            return "NULL"
        key = (f.min, f.max)
        if key not in self.by_bounds:
            if f.min is not None and f.max is not None:
                name = f"range_{_range_word(f.min)}_to_{_range_word(f.max)}"
            elif f.min is not None:
                name = f"range_from_{_range_word(f.min)}"
            else:
                name = f"range_up_to_{_range_word(f.max)}"  # type: ignore[arg-type]
            shown = f"{fmt_num(f.min) if f.min is not None else ''}..{fmt_num(f.max) if f.max is not None else ''}"
            self.by_bounds[key] = {"name": name, "init": range_init(f.min, f.max), "shown": shown}
        return "&" + self.by_bounds[key]["name"]

    @property
    def all(self) -> list[dict]:
        return sorted(self.by_bounds.values(), key=lambda r: r["name"])


# ------------------------------------------------------------------------------------------------
# Per-field calls




def c_arg(word: str, f: Field, ranges: Ranges) -> str:
    """A word of the registry's argument vocabulary (field_types.py) as a C argument for `f`."""
    if word == "range":
        return ranges.ref(f)
    if word == "word":
        return c_str(f.value or "")
    if word == "table":
        assert f.enum is not None
        return f"&{enum_def(f.enum)}"
    assert word == "max_length", word
    return str(f.max_length or 0)


class FieldArgs:
    """What the fields of the generated layouts take besides their type, kind by kind, each once:
    the tables layout_field indexes (FIELD_RANGES, FIELD_ENUMS, FIELD_WORDS and FIELD_EXPECTED of
    runtime/c/layout.c), so that a subset holds only what its own fields take."""

    def __init__(self, ranges: Ranges) -> None:
        self.ranges = ranges
        self.kinds: dict[str, dict[str, int]] = {"range": {}, "table": {}, "word": {}, "expected": {}}

    def _index(self, kind: str, ref: str) -> int:
        return self.kinds[kind].setdefault(ref, len(self.kinds[kind]))

    def arg(self, f: Field) -> str:
        """The layout_field.arg of `f`: its index in the table of its kind, or NO_ARG."""
        if "hemisphere" in f.field_type.args:
            return str(self.expected(f.field_type.hemisphere_expected))
        kind = next((word for word in f.field_type.args if word in ("range", "table", "word")), None)
        ref = c_arg(kind, f, self.ranges) if kind else "NULL"
        return "NO_ARG" if ref == "NULL" else str(self._index(kind, ref))  # NULL: a number of any value

    def expected(self, text: str) -> int:
        """The index of an error's `text` (what a field takes) in FIELD_EXPECTED."""
        return self._index("expected", c_str(text))

    def tables(self) -> list[dict]:
        """The tables as nmea.c defines them: name, element type and entries in index order, and
        whether only errors read them (-DNMEA_TERSE_ERRORS leaves those out)."""
        return [{"name": name, "type": c_type, "entries": list(self.kinds[kind]), "errors": kind == "expected"}
                for kind, name, c_type in (("range", "FIELD_RANGES", "nmea_range"),
                                           ("table", "FIELD_ENUMS", "nmea_enum_def"), ("word", "FIELD_WORDS", "char"),
                                           ("expected", "FIELD_EXPECTED", "char"))]


def field_init(f: Field, owner: str | None, args: FieldArgs) -> str:
    """The layout_field initializer of `f`, a member of struct `owner` (None: stored at offset 0,
    the value of a single-field group); its last members, the texts of its errors, in FIELD_NAMES,
    which -DNMEA_TERSE_ERRORS leaves out."""
    offset = f"offsetof({owner}, {member(f.id)})" if owner and f.field_type.c_type else "0"
    assert (f.max_length or 0) < 256, f"{f.id}: layout_field.max_length is a byte"
    return (f"{{{offset}, {args.arg(f)}, FIELD_{f.type.upper()}, {f.max_length or 0}, "
            f"FIELD_NAMES({args.expected(f.expected)}, {c_str(f.id)})}}")


def fast_call(f: Field, target: str, ranges: Ranges) -> str:
    """The fast path's call that reads field `f` into `target` from the line at `p` (see
    fast_frame in the runtime): read_call without the names errors need (a coordinate's reader
    knows its hemispheres)."""
    t = f.field_type
    args = ["&p"] + ([f"&{target}"] if t.c_type else [])
    args += [c_arg(word, f, ranges) for word in t.args if word != "hemisphere"]
    return f"fast_{t.c_fast}({', '.join(args)})"


def fast_put_call(f: Field, target: str) -> str:
    """The fast path's call that writes field `f` (its comma and text) with its fast_writer `w`:
    false when the general writer must write the sentence (a keyword's or literal's length is
    given with it)."""
    t = f.field_type
    word = f.value or ""
    rendered = {"value": target, "&value": f"&{target}", "word": f"{c_str(word)}, {len(word.encode())}",
                "table": f"&{enum_def(f.enum)}" if f.enum else ""}
    return f"fast_put_{t.c_put}(&w, {', '.join(rendered[a] for a in t.c_put_args)})"


def member_doc(f: Field) -> list[str]:
    unit = f" [{f.unit}]" if f.unit else ""
    fmt = f" ({f.format})" if f.format else ""
    since = f" (NMEA {f.since}, optional)" if f.since else (" (optional)" if f.optional else "")
    t = f.field_type
    extra = t.c_doc.format(value=f.value, enum_type=enum_type(f.enum) if f.enum else "",
                           enum_table=enum_def(f.enum) if f.enum else "")
    if f.bitfield is not None:
        extra += f" Bits: nmea_{f.bitfield.id}_<bits>(value) (bitfield {f.bitfield.id})."
    doc = f.doc.strip()
    doc += "" if doc.endswith((".", "!", "?", ")")) or not doc else "."
    return doc_lines(f"{f.name}{unit}{fmt}{since}: {doc}{extra} Empty: {t.c_empty}.")


# ------------------------------------------------------------------------------------------------
# Layout views


def field_view(f: Field, base: str, args: FieldArgs, owner: str | None) -> dict:
    """A field of struct `owner` (None: the value of a single-field group), read and written on
    the fast path through `base` ("s->", "e->" or the entry itself)."""
    target = f"{base}{member(f.id)}" if base.endswith(("->", ".")) else base
    stored = f.field_type.c_type is not None
    return {
        "field": f,
        "member": member(f.id) if stored else None,
        "type": f.field_type.c_type,
        "doc": member_doc(f) if stored else [],
        "init": field_init(f, owner, args),
        "takes": c_comment(f.expected),
        "fast": fast_call(f, target, args.ranges),
        "fast_put": fast_put_call(f, target),
    }


def optional_count_expr(widths: list[int]) -> str:
    """How many optional fields are present when `optional` wire fields follow the required
    ones (a field of two wire fields needs both)."""
    if all(w == 1 for w in widths):
        return "(uint8_t)optional"
    expr = "0"
    total = 0
    steps = []
    for n, w in enumerate(widths, 1):
        total += w
        steps.append((total, n))
    for total, n in steps:
        expr = f"optional >= {total} ? {n} : {expr}"
    return f"(uint8_t)({expr})"


def layout_view(sentence: Sentence, layout: Layout, args: FieldArgs) -> dict:
    snake = sentence.layout_snake(layout)
    group = layout.group
    kind = sentence.wire_kind
    before: list[dict] = []
    after: list[dict] = []
    optional: list[dict] = []
    seen_group = False
    for item in layout.items:  # (checks.py keeps ids off the members every struct has: S014)
        if isinstance(item, Group):
            seen_group = True
            continue
        view = field_view(item, "s->", args, f"nmea_{snake}")
        if item.is_optional:
            optional.append(view)
        elif seen_group:
            after.append(view)
        else:
            before.append(view)
    # An optional field (a keyword too) is written and shown when it was on the wire.
    for n, view in enumerate(optional, 1):
        view["index"] = n
        view["when"] = f"s->optional_count >= {n}"
    group_view = None
    if group is not None:
        single = group.single
        etype = entry_type(sentence, layout, group)
        if single:
            fields = [field_view(group.fields[0], "value", args, None)]
        else:
            fields = [field_view(f, "e->", args, etype) for f in group.fields]
        stored = [v for v in fields if v["member"] is not None]
        value_type = (group.fields[0].field_type.c_type if single else etype) if stored else None
        name = member(group.id)
        # The entries of a group that holds values stay on the wire (nmea_entries), read one at a
        # time by its accessor; a group of keywords only is counted.
        count = (f"{name}.count" if stored else f"{name}_count") if not group.is_fixed else None
        group_view = {
            "group": group,
            "id": c_str(group.id),
            "member": name if stored else None,
            "count": count,
            "count_member": f"{name}_count" if count and not stored else None,
            "entry_type": None if single or not stored else etype,
            "value_type": value_type,
            "accessor": group_accessor(sentence, layout, group) if stored else None,
            "single": single,
            "fields": fields,
            "stored": stored,
            "doc": doc_lines(f"{group.name}: {group.doc} " + (
                f"Always {group.max} entries" if group.is_fixed else f"{group.min} to {group.max} entries") + (
                f"; entry i is read by nmea_{snake}_{name}_at (nmea_entries)." if stored else
                "." if group.is_fixed else f"; {name}_count of them are on the wire.")),
        }
    struct = f"nmea_{snake}"
    ordered = before + after + optional
    group_init = None
    if group_view is not None:
        group_init = _designated([
            ("id", error_text(group.id)),
            ("fields", f"{snake}_group_fields"),
            ("field_count", len(group.fields)),
            ("width", group.width),
            ("min", group.min),
            ("max", group.max),
            ("single", "true" if group.single else "false"),
            ("offset", f"offsetof({struct}, {member(group.id)})" if group_view["stored"] else "NO_MEMBER"),
            ("entry_size", f"sizeof({group_view['value_type']})" if group_view["stored"] else 0),
            ("count_offset", f"offsetof({struct}, {group_view['count']})" if group_view["count"] else "NO_MEMBER"),
        ])
    head_member = {"standard": "talker", "text": "as_received"}.get(kind)
    same_as_main = sentence.same_as_main(layout) if layout.id else []
    layout_init = _designated([
        ("sentence", c_str(sentence.id)),
        ("address", c_str(sentence.address or "") if kind != "standard" else None),
        ("command", c_str((sentence.address or "").upper()) if kind == "text" else None),
        ("variant", c_str(layout.id) if layout.id else None),
        ("selector", c_str(layout.selector.upper()) if layout.selector is not None else None),  # upper_is
        ("same_as_main", f"{snake}_same_as_main" if same_as_main else None),
        ("fields", f"{snake}_fields" if ordered else "NO_FIELDS"),
        ("group", f"&{snake}_group" if group is not None else None),
        ("selector_at", layout.selector_at if layout.selector is not None else None),
        ("before", len(before) or None),
        ("after", len(after) or None),
        ("optional", len(optional) or None),
        ("fixed", layout.fixed_count or None),
        ("max_fields", layout.max_fields or None),
        ("optional_max", layout.optional_count or None),
        ("size", f"sizeof({struct})"),
        ("head", f"offsetof({struct}, {head_member})" if head_member else "NO_MEMBER"),
        ("optional_count", f"offsetof({struct}, optional_count)" if optional else "NO_MEMBER"),
        ("checksum", f"offsetof({struct}, checksum)" if kind != "text" else "NO_MEMBER"),
        ("kind", f"LAYOUT_{kind.upper()}"),
        ("start", f"'{sentence.start}'"),
    ])
    example = sentence.example_of(layout)
    # The fields read before the group (all of them when there is none) and after it.
    head = before + ([] if group_view else optional)
    tail = (after + optional) if group_view else []
    return {
        "sentence": sentence,
        "layout": layout,
        "kind": kind,
        "name": snake,
        "type": layout_type(sentence, layout),
        "const": layout_const(sentence, layout),
        "id": c_str(sentence.id),
        "start": sentence.start,
        "fast": kind != "text" and sentence.fast_path,
        "address": c_str(sentence.address or ""),
        "example": c_comment(example.line) if example and example.line else None,
        "example_manual": example.manual if example else None,
        "doc": doc_lines(layout.doc if layout.id else sentence.doc),
        "title": c_comment(f"{sentence.id}{' (' + layout.name + ')' if layout.id else ''}: "
                           f"{sentence.name if layout.id else layout.name}"),
        "before": before,
        "group": group_view,
        "after": after,
        "optional": optional,
        "fields": ordered,
        "init": layout_init,
        "same_as_main": same_as_main,
        "group_init": group_init,
        "head_fast": _conditions(head, "fast"),
        "tail_fast": _conditions(tail, "fast"),
        "head_fast_puts": _conditions(head, "fast_put"),
        "tail_fast_puts": _conditions(tail, "fast_put"),
        "optional_names": ", ".join(v["field"].id for v in optional),
        "optional_count": optional_count_expr([v["field"].wire_width for v in optional]),
        "fixed": layout.fixed_count,
        "max_fields": layout.max_fields,
        "optional_max": layout.optional_count,
        "source": sentence.source,
        "replies": [layout_const(r, lay) for r in sentence.replies for lay in r.layouts],
    }


def fix_views(spec: Spec, views: list[dict]) -> list[dict]:
    """The fix table (spec/fix.yaml): per layout with facts, its fields that carry them, each a
    pointer into the layout's field descriptors (runtime/c/fixes.c reads them with read_with's
    descriptors), the factor to the fact's unit and, for an enum mapped by the fact's `from`, the
    fact's value of each of the enum's codes."""
    out = []
    for v in views:
        layout = v["layout"]
        members = [f["field"] for f in v["fields"]]
        group_fields = layout.group.fields if layout.group is not None else []
        fields = []
        for fix in layout.fix_fields:
            f, fact = fix.field, fix.fact
            where = (f"&{v['name']}_group_fields[{group_fields.index(f)}]" if fix.group is not None
                     else f"&{v['name']}_fields[{members.index(f)}]")
            mapping = fact.values_of(f)
            codes = f.enum.values if f.enum is not None and mapping is not None else []
            values = f"{v['name']}_{f.id}_fix_values" if codes else None
            fields.append({
                "init": _braced([f"NMEA_FACT_{fact.id.upper()}", "true" if fix.group else "false", where,
                                            repr(float(fact.scale(f))), values or "NULL"]),
                "table": values,
                "value_list": [c_str(mapping[c.id]) if mapping and c.id in mapping else "NULL" for c in codes],
            })
        if fields:
            entry = v["group"]["value_type"] if v["group"] and any(fix.group for fix in layout.fix_fields) else None
            out.append({"name": v["name"], "const": v["const"], "members": fields, "entry": entry})
    return out


def _braced(members: list[str]) -> str:
    """A struct's initializer on one line: {a, b, c}."""
    return "{" + ", ".join(members) + "}"


def _designated(members: list[tuple[str, object]], width: int = 110) -> list[str]:
    """The lines of a designated initializer's members (those that are not None), each line at
    most `width` characters after its indentation."""
    lines: list[str] = []
    for name, value in members:
        if value is None:
            continue
        item = f".{name} = {value},"
        if lines and len(lines[-1]) + 1 + len(item) <= width:
            lines[-1] += " " + item
        else:
            lines.append(item)
    return lines


def _member_of(sentence: Sentence, layout: Layout, f: Field) -> str:
    return f"s->as.{sentence.layout_snake(layout)}.{member(f.id)}"


def reply_test(condition: pairing.Condition, target: str) -> str:
    """The C test that the member `target` holds a reply's `when` or `outcome` value."""
    f, value = condition.field, condition.value
    pairing = f.field_type.pairing
    if pairing == "number":
        return f"integer_is({target}, {int(value)})"
    if pairing == "code":
        assert f.enum is not None
        return f"({target}.present && {target}.value == {enum_const(f.enum, str(value))})"
    if pairing == "string":
        return f"text_is({target}, {c_str(value)})"
    assert pairing == "character", f.type
    return f"{target} == {char_literal(value)}"


def reply_pairings(spec: Spec) -> list[dict]:
    """Per command layout, the test that a parsed sentence `s` answers it (nmea_reply_to)."""
    out = []
    for command in spec.proprietary:
        tests = [" && ".join([f"s->id == {layout_const(p.reply, p.layout)}",
                              *(reply_test(c, _member_of(p.reply, p.layout, c.field)) for c in p.conditions)])
                 for p in pairing.pairings(command)]
        if len(tests) > 1:
            tests = [f"({t})" if " && " in t else t for t in tests]
        if tests:
            out += [{"const": layout_const(command, layout), "tests": tests} for layout in command.layouts]
    return out


def reply_judgements(spec: Spec) -> list[dict]:
    """Per reply layout that does not always report success, what it reports (reply_outcome)."""
    out = []
    for sentence in spec.proprietary:
        for layout, j in pairing.judged(sentence):
            if j.fixed is not None:
                expr = "NMEA_REPLY_ERROR"
            else:
                assert j.field is not None
                target = _member_of(sentence, layout, j.field)
                ok = pairing.any_of([reply_test(pairing.Condition(j.field, v), target) for v in j.ok])
                expr = f"{ok} ? NMEA_REPLY_OK : NMEA_REPLY_ERROR"
            out.append({"const": layout_const(sentence, layout), "expr": expr})
    return out


def _conditions(views: list[dict], call: str) -> list[str]:
    """The failure conditions of the fast path's reading or writing of fields (its `fast` or
    `fast_put` calls), for an `if (a || b ...) return false;` chain."""
    conds = [_read_condition(v, call) for v in views]
    if len(conds) == 1 and conds[0].startswith("("):
        conds[0] = conds[0][1:-1]
    return conds


def _read_condition(view: dict, call: str) -> str:
    """The failure condition of reading one field, in the `if (... || ...) return false;` chain."""
    if view.get("when"):
        return f"({view['when']} && !{view[call]})"
    return "!" + view[call]


def enum_texts(enums: list[EnumDef]) -> dict[str, str]:
    """Each text of the lookup tables (their ids, codes and code ids) once, as the name of a char
    array of its own: a firmware then links the texts of the tables it uses only (-fdata-sections
    --gc-sections keep or drop each array), each once however many tables have it. (As string
    literals they would share one section, which --gc-sections keeps whole with every table's
    texts in it.)"""
    names: dict[str, str] = {}
    for e in enums:
        for text in [e.id, *(text for v in e.values for text in (v.code, v.id))]:
            names.setdefault(text, f"enum_text_{len(names)}")
    return names


def enum_text_refs(names: dict[str, str]) -> dict[str, str]:
    """The C expression of each text of enum_texts: its array, or the end of a longer text's
    ("valid" is the tail of "invalid": enum_text_7 + 2), whose array then holds both. The
    shortest such text is taken, then its own (a firmware links few bytes for a short code)."""
    parent: dict[str, str | None] = dict.fromkeys(names)
    claimed: set[str] = set()
    for longer in sorted(names, key=len):  # each text's parent: the first longer text that ends with it
        for start in range(1, len(longer) + 1):
            tail = longer[start:]
            if tail in parent and tail not in claimed:
                parent[tail] = longer
                claimed.add(tail)
    refs = {}
    for text, name in names.items():
        root = text
        while (up := parent[root]) is not None:
            root = up
        refs[text] = f"{names[root]} + {len(root.encode()) - len(text.encode())}" if root != text else name
    return refs


def enum_view(e: EnumDef, texts: dict[str, str]) -> dict:
    return {
        "enum": e,
        "type": enum_type(e),
        "def": enum_def(e),
        "codes": f"{e.id}_codes",
        "name": texts[e.id],
        "doc": doc_lines(f"{e.id}: {e.name}. {e.doc}"),
        "class": f"NMEA_CODES_{e.code_class.upper()}",
        "values": [{
            "const": enum_const(e, v.id),
            "code": texts[v.code],
            "id": texts[v.id],
            "comment": f"{c_str(v.code)}: {c_str(v.id)}".replace("*/", "*\\/"),  # quoted: a renamed copy keeps them
            "doc": doc_lines(f'"{v.code}": {v.doc}' + (f" (NMEA {v.since})" if v.since else ""), 88),
        } for v in e.values],
    }


def json_max(spec: Spec, views: list[dict]) -> int:
    """A buffer size that holds the decode JSON (or error JSON) of any line of at most MAX_LINE
    bytes: every wire byte costs at most `per_byte` output bytes (an enum_chars code becomes its
    quoted id), every wire field at most `per_field` more (its key and punctuation). Lenient
    decoding adds up to MAX_PROBLEMS problems: their texts (wire bytes shown twice, the second
    time escaped twice: 6 bytes each at most) and per problem its name, what was expected and
    punctuation."""
    longest_id = max([len(v.id) for e in spec.enums for v in e.values] + [0])
    per_byte = max(8, longest_id + 4)
    all_fields = [f for s in spec.sentences for lay in s.layouts for f in lay.all_fields]
    keys = [len(f.id) for f in all_fields]
    per_field = max(keys + [0]) + 64
    fields = max([v["max_fields"] for v in views] + [0]) + 2
    groups = [len(item.id) for s in spec.sentences for lay in s.layouts for item in lay.items
              if isinstance(item, Group)]
    expected = max([len(c_str(f.expected)) for f in all_fields] + [0])
    per_problem = max(groups + [0]) + 8 + per_field + 2 * expected + 64
    return MAX_LINE * (1 + per_byte + 6) + fields * per_field + MAX_PROBLEMS * per_problem


def longest_line(spec: Spec) -> int:
    """NMEA_MAX_LINE's default: the longest line a layout of the spec can have (its start, address,
    every field at the longest text its reader takes, each entry of its group, and the checksum),
    at most the contract's MAX_LINE, which is also the bound of a layout with a field of no bound
    and of a text command (its words may be spaced out)."""
    longest = 0
    for s in spec.sentences:
        if s.wire_kind == "text":
            return MAX_LINE
        address = len(s.address) if s.is_proprietary else 5  # a talker and the sentence id
        for lay in s.layouts:
            texts: list[int | None] = []
            for item in lay.items:
                for f in item.fields * item.max if isinstance(item, Group) else [item]:
                    texts += f.field_type.longest_texts(f, MAX_DIGITS)
            if None in texts:
                return MAX_LINE
            longest = max(longest, 1 + address + sum(1 + t for t in texts if t is not None) + 3)  # $ … *hh
    return min(longest, MAX_LINE)




# ------------------------------------------------------------------------------------------------
# Bitfields and parameter tables


def bitfield_view(b: BitfieldDef) -> dict:
    bits = []
    for r in b.bits:
        wide = r.width > 32
        values = [{"const": bits_const(b, r, v), "value": v.value,
                   "doc": doc_lines(f"{v.value}: {v.doc}", 88)} for v in r.values]
        bits.append({
            "bits": r,
            "function": bits_function(b, r),
            "type": "uint64_t" if wide else "uint32_t",
            "mask": bits_mask(b, r),
            "mask_value": f"UINT64_C(0x{r.mask:X})",
            "max_value": f"UINT64_C(0x{r.max_value:X})",
            "low": r.low,
            "doc": doc_lines(f"Bit{'s' if r.width > 1 else ''} {r.label}: {r.doc}"),
            "values": values,
            # an enum holds values that fit an int
            "as_enum": all(v.value < 2**31 for v in r.values),
        })
    return {
        "bitfield": b,
        "doc": doc_lines(f"{b.id}: {b.name} ({b.width} bits). {b.doc} Bits the spec does not name are "
                         "reserved; no accessor refuses them."),
        "bits": bits,
    }


ENCODINGS = {"hex": "NMEA_PARAM_HEX", "decimal": "NMEA_PARAM_DECIMAL", "decimal_list": "NMEA_PARAM_DECIMAL_LIST",
             "text": "NMEA_PARAM_TEXT"}


def _opt_str(value: object) -> str:
    return "NULL" if value is None else c_str(str(value))


def table_view(t: TableDef) -> dict:
    params = []
    for i, p in enumerate(t.parameters):  # (size, count and max_length fit a byte: the schema)
        init = ", ".join([
            str(p.number), c_str(p.id), c_str(p.name), ENCODINGS[p.encoding], str(p.size or 0), str(p.count or 0),
            range_init(p.min, p.max), str(p.max_length or 0), _opt_str(p.default), _opt_str(p.unit),
            f"&{enum_def(p.enum)}" if p.enum else "NULL", _opt_str(p.bitfield.id if p.bitfield else None),
        ])
        params.append({
            "parameter": p,
            "init": "{" + init + "}",
            "macro": parameter_macro(t, p),
            "index": i,
            "doc": c_comment(f"{p.number}: {p.name}" + (f" [{p.unit}]" if p.unit else "")),
        })
    return {
        "table": t,
        "name": table_name(t),
        "count": table_count(t),
        "doc": doc_lines(f"{t.id}: {t.name}. {t.doc}"),
        "parameters": params,
    }


def vector_view(record: dict) -> dict:
    def lit(key: str) -> str:
        value = record.get(key)
        if value is None:
            return "NULL"
        assert len(value.encode("utf-8")) < 4000, "string literal too long for ISO C99"
        return c_str(value)

    return {
        "what": c_str(f"{record['sentence']} {record['manual_id']}: {record.get('where') or ''}"),
        "line": lit("line"), "decode": lit("decode"), "decode_values": lit("decode_values"),
        "raw": c_str(record["raw"]), "raw_decode": lit("raw_decode"),
    }


def _dispatch(spec: Spec, views: list[dict]) -> dict[str, list[dict]]:
    """The tables nmea_parse looks a line up in, each sorted by its key (bytewise): standard
    sentences by sentence id, proprietary `$` sentences by address, text commands by their
    command word in upper case. Each entry lists its layouts in parse order."""
    const = {(v["sentence"].id, v["layout"].id): v["const"] for v in views}

    def entry(key: str, suffix: str | None, pairs: list) -> dict:
        code = int.from_bytes(key.encode(), "big") if suffix else 0
        return {"key": c_str(key), "len": len(key.encode()), "suffix": c_str(suffix) if suffix else "NULL",
                "sort": key.encode(), "ids": [const[(s.id, lay.id)] for s, lay in pairs], "code": f"0x{code:06X}"}

    def standard_like(address: str) -> bool:  # what is_standard_address accepts
        return len(address) in (5, 6) and address[0] != "P"

    standard = [entry(s.id, s.id, [(s, lay) for lay in s.layouts]) for s in spec.standard if s.start == "$"]
    encapsulated = [entry(s.id, s.id, [(s, lay) for lay in s.layouts]) for s in spec.standard if s.start == "!"]
    addresses = sorted({s.address for s in spec.proprietary if s.framing == "sentence" and s.address})
    proprietary = [entry(a, None, spec.by_address(a)) for a in addresses if not standard_like(a)]
    # Proprietary addresses that look like a standard one ($GPSGG) come before the standard
    # sentences; keeping them apart spares a standard line the search of every proprietary address.
    talker_like = [entry(a, None, spec.by_address(a)) for a in addresses if standard_like(a)]
    words = sorted({s.address.upper() for s in spec.proprietary if s.framing == "text" and s.address})
    text = [entry(w, None, spec.text_command(w)) for w in words]
    return {name: sorted(table, key=lambda e: e["sort"])
            for name, table in (("standard", standard), ("encapsulated", encapsulated), ("talker_like", talker_like),
                                ("proprietary", proprietary), ("text", text))}


def perfect_hash(codes: list[int]) -> dict:
    """A multiplier and a table size under which `(code * multiplier mod 2^32) >> (32 - bits)`
    differs for every code: the standard tables are then looked up in one step, however many
    sentences the spec has (the search is deterministic, so the output is too)."""
    bits = max(2, (8 * max(len(codes), 1) - 1).bit_length())
    while True:
        for i in range(200_000):
            multiplier = (0x9E3779B1 + 2 * i) & 0xFFFFFFFF
            slots = [(code * multiplier & 0xFFFFFFFF) >> (32 - bits) for code in codes]
            if len(set(slots)) == len(slots):
                table = [0] * (1 << bits)
                for index, slot in enumerate(slots):
                    table[slot] = index + 1
                return {"multiplier": f"0x{multiplier:08X}u", "bits": bits, "slots": table,
                        "slot_type": "uint8_t" if len(codes) < 255 else "uint16_t"}
        bits += 1


# ------------------------------------------------------------------------------------------------
# The small profile's reader (-DNMEA_SMALL: runtime/c/small.c)

INT32_MIN, INT32_MAX = -(2**31), 2**31 - 1


def small_view(spec: Spec, views: list[dict], dispatch: dict[str, list[dict]]) -> dict | None:
    """The packed tables of the small reader (runtime/c/small.c), or None when the spec has what it
    does not read (a proprietary sentence, a text command, an encapsulation sentence, a keyword
    that picks the layout, a field type without a C small reader, more than 16 ranges, enums or
    words, a range of more than 32 bits): a -DNMEA_SMALL build of such a spec keeps the general
    reader. A field is two bytes: its type and the index of what it takes (a range, an enum, a
    word; a text's longest length as a range's max) in four bits each, its member's offset."""
    if any(table for name, table in dispatch.items() if name != "standard") or not views:
        return None
    if any(v["kind"] != "standard" or v["sentence"].start != "$" or v["layout"].selector is not None
           for v in views):
        return None
    ranges: dict[tuple[int, int, int, int], int] = {}
    enums: dict[str, int] = {}
    words: dict[str, int] = {}
    enum_defs: list[EnumDef] = []
    descriptors: list[str] = []
    layouts = []
    types: set[str] = set()

    def bound(value: float | None, none: int) -> tuple[int, int]:
        if value is None:
            return none, 0
        return fixed_point(value)

    def descriptor(f: Field, owner: str | None) -> str | None:
        t = f.field_type
        if t.c_small is None:
            return None
        arg = 0
        if t.numeric or t.has_length:
            low = bound(f.min, INT32_MIN) if t.numeric else (INT32_MIN, 0)
            high = bound(f.max, INT32_MAX) if t.numeric else (f.max_length or INT32_MAX, 0)
            if not all(INT32_MIN <= b <= INT32_MAX and s < 16 for b, s in (low, high)):
                return None
            arg = ranges.setdefault((low[0], low[1], high[0], high[1]), len(ranges))
        elif t.coded:
            assert f.enum is not None
            if f.enum.id not in enums:
                enums[f.enum.id] = len(enums)
                enum_defs.append(f.enum)
            arg = enums[f.enum.id]
        elif "word" in t.args:
            arg = words.setdefault(f.value or "", len(words))
        if arg > 15:
            return None
        offset = f"offsetof({owner}, {member(f.id)})" if owner and t.c_type else "0"
        types.add(t.c_small)
        return f"SMALL_{t.c_small} | {arg} << 4, {offset}"

    for v in views:
        struct = f"nmea_{v['name']}"
        group = v["group"]
        rows = [descriptor(fv["field"], struct) for fv in v["fields"]]
        entry: list[str | None] = []
        if group is not None:
            if not group["stored"]:
                return None
            owner = None if group["single"] else group["entry_type"]
            entry = [descriptor(fv["field"], owner) for fv in group["fields"]]
        if None in rows or None in entry:
            return None
        same = v["same_as_main"]
        if any(n >= 32 for n in same):
            return None
        layouts.append({
            "name": v["name"],
            "init": ", ".join(str(x) for x in [
                f"0x{sum(1 << n for n in same):X}u", len(descriptors), len(v["before"]), len(v["after"]),
                len(v["optional"]), v["fixed"], v["optional_max"] if group else v["max_fields"], f"sizeof({struct})",
                f"offsetof({struct}, checksum)",
                f"offsetof({struct}, optional_count)" if v["optional"] else 0,
                "SMALL_VARIANT" if v["layout"].id else 0,
                len(entry), group["group"].width if group else 0, group["group"].min if group else 0,
                group["group"].max if group else 0,
                f"offsetof({struct}, {group['member']})" if group else 0,
                f"offsetof({struct}, {group['count']})" if group and group["count"] else 0]),
            "fields": [r for r in rows + entry if r is not None],
        })
        descriptors += [r for r in rows + entry if r is not None]
    if len(descriptors) > 255:
        return None
    # the layouts of each standard sentence, consecutive in nmea_sentence_id's order
    order = [v["const"] for v in views]
    sentences = []
    for e in dispatch["standard"]:
        first = order.index(e["ids"][0])
        if e["ids"] != order[first:first + len(e["ids"])]:
            return None
        sentences.append((e["sort"].decode(), first + 1, len(e["ids"])))
    width = max(len(key) for key, _, _ in sentences)
    return {
        "layouts": layouts,
        "structs": [f"nmea_{v['name']}" for v in views],
        "ids": c_str("".join(key.ljust(width, "\0") for key, _, _ in sentences)),
        "id_width": width,
        "sentences": [(key, first, n) for key, first, n in sentences],
        "field_bytes": 2 * len(descriptors),
        "ranges": [f"{{{lo}, {hi}, {lo_s << 4 | hi_s}}}".replace(str(INT32_MIN), "INT32_MIN").replace(
            str(INT32_MAX), "INT32_MAX") for lo, lo_s, hi, hi_s in ranges] or ["{0, 0, 0}"],
        "enums": [{"id": e.id, "codes": c_str("".join(v.code.ljust(e.max_len, "\0") for v in e.values)),
                   "init": f"{len(e.values)}, {e.max_len}, {e.min_len}, NMEA_CODES_{e.code_class.upper()}"}
                  for e in enum_defs] or [{"id": "none", "codes": "NULL", "init": "0, 0, 0, 0"}],
        "words": [c_str(w) for w in words] or ["NULL"],
        "types": sorted(types),  # those the build reads: the small reader has the code of these only
    }


# The nmea_tag_type of each value type of spec/tag_block.yaml.
TAG_TYPES = {"integer": "NMEA_TAG_INTEGER", "group": "NMEA_TAG_GROUP", "text": "NMEA_TAG_TEXT"}


def emit(spec: Spec, env: jinja2.Environment) -> dict[str, str]:
    ranges = Ranges()
    args = FieldArgs(ranges)
    views = [layout_view(s, lay, args) for s in spec.sentences for lay in s.layouts]
    texts = enum_texts(spec.enums)
    refs = enum_text_refs(texts)
    enums = [enum_view(e, refs) for e in spec.enums]
    bitfields = [bitfield_view(b) for b in spec.bitfields]
    tables = [table_view(t) for t in spec.tables]
    dispatch = _dispatch(spec, views)
    sentences = [{
        "sentence": s,
        "const": layout_const(s, s.layout),
        "id": c_str(s.id),
        "layouts": [v for v in views if v["sentence"] is s],
    } for s in spec.sentences]
    # The fast path reads a standard-looking line by its last three letters ($GPGSV: GSV); only a
    # proprietary address whose last three letters name a standard sentence must be told apart.
    standard_ids = {e["sort"] for e in dispatch["standard"]}
    shadowing = [e for e in dispatch["talker_like"] if e["sort"][2:] in standard_ids]
    # The query ($CCGPQ): its entry of the standard table, which route takes for a 5-character
    # address that ends in Q and whose last three characters name no standard sentence.
    query = [i for i, e in enumerate(dispatch["standard"]) if e["sort"] == QUERY.encode()]
    context = {
        "query_index": query[0] if query else None,
        "shadowing_talker_like": bool(shadowing),
        "enums": enums, "layouts": views, "sentences": sentences, "ranges": ranges.all,
        "enum_texts": [(name, c_str(text)) for text, name in texts.items() if refs[text] == name],
        "field_args": args.tables(),
        "bitfields": bitfields, "tables": tables, "dispatch": dispatch,
        "hashes": {name: perfect_hash([int(e["code"], 16) for e in dispatch[name]])
                   for name in ("standard", "encapsulated") if dispatch[name]},
        "commands": [v for v in views if v["replies"]],
        "pairings": reply_pairings(spec), "judged": reply_judgements(spec),
        "fixes": fix_views(spec, views), "combined_talker": c_str(spec.combined_talker or ""),
        "talker_systems": [(c_str(t), c_str(g)) for t, g in spec.talker_systems.items()],
        "satellite_ids": [(c_str(g), low, high) for g, low, high in spec.satellite_ids],
        "tag_codes": [(c_str(c.code), c_str(c.id), c_str(c.name), TAG_TYPES[c.type]) for c in spec.tag_codes],
        "code_max": max([e.max_len for e in spec.enums] + [1]),
        "max_fields": max([v["max_fields"] for v in views] + [1]),
        # the most layouts one address or command word has (1: first_fit reads the one directly)
        "max_layouts": max([len(e["ids"]) for table in dispatch.values() for e in table] + [1]),
        "json_max": json_max(spec, views),
        "small": small_view(spec, views, dispatch),
        "max_line": longest_line(spec), "contract_max_line": MAX_LINE, "ais": carries_ais(spec), "ubx": carries_ubx(spec),
        "rtcm3": bool(spec.bit_messages),
        "runtime_h": runtime_header("runtime.h"),
        "runtime_api_h": (RUNTIME_C / "api.h").read_text(encoding="utf-8"),
        "runtime_c": runtime_source("runtime.c"),
    }
    files = {
        "c/nmea.h": env.get_template("c/nmea.h.j2").render(header=header(spec, "//"), **context),
        "c/nmea.c": env.get_template("c/nmea.c.j2").render(header=header(spec, "//"), **context),
        "c/nmea_tool.c": runtime_file(spec, "//", "c/tool.c"),
        "c/tests/test_examples.c": env.get_template("c/test_examples.c.j2").render(
            header=header(spec, "//"), vectors=[vector_view(r) for r in emit_vectors.example_vectors(spec)],
            commands=context["commands"], bitfields=bitfields, tables=tables,
            grouped=[v for v in context["layouts"] if v["group"] and v["group"]["accessor"]],
            reply_cases=[{"const": layout_const(c.command, c.layout), "line": c_str(c.line), "what": c_comment(
                f"{c.line} to {c.command.id}"), "expect": {"ok": "NMEA_REPLY_OK", "error": "NMEA_REPLY_ERROR"}.get(
                c.outcome or "", "NMEA_REPLY_NONE")} for c in pairing.reply_cases(spec)]),
    }
    return files
