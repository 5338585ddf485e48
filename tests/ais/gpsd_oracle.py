"""gpsd as an independent oracle of the AIS decoder: every message of gpsd's AIS samples
(tests/data/ais, PROVENANCE.md) decoded by nmeaspec.ais_messages and compared field by field with
the JSON gpsd decodes it to (unscaled: raw integers). gpsd's names are mapped to ours here.

The agreement per message type and each disagreement with its reason are in docs/ais-agreement.md
(test_gpsd_oracle.py keeps it current); `.venv/bin/python -m tests.ais.gpsd_oracle` writes it again."""

from __future__ import annotations

import json
import sys
from collections.abc import Iterator
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parents[2]
DATA = ROOT / "tests" / "data" / "ais"
sys.path.insert(0, str(ROOT / "generated" / "python"))

from nmeaspec import ais  # noqa: E402
from nmeaspec.ais_messages import APPLICATIONS, decode_payload  # noqa: E402
from nmeaspec.runtime import NmeaError  # noqa: E402

# gpsd's key of a field where it is not our id.
GPSD_KEYS = {"message_type": "type", "station_type": "stationtype", "ship_type": "shiptype"}
# Keys of gpsd's JSON that are no field: its own, the texts of codes, and composites built below.
NOT_FIELDS = {"class", "device", "scaled", "status_text", "shiptype_text", "epfd_text", "aid_type_text",
              "stationtype_text"}


def known_reason(message_type: int, key: str, ours: Any, theirs: Any) -> str | None:
    """Why gpsd's value differs from ours, where the difference is gpsd's (None: ours is wrong)."""
    if key == "vendorid" and isinstance(theirs, str) and theirs.startswith(ours):
        return ("gpsd reads the vendor ID as 7 characters (ITU-R M.1371-3), through the model and serial "
                "number bits M.1371-4 carved out of it; ours is the 3 characters M.1371-5 gives")
    if message_type == 26 and key == "radio" and theirs == 0:
        return "gpsd does not decode type 26's communication state (it reports 0); ours is the last 20 bits"
    if key == "message" and message_type == 1:
        return ("a type 1 of 163 bits, 5 short (sample.aivdm says so): gpsd reads its radio state from the "
                "14 bits left; ours refuses it (short_payload)")
    if message_type == 26 and key == "data" and ours[:-2] == theirs[:-2]:
        return ("gpsd copies type 26's data bytes whole and does not clear the bits of the last byte after "
                "the data, which belong to the communication state; ours writes them as 0 (gpsd's form)")
    return None


# Why ours keeps as data the bits of a DAC and FI in gpsd's samples (spec/ais/messages/
# addressed_binary.yaml and broadcast_binary.yaml say so too).
NOT_PUBLIC = "its layout is not public"
KEPT_AS_DATA = {
    (0, 29): NOT_PUBLIC, (200, 3): NOT_PUBLIC, (232, 1): NOT_PUBLIC, (669, 11): NOT_PUBLIC, (211, 1): NOT_PUBLIC,
    (415, 1): NOT_PUBLIC, (366, 56): NOT_PUBLIC + " (encrypted)", (366, 57): NOT_PUBLIC + " (encrypted)",
}


def kept_as_data(t: int, dac: int, fid: int, c: ApplicationAgreement) -> str | None:
    """Why none of the messages of a DAC and FI in a type `t` decode as an application (None: some do)."""
    if c.ours:
        return None
    if (t, dac, fid) in APPLICATIONS:
        return "every sample is cut short of the layout (below)"
    return KEPT_AS_DATA.get((dac, fid), "UNEXPLAINED: no application describes it")


def least_bits(application: type[ais.Application]) -> int:
    """The fewest data bits an application's layout reads: its required fields of fixed width and
    the fewest entries of its groups."""
    return sum(item.width or 0 if isinstance(item, ais.Field) and not item.optional else
               item.min * item.entry_width if isinstance(item, ais.Group) else 0 for item in application.LAYOUT)


