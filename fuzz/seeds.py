"""Seed corpus for the fuzzers: every example of the manuals (intact and damaged), the edge
cases, a sample of every real log and of gpsd's AIS samples (with whole messages of several
sentences and the assembly cases), stretches of gpsd's logs that mix NMEA with UBX and RTCM 3
frames, random sentences of every layout, decode's JSON of some
of them (the fuzz targets also read their input as JSON), and the corpus the last campaign grew
(fuzz/corpus.tar.xz, minimized), so that each run starts where the last one stopped. One file
per input, no line ending.

Usage: python fuzz/seeds.py OUT_DIR [--no-corpus]   (--no-corpus: without the campaign's corpus,
for the short run of make test)
"""

from __future__ import annotations

import hashlib
import json
import sys
import tarfile
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from generator import reference  # noqa: E402
from generator.build import load_spec  # noqa: E402
from tests.agreement.random_sentences import random_lines  # noqa: E402

CORPUS = ROOT.parent / "shared" / "corpus" / "real"
PER_LOG = 40


def seeds(with_corpus: bool = True) -> list[bytes]:
    spec = load_spec(ROOT / "spec")
    lines: list[str] = []
    for record in map(json.loads, (ROOT / "generated" / "vectors" / "examples.jsonl").read_text().splitlines()):
        lines.append(record["raw"])
        if record["line"]:
            lines.append(record["line"])
    lines += [s for _, _, s in random_lines(spec, 2, seed=99)]
    # A line holds bytes as characters up to U+00FF; a manual's text with a character beyond (a
    # Unicode minus) is its UTF-8 bytes, as the tools read it.
    out = [line.encode("latin-1") if max(map(ord, line), default=0) < 256 else line.encode() for line in lines]
    out += [line.rstrip(b"\r") for line in (ROOT / "tests" / "agreement" / "edge_cases.txt").read_bytes().split(b"\n")]
    for path in sorted(CORPUS.rglob("*.nmea")):
        logged = [line.rstrip(b"\r") for line in path.read_bytes().split(b"\n") if line]
        step = max(1, len(logged) // PER_LOG)
        out += logged[::step][:PER_LOG]
    out += ais_seeds()
    out += binary_seeds()
    out += [reference.decode_json(spec, line).encode() for line in lines[:400]]
    out += sorted(p.read_bytes() for p in (ROOT / "fuzz" / "regressions").glob("*") if p.is_file())
    if with_corpus:
        out += campaign_corpus()
    return [s for s in dict.fromkeys(out) if s]


def ais_seeds() -> list[bytes]:
    """A sample of gpsd's AIS sentences (tests/data/ais), the messages of several sentences among
    them whole (their lines joined), and the lines of each shared assembly case, for the
    assemblers."""
    ais = ROOT / "tests" / "data" / "ais"
    out: list[bytes] = []
    for path in sorted(ais.glob("*.chk")) + [ais / "sample.aivdm"]:
        logged = [line.rstrip(b"\r") for line in path.read_bytes().split(b"\n") if line.startswith(b"!")]
        out += logged[::max(1, len(logged) // PER_LOG)][:PER_LOG]
        firsts = [i for i, line in enumerate(logged) if line.split(b",")[1:3] == [b"2", b"1"]]
        out += [b"\n".join(logged[i:i + 2]) for i in firsts[:PER_LOG // 4]]
    cases = (json.loads(line) for line in (ais / "assembly_cases.jsonl").read_text().splitlines())
    out += ["\n".join(case["lines"]).encode("latin-1") for case in cases]
    return out


def binary_seeds() -> list[bytes]:
    """Stretches of gpsd's logs that interleave NMEA with binary frames (tests/data/ubx, rtcm3,
    skytraq, sirf, casic, sbf), up to a fuzz input's length, for the stream framers."""
    out: list[bytes] = []
    for path in [log for name in ("ubx", "rtcm3", "skytraq", "sirf", "casic", "sbf")
                 for log in sorted((ROOT / "tests" / "data" / name).glob("*.log"))
                 + sorted((ROOT / "tests" / "data" / name).glob("*.sbf"))]:
        data = path.read_bytes()
        step = max(1000, len(data) // PER_LOG)
        out += [data[at:at + 1000] for at in range(0, len(data), step)]
    return out


def campaign_corpus() -> list[bytes]:
    """The inputs of fuzz/corpus.tar.xz (written by fuzz/keep_corpus.py after a campaign)."""
    path = ROOT / "fuzz" / "corpus.tar.xz"
    if not path.is_file():
        return []
    with tarfile.open(path) as archive:
        return [archive.extractfile(m).read() for m in sorted(archive.getmembers(), key=lambda m: m.name)
                if m.isfile()]


def main() -> None:
    target = Path(sys.argv[1])
    target.mkdir(parents=True, exist_ok=True)
    for seed in seeds(with_corpus="--no-corpus" not in sys.argv[2:]):
        (target / hashlib.sha1(seed).hexdigest()).write_bytes(seed)


if __name__ == "__main__":
    main()
