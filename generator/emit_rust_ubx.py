"""Rust emitter of the binary messages (spec/binary/<protocol>/messages): the module `ubx_messages`
of the generated crate (and `skytraq_messages`, `sirf_messages`, `casic_messages`, `sbf_messages`, the same code
in their byte order and framing), a struct per layout (named as the Python classes of emit_python_ubx) with
straight-line `read`, `write` and JSON code over the runtime's byte reader and writer
(runtime/rust/src/ubx.rs; a run of fields at fixed offsets is read as one array after one length
check, `ByteReader::run`), a struct per repeated group's entry, and the `Message` enum that picks
a layout by class and id, then by length and version, as the Python runtime and the reference
decoder (generator/reference_binary.py) pick it.

Members follow the AIS module (emit_rust_ais.py): a number with a divisor, special values or an
enum keeps its raw integer (`<id>_raw`) and has an accessor giving its value (an `ais::Reading`
where special values may stand for it); a bitfield word is a member and each
named part an accessor (and a setter) over its bits, so that the bits no part names stay as sent;
characters and bytes are views of the payload (`&[u8]`, ISO 8859-1 characters as sent, NUL padding
included); a reserved field is an integer as wide as its bytes; a group is a `ubx::Group`, a view
of its entries' bytes read entry by entry; an optional field and those after it are Options."""

from __future__ import annotations

import jinja2

from .emit import header, typed_natively
from .emit_framing import KeptField, framing, kept_fields, wire_key
from .emit_python_ais import entry_class
from .emit_python_ubx import identity, title as title_of
from .emit_rust import rust_str, rustfmt
from .names_rust import ident
from .model import BinaryMessage, Payload, PayloadField, PayloadGroup, Spec
from .reference_ais import after

_INTS = (8, 16, 32, 64, 128)


def _int_type(bits: int, signed: bool = False) -> str:
    size = next(n for n in _INTS if bits <= n)
    return f"{'i' if signed else 'u'}{size}"


def _check(f: PayloadField) -> None:
    """What this emitter does not write yet fails the generation, naming the field."""
    where = f"{f.origin.file}: {f.id}"
    if f.base is not None:
        raise NotImplementedError(f"{where}: bases of binary fields have no Rust code yet")
    if f.special and f.type not in ("u1", "u2", "u4", "i1", "i2", "i4", "r4", "r8"):
        raise NotImplementedError(f"{where}: special values of a {f.type} field have no Rust code yet")
    if f.type in ("ch", "bytes") and f.bits is not None and f.bits % 8:
        raise NotImplementedError(f"{where}: a width in bits")
    for p in f.parts:
        if p.divisor is not None or p.special or p.type not in ("bool", "uint", "int", "enum"):
            raise NotImplementedError(f"{where}.{p.id}: a part of type {p.type} with a unit has no Rust code yet")


def member_name(f: PayloadField) -> str:
    """A field's member: its id, or `<id>_raw` for a raw integer read through an accessor (a
    divisor, special values, an enum; an id that ends in `_`, as MGA-GLO's `lambda_` dodges
    Python's keyword, without it: `lambda_raw`)."""
    return f"{f.id.rstrip('_')}_raw" if f.scaled or f.special or f.enum is not None else ident(f.id)


def _specials(f: PayloadField) -> str:
    """The special values of a field as the runtime's table: `&[(raw, "id"), ...]` (a float's: its
    bit patterns, in hex)."""
    if f.type in ("r4", "r8"):
        return "&[" + ", ".join(f"(0x{s.raw:X}, {rust_str(s.id)})" for s in f.special) + "]"
    return "&[" + ", ".join(f"({s.raw}, {rust_str(s.id)})" for s in f.special) + "]"


def _reading(f: PayloadField, raw: str) -> tuple[str, str]:
    """The expression of a field with special values as an `ais::Reading` (of its value divided,
    or of its integer) from its raw member's expression, and its type."""
    if f.type == "r4":
        return f"ubx::float_reading(u64::from({raw}.to_bits()), f64::from({raw}), {_specials(f)})", "ais::Reading<f64>"
    if f.type == "r8":
        return f"ubx::float_reading({raw}.to_bits(), {raw}, {_specials(f)})", "ais::Reading<f64>"
    wide = f"i64::from({raw})"
    if f.divisor is not None:
        return f"ais::scaled({wide}, {float(f.divisor)!r}, 0.0, {_specials(f)})", "ais::Reading<f64>"
    return f"ais::counted({wide}, 0, {_specials(f)})", "ais::Reading<i64>"


def plain_type(f: PayloadField) -> str:
    """The Rust type of a field's member when present."""
    t = f.type
    if t in ("ch", "bytes"):
        return "&'a [u8]"
    if t == "r4":
        return "f32"
    if t == "r8":
        return "f64"
    assert f.bits is not None
    return _int_type(f.bits, t.startswith("i"))


def part_type(p: PayloadField) -> str:
    if p.type == "bool":
        return "bool"
    return _int_type(p.bits or 1, p.type == "int")


