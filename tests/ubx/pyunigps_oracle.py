"""pyunigps (semuconsulting, BSD-3-Clause) as the oracle of the Unicore binary messages the spec
types (spec/binary/unicore/messages): the values our generated classes (nmeaspec.unicore_messages)
decode from each frame against pyunigps's, field by field, paired by name (ours in snake case,
theirs run together: sol_status is solstatus; ALIASES where the words differ).

No Unicore receiver log with binary frames is public that we found (pyunigps's own logs hold NMEA and
RTCM 3 only): the frames are pyunigps's example frames (tests/data/unicore/pyunigps_frames.log) and,
for each typed message, one frame pyunigps 1.0.1 built from the values of BUILD below
(tests/data/unicore/pyunigps_built.log, written by `python -m tests.ubx.pyunigps_oracle --build`).

pyunigps is no dependency of the package or of the tests: `python -m tests.ubx.pyunigps_oracle
--record`, run by a Python that has pyunigps (a venv of its own), writes what pyunigps decodes from
the frames to tests/data/unicore/pyunigps_decoded.jsonl (its version in the first line);
`.venv/bin/python -m tests.ubx.pyunigps_oracle` writes docs/unicore-agreement.md from it, and
tests/ubx/test_binary_messages.py fails when that is stale or when a value differs without a reason
listed here."""

from __future__ import annotations

import json
import math
import struct
import sys
from collections import Counter
from dataclasses import dataclass, field
from enum import Enum
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parents[2]
DATA = ROOT / "tests" / "data" / "unicore"
BUILT = DATA / "pyunigps_built.log"
RECORD = DATA / "pyunigps_decoded.jsonl"
DOC = ROOT / "docs" / "unicore-agreement.md"
LOGS = [DATA / "pyunigps_frames.log", BUILT]
# The messages the spec types, by pyunigps's name: their id.
TYPED = {"VERSION": 37, "OBSVM": 12, "PVTSLN": 1021, "BESTNAV": 2118, "BESTNAVXYZ": 240, "ADRNAV": 142,
         "UNIHEADING": 972, "RTKSTATUS": 509}
# The header's values of the built frames (pyunigps's names), none zero, each frame's its own (by its
# place in BUILD): the messages keep them and write them back (the round trip is byte for byte).
def header_values(index: int) -> dict[str, int]:
    return {"cpuidle": 37 + index, "timeref": index % 2, "timestatus": 1 + index % 3, "wno": 2406 + index,
            "tow": 123_456_000 + 1_250 * index, "version": 0x10203 + index, "leapsecond": 18, "delay": 5 + index}


# Our header fields by pyunigps's names.
HEADER_NAMES = {"cpu_idle": "cpuidle", "time_ref": "timeref", "time_status": "timestatus", "week": "wno",
                "time_of_week": "tow", "version": "version", "leap_seconds": "leapsecond", "output_delay": "delay"}
_MASKS = {"rtkverify": 1, "psrionocorr": 3, "gale1": 1, "gale5b": 1, "gpsl1": 1, "gpsl2": 1, "glol1": 1, "bdsb2l": 1}
_FIX = {"solstatus": 0, "postype": 50, "lat": 51.4761234567, "lon": -0.0012345678, "hmsl": 45.6789,
        "undulation": 47.125, "datumid": 61, "latstd": 0.0125, "lonstd": 0.01171875, "hmslstd": 0.025,
        "stationid": "0042", "diffage": 1.0, "solage": 0.0, "numsvs": 31, "numsolnsvs": 27, **_MASKS,
        "veltype": 8, "latency": 0.05, "horspd": 0.0123, "trkgnd": 271.5, "vertspd": -0.0042,
        "verspdstd": 0.011, "horspdstd": 0.007}