def cut_short(application: type[ais.Application], data: str) -> str | None:
    """Why gpsd decodes an application from data bits ours keeps: the frame is too short for it."""
    have, need = int(data.split(":")[0]), least_bits(application)
    if have >= need:
        return None
    return (f"gpsd's sample carries {have} data bits, short of the {need} DAC {application.DAC} FI {application.FID} "
            "needs: gpsd reads zeros past the frame's end, ours keeps its bits as data")


@dataclass
class Disagreement:
    where: str
    message_type: int
    key: str
    ours: Any
    theirs: Any
    reason: str | None


@dataclass
class TypeAgreement:
    messages: int = 0          # messages compared
    agree: int = 0             # messages whose every compared field agrees
    fields: int = 0            # field values compared
    disagreements: list[Disagreement] = field(default_factory=list)
    applications: dict[tuple[int, int], ApplicationAgreement] = field(default_factory=dict)
    """Its binary messages by the DAC and FI they carry."""


@dataclass
class ApplicationAgreement:
    messages: int = 0          # messages of the DAC and FI gpsd decoded
    ours: int = 0              # those our application decodes (the rest keep their data bits)
    fields: int = 0            # the application's field values compared
    differences: int = 0


def text(value: str) -> str:
    """Six-bit text as gpsd writes it: up to its first `@`, trailing spaces left out."""
    return value.split("@")[0].rstrip(" ")


def data_json(bits: str) -> str:
    """Binary data as gpsd writes it: its bit count, then its bytes in hex, the last padded with 0."""
    padded = bits + "0" * (-len(bits) % 8)
    return f"{len(bits)}:" + "".join(f"{int(padded[i:i + 8], 2):02x}" for i in range(0, len(padded), 8))


def raw_value(message: Any, f: ais.Field) -> Any:
    """A field's value as gpsd writes it (unscaled); `message` a record or a group's entry."""
    value = getattr(message, f.id)
    if isinstance(f, ais.Unsigned):
        return message.raw(f.id) if isinstance(message, ais.Record) else int(f.raw_number(value, ""))
    if isinstance(f, ais.Code):
        return int(value.value) if not isinstance(value, int) else value
    if isinstance(f, ais.Text):
        return text(value)
    if isinstance(f, ais.Data):
        return data_json(value)
    return value


def application_in_gpsd_form(application: ais.Application) -> dict[str, Any]:
    """An application's fields as gpsd names and writes them (raw integers), and its data bits."""
    out = {f.id: raw_value(application, f) for f in application.FIELDS.values()
           if getattr(application, f.id) is not None}
    for group in (item for item in application.LAYOUT if isinstance(item, ais.Group)):
        # gpsd writes a group as a list of objects (DAC 1 FI 14 and FI 32: `tidals`)
        # (an entry's choice: the fields of the case it took)
        out[group.id] = [{f.id: raw_value(entry, f) for f in ais.flat_fields(group.fields) if getattr(entry, f.id) is not None}
                         for entry in getattr(application, group.id)]
    # the data bits it is sent as: what gpsd gives for an application it does not decode
    out["data"] = data_json(application.bits("AIS application"))
    if {"day", "hour", "minute"} <= out.keys():  # DAC 1 FI 11 and FI 31
        out["timestamp"] = "{:02d}T{:02d}:{:02d}Z".format(*(out.pop(k) for k in ("day", "hour", "minute")))
    return out


