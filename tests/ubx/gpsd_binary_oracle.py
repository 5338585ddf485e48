"""gpsd as the oracle of the SkyTraq, SiRF and CASIC message layouts: the TPV and SKY reports gpsd
wrote for its logs (tests/data/<protocol>/<log>.chk, gpsd's regression expectations) against the
values our decoders read from the same logs' frames (nmeaspec.<protocol>_messages).

A report is tied to the decoded message whose value of the first field of its rule is the one the
report prints (at the report's precision); the rule's other fields are compared on that message.
A report no message holds that value for is counted apart, with the reason found for it.

`.venv/bin/python -m tests.ubx.gpsd_binary_oracle` writes docs/binary-agreement.md;
tests/ubx/test_binary_messages.py fails when it is stale or when a tied report disagrees.
"""

from __future__ import annotations

import json
import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Callable

from tests.ubx.pyubx2_oracle import ubx  # noqa: F401 (puts generated/python on the path)

from nmeaspec import binary, stream  # isort: skip

ROOT = Path(__file__).resolve().parents[2]
DATA = ROOT / "tests" / "data"
DOC = ROOT / "docs" / "binary-agreement.md"


@dataclass(frozen=True)
class Pair:
    """A gpsd report key, the decoded value it prints (a field, or a function of the message), and
    the decimals gpsd prints it with."""

    key: str
    ours: str | Callable[[Any], float]
    decimals: int
    name: str = ""

    def value(self, message: Any) -> float:
        return float(getattr(message, self.ours) if isinstance(self.ours, str) else self.ours(message))

    @property
    def label(self) -> str:
        return self.name or (self.ours if isinstance(self.ours, str) else "?")


@dataclass(frozen=True)
class Rule:
    log: str                 # tests/data/<protocol>/<log>
    report: str              # TPV, SKY
    address: str             # the message: 0xA8, MID 41, NAV-PV
    pairs: tuple[Pair, ...]  # the first ties a report to a message
    unmatched: str           # why a report no message holds the first value for exists
    explain: Callable[[str], set[float]] | None = None   # the first value of what else the log holds
    explain_decimals: int = 9   # ... compared at these decimals
    differ: str = ""         # why a tied report's other fields may differ from the message's


def _mid2_lat(log: str) -> set[float]:
    """The latitudes of MID 2's ECEF positions (WGS 84, Bowring's formula) and of MID 67 SID 1:
    gpsd reports a SiRFstarV's epoch from whichever of MID 2, 41 and 67 it took last."""
    a, f = 6378137.0, 1 / 298.257223563
    b = a * (1 - f)
    e2, ep2 = f * (2 - f), (a * a - b * b) / (b * b)
    out = {m.lat for m in messages(log, "MID 67 SID 1")}
    for m in messages(log, "MID 2"):
        p = math.hypot(m.x, m.y)
        theta = math.atan2(m.z * a, p * b)
        lat = math.atan2(m.z + ep2 * b * math.sin(theta) ** 3, p - e2 * a * math.cos(theta) ** 3)
        out.add(math.degrees(lat))
    return out


def _gga_lat(log: str) -> set[float]:
    """The latitudes of the log's GGA sentences (a dual-output receiver's NMEA)."""
    from nmeaspec import parse

    out = set()
    with (DATA / log).open("rb") as f:
        for item in stream.lines(f, binary=True):
            if isinstance(item, bytes) and item[3:6] == b"GGA":
                lat = getattr(parse(item), "lat", None)
                if lat is not None:
                    out.add(float(lat))
    return out


def _hypot(message: Any) -> float:
    return math.hypot(message.vel_n, message.vel_e)


