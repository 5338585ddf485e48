"""The intermediate model: the spec as typed objects with every derived fact.

Emitters read only this model, never the YAML. Each node remembers where it came from
(`origin`: file and YAML path) so that the semantic checks can point at it.
"""

from __future__ import annotations

import hashlib
from dataclasses import dataclass, field
from typing import Any

from .field_types import BIT_TYPES, TYPES, BitType, FieldType
from .paths import ROOT

# The NMEA version a parser must assume for fields without `since`.
BASE_VERSION = "2.0"


@dataclass
class Origin:
    file: str
    path: tuple[str | int, ...]


@dataclass
class Manual:
    id: str
    title: str
    maker: str
    """Who makes the receivers the manual describes (`standard` for the NMEA standard)."""
    file: str | None = None
    url: str | None = None
    language: str | None = None
    note: str | None = None


@dataclass
class GenericMessage:
    """A proprietary message real receivers send that stays a generic sentence: no public document
    gives its layout (spec/manuals.yaml, `generic`)."""
    message: str
    maker: str
    example: str
    where: str
    why: str
    origin: Origin


@dataclass
class EnumValue:
    code: str
    id: str
    doc: str
    manuals: list[str]
    since: str | None
    origin: Origin
    cli: str | None = None       # the `nmea command` words that pick this value: "set-baud 115200"

    @property
    def const_name(self) -> str:
        return self.id.upper()


@dataclass
class EnumDef:
    id: str
    name: str
    doc: str
    values: list[EnumValue]
    origin: Origin
    closed: bool = False         # `codes: closed`: a code the spec does not list is refused, never kept

    # Derived: what an unknown code must look like to be kept rather than rejected.
    @property
    def digits(self) -> bool:
        return any(ch.isdigit() for v in self.values for ch in v.code)

    @property
    def letters(self) -> bool:
        return any(ch.isalpha() for v in self.values for ch in v.code)

    @property
    def min_len(self) -> int:
        return min(len(v.code) for v in self.values)

    @property
    def max_len(self) -> int:
        return max(len(v.code) for v in self.values)

    @property
    def code_class(self) -> str:
        """`digits`, `letters` or `alnum`: the characters an unknown code may use; `closed`: no
        unknown code is kept."""
        if self.closed:
            return "closed"
        if self.digits and not self.letters:
            return "digits"
        if self.letters and not self.digits:
            return "letters"
        return "alnum"

    def by_code(self, code: str) -> EnumValue | None:
        return next((v for v in self.values if v.code == code), None)

    def by_id(self, value_id: str) -> EnumValue | None:
        return next((v for v in self.values if v.id == value_id), None)

    @property
    def camel(self) -> str:
        return camel(self.id)


@dataclass
class Fact:
    """One fact of a fix (spec/fix.yaml) that sentence fields carry: `fix: <id>`."""

    id: str
    name: str
    doc: str
    types: list[str]
    origin: Origin
    scope: str = "epoch"         # or "satellite": a field of a repeated group's entries
    unit: str | None = None      # the unit the fix gives it in
    units: dict[str, float] = field(default_factory=dict)   # a field's unit -> factor to `unit`
    enums: list[str] = field(default_factory=list)          # enums whose value ids it keeps
    values: list[str] = field(default_factory=list)         # its own values, mapped `from` enums
    mapping: dict[str, dict[str, str]] = field(default_factory=dict)   # enum id -> value id -> value

    def scale(self, f: Field) -> float:
        """The factor from the unit of `f` to the fact's unit (1 for a fact without units)."""
        return self.units.get(f.unit, 1.0) if f.unit else 1.0

    def values_of(self, f: Field) -> dict[str, str] | None:
        """What each value id of the enum of `f` is as the fact's value; None when the fact keeps
        the ids (or the field is no enum)."""
        return self.mapping.get(f.enum.id) if f.enum is not None else None


@dataclass
class TagCode:
    """A parameter code of a TAG block (spec/tag_block.yaml): `code` as written before the ':',
    `type` one of integer, group, text."""

    code: str
    id: str
    name: str
    type: str
    doc: str
    origin: Origin


@dataclass
class FixExample:
    """A stream of lines and the fixes every assembler must make of them (spec/fix.yaml)."""

    where: str
    lines: list[str]
    expect: list[dict[str, Any]]
    origin: Origin


@dataclass
class FixField:
    """A field that carries a fact of the fix, in a layout: `group` is the repeated group whose
    entries hold it, or None."""

    field: Field
    fact: Fact
    group: Group | None

    @property
    def path(self) -> str:
        """The field's attribute path in a decoded sentence: `time`, `satellites.prn`."""
        return f"{self.group.id}.{self.field.id}" if self.group else self.field.id


