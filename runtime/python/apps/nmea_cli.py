"""`nmea`: look at a receiver log and build vendor commands, from the command line.

    nmea show LOG|-        a table, JSON lines or CSV of the sentences, a summary on stderr
    nmea show --fixes LOG  the same of the fixes: one row per epoch (fixes.py)
    nmea command ...       the bytes of a vendor command, checked field by field
    nmea listen --port P   the sentences of a live receiver (needs pyserial), or of the network
                           (--udp PORT for IEC 61162-450 and plain UDP, --tcp HOST:PORT)
    nmea send --port P ... a vendor command sent to a receiver, and its reply
    nmea report LOG        the log as pictures in one HTML page (report.py; needs matplotlib)

Standard library only (listen and send import pyserial when they open a serial port). The tool other programs
drive, with the JSON the C and Rust tools print too, is `nmea-py` (contract_tool.py), not this one.
"""

from __future__ import annotations

import argparse
import csv
import io
import json
import os
import sys
import time
from collections import Counter
from collections.abc import Iterable, Iterator
from itertools import islice
from typing import IO, Any, cast

from .. import __version__
from ..api import Generic, Tagged, parse
from ..assembly import Assembled, MessageAssembler
from ..fixes import Fix, fixes
from ..network import host_port, tcp_feed, udp_feed
from ..receiver import Receiver, ReceiverError, ReplyTimeout, check_baud
from ..runtime import NmeaError
from ..stream import BadFrame, BinaryFrame, Item, lines, too_long, typed
from .commands import COMMANDS, SHORTCUTS, VENDORS, Command, Shortcut

SHOW_EXAMPLES = """\
examples:
  nmea show track.nmea                                   every sentence, one row each
  nmea track.nmea --sentences GGA --fields time,lat,lon,quality,satellites
  nmea show --json track.nmea | head                     JSON lines of decoded values
  nmea show --csv --fields time,lat,lon,speed --sentences RMC track.nmea > track.csv
  cat /dev/ttyUSB0 | nmea show - --sentences GGA,RMC     a live receiver
  nmea show --fixes track.nmea                           one row per epoch: time, position, ...
  nmea show --fixes --json track.nmea                    each fix whole, satellites included

Fields are the field ids of the reference docs (`time`, `lat`, `quality`...), plus `line`,
`talker`, `sentence` and the parameters of a line's TAG blocks as `tag.source`, `tag.time`...
(generated/docs/tag_block.md; JSON lines carry them as `tag_block`, the table and CSV put
them first in `fields`; a line of TAG blocks only is a row of sentence `TAG`). Latitudes and
longitudes are shown in signed decimal degrees, enums by value id. The summary (counts per
sentence, errors by kind, unknown sentences) goes to stderr. With --fixes, the columns are the facts of a fix (FIX_COLUMNS; `used` and `in_view` count the
satellites), and --json gives every fact of each.
"""

COMMAND_EXAMPLES = """\
examples:
  nmea command --list                        every vendor's commands and their arguments
  nmea command --list geos5
  nmea command geos5 set-baud 115200         a shortcut: $GPSGG,BDR115*09
  nmea command geos5 command BDR115          the same, by the command's field
  nmea command teseo pstmsetpar 1201 40 set-bits
  nmea command globalsat psrf103 --message gga --mode query --rate 0 --checksum-mode enabled
  nmea command comnav log gpgga ontime 1     text commands have no '$' and no checksum

Arguments are positional in field order, or `--field value`; an enum takes its code or its
value id. The bytes are written to stdout with CR LF, ready for the serial port.
"""


LIVE_EXAMPLES = """\
examples (a receiver on a serial port; pip install 'nmeaspec[serial]'):
  nmea listen --port /dev/ttyUSB0 --baud 9600               every sentence, until Ctrl-C
  nmea listen --port /dev/ttyUSB0 --sentences GGA --fields time,lat,lon,quality --log raw.nmea
  nmea listen --port COM3 --json --count 20                  20 sentences, then stop
  nmea listen --udp 60001 --group 239.192.0.1                an IEC 61162-450 group (MISC)
  nmea listen --udp 10110                                    a plain UDP feed
  nmea listen --tcp 192.168.1.10:10110 --sentences VDM       a TCP feed (a gateway, gpsd)
  nmea send --port /dev/ttyUSB0 mtk_pmtk pmtk220 200         5 Hz; prints the reply
  nmea send --port /dev/ttyUSB0 --baud 115200 quectel_lg290p pqtmcfgfixrate 100 --timeout 2
  nmea send --port /dev/ttyACM0 ubx MON-VER                  a UBX poll, and its answer
  nmea config get CFG-RATE-MEAS --port /dev/ttyACM0          u-blox configuration keys by name
  nmea config set CFG-RATE-MEAS 0.2 --layer ram,bbr --port /dev/ttyACM0

`send` builds the command as `nmea command` does, writes it and waits for the reply that the
spec pairs with it (e.g. $PMTK001,220,3 for $PMTK220). Exit status: 0 the reply says OK, 1 it
reports an error, 2 no reply within --timeout (or a mistake on the command line), 3 the port
cannot be used. --show-all prints the sentences that came meanwhile; --log keeps every byte.
"""


class CliError(Exception):
    """A mistake on the command line: printed without a traceback, exit status 2."""

    status = 2


# --------------------------------------------------------------------------------------------
# show


SPECIAL_FIELDS = ("line", "talker", "sentence")


