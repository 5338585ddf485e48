"""Decode rates on the real receiver logs in ../shared/corpus/real.

For every file: how many lines have a valid checksum, how many of those are sentences the spec
describes, and how many of these decode. Every one that does not decode must be explained in
corpus_exceptions.yaml (file, line, reason); an explanation that no longer applies fails too, so
the list stays true. The per-file table is printed at the end of the run and written to
build/reports/corpus.md."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
import yaml

from generator import reference
from generator.build import load_spec

from .test_agreement import CORPUS, CORPUS_FILES, ROOT, corpus, decode_all, input_lines

EXCEPTIONS = Path(__file__).with_name("corpus_exceptions.yaml")
REPORT = ROOT / "build" / "reports" / "corpus.md"
RATES: list[tuple[str, int, int, int, int]] = []


def _checksum_valid(line: bytes) -> bool:
    star = line.find(b"*")
    if line[:1] not in (b"$", b"!") or star < 0 or len(line) != star + 3:
        return False
    try:
        value = int(line[star + 1:], 16)
    except ValueError:
        return False
    check = 0
    for byte in line[1:star]:
        check ^= byte
    return check == value and all(0x20 <= b <= 0x7E for b in line)


@pytest.fixture(scope="module")
def spec():
    return load_spec(ROOT / "spec")


def _known(spec, line: bytes) -> bool:
    try:
        return bool(reference.candidates(spec, line.decode("latin-1"))[1])
    except reference.rt.NmeaError:
        return False


def test_corpus_decode_rates(spec) -> None:
    expected = yaml.safe_load(EXCEPTIONS.read_text()) or []
    explained = {(e["file"], e["line"]) for e in expected}
    unexplained, failing = [], set()
    logs = corpus()
    decoded = logs.lines_of(decode_all(logs.data, False, logs.origin))
    for path in CORPUS_FILES:
        name = str(path.relative_to(CORPUS))
        lines = input_lines(path.read_bytes())
        outputs = decoded[name]
        valid = known = ok = 0
        for line, out in zip(lines, outputs):
            if not _checksum_valid(line):
                continue
            valid += 1
            if not _known(spec, line):
                continue
            known += 1
            if json.loads(out)["ok"]:
                ok += 1
                continue
            text = line.decode("latin-1")
            failing.add((name, text))
            if (name, text) not in explained:
                unexplained.append(f"{name}: {text}\n    {out.decode()}")
        RATES.append((name, len(lines), valid, known, ok))
    REPORT.parent.mkdir(parents=True, exist_ok=True)
    REPORT.write_text(report())
    stale = sorted(explained - failing)
    assert not unexplained, "checksum-valid lines of known sentences that do not decode:\n" + "\n".join(unexplained)
    assert not stale, f"corpus_exceptions.yaml explains lines that now decode: {stale}"


def report() -> str:
    rows = ["| file | lines | checksum valid | known sentences | decoded | rate |", "| --- | ---: | ---: | ---: | ---: | ---: |"]
    total = [0, 0, 0, 0]
    for name, lines, valid, known, ok in RATES:
        rate = f"{100.0 * ok / known:.1f}%" if known else "-"
        rows.append(f"| {name} | {lines} | {valid} | {known} | {ok} | {rate} |")
        for i, v in enumerate((lines, valid, known, ok)):
            total[i] += v
    rate = f"{100.0 * total[3] / total[2]:.2f}%" if total[2] else "-"
    rows.append(f"| all | {total[0]} | {total[1]} | {total[2]} | {total[3]} | {rate} |")
    return "\n".join(rows) + "\n"
