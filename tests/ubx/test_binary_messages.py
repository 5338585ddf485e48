"""The typed messages of SkyTraq, SiRF, CASIC and SBF (spec/binary/{skytraq,sirf,casic,sbf}/messages,
nmeaspec.<protocol>_messages): every frame of gpsd's logs of those receivers whose message the spec
describes decodes into its class and encodes back byte-exact; the decoded JSON of every example is
the reference decoder's (generated/vectors/binary.jsonl); errors name the protocol and message
(`SKYTRAQ 0xA8`, `SIRF MID 41`, `CASIC NAV-PV`, `SBF 4007 rev 2`); `nmea show` gives the frames' rows
their values; pysbf2 agrees with the SBF blocks' values (docs/sbf-agreement.md)."""

from __future__ import annotations

import json
from collections import Counter
from dataclasses import fields as dataclass_fields, replace
from pathlib import Path

import pytest

from tests.ubx.pyubx2_oracle import ubx  # noqa: F401 (puts generated/python on the path)

from nmeaspec import binary, stream  # isort: skip
from nmeaspec.ais import Special  # isort: skip
from nmeaspec.apps.nmea_cli import main  # isort: skip
from nmeaspec.casic_messages import BY_ID as CASIC  # isort: skip
from nmeaspec.casic_messages.nav_pv import NavPv  # isort: skip
from nmeaspec.runtime import NmeaError  # isort: skip
from nmeaspec.sbf_messages import BY_ID as SBF  # isort: skip
from nmeaspec.sbf_messages.pvt_geodetic import PvtGeodetic  # isort: skip
from nmeaspec.sbf_messages.meas_epoch import MeasEpoch  # isort: skip
from nmeaspec.sbf_messages.sat_visibility import SatVisibility  # isort: skip
from nmeaspec.sirf_messages import BY_ID as SIRF  # isort: skip
from nmeaspec.sirf_messages.geodetic_nav import GeodeticNav  # isort: skip
from nmeaspec.sirf_messages.switch_to_nmea import SwitchToNmea, SwitchToNmeaSentence  # isort: skip
from nmeaspec.skytraq_messages import BY_ID as SKYTRAQ  # isort: skip
from nmeaspec.skytraq_messages.nav_data import NavData  # isort: skip

ROOT = Path(__file__).resolve().parents[2]
DATA = ROOT / "tests" / "data"
TABLES = {"skytraq": SKYTRAQ, "sirf": SIRF, "casic": CASIC}


def frames(protocol: str) -> list[bytes]:
    out: list[bytes] = []
    for log in sorted((DATA / protocol).glob("*.log")):
        with log.open("rb") as f:
            out += [item.data for item in stream.lines(f, binary=True)
                    if isinstance(item, stream.BinaryFrame) and item.protocol == protocol]
    return out


def described(protocol: str, data: bytes) -> bool:
    """Whether the spec describes the frame's message (by the key the protocol.yaml facts give)."""
    if protocol == "casic":
        return (data[4], data[5]) in CASIC
    return (data[4], data[5]) in TABLES[protocol] or (data[4],) in TABLES[protocol]


# What the logs hold of each described message (frames counted by hand from the logs' frame split,
# tests/ubx/test_binary_protocols.py): every one must decode.
EXPECTED = {
    "skytraq": {"0xA8": 239, "0xDC": 2, "0xDD": 2, "0xDE": 9, "0xDF": 9, "0xE0": 2},
    "sirf": {"MID 2": 66, "MID 4": 26, "MID 9": 7, "MID 13": 2, "MID 18": 6, "MID 41": 59, "MID 255": 8,
             "MID 67 SID 1": 59},
    "casic": {"NAV-DOP": 130, "NAV-PV": 130, "NAV-TIMEUTC": 130, "NAV-GPSINFO": 130, "NAV-BDSINFO": 130,
              "NAV-GLNINFO": 130},
}


@pytest.mark.parametrize("protocol", sorted(EXPECTED))
def test_every_described_frame_round_trips(protocol: str) -> None:
    seen: Counter[str] = Counter()
    unknown = 0
    for data in frames(protocol):
        message = stream.BinaryFrame(protocol, data).message()
        assert message.encode() == data, data.hex(" ")
        if isinstance(message, binary.Unknown):
            assert not described(protocol, data)
            unknown += 1
            continue
        assert described(protocol, data)
        assert isinstance(message, binary.Message) and message.PROTOCOL == protocol.upper()
        seen[message.ADDRESS] += 1
        again = type(message).from_payload(message.payload())
        assert again == message
    assert dict(seen) == EXPECTED[protocol]
    assert unknown == len(frames(protocol)) - sum(EXPECTED[protocol].values())


