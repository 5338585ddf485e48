"""`nmea report`: a receiver log as pictures, in one self-contained HTML page.

    nmea report track.nmea -o track.html

The page shows what a receiver's own viewer shows: the track, a sky plot, C/N0 per satellite over
time, the fix quality, the satellites used and the DOPs over time, and the sentences and decode
errors of the log. Nothing on it is fetched when it is viewed: the pictures are PNGs inside it.

The log is read once, as a stream of decoded sentences; the charts draw the fixes they make, one
per epoch (nmeaspec.fixes: the facts of GGA, RMC, GSA, GSV, PUBX and the other sentences of one
UTC time merged), gathered as it goes. A series that grows past its limit is thinned (every other point dropped, and from then
on only every second, fourth... point kept), so memory stays bounded however long the log is.
The pictures are drawn by matplotlib, an optional dependency (`pip install 'nmeaspec[report]'`)
imported only when a report is drawn: the rest of the package needs only the standard library.
"""

from __future__ import annotations

import argparse
import base64
import datetime as dt
import html
import io
import itertools
import math
import os
import statistics
import sys
import typing
from collections import Counter
from typing import TYPE_CHECKING, Any

from ..api import Tagged, parse
from ..assembly import MessageAssembler
from ..fixes import Fix, FixAssembler, Satellite, carries_facts
from ..runtime import NmeaError
from ..stream import lines, too_long
from .nmea_cli import CliError, _chunks, add_progress_options, open_log, progress_for

if TYPE_CHECKING:  # matplotlib is optional: without it these are Any to mypy
    from matplotlib.axes import Axes  # type: ignore[import-not-found, unused-ignore]
    from matplotlib.figure import Figure  # type: ignore[import-not-found, unused-ignore]
    from matplotlib.projections.polar import (  # type: ignore[import-not-found, unused-ignore]
        PolarAxes,
    )

REPORT_EXAMPLES = """\
examples:
  nmea report track.nmea                     writes track.html in the current directory
  nmea report track.nmea -o ~/track.html
  nmea report --progress big.nmea -o big.html

The page holds its pictures (PNG) and needs nothing else to be viewed. It needs matplotlib to be
drawn: pip install 'nmeaspec[report]'.
"""

INSTALL_HINT = (
    "nmea report draws with matplotlib, which is not installed: pip install 'nmeaspec[report]'"
)

# How much of a log the page keeps, whatever its length.
SERIES_LIMIT = 4000  # points of a series over time (the thinning keeps them evenly spread)
TRACK_LIMIT = 20000  # fixes of the track
CN0_LIMIT = 1500  # C/N0 samples of one satellite signal
TRAIL_LIMIT = 500  # sky positions of one satellite (kept only when they change)
MAX_SATELLITES = 400  # satellites (and signals) followed; later ones are only counted
MAX_KEYS = 500  # rows of the sentence table kept apart; the rest are counted together
FIRST_ERRORS = 10  # error lines quoted
MAX_TARGETS = 1000  # AIS stations followed; later ones are only counted
TARGET_TRACK_LIMIT = 500  # positions of one AIS station
TARGETS_LISTED = 50  # rows of the AIS table
TARGETS_NAMED = 12  # AIS stations labelled on their map
COLUMNS = 400  # time columns of the C/N0 picture
CN0_ROWS = 120  # satellite signals in the C/N0 picture (those with the most samples)

# Satellite systems: the letter of a satellite's name (RINEX style), its name and colour.
SYSTEMS: dict[str, tuple[str, str]] = {
    "G": ("GPS", "#1f77b4"),
    "R": ("GLONASS", "#d62728"),
    "E": ("Galileo", "#2ca02c"),
    "C": ("BeiDou", "#ff7f0e"),
    "J": ("QZSS", "#9467bd"),
    "I": ("NavIC", "#e377c2"),
    "S": ("SBAS", "#8c564b"),
    "?": ("other", "#7f7f7f"),
}

# Fix levels, in the order the quality chart stacks them, with their colours.
LEVELS: dict[str, str] = {
    "no fix": "#9e9e9e",
    "dead reckoning": "#8c564b",
    "2D": "#bcbd22",
    "3D": "#1f77b4",
    "autonomous": "#1f77b4",
    "differential": "#17becf",
    "precise": "#9467bd",
    "RTK float": "#ff7f0e",
    "RTK fixed": "#2ca02c",
    "other": "#e377c2",
}
# The level of a fix: GGA's quality where the epoch has it (value ids of gga_quality), else the
# mode indicator of NMEA 2.3 (pos_mode, gns_mode), else the fix dimension (GSA, PUBX,00).
QUALITY_LEVELS = {
    "invalid": "no fix",
    "autonomous": "autonomous",
    "differential": "differential",
    "pps": "precise",
    "rtk_fixed": "RTK fixed",
    "rtk_float": "RTK float",
    "dead_reckoning": "dead reckoning",
}
MODE_LEVELS = {
    "not_valid": "no fix",
    "estimated": "dead reckoning",
    "autonomous": "autonomous",
    "differential": "differential",
    "precise": "precise",
    "rtk_float": "RTK float",
    "rtk_fixed": "RTK fixed",
    "fixed_or_coarse": "RTK fixed",
}
DIMENSION_LEVELS = {"no_fix": "no fix", "fix_2d": "2D", "fix_3d": "3D"}
# A satellite system's letter (RINEX style), by the fix's system names.
SYSTEM_LETTERS = {
    "gps": "G",
    "glonass": "R",
    "galileo": "E",
    "beidou": "C",
    "qzss": "J",
    "navic": "I",
    "sbas": "S",
}

At = tuple[int, "float | None"]  # where a sample is: its line, and UTC seconds when known
P = typing.TypeVar("P")


