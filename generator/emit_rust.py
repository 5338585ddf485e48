"""Rust emitter: the crate `nmeaspec` (no dependencies, `#![no_std]` unless the `std` feature is
on) with a struct, parser and serializer per sentence layout over the hand-written runtime in
templates/rust/runtime, the `nmea-rs` tool and a test over the manuals' examples."""

from __future__ import annotations

import json
import re
import textwrap
from decimal import Decimal

import jinja2

from . import emit_vectors
from .emit import TEMPLATES, header
from .model import EnumDef, Field, Group, Layout, Sentence, Spec, camel, fmt_num

CRATE = "nmeaspec"
RUNTIME_MODULES = ["mod", "error", "frame", "layout", "types", "write", "json"]

# Expected texts the runtime's readers hold for the types whose description is fixed.
FIXED_EXPECTED = {
    "hex": "hex number",
    "time": "time hhmmss[.s]",
    "date": "date ddmmyy",
    "char": "one character",
    "latitude": "latitude ddmm.mmmm",
    "longitude": "longitude dddmm.mmmm",
}

KEYWORDS = {
    "as", "break", "const", "continue", "crate", "else", "enum", "extern", "false", "fn", "for", "if", "impl",
    "in", "let", "loop", "match", "mod", "move", "mut", "pub", "ref", "return", "self", "static", "struct",
    "super", "trait", "true", "type", "unsafe", "use", "where", "while", "async", "await", "dyn", "abstract",
    "become", "box", "do", "final", "macro", "override", "priv", "typeof", "unsized", "virtual", "yield", "try",
    "gen",
}

# Names a layout struct already uses for its own members.
RESERVED_FIELDS = {"talker", "trailing", "checksum"}

# Names the sentence modules import from the runtime; generated type names must differ.
RUNTIME_NAMES = {
    "Bound", "Checksum", "Code", "CodeChars", "Coordinate", "Date", "Error", "Fields", "Group", "Hex",
    "JsonFields", "Layout", "Name", "Number", "Range", "Reader", "Shape", "GroupShape", "Time", "WireWriter",
    "Sentence", "Generic", "LayoutId", "Frame", "Option", "Result", "Self",
}


def ident(name: str) -> str:
    """A Rust identifier for a spec id (raw when it is a keyword)."""
    if name in ("self", "super", "crate", "Self"):
        return name + "_"
    return f"r#{name}" if name in KEYWORDS else name


def rust_str(text: str) -> str:
    """A Rust string literal."""
    out = ['"']
    for ch in text:
        if ch == '"' or ch == "\\":
            out.append("\\" + ch)
        elif " " <= ch <= "~":
            out.append(ch)
        elif ch == "\n":
            out.append("\\n")
        else:
            out.append(f"\\u{{{ord(ch):x}}}")
    out.append('"')
    return "".join(out)


def rust_raw(text: str) -> str:
    """A raw string literal when the text is printable ASCII (more readable), else a plain one."""
    if not all(" " <= ch <= "~" for ch in text):
        return rust_str(text)
    hashes = 0
    while '"' + "#" * hashes in text:
        hashes += 1
    if hashes == 0 and '"' not in text and "\\" not in text:
        return f'"{text}"'
    return f'r{"#" * hashes}"{text}"{"#" * hashes}'


_LIST_START = re.compile(r"^([-*+]|\d+[.)])(\s|$)")


def doc_lines(text: str, width: int = 96) -> list[str]:
    """Wrapped doc text; no line may start like a Markdown list item or a heading."""
    lines = textwrap.wrap(" ".join(text.split()), width=width, break_long_words=False, break_on_hyphens=False)
    out: list[str] = []
    for line in lines:
        if out and (_LIST_START.match(line) or line.startswith("#") or line.startswith(">")):
            out[-1] += " " + line
        else:
            out.append(line)
    return [escape_doc(line) for line in out]


def escape_doc(line: str) -> str:
    """Keeps rustdoc from reading spec prose as links or HTML."""
    return re.sub(r"([\[\]<>])", r"\\\1", line)


def one_line(text: str) -> str:
    return escape_doc(" ".join(text.split()))


# ---------------------------------------------------------------------------------------------
# Types and per-field code