def _plain(value: Any) -> Any:
    """A decoded JSON value made friendlier: a coordinate as signed decimal degrees."""
    if isinstance(value, dict) and set(value) == {"deg", "min", "hemi"}:
        degrees = value["deg"] + value["min"] / 60
        return round(-degrees if value["hemi"] in ("S", "W") else degrees, 7)
    if isinstance(value, list):
        return [_plain(v) for v in value]
    if isinstance(value, dict):
        return {k: _plain(v) for k, v in value.items()}
    return value


def _text(value: Any) -> str:
    """A value as one table or CSV cell."""
    if value is None:
        return ""
    if isinstance(value, float):
        return repr(value)
    if isinstance(value, list):  # GSA's empty PRN slots are left out
        return " ".join(_text(v) for v in value if v is not None)
    if isinstance(value, dict):  # the fields of a group entry; empty ones are left out
        return "(" + " ".join(f"{k}={_text(v)}" for k, v in value.items() if v is not None) + ")"
    return str(value)


def _summary(fields: dict[str, Any]) -> str:
    """Every field with a value, as `id=value`: the last column of the default table."""
    return " ".join(f"{k}={_text(v)}" for k, v in fields.items() if v is not None and v != [])


class Summary:
    """What was read: sentences by id, errors by kind, unknown sentences by address."""

    LIMIT = 20  # rows per list: a log of many talkers has a long tail of unknown addresses

    def __init__(self) -> None:
        self.lines = 0
        self.sentences: Counter[str] = Counter()
        self.errors: Counter[str] = Counter()
        self.unknown: Counter[str] = Counter()
        self.ais: Counter[str] = Counter()  # AIS messages by id, and what did not decode by kind
        self.ais_errors: Counter[str] = Counter()

    def write(self, out: IO[str]) -> None:
        total_errors = sum(self.errors.values())
        out.write(
            f"{self.lines} lines: {sum(self.sentences.values())} sentences, "
            f"{sum(self.unknown.values())} unknown, {total_errors} errors\n"
        )
        for title, counts in (
            ("sentences", self.sentences),
            ("unknown", self.unknown),
            ("errors", self.errors),
            ("AIS messages", self.ais),
            ("AIS messages that did not decode", self.ais_errors),
        ):
            if counts:
                ranked = sorted(counts.items(), key=lambda kv: (-kv[1], kv[0]))
                width = max(len(k) for k, _ in ranked[: self.LIMIT])
                out.write(f"{title}:\n")
                for key, count in ranked[: self.LIMIT]:
                    out.write(f"  {key:<{width}}  {count}\n")
                if len(ranked) > self.LIMIT:
                    rest = ranked[self.LIMIT :]
                    out.write(f"  ... {len(rest)} more, {sum(c for _, c in rest)} lines\n")


class Progress:
    """A bar on stderr, redrawn at most ten times a second, that knows the size of the file."""

    def __init__(self, total: int, out: IO[str]) -> None:
        self.total = max(total, 1)
        self.out = out
        self.done = 0
        self.drawn = 0.0

    def advance(self, count: int) -> None:
        self.done += count
        now = time.monotonic()
        if now - self.drawn >= 0.1:
            self.drawn = now
            self._draw()

    def _draw(self) -> None:
        share = min(self.done / self.total, 1.0)
        bar = "#" * int(share * 30)
        self.out.write(
            f"\r[{bar:<30}] {share:4.0%} {self.done / 1e6:.1f}/{self.total / 1e6:.1f} MB"
        )
        self.out.flush()

    def finish(self) -> None:
        self._draw()
        self.out.write("\n")
        self.out.flush()


def open_log(name: str) -> tuple[IO[bytes], int | None]:
    """A log to read (a file, or - for stdin) and its size when it is a file."""
    if name == "-":
        return sys.stdin.buffer, None
    try:
        source = open(name, "rb")
    except OSError as err:
        raise CliError(f"cannot read {name}: {err.strerror}") from None
    return source, os.fstat(source.fileno()).st_size if os.path.isfile(name) else None


def progress_for(requested: bool | None, size: int | None) -> Progress | None:
    """The bar for a file of `size` bytes: as --progress/--no-progress say, else only where a
    person watches, and only when it is worth it."""
    if requested is None:
        requested = sys.stderr.isatty() and size is not None and size >= 4 << 20
    return Progress(size, sys.stderr) if requested and size else None


def add_progress_options(verb: argparse.ArgumentParser) -> None:
    verb.add_argument(
        "--progress",
        action="store_true",
        default=None,
        help="a progress bar on stderr (default: when stderr is a terminal and the file is large)",
    )
    verb.add_argument(
        "--no-progress", dest="progress", action="store_false", help="never a progress bar"
    )


def _chunks(source: IO[bytes], progress: Progress | None, size: int = 1 << 16) -> Iterator[bytes]:
    while chunk := source.read(size):
        if progress is not None:
            progress.advance(len(chunk))
        yield chunk


def records(
    chunks: Iterable[bytes], wanted: set[str] | None, summary: Summary, **options: bool
) -> Iterator[dict[str, Any]]:
    """Each sentence of a byte stream as {line, talker, sentence, fields}, counted in `summary`;
    errors are only counted. `wanted`: the sentence ids (or addresses of unknown sentences) to
    keep; `options`: parse()'s (lenient, strict)."""
    return framed_records(lines(chunks, binary=True), wanted, summary, **options)


