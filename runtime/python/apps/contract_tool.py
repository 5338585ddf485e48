"""The `nmea-py` tool: `decode` NMEA lines to JSON, `encode` that JSON back to sentences,
`stream` a byte stream that may hold garbage, cut lines or sentences run together, `fixes`: the
fix of each epoch of NMEA lines (Fix.to_dict, one JSON object per line).

Same behaviour, byte for byte, as nmea-c and nmea-rs; see docs/json.md.
"""

from __future__ import annotations

import json
import sys
from collections.abc import Iterator

from .. import __version__, decode_json, encode_json
from ..fixes import fixes
from ..runtime import json_too_deep
from ..stream import json_lines

USAGE = (
    "usage: nmea-py decode|stream [--values] [--lenient] [--require-checksum] [--strict]"
    " | encode | fixes | --version\n"
    "       (reads stdin, writes stdout)\n"
)
FLAGS = ("--values", "--lenient", "--require-checksum", "--strict")


def lines(data: bytes) -> list[str]:
    """Split on LF, drop one CR before it; a last line without LF counts, an empty tail does not."""
    parts = data.split(b"\n")
    if parts and parts[-1] == b"":
        parts.pop()
    return [(p[:-1] if p.endswith(b"\r") else p).decode("latin-1") for p in parts]


def main(argv: list[str] | None = None) -> int:
    args = sys.argv[1:] if argv is None else argv
    verb, flags = (args[0], args[1:]) if args else ("", [])
    if (
        verb in ("decode", "stream")
        and all(f in FLAGS for f in flags)
        and len(set(flags)) == len(flags)
    ):
        values, lenient, required, strict = (f in flags for f in FLAGS)
        out: Iterator[str]
        if verb == "decode":
            out = (
                decode_json(line, values, lenient, required, strict)
                for line in lines(sys.stdin.buffer.read())
            )
        else:
            options = {"lenient": lenient, "require_checksum": required, "strict": strict}
            out = json_lines(sys.stdin.buffer, values, **options)
        write = sys.stdout.buffer.write
        for text in out:
            write(text.encode("latin-1") + b"\n")
        return 0
    if verb == "--version" and not flags:
        print(f"nmea-py {__version__}")
        return 0
    if verb == "encode" and not flags:
        for line in lines(sys.stdin.buffer.read()):
            try:
                if not json_too_deep(line) and json.loads(line).get("ok") is False:
                    continue
            except (ValueError, AttributeError):
                pass
            sys.stdout.buffer.write(encode_json(line).encode("latin-1") + b"\n")
        return 0
    if verb == "fixes" and not flags:
        for fix in fixes(lines(sys.stdin.buffer.read())):
            sys.stdout.write(json.dumps(fix.to_dict(), separators=(",", ":")) + "\n")
        return 0
    sys.stderr.write(USAGE)
    return 2


if __name__ == "__main__":
    raise SystemExit(main())