RULES = (
    Rule("skytraq/skytraq-A8.log", "TPV", "0xA8", (
        Pair("ecefx", "ecef_x", 2), Pair("ecefy", "ecef_y", 2), Pair("ecefz", "ecef_z", 2),
        Pair("lat", "lat", 9), Pair("lon", "lon", 9), Pair("altHAE", "ellipsoid_alt", 4),
        Pair("altMSL", "msl_alt", 4), Pair("ecefvx", "ecef_vx", 2), Pair("ecefvy", "ecef_vy", 2),
        Pair("ecefvz", "ecef_vz", 2)),
        "no reason needed: none"),
    Rule("skytraq/skytraq-A8.log", "SKY", "0xA8", (
        Pair("gdop", "gdop", 2), Pair("pdop", "pdop", 2), Pair("hdop", "hdop", 2), Pair("vdop", "vdop", 2),
        Pair("tdop", "tdop", 2)),
        "no reason needed: none"),
    Rule("skytraq/skytraq-bin.log", "TPV", "0xDF", (
        Pair("ecefx", "ecef_x", 2), Pair("ecefy", "ecef_y", 2), Pair("ecefz", "ecef_z", 2),
        Pair("ecefvx", "ecef_vx", 2), Pair("ecefvy", "ecef_vy", 2), Pair("ecefvz", "ecef_vz", 2)),
        "no reason needed: none"),
    Rule("skytraq/skytraq-bin.log", "SKY", "0xDF", (
        Pair("gdop", "gdop", 2), Pair("pdop", "pdop", 2), Pair("hdop", "hdop", 2), Pair("vdop", "vdop", 2),
        Pair("tdop", "tdop", 2)),
        "the log's first SKY, before any 0xDF; its xdop and ydop, which no SkyTraq message carries, show gpsd "
        "computed its DOPs from the satellites' geometry (0xDE)"),
    Rule("sirf/sirfstarv.log", "TPV", "MID 41", (
        Pair("lat", "lat", 9), Pair("lon", "lon", 9), Pair("altHAE", "alt_ellipsoid", 4),
        Pair("altMSL", "alt_msl", 4), Pair("track", "cog", 4), Pair("speed", "sog", 3), Pair("climb", "climb", 3)),
        "hold the latitude of MID 2's ECEF position (to 1e-7 degrees) or of MID 67 SID 1: gpsd's TPV of "
        "those messages in that epoch", _mid2_lat, 7,
        "gpsd merges MID 2, 41 and 67 SID 1 of one epoch into one TPV; there its heights (to 0.1 mm, as its "
        "conversion of an ECEF position gives them) are not MID 41's, which differ by decimetres"),
    Rule("sirf/sirfstarv.log", "TPV", "MID 67 SID 1", (
        Pair("lat", "lat", 9), Pair("lon", "lon", 9), Pair("altHAE", "alt_ellipsoid", 4),
        Pair("altMSL", "alt_msl", 4), Pair("track", "cog", 4), Pair("speed", "sog", 3), Pair("climb", "climb", 3),
        Pair("epv", "evpe", 3), Pair("leapseconds", "leap_seconds", 0)),
        "hold the latitude of MID 2's ECEF position (to 1e-7 degrees) or of MID 41: gpsd's TPV of those "
        "messages in that epoch", lambda log: _mid2_lat(log) | {m.lat for m in messages(log, "MID 41")}, 7,
        "gpsd merges MID 2, 41 and 67 SID 1 of one epoch into one TPV; there its heights (to 0.1 mm, as its "
        "conversion of an ECEF position gives them) and other values are not MID 67's"),
    Rule("sirf/sirfstarv.log", "TPV", "MID 2", (
        Pair("ecefx", "x", 2), Pair("ecefy", "y", 2), Pair("ecefz", "z", 2),
        Pair("ecefvx", "vx", 2), Pair("ecefvy", "vy", 2), Pair("ecefvz", "vz", 2)),
        "no reason needed: none"),
    Rule("casic/quectel-l76k-dual.log", "TPV", "NAV-PV", (
        Pair("lat", "lat", 9), Pair("lon", "lon", 9), Pair("altHAE", "height", 4),
        Pair("geoidSep", "sep_geoid", 3), Pair("velN", "vel_n", 3), Pair("velE", "vel_e", 3),
        Pair("velD", lambda m: -m.vel_u, 3, "-vel_u"), Pair("speed", _hypot, 3, "hypot(vel_n, vel_e)"),
        Pair("track", "heading", 4)),
        "hold a GGA's latitude: gpsd's TPV of the log's NMEA sentences (GGA, RMC) in that epoch, at their "
        "precision", _gga_lat, 9,
        "gpsd merges the epoch's NMEA sentences and NAV-PV into one TPV: those reports' longitude, height, "
        "geoid separation and track are the GGA's and RMC's, at the sentences' precision"),
)