def test_vectors_are_the_reference_decoders() -> None:
    vectors = [json.loads(line) for line in (ROOT / "generated" / "vectors" / "binary.jsonl").read_text().splitlines()]
    assert {v["protocol"] for v in vectors} == {"skytraq", "sirf", "casic", "sbf", "unicore"}
    for v in vectors:
        data = bytes.fromhex(v["frame"])
        if "error" in v:   # a frame every decoder refuses, with this kind of error
            with pytest.raises(NmeaError) as err:
                stream.BinaryFrame(v["protocol"], data).message()
            assert err.value.kind == v["error"], v["where"]
            continue
        message = stream.BinaryFrame(v["protocol"], data).message()
        assert message.to_dict() == v["decode"], v["where"]
        assert message.encode() == data


def test_values_of_a_skytraq_fix() -> None:
    data = frames("skytraq")[2]   # skytraq-A8.log's third 0xA8: a 3D fix of 6 satellites
    message = stream.BinaryFrame("skytraq", data).message()
    assert isinstance(message, NavData)
    assert (message.fix_mode, message.num_sv, message.week) == (2, 6, 2258)
    assert message.lat == pytest.approx(38.9073528) and message.lon == pytest.approx(-77.04758, abs=1e-4)   # gpsd: TPV
    assert message.lat_raw == round(message.lat * 10_000_000)


def test_values_of_a_sirf_and_a_casic_fix() -> None:
    geodetic = next(stream.BinaryFrame("sirf", d).message() for d in frames("sirf") if d[4] == 41)
    assert isinstance(geodetic, GeodeticNav)
    assert (geodetic.year, geodetic.month, geodetic.day) == (2019, 4, 24)
    pv = next(stream.BinaryFrame("casic", d).message() for d in frames("casic") if d[4:6] == b"\x01\x03")
    assert isinstance(pv, NavPv)
    assert (pv.pos_valid, pv.num_sv, pv.gps, pv.glonass) == (7, 17, True, True)


def test_errors_name_the_protocol_and_message() -> None:
    data = bytearray(frames("skytraq")[0])
    cut = bytes(data[:4 + 20])   # the payload cut to its first 20 bytes, framed again
    frame = binary.Frame("skytraq", (0xA8,), cut[5:])
    with pytest.raises(NmeaError) as err:
        stream.BinaryFrame("skytraq", frame.encode()).message()
    assert err.value.kind == "short_payload" and "SKYTRAQ 0xA8" in str(err.value)
    damaged = bytearray(frames("sirf")[0])
    damaged[6] ^= 1
    with pytest.raises(NmeaError) as err:
        binary.decode(SIRF, "sirf", bytes(damaged))
    assert err.value.kind == "bad_checksum"


def test_the_switch_back_to_nmea_encodes() -> None:
    """SiRF MID 129: the input message that switches a port back from SiRF binary to NMEA."""
    switch = SwitchToNmea(mode=2, sentences=[SwitchToNmeaSentence(rate=1 if i in (0, 4) else 0, checksum=1)
                                            for i in range(10)], baud=9600)
    data = switch.encode()
    assert data[:5] == bytes((0xA0, 0xA2, 0x00, 0x18, 0x81)) and data[-2:] == b"\xb0\xb3"
    assert data[-6:-4] == (9600).to_bytes(2, "big")
    assert binary.decode(SIRF, "sirf", data) == switch


def test_show_rows_carry_the_values(capsys: pytest.CaptureFixture[str]) -> None:
    log = str(DATA / "casic" / "quectel-l76k-dual.log")
    assert main(["show", "--json", "-q", "--sentences", "CASIC NAV-PV", log]) == 0
    rows = [json.loads(line) for line in capsys.readouterr().out.splitlines()]
    assert len(rows) == 130 and rows[0]["sentence"] == "CASIC NAV-PV"
    assert rows[0]["fields"]["num_sv"] == 17 and rows[0]["fields"]["pos_valid"] == 7
    log = str(DATA / "sirf" / "sirfstarv.log")
    assert main(["show", "--json", "-q", "--sentences", "SIRF MID 41", log]) == 0
    rows = [json.loads(line) for line in capsys.readouterr().out.splitlines()]
    assert len(rows) == 59 and rows[0]["fields"]["year"] == 2019


