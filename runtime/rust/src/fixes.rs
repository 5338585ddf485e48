//! Fixes assembled across sentences: one [`Fix`] per epoch (the sentences of one UTC time of
//! day), by the rules of docs/fixes.md, as the Python package's `nmeaspec.fixes` makes them.
//!
//! Which field of which sentence carries which fact is the spec's (spec/fix.yaml and the `fix:`
//! keys of the sentences' fields): the generated `Sentence` reads them into [`Facts`]
//! ([`FixSource`]) and [`Systems`] holds the GNSS of talkers and satellite ids; this module only
//! merges facts:
//!
//! - An epoch is the run of sentences with the same time of day. A sentence without time joins
//!   the epoch under way; a sentence with another time closes it, as does the end of the stream
//!   ([`FixAssembler::finish`]). While the epoch has no time (a receiver without a fix), a
//!   sentence whose layout has a time field closes it when the epoch holds one from the same
//!   talker already.
//! - A fix holds only what the sentences of its epoch say, except the date: an epoch without one
//!   takes the last date seen, a day later when the time of day went back past midnight.
//! - Satellites in view come in sets (one per talker and signal); a set belongs to the epoch in
//!   which its last sentence arrives, a set missing a part is dropped. Satellites used are kept
//!   per GNSS: the system id of NMEA 4.10, else the talker, else the range of the satellite id.
//! - The mode is the receiver's where the epoch has it, else inferred: no fix when a sentence
//!   calls the position invalid, 3D with an altitude, 2D without.
//!
//! The fixes hold growing lists (satellites, sentences): this module needs `std`.

use core::fmt::{self, Write};
use std::string::String;
use std::vec::Vec;

use super::layout::Layout;
use super::parse::{parse_with, Layouts, Options};
use super::types::{Code, CodeChars, CodeEnum, Coordinate, Date, Number, Time};
use super::values::{days_from_civil, DateTime};
use super::write::write_json_str;

/// A date of the proleptic Gregorian calendar that exists (years 1 to 9999), with its year in
/// full: a fix's date may come from four digits (ZDA) or roll over past a two-digit one.
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct CalendarDate {
    /// The four-digit year.
    pub year: u16,
    /// 1 to 12.
    pub month: u8,
    /// 1 to the month's last day.
    pub day: u8,
}

impl CalendarDate {
    /// The date, when it exists.
    pub fn new(year: i64, month: i64, day: i64) -> Option<Self> {
        let (year, month, day) = (i32::try_from(year).ok()?, u8::try_from(month).ok()?, u8::try_from(day).ok()?);
        days_from_civil(year, month, day)?;
        Some(Self { year: u16::try_from(year).ok()?, month, day })
    }

    /// A `ddmmyy` date, its year by [`PIVOT_YEAR`](super::PIVOT_YEAR).
    pub fn of_date(date: Date) -> Option<Self> {
        Self::new(date.full_year().into(), date.month.into(), date.day.into())
    }

    /// The day after.
    pub fn next_day(self) -> Option<Self> {
        let (year, month, day) = (i64::from(self.year), i64::from(self.month), i64::from(self.day));
        Self::new(year, month, day + 1).or_else(|| Self::new(year, month + 1, 1)).or_else(|| Self::new(year + 1, 1, 1))
    }

    /// Days since 1970-01-01.
    pub fn days_since_epoch(self) -> i32 {
        days_from_civil(self.year.into(), self.month, self.day).unwrap_or_default()
    }
}

impl fmt::Display for CalendarDate {
    /// ISO 8601: `1994-03-23`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{:04}-{:02}-{:02}", self.year, self.month, self.day)
    }
}

/// A satellite in view, as one signal's set of sentences (GSV, PUBX,03) reports it.
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
#[derive(Clone, Debug, PartialEq)]
pub struct Satellite {
    /// Its GNSS (gps, sbas, glonass, galileo, beidou, qzss, navic), `None` when not told.
    pub system: Option<&'static str>,
    /// Its id in the NMEA numbering of its talker.
    pub id: i64,
    /// The talker of its set.
    pub talker: String,
    /// The signal id (NMEA 4.10) of its set, e.g. `signal_1`; `None` before NMEA 4.10.
    pub signal: Option<&'static str>,
    /// Elevation \[deg\].
    pub elevation: Option<i64>,
    /// Azimuth \[deg\].
    pub azimuth: Option<i64>,
    /// Carrier-to-noise density \[dB-Hz\]; `None` when not tracked.
    pub snr: Option<i64>,
    /// Whether the solution uses it, where the receiver says so beside it (PUBX,03).
    pub used: Option<bool>,
}

