"""The UBX framing layer (runtime/python/ubx.py, as generated into nmeaspec.ubx): checksum,
the typed errors, byte-exact round trips over every frame of gpsd's logs, pyubx2's agreement on
every one of them (docs/ubx-agreement.md), and the framing spec the runtime implements."""

from __future__ import annotations

from pathlib import Path

import pytest
import yaml

from tests.ubx import pyubx2_oracle
from tests.ubx.pyubx2_oracle import log_frames, ubx

ROOT = Path(__file__).resolve().parents[2]
# UBX-ACK-ACK acknowledging CFG-PRT (class 06 id 00), checksum as pyubx2 computes it.
ACK = bytes.fromhex("b562 0501 0200 0600 0e37")


def test_a_frame_decodes_and_encodes_back() -> None:
    frame = ubx.decode_frame(ACK)
    assert (frame.msg_class, frame.msg_id, frame.payload) == (0x05, 0x01, b"\x06\x00")
    assert frame.encode() == ACK


@pytest.mark.parametrize(("data", "kind"), [
    (ACK[:5], "short_frame"),
    (ACK[:-1], "short_frame"),
    (ACK + b"\x00", "long_frame"),
    (ACK[:-1] + b"\x38", "bad_checksum"),
    (b"$G" + ACK[2:], "bad_sync"),
])
def test_errors_are_typed(data: bytes, kind: str) -> None:
    with pytest.raises(ubx.NmeaError) as caught:
        ubx.decode_frame(data)
    assert caught.value.kind == kind


def test_an_error_names_the_frame() -> None:
    with pytest.raises(ubx.NmeaError) as caught:
        ubx.decode_frame(ACK[:-1] + b"\x38")
    assert caught.value.address == "UBX 0x05 0x01"


def test_split_frames_skips_text_and_broken_frames() -> None:
    stream = b"$GPGGA,,*66\r\n" + ACK[:-1] + b"\x38" + ACK + b"\xb5" + ACK
    assert [pos for pos, _ in ubx.split_frames(stream)] == [23, 34]
    nuls = b"\xb5\x62" + bytes(6)  # class 0, id 0, length 0 and its checksum of NULs: a break's bytes
    assert ubx.decode_frame(nuls).encode() == nuls
    assert [pos for pos, _ in ubx.split_frames(nuls + ACK)] == [8]


def test_every_logged_frame_encodes_back_byte_exact() -> None:
    frames = log_frames()
    assert len(frames) > 1900
    for name, raw, frame in frames:
        assert frame.encode() == raw, name


def test_the_agreement_report_is_current() -> None:
    assert (ROOT / "docs" / "ubx-agreement.md").read_text(encoding="utf-8") == pyubx2_oracle.report(), (
        "docs/ubx-agreement.md is stale: run `.venv/bin/python -m tests.ubx.pyubx2_oracle`")


def test_the_runtime_implements_the_framing_spec() -> None:
    frame = yaml.safe_load((ROOT / "spec" / "binary" / "ubx" / "protocol.yaml").read_text(encoding="utf-8"))["frame"]
    assert bytes(frame["sync"]) == ubx.SYNC
    assert frame["checksum"]["algorithm"] == "fletcher8"
    assert [field["type"] for field in frame["header"]] == ["u1", "u1", "u2"]
