//! The error type: what went wrong, where, and the message the tools print.
//!
//! An [`Error`] borrows the offending text from the input line, so making one allocates
//! nothing; its message is written out only when it is displayed.

use core::fmt;

use super::write::write_json_str;

/// What kind of problem an [`Error`] reports (the `kind` key of the tools' JSON).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ErrorKind {
    /// The line is over [`MAX_LINE`](super::MAX_LINE) bytes.
    TooLong,
    /// Not a sentence at all: empty, no `$`/`!` start, unprintable bytes, bad address.
    NotASentence,
    /// A TAG block before the sentence (or on its own) is malformed.
    BadTagBlock,
    /// The text after `*` is not two hex digits of one letter case.
    BadChecksum,
    /// The checksum differs from the XOR of the sentence body.
    ChecksumMismatch,
    /// Fewer fields than the layout needs, or a repeated group cut short.
    TooFewFields,
    /// More fields than the layout takes.
    TooManyFields,
    /// A field's text does not fit its type.
    BadField,
    /// `encode` input that is not decode's JSON.
    BadJson,
    /// The sentence has no checksum, and one is required.
    MissingChecksum,
    /// A command builder's buffer cannot hold the line (the tools never report it).
    BufferTooSmall,
}

impl ErrorKind {
    /// The kind as the tools print it, e.g. `"checksum_mismatch"`.
    pub const fn as_str(self) -> &'static str {
        match self {
            Self::TooLong => "too_long",
            Self::NotASentence => "not_a_sentence",
            Self::BadTagBlock => "bad_tag_block",
            Self::BadChecksum => "bad_checksum",
            Self::ChecksumMismatch => "checksum_mismatch",
            Self::TooFewFields => "too_few_fields",
            Self::TooManyFields => "too_many_fields",
            Self::BadField => "bad_field",
            Self::BadJson => "bad_json",
            Self::MissingChecksum => "missing_checksum",
            Self::BufferTooSmall => "buffer_too_small",
        }
    }
}

impl fmt::Display for ErrorKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.as_str())
    }
}

/// The spec name of a field: its id, or `group[n].id` inside a repeated group (n from 1).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Name {
    group: &'static str,
    entry: usize,
    id: &'static str,
}

impl Name {
    /// A field outside any group.
    pub const fn field(id: &'static str) -> Self {
        Self { group: "", entry: 0, id }
    }

    /// Field `id` of entry `entry` (1-based) of group `group` (a field outside any group when
    /// `group` is empty).
    pub const fn entry(group: &'static str, entry: usize, id: &'static str) -> Self {
        Self { group, entry, id }
    }

    /// The field's id.
    pub const fn id(&self) -> &'static str {
        self.id
    }

    /// The group and the 1-based entry, for a field inside a repeated group.
    pub const fn group(&self) -> Option<(&'static str, usize)> {
        if self.group.is_empty() {
            None
        } else {
            Some((self.group, self.entry))
        }
    }
}

impl fmt::Display for Name {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.group() {
            None => f.write_str(self.id),
            Some((group, entry)) => write!(f, "{group}[{entry}].{}", self.id),
        }
    }
}

