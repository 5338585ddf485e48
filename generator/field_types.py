"""The field-type registry: everything that differs by the type of a field, in one place.

A spec field has one of the types below (spec/schema lists the same names). What a type reads
and writes is behaviour, written once per runtime (runtime/c, runtime/rust, runtime/python);
everything the generator needs to know about a type to check, describe and call that behaviour is
here, and the model, the checks, the reference decoder and the emitters ask the type, never its
name: how many wire fields it spans, what an error says it takes, how the docs name it and how a
manual writes it, how an example's value is checked and written as JSON, how a reply is paired by
it, and per language the type that holds its value and the runtime pieces that read and write it.

What a reader or writer takes besides the text is said once, in a small vocabulary that each
emitter renders in its language (`args`): "range" (a number's min and max), "word" (the field's
`value`), "hemisphere" (what its hemisphere field takes), "table" (its enum's table), "max_length".

Adding a field type touches: its entry in TYPES below (an instance of the kind it belongs to, or
of a new FieldType subclass when no kind fits); its name in spec/schema/sentence.schema.json and
its row in spec/README.md and runtime/json.md; its reader and writer in each runtime:
runtime/python/runtime.py (reader function and FieldSpec class), runtime/c/runtime.h and
runtime.c (its FIELD_ constant, its case in the layout reader and writer, fast_<c_fast> and
fast_put_<c_put>), runtime/rust/src (the value type in types.rs, the Reader method in frame.rs,
the FastReader method in fast.rs). No other file of generator/ changes.
"""

from __future__ import annotations

import math
import struct
from dataclasses import dataclass
from decimal import Decimal
from types import ModuleType
from typing import TYPE_CHECKING, Any, Callable

from .numbers import fixed_point, fmt_num

if TYPE_CHECKING:
    from .model import EnumDef, Field


@dataclass
class Reading:
    """Where the reference decoder reads a field: what the Python runtime's readers take besides
    the wire texts."""
    rt: ModuleType                       # runtime/python/runtime.py
    address: str
    index: int                           # 1-based wire index of the field
    name: str                            # the field's name in errors (group entries: g[2].f)
    ignore_case: bool                    # text commands: words in any letter case
    member: Callable[[str, str], Any]    # an enum member from its code and value id