def _part_value(p: PayloadField, word: str, word_type: str) -> str:
    """The expression of part `p`'s value from the expression of its word."""
    width = p.bits or 1
    mask = (1 << width) - 1
    raw = f"({word} & {mask:#x})" if p.low == 0 else f"(({word} >> {p.low}) & {mask:#x})"
    if p.type == "bool":
        return f"{raw} != 0"
    kind = part_type(p)
    if p.type == "int":   # sign-extended from its top bit
        unsigned = _int_type(width)
        shift = int(kind[1:]) - width
        narrowed = raw if unsigned == word_type else f"{raw} as {unsigned}"   # (a u8 word's part: no cast to u8)
        return f"(({narrowed} as {kind}) << {shift}) >> {shift}" if shift else f"{raw} as {kind}"
    return raw[1:-1] if kind == word_type else f"{raw} as {kind}"


class _Record:
    """The code of one layout's struct or one group entry's."""

    def __init__(self, name: str, items: list, address: str, entries: dict[str, str] | None = None,
                 order: str = "le") -> None:
        self.name = name
        self.order = order       # le, be: the protocol's byte order
        self.entry_names = entries or {}   # a group's id -> its entry's struct
        self.address = address
        self.members: list[str] = []
        self.accessors: list[str] = []
        self.read: list[str] = []
        self.inits: list[str] = []
        self.write: list[str] = []
        self.json: list[str] = []
        self.entries: list[_Record] = []
        self.borrows = False     # a member borrows the payload ('a)
        self.optional = False    # an optional field came before: the rest are Options
        self.width = 0           # an entry's bytes
        # An entry of whole integers only, each (member, type, offset, bytes, key): read as one array of
        # its bytes at fixed offsets (one length check an entry, not one a field); None otherwise.
        self.plain: list[tuple[str, str, int, int, str]] | None = []
        self.values: dict[str, tuple[str, str]] = {}   # field or part id -> its value's expression and type
        # The fields of fixed width read since the last field of another kind, each (its read alone, its
        # member, its integer or float type, "" for characters or bytes, its bytes, key): a run read
        # after one length check, as one array, `fixed`.
        self.run: list[tuple[str, str, str, int, str]] = []
        self.trait: list[str] = []   # an entry's items of the Entry trait besides its own (a nested group's)
        for i, item in enumerate(items):
            if isinstance(item, PayloadGroup):
                self._end_run()
                self._group(item, items[i + 1:])
            elif isinstance(item, PayloadField):
                self._field(item, items[i + 1:])
            else:
                raise NotImplementedError(f"{item.origin.file}: a choice in a binary layout has no Rust code yet")
        self._end_run()

    def _end_run(self) -> None:
        """The reads of the run of fixed-width fields just ended: a field alone read as such; two or
        more fields as one array of their bytes, `fixed` (`ByteReader::run`: one length check, and a
        payload too short for the run names the first field it cuts), each field at its offset in it."""
        run, self.run = self.run, []
        if len(run) == 1:
            self.read.append(f"let {run[0][1]} = {run[0][0]};")
        elif run:
            table = ", ".join(f"({key}, {width})" for *_, width, key in run)
            self.read.append(f"let fixed: &[u8; {sum(width for *_, width, _ in run)}] = r.run(&[{table}])?;")
            at = 0
            for _, name, kind, width, _ in run:
                if kind == "u8":
                    self.read.append(f"let {name} = fixed[{at}];")
                elif kind:
                    value = ", ".join(f"fixed[{at + k}]" for k in range(width))
                    self.read.append(f"let {name} = {kind}::from_{self.order}_bytes([{value}]);")
                else:
                    self.read.append(f"let {name} = &fixed[{at}..{at + width}];")
                at += width

    def _field(self, f: PayloadField, following: list) -> None:
        _check(f)
        name, kind, key = member_name(f), plain_type(f), rust_str(f.id)
        width = f.bits // 8 if f.bits is not None else None
        if self.plain is not None:
            whole = width in (1, 2, 4, 8) and f.type not in ("ch", "bytes") and not f.optional and not self.optional
            self.plain = [*self.plain, (name, kind, self.width, width or 0, key)] if whole else None
        self.width += width or 0
        self.borrows = self.borrows or "'a" in kind
        if f.optional:
            self.optional = True
        certain = not self.optional
        unit = f" [{f.unit}]" if f.unit else ""
        told = f", as sent (`{ident(f.id)}()`: the float or its special value)" if f.special and f.type in ("r4", "r8") else ""
        self.members.append(f"/// {f.name}{unit}{told}.\npub {name}: {kind if certain else f'Option<{kind}>'},")
        if width is None:
            read = f"r.left({after(following) // 8})"
        elif f.type in ("ch", "bytes"):
            read = f"r.bytes({width}, {key})?"
        elif width in (1, 2, 4, 8, 16):
            read = f"{kind}::from_{self.order}_bytes(r.array({key})?)"
        else:   # a reserved field of 3, 5, 6, 7 or 9 bytes: its bytes at the low end of the integer
            pad = int(kind[1:]) // 8 - width
            span = f"[..{width}]" if self.order == "le" else f"[{pad}..]"
            o = self.order
            read = f"{{ let b: [u8; {width}] = r.array({key})?; let mut {o} = [0u8; {pad + width}]; " \
                   f"{o}{span}.copy_from_slice(&b); {kind}::from_{o}_bytes({o}) }}"
        if f.id == "fixed":
            raise NotImplementedError(f"{f.origin.file}: {f.id}: a field named as the bytes of a run of fields")
        if certain and width is not None and (f.type in ("ch", "bytes") or width in (1, 2, 4, 8, 16)):
            self.run.append((read, name, "" if f.type in ("ch", "bytes") else kind, width, key))
        elif certain:
            self._end_run()
            self.read.append(f"let {name} = {read};")
        elif f.optional:
            self._end_run()
            self.read.append(f"let {name} = if present && r.remaining() >= {width} {{ Some({read}) }} else {{ None }};")
            if following:
                self.read.append(f"let present = {name}.is_some();")
        else:
            self.read.append(f"let {name} = if present {{ Some({read}) }} else {{ None }};")
        self.inits.append(name)
        value = f"self.{name}" if certain else "v"
        if f.type in ("ch", "bytes"):
            put = f"w.put_sized({value}, {f'Some({width})' if width is not None else 'None'}, "\
                  f"{rust_str(self.address)}, {key})?;"
        elif width in (1, 2, 4, 8, 16):
            put = f"w.put(&{value}.to_{self.order}_bytes());"
        else:
            pad = int(kind[1:]) // 8 - width
            put = f"w.put(&{value}.to_{self.order}_bytes()[{f'..{width}' if self.order == 'le' else f'{pad}..'}]);"
        self.write.append(put if certain else f"let Some(v) = self.{name} else {{ break 'write; }}; {put}")
        json = self._json(f, value)
        self.json.append(json if certain else f"if let Some(v) = self.{name} {{ {json} }}")
        if certain:
            self.values[f.id] = (name, kind)
            for p in f.parts:
                self.values[p.id] = (_part_value(p, name, kind), part_type(p))
        self._accessors(f, kind, certain)

    def _json(self, f: PayloadField, value: str) -> str:
        key = rust_str(f.id)
        if f.enum is not None:
            return f"j.code({key}, ais::code::<{f.enum.camel}>(u64::from({value})).map(CodeEnum::id), u64::from({value}))?;"
        if f.special and f.type in ("r4", "r8"):   # the float or its special value's id
            reading, _ = _reading(f, value)
            return (f"match {reading} {{ ais::Reading::Value(x) => ubx::json_float(j, {key}, x)?, "
                    f"ais::Reading::Special(id) => j.text({key}, id)?, }}")
        if f.special:   # the value (divided) or the special value's id, then the raw integer
            reading, _ = _reading(f, value)
            number = "ubx::json_float(j, " + key + ", x)?" if f.divisor is not None else f"j.int({key}, x)?"
            return (f"match {reading} {{ ais::Reading::Value(x) => {number}, ais::Reading::Special(id) => "
                    f"j.text({key}, id)?, }} j.int({rust_str(f.id + '_raw')}, {value})?;")
        if f.divisor is not None:
            return f"ubx::json_float(j, {key}, {value} as f64 / {float(f.divisor)!r})?; j.int({rust_str(f.id + '_raw')}, {value})?;"
        if f.type == "r4":
            return f"ubx::json_float(j, {key}, f64::from({value}))?;"
        if f.type == "r8":
            return f"ubx::json_float(j, {key}, {value})?;"
        if f.type == "ch":
            return f"ubx::json_chars(j, {key}, {value})?;"
        if f.type == "bytes":
            return f"ubx::json_hex(j, {key}, {value})?;"
        if plain_type(f) in ("u128", "i128"):
            return f"write!(j.key({key})?, \"{{}}\", {value})?;"
        lines = [f"j.int({key}, {value})?;"]
        for p in f.parts:
            part = _part_value(p, value, plain_type(f))
            pkey = rust_str(p.id)
            if p.enum is not None:
                lines.append(f"j.code({pkey}, ais::code::<{p.enum.camel}>(u64::from({part})).map(CodeEnum::id), "
                             f"u64::from({part}))?;")
            elif p.type == "bool":
                lines.append(f"j.flag({pkey}, {part})?;")
            else:
                lines.append(f"j.int({pkey}, {part})?;")
        return " ".join(lines)

    def _accessors(self, f: PayloadField, kind: str, certain: bool) -> None:
        unit = f" [{f.unit}]" if f.unit else ""
        if f.enum is not None:
            doc = f"/// {f.name}: the enum's value of the raw code, None for a code it does not name."
            body = f"ais::code(u64::from(self.{member_name(f)}))" if certain else \
                f"self.{member_name(f)}.and_then(|raw| ais::code(u64::from(raw)))"
            self.accessors.append(f"{doc}\npub fn {ident(f.id)}(&self) -> Option<{f.enum.camel}> {{ {body} }}")
        elif f.special:
            expr, kind_of = _reading(f, "raw")
            doc = f"/// {f.name}{unit}{f': the raw integer divided by {f.divisor}' if f.divisor else ''}, or its special value."
            if f.type in ("r4", "r8"):
                doc = f"/// {f.name}{unit}: the float, or the special value whose bits it holds."
            if certain:
                self.accessors.append(f"{doc}\npub fn {ident(f.id)}(&self) -> {kind_of} {{ let raw = self.{member_name(f)}; {expr} }}")
            else:
                self.accessors.append(f"{doc}\npub fn {ident(f.id)}(&self) -> Option<{kind_of}> {{ self.{member_name(f)}.map(|raw| {expr}) }}")
        elif f.divisor is not None:
            doc = f"/// {f.name}{unit}: the raw integer divided by {f.divisor}."
            expr = f"raw as f64 / {float(f.divisor)!r}"
            if certain:
                self.accessors.append(f"{doc}\npub fn {ident(f.id)}(&self) -> f64 {{ let raw = self.{member_name(f)}; {expr} }}")
            else:
                self.accessors.append(f"{doc}\npub fn {ident(f.id)}(&self) -> Option<f64> {{ self.{member_name(f)}.map(|raw| {expr}) }}")
        if not f.parts:
            return
        if not certain:
            raise NotImplementedError(f"{f.origin.file}: {f.id}: an optional bitfield has no Rust code yet")
        for p in f.parts:
            width = p.bits or 1
            mask = (1 << width) - 1
            ptype = part_type(p)
            value = _part_value(p, f"self.{member_name(f)}", kind)
            punit = f" [{p.unit}]" if p.unit else ""
            if p.enum is not None:
                self.accessors.append(
                    f"/// {p.name} (bits of `{f.id}`): the enum's value of the raw code.\n"
                    f"pub fn {ident(p.id)}(&self) -> Option<{p.enum.camel}> {{ ais::code(u64::from({value})) }}")
                value_doc = "raw code"
            else:
                self.accessors.append(f"/// {p.name}{punit} (bit{'s' if width > 1 else ''} {p.low}"
                                      f"{f'-{p.low + width - 1}' if width > 1 else ''} of `{f.id}`).\n"
                                      f"pub fn {ident(p.id)}(&self) -> {ptype} {{ {value} }}")
                value_doc = "value"
            setter = f"set_{p.id}" if p.enum is None else f"set_{p.id}_raw"
            arg_type = ptype if p.enum is None else _int_type(width)
            raw = f"{kind}::from(value)" if p.type == "bool" else \
                f"(value as {kind} & {mask:#x})" if arg_type != kind else f"(value & {mask:#x})"
            shifted = f"{mask:#x}" if p.low == 0 else f"({mask:#x} << {p.low})"
            raw = raw if p.low == 0 else f"({raw} << {p.low})"
            self.accessors.append(
                f"/// Sets {p.name.lower()} (the {value_doc} in its bits of `{f.id}`; the other bits stay).\n"
                f"pub fn {setter}(&mut self, value: {arg_type}) {{"
                f"self.{member_name(f)} = (self.{member_name(f)} & !{shifted}) | {raw}; }}")

    def _group(self, g: PayloadGroup, following: list) -> None:
        entry = _Record(self.entry_names[g.id], g.fields, self.address, order=self.order)
        if g.nested is not None:
            self._nesting(g, entry)
            return
        self.entries.append(entry)
        key, name = rust_str(g.id), ident(g.id)
        lifetime = "<'a>" if entry.borrows else ""
        self.borrows = True
        if self.optional:
            raise NotImplementedError(f"{g.origin.file}: {g.id}: a group after an optional field has no Rust code yet")
        self.members.append(f"/// {g.name}: {g.min} to {g.max} entries.\npub {name}: ubx::Group<'a, {entry.name}{lifetime}>,")
        if isinstance(g.count, int):
            count = f"Some({g.count})"
        elif g.count is not None:
            value, kind = self.values[g.count]
            count = f"Some(usize::from({value}))" if kind in ("u8", "u16") else f"Some(({value}) as usize)"
        else:
            count = "None"
        if g.stride is not None:   # entries of as many bytes as the stride's field says
            stride, kind = self.values[g.stride]
            stride = f"usize::from({stride})" if kind in ("u8", "u16") else f"({stride}) as usize"
            self.read.append(f"let {name} = r.group_strided({count}, {stride}, {g.min}, {g.max}, {after(following) // 8}, "
                             f"{key}, {rust_str(g.stride)})?;")
            self.write.append(f"self.{name}.write_strided(w, {stride.replace(self.values[g.stride][0], 'self.' + self.values[g.stride][0])}, "
                              f"{rust_str(self.address)}, {rust_str(g.stride)}, {key})?;")
        else:
            self.read.append(f"let {name} = r.group({count}, {g.min}, {g.max}, {after(following) // 8}, {key})?;")
            self.write.append(f"self.{name}.write(w);")
        self.inits.append(name)
        self.json.append(f"self.{name}.json(j, {key})?;")


    def _usize(self, field: str, prefix: str = "") -> str:
        """The expression of field `field`'s value as a usize (`prefix`: self. for the writer)."""
        value, kind = self.values[field]
        return f"usize::from({prefix}{value})" if kind in ("u8", "u16") else f"({prefix}{value}) as usize"

    def _nesting(self, g: PayloadGroup, entry: _Record) -> None:
        """A group whose entries end with a group of their own (rule B010: SBF's Type-1 sub-blocks
        and their Type-2): a ubx::Nesting of the entries, each entry's group a ubx::Group set as the
        Nesting reads it (Entry::set_nested), its count read from the entry's bytes (nested_count)."""
        n = g.nested
        assert n is not None and isinstance(n.count, str) and isinstance(g.count, (str, int)) and g.stride
        inner = _Record(self.entry_names[n.id], n.fields, self.address, order=self.order)
        self.entries += [inner, entry]
        nested, lifetime = ident(n.id), "<'a>" if inner.borrows else ""
        entry.members.append(f"/// {n.name}: {n.count} entries.\npub {nested}: ubx::Group<'a, {inner.name}{lifetime}>,")
        entry.read.append(f"let {nested} = ubx::Group::default();")
        entry.inits.append(nested)
        entry.json.append(f"self.{nested}.json(j, {rust_str(n.id)})?;")
        entry.borrows, entry.plain = True, None
        at = 0
        for f in g.fields:   # the count's bytes in the entry
            if f.id == n.count:
                break
            at += (f.bits or 0) // 8
        count = next(f for f in g.fields if f.id == n.count)
        width = (count.bits or 0) // 8
        order = "le" if self.order == "le" else "be"
        if width == 1:
            read = f"head.get({at}).map_or(0, |&b| usize::from(b))"
        elif width == 2:
            read = f"head.get({at}..{at + 2}).map_or(0, |b| usize::from(u16::from_{order}_bytes([b[0], b[1]])))"
        else:
            raise NotImplementedError(f"{n.origin.file}: {n.id}: a nested group counted by a {count.type} has no Rust code yet")
        entry.trait += [f"const NESTED_WIDTH: usize = {inner.width};",
                        f"fn nested_count(head: &[u8]) -> usize {{ {read} }}",
                        f"fn set_nested(&mut self, bytes: &'a [u8], stride: usize) {{ self.{nested} = "
                        "ubx::Group::with_stride(bytes, stride).unwrap_or_default(); }"]
        key, name = rust_str(g.id), ident(g.id)
        self.borrows = True
        if self.optional:
            raise NotImplementedError(f"{g.origin.file}: {g.id}: a group after an optional field has no Rust code yet")
        self.members.append(f"/// {g.name} (each followed by its {n.id}): {g.min} to {g.max} entries.\n"
                            f"pub {name}: ubx::Nesting<'a, {entry.name}<'a>>,")
        count_of = f"{g.count}" if isinstance(g.count, int) else self._usize(g.count)
        assert n.stride is not None   # rule B010
        strides = self._usize(g.stride), self._usize(n.stride)
        self.read.append(f"let {name} = r.group_nesting({count_of}, {strides[0]}, {strides[1]}, {key}, "
                         f"{rust_str(g.stride)}, {rust_str(n.id)}, {rust_str(n.stride)})?;")
        written = self._usize(g.stride, "self."), self._usize(n.stride, "self.")
        self.write.append(f"self.{name}.write_strided(w, ({written[0]}, {written[1]}), {rust_str(self.address)}, "
                          f"({rust_str(g.stride)}, {rust_str(n.stride)}), {key}, {rust_str(n.id)})?;")
        self.inits.append(name)
        self.json.append(f"self.{name}.json(j, {key})?;")