@dataclass(frozen=True)
class SkyRule:
    """SKY reports' satellites against a message's: each report tied to the message whose
    satellites (PRN, azimuth, elevation) are the report's, its signal strengths then compared."""

    log: str
    address: str
    satellites: Callable[[Any], dict[int, tuple[float, float, float]]]   # PRN -> (az, el, ss)
    unmatched: str


SKY_RULES = (
    SkyRule("skytraq/skytraq-bin.log", "0xDE",
            lambda m: {s.svid: (float(s.azimuth), float(s.elevation), float(s.cn0)) for s in m.svs if s.svid},
            "no reason needed: none"),
    SkyRule("sirf/ublox-sirf1.log", "MID 4",
            lambda m: {c.svid: (c.azimuth * 1.5, c.elevation, sum(getattr(c, f"cno{i}") for i in range(1, 11)) / 10)
                       for c in m.channels if c.svid},
            "no reason needed: none"),
)


@dataclass
class SkyOutcome:
    rule: SkyRule
    reports: int = 0
    tied: int = 0
    satellites: int = 0
    agree: int = 0
    differences: list[str] = field(default_factory=list)


def compare_sky(rule: SkyRule) -> SkyOutcome:
    outcome = SkyOutcome(rule)
    decoded = [rule.satellites(m) for m in messages(rule.log, rule.address)]
    for line in (DATA / (rule.log + ".chk")).read_text().splitlines():
        report = json.loads(line)
        if report.get("class") != "SKY" or not report.get("satellites"):
            continue
        outcome.reports += 1
        theirs = {s["PRN"]: (s["az"], s["el"], s["ss"]) for s in report["satellites"]}
        candidates = [sats for sats in decoded if sats.keys() == theirs.keys() and all(
            _same(sats[prn][0], theirs[prn][0], 1) and _same(sats[prn][1], theirs[prn][1], 1) for prn in theirs)]
        if not candidates:
            continue
        tied = max(candidates, key=lambda sats: sum(_same(sats[p][2], theirs[p][2], 1) for p in theirs))
        outcome.tied += 1
        for prn, (_, _, ss) in theirs.items():
            outcome.satellites += 1
            if _same(tied[prn][2], ss, 1):
                outcome.agree += 1
            elif len(outcome.differences) < 5:
                outcome.differences.append(f"PRN {prn} ss {ss}, ours {tied[prn][2]}")
    return outcome


@dataclass
class Outcome:
    rule: Rule
    reports: int = 0
    tied: int = 0
    explained: int = 0   # reports tied to no message whose value `explain` finds
    agree: dict[str, int] = field(default_factory=dict)
    compared: dict[str, int] = field(default_factory=dict)
    differences: list[str] = field(default_factory=list)


def messages(log: str, address: str) -> list[Any]:
    protocol = log.split("/")[0]
    out = []
    with (DATA / log).open("rb") as f:
        for item in stream.lines(f, binary=True):
            if isinstance(item, stream.BinaryFrame) and item.protocol == protocol:
                message = item.message()
                if isinstance(message, binary.Message) and message.ADDRESS == address:
                    out.append(message)
    return out


def _same(ours: float, printed: float, decimals: int) -> bool:
    return abs(ours - printed) <= 0.5 * 10 ** -decimals + 1e-12 * max(1.0, abs(printed))


