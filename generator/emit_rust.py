"""Rust emitter: the crate `nmeaspec` (no dependencies, `#![no_std]` unless the `std` feature is
on) with a struct, parser, serializer and command builder per sentence layout over the
hand-written runtime in runtime/rust/src, the bitfields and parameter tables, the `nmea-rs`
tool and a test over the manuals' examples."""

from __future__ import annotations

import functools
import hashlib
import json
import re
import subprocess
import tempfile
import textwrap
from pathlib import Path

import jinja2

from . import cache, emit_vectors, pairing
from .emit import RUNTIME, char_literal, header, package_readme, runtime_file, typed_natively
from .field_types import codes_expected
from .model import QUERY, BitfieldDef, EnumDef, Field, FixField, Group, Layout, Sentence, Spec, TableDef, camel
from .names_rust import bits_const, entry_name, ident, parameter_const
from .numbers import fixed_point
from .rust_features import Gates, cfg, with_cfg

CRATE = "nmeaspec"
# The runtime crate's modules (runtime/rust/src), copied into the generated crate as src/runtime.
RUNTIME_MODULES = sorted(path.stem for path in (RUNTIME / "rust" / "src").glob("*.rs"))

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
    rust_type = f.field_type.rust_type
    assert rust_type is not None, f.type
    return rust_type.format(enum=f.enum.camel if f.enum else "")


def borrows(f: Field) -> bool:
    return "'a" in (f.field_type.rust_type or "")


def is_text(sentence: Sentence) -> bool:
    return sentence.framing == "text"


def framing_expr(sentence: Sentence) -> str:
    """The layout's `Framing` constant."""
    if not sentence.is_proprietary:
        return "Framing::Encapsulated" if sentence.start == "!" else "Framing::Standard"
    kind = "Text" if is_text(sentence) else "Proprietary"
    return f"Framing::{kind}({rust_str(sentence.address or '')})"


def bound(value: float) -> str:
    digits, scale = fixed_point(value)
    return f"Bound::int({digits})" if scale == 0 else f"Bound::new({digits}, {scale})"


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


def rust_arg(word: str, f: Field) -> str | None:
    """A word of the registry's argument vocabulary (field_types.py) as a Rust reader argument for
    `f`; None for what the reader knows from its type (a coordinate's hemispheres, an enum)."""
    if word == "range":
        return range_expr(f)
    if word == "word":
        return rust_str(f.value or "")
    if word == "max_length":
        return max_len(f.max_length)
    assert word in ("hemisphere", "table"), word
    return None


def fast_call(f: Field) -> tuple[str, list[str]]:
    """The fast path's reader call that takes field `f` from `f` (a FastReader, see
    runtime/fast.rs): read_call without the names and texts that errors need."""
    t = f.field_type
    return f"f.{t.rust_method}", [a for a in (rust_arg(word, f) for word in t.args) if a is not None]


def read_call(f: Field) -> tuple[str, list[str]]:
    """The reader call that takes field `f` from reader `f`: method and arguments."""
    method, args = fast_call(f)
    return method, [rust_str(f.id), *([rust_str(f.expected)] if f.field_type.rust_expected else []), *args]


# ---------------------------------------------------------------------------------------------
# Statements, each on one line: rustfmt() breaks the long ones as it does every .rs file. It
# leaves as written a construct it cannot fit in max_width (a test's long raw strings): those
# few are broken here, as rustfmt would if it could.
WIDTH = 120  # max_width of runtime/rust/rustfmt.toml


def fmt_call(indent: int, prefix: str, callee: str, args: list[str], suffix: str) -> list[str]:
    """`prefix callee(args)suffix`."""
    return [f"{' ' * indent}{prefix}{callee}({', '.join(args)}){suffix}"]


def fmt_struct(indent: int, prefix: str, name: str, members: list[tuple[str, str]], suffix: str) -> list[str]:
    return [f"{' ' * indent}{prefix}{name} {{ {', '.join(f'{k}: {v}' for k, v in members)} }}{suffix}"]


def fmt_const(indent: int, decl: str, value: str) -> list[str]:
    return [f"{' ' * indent}{decl} = {value};"]


def fmt_option(indent: int, key: str, value: str | None) -> list[str]:
    """A struct member `key: Some(value),` (or `None`), broken before a value too long for a line
    (see WIDTH)."""
    pad = " " * indent
    one = f"{pad}{key}: {'None' if value is None else f'Some({value})'},"
    return [one] if len(one) <= WIDTH else [f"{pad}{key}: Some(", f"{pad}    {value},", f"{pad}),"]


def fmt_arm(indent: int, pattern: str, value: str) -> list[str]:
    """A match arm `pattern => value,`."""
    return [f"{' ' * indent}{pattern} => {value},"]


def fmt_fast_arm(indent: int, pattern: str, layouts: list[str]) -> list[str]:
    """The match arm of the fast path's dispatch (lib.rs `read_sentence`) for an address with
    `layouts`: its first layout's reader, given the others."""
    rest = ", ".join(f"LayoutId::{n}" for n in layouts[1:])
    return fmt_arm(indent, pattern, f"read_layout::<LayoutId, {layouts[0]}, O>(fields, line, &[{rest}])")


def fmt_const_slice(indent: int, decl: str, items: list[str]) -> list[str]:
    """`decl = &[items];`."""
    return fmt_const(indent, decl, "&[" + ", ".join(items) + "]")


def reply_case_lines(spec: Spec, gates: Gates) -> list[str]:
    """The elements of tests/examples.rs's REPLY_CASES (a reply's line can be too long for one: see
    WIDTH)."""
    out: list[str] = []
    for case in pairing.reply_cases(spec):
        outcome = f"Some(ReplyOutcome::{case.outcome.capitalize()})" if case.outcome else "None"
        members = [f"command: LayoutId::{case.command.layout_camel(case.layout)}", f"line: {rust_str(case.line)}",
                   f"outcome: {outcome}"]
        one = f"    ReplyCase {{ {', '.join(members)} }},"
        lines = [one] if len(one) <= WIDTH else ["    ReplyCase {", *(f"        {m}," for m in members), "    },"]
        reply = spec.by_address(case.line[1:].split(",")[0].split("*")[0])
        vendors = {case.command.vendor} | {s.vendor for s, _ in reply if s.vendor}
        out += with_cfg(4, gates_all(vendors), lines)
    return out


def gates_all(vendors: set[str | None]) -> str:
    """The attribute that compiles an item only with every one of `vendors` ("" for none)."""
    features = sorted({v for v in vendors if v})
    if len(features) < 2:
        return cfg(set(features))
    return "#[cfg(all(" + ", ".join(f'feature = "{f}"' for f in features) + "))]"


