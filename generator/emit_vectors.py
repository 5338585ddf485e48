"""Language-neutral test vectors: every example of the manuals, with the JSON each tool must print,
lines outside what the manuals allow, with what each tool prints for them by its options, and the
fixes an assembler makes of the streams of spec/fix.yaml."""

from __future__ import annotations

import datetime
import hashlib
import json
import struct
from collections.abc import Iterator, Sequence
from contextlib import contextmanager
from typing import Any, Callable

import jinja2

from . import reference, reference_ais, reference_binary, reference_rtcm3
from .model import Payload, PayloadCase, PayloadChoice, PayloadField, PayloadGroup, PayloadItem, Spec


# One render pass decodes every example once: each emitter that shows the examples asks for them,
# and the spec does not change while they are rendered (render_all opens the pass).
_pass: dict[int, tuple[Spec, list[dict]]] | None = None


@contextmanager
def one_render_pass() -> Iterator[None]:
    global _pass
    _pass = {}
    try:
        yield
    finally:
        _pass = None


def example_vectors(spec: Spec) -> list[dict]:
    """Every example of the manuals with what the reference decodes of it (read, never changed, by
    the emitters)."""
    if _pass is None:
        return _example_vectors(spec)
    if id(spec) not in _pass:
        _pass[id(spec)] = (spec, _example_vectors(spec))
    return _pass[id(spec)][1]


def _example_vectors(spec: Spec) -> list[dict]:
    out = []
    for sentence in spec.sentences:
        for example in sentence.examples:
            manual = spec.manual(example.manual)
            line = example.line
            record: dict = {
                "manual": manual.file if manual and manual.file else example.manual,
                "manual_id": example.manual,
                "sentence": sentence.id,
                "where": example.where,
                "raw": example.raw,
                "checksum_ok": example.checksum_ok,
                "line": line,
            }
            if example.corrected:
                record["reason"] = example.reason
            if example.unrecoverable:
                record["unrecoverable"] = example.unrecoverable
            if line is not None:
                decoded = reference.decode(spec, line)
                assert decoded.layout is not None
                record["variant"] = decoded.layout.id
                record["expect"] = json.loads(reference.expect_json(decoded.layout, example.expect or {})[0])
                record["decode"] = reference.to_json(decoded)
                record["decode_values"] = reference.to_json(decoded, values=True)
            if line != example.raw:
                # As the tools read it: the text's UTF-8 bytes, one character a byte.
                record["raw_decode"] = reference.decode_json(spec, example.raw.encode("utf-8").decode("latin-1"))
            out.append(record)
    return out


# Lines that show how parsing treats a value outside what the manual allows, each decoded with
# the tools' options below: a number outside its range is kept and flagged unless --strict; an
# unknown code of a closed enum, or a line that a variant is not there for, is refused. A
# checksum of one hex digit equal to the sum (OpenCPN's instrument captures) is kept as sent and
# flagged (short_checksum) unless --strict, never when the digit differs; a decimal may end in
# its point (Signal K's `046.`), but a point alone, two points or a sign and a point are no number.
TOLERANCE_LINES = (
    "$PUBX,03,02,1,-,014,-1,08,000,12,U,207,-2,28,009*5C",  # u-blox: satellites below the horizon
    "$GPRMC,225446,A,4916.45,N,12311.12,W,000.5,454.7,191194,020.3,E*6C",  # course over 359.9
    "$GPRMC,225446,X,4916.45,N,12311.12,W,000.5,054.7,191194,020.3,E*71",  # status X: closed A/V
    "$GPRMC,225446,A,4916.45,Q,12311.12,W,000.5,054.7,191194,020.3,E*77",  # hemisphere Q: not `sentinel`
    "$IIRSA,28,A,,*b",  # OpenCPN's capture: the checksum 0B sent as one digit
    "$IIRSA,28,A,,*B",  # the same in upper case
    "$IIRSA,28,A,,*0b",  # the same in two digits
    "$IIRSA,28,A,,*c",  # one digit that is not the checksum: refused
    "$PXYZ,0AW*1",  # a sentence the spec does not describe, its checksum in one digit
    "$PUBX,03,02,1,-,014,-1,08,000,12,U,207,-2,28,AWx*b",  # one digit, then the fields' problems
    "$GPHDT,046.,T*07",  # a decimal that ends in its point (Signal K)
    "$GPHDT,.,T*35",  # a point alone
    "$GPHDT,46..,T*19",  # two points
    "$GPHDT,-.,T*18",  # a sign and a point
)
TOLERANCE_OPTIONS = ((), ("--strict",), ("--lenient", "--strict"))


