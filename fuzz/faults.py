r"""A serial line's damage, applied to a real log: the damage model of the fault-injection test
(tests/agreement/test_faults.py, `make test` and `make fuzz-faults`).

Each kind of damage is applied on its own, from a seeded random generator (the same log, kind,
seed and rate give the same bytes on every machine and Python version), at a rate a noisy line
could show:

| kind | what happens | default rate |
| --- | --- | --- |
| `drop` | bytes are lost (an overrun: one byte, sometimes a burst of up to 16) | 1 per 1000 bytes |
| `dup` | bytes arrive twice (one, sometimes up to 8) | 1 per 1000 bytes |
| `flip` | one bit of a byte is inverted (line noise) | 1 per 1000 bytes |
| `cut` | a line ends early: the rest of it up to its line ending, checksum included, is lost | 2 in 100 lines |
| `garbage` | bytes are inserted: a run of NULs (a break) or random bytes, 1 to 16 | 1 per 1000 bytes |
| `interleave` | two talkers share the line: the log and a second stream alternate in chunks of 1 to 320 bytes | - |
| `cr_lost` | a CR is lost (with CR LF endings the LF still ends the line) | 5 in 100 CRs |
| `lf_lost` | a LF is lost (with LF endings the lines run together) | 5 in 100 LFs |
| `eol_lost` | a whole line ending is lost: the lines run together | 5 in 100 line endings |
| `mix` | all of the single-stream kinds above at once, each at a fifth of its rate | - |

`rate` multiplies every default rate (and, for `interleave`, divides the mean chunk length).

The damaged stream is kept as a list of runs: bytes copied unchanged from a clean stream (its
index and the span) and bytes the damage made (flipped or inserted). That is what tells which
sentences of the clean log are still in the damaged stream, and where, without asking a reader:
see `intact`.

Framing (the tools' `stream` verb, generated/docs/json.md): CR and LF end a line, empty lines are
skipped, a `$` or `!` starts a new item, but for a `\` at the start of a line, which opens a TAG
block: up to its closing `\` every byte but CR and LF belongs to it, and a `$`, `!` or `\` right
after that continues the line. Outside a TAG block, `$@` starts an SBF block (spec/binary/sbf):
damage makes one now and then (a bit of `$A`, `$P` flipped), and, its CRC failing, the framer hands
on its two sync bytes as an item of their own and reads the bytes after them again (the clean
logs hold no binary frame). `items` is that rule as a regular expression.
"""

from __future__ import annotations

import bisect
import random
import re
from dataclasses import dataclass, field
from typing import Callable, Iterator

KINDS = ("drop", "dup", "flip", "cut", "garbage", "interleave", "cr_lost", "lf_lost", "eol_lost", "mix")

BYTE_RATE = 1 / 1000  # drop, dup, flip, garbage: events per byte
LINE_RATE = 2 / 100  # cut: lines cut short per line
ENDING_RATE = 5 / 100  # cr_lost, lf_lost, eol_lost: per CR, LF or line ending
CHUNK_MEAN = 160  # interleave: mean chunk length in bytes
MIX_SHARE = 1 / 5  # mix: each kind at this share of its rate

# One framed item: a line that starts with TAG blocks (closed ones, then an open one up to the
# line ending or what follows the last: a '$' or '!' and the rest up to the next CR, LF, '$' or
# '!'); the sync bytes of an SBF block that is none ("$@"); a '$' or '!' and what follows up to the
# next CR, LF, '$' or '!'; or a run of other bytes after a line ending (or at the start). Empty
# lines make no item.
_ITEM = re.compile(rb"(?=\\)(?:\\[^\r\n\\]*\\)*(?:\\[^\r\n\\]*|[$!]?[^\r\n$!]*)|\$@|[$!][^\r\n$!]*|[^\r\n$!]+")
_LINE = re.compile(rb"[^\r\n]+")
_ENDING = re.compile(rb"\r\n|\n|\r")


def items(data: bytes) -> list[tuple[int, int]]:
    """The spans (start, end) of the items the stream framer hands on, in order."""
    return [m.span() for m in _ITEM.finditer(data)]


