"""C emitter of the bit-packed payloads (spec/ais): the pair nmea_ais.h / nmea_ais.c, a struct per
layout with straight-line read, write and JSON functions over the runtime's bit reader and writer
(runtime/c/ais.{h,c}, pasted in), and nmea_ais_decode / nmea_ais_encode / nmea_ais_json that
dispatch on the message type and on DAC/FI. No heap: text and data are views of the payload.

As in the Rust module (emit_rust_ais.py): a field that may be missing (optional, after an
optional one, or in a case of a choice) has a `has_<member>` flag; a number with a divisor, a base
or special values and an enum keep their raw integer (`<id>_raw`)."""

from __future__ import annotations

import jinja2

from .emit import RUNTIME, header, runtime_source
from .emit_rust_ais import member_name, read_before
from .emit_python_ais import title as title_of
from .model import Payload, PayloadChoice, PayloadField, PayloadGroup, Spec
from .names_c import ais_entry_record, ais_struct, layout_const, member
from .reference_ais import after

BITS = "nmea_ais_bits"


def _c_str(text: str) -> str:
    return '"' + text.replace("\\", "\\\\").replace('"', '\\"') + '"'


def c_type(f: PayloadField) -> str:
    if f.type in ("text", "data") or f.type == "spare" and f.bits > 64:
        return BITS
    if f.type == "bool":
        return "bool"
    size = next(n for n in (8, 16, 32, 64) if f.bits <= n)
    return f"{'int' if f.type == 'int' else 'uint'}{size}_t"


