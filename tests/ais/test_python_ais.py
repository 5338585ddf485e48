"""The Python AIS codec (runtime/python/ais.py and the generated nmeaspec.ais_messages) against
the shared vectors (generated/vectors/ais.jsonl, the reference decoder's JSON of every example of
spec/ais/messages), byte-exact round trips over every single-sentence payload of gpsd's samples,
its errors, and the !AIVDM sentence's message."""

from __future__ import annotations

import dataclasses
import json
import sys
from decimal import Decimal
from pathlib import Path
from typing import Any

import pytest

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "generated" / "python"))

import nmeaspec  # noqa: E402
from nmeaspec import ais  # noqa: E402
from nmeaspec.ais_messages import APPLICATIONS, BY_TYPE, MeteoHydro, MeteoHydroImo236, decode_payload  # noqa: E402
from nmeaspec.ais_messages.position_report import PositionReport  # noqa: E402
from nmeaspec.ais_messages.static_voyage_data import StaticVoyageData  # noqa: E402
from nmeaspec.enums import VsdNavStatus  # noqa: E402
from nmeaspec.runtime import NmeaError  # noqa: E402

VECTORS = [json.loads(line) for line in (ROOT / "generated" / "vectors" / "ais.jsonl").open(encoding="utf-8")]
DATA = ROOT / "tests" / "data" / "ais"


def single_sentence_payloads() -> list[tuple[str, str, int]]:
    """(where, payload, fill bits) of every single-sentence !AIVDM/!AIVDO line of gpsd's samples."""
    out = []
    for path in sorted(DATA.iterdir()):
        for number, line in enumerate(path.read_text(encoding="utf-8", errors="replace").splitlines(), 1):
            if line.startswith(("!AIVDM,1,1,", "!AIVDO,1,1,")):
                fields = line.split("*")[0].split(",")
                out.append((f"{path.name}:{number}", fields[5], int(fields[6])))
    return out


@pytest.mark.parametrize("vector", VECTORS, ids=[v["where"][:50] for v in VECTORS])
def test_vector(vector: dict[str, Any]) -> None:
    if "error" in vector:
        with pytest.raises(NmeaError) as caught:
            decode_payload(vector["payload"], vector["fill_bits"])
        assert caught.value.kind == vector["error"], str(caught.value)
        return
    message = decode_payload(vector["payload"], vector["fill_bits"])
    assert message.to_dict() == vector["decode"]
    assert message.encode() == (vector["payload"], vector["fill_bits"])


def test_every_message_type_has_a_vector() -> None:
    decoded = {v["decode"]["message_type"] for v in VECTORS if "decode" in v}
    assert decoded == set(BY_TYPE) == set(range(1, 28))


def test_every_single_sentence_payload_of_gpsd_encodes_back_byte_for_byte() -> None:
    payloads = single_sentence_payloads()
    assert len(payloads) > 1500
    short = []
    for where, payload, fill_bits in payloads:
        try:
            message = decode_payload(payload, fill_bits)
        except NmeaError as err:
            assert err.kind == "short_payload", f"{where}: {err}"
            short.append(where)
            continue
        assert message.encode() == (payload, fill_bits), where
    assert short == ["sample.aivdm:1098"]   # "type=1 length=163": it ends inside the radio state


def test_a_position_report_in_units_with_its_raw_integers() -> None:
    m = decode_payload("15RTgt0PAso;90TKcjM8h6g208CQ", 0)
    assert isinstance(m, PositionReport)
    assert (m.status, m.speed, m.speed_raw, m.heading) == (VsdNavStatus.UNDER_WAY_ENGINE, 12.3, 123, 215)
    assert m.turn == ais.Special("left_no_indicator", -127) and m.turn_raw == -127
    assert m.lon == -74037230 / 600000 and m.lon_raw == -74037230
    assert m.lat_raw == 29028980 and m.course == 224.0


def test_not_available_is_a_named_value() -> None:
    m = decode_payload("16SteH0P00Jt63hHaa6SagvJ087r", 0)
    assert isinstance(m, PositionReport)
    assert m.heading == ais.Special("not_available", 511) and str(m.heading) == "not_available"
    assert m.to_dict()["heading"] == "not_available" and m.heading_raw == 511