@dataclass(frozen=True)
class Event:
    """One act of damage at offset `at` of clean stream `stream`.
    op: "drop" (`size` bytes lost), "dup" (`size` bytes sent twice), "flip" (the byte XOR `mask`),
    "insert" (`made` inserted before the byte at `at`), "switch" (interleave: the other stream
    takes over the line here)."""

    at: int
    op: str
    size: int = 0
    mask: int = 0
    made: bytes = b""
    stream: int = 0

    @property
    def extent(self) -> int:
        """Clean bytes the event covers: no other event may start inside them."""
        return {"drop": self.size, "dup": self.size, "flip": 1}.get(self.op, 0)

    def describe(self) -> str:
        where = f"stream {self.stream} byte {self.at}"
        detail = {"drop": f"{self.size} byte(s) lost", "dup": f"{self.size} byte(s) sent twice",
                  "flip": f"XOR 0x{self.mask:02x}", "insert": f"inserted {self.made!r}",
                  "switch": "the other stream takes over"}[self.op]
        return f"{where}: {self.op}, {detail}"


@dataclass(frozen=True)
class Run:
    """Bytes at offset `at` of the damaged stream: a copy of clean stream `stream`'s bytes
    [start, end), or (stream -1) `end - start` bytes the damage made."""

    at: int
    stream: int
    start: int
    end: int


@dataclass
class Damaged:
    kind: str
    seed: int
    data: bytes
    runs: list[Run]
    events: list[Event]
    _starts: list[int] = field(default_factory=list, repr=False)

    def origin(self, offset: int) -> tuple[int, int] | None:
        """(stream, clean offset) of the damaged stream's byte at `offset`; None for a made byte."""
        if not self._starts:
            self._starts = [run.at for run in self.runs]
        run = self.runs[bisect.bisect_right(self._starts, offset) - 1]
        return None if run.stream < 0 else (run.stream, run.start + offset - run.at)

    def events_near(self, offset: int, end: int, margin: int = 16) -> list[Event]:
        """The events that may have shaped the damaged bytes [offset, end)."""
        spots = [self.origin(i) for i in range(max(0, offset - 1), min(len(self.data), end + 1))]
        near = [spot for spot in spots if spot is not None]
        return [e for e in self.events
                if any(e.stream == s and pos - margin - e.extent <= e.at <= pos + margin for s, pos in near)]


class _Builder:
    def __init__(self) -> None:
        self.parts: list[bytes] = []
        self.runs: list[Run] = []
        self.length = 0

    def copy(self, stream: int, data: bytes, start: int, end: int) -> None:
        if end > start:
            self._add(Run(self.length, stream, start, end), data[start:end])

    def make(self, made: bytes) -> None:
        if made:
            self._add(Run(self.length, -1, 0, len(made)), made)

    def _add(self, run: Run, data: bytes) -> None:
        self.runs.append(run)
        self.parts.append(data)
        self.length += len(data)


def apply(kind: str, seed: int, data: bytes, events: list[Event]) -> Damaged:
    """Clean stream 0 with `events` applied (an event that starts inside the bytes of the one
    before it is left out)."""
    events = _disjoint(events)
    out = _Builder()
    done = 0
    for e in events:
        if e.op == "dup":
            out.copy(0, data, done, e.at + e.size)
            done = e.at
        else:
            out.copy(0, data, done, e.at)
            done = e.at + e.extent
            out.make(e.made if e.op == "insert" else bytes([data[e.at] ^ e.mask]) if e.op == "flip" else b"")
    out.copy(0, data, done, len(data))
    return Damaged(kind, seed, b"".join(out.parts), out.runs, events)


def _positions(rng: random.Random, length: int, rate: float) -> Iterator[int]:
    """Offsets in [0, length) with exponential gaps of mean 1 / rate."""
    at = -1
    while True:
        at += 1 + int(rng.expovariate(rate))
        if at >= length:
            return
        yield at


def _burst(rng: random.Random, most: int) -> int:
    return 1 if rng.random() < 0.75 else rng.randint(2, most)


def _drop(data: bytes, rng: random.Random, rate: float) -> Iterator[Event]:
    for at in _positions(rng, len(data), BYTE_RATE * rate):
        yield Event(at, "drop", size=min(_burst(rng, 16), len(data) - at))


def _dup(data: bytes, rng: random.Random, rate: float) -> Iterator[Event]:
    for at in _positions(rng, len(data), BYTE_RATE * rate):
        yield Event(at, "dup", size=min(_burst(rng, 8), len(data) - at))


def _flip(data: bytes, rng: random.Random, rate: float) -> Iterator[Event]:
    for at in _positions(rng, len(data), BYTE_RATE * rate):
        yield Event(at, "flip", mask=1 << rng.randrange(8))


