"""The `nmea` CLI as installed by pip into a fresh virtual environment, on real receiver
logs and on stdin, and its command builder for several vendors (every command's checksum is
verified)."""

from __future__ import annotations

import csv
import io
import json
import re
from functools import reduce
from pathlib import Path

import pytest

from .conftest import Venv, corpus_log, run

LOG = "gpsd/ac12.nmea"          # GP GGA/GSA/GSV/RMC/ZDA with a 3D fix
ERRORS_LOG = "gpsd/blumax-gps009.nmea"   # SiRF text lines that are not sentences


def nmea(env: Venv, *args: str | Path, input: bytes | None = None, check: bool = True):  # type: ignore[no-untyped-def]
    return run(env.bin / "nmea", *args, input=input, check=check, cwd=env.path.parent)


def test_table_of_chosen_fields(installed: Venv) -> None:
    result = nmea(installed, corpus_log(LOG), "--sentences", "GGA", "--fields", "line,time,lat,lon,quality,satellites")
    rows = result.stdout.decode().splitlines()
    assert rows[0].split() == ["line", "time", "lat", "lon", "quality", "satellites"]
    assert rows[1].split() == ["1", "19:32:21.00", "20.6287987", "-87.0680797", "autonomous", "4"]
    assert len(rows) == 1 + 7
    # aligned: every column starts at the same offset in every row
    starts = [rows[0].index(h) for h in ("time", "lat", "lon", "quality")]
    assert all(row[s - 2:s] == "  " and row[s] != " " for row in rows[1:] for s in starts)
    summary = result.stderr.decode()
    assert summary.startswith("51 lines: 51 sentences, 0 unknown, 0 errors\n")
    assert "  GSV  24\n" in summary and "  GGA  7\n" in summary


def test_json_lines(installed: Venv) -> None:
    out = nmea(installed, "show", "--json", "--sentences", "RMC", corpus_log(LOG)).stdout.decode().splitlines()
    first = json.loads(out[0])
    assert first["sentence"] == "RMC" and first["talker"] == "GP" and first["line"] == 6
    assert first["fields"]["lat"] == 20.6287983 and first["fields"]["status"] == "valid"
    assert all(json.loads(line)["sentence"] == "RMC" for line in out) and len(out) == 7


def test_csv(installed: Venv) -> None:
    out = nmea(installed, "show", "--csv", "--fields", "time,lat,lon,speed,date", "--sentences", "RMC",
               corpus_log(LOG)).stdout.decode()
    rows = list(csv.reader(io.StringIO(out)))
    assert rows[0] == ["time", "lat", "lon", "speed", "date"]
    assert rows[1][:3] == ["19:32:21.00", "20.6287983", "-87.06808"] and len(rows) == 8


UBX_LOG = Path(__file__).resolve().parents[1] / "data" / "ubx" / "ublox-neo-m8n.log"


def test_binary_frames_are_shown_with_their_messages(installed: Venv) -> None:
    """A log of NMEA and UBX: each UBX frame is a row named as u-blox names its message, with its
    decoded values (JSON: the same values the package's decode gives), counted in the summary;
    a damaged frame is counted as its reason."""
    from tests.ubx.pyubx2_oracle import ubx, ubx_messages

    data = UBX_LOG.read_bytes()
    frames = [frame for _, frame in ubx.split_frames(data)]
    result = nmea(installed, "show", "--json", "--sentences", "UBX NAV-PVT", "-", input=data)
    rows = [json.loads(line) for line in result.stdout.decode().splitlines()]
    pvts = [f for f in frames if (f.msg_class, f.msg_id) == (0x01, 0x07)]
    assert len(rows) == len(pvts) > 0
    first = json.loads(json.dumps(ubx_messages.message(pvts[0]).to_dict()))
    assert rows[0]["sentence"] == "UBX NAV-PVT" and rows[0]["talker"] is None
    assert rows[0]["fields"] == {k: v for k, v in first.items() if k != "message"}
    assert re.search(rf"\n  UBX NAV-PVT +{len(pvts)}\n", result.stderr.decode())
    damaged = data.replace(pvts[0].encode(), pvts[0].encode()[:-1] + b"\x00", 1)
    summary = nmea(installed, "show", "--sentences", "UBX NAV-PVT", "-", input=damaged).stderr.decode()
    assert re.search(rf"\n  UBX NAV-PVT +{len(pvts) - 1}\n", summary) and re.search(r"\n  bad_checksum +1\n", summary)


TAG_LINES = Path(__file__).resolve().parents[1] / "data" / "tag_blocks" / "real.nmea"