class Thinned(typing.Generic[P]):
    """The points of a series, at most `limit` of them: past the limit every other point is
    dropped, and from then on only every `stride`-th point added is kept, so that the points stay
    evenly spread over the log. The last point added is kept as well."""

    def __init__(self, limit: int) -> None:
        self.limit = limit
        self.points: list[P] = []
        self.stride = 1
        self.added = 0
        self.last: P | None = None

    def add(self, point: P) -> None:
        if self.added % self.stride == 0:
            self.points.append(point)
            if len(self.points) > self.limit:
                del self.points[1::2]
                self.stride *= 2
        self.added += 1
        self.last = point

    def all(self) -> list[P]:
        """The kept points, then the last one added."""
        if self.last is None or (self.points and self.points[-1] is self.last):
            return list(self.points)
        return [*self.points, self.last]


class Clock:
    """UTC time of day of the epochs, in seconds, with the day counted on past midnight: each
    time is put on the day that brings it within 12 hours of the previous one, so 23:59:59 then
    00:00:00 is a second later (and a receiver whose clock steps back across midnight goes
    back)."""

    def __init__(self) -> None:
        self.now: float | None = None
        self.days = 0
        self.low = math.inf
        self.high = -math.inf

    def see(self, time: dt.time) -> None:
        seconds = time.hour * 3600 + time.minute * 60 + time.second + time.microsecond / 1e6
        value = seconds + self.days * 86400
        if self.now is not None and value < self.now - 43200:
            self.days += 1
            value += 86400
        elif self.now is not None and value > self.now + 43200:
            self.days -= 1
            value -= 86400
        self.now = value
        self.low = min(self.low, value)
        self.high = max(self.high, value)


def satellite(sat: Satellite) -> tuple[str, int]:
    """A satellite's system letter and its number in that system, from the fix's system and the
    NMEA id (GLONASS 65-96, Galileo 301-336, BeiDou 401-463 or 201-263, QZSS 193-202 and SBAS
    33-64 as receivers number them, taken back to the system's own numbers)."""
    letter, prn = SYSTEM_LETTERS.get(sat.system or "", "?"), sat.id
    if letter == "R" and 65 <= prn <= 96:
        return letter, prn - 64
    if letter == "E" and 301 <= prn <= 336:
        return letter, prn - 300
    if letter == "C":
        return letter, prn - 400 if 401 <= prn <= 463 else prn - 200 if 201 <= prn <= 263 else prn
    if letter == "J" and 193 <= prn <= 202:
        return letter, prn - 192
    if letter == "S" and 33 <= prn <= 64:
        return letter, prn + 87
    return letter, prn


def satellite_name(system: str, number: int) -> str:
    return f"{system}{number:02d}"


def level_of(fix: Fix) -> str | None:
    """The fix level of an epoch (QUALITY_LEVELS), None when no sentence of it tells."""
    if fix.mode == "no_fix" or fix.fix_status == "invalid":
        return "no fix"
    for value, levels in ((fix.fix_quality, QUALITY_LEVELS), (fix.pos_mode, MODE_LEVELS),
                          (fix.mode, DIMENSION_LEVELS)):
        if value is not None:
            return levels.get(value, "other")
    return "autonomous" if fix.fix_status == "valid" else None


class Target:
    """An AIS station: its name (static reports), its positions (position reports) and how many
    messages it sent."""

    def __init__(self) -> None:
        self.name: str | None = None
        self.messages = 0
        self.track = Thinned[tuple[float, float]](TARGET_TRACK_LIMIT)


def _degrees_of(value: Any) -> float | None:
    """A position field of an AIS message in degrees; None when not available."""
    return float(value) if isinstance(value, float) else None


