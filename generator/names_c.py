"""C identifiers: how the spec's ids become the names of nmea.h (the default prefix `nmea_`;
naming.py renames them for --prefix), and which two things of a spec would share one."""

from __future__ import annotations

from .model import (BitfieldDef, Bits, BitValue, EnumDef, Group, Layout, Origin, Parameter, PayloadChoice, PayloadGroup,
                    Sentence, Spec, TableDef)
from .names import NameClaims

C_KEYWORDS = frozenset("""
auto break case char const continue default do double else enum extern float for goto if inline int
long register restrict return short signed sizeof static struct switch typedef union unsigned void
volatile while bool true false _Bool _Complex _Imaginary
""".split())


def member(name: str) -> str:
    return name + "_" if name in C_KEYWORDS else name


def enum_type(e: EnumDef) -> str:
    return f"nmea_{e.id}"


def enum_def(e: EnumDef) -> str:
    return f"nmea_{e.id}_def"


def enum_const(e: EnumDef, value_id: str) -> str:
    return f"NMEA_{e.id.upper()}_{value_id.upper()}"


def layout_const(sentence: Sentence, layout: Layout) -> str:
    return "NMEA_SENTENCE_" + sentence.layout_snake(layout).upper()


def entry_type(sentence: Sentence, layout: Layout, group: Group) -> str:
    """The struct of one entry of a repeated group: nmea_gsv_satellite for GSV's `satellites`."""
    word = group.id[:-1] if group.id.endswith("s") else group.id + "_entry"
    return f"nmea_{sentence.layout_snake(layout)}_{word}"


def layout_type(sentence: Sentence, layout: Layout) -> str:
    return f"nmea_{sentence.layout_snake(layout)}"


def layout_functions(sentence: Sentence, layout: Layout) -> list[str]:
    snake = sentence.layout_snake(layout)
    return [f"nmea_{verb}_{snake}" for verb in ("parse", "serialize", "build")]


def stores_entries(group: Group) -> bool:
    """Whether a group's entries hold values (a group of keywords only is just counted)."""
    return any(f.field_type.c_type is not None for f in group.fields)


def group_accessor(sentence: Sentence, layout: Layout, group: Group) -> str:
    """The function that reads entry i of a group that stores entries."""
    return f"nmea_{sentence.layout_snake(layout)}_{member(group.id)}_at"


def bits_function(b: BitfieldDef, bits: Bits) -> str:
    return f"nmea_{b.id}_{bits.id}"


def bits_mask(b: BitfieldDef, bits: Bits) -> str:
    return f"NMEA_{b.id.upper()}_{bits.id.upper()}_MASK"


def bits_const(b: BitfieldDef, bits: Bits, value: BitValue) -> str:
    return f"NMEA_{b.id.upper()}_{bits.id.upper()}_{value.id.upper()}"


def table_name(t: TableDef) -> str:
    return f"nmea_{t.id}"


def table_count(t: TableDef) -> str:
    return f"NMEA_{t.id.upper()}_COUNT"


def parameter_macro(t: TableDef, p: Parameter) -> str:
    return f"NMEA_{t.id.upper()}_{p.id.upper()}"


def ais_struct(record: str) -> str:
    """The struct of an AIS message, application or group entry (nmea_ais.h)."""
    return f"nmea_ais_{record}"


def ais_entry_record(record: str, group: PayloadGroup) -> str:
    """The record of one entry of a group: area_notice_sub_area for area_notice's `sub_areas`."""
    return f"{record}_{group.id[:-1] if group.id.endswith('s') else group.id + '_entry'}"


def ais_records(name: str, items: list, origin: Origin) -> list[tuple[str, Origin]]:
    """The records nmea_ais.h declares for a payload's items: its own (`name`) and one per group
    entry."""
    records = [(name, origin)]
    for item in items:
        if isinstance(item, PayloadGroup):
            records += ais_records(ais_entry_record(name, item), item.items, item.origin)
        elif isinstance(item, PayloadChoice):
            for case in item.cases:
                records += ais_records(name, case.items, origin)[1:]
    return records


def clashes(spec: Spec) -> list[tuple[Origin, str]]:
    """The C identifiers built from the spec's ids that two things would share."""
    names = NameClaims("C")
    for e in spec.enums:
        names.claim(enum_type(e), f"enum {e.id}", e.origin)
        for v in e.values:
            names.claim(enum_const(e, v.id), f"enum value {e.id}.{v.id}", v.origin)
    for s in spec.sentences:
        for lay in s.layouts:
            snake = s.layout_snake(lay)
            for name in (layout_type(s, lay), layout_const(s, lay), *layout_functions(s, lay)):
                names.claim(name, f"layout {snake}", lay.origin)
            group = lay.group
            if group is not None and stores_entries(group):
                for name in ([] if group.single else [entry_type(s, lay, group)]) + [group_accessor(s, lay, group)]:
                    names.claim(name, f"group {snake}.{group.id}", group.origin)
    for payload in [*spec.applications, *spec.payloads]:
        if payload.protocol == "ais":
            for record, origin in ais_records(payload.id, payload.items, payload.origin):
                names.claim(ais_struct(record), f"AIS record {record}", origin)
    for b in spec.bitfields:
        for bits in b.bits:
            what = f"bits {b.id}.{bits.id}"
            names.claim(bits_function(b, bits), what, bits.origin)
            names.claim(bits_mask(b, bits), what, bits.origin)
            for value in bits.values:
                names.claim(bits_const(b, bits, value), f"{what} = {value.value}", bits.origin)
    for t in spec.tables:
        names.claim(table_name(t), f"table {t.id}", t.origin)
        names.claim(table_count(t), f"table {t.id}", t.origin)
        for p in t.parameters:
            names.claim(parameter_macro(t, p), f"parameter {t.id}.{p.id}", p.origin)
    return names.clashes
