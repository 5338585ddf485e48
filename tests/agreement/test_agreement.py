"""The three tools (build/bin/nmea-{c,rs,py}) against each other and against the reference decoder:
on the manuals' examples, hand-written edge cases and every real receiver log in ../shared/corpus/real.

- decode and decode --values print byte-identical output in the three languages;
- decode prints exactly one JSON line per input line;
- every ok line re-encodes to exactly the input line;
- every line whose checksum is wrong is rejected as checksum_mismatch;
- on the examples, the output equals what the reference decoder (generator/reference.py) says.
"""

from __future__ import annotations

import bisect
import json
import os
import random
import subprocess
from dataclasses import dataclass
from functools import lru_cache
from pathlib import Path
from typing import Callable

import pytest
import yaml

ROOT = Path(__file__).resolve().parents[2]
# The tools under test: NMEA_TOOLS (make test-tools: build/test-bin), else make build's.
BIN = Path(os.environ.get("NMEA_TOOLS", ROOT / "build" / "bin"))
TOOLS = ["nmea-c", "nmea-rs", "nmea-py"]
CORPUS = ROOT.parent / "shared" / "corpus" / "real"
EDGE_CASES = Path(__file__).with_name("edge_cases.txt")
VECTORS = ROOT / "generated" / "vectors" / "examples.jsonl"
TOLERANCE = ROOT / "generated" / "vectors" / "tolerance.jsonl"
TAG_BLOCKS = ROOT / "generated" / "vectors" / "tag_blocks.jsonl"
TAG_BLOCK_LOGS = ROOT / "tests" / "data" / "tag_blocks" / "real.nmea"  # see PROVENANCE.md there


def run(tool: str, args: list[str], data: bytes) -> bytes:
    done = subprocess.run([str(BIN / tool), *args], input=data, capture_output=True, timeout=300)
    assert done.returncode == 0, f"{tool} {args} exited {done.returncode}: {done.stderr[-2000:]!r}"
    return done.stdout


def input_lines(data: bytes) -> list[bytes]:
    parts = data.split(b"\n")
    if parts and parts[-1] == b"":
        parts.pop()
    return [p[:-1] if p.endswith(b"\r") else p for p in parts]


def line_number(index: int) -> str:
    """How a failure names input line `index` of a stream read on its own."""
    return f"line {index + 1}"


def agreed(args: list[str], data: bytes, origin: Callable[[int], str] = line_number) -> bytes:
    """The output of `args`, after checking that the three tools agree byte for byte; `origin`
    names the input line of an index in a failure."""
    outputs = {tool: run(tool, args, data) for tool in TOOLS}
    reference = outputs[TOOLS[0]]
    for tool, out in outputs.items():
        if out != reference:
            a, b = reference.split(b"\n"), out.split(b"\n")
            diff = next(i for i in range(max(len(a), len(b))) if i >= len(a) or i >= len(b) or a[i] != b[i])
            line = input_lines(data)[diff] if diff < len(input_lines(data)) else b"(end)"
            pytest.fail(f"{TOOLS[0]} and {tool} disagree ({' '.join(args)}) on {origin(diff)}: {line[:200]!r}\n"
                        f"{TOOLS[0]}: {a[diff][:400] if diff < len(a) else b'(none)'!r}\n"
                        f"{tool}: {b[diff][:400] if diff < len(b) else b'(none)'!r}")
    return reference


@lru_cache(maxsize=None)
def decode_all(data: bytes, values: bool = False, origin: Callable[[int], str] = line_number) -> bytes:
    """decode's output, after checking that the three tools agree byte for byte."""
    return agreed(["decode", "--values"] if values else ["decode"], data, origin)


