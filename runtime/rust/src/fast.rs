//! The fast path of [`parse`](crate::parse): a `$` sentence in its usual form, read in one pass
//! without the bookkeeping that errors need. Whatever it is not sure of (a field it cannot read,
//! a field count that fits no layout, an unusual frame) it leaves to the general path
//! ([`Frame`](super::Frame), [`Reader`](super::Reader)), which then reads the line from the start
//! and finds the error. It accepts a subset of what the general path accepts and gives exactly
//! the same value (`parse_general` is the general path alone; the crate's tests and its fuzz
//! target check that both agree).

use super::frame::{xor_of_bytes, GroupShape, Shape, MAX_LINE};
use super::types::{
    Code, CodeChars, CodeEnum, Coordinate, Date, Entries, Hex, Number, Range, ReadEntry, Sign, Texts, Time, MAX_DIGITS,
};

/// A fast reader's refusal: the general path must read the line. (No payload, so that a value
/// and its refusal fit in the value's own bytes.)
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Unsure;

/// What a fast reader gives: the value read, or [`Unsure`].
pub type Read<T> = Result<T, Unsure>;

/// Adds the decimal digits of `line` from `at` on to `value`; where they end.
#[inline(always)]
fn take_digits(line: &[u8], mut at: usize, value: &mut u64) -> usize {
    while let Some(&b) = line.get(at) {
        let digit = b.wrapping_sub(b'0');
        if digit > 9 {
            break;
        }
        *value = value.wrapping_mul(10).wrapping_add(u64::from(digit));
        at += 1;
    }
    at
}

/// Whether `b` ends a field: `,` or `*` (one test: `,` is `*` + 2).
#[inline(always)]
const fn is_separator(b: u8) -> bool {
    b.wrapping_sub(b'*') & !2 == 0
}

const ONES: u64 = 0x0101_0101_0101_0101;
const LOW7: u64 = 0x7f7f_7f7f_7f7f_7f7f;

/// The high bit of each byte of `word` that equals `byte`.
#[inline(always)]
const fn bytes_equal(word: u64, byte: u8) -> u64 {
    let x = word ^ (byte as u64 * ONES);
    !(((x & LOW7) + LOW7) | x | LOW7)
}

/// How many high bits `mask` has (one per byte at most).
#[inline(always)]
const fn count_bytes(mask: u64) -> usize {
    ((mask >> 7).wrapping_mul(ONES) >> 56) as usize
}

/// Every pair of upper-case letters, `AAABAC…ZYZZ`.
const LETTER_PAIRS: &str = {
    const BYTES: [u8; 2 * 26 * 26] = {
        let mut bytes = [0; 2 * 26 * 26];
        let mut i = 0;
        while i < 26 * 26 {
            bytes[2 * i] = b'A' + (i / 26) as u8;
            bytes[2 * i + 1] = b'A' + (i % 26) as u8;
            i += 1;
        }
        bytes
    };
    match core::str::from_utf8(&BYTES) {
        Ok(pairs) => pairs,
        Err(_) => "",
    }
};

/// The value of each upper-case hex digit plus one; 0 for any other byte (a table: whether a
/// checksum digit is a letter or a digit is not worth a branch).
const UPPER_HEX: [u8; 256] = {
    let mut table = [0; 256];
    let mut i = 0;
    while i < 16 {
        table[b"0123456789ABCDEF"[i] as usize] = i as u8 + 1;
        i += 1;
    }
    table
};

/// The fields of a sentence in its usual frame, handed out in wire order to the fast readers:
/// each reads its field up to the `,` or `*` after it, and refuses ([`Unsure`]) whatever
/// it is not sure the general path reads the same way.
#[derive(Clone, Copy, Debug)]
pub struct FastReader<'a> {
    line: &'a [u8],
    address: &'a [u8],
    /// Where the next field starts.
    at: usize,
    count: usize,
}