/// The message of an [`Error`], kept as data; `Display` writes the exact text of docs/json.md.
#[derive(Clone, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum Message<'a> {
    /// `line is N bytes, the limit is MAX_LINE`
    LineTooLong {
        /// Bytes in the line (without its line ending).
        length: usize,
    },
    /// `empty line`
    EmptyLine,
    /// `line does not start with '$' or '!'`
    BadStart,
    /// `byte 0xhh at offset N is not printable ASCII`
    NotPrintable {
        /// The byte.
        byte: u8,
        /// Its offset in the line.
        offset: usize,
    },
    /// `TAG block has no closing backslash`
    TagUnclosed,
    /// `TAG block "TEXT" has no checksum`
    TagNoChecksum {
        /// The block between its backslashes.
        text: &'a str,
    },
    /// `TAG block checksum "TEXT" is not two hex digits of one letter case`
    TagBadChecksum {
        /// Everything between the `*` and the closing backslash.
        text: &'a str,
    },
    /// `TAG block checksum is TEXT, computed HH`
    TagChecksumMismatch {
        /// The two digits received.
        sent: &'a str,
        /// The XOR of the block's parameters.
        computed: u8,
    },
    /// `TAG block parameter "TEXT" is not code:value`
    TagBadParameter {
        /// The parameter.
        text: &'a str,
    },
    /// `TAG block parameter "TEXT": expected FORM`
    TagBadValue {
        /// The parameter.
        text: &'a str,
        /// What its code's value must look like.
        form: &'static str,
    },
    /// `TAG block is followed by neither '$', '!' nor a TAG block`
    TagFollowed,
    /// `TAG block parameter holds ',', '*' or a backslash` (a block built from parameters).
    TagParameterHolds,
    /// `checksum "TEXT" is not two hex digits of one letter case`
    BadChecksum {
        /// Everything after the `*`.
        text: &'a str,
    },
    /// `checksum is TEXT, computed HH`
    ChecksumMismatch {
        /// The two digits received.
        sent: &'a str,
        /// The XOR of the body.
        computed: u8,
    },
    /// `address "TEXT" is not letters and digits`
    BadAddress {
        /// The address as received.
        text: &'a str,
    },
    /// `address "TEXT" is not a GGA sentence` (a layout's own `parse` given another sentence)
    WrongSentence {
        /// The address as received.
        address: &'a str,
        /// The sentence the layout parses.
        expected: &'static str,
    },
    /// `the sentence has no checksum` (a checksum is required)
    MissingChecksum,
    /// `GGA needs at least N fields, found M`
    TooFew {
        /// The sentence id.
        sentence: &'static str,
        /// The fields the layout needs.
        need: usize,
        /// The fields on the wire.
        found: usize,
    },
    /// `GSV satellites entries take N fields each, M left over`
    GroupCut {
        /// The sentence id.
        sentence: &'static str,
        /// The group id.
        group: &'static str,
        /// Wire fields per entry.
        width: usize,
        /// Fields left after the last whole entry.
        left: usize,
    },
    /// `GGA takes at most N fields, found M`
    TooMany {
        /// The sentence id.
        sentence: &'static str,
        /// The most fields the layout takes.
        limit: usize,
        /// The fields on the wire.
        found: usize,
    },
    /// `expected DESCRIPTION, found "TEXT"`
    BadField {
        /// What the field should hold, from the spec.
        expected: &'static str,
        /// The field's text.
        text: &'a str,
    },
    /// `expected DESCRIPTION, found "TEXT"` too, for a number of the right form outside its
    /// field's range (which parsing keeps unless it is strict): a `bad_field` error.
    OutOfRange {
        /// What the field should hold, from the spec.
        expected: &'static str,
        /// The field's text.
        text: &'a str,
    },
    /// `the line needs N bytes, the buffer holds M` (a command builder's buffer).
    BufferTooSmall {
        /// Bytes of the line with its CR LF.
        needed: usize,
        /// Bytes the buffer holds.
        capacity: usize,
    },
    /// A `bad_json` message of the encode verb.
    #[cfg(feature = "std")]
    Json(std::string::String),
}

impl Message<'_> {
    /// The kind of error this message belongs to.
    pub const fn kind(&self) -> ErrorKind {
        match self {
            Self::LineTooLong { .. } => ErrorKind::TooLong,
            Self::EmptyLine
            | Self::BadStart
            | Self::NotPrintable { .. }
            | Self::BadAddress { .. }
            | Self::WrongSentence { .. } => ErrorKind::NotASentence,
            Self::TagUnclosed
            | Self::TagNoChecksum { .. }
            | Self::TagBadChecksum { .. }
            | Self::TagChecksumMismatch { .. }
            | Self::TagBadParameter { .. }
            | Self::TagBadValue { .. }
            | Self::TagFollowed
            | Self::TagParameterHolds => ErrorKind::BadTagBlock,
            Self::BadChecksum { .. } => ErrorKind::BadChecksum,
            Self::ChecksumMismatch { .. } => ErrorKind::ChecksumMismatch,
            Self::TooFew { .. } | Self::GroupCut { .. } => ErrorKind::TooFewFields,
            Self::TooMany { .. } => ErrorKind::TooManyFields,
            Self::BadField { .. } | Self::OutOfRange { .. } => ErrorKind::BadField,
            Self::MissingChecksum => ErrorKind::MissingChecksum,
            Self::BufferTooSmall { .. } => ErrorKind::BufferTooSmall,
            #[cfg(feature = "std")]
            Self::Json(_) => ErrorKind::BadJson,
        }
    }
}