def test_gpsd_agrees() -> None:
    """gpsd's reports for the same logs (tests/ubx/gpsd_binary_oracle.py, docs/binary-agreement.md):
    every value of a report tied to a message agrees, but where the rule says why gpsd merged
    another source into that report; every report tied to no message is explained."""
    from tests.ubx import gpsd_binary_oracle as oracle

    found = oracle.outcomes()
    assert oracle.DOC.read_text() == oracle.render(found), "run .venv/bin/python -m tests.ubx.gpsd_binary_oracle"
    results, skies = found
    for o in results:
        assert o.tied > 0, o.rule
        if not o.rule.differ:
            assert o.agree == o.compared, o.rule
        if o.rule.explain:
            assert o.explained == o.reports - o.tied, o.rule
        else:
            assert o.reports - o.tied <= 1, o.rule
    for k in skies:
        assert k.tied == k.reports > 0 and k.agree == k.satellites > 0, k.rule


# What pysbf2's logs (tests/data/sbf) hold of each described SBF block (blocks counted from the
# logs' frame split, tests/ubx/test_stream_frames.py); the other blocks stay binary.Unknown.
SBF_EXPECTED = {"4006 rev 2": 58, "4007 rev 2": 2, "5905 rev 0": 58, "5906 rev 0": 1, "5907 rev 0": 58,
                "5908 rev 0": 1, "4001 rev 0": 1, "5914 rev 0": 1, "4012 rev 0": 3, "4014 rev 1": 3,
                "4043 rev 0": 58, "5911 rev 0": 1, "5921 rev 0": 1, "4000 rev 3": 1,
                "4027 rev 1": 1, "4013 rev 0": 3}


def sbf_frames() -> list[bytes]:
    out: list[bytes] = []
    for log in sorted((DATA / "sbf").glob("*.sbf")) + sorted((DATA / "sbf").glob("*.log")):
        with log.open("rb") as f:
            out += [item.data for item in stream.lines(f, binary=True)
                    if isinstance(item, stream.BinaryFrame) and item.protocol == "sbf"]
    return out


def test_every_sbf_block_round_trips() -> None:
    """Every block of pysbf2's logs: a described one (by the header's block number and revision)
    decodes into its class, an other one stays Unknown with its number and revision; each encodes
    back byte-exact, its CRC and padding as sent."""
    seen: Counter[str] = Counter()
    unknown = 0
    blocks = sbf_frames()
    for data in blocks:
        message = stream.BinaryFrame("sbf", data).message()
        assert message.encode() == data, data.hex(" ")
        ident = int.from_bytes(data[4:6], "little")
        key = (ident & 0x1FFF, ident >> 13)
        if isinstance(message, binary.Unknown):
            assert key not in SBF and message.key == key
            assert message.to_dict()["number"] == key[0] and message.to_dict()["revision"] == key[1]
            unknown += 1
            continue
        assert key in SBF and message.KEY == key and message.PROTOCOL == "SBF"
        seen[message.ADDRESS] += 1
        assert type(message).from_payload(message.payload()) == message
    assert dict(seen) == SBF_EXPECTED
    assert unknown == len(blocks) - sum(SBF_EXPECTED.values())


def test_values_of_an_sbf_fix_and_its_do_not_use_values() -> None:
    block = next(d for d in sbf_frames() if int.from_bytes(d[4:6], "little") & 0x1FFF == 4007)
    pvt = stream.BinaryFrame("sbf", block).message()
    assert isinstance(pvt, PvtGeodetic)
    assert (pvt.tow, pvt.wnc, pvt.mode_type, pvt.nr_sv, pvt.reference_id) == (482847000, 2367, 6, 36, 123)
    assert pvt.latitude == pytest.approx(0.9310293523340808) and pvt.mean_corr_age == pytest.approx(2.78)
    # the float do-not-use value (-2e10): its id, its r4 bits kept; encoded back byte for byte
    assert pvt.cog == Special("do_not_use", 0xD09502F9) and pvt.to_dict()["cog"] == "do_not_use"
    assert pvt.encode() == block
    pvt.height = -2e10   # an r8 holding -2e10 reads back as the special value, its r8 bits
    assert PvtGeodetic.from_payload(pvt.payload()).height == Special("do_not_use", 0xC212A05F20000000)
    # sbfdata.sbf's first epoch: a stand-alone fix, without corrections
    cartesian = next(stream.BinaryFrame("sbf", d).message() for d in sbf_frames()
                     if int.from_bytes(d[4:6], "little") & 0x1FFF == 4006)
    assert cartesian.to_dict()["reference_id"] == "do_not_use" and cartesian.reference_id_raw == 65535
    assert cartesian.to_dict()["mean_corr_age"] == "do_not_use"