def tolerance_vectors(spec: Spec) -> list[dict]:
    return [{"line": line, "options": list(options),
             "decode": reference.decode_json(spec, line, lenient="--lenient" in options, strict="--strict" in options)}
            for line in TOLERANCE_LINES for options in TOLERANCE_OPTIONS]


# Values the manuals' examples lack: signs, 18 digits (past 2^53), rounding of degrees x 10^7 half
# way, 60 minutes, the two-digit year's pivot (68, 69), a leap second, days their month lacks.
VALUE_EDGES: tuple[tuple[str, ...], ...] = (
    ("number", "-007.50"), ("number", "+12"), ("number", "-0"), ("number", ".5"), ("number", "5."),
    ("number", "123456789012345678"), ("number", ".000000000000000001"), ("number", "9007199254740993"),
    ("number", "-99.95"), ("number", "0.1"),
    ("latitude", "0000.0003", "S"), ("latitude", "0000.000003", "N"), ("latitude", "8960.0", "N"),
    ("latitude", "0000.000009", "S"), ("latitude", "4916.4500000000000001", "N"),
    ("longitude", "18000.0000", "W"), ("longitude", "00000.0000000000000001", "E"),
    ("time", "235960.5"), ("time", "000000"), ("time", "123456.123456789"), ("time", "235959.9999"),
    ("date", "010100"), ("date", "311268"), ("date", "010169"), ("date", "291200"), ("date", "290299"),
    ("date", "310218"), ("date", "290200"),
    ("datetime", "311268", "235959.999"), ("datetime", "010170", "000000"), ("datetime", "310218", "120000"),
    ("datetime", "191194", "235960"),
    ("civil", "2000", "2", "29"), ("civil", "1900", "2", "29"), ("civil", "1970", "1", "1"),
    ("civil", "2024", "4", "31"), ("civil", "9999", "12", "31"), ("civil", "0", "1", "1"),
)


def value_vectors(spec: Spec) -> list[dict]:
    """What each language's value accessors give for every number, coordinate, time, date, and
    date and time of the manuals' examples, and for VALUE_EDGES: one record a value, by the
    reference runtime (doubles as their shortest round-trip text: compared exactly)."""
    rt = reference.rt
    seen: set[tuple[str, ...]] = set()
    out: list[dict] = []

    def add(key: tuple[str, ...]) -> None:
        if key not in seen:
            seen.add(key)
            out.append(value_record(key))

    for sentence in spec.sentences:
        for example in sentence.examples:
            if example.line is None:
                continue
            decoded = reference.decode(spec, example.line)
            assert decoded.layout is not None
            values = {item_id: (value, texts) for item_id, value, texts in decoded.values}
            for _, value, texts in decoded.values:
                for v, t in ([(ev, et) for entry in value for _, ev, et in entry] if texts is None else [(value, texts)]):
                    if isinstance(v, rt.Coordinate):
                        add(("latitude" if v.hemisphere in "NS" else "longitude", *t))
                    elif isinstance(v, (rt.Number, rt.Time, rt.Date)):
                        add(({rt.Number: "number", rt.Time: "time", rt.Date: "date"}[type(v)], t[0]))
            calendar = decoded.layout.calendar
            if calendar is None or values.get(calendar.time.id, (None,))[0] is None:
                continue
            if calendar.date and values.get(calendar.date.id, (None,))[0] is not None:
                add(("datetime", values[calendar.date.id][1][0], values[calendar.time.id][1][0]))
            elif calendar.year and all(values.get(f.id, (None,))[0] is not None
                                       for f in (calendar.year, calendar.month, calendar.day)):
                add(("civil", *(values[f.id][1][0] for f in (calendar.year, calendar.month, calendar.day))))
    for key in VALUE_EDGES:
        add(key)
    return out


