"""The C UBX pair (generated/c/nmea_ubx.{c,h}, through runtime/c/test_ubx.c --json) against the
Python classes (nmeaspec.ubx_messages) frame by frame: every UBX frame of gpsd's logs
(tests/data/ubx, tests/data/rtcm3) and made-up frames of every layout (bytes drawn from a
generator seeded with the layout's id: its fixed length, a version byte set; variable layouts at
several lengths, some of which cut a group) decode to the same JSON, or are refused with the same
error kind and field, and every frame that decodes encodes back byte-exact in C (the program
fails otherwise). The same for SkyTraq, SiRF, CASIC and SBF (nmeaspec.<protocol>_messages): every
frame of their logs (pysbf2's for SBF) and made-up frames of every layout, and of an id no layout
describes."""

from __future__ import annotations

import json
import os
import random
import subprocess
from pathlib import Path

import pytest

from tests.ubx.pyubx2_oracle import ubx, ubx_messages

from nmeaspec import binary, stream  # noqa: E402  (pyubx2_oracle puts generated/python on the path)
from nmeaspec import casic_messages, sbf_messages, sirf_messages, skytraq_messages  # noqa: E402

ROOT = Path(__file__).resolve().parents[2]
LOGS = sorted((ROOT / "tests" / "data" / "ubx").glob("*.log")) + sorted((ROOT / "tests" / "data" / "rtcm3").glob("*.log"))


@pytest.fixture(scope="module")
def c_program(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """runtime/c/test_ubx.c over the generated UBX pair alone, built here unoptimized."""
    program = tmp_path_factory.mktemp("ubx-c") / "test_ubx"
    cc = os.environ.get("CC", "cc")
    c = ROOT / "generated" / "c"
    subprocess.run([cc, "-std=c99", "-Wall", "-Wextra", "-Werror", "-pedantic", "-O0", "-DUBX_TEST_JSON_ONLY", "-I", str(c),
                    "-o", str(program), str(c / "nmea_ubx.c"), str(ROOT / "runtime" / "c" / "test_ubx.c")], check=True)
    return program


def version_at(cls: type[ubx.Message]) -> int | None:
    """The byte of a layout's selector (a type or version byte), when one tells it apart."""
    return None if cls.SELECT is None else cls.SELECT[1]


def log_frames() -> list[bytes]:
    """Every UBX frame of the logs, as the Python stream reader splits them."""
    return [frame.data for log in LOGS for frame in stream.lines([log.read_bytes()], binary=True)
            if isinstance(frame, stream.BinaryFrame) and frame.protocol == "ubx"]


def made_up_frames() -> list[bytes]:
    """A frame per fixed layout and five per variable one, its payload drawn at random."""
    out = []
    for layouts in ubx_messages.BY_ID.values():
        for cls in layouts:
            draw = random.Random(cls.ID)
            lengths = [cls.LENGTH] if cls.LENGTH is not None else [draw.randrange(4, 120) for _ in range(5)]
            for length in lengths:
                payload = bytearray(draw.randrange(256) for _ in range(length))
                at = version_at(cls)
                if at is not None and at < length:
                    payload[at] = cls.SELECT[2]
                out.append(ubx.Frame(cls.CLASS, cls.MSG_ID, bytes(payload)).encode())
    return out


OTHERS = {"skytraq": skytraq_messages, "sirf": sirf_messages, "casic": casic_messages, "sbf": sbf_messages}


def other_frames() -> list[tuple[str, bytes]]:
    """Every frame of the other protocols' logs, and made-up ones: a frame per fixed layout and
    five per variable one (drawn as made_up_frames draws them), and one of an id no layout has."""
    out = [(frame.protocol, frame.data) for name in OTHERS
           for log in sorted((ROOT / "tests" / "data" / name).glob("*.log")) + sorted((ROOT / "tests" / "data" / name).glob("*.sbf"))
           for frame in stream.lines([log.read_bytes()], binary=True)
           if isinstance(frame, stream.BinaryFrame) and frame.protocol == name]
    for name, module in OTHERS.items():
        for layouts in module.BY_ID.values():
            for cls in layouts:
                draw = random.Random(f"{name} {cls.ID}")
                lengths = [cls.LENGTH] if cls.LENGTH is not None else [draw.randrange(0, 120) for _ in range(5)]
                for length in lengths:
                    payload = bytearray(draw.randrange(256) for _ in range(length))
                    at = version_at(cls)
                    if at is not None and at < length:
                        payload[at] = cls.SELECT[2]
                    out.append((name, binary.Frame(name, cls.KEY, bytes(payload)).encode()))
                    specials = [f for f in cls.LAYOUT if isinstance(f, ubx.Float) and f.special]
                    if specials:   # and with its floats' special values (SBF's do-not-use -2e10: r4, r8)
                        message = cls.from_payload(bytes(payload))
                        for f in specials:
                            setattr(message, f.id, f.special[0])
                        out.append((name, message.encode()))
        key = (0x0B, 0x7F) if name == "casic" else (4000, 1) if name == "sbf" else (0x7E,)
        out.append((name, binary.Frame(name, key, b"\x01\x02").encode()))
    return out


def python_json(frame: bytes, protocol: str = "ubx") -> dict:
    try:
        if protocol != "ubx":
            return {"decode": OTHERS[protocol].decode(frame).to_dict()}
        return {"decode": ubx_messages.decode(frame).to_dict()}
    except ubx.NmeaError as e:
        return {"error": e.kind, "field": e.name or ""}


def compare(program: Path, frames: list[bytes] | list[tuple[str, bytes]], tmp_path: Path) -> int:
    hex_file = tmp_path / "frames.hex"
    named = [f if isinstance(f, tuple) else ("ubx", f) for f in frames]
    hex_file.write_text("".join((f"{p} " if p != "ubx" else "") + frame.hex() + "\n" for p, frame in named))
    run = subprocess.run([str(program), str(ROOT / "generated" / "vectors" / "ubx.jsonl"), "--json", str(hex_file)],
                         capture_output=True, check=False)
    lines = run.stdout.decode("latin-1").splitlines()
    failures = [line for line in lines if line.startswith("FAIL")]
    assert run.returncode == 0 and not failures, failures[:5]
    assert len(lines) == len(named)
    for line, (protocol, _) in zip(lines, named):
        got = json.loads(line)
        frame = bytes.fromhex(got.pop("frame"))
        assert got == python_json(frame, protocol), f"{protocol} {frame.hex()}"
    return len(lines)


def test_every_logged_frame_decodes_as_python_does(c_program: Path, tmp_path: Path) -> None:
    assert compare(c_program, log_frames(), tmp_path) >= 1900


def test_made_up_frames_of_every_layout_decode_as_python_does(c_program: Path, tmp_path: Path) -> None:
    frames = made_up_frames()
    assert compare(c_program, frames, tmp_path) == len(frames) > sum(len(layouts) for layouts in ubx_messages.BY_ID.values())


def test_other_protocols_frames_decode_as_python_does(c_program: Path, tmp_path: Path) -> None:
    frames = other_frames()
    assert compare(c_program, frames, tmp_path) == len(frames) > 1700