@dataclass
class Field:
    id: str
    name: str
    type: str
    doc: str
    manuals: list[str]
    origin: Origin
    format: str | None = None
    unit: str | None = None
    min: float | None = None
    max: float | None = None
    max_length: int | None = None
    enum_id: str | None = None
    value: str | None = None
    since: str | None = None
    optional: bool = False
    bitfield_id: str | None = None
    fix_id: str | None = None    # the fact of a fix it carries (spec/fix.yaml)
    # Derived by resolve():
    enum: EnumDef | None = None
    bitfield: BitfieldDef | None = None
    fact: Fact | None = None
    wire_index: int = 0          # 1-based index of the first wire field, within its group entry for grouped fields
    group: Group | None = None

    @property
    def field_type(self) -> FieldType:
        return TYPES[self.type]

    @property
    def wire_width(self) -> int:
        return self.field_type.wire_width

    @property
    def is_optional(self) -> bool:
        return self.optional or self.since is not None

    @property
    def expected(self) -> str:
        """What a bad_field error says the field should hold (the value part of lat/lon)."""
        return self.field_type.expected(self)

    @property
    def camel(self) -> str:
        return camel(self.id)


@dataclass
class Group:
    id: str
    name: str
    doc: str
    min: int
    max: int
    fields: list[Field]
    origin: Origin
    wire_index: int = 0

    @property
    def width(self) -> int:
        return sum(f.wire_width for f in self.fields)

    @property
    def is_fixed(self) -> bool:
        return self.min == self.max

    @property
    def single(self) -> bool:
        """A group of one field is a plain list of values."""
        return len(self.fields) == 1

    @property
    def camel(self) -> str:
        return camel(self.id)


Item = Field | Group


@dataclass
class Outcome:
    """Whether a reply reports success: always `ok` or always `error` (`fixed`), or ok when the
    field `field_id` holds one of the values `ok` (expect form: enum value ids, numbers, texts)."""

    fixed: str | None = None
    field_id: str | None = None
    ok: list[Any] = field(default_factory=list)
    origin: Origin | None = None


@dataclass
class ReplyRule:
    """One entry of a command's `replies`: the reply sentence, and the values its fields must have
    for it to answer this command (an acknowledgement that names the command, e.g. PMTK001)."""

    sentence_id: str
    when: dict[str, Any]
    origin: Origin
    sentence: Sentence | None = None     # derived by resolve()


# The names the derived accessors of a layout take (a layout with a field of that name has none).
QUERY = "Q"
"""The standard query's formatter ($CCGPQ,GGA): its address is two talker IDs, the requester's and
the listener's, then Q; every runtime reads a standard address of 5 characters ending in Q whose
formatter the spec does not know as the query, its talker the first four."""

POSITION_NAMES = ("latitude", "longitude")
CALENDAR_NAMES = ("datetime",)
# The ids of the integer fields that carry a date in three parts (ZDA: day, month, four-digit year).
DATE_PART_IDS = ("day", "month", "year")


@dataclass(frozen=True)
class Position:
    """A layout's one latitude and one longitude field."""

    lat: Field
    lon: Field


@dataclass(frozen=True)
class Calendar:
    """A layout's UTC time field and its date: one `date` field, or `day`, `month` and `year`."""

    time: Field
    date: Field | None = None
    day: Field | None = None
    month: Field | None = None
    year: Field | None = None


