//! The field types: what text each spec type accepts and how it is kept for a byte-exact round
//! trip. `Display` of each type writes its wire text back.

use core::cmp::Ordering;
use core::fmt::{self, Write};
use core::marker::PhantomData;

/// Most digits a number may have, so that it fits a signed 64-bit integer.
pub const MAX_DIGITS: usize = 18;

/// 10^n for n up to [`MAX_DIGITS`].
pub(crate) const POW10: [i64; 19] = {
    let mut table = [1i64; 19];
    let mut i = 1;
    while i < 19 {
        table[i] = table[i - 1] * 10;
        i += 1;
    }
    table
};

/// `value` followed by the decimal digits `bytes`; `None` for any other byte in them.
#[inline(always)]
fn append_digits(mut value: i64, bytes: &[u8]) -> Option<i64> {
    for &b in bytes {
        if !b.is_ascii_digit() {
            return None;
        }
        value = value * 10 + i64::from(b - b'0');
    }
    Some(value)
}

/// 10^`exp` (for `exp` up to 18).
const fn pow10(exp: u8) -> i64 {
    if (exp as usize) < POW10.len() {
        POW10[exp as usize]
    } else {
        i64::MAX
    }
}

/// How the checksum of a sentence is written.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Checksum {
    /// `*hh` with upper-case hex letters (also used when the digits have no letters).
    #[default]
    Upper,
    /// `*hh` with lower-case hex letters.
    Lower,
    /// A bare `*`: the checksum left out, as ST's manual writes its commands.
    Empty,
    /// No checksum at all.
    None,
    /// `*B`: one hex digit, a checksum under 16 as some instruments send it (kept unless
    /// parsing is strict; two digits once the checksum is 16 or more).
    ShortUpper,
    /// `*b`: one hex digit in lower case.
    ShortLower,
}

impl Checksum {
    /// The style of the received text after the `*` (`None` when there was no `*`): one
    /// character is a short checksum, a letter from `a` to `z` makes it lower case.
    pub fn of(text: Option<&str>) -> Self {
        let Some(text) = text else {
            return Self::None;
        };
        let lower = text.bytes().any(|b| b.is_ascii_lowercase());
        match text.chars().count() {
            0 => Self::Empty,
            1 if lower => Self::ShortLower,
            1 => Self::ShortUpper,
            _ if lower => Self::Lower,
            _ => Self::Upper,
        }
    }

    /// Whether `value` is written as one digit in this style: a short style while it is under 16.
    pub const fn is_short(self, value: u8) -> bool {
        matches!(self, Self::ShortUpper | Self::ShortLower) && value < 16
    }

    /// The digits of `value` in this style and how many (two, or one when
    /// [`is_short`](Self::is_short)); `None` for [`Checksum::Empty`] and [`Checksum::None`].
    pub fn digits(self, value: u8) -> Option<([u8; 2], usize)> {
        const UPPER: &[u8; 16] = b"0123456789ABCDEF";
        const LOWER: &[u8; 16] = b"0123456789abcdef";
        let table = match self {
            Self::Upper | Self::ShortUpper => UPPER,
            Self::Lower | Self::ShortLower => LOWER,
            Self::Empty | Self::None => return None,
        };
        if self.is_short(value) {
            return Some(([table[usize::from(value)], 0], 1));
        }
        Some(([table[usize::from(value >> 4)], table[usize::from(value & 15)]], 2))
    }
}

/// The sign of a number as written.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Sign {
    /// No sign character.
    #[default]
    Implicit,
    /// A `+`.
    Plus,
    /// A `-`.
    Minus,
}

/// A fixed-point number as received (integer and decimal fields): `digits` × 10^-`scale`,
/// with the integer digits (leading zeros included), the sign and the decimal point as written.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Number {
    /// All digits as one integer (`00188.976` → 188976).
    pub digits: i64,
    /// Digits after the point (`00188.976` → 3).
    pub scale: u8,
    /// Digits before the point, leading zeros included (`00188.976` → 5; `.5` → 0).
    pub width: u8,
    /// The sign as written.
    pub sign: Sign,
    /// Whether a decimal point was written (`5.` has one, with scale 0).
    pub point: bool,
}

impl Number {
    /// Whether the number is the integer `value`, written without decimals (`0220` is 220), as
    /// a reply's pairing with its command asks.
    pub fn is_integer(self, value: i64) -> bool {
        let signed = if self.sign == Sign::Minus { -self.digits } else { self.digits };
        self.scale == 0 && !self.point && signed == value
    }

    /// Parses `[+-]digits` (`integer`) or `[+-]digits[.digits]`; at most 18 digits.
    #[inline(always)]
    pub fn parse(text: &str, integer: bool) -> Option<Self> {
        let bytes = text.as_bytes();
        let (sign, body) = match bytes.first() {
            Some(b'+') => (Sign::Plus, &bytes[1..]),
            Some(b'-') => (Sign::Minus, &bytes[1..]),
            _ => (Sign::Implicit, bytes),
        };
        // One pass: digits accumulate (wrapping; a number with too many digits is refused
        // below anyway) and the point's position is noted.
        let (mut digits, mut point_at) = (0i64, None);
        for (at, &b) in body.iter().enumerate() {
            let digit = b.wrapping_sub(b'0');
            if digit <= 9 {
                digits = digits.wrapping_mul(10).wrapping_add(i64::from(digit));
            } else if b == b'.' && point_at.is_none() && !integer {
                point_at = Some(at);
            } else {
                return None;
            }
        }
        let count = body.len() - usize::from(point_at.is_some());
        if count == 0 || count > MAX_DIGITS {
            return None;
        }
        let whole = point_at.unwrap_or(body.len());
        let scale = (count - whole) as u8;
        Some(Self { digits, scale, width: whole as u8, sign, point: point_at.is_some() })
    }

