"""pyrtcm (semuconsulting), the oracle of the RTCM 3 message contents: every frame of the logs we
hold (gpsd's, tests/data/rtcm3) decoded by the generated classes (nmeaspec.rtcm3_messages, from
spec/binary/rtcm3/messages) and by pyrtcm, compared field by field, and one made-up payload per
message number no log carries. Fields are paired by the spec's `ref`, the data field number
(DF025) that pyrtcm names its attributes by; a group entry's k-th field is pyrtcm's <DF>_<kk>.
Numbers are compared in pyrtcm's scaling (ours: the raw integer over the spec's divisor; within
1e-9, relative). The counts per message number and every difference with its reason go to
docs/rtcm3-agreement.md; `.venv/bin/python -m tests.rtcm3.pyrtcm_oracle` rewrites it."""

from __future__ import annotations

import io
import math
import random
import re
import sys
from collections import Counter
from dataclasses import dataclass, field
from functools import cache
from pathlib import Path
from typing import Any

import pyrtcm
from pyrtcm import RTCMReader

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "generated" / "python"))

from nmeaspec import ais, rtcm3, rtcm3_messages  # noqa: E402

REPORT = ROOT / "docs" / "rtcm3-agreement.md"
LOGS = [log for log in sorted((ROOT / "tests" / "data").glob("*/*.log")) if b"\xd3" in log.read_bytes()]
# pyrtcm's name of the MSM epoch time, by system (ours: epoch_time, DF004, but GLONASS's two fields)
EPOCH = {1090: "DF248", 1110: "DF428", 1120: "DF427", 1130: "DF546"}
# What pyrtcm gives that is no field of the message: counts and satellite and signal ids it derives
DERIVED = re.compile(r"^(NSat|NSig|NCell|PRN_\d+|CELLPRN_\d+|CELLSIG_\d+)$")
# The counted texts: each counter's characters (pyrtcm: one attribute a character)
COUNTED = {"DF029": "DF030", "DF032": "DF033", "DF227": "DF228", "DF229": "DF230", "DF231": "DF232"}
# Why a field differs, by its pyrtcm name (its DF number)
REASONS = {
    "DF140": "pyrtcm reads the UTF-8 code units as ISO 8859-1 characters; ours decodes them as UTF-8 "
             "(the same bytes)",
    "DF081": "scale 16 s: kept as the raw integer (our divisors are whole numbers), pyrtcm multiplies",
    "DF093": "scale 16 s: kept as the raw integer (our divisors are whole numbers), pyrtcm multiplies",
    "DF430": "scale 16 s: kept as the raw integer (our divisors are whole numbers), pyrtcm multiplies",
    "DF442": "scale 16 s: kept as the raw integer (our divisors are whole numbers), pyrtcm multiplies",
    "DF293": "scale 60 s: kept as the raw integer (our divisors are whole numbers), pyrtcm multiplies",
    "DF304": "scale 60 s: kept as the raw integer (our divisors are whole numbers), pyrtcm multiplies",
    "DF493": "scale 8 s: kept as the raw integer (our divisors are whole numbers), pyrtcm multiplies",
    "DF505": "scale 8 s: kept as the raw integer (our divisors are whole numbers), pyrtcm multiplies",
}


@dataclass
class Agreement:
    frames: int = 0
    compared: int = 0
    equal: int = 0
    encoded: int = 0
    failed: str = ""   # pyrtcm's error, when it cannot parse the frame
    only_ours: set[str] = field(default_factory=set)
    only_theirs: set[str] = field(default_factory=set)
    differing: dict[str, tuple[Any, Any]] = field(default_factory=dict)


@cache
def log_frames() -> list[tuple[str, bytes]]:
    """Each RTCM 3 frame of the logs (as pyrtcm splits them, checksum checked) and its log."""
    return [(f"{log.parent.name}/{log.name}", raw) for log in LOGS
            for raw, _ in RTCMReader(io.BytesIO(log.read_bytes()), quitonerror=0)]


def _number(f: Any, value: Any) -> Any:
    """A value of ours in pyrtcm's terms: a flag as 0/1, a special value as its raw integer over the
    divisor (pyrtcm names no special value), a mask of data bits as its integer."""
    if isinstance(value, bool):
        return int(value)
    if isinstance(value, ais.Special):
        raw = 0 if value.id == "negative_zero" else value.raw
        divisor = getattr(f, "divisor", 1)
        return raw / divisor if divisor != 1 else raw
    if isinstance(f, ais.Data):
        return int(value, 2) if value else 0
    return value