/// What the sentences of one epoch say. Every fact is `None` when no sentence of the epoch gave
/// it; units are those of spec/fix.yaml (degrees, metres, metres per second); enum facts are
/// value ids (`"fix_3d"`).
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Fix {
    /// UTC time of day (a leap second is no time).
    pub time: Option<Time>,
    /// UTC date.
    pub date: Option<CalendarDate>,
    /// Latitude, signed decimal degrees.
    pub latitude: Option<f64>,
    /// Longitude, signed decimal degrees.
    pub longitude: Option<f64>,
    /// Altitude above mean sea level \[m\].
    pub altitude_msl: Option<f64>,
    /// Height of the geoid above the ellipsoid \[m\].
    pub geoid_separation: Option<f64>,
    /// Height above the ellipsoid \[m\]: as sent (PUBX,00), else MSL altitude plus geoid
    /// separation.
    pub altitude_hae: Option<f64>,
    /// Speed over ground \[m/s\].
    pub speed: Option<f64>,
    /// Course over ground \[deg\] from true north.
    pub course: Option<f64>,
    /// GGA's quality as a value id of gga_quality (autonomous, differential, rtk_fixed, ...).
    pub fix_quality: Option<&'static str>,
    /// valid or invalid (RMC, GLL).
    pub fix_status: Option<&'static str>,
    /// The NMEA 2.3 mode indicator as a value id (autonomous, differential, not_valid, ...).
    pub pos_mode: Option<&'static str>,
    /// no_fix, fix_2d or fix_3d: the receiver's (GSA, PUBX,00), else inferred (module doc).
    pub mode: Option<&'static str>,
    /// Position dilution of precision.
    pub pdop: Option<f64>,
    /// Horizontal dilution of precision.
    pub hdop: Option<f64>,
    /// Vertical dilution of precision.
    pub vdop: Option<f64>,
    /// Time dilution of precision.
    pub tdop: Option<f64>,
    /// Latitude error \[m\].
    pub lat_error: Option<f64>,
    /// Longitude error \[m\].
    pub lon_error: Option<f64>,
    /// Altitude error \[m\].
    pub alt_error: Option<f64>,
    /// Horizontal error \[m\].
    pub horizontal_error: Option<f64>,
    /// The receiver's count of satellites used (GGA, GNS, PUBX,00): the combined talker's (GN),
    /// else a proprietary sentence's (the receiver's total: PUBX,00 beside GPGGA), else the sum of
    /// each talker's (one GGA per system).
    pub satellites_used: Option<i64>,
    /// The ids of the satellites used, per GNSS (`"unknown"` when no rule tells it), in the
    /// order they came.
    pub used: Vec<(&'static str, Vec<i64>)>,
    /// The satellites in view, one entry per satellite and signal.
    pub in_view: Vec<Satellite>,
    /// The sentences the fix came from, in order: talker and formatter (`GNGGA`) or the id of a
    /// proprietary sentence (`PUBX_POSITION`).
    pub sentences: Vec<String>,
}

impl Fix {
    /// The epoch's UTC date and time, when both are known.
    pub fn datetime(&self) -> Option<DateTime> {
        let date = self.date?;
        DateTime::new(date.year.into(), date.month, date.day, self.time?)
    }

    /// How many satellites the GSA sentences of the epoch list as used.
    pub fn used_count(&self) -> usize {
        self.used.iter().map(|(_, ids)| ids.len()).sum()
    }

    /// How many distinct satellites are in view (a satellite of several signals once).
    pub fn in_view_count(&self) -> usize {
        let mut seen: Vec<(Option<&str>, i64)> = self.in_view.iter().map(|s| (s.system, s.id)).collect();
        seen.sort_unstable();
        seen.dedup();
        seen.len()
    }

    /// Writes the fix as one JSON object: the members of Python's `Fix.to_dict()` in its order,
    /// date and time in ISO 8601, numbers as Python's `json` writes them.
    pub fn write_json<W: Write + ?Sized>(&self, w: &mut W) -> fmt::Result {
        w.write_str("{\"time\":")?;
        match self.time {
            Some(time) => write_iso_time(w, time)?,
            None => w.write_str("null")?,
        }
        w.write_str(",\"date\":")?;
        match self.date {
            Some(date) => write!(w, "\"{date}\"")?,
            None => w.write_str("null")?,
        }
        let reals = [
            ("latitude", self.latitude),
            ("longitude", self.longitude),
            ("altitude_msl", self.altitude_msl),
            ("geoid_separation", self.geoid_separation),
            ("altitude_hae", self.altitude_hae),
            ("speed", self.speed),
            ("course", self.course),
        ];
        for (name, value) in reals {
            write!(w, ",\"{name}\":")?;
            write_real(w, value)?;
        }
        for (name, value) in [
            ("fix_quality", self.fix_quality),
            ("fix_status", self.fix_status),
            ("pos_mode", self.pos_mode),
            ("mode", self.mode),
        ] {
            write!(w, ",\"{name}\":")?;
            write_text(w, value)?;
        }
        let reals = [
            ("pdop", self.pdop),
            ("hdop", self.hdop),
            ("vdop", self.vdop),
            ("tdop", self.tdop),
            ("lat_error", self.lat_error),
            ("lon_error", self.lon_error),
            ("alt_error", self.alt_error),
            ("horizontal_error", self.horizontal_error),
        ];
        for (name, value) in reals {
            write!(w, ",\"{name}\":")?;
            write_real(w, value)?;
        }
        w.write_str(",\"satellites_used\":")?;
        write_whole(w, self.satellites_used)?;
        w.write_str(",\"used\":{")?;
        for (i, (system, ids)) in self.used.iter().enumerate() {
            if i > 0 {
                w.write_char(',')?;
            }
            write_json_str(w, system)?;
            w.write_str(":[")?;
            for (j, id) in ids.iter().enumerate() {
                write!(w, "{}{id}", if j > 0 { "," } else { "" })?;
            }
            w.write_char(']')?;
        }
        w.write_str("},\"in_view\":[")?;
        for (i, s) in self.in_view.iter().enumerate() {
            w.write_str(if i > 0 { ",{\"system\":" } else { "{\"system\":" })?;
            write_text(w, s.system)?;
            write!(w, ",\"id\":{},\"talker\":", s.id)?;
            write_json_str(w, &s.talker)?;
            w.write_str(",\"signal\":")?;
            write_text(w, s.signal)?;
            for (name, value) in [("elevation", s.elevation), ("azimuth", s.azimuth), ("snr", s.snr)] {
                write!(w, ",\"{name}\":")?;
                write_whole(w, value)?;
            }
            w.write_str(match s.used {
                Some(true) => ",\"used\":true}",
                Some(false) => ",\"used\":false}",
                None => ",\"used\":null}",
            })?;
        }
        w.write_str("],\"sentences\":[")?;
        for (i, sentence) in self.sentences.iter().enumerate() {
            if i > 0 {
                w.write_char(',')?;
            }
            write_json_str(w, sentence)?;
        }
        w.write_str("]}")
    }

    /// The facts of one sentence, the later sentence of an epoch winning.
    fn merge(&mut self, facts: &Facts<'_>) {
        let reals = [
            (&mut self.latitude, facts.latitude),
            (&mut self.longitude, facts.longitude),
            (&mut self.altitude_msl, facts.altitude_msl),
            (&mut self.geoid_separation, facts.geoid_separation),
            (&mut self.altitude_hae, facts.altitude_hae),
            (&mut self.speed, facts.speed),
            (&mut self.course, facts.course),
            (&mut self.pdop, facts.pdop),
            (&mut self.hdop, facts.hdop),
            (&mut self.vdop, facts.vdop),
            (&mut self.tdop, facts.tdop),
            (&mut self.lat_error, facts.lat_error),
            (&mut self.lon_error, facts.lon_error),
            (&mut self.alt_error, facts.alt_error),
            (&mut self.horizontal_error, facts.horizontal_error),
        ];
        for (fact, value) in reals {
            if value.is_some() {
                *fact = value;
            }
        }
        let ids = [
            (&mut self.fix_quality, facts.fix_quality),
            (&mut self.fix_status, facts.fix_status),
            (&mut self.pos_mode, facts.pos_mode),
            (&mut self.mode, facts.mode),
        ];
        for (fact, value) in ids {
            if value.is_some() {
                *fact = value;
            }
        }
    }

    /// The mode where no sentence of the epoch gives it (module doc).
    fn inferred_mode(&self) -> Option<&'static str> {
        if self.latitude.is_none() && self.fix_quality.is_none() && self.fix_status.is_none() {
            return None;
        }
        let invalid = self.fix_status == Some("invalid")
            || self.fix_quality == Some("invalid")
            || self.pos_mode == Some("not_valid")
            || self.latitude.is_none();
        Some(if invalid {
            "no_fix"
        } else if self.altitude_msl.is_some() || self.altitude_hae.is_some() {
            "fix_3d"
        } else {
            "fix_2d"
        })
    }
}

