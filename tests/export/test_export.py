"""`nmea export`: logs as Parquet tables (nmeaspec.apps.export), read back with pyarrow and
compared with what the package itself decodes from the same lines."""

from __future__ import annotations

import datetime as dt
import json
import math
import sys
from pathlib import Path
from typing import Any

import pytest

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "generated" / "python"))

import pyarrow as pa  # noqa: E402
import pyarrow.parquet as pq  # noqa: E402

import nmeaspec  # noqa: E402
from nmeaspec import ais, sentences  # noqa: E402
from nmeaspec.ais_messages import BY_TYPE, decode_payload  # noqa: E402
from nmeaspec.apps import export  # noqa: E402
from nmeaspec.apps.nmea_cli import main  # noqa: E402
from nmeaspec.assembly import MessageAssembler  # noqa: E402
from nmeaspec.fixes import carries_facts, fixes  # noqa: E402

CORPUS = ROOT.parent / "shared" / "corpus" / "real"
LOG = CORPUS / "gpsd" / "ublox-neo-m9n-nmea.nmea"  # GN RMC/VTG/GGA/GSA/GSV/GLL/GST/ZDA, NMEA 4.11
VECTORS = ROOT / "generated" / "vectors"


def lines_of(path: Path) -> list[str]:
    return [line for line in path.read_text(encoding="latin-1").splitlines() if line]


@pytest.fixture(scope="module")
def tables(tmp_path_factory: pytest.TempPathFactory) -> Path:
    out = tmp_path_factory.mktemp("tables")
    assert main(["export", "-q", str(LOG), "-o", str(out)]) == 0
    return out


def test_the_tables_of_a_log(tables: Path) -> None:
    names = sorted(p.stem for p in tables.glob("*.parquet"))
    decoded = [nmeaspec.parse(line) for line in lines_of(LOG)]
    assert names == sorted({s.SENTENCE for s in decoded}) + ["fixes"]
    assert names == ["GBS", "GGA", "GLL", "GSA", "GST", "GSV", "RMC", "VTG", "ZDA", "fixes"]
    for name in names[:-1]:
        table = pq.read_table(tables / f"{name}.parquet")
        assert table.schema == export.schema(pa, name)
        assert table.num_rows == sum(1 for s in decoded if s.SENTENCE == name)


def test_sentence_rows_are_the_sentences_values(tables: Path) -> None:
    table = pq.read_table(tables / "GGA.parquet").to_pylist()
    gga = [(n, s) for n, s in enumerate((nmeaspec.parse(line) for line in lines_of(LOG)), 1) if s.SENTENCE == "GGA"]
    assert len(table) == len(gga) == 61
    for row, (number, sentence) in zip(table, gga):
        assert row["log"] == LOG.name and row["line"] == number and row["talker"] == sentence.talker
        assert row["time"] == sentence.time.to_time().replace(tzinfo=None)
        assert row["lat"] == float(sentence.lat) and row["lon"] == float(sentence.lon)
        assert row["altitude"] == float(sentence.altitude) and row["satellites"] == int(sentence.satellites)
        assert row["quality"] == sentence.quality.id and row["variant"] is None and row["problems"] == []
    first = table[0]
    assert (first["time"], first["lat"], first["altitude"]) == (dt.time(22, 37, 45), pytest.approx(38.110494, abs=1e-6), 83.1)
    gsv = pq.read_table(tables / "GSV.parquet")
    assert gsv.schema.field("satellites").type == pa.list_(pa.struct(
        [("prn", pa.int64()), ("elevation", pa.int64()), ("azimuth", pa.int64()), ("snr", pa.int64())]))
    assert gsv.schema.field("signal_id").type == pa.string()


def test_fix_rows_are_the_fixes(tables: Path) -> None:
    rows = pq.read_table(tables / "fixes.parquet").to_pylist()
    expected = list(fixes(lines_of(LOG)))
    assert len(rows) == len(expected) == 61
    for row, fix in zip(rows, expected):
        assert row["datetime"] == fix.datetime and row["time"] == fix.time and row["date"] == fix.date
        for name in ("latitude", "longitude", "altitude_msl", "speed", "hdop", "mode", "fix_quality",
                     "satellites_used", "sentences"):
            assert row[name] == getattr(fix, name), name
        assert row["used_count"] == fix.used_count and row["in_view_count"] == fix.in_view_count
        assert row["used"] == [{"system": s, "id": i} for s, ids in fix.used.items() for i in ids]
        assert [(s["system"], s["id"], s["signal"], s["snr"]) for s in row["in_view"]] == \
            [(s.system, s.id, s.signal, s.snr) for s in fix.in_view]
    # each epoch's lines: from its first sentence to its last, one after the other
    assert rows[0]["first_line"] == 1 and all(r["first_line"] <= r["last_line"] for r in rows)
    assert all(a["last_line"] < b["first_line"] for a, b in zip(rows, rows[1:]))
    carrying = [n for n, line in enumerate(lines_of(LOG), 1) if carries_facts(nmeaspec.parse(line))]
    assert rows[-1]["last_line"] == carrying[-1] and len(carrying) < len(lines_of(LOG))  # GBS: no fact