@dataclass
class Layout:
    """One way the fields of a sentence are laid out on the wire."""

    id: str | None               # None for the main layout, else the variant id
    name: str
    doc: str
    items: list[Item]
    manuals: list[str]
    origin: Origin
    outcome: Outcome | None = None   # replies: whether this layout reports success

    @property
    def fields(self) -> list[Field]:
        """Top-level fields, in wire order (groups left out)."""
        return [i for i in self.items if isinstance(i, Field)]

    @property
    def group(self) -> Group | None:
        return next((i for i in self.items if isinstance(i, Group)), None)

    @property
    def all_fields(self) -> list[Field]:
        """Every field in wire order, a group's as in one entry."""
        out: list[Field] = []
        for item in self.items:
            out += item.fields if isinstance(item, Group) else [item]
        return out

    @property
    def required_items(self) -> list[Item]:
        return [i for i in self.items if not (isinstance(i, Field) and i.is_optional)]

    @property
    def optional_fields(self) -> list[Field]:
        return [i for i in self.items if isinstance(i, Field) and i.is_optional]

    @property
    def fixed_count(self) -> int:
        """Wire fields outside the group that are always present."""
        return sum(i.wire_width for i in self.required_items if isinstance(i, Field))

    @property
    def optional_count(self) -> int:
        return sum(f.wire_width for f in self.optional_fields)

    @property
    def selector(self) -> str | None:
        """The keyword that picks this layout: the first keyword among the fields every line of
        it has at a fixed place (RQUERY in $GPSGG,RQUERY,…; SAT in $PGLOR,2,SAT,…)."""
        found = self._selector()
        return found[1] if found else None

    @property
    def selector_at(self) -> int:
        """The wire index (0-based, after the address) of the selector; 0 when there is none."""
        found = self._selector()
        return found[0] if found else 0

    def _selector(self) -> tuple[int, str] | None:
        at = 0
        for item in self.items:
            if isinstance(item, Group) or item.is_optional:
                return None
            if item.field_type.keyword:
                return at, str(item.value)
            at += item.wire_width
        return None

    @property
    def fix_fields(self) -> list[FixField]:
        """The fields that carry facts of a fix, in wire order."""
        out: list[FixField] = []
        for item in self.items:
            for f in item.fields if isinstance(item, Group) else [item]:
                if f.fact is not None:
                    out.append(FixField(f, f.fact, item if isinstance(item, Group) else None))
        return out

    def wire_readings(self) -> list[tuple[Any, ...]] | None:
        """What each wire field takes (field_types' readings), in wire order, optional trailing
        fields included; None when a repeated group of variable length moves the fields after
        it from line to line."""
        g = self.group
        if g is not None and not g.is_fixed:
            return None
        out: list[tuple[Any, ...]] = []
        for item in self.items:
            for f in item.fields * item.max if isinstance(item, Group) else [item]:
                out += f.field_type.readings(f)
        return out

    @property
    def position(self) -> Position | None:
        """The layout's position, when its top-level fields hold exactly one latitude and one
        longitude: what the sentence-level `latitude` and `longitude` accessors read."""
        lats = [f for f in self.fields if f.type == "latitude"]
        lons = [f for f in self.fields if f.type == "longitude"]
        if len(lats) != 1 or len(lons) != 1 or self._taken(POSITION_NAMES):
            return None
        return Position(lats[0], lons[0])

    @property
    def calendar(self) -> Calendar | None:
        """The layout's UTC date and time, when its top-level fields hold exactly one time and
        one date: a `date` field (ddmmyy), or the integer fields `day`, `month` and a four-digit
        `year` (ZDA's form). What the sentence-level `datetime` accessors read."""
        times = [f for f in self.fields if f.type == "time"]
        dates = [f for f in self.fields if f.type == "date"]
        if len(times) != 1 or self._taken(CALENDAR_NAMES):
            return None
        if len(dates) == 1:
            return Calendar(times[0], date=dates[0])
        by_id = {f.id: f for f in self.fields if f.type == "integer"}
        day, month, year = (by_id.get(i) for i in DATE_PART_IDS)
        if dates or not (day and month and year) or year.format != "xxxx":
            return None
        return Calendar(times[0], day=day, month=month, year=year)

    def _taken(self, names: tuple[str, ...]) -> bool:
        """Whether a field already has one of the names a derived accessor would take."""
        return any(f.id in names for f in self.fields)

    @property
    def min_fields(self) -> int:
        g = self.group
        return self.fixed_count + (g.min * g.width if g else 0)

    @property
    def max_fields(self) -> int:
        g = self.group
        return self.fixed_count + self.optional_count + (g.max * g.width if g else 0)


@dataclass
class Example:
    manual: str
    where: str | None
    raw: str
    corrected: str | None
    reason: str | None
    unrecoverable: str | None
    variant: str | None
    expect: dict[str, Any] | None
    origin: Origin
    checksum_ok: bool = False

    @property
    def line(self) -> str | None:
        """The intact sentence: the correction when there is one (a checksum can be intact while the
        layout is damaged: XOR cannot see a moved comma or two added ones), else the manual's text."""
        if self.corrected:
            return self.corrected
        return self.raw if self.checksum_ok and not self.unrecoverable else None


@dataclass
class Note:
    manuals: list[str]
    text: str


# The standard sentences that get a fast path (see Sentence.fast_path): a receiver's per-fix output.
FAST_PATH_SENTENCES = frozenset({"GGA", "GLL", "GNS", "GSA", "GST", "GSV", "HDT", "RMC", "VTG", "ZDA"})


