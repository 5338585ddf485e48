"""Builds the benchmark corpus: every line of the real receiver logs that is a checksummed `$` sentence
of one of the common types, repeated in order to the wanted number of lines, CR LF endings.

Deterministic: the logs are read in sorted path order and the lines kept in file order.

    python3 bench/corpus.py [--lines N] [--source DIR] [--out FILE]
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


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--lines", type=int, default=1_000_000)
    parser.add_argument("--source", type=Path, default=DEFAULT_SOURCE)
    parser.add_argument("--out", type=Path, default=DEFAULT_OUT)
    args = parser.parse_args()
    print(json.dumps(build(args.lines, args.source, args.out)))


if __name__ == "__main__":
    main()
