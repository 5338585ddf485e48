"""The assembler's epoch rules on short made-up streams (the checksums are computed)."""

from __future__ import annotations

import datetime as dt

from . import gpsd_oracle  # noqa: F401  (puts generated/python on the path)
from nmeaspec import runtime
from nmeaspec.fixes import FixAssembler, fixes


def line(body: str) -> str:
    return f"${body}*{runtime.checksum(body):02X}"


RMC = "GPRMC,{t},A,4807.038,N,01131.000,E,022.4,084.4,{d},003.1,W,A"
GGA = "GPGGA,{t},4807.038,N,01131.000,E,1,08,0.9,545.4,M,46.9,M,,"


def test_one_fix_per_epoch_with_timeless_sentences_joining_it() -> None:
    stream = [line(RMC.format(t="120000", d="230394")), line(GGA.format(t="120000")),
              line("GPGSA,A,3,04,05,,09,12,,,24,,,,,2.5,1.3,2.1"), line(RMC.format(t="120001", d="230394"))]
    first, second = fixes(stream)
    assert first.datetime == dt.datetime(1994, 3, 23, 12, 0, tzinfo=dt.timezone.utc)
    assert round(first.latitude, 6) == 48.1173 and round(first.longitude, 6) == 11.516667
    assert first.altitude_msl == 545.4 and round(first.altitude_hae, 6) == 592.3
    assert round(first.speed, 4) == round(22.4 * 0.514444, 4) and first.course == 84.4
    assert first.mode == "fix_3d" and first.used == {"gps": [4, 5, 9, 12, 24]} and first.pdop == 2.5
    assert first.sentences == ["GPRMC", "GPGGA", "GPGSA"]
    # the second epoch has no GGA nor GSA: nothing of them is carried over
    assert second.altitude_msl is None and second.used == {} and second.mode == "fix_2d"


def test_the_date_rolls_over_at_midnight() -> None:
    stream = [line(RMC.format(t="235959", d="311299")), line(GGA.format(t="000000"))]
    before, after = fixes(stream)
    assert before.date == dt.date(1999, 12, 31) and after.date == dt.date(2000, 1, 1)


def test_a_gsv_set_is_the_epochs_when_its_last_message_arrives() -> None:
    assembler = FixAssembler()
    assembler.feed(line(GGA.format(t="120000")))
    assembler.feed(line("GPGSV,2,1,05,01,40,083,46,02,17,308,41,12,07,344,39,14,22,228,45,1"))
    assembler.feed(line("GPGSV,2,2,05,32,10,100,,1"))
    assembler.feed(line("GLGSV,2,1,05,65,40,083,46,66,17,308,41,67,07,344,39,68,22,228,45,1"))
    fix = assembler.close()
    assert fix is not None
    assert [(s.system, s.id, s.signal) for s in fix.in_view][-1] == ("gps", 32, "signal_1")
    assert fix.in_view_count == 5  # the GLONASS set lacks its second message
    assert fix.in_view[0].snr == 46 and fix.in_view[-1].snr is None


def test_multi_constellation_gsa_by_system_id() -> None:
    stream = [line("GNGGA,120000,4807.038,N,01131.000,E,1,08,0.9,545.4,M,46.9,M,,"),
              line("GNGSA,A,3,01,02,,,,,,,,,,,1.0,0.5,0.8,1"),
              line("GNGSA,A,3,65,70,,,,,,,,,,,1.0,0.5,0.8,2")]
    (fix,) = fixes(stream)
    assert fix.used == {"gps": [1, 2], "glonass": [65, 70]} and fix.used_count == 4


def test_pubx_position_carries_the_same_facts() -> None:
    body = "PUBX,00,081350.00,4717.113210,N,00833.915187,E,546.589,G3,2.1,2.0,0.007,77.52,0.007,,0.92,1.19,0.77,9,0,0"
    (fix,) = fixes([line(body)])
    assert fix.mode == "fix_3d" and fix.altitude_hae == 546.589 and fix.horizontal_error == 2.1
    assert round(fix.speed, 6) == round(0.007 / 3.6, 6) and fix.satellites_used == 9
    assert fix.sentences == ["PUBX_POSITION"]
