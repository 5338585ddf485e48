"""AIS messages joined across sentences (nmeaspec.assembly): on gpsd's samples every message
comes out as a joiner of fragments in order under their key gives it (whole or incomplete, its
payload and fill bits, its sentences byte for byte; channels A and B interleave there), and the
hard cases (interleaved, out of order, a fragment lost or repeated, a sequential id reused, slots
full, TAG groups) give what the module promises."""

from __future__ import annotations

import json
import os
import subprocess
import sys

from .gpsd_oracle import DATA  # first: it puts generated/python on the path
from . import assembly_cases  # noqa: E402

from nmeaspec import NmeaError, Tagged, parse  # noqa: E402
from nmeaspec.assembly import Assembled, MessageAssembler  # noqa: E402

# Type 5 (static and voyage data) in two fragments, sequential id 9, channel B (gpsd's ais-nmea.log).
FIRST = "!AIVDM,2,1,9,B,55R3Vn82=ILTQ3KKS>1<D60Dq@E918U<F222221J1`?164vc03S1CCAD,0*2A"
SECOND = "!AIVDM,2,2,9,B,`88888888888880,2*76"
SINGLE = "!AIVDM,1,1,,B,13aDp<PP000IwSlN?Wm@0?wN2<1T,0*29"
GGA = "$GPGGA,123519,4807.038,N,01131.000,E,1,08,0.9,545.4,M,46.9,M,,*47"


def with_id(line: str, sequence: str, channel: str = "B") -> str:
    """The sentence with another sequential id and channel, its checksum made right."""
    fields = line.split("*")[0].split(",")
    fields[3], fields[4] = sequence, channel
    body = ",".join(fields)
    checksum = 0
    for char in body[1:]:
        checksum ^= ord(char)
    return f"{body}*{checksum:02X}"


def feed(assembler: MessageAssembler, lines: list[str]) -> list[Assembled]:
    out: list[Assembled] = []
    for line in lines:
        out += assembler.feed(parse(line))
    return out


def decodes(line: str) -> bool:
    try:
        parse(line)
    except NmeaError:
        return False
    return True


def texts(done: Assembled) -> list[str]:
    return [s.to_sentence() for s in done.sentences]


def in_order(lines: list[str]) -> tuple[list[tuple[str, ...]], list[tuple[str, ...]]]:
    """The messages of lines whose fragments come in order under their key (address, channel and
    sequential id): the sentences of each whole message, in the order they complete, and of each
    message a fragment is missing from."""
    whole: list[tuple[str, ...]] = []
    broken: list[tuple[str, ...]] = []
    current: dict[tuple[str, ...], list[str]] = {}
    for line in lines:
        address, count, number, sequence, channel = line.split(",")[:5]
        key = (address, sequence, channel)
        if int(number) == 1 and current.get(key):
            broken.append(tuple(current.pop(key)))
        current.setdefault(key, []).append(line)
        if number == count:
            message = current.pop(key)
            (whole if len(message) == int(count) else broken).append(tuple(message))
    return whole, broken + [tuple(left) for left in current.values()]


def test_every_message_of_gpsds_samples_joins_as_gpsd_joined_it() -> None:
    for path in sorted(DATA.glob("*.log.chk")) + [DATA / "sample.aivdm"]:
        # the sentences our parser reads (sample.aivdm has a few with text after the checksum)
        lines = [line for line in path.read_text(encoding="utf-8").splitlines() if line.startswith("!AIVD")
                 and decodes(line)]
        whole, broken = in_order(lines)
        assembler = MessageAssembler()
        done = feed(assembler, lines) + assembler.finish()
        assert [tuple(texts(d)) for d in done if d.error is None or d.error.kind != "incomplete_message"] == whole
        assert sorted(tuple(texts(d)) for d in done if d.error and d.error.kind == "incomplete_message") == \
            sorted(broken), path.name
        for message in (d for d in done if d.message is not None):
            fields = [t.split("*")[0].split(",") for t in texts(message)]
            assert message.message.encode() == ("".join(f[5] for f in fields), int(fields[-1][6]))
        assert sorted(t for d in done for t in texts(d)) == sorted(lines), path.name  # no sentence lost


def test_a_message_of_one_sentence_comes_at_once() -> None:
    (done,) = MessageAssembler().feed(parse(SINGLE))
    assert done.error is None and done.message is not None and texts(done) == [SINGLE]
    assert MessageAssembler().feed(parse(GGA)) == []


def test_interleaved_and_out_of_order() -> None:
    other_first, other_second = with_id(FIRST, "3", "A"), with_id(SECOND, "3", "A")
    assembler = MessageAssembler()
    done = feed(assembler, [other_second, FIRST, GGA, SINGLE, other_first, SECOND])
    assert [texts(d) for d in done] == [[SINGLE], [other_first, other_second], [FIRST, SECOND]]
    assert all(d.error is None for d in done)
    assert done[1].message == done[2].message and done[1].message.encode()[1] == 2
    assert assembler.finish() == []


