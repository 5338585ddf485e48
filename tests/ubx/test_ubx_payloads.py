"""UBX payloads read and written by the AIS payload model's field classes and walkers (ais.py)
through the little-endian ByteReader and ByteWriter (ubx.py): a NAV-TIMEGPS layout written by
hand, until spec/binary/ubx describes the messages, checked field by field against pyubx2 on
every NAV-TIMEGPS frame of gpsd's logs and written back byte-exact."""

from __future__ import annotations

import sys
from pathlib import Path
from typing import Any

import pyubx2
import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "generated" / "python"))

from nmeaspec import ais, ubx  # noqa: E402
from tests.ubx.pyubx2_oracle import log_frames  # noqa: E402

# UBX-NAV-TIMEGPS (0x01 0x20), UBX-13003221: iTOW U4 ms, fTOW I4 ns, week I2, leapS I1 s,
# valid X1 (towValid, weekValid, leapSValid in bits 0-2), tAcc U4 ns.
NAV_TIMEGPS = (
    ais.Unsigned("iTOW", 32, divisor=1000),
    ais.Signed("fTOW", 32),
    ais.Signed("week", 16),
    ais.Signed("leapS", 8),
    ais.Unsigned("valid", 8),
    ais.Unsigned("tAcc", 32),
)


def decode(payload: bytes) -> dict[str, Any]:
    values: dict[str, Any] = {}
    ais.read_items(NAV_TIMEGPS, ubx.ByteReader(payload, "UBX NAV-TIMEGPS"), values)
    return values


def encode(values: dict[str, Any]) -> bytes:
    writer = ubx.ByteWriter()
    ais.write_items(NAV_TIMEGPS, type("Message", (), values), writer, "UBX NAV-TIMEGPS")
    return bytes(writer.payload)


def test_every_logged_nav_timegps_agrees_with_pyubx2_and_encodes_back() -> None:
    frames = [(raw, frame) for _, raw, frame in log_frames() if (frame.msg_class, frame.msg_id) == (0x01, 0x20)]
    assert len(frames) == 156
    for raw, frame in frames:
        ours = decode(frame.payload)
        theirs = pyubx2.UBXReader.parse(raw)
        assert ours["iTOW"] == theirs.iTOW / 1000
        assert [ours[name] for name in ("fTOW", "week", "leapS", "tAcc")] == \
            [theirs.fTOW, theirs.week, theirs.leapS, theirs.tAcc]
        assert [ours["valid"] >> bit & 1 for bit in range(3)] == \
            [theirs.towValid, theirs.weekValid, theirs.leapSValid]
        assert encode(ours) == frame.payload


def test_a_short_payload_names_message_field_and_bytes() -> None:
    with pytest.raises(ais.NmeaError) as caught:
        decode(bytes(8))
    assert (caught.value.kind, caught.value.address, caught.value.name) == ("short_payload", "UBX NAV-TIMEGPS", "week")
    assert caught.value.message == "week needs bytes 8-9, the payload has 8"