    /// Whether the number was written with a `-` (also for `-0`).
    pub const fn is_negative(self) -> bool {
        matches!(self.sign, Sign::Minus)
    }

    /// The value as a signed fixed-point integer: `digits` with the sign applied.
    pub const fn signed_digits(self) -> i64 {
        if self.is_negative() {
            -self.digits
        } else {
            self.digits
        }
    }

    /// The value as a float.
    pub fn to_f64(self) -> f64 {
        self.signed_digits() as f64 / POW10[usize::from(self.scale)] as f64
    }

    /// The integer part of the value (toward zero).
    pub const fn trunc(self) -> i64 {
        self.signed_digits() / POW10[self.scale as usize]
    }

    fn split(self) -> (u64, u64) {
        let unit = POW10[usize::from(self.scale)] as u64;
        let digits = self.digits as u64;
        (digits / unit, digits % unit)
    }

    /// Writes the value as a JSON number without leading or trailing zeros (`188.862`, `-2`).
    pub fn write_json_value<W: fmt::Write + ?Sized>(self, w: &mut W) -> fmt::Result {
        let (whole, frac) = self.split();
        if self.is_negative() && self.digits != 0 {
            w.write_char('-')?;
        }
        write_digits(w, whole, 1)?;
        if frac != 0 {
            let mut frac = frac;
            let mut scale = usize::from(self.scale);
            while frac % 10 == 0 {
                frac /= 10;
                scale -= 1;
            }
            w.write_char('.')?;
            write_digits(w, frac, scale)?;
        }
        Ok(())
    }
}

impl Number {
    /// Writes the wire text in one piece: sign, integer digits zero-padded to `width`, point
    /// and fraction.
    #[inline]
    pub fn write_text<W: fmt::Write + ?Sized>(self, w: &mut W) -> fmt::Result {
        let mut text = Ascii::new();
        self.push_text(&mut text);
        w.write_str(text.as_str())
    }

    pub(crate) fn push_text(self, text: &mut Ascii) {
        let (whole, frac) = self.split();
        match self.sign {
            Sign::Implicit => {}
            Sign::Plus => text.push(b'+'),
            Sign::Minus => text.push(b'-'),
        }
        if self.width > 0 {
            text.digits(whole, usize::from(self.width));
        }
        if self.point {
            text.push(b'.');
            if self.scale > 0 {
                text.digits(frac, usize::from(self.scale));
            }
        }
    }
}

impl fmt::Display for Number {
    /// The wire text: sign, integer digits zero-padded to `width`, point and fraction.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        self.write_text(f)
    }
}

/// Writes `value` in decimal, zero-padded to at least `width` digits.
pub(crate) fn write_digits<W: fmt::Write + ?Sized>(w: &mut W, value: u64, width: usize) -> fmt::Result {
    let mut text = Ascii::new();
    text.digits(value, width);
    w.write_str(text.as_str())
}

/// The wire text of a value put together on the stack, so that it is written with one
/// `write_str` and without the `fmt` machinery: ASCII only, at most [`Ascii::CAPACITY`] bytes
/// (a number's digits before or after its point are at most 24, as `fmt` padding was).
#[derive(Clone, Copy, Debug)]
pub struct Ascii {
    bytes: [u8; Ascii::CAPACITY],
    len: usize,
}

impl Default for Ascii {
    fn default() -> Self {
        Self::new()
    }
}

impl Ascii {
    /// The longest text: a coordinate's degrees, minutes and hemisphere.
    pub const CAPACITY: usize = 96;

    /// No text.
    pub const fn new() -> Self {
        Self { bytes: [0; Self::CAPACITY], len: 0 }
    }

    /// The text as bytes.
    pub fn as_bytes(&self) -> &[u8] {
        &self.bytes[..self.len]
    }

    #[inline]
    pub(crate) fn push(&mut self, byte: u8) {
        if let Some(slot) = self.bytes.get_mut(self.len) {
            *slot = byte;
            self.len += 1;
        }
    }

    /// `value` in decimal, zero-padded to at least `width` digits (at most 24).
    #[inline]
    pub(crate) fn digits(&mut self, mut value: u64, width: usize) {
        let width = width.min(24);
        let mut count = 1;
        let mut rest = value / 10;
        while rest > 0 {
            count += 1;
            rest /= 10;
        }
        let count = count.max(width);
        let end = (self.len + count).min(Self::CAPACITY);
        let start = self.len.min(end);
        for slot in self.bytes[start..end].iter_mut().rev() {
            *slot = b'0' + (value % 10) as u8;
            value /= 10;
        }
        self.len = end;
    }

    /// Two digits (`value` below 100).
    #[inline]
    pub(crate) fn two_digits(&mut self, value: u8) {
        self.push(b'0' + value / 10 % 10);
        self.push(b'0' + value % 10);
    }