@dataclass(frozen=True)
class FieldType:
    """A type whose value is one wire text read as it is (time, date, char): the base of the kinds."""
    name: str
    doc_name: str              # the Type column of the docs
    placeholder: str           # how a manual writes it, when the field gives no format
    c_type: str | None         # the C member's type (None: nothing stored, the layout implies it)
    c_empty: str               # what an empty field leaves in that member, for the member docs
    c_fast: str                # the C fast path's reader, fast_<c_fast>, and writer, fast_put_<c_put>
    c_put: str
    rust_type: str | None      # the Rust member's type inside Option ({enum}: its enum's Rust name)
    python_type: str           # the Python member's type ({enum}: its enum's class)
    python_spec: str           # the Python runtime's FieldSpec class
    reader: str = ""           # the Python runtime's reader, <reader>(text, address, index, name, expected, ...)
    expected_text: str | None = None   # what a bad_field error says it takes, when the type alone decides
    wire_width: int = 1        # wire fields a value spans (a latitude and its hemisphere: 2)
    args: tuple[str, ...] = ()         # what its readers take besides the text (see the module's docstring)
    c_put_args: tuple[str, ...] = ("&value",)   # what the C fast writer takes: "value", "&value" or args
    c_doc: str = ""            # what the C member's docs add ({value}, {enum_type}, {enum_table})
    rust_reader: str = ""      # the Rust Reader's and FastReader's method (default: the type's name)
    rust_expected: bool = False        # the Rust reader takes the expected text (it cannot derive it)
    pairing: str | None = None         # how a reply's `when` compares it: number, code, string, character
    python_pairing: str = "text"       # the kind runtime.holds() compares it as
    memo: bool = False         # values are looked up by text first (see the runtimes' known tables)
    keyword: bool = False      # a fixed word that picks the layout; nothing is stored
    bits: bool = False         # a bitfield may name its bits
    verbatim: bool = False     # the value is the wire text itself (Rust keeps a group of it as received)
    per_char: bool = False     # codes: one one-character code per character
    hemispheres: str = ""      # coordinates: the letters their hemisphere field takes, positive first
    longest: int | None = None  # the longest text its readers take (None: no bound, or see longest_texts)
    c_small: str | None = None  # the C small reader's type, SMALL_<c_small> (runtime/c/small.c; None: it has none)

    @property
    def numeric(self) -> bool:
        """A number with an optional range (min, max)."""
        return "range" in self.args

    @property
    def coded(self) -> bool:
        """Its values are codes of an enum."""
        return "table" in self.args

    @property
    def has_length(self) -> bool:
        return "max_length" in self.args

    @property
    def hemisphere_expected(self) -> str:
        return f"hemisphere {self.hemispheres[0]} or {self.hemispheres[1]}"

    @property
    def rust_method(self) -> str:
        return self.rust_reader or self.name

    def expected(self, f: Field) -> str:
        """What a bad_field error says field `f` should hold (the value part of a coordinate)."""
        assert self.expected_text is not None, self.name
        return self.expected_text

    def read(self, f: Field, texts: list[str], at: Reading) -> Any:
        """The reference decoder's value of `f` from its wire texts."""
        return getattr(at.rt, self.reader)(texts[0], at.address, at.index, at.name, f.expected)

    def expect_json(self, f: Field, value: Any, rt: ModuleType) -> str:
        """An example's expected value (YAML `expect`, not None) as the decoded JSON; TypeError,
        ValueError or KeyError when it cannot be a value of `f`."""
        if not isinstance(value, str):
            raise TypeError(f"{self.name} expects a string")
        return rt.json_str(value)

    def placeholders(self, f: Field) -> list[str]:
        """How the manual writes the field's wire text, one string per wire field."""
        return [f.format or self.placeholder]

    def longest_texts(self, f: Field, max_digits: int) -> list[int | None]:
        """The longest text the runtimes' readers take for field `f`, one per wire field (None: no
        bound); `max_digits` is the contract's most digits of a number."""
        return [self.longest]

    def readings(self, f: Field) -> list[tuple[Any, ...]]:
        """What field `f` takes, one entry per wire field: two fields (of two layouts) with equal
        readings take the same texts as the same values."""
        return [(self.name, f.min, f.max, f.max_length, f.value, f.enum_id)]

    def pairing_problem(self, f: Field, value: Any) -> str | None:
        """Why `value` (expect form) cannot be a value of `f` in a reply's `when` or `outcome`."""
        kinds = ", ".join(t.name for t in TYPES.values() if t.pairing)
        return f"field {f.id} is {self.name}: a reply is paired or judged only by {kinds} fields"


@dataclass(frozen=True)
class CharType(FieldType):
    def pairing_problem(self, f: Field, value: Any) -> str | None:
        if not isinstance(value, str) or len(value) != 1:
            return f"field {f.id} is {self.name}: {value!r} is not one"
        return None


@dataclass(frozen=True)
class NumberType(FieldType):
    """integer, decimal: a fixed-point number, within its range if the field gives one."""
    integer: bool = False

    def expected(self, f: Field) -> str:
        what = "integer" if self.integer else "decimal number"
        if f.min is not None and f.max is not None:
            return f"{what} {fmt_num(f.min)}..{fmt_num(f.max)}"
        if f.min is not None:
            return f"{what} of at least {fmt_num(f.min)}"
        if f.max is not None:
            return f"{what} of at most {fmt_num(f.max)}"
        return what

    def longest_texts(self, f: Field, max_digits: int) -> list[int | None]:
        return [1 + max_digits + (0 if self.integer else 1)]  # a sign, the digits, a point

    def read(self, f: Field, texts: list[str], at: Reading) -> Any:
        low, high = (None if b is None else Decimal(str(b)) for b in (f.min, f.max))
        return at.rt.number_field(texts[0], self.integer, at.address, at.index, at.name, f.expected, low, high)

    def expect_json(self, f: Field, value: Any, rt: ModuleType) -> str:
        return number_json(value, rt)

    def pairing_problem(self, f: Field, value: Any) -> str | None:
        if not self.pairing:
            return super().pairing_problem(f, value)
        if isinstance(value, bool) or not isinstance(value, int):
            return f"field {f.id} is an integer: {value!r} is not one"
        return None


