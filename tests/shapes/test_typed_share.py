"""The typed share of real logs outside the shared corpus: per log, the lines (those that start
with `$` or `!`) that the Python package decodes into a sentence the spec describes (behind its
TAG blocks or stray `$`, if any), rather than a Generic one or an error. No log may fall below the figure measured (typed_share.json); after a
change that raises one, record the new figures with
`UPDATE_TYPED_SHARE=1 .venv/bin/python -m pytest tests/shapes`.

The logs: pynmeagps's test logs (tests/data/pynmeagps) and gpsd's NMEA logs that the shared corpus
does not hold (tests/data/gpsd_logs), marine instrument sentences from other libraries' tests and
Java Marine API's ship capture (tests/data/marine), the test sentences of go-nmea, AeroRust's nmea,
minmea and lwgps with AeroRust's Quectel capture (tests/data/libraries), and two real ship captures
from OpenCPN's test data (tests/data/opencpn); each directory's PROVENANCE.md names the source."""

from __future__ import annotations

import json
import os
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "generated" / "python"))

import nmeaspec  # noqa: E402

DATA = ROOT / "tests" / "data"
SOURCES = ("pynmeagps", "gpsd_logs", "marine", "libraries", "opencpn")
MEASURED_FILE = Path(__file__).with_name("typed_share.json")
MEASURED: dict[str, list[int]] = json.loads(MEASURED_FILE.read_text(encoding="utf-8"))


def logs() -> list[str]:
    """Every log, as `<source>/<file name>`."""
    return sorted(f"{source}/{path.name}" for source in SOURCES for path in (DATA / source).glob("*.log"))


def typed_share(log: str) -> tuple[int, int]:
    """(typed lines, lines) of one log."""
    lines = typed = 0
    for raw in (DATA / log).read_bytes().splitlines():
        if raw[:1] not in (b"$", b"!"):
            continue  # gpsd's comment headers, binary between sentences
        lines += 1
        try:
            sentence = nmeaspec.parse(raw.decode("latin-1"))
        except nmeaspec.NmeaError:
            continue
        if isinstance(sentence, nmeaspec.Tagged):  # TAG blocks or a stray `$` before the sentence
            sentence = sentence.sentence
        typed += sentence is not None and not isinstance(sentence, nmeaspec.Generic)
    return typed, lines


@pytest.fixture(scope="module")
def found() -> dict[str, tuple[int, int]]:
    figures = {log: typed_share(log) for log in logs()}
    if os.environ.get("UPDATE_TYPED_SHARE"):
        MEASURED_FILE.write_text(json.dumps({log: list(f) for log, f in figures.items()}, indent=1) + "\n",
                                 encoding="utf-8")
        MEASURED.clear()
        MEASURED.update({log: list(f) for log, f in figures.items()})
    return figures


def test_every_log_is_measured(found: dict[str, tuple[int, int]]) -> None:
    assert sorted(MEASURED) == sorted(found)


def test_no_log_falls(found: dict[str, tuple[int, int]], capsys: pytest.CaptureFixture[str]) -> None:
    fallen = [f"{log}: {found[log][0]} of {found[log][1]} typed, measured {typed} of {lines}"
              for log, (typed, lines) in MEASURED.items() if log in found and found[log][0] < typed]
    with capsys.disabled():
        print("\n" + report(found))
    assert not fallen, "\n".join(fallen)


def report(found: dict[str, tuple[int, int]]) -> str:
    """Per log and per source: typed lines, lines, share."""
    rows = [f"{log:55} {typed:5} / {lines:5}  {100 * typed / lines:6.2f}%"
            for log, (typed, lines) in found.items() if lines]
    for source in SOURCES:
        typed = sum(f[0] for log, f in found.items() if log.startswith(source + "/"))
        lines = sum(f[1] for log, f in found.items() if log.startswith(source + "/"))
        rows.append(f"{'all of ' + source:55} {typed:5} / {lines:5}  {100 * typed / lines:6.2f}%")
    return "\n".join(rows)
