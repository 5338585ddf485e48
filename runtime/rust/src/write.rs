//! Writing sentences back (with their checksum) and the tools' JSON, into any `fmt::Write`.

use core::fmt::{self, Write};

use super::error::Problems;
use super::frame;
use super::types::{
    Ascii, Checksum, Code, CodeChars, CodeEnum, Coordinate, Date, Entries, Hex, Number, Sign, Texts, Time, MAX_DIGITS,
    POW10,
};

/// A field value: how it is written on the wire and in both JSON forms of the tools.
pub trait FieldValue {
    /// Wire fields the value takes (2 for latitude and longitude).
    const WIDTH: usize = 1;

    /// Writes the wire text (fields joined by `,`).
    fn write_wire<W: Write + ?Sized>(&self, w: &mut W) -> fmt::Result;

    /// Writes the wire text, fields joined by `separator` (a space in a text command).
    fn write_wire_fields<W: Write + ?Sized>(&self, w: &mut W, separator: char) -> fmt::Result {
        let _ = separator;
        self.write_wire(w)
    }

    /// Writes the lossless JSON form of `decode`: the text as a string.
    fn write_text_json<W: Write + ?Sized>(&self, w: &mut W) -> fmt::Result {
        w.write_char('"')?;
        self.write_wire(&mut JsonEscape(w))?;
        w.write_char('"')
    }

    /// Writes the decoded JSON form of `decode --values`.
    fn write_value_json<W: Write + ?Sized>(&self, w: &mut W) -> fmt::Result;

    /// Appends the wire text (fields joined by `separator`) when it is ASCII put together
    /// without `fmt` (numbers, times, dates, coordinates): `false` for the other types, which
    /// [`FieldValue::write_wire_fields`] writes.
    #[inline]
    fn push_ascii(&self, text: &mut Ascii, separator: u8) -> bool {
        let _ = (text, separator);
        false
    }

    /// Puts the wire text (fields joined by `,`) into `out`, byte for byte what
    /// [`FieldValue::write_wire`] writes, when it is ASCII; `None` when it is not, or does not
    /// fit (the caller then writes the text with `fmt`).
    #[inline]
    fn put_wire(&self, out: &mut ByteWriter<'_>) -> Option<()> {
        let _ = out;
        None
    }

    /// `,` and [`FieldValue::put_wire`].
    #[inline]
    fn put_field(&self, out: &mut ByteWriter<'_>) -> Option<()> {
        out.put(b",")?;
        self.put_wire(out)
    }
}

impl FieldValue for Number {
    #[inline]
    fn write_wire<W: Write + ?Sized>(&self, w: &mut W) -> fmt::Result {
        self.write_text(w)
    }

    #[inline]
    fn push_ascii(&self, text: &mut Ascii, _separator: u8) -> bool {
        self.push_text(text);
        true
    }

    fn write_value_json<W: Write + ?Sized>(&self, w: &mut W) -> fmt::Result {
        self.write_json_value(w)
    }

    #[inline]
    fn put_wire(&self, out: &mut ByteWriter<'_>) -> Option<()> {
        out.number(*self)
    }

    #[inline]
    fn put_field(&self, out: &mut ByteWriter<'_>) -> Option<()> {
        out.comma_number(*self)
    }
}

impl FieldValue for Hex {
    fn write_wire<W: Write + ?Sized>(&self, w: &mut W) -> fmt::Result {
        write!(w, "{self}")
    }

    fn write_value_json<W: Write + ?Sized>(&self, w: &mut W) -> fmt::Result {
        write!(w, "{}", self.value)
    }

    #[inline]
    fn put_wire(&self, out: &mut ByteWriter<'_>) -> Option<()> {
        out.hex(*self)
    }
}

impl FieldValue for Time {
    #[inline]
    fn write_wire<W: Write + ?Sized>(&self, w: &mut W) -> fmt::Result {
        self.write_text(w)
    }

    #[inline]
    fn push_ascii(&self, text: &mut Ascii, _separator: u8) -> bool {
        self.push_text(text);
        true
    }

    fn write_value_json<W: Write + ?Sized>(&self, w: &mut W) -> fmt::Result {
        self.write_json_value(w)
    }

    #[inline]
    fn put_wire(&self, out: &mut ByteWriter<'_>) -> Option<()> {
        out.time(*self)
    }
}

impl FieldValue for Date {
    #[inline]
    fn write_wire<W: Write + ?Sized>(&self, w: &mut W) -> fmt::Result {
        self.write_text(w)
    }

    #[inline]
    fn push_ascii(&self, text: &mut Ascii, _separator: u8) -> bool {
        self.push_text(text);
        true
    }

    fn write_value_json<W: Write + ?Sized>(&self, w: &mut W) -> fmt::Result {
        self.write_json_value(w)
    }

    #[inline]
    fn put_wire(&self, out: &mut ByteWriter<'_>) -> Option<()> {
        out.two_digit_parts([self.day, self.month, self.year])
    }
}

impl FieldValue for Coordinate {
    const WIDTH: usize = 2;

    fn write_wire<W: Write + ?Sized>(&self, w: &mut W) -> fmt::Result {
        self.write_wire_fields(w, ',')
    }

