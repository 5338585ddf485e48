"""The generated UBX message classes (nmeaspec.ubx_messages, from spec/binary/ubx): every frame of
gpsd's logs decoded field by field as pyubx2 decodes it (docs/ubx-agreement.md lists what differs
and why) and encoded back byte-exact; the shared vectors (generated/vectors/ubx.jsonl) decoded as
the reference decoder does; typed errors naming protocol, message and field."""

from __future__ import annotations

import json
import random
from pathlib import Path

import pytest

from tests.ubx.pyubx2_oracle import differences, field_agreement, log_frames, made_up_agreement, ubx, ubx_messages

ROOT = Path(__file__).resolve().parents[2]
VECTORS = [json.loads(line) for line in (ROOT / "generated" / "vectors" / "ubx.jsonl").read_text().splitlines()]


def test_every_logged_message_agrees_with_pyubx2_and_encodes_back() -> None:
    rows = field_agreement()
    assert sum(a.frames for a in rows.values()) == len(log_frames())
    for name, a in rows.items():
        assert (a.equal, a.encoded) == (a.compared, a.frames), (name, a.differing)


def test_layouts_no_log_carries_agree_with_pyubx2_but_for_known_reasons() -> None:
    rows = made_up_agreement()
    assert len(rows) >= 16
    for name, a in rows.items():
        assert a.encoded == a.frames, name
        assert not [row for row in differences(name, a) if "not described" in row], name


def test_the_compiled_readers_read_as_the_generic_reader() -> None:
    for _, _, frame in log_frames():
        message = ubx_messages.message(frame)
        assert isinstance(message, ubx.Message)
        assert message == type(message).read_generic(frame.payload), message.ADDRESS


@pytest.mark.parametrize("vector", VECTORS, ids=[v["where"] for v in VECTORS])
def test_the_shared_vectors(vector: dict) -> None:
    data = bytes.fromhex(vector["frame"])
    if "error" in vector:
        with pytest.raises(ubx.NmeaError) as caught:
            ubx_messages.decode(data)
        assert caught.value.kind == vector["error"]
        return
    message = ubx_messages.decode(data)
    assert message.to_dict() == vector["decode"]
    assert message.encode() == data


def test_a_short_payload_names_message_field_and_bytes() -> None:
    frame = ubx.Frame(0x01, 0x07, bytes(28))
    with pytest.raises(ubx.NmeaError) as caught:
        ubx_messages.message(frame)
    assert (caught.value.kind, caught.value.address, caught.value.name) == ("short_payload", "UBX NAV-PVT", "lat")
    assert caught.value.message == "lat needs bytes 28-31, the payload has 28"


def test_an_unknown_class_and_id_keeps_its_payload() -> None:
    frame = ubx.Frame(0x7F, 0x01, b"\x01\x02")
    message = ubx_messages.message(frame)
    assert isinstance(message, ubx.Unknown)
    assert message.encode() == frame.encode()


def test_a_message_built_in_code_encodes_its_counts_and_parts() -> None:
    sat = ubx_messages.NavSat(itow=1000, version=1, reserved0=0, svs=[
        ubx_messages.nav_sat.NavSatSv(gnss_id=0, sv_id=5, cno=40, elev=30, azim=120, pr_res=-1.5, flags=None,
                                      sv_used=True, quality_ind=7, health=1, diff_corr=False, smoothed=False,
                                      orbit_source=1, eph_avail=True, alm_avail=True, ano_avail=False, aop_avail=False,
                                      sbas_corr_used=False, rtcm_corr_used=False, slas_corr_used=False,
                                      spartn_corr_used=False, pr_corr_used=False, cr_corr_used=False,
                                      do_corr_used=False)])
    decoded = ubx_messages.decode(sat.encode())
    assert isinstance(decoded, ubx_messages.NavSat)
    assert decoded.num_svs == 1 and decoded.svs[0].pr_res == -1.5 and decoded.svs[0].flags == 0x191F


def test_a_poll_and_its_reply_are_paired() -> None:
    poll = ubx_messages.decode(ubx_messages.NavPvtPoll().encode())
    assert isinstance(poll, ubx_messages.NavPvtPoll) and poll.REPLIES == ("nav_pvt",)
    assert ubx_messages.CfgPrt.REPLIES == ("ack_ack", "ack_nak")


