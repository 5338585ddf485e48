"""Builds the benchmark corpus: every line of the real receiver logs that is a checksummed `$` sentence
of one of the common types, repeated in order to the wanted number of lines, CR LF endings.

Deterministic: the logs are read in sorted path order and the lines kept in file order.

    python3 bench/corpus.py [--lines N] [--source DIR] [--out FILE] [--ais | --ubx | --mixed]

--ais: the AIS corpus instead (build_ais: gpsd's single-sentence AIS lines of tests/data/ais), for the
drivers' ours-ais and peers; --ubx: the UBX corpus (build_ubx: the frames of gpsd's u-blox logs in
tests/data/ubx, a frame as hex digits a line), for bench/python/driver.py's ours-ubx and pyubx2;
--mixed: the mixed corpus (build_mixed: gpsd's logs of NMEA with UBX and RTCM 3, repeated whole to
at least --lines bytes), for the C driver's stream splitting (framer).
"""

from __future__ import annotations

import argparse
import json
import re
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
TYPES = ("GGA", "RMC", "GSV", "GSA", "VTG", "GLL", "ZDA", "GST")
DEFAULT_SOURCE = ROOT.parent / "shared" / "corpus" / "real"
DEFAULT_OUT = ROOT / "build" / "bench" / "corpus.nmea"

# `$`, a talker + type address, the fields, `*` and two hex digits; printable ASCII only.
SENTENCE = re.compile(rb"\$([A-Z0-9]{2}([A-Z]{3}))(,[\x20-\x29\x2b-\x7e]*)?\*([0-9A-Fa-f]{2})")


def checksum_ok(line: bytes) -> bool:
    body, _, given = line[1:].rpartition(b"*")
    total = 0
    for byte in body:
        total ^= byte
    return total == int(given, 16)


def source_lines(source: Path) -> list[bytes]:
    """The eligible lines of every log under `source`, in sorted path order."""
    kept = []
    for path in sorted(p for p in source.rglob("*") if p.is_file() and p.suffix == ".nmea"):
        for raw in path.read_bytes().split(b"\n"):
            line = raw.rstrip(b"\r")
            match = SENTENCE.fullmatch(line)
            if match and match.group(2).decode() in TYPES and checksum_ok(line):
                kept.append(line)
    return kept


def build(lines: int, source: Path = DEFAULT_SOURCE, out: Path = DEFAULT_OUT) -> dict:
    """Writes the corpus to `out` (unchanged files are not rewritten) and returns its summary."""
    pool = source_lines(source)
    if not pool:
        sys.exit(f"no eligible line under {source}")
    data = b"".join(pool[i % len(pool)] + b"\r\n" for i in range(lines))
    out.parent.mkdir(parents=True, exist_ok=True)
    if not out.exists() or out.read_bytes() != data:
        out.write_bytes(data)
    by_type: dict[str, int] = {}
    for i in range(lines):
        kind = pool[i % len(pool)][3:6].decode()
        by_type[kind] = by_type.get(kind, 0) + 1
    return {"lines": lines, "bytes": len(data), "distinct_lines": len(set(pool)), "source_lines": len(pool),
            "by_type": dict(sorted(by_type.items()))}


AIS_SOURCE = ROOT / "tests" / "data" / "ais"
AIS_OUT = ROOT / "build" / "bench" / "corpus-ais.nmea"
# A single-sentence `!AIVDM`/`!AIVDO` line: count and number 1, a payload, fill bits, checksum.
AIS_SENTENCE = re.compile(rb"!AIVD[MO],1,1,[0-9]?,[AB12]?,[0-W`-w]+,[0-5]\*[0-9A-F]{2}")


def build_ais(lines: int, source: Path = AIS_SOURCE, out: Path = AIS_OUT) -> dict:
    """The AIS corpus: gpsd's real AIS sentences (tests/data/ais) of one sentence each, with their
    checksums intact, repeated in file order to `lines` lines, CR LF endings."""
    pool = [line.rstrip(b"\r") for path in sorted(source.glob("*.chk")) + [source / "sample.aivdm"]
            for line in path.read_bytes().split(b"\n")
            if AIS_SENTENCE.fullmatch(line.rstrip(b"\r")) and checksum_ok(line.rstrip(b"\r"))]
    data = b"".join(pool[i % len(pool)] + b"\r\n" for i in range(lines))
    out.parent.mkdir(parents=True, exist_ok=True)
    if not out.exists() or out.read_bytes() != data:
        out.write_bytes(data)
    return {"lines": lines, "bytes": len(data), "distinct_lines": len(set(pool)), "source_lines": len(pool)}


