"""`stream --ubx`: each UBX frame's object also carries the message it decodes to (`ubx`, the
decoded JSON of generated/vectors/ubx.jsonl) or why it does not (`ubx_error`), byte for byte alike
in the three tools. Over gpsd's logs (tests/data/ubx, tests/data/rtcm3) and made-up frames:
every message is the Python package's decoding of the frame, each decoded frame encodes back to
its bytes, and without --ubx the output is the same less those members."""

from __future__ import annotations

import json

import pytest

from tests.agreement.test_agreement import ACK, BINARY_CASES, BINARY_LOGS, GGA, run

UBX_TOOLS = ["nmea-c", "nmea-rs", "nmea-py"]


def frame(msg_class: int, msg_id: int, payload: bytes) -> bytes:
    from tests.ubx.pyubx2_oracle import ubx

    return ubx.Frame(msg_class, msg_id, payload).encode()


# A NAV-TIMEGPS cut to 10 bytes (short_payload, naming leap_s), a class and id the spec does not
# describe, a MON-VER (characters with NUL padding, a group of the bytes left), a NAV-PVT of zeros,
# a NAV-SAT whose count says more satellites than its payload holds (a group cut short).
MADE_UP = (GGA + frame(0x01, 0x20, bytes(10)) + frame(0x7F, 0x01, b"\xaa") + GGA
           + frame(0x01, 0x35, bytes(4) + b"\x01\x03" + bytes(2) + bytes(12))
           + frame(0x0A, 0x04, b"ROM CORE 3.01 (107888)".ljust(30, b"\0") + b"00080000".ljust(10, b"\0")
                   + b"PROTVER=18.00".ljust(30, b"\0")) + frame(0x01, 0x07, bytes(92)) + ACK)


def agreed_ubx(data: bytes) -> bytes:
    outputs = {tool: run(tool, ["stream", "--ubx"], data) for tool in UBX_TOOLS}
    reference = outputs[UBX_TOOLS[0]]
    for tool, out in outputs.items():
        a, b = reference.splitlines(), out.splitlines()
        differing = next((i for i in range(max(len(a), len(b))) if a[i:i + 1] != b[i:i + 1]), None)
        assert differing is None, (f"{UBX_TOOLS[0]} and {tool} disagree on line {differing}:\n"
                                   f"{a[differing:differing + 1]!r}\n{b[differing:differing + 1]!r}")
    return reference


@pytest.mark.parametrize("name", [p.name for p in BINARY_LOGS] + ["binary cases", "made-up frames"])
def test_stream_ubx_prints_each_frames_message(name: str) -> None:
    from tests.ubx.pyubx2_oracle import ubx, ubx_messages

    data = {p.name: p for p in BINARY_LOGS}[name].read_bytes() if name.endswith(".log") else \
        BINARY_CASES if name == "binary cases" else MADE_UP
    objects = [json.loads(line) for line in agreed_ubx(data).splitlines()]
    plain = [json.loads(line) for line in run("nmea-py", ["stream"], data).splitlines()]
    assert [{k: v for k, v in o.items() if k not in ("ubx", "ubx_error")} for o in objects] == plain
    frames = [o for o in objects if o.get("protocol") == "ubx" and o["ok"]]
    log = {p.name: p for p in BINARY_LOGS}.get(name)
    assert frames or (log is not None and log.parent.name != "ubx"), name  # the other logs may hold none
    for o in frames:
        data = bytes.fromhex(o["frame"])
        try:
            message = ubx_messages.decode(data)
        except ubx.NmeaError as err:
            assert o["ubx_error"] == json.loads(err.error_json()) and "ubx" not in o
            continue
        assert o["ubx"] == message.to_dict() and "ubx_error" not in o
        assert message.encode() == data
    if name == "made-up frames":
        assert [o.get("ubx", {}).get("message", o.get("ubx_error", {}).get("name")) for o in frames] == [
            "leap_s", None, "svs", "mon_ver", "nav_pvt", "ack_ack"]
