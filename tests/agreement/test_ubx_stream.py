"""`stream --ubx`: each UBX frame's object also carries the message it decodes to (`ubx`, the
decoded JSON of generated/vectors/ubx.jsonl) or why it does not (`ubx_error`), and each SkyTraq,
SiRF, CASIC and SBF frame's alike under its protocol's name (`sirf`, `sirf_error`), byte for byte alike
in the three tools. Over gpsd's logs (tests/data/*) and made-up frames: every message is the Python
package's decoding of the frame, each decoded frame encodes back to its bytes, and without --ubx
the output is the same less those members."""

from __future__ import annotations

import json

import pytest

from tests.agreement.test_agreement import ACK, BINARY_CASES, BINARY_LOGS, GGA, SBF_LOGS, run

UBX_TOOLS = ["nmea-c", "nmea-rs", "nmea-py"]
TYPED = ("ubx", "skytraq", "sirf", "casic", "sbf", "unicore")   # the protocols whose messages the tools decode


def frame(msg_class: int, msg_id: int, payload: bytes) -> bytes:
    from tests.ubx.pyubx2_oracle import ubx

    return ubx.Frame(msg_class, msg_id, payload).encode()


def other(protocol: str, key: tuple[int, ...], payload: bytes) -> bytes:
    from tests.ubx.pyubx2_oracle import ubx  # noqa: F401 (puts generated/python on the path)

    from nmeaspec import binary

    return binary.Frame(protocol, key, payload).encode()


# A NAV-TIMEGPS cut to 10 bytes (short_payload, naming leap_s), a class and id the spec does not
# describe, a MON-VER (characters with NUL padding, a group of the bytes left), a NAV-PVT of zeros,
# a NAV-SAT whose count says more satellites than its payload holds (a group cut short); a SkyTraq
# 0xA8 cut to 20 bytes (naming msl_alt), a SiRF id no layout describes, a CASIC NAV-PV of zeros; an
# SBF PVTGeodetic (4007 rev 2) cut to 20 bytes after its header (naming longitude), a block number
# no layout describes (4000 rev 1), a ReceiverTime (5914) of do-not-use values with 4 bytes more.
MADE_UP = (GGA + frame(0x01, 0x20, bytes(10)) + frame(0x7F, 0x01, b"\xaa") + GGA
           + frame(0x01, 0x35, bytes(4) + b"\x01\x03" + bytes(2) + bytes(12))
           + frame(0x0A, 0x04, b"ROM CORE 3.01 (107888)".ljust(30, b"\0") + b"00080000".ljust(10, b"\0")
                   + b"PROTVER=18.00".ljust(30, b"\0")) + frame(0x01, 0x07, bytes(92)) + ACK
           + other("skytraq", (0xA8,), bytes(20)) + GGA + other("sirf", (0x7E,), b"\x01\x02")
           + other("casic", (0x01, 0x03), bytes(80)) + GGA
           + other("sbf", (4007, 2), bytes(20)) + other("sbf", (4000, 1), b"\x01\x02\x03\x04") + GGA
           + other("sbf", (5914, 0), b"\xff" * 4 + b"\xff\xff" + b"\x80" * 7 + b"\x00\x00\x00" + bytes(4)))


def agreed_ubx(data: bytes) -> bytes:
    outputs = {tool: run(tool, ["stream", "--ubx"], data) for tool in UBX_TOOLS}
    reference = outputs[UBX_TOOLS[0]]
    for tool, out in outputs.items():
        a, b = reference.splitlines(), out.splitlines()
        differing = next((i for i in range(max(len(a), len(b))) if a[i:i + 1] != b[i:i + 1]), None)
        assert differing is None, (f"{UBX_TOOLS[0]} and {tool} disagree on line {differing}:\n"
                                   f"{a[differing:differing + 1]!r}\n{b[differing:differing + 1]!r}")
    return reference


@pytest.mark.parametrize("name", [p.name for p in BINARY_LOGS] + ["sbf logs", "binary cases", "made-up frames"])
def test_stream_ubx_prints_each_frames_message(name: str) -> None:
    from tests.ubx.pyubx2_oracle import ubx, ubx_messages

    data = {p.name: p for p in BINARY_LOGS}[name].read_bytes() if name.endswith(".log") else \
        b"".join(p.read_bytes() for p in SBF_LOGS) if name == "sbf logs" else \
        BINARY_CASES if name == "binary cases" else MADE_UP
    objects = [json.loads(line) for line in agreed_ubx(data).splitlines()]
    plain = [json.loads(line) for line in run("nmea-py", ["stream"], data).splitlines()]
    members = {*TYPED, *(f"{p}_error" for p in TYPED)}
    assert [{k: v for k, v in o.items() if k not in members} for o in objects] == plain
    frames = [o for o in objects if o.get("protocol") in TYPED and o["ok"]]
    log = {p.name: p for p in BINARY_LOGS}.get(name)
    assert frames or (log is not None and log.parent.name in ("rtcm3", "sbf", "unicore")), name  # those logs may hold none
    from nmeaspec import stream

    for o in frames:
        data, protocol = bytes.fromhex(o["frame"]), o["protocol"]
        assert {k for k in o if k in members} in ({protocol}, {f"{protocol}_error"}), o
        try:
            message = ubx_messages.decode(data) if protocol == "ubx" else stream.BinaryFrame(protocol, data).message()
        except ubx.NmeaError as err:
            assert o[f"{protocol}_error"] == json.loads(err.error_json())
            continue
        assert o[protocol] == message.to_dict()
        assert message.encode() == data   # byte for byte (Unicore's header fields kept: its `header`)
    if name == "made-up frames":
        assert [o.get(o["protocol"], {}).get("message", o.get(f"{o['protocol']}_error", {}).get("name"))
                for o in frames] == ["leap_s", None, "svs", "mon_ver", "nav_pvt", "ack_ack", "msl_alt", None, "nav_pv",
                                     "longitude", None, "receiver_time"]