class Log:
    """What a report shows of a log, gathered line by line (read) in bounded memory: the
    sentences and errors counted, and the fixes the sentences make (nmeaspec.fixes), epoch by
    epoch, as series over time."""

    def __init__(self) -> None:
        self.lines = 0
        self.decoded = 0
        self.counts: Counter[tuple[str, str]] = Counter()  # (sentence id or address, talker)
        self.names: dict[str, str] = {}
        self.errors: Counter[str] = Counter()
        self.first_errors: list[tuple[int, str, str, str]] = []
        self.clock = Clock()
        self.timed = 0
        self.untimed = 0
        self.dates: list[str] = []  # the first and the last date seen
        self.epochs = 0
        self.fix_sentences: Counter[str] = Counter()  # the sentences that made the fixes
        self.track = Thinned[tuple[At, float, float, str]](TRACK_LIMIT)
        self.quality = Thinned[tuple[At, str]](SERIES_LIMIT)
        self.used = Thinned[tuple[At, float]](SERIES_LIMIT)
        self.in_view = Thinned[tuple[At, float]](SERIES_LIMIT)
        self.dops = {name: Thinned[tuple[At, float]](SERIES_LIMIT) for name in ("HDOP", "PDOP", "VDOP")}
        self.cn0: dict[tuple[str, int, str], Thinned[tuple[At, float]]] = {}
        self.trails: dict[tuple[str, int], Thinned[tuple[float, float]]] = {}
        self.tracked: dict[tuple[str, int], bool] = {}  # whether it had a C/N0 in its last epoch
        self.ignored_satellites = 0
        self.targets: dict[int, Target] = {}
        self.ais_messages = 0
        self.ais_unfollowed = 0  # messages of stations beyond MAX_TARGETS
        self.ais_errors: Counter[str] = Counter()
        self._assembler = MessageAssembler()
        self._fixes = FixAssembler()
        self._epoch_line = 0  # the first line of the epoch under way

    # -- reading ------------------------------------------------------------------------------

    def read(self, items: typing.Iterable[bytes | int]) -> None:
        for number, item in enumerate(items, 1):
            self.lines += 1
            try:
                if isinstance(item, int):
                    raise too_long(item)
                sentence = parse(item)
            except NmeaError as err:
                self._error(number, err, item)
                continue
            for done in self._assembler.feed(sentence):
                self._ais(done.message, done.error)
            if isinstance(sentence, Tagged):  # the sentence behind its TAG blocks, if any
                sentence = sentence.sentence
                if sentence is None:
                    continue
            self.add(number, sentence)
        fix = self._fixes.close()
        if fix is not None:
            self._epoch(fix, self._epoch_line)
        for done in self._assembler.finish():
            self._ais(done.message, done.error)

    def _ais(self, message: Any, error: NmeaError | None) -> None:
        """Take in an AIS message, or count why one did not decode or complete."""
        if message is None:
            assert error is not None
            self.ais_errors[error.kind] += 1
            return
        self.ais_messages += 1
        mmsi = getattr(message, "mmsi", None)
        if not isinstance(mmsi, int):
            return
        target = self.targets.get(mmsi)
        if target is None:
            if len(self.targets) >= MAX_TARGETS:
                self.ais_unfollowed += 1
                return
            target = self.targets[mmsi] = Target()
        target.messages += 1
        name = getattr(message, "shipname", None) or getattr(message, "name", None)
        if isinstance(name, str) and name.rstrip("@ "):
            target.name = name.rstrip("@ ")
        lat, lon = _degrees_of(getattr(message, "lat", None)), _degrees_of(getattr(message, "lon", None))
        if lat is not None and lon is not None:
            target.track.add((lat, lon))

    def _error(self, number: int, err: NmeaError, item: bytes | int) -> None:
        self.errors[err.kind] += 1
        if len(self.first_errors) < FIRST_ERRORS:
            text = f"({item} bytes)" if isinstance(item, int) else _printable(item)
            self.first_errors.append((number, err.kind, str(err), text))

    def _count(self, name: str, talker: str, description: str) -> None:
        key = (name, talker)
        if key not in self.counts and len(self.counts) >= MAX_KEYS:
            key = ("(others)", "")
        self.counts[key] += 1
        if name not in self.names and len(self.names) < MAX_KEYS:
            self.names[name] = description

    def add(self, number: int, sentence: Any) -> None:
        """Take in one decoded sentence, the `number`th line of the log."""
        self.decoded += 1
        name = sentence.SENTENCE
        if name is None:  # a well-formed sentence the spec does not describe
            self._count(sentence.address, "", "not in the spec")
            return
        talker = getattr(sentence, "talker", "") if sentence.ADDRESS is None else ""
        self._count(name, talker, _description(sentence))
        if not carries_facts(sentence):
            return
        self.fix_sentences[name] += 1
        fix = self._fixes.feed(sentence)
        if fix is not None:
            self._epoch(fix, self._epoch_line)
            self._epoch_line = 0
        self._epoch_line = self._epoch_line or number

    def _epoch(self, fix: Fix, line: int) -> None:
        """Take in the fix of an epoch that began at `line`."""
        self.epochs += 1
        if fix.time is not None:
            self.clock.see(fix.time)
            self.timed += 1
            at: At = (line, self.clock.now)
        else:
            self.untimed += 1
            at = (line, None)
        if fix.date is not None:
            text = fix.date.isoformat()
            if not self.dates:
                self.dates.append(text)
            self.dates[1:] = [text]
        level = level_of(fix)
        if level is not None:
            self.quality.add((at, level))
            position = (fix.latitude, fix.longitude)
            if level != "no fix" and position[0] is not None and position[1] is not None \
                    and position != (0.0, 0.0):  # 0, 0: a receiver's placeholder, not a place
                self.track.add((at, position[0], position[1], level))
        # the receiver's count (GGA caps it at 12 on some) or the ids GSA lists, the larger
        used = max(fix.satellites_used or 0, fix.used_count) if fix.satellites_used is not None \
            or fix.used else None
        if used is not None:
            self.used.add((at, float(used)))
        if fix.in_view:
            self.in_view.add((at, float(fix.in_view_count)))
        for name in self.dops:
            value = getattr(fix, name.lower())
            if value is not None:
                self.dops[name].add((at, value))
        self._satellites(fix, at)

    def _satellites(self, fix: Fix, at: At) -> None:
        """The sky positions and C/N0 of the satellites in view of an epoch."""
        tracked: dict[tuple[str, int], bool] = {}
        for entry in fix.in_view:
            sat = satellite(entry)
            if sat not in self.trails and len(self.trails) >= MAX_SATELLITES:
                self.ignored_satellites += 1
                continue
            trail = self.trails.setdefault(sat, Thinned(TRAIL_LIMIT))
            elevation, azimuth = entry.elevation, entry.azimuth
            if azimuth is not None and elevation is not None and 0 <= elevation <= 90:
                place = (float(azimuth), float(elevation))
                if trail.last != place:
                    trail.add(place)
            tracked.setdefault(sat, False)
            if entry.snr:  # 0 is what some receivers send for a satellite they do not track
                tracked[sat] = True
                key = (*sat, entry.signal or "")
                cn0 = self.cn0.get(key)
                if cn0 is None and len(self.cn0) < MAX_SATELLITES:
                    cn0 = self.cn0[key] = Thinned(CN0_LIMIT)
                if cn0 is not None:
                    cn0.add((at, float(entry.snr)))
        self.tracked.update(tracked)


def _description(sentence: Any) -> str:
    """The title of a sentence class: "Global positioning system fix data" for GGA."""
    first = (type(sentence).__doc__ or "").strip().split("\n", 1)[0]
    return first.partition(": ")[2].rstrip(".") or first


def _printable(line: bytes, limit: int = 120) -> str:
    text = line.decode("latin-1")
    text = "".join(c if c.isprintable() else f"\\x{ord(c):02x}" for c in text)
    return text if len(text) <= limit else text[: limit - 1] + "…"


# --------------------------------------------------------------------------------------------
# the pictures