    /// `hhmmss` or `ddmmyy`: two digits a part; a part above 99 (only in a value built by hand)
    /// is written whole.
    #[inline]
    pub(crate) fn two_digit_parts(&mut self, parts: [u8; 3]) {
        for part in parts {
            if part < 100 {
                self.two_digits(part);
            } else {
                self.digits(u64::from(part), 2);
            }
        }
    }

    /// The text.
    #[inline]
    pub fn as_str(&self) -> &str {
        // Only ASCII bytes are pushed.
        core::str::from_utf8(&self.bytes[..self.len]).unwrap_or("")
    }
}

/// An inclusive bound of a number range: `digits` × 10^-`scale` (signed).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Bound {
    /// The bound as a signed fixed-point integer.
    pub digits: i64,
    /// Digits after the point.
    pub scale: u8,
}

impl Bound {
    /// `digits` × 10^-`scale`, e.g. `Bound::new(9999, 1)` for 999.9.
    pub const fn new(digits: i64, scale: u8) -> Self {
        Self { digits, scale }
    }

    /// A whole number.
    pub const fn int(value: i64) -> Self {
        Self { digits: value, scale: 0 }
    }

    #[inline(always)]
    fn cmp_number(self, number: Number) -> Ordering {
        let value = number.signed_digits();
        if self.scale == number.scale {
            return self.digits.cmp(&value);
        }
        // Both at the larger scale, exactly: 18 digits times 10^18 fit in an i128.
        let scale = self.scale.max(number.scale);
        let widen = |digits: i64, from: u8| i128::from(digits) * i128::from(pow10(scale - from));
        widen(self.digits, self.scale).cmp(&widen(value, number.scale))
    }
}

/// The inclusive value range of an integer or decimal field.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Range {
    /// The least value allowed.
    pub min: Option<Bound>,
    /// The greatest value allowed.
    pub max: Option<Bound>,
}

impl Range {
    /// Any value.
    pub const ANY: Self = Self { min: None, max: None };

    /// `min..=max`.
    pub const fn between(min: Bound, max: Bound) -> Self {
        Self { min: Some(min), max: Some(max) }
    }

    /// `min` or more.
    pub const fn at_least(min: Bound) -> Self {
        Self { min: Some(min), max: None }
    }

    /// `max` or less.
    pub const fn at_most(max: Bound) -> Self {
        Self { min: None, max: Some(max) }
    }

    /// Whether `number` lies in the range.
    #[inline(always)]
    pub fn contains(self, number: Number) -> bool {
        self.min.is_none_or(|min| min.cmp_number(number) != Ordering::Greater)
            && self.max.is_none_or(|max| max.cmp_number(number) != Ordering::Less)
    }
}

/// An unsigned hexadecimal number (at most 16 digits); digit count and letter case are kept.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Hex {
    /// The value.
    pub value: u64,
    /// Digits written, leading zeros included.
    pub digits: u8,
    /// Whether the letters were lower case.
    pub lower: bool,
}

impl Hex {
    /// Parses up to 16 hex digits whose letters are all of one case.
    pub fn parse(text: &str) -> Option<Self> {
        Self::parse_bytes(text.as_bytes())
    }

    /// [`Hex::parse`] of a field's bytes.
    #[inline(always)]
    pub fn parse_bytes(text: &[u8]) -> Option<Self> {
        if text.len() > 16 {
            return None;
        }
        let (mut value, mut upper, mut lower) = (0u64, false, false);
        for &b in text {
            let digit = match b {
                b'0'..=b'9' => b - b'0',
                b'A'..=b'F' => {
                    upper = true;
                    b - b'A' + 10
                }
                b'a'..=b'f' => {
                    lower = true;
                    b - b'a' + 10
                }
                _ => return None,
            };
            value = value << 4 | u64::from(digit);
        }
        if upper && lower {
            return None;
        }
        Some(Self { value, digits: text.len() as u8, lower })
    }
}

impl fmt::Display for Hex {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let width = usize::from(self.digits);
        if self.lower {
            write!(f, "{:0width$x}", self.value)
        } else {
            write!(f, "{:0width$X}", self.value)
        }
    }
}

/// UTC time of day `hhmmss[.f…]`; the number of fraction digits is kept.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Time {
    /// 0 to 23.
    pub hour: u8,
    /// 0 to 59.
    pub minute: u8,
    /// 0 to 60 (leap second).
    pub second: u8,
    /// The fraction digits as an integer (`.05` → 5).
    pub fraction: u32,
    /// Fraction digits written (0 to 9).
    pub fraction_digits: u8,
    /// Whether a point was written.
    pub point: bool,
}

impl Time {
    /// Parses `hhmmss` with an optional `.` and up to 9 fraction digits.
    #[inline(always)]
    pub fn parse(text: &str) -> Option<Self> {
        Self::parse_bytes(text.as_bytes())
    }

    /// [`Time::parse`] of a field's bytes.
    #[inline(always)]
    pub fn parse_bytes(bytes: &[u8]) -> Option<Self> {
        // Six digits, then the point if any: a point elsewhere fails the digit checks.
        let (c, frac, point) = match bytes.get(6) {
            None if bytes.len() == 6 => (bytes, &bytes[6..], false),
            Some(b'.') => (&bytes[..6], &bytes[7..], true),
            _ => return None,
        };
        if frac.len() > 9 {
            return None;
        }
        let mut fraction = 0u32;
        for &b in frac {
            if !b.is_ascii_digit() {
                return None;
            }
            fraction = fraction * 10 + u32::from(b - b'0');
        }
        Self::from_parts(c, fraction, frac.len(), point)
    }

