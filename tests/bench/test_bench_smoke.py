"""The benchmark harness at a tiny size: our implementations only (no peers, nothing fetched), one
round over 2,000 lines, the Rust driver built with the standard sentences only (the crate's
tests build the rest), the C driver unoptimized and linked with make test's test object of nmea.c
when there is one (NMEA_C_OBJECT). Checks the shape of results.json and that every
line parses and comes back byte for byte; the timings of so small a run mean nothing."""

import json
import os
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
OUT = ROOT / "build" / "bench-smoke"
LINES = 2000
OURS = {"ours-c": "c", "ours-rust": "rust", "ours-python": "python"}
OPS = ("parse", "serialize", "roundtrip")
AIS = {"ours-c-ais": "c", "ours-rust-ais": "rust", "ours-python-ais": "python"}  # over the AIS corpus
AIS_ROWS = {("ours-c-ais", "parse"), ("ours-rust-ais", "parse"), ("ours-python-ais", "parse"), ("ours-python-ais", "serialize")}
UBX_ROWS = {("ours-c-ubx", "parse"), ("ours-rust-ubx", "parse"), ("ours-python-ubx", "parse")}  # a frame a line
STREAM_ROWS = {("ours-c-stream", "frame"), ("ours-c-stream-nmea", "frame")}  # the C framer: mixed log, NMEA corpus
FIXES = set(OURS)  # each has a fix assembler: a `fixes` row (parse and assemble every line) each


def test_bench_smoke():
    compiled = ["--c-object", os.environ["NMEA_C_OBJECT"]] if os.environ.get("NMEA_C_OBJECT") else []
    subprocess.run([sys.executable, "bench/run.py", "--lines", str(LINES), "--rounds", "1", "--no-peers",
                    "--no-docs", "--no-memory", "--no-instructions", "--cargo-profile", "smoke", "--c-optimization=-O0",
                    "--standard-only", *compiled,
                    "--out", str(OUT)],
                   cwd=ROOT, check=True, stdout=subprocess.DEVNULL)
    report = json.loads((OUT / "results.json").read_text())
    assert report["corpus"]["lines"] == LINES
    assert report["corpus"]["bytes"] == (OUT / "corpus.nmea").stat().st_size
    rows = {(r["name"], r["op"]): r for r in report["results"]}
    expected = {(name, op) for name in OURS for op in OPS} | {("ceiling-c", "parse")}
    expected |= {(name, "fixes") for name in FIXES}
    expected |= AIS_ROWS | UBX_ROWS | STREAM_ROWS
    assert set(rows) == expected
    for (name, op), row in rows.items():
        assert set(row) >= {"name", "lang", "op", "corpus", "ns_per_line", "ok_lines"}
        assert row["lang"] == {**OURS, **AIS, "ours-rust-ubx": "rust", "ours-python-ubx": "python"}.get(name, "c")
        assert row["ns_per_line"] > 0
        assert row["corpus"] == ("ais" if name in AIS else "ubx" if (name, op) in UBX_ROWS
                                 else "mixed" if name == "ours-c-stream" else "nmea")
        if name not in AIS and (name, op) not in STREAM_ROWS:
            # every corpus line (UBX: frame) parses and, serialized, is the input byte for byte
            assert row["ok_lines"] == LINES, (name, op)
    # Every AIS line whose message decodes is written back byte for byte (a few real payloads are
    # shorter than their type's layout: ours refuses them).
    decoded = rows[("ours-python-ais", "parse")]["ok_lines"]
    assert LINES * 0.99 < decoded == rows[("ours-python-ais", "serialize")]["ok_lines"]
    assert rows[("ours-c-ais", "parse")]["ok_lines"] == rows[("ours-rust-ais", "parse")]["ok_lines"] == decoded
    assert rows[("ours-rust-ais", "parse")]["allocations"] == 0
    assert rows[("ours-rust-ubx", "parse")]["allocations"] == 0
    # The framer: the NMEA corpus is its lines, every one kept; the mixed log holds lines and UBX and
    # RTCM 3 frames, each counted as a line or a frame (a few damaged ones rejected).
    nmea_alone, mixed = rows[("ours-c-stream-nmea", "frame")], rows[("ours-c-stream", "frame")]
    assert nmea_alone["ok_lines"] == nmea_alone["text_lines"] == LINES and nmea_alone["frames"] == 0
    assert nmea_alone["bytes"] == report["corpus"]["bytes"] and mixed["bytes"] == report["mixed_corpus"]["bytes"]
    assert mixed["frames"] >= report["mixed_corpus"]["ubx_frames"] > 0 and mixed["text_lines"] > 0
    assert mixed["ok_lines"] == mixed["text_lines"] + mixed["frames"] and mixed["ns_per_byte"] > 0
    assert report["ais_corpus"]["bytes"] == (OUT / "corpus-ais.nmea").stat().st_size
    assert report["ubx_corpus"]["frames"] == LINES and report["ubx_corpus"]["distinct_frames"] > 100
    for op in OPS:
        assert rows[("ours-rust", op)]["allocations"] == 0
        assert set(rows[("ours-c", op)]["by_type"]) <= {"GGA", "RMC", "GSV", "GSA", "VTG", "GLL", "ZDA", "GST"}
    assert report["c_object"]["heap"] == []
    assert report["struct_sizes"]["nmea_sentence"] > 0
    assert (OUT / "results.md").read_text().startswith("Corpus: 2,000 lines")