def reply_test(condition: pairing.Condition, target: str) -> str:
    """The Rust test that the member `target` (an Option) holds a reply's `when` or `outcome` value."""
    f, value = condition.field, condition.value
    pairing = f.field_type.pairing
    if pairing == "number":
        return f"{target}.is_some_and(|n| n.is_integer({int(value)}))"
    if pairing == "code":
        assert f.enum is not None
        variant = camel(str(value))
        variant = "Self_" if variant == "Self" else variant
        return f"{target} == Some(Code::Known(crate::enums::{f.enum.camel}::{variant}))"
    if pairing == "string":
        return f"{target} == Some({rust_str(value)})"
    assert pairing == "character", f.type
    return f"{target} == Some({char_literal(value)})"


def reply_pairing_arms(spec: Spec) -> tuple[list[str], list[str]]:
    """The arms of `Sentence::reply_to` (command layout, reply layout => the reply's fields hold
    what the spec pairs them by) and of `reply_outcome` (reply layout => what it reports)."""
    reply_arms: list[str] = []
    for command in spec.proprietary:
        for p in pairing.pairings(command):
            binding = "s" if p.conditions else "_"
            tests = [reply_test(c, f"s.{ident(c.field.id)}") for c in p.conditions] or ["true"]
            reply_arms += [line for layout in command.layouts
                           for line in with_cfg(12, gates_all({command.vendor, p.reply.vendor}), fmt_arm(
                               12, f"(LayoutId::{command.layout_camel(layout)}, "
                               f"Self::{p.reply.layout_camel(p.layout)}({binding}))", " && ".join(tests)))]
    outcome_arms: list[str] = []
    for sentence in spec.proprietary:
        for layout, j in pairing.judged(sentence):
            name = sentence.layout_camel(layout)
            if j.fixed is not None:
                arm = fmt_arm(12, f"Self::{name}(_)", "ReplyOutcome::Error")
            else:
                assert j.field is not None
                target = f"s.{ident(j.field.id)}"
                ok = " || ".join(reply_test(pairing.Condition(j.field, v), target) for v in j.ok)
                arm = fmt_arm(12, f"Self::{name}(s)", f"ReplyOutcome::judged({ok})")
            outcome_arms += with_cfg(12, gates_all({sentence.vendor}), arm)
    return reply_arms, outcome_arms


def fmt_slice(indent: int, head: str, items: list[str], suffix: str) -> list[str]:
    """`head&[items]suffix` (a match arm, a return)."""
    return [f"{' ' * indent}{head}&[{', '.join(items)}]{suffix}"]


def fmt_tuple(indent: int, items: list[str], suffix: str) -> list[str]:
    """A tuple, one item a line when it is too long for a line (see WIDTH)."""
    pad = " " * indent
    one = f"{pad}({', '.join(items)}){suffix}"
    return [one] if len(one) <= WIDTH else [f"{pad}(", *[f"{pad}    {i}," for i in items], f"{pad}){suffix}"]


def fmt_use(path: str, names: set[str], prefix: str = "use") -> list[str]:
    """`use path::{names};` (rustfmt orders the names)."""
    listed = ", ".join(sorted(names))
    return [f"{prefix} {path}::{{{listed}}};" if len(names) > 1 else f"{prefix} {path}::{listed};"]


def field_doc(f: Field) -> list[str]:
    title = f.name + (f" [{f.unit}]" if f.unit else "")
    if f.since:
        title += f" (NMEA {f.since}, optional)"
    elif f.optional:
        title += " (optional)"
    return doc_lines(f"{title}: {f.doc}", 92)


# ---------------------------------------------------------------------------------------------
# The field diagram of a layout, AeroRust nmea style


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
                    for text in f.field_type.placeholders(f):
                        parts.append((index, text))
                        index += 1
            if collapse:
                parts.append((None, "..."))
                index += (item.max - 1) * item.width
            continue
        for text in item.field_type.placeholders(item):
            parts.append((index, text))
            index += 1
    if is_text(sentence):
        head, sep, tail = sentence.address or "", " ", ""
    else:
        head, sep, tail = (f"${sentence.address}" if sentence.is_proprietary else f"$--{sentence.id}"), ",", "*hh"
    if not parts:
        return [head + tail]
    prefix = head + sep
    line = prefix + sep.join(text for _, text in parts) + tail
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


def field_view(f: Field, indent: int, prefix: str, suffix: str) -> dict:
    callee, args = read_call(f)
    return {
        "field": f,
        "ident": ident(f.id),
        "type": f"Option<{base_type(f)}>",
        "read": fmt_call(indent, prefix, callee, args, suffix),
        "width": f.wire_width,
        "doc": field_doc(f) + bits_doc(f),
    }


def entry_read(fields: list[dict]) -> list[str]:
    """`Ok(Self { field: read?, ... })` of an entry's reader."""
    return ["        Ok(Self { " + ", ".join(line.strip().rstrip(",") for fv in fields for line in fv["read"]) + " })"]


def needs_reads_first(spec: Spec, sentence: Sentence, layout: Layout) -> bool:
    """Whether the dispatch asks a layout whether a line's first field reads as its first (see
    the runtime's `claimed`): a proprietary `$` layout without a keyword whose address has
    layouts with one."""
    return (sentence.is_proprietary and sentence.framing == "sentence" and layout.selector is None
            and any(other.selector is not None for _, other in spec.by_address(sentence.address or "")))


def reads_first_body(spec: Spec, sentence: Sentence, layout: Layout) -> list[str] | None:
    """The body of a layout's `reads_first` (`needs_reads_first`), or None: the first field read
    as parse_fields reads it, a number outside its range accepted."""
    if not needs_reads_first(spec, sentence, layout):
        return None
    if not layout.items:
        return ["        fields.is_empty()"]
    first = layout.items[0]
    if isinstance(first, Group):
        return ["        let _ = fields;", "        true"]
    callee, args = read_call(first)
    value = f"Option<{base_type(first)}>"
    short = "fields.is_empty()" if first.wire_width == 1 else f"fields.len() < {first.wire_width}"
    lines = [f"        if {short} {{", "            return true;", "        }", "        let mut f = fields.reader();"]
    lines += fmt_call(8, f"let read: Result<{value}, Error<'_>> = ", callee, args, ";")
    lines.append("        read.map_or_else(|error| error.is_out_of_range(), |_| true)")
    return lines


