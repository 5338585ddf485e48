"""The stream framer's SkyTraq, SiRF and CASIC frames (spec/binary/{skytraq,sirf,casic}): gpsd's
logs of those receivers split byte-exact at every chunk size, every frame's checksum and end bytes
right by a checker written here from the protocols' facts, as many frames as that checker finds
scanning the log; A0 starts both SiRF (A0 A2) and SkyTraq (A0 A1); damage over a log of all three
(fuzz/faults.py) loses no intact frame and takes no damaged one."""

from __future__ import annotations

import binascii

from pathlib import Path

import pytest

from fuzz import faults
from tests.ubx.pyubx2_oracle import ubx  # noqa: F401 (puts generated/python on the path)

from nmeaspec import stream  # isort: skip
from tests.ubx.test_stream_frames import assert_damage_keeps_frames, split, without_line_endings  # isort: skip

ROOT = Path(__file__).resolve().parents[2]
DATA = ROOT / "tests" / "data"
LOGS = sorted(p for name in ("skytraq", "sirf", "casic") for p in (DATA / name).glob("*.log"))
GGA = b"$GPGGA,1*00\r\n"


def _xor(data: bytes) -> int:
    x = 0
    for byte in data:
        x ^= byte
    return x


def checked(data: bytes) -> str | None:
    """The protocol of a whole frame whose checksum and end bytes are right (the facts of each
    protocol.yaml, written out), else None."""
    if data[:2] == b"\xa0\xa1" and len(data) == 7 + (data[2] << 8 | data[3]):
        if data[-3] == _xor(data[4:-3]) and data[-2:] == b"\r\n":
            return "skytraq"
    if data[:2] == b"\xa0\xa2" and len(data) == 8 + (data[2] << 8 | data[3]):  # its top bit reserved, 0
        if (data[-4] << 8 | data[-3]) == sum(data[4:-4]) & 0x7FFF and data[-2:] == b"\xb0\xb3":
            return "sirf"
    if data[:2] == b"\xba\xce" and len(data) == 10 + (data[2] | data[3] << 8):
        body = data[2:-4] + bytes(-(len(data) - 6) % 4)
        words = sum(int.from_bytes(body[i:i + 4], "little") for i in range(0, len(body), 4))
        if words & 0xFFFFFFFF == int.from_bytes(data[-4:], "little"):
            return "casic"
    if data[:3] == b"\xaa\x44\xb5" and len(data) == 28 + int.from_bytes(data[6:8], "little"):
        crc = 0  # CRC-32: reflected 0xEDB88320, initial value 0, no final inversion, little endian
        for byte in data[:-4]:
            crc ^= byte
            for _ in range(8):
                crc = crc >> 1 ^ (0xEDB88320 if crc & 1 else 0)
        if crc == int.from_bytes(data[-4:], "little"):
            return "unicore"
    if data[:2] == b"$@" and len(data) == int.from_bytes(data[6:8], "little") >= 8:  # the length counts it all
        if binascii.crc_hqx(data[4:], 0) == int.from_bytes(data[2:4], "little"):  # CRC-CCITT, before the id
            return "sbf"
    return None


def scan(data: bytes) -> list[bytes]:
    """Every right frame of the three protocols in `data`, found at each A0 or BA byte (frames of
    gpsd's logs never overlap)."""
    found, at = [], 0
    while at < len(data) - 1:
        for size in (7 + (data[at + 2] << 8 | data[at + 3]) if at + 4 <= len(data) else 0,
                     8 + (data[at + 2] << 8 | data[at + 3]) if at + 4 <= len(data) else 0,
                     10 + (data[at + 2] | data[at + 3] << 8) if at + 4 <= len(data) else 0):
            if size and checked(data[at:at + size]):
                found.append(data[at:at + size])
                at += size
                break
        else:
            at += 1
    return found


def scan_sbf(data: bytes) -> list[bytes]:
    """Every right SBF block in `data`, found at each "$@" (blocks never overlap)."""
    found, at = [], data.find(b"$@")
    while 0 <= at < len(data) - 7:
        size = int.from_bytes(data[at + 6:at + 8], "little")
        if checked(data[at:at + size]) == "sbf":
            found.append(data[at:at + size])
            at += size
        else:
            at += 1
        at = data.find(b"$@", at)
    return found


@pytest.mark.parametrize("log", LOGS, ids=lambda p: p.name)
def test_a_log_splits_byte_exact(log: Path) -> None:
    data = log.read_bytes()
    items = split(data)
    assert split(data, 777) == items
    if len(data) < 60_000:
        assert split(data, 1) == items
    frames = [item for item in items if isinstance(item, stream.BinaryFrame)]
    assert [f.data for f in frames] == scan(data) and frames
    assert all(checked(f.data) == f.protocol == log.parent.name for f in frames)
    joined = b"".join(item if isinstance(item, bytes) else item.data for item in items if not isinstance(item, int))
    assert joined == without_line_endings(data, items)
    # what is not a frame is gpsd's comment lines, NMEA sentences and a frame cut at a log's end
    assert all(item.reason == "cut" for item in items if isinstance(item, stream.BadFrame))


