"""The framing table of the binary protocols (generator/emit_framing.py): the runtimes' copies
(runtime/c/framings.h and .c, runtime/rust/src/framings.rs, runtime/python/framings.py) are what
spec/binary/*/protocol.yaml gives, and a frame the framers cannot take is refused with its reason."""

from __future__ import annotations

import copy
from pathlib import Path

import pytest

from generator import emit_framing
from generator.build import load_spec

ROOT = Path(__file__).resolve().parents[2]
SPEC = load_spec(ROOT / "spec")


def test_the_runtimes_hold_the_spec_table() -> None:
    assert emit_framing.stale(SPEC) == [], "run make generate"


def test_the_table_of_ubx_and_rtcm3() -> None:
    table = {f.protocol: f for f in emit_framing.framings(SPEC)}
    ubx, rtcm3 = table["ubx"], table["rtcm3"]
    assert (ubx.sync, ubx.follow, ubx.length_at, ubx.length_size, ubx.big_endian, ubx.header) \
        == (b"\xb5\x62", (0x62, 0xFF), 4, 2, False, 6)
    assert (ubx.checksum, ubx.check_from, ubx.check_size, ubx.identity) \
        == ("fletcher8", 2, 2, (("class", 16, 8), ("id", 24, 8)))
    # RTCM 3: one sync byte, then 6 reserved bits of zero and a 10-bit length
    assert (rtcm3.sync, rtcm3.follow, rtcm3.length_at, rtcm3.length_mask, rtcm3.header) \
        == (b"\xd3", (0x00, 0xFC), 1, 0xFFFF, 3)  # the reserved bits read with the length (and zero)
    assert (rtcm3.checksum, rtcm3.check_from, rtcm3.identity) == ("crc24q", 0, (("message_number", 24, 12),))


@pytest.mark.parametrize("change, reason", [
    (lambda f: f.__setitem__("sync", [1, 2, 3, 4]), "sync of 4 bytes"),
    (lambda f: f["checksum"].__setitem__("algorithm", "crc64"), "checksum crc64"),
    (lambda f: f["checksum"].__setitem__("over", ["payload", "class"]), "a checksum over"),
    (lambda f: f["header"][2].pop("counts"), "one header field counts the payload"),
    # a '$' sync must be told from a sentence's start by its second byte; '!' starts one always
    (lambda f: f.__setitem__("sync", [0x24, 0x47]), "would take a line's bytes"),
    (lambda f: f.__setitem__("sync", [0x21, 0x40]), "would take a line's bytes"),
    (lambda f: f["checksum"].__setitem__("at", "length"), "checksum at length"),
])
def test_a_frame_the_framers_cannot_take(change, reason) -> None:  # type: ignore[no-untyped-def]
    ubx = copy.deepcopy(next(p for p in SPEC.protocols if p.id == "ubx"))
    change(ubx.frame)
    with pytest.raises(emit_framing.FramingError, match=reason):
        emit_framing.framing(ubx)


def test_protocols_that_start_alike() -> None:
    twin = copy.deepcopy(next(p for p in SPEC.protocols if p.id == "ubx"))
    twin.id = "twin"
    SPEC2 = copy.copy(SPEC)
    SPEC2.protocols = [*SPEC.protocols, twin]
    with pytest.raises(emit_framing.FramingError, match="start alike"):
        emit_framing.framings(SPEC2)
    # the second of three sync bytes goes to the line when the third does not follow: no line or sync byte
    for second in (0x24, 0x0A, 0xB5):
        uni = copy.deepcopy(next(p for p in SPEC.protocols if p.id == "unicore"))
        uni.frame["sync"] = [0xAA, second, 0xB5]
        SPEC2.protocols = [p for p in SPEC.protocols if p.id != "unicore"] + [uni]
        with pytest.raises(emit_framing.FramingError, match="second of three sync bytes"):
            emit_framing.framings(SPEC2)


def test_the_table_of_skytraq_sirf_and_casic() -> None:
    table = {f.protocol: f for f in emit_framing.framings(SPEC)}
    sky, sirf, casic = table["skytraq"], table["sirf"], table["casic"]
    assert (sky.sync, sky.length_at, sky.big_endian, sky.header, sky.checksum, sky.check_from, sky.end) \
        == (b"\xa0\xa1", 2, True, 4, "xor8", 4, b"\r\n")
    # SiRF: the reserved top bit is read with the 15-bit length (set, the frame is too long)
    assert (sirf.sync, sirf.length_at, sirf.length_mask, sirf.checksum, sirf.check_size, sirf.end) \
        == (b"\xa0\xa2", 2, 0xFFFF, "sum15", 2, b"\xb0\xb3")
    assert (casic.sync, casic.length_at, casic.big_endian, casic.header, casic.checksum, casic.check_from) \
        == (b"\xba\xce", 2, False, 6, "sum32", 2)
    assert sky.identity == sirf.identity == (("id", 32, 8),)
    assert casic.identity == (("class", 32, 8), ("id", 40, 8))


def test_the_table_of_sbf() -> None:
    """SBF: the CRC in the header before what it covers (the id to the block's end), a length
    that counts the whole block, the id's 13-bit number and 3-bit revision read least significant
    bit first (little endian)."""
    sbf = {f.protocol: f for f in emit_framing.framings(SPEC)}["sbf"]
    assert (sbf.sync, sbf.follow, sbf.length_at, sbf.length_size, sbf.big_endian, sbf.header, sbf.length_adds) \
        == (b"$@", (0x40, 0xFF), 6, 2, False, 8, 0)
    assert (sbf.checksum, sbf.check_at, sbf.check_from, sbf.check_size, sbf.trailer) == ("crc16_ccitt", 2, 4, 2, 0)
    assert sbf.identity == (("number", 32, 13), ("revision", 45, 3))
    ubx = {f.protocol: f for f in emit_framing.framings(SPEC)}["ubx"]
    assert (ubx.length_adds, ubx.check_at, ubx.trailer) == (8, 0, 2)  # header and checksum beyond the payload


def test_the_table_of_unicore() -> None:
    """Unicore: synced on AA 44 B5 (the third byte checked as it comes), a 24-byte header whose
    length counts the body alone, its message id the one field that tells the message (the header's
    time and status fields passed over: identity: false), a CRC-32 from the sync to the body's end."""
    uni = {f.protocol: f for f in emit_framing.framings(SPEC)}["unicore"]
    assert (uni.sync, uni.follow, uni.length_at, uni.length_size, uni.big_endian, uni.header, uni.length_adds) \
        == (b"\xaa\x44\xb5", (0x44, 0xFF), 6, 2, False, 24, 28)
    assert '{"unicore", {0xAA, 0x44, 0xB5}, 0xFF, 3,' in emit_framing.c_source(emit_framing.framings(SPEC))
    assert (uni.checksum, uni.check_at, uni.check_from, uni.check_size, uni.trailer) == ("crc32", 0, 0, 4, 4)
    assert uni.identity == (("message_id", 32, 16),)
