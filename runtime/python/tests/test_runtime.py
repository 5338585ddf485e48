"""Unit tests of the Python runtime on its own (make test-runtimes): runtime/python/runtime.py
imported as it is, without any generated sentence module. The same cases as runtime/c/test_runtime.c."""

from __future__ import annotations

import importlib.util
import sys
from pathlib import Path

import pytest

_PATH = Path(__file__).resolve().parents[1] / "runtime.py"
_SPEC = importlib.util.spec_from_file_location("nmea_runtime_under_test", _PATH)
assert _SPEC and _SPEC.loader
rt = importlib.util.module_from_spec(_SPEC)
sys.modules[_SPEC.name] = rt
_SPEC.loader.exec_module(rt)


def test_a_sentence_frames() -> None:
    f = rt.frame("$GPGLL,5550.6135,N,03732.2515,E,075241.00,A,A*6E")
    assert (f.start, f.address, len(f.fields), f.checksum) == ("$", "GPGLL", 7, "6E")
    assert rt.frame("$PSTMSAVEPAR*58").fields == []
    assert rt.frame("$GPGLL,1*4d").checksum == "4d"
    assert rt.frame("$GPTXT,hello").checksum is None


@pytest.mark.parametrize(
    "line, kind, message",
    [
        ("", "not_a_sentence", "empty line"),
        ("GPGGA,1*00", "not_a_sentence", "line does not start with '$' or '!'"),
        (
            "$GPGLL,5550.6135,N,03732.2515,E,075241.00,A,A*6C",
            "checksum_mismatch",
            "checksum is 6C, computed 6E",
        ),
        ("$GPGLL,1*4D4", "bad_checksum", 'checksum "4D4" is not two hex digits of one letter case'),
        ("$GP\x01GLL,1", "not_a_sentence", "byte 0x01 at offset 3 is not printable ASCII"),
        (
            "$" + "A" * rt.MAX_LINE,
            "too_long",
            f"line is {rt.MAX_LINE + 1} bytes, the limit is {rt.MAX_LINE}",
        ),
    ],
)
def test_a_bad_line_is_refused_with_its_kind_and_message(
    line: str, kind: str, message: str
) -> None:
    with pytest.raises(rt.NmeaError) as caught:
        rt.frame(line)
    assert (caught.value.kind, caught.value.message) == (kind, message)


def test_a_missing_checksum_is_refused_when_one_is_required() -> None:
    with pytest.raises(rt.NmeaError) as caught:
        rt.frame("$GPGLL,1", require_checksum=True)
    assert (caught.value.kind, caught.value.message) == (
        "missing_checksum",
        "the sentence has no checksum",
    )


def test_a_checksum_of_one_digit_is_kept_unless_strict() -> None:
    frame = rt.frame("$PXYZ,0AW*1")  # the checksum is 0x01
    assert rt.checksum_case(frame.checksum) == "short_upper"
    assert rt.assemble("$", "PXYZ", ["0AW"], "short_lower") == "$PXYZ,0AW*1"
    assert rt.assemble("$", "PXYZ", ["1"], "short_lower") == "$PXYZ,1*16"  # two digits from 16 on
    for line, strict in (("$PXYZ,0AW*1", True), ("$PXYZ,0AW*2", False)):
        with pytest.raises(rt.NmeaError) as caught:
            rt.frame(line, strict=strict)
        assert caught.value.kind == "bad_checksum"


def test_a_query_address_is_two_talkers_and_q() -> None:
    assert rt.is_query_address("$", "CCGPQ")
    assert not rt.is_query_address("!", "CCGPQ")  # an encapsulation sentence is never one
    assert not rt.is_query_address("$", "PCGPQ")  # proprietary
    assert not rt.is_query_address("$", "CCGPQA")  # six characters: a 4-character formatter


def test_checksum_is_the_xor_of_the_body() -> None:
    assert rt.checksum("GPGLL,1") == 0x4D
    assert rt.checksum("PSTMSAVEPAR") == 0x58
    assert rt.checksum("A" * 9) == ord("A")