    #[inline]
    fn push_ascii(&self, text: &mut Ascii, separator: u8) -> bool {
        if !self.hemisphere.is_ascii() {
            return false;
        }
        self.push_value_text(text);
        text.push(separator);
        text.push(self.hemisphere as u8);
        true
    }

    #[inline]
    fn write_wire_fields<W: Write + ?Sized>(&self, w: &mut W, separator: char) -> fmt::Result {
        self.write_value_text(w)?;
        w.write_char(separator)?;
        w.write_char(self.hemisphere)
    }

    fn write_text_json<W: Write + ?Sized>(&self, w: &mut W) -> fmt::Result {
        w.write_str("[\"")?;
        self.write_value_text(w)?;
        w.write_str("\",")?;
        write_json_char(w, self.hemisphere)?;
        w.write_char(']')
    }

    fn write_value_json<W: Write + ?Sized>(&self, w: &mut W) -> fmt::Result {
        self.write_json_value(w)
    }

    #[inline]
    fn put_wire(&self, out: &mut ByteWriter<'_>) -> Option<()> {
        out.coordinate(*self)
    }
}

impl FieldValue for char {
    fn write_wire<W: Write + ?Sized>(&self, w: &mut W) -> fmt::Result {
        w.write_char(*self)
    }

    fn write_value_json<W: Write + ?Sized>(&self, w: &mut W) -> fmt::Result {
        write_json_char(w, *self)
    }

    #[inline]
    fn put_wire(&self, out: &mut ByteWriter<'_>) -> Option<()> {
        out.put(&[u8::try_from(*self).ok().filter(u8::is_ascii)?])
    }
}

impl FieldValue for &str {
    fn write_wire<W: Write + ?Sized>(&self, w: &mut W) -> fmt::Result {
        w.write_str(self)
    }

    fn write_text_json<W: Write + ?Sized>(&self, w: &mut W) -> fmt::Result {
        write_json_str(w, self)
    }

    fn write_value_json<W: Write + ?Sized>(&self, w: &mut W) -> fmt::Result {
        write_json_str(w, self)
    }

    #[inline]
    fn put_wire(&self, out: &mut ByteWriter<'_>) -> Option<()> {
        out.str(self)
    }
}

impl<E: CodeEnum> FieldValue for Code<'_, E> {
    fn write_wire<W: Write + ?Sized>(&self, w: &mut W) -> fmt::Result {
        w.write_str(self.code())
    }

    fn write_text_json<W: Write + ?Sized>(&self, w: &mut W) -> fmt::Result {
        write_json_str(w, self.code())
    }

    fn write_value_json<W: Write + ?Sized>(&self, w: &mut W) -> fmt::Result {
        write_json_str(w, self.id())
    }

    #[inline]
    fn put_wire(&self, out: &mut ByteWriter<'_>) -> Option<()> {
        out.str(self.code())
    }
}

impl<E: CodeEnum> FieldValue for CodeChars<'_, E> {
    fn write_wire<W: Write + ?Sized>(&self, w: &mut W) -> fmt::Result {
        w.write_str(self.as_str())
    }

    fn write_text_json<W: Write + ?Sized>(&self, w: &mut W) -> fmt::Result {
        write_json_str(w, self.as_str())
    }

    fn write_value_json<W: Write + ?Sized>(&self, w: &mut W) -> fmt::Result {
        w.write_char('[')?;
        for (i, code) in self.iter().enumerate() {
            if i > 0 {
                w.write_char(',')?;
            }
            write_json_str(w, code.id())?;
        }
        w.write_char(']')
    }

    #[inline]
    fn put_wire(&self, out: &mut ByteWriter<'_>) -> Option<()> {
        out.str(self.as_str())
    }
}

/// Writes the fields of a sentence, each after a `,` (a space in a text command), and keeps the
/// XOR checksum of every byte written (a character above U+00FF counts as its low byte, as
/// Latin-1 would). The text is gathered in a small buffer and handed to `out` in a few large
/// pieces: [`WireWriter::finish`] writes what is left.
pub struct WireWriter<'w, W: Write + ?Sized> {
    out: &'w mut W,
    sum: u8,
    separator: char,
    problems: &'w Problems<'w>,
    index: usize,
    staged: [u8; STAGE],
    len: usize,
}

/// Bytes a [`WireWriter`] gathers before it writes them out: most sentences in one piece.
const STAGE: usize = 128;

static NO_PROBLEMS: Problems<'static> = Problems::new();

impl<'w, W: Write + ?Sized> WireWriter<'w, W> {
    /// A writer of `,`-separated fields into `out`, checksum 0.
    pub fn new(out: &'w mut W) -> Self {
        Self { out, sum: 0, separator: ',', problems: &NO_PROBLEMS, index: 0, staged: [0; STAGE], len: 0 }
    }

    /// A writer of the space-separated words of a text command into `out`.
    pub fn words(out: &'w mut W) -> Self {
        Self { out, sum: 0, separator: ' ', problems: &NO_PROBLEMS, index: 0, staged: [0; STAGE], len: 0 }
    }

    /// The same writer, putting back the text of each field lenient parsing left empty (the
    /// fields are counted by the `,` written).
    pub fn with_problems(self, problems: &'w Problems<'w>) -> Self {
        Self { problems, ..self }
    }

