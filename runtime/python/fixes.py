"""Fixes assembled across sentences: one `Fix` per epoch (the sentences of one UTC time of day).

    >>> from nmeaspec.fixes import fixes
    >>> for fix in fixes(open("drive.nmea")):   # doctest: +SKIP
    ...     print(fix.datetime, fix.latitude, fix.longitude, fix.mode)

Which field of which sentence carries which fact is the spec's (spec/fix.yaml and the `fix:` keys
of the sentences' fields, generated into fix_fields.py); this module only merges facts:

- An epoch is the run of sentences with the same time of day. A sentence without time (GSA, GSV,
  VTG, PUBX,03) joins the epoch under way; a sentence with another time closes it, as does the end
  of the stream (`FixAssembler.close`). While no sentence of the epoch has given a time (a
  receiver without a fix leaves it empty), a sentence whose layout has a time field closes it when
  the epoch already holds one from the same talker (GGA after GGA).
- A fix holds only what the sentences of its epoch say: a sentence sent at a lower rate leaves the
  other epochs without its facts. The one exception is the date: an epoch without one takes the
  last date seen, a day later when the time of day went back past midnight.
- Satellites in view come in sets of GSV sentences (one per talker and signal); a set belongs to
  the epoch in which its last sentence arrives. Satellites used (GSA) are kept per GNSS: the
  system id of NMEA 4.10, else the talker, else (GP, GN) the range of the satellite id.
- The mode (no fix, 2D, 3D) is the receiver's (GSA, PUBX,00) where the epoch has it, else
  inferred: no fix when a sentence calls the position invalid, 3D with an altitude, 2D without.
"""

from __future__ import annotations

import datetime as _dt
from collections.abc import Iterable, Iterator
from dataclasses import asdict, dataclass, field, fields
from typing import Any, NamedTuple

from . import runtime as rt
from .api import Tagged, parse
from .fix_fields import COMBINED_TALKER, DECIMAL_FACTS, FIELDS, SATELLITE_IDS, TALKER_SYSTEMS, FixField
from .runtime import NmeaError


@dataclass(slots=True)
class Satellite:
    """A satellite in view, as one signal's GSV set (or PUBX,03) reports it."""

    system: str | None
    """Its GNSS (gps, sbas, glonass, galileo, beidou, qzss, navic), None when not told."""
    id: int
    """Its id in the NMEA numbering of its talker."""
    talker: str
    signal: str | None = None
    """The signal id (NMEA 4.10) of its set, e.g. signal_1; None before NMEA 4.10."""
    elevation: int | None = None
    azimuth: int | None = None
    snr: int | None = None
    """Carrier-to-noise density [dB-Hz]; None when not tracked."""
    used: bool | None = None
    """Whether the solution uses it, where the receiver says so beside it (PUBX,03)."""