impl fmt::Display for Message<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::LineTooLong { length } => {
                write!(f, "line is {length} bytes, the limit is {}", super::MAX_LINE)
            }
            Self::EmptyLine => f.write_str("empty line"),
            Self::BadStart => f.write_str("line does not start with '$' or '!'"),
            Self::NotPrintable { byte, offset } => {
                write!(f, "byte 0x{byte:02x} at offset {offset} is not printable ASCII")
            }
            Self::TagUnclosed => f.write_str("TAG block has no closing backslash"),
            Self::TagNoChecksum { text } => {
                f.write_str("TAG block ")?;
                write_json_str(f, text)?;
                f.write_str(" has no checksum")
            }
            Self::TagBadChecksum { text } => {
                f.write_str("TAG block checksum ")?;
                write_json_str(f, text)?;
                f.write_str(" is not two hex digits of one letter case")
            }
            Self::TagChecksumMismatch { sent, computed } => {
                write!(f, "TAG block checksum is {sent}, computed {computed:02X}")
            }
            Self::TagBadParameter { text } => {
                f.write_str("TAG block parameter ")?;
                write_json_str(f, text)?;
                f.write_str(" is not code:value")
            }
            Self::TagBadValue { text, form } => {
                f.write_str("TAG block parameter ")?;
                write_json_str(f, text)?;
                write!(f, ": expected {form}")
            }
            Self::TagFollowed => f.write_str("TAG block is followed by neither '$', '!' nor a TAG block"),
            Self::TagParameterHolds => f.write_str("TAG block parameter holds ',', '*' or a backslash"),
            Self::BadChecksum { text } => {
                f.write_str("checksum ")?;
                write_json_str(f, text)?;
                f.write_str(" is not two hex digits of one letter case")
            }
            Self::ChecksumMismatch { sent, computed } => {
                write!(f, "checksum is {sent}, computed {computed:02X}")
            }
            Self::BadAddress { text } => {
                f.write_str("address ")?;
                write_json_str(f, text)?;
                f.write_str(" is not letters and digits")
            }
            Self::WrongSentence { address, expected } => {
                f.write_str("address ")?;
                write_json_str(f, address)?;
                write!(f, " is not a {expected} sentence")
            }
            Self::TooFew { sentence, need, found } => {
                write!(f, "{sentence} needs at least {need} fields, found {found}")
            }
            Self::GroupCut { sentence, group, width, left } => {
                write!(f, "{sentence} {group} entries take {width} fields each, {left} left over")
            }
            Self::TooMany { sentence, limit, found } => {
                write!(f, "{sentence} takes at most {limit} fields, found {found}")
            }
            Self::BadField { expected, text } | Self::OutOfRange { expected, text } => {
                write!(f, "expected {expected}, found ")?;
                write_json_str(f, text)
            }
            Self::MissingChecksum => f.write_str("the sentence has no checksum"),
            Self::BufferTooSmall { needed, capacity } => {
                write!(f, "the line needs {needed} bytes, the buffer holds {capacity}")
            }
            #[cfg(feature = "std")]
            Self::Json(message) => f.write_str(message),
        }
    }
}

/// A line that is not a valid sentence, or a sentence that does not fit its layout.
///
/// `Display` gives `kind: ADDRESS field N (name): message`; [`Error::write_json`] the tools'
/// JSON form.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Error<'a> {
    address: Option<&'a str>,
    field: Option<u32>,
    name: Option<Name>,
    message: Message<'a>,
}

impl<'a> Error<'a> {
    /// An error about the sentence at `address` (`None`: the line has none).
    pub const fn new(address: Option<&'a str>, message: Message<'a>) -> Self {
        Self { address, field: None, name: None, message }
    }

    /// A `too_long` error for a line of `length` bytes.
    pub const fn too_long(length: usize) -> Self {
        Self::new(None, Message::LineTooLong { length })
    }

