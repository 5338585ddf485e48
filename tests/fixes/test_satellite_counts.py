"""Whose count of satellites used is the fix's, the same in the three tools' `fixes` verb: the
combined talker's (GN), else a proprietary sentence's (u-blox PUBX,00 counts every satellite the
solution uses, also where the receiver sends GPGGA beside it), else the sum of each talker's
(SiRF V's GPGGA and GLGGA). The streams are built here from the spec's own example lines with one
time of day, so that they make one epoch each."""

from __future__ import annotations

import json
import os
import subprocess
from pathlib import Path

import pytest

from .gpsd_oracle import ROOT
from nmeaspec.fixes import fixes
from nmeaspec.runtime import checksum


def sentence(body: str) -> str:
    return f"{body}*{checksum(body[1:]):02X}"


GPGGA = sentence("$GPGGA,081350.00,4717.11399,N,00833.91590,E,1,08,1.01,499.6,M,48.0,M,,")
GNGGA = sentence("$GNGGA,081350.00,4717.11399,N,00833.91590,E,1,12,1.01,499.6,M,48.0,M,,")
GLGGA = sentence("$GLGGA,081350.00,4717.11399,N,00833.91590,E,1,03,1.01,499.6,M,48.0,M,,")
PUBX = "$PUBX,00,081350.00,4717.113210,N,00833.915187,E,546.589,G3,2.1,2.0,0.007,77.52,0.007,,0.92,1.19,0.77,9,0,0*5F"
CASES = [
    ([GPGGA, GLGGA], 11),      # one GGA per system: their sum
    ([GPGGA, PUBX], 9),        # the receiver's total, not 8 + 9
    ([PUBX, GPGGA], 9),
    ([GNGGA, PUBX], 12),       # the combined talker's first
    ([GPGGA, GLGGA, GNGGA], 12),
]


def tool(name: str) -> Path:
    tools = os.environ.get("NMEA_TOOLS")
    if tools:
        return Path(tools) / name
    subprocess.run(["make", "--no-print-directory", "-s", f"build/test-bin/{name}"], cwd=ROOT, check=True)
    return ROOT / "build" / "test-bin" / name


@pytest.mark.parametrize("lines, used", CASES, ids=[" ".join(l[1:6] for l in c[0]) for c in CASES])
def test_the_count_of_satellites_used(lines: list[str], used: int) -> None:
    (fix,) = fixes(lines)
    assert fix.satellites_used == used and fix.time is not None
    stream = "".join(f"{line}\r\n" for line in lines).encode()
    for name in ("nmea-c", "nmea-rs", "nmea-py"):
        out = subprocess.run([str(tool(name)), "fixes"], input=stream, capture_output=True, check=True).stdout
        (printed,) = [json.loads(line) for line in out.decode("ascii").splitlines()]
        assert printed["satellites_used"] == used, name


def test_a_second_antennas_sentences_are_not_the_fix() -> None:
    """Unicore's GGAH carries GGA's fields for the heading antenna (spec `like: GGA`): the three
    tools keep it out of the fix, whose position and count stay the first antenna's GGA's."""
    first = sentence("$GNGGA,073346.00,4004.73874301,N,11614.19077585,E,1,28,0.6,64.2831,M,8.4925,M,,")
    second = sentence("$GNGGAH,073346.00,4004.73814597,N,11614.19908275,E,4,20,0.6,64.3000,M,8.4925,M,,")
    (fix,) = fixes([first, second])
    assert (fix.satellites_used, fix.fix_quality, fix.sentences) == (28, "autonomous", ["GNGGA"])
    assert abs(fix.latitude - (40 + 4.73874301 / 60)) < 1e-12
    stream = f"{first}\r\n{second}\r\n".encode()
    for name in ("nmea-c", "nmea-rs", "nmea-py"):
        out = subprocess.run([str(tool(name)), "fixes"], input=stream, capture_output=True, check=True).stdout
        (printed,) = [json.loads(line) for line in out.decode("ascii").splitlines()]
        assert (printed["satellites_used"], printed["latitude"]) == (28, fix.latitude), name
