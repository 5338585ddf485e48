//! The field values as the numbers and dates an application computes with: `f64::from` a number
//! or a coordinate (signed decimal degrees), `i64::try_from` a whole number, degrees × 10^7,
//! milliseconds of the day, days since 1970-01-01, a UTC [`DateTime`]; with the `time` or `chrono`
//! feature, those crates' types. The Python and C runtimes give the same values
//! (generated/vectors/values.jsonl).

use core::fmt;

use super::types::{Coordinate, Date, Number, Time, POW10};

/// Two-digit years below it are 20yy, the others 19yy (00–68: 2000–2068, 69–99: 1969–1999): the
/// POSIX rule of `strptime`'s `%y`, as pynmea2 reads them (gpsd takes its build century, 20yy).
pub const PIVOT_YEAR: u8 = 69;

impl From<Number> for f64 {
    /// The nearest double for up to 15 significant digits (see [`Number::to_f64`]).
    fn from(number: Number) -> Self {
        number.to_f64()
    }
}

impl From<Coordinate> for f64 {
    /// Signed decimal degrees (see [`Coordinate::to_degrees`]).
    fn from(coordinate: Coordinate) -> Self {
        coordinate.to_degrees()
    }
}

/// What `i64::try_from` a [`Number`] with a fraction (`12.5`) gives: [`Number::trunc`] takes its
/// integer part.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct NotWhole;

impl fmt::Display for NotWhole {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("the number has a fraction")
    }
}

#[cfg(feature = "std")]
impl std::error::Error for NotWhole {}

impl TryFrom<Number> for i64 {
    type Error = NotWhole;

    /// The value of a whole number (`12`, `-007`, `5.0`).
    fn try_from(number: Number) -> Result<Self, NotWhole> {
        let unit = POW10[usize::from(number.scale)];
        if number.digits % unit == 0 {
            Ok(number.signed_digits() / unit)
        } else {
            Err(NotWhole)
        }
    }
}

impl Number {
    /// [`Number::to_f64`] rounded to an `f32`.
    pub fn to_f32(self) -> f32 {
        self.to_f64() as f32
    }
}

impl Coordinate {
    /// Signed degrees × 10^7 (south and west negative), exact integer arithmetic rounded half
    /// away from zero: `4916.45,N` is 492741667.
    pub fn degrees_e7(self) -> i32 {
        // minutes = digits / 10^scale: at most 60 (digits <= 60 × 10^scale, scale <= 16), so
        // neither branch overflows.
        let (digits, scale) = (self.minutes.digits, usize::from(self.minutes.scale));
        let minutes_e7 = if scale <= 7 {
            (digits * POW10[7 - scale] + 30) / 60
        } else {
            (digits + 30 * POW10[scale - 7]) / (60 * POW10[scale - 7])
        };
        let e7 = i64::from(self.degrees) * 10_000_000 + minutes_e7;
        (if matches!(self.hemisphere, 'S' | 'W') { -e7 } else { e7 }) as i32
    }
}

impl Time {
    /// Milliseconds since midnight, digits after the third decimal dropped; a leap second (60)
    /// counts on past 86,400,000.
    pub fn ms_of_day(self) -> u32 {
        let seconds = (u32::from(self.hour) * 60 + u32::from(self.minute)) * 60 + u32::from(self.second);
        let ms = u64::from(self.fraction) * 1000 / POW10[usize::from(self.fraction_digits)] as u64;
        seconds * 1000 + ms as u32
    }

    /// Nanoseconds of the fraction (9 digits at most: exact).
    #[cfg(any(feature = "time", feature = "chrono"))]
    fn nanos(self) -> u32 {
        self.fraction * POW10[9 - usize::from(self.fraction_digits)] as u32
    }

    /// The `time` crate's time of day; `None` for a leap second, which it cannot hold.
    #[cfg(feature = "time")]
    pub fn to_time(self) -> Option<time::Time> {
        time::Time::from_hms_nano(self.hour, self.minute, self.second, self.nanos()).ok()
    }

    /// chrono's time of day; `None` for a leap second (second 60).
    #[cfg(feature = "chrono")]
    pub fn to_naive_time(self) -> Option<chrono::NaiveTime> {
        chrono::NaiveTime::from_hms_nano_opt(self.hour.into(), self.minute.into(), self.second.into(), self.nanos())
    }
}

impl Date {
    /// The four-digit year: 00–68 are 2000–2068, 69–99 are 1969–1999 ([`PIVOT_YEAR`]).
    pub fn full_year(self) -> u16 {
        u16::from(self.year) + if self.year < PIVOT_YEAR { 2000 } else { 1900 }
    }

    /// Days since 1970-01-01 (the year by [`PIVOT_YEAR`]); `None` for a day its month lacks.
    pub fn days_since_epoch(self) -> Option<i32> {
        days_from_civil(self.full_year().into(), self.month, self.day)
    }

    /// The `time` crate's date (the year by [`PIVOT_YEAR`]); `None` for a day its month lacks.
    #[cfg(feature = "time")]
    pub fn to_date(self) -> Option<time::Date> {
        let month = time::Month::try_from(self.month).ok()?;
        time::Date::from_calendar_date(self.full_year().into(), month, self.day).ok()
    }

    /// chrono's date (the year by [`PIVOT_YEAR`]); `None` for a day its month lacks.
    #[cfg(feature = "chrono")]
    pub fn to_naive_date(self) -> Option<chrono::NaiveDate> {
        chrono::NaiveDate::from_ymd_opt(self.full_year().into(), self.month.into(), self.day.into())
    }
}

