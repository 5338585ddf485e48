"""u-blox UBX frames: the framing layer (spec/binary/ubx/protocol.yaml) and the base of the
generated message classes (nmeaspec.ubx_messages, from spec/binary/ubx/messages).

A frame is the sync bytes B5 62, a class and an id byte, the payload's length (two bytes, little
endian, the payload alone) and the payload, closed by a Fletcher-8 checksum over class..payload.
A frame decodes to its class, id and payload and encodes back to the same bytes. A payload is
read and written by the field classes and item walkers of the AIS payloads (ais.py: one model of
payloads) through ByteReader and ByteWriter, which hold the little-endian byte order: offsets and
widths stay in bits, whole bytes here. A message decodes into the class of its layout and encodes
back to the same bytes (reserved bytes, bits of a bitfield no part names and bytes after the
layout are kept); a frame of a class/id the spec does not describe stays an Unknown with its
payload. Facts from u-blox UBX-13003221 (u-blox 8 / M8 Receiver description, "UBX protocol":
frame structure and checksum).
"""

from __future__ import annotations

import math
import struct
from collections.abc import Iterator
from dataclasses import MISSING, dataclass, fields as dataclass_fields, replace
from zlib import adler32
from typing import Any, ClassVar, Literal

from .ais import (Bitfield, Code, Field, Flag, Group, Item, Signed, Spare, Special, Unsigned, _bad_value, flat_fields,
                  items_json, read_items, write_items)
from .runtime import NmeaError

__all__ = ["Bitfield", "Bytes", "ByteReader", "ByteWriter", "Chars", "Float", "Frame", "Group", "Message",
           "NmeaError", "Unknown", "answers", "decode", "decode_frame", "fletcher8", "frame_size", "layout_for",
           "main_layout", "message", "split_frames"]

SYNC = b"\xb5\x62"
HEADER_SIZE = 6  # sync, class, id, length
CHECKSUM_SIZE = 2


def fletcher8(data: bytes) -> bytes:
    """The two checksum bytes (CK_A, CK_B) of `data`: 8-bit Fletcher, both sums modulo 256. CK_A
    after each byte is the running sum of the bytes, CK_B the sum of those running sums."""
    return bytes(_fletcher(data))


_LOW = bytes(i & 15 for i in range(256))
_HIGH = bytes(i >> 4 for i in range(256))
_CHUNK = 92


def _fletcher(data: bytes | bytearray) -> tuple[int, int]:
    """CK_A and CK_B of `data`, summed in C rather than byte by byte: zlib's Adler-32 of a chunk
    is 1 + its sum S and n + its sum of running sums B (n bytes), both modulo 65521. Over the low
    and the high nibbles of the bytes apart (bytes.translate), a chunk of up to 92 bytes keeps
    both below 65521 (15 * 92 * 93 / 2 + 92 = 64,262), so they are exact: S = S_low + 16 S_high,
    B = B_low + 16 B_high. Chunks add up: a chunk's S counts once more for each byte after it."""
    if not isinstance(data, (bytes, bytearray)):
        data = bytes(data)
    n = len(data)
    low, high = data.translate(_LOW), data.translate(_HIGH)
    if n <= _CHUNK:
        a_low, a_high = adler32(low), adler32(high)
        return ((a_low & 0xFFFF) - 1 + 16 * ((a_high & 0xFFFF) - 1)) & 0xFF, \
            ((a_low >> 16) - n + 16 * ((a_high >> 16) - n)) & 0xFF
    total = running = 0
    for start in range(0, n, _CHUNK):
        end = min(start + _CHUNK, n)
        a_low, a_high = adler32(low[start:end]), adler32(high[start:end])
        chunk = (a_low & 0xFFFF) - 1 + 16 * ((a_high & 0xFFFF) - 1)
        running += (a_low >> 16) - (end - start) + 16 * ((a_high >> 16) - (end - start)) + (n - end) * chunk
        total += chunk
    return total & 0xFF, running & 0xFF


