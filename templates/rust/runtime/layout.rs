//! What every generated sentence layout provides, and the generic form of sentences the spec
//! does not describe.

use core::fmt::{self, Write};

use super::error::{Error, Message};
use super::frame::{is_standard_address, Fields, Frame, Shape};
use super::types::Checksum;
use super::write::{write_json_str, write_sentence, Discard, JsonEscape, JsonFields, WireWriter};

/// One layout of a standard sentence (a struct generated from the spec, e.g. `Gga`).
pub trait Layout<'a>: Sized {
    /// The sentence id, e.g. `"GGA"`.
    const SENTENCE: &'static str;
    /// The variant id, `None` for the main layout.
    const VARIANT: Option<&'static str>;
    /// How the layout's fields are counted.
    const SHAPE: Shape;

    /// Decodes the fields after the address; the error names the field at fault.
    fn parse_fields(fields: Fields<'a>, checksum: Checksum) -> Result<Self, Error<'a>>;

    /// The talker ID (`GP`, `GN`, …).
    fn talker(&self) -> &'a str;

    /// How the checksum is written.
    fn checksum(&self) -> Checksum;

    /// Writes every field after the address, each preceded by `,`.
    fn write_fields<W: Write + ?Sized>(&self, w: &mut WireWriter<'_, W>) -> fmt::Result;

    /// Writes the members of the `fields` object of the tools' JSON.
    fn write_json_fields<W: Write + ?Sized>(&self, j: &mut JsonFields<'_, W>) -> fmt::Result;

    /// Appends the wire fields described by a `fields` object of decode's lossless JSON.
    #[cfg(feature = "std")]
    fn fields_from_json(fields: &super::json::Value, out: &mut super::json::WireFields) -> Result<(), Error<'static>>;

    /// Parses a whole line (a trailing LF or CR LF is allowed) that must be this sentence.
    fn parse_line(line: &'a str) -> Result<Self, Error<'a>> {
        let frame = Frame::parse(strip_line_ending(line.as_bytes()))?;
        let address = frame.address;
        if !is_standard_address(frame.start, address) || &address[2..] != Self::SENTENCE {
            let message = Message::WrongSentence { address, expected: Self::SENTENCE };
            return Err(Error::new(Some(address), message));
        }
        Self::parse_fields(frame.fields, frame.checksum)
    }

    /// Writes the sentence text, checksum included unless it is [`Checksum::None`]; no line
    /// ending.
    fn write_sentence<W: Write + ?Sized>(&self, out: &mut W) -> fmt::Result {
        write_sentence(out, "$", [self.talker(), Self::SENTENCE], self.checksum(), |w| self.write_fields(w))
    }

    /// Writes the tools' JSON line (`values`: decoded values instead of the lossless texts).
    fn write_json<W: Write + ?Sized>(&self, out: &mut W, values: bool) -> fmt::Result {
        let mut sink = Discard;
        let mut body = WireWriter::new(&mut sink);
        body.write_str(self.talker())?;
        body.write_str(Self::SENTENCE)?;
        self.write_fields(&mut body)?;
        let sum = body.checksum();
        out.write_str("{\"ok\":true,\"start\":\"$\",\"address\":\"")?;
        JsonEscape(&mut *out).write_str(self.talker())?;
        out.write_str(Self::SENTENCE)?;
        out.write_str("\",\"talker\":")?;
        write_json_str(out, self.talker())?;
        write!(out, ",\"sentence\":\"{}\",\"variant\":", Self::SENTENCE)?;
        match Self::VARIANT {
            Some(variant) => write!(out, "\"{variant}\"")?,
            None => out.write_str("null")?,
        }
        out.write_str(",\"fields\":")?;
        let mut fields = JsonFields::begin(&mut *out, values)?;
        self.write_json_fields(&mut fields)?;
        fields.end()?;
        write_checksum_json(out, self.checksum(), sum)
    }

    /// The tools' JSON line (`values`: decoded values instead of the lossless texts).
    #[cfg(feature = "std")]
    fn to_json(&self, values: bool) -> std::string::String {
        let mut out = std::string::String::new();
        let _ = self.write_json(&mut out, values);
        out
    }
}

fn write_checksum_json<W: Write + ?Sized>(out: &mut W, checksum: Checksum, sum: u8) -> fmt::Result {
    match checksum.digits(sum) {
        Some([a, b]) => write!(out, ",\"checksum\":\"{}{}\"}}", char::from(a), char::from(b)),
        None => out.write_str(",\"checksum\":null}"),
    }
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
        write_sentence(out, self.start, ["", ""], self.checksum, |w| self.write_body(w))
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
        write_checksum_json(out, self.checksum, sum)
    }
}

impl fmt::Display for Generic<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        self.write_sentence(f)
    }
}
