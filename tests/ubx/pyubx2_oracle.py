"""pyubx2 (semuconsulting), the oracle of the UBX frames that gpsd's regression logs carry
(tests/data/ubx): every frame our reader splits out must be one pyubx2 accepts (checksum
validated) and serializes back to the same bytes, and every field our generated classes
(nmeaspec.ubx_messages) decode must hold pyubx2's value for it. Fields are paired by name: ours
are u-blox's names in snake case (h_msl for hMSL), a group entry's k-th field is pyubx2's
<name>_<kk>. The counts per message go to docs/ubx-agreement.md;
`.venv/bin/python -m tests.ubx.pyubx2_oracle` rewrites it."""

from __future__ import annotations

import math
import random
import re
import sys
from collections import Counter
from dataclasses import dataclass, field
from enum import Enum
from pathlib import Path
from typing import Any

import pyubx2

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "generated" / "python"))

from nmeaspec import ubx, ubx_messages  # noqa: E402

DATA = ROOT / "tests" / "data" / "ubx"
REPORT = ROOT / "docs" / "ubx-agreement.md"
# pyubx2 tells a message's direction by the mode it is parsed in: receiver output first.
MODES = (pyubx2.GET, pyubx2.SET, pyubx2.POLL)


def log_frames() -> list[tuple[str, bytes, ubx.Frame]]:
    """(log name, the frame's bytes as logged, the frame) for every frame of every log."""
    frames = []
    for log in sorted(DATA.glob("*.log")):
        data = log.read_bytes()
        for pos, frame in ubx.split_frames(data):
            frames.append((log.name, data[pos:pos + len(frame.payload) + 8], frame))
    return frames


def pyubx2_message(raw: bytes) -> Any:
    """pyubx2's message of `raw`, parsed as receiver output, else as input, else as a poll."""
    error: Exception | None = None
    for mode in MODES:
        try:
            message = pyubx2.UBXReader.parse(raw, validate=pyubx2.VALCKSUM, msgmode=mode)
        except (pyubx2.UBXParseError, pyubx2.UBXMessageError, pyubx2.UBXTypeError) as exc:
            error = exc
            continue
        return message
    raise AssertionError(f"pyubx2 rejects {raw.hex(' ')}: {error}")


def pyubx2_identity(raw: bytes) -> tuple[str, bytes]:
    """pyubx2's name of the message in `raw` and its serialization of what it parsed."""
    message = pyubx2_message(raw)
    return message.identity, message.serialize()


def _key(name: str) -> str:
    """A field name as both sides spell it: lower case, no underscores (hMSL, h_msl: hmsl)."""
    return name.replace("_", "").lower()


def our_fields(message: ubx.Message) -> dict[str, Any]:
    """Our decoded message by pyubx2's keys (an enum member as its code, as pyubx2 has no enums; a
    group entry's fields suffixed with its number); the raw integers beside scaled values left
    out."""
    def members(record: Any, fields: Any, suffix: str) -> dict[str, Any]:
        out = {}
        for f in fields:
            value = getattr(record, f.id)
            if value is not None and not isinstance(f, ubx.Group):
                out[_key(f.id) + suffix] = _plain(value)
        return out

    out = members(message, message.FIELDS.values(), "")
    for group in (item for item in message.LAYOUT if isinstance(item, ubx.Group)):
        fields = [f for item in group.fields for f in ubx.flat_fields((item,))]
        for k, entry in enumerate(getattr(message, group.id), 1):
            out.update(members(entry, fields, f"_{k:02d}"))
    return out


def _plain(value: Any) -> Any:
    """A member's value as pyubx2 gives it: an enum member as its code, bytes as hex."""
    if isinstance(value, Enum):
        return int(value.value)
    return value.hex() if isinstance(value, bytes) else value


def their_fields(message: Any) -> dict[str, Any]:
    out = {}
    for name, value in vars(message).items():
        if name.startswith("_"):
            continue
        group = re.fullmatch(r"(.*?)_(\d\d)", name)
        out[f"{_key(group[1])}_{group[2]}" if group else _key(name)] = value
    return out


