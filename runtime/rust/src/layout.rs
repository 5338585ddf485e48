//! What every generated sentence layout provides, the generic form of sentences the spec
//! does not describe, and the command builders' checked serialization.

use core::fmt::{self, Write};

use super::error::{Error, Message, ProblemKind, Problems};
use super::fast::{FastReader, Read, Unsure};
use super::frame::{is_command_word, is_standard_address, talker_length, Fields, Frame, Shape, MAX_LINE};
use super::types::Checksum;
use super::write::{
    write_json_str, write_sentence, write_sentence_with, write_words_json, ByteWriter, Discard, FieldSink, JsonEscape,
    JsonFields, Latin1Bytes, SameUpper, WireWriter,
};

/// How a sentence is framed and addressed.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Framing {
    /// `$`, a talker ID and the sentence id: `$GPGGA,…*hh`.
    Standard,
    /// `!`, a talker ID and the sentence id: an encapsulation sentence, `!AIVDM,…*hh`.
    Encapsulated,
    /// `$` and a fixed proprietary address: `$PSTMSETPAR,…*hh`.
    Proprietary(&'static str),
    /// A text command (ComNav): its command word and arguments separated by single spaces, no
    /// `$`, no checksum, matched ignoring case.
    Text(&'static str),
}

impl Framing {
    /// The start delimiter: `$`, `!` for an encapsulation sentence, `""` for a text command.
    pub const fn start(self) -> &'static str {
        match self {
            Self::Encapsulated => "!",
            Self::Text(_) => "",
            Self::Standard | Self::Proprietary(_) => "$",
        }
    }
}