def our_fields(message: rtcm3.Message) -> dict[str, tuple[Any, Any]]:
    """Each field of ours by pyrtcm's name: (its field, its value)."""
    number = getattr(message, "message_number")
    out: dict[str, tuple[Any, Any]] = {}
    refs = {f.id: ref for f, ref in REFS[type(message)].items()}

    def put(f: Any, value: Any, suffix: str) -> None:
        name = refs[f.id]
        if f.id == "epoch_time" and number - number % 10 in EPOCH:
            name = EPOCH[number - number % 10]
        if name == "ExtSatInfo" and number - number % 10 == 1080:
            name = "DF419"   # pyrtcm's name of GLONASS's extended satellite information
        out[name + suffix] = (f, value)

    for item in type(message).LAYOUT:
        if isinstance(item, ais.Group):
            for k, entry in enumerate(getattr(message, item.id), 1):
                for f in item.fields:
                    put(f, getattr(entry, f.id), f"_{k:02d}")
        else:
            for f in ais.flat_fields((item,)):
                value = getattr(message, f.id)
                if value is not None:
                    put(f, value, "")
    return out


def their_fields(parsed: Any) -> dict[str, Any]:
    """pyrtcm's attributes; a counted text's characters (DF030_01, ...) joined as one text."""
    out: dict[str, Any] = {}
    for name, value in vars(parsed).items():
        if name.startswith("_") or DERIVED.match(name):
            continue
        chars = re.fullmatch(r"(DF030|DF033|DF228|DF230|DF232)_\d\d", name)
        if chars:
            out[chars.group(1)] = out.get(chars.group(1), "") + value
        else:
            out[name] = value
    for counter, text in COUNTED.items():   # no characters: pyrtcm has no attribute
        if counter in out:
            out.setdefault(text, "")
    return out


def same(ours: Any, theirs: Any) -> bool:
    if isinstance(ours, (int, float)) and isinstance(theirs, (int, float)):
        return math.isclose(ours, theirs, rel_tol=1e-9, abs_tol=1e-12)
    return bool(ours == theirs)


def _compare(row: Agreement, message: rtcm3.Message, parsed: Any, raw: bytes) -> None:
    row.frames += 1
    row.encoded += message.encode() == raw
    ours = our_fields(message)
    theirs = their_fields(parsed)
    row.only_ours |= {n for n in ours if n not in theirs}
    row.only_theirs |= {n for n in theirs if n not in ours}
    for name, (f, value) in ours.items():
        if name not in theirs:
            continue
        row.compared += 1
        if same(_number(f, value), theirs[name]):
            row.equal += 1
        else:
            row.differing.setdefault(name, (value, theirs[name]))


def _refs() -> dict[type, dict[Any, str]]:
    """Each message class's fields with their `ref` (read from the spec: the classes do not keep it)."""
    import yaml

    out: dict[type, dict[Any, str]] = {}
    for path in sorted((ROOT / "spec" / "binary" / "rtcm3" / "messages").glob("*.yaml")):
        data = yaml.safe_load(path.read_text(encoding="utf-8"))
        refs: dict[str, str] = {}

        def walk(items: list[dict[str, Any]]) -> None:
            for item in items:
                if "group" in item:
                    walk(item["fields"])
                elif "choice" in item:
                    for case in item["cases"]:
                        walk(case["fields"])
                else:
                    refs[item["id"]] = item.get("ref", item["id"])

        walk(data["fields"])
        cls = rtcm3_messages.BY_NUMBER[data["numbers"][0]]
        out[cls] = {f: refs[f.id] for f in [*cls.FIELDS.values(),
                                            *(g for i in cls.LAYOUT if isinstance(i, ais.Group) for g in i.fields)]}
    return out


REFS = _refs()


@cache
def field_agreement() -> dict[int, Agreement]:
    """Per message number of the logs' frames the spec describes."""
    rows: dict[int, Agreement] = {}
    for _, raw in log_frames():
        message = rtcm3_messages.decode(raw)
        if isinstance(message, rtcm3.Message):
            number = getattr(message, "message_number")
            _compare(rows.setdefault(number, Agreement()), message, RTCMReader.parse(raw), raw)
    return dict(sorted(rows.items()))


def made_up(number: int) -> bytes:
    """A frame of message `number` from bits drawn from a generator seeded with the number: masks
    of MSM messages few (up to 6 satellites, 3 signals), the rest random, cut where our layout
    ends (the padding bits zero)."""
    rng = random.Random(number)
    bits = [rng.getrandbits(1) for _ in range(8 * 1000)]
    bits[:12] = [int(b) for b in format(number, "012b")]
    cls = rtcm3_messages.BY_NUMBER[number]
    if "satellite_mask" in cls.FIELDS:
        start = 12 + 12 + 30 + 1 + 3 + 7 + 2 + 2 + 1 + 3
        satellites = set(rng.sample(range(64), rng.randint(1, 6)))
        signals = set(rng.sample(range(32), rng.randint(1, 3)))
        bits[start:start + 96] = [int(i in satellites) for i in range(64)] + [int(i in signals) for i in range(32)]
    if "satellite_count" in cls.FIELDS:   # as many satellites as the frame's 1023 bytes hold
        bits[12 + 12 + 30 + 1:12 + 12 + 30 + 1 + 5] = [int(b) for b in format(rng.randint(1, 8), "05b")]
    payload = int("".join(map(str, bits)), 2).to_bytes(1000, "big")
    message = cls.from_payload(payload)
    message.trailing = ""
    return rtcm3.frame(message.payload())