@dataclass
class Sentence:
    id: str
    name: str
    doc: str
    talkers: list[str]
    manuals: list[str]
    layout: Layout
    variants: list[Layout]
    notes: list[Note]
    examples: list[Example]
    origin: Origin
    source: str                  # spec file, relative to the repository
    extensions: list[str] = field(default_factory=list)   # overlays' extensions/ files that add to it
    address: str | None = None   # proprietary: the exact address (text framing: the command word)
    framing: str = "sentence"    # "sentence" ($…*hh) or "text" (space-separated words)
    start: str = "$"             # standard sentences: "$", or "!" for encapsulation (AIS VDM/VDO)
    domain: str | None = None    # standard sentences: what they are about, for the docs index
    kind: str = "standard"       # standard, command, reply or output
    vendor: str | None = None
    reply_rules: list[ReplyRule] = field(default_factory=list)
    replies: list[Sentence] = field(default_factory=list)   # derived by resolve(): each reply sentence once
    encapsulates: dict[str, str] | None = None   # the fields that carry a message of spec/ais: protocol, payload, ...
    like: str | None = None      # a standard sentence whose main layout this one takes (Unicore's GGAH: GGA)
    like_source: str | None = None   # that sentence's spec file

    @property
    def files(self) -> list[str]:
        """The spec files the sentence is made from: its own, the extensions laid over it, and
        the file of the sentence whose fields it takes (`like`)."""
        return [self.source, *self.extensions, *([self.like_source] if self.like_source else [])]

    @property
    def reply_ids(self) -> list[str]:
        """The ids of the sentences that answer this command, each once, in spec order."""
        return list(dict.fromkeys(r.sentence_id for r in self.reply_rules))

    @property
    def is_proprietary(self) -> bool:
        return self.address is not None

    @property
    def talker_length(self) -> int:
        """The characters of a standard sentence's talker, its address but the formatter: 2, or 4
        for the query (the requester's and the listener's talker IDs)."""
        return 4 if self.id == QUERY else 2

    @property
    def fast_path(self) -> bool:
        """Whether C and Rust give the sentence a fast reader and writer besides the general
        ones: the standard sentences a GNSS receiver sends with every fix, and the proprietary
        outputs; the others (instruments, alarms, AIS, commands and their replies, ...) take the
        general path, which keeps the code small as the spec grows."""
        return self.id in FAST_PATH_SENTENCES or (self.is_proprietary and self.kind == "output")

    @property
    def wire_kind(self) -> str:
        """How its lines are framed: "standard" ($ or ! + talker + sentence id), "proprietary"
        ($ + its fixed address) or "text" (a command of words separated by spaces)."""
        if not self.is_proprietary:
            return "standard"
        return "text" if self.framing == "text" else "proprietary"

    def example_of(self, layout: Layout) -> Example | None:
        """The manual example every language's docs show for a layout: of its examples with a
        line, the one with the most fields filled in (the first of those)."""
        examples = [ex for ex in self.examples if ex.line and ex.variant == layout.id]
        return max(examples, key=lambda ex: sum(1 for t in (ex.line or "").split("*")[0].split(",") if t),
                   default=None)

    @property
    def layouts(self) -> list[Layout]:
        return [self.layout, *self.variants]

    def same_as_main(self, variant: Layout) -> list[int]:
        """The wire fields (1-based) that `variant` reads as the main layout does. A line the main
        layout refuses for one of them is not one the variant exists for, so the variant is not
        tried on it; a line refused for its field count, or for a field the variant reads
        otherwise, is. (None when no line has a field count both layouts take.)"""
        main, other = self.layout.wire_readings(), variant.wire_readings()
        if main is None or other is None or variant.max_fields < self.layout.min_fields \
                or variant.min_fields > self.layout.max_fields:
            return []
        return [i for i, (a, b) in enumerate(zip(main, other), 1) if a == b]

    @property
    def camel(self) -> str:
        return camel(self.id.lower())

    def layout_camel(self, layout: Layout) -> str:
        return self.camel + (camel(layout.id) if layout.id else "")

    def layout_snake(self, layout: Layout) -> str:
        return self.id.lower() + (f"_{layout.id}" if layout.id else "")

    def command_name(self, layout: Layout) -> str:
        """The name `nmea command VENDOR NAME` knows a command layout by: its id without the vendor
        prefix, then the variant, in kebab case (geos5_nquery_request -> nquery-request)."""
        name = self.id.lower().removeprefix(f"{self.vendor}_") + (f"_{layout.id}" if layout.id else "")
        return name.replace("_", "-")


@dataclass
class BitValue:
    value: int
    id: str
    doc: str


@dataclass
class Bits:
    high: int
    low: int
    id: str
    doc: str
    values: list[BitValue]
    origin: Origin

    @property
    def width(self) -> int:
        return self.high - self.low + 1

    @property
    def max_value(self) -> int:
        return (1 << self.width) - 1

    @property
    def mask(self) -> int:
        return self.max_value << self.low

    @property
    def label(self) -> str:
        return str(self.high) if self.high == self.low else f"{self.high}:{self.low}"


@dataclass
class BitfieldDef:
    id: str
    name: str
    doc: str
    width: int
    manuals: list[str]
    bits: list[Bits]
    origin: Origin

    @property
    def camel(self) -> str:
        return camel(self.id)


@dataclass
class Parameter:
    number: int
    id: str
    name: str
    doc: str
    encoding: str
    origin: Origin
    size: int | None = None
    count: int | None = None
    min: float | None = None
    max: float | None = None
    max_length: int | None = None
    default: str | None = None
    unit: str | None = None
    enum_id: str | None = None
    bitfield_id: str | None = None
    takes_effect: str | None = None
    enum: EnumDef | None = None
    bitfield: BitfieldDef | None = None


@dataclass
class TableDef:
    id: str
    name: str
    doc: str
    manuals: list[str]
    parameters: list[Parameter]
    origin: Origin

    @property
    def camel(self) -> str:
        return camel(self.id)


@dataclass
class Special:
    """A raw value of a bit field that is no number: `not_available`, `manual_input`, ... Of a float
    field (r4, r8), the spec writes the float (`value`) and `raw` is the bit pattern, in the field's
    own width, of the float of that width nearest to it (field_types.float_bits): what the
    runtimes compare (SBF's -2e10: 0xD09502F9 as an r4, 0xC212A05F20000000 as an r8)."""
    raw: int
    id: str
    doc: str
    value: float | None = None   # a float field's special value as the spec writes it

    @property
    def shown(self) -> str:
        """The special value in docs: its raw integer, or a float's value (-2e+10)."""
        return str(self.raw) if self.value is None else f"{self.value:g}"


@dataclass(frozen=True)
class Ones:
    """A count given by mask fields: the product of the numbers of bits set in each (RTCM 3 MSM:
    satellites x signals)."""
    fields: tuple[str, ...]


Count = str | int | Ones   # a field's value (its id), a number, or the bits set in mask fields