class Axis:
    """The time axis of the charts: UTC time of day when most samples have one, else the line."""

    NICE = (1, 2, 5, 10, 15, 30, 60, 120, 300, 600, 900, 1800, 3600, 7200, 10800, 21600, 43200)

    def __init__(self, log: Log) -> None:
        total = log.timed + log.untimed
        self.utc = log.timed > 0 and log.timed >= 0.9 * total
        self.dropped = log.untimed if self.utc else 0
        date = f", {log.dates[0]}" if log.dates else ""
        self.label = f"UTC{date}" if self.utc else "line of the log"

    def x(self, at: At) -> float | None:
        return at[1] if self.utc else float(at[0])

    def points(self, series: typing.Iterable[tuple[At, P]]) -> tuple[list[float], list[P]]:
        xs: list[float] = []
        values: list[P] = []
        for at, value in series:
            x = self.x(at)
            if x is not None:
                xs.append(x)
                values.append(value)
        return xs, values

    def style(self, ax: Axes, low: float, high: float) -> None:
        ax.set_xlabel(self.label)
        if not self.utc:
            return
        from matplotlib.ticker import (  # type: ignore[import-not-found, unused-ignore]
            FuncFormatter,
            MultipleLocator,
        )

        span = max(high - low, 1.0)
        step = next((n for n in self.NICE if span / n <= 8), 86400)
        ax.xaxis.set_major_locator(MultipleLocator(step))
        ax.xaxis.set_major_formatter(FuncFormatter(lambda value, _: clock_text(value, step < 60)))


def clock_text(seconds: float, with_seconds: bool = True) -> str:
    day, rest = divmod(seconds, 86400)
    hours, rest = divmod(int(rest), 3600)
    minutes, secs = divmod(rest, 60)
    text = f"{hours:02d}:{minutes:02d}" + (f":{secs:02d}" if with_seconds else "")
    return f"{text} {int(day):+d}d" if day else text


def _figure(width: float, height: float) -> Figure:
    from matplotlib.figure import Figure  # type: ignore[import-not-found, unused-ignore]

    figure = Figure(figsize=(width, height), layout="constrained")
    return figure


def _png(figure: Figure) -> str:
    """The picture as a data: URI (no date or software in it: the same log, the same bytes)."""
    buffer = io.BytesIO()
    figure.savefig(buffer, format="png", dpi=DPI, metadata={"Software": None})
    return "data:image/png;base64," + base64.b64encode(buffer.getvalue()).decode("ascii")


DPI = 130


def _sources(log: Log) -> str:
    """The sentences the fixes came from, most first: "GGA, RMC, GSA"."""
    return ", ".join(name for name, _ in log.fix_sentences.most_common())


def draw_track(log: Log, axis: Axis) -> tuple[str, str] | None:
    """The track in metres east and north of its centre (equal aspect), coloured by fix level."""
    if not log.track.added:
        return None
    points = log.track.all()
    lats = [p[1] for p in points]
    lons = [p[2] for p in points]
    if max(lons) - min(lons) > 180:  # across the antimeridian
        lons = [lon + 360 if lon < 0 else lon for lon in lons]
    lat0 = (max(lats) + min(lats)) / 2
    lon0 = (max(lons) + min(lons)) / 2
    metres = math.pi / 180 * 6371008.8
    east = [(lon - lon0) * metres * math.cos(math.radians(lat0)) for lon in lons]
    north = [(lat - lat0) * metres for lat in lats]
    extent = max(max(east) - min(east), max(north) - min(north))
    unit, scale = ("km", 1000.0) if extent > 5000 else ("m", 1.0)
    east = [e / scale for e in east]
    north = [n / scale for n in north]
    figure = _figure(5.6, 5.4)
    ax = figure.add_subplot()
    ax.plot(east, north, color="#b0b0b0", linewidth=0.8, zorder=1)
    levels = [p[3] for p in points]
    for level, colour in LEVELS.items():
        chosen = [i for i, lv in enumerate(levels) if lv == level]
        if chosen:
            ax.scatter(
                [east[i] for i in chosen],
                [north[i] for i in chosen],
                s=7,
                color=colour,
                label=f"{level} ({len(chosen)})",
                zorder=2,
                linewidths=0,
            )
    ends = (
        (slice(None, 1), "^", 110, "#2ca02c", "start"),
        (slice(-1, None), "s", 80, "#d62728", "end"),
    )
    for end, marker, area, colour, label in ends:
        ax.scatter(
            east[end],
            north[end],
            marker=marker,
            s=area,
            color=colour,
            edgecolors="black",
            label=label,
            zorder=3,
        )
    if extent < 2.0:  # one place: a few metres around it
        ax.set_xlim(-1.5, 1.5)
        ax.set_ylim(-1.5, 1.5)
        ax.set_aspect("equal", adjustable="box")
    else:
        ax.set_aspect("equal", adjustable="datalim")
    ax.set_xlabel(f"east [{unit}]")
    ax.set_ylabel(f"north [{unit}]")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8, loc="best", framealpha=0.85)
    ax.set_title(
        f"centre {_degrees(lat0, 'NS')}, {_degrees(lon0 if lon0 <= 180 else lon0 - 360, 'EW')}",
        fontsize=10,
    )
    size = f"{extent / scale:.3g} {unit}"
    caption = (
        f"{log.track.added} fixes with a position"
        + (f" (every {log.track.stride}th drawn)" if log.track.stride > 1 else "")
        + f", merged from {_sources(log)}; the track spans {size}. Start ▲, end ■."
    )
    return _png(figure), caption