class _Record:
    """The C code of one layout (a message, an application, a group's entry)."""

    def __init__(self, name: str, items: list, dispatches: bool = False, entry: bool = False) -> None:
        self.name = name          # snake: position_report, binary_acknowledge_ack
        self.dispatches = dispatches
        self.entry = entry        # a group's entry: its choices' selectors are its own fields, read before them
        self.members: list[str] = []
        self.read: list[str] = []
        self.write: list[str] = []
        self.json: list[str] = []
        self.optional = False
        self.uncertain = False
        self.certain: set[str] = set()
        self.entries: list[_Record] = []
        self.specials: list[str] = []
        self._walk(items, [], True)

    def _walk(self, items: list, rest: list, certain: bool) -> bool:
        for i, item in enumerate(items):
            following = items[i + 1:] + rest
            if isinstance(item, PayloadField):
                if item.optional:
                    certain = False
                    self.optional = True
                    self.read.append(f"if (ais_remaining(r) < {item.bits}) goto done;")
                self._field(item, following, certain)
            elif isinstance(item, PayloadGroup):
                self._group(item, following)
            else:
                self._choice(item, following)
                certain = False
        return certain

    def _field(self, f: PayloadField, following: list, certain: bool) -> None:
        name, kind, width, key = member_name(f), c_type(f), f.bits, _c_str(f.id)
        self.members.append(f"{kind} {name}; /* {f.name}{f' [{f.unit}]' if f.unit else ''} */")
        if certain:
            self.certain.add(name)
        else:
            self.uncertain = True
            self.members.append(f"bool has_{name};")
        has = "" if certain else f" m->has_{name} = true;"
        if kind == BITS:
            if width is None:
                left = f"(ais_remaining(r) > {after(following)} ? ais_remaining(r) - {after(following)} : 0)" \
                    if after(following) else "ais_remaining(r)"
                width_expr = f"{left} / 6 * 6" if f.type == "text" else left
            else:
                width_expr = str(width)
            self.read.append(f"if (!ais_take_bits(r, {width_expr}, {key}, &m->{name})) return false;{has}")
            put = f"if (!ais_put_bits(w, m->{name}, {key})) return false;" if width is None else \
                f"if (!ais_put_fixed(w, m->{name}, {width}, {'true' if f.type == 'text' else 'false'}, {key})) return false;"
        elif f.type == "int":
            self.read.append(f"if (!ais_take_signed(r, {width}, {key}, &signed_raw)) return false; "
                             f"m->{name} = ({kind})signed_raw;{has}")
            put = f"if (!ais_put_signed(w, m->{name}, {width}, {key})) return false;"
        else:
            value = "raw == 1" if kind == "bool" else f"({kind})raw"
            self.read.append(f"if (!ais_take(r, {width}, {key}, &raw)) return false; m->{name} = {value};{has}")
            put = f"if (!ais_put(w, m->{name}, {width}, {key})) return false;"
        if f.dispatch and self.dispatches:
            put = f"if (m->has_application) {{ if (!ais_write_application(&m->application, w)) return false; }} " \
                  f"else {{ {put} }}"
        self.write.append(put if certain else f"if (!m->has_{name}) goto done; {put}")
        line = self._json(f, f"m->{name}")
        if f.dispatch and self.dispatches:
            line = f"if (!m->has_application) {{ {line} }}"
        self.json.append(line if certain else f"if (m->has_{name}) {{ {line} }}")

    def _json(self, f: PayloadField, value: str) -> str:
        key = _c_str(f.id)
        if f.enum is not None:
            return f"ais_json_code(j, {key}, ais_{f.enum.id}_id({value}), {value});"
        if f.scaled:
            table = f"ais_{self.name}_{f.id}_specials"
            if f.special:
                rows = ", ".join(f"{{{s.raw}, {_c_str(s.id)}}}" for s in f.special)
                self.specials.append(f"static const nmea_ais_special {table}[] = {{{rows}}};")
            real = "true" if f.divisor is not None or isinstance(f.base, float) else "false"
            specials = f"{table}, {len(f.special)}" if f.special else "NULL, 0"
            return (f"ais_json_reading(j, {key}, (int64_t){value}, {float(f.divisor or 1)!r}, {float(f.base or 0)!r}, "
                    f"{real}, {specials});")
        if f.type == "bool":
            return f"ais_json_flag(j, {key}, {value});"
        if f.type == "text":
            return f"ais_json_text(j, {key}, {value});"
        if c_type(f) == BITS:
            return f"ais_json_bits(j, {key}, {value});"
        if c_type(f) == "uint64_t":
            return f"ais_json_uint(j, {key}, (unsigned long long){value});"
        return f"ais_json_int(j, {key}, (long long){value});"

    def _group(self, g: PayloadGroup, following: list) -> None:
        entry = _Record(ais_entry_record(self.name, g), g.items, entry=True)
        self.entries.append(entry)
        key, struct = _c_str(g.id), ais_struct(entry.name)
        self.members += [f"{struct} {g.id}[{g.max}]; /* {g.name} */", f"size_t {g.id}_count;"]
        self.read.append(f"{{ size_t i; if (!ais_entries(r, {g.min}, {g.max}, {g.entry_width}, {after(following)}, {key}, "
                         f"&m->{g.id}_count)) return false; for (i = 0; i < m->{g.id}_count; i++) "
                         f"if (!ais_read_{entry.name}(r, &m->{g.id}[i])) return false; }}")
        self.write.append(f"{{ size_t i; for (i = 0; i < m->{g.id}_count; i++) "
                          f"if (!ais_write_{entry.name}(&m->{g.id}[i], w)) return false; }}")
        self.json.append(f"{{ size_t i; ais_json_key(j, {key}); ais_json_puts(j, \"[\"); "
                         f"for (i = 0; i < m->{g.id}_count; i++) {{ if (i) ais_json_puts(j, \",\"); "
                         f"ais_json_open(j); ais_json_{entry.name}(&m->{g.id}[i], j); ais_json_close(j); }} "
                         f"ais_json_puts(j, \"]\"); }}")

    def _choice(self, c: PayloadChoice, following: list) -> None:
        assert c.selector is not None and c.selector.offset is not None
        by = c.selector
        reads, writes = [], []
        for case in sorted(c.cases, key=lambda case: case.is_default):
            inner = _Record(self.name, [], self.dispatches)
            inner.certain = self.certain
            inner._walk(case.items, following, False)
            self.optional = self.optional or inner.optional
            self.uncertain = self.uncertain or inner.uncertain
            self.members += inner.members
            self.json += inner.json
            self.entries += inner.entries
            self.specials += inner.specials
            reads.append((case, " ".join(inner.read)))
            writes.append((case, " ".join(inner.write)))
        selector = f"m->{member_name(by)}"
        guard = "" if member_name(by) in self.certain else f"m->has_{member_name(by)} && "
        if self.entry or read_before(c, member_name(by), self.certain):  # its selector is read already
            self.read.append(f"{{ uint64_t selector = (uint64_t){selector}; {_if_chain(reads, 'selector', '')} }}")
        else:
            self.read.append(f"if (!ais_peek(r, {by.offset}, {by.bits}, {_c_str(by.id)}, &selector)) "
                             f"return false; {_if_chain(reads, 'selector', '')}")
        self.write.append(f"{{ uint64_t selector = (uint64_t){selector}; {_if_chain(writes, 'selector', guard)} }}")