def test_what_the_layout_does_not_read_is_kept_as_sent() -> None:
    m = decode_payload("15RTgt0PAso;90TKcjM8h6g208CQ", 0)
    m.spare, m.padding = 5, ""
    payload, fill_bits = m.encode()
    again = decode_payload(payload, fill_bits)
    assert again.spare == 5 and again.encode() == (payload, fill_bits)
    # Characters after the text's @ padding, 3 bits beyond a type 5's 424 and set fill bits.
    joined = "55?MbV02;H;s<HtKR20EHE:0@T4@Dn2222222216L961O5Gf0NSQEp6ClRp888888888880"
    voyage = decode_payload(joined, 2)
    assert isinstance(voyage, StaticVoyageData)
    voyage.shipname = "EVER DIADEM@@X@  @@ "
    voyage.trailing, voyage.padding = "101", "11010"
    payload, fill_bits = voyage.encode()
    assert fill_bits == 5
    again = decode_payload(payload, fill_bits)
    assert isinstance(again, StaticVoyageData)
    assert (again.shipname, again.trailing, again.padding) == ("EVER DIADEM@@X@  @@ ", "101", "11010")


@pytest.mark.parametrize("payload, fill_bits, kind, message", [
    ("15RTgt0PAso;90TKcjM8h6g208C", 0, "short_payload", "radio needs bits 149-167, the payload has 162"),
    ("15RTgt0PAso;90TKcjM8h6g208CQ", 6, "bad_armor", "fill bits are 0-5 (none for an empty payload), not 6"),
    ("15RTgt0PAso;90TKcjM8h6g2X8CQ", 0, "bad_armor", "character 'X' at offset 24 is not six-bit armoring"),
    ("w", 0, "unknown_message", "message type 63 is not one the spec describes"),
])
def test_errors_name_the_message_type_and_field(payload: str, fill_bits: int, kind: str, message: str) -> None:
    with pytest.raises(NmeaError) as caught:
        decode_payload(payload, fill_bits)
    assert (caught.value.kind, caught.value.message) == (kind, message)
    if kind == "short_payload":
        assert (caught.value.address, caught.value.name) == ("AIS type 1", "radio")


def test_encoding_refuses_a_value_its_field_cannot_hold() -> None:
    m = decode_payload("15RTgt0PAso;90TKcjM8h6g208CQ", 0)
    m.heading = 512
    with pytest.raises(NmeaError) as caught:
        m.encode()
    assert (caught.value.kind, caught.value.name, caught.value.address) == ("bad_value", "heading", "AIS type 1")


@pytest.mark.parametrize("value, refused", [(1.5, True), (False, True), (123.0, False), (123, False)])
def test_a_whole_number_field_is_never_rounded_in_silence(value: object, refused: bool) -> None:
    """A float for a field of whole numbers (no scale) is taken only when it is one: 1.5 MMSIs is an
    error, not MMSI 2; a scaled field rounds to its nearest raw value, as its unit says it must."""
    m = decode_payload("15RTgt0PAso;90TKcjM8h6g208CQ", 0)
    m.mmsi = value
    if refused:
        with pytest.raises(NmeaError) as caught:
            m.encode()
        assert (caught.value.kind, caught.value.name) == ("bad_value", "mmsi")
    else:
        assert decode_payload(*m.encode()).mmsi == 123
    m.mmsi, m.speed = 123, 10.04  # knots in tenths: the nearest, 100
    assert decode_payload(*m.encode()).speed == 10.0


def test_a_vdm_sentence_gives_its_message() -> None:
    vdm = nmeaspec.parse("!AIVDM,1,1,,B,13nUgBWP01PkHvDU7<kC4wvJ2>`<,0*27")
    assert vdm.message == decode_payload("13nUgBWP01PkHvDU7<kC4wvJ2>`<", 0)
    assert isinstance(vdm.message, PositionReport)
    first = nmeaspec.parse("!AIVDM,2,1,7,A,53aGulD0000000c7?0918Tq<E>0<Q8U=@Tp400155P:22uG`002ShTj0,0*05")
    assert first.message is None


