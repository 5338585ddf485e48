"""C emitter of the bit messages told by a number (spec/binary/rtcm3/messages): the pair
nmea_rtcm3.h / nmea_rtcm3.c, which needs nothing of nmea.h (as the UBX pair): a struct per layout
with straight-line read, write and JSON functions over RTCM 3's frame, bit reader and writer
(runtime/c/rtcm3.{h,c}, pasted in), and nmea_rtcm3_decode_frame / _decode_payload / _encode /
_json that dispatch on the message number. No heap: characters, data and the bits after a layout
are views of the payload; a group is an array of the layout's maximum with its count.

As the Rust module (emit_rust_rtcm3.py) and emit_c_ais's records: a field of a case of a choice
has a `has_<member>` flag; a number with a divisor or special values, and a sign-magnitude
number (its negative zero `1 << (bits - 1)`), keep their raw integer (`<id>_raw`); a width
counted by another field, groups counted by a field or by the bits set in mask fields, read
field by field for `order: field_major`."""

from __future__ import annotations

import jinja2

from .emit import RUNTIME, header, runtime_source
from .emit_c_ais import _c_str, _if_chain, c_layout
from .emit_python_rtcm3 import title as title_of
from .emit_rust_ais import member_name as ais_member_name
from .emit_rust_rtcm3 import CHARS, member_name, raw_member, unit_bits
from .model import Ones, Payload, PayloadChoice, PayloadField, PayloadGroup, Spec

BITS = "nmea_rtcm3_bits"


def c_type(f: PayloadField) -> str:
    if f.type in CHARS or f.type == "data" or f.bits is None or f.count is not None:
        return BITS
    if f.type == "bool":
        return "bool"
    if f.type == "smag":
        return "int64_t"   # its negative zero, 1 << (bits - 1), is no number of its width
    size = next(n for n in (8, 16, 32, 64) if f.bits <= n)
    return f"{'int' if f.type == 'int' else 'uint'}{size}_t"


def struct_name(name: str) -> str:
    return f"nmea_rtcm3_{name}"