def draw_targets(log: Log) -> tuple[str, str] | None:
    """The AIS stations' tracks in kilometres east and north of their centre, the last position of
    each a dot; the stations that sent most are labelled."""
    tracks = {mmsi: t.track.all() for mmsi, t in log.targets.items() if t.track.added}
    if not tracks:
        return None
    lats = [lat for points in tracks.values() for lat, _ in points]
    lons = [lon for points in tracks.values() for _, lon in points]
    wrap = max(lons) - min(lons) > 180  # across the antimeridian
    if wrap:
        lons = [lon + 360 if lon < 0 else lon for lon in lons]
    lat0 = (max(lats) + min(lats)) / 2
    lon0 = (max(lons) + min(lons)) / 2
    km = math.pi / 180 * 6371.0088

    def xy(lat: float, lon: float) -> tuple[float, float]:
        lon = lon + 360 if wrap and lon < 0 else lon
        return (lon - lon0) * km * math.cos(math.radians(lat0)), (lat - lat0) * km

    spread = xy(max(lats), max(lons))[1] - xy(min(lats), min(lons))[1]
    world = spread > 2000 or max(lons) - min(lons) > 20  # too wide for a flat map in km
    figure = _figure(5.6, 5.4)
    ax = figure.add_subplot()
    named = sorted(tracks, key=lambda m: (-log.targets[m].messages, m))[:TARGETS_NAMED]
    for mmsi, points in tracks.items():
        east, north = zip(*((lon, lat) if world else xy(lat, lon) for lat, lon in points))
        ax.plot(east, north, linewidth=0.8, color="#7f9fbf", zorder=1)
        ax.scatter(east[-1:], north[-1:], s=9, color="#1f4e79", zorder=2, linewidths=0)
        if mmsi in named:
            ax.annotate(log.targets[mmsi].name or str(mmsi), (east[-1], north[-1]), fontsize=7,
                        xytext=(3, 3), textcoords="offset points")
    if world:
        ax.set_xlabel("longitude [°]")
        ax.set_ylabel("latitude [°]")
    else:
        ax.set_aspect("equal", adjustable="datalim")
        ax.set_xlabel("east [km]")
        ax.set_ylabel("north [km]")
    ax.grid(alpha=0.3)
    ax.set_title(
        f"centre {_degrees(lat0, 'NS')}, {_degrees(lon0 if lon0 <= 180 else lon0 - 360, 'EW')}",
        fontsize=10,
    )
    caption = (
        f"{len(tracks)} AIS stations with positions ({sum(t.track.added for t in log.targets.values())} "
        f"position reports); the last position of each is a dot, the {len(named)} that sent most "
        "are named."
    )
    return _png(figure), caption


def _target_table(log: Log) -> str:
    """The AIS stations that sent most: MMSI, name, messages, last position."""
    if not log.ais_messages and not log.ais_errors:
        return ""
    rows = []
    ranked = sorted(log.targets.items(), key=lambda kv: (-kv[1].messages, kv[0]))
    for mmsi, target in ranked[:TARGETS_LISTED]:
        points = target.track.all()
        where = (f"{_degrees(points[-1][0], 'NS')}, {_degrees(points[-1][1], 'EW')}"
                 if points else "")
        rows.append(
            f'<tr><td class="n">{mmsi}</td><td>{html.escape(target.name or "")}</td>'
            f'<td class="n">{target.messages:,}</td><td>{html.escape(where)}</td></tr>'
        )
    out = [
        "<table><tr><th>MMSI</th><th>name</th>"
        '<th class="n">messages</th><th>last position</th></tr>',
        *rows,
        "</table>",
    ]
    notes = [f"{log.ais_messages:,} AIS messages from {len(log.targets):,} stations"]
    if len(ranked) > TARGETS_LISTED:
        notes.append(f"the {TARGETS_LISTED} that sent most listed")
    if log.ais_unfollowed:
        notes.append(f"{log.ais_unfollowed:,} messages of further stations only counted")
    if log.ais_errors:
        notes.append("not decoded: " + ", ".join(f"{kind} {n:,}" for kind, n in
                                                 sorted(log.ais_errors.items())))
    out.append(f'<p class="caption">{html.escape("; ".join(notes))}.</p>')
    return "".join(out)


def _degrees(value: float, hemispheres: str) -> str:
    return f"{abs(value):.5f}° {hemispheres[0] if value >= 0 else hemispheres[1]}"


def draw_sky(log: Log) -> tuple[str, str] | None:
    """Azimuth and elevation of every satellite: its trail over the log, a dot where it was last
    (filled when it was tracked, with a C/N0), coloured by system."""
    sats = sorted((sat, t) for sat, t in log.trails.items() if t.last is not None)
    if not sats:
        return None
    figure = _figure(5.6, 5.4)
    ax = typing.cast("PolarAxes", figure.add_subplot(projection="polar"))
    ax.set_theta_zero_location("N")
    ax.set_theta_direction(-1)
    ax.set_rlim(0, 90)
    ax.set_yticks([30, 60, 90], ["60°", "30°", "0°"], fontsize=7, color="#666")
    ax.set_xticks(
        [math.radians(a) for a in range(0, 360, 45)], ["N", "NE", "E", "SE", "S", "SW", "W", "NW"]
    )
    ax.set_rlabel_position(112)
    ax.grid(alpha=0.4)
    systems: Counter[str] = Counter()
    for (system, number), trail in sats:
        colour = SYSTEMS[system][1]
        systems[system] += 1
        points = trail.all()
        for piece in _pieces(points):
            if len(piece) > 1:
                theta = _unwrapped([math.radians(az) for az, _ in piece])
                ax.plot(theta, [90 - el for _, el in piece], color=colour, linewidth=1.2, alpha=0.5)
        theta = [math.radians(az) for az, _ in points]
        radius = [90 - el for _, el in points]
        tracked = log.tracked.get((system, number), False)
        ax.scatter(
            theta[-1:],
            radius[-1:],
            s=60,
            color=colour if tracked else "white",
            edgecolors=colour,
            linewidths=1.5,
            zorder=3,
        )
        ax.annotate(
            satellite_name(system, number),
            (theta[-1], radius[-1]),
            fontsize=7,
            xytext=(5, 4),
            textcoords="offset points",
            color="#222",
        )
    for system, count in sorted(systems.items(), key=lambda kv: list(SYSTEMS).index(kv[0])):
        name, colour = SYSTEMS[system]
        ax.scatter([], [], s=40, color=colour, label=f"{name} ({count})")
    figure.legend(loc="outside lower center", ncols=min(len(systems), 5), fontsize=8, frameon=False)
    caption = (
        f"{len(sats)} satellites in view. Lines: where each was over the log; dots: where it was "
        "last seen, filled when it was tracked then (it had a C/N0)."
    )
    if log.ignored_satellites:
        caption += (
            f" {log.ignored_satellites} entries of satellites past the first {MAX_SATELLITES} "
            "are left out."
        )
    return _png(figure), caption


def _pieces(points: list[tuple[float, float]]) -> list[list[tuple[float, float]]]:
    """A satellite's trail cut where it jumps more than 10 degrees across the sky (a receiver
    that reported a wrong place, or a satellite gone and back): no line is drawn across a jump."""
    pieces: list[list[tuple[float, float]]] = []
    for point in points:
        if pieces and _apart(pieces[-1][-1], point) <= 10:
            pieces[-1].append(point)
        else:
            pieces.append([point])
    return pieces


