"""Rust emitter of the bit messages told by a number (spec/binary/rtcm3/messages): the module
`rtcm3_messages` of the generated crate, a struct per layout with straight-line `read`, `write`
and JSON code over the bit layouts' one reader and writer (runtime/rust/src/ais.rs, over a
payload's bytes) and RTCM 3's frame, groups and characters (runtime/rust/src/rtcm3.rs), and the
`Message` enum that dispatches on the message number.

emit_rust_ais's records, with what RTCM 3 adds: a width counted by another field (characters,
the MSM cell mask), groups counted by a field or by the bits set in mask fields (an
`rtcm3::Group` of the layout's maximum, no heap), field-major groups (each field for every entry
in turn), sign-magnitude numbers (the raw integer kept, its negative zero `1 << (bits - 1)`, the
special value `negative_zero`), ISO 8859-1 and UTF-8 characters as views of the payload."""

from __future__ import annotations

import re

import jinja2

from .emit import header, runtime_file
from .emit_python_rtcm3 import title as title_of
from .emit_rust import rust_str, rustfmt
from .emit_rust_ais import _as_i64, _int_type, _labelled, _Record, _read_fn
from .model import Ones, Payload, PayloadField, PayloadGroup, Spec, camel

CHARS = {"latin1": False, "utf8": True}   # the character types, and whether their bytes are UTF-8


def raw_member(f: PayloadField) -> bool:
    """Whether the member holds a raw integer read through an accessor (`<id>_raw`)."""
    return f.scaled or f.type == "smag"


def member_name(f: PayloadField) -> str:
    return f"{f.id}_raw" if raw_member(f) else f.id


def plain_type(f: PayloadField) -> str:
    """The Rust type of a field's member."""
    if f.type in CHARS:
        return "rtcm3::Chars<'a>"
    if f.type == "data" or f.bits is None:
        return "ais::Bits<'a>"
    if f.type == "smag":
        return "i64"   # its negative zero, 1 << (bits - 1), is no number of its width
    if f.type == "bool":
        return "bool"
    return _int_type(f.bits, f.type == "int")


def count_of(count: str | Ones, owner: str) -> str:
    """A count as a usize expression over the members of `owner` (`m` reading, `self` writing)."""
    if isinstance(count, Ones):
        ones = [f"{owner}.{name}.count_ones() as usize" for name in count.fields]
        return ones[0] if len(ones) == 1 else " * ".join(f"({one})" for one in ones)
    return f"{owner}.{count} as usize"


def unit_bits(f: PayloadField) -> int:
    return 8 if f.type in CHARS else 1