class Record:
    """The C code of one RTCM 3 layout (a message, or a group's entry)."""

    def __init__(self, name: str, items: list, fields: dict[str, PayloadField]) -> None:
        self.name = name
        self.fields = fields   # the layout's fields by id (the masks a count names)
        self.members: list[str] = []
        self.read: list[str] = []
        self.write: list[str] = []
        self.json: list[str] = []
        self.certain: set[str] = set()
        self.entries: list[Record] = []
        self.specials: list[str] = []
        self.field_major = False   # an entry of a group read field by field (inline: no read and write functions)
        self._walk(items, True)

    def _walk(self, items: list, certain: bool) -> None:
        for item in items:
            if isinstance(item, PayloadField):
                assert not item.optional, f"{item.id}: RTCM 3 layouts have no optional fields"
                self._field(item, certain)
            elif isinstance(item, PayloadGroup):
                self._group(item)
            else:
                self._choice(item)

    def count_of(self, count: str | Ones, owner: str) -> str:
        """A count as a size_t expression over the members of `owner` (`m`)."""
        if isinstance(count, Ones):
            ones = [f"rtcm3_count_ones({owner}->{name})" if c_type(self.fields[name]) == BITS
                    else f"rtcm3_ones({owner}->{name})" for name in count.fields]
            return " * ".join(ones)
        return f"(size_t){owner}->{count}"

    def _field(self, f: PayloadField, certain: bool) -> None:
        name, kind, width, key = member_name(f), c_type(f), f.bits, _c_str(f.id)
        self.members.append(f"{kind} {name}; /* {f.name}{f' [{f.unit}]' if f.unit else ''}"
                            f"{f' ({f.ref})' if f.ref else ''} */")
        if certain:
            self.certain.add(name)
        else:
            self.members.append(f"bool has_{name};")
        has = "" if certain else f" m->has_{name} = true;"
        if kind == BITS:
            width_expr = (f"({self.count_of(f.count, 'm')}) * {unit_bits(f)}" if f.count is not None
                          else str(width) if width is not None else "rtcm3_remaining(r)")
            self.read.append(f"if (!rtcm3_take_bits(r, {width_expr}, {key}, &m->{name})) return false;{has}")
            put = (f"if (!rtcm3_put_counted(w, m->{name}, {self.count_of(f.count, 'm')}, {unit_bits(f)}, {key})) "
                   f"return false;" if f.count is not None else f"if (!rtcm3_put_bits(w, m->{name}, {key})) return false;")
        elif f.type in ("int", "smag"):
            take = "rtcm3_take_smag" if f.type == "smag" else "rtcm3_take_signed"
            self.read.append(f"if (!{take}(r, {width}, {key}, &signed_raw)) return false; "
                             f"m->{name} = ({kind})signed_raw;{has}")
            put_fn = "rtcm3_put_smag" if f.type == "smag" else "rtcm3_put_signed"
            put = f"if (!{put_fn}(w, m->{name}, {width}, {key})) return false;"
        else:
            value = "raw == 1" if kind == "bool" else f"({kind})raw"
            self.read.append(f"if (!rtcm3_take(r, {width}, {key}, &raw)) return false; m->{name} = {value};{has}")
            put = f"if (!rtcm3_put(w, (uint64_t)m->{name}, {width}, {key})) return false;"
        self.write.append(put if certain else f"if (!m->has_{name}) return rtcm3_missing(w, {key}); {put}")
        line = self._json(f, f"m->{name}")
        self.json.append(line if certain else f"if (m->has_{name}) {{ {line} }}")

    def _json(self, f: PayloadField, value: str) -> str:
        key = _c_str(f.id)
        if raw_member(f):
            assert f.base is None, f"{f.id}: RTCM 3 numbers have no base"
            specials = [(s.raw, s.id) for s in f.special]
            if f.type == "smag":
                specials.insert(0, (1 << (f.bits - 1), "negative_zero"))
            table = f"rtcm3_{self.name}_{f.id}_specials"
            if specials:
                rows = ", ".join(f"{{{raw}, {_c_str(id_)}}}" for raw, id_ in specials)
                self.specials.append(f"static const nmea_rtcm3_special {table}[] = {{{rows}}};")
            real = "true" if f.divisor is not None else "false"
            listed = f"{table}, {len(specials)}" if specials else "NULL, 0"
            always = "true" if f.scaled else "false"   # a plain sign-magnitude number: its raw beside a special only
            return (f"rtcm3_json_reading(j, {key}, (int64_t){value}, {float(f.divisor or 1)!r}, {real}, {listed}, "
                    f"{always});")
        if f.type in CHARS:
            return f"rtcm3_json_chars(j, {key}, {value}, {'true' if CHARS[f.type] else 'false'});"
        if f.type == "bool":
            return f"rtcm3_json_flag(j, {key}, {value});"
        if c_type(f) == BITS:
            return f"rtcm3_json_bits(j, {key}, {value});"
        if f.type == "int":
            return f"rtcm3_json_int(j, {key}, (long long){value});"
        return f"rtcm3_json_uint(j, {key}, (unsigned long long){value});"

    def _group(self, g: PayloadGroup) -> None:
        assert g.count is not None and not isinstance(g.count, int), f"{g.id}: an RTCM 3 group is counted"
        entry = Record(self.name + "_" + (g.id[:-1] if g.id.endswith("s") else g.id + "_entry"), g.fields, self.fields)
        entry.field_major = g.field_major
        self.entries.append(entry)
        key, struct = _c_str(g.id), struct_name(entry.name)
        self.members += [f"{struct} {g.id}[{g.max}]; /* {g.name} */", f"size_t {g.id}_count;"]
        self.specials += entry.specials
        self.read.append(f"if (!rtcm3_counted(r, {self.count_of(g.count, 'm')}, {g.max}, {g.entry_width}, {key}, "
                         f"&m->{g.id}_count)) return false;")
        self.write.append(f"if (m->{g.id}_count > {g.max}) return rtcm3_entries_said(w, m->{g.id}_count, {g.max}, {key});")
        if isinstance(g.count, Ones):
            self.write.append(f"if (!rtcm3_entries_said(w, m->{g.id}_count, {self.count_of(g.count, 'm')}, {key})) "
                              f"return false;")
        loop = f"{{ size_t i; for (i = 0; i < m->{g.id}_count; i++) {{"
        if g.field_major:
            for line in entry.read:
                self.read.append(f"{loop} {struct} *e = &m->{g.id}[i]; {line.replace('m->', 'e->')} }} }}")
            for line in entry.write:
                self.write.append(f"{loop} const {struct} *e = &m->{g.id}[i]; {line.replace('m->', 'e->')} }} }}")
        else:
            self.read.append(f"{loop} if (!rtcm3_read_{entry.name}(r, &m->{g.id}[i])) return false; }} }}")
            self.write.append(f"{loop} if (!rtcm3_write_{entry.name}(&m->{g.id}[i], w)) return false; }} }}")
        self.json.append(f"{{ size_t i; rtcm3_json_key(j, {key}); rtcm3_json_puts(j, \"[\"); "
                         f"for (i = 0; i < m->{g.id}_count; i++) {{ if (i) rtcm3_json_puts(j, \",\"); "
                         f"rtcm3_json_open(j); rtcm3_json_{entry.name}(&m->{g.id}[i], j); rtcm3_json_close(j); }} "
                         f"rtcm3_json_puts(j, \"]\"); }}")

    def _choice(self, c: PayloadChoice) -> None:
        assert c.selector is not None and c.selector.offset is not None
        by = c.selector
        reads, writes = [], []
        for case in sorted(c.cases, key=lambda case: case.is_default):
            inner = Record(self.name, [], self.fields)
            inner._walk(case.items, False)
            self.members += inner.members
            self.json += inner.json
            self.specials += inner.specials
            reads.append((case, " ".join(inner.read)))
            writes.append((case, " ".join(inner.write)))
        self.read.append(f"if (!rtcm3_peek(r, {by.offset}, {by.bits}, {_c_str(by.id)}, &selector)) "
                         f"return false; {_if_chain(reads, 'selector', '')}")
        self.write.append(f"{{ uint64_t selector = (uint64_t)m->{ais_member_name(by)}; "
                          f"{_if_chain(writes, 'selector', '')} }}")


