//! What the tools' `decode` and `encode` verbs do with one line, over any spec (see
//! [`Layouts`]): a line to its JSON, and (with `std`) decode's lossless JSON back to the sentence.

use core::fmt::{self, Write};

use super::parse::{parse_with, Layouts, Options};

#[cfg(feature = "std")]
use {
    super::error::{Error, ErrorKind},
    super::frame::Fields,
    super::json::{self, Value, WireFields},
    super::layout::{Framing, Generic},
    super::parse::{refit, Parsed},
    super::tag::TagBlocks,
    super::types::Checksum,
    std::string::{String, ToString},
};

/// Writes `decode`'s output for one line (without line ending): the sentence, with its problems,
/// or the error as JSON.
pub fn write_decoded<L: Layouts, W: Write + ?Sized>(out: &mut W, line: &[u8], values: bool) -> fmt::Result {
    write_decoded_with::<L, W>(out, line, values, Options::default())
}

/// [`write_decoded`] with options (`decode --lenient --require-checksum --strict`).
pub fn write_decoded_with<L: Layouts, W: Write + ?Sized>(
    out: &mut W,
    line: &[u8],
    values: bool,
    options: Options,
) -> fmt::Result {
    match parse_with::<L>(line, options) {
        Ok(parsed) => parsed.write_json(out, values),
        Err(err) => err.write_json(out),
    }
}

/// A sentence rebuilt from decode's lossless JSON: its address and wire fields, ready to parse.
#[cfg(feature = "std")]
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Rebuilt<L> {
    start: String,
    address: String,
    fields: WireFields,
    checksum: Checksum,
    layout: Option<L>,
    /// A text command: its words joined by spaces, the command word as written.
    line: Option<String>,
    /// A sentence lenient decoding kept (its JSON has `"problems"`): parsed leniently again.
    lenient: bool,
    /// The TAG blocks and stray `$` before it, written back from the JSON (checked when parsed),
    /// followed by a `$` that stands for the sentence's start.
    tag_blocks: Option<String>,
}

#[cfg(feature = "std")]
impl<L: Layouts> Rebuilt<L> {
    /// Parses the rebuilt fields through the same field parsers as a received line: a number
    /// outside its range is kept, as decoding kept it, whether or not the JSON lists it among
    /// the problems; a sentence whose JSON lists problems is parsed leniently (text commands
    /// are always read strictly).
    pub fn parse(&self) -> Result<Parsed<'_, L::Sentence<'_>>, Error<'_>> {
        let Some(text) = &self.tag_blocks else {
            return self.parse_sentence();
        };
        let (blocks, _) = TagBlocks::read(text.as_bytes(), L::TAG_CODES)?;
        let alone = self.start.is_empty();
        let mut parsed = if alone {
            let empty = Generic { start: "", address: "", fields: Fields::new("", "", 0), checksum: Checksum::None };
            Parsed::from(L::Sentence::from(empty))
        } else {
            self.parse_sentence()?
        };
        parsed.tag_blocks = blocks.with_alone(alone);
        Ok(parsed)
    }

    /// [`Rebuilt::parse`] of the sentence alone.
    fn parse_sentence(&self) -> Result<Parsed<'_, L::Sentence<'_>>, Error<'_>> {
        let mut fields = self.fields.fields(&self.address);
        if let Some(line) = &self.line {
            fields = fields.with_line(line);
        }
        match self.layout {
            Some(layout) => match layout.parse_fields(fields, self.checksum) {
                Ok(sentence) => Ok(sentence.into()),
                Err(error) if self.line.is_none() && error.kind() == ErrorKind::BadField => {
                    let options = Options { lenient: self.lenient, ..Options::default() };
                    refit(&[layout], fields, self.checksum, error, options)
                }
                Err(error) => Err(error),
            },
            None => {
                let generic = Generic { start: &self.start, address: &self.address, fields, checksum: self.checksum };
                let sentence: L::Sentence<'_> = generic.into();
                Ok(sentence.into())
            }
        }
    }

    /// Rebuilds a sentence from one object of decode's lossless JSON (`bad_json` errors name
    /// what is missing or malformed).
    pub fn from_json(obj: &Value) -> Result<Self, Error<'static>> {
        if !obj.is_object() {
            return Err(Error::bad_json("not a JSON object"));
        }
        if obj.get("tag_blocks").is_none() && obj.get("stray").is_none() {
            return Self::sentence_from_json(obj);
        }
        let mut before = match obj.get("tag_blocks") {
            Some(items) => json::tag_blocks(items)?,
            None => String::new(),
        };
        if let Some(stray) = obj.get("stray") {
            match stray {
                Value::String(text) if !text.is_empty() && text.bytes().all(|b| b == b'$') => before.push_str(text),
                _ => return Err(Error::bad_json("\"stray\" is not one or more \"$\"")),
            }
        }
        before.push('$');
        let stray = obj.get("stray").is_some();
        let tag_blocks = Some(before);
        if obj.get("start").is_none() {
            if stray {
                return Err(Error::bad_json("\"stray\" without a sentence"));
            }
            // a line of TAG blocks only
            let (start, address, fields) = (String::new(), String::new(), WireFields::default());
            let checksum = Checksum::None;
            return Ok(Self { start, address, fields, checksum, layout: None, line: None, lenient: false, tag_blocks });
        }
        Ok(Self { tag_blocks, ..Self::sentence_from_json(obj)? })
    }

    /// [`Rebuilt::from_json`] of the sentence alone.
    fn sentence_from_json(obj: &Value) -> Result<Self, Error<'static>> {
        let checksum = json::checksum_case(json::opt_text(obj, "checksum")?);
        let Some(sentence) = json::opt_text(obj, "sentence")? else {
            let items = json::list(obj, "fields")?;
            let start = json::str_member(obj, "start")?.to_string();
            if start != "$" && start != "!" {
                return Err(Error::bad_json("\"start\" is not \"$\" or \"!\""));
            }
            let address = json::word(obj, "address")?.to_string();
            let mut fields = WireFields::default();
            for item in items {
                fields.push(json::text(item)?);
            }
            return Ok(Self {
                start,
                address,
                fields,
                checksum,
                layout: None,
                line: None,
                lenient: false,
                tag_blocks: None,
            });
        };
        let variant = json::opt_text(obj, "variant")?;
        let unknown = || Error::bad_json(format!("unknown sentence \"{sentence}\""));
        let layout = L::find(sentence, variant).ok_or_else(unknown)?;
        let fields = json::member(obj, "fields")?;
        if !fields.is_object() {
            return Err(Error::bad_json("\"fields\" is not an object"));
        }
        let mut wire = WireFields::default();
        layout.fields_from_json(fields, &mut wire)?;
        if obj.get("problems").is_some() {
            return Self::with_problems(obj, layout, wire, checksum);
        }
        let (address, checksum, line) = match layout.framing() {
            Framing::Standard | Framing::Encapsulated => {
                (format!("{}{}", json::talker(obj, layout.sentence())?, layout.sentence()), checksum, None)
            }
            Framing::Proprietary(address) => (address.to_string(), checksum, None),
            Framing::Text(command) => {
                // A text command: its word as written, its letter case kept.
                let word = json::word(obj, "address")?;
                if !word.eq_ignore_ascii_case(command) {
                    return Err(Error::bad_json(format!("\"address\" is not {command}")));
                }
                (word.to_string(), Checksum::None, Some(wire.command_line(word)))
            }
        };
        let start = "$".to_string();
        Ok(Self {
            start,
            address,
            fields: wire,
            checksum,
            layout: Some(layout),
            line,
            lenient: false,
            tag_blocks: None,
        })
    }

    /// A sentence that lenient decoding kept: its problem fields' texts go back where they
    /// were, and it is parsed leniently again.
    fn with_problems(obj: &Value, layout: L, mut wire: WireFields, checksum: Checksum) -> Result<Self, Error<'static>> {
        if json::str_member(obj, "start")?.is_empty() {
            return Err(Error::bad_json("a text command has no problems"));
        }
        for problem in json::list(obj, "problems")? {
            let index = match json::member(problem, "field")? {
                Value::Integer(Some(index)) => usize::try_from(*index).ok().filter(|&i| i <= wire.len()),
                Value::Null => continue, // no field's: a short checksum, which "checksum" says
                _ => None,
            };
            let Some(index) = index else {
                return Err(Error::bad_json("a problem's \"field\" is not the index of a field"));
            };
            wire.set(index - 1, json::text(json::member(problem, "text")?)?);
        }
        let address = match layout.framing() {
            Framing::Standard | Framing::Encapsulated => {
                format!("{}{}", json::talker(obj, layout.sentence())?, layout.sentence())
            }
            Framing::Proprietary(address) | Framing::Text(address) => address.to_string(),
        };
        Ok(Self {
            start: "$".to_string(),
            address,
            fields: wire,
            checksum,
            layout: Some(layout),
            line: None,
            lenient: true,
            tag_blocks: None,
        })
    }
}