def test_a_lost_fragment_is_reported_and_nothing_else_is_lost() -> None:
    assembler = MessageAssembler(lifetime=3)
    done = feed(assembler, [FIRST, SINGLE, SINGLE])
    assert [texts(d) for d in done] == [[SINGLE], [SINGLE]]
    (gone, single) = feed(assembler, [SINGLE])
    assert texts(gone) == [FIRST] and gone.message is None
    assert isinstance(gone.error, NmeaError) and gone.error.kind == "incomplete_message"
    assert str(gone.error) == "incomplete_message: AIS: fragment 2 of 2 never came"
    assert texts(single) == [SINGLE]
    assembler = MessageAssembler()
    assert feed(assembler, [SECOND]) == []
    (left,) = assembler.finish()
    assert texts(left) == [SECOND] and "fragment 1 of 2 never came" in str(left.error)


def test_a_repeated_fragment_or_reused_id_starts_a_new_message() -> None:
    assembler = MessageAssembler()
    done = feed(assembler, [FIRST, FIRST, SECOND])
    assert [(texts(d), d.error.kind if d.error else None) for d in done] == [
        ([FIRST], "incomplete_message"), ([FIRST, SECOND], None)]


def test_slots_bound_the_messages_under_way() -> None:
    assembler = MessageAssembler(slots=2)
    firsts = [with_id(FIRST, str(i)) for i in range(3)]
    done = feed(assembler, firsts)
    assert [(texts(d), d.error.kind) for d in done] == [([firsts[0]], "incomplete_message")]
    done = feed(assembler, [with_id(SECOND, "1"), with_id(SECOND, "2")])
    assert [texts(d) for d in done] == [[firsts[1], with_id(SECOND, "1")], [firsts[2], with_id(SECOND, "2")]]


def test_a_tag_group_ties_fragments_whatever_their_ids() -> None:
    def tagged(group: str, line: str) -> str:
        text = f"g:{group},s:r3669961"
        checksum = 0
        for char in text:
            checksum ^= ord(char)
        return f"\\{text}*{checksum:02X}\\{line}"

    lines = [tagged("1-2-1001", FIRST), tagged("1-2-1002", with_id(FIRST, "9")),
             tagged("2-2-1002", with_id(SECOND, "4")), tagged("2-2-1001", with_id(SECOND, "7"))]
    done = MessageAssembler().feed
    out = [d for line in lines for d in done(parse(line))]
    assert [[s.to_sentence() for s in d.sentences] for d in out] == [[lines[1], lines[2]], [lines[0], lines[3]]]
    assert all(isinstance(s, Tagged) for d in out for s in d.sentences)
    assert all(d.message is not None for d in out)


def test_nmea_show_gives_each_message_with_the_sentence_that_completes_it() -> None:
    log = "\r\n".join([FIRST, GGA, SINGLE, SECOND, with_id(FIRST, "1")]) + "\r\n"
    show = subprocess.run([sys.executable, "-m", "nmeaspec.apps.nmea_cli", "show", "--json", "-"],
                          input=log.encode(), capture_output=True, check=True,
                          env={**os.environ, "PYTHONPATH": str(DATA.parents[2] / "generated" / "python")})
    records = [json.loads(line) for line in show.stdout.decode().splitlines()]
    assert [(r["line"], r.get("ais", {}).get("message"), r.get("ais", {}).get("mmsi")) for r in records] == [
        (1, None, None), (2, None, None), (3, "position_report", 244660274),
        (4, "static_voyage_data", 371255000), (5, None, None)]
    assert records[3]["ais"]["shipname"].rstrip("@ ") == "SEA ENTERPRISE"
    assert show.stderr.decode().endswith(
        "AIS messages:\n  position_report     1\n  static_voyage_data  1\n"
        "AIS messages that did not decode:\n  incomplete_message  1\n")
    table = subprocess.run([sys.executable, "-m", "nmeaspec.apps.nmea_cli", "show", "--fields",
                            "line,ais.message,ais.mmsi,ais.lat", "-q", "-"], input=log.encode(),
                           capture_output=True, check=True,
                           env={**os.environ, "PYTHONPATH": str(DATA.parents[2] / "generated" / "python")})
    assert table.stdout.decode().splitlines()[4].split() == ["4", "static_voyage_data", "371255000"]


def test_the_shared_cases_are_what_this_assembler_gives() -> None:
    """tests/data/ais/assembly_cases.jsonl, which the C and Rust assemblers are tested against, is
    current (`.venv/bin/python -m tests.ais.assembly_cases` writes it again)."""
    assert assembly_cases.PATH.read_text(encoding="utf-8") == assembly_cases.render()