impl<'a> FastReader<'a> {
    /// The usual frame: `$`, an address of letters and digits followed by a comma, the fields,
    /// and `*hh` with upper-case hex digits (or none) matching the XOR of the body; at least 12
    /// and at most [`MAX_LINE`] bytes. The body is read 8 bytes at a time, its last bytes as the
    /// word that ends it, for its checksum and its commas (the field count); what the fields
    /// hold is left to the readers, which refuse what their type does not take (a reader of any
    /// text refuses a byte that is not printable ASCII), and [`FastReader::end`] checks that
    /// the last field ends at the final `*` (a `*` in the body would end a field early).
    #[inline(always)]
    pub fn frame(line: &'a [u8]) -> Option<Self> {
        let len = line.len();
        if !(12..=MAX_LINE).contains(&len) || line[0] != b'$' || line[len - 3] != b'*' {
            return None;
        }
        let body = &line[1..len - 3];
        let (mut sum, mut commas) = (0u64, 0usize);
        let mut words = body.chunks_exact(8);
        for word in &mut words {
            let word = u64::from_le_bytes(word.try_into().ok()?);
            sum ^= word;
            commas += count_bytes(bytes_equal(word, b','));
        }
        // The last bytes: the top of the word that ends the body, moved down (none when the
        // body is whole words: shifted out entirely).
        let shift = 8 * (8 - words.remainder().len()) as u32;
        let end = u64::from_le_bytes(body[body.len() - 8..].try_into().ok()?);
        let (last, keep) = (end.checked_shr(shift).unwrap_or(0), u64::MAX.checked_shr(shift).unwrap_or(0));
        sum ^= last;
        commas += count_bytes(bytes_equal(last, b',') & keep);
        let (high, low) = (UPPER_HEX[usize::from(line[len - 2])], UPPER_HEX[usize::from(line[len - 1])]);
        if high == 0 || low == 0 || (high - 1) << 4 | (low - 1) != xor_of_bytes(sum) {
            return None;
        }
        let end = body.iter().position(|b| !b.is_ascii_alphanumeric())?;
        if end == 0 || body[end] != b',' {
            return None;
        }
        Some(Self { line, address: &body[..end], at: end + 2, count: commas })
    }