def layout_view(spec: Spec, sentence: Sentence, layout: Layout) -> dict:
    name = sentence.layout_camel(layout)
    text = is_text(sentence)
    items: list[dict] = []
    entries: list[dict] = []
    optional_wire = 0
    optional_index = 0
    for item in layout.items:
        if isinstance(item, Group):
            g = item
            if g.single and g.fields[0].field_type.verbatim:
                # Kept as the wire text: a struct stays small whatever the group's maximum.
                f = g.fields[0]
                read = fmt_call(8, f"out.{ident(g.id)} = ", "f.texts",
                                [rust_str(g.id), rust_str(f.id), "repeats", rust_str(f.expected), max_len(f.max_length)],
                                "?;")
                fast = fmt_call(8, f"self.{ident(g.id)} = ", "f.texts", ["repeats", max_len(f.max_length)], "?;")
                items.append({"kind": "texts", "group": g, "ident": ident(g.id), "read": read, "fast": fast,
                              "optional": None,
                              "type": "Texts<'a>", "width": 1,
                              "doc": doc_lines(f"{g.name}: {g.min} to {g.max} values of {f.name.lower()}, as "
                                               f"received: {f.doc}", 92)})
            elif g.single:
                f = g.fields[0]
                callee, args = read_call(f)
                reader = f"read_{sentence.layout_snake(layout)}_{g.id}"
                value = f"Option<{base_type(f)}>"
                # The general reader of one value, named: the values stay on the wire and a
                # parsed sentence reads them again with it.
                value_reader = {"name": reader, "type": value, "body": fmt_call(4, "", callee, args, ""),
                                "group": g}
                read = fmt_call(8, f"out.{ident(g.id)} = ", "f.entries",
                                [rust_str(g.id), "repeats", str(f.wire_width), reader], "?;")
                fast_callee, fast_args = fast_call(f)
                fast = fmt_call(8, f"self.{ident(g.id)} = ", "f.values",
                                ["repeats", str(f.wire_width), f"|f| {fast_callee}({', '.join(fast_args)})", reader],
                                "?;")
                unit = f" [{f.unit}]" if f.unit else ""
                items.append({"kind": "values", "group": g, "ident": ident(g.id), "read": read, "fast": fast,
                              "optional": None, "value_reader": value_reader,
                              "type": f"Entries<'a, {value}>", "width": f.wire_width,
                              "doc": doc_lines(f"{g.name}: {g.min} to {g.max} values of {f.name.lower()}{unit}: "
                                               f"{f.doc} Kept as received, read by `iter()` and `get(i)`.", 92)
                              + bits_doc(f)})
            else:
                entry = entry_name(sentence, layout, g)
                fields = [field_view(f, 12, f"{ident(f.id)}: ", "?,") for f in g.fields]
                lifetime = any(borrows(f) for f in g.fields)
                entry_type = entry + ("<'a>" if lifetime else "")
                read_fast = [line for f in g.fields
                             for line in fmt_call(8, f"self.{ident(f.id)} = ", *fast_call(f), "?;")]
                entries.append({"name": entry, "group": g, "fields": fields, "lifetime": lifetime,
                                "type": entry_type, "read": entry_read(fields), "read_fast": read_fast})
                read = fmt_call(8, f"out.{ident(g.id)} = ", "f.entries",
                                [rust_str(g.id), "repeats", str(g.width), f"{entry}::read"], "?;")
                fast = fmt_call(8, f"self.{ident(g.id)} = ", "f.entries",
                                ["repeats", str(g.width), f"{entry}::read_fast", f"{entry}::read"], "?;")
                items.append({"kind": "entries", "group": g, "ident": ident(g.id), "entry": entry, "read": read,
                              "fast": fast,
                              "optional": None, "lifetime": lifetime,
                              "type": f"Entries<'a, {entry_type}>",
                              "doc": doc_lines(f"{g.name}: {g.min} to {g.max} entries, kept as received: read "
                                               "them by `iter()` and `get(i)`.", 92)})
            continue
        optional = None
        if item.is_optional:
            optional_wire += item.wire_width
            optional_index += 1
            optional = {"wire": optional_wire, "index": optional_index}
        indent = 12 if optional else 8
        if item.field_type.keyword:
            callee, args = read_call(item)
            view = {"field": item, "ident": ident(item.id), "read": fmt_call(indent, "", callee, args, "?;"),
                    "fast": fmt_call(indent, "", *fast_call(item), "?;"),
                    "width": 1, "word": rust_str(item.value or "")}
            view["kind"] = "keyword"
        else:
            view = field_view(item, indent, f"out.{ident(item.id)} = ", "?;")
            view["fast"] = fmt_call(indent, f"self.{ident(item.id)} = ", *fast_call(item), "?;")
            view["kind"] = "field"
        view["optional"] = optional
        items.append(view)
    group = layout.group
    optional = [it for it in items if it.get("optional")]
    binding = ("repeats" if group else "_", "extra" if optional else "_")
    example = sentence.example_of(layout)
    manual = spec.manual(example.manual) if example else None
    title = f"{sentence.id}: {sentence.name}" if not layout.id else f"{sentence.id} ({layout.name})"
    members = [it for it in items if it["kind"] != "keyword"]
    if not sentence.is_proprietary:
        talker = "fields.talker()" if sentence.talker_length == 2 else f"fields.talker_of({sentence.talker_length})"
        framing_members = [f"talker: {talker}", "checksum"]
    elif text:
        framing_members = ["as_received: fields.line()"]
    else:
        framing_members = ["checksum"]
    assigned = bool(members) or bool(optional)
    init = [f"        let {'mut ' if assigned else ''}out = Self {{ "
            + ", ".join(framing_members + (["..Self::default()"] if assigned else [])) + " };"]
    fast = fast_reader(sentence, items) if sentence.fast_path and not text else []
    lifetime = (not sentence.is_proprietary or text
                or any(it["kind"] == "field" and borrows(it["field"]) for it in items)
                or any(it["kind"] in ("texts", "values", "entries") for it in items))
    keywords = [it["field"] for it in items if it["kind"] == "keyword"]
    reader = "fields.reader().ignoring_case()" if text else "fields.reader()"
    reads_first = reads_first_body(spec, sentence, layout)
    if text:
        what = f"`{sentence.address} …` command (its words in any letter case)"
    elif sentence.is_proprietary:
        what = f"`${sentence.address}` line"
    else:
        what = f"`$--{sentence.id}` line"
    return {
        "layout": layout,
        "name": name,
        "type": name + ("<'a>" if lifetime else ""),
        "lifetime": lifetime,
        "title": title,
        "doc": doc_lines(layout.doc if layout.id else sentence.doc),
        "diagram": diagram(sentence, layout),
        "example": example.line if example else None,
        "example_from": (manual.title if manual else example.manual) if example else None,
        "items": items,
        "entries": entries,
        "value_readers": [it["value_reader"] for it in items if it["kind"] == "values"],
        "group": group,
        "optional": optional,
        "optional_names": ", ".join(f"`{it['field'].id}`" for it in optional),
        "binding": binding,
        "shape": shape_lines(sentence, layout),
        "variant": fmt_const(4, "const VARIANT: Option<&'static str>",
                             f"Some({rust_str(layout.id)})" if layout.id else "None"),
        "framing": fmt_const(4, "const FRAMING: Framing", framing_expr(sentence)),
        "words": fmt_const_slice(4, "const WORDS: &'static [(&'static str, usize)]",
                                 [f"({rust_str(it['field'].id)}, {it['width']})" for it in items]) if text else [],
        "json": json_const(items),
        "derived": derived_view(layout),
        "visit": visit_lines(items),
        "init": init,
        "fast": fast,
        "fast_path": sentence.fast_path and not text,
        "reader": fmt_const(8, "let mut f", reader) if items else [],
        "reads_first": reads_first,
        "checksum_arg": "_checksum" if text else "checksum",
        "keywords": doc_lines("Keywords (fixed words, not members: parsing checks them, writing puts them "
                              "back): " + ", ".join(f"`{f.id}` = `{f.value}`" for f in keywords) + ".")
        if keywords else [],
        "parse_doc": doc_lines(f"Parses a whole {what} with this layout; a trailing LF or CR LF is allowed.", 92),
        "display_doc": "The command's words separated by single spaces; no line ending." if text else
        "The sentence text, checksum included unless it is `Checksum::None`; no line ending.",
        "selector": layout.selector,
        "text": text,
    }


