//! Reading sentences from a byte stream: a serial port, a socket, a file, in chunks of any size.
//!
//! The [`Framer`] cuts the stream into lines the way a receiver's output is meant to be cut, and
//! keeps going whatever arrives:
//! - CR LF, LF and a bare CR all end a line; empty lines are skipped;
//! - a `$` or `!` always starts a new sentence: whatever came before it on the line (garbage, or
//!   a sentence cut short) is handed on as a line of its own, and is reported by the decoder;
//! - but a `\` at the start of a line opens a TAG block, which keeps its sentence: up to the
//!   block's closing `\` every byte but CR and LF belongs to it, and a `$`, `!` or `\` right
//!   after that continues the line;
//! - a line longer than [`MAX_LINE`] is not kept: its bytes are only counted, and it is reported
//!   as `too_long` with its length;
//! - a last line without an ending still counts ([`Framer::finish`]).
//!
//! [`Framer::with_binary_frames`] also takes the binary frames a receiver interleaves with its
//! sentences (spec/binary/*/protocol.yaml, the generated [`FRAMINGS`]): outside a TAG block, a frame's sync bytes
//! end the line before them, and the frame is handed on whole once its checksum matches. A frame
//! whose checksum fails, that the stream cuts short or that is longer than [`MAX_FRAME`] is a
//! [`Item::BadFrame`] of its sync bytes, and the bytes after them are read again, so that no
//! sentence or frame it seemed to hold is lost. Lines, frames and bad frames concatenate to the
//! stream less the line endings.
//!
//! The framer holds one line and one frame in fixed arrays: no allocation.

use super::frame::MAX_LINE;

/// The longest binary frame the framer holds: an RTCM 3 frame's 1,029 bytes, and the long UBX
/// frames of a multi-band receiver (a ZED-F9P's NAV-SAT or RXM-RAWX of 40 signals: 1,200 bytes).
pub const MAX_FRAME: usize = 2048;

pub use super::framings::{Protocol, FRAMINGS};

/// The checksums of binary frames (spec/schema/binary_protocol.schema.json).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ChecksumKind {
    /// Two 8-bit running sums (CK_A, CK_B), sent in that order.
    Fletcher8,
    /// The XOR of the bytes.
    Xor8,
    /// The sum of the bytes modulo 2^15, two bytes big endian.
    Sum15,
    /// The sum of the bytes as 32-bit little-endian words (a short last word padded with zeros),
    /// four bytes little endian.
    Sum32,
    /// CRC-24Q, three bytes big endian.
    Crc24q,
    /// CRC-CCITT (polynomial 0x1021, initial value 0), two bytes little endian.
    Crc16Ccitt,
    /// CRC-32 (reflected polynomial 0xEDB88320, initial value 0, no final inversion), four bytes
    /// little endian.
    Crc32,
}

/// The framing of a binary protocol (spec/binary/<protocol>/protocol.yaml): a row of the
/// generated [`FRAMINGS`]. Offsets count from the first sync byte.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct FrameFormat {
    /// Its name in the tools' JSON: `ubx`.
    pub name: &'static str,
    /// The first sync byte; the value of the next byte's bits under `follow_mask`; the third
    /// (when `sync_len` is 3), checked as it comes.
    pub sync: [u8; 3],
    /// The bits of the byte after the first sync byte that must hold `sync[1]`.
    pub follow_mask: u8,
    /// Its sync bytes (1 to 3): what a rejected frame is handed on as.
    pub sync_len: usize,
    /// The length field's first byte.
    pub length_at: usize,
    /// The length field's bytes (1 or 2).
    pub length_size: usize,
    /// Whether the length field is big endian.
    pub big_endian: bool,
    /// The field's bits that are the length.
    pub length_mask: u16,
    /// Bytes before the payload, sync included.
    pub header: usize,
    /// The frame's bytes beyond what its length counts (0: the length counts them all).
    pub length_adds: usize,
    /// The checksum, from `check_from` to the payload's end.
    pub checksum: ChecksumKind,
    /// The first byte the checksum covers.
    pub check_from: usize,
    /// Where the checksum sits in the header; 0: after the payload.
    pub check_at: usize,
    /// The checksum's bytes.
    pub check_size: usize,
    /// The bytes after it that end every frame.
    pub end: &'static [u8],
    /// The fields that tell the frame's message: name, bit offset, bits (numbered most
    /// significant first in a big-endian frame, least significant first in a little-endian one).
    pub identity: &'static [(&'static str, usize, usize)],
}