/// A time as Python's `time.isoformat()` writes it: `hh:mm:ss`, then `.ffffff` when the
/// microseconds (digits after the sixth dropped) are not zero.
fn write_iso_time<W: Write + ?Sized>(w: &mut W, time: Time) -> fmt::Result {
    write!(w, "\"{:02}:{:02}:{:02}", time.hour, time.minute, time.second)?;
    match micros(time) % 1_000_000 {
        0 => w.write_char('"'),
        micros => write!(w, ".{micros:06}\""),
    }
}

/// A double as Python's `repr` (and `json`) writes it ([`write_repr`](super::repr::write_repr)).
fn write_real<W: Write + ?Sized>(w: &mut W, value: Option<f64>) -> fmt::Result {
    match value {
        Some(value) => super::repr::write_repr(w, value),
        None => w.write_str("null"),
    }
}

fn write_whole<W: Write + ?Sized>(w: &mut W, value: Option<i64>) -> fmt::Result {
    match value {
        Some(value) => write!(w, "{value}"),
        None => w.write_str("null"),
    }
}

fn write_text<W: Write + ?Sized>(w: &mut W, value: Option<&str>) -> fmt::Result {
    match value {
        Some(text) => write_json_str(w, text),
        None => w.write_str("null"),
    }
}

/// The microseconds of a time of day, digits after the sixth decimal dropped: what tells two
/// epochs apart (Python's `datetime.time`).
fn micros(time: Time) -> u64 {
    let fraction = u64::from(time.fraction) * 1_000_000;
    let seconds = (u64::from(time.hour) * 60 + u64::from(time.minute)) * 60 + u64::from(time.second);
    seconds * 1_000_000 + fraction / 10u64.pow(u32::from(time.fraction_digits))
}