@dataclass(slots=True)
class Fix:
    """What the sentences of one epoch say. Every fact is None when no sentence of the epoch
    gave it; units are those of spec/fix.yaml (degrees, metres, metres per second)."""

    time: _dt.time | None = None
    date: _dt.date | None = None
    latitude: float | None = None
    longitude: float | None = None
    altitude_msl: float | None = None
    geoid_separation: float | None = None
    altitude_hae: float | None = None
    """Height above the ellipsoid: as sent (PUBX,00), else MSL altitude plus geoid separation."""
    speed: float | None = None
    course: float | None = None
    fix_quality: str | None = None
    """GGA's quality as a value id of gga_quality (autonomous, differential, rtk_fixed, ...)."""
    fix_status: str | None = None
    """valid or invalid (RMC, GLL)."""
    pos_mode: str | None = None
    """The NMEA 2.3 mode indicator as a value id (autonomous, differential, not_valid, ...)."""
    mode: str | None = None
    """no_fix, fix_2d or fix_3d: the receiver's (GSA, PUBX,00), else inferred (module doc)."""
    pdop: float | None = None
    hdop: float | None = None
    vdop: float | None = None
    tdop: float | None = None
    lat_error: float | None = None
    lon_error: float | None = None
    alt_error: float | None = None
    horizontal_error: float | None = None
    satellites_used: int | None = None
    """The receiver's count of satellites used (GGA, GNS, PUBX,00): the combined talker's (GN),
    else a proprietary sentence's (the receiver's total: PUBX,00 beside GPGGA), else the sum of
    each talker's (one GGA per system)."""
    used: dict[str, list[int]] = field(default_factory=dict)
    """The ids of the satellites used, per GNSS ("unknown" when no rule tells it)."""
    in_view: list[Satellite] = field(default_factory=list)
    """The satellites in view, one entry per satellite and signal."""
    sentences: list[str] = field(default_factory=list)
    """The sentences the fix came from, in order: talker and formatter (GNGGA) or the id of a
    proprietary sentence (PUBX_POSITION)."""

    @property
    def datetime(self) -> _dt.datetime | None:
        """The epoch's UTC date and time, when both are known."""
        if self.date is None or self.time is None:
            return None
        return _dt.datetime.combine(self.date, self.time, tzinfo=_dt.timezone.utc)

    @property
    def used_count(self) -> int:
        """How many satellites the GSA sentences of the epoch list as used."""
        return sum(len(ids) for ids in self.used.values())

    @property
    def in_view_count(self) -> int:
        """How many distinct satellites are in view (a satellite of several signals once)."""
        return len({(s.system, s.id) for s in self.in_view})

    def to_dict(self) -> dict[str, Any]:
        """The fix as plain values (ISO 8601 texts for date and time), for JSON and tables."""
        out: dict[str, Any] = {}
        for member in fields(self):
            value = getattr(self, member.name)
            if member.name == "in_view":
                value = [asdict(s) for s in value]
            elif isinstance(value, (_dt.date, _dt.time)):
                value = value.isoformat()
            out[member.name] = value
        return out


# The facts a Fix holds as the sentences give them, under their own names (the later sentence of
# an epoch wins); time, date and the satellites are merged by FixAssembler.
_SCALARS = frozenset(f.name for f in fields(Fix)) - {
    "time", "date", "satellites_used", "used", "in_view", "sentences"
}