def visit_lines(items: list[dict]) -> list[str]:
    """The body of a layout's `visit`: each item into the sink, optional ones while on the wire."""
    lines: list[str] = []
    for it in items:
        optional = it.get("optional")
        indent = 12 if optional else 8
        key = rust_str(it["field"].id if it.get("field") is not None else it["group"].id)
        method = {"keyword": "keyword", "values": "values", "texts": "texts", "entries": "entries"}.get(
            it["kind"], "field")
        value = it["word"] if it["kind"] == "keyword" else f"&self.{it['ident']}"
        call = fmt_call(indent, "", f"sink.{method}", [key, value], "?;")
        lines += [f"        if self.trailing >= {optional['index']} {{", *call, "        }"] if optional else call
    return lines


def json_const(items: list[dict]) -> list[str]:
    """`const JSON`: the JsonMember of each item (what reading decode's JSON back looks for)."""
    members: list[str] = []
    for it in items:
        if it["kind"] in ("values", "texts"):
            members.append(f"JsonMember::Values({rust_str(it['group'].id)}, {it['group'].fields[0].wire_width})")
        elif it["kind"] == "entries":
            pairs = ", ".join(f"({rust_str(f.id)}, {f.wire_width})" for f in it["group"].fields)
            members.append(f"JsonMember::Entries({rust_str(it['group'].id)}, &[{pairs}])")
        else:
            kind = "Optional" if it.get("optional") else "Field"
            members.append(f"JsonMember::{kind}({rust_str(it['field'].id)}, {it['field'].wire_width})")
    return fmt_const_slice(4, "const JSON: &'static [JsonMember]", members)


def fast_reader(sentence: Sentence, items: list[dict]) -> list[str]:
    """The body of a layout's fast reader (`read_fast`, see runtime/fast.rs): each member read
    into the default struct where it is."""
    lines = ["        self.talker = f.talker()?;"] if not sentence.is_proprietary else []
    lines.append("        self.checksum = Checksum::Upper;")
    for it in items:
        optional = it["optional"]
        if not optional:
            lines += it["fast"]
            continue
        lines += [f"        if extra >= {optional['wire']} {{", *it["fast"],
                  f"            self.trailing = {optional['index']};", "        }"]
    lines.append("        f.end()")
    return lines


def bits_doc(f: Field) -> list[str]:
    """A doc line linking a field to the bitfield that names its bits."""
    if f.bitfield is None:
        return []
    return [f"Named bits: [`{f.bitfield.camel}`](crate::bitfields::{f.bitfield.camel})."]


def shape_lines(sentence: Sentence, layout: Layout) -> list[str]:
    g = layout.group
    group = "None"
    if g is not None:
        group = fmt_struct(0, "", "Some(GroupShape", [("id", rust_str(g.id)), ("width", str(g.width)),
                                                        ("min", str(g.min)), ("max", str(g.max))], ")")[0]
    members = [("sentence", rust_str(sentence.id)), ("fixed", str(layout.fixed_count)),
               ("optional", str(layout.optional_count)), ("group", group)]
    return fmt_struct(4, "const SHAPE: Shape = ", "Shape", members, ";")


def derived_view(layout: Layout) -> list[dict]:
    """The sentence-level values of a layout with one position or one date and time (the model's
    position and calendar): each method's name, return type, docs and body."""
    out: list[dict] = []
    if layout.position:
        for name, f, negative in (("latitude", layout.position.lat, "south"),
                                  ("longitude", layout.position.lon, "west")):
            out.append({"name": name, "type": "Option<f64>", "body": f"self.{ident(f.id)}.map(f64::from)",
                        "doc": doc_lines(f"{f.name} in signed decimal degrees ({negative} negative).", 92)})
    if (c := layout.calendar):
        if c.date:
            body = f"DateTime::of_date(self.{ident(c.date.id)}?, self.{ident(c.time.id)}?)"
            parts = f"`{c.date.id}` (two-digit years 00–68 are 20yy, 69–99 19yy)"
        else:
            body = (f"DateTime::of_parts(self.{ident(c.year.id)}?, self.{ident(c.month.id)}?, "
                    f"self.{ident(c.day.id)}?, self.{ident(c.time.id)}?)")
            parts = f"`{c.day.id}`, `{c.month.id}`, `{c.year.id}`"
        out.append({"name": "datetime", "type": "Option<DateTime>", "body": body,
                    "doc": doc_lines(f"The UTC date and time of {parts} and `{c.time.id}`; `None` when a field is "
                                     "empty, for a day its month lacks or a leap second.", 92)})
    return out


