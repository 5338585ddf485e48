"""Unit tests of the AIS runtime on its own (make test-runtimes): runtime/python/ais.py imported as
it is, beside runtime.py in a package of their own, over a small hand-written layout instead of
the generated messages (those are tested against the shared vectors in tests/ais)."""

from __future__ import annotations

import importlib.util
import sys
import types
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, ClassVar

import pytest

_HERE = Path(__file__).resolve().parents[1]
_PACKAGE = types.ModuleType("nmea_ais_under_test")
_PACKAGE.__path__ = [str(_HERE)]
sys.modules[_PACKAGE.__name__] = _PACKAGE


def _load(name: str) -> Any:
    spec = importlib.util.spec_from_file_location(f"{_PACKAGE.__name__}.{name}", _HERE / f"{name}.py")
    assert spec and spec.loader
    module = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = module
    spec.loader.exec_module(module)
    return module


rt = _load("runtime")
ais = _load("ais")


@dataclass(slots=True)
class Reading:
    channel: int | None = None
    value: int | None = None


@dataclass
class Report(ais.Message):
    """The golden fixture's test_report: a flag, numbers in a unit (one with a special value), text,
    a choice after its selector, a group."""

    TYPES: ClassVar[tuple[int, ...]] = (1,)
    LAYOUT: ClassVar[tuple[Any, ...]] = (
        ais.Unsigned("message_type", 6),
        ais.Flag("addressed", 1),
        ais.Unsigned("quality", 4),
        ais.Unsigned("speed", 10, divisor=10, special=(ais.Special("not_available", 1023),)),
        ais.Signed("lon", 28, divisor=600000),
        ais.Text("name", 24),
        ais.Choice("addressed", 6, 1, (
            ais.Case(frozenset({1}), None, (ais.Unsigned("dest_mmsi", 30),)),
            ais.Case(frozenset(), None, (ais.Spare("spare", 30),)),
        )),
        ais.Group("readings", Reading, (ais.Unsigned("channel", 8), ais.Signed("value", 8)), 1, 2),
    )

    message_type: int | None = None
    addressed: bool | None = None
    quality: int | None = None
    speed: float | Any = None
    lon: float | None = None
    name: str | None = None
    dest_mmsi: int | None = None
    spare: int | None = None
    readings: list[Reading] = field(default_factory=list)


BY_TYPE = {1: Report}
# The example of tests/generator/golden/spec/ais/messages/test_report.yaml: two readings, a
# trailing bit and fill bits set.
PAYLOAD = "1Uwujj@90Q0@:sa:80wsT0g"


def test_armor_maps_six_bits_to_its_characters() -> None:
    assert [ais.armor_value(ch) for ch in "0W`w"] == [0, 39, 40, 63]
    assert ais.armor_value("X") is None and ais.armor_value("_") is None
    assert "".join(ais.armor_char(v) for v in (0, 39, 40, 63)) == "0W`w"


def test_a_layout_decodes_and_encodes_back() -> None:
    message = ais.decode(BY_TYPE, {}, PAYLOAD, 2)
    assert isinstance(message, Report)
    assert (message.addressed, message.speed, message.name, message.dest_mmsi, message.spare) == \
        (True, ais.Special("not_available", 1023), "AB@ ", 366814480, None)
    assert message.lon == -74037230 / 600000 and message.raw("lon") == -74037230
    assert message.readings == [Reading(7, -3), Reading(200, 5)]
    assert (message.trailing, message.padding) == ("1", "11")
    assert message.encode() == (PAYLOAD, 2)
    assert message.to_dict()["speed"] == "not_available" and message.to_dict()["speed_raw"] == 1023


def test_the_other_case_of_a_choice() -> None:
    message = ais.decode(BY_TYPE, {}, PAYLOAD, 2)
    message.addressed, message.spare = False, 12345
    again = ais.decode(BY_TYPE, {}, *message.encode())
    assert (again.addressed, again.dest_mmsi, again.spare) == (False, None, 12345)


@pytest.mark.parametrize("payload, fill_bits, kind", [
    (PAYLOAD, 6, "bad_armor"),
    ("X", 0, "bad_armor"),
    ("", 1, "bad_armor"),
    ("w", 0, "unknown_message"),
    (PAYLOAD[:10], 0, "short_payload"),
])
def test_errors(payload: str, fill_bits: int, kind: str) -> None:
    with pytest.raises(rt.NmeaError) as caught:
        ais.decode(BY_TYPE, {}, payload, fill_bits)
    assert caught.value.kind == kind


def test_encoding_checks_each_value() -> None:
    message = ais.decode(BY_TYPE, {}, PAYLOAD, 2)
    message.name = "ab"
    with pytest.raises(rt.NmeaError) as caught:
        message.encode()
    assert (caught.value.kind, caught.value.name) == ("bad_value", "name")