def check_stream(data: bytes, origin: Callable[[int], str] = line_number) -> list[dict]:
    """The properties every input must have; returns the decoded objects. `origin` names the input
    line of an index in a failure."""
    lines = input_lines(data)
    out = decode_all(data, False, origin).split(b"\n")
    assert out[-1] == b"" and len(out) - 1 == len(lines), "decode must print one line per input line"
    decode_all(data, True, origin)
    objects = [json.loads(line) for line in out[:-1]]
    ok = [i for i, obj in enumerate(objects) if obj["ok"]]
    ok_json = b"".join(out[i] + b"\n" for i in ok)
    encoded = {tool: run(tool, ["encode"], ok_json) for tool in TOOLS}
    for tool, text in encoded.items():
        assert text == encoded[TOOLS[0]], f"{tool} encodes differently from {TOOLS[0]}"
    back = encoded[TOOLS[0]].split(b"\n")[:-1]
    assert len(back) == len(ok)
    for i, again in zip(ok, back):
        assert again == lines[i], f"round trip changed {lines[i]!r} ({origin(i)}) into {again!r}"
    for i, (line, obj) in enumerate(zip(lines, objects)):
        if wrong_checksum(line):
            assert not obj["ok"] and obj["error"]["kind"] == "checksum_mismatch", (origin(i), line, obj)
    return objects


def wrong_checksum(line: bytes) -> bool:
    """A printable line of the form $...*HH whose two hex digits differ from the XOR of its body
    (after its last leading `$`: `$$GNGSA` is the sentence `$GNGSA` behind a stray `$`)."""
    if not line or line[:1] not in (b"$", b"!") or len(line) > 1024 or any(b < 0x20 or b > 0x7E for b in line):
        return False
    star = line.find(b"*")
    if star < 0 or len(line) != star + 3:
        return False
    digits = line[star + 1:].decode()
    if not all(c in "0123456789abcdefABCDEF" for c in digits) or (digits.lower() != digits and digits.upper() != digits):
        return False
    value = 0
    for byte in line[len(line) - len(line.lstrip(b"$")) or 1:star]:
        value ^= byte
    return value != int(digits, 16)


def sentence_json(output: bytes) -> list[str]:
    """decode's lines without the AIS message a line's object may end with (json.md: the tools add
    it; the reference decodes the sentence)."""
    lines = output.decode().splitlines()
    for member in (',"ais":', ',"ais_error":'):
        lines = [line[:line.find(member)] + "}" if member in line else line for line in lines]
    return lines


def test_tools_are_built() -> None:
    for tool in TOOLS:
        assert (BIN / tool).exists(), f"{tool} missing: run make build"


def test_examples_match_the_reference() -> None:
    vectors = [json.loads(line) for line in VECTORS.read_text().splitlines()]
    assert vectors, "no examples"
    lines = [v["line"] for v in vectors if v["line"]]
    data = "".join(line + "\n" for line in lines).encode()
    check_stream(data)
    assert sentence_json(decode_all(data)) == [v["decode"] for v in vectors if v["line"]]
    assert sentence_json(decode_all(data, True)) == [v["decode_values"] for v in vectors if v["line"]]
    damaged = [v for v in vectors if "raw_decode" in v]
    raw = "".join(v["raw"] + "\n" for v in damaged).encode()
    assert sentence_json(decode_all(raw)) == [v["raw_decode"] for v in damaged]


def test_tolerance_vectors() -> None:
    """A number outside its range is kept and flagged unless --strict, which refuses it as before;
    unknown codes of closed enums are refused; a one-digit checksum is kept and flagged unless
    --strict; each line with its options as the reference says,
    and what is kept encodes back to the line (with or without the problems of numbers kept)."""
    vectors = [json.loads(line) for line in TOLERANCE.read_text().splitlines()]
    kinds = set()
    for options in {tuple(v["options"]) for v in vectors}:
        chosen = [v for v in vectors if tuple(v["options"]) == options]
        data = "".join(v["line"] + "\n" for v in chosen).encode()
        out = agreed(["decode", *options], data).decode().splitlines()
        assert out == [v["decode"] for v in chosen], options
        kept = [(v["line"], o) for v, o in zip(chosen, out) if o.startswith('{"ok":true')]
        back = agreed(["encode"], "".join(o + "\n" for _, o in kept).encode()).decode().splitlines()
        assert back == [line for line, _ in kept], options
        if not options:  # a number kept outside its range encodes back without its problem listed
            bare = [json.dumps({k: v for k, v in json.loads(o).items() if k != "problems"}) for _, o in kept]
            back = agreed(["encode"], "".join(b + "\n" for b in bare).encode()).decode().splitlines()
            assert back == [line for line, _ in kept]
        kinds |= {p["kind"] for o in out for p in json.loads(o).get("problems", [])}
    assert kinds == {"out_of_range", "left_empty", "short_checksum"}


