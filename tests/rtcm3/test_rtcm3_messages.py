"""The generated RTCM 3 message classes (nmeaspec.rtcm3_messages, from spec/binary/rtcm3): every
frame of the logs we hold decoded as the reference decoder (generator/reference_rtcm3.py) decodes
it and encoded back byte-exact; the shared vectors (generated/vectors/rtcm3.jsonl); typed errors
naming protocol, message and field; encoding what a caller builds or changes."""

from __future__ import annotations

import io
import json
import sys
from pathlib import Path

import pytest
from pyrtcm import RTCMReader

from generator import reference_rtcm3
from generator.build import load_spec

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "generated" / "python"))

from nmeaspec import ais, rtcm3, rtcm3_messages  # noqa: E402
from nmeaspec.runtime import NmeaError  # noqa: E402

VECTORS = [json.loads(line) for line in (ROOT / "generated" / "vectors" / "rtcm3.jsonl").read_text().splitlines()]
LOGS = [log for log in sorted((ROOT / "tests" / "data").glob("*/*.log")) if b"\xd3" in log.read_bytes()]


def log_frames() -> list[bytes]:
    return [raw for log in LOGS for raw, _ in RTCMReader(io.BytesIO(log.read_bytes()), quitonerror=0)]


@pytest.fixture(scope="module")
def spec():
    return load_spec(ROOT / "spec")


def test_every_logged_frame_decodes_as_the_reference_and_encodes_back(spec) -> None:
    frames = log_frames()
    described = 0
    for raw in frames:
        message = rtcm3_messages.decode(raw)
        assert message.encode() == raw
        assert json.loads(json.dumps(message.to_dict())) == json.loads(json.dumps(reference_rtcm3.decode(spec, raw)))
        described += isinstance(message, rtcm3.Message)
        assert isinstance(message, rtcm3.Message) == ((raw[3] << 4 | raw[4] >> 4) in rtcm3_messages.BY_NUMBER)
    assert len(frames) >= 250 and described >= 230


def test_the_vectors(spec) -> None:
    assert len(VECTORS) >= 20
    for vector in VECTORS:
        frame = bytes.fromhex(vector["frame"])
        if "error" in vector:
            with pytest.raises(NmeaError) as caught:
                rtcm3_messages.decode(frame)
            assert caught.value.kind == vector["error"], vector["where"]
            continue
        message = rtcm3_messages.decode(frame)
        assert json.loads(json.dumps(message.to_dict())) == vector["decode"], vector["where"]
        assert message.encode() == frame


def test_a_payload_decodes_as_its_frame() -> None:
    raw = bytes.fromhex("d300133ed7d30202980edeef34b4bd62ac0941986f33360b98")
    message = rtcm3_messages.decode_payload(raw[3:-3])
    assert message == rtcm3_messages.decode(raw)
    assert isinstance(message, rtcm3_messages.StationArp)
    assert (message.station_id, message.ecef_x, message.ecef_x_raw, message.antenna_height) == \
        (2003, 1114104.5999, 11141045999, None)
    assert message.payload() == raw[3:-3]
    assert f"{message.PROTOCOL} {message.ADDRESS}" == "RTCM3 1005"   # as nmea show names its row


def test_errors_name_protocol_message_and_field() -> None:
    with pytest.raises(NmeaError) as caught:
        rtcm3_messages.decode(bytes.fromhex("d300033ed0007a79fe"))
    assert (caught.value.kind, caught.value.name) == ("short_payload", "itrf_year")
    assert str(caught.value).startswith("short_payload: RTCM3 1005: "), str(caught.value)
    for frame, kind in (("d300044ce00080ededd7", "bad_checksum"), ("d300044ce00080eded", "short_frame"),
                        ("d300044ce00080ededd600", "long_frame"), ("b5620501", "bad_sync")):
        with pytest.raises(NmeaError) as caught:
            rtcm3_messages.decode(bytes.fromhex(frame))
        assert caught.value.kind == kind, frame


