//! TAG blocks (NMEA 0183 4.00, IEC 61162-450): `\code:value,...*hh\` before a sentence, or on a
//! line of their own. A parsed line keeps the text of its blocks ([`TagBlocks`], checked,
//! borrowed from the line), which is written back as it is; [`TagBlocks::iter`] and
//! [`TagBlock::params`] read the parameters out of it, [`write_tag_block`] writes a new block.
//! The codes the spec names and their value types come from the generated [`TagCode`] table
//! (`Layouts::TAG_CODES`). Nothing here allocates.

use core::fmt::{self, Write};

use super::error::{Error, Message};
use super::frame::{checksum, hex_value};
use super::write::write_json_str;

/// The value type of a code the spec names (spec/tag_block.yaml).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum TagType {
    /// 1 to 18 digits, kept as sent (`c`: UNIX time, `n`: line count, ...).
    Integer,
    /// Sentence number, count and group id joined by `-` (`g`).
    Group,
    /// Anything but `,`, `*` and `\` (`s`: source, `d`: destination, ...).
    Text,
}

impl TagType {
    /// What a value of the type must look like, as errors say it; `None` for a text.
    const fn form(self) -> Option<&'static str> {
        match self {
            Self::Integer => Some("digits"),
            Self::Group => Some("n-m-id"),
            Self::Text => None,
        }
    }

    /// An empty value fits any type; an integer is 1 to 18 digits, a group three of them joined
    /// by `-`.
    fn fits(self, value: &str) -> bool {
        let digits = |t: &str| (1..=18).contains(&t.len()) && t.bytes().all(|b| b.is_ascii_digit());
        match self {
            _ if value.is_empty() => true,
            Self::Text => true,
            Self::Integer => digits(value),
            Self::Group => value.split('-').count() == 3 && value.split('-').all(digits),
        }
    }
}

/// A code the spec names.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct TagCode {
    /// As written before the `:`.
    pub code: &'static str,
    /// The spec's id: `"time"`, `"source"`, ...
    pub id: &'static str,
    /// The spec's name.
    pub name: &'static str,
    /// Its value type.
    pub kind: TagType,
}

/// What a line holds before its sentence, as received: its TAG blocks one after another, then
/// the stray `$` of a start sent more than once (an ST Teseo's `$$GNGSA,…`: the first `$`; the
/// checksum is the sentence's own). Empty: nothing.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct TagBlocks<'a> {
    text: &'a str,
    alone: bool,
}

impl<'a> TagBlocks<'a> {
    /// No TAG blocks.
    pub const NONE: Self = Self { text: "", alone: false };

