//! AIS payloads: the six-bit armoring of `!AIVDM`/`!AIVDO`, and a bit reader and writer over it.
//!
//! The Rust side of the Python runtime's ais.py, with its rules and error messages. Decoding reads
//! the armored characters in place and allocates nothing: six-bit text and binary data are views
//! of the payload's bits. Encoding writes into a fixed buffer. What a decoder keeps as sent (spare
//! bits, text after its `@` padding, bits after the layout, the values of the fill bits) is read
//! as views and written back bit for bit. Facts from ITU-R M.1371-5 (armoring: annex 8, table 47)
//! and gpsd's "AIVDM/AIVDO protocol decoding".
//!
//! The same reader and writer read and write RTCM 3 payloads (bytes, eight bits each: see
//! [`Payload::bytes`], [`BitWriter::bytes`]); their errors then name `RTCM3` and the message number.

use core::fmt;

/// The characters of six-bit text, by their value (`@`, value 0, pads a text to its width).
pub const SIXBIT_TEXT: &[u8; 64] = b"@ABCDEFGHIJKLMNOPQRSTUVWXYZ[\\]^_ !\"#$%&'()*+,-./0123456789:;<=>?";

/// The most bits an encoded message holds: five slots of 256 bits, more than any message's data
/// and the bits some transmitters send after it.
pub const MAX_BITS: usize = 5 * 256;

/// The armored characters an AIS payload being written holds.
pub const MAX_CHARS: usize = MAX_BITS.div_ceil(6);

/// The six bits an armored payload character carries (`0`-`W` are 0-39, `` ` ``-`w` 40-63).
pub const fn armor_value(ch: u8) -> Option<u8> {
    match ch {
        b'0'..=b'W' => Some(ch - 48),
        b'`'..=b'w' => Some(ch - 56),
        _ => None,
    }
}

/// The armored character of six bits (`value` below 64).
pub const fn armor_char(value: u8) -> u8 {
    if value < 40 {
        value + 48
    } else {
        value + 56
    }
}

/// The six-bit text value of a character, None for one six-bit text cannot carry.
pub const fn text_value(ch: u8) -> Option<u8> {
    match ch {
        b'@'..=b'_' => Some(ch - 64),
        b' '..=b'?' => Some(ch),
        _ => None,
    }
}

/// What is wrong with a payload or a value to encode (runtime/contract.yaml's `payload_kinds`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum AisErrorKind {
    /// A character outside the armoring, or fill bits outside 0-5.
    BadArmor,
    /// The payload ends before a field's last bit.
    ShortPayload,
    /// A message type the spec does not describe.
    UnknownMessage,
    /// A value to encode its field cannot hold.
    BadValue,
}

impl AisErrorKind {
    /// The kind as the JSON contract names it.
    pub const fn as_str(self) -> &'static str {
        match self {
            AisErrorKind::BadArmor => "bad_armor",
            AisErrorKind::ShortPayload => "short_payload",
            AisErrorKind::UnknownMessage => "unknown_message",
            AisErrorKind::BadValue => "bad_value",
        }
    }
}

/// The facts an error message is written from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Detail {
    Character { ch: u8, offset: usize },
    FillBits(u8),
    Short { offset: usize, width: usize, length: usize },
    UnknownType(u8),
    TooWide { raw: i64, width: usize },
    NotText(u8),
    TooLong,
    FewEntries { min: usize, width: usize, left: usize },
    CountedEntries { count: usize, width: usize, left: usize },
    TooMany { count: usize, max: usize },
    Units { units: usize, bits: usize },
    Said { len: usize, count: usize },
    Width { width: usize, bits: usize, text: bool },
    Missing,
}

/// An AIS payload error (or an RTCM 3 payload's): its kind, the message type (number) and field
/// it concerns when known.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct AisError {
    /// What is wrong.
    pub kind: AisErrorKind,
    /// The message type (an RTCM 3 message number), once read.
    pub message_type: Option<u16>,
    /// The field being read or written.
    pub field: Option<&'static str>,
    detail: Detail,
    rtcm3: bool,
}

impl AisError {
    fn new(kind: AisErrorKind, message_type: Option<u16>, field: Option<&'static str>, detail: Detail) -> Self {
        AisError { kind, message_type, field, detail, rtcm3: false }
    }

    fn of(mut self, rtcm3: bool) -> Self {
        self.rtcm3 = rtcm3;
        self
    }

    /// Writes the error's address: `AIS type 5` (`AIS` before the type is read), `RTCM3 1005`.
    fn address<W: fmt::Write + ?Sized>(&self, w: &mut W) -> fmt::Result {
        w.write_str(if self.rtcm3 { "RTCM3" } else { "AIS" })?;
        match self.message_type {
            Some(t) if self.rtcm3 => write!(w, " {t}"),
            Some(t) => write!(w, " type {t}"),
            None => Ok(()),
        }
    }
}

