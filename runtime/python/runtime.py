"""Hand-written runtime of the generated NMEA 0183 codecs: framing, checksum, field types, errors.

Every sentence module generated from the spec is a thin layer over these helpers. The rules here
(what text each field type accepts, the error messages, the JSON form) are shared with the C and
Rust runtimes byte for byte; see docs/json.md.
"""

from __future__ import annotations

import datetime as dt
from dataclasses import dataclass
from decimal import Decimal
from enum import Enum
from collections.abc import Iterable
from typing import Any, Callable, ClassVar, Final, NamedTuple, TypeVar

MAX_LINE: Final = 1024
"""Longest line (without its line ending) the parser accepts."""

MAX_PROBLEMS: Final = 8
"""Most problems one sentence may have, fields kept outside their range and fields lenient
parsing leaves empty together (as many as C and Rust keep)."""

MAX_DIGITS: Final = 18
"""Most digits a number may have, so that every runtime holds it in a signed 64-bit integer."""

_HEX_DIGITS: Final = frozenset("0123456789abcdefABCDEF")


class NmeaError(ValueError):
    """A line that is not a valid sentence, or a sentence that does not fit its layout."""

    def __init__(
        self,
        kind: str,
        message: str,
        address: str | None = None,
        field: int | None = None,
        name: str | None = None,
        text: str | None = None,
        out_of_range: bool = False,
    ) -> None:
        super().__init__(message)
        self.kind = kind
        self.message = message
        self.address = address
        self.field = field
        self.name = name
        self.text = text  # bad_field: the field's text as received
        # bad_field: a number outside its field's range, which parsing keeps unless it is strict
        self.out_of_range = out_of_range

    @property
    def problem_kind(self) -> str:
        """As a problem of a decoded sentence: "out_of_range" (the value is kept as sent) or
        "left_empty" (lenient parsing read the field as empty)."""
        return "out_of_range" if self.out_of_range else "left_empty"

    def __str__(self) -> str:
        where = self.address or "line"
        if self.field is not None:
            where += f" field {self.field} ({self.name})"
        return f"{self.kind}: {where}: {self.message}"

    def to_json(self) -> str:
        return f'{{"ok":false,"error":{self.error_json()}}}'

    def error_json(self) -> str:
        """The error object of to_json (also an AIS message's `ais_error`)."""
        return (
            f'{{"kind":{json_str(self.kind)},"address":{json_opt(self.address)},'
            f'"field":{"null" if self.field is None else self.field},"name":{json_opt(self.name)},'
            f'"message":{json_str(self.message)}}}'
        )


class _Absent:
    """Marks an optional trailing field that was not on the wire (not even a comma)."""

    _instance: _Absent | None = None

    def __new__(cls) -> _Absent:
        if cls._instance is None:
            cls._instance = super().__new__(cls)
        return cls._instance

    def __repr__(self) -> str:
        return "ABSENT"

    def __bool__(self) -> bool:
        return False

    def text(self) -> str:
        return ""


ABSENT: Final = _Absent()


# ---------------------------------------------------------------------------------------------
# Framing


@dataclass(slots=True)
class Frame:
    """A line split into its parts; the checksum, if any, has been verified."""

    start: str
    address: str
    fields: list[str]
    checksum: str | None


def checksum(body: str) -> int:
    """XOR of every byte between the start character and the '*': the bytes read as one integer
    and folded onto themselves in halves, far fewer Python steps than a loop over the bytes."""
    value = int.from_bytes(body.encode("latin-1"), "little")
    if len(body) > 128:  # folded to 128 bytes first
        shift = 8 << (len(body) - 1).bit_length()  # the smallest power-of-two width that holds it
        while shift > 1024:
            shift >>= 1
            value ^= value >> shift
    # then in line, no loop: a sentence is rarely longer
    if len(body) > 64:
        value ^= value >> 512
    value ^= value >> 256
    value ^= value >> 128
    value ^= value >> 64
    value ^= value >> 32
    value ^= value >> 16
    value ^= value >> 8
    return value & 0xFF


def frame(line: str, require_checksum: bool = False, strict: bool = False) -> Frame:
    """Split one line (without its line ending) into a Frame; with `require_checksum`, a sentence
    without a checksum (or with a bare '*') is refused. A checksum of one hex digit that equals
    the sum (some instruments send `*b` for `*0b`) is kept as sent, unless `strict`."""
    if len(line) > MAX_LINE:
        raise NmeaError("too_long", f"line is {len(line)} bytes, the limit is {MAX_LINE}")
    if not line:
        raise NmeaError("not_a_sentence", "empty line")
    start = line[0]
    if start != "$" and start != "!":
        raise NmeaError("not_a_sentence", "line does not start with '$' or '!'")
    check_printable(line)
    star = line.find("*")
    body = line[1:] if star < 0 else line[1:star]
    parts = body.split(",")
    address = parts[0]
    named = address if address.isalnum() else None
    sent = None
    if star >= 0:
        sent = line[star + 1 :]
        # A bare '*' leaves the checksum out, as ST's manual writes its commands.
        if sent:
            if len(sent) == 1 and not strict and sent in _HEX_DIGITS and int(sent, 16) == checksum(body):
                pass  # one digit that is the checksum: kept as sent (short_checksum)
            elif (
                len(sent) != 2
                or sent[0] not in _HEX_DIGITS
                or sent[1] not in _HEX_DIGITS
                or (sent != sent.upper() and sent != sent.lower())
            ):
                raise bad_checksum(sent, named)
            computed = checksum(body)
            if int(sent, 16) != computed:
                raise NmeaError(
                    "checksum_mismatch", f"checksum is {sent}, computed {computed:02X}", named
                )
    if named is None:
        raise NmeaError("not_a_sentence", f"address {json_str(address)} is not letters and digits")
    if require_checksum and not sent:
        raise NmeaError("missing_checksum", "the sentence has no checksum", named)
    return Frame(start, address, parts[1:], sent)


def bad_checksum(sent: str, address: str | None) -> NmeaError:
    """The error of a checksum that is not two hex digits of one letter case (strict parsing's of
    a one-digit checksum, which is otherwise kept)."""
    return NmeaError(
        "bad_checksum", f"checksum {json_str(sent)} is not two hex digits of one letter case", address
    )


def short_checksum_json(sent: str | None) -> str:
    """The tools' JSON problem of a checksum written as one hex digit (`sent`; none: ""), which
    strict parsing refuses as bad_checksum, as the start of a `problems` array's items."""
    if sent is None or len(sent) != 1:
        return ""
    return (
        f'{{"kind":"short_checksum","field":null,"name":null,"text":{json_str(sent)},'
        f'"message":{json_str(bad_checksum(sent, None).message)}}}'
    )


def check_printable(line: str) -> None:
    """Refuse a line with a byte outside printable ASCII, naming the first."""
    if not line.isascii() or not line.isprintable():
        for offset, ch in enumerate(line):
            if not " " <= ch <= "~":
                raise NmeaError(
                    "not_a_sentence",
                    f"byte 0x{ord(ch):02x} at offset {offset} is not printable ASCII",
                )


def text_frame(line: str) -> Frame:
    """Split a text command (ComNav: words separated by single spaces, no '$', no checksum)."""
    if len(line) > MAX_LINE:
        raise NmeaError("too_long", f"line is {len(line)} bytes, the limit is {MAX_LINE}")
    check_printable(line)
    words = line.split(" ")
    return Frame("", words[0], words[1:], None)


def first_word(line: str) -> str:
    """The command word of a possible text command: the text before the first space."""
    return line.split(" ", 1)[0]


def checked_bytes(line: str, parse: Any, text: bool) -> bytes:
    """`line` plus CR LF, after reading it back with `parse` so that a bad field is refused
    before anything is sent."""
    frame = text_frame(line) if text else globals()["frame"](line)
    parse(frame.address, frame.fields, checksum_case(frame.checksum), line)
    return (line + "\r\n").encode("ascii")


def words_json(ids: tuple[str, ...], line: str) -> str:
    """The lossless `fields` object of a text command: each word as written."""
    words = line.split(" ")[1:]
    return "{" + ",".join(f'"{i}":{json_str(w) if w else "null"}' for i, w in zip(ids, words)) + "}"


def is_standard_address(start: str, address: str) -> bool:
    """A talker ID and a sentence formatter: `$` (or `!`, an encapsulation sentence such as AIS
    VDM), 5 characters (6 for a receiver's 4-character formatter, Unicore's GGAH), not
    proprietary (`P…`)."""
    return start in ("$", "!") and (len(address) == 5 or len(address) == 6) and address[0] != "P"


QUERY: Final = "Q"
"""The standard query's formatter ($CCGPQ,GGA: CC asks GP for GGA)."""


def is_query_address(start: str, address: str) -> bool:
    """A standard query: `$`, two talker IDs (the requester's and the listener's) and `Q`, not
    proprietary; read as one when the last three characters are no formatter the spec knows."""
    return start == "$" and len(address) == 5 and address[4] == QUERY and address[0] != "P"


def assemble(start: str, address: str, fields: list[str], checksum_style: str | None) -> str:
    """The sentence text: start, address, fields and the checksum written in `checksum_style`
    ("upper", "lower", "empty" for a bare '*', None for none, or "short_upper", "short_lower":
    one hex digit while the checksum is under 16, as received)."""
    return checksummed(start, ",".join([address, *fields]), checksum_style)


def checksummed(start: str, body: str, checksum_style: str | None) -> str:
    """The sentence of `body` (address and fields), as assemble writes it."""
    if checksum_style == "upper":  # the usual case first
        return f"{start}{body}*{_CHECKSUM_HEX[checksum(body)]}"
    if checksum_style is None:
        return start + body
    if checksum_style == "empty":
        return f"{start}{body}*"
    sum_ = checksum(body)
    text = f"{sum_:X}" if sum_ < 16 and checksum_style.startswith("short_") else _CHECKSUM_HEX[sum_]
    return f"{start}{body}*{text.lower() if checksum_style.endswith('lower') else text}"


_CHECKSUM_HEX: Final = tuple(f"{value:02X}" for value in range(256))


# ---------------------------------------------------------------------------------------------
# TAG blocks (NMEA 0183 4.00, IEC 61162-450): `\code:value,...*hh\` before a sentence, or on a
# line of its own. The codes, their names and value types come from spec/tag_block.yaml, as the
# CODES of the generated subclass (nmeaspec.tag_block.TagBlock).


class TagCode(NamedTuple):
    """A parameter code the spec names: its `id` (the keyword TagBlock takes) and value `type`
    (integer, group or text)."""

    code: str
    id: str
    type: str


class TagGroup(NamedTuple):
    """A grouping parameter (g): sentence `number` of `total` in the group `id`."""

    number: int
    total: int
    id: int


_TAG_FORMS: Final = {"integer": "digits", "group": "n-m-id"}
"""What a value of each type that has a form must look like (a text takes anything)."""


def _is_digits(text: str) -> bool:
    return 0 < len(text) <= MAX_DIGITS and text.isascii() and text.isdigit()