    /// The address: letters and digits.
    pub const fn address(&self) -> &'a [u8] {
        self.address
    }

    /// The talker ID of a standard sentence (the first two characters of its address). Two
    /// upper-case letters, nearly always, are taken from [`LETTER_PAIRS`]: the same text, with
    /// no UTF-8 check of the line's bytes to pay for.
    #[inline(always)]
    pub fn talker(&self) -> Read<&'a str> {
        match *self.address {
            [first @ b'A'..=b'Z', second @ b'A'..=b'Z', ..] => {
                let at = 2 * (usize::from(first - b'A') * 26 + usize::from(second - b'A'));
                LETTER_PAIRS.get(at..at + 2).ok_or(Unsure)
            }
            _ => core::str::from_utf8(self.address.get(..2).ok_or(Unsure)?).map_err(|_| Unsure),
        }
    }

    /// [`Fields::shape`](super::Fields::shape) without its errors: how many times the group
    /// occurs and how many optional trailing wire fields follow; `None` when the field count
    /// does not fit the layout (the general path cannot read the line with it either).
    #[inline(always)]
    pub fn shape(&self, shape: &Shape) -> Option<(usize, usize)> {
        let (count, fixed, optional) = (self.count, shape.fixed, shape.optional);
        let Some(GroupShape { width, min, max, .. }) = shape.group else {
            return (fixed..=fixed + optional).contains(&count).then(|| (0, count - fixed));
        };
        if count < fixed + min * width {
            return None;
        }
        let rest = count - fixed;
        let repeats = (rest / width).min(max);
        let extra = rest - repeats * width;
        (extra <= optional).then_some((repeats, extra))
    }

    /// Whether the last field ended at the final `*`: only the checksum digits are left.
    #[inline(always)]
    pub fn end(&self) -> Read<()> {
        if self.at + 2 == self.line.len() {
            Ok(())
        } else {
            Err(Unsure)
        }
    }

    /// The next field, up to the `,` or `*` after it.
    #[inline(always)]
    fn span(&mut self) -> Read<&'a [u8]> {
        let (line, start) = (self.line, self.at);
        let rest = line.get(start..).ok_or(Unsure)?;
        let len = rest.iter().position(|&b| is_separator(b)).ok_or(Unsure)?;
        self.at = start + len + 1;
        Ok(&rest[..len])
    }

    /// [`FastReader::span`] of a field that takes any text: refused when a byte of it is not
    /// printable ASCII.
    #[inline(always)]
    fn printable_span(&mut self) -> Read<&'a [u8]> {
        let (line, start) = (self.line, self.at);
        let mut end = start;
        loop {
            match line.get(end) {
                Some(b',' | b'*') => break,
                Some(b' '..=b'~') => end += 1,
                _ => return Err(Unsure),
            }
        }
        self.at = end + 1;
        line.get(start..end).ok_or(Unsure)
    }

    /// The next field, `None` when it is empty; each reader then takes it with the general
    /// path's own parser of its type.
    #[inline(always)]
    fn field(&mut self) -> Read<Option<&'a [u8]>> {
        let text = self.span()?;
        Ok((!text.is_empty()).then_some(text))
    }

    /// An integer `[+-]digits` within `range`.
    #[inline(always)]
    pub fn integer(&mut self, range: Range) -> Read<Option<Number>> {
        self.number(range, true)
    }

    /// A decimal number `[+-]digits[.digits]` within `range`.
    #[inline(always)]
    pub fn decimal(&mut self, range: Range) -> Read<Option<Number>> {
        self.number(range, false)
    }

    /// A number in one pass over its bytes, as [`Number::parse`] reads it: a sign, digits and
    /// (not for an `integer`) at most one point, [`MAX_DIGITS`] digits at most. This is the form
    /// of nearly every field, empty or starting with a digit (no sign, at least one digit, which
    /// spares the checks of both); [`FastReader::signed_number`] takes the others.
    #[inline(always)]
    fn number(&mut self, range: Range, integer: bool) -> Read<Option<Number>> {
        let (line, start) = (self.line, self.at);
        let first = *line.get(start).ok_or(Unsure)?;
        let digit = first.wrapping_sub(b'0');
        if digit > 9 {
            if is_separator(first) {
                self.at = start + 1;
                return Ok(None);
            }
            let (number, next) = signed_number(line, start, integer).ok_or(Unsure)?;
            self.at = next;
            return if range.contains(number) { Ok(Some(number)) } else { Err(Unsure) };
        }
        let mut digits = u64::from(digit);
        let mut end = take_digits(line, start + 1, &mut digits);
        let whole = end - start;
        let point = !integer && line.get(end) == Some(&b'.');
        if point {
            end = take_digits(line, end + 1, &mut digits);
        }
        let count = end - start - usize::from(point);
        if !line.get(end).is_some_and(|&b| is_separator(b)) || count > MAX_DIGITS {
            return Err(Unsure);
        }
        self.at = end + 1;
        let number = Number {
            digits: digits as i64,
            scale: (count - whole) as u8,
            width: whole as u8,
            sign: Sign::Implicit,
            point,
        };
        if range.contains(number) {
            Ok(Some(number))
        } else {
            Err(Unsure)
        }
    }

    /// A field `parse` reads, or none: `Unsure` when `parse` refuses it. `parse` is a function
    /// item or closure, inlined here like the rest: no call through a pointer.
    #[inline(always)]
    fn parsed<T>(&mut self, parse: impl FnOnce(&[u8]) -> Option<T>) -> Read<Option<T>> {
        match self.field()? {
            None => Ok(None),
            Some(text) => parse(text).map(Some).ok_or(Unsure),
        }
    }

    /// Hex digits.
    #[inline(always)]
    pub fn hex(&mut self) -> Read<Option<Hex>> {
        self.parsed(Hex::parse_bytes)
    }

    /// A time `hhmmss[.s…]` in one pass, as [`Time::parse_bytes`] reads it.
    #[inline(always)]
    pub fn time(&mut self) -> Read<Option<Time>> {
        let (line, start) = (self.line, self.at);
        if line.get(start).is_some_and(|&b| is_separator(b)) {
            self.at = start + 1;
            return Ok(None);
        }
        let (mut end, mut fraction, point) = (start + 6, 0u64, line.get(start + 6) == Some(&b'.'));
        if point {
            end = take_digits(line, start + 7, &mut fraction);
        }
        let frac = end.saturating_sub(start + 7);
        if !line.get(end).is_some_and(|&b| is_separator(b)) || frac > 9 {
            return Err(Unsure);
        }
        self.at = end + 1;
        let digits = line.get(start..start + 6).ok_or(Unsure)?;
        Time::from_parts(digits, fraction as u32, frac, point).map(Some).ok_or(Unsure)
    }

    /// A date `ddmmyy` in one pass, as [`Date::parse_bytes`] reads it.
    #[inline(always)]
    pub fn date(&mut self) -> Read<Option<Date>> {
        let (line, start) = (self.line, self.at);
        if line.get(start).is_some_and(|&b| is_separator(b)) {
            self.at = start + 1;
            return Ok(None);
        }
        if !line.get(start + 6).is_some_and(|&b| is_separator(b)) {
            return Err(Unsure);
        }
        self.at = start + 7;
        Date::from_parts(line.get(start..start + 6).ok_or(Unsure)?).map(Some).ok_or(Unsure)
    }

    /// One printable ASCII character.
    #[inline(always)]
    pub fn char(&mut self) -> Read<Option<char>> {
        match self.printable_span()? {
            [] => Ok(None),
            &[b] => Ok(Some(char::from(b))),
            _ => Err(Unsure),
        }
    }

    /// Exactly `value` (or nothing).
    #[inline(always)]
    pub fn literal(&mut self, value: &'static str) -> Read<Option<&'a str>> {
        match self.field()? {
            None => Ok(None),
            Some(text) if text == value.as_bytes() => Ok(Some(value)),
            Some(_) => Err(Unsure),
        }
    }

    /// Printable text, at most `max_length` characters.
    #[inline(always)]
    pub fn text(&mut self, max_length: Option<usize>) -> Read<Option<&'a str>> {
        let text = self.printable_span()?;
        if max_length.is_some_and(|max| text.len() > max) {
            return Err(Unsure);
        }
        if text.is_empty() {
            return Ok(None);
        }
        core::str::from_utf8(text).map(Some).map_err(|_| Unsure)
    }

    /// Exactly the word `keyword`.
    #[inline(always)]
    pub fn keyword(&mut self, keyword: &'static str) -> Read<()> {
        if self.span()? == keyword.as_bytes() {
            Ok(())
        } else {
            Err(Unsure)
        }
    }

    /// A code of enum `E` the spec knows (a code it does not know is the general path's to keep).
    #[inline(always)]
    pub fn code<E: CodeEnum>(&mut self) -> Read<Option<Code<'a, E>>> {
        self.parsed(|text| E::from_code_bytes(text).map(Code::Known))
    }

    /// A run of one-character codes of enum `E`, at most `max_length`.
    #[inline(always)]
    pub fn code_chars<E: CodeEnum>(&mut self, max_length: Option<usize>) -> Read<Option<CodeChars<'a, E>>> {
        let Some(text) = self.field()? else {
            return Ok(None);
        };
        let text = core::str::from_utf8(text).map_err(|_| Unsure)?;
        CodeChars::parse(text, max_length).map(Some).ok_or(Unsure)
    }

    /// A latitude: `ddmm.mmmm` and `N`/`S`, both empty or both set.
    #[inline(always)]
    pub fn latitude(&mut self) -> Read<Option<Coordinate>> {
        self.coordinate(2, 90, [b'N', b'S'])
    }

    /// A longitude: `dddmm.mmmm` and `E`/`W`, both empty or both set.
    #[inline(always)]
    pub fn longitude(&mut self) -> Read<Option<Coordinate>> {
        self.coordinate(3, 180, [b'E', b'W'])
    }

    /// The value and hemisphere fields in one pass, as [`Coordinate::parse_bytes`] and the
    /// hemisphere check read them.
    #[inline(always)]
    fn coordinate(&mut self, degree_digits: usize, max_degrees: u8, hemispheres: [u8; 2]) -> Read<Option<Coordinate>> {
        let (line, start) = (self.line, self.at);
        let mut whole_value = 0u64;
        let mut end = take_digits(line, start, &mut whole_value);
        let whole = end - start;
        let mut minutes = whole_value % 100;
        let point = line.get(end) == Some(&b'.');
        if point {
            end = take_digits(line, end + 1, &mut minutes);
        }
        let frac = end - start - whole - usize::from(point);
        let ends_field = |at: usize| line.get(at).is_some_and(|&b| is_separator(b));
        if !ends_field(end) {
            return Err(Unsure);
        }
        if end == start {
            // no value: no hemisphere either
            self.at = end + 2;
            return if ends_field(end + 1) { Ok(None) } else { Err(Unsure) };
        }
        match line.get(end + 1) {
            Some(&h) if hemispheres.contains(&h) && ends_field(end + 2) => {
                self.at = end + 3;
                let mut value =
                    Coordinate::from_parts(whole_value, whole, minutes, frac, point, degree_digits, max_degrees)
                        .ok_or(Unsure)?;
                value.hemisphere = char::from(h);
                Ok(Some(value))
            }
            _ => Err(Unsure),
        }
    }

    /// `count` values of a repeated group of one text field (each printable, at most
    /// `max_length`), kept as their wire text.
    #[inline(always)]
    pub fn texts(&mut self, count: usize, max_length: Option<usize>) -> Read<Texts<'a>> {
        let start = self.at;
        let mut end = start;
        for _ in 0..count {
            let text = self.printable_span()?;
            if max_length.is_some_and(|max| text.len() > max) {
                return Err(Unsure);
            }
            end = self.at - 1;
        }
        let text = self.line.get(start..end).ok_or(Unsure)?;
        Ok(Texts::ascii(text, count))
    }

    /// Reads `count` entries of `width` wire fields of a repeated group of several fields, each
    /// filled in a default entry by `read_fast` to check it, and keeps them as received (read
    /// again with `read`, the general reader, when asked for).
    #[inline(always)]
    pub fn entries<T: Copy + Default>(
        &mut self,
        count: usize,
        width: usize,
        mut read_fast: impl FnMut(&mut T, &mut Self) -> Read<()>,
        read: ReadEntry<'a, T>,
    ) -> Read<Entries<'a, T>> {
        let start = self.at;
        for _ in 0..count {
            read_fast(&mut T::default(), self)?;
        }
        self.kept(start, count, width, read)
    }

    /// Reads `count` values of `width` wire fields of a repeated group of one field with
    /// `read_fast` to check them, and keeps them as received (read again with `read` when asked
    /// for).
    #[inline(always)]
    pub fn values<T: Copy + Default>(
        &mut self,
        count: usize,
        width: usize,
        mut read_fast: impl FnMut(&mut Self) -> Read<T>,
        read: ReadEntry<'a, T>,
    ) -> Read<Entries<'a, T>> {
        let start = self.at;
        for _ in 0..count {
            read_fast(self)?;
        }
        self.kept(start, count, width, read)
    }

    /// The `count` entries of `width` wire fields read since `start`, as their wire text.
    #[inline(always)]
    fn kept<T: Copy + Default>(
        &self,
        start: usize,
        count: usize,
        width: usize,
        read: ReadEntry<'a, T>,
    ) -> Read<Entries<'a, T>> {
        let end = if count > 0 { self.at - 1 } else { start };
        let text = self.line.get(start..end).ok_or(Unsure)?;
        Ok(Entries::on_wire(Texts::ascii(text, count * width), count, false, read))
    }
}