/// Days since 1970-01-01 of a proleptic Gregorian date, years 1 to 9999; `None` for a day its
/// month lacks.
pub fn days_from_civil(year: i32, month: u8, day: u8) -> Option<i32> {
    const MONTH_DAYS: [u8; 12] = [31, 28, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31];
    let leap = (year % 4 == 0 && year % 100 != 0) || year % 400 == 0;
    let last = MONTH_DAYS.get(usize::from(month).checked_sub(1)?)? + u8::from(month == 2 && leap);
    if !(1..=9999).contains(&year) || !(1..=last).contains(&day) {
        return None;
    }
    // Days since 0000-03-01, years counted from March so that a leap day ends its year (the
    // month lengths from March, 31 30 31 30 31 31 30 31 30 31 31 28, are what (153 m + 2) / 5
    // sums), less the 719,468 days to 1970-01-01.
    let y = year - i32::from(month <= 2);
    let m = i32::from(if month <= 2 { month + 9 } else { month - 3 });
    let day_of_year = (153 * m + 2) / 5 + i32::from(day) - 1;
    Some(y * 365 + y / 4 - y / 100 + y / 400 + day_of_year - 719_468)
}

/// A UTC date and time that exists: a day its month has, years 1 to 9999, no leap second (as
/// Python's `datetime`, `time` and `chrono` hold them).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct DateTime {
    /// The four-digit year.
    pub year: u16,
    /// 1 to 12.
    pub month: u8,
    /// 1 to the month's last day.
    pub day: u8,
    /// The time of day, its second at most 59.
    pub time: Time,
    days: i32,
}

impl DateTime {
    /// The date and time, when they exist.
    pub fn new(year: i32, month: u8, day: u8, time: Time) -> Option<Self> {
        let days = days_from_civil(year, month, day)?;
        (time.second <= 59).then_some(Self { year: year as u16, month, day, time, days })
    }

    /// A `ddmmyy` date (the year by [`PIVOT_YEAR`]) at a time.
    pub fn of_date(date: Date, time: Time) -> Option<Self> {
        Self::new(date.full_year().into(), date.month, date.day, time)
    }

    /// A date in three integer fields (ZDA: the year with four digits) at a time.
    pub fn of_parts(year: Number, month: Number, day: Number, time: Time) -> Option<Self> {
        let part = |n: Number| i64::try_from(n).ok().and_then(|v| u8::try_from(v).ok());
        Self::new(i64::try_from(year).ok()?.try_into().ok()?, part(month)?, part(day)?, time)
    }

    /// Days since 1970-01-01.
    pub fn days_since_epoch(self) -> i32 {
        self.days
    }

    /// Milliseconds since 1970-01-01T00:00Z (digits after the third decimal dropped).
    pub fn timestamp_ms(self) -> i64 {
        i64::from(self.days) * 86_400_000 + i64::from(self.time.ms_of_day())
    }

    /// The `time` crate's date and time, at offset UTC.
    #[cfg(feature = "time")]
    pub fn to_offset_date_time(self) -> Option<time::OffsetDateTime> {
        let month = time::Month::try_from(self.month).ok()?;
        let date = time::Date::from_calendar_date(self.year.into(), month, self.day).ok()?;
        Some(time::PrimitiveDateTime::new(date, self.time.to_time()?).assume_utc())
    }

    /// chrono's date and time in UTC.
    #[cfg(feature = "chrono")]
    pub fn to_chrono(self) -> Option<chrono::DateTime<chrono::Utc>> {
        let date = chrono::NaiveDate::from_ymd_opt(self.year.into(), self.month.into(), self.day.into())?;
        Some(date.and_time(self.time.to_naive_time()?).and_utc())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn values_as_rust_expects_them() {
        let number = Number::parse("-007.50", false).unwrap();
        assert_eq!((f64::from(number), i64::try_from(number), number.trunc()), (-7.5, Err(NotWhole), -7));
        assert_eq!(i64::try_from(Number::parse("-12.00", false).unwrap()), Ok(-12));
        let mut lat = Coordinate::parse("4916.45", 2, 90).unwrap();
        lat.hemisphere = 'S';
        assert_eq!((f64::from(lat), lat.degrees_e7()), (-49.274166666666666, -492_741_667));
        let time = Time::parse("225446.1234567").unwrap();
        assert_eq!(time.ms_of_day(), 82_486_123);
        // The pivot: 00-68 are 20yy, 69-99 19yy.
        assert_eq!(Date::parse("311268").unwrap().full_year(), 2068);
        assert_eq!(Date::parse("010169").unwrap().days_since_epoch(), Some(-365));
        assert_eq!(Date::parse("310218").unwrap().days_since_epoch(), None);
        let when = DateTime::of_date(Date::parse("010170").unwrap(), time).unwrap();
        assert_eq!(when.timestamp_ms(), 82_486_123);
        assert_eq!(DateTime::of_date(Date::parse("010170").unwrap(), Time::parse("235960").unwrap()), None);
        let [y, m, d] = ["2003", "10", "14"].map(|t| Number::parse(t, true).unwrap());
        assert_eq!(DateTime::of_parts(y, m, d, time).map(DateTime::days_since_epoch), Some(12_339));
    }

    #[cfg(feature = "time")]
    #[test]
    fn time_crate() {
        let when = DateTime::of_date(Date::parse("191194").unwrap(), Time::parse("225446.5").unwrap()).unwrap();
        let t = when.to_offset_date_time().unwrap();
        assert_eq!(t.unix_timestamp() * 1000 + i64::from(t.millisecond()), when.timestamp_ms());
    }

    #[cfg(feature = "chrono")]
    #[test]
    fn chrono_crate() {
        let when = DateTime::of_date(Date::parse("191194").unwrap(), Time::parse("225446.5").unwrap()).unwrap();
        assert_eq!(when.to_chrono().unwrap().timestamp_millis(), when.timestamp_ms());
    }
}