    /// The text before the sentence: the blocks, backslashes included, and the stray `$`.
    pub const fn as_str(&self) -> &'a str {
        self.text
    }

    /// Whether the line had nothing before its sentence.
    pub const fn is_empty(&self) -> bool {
        self.text.is_empty()
    }

    /// The blocks' text, backslashes included (a block ends with `\`, so the stray `$` are
    /// what follows the last one).
    pub fn blocks_str(&self) -> &'a str {
        self.text.trim_end_matches('$')
    }

    /// The `$` sent before the sentence's own start (`$$GNGSA`: `"$"`); empty for none.
    pub fn stray(&self) -> &'a str {
        &self.text[self.blocks_str().len()..]
    }

    /// Whether the line holds TAG blocks only (its sentence is then an empty generic one).
    pub const fn alone(&self) -> bool {
        self.alone
    }

    /// Each block in turn.
    pub fn iter(&self) -> impl Iterator<Item = TagBlock<'a>> {
        // A checked block: `\`, its parameters, `*`, two digits, `\`.
        self.blocks_str().split_terminator('\\').filter(|part| !part.is_empty()).map(|inner| {
            let (params, checksum) = inner.rsplit_once('*').unwrap_or((inner, ""));
            TagBlock { params, checksum }
        })
    }

    /// The value of the first parameter with `code`, or `None`.
    pub fn get(&self, code: &str) -> Option<&'a str> {
        self.iter().flat_map(|block| block.params()).find(|&(c, _)| c == code).map(|(_, value)| value)
    }

    /// Checks the TAG blocks at the start of `line` (which starts with `\\`, or with the `$$`
    /// of a start sent more than once), and takes the stray `$` after them: what comes before
    /// the sentence, and the rest of the line, a `$`/`!` sentence or nothing.
    pub fn read(line: &'a [u8], codes: &[TagCode]) -> Result<(Self, &'a [u8]), Error<'a>> {
        let error = |message| Err(Error::new(None, message));
        if let Some(offset) = line.iter().position(|b| !(0x20..=0x7e).contains(b)) {
            return error(Message::NotPrintable { byte: line[offset], offset });
        }
        let Ok(text) = core::str::from_utf8(line) else {
            return error(Message::NotPrintable { byte: line[0], offset: 0 });
        };
        let mut rest = text;
        while let Some(after) = rest.strip_prefix('\\') {
            let Some((inner, next)) = after.split_once('\\') else {
                return error(Message::TagUnclosed);
            };
            let Some((body, sent)) = inner.split_once('*') else {
                return error(Message::TagNoChecksum { text: inner });
            };
            let b = sent.as_bytes();
            let one_case = !(b.iter().any(u8::is_ascii_uppercase) && b.iter().any(u8::is_ascii_lowercase));
            if b.len() != 2 || !b.iter().all(u8::is_ascii_hexdigit) || !one_case {
                return error(Message::TagBadChecksum { text: sent });
            }
            let computed = checksum(body.as_bytes());
            if hex_value(b[0]) << 4 | hex_value(b[1]) != computed {
                return error(Message::TagChecksumMismatch { sent, computed });
            }
            for param in body.split(',') {
                let Some((code, value)) = param.split_once(':') else {
                    return error(Message::TagBadParameter { text: param });
                };
                if code.is_empty() || !code.bytes().all(|b| b.is_ascii_alphanumeric()) {
                    return error(Message::TagBadParameter { text: param });
                }
                if let Some(known) = codes.iter().find(|c| c.code == code) {
                    if let Some(form) = known.kind.form().filter(|_| !known.kind.fits(value)) {
                        return error(Message::TagBadValue { text: param, form });
                    }
                }
            }
            rest = next;
        }
        if !rest.is_empty() && !rest.starts_with(['$', '!']) {
            return error(Message::TagFollowed);
        }
        let stray = rest.bytes().take_while(|&b| b == b'$').count().saturating_sub(1);
        let rest = &rest[stray..];
        let blocks = &text[..text.len() - rest.len()];
        Ok((Self { text: blocks, alone: rest.is_empty() }, rest.as_bytes()))
    }

    /// The same blocks as those of a line that holds them only (`alone`) or not.
    #[cfg(feature = "std")]
    pub(crate) const fn with_alone(self, alone: bool) -> Self {
        Self { alone, ..self }
    }

    /// Writes the tools' members for what comes before the sentence: the `"tag_blocks"` array
    /// (when there are blocks, or nothing at all), then `"stray"` (when there is a stray `$`).
    pub fn write_json<W: Write + ?Sized>(&self, out: &mut W) -> fmt::Result {
        let stray = self.stray();
        if !stray.is_empty() {
            if !self.blocks_str().is_empty() {
                self.write_blocks_json(out)?;
                out.write_char(',')?;
            }
            out.write_str("\"stray\":")?;
            return write_json_str(out, stray);
        }
        self.write_blocks_json(out)
    }

    /// Writes the tools' `"tag_blocks"` array.
    fn write_blocks_json<W: Write + ?Sized>(&self, out: &mut W) -> fmt::Result {
        out.write_str("\"tag_blocks\":[")?;
        for (i, block) in self.iter().enumerate() {
            out.write_str(if i == 0 { "{\"params\":[" } else { ",{\"params\":[" })?;
            for (j, (code, value)) in block.params().enumerate() {
                out.write_str(if j == 0 { "{\"code\":" } else { ",{\"code\":" })?;
                write_json_str(out, code)?;
                out.write_str(",\"value\":")?;
                write_json_str(out, value)?;
                out.write_char('}')?;
            }
            write!(out, "],\"checksum\":\"{}\"}}", block.checksum)?;
        }
        out.write_char(']')
    }
}

impl fmt::Display for TagBlocks<'_> {
    /// The blocks as received.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.text)
    }
}

/// One TAG block of a line.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct TagBlock<'a> {
    params: &'a str,
    checksum: &'a str,
}

impl<'a> TagBlock<'a> {
    /// Its parameters, `(code, value)` as written, in wire order (unknown codes too).
    pub fn params(&self) -> impl Iterator<Item = (&'a str, &'a str)> {
        self.params.split(',').map(|param| param.split_once(':').unwrap_or((param, "")))
    }

    /// Its checksum as received (two hex digits, case kept).
    pub const fn checksum(&self) -> &'a str {
        self.checksum
    }
}

/// Writes one TAG block of `params` (`lower`: the checksum in lower case) at the start of `buf`,
/// checked as a received block is read: its length, or the error (`bad_tag_block`; `too_long`
/// when `buf` cannot hold it).
pub fn write_tag_block<'b>(
    buf: &'b mut [u8],
    params: &[(&str, &str)],
    lower: bool,
    codes: &[TagCode],
) -> Result<usize, Error<'b>> {
    let needed = 4 + params.iter().map(|(code, value)| 2 + code.len() + value.len()).sum::<usize>().max(1);
    if needed > buf.len() {
        return Err(Error::too_long(needed));
    }
    let mut end = 0;
    for (i, (code, value)) in params.iter().enumerate() {
        for part in [if i == 0 { "\\" } else { "," }, code, ":", value] {
            buf[end..end + part.len()].copy_from_slice(part.as_bytes());
            end += part.len();
        }
    }
    if params.is_empty() {
        buf[0] = b'\\';
        end = 1;
    }
    let sum = checksum(&buf[1..end]);
    let digits: &[u8; 16] = if lower { b"0123456789abcdef" } else { b"0123456789ABCDEF" };
    buf[end..end + 4].copy_from_slice(&[b'*', digits[usize::from(sum >> 4)], digits[usize::from(sum & 15)], b'\\']);
    let len = end + 4;
    match TagBlocks::read(&buf[..len], codes) {
        Ok((blocks, _)) if blocks.text.len() == len => Ok(len),
        Ok(_) => Err(Error::new(None, Message::TagParameterHolds)),
        Err(err) => Err(err),
    }
}