@dataclass(frozen=True)
class HexType(FieldType):
    def expect_json(self, f: Field, value: Any, rt: ModuleType) -> str:
        if not isinstance(value, int):
            raise TypeError(f"{self.name} expects an integer")
        return str(value)


@dataclass(frozen=True)
class CoordinateType(FieldType):
    """latitude, longitude: degrees and minutes, then a hemisphere field."""
    degree_digits: int = 2

    def longest_texts(self, f: Field, max_digits: int) -> list[int | None]:
        return [self.degree_digits + max_digits + 1, 1]  # degrees, minutes of at most max_digits digits and a point

    def read(self, f: Field, texts: list[str], at: Reading) -> Any:
        return at.rt.coordinate_field(texts[0], texts[1], at.address, at.index, at.name, f.expected,
                                      self.hemisphere_expected, self.hemispheres)

    def expect_json(self, f: Field, value: Any, rt: ModuleType) -> str:
        if set(value) != {"deg", "min", "hemi"}:
            raise KeyError("expects {deg, min, hemi}")
        return (f'{{"deg":{int(value["deg"])},"min":{number_json(value["min"], rt)},'
                f'"hemi":{rt.json_str(str(value["hemi"]))}}}')

    def placeholders(self, f: Field) -> list[str]:
        parts = (f.format or self.placeholder).split(",")
        return parts if len(parts) == 2 else [parts[0], "a"]

    def readings(self, f: Field) -> list[tuple[Any, ...]]:
        return [(self.name,), ("codes", tuple(self.hemispheres))]  # the hemisphere: a closed set


@dataclass(frozen=True)
class WordType(FieldType):
    """literal, keyword: the field's one word (`value`), or (a literal) nothing."""

    def expected(self, f: Field) -> str:
        return f.value or "" if self.keyword else f"{f.value} or nothing"

    def read(self, f: Field, texts: list[str], at: Reading) -> Any:
        if self.keyword:
            return at.rt.keyword_field(texts[0], at.address, at.index, at.name, f.expected, f.value, at.ignore_case)
        return at.rt.literal_field(texts[0], at.address, at.index, at.name, f.expected, f.value)

    def placeholders(self, f: Field) -> list[str]:
        return [f.format or f.value or "a"]

    def longest_texts(self, f: Field, max_digits: int) -> list[int | None]:
        return [len(f.value or "")]


@dataclass(frozen=True)
class TextType(FieldType):
    def expected(self, f: Field) -> str:
        return f"text of at most {f.max_length} characters" if f.max_length else "text"

    def longest_texts(self, f: Field, max_digits: int) -> list[int | None]:
        return [f.max_length]

    def read(self, f: Field, texts: list[str], at: Reading) -> Any:
        return at.rt.text_field(texts[0], at.address, at.index, at.name, f.expected, f.max_length)

    def pairing_problem(self, f: Field, value: Any) -> str | None:
        if not isinstance(value, str) or not value:
            return f"field {f.id} is {self.name}: {value!r} is not one"
        return None


@dataclass(frozen=True)
class CodeType(FieldType):
    """enum (one code), enum_chars (one one-character code per character)."""

    def expected(self, f: Field) -> str:
        assert f.enum is not None
        return codes_expected(f.enum, self.per_char)

    def read(self, f: Field, texts: list[str], at: Reading) -> Any:
        e = f.enum
        assert e is not None
        by_code = {v.code: at.member(v.code, v.id) for v in e.values}
        if self.per_char:
            return at.rt.enum_chars_field(texts[0], at.address, at.index, at.name, f.expected, by_code,
                                          e.code_class, f.max_length)
        return at.rt.enum_field(texts[0], at.address, at.index, at.name, f.expected, by_code, e.code_class,
                                e.min_len, e.max_len, at.ignore_case)

    def longest_texts(self, f: Field, max_digits: int) -> list[int | None]:
        assert f.enum is not None
        return [f.max_length if self.per_char else f.enum.max_len]

    def expect_json(self, f: Field, value: Any, rt: ModuleType) -> str:
        assert f.enum is not None
        if self.per_char and not isinstance(value, list):
            raise TypeError(f"{self.name} expects a list of value ids")
        for v in value if self.per_char else [value]:
            if f.enum.by_id(str(v)) is None:
                raise ValueError(f"{v!r} is not a value id of enum {f.enum.id}")
        if self.per_char:
            return "[" + ",".join(rt.json_str(str(v)) for v in value) + "]"
        return rt.json_str(str(value))

    def placeholders(self, f: Field) -> list[str]:
        if f.format or self.per_char:
            return super().placeholders(f)
        assert f.enum is not None
        return [("a" if f.enum.letters else "x") * f.enum.max_len]

    def readings(self, f: Field) -> list[tuple[Any, ...]]:
        assert f.enum is not None
        if f.enum.closed and not self.per_char:  # as a coordinate's hemisphere reads N or S
            return [("codes", tuple(sorted(v.code for v in f.enum.values)))]
        return super().readings(f)

    def pairing_problem(self, f: Field, value: Any) -> str | None:
        if not self.pairing:
            return super().pairing_problem(f, value)
        if f.enum is None or f.enum.by_id(str(value)) is None:
            return f"{value!r} is not a value id of enum {f.enum.id if f.enum else '?'}"
        return None