def frame_record(frame: BinaryFrame) -> tuple[str, dict[str, Any]]:
    """A binary frame's name and fields: a UBX frame's message as u-blox names it (`NAV-PVT`) with
    its decoded values (a class and id the spec does not describe: `UBX 0x01 0x07` with its
    payload); an RTCM 3 frame as its protocol and message number (`RTCM3 1005`) with its decoded
    values (a number the spec does not describe: its payload); a SkyTraq, SiRF or CASIC frame's as
    `SKYTRAQ 0xA8`, `SIRF MID 2`, `CASIC NAV-PV` with its values; another frame as its protocol
    and identity (`SIRF 51`, a MID the spec does not describe). Raises NmeaError for a payload its
    layout does not fit."""
    identity = " ".join([frame.protocol.upper(), *(str(v) for v in frame.identity.values() if v is not None)])
    if frame.protocol in ("ubx", "rtcm3") and typed(frame.protocol):
        message = frame.message()
        fields = {k: v for k, v in message.to_dict().items() if k not in ("message", "message_number")}
        if frame.protocol == "rtcm3":
            return identity, fields
        name = getattr(message, "ADDRESS", None)
        return (f"UBX {name}" if name else f"UBX 0x{frame.data[2]:02X} 0x{frame.data[3]:02X}"), fields
    try:
        message = frame.message()   # SkyTraq, SiRF, CASIC: `SKYTRAQ 0xA8`, `SIRF MID 2`, `CASIC NAV-PV`
    except ValueError:   # a protocol whose messages are not typed
        message = None
    if message is not None and getattr(message, "ADDRESS", None):
        return f"{message.PROTOCOL} {message.ADDRESS}", {k: v for k, v in message.to_dict().items() if k != "message"}
    return identity, {}


def framed_records(
    items: Iterable[Item], wanted: set[str] | None, summary: Summary, **options: bool
) -> Iterator[dict[str, Any]]:
    """records() of lines already framed (an int: the length of an overlong line; binary frames
    as the framer gives them: a BadFrame is counted as its reason). The record of the sentence
    that completes an AIS message (nmeaspec.assembly) has it as `ais`."""
    assembler = MessageAssembler()
    for number, item in enumerate(items, 1):
        summary.lines += 1
        if isinstance(item, BadFrame):
            summary.errors[item.reason] += 1
            continue
        if isinstance(item, BinaryFrame):
            try:
                name, fields = frame_record(item)
            except NmeaError as err:
                summary.errors[err.kind] += 1
                continue
            summary.sentences[name] += 1
            if wanted is None or name in wanted:
                yield {"line": number, "talker": None, "sentence": name, "fields": fields}
            continue
        try:
            if isinstance(item, int):
                raise too_long(item)
            line = parse(item, **options)
        except NmeaError as err:
            summary.errors[err.kind] += 1
            continue
        sentence, tags = line, None
        if isinstance(line, Tagged):
            tags = tag_values(line)
            sentence = line.sentence
        name, talker, fields = ("TAG", None, {}) if sentence is None else describe(sentence)
        if isinstance(sentence, Generic):
            summary.unknown[name] += 1
        else:
            summary.sentences[name] += 1
        message = _assembled(assembler.feed(line), summary)
        if wanted is None or name in wanted:
            record = {"line": number, "talker": talker, "sentence": name, "fields": fields}
            if tags is not None:
                record["tag_block"] = tags
            if message is not None:
                record["ais"] = message
            yield record
    _assembled(assembler.finish(), summary)


def _assembled(done: list[Assembled], summary: Summary) -> dict[str, Any] | None:
    """The AIS message (as plain values, its id first) that the line completed, if any; each
    message and each one that did not decode or complete is counted."""
    found = None
    for assembled in done:
        if assembled.message is None:
            assert assembled.error is not None
            summary.ais_errors[assembled.error.kind] += 1
            continue
        summary.ais[assembled.message.ID] += 1
        found = {"message": assembled.message.ID, **assembled.message.to_dict()}
    return found


def tag_values(tagged: Tagged) -> dict[str, Any]:
    """The parameters of a line's TAG blocks as plain values by the spec's id (an unknown code
    by itself), the first of each."""
    values: dict[str, Any] = {}
    for block in tagged.tag_blocks:
        for key, value in block.to_dict().items():
            values.setdefault(key, value)
    return values


def describe(sentence: Any) -> tuple[str, str | None, dict[str, Any]]:
    """A decoded sentence's name (its id, or the address of a generic one), its talker and its
    fields as plain values."""
    if isinstance(sentence, Generic):
        return sentence.address, None, {"fields": sentence.fields}
    fields = _plain(json.loads(sentence.fields_json(True)))
    return sentence.SENTENCE, getattr(sentence, "talker", None), fields


def _row(record: dict[str, Any], fields: list[str] | None) -> list[Any]:
    if fields is None:
        summary = _summary(record["fields"])
        if "ais" in record:  # the message rather than its armored payload
            summary = _summary({k: v for k, v in record["ais"].items() if not k.endswith("_raw")})
        if "tag_block" in record:
            summary = ("tag" + _text(record["tag_block"]) + " " + summary).rstrip()
        return [record["line"], record["talker"], record["sentence"], summary]
    return [_cell(record, f) for f in fields]


def _cell(record: dict[str, Any], field: str) -> Any:
    """A --fields column of a record: a special field, a TAG block parameter, a field of its AIS
    message, a field."""
    if field in SPECIAL_FIELDS:
        return record[field]
    if field.startswith("tag."):
        return record.get("tag_block", {}).get(field[4:])
    if field.startswith("ais."):
        return record.get("ais", {}).get(field[4:])
    return record["fields"].get(field)