def record_code(record: _Record, payload: Payload | None, message: BinaryMessage | None,
                wire: tuple[int, ...] = (), kept: bool = False) -> str:
    """The struct, its constants and accessors and its read/write/JSON code."""
    entry = payload is None
    borrows = record.borrows or not entry
    lifetime = "<'a>" if borrows else ""
    members = list(record.members)
    if not entry:
        members.append("/// Bytes after the layout's last field, as sent (a newer firmware's additions).\n"
                       "pub trailing: &'a [u8],")
    reads = list(record.read)
    if entry and record.plain:   # Group keeps whole entries only: the one check never fails there
        reads = [f"let b: [u8; {record.width}] = r.array({record.plain[0][4]})?;"]
        for name, kind, offset, width, _ in record.plain:
            at = ", ".join(f"b[{offset + k}]" for k in range(width))
            reads.append(f"let {name} = {kind}::from_{record.order}_bytes([{at}]);")
    inits = list(record.inits)
    if not entry:
        reads.append("let trailing = r.rest();")
        inits.append("trailing")
    if record.optional:
        reads.insert(0, "let present = true;")
    write_body = " ".join(record.write)
    if record.optional:
        write_body = f"'write: {{ {write_body} }}"
    if not entry:
        write_body += " w.put(self.trailing);"
    doc = f"/// One entry of {record.name}." if entry else f"/// {title_of(message, payload)}"
    if kept:   # the frame's header fields of `identity: false` (Unicore's time and status)
        members = ["/// The frame's header fields besides its sync, message id and length (time and status).",
                   "pub header: Header,", *members]
        inits = [*inits, "header: Header::default()"]
    out = [doc, "#[derive(Clone, Copy, Debug, Default, PartialEq)]", f"pub struct {record.name}{lifetime} {{", *members,
           "}", ""]
    impl: list[str] = []
    if not entry:
        assert payload is not None and message is not None
        length = f"Some({payload.fixed_width // 8})" if payload.fixed_width is not None else "None"
        select = f"Some(({rust_str(payload.select[0])}, {payload.select_at}, {payload.select[1]:#04x}))" \
            if payload.select is not None else "None"
        strs = lambda words: "&[" + ", ".join(rust_str(w) for w in words) + "]"  # noqa: E731
        ubx = message.protocol == "ubx"
        key = "[" + ", ".join(f"{k:#04x}" for k in wire) + "]"
        impl += [f"/// The spec's id of the layout.\npub const ID: &'static str = {rust_str(payload.id)};",
                 f"/// How {'u-blox names' if ubx else 'errors name'} the message.\n"
                 f"pub const ADDRESS: &'static str = {rust_str(message.address)};",
                 *([f"/// The message class.\npub const CLASS: u8 = {message.class_number:#04x};",
                    f"/// The message id.\npub const MSG_ID: u8 = {message.msg_id:#04x};"] if ubx else
                   [f"/// The bytes that tell the message: {identity(message)}.\npub const KEY: &'static [u8] = &{key};"]),
                 f"/// The payload's bytes, when the layout fixes them.\npub const LENGTH: Option<usize> = {length};",
                 "/// The field (its name and byte) whose value tells it from another layout of its class and id, and\n"
                 f"/// that value (a type, command or version byte).\npub const SELECT: Option<(&'static str, usize, u8)> = {select};",
                 f"/// Who sends it: poll and input go to the receiver, output comes from it.\n"
                 f"pub const DIRECTIONS: &'static [&'static str] = {strs(payload.directions)};",
                 f"/// The layouts (ids) the receiver answers it with.\npub const REPLIES: &'static [&'static str] = "
                 f"{strs(payload.replies)};"]
    if payload is not None and payload.select is not None and payload.select_field is not None:
        impl.append(f"/// The layout's default with its `{payload.select[0]}` set to the value that picks it.\n"
                    f"#[must_use]\npub fn new() -> Self {{ Self {{ {member_name(payload.select_field)}: "
                    f"{payload.select[1]:#04x}, ..Self::default() }} }}")
    impl += record.accessors
    init = ", ".join(inits)
    if entry:
        impl_head = f"impl<'a> ubx::Entry<'a> for {record.name}{lifetime} {{"
        out += [impl_head, f"const WIDTH: usize = {record.width};",
                f"fn read(r: &mut ubx::ByteReader<'a>) -> Result<Self, UbxError> {{ {' '.join(reads)} Ok(Self {{ {init} }}) }}",
                f"fn write(&self, w: &mut ubx::ByteWriter<'_>) -> Result<(), UbxError> {{ {write_body} Ok(()) }}",
                "fn json_members<W: fmt::Write>(&self, j: &mut JsonObject<'_, W>) -> fmt::Result {"
                + " ".join(record.json) + " Ok(()) }", *record.trait, "}", ""]
        if record.accessors:
            out += [f"impl{lifetime} {record.name}{lifetime} {{", *record.accessors, "}", ""]
        return "\n".join(out)
    assert message is not None
    if message.protocol == "ubx":
        reader = "ubx::ByteReader::new(payload, Self::ADDRESS, (Self::CLASS, Self::MSG_ID))"
        encode = "ubx::encode_frame(buf, Self::CLASS, Self::MSG_ID, Self::ADDRESS, |w| self.write(w))"
        what, frame, vectors = "`payload`", "sync bytes to checksum", "ubx.jsonl"
    else:
        reader = f"ubx::ByteReader::new(payload, Self::ADDRESS, (0, 0)).of_protocol({rust_str(message.protocol.upper())})"
        encode = f"ubx::encode_frame_of(buf, Protocol::{message.protocol.capitalize()}, Self::KEY, Self::ADDRESS, |w| self.write(w))"
        if kept:
            encode = (f"ubx::encode_frame_with(buf, Protocol::{message.protocol.capitalize()}, Self::KEY, Self::ADDRESS, "
                      "|h| self.header.write(h), |w| self.write(w))")
        what = "`payload` (the bytes after its key)" if not message.msg_class else "`payload`"
        frame, vectors = "sync bytes to checksum and end bytes", "binary.jsonl"
    out += [f"impl<'a> {record.name}<'a> {{", *impl,
            f"/// The message of {what}, read as this layout (a short payload names the field it cuts).\n"
            f"pub fn read(payload: &'a [u8]) -> Result<Self, UbxError> {{"
            f"let r = &mut {reader};"
            f"{' '.join(reads)} Ok(Self {{ {init} }}) }}",
            f"/// Writes the payload{' after its key' if not message.msg_class else ''}.\npub fn write(&self, w: &mut ubx::ByteWriter<'_>) -> Result<(), UbxError> {{ "
            f"{write_body} Ok(()) }}",
            f"/// The whole frame, {frame}, written into `buf`.\n"
            "pub fn encode<'b>(&self, buf: &'b mut [u8]) -> Result<&'b [u8], UbxError> {"
            f"{encode} }}",
            f"/// The members of its decoded JSON (those of generated/vectors/{vectors}), in order.\n"
            "pub fn json_members<W: fmt::Write>(&self, j: &mut JsonObject<'_, W>) -> fmt::Result {"
            + ("self.header.json(j)?; " if kept else "")
            + " ".join(record.json) + " ubx::json_hex(j, \"trailing\", self.trailing) }", "}", ""]
    return "\n".join(out)


