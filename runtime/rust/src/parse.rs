//! The parser over any spec: the fast path and the general path, the first layout that fits a
//! framed line, the second reading that keeps numbers outside their range and (lenient parsing)
//! leaves fields at fault empty, and what a sentence writes of itself whatever its layout. The
//! generated crate describes its layouts with [`Layouts`] (its `LayoutId`) and its sentence with
//! [`Decoded`] (its `Sentence`); its `parse` and `parse_with` call these functions.

use core::fmt::{self, Write};

use super::error::{Error, ErrorKind, Message, ProblemKind, Problems};
use super::fast::{FastReader, Unsure};
use super::frame::{first_word, Fields, Frame, MAX_LINE};
use super::layout::{build, strip_line_ending, Framing, Generic, Layout};
use super::tag::{TagBlocks, TagCode};
use super::types::Checksum;
use super::write::{ByteWriter, Latin1Bytes};

/// The spec's layouts, as the generated `LayoutId` lists them: what the parser needs to find the
/// layouts a line may have and to decode it with one.
pub trait Layouts: Copy + PartialEq + 'static {
    /// A decoded line: the struct of one layout, or a [`Generic`] sentence.
    type Sentence<'a>: Decoded + From<Generic<'a>>;

    /// Every layout, in parse order.
    #[cfg(feature = "std")]
    const ALL: &'static [Self];

    /// The TAG block codes the spec names (spec/tag_block.yaml).
    const TAG_CODES: &'static [TagCode];

    /// The layouts a framed line may have, in the order the parser tries them: those of a `$` or
    /// `!` address, or of a text command's word (start `""`); none for anything else.
    fn of(start: &str, address: &[u8]) -> &'static [Self];

    /// The sentence id.
    #[cfg(feature = "std")]
    fn sentence(self) -> &'static str;

    /// The variant id, `None` for a main layout.
    #[cfg(feature = "std")]
    fn variant(self) -> Option<&'static str>;

    /// How the sentence is framed and addressed.
    fn framing(self) -> Framing;

    /// The keyword that picks this layout and its wire index (0-based, after the address).
    fn keyword(self) -> Option<(&'static str, usize)>;

    /// Whether the line's first field reads as this layout's first (a number outside its range
    /// does; a layout without fields: whether the line has none), asked of a layout without a
    /// keyword whose address has layouts with one ([`claimed`]).
    fn reads_first(self, fields: Fields<'_>) -> bool {
        let _ = fields;
        true
    }

    /// The main layout of this layout's sentence (itself for a main layout).
    fn main_layout(self) -> Self {
        self
    }

    /// A variant: the wire fields (1-based) it reads as its main layout does. A line its main
    /// layout refuses for one of them is not one it exists for, and it is not tried on it.
    fn same_as_main(self) -> &'static [u16] {
        &[]
    }

    /// Decodes the fields after the address with this layout.
    fn parse_fields<'a>(self, fields: Fields<'a>, checksum: Checksum) -> Result<Self::Sentence<'a>, Error<'a>>;

    /// The fast path of [`parse`]: a `$` sentence in its usual frame (see [`FastReader::frame`]),
    /// read by the fast reader ([`read_layout`]) of the first layout of its address whose field
    /// count fits it; when that reader is not sure, or none fits, what `O` makes of the general
    /// path. What it reads has an upper-case checksum and no field at fault, so [`parse_with`]'s
    /// options would not change it.
    fn read_sentence<'a, O: Outcome<'a, Self>>(fields: FastReader<'a>, line: &'a [u8]) -> O;

    /// [`Layouts::read_sentence`] with the next of `layouts`, the layouts of the address that
    /// remain.
    fn read_next<'a, O: Outcome<'a, Self>>(layouts: &[Self], fields: FastReader<'a>, line: &'a [u8]) -> O;

    /// Appends the wire fields described by a `fields` object of decode's lossless JSON.
    #[cfg(feature = "std")]
    fn fields_from_json(
        self,
        fields: &super::json::Value,
        out: &mut super::json::WireFields,
    ) -> Result<(), Error<'static>>;

    /// The command builders' serialization: writes the line with `write` into `buf`, reads it
    /// back with this layout and appends CR LF (see [`build`]).
    fn build<'b>(
        self,
        buf: &'b mut [u8],
        write: impl FnOnce(&mut Latin1Bytes<'_>) -> fmt::Result,
    ) -> Result<&'b [u8], Error<'b>> {
        build(buf, self.framing(), write, |fields, checksum| self.parse_fields(fields, checksum).map(drop))
    }

    /// The first layout of sentence `sentence` with variant `variant`.
    #[cfg(feature = "std")]
    fn find(sentence: &str, variant: Option<&str>) -> Option<Self> {
        Self::ALL.iter().copied().find(|layout| layout.sentence() == sentence && layout.variant() == variant)
    }
}