def write_table(
    rows: Iterable[list[Any]], header: list[str], out: IO[str], block: int = 200, live: bool = False
) -> None:
    """Aligned columns, printed a block of rows at a time so that a long log streams; a column
    only ever widens. The last column is not padded. `live`: every row as it comes, flushed."""
    if live:
        block = 1
    widths = [len(h) for h in header]

    def flush(batch: list[list[str]]) -> None:
        for cells in batch:
            for i, text in enumerate(cells[:-1]):
                widths[i] = max(widths[i], len(text))
        for cells in batch:
            out.write(
                "  ".join(t.ljust(w) for t, w in zip(cells[:-1], widths))
                + ("  " if len(cells) > 1 else "")
                + cells[-1]
                + "\n"
            )
        if live:
            out.flush()

    batch: list[list[str]] = [header]
    for row in rows:
        batch.append([_text(v) for v in row])
        if len(batch) >= block:
            flush(batch)
            batch = []
    flush(batch)


def view_of(args: argparse.Namespace) -> tuple[list[str] | None, set[str] | None]:
    """The columns (--fields) and the sentences (--sentences) asked for."""
    fields = [f.strip() for f in args.fields.split(",") if f.strip()] if args.fields else None
    wanted = (
        {s.strip().upper() for s in args.sentences.split(",") if s.strip()}
        if args.sentences
        else None
    )
    return fields, wanted


def write_records(
    stream: Iterable[dict[str, Any]],
    form: str,
    fields: list[str] | None,
    out: IO[str],
    live: bool = False,
) -> None:
    """The records as a table, JSON lines or CSV (`form`); `live`: each flushed as it comes."""
    if form == "json":
        for record in stream:
            if fields is not None:
                record = {f: _row(record, [f])[0] for f in fields}
            out.write(json.dumps(record, ensure_ascii=False) + "\n")
            if live:
                out.flush()
    elif form == "csv":
        writer = csv.writer(out, lineterminator="\n")
        writer.writerow(fields or ["line", "talker", "sentence", "fields"])
        for record in stream:
            writer.writerow([_text(v) for v in _row(record, fields)])
            if live:
                out.flush()
    else:
        write_table(
            (_row(r, fields) for r in stream),
            fields or ["line", "talker", "sentence", "fields"],
            out,
            live=live,
        )
    out.flush()


# The columns of `show --fixes` by default; --fields takes any fact of Fix.to_dict().
FIX_COLUMNS = ["time", "date", "latitude", "longitude", "altitude_msl", "speed", "course", "mode",
               "fix_quality", "hdop", "used", "in_view", "sentences"]


def parsed(items: Iterable[bytes | int], summary: Summary, **options: bool) -> Iterator[Any]:
    """The decoded sentences of framed lines (an int: the length of an overlong line), each
    counted in `summary`; errors are only counted."""
    for item in items:
        summary.lines += 1
        try:
            if isinstance(item, int):
                raise too_long(item)
            sentence = parse(item, **options)
        except NmeaError as err:
            summary.errors[err.kind] += 1
            continue
        if isinstance(sentence, Tagged):  # the sentence behind its TAG blocks
            sentence = sentence.sentence
            if sentence is None:
                summary.sentences["TAG"] += 1
                continue
        if isinstance(sentence, Generic):
            summary.unknown[sentence.address] += 1
        else:
            summary.sentences[sentence.SENTENCE] += 1
        yield sentence


def fix_row(fix: Fix) -> dict[str, Any]:
    """A fix as one row: its facts (coordinates to 1e-7 degrees, about a centimetre, other numbers
    to 4 decimals), the satellites counted, the sentences as one text."""
    row = {k: round(v, 7 if k in ("latitude", "longitude") else 4) if isinstance(v, float) else v
           for k, v in fix.to_dict().items()}
    row.update(used=fix.used_count or fix.satellites_used, in_view=fix.in_view_count or None,
               sentences=" ".join(fix.sentences))
    return row


def write_fixes(stream: Iterable[Fix], form: str, fields: list[str] | None, out: IO[str]) -> None:
    """The fixes as a table or CSV of `fields` (FIX_COLUMNS by default), or JSON lines of each
    whole fix (of `fields` only, when given)."""
    columns = fields or FIX_COLUMNS
    if form == "json":
        for fix in stream:
            whole = fix.to_dict()
            out.write(json.dumps({f: whole.get(f) for f in fields} if fields else whole) + "\n")
    elif form == "csv":
        writer = csv.writer(out, lineterminator="\n")
        writer.writerow(columns)
        for fix in stream:
            row = fix_row(fix)
            writer.writerow([_text(row.get(f)) for f in columns])
    else:
        write_table(([fix_row(fix).get(f) for f in columns] for fix in stream), columns, out)
    out.flush()


def _quiet_stdout() -> None:
    """After a broken pipe (`nmea show log | head`): no error when Python flushes stdout."""
    sys.stdout = io.TextIOWrapper(io.BytesIO())


def parse_options(args: argparse.Namespace) -> dict[str, bool]:
    """parse()'s options as the command line gives them."""
    return {"lenient": args.lenient, "strict": args.strict}


def show(args: argparse.Namespace) -> int:
    fields, wanted = view_of(args)
    source, size = open_log(args.log)
    progress = progress_for(args.progress, size)
    summary = Summary()
    try:
        if args.fixes:
            sentences = parsed(lines(_chunks(source, progress)), summary, **parse_options(args))
            write_fixes(fixes(sentences), args.format, fields, sys.stdout)
        else:
            stream = records(_chunks(source, progress), wanted, summary, **parse_options(args))
            write_records(stream, args.format, fields, sys.stdout)
    except BrokenPipeError:  # `nmea show log | head`
        _quiet_stdout()
        return 0
    finally:
        if source is not sys.stdin.buffer:
            source.close()
    if progress is not None:
        progress.finish()
    if not args.quiet:
        summary.write(sys.stderr)
    return 0