    #[inline]
    fn put(&mut self, s: &str) -> fmt::Result {
        if !s.is_ascii() {
            self.sum = s.chars().fold(self.sum, |sum, c| sum ^ (c as u32 as u8));
            self.flush()?;
            return self.out.write_str(s);
        }
        self.put_ascii(s.as_bytes())
    }

    /// Appends ASCII bytes, adding them to the checksum.
    #[inline]
    fn put_ascii(&mut self, bytes: &[u8]) -> fmt::Result {
        let end = self.len + bytes.len();
        let Some(slots) = self.staged.get_mut(self.len..end) else {
            self.sum = bytes.iter().fold(self.sum, |sum, b| sum ^ b);
            self.flush()?;
            // Only ASCII bytes come here.
            return self.out.write_str(core::str::from_utf8(bytes).map_err(|_| fmt::Error)?);
        };
        let mut sum = self.sum;
        for (slot, &b) in slots.iter_mut().zip(bytes) {
            *slot = b;
            sum ^= b;
        }
        (self.sum, self.len) = (sum, end);
        Ok(())
    }

    /// Writes out what is gathered (whole strings only, so it is valid UTF-8).
    fn flush(&mut self) -> fmt::Result {
        let staged = core::str::from_utf8(&self.staged[..self.len]).map_err(|_| fmt::Error)?;
        self.len = 0;
        self.out.write_str(staged)
    }

    /// Writes out the rest of the text; the writer is done.
    pub fn finish(mut self) -> fmt::Result {
        self.flush()
    }

    /// The XOR of everything written so far.
    pub const fn checksum(&self) -> u8 {
        self.sum
    }

    /// Writes `,` and the field (`WIDTH` empty fields when it is `None`).
    pub fn field<T: FieldValue>(&mut self, value: &Option<T>) -> fmt::Result {
        let separator = self.separator;
        if let Some(value) = value.as_ref().filter(|_| self.problems.is_empty()) {
            let mut text = Ascii::new();
            text.push(separator as u8);
            if value.push_ascii(&mut text, separator as u8) {
                return self.put_ascii(text.as_bytes());
            }
        }
        self.write_char(separator)?;
        match value {
            Some(value) => value.write_wire_fields(self, separator),
            None => (1..T::WIDTH).try_for_each(|_| self.write_char(separator)),
        }
    }

    /// Writes `,` and a keyword (the word that picks the layout).
    pub fn keyword(&mut self, word: &str) -> fmt::Result {
        let separator = self.separator;
        self.write_char(separator)?;
        self.write_str(word)
    }

    /// Writes each value of a single-field group.
    pub fn fields<T: FieldValue>(&mut self, values: &[Option<T>]) -> fmt::Result {
        values.iter().try_for_each(|value| self.field(value))
    }

    /// Writes each value of a group of one text field.
    pub fn texts(&mut self, values: &Texts<'_>) -> fmt::Result {
        values.iter().try_for_each(|value| self.field(&value))
    }
}

impl<W: Write + ?Sized> Write for WireWriter<'_, W> {
    fn write_str(&mut self, s: &str) -> fmt::Result {
        if self.problems.is_empty() {
            return self.put(s);
        }
        let mut rest = s;
        while let Some(at) = rest.find(',') {
            self.put(&rest[..=at])?;
            rest = &rest[at + 1..];
            self.index += 1;
            if let Some(text) = self.problems.text_of(self.index) {
                self.put(text)?;
            }
        }
        self.put(rest)
    }
}

/// A sink that keeps nothing: with a [`WireWriter`] over it, computes a checksum.
#[derive(Clone, Copy, Debug, Default)]
pub struct Discard;

impl Write for Discard {
    fn write_str(&mut self, _: &str) -> fmt::Result {
        Ok(())
    }
}