/// What the generated `Sentence` writes, whatever its layout: its text and its JSON line, with
/// the fields lenient parsing left empty put back.
pub trait Decoded {
    /// Writes the sentence text (no line ending) with the text of each of `problems` put back.
    fn write_sentence_with<W: Write + ?Sized>(&self, out: &mut W, problems: &Problems<'_>) -> fmt::Result;

    /// Writes the tools' JSON line (`values`: decoded values instead of the lossless texts);
    /// `"problems"` follows `"fields"` when there are any.
    fn write_json_with<W: Write + ?Sized>(&self, out: &mut W, values: bool, problems: &Problems<'_>) -> fmt::Result;

    /// The sentence text put at the start of `buf` without the `fmt` machinery: its length, or
    /// `None` for a text that is not all ASCII, a text command, or a buffer too small.
    fn put_sentence(&self, buf: &mut [u8]) -> Option<usize>;

    /// The sentence text with the text of each of `problems` put back, at the start of `buf`:
    /// its length, or `None` when `buf` cannot hold it. An ASCII text without problems (every
    /// parsed `$` sentence) is written without the `fmt` machinery.
    fn serialize_with(&self, buf: &mut [u8], problems: &Problems<'_>) -> Option<usize> {
        if problems.is_empty() {
            if let Some(len) = self.put_sentence(buf) {
                return Some(len);
            }
        }
        let mut w = ByteWriter::new(buf);
        self.write_sentence_with(&mut w, problems).ok()?;
        Some(w.len())
    }
}

/// What the fast path of [`parse`] gives: the sentence it read or, when it is not sure, what the
/// general path makes of the line ([`parse`]: the result of [`parse_general`]; [`parse_fast`]:
/// `None`).
pub trait Outcome<'a, L: Layouts> {
    /// The sentence the fast path read.
    fn read(sentence: L::Sentence<'a>) -> Self;
    /// What the general path makes of `line`.
    fn general(line: &'a [u8]) -> Self;
}

impl<'a, L: Layouts> Outcome<'a, L> for Result<L::Sentence<'a>, Error<'a>> {
    #[inline(always)]
    fn read(sentence: L::Sentence<'a>) -> Self {
        Ok(sentence)
    }

    fn general(line: &'a [u8]) -> Self {
        general::<L>(line)
    }
}

impl<'a, L: Layouts> Outcome<'a, L> for Option<L::Sentence<'a>> {
    #[inline(always)]
    fn read(sentence: L::Sentence<'a>) -> Self {
        Some(sentence)
    }

    fn general(_: &'a [u8]) -> Self {
        None
    }
}

/// Decodes one line (a trailing LF or CR LF is allowed) into the struct of its layout, or a
/// [`Generic`] sentence: the fast path, else the general path. A number outside its field's
/// range is kept as sent ([`parse_with`] lists it among the problems, or refuses it when
/// strict).
pub fn parse<L: Layouts>(line: &[u8]) -> Result<L::Sentence<'_>, Error<'_>> {
    let line = strip_line_ending(line);
    match FastReader::frame(line) {
        Some(fields) => L::read_sentence(fields, line),
        None => general::<L>(line),
    }
}

/// [`parse`] without its fast path: the general path alone, which reads every line and finds
/// every error.
pub fn parse_general<L: Layouts>(line: &[u8]) -> Result<L::Sentence<'_>, Error<'_>> {
    general::<L>(strip_line_ending(line))
}

/// The fast path of [`parse`] alone: the sentence, or `None` for a line it leaves to the general
/// path.
pub fn parse_fast<L: Layouts>(line: &[u8]) -> Option<L::Sentence<'_>> {
    let line = strip_line_ending(line);
    L::read_sentence(FastReader::frame(line)?, line)
}

/// The fast path with layout `S` of `L` (`rest`: the layouts to try after it).
///
/// Each step of the fast path returns what the next one returns, so that the sentence read is
/// copied once, into the caller's result: a copy of what was just written waits for those
/// writes to land.
#[inline(never)]
pub fn read_layout<'a, L: Layouts, S: Layout<'a> + Default + Into<L::Sentence<'a>>, O: Outcome<'a, L>>(
    fields: FastReader<'a>,
    line: &'a [u8],
    rest: &[L],
) -> O {
    let Some((repeats, extra)) = fields.shape(&S::SHAPE) else {
        return L::read_next(rest, fields, line);
    };
    let mut layout = S::default();
    match layout.read_fast(fields, repeats, extra) {
        Ok(()) => O::read(layout.into()),
        Err(Unsure) => O::general(line),
    }
}

/// Whether a line that does not start with `$` or `!` is a text command: its first word is a
/// command word of the spec (ignoring case).
fn is_text_command<L: Layouts>(line: &[u8]) -> bool {
    !matches!(line.first(), Some(b'$' | b'!')) && !L::of("", first_word(line)).is_empty()
}

/// The general path of [`parse`], for a line without its line ending.
fn general<L: Layouts>(line: &[u8]) -> Result<L::Sentence<'_>, Error<'_>> {
    general_with::<L>(line, Options::default()).map(|parsed| parsed.sentence)
}

/// How `parse_with` reads a line. By default a `$`/`!` sentence with a number of the right form
/// outside its field's range is decoded with the number kept as sent, listed in
/// [`Parsed::problems`] ([`ProblemKind::OutOfRange`](super::ProblemKind)).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct Options {
    /// Keep a `$`/`!` sentence whose fields do not all fit their types: each other field at
    /// fault is read as empty and listed in [`Parsed::problems`] (at most
    /// [`MAX_PROBLEMS`](super::MAX_PROBLEMS) problems in all). Text commands are always read
    /// strictly.
    pub lenient: bool,
    /// Refuse a `$`/`!` sentence without a checksum (or with a bare `*`): `missing_checksum`.
    pub require_checksum: bool,
    /// Refuse a number outside its field's range as `bad_field` (or, `lenient`, leave it empty).
    pub strict: bool,
}