def _apart(a: tuple[float, float], b: tuple[float, float]) -> float:
    """The angle in degrees between two (azimuth, elevation) directions."""
    (az1, el1), (az2, el2) = [(math.radians(az), math.radians(el)) for az, el in (a, b)]
    cosine = math.sin(el1) * math.sin(el2) + math.cos(el1) * math.cos(el2) * math.cos(az1 - az2)
    return math.degrees(math.acos(max(-1.0, min(1.0, cosine))))


def _unwrapped(theta: list[float]) -> list[float]:
    """Angles made continuous (359 degrees then 1 is 361): a line across north stays short."""
    out = theta[:1]
    for angle in theta[1:]:
        turns = round((out[-1] - angle) / math.tau)
        out.append(angle + turns * math.tau)
    return out


def draw_cn0(log: Log, axis: Axis) -> tuple[str, str] | None:
    """C/N0 of every satellite signal over time: a row each, a column per stretch of time."""
    series: list[tuple[tuple[str, int, str], list[float], list[float]]] = []
    for key, samples in log.cn0.items():
        xs, values = axis.points(samples.all())
        if xs:
            series.append((key, xs, values))
    if not series:
        return None
    hidden = 0
    if len(series) > CN0_ROWS:
        series.sort(key=lambda s: -log.cn0[s[0]].added)
        hidden = len(series) - CN0_ROWS
        series = series[:CN0_ROWS]
    order = list(SYSTEMS)
    series.sort(key=lambda s: (order.index(s[0][0]), s[0][1], s[0][2]))
    signals: Counter[tuple[str, int]] = Counter((k[0], k[1]) for k, _, _ in series)
    labels = [
        satellite_name(k[0], k[1]) + (f" sig {k[2]}" if signals[(k[0], k[1])] > 1 else "")
        for k, _, _ in series
    ]
    every = sorted({x for _, xs, _ in series for x in xs})
    steps = [b - a for a, b in itertools.pairwise(every) if b > a]
    step = statistics.median(steps) if steps else 1.0
    low, high = every[0] - step / 2, every[-1] + step / 2
    columns = max(1, min(COLUMNS, round((high - low) / step)))
    width = (high - low) / columns
    grid: list[list[float]] = []
    for _, xs, values in series:
        sums = [0.0] * columns
        counts = [0] * columns
        for x, value in zip(xs, values):
            column = min(columns - 1, max(0, int((x - low) / width)))
            sums[column] += value
            counts[column] += 1
        grid.append([s / c if c else math.nan for s, c in zip(sums, counts)])
    edges = [low + i * width for i in range(columns + 1)]
    rows = len(series)
    figure = _figure(11.0, 1.4 + 0.16 * max(rows, 6))
    ax = figure.add_subplot()
    mesh = ax.pcolormesh(edges, list(range(rows + 1)), grid, cmap="viridis", vmin=15, vmax=55)
    figure.colorbar(mesh, ax=ax, label="C/N0 [dB-Hz]", pad=0.01, aspect=30)
    ax.set_yticks([i + 0.5 for i in range(rows)], labels, fontsize=7 if rows > 30 else 8)
    for tick, (key, _, _) in zip(ax.get_yticklabels(), series):
        tick.set_color(SYSTEMS[key[0]][1])
    ax.set_ylim(rows, 0)
    ax.set_facecolor("#f4f4f4")
    axis.style(ax, low, high)
    caption = (
        f"{rows} satellite signals with a C/N0, coloured by dB-Hz (blank: not tracked)"
        + (f"; {hidden} more with fewer samples are left out" if hidden else "")
        + ". Labels are coloured by system."
    )
    return _png(figure), caption


def draw_quality(log: Log, axis: Axis) -> tuple[str, str] | None:
    """Fix level, satellites used and in view, and DOPs over time, one above the other: the
    charts that have something to show."""
    quality_x, quality = axis.points(log.quality.all())
    used = axis.points(log.used.all())
    view = axis.points(log.in_view.all())
    dops = {name: axis.points(series.all()) for name, series in log.dops.items()}
    dops = {name: xy for name, xy in dops.items() if xy[0]}
    present = [lv for lv in LEVELS if lv in set(quality)]
    charts = [
        (name, height)
        for name, height, shown in (
            ("fix", 0.5 + 0.28 * len(present), bool(quality_x)),
            ("satellites", 1.9, bool(used[0] or view[0])),
            ("dop", 1.9, bool(dops)),
        )
        if shown
    ]
    if not charts:
        return None
    figure = _figure(11.0, 0.9 + sum(h for _, h in charts))
    axes = figure.subplots(
        len(charts), 1, sharex=True, height_ratios=[h for _, h in charts], squeeze=False
    )[:, 0]
    every: list[float] = []
    missing = []
    for (name, _), ax in zip(charts, axes):
        if name == "fix":
            ys = [present.index(lv) for lv in quality]
            ax.step(quality_x, ys, where="post", color="#c8c8c8", linewidth=1, zorder=1)
            ax.scatter(
                quality_x, ys, c=[LEVELS[lv] for lv in quality], s=10, zorder=2, linewidths=0
            )
            ax.set_yticks(range(len(present)), present, fontsize=8)
            ax.set_ylim(-0.6, len(present) - 0.4)
            ax.set_title("fix", fontsize=9, loc="left")
            every += quality_x
        elif name == "satellites":
            peak = 1.0
            for (xs, values), label, colour in (
                (view, "in view", "#9e9e9e"),
                (used, "used", "#1f77b4"),
            ):
                if xs:
                    ax.step(
                        xs,
                        values,
                        where="post",
                        color=colour,
                        label=label,
                        linewidth=1.3,
                        marker="o" if len(xs) <= 60 else None,
                        markersize=3,
                    )
                    peak = max(peak, *values)
                    every += xs
            ax.set_ylim(0, peak * 1.15)
            ax.set_title("satellites", fontsize=9, loc="left")
        else:
            colours = {"HDOP": "#1f77b4", "PDOP": "#ff7f0e", "VDOP": "#2ca02c"}
            peak = 0.0
            for label, (xs, values) in dops.items():
                ax.plot(
                    xs,
                    values,
                    color=colours[label],
                    linewidth=1.2,
                    label=label,
                    marker="o" if len(xs) <= 60 else None,
                    markersize=3,
                )
                peak = max(peak, *values)
                every += xs
            ax.set_ylim(0, min(max(peak * 1.1, 2.0), 20.0))
            clipped = " (above 20 not drawn)" if peak > 20 else ""
            ax.set_title(f"dilution of precision{clipped}", fontsize=9, loc="left")
        if name != "fix":
            ax.legend(fontsize=8, loc="upper left", bbox_to_anchor=(1.005, 1.0), frameon=False)
        ax.grid(alpha=0.3)
    for name, text in (
        ("fix", "fix quality"),
        ("satellites", "satellite counts"),
        ("dop", "DOPs"),
    ):
        if name not in {n for n, _ in charts}:
            missing.append(text)
    low, high = min(every), max(every)
    span = (high - low) * 0.01 or 0.5
    axes[-1].set_xlim(low - span, high + span)
    axis.style(axes[-1], low, high)
    caption = f"Fix level, satellites used and in view, and DOPs over time, epoch by epoch ({_sources(log)})."
    if missing:
        caption += f" Not in this log: {'; '.join(missing)}."
    if axis.dropped:
        caption += f" {axis.dropped} samples before the first UTC time are left out."
    return _png(figure), caption


