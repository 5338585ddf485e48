"""AIS payloads: the six-bit armoring of `!AIVDM`/`!AIVDO`, and one reader and one writer of the
bit layouts the generated message classes describe (`LAYOUT`, a tuple of the field classes below).

A payload decodes to its message and encodes back to the same characters and fill bits: spare
bits, text after its `@` padding, the values of the fill bits and bits beyond the layout (kept in
`trailing`) are all kept as sent. The same reader and writer walk the payloads of binary frames
(ubx.py: little-endian bytes, bitfields, counted groups). Facts from ITU-R M.1371-5 (armoring:
table 47 of annex 8; the layouts: annex 8) and gpsd's "AIVDM/AIVDO protocol decoding".
"""

from __future__ import annotations

import binascii
import dataclasses
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, ClassVar, NamedTuple

from .runtime import NmeaError, Number

if TYPE_CHECKING:  # binary frames read and write their payloads with the same item walkers
    from .ubx import ByteReader, ByteWriter

SIXBIT_TEXT = "@ABCDEFGHIJKLMNOPQRSTUVWXYZ[\\]^_ !\"#$%&'()*+,-./0123456789:;<=>?"
"""The characters of six-bit text, by their value (`@`, value 0, pads a text to its width)."""

_TEXT_CHARS = frozenset(SIXBIT_TEXT)


def armor_value(ch: str) -> int | None:
    """The six bits an armored payload character carries ('0'-'W' are 0-39, '`'-'w' 40-63)."""
    code = ord(ch)
    if 48 <= code <= 87:
        return code - 48
    if 96 <= code <= 119:
        return code - 56
    return None


def armor_char(value: int) -> str:
    return chr(value + 48 if value < 40 else value + 56)


# Base64 (RFC 4648) also packs six bits a character, most significant first: armoring is base64
# with another alphabet, so a payload becomes its bits, and bits their armor, at C speed.
_BASE64 = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/"
_BASE64_TO_ARMOR = bytes.maketrans(_BASE64, bytes(ord(armor_char(v)) for v in range(64)))
_BASE64_TO_TEXT = bytes.maketrans(_BASE64, SIXBIT_TEXT.encode("ascii"))
_TEXT_TO_BASE64 = bytes.maketrans(SIXBIT_TEXT.encode("ascii"), _BASE64)
"""Each six-bit text character to its base64 one (to_raw has checked the text)."""
_ARMOR_TO_BASE64 = bytes(_BASE64[v] if (v := armor_value(chr(code))) is not None else ord("!") for code in range(256))
"""Each armor character to its base64 one, any other byte to '!', which base64 has not."""