def _fits(message: BinaryMessage, layout: Payload) -> str | None:
    """The condition a payload fits `layout` under (None: any payload)."""
    conditions = []
    if layout.fixed_width is not None:
        conditions.append(f"payload.len() == {layout.fixed_width // 8}" if layout.fixed_width else "payload.is_empty()")
    if layout.select is not None:
        at = layout.select_at
        assert at is not None
        conditions.append(f"payload.{'first()' if at == 0 else f'get({at})'} == Some(&{layout.select[1]:#04x})")
    return " && ".join(conditions) or None


def dispatch_arm(message: BinaryMessage, wire: tuple[int, ...]) -> str:
    """The match arm of a class and id (UBX), of the header's class and id (CASIC) or of the
    payload's first bytes, its id and sub-id (SkyTraq, SiRF: the layout reads the rest): the first
    layout that fits, else the main one."""
    main = next((lay for lay in message.layouts if "output" in lay.directions), message.layouts[-1])
    read = lambda lay: f"Message::{lay.camel}({lay.camel}::read(payload)?)"  # noqa: E731
    tests: list[tuple[str, Payload]] = []
    last = main   # what a payload no condition holds for is read as
    for layout in message.layouts:
        condition = _fits(message, layout)
        if condition is None:
            last = layout
            break
        tests.append((condition, layout))
    else:   # a selector value no layout names: the first selected layout of the payload's length
        lengths: set[int] = set()
        for layout in message.layouts:
            if layout.select is not None and layout.fixed_width is not None and layout.fixed_width not in lengths:
                lengths.add(layout.fixed_width)
                size = layout.fixed_width // 8
                condition = f"payload.len() == {size}" if size else "payload.is_empty()"
                if tests and tests[-1][1] is layout and tests[-1][0].startswith(condition + " && "):
                    tests.pop()   # its test of length and selector: the length alone says the same
                tests.append((condition, layout))
    while tests and tests[-1][1] is last:   # a last test that reads what the fallback reads
        tests.pop()
    branches = [f"if {condition} {{ {read(layout)} }}" for condition, layout in tests] + [read(last)]
    body = branches[0] if len(branches) == 1 else " else ".join(
        b if b.startswith("if ") else f"{{ {b} }}" for b in branches)
    key = ", ".join(f"{k:#04x}" for k in wire)
    if message.protocol == "ubx":
        return f"({key}) => {body},"
    if message.header_key:   # CASIC: the header's class and id; SBF: its id (block number, revision)
        return f"Some([{key}]) => {body},"
    return f"[{key}, payload @ ..] => {body},"