/// Writes `encode`'s output for one parsed line of decode's JSON (`None`: not JSON): the
/// sentence, or the error as JSON; no line ending.
#[cfg(feature = "std")]
pub fn write_encoded<L: Layouts, W: Write + ?Sized>(out: &mut W, obj: Option<&Value>) -> fmt::Result {
    let rebuilt = match obj.map(Rebuilt::<L>::from_json) {
        None => return Error::bad_json("not JSON").write_json(out),
        Some(Err(err)) => return err.write_json(out),
        Some(Ok(rebuilt)) => rebuilt,
    };
    let written = match rebuilt.parse() {
        Ok(parsed) => write!(out, "{parsed}"),
        Err(err) => err.write_json(out),
    };
    written
}

/// `decode`'s output for one line (without line ending): the sentence or the error as JSON.
#[cfg(feature = "std")]
pub fn decode_json<L: Layouts>(line: &[u8], values: bool) -> String {
    let mut out = String::new();
    let _ = write_decoded::<L, _>(&mut out, line, values);
    out
}

/// [`decode_json`] with options.
#[cfg(feature = "std")]
pub fn decode_json_with<L: Layouts>(line: &[u8], values: bool, options: Options) -> String {
    let mut out = String::new();
    let _ = write_decoded_with::<L, _>(&mut out, line, values, options);
    out
}

/// `encode`'s output for one line of decode's JSON: the sentence, or the error as JSON.
#[cfg(feature = "std")]
pub fn encode_json<L: Layouts>(line: &[u8]) -> String {
    let mut out = String::new();
    let _ = write_encoded::<L, _>(&mut out, Value::parse(line).as_ref());
    out
}

#[cfg(all(test, feature = "std"))]
mod tests {
    use super::super::parse::tests::NoLayout;
    use super::*;

    #[test]
    fn decode_json_reads_back_to_the_line() {
        let line = b"$PXUNKNOWN,00,01,,1*";
        let json = decode_json::<NoLayout>(line, false);
        assert!(json.starts_with(r#"{"ok":true,"start":"$","address":"PXUNKNOWN","#), "{json}");
        assert_eq!(encode_json::<NoLayout>(json.as_bytes()).as_bytes(), line);
        assert!(encode_json::<NoLayout>(b"[]").contains(r#""kind":"bad_json""#));
        assert!(decode_json::<NoLayout>(b"", false).contains(r#""kind":"not_a_sentence""#));
    }
}