@dataclass
class PayloadField:
    """One field of a bit-packed payload, most significant bit first."""
    id: str
    name: str
    type: str
    bits: int | None             # None: the bits left (a text: the whole characters left)
    doc: str
    origin: Origin
    unit: str | None = None
    divisor: int | None = None   # the value in `unit` is the raw integer divided by it, plus `base`
    base: float | None = None    # the value of raw 0
    enum_id: str | None = None
    optional: bool = False       # present when the payload has its bits
    special: list[Special] = field(default_factory=list)
    dispatch: list[str] = field(default_factory=list)   # data: the fields that will pick an application layout
    parts: list[PayloadField] = field(default_factory=list)   # a bitfield word's named bit ranges
    low: int = 0                 # a part: its lowest bit in the word (bit 0: the least significant)
    count: str | Ones | None = None   # a counted width: as many characters (bits for data) as this says
    ref: str | None = None       # its name in the protocol's documents (RTCM 3: DF025)
    byte_order: str = "little"   # a binary frame's field: its protocol's (derived)
    # Derived by resolve():
    enum: EnumDef | None = None
    offset: int | None = None    # the first bit, when no variable item comes before it

    @property
    def bit_type(self) -> BitType:
        return BIT_TYPES[self.type]

    @property
    def width(self) -> int | None:
        return self.bits

    @property
    def scaled(self) -> bool:
        """A number that has a value in a unit besides its raw integer (a divisor or special values);
        a float's special values are its own value's bit patterns, no raw integer beside it."""
        return self.divisor is not None or self.base is not None or bool(self.special) and self.type not in ("r4", "r8")

    @property
    def camel(self) -> str:
        return camel(self.id)


@dataclass
class PayloadGroup:
    """Entries repeated while the payload has bits for them (up to `max`), as many as the field
    `count` (read before the group) says, or (`count` a number) that many."""
    id: str
    name: str
    doc: str
    min: int
    max: int
    items: list[PayloadField | PayloadChoice | PayloadGroup]   # an entry's fields, choices by a field of the
                                 # entry, and last a nested group (SBF's Type-2 sub-blocks: rule B010)
    origin: Origin
    count: Count | None = None
    offset: int | None = None
    field_major: bool = False    # the entries' first fields, then their second fields, ... (RTCM 3 MSM)
    stride: str | None = None    # the field that holds each entry's bytes (SBF's SBLength): the fields are
                                 # read from each entry's start, the bytes after them are its last field,
                                 # `trailing` (bytes, as sent: a newer firmware's additions)

    @property
    def fields(self) -> list[PayloadField]:
        """An entry's fields, those of every case of its choices included, in order (not those
        of its nested group's entries)."""
        return flat_fields([i for i in self.items if not isinstance(i, PayloadGroup)])

    @property
    def nested(self) -> PayloadGroup | None:
        """The group each entry ends with (SBF's Type-2 sub-blocks after a Type-1): counted by a
        field of the entry, strided by a field of the message; None for most."""
        return next((i for i in self.items if isinstance(i, PayloadGroup)), None)

    @property
    def all_fields(self) -> list[PayloadField]:
        """An entry's fields, then its nested group's."""
        nested = self.nested
        return self.fields + (nested.all_fields if nested is not None else [])

    @property
    def choices(self) -> list[PayloadChoice]:
        """The choices of an entry (each by a field of the entry before it)."""
        return [i for i in self.items if isinstance(i, PayloadChoice)]

    @property
    def entry_width(self) -> int:
        """An entry's bits: its fields' (a choice's: those of its first case; rule A013 makes every
        case as wide; a stride's entry: the least it takes, its trailing bytes left out)."""
        return sum((i.bits or 0) if isinstance(i, PayloadField) else (i.cases[0].width or 0) for i in self.items
                   if not isinstance(i, PayloadGroup))

    @property
    def width(self) -> int | None:
        return self.entry_width * self.count if isinstance(self.count, int) and self.stride is None \
            and self.nested is None else None

    @property
    def camel(self) -> str:
        return camel(self.id)


@dataclass
class PayloadCase:
    """One layout of a choice: taken when the selector's raw value is one of `values`, within
    `range`, or (neither given) when no other case holds. Its items are fields and choices."""
    values: list[int]
    range: tuple[int, int] | None
    items: list[PayloadField | PayloadChoice]

    @property
    def is_default(self) -> bool:
        return not self.values and self.range is None

    @property
    def fields(self) -> list[PayloadField]:
        return flat_fields(self.items)

    @property
    def width(self) -> int | None:
        return items_width(self.items)

    def holds(self, raw: int) -> bool:
        return raw in self.values or (self.range is not None and self.range[0] <= raw <= self.range[1])


@dataclass
class PayloadChoice:
    """Bits laid out one of several ways, picked by the raw value of another field."""
    id: str
    by: str
    doc: str
    cases: list[PayloadCase]
    origin: Origin
    # Derived by resolve():
    selector: PayloadField | None = None
    offset: int | None = None

    @property
    def width(self) -> int | None:
        """The width every case has, or None when they differ."""
        widths = {c.width for c in self.cases}
        return widths.pop() if len(widths) == 1 else None

    @property
    def fields(self) -> list[PayloadField]:
        return [f for case in self.cases for f in case.fields]