def test_an_application_decodes_from_its_message_s_data_and_encodes_back() -> None:
    payload = "8h2=Vg@0Gh0TN1N>vAB0@PegFPClDIFcgwl?wnSwe7wvlOwwsAwwnSGmwvh0"
    message = decode_payload(payload, 0)
    meteo = message.application
    assert isinstance(meteo, MeteoHydro) and getattr(message, "data") is None
    assert (meteo.airtemp, meteo.airtemp_raw, meteo.pressure, meteo.pressure_raw) == (15.8, 158, 1012, 213)
    assert meteo.waterlevel == ais.Special("not_available", 4001)
    meteo.waterlevel = -9.84   # raw 16: metres from the chart datum, from -10
    again = decode_payload(*message.encode())
    assert isinstance(again.application, MeteoHydro)
    assert (again.application.waterlevel, again.application.waterlevel_raw) == (-9.84, 16)


def test_a_scaled_value_with_a_base_is_the_float_nearest_its_decimal() -> None:
    """raw / divisor + base in that order rounds twice (819 / 10 - 60 gives 21.900000000000006);
    every raw value of IMO 236's air temperature (÷ 10, from -60) gives the float of its decimal."""
    message = decode_payload("8@2<HV@0BkLfrhhJWJT0SQrhF;<qoweVwwwwwwwwwwwwwwwwwwwwwwwwwt0", 2)
    meteo = message.application
    assert isinstance(meteo, MeteoHydroImo236)
    assert (repr(meteo.airtemp), meteo.airtemp_raw) == ("21.9", 819)
    field = next(item for item in MeteoHydroImo236.LAYOUT if getattr(item, "id", None) == "airtemp")
    assert isinstance(field, ais.Unsigned)
    for raw in range(2047):   # 2047: not available
        assert field.from_raw(raw, 11) == float(Decimal(raw) / 10 - 60), raw


def test_data_an_application_does_not_read_stays_data() -> None:
    message = decode_payload("85Mwp`1Kf3aCnsNvBWLi=wQuNhA5t43N`5nCuI=p<IBfVqnMgPGs", 0)  # DAC 366 FI 56
    assert message.application is None and getattr(message, "data")


def _generic_decode(payload: str, fill_bits: int) -> ais.Message:
    """decode_payload by the generic reader only (Record.read), never the compiled decoders."""
    value, length, padding = ais._unarmor(payload, fill_bits)
    if length < 6:
        ais.BitReader(value, length, "AIS").peek(0, 6, "message_type")
    cls = BY_TYPE[value >> (length - 6)]
    reader = ais.BitReader(value, length, f"AIS type {value >> (length - 6)}")
    values = cls.read(reader)
    trailing = ais.bits_text(value & ((1 << reader.remaining) - 1), reader.remaining)
    message = cls(**values, trailing=trailing, padding=padding)
    if cls.DISPATCH is not None:
        message.application = ais._application(message, APPLICATIONS, compiled=False)
    return message


def _outcome(decode: Any, payload: str, fill_bits: int) -> tuple[Any, ...]:
    try:
        message = decode(payload, fill_bits)
    except NmeaError as error:
        return "error", str(error), error.name
    members = [(f.name, getattr(message, f.name)) for f in dataclasses.fields(message)]
    return type(message), members, message.to_dict()


def test_the_compiled_decoders_read_what_the_generic_reader_reads() -> None:
    """Every gpsd payload, and each message type's first payload cut at every length (with each
    count of fill bits, a character changed): the same members in the same order, or the same
    error (short payloads, optional fields missing, groups and choices)."""
    payloads = [(payload, fill) for _, payload, fill in single_sentence_payloads()]
    firsts: dict[str, str] = {}
    for vector in VECTORS:
        if "decode" in vector:
            firsts.setdefault(vector["message"], vector["payload"])
    for payload in firsts.values():
        payloads += [(payload[:n], fill) for n in range(len(payload) + 2) for fill in (0, 1, 5)]
        payloads += [(payload + "w0", 3), (payload[:5] + "w" + payload[6:], 0)]
    for payload, fill in payloads:
        assert _outcome(decode_payload, payload, fill) == _outcome(_generic_decode, payload, fill), (payload, fill)