# --------------------------------------------------------------------------------------------
# the page

STYLE = """
body { font: 15px/1.45 system-ui, -apple-system, "Segoe UI", Roboto, sans-serif; color: #1d232a;
  background: #eef1f4; margin: 0; }
main { max-width: 1180px; margin: 0 auto; padding: 18px 20px 40px; }
h1 { font-size: 24px; margin: 6px 0 2px; word-break: break-all; }
h2 { font-size: 18px; margin: 0 0 10px; }
nav a { margin-right: 14px; color: #1f5fa8; text-decoration: none; font-size: 14px; }
section { background: #fff; border-radius: 8px; padding: 16px 18px; margin: 16px 0;
  box-shadow: 0 1px 3px rgba(0,0,0,.08); }
.pair { display: grid; grid-template-columns: repeat(auto-fit, minmax(430px, 1fr)); gap: 16px; }
.pair section { margin: 0; }
img { max-width: 100%; height: auto; display: block; margin: 0 auto; }
.caption, .empty { color: #56606b; font-size: 13px; margin: 8px 0 0; }
.empty { font-size: 15px; padding: 30px 0; text-align: center; }
.tiles { display: grid; grid-template-columns: repeat(auto-fit, minmax(150px, 1fr)); gap: 10px; }
.tile { background: #f6f8fa; border-radius: 6px; padding: 8px 12px; }
.tile b { display: block; font-size: 19px; }
.tile span { color: #56606b; font-size: 12px; }
table { border-collapse: collapse; width: 100%; font-size: 14px; margin-bottom: 12px; }
th, td {
  text-align: left; padding: 4px 10px; border-bottom: 1px solid #e4e7eb; vertical-align: top;
}
th { background: #f6f8fa; font-weight: 600; }
td.n { text-align: right; font-variant-numeric: tabular-nums; }
code { font-size: 12.5px; word-break: break-all; }
.bad { color: #b42318; }
"""


def _tile(value: str, label: str, css: str = "") -> str:
    return (
        f'<div class="tile"><b{css}>{html.escape(value)}</b><span>{html.escape(label)}</span></div>'
    )


def _section(anchor: str, title: str, picture: tuple[str, str] | None, empty: str, alt: str) -> str:
    if picture is None:
        body = f'<p class="empty">{html.escape(empty)}</p>'
    else:
        uri, caption = picture
        body = (
            f'<img src="{uri}" alt="{html.escape(alt)}">'
            f'<p class="caption">{html.escape(caption)}</p>'
        )
    return f'<section id="{anchor}"><h2>{html.escape(title)}</h2>{body}</section>'


def _summary(log: Log, name: str) -> str:
    errors = sum(log.errors.values())
    unknown = sum(
        n for (key, talker), n in log.counts.items() if log.names.get(key) == "not in the spec"
    )
    share = log.decoded / log.lines if log.lines else 0.0
    tiles = [
        _tile(f"{log.lines:,}", "lines"),
        _tile(f"{log.decoded:,}", f"sentences ({share:.1%} of the lines)"),
        _tile(f"{errors:,}", "decode errors", ' class="bad"' if errors else ""),
        _tile(f"{unknown:,}", "sentences not in the spec"),
    ]
    if log.clock.now is not None:
        low, high = log.clock.low, log.clock.high
        tiles.append(_tile(f"{clock_text(low)} – {clock_text(high)}", "UTC"))
        tiles.append(_tile(_duration(high - low), "duration"))
    if log.dates:
        tiles.append(_tile(" – ".join(dict.fromkeys(log.dates)), "date"))
    tiles.append(_tile(f"{log.track.added:,}", "fixes with a position"))
    systems = Counter(system for system, _ in log.trails)
    if systems:
        seen = ", ".join(
            f"{SYSTEMS[s][0]} {n}"
            for s, n in sorted(systems.items(), key=lambda kv: list(SYSTEMS).index(kv[0]))
        )
        tiles.append(_tile(str(len(log.trails)), f"satellites seen: {seen}"))
    return '<section id="summary"><div class="tiles">' + "".join(tiles) + "</div></section>"


def _duration(seconds: float) -> str:
    seconds = round(seconds)
    hours, rest = divmod(seconds, 3600)
    minutes, secs = divmod(rest, 60)
    return f"{hours} h {minutes:02d} min" if hours else f"{minutes} min {secs:02d} s"