def ours_in_gpsd_form(message: ais.Message) -> dict[str, Any]:
    """The message's fields, and its application's, as gpsd names and writes them (raw integers)."""
    out: dict[str, Any] = {}
    if message.application is not None:
        out.update(application_in_gpsd_form(message.application))
    for item in message.LAYOUT:
        if isinstance(item, ais.Group):
            for n, entry in enumerate(getattr(message, item.id), 1):
                for f in item.fields:
                    if f.id != "seqno":  # gpsd keeps no acknowledgement's sequence number
                        out[f"{f.id}{n}"] = getattr(entry, f.id)
            continue
        for f in (item,) if isinstance(item, ais.Field) else item.fields:
            if getattr(message, f.id) is not None:
                out[GPSD_KEYS.get(f.id, f.id)] = raw_value(message, f)
    t = out["type"]
    if t in (4, 11):
        out["timestamp"] = "{:04d}-{:02d}-{:02d}T{:02d}:{:02d}:{:02d}Z".format(
            *(out.pop(k) for k in ("year", "month", "day", "hour", "minute", "second")))
    if t == 5:
        out["eta"] = "{:02d}-{:02d}T{:02d}:{:02d}Z".format(
            *(out.pop(k) for k in ("eta_month", "eta_day", "eta_hour", "eta_minute")))
    if t == 21:
        out["name"] = text(getattr(message, "name") + getattr(message, "name_ext"))
        out.pop("name_ext")
    if t in (25, 26) and "dac" in out:
        out["app_id"] = out.pop("dac") * 64 + out.pop("fid")
    return out


def compare(where: str, payload: str, fill_bits: int, theirs: dict[str, Any],
            agreement: dict[int, TypeAgreement]) -> None:
    t = theirs["type"]
    tally = agreement.setdefault(t, TypeAgreement())
    tally.messages += 1
    try:
        message = decode_payload(payload, fill_bits)
        ours = ours_in_gpsd_form(message)
    except NmeaError as err:
        tally.disagreements.append(Disagreement(where, t, "message", str(err), "decoded",
                                                known_reason(t, "message", err, theirs)))
        return
    carried: ApplicationAgreement | None = None
    from_application: set[str] = set()
    cut = False
    if t in (6, 8) and "dac" in theirs:
        carried = tally.applications.setdefault((theirs["dac"], theirs["fid"]), ApplicationAgreement())
        carried.messages += 1
        if message.application is not None:
            carried.ours += 1
            from_application = set(application_in_gpsd_form(message.application))
        elif "data" not in theirs and (t, theirs["dac"], theirs["fid"]) in APPLICATIONS:
            # gpsd decoded an application whose data ours keeps: the frame must be too short for it
            data = ours["data"]
            tally.disagreements.append(Disagreement(where, t, "application", data, "decoded",
                                                    cut_short(APPLICATIONS[t, theirs["dac"], theirs["fid"]], data)))
            carried.differences += 1
            cut = True
    clean = not cut
    for key, value in theirs.items():
        if key in NOT_FIELDS:
            continue
        if key not in ours:
            continue  # a field we do not have here: an application's, a case not taken, one gpsd zero-fills
        tally.fields += 1
        mine = ours[key]
        if carried is not None and key in from_application:
            carried.fields += 1
            carried.differences += mine != value
        if mine != value:  # gpsd writes some flags as 0 and 1: equal to False and True
            clean = False
            tally.disagreements.append(Disagreement(where, t, key, mine, value, known_reason(t, key, mine, value)))
    tally.agree += clean


def pairs() -> Iterator[tuple[str, str, int, dict[str, Any]]]:
    """(where, payload, fill bits, gpsd's JSON) of every message of the samples gpsd decoded; a
    message of several sentences has its fragments' payloads joined."""
    for path in sorted(DATA.glob("*.log.chk")):
        lines = path.read_text(encoding="utf-8", errors="replace").splitlines()
        joined, fill = "", 0
        for number, line in enumerate(lines, 1):
            if not line.startswith(("!AIVDM", "!AIVDO")):
                continue
            fields = line.split("*")[0].split(",")
            joined = (joined if fields[2] != "1" else "") + fields[5]
            fill = int(fields[6])
            if fields[1] != fields[2]:
                continue
            after = lines[number] if number < len(lines) else ""
            if after.startswith('{"class":"AIS"'):
                yield f"{path.name}:{number}", joined, fill, json.loads(after)
    # sample.aivdm's decodes are one JSON line per message it decoded, in order.
    decoded = iter(json.loads(line) for line in (DATA / "sample.aivdm.ju.chk").open(encoding="utf-8"))
    pending = next(decoded, None)
    joined = ""
    for number, line in enumerate((DATA / "sample.aivdm").read_text(encoding="utf-8").splitlines(), 1):
        if not line.startswith("!") or pending is None:
            continue
        fields = line.split("*")[0].split(",")
        joined = (joined if fields[2] != "1" else "") + fields[5]
        if fields[1] != fields[2]:
            continue
        reader, _ = ais.unarmor(joined, int(fields[6]))
        if (reader.peek(0, 6, "type"), reader.peek(8, 30, "mmsi")) == (pending["type"], pending["mmsi"]):
            yield f"sample.aivdm:{number}", joined, int(fields[6]), pending
            pending = next(decoded, None)