def compare(rule: Rule) -> Outcome:
    outcome = Outcome(rule)
    decoded = messages(rule.log, rule.address)
    others = rule.explain(rule.log) if rule.explain else set()
    first = rule.pairs[0]
    reports = [json.loads(line) for line in (DATA / (rule.log + ".chk")).read_text().splitlines()]
    for report in reports:
        if report.get("class") != rule.report or first.key not in report:
            continue
        outcome.reports += 1
        tied = [m for m in decoded if _same(first.value(m), report[first.key], first.decimals)]
        if not tied:
            outcome.explained += any(_same(v, report[first.key], rule.explain_decimals) for v in others)
            continue
        outcome.tied += 1
        message = max(tied, key=lambda m: sum(p.key in report and _same(p.value(m), report[p.key], p.decimals)
                                              for p in rule.pairs))
        for pair in rule.pairs:
            if pair.key not in report:
                continue
            outcome.compared[pair.key] = outcome.compared.get(pair.key, 0) + 1
            if _same(pair.value(message), report[pair.key], pair.decimals):
                outcome.agree[pair.key] = outcome.agree.get(pair.key, 0) + 1
            elif len(outcome.differences) < 5:
                outcome.differences.append(f"{pair.key} {report[pair.key]!r}, ours {pair.label} "
                                           f"{pair.value(message)!r}")
    return outcome


def outcomes() -> tuple[list[Outcome], list[SkyOutcome]]:
    return [compare(rule) for rule in RULES], [compare_sky(rule) for rule in SKY_RULES]


def render(found: tuple[list[Outcome], list[SkyOutcome]]) -> str:
    results, skies = found
    lines = [
        "# SkyTraq, SiRF and CASIC messages: agreement with gpsd",
        "",
        "Written by `.venv/bin/python -m tests.ubx.gpsd_binary_oracle`; tests/ubx/test_binary_messages.py",
        "fails when it is stale. gpsd's reports (TPV, SKY) for its logs of these receivers",
        "(tests/data/<protocol>/<log>.chk, PROVENANCE.md) against the values nmeaspec's",
        "<protocol>_messages decode from the same logs' frames. A report is tied to the decoded",
        "message that holds the value of the rule's first field at the report's precision; the other",
        "fields are compared on that message, each within half the last decimal gpsd prints.",
        "",
        "| log | report | message | reports | tied | field: agree / compared |",
        "| --- | --- | --- | ---: | ---: | --- |",
    ]
    for o in results:
        fields = ", ".join(f"{p.key}={p.label}: {o.agree.get(p.key, 0)} / {o.compared.get(p.key, 0)}"
                           for p in o.rule.pairs if p.key in o.compared)
        lines.append(f"| {o.rule.log.split('/')[1]} | {o.rule.report} | {o.rule.address} | {o.reports} | {o.tied} | "
                     f"{fields} |")
    lines += ["", "| log | SKY satellites of | reports | tied | satellites: ss agree / compared |",
              "| --- | --- | ---: | ---: | --- |"]
    for k in skies:
        lines.append(f"| {k.rule.log.split('/')[1]} | {k.rule.address} | {k.reports} | {k.tied} | "
                     f"{k.agree} / {k.satellites} |")
    lines += ["", "## Differences", ""]
    for o in results:
        if o.differences or o.reports != o.tied:
            where = f"- {o.rule.log.split('/')[1]} {o.rule.report} / {o.rule.address}:"
            if o.reports != o.tied:
                lines.append(f"{where} {o.reports - o.tied} reports tied to no message" + (
                    f", {o.explained} of them {o.rule.unmatched}." if o.rule.explain else f": {o.rule.unmatched}."))
            if o.differences:
                disagree = sum(o.compared.values()) - sum(o.agree.values())
                lines.append(f"{where} {disagree} values of tied reports differ: {o.rule.differ}. First ones: "
                             + "; ".join(o.differences) + ".")
    for k in skies:
        if k.differences or k.reports != k.tied:
            lines.append(f"- {k.rule.log.split('/')[1]} SKY / {k.rule.address}: {k.reports - k.tied} reports tied to "
                         f"no message ({k.rule.unmatched})" + "".join(f"; {d}" for d in k.differences))
    return "\n".join(lines) + "\n"


if __name__ == "__main__":
    DOC.write_text(render(outcomes()))
    print(DOC.read_text())
