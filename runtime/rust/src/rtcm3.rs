//! RTCM 3 messages: what the generated `rtcm3_messages` module reads and writes them with, besides
//! the bit layouts' one reader and writer ([`ais::BitReader`] over a payload's bytes,
//! [`ais::BitWriter::bytes`]): the frame (preamble, length, CRC-24Q) checked and written, groups of
//! a fixed capacity, characters as sent, a message number no layout describes kept with its
//! payload. The Rust side of the Python runtime's rtcm3.py, with its rules and error messages.
//! Decoding allocates nothing: characters and data are views of the payload's bits. Facts from
//! the public field lists named in spec/binary/rtcm3/protocol.yaml (pyrtcm, gpsd, RTKLIB).

use core::fmt;

use super::ais::{self, AisError, Bits};
use super::stream::crc24q;

/// The preamble of every frame.
pub const PREAMBLE: u8 = 0xD3;
/// The most bytes a payload holds (its length has 10 bits).
pub const MAX_PAYLOAD: usize = 1023;
/// The most bytes a frame holds: preamble and length, the payload, the checksum.
pub const MAX_FRAME: usize = 3 + MAX_PAYLOAD + 3;

/// The writer of a payload.
pub type Writer = ais::BitWriter<MAX_PAYLOAD>;

/// Why bytes are no RTCM 3 frame (the kinds of Python's `rtcm3.payload_of`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FrameError {
    /// The first byte is not the preamble D3 (None: there is no byte).
    BadSync(Option<u8>),
    /// Fewer bytes than the length field says (`size`: what it says; `len`: the bytes there are).
    ShortFrame {
        /// The frame's bytes by its length field (0 when fewer than 6 bytes hold no length).
        size: usize,
        /// The bytes there are.
        len: usize,
    },
    /// More bytes than the length field says.
    LongFrame {
        /// The frame's bytes by its length field.
        size: usize,
        /// The bytes there are.
        len: usize,
    },
    /// The checksum sent differs from the one computed.
    BadChecksum {
        /// The three bytes sent, as a big-endian number.
        sent: u32,
        /// What they should be.
        computed: u32,
    },
}

impl FrameError {
    /// The kind as the JSON names it.
    pub const fn kind(&self) -> &'static str {
        match self {
            FrameError::BadSync(_) => "bad_sync",
            FrameError::ShortFrame { .. } => "short_frame",
            FrameError::LongFrame { .. } => "long_frame",
            FrameError::BadChecksum { .. } => "bad_checksum",
        }
    }
}

impl fmt::Display for FrameError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}: RTCM3: ", self.kind())?;
        match *self {
            FrameError::BadSync(Some(byte)) => write!(f, "an RTCM 3 frame starts with D3, not {byte:02X}"),
            FrameError::BadSync(None) => f.write_str("an RTCM 3 frame starts with D3, not nothing"),
            FrameError::ShortFrame { size: 0, len } => write!(f, "a frame takes at least 6 bytes, there are {len}"),
            FrameError::ShortFrame { size, len } | FrameError::LongFrame { size, len } => {
                write!(f, "the length field says {size} bytes, the frame has {len}")
            }
            FrameError::BadChecksum { sent, computed } => {
                let [_, a, b, c] = sent.to_be_bytes();
                let [_, x, y, z] = computed.to_be_bytes();
                write!(f, "checksum {a:02X} {b:02X} {c:02X}, computed {x:02X} {y:02X} {z:02X}")
            }
        }
    }
}

#[cfg(feature = "std")]
impl std::error::Error for FrameError {}

/// Why a frame does not decode: the frame itself, or its payload for its layout.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Error {
    /// The frame's preamble, length or checksum.
    Frame(FrameError),
    /// The payload (short_payload, bad_value), naming the message number and field.
    Payload(AisError),
}

impl Error {
    /// The kind as the JSON names it.
    pub const fn kind(&self) -> &'static str {
        match self {
            Error::Frame(err) => err.kind(),
            Error::Payload(err) => err.kind.as_str(),
        }
    }
}

impl From<FrameError> for Error {
    fn from(err: FrameError) -> Self {
        Error::Frame(err)
    }
}

impl From<AisError> for Error {
    fn from(err: AisError) -> Self {
        Error::Payload(err)
    }
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Error::Frame(err) => err.fmt(f),
            Error::Payload(err) => err.fmt(f),
        }
    }
}

