"""The u-blox configuration database (spec/binary/ubx/config_keys.yaml) in Python: the key table
(nmeaspec.ubx_config_keys) agrees with pyubx2's, the CFG-VALSET/VALGET/VALDEL builders
(nmeaspec.ubx_config) make pyubx2's bytes, every key's value decodes as pyubx2 decodes it and
encodes back byte-exact, bad input is a typed error naming the key (test_config_tool.py: the
same on a receiver)."""

from __future__ import annotations

import random
import sys
from pathlib import Path
from typing import Any

import pytest
from pyubx2 import UBXMessage, UBXReader
from pyubx2.ubxtypes_configdb import UBX_CONFIG_DATABASE

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "generated" / "python"))

from nmeaspec import ubx, ubx_config, ubx_messages  # noqa: E402
from nmeaspec.ais import Special  # noqa: E402
from nmeaspec.runtime import NmeaError  # noqa: E402

DB = ubx_config.database()
PYUBX2_TYPE = {"L001": "L", "U001": "U1", "U002": "U2", "U004": "U4", "U008": "U8", "I001": "I1", "I002": "I2",
               "I004": "I4", "I008": "I8", "X001": "X1", "X002": "X2", "X004": "X4", "X008": "X8", "E001": "E1",
               "E002": "E2", "E004": "E4", "R004": "R4", "R008": "R8"}


def valget_answer(pairs: bytes, layer: int = 0, position: int = 0) -> bytes:
    return ubx.Frame(0x06, 0x8B, bytes((1, layer)) + position.to_bytes(2, "little") + pairs).encode()


# --------------------------------------------------------------------------------------------
# the key table


def test_every_key_of_pyubx2_has_its_id_and_type() -> None:
    assert len(UBX_CONFIG_DATABASE) == 1343 and len(DB.keys) == 1342   # one pyubx2 name is an alias
    for name, (key_id, kind) in UBX_CONFIG_DATABASE.items():
        key = DB.key(name)
        assert (key.id, key.type) == (key_id, PYUBX2_TYPE[kind]), name
    assert {k.name.replace("-", "_") for k in DB.keys} <= set(UBX_CONFIG_DATABASE)
    assert DB.key("CFG_BDS_USE_PRN_1_TO_5") is DB.key("CFG-BDS-USE_GEO_PRN")


def test_names_ids_and_scales_as_the_interface_description_gives_them() -> None:
    meas = DB.key("CFG-RATE-MEAS")
    assert (meas.id, meas.type, meas.divisor, meas.unit, meas.size) == (0x30210001, "U2", 1000, "s", 2)
    assert DB.key("cfg_rate_meas") is meas and DB.key(0x30210001) is meas and DB.key("0x30210001") is meas
    assert DB.key("CFG-HW-ANT_CFG_VOLTCTRL").id == 0x10A3002E   # an item's name keeps its underscores
    assert DB.key("CFG-TMODE-LAT").divisor == 10_000_000
    assert DB.key("CFG-NAVSPG-DYNMODEL").enum == {"PORT": 0, "STAT": 2, "PED": 3, "AUTOM": 4, "SEA": 5, "AIR1": 6,
                                                   "AIR2": 7, "AIR4": 8, "WRIST": 9, "BIKE": 10, "MOWER": 11,
                                                   "ESCOOTER": 12}
    with pytest.raises(NmeaError) as caught:
        DB.key("CFG-RATE-MESA")
    assert caught.value.kind == "unknown_key" and "CFG-RATE-MEAS" in caught.value.message
    unknown = DB.key(0x40FE0001)   # not in the table: sized by its id
    assert (unknown.name, unknown.size) == ("0x40FE0001", 4)
    with pytest.raises(NmeaError, match="bits 28-30"):
        DB.key(0x70FE0001)