def base_type(f: Field) -> str:
    t = f.type
    simple = {"integer": "Number", "decimal": "Number", "hex": "Hex", "time": "Time", "date": "Date",
              "latitude": "Coordinate", "longitude": "Coordinate", "char": "char", "literal": "&'a str",
              "text": "&'a str"}
    if t in simple:
        return simple[t]
    assert f.enum is not None
    return f"Code<'a, {f.enum.camel}>" if t == "enum" else f"CodeChars<'a, {f.enum.camel}>"


def borrows(f: Field) -> bool:
    return f.type in ("literal", "text", "enum", "enum_chars")


def bound(value: float) -> str:
    number = Decimal(fmt_num(value))
    sign, digits, exponent = number.as_tuple()
    assert isinstance(exponent, int)
    magnitude = int("".join(map(str, digits)) or "0")
    if exponent > 0:
        magnitude *= 10 ** exponent
        exponent = 0
    signed = -magnitude if sign else magnitude
    return f"Bound::int({signed})" if exponent == 0 else f"Bound::new({signed}, {-exponent})"


def range_expr(f: Field) -> str:
    if f.min is not None and f.max is not None:
        return f"Range::between({bound(f.min)}, {bound(f.max)})"
    if f.min is not None:
        return f"Range::at_least({bound(f.min)})"
    if f.max is not None:
        return f"Range::at_most({bound(f.max)})"
    return "Range::ANY"


def max_len(value: int | None) -> str:
    return "None" if value is None else f"Some({value})"


def read_call(f: Field) -> tuple[str, list[str]]:
    """The reader call that takes field `f` from reader `f`: method and arguments."""
    t = f.type
    name = rust_str(f.id)
    if t in FIXED_EXPECTED:
        assert f.expected == FIXED_EXPECTED[t], (f.expected, t)
        if t in ("latitude", "longitude"):
            assert f.hemisphere_expected == ("hemisphere N or S" if t == "latitude" else "hemisphere E or W")
        return f"f.{t}", [name]
    if t in ("integer", "decimal"):
        return f"f.{t}", [name, rust_str(f.expected), range_expr(f)]
    if t == "literal":
        return "f.literal", [name, rust_str(f.expected), rust_str(f.value or "")]
    if t == "text":
        return "f.text", [name, rust_str(f.expected), max_len(f.max_length)]
    assert f.enum is not None
    if t == "enum":
        assert f.expected == enum_expected(f.enum, False)
        return "f.code", [name]
    assert f.expected == enum_expected(f.enum, True)
    return "f.code_chars", [name, max_len(f.max_length)]


# ---------------------------------------------------------------------------------------------
# Formatting: the statements come out as rustfmt would write them (templates/rust/rustfmt.toml:
# max_width 120, use_small_heuristics Max), so that `cargo fmt --check` passes on the crate.

WIDTH = 120


def fmt_call(indent: int, prefix: str, callee: str, args: list[str], suffix: str, next_line: bool) -> list[str]:
    """`prefix callee(args)suffix`: one line, else (for an assignment, `next_line`) the call on
    the next line, else one argument per line."""
    pad = " " * indent
    call = f"{callee}({', '.join(args)})"
    one = f"{pad}{prefix}{call}{suffix}"
    # rustfmt keeps a `call()?` on the line only when it ends 2 columns short of the limit (a
    # struct member of a one-letter name excepted); measured with rustfmt 1.9.
    short_member = not next_line and len(prefix.rstrip(": ")) == 1
    if len(one) <= (WIDTH if short_member or not suffix.startswith("?") else WIDTH - 2):
        return [one]
    if next_line and len(pad) + 4 + len(call) + len(suffix) <= WIDTH:
        return [f"{pad}{prefix.rstrip()}", f"{pad}    {call}{suffix}"]
    return [f"{pad}{prefix}{callee}(", *[f"{pad}    {a}," for a in args], f"{pad}){suffix}"]