@dataclass(frozen=True)
class Frame:
    msg_class: int
    msg_id: int
    payload: bytes

    @property
    def address(self) -> str:
        """Errors' address until the message layouts name the frame: "UBX 0x01 0x07"."""
        return f"UBX 0x{self.msg_class:02X} 0x{self.msg_id:02X}"

    def encode(self) -> bytes:
        body = bytes((self.msg_class, self.msg_id)) + len(self.payload).to_bytes(2, "little") + self.payload
        return SYNC + body + fletcher8(body)


class ByteReader:
    """A payload's fields, little endian (UBX, CASIC) or big endian (SkyTraq, SiRF), with
    BitReader's interface (ais.read_items walks either): offsets and widths in bits, each a whole
    number of bytes."""

    __slots__ = ("payload", "length", "pos", "where", "order")

    def __init__(self, payload: bytes, where: str, order: Literal["little", "big"] = "little") -> None:
        self.payload = payload
        self.length = 8 * len(payload)
        self.pos = 0
        self.where = where  # errors' address: "UBX NAV-PVT"
        self.order: Literal["little", "big"] = order

    @property
    def remaining(self) -> int:
        return self.length - self.pos

    def peek(self, offset: int, width: int, name: str) -> int:
        first, last = offset // 8, (offset + width) // 8 - 1
        if offset + width > self.length:
            where = f"byte {first}" if first == last else f"bytes {first}-{last}"
            raise NmeaError("short_payload", f"{name} needs {where}, the payload has {len(self.payload)}", self.where,
                            name=name)
        return int.from_bytes(self.payload[first:last + 1], self.order)

    def take(self, width: int, name: str) -> int:
        raw = self.peek(self.pos, width, name)
        self.pos += width
        return raw