impl AisError {
    /// The error's message alone (`"fill bits are 0-5 (none for an empty payload), not 7"`).
    pub fn message(&self) -> impl fmt::Display + '_ {
        AisMessage(self)
    }

    /// The error as the tools' JSON error object: its kind, `AIS type N` (`AIS` before the type
    /// is read) as its address, the field as its name, and its message.
    pub fn write_json<W: fmt::Write + ?Sized>(&self, w: &mut W) -> fmt::Result {
        write!(w, "{{\"kind\":\"{}\",\"address\":\"", self.kind.as_str())?;
        self.address(w)?;
        w.write_str("\",\"field\":null,\"name\":")?;
        match self.field {
            Some(field) => write!(w, "\"{field}\"")?,
            None => w.write_str("null")?,
        }
        w.write_str(",\"message\":")?;
        super::write::write_json_display(w, &self.message())?;
        w.write_char('}')
    }
}

impl fmt::Display for AisError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}: ", self.kind.as_str())?;
        self.address(f)?;
        write!(f, ": {}", self.message())
    }
}

struct AisMessage<'e>(&'e AisError);

impl fmt::Display for AisMessage<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let field = self.0.field.unwrap_or("payload");
        match self.0.detail {
            Detail::Character { ch, offset } => {
                write!(f, "character '{}' at offset {offset} is not six-bit armoring", char::from(ch))
            }
            Detail::FillBits(n) => write!(f, "fill bits are 0-5 (none for an empty payload), not {n}"),
            Detail::Short { offset, width, length } => {
                write!(f, "{field} needs bits {offset}-{}, the payload has {length}", offset + width - 1)
            }
            Detail::UnknownType(t) => write!(f, "message type {t} is not one the spec describes"),
            Detail::TooWide { raw, width } => write!(f, "{field} takes a raw value of {width} bits, not {raw}"),
            Detail::NotText(ch) => write!(f, "{field} takes six-bit text characters, not '{}'", ch.escape_ascii()),
            Detail::TooLong if self.0.rtcm3 => write!(f, "{field} does not fit in a payload of 1023 bytes"),
            Detail::TooLong => write!(f, "{field} does not fit in a message of {MAX_BITS} bits"),
            Detail::FewEntries { min, width, left } => {
                write!(f, "{field} needs at least {min} entries of {width} bits, {left} bits left")
            }
            Detail::CountedEntries { count, width, left } => {
                write!(f, "{field} needs {count} entries of {width} bits, {left} bits left")
            }
            Detail::TooMany { count, max } => write!(f, "{field} has {count} entries, at most {max}"),
            Detail::Missing => write!(f, "{field} is missing: the message's case of its layout has it"),
            Detail::Width { width, bits, text: true } => {
                write!(f, "{field} takes {} six-bit text characters, not {}", width / 6, bits / 6)
            }
            Detail::Width { width, bits, text: false } => write!(f, "{field} takes {width} bits, not {bits}"),
            Detail::Said { len, count } => write!(f, "{field} has {len} entries, its masks' bits set say {count}"),
            Detail::Units { units, bits } => {
                write!(f, "{field} takes {units} units, as its count says, not {bits} bits")
            }
        }
    }
}

#[cfg(feature = "std")]
impl std::error::Error for AisError {}

/// An armored payload whose characters and fill bits are checked: its bits, read in place.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Payload<'a> {
    armored: &'a [u8],
    fill_bits: u8,
    /// The bits of a unit: 6 (an armored character), 8 (a byte of an RTCM 3 payload).
    unit: u8,
}

impl<'a> Payload<'a> {
    /// The payload of a sentence (or of its fragments joined) and its fill bits.
    pub fn new(armored: &'a [u8], fill_bits: u8) -> Result<Self, AisError> {
        if fill_bits > 5 || fill_bits > 0 && armored.is_empty() {
            return Err(AisError::new(AisErrorKind::BadArmor, None, None, Detail::FillBits(fill_bits)));
        }
        if let Some(offset) = armored.iter().position(|&ch| armor_value(ch).is_none()) {
            let ch = armored[offset];
            return Err(AisError::new(AisErrorKind::BadArmor, None, None, Detail::Character { ch, offset }));
        }
        Ok(Payload { armored, fill_bits, unit: 6 })
    }

    /// The bits of an RTCM 3 payload: its bytes, eight bits each, most significant first.
    pub fn bytes(data: &'a [u8]) -> Self {
        Payload { armored: data, fill_bits: 0, unit: 8 }
    }

    /// The message's bits: the characters' bits but the fill bits.
    pub fn bit_len(&self) -> usize {
        self.armored.len() * usize::from(self.unit) - usize::from(self.fill_bits)
    }

    /// The number of fill bits.
    pub fn fill_bits(&self) -> u8 {
        self.fill_bits
    }

    /// The values of the fill bits, as sent (some transmitters send them non-zero).
    pub fn padding(&self) -> u8 {
        self.armored.last().map_or(0, |&ch| sixbits(ch) & ((1 << self.fill_bits) - 1))
    }

