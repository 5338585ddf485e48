"""The README's counts of what the spec describes are the model's (they were kept by hand)."""

from __future__ import annotations

import re
from pathlib import Path

from generator.build import load_spec

ROOT = Path(__file__).resolve().parents[2]


def test_the_readme_counts_what_the_spec_describes() -> None:
    spec = load_spec(ROOT / "spec")
    text = " ".join((ROOT / "README.md").read_text(encoding="utf-8").split())
    proprietary = [s for s in spec.sentences if s.is_proprietary]
    manuals = {m.id: m for m in spec.manuals}
    counts = {
        "standard NMEA 0183 sentences": sum(not s.is_proprietary for s in spec.sentences),
        "AIS message types": len({t for p in spec.payloads if p.protocol == "ais" for t in p.types}),
        "u-blox UBX messages": len({(m.id) for m in spec.binary if m.protocol == "ubx"}),
        "binary application messages": len(spec.applications),
        "RTCM 3 message numbers": len({t for m in spec.bit_messages if m.protocol == "rtcm3" for t in m.types}),
        "SkyTraq, SiRF \\(OSP\\) and CASIC binary messages":
            sum(m.protocol in ("skytraq", "sirf", "casic") for m in spec.binary),
        "Septentrio SBF blocks": sum(m.protocol == "sbf" for m in spec.binary),
        "Unicore binary logs": sum(m.protocol == "unicore" for m in spec.binary),
        "proprietary sentences, commands and replies": len(proprietary),
        "manuals of": len({s.vendor for s in proprietary}),
        "receiver makers": len({manuals[s.vendor].maker for s in proprietary}),
        "typed command builders": sum(len(s.layouts) for s in spec.sentences if s.kind == "command"),
    }
    for words, count in counts.items():
        found = re.findall(rf"(\d[\d,]*) (?:the )?{words}", text)
        assert found, f"README: no count before {words!r}"
        assert [int(n.replace(",", "")) for n in found] == [count] * len(found), (words, found, count)