def armor(value: int, length: int) -> str:
    """The armored characters of `length` bits (a multiple of six) holding `value`."""
    pad = -length % 24  # base64 takes whole bytes, three for four characters
    data = (value << pad).to_bytes((length + pad) // 8, "big")
    return binascii.b2a_base64(data, newline=False)[:length // 6].translate(_BASE64_TO_ARMOR).decode("ascii")


class Special(NamedTuple):
    """A raw value that is no number (`not_available`, `manual_input`, ...): what a field holds
    instead of a value in its unit."""

    id: str
    raw: int

    def __str__(self) -> str:
        return self.id


class BitReader:
    """The bits of a payload, read most significant first."""

    __slots__ = ("value", "length", "pos", "where")

    def __init__(self, value: int, length: int, where: str) -> None:
        self.value = value
        self.length = length
        self.pos = 0
        self.where = where  # errors' address: "AIS type 5"

    @property
    def remaining(self) -> int:
        return self.length - self.pos

    def peek(self, offset: int, width: int, name: str) -> int:
        """The `width` bits at `offset` as an unsigned integer."""
        if offset + width > self.length:
            raise NmeaError("short_payload", f"{name} needs bits {offset}-{offset + width - 1}, the payload has "
                            f"{self.length}", self.where, name=name)
        return (self.value >> (self.length - offset - width)) & ((1 << width) - 1)

    def take(self, width: int, name: str) -> int:
        raw = self.peek(self.pos, width, name)
        self.pos += width
        return raw


class BitWriter:
    __slots__ = ("value", "length")

    def __init__(self) -> None:
        self.value = 0
        self.length = 0

    def put(self, raw: int, width: int) -> None:
        self.value = (self.value << width) | (raw & ((1 << width) - 1))
        self.length += width

    def put_bits(self, bits: str) -> None:
        if bits:
            self.put(int(bits, 2), len(bits))


class Fragment(NamedTuple):
    """What an encapsulation sentence (`!AIVDM`) says of the message it carries all or part of:
    the fields the spec's `encapsulates` names (nmeaspec.assembly joins fragments)."""

    total: int
    number: int
    sequence: int | None
    channel: str | None
    payload: str
    fill_bits: int

    @classmethod
    def of(cls, total: Any, number: Any, sequence: Any, channel: Any, payload: str | None,
           fill_bits: Any) -> Fragment | None:
        """From a sentence's fields (Numbers, an enum member or its text); None when the count
        is not 1-9 or the number is empty. A number counts when it is a whole 0-255 written
        without a minus (what the C and Rust fragments hold): the sequential id is None
        otherwise, the fill bits 0."""
        count, number = _small(total), _small(number)
        if count is None or not 1 <= count <= 9 or number is None:
            return None
        return cls(count, number, _small(sequence),
                   None if channel is None else str(getattr(channel, "value", channel)), payload or "",
                   _small(fill_bits) or 0)


_DIGITS = {str(digit): digit for digit in range(10)}


def whole(number: Any) -> int:
    """int(number) of a sentence's integer field, by one lookup for a Number of one digit as
    received (an AIS sentence's fragment count and fill bits: its message's hot path)."""
    if number.__class__ is Number:
        try:
            return _DIGITS[number._text]  # its text as received (number.text() without its call)
        except (AttributeError, KeyError):
            pass
    return int(number)


def _small(number: Any) -> int | None:
    """A fragment field's number (a Number) when it is a whole 0-255 written without a minus,
    None for another or none."""
    if number is None or number.scale or number.sign == "-" or number.digits > 255:
        return None
    return int(number.digits)


def bits_text(value: int, width: int) -> str:
    return format(value, f"0{width}b") if width else ""


@dataclass(frozen=True, slots=True)
class Field:
    """One field of a layout: its member, its width (None: the bits left before the `after`
    bits of the fields that follow), and whether it may be missing at the payload's end."""

    id: str
    width: int | None
    optional: bool = False
    after: int = 0
    count: str | tuple[str, ...] | None = None
    """A counted width (RTCM 3): as many characters (bits for data) as the member `count` says, or
    (a tuple) as the bits set in those mask members, multiplied."""

    def size(self, reader: BitReader | ByteReader) -> int:
        return self.width if self.width is not None else max(reader.remaining - self.after, 0)

    def counted(self, number: int) -> int:
        """The bits of `number` units of a counted field (data: bits; characters: their bytes')."""
        return number

    def from_raw(self, raw: int, width: int) -> Any:
        return raw

    def to_raw(self, value: Any, where: str) -> tuple[int, int]:
        """The raw bits of `value` and their width."""
        assert self.width is not None
        if not isinstance(value, int) or not 0 <= value < 1 << self.width:
            raise _bad_value(where, self.id, value, f"an integer of {self.width} bits")
        return value, self.width

    def put_json(self, out: dict[str, Any], value: Any) -> None:
        """Puts the field's decoded JSON members into `out`."""
        out[self.id] = value


def _bad_value(where: str, name: str, value: Any, wanted: str) -> NmeaError:
    return NmeaError("bad_value", f"{name} takes {wanted}, not {value!r}", where, name=name)


@dataclass(frozen=True, slots=True)
class Unsigned(Field):
    """An unsigned integer; its value in a unit is the raw integer divided by `divisor`, plus
    `base` (the value of raw 0); special raw values are Special, never a number."""

    divisor: int = 1
    base: int | float = 0
    special: tuple[Special, ...] = ()

    def signed(self, raw: int, width: int) -> int:
        return raw

    def bounds(self, width: int) -> tuple[int, int]:
        return 0, (1 << width) - 1

    def from_raw(self, raw: int, width: int) -> Any:
        number = self.signed(raw, width)
        if self.special:
            for s in self.special:
                if s.raw == number:
                    return s
        if self.divisor == 1:
            return number + self.base
        # the base moved into the raw scale first: (819 - 600) / 10 is 21.9, 819 / 10 - 60 is not
        return (number + self.base * self.divisor) / self.divisor

    def raw_number(self, value: Any, where: str) -> int:
        """The raw integer of a value (a Special, or a number in the field's unit)."""
        if isinstance(value, Special):
            return value.raw
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            raise _bad_value(where, self.id, value, "a number")
        if self.divisor == 1 and isinstance(self.base, int):
            if isinstance(value, float) and not value.is_integer():  # never rounded in silence
                raise _bad_value(where, self.id, value, "a whole number")
            return int(value) - self.base
        return round((value - self.base) * self.divisor)

    def to_raw(self, value: Any, where: str) -> tuple[int, int]:
        assert self.width is not None
        raw = self.raw_number(value, where)
        low, high = self.bounds(self.width)
        if not low <= raw <= high:
            raise _bad_value(where, self.id, value, f"a raw value {low}..{high}")
        return raw & ((1 << self.width) - 1), self.width

    def put_json(self, out: dict[str, Any], value: Any) -> None:
        if self.divisor == 1 and not self.base and not self.special:
            out[self.id] = value
        elif isinstance(value, Special):
            out[self.id] = str(value)
            out[f"{self.id}_raw"] = value.raw
        else:
            out[self.id] = value
            out[f"{self.id}_raw"] = self.raw_number(value, "")


@dataclass(frozen=True, slots=True)
class Signed(Unsigned):
    """A two's-complement integer."""

    def signed(self, raw: int, width: int) -> int:
        return raw - (1 << width) if raw >> (width - 1) else raw

    def bounds(self, width: int) -> tuple[int, int]:
        return -(1 << (width - 1)), (1 << (width - 1)) - 1


@dataclass(frozen=True, slots=True)
class Flag(Field):
    def from_raw(self, raw: int, width: int) -> Any:
        return bool(raw)

    def to_raw(self, value: Any, where: str) -> tuple[int, int]:
        if not isinstance(value, bool):
            raise _bad_value(where, self.id, value, "True or False")
        return int(value), 1


_MEMBERS: dict[Any, dict[str, Any]] = {}
"""The members of each enum by code (an enum call is slow)."""


@dataclass(frozen=True, slots=True)
class Code(Field):
    """A code of an enum whose codes are decimal numbers; an unknown code stays its number."""

    enum: Any = None

    def from_raw(self, raw: int, width: int) -> Any:
        members = _MEMBERS.get(self.enum)
        if members is None:
            members = _MEMBERS[self.enum] = {m.value: m for m in self.enum}
        return members.get(str(raw), raw)

    def to_raw(self, value: Any, where: str) -> tuple[int, int]:
        return Field.to_raw(self, int(value.value) if isinstance(value, self.enum) else value, where)

    def put_json(self, out: dict[str, Any], value: Any) -> None:
        out[self.id] = value.name.lower() if isinstance(value, self.enum) else value


@dataclass(frozen=True, slots=True)
class Text(Field):
    """Six-bit text as sent, `@` padding and trailing spaces included; of the bits left (a
    variable text), the whole characters."""

    def size(self, reader: BitReader | ByteReader) -> int:
        return self.width if self.width is not None else max(reader.remaining - self.after, 0) // 6 * 6

    def from_raw(self, raw: int, width: int) -> Any:
        # the characters of the whole six-bit groups from the top, by base64 at C speed
        count = width // 6
        if not count:
            return ""
        bits = count * 6
        pad = -bits % 24
        data = ((raw >> (width - bits) & ((1 << bits) - 1)) << pad).to_bytes((bits + pad) // 8, "big")
        return binascii.b2a_base64(data, newline=False)[:count].translate(_BASE64_TO_TEXT).decode("ascii")

    def to_raw(self, value: Any, where: str) -> tuple[int, int]:
        if not isinstance(value, str) or not _TEXT_CHARS.issuperset(value) \
                or self.width is not None and len(value) * 6 != self.width:
            length = f"{self.width // 6} " if self.width is not None else ""
            raise _bad_value(where, self.id, value, f"{length}six-bit text characters")
        pad = -len(value) % 4  # base64 takes four characters at a time
        data = binascii.a2b_base64(value.encode("ascii").translate(_TEXT_TO_BASE64) + b"A" * pad, strict_mode=True)
        return int.from_bytes(data, "big") >> 6 * pad, len(value) * 6


@dataclass(frozen=True, slots=True)
class Data(Field):
    """Binary data, as the text of its bits ('0' and '1'). `dispatch` names the fields whose
    values will choose an application layout for them (none is described yet)."""

    dispatch: tuple[str, ...] = ()

    def from_raw(self, raw: int, width: int) -> Any:
        return bits_text(raw, width)

    def to_raw(self, value: Any, where: str) -> tuple[int, int]:
        if not isinstance(value, str) or value.strip("01") or self.width is not None and len(value) != self.width:
            raise _bad_value(where, self.id, value, "a text of bits")
        return (int(value, 2) if value else 0), len(value)


@dataclass(frozen=True, slots=True)
class Spare(Field):
    """Spare or reserved bits, kept as sent (some stations send them non-zero)."""


@dataclass(frozen=True, slots=True)
class Bitfield(Field):
    """A word of flags and small numbers: its raw integer is the member `id`, each named part
    (`parts`: its lowest bit and its field) a member of its own. Written back, the parts' values
    replace their bits of the word; the bits no part names stay as sent."""

    parts: tuple[tuple[int, Field], ...] = ()

    def read_parts(self, raw: int, values: dict[str, Any]) -> None:
        for low, part in self.parts:
            width = part.width or 1
            values[part.id] = part.from_raw(raw >> low & ((1 << width) - 1), width)

    def word(self, record: Any, where: str) -> int:
        """The word of `record`'s members: its raw word (0 when None) with the parts set."""
        raw = getattr(record, self.id) or 0
        for low, part in self.parts:
            value = getattr(record, part.id)
            if value is not None:
                bits, width = part.to_raw(value, where)
                raw = raw & ~(((1 << width) - 1) << low) | bits << low
        return raw

    def to_raw(self, value: Any, where: str) -> tuple[int, int]:
        raise AssertionError("a bitfield is written from its record (word)")


@dataclass(frozen=True, slots=True)
class Group:
    """Entries of `fields` (the class `entry`) repeated as many times as the member `count` says
    (`count` a number: that many times) or, without one, while the bits left before the `after`
    bits hold one, at most `max` times."""

    id: str
    entry: type
    fields: tuple[Field | Choice | Group, ...]
    """An entry's fields, and choices by a field of the entry before them (every case as wide), and
    last, maybe, a group of the entry's own."""
    min: int
    max: int
    after: int = 0
    count: str | int | tuple[str, ...] | None = None
    field_major: bool = False
    """The entries' first fields, then their second fields, and so on (RTCM 3 MSM)."""
    stride: str | None = None
    """The member that holds each entry's bytes (SBF's SBLength): an entry's fields are read from
    its start, its last field (`trailing`, the bytes left) keeps the bytes after them as sent; a
    group may end the entry (SBF's Type-2 sub-blocks after each Type-1), counted by a member of
    the entry, its stride a member of the message, its entries after the stride's bytes."""

    @property
    def entry_width(self) -> int:
        return sum((f.width or 0) if isinstance(f, Field) else _case_width(f.cases[0]) for f in self.fields
                   if not isinstance(f, Group))

    @property
    def nested(self) -> Group | None:
        """The group each entry ends with, if any."""
        last = self.fields[-1] if self.fields else None
        return last if isinstance(last, Group) else None


@dataclass(frozen=True, slots=True)
class Case:
    """One layout of a choice: taken for the raw values `values` or within `range` (neither: any
    value no other case takes)."""

    values: frozenset[int]
    range: tuple[int, int] | None
    items: tuple[Field | Choice, ...]

    def holds(self, raw: int) -> bool:
        return raw in self.values or self.range is not None and self.range[0] <= raw <= self.range[1]


@dataclass(frozen=True, slots=True)
class Choice:
    """Bits laid out as the case that holds the raw value of the field `by` (at bits `offset`..,
    `width` wide: it may come after the choice; in a group's entry, counted from the entry's first
    bit, and before the choice)."""

    by: str
    offset: int
    width: int
    cases: tuple[Case, ...]

    def case(self, raw: int) -> Case | None:
        found = next((c for c in self.cases if c.holds(raw)), None)
        return found or next((c for c in self.cases if not c.values and c.range is None), None)

    @property
    def fields(self) -> tuple[Field, ...]:
        """The fields of every case, in order."""
        return tuple(f for case in self.cases for f in flat_fields(case.items))


Item = Field | Group | Choice


def count_of(count: str | int | tuple[str, ...], values: Any) -> int:
    """How many a `count` says, from the members read or set (a dict, or a record): a number, a
    member's value, or (a tuple) the product of the bits set in mask members (an integer, or
    data as '0'/'1' text)."""
    if isinstance(count, int):
        return count
    get = values.get if isinstance(values, dict) else lambda name: getattr(values, name)
    if isinstance(count, str):
        number = get(count)
        return number if isinstance(number, int) else 0
    total = 1
    for name in count:
        mask = get(name)
        total *= mask.count("1") if isinstance(mask, str) else bin(mask).count("1") if isinstance(mask, int) else 0
    return total


def flat_fields(items: tuple[Item, ...]) -> tuple[Field, ...]:
    """The fields of `items` outside groups, a bitfield's parts after it."""
    return tuple(f for item in items for f in ((item, *(p for _, p in item.parts)) if isinstance(item, Bitfield) else
                                               (item,) if isinstance(item, Field) else
                                               item.fields if isinstance(item, Choice) else ()))


def _case_width(case: Case) -> int:
    """The bits of a case of a group entry's choice (fields of fixed width only)."""
    return sum(f.width or 0 for f in case.items if isinstance(f, Field))


def read_items(items: tuple[Item, ...], reader: BitReader | ByteReader, values: dict[str, Any],
               start: int = 0) -> bool:
    """Read `items` into `values`; False once an optional field finds too few bits (it and what
    follows stay None). `start`: the first bit of the record (a group's entry) whose bits a
    choice's offset counts."""
    for item in items:
        if isinstance(item, Field):
            width = item.width
            if width is None:
                width = item.size(reader) if item.count is None else item.counted(count_of(item.count, values))
            if item.optional and reader.remaining < width:
                return False
            raw = reader.take(width, item.id)
            values[item.id] = item.from_raw(raw, width)
            if isinstance(item, Bitfield):
                item.read_parts(raw, values)
        elif isinstance(item, Group) and item.stride is not None:
            _read_strided(item, reader, values)
        elif isinstance(item, Group):
            if item.count is None:
                count = min(item.max, max(reader.remaining - item.after, 0) // item.entry_width)
            else:
                count = item.count if isinstance(item.count, int) else \
                    values[item.count] if isinstance(item.count, str) else count_of(item.count, values)
            if count < item.min or count * item.entry_width > reader.remaining:
                # A count from the bits left says the least a group takes (as C and Rust say it).
                needs = f"at least {item.min}" if item.count is None else str(count)
                raise NmeaError("short_payload", f"{item.id} needs {needs} entries of {item.entry_width} bits, "
                                f"{reader.remaining} bits left", reader.where, name=item.id)
            if isinstance(item.count, tuple) and count > item.max:  # masks may set more bits than a group holds
                raise NmeaError("bad_value", f"{item.id} has {count} entries, at most {item.max}", reader.where,
                                name=item.id)
            if item.field_major:  # each field for every entry in turn
                columns: list[dict[str, Any]] = [{} for _ in range(count)]
                for f in flat_fields(item.fields):  # fixed widths (rule A005), no choices (A013)
                    width = f.width or 0
                    for column in columns:
                        raw = reader.take(width, f.id)
                        column[f.id] = f.from_raw(raw, width)
                        if isinstance(f, Bitfield):
                            f.read_parts(raw, column)
                values[item.id] = [item.entry(**column) for column in columns]
                continue
            entries = []
            for _ in range(count):
                entry: dict[str, Any] = {}
                read_items(item.fields, reader, entry, reader.pos)
                entries.append(item.entry(**entry))
            values[item.id] = entries
        else:
            case = item.case(reader.peek(start + item.offset, item.width, item.by))
            if case is not None and not read_items(case.items, reader, values, start):
                return False
    return True


def _read_strided(item: Group, reader: BitReader | ByteReader, values: dict[str, Any],
                  block: dict[str, Any] | None = None) -> None:
    """A group whose entries are as many bytes as the member `item.stride` says (at least their
    fields'): each entry read from its start, within its bytes (its last field takes the rest),
    then the entries of the group it ends with, if any. `values` holds the members its count
    names, `block` (None: `values`) those of the message, which its stride names."""
    assert item.stride is not None
    stride = 8 * (values if block is None else block)[item.stride]
    count = 1 if item.count is None else item.count if isinstance(item.count, int) else \
        values[item.count] if isinstance(item.count, str) else count_of(item.count, values)
    if count and stride < item.entry_width:   # (the stride of no entry says nothing)
        raise NmeaError("bad_value", f"{item.stride} is {stride // 8}, an entry of {item.id} takes at least "
                        f"{item.entry_width // 8} bytes", reader.where, name=item.stride)
    if item.count is None:
        count = min(item.max, max(reader.remaining - item.after, 0) // stride)
    if count < item.min or count * stride > reader.remaining:
        needs = f"at least {item.min}" if item.count is None else str(count)
        raise NmeaError("short_payload", f"{item.id} needs {needs} entries of {stride} bits, "
                        f"{reader.remaining} bits left", reader.where, name=item.id)
    length = reader.length
    nested = item.nested
    fields = item.fields[:-1] if nested is not None else item.fields
    entries = []
    for k in range(count):
        if reader.pos + stride > length:   # (after a nested group's entries: the next entry cut)
            raise NmeaError("short_payload", f"{item.id} needs {count - k} entries of {stride} bits, "
                            f"{length - reader.pos} bits left", reader.where, name=item.id)
        reader.length = reader.pos + stride   # the entry's bytes: its last field reads to their end
        entry: dict[str, Any] = {}
        try:
            read_items(fields, reader, entry)
        finally:
            reader.length = length
        if nested is not None:   # its own entries, after its bytes
            _read_strided(nested, reader, entry, values if block is None else block)
        entries.append(item.entry(**entry))
    values[item.id] = entries


class Prefix(NamedTuple):
    """A layout's leading fields of fixed width compiled into one function (the generic reader
    costs several calls a field): `read(value, length)` returns their members (a dict) from a payload of at
    least `bits` bits; `put_json(record, out)` puts their decoded JSON members."""

    items: int  # how many of the layout's items it reads
    bits: int
    read: Any
    put_json: Any


_TABLE_BITS = 10
"""A number of at most this many bits that is signed, scaled or has special values is decoded by
a table of its every value (1,024 at most)."""


def _value_expr(item: Field, name: str, raw: str, names: dict[str, Any]) -> str:
    """The expression of `item`'s decoded value from `raw` (an expression of its raw bits,
    evaluated once), exactly what its from_raw gives: numbers (their unit and special values
    included), flags, codes and spare bits in line, the field's own conversion for the others
    (text, data). `name` names the field in `names`, the compiled code's globals, where the
    tables the expression uses are put."""
    names[name] = item
    width = item.width
    assert width is not None
    if isinstance(item, Unsigned) and width <= _TABLE_BITS and (isinstance(item, Signed) or item.special
                                                                 or item.divisor != 1 or item.base):
        # a small field's every value, by its raw integer: its from_raw once for each
        names[f"{name}_values"] = tuple(item.from_raw(code, width) for code in range(1 << width))
        return f"{name}_values[{raw}]"
    if isinstance(item, Unsigned):
        if isinstance(item, Signed):  # two's complement: the sign bit's weight negated
            raw = f"(({raw} ^ {1 << (width - 1)}) - {1 << (width - 1)})"
        operand = "r" if item.special else raw
        if item.divisor == 1:
            number = operand + (f" + {item.base!r}" if item.base or isinstance(item.base, float) else "")
        elif item.base:  # as from_raw: the base moved into the raw scale before the division
            number = f"({operand} + {item.base * item.divisor!r}) / {item.divisor}"
        else:
            number = f"{operand} / {item.divisor}"
        if not item.special:
            return number
        if len(item.special) == 1:
            names[f"{name}_special"] = item.special[0]
            return f"{name}_special if (r := {raw}) == {item.special[0].raw} else {number}"
        names[f"{name}_special"] = {sp.raw: sp for sp in item.special}
        return f"{name}_special[r] if (r := {raw}) in {name}_special else {number}"
    if isinstance(item, Flag):
        return f"{raw} != 0"
    if isinstance(item, Code):
        # by the raw integer of each member whose value is one written in decimal
        members = {int(m.value): m for m in item.enum
                   if isinstance(m.value, str) and m.value.isdigit() and str(int(m.value)) == m.value}
        if width <= 8:  # a table of every raw value
            names[f"{name}_members"] = tuple(members.get(code, code) for code in range(1 << width))
            return f"{name}_members[{raw}]"
        names[f"{name}_members"] = members
        return f"{name}_members.get(r := {raw}, r)"
    if type(item) in (Field, Spare):
        return raw
    if type(item) is Data:
        return f"format({raw}, '0{width}b')"  # bits_text
    if type(item) is Text and width % 6 == 0 and width:  # from_raw's steps, their sizes known
        pad = -width % 24
        names["b2a_base64"], names["BASE64_TO_TEXT"] = binascii.b2a_base64, _BASE64_TO_TEXT
        data = f"({raw} << {pad}).to_bytes({(width + pad) // 8}, 'big')" if pad else f"{raw}.to_bytes({width // 8}, 'big')"
        chars = f"b2a_base64({data}, newline=False)" + (f"[:{width // 6}]" if pad else "")
        return f"{chars}.translate(BASE64_TO_TEXT).decode('ascii')"
    return f"{name}.from_raw({raw}, {width})"


def compile_prefix(items: tuple[Item, ...]) -> Prefix:
    """The Prefix of `items`: straight-line code for numbers (their unit and special values
    included), flags, codes and spare bits, the field's own conversion for the others (text,
    data); the first item that is not a field of fixed width (a group, a choice, a variable or
    optional field) ends it. Decoded values and JSON are exactly those of the field classes."""
    put = ["def put_json(record, out):"]
    names: dict[str, Any] = {"Special": Special}
    members: list[str] = []  # each field's key and value expression in a dict display
    offset = count = 0
    prefix_bits = 0
    for item in items:
        if not isinstance(item, Field) or item.width is None or item.optional:
            break
        prefix_bits += item.width
    for item in items:
        if not isinstance(item, Field) or item.width is None or item.optional:
            break
        width, key, name = item.width, repr(item.id), f"f{count}"
        names[name] = item
        # `v` holds the prefix's bits only: constant shifts and masks take each field out
        shift = prefix_bits - offset - width
        raw = "v" if shift == 0 else f"v >> {shift}"
        if offset:
            raw = f"({raw}) & {(1 << width) - 1}"
        raw = f"({raw})"
        put.append(f"    value = record.{item.id}")
        members.append(f"{key}: {_value_expr(item, name, raw, names)}")
        if isinstance(item, Unsigned):
            if item.divisor == 1 and not item.base and not item.special:
                put.append(f"    if value is not None: out[{key}] = value")
            else:
                # the raw integer of a number in the unit; anything else as the field says
                if item.divisor == 1 and isinstance(item.base, int):
                    back = f"value - {item.base} if value.__class__ is int else round(value - {item.base})"
                else:
                    back = f"round((value - {item.base!r}) * {item.divisor})"
                put.append("    if value.__class__ is float or value.__class__ is int:")
                put.append(f"        out[{key}] = value")
                put.append(f"        out[{key[:-1]}_raw'] = {back}")
                put.append(f"    elif value is not None: {name}.put_json(out, value)")
        elif isinstance(item, Flag) or type(item) in (Field, Spare):
            put.append(f"    if value is not None: out[{key}] = value")
        elif isinstance(item, Code):
            names[f"{name}_enum"] = item.enum
            put.append(f"    if value is not None: out[{key}] = value.name.lower() "
                       f"if isinstance(value, {name}_enum) else value")
        else:
            put.append(f"    if value is not None: {name}.put_json(out, value)")
        offset += width
        count += 1
    read = ["def read(value, length):", f"    v = value >> (length - {offset})",
            "    return {", *(f"        {m}," for m in members), "    }"]
    put.append("    return out")
    exec("\n".join(read + put), names)  # code built above from the spec's layout, never from input
    return Prefix(count, offset, names["read"], names["put_json"])

_STRAIGHT = (Field, Spare, Unsigned, Signed, Flag, Code, Text, Data)
"""The field classes a compiled decoder reads in line (a bitfield's parts, a counted width or
a group take the generic reader)."""


def _case_test(case: Case) -> str:
    """The condition on `r` (the selector's raw value) under which a compiled reader or writer
    takes `case`: its values, its range, or either."""
    tests = [f"r in {sorted(case.values)!r}"] if case.values else []
    if case.range is not None:
        tests.append(f"{case.range[0]} <= r <= {case.range[1]}")
    return " or ".join(tests)


def compile_decoder(cls: type[Message] | type[Application]) -> Any:
    """decode(value, length, padding, applications): the message of class `cls` from its payload's
    bits (one integer, `length` bits) and its fill bits' values, by straight-line code: every
    field's bits taken by constant shifts and masks, a choice by its selector's raw value, the
    members set at once; the application of `applications` its data bits carry (a message whose
    layout has a DISPATCH field), as _application finds it: when the data end the payload, by the
    application's own decoder from their bits, else (and when that one does not read them) by
    _application. None when the payload is shorter than the fields it reads need: the generic
    reader (Record.read) then says which field is missing, or that an optional one ends the
    message. A group (or a field of another kind) is read from its offset on by the generic
    reader. The members are exactly those Record.read and decode would give."""
    names: dict[str, Any] = {"new": object.__new__, "cls": cls, "BitReader": BitReader,
                             "read_items": read_items, "bits_text": bits_text, "application_of": _application,
                             "NmeaError": NmeaError}
    members: dict[str, str] = {}  # each member's default, as a literal
    for f in dataclasses.fields(cls):
        if f.default is not dataclasses.MISSING and (f.default is None or isinstance(f.default, (str, int))):
            members[f.name] = repr(f.default)
        elif f.default_factory is list:
            members[f.name] = "[]"
        else:  # a default no literal makes
            return None
    if "__post_init__" in dir(cls):
        return None
    if "padding" in members:  # a message's; an application has none
        members["padding"] = "padding"
    dispatch = cls.DISPATCH if issubclass(cls, Message) else None
    if dispatch is not None:  # its application set last, from the members it reads
        del members["application"]
    where = repr(f"AIS DAC {cls.DAC} FI {cls.FID}") if issubclass(cls, Application) else \
        "'AIS type ' + str(value >> (length - 6))"
    code = ["def decode(value, length, padding, applications):"]
    counter = [0]

    def build(set_: dict[str, str], trailing: str, pad: str, application: str | None = None) -> list[str]:
        """The lines that end the message `m` (made first, each field's member set as it is read)
        of the members `set_` (id: its expression, `m.<id>` when set already): each member not yet
        set then set (slots: the generated classes'; a subclass without them keeps its own in its
        dict), then its application (`application`, else _application's)."""
        values = {member: set_.get(member, trailing if member == "trailing" else default)
                  for member, default in members.items()}
        if dispatch is not None:
            values["application"] = application or "application_of(m, applications)"
        return [*(f"{pad}m.{member} = {value}" for member, value in values.items() if value != f"m.{member}"),
                f"{pad}return m"]

    def generic(items: list[Item], offset: int, set_: dict[str, str], pad: str) -> list[str]:
        """The lines that read `items` from bit `offset` on by the generic reader."""
        counter[0] += 1
        rest = f"rest{counter[0]}"
        names[rest] = tuple(items)
        values = ", ".join(f"{member!r}: {var}" for member, var in set_.items())
        return [f"{pad}reader = BitReader(value, length, {where})",
                f"{pad}reader.pos = {offset}",
                f"{pad}values = {{{values}}}", f"{pad}read_items({rest}, reader, values)",
                f"{pad}left = reader.remaining",
                f"{pad}trailing = bits_text(value & ((1 << left) - 1), left)",
                *build({member: f"values.get({member!r}, {members[member]})" for member in members
                        if member not in ("trailing", "padding")}, "trailing", pad)]

    def walk(items: list[Item], offset: int, set_: dict[str, str], pad: str) -> list[str]:
        """The lines that read `items` from bit `offset` on, the members `set_` read before them."""
        out: list[str] = []
        set_ = dict(set_)
        i = 0
        while i < len(items):
            item = items[i]
            run: list[Field] = []  # fields of fixed width read from one window of bits
            end = offset
            for f in items[i:]:
                if (not isinstance(f, Field) or type(f) not in _STRAIGHT or f.width is None or f.count is not None
                        or f.optional and run):
                    break
                run.append(f)
                end += f.width
                if f.optional:  # a run of its own: the message may end before it
                    break
            if run:
                if run[0].optional:  # too few bits left for it: the message ends before it
                    out.append(f"{pad}if length < {end}:")
                    left = f"length - {offset}"
                    out += build(set_, f"bits_text(value & ((1 << ({left})) - 1), {left})", pad + "    ")
                else:
                    out += [f"{pad}if length < {end}:", f"{pad}    return None"]
                out.append(f"{pad}v = value >> (length - {end})")
                at = offset
                for f in run:
                    assert f.width is not None
                    shift = end - at - f.width
                    raw = "v" if shift == 0 else f"v >> {shift}"
                    if at:  # `v` holds the bits before the run too
                        raw = f"({raw}) & {(1 << f.width) - 1}"
                    counter[0] += 1
                    out.append(f"{pad}m.{f.id} = {_value_expr(f, f'f{counter[0]}', f'({raw})', names)}")
                    set_[f.id] = f"m.{f.id}"
                    at += f.width
                offset = end
                i += len(run)
                continue
            if (item is dispatch and type(item) is Data and item.width is None and not item.optional
                    and not item.after and i == len(items) - 1 and "message_type" in set_
                    and all(member in set_ for member in item.dispatch)):
                # the data that end the message, the application their DAC and FI name (as
                # _application finds it) read from their bits; data when there is none
                names["DATA"] = item
                dac, fid = (set_[member] for member in item.dispatch)
                data = build({**set_, item.id: "None"}, '""', pad + "        ", "application")
                text = build({**set_, item.id: "bits_text(raw, width)"}, '""', pad, "None")
                return out + [
                    f"{pad}width = max(length - {offset}, 0)",
                    f"{pad}raw = value & ((1 << width) - 1)",
                    f"{pad}application_cls = applications.get(({set_['message_type']}, {dac}, {fid}))",
                    f"{pad}if application_cls is not None:",
                    f"{pad}    try:",
                    f"{pad}        application = application_cls._decoder(raw, width, '', None)",
                    f"{pad}    except NmeaError:  # (_application: the data stay data)",
                    f"{pad}        application = None",
                    f"{pad}    if application is not None:",
                    *data,
                    *build({**set_, item.id: "bits_text(raw, width)"}, '""', pad + "    "),
                    *text]
            if (isinstance(item, (Text, Data)) and type(item) in _STRAIGHT and item.width is None
                    and item.count is None and not item.optional and not item.after and i == len(items) - 1):
                # the variable field that ends the message: the bits left (text: whole characters)
                width = f"(length - {offset}) // 6 * 6" if isinstance(item, Text) else f"length - {offset}"
                counter[0] += 1
                var, name = f"x{counter[0]}", f"f{counter[0]}"
                names[name] = item
                out += [f"{pad}width = max({width}, 0)",
                        f"{pad}{var} = {name}.from_raw(value >> (length - {offset} - width) & ((1 << width) - 1), width)",
                        f"{pad}left = length - {offset} - width"]
                set_[item.id] = var
                return out + build(set_, "bits_text(value & ((1 << left) - 1), left)", pad)
            if isinstance(item, Choice):
                sel_end = item.offset + item.width
                selector = cls.FIELDS.get(item.by)
                if (item.by in set_ and selector is not None and selector.width == item.width
                        and (type(selector) in (Field, Spare) or type(selector) is Unsigned and selector.divisor == 1
                             and not selector.base and not selector.special)):
                    out.append(f"{pad}r = {set_[item.by]}")  # its member: its raw value, read already
                else:
                    out += [f"{pad}if length < {sel_end}:", f"{pad}    return None",
                            f"{pad}r = value >> (length - {sel_end}) & {(1 << item.width) - 1}"]
                default = next((c for c in item.cases if not c.values and c.range is None), None)
                first = True
                for case in item.cases:
                    if case is default:
                        continue
                    out.append(f"{pad}{'if' if first else 'elif'} {_case_test(case)}:")
                    out += walk([*case.items, *items[i + 1:]], offset, set_, pad + "    ")
                    first = False
                tail = [*(default.items if default is not None else ()), *items[i + 1:]]
                if first:
                    return out + walk(tail, offset, set_, pad)
                out.append(f"{pad}else:")
                return out + walk(tail, offset, set_, pad + "    ")
            if isinstance(item, Group) and i == len(items) - 1:
                lines = _group_lines(item, offset, names, pad)
                if lines is not None:
                    set_[item.id] = "entries"
                    return out + lines + build(set_, "bits_text(value & ((1 << left) - 1), left)", pad)
            return out + generic(items[i:], offset, set_, pad)
        return out + build(set_, f'"" if length == {offset} else bits_text(value & ((1 << (length - {offset})) - 1), '
                                 f'length - {offset})', pad)

    code += ["    m = new(cls)", *walk(list(cls.LAYOUT), 0, {}, "    ")]
    source = "\n".join(code)
    exec(source, names)  # code built above from the spec's layout, never from input
    return names["decode"]


def _group_lines(group: Group, offset: int, names: dict[str, Any], pad: str) -> list[str] | None:
    """The lines of compile_decoder that read `group`, the layout's last item, from bit `offset`
    on into `entries` (and the bits left after them into `left`), as read_items reads it: its
    entries' count from the bits left (or a fixed count), each entry's fields of fixed width by
    constant shifts and masks, its class made as compile_decoder makes a message. The count out
    of bounds returns None (the generic reader says why). None for a group of another kind."""
    fields = [f for f in group.fields if isinstance(f, Field)]
    width = group.entry_width
    if (group.count is not None and not isinstance(group.count, int) or group.after or group.stride is not None
            or group.field_major or not width or len(fields) != len(group.fields)
            or not all(type(f) in _STRAIGHT and f.width is not None and f.count is None and not f.optional
                       for f in fields)):
        return None
    entry = group.entry
    entry_fields = dataclasses.fields(entry)
    if ([f.name for f in entry_fields] != [f.id for f in fields] or "__post_init__" in dir(entry)
            or any(f.default is not None for f in entry_fields)):
        return None
    name = f"g{offset}_{group.id}"
    names[name] = entry
    count = f"min({group.max}, (length - {offset}) // {width})" if group.count is None else str(group.count)
    out = [f"count = {count}",
           f"if count < {group.min} or count * {width} > length - {offset}:",
           "    return None",
           "entries = []",
           f"at = length - {offset}",
           "for _ in range(count):",
           f"    at -= {width}",
           f"    v = value >> at & {(1 << width) - 1}",
           f"    e = new({name})"]
    end = 0
    for n, f in enumerate(fields):
        assert f.width is not None
        end += f.width
        shift = width - end
        raw = "v" if shift == 0 else f"v >> {shift}"
        if end != f.width:
            raw = f"({raw}) & {(1 << f.width) - 1}"
        out.append(f"    e.{f.id} = {_value_expr(f, f'{name}_{n}', f'({raw})', names)}")
    out += ["    entries.append(e)", "left = at"]
    return [pad + line for line in out]


class WritePrefix(NamedTuple):
    """A layout's leading fields of fixed width that are numbers, flags, codes, text or spare bits,
    compiled into one function: `write(record, where)` returns their `bits` bits as one integer
    (`where` None: an AIS message's, made only for an error)."""

    items: int  # how many of the layout's items it writes
    bits: int
    write: Any


def compile_write_prefix(items: tuple[Item, ...]) -> WritePrefix:
    """The WritePrefix of `items`: straight-line code for the values a decoder gives (an int or
    float in range, a bool, a member of the field's enum), the field's own to_raw for any other
    (text always), which raises the error write_items would. The first item of another kind ends
    it (a bitfield writes from its parts, a data field may be an application's)."""
    code = ["def write(record, where):", "    bits = 0"]
    names: dict[str, Any] = {"Special": Special, "_where": _where}
    offset = count = 0
    for item in items:
        if not _writes_in_line(item):
            break
        assert isinstance(item, Field) and item.width is not None
        code += _write_field(item, f"f{count}", names, "    ")
        offset += item.width
        count += 1
    code.append("    return bits")
    exec("\n".join(code), names)  # code built above from the spec's layout, never from input
    return WritePrefix(count, offset, names["write"])


def _writes_in_line(item: Item, optional: bool = False) -> bool:
    """Whether _write_field writes `item`: a number, flag, code, text or spare bits of fixed width
    (and, `optional`, one the message may end before)."""
    return (isinstance(item, Field) and type(item) in (Field, Spare, Unsigned, Signed, Flag, Code, Text)
            and item.width is not None and (optional or not item.optional))


def _write_field(item: Field, name: str, names: dict[str, Any], pad: str, into: str | None = None,
                 owner: str = "record") -> list[str]:
    """The lines that put `item`'s bits below `bits` (`record` the message, `where` the errors'
    address or None), `name` its name in `names`; `into`: the lines that set that variable to
    them instead (to_raw's raw integer); `owner`: the variable of the record that holds it (a
    group's entry)."""
    width = item.width
    assert width is not None
    names[name] = item
    code: list[str] = []
    code.append(f"    value = {owner}.{item.id}")
    fallback = f"{name}.to_raw(value, where or _where(record))[0]"
    if isinstance(item, Unsigned):
        low, high = item.bounds(width)
        mask = f" & {(1 << width) - 1}" if low < 0 else ""  # a negative number's two's complement
        if item.divisor == 1 and isinstance(item.base, int) and not item.special:
            # a whole number in range (a float: to_raw, which takes whole ones only)
            raw = f"(raw := value - {item.base})" if item.base else "value"
            fast = (f"value.__class__ is int and {low} <= {raw} <= {high}", f"{'raw' if item.base else 'value'}{mask}")
        else:
            if item.divisor == 1 and isinstance(item.base, int):
                number, numeric = f"value - {item.base}" if item.base else "value", "value.__class__ is int"
            else:
                offset_ = f"(value - {item.base!r})" if item.base or isinstance(item.base, float) else "value"
                number = f"round({offset_} * {item.divisor})" if item.divisor != 1 else f"round({offset_})"
                numeric = "value.__class__ is float or value.__class__ is int"  # a decoded value: a float
            special = " else value.raw if value.__class__ is Special" if item.special else ""
            # any other value: a number below the range, so that to_raw says what is wrong
            code.append(f"    raw = {number} if {numeric}{special} else {low - 1}")
            fast = f"{low} <= raw <= {high}", f"raw{mask}"
    elif isinstance(item, Flag):
        fast = "value is True or value is False", "value"
    elif type(item) is Text and width % 6 == 0:  # six-bit text of its whole width, as to_raw reads it
        chars, zeros = width // 6, -(width // 6) % 4
        names["a2b_base64"], names["TEXT_TO_BASE64"], names["TEXT_CHARS"] = \
            binascii.a2b_base64, _TEXT_TO_BASE64, _TEXT_CHARS
        data = "value.encode('ascii').translate(TEXT_TO_BASE64)" + (f" + {b'A' * zeros!r}" if zeros else "")
        number = f"int.from_bytes(a2b_base64({data}, strict_mode=True), 'big')" + (f" >> {6 * zeros}" if zeros else "")
        fast = f"value.__class__ is str and len(value) == {chars} and TEXT_CHARS.issuperset(value)", number
    elif isinstance(item, Text):  # the field's to_raw checks it
        fast = None
    elif isinstance(item, Code):  # a member of the field's enum whose code fits; to_raw for any other
        codes: dict[Any, int] = {}  # by each member's value
        for member in item.enum:
            try:
                code_value = int(member.value)
            except (TypeError, ValueError):
                continue
            if 0 <= code_value <= (1 << width) - 1:
                codes[member._value_] = code_value
        names[f"{name}_enum"], names[f"{name}_codes"] = item.enum, codes
        fast = (f"value.__class__ is {name}_enum and (raw := {name}_codes.get(value._value_)) is not None", "raw")
    else:
        fast = f"value.__class__ is int and 0 <= value <= {(1 << width) - 1}", "value"
    raw = fallback if fast is None else f"({fast[1]} if {fast[0]} else {fallback})"
    code.append(f"    {into} = {raw}" if into else f"    bits = bits << {width} | {raw}")
    return [pad + line[4:] for line in code]


def compile_encoder(items: tuple[Item, ...], raw: bool = False) -> Any:
    """encode(record): a message's armored payload and fill bits (Message.encode), its layout
    `items` written as write_items writes them, by straight-line code: each field in line
    (_write_field) or by its own to_raw (a variable width, data an application carries), a
    choice by the raw value of its selector's member, the message ending at an optional field
    left None; from a group on, write_items. Then its trailing bits, its fill bits (padding) and
    the armor, in line wherever the layout ends. The errors' address is made only for an error.
    `raw`: encode(record, where, message), an application's bits (Application.raw_bits): its
    layout and trailing bits as one integer and their count, errors naming `where` or `message`."""
    names: dict[str, Any] = {"Special": Special, "_where": _where, "BitWriter": BitWriter,
                             "write_items": write_items, "_bad_value": _bad_value,
                             "b2a_base64": binascii.b2a_base64, "BASE64_TO_ARMOR": _BASE64_TO_ARMOR,
                             "PADDINGS": _PADDINGS, "_armored": _armored}
    if raw:  # errors name the `where` given, else the message's (none: an empty one)
        names["_where"] = _message_where
    counter = [0]
    by_id = {f.id: f for f in flat_fields(items)}  # as Record.field finds them

    def finish(length: str, pad: str, known: int | None = None) -> list[str]:
        """The lines that end the message of `bits` and `length` (an expression; `known`: its
        value, when the layout's path so far has fixed widths only): its trailing bits and fill
        bits added (as BitWriter.put_bits would), its armor returned."""
        usual: list[str] = []
        if raw:  # an application's bits: its trailing bits after them
            return [f"{pad}length = {length}",
                    f"{pad}trailing = record.trailing",
                    f"{pad}if trailing:",
                    f"{pad}    bits = bits << len(trailing) | int(trailing, 2) & ((1 << len(trailing)) - 1)",
                    f"{pad}    length += len(trailing)",
                    f"{pad}return bits, length"]
        if known is not None:  # no trailing bits, fill bits of value 0: every size a constant
            fill = -known % 6
            zeros = -(known + fill) % 24
            data = f"(bits << {fill + zeros})" if fill + zeros else "bits"
            chars = f"[:{(known + fill) // 6}]" if zeros else ""
            usual = [f"{pad}if not record.trailing and record.padding == \"\":",
                     f"{pad}    return b2a_base64({data}.to_bytes({(known + fill + zeros) // 8}, \"big\"), "
                     f"newline=False){chars}.translate(BASE64_TO_ARMOR).decode(\"ascii\"), {fill}"]
            if fill:  # fill bits as sent (their values in padding), no trailing bits
                shifted = f" << {zeros}" if zeros else ""
                usual += [f"{pad}if not record.trailing and (p := PADDINGS.get(record.padding)) is not None "
                          f"and len(record.padding) == {fill}:",
                          f"{pad}    return b2a_base64(((bits << {fill} | p){shifted}).to_bytes("
                          f"{(known + fill + zeros) // 8}, \"big\"), newline=False){chars}"
                          f".translate(BASE64_TO_ARMOR).decode(\"ascii\"), {fill}"]
        return [*usual, f"{pad}return _armored(bits, {length}, record)"]

    def walk(items: list[Item], static: int, pad: str, fixed: bool = True) -> list[str]:
        """The lines that write `items`, `static` bits counted but not yet added to `length`
        (`fixed`: `length` still 0)."""
        out: list[str] = []
        for i, item in enumerate(items):
            counter[0] += 1
            name = f"f{counter[0]}"
            if isinstance(item, Field) and item.optional:
                out += [f"{pad}if record.{item.id} is None:",
                        *finish(f"length + {static}", pad + "    ", static if fixed else None)]
            if _writes_in_line(item, optional=True):
                assert isinstance(item, Field) and item.width is not None
                out += _write_field(item, name, names, pad)
                static += item.width
            elif isinstance(item, Field) and item.count is None:
                names[name] = item
                out.append(f"{pad}value = record.{item.id}")
                application = isinstance(item, Data) and not raw
                if application and item.width is None:  # its application's bits, as one integer
                    out += [f"{pad}if value is None and record.application is not None:",
                            f"{pad}    raw, width = record.application.raw_bits(where, record)",
                            f"{pad}else:"]
                    pad += "    "
                elif application:
                    out += [f"{pad}if value is None and record.application is not None:",
                            f"{pad}    value = record.application.bits(where or _where(record))"]
                fallback = f"{name}.to_raw(value, where or _where(record))"
                if isinstance(item, Bitfield):
                    out.append(f"{pad}raw, width = {name}.word(record, where or _where(record)), {item.width or 0}")
                elif type(item) is Data:  # bits as text, as to_raw reads them
                    sized = f" and len(value) == {item.width}" if item.width is not None else ""
                    out.append(f"{pad}raw, width = (int(value, 2) if value else 0, len(value)) "
                               f"if value.__class__ is str and not value.strip('01'){sized} else {fallback}")
                elif type(item) is Text and item.width is None:  # six-bit text, as to_raw reads it
                    names.update(a2b_base64=binascii.a2b_base64, TEXT_TO_BASE64=_TEXT_TO_BASE64,
                                 TEXT_CHARS=_TEXT_CHARS, PADS=_BASE64_PADS, DROPS=_BASE64_DROPS)
                    data = "value.encode('ascii').translate(TEXT_TO_BASE64) + PADS[len(value) & 3]"
                    out.append(f"{pad}raw, width = (0, 0) if value == '' else (int.from_bytes(a2b_base64({data}, "
                               f"strict_mode=True), 'big') >> DROPS[len(value) & 3], len(value) * 6) "
                               f"if value.__class__ is str and TEXT_CHARS.issuperset(value) else {fallback}")
                else:
                    out.append(f"{pad}raw, width = {fallback}")
                if application and item.width is None:
                    pad = pad[:-4]
                out += [f"{pad}bits = bits << width | raw & ((1 << width) - 1)", f"{pad}length += width"]
                fixed = False
            elif isinstance(item, Choice):
                names[name] = item
                selector = by_id[item.by]
                if _writes_in_line(selector, optional=True):  # its raw value as _write_field writes it
                    out += _write_field(selector, f"{name}_by", names, pad, into="r")
                else:
                    out.append(f"{pad}r = record.field({item.by!r}).to_raw(record.{item.by}, where or _where(record))[0]")
                default = next((c for c in item.cases if not c.values and c.range is None), None)
                first = True
                for case in item.cases:
                    if case is default:
                        continue
                    out.append(f"{pad}{'if' if first else 'elif'} {_case_test(case)}:")
                    out += walk([*case.items, *items[i + 1:]], static, pad + "    ", fixed)
                    first = False
                tail = [*(default.items if default is not None else ()), *items[i + 1:]]
                if first:
                    return out + walk(tail, static, pad, fixed)
                return out + [f"{pad}else:", *walk(tail, static, pad + "    ", fixed)]
            elif (isinstance(item, Group) and i == len(items) - 1 and not item.after and item.stride is None
                  and not item.field_major and (item.count is None or isinstance(item.count, int))
                  and all(_writes_in_line(f) for f in item.fields)):
                # a group that ends the layout, its entries' fields in line (as write_items writes them)
                out += [f"{pad}for entry in record.{item.id}:"]
                for n, f in enumerate(item.fields):
                    assert isinstance(f, Field)
                    out += _write_field(f, f"{name}_{n}", names, pad + "    ", owner="entry")
                out.append(f"{pad}    length += {item.entry_width}")
                return out + finish(f"length + {static}", pad)
            else:  # a group, a counted field: the generic writer
                names[name] = tuple(items[i:])
                return out + [f"{pad}writer = BitWriter()", f"{pad}writer.put(bits, length + {static})",
                              f"{pad}write_items({name}, record, writer, where or _where(record))",
                              f"{pad}bits = writer.value", *finish("writer.length", pad)]
        return out + finish(f"length + {static}", pad, static if fixed else None)

    head = ["def encode(record, where, message):", "    bits = length = 0"] if raw else \
        ["def encode(record):", "    bits = length = 0", "    where = None"]
    code = [*head, *walk(list(items), 0, "    ")]
    if raw:  # the errors' address: `where`, else the message's
        code = [line.replace("_where(record)", "_where(message)") for line in code]
    exec("\n".join(code), names)  # code built above from the spec's layout, never from input
    return names["encode"]


def _armored(bits: int, length: int, record: Any) -> tuple[str, int]:
    """The armored payload and fill bits of a message's `length` bits (`bits`) and its trailing
    bits and padding (its fill bits as sent, or zeros): the end of every compiled encoder but for
    the usual case it writes in line."""
    trailing = record.trailing
    if trailing:
        bits = bits << len(trailing) | int(trailing, 2) & ((1 << len(trailing)) - 1)
        length += len(trailing)
    fill = -length % 6
    padding = record.padding
    if padding == "":
        bits <<= fill
    elif padding.strip("01") or len(padding) != fill:
        raise _bad_value(_where(record), "padding", padding, f"{fill} bits")
    else:
        bits = bits << fill | int(padding, 2)
    length += fill
    zeros = -length % 24  # base64 takes whole bytes, three for four characters
    data = (bits << zeros).to_bytes((length + zeros) // 8, "big")
    return binascii.b2a_base64(data, newline=False)[:length // 6].translate(_BASE64_TO_ARMOR).decode("ascii"), fill


def _message_where(message: Any) -> str:
    """The errors' address of the message an application's bits are written for ("" for none)."""
    return "" if message is None else _where(message)


def _written(writer: BitWriter | ByteWriter) -> int:
    """The bytes written so far."""
    return writer.length // 8 if isinstance(writer, BitWriter) else len(writer.payload)


def write_items(items: tuple[Item, ...], message: Any, writer: BitWriter | ByteWriter, where: str,
                block: Any = None) -> bool:
    """Write the values of `items` from `message`'s members; False at an optional field left None.
    `block` (None: `message`) holds the members a group's stride names (a nested group's: the
    message's, not its entry's)."""
    for item in items:
        if isinstance(item, Field):
            value = getattr(message, item.id)
            if value is None and item.optional:
                return False
            if value is None and isinstance(item, Data) and getattr(message, "application", None) is not None:
                value = message.application.bits(where)
            if isinstance(item, Bitfield):
                writer.put(item.word(message, where), item.width or 0)
            elif item.count is not None:  # as many units as the count says
                raw, width = item.to_raw(value, where)
                number = count_of(item.count, message)
                if width != item.counted(number):
                    raise _bad_value(where, item.id, value, f"{number} units, as {item.count} says")
                writer.put(raw, width)
            else:
                writer.put(*item.to_raw(value, where))
        elif isinstance(item, Group):
            entries = getattr(message, item.id)
            if isinstance(item.count, tuple) and len(entries) != count_of(item.count, message):
                raise _bad_value(where, item.id, f"{len(entries)} entries",
                                 f"{count_of(item.count, message)} entries, as the bits set in "
                                 f"{' and '.join(item.count)} say")
            if item.field_major:
                for f in flat_fields(item.fields):  # fixed widths (rule A005), no choices (A013)
                    for entry in entries:
                        if isinstance(f, Bitfield):
                            writer.put(f.word(entry, where), f.width or 0)
                        else:
                            writer.put(*f.to_raw(getattr(entry, f.id), where))
                continue
            outer = message if block is None else block
            stride = getattr(outer, item.stride) if item.stride is not None else None
            nested = item.nested
            fields = item.fields[:-1] if nested is not None else item.fields
            for entry in entries:
                start = _written(writer)
                write_items(fields, entry, writer, where)
                if item.stride is not None and _written(writer) - start != stride:
                    raise _bad_value(where, item.stride, stride, f"the bytes of each entry of {item.id} "
                                     f"({_written(writer) - start})")
                if nested is not None:   # the entry's own group, after its bytes
                    if len(getattr(entry, nested.id)) != count_of(nested.count or 0, entry):
                        raise _bad_value(where, str(nested.count), count_of(nested.count or 0, entry),
                                         f"the number of entries of {nested.id} ({len(getattr(entry, nested.id))})")
                    write_items((nested,), entry, writer, where, outer)
        else:  # the selector: a field of the entry before the choice, or of the message
            selector = next((f for f in items if isinstance(f, Field) and f.id == item.by), None) or \
                message.field(item.by)
            case = item.case(selector.to_raw(getattr(message, item.by), where)[0])
            if case is not None and not write_items(case.items, message, writer, where):
                return False
    return True


def items_json(items: tuple[Item, ...], message: Any) -> dict[str, Any]:
    """The decoded JSON members of a message or group entry: each field present, in order."""
    out: dict[str, Any] = {}
    for item in items:
        if isinstance(item, Group):
            out[item.id] = [items_json(item.fields, entry) for entry in getattr(message, item.id)]
        else:
            for f in flat_fields((item,)):
                value = getattr(message, f.id)
                if value is not None:
                    f.put_json(out, value)
    return out


@dataclass(kw_only=True, slots=True)
class Record:
    """A decoded layout (a message, or the application its data bits carry): its fields, then
    the bits after the layout's last field, as sent ('0' and '1')."""

    trailing: str = ""
    """Bits after the layout's last field, as sent: a type 5 of 424 + 2 bits keeps 2."""

    ID: ClassVar[str]
    """The spec's id of the message or application (`position_report`, `meteo_hydro`)."""
    LAYOUT: ClassVar[tuple[Item, ...]]
    FIELDS: ClassVar[dict[str, Field]]
    _prefix: ClassVar[Prefix]
    _write_prefix: ClassVar[WritePrefix]
    DISPATCH: ClassVar[Data | None]
    """The data field whose bits an application may carry (the one with a `dispatch`)."""

    def __init_subclass__(cls, **kwargs: Any) -> None:
        # super() named: a slots dataclass is a new class, which a bare super() does not know
        super(Record, cls).__init_subclass__(**kwargs)
        if "LAYOUT" in cls.__dict__:
            cls.FIELDS = {f.id: f for f in flat_fields(cls.LAYOUT)}
            cls.DISPATCH = next((f for f in cls.FIELDS.values() if isinstance(f, Data) and f.dispatch), None)

    @classmethod
    def prefix(cls) -> Prefix:
        """The layout's compiled prefix, compiled on first use (not when the package loads)."""
        found: Prefix | None = cls.__dict__.get("_prefix")
        if found is None:
            found = compile_prefix(cls.LAYOUT)
            cls._prefix = found
        return found

    def write(self, writer: BitWriter, where: str) -> None:
        """Writes the layout's fields (its compiled write prefix, then the rest), then trailing."""
        prefix: WritePrefix | None = type(self).__dict__.get("_write_prefix")
        if prefix is None:
            prefix = compile_write_prefix(self.LAYOUT)
            type(self)._write_prefix = prefix
        writer.put(prefix.write(self, where), prefix.bits)
        if prefix.items < len(self.LAYOUT):
            write_items(self.LAYOUT[prefix.items:], self, writer, where)
        writer.put_bits(self.trailing)

    @classmethod
    def read(cls, reader: BitReader) -> dict[str, Any]:
        """The members of the layout from `reader` (its compiled prefix, then the rest)."""
        prefix = cls.prefix()
        if reader.pos == 0 and reader.length >= prefix.bits:
            values: dict[str, Any] = prefix.read(reader.value, reader.length)
            reader.pos = prefix.bits
            read_items(cls.LAYOUT[prefix.items:], reader, values)
        else:  # short: the generic reader says where
            values = {}
            read_items(cls.LAYOUT, reader, values)
        return values

    @classmethod
    def field(cls, name: str) -> Field:
        """The layout's field of member `name`."""
        return cls.FIELDS[name]

    def raw(self, name: str) -> int | None:
        """The raw integer of a number's member (a value in a unit or a special value); None when
        the member is None."""
        value = getattr(self, name)
        f = self.FIELDS[name]
        raw_number = getattr(f, "raw_number", None)  # numbers (Unsigned, rtcm3.SignMagnitude)
        return None if value is None or raw_number is None else int(raw_number(value, ""))

    def to_dict(self) -> dict[str, Any]:
        """The record as the decoded JSON of generated/vectors/ais.jsonl: each field present by
        its id (a number in a unit beside its raw integer as <id>_raw, a special value by its id,
        an enum value by its id, text as sent, data as its bits), then trailing."""
        return {**self._json(), "trailing": self.trailing}

    def _json(self) -> dict[str, Any]:
        prefix = self.prefix()
        out: dict[str, Any] = prefix.put_json(self, {})
        out.update(items_json(self.LAYOUT[prefix.items:], self))
        return out


@dataclass(kw_only=True, slots=True)
class Application(Record):
    """An application message (IMO SN.1/Circ.289, regional ones): the data bits of the binary
    messages whose DAC and FI fields hold a key of CARRIERS, of the types it names (DAC and FID: the
    first key)."""

    DAC: ClassVar[int]
    FID: ClassVar[int]
    CARRIERS: ClassVar[dict[tuple[int, int], tuple[int, ...]]]
    _decoder: ClassVar[Any]
    """decode(value, length, padding, applications): the class's compiled decoder (compile_decoder,
    `padding` and `applications` unused), compiled on first use."""

    def __init_subclass__(cls, **kwargs: Any) -> None:
        super(Application, cls).__init_subclass__(**kwargs)
        if "LAYOUT" in cls.__dict__:
            cls._decoder = _first_decoder(cls)

            def first_raw(self: Application, where: str | None, message: Any = None) -> tuple[int, int]:
                raw_bits = compile_encoder(cls.LAYOUT, raw=True)
                raw_bits.__doc__ = first_raw.__doc__
                raw_bits.__defaults__ = (None,)
                cls.raw_bits = raw_bits  # type: ignore[method-assign]
                return raw_bits(self, where, message)  # type: ignore[no-any-return]

            first_raw.__doc__ = Application.raw_bits.__doc__
            cls.raw_bits = first_raw  # type: ignore[method-assign]

    def raw_bits(self, where: str | None, message: Any = None) -> tuple[int, int]:
        """The data bits it is sent as, as one integer, and their count (each application class's
        own, compiled on first use: compile_encoder); errors name `where`, else (None) the address
        of `message`, the message it is written for."""
        raw_bits = compile_encoder(type(self).LAYOUT, raw=True)
        return raw_bits(self, where, message)  # type: ignore[no-any-return]

    def bits(self, where: str) -> str:
        """The data bits it is sent as."""
        raw, length = self.raw_bits(where)
        return bits_text(raw, length)


@dataclass(kw_only=True, slots=True)
class Message(Record):
    """What every decoded AIS message has besides its layout's fields."""

    padding: str = ""
    """The fill bits' values ('0' and '1'), as sent: fill bits are meant to be 0 but need not be."""
    application: Application | None = None
    """What its data bits carry, when the spec describes the application its DAC and FI name (its
    data member is then None)."""

    TYPES: ClassVar[tuple[int, ...]]
    _decoder: ClassVar[Any]
    """decode(value, length, padding, applications): the class's compiled decoder
    (compile_decoder), compiled on first use (not when the package loads)."""

    def __init_subclass__(cls, **kwargs: Any) -> None:
        super(Message, cls).__init_subclass__(**kwargs)
        if "LAYOUT" in cls.__dict__:
            cls._decoder = _first_decoder(cls)

            def first_encode(self: Message) -> tuple[str, int]:
                encode = compile_encoder(cls.LAYOUT)
                encode.__doc__ = first_encode.__doc__
                cls.encode = encode  # type: ignore[method-assign]
                return encode(self)  # type: ignore[no-any-return]

            first_encode.__doc__ = Message.encode.__doc__
            cls.encode = first_encode  # type: ignore[method-assign]

    def encode(self) -> tuple[str, int]:
        """The armored payload and its fill bits (each message class's own encode, compiled on
        first use: compile_encoder)."""
        encode = compile_encoder(type(self).LAYOUT)
        return encode(self)  # type: ignore[no-any-return]

    def to_dict(self) -> dict[str, Any]:
        """As Record.to_dict, the application's (when there is one) before trailing, then padding."""
        out = self._json()
        if self.application is not None:
            out["application"] = self.application.to_dict()
        return {**out, "trailing": self.trailing, "padding": self.padding}


def _first_decoder(cls: type[Message] | type[Application]) -> Any:
    """The decoder of `cls` until its first use, which compiles it (compile_decoder)."""
    def first(value: int, length: int, padding: str, applications: Any) -> Any:
        decoder = cls._decoder = compile_decoder(cls) or _no_decoder
        return decoder(value, length, padding, applications)

    return first


def _no_decoder(value: int, length: int, padding: str, applications: Any) -> None:
    """The decoder of a class compile_decoder does not compile: the generic reader reads it."""
    return None


def _where(message: Any) -> str:
    """Errors' address for a message: "AIS type 5"."""
    return f"AIS type {getattr(message, 'message_type')}"


def unarmor(payload: str, fill_bits: int) -> tuple[BitReader, str]:
    """The payload's message bits, and the values of its fill bits."""
    value, length, padding = _unarmor(payload, fill_bits)
    return BitReader(value, length, "AIS"), padding


_a2b_base64 = binascii.a2b_base64
_BASE64_PADS = (b"", b"AAA", b"AA", b"A")
"""What a payload of n characters takes to a whole number of base64 groups, by n % 4; the
bits they add (_BASE64_DROPS) are dropped."""
_BASE64_DROPS = (0, 18, 12, 6)
_PADDINGS = {bits_text(value, n): value for n in range(1, 6) for value in range(1 << n)}
"""The value of each text of 1-5 fill bits ('0' and '1')."""
_FILL_TEXTS = tuple(tuple(bits_text(low & ((1 << n) - 1), n) for low in range(32)) for n in range(6))
"""The fill bits' values of n fill bits as text, by the payload's last five bits."""


def _unarmor(payload: str, fill_bits: int) -> tuple[int, int, str]:
    """The payload's message bits as one integer, their count, and the values of its fill bits."""
    if not 0 <= fill_bits <= 5 or fill_bits and not payload:
        raise NmeaError("bad_armor", f"fill bits are 0-5 (none for an empty payload), not {fill_bits}", "AIS")
    try:
        pad = -len(payload) % 4  # base64 takes four characters at a time
        data = binascii.a2b_base64(payload.encode("ascii").translate(_ARMOR_TO_BASE64) + b"A" * pad, strict_mode=True)
        value = int.from_bytes(data, "big") >> 6 * pad
    except (UnicodeEncodeError, binascii.Error):  # a character no armor value stands for
        offset, ch = next((i, ch) for i, ch in enumerate(payload) if armor_value(ch) is None)
        raise NmeaError("bad_armor", f"character '{ch}' at offset {offset} is not six-bit armoring", "AIS") from None
    if fill_bits:
        return value >> fill_bits, len(payload) * 6 - fill_bits, format(value & ((1 << fill_bits) - 1), f"0{fill_bits}b")
    return value, len(payload) * 6, ""


def sentence_message(by_type: dict[int, type[Message]], applications: dict[tuple[int, int, int], type[Application]],
                     count: Any, payload: str | None, fill_bits: Any) -> Message | None:
    """The message of an encapsulation sentence (its fragment count, payload and fill bits, as
    read: Numbers), as decode gives it; None for one sentence of a message of several."""
    try:  # whole() in line for the usual texts ("1", a digit)
        fill = _DIGITS[fill_bits._text] if count._text == "1" and count.__class__ is Number \
            and fill_bits.__class__ is Number else -1
    except (AttributeError, KeyError):
        fill = -1
    if fill < 0 or not payload:
        if count is None or whole(count) != 1:
            return None
        fill = 0 if fill_bits is None else whole(fill_bits)
        return decode(by_type, applications, payload or "", fill)
    # decode's usual case in line (the fill bits 0-9, the payload's first character an armor one)
    size = len(payload)
    try:
        value = int.from_bytes(_a2b_base64(payload.encode("ascii").translate(_ARMOR_TO_BASE64)
                                           + _BASE64_PADS[size & 3], strict_mode=True), "big")
    except (ValueError, UnicodeEncodeError):
        value = -1
    length = size * 6 - fill
    if value < 0 or fill > 5 or length < 6:
        return decode(by_type, applications, payload, fill)  # raises, saying why
    value >>= _BASE64_DROPS[size & 3]
    padding = ""
    if fill:
        padding = _FILL_TEXTS[fill][value & 31]
        value >>= fill
    cls = by_type.get(value >> (length - 6))
    if cls is None:
        return decode(by_type, applications, payload, fill)
    message: Message | None = cls._decoder(value, length, padding, applications)
    if message is None:
        return decode(by_type, applications, payload, fill)  # short, or ended by an optional field
    return message


def _application(message: Message, applications: dict[tuple[int, int, int], type[Application]],
                 compiled: bool = True) -> Application | None:
    """What the message's data bits carry, when `applications` (by message type, DAC and FI) has
    one for them that reads them; its data member is then set to None. Data that the
    application does not read stays data. `compiled`: by the application's compiled decoder,
    when it reads the bits (else, and always when False, by the generic reader)."""
    data = message.DISPATCH
    bits = getattr(message, data.id) if data is not None else None
    if data is None or bits is None:
        return None
    first, second = data.dispatch  # the DAC's and the FI's members
    dac, fid = getattr(message, first), getattr(message, second)
    cls = applications.get((getattr(message, "message_type"), dac, fid))
    if cls is None:
        return None
    raw = int(bits, 2) if bits else 0
    try:
        application: Application | None = cls._decoder(raw, len(bits), "", None) if compiled else None
        if application is None:
            reader = BitReader(raw, len(bits), f"AIS DAC {dac} FI {fid}")
            application = cls(**cls.read(reader), trailing=bits[reader.pos:])
    except NmeaError:
        return None
    setattr(message, data.id, None)
    return application


def decode(by_type: dict[int, type[Message]], applications: dict[tuple[int, int, int], type[Application]],
           payload: str, fill_bits: int) -> Message:
    """The message of an armored payload, as the class its type number names in `by_type`, with
    the application of `applications` its data bits carry."""
    # _unarmor in line (the hot path): base64 takes whole groups of four characters
    size = len(payload)
    try:
        if not 0 <= fill_bits <= 5 or fill_bits and not size:
            raise ValueError
        value = int.from_bytes(_a2b_base64(payload.encode("ascii").translate(_ARMOR_TO_BASE64)
                                           + _BASE64_PADS[size & 3], strict_mode=True), "big")
    except (ValueError, UnicodeEncodeError):  # binascii.Error is a ValueError
        value = -1
    if value < 0:
        _unarmor(payload, fill_bits)  # raises bad_armor, saying why
    value >>= _BASE64_DROPS[size & 3]
    padding = ""
    if fill_bits:
        padding = _FILL_TEXTS[fill_bits][value & 31]
        value >>= fill_bits
    length = size * 6 - fill_bits
    if length < 6:
        BitReader(value, length, "AIS").peek(0, 6, "message_type")  # raises short_payload
    message_type = value >> (length - 6)
    cls = by_type.get(message_type)
    if cls is None:
        raise NmeaError("unknown_message", f"message type {message_type} is not one the spec describes",
                        f"AIS type {message_type}", name="message_type")
    message: Message | None = cls._decoder(value, length, padding, applications)
    if message is None:  # short, or ended by an optional field: the generic reader says how
        reader = BitReader(value, length, f"AIS type {message_type}")
        values = cls.read(reader)
        trailing = bits_text(reader.value & ((1 << reader.remaining) - 1), reader.remaining)
        message = cls(**values, trailing=trailing, padding=padding)
        if cls.DISPATCH is not None:  # (a compiled decoder finds it itself)
            message.application = _application(message, applications)
    return message