/// What one sentence says about its epoch, each fact converted to the fix's unit and type: what
/// the generated table ([`FixSource`]) reads from the fields spec/fix.yaml's `fix:` keys name.
#[derive(Clone, Debug, Default, PartialEq)]
#[allow(missing_docs)] // the facts of spec/fix.yaml, under their ids
pub struct Facts<'a> {
    /// The sentence's talker (empty for a proprietary one).
    pub talker: &'a str,
    /// The spec's id of the sentence (`GGA`, `PUBX_POSITION`).
    pub sentence: &'static str,
    /// Every fact the sentence's layout carries, whether or not this sentence gives it.
    pub carried: &'static [&'static str],
    pub time: Option<Time>,
    pub date: Option<CalendarDate>,
    pub day: Option<i64>,
    pub month: Option<i64>,
    pub year: Option<i64>,
    pub latitude: Option<f64>,
    pub longitude: Option<f64>,
    pub altitude_msl: Option<f64>,
    pub geoid_separation: Option<f64>,
    pub altitude_hae: Option<f64>,
    pub speed: Option<f64>,
    pub course: Option<f64>,
    pub fix_quality: Option<&'static str>,
    pub fix_status: Option<&'static str>,
    pub pos_mode: Option<&'static str>,
    pub mode: Option<&'static str>,
    pub pdop: Option<f64>,
    pub hdop: Option<f64>,
    pub vdop: Option<f64>,
    pub tdop: Option<f64>,
    pub lat_error: Option<f64>,
    pub lon_error: Option<f64>,
    pub alt_error: Option<f64>,
    pub horizontal_error: Option<f64>,
    pub satellites_used: Option<i64>,
    pub used_system: Option<&'static str>,
    pub in_view_total: Option<i64>,
    pub set_size: Option<i64>,
    pub set_index: Option<i64>,
    pub signal: Option<&'static str>,
    /// The entries of the layout's repeated group, one per satellite.
    pub entries: Vec<EntryFacts>,
}