def module_imports(views: list[dict]) -> list[str]:
    runtime = {"Checksum", "Error", "FieldSink", "Fields", "Framing", "JsonMember", "Layout", "Layouts", "Shape"}
    enums: set[str] = set()
    for view in views:
        if view["group"] is not None:
            runtime.add("GroupShape")
        if any(it["kind"] in ("values", "entries") for it in view["items"]):
            runtime |= {"Entries", "Reader"}
        if any(it["kind"] == "texts" for it in view["items"]):
            runtime.add("Texts")
        if view["entries"]:
            runtime |= {"Entry", "Reader"}
        if view["layout"].calendar:
            runtime.add("DateTime")
        if not view["text"] and view["fast_path"]:
            runtime |= {"FastReader", "Read"}
        fields = [it["field"] for it in view["items"] if it["kind"] == "field"]
        fields += [it["group"].fields[0] for it in view["items"] if it["kind"] == "values"]
        fields += [fv["field"] for e in view["entries"] for fv in e["fields"]]
        for f in fields:
            t = base_type(f)
            for name in ("Number", "Hex", "Time", "Date", "Coordinate", "CodeChars", "Code"):
                if t == name or t.startswith(name + "<"):
                    runtime.add(name)
            if f.field_type.numeric:
                runtime.add("Range")
                if f.min is not None or f.max is not None:
                    runtime.add("Bound")
            if f.enum is not None:
                enums.add(f.enum.camel)
    lines: list[str] = []
    if enums:
        lines += fmt_use("crate::enums", enums)
    lines += fmt_use("crate::runtime", runtime)
    lines += ["use crate::LayoutId;"]
    return lines


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
        "expected": fmt_const(4, "const EXPECTED: &'static str", rust_str(codes_expected(e, False))),
        "expected_chars": fmt_const(4, "const EXPECTED_CHARS: &'static str", rust_str(codes_expected(e, True))),
        "class": e.code_class.capitalize(),
        "all": fmt_const_slice(4, "const ALL: &'static [Self]", [f"Self::{v['name']}" for v in variants]),
    }


def hex_literal(value: int) -> str:
    """`0xABCD`, digits grouped by four from the right when longer (`0x8000_0000`)."""
    digits = f"{value:X}"
    groups = []
    while len(digits) > 4:
        groups.insert(0, digits[-4:])
        digits = digits[:-4]
    return "0x" + "_".join([digits, *groups])


def bitfield_view(b: BitfieldDef, on_integers: bool) -> dict:
    """`on_integers`: an integer field uses the bitfield (it then converts from a Number too)."""
    bits_type = next(f"u{n}" for n in (8, 16, 32, 64) if b.width <= n)
    type_bits = int(bits_type[1:])
    ranges = []
    constants = []
    for bits in b.bits:
        max_value = hex_literal(bits.max_value)
        full = bits.low == 0 and bits.width == type_bits
        if full:
            get, put = "self.0", "Self(value)"
        elif bits.low == 0:
            get = f"self.0 & {max_value}"
            put = f"Self((self.0 & !{hex_literal(bits.mask)}) | (value & {max_value}))"
        else:
            get = f"self.0 >> {bits.low}" if bits.high == type_bits - 1 else f"(self.0 >> {bits.low}) & {max_value}"
            put = f"Self((self.0 & !{hex_literal(bits.mask)}) | ((value & {max_value}) << {bits.low}))"
        label = f"Bit {bits.label}" if bits.width == 1 else f"Bits {bits.label}"
        name = ident(bits.id)
        ranges.append({
            "name": name, "setter": f"with_{bits.id}", "read": get, "write": put,
            "doc": doc_lines(f"{label} (`{bits.id}`): {bits.doc}", 92),
            "set_doc": doc_lines(f"The value with {label.lower()} (`{bits.id}`) set to `value` "
                                 f"(its low {bits.width} bit{'s' if bits.width > 1 else ''}).", 92),
        })
        for v in bits.values:
            constants.append({"name": bits_const(bits, v), "value": str(v.value),
                              "doc": doc_lines(f"`{bits.id}` = {v.value}: {v.doc}", 92)})
    return {
        "name": b.camel, "type": bits_type, "doc": doc_lines(f"{b.name} ({b.width} bits): {b.doc}"),
        "ranges": ranges, "constants": constants,
        "from_hex": "Self(hex.value)" if bits_type == "u64" else f"Self(hex.value as {bits_type})",
        "from_number": f"Self(number.trunc() as {bits_type})" if on_integers else None,
    }


ENCODINGS = {"hex": "Hex", "decimal": "Decimal", "decimal_list": "DecimalList", "text": "Text"}


def table_view(t: TableDef) -> dict:
    def opt(value: object, render=None) -> str:
        if value is None:
            return "None"
        return f"Some({render(value) if render else value})"

    parameters = []
    for prm in t.parameters:
        links = []
        if prm.enum is not None:
            links.append(f"Values: [`{prm.enum.camel}`](crate::enums::{prm.enum.camel}).")
        if prm.bitfield is not None:
            links.append(f"Bits: [`{prm.bitfield.camel}`](crate::bitfields::{prm.bitfield.camel}).")
        title = prm.name + (f" [{prm.unit}]" if prm.unit else "")
        effect = f" Takes effect {prm.takes_effect}." if prm.takes_effect else ""
        members = [
            ("number", str(prm.number)),
            ("id", rust_str(prm.id)),
            ("name", rust_str(prm.name)),
            ("encoding", f"Encoding::{ENCODINGS[prm.encoding]}"),
            ("size", opt(prm.size)),
            ("count", opt(prm.count)),
            ("min", opt(prm.min, bound)),
            ("max", opt(prm.max, bound)),
            ("max_length", opt(prm.max_length)),
            ("default", opt(prm.default, lambda v: rust_str(str(v)))),
            ("unit", opt(prm.unit, rust_str)),
            ("enum_id", opt(prm.enum_id, rust_str)),
            ("bitfield_id", opt(prm.bitfield_id, rust_str)),
        ]
        parameters.append({
            "name": parameter_const(prm),
            "doc": doc_lines(f"{prm.number}, {title}: {prm.doc}{effect}", 92) + links,
            "members": [f"        {k}: {v}," for k, v in members],
        })
    names = [prm["name"] for prm in parameters]
    return {
        "table": t, "module": ident(t.id), "const": t.id.upper(), "doc": doc_lines(f"{t.name}: {t.doc}"),
        "parameters": parameters,
        "head": table_head(t, names),
    }


def table_head(t: TableDef, names: list[str]) -> list[str]:
    """`pub const TABLE: Table = Table { … };`."""
    members = [("id", rust_str(t.id)), ("name", rust_str(t.name)), ("parameters", "&[" + ", ".join(names) + "]")]
    return fmt_struct(4, "pub const TABLE: Table = ", "Table", members, ";")