def test_an_msm7_keeps_its_masks_and_cells_and_checks_them() -> None:
    raw = next(f for f in log_frames() if f[3] << 4 | f[4] >> 4 == 1077)
    message = rtcm3_messages.decode(raw)
    assert isinstance(message, rtcm3_messages.Msm7)
    satellites = bin(message.satellite_mask or 0).count("1")
    signals = bin(message.signal_mask or 0).count("1")
    assert len(message.cell_mask or "") == satellites * signals
    assert len(message.satellites) == satellites and len(message.cells) == (message.cell_mask or "").count("1")
    message.cells[0].cnr = 40.5
    again = rtcm3_messages.decode(message.encode())
    assert isinstance(again, rtcm3_messages.Msm7) and again.cells[0].cnr == 40.5 and again.cells[1:] == message.cells[1:]
    message.cells.pop()
    with pytest.raises(NmeaError) as caught:
        message.encode()
    assert (caught.value.kind, caught.value.name) == ("bad_value", "cells")
    assert "RTCM3 1077" in str(caught.value)


def test_counted_text_and_built_messages() -> None:
    built = rtcm3_messages.AntennaDescriptor(message_number=1007, station_id=5, descriptor_length=4,
                                             descriptor="ABCD", setup_id=1)
    frame = built.encode()
    assert rtcm3_messages.decode(frame) == built
    built.descriptor = "ABC"
    with pytest.raises(NmeaError) as caught:
        built.encode()
    assert (caught.value.kind, caught.value.name) == ("bad_value", "descriptor")
    text = rtcm3_messages.TextString(message_number=1029, station_id=1, mjd=2, seconds_of_day=3, characters=2,
                                     code_units=3, text="жa")
    assert rtcm3_messages.decode(text.encode()) == text


def test_sign_magnitude_and_its_negative_zero() -> None:
    glonass = [m for m in map(rtcm3_messages.decode, log_frames()) if isinstance(m, rtcm3_messages.GlonassEphemeris)]
    zeros = [m for m in glonass if m.gamma == ais.Special("negative_zero", 1024)]
    assert zeros and all(m.to_dict()["gamma"] == "negative_zero" for m in zeros)
    negative = next(m for m in glonass if isinstance(m.x, float) and m.x < 0)
    assert negative.x_raw == round(negative.x * 2048)
    field = rtcm3_messages.GlonassEphemeris.field("x")
    assert field.to_raw(-1.0, "") == ((1 << 26) | 2048, 27)
    with pytest.raises(NmeaError):
        field.to_raw(float(1 << 16), "RTCM3 1020")


def test_unknown_numbers_stay_frames() -> None:
    frame = bytes.fromhex("d30002fe80bbfe86")
    message = rtcm3_messages.decode(frame)
    assert isinstance(message, rtcm3.Unknown)
    assert message.to_dict() == {"message": None, "message_number": 4072, "payload": "fe80"}
    assert message.encode() == frame


def test_nmea_show_gives_rtcm3_rows_their_values() -> None:
    import subprocess

    log = ROOT / "tests" / "data" / "rtcm3" / "rtcm3.log"
    shown = subprocess.run([sys.executable, "-m", "nmeaspec.apps.nmea_cli", "show", "--json", str(log)],
                           cwd=ROOT / "generated" / "python", capture_output=True, check=True).stdout.decode()
    rows = {r["sentence"]: r["fields"] for r in map(json.loads, shown.splitlines())}
    assert rows["RTCM3 1005"]["ecef_x"] == 1114104.5999 and rows["RTCM3 1005"]["station_id"] == 2003
    assert rows["RTCM3 1029"]["text"] == "UTF-8 проверка wörter"


def test_random_payloads_decode_or_fail_typed_and_encode_back() -> None:
    import random

    rng = random.Random(31)
    outcomes: dict[str, int] = {}
    for number in rtcm3_messages.BY_NUMBER:
        for _ in range(40):
            payload = bytearray(rng.getrandbits(8) for _ in range(rng.randint(0, 300)))
            if len(payload) >= 2:   # the message number, the rest random
                payload[0], payload[1] = number >> 4, (number & 15) << 4 | payload[1] & 15
            frame = rtcm3.frame(bytes(payload))
            try:
                message = rtcm3_messages.decode(frame)
            except NmeaError as err:
                outcomes[err.kind] = outcomes.get(err.kind, 0) + 1
                continue
            assert message.encode() == frame, number
            json.dumps(message.to_dict())
            outcomes["decoded"] = outcomes.get("decoded", 0) + 1
    assert set(outcomes) == {"decoded", "short_payload"} and outcomes["decoded"] >= 300, outcomes
