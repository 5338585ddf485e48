"""The AIS decoder against gpsd's decodes of its AIS samples (gpsd_oracle.py): every field of
every message gpsd decodes agrees, or differs for a reason known to be gpsd's (docs/ais-agreement.md,
per message type). Measured (2026-11):
1,721 messages of the 27 types (1,702 agree in every field), 26,432 field values (1,345 of them
those of 137 binary messages' applications: DAC 1 FI 2, 11, 16, 30, 31 and 40, DAC 200 FI 10 and
55, DAC 235 FI 10; where gpsd does not decode an application, its data bits), 21 differences,
all gpsd's:
- type 6 application (7): gpsd's samples of DAC 1 FI 12, 14, 18 and 32 are cut short of their
  layouts; gpsd reads zeros past the frame's end, ours keeps the bits as data.
- type 24 vendorid (6): gpsd reads 7 characters (ITU-R M.1371-3), through the model and serial
  number bits that M.1371-4 carved out of the vendor ID; ours is M.1371-5's 3 characters.
- type 26 radio (5): gpsd does not decode type 26's communication state (it reports 0).
- type 26 data (2): gpsd does not clear the bits of the data's last byte that belong to the
  communication state.
- type 1 (1): sample.aivdm's "type=1 length=163": gpsd reads its radio state from the 14 bits
  left; ours refuses it (short_payload)."""

from __future__ import annotations

from . import gpsd_oracle

FOUND = gpsd_oracle.agreement()


def test_every_message_type_is_compared() -> None:
    assert sorted(FOUND) == list(range(1, 28))
    assert sum(a.messages for a in FOUND.values()) == 1721
    assert sum(a.fields for a in FOUND.values()) == 26432


def test_the_applications_decode_every_message_of_their_dac_and_fi() -> None:
    decoded = {(t, dac, fid): (c.messages, c.ours, c.differences)
               for t, a in FOUND.items() for (dac, fid), c in a.applications.items() if c.ours}
    assert decoded == {(8, 1, 11): (10, 10, 0), (8, 1, 31): (8, 8, 0), (8, 200, 10): (51, 51, 0),
                       (6, 200, 55): (49, 49, 0), (6, 235, 10): (7, 7, 0), (6, 1, 2): (6, 6, 0),
                       (6, 1, 30): (1, 1, 0), (6, 1, 40): (3, 3, 0), (8, 1, 16): (2, 2, 0), (8, 367, 33): (1, 1, 0)}


def test_each_dac_and_fi_ours_keeps_as_data_has_a_reason() -> None:
    kept = {(t, dac, fid): gpsd_oracle.kept_as_data(t, dac, fid, c)
            for t, a in FOUND.items() for (dac, fid), c in a.applications.items()}
    assert [key for key, why in kept.items() if why and why.startswith("UNEXPLAINED")] == []


def test_every_difference_has_a_known_reason() -> None:
    unexplained = [f"{d.where}: type {d.message_type} {d.key}: ours {d.ours!r}, gpsd {d.theirs!r}"
                   for a in FOUND.values() for d in a.disagreements if d.reason is None]
    assert unexplained == []


def test_the_known_differences_are_those_measured() -> None:
    found = sorted((d.message_type, d.key) for a in FOUND.values() for d in a.disagreements)
    assert found == sorted([(1, "message")] + [(6, "application")] * 7 + [(24, "vendorid")] * 6 + [(26, "radio")] * 5
                           + [(26, "data")] * 2)


def test_the_agreement_report_is_current() -> None:
    assert gpsd_oracle.REPORT.read_text(encoding="utf-8") == gpsd_oracle.report(FOUND), \
        "docs/ais-agreement.md is stale: run `.venv/bin/python -m tests.ais.gpsd_oracle`"