PayloadItem = PayloadField | PayloadGroup | PayloadChoice


def flat_fields(items: list[PayloadItem] | list[PayloadField | PayloadChoice]) -> list[PayloadField]:
    """Every field of `items`, those of groups and of every case of choices included, in order."""
    out: list[PayloadField] = []
    for item in items:
        out += [item] if isinstance(item, PayloadField) else item.all_fields if isinstance(item, PayloadGroup) \
            else item.fields
    return out


def items_width(items: list[PayloadItem] | list[PayloadField | PayloadChoice]) -> int | None:
    """The sum of the widths when every item is fixed and none optional; else None."""
    total = 0
    for item in items:
        if item.width is None or isinstance(item, PayloadField) and item.optional:
            return None
        total += item.width
    return total


@dataclass
class PayloadExample:
    manual: str
    where: str
    payload: str
    fill_bits: int
    expect: dict[str, Any] | None
    origin: Origin


@dataclass
class Route:
    """One way an application message is sent: the DACs and FI its carriers' data carry it under,
    and those message types (a layout several DAC/FIs share has one route each)."""
    dacs: list[int]
    fid: int
    carriers: list[int]

    @property
    def keys(self) -> list[tuple[int, int]]:
        """Its (DAC, FI) pairs."""
        return [(dac, self.fid) for dac in self.dacs]

    @property
    def text(self) -> str:
        """As the docs name it: "DAC 235 or 250 FI 10"."""
        return f"DAC {' or '.join(map(str, self.dacs))} FI {self.fid}"


@dataclass
class Payload:
    """One bit-packed message layout (spec/ais/messages): the message types it describes and its
    fields."""
    id: str
    name: str
    doc: str
    types: list[int]
    manuals: list[str]
    length: int | None           # the documented length of a fixed layout
    items: list[PayloadItem]
    notes: list[Note]
    examples: list[PayloadExample]
    origin: Origin
    protocol: str = "ais"
    application: tuple[int, int] | None = None   # an application message: its (first) DAC and FI
    routes: list[Route] = field(default_factory=list)   # ... every DAC, FI and message type it is sent under
    applications: list[Payload] = field(default_factory=list)   # derived: a message's applications
    directions: list[str] = field(default_factory=list)   # a binary layout: poll, input, output
    select: tuple[str, int] | None = None   # a binary layout told apart by a u1 field's value: (field id, value)
    replies: list[str] = field(default_factory=list)   # the layouts that answer this one (ids)
    acknowledges: tuple[str, str] | None = None   # an acknowledgement: its fields of the answered class and id
    frame: BinaryMessage | None = None   # a binary layout: its message (class and id)
    frame_examples: list[BinaryExample] = field(default_factory=list)   # a bit message's (RTCM 3): whole frames

    @property
    def select_field(self) -> PayloadField | None:
        """The field whose value picks this layout among those of its message (`select`)."""
        return None if self.select is None else next((f for f in self.items if isinstance(f, PayloadField)
                                                      and f.id == self.select[0]), None)

    @property
    def select_at(self) -> int | None:
        """The byte of the selecting field (None: no selector, or one not at a fixed offset)."""
        f = self.select_field
        return None if f is None or f.offset is None else f.offset // 8

    @property
    def keys(self) -> list[tuple[int, int]]:
        """An application's (DAC, FI) pairs: one per DAC and FI it is sent under."""
        return [key for route in self.routes for key in route.keys]

    @property
    def carriers(self) -> list[int]:
        """The message types whose data carry an application, under one of its DAC/FIs or another."""
        return sorted({t for route in self.routes for t in route.carriers})

    def carriers_of(self, key: tuple[int, int]) -> list[int]:
        """The message types whose data carry an application under a (DAC, FI) of it."""
        return next((route.carriers for route in self.routes if key in route.keys), [])

    @property
    def routes_text(self) -> str:
        """An application's DAC/FIs as the docs name them: "DAC 235 or 250 FI 10", "DAC 1 FI 22 or
        DAC 1 FI 23"."""
        return " or ".join(route.text for route in self.routes)

    @property
    def data_field(self) -> PayloadField | None:
        """The field whose bits an application layout may describe (its `dispatch`)."""
        return next((f for f in self.fields if f.dispatch), None)

    @property
    def fields(self) -> list[PayloadField]:
        """Every field, those of the groups and of every case included, in order."""
        return flat_fields(self.items)

    @property
    def fixed_width(self) -> int | None:
        return items_width(self.items)

    @property
    def camel(self) -> str:
        return camel(self.id)


@dataclass
class BinaryProtocol:
    """A binary protocol's framing (spec/binary/<protocol>/protocol.yaml): its documents and the
    classes its message ids are grouped in."""
    id: str
    name: str
    documents: dict[str, str]   # id -> title
    classes: dict[str, int]     # name (nav) -> class number
    origin: Origin
    frame: dict[str, Any] = field(default_factory=dict)       # the `frame:` of protocol.yaml
    identity: list[dict[str, Any]] = field(default_factory=list)  # the payload's first fields that tell its message

    @property
    def byte_order(self) -> str:
        """Of its fields: "little" (UBX, CASIC) or "big" (SkyTraq, SiRF)."""
        return str(self.frame.get("byte_order", "little"))