/// A sentence decoded by `parse_with`, its problems (the numbers kept outside their range, and
/// the fields lenient parsing left empty, with their text as received, written back by `Display`
/// so that the round trip stays exact) and what came before it (TAG blocks, a stray `$`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Parsed<'a, S> {
    /// The decoded sentence (fields at fault are `None`); an empty [`Generic`] one for a line of
    /// TAG blocks only ([`TagBlocks::alone`]).
    pub sentence: S,
    /// The numbers kept outside their range and the fields lenient parsing left empty, in the
    /// order their errors came.
    pub problems: Problems<'a>,
    /// The TAG blocks before the sentence and the stray `$` of a start sent twice, as received
    /// (none: empty).
    pub tag_blocks: TagBlocks<'a>,
}

impl<S> From<S> for Parsed<'_, S> {
    fn from(sentence: S) -> Self {
        Self { sentence, problems: Problems::new(), tag_blocks: TagBlocks::NONE }
    }
}

/// A writer that holds back the last character written to it: the closing brace of a sentence's
/// JSON, in whose place the TAG blocks go.
struct HoldLast<'w, W: ?Sized> {
    out: &'w mut W,
    last: Option<char>,
}

impl<W: Write + ?Sized> Write for HoldLast<'_, W> {
    fn write_str(&mut self, s: &str) -> fmt::Result {
        let mut chars = s.chars();
        let Some(last) = chars.next_back() else {
            return Ok(());
        };
        if let Some(held) = self.last.replace(last) {
            self.out.write_char(held)?;
        }
        self.out.write_str(chars.as_str())
    }
}