    /// The time whose `hhmmss` are the first six bytes of `c`, with `frac` fraction digits (at
    /// most 9) worth `fraction`: `None` when those bytes are not digits or out of range.
    #[inline(always)]
    pub(crate) fn from_parts(c: &[u8], fraction: u32, frac: usize, point: bool) -> Option<Self> {
        let hour = two_digits(*c.first()?, *c.get(1)?)?;
        let minute = two_digits(*c.get(2)?, *c.get(3)?)?;
        let second = two_digits(*c.get(4)?, *c.get(5)?)?;
        if hour > 23 || minute > 59 || second > 60 {
            return None;
        }
        Some(Self { hour, minute, second, fraction, fraction_digits: frac as u8, point })
    }

    /// Seconds since midnight, fraction included.
    pub fn seconds(self) -> f64 {
        let whole = u32::from(self.hour) * 3600 + u32::from(self.minute) * 60 + u32::from(self.second);
        f64::from(whole) + f64::from(self.fraction) / POW10[usize::from(self.fraction_digits)] as f64
    }

    /// Writes the JSON value `"hh:mm:ss[.fff]"`.
    pub fn write_json_value<W: fmt::Write + ?Sized>(self, w: &mut W) -> fmt::Result {
        write!(w, "\"{:02}:{:02}:{:02}", self.hour, self.minute, self.second)?;
        if self.fraction_digits > 0 {
            w.write_char('.')?;
            write_digits(w, u64::from(self.fraction), usize::from(self.fraction_digits))?;
        }
        w.write_char('"')
    }
}

impl Time {
    /// Writes the wire text `hhmmss[.f…]` in one piece.
    #[inline]
    pub fn write_text<W: fmt::Write + ?Sized>(self, w: &mut W) -> fmt::Result {
        let mut text = Ascii::new();
        self.push_text(&mut text);
        w.write_str(text.as_str())
    }

    pub(crate) fn push_text(self, text: &mut Ascii) {
        text.two_digit_parts([self.hour, self.minute, self.second]);
        if self.point {
            text.push(b'.');
            if self.fraction_digits > 0 {
                text.digits(u64::from(self.fraction), usize::from(self.fraction_digits));
            }
        }
    }
}

impl fmt::Display for Time {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        self.write_text(f)
    }
}

fn two_digits(a: u8, b: u8) -> Option<u8> {
    if a.is_ascii_digit() && b.is_ascii_digit() {
        Some((a - b'0') * 10 + (b - b'0'))
    } else {
        None
    }
}

/// A date `ddmmyy` with a two-digit year.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Date {
    /// 1 to 31.
    pub day: u8,
    /// 1 to 12.
    pub month: u8,
    /// Two-digit year, 0 to 99.
    pub year: u8,
}

impl Date {
    /// Parses `ddmmyy` (day 1 to 31, month 1 to 12).
    #[inline(always)]
    pub fn parse(text: &str) -> Option<Self> {
        Self::parse_bytes(text.as_bytes())
    }

    /// [`Date::parse`] of a field's bytes.
    #[inline(always)]
    pub fn parse_bytes(b: &[u8]) -> Option<Self> {
        if b.len() != 6 {
            return None;
        }
        Self::from_parts(b)
    }

    /// The date whose `ddmmyy` are the first six bytes of `b`: `None` when those bytes are not
    /// digits or out of range.
    #[inline(always)]
    pub(crate) fn from_parts(b: &[u8]) -> Option<Self> {
        let day = two_digits(*b.first()?, *b.get(1)?)?;
        let month = two_digits(*b.get(2)?, *b.get(3)?)?;
        let year = two_digits(*b.get(4)?, *b.get(5)?)?;
        if !(1..=31).contains(&day) || !(1..=12).contains(&month) {
            return None;
        }
        Some(Self { day, month, year })
    }

    /// Writes the JSON value `"yy-mm-dd"`.
    pub fn write_json_value<W: fmt::Write + ?Sized>(self, w: &mut W) -> fmt::Result {
        write!(w, "\"{:02}-{:02}-{:02}\"", self.year, self.month, self.day)
    }
}

impl Date {
    /// Writes the wire text `ddmmyy` in one piece.
    #[inline]
    pub fn write_text<W: fmt::Write + ?Sized>(self, w: &mut W) -> fmt::Result {
        let mut text = Ascii::new();
        self.push_text(&mut text);
        w.write_str(text.as_str())
    }

    pub(crate) fn push_text(self, text: &mut Ascii) {
        text.two_digit_parts([self.day, self.month, self.year]);
    }
}

impl fmt::Display for Date {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        self.write_text(f)
    }
}

/// Latitude or longitude as received: degrees, minutes (fixed point) and hemisphere.
///
/// On the wire it takes two fields, `ddmm.mmmm,N` or `dddmm.mmmm,E`; `Display` writes both.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Coordinate {
    /// Whole degrees (at most 90 or 180).
    pub degrees: u8,
    /// Minutes, at most 60; always written with two integer digits.
    pub minutes: Number,
    /// `N`, `S`, `E` or `W`.
    pub hemisphere: char,
    /// Digits written for the degrees, leading zeros included.
    pub degree_digits: u8,
}