#[cfg(feature = "std")]
impl std::error::Error for Error {}

/// The payload of the one frame `data` holds, its preamble, length and checksum checked.
pub fn payload_of(data: &[u8]) -> Result<&[u8], FrameError> {
    match data.first() {
        Some(&PREAMBLE) => {}
        other => return Err(FrameError::BadSync(other.copied())),
    }
    if data.len() < 6 {
        return Err(FrameError::ShortFrame { size: 0, len: data.len() });
    }
    let size = 3 + (usize::from(data[1] & 0x03) << 8 | usize::from(data[2])) + 3;
    if data.len() != size {
        let len = data.len();
        return Err(if len < size {
            FrameError::ShortFrame { size, len }
        } else {
            FrameError::LongFrame { size, len }
        });
    }
    let (body, sent) = data.split_at(size - 3);
    let sent = u32::from(sent[0]) << 16 | u32::from(sent[1]) << 8 | u32::from(sent[2]);
    let computed = crc24q(body);
    if sent != computed {
        return Err(FrameError::BadChecksum { sent, computed });
    }
    Ok(&data[3..size - 3])
}

/// The message number of a payload (its first 12 bits), None when it has fewer than two bytes.
pub fn message_number(payload: &[u8]) -> Option<u16> {
    match payload {
        [a, b, ..] => Some(u16::from(*a) << 4 | u16::from(*b) >> 4),
        _ => None,
    }
}

/// A whole frame, written.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Frame {
    bytes: [u8; MAX_FRAME],
    len: usize,
}

impl Frame {
    /// The frame of a payload (at most [`MAX_PAYLOAD`] bytes: the writer holds no more).
    pub fn of(payload: &[u8]) -> Self {
        let n = payload.len().min(MAX_PAYLOAD);
        let mut bytes = [0u8; MAX_FRAME];
        bytes[0] = PREAMBLE;
        bytes[1] = (n >> 8) as u8;
        bytes[2] = (n & 0xFF) as u8;
        bytes[3..3 + n].copy_from_slice(&payload[..n]);
        let crc = crc24q(&bytes[..3 + n]).to_be_bytes();
        bytes[3 + n..6 + n].copy_from_slice(&crc[1..]);
        Frame { bytes, len: n + 6 }
    }

    /// Its bytes.
    pub fn as_bytes(&self) -> &[u8] {
        &self.bytes[..self.len]
    }
}

/// The entries of a group, at most `N` (an MSM's 64 satellites, 64 cells), in order.
#[derive(Clone, Copy)]
pub struct Group<T: Copy + Default, const N: usize> {
    entries: [T; N],
    len: usize,
}

impl<T: Copy + Default, const N: usize> Default for Group<T, N> {
    fn default() -> Self {
        Group { entries: [T::default(); N], len: 0 }
    }
}

impl<T: Copy + Default, const N: usize> Group<T, N> {
    /// A group of the entries of `entries`, None when they are more than `N`.
    pub fn from_slice(entries: &[T]) -> Option<Self> {
        let mut group = Self::default();
        group.entries.get_mut(..entries.len())?.copy_from_slice(entries);
        group.len = entries.len();
        Some(group)
    }

    /// `len` entries of their default values, their fields set one by one next (at most `N`).
    pub fn with_len(len: usize) -> Self {
        Group { len: len.min(N), ..Self::default() }
    }

    /// Adds an entry; false when the group holds `N` already.
    pub fn push(&mut self, entry: T) -> bool {
        match self.entries.get_mut(self.len) {
            Some(slot) => {
                *slot = entry;
                self.len += 1;
                true
            }
            None => false,
        }
    }

    /// How many entries.
    pub fn len(&self) -> usize {
        self.len
    }

    /// Whether there are none.
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// The entries.
    pub fn as_slice(&self) -> &[T] {
        &self.entries[..self.len]
    }

    /// The entries, to change.
    pub fn as_mut_slice(&mut self) -> &mut [T] {
        &mut self.entries[..self.len]
    }

    /// The entries, in order.
    pub fn iter(&self) -> core::slice::Iter<'_, T> {
        self.as_slice().iter()
    }
}

impl<T: Copy + Default + fmt::Debug, const N: usize> fmt::Debug for Group<T, N> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_list().entries(self.iter()).finish()
    }
}

