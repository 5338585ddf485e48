"""gpsd as the oracle of the fixes: its regression logs (../shared/corpus/real/gpsd/*.nmea) and
the TPV and SKY reports gpsd writes for them (tests/data/gpsd/*.log.chk, see PROVENANCE.md there).

gpsd reports after each sentence, so an epoch has many TPVs; its last TPV of a time of day holds
all the epoch told it, and so does the last SKY before the next epoch's first TPV. Each fact is
compared where both sides have it; `agreement` counts, per fact, the epochs compared and those
that agree. Run as a script, it prints the figures as JSON (gpsd_agreement.json).
"""

from __future__ import annotations

import json
import sys
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parents[2]
CORPUS = ROOT.parent / "shared" / "corpus" / "real" / "gpsd"
CHECKS = ROOT / "tests" / "data" / "gpsd"
sys.path.insert(0, str(ROOT / "generated" / "python"))

from nmeaspec.fixes import Fix, fixes  # noqa: E402

FACTS = ("epoch", "date", "position", "altitude", "altitude_hae", "speed", "mode", "used", "in_view")
MODES = {"no_fix": 1, "fix_2d": 2, "fix_3d": 3}


def gpsd_epochs(chk: Path) -> dict[str, dict[str, Any]]:
    """gpsd's view of each epoch, by time of day (hh:mm:ss.fff): its last TPV and last SKYs."""
    epochs: dict[str, dict[str, Any]] = {}
    current: dict[str, Any] | None = None
    for line in chk.read_text(encoding="latin-1").splitlines():
        if not line.startswith("{"):
            continue
        report = json.loads(line)
        if report.get("class") == "TPV" and "time" in report:
            key = report["time"][11:23]
            current = epochs.setdefault(key, {})
            current["tpv"] = report
        elif report.get("class") == "SKY" and current is not None:
            for count in ("uSat", "nSat"):
                if count in report:
                    current[count] = report[count]
    return epochs


def _time_key(fix: Fix) -> str | None:
    return None if fix.time is None else fix.time.isoformat(timespec="milliseconds")


def compare(fix: Fix, gpsd: dict[str, Any]) -> dict[str, bool]:
    """Per fact both sides have: whether they agree."""
    tpv = gpsd["tpv"]
    out: dict[str, bool] = {"epoch": True}
    if fix.date is not None:
        out["date"] = fix.date.isoformat() == tpv["time"][:10]
    if fix.latitude is not None and "lat" in tpv:
        out["position"] = abs(fix.latitude - tpv["lat"]) <= 1e-6 and abs(fix.longitude - tpv["lon"]) <= 1e-6
    if fix.altitude_msl is not None and "altMSL" in tpv:
        out["altitude"] = abs(fix.altitude_msl - tpv["altMSL"]) <= 1e-3
    if fix.altitude_hae is not None and "altHAE" in tpv:
        out["altitude_hae"] = abs(fix.altitude_hae - tpv["altHAE"]) <= 1e-3
    if fix.speed is not None and "speed" in tpv:
        out["speed"] = abs(fix.speed - tpv["speed"]) <= 1e-3
    if fix.mode is not None and "mode" in tpv:
        out["mode"] = MODES[fix.mode] == tpv["mode"]
    used = fix.used_count or fix.satellites_used
    if used is not None and "uSat" in gpsd:
        out["used"] = used == gpsd["uSat"]
    if fix.in_view and "nSat" in gpsd:
        out["in_view"] = fix.in_view_count == gpsd["nSat"]
    return out


def agreement(log: str) -> dict[str, list[int]]:
    """Per fact: [epochs compared, epochs that agree]; `epoch`: [our epochs, those gpsd has]."""
    gpsd = gpsd_epochs(CHECKS / f"{log}.log.chk")
    counts = {fact: [0, 0] for fact in FACTS}
    with open(CORPUS / f"{log}.nmea", encoding="latin-1", newline="") as lines:
        for fix in fixes(lines):
            key = _time_key(fix)
            counts["epoch"][0] += 1
            if key is None or key not in gpsd:
                continue
            for fact, agrees in compare(fix, gpsd[key]).items():
                if fact != "epoch":
                    counts[fact][0] += 1
                counts[fact][1] += agrees
    return counts


def logs() -> list[str]:
    return sorted(p.name.removesuffix(".log.chk") for p in CHECKS.glob("*.log.chk"))


if __name__ == "__main__":
    print(json.dumps({log: agreement(log) for log in logs()}, indent=1, sort_keys=True))