@cache
def made_up_agreement() -> dict[int, Agreement]:
    """Per message number the spec describes that no log carries."""
    logged = {raw[3] << 4 | raw[4] >> 4 for _, raw in log_frames()}
    rows: dict[int, Agreement] = {}
    for number in sorted(set(rtcm3_messages.BY_NUMBER) - logged):
        raw = made_up(number)
        message = rtcm3_messages.decode(raw)
        assert isinstance(message, rtcm3.Message)
        row = rows.setdefault(number, Agreement())
        try:
            parsed = RTCMReader.parse(raw)
        except pyrtcm.RTCMTypeError as err:   # pyrtcm 1.2.1 cannot read MSM2
            row.frames, row.encoded = 1, int(message.encode() == raw)
            row.failed = f"{type(err).__name__} (its MSM2 table of DF420 is a set, not a dict)"
            continue
        _compare(row, message, parsed, raw)
    return rows


def _reason(name: str) -> str:
    base = re.sub(r"_\d\d$", "", name)
    return REASONS.get(base, "not described by the other side")


def differences(number: int, a: Agreement) -> list[str]:
    """The rows of the differences table of one message number."""
    rows = []
    for side, names in (("ours", a.only_ours), ("pyrtcm", a.only_theirs), ("differs", set(a.differing))):
        for base in sorted({re.sub(r"_\d\d$", "", n) for n in names}):
            rows.append(f"| {number} | `{base}` | {side} | {_reason(base)} |")
    return rows


def report() -> str:
    fields = field_agreement()
    made = made_up_agreement()
    logs = Counter(log for log, _ in log_frames())
    numbers = Counter(raw[3] << 4 | raw[4] >> 4 for _, raw in log_frames())
    lines = [
        "# RTCM 3 messages: agreement with pyrtcm",
        "",
        "Written by `.venv/bin/python -m tests.rtcm3.pyrtcm_oracle`; tests/rtcm3/test_pyrtcm_oracle.py",
        "fails when it is stale. The frames are those of the logs in tests/data that hold RTCM 3",
        f"(PROVENANCE.md), as pyrtcm {pyrtcm.__version__} splits them (checksum checked).",
        "",
        "| log | frames |",
        "| --- | ---: |",
        *(f"| {name} | {count} |" for name, count in sorted(logs.items())),
        "",
        "Message numbers the spec does not describe stay frames (rtcm3.Unknown): "
        + ", ".join(f"{n} ({c} frames)" for n, c in sorted(numbers.items()) if n not in rtcm3_messages.BY_NUMBER)
        + ".",
        "",
        "## Field by field",
        "",
        "Each frame decoded by the generated classes (nmeaspec.rtcm3_messages, from spec/binary/rtcm3)",
        "and by pyrtcm; fields paired by data field number (the spec's `ref`; a group entry's k-th field",
        "pyrtcm's `<DF>_<kk>`), numbers in pyrtcm's scaling (ours: raw / divisor; within 1e-9), a",
        "special value (`invalid`, `negative_zero`) as its raw number. Encoded back: the frames our",
        "classes write back byte-exact from the decoded message.",
        "",
        "| message | frames | values compared | equal | encoded back byte-exact |",
        "| --- | ---: | ---: | ---: | ---: |",
        *(f"| {n} | {a.frames} | {a.compared} | {a.equal} | {a.encoded} |" for n, a in fields.items()),
        "",
        "Fields one side has and the other does not, or whose values differ, and why (pyrtcm's",
        "satellite and cell counts and ids, NSat, NSig, NCell, PRN, CELLPRN, CELLSIG, are derived, no",
        "fields, and left out):",
        "",
        "| message | field | side | why |",
        "| --- | --- | --- | --- |",
        *(row for n, a in fields.items() for row in differences(n, a)),
        "",
        "## Messages no log carries",
        "",
        "Each message number the spec describes that no frame of the logs has, decoded from a made-up",
        "payload (bits drawn from a generator seeded with the number; MSM masks of up to 6 satellites",
        "and 3 signals) by our class and by pyrtcm, compared as above.",
        "",
        "| message | values compared | equal | encoded back byte-exact | pyrtcm |",
        "| --- | ---: | ---: | ---: | --- |",
        *(f"| {n} | {a.compared} | {a.equal} | {'yes' if a.encoded == a.frames else 'no'} | "
          f"{'fails: ' + a.failed if a.failed else 'parses'} |" for n, a in made.items()),
        "",
        "| message | field | side | why |",
        "| --- | --- | --- | --- |",
        *(row for n, a in made.items() for row in differences(n, a)),
    ]
    lines.append("")
    return "\n".join(lines)


if __name__ == "__main__":
    REPORT.write_text(report(), encoding="utf-8")