/// A member of a layout's `fields` object, in wire order: what reading decode's JSON back into
/// wire fields looks for (`Layout::fields_from_json`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum JsonMember {
    /// A field: its key and how many wire fields it takes.
    Field(&'static str, usize),
    /// An optional trailing field, left out of the object when it is not on the wire.
    Optional(&'static str, usize),
    /// A group of one field: an array of its values.
    Values(&'static str, usize),
    /// A group of several fields: an array of objects with these members.
    Entries(&'static str, &'static [(&'static str, usize)]),
}

/// What a sentence is for.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Kind {
    /// A standard NMEA sentence.
    Standard,
    /// A command, host to receiver.
    Command,
    /// The receiver's answer to a command.
    Reply,
    /// A proprietary sentence the receiver sends on its own.
    Output,
}

/// What a reply to a command reports (see `Sentence::reply_to`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ReplyOutcome {
    /// The command was carried out, or here is what it asked for.
    Ok,
    /// The receiver refused the command or failed to carry it out.
    Error,
}

impl ReplyOutcome {
    /// `Ok` when `ok`, else `Error`.
    pub const fn judged(ok: bool) -> Self {
        if ok {
            Self::Ok
        } else {
            Self::Error
        }
    }
}

/// One layout of a sentence (a struct generated from the spec, e.g. `Gga`).
pub trait Layout<'a>: Sized {
    /// The sentence id, e.g. `"GGA"`.
    const SENTENCE: &'static str;
    /// The variant id, `None` for the main layout.
    const VARIANT: Option<&'static str>;
    /// How the sentence is framed and addressed.
    const FRAMING: Framing;
    /// How the layout's fields are counted.
    const SHAPE: Shape;
    /// A text command's fields and the words each takes: the keys of its lossless JSON, which
    /// shows the words as written.
    const WORDS: &'static [(&'static str, usize)] = &[];
    /// The members of its `fields` object in decode's JSON.
    const JSON: &'static [JsonMember];

    /// Decodes the fields after the address; the error names the field at fault.
    fn parse_fields(fields: Fields<'a>, checksum: Checksum) -> Result<Self, Error<'a>>;

    /// [`Layout::parse_fields`] on the fast path of [`parse`](crate::parse): fills `self`, the
    /// layout's default struct, from the fields of a sentence in its usual frame
    /// ([`FastReader::frame`]) whose count fits the layout ([`FastReader::shape`] gave `repeats`
    /// and `extra`), exactly as `parse_fields` would decode them; or [`Unsure`] when the general
    /// path must decide (`self` is then half filled). A text command has no fast reader.
    fn read_fast(&mut self, fields: FastReader<'a>, repeats: usize, extra: usize) -> Read<()> {
        let _ = (fields, repeats, extra);
        Err(Unsure)
    }

    /// The talker ID (`GP`, `GN`, …) of a standard sentence; empty for the others.
    fn talker(&self) -> &'a str {
        ""
    }

    /// How the checksum is written ([`Checksum::None`] for a text command).
    fn checksum(&self) -> Checksum {
        Checksum::None
    }

    /// A text command as received, written back as it is while its words still match the
    /// fields ignoring case.
    fn as_received(&self) -> Option<&'a str> {
        None
    }

    /// Writes every field after the address into `sink`, in wire order: the wire (each field
    /// preceded by `,`, a space in a text command) or the `fields` object of the tools' JSON.
    fn visit<S: FieldSink>(&self, sink: &mut S) -> fmt::Result;

    /// Writes every field after the address, each preceded by `,` (a space in a text command).
    fn write_fields<W: Write + ?Sized>(&self, w: &mut WireWriter<'_, W>) -> fmt::Result {
        self.visit(w)
    }

    /// [`Layout::write_fields`] into a byte buffer without `fmt`, when the text is ASCII;
    /// `None`: leave it to `write_fields`.
    fn put_fields(&self, w: &mut ByteWriter<'_>) -> Option<()> {
        self.visit(w).ok()
    }

    /// Writes the members of the `fields` object of the tools' JSON.
    fn write_json_fields<W: Write + ?Sized>(&self, j: &mut JsonFields<'_, W>) -> fmt::Result {
        self.visit(j)
    }

    /// Appends the wire fields described by a `fields` object of decode's lossless JSON.
    #[cfg(feature = "std")]
    fn fields_from_json(fields: &super::json::Value, out: &mut super::json::WireFields) -> Result<(), Error<'static>> {
        use super::json::list;
        for member in Self::JSON {
            match *member {
                JsonMember::Field(key, width) => out.member(fields, key, width)?,
                JsonMember::Optional(key, width) => out.optional(fields, key, width)?,
                JsonMember::Values(key, width) => {
                    for value in list(fields, key)? {
                        out.value(value, width)?;
                    }
                }
                JsonMember::Entries(key, members) => {
                    for entry in list(fields, key)? {
                        for &(key, width) in members {
                            out.member(entry, key, width)?;
                        }
                    }
                }
            }
        }
        Ok(())
    }

    /// Parses a whole line (a trailing LF or CR LF is allowed) that must be this sentence.
    fn parse_line(line: &'a str) -> Result<Self, Error<'a>> {
        let line = strip_line_ending(line.as_bytes());
        let frame = match Self::FRAMING {
            Framing::Text(_) => Frame::parse_text(line)?,
            _ => Frame::parse(line)?,
        };
        let address = frame.address;
        let fits = match Self::FRAMING {
            Framing::Standard | Framing::Encapsulated => {
                is_standard_address(frame.start, address)
                    && frame.start == Self::FRAMING.start()
                    && address.len() == talker_length(Self::SENTENCE) + Self::SENTENCE.len()
                    && address.ends_with(Self::SENTENCE)
            }
            Framing::Proprietary(expected) => frame.start == "$" && address == expected,
            Framing::Text(word) => is_command_word(address.as_bytes(), word),
        };
        if !fits {
            let message = Message::WrongSentence { address, expected: Self::SENTENCE };
            return Err(Error::new(Some(address), message));
        }
        Self::parse_fields(frame.fields, frame.checksum)
    }

    /// Writes the sentence text, checksum included unless it is [`Checksum::None`] (a text
    /// command: its words); no line ending. The text is put together on the stack and written
    /// at once (see [`Layout::serialize_into`]), or written piece by piece when that cannot be.
    fn write_sentence<W: Write + ?Sized>(&self, out: &mut W) -> fmt::Result {
        let mut buf = [0; MAX_LINE];
        match self.put_sentence(&mut buf) {
            Some(len) => out.write_str(core::str::from_utf8(&buf[..len]).map_err(|_| fmt::Error)?),
            None => self.write_sentence_with(out, &Problems::new()),
        }
    }

    /// The sentence text, what `Display` writes (no line ending), put at the start of `buf`, as
    /// C's `nmea_serialize` does: its length, or `None` when `buf` cannot hold it. Without the
    /// `fmt` machinery for an ASCII text (every parsed `$` sentence), with it for any other.
    fn serialize_into(&self, buf: &mut [u8]) -> Option<usize> {
        if let Some(len) = self.put_sentence(buf) {
            return Some(len);
        }
        let mut w = ByteWriter::new(buf);
        self.write_sentence_with(&mut w, &Problems::new()).ok()?;
        Some(w.len())
    }

    /// [`Layout::serialize_into`] without `fmt`: `None` when the text is not all ASCII, a text
    /// command, or longer than `buf`.
    #[doc(hidden)]
    fn put_sentence(&self, buf: &mut [u8]) -> Option<usize> {
        let mut w = ByteWriter::new(buf);
        w.str(Self::FRAMING.start())?;
        match Self::FRAMING {
            Framing::Standard | Framing::Encapsulated => {
                w.str(self.talker())?;
                w.str(Self::SENTENCE)?;
            }
            Framing::Proprietary(address) => w.str(address)?,
            Framing::Text(_) => return None,
        }
        self.put_fields(&mut w)?;
        w.finish(self.checksum())
    }

    /// [`Layout::write_sentence`] for a sentence lenient parsing kept: the text of each field
    /// it left empty is written back (a text command has none).
    fn write_sentence_with<W: Write + ?Sized>(&self, out: &mut W, problems: &Problems<'_>) -> fmt::Result {
        let checksum = self.checksum();
        match Self::FRAMING {
            Framing::Standard | Framing::Encapsulated => write_sentence_with(
                out,
                Self::FRAMING.start(),
                [self.talker(), Self::SENTENCE],
                checksum,
                problems,
                |w| self.write_fields(w),
            ),
            Framing::Proprietary(address) => {
                write_sentence_with(out, "$", [address, ""], checksum, problems, |w| self.write_fields(w))
            }
            Framing::Text(word) => match self.received_text(word) {
                Some(line) => out.write_str(line),
                None => self.write_words(word, out),
            },
        }
    }

    /// A text command's words in the spec's spelling: the command word, then each field after a
    /// space.
    #[doc(hidden)]
    fn write_words<W: Write + ?Sized>(&self, word: &str, out: &mut W) -> fmt::Result {
        let mut w = WireWriter::words(out);
        w.write_str(word)?;
        self.write_fields(&mut w)?;
        w.finish()
    }

    /// The text command as received, when its upper-cased words equal those of the fields (the
    /// command is then written back as it came).
    #[doc(hidden)]
    fn received_text(&self, word: &str) -> Option<&'a str> {
        let received = self.as_received()?;
        let mut compare = SameUpper::new(received);
        (self.write_words(word, &mut compare).is_ok() && compare.finished()).then_some(received)
    }

    /// Writes the tools' JSON line (`values`: decoded values instead of the lossless texts).
    fn write_json<W: Write + ?Sized>(&self, out: &mut W, values: bool) -> fmt::Result {
        self.write_json_with(out, values, &Problems::new())
    }

    /// [`Layout::write_json`] for a sentence lenient parsing kept: `"problems"` follows
    /// `"fields"`, and the checksum is that of the sentence with the problem texts put back.
    fn write_json_with<W: Write + ?Sized>(&self, out: &mut W, values: bool, problems: &Problems<'_>) -> fmt::Result {
        let (address, talker) = match Self::FRAMING {
            Framing::Text(word) => return self.write_command_json(word, out, values),
            Framing::Proprietary(address) => ([address, ""], None),
            Framing::Standard | Framing::Encapsulated => ([self.talker(), Self::SENTENCE], Some(self.talker())),
        };
        let mut sink = Discard;
        let mut body = WireWriter::new(&mut sink).with_problems(problems);
        body.write_str(address[0])?;
        body.write_str(address[1])?;
        self.write_fields(&mut body)?;
        let sum = body.checksum();
        out.write_str("{\"ok\":true,\"start\":\"")?;
        out.write_str(Self::FRAMING.start())?;
        out.write_str("\",\"address\":\"")?;
        JsonEscape(&mut *out).write_str(address[0])?;
        JsonEscape(&mut *out).write_str(address[1])?;
        out.write_str("\",\"talker\":")?;
        match talker {
            Some(talker) => write_json_str(out, talker)?,
            None => out.write_str("null")?,
        }
        self.write_json_fields_object(out, values)?;
        write_problems_json(out, problems, self.checksum(), sum)?;
        write_checksum_json(out, self.checksum(), sum)
    }

    /// The JSON line of a text command: start `""`, the command word as written, the words as
    /// written (`values`: the decoded values), no checksum.
    #[doc(hidden)]
    fn write_command_json<W: Write + ?Sized>(&self, word: &str, out: &mut W, values: bool) -> fmt::Result {
        let received = self.received_text(word);
        let address = received.map_or(word, |line| line.split(' ').next().unwrap_or(line));
        out.write_str("{\"ok\":true,\"start\":\"\",\"address\":")?;
        write_json_str(out, address)?;
        out.write_str(",\"talker\":null")?;
        match received {
            Some(line) if !values => {
                write_sentence_json(out, Self::SENTENCE, Self::VARIANT)?;
                out.write_str(",\"fields\":{")?;
                write_words_json(out, line, Self::WORDS)?;
                out.write_char('}')?;
            }
            _ => self.write_json_fields_object(out, values)?,
        }
        out.write_str(",\"checksum\":null}")
    }

    /// `"sentence"`, `"variant"` and the `"fields"` object of the JSON line.
    #[doc(hidden)]
    fn write_json_fields_object<W: Write + ?Sized>(&self, out: &mut W, values: bool) -> fmt::Result {
        write_sentence_json(out, Self::SENTENCE, Self::VARIANT)?;
        out.write_str(",\"fields\":")?;
        let mut fields = JsonFields::begin(&mut *out, values)?;
        self.write_json_fields(&mut fields)?;
        fields.end()
    }

    /// The tools' JSON line (`values`: decoded values instead of the lossless texts).
    #[cfg(feature = "std")]
    fn to_json(&self, values: bool) -> std::string::String {
        let mut out = std::string::String::new();
        let _ = self.write_json(&mut out, values);
        out
    }
}

