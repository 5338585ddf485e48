"""The framing table of the binary protocols (spec/binary/*/protocol.yaml) that the three stream
framers loop over: per protocol its sync bytes, where its length field is and what it counts, its
header, checksum (one kind of a fixed set) and end bytes, and the fields that tell its message.

Each runtime compiles and is tested on its own (runtime/README.md), so the table is written into
runtime/ (runtime/c/framings.h and framings.c, runtime/rust/src/framings.rs,
runtime/python/framings.py) by `make generate` from the checkout's spec, and copied into
generated/ with the rest of the runtime; tests/generator/test_framing.py holds them to the spec.
A new protocol is a protocol.yaml."""

from __future__ import annotations

import re
from dataclasses import dataclass
from pathlib import Path

from .emit import RUNTIME, REGENERATE
from .model import BinaryMessage, BinaryProtocol, Spec
from .paths import LICENSE

# The checksums the runtimes compute, by the protocol.yaml name: its bytes after the payload.
CHECKSUMS = {"fletcher8": 2, "xor8": 1, "sum15": 2, "sum32": 4, "crc24q": 3, "crc16_ccitt": 2, "crc32": 4}
# Bytes that end or start a line, or open a TAG block: no sync byte but '$' (which also starts
# a sentence: a protocol that syncs on it is told apart by its second byte, never an NMEA address's).
_LINE_BYTES = b"\r\n!\\"
# The files written, under runtime/.
FILES = ("c/framings.h", "c/framings.c", "rust/src/framings.rs", "python/framings.py")


class FramingError(ValueError):
    """A protocol.yaml whose frame the framers cannot take (a generator limit, said in full)."""


@dataclass(frozen=True)
class Framing:
    protocol: str               # ubx
    sync: bytes                 # the sync bytes a rejected frame is handed on as (1 to 3)
    follow: tuple[int, int]     # the byte after the first sync byte: (value, mask) of its bits
    length_at: int              # the length field: its first byte, from the first sync byte
    length_size: int            # 1 or 2 bytes
    big_endian: bool
    length_mask: int            # the bits of the field that are the length
    header: int                 # bytes before the payload, sync included
    length_adds: int            # the frame's bytes beyond what its length counts (0: it counts them all)
    checksum: str               # a key of CHECKSUMS
    check_from: int             # the first byte the checksum covers (it ends with the payload)
    check_at: int               # where the checksum sits in the header; 0: after the payload
    end: bytes                  # the bytes after the checksum that end a frame
    identity: tuple[tuple[str, int, int], ...]  # (name, bit offset from the sync, bits): what tells the message
    # (bits numbered most significant first in a big-endian frame, least significant first in a little-endian one)
    kept: tuple[tuple[str, int, int], ...] = ()  # (name, byte offset from the sync, bytes): the header's fields
    # of `identity: false` (Unicore's time and status), which a decoded message keeps and writes back

    @property
    def check_size(self) -> int:
        return CHECKSUMS[self.checksum]

    @property
    def trailer(self) -> int:
        """The bytes after the payload: the checksum (unless it sits in the header) and end bytes."""
        return (0 if self.check_at else self.check_size) + len(self.end)


_BITS = re.compile(r"^(u|b)(\d+)$")


def _bits(type_: str) -> int:
    m = _BITS.match(type_)
    if not m:
        raise FramingError(f"header field type {type_}")
    return int(m[2]) * (8 if m[1] == "u" else 1)