def test_unknown_sentences_and_errors_are_tables(tmp_path: Path) -> None:
    log = tmp_path / "mixed.nmea"
    log.write_bytes(b"$GPGGA,075140.00,5550.613522,N,03732.251556,E,2,22,0.5,00188.862,M,0014.4,M,001.0,0000*4F\r\n"
                    + _with_checksum("$PXYZ,1,2").encode() + b"\r\n$GPGGA,1*00\r\nnot a sentence\r\n")
    assert main(["export", "-q", str(log), "-o", str(tmp_path / "out")]) == 0
    unknown = pq.read_table(tmp_path / "out" / "unknown.parquet").to_pylist()
    assert unknown == [{"log": "mixed.nmea", "line": 2, "address": "PXYZ", "fields": ["1", "2"]}]
    errors = pq.read_table(tmp_path / "out" / "errors.parquet").to_pylist()
    assert [(e["line"], e["kind"], e["text"]) for e in errors] == \
        [(3, "checksum_mismatch", "$GPGGA,1*00"), (4, "not_a_sentence", "not a sentence")]
    assert errors[0]["message"].startswith("checksum_mismatch: ")


def test_out_of_range_values_are_kept_with_their_problem(tmp_path: Path) -> None:
    log = tmp_path / "low.nmea"  # an elevation outside -90..90, kept as sent and flagged
    log.write_text(_with_checksum("$GPGSV,1,1,01,05,-92,120,30") + "\r\n")
    assert main(["export", "-q", str(log), "-o", str(tmp_path / "out")]) == 0
    (row,) = pq.read_table(tmp_path / "out" / "GSV.parquet").to_pylist()
    assert row["satellites"][0]["elevation"] == -92
    assert [(p["kind"], p["field"]) for p in row["problems"]] == [("out_of_range", "satellites[1].elevation")]


def _with_checksum(body: str) -> str:
    return f"{body}*{nmeaspec.runtime.checksum(body[1:]):02X}"


def test_every_sentence_of_the_spec_has_a_table_schema() -> None:
    """The columns come from the spec: every sentence id makes a schema without a column two
    layouts type differently."""
    ids = sorted(sentences._MODULES)
    assert len(ids) > 600
    for name in ids:
        table_schema = export.schema(pa, name)
        assert table_schema.names[:2] == ["log", "line"] and table_schema.names[-1] == "problems"


def test_every_example_of_the_manuals_fits_its_schema() -> None:
    """The plain values of every field type fit the column type its runtime class declares."""
    seen: dict[str, list[dict[str, Any]]] = {}
    for record in map(json.loads, (VECTORS / "examples.jsonl").read_text(encoding="utf-8").splitlines()):
        if not record.get("checksum_ok", True) or record.get("line") is None:
            continue
        try:
            sentence = nmeaspec.parse(record["line"])
        except nmeaspec.NmeaError:
            continue
        if isinstance(sentence, nmeaspec.Tagged):
            sentence = sentence.sentence
        if sentence is None or isinstance(sentence, nmeaspec.Generic):
            continue
        seen.setdefault(sentence.SENTENCE, []).append(export._sentence_row(sentence, "examples", 1))
    assert len(seen) > 500
    for name, table_rows in seen.items():
        table = pa.Table.from_pylist(table_rows, schema=export.schema(pa, name))
        assert table.num_rows == len(table_rows)
        back = table.to_pylist()
        for got, want in zip(back, table_rows):  # no value changed on its way into Arrow
            assert _same(got, want), (name, got, want)


def _same(a: Any, b: Any) -> bool:
    if isinstance(b, dict):
        return all(_same(a.get(k), v) for k, v in b.items())
    if isinstance(b, list):
        return len(a) == len(b) and all(_same(x, y) for x, y in zip(a, b))
    if isinstance(b, dt.time) and b.tzinfo is not None:  # time64 has no zone: the column is UTC
        return bool(a == b.replace(tzinfo=None))
    if isinstance(b, float):
        return a == b or (math.isnan(a) and math.isnan(b))
    return bool(a == b)


def test_separate_exports_concatenate(tmp_path: Path) -> None:
    logs = sorted((CORPUS / "gpsd").glob("*.nmea"))[:6]
    for n, log in enumerate(logs):
        assert main(["export", "-q", str(log), "-o", str(tmp_path / f"part-{n}")]) == 0
    for name in ("fixes", "GGA", "RMC"):
        parts = [pq.read_table(p) for p in sorted(tmp_path.glob(f"part-*/{name}.parquet"))]
        assert len(parts) >= 2, name
        whole = pa.concat_tables(parts)  # one schema: it raises otherwise
        assert whole.num_rows == sum(p.num_rows for p in parts)
    assert main(["export", "-q", *map(str, logs), "-o", str(tmp_path / "all")]) == 0
    together = pq.read_table(tmp_path / "all" / "fixes.parquet")
    apart = pa.concat_tables([pq.read_table(p) for p in sorted(tmp_path.glob("part-*/fixes.parquet"))])
    assert together.to_pylist() == apart.to_pylist()


