"""pyrtcm as the oracle of the RTCM 3 message contents (tests/rtcm3/pyrtcm_oracle.py): every
field of every frame of the logs and of one made-up payload per other message number agrees with
pyrtcm but for the differences docs/rtcm3-agreement.md lists with their reasons, and that page
is the oracle's current report."""

from __future__ import annotations

from tests.rtcm3.pyrtcm_oracle import REPORT, differences, field_agreement, log_frames, made_up_agreement, report


def test_every_logged_message_agrees_with_pyrtcm_and_encodes_back() -> None:
    rows = field_agreement()
    from nmeaspec import rtcm3_messages

    described = [raw for _, raw in log_frames() if raw[3] << 4 | raw[4] >> 4 in rtcm3_messages.BY_NUMBER]
    assert sum(a.frames for a in rows.values()) == len(described) >= 230
    for number, a in rows.items():
        assert a.encoded == a.frames, number
        assert a.compared >= 6 and not a.only_theirs, (number, a.only_theirs)
        assert not [row for row in differences(number, a) if "not described" in row], number


def test_messages_no_log_carries_agree_with_pyrtcm_but_for_known_reasons() -> None:
    rows = made_up_agreement()
    assert len(rows) >= 30
    for number, a in rows.items():
        assert a.encoded == a.frames, number
        assert a.failed or a.compared >= 10, number
        assert not [row for row in differences(number, a) if "not described" in row], number
    assert {n for n, a in rows.items() if a.failed} == {1072, 1082, 1092, 1102, 1112, 1122, 1132}


def test_the_report_is_current() -> None:
    assert REPORT.read_text(encoding="utf-8") == report(), \
        "docs/rtcm3-agreement.md is stale: .venv/bin/python -m tests.rtcm3.pyrtcm_oracle"