def codes_expected(enum: EnumDef, per_char: bool) -> str:
    """What an enum field (`per_char`: an enum_chars field) of `enum` takes, in a bad_field error."""
    return f"{enum.id} code{'s' if per_char else ''} ({' '.join(v.code for v in enum.values)})"


def number_json(value: Any, rt: ModuleType) -> str:
    """A spec number as the decoded JSON writes it."""
    if isinstance(value, bool):
        raise TypeError("a number, not a boolean")
    digits, scale = fixed_point(str(value))
    return rt.decimal_json(abs(digits), scale, digits < 0)


TYPES: dict[str, FieldType] = {t.name: t for t in (
    NumberType("integer", "integer", "x", "nmea_number", "present false", "integer", "number", "Number",
               "rt.Number", "IntegerField", args=("range",), rust_expected=True, pairing="number",
               python_pairing="integer", memo=True, bits=True, integer=True, c_small="INTEGER"),
    NumberType("decimal", "decimal", "x.x", "nmea_number", "present false", "decimal", "number", "Number",
               "rt.Number", "DecimalField", args=("range",), rust_expected=True, memo=True, c_small="DECIMAL"),
    HexType("hex", "hex", "h", "nmea_hex", "present false", "hex", "hex", "Hex", "rt.Hex", "HexField",
            reader="hex_field", expected_text="hex number", memo=True, bits=True, longest=16, c_small="HEX"),
    FieldType("time", "UTC time", "hhmmss.ss", "nmea_time", "present false", "time", "time", "Time", "rt.Time",
              "TimeField", reader="time_field", expected_text="time hhmmss[.s]", memo=True, longest=16,
              c_small="TIME"),
    FieldType("date", "date", "ddmmyy", "nmea_date", "present false", "date", "date", "Date", "rt.Date",
              "DateField", reader="date_field", expected_text="date ddmmyy", memo=True, longest=6, c_small="DATE"),
    CoordinateType("latitude", "latitude + N/S", "ddmm.mm", "nmea_coordinate", "present false", "latitude",
                   "coordinate", "Coordinate", "rt.Coordinate", "LatitudeField", wire_width=2,
                   expected_text="latitude ddmm.mmmm", args=("hemisphere",), memo=True, hemispheres="NS",
                   c_small="LATITUDE"),
    CoordinateType("longitude", "longitude + E/W", "dddmm.mm", "nmea_coordinate", "present false", "longitude",
                   "coordinate", "Coordinate", "rt.Coordinate", "LongitudeField", wire_width=2,
                   expected_text="longitude dddmm.mmmm", args=("hemisphere",), memo=True, hemispheres="EW",
                   degree_digits=3, c_small="LONGITUDE"),
    CharType("char", "character", "a", "char", "0", "char", "char_field", "char", "str", "CharField",
             reader="char_field", expected_text="one character", c_put_args=("value",), pairing="character",
             longest=1, c_small="CHAR"),
    WordType("literal", "literal", "a", "bool", "false", "literal", "literal", "&'a str", "str", "LiteralField",
             args=("word",), c_put_args=("value", "word"), c_doc=' True when the field holds "{value}".',
             rust_expected=True, c_small="LITERAL"),
    WordType("keyword", "keyword", "a", None, "", "keyword", "keyword", None, "str", "KeywordField",
             args=("word",), c_put_args=("word",), keyword=True, c_small="KEYWORD"),
    TextType("text", "text", "c--c", "nmea_text", "length 0", "text", "text_field", "&'a str", "str", "TextField",
             args=("max_length",), c_put_args=("value",), rust_expected=True, pairing="string", verbatim=True,
             c_small="TEXT"),
    CodeType("enum", "enum", "x", "nmea_enum", "present false", "enum", "enum", "Code<'a, {enum}>", "{enum} | str",
             "EnumField", args=("table",), c_put_args=("&value", "table"), rust_reader="code", pairing="code",
             python_pairing="enum", c_doc=" Values: {enum_type} (table {enum_table}).", c_small="ENUM"),
    CodeType("enum_chars", "enum characters", "c--c", "nmea_text", "length 0", "enum_chars", "text_field",
             "CodeChars<'a, {enum}>", "list[{enum} | str]", "EnumCharsField", args=("table", "max_length"),
             c_put_args=("value",), rust_reader="code_chars", per_char=True,
             c_doc=" One code of {enum_type} per character (table {enum_table})."),
)}