impl<S: Decoded> Parsed<'_, S> {
    /// Writes the tools' JSON line: `"problems"` follows `"fields"` when there are any, and
    /// `"tag_blocks"` and `"stray"` come last (alone after `"ok"` for a line of TAG blocks only).
    pub fn write_json<W: Write + ?Sized>(&self, out: &mut W, values: bool) -> fmt::Result {
        if self.tag_blocks.is_empty() {
            return self.sentence.write_json_with(out, values, &self.problems);
        }
        if self.tag_blocks.alone() {
            out.write_str("{\"ok\":true,")?;
        } else {
            self.sentence.write_json_with(&mut HoldLast { out: &mut *out, last: None }, values, &self.problems)?;
            out.write_char(',')?;
        }
        self.tag_blocks.write_json(out)?;
        out.write_char('}')
    }

    /// The tools' JSON line (`values`: decoded values instead of the lossless texts).
    #[cfg(feature = "std")]
    pub fn to_json(&self, values: bool) -> std::string::String {
        let mut out = std::string::String::new();
        let _ = self.write_json(&mut out, values);
        out
    }

    /// The sentence text with the problem fields' texts put back (what `Display` writes, no
    /// line ending) at the start of `buf`: its length, or `None` when `buf` cannot hold it.
    pub fn serialize_into(&self, buf: &mut [u8]) -> Option<usize> {
        let tags = self.tag_blocks.as_str().as_bytes();
        buf.get_mut(..tags.len())?.copy_from_slice(tags);
        if self.tag_blocks.alone() {
            return Some(tags.len());
        }
        Some(tags.len() + self.sentence.serialize_with(&mut buf[tags.len()..], &self.problems)?)
    }
}

impl<S: Decoded> fmt::Display for Parsed<'_, S> {
    /// The TAG blocks as received and the sentence text with the problem fields' texts put
    /// back; no line ending.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.tag_blocks.as_str())?;
        if self.tag_blocks.alone() {
            return Ok(());
        }
        if self.problems.is_empty() {
            // Put together on the stack and written at once, as `Sentence`'s `Display` does.
            let mut buf = [0; MAX_LINE];
            if let Some(len) = self.sentence.put_sentence(&mut buf) {
                return f.write_str(core::str::from_utf8(&buf[..len]).map_err(|_| fmt::Error)?);
            }
        }
        self.sentence.write_sentence_with(f, &self.problems)
    }
}

/// [`parse`] with options: lenient decoding, required checksums, strict ranges.
pub fn parse_with<L: Layouts>(line: &[u8], options: Options) -> Result<Parsed<'_, L::Sentence<'_>>, Error<'_>> {
    let line = strip_line_ending(line);
    if line.first() == Some(&b'\\') || line.starts_with(b"$$") {
        return parse_tagged::<L>(line, options, parse_with::<L>);
    }
    let fast = FastReader::frame(line).and_then(|fields| L::read_sentence::<Option<_>>(fields, line));
    if let Some(sentence) = fast {
        return Ok(sentence.into());
    }
    general_with::<L>(line, options)
}

/// How the sentence after a line's TAG blocks is read: [`parse_with`] or its general path alone.
type SentenceParser<L> = for<'a> fn(&'a [u8], Options) -> Result<Parsed<'a, <L as Layouts>::Sentence<'a>>, Error<'a>>;

