"""Rust emitter of the bit-packed payloads (spec/ais/messages, spec/ais/applications): the module
`ais_messages` of the generated crate, a struct per layout with straight-line `read`, `write` and
JSON code over the runtime's bit reader and writer (runtime/rust/src/ais.rs), and the `Message`
and `Application` enums that dispatch on the message type and on DAC/FI.

A field that is always there is a plain member; one that may be missing (optional, after an
optional one, or in a case of a choice) is an Option. A number with a divisor, a base or special
values keeps its raw integer (`<id>_raw`) and has an accessor giving its `Reading`; an enum keeps its
raw code and has an accessor giving the enum's value."""

from __future__ import annotations

import re

import jinja2

from .emit import header
from .emit_rust import rust_str, rustfmt
from .emit_python_ais import title as title_of
from .model import Payload, PayloadChoice, PayloadField, PayloadGroup, Spec, camel

from .reference_ais import after


def _int_type(bits: int, signed: bool) -> str:
    size = next(n for n in (8, 16, 32, 64) if bits <= n)
    return f"{'i' if signed else 'u'}{size}"


def _is_float(f: PayloadField) -> bool:
    return f.divisor is not None or isinstance(f.base, float)


def _raw_member(f: PayloadField) -> bool:
    """Whether the member holds a raw integer read through an accessor (`<id>_raw`)."""
    return f.scaled or f.enum is not None


def _as_i64(kind: str, value: str) -> str:
    return value if kind == "i64" else f"{value} as i64" if kind == "u64" else f"i64::from({value})"


def _reading(f: PayloadField, raw: str) -> tuple[str, str]:
    """The expression of a number's Reading from its raw integer (an i64 expression), and its type."""
    specials = ", ".join(f"({s.raw}, {rust_str(s.id)})" for s in f.special)
    if _is_float(f):
        return f"ais::scaled({raw}, {float(f.divisor or 1)!r}, {float(f.base or 0)!r}, &[{specials}])", "ais::Reading<f64>"
    return f"ais::counted({raw}, {int(f.base or 0)}, &[{specials}])", "ais::Reading<i64>"


def member_name(f: PayloadField) -> str:
    return f"{f.id}_raw" if _raw_member(f) else f.id


def plain_type(f: PayloadField) -> str:
    """The Rust type of a field's member when present."""
    if f.type in ("uint", "enum") or f.type == "spare" and f.bits <= 64:
        return _int_type(f.bits, False)
    if f.type == "int":
        return _int_type(f.bits, True)
    return {"bool": "bool", "text": "ais::SixBitText<'a>", "data": "ais::Bits<'a>", "spare": "ais::Bits<'a>"}[f.type]