def test_sbf_errors_name_the_block() -> None:
    block = next(d for d in sbf_frames() if int.from_bytes(d[4:6], "little") & 0x1FFF == 4007)
    cut = binary.Frame("sbf", (4007, 2), block[8:40])   # the body cut to 32 bytes, framed again (CRC, length)
    with pytest.raises(NmeaError) as err:
        stream.BinaryFrame("sbf", cut.encode()).message()
    assert err.value.kind == "short_payload" and "SBF 4007 rev 2" in str(err.value)
    damaged = bytearray(block)
    damaged[20] ^= 1
    with pytest.raises(NmeaError) as err:
        binary.decode(SBF, "sbf", bytes(damaged))
    assert err.value.kind == "bad_checksum"


def test_sbf_sub_blocks_of_their_sblength() -> None:
    """A sub-block is SBLength bytes: its fields from its start, the bytes after them kept as its
    trailing (a newer firmware's); an SBLength shorter than the fields is refused naming the block
    and the field; an entry of another size than SBLength is not encoded."""
    sky = next(stream.BinaryFrame("sbf", d).message() for d in sbf_frames()
               if int.from_bytes(d[4:6], "little") & 0x1FFF == 4012)
    assert isinstance(sky, SatVisibility) and (sky.n, sky.sb_length, len(sky.sat_info)) == (47, 8, 47)
    first = sky.sat_info[0]
    assert (first.svid, first.azimuth, first.elevation, first.trailing) == (3, 66.97, 85.98, b"")
    longer = SatVisibility(tow=sky.tow, wnc=sky.wnc, n=2, sb_length=None,
                           sat_info=[replace(e, trailing=b"\xaa\xbb") for e in sky.sat_info[:2]])
    again = SatVisibility.from_payload(longer.payload())
    assert again.sb_length == 10 and again.sat_info == longer.sat_info and again.payload() == longer.payload()
    longer.sat_info[1].trailing = b"\xaa"
    with pytest.raises(NmeaError) as err:
        longer.payload()
    assert err.value.kind == "bad_value" and err.value.name == "sb_length"
    short = bytearray(sky.payload())
    short[7] = 4   # SBLength 4: a SatInfo's fields take 8
    with pytest.raises(NmeaError) as err:
        SatVisibility.from_payload(bytes(short))
    assert (err.value.kind, err.value.name) == ("bad_value", "sb_length")
    assert str(err.value).endswith("SBF 4012 rev 0: sb_length is 4, an entry of sat_info takes at least 8 bytes"), \
        str(err.value)


def test_sbf_sub_blocks_of_sub_blocks() -> None:
    """MeasEpoch: Type-1 sub-blocks of SB1Length, each followed by its N2 Type-2 of SB2Length (rule
    B010), read with both levels' trailing bytes and encoded back byte for byte; Type-2 entries of
    another number than N2 are not encoded; an SB2Length shorter than the fields is refused naming
    it (the frames of generated/vectors/binary.jsonl show the rest to the three languages)."""
    epoch = next(stream.BinaryFrame("sbf", d).message() for d in sbf_frames()
                 if int.from_bytes(d[4:6], "little") & 0x1FFF == 4027)
    assert isinstance(epoch, MeasEpoch) and (epoch.n1, epoch.sb1_length, epoch.sb2_length) == (44, 20, 12)
    assert len(epoch.type1) == 44 and sum(len(t.type2) for t in epoch.type1) == 56
    first = epoch.type1[0]
    assert (first.svid, first.n2, len(first.type2), first.type2[0].code_offset_msb) == (17, 2, 2, -1)
    longer = replace(epoch, n1=None, sb1_length=None, sb2_length=None,
                     type1=[replace(t, trailing=b"\x01\x02", type2=[replace(e, trailing=b"\x03\x04") for e in t.type2])
                            for t in epoch.type1[:3]])
    again = MeasEpoch.from_payload(longer.payload())
    assert (again.n1, again.sb1_length, again.sb2_length) == (3, 22, 14) and again.type1 == longer.type1
    assert again.payload() == longer.payload()
    longer.type1[0].n2 = 1
    with pytest.raises(NmeaError) as err:
        longer.payload()
    assert (err.value.kind, err.value.name) == ("bad_value", "n2")
    short = bytearray(epoch.payload())
    short[8] = 8   # SB2Length 8: a Type-2's fields take 12
    with pytest.raises(NmeaError) as err:
        MeasEpoch.from_payload(bytes(short))
    assert (err.value.kind, err.value.name) == ("bad_value", "sb2_length")
    assert str(err.value).endswith("sb2_length is 8, an entry of type2 takes at least 12 bytes"), str(err.value)