def test_numbers_keep_their_text() -> None:
    number = rt.parse_decimal("-007.50")
    assert number is not None
    assert (number.digits, number.scale, number.width, number.sign, number.point) == (
        750,
        2,
        3,
        "-",
        True,
    )
    assert rt.parse_decimal("1.2.3") is None
    assert rt.parse_integer("1.5") is None
    assert rt.parse_integer("9" * rt.MAX_DIGITS) is not None
    assert rt.parse_integer("9" * (rt.MAX_DIGITS + 1)) is None


def test_error_json() -> None:
    error = rt.NmeaError(
        "bad_field", 'expected integer 0..99, found "x"', "GPGSV", 3, "satellites_in_view", "x"
    )
    assert error.to_json() == (
        '{"ok":false,"error":{"kind":"bad_field","address":"GPGSV","field":3,"name":"satellites_in_view",'
        '"message":"expected integer 0..99, found \\"x\\""}}'
    )


def test_a_number_outside_its_range_is_refused_unless_its_text_is_range_kept() -> None:
    memo: dict[str, object] = {}
    args = ("GPTST", 1, "count", "integer 0..99", 0, 99, memo)
    with pytest.raises(rt.NmeaError) as refused:
        rt.number_field("123", True, *args)
    assert refused.value.out_of_range and refused.value.problem_kind == "out_of_range"
    kept = rt.number_field(rt.RangeKept("123"), True, *args)
    assert kept is not None and kept.digits == 123 and "123" not in memo  # never remembered
    with pytest.raises(rt.NmeaError) as malformed:
        rt.number_field(rt.RangeKept("12x"), True, *args)
    assert not malformed.value.out_of_range and malformed.value.problem_kind == "left_empty"
    assert rt.problem_json(refused.value) == (
        '{"kind":"out_of_range","field":1,"name":"count","text":"123",'
        '"message":"expected integer 0..99, found \\"123\\""}'
    )
    assert rt.with_problems(["123", "abc"], [refused.value]) == ["123", "abc"]


def test_values_as_python_expects_them() -> None:
    import datetime as dt

    number = rt.parse_decimal("-007.50")
    assert (float(number), int(number), number.text()) == (-7.5, -7, "-007.50")
    assert int(rt.parse_hex("1F")) == 31
    time = rt.parse_time("225446.1234567")
    assert time.to_time() == dt.time(22, 54, 46, 123456, tzinfo=dt.timezone.utc)
    assert time.ms_of_day() == 82486123
    with pytest.raises(ValueError):
        rt.parse_time("235960").to_time()  # datetime holds no leap second
    # The pivot: 00-68 are 20yy, 69-99 19yy.
    assert rt.parse_date("311268").to_date() == dt.date(2068, 12, 31)
    assert rt.parse_date("010169").to_date() == dt.date(1969, 1, 1)
    assert rt.parse_date("010170").days_since_epoch() == 0
    lat = rt.coordinate_field("4916.45", "S", "GPGLL", 1, "lat", "", "", "NS", {})
    assert (float(lat), lat.degrees_e7(), lat.degrees) == (-49.274166666666666, -492741667, 49)
    when = rt.utc_datetime(rt.parse_date("191194"), time)
    assert when == dt.datetime(1994, 11, 19, 22, 54, 46, 123456, tzinfo=dt.timezone.utc)
    assert rt.utc_datetime(rt.parse_date("310218"), time) is None  # no 31 February
    assert rt.utc_datetime(None, time) is None
    parts = [rt.Number.of(n) for n in (2003, 10, 14)]
    assert rt.utc_datetime_of(*parts, time) == when.replace(2003, 10, 14)
    assert rt.plain(rt.ABSENT) is None and rt.plain(lat) == float(lat)
    assert rt.plain(rt.parse_time("235960")) is None