def test_tag_blocks() -> None:
    """The lines of spec/tag_block.yaml decode as the reference decoder says, in the three tools,
    each good one encodes back to the line, and `stream` reads them as `decode` does."""
    vectors = [json.loads(line) for line in TAG_BLOCKS.read_text().splitlines()]
    data = "".join(v["line"] + "\n" for v in vectors).encode()
    out = agreed(["decode"], data).decode().splitlines()
    assert sentence_json(agreed(["decode"], data)) == [v["decode"] for v in vectors]
    agreed(["decode", "--values"], data)
    assert agreed(["stream"], data).decode().splitlines() == out
    kept = [(v["line"], o) for v, o in zip(vectors, out) if o.startswith('{"ok":true')]
    back = agreed(["encode"], "".join(o + "\n" for _, o in kept).encode()).decode().splitlines()
    assert back == [line for line, _ in kept]
    assert {json.loads(o)["error"]["kind"] for o in out if not o.startswith('{"ok":true')} == {
        "bad_tag_block", "not_a_sentence", "checksum_mismatch"}


def test_real_tag_blocks() -> None:
    """Real lines with TAG blocks (tests/data/tag_blocks): decoded by every tool and written back
    byte for byte."""
    data = TAG_BLOCK_LOGS.read_bytes()
    objects = check_stream(data)
    assert all(o["ok"] and o["tag_blocks"] for o in objects)


def test_edge_cases() -> None:
    objects = check_stream(EDGE_CASES.read_bytes())
    kinds = {o["error"]["kind"] for o in objects if not o["ok"]}
    for kind in ("checksum_mismatch", "bad_checksum", "not_a_sentence", "too_few_fields", "too_many_fields",
                 "bad_field", "too_long"):
        assert kind in kinds, f"edge cases no longer produce {kind}"


def test_empty_and_unterminated_input() -> None:
    assert decode_all(b"") == b""
    assert decode_all(b"$GPHDT,1.0,T").count(b"\n") == 1
    assert decode_all(b"\n\n").count(b"\n") == 2


CORPUS_FILES = sorted(CORPUS.rglob("*.nmea"))


@dataclass(frozen=True)
class Corpus:
    """Every real log, one after the other, each ending with a newline: the tools run once per verb
    over all of them (the Python tool's start-up is most of a small log's time)."""

    data: bytes
    files: tuple[tuple[str, int], ...]  # each log's name and first line (0-based), in order

    def origin(self, index: int) -> str:
        """The file and line of the input line `index`."""
        at = bisect.bisect_right([first for _, first in self.files], index) - 1
        name, first = self.files[at]
        return f"{name}:{index - first + 1}"

    def lines_of(self, output: bytes) -> dict[str, list[bytes]]:
        """Output lines (one per input line), by log."""
        lines = output.split(b"\n")[:-1]
        bounds = [first for _, first in self.files] + [len(lines)]
        return {name: lines[bounds[i]:bounds[i + 1]] for i, (name, _) in enumerate(self.files)}


@lru_cache(maxsize=None)
def corpus() -> Corpus:
    parts, files, count = [], [], 0
    for path in CORPUS_FILES:
        data = path.read_bytes()
        data = data if data.endswith(b"\n") or not data else data + b"\n"
        files.append((str(path.relative_to(CORPUS)), count))
        parts.append(data)
        count += len(input_lines(data))
    return Corpus(b"".join(parts), tuple(files))