def test_rows_are_written_a_row_group_at_a_time(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    whole = tmp_path / "whole"
    assert main(["export", "-q", str(LOG), "-o", str(whole)]) == 0
    monkeypatch.setattr(export, "ROW_GROUP", 16)
    monkeypatch.setattr(export, "BUFFERED", 40)
    small = tmp_path / "small"
    assert main(["export", "-q", str(LOG), "-o", str(small)]) == 0
    assert pq.ParquetFile(small / "GSV.parquet").metadata.num_row_groups > 10
    assert pq.ParquetFile(small / "GGA.parquet").metadata.num_row_groups > 3
    for path in whole.glob("*.parquet"):
        assert pq.read_table(small / path.name).to_pylist() == pq.read_table(path).to_pylist(), path.name


def test_only_some_tables(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["export", "--only", "fixes,GGA", str(LOG), "-o", str(tmp_path)]) == 0
    assert sorted(p.name for p in tmp_path.iterdir()) == ["GGA.parquet", "fixes.parquet"]
    assert capsys.readouterr().err == f"wrote 2 tables to {tmp_path}: GGA 61, fixes 61\n"


def test_mistakes(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["export", str(tmp_path / "nowhere.nmea"), "-o", str(tmp_path / "out")]) == 2
    assert capsys.readouterr().err == f"nmea: cannot read {tmp_path / 'nowhere.nmea'}: No such file or directory\n"
    assert not (tmp_path / "out").exists()
    with pytest.raises(SystemExit):
        main(["export", str(LOG)])  # no -o
    assert "-o/--output" in capsys.readouterr().err


AIS_LOG = CORPUS / "gpsd" / "ais-nmea.nmea"  # AIVDM of 30 ships in a Dutch harbour, type 5 in two sentences


def test_ais_messages_are_tables_of_their_kind(tmp_path: Path) -> None:
    assert main(["export", "-q", str(AIS_LOG), "-o", str(tmp_path)]) == 0
    decoded: dict[str, list[tuple[int, Any]]] = {}
    assembler = MessageAssembler()
    for number, line in enumerate(lines_of(AIS_LOG), 1):
        for done in assembler.feed(nmeaspec.parse(line)):
            if done.message is not None:
                decoded.setdefault(f"ais_{done.message.ID}", []).append((number, done.message))
    assert sorted(p.stem for p in tmp_path.glob("ais_*.parquet")) == sorted(decoded)
    assert "ais_static_voyage_data" in decoded  # assembled from two sentences each
    for table, messages in decoded.items():
        rows = pq.read_table(tmp_path / f"{table}.parquet").to_pylist()
        assert [(r["line"], r["mmsi"], r["message_type"]) for r in rows] == \
            [(n, m.mmsi, m.message_type) for n, m in messages], table
    report = pq.read_table(tmp_path / "ais_position_report.parquet").to_pylist()
    for row, (_, message) in zip(report, decoded["ais_position_report"]):
        for name in ("lon", "lat", "speed", "course", "heading", "turn"):
            value = getattr(message, name)
            if isinstance(value, ais.Special):  # "not available" is said as such, never a number
                assert (row[name], row[f"{name}_special"], row[f"{name}_raw"]) == (None, value.id, value.raw)
            else:
                assert row[name] == value and row[f"{name}_special"] is None
        assert row["status"] == (message.status.name.lower() if message.status is not None else None)
    voyage = pq.read_table(tmp_path / "ais_static_voyage_data.parquet").to_pylist()
    assert any(r["shipname"].rstrip("@ ") == "TIJMA" for r in voyage)  # text as sent, padding kept


def test_every_ais_vector_fits_its_kinds_schema() -> None:
    """The columns of every AIS message kind come from its layout: each decoded vector of
    generated/vectors/ais.jsonl makes a row of its table's schema, unchanged through Arrow."""
    kinds = {cls.ID for cls in BY_TYPE.values()}
    for kind in kinds:
        assert export.schema(pa, f"ais_{kind}").names[:2] == ["log", "line"]
    seen = set()
    for record in map(json.loads, (VECTORS / "ais.jsonl").read_text(encoding="utf-8").splitlines()):
        if "decode" not in record:  # a vector of a payload that decodes to an error
            continue
        message = decode_payload(record["payload"], record["fill_bits"])
        row = export._ais_row(message, "vectors", 1)
        table = pa.Table.from_pylist([row.values], schema=export.schema(pa, row.table))
        assert _same(table.to_pylist()[0], row.values), record["where"]
        seen.add(message.ID)
    assert seen == kinds