def command_example(spec: Spec) -> dict | None:
    """The builder example of lib.rs: the first command (one with a keyword, framed with `$`,
    preferred) that a default struct builds, and the bytes it makes."""
    layouts = [(s, lay) for s in spec.proprietary if s.kind == "command" for lay in s.layouts
               if lay.group is None or lay.group.min == 0]
    layouts.sort(key=lambda p: (p[0].framing != "sentence", p[1].selector is None))
    if not layouts:
        return None
    s, lay = layouts[0]
    texts: list[str] = []
    for item in lay.items:
        if isinstance(item, Group) or item.is_optional:
            continue
        texts += [item.value or ""] if item.field_type.keyword else [""] * item.wire_width
    if s.framing == "text":
        line = " ".join([s.address or "", *texts])
    else:
        body = ",".join([s.address or "", *texts])
        sum_ = 0
        for ch in body:
            sum_ ^= ord(ch)
        line = f"${body}*{sum_:02X}"
    return {"layout": s.layout_camel(lay), "bytes": "b" + rust_str(line)[:-1] + '\\r\\n"'}




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


def fix_value(fix: FixField, value: str) -> str:
    """The conversion of a field's value (`value`, a Rust expression) to its fact's, by the field's
    type and the fact's (runtime/rust/src/fixes.rs)."""
    f, fact = fix.field, fix.fact
    if f.type in ("time", "date"):
        return f"fixes::{f.type}({value})"
    if f.type in ("latitude", "longitude"):
        return f"fixes::degrees({value})"
    if f.type == "enum_chars":
        return f"fixes::first_mode({value})"
    if f.type == "enum":
        values = fact.values_of(f)
        if values is None:
            return f"fixes::id({value})"
        pairs = ", ".join(f"({rust_str(k)}, {rust_str(v)})" for k, v in values.items())
        return f"fixes::mapped({value}, &[{pairs}])"
    if f.type in ("integer", "decimal"):
        return f"fixes::real({value}, {float(fact.scale(f))!r})" if "decimal" in fact.types else f"fixes::whole({value})"
    raise ValueError(f"{f.id}: no Rust conversion of a {f.type} field to fact {fact.id}")


def fix_arm(s: Sentence, layout: Layout, gate: str) -> list[str]:
    """The match arm of one layout in `FixSource for Sentence`: its facts read into a `Facts`."""
    fixes = layout.fix_fields
    carried = ", ".join(rust_str(fact) for fact in dict.fromkeys(fix.fact.id for fix in fixes))
    lines = [f"Self::{s.layout_camel(layout)}(s) => {{", f"let mut f = Facts::of(s, &[{carried}]);"]
    lines += [f"f.{fix.fact.id} = {fix_value(fix, f's.{ident(fix.field.id)}')};" for fix in fixes if fix.group is None]
    group = next((fix.group for fix in fixes if fix.group is not None), None)
    if group is not None:
        entry = [fix for fix in fixes if fix.group is group]
        members = [f"{fix.fact.id}: {fix_value(fix, 'e' if group.single else f'e.{ident(fix.field.id)}')}"
                   for fix in entry]
        lines.append(f"f.entries = s.{ident(group.id)}.iter().map(|e| fixes::EntryFacts {{ {', '.join(members)}, "
                     "..fixes::EntryFacts::default() }).collect();")
    return with_cfg(0, gate, lines + ["Some(f)", "}"])


def fix_fields(spec: Spec, env: jinja2.Environment, gates: Gates) -> str:
    """src/fix_fields.rs: the generated `Sentence` read as the facts of a fix (spec/fix.yaml)."""
    sources = sorted({*spec.fix_sources, *(f for s, _ in spec.fix_layouts for f in s.files)})
    arms = [line for s, layout in spec.fix_layouts for line in fix_arm(s, layout, gates.sentence(s))]
    return env.get_template("rust/fix_fields.rs.j2").render(
        header=header(spec, "//", ["templates/rust/fix_fields.rs.j2", *sources]), arms=arms, crate=CRATE,
        example=spec.fix_examples[0] if spec.fix_examples else None,
        talkers=", ".join(f"({rust_str(k)}, {rust_str(v)})" for k, v in spec.talker_systems.items()),
        satellite_ids=", ".join(f"({rust_str(g)}, {low}, {high})" for g, low, high in spec.satellite_ids),
        combined_talker=f"Some({rust_str(spec.combined_talker)})" if spec.combined_talker else "None")


def frame_message_arms(spec: Spec) -> list[tuple[str, str, str]]:
    """json::write_frame_message's arms, one per protocol whose messages the crate types: the
    protocol's `Protocol` variant, its name in the JSON and how its module decodes a frame (an
    RTCM 3 frame's payload sits between its 3-byte header and its CRC)."""
    arms = [(p.capitalize(), p, f"crate::{p}_messages::Message::from_frame(frame)") for p in typed_natively(spec)]
    if spec.bit_messages:
        arms.append(("Rtcm3", "rtcm3", "crate::rtcm3_messages::Message::from_payload("
                                       "frame.get(3..frame.len().saturating_sub(3)).unwrap_or_default())"))
    return sorted(arms)


def untyped_protocols(spec: Spec) -> str:
    """The framed protocols json::write_frame_message does not type, for its doc (\"\" if none)."""
    typed = {*typed_natively(spec), *(["rtcm3"] if spec.bit_messages else [])}
    names = [p.name for p in spec.protocols if p.id not in typed]
    return f" ({', '.join(names)})" if names else ""