impl Coordinate {
    /// Parses the value field: `max_degree_digits` is 2 for a latitude, 3 for a longitude.
    /// The hemisphere is left empty (`'\0'`).
    #[inline(always)]
    pub fn parse(text: &str, max_degree_digits: usize, max_degrees: u8) -> Option<Self> {
        Self::parse_bytes(text.as_bytes(), max_degree_digits, max_degrees)
    }

    /// [`Coordinate::parse`] of a field's bytes.
    #[inline(always)]
    pub fn parse_bytes(text: &[u8], max_degree_digits: usize, max_degrees: u8) -> Option<Self> {
        let (whole, frac, point) = match text.iter().position(|&b| b == b'.') {
            Some(at) => (&text[..at], &text[at + 1..], true),
            None => (text, &[][..], false),
        };
        if whole.len() < 2 || whole.len() > 2 + max_degree_digits || frac.len() > MAX_DIGITS - 2 {
            return None;
        }
        // At most 5 whole digits and 16 after the point (checked above): no overflow.
        let whole_value = append_digits(0, whole)?;
        let minutes = append_digits(whole_value % 100, frac)?;
        Self::from_parts(
            whole_value as u64,
            whole.len(),
            minutes as u64,
            frac.len(),
            point,
            max_degree_digits,
            max_degrees,
        )
    }

    /// The coordinate whose value field has `whole` digits before the point worth `whole_value`
    /// and `frac` after it (the minutes, fraction included, worth `minutes`): `None` when the
    /// counts or the values are out of range. The hemisphere is left empty (`'\0'`).
    #[inline(always)]
    pub(crate) fn from_parts(
        whole_value: u64,
        whole: usize,
        minutes: u64,
        frac: usize,
        point: bool,
        max_degree_digits: usize,
        max_degrees: u8,
    ) -> Option<Self> {
        if whole < 2 || whole > 2 + max_degree_digits || frac > MAX_DIGITS - 2 {
            return None;
        }
        let degrees = whole_value / 100;
        if degrees > u64::from(max_degrees) || minutes > 60 * POW10[frac] as u64 {
            return None;
        }
        let minutes = Number { digits: minutes as i64, scale: frac as u8, width: 2, sign: Sign::Implicit, point };
        Some(Self { degrees: degrees as u8, minutes, hemisphere: '\0', degree_digits: (whole - 2) as u8 })
    }

    /// Signed decimal degrees (south and west negative).
    pub fn to_degrees(self) -> f64 {
        let value = f64::from(self.degrees) + self.minutes.to_f64() / 60.0;
        if matches!(self.hemisphere, 'S' | 'W') {
            -value
        } else {
            value
        }
    }

    /// Writes the value field (without the hemisphere).
    pub fn write_value_text<W: fmt::Write + ?Sized>(self, w: &mut W) -> fmt::Result {
        let mut text = Ascii::new();
        self.push_value_text(&mut text);
        w.write_str(text.as_str())
    }

    pub(crate) fn push_value_text(self, text: &mut Ascii) {
        if self.degree_digits > 0 {
            text.digits(u64::from(self.degrees), usize::from(self.degree_digits));
        }
        self.minutes.push_text(text);
    }

    /// Writes the JSON value `{"deg":55,"min":50.613522,"hemi":"N"}`.
    pub fn write_json_value<W: fmt::Write + ?Sized>(self, w: &mut W) -> fmt::Result {
        write!(w, "{{\"deg\":{},\"min\":", self.degrees)?;
        self.minutes.write_json_value(w)?;
        w.write_str(",\"hemi\":")?;
        super::write::write_json_char(w, self.hemisphere)?;
        w.write_char('}')
    }
}

impl fmt::Display for Coordinate {
    /// Both wire fields: `5550.613522,N`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        self.write_value_text(f)?;
        f.write_char(',')?;
        f.write_char(self.hemisphere)
    }
}

/// Whether `text` upper-cased (ASCII letters) is exactly `upper`: how text commands match their
/// command word, keywords and enum codes.
pub fn upper_eq(text: &str, upper: &str) -> bool {
    text.len() == upper.len() && text.bytes().zip(upper.bytes()).all(|(a, b)| a.to_ascii_uppercase() == b)
}

/// Which characters the codes of an enum use: an unknown code must use the same ones to be
/// kept (rather than rejected).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CodeClass {
    /// ASCII digits only.
    Digits,
    /// ASCII letters only.
    Letters,
    /// ASCII letters and digits.
    Alnum,
    /// None: a closed set (N/S, A/V, units) refuses every code it does not list.
    Closed,
}

impl CodeClass {
    /// Whether a code the spec does not know is still well formed: `min..=max` characters of
    /// this class.
    pub fn admits(self, text: &str, min: usize, max: usize) -> bool {
        (min..=max).contains(&text.len())
            && text.bytes().all(|b| match self {
                Self::Digits => b.is_ascii_digit(),
                Self::Letters => b.is_ascii_alphabetic(),
                Self::Alnum => b.is_ascii_alphanumeric(),
                Self::Closed => false,
            })
    }
}