class FixAssembler:
    """Turns a stream of sentences into fixes: `feed` each parsed sentence (or line) in order, it
    returns the fix of the epoch the sentence closed, if any; `close` ends the stream."""

    def __init__(self) -> None:
        self._fix: Fix | None = None
        self._sets: dict[tuple[str, str | None], tuple[int, list[Satellite]]] = {}
        self._last_date: tuple[_dt.date, _dt.time | None] | None = None
        self._counts: dict[str, int] = {}  # satellites used, by talker, in the epoch under way

    def feed(self, sentence: Any) -> Fix | None:
        """Add one sentence (a parsed one, or a line: one that does not parse is skipped)."""
        if isinstance(sentence, (str, bytes)):
            try:
                sentence = parse(sentence)
            except NmeaError:
                return None
        if isinstance(sentence, Tagged):  # the sentence behind its TAG blocks, if any
            sentence = sentence.sentence
        layout = _layout(type(sentence))
        if layout is None:
            return None
        facts, groups = _facts(sentence, layout)
        closed = None
        time = facts.pop("time", None)
        talker = getattr(sentence, "talker", None) or ""
        source = talker + type(sentence).SENTENCE
        under_way = self._fix
        if under_way is not None and (
            time is not None and under_way.time not in (None, time)
            # no time of day yet (a receiver without a fix): a sentence that has a time field
            # comes once an epoch, so its second one starts the next
            or time is None and under_way.time is None and "time" in layout.carried
            and source in under_way.sentences
        ):
            closed = self._finish()
        fix = self._fix if self._fix is not None else Fix()
        self._fix = fix
        if time is not None:
            fix.time = time
        fix.sentences.append(source)
        self._merge(fix, facts, groups, layout.carried, talker)
        return closed

    def close(self) -> Fix | None:
        """The fix of the epoch under way, at the end of the stream."""
        return self._finish() if self._fix is not None else None

    def _merge(
        self,
        fix: Fix,
        facts: dict[str, Any],
        groups: list[dict[str, Any]],
        carried: frozenset[str],
        talker: str,
    ) -> None:
        for name, value in facts.items():
            if name in _SCALARS and value is not None:
                setattr(fix, name, value)
        count = facts.get("satellites_used")
        if count is not None:
            self._counts[talker] = count
        date = facts.get("date") or _calendar(facts)
        if date is not None:
            fix.date = date
        if "used_satellite" in carried:
            system = facts.get("used_system")
            for entry in groups:
                sat = entry.get("used_satellite")
                if sat is not None:
                    ids = fix.used.setdefault(system or _system(talker, sat) or "unknown", [])
                    if sat not in ids:
                        ids.append(sat)
        if "satellite" in carried:
            self._satellites(fix, facts, groups, talker)

    def _satellites(
        self, fix: Fix, facts: dict[str, Any], groups: list[dict[str, Any]], talker: str
    ) -> None:
        """Collect a set of satellites in view; a set is the epoch's when its last part arrives
        (a report in one sentence, PUBX,03, is a set of one)."""
        signal = facts.get("signal")
        sats = [_satellite(g, talker, signal) for g in groups if g.get("satellite") is not None]
        size, index = facts.get("set_size") or 1, facts.get("set_index") or 1
        key = (talker, signal)
        if index == 1:
            self._sets[key] = (1, sats)
        elif key in self._sets and self._sets[key][0] == index - 1:
            self._sets[key] = (index, self._sets[key][1] + sats)
        else:  # a part missing: the set is incomplete
            self._sets.pop(key, None)
            return
        if index == size:
            kept = [s for s in fix.in_view if (s.talker, s.signal) != key]
            fix.in_view = kept + self._sets.pop(key)[1]

    def _finish(self) -> Fix:
        fix = self._fix
        assert fix is not None
        self._fix = None
        if fix.date is None and self._last_date is not None and fix.time is not None:
            date, time = self._last_date
            rolled_over = time is not None and fix.time < time
            fix.date = date + _dt.timedelta(days=1) if rolled_over else date
        if fix.date is not None:
            self._last_date = (fix.date, fix.time)
        counts, self._counts = self._counts, {}
        if counts:  # the combined talker's, else a proprietary sentence's (the receiver's total)
            total = counts.get(COMBINED_TALKER) if COMBINED_TALKER else None
            fix.satellites_used = total if total is not None else counts.get("", sum(counts.values()))
        msl, separation = fix.altitude_msl, fix.geoid_separation
        if fix.altitude_hae is None and msl is not None and separation is not None:
            fix.altitude_hae = msl + separation
        if fix.mode is None:
            fix.mode = _inferred_mode(fix)
        return fix


def fixes(stream: Iterable[Any]) -> Iterator[Fix]:
    """The fixes of a stream of parsed sentences or lines (an open log file), epoch by epoch."""
    assembler = FixAssembler()
    for sentence in stream:
        fix = assembler.feed(sentence)
        if fix is not None:
            yield fix
    last = assembler.close()
    if last is not None:
        yield last


def carries_facts(sentence: Any) -> bool:
    """Whether a parsed sentence has fields that carry facts of a fix (FixAssembler.feed takes
    it into an epoch; it skips the others)."""
    return _layout(type(sentence)) is not None


class _Layout(NamedTuple):
    """The fields of a layout that carry facts, as the assembler reads them."""

    fields: tuple[FixField, ...]        # outside the group
    group: str | None                    # the repeated group with satellite facts
    entry: tuple[FixField, ...]         # the facts of each of its entries
    carried: frozenset[str]             # every fact the layout carries


_LAYOUTS: dict[type, _Layout | None] = {}


def _layout(cls: type) -> _Layout | None:
    """The fact-carrying fields of a sentence class, or None (worked out once per class)."""
    try:
        return _LAYOUTS[cls]
    except KeyError:
        carried = FIELDS.get((getattr(cls, "SENTENCE", ""), getattr(cls, "VARIANT", None)))
        layout = None if carried is None else _Layout(
            tuple(f for f in carried if f.group is None),
            next((f.group for f in carried if f.group is not None), None),
            tuple(f for f in carried if f.group is not None),
            frozenset(f.fact for f in carried),
        )
        _LAYOUTS[cls] = layout
        return layout