/// A line that starts with TAG blocks or a start sent more than once (`$$GNGSA`): what comes
/// before the sentence ([`TagBlocks`]), then the sentence read by `parse` (none: an empty
/// [`Generic`] sentence).
fn parse_tagged<L: Layouts>(
    line: &[u8],
    options: Options,
    parse: SentenceParser<L>,
) -> Result<Parsed<'_, L::Sentence<'_>>, Error<'_>> {
    if line.len() > MAX_LINE {
        return Err(Error::too_long(line.len()));
    }
    let (tag_blocks, rest) = TagBlocks::read(line, L::TAG_CODES)?;
    let mut parsed = if rest.is_empty() {
        let empty = Generic { start: "", address: "", fields: Fields::new("", "", 0), checksum: Checksum::None };
        Parsed::from(L::Sentence::from(empty))
    } else {
        parse(rest, options)?
    };
    parsed.tag_blocks = tag_blocks;
    Ok(parsed)
}

/// [`parse_with`] without its fast path (see [`parse_general`]).
pub fn parse_with_general<L: Layouts>(line: &[u8], options: Options) -> Result<Parsed<'_, L::Sentence<'_>>, Error<'_>> {
    let line = strip_line_ending(line);
    if line.first() == Some(&b'\\') || line.starts_with(b"$$") {
        return parse_tagged::<L>(line, options, parse_with_general::<L>);
    }
    general_with::<L>(line, options)
}

/// The general path of [`parse_with`], for a line without its line ending.
fn general_with<L: Layouts>(line: &[u8], options: Options) -> Result<Parsed<'_, L::Sentence<'_>>, Error<'_>> {
    if is_text_command::<L>(line) {
        return parse_frame::<L>(Frame::parse_text(line)?).map(Parsed::from);
    }
    let frame = Frame::parse_checked(line, options.require_checksum, options.strict)?;
    let layouts = L::of(frame.start, frame.address.as_bytes());
    if !claimed(layouts, &frame) {
        let sentence: L::Sentence<'_> = Generic::from_frame(frame).into();
        return Ok(sentence.into());
    }
    match first_fit(layouts, frame.fields, frame.checksum) {
        Ok(sentence) => Ok(sentence.into()),
        Err(error) if error.kind() == ErrorKind::BadField && (options.lenient || !options.strict) => {
            refit(layouts, frame.fields, frame.checksum, error, options)
        }
        Err(error) => Err(error),
    }
}

/// Parses again, one field at fault at a time: a number outside its range kept as sent (unless
/// `options.strict`), any other field (`options.lenient`) left empty. A field neither can take
/// (or one already empty that still does not fit), or one problem more than
/// [`MAX_PROBLEMS`](super::MAX_PROBLEMS), ends the attempt with its error.
pub fn refit<'a, L: Layouts>(
    layouts: &[L],
    mut fields: Fields<'a>,
    checksum: Checksum,
    mut error: Error<'a>,
    options: Options,
) -> Result<Parsed<'a, L::Sentence<'a>>, Error<'a>> {
    let mut problems = Problems::new();
    loop {
        let kind = if error.is_out_of_range() && !options.strict {
            ProblemKind::OutOfRange
        } else if options.lenient {
            ProblemKind::LeftEmpty
        } else {
            return Err(error);
        };
        let Some(problem) = error.problem(kind) else {
            return Err(error);
        };
        let index = problem.field();
        if fields.get(index).is_none_or(str::is_empty) || !problems.push(problem) {
            return Err(error);
        }
        fields = if kind == ProblemKind::OutOfRange { fields.with_range_kept(index) } else { fields.with_blank(index) };
        match first_fit(layouts, fields, checksum) {
            Ok(sentence) => return Ok(Parsed { sentence, problems, tag_blocks: TagBlocks::NONE }),
            Err(again) => error = again,
        }
    }
}