fn write_sentence_json<W: Write + ?Sized>(out: &mut W, sentence: &str, variant: Option<&str>) -> fmt::Result {
    write!(out, ",\"sentence\":\"{sentence}\",\"variant\":")?;
    match variant {
        Some(variant) => write!(out, "\"{variant}\""),
        None => out.write_str("null"),
    }
}

/// Writes `,"problems":[...]` (nothing when there are none): a checksum `sum` written as one
/// digit in style `checksum` (the short_checksum problem, what strict parsing refuses), then
/// `problems`.
pub(crate) fn write_problems_json<W: Write + ?Sized>(
    out: &mut W,
    problems: &Problems<'_>,
    checksum: Checksum,
    sum: u8,
) -> fmt::Result {
    let Some(([digit, _], 1)) = checksum.digits(sum) else {
        return problems.write_json(out);
    };
    let digit = [digit];
    let text = core::str::from_utf8(&digit).map_err(|_| fmt::Error)?;
    out.write_str(",\"problems\":[{\"kind\":\"")?;
    out.write_str(ProblemKind::ShortChecksum.as_str())?;
    out.write_str("\",\"field\":null,\"name\":null,\"text\":")?;
    write_json_str(out, text)?;
    out.write_str(",\"message\":")?;
    super::write::write_json_display(out, &Message::BadChecksum { text })?;
    out.write_char('}')?;
    for problem in problems.iter() {
        out.write_char(',')?;
        problem.write_json(out)?;
    }
    out.write_char(']')
}