def _blocks(spec: Spec, messages: list[BinaryMessage]) -> tuple[list[str], list[Payload]]:
    """The code of every layout of `messages` (its entries' structs first) and the layouts."""
    blocks: list[str] = []
    layouts: list[Payload] = []
    for message in messages:
        order = "be" if message.byte_order == "big" else "le"
        for layout in message.layouts:
            names = {n.id: entry_class(layout, n) for g in layout.items if isinstance(g, PayloadGroup)
                     for n in (g, g.nested) if n is not None}
            record = _Record(layout.camel, layout.items, message.address, names, order=order)
            for entry in record.entries:
                blocks.append(record_code(entry, None, None))
            blocks.append(record_code(record, layout, message, wire_key(spec, message), bool(_kept(spec, message.protocol))))
            layouts.append(layout)
    return blocks, layouts


def _enums(messages: list[BinaryMessage]) -> list[str]:
    """The enums the messages' fields (and bitfields' parts) name, as Rust types."""
    fields = [p for m in messages for lay in m.layouts for f in lay.fields for p in (f, *f.parts)]
    return sorted({f.enum.camel for f in fields if f.enum})


def _key_span(spec: Spec, protocol: str) -> tuple[int, int]:
    """The header's bytes that hold a message's key (where the header holds it)."""
    f = framing(next(p for p in spec.protocols if p.id == protocol))
    return min(at for _, at, _ in f.identity) // 8, (max(at + bits for _, at, bits in f.identity) + 7) // 8