/// Characters as sent, eight bits each: ISO 8859-1 (`latin1`), or UTF-8 code units (`utf8`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Chars<'a> {
    bits: Bits<'a>,
}

impl<'a> Chars<'a> {
    /// The characters of these bits (whole bytes).
    pub fn new(bits: Bits<'a>) -> Self {
        Chars { bits }
    }

    /// The bits they were read from.
    pub fn bits(&self) -> Bits<'a> {
        self.bits
    }

    /// How many bytes (code units).
    pub fn len(&self) -> usize {
        self.bits.len() / 8
    }

    /// Whether there are none.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The bytes, in order.
    pub fn bytes(&self) -> impl Iterator<Item = u8> + 'a {
        let bits = self.bits;
        (0..bits.len() / 8).map(move |i| bits.get(8 * i, 8) as u8)
    }

    /// The characters, each byte one of ISO 8859-1.
    pub fn latin1(&self) -> impl Iterator<Item = char> + 'a {
        self.bytes().map(char::from)
    }

    /// The characters of UTF-8 code units; a byte that is no UTF-8 as Err(byte) (Python keeps it
    /// as a surrogate escape).
    pub fn utf8(&self) -> impl Iterator<Item = Result<char, u8>> + 'a {
        let bytes = *self;
        let mut at = 0;
        core::iter::from_fn(move || {
            let total = bytes.len();
            if at >= total {
                return None;
            }
            let byte = |i: usize| bytes.bits.get(8 * i, 8) as u8;
            let first = byte(at);
            let more = match first {
                0x00..=0x7F => 0,
                0xC2..=0xDF => 1,
                0xE0..=0xEF => 2,
                0xF0..=0xF4 => 3,
                _ => usize::MAX,
            };
            if more == 0 {
                at += 1;
                return Some(Ok(char::from(first)));
            }
            let mut buf = [first, 0, 0, 0];
            let whole = more != usize::MAX && at + more < total && {
                (1..=more).all(|k| {
                    buf[k] = byte(at + k);
                    buf[k] & 0xC0 == 0x80
                })
            };
            match whole.then(|| core::str::from_utf8(&buf[..=more]).ok()).flatten() {
                Some(text) => {
                    at += more + 1;
                    text.chars().next().map(Ok)
                }
                None => {
                    at += 1;
                    Some(Err(first))
                }
            }
        })
    }
}

/// Writes `chars` as a JSON string as Python's `json.dumps` does (ASCII only: `\uXXXX` for the
/// rest, a byte that is no UTF-8 as its surrogate escape `\udcXX`).
pub fn write_json_chars<W: fmt::Write>(out: &mut W, chars: Chars<'_>, utf8: bool) -> fmt::Result {
    out.write_char('"')?;
    if utf8 {
        for ch in chars.utf8() {
            match ch {
                Ok(ch) => json_char(out, ch)?,
                Err(byte) => write!(out, "\\udc{byte:02x}")?,
            }
        }
    } else {
        chars.latin1().try_for_each(|ch| json_char(out, ch))?;
    }
    out.write_char('"')
}

/// A character in a JSON string, as Python's `json.dumps` writes it.
fn json_char<W: fmt::Write>(out: &mut W, ch: char) -> fmt::Result {
    match ch {
        '"' => out.write_str("\\\""),
        '\\' => out.write_str("\\\\"),
        '\n' => out.write_str("\\n"),
        '\r' => out.write_str("\\r"),
        '\t' => out.write_str("\\t"),
        '\u{8}' => out.write_str("\\b"),
        '\u{c}' => out.write_str("\\f"),
        ' '..='~' => out.write_char(ch),
        _ => {
            let mut units = [0u16; 2];
            ch.encode_utf16(&mut units).iter().try_for_each(|unit| write!(out, "\\u{unit:04x}"))
        }
    }
}

/// A frame of a message number no layout describes (the proprietary 4001-4095, ...), kept with
/// its payload.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Unknown<'a> {
    /// The message number, None for a payload of fewer than two bytes.
    pub message_number: Option<u16>,
    /// The payload, as sent.
    pub payload: &'a [u8],
}

