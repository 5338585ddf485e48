"""pyubx2 (semuconsulting), the oracle of the UBX frames that gpsd's regression logs carry
(tests/data/ubx): every frame our reader splits out must be one pyubx2 accepts (checksum
validated) and serializes back to the same bytes. The frame count per message goes to
docs/ubx-agreement.md; `.venv/bin/python -m tests.ubx.pyubx2_oracle` rewrites it.

Field-by-field comparison waits for the generated message classes (issue 31, item 2)."""

from __future__ import annotations

import sys
from collections import Counter
from pathlib import Path

import pyubx2

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "generated" / "python"))

from nmeaspec import ubx  # noqa: E402

DATA = ROOT / "tests" / "data" / "ubx"
REPORT = ROOT / "docs" / "ubx-agreement.md"
# pyubx2 tells a message's direction by the mode it is parsed in: receiver output first.
MODES = (pyubx2.GET, pyubx2.SET, pyubx2.POLL)


def log_frames() -> list[tuple[str, bytes, ubx.Frame]]:
    """(log name, the frame's bytes as logged, the frame) for every frame of every log."""
    frames = []
    for log in sorted(DATA.glob("*.log")):
        data = log.read_bytes()
        for pos, frame in ubx.split_frames(data):
            frames.append((log.name, data[pos:pos + len(frame.payload) + 8], frame))
    return frames


def pyubx2_identity(raw: bytes) -> tuple[str, bytes]:
    """pyubx2's name of the message in `raw` and its serialization of what it parsed."""
    error: Exception | None = None
    for mode in MODES:
        try:
            message = pyubx2.UBXReader.parse(raw, validate=pyubx2.VALCKSUM, msgmode=mode)
        except (pyubx2.UBXParseError, pyubx2.UBXMessageError, pyubx2.UBXTypeError) as exc:
            error = exc
            continue
        return message.identity, message.serialize()
    raise AssertionError(f"pyubx2 rejects {raw.hex(' ')}: {error}")


def agreement() -> dict[str, tuple[int, int]]:
    """Per pyubx2 identity: (frames, frames pyubx2 serializes back byte-exact)."""
    frames: Counter[str] = Counter()
    same: Counter[str] = Counter()
    for _, raw, _ in log_frames():
        identity, serialized = pyubx2_identity(raw)
        frames[identity] += 1
        same[identity] += serialized == raw
    return {identity: (frames[identity], same[identity]) for identity in sorted(frames)}


def report() -> str:
    rows = agreement()
    logs = Counter(name for name, _, _ in log_frames())
    lines = [
        "# UBX frames: agreement with pyubx2",
        "",
        "Written by `.venv/bin/python -m tests.ubx.pyubx2_oracle`; tests/ubx/test_ubx_frames.py fails",
        "when it is stale. The frames are those of gpsd's regression logs in tests/data/ubx",
        "(PROVENANCE.md), split by nmeaspec.ubx.split_frames. Every frame's checksum is accepted by",
        f"pyubx2 {pyubx2.__version__} and our encoder writes it back byte-exact. Field-by-field",
        "comparison comes with the generated message classes.",
        "",
        "| log | frames |",
        "| --- | ---: |",
        *(f"| {name} | {count} |" for name, count in sorted(logs.items())),
        "",
        "| message (pyubx2) | frames | pyubx2 re-serializes byte-exact |",
        "| --- | ---: | ---: |",
        *(f"| {identity} | {count} | {same} |" for identity, (count, same) in rows.items()),
        "",
    ]
    return "\n".join(lines)


if __name__ == "__main__":
    REPORT.write_text(report(), encoding="utf-8")
