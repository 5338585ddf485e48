"""pyais (https://github.com/M0r13n/pyais, MIT) as a second oracle of the AIS decoder: every
message of gpsd's AIS samples (the pairs of gpsd_oracle.py) decoded by both and compared field by
field in units (pyais scales numbers and names special values by their number). pyais is a
dependency of the tests only (requirements.txt), never of the generated code.

Run it to print the agreement per message type and each difference with its reason:
`.venv/bin/python -m tests.ais.pyais_oracle`."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from . import gpsd_oracle
from .gpsd_oracle import Disagreement, TypeAgreement
from nmeaspec import ais
from nmeaspec.ais_messages import decode_payload
from nmeaspec.runtime import NmeaError


def _renamed(message_type: int, key: str) -> str:
    """Our id of a pyais key."""
    common = {"msg_type": "message_type", "spare_1": "spare", "spare_2": "spare2", "spare_3": "spare3",
              "spare_4": "spare4", "empty_1": "empty1", "empty_2": "empty2"}
    if key in common:
        return common[key]
    if key == "ship_type":
        return "ship_type" if message_type == 23 else "shiptype"
    if message_type == 5 and key in ("month", "day", "hour", "minute"):
        return f"eta_{key}"
    if key == "reserved_1":
        return "reserved" if message_type in (18, 19) else "regional"
    if key == "reserved_2":
        return "regional"
    return key


def known_reason(message_type: int, key: str, ours: Any, theirs: Any) -> str | None:
    """Why pyais's value differs from ours, where the difference is pyais's (None: ours is wrong)."""
    if key == "turn":
        return "pyais gives the rate of turn in degrees per minute, (raw / 4.733)²; ours is the ROT_AIS indicator"
    if message_type in (17, 22, 23) and key.endswith(("lon", "lat")) and isinstance(theirs, float) \
            and abs(theirs / 60 - ours) < 1e-9:
        return "pyais gives these 1/10-minute coordinates in minutes, not degrees"
    if message_type == 17 and key == "lat" and isinstance(theirs, float) \
            and abs(theirs * 10 - 2**17 - ours * 600) < 1e-6:
        return "pyais reads type 17's latitude as unsigned: a southern one comes out above 2^16 / 10 minutes"
    if key in ("ship_type", "epfd") and isinstance(theirs, int) and theirs < ours:
        return ("pyais folds a code its enum lacks into another (0, not available, or the first of a reserved "
                "range); ours keeps the code")
    if key in ("name_ext", "full_name") and isinstance(theirs, str) and theirs.startswith(ours) \
            and len(theirs) == len(ours) + 1:
        return "pyais reads the bits after the extension's last whole character as one more character"
    if message_type == 26 and key == "radio" and theirs is None:
        return "pyais does not decode type 26's communication state"
    if message_type == 26 and key == "data" and theirs.startswith(ours[:-1]) and len(theirs) > len(ours):
        return "pyais keeps type 26's communication state in its data"
    if message_type == 26 and key == "data" and theirs.startswith(ours[2:-1]):
        return ("pyais reads an application identifier from an addressed unstructured type 26: its data starts "
                "16 bits late")
    if key == "message":
        return "a payload ours refuses (short_payload)"
    return None


def unit_value(record: ais.Record, f: ais.Field) -> Any:
    """A field's value as pyais gives it: a number in its unit, also a special value's."""
    value = getattr(record, f.id)
    if value is None:
        return None
    if isinstance(f, ais.Unsigned):
        raw = record.raw(f.id)
        assert raw is not None
        return (raw / f.divisor if f.divisor != 1 else raw) + f.base
    if isinstance(f, ais.Code):
        return value if isinstance(value, int) else int(value.value)
    if isinstance(f, ais.Text):
        return value.rstrip("@").strip(" ")
    if isinstance(f, ais.Data):
        padded = value + "0" * (-len(value) % 8)
        return bytes(int(padded[i:i + 8], 2) for i in range(0, len(padded), 8))
    return value


def ours_in_pyais_form(message: ais.Message) -> dict[str, Any]:
    out = {f.id: unit_value(message, f) for f in message.FIELDS.values()}
    t = out["message_type"]
    for group in (item for item in message.LAYOUT if isinstance(item, ais.Group)):
        for n, entry in enumerate(getattr(message, group.id), 1):
            for f in group.fields:
                key = {"mmsi": f"mmsi{n}", "seqno": f"mmsiseq{n}"}.get(f.id, f"{f.id}{n}")
                out[key] = getattr(entry, f.id)
    if t == 21:
        out["full_name"] = getattr(message, "name").rstrip("@").strip(" ") + out.pop("name_ext")
    if t in (25, 26) and out.get("dac") is not None:
        out["app_id"] = out["dac"] * 64 + out["fid"]
    return {k: v for k, v in out.items() if v is not None}


def same(ours: Any, theirs: Any) -> bool:
    if theirs is None:
        return ours == ""  # pyais: no name extension
    if isinstance(theirs, float) and not isinstance(ours, bool):
        return isinstance(ours, (int, float)) and abs(theirs - ours) <= 1e-6  # pyais rounds to 6 decimals
    return bool(ours == theirs)


def agreement(pyais_decode: Callable[[str], Any]) -> dict[int, TypeAgreement]:
    """Per message type, the messages and fields compared and each difference (a pyais field we
    do not have, e.g. of an application we do not describe, is not compared)."""
    found: dict[int, TypeAgreement] = {}
    for where, payload, fill_bits, _ in gpsd_oracle.pairs():
        theirs = pyais_decode(f"!AIVDM,1,1,,A,{payload},{fill_bits}*00").asdict()
        t = theirs["msg_type"]
        tally = found.setdefault(t, TypeAgreement())
        tally.messages += 1
        try:
            ours = ours_in_pyais_form(decode_payload(payload, fill_bits))
        except NmeaError as err:
            tally.disagreements.append(Disagreement(where, t, "message", str(err), "decoded",
                                                    known_reason(t, "message", err, theirs)))
            continue
        clean = True
        for key, value in theirs.items():
            mine = ours.get(_renamed(t, key))
            if mine is None:
                continue
            tally.fields += 1
            if not same(mine, value):
                clean = False
                tally.disagreements.append(Disagreement(where, t, key, mine, value, known_reason(t, key, mine, value)))
        tally.agree += clean
    return dict(sorted(found.items()))


def main() -> None:
    from pyais import decode

    found = agreement(lambda line: decode(line, error_if_checksum_invalid=False))
    print("type  messages  agree  fields  differences (explained)")
    for t, a in found.items():
        explained = sum(1 for d in a.disagreements if d.reason)
        print(f"{t:4}  {a.messages:8}  {a.agree:5}  {a.fields:6}  {len(a.disagreements)} ({explained})")
    for a in found.values():
        for d in a.disagreements:
            print(f"{d.where}: type {d.message_type} {d.key}: ours {d.ours!r}, pyais {d.theirs!r}: "
                  f"{d.reason or 'UNEXPLAINED'}")


if __name__ == "__main__":
    main()