# --------------------------------------------------------------------------------------------
# command


def _kebab(text: str) -> str:
    return text.lower().replace("_", "-")


def _vendor(name: str) -> str:
    vendor = name.lower()
    if vendor not in VENDORS:
        raise CliError(f"unknown vendor {name!r}; vendors: {', '.join(VENDORS)}")
    return vendor


def _typed(command: Command) -> list[Any]:
    """The arguments a user gives (keywords are fixed)."""
    return [a for a in command.arguments if a.type != "keyword"]


def _enum_code(argument: Any, given: str) -> str:
    """An enum argument as its code: the code itself, or a value id in any case, '-' for '_'."""
    if given in argument.enum.BY_CODE:
        return given
    key = given.lower().replace("-", "_")
    for member in argument.enum:
        if member.id == key or member.value.lower() == given.lower():
            return str(member.value)
    codes = ", ".join(
        _kebab(m.id) if _kebab(m.id) == str(m.value).lower() else f"{m.value} ({_kebab(m.id)})"
        for m in argument.enum
    )
    raise CliError(f"{argument.id}: {given!r} is not one of {codes}")


def usage_of(command: Command) -> str:
    parts = []
    for a in command.arguments:
        word = (a.value or "").lower() if a.type == "keyword" else a.id.upper()
        parts.append(f"[{word}]" if a.optional or a.type == "keyword" else word)
    return " ".join([command.name, *parts])


def list_commands(vendor: str | None) -> str:
    out = []
    for vendor_id, title in VENDORS.items():
        if vendor is not None and vendor_id != vendor:
            continue
        out.append(f"{vendor_id}: {title}")
        for command in (c for c in COMMANDS if c.vendor == vendor_id):
            out.append(f"  {usage_of(command):<40} {_short(command.doc)}")
            for a in _typed(command):
                choices = (
                    f" ({', '.join(_kebab(m.id) for m in a.enum)})" if a.enum is not None else ""
                )
                out.append(
                    f"      {a.id.upper()}: {a.type}{', optional' if a.optional else ''}{choices}. "
                    f"{_short(a.doc)}"
                )
        groups: dict[str, list[Shortcut]] = {}
        for s in (s for s in SHORTCUTS if s.vendor == vendor_id):
            groups.setdefault(s.words[0], []).append(s)
        if groups:
            out.append("  shortcuts:")
        for name, shortcuts in groups.items():
            args = "|".join(" ".join(s.words[1:]) for s in shortcuts)
            doc = (
                shortcuts[0].doc
                if len(shortcuts) == 1
                else f"{shortcuts[0].command} "
                f"{' '.join(k.upper() for k, _ in shortcuts[0].values)} "
                + "|".join(v for s in shortcuts for _, v in s.values)
            )
            out.append(f"  {(name + ' ' + args).strip():<40} {_short(doc)}")
    return "\n".join(out) + "\n"


def _short(text: str, limit: int = 90) -> str:
    return text if len(text) <= limit else text[: limit - 1].rstrip() + "…"


def _split_options(words: list[str]) -> tuple[list[str], dict[str, str]]:
    positional, named = [], {}
    i = 0
    while i < len(words):
        word = words[i]
        if word.startswith("--") and len(word) > 2:
            key, eq, value = word[2:].partition("=")
            if not eq:
                if i + 1 >= len(words):
                    raise CliError(f"--{key} needs a value")
                i += 1
                value = words[i]
            named[key.replace("-", "_").lower()] = value
        else:
            positional.append(word)
        i += 1
    return positional, named


def build(vendor: str, words: list[str], checksum: bool = True) -> bytes:
    """The bytes of the command `words` (name and arguments) of `vendor`; raises CliError."""
    data: bytes = build_sentence(vendor, words, checksum).to_bytes()
    return data


def build_sentence(vendor: str, words: list[str], checksum: bool = True) -> Any:
    """The command sentence `words` (name and arguments) of `vendor`, every field checked;
    raises CliError."""
    vendor = _vendor(vendor)
    if not words:
        raise CliError("which command? see nmea command --list " + vendor)
    positional, named = _split_options(words)
    shortcut = next(
        (
            s
            for s in SHORTCUTS
            if s.vendor == vendor and list(s.words) == [w.lower() for w in positional]
        ),
        None,
    )
    if shortcut is not None:
        positional, named = [shortcut.command], {**dict(shortcut.values), **named}
    elif any(s.vendor == vendor and s.words[0] == positional[0].lower() for s in SHORTCUTS):
        choices = [
            " ".join(s.words[1:])
            for s in SHORTCUTS
            if s.vendor == vendor and s.words[0] == positional[0].lower()
        ]
        raise CliError(f"{positional[0]} takes one of: {', '.join(choices)}")
    name = positional[0].lower()
    command = next((c for c in COMMANDS if c.vendor == vendor and c.name == name), None)
    if command is None:
        known = ", ".join(c.name for c in COMMANDS if c.vendor == vendor)
        raise CliError(f"{vendor} has no command {name!r}; its commands: {known}")
    typed = _typed(command)
    given = positional[1:]
    values: dict[str, str] = {}
    for a in command.arguments:  # positional, in field order; a keyword may be typed or left out
        if not given:
            break
        if a.type == "keyword":
            if given[0].upper() == (a.value or "").upper():
                given.pop(0)
        else:
            values[a.id] = given.pop(0)
    if given:
        raise CliError(f"too many arguments; usage: {usage_of(command)}")
    for key, value in named.items():
        if key not in {a.id for a in typed}:
            raise CliError(
                f"{command.name} has no argument --{key.replace('_', '-')}; "
                f"usage: {usage_of(command)}"
            )
        if key in values and values[key] != value:
            raise CliError(f"{key} given twice")
        values[key] = value
    texts: list[str] = []
    for a in command.arguments:
        if a.type == "keyword":
            texts.append(a.value or "")
        elif a.id in values:
            text = values[a.id]
            texts.append(_enum_code(a, text) if a.enum is not None and a.type == "enum" else text)
        elif a.optional:
            break
        else:
            raise CliError(f"missing {a.id.upper()}; usage: {usage_of(command)}")
    later = [a.id for a in command.arguments[len(texts) :] if a.id in values]
    if later:
        raise CliError(f"{', '.join(later)} needs the optional arguments before it")
    address = command.layout.ADDRESS
    try:
        if command.text:
            sentence = command.layout.parse_fields(
                address, texts, None, " ".join([address, *texts])
            )
        else:
            sentence = command.layout.parse_fields(address, texts, "upper" if checksum else None)
        sentence.to_bytes()
        return sentence
    except NmeaError as err:
        if err.kind == "bad_field" and err.name:
            raise CliError(
                f"{command.name} {err.name}: {err.message}; usage: {usage_of(command)}"
            ) from None
        raise CliError(str(err)) from None


