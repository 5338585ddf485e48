"""The Python benchmark driver: reads the corpus into memory once, then times one operation of one
implementation over its lines and prints a JSON object.

    driver.py IMPL OP CORPUS [--lines N] [--by-type]

IMPL: ours (nmeaspec), pynmea2, pynmea2-allfields (parse, then read every attribute its `fields`
table names, since pynmea2 converts lazily), pynmeagps (NMEAReader.parse); over the AIS corpus
(corpus.build_ais), ours-ais (the line parsed and its AIS message decoded, every field; serialize:
the message encoded, the sentence written back) and pyais (pyais.decode; serialize: encode_msg); over the UBX
corpus (corpus.build_ubx, a frame as hex digits a line), ours-ubx (nmeaspec.ubx_messages.decode, every field)
and pyubx2 (UBXReader.parse, checksum checked), parse only. OP: parse, serialize
(the lines are parsed chunk by chunk outside the timed region, only writing them back is timed:
ours .to_sentence(), pynmea2 .render(), pynmeagps .serialize()), roundtrip (both, per line,
counting lines written back byte for byte), fixes (ours only: each line parsed and fed to the fix
assembler, nmeaspec.fixes; ok lines are the lines parsed). --lines N: only the first N lines.
"""

from __future__ import annotations

import argparse
import json
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "generated" / "python"))

CHUNK = 2048
UBX = ("ours-ubx", "pyubx2")  # over the UBX corpus (corpus.build_ubx)


def implementation(name: str):
    """(parse, serialize) of `name`: parse(line without CR LF, line with it) returns the parsed
    object or raises; serialize(parsed) returns the text written back, comparable with the line
    (str without CR LF, or bytes with it: see `serialized_with_crlf`)."""
    if name == "ours":
        import nmeaspec

        parse = nmeaspec.parse
        return (lambda text, raw: parse(text)), (lambda sentence: sentence.to_sentence())
    if name in ("pynmea2", "pynmea2-allfields"):
        import pynmea2

        parse = pynmea2.parse
        if name == "pynmea2":
            return (lambda text, raw: parse(text)), (lambda message: message.render())

        def parse_all(text, raw):
            message = parse(text)
            for field in message.fields:
                getattr(message, field[1])
            return message

        return parse_all, None
    if name == "pynmeagps":
        from pynmeagps import NMEAReader

        reader_parse = NMEAReader.parse

        def parse_gps(text, raw):
            message = reader_parse(raw)
            if message is None:
                raise ValueError("not parsed")
            return message

        return parse_gps, (lambda message: message.serialize())
    if name == "ours-ais":
        import nmeaspec

        parse = nmeaspec.parse

        def decode_ais(text, raw):
            sentence = parse(text)
            return sentence, sentence.message  # every field of the message decoded

        def encode_ais(parsed):
            sentence, message = parsed
            payload, fill_bits = message.encode()
            return sentence.to_sentence() if (payload, fill_bits) == (sentence.payload, int(sentence.fill_bits)) else ""

        return decode_ais, encode_ais
    if name == "ours-ubx":
        from nmeaspec import ubx_messages

        decode_ubx = ubx_messages.decode
        return (lambda frame, raw: decode_ubx(frame)), None  # every field of the message decoded
    if name == "pyubx2":
        import pyubx2

        reader_parse, validate = pyubx2.UBXReader.parse, pyubx2.VALCKSUM
        return (lambda frame, raw: reader_parse(frame, validate=validate)), None
    if name == "pyais":
        import pyais

        decode, encode = pyais.decode, pyais.encode_msg

        def decode_pyais(text, raw):
            fields = text.split(",")
            return fields[0][3:], fields[4], decode(text)  # pyais decodes every field eagerly

        def encode_pyais(parsed):
            kind, channel, message = parsed
            channel = {"1": "A", "2": "B", "": "A"}.get(channel, channel)  # pyais takes A or B only
            return encode(message, talker_id="AI", sentence_type=kind, radio_channel=channel)[0]

        return decode_pyais, encode_pyais
    sys.exit(f"unknown implementation {name}")