def test_real_logs() -> None:
    check_stream(corpus().data, corpus().origin)


def test_logs_outside_the_corpus() -> None:
    """The logs the typed share is measured on (tests/shapes: pynmeagps's, gpsd's, the marine
    libraries' test sentences, other libraries' and OpenCPN's captures, with their comment headers,
    binary frames, damaged and odd lines): the same properties, the three tools agreeing on every
    line, and the share of lines each decodes into a sentence the spec describes the same."""
    paths = [path for source in ("pynmeagps", "gpsd_logs", "marine", "libraries", "opencpn")
             for path in sorted((ROOT / "tests" / "data" / source).glob("*.log"))]
    parts, starts, count = [], [], 0
    for path in paths:
        data = path.read_bytes()
        data = data if data.endswith(b"\n") or not data else data + b"\n"
        starts.append((path.name, count))
        parts.append(data)
        count += len(input_lines(data))

    def origin(index: int) -> str:
        name, first = max((s for s in starts if s[1] <= index), key=lambda s: s[1])
        return f"{name}:{index - first + 1}"

    objects = check_stream(b"".join(parts), origin)
    typed = sum(o["ok"] and o.get("sentence") is not None for o in objects)
    assert typed > 5000, typed


def test_corpus_present() -> None:
    assert len(CORPUS_FILES) > 50, f"expected the real logs in {CORPUS}"


STREAM_CASES = Path(__file__).with_name("stream_cases.bin")
REGRESSIONS = ROOT / "fuzz" / "regressions"


AIS_LOGS = sorted((ROOT / "tests" / "data" / "ais").glob("*.chk")) + [ROOT / "tests" / "data" / "ais" / "sample.aivdm"]
AIS_CASES = ROOT / "tests" / "data" / "ais" / "assembly_cases.jsonl"


def test_ais_messages() -> None:
    """The AIS messages of gpsd's samples (tests/data/ais), of the shared assembly cases' lines, of
    the real logs that hold AIS and of the edge cases: decode adds each message of one sentence, stream also those joined across
    sentences and an incomplete_message line for each given up, byte for byte alike in the three
    tools, with and without --values and --lenient; every decode line with its message encodes
    back to the line."""
    cases = [json.loads(line) for line in AIS_CASES.read_text().splitlines()]
    data = b"".join(path.read_bytes() for path in AIS_LOGS)
    data += "".join(line + "\n" for case in cases for line in case["lines"]).encode()
    data += b"".join(path.read_bytes() for path in CORPUS_FILES if b"!AIVD" in path.read_bytes())
    data += EDGE_CASES.read_bytes()  # payloads that do not decode, fragments and keys out of bounds
    decoded = check_stream(data)
    one = [o for o in decoded if o["ok"] and o.get("sentence") in ("VDM", "VDO") and o["fields"]["fragment_count"] == "1"]
    assert one and all(("ais" in o) != ("ais_error" in o) for o in one)
    assert not [o for o in decoded if ("ais" in o or "ais_error" in o) and o not in one]
    for args in (["stream"], ["stream", "--values"], ["stream", "--lenient"]):
        streamed = [json.loads(line) for line in agreed(args, data).splitlines()]
        messages = [o for o in streamed if "ais" in o]
        given_up = [o for o in streamed if not o["ok"] and o["error"]["kind"] == "incomplete_message"]
        assert len(messages) > len([o for o in one if "ais" in o]) and given_up
    kinds = {o["ais_error"]["kind"] for o in decoded if "ais_error" in o}
    assert kinds >= {"bad_armor", "short_payload"}, kinds
    print(f"AIS: {len(one)} single-sentence messages decoded alike ({len(kinds)} error kinds), "
          f"{len(messages)} in stream with {len(given_up)} given up")