def agreement() -> dict[int, TypeAgreement]:
    found: dict[int, TypeAgreement] = {}
    for where, payload, fill_bits, theirs in pairs():
        compare(where, payload, fill_bits, theirs, found)
    return dict(sorted(found.items()))


REPORT = ROOT / "docs" / "ais-agreement.md"


def report(found: dict[int, TypeAgreement]) -> str:
    """The agreement as Markdown: a row per message type, then each disagreement with its reason."""
    lines = [
        "# AIS messages checked against gpsd",
        "",
        "Every message of gpsd's AIS samples (tests/data/ais, PROVENANCE.md names them) decoded by",
        "`nmeaspec.ais_messages` and compared field by field, in raw integers, with the JSON gpsd",
        "decodes it to (tests/ais/gpsd_oracle.py maps gpsd's names to ours). A message agrees when",
        "every field both decode agrees. Written by `.venv/bin/python -m tests.ais.gpsd_oracle`;",
        "tests/ais/test_gpsd_oracle.py fails when it is stale or a difference has no known reason.",
        "",
        "| type | messages | agree | fields compared | differences |",
        "|---:|---:|---:|---:|---:|",
    ]
    lines += [f"| {t} | {a.messages} | {a.agree} | {a.fields} | {len(a.disagreements)} |" for t, a in found.items()]
    total = list(found.values())
    lines.append(f"| all | {sum(a.messages for a in total)} | {sum(a.agree for a in total)} "
                 f"| {sum(a.fields for a in total)} | {sum(len(a.disagreements) for a in total)} |")
    lines += ["", "## Binary applications (types 6 and 8)", "",
              "The DAC and FI of each binary message gpsd decoded; `ours` counts those whose data bits the",
              "spec's application of that DAC and FI (spec/ais/applications) decodes, the rest keep them as",
              "data (gpsd's JSON then gives either its data bits or fields of an application we lack).", "",
              "| type | DAC | FI | messages | ours | fields compared | differences |",
              "|---:|---:|---:|---:|---:|---:|---:|"]
    lines += [f"| {t} | {dac} | {fid} | {c.messages} | {c.ours} | {c.fields} | {c.differences} |"
              for t, a in found.items() for (dac, fid), c in sorted(a.applications.items())]
    lines += ["", "Those ours decodes none of:", ""]
    lines += [f"- type {t}, DAC {dac} FI {fid}: {why}." for t, a in found.items()
              for (dac, fid), c in sorted(a.applications.items()) if (why := kept_as_data(t, dac, fid, c))]
    lines += ["", "## Differences", ""]
    lines += [f"- `{d.where}`, type {d.message_type} `{d.key}`: ours `{d.ours!r}`, gpsd `{d.theirs!r}`. "
              f"{d.reason or 'UNEXPLAINED: a defect of ours'}." for a in total for d in a.disagreements]
    return "\n".join(lines) + "\n"


def main() -> None:
    REPORT.write_text(report(agreement()), encoding="utf-8")
    print(f"wrote {REPORT.relative_to(ROOT)}")


if __name__ == "__main__":
    main()