    /// A reader from the first bit.
    pub fn reader(&self) -> BitReader<'a> {
        BitReader { payload: *self, pos: 0, end: self.bit_len(), message_type: None }
    }

    /// The `width` bits (at most 64) at `offset`, most significant first; the caller keeps them
    /// inside the characters.
    fn raw(&self, offset: usize, width: usize) -> u64 {
        let mut raw = 0u64;
        let (mut pos, end) = (offset, offset + width);
        if self.unit == 8 {
            while pos < end {
                let in_byte = pos % 8;
                let take = (8 - in_byte).min(end - pos);
                let chunk = (self.armored[pos / 8] >> (8 - in_byte - take)) & ((1u16 << take) - 1) as u8;
                raw = raw << take | u64::from(chunk);
                pos += take;
            }
            return raw;
        }
        while pos < end {
            let in_char = pos % 6;
            let take = (6 - in_char).min(end - pos);
            let chunk = (sixbits(self.armored[pos / 6]) >> (6 - in_char - take)) & ((1 << take) - 1);
            raw = raw << take | u64::from(chunk);
            pos += take;
        }
        raw
    }
}

/// The six bits of a character already checked.
fn sixbits(ch: u8) -> u8 {
    armor_value(ch).unwrap_or(0)
}

/// Bits of a payload kept as sent: binary data, spare bits, bits after a layout.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Bits<'a> {
    payload: Payload<'a>,
    offset: usize,
    len: usize,
}

impl<'a> Bits<'a> {
    /// How many bits.
    pub fn len(&self) -> usize {
        self.len
    }

    /// Whether there are none.
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// The `width` bits (at most 64) at `offset` of these bits, most significant first; the
    /// caller keeps them inside.
    pub fn get(&self, offset: usize, width: usize) -> u64 {
        debug_assert!(offset + width <= self.len && width <= 64);
        self.payload.raw(self.offset + offset, width)
    }

    /// How many of the bits are set (an RTCM 3 MSM's cells, in its cell mask).
    pub fn count_ones(&self) -> u32 {
        (0..self.len).step_by(64).map(|start| self.get(start, (self.len - start).min(64)).count_ones()).sum()
    }

    /// The bits from the first, most significant first.
    pub fn iter(&self) -> impl Iterator<Item = bool> + 'a {
        let (payload, offset) = (self.payload, self.offset);
        (0..self.len).map(move |i| payload.raw(offset + i, 1) == 1)
    }

    /// A reader of these bits alone (an application's layout in a message's data).
    pub fn reader(&self) -> BitReader<'a> {
        BitReader { payload: self.payload, pos: self.offset, end: self.offset + self.len, message_type: None }
    }

    /// The six-bit text these bits carry, whole characters only.
    pub fn text(&self) -> SixBitText<'a> {
        SixBitText { bits: Bits { len: self.len / 6 * 6, ..*self } }
    }
}

/// The bits as the text of their values (`"0110"`), the form of the vectors' and the JSON's data.
impl fmt::Display for Bits<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        self.iter().try_for_each(|bit| f.write_str(if bit { "1" } else { "0" }))
    }
}

/// Six-bit text as sent, `@` padding and trailing spaces included.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct SixBitText<'a> {
    bits: Bits<'a>,
}

impl<'a> SixBitText<'a> {
    /// The characters.
    pub fn chars(&self) -> impl Iterator<Item = char> + 'a {
        let bits = self.bits;
        (0..bits.len / 6).map(move |i| char::from(SIXBIT_TEXT[bits.payload.raw(bits.offset + 6 * i, 6) as usize]))
    }

    /// The text up to its first `@`, trailing spaces left out: the name a station meant.
    pub fn trimmed(&self) -> impl Iterator<Item = char> + 'a {
        let shown = self.chars().take_while(|&ch| ch != '@');
        let end = shown.enumerate().filter(|&(_, ch)| ch != ' ').last().map_or(0, |(i, _)| i + 1);
        self.chars().take(end)
    }

    /// The bits it was read from.
    pub fn bits(&self) -> Bits<'a> {
        self.bits
    }

    /// Text of a message a program builds (a name, a call sign, a safety message), armored into
    /// `buf` (a byte a character). A field of fixed width takes exactly its characters: pad a
    /// shorter text with `@`, as transmitters do. Errors: a character six-bit text cannot carry
    /// (lower case, outside ASCII), a `buf` shorter than the text (bad_value).
    pub fn armor_into(text: &str, buf: &'a mut [u8]) -> Result<Self, AisError> {
        let error = |detail| AisError::new(AisErrorKind::BadValue, None, Some("text"), detail);
        let slots = buf.get_mut(..text.len()).ok_or(error(Detail::TooLong))?;
        for (slot, ch) in slots.iter_mut().zip(text.bytes()) {
            let value = text_value(ch).ok_or(error(Detail::NotText(ch)))?;
            *slot = armor_char(value);
        }
        let payload = Payload { armored: &buf[..text.len()], fill_bits: 0, unit: 6 };
        Ok(SixBitText { bits: Bits { payload, offset: 0, len: 6 * text.len() } })
    }
}

impl fmt::Display for SixBitText<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        self.chars().try_for_each(|ch| fmt::Write::write_char(f, ch))
    }
}

impl PartialEq<&str> for SixBitText<'_> {
    fn eq(&self, other: &&str) -> bool {
        self.chars().eq(other.chars())
    }
}