def _tag_value_fits(kind: str, value: str) -> bool:
    """An empty value fits any type (the parameter has no value); an integer is 1 to 18 digits,
    a group three of them joined by '-'."""
    if not value or kind == "text":
        return True
    if kind == "integer":
        return _is_digits(value)
    parts = value.split("-")
    return len(parts) == 3 and all(_is_digits(p) for p in parts)


def _tag_error(message: str) -> NmeaError:
    return NmeaError("bad_tag_block", message)


class TagBlock:
    """One TAG block: its parameters (code, value text) in wire order, unknown codes and
    repeated ones included, and how its checksum is written ("upper" or "lower"). Its text is the
    one received, byte for byte.

    Built from keywords, in the order given: `TagBlock(source="r003669945", time=1241544035)`
    is `\\s:r003669945,c:1241544035*hh\\` (to_text()); integers are written as they are, a
    group as a TagGroup or (number, count, id); `params` come first. The values are checked as
    a received block's are (NmeaError bad_tag_block). Reading, the generated subclass has a
    property per code (`block.source`, `block.time`: the first value, an int for an integer, a
    TagGroup for a group, None when absent or empty); `block.get(code)` gives the text of any
    code."""

    __slots__ = ("params", "checksum")
    CODES: ClassVar[dict[str, TagCode]] = {}
    """The codes the spec names, by code (the generated subclass sets them)."""
    params: tuple[tuple[str, str], ...]
    checksum: str

    def __init__(
        self, params: Iterable[tuple[str, str]] = (), checksum: str = "upper", **values: Any
    ) -> None:
        by_id = {c.id: c.code for c in self.CODES.values()}
        named = []
        for name, value in values.items():
            if name not in by_id:
                raise TypeError(f"a TAG block has no parameter {name!r}")
            named.append((by_id[name], _tag_text(value)))
        self.params = (*params, *named)
        self.checksum = checksum
        blocks, rest = read_tag_blocks(type(self), self.to_text())
        if rest or blocks[0].params != self.params:
            raise _tag_error("TAG block parameter holds ',', '*' or a backslash")

    def to_text(self) -> str:
        """The block as written on the wire, backslashes included."""
        body = ",".join(f"{code}:{value}" for code, value in self.params)
        return _block_text(body, self.checksum)

    def get(self, code: str) -> str | None:
        """The text of the first parameter with this code, or None."""
        return next((value for c, value in self.params if c == code), None)

    def integer_of(self, code: str) -> int | None:
        """The first value of an integer code, None when absent or empty."""
        value = self.get(code)
        return int(value) if value else None

    def group_of(self, code: str) -> TagGroup | None:
        """The first value of a group code, None when absent or empty."""
        value = self.get(code)
        return TagGroup(*map(int, value.split("-"))) if value else None

    def text_of(self, code: str) -> str | None:
        """The first value of a text code, None when absent or empty."""
        return self.get(code) or None

    def to_dict(self) -> dict[str, Any]:
        """The parameters as plain values, by the spec's id (an unknown code by itself): the
        first of each code."""
        out: dict[str, Any] = {}
        for code, _ in self.params:
            known = self.CODES.get(code)
            key = known.id if known else code
            if key not in out:
                value = getattr(self, key) if known else self.get(code)
                out[key] = value._asdict() if isinstance(value, TagGroup) else value
        return out

    def to_json(self) -> str:
        params = ",".join(
            f'{{"code":{json_str(c)},"value":{json_str(v)}}}' for c, v in self.params
        )
        return f'{{"params":[{params}],"checksum":"{self.to_text()[-3:-1]}"}}'

    def __eq__(self, other: object) -> bool:
        return isinstance(other, TagBlock) and self.to_text() == other.to_text()

    def __hash__(self) -> int:
        return hash(self.to_text())

    def __repr__(self) -> str:
        return f"{type(self).__name__}({self.to_text()!r})"


def _block_text(body: str, checksum_style: str | None) -> str:
    text = f"{checksum(body):02X}"
    return f"\\{body}*{text.lower() if checksum_style == 'lower' else text}\\"


def _tag_text(value: Any) -> str:
    if isinstance(value, tuple):
        return "-".join(str(part) for part in value)
    return str(value)


TagBlockT = TypeVar("TagBlockT", bound=TagBlock)


def read_tag_blocks(cls: type[TagBlockT], line: str) -> tuple[tuple[TagBlockT, ...], str]:
    """The TAG blocks at the start of `line` and the rest of the line after them: a `$`/`!`
    sentence, or empty for a line of TAG blocks only. Raises NmeaError bad_tag_block saying what
    is wrong (not_a_sentence for a byte outside printable ASCII)."""
    check_printable(line)
    blocks: list[TagBlockT] = []
    while line[:1] == "\\":
        close = line.find("\\", 1)
        if close < 0:
            raise _tag_error("TAG block has no closing backslash")
        inner = line[1:close]
        star = inner.find("*")
        if star < 0:
            raise _tag_error(f"TAG block {json_str(inner)} has no checksum")
        body, sent = inner[:star], inner[star + 1 :]
        if (
            len(sent) != 2
            or sent[0] not in _HEX_DIGITS
            or sent[1] not in _HEX_DIGITS
            or (sent != sent.upper() and sent != sent.lower())
        ):
            raise _tag_error(
                f"TAG block checksum {json_str(sent)} is not two hex digits of one letter case"
            )
        computed = checksum(body)
        if int(sent, 16) != computed:
            raise _tag_error(f"TAG block checksum is {sent}, computed {computed:02X}")
        params = []
        for param in body.split(","):
            code, colon, value = param.partition(":")
            if not colon or not code.isascii() or not code.isalnum():
                raise _tag_error(f"TAG block parameter {json_str(param)} is not code:value")
            known = cls.CODES.get(code)
            if known is not None and not _tag_value_fits(known.type, value):
                raise _tag_error(
                    f"TAG block parameter {json_str(param)}: expected {_TAG_FORMS[known.type]}"
                )
            params.append((code, value))
        block = object.__new__(cls)
        block.params = tuple(params)
        block.checksum = checksum_case(sent) or "upper"
        blocks.append(block)
        line = line[close + 1 :]
    if line[:1] not in ("", "$", "!"):
        raise _tag_error("TAG block is followed by neither '$', '!' nor a TAG block")
    return tuple(blocks), line


def tag_blocks_from_json(cls: type[TagBlockT], items: Any) -> tuple[TagBlockT, ...]:
    """The blocks of a `tag_blocks` array of the tools' JSON, read back as received ones."""
    if not isinstance(items, list) or not items:
        raise bad_json('"tag_blocks" is not an array of TAG blocks')
    blocks = ""
    for item in items:
        params = []
        for param in json_list(item, "params"):
            texts = json_str_member(param, "code"), json_str_member(param, "value")
            for text in texts:
                if not (text.isascii() and text.isprintable()) or any(c in text for c in ",*\\"):
                    raise bad_json(
                        f"TAG block text {json_str(text)} holds ',', '*', a backslash or a byte"
                        " outside printable ASCII"
                    )
            params.append(":".join(texts))
        blocks += _block_text(",".join(params), checksum_case(json_str_member(item, "checksum")))
    return read_tag_blocks(cls, blocks)[0]


# ---------------------------------------------------------------------------------------------
# Field types. Each parser takes the field's text (never empty: the caller maps "" to None)
# and returns the typed value, or None when the text does not fit the type.
#
# The values are immutable. One read from the wire keeps its text and works its parts out only
# when they are first asked for, so that reading a sentence costs little more than checking it;
# one built from its parts (Number(5, 1)) works its text out when first asked. Either way the
# public attributes, equality, hashing and repr are those of the parts.

_new = object.__new__


class _Value:
    """Base of the field value types: the text as received and/or the parts, each worked out from
    the other on first use (an unset slot raises AttributeError)."""

    __slots__ = ("_text", "_parts")
    _text: str
    _parts: tuple[Any, ...]
    _FIELDS: tuple[str, ...] = ()

    @classmethod
    def _read(cls, text: str) -> Any:
        """A value of a text the caller has checked, its parts left for later."""
        value = _new(cls)
        value._text = text
        return value

    def _split(self) -> tuple[Any, ...]:
        try:
            return self._parts
        except AttributeError:
            parts = self._parts = self._parts_of(self._text)
            return parts

    def text(self) -> str:
        """The wire text."""
        try:
            return self._text
        except AttributeError:
            text = self._text = self._text_of(*self._parts)
            return text

    @staticmethod
    def _parts_of(text: str) -> tuple[Any, ...]:
        raise NotImplementedError

    @staticmethod
    def _text_of(*parts: Any) -> str:
        raise NotImplementedError

    def __eq__(self, other: object) -> bool:
        if other.__class__ is self.__class__:
            return self._split() == other._split()
        return NotImplemented

    def __hash__(self) -> int:
        return hash(self._split())

    def __repr__(self) -> str:
        parts = ", ".join(f"{name}={value!r}" for name, value in zip(self._FIELDS, self._split()))
        return f"{type(self).__name__}({parts})"


_DIGIT_VALUES: Final = {str(digit): digit for digit in range(10)}


class Number(_Value):
    """A fixed-point number as received: its digits as an integer, the number of decimals,
    the number of integer digits (leading zeros included) and the sign as written."""

    __slots__ = ()
    __match_args__ = _FIELDS = ("digits", "scale", "width", "sign", "point")

    def __init__(
        self, digits: int, scale: int = 0, width: int = 1, sign: str = "", point: bool = False
    ) -> None:
        self._parts = (digits, scale, width, sign, point)

    @property
    def digits(self) -> int:
        return self._split()[0]  # type: ignore[no-any-return]

    @property
    def scale(self) -> int:
        return self._split()[1]  # type: ignore[no-any-return]

    @property
    def width(self) -> int:
        return self._split()[2]  # type: ignore[no-any-return]

    @property
    def sign(self) -> str:
        return self._split()[3]  # type: ignore[no-any-return]

    @property
    def point(self) -> bool:
        return self._split()[4]  # type: ignore[no-any-return]

    @staticmethod
    def _parts_of(text: str) -> tuple[int, int, int, str, bool]:
        sign = text[0] if text[0] == "+" or text[0] == "-" else ""
        whole, point, frac = text[len(sign) :].partition(".")
        return int(whole + frac), len(frac), len(whole), sign, bool(point)

    @staticmethod
    def _text_of(digits: int, scale: int, width: int, sign: str, point: bool) -> str:
        whole, frac = divmod(digits, 10**scale)
        out = sign + (str(whole).zfill(width) if width else "")
        if point:
            out += "." + (str(frac).zfill(scale) if scale else "")
        return out

    @property
    def value(self) -> Decimal:
        digits, scale, _, sign, _ = self._split()
        magnitude = Decimal(digits).scaleb(-scale)
        return -magnitude if sign == "-" else magnitude

    def __int__(self) -> int:
        """The integer part (toward zero), as int() of a float."""
        try:
            return _DIGIT_VALUES[self._text]  # one digit as received: most counts and indexes
        except (AttributeError, KeyError):
            pass
        text = getattr(self, "_text", None)
        if text is not None and text.isdigit() and text.isascii():  # a whole number as received
            return int(text)
        digits, scale, _, sign, _ = self._split()
        whole: int = digits // 10**scale
        return -whole if sign == "-" else whole

    def __float__(self) -> float:
        """The nearest double for up to 15 significant digits (2^53); the same double as C's
        nmea_to_double and Rust's f64::from for every number: the signed digits and 10^scale as
        doubles, divided (exact operands, one rounding)."""
        digits, scale, _, sign, _ = self._split()
        return float(-digits if sign == "-" else digits) / float(10**scale)

    def value_json(self) -> str:
        """The number in JSON, from its text: no '+', no leading or trailing zeros, no sign on
        zero (what decimal_json writes of its parts)."""
        text = self.text()
        negative = text[0] == "-"
        if negative or text[0] == "+":
            text = text[1:]
        whole, _, frac = text.partition(".")
        whole = whole.lstrip("0") or "0"
        frac = frac.rstrip("0")
        out = whole + "." + frac if frac else whole
        return "-" + out if negative and (frac or whole != "0") else out

    @classmethod
    def of(cls, value: int | str | Decimal) -> Number:
        """A number from a Python value, written the plain way (no leading zeros, no '+')."""
        parsed = parse_number(str(value), integer=False)
        if parsed is None:
            raise ValueError(f"not a number: {value!r}")
        return parsed