def same(ours: Any, theirs: Any) -> bool:
    """Whether our value is pyubx2's (its scaled numbers within rounding)."""
    if isinstance(theirs, bytes):   # characters or a bitfield word pyubx2 keeps as bytes
        return bool(ours.encode("latin-1") == theirs if isinstance(ours, str) else
                    ours == int.from_bytes(theirs, "little"))
    if isinstance(theirs, list) and isinstance(ours, str):   # our bytes (hex), its list of byte values
        return bytes.fromhex(ours) == bytes(theirs)
    if isinstance(ours, str) and isinstance(theirs, int):   # our bytes (hex), its little-endian integer
        return int.from_bytes(bytes.fromhex(ours), "little") == theirs
    if isinstance(theirs, float) or isinstance(ours, float):
        return math.isclose(ours, theirs, rel_tol=1e-9, abs_tol=1e-12)
    return bool(ours == theirs)


@dataclass
class Agreement:
    """One message's agreement: its frames, field values compared and equal, the frames we encode
    back byte-exact, fields one side has that the other lacks, and the differing fields."""

    frames: int = 0
    compared: int = 0
    equal: int = 0
    encoded: int = 0
    only_ours: set[str] = field(default_factory=set)
    only_theirs: set[str] = field(default_factory=set)
    differing: Counter[str] = field(default_factory=Counter)
    words: set[str] = field(default_factory=set)   # our bitfield words (keys)
    whole: set[str] = field(default_factory=set)   # our parts of a word pyubx2 keeps whole (keys)


def _compare(row: Agreement, message: ubx.Message, theirs: Any) -> None:
    """Adds one decoded message and pyubx2's decode of the same frame to `row`."""
    ours, their_values = our_fields(message), their_fields(theirs)
    for name, value in ours.items():
        if name not in their_values:
            row.only_ours.add(name)
            continue
        row.compared += 1
        if same(value, their_values[name]):
            row.equal += 1
        else:
            row.differing[name] += 1
    row.only_theirs |= {name for name in their_values if name not in ours}
    words = [f for f in message.FIELDS.values() if isinstance(f, ubx.Bitfield)]
    for group in (item for item in message.LAYOUT if isinstance(item, ubx.Group)):
        words += [f for f in group.fields if isinstance(f, ubx.Bitfield)]
    row.words |= {_key(f.id) for f in words}
    row.whole |= {_key(part.id) for f in words for _, part in f.parts
                  if _key(f.id) in their_values or _key(f.id) + "_01" in their_values}


def field_agreement() -> dict[str, Agreement]:
    """Per message our classes decode: how its fields agree with pyubx2's."""
    out: dict[str, Agreement] = {}
    for _, raw, frame in log_frames():
        message = ubx_messages.message(frame)
        if isinstance(message, ubx.Unknown):
            continue
        row = out.setdefault(message.ADDRESS, Agreement())
        row.frames += 1
        row.encoded += message.encode() == raw
        _compare(row, message, pyubx2_message(raw))
    return out


ENTRIES = 2   # the entries of each group of a made-up payload
# The type byte of layouts the spec tells apart by length alone, which pyubx2 reads to pick its layout (a
# layout with a selector, MGA-GPS's and MGA-INI's, gets its SELECT value).
TYPE_BYTES = {"mga_ack": 1, "mga_ano": 0, "rxm_rlm": 2, "rxm_rlm_short": 1}
# The field that tells how many bytes the trailing bytes field holds, which pyubx2 reads as its count (the
# spec's bytes field takes the bytes left): set to the made-up bytes' number.
SIZE_FIELDS = {"mga_flash_data": "size", "rxm_pmp_v1": "num_bytes_user_data"}
TEXT_BYTES = 6   # the made-up bytes of a text or bytes field that takes the bytes left