def _ais_line(bits: str) -> str:
    """A one-sentence !AIVDM line of a message's bits (armored, fill bits, checksum)."""
    fill = -len(bits) % 6
    bits += "0" * fill
    values = (int(bits[i:i + 6], 2) for i in range(0, len(bits), 6))
    body = f"AIVDM,1,1,,A,{''.join(chr(v + 48 if v < 40 else v + 56) for v in values)},{fill}"
    checksum = 0
    for char in body:
        checksum ^= ord(char)
    return f"!{body}*{checksum:02X}"


def test_ais_applications_of_random_bits() -> None:
    """Each application message of spec/ais/applications carried by a type 6 and a type 8 whose
    data are seeded random bits of every length a sentence holds (short of the layout, whole, past
    it; the cases of a choice, selector values no case names): the three tools decode them alike
    and encode each back byte for byte. It reaches the layouts no real capture gives an example of."""
    rng = random.Random(30)
    lines, keys = [], []
    for path in sorted((ROOT / "spec" / "ais" / "applications").glob("*.yaml")):
        doc = yaml.safe_load(path.read_text(encoding="utf-8"))
        routes = doc["application"]
        for app in routes if isinstance(routes, list) else [routes]:   # a layout sent under several FIs
            dacs = app["dac"] if isinstance(app["dac"], list) else [app["dac"]]
            if doc.get("length", 0) + 56 <= 372:   # a layout longer than a sentence (DAC 1 FI 13): the vectors'
                keys += [(dac, app["fid"]) for dac in dacs]   # payload built from it, in two sentences, only
            for carrier, dac in ((carrier, dac) for carrier in (6, 8) for dac in dacs):
                # type, repeat, MMSI; type 6: sequence number, destination, retransmit, spare; type 8: spare
                after = f"{rng.getrandbits(2):02b}{rng.getrandbits(30):030b}00" if carrier == 6 else "00"
                header = f"{carrier:06b}00{rng.getrandbits(30):030b}{after}{dac:010b}{app['fid']:06b}"
                for length in range(373 - len(header)):   # a sentence of at most 62 characters of payload
                    lines.append(_ais_line(header + f"{rng.getrandbits(length):0{length}b}"[:length]))
    objects = check_stream("".join(line + "\n" for line in lines).encode())
    decoded = {(o["ais"]["dac"], o["ais"]["fid"]) for o in objects if "application" in o.get("ais", {})}
    assert decoded == set(keys), set(keys) - decoded


def test_stream_verb() -> None:
    """stream frames garbage, cut lines, sentences run together, bare CRs and overlong lines the
    same way in the three tools, with and without --lenient."""
    data = STREAM_CASES.read_bytes() + EDGE_CASES.read_bytes()
    items = agreed(["stream"], data).split(b"\n")[:-1]
    assert len(items) > 20
    agreed(["stream", "--values", "--lenient"], data)
    agreed(["stream", "--require-checksum"], data)


# gpsd's logs of every protocol spec/binary describes, in tests/data/<protocol> (pysbf2's that mix
# NMEA and RTCM 3 with SBF among them)
BINARY_LOGS = [log for name in sorted(p.parent.name for p in (ROOT / "spec" / "binary").glob("*/protocol.yaml"))
               for log in sorted((ROOT / "tests" / "data" / name).glob("*.log"))]