def decimal_json(digits: int, scale: int, negative: bool) -> str:
    """A JSON number for digits * 10^-scale, without leading or trailing zeros."""
    whole, frac = divmod(digits, 10**scale)
    text = str(whole)
    if frac:
        text += "." + str(frac).zfill(scale).rstrip("0")
    if negative and digits:
        text = "-" + text
    return text


def parse_number(text: str, integer: bool) -> Number | None:
    if text.isdigit() and text.isascii():  # the common case: digits only
        if len(text) > MAX_DIGITS:
            return None
        return Number._read(text)  # type: ignore[no-any-return]
    body = text[1:] if text[0] == "+" or text[0] == "-" else text
    whole, point, frac = body.partition(".")
    if integer and point:
        return None
    if not (whole + frac) or len(whole) + len(frac) > MAX_DIGITS:
        return None
    if (
        (whole and not whole.isdigit())
        or (frac and not frac.isdigit())
        or not whole.isascii()
        or not frac.isascii()
    ):
        return None
    return Number._read(text)  # type: ignore[no-any-return]


def parse_integer(text: str) -> Number | None:
    return parse_number(text, integer=True)


def parse_decimal(text: str) -> Number | None:
    return parse_number(text, integer=False)


class Hex(_Value):
    """An unsigned hexadecimal number; digit count and letter case are kept."""

    __slots__ = ()
    __match_args__ = _FIELDS = ("value", "digits", "lower")

    def __init__(self, value: int, digits: int = 1, lower: bool = False) -> None:
        self._parts = (value, digits, lower)

    @property
    def value(self) -> int:
        return self._split()[0]  # type: ignore[no-any-return]

    @property
    def digits(self) -> int:
        return self._split()[1]  # type: ignore[no-any-return]

    @property
    def lower(self) -> bool:
        return self._split()[2]  # type: ignore[no-any-return]

    @staticmethod
    def _parts_of(text: str) -> tuple[int, int, bool]:
        return int(text, 16), len(text), text != text.upper()

    @staticmethod
    def _text_of(value: int, digits: int, lower: bool) -> str:
        out = f"{value:0{digits}X}"
        return out.lower() if lower else out

    def __int__(self) -> int:
        return self.value

    def __index__(self) -> int:
        return self.value

    def value_json(self) -> str:
        return str(self.value)


def parse_hex(text: str) -> Hex | None:
    if len(text) > 16 or not _HEX_DIGITS.issuperset(text):
        return None
    if text != text.upper() and text != text.lower():
        return None
    return Hex._read(text)  # type: ignore[no-any-return]


class Time(_Value):
    """UTC time of day hhmmss[.f…]; the number of fraction digits is kept."""

    __slots__ = ()
    __match_args__ = _FIELDS = ("hour", "minute", "second", "fraction", "fraction_digits", "point")

    def __init__(
        self,
        hour: int,
        minute: int,
        second: int,
        fraction: int = 0,
        fraction_digits: int = 0,
        point: bool = False,
    ) -> None:
        self._parts = (hour, minute, second, fraction, fraction_digits, point)

    @property
    def hour(self) -> int:
        return self._split()[0]  # type: ignore[no-any-return]

    @property
    def minute(self) -> int:
        return self._split()[1]  # type: ignore[no-any-return]

    @property
    def second(self) -> int:
        return self._split()[2]  # type: ignore[no-any-return]

    @property
    def fraction(self) -> int:
        return self._split()[3]  # type: ignore[no-any-return]

    @property
    def fraction_digits(self) -> int:
        return self._split()[4]  # type: ignore[no-any-return]

    @property
    def point(self) -> bool:
        return self._split()[5]  # type: ignore[no-any-return]

    @staticmethod
    def _parts_of(text: str) -> tuple[int, int, int, int, int, bool]:
        clock, point, frac = text.partition(".")
        return (
            int(clock[0:2]),
            int(clock[2:4]),
            int(clock[4:6]),
            int(frac) if frac else 0,
            len(frac),
            bool(point),
        )

    @staticmethod
    def _text_of(
        hour: int, minute: int, second: int, fraction: int, fraction_digits: int, point: bool
    ) -> str:
        out = f"{hour:02d}{minute:02d}{second:02d}"
        if point:
            out += "." + (str(fraction).zfill(fraction_digits) if fraction_digits else "")
        return out

    def ms_of_day(self) -> int:
        """Milliseconds since midnight, digits after the third decimal dropped (a leap second,
        second 60, counts on past 86,400,000)."""
        hour, minute, second, fraction, fraction_digits, _ = self._split()
        ms: int = (
            (hour * 60 + minute) * 60 + second
        ) * 1000 + fraction * 1000 // 10**fraction_digits
        return ms

    def to_time(self) -> dt.time:
        """A `datetime.time` in UTC, digits after the sixth decimal dropped; ValueError for a
        leap second (second 60), which datetime cannot hold."""
        hour, minute, second, fraction, fraction_digits, _ = self._split()
        micro = fraction * 1_000_000 // 10**fraction_digits
        return dt.time(hour, minute, second, micro, tzinfo=dt.timezone.utc)

    def value_json(self) -> str:
        hour, minute, second, fraction, fraction_digits, _ = self._split()
        out = f"{hour:02d}:{minute:02d}:{second:02d}"
        if fraction_digits:
            out += "." + str(fraction).zfill(fraction_digits)
        return f'"{out}"'


def parse_time(text: str) -> Time | None:
    clock, point, frac = text.partition(".")
    if len(clock) != 6 or not clock.isdigit() or not clock.isascii() or len(frac) > 9:
        return None
    if frac and not (frac.isdigit() and frac.isascii()):
        return None
    # Two ASCII digits compare as text the way they do as numbers.
    if clock[0:2] > "23" or clock[2:4] > "59" or clock[4:6] > "60":
        return None
    return Time._read(text)  # type: ignore[no-any-return]


PIVOT_YEAR: Final = 69
"""Two-digit years below it are 20yy, the others 19yy (00-68: 2000-2068, 69-99: 1969-1999): the
POSIX rule of strptime's %y, which pynmea2 inherits (gpsd instead takes its build century, 20yy)."""


def full_year(yy: int) -> int:
    """The four-digit year of a two-digit one (PIVOT_YEAR)."""
    return yy + (2000 if yy < PIVOT_YEAR else 1900)


_EPOCH_ORDINAL: Final = dt.date(1970, 1, 1).toordinal()


class Date(_Value):
    """A date ddmmyy with a two-digit year (full_year: 00-68 are 2000-2068, 69-99 1969-1999)."""

    __slots__ = ()
    __match_args__ = _FIELDS = ("day", "month", "year")

    def __init__(self, day: int, month: int, year: int) -> None:
        self._parts = (day, month, year)

    @property
    def day(self) -> int:
        return self._split()[0]  # type: ignore[no-any-return]

    @property
    def month(self) -> int:
        return self._split()[1]  # type: ignore[no-any-return]

    @property
    def year(self) -> int:
        return self._split()[2]  # type: ignore[no-any-return]

    @staticmethod
    def _parts_of(text: str) -> tuple[int, int, int]:
        return int(text[0:2]), int(text[2:4]), int(text[4:6])

    @staticmethod
    def _text_of(day: int, month: int, year: int) -> str:
        return f"{day:02d}{month:02d}{year:02d}"

    @property
    def full_year(self) -> int:
        """The four-digit year: 00-68 are 2000-2068, 69-99 are 1969-1999 (PIVOT_YEAR)."""
        return full_year(self.year)

    def to_date(self) -> dt.date:
        """A `datetime.date`, its year by the pivot of full_year (00-68: 20yy, 69-99: 19yy);
        ValueError for a day its month does not have (310218)."""
        day, month, year = self._split()
        return dt.date(full_year(year), month, day)

    def days_since_epoch(self) -> int:
        """Days since 1970-01-01 (full_year's pivot); ValueError as to_date."""
        return self.to_date().toordinal() - _EPOCH_ORDINAL

    def value_json(self) -> str:
        day, month, year = self._split()
        return f'"{year:02d}-{month:02d}-{day:02d}"'


def parse_date(text: str) -> Date | None:
    if len(text) != 6 or not text.isdigit() or not text.isascii():
        return None
    if not "01" <= text[0:2] <= "31" or not "01" <= text[2:4] <= "12":
        return None
    return Date._read(text)  # type: ignore[no-any-return]


class Coordinate(_Value):
    """Latitude or longitude as received: degrees, minutes (fixed point) and hemisphere."""

    __slots__ = ("_hemisphere",)
    __match_args__ = _FIELDS = ("degrees", "minutes", "hemisphere", "degree_digits")

    def __init__(
        self, degrees: int, minutes: Number, hemisphere: str, degree_digits: int = 2
    ) -> None:
        self._parts = (degrees, minutes, hemisphere, degree_digits)
        self._hemisphere = hemisphere

    @classmethod
    def _read_pair(cls, text: str, hemisphere: str) -> Coordinate:
        """A coordinate of a value text and hemisphere the caller has checked."""
        value = _new(cls)
        value._text = text
        value._hemisphere = hemisphere
        return value

    @property
    def degrees(self) -> int:
        return self._split()[0]  # type: ignore[no-any-return]

    @property
    def minutes(self) -> Number:
        return self._split()[1]  # type: ignore[no-any-return]

    @property
    def hemisphere(self) -> str:
        return self._hemisphere

    @property
    def degree_digits(self) -> int:
        return self._split()[3]  # type: ignore[no-any-return]

    def _split(self) -> tuple[Any, ...]:
        try:
            return self._parts
        except AttributeError:
            whole, point, frac = self._text.partition(".")
            degree_text = whole[:-2]
            minutes = Number._read(whole[-2:] + point + frac)
            parts = self._parts = (
                int(degree_text) if degree_text else 0,
                minutes,
                self._hemisphere,
                len(degree_text),
            )
            return parts

    def text(self) -> str:
        """The wire text of the value field (the hemisphere is the next field)."""
        try:
            return self._text
        except AttributeError:
            degrees, minutes, _, degree_digits = self._parts
            text: str = (
                str(degrees).zfill(degree_digits) if degree_digits else ""
            ) + minutes.text()
            self._text = text
            return text

    @property
    def decimal_degrees(self) -> float:
        """Signed decimal degrees (south and west negative): the degrees plus the minutes' double
        divided by 60, in doubles, as Rust's f64::from (within one ulp of the exact value)."""
        degrees, minutes, hemisphere, _ = self._split()
        value: float = degrees + float(minutes) / 60.0
        return -value if hemisphere in ("S", "W") else value

    def __float__(self) -> float:
        return self.decimal_degrees

    def degrees_e7(self) -> int:
        """Signed degrees x 10^7, exact, rounded half away from zero (C's nmea_coordinate_e7)."""
        degrees, minutes, hemisphere, _ = self._split()
        # minutes = digits / 10^scale; degrees x 10^7 = degrees * 10^7 + digits * 10^7 / (60 * 10^scale).
        num = minutes.digits * 10**7 + degrees * 10**7 * 60 * 10**minutes.scale
        den = 60 * 10**minutes.scale
        e7: int = (2 * num + den) // (2 * den)
        return -e7 if hemisphere in ("S", "W") else e7

    def texts(self) -> tuple[str, str]:
        return self.text(), self._hemisphere

    def value_json(self) -> str:
        degrees, minutes, hemisphere, _ = self._split()
        return f'{{"deg":{degrees},"min":{minutes.value_json()},"hemi":"{hemisphere}"}}'


