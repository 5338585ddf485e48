"""Differential check: the same inputs through nmea-c, nmea-rs and nmea-py, which must print the
same bytes for decode, decode --values, decode --lenient, stream and encode.

Usage: python fuzz/differential.py DIR_OR_FILE...   (every file is one input; build/bin has the tools)
Each input becomes one line of a decode run and a chunk of a stream run. Exits non-zero on any
difference and writes the input to fuzz/regressions/ so that it is replayed from then on.
"""

from __future__ import annotations

import hashlib
import os
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
TOOLS = [Path(os.environ.get("NMEA_TOOLS", ROOT / "build" / "bin")) / name for name in ("nmea-c", "nmea-rs", "nmea-py")]
REGRESSIONS = ROOT / "fuzz" / "regressions"
RUNS = [["decode"], ["decode", "--values"], ["decode", "--lenient"], ["decode", "--require-checksum"], ["stream"]]


def run(tool: Path, args: list[str], data: bytes) -> bytes:
    done = subprocess.run([str(tool), *args], input=data, capture_output=True, timeout=600)
    if done.returncode != 0:
        raise SystemExit(f"{tool.name} {' '.join(args)} exited {done.returncode}: {done.stderr[-500:]!r}")
    return done.stdout


def inputs(paths: list[str]) -> list[bytes]:
    out = []
    for name in paths:
        path = Path(name)
        if not path.exists():  # a fuzzer that has not run yet
            continue
        files = sorted(p for p in path.rglob("*") if p.is_file()) if path.is_dir() else [path]
        for file in files:
            try:
                out.append(file.read_bytes())
            except FileNotFoundError:  # a fuzzer still running replaced it by a smaller input
                continue
    return out


def first_difference(outputs: list[bytes]) -> int | None:
    lines = [o.split(b"\n") for o in outputs]
    for i in range(max(len(x) for x in lines)):
        row = {x[i] if i < len(x) else None for x in lines}
        if len(row) > 1:
            return i
    return None


def main() -> int:
    items = [i for i in inputs(sys.argv[1:]) if b"\n" not in i]
    data = b"".join(i + b"\n" for i in items)
    failed = False
    for args in RUNS:
        outputs = [run(tool, args, data) for tool in TOOLS]
        at = first_difference(outputs)
        if at is not None:
            failed = True
            culprit = items[at] if args[0] == "decode" and at < len(items) else data
            REGRESSIONS.mkdir(exist_ok=True)
            (REGRESSIONS / hashlib.sha1(culprit).hexdigest()[:16]).write_bytes(culprit)
            print(f"{' '.join(args)}: the tools differ on output line {at + 1} (input saved in fuzz/regressions)")
            for tool, out in zip(TOOLS, outputs):
                lines = out.split(b"\n")
                print(f"  {tool.name}: {lines[at][:300] if at < len(lines) else b'(none)'!r}")
    decoded = [run(tool, ["decode"], data) for tool in TOOLS][0]
    ok_lines = b"".join(line + b"\n" for line in decoded.split(b"\n") if line.startswith(b'{"ok":true'))
    encoded = [run(tool, ["encode"], ok_lines) for tool in TOOLS]
    if len(set(encoded)) > 1:
        failed = True
        print("encode: the tools differ")
    print(f"differential: {len(items)} inputs, {len(RUNS) + 1} verbs, three tools: {'DIFFERENT' if failed else 'identical'}")
    return 1 if failed else 0


if __name__ == "__main__":
    raise SystemExit(main())