def record_code(record: Record, message: bool, doc: str) -> tuple[str, str]:
    """The struct (for the header) and the functions of a record."""
    struct = struct_name(record.name)
    members = list(record.members)
    if message:
        members.append(f"{BITS} trailing; /* bits after the layout, as sent (the padding to a byte) */")
    typedef = f"/* {doc} */\n" + "typedef struct {\n    " + "\n    ".join(members) + f"\n}} {struct};\n"
    reads = " ".join(record.read) + (" m->trailing = rtcm3_rest(r);" if message else "")
    writes = " ".join(record.write) + \
        (" if (!rtcm3_put_bits(w, m->trailing, \"trailing\")) return false;" if message else "")
    json = " ".join(record.json) + (" rtcm3_json_bits(j, \"trailing\", m->trailing);" if message else "")
    declared = [f"{c_type} {name};" for c_type, name in
                (("uint64_t", "raw"), ("int64_t", "signed_raw"), ("uint64_t", "selector")) if f"&{name})" in reads]
    reads = " ".join(declared) + " " + reads
    code = "\n".join([] if record.field_major else [
        f"static bool rtcm3_read_{record.name}(nmea_rtcm3_reader *r, {struct} *m)",
        c_layout(f"{{ {reads} return true; }}"),
        "",
        f"static bool rtcm3_write_{record.name}(const {struct} *m, nmea_rtcm3_writer *w)",
        c_layout(f"{{ {writes} return true; }}"),
        ""]) + "\n".join([
        f"static void rtcm3_json_{record.name}(const {struct} *m, nmea_rtcm3_json_out *j)",
        c_layout(f"{{ {json} }}"), ""])
    return typedef, code


def emit(spec: Spec, env: jinja2.Environment) -> dict[str, str]:
    messages: list[Payload] = [m for m in spec.bit_messages if m.protocol == "rtcm3"]
    if not messages:
        return {}
    typedefs: list[str] = []
    functions: list[str] = []
    specials: list[str] = []
    for payload in messages:
        record = Record(payload.id, payload.items, {f.id: f for f in payload.fields})
        for entry in record.entries:
            t, c = record_code(entry, False, f"One entry of {entry.name}.")
            typedefs.append(t)
            functions.append(c)
        t, c = record_code(record, True, title_of(payload))
        typedefs.append(t)
        functions.append(c)
        specials += record.specials
    sources = [m.origin.file for m in messages]
    context = dict(messages=messages, typedefs=typedefs, functions=functions, specials=specials,
                   runtime_h=(RUNTIME / "c" / "rtcm3.h").read_text(encoding="utf-8"),
                   runtime_c=runtime_source("rtcm3.c"))
    return {
        "c/nmea_rtcm3.h": env.get_template("c/nmea_rtcm3.h.j2").render(
            header=header(spec, "//", ["templates/c/nmea_rtcm3.h.j2", "runtime/c/rtcm3.h", *sources]), **context),
        "c/nmea_rtcm3.c": env.get_template("c/nmea_rtcm3.c.j2").render(
            header=header(spec, "//", ["templates/c/nmea_rtcm3.c.j2", "runtime/c/rtcm3.c", *sources]), **context),
    }