def _generic_encode(message: ais.Message) -> tuple[str, int]:
    """Message.encode by the generic writer only (write_items), never the compiled encoders."""
    writer = ais.BitWriter()
    where = f"AIS type {message.message_type}"  # type: ignore[attr-defined]
    if message.application is not None:  # its data bits by the generic writer too
        data = ais.BitWriter()
        ais.write_items(type(message.application).LAYOUT, message.application, data, where)
        data.put_bits(message.application.trailing)
        message = dataclasses.replace(message, application=None)
        setattr(message, "data", ais.bits_text(data.value, data.length))
    ais.write_items(type(message).LAYOUT, message, writer, where)
    writer.put_bits(message.trailing)
    fill = -writer.length % 6
    if message.padding and (message.padding.strip("01") or len(message.padding) != fill):
        raise NmeaError("bad_value", "padding", where, name="padding")
    writer.put_bits(message.padding or "0" * fill)
    return ais.armor(writer.value, writer.length), fill


def test_the_compiled_encoders_write_what_the_generic_writer_writes() -> None:
    """Every gpsd payload and vector decoded, then written by both (each message with its first
    number, and its groups' entries' first number, made one too large): the same payload and fill
    bits, or the same error naming the same field."""
    payloads = [(payload, fill) for _, payload, fill in single_sentence_payloads()]
    payloads += [(v["payload"], v["fill_bits"]) for v in VECTORS if "decode" in v]
    for payload, fill in payloads:
        try:
            message = decode_payload(payload, fill)
        except NmeaError:  # (the payloads no message decodes from)
            continue
        changes: list[Any] = [None]
        records = [message, *(entry for f in dataclasses.fields(message)
                              if isinstance(entries := getattr(message, f.name), list) for entry in entries)]
        for record in records:
            number = next((f.name for f in dataclasses.fields(record)
                           if type(getattr(record, f.name)) is int and f.name != "message_type"), None)
            if number is not None:
                changes.append((record, number, getattr(record, number)))
        for change in changes:
            if change is not None:
                change[0].__setattr__(change[1], change[2] + (1 << 40))
            outcomes = []
            for encode in (type(message).encode, _generic_encode):
                try:
                    outcomes.append(encode(message))
                except NmeaError as error:
                    outcomes.append(("error", error.kind, error.name))
            assert outcomes[0] == outcomes[1], (payload, change)
            if change is not None:
                change[0].__setattr__(change[1], change[2])


def test_the_ais_sentence_fast_path_reads_what_the_general_path_reads() -> None:
    """nmeaspec.parse of an `!` line in its usual form (the fast path at the start of api.parse) against the general
    path (a line given as bytes takes it): gpsd's sentences and damaged copies of a sample."""
    lines = []
    for path in sorted(DATA.iterdir()):
        lines += [line for line in path.read_text(encoding="utf-8", errors="replace").splitlines()
                  if line.startswith("!")]
    for line in lines[::25]:
        fields = line.split(",")
        lines += [line.lower(), line[:-2] + line[-2:].lower(), line[:-1], line.replace(",", ",,", 1),
                  line.replace(",", "\t", 1), "!" + line, line + "*"]
        for k in range(1, len(fields)):  # a field changed, the checksum made to match
            for text in ("", "x", "10", "-1", "1.5", "C"):
                body = ",".join(fields[:k] + [text] + fields[k + 1:]).split("*")[0]
                lines.append(f"{body}*{nmeaspec.runtime.checksum(body[1:]):02X}")
    assert len(lines) > 3000
    for line in lines:
        outcomes = []
        for given in (line, line.encode("latin-1")):
            try:
                sentence = nmeaspec.parse(given)
                outcomes.append((repr(sentence), sentence.to_sentence()))
            except NmeaError as error:
                outcomes.append(("error", str(error)))
        assert outcomes[0] == outcomes[1], line
