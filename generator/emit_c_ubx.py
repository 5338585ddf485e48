"""C emitter of the binary messages (spec/binary/ubx, and the other protocols' of
spec/binary/<protocol>/messages: SkyTraq, SiRF, CASIC, SBF): the pair nmea_ubx.h / nmea_ubx.c, beside
the NMEA pair and independent of it (a firmware links it only if it wants UBX). A struct per
layout, every field typed; a descriptor per layout (its items: kind, bytes, member offset, scale,
enum, group) that one reader, one writer and one JSON printer interpret (runtime/c/ubx.{h,c},
pasted in), as STYLE.md's "layouts as data" says, and for the layouts the receiver sends a
straight-line reader (_FastReader: fixed offsets) that decode tries first, falling back on the
interpreter for whatever it does not read whole (errors are the interpreter's); nmea_ubx_decode / nmea_ubx_encode /
nmea_ubx_json dispatch on the class and id, then the length and version, as Python's ubx.message;
nmea_ubx_decode_frame_of on another protocol's key (its header's class and id, or its payload's id
and sub-id), as Python's binary.message, each protocol framed by its row of a framing table
(emit_framing's facts) and read in its byte order. A layout of another protocol is named with its
protocol (nmea_ubx_skytraq_nav_data, NMEA_UBX_MSG_SKYTRAQ_NAV_DATA).

No heap, no VLA: a group is an array of a fixed maximum (what its count field, the spec's maximum
and a 65535-byte payload allow, lowered by a firmware with NMEA_UBX_MAX_ENTRIES or the group's own
NMEA_UBX_<LAYOUT>_<GROUP>_MAX); a field of the bytes left and the trailing bytes are views of the
payload. Struct members keep the wire order except the groups' arrays, which come last so that
every other member's offset stays small whatever the maxima."""

from __future__ import annotations

import jinja2

from .emit import RUNTIME, header, runtime_source, typed_natively
from .emit_framing import framing, kept_fields, wire_key
from .emit_python_ubx import title
from .model import BinaryProtocol, EnumDef, PayloadField, PayloadGroup, Spec
from .names_c import member
from .reference_ais import after

MAX_PAYLOAD = 0xFFFF


def _c_str(text: str) -> str:
    return '"' + text.replace("\\", "\\\\").replace('"', '\\"') + '"'


def _int_bytes(size: int) -> int:
    """The bytes of the C integer that holds `size` bytes."""
    return next(n for n in (1, 2, 4, 8) if size <= n)