/// [`FastReader::number`] of a field at `at` that starts with a sign or a point (or that no
/// number reader takes), before its range is checked: the number and where the next field
/// starts. (Neither the range nor the reader is passed: either would be written out to memory
/// before every field, for this rare call.)
#[cold]
#[inline(never)]
fn signed_number(line: &[u8], at: usize, integer: bool) -> Option<(Number, usize)> {
    let (sign, start) = match line.get(at) {
        Some(b'-') => (Sign::Minus, at + 1),
        Some(b'+') => (Sign::Plus, at + 1),
        _ => (Sign::Implicit, at), // a point, or what the checks below refuse
    };
    let mut digits = 0u64;
    let mut end = take_digits(line, start, &mut digits);
    let whole = end - start;
    let point = !integer && line.get(end) == Some(&b'.');
    if point {
        end = take_digits(line, end + 1, &mut digits);
    }
    let count = end - start - usize::from(point);
    if !line.get(end).is_some_and(|&b| is_separator(b)) || count > MAX_DIGITS || count == 0 {
        return None; // not a number, too long, or a sign or a point alone
    }
    let number = Number { digits: digits as i64, scale: (count - whole) as u8, width: whole as u8, sign, point };
    Some((number, end + 1))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn frames_count_commas_and_check_the_sum() {
        let line = b"$GPGSV,4,1,15,05,00,000,17,07,06,105,20,08,11,032,15,10,00,000,16*77";
        let reader = FastReader::frame(line).unwrap();
        assert_eq!((reader.address(), reader.count), (&b"GPGSV"[..], 19));
        assert!(FastReader::frame(b"$GPGSV,4,1,15,05,00,000,17,07,06,105,20,08,11,032,15,10,00,000,16*78").is_none());
        assert!(FastReader::frame(b"$GPHDT,1.0,T*34").is_some());
        assert!(FastReader::frame(b"$GPHDT,1.0,T*3a").is_none());
        // Bodies of every length around the word size, commas here and there.
        for len in 0..24 {
            let mut line = [0u8; 40];
            line[..7].copy_from_slice(b"$GPTXT,");
            for i in 0..len {
                line[7 + i] = if i % 3 == 0 { b',' } else { b'a' + i as u8 };
            }
            let body = &line[1..7 + len];
            let (sum, commas) = (body.iter().fold(0, |x, b| x ^ b), body.iter().filter(|&&b| b == b',').count());
            let digits = b"0123456789ABCDEF";
            line[7 + len] = b'*';
            (line[8 + len], line[9 + len]) = (digits[usize::from(sum >> 4)], digits[usize::from(sum & 15)]);
            let reader = FastReader::frame(&line[..10 + len]);
            assert_eq!(reader.map(|r| r.count), (len >= 2).then_some(commas), "{len}");
        }
    }
}