impl Unknown<'_> {
    /// Its JSON: `{"message":null,"message_number":N,"payload":"<hex>"}`.
    pub fn write_json<W: fmt::Write>(&self, out: &mut W) -> fmt::Result {
        out.write_str("{\"message\":null,\"message_number\":")?;
        match self.message_number {
            Some(number) => write!(out, "{number}")?,
            None => out.write_str("null")?,
        }
        out.write_str(",\"payload\":\"")?;
        self.payload.iter().try_for_each(|byte| write!(out, "{byte:02x}"))?;
        out.write_str("\"}")
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    extern crate std;
    use std::string::{String, ToString};

    // rtcm3.log's 1005 frame
    const ARP: &str = "d300133ed7d30202980edeef34b4bd62ac0941986f33360b98";

    fn unhex(text: &str) -> std::vec::Vec<u8> {
        (0..text.len()).step_by(2).map(|i| u8::from_str_radix(&text[i..i + 2], 16).unwrap()).collect()
    }

    #[test]
    fn a_frame_is_checked_and_written_back() {
        let frame = unhex(ARP);
        let payload = payload_of(&frame).unwrap();
        assert_eq!((payload.len(), message_number(payload)), (19, Some(1005)));
        assert_eq!(Frame::of(payload).as_bytes(), &frame[..]);
        let mut bad = frame.clone();
        bad[24] ^= 1;
        assert_eq!(
            payload_of(&bad).unwrap_err().to_string(),
            "bad_checksum: RTCM3: checksum 36 0B 99, computed 36 0B 98"
        );
        assert_eq!(payload_of(&frame[..10]).unwrap_err().kind(), "short_frame");
        assert_eq!(payload_of(&[&frame[..], &[0]].concat()).unwrap_err().kind(), "long_frame");
        assert_eq!(
            payload_of(b"").unwrap_err().to_string(),
            "bad_sync: RTCM3: an RTCM 3 frame starts with D3, not nothing"
        );
    }

    #[test]
    fn fields_read_and_write_msb_first_over_bytes() {
        let frame = unhex(ARP);
        let payload = payload_of(&frame).unwrap();
        let bits = ais::Payload::bytes(payload);
        let mut r = bits.reader();
        r.set_message_type(1005u16);
        assert_eq!((r.take(12, "message_number"), r.take(12, "station_id")), (Ok(1005), Ok(2003)));
        let mut w = Writer::bytes(1005);
        w.put(1005, 12, "message_number").unwrap();
        w.put(2003, 12, "station_id").unwrap();
        w.put_bits(r.rest(), "rest").unwrap();
        assert_eq!(w.written(), payload);
        let err = bits.reader().take_bits(200, "ecef_z").unwrap_err();
        assert_eq!(err.to_string(), "short_payload: RTCM3: ecef_z needs bits 0-199, the payload has 152");
    }

    #[test]
    fn sign_magnitude_keeps_its_negative_zero() {
        let mut w = Writer::bytes(1020);
        for value in [5, -5, 8, 0] {
            w.put_smag(value, 4, "n").unwrap();
        }
        assert_eq!(w.written(), [0x5D, 0x80]);
        let data = [0x5D, 0x80];
        let bits = ais::Payload::bytes(&data);
        let mut r = bits.reader();
        let values: std::vec::Vec<_> = (0..4).map(|_| r.take_smag(4, "n").unwrap()).collect();
        assert_eq!(values, [5, -5, 8, 0]);
        assert_eq!(w.put_smag(-8, 4, "n").unwrap_err().kind, ais::AisErrorKind::BadValue);
    }

    #[test]
    fn characters_are_json_as_python_writes_them() {
        let data = "a\"é\u{43f}😀".as_bytes().iter().copied().chain([0xFF, b'\n']).collect::<std::vec::Vec<_>>();
        let bits = ais::Payload::bytes(&data);
        let chars = Chars::new(bits.reader().take_bits(8 * data.len(), "text").unwrap());
        let mut out = String::new();
        write_json_chars(&mut out, chars, true).unwrap();
        assert_eq!(out, r#""a\"\u00e9\u043f\ud83d\ude00\udcff\n""#);
        out.clear();
        write_json_chars(&mut out, Chars::new(bits.reader().take_bits(16, "text").unwrap()), false).unwrap();
        assert_eq!(out, r#""a\"""#);
    }

    #[test]
    fn groups_hold_at_most_their_capacity() {
        let mut group: Group<u8, 2> = Group::default();
        assert!(group.push(1) && group.push(2) && !group.push(3));
        assert_eq!(group.as_slice(), [1, 2]);
        assert!(Group::<u8, 2>::from_slice(&[1, 2, 3]).is_none());
    }
}