# Six-bit text: each character's six bits are its index here (ITU-R M.1371-5, table 47; `@` pads).
SIXBIT_CHARS = "@ABCDEFGHIJKLMNOPQRSTUVWXYZ[\\]^_ !\"#$%&'()*+,-./0123456789:;<=>?"


@dataclass(frozen=True)
class BitType:
    """A type of the fields of bit-packed payloads (spec/ais/messages): what the checks, the
    reference decoder, the docs and the emitters need to know of it. Its reader and writer are the
    runtime's field class `python_spec` (runtime/python/ais.py). Adding one: an entry in BIT_TYPES,
    its name in spec/schema/payload.schema.json and its class in runtime/python/ais.py."""
    name: str
    doc_name: str              # the Type column of the docs
    python_spec: str           # the Python runtime's field class (ais.<python_spec>)
    python_type: str           # the Python member's type ({enum}: its enum's class)
    min_bits: int = 1
    max_bits: int | None = 64  # None: any width (data)
    char_bits: int = 1         # the width is a whole number of these (text: six-bit characters)
    variable: bool = False     # may take the bits left (no `bits`)
    numeric: bool = False      # takes a divisor, a unit and special values
    signed: bool = False
    coded: bool = False        # its raw values are codes of an enum
    enums: bool = False        # may name an enum whose codes its raw values are (enum; u1..u8)
    selects: bool = False      # its raw value, read unsigned, may pick the case of a choice
    dispatches: bool = False   # its bits may be an application's, picked by other fields (`dispatch`)
    size: int | None = None    # a byte type (binary frames): its bytes, when the type fixes them
    order: str = "msb"         # "msb": bits, most significant first (AIS); "le": whole bytes, little endian
    module: str = "ais"        # the Python runtime module of its field class
    has_parts: bool = False    # a bitfield word whose bit ranges are named (`parts`)

    @property
    def in_bytes(self) -> bool:
        """A type of byte-oriented frames (spec/binary), little endian."""
        return self.order == "le"

    def raw(self, bits: str) -> Any:
        """The reference decoder's raw value of a field from its bits ('0'/'1' text; a byte
        type's: its little-endian integer's bits)."""
        return int(bits, 2) if bits else 0

    def json(self, f: Any, raw: Any) -> dict[str, Any]:
        """The decoded JSON members of field `f` (a PayloadField) with raw value `raw`."""
        return {f.id: raw}

    def raw_range(self, width: int) -> tuple[int, int]:
        """The raw values `width` bits hold."""
        return (-(1 << (width - 1)), (1 << (width - 1)) - 1) if self.signed else (0, (1 << width) - 1)