def fmt_group_read(indent: int, target: str, group: str, callee: str, args: list[str]) -> list[str]:
    """`out.target = f.group(group, repeats, |f| callee(args))?;` as rustfmt writes it: on one
    line, else the call on the next line, else the closure as a block (after `=` or on the next
    line)."""
    pad = " " * indent
    body = f"{callee}({', '.join(args)})"
    call = f"f.group({group}, repeats, |f| {body})"
    if len(f"{pad}out.{target} = {call}?;") <= WIDTH - 2:
        return [f"{pad}out.{target} = {call}?;"]
    if len(f"{pad}    {call}?;") <= WIDTH:
        return [f"{pad}out.{target} =", f"{pad}    {call}?;"]
    head = f"f.group({group}, repeats, |f| {{"
    if len(f"{pad}out.{target} = {head}") <= WIDTH - 5:
        return [f"{pad}out.{target} = {head}", *fmt_call(indent + 4, "", callee, args, "", False), f"{pad}}})?;"]
    if len(f"{pad}    {head}") <= WIDTH - 4:
        return [f"{pad}out.{target} =", f"{pad}    {head}", *fmt_call(indent + 8, "", callee, args, "", False),
                f"{pad}    }})?;"]
    return [f"{pad}out.{target} = f.group(", f"{pad}    {group},", f"{pad}    repeats,",
            *fmt_call(indent + 4, "|f| ", callee, args, ",", False), f"{pad})?;"]


def fmt_struct(indent: int, prefix: str, name: str, members: list[tuple[str, str]], suffix: str) -> list[str]:
    pad = " " * indent
    literal = f"{name} {{ {', '.join(f'{k}: {v}' for k, v in members)} }}{suffix}"
    if len(pad) + len(prefix) + len(literal) <= WIDTH:
        return [f"{pad}{prefix}{literal}"]
    if prefix.endswith("= ") and len(pad) + 4 + len(literal) <= WIDTH:
        return [f"{pad}{prefix.rstrip()}", f"{pad}    {literal}"]
    return [f"{pad}{prefix}{name} {{", *[f"{pad}    {k}: {v}," for k, v in members], f"{pad}}}{suffix}"]


def fmt_const(indent: int, decl: str, value: str) -> list[str]:
    pad = " " * indent
    one = f"{pad}{decl} = {value};"
    if len(one) <= WIDTH or len(pad) + 4 + len(value) + 1 > WIDTH:
        return [one]
    return [f"{pad}{decl} =", f"{pad}    {value};"]


def fmt_option(indent: int, key: str, value: str | None) -> list[str]:
    """A struct member `key: Some(value),` (or `None`)."""
    pad = " " * indent
    if value is None:
        return [f"{pad}{key}: None,"]
    one = f"{pad}{key}: Some({value}),"
    if len(one) <= WIDTH:
        return [one]
    return [f"{pad}{key}: Some(", f"{pad}    {value},", f"{pad}),"]


def fmt_tuple(indent: int, items: list[str], suffix: str) -> list[str]:
    pad = " " * indent
    one = f"{pad}({', '.join(items)}){suffix}"
    if len(one) <= WIDTH:
        return [one]
    return [f"{pad}(", *[f"{pad}    {i}," for i in items], f"{pad}){suffix}"]


def fmt_array(indent: int, decl: str, items: list[str]) -> list[str]:
    pad = " " * indent
    array = f"[{', '.join(items)}];"
    if len(pad) + len(decl) + 3 + len(array) <= WIDTH:
        return [f"{pad}{decl} = {array}"]
    if len(pad) + 4 + len(array) <= WIDTH:
        return [f"{pad}{decl} =", f"{pad}    {array}"]
    return [f"{pad}{decl} = [", *[f"{pad}    {i}," for i in items], f"{pad}];"]


def rust_sorted(names: set[str]) -> list[str]:
    """Names in rustfmt's order of a use list: snake case, then CamelCase, then CONSTANTS."""
    def key(name: str) -> tuple[int, str]:
        if name == "self":
            return (0, name)
        if name.isupper():
            return (3, name)
        return (2 if name[:1].isupper() else 1, name)
    return sorted(names, key=key)


def fmt_use(path: str, names: list[str], prefix: str = "use") -> list[str]:
    one = f"{prefix} {path}::{{{', '.join(names)}}};" if len(names) > 1 else f"{prefix} {path}::{names[0]};"
    if len(one) < WIDTH - 1:
        return [one]
    lines, line = [], "   "
    for name in names:
        part = f" {name},"
        if len(line) + len(part) >= WIDTH:
            lines.append(line)
            line = "   "
        line += part
    lines.append(line)
    return [f"{prefix} {path}::{{", *lines, "};"]