# The sentence-level accessors (latitude, longitude, datetime) that the generated classes have
# where the spec gives a layout one position or one date and time.


def degrees(value: Coordinate | None | _Absent) -> float | None:
    """A latitude or longitude in signed decimal degrees; None for an empty field."""
    return value.decimal_degrees if isinstance(value, Coordinate) else None


def utc_datetime(date: Date | None | _Absent, time: Time | None | _Absent) -> dt.datetime | None:
    """The UTC datetime of a date field and a time field; None when either is empty or when
    datetime cannot hold them (a day its month lacks, a leap second)."""
    if not isinstance(date, Date):
        return None
    return _at(full_year(date.year), date.month, date.day, time)


def utc_datetime_of(
    year: Number | None | _Absent,
    month: Number | None | _Absent,
    day: Number | None | _Absent,
    time: Time | None | _Absent,
) -> dt.datetime | None:
    """utc_datetime of a date in three integer fields (ZDA: day, month, four-digit year)."""
    if not (isinstance(year, Number) and isinstance(month, Number) and isinstance(day, Number)):
        return None
    return _at(int(year), int(month), int(day), time)


def _at(year: int, month: int, day: int, time: Time | None | _Absent) -> dt.datetime | None:
    if not isinstance(time, Time):
        return None
    try:
        return dt.datetime.combine(dt.date(year, month, day), time.to_time())
    except ValueError:
        return None


def plain(value: Any) -> Any:
    """A field value as a plain Python value (to_dict): a number as a float, a time, date or
    date and time as datetime's (None where datetime cannot hold it), a coordinate as signed
    decimal degrees, a hex number as an int, an enum as its value id (an unknown code as sent),
    text as text, an empty or absent field as None."""
    if value is None or value is ABSENT:
        return None
    if value.__class__ is str:
        return value
    if isinstance(value, CodeEnum):
        return value.id
    if isinstance(value, list):
        return [plain(v) for v in value]
    if isinstance(value, (Time, Date)):
        try:
            return value.to_time() if isinstance(value, Time) else value.to_date()
        except ValueError:
            return None
    if isinstance(value, Hex):
        return value.value
    if isinstance(value, (Number, Coordinate)):
        return float(value)
    return str(value)


def parse_coordinate(text: str, max_degree_digits: int, max_degrees: int) -> Coordinate | None:
    """ddmm.mmmm (latitude) or dddmm.mmmm (longitude): the two digits before the point are
    whole minutes, the digits before them degrees."""
    whole, point, frac = text.partition(".")
    if not 2 <= len(whole) <= 2 + max_degree_digits or not whole.isdigit() or not whole.isascii():
        return None
    if len(frac) > MAX_DIGITS - 2 or (frac and not (frac.isdigit() and frac.isascii())):
        return None
    degree_text = whole[:-2]
    if degree_text and int(degree_text) > max_degrees:
        return None
    minutes = whole[-2:]  # at most 60 minutes: 60 itself only with a zero fraction
    if minutes > "60" or (minutes == "60" and frac.strip("0")):
        return None
    return Coordinate._read_pair(text, "")


def is_code_like(text: str, code_class: str, min_len: int, max_len: int) -> bool:
    """Whether an enum code the spec does not know is still well formed for its enum: the same
    length range and character class (`digits`, `letters`, `alnum`) as the known codes. A closed
    enum (`closed`: N/S, A/V, units) keeps none."""
    if code_class == "closed" or not min_len <= len(text) <= max_len or not text.isascii():
        return False
    if code_class == "digits":
        return text.isdigit()
    if code_class == "letters":
        return text.isalpha()
    return text.isalnum()


class CodeEnum(Enum):
    """Base of generated enums: the member's value is the wire code."""

    @property
    def id(self) -> str:
        return self.name.lower()

    def text(self) -> str:
        """The wire code."""
        return self._value_  # type: ignore[no-any-return]


def by_code(enum: type[CodeEnum]) -> dict[str, Any]:
    """An enum's members by wire code (its BY_CODE)."""
    return {member.value: member for member in enum}


def holds_selector(layout: Any, fields: list[str]) -> bool:
    """Whether the fields hold the layout's keyword (SELECTOR) in its place, ignoring case."""
    at = getattr(layout, "SELECTOR_AT", 0)
    return (
        layout.SELECTOR is not None
        and at < len(fields)
        and fields[at].upper() == layout.SELECTOR.upper()
    )


def claimed(layouts: tuple[Any, ...], fields: list[str]) -> bool:
    """Whether one of the layouts of an address may read the line: one whose keyword the line
    holds, or one without a keyword, when no layout of the address has one or when the line's
    first field reads as that layout's first (reads_first). Else the line is a message of a known
    family that the spec does not know, kept as a generic sentence: `$PASHR,BTS,...` beside the
    keyword-less `$PASHR,<time>,...` of RT300."""
    keyed = any(layout.SELECTOR is not None for layout in layouts)
    return any(
        holds_selector(layout, fields) if layout.SELECTOR is not None else not keyed or reads_first(layout, fields)
        for layout in layouts
    )


def reads_first(layout: Any, fields: list[str]) -> bool:
    """Whether the line's first field reads as the first field of `layout` (a number outside its
    range does; a layout without fields: whether the line has none). A layout that starts with a
    group, or a line too short for the first field, is left to the reader's count."""
    items = layout.LAYOUT.items
    if not items:
        return not fields
    first = items[0]
    if not isinstance(first, FieldSpec) or len(fields) < first.width:
        return True
    try:
        first.read(fields, 0, "", first.id)
    except NmeaError as err:
        return err.out_of_range
    return True


# A reply's pairing with a command and its outcome (generated REPLY_RULES and OUTCOME):
# (field id, "integer" | "enum" | "text", value) tests; an enum is tested by value id.
FieldTest = tuple[str, str, Any]
ReplyRule = tuple[str, "str | None", tuple[FieldTest, ...]]
Outcome = Any  # "error", or a tuple of FieldTest of which one must hold for success


def holds(sentence: Any, test: FieldTest) -> bool:
    """Whether a field of a decoded sentence holds the value of `test`."""
    field_id, kind, want = test
    value = getattr(sentence, field_id, None)
    if kind == "integer":
        return (
            isinstance(value, Number)
            and value.scale == 0
            and not value.point
            and (-value.digits if value.sign == "-" else value.digits) == want
        )
    if kind == "enum":
        return isinstance(value, CodeEnum) and value.id == want
    return isinstance(value, str) and value == want


def reply_outcome(command: Any, sentence: Any) -> str | None:
    """ "ok" or "error" when `sentence` (decoded) answers `command` (a command class or instance),
    None when it does not answer it."""
    sentence_id, variant = getattr(sentence, "SENTENCE", None), getattr(sentence, "VARIANT", None)
    for reply_id, reply_variant, tests in getattr(command, "REPLY_RULES", ()):
        if (
            reply_id == sentence_id
            and reply_variant == variant
            and all(holds(sentence, t) for t in tests)
        ):
            outcome = getattr(sentence, "OUTCOME", None)
            if outcome is None:
                return "ok"
            return (
                "ok" if outcome != "error" and any(holds(sentence, t) for t in outcome) else "error"
            )
    return None


def enum_text(value: CodeEnum | str) -> str:
    return value.value if isinstance(value, CodeEnum) else value


def enum_value_json(value: CodeEnum | str) -> str:
    return json_str(value.id if isinstance(value, CodeEnum) else value)


# ---------------------------------------------------------------------------------------------
# JSON


def json_str(text: str) -> str:
    """A JSON string: '"' and '\\' escaped, every byte outside 0x20-0x7E as \\u00hh."""
    if text.isascii() and text.isprintable() and '"' not in text and "\\" not in text:
        return f'"{text}"'
    out = ['"']
    for ch in text:
        if ch == '"' or ch == "\\":
            out.append("\\" + ch)
        elif " " <= ch <= "~":
            out.append(ch)
        else:
            out.append(f"\\u{ord(ch) & 0xFF:04x}")
    out.append('"')
    return "".join(out)


def json_opt(text: str | None) -> str:
    return "null" if text is None else json_str(text)


def bad_field(
    address: str, index: int, name: str, expected: str, text: str, out_of_range: bool = False
) -> NmeaError:
    message = f"expected {expected}, found {json_str(text)}"
    return NmeaError("bad_field", message, address, index, name, text, out_of_range)


class RangeKept(str):
    """The text of a field whose value parsing keeps outside the field's range (a problem of the
    sentence): the number readers do not check its range, nor remember its value."""

    __slots__ = ()


def problem_json(problem: NmeaError) -> str:
    """A problem of a decoded sentence: its kind, where it is, its text as received, and why."""
    return (
        f'{{"kind":"{problem.problem_kind}","field":{problem.field},"name":{json_opt(problem.name)},'
        f'"text":{json_opt(problem.text)},"message":{json_str(problem.message)}}}'
    )


def with_problems(fields: list[str], problems: list[NmeaError]) -> list[str]:
    """The wire fields, with the text of every field lenient parsing left empty put back."""
    if not problems:
        return fields
    out = list(fields)
    for problem in problems:
        if (
            not problem.out_of_range
            and problem.field is not None
            and problem.field <= len(out)
            and problem.text is not None
        ):
            out[problem.field - 1] = problem.text
    return out


def too_few(address: str, sentence: str, need: int, found: int) -> NmeaError:
    return NmeaError(
        "too_few_fields", f"{sentence} needs at least {need} fields, found {found}", address
    )


def too_many(address: str, sentence: str, limit: int, found: int) -> NmeaError:
    return NmeaError(
        "too_many_fields", f"{sentence} takes at most {limit} fields, found {found}", address
    )


