"""pysbf2 (semuconsulting, BSD-3-Clause) as the oracle of the SBF blocks the spec types
(spec/binary/sbf/messages) over pysbf2's own logs (tests/data/sbf): the values our generated classes
(nmeaspec.sbf_messages) decode from each block against pysbf2's, field by field, paired by name
(ours are Septentrio's names in snake case: RxClkBias is rx_clk_bias).

pysbf2 is no dependency of the package or of the tests: `python -m tests.ubx.pysbf2_oracle --record`,
run by a Python that has pysbf2 (a venv of its own), writes what pysbf2 decodes from the logs to
tests/data/sbf/pysbf2_decoded.jsonl (its version in the first line); `.venv/bin/python -m
tests.ubx.pysbf2_oracle` writes docs/sbf-agreement.md from it, and tests/ubx/test_binary_messages.py
fails when that is stale or when a value differs without a reason listed here."""

from __future__ import annotations

import json
import math
import re
import struct
import sys
from collections import Counter
from dataclasses import dataclass, field
from enum import Enum
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parents[2]
DATA = ROOT / "tests" / "data" / "sbf"
RECORD = DATA / "pysbf2_decoded.jsonl"
DOC = ROOT / "docs" / "sbf-agreement.md"
LOGS = sorted(DATA.glob("*.sbf")) + sorted(DATA.glob("*.log"))
# The blocks the spec types, by pysbf2's name.
TYPED = {"PVTGeodetic": 4007, "PVTCartesian": 4006, "PosCovCartesian": 5905, "PosCovGeodetic": 5906,
         "VelCovCartesian": 5907, "VelCovGeodetic": 5908, "DOP": 4001, "ReceiverTime": 5914, "SatVisibility": 4012,
         "ReceiverStatus": 4014, "BaseVectorCart": 4043, "EndOfPVT": 5921, "xPPSOffset": 5911, "MeasExtra": 4000, "MeasEpoch": 4027,
         "ChannelStatus": 4013}
# pysbf2's names that snake case does not make ours; its reserved bits, which we keep unnamed.
NAMES = {"WNc": "wnc", "TOW": "tow", "2D": "two_d", "Type": "mode_type", "NrSV": "nr_sv", "Corr_DO229Active":
         "corr_do229_active", "RAIMIntegrity": "raim_integrity", "GalHPCAFail": "gal_hpca_fail",
         "PPPSeedAge": "ppp_seed_age", "PPPSeedType": "ppp_seed_type", "HAccuracy": "h_accuracy",
         "VAccuracy": "v_accuracy", "BaseARP": "base_arp", "ARPOffset": "arp_offset", "DeltaLS": "delta_ls",
         "UTCMin": "utc_min", "UTCSec": "utc_sec", "UTCYear": "utc_year", "UTCMonth": "utc_month",
         "UTCDay": "utc_day", "UTCHour": "utc_hour", "SyncLevel": "sync_level", "PDOP": "pdop", "TDOP": "tdop",
         "HDOP": "hdop", "VDOP": "vdop", "HPL": "hpl", "VPL": "vpl", "Vn": "vn", "Ve": "ve", "Vu": "vu",
         "Vx": "vx", "Vy": "vy", "Vz": "vz", "X": "x", "Y": "y", "Z": "z", "COG": "cog",
         "Corr_RTKType": "corr_rtk_type", "SBLength": "sb_length", "CPULoad": "cpu_load", "SISError": "sis_error",
         "CPUOverloadError": "cpu_overload_error", "MissEventError": "missed_event_error", "WnSer": "wn_set",
         "SVID": "svid", "MPCorrection": "mp_correction", "CarMPCorr": "car_mp_corr", "CN0HighRes": "cn0_high_res",
         "E6BUsed": "e6b_used", "PRSmoothed": "pr_smoothed", "PVTInfo": "pvt_info", "PVTStatus": "pvt_status"}
RESERVED = re.compile(r"^Reserved\d*$")
# pysbf2's fields we leave out, and why.
LEFT_OUT = {"SigAuth": "a bit of AlertFlag that revision 3 adds (the logs' blocks are revision 2: reserved there)",
            "NavMsgAuth": "a bit of AlertFlag that revision 3 adds (the logs' blocks are revision 2: reserved there)",
            "SVIDFull": "pysbf2's own addition to each SatInfo sub-block, no field of Septentrio's layout"}