#[cfg(test)]
mod tests {
    use super::super::parse::tests::NoLayout;
    use super::super::parse::{parse_with, Layouts, Options};
    use super::super::write::ByteWriter;
    use super::*;

    const CODES: &[TagCode] = NoLayout::TAG_CODES;

    /// The error's message for `line` (written into `buf`).
    fn message<'b>(line: &[u8], buf: &'b mut [u8]) -> &'b str {
        let mut w = ByteWriter::new(buf);
        let _ = write!(w, "{}", TagBlocks::read(line, CODES).map(|_| ()).unwrap_err());
        let len = w.len();
        core::str::from_utf8(&buf[..len]).unwrap_or_default()
    }

    #[test]
    fn blocks_are_read_and_written_back() {
        let line = b"\\g:1-2-073874,q:u,s:r003669945,c:1241544035*16\\\\t:*4E\\$GPTST,12,abc*27";
        let parsed = parse_with::<NoLayout>(line, Options::default()).unwrap();
        assert_eq!(parsed.tag_blocks.as_str().len(), 54);
        assert!(!parsed.tag_blocks.alone());
        assert_eq!(parsed.tag_blocks.get("g"), Some("1-2-073874"));
        assert_eq!(parsed.tag_blocks.get("t"), Some(""));
        assert_eq!(parsed.tag_blocks.get("d"), None);
        let first = parsed.tag_blocks.iter().next().unwrap();
        assert_eq!(first.checksum(), "16");
        assert_eq!(first.params().nth(1), Some(("q", "u")));
        let mut buf = [0; 128];
        let len = parsed.serialize_into(&mut buf).unwrap();
        assert_eq!(&buf[..len], line);
        assert_eq!(parsed.serialize_into(&mut buf[..line.len() - 1]), None);

        let alone = parse_with::<NoLayout>(b"\\s:2573535,c:1671533231*08\\", Options::default()).unwrap();
        assert!(alone.tag_blocks.alone());
        let len = alone.serialize_into(&mut buf).unwrap();
        assert_eq!(&buf[..len], b"\\s:2573535,c:1671533231*08\\");
    }

    #[test]
    fn bad_blocks_say_why() {
        let buf = &mut [0; 128];
        assert_eq!(message(b"\\s:x*00\\", buf), "bad_tag_block: line: TAG block checksum is 00, computed 31");
        assert!(message(b"\\s:x*31", buf).ends_with("TAG block has no closing backslash"));
        assert!(message(b"\\s:x\\", buf).ends_with("TAG block \"s:x\" has no checksum"));
        assert!(
            message(b"\\s:x*3\\", buf).ends_with("TAG block checksum \"3\" is not two hex digits of one letter case")
        );
        assert!(message(b"\\sx*0B\\", buf).ends_with("TAG block parameter \"sx\" is not code:value"));
        assert!(message(b"\\*00\\", buf).ends_with("TAG block parameter \"\" is not code:value"));
        assert!(message(b"\\g:1-2*73\\", buf).ends_with("TAG block parameter \"g:1-2\": expected n-m-id"));
        assert!(message(b"\\s:x*31\\GPGGA", buf).ends_with("TAG block is followed by neither '$', '!' nor a TAG block"));
        assert!(message(b"\\s:\x01*48\\", buf).ends_with("byte 0x01 at offset 3 is not printable ASCII"));
    }

    #[test]
    fn a_block_is_built_from_parameters() {
        let mut buf = [0; 64];
        let len = write_tag_block(&mut buf, &[("s", "r003669945"), ("c", "1241544035")], false, CODES).unwrap();
        assert_eq!(&buf[..len], b"\\s:r003669945,c:1241544035*79\\");
        let err = write_tag_block(&mut buf, &[("c", "12a")], false, CODES).unwrap_err();
        assert_eq!(err.kind(), super::super::error::ErrorKind::BadTagBlock);
        assert!(write_tag_block(&mut [0; 8], &[("s", "r003669945")], false, CODES).is_err());
    }

    #[cfg(feature = "std")]
    #[test]
    fn the_json_round_trips() {
        use super::super::tools::{decode_json, encode_json};
        for line in [&b"\\s:r003669945,c:0241544035*78\\!GPXYZ,1*51"[..], b"\\s:x*31\\\\t:*4e\\"] {
            let json = decode_json::<NoLayout>(line, false);
            assert!(json.contains("\"tag_blocks\":[{\"params\":[{\"code\":\"s\""), "{json}");
            assert_eq!(encode_json::<NoLayout>(json.as_bytes()).as_bytes(), line);
        }
        assert_eq!(
            decode_json::<NoLayout>(b"\\s:x*31\\", false),
            r#"{"ok":true,"tag_blocks":[{"params":[{"code":"s","value":"x"}],"checksum":"31"}]}"#
        );
    }
}