def command(args: argparse.Namespace) -> int:
    if args.list:
        vendor = _vendor(args.words[0]) if args.words else None
        sys.stdout.write(list_commands(vendor))
        return 0
    if not args.words:
        raise CliError("give VENDOR NAME [ARGS], or --list")
    data = build(args.words[0], args.words[1:], checksum=not args.no_checksum)
    sys.stdout.buffer.write(data)
    sys.stdout.flush()
    return 0


# --------------------------------------------------------------------------------------------
# listen, send: a receiver on a serial port (pyserial, imported only by these verbs)


class PortProblem(CliError):
    """The port cannot be opened or used, or pyserial is missing: exit status 3."""

    status = 3


def _baud(text: str) -> int:
    try:
        return check_baud(text)
    except ValueError as err:
        raise CliError(f"--baud {err}") from None


def _seconds(option: str, text: str | float | None) -> float | None:
    if text is None:
        return None
    try:
        value = float(text)
    except ValueError:
        value = -1.0
    if not value > 0 or value == float("inf"):
        raise CliError(f"{option} {text!r}: give a number of seconds above 0")
    return value


def _open_source(args: argparse.Namespace, **options: Any) -> Receiver:
    """The receiver of --port, --tcp or --udp (listen only): exactly one of them."""
    udp = getattr(args, "udp", None)
    sources = (("--port", args.port), ("--tcp", args.tcp), ("--udp", udp))
    given = [name for name, value in sources if value]
    if len(given) > 1:
        raise CliError(f"give one source, not {' and '.join(given)}")
    if getattr(args, "group", None) and udp is None:
        raise CliError("--group joins a multicast group of a UDP port: give --udp PORT too")
    if args.tcp:
        try:
            host, port = host_port(args.tcp)
        except ValueError as err:
            raise CliError(f"--tcp {err}") from None
        try:
            return Receiver(tcp_feed(host, port), **options)
        except OSError as err:
            raise PortProblem(f"cannot connect to {args.tcp}: {err.strerror or err}") from None
    if udp is not None:
        if not 0 < udp < 65536:
            raise CliError(f"--udp {udp}: give a port number from 1 to 65535")
        try:
            return Receiver(udp_feed(udp, args.group, args.interface or ""), **options)
        except OSError as err:
            where = f"group {args.group} on UDP port {udp}" if args.group else f"UDP port {udp}"
            raise PortProblem(f"cannot listen to {where}: {err.strerror or err}") from None
    if not args.port:
        also = ", --tcp HOST:PORT or --udp PORT" if hasattr(args, "udp") else " or --tcp HOST:PORT"
        raise CliError(f"which port? give --port DEVICE (e.g. --port /dev/ttyUSB0){also}")
    try:
        return Receiver.open(args.port, _baud(args.baud), **options)
    except ReceiverError as err:
        raise PortProblem(str(err)) from None


def _append_log(path: str | None) -> IO[bytes] | None:
    if path is None:
        return None
    try:
        return open(path, "ab")
    except OSError as err:
        raise CliError(f"cannot write {path}: {err.strerror}") from None


def listen(args: argparse.Namespace) -> int:
    fields, wanted = view_of(args)
    duration = _seconds("--duration", args.duration)
    if args.count is not None and args.count <= 0:
        raise CliError(f"--count {args.count}: give a number of sentences above 0")
    summary = Summary()
    with _open_source(args) as receiver:
        receiver.log = log = _append_log(args.log)
        lines_read = cast(Iterator[bytes | int], receiver.lines(duration))  # not binary: lines only
        stream = framed_records(lines_read, wanted, summary, **parse_options(args))
        if args.count is not None:
            stream = islice(stream, args.count)
        try:
            write_records(stream, args.format, fields, sys.stdout, live=True)
        except KeyboardInterrupt:  # Ctrl-C: the normal way to stop
            sys.stdout.flush()
        except BrokenPipeError:  # `nmea listen ... | head`
            _quiet_stdout()
            return 0
        except ReceiverError as err:
            raise PortProblem(str(err)) from None
        finally:
            if log is not None:
                log.close()
    if not args.quiet:
        summary.write(sys.stderr)
    return 0