/// Writes a whole sentence: `start`, the address, the fields written by `fields`, and the
/// checksum in the given style.
pub fn write_sentence<W: Write + ?Sized>(
    out: &mut W,
    start: &str,
    address: [&str; 2],
    checksum: super::Checksum,
    fields: impl FnOnce(&mut WireWriter<'_, W>) -> fmt::Result,
) -> fmt::Result {
    write_sentence_with(out, start, address, checksum, &NO_PROBLEMS, fields)
}

/// [`write_sentence`], putting back the text of each field lenient parsing left empty.
pub fn write_sentence_with<W: Write + ?Sized>(
    out: &mut W,
    start: &str,
    address: [&str; 2],
    checksum: super::Checksum,
    problems: &Problems<'_>,
    fields: impl FnOnce(&mut WireWriter<'_, W>) -> fmt::Result,
) -> fmt::Result {
    out.write_str(start)?;
    let mut w = WireWriter::new(out).with_problems(problems);
    w.write_str(address[0])?;
    w.write_str(address[1])?;
    fields(&mut w)?;
    let sum = w.checksum();
    w.finish()?;
    if let Some(([high, low], n)) = checksum.digits(sum) {
        let digits = [b'*', high, low];
        out.write_str(core::str::from_utf8(&digits[..=n]).map_err(|_| fmt::Error)?)?;
    } else if checksum == super::Checksum::Empty {
        out.write_char('*')?;
    }
    Ok(())
}

/// Puts a sentence's text into a byte buffer without the `fmt` machinery: what `Display` writes,
/// byte for byte, when it is ASCII (as every parsed `$` sentence is). Each piece is checked once
/// for room; a piece that is not ASCII, or a value built by hand that `Display` writes in an
/// unusual way, or the end of the buffer, makes it give up (`None`) and the caller writes the
/// text with `fmt` instead. As a `fmt::Write` it takes any text, as UTF-8 (that fallback).
#[derive(Debug)]
pub struct ByteWriter<'b> {
    buf: &'b mut [u8],
    len: usize,
}

/// Whether `value` has at most `count` decimal digits, `count` at most [`MAX_DIGITS`] (the most
/// [`ByteWriter`] writes in one run).
#[inline(always)]
fn fits_in_digits(value: u64, count: usize) -> bool {
    count <= MAX_DIGITS && value < POW10[count] as u64
}

/// "00", "01", … "99": two digits at a time.
const DIGIT_PAIRS: [[u8; 2]; 100] = {
    let mut pairs = [[0; 2]; 100];
    let mut i = 0;
    while i < 100 {
        pairs[i] = [b'0' + (i / 10) as u8, b'0' + (i % 10) as u8];
        i += 1;
    }
    pairs
};

/// Puts the last `count` decimal digits of `value` into `out`, ending at `end`, two at a time;
/// what is left of `value` (`None`: they do not fit before `end`).
#[inline(always)]
fn digits_ending_at(out: &mut [u8], end: usize, mut value: u64, count: usize) -> Option<u64> {
    let slots = out.get_mut(end.checked_sub(count)?..end)?;
    let mut pairs = slots.rchunks_exact_mut(2);
    for pair in pairs.by_ref() {
        pair.copy_from_slice(&DIGIT_PAIRS[(value % 100) as usize]);
        value /= 100;
    }
    if let [digit] = pairs.into_remainder() {
        *digit = b'0' + (value % 10) as u8;
        value /= 10;
    }
    Some(value)
}

/// The text of an integer written with one to three digits (the most common number of all) in
/// the low bytes of a word, and its length; `None` for any other number.
#[inline(always)]
fn small_integer(number: Number) -> Option<(u32, usize)> {
    let value = number.digits as u64; // a negative one (built by hand) is refused below
    let plain = number.scale == 0 && !number.point && number.sign == Sign::Implicit;
    if !plain || value >= 1000 || number.width.wrapping_sub(1) >= 3 {
        return None;
    }
    let len = usize::from(number.width).max(1 + usize::from(value >= 10) + usize::from(value >= 100));
    // Shifted so that the first `len` bytes hold the last `len` digits.
    Some((THREE_DIGITS[value as usize] >> (8 * (3 - len)), len))
}

/// 0 to 999 in three digits, in the low bytes of a word ("007" is `0x37_30_30`): a table rather
/// than three divisions, for the numbers most written.
const THREE_DIGITS: [u32; 1000] = {
    let mut table = [0; 1000];
    let mut i = 0;
    while i < 1000 {
        table[i] = 0x30_3030 | (i / 100) as u32 | ((i / 10 % 10) << 8) as u32 | ((i % 10) << 16) as u32;
        i += 1;
    }
    table
};

impl<'b> ByteWriter<'b> {
    /// A writer into `buf`, from its start.
    pub fn new(buf: &'b mut [u8]) -> Self {
        Self { buf, len: 0 }
    }

    /// The bytes written so far.
    pub const fn len(&self) -> usize {
        self.len
    }

    /// Whether nothing was written yet.
    pub const fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// The next `N` bytes of the buffer, to fill: one check for a whole field.
    #[inline(always)]
    fn room<const N: usize>(&mut self) -> Option<&mut [u8; N]> {
        let end = self.len.checked_add(N)?;
        self.buf.get_mut(self.len..end)?.try_into().ok()
    }

    /// Bytes already known to be ASCII.
    #[inline(always)]
    fn put(&mut self, bytes: &[u8]) -> Option<()> {
        let end = self.len.checked_add(bytes.len())?;
        self.buf.get_mut(self.len..end)?.copy_from_slice(bytes);
        self.len = end;
        Some(())
    }

    /// ASCII text (`None` for any other).
    #[inline]
    pub fn str(&mut self, text: &str) -> Option<()> {
        if !text.is_ascii() {
            return None;
        }
        self.put(text.as_bytes())
    }

    /// A number as [`Number`]'s `Display` writes it: sign, integer digits zero-padded to its
    /// width, point and fraction (`None` for one built by hand that it writes otherwise). The
    /// most common of all, a [`small_integer`], is put here without a branch; any other by
    /// [`ByteWriter::any_number`], out of line.
    #[inline]
    pub fn number(&mut self, number: Number) -> Option<()> {
        let Some((text, len)) = small_integer(number) else {
            return self.any_number(number);
        };
        *self.room::<4>()? = text.to_le_bytes();
        self.len += len;
        Some(())
    }

    /// `,` and a number: a small integer's text in the same word as its comma.
    #[inline]
    pub fn comma_number(&mut self, number: Number) -> Option<()> {
        let Some((text, len)) = small_integer(number) else {
            self.put(b",")?;
            return self.any_number(number);
        };
        *self.room::<4>()? = (u32::from(b',') | text << 8).to_le_bytes();
        self.len += 1 + len;
        Some(())
    }

    /// [`ByteWriter::number`] for any number.
    #[inline(never)]
    fn any_number(&mut self, number: Number) -> Option<()> {
        let (width, scale) = (usize::from(number.width), usize::from(number.scale));
        let count = width + scale;
        let digits = u64::try_from(number.digits).ok()?;
        if !fits_in_digits(digits, count) || (scale > 0 && !number.point) {
            return None;
        }
        let room = self.room::<24>()?;
        let at = usize::from(number.sign != Sign::Implicit);
        room[0] = if number.sign == Sign::Minus { b'-' } else { b'+' };
        let point = at + width;
        let end = point + usize::from(number.point) + scale;
        let whole = digits_ending_at(room, end, digits, scale)?;
        if number.point {
            room[point] = b'.';
        }
        digits_ending_at(room, point, whole, width)?;
        self.len += end;
        Some(())
    }

    /// `value` in `count` decimal digits (it has no more).
    #[inline(always)]
    fn digits(&mut self, value: u64, count: usize) -> Option<()> {
        digits_ending_at(self.room::<20>()?, count, value, count)?;
        self.len += count;
        Some(())
    }

    /// Two digits a part, as times and dates are written (`None` for a part above 99, only in
    /// a value built by hand).
    #[inline]
    pub fn two_digit_parts(&mut self, parts: [u8; 3]) -> Option<()> {
        let room = self.room::<6>()?;
        for (pair, part) in room.chunks_exact_mut(2).zip(parts) {
            if part > 99 {
                return None;
            }
            pair[0] = b'0' + part / 10;
            pair[1] = b'0' + part % 10;
        }
        self.len += 6;
        Some(())
    }

    /// A time as [`Time`]'s `Display` writes it: `hhmmss`, and the point and fraction digits.
    #[inline]
    pub fn time(&mut self, time: Time) -> Option<()> {
        self.two_digit_parts([time.hour, time.minute, time.second])?;
        if !time.point {
            return Some(());
        }
        let count = usize::from(time.fraction_digits);
        if !fits_in_digits(u64::from(time.fraction), count) {
            return None;
        }
        self.put(b".")?;
        self.digits(u64::from(time.fraction), count)
    }

    /// A latitude or longitude as [`Coordinate`]'s `Display` writes it: degrees zero-padded to
    /// their digits, minutes, `,` and the hemisphere.
    #[inline]
    pub fn coordinate(&mut self, coordinate: Coordinate) -> Option<()> {
        let count = usize::from(coordinate.degree_digits);
        if !fits_in_digits(u64::from(coordinate.degrees), count) || !coordinate.hemisphere.is_ascii() {
            return None;
        }
        self.digits(u64::from(coordinate.degrees), count)?;
        self.number(coordinate.minutes)?;
        self.put(&[b',', coordinate.hemisphere as u8])
    }

    /// A hex number as [`Hex`]'s `Display` writes it: its digits, zero-padded to its width.
    #[inline]
    pub fn hex(&mut self, hex: Hex) -> Option<()> {
        let needed = (64 - hex.value.leading_zeros()).div_ceil(4).max(1) as usize;
        let count = needed.max(usize::from(hex.digits));
        let room = self.room::<32>()?;
        let table = if hex.lower { b"0123456789abcdef" } else { b"0123456789ABCDEF" };
        let mut value = hex.value;
        for slot in room.get_mut(..count)?.iter_mut().rev() {
            *slot = table[(value & 15) as usize];
            value >>= 4;
        }
        self.len += count;
        Some(())
    }

    /// `,` and a field (`WIDTH` empty fields when it is `None`).
    #[inline]
    pub fn field<T: FieldValue>(&mut self, value: &Option<T>) -> Option<()> {
        match value {
            Some(value) => value.put_field(self),
            None if T::WIDTH == 2 => self.put(b",,"),
            None => self.put(b","),
        }
    }

    /// `,` and a keyword.
    #[inline]
    pub fn keyword(&mut self, word: &str) -> Option<()> {
        self.put(b",")?;
        self.str(word)
    }

    /// Each value of a single-field group.
    #[inline]
    pub fn fields<T: FieldValue>(&mut self, values: &[Option<T>]) -> Option<()> {
        values.iter().try_for_each(|value| self.field(value))
    }

    /// Each value of a group of one text field (as received in one piece, when lenient parsing
    /// left none of them empty).
    pub fn texts(&mut self, values: &Texts<'_>) -> Option<()> {
        if values.blanks().is_empty() && !values.is_empty() && values.separator() == b',' {
            self.put(b",")?;
            return self.put(values.as_bytes());
        }
        values.iter().try_for_each(|value| self.field(&value))
    }

    /// Ends a sentence written from its start character on: `*` and the XOR of everything after
    /// that character, in the checksum's style. The sentence's length.
    #[inline]
    pub fn finish(mut self, checksum: Checksum) -> Option<usize> {
        let sum = frame::checksum(self.buf.get(1..self.len)?);
        match checksum.digits(sum) {
            Some(([high, low], 2)) => self.put(&[b'*', high, low])?,
            Some(([digit, _], _)) => self.put(&[b'*', digit])?,
            None if checksum == Checksum::Empty => self.put(b"*")?,
            None => {}
        }
        Some(self.len)
    }
}

impl Write for ByteWriter<'_> {
    /// Any text, as UTF-8 (the fallback of the byte writers: text with characters outside ASCII).
    fn write_str(&mut self, s: &str) -> fmt::Result {
        self.put(s.as_bytes()).ok_or(fmt::Error)
    }
}