def test_tag_blocks_in_table_csv_and_json(installed: Venv) -> None:
    lines = TAG_LINES.read_bytes() + b"\\s:2573535,c:1671533231*08\\\n"
    table = nmea(installed, "show", "-", input=lines).stdout.decode().splitlines()
    assert table[1].split()[:4] == ["1", "AI", "VDM", "tag(group=(number=1"]
    assert "source=r003669945 time=1241544035)" in table[1]
    assert table[-1].split() == ["10", "TAG", "tag(source=2573535", "time=1671533231)"]
    rows = list(csv.reader(io.StringIO(nmea(
        installed, "show", "--csv", "--fields", "line,sentence,tag.source,tag.time,tag.q", "-", input=lines
    ).stdout.decode())))
    assert rows[0] == ["line", "sentence", "tag.source", "tag.time", "tag.q"]
    assert rows[9] == ["9", "VDM", "rORBCOMM000", "1426032001", "u"]
    records = [json.loads(r) for r in nmea(installed, "show", "--json", "-", input=lines).stdout.splitlines()]
    assert records[4]["tag_block"] == {"source": "APIDSSRC1", "group": {"number": 1, "total": 2, "id": 5649},
                                       "line_count": 8851, "time": 2780328}
    assert "tag_block" in records[-1] and records[-1]["sentence"] == "TAG"


def test_stdin_errors_and_no_progress_bar_in_a_pipe(installed: Venv) -> None:
    data = corpus_log(ERRORS_LOG).read_bytes()
    result = nmea(installed, "-", "--fields", "sentence", input=data)
    assert result.stdout.decode().splitlines()[1:4] == ["GGA", "GLL", "GSA"]
    summary = result.stderr.decode()
    assert summary.startswith("67 lines: 59 sentences, 0 unknown, 8 errors\n")
    assert "errors:\n  not_a_sentence  8\n" in summary
    assert "\r" not in summary and "%" not in summary


def test_progress_bar_on_request(installed: Venv) -> None:
    result = nmea(installed, "show", "--progress", "-q", "--json", corpus_log(LOG))
    assert "100%" in result.stderr.decode() and result.stderr.decode().startswith("\r[")


def _checked(data: bytes) -> bytes:
    """The bytes of a '$' command, after checking that they end in CR LF and that the checksum fits."""
    assert data.endswith(b"\r\n")
    body, star, checksum = data[1:-2].rpartition(b"*")
    if star:
        assert int(checksum, 16) == reduce(lambda a, b: a ^ b, body, 0), data
    return data


@pytest.mark.parametrize(("words", "expected"), [
    (["geos5", "set-baud", "115200"], b"$GPSGG,BDR115*09\r\n"),
    (["geos5", "command", "BDR115"], b"$GPSGG,BDR115*09\r\n"),
    (["geos5", "output", "gga", "on"], b"$GPSGG,GGA ON*08\r\n"),
    (["geos5", "nquery-request"], b"$GPSGG,NQUERY*6C\r\n"),
    (["teseo", "pstmsetpar", "1201", "40", "set-bits"], b"$PSTMSETPAR,1201,40,1*00\r\n"),
    (["teseo", "pstmcold", "3"], b"$PSTMCOLD,3*01\r\n"),
    (["globalsat", "psrf103", "--message", "gga", "--mode", "query", "--rate", "0", "--checksum-mode", "enabled"],
     b"$PSRF103,00,01,0,01*15\r\n"),
    (["comnav", "log", "gpgga", "ontime", "1"], b"LOG GPGGA ONTIME 1\r\n"),
    (["comnav", "nmeatalker-list"], b"NMEATALKER LIST\r\n"),
])
def test_command_builder(installed: Venv, words: list[str], expected: bytes) -> None:
    assert _checked(nmea(installed, "command", *words).stdout) == expected


def test_command_errors_and_list(installed: Venv) -> None:
    bad = nmea(installed, "command", "geos5", "set-baud", "1234", check=False)
    assert bad.returncode == 2 and b"115200" in bad.stderr and bad.stdout == b""
    bad = nmea(installed, "command", "globalsat", "psrf103", "--rate", "x", "--message", "gga", "--mode", "query",
               "--checksum-mode", "enabled", check=False)
    assert bad.returncode == 2 and b"rate" in bad.stderr
    listing = nmea(installed, "command", "--list", "teseo").stdout.decode()
    assert "pstmsetpar BLOCK_PARAM VALUE [MODE]" in listing and "geos5" not in listing
    assert b"set-baud 4800|9600" in nmea(installed, "command", "--list").stdout
    assert b"examples:" in nmea(installed, "command", "--help").stdout