/// Decodes a framed line with the layouts of its address ([`Layouts::of`]), the first that
/// fits; [`Generic`] when the spec knows none.
fn parse_frame<L: Layouts>(frame: Frame<'_>) -> Result<L::Sentence<'_>, Error<'_>> {
    let layouts = L::of(frame.start, frame.address.as_bytes());
    if !claimed(layouts, &frame) {
        return Ok(Generic::from_frame(frame).into());
    }
    first_fit(layouts, frame.fields, frame.checksum)
}

/// Whether `fields` hold `layout`'s keyword in its place (ignoring case).
fn holds_keyword<L: Layouts>(layout: L, fields: &Fields<'_>) -> bool {
    layout.keyword().is_some_and(|(keyword, at)| {
        !fields.is_empty() && fields.get(at + 1).is_some_and(|word| word.eq_ignore_ascii_case(keyword))
    })
}

/// Whether one of the layouts of the line's address may read it: for a `$` line, one whose
/// keyword the line holds, or one without a keyword, when no layout of the address has one or
/// when the line's first field reads as that layout's first ([`Layouts::reads_first`]); else the
/// line is a message of a known family that the spec does not know, kept as a [`Generic`]
/// sentence (`$PASHR,BTS,…` beside RT300's keyword-less `$PASHR,<time>,…`).
fn claimed<L: Layouts>(layouts: &[L], frame: &Frame<'_>) -> bool {
    let keyed = layouts.iter().any(|layout| layout.keyword().is_some());
    !layouts.is_empty()
        && (frame.start != "$"
            || layouts.iter().any(|&layout| match layout.keyword() {
                Some(_) => holds_keyword(layout, &frame.fields),
                None => !keyed || layout.reads_first(frame.fields),
            }))
}

/// The first of `layouts` (not empty) that fits the fields; a variant is passed over when the main
/// layout of its sentence, tried last before it, refused a field the variant reads the same way
/// ([`Layouts::same_as_main`]). When none does, the error of the contenders (the layouts whose
/// keyword the first field holds, else all): the first that is a bad field, else the first.
fn first_fit<'a, L: Layouts>(
    layouts: &[L],
    fields: Fields<'a>,
    checksum: Checksum,
) -> Result<L::Sentence<'a>, Error<'a>> {
    let Some((&first, others)) = layouts.split_first() else {
        return Err(Error::new(None, Message::EmptyLine));
    };
    let error = match first.parse_fields(fields, checksum) {
        Ok(sentence) => return Ok(sentence),
        Err(error) => error,
    };
    if others.is_empty() {
        return Err(error);
    }
    let rank = |layout: L, error: &Error<'_>| {
        u8::from(!holds_keyword(layout, &fields)) * 2 + u8::from(error.kind() != ErrorKind::BadField)
    };
    // The main layout tried last, when it refused a field: that layout and the field.
    let refused_by = |layout: L, error: &Error<'_>| {
        error
            .field()
            .filter(|_| error.kind() == ErrorKind::BadField && layout.main_layout() == layout)
            .map(|at| (layout, at))
    };
    let mut refused = refused_by(first, &error);
    let mut best = (rank(first, &error), error);
    for &layout in others {
        if let Some((main, at)) = refused {
            if layout.main_layout() == main
                && layout != main
                && layout.same_as_main().iter().any(|&f| usize::from(f) == at)
            {
                continue;
            }
        }
        match layout.parse_fields(fields, checksum) {
            Ok(sentence) => return Ok(sentence),
            Err(error) => {
                if layout.main_layout() == layout {
                    refused = refused_by(layout, &error);
                }
                let rank = rank(layout, &error);
                if rank < best.0 {
                    best = (rank, error);
                }
            }
        }
    }
    Err(best.1)
}

#[cfg(test)]
pub(super) mod tests {
    use super::super::tag::TagType;
    use super::*;

    /// A spec without layouts: every well-formed line is a generic sentence.
    #[derive(Clone, Copy, Debug, PartialEq, Eq)]
    pub enum NoLayout {}