class _Record:
    """The code of one layout's struct (a message, an application, a group's entry)."""

    def __init__(self, name: str, items: list, dispatches: bool = False, entry: bool = False) -> None:
        self.name = name
        self.dispatches = dispatches  # its data field may carry an application
        self.entry = entry  # a group's entry: its choices' selectors are its own fields, read before them
        self.items = items
        self.members: list[str] = []
        self.accessors: list[str] = []
        self.read: list[str] = []
        self.write: list[str] = []
        self.json: list[str] = []
        self.optional = False    # an optional field may end the reading ('read)
        self.uncertain = False   # a field may be missing, ending the writing ('write)
        self.certain: set[str] = set()
        self.entries: list[_Record] = []
        self._walk(items, [], True)

    def _walk(self, items: list, rest: list, certain: bool) -> bool:
        """Add the code of `items` (followed by `rest`); whether what follows is still certain."""
        for i, item in enumerate(items):
            following = items[i + 1:] + rest
            if isinstance(item, PayloadField):
                if item.optional:
                    certain = False
                    self.optional = True
                    self.read.append(f"if r.remaining() < {item.bits} {{ break 'read; }}")
                self._field(item, following, certain)
            elif isinstance(item, PayloadGroup):
                self._group(item, following)
            else:
                self._choice(item, following)
                certain = False
        return certain

    def _field(self, f: PayloadField, following: list, certain: bool) -> None:
        name, kind, width, key = member_name(f), plain_type(f), f.bits, rust_str(f.id)
        if certain:
            self.certain.add(name)
        else:
            self.uncertain = True
        self.members.append(f"/// {f.name}{f' [{f.unit}]' if f.unit else ''}.\n"
                            f"pub {name}: {kind if certain else f'Option<{kind}>'},")
        if width is None:
            left = f"r.remaining().saturating_sub({after(following)})" if after(following) else "r.remaining()"
            read = f"r.take_text({left} / 6, {key})?" if f.type == "text" else f"r.take_bits({left}, {key})?"
        elif f.type == "int":
            read = f"r.take_signed({width}, {key})?" + ("" if kind == "i64" else f" as {kind}")
        elif f.type == "bool":
            read = f"r.take({width}, {key})? == 1"
        elif f.type == "text":
            read = f"r.take_text({width // 6}, {key})?"
        elif kind == "ais::Bits<'a>":
            read = f"r.take_bits({width}, {key})?"
        else:
            read = f"r.take({width}, {key})?" + ("" if kind == "u64" else f" as {kind}")
        self.read.append(f"m.{name} = {read if certain else f'Some({read})'};")
        value = "v" if not certain else f"self.{name}"
        if f.type == "text":
            put = f"w.put_bits({value}.bits(), {key})?;" if width is None else \
                f"w.put_fixed({value}.bits(), {width}, true, {key})?;"
        elif kind == "ais::Bits<'a>":
            put = f"w.put_bits({value}, {key})?;" if width is None else f"w.put_fixed({value}, {width}, false, {key})?;"
        elif f.type == "int":
            put = f"w.put_signed({value if kind == 'i64' else f'i64::from({value})'}, {width}, {key})?;"
        else:
            put = f"w.put({value if kind == 'u64' else f'u64::from({value})'}, {width}, {key})?;"
        if f.dispatch and self.dispatches:
            put = f"match &self.application {{ Some(app) => app.write(w)?, None => {{ {put} }} }}"
        self.write.append(put if certain else f"let Some(v) = self.{name} else {{ break 'write; }}; {put}")
        self.json.append(self._json(f, "v" if not certain else f"self.{name}", certain))
        if _raw_member(f):
            self.accessors.append(self._accessor(f, kind, certain))

    def _json(self, f: PayloadField, value: str, certain: bool) -> str:
        key = rust_str(f.id)
        kind = plain_type(f)
        if _raw_member(f):  # its value through its accessor
            accessor = f"self.{f.id}()" if certain or f.enum else "reading"
            if f.enum is not None:
                line = f"j.code({key}, {accessor}.map(CodeEnum::id), u64::from({value}))?;"
            else:
                line = f"j.reading({key}, {accessor}, {rust_str(f.id + '_raw')}, {_as_i64(kind, value)})?;"
            if not certain and f.enum is None:
                return f"if let (Some(v), Some(reading)) = (self.{member_name(f)}, self.{f.id}()) {{ {line} }}"
        elif f.type == "bool":
            line = f"j.flag({key}, {value})?;"
        elif f.type in ("text", "data") or kind == "ais::Bits<'a>":
            line = f"j.text({key}, {value})?;"
        else:
            line = f"j.int({key}, {value})?;"
        if f.dispatch and self.dispatches:
            line = f"if self.application.is_none() {{ {line} }}"
        return line if certain else f"if let Some(v) = self.{member_name(f)} {{ {line} }}"

    def _accessor(self, f: PayloadField, kind: str, certain: bool) -> str:
        if f.enum is not None:
            body = "ais::code(u64::from(raw))"
            result = f"Option<{f.enum.camel}>"
            doc = f"/// {f.name}: the enum's value of the raw code, None for a code it does not name."
            if certain:
                return f"{doc}\npub fn {f.id}(&self) -> {result} {{ let raw = self.{f.id}_raw; {body} }}"
            return f"{doc}\npub fn {f.id}(&self) -> {result} {{ self.{f.id}_raw.and_then(|raw| {body}) }}"
        body, result = _reading(f, _as_i64(kind, "raw"))
        doc = f"/// {f.name}{f' [{f.unit}]' if f.unit else ''}, or its special value."
        if certain:
            return f"{doc}\npub fn {f.id}(&self) -> {result} {{ let raw = self.{f.id}_raw; {body} }}"
        return f"{doc}\npub fn {f.id}(&self) -> Option<{result}> {{ self.{f.id}_raw.map(|raw| {body}) }}"

    def _group(self, g: PayloadGroup, following: list) -> None:
        entry = _Record(self.name + camel(g.id[:-1] if g.id.endswith("s") else g.id + "_entry"), g.items, entry=True)
        self.entries.append(entry)
        key = rust_str(g.id)
        lifetime = "<'a>" if any("'a" in m for m in entry.members) else ""
        self.members.append(f"/// {g.name}: {g.min} to {g.max} entries.\n"
                            f"pub {g.id}: [Option<{entry.name}{lifetime}>; {g.max}],")
        self.read.append(f"let count = r.entries({g.min}, {g.max}, {g.entry_width}, {after(following)}, {key})?;"
                         f"for slot in m.{g.id}.iter_mut().take(count) {{ *slot = Some({entry.name}::read(r)?); }}")
        self.write.append(f"for entry in self.{g.id}.iter().flatten() {{ entry.write(w)?; }}")
        self.json.append(f"{{ let out = j.key({key})?; out.write_char('[')?;"
                         f"for (i, entry) in self.{g.id}.iter().flatten().enumerate() {{"
                         f"if i > 0 {{ out.write_char(',')?; }} let mut e = ais::JsonObject::new(out)?;"
                         f"entry.json_members(&mut e)?; e.finish()?; }} out.write_char(']')?; }}")

    def _choice(self, c: PayloadChoice, following: list) -> None:
        assert c.selector is not None and c.selector.offset is not None
        by = c.selector
        reads, writes = [], []
        for case in sorted(c.cases, key=lambda case: case.is_default):
            pattern = " | ".join(map(str, case.values)) if case.values else \
                f"{case.range[0]}..={case.range[1]}" if case.range else "_"
            inner = type(self)(self.name, [], self.dispatches)
            inner.certain = self.certain  # a selector may be a field before the choice
            inner._walk(case.items, following, False)
            self.optional = self.optional or inner.optional
            self.uncertain = self.uncertain or inner.uncertain
            self.members += inner.members
            self.accessors += inner.accessors
            self.json += inner.json
            self.entries += inner.entries
            reads.append(f"{pattern} => {{ {' '.join(inner.read)} }}")
            writes.append(f"{pattern} => {{ {' '.join(inner.write)} }}")
        if not any(case.is_default for case in c.cases):
            reads.append("_ => {}")
            writes.append("_ => {}")
        if self.entry or read_before(c, member_name(by), self.certain):  # its selector is read already
            raw = f"m.{member_name(by)}"
            self.read.append(f"match {raw if plain_type(by) == 'u64' else f'u64::from({raw})'} {{ {' '.join(reads)} }}")
        else:
            self.read.append(f"match r.peek({by.offset}, {by.bits}, {rust_str(by.id)})? {{ {' '.join(reads)} }}")
        selector = f"self.{member_name(by)}"
        if member_name(by) in self.certain:
            selector = selector if plain_type(by) == "u64" else f"u64::from({selector})"
        else:  # the selector comes after the choice: None writes no case
            selector = f"{selector}.map(u64::from)"
            writes = [w if w.startswith("_") else f"Some({w.split(' => ', 1)[0]}) => {w.split(' => ', 1)[1]}" for w in writes]
        self.write.append(f"match {selector} {{ {' '.join(writes)} }}")