# pysbf2's logs of SBF alone, run as one input (a tool's start costs more than their bytes)
SBF_LOGS = sorted((ROOT / "tests" / "data" / "sbf").glob("*.sbf"))
ACK = bytes.fromhex("b562 0501 0200 0600 0e37")  # UBX ACK-ACK of CFG-PRT
RTCM = bytes.fromhex("d3 0002 3ee0 6d7f60")  # RTCM 3, message number 0x3EE
GGA = b"$GPGGA,1*00\r\n"
SKY = bytes.fromhex("a0a1 0002 0201 03 0d0a")  # SkyTraq message 0x02, body 01: XOR 03
SIRF = bytes.fromhex("a0a2 0002 8401 0085 b0b3")  # SiRF MID 132, body 01: sum 0x85
CASIC = bytes.fromhex("bace 0000 0601 00000601")  # CASIC class 0x06, id 0x01, no payload
SBF = bytes.fromhex("2440 bd13 1a17 1800 702fcb1c3f091905170e0b0012070000")  # SBF ReceiverTime (5914, revision 0)
UNI = (ROOT / "tests" / "data" / "unicore" / "pyunigps_frames.log").read_bytes()[:33]  # Unicore, id 65512, 5 bytes
# binary bytes between sentences; a '$' and a line ending in a payload; a bad checksum; frames cut
# by a sentence and by the end; sync bytes that start no frame; a frame in a bad one; one longer
# than the readers hold; none in a TAG block
BINARY_CASES = (GGA + ACK + GGA + RTCM + b"$GPGGA" + ACK + b",1*00\r\n"
                + bytes.fromhex("b562 0102 0500") + b"$GP\r\n" + bytes.fromhex("4f88") + GGA
                + ACK[:-1] + b"\x00" + GGA + ACK[:7] + GGA + RTCM[:4] + GGA
                + b"\xb5\x00\xd3\xff" + GGA + b"\xb5\x62\x01\x02\x03\x00" + ACK + GGA
                + b"\xb5\x62" + bytes(6) + GGA + b"\xb5\x62\x01\x02\x00\x08" + b"abc\n" * 600 + b"\\s:\xb5\x62*00\\" + GGA
                # SkyTraq, SiRF and CASIC: whole; checksum or end bytes wrong; SiRF's reserved bit
                # set (too long); A0 starting neither
                + SKY + GGA + SKY[:-3] + b"\x04\r\n" + GGA + SIRF + SIRF[:-1] + b"\xb4" + GGA + CASIC
                + CASIC[:-1] + b"\x02" + GGA + b"\xa0\xa2\x80" + SIRF[3:] + GGA + b"\xa0\xa3" + GGA
                # SBF: whole, right after a sentence's text; its CRC wrong before a sentence; a length
                # under its header's 8 bytes; cut by a sentence; "$@" in a TAG block
                + b"$GPGGA,2" + SBF + GGA + SBF[:2] + b"\x00" + SBF[3:] + GGA + SBF[:6] + b"\x04\x00" + GGA
                + SBF[:12] + GGA + b"\\s:$@*00\\" + GGA
                # Unicore: whole after a sentence's text; its CRC wrong; NovAtel's AA 44 12 and AA 44 AA
                # (no frame: the third sync byte is checked as it comes); cut by a sentence; AA 44 before a sentence
                + b"$GPGGA,3" + UNI + GGA + UNI[:-1] + b"\x00" + GGA + b"\xaa\x44\x12\x1c\x2a\x00\x00\x20" + bytes(range(0x30, 0x44)) + GGA
                + b"\xaa\x44\xaa\x44" + UNI + UNI[:20] + GGA + b"\xaa\x44" + GGA + ACK[:7])