/// A lookup table of the spec (generated in [`crate::enums`]): each value has a wire code and
/// a spec id.
pub trait CodeEnum: Copy + Sized + 'static {
    /// What a `bad_field` error says an enum field should hold.
    const EXPECTED: &'static str;
    /// What a `bad_field` error says an enum_chars field should hold.
    const EXPECTED_CHARS: &'static str;
    /// The characters of the known codes.
    const CLASS: CodeClass;
    /// Length of the shortest known code.
    const MIN_LEN: usize;
    /// Length of the longest known code.
    const MAX_LEN: usize;
    /// Every value, in the spec's order.
    const ALL: &'static [Self];

    /// The value with wire code `code`.
    fn from_code(code: &str) -> Option<Self>;
    /// The value with wire code `code` given as bytes (how the fast path of parsing reads it).
    #[inline]
    fn from_code_bytes(code: &[u8]) -> Option<Self> {
        core::str::from_utf8(code).ok().and_then(Self::from_code)
    }
    /// The wire code.
    fn code(self) -> &'static str;
    /// The spec id (`"differential"`).
    fn id(self) -> &'static str;
}

/// An enum field's value: a code the spec knows, or a well-formed one it does not.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Code<'a, E> {
    /// A code of the spec.
    Known(E),
    /// A code the spec does not list, of the same form as the known ones.
    Unknown(&'a str),
}

impl<'a, E: CodeEnum> Code<'a, E> {
    /// Reads a code: known, or unknown of length `min..=max` and the enum's character class.
    #[inline(always)]
    pub fn parse(text: &'a str, min: usize, max: usize) -> Option<Self> {
        match E::from_code(text) {
            Some(value) => Some(Self::Known(value)),
            None if E::CLASS.admits(text, min, max) => Some(Self::Unknown(text)),
            None => None,
        }
    }

    /// Reads a code of a text command, whose known codes match ignoring case (the text upper-cased
    /// is looked up); an unknown one is kept as written.
    pub fn parse_ignoring_case(text: &'a str, min: usize, max: usize) -> Option<Self> {
        match E::ALL.iter().find(|value| upper_eq(text, value.code())) {
            Some(&value) => Some(Self::Known(value)),
            None if E::CLASS.admits(text, min, max) => Some(Self::Unknown(text)),
            None => None,
        }
    }

    /// The wire code.
    pub fn code(self) -> &'a str {
        match self {
            Self::Known(value) => value.code(),
            Self::Unknown(code) => code,
        }
    }

    /// The spec's value, if the code is known.
    pub fn known(self) -> Option<E> {
        match self {
            Self::Known(value) => Some(value),
            Self::Unknown(_) => None,
        }
    }

    /// The spec id, or the code itself when unknown (the `decode --values` form).
    pub fn id(self) -> &'a str {
        match self {
            Self::Known(value) => value.id(),
            Self::Unknown(code) => code,
        }
    }
}

impl<E: CodeEnum> From<E> for Code<'_, E> {
    fn from(value: E) -> Self {
        Self::Known(value)
    }
}

impl<E: CodeEnum> fmt::Display for Code<'_, E> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.code())
    }
}

/// An enum_chars field: a run of one-character codes (GNS mode `ANNN`), kept as its text.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct CodeChars<'a, E> {
    text: &'a str,
    values: PhantomData<E>,
}

impl<'a, E: CodeEnum> CodeChars<'a, E> {
    /// Reads a run of codes, each known or a well-formed unknown one; at most `max_length`.
    pub fn parse(text: &'a str, max_length: Option<usize>) -> Option<Self> {
        if max_length.is_some_and(|max| text.len() > max) {
            return None;
        }
        let ok = (0..text.len()).all(|i| text.get(i..i + 1).is_some_and(|c| Code::<E>::parse(c, 1, 1).is_some()));
        ok.then_some(Self { text, values: PhantomData })
    }

    /// The wire text.
    pub fn as_str(self) -> &'a str {
        self.text
    }

    /// The codes, one per character.
    pub fn iter(self) -> impl Iterator<Item = Code<'a, E>> {
        let text = self.text;
        (0..text.len()).map(move |i| {
            let code = text.get(i..i + 1).unwrap_or("");
            E::from_code(code).map_or(Code::Unknown(code), Code::Known)
        })
    }
}

impl<E: CodeEnum> fmt::Display for CodeChars<'_, E> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.text)
    }
}

/// The values of a repeated group of one text field, kept as received: their wire text (joined
/// by `,`) and how many there are. It stays small whatever the group's maximum (ST's sentences
/// take up to 64 raw values). The text is kept as the line's bytes, which are UTF-8 (a `&str`
/// given, or what the fast path checked is printable ASCII): parsing does not pay for making
/// them a `&str`, which [`Texts::as_str`] does when it is asked for.
#[derive(Clone, Copy, PartialEq, Eq, Hash)]
pub struct Texts<'a> {
    text: &'a [u8],
    count: usize,
    separator: u8,
    blanks: super::frame::Blanks,
}

impl Default for Texts<'_> {
    fn default() -> Self {
        Self::new("", 0)
    }
}

impl<'a> Texts<'a> {
    /// `count` values joined by `,` in `text` (`Texts::new("A,,B", 3)`).
    pub const fn new(text: &'a str, count: usize) -> Self {
        Self::joined(text, count, b',')
    }