@dataclass(frozen=True)
class BitNumber(BitType):
    """uint, int: an integer, in a unit once divided by the field's divisor; a special value is
    named, never a number."""

    def raw(self, bits: str) -> Any:
        value = int(bits, 2)
        return value - (1 << len(bits)) if self.signed and bits[0] == "1" else value

    def json(self, f: Any, raw: Any) -> dict[str, Any]:
        if f.enum:   # a byte type's codes (u1 with an enum), as an enum field's
            return BIT_TYPES["enum"].json(f, raw)
        if not f.scaled:
            return {f.id: raw}
        special = next((s.id for s in f.special if s.raw == raw), None)
        if f.divisor and f.base:  # the base moved into the raw scale: (819 - 600) / 10 is 21.9, 819 / 10 - 60 is not
            value = (raw + f.base * f.divisor) / f.divisor
        else:
            value = raw / f.divisor if f.divisor else raw
            value = value + f.base if f.base is not None else value
        return {f.id: special if special is not None else value, f"{f.id}_raw": raw}


@dataclass(frozen=True)
class BitFlag(BitType):
    def raw(self, bits: str) -> Any:
        return bits == "1"


@dataclass(frozen=True)
class BitCode(BitType):
    """enum: an unsigned code of the field's enum (its code is the decimal number); an unknown
    code is kept as its number."""

    def json(self, f: Any, raw: Any) -> dict[str, Any]:
        value = f.enum.by_code(str(raw)) if f.enum else None
        return {f.id: value.id if value else raw}


@dataclass(frozen=True)
class BitText(BitType):
    """Six-bit text, as sent: `@` padding and trailing spaces kept."""

    def raw(self, bits: str) -> Any:
        return "".join(SIXBIT_CHARS[int(bits[i:i + 6], 2)] for i in range(0, len(bits) - len(bits) % 6, 6))


@dataclass(frozen=True)
class BitData(BitType):
    """Binary data, kept as the text of its bits ('0'/'1')."""

    def raw(self, bits: str) -> Any:
        return bits


@dataclass(frozen=True)
class BitSignMagnitude(BitNumber):
    """smag: a sign bit (1: negative), then the magnitude (RTCM 3's GLONASS terms). A negative
    zero is no number: the special value negative_zero, its raw integer the bits (sign set)."""

    def raw(self, bits: str) -> Any:
        value = int(bits[1:], 2) if len(bits) > 1 else 0
        return "negative_zero" if bits[0] == "1" and not value else -value if bits[0] == "1" else value

    def json(self, f: Any, raw: Any) -> dict[str, Any]:
        if raw == "negative_zero":
            return {f.id: raw, f"{f.id}_raw": 1 << (f.bits - 1)}
        return super().json(f, raw)

    def raw_range(self, width: int) -> tuple[int, int]:
        return -((1 << (width - 1)) - 1), (1 << (width - 1)) - 1