def enum_expected(e: EnumDef, chars: bool) -> str:
    codes = " ".join(v.code for v in e.values)
    return f"{e.id} code{'s' if chars else ''} ({codes})"


def field_doc(f: Field) -> list[str]:
    title = f.name + (f" [{f.unit}]" if f.unit else "")
    if f.since:
        title += f" (NMEA {f.since}, optional)"
    elif f.optional:
        title += " (optional)"
    return doc_lines(f"{title}: {f.doc}", 92)


# ---------------------------------------------------------------------------------------------
# The field diagram of a layout, AeroRust nmea style


def placeholders(f: Field) -> list[str]:
    """How the manual writes a field's wire text, one string per wire field."""
    t = f.type
    if t in ("latitude", "longitude"):
        fmt = f.format or ("ddmm.mm" if t == "latitude" else "dddmm.mm")
        parts = fmt.split(",")
        return parts if len(parts) == 2 else [parts[0], "a"]
    if f.format:
        return [f.format]
    if t == "literal":
        return [f.value or "a"]
    if t == "enum":
        assert f.enum is not None
        return ["x" * f.enum.max_len if f.enum.code_class == "digits" else "a" * f.enum.max_len]
    return [{"integer": "x", "decimal": "x.x", "hex": "h", "time": "hhmmss.ss", "date": "ddmmyy", "char": "a",
             "enum_chars": "c--c", "text": "c--c"}[t]]


def diagram(sentence: Sentence, layout: Layout) -> list[str]:
    """Numbered wire fields over the sentence's layout, e.g.

               1         2        3 4         5 6
               |         |        | |         | |
        $--GLL,ddmm.mmmm,a,dddmm.mm,a,hhmmss.ss,A*hh
    """
    parts: list[tuple[int | None, str]] = []
    index = 1
    for item in layout.items:
        if isinstance(item, Group):
            collapse = item.max * item.width > 16
            shown = 1 if collapse else item.max
            for _ in range(shown):
                for f in item.fields:
                    for text in placeholders(f):
                        parts.append((index, text))
                        index += 1
            if collapse:
                parts.append((None, "..."))
                index += (item.max - 1) * item.width
            continue
        for text in placeholders(item):
            parts.append((index, text))
            index += 1
    if not parts:
        return [f"$--{sentence.id}*hh"]
    prefix = f"$--{sentence.id},"
    line = prefix + ",".join(text for _, text in parts) + "*hh"
    columns = []
    at = len(prefix)
    for label, text in parts:
        if label is not None:
            columns.append((at, str(label)))
        at += len(text) + 1
    rows: list[list[str]] = []

    def free(row: list[str], start: int, end: int) -> bool:
        return all(row[i] == " " for i in range(max(start, 0), min(end, len(row))))

    width = len(line) + 8
    for col, label in columns:
        r = 0
        while True:
            if r == len(rows):
                rows.append([" "] * width)
            if free(rows[r], col - 1, col + len(label) + 1) and all(rows[k][col] == " " for k in range(r)):
                break
            r += 1
        for i, ch in enumerate(label):
            rows[r][col + i] = ch
        for k in range(r):
            rows[k][col] = "|"
    bars = [" "] * width
    for col, _ in columns:
        bars[col] = "|"
    out = ["".join(row).rstrip() for row in reversed(rows)]
    out.append("".join(bars).rstrip())
    out.append(line)
    return out


# ---------------------------------------------------------------------------------------------
# Views: everything the templates print, computed here


def entry_name(sentence: Sentence, layout: Layout, group: Group) -> str:
    word = group.camel
    return sentence.layout_camel(layout) + (word[:-1] if word.endswith("s") else word + "Entry")


def field_view(f: Field, indent: int, prefix: str, suffix: str, next_line: bool) -> dict:
    callee, args = read_call(f)
    return {
        "field": f,
        "ident": ident(f.id),
        "type": f"Option<{base_type(f)}>",
        "read": fmt_call(indent, prefix, callee, args, suffix, next_line),
        "width": f.wire_width,
        "doc": field_doc(f),
    }


def entry_read(fields: list[dict]) -> list[str]:
    """`Ok(Self { field: read?, ... })` of an entry's reader, on one line when it fits."""
    reads = [fv["read"] for fv in fields]
    if all(len(r) == 1 for r in reads):
        one = "        Ok(Self { " + ", ".join(r[0].strip().rstrip(",") for r in reads) + " })"
        if len(one) <= WIDTH:
            return [one]
    return ["        Ok(Self {", *[line for r in reads for line in r], "        })"]