# The values each built frame holds, by pyunigps's names (the fields left out: pyunigps's zero).
BUILD: dict[str, dict[str, Any]] = {
    "VERSION": {"device": 18, "swversion": "R4.10Build5251", "authtype": "HRPT00-S10C-P", "psn": "2310415000012",
                "efuseid": "ffff48ffff0fffff", "comptime": "2021/11/26"},
    "BESTNAV": {**_FIX, "vsolstatus": 0, "age": 0.0},
    "ADRNAV": {**_FIX, "postype": 49, "solstatus2": 0, "agediff": 1.0},
    "BESTNAVXYZ": {"solstatus": 0, "postype": 16, "px": 3978654.1234, "py": -276.5678, "pz": 4968470.9012,
                   "pxstd": 1.25, "pystd": 0.75, "pzstd": 2.5, "vsolstatus": 0, "veltype": 8, "velx": 0.0125,
                   "vely": -0.002, "velz": 0.004, "velxstd": 0.05, "velystd": 0.05, "velzstd": 0.0625,
                   "stationid": "0000", "vellatency": 0.05, "diffage": 0.0, "solage": 0.0, "numsvs": 35,
                   "numsolnsvs": 30, "numggl1": 30, "numsolnmultisvs": 28, **_MASKS},
    "UNIHEADING": {"solstatus": 0, "postype": 50, "length": 1.2345, "heading": 123.456, "pitch": -1.5,
                   "hdgstddev": 0.125, "ptchstddev": 0.25, "stationid": "0042", "numsvs": 28, "numsolnsvs": 24,
                   "numobs": 26, "nummulti": 22, **_MASKS},
    "RTKSTATUS": {"gpssource": 0x07, "bdssource1": 0x0F, "bdssource2": 0x01, "glosource": 0x03,
                  "galsource1": 0x05, "galsource2": 0x02, "qzsssource": 0x01, "postype": 50, "calcstatus": 5,
                  "iondetected": 0, "dualrtkflag": 1, "adrnumber": 27},
    "PVTSLN": {"bestpostype": 50, "bestposhmsl": 45.625, "bestposlat": 51.4761234567, "bestposlon": -0.0012345678,
               "bestposhmslstd": 0.025, "bestposlatstd": 0.0125, "bestposlonstd": 0.01171875,
               "bestposdiffage": 1.0, "psrpostype": 16, "psrposhmsl": 46.5, "psrposlat": 51.47613,
               "psrposlon": -0.00124, "undulation": 47.125, "bestpossvs": 31, "bestpossolnsvs": 27,
               "psrpossvs": 31, "psrpossolnsvs": 29, "psrvelnorth": 0.011, "psrveleast": -0.004,
               "psrvelground": 0.0117, "headingtype": 50, "headinglength": 1.2345, "headingdegree": 123.456,
               "headingpitch": -1.5, "headingtrackedsvs": 28, "headingsolnsvs": 24, "headingggl1": 24,
               "headingggl1l2": 22, "gdop": 1.25, "pdop": 1.125, "hdop": 0.625, "htdop": 0.75, "tdop": 0.5,
               "cutoff": 10.0, "prnnum": 3},
    "OBSVM": {"numobs": 2, "glofreq_01": 0, "prn_01": 5, "psr_01": 21456789.123, "adr_01": -112754321.4567,
              "psrstd_01": 0.05, "adrstd_01": 0.0012, "doppfreq_01": -1234.5, "cno_01": 45.25,
              "locktime_01": 123.5, "svchan_01": 3, "cpsflag_01": 1, "psrflag_01": 1, "gnss_01": 0,
              "sigtype_01": 0,
              "glofreq_02": 9, "prn_02": 4, "psr_02": 20123456.789, "adr_02": -107654321.25,
              "psrstd_02": 0.12, "adrstd_02": 0.0034, "doppfreq_02": 2345.25, "cno_02": 41.5,
              "locktime_02": 2.25, "svchan_02": 17, "cpsflag_02": 1, "psrflag_02": 1, "gnss_02": 1,
              "sigtype_02": 5, "L2Cflag_02": 0},
}
# The payload's bytes after BUILD's values: PVTSLN's satellites used (5, 13, 141), two bytes each.
PAYLOAD_TAIL = {"PVTSLN": bytes.fromhex("05000d008d00")}
# Our field names whose pyunigps name is not theirs run together (by message, then for all).
ALIASES: dict[str, dict[str, str]] = {
    "ADRNAV": {"vel_sol_status": "solstatus2", "age": "agediff"},
    "": {"height": "hmsl", "height_std": "hmslstd", "best_pos_height": "bestposhmsl",
         "best_pos_height_std": "bestposhmslstd", "psr_pos_height": "psrposhmsl", "rtk_verified": "rtkverify",
         "iono_correction": "psrionocorr", "vel_sol_status": "vsolstatus", "vert_spd_std": "verspdstd",
         "bds_b1": "bdsb1l", "bds_b3": "bdsb3l", "bds_b2": "bdsb2l", "hdg_std": "hdgstddev",
         "ptch_std": "ptchstddev", "dopp": "doppfreq", "cn0": "cno", "phase_lock": "cpsflag",
         "code_lock": "psrflag", "system": "gnss", "signal_type": "sigtype", "l2c_flag": "L2Cflag"},
}
# Our fields pyunigps has no value of, and why.
NOT_COMPARED = {
    "bds_b1i": "pyunigps names bit 4 of the Galileo/BDS-3 mask and bit 6 of the GPS/GLONASS/BDS-2 mask alike "
               "(bdsb1l): its decoded values hold the second",
    "bds_b3i": "pyunigps names bit 5 of the Galileo/BDS-3 mask and bit 3 of the GPS/GLONASS/BDS-2 mask alike "
               "(bdsb3l): its decoded values hold the second",
}
# pyunigps's values that are no field here, and why (reserved ones are passed over).
LEFT_OUT: dict[str, str] = {}