class ByteWriter:
    """A payload's fields written in a byte order, with BitWriter's interface (ais.write_items)."""

    __slots__ = ("payload", "order")

    def __init__(self, order: Literal["little", "big"] = "little") -> None:
        self.payload = bytearray()
        self.order: Literal["little", "big"] = order

    def put(self, raw: int, width: int) -> None:
        self.payload += raw.to_bytes(width // 8, self.order)


def frame_size(data: bytes | bytearray | memoryview, start: int = 0) -> int:
    """The size of the frame whose sync bytes are at `start`, read from its length field."""
    if len(data) - start < HEADER_SIZE:
        raise NmeaError("short_frame", f"a UBX header needs {HEADER_SIZE} bytes, there are {len(data) - start}", "UBX")
    return HEADER_SIZE + int.from_bytes(data[start + 4:start + 6], "little") + CHECKSUM_SIZE


def decode_frame(data: bytes) -> Frame:
    """The one frame `data` holds, its sync bytes, length and checksum checked."""
    if not SYNC.startswith(data[:2]):  # a cut-off start is short_frame below
        raise NmeaError("bad_sync", f"a UBX frame starts with B5 62, not {data[:2].hex(' ').upper()}", "UBX")
    size = frame_size(data)
    frame = Frame(data[2], data[3], bytes(data[HEADER_SIZE:size - CHECKSUM_SIZE]))
    if len(data) < size:
        raise NmeaError("short_frame", f"the length field says {size} bytes, the frame has {len(data)}", frame.address)
    if len(data) > size:
        raise NmeaError("long_frame", f"the length field says {size} bytes, the frame has {len(data)}", frame.address)
    expected = fletcher8(data[2:size - CHECKSUM_SIZE])
    if data[size - CHECKSUM_SIZE:size] != expected:
        raise NmeaError("bad_checksum", f"checksum {data[-2:].hex(' ').upper()}, computed "
                        f"{expected.hex(' ').upper()}", frame.address)
    return frame


def split_frames(data: bytes) -> Iterator[tuple[int, Frame]]:
    """The valid frames in a stream that mixes them with text (NMEA) and noise, each with its
    offset. A sync pair whose frame is cut short or fails its checksum is skipped byte by byte, as
    a receiver resynchronizes; so is one whose header is NUL bytes (class 0, id 0, length 0: what a
    line break's NULs after a sync make, its checksum of NULs matching), as the stream readers do."""
    pos = data.find(SYNC)
    while pos >= 0:
        if not any(data[pos + 2:pos + 6]) and len(data) >= pos + 6:
            pos = data.find(SYNC, pos + 1)
            continue
        try:
            size = frame_size(data, pos)
            frame = decode_frame(data[pos:pos + size])
        except NmeaError:
            pos = data.find(SYNC, pos + 1)
            continue
        yield pos, frame
        pos = data.find(SYNC, pos + size)


@dataclass(frozen=True, slots=True)
class Float(Field):
    """r4, r8: an IEEE 754 float, little endian. A NaN is a Special("nan", raw) that keeps its bits
    (a float would lose a single's payload); JSON: "nan", and the infinities "inf", "-inf". The
    field's special values (SBF's do-not-use -2e10) are Specials whose raw is the float's bit
    pattern in the field's width, compared bit for bit; JSON: their ids."""

    special: tuple[Special, ...] = ()

    def from_raw(self, raw: int, width: int) -> Any:
        for s in self.special:
            if s.raw == raw:
                return s
        value = struct.unpack("<f" if width == 32 else "<d", raw.to_bytes(width // 8, "little"))[0]
        return value if value == value else Special("nan", raw)

    def to_raw(self, value: Any, where: str) -> tuple[int, int]:
        assert self.width is not None
        if isinstance(value, Special):
            return value.raw, self.width
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            raise _bad_value(where, self.id, value, "a number")
        return int.from_bytes(struct.pack("<f" if self.width == 32 else "<d", value), "little"), self.width

    def put_json(self, out: dict[str, Any], value: Any) -> None:
        out[self.id] = str(value) if isinstance(value, Special) or not math.isfinite(value) else value


@dataclass(frozen=True, slots=True)
class Chars(Field):
    """ch: characters as sent, ISO 8859-1, NUL padding included; without a width, the bytes left.
    `big`: of a big-endian protocol, whose reader gives the bytes' big-endian integer."""

    big: bool = False

    def from_raw(self, raw: int, width: int) -> Any:
        return raw.to_bytes(width // 8, "big" if self.big else "little").decode("latin-1")

    def to_raw(self, value: Any, where: str) -> tuple[int, int]:
        data = value.encode("latin-1", "replace") if isinstance(value, str) else None
        if data is None or self.width is not None and 8 * len(data) != self.width:
            size = f"{self.width // 8} " if self.width is not None else ""
            raise _bad_value(where, self.id, value, f"a text of {size}ISO 8859-1 characters")
        return int.from_bytes(data, "big" if self.big else "little"), 8 * len(data)


@dataclass(frozen=True, slots=True)
class Bytes(Field):
    """bytes: binary data as sent (JSON: lower-case hex); without a width, the bytes left.
    `big`: as Chars."""

    big: bool = False

    def from_raw(self, raw: int, width: int) -> Any:
        return raw.to_bytes(width // 8, "big" if self.big else "little")

    def to_raw(self, value: Any, where: str) -> tuple[int, int]:
        if not isinstance(value, bytes) or self.width is not None and 8 * len(value) != self.width:
            raise _bad_value(where, self.id, value, "bytes" if self.width is None else f"{self.width // 8} bytes")
        return int.from_bytes(value, "big" if self.big else "little"), 8 * len(value)

    def put_json(self, out: dict[str, Any], value: Any) -> None:
        out[self.id] = value.hex()


_INTEGER_CODES = {8: "B", 16: "H", 32: "I", 64: "Q"}
MEMO_PARTS = 4   # a bitfield of this many parts or more: its parts' values remembered by word
MEMO = 4096      # words remembered per bitfield, at most


def _struct_code(f: Field) -> str | None:
    """The struct code that reads field `f` whole (None: a width no code reads); a float is read as
    its integer (Float.from_raw keeps a NaN's bits)."""
    width = f.width
    if width is None:
        return None
    if isinstance(f, (Chars, Bytes)):
        return f"{width // 8}s"
    code = _INTEGER_CODES.get(width, f"{width // 8}s" if type(f) is Spare else None)
    return code.lower() if code is not None and isinstance(f, Signed) else code


class _Compiler:
    """Straight-line source of a layout's decoder: struct.unpack_from for each run of fixed fields
    (into locals), a list comprehension over struct.iter_unpack for a group's entries, the values
    converted inline as the field classes convert them and put in one dict display, which becomes
    the message's __dict__ (the generic reader costs several calls a field; this one a call per
    run). Decoded values are exactly those of read_items, which tests/ubx checks frame by frame."""

    def __init__(self, big: bool = False) -> None:
        self.names: dict[str, Any] = {"Special": Special, "unpack_from": struct.unpack_from,
                                      "iter_unpack": struct.iter_unpack, "from_bytes": int.from_bytes,
                                      "new": object.__new__, "make": _make}
        self.lines: list[str] = []
        self.defs: list[str] = []
        self.locals = 0
        self.order = ">" if big else "<"  # the struct format's byte order

    def name(self, value: Any) -> str:
        key = f"n{len(self.names)}"
        self.names[key] = value
        return key

    def local(self) -> str:
        self.locals += 1
        return f"v{self.locals}"

    def parts(self, f: Bitfield, raw: str) -> str:
        """An expression of the tuple of bitfield `f`'s part values, its word `raw` (a local):
        a function of the word, remembered by word (the values are immutable; at most MEMO
        words), so that the words a receiver repeats (a satellite's flags) cost a lookup."""
        memo, function = self.name({}), f"parts{len(self.defs)}"
        values = []
        for low, part in f.parts:
            shifted = f"w >> {low}" if low else "w"
            values += [value for _, value in self.convert(part, f"({shifted} & {(1 << (part.width or 1)) - 1})")]
        self.defs += [f"def {function}(w):", f"    p = ({', '.join(values)},)",
                      f"    if len({memo}) < {MEMO}: {memo}[w] = p", "    return p"]
        return f"({memo}.get({raw}) or {function}({raw}))"

    def convert(self, f: Field, raw: str, statements: list[str] | None = None) -> list[tuple[str, str]]:
        """The (key, expression) pairs of field `f` (a bitfield's word, then its parts) whose raw
        value is `raw`, a local name or a parenthesized expression. A bitfield of MEMO_PARTS parts
        or more takes its parts from parts(): into a local, by a line added to `statements`, or
        (no `statements`: a group entry's arguments) as one starred pair ("*", "*(...)")."""
        if isinstance(f, Unsigned):
            number = raw
            if isinstance(f, Signed) and f.width is not None and not _struct_code(f):   # a part: sign by hand
                number = f"({raw} - {1 << f.width} if {raw} >> {f.width - 1} else {raw})"
            value = number if f.divisor == 1 else f"{number} / {f.divisor}"
            value += f" + {f.base!r}" if f.base or isinstance(f.base, float) else ""
            if f.special:
                value = f"{self.name({sp.raw: sp for sp in f.special})}.get({number}) or {value}"
            pairs = [(f.id, value)]
        elif isinstance(f, Flag):
            pairs = [(f.id, f"{raw} != 0")]
        elif isinstance(f, Code):
            # Code.from_raw looks str(raw) up among the values: those written in decimal, by number
            members = {int(m.value): m for m in f.enum
                       if isinstance(m.value, str) and m.value.isdigit() and str(int(m.value)) == m.value}
            pairs = [(f.id, f"{self.name(members)}.get({raw}, {raw})")]
        elif isinstance(f, Chars):
            pairs = [(f.id, f"{raw}.decode('latin-1')")]
        elif isinstance(f, Float):   # read as its integer: a NaN keeps its bits, a special value is its bits'
            value = f"{self.name(f)}.from_raw({raw}, {f.width})"
            if f.special:
                value = f"{self.name({sp.raw: sp for sp in f.special})}.get({raw}) or {value}"
            pairs = [(f.id, value)]
        elif type(f) is Spare and f.width not in _INTEGER_CODES:
            pairs = [(f.id, f"from_bytes({raw}, '{'big' if self.order == '>' else 'little'}')")]
        else:   # a whole integer, bytes
            pairs = [(f.id, raw)]
        if isinstance(f, Bitfield) and len(f.parts) >= MEMO_PARTS:
            found = self.parts(f, raw)
            if statements is None:
                return [*pairs, ("*", f"*{found}")]
            local = self.local()
            statements.append(f"{local} = {found}")
            return [*pairs, *((part.id, f"{local}[{i}]") for i, (_, part) in enumerate(f.parts))]
        if isinstance(f, Bitfield):
            for low, part in f.parts:
                shifted = f"{raw} >> {low}" if low else raw
                pairs += self.convert(part, f"({shifted} & {(1 << (part.width or 1)) - 1})")
        return pairs

    def run(self, fields: list[Field], statements: list[str]) -> tuple[str, list[str], list[tuple[str, str]]]:
        """The struct format that reads the fixed `fields`, the locals it unpacks them into and
        their (key, expression) pairs (with the lines that compute some, added to `statements`)."""
        fmt = self.order + "".join(_struct_code(f) or "" for f in fields)
        names = [self.local() for _ in fields]
        pairs = [pair for f, raw in zip(fields, names) for pair in self.convert(f, raw, statements)]
        return fmt, names, pairs


def _display(pairs: list[tuple[str, str]]) -> str:
    return "{" + ", ".join(f"{key!r}: {value}" for key, value in pairs) + "}"


def _instance(c: _Compiler, cls: type[Message], pairs: list[tuple[str, str]], pos: str) -> str:
    """An expression of the message whose members the `pairs` read (the others their defaults)
    and whose trailing bytes start at `pos`: what cls(**values, trailing=...) makes, without the
    call (the instance takes the dict of its members as its __dict__: those read and trailing,
    or with some left to their defaults, every member in its fields' order, as __init__ sets
    them)."""
    found = dict(pairs)
    trailing = ("trailing", f"payload[{pos}:]")
    if found.keys() == {f.name for f in dataclass_fields(cls)} - {"trailing"}:   # every member read
        return f"make(cls, {_display([*pairs, trailing])})"
    members: list[tuple[str, str]] = []
    for f in dataclass_fields(cls):
        if f.name == "trailing":
            members.append(trailing)
        elif f.name in found:
            members.append((f.name, found.pop(f.name)))
        elif f.default is not MISSING:
            members.append((f.name, "None" if f.default is None else c.name(f.default)))
        elif f.default_factory is not MISSING:
            members.append((f.name, f"{c.name(f.default_factory)}()"))
        else:
            found[f.name] = ""   # no value: the call says so
    if found:   # a member the class does not have, or one without a value
        return f"cls(**{_display(pairs)}, trailing=payload[{pos}:])"
    return f"make(cls, {_display(members)})"


def _make(cls: type[Message], members: dict[str, Any]) -> Message:
    message = object.__new__(cls)
    message.__dict__ = members
    return message


def compile_reader(cls: type[Message]) -> Any:
    """`read(payload)` of a layout: the message of `payload`, by the generic reader when the
    payload is not one it reads whole (too short, a count too large: the generic reader then says
    where); None for a layout with what it does not compile (a choice; a group of variable
    entries)."""
    items = cls.LAYOUT
    c = _Compiler(cls.BIG)
    c.names["cls"], c.names["generic"] = cls, cls.read_generic
    pos = "0"
    fixed: list[Field] = []
    pairs: list[tuple[str, str]] = []
    pad = "    "

    def flush() -> None:
        nonlocal pos, fixed
        if not fixed:
            return
        statements: list[str] = []
        fmt, names, found = c.run(fixed, statements)
        size = struct.calcsize(fmt)
        c.lines += [f"{pad}if len(payload) < {pos} + {size}: return generic(payload)",
                    f"{pad}{', '.join(names)}, = unpack_from({fmt!r}, payload, {pos})",
                    *(pad + line for line in statements)]
        pairs.extend(found)
        pos = f"{pos} + {size}" if pos != "0" else str(size)
        fixed = []

    for index, item in enumerate(items):
        if isinstance(item, Field) and _struct_code(item) and not item.optional:
            fixed.append(item)
            continue
        flush()
        if isinstance(item, Field) and item.optional and _struct_code(item):
            size = (item.width or 0) // 8
            # without its bytes, the message of the fields before it (the others left None)
            c.lines.append(f"{pad}if len(payload) < {pos} + {size}: return {_instance(c, cls, pairs, pos)}")
            fixed.append(item)
            flush()
        elif isinstance(item, (Chars, Bytes)) and item.width is None and index == len(items) - 1:
            rest = c.local()
            c.lines.append(f"{pad}{rest} = payload[{pos}:]")
            pairs += c.convert(item, rest)
            pos = "len(payload)"
        elif isinstance(item, Group) and not isinstance(item.count, tuple) \
                and len(fields := [f for f in item.fields if isinstance(f, Field)]) == len(item.fields) \
                and all(_struct_code(f) for f in fields):   # (a count of mask bits: RTCM 3's, read generically)
            entry = c.name(item.entry)
            fmt = c.order + "".join(_struct_code(f) or "" for f in fields)
            size = struct.calcsize(fmt)
            if isinstance(item.count, int):
                count = str(item.count)
            elif isinstance(item.count, str):
                count = f"({dict(pairs)[item.count]})"
            else:
                count = f"min({item.max}, (len(payload) - ({pos}) - {item.after // 8}) // {size})"
            counted, end, entries = c.local(), c.local(), c.local()
            c.lines += [f"{pad}{counted} = {count}",
                        f"{pad}{end} = {pos} + {counted} * {size}",
                        f"{pad}if {counted} < {item.min} or len(payload) < {end}: return generic(payload)"]
            names = [c.local() for _ in fields]
            values = [value for f, raw in zip(fields, names) for _, value in c.convert(f, raw)]
            c.lines.append(f"{pad}{entries} = [{entry}({', '.join(values)}) for {', '.join(names)}, "
                           f"in iter_unpack({fmt!r}, payload[{pos}:{end}])]")
            pairs.append((item.id, entries))
            pos = end
        else:
            return None
    flush()
    instance = _instance(c, cls, pairs, pos)
    if instance.startswith("make("):   # inline
        instance = instance[len("make(cls, "):-1]
        end_lines = ["    message = new(cls)", f"    message.__dict__ = {instance}", "    return message"]
    else:
        end_lines = [f"    return {instance}"]
    body = [*c.defs, "def read(payload):", *c.lines, *end_lines]
    exec("\n".join(body), c.names)  # code built above from the generated layout, never from input
    return c.names["read"]


@dataclass(kw_only=True)
class Message:
    """A decoded UBX message, one layout of a class and id (the generated classes of
    nmeaspec.ubx_messages): its fields, then the payload's bytes after the layout, as sent."""

    trailing: bytes = b""
    """Bytes after the layout's last field, as sent (a newer firmware's additions)."""

    ID: ClassVar[str]
    """The spec's id of the layout (`nav_pvt`, `nav_pvt_poll`)."""
    ADDRESS: ClassVar[str]
    """How u-blox names the message: NAV-PVT."""
    CLASS: ClassVar[int]
    MSG_ID: ClassVar[int]
    DIRECTIONS: ClassVar[tuple[str, ...]]
    """Who sends it: "poll" and "input" go to the receiver, "output" comes from it."""
    LENGTH: ClassVar[int | None]
    """The payload's bytes, when the layout fixes them."""
    SELECT: ClassVar[tuple[str, int, int] | None]
    """The field (its id and byte) whose value tells it from another layout of its class and id,
    and that value: a type, command or version byte (("type", 0, 0x10))."""
    REPLIES: ClassVar[tuple[str, ...]]
    """The layouts (ids) the receiver answers it with."""
    ACKNOWLEDGES: ClassVar[tuple[str, str] | None] = None
    """An acknowledgement: its members that hold the class and id of the message it answers."""
    PROTOCOL: ClassVar[str] = "UBX"
    """How errors and documents name its protocol (the generated classes of other protocols: SKYTRAQ, SIRF, CASIC)."""
    BIG: ClassVar[bool] = False
    """Whether its protocol's fields are big endian (SkyTraq, SiRF)."""
    LAYOUT: ClassVar[tuple[Item, ...]]
    FIELDS: ClassVar[dict[str, Field]]
    _read: ClassVar[Any]
    """The layout's compiled reader (compile_reader), made on first use; False: none."""

    def __init_subclass__(cls, **kwargs: Any) -> None:
        super().__init_subclass__(**kwargs)
        if "LAYOUT" in cls.__dict__:
            cls.FIELDS = {f.id: f for f in flat_fields(cls.LAYOUT)}

    @classmethod
    def fits(cls, payload: bytes) -> bool:
        """Whether `payload` has this layout's length (a fixed one) and its selector's value (when
        it has one)."""
        if cls.LENGTH is not None and len(payload) != cls.LENGTH:
            return False
        if cls.SELECT is not None:
            _, at, value = cls.SELECT
            return at < len(payload) and payload[at] == value
        return True

    @classmethod
    def from_payload(cls, payload: bytes) -> Message:
        """The message of `payload`, read as this layout: by its compiled reader, else (a payload
        it does not read whole) by the generic one, which names what is missing."""
        read: Any = cls.__dict__.get("_read")
        if read is None:
            read = cls._read = compile_reader(cls) or False
        return read(payload) if read else cls.read_generic(payload)

    @classmethod
    def read_generic(cls, payload: bytes) -> Message:
        """The message of `payload` read field by field by ais.read_items."""
        reader = ByteReader(payload, f"{cls.PROTOCOL} {cls.ADDRESS}", "big" if cls.BIG else "little")
        values: dict[str, Any] = {}
        read_items(cls.LAYOUT, reader, values)
        return cls(**values, trailing=payload[reader.pos // 8:])

    def payload(self) -> bytes:
        """The payload it is sent as; a count left None is written as its group's number of
        entries, a selector (type, version) left None as the layout's value (the message itself is
        left as it is); a stride (SBF's SBLength) left None as the bytes of the first entry."""
        implied: dict[str, Any] = {}
        if self.SELECT is not None and getattr(self, self.SELECT[0]) is None:
            implied[self.SELECT[0]] = self.SELECT[2]
        for group in self.LAYOUT:
            if not isinstance(group, Group):
                continue
            entries = getattr(self, group.id)
            if isinstance(group.count, str) and getattr(self, group.count) is None:
                implied[group.count] = len(entries)
            if group.stride is not None and getattr(self, group.stride) is None:   # the first entry's bytes
                implied[group.stride] = group.entry_width // 8 + (len(entries[0].trailing or b"") if entries else 0)
            nested = group.nested
            if nested is not None and nested.stride is not None and getattr(self, nested.stride) is None:
                inner = [e for entry in entries for e in getattr(entry, nested.id)]
                implied[nested.stride] = nested.entry_width // 8 + (len(inner[0].trailing or b"") if inner else 0)
        writer = ByteWriter("big" if self.BIG else "little")
        message = replace(self, **implied) if implied else self
        write_items(self.LAYOUT, message, writer, f"{self.PROTOCOL} {self.ADDRESS}")
        return bytes(writer.payload) + self.trailing

    def frame(self) -> Frame:
        return Frame(self.CLASS, self.MSG_ID, self.payload())

    def encode(self) -> bytes:
        """The whole frame, sync bytes to checksum."""
        return self.frame().encode()

    def raw(self, name: str) -> int | None:
        """The raw integer of a scaled number's member; None when the member is None."""
        value = getattr(self, name)
        f = self.FIELDS[name]
        return None if value is None or not isinstance(f, Unsigned) else f.raw_number(value, "")

    def to_dict(self) -> dict[str, Any]:
        """The message as the decoded JSON of generated/vectors/ubx.jsonl: the layout's id as
        `message`, each field present by its id (a number in a unit beside its raw integer as
        <id>_raw, an enum value by its id, a bitfield's word and then its parts, characters as
        sent, bytes as hex), then the trailing bytes as hex."""
        return {"message": self.ID, **items_json(self.LAYOUT, self), "trailing": self.trailing.hex()}


def answers(request: Message, reply: Message | Unknown) -> bool:
    """Whether `reply` answers `request`: a layout the request's REPLIES names, and (an
    acknowledgement, ACK-ACK or ACK-NAK) one of the request's class and id (UBX-13003221: a CFG
    message is answered by one of them)."""
    if not isinstance(reply, Message) or reply.ID not in request.REPLIES:
        return False
    if reply.ACKNOWLEDGES is None:
        return True
    msg_class, msg_id = (getattr(reply, name) for name in reply.ACKNOWLEDGES)
    return (msg_class, msg_id) == (request.CLASS, request.MSG_ID)


@dataclass
class Unknown:
    """A frame of a class and id the spec does not describe, kept with its payload."""

    msg_class: int
    msg_id: int
    payload: bytes

    def encode(self) -> bytes:
        return Frame(self.msg_class, self.msg_id, self.payload).encode()

    def to_dict(self) -> dict[str, Any]:
        return {"message": None, "class": self.msg_class, "id": self.msg_id, "payload": self.payload.hex()}


def message(by_id: dict[tuple[int, int], tuple[type[Message], ...]], frame: Frame) -> Message | Unknown:
    """The message of `frame` as the layout of its class and id (in `by_id`, in spec order) that
    layout_for picks: the one whose length and selector's value (type, version) the payload has,
    else its main layout (the first the receiver sends: a short payload then names the field it
    cuts, a long one keeps the rest as trailing); an Unknown when no layout describes the class and
    id."""
    layouts = by_id.get((frame.msg_class, frame.msg_id))
    if not layouts:
        return Unknown(frame.msg_class, frame.msg_id, frame.payload)
    return layout_for(layouts, frame.payload).from_payload(frame.payload)


def decode(by_id: dict[tuple[int, int], tuple[type[Message], ...]], data: bytes) -> Message | Unknown:
    """message(by_id, decode_frame(data)): a frame whose sync, length and checksum are right and
    whose class and id `by_id` describes is read without building its Frame (the common case);
    anything else is decode_frame's, which says what is wrong."""
    size = len(data)
    if (size >= HEADER_SIZE + CHECKSUM_SIZE and data[0] == 0xB5 and data[1] == 0x62
            and size == HEADER_SIZE + CHECKSUM_SIZE + (data[4] | data[5] << 8)):
        body = bytes(data[2:size - CHECKSUM_SIZE])
        layouts = by_id.get((body[0], body[1]))
        n = len(body)
        if n <= _CHUNK:   # _fletcher's one chunk, inline
            low, high = adler32(body.translate(_LOW)), adler32(body.translate(_HIGH))
            right = ((low & 0xFFFF) - 1 + 16 * ((high & 0xFFFF) - 1)) & 0xFF == data[size - 2] \
                and ((low >> 16) - n + 16 * ((high >> 16) - n)) & 0xFF == data[size - 1]
        else:
            right = _fletcher(body) == (data[size - 2], data[size - 1])
        if layouts and right:
            payload = body[4:]
            if len(layouts) == 1:   # what fits, or else main_layout, is this one: from_payload's work
                read = layouts[0].__dict__.get("_read")
                return read(payload) if read else layouts[0].from_payload(payload)
            return layout_for(layouts, payload).from_payload(payload)
    return message(by_id, decode_frame(data))


def layout_for(layouts: tuple[type[Message], ...], payload: bytes) -> type[Message]:
    """The layout (of one class and id, in spec order) `payload` is read as: the first whose length
    and selector's value it has (Message.fits); else, a selector value no layout names (a type or
    version byte), the first selected layout of its fixed length, the byte kept as sent; else the
    main layout."""
    for cls in layouts:
        if cls.fits(payload):
            return cls
    size = len(payload)
    for cls in layouts:
        if cls.SELECT is not None and cls.LENGTH == size:
            return cls
    return main_layout(layouts)


def main_layout(layouts: tuple[type[Message], ...]) -> type[Message]:
    """The layout a payload of no layout's length is read as: the first output one, else the last."""
    return next((c for c in layouts if "output" in c.DIRECTIONS), layouts[-1])