def layout_view(spec: Spec, sentence: Sentence, layout: Layout) -> dict:
    name = sentence.layout_camel(layout)
    items: list[dict] = []
    entries: list[dict] = []
    optional_wire = 0
    optional_index = 0
    for item in layout.items:
        if isinstance(item, Group):
            g = item
            if g.single:
                f = g.fields[0]
                callee, args = read_call(f)
                read = fmt_group_read(8, ident(g.id), rust_str(g.id), callee, args)
                unit = f" [{f.unit}]" if f.unit else ""
                items.append({"kind": "values", "group": g, "ident": ident(g.id), "read": read, "optional": None,
                              "type": f"Group<Option<{base_type(f)}>, {g.max}>", "width": f.wire_width,
                              "doc": doc_lines(f"{g.name}: {g.min} to {g.max} values of {f.name.lower()}{unit}: "
                                               f"{f.doc}", 92)})
            else:
                entry = entry_name(sentence, layout, g)
                fields = [field_view(f, 12, f"{ident(f.id)}: ", "?,", False) for f in g.fields]
                lifetime = any(borrows(f) for f in g.fields)
                entry_type = entry + ("<'a>" if lifetime else "")
                entries.append({"name": entry, "group": g, "fields": fields, "lifetime": lifetime,
                                "type": entry_type, "read": entry_read(fields)})
                read = fmt_call(8, f"out.{ident(g.id)} = ", "f.group", [rust_str(g.id), "repeats", f"{entry}::read"],
                                "?;", True)
                items.append({"kind": "entries", "group": g, "ident": ident(g.id), "entry": entry, "read": read,
                              "optional": None,
                              "type": f"Group<{entry_type}, {g.max}>",
                              "doc": doc_lines(f"{g.name}: {g.min} to {g.max} entries.", 92)})
            continue
        optional = None
        if item.is_optional:
            optional_wire += item.wire_width
            optional_index += 1
            optional = {"wire": optional_wire, "index": optional_index}
        view = field_view(item, 12 if optional else 8, f"out.{ident(item.id)} = ", "?;", True)
        view["kind"] = "field"
        view["optional"] = optional
        items.append(view)
    for it in items:
        some_id = it["field"].id if it.get("field") is not None else it["group"].id
        assert some_id not in RESERVED_FIELDS, f"{sentence.id}: {some_id} is a reserved name in the Rust structs"
    group = layout.group
    optional = [it for it in items if it.get("optional")]
    binding = ("repeats" if group else "_", "extra" if optional else "_")
    # The manual's example with the most fields filled in shows the layout best.
    examples = [ex for ex in sentence.examples if ex.line and ex.variant == layout.id]
    example = max(examples, key=lambda ex: sum(1 for t in (ex.line or "").split("*")[0].split(",") if t),
                  default=None)
    manual = spec.manual(example.manual) if example else None
    title = f"{sentence.id}: {sentence.name}" if not layout.id else f"{sentence.id} ({layout.name})"
    return {
        "layout": layout,
        "name": name,
        "title": title,
        "doc": doc_lines(layout.doc if layout.id else sentence.doc),
        "diagram": diagram(sentence, layout),
        "example": example.line if example else None,
        "example_from": (manual.title if manual else example.manual) if example else None,
        "items": items,
        "entries": entries,
        "group": group,
        "optional": optional,
        "optional_names": ", ".join(f"`{it['field'].id}`" for it in optional),
        "binding": binding,
        "shape": shape_lines(sentence, layout),
        "variant": fmt_const(4, "const VARIANT: Option<&'static str>",
                             f"Some({rust_str(layout.id)})" if layout.id else "None"),
    }


def shape_lines(sentence: Sentence, layout: Layout) -> list[str]:
    g = layout.group
    group = "None"
    if g is not None:
        group = fmt_struct(0, "", "Some(GroupShape", [("id", rust_str(g.id)), ("width", str(g.width)),
                                                        ("min", str(g.min)), ("max", str(g.max))], ")")[0]
    members = [("sentence", rust_str(sentence.id)), ("fixed", str(layout.fixed_count)),
               ("optional", str(layout.optional_count)), ("group", group)]
    return fmt_struct(4, "const SHAPE: Shape = ", "Shape", members, ";")