impl FrameFormat {
    /// The bytes after the payload: the checksum (unless it sits in the header) and end bytes.
    pub const fn trailer_len(&self) -> usize {
        (if self.check_at == 0 { self.check_size } else { 0 }) + self.end.len()
    }

    /// The frame's bytes, sync to end, from its header.
    pub(crate) fn frame_len(&self, header: &[u8]) -> usize {
        let first = usize::from(header[self.length_at]);
        let length = match (self.length_size, self.big_endian) {
            (2, true) => first << 8 | usize::from(header[self.length_at + 1]),
            (2, false) => first | usize::from(header[self.length_at + 1]) << 8,
            _ => first,
        };
        (length & usize::from(self.length_mask)) + self.length_adds
    }

    /// A whole frame's checksum and end bytes as sent, and as they must be, each as a big-endian
    /// number.
    pub(crate) fn check(&self, frame: &[u8]) -> (u32, u32) {
        let body = frame.len() - self.trailer_len();
        let at = if self.check_at == 0 { body } else { self.check_at };
        let sent = frame[at..at + self.check_size]
            .iter()
            .chain(&frame[frame.len() - self.end.len()..])
            .fold(0u32, |sum, &b| sum << 8 | u32::from(b));
        let bytes = &frame[self.check_from..body];
        let sum = match self.checksum {
            ChecksumKind::Fletcher8 => {
                let (a, b) = bytes.iter().fold((0u8, 0u8), |(a, b), &byte| {
                    let a = a.wrapping_add(byte);
                    (a, b.wrapping_add(a))
                });
                u32::from(a) << 8 | u32::from(b)
            }
            ChecksumKind::Xor8 => u32::from(bytes.iter().fold(0u8, |x, &byte| x ^ byte)),
            ChecksumKind::Sum15 => bytes.iter().fold(0u32, |sum, &byte| sum.wrapping_add(u32::from(byte))) & 0x7FFF,
            ChecksumKind::Sum32 => bytes
                .iter()
                .enumerate()
                .fold(0u32, |sum, (i, &byte)| sum.wrapping_add(u32::from(byte) << (8 * (i & 3))))
                .swap_bytes(),
            ChecksumKind::Crc24q => crc24q(bytes),
            ChecksumKind::Crc16Ccitt => u32::from(crc16_ccitt(bytes).swap_bytes()),
            ChecksumKind::Crc32 => crc32(bytes).swap_bytes(),
        };
        (sent, self.end.iter().fold(sum, |check, &byte| check << 8 | u32::from(byte)))
    }

    /// Each identity field of a whole frame: its name and value (None past the payload's end).
    pub fn identity_of<'f>(&'f self, frame: &'f [u8]) -> impl Iterator<Item = (&'static str, Option<u32>)> + 'f {
        let body = 8 * frame.len().saturating_sub(self.trailer_len());
        let big = self.big_endian;
        self.identity.iter().map(move |&(name, at, bits)| {
            let value = (at + bits <= body).then(|| {
                if big {
                    (at..at + bits).fold(0u32, |v, bit| v << 1 | u32::from(frame[bit / 8] >> (7 - bit % 8) & 1))
                } else {
                    (at..at + bits).rev().fold(0u32, |v, bit| v << 1 | u32::from(frame[bit / 8] >> (bit % 8) & 1))
                }
            });
            (name, value)
        })
    }
}

impl Protocol {
    /// Its framing.
    pub fn framing(self) -> &'static FrameFormat {
        &FRAMINGS[self as usize]
    }

    /// Its name in the tools' JSON: `ubx`, `rtcm3`.
    pub fn name(self) -> &'static str {
        self.framing().name
    }

    /// Its sync bytes.
    pub fn sync_len(self) -> usize {
        self.framing().sync_len
    }

    /// The bytes after the payload: checksum and end bytes.
    pub fn trailer_len(self) -> usize {
        self.framing().trailer_len()
    }

    /// Whether `byte` starts a frame of some protocol.
    fn starts_frame(byte: u8) -> bool {
        FRAMINGS.iter().any(|f| f.sync[0] == byte)
    }

    /// The protocol whose frames start with `first` then `next`.
    fn starting_with(first: u8, next: u8) -> Option<Protocol> {
        Protocol::ALL.into_iter().find(|p| {
            let f = p.framing();
            f.sync[0] == first && next & f.follow_mask == f.sync[1]
        })
    }
}