def test_binary_frames_in_stream() -> None:
    """stream splits gpsd's logs that interleave NMEA with UBX and RTCM 3, its SkyTraq, SiRF and
    CASIC logs, pysbf2's SBF logs (one with NMEA and RTCM 3), and the binary cases, byte for byte alike in the three tools: every frame's
    checksum right, the UBX frames those ubx.split_frames finds, and the items concatenating to the
    input less its line endings."""
    from tests.ubx.pyubx2_oracle import ubx
    from tests.ubx.test_binary_protocols import checked
    from nmeaspec.stream import crc24q

    sbf = b"".join(path.read_bytes() for path in SBF_LOGS)
    for data in [path.read_bytes() for path in BINARY_LOGS] + [sbf, BINARY_CASES]:
        objects = [json.loads(line) for line in agreed(["stream"], data).splitlines()]
        frames = [bytes.fromhex(o["frame"]) for o in objects if "frame" in o]
        assert [f for f, o in zip(frames, [o for o in objects if "frame" in o]) if o["protocol"] == "ubx"] == [
            frame.encode() for _, frame in ubx.split_frames(data)]
        for frame, o in zip(frames, [o for o in objects if "frame" in o]):
            assert o["length"] == len(frame)
            if o["protocol"] == "rtcm3":
                assert crc24q(frame[:-3]) == frame[-3:] and o["message_number"] == (frame[3] << 4 | frame[4] >> 4)
            elif o["protocol"] == "ubx":
                assert ubx.fletcher8(frame[2:-2]) == frame[-2:] and (o["class"], o["id"]) == (frame[2], frame[3])
            elif o["protocol"] == "sbf":  # the id's low 13 bits and top 3, little endian
                ident = int.from_bytes(frame[4:6], "little")
                assert checked(frame) == "sbf" and (o["number"], o["revision"]) == (ident & 0x1FFF, ident >> 13)
            elif o["protocol"] == "unicore":  # the message id, little endian, after AA 44 B5 and the CPU byte
                assert checked(frame) == "unicore" and o["message_id"] == int.from_bytes(frame[4:6], "little")
            elif o["protocol"] == "casic":
                assert checked(frame) == "casic" and (o["class"], o["id"]) == (frame[4], frame[5])
            else:  # SkyTraq and SiRF: the message id is the payload's first byte
                assert checked(frame) == o["protocol"] and o["id"] == frame[4]
        # the frames and rejected sync bytes lie in the input in their order (tests/ubx holds the
        # lines between them byte-exact)
        rest = data
        for o in objects:
            if "frame" in o or "bytes" in o:
                piece = bytes.fromhex(o.get("frame") or o["bytes"])
                rest = rest[rest.index(piece) + len(piece):]
    kinds = {o["error"]["kind"] for o in objects if "bytes" in o}
    assert kinds == {"bad_checksum", "too_long", "too_short", "nul_header", "cut"}, kinds
    agreed(["stream", "--values"], BINARY_CASES)


def test_lenient_and_required_checksum() -> None:
    data = EDGE_CASES.read_bytes()
    lenient = agreed(["decode", "--lenient"], data)
    assert b'"problems":[' in lenient
    kept = b"".join(line + b"\n" for line in lenient.split(b"\n") if line.startswith(b'{"ok":true'))
    back = agreed(["encode"], kept).split(b"\n")[:-1]
    originals = [line for line, out in zip(input_lines(data), lenient.split(b"\n")) if out.startswith(b'{"ok":true')]
    assert back == originals, "lenient decoding must round-trip exactly"
    assert b"missing_checksum" in agreed(["decode", "--require-checksum"], data)


def test_fuzz_regressions() -> None:
    """Every input a fuzzer ever found a problem with, through the three tools."""
    for path in sorted(REGRESSIONS.glob("*")):
        if path.is_file() and path.stat().st_size:
            data = path.read_bytes()
            check_stream(data)
            agreed(["stream", "--lenient"], data)


def test_encode_takes_the_checksum_case_from_ascii_letters() -> None:
    """decode's "checksum" says how encode writes the checksum: lower case when it holds a letter
    from a to z (whatever else it holds), else upper case; the three tools agree."""
    body = "GPGLL,5550.6135,N,03732.2515,E,075140.00,A,A"
    total = 0
    for byte in body.encode():
        total ^= byte
    decoded = json.loads(agreed(["decode"], f"${body}*{total:02X}\n".encode()))
    cases = {"6a": "lower", "\u00df": "upper", "\u00dfx": "lower", "AB": "upper", "": "empty"}
    data = "".join(json.dumps(dict(decoded, checksum=text), separators=(",", ":")) + "\n" for text in cases)
    lines = agreed(["encode"], data.encode()).decode().splitlines()
    assert len(lines) == len(cases), lines
    for line, want in zip(lines, cases.values()):
        digits = line[line.rfind("*") + 1:]
        assert {"empty": digits == "", "upper": digits == f"{total:02X}", "lower": digits == f"{total:02x}"}[want], \
            (want, line)