def test_pysbf2_agrees() -> None:
    """pysbf2's values of the same blocks (tests/ubx/pysbf2_oracle.py, docs/sbf-agreement.md): every
    field compared agrees, but the do-not-use values, named here; pysbf2's fields left out each
    have their reason."""
    from tests.ubx import pysbf2_oracle as oracle

    found = oracle.outcomes()
    assert oracle.DOC.read_text() == oracle.render(found), "run .venv/bin/python -m tests.ubx.pysbf2_oracle"
    assert [o.block for o in found] == list(oracle.TYPED)
    for o in found:
        assert o.round_trip == o.count > 0 and not o.differ, o.block
        assert all(o.agree[k] + o.special[k] == n for k, n in o.fields.items()), o.block
        assert all(name in oracle.LEFT_OUT for name in o.missing), o.block


def test_pyunigps_agrees() -> None:
    """pyunigps's values of the same Unicore frames (tests/ubx/pyunigps_oracle.py,
    docs/unicore-agreement.md): every field compared agrees, each frame encodes back byte for byte,
    pyunigps's fields left out and ours not compared each have their reason."""
    from tests.ubx import pyunigps_oracle as oracle

    found = oracle.outcomes()
    assert oracle.DOC.read_text() == oracle.render(found), "run .venv/bin/python -m tests.ubx.pyunigps_oracle"
    assert [o.message for o in found] == list(oracle.TYPED)
    for o in found:
        assert o.round_trip == o.count > 0 and not o.differ, o.message
        assert o.fields and all(o.agree[k] == n for k, n in o.fields.items()), o.message
        assert all(name in oracle.LEFT_OUT for name in o.missing), o.message
        assert o.not_compared <= set(oracle.NOT_COMPARED), o.message


def test_unicore_messages_and_their_errors() -> None:
    """A Unicore frame is told by its header's message id: BESTNAVB's values and header fields; a
    frame of an id the spec does not type kept with its payload and header fields; a message built
    by hand has its header fields 0 unless set, one its bytes cannot hold named by message and field;
    a body cut short named by message and field; a NovAtel-style third sync byte refused."""
    from nmeaspec import unicore_messages
    from tests.ubx import pyunigps_oracle as oracle

    built = oracle.frames(oracle.BUILT.read_bytes())
    frame = next(f for f in built if int.from_bytes(f[4:6], "little") == 2118)
    best = unicore_messages.decode(frame)
    assert isinstance(best, unicore_messages.BestnavB)
    assert best.ADDRESS == "BESTNAVB" and best.to_dict()["pos_type"] == "narrow_int"
    assert best.lat == pytest.approx(51.4761234567) and best.num_svs == 31
    assert best.header == unicore_messages.Header(38, 1, 2, 2407, 123_457_250, 0x10204, 0, 18, 6)
    assert list(best.to_dict())[:2] == ["message", "header"] and best.encode() == frame
    test = (ROOT / "tests" / "data" / "unicore" / "pyunigps_frames.log").read_bytes()[:33]
    unknown = unicore_messages.decode(test)
    assert isinstance(unknown, binary.Unknown) and unknown.key == (65512,) and unknown.payload == bytes([1, 2, 3, 4, 5])
    assert unknown.header is not None and unknown.header.week == 17459 and unknown.encode() == test
    # built by hand: zeros in the header, or what is set
    fields = {f.name: getattr(best, f.name) for f in dataclass_fields(best) if f.name != "header"}
    assert unicore_messages.BestnavB(**fields).encode()[:24] == frame[:3] + b"\0" + frame[4:8] + bytes(16)
    dated = unicore_messages.BestnavB(**fields, header=unicore_messages.Header(week=2407, time_of_week=123_457_250))
    assert unicore_messages.decode(dated.encode()) == dated
    dated.header.week = 1 << 16
    with pytest.raises(NmeaError) as err:
        dated.encode()
    assert err.value.kind == "bad_value" and err.value.address == "UNICORE BESTNAVB" and err.value.name == "header.week"
    cut = binary.Frame("unicore", (2118,), best.payload()[:40]).encode()
    with pytest.raises(NmeaError) as err:
        unicore_messages.decode(cut)
    assert err.value.kind == "short_payload" and "BESTNAVB" in str(err.value)
    with pytest.raises(NmeaError) as err:
        unicore_messages.decode(b"\xaa\x44\x12" + built[0][3:])
    assert err.value.kind == "bad_sync"
