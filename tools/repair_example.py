#!/usr/bin/env python3
"""Suggest single-edit repairs of a damaged manual example whose XOR checksum fails.

Usage: tools/repair_example.py '$GPGGA,...*40' [...]

Prints the computed checksum and every sentence one edit away (insert, delete or replace one
character of the body, or swap two neighbours) whose checksum matches the printed one. It only
proposes; the spec author picks the repair the field layout supports and writes the reason.
"""
import signal
import sys
from functools import reduce

ALPHABET = "0123456789ABCDEFGHIJKLMNOPQRSTUVWXYZ,.-+"


def checksum(body: str) -> int:
    return reduce(lambda acc, ch: acc ^ ord(ch), body, 0)


def candidates(body: str):
    for i in range(len(body) + 1):
        for ch in ALPHABET:
            yield f"insert {ch!r} at {i}", body[:i] + ch + body[i:]
    for i in range(len(body)):
        yield f"delete {body[i]!r} at {i}", body[:i] + body[i + 1:]
        for ch in ALPHABET:
            if ch != body[i]:
                yield f"replace {body[i]!r} at {i} by {ch!r}", body[:i] + ch + body[i + 1:]
    for i in range(len(body) - 1):
        if body[i] != body[i + 1]:
            yield f"swap at {i}", body[:i] + body[i + 1] + body[i] + body[i + 2:]


def main() -> None:
    signal.signal(signal.SIGPIPE, signal.SIG_DFL)
    for raw in sys.argv[1:]:
        # A line that lost its '$' still sums from its first character.
        start, rest = (raw[0], raw[1:]) if raw[:1] in ("$", "!") else ("", raw)
        body, star, printed = rest.partition("*")
        if not star or not printed:
            print(f"{raw}\n  no checksum to verify (computed {checksum(body):02X})")
            continue
        try:
            want = int(printed[:2], 16)
        except ValueError:
            print(f"{raw}\n  the checksum {printed!r} is not hex (computed {checksum(body):02X})")
            continue
        print(f"{raw}\n  computed {checksum(body):02X}, printed {printed[:2]}")
        if checksum(body) == want:
            print("  intact")
            continue
        delta = checksum(body) ^ want
        print(f"  body is off by XOR 0x{delta:02X}; or the printed checksum is wrong: {start}{body}*{checksum(body):02X}")
        seen = set()
        for what, fixed in candidates(body):
            if checksum(fixed) == want and fixed not in seen:
                seen.add(fixed)
                if "insert ','" in what or "delete" in what or "swap" in what or len(seen) < 40:
                    print(f"  {what}: {start}{fixed}*{printed[:2]}")


if __name__ == "__main__":
    main()