def group_cut(address: str, sentence: str, group: str, width: int, left: int) -> NmeaError:
    return NmeaError(
        "too_few_fields",
        f"{sentence} {group} entries take {width} fields each, {left} left over",
        address,
    )


def split_group(
    address: str,
    sentence: str,
    group: str,
    count: int,
    fixed: int,
    width: int,
    minimum: int,
    maximum: int,
    optional: int,
) -> tuple[int, int]:
    """How many times the layout's repeated group occurs in a sentence of `count` fields and how
    many optional trailing fields follow it. `fixed` counts the required fields outside the
    group."""
    rest = count - fixed
    if rest < minimum * width:
        raise too_few(address, sentence, fixed + minimum * width, count)
    repeats = min(rest // width, maximum)
    extra = rest - repeats * width
    if extra > optional:
        if repeats == maximum:
            raise too_many(address, sentence, fixed + maximum * width + optional, count)
        raise group_cut(address, sentence, group, width, extra)
    return repeats, extra


MAX_JSON_DEPTH: Final = 500
"""Deepest nesting of arrays and objects `encode` reads; deeper is "not JSON" in every tool."""


def json_too_deep(text: str) -> bool:
    """Whether `text` opens more than MAX_JSON_DEPTH arrays and objects at once (outside
    strings)."""
    if text.count("[") + text.count("{") <= MAX_JSON_DEPTH:  # nothing can be deeper than that: no scan
        return False
    depth = 0
    in_string = escaped = False
    for ch in text:
        if in_string:
            if escaped:
                escaped = False
            elif ch == "\\":
                escaped = True
            elif ch == '"':
                in_string = False
        elif ch == '"':
            in_string = True
        elif ch in "[{":
            depth += 1
            if depth > MAX_JSON_DEPTH:
                return True
        elif ch in "]}":
            depth -= 1
    return False


def decode_json_line(line: str) -> Any:
    """Parse one line of `decode` output (the tools' own JSON, nothing more general)."""
    import json

    return json.loads(line)


# ---------------------------------------------------------------------------------------------
# Field readers used by the generated parsers: "" is an empty field (None), text that does not
# fit raises bad_field naming the sentence, the field and what was expected.


def in_range(number: Number, low: Decimal | None, high: Decimal | None) -> bool:
    if low is None and high is None:
        return True
    value = number.value
    return (low is None or value >= low) and (high is None or value <= high)


KNOWN_LIMIT: Final = 256
"""Most texts one table of known values holds before it starts again (see `known`)."""

_KNOWN: dict[str, dict[Any, Any]] = {}


def known(rule: str) -> dict[Any, Any]:
    """The table of values already read under one field rule ("integer 0..99", "time", ...), by
    wire text. Values are immutable, so a text read before under the same rule takes the value it
    gave then: the generated parsers look a text up here first, which spares nearly all the work
    for the texts receivers repeat (satellite numbers, elevations, the time of each fix...)."""
    return _KNOWN.setdefault(rule, {})


def remember(table: dict[Any, Any] | None, key: Any, value: Any) -> None:
    if table is not None:
        if len(table) >= KNOWN_LIMIT:
            table.clear()
        table[key] = value


def _within(
    text: str, integer: bool, low: Decimal | int | None, high: Decimal | int | None
) -> bool:
    """Whether a number's text (already checked) lies in [low, high], compared exactly."""
    if low is None and high is None:
        return True
    value = int(text) if integer else Decimal(text)
    return (low is None or value >= low) and (high is None or value <= high)


def number_field(
    text: str,
    integer: bool,
    address: str,
    index: int,
    name: str,
    expected: str,
    low: Decimal | int | None = None,
    high: Decimal | int | None = None,
    table: dict[str, Number] | None = None,
) -> Number | None:
    """An integer (`integer`) or decimal field, in [low, high] when they are given (but for a
    RangeKept text)."""
    if not text:
        return None
    number = parse_number(text, integer)
    if number is None:
        raise bad_field(address, index, name, expected, text)
    if not _within(text, integer, low, high):
        if text.__class__ is not RangeKept:
            raise bad_field(address, index, name, expected, text, out_of_range=True)
        return number
    remember(table, text, number)
    return number


def hex_field(
    text: str,
    address: str,
    index: int,
    name: str,
    expected: str,
    table: dict[str, Hex] | None = None,
) -> Hex | None:
    if not text:
        return None
    value = parse_hex(text)
    if value is None:
        raise bad_field(address, index, name, expected, text)
    remember(table, text, value)
    return value


def time_field(
    text: str,
    address: str,
    index: int,
    name: str,
    expected: str,
    table: dict[str, Time] | None = None,
) -> Time | None:
    if not text:
        return None
    value = parse_time(text)
    if value is None:
        raise bad_field(address, index, name, expected, text)
    remember(table, text, value)
    return value


def date_field(
    text: str,
    address: str,
    index: int,
    name: str,
    expected: str,
    table: dict[str, Date] | None = None,
) -> Date | None:
    if not text:
        return None
    value = parse_date(text)
    if value is None:
        raise bad_field(address, index, name, expected, text)
    remember(table, text, value)
    return value


def coordinate_field(
    text: str,
    hemisphere: str,
    address: str,
    index: int,
    name: str,
    expected: str,
    hemisphere_expected: str,
    hemispheres: str,
    table: dict[tuple[str, str], Coordinate] | None = None,
) -> Coordinate | None:
    """Latitude (hemispheres "NS") or longitude ("EW"): a value field and a hemisphere field,
    both empty or both set."""
    latitude = hemispheres == "NS"
    if not text:
        if hemisphere:
            raise bad_field(address, index, name, expected, text)
        return None
    value = parse_coordinate(text, 2 if latitude else 3, 90 if latitude else 180)
    if value is None:
        raise bad_field(address, index, name, expected, text)
    if len(hemisphere) != 1 or hemisphere not in hemispheres:
        raise bad_field(address, index + 1, name, hemisphere_expected, hemisphere)
    coordinate = Coordinate._read_pair(text, hemisphere)
    remember(table, (text, hemisphere), coordinate)
    return coordinate


def char_field(text: str, address: str, index: int, name: str, expected: str) -> str | None:
    if not text:
        return None
    if len(text) != 1:
        raise bad_field(address, index, name, expected, text)
    return text


def literal_field(
    text: str, address: str, index: int, name: str, expected: str, literal: str
) -> str | None:
    if not text:
        return None
    if text != literal:
        raise bad_field(address, index, name, expected, text)
    return text


def keyword_field(
    text: str,
    address: str,
    index: int,
    name: str,
    expected: str,
    keyword: str,
    ignore_case: bool = False,
) -> str:
    """A fixed word that must be there (it picks the layout); returned in the spec's spelling."""
    if text != keyword and not (ignore_case and text.upper() == keyword):
        raise bad_field(address, index, name, expected, text)
    return keyword


def text_field(
    text: str, address: str, index: int, name: str, expected: str, max_length: int | None = None
) -> str | None:
    if not text:
        return None
    if max_length is not None and len(text) > max_length:
        raise bad_field(address, index, name, expected, text)
    return text


def enum_field(
    text: str,
    address: str,
    index: int,
    name: str,
    expected: str,
    by_code: dict[str, Any],
    code_class: str,
    min_len: int,
    max_len: int,
    ignore_case: bool = False,
) -> Any:
    """An enum member for a known code, the code itself for a well-formed unknown one."""
    if not text:
        return None
    member = by_code.get(text.upper() if ignore_case else text)
    if member is not None:
        return member
    if not is_code_like(text, code_class, min_len, max_len):
        raise bad_field(address, index, name, expected, text)
    return text


def enum_chars_field(
    text: str,
    address: str,
    index: int,
    name: str,
    expected: str,
    by_code: dict[str, Any],
    code_class: str,
    max_length: int | None,
) -> list[Any] | None:
    """A run of one-character codes (GNS mode "ANNN"): one member or unknown code per character."""
    if not text:
        return None
    if max_length is not None and len(text) > max_length:
        raise bad_field(address, index, name, expected, text)
    out = []
    for ch in text:
        member = by_code.get(ch)
        if member is None:
            if not is_code_like(ch, code_class, 1, 1):
                raise bad_field(address, index, name, expected, text)
            member = ch
        out.append(member)
    return out


def enum_chars_text(values: list[Any]) -> str:
    return "".join(enum_text(v) for v in values)


# ---------------------------------------------------------------------------------------------
# Writing fields back and describing them as JSON


def text_of(value: Any) -> str:
    """The wire text of a field value (not lat/lon, whose value spans two fields)."""
    if value is None:
        return ""
    if isinstance(value, _Value):  # numbers, times, dates, hex values: most fields
        try:
            return value._text  # as received (value.text() without its call)
        except AttributeError:
            return value.text()
    if value.__class__ is str:
        return value
    if isinstance(value, list):
        return enum_chars_text(value)
    if isinstance(value, str):
        return str(value)
    return value.text()  # type: ignore[no-any-return]


def coordinate_texts(value: Coordinate | None) -> tuple[str, str]:
    return ("", "") if value is None else value.texts()


def text_json(value: Any) -> str:
    """A field value in the lossless JSON form of `decode`."""
    if value is None:
        return "null"
    if isinstance(value, Coordinate):
        number, hemisphere = value.texts()
        return f"[{json_str(number)},{json_str(hemisphere)}]"
    return json_str(text_of(value))


def field_text_json(value: Any) -> str:
    """text_json of the value of one wire field (not a coordinate's two); numbers first, most of
    what a log carries, whose text is digits, a sign and a point only."""
    if value.__class__ is Number:
        return f'"{value.text()}"'
    if value is None:
        return "null"
    return json_str(text_of(value))


def value_json(value: Any) -> str:
    """A field value in the decoded JSON form of `decode --values`."""
    if value.__class__ is Number:  # most of what a log carries
        return value.value_json()
    if value is None:
        return "null"
    if isinstance(value, str):
        return json_str(value)
    if isinstance(value, CodeEnum):
        return json_str(value.id)
    if isinstance(value, list):
        return "[" + ",".join(enum_value_json(v) for v in value) + "]"
    text: str = value.value_json()
    return text


# ---------------------------------------------------------------------------------------------
# Reading the tools' lossless JSON back (the `encode` verb)


def bad_json(message: str) -> NmeaError:
    return NmeaError("bad_json", message)


def json_member(obj: Any, key: str) -> Any:
    if not isinstance(obj, dict) or key not in obj:
        raise bad_json(f'missing "{key}"')
    return obj[key]


def json_list(obj: Any, key: str) -> list[Any]:
    value = json_member(obj, key)
    if not isinstance(value, list):
        raise bad_json(f'"{key}" is not an array')
    return value


def json_texts(value: Any, width: int) -> list[str]:
    """The wire texts of one JSON field value: a string or null, or for latitude/longitude
    (width 2) null or an array of two."""
    if width == 2:
        if value is None:
            return ["", ""]
        if isinstance(value, list) and len(value) == 2:
            return [json_text(value[0]), json_text(value[1])]
        raise bad_json("a latitude or longitude is not null or an array of two")
    return [json_text(value)]


def json_text(value: Any) -> str:
    if value is None:
        return ""
    if not isinstance(value, str):
        raise bad_json("a field value is not a string or null")
    if not (value.isascii() and value.isprintable()) or "," in value or "*" in value:
        raise bad_json(
            f"field text {json_str(value)} holds ',', '*' or a byte outside printable ASCII"
        )
    return value


def checksum_case(text: str | None) -> str | None:
    """How a received checksum was written: None (absent), "empty" (a bare '*'), "lower" or
    "upper"; "short_lower" or "short_upper" for one digit."""
    if text is None:
        return None
    if not text:
        return "empty"
    short = "short_" if len(text) == 1 else ""
    if text.isascii():  # upper() changes exactly the letters a to z
        return short + ("lower" if text != text.upper() else "upper")
    return short + ("lower" if any("a" <= c <= "z" for c in text) else "upper")


def assemble_text(address: str, fields: list[str], as_received: str | None) -> str:
    """A text command: its words joined by single spaces, in the letter case it was received in."""
    line = " ".join([address, *fields])
    if as_received is not None and as_received.upper() == line.upper():
        return as_received
    return line


def json_opt_text(obj: Any, key: str) -> str | None:
    value = json_member(obj, key)
    if value is not None and not isinstance(value, str):
        raise bad_json(f'"{key}" is not a string or null')
    return value


def json_word(obj: Any, key: str) -> str:
    """A member that must be letters and digits (an address, a talker ID, a command word)."""
    value = json_member(obj, key)
    if not isinstance(value, str) or not value.isascii() or not value.isalnum():
        raise bad_json(f'"{key}" is not letters and digits')
    return value


def json_talker(obj: Any, sentence: str = "") -> str:
    """The talker of standard sentence `sentence`: two letters and digits, as decode gives it (a
    longer one would make another address); four, two talker IDs, for the query."""
    value = json_word(obj, "talker")
    if len(value) != (4 if sentence == QUERY else 2):
        raise bad_json(f'"talker" is not {"four" if sentence == QUERY else "two"} letters and digits')
    return value


def json_str_member(obj: Any, key: str) -> str:
    value = json_member(obj, key)
    if not isinstance(value, str):
        raise bad_json(f'"{key}" is not a string')
    return value


# ---------------------------------------------------------------------------------------------
# Configuration parameter tables (ST's CDB): the wire text of a value


@dataclass(frozen=True)
class Parameter:
    """One parameter of a receiver's configuration table and how its value is written."""

    number: int
    id: str
    name: str
    encoding: str  # hex, decimal, decimal_list or text
    size: int | None = None
    count: int | None = None
    minimum: float | None = None
    maximum: float | None = None
    max_length: int | None = None
    default: str | None = None
    unit: str | None = None
    enum: Any = None
    bitfield: Any = None
    doc: str = ""

    def encode(self, value: Any) -> list[str]:
        """The wire field(s) for `value`: an int (hex), a number (decimal), a sequence of numbers
        (decimal_list) or a string (text). Raises ValueError naming the parameter."""
        where = f"parameter {self.number} ({self.id})"
        if self.encoding == "hex":
            number = int(value.value, 16) if isinstance(value, CodeEnum) else int(value)
            self._check_range(number, where)
            if number < 0 or (self.size is not None and number >= 1 << (8 * self.size)):
                raise ValueError(f"{where}: {number} does not fit {self.size} byte(s)")
            return [f"{number:X}"]
        if self.encoding == "decimal":
            amount = Decimal(str(value))
            self._check_range(amount, where)
            return [str(amount)]
        if self.encoding == "decimal_list":
            values = [Decimal(str(v)) for v in value]
            if self.count is not None and len(values) != self.count:
                raise ValueError(f"{where}: expected {self.count} values, got {len(values)}")
            for v in values:
                self._check_range(v, where)
            return [str(v) for v in values]
        text = str(value)
        if self.max_length is not None and len(text) > self.max_length:
            raise ValueError(f"{where}: text longer than {self.max_length}")
        if not (text.isascii() and text.isprintable()) or any(ch in ",*$!" for ch in text):
            raise ValueError(
                f"{where}: text holds ',', '*', '$', '!' or a byte outside printable ASCII"
            )
        return [text]

    def _check_range(self, number: Any, where: str) -> None:
        if self.minimum is not None and number < Decimal(str(self.minimum)):
            raise ValueError(f"{where}: {number} is below {self.minimum}")
        if self.maximum is not None and number > Decimal(str(self.maximum)):
            raise ValueError(f"{where}: {number} is above {self.maximum}")


# ---------------------------------------------------------------------------------------------
# Layouts: each generated sentence class describes its fields in LAYOUT, and the reading,
# writing and JSON here interpret it (the generated modules hold no code of their own).


class FieldSpec:
    """One field of a layout: its id, what it takes (for errors), how many wire fields it spans
    and, for an optional trailing field, how many optional wire fields must be there for it."""

    __slots__ = ("id", "expected", "width", "optional_index", "offset")

    width_of: ClassVar[int] = 1
    PLAIN: ClassVar[Any] = str
    """The type of what plain() gives for the field's values (None aside): for tables."""

    def __init__(self, id: str, expected: str, optional: bool = False) -> None:
        self.id = id
        self.expected = expected
        self.width = self.width_of
        self.optional_index = 0 if not optional else -1  # set by Layout: its cumulative wire width
        self.offset = 0  # in a group's entry: its wire index from the entry's first field

    def read(self, fields: list[str], pos: int, address: str, name: str) -> Any:
        """The value of the field at `pos` of `fields`; raises NmeaError naming `name`."""
        raise NotImplementedError

    def known_values(self) -> dict[Any, Any]:
        """Values by wire text that read() would give for them (looked up first: a dict lookup
        is most of what reading a field costs then)."""
        return _NOTHING_KNOWN

    def plain(self, value: Any) -> Any:
        """The field's value as a plain Python value (see the function plain)."""
        return plain(value)


_NOTHING_KNOWN: dict[Any, Any] = {}


class _Memo(FieldSpec):
    """A field whose values are looked up by text first (see known): most fields of a fix."""

    __slots__ = ("memo",)

    def __init__(self, id: str, expected: str, rule: str, optional: bool = False) -> None:
        super().__init__(id, expected, optional)
        self.memo = known(rule)

    def known_values(self) -> dict[Any, Any]:
        return self.memo


class IntegerField(_Memo):
    """An integer field, in [low, high] when they are given (DecimalField: a decimal number)."""

    __slots__ = ("low", "high")
    KIND: ClassVar[str] = "integer"
    PLAIN: ClassVar[Any] = int

    def __init__(
        self,
        id: str,
        expected: str,
        low: Decimal | int | None = None,
        high: Decimal | int | None = None,
        optional: bool = False,
    ) -> None:
        super().__init__(id, expected, _rule(self.KIND, low, high), optional)
        self.low, self.high = low, high

    def read(self, fields: list[str], pos: int, address: str, name: str) -> Any:
        integer, args = self.KIND == "integer", (self.expected, self.low, self.high, self.memo)
        return number_field(fields[pos], integer, address, pos + 1, name, *args)

    def plain(self, value: Any) -> Any:
        return int(value) if isinstance(value, Number) else plain(value)


class DecimalField(IntegerField):
    __slots__ = ()
    KIND = "decimal"
    PLAIN = float

    def plain(self, value: Any) -> Any:
        return plain(value)


def _coordinate_pair(value: Any) -> tuple[str, str]:
    """The two wire texts of a latitude or longitude (empty when it is None or absent)."""
    return ("", "") if value is None or value is ABSENT else value.texts()


def _rule(kind: str, low: Decimal | int | None, high: Decimal | int | None) -> str:
    """The memo table's rule of a number field: its type and range ("integer 0..99")."""
    if low is None and high is None:
        return kind
    return f"{kind} {'' if low is None else low}..{'' if high is None else high}"


class _Parsed(_Memo):
    """A field one parser of the runtime reads whole (hex, time, date)."""

    __slots__ = ()
    KIND: ClassVar[str]

    def __init__(self, id: str, expected: str, optional: bool = False) -> None:
        super().__init__(id, expected, self.KIND, optional)

    def read(self, fields: list[str], pos: int, address: str, name: str) -> Any:
        parse: Callable[..., Any] = _PARSERS[self.KIND]
        return parse(fields[pos], address, pos + 1, name, self.expected, self.memo)


_PARSERS: dict[str, Callable[..., Any]] = {"hex": hex_field, "time": time_field, "date": date_field}


class HexField(_Parsed):
    __slots__ = ()
    KIND = "hex"
    PLAIN = int


class TimeField(_Parsed):
    __slots__ = ()
    KIND = "time"
    PLAIN = dt.time


class DateField(_Parsed):
    __slots__ = ()
    KIND = "date"
    PLAIN = dt.date


class LatitudeField(_Memo):
    """A latitude and its hemisphere: two wire fields (its values are known by both texts)."""

    __slots__ = ("hemisphere_expected",)
    width_of = 2
    PLAIN = float  # signed decimal degrees
    HEMISPHERES: ClassVar[str] = "NS"

    def __init__(
        self, id: str, expected: str, hemisphere_expected: str, optional: bool = False
    ) -> None:
        super().__init__(
            id, expected, "latitude" if self.HEMISPHERES == "NS" else "longitude", optional
        )
        self.hemisphere_expected = hemisphere_expected

    def read(self, fields: list[str], pos: int, address: str, name: str) -> Any:
        args = (self.expected, self.hemisphere_expected, self.HEMISPHERES, self.memo)
        return coordinate_field(fields[pos], fields[pos + 1], address, pos + 1, name, *args)


class LongitudeField(LatitudeField):
    __slots__ = ()
    HEMISPHERES = "EW"


class CharField(FieldSpec):
    __slots__ = ()

    def read(self, fields: list[str], pos: int, address: str, name: str) -> Any:
        return char_field(fields[pos], address, pos + 1, name, self.expected)


class LiteralField(FieldSpec):
    """A fixed word that may be left empty (a unit, "M")."""

    __slots__ = ("word",)

    def __init__(self, id: str, expected: str, word: str, optional: bool = False) -> None:
        super().__init__(id, expected, optional)
        self.word = word

    def read(self, fields: list[str], pos: int, address: str, name: str) -> Any:
        return literal_field(fields[pos], address, pos + 1, name, self.expected, self.word)

    def known_values(self) -> dict[Any, Any]:
        return {self.word: self.word}


class KeywordField(LiteralField):
    """A fixed word that must be there (it picks the layout); in a text command ignoring case."""

    __slots__ = ("ignore_case",)

    def __init__(self, id: str, expected: str, word: str, optional: bool = False) -> None:
        super().__init__(id, expected, word, optional)
        self.ignore_case = False

    def read(self, fields: list[str], pos: int, address: str, name: str) -> Any:
        return keyword_field(
            fields[pos], address, pos + 1, name, self.expected, self.word, self.ignore_case
        )

    def known_values(self) -> dict[Any, Any]:
        return _NOTHING_KNOWN if self.ignore_case else {self.word: self.word}


class TextField(FieldSpec):
    __slots__ = ("max_length",)

    def __init__(
        self, id: str, expected: str, max_length: int | None = None, optional: bool = False
    ) -> None:
        super().__init__(id, expected, optional)
        self.max_length = max_length

    def read(self, fields: list[str], pos: int, address: str, name: str) -> Any:
        return text_field(fields[pos], address, pos + 1, name, self.expected, self.max_length)


class EnumField(FieldSpec):
    """A code of a lookup table (spec/enums): its member, or a well-formed unknown code as text."""

    __slots__ = ("enum", "ignore_case")

    def __init__(self, id: str, expected: str, enum: Any, optional: bool = False) -> None:
        super().__init__(id, expected, optional)
        self.enum = enum
        self.ignore_case = False

    def read(self, fields: list[str], pos: int, address: str, name: str) -> Any:
        e = self.enum
        table = (e.BY_CODE, e.CODE_CLASS, e.MIN_LEN, e.MAX_LEN, self.ignore_case)
        return enum_field(fields[pos], address, pos + 1, name, self.expected, *table)

    def known_values(self) -> dict[Any, Any]:
        return _NOTHING_KNOWN if self.ignore_case else self.enum.BY_CODE


class EnumCharsField(FieldSpec):
    """A run of one-character codes (GNS mode "ANNN")."""

    __slots__ = ("enum", "max_length")
    PLAIN = list[str]

    def __init__(
        self,
        id: str,
        expected: str,
        enum: Any,
        max_length: int | None = None,
        optional: bool = False,
    ) -> None:
        super().__init__(id, expected, optional)
        self.enum = enum
        self.max_length = max_length

    def read(self, fields: list[str], pos: int, address: str, name: str) -> Any:
        e = self.enum
        return enum_chars_field(
            fields[pos],
            address,
            pos + 1,
            name,
            self.expected,
            e.BY_CODE,
            e.CODE_CLASS,
            self.max_length,
        )


class Group:
    """A repeated group: `minimum` to `maximum` entries of `fields`, each entry an `entry`
    dataclass (None for a group of one field, whose entries are its values)."""

    __slots__ = ("id", "entry", "fields", "minimum", "maximum", "width")

    def __init__(
        self, id: str, entry: Any, fields: tuple[FieldSpec, ...], minimum: int, maximum: int
    ) -> None:
        self.id, self.entry, self.fields = id, entry, fields
        self.minimum, self.maximum = minimum, maximum
        self.width = 0
        for f in fields:
            f.offset = self.width
            self.width += f.width


def _in_line(spec: FieldSpec, value: str, names: dict[str, Any]) -> str:
    """The expression of the wire text of `spec`'s `value` (an expression) with text_of's cases
    in line, a value without its text raising AttributeError (the caller then calls text_of);
    the names it uses put into `names` (text_of, _Value, the field's enum)."""
    if spec.width == 2:
        return f"*pair({value})"
    member = ""
    enum = getattr(spec, "enum", None)
    if enum is not None and not issubclass(enum, str) and enum.text is CodeEnum.text:
        names[f"E_{spec.id}"] = enum  # a member's text: its code
        member = f"v._value_ if v.__class__ is E_{spec.id} else "
    return (
        f'("" if (v := {value}) is None else v if v.__class__ is str '
        f"else v._text if isinstance(v, _Value) else {member}text_of(v))"
    )


class Layout:
    """What the generated class of a sentence layout says of its wire form: the sentence id, its
    kind ("standard", "proprietary" or "text"), its start ('$' or '!'), how many wire fields the
    required ones take and at most, and its items (fields and at most one Group) in wire order,
    optional trailing fields last.

    Reading is the hot path: the layout compiles its reader once, from these items, into a
    Python function that reads each field in its place (looking its text up among the values
    already read first) and makes the instance, as dataclasses compiles __init__."""

    __slots__ = (
        "sentence",
        "kind",
        "start",
        "fixed",
        "max_fields",
        "items",
        "group",
        "optional_max",
        "field_ids",
        "parse",
        "write",
        "joined",
        "_json_writers",
    )

    def __init__(
        self,
        sentence: str,
        kind: str,
        start: str,
        fixed: int,
        max_fields: int,
        items: tuple[FieldSpec | Group, ...],
    ) -> None:
        self.sentence, self.kind, self.start = sentence, kind, start
        self.fixed, self.max_fields, self.items = fixed, max_fields, items
        self.group = next((item for item in items if isinstance(item, Group)), None)
        self.field_ids = tuple(item.id for item in items)
        self.optional_max = 0
        for item in items:
            if isinstance(item, FieldSpec):
                if item.optional_index:
                    self.optional_max += item.width
                    item.optional_index = self.optional_max
                if kind == "text" and isinstance(item, (KeywordField, EnumField)):
                    item.ignore_case = True  # a text command's words match ignoring case
        self.parse: Callable[..., Any] = self._compile()
        self.write: Callable[[Any], list[str]] = self._compile_writer()
        self.joined: Callable[[Any, str], str] | None = self._compile_joined()
        # json(sentence, values) for the texts and the values, each compiled on first use.
        self._json_writers: list[Callable[[Any], str] | None] = [None, None]

    def _compile(self) -> Callable[..., Any]:
        """parse(cls, address, fields, checksum, line): an instance of `cls` read from the wire
        fields after the address; raises NmeaError naming the field at fault."""
        names: dict[str, Any] = {
            "too_few": too_few,
            "too_many": too_many,
            "split_group": split_group,
            "ABSENT": ABSENT,
            "NmeaError": NmeaError,
        }

        def read(spec: FieldSpec, n: str, pos: str, name: str) -> str:
            """The expression that reads `spec` at wire index `pos` (an expression)."""
            names[f"known{n}"], names[f"read{n}"] = spec.known_values().get, spec.read
            text = f"(fields[{pos}], fields[{pos} + 1])" if spec.width == 2 else f"fields[{pos}]"
            expr = f"known{n}({text}) or read{n}(fields, {pos}, address, {name})"
            return (
                f"({expr}) if {text} else None"
                if isinstance(spec, _Memo) and spec.width == 1
                else expr
            )

        group = self.group
        code = [
            'def parse(cls, address, fields, checksum="upper", line=None):',
            "    count = len(fields)",
        ]
        if group is None:
            code += [
                f"    if count < {self.fixed}:",
                f"        raise too_few(address, {self.sentence!r}, {self.fixed}, count)",
                f"    if count > {self.max_fields}:",
                f"        raise too_many(address, {self.sentence!r}, {self.max_fields}, count)",
                f"    optional = count - {self.fixed}",
            ]
        else:
            code.append(
                f"    repeats, optional = split_group(address, {self.sentence!r}, {group.id!r}, count, "
                f"{self.fixed}, {group.width}, {group.minimum}, {group.maximum}, {self.optional_max})"
            )
        values, at, pos = [], 0, "0"
        for n, item in enumerate(self.items):
            values.append(f"v{n}")
            if isinstance(item, Group):
                code += [
                    f"    v{n} = []",
                    f"    pos = {at}",
                    "    try:",
                    "        for n in range(repeats):",
                ]
                if item.entry is None:
                    (f,) = item.fields
                    code.append(f"            v{n}.append({read(f, f'{n}_0', 'pos', repr(f.id))})")
                else:
                    names[f"entry{n}"] = item.entry
                    args = ", ".join(
                        read(f, f"{n}_{k}", f"pos + {f.offset}", repr(f.id))
                        for k, f in enumerate(item.fields)
                    )
                    code.append(f"            v{n}.append(entry{n}({args}))")
                code += [
                    f"            pos += {item.width}",
                    "    except NmeaError as error:",
                    f'        error.name = f"{item.id}[{{n + 1}}].{{error.name}}"',
                    "        raise",
                ]
                at, pos = 0, "pos"
                continue
            place = f"{pos} + {at}" if pos == "pos" else str(at)
            if item.optional_index:
                code += [
                    f"    v{n} = ABSENT",
                    f"    if optional >= {item.optional_index}:",
                    f"        v{n} = {read(item, str(n), place, repr(item.id))}",
                ]
            else:
                code.append(f"    v{n} = {read(item, str(n), place, repr(item.id))}")
            at += item.width
        # a standard sentence's talker: its address but the formatter (two talker IDs of a query)
        head = {"standard": [f"address[:{-len(self.sentence)}]"], "proprietary": [], "text": ["line"]}[self.kind]
        tail = ["[]"] if self.kind == "text" else ["[]", "checksum"]
        code.append(f"    return cls({', '.join(head + values + tail)})")
        exec("\n".join(code), names)  # noqa: S102 (source made above from the layout's own items)
        parse: Callable[..., Any] = names["parse"]
        return parse

    def _compile_writer(self) -> Callable[[Any], list[str]]:
        """write(sentence): the wire text of every field after the address, optional trailing
        fields up to the last one present."""
        names: dict[str, Any] = {
            "text_of": text_of,
            "pair": _coordinate_pair,
            "ABSENT": ABSENT,
            "_Value": _Value,
        }

        def texts(spec: FieldSpec, value: str) -> str:
            return f"*pair({value})" if spec.width == 2 else f"text_of({value})"

        def in_line(spec: FieldSpec, value: str) -> str:
            return _in_line(spec, value, names)

        def body(texts: Callable[[FieldSpec, str], str]) -> list[str]:
            """The lines of write after its first, each field's text by `texts`."""
            code = ["    out = []"]
            for item in self.items:
                if isinstance(item, Group):
                    if item.entry is None:
                        code.append(f"    out += [{texts(item.fields[0], 'e')} for e in s.{item.id}]")
                    else:
                        entry = ", ".join(texts(f, f"e.{f.id}") for f in item.fields)
                        code += [f"    for e in s.{item.id}:", f"        out += [{entry}]"]
                elif not item.optional_index:
                    code.append(f"    out += [{texts(item, f's.{item.id}')}]")
            if trailing:
                for n, item in enumerate(reversed(trailing)):
                    code += [
                        f"    {'if' if n == 0 else 'elif'} s.{item.id} is not ABSENT:",
                        f"        last = {item.optional_index}",
                    ]
                code += ["    else:", "        last = 0"]
                for item in trailing:
                    code += [
                        f"    if last >= {item.optional_index}:",
                        f"        out += [{texts(item, f's.{item.id}')}]",
                    ]
            code.append("    return out")
            # consecutive fields' texts in one list display (most layouts: all of them, returned)
            merged: list[str] = []
            for line in code:
                if (
                    merged
                    and line.startswith("    out += [")
                    and merged[-1].startswith("    out += [")
                    and " for e in " not in line + merged[-1]  # a group's comprehension
                ):
                    merged[-1] = merged[-1][:-1] + ", " + line[len("    out += [") :]
                else:
                    merged.append(line)
            single = len(merged) == 3 and merged[0] == "    out = []" and merged[2] == "    return out"
            if single and merged[1].startswith("    out += ["):
                merged = ["    return " + merged[1][len("    out += ") :]]
            return merged

        trailing = [
            item for item in self.items if isinstance(item, FieldSpec) and item.optional_index
        ]
        # the texts in line first; a value that has not worked its text out yet, by text_of
        merged = [
            "def write(s):",
            "    try:",
            *("    " + line for line in body(in_line)),
            "    except AttributeError:",
            "        pass",
            *body(texts),
        ]
        exec("\n".join(merged), names)  # noqa: S102 (source made above from the layout's own items)
        write: Callable[[Any], list[str]] = names["write"]
        return write

    def _compile_joined(self) -> Callable[[Any, str], str] | None:
        """joined(sentence, address): the address and every field's text, joined by commas, in one
        f-string (write's texts in line); None for a layout with a group, optional fields or a
        field of two."""
        fields = [item for item in self.items if isinstance(item, FieldSpec)]
        if len(fields) != len(self.items) or any(f.optional_index or f.width != 1 for f in fields):
            return None
        names: dict[str, Any] = {"text_of": text_of, "_Value": _Value, "write": self.write}
        texts = "".join(f",{{{_in_line(f, f's.{f.id}', names)}}}" for f in fields)
        code = [
            "def joined(s, address):",
            "    try:",
            f"        return f'{{address}}{texts}'",
            "    except AttributeError:  # a value that has not worked its text out yet",
            "        return ','.join([address, *write(s)])",
        ]
        exec("\n".join(code), names)  # noqa: S102 (source made above from the layout's own items)
        joined: Callable[[Any, str], str] = names["joined"]
        return joined

    def _compile_standard(self, fallback: Callable[[Any], str]) -> Callable[[Any], str] | None:
        """to_sentence(s) of a standard sentence whose fields joined writes: _compile_joined's
        f-string of its talker, address and fields, then checksum (up to 128 bytes) in line;
        `fallback` writes a sentence with problems or a value without its text. None for a
        layout without joined."""
        fields = [item for item in self.items if isinstance(item, FieldSpec)]
        if self.joined is None or self.kind != "standard":
            return None
        names: dict[str, Any] = {"text_of": text_of, "_Value": _Value, "fallback": fallback,
                                 "checksummed": checksummed, "checksum": checksum, "HEX": _CHECKSUM_HEX}
        texts = "".join(f",{{{_in_line(f, f's.{f.id}', names)}}}" for f in fields)
        start, suffix = self.start, self.sentence
        code = [
            "def to_sentence(s):",
            "    if s.problems:",
            "        return fallback(s)",
            "    try:",
            f"        body = f'{{s.talker}}{suffix}{texts}'",
            "    except AttributeError:  # a value that has not worked its text out yet",
            "        return fallback(s)",
            "    size = len(body)",
            "    if s.checksum != 'upper' or size > 128:",
            f"        return checksummed({start!r}, body, s.checksum)",
            "    value = int.from_bytes(body.encode('latin-1'), 'little')  # checksum in line",
            "    if size > 64:",
            "        value ^= value >> 512",
            "    if size > 32:",
            "        value ^= value >> 256",
            "    if size > 16:",
            "        value ^= value >> 128",
            "    value ^= value >> 64",
            "    value ^= value >> 32",
            "    value ^= value >> 16",
            f"    return f'{start}{{body}}*{{HEX[(value ^ value >> 8) & 255]}}'",
        ]
        exec("\n".join(code), names)  # noqa: S102 (source made above from the layout's own items)
        to_sentence: Callable[[Any], str] = names["to_sentence"]
        return to_sentence

    def sentence_writer(self, address: str) -> Callable[[Any], str]:
        """to_sentence(sentence): its text (see Sentence.to_sentence), `address` that of a
        proprietary sentence or text command."""
        write, joined, start, suffix = self.write, self.joined, self.start, self.sentence

        def text_command(s: Any) -> str:
            return assemble_text(address, with_problems(write(s), s.problems), s.as_received)

        def standard(s: Any) -> str:
            if joined is None or s.problems:
                return assemble(start, s.talker + suffix, with_problems(write(s), s.problems), s.checksum)
            body = joined(s, s.talker + suffix)
            if s.checksum == "upper":  # checksummed's usual case in line
                return f"{start}{body}*{_CHECKSUM_HEX[checksum(body)]}"
            return checksummed(start, body, s.checksum)

        def proprietary(s: Any) -> str:
            return assemble(start, address, with_problems(write(s), s.problems), s.checksum)

        def general(s: Any) -> str:
            return assemble(start, s.talker + suffix, with_problems(write(s), s.problems), s.checksum)

        compiled = self._compile_standard(general)
        if compiled is not None:
            return compiled
        return {"text": text_command, "standard": standard}.get(self.kind, proprietary)

    def json(self, sentence: Any, values: bool) -> str:
        """The `fields` object of the tools' JSON (`values`: decoded values instead of texts)."""
        writer = self._json_writers[values]
        if writer is None:
            writer = self._json_writers[values] = self._compile_json(values)
        return writer(sentence)

    def _compile_json(self, values: bool) -> Callable[[Any], str]:
        """json(sentence) for one form, compiled once as the reader is (decode writes every line
        of a log): one f-string of the members in wire order, a group's entries joined before it,
        each optional trailing field appended when present."""
        names: dict[str, Any] = {
            "show": value_json if values else text_json,
            "show1": value_json if values else field_text_json,
            "ABSENT": ABSENT,
        }

        def member(spec: FieldSpec, owner: str) -> str:
            show = "show" if spec.width == 2 else "show1"
            return f'"{spec.id}":{{{show}({owner}.{spec.id})}}'

        code = ["def json(s):"]
        required: list[str] = []
        optional: list[FieldSpec] = []
        for n, item in enumerate(self.items):
            if isinstance(item, Group):
                if item.entry is None:
                    show = "show" if item.fields[0].width == 2 else "show1"
                    entries = f"{show}(e) for e in s.{item.id}"
                else:
                    entry = ",".join(member(f, "e") for f in item.fields)
                    entries = f"f'{{{{{entry}}}}}' for e in s.{item.id}"
                code.append(f"    entries{n} = ','.join([{entries}])")
                required.append(f'"{item.id}":[{{entries{n}}}]')
            elif item.optional_index:
                optional.append(item)
            else:
                required.append(member(item, "s"))
        # Each optional member is written with a comma before it; without a required member, the
        # first comma is dropped at the end.
        code.append(f"    text = f'{{{{{','.join(required)}'" if required else "    text = ''")
        for item in optional:
            code += [
                f"    if s.{item.id} is not ABSENT:",
                f"        text += f',{member(item, 's')}'",
            ]
        code.append("    return text + '}'" if required else "    return '{' + text[1:] + '}'")
        exec("\n".join(code), names)  # noqa: S102 (source made above from the layout's own items)
        json: Callable[[Any], str] = names["json"]
        return json

    def to_dict(self, sentence: Any) -> dict[str, Any]:
        """The fields of `sentence` as plain Python values (FieldSpec.plain), by field id; a
        group as a list of entries (a list of dicts, or of values for a group of one field)."""
        out: dict[str, Any] = {}
        for item in self.items:
            value = getattr(sentence, item.id)
            if isinstance(item, Group):
                if item.entry is None:
                    out[item.id] = [item.fields[0].plain(v) for v in value]
                else:
                    out[item.id] = [
                        {f.id: f.plain(getattr(e, f.id)) for f in item.fields} for e in value
                    ]
            else:
                out[item.id] = item.plain(value)
        return out

    def from_json(self, fields: dict[str, Any]) -> list[str]:
        """The wire fields described by a `fields` object of the tools' lossless JSON."""
        out: list[str] = []
        for item in self.items:
            if isinstance(item, Group):
                for entry in json_list(fields, item.id):
                    if item.entry is None:
                        out += json_texts(entry, item.width)
                    else:
                        for f in item.fields:
                            out += json_texts(json_member(entry, f.id), f.width)
            elif item.optional_index:
                if item.id in fields:
                    out += json_texts(fields[item.id], item.width)
            else:
                out += json_texts(json_member(fields, item.id), item.width)
        return out


SentenceT = TypeVar("SentenceT", bound="Sentence")


class Sentence:
    """The base of every generated sentence class: reading, writing and JSON through its
    LAYOUT. A standard sentence's class starts with `talker`, a text command's with
    `as_received`; then come the items of the layout, `problems` and (but for a text command)
    `checksum`."""

    __slots__ = ()

    LAYOUT: ClassVar[Layout]
    SENTENCE: ClassVar[str]
    ADDRESS: ClassVar[str | None]
    SAME_AS_MAIN: ClassVar[frozenset[int]] = frozenset()
    """A variant: the wire fields (1-based) it reads as its main layout does (see api._first_fit)."""
    DERIVED: ClassVar[tuple[str, ...]] = ()
    """The sentence-level values the class derives from its fields (latitude, longitude,
    datetime), which to_dict gives beside the fields."""
    problems: list[NmeaError]

    def __init_subclass__(cls, **kwargs: Any) -> None:
        """A sentence class takes its layout's compiled reader and writer as its own methods:
        no call in between on the hot path."""
        super().__init_subclass__(**kwargs)
        layout = cls.__dict__.get("LAYOUT")
        if layout is not None:
            cls.parse_fields = classmethod(layout.parse)  # type: ignore[assignment]
            cls.fields = layout.write  # type: ignore[method-assign]
            cls.to_sentence = layout.sentence_writer(cls.ADDRESS or "")  # type: ignore[method-assign]

    @classmethod
    def parse_fields(
        cls: type[SentenceT],
        address: str,
        fields: list[str],
        checksum: str | None = "upper",
        line: str | None = None,
    ) -> SentenceT:
        """Decode the fields after the address; raises NmeaError naming the field at fault."""
        sentence: SentenceT = cls.LAYOUT.parse(cls, address, fields, checksum, line)
        return sentence

    def fields(self) -> list[str]:
        """The wire text of every field after the address."""
        return self.LAYOUT.write(self)

    def to_sentence(self) -> str:
        """The sentence text, checksum included unless `checksum` is None (a text command: its
        words separated by single spaces); no line ending."""
        return self.LAYOUT.sentence_writer(self.ADDRESS or "")(self)

    def to_bytes(self) -> bytes:
        """The exact bytes to send, CR LF included, once every field has been checked the way a
        receiver would read it; raises NmeaError naming the field at fault."""
        return checked_bytes(self.to_sentence(), self.parse_fields, self.LAYOUT.kind == "text")

    def fields_json(self, values: bool = False) -> str:
        """The `fields` object of the tools' JSON (`values`: decoded values instead of texts)."""
        if self.LAYOUT.kind == "text" and not values:
            return words_json(self.LAYOUT.field_ids, self.to_sentence())
        return self.LAYOUT.json(self, values)

    def to_dict(self) -> dict[str, Any]:
        """The sentence as plain Python values, for pandas, JSON or a database: `talker` (a
        standard sentence), each field by id (FieldSpec.plain: numbers as int or float, times and
        dates as datetime's, coordinates as signed degrees, enums as value ids, groups as lists)
        and the DERIVED values (latitude, longitude, datetime)."""
        out: dict[str, Any] = {"talker": self.talker} if hasattr(self, "talker") else {}
        out.update(self.LAYOUT.to_dict(self))
        for name in self.DERIVED:
            out[name] = getattr(self, name)
        return out

    @classmethod
    def fields_from_json(cls, fields: dict[str, Any]) -> list[str]:
        """The wire fields described by a `fields` object of the tools' lossless JSON."""
        return cls.LAYOUT.from_json(fields)