fn write_checksum_json<W: Write + ?Sized>(out: &mut W, checksum: Checksum, sum: u8) -> fmt::Result {
    match checksum.digits(sum) {
        Some(([a, _], 1)) => write!(out, ",\"checksum\":\"{}\"}}", char::from(a)),
        Some(([a, b], _)) => write!(out, ",\"checksum\":\"{}{}\"}}", char::from(a), char::from(b)),
        None if checksum == Checksum::Empty => out.write_str(",\"checksum\":\"\"}"),
        None => out.write_str(",\"checksum\":null}"),
    }
}

/// A buffer this long always holds what a command builder writes: the longest line and CR LF.
pub const BUILD_CAPACITY: usize = MAX_LINE + 2;

/// What the command builders (`to_bytes` of each sentence struct) share: writes the line with
/// `write` into `buf` in one pass (each character as one byte, Latin-1), reads it back the way
/// a receiver would (framing, then `check`, the layout's own parser) and appends CR LF. The
/// error is the parser's, naming the field at fault; `buffer_too_small` when `buf` cannot hold
/// the line (what did fit may then have been written).
pub fn build<'b>(
    buf: &'b mut [u8],
    framing: Framing,
    write: impl FnOnce(&mut Latin1Bytes<'_>) -> fmt::Result,
    check: impl FnOnce(Fields<'b>, Checksum) -> Result<(), Error<'b>>,
) -> Result<&'b [u8], Error<'b>> {
    let capacity = buf.len();
    let mut out = Latin1Bytes::new(buf);
    let written = write(&mut out);
    let length = out.needed();
    if length > MAX_LINE {
        return Err(Error::too_long(length));
    }
    let needed = length + 2;
    let too_small = || Error::new(None, Message::BufferTooSmall { needed, capacity });
    if needed > capacity {
        return Err(too_small());
    }
    written.map_err(|_| too_small())?;
    buf[length..needed].copy_from_slice(b"\r\n");
    let buf: &'b [u8] = buf;
    let line = &buf[..length];
    let frame = match framing {
        Framing::Text(_) => Frame::parse_text(line)?,
        _ => Frame::parse(line)?,
    };
    check(frame.fields, frame.checksum)?;
    Ok(&buf[..needed])
}

/// Drops one trailing LF or CR LF.
pub fn strip_line_ending(line: &[u8]) -> &[u8] {
    match line {
        [rest @ .., b'\r', b'\n'] | [rest @ .., b'\n'] => rest,
        _ => line,
    }
}

/// A well-formed sentence the spec does not describe: its address and raw fields.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Generic<'a> {
    /// `"$"` or `"!"`.
    pub start: &'a str,
    /// The address (talker and formatter, or a proprietary address).
    pub address: &'a str,
    /// The fields as received.
    pub fields: Fields<'a>,
    /// How the checksum is written.
    pub checksum: Checksum,
}