def emit(spec: Spec, env: jinja2.Environment) -> dict[str, str]:
    env.globals.update(rust_str=rust_str, rust_raw=rust_raw, one_line=one_line)
    base = "rust"
    files: dict[str, str] = {}
    for module in RUNTIME_MODULES:
        files[f"{base}/src/runtime/{module}.rs"] = runtime_file(spec, "//", f"rust/src/{module}.rs", blank_line=True)
    files[f"{base}/src/bin/nmea-rs.rs"] = runtime_file(spec, "//", "rust/crate/bin/nmea-rs.rs", blank_line=True)
    files[f"{base}/tests/fast_path.rs"] = runtime_file(spec, "//", "rust/crate/tests/fast_path.rs", blank_line=True)
    files[f"{base}/tests/values.rs"] = runtime_file(spec, "//", "rust/crate/tests/values.rs", blank_line=True)
    files[f"{base}/tests/tag_blocks.rs"] = runtime_file(spec, "//", "rust/crate/tests/tag_blocks.rs", blank_line=True)
    files[f"{base}/tests/ais.rs"] = runtime_file(spec, "//", "rust/crate/tests/ais.rs", blank_line=True)
    files[f"{base}/tests/assembly.rs"] = runtime_file(spec, "//", "rust/crate/tests/assembly.rs", blank_line=True)
    if spec.binary:
        files[f"{base}/tests/ubx.rs"] = runtime_file(spec, "//", "rust/crate/tests/ubx.rs", blank_line=True)

    gates = Gates(spec)
    layouts = []
    for s in spec.sentences:
        views = [layout_view(spec, s, lay) for lay in s.layouts]
        gate = gates.sentence(s)
        enum_files = sorted({f.enum.origin.file for lay in s.layouts for f in lay.all_fields if f.enum})
        bitfield_files = sorted({f.bitfield.origin.file for lay in s.layouts for f in lay.all_fields if f.bitfield})
        module_file = sentence_module(s).removeprefix("r#")
        files[f"{base}/src/sentences/{module_file}.rs"] = env.get_template("rust/sentence.rs.j2").render(
            header=header(spec, "//", [*s.files, *enum_files, *bitfield_files]), sentence=s, doc=doc_lines(s.doc),
            layouts=views, imports=module_imports(views))
        for view in views:
            name = view["name"]
            reply_names = [r.layout_camel(lay) for r in s.replies for lay in r.layouts]
            parse_arm = with_cfg(12, gate, fmt_arm(
                12, f"Self::{name}", f"{name}::parse_fields(fields, checksum).map(Sentence::{name})"))
            fast_arm = with_cfg(8, gate, fmt_arm(8, f"LayoutId::{name}", f"read_layout::<LayoutId, {name}, O>(fields, line, rest)"))
            layouts.append({
                "sentence": s, "name": name, "layout": view["layout"], "title": view["title"], "type": view["type"],
                "main": s.layout_camel(s.layout),
                "same_as_main": s.same_as_main(view["layout"]) if view["layout"].id else [],
                "encapsulates": s.encapsulates if (s.encapsulates or {}).get("protocol") == "ais" else None,
                "layout_sentence": rust_str(s.id),
                "lifetime": view["lifetime"], "kind": camel(s.kind), "parse_arm": parse_arm, "fast_arm": fast_arm, "cfg": gate,
                "reads_first": view["reads_first"] is not None,
                "framing_arm": with_cfg(12, gate, fmt_arm(12, f"Self::{name}", framing_expr(s))),
                "replies_arm": with_cfg(12, gate, fmt_slice(12, f"Self::{name} => ", [f"Self::{r}" for r in reply_names],
                                                            ",")),
            })
    modules = [{"sentence": s, "module": sentence_module(s), "cfg": gates.sentence(s), "uses": fmt_use(
        sentence_module(s), {s.layout_camel(lay) for lay in s.layouts}, "pub use")} for s in spec.sentences]
    # rustfmt sorts `mod` items by the name without `r#`, `use` items by the path as written.
    files[f"{base}/src/sentences/mod.rs"] = env.get_template("rust/sentences_mod.rs.j2").render(
        header=header(spec, "//"), sentences=sorted(modules, key=lambda m: m["module"].removeprefix("r#")),
        uses=sorted(modules, key=lambda m: m["module"]))
    files[f"{base}/src/enums.rs"] = env.get_template("rust/enums.rs.j2").render(
        header=header(spec, "//", [e.origin.file for e in spec.enums]), enums=[{**enum_view(e), "cfg": gates.enum(e.id)} for e in spec.enums])
    files[f"{base}/src/bitfields.rs"] = env.get_template("rust/bitfields.rs.j2").render(
        header=header(spec, "//", [b.origin.file for b in spec.bitfields]),
        bitfields=[{"cfg": gates.bitfield(b.id)} | bitfield_view(b, any(f.bitfield is b and f.field_type.numeric for s in spec.sentences
                                        for lay in s.layouts for f in lay.all_fields))
                   for b in spec.bitfields],
        uses_numbers=any(f.bitfield is not None and f.field_type.numeric for s in spec.sentences
                         for lay in s.layouts for f in lay.all_fields),
        hex_cfg=gates.union([gates.bitfield(b.id) for b in spec.bitfields]),
        number_cfg=gates.union([gates.bitfield(f.bitfield.id) for s in spec.sentences for lay in s.layouts
                                for f in lay.all_fields if f.bitfield is not None and f.field_type.numeric]))
    files[f"{base}/src/tables.rs"] = env.get_template("rust/tables.rs.j2").render(
        header=header(spec, "//", [t.origin.file for t in spec.tables]), tables=[{**table_view(t), "cfg": gates.table(t.id)} for t in spec.tables],
        imports=fmt_use("crate::runtime", {"Encoding", "Parameter", "Table"} | (
            {"Bound"} if any(p.min is not None or p.max is not None for t in spec.tables for p in t.parameters)
            else set())) if spec.tables else [])
    files[f"{base}/src/fix_fields.rs"] = fix_fields(spec, env, gates)
    vectors = emit_vectors.example_vectors(spec)
    intact = [v for v in vectors if v["line"]]
    first = None
    candidates = [v for v in intact if v["sentence"] == "GGA"] or [
        v for v in intact if not spec.sentence(v["sentence"]).is_proprietary]
    if candidates:
        v = max(candidates, key=lambda v: sum(1 for t in v["line"].split("*")[0].split(",") if t))
        s = spec.sentence(v["sentence"])
        lay = next(lay for lay in s.layouts if lay.id == v["variant"])
        filled = [f for f in lay.fields if not f.is_optional and not f.field_type.keyword
                  and json.loads(v["decode"])["fields"].get(f.id)]
        if filled:
            first = {"line": v["line"], "layout": s.layout_camel(lay), "var": ident(s.id.lower()),
                     "talker": v["line"][1:3], "field": ident(filled[0].id)}
    unit_examples: list[str] = []
    for lay in layouts:
        found = next((v for v in intact if v["sentence"] == lay["sentence"].id
                      and v["variant"] == lay["layout"].id), None)
        if found:
            unit_examples += with_cfg(8, lay["cfg"], fmt_tuple(8, [rust_raw(found["line"]), rust_raw(found["decode"])], ","))
    # Proprietary `$` addresses: those that look standard (GeoS-5's GPSGG) are looked up before the
    # standard sentences, the others on their own.
    proprietary_arms: list[str] = []
    standard_like_arms: list[str] = []
    proprietary_fast_arms: list[str] = []
    standard_like_fast_arms: list[str] = []
    for address in sorted({s.address for s in spec.proprietary if s.framing == "sentence" and s.address}):
        owners = spec.by_address(address)
        names = [s.layout_camel(lay) for s, lay in owners]
        standard_like = len(address) == 5 and not address.startswith("P")
        arms = standard_like_arms if standard_like else proprietary_arms
        indent = 12 if standard_like else 8
        gate = cfg({s.vendor for s, _ in owners if s.vendor})
        arms += with_cfg(indent, gate,
                         fmt_slice(indent, f"b{rust_str(address)} => ", [f"LayoutId::{n}" for n in names], ","))
        fast_arms = standard_like_fast_arms if standard_like else proprietary_fast_arms
        fast_arms += with_cfg(indent, gate, fmt_fast_arm(indent, f"b{rust_str(address)}", names))
    standard_arms: list[str] = []
    encapsulated_arms: list[str] = []
    standard_fast_arms: list[str] = []
    for s in spec.standard:
        arm = fmt_slice(8, f'b"{s.id}" => ', [f"LayoutId::{s.layout_camel(lay)}" for lay in s.layouts], ",")
        if s.start == "!":  # the fast path reads `$` sentences only
            encapsulated_arms += arm
            continue
        standard_arms += arm
        if s.fast_path:
            standard_fast_arms += fmt_fast_arm(8, f'b"{s.id}"', [s.layout_camel(lay) for lay in s.layouts])
    text_commands = []
    for word in sorted({(s.address or "").upper() for s in spec.proprietary if s.framing == "text"}):
        owners = spec.text_command(word)
        names = [s.layout_camel(lay) for s, lay in owners]
        text_commands.append({"word": word, "cfg": cfg({s.vendor for s, _ in owners if s.vendor}),
                              "lines": fmt_slice(8, "return ", [f"LayoutId::{n}" for n in names], ";")})
    # Text commands compile with their receivers' features; without them, a fallback finds none.
    text_cfg = cfg(None if not text_commands or any(not t["cfg"] for t in text_commands) else
                   {s.vendor for s in spec.proprietary if s.framing == "text" and s.vendor})
    reply_arms, outcome_arms = reply_pairing_arms(spec)
    files[f"{base}/src/lib.rs"] = env.get_template("rust/lib.rs.j2").render(
        header=header(spec, "//"), spec=spec, layouts=layouts, example=first, command=command_example(spec),
        unit_examples=unit_examples, proprietary_arms=proprietary_arms, standard_arms=standard_arms,
        encapsulated_arms=encapsulated_arms,
        standard_like_arms=standard_like_arms, standard_fast_arms=standard_fast_arms,
        has_query=any(s.id == QUERY for s in spec.standard),
        proprietary_fast_arms=proprietary_fast_arms, standard_like_fast_arms=standard_like_fast_arms,
        text_commands=text_commands, reply_arms=reply_arms, outcome_arms=outcome_arms,
        tag_codes=[f"TagCode {{ code: {rust_str(c.code)}, id: {rust_str(c.id)}, name: {rust_str(c.name)}, "
                   f"kind: TagType::{TAG_TYPES[c.type]} }}," for c in spec.tag_codes],
        runtime_uses=fmt_use("runtime", {"read_layout", "Decoded", "FastReader", "Layouts", "Outcome"}),
        binary_protocols=typed_natively(spec), frame_arms=frame_message_arms(spec),
        untyped=untyped_protocols(spec),
        text_cfg=text_cfg, text_not_cfg=text_cfg.replace("#[cfg(", "#[cfg(not(", 1)[:-1] + ")]" if text_cfg else "",
        all_layouts=["    pub const ALL: &'static [Self] = &[",
                     *[line for lay in layouts for line in with_cfg(8, lay["cfg"], [f"        Self::{lay['name']},"])],
                     "    ];"])
    files[f"{base}/Cargo.toml"] = env.get_template("rust/Cargo.toml.j2").render(
        header=header(spec, "#", ["templates/rust/Cargo.toml.j2"]), crate=CRATE, vendors=gates.features,
        extras=message_features(spec), ubx=bool(spec.binary))
    files[f"{base}/README.md"] = package_readme(spec, env, "rust/README.md.j2", crate=CRATE)
    files[f"{base}/rustfmt.toml"] = runtime_file(spec, "#", "rust/rustfmt.toml", blank_line=True)
    files[f"{base}/tests/examples.rs"] = env.get_template("rust/examples.rs.j2").render(
        header=header(spec, "//"), vectors=[{"rust": example_lines(v), "cfg": gates.sentence(spec.sentence(v["sentence"]))} for v in vectors],
        crate=CRATE, reply_cases=reply_case_lines(spec, gates))
    return rustfmt(files)