/// Writes into a byte buffer, each character as one byte (its low byte, as Latin-1 would), and
/// counts the bytes needed even past the end of the buffer.
pub struct Latin1Bytes<'b> {
    buf: &'b mut [u8],
    needed: usize,
}

impl<'b> Latin1Bytes<'b> {
    /// A writer into `buf`.
    pub fn new(buf: &'b mut [u8]) -> Self {
        Self { buf, needed: 0 }
    }

    /// The bytes written so far, those that did not fit included.
    pub const fn needed(&self) -> usize {
        self.needed
    }
}

impl Write for Latin1Bytes<'_> {
    #[inline]
    fn write_str(&mut self, s: &str) -> fmt::Result {
        let end = self.needed + s.len();
        if s.is_ascii() {
            if let Some(slots) = self.buf.get_mut(self.needed..end) {
                slots.copy_from_slice(s.as_bytes());
            }
            self.needed = end;
            return Ok(());
        }
        for c in s.chars() {
            if let Some(slot) = self.buf.get_mut(self.needed) {
                *slot = c as u32 as u8;
            }
            self.needed += 1;
        }
        Ok(())
    }
}

/// Compares what is written with a text, ignoring the case of ASCII letters: fails as soon as
/// they differ; [`SameUpper::finished`] tells whether all of the text was matched.
pub struct SameUpper<'r> {
    rest: core::str::Chars<'r>,
}