SEND_OPTIONS = {
    "--port": "port",
    "--tcp": "tcp",
    "--baud": "baud",
    "--timeout": "timeout",
    "--log": "log",
}
SEND_FLAGS = {"--show-all": "show_all"}


def _arguments_of(vendor: str, name: str) -> set[str]:
    """The argument ids of the command (or of the shortcut's commands) that `name` names."""
    vendor, name = vendor.lower(), name.lower()
    names = {name} | {s.command for s in SHORTCUTS if s.vendor == vendor and s.words[0] == name}
    return {a.id for c in COMMANDS if c.vendor == vendor and c.name in names for a in c.arguments}


def send_options(argv: list[str]) -> argparse.Namespace:
    """`nmea send`'s own options, anywhere on the line, and the command's words. After VENDOR
    NAME an option that is also an argument of that command is the command's
    (`mtk_pmtk pmtk251 --baud 115200`)."""
    values: dict[str, Any] = {"port": None, "tcp": None, "baud": "9600", "timeout": "5"}
    values["log"] = None
    values["show_all"] = False
    words: list[str] = []
    i = 0
    while i < len(argv):
        word = argv[i]
        key, eq, value = word.partition("=")
        mine = key in SEND_OPTIONS or (key in SEND_FLAGS and not eq)
        if mine and len(words) >= 2 and key[2:].replace("-", "_") in _arguments_of(*words[:2]):
            mine = False
        if not mine:
            words.append(word)
        elif key in SEND_FLAGS:
            values[SEND_FLAGS[key]] = True
        else:
            if not eq:
                if i + 1 >= len(argv):
                    raise CliError(f"{key} needs a value")
                i += 1
                value = argv[i]
            values[SEND_OPTIONS[key]] = value
        i += 1
    return argparse.Namespace(words=words, **values)


def _line_of(data: bytes) -> str:
    return data.decode("latin-1").rstrip("\r\n")


def _meanwhile(items: list[Any], out: IO[str]) -> None:
    for item in items:
        if isinstance(item, NmeaError):
            out.write(f"  ({item.kind}: {item})\n")
        else:
            name, _, fields = describe(item)
            out.write(f"  {name}  {_summary(fields)}\n")


def send(args: argparse.Namespace) -> int:
    if args.words[:1] == ["ubx"]:  # a UBX message: apps/ubx_cli.py
        from .ubx_cli import send_ubx

        return send_ubx(args)
    if len(args.words) < 2:
        raise CliError("give VENDOR NAME [ARGS] (or ubx MESSAGE [JSON]); see nmea command --list")
    timeout = _seconds("--timeout", args.timeout)
    assert timeout is not None
    sentence = build_sentence(args.words[0], args.words[1:])
    out = sys.stdout
    with _open_source(args, errors="yield") as receiver:
        receiver.log = log = _append_log(args.log)
        try:
            data = receiver.write(sentence)
            out.write(f"> {_line_of(data)}\n")
            if not getattr(sentence, "REPLY_RULES", ()):
                out.write(f"nothing answers {sentence.SENTENCE} in the spec: sent, not waiting\n")
                return 0
            out.flush()
            reply = receiver.wait_reply(sentence, timeout)
        except ReplyTimeout as err:
            if args.show_all:
                _meanwhile(err.received, out)
            out.flush()
            sys.stderr.write(f"nmea: {err}\n")
            return 2
        except ReceiverError as err:
            raise PortProblem(str(err)) from None
        finally:
            if log is not None:
                log.close()
    if args.show_all:
        _meanwhile(reply.received, out)
    name, _, fields = describe(reply.sentence)
    out.write(f"< {_line_of(reply.line)}\n{reply.outcome}: {name}  {_summary(fields)}\n")
    out.flush()
    return 0 if reply.ok else 1


# --------------------------------------------------------------------------------------------


def _view_options(verb: argparse.ArgumentParser) -> None:
    """The options of what `show` and `listen` print."""
    form = verb.add_mutually_exclusive_group()
    form.add_argument(
        "--json", dest="format", action="store_const", const="json", help="JSON lines"
    )
    form.add_argument(
        "--csv", dest="format", action="store_const", const="csv", help="CSV with a header row"
    )
    verb.add_argument(
        "--fields", metavar="F,F...", help="the columns: field ids, line, talker, sentence"
    )
    verb.add_argument(
        "--sentences", metavar="S,S...", help="only these sentences (GGA,RMC or PSTMTG)"
    )
    verb.add_argument(
        "--lenient",
        action="store_true",
        help="keep sentences with fields that do not fit (left empty)",
    )
    verb.add_argument(
        "--strict",
        action="store_true",
        help="refuse sentences with a number outside its field's range (kept by default)",
    )
    verb.add_argument("-q", "--quiet", action="store_true", help="no summary on stderr")


def _port_options(verb: argparse.ArgumentParser) -> None:
    verb.add_argument(
        "--port",
        metavar="DEVICE",
        help="the serial port: /dev/ttyUSB0, COM3, or a pyserial URL such as rfc2217://host:port",
    )
    verb.add_argument(
        "--tcp", metavar="HOST:PORT", help="a receiver or feed behind TCP instead of a serial port"
    )
    verb.add_argument(
        "--baud", default="9600", metavar="N", help="its speed in bit/s (default: 9600)"
    )
    verb.add_argument(
        "--log",
        metavar="FILE",
        help="append every byte received to FILE, exactly as it came (UDP: each datagram's lines)",
    )