/// CRC-24Q of RTCM 3 (polynomial 0x1864CFB, initial value 0, no reflection).
pub fn crc24q(data: &[u8]) -> u32 {
    let mut crc = 0u32;
    for &byte in data {
        crc ^= u32::from(byte) << 16;
        for _ in 0..8 {
            crc = if crc & 0x80_0000 != 0 { (crc << 1) ^ 0x186_4CFB } else { crc << 1 };
        }
    }
    crc & 0xFF_FFFF
}

/// CRC-CCITT of SBF (polynomial 0x1021, initial value 0, no reflection).
pub fn crc16_ccitt(data: &[u8]) -> u16 {
    let mut crc = 0u16;
    for &byte in data {
        crc ^= u16::from(byte) << 8;
        for _ in 0..8 {
            crc = if crc & 0x8000 != 0 { (crc << 1) ^ 0x1021 } else { crc << 1 };
        }
    }
    crc
}

/// The CRC-32 of each byte value (reflected polynomial 0xEDB88320), computed at compile time.
const CRC32_TABLE: [u32; 256] = {
    let mut table = [0u32; 256];
    let mut i = 0;
    while i < 256 {
        let mut crc = i as u32;
        let mut bit = 0;
        while bit < 8 {
            crc = if crc & 1 != 0 { (crc >> 1) ^ 0xEDB8_8320 } else { crc >> 1 };
            bit += 1;
        }
        table[i] = crc;
        i += 1;
    }
    table
};

/// CRC-32 of Unicore's binary frames (reflected polynomial 0xEDB88320, initial value 0, no final
/// inversion): a byte a lookup.
pub fn crc32(data: &[u8]) -> u32 {
    data.iter().fold(0u32, |crc, &byte| (crc >> 8) ^ CRC32_TABLE[usize::from(crc.to_le_bytes()[0] ^ byte)])
}

/// Why what began like a binary frame is not one.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FrameError {
    /// The checksum sent differs from the one computed.
    BadChecksum {
        /// The frame's checksum and end bytes, as a big-endian number.
        sent: u32,
        /// What they should be.
        computed: u32,
    },
    /// Its length field says more bytes than [`MAX_FRAME`]: the frame's length.
    TooLong(usize),
    /// Its length field (one that counts the whole frame) says fewer bytes than its header and
    /// checksum hold: the frame's length.
    TooShort(usize),
    /// Its header after the sync is NUL bytes (a UBX frame of class 0, id 0 and no payload would
    /// have a checksum of NULs too): what a break after a sync makes.
    NulHeader,
    /// The stream ends inside it.
    Cut,
}

impl FrameError {
    /// Its kind in the tools' JSON.
    pub const fn kind(self) -> &'static str {
        match self {
            FrameError::BadChecksum { .. } => "bad_checksum",
            FrameError::TooLong(_) => "too_long",
            FrameError::TooShort(_) => "too_short",
            FrameError::NulHeader => "nul_header",
            FrameError::Cut => "cut",
        }
    }
}