UBX_SOURCE = ROOT / "tests" / "data" / "ubx"
UBX_OUT = ROOT / "build" / "bench" / "corpus-ubx.hex"


def ubx_frames(data: bytes) -> list[bytes]:
    """The UBX frames of a log, in order: sync B5 62, class, id, length, payload and a Fletcher-8
    checksum that holds (a sync pair whose frame does not check is passed over byte by byte)."""
    frames, at = [], data.find(b"\xb5\x62")
    while 0 <= at <= len(data) - 8:
        end = at + 8 + int.from_bytes(data[at + 4:at + 6], "little")
        a = b = 0
        for byte in data[at + 2:end - 2]:
            a = (a + byte) & 0xFF
            b = (b + a) & 0xFF
        if end <= len(data) and data[end - 2:end] == bytes((a, b)) and data[at + 2:at + 6] != bytes(4):
            frames.append(data[at:end])
            at = data.find(b"\xb5\x62", end)
        else:
            at = data.find(b"\xb5\x62", at + 1)
    return frames


def build_ubx(frames: int, source: Path = UBX_SOURCE, out: Path = UBX_OUT) -> dict:
    """The UBX corpus: the frames of gpsd's u-blox logs (tests/data/ubx), in file order, repeated
    to `frames` frames, each as one line of hex digits (the drivers turn them back into bytes
    before they time anything)."""
    pool = [frame for path in sorted(source.glob("*.log")) for frame in ubx_frames(path.read_bytes())]
    data = b"".join(pool[i % len(pool)].hex().encode() + b"\n" for i in range(frames))
    out.parent.mkdir(parents=True, exist_ok=True)
    if not out.exists() or out.read_bytes() != data:
        out.write_bytes(data)
    return {"frames": frames, "bytes": sum(len(pool[i % len(pool)]) for i in range(frames)),
            "distinct_frames": len(set(pool)), "source_frames": len(pool)}


MIXED_SOURCES = (ROOT / "tests" / "data" / "ubx", ROOT / "tests" / "data" / "rtcm3")
MIXED_OUT = ROOT / "build" / "bench" / "corpus-mixed.log"


def build_mixed(size: int, sources: tuple[Path, ...] = MIXED_SOURCES, out: Path = MIXED_OUT) -> dict:
    """The mixed corpus: gpsd's receiver logs that interleave NMEA sentences with UBX and RTCM 3
    frames (tests/data/ubx, tests/data/rtcm3: their bytes as the receivers sent them, the logs'
    `#` comment lines included), one after another in sorted path order, repeated whole until the
    corpus holds at least `size` bytes (the C driver's `framer` splits it, and the NMEA corpus, into
    items)."""
    pool = b"".join(path.read_bytes() for source in sources for path in sorted(source.glob("*.log")))
    data = pool * max(1, -(-size // len(pool)))
    out.parent.mkdir(parents=True, exist_ok=True)
    if not out.exists() or out.read_bytes() != data:
        out.write_bytes(data)
    return {"bytes": len(data), "source_bytes": len(pool), "repeats": len(data) // len(pool),
            "ubx_frames": len(ubx_frames(data))}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--lines", type=int, default=1_000_000)
    parser.add_argument("--source", type=Path)
    parser.add_argument("--out", type=Path)
    parser.add_argument("--ais", action="store_true", help="the AIS corpus (build_ais) from --source or tests/data/ais")
    parser.add_argument("--ubx", action="store_true", help="the UBX corpus (build_ubx) from --source or tests/data/ubx")
    parser.add_argument("--mixed", action="store_true",
                        help="the mixed corpus (build_mixed: --lines is its least size in bytes) from the UBX and RTCM 3 logs")
    args = parser.parse_args()
    if args.mixed:
        print(json.dumps(build_mixed(args.lines, (args.source,) if args.source else MIXED_SOURCES,
                                     args.out or MIXED_OUT)))
    elif args.ubx:
        print(json.dumps(build_ubx(args.lines, args.source or UBX_SOURCE, args.out or UBX_OUT)))
    elif args.ais:
        print(json.dumps(build_ais(args.lines, args.source or AIS_SOURCE, args.out or AIS_OUT)))
    else:
        print(json.dumps(build(args.lines, args.source or DEFAULT_SOURCE, args.out or DEFAULT_OUT)))


if __name__ == "__main__":
    main()