def _if_chain(cases: list, selector: str, guard: str) -> str:
    """if / else if over the cases (the default case last, as `else`)."""
    out: list[str] = []
    for case, body in cases:
        if case.is_default:
            out.append(f"{{ {body} }}")
            continue
        tests = [f"{selector} == {v}u" for v in case.values]
        if case.range:
            tests.append(f"({selector} >= {case.range[0]}u && {selector} <= {case.range[1]}u)")
        test = tests[0] if len(tests) == 1 and not guard else f"({' || '.join(tests)})"
        out.append(f"if ({guard}{test}) {{ {body} }}")
    return " else ".join(out) if out else ""


def c_layout(code: str, indent: int = 0) -> str:
    """C written on one line laid out a statement a line, blocks indented by four: a `{` and a `;`
    outside parentheses end a line, a `}` stands on its own (`} else` kept together); strings and
    characters are copied as they are."""
    lines: list[str] = []
    line, depth, parens, i = "", indent, 0, 0

    def end(text: str) -> None:
        if text.strip():
            lines.append("    " * depth + text.strip())

    while i < len(code):
        ch = code[i]
        if ch in "\"'":  # a literal, to its closing quote
            close = i + 1
            while code[close] != ch:
                close += 2 if code[close] == "\\" else 1
            line += code[i:close + 1]
            i = close + 1
            continue
        parens += (ch == "(") - (ch == ")")
        if ch == "{":
            end(line + "{")
            line, depth = "", depth + 1
        elif ch == "}":
            end(line)
            depth -= 1
            line = "}"
            rest = code[i + 1:].lstrip()
            if not rest.startswith("else") and not rest.startswith(";"):
                end(line)
                line = ""
        elif ch == ";" and parens == 0:
            end(line + ";")
            line = ""
        else:
            line += ch
        i += 1
    end(line)
    return "\n".join(lines)