impl<'a> Generic<'a> {
    /// The generic form of a framed line.
    pub const fn from_frame(frame: Frame<'a>) -> Self {
        Self { start: frame.start, address: frame.address, fields: frame.fields, checksum: frame.checksum }
    }

    fn write_body<W: Write + ?Sized>(&self, w: &mut WireWriter<'_, W>) -> fmt::Result {
        w.write_str(self.address)?;
        if !self.fields.is_empty() {
            w.write_char(',')?;
            w.write_str(self.fields.as_str())?;
        }
        Ok(())
    }

    /// Writes the sentence text; no line ending.
    pub fn write_sentence<W: Write + ?Sized>(&self, out: &mut W) -> fmt::Result {
        let mut buf = [0; MAX_LINE];
        match self.put_sentence(&mut buf) {
            Some(len) => out.write_str(core::str::from_utf8(&buf[..len]).map_err(|_| fmt::Error)?),
            None => write_sentence(out, self.start, ["", ""], self.checksum, |w| self.write_body(w)),
        }
    }

    /// The sentence text put at the start of `buf` (see [`Layout::serialize_into`]): its
    /// length, or `None` when `buf` cannot hold it.
    pub fn serialize_into(&self, buf: &mut [u8]) -> Option<usize> {
        if let Some(len) = self.put_sentence(buf) {
            return Some(len);
        }
        let mut w = ByteWriter::new(buf);
        write_sentence(&mut w, self.start, ["", ""], self.checksum, |w| self.write_body(w)).ok()?;
        Some(w.len())
    }

    /// [`Generic::serialize_into`] without `fmt`: `None` when the text is not all ASCII.
    #[doc(hidden)]
    pub fn put_sentence(&self, buf: &mut [u8]) -> Option<usize> {
        if self.start.len() != 1 {
            return None; // `finish` sums what follows a start character
        }
        let mut w = ByteWriter::new(buf);
        w.str(self.start)?;
        w.str(self.address)?;
        if !self.fields.is_empty() {
            w.str(",")?;
            w.str(self.fields.as_str())?;
        }
        w.finish(self.checksum)
    }

    /// Writes the tools' JSON line: the fields as an array of strings.
    pub fn write_json<W: Write + ?Sized>(&self, out: &mut W) -> fmt::Result {
        let mut sink = Discard;
        let mut body = WireWriter::new(&mut sink);
        self.write_body(&mut body)?;
        let sum = body.checksum();
        out.write_str("{\"ok\":true,\"start\":")?;
        write_json_str(out, self.start)?;
        out.write_str(",\"address\":")?;
        write_json_str(out, self.address)?;
        out.write_str(",\"talker\":null,\"sentence\":null,\"variant\":null,\"fields\":[")?;
        for (i, field) in self.fields.iter().enumerate() {
            if i > 0 {
                out.write_char(',')?;
            }
            write_json_str(out, field)?;
        }
        out.write_char(']')?;
        write_problems_json(out, &Problems::new(), self.checksum, sum)?;
        write_checksum_json(out, self.checksum, sum)
    }
}

impl fmt::Display for Generic<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        self.write_sentence(f)
    }
}