def _kept(spec: Spec, protocol: str) -> list[KeptField]:
    """The header fields a decoded message of `protocol` keeps (Unicore's time and status)."""
    return kept_fields(next(p for p in spec.protocols if p.id == protocol))


def header_code(spec: Spec, protocol: str) -> str:
    """The protocol's Header: a member per kept header field, read from and written to a frame's
    header (sync bytes to the payload) at its place, and its JSON object (`header`)."""
    p = next(p for p in spec.protocols if p.id == protocol)
    kept, f = kept_fields(p), framing(p)
    types = {1: "u8", 2: "u16", 4: "u32"}
    order = "be" if f.big_endian else "le"
    members = [line for k in kept for line in (f"/// {k.doc}.", f"pub {k.id}: {types[k.size]},")]
    reads = [f"{k.id}: " + (f"h[{k.at}]" if k.size == 1 else f"{types[k.size]}::from_{order}_bytes([" +
                            ", ".join(f"h[{k.at + i}]" for i in range(k.size)) + "])") for k in kept]
    writes = [f"h[{k.at}] = self.{k.id};" if k.size == 1 else
              f"h[{k.at}..{k.at + k.size}].copy_from_slice(&self.{k.id}.to_{order}_bytes());" for k in kept]
    json = [f"o.int({rust_str(k.id)}, self.{k.id})?;" for k in kept]
    return "\n".join([
        f"/// The fields of a {p.name} frame's header besides its sync, message id and length, which a decoded",
        "/// message keeps and its frame is written with (0 in a message built by hand, unless set).",
        "#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]", "pub struct Header {", *members, "}", "",
        "impl Header {",
        f"/// The header's bytes, sync to payload.\npub const SIZE: usize = {f.header};",
        "/// Its fields of a frame's header (sync bytes to the payload; bytes it lacks read as 0).",
        "#[must_use]\npub fn read(header: &[u8]) -> Self {",
        "let mut h = [0u8; Self::SIZE]; let n = header.len().min(Self::SIZE); h[..n].copy_from_slice(&header[..n]);",
        f"Self {{ {', '.join(reads)} }} }}",
        "/// Sets its fields in a frame's header (sync bytes to the payload; one shorter is left as it is).",
        "pub fn write(&self, header: &mut [u8]) {",
        "if let Some(h) = header.get_mut(..Self::SIZE) {", *writes, "} }",
        "/// Writes its JSON object as the member `header`.",
        "pub fn json<W: fmt::Write>(&self, j: &mut JsonObject<'_, W>) -> fmt::Result {",
        "let mut o = JsonObject::new(j.key(\"header\")?)?;", *json, "o.finish() }", "}", ""])


