"""The field-type registry: everything that differs by the type of a field, in one place.

A spec field has one of the types below (spec/schema lists the same names). What a type reads
and accepts is behaviour, written once per runtime (runtime/, generator/reference.py);
what the generator needs to know about a type to name, describe and call that behaviour is here:
how many wire fields it spans, what an error says it takes when that does not depend on the field,
how the docs name it, how a manual writes it, and per language the type that holds its value and
the runtime piece that reads it. Adding a type means a row here and its behaviour in each runtime.
"""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class FieldType:
    name: str
    wire_width: int            # wire fields a value spans (a latitude and its hemisphere: 2)
    expected: str | None       # what a bad_field error says it takes, when the type alone decides
    doc_name: str              # the Type column of the docs
    placeholder: str           # how a manual writes it, when the field gives no format
    c_type: str | None         # the C member's type (None: nothing stored, the layout implies it)
    c_empty: str               # what an empty field leaves in that member, for the member docs
    c_fast: str                # the C fast path's reader, fast_<c_fast>, and writer, fast_put_<c_put>
    c_put: str
    rust_type: str | None      # the Rust member's type inside Option (enums: see rust_type())
    python_type: str | None    # the Python member's type (enums: see python_type())
    python_spec: str           # the Python runtime's FieldSpec class
    memo: bool = False         # values are looked up by text first (see the runtimes' known tables)


TYPES: dict[str, FieldType] = {t.name: t for t in (
    FieldType("integer", 1, None, "integer", "x", "nmea_number", "present false", "integer", "number",
              "Number", "rt.Number", "IntegerField", memo=True),
    FieldType("decimal", 1, None, "decimal", "x.x", "nmea_number", "present false", "decimal", "number",
              "Number", "rt.Number", "DecimalField", memo=True),
    FieldType("hex", 1, "hex number", "hex", "h", "nmea_hex", "present false", "hex", "hex",
              "Hex", "rt.Hex", "HexField", memo=True),
    FieldType("time", 1, "time hhmmss[.s]", "UTC time", "hhmmss.ss", "nmea_time", "present false", "time", "time",
              "Time", "rt.Time", "TimeField", memo=True),
    FieldType("date", 1, "date ddmmyy", "date", "ddmmyy", "nmea_date", "present false", "date", "date",
              "Date", "rt.Date", "DateField", memo=True),
    FieldType("latitude", 2, "latitude ddmm.mmmm", "latitude + N/S", "ddmm.mm", "nmea_coordinate", "present false",
              "latitude", "coordinate", "Coordinate", "rt.Coordinate", "LatitudeField", memo=True),
    FieldType("longitude", 2, "longitude dddmm.mmmm", "longitude + E/W", "dddmm.mm", "nmea_coordinate",
              "present false", "longitude", "coordinate", "Coordinate", "rt.Coordinate", "LongitudeField",
              memo=True),
    FieldType("char", 1, "one character", "character", "a", "char", "0", "char", "char_field",
              "char", "str", "CharField"),
    FieldType("literal", 1, None, "literal", "a", "bool", "false", "literal", "literal",
              "&'a str", "str", "LiteralField"),
    FieldType("keyword", 1, None, "keyword", "a", None, "", "keyword", "keyword",
              None, "str", "KeywordField"),
    FieldType("text", 1, None, "text", "c--c", "nmea_text", "length 0", "text", "text_field",
              "&'a str", "str", "TextField"),
    FieldType("enum", 1, None, "enum", "x", "nmea_enum", "present false", "enum", "enum",
              None, None, "EnumField"),
    FieldType("enum_chars", 1, None, "enum characters", "c--c", "nmea_text", "length 0", "enum_chars", "text_field",
              None, None, "EnumCharsField"),
)}


def field_type(name: str) -> FieldType:
    return TYPES[name]