impl<'r> SameUpper<'r> {
    /// A comparison with `text`.
    pub fn new(text: &'r str) -> Self {
        Self { rest: text.chars() }
    }

    /// Whether everything written so far equals the whole text.
    pub fn finished(&self) -> bool {
        self.rest.clone().next().is_none()
    }
}

impl Write for SameUpper<'_> {
    fn write_str(&mut self, s: &str) -> fmt::Result {
        for c in s.chars() {
            match self.rest.next() {
                Some(r) if r.eq_ignore_ascii_case(&c) => {}
                _ => return Err(fmt::Error),
            }
        }
        Ok(())
    }
}

/// The lossless `fields` members of a text command as received (inside the object's braces):
/// its words after the command word, one per field of `words` (id, wire fields), `null` when
/// empty; a latitude or longitude takes two words, an array (`null` when both are empty).
pub fn write_words_json<W: Write + ?Sized>(out: &mut W, line: &str, words: &[(&str, usize)]) -> fmt::Result {
    let mut rest = line.split(' ').skip(1);
    for (i, &(id, width)) in words.iter().enumerate() {
        let Some(first) = rest.next() else {
            break;
        };
        if i > 0 {
            out.write_char(',')?;
        }
        write!(out, "\"{id}\":")?;
        if width == 2 {
            let second = rest.next().unwrap_or("");
            if first.is_empty() && second.is_empty() {
                out.write_str("null")?;
            } else {
                out.write_char('[')?;
                write_json_str(out, first)?;
                out.write_char(',')?;
                write_json_str(out, second)?;
                out.write_char(']')?;
            }
        } else if first.is_empty() {
            out.write_str("null")?;
        } else {
            write_json_str(out, first)?;
        }
    }
    Ok(())
}

/// The `fields` object of the tools' JSON: writes `{`, then `"key":value` members, and `}` when
/// finished.
pub struct JsonFields<'w, W: Write + ?Sized> {
    out: &'w mut W,
    values: bool,
    first: bool,
}

impl<'w, W: Write + ?Sized> JsonFields<'w, W> {
    /// Starts an object; `values` picks the decoded form of `decode --values`.
    pub fn begin(out: &'w mut W, values: bool) -> Result<Self, fmt::Error> {
        out.write_char('{')?;
        Ok(Self { out, values, first: true })
    }

    /// Closes the object.
    pub fn end(self) -> fmt::Result {
        self.out.write_char('}')
    }

    fn key(&mut self, key: &str) -> fmt::Result {
        if !self.first {
            self.out.write_char(',')?;
        }
        self.first = false;
        self.out.write_char('"')?;
        self.out.write_str(key)?;
        self.out.write_str("\":")
    }

    fn value<T: FieldValue>(&mut self, value: &Option<T>) -> fmt::Result {
        match value {
            None => self.out.write_str("null"),
            Some(v) if self.values => v.write_value_json(self.out),
            Some(v) => v.write_text_json(self.out),
        }
    }

    /// A field: `"key":value` (`null` when empty).
    pub fn field<T: FieldValue>(&mut self, key: &str, value: &Option<T>) -> fmt::Result {
        self.key(key)?;
        self.value(value)
    }

    /// A keyword: `"key":"WORD"` in both forms.
    pub fn keyword(&mut self, key: &str, word: &str) -> fmt::Result {
        self.key(key)?;
        write_json_str(self.out, word)
    }

    /// A group of one field: an array of bare values.
    pub fn values<T: FieldValue + Copy>(&mut self, key: &str, values: &Entries<'_, Option<T>>) -> fmt::Result {
        self.key(key)?;
        self.out.write_char('[')?;
        for (i, value) in values.iter().enumerate() {
            if i > 0 {
                self.out.write_char(',')?;
            }
            self.value(&value)?;
        }
        self.out.write_char(']')
    }