class Record(_Record):
    """The code of one RTCM 3 layout's struct (a message, or a group's entry)."""

    def _walk(self, items: list, rest: list, certain: bool) -> bool:
        """As emit_rust_ais's, but what follows a choice stays certain: every case ends where the
        bits say (no optional fields end an RTCM 3 layout)."""
        for i, item in enumerate(items):
            following = items[i + 1:] + rest
            if isinstance(item, PayloadField):
                assert not item.optional, f"{item.id}: RTCM 3 layouts have no optional fields"
                self._field(item, following, certain)
            elif isinstance(item, PayloadGroup):
                self._group(item, following)
            else:
                self._choice(item, following)
        return certain

    def _field(self, f: PayloadField, following: list, certain: bool) -> None:
        """A field's member, read, write and JSON; one in a case of a choice (not `certain`) is
        an Option, None when the message's case has no such field."""
        name, kind, width, key = member_name(f), plain_type(f), f.bits, rust_str(f.id)
        if certain:
            self.certain.add(name)
        self.members.append(f"/// {f.name}{f' [{f.unit}]' if f.unit else ''}{f' ({f.ref})' if f.ref else ''}.\n"
                            f"pub {name}: {kind if certain else f'Option<{kind}>'},")
        if f.count is not None:
            self.read.append(f"let units = {count_of(f.count, 'm')};")
            read = f"r.take_bits({'units' if unit_bits(f) == 1 else f'units * {unit_bits(f)}'}, {key})?"
        elif width is None:
            read = f"r.take_bits(r.remaining(), {key})?"
        elif f.type == "smag":
            read = f"r.take_smag({width}, {key})?"
        elif f.type == "int":
            read = f"r.take_signed({width}, {key})?" + ("" if kind == "i64" else f" as {kind}")
        elif f.type == "bool":
            read = f"r.take({width}, {key})? == 1"
        elif kind == "ais::Bits<'a>" or f.type in CHARS:
            read = f"r.take_bits({width}, {key})?"
        else:
            read = f"r.take({width}, {key})?" + ("" if kind == "u64" else f" as {kind}")
        if f.type in CHARS:
            read = f"rtcm3::Chars::new({read})"
        self.read.append(f"m.{name} = {read if certain else f'Some({read})'};")
        value = (f"self.{name}" if certain else "v") + (".bits()" if f.type in CHARS else "")
        if f.count is not None:
            put = f"w.put_counted({value}, {count_of(f.count, 'self')}, {unit_bits(f)}, {key})?;"
        elif kind in ("ais::Bits<'a>", "rtcm3::Chars<'a>"):
            put = f"w.put_bits({value}, {key})?;"
        elif f.type == "smag":
            put = f"w.put_smag({value}, {width}, {key})?;"
        elif f.type == "int":
            put = f"w.put_signed({value if kind == 'i64' else f'i64::from({value})'}, {width}, {key})?;"
        else:
            put = f"w.put({value if kind == 'u64' else f'u64::from({value})'}, {width}, {key})?;"
        self.write.append(put if certain else f"let Some(v) = self.{name} else {{ return Err(w.missing({key})); }}; {put}")
        line = self._json_line(f, f"self.{name}" if certain else "v", f"self.{f.id}()" if certain else "reading")
        if not certain:
            line = (f"if let (Some(v), Some(reading)) = (self.{name}, self.{f.id}()) {{ {line} }}" if raw_member(f)
                    else f"if let Some(v) = self.{name} {{ {line} }}")
        self.json.append(line)
        if raw_member(f):
            self.accessors.append(self._reading_accessor(f, certain))

    def _specials(self, f: PayloadField) -> str:
        specials = [(s.raw, s.id) for s in f.special]
        if f.type == "smag":
            specials.insert(0, (1 << (f.bits - 1), "negative_zero"))
        return ", ".join(f"({raw}, {rust_str(id_)})" for raw, id_ in specials)

    def _reading(self, f: PayloadField) -> tuple[str, str]:
        raw = _as_i64(plain_type(f), "raw")
        if f.divisor is not None or isinstance(f.base, float):
            return (f"ais::scaled({raw}, {float(f.divisor or 1)!r}, {float(f.base or 0)!r}, &[{self._specials(f)}])",
                    "ais::Reading<f64>")
        return f"ais::counted({raw}, {int(f.base or 0)}, &[{self._specials(f)}])", "ais::Reading<i64>"

    def _reading_accessor(self, f: PayloadField, certain: bool) -> str:
        body, result = self._reading(f)
        extra = " (negative_zero: the sign bit alone)" if f.type == "smag" else ""
        doc = f"/// {f.name}{f' [{f.unit}]' if f.unit else ''}, or its special value{extra}."
        if certain:
            return f"{doc}\npub fn {f.id}(&self) -> {result} {{ let raw = self.{f.id}_raw; {body} }}"
        return f"{doc}\npub fn {f.id}(&self) -> Option<{result}> {{ self.{f.id}_raw.map(|raw| {body}) }}"

    def _json_line(self, f: PayloadField, value: str, reading: str) -> str:
        key = rust_str(f.id)
        if f.type == "smag" and not f.scaled:   # the raw integer beside a special value only
            return (f"match {reading} {{ ais::Reading::Value(v) => j.int({key}, v)?, "
                    f"special => j.reading({key}, special, {rust_str(f.id + '_raw')}, {value})?, }}")
        if raw_member(f):
            return f"j.reading({key}, {reading}, {rust_str(f.id + '_raw')}, {_as_i64(plain_type(f), value)})?;"
        if f.type in CHARS:
            return f"rtcm3::write_json_chars(j.key({key})?, {value}, {'true' if CHARS[f.type] else 'false'})?;"
        if f.type == "bool":
            return f"j.flag({key}, {value})?;"
        if plain_type(f) == "ais::Bits<'a>":
            return f"j.text({key}, {value})?;"
        return f"j.int({key}, {value})?;"

    def _group(self, g: PayloadGroup, following: list) -> None:
        assert g.count is not None and not isinstance(g.count, int), f"{g.id}: an RTCM 3 group is counted"
        entry = Record(self.name + camel(g.id[:-1] if g.id.endswith("s") else g.id + "_entry"), g.fields)
        self.entries.append(entry)
        key = rust_str(g.id)
        said = ("the bits set in " + " x ".join(g.count.fields)) if isinstance(g.count, Ones) else g.count
        order = ", sent field by field" if g.field_major else ""
        self.members.append(f"/// {g.name}: as many entries as {said} says (at most {g.max}){order}.\n"
                            f"pub {g.id}: rtcm3::Group<{entry.name}, {g.max}>,")
        self.read.append(f"let count = r.counted({count_of(g.count, 'm')}, {g.max}, {g.entry_width}, {key})?;")
        self.read.append(f"m.{g.id} = rtcm3::Group::with_len(count);")
        if isinstance(g.count, Ones):
            self.write.append(f"if self.{g.id}.len() != {count_of(g.count, 'self')} {{ "
                              f"return Err(w.entries_error(self.{g.id}.len(), {count_of(g.count, 'self')}, {key})); }}")
        if g.field_major:
            for line in entry.read:
                simple = re.fullmatch(r"m\.(\w+) = (.*);", line)
                assert simple is not None, line
                self.read.append(f"for e in m.{g.id}.as_mut_slice() {{ e.{simple[1]} = {simple[2]}; }}")
            for line in entry.write:
                self.write.append(f"for e in self.{g.id}.iter() {{ {line.replace('self.', 'e.')} }}")
        else:
            self.read.append(f"for e in m.{g.id}.as_mut_slice() {{ *e = {entry.name}::read(r)?; }}")
            self.write.append(f"for e in self.{g.id}.iter() {{ e.write(w)?; }}")
        self.json.append(f"{{ let out = j.key({key})?; out.write_char('[')?;"
                         f"for (i, entry) in self.{g.id}.iter().enumerate() {{"
                         f"if i > 0 {{ out.write_char(',')?; }} let mut e = ais::JsonObject::new(out)?;"
                         f"entry.json_members(&mut e)?; e.finish()?; }} out.write_char(']')?; }}")