def read_before(c: PayloadChoice, member: str, certain: set[str]) -> bool:
    """Whether a top-level choice's selector is a field read before it, always present (then its
    value picks the case; otherwise the choice peeks at its bits in the message, which an
    application's reader cannot: A007 has an application's selector before its choice)."""
    assert c.selector is not None and c.selector.offset is not None
    return member in certain and (c.offset is None or c.selector.offset < c.offset)


def _labelled(label: str, lines: list[str], used: bool) -> str:
    body = "\n".join(lines)
    return f"'{label}: {{ {body} }}" if used else body


def _read_fn(reads: list[str], labelled: bool, members: int, lifetime: str) -> str:
    """The function reading a record: the fields always there (a leading run) in the struct's
    initializer, in order, the others assigned as they are read."""
    init: list[str] = []
    for line in reads:
        simple = re.fullmatch(r"m\.(\w+) = ([^;]*);", line)
        if simple is None:
            break
        init.append(f"{simple[1]}: {simple[2]},")
    rest = reads[len(init):]
    if len(init) < members:
        init.append("..Self::default()")
    body = _labelled("read", [line for line in rest if line != "m.trailing = r.rest();"], labelled) + \
        (" m.trailing = r.rest();" if "m.trailing = r.rest();" in rest else "")
    binding = "let mut m" if rest else "let m"
    return (f"/// Reads the layout's fields from `r`.\n"
            f"pub fn read(r: &mut ais::BitReader<{lifetime}>) -> Result<Self, ais::AisError> {{"
            f"{binding} = Self {{ {' '.join(init)} }}; {body} Ok(m) }}")