/// The bits of a payload read most significant first; errors name the message type (once
/// [`BitReader::set_message_type`] gave it) and the field read.
#[derive(Clone, Debug)]
pub struct BitReader<'a> {
    payload: Payload<'a>,
    pos: usize,
    end: usize,
    message_type: Option<u16>,
}

impl<'a> BitReader<'a> {
    /// The message type (an RTCM 3 message number) errors name from now on.
    pub fn set_message_type(&mut self, message_type: u16) {
        self.message_type = Some(message_type);
    }

    fn error(&self, kind: AisErrorKind, field: &'static str, detail: Detail) -> AisError {
        AisError::new(kind, self.message_type, Some(field), detail).of(self.payload.unit == 8)
    }

    /// The bits read so far.
    pub fn position(&self) -> usize {
        self.pos
    }

    /// The bits left.
    pub fn remaining(&self) -> usize {
        self.end - self.pos
    }

    /// How many entries of `width` bits a repeated group holds: as many as the bits left before
    /// the `after` bits of what follows it hold, at most `max`; too few for `min` is an error.
    pub fn entries(
        &self,
        min: usize,
        max: usize,
        width: usize,
        after: usize,
        field: &'static str,
    ) -> Result<usize, AisError> {
        let left = self.remaining();
        let count = max.min(left.saturating_sub(after) / width);
        if count < min {
            return Err(self.error(AisErrorKind::ShortPayload, field, Detail::FewEntries { min, width, left }));
        }
        Ok(count)
    }

    /// How many entries of `width` bits a group counted by a field or by mask bits holds: `count`,
    /// when the bits left hold them (else short_payload) and `max` holds them (else bad_value).
    pub fn counted(&self, count: usize, max: usize, width: usize, field: &'static str) -> Result<usize, AisError> {
        let left = self.remaining();
        if count.saturating_mul(width) > left {
            return Err(self.error(AisErrorKind::ShortPayload, field, Detail::CountedEntries { count, width, left }));
        }
        if count > max {
            return Err(self.error(AisErrorKind::BadValue, field, Detail::TooMany { count, max }));
        }
        Ok(count)
    }