@dataclass
class BinaryExample:
    """A whole frame of the message (from a receiver's log) and values it decodes to."""
    where: str
    frame: bytes
    expect: dict[str, Any] | None
    origin: Origin


@dataclass
class BinaryMessage:
    """One message of a binary protocol (a UBX class and id) and its layouts: one per direction,
    or several of one direction told apart by length or by a selector (a type, command or version
    byte: Payload.select)."""
    id: str                     # nav_pvt
    name: str
    doc: str
    protocol: str
    msg_class: str              # nav
    msg_id: int
    documents: list[str]
    layouts: list[Payload]
    origin: Origin
    examples: list[BinaryExample] = field(default_factory=list)
    class_number: int = 0       # derived from the protocol's classes
    sub_id: int | None = None   # a protocol without classes: the byte after the id (SkyTraq sub-id, SiRF SID)
    revision: int | None = None  # SBF: the block's revision, told with its number in the header's id
    byte_order: str = "little"  # derived from the protocol's frame
    header_key: bool = True     # derived: the key is in the frame's header (not the payload's first bytes)

    @property
    def address(self) -> str:
        """How documents and errors name it after the protocol: NAV-PVT (UBX, CASIC: class and
        name), 0xA8 or 0x64 0x80 (SkyTraq: id and sub-id), MID 2 or MID 93 SID 18 (SiRF), 4007 rev 2
        (SBF: block number and revision)."""
        if self.msg_class:
            return self.id.upper().replace("_", "-", 1)
        if self.revision is not None:
            return f"{self.msg_id} rev {self.revision}"
        if self.protocol == "unicore":   # its binary log's name: VERSIONB, BESTNAVB
            return self.id.upper().replace("_", "")
        if self.protocol == "sirf":
            return f"MID {self.msg_id}" + (f" SID {self.sub_id}" if self.sub_id is not None else "")
        return f"0x{self.msg_id:02X}" + (f" 0x{self.sub_id:02X}" if self.sub_id is not None else "")

    @property
    def key(self) -> tuple[int, ...]:
        """What tells it in a frame: class and id, block number and revision (SBF), or id (and sub-id)."""
        if self.msg_class:
            return (self.class_number, self.msg_id)
        if self.revision is not None:
            return (self.msg_id, self.revision)
        return (self.msg_id,) if self.sub_id is None else (self.msg_id, self.sub_id)

    @property
    def prefix(self) -> int:
        """The bytes of `key` that open the payload (SkyTraq, SiRF: id and sub-id); UBX and CASIC
        carry theirs in the header, SBF its block number and revision."""
        return 0 if self.msg_class or self.header_key else len(self.key)


# The bytes of a configuration value by the size code of its key id (bits 28-30): 1 a bit (in a
# byte), 2 one byte, 3 two, 4 four, 5 eight (u-blox UBX-18010854, "Configuration interface").
CONFIG_SIZES = {1: 1, 2: 1, 3: 2, 4: 4, 5: 8}
# The size code of each configuration value type.
CONFIG_TYPE_SIZE = {"L": 1, "U1": 2, "I1": 2, "X1": 2, "E1": 2, "U2": 3, "I2": 3, "X2": 3, "E2": 3,
                    "U4": 4, "I4": 4, "X4": 4, "E4": 4, "R4": 4, "U8": 5, "I8": 5, "X8": 5, "R8": 5}


@dataclass
class ConfigEnum:
    """Named values of configuration keys of an enumeration type (E1, E2, E4)."""
    id: str
    doc: str
    values: dict[str, int]
    origin: Origin


@dataclass
class ConfigKey:
    """One key of a configuration database: CFG-RATE-MEAS, its 32-bit id, its value's type and
    the scale and unit of the number it holds."""
    group: str                  # RATE
    item: str                   # MEAS
    id: int
    type: str                   # L, U1 .. U8, I1 .. I8, X1 .. X8, E1 .. E4, R4, R8
    origin: Origin
    group_id: int = 0           # the group's id (bits 16-23 of `id`, checked)
    scale: float | None = None
    unit: str | None = None
    enum_id: str | None = None
    aliases: list[str] = field(default_factory=list)
    doc: str = ""
    documents: list[str] = field(default_factory=list)   # the group's
    enum: ConfigEnum | None = None   # resolved

    @property
    def name(self) -> str:
        """How u-blox names it: CFG-RATE-MEAS."""
        return f"CFG-{self.group}-{self.item}"

    @property
    def divisor(self) -> int:
        """The raw integer divided by it is the value in `unit` (1/scale, a whole number)."""
        return 1 if self.scale is None else round(1 / self.scale)


@dataclass
class ConfigGroup:
    id: int
    name: str                   # RATE
    title: str
    documents: list[str]
    keys: list[ConfigKey]
    origin: Origin