    /// A `bad_field` error: wire field `field` (1-based, after the address) named `name`
    /// holds `text`, which is not `expected`.
    pub const fn bad_field(address: &'a str, field: usize, name: Name, expected: &'static str, text: &'a str) -> Self {
        Self {
            address: Some(address),
            field: Some(field as u32),
            name: Some(name),
            message: Message::BadField { expected, text },
        }
    }

    /// The same `bad_field` error, for a number of the right form outside its field's range
    /// (which parsing keeps unless it is strict).
    #[must_use]
    pub fn outside_range(self) -> Self {
        match self.message {
            Message::BadField { expected, text } => Self { message: Message::OutOfRange { expected, text }, ..self },
            _ => self,
        }
    }

    /// Whether this `bad_field` error is a number outside its field's range.
    pub const fn is_out_of_range(&self) -> bool {
        matches!(self.message, Message::OutOfRange { .. })
    }

    /// A `bad_json` error of the encode verb.
    #[cfg(feature = "std")]
    pub fn bad_json(message: impl Into<std::string::String>) -> Self {
        Self::new(None, Message::Json(message.into()))
    }

    /// What kind of problem this is.
    pub const fn kind(&self) -> ErrorKind {
        self.message.kind()
    }

    /// The address of the sentence, when the line has a well-formed one.
    pub const fn address(&self) -> Option<&'a str> {
        self.address
    }

    /// The 1-based index of the wire field at fault (after the address), if a single one is.
    pub const fn field(&self) -> Option<usize> {
        match self.field {
            Some(field) => Some(field as usize),
            None => None,
        }
    }

    /// The spec name of the field at fault.
    pub const fn name(&self) -> Option<Name> {
        self.name
    }

    /// The field's text as received, for a `bad_field` error.
    pub const fn text(&self) -> Option<&'a str> {
        match self.message {
            Message::BadField { text, .. } | Message::OutOfRange { text, .. } => Some(text),
            _ => None,
        }
    }

    /// The problem of `kind` a sentence parsing keeps records for a `bad_field` error.
    pub const fn problem(&self, kind: ProblemKind) -> Option<FieldProblem<'a>> {
        match (self.field, self.name, &self.message) {
            (
                Some(field),
                Some(name),
                Message::BadField { expected, text } | Message::OutOfRange { expected, text },
            ) => Some(FieldProblem { kind, field, name, expected, text }),
            _ => None,
        }
    }

    /// The message (without kind and place), e.g. `checksum is 40, computed 6C`.
    pub const fn message(&self) -> &Message<'a> {
        &self.message
    }

    /// Writes the tools' JSON line for this error (without line ending).
    pub fn write_json<W: fmt::Write + ?Sized>(&self, w: &mut W) -> fmt::Result {
        w.write_str("{\"ok\":false,\"error\":{\"kind\":\"")?;
        w.write_str(self.kind().as_str())?;
        w.write_str("\",\"address\":")?;
        match self.address {
            Some(address) => write_json_str(w, address)?,
            None => w.write_str("null")?,
        }
        w.write_str(",\"field\":")?;
        match self.field {
            Some(field) => write!(w, "{field}")?,
            None => w.write_str("null")?,
        }
        w.write_str(",\"name\":")?;
        match self.name {
            Some(name) => super::write::write_json_display(w, &name)?,
            None => w.write_str("null")?,
        }
        w.write_str(",\"message\":")?;
        super::write::write_json_display(w, &self.message)?;
        w.write_str("}}")
    }

    /// The tools' JSON line for this error (without line ending).
    #[cfg(feature = "std")]
    pub fn to_json(&self) -> std::string::String {
        let mut out = std::string::String::new();
        let _ = self.write_json(&mut out);
        out
    }
}

impl fmt::Display for Error<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}: {}", self.kind(), self.address.unwrap_or("line"))?;
        if let (Some(field), Some(name)) = (self.field, self.name) {
            write!(f, " field {field} ({name})")?;
        }
        write!(f, ": {}", self.message)
    }
}

#[cfg(feature = "std")]
impl std::error::Error for Error<'_> {}