def protocols(spec: Spec) -> list[str]:
    """The binary protocols besides UBX whose messages the Rust crate types, each a module of its own."""
    return [p for p in typed_natively(spec) if p != "ubx"]


def emit(spec: Spec, env: jinja2.Environment) -> dict[str, str]:
    files: dict[str, str] = {}
    for protocol in protocols(spec):   # SkyTraq, SiRF, CASIC, SBF
        others = sorted((m for m in spec.binary if m.protocol == protocol), key=lambda m: (len(m.key) == 1, m.key))
        blocks, layouts = _blocks(spec, others)
        name = next((p.name for p in spec.protocols if p.id == protocol), protocol)
        files[f"rust/src/{protocol}_messages.rs"] = env.get_template("rust/binary_messages.rs.j2").render(
            header=header(spec, "//", ["templates/rust/binary_messages.rs.j2", *(m.origin.file for m in others)]),
            blocks=blocks, layouts=layouts, arms=[dispatch_arm(m, wire_key(spec, m)) for m in others], name=name,
            protocol=protocol, variant=protocol.capitalize(),
            in_header=others[0].header_key, order=others[0].byte_order, enums=_enums(others),
            told="block number and revision" if others[0].revision is not None else "class and id",
            key_span="{}..{}".format(*_key_span(spec, protocol)),
            header_struct=header_code(spec, protocol) if _kept(spec, protocol) else "")
    messages = [m for m in spec.binary if m.protocol == "ubx"]
    if not messages:
        return rustfmt(files)
    blocks, layouts = _blocks(spec, messages)
    enums = _enums(messages)
    sources = [m.origin.file for m in messages]
    files["rust/src/ubx_messages.rs"] = env.get_template("rust/ubx_messages.rs.j2").render(
        header=header(spec, "//", ["templates/rust/ubx_messages.rs.j2", *sources]), blocks=blocks, enums=enums,
        layouts=layouts, arms=[dispatch_arm(m, wire_key(spec, m)) for m in messages],
        groups={lay.camel: [ident(g.id) for g in lay.items if isinstance(g, PayloadGroup)] for lay in layouts},
        example=any(lay.id == "ack_ack" for lay in layouts))
    return rustfmt(files)
