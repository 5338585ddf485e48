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
//! The framer holds one line in a fixed array: no allocation.

use super::frame::MAX_LINE;

/// One framed item of the stream.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Item<'a> {
    /// A line (without its line ending), at most [`MAX_LINE`] bytes.
    Line(&'a [u8]),
    /// A line over [`MAX_LINE`] bytes: its length (the bytes were not kept).
    TooLong(usize),
}

/// Cuts bytes fed in any chunks into lines and overlong lines (see the module documentation).
#[derive(Clone, Debug)]
pub struct Framer {
    line: [u8; MAX_LINE],
    /// Bytes of the current line, counted (also past [`MAX_LINE`]).
    length: usize,
    /// The current line was handed out: start a new one at the next byte.
    handed: bool,
    /// The start character (`$`/`!`) the next line begins with, once the current one is handed.
    pending: Option<u8>,
    /// Where the current line is as to TAG blocks.
    tag: TagState,
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
    /// A framer at the start of a stream.
    pub const fn new() -> Self {
        Self { line: [0; MAX_LINE], length: 0, handed: false, pending: None, tag: TagState::Outside }
    }

    /// Takes one byte; the item it completes, if any (valid until the next call).
    pub fn push(&mut self, byte: u8) -> Option<Item<'_>> {
        self.restart();
        match byte {
            b'\r' | b'\n' => return self.end_line(),
            // opens a block (at the start, or right after one), or closes the open one
            b'\\' if self.length == 0 || self.tag != TagState::Outside => {
                self.tag = if self.tag == TagState::InBlock { TagState::AfterBlock } else { TagState::InBlock };
            }
            b'$' | b'!' if self.tag == TagState::Outside => {
                self.pending = Some(byte);
                return self.end_line();
            }
            // the sentence after the blocks, or whatever else follows them
            _ if self.tag == TagState::AfterBlock => self.tag = TagState::Outside,
            _ => {}
        }
        if let Some(slot) = self.line.get_mut(self.length) {
            *slot = byte;
        }
        self.length = self.length.saturating_add(1);
        None
    }

    /// Feeds a chunk of the stream; `each` gets every item it completes, in order.
    pub fn feed(&mut self, data: &[u8], mut each: impl FnMut(Item<'_>)) {
        for &byte in data {
            if let Some(item) = self.push(byte) {
                each(item);
            }
        }
    }

    /// The last line, when the stream ended without a line ending; the framer is then at the
    /// start of a new stream.
    pub fn finish(&mut self) -> Option<Item<'_>> {
        self.restart();
        self.end_line()
    }

    fn restart(&mut self) {
        if self.handed {
            self.handed = false;
            self.length = 0;
            if let Some(start) = self.pending.take() {
                self.line[0] = start;
                self.length = 1;
            }
        }
    }

    fn end_line(&mut self) -> Option<Item<'_>> {
        self.handed = true;
        self.tag = TagState::Outside;
        match self.length {
            0 => None,
            length if length <= MAX_LINE => Some(Item::Line(&self.line[..length])),
            length => Some(Item::TooLong(length)),
        }
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
            }
            n += 1;
        };
        for chunk in chunks {
            framer.feed(chunk, &mut keep);
        }
        if let Some(item) = framer.finish() {
            keep(item);
        }
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
                if let Some(item) = framer.finish() {
                    keep(item);
                }
            }
            assert_eq!(&out[..len], expected);
        }
    }

    #[test]
    fn overlong_lines_are_counted() {
        let mut framer = Framer::new();
        let mut seen = None;
        for _ in 0..MAX_LINE + 5 {
            assert!(framer.push(b'a').is_none());
        }
        if let Some(item) = framer.push(b'\n') {
            seen = Some(item == Item::TooLong(MAX_LINE + 5));
        }
        assert_eq!(seen, Some(true));
        assert!(framer.finish().is_none());
    }
}
