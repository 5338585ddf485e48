"""Which layout of an address with keywords claims a line when none of its keywords is there: a
layout without a keyword claims it only when the line's first field reads as that layout's
first field (a number outside its range does; a layout without fields: when the line has none).
Otherwise the line is a message of the family the spec does not know, kept as a Generic
sentence, not refused: an Ashtech `$PASHR,<keyword>,...` the spec does not know beside RT300's keyword-less
`$PASHR,<time>,...`. The three languages agree on these lines (tests/agreement/edge_cases.txt)."""

from __future__ import annotations

import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "generated" / "python"))

import nmeaspec  # noqa: E402
from nmeaspec.runtime import checksum  # noqa: E402


def line(body: str) -> str:
    return f"${body}*{checksum(body):02X}"


@pytest.mark.parametrize("body, sentence", [
    ("PASHR,123519.00,1.0,T,2.0,3.0,,0.1,0.1,0.1,1,2", "PASHR"),          # RT300: a time first
    ("PASHR,,1.0,T,2.0,3.0,,0.1,0.1,0.1,1,2", "PASHR"),                   # an empty field reads
    ("PASHR,BTS,C,1,btsdev1,hs-344-fg,87,H,1,btsdev2,pc-377xs,68,T,0,,,", "PASHR_BTS"),  # a keyword
    ("PASHR,QQQ,C,1,btsdev1,hs-344-fg,87,H,1,btsdev2,pc-377xs,68,T,0,,,", None),  # no keyword known
    ("PASHR,12X519.00,1.0,T", None),
    ("PQTMDEBUGOFF", "PQTMDEBUGOFF"),                                    # no fields, as its layout
    ("PQTMDEBUGOFF,OK", "PQTMDEBUGOFF_RESULT"),                           # the reply's keyword
    ("PQTMDEBUGOFF,FOO", None),
    ("PMTK314,0,1,0,1,1,5,0,0,0,0,0,0,0,0,0,0,0,0,0", "PMTK314"),
    ("PMTK314,X", None),
    ("PTNLRIO,Q", None),
])
def test_the_claim(body: str, sentence: str | None) -> None:
    parsed = nmeaspec.parse(line(body))
    if sentence is None:
        assert isinstance(parsed, nmeaspec.Generic) and parsed.to_sentence() == line(body)
    else:
        assert parsed.SENTENCE == sentence


def test_a_claimed_line_still_reports_its_fault() -> None:
    """A line the keyword-less layout claims is read by it: a fault after the first field is an
    error, not a generic sentence."""
    with pytest.raises(nmeaspec.NmeaError):
        nmeaspec.parse(line("PASHR,123519.00,1.0"))