/// What parsing did with a field at fault (the `kind` of a problem in the tools' JSON).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ProblemKind {
    /// `left_empty`: lenient parsing read the field as empty.
    LeftEmpty,
    /// `out_of_range`: a number outside its field's range, kept as sent.
    OutOfRange,
    /// `short_checksum`: a checksum sent as one hex digit, kept as sent. Never among
    /// [`Problems`]: the sentence's [`Checksum`](super::Checksum) style says it
    /// (`ShortUpper`, `ShortLower`); the tools' JSON lists it first.
    ShortChecksum,
}

impl ProblemKind {
    /// The kind as the tools print it, e.g. `"out_of_range"`.
    pub const fn as_str(self) -> &'static str {
        match self {
            Self::LeftEmpty => "left_empty",
            Self::OutOfRange => "out_of_range",
            Self::ShortChecksum => "short_checksum",
        }
    }
}

/// A field at fault in a sentence parsing kept: a number outside its field's range, kept as
/// sent, or a field lenient parsing left empty. Where it is, its text as received, and why (the
/// `bad_field` error it gave).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct FieldProblem<'a> {
    kind: ProblemKind,
    field: u32,
    name: Name,
    expected: &'static str,
    text: &'a str,
}

impl<'a> FieldProblem<'a> {
    /// What parsing did with the field.
    pub const fn kind(&self) -> ProblemKind {
        self.kind
    }

    /// The 1-based index of the wire field (after the address).
    pub const fn field(&self) -> usize {
        self.field as usize
    }

    /// The spec name of the field.
    pub const fn name(&self) -> Name {
        self.name
    }

    /// The field's text as received.
    pub const fn text(&self) -> &'a str {
        self.text
    }

    /// The `bad_field` message: `expected DESCRIPTION, found "TEXT"`.
    pub const fn message(&self) -> Message<'a> {
        Message::BadField { expected: self.expected, text: self.text }
    }

    /// Writes the `problems` entry of the tools' JSON.
    pub fn write_json<W: fmt::Write + ?Sized>(&self, w: &mut W) -> fmt::Result {
        write!(w, "{{\"kind\":\"{}\",\"field\":{},\"name\":", self.kind.as_str(), self.field)?;
        super::write::write_json_display(w, &self.name)?;
        w.write_str(",\"text\":")?;
        write_json_str(w, self.text)?;
        w.write_str(",\"message\":")?;
        super::write::write_json_display(w, &self.message())?;
        w.write_char('}')
    }
}

/// The problems of one sentence (numbers kept outside their range, fields lenient parsing left
/// empty), in the order their errors came: at most [`MAX_PROBLEMS`](super::MAX_PROBLEMS), kept
/// inline (no allocation).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Problems<'a> {
    items: [Option<FieldProblem<'a>>; super::MAX_PROBLEMS],
    len: usize,
}

impl<'a> Problems<'a> {
    /// No problems.
    pub const fn new() -> Self {
        Self { items: [None; super::MAX_PROBLEMS], len: 0 }
    }

    /// Adds a problem; `false` when there are already [`MAX_PROBLEMS`](super::MAX_PROBLEMS).
    pub fn push(&mut self, problem: FieldProblem<'a>) -> bool {
        let Some(slot) = self.items.get_mut(self.len) else {
            return false;
        };
        *slot = Some(problem);
        self.len += 1;
        true
    }

    /// How many there are.
    pub const fn len(&self) -> usize {
        self.len
    }

    /// Whether there are none.
    pub const fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// The problems in order.
    pub fn iter(&self) -> impl Iterator<Item = &FieldProblem<'a>> + '_ {
        self.items[..self.len].iter().flatten()
    }

    /// The text to write back for wire field `index`, if lenient parsing left it empty.
    pub fn text_of(&self, index: usize) -> Option<&'a str> {
        self.iter().find(|p| p.field() == index && p.kind == ProblemKind::LeftEmpty).map(|p| p.text)
    }

    /// Writes `,"problems":[...]` (nothing when there are none).
    pub fn write_json<W: fmt::Write + ?Sized>(&self, w: &mut W) -> fmt::Result {
        if self.is_empty() {
            return Ok(());
        }
        w.write_str(",\"problems\":[")?;
        for (i, problem) in self.iter().enumerate() {
            if i > 0 {
                w.write_char(',')?;
            }
            problem.write_json(w)?;
        }
        w.write_char(']')
    }
}