def theirs_name(message: str, ours: str) -> str:
    return ALIASES.get(message, {}).get(ours) or ALIASES[""].get(ours) or ours.replace("_", "")


def frames(data: bytes) -> list[bytes]:
    """The Unicore frames of a log whose CRC-32 holds, in order."""
    import zlib

    found, at = [], data.find(b"\xaa\x44\xb5")
    while 0 <= at <= len(data) - 28:
        size = 28 + int.from_bytes(data[at + 6:at + 8], "little")
        frame = data[at:at + size]
        if len(frame) == size and (zlib.crc32(frame[:-4], ~0) ^ ~0) & 0xFFFFFFFF == int.from_bytes(frame[-4:], "little"):
            found.append(frame)
            at = data.find(b"\xaa\x44\xb5", at + size)
        else:
            at = data.find(b"\xaa\x44\xb5", at + 1)
    return found


def build() -> None:
    """pyunigps's frames of BUILD's values, one per typed message (pyunigps 1.0.1's UNIMessage)."""
    from pyunigps import UNIMessage
    from pyunigps.unitypes_core import GET

    out = []
    for index, (name, values) in enumerate(BUILD.items()):
        kwargs = {k: v for k, v in values.items() if k != "length"}
        header = header_values(index)
        message = UNIMessage(TYPED[name], msgmode=GET, **header, **kwargs)
        if name in PAYLOAD_TAIL or "length" in values:
            # the constructor takes neither a group of as many entries as the bytes left (PVTSLN's
            # satellites: appended to its payload) nor UNIHEADING's baseline length (its `length` is the header's)
            payload = bytearray(message.payload) + PAYLOAD_TAIL.get(name, b"")
            if "length" in values:
                payload[8:12] = struct.pack("<f", values["length"])
            message = UNIMessage(TYPED[name], msgmode=GET, **header, payload=bytes(payload))
        out.append(message.serialize())
    BUILT.write_bytes(b"".join(out))


def record() -> None:
    """pyunigps's values of every frame of the logs, by the frame's index in its log."""
    import pyunigps
    from pyunigps import UNIReader

    lines = [json.dumps({"pyunigps": getattr(pyunigps, "version", "?")})]
    for log in LOGS:
        for index, frame in enumerate(frames(log.read_bytes())):
            parsed = UNIReader.parse(frame)
            values = {k: v for k, v in vars(parsed).items() if not k.startswith("_")}
            lines.append(json.dumps({"log": log.name, "index": index, "identity": parsed.identity,
                                     "msgid": int.from_bytes(frame[4:6], "little"), "values": values},
                                    separators=(",", ":")))
    RECORD.write_text("\n".join(lines) + "\n")


@dataclass
class Outcome:
    message: str
    count: int = 0
    fields: Counter[str] = field(default_factory=Counter)   # field: compared
    agree: Counter[str] = field(default_factory=Counter)
    missing: set[str] = field(default_factory=set)   # pyunigps's fields we have no field of
    not_compared: set[str] = field(default_factory=set)
    differ: list[str] = field(default_factory=list)
    round_trip: int = 0


def _equal(ours: Any, theirs: Any) -> bool:
    if isinstance(theirs, float) or isinstance(ours, float):
        return math.isclose(float(ours), float(theirs), rel_tol=1e-9, abs_tol=1e-12)
    if isinstance(ours, str) and isinstance(theirs, str):   # text: pyunigps keeps the padding
        return ours.rstrip("\x00 ") == theirs.rstrip("\x00 ")
    return bool(ours == theirs)