class TagBlock(rt.TagBlock):
    """What the generated nmeaspec.tag_block.TagBlock gives the runtime: the codes, a property
    each (three of the spec's)."""

    __slots__ = ()
    CODES = {
        "c": rt.TagCode("c", "time", "integer"),
        "g": rt.TagCode("g", "group", "group"),
        "s": rt.TagCode("s", "source", "text"),
    }

    @property
    def time(self) -> int | None:
        return self.integer_of("c")

    @property
    def group(self) -> rt.TagGroup | None:
        return self.group_of("g")

    @property
    def source(self) -> str | None:
        return self.text_of("s")


def test_tag_blocks_are_read_and_written_back() -> None:
    line = "\\g:1-2-073874,q:u,s:r003669945,c:1241544035*16\\\\t:*4E\\$GPTST,12,abc*27"
    blocks, rest = rt.read_tag_blocks(TagBlock, line)
    assert rest == "$GPTST,12,abc*27"
    assert "".join(b.to_text() for b in blocks) + rest == line
    first = blocks[0]
    assert first.params[1] == ("q", "u") and first.get("t") is None and blocks[1].get("t") == ""
    assert (first.time, first.group, first.source) == (
        1241544035, rt.TagGroup(1, 2, 73874), "r003669945"
    )
    assert first.to_dict() == {"group": {"number": 1, "total": 2, "id": 73874}, "q": "u",
                               "source": "r003669945", "time": 1241544035}
    assert blocks[1].checksum == "upper" and rt.read_tag_blocks(TagBlock, "\\s:x*31\\")[1] == ""
    lower = rt.read_tag_blocks(TagBlock, "\\t:*4e\\")[0][0]
    assert lower.checksum == "lower" and lower.to_text() == "\\t:*4e\\"
    assert first.to_json() == (
        '{"params":[{"code":"g","value":"1-2-073874"},{"code":"q","value":"u"},'
        '{"code":"s","value":"r003669945"},{"code":"c","value":"1241544035"}],"checksum":"16"}'
    )


def test_a_tag_block_is_built_from_its_values() -> None:
    block = TagBlock(source="r003669945", time=1241544035)
    assert block.to_text() == "\\s:r003669945,c:1241544035*79\\"
    assert TagBlock([("x", "1")], group=(1, 2, 3)).to_text() == "\\x:1,g:1-2-3*32\\"
    with pytest.raises(rt.NmeaError, match="expected digits"):
        TagBlock(time="12a")
    with pytest.raises(rt.NmeaError, match="holds ',', '\\*' or a backslash"):
        TagBlock(source="a,b:c")
    with pytest.raises(TypeError):
        TagBlock(destination="x")


@pytest.mark.parametrize(
    "line, kind, message",
    [
        ("\\s:x*00\\", "bad_tag_block", "TAG block checksum is 00, computed 31"),
        ("\\s:x*31", "bad_tag_block", "TAG block has no closing backslash"),
        ("\\s:x\\", "bad_tag_block", 'TAG block "s:x" has no checksum'),
        ("\\s:x*3\\", "bad_tag_block",
         'TAG block checksum "3" is not two hex digits of one letter case'),
        ("\\sx*0B\\", "bad_tag_block", 'TAG block parameter "sx" is not code:value'),
        ("\\*00\\", "bad_tag_block", 'TAG block parameter "" is not code:value'),
        ("\\g:1-2*73\\", "bad_tag_block", 'TAG block parameter "g:1-2": expected n-m-id'),
        ("\\s:x*31\\GPGGA", "bad_tag_block",
         "TAG block is followed by neither '$', '!' nor a TAG block"),
        ("\\s:\x01*48\\", "not_a_sentence", "byte 0x01 at offset 3 is not printable ASCII"),
    ],
)
def test_bad_tag_blocks_say_why(line: str, kind: str, message: str) -> None:
    with pytest.raises(rt.NmeaError) as refused:
        rt.read_tag_blocks(TagBlock, line)
    assert (refused.value.kind, refused.value.message) == (kind, message)