def test_wildcards() -> None:
    assert DB.key_ids(["CFG-RATE-*"]) == [0x0021FFFF]
    assert DB.key_ids(["CFG_RATE_*", "cfg-*"]) == [0x0021FFFF, 0x0FFFFFFF]
    assert DB.key_ids(["CFG-SIGNAL-*"]) == [0x0031FFFF, 0x0032FFFF]   # a group of two ids
    with pytest.raises(NmeaError, match="no configuration group 'CFG-RATES'"):
        DB.key_ids(["CFG-RATES-*"])
    with pytest.raises(NmeaError, match="1 to 64 keys, not 65"):
        DB.key_ids(["CFG-MSGOUT-*"] * 65)


# --------------------------------------------------------------------------------------------
# the builders, against pyubx2's


def test_valset_valget_valdel_make_pyubx2s_bytes() -> None:
    message = ubx_config.valset({"CFG-RATE-MEAS": 0.1, "CFG_UART1_BAUDRATE": 115200, "CFG-RATE-TIMEREF": "GPS",
                                 "CFG-NMEA-HIGHPREC": True, "CFG-TMODE-LAT": -47.1234567,
                                 "CFG-TP-DUTY_TP1": 12.5, "CFG-TMODE-ECEF_X_HP": -9.9}, layers=("ram", "bbr"))
    theirs = UBXMessage.config_set(3, 0, [("CFG_RATE_MEAS", 100), ("CFG_UART1_BAUDRATE", 115200),
                                          ("CFG_RATE_TIMEREF", 1), ("CFG_NMEA_HIGHPREC", 1),
                                          ("CFG_TMODE_LAT", -471234567), ("CFG_TP_DUTY_TP1", 12.5),
                                          ("CFG_TMODE_ECEF_X_HP", -99)])
    assert message.encode() == theirs.serialize()
    assert ubx_messages.decode(message.encode()) == message   # decoded again: the same message
    assert ubx_config.values(message) == {"CFG-RATE-MEAS": 0.1, "CFG-UART1-BAUDRATE": 115200,
                                          "CFG-RATE-TIMEREF": "GPS", "CFG-NMEA-HIGHPREC": True,
                                          "CFG-TMODE-LAT": -47.1234567, "CFG-TP-DUTY_TP1": 12.5,
                                          "CFG-TMODE-ECEF_X_HP": -9.9}
    transaction = ubx_config.valset({"CFG-RATE-NAV": 2}, layers=("flash",), transaction=1)
    assert transaction.encode() == UBXMessage.config_set(4, 1, [("CFG_RATE_NAV", 2)]).serialize()
    assert (transaction.ID, transaction.action, transaction.flash) == ("cfg_valset", 1, True)
    poll = ubx_config.valget(["CFG-RATE-MEAS", "CFG-NAVSPG-DYNMODEL"], layer="flash", position=3)
    assert poll.encode() == UBXMessage.config_poll(2, 3, ["CFG_RATE_MEAS", "CFG_NAVSPG_DYNMODEL"]).serialize()
    delete = ubx_config.valdel(["CFG-RATE-MEAS", 0x20110021])
    assert delete.encode() == UBXMessage.config_del(6, 0, ["CFG_RATE_MEAS", "CFG_NAVSPG_DYNMODEL"]).serialize()
    assert ubx_config.valget(["CFG-MSGOUT-*"]).encode() == UBXMessage.config_poll(0, 0, [0x0091FFFF]).serialize()


def _random_raw(key: ubx_config.Key, rng: random.Random) -> int:
    if key.type == "L":
        return rng.randrange(2)
    if key.enum and rng.random() < 0.7:
        return rng.choice(list(key.enum.values()))
    return rng.randrange(1 << 8 * key.size)