def _command_words(verb: argparse.ArgumentParser, help: str) -> None:
    """VENDOR NAME [ARGS]: a command as `command` and `send` take it."""
    verb.add_argument("words", nargs=argparse.REMAINDER, metavar="VENDOR NAME [ARGS]", help=help)


def parser() -> argparse.ArgumentParser:
    top = argparse.ArgumentParser(
        prog="nmea",
        formatter_class=argparse.RawDescriptionHelpFormatter,
        description="Read NMEA 0183 logs and live receivers, and build and send GNSS receiver "
        "commands.",
        epilog="`nmea LOG` is `nmea show LOG`.\n\n"
        + SHOW_EXAMPLES
        + "\n"
        + COMMAND_EXAMPLES
        + "\n"
        + LIVE_EXAMPLES,
    )
    top.add_argument("--version", action="version", version=f"nmea {__version__}")
    verbs = top.add_subparsers(dest="verb", metavar="show|command|listen|send|config|report|export")
    s = verbs.add_parser(
        "show",
        help="print the sentences of a log (a file, or - for stdin)",
        formatter_class=argparse.RawDescriptionHelpFormatter,
        epilog=SHOW_EXAMPLES,
    )
    s.add_argument("log", nargs="?", default="-", help="the log file, or - (the default) for stdin")
    _view_options(s)
    s.add_argument(
        "--fixes", action="store_true", help="one row per epoch: the fixes the sentences make"
    )
    add_progress_options(s)
    s.set_defaults(format="table", run=show)
    c = verbs.add_parser(
        "command",
        help="print the bytes of a vendor command",
        formatter_class=argparse.RawDescriptionHelpFormatter,
        epilog=COMMAND_EXAMPLES,
    )
    c.add_argument(
        "--list", action="store_true", help="list the commands (of one vendor) with their arguments"
    )
    c.add_argument(
        "--no-checksum", action="store_true", help="send a '$' command without its checksum"
    )
    _command_words(c, f"vendors: {', '.join(VENDORS)}")
    c.set_defaults(run=command)
    li = verbs.add_parser(
        "listen",
        help="print the sentences of a live receiver on a serial port (needs pyserial) or of "
        "the network",
        formatter_class=argparse.RawDescriptionHelpFormatter,
        epilog=LIVE_EXAMPLES,
    )
    _port_options(li)
    li.add_argument(
        "--udp",
        type=int,
        metavar="PORT",
        help="the datagrams of a UDP port (IEC 61162-450 or plain)",
    )
    li.add_argument(
        "--group", metavar="ADDR", help="join this multicast group (IEC 61162-450: 239.192.0.x)"
    )
    li.add_argument(
        "--interface",
        metavar="ADDR",
        help="the local address to listen on (its interface joins --group)",
    )
    li.add_argument("--count", type=int, metavar="N", help="stop after N sentences shown")
    li.add_argument("--duration", metavar="S", help="stop after S seconds")
    _view_options(li)
    li.set_defaults(format="table", run=listen)
    se = verbs.add_parser(
        "send",
        help="send a vendor command to a receiver and print its reply (needs pyserial)",
        usage="nmea send --port DEVICE [--baud N] [--timeout S] [--show-all] [--log FILE] "
        "VENDOR NAME [ARGS]",
        formatter_class=argparse.RawDescriptionHelpFormatter,
        epilog=LIVE_EXAMPLES,
    )
    _port_options(se)
    se.add_argument(
        "--timeout", default="5", metavar="S", help="how long to wait for the reply (default: 5)"
    )
    se.add_argument(
        "--show-all", action="store_true", help="print the sentences that come before the reply"
    )
    _command_words(se, "the command, as `nmea command` takes it; or ubx MESSAGE [JSON], or ubx HEX")
    verbs.add_parser(
        "config",
        help="read, write and delete u-blox configuration keys by name (CFG-VALGET, CFG-VALSET, "
        "CFG-VALDEL; see nmea config -h)",
        add_help=False,
    )
    from .export import add_parser as add_export  # here: export and report import this module
    from .report import add_parser as add_report

    add_report(verbs)
    add_export(verbs)
    return top


VERBS = ("show", "command", "listen", "send", "config", "report", "export", "-h", "--help", "--version")


def main(argv: list[str] | None = None) -> int:
    args = list(sys.argv[1:] if argv is None else argv)
    if not args and sys.stdin.isatty():  # `nmea` alone at a prompt: nothing to read, say how
        args = ["--help"]
    if not args or args[0] not in VERBS:
        args.insert(0, "show")
    try:
        if args[0] in ("command", "send") and any(a in ("-h", "--help") for a in args[1:]):
            parser().parse_args([args[0], "--help"])
        if args[0] == "command":  # its options may come anywhere; `--field value` are the command's
            flags = [a for a in args[1:] if a in ("--list", "--no-checksum")]
            words = [a for a in args[1:] if a not in flags]
            return command(
                argparse.Namespace(
                    list="--list" in flags, no_checksum="--no-checksum" in flags, words=words
                )
            )
        if args[0] == "send":
            return send(send_options(args[1:]))
        if args[0] == "config":  # u-blox configuration keys: apps/ubx_cli.py
            from .ubx_cli import config

            return config(args[1:])
        parsed = parser().parse_args(args)
        result: int = parsed.run(parsed)
        return result
    except CliError as err:
        sys.stderr.write(f"nmea: {err}\n")
        return err.status
    except KeyboardInterrupt:
        return 130


if __name__ == "__main__":
    raise SystemExit(main())