    /// `count` values joined by `separator`.
    pub(crate) const fn joined(text: &'a str, count: usize, separator: u8) -> Self {
        Self { text: text.as_bytes(), count, separator, blanks: super::frame::Blanks::EMPTY }
    }

    /// `count` values joined by `,` in bytes the fast path has read as printable ASCII.
    pub(crate) const fn ascii(text: &'a [u8], count: usize) -> Self {
        Self { text, count, separator: b',', blanks: super::frame::Blanks::EMPTY }
    }

    /// The same values with the entries in `blanks` (1-based) read as empty (lenient parsing).
    pub(crate) const fn blanking(self, blanks: super::frame::Blanks) -> Self {
        Self { blanks, ..self }
    }

    /// How many values there are.
    pub const fn len(&self) -> usize {
        self.count
    }

    /// Whether there are none.
    pub const fn is_empty(&self) -> bool {
        self.count == 0
    }

    /// The values as received, joined by `,`.
    pub const fn as_str(&self) -> &'a str {
        match core::str::from_utf8(self.text) {
            Ok(text) => text,
            Err(_) => "", // not reached: the text is always UTF-8
        }
    }

    /// [`Texts::as_str`] as the bytes it is made of.
    pub(crate) const fn as_bytes(&self) -> &'a [u8] {
        self.text
    }

    /// The separator between the values.
    pub(crate) const fn separator(&self) -> u8 {
        self.separator
    }

    /// The values lenient parsing reads as empty (1-based).
    pub(crate) const fn blanks(&self) -> super::frame::Blanks {
        self.blanks
    }

    /// The values in order, `None` for an empty one.
    pub fn iter(&self) -> impl Iterator<Item = Option<&'a str>> + 'a {
        let (mut rest, separator, blanks) = (self.as_str(), self.separator, self.blanks);
        (1..=self.count).map(move |entry| {
            let value = match rest.bytes().position(|b| b == separator) {
                Some(at) => {
                    let value = &rest[..at];
                    rest = &rest[at + 1..];
                    value
                }
                None => core::mem::take(&mut rest),
            };
            (!value.is_empty() && (blanks.is_empty() || !blanks.contains(entry))).then_some(value)
        })
    }
}

impl fmt::Debug for Texts<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("Texts")
            .field("text", &self.as_str())
            .field("count", &self.count)
            .field("separator", &self.separator)
            .field("blanks", &self.blanks)
            .finish()
    }
}

/// How an entry of a repeated group is read from its wire fields (the layout's own reader).
pub type ReadEntry<'a, T> = fn(&mut super::frame::Reader<'a>) -> Result<T, super::error::Error<'a>>;

/// The entries of a repeated group (GSV's satellites, GSA's satellite IDs, ...). A parsed
/// sentence keeps them as received, their wire text, and reads each one when it is asked for: a
/// sentence stays small whatever the group's maximum (PUBX,03 takes 64 entries). A sentence to
/// build holds the caller's slice ([`Entries::from_items`]).
#[derive(Clone, Copy)]
pub struct Entries<'a, T> {
    /// The entries' wire fields, lenient parsing's blanks included.
    wire: Texts<'a>,
    count: usize,
    ignore_case: bool,
    read: Option<ReadEntry<'a, T>>,
    items: &'a [T],
}

impl<T> Default for Entries<'_, T> {
    fn default() -> Self {
        Self { wire: Texts::new("", 0), count: 0, ignore_case: false, read: None, items: &[] }
    }
}

impl<'a, T: Copy + Default> Entries<'a, T> {
    /// The entries of a sentence to build.
    pub const fn from_items(items: &'a [T]) -> Self {
        Self { wire: Texts::joined("", 0, b','), count: items.len(), ignore_case: false, read: None, items }
    }

    /// `count` entries as received: `wire` holds their fields, read back with `read`.
    pub(crate) const fn on_wire(wire: Texts<'a>, count: usize, ignore_case: bool, read: ReadEntry<'a, T>) -> Self {
        Self { wire, count, ignore_case, read: Some(read), items: &[] }
    }

    /// How many entries there are.
    pub const fn len(&self) -> usize {
        self.count
    }

    /// Whether there are none.
    pub const fn is_empty(&self) -> bool {
        self.count == 0
    }

    /// The entries' fields as received (joined by `,`), or `None` for entries built from a
    /// slice.
    pub fn as_wire(&self) -> Option<&'a str> {
        self.read.map(|_| self.wire.as_str())
    }

    /// The wire fields of entries read from a line (`None` for entries built from a slice).
    pub(crate) fn wire(&self) -> Option<&Texts<'a>> {
        self.read.map(|_| &self.wire)
    }

    /// The caller's entries (empty for entries read from a line).
    pub const fn items(&self) -> &'a [T] {
        self.items
    }

    /// Entry `index` (0-based), or `None` past the last.
    pub fn get(&self, index: usize) -> Option<T> {
        self.iter().nth(index)
    }

    /// The entries in order.
    pub fn iter(&self) -> EntryIter<'a, T> {
        let reader = super::frame::Reader::over(self.wire.as_str(), self.wire.separator(), self.wire.blanks());
        EntryIter {
            reader: if self.ignore_case { reader.ignoring_case() } else { reader },
            read: self.read,
            items: self.items,
            next: 0,
            count: self.count,
        }
    }
}

