"""pyrtcm, the RTCM 3 library of the pyubx2 family, as an oracle of the stream framer's RTCM 3
frames: over every log here that holds RTCM 3 (gpsd's, tests/data/rtcm3; one interleaves NMEA,
UBX and RTCM 3 on one port), pyrtcm's RTCMReader (which checks each frame's CRC-24Q) and
Framer(binary=True) find the same frames, byte for byte, with the same message numbers."""

from __future__ import annotations

import io
from pathlib import Path

import pytest
from pyrtcm import RTCMReader

from tests.ubx.pyubx2_oracle import ubx  # noqa: F401 (puts generated/python on the path)

from nmeaspec import stream  # isort: skip

ROOT = Path(__file__).resolve().parents[2]
LOGS = [log for log in sorted((ROOT / "tests" / "data").glob("*/*.log")) if b"\xd3" in log.read_bytes()]


@pytest.mark.parametrize("log", LOGS, ids=lambda p: f"{p.parent.name}/{p.name}")
def test_the_frames_pyrtcm_finds(log: Path) -> None:
    data = log.read_bytes()
    theirs = [(raw, int(parsed.identity)) for raw, parsed in RTCMReader(io.BytesIO(data), quitonerror=0)]
    framer = stream.Framer(binary=True)
    ours = [(item.data, item.identity["message_number"]) for item in framer.feed(data) + framer.end()
            if isinstance(item, stream.BinaryFrame) and item.protocol == "rtcm3"]
    assert ours == theirs


def test_the_logs_hold_frames() -> None:
    frames = sum(1 for log in LOGS for _ in RTCMReader(io.BytesIO(log.read_bytes()), quitonerror=0))
    assert len(LOGS) >= 3 and frames >= 200
