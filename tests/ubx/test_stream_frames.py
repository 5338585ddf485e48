"""The stream framer's binary frames (runtime/python/stream.py, Framer(binary=True)): gpsd's logs
that interleave NMEA with UBX and RTCM 3 split byte-exact, every frame's checksum right and as many
frames as ubx.split_frames finds; damaged, cut and overlong frames reported, and nothing intact
after them lost; the RTCM 3 framing spec the framer implements."""

from __future__ import annotations

from pathlib import Path

import pytest
import yaml

from fuzz import faults
from tests.ubx.pyubx2_oracle import ubx

from nmeaspec import stream  # isort: skip (pyubx2_oracle puts generated/python on the path)

ROOT = Path(__file__).resolve().parents[2]
LOGS = sorted((ROOT / "tests" / "data" / "ubx").glob("*.log")) + sorted((ROOT / "tests" / "data" / "rtcm3").glob("*.log"))
ACK = bytes.fromhex("b562 0501 0200 0600 0e37")  # UBX ACK-ACK of CFG-PRT
RTCM = bytes.fromhex("d3 0002 3ee0 6d7f60")  # an RTCM 3 frame of two payload bytes: message number 0x3EE
GGA = b"$GPGGA,1*00\r\n"


def split(data: bytes, chunk: int = 4096) -> list[stream.Item]:
    framer = stream.Framer(binary=True)
    items = [item for i in range(0, len(data), chunk) for item in framer.feed(data[i:i + chunk])]
    return items + framer.end()


def joined(items: list[stream.Item]) -> bytes:
    return b"".join(item if isinstance(item, bytes) else item.data for item in items if not isinstance(item, int))


def without_line_endings(data: bytes, items: list[stream.Item]) -> bytes:
    """The stream less the CR and LF bytes outside its frames: what the items must concatenate to."""
    out, pos = bytearray(), 0
    for frame in (item for item in items if isinstance(item, stream.BinaryFrame)):
        at = data.index(frame.data, pos)
        out += data[pos:at].replace(b"\r", b"").replace(b"\n", b"") + frame.data
        pos = at + len(frame.data)
    return bytes(out + data[pos:].replace(b"\r", b"").replace(b"\n", b""))


def test_crc24q() -> None:
    assert stream.crc24q(RTCM[:-3]) == RTCM[-3:]
    assert stream.crc24q(b"") == b"\x00\x00\x00"


@pytest.mark.parametrize("log", LOGS, ids=lambda p: p.name)
def test_a_mixed_log_splits_byte_exact(log: Path) -> None:
    data = log.read_bytes()
    items = split(data, 777)
    assert items == split(data, 1) == split(data)
    frames = [item for item in items if isinstance(item, stream.BinaryFrame)]
    assert frames, "every log holds frames"
    assert joined(items) == without_line_endings(data, items)
    ubx_frames = [f for f in frames if f.protocol == "ubx"]
    assert [f.data for f in ubx_frames] == [frame.encode() for _, frame in ubx.split_frames(data)]
    for frame in frames:
        if frame.protocol == "rtcm3":
            assert stream.crc24q(frame.data[:-3]) == frame.data[-3:]
            assert 1 <= frame.identity["message_number"] <= 4095
        else:
            assert ubx.decode_frame(frame.data).payload == frame.data[6:-2]
    # what is not a frame is gpsd's comment lines, NMEA sentences and the cut frame at a log's end
    assert all(item.reason == "cut" for item in items if isinstance(item, stream.BadFrame))


def test_a_frame_item_names_its_message() -> None:
    (frame,) = split(ACK)
    assert isinstance(frame, stream.BinaryFrame)
    assert frame.identity == {"class": 5, "id": 1, "name": "ACK-ACK"}
    assert frame.message().to_dict()["message"] == "ack_ack"
    (rtcm,) = split(RTCM)
    assert isinstance(rtcm, stream.BinaryFrame) and rtcm.identity == {"message_number": 0x3EE}


def kinds(items: list[stream.Item]) -> list[object]:
    return [item if isinstance(item, (bytes, int)) else
            (item.protocol if isinstance(item, stream.BinaryFrame) else f"{item.protocol} {item.reason}")
            for item in items]


