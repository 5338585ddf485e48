"""`stream --rtcm3`: each RTCM 3 frame's object also carries the message it decodes to (`rtcm3`,
the decoded JSON of generated/vectors/rtcm3.jsonl) or why it does not (`rtcm3_error`), byte for
byte alike in the three tools. Over the logs in tests/data that hold RTCM 3 and made-up frames:
every message is the Python package's decoding of the frame, each decoded frame encodes back to
its bytes, and without --rtcm3 the output is the same less those members."""

from __future__ import annotations

import json
import sys

import pytest

from tests.agreement.test_agreement import BINARY_LOGS, GGA, ROOT, run

sys.path.insert(0, str(ROOT / "generated" / "python"))  # the made-up frames below are the package's

RTCM3_TOOLS = ["nmea-c", "nmea-rs", "nmea-py"]
RTCM3_LOGS = [log for log in BINARY_LOGS if log.parent.name == "rtcm3"]


def frame(*fields: tuple[int, int]) -> bytes:
    """The frame of a payload of (value, bits) fields, zero bits to a whole byte."""
    from nmeaspec import rtcm3

    value = length = 0
    for raw, bits in fields:
        value, length = value << bits | raw, length + bits
    value, length = value << (-length % 8), length + (-length % 8)
    return rtcm3.frame(value.to_bytes(length // 8, "big"))


TEXT = "é\"x".encode() + b"\xff"  # UTF-8, a quote, and a byte that is no UTF-8
# A 1005 cut after its station id (short_payload, naming itrf_year); 4072, which the spec does not
# describe; a 1029 of that text; an MSM7 whose masks set 66 cells (bad_value: at most 64); a
# payload of one byte (no message number).
MADE_UP = (GGA + frame((1005, 12), (0, 12)) + frame((4072, 12), (0, 4)) + GGA
           + frame((1029, 12), (7, 12), (60000, 16), (3600, 17), (4, 7), (len(TEXT), 8),
                   (int.from_bytes(TEXT, "big"), 8 * len(TEXT)))
           + frame((1077, 12), (7, 12), (0, 49), (0b111 << 61, 64), ((1 << 22) - 1 << 10, 32), ((1 << 66) - 1, 66),
                   (0, 3 * 36 + 66 * 80))
           + frame((0x43, 8)) + GGA)


def agreed_rtcm3(data: bytes) -> bytes:
    outputs = {tool: run(tool, ["stream", "--rtcm3"], data) for tool in RTCM3_TOOLS}
    reference = outputs[RTCM3_TOOLS[0]]
    for tool, out in outputs.items():
        a, b = reference.splitlines(), out.splitlines()
        differing = next((i for i in range(max(len(a), len(b))) if a[i:i + 1] != b[i:i + 1]), None)
        assert differing is None, (f"{RTCM3_TOOLS[0]} and {tool} disagree on line {differing}:\n"
                                   f"{a[differing:differing + 1]!r}\n{b[differing:differing + 1]!r}")
    return reference


@pytest.mark.parametrize("name", [p.name for p in RTCM3_LOGS] + ["made-up frames"])
def test_stream_rtcm3_prints_each_frames_message(name: str) -> None:
    from nmeaspec import rtcm3, rtcm3_messages

    data = {p.name: p for p in RTCM3_LOGS}[name].read_bytes() if name.endswith(".log") else MADE_UP
    objects = [json.loads(line) for line in agreed_rtcm3(data).splitlines()]
    plain = [json.loads(line) for line in run("nmea-py", ["stream"], data).splitlines()]
    assert [{k: v for k, v in o.items() if k not in ("rtcm3", "rtcm3_error")} for o in objects] == plain
    frames = [o for o in objects if o.get("protocol") == "rtcm3" and o["ok"]]
    assert frames, name
    decoded = 0
    for o in frames:
        data = bytes.fromhex(o["frame"])
        try:
            message = rtcm3_messages.decode(data)
        except rtcm3.NmeaError as err:
            assert o["rtcm3_error"] == json.loads(err.error_json()) and "rtcm3" not in o
            continue
        assert o["rtcm3"] == message.to_dict() and "rtcm3_error" not in o
        assert message.encode() == data
        decoded += message.to_dict()["message"] is not None
    print(f"{name}: {len(frames)} RTCM 3 frames, {decoded} decoded alike by the three tools")
    if name == "made-up frames":
        assert [o.get("rtcm3", {}).get("message", o.get("rtcm3_error", {}).get("name")) for o in frames] == [
            "itrf_year", None, "text_string", "cells", None]