def test_layouts_of_one_class_and_id_are_told_apart_by_version_and_length() -> None:
    key = ubx_messages.cfg_valget.CfgValgetPollKey(key=0x40520001)   # a u4 item: its size in bits 28-30
    poll = ubx_messages.decode(ubx_messages.CfgValgetPoll(layer=0, position=0, keys=[key]).encode())
    assert isinstance(poll, ubx_messages.CfgValgetPoll) and poll.version == 0 and poll.keys == [key]
    answer = ubx_messages.CfgValget(layer=0, position=0, cfg_data=bytes.fromhex("01005240 00c20100"))
    assert isinstance(ubx_messages.decode(answer.encode()), ubx_messages.CfgValget)
    old = ubx_messages.NavRelposnedV0(ref_station_id=0, itow=0, rel_pos_n=0, rel_pos_e=0, rel_pos_d=0, rel_pos_hpn=0,
                                      rel_pos_hpe=0, rel_pos_hpd=0, reserved1=0, reserved2=0, acc_n=0, acc_e=0,
                                      acc_d=0, carr_soln=2)
    decoded = ubx_messages.decode(old.encode())
    assert isinstance(decoded, ubx_messages.NavRelposnedV0) and decoded.carr_soln == 2 and decoded.version == 0


def test_layouts_of_one_length_are_told_apart_by_their_type_byte() -> None:
    # MGA-INI's CLKD (type 0x20) and FREQ (0x21) are both 12 bytes: a type left None is written as
    # the layout's, and the type read picks the layout back.
    clkd = ubx_messages.MgaIniClkd(version=0, reserved0=0, clk_d=-1234, clk_d_acc=100)
    freq = ubx_messages.MgaIniFreq(version=0, reserved0=0, flags=0, freq=1.5, freq_acc=7)
    assert clkd.encode().hex(" ") == "b5 62 13 40 0c 00 20 00 00 00 2e fb ff ff 64 00 00 00 0a ea"
    for built in (clkd, freq):
        decoded = ubx_messages.decode(built.encode())
        assert type(decoded) is type(built) and decoded.type == built.SELECT[2] and built.type is None
    # a type no layout names (0x2F): read as the first layout of its length, the byte kept as sent
    frame = ubx.Frame(0x13, 0x40, bytes.fromhex("2f00000001000000 02000000")).encode()
    odd = ubx_messages.decode(frame)
    assert isinstance(odd, ubx_messages.MgaIniClkd) and odd.type == 0x2F and odd.encode() == frame


def test_a_reply_answers_the_request_it_names() -> None:
    rate = ubx_messages.CfgRate(meas_rate=200, nav_rate=1, time_ref=1)
    assert ubx.answers(rate, ubx_messages.AckAck(cls_id=0x06, msg_id=0x08))
    assert ubx.answers(rate, ubx_messages.AckNak(cls_id=0x06, msg_id=0x08))
    assert not ubx.answers(rate, ubx_messages.AckAck(cls_id=0x06, msg_id=0x00))   # CFG-PRT's
    poll = ubx_messages.NavPvtPoll()
    assert ubx.answers(poll, ubx_messages.NavPvt())
    assert not ubx.answers(poll, ubx_messages.AckAck(cls_id=0x01, msg_id=0x07))


def test_any_payload_decodes_and_encodes_back_or_gets_a_typed_error() -> None:
    draw = random.Random(31)
    for (msg_class, msg_id) in ubx_messages.BY_ID:
        for _ in range(60):
            frame = ubx.Frame(msg_class, msg_id, bytes(draw.randrange(256) for _ in range(draw.randrange(110))))
            try:
                message = ubx_messages.message(frame)
            except ubx.NmeaError as err:
                assert err.kind == "short_payload" and err.address.startswith("UBX "), str(err)
                continue
            assert message.encode() == frame.encode(), message


def test_a_nan_keeps_its_bits() -> None:
    payload = bytes(16) + bytes.fromhex("0100a07f") + bytes(44)   # pos_cov_nn: a signalling NaN
    message = ubx_messages.message(ubx.Frame(0x01, 0x36, payload))
    assert isinstance(message, ubx_messages.NavCov) and message.to_dict()["pos_cov_nn"] == "nan"
    assert message.payload() == payload


def test_a_whole_number_field_is_never_rounded_in_silence() -> None:
    """CFG-RATE's measurement period is whole milliseconds: 100.7 is refused, 100.0 taken."""
    rate = ubx_messages.decode(bytes.fromhex("b562060806006400010001007a12"))
    rate.meas_rate = 100.7
    with pytest.raises(ubx.NmeaError) as caught:
        rate.encode()
    assert (caught.value.kind, caught.value.name) == ("bad_value", "meas_rate")
    rate.meas_rate = 100.0
    assert rate.encode() == bytes.fromhex("b562060806006400010001007a12")