# A sub-block's fields: pysbf2 names the k-th entry's <Name>_<k> (two digits or more, from 01), and the j-th
# sub-block nested in it <Name>_<k>_<j>; ours are the entries of the layout's one group,
# <group>.<field> here (<group>.<nested group>.<field>).
ENTRY = re.compile(r"^(.+?)_(\d{2,})(?:_(\d{2,}))?$")
# Fields whose unit pysbf2 converts (block, our field): the factor from ours to its, the relative
# tolerance of the comparison and why. Each such value is counted as agreeing once converted.
CONVERTED: dict[tuple[str, str], tuple[Any, float, str]] = {("xPPSOffset", "offset"): (1e-9, 1e-3, "pysbf2 gives the offset in seconds, rounded to 4 significant "
                                                    "digits (5.406e-09); ours is the r4 as sent, in ns (5.40565...)"),
             ("MeasExtra", "meas_extra_channel.car_mp_corr"): (1000, 1e-9, "pysbf2 gives it in millicycles; ours "
                                                               "in cycles (the guide's 1/512 cycle)"),
             ("MeasExtra", "meas_extra_channel.cn0_high_res"): (1 / 32, 1e-9, "pysbf2 gives it in dB-Hz; ours is "
                                                                "the 3-bit part as sent (0.03125 dB-Hz each)"),
             ("MeasEpoch", "type1.code_msb"): (4294967.296, 1e-9, "pysbf2 gives it in metres (4294967.296 m each); "
                                               "ours is the 4-bit part as sent (a scale above 1 is left raw)"),
             ("MeasEpoch", "type1.carrier_msb"): (65.536, 1e-9, "pysbf2 gives it in cycles (65.536 each); ours is the "
                                                  "i1 as sent (a scale above 1 is left raw)"),
             ("MeasEpoch", "type1.type2.code_offset_msb"): (
                 lambda v: v % 8 * 65.536, 1e-9, "pysbf2 reads the 3 bits unsigned and in metres (7: 458.752 m); ours "
                 "are the guide's two's complement as sent (7: -1, 65.536 m each)"),
             ("MeasEpoch", "type1.type2.doppler_offset_msb"): (
                 lambda v: v % 32 * 6.5536, 1e-9, "pysbf2 reads the 5 bits unsigned and in Hz (31: 203.1616 Hz); ours "
                 "are the guide's two's complement as sent (31: -1, 6.5536 Hz each)")}


def _convert(key: tuple[str, str], value: Any) -> Any:
    """Our value in pysbf2's unit (CONVERTED)."""
    factor = CONVERTED[key][0]
    return factor(value) if callable(factor) else value * factor


def snake(name: str) -> str:
    if name in NAMES:
        return NAMES[name]
    if name.startswith("Cov_"):   # Cov_VxVy: cov_vxvy
        return name.lower()
    return re.sub(r"(?<=[a-z0-9])(?=[A-Z])", "_", name).lower()


def sbf_blocks(data: bytes) -> list[bytes]:
    """The SBF blocks of a log whose CRC holds, in order (binascii's CRC-CCITT)."""
    import binascii

    found, at = [], data.find(b"$@")
    while 0 <= at < len(data) - 7:
        size = int.from_bytes(data[at + 6:at + 8], "little")
        if size >= 8 and binascii.crc_hqx(data[at + 4:at + size], 0) == int.from_bytes(data[at + 2:at + 4], "little"):
            found.append(data[at:at + size])
            at = data.find(b"$@", at + size)
        else:
            at = data.find(b"$@", at + 1)
    return found


def record() -> None:
    """pysbf2's values of every typed block of the logs, by the block's index among the log's SBF blocks."""
    import pysbf2

    lines = [json.dumps({"pysbf2": pysbf2.version if hasattr(pysbf2, "version") else "?"})]
    for log in LOGS:
        for index, block in enumerate(sbf_blocks(log.read_bytes())):
            parsed = pysbf2.SBFReader.parse(block)
            if parsed.identity in TYPED:
                values = {k: v for k, v in vars(parsed).items() if not k.startswith("_")}
                lines.append(json.dumps({"log": log.name, "index": index, "block": parsed.identity, "values": values},
                                        separators=(",", ":")))
    RECORD.write_text("\n".join(lines) + "\n")


@dataclass
class Outcome:
    block: str
    count: int = 0
    fields: Counter[str] = field(default_factory=Counter)   # field: compared
    agree: Counter[str] = field(default_factory=Counter)
    special: Counter[str] = field(default_factory=Counter)   # a do-not-use value: ours named, pysbf2's a number
    missing: set[str] = field(default_factory=set)   # pysbf2's fields we have no field of
    differ: list[str] = field(default_factory=list)
    round_trip: int = 0
    converted: set[str] = field(default_factory=set)   # fields compared in pysbf2's unit (CONVERTED)


def _equal(ours: Any, theirs: Any) -> bool:
    if isinstance(theirs, float) or isinstance(ours, float):
        return math.isclose(float(ours), float(theirs), rel_tol=1e-9, abs_tol=1e-12)
    return bool(ours == theirs)


def _special_agrees(f: Any, value: Any, theirs: Any) -> bool:
    """Whether pysbf2's number is the raw value of our special value: a float's bits in the
    field's width (-2e10), an integer's raw value (divided by the field's divisor: 655.35 for 65535)."""
    if isinstance(theirs, bool) or not isinstance(theirs, (int, float)):
        return False
    if type(f).__name__ == "Float":
        packed = struct.pack("<f" if f.width == 32 else "<d", theirs)
        return int.from_bytes(packed, "little") == value.raw
    return round((theirs - f.base) * f.divisor) == value.raw