def message_features(spec: Spec) -> list[str]:
    """The crate's features beside the receivers': the modules of messages inside a sentence's
    payload or a binary frame, which a user who reads sentences only leaves out of the build."""
    return [name for name, present in (("ais", spec.payloads), ("binary", spec.binary or spec.config_keys or spec.bit_messages)) if present]


# The runtime's TagType of each value type of spec/tag_block.yaml.
TAG_TYPES = {"integer": "Integer", "group": "Group", "text": "Text"}


def rustfmt(files: dict[str, str]) -> dict[str, str]:
    """`files` with every .rs file as rustfmt writes it under the crate's rustfmt.toml (so that
    `cargo fmt --check` passes by construction): one rustfmt process over the files it has not
    formatted before, in a temporary directory. What rustfmt wrote is kept in the generator's cache
    by the digest of rustfmt's version, its configuration and the file, so that generating again
    (make check, the tests, a firmware build) runs rustfmt only on the files that changed."""
    sources = [path for path in files if path.endswith(".rs")]
    identity = _rustfmt_identity()
    digests = {path: hashlib.sha256(identity + files[path].encode("utf-8")).hexdigest() for path in sources}
    formatted = {path: data.decode("utf-8") for path in sources if (data := cache.read(f"rustfmt/{digests[path]}"))}
    todo = [path for path in sources if path not in formatted]
    if not todo:
        return files | formatted
    with tempfile.TemporaryDirectory() as tmp:
        for path in sources:  # every file: a `mod` names its file, formatted or not
            (Path(tmp) / path).parent.mkdir(parents=True, exist_ok=True)
            (Path(tmp) / path).write_text(formatted.get(path, files[path]), encoding="utf-8")
        command = ["rustfmt", "--edition", "2021", "--config-path", str(RUSTFMT_CONFIG), "--config", "skip_children=true",
                   *todo]
        run = subprocess.run(command, cwd=tmp, capture_output=True, text=True)
        if run.returncode != 0:
            raise SystemExit(f"generator: rustfmt failed on the generated Rust:\n{run.stderr}")
        for path in todo:
            formatted[path] = (Path(tmp) / path).read_text(encoding="utf-8")
            cache.write(f"rustfmt/{digests[path]}", formatted[path].encode("utf-8"))
    return files | formatted


RUSTFMT_CONFIG = RUNTIME / "rust" / "rustfmt.toml"


@functools.cache
def _rustfmt_identity() -> bytes:
    """What rustfmt's output depends on besides the file: its version and the configuration."""
    try:
        version = subprocess.run(["rustfmt", "--version"], capture_output=True, check=True).stdout
    except (FileNotFoundError, subprocess.CalledProcessError):
        raise SystemExit("generator: rustfmt is missing; install it with `rustup component add rustfmt`") from None
    return version + RUSTFMT_CONFIG.read_bytes() + b"\0"