def record_code(record: Record, message: bool, doc: str) -> str:
    """The struct, its accessors and its read/write/JSON code."""
    members = list(record.members)
    if message:
        members.append("/// Bits after the layout's last field, as sent (the padding to a whole byte).\n"
                       "pub trailing: ais::Bits<'a>,")
    uses_a = message or any("'a" in m for m in members)
    lifetime = "<'a>" if uses_a else ""
    out = [doc, "#[derive(Clone, Copy, Debug, Default)]", f"pub struct {record.name}{lifetime} {{", *members, "}", ""]
    reads = record.read + (["m.trailing = r.rest();"] if message else [])
    out += [f"impl{lifetime} {record.name}{lifetime} {{", *record.accessors,
            _read_fn(reads, False, len(members), "'a" if uses_a else "'_"),
            "/// Writes the layout's fields to `w`.\n"
            f"pub fn write(&self, w: &mut rtcm3::Writer) -> Result<(), ais::AisError> {{ "
            f"{_labelled('write', record.write, False)}"
            + (" w.put_bits(self.trailing, \"trailing\")?;" if message else "") + " Ok(()) }",
            "/// The members of its decoded JSON (those of generated/vectors/rtcm3.jsonl), in order.\n"
            "pub fn json_members<W: fmt::Write>(&self, j: &mut ais::JsonObject<'_, W>) -> fmt::Result {"
            + " ".join(record.json)
            + (" j.text(\"trailing\", self.trailing)?;" if message else "")
            + " Ok(()) }", "}", ""]
    return "\n".join(out)


def number_pattern(numbers: list[int]) -> str:
    """The match pattern of a layout's message numbers: a range when they follow each other."""
    if len(numbers) > 2 and numbers == list(range(numbers[0], numbers[-1] + 1)):
        return f"{numbers[0]}..={numbers[-1]}"
    return " | ".join(map(str, numbers))


def emit(spec: Spec, env: jinja2.Environment) -> dict[str, str]:
    messages: list[Payload] = [m for m in spec.bit_messages if m.protocol == "rtcm3"]
    if not messages:
        return {}
    blocks: list[str] = []
    for payload in messages:
        record = Record(payload.camel, payload.items)
        for entry in record.entries:
            blocks.append(record_code(entry, False, f"/// One entry of {entry.name}."))
        blocks.append(record_code(record, True, f"/// {title_of(payload)}"))
    sources = [m.origin.file for m in messages]
    tests = {"rust/tests/rtcm3/mod.rs": runtime_file(spec, "//", "rust/crate/tests/rtcm3/mod.rs", blank_line=True)}
    return tests | rustfmt({"rust/src/rtcm3_messages.rs": env.get_template("rust/rtcm3_messages.rs.j2").render(
        header=header(spec, "//", ["templates/rust/rtcm3_messages.rs.j2", *sources]), blocks=blocks,
        messages=messages, number_pattern=number_pattern)})