    /// The bits from here to the end, as sent (the bits after a layout).
    pub fn rest(&mut self) -> Bits<'a> {
        let bits = Bits { payload: self.payload, offset: self.pos, len: self.remaining() };
        self.pos = self.end;
        bits
    }

    /// The error of a message type no layout describes.
    pub fn unknown_message(&self, message_type: u8) -> AisError {
        let detail = Detail::UnknownType(message_type);
        AisError::new(AisErrorKind::UnknownMessage, Some(message_type.into()), Some("message_type"), detail)
    }

    fn check(&self, offset: usize, width: usize, field: &'static str) -> Result<(), AisError> {
        let length = self.end;
        if offset + width > length {
            return Err(self.error(AisErrorKind::ShortPayload, field, Detail::Short { offset, width, length }));
        }
        Ok(())
    }

    /// The `width` bits (at most 64) at `offset` as an unsigned integer, without moving: a
    /// choice's selector further on.
    pub fn peek(&self, offset: usize, width: usize, field: &'static str) -> Result<u64, AisError> {
        debug_assert!(width <= 64);
        self.check(offset, width, field)?;
        Ok(self.payload.raw(offset, width))
    }

    /// The next `width` bits (at most 64), unsigned.
    pub fn take(&mut self, width: usize, field: &'static str) -> Result<u64, AisError> {
        let raw = self.peek(self.pos, width, field)?;
        self.pos += width;
        Ok(raw)
    }

    /// The next `width` bits (1 to 64), two's complement.
    pub fn take_signed(&mut self, width: usize, field: &'static str) -> Result<i64, AisError> {
        let raw = self.take(width, field)?;
        let unused = 64 - width as u32;
        Ok(((raw << unused) as i64) >> unused)
    }

    /// The next `width` bits (2 to 64), sign and magnitude (RTCM 3): the number, or its negative
    /// zero as the bits sent, `1 << (width - 1)`, a raw value no number has.
    pub fn take_smag(&mut self, width: usize, field: &'static str) -> Result<i64, AisError> {
        let raw = self.take(width, field)?;
        let sign = 1u64 << (width - 1);
        Ok(if raw & sign != 0 && raw != sign { -((raw & (sign - 1)) as i64) } else { raw as i64 })
    }

    /// The next `width` bits as a view.
    pub fn take_bits(&mut self, width: usize, field: &'static str) -> Result<Bits<'a>, AisError> {
        self.check(self.pos, width, field)?;
        let bits = Bits { payload: self.payload, offset: self.pos, len: width };
        self.pos += width;
        Ok(bits)
    }

    /// The next `chars` characters of six-bit text.
    pub fn take_text(&mut self, chars: usize, field: &'static str) -> Result<SixBitText<'a>, AisError> {
        Ok(SixBitText { bits: self.take_bits(6 * chars, field)? })
    }
}

/// A payload being written: fields go in most significant bit first. An AIS payload's
/// ([`BitWriter::new`]) units are armored characters, and [`BitWriter::finish`] pads the last one
/// with the fill bits; an RTCM 3 payload's ([`BitWriter::bytes`], `N` of them at most) are bytes.
#[derive(Clone, Debug)]
pub struct BitWriter<const N: usize = MAX_CHARS> {
    values: [u8; N],
    len: usize,
    message_type: Option<u16>,
    unit: u8,
}

impl<const N: usize> Default for BitWriter<N> {
    fn default() -> Self {
        BitWriter { values: [0; N], len: 0, message_type: None, unit: 6 }
    }
}

impl BitWriter {
    /// An empty AIS payload whose errors name `message_type`.
    pub fn new(message_type: u8) -> Self {
        BitWriter { message_type: Some(message_type.into()), ..BitWriter::default() }
    }

    /// The armored payload: the last character padded with `padding`, the values of the fill
    /// bits as sent (0 for a new message).
    pub fn finish(mut self, padding: u8) -> Result<Armored, AisError> {
        let fill_bits = ((6 - self.len % 6) % 6) as u8;
        if u64::from(padding) >> fill_bits != 0 {
            return Err(self.error("padding", Detail::TooWide { raw: i64::from(padding), width: fill_bits.into() }));
        }
        self.put_raw(u64::from(padding), fill_bits.into(), "padding")?;
        let chars = self.len / 6;
        self.values[..chars].iter_mut().for_each(|value| *value = armor_char(*value));
        Ok(Armored { chars: self.values, len: chars, fill_bits })
    }
}

impl<const N: usize> BitWriter<N> {
    /// An empty RTCM 3 payload of at most `N` bytes whose errors name `message_number`.
    pub fn bytes(message_number: u16) -> Self {
        BitWriter { message_type: Some(message_number), unit: 8, ..BitWriter::default() }
    }

    fn error(&self, field: &'static str, detail: Detail) -> AisError {
        AisError::new(AisErrorKind::BadValue, self.message_type, Some(field), detail).of(self.unit == 8)
    }

    /// The payload's bytes (an RTCM 3 payload's), the last one filled with zero bits.
    pub fn written(&self) -> &[u8] {
        let bytes = self.len.div_ceil(8);
        &self.values[..bytes]
    }

    /// The bits written so far.
    pub fn bit_len(&self) -> usize {
        self.len
    }

    /// `raw`'s low `width` bits (at most 64); a raw value wider than `width` bits is refused.
    pub fn put(&mut self, raw: u64, width: usize, field: &'static str) -> Result<(), AisError> {
        if width < 64 && raw >> width != 0 {
            return Err(self.error(field, Detail::TooWide { raw: raw as i64, width }));
        }
        self.put_raw(raw, width, field)
    }

    /// `value` in `width` bits (1 to 64), two's complement.
    pub fn put_signed(&mut self, value: i64, width: usize, field: &'static str) -> Result<(), AisError> {
        let unused = 64 - width as u32;
        if (value << unused) >> unused != value {
            return Err(self.error(field, Detail::TooWide { raw: value, width }));
        }
        self.put_raw(value as u64 & (u64::MAX >> unused), width, field)
    }

    /// Bits kept as sent, bit for bit.
    pub fn put_bits(&mut self, bits: Bits<'_>, field: &'static str) -> Result<(), AisError> {
        (0..bits.len).step_by(64).try_for_each(|start| {
            let width = (bits.len - start).min(64);
            self.put_raw(bits.payload.raw(bits.offset + start, width), width, field)
        })
    }

    /// Bits of a field of fixed width: exactly `width` of them (a text built by a program may
    /// have fewer characters than its field).
    pub fn put_fixed(&mut self, bits: Bits<'_>, width: usize, text: bool, field: &'static str) -> Result<(), AisError> {
        if bits.len != width {
            return Err(self.error(field, Detail::Width { width, bits: bits.len, text }));
        }
        self.put_bits(bits, field)
    }

    /// `value` in `width` bits (2 to 64), sign and magnitude; `1 << (width - 1)` writes the
    /// negative zero [`BitReader::take_smag`] reads.
    pub fn put_smag(&mut self, value: i64, width: usize, field: &'static str) -> Result<(), AisError> {
        let sign = 1u64 << (width - 1);
        let magnitude = value.unsigned_abs();
        if value as u64 == sign {
            return self.put_raw(sign, width, field);
        }
        if magnitude >= sign {
            return Err(self.error(field, Detail::TooWide { raw: value, width }));
        }
        self.put_raw(if value < 0 { sign | magnitude } else { magnitude }, width, field)
    }

    /// Bits of a field counted by another (RTCM 3's characters, an MSM's cell mask): as many
    /// `units` of `unit_bits` as the count says, else bad_value.
    pub fn put_counted(
        &mut self,
        bits: Bits<'_>,
        units: usize,
        unit_bits: usize,
        field: &'static str,
    ) -> Result<(), AisError> {
        if bits.len() != units * unit_bits {
            return Err(self.error(field, Detail::Units { units, bits: bits.len() }));
        }
        self.put_bits(bits, field)
    }

    /// The error of a field a case of a choice has that the message leaves out (None).
    pub fn missing(&self, field: &'static str) -> AisError {
        self.error(field, Detail::Missing)
    }

    /// The error of a group of `len` entries whose count (its masks' bits set) says `count`.
    pub fn entries_error(&self, len: usize, count: usize, field: &'static str) -> AisError {
        self.error(field, Detail::Said { len, count })
    }

    /// Six-bit text, each character checked.
    pub fn put_text(&mut self, text: &str, field: &'static str) -> Result<(), AisError> {
        text.bytes().try_for_each(|ch| match text_value(ch) {
            Some(value) => self.put_raw(u64::from(value), 6, field),
            None => Err(self.error(field, Detail::NotText(ch))),
        })
    }

    fn put_raw(&mut self, raw: u64, width: usize, field: &'static str) -> Result<(), AisError> {
        let unit = usize::from(self.unit);
        if self.len + width > if unit == 6 { MAX_BITS } else { N * 8 } {
            return Err(self.error(field, Detail::TooLong));
        }
        let mut left = width;
        while left > 0 {
            let in_unit = self.len % unit;
            let put = (unit - in_unit).min(left);
            let chunk = (raw >> (left - put)) as u8 & ((1u16 << put) - 1) as u8;
            let value = &mut self.values[self.len / unit];
            // a byte's bits go in from its top: the bits not written yet stay 0
            *value |= chunk << (unit - in_unit - put);
            self.len += put;
            left -= put;
        }
        Ok(())
    }
}

/// An encoded payload: its armored characters and fill bits.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Armored {
    chars: [u8; MAX_CHARS],
    len: usize,
    fill_bits: u8,
}