impl<'a> Facts<'a> {
    /// No facts yet, of a sentence whose layout carries `carried`.
    pub fn of<L: Layout<'a>>(sentence: &L, carried: &'static [&'static str]) -> Self {
        Self { talker: sentence.talker(), sentence: L::SENTENCE, carried, ..Self::default() }
    }

    fn carries(&self, fact: &str) -> bool {
        self.carried.contains(&fact)
    }
}

/// The facts of one entry of a repeated group: one satellite.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[allow(missing_docs)] // the satellite facts of spec/fix.yaml, under their ids
pub struct EntryFacts {
    pub used_satellite: Option<i64>,
    pub satellite: Option<i64>,
    pub elevation: Option<i64>,
    pub azimuth: Option<i64>,
    pub snr: Option<i64>,
    pub satellite_used: Option<&'static str>,
}

/// A decoded sentence read as the facts of a fix (the generated `Sentence` implements it from
/// the spec's `fix:` keys).
pub trait FixSource {
    /// The facts the sentence gives; `None` for a sentence whose layout carries none.
    fn facts(&self) -> Option<Facts<'_>>;
}

/// The GNSS of talkers and of satellite ids (spec/fix.yaml).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Systems {
    /// The GNSS each talker of one system reports on.
    pub talkers: &'static [(&'static str, &'static str)],
    /// Under the other talkers (GP, GN): the GNSS of each range of satellite ids.
    pub satellite_ids: &'static [(&'static str, i64, i64)],
    /// The talker of a solution of several systems, whose count of satellites used is the fix's.
    pub combined_talker: Option<&'static str>,
}

impl Systems {
    /// The GNSS of a satellite id under a talker.
    fn of(&self, talker: &str, satellite: i64) -> Option<&'static str> {
        let by_talker = self.talkers.iter().find(|(t, _)| *t == talker).map(|&(_, system)| system);
        by_talker.or_else(|| {
            self.satellite_ids.iter().find(|(_, low, high)| (*low..=*high).contains(&satellite)).map(|&(s, _, _)| s)
        })
    }
}

/// A set of satellites in view under way: its talker and signal, the last part that came, the
/// satellites so far.
#[derive(Clone, Debug)]
struct Set {
    talker: String,
    signal: Option<&'static str>,
    index: i64,
    satellites: Vec<Satellite>,
}

/// Turns a stream of sentences into fixes: [`FixAssembler::feed`] each decoded sentence in
/// order, it gives the fix of the epoch the sentence closed, if any; [`FixAssembler::finish`]
/// ends the stream.
#[derive(Clone, Debug)]
pub struct FixAssembler {
    systems: &'static Systems,
    fix: Option<Fix>,
    sets: Vec<Set>,
    last_date: Option<(CalendarDate, Option<Time>)>,
    /// Satellites used, by talker, in the epoch under way.
    counts: Vec<(String, i64)>,
}

impl FixAssembler {
    /// An assembler of the spec's systems.
    pub const fn with_systems(systems: &'static Systems) -> Self {
        Self { systems, fix: None, sets: Vec::new(), last_date: None, counts: Vec::new() }
    }