@dataclass(frozen=True)
class BitChars(BitType):
    """latin1, utf8: characters of eight bits each, as sent (utf8: its code units decoded, bytes
    that are no UTF-8 kept as surrogate escapes)."""

    def raw(self, bits: str) -> Any:
        data = int(bits, 2).to_bytes(len(bits) // 8, "big") if bits else b""
        return data.decode("latin-1") if self.name == "latin1" else data.decode("utf-8", "surrogateescape")


def float_bits(value: float, bits: int) -> int | None:
    """The bit pattern (unsigned) of the float of `bits` bits (32, 64) nearest to `value`; None
    when that width has no finite float for it (a NaN, an infinity, beyond the largest single)."""
    try:
        packed = struct.pack("<f" if bits == 32 else "<d", value)
    except OverflowError:
        return None
    raw = int.from_bytes(packed, "little")
    unpacked = struct.unpack("<f" if bits == 32 else "<d", packed)[0]
    return raw if math.isfinite(unpacked) else None


@dataclass(frozen=True)
class ByteFloat(BitType):
    """r4, r8: an IEEE 754 float, little endian; a special value (its bit pattern in the field's
    width) is named, never a number."""

    def raw(self, bits: str) -> Any:
        value = struct.unpack("<f" if len(bits) == 32 else "<d", int(bits, 2).to_bytes(len(bits) // 8, "little"))[0]
        return value if math.isfinite(value) else str(value)   # JSON has no NaN or infinity

    def json(self, f: Any, raw: Any) -> dict[str, Any]:
        if f.special and isinstance(raw, float):
            bits = float_bits(raw, f.bits)
            return {f.id: next((s.id for s in f.special if s.raw == bits), raw)}
        return {f.id: raw}


@dataclass(frozen=True)
class ByteWord(BitType):
    """x1..x4: a bitfield word; its raw integer, and each named part (`parts`) by its id."""

    def json(self, f: Any, raw: Any) -> dict[str, Any]:
        out = {f.id: raw}
        for part in f.parts:
            out.update(part.bit_type.json(part, part.bit_type.raw(format(raw >> part.low & (1 << part.bits) - 1,
                                                                         f"0{part.bits}b"))))
        return out


@dataclass(frozen=True)
class ByteChars(BitType):
    """ch: characters as sent (ISO 8859-1, NUL padding kept)."""

    def raw(self, bits: str) -> Any:
        return int(bits, 2).to_bytes(len(bits) // 8, "little").decode("latin-1") if bits else ""


@dataclass(frozen=True)
class ByteData(BitType):
    """bytes: binary data, kept as sent (JSON: lower-case hex)."""

    def raw(self, bits: str) -> Any:
        return int(bits, 2).to_bytes(len(bits) // 8, "little").hex() if bits else ""


def _byte_types() -> list[BitType]:
    """The integers of binary frames (u-blox's notation): U1..U8 unsigned, I1..I8 two's complement,
    X1..X4 bitfields, each of 1, 2, 4 or 8 bytes, little endian."""
    out: list[BitType] = []
    for size in (1, 2, 4, 8):
        bits = 8 * size
        out += [BitNumber(f"u{size}", f"U{size} unsigned", "Unsigned", "int", min_bits=bits, max_bits=bits,
                          numeric=True, enums=True, selects=True, size=size, order="le"),
                BitNumber(f"i{size}", f"I{size} signed", "Signed", "int", min_bits=bits, max_bits=bits, numeric=True,
                          signed=True, size=size, order="le")]
        if size < 8:
            out.append(ByteWord(f"x{size}", f"X{size} bitfield", "Bitfield", "int", min_bits=bits, max_bits=bits,
                                selects=True, size=size, order="le", has_parts=True))
    return out


BIT_TYPES: dict[str, BitType] = {t.name: t for t in (
    BitNumber("uint", "unsigned", "Unsigned", "int", numeric=True, selects=True),
    BitNumber("int", "signed (two's complement)", "Signed", "int", min_bits=2, numeric=True, signed=True),
    BitFlag("bool", "flag", "Flag", "bool", max_bits=1, selects=True),
    BitCode("enum", "enum", "Code", "{enum} | int", coded=True, enums=True, selects=True),
    BitText("text", "six-bit text", "Text", "str", min_bits=6, max_bits=None, char_bits=6, variable=True),
    BitData("data", "binary data", "Data", "str", max_bits=None, variable=True, dispatches=True),
    BitType("spare", "spare (kept as sent)", "Spare", "int"),
    BitSignMagnitude("smag", "signed (sign and magnitude)", "SignMagnitude", "int", min_bits=2, numeric=True,
                     signed=True, module="rtcm3"),
    BitChars("latin1", "characters (ISO 8859-1, kept as sent)", "Latin1", "str", min_bits=8, max_bits=None,
             char_bits=8, variable=True, module="rtcm3"),
    BitChars("utf8", "UTF-8 text (its code units)", "Utf8", "str", min_bits=8, max_bits=None, char_bits=8,
             variable=True, module="rtcm3"),
    *_byte_types(),
    ByteFloat("r4", "R4 float (IEEE 754 single)", "Float", "float | ais.Special", min_bits=32, max_bits=32, numeric=True, size=4,
              order="le", module="ubx"),
    ByteFloat("r8", "R8 float (IEEE 754 double)", "Float", "float | ais.Special", min_bits=64, max_bits=64, numeric=True, size=8,
              order="le", module="ubx"),
    ByteChars("ch", "characters (kept as sent)", "Chars", "str", min_bits=8, max_bits=None, char_bits=8,
              variable=True, order="le", module="ubx"),
    ByteData("bytes", "bytes (kept as sent)", "Bytes", "bytes", min_bits=8, max_bits=None, char_bits=8,
             variable=True, order="le", module="ubx"),
    BitType("reserved", "reserved (kept as sent)", "Spare", "int", min_bits=8, max_bits=None, char_bits=8,
            order="le"),
)}
