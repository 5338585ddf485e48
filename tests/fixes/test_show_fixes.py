"""`nmea show --fixes`: one row per epoch, as a table, CSV or JSON lines."""

from __future__ import annotations

import csv
import io
import json

import pytest

from .gpsd_oracle import CORPUS
from nmeaspec.apps.nmea_cli import FIX_COLUMNS, main

LOG = str(CORPUS / "ublox-neo-m9n-nmea.nmea")   # GN RMC/VTG/GGA/GSA/GSV/GLL/GST/ZDA, NMEA 4.11


def show(capsys: pytest.CaptureFixture[str], *args: str) -> str:
    assert main(["show", "--fixes", "-q", *args, LOG]) == 0
    return capsys.readouterr().out


def test_table(capsys: pytest.CaptureFixture[str]) -> None:
    rows = show(capsys).splitlines()
    assert rows[0].split() == FIX_COLUMNS
    assert rows[1].split()[:12] == ["22:37:45", "2020-07-11", "38.110494", "-122.626897", "83.1", "0.0206",
                                    "fix_3d", "differential", "0.54", "25", "43", "GNRMC"]
    assert len(rows) == 1 + 61


def test_csv(capsys: pytest.CaptureFixture[str]) -> None:
    rows = list(csv.reader(io.StringIO(show(capsys, "--csv", "--fields", "time,latitude,used,in_view"))))
    assert rows[0] == ["time", "latitude", "used", "in_view"]
    assert rows[1] == ["22:37:45", "38.110494", "25", "43"] and len(rows) == 1 + 61


def test_json_gives_each_fix_whole(capsys: pytest.CaptureFixture[str]) -> None:
    first = json.loads(show(capsys, "--json").splitlines()[0])
    assert first["time"] == "22:37:45" and first["date"] == "2020-07-11" and first["mode"] == "fix_3d"
    assert first["used"]["galileo"] == [3, 5, 30, 27, 15]
    assert {"system": "galileo", "id": 3, "talker": "GA", "signal": "signal_7", "elevation": 44,
            "azimuth": 149, "snr": 40, "used": None} in first["in_view"]
    assert first["sentences"][:3] == ["GNRMC", "GNVTG", "GNGGA"]