def _tables(log: Log) -> str:
    total = sum(log.counts.values()) or 1
    rows = []
    for (name, talker), count in sorted(log.counts.items(), key=lambda kv: (-kv[1], kv[0])):
        rows.append(
            f"<tr><td>{html.escape(name)}</td><td>{html.escape(talker)}</td>"
            f"<td>{html.escape(log.names.get(name, ''))}</td>"
            f'<td class="n">{count:,}</td><td class="n">{count / total:.1%}</td></tr>'
        )
    out = [
        '<section id="sentences"><h2>Sentences</h2>',
        "<table><tr><th>sentence</th><th>talker</th><th>what it is</th>"
        + '<th class="n">count</th><th class="n">share</th></tr>',
        *rows,
        "</table>",
    ]
    if log.errors:
        out.append('<h2>Decode errors</h2><table><tr><th>kind</th><th class="n">lines</th></tr>')
        for kind, count in sorted(log.errors.items(), key=lambda kv: (-kv[1], kv[0])):
            out.append(f'<tr><td>{html.escape(kind)}</td><td class="n">{count:,}</td></tr>')
        out.append("</table>")
        out.append(
            "<table><tr><th>line</th><th>kind</th>"
            f"<th>first {len(log.first_errors)} errors</th></tr>"
        )
        for number, kind, message, text in log.first_errors:
            out.append(
                f'<tr><td class="n">{number}</td><td>{html.escape(kind)}</td>'
                f"<td>{html.escape(message)}<br><code>{html.escape(text)}</code></td></tr>"
            )
        out.append("</table>")
    else:
        out.append('<p class="caption">No decode errors.</p>')
    out.append("</section>")
    return "".join(out)


def page(log: Log, name: str) -> str:
    """The whole report as one HTML page."""
    axis = Axis(log)
    track = draw_track(log, axis)
    sky = draw_sky(log)
    cn0 = draw_cn0(log, axis)
    quality = draw_quality(log, axis)
    targets = _target_table(log)  # only for a log with AIS messages
    title = f"nmea report: {name}"
    nav = "".join(
        f'<a href="#{anchor}">{text}</a>'
        for anchor, text in (
            ("track", "Track"),
            ("sky", "Sky"),
            ("cn0", "C/N0"),
            ("quality", "Fix and DOP"),
            *((("ais", "AIS targets"),) if targets else ()),
            ("sentences", "Sentences and errors"),
        )
    )
    ais = ""
    if targets:
        ais = _section(
            "ais",
            "AIS targets",
            draw_targets(log),
            "No positions in the AIS messages of this log.",
            "the tracks of the AIS stations",
        ).replace("</section>", targets + "</section>")
    return "".join(
        [
            '<!DOCTYPE html>\n<html lang="en"><head><meta charset="utf-8">',
            '<meta name="viewport" content="width=device-width, initial-scale=1">',
            f"<title>{html.escape(title)}</title><style>{STYLE}</style></head><body><main>",
            f"<h1>{html.escape(name)}</h1><nav>{nav}</nav>",
            _summary(log, name),
            '<div class="pair">',
            _section(
                "track",
                "Track",
                track,
                "No position fixes in this log (no epoch with a valid position).",
                "the track of the fixes",
            ),
            _section(
                "sky",
                "Sky plot",
                sky,
                "No satellite positions in this log (no satellites in view with elevation and azimuth).",
                "sky plot of the satellites",
            ),
            "</div>",
            _section(
                "cn0",
                "C/N0 per satellite",
                cn0,
                "No signal strengths in this log (no satellites in view with a C/N0).",
                "C/N0 of each satellite over time",
            ),
            _section(
                "quality",
                "Fix quality, satellites and DOP",
                quality,
                "No fix quality, "
                "satellite counts or DOPs in this log (no sentence that carries them).",
                "fix quality, satellites and DOP over time",
            ),
            ais,
            _tables(log),
            "</main></body></html>\n",
        ]
    )


# --------------------------------------------------------------------------------------------
# the verb


def _check_matplotlib() -> None:
    try:
        import matplotlib  # type: ignore[import-not-found, unused-ignore]  # noqa: F401
    except ImportError:
        raise CliError(INSTALL_HINT) from None


def report(args: argparse.Namespace) -> int:
    _check_matplotlib()  # before reading a long log for nothing
    source, size = open_log(args.log)
    name = "stdin" if args.log == "-" else os.path.basename(args.log)
    output = args.output or (
        "report.html" if args.log == "-" else os.path.splitext(name)[0] + ".html"
    )
    progress = progress_for(args.progress, size)
    log = Log()
    try:
        log.read(lines(_chunks(source, progress)))
    finally:
        if source is not sys.stdin.buffer:
            source.close()
    if progress is not None:
        progress.finish()
    if log.lines == 0:
        raise CliError(f"{args.log} is empty")
    if log.decoded == 0:
        kind = log.errors.most_common(1)[0][0]
        raise CliError(
            f"{args.log} is not an NMEA log: none of its {log.lines} lines decodes ({kind})"
        )
    text = page(log, name)
    try:
        if output == "-":
            sys.stdout.write(text)
            sys.stdout.flush()
        else:
            with open(output, "w", encoding="utf-8") as out:
                out.write(text)
    except OSError as err:
        raise CliError(f"cannot write {output}: {err.strerror}") from None
    if not args.quiet:
        errors = sum(log.errors.values())
        sys.stderr.write(
            f"wrote {output}: {log.lines} lines, {log.decoded} sentences, {errors} errors\n"
        )
    return 0


def add_parser(verbs: Any) -> None:
    """The `report` verb of `nmea` (nmea_cli.py)."""
    r = verbs.add_parser(
        "report",
        help="draw a log as one HTML page: track, sky plot, C/N0, fix quality, errors",
        formatter_class=argparse.RawDescriptionHelpFormatter,
        epilog=REPORT_EXAMPLES,
    )
    r.add_argument("log", help="the log file, or - for stdin")
    r.add_argument(
        "-o",
        "--output",
        metavar="HTML",
        help="the page to write (default: the log's name with .html, here; - for stdout)",
    )
    add_progress_options(r)
    r.add_argument("-q", "--quiet", action="store_true", help="no summary line on stderr")
    r.set_defaults(run=report)