def serialized_with_crlf(name: str) -> bool:
    return name == "pynmeagps"


def time_parse(parse, lines):
    ok = 0
    start = time.perf_counter()
    for text, raw in lines:
        try:
            parse(text, raw)
        except Exception:  # a peer's error of any kind is a line it did not parse
            continue
        ok += 1
    return time.perf_counter() - start, ok


def time_serialize(parse, serialize, with_crlf, lines):
    seconds, ok = 0.0, 0
    for begin in range(0, len(lines), CHUNK):
        parsed = []
        for text, raw in lines[begin:begin + CHUNK]:
            try:
                parsed.append((parse(text, raw), raw if with_crlf else text))
            except Exception:
                pass
        start = time.perf_counter()
        written = [serialize(item) for item, _ in parsed]
        seconds += time.perf_counter() - start
        ok += sum(out == expected for out, (_, expected) in zip(written, parsed))
    return seconds, ok


def time_roundtrip(parse, serialize, with_crlf, lines):
    ok = 0
    start = time.perf_counter()
    for text, raw in lines:
        try:
            out = serialize(parse(text, raw))
        except Exception:
            continue
        ok += out == (raw if with_crlf else text)
    return time.perf_counter() - start, ok


def time_fixes(lines):
    from nmeaspec.fixes import FixAssembler
    from nmeaspec import NmeaError, parse

    assembler = FixAssembler()
    ok = 0
    start = time.perf_counter()
    for text, _ in lines:
        try:
            sentence = parse(text)
        except NmeaError:
            continue
        ok += 1
        assembler.feed(sentence)
    assembler.close()
    return time.perf_counter() - start, ok


def run(name, op, lines):
    if op == "fixes" and name == "ours":
        return time_fixes(lines)
    parse, serialize = implementation(name)
    if op == "parse":
        return time_parse(parse, lines)
    if serialize is None:
        sys.exit(f"{name} has no serializer")
    if op == "serialize":
        return time_serialize(parse, serialize, serialized_with_crlf(name), lines)
    if op == "roundtrip":
        return time_roundtrip(parse, serialize, serialized_with_crlf(name), lines)
    sys.exit(f"unknown operation {op}")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("impl")
    parser.add_argument("op")
    parser.add_argument("corpus", type=Path)
    parser.add_argument("--lines", type=int, default=0)
    parser.add_argument("--by-type", action="store_true")
    args = parser.parse_args()
    data = args.corpus.read_bytes()
    raws = data.splitlines(keepends=True)
    if args.lines:
        raws = raws[:args.lines]
    lines = [(raw.decode("ascii").rstrip("\r\n"), raw) for raw in raws]
    if args.impl in UBX:  # the UBX corpus: a frame's bytes as hex digits a line
        lines = [(bytes.fromhex(text), raw) for text, raw in lines]
    run(args.impl, args.op, lines[:2000])  # warm up: imports, caches
    seconds, ok = run(args.impl, args.op, lines)
    result = {"impl": args.impl, "op": args.op, "lines": len(lines), "bytes": sum(map(len, raws)),
              "ns_per_line": round(seconds * 1e9 / max(len(lines), 1), 2), "ok_lines": ok}
    if args.by_type:
        groups: dict[str, list] = {}
        for line in lines:
            groups.setdefault(line[0][3:6], []).append(line)
        result["by_type"] = {}
        for kind, group in groups.items():
            seconds, ok = run(args.impl, args.op, group)
            result["by_type"][kind] = {"ns_per_line": round(seconds * 1e9 / len(group), 2), "ok_lines": ok,
                                       "lines": len(group)}
    print(json.dumps(result))


if __name__ == "__main__":
    main()