impl Armored {
    /// The armored characters.
    pub fn as_str(&self) -> &str {
        // Armored characters are ASCII.
        core::str::from_utf8(&self.chars[..self.len]).unwrap_or_default()
    }

    /// The number of fill bits.
    pub fn fill_bits(&self) -> u8 {
        self.fill_bits
    }
}

/// The value of a number in its unit, or the special value its raw integer is instead.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Reading<T> {
    /// A value in the field's unit.
    Value(T),
    /// A raw value that is no number (`not_available`, `manual_input`, ...), by its spec id.
    Special(&'static str),
}

/// The special value of `raw` among `specials` (raw value, id).
fn special(raw: i64, specials: &[(i64, &'static str)]) -> Option<&'static str> {
    specials.iter().find(|&&(value, _)| value == raw).map(|&(_, id)| id)
}

/// A number with a divisor or a fractional base: `(raw + base * divisor) / divisor` (the base moved
/// into the raw scale first: (819 - 600) / 10 is 21.9, 819 / 10 - 60 is not), or its special value.
pub fn scaled(raw: i64, divisor: f64, base: f64, specials: &[(i64, &'static str)]) -> Reading<f64> {
    special(raw, specials).map_or_else(|| Reading::Value((raw as f64 + base * divisor) / divisor), Reading::Special)
}

/// A whole number: `raw + base`, or its special value.
pub fn counted(raw: i64, base: i64, specials: &[(i64, &'static str)]) -> Reading<i64> {
    special(raw, specials).map_or_else(|| Reading::Value(raw + base), Reading::Special)
}

/// The value of an enum field's raw code, None for a code the enum does not name.
pub fn code<E: super::CodeEnum>(raw: u64) -> Option<E> {
    let mut digits = [0u8; 20];
    let mut start = digits.len();
    let mut rest = raw;
    loop {
        start -= 1;
        digits[start] = b'0' + (rest % 10) as u8;
        rest /= 10;
        if rest == 0 {
            break;
        }
    }
    E::from_code_bytes(&digits[start..])
}

/// A JSON object written member by member, in the form of generated/vectors/ais.jsonl (Python's
/// `json.dumps` with compact separators): what the tools print and the tests compare.
pub struct JsonObject<'w, W: fmt::Write> {
    out: &'w mut W,
    empty: bool,
}

impl<'w, W: fmt::Write> JsonObject<'w, W> {
    /// An object opened at the end of `out`.
    pub fn new(out: &'w mut W) -> Result<Self, fmt::Error> {
        out.write_char('{')?;
        Ok(JsonObject { out, empty: true })
    }

    /// The writer, after the key `name` of the next member (its value is the caller's to write).
    pub fn key(&mut self, name: &str) -> Result<&mut W, fmt::Error> {
        if !self.empty {
            self.out.write_char(',')?;
        }
        self.empty = false;
        write!(self.out, "\"{name}\":")?;
        Ok(self.out)
    }

    /// An integer member.
    pub fn int(&mut self, name: &str, value: impl Into<i128>) -> fmt::Result {
        write!(self.key(name)?, "{}", value.into())
    }

    /// A true or false member.
    pub fn flag(&mut self, name: &str, value: bool) -> fmt::Result {
        write!(self.key(name)?, "{value}")
    }

    /// A string member (text of bits or six-bit characters, `"` and `\\` escaped).
    pub fn text(&mut self, name: &str, value: impl fmt::Display) -> fmt::Result {
        let out = self.key(name)?;
        out.write_char('"')?;
        fmt::Write::write_fmt(&mut Escaped(out), format_args!("{value}"))?;
        out.write_char('"')
    }

    /// A number's members: its value (or special value's id), then its raw integer as `raw_name`.
    pub fn reading<T: JsonNumber>(&mut self, name: &str, value: Reading<T>, raw_name: &str, raw: i64) -> fmt::Result {
        match value {
            Reading::Value(number) => number.write(self.key(name)?)?,
            Reading::Special(id) => self.text(name, id)?,
        }
        self.int(raw_name, raw)
    }

    /// An enum's member: the id of its value, or the raw code the enum does not name.
    pub fn code(&mut self, name: &str, id: Option<&str>, raw: u64) -> fmt::Result {
        match id {
            Some(id) => self.text(name, id),
            None => self.int(name, raw),
        }
    }

    /// Closes the object.
    pub fn finish(self) -> fmt::Result {
        self.out.write_char('}')
    }
}

/// A number as Python's JSON writes it: a float always with a fraction or an exponent.
pub trait JsonNumber: Copy {
    /// Writes the number.
    fn write<W: fmt::Write>(self, out: &mut W) -> fmt::Result;
}

impl JsonNumber for i64 {
    fn write<W: fmt::Write>(self, out: &mut W) -> fmt::Result {
        write!(out, "{self}")
    }
}

impl JsonNumber for f64 {
    /// Python's `repr` ([`write_repr`](super::repr::write_repr)); `inf` and `NaN` as Rust writes them.
    fn write<W: fmt::Write>(self, out: &mut W) -> fmt::Result {
        if !self.is_finite() {
            return write!(out, "{self}");
        }
        super::repr::write_repr(out, self)
    }
}

/// A writer escaping what a JSON string cannot hold as it is.
struct Escaped<'w, W: fmt::Write>(&'w mut W);

impl<W: fmt::Write> fmt::Write for Escaped<'_, W> {
    fn write_str(&mut self, s: &str) -> fmt::Result {
        s.chars().try_for_each(|ch| match ch {
            '"' | '\\' => write!(self.0, "\\{ch}"),
            _ => self.0.write_char(ch),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    extern crate std;
    use std::string::ToString;

    // The README's type 1 (gpsd's sample.aivdm).
    const TYPE_1: &[u8] = b"15RTgt0PAso;90TKcjM8h6g208CQ";
    // A type 5 of two sentences joined (sample.aivdm's EVER DIADEM), 2 fill bits.
    const TYPE_5: &[u8] = b"55?MbV02;H;s<HtKR20EHE:0@T4@Dn2222222216L961O5Gf0NSQEp6ClRp888888888880";

    #[test]
    fn armoring_covers_the_64_values_both_ways() {
        for value in 0..64 {
            assert_eq!(armor_value(armor_char(value)), Some(value));
        }
        assert_eq!((armor_value(b'X'), armor_value(b'_'), armor_value(b'x')), (None, None, None));
        for (value, &ch) in SIXBIT_TEXT.iter().enumerate() {
            assert_eq!(text_value(ch), Some(value as u8));
        }
        assert_eq!(text_value(b'a'), None);
    }

    #[test]
    fn a_position_report_reads_field_by_field() {
        let payload = Payload::new(TYPE_1, 0).unwrap();
        let mut r = payload.reader();
        assert_eq!(r.take(6, "message_type"), Ok(1));
        r.set_message_type(1);
        assert_eq!((r.take(2, "repeat"), r.take(30, "mmsi")), (Ok(0), Ok(371798000)));
        assert_eq!((r.take(4, "status"), r.take_signed(8, "turn")), (Ok(0), Ok(-127)));
        assert_eq!(r.take(10, "speed"), Ok(123));
        assert_eq!(r.position(), 60);
        assert_eq!(r.remaining(), 108);
    }

    #[test]
    fn text_is_kept_as_sent() {
        let payload = Payload::new(TYPE_5, 2).unwrap();
        let mut r = payload.reader();
        r.take_bits(70, "head").unwrap();
        let callsign = r.take_text(7, "callsign").unwrap();
        let shipname = r.take_text(20, "shipname").unwrap();
        assert_eq!(callsign, "3FOF8  ");
        assert_eq!(shipname.to_string(), "EVER DIADEM         ");
        assert!(shipname.trimmed().eq("EVER DIADEM".chars()));
        assert_eq!(payload.bit_len(), 424);
    }

    /// Every payload read in pieces of every width and written back gives its characters and
    /// fill bits, the fill bits' values included.
    #[test]
    fn bits_written_back_give_the_same_payload() {
        let with_padding = b"15RTgt0PAso;90TKcjM8h6g208CS";
        for (armored, fill) in [(TYPE_1, 0), (TYPE_5, 2), (&with_padding[..], 1)] {
            let payload = Payload::new(armored, fill).unwrap();
            for width in [1, 5, 7, 30, 64] {
                let (mut r, mut w) = (payload.reader(), BitWriter::new(0));
                while r.remaining() > 0 {
                    let n = width.min(r.remaining());
                    w.put(r.take(n, "piece").unwrap(), n, "piece").unwrap();
                }
                let out = w.finish(payload.padding()).unwrap();
                assert_eq!((out.as_str().as_bytes(), out.fill_bits()), (armored, fill));
            }
            let mut w = BitWriter::new(0);
            w.put_bits(payload.reader().take_bits(payload.bit_len(), "all").unwrap(), "all").unwrap();
            assert_eq!(w.finish(payload.padding()).unwrap().as_str().as_bytes(), armored);
        }
    }

    #[test]
    fn signed_and_text_values_are_written_in_their_width() {
        let mut w = BitWriter::new(1);
        w.put_signed(-127, 8, "turn").unwrap();
        w.put_text("A@ ", "name").unwrap();
        let out = w.finish(0).unwrap();
        let payload = Payload::new(out.as_str().as_bytes(), out.fill_bits()).unwrap();
        let mut r = payload.reader();
        assert_eq!(r.take_signed(8, "turn"), Ok(-127));
        assert_eq!(r.take_text(3, "name").unwrap(), "A@ ");
    }

    #[test]
    fn numbers_and_text_are_written_as_pythons_json() {
        let mut out = std::string::String::new();
        let mut j = JsonObject::new(&mut out).unwrap();
        j.reading("speed", scaled(123, 10.0, 0.0, &[(1023, "not_available")]), "speed_raw", 123).unwrap();
        j.reading("lat", scaled(0, 600000.0, 0.0, &[]), "lat_raw", 0).unwrap();
        j.reading("heading", counted(511, 0, &[(511, "not_available")]), "heading_raw", 511).unwrap();
        j.text("name", "A\"B\\").unwrap();
        j.finish().unwrap();
        assert_eq!(
            out,
            r#"{"speed":12.3,"speed_raw":123,"lat":0.0,"lat_raw":0,"heading":"not_available","heading_raw":511,"name":"A\"B\\"}"#
        );
    }

    #[test]
    fn floats_are_written_as_pythons_repr() {
        let cases = [
            (0.0, "0.0"),
            (-0.16135025024414062, "-0.16135025024414062"),
            (1e-5, "1e-05"),
            (-1.862645149230957e-09, "-1.862645149230957e-09"),
            (0.0001, "0.0001"),
            (1.5e16, "1.5e+16"),
            (1e16, "1e+16"),
            (123456789.0, "123456789.0"),
            (9999999999999998.0, "9999999999999998.0"),
            (12.3, "12.3"),
            (-4850729.7108, "-4850729.7108"),
        ];
        for (value, text) in cases {
            let mut out = std::string::String::new();
            value.write(&mut out).unwrap();
            assert_eq!(out, text);
        }
    }

    #[test]
    fn a_group_takes_the_entries_the_bits_hold() {
        // A type 7 of 40 bits after its header: one acknowledgement of 32 bits and 8 bits over.
        let payload = Payload::new(b"702R5`hwCjq8", 0).unwrap();
        let mut r = payload.reader();
        r.take_bits(40, "head").unwrap();
        assert_eq!(r.entries(1, 4, 32, 0, "acks"), Ok(1));
        let err = r.entries(2, 4, 32, 0, "acks").unwrap_err();
        assert_eq!(err.to_string(), "short_payload: AIS: acks needs at least 2 entries of 32 bits, 32 bits left");
    }

    #[test]
    fn errors_name_the_message_type_and_the_field() {
        let short = Payload::new(&TYPE_1[..11], 0).unwrap();
        let mut r = short.reader();
        r.set_message_type(1);
        let err = r.take_bits(61, "head").and_then(|_| r.take(28, "lon")).unwrap_err();
        assert_eq!((err.kind, err.message_type, err.field), (AisErrorKind::ShortPayload, Some(1), Some("lon")));
        assert_eq!(err.to_string(), "short_payload: AIS type 1: lon needs bits 61-88, the payload has 66");
        let err = Payload::new(b"15RT~", 0).unwrap_err();
        assert_eq!(err.to_string(), "bad_armor: AIS: character '~' at offset 4 is not six-bit armoring");
        let err = Payload::new(TYPE_1, 6).unwrap_err();
        assert_eq!(err.to_string(), "bad_armor: AIS: fill bits are 0-5 (none for an empty payload), not 6");
        assert_eq!(
            short.reader().unknown_message(28).to_string(),
            "unknown_message: AIS type 28: message type 28 is not one the spec describes"
        );
        let mut w = BitWriter::new(5);
        assert_eq!(w.put(64, 6, "repeat").unwrap_err().kind, AisErrorKind::BadValue);
        assert_eq!(w.put_signed(-129, 8, "turn").unwrap_err().field, Some("turn"));
        assert_eq!(
            w.put_text("a", "shipname").unwrap_err().to_string(),
            "bad_value: AIS type 5: shipname takes six-bit text characters, not 'a'"
        );
        w.put(1, 1, "flag").unwrap();
        assert_eq!(w.finish(32).unwrap_err().field, Some("padding"));
    }
}