def module_imports(views: list[dict]) -> list[str]:
    runtime = {"Checksum", "Error", "Fields", "JsonFields", "Layout", "Shape", "WireWriter"}
    enums: set[str] = set()
    for view in views:
        if view["group"] is not None:
            runtime |= {"Group", "GroupShape"}
        if view["entries"]:
            runtime.add("Reader")
        fields = [it["field"] for it in view["items"] if it["kind"] == "field"]
        fields += [it["group"].fields[0] for it in view["items"] if it["kind"] == "values"]
        fields += [fv["field"] for e in view["entries"] for fv in e["fields"]]
        for f in fields:
            t = base_type(f)
            for name in ("Number", "Hex", "Time", "Date", "Coordinate", "CodeChars", "Code"):
                if t == name or t.startswith(name + "<"):
                    runtime.add(name)
            if f.type in ("integer", "decimal"):
                runtime.add("Range")
                if f.min is not None or f.max is not None:
                    runtime.add("Bound")
            if f.enum is not None:
                enums.add(f.enum.camel)
    lines: list[str] = []
    if enums:
        lines += fmt_use("crate::enums", rust_sorted(enums))
    lines += ['#[cfg(feature = "std")]', "use crate::runtime::json;"]
    lines += fmt_use("crate::runtime", rust_sorted(runtime))
    return lines


def check_names(spec: Spec) -> None:
    taken: dict[str, str] = {}
    for e in spec.enums:
        taken[e.camel] = f"enum {e.id}"
    for s in spec.sentences:
        for lay in s.layouts:
            name = s.layout_camel(lay)
            assert name not in taken, f"{name} ({s.id}) clashes with {taken[name]}"
            taken[name] = f"sentence {s.id}"
            g = lay.group
            if g is not None and not g.single:
                entry = entry_name(s, lay, g)
                assert entry not in taken or taken[entry].startswith(f"entry of {s.id}"), entry
                taken[entry] = f"entry of {s.id}"
    for name, what in taken.items():
        assert name not in RUNTIME_NAMES, f"{what} would be named {name}, a name of the Rust runtime"


def enum_view(e: EnumDef) -> dict:
    variants = []
    for v in e.values:
        name = camel(v.id)
        if name == "Self":
            name = "Self_"
        variants.append({"value": v, "name": name, "doc": doc_lines(v.doc + (
            f" (NMEA {v.since})" if v.since else ""), 92)})
    return {
        "enum": e,
        "name": e.camel,
        "doc": doc_lines(f"{e.name}: {e.doc}"),
        "variants": variants,
        "expected": fmt_const(4, "const EXPECTED: &'static str", rust_str(enum_expected(e, False))),
        "expected_chars": fmt_const(4, "const EXPECTED_CHARS: &'static str", rust_str(enum_expected(e, True))),
        "class": {"digits": "Digits", "letters": "Letters", "alnum": "Alnum"}[e.code_class],
    }


def all_fields(layout: Layout) -> list[Field]:
    out: list[Field] = []
    for item in layout.items:
        out += item.fields if isinstance(item, Group) else [item]
    return out


def sentence_module(s: Sentence) -> str:
    return ident(s.id.lower())


def example_lines(v: dict) -> list[str]:
    """The members of one `Example` of tests/examples.rs."""
    def opt(key: str) -> str | None:
        return rust_raw(v[key]) if v.get(key) is not None else None

    return [
        f"        manual: {rust_raw(v['manual_id'])},",
        f"        raw: {rust_raw(v['raw'])},",
        f"        checksum_ok: {'true' if v['checksum_ok'] else 'false'},",
        *fmt_option(8, "line", opt("line")),
        *fmt_option(8, "decode", opt("decode")),
        *fmt_option(8, "decode_values", opt("decode_values")),
        *fmt_option(8, "raw_decode", opt("raw_decode")),
    ]