@pytest.mark.parametrize(("data", "expected"), [
    # binary bytes between sentences, and a frame that cuts a sentence short
    (GGA + ACK + GGA + RTCM + b"$GPGGA" + ACK + b",1*00\r\n", [GGA[:-2], "ubx", GGA[:-2], "rtcm3", b"$GPGGA", "ubx", b",1*00"]),
    # a '$' and a line ending inside a payload belong to the frame
    (ubx.Frame(1, 2, b"$GP\r\n").encode() + GGA, ["ubx", GGA[:-2]]),
    # a bad checksum: the sync bytes are reported, what follows them is read again
    (ACK[:-1] + b"\x00" + GGA, ["ubx bad_checksum", ACK[2:-1] + b"\x00", GGA[:-2]]),
    # a frame cut short by a sentence: the sentence is not lost
    (ACK[:7] + GGA + ACK, ["ubx bad_checksum", ACK[2:7], GGA[:-2], "ubx"]),
    (RTCM[:4] + GGA + GGA, ["rtcm3 bad_checksum", RTCM[1:4], GGA[:-2], GGA[:-2]]),
    # cut by the end of the stream, and a lone sync byte at the end
    (GGA + ACK[:7], [GGA[:-2], "ubx cut", ACK[2:7]]),
    (GGA + b"\xb5", [GGA[:-2], b"\xb5"]),
    # sync bytes that start no frame are bytes of the line
    (b"\xb5\x00\xd3\xff" + GGA, [b"\xb5\x00\xd3\xff", GGA[:-2]]),
    # a frame inside another's bad frame is found
    (b"\xb5\x62\x01\x02\x03\x00" + ACK + GGA, ["ubx bad_checksum", b"\x01\x02\x03\x00", "ubx", GGA[:-2]]),
    # a break's NUL bytes after a sync (a checksum of NULs matches them)
    (b"\xb5\x62" + bytes(6) + GGA, ["ubx nul_header", bytes(4 + 2), GGA[:-2]]),
    # no frame inside a TAG block
    (b"\\s:\xb5\x62*00\\" + GGA, [b"\\s:\xb5\x62*00\\" + GGA[:-2]]),
])
def test_damage_is_reported_and_nothing_intact_is_lost(data: bytes, expected: list[object]) -> None:
    assert kinds(split(data)) == expected
    assert kinds(split(data, 1)) == expected