@dataclass
class ConfigDatabase:
    """spec/binary/<protocol>/config_keys.yaml: the keys of a receiver's configuration database."""
    protocol: str
    library: str
    not_found: str
    enums: dict[str, ConfigEnum]
    groups: list[ConfigGroup]
    origin: Origin

    @property
    def keys(self) -> list[ConfigKey]:
        return [k for g in self.groups for k in g.keys]


@dataclass
class Spec:
    manuals: list[Manual]
    enums: list[EnumDef]
    sentences: list[Sentence]
    sources: list[str]
    digest: str
    file_digests: dict[str, str] = field(default_factory=dict)
    bitfields: list[BitfieldDef] = field(default_factory=list)
    tables: list[TableDef] = field(default_factory=list)
    generic: list[GenericMessage] = field(default_factory=list)
    facts: list[Fact] = field(default_factory=list)
    fix_sources: list[str] = field(default_factory=list)   # the fix.yaml files loaded
    fix_examples: list[FixExample] = field(default_factory=list)
    talker_systems: dict[str, str] = field(default_factory=dict)   # spec/fix.yaml: talker -> GNSS
    combined_talker: str | None = None   # spec/fix.yaml: the talker of a solution of several systems
    satellite_ids: list[tuple[str, int, int]] = field(default_factory=list)  # (GNSS, first id, last id)
    tag_codes: list[TagCode] = field(default_factory=list)   # spec/tag_block.yaml
    tag_manuals: list[str] = field(default_factory=list)
    tag_examples: list[tuple[str, str]] = field(default_factory=list)   # (where, line)
    tag_sources: list[str] = field(default_factory=list)     # the tag_block.yaml files loaded
    enum_by_id: dict[str, EnumDef] = field(default_factory=dict)
    payloads: list[Payload] = field(default_factory=list)   # spec/ais/messages
    applications: list[Payload] = field(default_factory=list)   # spec/ais/applications
    protocols: list[BinaryProtocol] = field(default_factory=list)   # spec/binary/*/protocol.yaml
    binary: list[BinaryMessage] = field(default_factory=list)      # spec/binary/*/messages
    config_keys: list[ConfigDatabase] = field(default_factory=list)  # spec/binary/*/config_keys.yaml
    bit_messages: list[Payload] = field(default_factory=list)  # spec/binary/<protocol>/messages of bit layouts (RTCM 3)

    def digest_of(self, sources: list[str]) -> str:
        """A short hash of the given spec or template files, so that a generated file's header
        changes only when what it is made from changes."""
        h = hashlib.sha256()
        for source in sources:
            known = self.file_digests.get(source)
            if known is None:
                path = ROOT / source
                known = hashlib.sha256(path.read_bytes()).hexdigest() if path.is_file() else source
            h.update(source.encode() + b"\0" + known.encode())
        return h.hexdigest()[:16]

    def manual(self, manual_id: str) -> Manual | None:
        return next((m for m in self.manuals if m.id == manual_id), None)

    @property
    def fix_layouts(self) -> list[tuple[Sentence, Layout]]:
        """The layouts with fields that carry facts of a fix, in spec order."""
        return [(s, layout) for s in self.sentences for layout in s.layouts if layout.fix_fields]

    def sentence(self, sentence_id: str) -> Sentence | None:
        return next((s for s in self.sentences if s.id == sentence_id), None)

    @property
    def standard(self) -> list[Sentence]:
        return [s for s in self.sentences if not s.is_proprietary]

    @property
    def proprietary(self) -> list[Sentence]:
        return [s for s in self.sentences if s.is_proprietary]

    def by_address(self, address: str) -> list[tuple[Sentence, Layout]]:
        """The layouts of the proprietary `$` sentences with this exact address, in parse order."""
        return self._addresses().get(address, [])

    def _addresses(self) -> dict[str, list[tuple[Sentence, Layout]]]:
        """by_address for every address at once (the reference decoder asks once per example),
        built again when the list of sentences is another or has grown (an overlay, a test)."""
        cached = self.__dict__.get("_address_index")
        if cached is None or cached[0] is not self.sentences or cached[1] != len(self.sentences):
            owners: dict[str, list[Sentence]] = {}
            for s in self.sentences:
                if s.address is not None and s.framing == "sentence":
                    owners.setdefault(s.address, []).append(s)
            cached = (self.sentences, len(self.sentences), {a: _parse_order(found) for a, found in owners.items()})
            self.__dict__["_address_index"] = cached
        return cached[2]

    def text_command(self, word: str) -> list[tuple[Sentence, Layout]]:
        """The layouts of the text commands whose command word is `word` (ignoring case), in parse order."""
        upper = word.upper()
        return _parse_order([s for s in self.sentences
                             if s.framing == "text" and s.address and s.address.upper() == upper])


def _parse_order(sentences: list[Sentence]) -> list[tuple[Sentence, Layout]]:
    """Layouts that start with a keyword first (they are the specific ones), then the others,
    each in file order."""
    pairs = [(s, layout) for s in sentences for layout in s.layouts]
    return [p for p in pairs if p[1].selector is not None] + [p for p in pairs if p[1].selector is None]


def camel(snake: str) -> str:
    return "".join(part[:1].upper() + part[1:] for part in snake.split("_"))