    /// A group of one text field: an array of strings (`null` when empty).
    pub fn texts(&mut self, key: &str, values: &Texts<'_>) -> fmt::Result {
        self.key(key)?;
        self.out.write_char('[')?;
        for (i, value) in values.iter().enumerate() {
            if i > 0 {
                self.out.write_char(',')?;
            }
            self.value(&value)?;
        }
        self.out.write_char(']')
    }

    /// A group of several fields: an array of objects, each written by `entry`.
    pub fn entries<T: Copy + Default>(
        &mut self,
        key: &str,
        entries: &Entries<'_, T>,
        mut entry: impl FnMut(&T, &mut JsonFields<'_, W>) -> fmt::Result,
    ) -> fmt::Result {
        self.key(key)?;
        self.out.write_char('[')?;
        for (i, item) in entries.iter().enumerate() {
            if i > 0 {
                self.out.write_char(',')?;
            }
            let mut object = JsonFields::begin(&mut *self.out, self.values)?;
            entry(&item, &mut object)?;
            object.end()?;
        }
        self.out.write_char(']')
    }
}

/// Writes everything through JSON string escaping (without the quotes).
pub struct JsonEscape<'w, W: Write + ?Sized>(pub &'w mut W);

impl<W: Write + ?Sized> Write for JsonEscape<'_, W> {
    fn write_str(&mut self, s: &str) -> fmt::Result {
        let plain = |b: u8| (0x20..=0x7e).contains(&b) && b != b'"' && b != b'\\';
        if s.bytes().all(plain) {
            return self.0.write_str(s);
        }
        for c in s.chars() {
            match c {
                '"' => self.0.write_str("\\\"")?,
                '\\' => self.0.write_str("\\\\")?,
                ' '..='~' => self.0.write_char(c)?,
                _ => write!(self.0, "\\u00{:02x}", c as u32 & 0xff)?,
            }
        }
        Ok(())
    }
}

/// Writes a JSON string: `"` and `\` escaped, every character outside 0x20-0x7E as `\u00hh`
/// (its low byte).
pub fn write_json_str<W: Write + ?Sized>(w: &mut W, text: &str) -> fmt::Result {
    w.write_char('"')?;
    JsonEscape(&mut *w).write_str(text)?;
    w.write_char('"')
}

/// Writes one character as a JSON string.
pub fn write_json_char<W: Write + ?Sized>(w: &mut W, c: char) -> fmt::Result {
    let mut buf = [0u8; 4];
    write_json_str(w, c.encode_utf8(&mut buf))
}

/// Writes the `Display` text of `value` as a JSON string.
pub fn write_json_display<W: Write + ?Sized>(w: &mut W, value: &dyn fmt::Display) -> fmt::Result {
    w.write_char('"')?;
    write!(JsonEscape(&mut *w), "{value}")?;
    w.write_char('"')
}

/// Where the fields of a layout go, in wire order: the wire ([`WireWriter`], or [`ByteWriter`]
/// without `fmt`) or the `fields` object of the tools' JSON ([`JsonFields`]). Each layout and
/// group entry writes itself once, into any of them (`Layout::visit`, [`Entry::visit`]); the
/// wire writers pass the keys over.
pub trait FieldSink {
    /// A field under its key.
    fn field<T: FieldValue>(&mut self, key: &str, value: &Option<T>) -> fmt::Result;
    /// A keyword (the word that picks the layout).
    fn keyword(&mut self, key: &str, word: &str) -> fmt::Result;
    /// The values of a group of one field.
    fn values<T: FieldValue + Copy>(&mut self, key: &str, values: &Entries<'_, Option<T>>) -> fmt::Result;
    /// The values of a group of one text field.
    fn texts(&mut self, key: &str, values: &Texts<'_>) -> fmt::Result;
    /// The entries of a group of several fields.
    fn entries<T: Entry + Copy + Default>(&mut self, key: &str, entries: &Entries<'_, T>) -> fmt::Result;
}

/// One entry of a repeated group of several fields (a struct generated from the spec).
pub trait Entry {
    /// Writes the entry's fields into `sink`.
    fn visit<S: FieldSink>(&self, sink: &mut S) -> fmt::Result;
}

impl<W: Write + ?Sized> FieldSink for WireWriter<'_, W> {
    #[inline]
    fn field<T: FieldValue>(&mut self, _: &str, value: &Option<T>) -> fmt::Result {
        WireWriter::field(self, value)
    }

    fn keyword(&mut self, _: &str, word: &str) -> fmt::Result {
        WireWriter::keyword(self, word)
    }

    fn values<T: FieldValue + Copy>(&mut self, _: &str, values: &Entries<'_, Option<T>>) -> fmt::Result {
        match values.wire() {
            Some(wire) => WireWriter::texts(self, wire),
            None => self.fields(values.items()),
        }
    }

    fn texts(&mut self, _: &str, values: &Texts<'_>) -> fmt::Result {
        WireWriter::texts(self, values)
    }

    fn entries<T: Entry + Copy + Default>(&mut self, _: &str, entries: &Entries<'_, T>) -> fmt::Result {
        match entries.wire() {
            Some(wire) => WireWriter::texts(self, wire),
            None => entries.items().iter().try_for_each(|entry| entry.visit(self)),
        }
    }
}

/// `Err` where the byte writer gives up (the text is not ASCII, or the buffer is full).
impl FieldSink for ByteWriter<'_> {
    #[inline]
    fn field<T: FieldValue>(&mut self, _: &str, value: &Option<T>) -> fmt::Result {
        ByteWriter::field(self, value).ok_or(fmt::Error)
    }

    #[inline]
    fn keyword(&mut self, _: &str, word: &str) -> fmt::Result {
        ByteWriter::keyword(self, word).ok_or(fmt::Error)
    }

    #[inline]
    fn values<T: FieldValue + Copy>(&mut self, _: &str, values: &Entries<'_, Option<T>>) -> fmt::Result {
        match values.wire() {
            Some(wire) => ByteWriter::texts(self, wire),
            None => self.fields(values.items()),
        }
        .ok_or(fmt::Error)
    }

    fn texts(&mut self, _: &str, values: &Texts<'_>) -> fmt::Result {
        ByteWriter::texts(self, values).ok_or(fmt::Error)
    }

    #[inline]
    fn entries<T: Entry + Copy + Default>(&mut self, _: &str, entries: &Entries<'_, T>) -> fmt::Result {
        match entries.wire() {
            Some(wire) => ByteWriter::texts(self, wire).ok_or(fmt::Error),
            None => entries.items().iter().try_for_each(|entry| entry.visit(self)),
        }
    }
}

impl<W: Write + ?Sized> FieldSink for JsonFields<'_, W> {
    fn field<T: FieldValue>(&mut self, key: &str, value: &Option<T>) -> fmt::Result {
        JsonFields::field(self, key, value)
    }