def test_a_frame_longer_than_the_buffer_is_reported_and_read_as_bytes() -> None:
    big = ubx.Frame(1, 2, b"abc\n" * (stream.MAX_FRAME // 4)).encode()
    items = split(big + GGA)
    assert kinds(items[:1]) == ["ubx too_long"] and items[-1] == GGA[:-2]
    assert isinstance(items[0], stream.BadFrame) and items[0].message == (
        f"frame is {len(big)} bytes, the limit is {stream.MAX_FRAME}")
    assert joined(items) == without_line_endings(big + GGA, items)
    assert not any(isinstance(item, stream.BinaryFrame) for item in items)


def test_without_binary_the_framer_takes_lines_only() -> None:
    assert stream.Framer().feed(ACK + GGA) == [ACK, GGA[:-2]]


def test_the_rtcm3_framing_spec() -> None:
    spec = yaml.safe_load((ROOT / "spec" / "binary" / "rtcm3" / "protocol.yaml").read_text(encoding="utf-8"))
    frame = spec["frame"]
    assert bytes(frame["sync"]) == RTCM[:1]
    assert [(f["type"], f.get("value")) for f in frame["header"]] == [("b6", 0), ("b10", None)]
    assert frame["checksum"] == {"algorithm": "crc24q", "over": ["sync", "payload"]}
    assert spec["identity"] == [{"id": "message_number", "type": "b12"}]


def frame_spans(data: bytes) -> list[tuple[int, int]]:
    """Where the frames the framer finds in `data` lie."""
    spans, pos = [], 0
    for frame in (item for item in split(data) if isinstance(item, stream.BinaryFrame)):
        pos = data.index(frame.data, pos)
        spans.append((pos, pos + len(frame.data)))
        pos += len(frame.data)
    return spans


def assert_damage_keeps_frames(kind: str, logs: list[bytes]) -> None:
    """fuzz/faults.py's damage of `kind` over two clean streams: every frame a copy run holds whole
    is found, every frame found is one of the clean streams'."""
    spans = [frame_spans(log) for log in logs]
    damaged = faults.damage(kind, 1, logs[0], logs[1])
    found = [item.data for item in split(damaged.data) if isinstance(item, stream.BinaryFrame)]
    clean = {logs[s][a:b] for s in range(2) for a, b in spans[s]}
    assert all(frame in clean for frame in found), "a damaged frame was taken"
    whole = [logs[run.stream][a:b] for run in damaged.runs if run.stream >= 0
             for a, b in spans[run.stream] if run.start <= a and b <= run.end]
    assert whole and len(found) >= len(whole)
    left = list(found)
    for frame in whole:  # each intact frame among those found (a doubled run holds one twice)
        left.remove(frame)


@pytest.mark.parametrize("kind", faults.KINDS)
def test_damage_loses_no_intact_frame_and_takes_no_damaged_one(kind: str) -> None:
    """fuzz/faults.py's damage over a log of UBX and NMEA (the other stream of `interleave`: one of
    RTCM 3 and NMEA): every frame a copy run holds whole is found, every frame found is one of the
    clean logs'."""
    logs = [(ROOT / "tests" / "data" / "ubx" / "ublox-neo-m8l.log").read_bytes(),
            (ROOT / "tests" / "data" / "rtcm3" / "ublox-f9p-rtcm.log").read_bytes()]
    assert_damage_keeps_frames(kind, logs)


# Septentrio SBF: pysbf2's logs (tests/data/sbf), their blocks as many as pysbf2 reads in each
# (pysbf2 1.0.7's SBFReader over the same files; the damaged block of pygpsdata_bad and the cut one
# of pygpsdata_x5_pvttruncated it refuses too).
SBF_DIR = ROOT / "tests" / "data" / "sbf"
SBF_BLOCKS = {"pygpsdata_bad.sbf": 6, "pygpsdata_mixed.log": 2, "pygpsdata_x5_constellations.sbf": 21,
              "pygpsdata_x5_measurements.sbf": 3, "pygpsdata_x5_pvtextra.sbf": 4, "pygpsdata_x5_pvttruncated.sbf": 3,
              "pygpsdata_x5_time.sbf": 2, "pygpsdata_x5status.sbf": 39, "sbfdata.sbf": 232}
SBF = bytes.fromhex("2440 bd13 1a17 1800 702fcb1c3f091905170e0b0012070000")  # ReceiverTime


def test_sbf_logs_split_into_pysbf2s_blocks() -> None:
    from tests.ubx.test_binary_protocols import checked

    assert sorted(p.name for p in SBF_DIR.iterdir() if p.suffix in (".sbf", ".log")) == sorted(SBF_BLOCKS)
    for name, count in SBF_BLOCKS.items():
        data = (SBF_DIR / name).read_bytes()
        items = split(data, 97)
        assert items == split(data)
        frames = [item for item in items if isinstance(item, stream.BinaryFrame) and item.protocol == "sbf"]
        assert len(frames) == count, name
        assert joined(items) == without_line_endings(data, items)
        for frame in frames:  # the CRC (binascii's CRC-CCITT), the length and the id as the block holds them
            ident = int.from_bytes(frame.data[4:6], "little")
            assert checked(frame.data) == "sbf" and len(frame.data) % 4 == 0
            assert frame.identity == {"number": ident & 0x1FFF, "revision": ident >> 13}
    bad = [item for item in split((SBF_DIR / "pygpsdata_bad.sbf").read_bytes()) if isinstance(item, stream.BadFrame)]
    assert [(b.reason, b.message) for b in bad] == [("too_short", "frame is 0 bytes, the least is 8")]
    cut = [item for item in split((SBF_DIR / "pygpsdata_x5_pvttruncated.sbf").read_bytes())
           if isinstance(item, stream.BadFrame)]
    assert [b.reason for b in cut] == ["cut"]


def test_a_mixed_nmea_and_sbf_stream_at_every_chunk_size() -> None:
    """pysbf2's log of NMEA, RTCM 3 and SBF, with sentences and damaged blocks around its own."""
    data = ((SBF_DIR / "pygpsdata_mixed.log").read_bytes() + b"$GPGGA,2" + SBF + GGA + SBF[:3] + b"\x00" + SBF[4:]
            + GGA + SBF[:12] + GGA)
    items = split(data)
    assert kinds(items)[-9:] == [b"$GPGGA,2", "sbf", GGA[:-2], "sbf bad_checksum", SBF[2:3] + b"\x00" + SBF[4:],
                                 GGA[:-2], "sbf bad_checksum", SBF[2:12], GGA[:-2]]
    assert [i.protocol for i in items if isinstance(i, stream.BinaryFrame)] == ["rtcm3", "rtcm3", "sbf", "sbf", "sbf"]
    for chunk in range(1, len(data) + 1, 3):
        assert split(data, chunk) == items, chunk


@pytest.mark.parametrize(("data", "expected"), [
    # "$@" starts a block, any other '$' a sentence
    (b"$GP" + SBF + b"$@" + GGA, [b"$GP", "sbf", "sbf too_long", GGA[:-2]]),
    # a length under the header's 8 bytes; a length of more than the framer holds
    (b"$@\x01\x02\x03\x04\x04\x00" + GGA, ["sbf too_short", b"\x01\x02\x03\x04\x04\x00", GGA[:-2]]),
    (b"$@\x01\x02\x03\x04\x04\x09" + GGA, ["sbf too_long", b"\x01\x02\x03\x04\x04\x09", GGA[:-2]]),
    # a break's NUL bytes after "$@"; no block in a TAG block
    (b"$@" + bytes(6) + GGA, ["sbf nul_header", bytes(6), GGA[:-2]]),
    (b"\\s:$@*00\\" + GGA, [b"\\s:$@*00\\" + GGA[:-2]]),
])
def test_sbf_damage_is_reported_and_nothing_intact_is_lost(data: bytes, expected: list[object]) -> None:
    assert kinds(split(data)) == expected
    assert kinds(split(data, 1)) == expected


@pytest.mark.parametrize("kind", faults.KINDS)
def test_damage_to_sbf_and_nmea_loses_no_intact_block(kind: str) -> None:
    """fuzz/faults.py's damage over SBF blocks between NMEA sentences (pysbf2's sbfdata.sbf, a block
    then a sentence of gpsd's UBX log in turn; the other stream: pysbf2's status blocks)."""
    from tests.ubx.test_binary_protocols import scan_sbf

    nmea = [line.rstrip(b"\r") + b"\r\n" for line in (ROOT / "tests" / "data" / "ubx" / "ublox-neo-m8l.log")
            .read_bytes().split(b"\n") if line.startswith(b"$G") and line.rstrip(b"\r").isascii()]
    blocks = scan_sbf((SBF_DIR / "sbfdata.sbf").read_bytes())[:80]
    mixed = b"".join(block + nmea[i % len(nmea)] for i, block in enumerate(blocks))
    assert_damage_keeps_frames(kind, [mixed, (SBF_DIR / "pygpsdata_x5status.sbf").read_bytes()])


# Unicore binary: the frames of pyunigps's examples (tests/data/unicore), each once.
UNI_LOG = ROOT / "tests" / "data" / "unicore" / "pyunigps_frames.log"


def test_unicore_frames_split_from_nmea_at_every_chunk_size() -> None:
    """The three frames alone, then between sentences with a damaged one, one cut short (read on
    into the sentences after it, its CRC then wrong) and NovAtel's AA 44 12 and AA 44 then other
    bytes (the third sync byte checked as it comes: no frame, their bytes the line's, the sentence
    after them handed on as soon as it ends): every frame whole, its CRC-32 and id as the frame
    holds them, nothing else taken for a frame."""
    from tests.ubx.test_binary_protocols import checked

    log = UNI_LOG.read_bytes()
    frames = [item for item in split(log) if isinstance(item, stream.BinaryFrame)]
    assert [f.data for f in frames] == [log[:33], log[33:81], log[81:]]
    assert [f.identity for f in frames] == [{"message_id": 65512}, {"message_id": 65514}, {"message_id": 17}]
    assert all(checked(f.data) == "unicore" for f in frames)
    uni = log[:33]
    novatel = b"\xaa\x44\x12\x1c\x2a\x00\x00\x20" + bytes(range(0x30, 0x44))
    data = (GGA + log[33:] + b"$GPGGA,2" + uni + GGA + uni[:-1] + b"\x00" + GGA + novatel + GGA + b"\xaa\x44\xaa\x44"
            + uni + GGA + uni[:20] + GGA + b"\xaa\x44")
    items = split(data)
    assert kinds(items) == [GGA[:-2], "unicore", "unicore", b"$GPGGA,2", "unicore", GGA[:-2], "unicore bad_checksum",
                            uni[3:-1] + b"\x00", GGA[:-2], novatel, GGA[:-2], b"\xaa\x44\xaa\x44", "unicore", GGA[:-2],
                            "unicore bad_checksum", uni[3:20], GGA[:-2], b"\xaa\x44"]
    assert joined(items) == without_line_endings(data, items)
    for chunk in range(1, len(data) + 1, 7):
        assert split(data, chunk) == items, chunk
    # a sentence after NovAtel's sync is handed on the moment its line ends, not after 24 bytes
    framer = stream.Framer(binary=True)
    assert framer.feed(GGA + novatel[:3]) == [GGA[:-2]]
    assert framer.feed(GGA) == [novatel[:3], GGA[:-2]]


@pytest.mark.parametrize("kind", faults.KINDS)
def test_damage_to_unicore_and_nmea_loses_no_intact_frame(kind: str) -> None:
    """fuzz/faults.py's damage over Unicore frames (pyunigps's, tests/data/unicore) between NMEA
    sentences and NovAtel-style AA 44 12 headers (the other stream: the same frames in reverse
    order, with AA 44 before each)."""
    from tests.ubx.pyunigps_oracle import frames as unicore_frames

    built = unicore_frames(UNI_LOG.read_bytes() + (UNI_LOG.parent / "pyunigps_built.log").read_bytes())
    novatel = b"\xaa\x44\x12\x1c\x2a\x00\x00\x20" + bytes(range(0x30, 0x44))
    one = b"".join(frame + GGA + (novatel if i % 3 == 0 else b"") for i, frame in enumerate(built))
    other = b"".join(b"\xaa\x44" + frame + b"$GPGGA,2*00\r\n" for frame in reversed(built))
    assert len(frame_spans(one)) == len(frame_spans(other)) == len(built) == 11
    assert_damage_keeps_frames(kind, [one, other])