def made_up_payload(cls: type[ubx.Message], draw: random.Random) -> bytes:
    """A payload of layout `cls` with bytes drawn from `draw`: its selector (version, type) set,
    each group given ENTRIES entries (its count field or part set to say so), a text or byte field
    of the bytes left given six letters."""
    counts = {item.count for item in cls.LAYOUT if isinstance(item, ubx.Group) and isinstance(item.count, str)}
    out = bytearray()
    for item in cls.LAYOUT:
        if isinstance(item, ubx.Group):
            number = item.count if isinstance(item.count, int) else ENTRIES
            out += bytes(draw.randrange(256) for _ in range(number * item.entry_width // 8))
            continue
        if item.width is None:
            out += bytes(draw.choice(b"ABCDEFGHIJKLMNOPQRSTUVWXYZ") for _ in range(TEXT_BYTES))
            continue
        raw = draw.getrandbits(item.width)
        if cls.SELECT is not None and item.id == cls.SELECT[0]:
            raw = cls.SELECT[2]
        if item.id == "type" and cls.ID in TYPE_BYTES:
            raw = TYPE_BYTES[cls.ID]
        if item.id in counts:
            raw = ENTRIES
        if SIZE_FIELDS.get(cls.ID) == item.id:
            raw = TEXT_BYTES
        for low, part in getattr(item, "parts", ()):
            if part.id in counts:
                width = part.width or 1
                raw = raw & ~(((1 << width) - 1) << low) | ENTRIES << low
        out += raw.to_bytes(item.width // 8, "little")
    return bytes(out)


def made_up_agreement() -> dict[str, Agreement]:
    """Per layout with a payload that no log carries: how its fields agree with pyubx2's on a
    made-up payload (made_up_payload, from a generator seeded with the layout's id), parsed by
    pyubx2 in the mode of the layout's direction."""
    logged = {message.ID for _, _, frame in log_frames() for message in [ubx_messages.message(frame)]
              if isinstance(message, ubx.Message)}
    out: dict[str, Agreement] = {}
    for layouts in ubx_messages.BY_ID.values():
        for cls in layouts:
            if cls.ID in logged or not cls.LAYOUT:
                continue
            payload = made_up_payload(cls, random.Random(cls.ID))
            frame = ubx.Frame(cls.CLASS, cls.MSG_ID, payload)
            chosen = ubx_messages.message(frame)   # a layout told from it by its direction alone: the first
            assert isinstance(chosen, cls) or not set(type(chosen).DIRECTIONS) & set(cls.DIRECTIONS), cls.ID
            message = cls.from_payload(payload)
            mode = (pyubx2.GET if "output" in cls.DIRECTIONS else pyubx2.SET if "input" in cls.DIRECTIONS
                    else pyubx2.POLL)
            row = out.setdefault(cls.ID, Agreement())
            row.frames += 1
            row.encoded += message.encode() == frame.encode()
            if cls.ID in PYUBX2_FAILS:   # checked by the test: pyubx2 still fails on it
                continue
            _compare(row, message, pyubx2.UBXReader.parse(frame.encode(), msgmode=mode))
    return dict(sorted(out.items()))


# Layouts pyubx2 cannot parse, and why: the made-up agreement decodes and encodes them, compares none
# (CFG-FIXSEED and AID-ALM wait in tests/ubx/pending).
PYUBX2_FAILS = {
    "cfg_fixseed": "pyubx2 1.4.0 names a field `length`, which clashes with its message's length property",
    "aid_alm": "pyubx2 1.4.0 fails on its optional block of almanac words (optBlock) as receiver output",
    "aid_alm_empty": "pyubx2 1.4.0 fails on its optional block of almanac words (optBlock) as receiver output",
}


def agreement() -> dict[str, tuple[int, int]]:
    """Per pyubx2 identity: (frames, frames pyubx2 serializes back byte-exact)."""
    frames: Counter[str] = Counter()
    same: Counter[str] = Counter()
    for _, raw, _ in log_frames():
        identity, serialized = pyubx2_identity(raw)
        frames[identity] += 1
        same[identity] += serialized == raw
    return {identity: (frames[identity], same[identity]) for identity in sorted(frames)}


# Why a field one side has is missing on the other, or differs, by field (pyubx2's keys).
HIGH_PRECISION = ("pyubx2 adds the high precision component to the standard one (its lat is lat + lat_hp); we keep "
                  "both as sent")
NEWER = "a bit that newer F9 firmware names and the layout's document reserves"
REASONS = {
    "sec": "u-blox names the second `sec`; pyubx2 `second`",
    "second": "u-blox names the second `sec`; pyubx2 `second`",
    "authtime": NEWER, "nmafixstatus": NEWER, "authstatus": NEWER, "tpnotlocked": NEWER,
    "clascorrused": NEWER, "lppcorrused": NEWER, "hascorrused": NEWER,
    "msgsource": NEWER,
    "sigcfgmask": "u-blox names the mask `sigCfgMask`; pyubx2 `sigCfMask`",
    "sigcfmask": "u-blox names the mask `sigCfgMask`; pyubx2 `sigCfMask`",
    **{name: "pyubx2 reads one protocol's block with a group of six port masks; ours a group of blocks (a protocol "
             "and its six named port masks)"
       for name in ("protocolid", "enableerror", "enablewarning", "enablenotice", "enabletest", "enabledebug")},
    **{name: "pyubx2 decodes the configuration items by key (cfg_0x..., keys_NN); ours keep the key ids as a group "
             "of u4 and the key-value pairs as cfg_data bytes (the configuration database decodes them)"
       for name in ("key", "keys", "cfgdata")},
    "action": "version 0 reserves the byte that version 1 gives the transaction; pyubx2 names it `action`",
    "text": "an INF message's text: ours `text`, pyubx2 `message`",
    "message": "an INF message's text: ours `text`, pyubx2 `message`",
    "version": "the message version byte, which the M8 document reserves and pyubx2 counts in a reserved field",
    **{name: "u-blox names the uncertainties `intDeltaFreqUnc`, `extDeltaFreqUnc`; pyubx2 ends them in `U`"
       for name in ("intdeltafrequnc", "extdeltafrequnc", "intdeltafrequ", "extdeltafrequ")},
    "bytes": "LOG-STRING's text: ours one text field, pyubx2 its bytes one by one (bytes_NN)",
    **{name: "MON-COMMS's messages parsed per protocol: ours msgs0..msgs3 of each port, pyubx2 a nested group "
             "(msgs_PP_NN)" for name in ("msgs0", "msgs1", "msgs2", "msgs3", "msgs01", "msgs02")},
    "outputport": "bits of MON-COMMS txErrors that pyubx2 names and the F9 document at hand does not; kept in the word",
    **{name: "pyubx2 reads one MON-IO port block; ours the blocks of every port (a group)"
       for name in ("rxbytes", "txbytes", "parityerrs", "framingerrs", "overrunerrs", "breakcond", "rxbusy", "txbusy")},
    **{name: "pyubx2 gives the raw integer (0.01 deg); ours is in degrees, its <id>_raw pyubx2's value"
       for name in ("plposhorizorient", "plvelhorizorient")},
    **{name: "MON-SPAN's 256 spectrum bins: ours two byte fields of 128 (a fixed field holds at most 255 bytes), "
             "pyubx2 one list" for name in ("spectrum", "spectrum0", "spectrum1")},
    "data": "MGA-DBD's database bytes, MGA-FLASH-DATA's data: ours one bytes field, pyubx2 its bytes one by one "
            "(data_NN)",
    "svid": "a poll of one satellite: ours its svid, pyubx2 a group of them (svid_NN)",
    "maxdevlifetime": "u-blox names it `maxDevLifeTime`; pyubx2 `maxDevLifeTim`",
    "maxdevlifetim": "u-blox names it `maxDevLifeTime`; pyubx2 `maxDevLifeTim`",
    "mincnomask": "the mask bit u-blox names `minCno`, beside the field `minCNO`: pyubx2 keeps one of the two names",
    "beidou": "version 0 of CFG-NMEA: pyubx2 names the BeiDou filter bit `bBeidou`",
    "bbeidou": "version 0 of CFG-NMEA: pyubx2 names the BeiDou filter bit `bBeidou`",
    "extintinactivityms": "pyubx2 knows only version 2 of CFG-PM2 (48 bytes); version 1 (44 bytes) has no EXTINT inactivity",
    **{name: "a time or term in units of its scale (16 s, 60 s, 600 s, 3600 s, 4096 s, 15 min, 2^11 s and so on): "
             "ours the raw count (the unit in its name), pyubx2 the count times the scale"
       for name in ("toc", "toe", "toa", "tot", "utctot", "t0g", "tb", "beta0", "beta1", "beta2", "beta3",
                    "ionobeta0", "ionobeta1", "ionobeta2", "ionobeta3")},
    "bgde1e5b": "pyubx2 gives the raw integer (2^-32 s); ours is in seconds, its <id>_raw pyubx2's value",
    "omega": "GLONASS almanac: pyubx2 gives the raw integer (2^-15 semicircle); ours in semicircles, <id>_raw pyubx2's",
    "relposheadingvalid": "a bit version 1 names and version 0 reserves",
    "relposnormalized": "a bit version 1 names and version 0 reserves",
    "calibttag": "pyubx2 repeats the data entries over the whole payload: it reads our optional calib_ttag as one "
                 "more data entry (its datafield_NN and datatype_NN beyond num_meas)",
    "datafield": "pyubx2 reads the optional calib_ttag as one more data entry",
    "datatype": "pyubx2 reads the optional calib_ttag as one more data entry",
    "enable": "u-blox names the TX-ready enable bit `en`; pyubx2 `enable`",
    "en": "u-blox names the TX-ready enable bit `en`; pyubx2 `enable`",
    "mem": "u-blox names MON-TXBUF's memory allocation error bit `mem`; pyubx2 `lem`",
    "lem": "u-blox names MON-TXBUF's memory allocation error bit `mem`; pyubx2 `lem`",
    "rate": "the rate on the current port, or our group of the six ports' rates; pyubx2 names each port's rate",
    "rateddc": "pyubx2 names each port's rate; ours are a group of six (or the current port's one)",
    "rateuart1": "pyubx2 names each port's rate", "rateuart2": "pyubx2 names each port's rate",
    "rateusb": "pyubx2 names each port's rate", "ratespi": "pyubx2 names each port's rate",
    "reserved": "pyubx2 names each port's rate and the sixth (reserved) port's",
    **{name: "pyubx2 gives the raw integer (0.1 mm); ours is in mm, its <id>_raw pyubx2's value"
       for name in ("fixedposacc", "svinacclimit", "meanxhp", "meanyhp", "meanzhp", "meanacc")},
    **{name: HIGH_PRECISION for name in ("lon", "lat", "height", "hmsl", "lonhp", "lathp", "heighthp", "hmslhp",
                                         "relposn", "relpose", "relposd", "relposlength", "relposhpn", "relposhpe",
                                         "relposhpd", "relposhplength", "ecefx", "ecefy", "ecefz", "ecefxhp",
                                         "ecefyhp", "ecefzhp")},
}


# Why, for a field of one message or layout only (where its name means something else than in REASONS).
REASONS_OF = {
    **{("mon_batch", name): "pyubx2 1.4.0 has no MON-BATCH (an M8 message): it names it MON-0a32-NOMINAL, no "
                            "fields"
       for name in ("version", "reserved1", "filllevel", "dropsall", "dropssincemon", "nextmsgcnt")},
    **{("rxm_pmp", name): "RXM-PMP version 0's 504 bytes of user data: ours two bytes fields of 252 (a fixed field "
                          "holds at most 255 bytes), pyubx2 one" for name in ("userdata", "userdata0", "userdata1")},
    ("rxm_imes", "lat"): "IMES latitude: ours in semicircles (2^-24), pyubx2 in degrees (180 times ours)",
    ("rxm_imes", "lon"): "IMES longitude: ours in semicircles (2^-24, the M8 description's 360 * 2^-25 deg), pyubx2 "
                         "in degrees of 180 * 2^-31 deg a step (a scale 128 times finer than the description's)",
}


def _reason(name: str, words: set[str], whole: set[str] = frozenset(), where: str = "") -> str:
    base = re.sub(r"_\d\d$", "", name)
    if (where, base) in REASONS_OF:
        return REASONS_OF[where, base]
    if base in words:
        return "the bitfield word itself: pyubx2 gives only its parts (we keep the word for bits no part names)"
    if base in whole:
        return "a named part of a bitfield word pyubx2 keeps whole (the word's values agree)"
    if base in REASONS:
        return REASONS[base]
    if re.fullmatch(r"prn\d+", base):
        return "pyubx2 names each PRN bit of the SBAS scan masks; we keep the masks as words"
    if base in ("devbbr", "devflash", "deveeprom", "devspiflash"):
        return "pyubx2 reads CFG-CFG without its device mask (12 bytes) as if it had one"
    if re.fullmatch(r"sf\dd\d", base):
        return "AID-EPH's subframe words: ours fields, pyubx2 an optional group (sfNdM_01)"
    if base.startswith("cfg0x"):
        return REASONS["cfgdata"]
    if base.startswith("reserved"):
        return "reserved bytes, numbered as the document numbers them (from 1) and as pyubx2 does (from 0)"
    return "not described by the other side"


def differences(name: str, a: Agreement) -> list[str]:
    """The rows of the differences table of one message or layout."""
    rows = []
    for side, names in (("ours", a.only_ours), ("pyubx2", a.only_theirs), ("differs", set(a.differing))):
        for base in sorted({re.sub(r"_\d\d$", "", n) for n in names}):
            rows.append(f"| {name} | `{base}` | {side} | {_reason(base, a.words, a.whole, name)} |")
    return rows


def report() -> str:
    rows = agreement()
    fields = field_agreement()
    made_up = made_up_agreement()
    logs = Counter(name for name, _, _ in log_frames())
    lines = [
        "# UBX frames: agreement with pyubx2",
        "",
        "Written by `.venv/bin/python -m tests.ubx.pyubx2_oracle`; tests/ubx/test_ubx_frames.py fails",
        "when it is stale. The frames are those of gpsd's regression logs in tests/data/ubx",
        "(PROVENANCE.md), split by nmeaspec.ubx.split_frames. Every frame's checksum is accepted by",
        f"pyubx2 {pyubx2.__version__} and our encoder writes it back byte-exact.",
        "",
        "| log | frames |",
        "| --- | ---: |",
        *(f"| {name} | {count} |" for name, count in sorted(logs.items())),
        "",
        "| message (pyubx2) | frames | pyubx2 re-serializes byte-exact |",
        "| --- | ---: | ---: |",
        *(f"| {identity} | {count} | {same} |" for identity, (count, same) in rows.items()),
        "",
        "## Field by field",
        "",
        "Each frame decoded by the generated classes (nmeaspec.ubx_messages, from spec/binary/ubx) and by",
        "pyubx2; fields paired by name (u-blox's names: ours in snake case, a group entry's k-th field",
        "pyubx2's `<name>_<kk>`), numbers in their units (scaled ones within 1e-9). Encoded back: the",
        "frames our classes write back byte-exact from the decoded message.",
        "",
        "| message | frames | values compared | equal | encoded back byte-exact |",
        "| --- | ---: | ---: | ---: | ---: |",
        *(f"| {name} | {a.frames} | {a.compared} | {a.equal} | {a.encoded} |" for name, a in sorted(fields.items())),
        "",
        "Fields one side has and the other does not, or whose values differ, and why:",
        "",
        "| message | field | side | why |",
        "| --- | --- | --- | --- |",
        *(row for name, a in sorted(fields.items()) for row in differences(name, a)),
        "",
        "## Layouts no log carries",
        "",
        "Each fixed layout with a payload that no frame of the logs has, decoded from a made-up payload",
        "(bytes drawn from a generator seeded with the layout's id, its selector set: version, type) by",
        "our class and by pyubx2 parsing it as the layout's direction (output, input, poll), compared as",
        "above.",
        "",
        "| layout | values compared | equal | encoded back byte-exact |",
        "| --- | ---: | ---: | ---: |",
        *(f"| {name} | {a.compared} | {a.equal} | {'yes' if a.encoded == a.frames else 'no'} |"
          for name, a in made_up.items()),
        "",
        "| layout | field | side | why |",
        "| --- | --- | --- | --- |",
        *(row for name, a in made_up.items() for row in differences(name, a)),
    ]
    fails = [f"- {name}: {why}" for name, why in sorted(PYUBX2_FAILS.items()) if name in made_up]
    if fails:
        lines += ["", "Layouts pyubx2 cannot parse (decoded and encoded back by ours, not compared):", "", *fails]
    lines.append("")
    return "\n".join(lines)


if __name__ == "__main__":
    REPORT.write_text(report(), encoding="utf-8")
