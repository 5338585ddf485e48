"""A start sent twice: an ST Teseo LIV4F sends `$$GNGSA,...*3E`, whose checksum is that of the
sentence from its last `$`. parse() reads that sentence and keeps the stray `$` before it (in a
Tagged, as TAG blocks are kept), so the line writes back byte for byte; the tools' JSON says so
in `"stray"` (runtime/json.md), the same in the three languages (tests/agreement's edge cases)."""

from __future__ import annotations

import json
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "generated" / "python"))

import nmeaspec  # noqa: E402
from nmeaspec.runtime import checksum  # noqa: E402
from nmeaspec.sentences import Gsa, Vtg  # noqa: E402

LOG = ROOT / "tests" / "data" / "gpsd_logs" / "st-teseo-liv4f.log"


def test_the_sentence_after_a_stray_start() -> None:
    line = "$$GNGSA,A,3,44,34,25,11,19,23,38,,,,,,2.5,1.7,1.8,4*3E"
    parsed = nmeaspec.parse(line + "\r\n")
    assert isinstance(parsed, nmeaspec.Tagged) and parsed.stray == "$" and parsed.tag_blocks == ()
    gsa = parsed.sentence
    assert isinstance(gsa, Gsa) and gsa.talker == "GN" and [int(p) for p in gsa.prns if p] == [44, 34, 25, 11, 19, 23, 38]
    assert parsed.to_sentence() == line and parsed.to_bytes() == (line + "\r\n").encode()
    assert parsed.to_dict()["stray"] == "$" and parsed.to_dict()["hdop"] == 1.7
    decoded = json.loads(nmeaspec.to_json(parsed))
    assert decoded["stray"] == "$" and "tag_blocks" not in decoded and decoded["checksum"] == "3E"
    assert nmeaspec.from_json(decoded).to_sentence() == line


def test_more_stray_starts_and_tag_blocks_before_them() -> None:
    tagged = nmeaspec.parse("\\s:r003669945,c:1241544035*79\\$$$GNVTG,120.9,T,,M,0.5,N,0.8,K,A*14")
    assert tagged.stray == "$$" and [b.source for b in tagged.tag_blocks] == ["r003669945"]
    assert isinstance(tagged.sentence, Vtg)
    assert tagged.to_sentence() == "\\s:r003669945,c:1241544035*79\\$$$GNVTG,120.9,T,,M,0.5,N,0.8,K,A*14"
    assert json.loads(nmeaspec.to_json(tagged))["stray"] == "$$"


@pytest.mark.parametrize("line, kind", [
    ("$$GNVTG,120.9,T,,M,0.5,N,0.8,K,A*15", "checksum_mismatch"),  # the sentence's own checksum
    ("$$", "not_a_sentence"),
    ("$$GN\x01VTG", "not_a_sentence"),
    ("$$" + "A" * 2000, "too_long"),
])
def test_what_a_stray_start_does_not_excuse(line: str, kind: str) -> None:
    with pytest.raises(nmeaspec.NmeaError) as caught:
        nmeaspec.parse(line)
    assert caught.value.kind == kind


def test_every_line_of_the_teseo_log_is_read() -> None:
    """Typed but for the 20 antenna status lines, whose layout no public document gives (the
    spec's generic list); the one line whose checksum fails (a GSV of the log) is refused."""
    lines = [raw.decode("ascii") for raw in LOG.read_bytes().splitlines() if raw.startswith(b"$$")]
    assert len(lines) == 330
    generic = []
    for line in lines:
        body, sent = line[2:].split("*")
        if checksum(body) != int(sent, 16):
            with pytest.raises(nmeaspec.NmeaError, match="checksum_mismatch"):
                nmeaspec.parse(line)
            continue
        parsed = nmeaspec.parse(line)
        assert parsed.stray == "$" and parsed.to_sentence() == line, line
        if isinstance(parsed.sentence, nmeaspec.Generic):
            generic.append(parsed.sentence.address)
    assert generic == ["PSTMANTENNASTATUS"] * 20


@pytest.mark.parametrize("obj, message", [
    ({"ok": True, "stray": "$"}, '"stray" without a sentence'),
    ({"ok": True, "stray": "$x", "start": "$", "address": "XYZAB", "talker": None, "sentence": None,
      "variant": None, "fields": ["1"], "checksum": "45"}, '"stray" is not one or more "$"'),
])
def test_json_stray_must_be_starts_before_a_sentence(obj: dict, message: str) -> None:
    with pytest.raises(nmeaspec.NmeaError) as caught:
        nmeaspec.from_json(obj)
    assert caught.value.kind == "bad_json" and message in str(caught.value)