def test_every_key_decodes_as_pyubx2_decodes_it_and_encodes_back() -> None:
    """A CFG-VALGET answer of every key (64 a frame) with random values: decoded, by name, to what
    pyubx2 reads (a scaled value times its divisor, an enumeration's number), and written back to
    the same bytes."""
    rng = random.Random(31)
    keys = list(DB.keys)
    for start in range(0, len(keys), 64):
        chunk = keys[start:start + 64]
        raws = {k.name: _random_raw(k, rng) for k in chunk}
        pairs = b"".join(k.id.to_bytes(4, "little") + raws[k.name].to_bytes(k.size, "little") for k in chunk)
        frame = valget_answer(pairs)
        message = ubx_messages.decode(frame)
        ours = ubx_config.values(message)
        assert list(ours) == [k.name for k in chunk]
        assert DB.encode_values(ours) == pairs
        assert ubx_config.values(message, raw=True) == raws
        theirs = UBXReader.parse(frame)
        for k in chunk:
            value, expected = ours[k.name], getattr(theirs, k.name.replace("-", "_"))
            if isinstance(value, Special):   # a NaN's bits
                assert expected != expected
                continue
            if k.enum and isinstance(value, str):
                value = k.enum[value]
            elif k.divisor != 1:
                value = round(value * k.divisor)
            if k.type[0] == "X":   # pyubx2: the bytes
                expected = int.from_bytes(expected, "little")
            if k.type[0] == "R":
                assert value == pytest.approx(expected, rel=1e-6), k.name
            else:
                assert value == expected, k.name


def test_unknown_keys_kept_raw_and_cut_values_named() -> None:
    pairs = (0x30210001).to_bytes(4, "little") + (250).to_bytes(2, "little") \
        + (0x40FE0001).to_bytes(4, "little") + (0xDEADBEEF).to_bytes(4, "little") \
        + (0x10FE0002).to_bytes(4, "little") + b"\x01"
    values = DB.decode_values(pairs)
    assert values == {"CFG-RATE-MEAS": 0.25, "0x40FE0001": 0xDEADBEEF, "0x10FE0002": 1}
    assert DB.encode_values({"CFG-RATE-MEAS": 0.25, 0x40FE0001: ubx_config.Raw(0xDEADBEEF),
                             "0x10FE0002": ubx_config.Raw(1)}) == pairs
    with pytest.raises(NmeaError) as caught:
        DB.decode_values(pairs[:5])
    assert (caught.value.kind, caught.value.name) == ("short_payload", "CFG-RATE-MEAS")
    assert str(caught.value) == "short_payload: UBX CFG-VALGET: CFG-RATE-MEAS needs 2 bytes at byte 4, there are 1"
    with pytest.raises(NmeaError) as caught:
        DB.decode_values(pairs[:12])
    assert (caught.value.kind, caught.value.name) == ("short_payload", "0x40FE0001")
    with pytest.raises(NmeaError) as caught:
        DB.decode_values(pairs[:2])
    assert (caught.value.kind, caught.value.name) == ("short_payload", "key")
    with pytest.raises(NmeaError) as caught:
        DB.decode_values((0x70FE0001).to_bytes(4, "little") + b"\x00")
    assert (caught.value.kind, caught.value.name) == ("bad_key", "0x70FE0001")


@pytest.mark.parametrize("name, value, wanted", [
    ("CFG-RATE-MEAS", 65.536, "a raw value 0..65535 (s x 1000)"),
    ("CFG-RATE-MEAS", "fast", "a number"),
    ("CFG-NAVSPG-DYNMODEL", "CAR", "one of PORT, STAT"),
    ("CFG-NMEA-HIGHPREC", 2, "true or false"),
    ("CFG-UART1-BAUDRATE", 9600.5, "a whole number"),
    ("CFG-NAVSPG-INFIL_MINELEV", -129, "a raw value -128..127"),
    ("CFG-TP-DUTY_TP1", "half", "a number"),
])
def test_bad_values_are_typed_errors_naming_the_key(name: str, value: Any, wanted: str) -> None:
    with pytest.raises(NmeaError) as caught:
        ubx_config.valset({name: value})
    assert (caught.value.kind, caught.value.name, caught.value.address) == ("bad_value", name, "UBX CFG-VALSET")
    assert wanted in caught.value.message


def test_bad_layers() -> None:
    with pytest.raises(NmeaError, match="takes the layers bbr, flash, not 'ram'"):
        ubx_config.valdel(["CFG-RATE-MEAS"], layers=("ram",))
    with pytest.raises(NmeaError, match="reads one layer of ram, bbr, flash, default"):
        ubx_config.valget(["CFG-RATE-MEAS"], layer="rom")
    with pytest.raises(NmeaError, match="needs a layer"):
        ubx_config.valset({"CFG-RATE-MEAS": 0.1}, layers=())