def test_identity() -> None:
    frames = {f.protocol: f for log in LOGS for f in split(log.read_bytes()) if isinstance(f, stream.BinaryFrame)}
    sky, sirf, casic = frames["skytraq"], frames["sirf"], frames["casic"]
    assert sky.identity == {"id": sky.data[4]} and sirf.identity == {"id": sirf.data[4]}
    assert casic.identity == {"class": casic.data[4], "id": casic.data[5]}
    assert sky.to_json().startswith(f'{{"ok":true,"protocol":"skytraq","id":{sky.data[4]},"length":{len(sky.data)},')


# Made-up frames of each protocol (their checksums computed by hand from the facts).
SKY = bytes.fromhex("a0a1 0002 0201 03 0d0a")   # message 0x02, body 01: XOR 03
SIRF = bytes.fromhex("a0a2 0002 8401 0085 b0b3")  # MID 132, body 01: sum 0x85
CASIC = bytes.fromhex("bace 0000 0601 00000601")  # class 0x06, id 0x01, no payload: 0x01060000 little endian


def kinds(items: list[stream.Item]) -> list[object]:
    return [item if isinstance(item, (bytes, int)) else
            (item.protocol if isinstance(item, stream.BinaryFrame) else f"{item.protocol} {item.reason}")
            for item in items]


@pytest.mark.parametrize(("data", "expected"), [
    (SKY + GGA + SIRF + GGA + CASIC, ["skytraq", GGA[:-2], "sirf", GGA[:-2], "casic"]),
    # A0 starts both: the second byte names the protocol, the checksum decides
    (b"\xa0\xa3" + GGA, [b"\xa0\xa3", GGA[:-2]]),
    (SKY[:-3] + b"\x04\r\n" + GGA, ["skytraq bad_checksum", SKY[2:-3] + b"\x04", GGA[:-2]]),
    # the end bytes count with the checksum
    (SIRF[:-1] + b"\xb4" + GGA, ["sirf bad_checksum", SIRF[2:-1] + b"\xb4", GGA[:-2]]),
    (CASIC[:-1] + b"\x02" + GGA, ["casic bad_checksum", CASIC[2:-1] + b"\x02", GGA[:-2]]),
    # a frame cut by a sentence, and by the end
    (SIRF[:5] + GGA + SKY, ["sirf bad_checksum", SIRF[2:5], GGA[:-2], "skytraq"]),
    (GGA + CASIC[:7], [GGA[:-2], "casic cut", CASIC[2:7]]),
    # SiRF's reserved top bit of the length, set: read with the length, it makes the frame too long
    (b"\xa0\xa2\x80" + SIRF[3:] + GGA, ["sirf too_long", b"\x80" + SIRF[3:], GGA[:-2]]),
    # a break after a sync
    (b"\xa0\xa1\x00\x00" + GGA, ["skytraq nul_header", b"\x00\x00", GGA[:-2]]),
])
def test_damage_is_reported_and_nothing_intact_is_lost(data: bytes, expected: list[object]) -> None:
    assert kinds(split(data)) == expected
    assert kinds(split(data, 1)) == expected


def test_bad_checksum_message() -> None:
    (bad, *_) = split(SKY[:-3] + b"\x04\r\n")
    assert isinstance(bad, stream.BadFrame) and bad.message == "checksum 04 0D 0A, computed 03 0D 0A"


def mixed() -> bytes:
    """A stream of the three protocols' logs and NMEA: the CASIC log's first 60,000 bytes, the
    SkyTraq and SiRF logs."""
    logs = {p.name: p.read_bytes() for p in LOGS}
    return (logs["quectel-l76k-dual.log"][:60_000] + logs["skytraq-A8.log"] + logs["ublox-sirf1.log"]
            + logs["sirfstarv.log"][:20_000])


@pytest.mark.parametrize("kind", faults.KINDS)
def test_damage_loses_no_intact_frame_and_takes_no_damaged_one(kind: str) -> None:
    """fuzz/faults.py's damage over the mixed stream (the other stream of `interleave`: gpsd's
    SkyTraq binary log): every frame a copy run holds whole is found, every frame found is one of
    the clean streams'."""
    logs = [mixed(), (DATA / "skytraq" / "skytraq-bin.log").read_bytes() * 4]
    assert_damage_keeps_frames(kind, logs)