/// One framed item of the stream.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Item<'a> {
    /// A line (without its line ending), at most [`MAX_LINE`] bytes.
    Line(&'a [u8]),
    /// A line over [`MAX_LINE`] bytes: its length (the bytes were not kept).
    TooLong(usize),
    /// A binary frame whose checksum matched: sync bytes to checksum.
    Frame(Protocol, &'a [u8]),
    /// What began like a binary frame and is not one: its sync bytes (the bytes after them are
    /// read again).
    BadFrame(Protocol, FrameError, &'a [u8]),
}

/// Cuts bytes fed in any chunks into lines, overlong lines and (with binary frames) frames (see
/// the module documentation).
#[derive(Clone, Debug)]
pub struct Framer {
    line: [u8; MAX_LINE],
    /// Bytes of the current line, counted (also past [`MAX_LINE`]).
    length: usize,
    /// Where the current line is as to TAG blocks.
    tag: TagState,
    /// Whether binary frames are taken.
    binary: bool,
    /// A binary frame under way, from its first sync byte; the bytes to read again at the end.
    frame: [u8; MAX_FRAME],
    frame_len: usize,
    /// Its length from its header, once that is in; 0 before.
    frame_size: usize,
    protocol: Protocol,
    /// Where the bytes to read again start in `frame` (they end at its end): [`MAX_FRAME`] when none.
    replay: usize,
}

/// Where a line is as to TAG blocks.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum TagState {
    Outside,
    InBlock,
    AfterBlock,
}

impl Default for Framer {
    fn default() -> Self {
        Self::new()
    }
}

impl Framer {
    /// A framer of NMEA lines at the start of a stream.
    pub const fn new() -> Self {
        Self {
            line: [0; MAX_LINE],
            length: 0,
            tag: TagState::Outside,
            binary: false,
            frame: [0; MAX_FRAME],
            frame_len: 0,
            frame_size: 0,
            protocol: Protocol::ALL[0],
            replay: MAX_FRAME,
        }
    }

    /// A framer of NMEA lines and binary frames at the start of a stream.
    pub const fn with_binary_frames() -> Self {
        let mut framer = Self::new();
        framer.binary = true;
        framer
    }

    /// Feeds a chunk of the stream; `each` gets every item it completes, in order (each valid
    /// for the call).
    pub fn feed(&mut self, data: &[u8], mut each: impl FnMut(Item<'_>)) {
        for &byte in data {
            self.step(byte, &mut each);
            self.read_again(&mut each);
        }
    }

    /// Ends the stream: `each` gets the last line, when the stream ended without a line ending,
    /// and what a frame cut short by the end held; the framer is then at the start of a new stream.
    pub fn finish(&mut self, mut each: impl FnMut(Item<'_>)) {
        while self.frame_len > 0 {
            if self.frame_len == 1 || self.frame_len < self.protocol.sync_len() {
                self.unstart(&mut each); // a sync cut short by the end: bytes of the line
            } else {
                self.reject(FrameError::Cut, &mut each);
                self.read_again(&mut each);
            }
        }
        self.end_line(&mut each);
    }

    /// Reads the bytes of rejected frames again, up to the buffer's end.
    fn read_again(&mut self, each: &mut impl FnMut(Item<'_>)) {
        while self.replay < MAX_FRAME {
            let byte = self.frame[self.replay];
            self.replay += 1;
            self.step(byte, each);
        }
    }

    /// Takes one byte.
    fn step(&mut self, byte: u8, each: &mut impl FnMut(Item<'_>)) {
        if self.frame_len == 1 {
            match Protocol::starting_with(self.frame[0], byte) {
                Some(protocol) => self.protocol = protocol,
                None => {
                    self.frame_len = 0; // no frame: its first byte was one of the line
                    self.line_byte(self.frame[0], each);
                }
            }
        }
        if self.frame_len > 0 {
            self.frame_byte(byte, each);
        } else if self.binary && self.tag == TagState::Outside && Protocol::starts_frame(byte) {
            self.frame[0] = byte;
            self.frame_len = 1;
        } else {
            self.line_byte(byte, each);
        }
    }

    /// A byte of the frame under way, after its first.
    fn frame_byte(&mut self, byte: u8, each: &mut impl FnMut(Item<'_>)) {
        let protocol = self.protocol;
        let framing = protocol.framing();
        if self.frame_len < 3 {
            // the sync's bytes: a third one checked as it comes (no frame: it starts none whose third byte it is)
            if self.frame_len == 2 && framing.sync_len > 2 && byte != framing.sync[2] {
                self.unstart(each);
                return self.step(byte, each);
            }
            if self.frame_len + 1 == framing.sync_len.max(2) {
                self.end_line(each); // the line before the frame, its sync whole
            }
        }
        self.frame[self.frame_len] = byte;
        self.frame_len += 1;
        if self.frame_len == framing.header {
            self.frame_size = framing.frame_len(&self.frame[..self.frame_len]);
            if self.frame[framing.sync_len..self.frame_len].iter().all(|&b| b == 0) {
                self.reject(FrameError::NulHeader, each); // what a break's NUL bytes after a sync make
            } else if self.frame_size > MAX_FRAME {
                self.reject(FrameError::TooLong(self.frame_size), each);
            } else if self.frame_size < framing.header + framing.trailer_len() {
                self.reject(FrameError::TooShort(self.frame_size), each);
            }
        }
        if self.frame_len > 0 && self.frame_len == self.frame_size {
            let (sent, computed) = framing.check(&self.frame[..self.frame_size]);
            if sent == computed {
                each(Item::Frame(protocol, &self.frame[..self.frame_size]));
                self.frame_len = 0;
                self.frame_size = 0;
            } else {
                self.reject(FrameError::BadChecksum { sent, computed }, each);
            }
        }
    }

    /// The sync bytes so far of what turns out to be no frame (a third sync byte that does not
    /// follow, or the stream's end): bytes of the line, as a first sync byte no second follows.
    fn unstart(&mut self, each: &mut impl FnMut(Item<'_>)) {
        let (sync, len) = ([self.frame[0], self.frame[1]], self.frame_len.min(2));
        self.frame_len = 0;
        for &byte in &sync[..len] {
            self.line_byte(byte, each);
        }
    }

    /// Reports the frame under way as `error`; the bytes after its sync are to be read again,
    /// before those still to be read again: both lie at the buffer's end. (A frame found among
    /// them grows from the buffer's start and never reaches the byte being read.)
    fn reject(&mut self, error: FrameError, each: &mut impl FnMut(Item<'_>)) {
        let sync = self.protocol.sync_len();
        each(Item::BadFrame(self.protocol, error, &self.frame[..sync]));
        self.replay -= self.frame_len - sync;
        self.frame.copy_within(sync..self.frame_len, self.replay);
        self.frame_len = 0;
        self.frame_size = 0;
    }

    fn line_byte(&mut self, byte: u8, each: &mut impl FnMut(Item<'_>)) {
        match byte {
            b'\r' | b'\n' => return self.end_line(each),
            // opens a block (at the start, or right after one), or closes the open one
            b'\\' if self.length == 0 || self.tag != TagState::Outside => {
                self.tag = if self.tag == TagState::InBlock { TagState::AfterBlock } else { TagState::InBlock };
            }
            b'$' | b'!' if self.tag == TagState::Outside => self.end_line(each),
            // the sentence after the blocks, or whatever else follows them
            _ if self.tag == TagState::AfterBlock => self.tag = TagState::Outside,
            _ => {}
        }
        if let Some(slot) = self.line.get_mut(self.length) {
            *slot = byte;
        }
        self.length = self.length.saturating_add(1);
    }

    fn end_line(&mut self, each: &mut impl FnMut(Item<'_>)) {
        self.tag = TagState::Outside;
        match self.length {
            0 => {}
            length if length <= MAX_LINE => each(Item::Line(&self.line[..length])),
            length => each(Item::TooLong(length)),
        }
        self.length = 0;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn items(chunks: &[&[u8]]) -> ([([u8; 16], usize); 8], usize) {
        let mut framer = Framer::new();
        let mut out = [([0u8; 16], 0usize); 8];
        let mut n = 0;
        let mut keep = |item: Item<'_>| {
            match item {
                Item::Line(line) => {
                    out[n].0[..line.len()].copy_from_slice(line);
                    out[n].1 = line.len();
                }
                Item::TooLong(length) => out[n].1 = 1000 + length,
                Item::Frame(..) | Item::BadFrame(..) => unreachable!("no binary frames"),
            }
            n += 1;
        };
        for chunk in chunks {
            framer.feed(chunk, &mut keep);
        }
        framer.finish(&mut keep);
        (out, n)
    }

    #[test]
    fn lines_end_at_cr_lf_and_sentence_starts() {
        let (out, n) = items(&[b"ab\r\n\r\n$A,", b"1$B\rx!", b"C"]);
        let lines: [&[u8]; 5] = [b"ab", b"$A,1", b"$B", b"x", b"!C"];
        assert_eq!(n, 5);
        for (i, line) in lines.iter().enumerate() {
            assert_eq!(&out[i].0[..out[i].1], *line);
        }
        let (_, n) = items(&[b"$", b"$"]);
        assert_eq!(n, 2);
    }

    #[test]
    fn a_tag_block_keeps_its_sentence() {
        let stream: &[u8] =
            b"junk\\s:1*00\\$GPGGA,1*00\r\n\\s:x*31\\\\c:1*00\\!AIVDM,x\n$GPRMC\\x\\$GPGGA\n\\g:1$2\\$GP\\x";
        let expected: &[u8] =
            b"junk\\s:1*00\\|$GPGGA,1*00|\\s:x*31\\\\c:1*00\\!AIVDM,x|$GPRMC\\x\\|$GPGGA|\\g:1$2\\$GP\\x|";
        for chunk in 1..=stream.len() {
            let mut framer = Framer::new();
            let (mut out, mut len) = ([0u8; 256], 0);
            {
                let mut keep = |item: Item<'_>| {
                    if let Item::Line(line) = item {
                        out[len..len + line.len()].copy_from_slice(line);
                        out[len + line.len()] = b'|';
                        len += line.len() + 1;
                    }
                };
                for part in stream.chunks(chunk) {
                    framer.feed(part, &mut keep);
                }
                framer.finish(&mut keep);
            }
            assert_eq!(&out[..len], expected);
        }
    }

    #[test]
    fn overlong_lines_are_counted() {
        let mut framer = Framer::new();
        let mut seen = 0;
        for _ in 0..MAX_LINE + 5 {
            framer.feed(b"a", |_| seen += 1);
        }
        assert_eq!(seen, 0);
        framer.feed(b"\n", |item| {
            assert_eq!(item, Item::TooLong(MAX_LINE + 5));
            seen += 1;
        });
        framer.finish(|_| seen += 1);
        assert_eq!(seen, 1);
    }

    const ACK: &[u8] = b"\xb5\x62\x05\x01\x02\x00\x06\x00\x0e\x37"; // UBX ACK-ACK of CFG-PRT
    const RTCM: &[u8] = b"\xd3\x00\x02\x3e\xe0\x6d\x7f\x60"; // RTCM 3, message number 0x3EE
    /// SBF ReceiverTime (block 5914, revision 0).
    const SBF: &[u8] = b"$@\xbd\x13\x1a\x17\x18\x00\x70\x2f\xcb\x1c\x3f\x09\x19\x05\x17\x0e\x0b\x00\x12\x07\x00\x00";

    /// The items of `stream` fed in chunks of every size, alike, each written as text: a line or
    /// a bad frame's sync bytes in hex, a frame as its protocol, a bad frame with its kind.
    fn binary_items(stream: &[u8], expected: &[u8]) {
        for chunk in 1..=stream.len() {
            let mut framer = Framer::with_binary_frames();
            let (mut out, mut len) = ([0u8; 512], 0);
            {
                let mut put = |text: &[u8]| {
                    out[len..len + text.len()].copy_from_slice(text);
                    len += text.len();
                };
                let mut keep = |item: Item<'_>| {
                    match item {
                        Item::Line(line) => put(line),
                        Item::TooLong(_) => put(b"too long"),
                        Item::Frame(protocol, frame) => {
                            let first = match protocol {
                                Protocol::Ubx => ACK[0],
                                Protocol::Sbf => SBF[0],
                                Protocol::Unicore => 0xAA,
                                _ => RTCM[0],
                            };
                            assert_eq!(frame[0], first);
                            put(protocol.name().as_bytes());
                        }
                        Item::BadFrame(protocol, error, sync) => {
                            assert_eq!(sync.len(), protocol.sync_len());
                            put(protocol.name().as_bytes());
                            put(b" ");
                            put(error.kind().as_bytes());
                        }
                    }
                    put(b"|");
                };
                for part in stream.chunks(chunk) {
                    framer.feed(part, &mut keep);
                }
                framer.finish(&mut keep);
            }
            assert_eq!(&out[..len], expected, "chunks of {chunk}");
        }
    }

    #[test]
    fn binary_frames_between_and_inside_lines() {
        let mut stream = [0u8; 64];
        let parts: [&[u8]; 5] = [b"$GPGGA,1\r\n", ACK, b"$GP", RTCM, b"GGA\n$A"];
        let mut len = 0;
        for part in parts {
            stream[len..len + part.len()].copy_from_slice(part);
            len += part.len();
        }
        binary_items(&stream[..len], b"$GPGGA,1|ubx|$GP|rtcm3|GGA|$A|");
        assert_eq!(crc24q(&RTCM[..5]), 0x6D_7F60);
    }

    #[test]
    fn a_unicore_frame_between_sentences() {
        // pyunigps's test frame (tests/data/unicore): message id 65512, a 5-byte body, CRC-32 C1 FF D2 AA
        const UNI: &[u8] = b"\xaa\x44\xb5\x00\xe8\xff\x05\x00\x11\x22\x33\x44\x55\x66\x77\x88\x99\x00\x11\x22\x33\x44\x55\x66\x01\x02\x03\x04\x05\xc1\xff\xd2\xaa";
        assert_eq!(crc32(&UNI[..29]), 0xAAD2_FFC1);
        assert_eq!(crc32(b""), 0);
        let mut stream = [0u8; 80];
        let len = [&b"$A\n"[..], UNI, b"$B\n"].iter().fold(0, |at, part| {
            stream[at..at + part.len()].copy_from_slice(part);
            at + part.len()
        });
        binary_items(&stream[..len], b"$A|unicore|$B|");
        // NovAtel's AA 44 12, AA 44 AA, AA 44 at the end: no frame, the third sync byte checked as it comes
        binary_items(b"$A\n\xaa\x44\x12\x1c\x2a$B\n", b"$A|\xaa\x44\x12\x1c\x2a|$B|");
        let len = [&b"\xaa\x44\xaa\x44"[..], UNI, b"\xaa\x44"].iter().fold(0, |at, part| {
            stream[at..at + part.len()].copy_from_slice(part);
            at + part.len()
        });
        binary_items(&stream[..len], b"\xaa\x44\xaa\x44|unicore|\xaa\x44|");
    }

    #[test]
    fn a_bad_frame_is_reported_and_what_it_held_read_again() {
        // a bad checksum; a frame cut short by a sentence, then by the stream's end
        binary_items(
            b"\xb5\x62\x05\x01\x02\x00\x06\x00\x0e\x00$A\n",
            b"ubx bad_checksum|\x05\x01\x02\x00\x06\x00\x0e\x00|$A|",
        );
        binary_items(b"\xb5\x62\x05\x01\x02\x00\x06$A,1\n", b"ubx bad_checksum|\x05\x01\x02\x00\x06|$A,1|");
        binary_items(b"$A\n\xd3\x00\x05\x01", b"$A|rtcm3 cut|\x00\x05\x01|");
        // a frame inside a bad one; sync bytes that start no frame; a lone sync byte at the end
        binary_items(
            b"\xb5\x62\x01\x02\x03\x00\xb5\x62\x05\x01\x02\x00\x06\x00\x0e\x37$A",
            b"ubx bad_checksum|\x01\x02\x03\x00|ubx|$A|",
        );
        binary_items(
            b"\xb5\x00\xd3\xff\xb5\xb5\x62\x05\x01\x02\x00\x06\x00\x0e\x37\xd3",
            b"\xb5\x00\xd3\xff\xb5|ubx|\xd3|",
        );
        // no frame inside a TAG block
        binary_items(b"\\s:\xb5\x62*00\\$A", b"\\s:\xb5\x62*00\\$A|");
    }

    #[test]
    fn sbf_blocks_beside_sentences() {
        // "$@" starts a block, any other '$' a sentence; its CRC wrong; a length under its header's
        let mut stream = [0u8; 64];
        let parts: [&[u8]; 4] = [b"$GPGGA,1", SBF, b"$GP\n", SBF];
        let mut len = 0;
        for part in parts {
            stream[len..len + part.len()].copy_from_slice(part);
            len += part.len();
        }
        binary_items(&stream[..len], b"$GPGGA,1|sbf|$GP|sbf|");
        binary_items(b"$@\xbd\x13\x1a\x17\x0c\x00ab$A,1\n", b"sbf bad_checksum|\xbd\x13\x1a\x17\x0c\x00ab|$A,1|");
        binary_items(b"$@\x01\x02\x03\x04\x04\x00$A\n", b"sbf too_short|\x01\x02\x03\x04\x04\x00|$A|");
        assert_eq!(crc16_ccitt(&SBF[4..]), 0x13BD);
        let framing = Protocol::Sbf.framing();
        let mut identity = framing.identity_of(SBF);
        assert_eq!(identity.next(), Some(("number", Some(5914))));
        assert_eq!(identity.next(), Some(("revision", Some(0))));
    }

    #[test]
    fn a_frame_longer_than_the_buffer_is_reported() {
        // UBX, payload length 0x0800: 2,056 bytes in all
        binary_items(b"\xb5\x62\x01\x02\x00\x08ab", b"ubx too_long|\x01\x02\x00\x08ab|");
        // what a break's NUL bytes after a sync make (its checksum would be NULs too)
        binary_items(b"\xb5\x62\0\0\0\0\0\0$A", b"ubx nul_header|\0\0\0\0\0\0|$A|");
    }
}
