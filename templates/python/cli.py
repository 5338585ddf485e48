"""The `nmea-py` tool: `decode` NMEA lines to JSON, `encode` that JSON back to sentences.

Same behaviour, byte for byte, as nmea-c and nmea-rs; see docs/json.md.
"""

from __future__ import annotations

import json
import sys

from . import decode_json, encode_json

USAGE = "usage: nmea-py decode [--values] | encode   (reads stdin, writes stdout)\n"


def lines(data: bytes) -> list[str]:
    """Split on LF, drop one CR before it; a last line without LF counts, an empty tail does not."""
    parts = data.split(b"\n")
    if parts and parts[-1] == b"":
        parts.pop()
    return [(p[:-1] if p.endswith(b"\r") else p).decode("latin-1") for p in parts]


def main(argv: list[str] | None = None) -> int:
    args = sys.argv[1:] if argv is None else argv
    if args == ["decode"] or args == ["decode", "--values"]:
        values = len(args) == 2
        out = [decode_json(line, values) for line in lines(sys.stdin.buffer.read())]
    elif args == ["encode"]:
        out = []
        for line in lines(sys.stdin.buffer.read()):
            try:
                if json.loads(line).get("ok") is False:
                    continue
            except (ValueError, AttributeError, RecursionError):
                pass
            out.append(encode_json(line))
    else:
        sys.stderr.write(USAGE)
        return 2
    sys.stdout.buffer.write("".join(text + "\n" for text in out).encode("latin-1"))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