def outcomes() -> list[Outcome]:
    sys.path.insert(0, str(ROOT / "generated" / "python"))
    from nmeaspec import unicore_messages

    recorded = [json.loads(line) for line in RECORD.read_text().splitlines()[1:]]
    logs = {log.name: frames(log.read_bytes()) for log in LOGS}
    out: dict[str, Outcome] = {}
    by_id = {number: name for name, number in TYPED.items()}
    for r in recorded:
        name = by_id.get(r["msgid"])
        if name is None:   # a frame of an id the spec does not type (pyunigps's test frames)
            continue
        o = out.setdefault(name, Outcome(name))
        o.count += 1
        data = logs[r["log"]][r["index"]]
        message = unicore_messages.decode(data)
        o.round_trip += message.encode() == data
        ours: dict[str, tuple[str, Any]] = {}
        for key, value in message.to_dict().items():
            if key == "message":
                continue
            if key == "header":   # the frame's header fields the message keeps
                ours.update({HEADER_NAMES[k]: (f"header.{k}", v) for k, v in value.items() if k in HEADER_NAMES})
                continue
            if isinstance(value, list):   # a group: its entries' fields, numbered from 1
                for i, entry in enumerate(value, 1):
                    ours.update({f"{theirs_name(name, k)}_{i:02d}": (k, v) for k, v in entry.items()})
            elif isinstance(value, dict):   # a bit field's parts
                ours.update({theirs_name(name, k): (k, v) for k, v in value.items()})
            else:   # (an enum's code, not its id)
                ours[theirs_name(name, key)] = (key, getattr(message, key))
        for key, (field_id, value) in ours.items():
            if field_id in NOT_COMPARED:
                o.not_compared.add(field_id)
                continue
            if field_id.startswith("reserved") or key not in r["values"]:
                continue
            theirs = r["values"][key]
            o.fields[field_id] += 1
            if isinstance(value, Enum):
                value = int(value.value)
            if _equal(value, theirs):
                o.agree[field_id] += 1
            elif len(o.differ) < 5:
                o.differ.append(f"{r['log']} frame {r['index']} {field_id}: ours {value!r}, pyunigps {theirs!r}")
        for key in r["values"]:
            if key not in ours and not key.startswith("reserved"):
                o.missing.add(key)
    return [out[name] for name in TYPED if name in out]


def render(found: list[Outcome]) -> str:
    version = json.loads(RECORD.read_text().splitlines()[0])["pyunigps"]
    lines = ["# Unicore binary messages: agreement with pyunigps", "",
             "Written by `.venv/bin/python -m tests.ubx.pyunigps_oracle`; tests/ubx/test_binary_messages.py",
             f"fails when it is stale. pyunigps {version}'s values of the typed Unicore messages (recorded in",
             "tests/data/unicore/pyunigps_decoded.jsonl by `python -m tests.ubx.pyunigps_oracle --record` in a",
             "venv that has pyunigps) against the values nmeaspec.unicore_messages decodes from the same frames,",
             "field by field (floats within 1e-9 relative; text without its NUL or space padding). No public",
             "receiver log with Unicore binary frames was found: the frames are pyunigps's example frames",
             "(tests/data/unicore/pyunigps_frames.log, none of a typed message: see below) and one frame per",
             "typed message that pyunigps built from chosen values (tests/data/unicore/pyunigps_built.log,",
             "PROVENANCE.md; their header's CPU idle, time and status fields set, none zero). The header's",
             "fields (header.*) are compared as the others are. Round trip: the decoded message encodes back to",
             "its frame, byte for byte.", "",
             "| message | frames | round trip | fields agreeing / compared |",
             "| --- | ---: | ---: | --- |"]
    for o in found:
        fields = ", ".join(f"{k}: {o.agree[k]} / {n}" for k, n in o.fields.items())
        lines.append(f"| {o.message} | {o.count} | {o.round_trip} / {o.count} | {fields} |")
    lines += ["", "## Differences", "",
              "- pyunigps's example frame of a 308-byte VERSION-like body (pyunigps_frames.log, the third) "
              "carries message id 17, not VERSION's 37 (the manual's id, and pyunigps 1.0.1's own table): "
              "pyunigps decodes it as an unknown message, and so do we."]
    notes = [f"- {o.message}: pyunigps's {name}, not typed here: {LEFT_OUT.get(name, 'no reason known')}."
             for o in found for name in sorted(o.missing)]
    for name in sorted({n for o in found for n in o.not_compared}):
        notes.append(f"- Our {name} ({', '.join(o.message for o in found if name in o.not_compared)}) not "
                     f"compared: {NOT_COMPARED[name]}.")
    notes += [f"- {o.message}: {d}" for o in found for d in o.differ]
    lines += notes
    return "\n".join(lines) + "\n"


if __name__ == "__main__":
    if "--build" in sys.argv:
        build()
    elif "--record" in sys.argv:
        record()
    else:
        DOC.write_text(render(outcomes()))