def value_record(key: tuple[str, ...]) -> dict:
    """One record of value_vectors: the input texts, their parts (what a C struct holds) and the
    values every language must give."""
    rt = reference.rt
    kind, *texts = key
    if kind == "number":
        n = rt.parse_decimal(texts[0])
        return {"type": kind, "text": texts[0], "digits": n.digits, "scale": n.scale, "negative": n.sign == "-",
                "double": repr(float(n)), "float": repr(struct.unpack("f", struct.pack("f", float(n)))[0]),
                "int": int(n)}
    if kind in ("latitude", "longitude"):
        c = rt.parse_coordinate(texts[0], 2 if kind == "latitude" else 3, 90 if kind == "latitude" else 180)
        c = rt.Coordinate(c.degrees, c.minutes, texts[1], c.degree_digits)
        return {"type": kind, "text": texts[0], "hemisphere": texts[1], "deg": c.degrees,
                "minutes_digits": c.minutes.digits, "minutes_scale": c.minutes.scale,
                "degrees": repr(float(c)), "e7": c.degrees_e7()}
    if kind == "time":
        t = rt.parse_time(texts[0])
        return {"type": kind, "text": texts[0], "hour": t.hour, "minute": t.minute, "second": t.second,
                "fraction": t.fraction, "fraction_digits": t.fraction_digits, "ms": t.ms_of_day()}
    if kind == "date":
        d = rt.parse_date(texts[0])
        return {"type": kind, "text": texts[0], "day": d.day, "month": d.month, "year": d.year,
                "full_year": d.full_year, "days": _or_none(d.days_since_epoch)}
    if kind == "datetime":
        d, t = rt.parse_date(texts[0]), rt.parse_time(texts[1])
        when = rt.utc_datetime(d, t)
        return {"type": kind, "date": texts[0], "time": texts[1],
                "ms": None if when is None else (when - UNIX_EPOCH) // datetime.timedelta(milliseconds=1)}
    year, month, day = (int(rt.parse_integer(text)) for text in texts)
    return {"type": kind, "year": year, "month": month, "day": day,
            "days": _or_none(lambda: (datetime.date(year, month, day) - EPOCH).days)}


EPOCH = datetime.date(1970, 1, 1)
UNIX_EPOCH = datetime.datetime(1970, 1, 1, tzinfo=datetime.timezone.utc)


def _or_none(value: Callable[[], int]) -> int | None:
    """The value, or None where datetime holds no such date (a day its month lacks, year 0)."""
    try:
        return value()
    except ValueError:
        return None


def tag_block_vectors(spec: Spec) -> list[dict]:
    """The examples of spec/tag_block.yaml: each line and its decode (a good line's encode is
    the line itself)."""
    return [{"where": where, "line": line, "decode": reference.decode_json(spec, line)}
            for where, line in spec.tag_examples]


def fix_vectors(spec: Spec) -> list[dict]:
    """The examples of spec/fix.yaml: lines and the facts of each fix an assembler makes of them."""
    return [{"where": e.where, "lines": e.lines, "fixes": e.expect} for e in spec.fix_examples]


# Payloads every AIS decoder must refuse, with the kind of its error (json.md, "AIS payloads"),
# as the spec/ tree describes the messages.
AIS_ERROR_PAYLOADS = (
    ("15RTgt0PAso;90TKcjM8h6g208C", 0, "a type 1 cut short inside its radio state"),
    ("15RTgt0PAso;90TKcjM8h6g208CQ", 6, "fill bits over 5"),
    ("15RTgt0PAso;90TKcjM8h6g2X8CQ", 0, "X is no armor character"),
    ("", 1, "fill bits with no payload"),
    ("w", 0, "message type 63, which no message describes"),
    ("702R5`hw", 0, "a type 7 with no whole acknowledgement"),
)


def _pattern_bits(seed: str) -> Iterator[str]:
    """An endless, fixed sequence of '0' and '1' drawn from `seed` (SHA-256 in counter mode)."""
    block = 0
    while True:
        digest = hashlib.sha256(f"{seed}:{block}".encode()).digest()
        yield from "".join(f"{byte:08b}" for byte in digest)
        block += 1


def built_application(spec: Spec, application: Payload, key: tuple[int, int],
                      message_type: int | None = None) -> tuple[str, int]:
    """A payload built from an application's layout (armored text, fill bits), for a DAC and FI of it
    (`key`) no public capture shows: the first message type that carries it so (or `message_type`),
    that DAC and FI, every field's bits drawn from a fixed sequence seeded by the application's id (an
    enum's: its first code; spare bits: 0; a field of the bits left: 48 of them), every group full."""
    draw = _pattern_bits(application.id)

    def bits_of(f: PayloadField) -> str:
        width = 48 if f.bits is None else f.bits   # 48: whole six-bit characters and bytes
        if f.type == "spare":
            return "0" * width
        if f.enum is not None:
            return f"{int(f.enum.values[0].code):0{width}b}"
        return "".join(next(draw) for _ in range(width))

    def items_bits(items: Sequence[PayloadItem], k: int) -> str:
        """The bits of `items` (an application's, a group entry's): a choice takes its k-th named
        case in turn (entry k of a group; the first at the top), its selector that case's first
        value; a group is full."""
        cases: dict[str, tuple[PayloadCase, int]] = {}
        for choice in (i for i in items if isinstance(i, PayloadChoice)):
            named = [c for c in choice.cases if not c.is_default]
            case = named[k % len(named)]
            cases[choice.by] = case, case.values[0] if case.values else case.range[0]  # type: ignore[index]
        bits = ""
        for part in items:
            if isinstance(part, PayloadGroup):
                bits += "".join(items_bits(part.items, j) for j in range(part.max))
            elif isinstance(part, PayloadChoice):
                bits += "".join(bits_of(f) for f in cases[part.by][0].fields)
            elif part.id in cases:
                bits += f"{cases[part.id][1]:0{part.bits}b}"
            else:
                bits += bits_of(part)
        return bits

    data = items_bits(application.items, 0)
    message_type = application.carriers_of(key)[0] if message_type is None else message_type
    carrier = reference_ais.payload_of(spec, message_type)
    assert carrier is not None and carrier.data_field is not None
    dac, fid = carrier.data_field.dispatch
    fixed = {"message_type": message_type, dac: key[0], fid: key[1]}
    bits = ""
    for item in carrier.items:
        assert isinstance(item, PayloadField) and item.bits is not None or item is carrier.data_field
        if item is carrier.data_field:
            bits += data
        elif item.id in fixed:
            bits += f"{fixed[item.id]:0{item.bits}b}"
        else:
            bits += bits_of(item)
    fill_bits = -len(bits) % 6
    bits += "0" * fill_bits
    armored = "".join(chr(v + 48 + (8 if v > 39 else 0)) for v in (int(bits[i:i + 6], 2) for i in range(0, len(bits), 6)))
    return armored, fill_bits


def ais_vectors(spec: Spec) -> list[dict]:
    """The payload examples of spec/ais (messages, and messages that carry an application) with the
    JSON each decoder must make of them, a payload built from the layout of each application that
    has no example, and payloads each must refuse with the kind of its error."""
    out: list[dict] = []
    for payload in [*spec.payloads, *spec.applications]:
        for e in payload.examples:
            out.append({"message": payload.id, "where": e.where, "payload": e.payload, "fill_bits": e.fill_bits,
                        "decode": reference_ais.decode(spec, e.payload, e.fill_bits)})
        shown = {(out[-1 - i]["decode"].get("dac"), out[-1 - i]["decode"].get("fid")) for i in range(len(payload.examples))}
        for dac, fid in (k for k in payload.keys if k not in shown):   # a DAC no example shows
            text, fill_bits = built_application(spec, payload, (dac, fid))
            decoded = reference_ais.decode(spec, text, fill_bits)
            assert decoded.get("application", {}).get("trailing") == "", f"{payload.id}: the built payload is not it"
            out.append({"message": payload.id, "where": f"built from the layout of {payload.id}, DAC {dac} FI {fid} "
                        "(no public capture): fields from a fixed pseudo-random sequence, groups full", "payload": text,
                        "fill_bits": fill_bits, "decode": decoded})
        for dac, fid in payload.keys:   # a DAC and FI in a message type that carries the layout under another
            for message_type in (t for t in payload.carriers if t not in payload.carriers_of((dac, fid))):
                text, fill_bits = built_application(spec, payload, (dac, fid), message_type)
                decoded = reference_ais.decode(spec, text, fill_bits)
                assert "application" not in decoded, f"{payload.id}: DAC {dac} FI {fid} read in type {message_type}"
                out.append({"message": None, "where": f"the layout of {payload.id} as DAC {dac} FI {fid} in type "
                            f"{message_type}, which does not carry it so: its data stay data", "payload": text,
                            "fill_bits": fill_bits, "decode": decoded})
    for text, fill_bits, where in AIS_ERROR_PAYLOADS:
        record: dict = {"message": None, "where": where, "payload": text, "fill_bits": fill_bits}
        try:
            record["decode"] = reference_ais.decode(spec, text, fill_bits)   # a spec that describes it
        except reference_ais.PayloadError as err:
            record["error"] = err.kind
        out.append(record)
    return out


# Frames every UBX decoder must read as the reference decoder does, or refuse with the same kind of
# error: (frame hex, what it shows).
UBX_CASES = (
    ("b5 62 01 20 00 00 21 64", "a NAV-TIMEGPS poll (empty payload)"),
    ("b5 62 01 20 0a 00 00 00 00 00 00 00 00 00 00 00 2b 26", "a NAV-TIMEGPS cut to 10 bytes: leap_s is cut"),
    ("b5 62 05 01 03 00 06 00 07 16 51", "an ACK-ACK of 3 bytes: its main layout, the third byte trailing"),
    ("b5 62 7f 7f 02 00 01 02 03 81", "class 0x7F id 0x7F, which no message describes: kept with its payload"),
    ("b5 62 05 01 02 00 06 00 0e 38", "a checksum off by one"),
    ("b5 62 13 40 14 00 05 00 00 00 01 02 03 04 05 06 07 08 09 0a 0b 0c 0d 0e 0f 10 f4 d4",
     "an MGA-INI of type 0x05, which no layout names: read as the first of its length (POS_XYZ), the type kept"),
    ("b5 62 13 00 10 00 01 00 00 00 0a 0b 0c 0d 0e 0f 10 11 12 13 14 15 de d6",
     "an MGA-GPS of 16 bytes whose type says ephemeris (1): read by its length (IONO), the type kept"),
    ("b5 62 0d 15 0c 00 02 00 01 01 00 00 e8 03 b8 0b 32 00 12 c2",
     "a TIM-VCOCAL of 12 bytes, type 2: the calibration's start (input), not its result (type 3)"),
)


def _frame_vectors(examples: Iterator[tuple[str, Any]], cases: tuple[tuple[str, str], ...],
                   decode: Callable[[bytes], dict], refused: type[Exception]) -> list[dict]:
    """Example frames (message id and example) with the JSON `decode` makes of them, then the
    `cases` (frame hex, what it shows): decoded, or the kind of the `refused` error they raise."""
    out: list[dict] = [{"message": message, "where": e.where, "frame": e.frame.hex(" "), "decode": decode(e.frame)}
                       for message, e in examples]
    for frame, where in cases:
        record: dict = {"message": None, "where": where, "frame": frame}
        try:
            record["decode"] = decode(bytes.fromhex(frame))
        except refused as err:
            record["error"] = getattr(err, "kind")  # both error types carry it
        out.append(record)
    return out


def ubx_vectors(spec: Spec) -> list[dict]:
    """The example frames of spec/binary/ubx with the JSON each decoder must make of them, and
    frames each must refuse with the kind of its error."""
    examples = ((m.id, e) for m in spec.binary if m.protocol == "ubx" for e in m.examples)
    return _frame_vectors(examples, UBX_CASES, lambda frame: reference_binary.decode(spec, frame),
                          reference_ais.PayloadError)


# Frames every RTCM 3 decoder must read as the reference decoder does, or refuse with the same kind
# of error: (frame hex, what it shows).
RTCM3_CASES = (
    ("d3 00 04 4c e0 00 80 ed ed d7", "a 1230 frame whose checksum is off by one"),
    ("d3 00 03 3e d0 00 7a 79 fe", "a 1005 payload cut to 3 bytes: itrf_year is cut"),
    ("d3 00 02 fe 80 bb fe 86", "message 4072 (u-blox, not public): kept with its payload"),
    ("d3 00 0c 4c e0 00 8f ff ff ff ff ff ff ff ff c9 2e cc", "a 1230 of four biases, each the raw -1 (0xFFFF)"),
)


def rtcm3_vectors(spec: Spec) -> list[dict]:
    """The example frames of the bit messages (spec/binary/rtcm3) with the JSON each decoder must
    make of them, and frames each must refuse with the kind of its error."""
    examples = ((m.id, e) for m in spec.bit_messages for e in m.frame_examples)
    return _frame_vectors(examples, RTCM3_CASES, lambda frame: reference_rtcm3.decode(spec, frame),
                          reference_rtcm3.FrameError)


# Frames of the other protocols every decoder must read as the reference decoder does, or refuse
# with the same kind of error: (protocol, frame hex, what it shows). SBF's sub-blocks, whose bytes
# (SBLength) a newer firmware may make longer than the layout's fields, and MeasEpoch's sub-blocks
# of sub-blocks.
BINARY_CASES = (
    ("sbf", "24 40 15 cd ac 0f 24 00 e0 52 c9 1c 3f 09 02 0a 03 00 29 1a 96 21 00 02 aa bb 04 00 ab 43 c6 0c 01 01 cc dd",
     "a SatVisibility of two SatInfo sub-blocks of 10 bytes: the 2 after the fields kept as each one's trailing"),
    ("sbf", "24 40 cb aa ac 0f 14 00 e0 52 c9 1c 3f 09 01 04 03 00 29 1a",
     "a SatVisibility whose SBLength (4) is shorter than a SatInfo's fields (8): refused"),
    ("sbf", "24 40 31 f0 ac 0f 20 00 e0 52 c9 1c 3f 09 03 08 03 00 29 1a 96 21 00 02 04 00 ab 43 c6 0c 01 01",
     "a SatVisibility whose N says 3 sub-blocks of 8 bytes, the block holding 2"),
    ("sbf", "24 40 b4 f2 ac 0f 14 00 e0 52 c9 1c 3f 09 00 00 00 00 00 00",
     "a SatVisibility of no sub-block and an SBLength of 0 (the stride of no entry says nothing), padding kept"),
    # MeasEpoch: Type-1 sub-blocks (SB1Length) each followed by its N2 Type-2 sub-blocks (SB2Length)
    ("sbf", "24 40 85 fe bb 2f 5c 00 68 a2 bf 1c 3f 09 02 16 0e 01 0c 00 01 00 11 01 15 cd 5b 07 e0 b1 ff ff f4 01 fd a0 2a 00 01 02 aa bb 02 28 96 f7 ff 01 e8 fd 2c 01 39 30 cc dd 02 28 96 f7 ff 01 e8 fd 2c 01 39 30 ee ff 02 00 05 01 15 cd 5b 07 e0 b1 ff ff f4 01 fd a0 2a 00 01 00 11 22",
     "a MeasEpoch of two Type-1 sub-blocks of 22 bytes (the first followed by two Type-2 of 14, the second by none): the 2 bytes after each one's fields kept as its trailing, at both levels"),
    ("sbf", "24 40 c9 8c bb 2f 30 00 68 a2 bf 1c 3f 09 01 14 08 01 0c 00 01 00 11 01 15 cd 5b 07 e0 b1 ff ff f4 01 fd a0 2a 00 01 01 02 28 96 f7 ff 01 e8 fd",
     "a MeasEpoch whose SB2Length (8) is shorter than a Type-2 sub-block's fields (12): refused"),
    ("sbf", "24 40 1a 40 bb 2f 34 00 68 a2 bf 1c 3f 09 01 14 0c 01 0c 00 01 00 11 01 15 cd 5b 07 e0 b1 ff ff f4 01 fd a0 2a 00 01 03 02 28 96 f7 ff 01 e8 fd 2c 01 39 30",
     "a MeasEpoch whose Type-1 sub-block says 3 Type-2 sub-blocks of 12 bytes, the block holding 1"),
    ("sbf", "24 40 62 c3 bb 2f 40 00 68 a2 bf 1c 3f 09 02 14 0c 01 0c 00 01 00 11 01 15 cd 5b 07 e0 b1 ff ff f4 01 fd a0 2a 00 01 02 02 28 96 f7 ff 01 e8 fd 2c 01 39 30 02 28 96 f7 ff 01 e8 fd 2c 01 39 30",
     "a MeasEpoch of N1 2 whose first Type-1's two Type-2 sub-blocks leave no bytes for the second Type-1"),
)


def binary_vectors(spec: Spec) -> list[dict]:
    """The example frames of the other binary protocols (spec/binary/{skytraq,sirf,casic,sbf}) with
    the JSON each decoder must make of them, then the BINARY_CASES of the protocols the spec types:
    decoded, or the kind of the error they raise."""
    out = [{"protocol": message.protocol, "message": message.id, "where": e.where, "frame": e.frame.hex(" "),
            "decode": reference_binary.decode(spec, e.frame)}
           for message in spec.binary if message.protocol != "ubx" for e in message.examples]
    typed = {m.protocol for m in spec.binary}
    for protocol, frame, where in BINARY_CASES:
        if protocol in typed:
            cases = _frame_vectors(iter(()), ((frame, where),), lambda data: reference_binary.decode(spec, data),
                                   reference_ais.PayloadError)
            out += [{"protocol": protocol, **record} for record in cases]
    return out


def emit(spec: Spec, env: jinja2.Environment) -> dict[str, str]:
    def jsonl(records: list[dict]) -> str:
        return "".join(json.dumps(r, ensure_ascii=True, separators=(",", ":")) + "\n" for r in records)

    files = {"vectors/ubx.jsonl": jsonl(ubx_vectors(spec))} if spec.binary else {}
    if spec.bit_messages:
        files["vectors/rtcm3.jsonl"] = jsonl(rtcm3_vectors(spec))
    if any(m.protocol != "ubx" for m in spec.binary):
        files["vectors/binary.jsonl"] = jsonl(binary_vectors(spec))
    return {**files, "vectors/examples.jsonl": jsonl(example_vectors(spec)),
            "vectors/tolerance.jsonl": jsonl(tolerance_vectors(spec)),
            "vectors/values.jsonl": jsonl(value_vectors(spec)),
            "vectors/fixes.jsonl": jsonl(fix_vectors(spec)),
            "vectors/tag_blocks.jsonl": jsonl(tag_block_vectors(spec)),
            "vectors/ais.jsonl": jsonl(ais_vectors(spec))}
