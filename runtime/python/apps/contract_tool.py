"""The `nmea-py` tool: `decode` NMEA lines to JSON, `encode` that JSON back to sentences,
`stream` a byte stream that may hold garbage, cut lines or sentences run together, `fixes` the
fixes of NMEA lines (one JSON object per epoch: Fix.to_dict, docs/fixes.md). decode and stream
add the AIS message a line carries, stream also those joined across sentences.

Same behaviour, byte for byte, as nmea-c and nmea-rs; see docs/json.md.
"""

from __future__ import annotations

import json
import sys
from collections.abc import Iterable, Iterator
from typing import TYPE_CHECKING, Any

from .. import __version__
from ..api import Tagged, encode_object, parse, read_json_line, to_json
from ..fixes import fixes
from ..runtime import NmeaError
from ..stream import BadFrame, BinaryFrame, Item, lines as framed, too_long, typed

if TYPE_CHECKING:
    from ..assembly import Assembled

USAGE = (
    "usage: nmea-py decode|stream [--values] [--lenient] [--require-checksum] [--strict] [--ubx] [--rtcm3]"
    " | encode | fixes | --version\n"
    "       (reads stdin, writes stdout)\n"
)
FLAGS = ("--values", "--lenient", "--require-checksum", "--strict", "--ubx", "--rtcm3")


def lines(data: bytes) -> list[str]:
    """Split on LF, drop one CR before it; a last line without LF counts, an empty tail does not."""
    parts = data.split(b"\n")
    if parts and parts[-1] == b"":
        parts.pop()
    return [(p[:-1] if p.endswith(b"\r") else p).decode("latin-1") for p in parts]


def with_message(text: str, assembled: Assembled) -> str:
    """A line's JSON with the AIS message it completes last: `ais`, or `ais_error` when its payload
    does not decode."""
    if assembled.message is not None:
        return f'{text[:-1]},"ais":{json.dumps(assembled.message.to_dict(), separators=(",", ":"))}}}'
    assert assembled.error is not None
    return f'{text[:-1]},"ais_error":{assembled.error.error_json()}}}'


def with_ubx(frame: BinaryFrame) -> str:
    """stream --ubx: a UBX frame's JSON with the message it carries: `ubx`, its decoded JSON
    (that of generated/vectors/ubx.jsonl), or `ubx_error` when its payload does not decode; a
    SkyTraq, SiRF, CASIC or SBF frame's alike, under its protocol's name (`sirf`, `sirf_error`: the
    JSON of generated/vectors/binary.jsonl)."""
    text = frame.to_json()
    if not typed(frame.protocol):
        return text
    try:
        message = frame.message()
    except NmeaError as err:
        return f'{text[:-1]},"{frame.protocol}_error":{err.error_json()}}}'
    return f'{text[:-1]},"{frame.protocol}":{json.dumps(message.to_dict(), separators=(",", ":"))}}}'


def with_rtcm3(frame: BinaryFrame) -> str:
    """stream --rtcm3: an RTCM 3 frame's JSON with the message it carries: `rtcm3`, its decoded
    JSON (that of generated/vectors/rtcm3.jsonl), or `rtcm3_error` when its payload does not
    decode."""
    text = frame.to_json()
    try:
        message = frame.message()
    except NmeaError as err:
        return f'{text[:-1]},"rtcm3_error":{err.error_json()}}}'
    return f'{text[:-1]},"rtcm3":{json.dumps(message.to_dict(), separators=(",", ":"))}}}'


def decoded(items: Iterable[str], values: bool, options: dict[str, bool]) -> Iterator[str]:
    """decode: each line's JSON, with the AIS message of a sentence that carries a whole one."""
    for line in items:
        try:
            sentence = parse(line, **options)
        except NmeaError as err:
            yield err.to_json()
            continue
        text = to_json(sentence, values)
        inner = sentence.sentence if isinstance(sentence, Tagged) else sentence
        fragment = getattr(inner, "fragment", None)
        if fragment is not None and fragment.total == 1:
            from ..assembly import MessageAssembler  # by the first AIS line

            (assembled,) = MessageAssembler().feed(sentence)  # a message of one sentence, at once
            text = with_message(text, assembled)
        yield text


def streamed(items: Iterable[Item], values: bool, options: dict[str, bool], ubx: bool = False,
             rtcm3: bool = False) -> Iterator[str]:
    """stream: each framed line's JSON, with the AIS message it completes (of one sentence or
    joined across several); after it, an incomplete_message error for each message it gives up,
    and at the end for those left under way; each binary frame's JSON (`ubx`: with the UBX
    message it carries; `rtcm3`: an RTCM 3 frame with its message)."""
    from ..assembly import MessageAssembler

    assembler = MessageAssembler()
    for item in items:
        if isinstance(item, BinaryFrame) and rtcm3 and item.protocol == "rtcm3":
            yield with_rtcm3(item) if typed("rtcm3") else item.to_json()
            continue
        if isinstance(item, BinaryFrame) and ubx and item.protocol != "rtcm3":
            yield with_ubx(item)
            continue
        if isinstance(item, (BinaryFrame, BadFrame)):
            yield item.to_json()
            continue
        try:
            if isinstance(item, int):
                raise too_long(item)
            sentence: Any = parse(item, **options)
        except NmeaError as err:
            yield err.to_json()
            continue
        text = to_json(sentence, values)
        given_up = []
        for assembled in assembler.feed(sentence):
            if assembled.error is not None and assembled.error.kind == "incomplete_message":
                given_up.append(assembled.error.to_json())
            else:
                text = with_message(text, assembled)
        yield text
        yield from given_up
    for assembled in assembler.finish():
        assert assembled.error is not None
        yield assembled.error.to_json()


def main(argv: list[str] | None = None) -> int:
    args = sys.argv[1:] if argv is None else argv
    verb, flags = (args[0], args[1:]) if args else ("", [])
    if (
        verb in ("decode", "stream")
        and all(f in FLAGS for f in flags)
        and len(set(flags)) == len(flags)
    ):
        values, lenient, required, strict, ubx, rtcm3 = (f in flags for f in FLAGS)
        options = {"lenient": lenient, "require_checksum": required, "strict": strict}
        out: Iterator[str]
        if verb == "decode":
            out = decoded(lines(sys.stdin.buffer.read()), values, options)
        else:
            out = streamed(framed(sys.stdin.buffer, binary=True), values, options, ubx, rtcm3)
        write = sys.stdout.buffer.write
        for text in out:
            write(text.encode("latin-1") + b"\n")
        return 0
    if verb == "--version" and not flags:
        print(f"nmea-py {__version__}")
        return 0
    if verb == "fixes" and not flags:
        for fix in fixes(lines(sys.stdin.buffer.read())):
            sys.stdout.write(json.dumps(fix.to_dict(), separators=(",", ":")) + "\n")
        return 0
    if verb == "encode" and not flags:
        for line in lines(sys.stdin.buffer.read()):
            try:
                obj = read_json_line(line)
            except NmeaError as err:
                text = err.to_json()
            else:
                if isinstance(obj, dict) and obj.get("ok") is False:
                    continue  # decode's line for a line it refused: nothing to encode
                text = encode_object(obj)
            sys.stdout.buffer.write(text.encode("latin-1") + b"\n")
        return 0
    sys.stderr.write(USAGE)
    return 2


if __name__ == "__main__":
    raise SystemExit(main())