    /// Adds one sentence; a sentence that carries no fact is skipped.
    pub fn feed<S: FixSource + ?Sized>(&mut self, sentence: &S) -> Option<Fix> {
        let mut facts = sentence.facts()?;
        let time = facts.time.take();
        let source = [facts.talker, facts.sentence].concat();
        let closed = match (&self.fix, time) {
            (Some(Fix { time: Some(a), .. }), Some(b)) if micros(*a) != micros(b) => self.close(),
            // No time of day yet: a sentence with a time field comes once an epoch.
            (Some(fix), None)
                if fix.time.is_none() && facts.carried.contains(&"time") && fix.sentences.contains(&source) =>
            {
                self.close()
            }
            _ => None,
        };
        let mut fix = self.fix.take().unwrap_or_default();
        if time.is_some() {
            fix.time = time;
        }
        fix.sentences.push(source);
        self.merge(&mut fix, &facts);
        self.fix = Some(fix);
        closed
    }

    /// Parses a line with the layouts `L` and adds it ([`FixAssembler::feed`]), behind its TAG
    /// blocks if any; a line that does not parse is skipped.
    pub fn feed_line_of<L: Layouts>(&mut self, line: &[u8]) -> Option<Fix>
    where
        for<'a> L::Sentence<'a>: FixSource,
    {
        parse_with::<L>(line, Options::default()).ok().and_then(|parsed| self.feed(&parsed.sentence))
    }

    /// The fix of the epoch under way, at the end of the stream.
    pub fn finish(&mut self) -> Option<Fix> {
        self.close()
    }

    fn merge(&mut self, fix: &mut Fix, facts: &Facts<'_>) {
        fix.merge(facts);
        if let Some(count) = facts.satellites_used {
            match self.counts.iter_mut().find(|(talker, _)| talker == facts.talker) {
                Some((_, known)) => *known = count,
                None => self.counts.push((facts.talker.into(), count)),
            }
        }
        let calendar = || CalendarDate::new(facts.year?, facts.month?, facts.day?);
        if let Some(date) = facts.date.or_else(calendar) {
            fix.date = Some(date);
        }
        if facts.carries("used_satellite") {
            for satellite in facts.entries.iter().filter_map(|e| e.used_satellite) {
                let system =
                    facts.used_system.or_else(|| self.systems.of(facts.talker, satellite)).unwrap_or("unknown");
                let at = match fix.used.iter().position(|(s, _)| *s == system) {
                    Some(at) => at,
                    None => {
                        fix.used.push((system, Vec::new()));
                        fix.used.len() - 1
                    }
                };
                let ids = &mut fix.used[at].1;
                if !ids.contains(&satellite) {
                    ids.push(satellite);
                }
            }
        }
        if facts.carries("satellite") {
            self.satellites(fix, facts);
        }
    }

    /// Collects a set of satellites in view; a set is the epoch's when its last part arrives (a
    /// report in one sentence, PUBX,03, is a set of one).
    fn satellites(&mut self, fix: &mut Fix, facts: &Facts<'_>) {
        let (talker, signal) = (facts.talker, facts.signal);
        let satellites = facts.entries.iter().filter_map(|entry| {
            Some(Satellite {
                system: self.systems.of(talker, entry.satellite?),
                id: entry.satellite?,
                talker: talker.into(),
                signal,
                elevation: entry.elevation,
                azimuth: entry.azimuth,
                snr: entry.snr,
                used: entry.satellite_used.map(|used| used == "used"),
            })
        });
        let part = |n: Option<i64>| n.filter(|&n| n != 0).unwrap_or(1);
        let (size, index) = (part(facts.set_size), part(facts.set_index));
        let at = self.sets.iter().position(|set| set.talker == talker && set.signal == signal);
        let at = match at {
            _ if index == 1 => {
                let set = Set { talker: talker.into(), signal, index, satellites: satellites.collect() };
                match at {
                    Some(at) => {
                        self.sets[at] = set;
                        at
                    }
                    None => {
                        self.sets.push(set);
                        self.sets.len() - 1
                    }
                }
            }
            Some(at) if self.sets[at].index == index - 1 => {
                let set = &mut self.sets[at];
                set.index = index;
                set.satellites.extend(satellites);
                at
            }
            // A part missing: the set is incomplete.
            Some(at) => {
                self.sets.remove(at);
                return;
            }
            None => return,
        };
        if index == size {
            let set = self.sets.remove(at);
            fix.in_view.retain(|s| !(s.talker == set.talker && s.signal == set.signal));
            fix.in_view.extend(set.satellites);
        }
    }