def _garbage(data: bytes, rng: random.Random, rate: float) -> Iterator[Event]:
    for at in _positions(rng, len(data), BYTE_RATE * rate):
        size = rng.randint(1, 16)
        made = bytes(size) if rng.random() < 0.5 else bytes(rng.randrange(256) for _ in range(size))
        yield Event(at, "insert", made=made)


def _cut(data: bytes, rng: random.Random, rate: float) -> Iterator[Event]:
    for line in _LINE.finditer(data):
        if rng.random() >= LINE_RATE * rate:
            continue
        text = line.group()
        star = text.find(b"*")
        keep = star if star > 0 else len(text)  # a line without a checksum loses at least a byte
        if keep > 1:
            cut = rng.randrange(1, keep)
            yield Event(line.start() + cut, "drop", size=len(text) - cut)


def _lost(pattern: bytes) -> Callable[[bytes, random.Random, float], Iterator[Event]]:
    found = re.compile(pattern)

    def lose(data: bytes, rng: random.Random, rate: float) -> Iterator[Event]:
        for ending in found.finditer(data):
            if rng.random() < ENDING_RATE * rate:
                yield Event(ending.start(), "drop", size=ending.end() - ending.start())

    return lose


_SINGLE = {"drop": _drop, "dup": _dup, "flip": _flip, "cut": _cut, "garbage": _garbage,
           "cr_lost": _lost(rb"\r"), "lf_lost": _lost(rb"\n"), "eol_lost": _lost(_ENDING.pattern)}


def _disjoint(events: list[Event]) -> list[Event]:
    """Sorted by offset; an event that starts inside the bytes of the one before is left out."""
    kept: list[Event] = []
    end = 0
    for e in sorted(events, key=lambda e: e.at):
        if e.at >= end:
            kept.append(e)
            end = e.at + e.extent
    return kept


def damage(kind: str, seed: int, data: bytes, partner: bytes = b"", rate: float = 1.0) -> Damaged:
    """`data` (clean stream 0) damaged by `kind`; `interleave` mixes in `partner` (clean stream 1)."""
    rng = random.Random(f"{kind}:{seed}")
    if kind == "interleave":
        return _interleave(seed, data, partner, rng, rate)
    if kind == "mix":
        events = [e for name in _SINGLE for e in _SINGLE[name](data, rng, rate * MIX_SHARE)]
    else:
        events = list(_SINGLE[kind](data, rng, rate))
    return apply(kind, seed, data, events)


def _interleave(seed: int, a: bytes, b: bytes, rng: random.Random, rate: float) -> Damaged:
    out = _Builder()
    streams = (a, b)
    done = [0, 0]
    events = []
    turn = 0
    most = max(1, round(2 * CHUNK_MEAN / rate))
    while done[0] < len(a) or done[1] < len(b):
        size = rng.randint(1, most)
        start = done[turn]
        if start < len(streams[turn]):
            events.append(Event(start, "switch", stream=turn))
            done[turn] = min(start + size, len(streams[turn]))
            out.copy(turn, streams[turn], start, done[turn])
        turn ^= 1
    return Damaged("interleave", seed, b"".join(out.parts), out.runs, events)


def intact(damaged: Damaged, clean_items: list[list[tuple[int, int]]]) -> dict[int, tuple[int, int, int]]:
    """The clean items the damaged stream still holds whole, framed so that a reader finds them:
    {offset in the damaged stream: (stream, item index, length)}.

    A clean item [start, end) of stream s is intact at offset x when
    - one copy run of s holds all of [start, end) (no byte of it lost, changed or doubled, nothing
      inserted inside it), placing it at x; and
    - the framer frames exactly [x, x + length) as an item (`items`).
    A run of doubled bytes can hold a short item twice: both places count."""
    data = damaged.data
    framed = set(items(data))
    found: dict[int, tuple[int, int, int]] = {}
    starts = [[start for start, _ in spans] for spans in clean_items]
    for run in damaged.runs:
        if run.stream < 0:
            continue
        spans = clean_items[run.stream]
        i = bisect.bisect_left(starts[run.stream], run.start)
        while i < len(spans) and spans[i][1] <= run.end:
            start, end = spans[i]
            x, y = run.at + start - run.start, run.at + end - run.start
            if (x, y) in framed:
                found[x] = (run.stream, i, end - start)
            i += 1
    return found