def _facts(sentence: Any, layout: _Layout) -> tuple[dict[str, Any], list[dict[str, Any]]]:
    """The facts a sentence gives (converted to the Fix's types), and its group's, one dict per
    entry."""
    facts = {f.fact: _value(getattr(sentence, f.field), f) for f in layout.fields if f.field}
    if layout.group is None:
        return facts, []
    groups = [
        {f.fact: _value(getattr(entry, f.field) if f.field else entry, f) for f in layout.entry}
        for entry in getattr(sentence, layout.group)
    ]
    return facts, groups


def _value(value: Any, f: FixField) -> Any:
    """A field's value as the fact's: numbers scaled to its unit, enums as value ids (mapped by
    the spec's `from`), coordinates in signed degrees, time and date as datetime's."""
    if value is None or value is rt.ABSENT:
        return None
    if isinstance(value, rt.Number):  # a float where a decimal field may carry the fact
        number = float(value) if f.fact in DECIMAL_FACTS else int(value)
        return number * f.scale if f.scale != 1.0 else number
    convert = _CONVERT.get(type(value))
    if convert is not None:
        converted = convert(value)
        return converted * f.scale if f.scale != 1.0 and converted is not None else converted
    if isinstance(value, rt.CodeEnum):
        return f.values.get(value.id) if f.values is not None else value.id
    if isinstance(value, list):  # enum_chars: the first mode that is not not_valid
        ids = [v.id for v in value if isinstance(v, rt.CodeEnum)]
        return next((i for i in ids if i != "not_valid"), ids[0] if ids else None)
    return None  # an unknown enum code kept as text: no fact


def _system(talker: str, sat: int) -> str | None:
    """The GNSS of a satellite id under a talker (GP and GN: by the id's range)."""
    system = TALKER_SYSTEMS.get(talker)
    if system is not None:
        return system
    return next((name for name, low, high in SATELLITE_IDS if low <= sat <= high), None)


def _satellite(entry: dict[str, Any], talker: str, signal: str | None) -> Satellite:
    """A satellite in view of a group entry's facts."""
    sat = entry["satellite"]
    used = entry.get("satellite_used")
    return Satellite(_system(talker, sat), sat, talker, signal, entry.get("elevation"),
                     entry.get("azimuth"), entry.get("snr"), used == "used" if used else None)


def _calendar(facts: dict[str, Any]) -> _dt.date | None:
    """A date of three numbers (ZDA's day, month, year)."""
    try:
        return _dt.date(int(facts["year"]), int(facts["month"]), int(facts["day"]))
    except (KeyError, TypeError, ValueError):
        return None


def _inferred_mode(fix: Fix) -> str | None:
    """The mode where no sentence of the epoch gives it (module doc)."""
    if fix.latitude is None and fix.fix_quality is None and fix.fix_status is None:
        return None
    if fix.fix_status == "invalid" or fix.fix_quality == "invalid" or fix.pos_mode == "not_valid" \
            or fix.latitude is None:
        return "no_fix"
    return "fix_3d" if fix.altitude_msl is not None or fix.altitude_hae is not None else "fix_2d"


# --- Value conversions: the value types' own accessors (the same values as C and Rust give).

def _degrees(value: rt.Coordinate) -> float:
    return float(value)


def _time(value: rt.Time) -> _dt.time | None:
    """The time of day (Fix.datetime adds UTC); None for a leap second, which datetime cannot
    hold."""
    try:
        return value.to_time().replace(tzinfo=None)
    except ValueError:
        return None


def _date(value: rt.Date) -> _dt.date | None:
    """The date by the runtime's two-digit year rule (Date.full_year); None for a day its month
    does not have."""
    try:
        return value.to_date()
    except ValueError:
        return None


_CONVERT: dict[type, Any] = {
    rt.Coordinate: _degrees, rt.Time: _time, rt.Date: _date,
}