def record_code(record: _Record, kind: str, doc: str) -> str:
    """The struct, its accessors and its read/write/JSON code; `kind`: message, application, entry."""
    lifetime = "<'a>" if kind != "entry" else ""
    members = list(record.members)
    if kind != "entry":
        members.append("/// Bits after the layout's last field, as sent (a type 5 of 424 + 2 bits keeps 2).\n"
                       "pub trailing: ais::Bits<'a>,")
    if kind == "message":
        members.append("/// The values of the fill bits, as sent (meant to be 0, not always).\npub padding: u8,")
        if record.dispatches:
            members.append("/// What the data bits carry when the spec describes the application their DAC and FI "
                           "name (`data` is then not written).\npub application: Option<Application<'a>>,")
    uses_a = kind != "entry" or any("'a" in m for m in members)
    lifetime = "<'a>" if uses_a else ""
    out = [doc, "#[derive(Clone, Copy, Debug, Default)]", f"pub struct {record.name}{lifetime} {{", *members, "}", ""]
    reads = record.read + (["m.trailing = r.rest();"] if kind != "entry" else [])
    write_body = _labelled("write", record.write, record.uncertain)
    out += [f"impl{lifetime} {record.name}{lifetime} {{", *record.accessors,
            _read_fn(reads, record.optional, len(members), "'a" if uses_a else "'_"),
            f"/// Writes the layout's fields to `w`.\n"
            f"pub fn write(&self, w: &mut ais::BitWriter) -> Result<(), ais::AisError> {{ {write_body}"
            + (" w.put_bits(self.trailing, \"trailing\")?;" if kind != "entry" else "") + " Ok(()) }",
            "/// The members of its decoded JSON (those of generated/vectors/ais.jsonl), in order.\n"
            "pub fn json_members<W: fmt::Write>(&self, j: &mut ais::JsonObject<'_, W>) -> fmt::Result {"
            + " ".join(record.json)
            + (" if let Some(app) = &self.application { let mut o = ais::JsonObject::new(j.key(\"application\")?)?; "
               "app.json_members(&mut o)?; o.finish()?; }" if record.dispatches else "")
            + (" j.text(\"trailing\", self.trailing)?;" if kind != "entry" else "")
            + " Ok(()) }", "}", ""]
    return "\n".join(out)


def application_read(payload: Payload, record: _Record) -> str:
    """The expression of a decoded message `m`'s application (its data field's dispatch)."""
    data = payload.data_field
    assert data is not None
    names = [*data.dispatch, data.id]
    values = [f"m.{n}" for n in names]
    call = "Application::read(message_type, u64::from(dac), u64::from(fid), data)"
    if all(n in record.certain for n in names):
        return f"{{ let (dac, fid, data) = ({', '.join(values)}); {call} }}"
    wrapped = [v if n not in record.certain else f"Some({v})" for n, v in zip(names, values)]
    return f"match ({', '.join(wrapped)}) {{ (Some(dac), Some(fid), Some(data)) => {call}, _ => None }}"


def type_pattern(types: list[int]) -> str:
    """The match pattern of a layout's message types: a range when they follow each other."""
    if len(types) > 2 and types == list(range(types[0], types[-1] + 1)):
        return f"{types[0]}..={types[-1]}"
    return " | ".join(map(str, types))


def emit(spec: Spec, env: jinja2.Environment) -> dict[str, str]:
    if not spec.payloads:
        return {}
    blocks: list[str] = []
    reads: dict[str, str] = {}
    for payload in [*spec.payloads, *spec.applications]:
        kind = "application" if payload.application else "message"
        record = _Record(payload.camel, payload.items, bool(payload.applications))
        for entry in record.entries:
            blocks.append(record_code(entry, "entry", f"/// One entry of {entry.name}."))
        title = f"/// {title_of(payload)}"
        blocks.append(record_code(record, kind, title))
        if record.dispatches:
            reads[payload.id] = application_read(payload, record)
    enums = sorted({f.enum.camel for p in [*spec.payloads, *spec.applications] for f in p.fields if f.enum})
    sources = [p.origin.file for p in [*spec.payloads, *spec.applications]]
    return rustfmt({"rust/src/ais_messages.rs": env.get_template("rust/ais_messages.rs.j2").render(
        header=header(spec, "//", ["templates/rust/ais_messages.rs.j2", *sources]), blocks=blocks, enums=enums,
        payloads=spec.payloads, applications=spec.applications, reads=reads, type_pattern=type_pattern)})