def record_code(record: _Record, kind: str, doc: str) -> tuple[str, str]:
    """The struct (for the header) and the functions of a record."""
    struct = ais_struct(record.name)
    members = list(record.members)
    if kind != "entry":
        members.append("nmea_ais_bits trailing; /* bits after the layout, as sent */")
    if kind == "message":
        members.append("uint8_t padding; /* the fill bits' values, as sent */")
        if record.dispatches:
            members += ["bool has_application;", "nmea_ais_application application;"]
    typedef = f"/* {doc} */\n" + "typedef struct {\n    " + "\n    ".join(members) + f"\n}} {struct};\n"
    done = " done:" if record.optional else ""
    reads = " ".join(record.read) + done + (" m->trailing = ais_rest(r);" if kind != "entry" else "")
    writes = " ".join(record.write) + (" done:" if record.uncertain else "") + \
        (" if (!ais_put_bits(w, m->trailing, \"trailing\")) return false;" if kind != "entry" else "")
    json = " ".join(record.json)
    if kind == "message" and record.dispatches:
        json += " if (m->has_application) { ais_json_key(j, \"application\"); ais_json_open(j); " \
                "ais_json_application(&m->application, j); ais_json_close(j); }"
    if kind != "entry":
        json += " ais_json_bits(j, \"trailing\", m->trailing);"
    # The locals the reads use: a field's raw bits (unsigned, signed), a choice's selector.
    declared = [f"{c_type} {name};" for c_type, name in
                (("uint64_t", "raw"), ("int64_t", "signed_raw"), ("uint64_t", "selector")) if f"&{name})" in reads]
    reads = " ".join(declared) + " " + reads
    code = "\n".join([
        *record.specials,
        f"static bool ais_read_{record.name}(nmea_ais_reader *r, {struct} *m)",
        c_layout(f"{{ {reads}{';' if reads.endswith(':') else ''} return true; }}"),
        "",
        f"static bool ais_write_{record.name}(const {struct} *m, nmea_ais_writer *w)",
        c_layout(f"{{ {writes}{';' if writes.endswith(':') else ''} return true; }}"),
        "",
        f"static void ais_json_{record.name}(const {struct} *m, nmea_ais_json_out *j)",
        c_layout(f"{{ {json} }}"), ""])
    return typedef, code


def carries_ais(spec: Spec) -> bool:
    """Whether the C pair holds a sentence that encapsulates AIS (VDM, VDO), and so the AIS pair
    beside it: a `--only` subset without them has none of it."""
    return bool(spec.payloads) and any((s.encapsulates or {}).get("protocol") == "ais" for s in spec.sentences)


def emit(spec: Spec, env: jinja2.Environment) -> dict[str, str]:
    if not carries_ais(spec):
        return {}
    typedefs: list[str] = []
    app_typedefs: list[str] = []
    functions: list[str] = []
    dispatching: list[Payload] = []
    certain: dict[str, set[str]] = {}
    for payload in [*spec.applications, *spec.payloads]:
        kind = "application" if payload.application else "message"
        record = _Record(payload.id, payload.items, bool(payload.applications))
        if record.dispatches:
            dispatching.append(payload)
        certain[payload.id] = record.certain
        for entry in record.entries:
            t, c = record_code(entry, "entry", f"One entry of {entry.name}.")
            (app_typedefs if payload.application else typedefs).append(t)
            functions.append(c)
        title = title_of(payload)
        t, c = record_code(record, kind, title)
        (app_typedefs if payload.application else typedefs).append(t)
        functions.append(c)
    enums = sorted({f.enum.id: f.enum for p in [*spec.payloads, *spec.applications] for f in p.fields if f.enum}.items())
    sources = [p.origin.file for p in [*spec.payloads, *spec.applications]]
    # nmea_ais_fragment_of: each layout of an encapsulation sentence, its fields by their roles.
    encapsulations = [dict(const=layout_const(s, lay), sentence=s.id, struct=s.layout_snake(lay),
                           roles={role: member(f) for role, f in s.encapsulates.items() if role != "protocol"})
                      for s in spec.sentences if (s.encapsulates or {}).get("protocol") == "ais"
                      for lay in s.layouts]
    context = dict(encapsulations=encapsulations, payloads=spec.payloads, applications=spec.applications, typedefs=typedefs,
                   app_typedefs=app_typedefs, functions=functions, enums=[e for _, e in enums],
                   dispatching=dispatching,
                   has=lambda p, name: "" if name in certain[p.id] else f"m->has_{name} && ",
                   runtime_h=(RUNTIME / "c" / "ais.h").read_text(encoding="utf-8"),
                   runtime_c=runtime_source("ais.c"))
    return {
        "c/nmea_ais.h": env.get_template("c/nmea_ais.h.j2").render(
            header=header(spec, "//", ["templates/c/nmea_ais.h.j2", "runtime/c/ais.h", *sources]), **context),
        "c/nmea_ais.c": env.get_template("c/nmea_ais.c.j2").render(
            header=header(spec, "//", ["templates/c/nmea_ais.c.j2", "runtime/c/ais.c", *sources]), **context),
    }