    fn close(&mut self) -> Option<Fix> {
        let mut fix = self.fix.take()?;
        if let (None, Some((date, last)), Some(time)) = (fix.date, self.last_date, fix.time) {
            let rolled_over = last.is_some_and(|last| micros(time) < micros(last));
            fix.date = if rolled_over { date.next_day() } else { Some(date) };
        }
        if let Some(date) = fix.date {
            self.last_date = Some((date, fix.time));
        }
        if !self.counts.is_empty() {
            // The combined talker's count, else a proprietary sentence's (the receiver's total), else the sum.
            let of = |wanted: Option<&str>| self.counts.iter().find(|(talker, _)| Some(talker.as_str()) == wanted);
            let total = of(self.systems.combined_talker).or_else(|| of(Some("")));
            fix.satellites_used = Some(total.map_or_else(|| self.counts.iter().map(|(_, n)| n).sum(), |(_, n)| *n));
            self.counts.clear();
        }
        if let (None, Some(msl), Some(separation)) = (fix.altitude_hae, fix.altitude_msl, fix.geoid_separation) {
            fix.altitude_hae = Some(msl + separation);
        }
        if fix.mode.is_none() {
            fix.mode = fix.inferred_mode();
        }
        Some(fix)
    }
}

/// The fixes of a stream of lines, epoch by epoch (see [`FixAssembler`]); lines that do not
/// parse are skipped.
#[derive(Clone, Debug)]
pub struct Fixes<L, I> {
    lines: I,
    assembler: FixAssembler,
    done: bool,
    layouts: core::marker::PhantomData<L>,
}

impl<L, I> Fixes<L, I> {
    /// The fixes of `lines`, assembled with the spec's systems.
    pub fn new(lines: I, systems: &'static Systems) -> Self {
        Self { lines, assembler: FixAssembler::with_systems(systems), done: false, layouts: core::marker::PhantomData }
    }
}

impl<L: Layouts, I: Iterator> Iterator for Fixes<L, I>
where
    I::Item: AsRef<[u8]>,
    for<'a> L::Sentence<'a>: FixSource,
{
    type Item = Fix;

    fn next(&mut self) -> Option<Fix> {
        if self.done {
            return None;
        }
        for line in self.lines.by_ref() {
            if let Some(fix) = self.assembler.feed_line_of::<L>(line.as_ref()) {
                return Some(fix);
            }
        }
        self.done = true;
        self.assembler.finish()
    }
}

// --- The conversions of the generated table: a field's value as its fact's.

/// A time of day; a leap second is no time (Python's `datetime.time` cannot hold it).
pub fn time(value: Option<Time>) -> Option<Time> {
    value.filter(|time| time.second < 60)
}

/// A `ddmmyy` date, when it exists.
pub fn date(value: Option<Date>) -> Option<CalendarDate> {
    value.and_then(CalendarDate::of_date)
}

/// A coordinate in signed decimal degrees.
pub fn degrees(value: Option<Coordinate>) -> Option<f64> {
    value.map(f64::from)
}

/// A number in the fact's unit: `scale` is the factor from the field's unit.
pub fn real(value: Option<Number>, scale: f64) -> Option<f64> {
    value.map(|n| f64::from(n) * scale)
}

/// A whole number (a count, an id).
pub fn whole(value: Option<Number>) -> Option<i64> {
    value.and_then(|n| i64::try_from(n).ok())
}

/// An enum's value id (a code the spec does not know is no fact).
pub fn id<E: CodeEnum>(value: Option<Code<'_, E>>) -> Option<&'static str> {
    value.and_then(Code::known).map(E::id)
}

/// An enum's value id mapped to the fact's value (spec/fix.yaml's `from`).
pub fn mapped<E: CodeEnum>(value: Option<Code<'_, E>>, map: &[(&str, &'static str)]) -> Option<&'static str> {
    let id = id(value)?;
    map.iter().find(|(from, _)| *from == id).map(|&(_, to)| to)
}

