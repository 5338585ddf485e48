"""The AIS decoder against pyais (pyais_oracle.py; requirements.txt installs pyais in the test
environment, the generated code does not use it). Measured with pyais 3.3.1 (2026-11): 1,721 messages of the 27 types (1,657 agree
in every field), 26,268 field values, 85 differences, all pyais's: the rate of turn in degrees per
minute (34), the 1/10-minute coordinates of types 17, 22 and 23 in minutes (25), ship type and
EPFD codes its enums lack folded into others (9), a name extension's partial last character (5),
type 26's communication state (5 not decoded, 4 kept in its data), the data of an addressed
unstructured type 26 read 16 bits late (1), type 17's latitude read as unsigned (1); and the type 1
of 163 bits ours refuses (1)."""

from __future__ import annotations

import pyais

from . import pyais_oracle


def test_every_difference_with_pyais_has_a_known_reason() -> None:
    found = pyais_oracle.agreement(lambda line: pyais.decode(line, error_if_checksum_invalid=False))
    assert sorted(found) == list(range(1, 28))
    unexplained = [f"{d.where}: type {d.message_type} {d.key}: ours {d.ours!r}, pyais {d.theirs!r}"
                   for a in found.values() for d in a.disagreements if d.reason is None]
    assert unexplained == []
