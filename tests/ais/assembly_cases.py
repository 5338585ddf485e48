"""The shared cases of AIS messages assembled across sentences (tests/data/ais/assembly_cases.jsonl),
as Python's MessageAssembler (nmeaspec.assembly, the reference) assembles them; the C and Rust
assemblers are tested against the file, test_assembly.py checks it is current, and
`.venv/bin/python -m tests.ais.assembly_cases` writes it again.

A case: `lines` fed in order to an assembler of `slots` and `lifetime`, then finished; `events` in
the order they come, each with `after` (the index of the line whose feed gave it, null: finish),
`lines` (the indices of its sentences, in fragment order), `payload` and `fill_bits` of a joined
message (the fragments' payloads in number order, the last one's fill bits), and `error`, the kind,
for a message given up (`incomplete_message`, no payload) or one whose payload does not decode."""

from __future__ import annotations

import json
from typing import Any

from .gpsd_oracle import DATA  # first: it puts generated/python on the path

from nmeaspec import Tagged, parse  # noqa: E402
from nmeaspec.assembly import MessageAssembler  # noqa: E402

PATH = DATA / "assembly_cases.jsonl"

# Type 5 (static and voyage data) in two fragments, sequential id 9, channel B (gpsd's ais-nmea.log).
FIRST = "!AIVDM,2,1,9,B,55R3Vn82=ILTQ3KKS>1<D60Dq@E918U<F222221J1`?164vc03S1CCAD,0*2A"
SECOND = "!AIVDM,2,2,9,B,`88888888888880,2*76"
SINGLE = "!AIVDM,1,1,,B,13aDp<PP000IwSlN?Wm@0?wN2<1T,0*29"
GGA = "$GPGGA,123519,4807.038,N,01131.000,E,1,08,0.9,545.4,M,46.9,M,,*47"


def checksummed(body: str) -> str:
    checksum = 0
    for char in body[1:]:
        checksum ^= ord(char)
    return f"{body}*{checksum:02X}"


def with_id(line: str, sequence: str, channel: str = "B", address: str | None = None) -> str:
    """The sentence with another sequential id and channel (and address), its checksum made right."""
    fields = line.split("*")[0].split(",")
    fields[3], fields[4] = sequence, channel
    if address is not None:
        fields[0] = address
    return checksummed(",".join(fields))


def three(part: int, payload: str, fill_bits: int = 0, sequence: str = "5") -> str:
    """A fragment of a message in three (the type 5 above split again)."""
    return checksummed(f"!AIVDM,3,{part},{sequence},A,{payload},{fill_bits}")


def tagged(group: str, line: str, source: str = "r3669961") -> str:
    text = f"g:{group},s:{source}"
    checksum = 0
    for char in text:
        checksum ^= ord(char)
    return f"\\{text}*{checksum:02X}\\{line}"


HEAD, TAIL = FIRST.split(",")[5], SECOND.split(",")[5]
CASES: list[dict[str, Any]] = [
    {"where": "a message of one sentence comes at once; other sentences give nothing",
     "lines": [GGA, SINGLE]},
    {"where": "interleaved with another message, out of order",
     "lines": [with_id(SECOND, "3", "A"), FIRST, GGA, SINGLE, with_id(FIRST, "3", "A"), SECOND]},
    {"where": "three fragments in every order",
     "lines": [three(3, TAIL, 2), three(1, HEAD[:30]), three(2, HEAD[30:]),
               three(2, HEAD[30:]), three(3, TAIL, 2), three(1, HEAD[:30])]},
    {"where": "a lost fragment, given up after the lifetime; nothing else lost", "lifetime": 3,
     "lines": [FIRST, SINGLE, SINGLE, SINGLE]},
    {"where": "a fragment with no first, given up when the stream ends", "lines": [SECOND, GGA]},
    {"where": "a repeated fragment starts a new message", "lines": [FIRST, FIRST, SECOND]},
    {"where": "another count under the same key starts a new message",
     "lines": [with_id(three(1, HEAD[:30]), "9"), FIRST, SECOND]},
    {"where": "the same id on the other channel or from another talker is another message",
     "lines": [FIRST, with_id(FIRST, "9", "A"), with_id(FIRST, "9", address="!BSVDM"), SECOND,
               with_id(SECOND, "9", address="!BSVDM"), with_id(SECOND, "9", "A")]},
    {"where": "slots full: the oldest message under way is given up", "slots": 2,
     "lines": [with_id(FIRST, "0"), with_id(FIRST, "1"), with_id(FIRST, "2"), with_id(SECOND, "1"),
               with_id(SECOND, "2"), with_id(SECOND, "0")]},
    {"where": "TAG groups tie fragments whatever their ids",
     "lines": [tagged("1-2-1001", FIRST), tagged("1-2-1002", with_id(FIRST, "9")),
               tagged("2-2-1002", with_id(SECOND, "4")), tagged("2-2-1001", with_id(SECOND, "7"))]},
    {"where": "a TAG group's id is a number: leading zeros name the same group",
     "lines": [tagged("1-2-0073874", FIRST), tagged("2-2-73874", SECOND)]},
    {"where": "a TAG group from another source is another message",
     "lines": [tagged("1-2-7", FIRST), tagged("2-2-7", SECOND, "r1"), tagged("2-2-7", SECOND)]},
    {"where": "a payload past the capacity (558 characters): the message is given up, the fragment alone",
     "lines": [three(1, "5" * 300), three(2, "5" * 300), checksummed("!AIVDM,2,1,6,A," + "5" * 600 + ",0"), SINGLE]},
    {"where": "a key past its 40 bytes (a long TAG source): the fragment is given up alone",
     "lines": [tagged("1-2-7", FIRST, "s" * 40), SINGLE]},
    {"where": "a joined payload that does not decode",
     "lines": [checksummed("!AIVDM,2,1,1,A,w,0"), checksummed("!AIVDM,2,2,1,A,w,0")]},
]


def events(case: dict[str, Any]) -> list[dict[str, Any]]:
    """What Python's assembler gives of the case's lines, in the form of the file."""
    assembler = MessageAssembler(slots=case.get("slots", 16), lifetime=case.get("lifetime", 100))
    parsed = [parse(line) for line in case["lines"]]
    index = {id(p): i for i, p in enumerate(parsed)}
    out = []
    for after, done in [(i, d) for i, p in enumerate(parsed) for d in assembler.feed(p)] + \
            [(None, d) for d in assembler.finish()]:
        event: dict[str, Any] = {"after": after, "lines": [index[id(s)] for s in done.sentences]}
        if done.error is None or done.error.kind != "incomplete_message":
            fragments = [(s.sentence if isinstance(s, Tagged) else s).fragment for s in done.sentences]
            event["payload"] = "".join(f.payload for f in fragments)
            event["fill_bits"] = fragments[-1].fill_bits
        if done.error is not None:
            event["error"] = done.error.kind
        out.append(event)
    return out


def render() -> str:
    return "".join(json.dumps({"where": c["where"], "slots": c.get("slots", 16), "lifetime": c.get("lifetime", 100),
                               "lines": c["lines"], "events": events(c)}, separators=(",", ":")) + "\n"
                   for c in CASES)


if __name__ == "__main__":
    PATH.write_text(render(), encoding="utf-8")