/// Of a run of mode indicators (one per system, GNS), the first that is not `not_valid`, else
/// the first.
pub fn first_mode<E: CodeEnum>(value: Option<CodeChars<'_, E>>) -> Option<&'static str> {
    let mut ids = value?.iter().filter_map(Code::known).map(E::id);
    let first = ids.next()?;
    Some(if first == "not_valid" { ids.find(|&id| id != "not_valid").unwrap_or(first) } else { first })
}

#[cfg(test)]
mod tests {
    use super::*;

    const SYSTEMS: Systems =
        Systems { talkers: &[("GL", "glonass")], satellite_ids: &[("gps", 1, 32)], combined_talker: Some("GN") };

    /// A sentence as its facts (the generated table's part, in the crate).
    struct Said(Facts<'static>);

    impl FixSource for Said {
        fn facts(&self) -> Option<Facts<'_>> {
            Some(self.0.clone())
        }
    }

    fn at(time: &str, facts: Facts<'static>) -> Said {
        Said(Facts { talker: "GP", sentence: "GGA", time: Time::parse(time), ..facts })
    }

    #[test]
    fn an_epoch_closes_on_another_time_and_takes_the_last_date_past_midnight() {
        let mut assembler = FixAssembler::with_systems(&SYSTEMS);
        let date = CalendarDate::new(1999, 12, 31);
        assert_eq!(assembler.feed(&at("235959", Facts { date, latitude: Some(1.5), ..Facts::default() })), None);
        let first = assembler.feed(&at("000000.50", Facts::default())).unwrap();
        assert_eq!((first.date, first.mode, first.latitude), (date, Some("fix_2d"), Some(1.5)));
        let second = assembler.finish().unwrap();
        assert_eq!(second.date, CalendarDate::new(2000, 1, 1));
        assert_eq!(second.datetime().map(DateTime::timestamp_ms), Some(946_684_800_500));
        assert_eq!((second.latitude, second.mode, second.sentences.len()), (None, None, 1));
        let mut json = String::new();
        second.write_json(&mut json).unwrap();
        assert!(json.starts_with("{\"time\":\"00:00:00.500000\",\"date\":\"2000-01-01\",\"latitude\":null"));
    }

    #[test]
    fn satellites_used_go_by_system_id_talker_or_id_range() {
        let mut assembler = FixAssembler::with_systems(&SYSTEMS);
        let entries = |ids: &[i64]| -> Vec<EntryFacts> {
            ids.iter().map(|&id| EntryFacts { used_satellite: Some(id), ..EntryFacts::default() }).collect()
        };
        let carried = &["used_satellite"];
        for (talker, system, ids) in [("GN", None, &[1, 40][..]), ("GL", None, &[65]), ("GN", Some("galileo"), &[1])] {
            let facts = Facts { talker, carried, used_system: system, entries: entries(ids), ..Facts::default() };
            assembler.feed(&Said(facts));
        }
        let fix = assembler.finish().unwrap();
        assert_eq!(fix.used, [("gps", vec![1]), ("unknown", vec![40]), ("glonass", vec![65]), ("galileo", vec![1])]);
    }

    #[test]
    fn doubles_are_written_as_python_writes_them() {
        for (value, text) in
            [(545.0, "545.0"), (0.1, "0.1"), (1e-5, "1e-05"), (1.5e16, "1.5e+16"), (-0.0001, "-0.0001")]
        {
            let mut out = String::new();
            write_real(&mut out, Some(value)).unwrap();
            assert_eq!(out, text);
        }
    }

    #[test]
    fn the_day_after_the_last_of_a_month_or_year() {
        let day = |y, m, d| CalendarDate::new(y, m, d).unwrap();
        assert_eq!(day(2024, 2, 28).next_day(), Some(day(2024, 2, 29)));
        assert_eq!(day(2023, 2, 28).next_day(), Some(day(2023, 3, 1)));
        assert_eq!(day(1999, 12, 31).next_day(), Some(day(2000, 1, 1)));
        assert_eq!(CalendarDate::new(2023, 2, 29), None);
    }
}