    impl Layouts for NoLayout {
        type Sentence<'a> = Generic<'a>;
        #[cfg(feature = "std")]
        const ALL: &'static [Self] = &[];
        const TAG_CODES: &'static [TagCode] = &[
            TagCode { code: "c", id: "time", name: "UNIX time", kind: TagType::Integer },
            TagCode { code: "g", id: "group", name: "Sentence grouping", kind: TagType::Group },
            TagCode { code: "s", id: "source", name: "Source", kind: TagType::Text },
        ];

        fn of(_: &str, _: &[u8]) -> &'static [Self] {
            &[]
        }

        #[cfg(feature = "std")]
        fn sentence(self) -> &'static str {
            match self {}
        }

        #[cfg(feature = "std")]
        fn variant(self) -> Option<&'static str> {
            match self {}
        }

        fn framing(self) -> Framing {
            match self {}
        }

        fn keyword(self) -> Option<(&'static str, usize)> {
            match self {}
        }

        fn parse_fields<'a>(self, _: Fields<'a>, _: Checksum) -> Result<Generic<'a>, Error<'a>> {
            match self {}
        }

        fn read_sentence<'a, O: Outcome<'a, Self>>(_: FastReader<'a>, line: &'a [u8]) -> O {
            O::general(line)
        }

        fn read_next<'a, O: Outcome<'a, Self>>(_: &[Self], _: FastReader<'a>, line: &'a [u8]) -> O {
            O::general(line)
        }

        #[cfg(feature = "std")]
        fn fields_from_json(
            self,
            _: &super::super::json::Value,
            _: &mut super::super::json::WireFields,
        ) -> Result<(), Error<'static>> {
            match self {}
        }
    }

    impl Decoded for Generic<'_> {
        fn write_sentence_with<W: Write + ?Sized>(&self, out: &mut W, _: &Problems<'_>) -> fmt::Result {
            self.write_sentence(out)
        }

        fn write_json_with<W: Write + ?Sized>(&self, out: &mut W, _: bool, _: &Problems<'_>) -> fmt::Result {
            self.write_json(out)
        }

        fn put_sentence(&self, buf: &mut [u8]) -> Option<usize> {
            self.put_sentence(buf)
        }
    }

    #[test]
    fn lines_the_spec_does_not_describe_are_generic() {
        let line = "$PXUNKNOWN,00,01,,1*\r\n";
        let sentence = parse::<NoLayout>(line.as_bytes()).unwrap();
        assert_eq!((sentence.address, sentence.fields.as_str()), ("PXUNKNOWN", "00,01,,1"));
        assert_eq!(parse_general::<NoLayout>(line.as_bytes()), Ok(sentence));
        assert_eq!(parse_fast::<NoLayout>(line.as_bytes()), None);
        let lenient = Options { lenient: true, ..Options::default() };
        let parsed = parse_with::<NoLayout>(line.as_bytes(), lenient).unwrap();
        assert_eq!(parsed, Parsed::from(sentence));
        let mut buf = [0; MAX_LINE];
        let len = parsed.serialize_into(&mut buf).unwrap();
        assert_eq!(&buf[..len], line.trim_end().as_bytes());
        assert_eq!(parsed.serialize_into(&mut buf[..len - 1]), None);
    }

    #[test]
    fn framing_errors_come_before_layouts() {
        let kind = |line: &str| parse::<NoLayout>(line.as_bytes()).unwrap_err().kind();
        assert_eq!(kind("$GPGGA,1*00"), ErrorKind::ChecksumMismatch);
        assert_eq!(kind("$GP GGA,1"), ErrorKind::NotASentence);
        assert_eq!(kind("NMEATALKER GGA GP"), ErrorKind::NotASentence);
        let required = Options { require_checksum: true, ..Options::default() };
        let error = parse_with::<NoLayout>(b"$GPHDT,1.0,T*", required).unwrap_err();
        assert_eq!(error.kind(), ErrorKind::MissingChecksum);
    }
}
