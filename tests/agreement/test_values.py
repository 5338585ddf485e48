"""The value accessors of Python and C against generated/vectors/values.jsonl (the Rust crate's
tests/values.rs reads the same file): every number, coordinate, time, date, and date and time of
the manuals' examples plus edge cases, as doubles (compared exactly: the same bits), degrees x
10^7, milliseconds of the day, days since 1970 and milliseconds since 1970.

Python parses each value's text with the generated package's runtime; the C program
(tests/agreement/values.c, built here against generated/c/nmea.c) takes the parts its structs
hold and prints what the accessors give."""

from __future__ import annotations

import json
import os
import struct
import subprocess
import sys
from pathlib import Path
from typing import Any

import pytest

ROOT = Path(__file__).resolve().parents[2]
VECTORS = [json.loads(line) for line in (ROOT / "generated" / "vectors" / "values.jsonl").read_text().splitlines()]
sys.path.insert(0, str(ROOT / "generated" / "python"))

from nmeaspec import runtime as rt  # noqa: E402


def python_values(v: dict[str, Any]) -> dict[str, Any]:
    """What the Python runtime gives for the record's texts, in the record's terms."""
    kind = v["type"]
    if kind == "number":
        n = rt.parse_decimal(v["text"])
        return {"double": float(n), "float": struct.unpack("f", struct.pack("f", float(n)))[0], "int": int(n)}
    if kind in ("latitude", "longitude"):
        c = rt.parse_coordinate(v["text"], 2 if kind == "latitude" else 3, 90 if kind == "latitude" else 180)
        c = rt.Coordinate(c.degrees, c.minutes, v["hemisphere"], c.degree_digits)
        return {"degrees": float(c), "e7": c.degrees_e7()}
    if kind == "time":
        return {"ms": rt.parse_time(v["text"]).ms_of_day()}
    if kind == "date":
        d = rt.parse_date(v["text"])
        try:
            days: int | None = d.days_since_epoch()
        except ValueError:
            days = None
        return {"full_year": d.full_year, "days": days}
    if kind == "datetime":
        when = rt.utc_datetime(rt.parse_date(v["date"]), rt.parse_time(v["time"]))
        return {"ms": None if when is None else int(when.timestamp()) * 1000 + when.microsecond // 1000}
    year, month, day = (rt.Number.of(v[k]) for k in ("year", "month", "day"))
    when = rt.utc_datetime_of(year, month, day, rt.Time(0, 0, 0))
    return {"days": None if when is None else int(when.timestamp()) // 86400}


def expected(v: dict[str, Any], keys: tuple[str, ...]) -> dict[str, Any]:
    """The record's values, doubles read from their text."""
    return {k: float(v[k]) if k in ("double", "float", "degrees") else v[k] for k in keys}


def test_python_gives_the_vectors_values() -> None:
    wrong = []
    for v in VECTORS:
        got = python_values(v)
        if got != expected(v, tuple(got)):
            wrong.append((v, got))
    assert not wrong, wrong[:5]


def c_input(v: dict[str, Any]) -> str:
    """The record as the C program reads it: its kind and the parts of its value."""
    kind = v["type"]
    if kind == "number":
        return f"number {v['digits']} {v['scale']} {int(v['negative'])}"
    if kind in ("latitude", "longitude"):
        return f"coordinate {v['deg']} {v['minutes_digits']} {v['minutes_scale']} {ord(v['hemisphere'])}"
    if kind == "time":
        return f"time {v['hour']} {v['minute']} {v['second']} {v['fraction']} {v['fraction_digits']}"
    if kind == "date":
        return f"date {v['day']} {v['month']} {v['year']}"
    if kind == "datetime":
        d, t = rt.parse_date(v["date"]), rt.parse_time(v["time"])
        return (f"datetime {d.day} {d.month} {d.year} {t.hour} {t.minute} {t.second} {t.fraction} "
                f"{t.fraction_digits}")
    return f"civil {v['year']} {v['month']} {v['day']}"


def c_values(v: dict[str, Any], out: str) -> dict[str, Any]:
    """The C program's line for a record, in the record's terms ("-": false, None)."""
    words: list[Any] = [None if w == "-" else w for w in out.split()]
    kind = v["type"]
    if kind == "number":
        return {"double": float(words[0]), "float": float(words[1])}
    if kind in ("latitude", "longitude"):
        return {"e7": int(words[0])}
    if kind == "date":
        return {"full_year": int(words[0]), "days": None if words[1] is None else int(words[1])}
    key = "days" if kind == "civil" else "ms"
    return {key: None if words[0] is None else int(words[0])}


@pytest.fixture(scope="module")
def c_program(tmp_path_factory: pytest.TempPathFactory) -> Path:
    exe = tmp_path_factory.mktemp("values") / "values"
    cc = os.environ.get("CC", "cc")
    # NMEA_C_OBJECT: nmea.c compiled already (make test-tools links the tools' test object).
    pair = os.environ.get("NMEA_C_OBJECT") or str(ROOT / "generated" / "c" / "nmea.c")
    subprocess.run([cc, "-std=c99", "-Wall", "-Wextra", "-Werror", "-pedantic", "-O0",
                    "-I", str(ROOT / "generated" / "c"), "-o", str(exe),
                    str(Path(__file__).with_name("values.c")), pair], check=True)
    return exe


def test_c_gives_the_vectors_values(c_program: Path) -> None:
    data = "".join(c_input(v) + "\n" for v in VECTORS)
    lines = subprocess.run([str(c_program)], input=data, capture_output=True, text=True, check=True).stdout.splitlines()
    assert len(lines) == len(VECTORS)
    wrong = []
    for v, line in zip(VECTORS, lines):
        got = c_values(v, line)
        if got != expected(v, tuple(got)):
            wrong.append((v, got))
    assert not wrong, wrong[:5]