def framing(p: BinaryProtocol) -> Framing:
    frame = p.frame
    where = f"{p.origin.file}: frame"
    sync = bytes(frame["sync"])
    if not 1 <= len(sync) <= 3:
        raise FramingError(f"{where}: sync of {len(sync)} bytes (the framers take 1 to 3)")
    if sync[0] in _LINE_BYTES or sync[0] == ord("$") and (len(sync) < 2 or chr(sync[1]).isalnum()):
        raise FramingError(f"{where}: sync {sync.hex(' ')} would take a line's bytes (a '$' sync needs a "
                           "second byte that starts no sentence)")
    big = frame.get("byte_order", "little") == "big"
    fields, bit = [], 8 * len(sync)
    for f in frame["header"]:
        width = _bits(f["type"])
        fields.append((f, bit, width))
        bit += width
    if bit % 8:
        raise FramingError(f"{where}: header of {bit} bits, not whole bytes")
    header = bit // 8
    lengths = [(f, at, width) for f, at, width in fields if f.get("counts")]
    if len(lengths) != 1:
        raise FramingError(f"{where}: one header field counts the payload or the frame")
    f, at, width = lengths[0]
    if f["type"].startswith("u"):
        length_at, length_size, mask = at // 8, width // 8, (1 << width) - 1
    else:   # a bit field, most significant bit first, ending on a byte
        if (at + width) % 8 or not big:
            raise FramingError(f"{where}: a length of bits ends on a byte, big endian")
        length_at = at // 8
        length_size = (at + width) // 8 - length_at
        mask = (1 << width) - 1
    if length_size > 2:
        raise FramingError(f"{where}: a length field of {length_size} bytes (the framers take 1 or 2)")
    # a reserved field of zeros in the length's bytes is read with it: set, it makes the frame too long
    low, high = 8 * length_at, 8 * (length_at + length_size)
    for g, at, width in fields:
        if "value" in g and low <= at and at + width <= high:
            if g["value"] != 0:
                raise FramingError(f"{where}: a reserved field beside the length holds zeros")
            mask |= ((1 << width) - 1) << (high - at - width)
    if len(sync) >= 2:
        follow = (sync[1], 0xFF)
    else:   # fixed bits of the header's first byte
        value = mask_bits = 0
        for g, at, width in fields:
            if "value" in g and at + width <= 16:
                shift = 16 - at - width
                mask_bits |= ((1 << width) - 1) << shift
                value |= g["value"] << shift
        follow = (value, mask_bits)
    checksum = frame["checksum"]
    if checksum["algorithm"] not in CHECKSUMS:
        raise FramingError(f"{where}: checksum {checksum['algorithm']} (the framers compute "
                           f"{', '.join(CHECKSUMS)})")
    first, last = checksum["over"]
    offsets = {"sync": 0, "payload": header} | {g["id"]: at // 8 for g, at, _ in fields}
    if last != "payload" or first not in offsets:
        raise FramingError(f"{where}: a checksum over [sync, header field or payload, payload]")
    check_at = 0
    if "at" in checksum:   # in the header, before what it covers
        held = [(g, at, width) for g, at, width in fields if g["id"] == checksum["at"]]
        if not held or held[0][0]["type"] != f"u{CHECKSUMS[checksum['algorithm']]}" \
                or held[0][1] // 8 >= offsets[first]:
            raise FramingError(f"{where}: checksum at {checksum['at']}: a header field of its bytes before "
                               "what it covers")
        check_at = held[0][1] // 8
    size = CHECKSUMS[checksum["algorithm"]]
    adds = 0 if f["counts"] == "frame" else header + (0 if check_at else size) + len(frame.get("end", []))
    identity = [(g["id"], at, width) for g, at, width in fields
                if not g.get("counts") and "value" not in g and g["id"] != checksum.get("at")
                and g.get("identity", True)]
    at = 8 * header
    for g in p.identity:
        identity.append((g["id"], at, _bits(g["type"])))
        at += _bits(g["type"])
    if len(identity) > 2 or any(width > 16 for _, _, width in identity):
        raise FramingError(f"{where}: at most two identity fields of 16 bits")
    kept = tuple((g["id"], at // 8, width // 8) for g, at, width in fields if g.get("identity", True) is False)
    if any(g["type"] not in ("u1", "u2", "u4") for g, _, _ in fields if g.get("identity", True) is False):
        raise FramingError(f"{where}: a header field of `identity: false` is u1, u2 or u4")
    return Framing(p.id, sync, follow, length_at, length_size, big, mask, header, adds, checksum["algorithm"],
                   offsets[first], check_at, bytes(frame.get("end", [])), tuple(identity), kept)


@dataclass(frozen=True)
class KeptField:
    """A header field of `identity: false` (Unicore's time and status) that a decoded message keeps
    (its protocol's header type, generated in the three languages) and its frame is written with."""
    id: str
    at: int      # its first byte, from the first sync byte
    size: int    # its bytes (1, 2 or 4: unsigned)
    doc: str


def kept_fields(p: BinaryProtocol) -> list[KeptField]:
    """The header fields a decoded message of protocol `p` keeps (Framing.kept), with their docs."""
    docs = {g["id"]: g.get("doc", g["id"]) for g in p.frame["header"]}
    return [KeptField(name, at, size, docs[name]) for name, at, size in framing(p).kept]


def header_key(f: Framing, values: tuple[int, ...]) -> tuple[int, ...]:
    """The header's bytes that hold a message's key `values` (one per identity field, as the model's
    BinaryMessage.key gives them): CASIC's class and id are two bytes as they are; SBF's block number
    (13 bits) and revision (3 bits) share the two bytes of its id, little endian. What the Rust and C
    framers compare and write where the header holds the key."""
    first = min(at for _, at, _ in f.identity) // 8
    last = (max(at + bits for _, at, bits in f.identity) + 7) // 8
    word = 0
    for (_, at, bits), value in zip(f.identity, values):
        shift = 8 * last - at - bits if f.big_endian else at - 8 * first
        word |= (value & ((1 << bits) - 1)) << shift
    return tuple(word.to_bytes(last - first, "big" if f.big_endian else "little"))


def wire_key(spec: Spec, message: BinaryMessage) -> tuple[int, ...]:
    """The bytes that tell `message` in a frame: its header's key bytes (header_key) where the
    header holds the key, else its key (the payload's first bytes: SkyTraq's, SiRF's id and sub-id)."""
    f = framing(next(p for p in spec.protocols if p.id == message.protocol))
    if f.identity and all(at // 8 < f.header for _, at, _ in f.identity):
        return header_key(f, message.key)
    return message.key


def framings(spec: Spec) -> list[Framing]:
    out = [framing(p) for p in sorted(spec.protocols, key=lambda p: p.id)]
    for i, a in enumerate(out):
        for b in out[i + 1:]:
            if a.sync[0] == b.sync[0] and (a.follow[0] ^ b.follow[0]) & a.follow[1] & b.follow[1] == 0:
                raise FramingError(f"protocols {a.protocol} and {b.protocol} start alike: their sync bytes "
                                   "must differ within the first two bytes")
    firsts = {f.sync[0] for f in out}
    for f in out:   # a third sync byte that does not follow hands the two before it to the line
        if len(f.sync) == 3 and (f.sync[1] in _LINE_BYTES + b"$" or f.sync[1] in firsts):
            raise FramingError(f"protocol {f.protocol}: the second of three sync bytes, {f.sync[1]:02X}, "
                               "ends or starts a line or a frame")
    return out


def _banner(comment: str) -> str:
    lines = ["@generated by the NMEA spec generator from spec/binary/<protocol>/protocol.yaml (generator/emit_framing.py).",
             "DO NOT EDIT.", f"SPDX-License-Identifier: {LICENSE}", f"Regenerate: {REGENERATE}"]
    return "".join(f"{comment} {line}\n" for line in lines)


def _c_banner() -> str:
    return "/* " + "\n   ".join(line.strip() for line in _banner("").splitlines()) + " */\n"


def _py_bytes(data: bytes) -> str:
    return 'b"' + "".join(f"\\x{b:02x}" for b in data) + '"'


def _hex(data: bytes | tuple[int, ...]) -> str:
    return ", ".join(f"0x{b:02X}" for b in data)


def _table_sync(f: Framing) -> bytes:
    """The C and Rust tables' three sync bytes: the first, the second's bits under the follow mask,
    the third (0 when the sync is shorter: sync_len says)."""
    return (f.sync[:1] + bytes([f.follow[0]]) + f.sync[2:] + bytes(3))[:3]


def c_header(table: list[Framing]) -> str:
    consts = ", ".join(["NMEA_LINE"] + [f"NMEA_{f.protocol.upper()}" for f in table])
    syncs = ", ".join(f"[0x{s:02X}] = 4" for s in sorted({f.sync[0] for f in table} - {ord("$")}))
    dollar = 4 if any(f.sync[0] == ord("$") for f in table) else 2
    kinds = "".join(f"#define NMEA_FRAMING_{k.upper()}\n" for k in CHECKSUMS if any(f.checksum == k for f in table))
    return _c_banner() + f"""
#ifndef NMEA_NO_BINARY_FRAMES
/** What a framed item is: a line, or a binary frame of a protocol of spec/binary/. */
typedef enum {{ {consts} }} nmea_protocol;

/** The binary protocols, each an entry of nmea_framings (at its nmea_protocol less one). */
#define NMEA_FRAMING_COUNT {len(table)}

/* The first sync bytes of the protocols, as the framer's byte classes mark them ('$' apart: its
   class, 4 when it may also start a frame, else 2: it starts a sentence). */
#define NMEA_FRAME_SYNCS {syncs}
#define NMEA_FRAME_DOLLAR {dollar}

/* The checksums the protocols use (the framer computes only those). */
{kinds}#endif
"""


def c_source(table: list[Framing]) -> str:
    rows = []
    for f in table:
        ids = ", ".join(f'{{"{n}", {at}, {bits}}}' for n, at, bits in f.identity) or "{0, 0, 0}"
        rows.append(f"""    {{"{f.protocol}", {{{_hex(_table_sync(f))}}}, 0x{f.follow[1]:02X}, {len(f.sync)}, \
{f.length_at}, {f.length_size}, {int(f.big_endian)}, 0x{f.length_mask:04X}, {f.header}, {f.length_adds}, \
NMEA_CHECKSUM_{f.checksum.upper()}, {f.check_from}, {f.check_at}, {f.check_size}, {{{_hex(f.end) or '0'}}}, {len(f.end)}, \
{{{ids}}}}},""")
    return _c_banner() + f"""
#ifndef NMEA_NO_BINARY_FRAMES
/* The framing of each binary protocol, by its nmea_protocol less one. */
const nmea_framing nmea_framings[NMEA_FRAMING_COUNT] = {{
{chr(10).join(rows)}
}};
#endif
"""


def rust_source(table: list[Framing]) -> str:
    variants, rows = [], []
    for f in table:
        name = f.protocol.capitalize()
        variants.append(f"    /// {f.protocol}: sync {' '.join(f'{b:02X}' for b in f.sync)}.\n    {name},")
        ids = ", ".join(f'("{n}", {at}, {bits})' for n, at, bits in f.identity)
        rows.append(f"""    FrameFormat {{
        name: "{f.protocol}",
        sync: [{_hex(_table_sync(f))}],
        follow_mask: 0x{f.follow[1]:02X},
        sync_len: {len(f.sync)},
        length_at: {f.length_at},
        length_size: {f.length_size},
        big_endian: {'true' if f.big_endian else 'false'},
        length_mask: 0x{f.length_mask:04X},
        header: {f.header},
        length_adds: {f.length_adds},
        checksum: ChecksumKind::{''.join(w.capitalize() for w in f.checksum.split('_'))},
        check_from: {f.check_from},
        check_at: {f.check_at},
        check_size: {f.check_size},
        end: &[{_hex(f.end)}],
        identity: &[{ids}],
    }},""")
    names = ", ".join(f"Protocol::{f.protocol.capitalize()}" for f in table)
    return _banner("//") + f"""
//! The framing of each binary protocol of spec/binary (see stream.rs).

use super::stream::{{ChecksumKind, FrameFormat}};

/// A binary protocol the framer tells from NMEA.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Protocol {{
{chr(10).join(variants)}
}}

impl Protocol {{
    /// Every protocol, in the order of [`FRAMINGS`].
    pub const ALL: [Protocol; {len(table)}] = [{names}];
}}

/// The framing of each protocol, by its [`Protocol`] as an index.
pub static FRAMINGS: [FrameFormat; {len(table)}] = [
{chr(10).join(rows)}
];
"""


def python_source(table: list[Framing]) -> str:
    rows = []
    for f in table:
        rows.append(f"    Framing({f.protocol!r}, {_py_bytes(f.sync)}, 0x{f.follow[0]:02X}, 0x{f.follow[1]:02X}, "
                    f"{f.length_at}, {f.length_size}, {f.big_endian}, 0x{f.length_mask:04X}, {f.header}, "
                    f"{f.length_adds},\n            {f.checksum!r}, {f.check_from}, {f.check_at}, {f.check_size}, "
                    f"{_py_bytes(f.end)}, "
                    f"{tuple(f.identity)!r}" + (f",\n            {f.kept!r}" if f.kept else "") + "),")
    return _banner("#") + f'''"""The framing of each binary protocol of spec/binary (see stream.py)."""

from __future__ import annotations

from typing import NamedTuple


class Framing(NamedTuple):
    """How a binary protocol's frame is told from noise."""

    protocol: str  # its name in the tools' JSON
    sync: bytes  # its sync bytes (1 to 3): what a rejected frame is handed on as; a third is checked as it comes
    follow: int  # the byte after the first sync byte, its bits under follow_mask
    follow_mask: int
    length_at: int  # the length field: its first byte, from the sync
    length_size: int  # its bytes
    big_endian: bool
    length_mask: int  # the bits that are the length
    header: int  # bytes before the payload, sync included
    length_adds: int  # the frame's bytes beyond what its length counts (0: the length counts them all)
    checksum: str  # fletcher8, xor8, sum15, sum32, crc24q, crc16_ccitt, crc32
    check_from: int  # the first byte the checksum covers (it ends with the payload)
    check_at: int  # where the checksum sits in the header; 0: after the payload
    check_size: int  # the checksum's bytes
    end: bytes  # the bytes after the checksum that end the frame
    # (name, bit offset from the sync, bits): what tells the message; the bits numbered most
    # significant first in a big-endian frame, least significant first in a little-endian one
    identity: tuple[tuple[str, int, int], ...]
    # (name, byte offset from the sync, bytes): the header's other fields (Unicore's time and status),
    # unsigned, which a decoded message keeps (binary.Header) and writes back
    kept: tuple[tuple[str, int, int], ...] = ()

    @property
    def trailer(self) -> int:
        """The bytes after the payload: the checksum (unless it sits in the header) and end bytes."""
        return (0 if self.check_at else self.check_size) + len(self.end)


FRAMINGS = (
{chr(10).join(rows)}
)
'''


def render(spec: Spec) -> dict[str, str]:
    """The table files by their path under runtime/."""
    from .emit_rust import rustfmt

    table = framings(spec)
    rust = rustfmt({"framings.rs": rust_source(table)})["framings.rs"]
    return {"c/framings.h": c_header(table), "c/framings.c": c_source(table), "rust/src/framings.rs": rust,
            "python/framings.py": python_source(table)}


def stale(spec: Spec) -> list[Path]:
    """The table files under runtime/ that differ from the spec's (written by write)."""
    return [RUNTIME / rel for rel, text in render(spec).items()
            if not (RUNTIME / rel).exists() or (RUNTIME / rel).read_text(encoding="utf-8") != text]


def write(spec: Spec) -> list[Path]:
    files = render(spec)
    out = []
    for rel in FILES:
        path = RUNTIME / rel
        if not path.exists() or path.read_text(encoding="utf-8") != files[rel]:
            path.write_text(files[rel], encoding="utf-8")
            out.append(path)
    return out