def emit(spec: Spec, env: jinja2.Environment) -> dict[str, str]:
    check_names(spec)
    env.globals.update(rust_str=rust_str, rust_raw=rust_raw, one_line=one_line)
    base = "rust"
    files: dict[str, str] = {}
    for module in RUNTIME_MODULES:
        source = f"templates/rust/runtime/{module}.rs"
        text = (TEMPLATES / "rust" / "runtime" / f"{module}.rs").read_text(encoding="utf-8")
        files[f"{base}/src/runtime/{module}.rs"] = header(spec, "//", [source]) + "\n" + text
    tool = (TEMPLATES / "rust" / "nmea-rs.rs").read_text(encoding="utf-8")
    files[f"{base}/src/bin/nmea-rs.rs"] = header(spec, "//", ["templates/rust/nmea-rs.rs"]) + "\n" + tool

    layouts = []
    for s in spec.sentences:
        views = [layout_view(spec, s, lay) for lay in s.layouts]
        enum_files = sorted({f.enum.origin.file for lay in s.layouts for f in all_fields(lay) if f.enum})
        module_file = sentence_module(s).removeprefix("r#")
        files[f"{base}/src/sentences/{module_file}.rs"] = env.get_template("rust/sentence.rs.j2").render(
            header=header(spec, "//", [s.source, *enum_files]), sentence=s, doc=doc_lines(s.doc), layouts=views,
            imports=module_imports(views))
        for view in views:
            layouts.append({"sentence": s, "name": view["name"], "layout": view["layout"], "title": view["title"]})
    dispatch = []
    for s in spec.sentences:
        names = [s.layout_camel(lay) for lay in s.layouts]
        dispatch.append({"sentence": s, "main": names[0], "variants": names[1:]})
    files[f"{base}/src/sentences/mod.rs"] = env.get_template("rust/sentences_mod.rs.j2").render(
        header=header(spec, "//"), sentences=[
            {"sentence": s, "module": sentence_module(s), "uses": fmt_use(
                sentence_module(s), rust_sorted({s.layout_camel(lay) for lay in s.layouts}), "pub use")}
            for s in spec.sentences])
    files[f"{base}/src/enums.rs"] = env.get_template("rust/enums.rs.j2").render(
        header=header(spec, "//", [e.origin.file for e in spec.enums]), enums=[enum_view(e) for e in spec.enums])
    vectors = emit_vectors.example_vectors(spec)
    intact = [v for v in vectors if v["line"]]
    first = None
    candidates = [v for v in intact if v["sentence"] == "GGA"] or intact
    if candidates:
        v = max(candidates, key=lambda v: sum(1 for t in v["line"].split("*")[0].split(",") if t))
        s = spec.sentence(v["sentence"])
        lay = next(lay for lay in s.layouts if lay.id == v["variant"])
        filled = [f for f in lay.fields if not f.is_optional and json.loads(v["decode"])["fields"].get(f.id)]
        if filled:
            first = {"line": v["line"], "layout": s.layout_camel(lay), "var": ident(s.id.lower()),
                     "talker": v["line"][1:3], "field": ident(filled[0].id)}
    unit_examples: list[str] = []
    for lay in layouts:
        found = next((v for v in intact if v["sentence"] == lay["sentence"].id
                      and v["variant"] == lay["layout"].id), None)
        if found:
            unit_examples += fmt_tuple(8, [rust_raw(found["line"]), rust_raw(found["decode"])], ",")
    files[f"{base}/src/lib.rs"] = env.get_template("rust/lib.rs.j2").render(
        header=header(spec, "//"), spec=spec, layouts=layouts, dispatch=dispatch, example=first,
        unit_examples=unit_examples,
        all_layouts=fmt_array(4, f"pub const ALL: [Self; {len(layouts)}]", [f"Self::{lay['name']}" for lay in layouts]))
    files[f"{base}/Cargo.toml"] = env.get_template("rust/Cargo.toml.j2").render(
        header=header(spec, "#", ["templates/rust/Cargo.toml.j2"]), crate=CRATE)
    rustfmt = (TEMPLATES / "rust" / "rustfmt.toml").read_text(encoding="utf-8")
    files[f"{base}/rustfmt.toml"] = header(spec, "#", ["templates/rust/rustfmt.toml"]) + "\n" + rustfmt
    files[f"{base}/tests/examples.rs"] = env.get_template("rust/examples.rs.j2").render(
        header=header(spec, "//"), vectors=[{"rust": example_lines(v)} for v in vectors], crate=CRATE)
    return files