def _part_bytes(bits: int) -> int:
    """The bytes of the C integer that holds a bitfield's part of `bits` bits."""
    return _int_bytes((bits + 7) // 8)


def _doc(f: PayloadField) -> str:
    """A member's comment: the field's name, unit, and its enum or how its raw integer scales."""
    unit = f" [{f.unit}]" if f.unit else ""
    scale = f"; a code of {f.enum.id} (its JSON: the code's id)" if f.enum is not None else ""
    if f.scaled:
        scale = f"; raw, value = raw{f' / {f.divisor}' if f.divisor else ''}{f' + {f.base}' if f.base else ''}"
    if f.special:   # its special values, which the JSON gives by id
        scale += "; " + ", ".join(f"{s.shown}: {s.id}" for s in f.special)
    return (f.name + unit + scale).replace("*/", "* /")


class _Layout:
    """The C code of one layout (or a group's entry): its struct and its descriptor rows."""

    def __init__(self, struct: str, prefix: str, items: list, upper: str, big: bool = False) -> None:
        self.big = big              # of a big-endian protocol
        # The bytes of each integer member a group may be counted by (a field, a bitfield's part).
        self.counters: dict[str, tuple[int, int]] = {}
        for f in items:
            if isinstance(f, PayloadField) and f.bits is not None and f.bit_type.size:
                self.counters[f.id] = (_int_bytes(f.bits // 8), f.bits)
                self.counters.update({p.id: (_part_bytes(p.bits or 1), p.bits or 1) for p in f.parts})
        self.items = items
        self.doc = ""
        self.struct = struct        # nmea_ubx_nav_pvt
        self.cid = ""               # nav_pvt: its member of nmea_ubx_message's union (a layout's, not an entry's)
        self.prefix = prefix        # ubx_nav_pvt (of its tables)
        self.upper = upper          # NAV_PVT (of its defines)
        self.members: list[str] = []
        self.arrays: list[str] = []
        self.rows: list[str] = []
        self.tables: list[str] = []     # scales, enums, groups: before the rows
        self.entries: list[_Layout] = []
        self.defines: list[str] = []
        self.names: set[str] = set()
        for i, item in enumerate(items):
            if isinstance(item, PayloadGroup):
                self._group(item, items[i + 1:])
            else:
                self._field(item, items[i + 1:])

    def _name(self, name: str) -> str:
        assert name not in self.names, f"{self.struct}: two members named {name}"
        self.names.add(name)
        return name

    def _row(self, f: PayloadField, name: str, kind: str, size: int, width: int, *, low: int = 0,
             print_as: str = "NUMBER", has: str = "0", after_bytes: int = 0, optional: bool = False) -> None:
        extra = "NULL"
        if f.enum is not None:   # its enum's table (enum_table), one for every field of it
            extra, print_as = f"&ubx_enum_{f.enum.id}", "CODE"
        elif f.scaled or f.special:   # a float's special values: their bit patterns (raw), no scale
            specials = "NULL, 0"
            if f.special:
                # a float's bit pattern as the int64_t of its bits (an r8's may have the top bit set)
                rows = ", ".join(f"{{{s.raw - (1 << 64) if s.raw >= 1 << 63 else s.raw}, {_c_str(s.id)}}}"
                                 for s in f.special)
                self.tables.append(f"static const nmea_ubx_special {self.prefix}_{f.id}_specials[] = {{{rows}}};")
                specials = f"{self.prefix}_{f.id}_specials, {len(f.special)}"
            real = "true" if f.divisor is not None or isinstance(f.base, float) else "false"
            self.tables.append(f"static const nmea_ubx_scale {self.prefix}_{f.id}_scale = "
                               f"{{{float(f.divisor or 1)!r}, {float(f.base or 0)!r}, {real}, {specials}}};")
            extra = f"&{self.prefix}_{f.id}_scale"
            print_as = "NUMBER" if f.type in ("r4", "r8") else "SCALED"
        self.rows.append(self.row(f.id, extra, f"offsetof({self.struct}, {name})", has, after_bytes, kind, size, width, low,
                                  print_as, optional))

    @staticmethod
    def row(key: str, extra: str, offset: str, has: str, after_bytes: int, kind: str, size: int, width: int, low: int,
            print_as: str, optional: bool) -> str:
        """A descriptor row (nmea_ubx_item) in its members' order."""
        return (f"{{{_c_str(key)}, {extra}, {offset}, {has}, {after_bytes}, NMEA_UBX_ITEM_{kind}, {size}, {width}, {low}, "
                f"NMEA_UBX_PRINT_{print_as}, {'true' if optional else 'false'}}}")

    def _field(self, f: PayloadField, following: list) -> None:
        t = f.bit_type
        name = self._name(member(f.id))
        has = "0"
        if f.optional:
            flag = self._name(f"has_{name}")
            self.members.append(f"bool {flag}; /* whether the payload has {name} */")
            has = f"offsetof({self.struct}, {flag})"
        doc = _doc(f)
        if f.bits is None:   # ch, bytes of the bytes left: a view
            assert t.name in ("ch", "bytes"), f"{self.struct}.{name}: {t.name} of the bytes left"
            self.members.append(f"nmea_ubx_bytes {name}; /* {doc} (the bytes left{', ISO 8859-1' if t.name == 'ch' else ''}) */")
            self._row(f, name, "VIEW", 0, 0, print_as="CHARS" if t.name == "ch" else "HEX",
                      after_bytes=after(following) // 8)
            return
        size = f.bits // 8
        if t.name == "reserved" and size > 8 and self.big:
            raise NotImplementedError(f"{f.origin.file}: {f.id}: a reserved field of {size} bytes, big endian, "
                                      "has no C code yet (its JSON integer)")
        if t.name in ("ch", "bytes") or t.name == "reserved" and size > 8:
            c_type = "char" if t.name == "ch" else "uint8_t"
            self.members.append(f"{c_type} {name}[{size}]; /* {doc}{' (as sent)' if t.name != 'bytes' else ''} */")
            self._row(f, name, "ARRAY", size, size,
                      print_as={"ch": "CHARS", "bytes": "HEX"}.get(t.name, "BIG"), has=has, optional=f.optional)
            return
        if t.name in ("r4", "r8"):
            self.members.append(f"{'float' if size == 4 else 'double'} {name}; /* {doc} (its bits as sent) */")
            self._row(f, name, "FLOAT", size, size, has=has, optional=f.optional)
            return
        width = _int_bytes(size)
        signed = t.signed
        kind = "WORD" if t.has_parts else "SIGNED" if signed else "UNSIGNED"
        self.members.append(f"{'int' if signed else 'uint'}{8 * width}_t {name}; /* {doc}"
                            f"{' (bitfield)' if t.has_parts else ''}{' (reserved, as sent)' if t.name == 'reserved' else ''} */")
        self._row(f, name, kind, size, width, has=has, optional=f.optional)
        for part in f.parts:
            pname = self._name(member(part.id))
            bits = part.bits or 1
            last = part.low + bits - 1
            where = f"bit {part.low}" if bits == 1 else f"bits {part.low}-{last}"
            if part.type == "bool":
                self.members.append(f"bool {pname}; /* {_doc(part)} ({name} {where}) */")
                self._row(part, pname, "PART_FLAG", bits, 1, low=part.low)
                continue
            pwidth = _part_bytes(bits)
            psigned = part.bit_type.signed
            self.members.append(f"{'int' if psigned else 'uint'}{8 * pwidth}_t {pname}; /* {_doc(part)} ({name} {where}) */")
            self._row(part, pname, "PART_SIGNED" if psigned else "PART", bits, pwidth, low=part.low)

    def _group(self, g: PayloadGroup, following: list) -> None:
        # The interpreter reads an entry field by field: no optional field or bytes left in it (but a
        # stride's trailing bytes, its last field: a view of the entry's bytes after its fields), and
        # maybe a nested group after them (rule B010), whose entries of every entry are one array of
        # the message, each entry's from its index (<nested>_first) on.
        fixed_fields = g.fields[:-1] if g.stride is not None else g.fields
        assert all(isinstance(f, PayloadField) and f.bits is not None and not f.optional for f in fixed_fields), g.id
        word = g.id[:-1] if g.id.endswith("s") else g.id + "_entry"
        entry = _Layout(f"{self.struct}_{word}", f"{self.prefix}_{word}", list(g.fields), f"{self.upper}_{word.upper()}",
                        self.big)
        assert not entry.entries, f"{self.struct}.{g.id}: a group in a group"
        entry.doc = f"One entry of {g.name.lower()} ({g.id})."
        name = self._name(member(g.id))
        count_name = self._name(f"{name}_count")
        entry_bytes = g.entry_width // 8
        fixed = sum(f.bits // 8 for f in self.items if isinstance(f, PayloadField) and f.bits is not None)
        natural = min(g.max, (MAX_PAYLOAD - fixed) // entry_bytes)
        if g.count is None and g.max >= MAX_PAYLOAD:   # the bytes left, no maximum in the spec (SiRF MID 4):
            natural = min(natural, 255)                   # as many as a U1 count says, not 4,368

        count_kind, count, count_offset, count_member = "LEFT", 0, "0", 1
        if isinstance(g.count, int):
            count_kind, count, natural = "FIXED", g.count, g.count
        elif g.count:
            count_member, bits = self.counters[g.count]
            count_kind, count_offset = "FIELD", f"offsetof({self.struct}, {member(g.count)})"
            natural = min(natural, (1 << bits) - 1)
        nested = "NULL, NULL, 0, 0"
        if g.nested is not None:
            nested = self._nested(g, entry, natural)
        self.entries.append(entry)
        define = self._bound(g.id, natural)
        self.members.append(f"uint16_t {count_name}; /* the entries of {name} */")
        self.arrays.append(f"{entry.struct} {name}[{define}]; /* {g.name} */")
        table = f"{self.prefix}_{g.id}_group"
        self.tables.append(
            f"static const nmea_ubx_group {table} = {{{entry.prefix}_items, {len(entry.rows)}, NMEA_UBX_COUNT_{count_kind}, "
            f"{count_member}, {count_offset}, {count}, {g.min}, {g.max}, {define}, {entry_bytes}, sizeof({entry.struct}), "
            f"{after(following) // 8}, offsetof({self.struct}, {count_name}), "
            + (f"{self.counters[g.stride][0]}, offsetof({self.struct}, {member(g.stride)}), {_c_str(g.stride)}, "
               if g.stride else "0, 0, NULL, ") + f"{nested}}};")
        self.rows.append(self.row(g.id, f"&{table}", f"offsetof({self.struct}, {name})", "0", 0, "GROUP", 0, 0, 0,
                                  "NUMBER", False))

    def _bound(self, group_id: str, natural: int) -> str:
        """The macro of a group's array size: `natural` entries, at most NMEA_UBX_MAX_ENTRIES, unless
        the build sets it."""
        define = f"NMEA_UBX_{self.upper}_{group_id.upper()}_MAX"
        self.defines += [f"#ifndef {define}",
                         f"#define {define} ({natural} < NMEA_UBX_MAX_ENTRIES ? {natural} : NMEA_UBX_MAX_ENTRIES)",
                         "#endif"]
        return define

    def _nested(self, g: PayloadGroup, entry: _Layout, outer: int) -> str:
        """The group each entry of `g` ends with: its entries' struct, the message's one array of them
        (of `outer` entries by default, as many as the outer group's: one each when that is full; a
        build may set NMEA_UBX_<LAYOUT>_<GROUP>_MAX), its descriptor; the outer descriptor's last
        members (nested, nested_id, nested_offset, nested_first)."""
        n = g.nested
        assert n is not None and isinstance(n.count, str) and n.nested is None
        word = n.id[:-1] if n.id.endswith("s") else n.id + "_entry"
        inner = _Layout(f"{self.struct}_{word}", f"{self.prefix}_{word}", list(n.fields), f"{self.upper}_{word.upper()}",
                        self.big)
        inner.doc = f"One entry of {n.name.lower()} ({n.id}; every entry of {g.id}'s in one array)."
        self.entries.append(inner)
        name = self._name(member(n.id))
        count_name = self._name(f"{name}_count")
        first = entry._name(f"{name}_first")
        entry.members.append(f"uint16_t {first}; /* the index in {name} of its first entry "
                             f"({member(n.count)} of them) */")
        define = self._bound(n.id, outer)
        self.members.append(f"uint16_t {count_name}; /* the entries of {name}, every {g.id} entry's */")
        self.arrays.append(f"{inner.struct} {name}[{define}]; /* {n.name}: those of {g.id}[k] from its {first} on */")
        count_member, _ = entry.counters[n.count]
        assert n.stride is not None   # rule B010
        stride = f"{self.counters[n.stride][0]}, offsetof({self.struct}, {member(n.stride)}), {_c_str(n.stride)}"
        table = f"{self.prefix}_{n.id}_group"
        self.tables.append(
            f"static const nmea_ubx_group {table} = {{{inner.prefix}_items, {len(inner.rows)}, NMEA_UBX_COUNT_FIELD, "
            f"{count_member}, offsetof({entry.struct}, {member(n.count)}), 0, {n.min}, {n.max}, {define}, "
            f"{n.entry_width // 8}, sizeof({inner.struct}), 0, offsetof({self.struct}, {count_name}), {stride}, "
            "NULL, NULL, 0, 0};")
        return f"&{table}, {_c_str(n.id)}, offsetof({self.struct}, {name}), offsetof({entry.struct}, {first})"

    def typedef(self, doc: str, trailing: bool) -> str:
        members = list(self.members)
        if trailing:
            members.append("nmea_ubx_bytes trailing; /* the payload's bytes after the layout, as sent */")
        members += self.arrays
        if not members:
            members = ["uint8_t empty; /* no field */"]
        return f"/* {doc} */\n" + "typedef struct {\n    " + "\n    ".join(members) + f"\n}} {self.struct};\n"

    def code(self) -> str:
        rows = ",\n    ".join(self.rows)
        items = f"static const nmea_ubx_item {self.prefix}_items[] = {{\n    {rows}\n}};" if self.rows \
            else f"static const nmea_ubx_item {self.prefix}_items[1] = {{{self.row('', 'NULL', '0', '0', 0, 'UNSIGNED', 0, 0, 0, 'NUMBER', False)}}};"
        return "\n".join([*self.tables, items, ""])


def _load(size: int, big: bool, at: str) -> str:
    """The C expression of the `size` bytes at `at` as an unsigned integer of the protocol's order."""
    if size == 1:
        base, _, offset = at.partition(" + ")
        return f"{base}[{offset or 0}]"
    if big:
        return f"ubx_be({at}, {size})"
    return {2: f"ubx_u16({at})", 4: f"ubx_u32({at})", 8: f"ubx_u64({at})"}.get(size, f"ubx_le({at}, {size})")


class _FastReader:
    """A layout's straight-line reader (STYLE.md: "a straight-line fast reader only where the
    benchmark shows it pays": nmea_ubx_decode, bench ours-c-ubx): the struct the interpreter
    (ubx_read_layout) fills from a payload it reads without an error, the same members (not the
    padding between them: no memset of the struct, each member stored once); for any other payload
    (short, a group's count out of bounds) it gives up before deciding anything, and the
    interpreter reads the payload and names the error. Fixed offsets from `q`, which moves on after
    a group or a field of the bytes left; `left` counts the bytes from `q` on."""

    def __init__(self, layout: "_Layout") -> None:
        self.layout = layout
        self.big = layout.big
        self.lines: list[str] = []
        self.uses_word = False
        self.uses_k = False
        self.uses_done = False

    def _value(self, f: PayloadField, at: str, target: str, indent: str) -> int:
        """Statements reading field `f` (fixed bits, not a group) at `at` into `target` (its member,
        `e->` or `m->`); its parts after it. Returns its bytes."""
        t = f.bit_type
        assert f.bits is not None
        size = f.bits // 8
        name = member(f.id)
        out = self.lines
        if t.name in ("ch", "bytes") or t.name == "reserved" and size > 8:
            out.append(f"{indent}memcpy({target}{name}, {at}, {size});")
            return size
        raw = _load(size, self.big, at)
        if t.name in ("r4", "r8"):
            bits = "uint32_t" if size == 4 else "uint64_t"
            out.append(f"{indent}{{ /* a float's bits, as sent */")
            out.append(f"{indent}    {bits} bits = ({bits}){raw};")
            out.append(f"{indent}    memcpy(&{target}{name}, &bits, {size});")
            out.append(f"{indent}}}")
            return size
        width = _int_bytes(size)
        c_type = f"{'int' if t.signed else 'uint'}{8 * width}_t"
        if f.parts:
            self.uses_word = True
            out.append(f"{indent}w = {raw};")
            out.append(f"{indent}{target}{name} = ({c_type})w;")
            for part in f.parts:
                pbits = part.bits or 1
                mask = f"0x{(1 << pbits) - 1:X}u" if pbits < 64 else "~(uint64_t)0"
                bits_of = f"(w >> {part.low} & {mask})" if part.low else f"(w & {mask})"
                pname = member(part.id)
                if part.type == "bool":
                    out.append(f"{indent}{target}{pname} = {bits_of} != 0;")
                    continue
                ptype = f"{'int' if part.bit_type.signed else 'uint'}{8 * _part_bytes(pbits)}_t"
                if part.bit_type.signed:
                    out.append(f"{indent}{target}{pname} = ({ptype})(int64_t)ubx_sign({bits_of}, {pbits});")
                else:
                    out.append(f"{indent}{target}{pname} = ({ptype}){bits_of};")
            return size
        if t.signed and size != width:
            out.append(f"{indent}{target}{name} = ({c_type})(int64_t)ubx_sign({raw}, {8 * size});")
        elif t.signed or size != width or self.big:
            out.append(f"{indent}{target}{name} = ({c_type}){raw};")
        else:
            out.append(f"{indent}{target}{name} = {raw};")
        return size

    def _flush(self, offset: int) -> None:
        """`q` moved on past the `offset` bytes read from it."""
        if offset:
            self.lines.append(f"    q += {offset};")
            self.lines.append(f"    left -= {offset};")

    def code(self) -> str:
        lay = self.layout
        items = lay.items
        out = self.lines
        # No memset of the struct: every member is stored below but an optional field's, whose
        # absence zeroes its flag and what follows (the padding between members is not written).
        offset = 0        # bytes read from q on, checked (`run` of them)
        checked = 0
        for i, item in enumerate(items):
            following = items[i + 1:]
            if isinstance(item, PayloadGroup):
                self._flush(offset)
                offset = checked = 0
                self._group(item, following)
                continue
            f = item
            name = member(f.id)
            if f.bits is None:   # a field of the bytes left: a view
                self._flush(offset)
                offset = checked = 0
                tail = after(following) // 8
                out.append(f"    m->{name}.ptr = q;")
                out.append(f"    m->{name}.len = left > {tail} ? left - {tail} : 0;")
                out.append(f"    q += m->{name}.len;")
                out.append(f"    left -= m->{name}.len;")
                continue
            size = f.bits // 8
            if f.optional:
                self._flush(offset)
                offset = checked = 0
                self.uses_done = True
                out.append(f"    if (left < {size}) {{ /* an optional field the payload has not: nothing after it */")
                out.append(f"        memset(&m->has_{name}, 0, offsetof({lay.struct}, trailing) - "
                           f"offsetof({lay.struct}, has_{name}));")
                out.append("        goto done;")
                out.append("    }")
                out.append(f"    m->has_{name} = true;")
                self._value(f, "q", "m->", "    ")
                out.append(f"    q += {size};")
                out.append(f"    left -= {size};")
                continue
            if offset >= checked:   # a run of required fields of fixed offsets: their bytes checked once
                run = 0
                for g in items[i:]:
                    if not isinstance(g, PayloadField) or g.bits is None or g.optional:
                        break
                    run += g.bits // 8
                out.append(f"    if (left < {offset + run})")
                out.append("        return false;")
                checked = offset + run
            self._value(f, f"q + {offset}" if offset else "q", "m->", "    ")
            offset += size
        self._flush(offset)
        if self.uses_done:
            out.append("done:")
        out.append("    m->trailing.ptr = q;")
        out.append("    m->trailing.len = left;")
        out.append("    return true;")
        head = [f"static bool {lay.prefix}_fast(const uint8_t *p, size_t len, nmea_ubx_message *out)", "{",
                f"    {lay.struct} *m = &out->as.{lay.cid};", "    const uint8_t *q = p;", "    size_t left = len;"]
        if self.uses_word:
            head.append("    uint64_t w;")
        if self.uses_k:
            head.append("    size_t k;")
        return "\n".join([*head, *out, "}", ""])

    def _group(self, g: PayloadGroup, following: list) -> None:
        lay = self.layout
        out = self.lines
        name = member(g.id)
        entry_bytes = g.entry_width // 8
        define = f"NMEA_UBX_{lay.upper}_{g.id.upper()}_MAX"
        self.uses_k = True
        out.append("    {")
        if isinstance(g.count, int):
            out.append(f"        size_t count = {g.count};")
        elif g.count:
            width, _ = lay.counters[g.count]
            out.append(f"        size_t count = (uint{8 * width}_t)m->{member(g.count)};")
        else:
            tail = after(following) // 8
            out.append(f"        size_t count = left > {tail} ? (left - {tail}) / {entry_bytes} : 0;")
            out.append(f"        if (count > {g.max})")
            out.append(f"            count = {g.max};")
        low = f"count < {g.min} || " if g.min else ""
        out.append(f"        if ({low}count * {entry_bytes} > left || count > {define})")
        out.append("            return false;")
        out.append(f"        for (k = 0; k < count; k++, q += {entry_bytes}) {{")
        out.append(f"            {lay.struct}_{g.id[:-1] if g.id.endswith('s') else g.id + '_entry'} *e = &m->{name}[k];")
        offset = 0
        for f in g.fields:
            offset += self._value(f, f"q + {offset}" if offset else "q", "e->", "            ")
        out.append("        }")
        out.append(f"        left -= count * {entry_bytes};")
        out.append(f"        m->{name}_count = (uint16_t)count;")
        out.append("    }")


def enum_table(e: EnumDef) -> str:
    """An enum's codes and ids (nmea_ubx_codes), which its fields' JSON prints."""
    rows = ", ".join(f"{{{v.code}, {_c_str(v.id)}}}" for v in e.values)
    return (f"static const nmea_ubx_code ubx_enum_{e.id}_list[] = {{{rows}}};\n"
            f"static const nmea_ubx_codes ubx_enum_{e.id} = {{ubx_enum_{e.id}_list, {len(e.values)}}};\n")


def carries_ubx(spec: Spec) -> bool:
    """Whether the spec describes UBX messages, and so the UBX pair beside the NMEA one."""
    return any(m.protocol == "ubx" for m in spec.binary)


def _framing_row(p: BinaryProtocol) -> str:
    """A protocol's row of ubx_framings (nmea_ubx_framing)."""
    f = framing(p)
    where = f"{p.origin.file}: frame"
    if len(f.sync) < 2 or f.length_size != 2:
        raise NotImplementedError(f"{where}: the UBX pair frames two or three sync bytes and a length of two bytes")
    # the header's bytes that hold the key (a class and an id byte; SBF's number and revision, Unicore's id)
    key_at = {b for _, at, bits in f.identity for b in range(at // 8, (at + bits - 1) // 8 + 1)}
    if not key_at <= set(range(f.header)):   # the key starts the payload: its id (and sub-id)
        key_at = set()
    elif len(key_at) != 2 or max(key_at) != min(key_at) + 1:
        raise NotImplementedError(f"{where}: a key in the header is two bytes (a class and an id byte, or a word)")
    end = list(f.end) + [0] * (2 - len(f.end))
    fields = "{0, 0, 0}, {0, 0, 0}"
    if key_at:   # the key's fields in the 16-bit word of its two header bytes, in the protocol's byte order
        first = 8 * min(key_at)
        fields = ", ".join([f'{{"{name}", {16 - (at - first) - bits if f.big_endian else at - first}, {bits}}}'
                            for name, at, bits in f.identity] + ["{0, 0, 0}"] * (2 - len(f.identity)))
    sync = ", ".join(f"0x{b:02X}" for b in f.sync + bytes(3 - len(f.sync)))
    kept = f"ubx_kept_{p.id}, {len(f.kept)}" if f.kept else "NULL, 0"
    return (f'{{"{p.id}", "{p.id.upper()}", {{{sync}}}, {len(f.sync)}, {f.header}, {f.length_at}, '
            f'0x{f.length_mask:04X}, {min(key_at) if key_at else 0}, NMEA_UBX_CHECK_{f.checksum.upper()}, {f.check_from}, '
            f'{f.check_size}, {{0x{end[0]:02X}, 0x{end[1]:02X}}}, {len(f.end)}, {"true" if f.big_endian else "false"}, '
            f'{f.length_adds}, {f.check_at}, {{{fields}}}, {kept}}}')


def _kept(p: BinaryProtocol) -> dict | None:
    """A protocol's header fields that a message keeps (Unicore's time and status): its struct
    (nmea_ubx_<protocol>_header, the member `header.<protocol>` of nmea_ubx_message) and its table
    of nmea_ubx_header_field; None for a protocol with none."""
    fields = kept_fields(p)
    if not fields:
        return None
    types = {1: "uint8_t", 2: "uint16_t", 4: "uint32_t"}
    return {"protocol": p.id, "struct": f"nmea_ubx_{p.id}_header", "name": p.name,
            "members": [f"{types[k.size]} {k.id}; /* {k.doc} */" for k in fields],
            "rows": [f'{{"{k.id}", {k.at}, {k.size}, offsetof(nmea_ubx_message, header.{p.id}.{k.id})}}'
                     for k in fields]}


def _pick(layouts: list[dict], first: int) -> list[tuple[str, int]]:
    """The layout of a message (its `layouts`, numbered from `first`) a payload is read as, as
    ubx_layout_for chooses it, decided here from their lengths and selectors: (condition on `len`
    and `payload`, layout) in order, the last with no condition."""
    rows = []
    for i, lay in enumerate(layouts, first):
        conds = []
        length, value, at = lay["length"], lay["select_value"], lay["select_at"]
        if length >= 0:
            conds.append(f"len == {length}")
        if value >= 0:
            if 0 <= length <= at:   # its selector beyond its length: never this one
                continue
            if length < 0:
                conds.append(f"len > {at}")
            conds.append(f"payload[{at}] == 0x{value:02X}")
        if not conds:
            rows.append(("", i))
            break
        rows.append((" && ".join(conds), i))
    else:
        # a selector value no layout names: the selected layout of its length; else the first the
        # receiver sends, else the last
        rows += [(f"len == {lay['length']}", i) for i, lay in enumerate(layouts, first)
                 if lay["select_value"] >= 0 and lay["length"] >= 0]
        rows.append(("", next((i for i, lay in enumerate(layouts, first) if lay["output"]), first + len(layouts) - 1)))
    while len(rows) > 1 and rows[-2][1] == rows[-1][1]:   # a test that picks what the default picks
        del rows[-2]
    return rows


def emit(spec: Spec, env: jinja2.Environment) -> dict[str, str]:
    if not carries_ubx(spec):
        return {}
    ubx = sorted((m for m in spec.binary if m.protocol == "ubx"), key=lambda m: (m.class_number, m.msg_id))
    # The other protocols' messages by protocol, then key (an id and sub-id before the id alone).
    names = ["ubx", *[p for p in typed_natively(spec) if p != "ubx"]]
    protocols = [next(p for p in spec.protocols if p.id == name) for name in names]
    others = sorted((m for m in spec.binary if m.protocol in names[1:]),
                    key=lambda m: (names.index(m.protocol), len(m.key) == 1, m.key))
    messages = ubx + others
    layouts = []
    for message in messages:
        for layout in message.layouts:
            cid = layout.id if message.protocol == "ubx" else f"{message.protocol}_{layout.id}"
            code = _Layout(f"nmea_ubx_{cid}", f"ubx_{cid}", layout.items, cid.upper(), message.byte_order == "big")
            code.cid = cid
            select_at = layout.select_at if layout.select is not None else 0
            assert select_at is not None
            key = list(wire_key(spec, message)) + [0] * (2 - len(message.key))
            layouts.append(dict(
                message=message, layout=layout, code=code, cid=cid, key=key, protocol=message.protocol.upper(),
                key_len=0 if message.header_key else len(message.key),
                typedefs=[e.typedef(e.doc, False) for e in code.entries] + [code.typedef(title(message, layout), True)],
                tables="\n".join([*(e.code() for e in code.entries), code.code()]),
                # a straight-line reader for what the receiver sends (a stream's messages), not
                # for the commands only a host writes, which the interpreter reads (flash)
                # (none for a layout of a stride's group, whose entries' bytes the interpreter bounds)
                fast=_FastReader(code).code() if "output" in layout.directions
                and not any(isinstance(g, PayloadGroup) and g.stride for g in layout.items) else "",
                defines=[d for e in code.entries for d in e.defines] + code.defines,
                length=layout.fixed_width // 8 if layout.fixed_width is not None else -1,
                select_value=layout.select[1] if layout.select is not None else -1, select_at=select_at,
                n_items=len(code.rows), output="output" in layout.directions))
    enums = {f.enum.id: f.enum for m in messages for lay in m.layouts for field in lay.fields
             for f in (field, *field.parts) if f.enum}
    sources = [m.origin.file for m in messages] + sorted({e.origin.file for e in enums.values()})
    keyed, first = [], 0
    for m in messages:   # each message's layouts: the first and the last of ubx_layouts
        last = first + len(m.layouts) - 1
        key = list(wire_key(spec, m)) + [0] * (2 - len(m.key))
        keyed.append(dict(message=m, first=first, last=last, key=key, protocol=m.protocol.upper(),
                          key_len=0 if m.header_key else len(m.key), pick=_pick(layouts[first:last + 1], first)))
        first = last + 1
    classes: dict[int, list[dict]] = {}   # UBX's messages by class (the fast build's switch)
    for k in keyed[:len(ubx)]:
        classes.setdefault(k["key"][0], []).append(k)
    context = dict(layouts=layouts, ubx=keyed[:len(ubx)], others=keyed[len(ubx):], classes=sorted(classes.items()),
                   protocols=[p.id.upper() for p in protocols], framings=[_framing_row(p) for p in protocols],
                   kept=[k for k in (_kept(p) for p in protocols) if k],
                   enums=[enum_table(enums[key]) for key in sorted(enums)],
                   runtime_h=(RUNTIME / "c" / "ubx.h").read_text(encoding="utf-8"),
                   nested=any(isinstance(g, PayloadGroup) and g.nested is not None
                              for m in messages for lay in m.layouts for g in lay.items),
                   runtime_c=runtime_source("ubx.c"))
    return {
        "c/nmea_ubx.h": env.get_template("c/nmea_ubx.h.j2").render(
            header=header(spec, "//", ["templates/c/nmea_ubx.h.j2", "runtime/c/ubx.h", *sources]), **context),
        "c/nmea_ubx.c": env.get_template("c/nmea_ubx.c.j2").render(
            header=header(spec, "//", ["templates/c/nmea_ubx.c.j2", "runtime/c/ubx.c", *sources]), **context),
    }