/// The entries of an [`Entries`], in order.
#[derive(Clone, Debug)]
pub struct EntryIter<'a, T> {
    reader: super::frame::Reader<'a>,
    read: Option<ReadEntry<'a, T>>,
    items: &'a [T],
    next: usize,
    count: usize,
}

impl<T: Copy + Default> Iterator for EntryIter<'_, T> {
    type Item = T;

    fn next(&mut self) -> Option<T> {
        if self.next >= self.count {
            return None;
        }
        self.next += 1;
        match self.read {
            // A parsed sentence's entries read as they did when it was parsed.
            Some(read) => Some(read(&mut self.reader).unwrap_or_default()),
            None => self.items.get(self.next - 1).copied(),
        }
    }

    fn size_hint(&self) -> (usize, Option<usize>) {
        let left = self.count - self.next;
        (if self.read.is_some() { left } else { left.min(self.items.len().saturating_sub(self.next)) }, Some(left))
    }
}

impl<'a, T: Copy + Default> IntoIterator for &Entries<'a, T> {
    type Item = T;
    type IntoIter = EntryIter<'a, T>;

    fn into_iter(self) -> Self::IntoIter {
        self.iter()
    }
}

impl<T: Copy + Default + PartialEq> PartialEq for Entries<'_, T> {
    fn eq(&self, other: &Self) -> bool {
        self.count == other.count && self.iter().eq(other.iter())
    }
}

impl<T: Copy + Default + Eq> Eq for Entries<'_, T> {}

impl<T: Copy + Default + fmt::Debug> fmt::Debug for Entries<'_, T> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_list().entries(self.iter()).finish()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_keep_their_text() {
        for text in ["0", "-0.0", "+.5", "5.", "00188.976", "123456789012345678"] {
            let number = Number::parse(text, false).unwrap();
            let mut out = [0u8; 32];
            let mut w = crate::runtime::write::tests::Buf::new(&mut out);
            core::fmt::Write::write_fmt(&mut w, format_args!("{number}")).unwrap();
            assert_eq!(w.as_str(), text);
        }
        for text in ["", "+", ".", "1.2.3", "1e5", "1234567890123456789", "-"] {
            assert_eq!(Number::parse(text, false), None, "{text}");
        }
        assert_eq!(Number::parse("1.5", true), None);
    }

    #[test]
    fn ranges_compare_exactly() {
        let range = Range::between(Bound::int(0), Bound::new(9999, 1));
        let number = |text| Number::parse(text, false).unwrap();
        assert!(range.contains(number("999.90")));
        assert!(!range.contains(number("999.91")));
        assert!(range.contains(number("-0.0")));
        assert!(!range.contains(number("-0.001")));
        assert!(Range::at_most(Bound::int(7)).contains(number("6.99999999999999999")));
        assert!(!Range::at_least(Bound::int(1)).contains(number("0.99999999999999999")));
    }

    #[test]
    fn coordinates_allow_sixty_minutes() {
        assert!(Coordinate::parse("8960.000000", 2, 90).is_some());
        assert!(Coordinate::parse("8960.000001", 2, 90).is_none());
        assert!(Coordinate::parse("9100.0", 2, 90).is_none());
        assert_eq!(Coordinate::parse("50.1", 2, 90).map(|c| c.degree_digits), Some(0));
    }

    /// A group of pairs (an integer 0..99, then any text), as a layout's reader reads one entry.
    fn pair<'a>(f: &mut super::super::frame::Reader<'a>) -> Result<(Option<Number>, &'a str), super::super::Error<'a>> {
        let number = f.integer("n", "integer 0..99", Range::between(Bound::int(0), Bound::int(99)))?;
        Ok((number, f.text("t", "text", None)?.unwrap_or("")))
    }

    #[test]
    fn entries_read_from_the_wire_as_parsed() {
        use super::super::frame::{Blanks, Reader};
        let mut f = Reader::over("07,a,x1,b,42,", b',', Blanks::EMPTY.with(3));
        let entries = f.entries("pairs", 3, 2, pair).unwrap();
        assert_eq!(entries.len(), 3);
        assert_eq!(entries.as_wire(), Some("07,a,x1,b,42,"));
        let n = |text| Number::parse(text, true);
        // wire field 3 ("x1") was read as empty (lenient parsing's blank): so it reads again
        let read: [(Option<Number>, &str); 3] = [(n("07"), "a"), (None, "b"), (n("42"), "")];
        assert!(entries.iter().eq(read));
        assert_eq!(entries.get(1), Some((None, "b")));
        assert_eq!(entries.get(3), None);
        // the same entries given by the caller are equal to them
        assert_eq!(entries, Entries::from_items(&read));
        assert_ne!(entries, Entries::from_items(&read[..2]));
        assert_eq!(Entries::from_items(&read).as_wire(), None);
    }

    #[test]
    fn a_bad_entry_is_refused_where_it_is() {
        let mut f = super::super::frame::Fields::new("GPTST", "07,a,100,b", 4).reader();
        let err = f.entries("pairs", 2, 2, pair).unwrap_err();
        assert!(err.kind() == super::super::ErrorKind::BadField && err.is_out_of_range());
        assert_eq!(err.field(), Some(3));
    }
}