    fn keyword(&mut self, key: &str, word: &str) -> fmt::Result {
        JsonFields::keyword(self, key, word)
    }

    fn values<T: FieldValue + Copy>(&mut self, key: &str, values: &Entries<'_, Option<T>>) -> fmt::Result {
        JsonFields::values(self, key, values)
    }

    fn texts(&mut self, key: &str, values: &Texts<'_>) -> fmt::Result {
        JsonFields::texts(self, key, values)
    }

    fn entries<T: Entry + Copy + Default>(&mut self, key: &str, entries: &Entries<'_, T>) -> fmt::Result {
        JsonFields::entries(self, key, entries, |entry, object| entry.visit(object))
    }
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;

    /// A `fmt::Write` into a fixed buffer, so that the tests need no allocator.
    pub(crate) struct Buf<'b> {
        data: &'b mut [u8],
        len: usize,
    }

    impl<'b> Buf<'b> {
        pub(crate) fn new(data: &'b mut [u8]) -> Self {
            Self { data, len: 0 }
        }

        pub(crate) fn as_str(&self) -> &str {
            core::str::from_utf8(&self.data[..self.len]).unwrap()
        }
    }

    impl Write for Buf<'_> {
        fn write_str(&mut self, s: &str) -> fmt::Result {
            let end = self.len + s.len();
            self.data.get_mut(self.len..end).ok_or(fmt::Error)?.copy_from_slice(s.as_bytes());
            self.len = end;
            Ok(())
        }
    }

    #[test]
    fn json_strings_escape_quotes_backslashes_and_other_bytes() {
        let mut out = [0u8; 64];
        let mut w = Buf::new(&mut out);
        write_json_str(&mut w, "a\"b\\c\u{7f}\u{e9}\u{1f600}").unwrap();
        assert_eq!(w.as_str(), r#""a\"b\\c\u007f\u00e9\u0000""#);
    }

    #[test]
    fn numbers_as_json_values_drop_leading_and_trailing_zeros() {
        for (text, json) in [("00188.860", "188.86"), ("-0.0", "0"), ("-2", "-2"), (".5", "0.5"), ("5.", "5")] {
            let mut out = [0u8; 32];
            let mut w = Buf::new(&mut out);
            Number::parse(text, false).unwrap().write_json_value(&mut w).unwrap();
            assert_eq!(w.as_str(), json);
        }
    }

    #[test]
    fn the_byte_writer_puts_numbers_back_as_written() {
        let texts =
            ["0", "00", "000", "7", "07", "007", "0007", "99", "099", "359", "999", "1000", "-5", "+5", "5.", ".5"];
        for text in texts.iter().chain(&["0.0", "-0.0", "00188.860", "123456789012.345678", "-.5"]) {
            let number = Number::parse(text, false).unwrap();
            let mut out = [0u8; 64];
            let mut w = ByteWriter::new(&mut out);
            w.number(number).unwrap();
            w.comma_number(number).unwrap();
            let (n, len) = (text.len(), w.len());
            assert_eq!((&out[..n], out[n], &out[n + 1..len]), (text.as_bytes(), b',', text.as_bytes()), "{text}");
        }
        // Refused, for the fmt writer to write: a number built by hand that Display writes
        // otherwise, and a buffer too small.
        let whole = Number { digits: 1234, scale: 0, width: 2, sign: Sign::Implicit, point: false };
        assert_eq!(ByteWriter::new(&mut [0; 40]).number(whole), None);
        let negative = Number { digits: -5, ..whole };
        assert_eq!(ByteWriter::new(&mut [0; 40]).number(negative), None);
        assert_eq!(ByteWriter::new(&mut [0; 3]).number(Number::parse("5", true).unwrap()), None);
    }
}