def outcomes() -> list[Outcome]:
    sys.path.insert(0, str(ROOT / "generated" / "python"))
    from nmeaspec import sbf_messages
    from nmeaspec.ais import Group, Special, flat_fields

    recorded = [json.loads(line) for line in RECORD.read_text().splitlines()[1:]]
    blocks = {log.name: sbf_blocks(log.read_bytes()) for log in LOGS}
    out: dict[str, Outcome] = {}
    for r in recorded:
        o = out.setdefault(r["block"], Outcome(r["block"]))
        o.count += 1
        data = blocks[r["log"]][r["index"]]
        message = sbf_messages.decode(data)
        o.round_trip += message.encode() == data
        ours = message.to_dict()
        groups = [g for g in type(message).LAYOUT if isinstance(g, Group)]
        for name, theirs in r["values"].items():
            if RESERVED.match(name):
                continue
            entry = ENTRY.match(name)
            if entry and groups:   # the k-th sub-block's field (or its j-th nested sub-block's)
                if RESERVED.match(entry.group(1)):
                    continue
                group = groups[0]
                owner, path = getattr(message, group.id)[int(entry.group(2)) - 1], group.id
                if entry.group(3):
                    group = next(g for g in group.fields if isinstance(g, Group))
                    owner, path = getattr(owner, group.id)[int(entry.group(3)) - 1], f"{path}.{group.id}"
                base = snake(entry.group(1))
                entry_fields = {f.id: f for f in flat_fields(group.fields)}
                if base not in entry_fields:
                    o.missing.add(entry.group(1))
                    continue
                key, spec = f"{path}.{base}", entry_fields[base]
            else:
                key = snake(name)
                if key not in ours:
                    o.missing.add(name)
                    continue
                owner, spec, base = message, message.FIELDS.get(key), key
            o.fields[key] += 1
            value = getattr(owner, base)
            converted = CONVERTED.get((r["block"], key))
            if isinstance(value, Special):   # a do-not-use value, by its id: pysbf2's number is its raw value
                if _special_agrees(spec, value, theirs) or converted is not None and math.isclose(
                        _convert((r["block"], key), value.raw), theirs, rel_tol=converted[1]):
                    o.special[key] += 1
                elif len(o.differ) < 5:
                    o.differ.append(f"{r['log']} block {r['index']} {key}: ours {value.id} (raw {value.raw}), "
                                    f"pysbf2 {theirs!r}")
                continue
            if isinstance(value, Enum):   # an enum's code
                value = int(value.value)
            if converted is not None and math.isclose(_convert((r["block"], key), value), theirs, rel_tol=converted[1]):
                o.agree[key] += 1
                o.converted.add(key)
            elif _equal(value, theirs):
                o.agree[key] += 1
            elif len(o.differ) < 5:
                o.differ.append(f"{r['log']} block {r['index']} {key}: ours {value!r}, pysbf2 {theirs!r}")
    return [out[name] for name in TYPED if name in out]


def render(found: list[Outcome]) -> str:
    version = json.loads(RECORD.read_text().splitlines()[0])["pysbf2"]
    lines = ["# SBF blocks: agreement with pysbf2", "",
             "Written by `.venv/bin/python -m tests.ubx.pysbf2_oracle`; tests/ubx/test_binary_messages.py fails",
             f"when it is stale. pysbf2 {version}'s values of the typed SBF blocks of its own logs",
             "(tests/data/sbf, PROVENANCE.md; recorded in tests/data/sbf/pysbf2_decoded.jsonl by",
             "`python -m tests.ubx.pysbf2_oracle --record` in a venv that has pysbf2) against the values",
             "nmeaspec.sbf_messages decodes from the same blocks, field by field (floats within 1e-9",
             "relative). A do-not-use value is a named special value here (`do_not_use`) and a number in",
             "pysbf2 (655.35 s for a mean age of corrections of raw 65535; -2e10 for a float, whose bits",
             "are the float do-not-use value's): counted apart when pysbf2's number is that raw value, a",
             "difference otherwise. A sub-block's field (pysbf2's <Name>_<k>) is counted as",
             "<group>.<field> over every sub-block. Round trip: the decoded block encodes back to its bytes.", "",
             "| block | blocks | round trip | fields agreeing / compared | do-not-use values |",
             "| --- | ---: | ---: | --- | --- |"]
    for o in found:
        fields = ", ".join(f"{k}: {o.agree[k]} / {n}" for k, n in o.fields.items())
        special = ", ".join(f"{k}: {n}" for k, n in o.special.items()) or "none"
        lines.append(f"| {o.block} | {o.count} | {o.round_trip} / {o.count} | {fields} | {special} |")
    lines += ["", "## Differences", ""]
    notes = [f"- {o.block}: pysbf2's {name}, not typed here: {LEFT_OUT.get(name, 'no reason known')}."
             for o in found for name in sorted(o.missing)]
    notes += [f"- {o.block}: {name} compared in pysbf2's unit: {CONVERTED[(o.block, name)][2]}."
              for o in found for name in sorted(o.converted)]
    notes += [f"- {o.block}: {d}" for o in found for d in o.differ]
    lines += notes or ["None."]
    return "\n".join(lines) + "\n"


if __name__ == "__main__":
    if "--record" in sys.argv:
        record()
    else:
        DOC.write_text(render(outcomes()))
