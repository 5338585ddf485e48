//! Framing: one pass over a line checks it and splits it into start, address, fields and
//! checksum; then a [`Reader`] hands out the fields one by one to the typed field readers.
//! Text commands (words separated by single spaces, no `$`, no checksum) are framed by
//! [`Frame::parse_text`].

use super::error::{Error, Message, Name};
use super::types::{
    upper_eq, Checksum, Code, CodeChars, CodeEnum, Coordinate, Date, Entries, Hex, Number, Range, ReadEntry, Sign,
    Texts, Time, MAX_DIGITS,
};

/// Longest line (without its line ending) the parser accepts.
pub const MAX_LINE: usize = 1024;

/// Most problems one sentence may have (numbers kept outside their range and fields left
/// empty, together).
pub const MAX_PROBLEMS: usize = 8;

/// Added to a wire index in [`Blanks`]: the number there is kept outside its range. (No line has
/// that many fields, and an index so marked is never taken for a field read as empty.)
const RANGE_KEPT: usize = 0x8000;

/// The wire fields (1-based indices) at fault in a second reading: read as empty (lenient
/// parsing) or, marked with `RANGE_KEPT`, numbers read without their range. At most
/// [`MAX_PROBLEMS`], kept inline so that [`Fields`] stays a copyable view of the line.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct Blanks {
    at: [u16; MAX_PROBLEMS],
    len: u8,
}

impl Blanks {
    /// No field left empty.
    pub const EMPTY: Self = Self { at: [0; MAX_PROBLEMS], len: 0 };

    /// Whether wire field `index` is left empty.
    #[inline]
    pub fn contains(&self, index: usize) -> bool {
        self.at[..usize::from(self.len)].iter().any(|&at| usize::from(at) == index)
    }

    /// How many fields are left empty.
    pub const fn len(&self) -> usize {
        self.len as usize
    }

    /// Whether no field is left empty.
    pub const fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// The fields of this set among the `count` after wire field `first`, numbered from 1 there.
    #[must_use]
    pub fn within(&self, first: usize, count: usize) -> Self {
        let mut out = Self::EMPTY;
        for &at in &self.at[..usize::from(self.len)] {
            let at = usize::from(at);
            if at > first && at <= first + count {
                out = out.with(at - first);
            }
        }
        out
    }

    /// The same set with wire field `index` added (ignored once full).
    #[must_use]
    pub fn with(mut self, index: usize) -> Self {
        if usize::from(self.len) < MAX_PROBLEMS {
            self.at[usize::from(self.len)] = u16::try_from(index).unwrap_or(u16::MAX);
            self.len += 1;
        }
        self
    }
}

const LATITUDE: &str = "latitude ddmm.mmmm";
const LONGITUDE: &str = "longitude dddmm.mmmm";
const NORTH_SOUTH: &str = "hemisphere N or S";
const EAST_WEST: &str = "hemisphere E or W";

/// XOR of every byte of `body` (the bytes between the start character and the `*`), 8 at a time.
#[inline]
pub fn checksum(body: &[u8]) -> u8 {
    let mut words = body.chunks_exact(8);
    let sum = words.by_ref().fold(0u64, |sum, word| sum ^ u64::from_le_bytes(word.try_into().unwrap_or_default()));
    words.remainder().iter().fold(xor_of_bytes(sum), |sum, b| sum ^ b)
}

/// XOR of the 8 bytes of `word`.
#[inline(always)]
pub(crate) const fn xor_of_bytes(mut word: u64) -> u8 {
    word ^= word >> 32;
    word ^= word >> 16;
    word ^= word >> 8;
    word as u8
}

/// The standard query's formatter (`$CCGPQ,GGA`: CC asks GP for GGA), whose talker is two
/// talker IDs, the requester's and the listener's.
pub const QUERY: &str = "Q";

/// How many characters the talker of standard sentence `sentence` has: 2, or 4 for the query.
pub fn talker_length(sentence: &str) -> usize {
    if sentence == QUERY {
        4
    } else {
        2
    }
}

/// A line split into its parts; its checksum, if any, has been verified.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Frame<'a> {
    /// `"$"` or `"!"`; `""` for a text command.
    pub start: &'a str,
    /// Everything between the start character and the first `,` (or `*`): letters and digits.
    /// For a text command, its first word as received.
    pub address: &'a str,
    /// The fields after the address.
    pub fields: Fields<'a>,
    /// How the checksum was written.
    pub checksum: Checksum,
}

impl<'a> Frame<'a> {
    /// Checks and splits one line (without its line ending), in the order of docs/json.md:
    /// length, start, printable bytes, checksum form, checksum value, address.
    pub fn parse(line: &'a [u8]) -> Result<Self, Error<'a>> {
        Self::parse_checked(line, false, false)
    }

    /// [`Frame::parse`]; with `require_checksum`, a sentence without a checksum (or with a bare
    /// `*`) is refused as `missing_checksum`, after the address check. A checksum of one hex
    /// digit that equals the sum (some instruments send `*b` for `*0b`) is kept as sent
    /// ([`Checksum::ShortLower`], [`Checksum::ShortUpper`]), unless `strict`.
    pub fn parse_checked(line: &'a [u8], require_checksum: bool, strict: bool) -> Result<Self, Error<'a>> {
        let not_a_sentence = |message| Error::new(None, message);
        if line.len() > MAX_LINE {
            return Err(Error::too_long(line.len()));
        }
        let start = match line.first() {
            None => return Err(not_a_sentence(Message::EmptyLine)),
            Some(b'$') => "$",
            Some(b'!') => "!",
            Some(_) => return Err(not_a_sentence(Message::BadStart)),
        };
        let Scan { printable, mut sum, mut commas, stars } = Scan::of(&line[1..]);
        if !printable {
            let offset = line.iter().position(|b| !(0x20..=0x7e).contains(b)).unwrap_or(0);
            return Err(not_a_sentence(Message::NotPrintable { byte: line[offset], offset }));
        }
        // The checksum star is nearly always the only one, third byte from the end. What follows
        // the first star is not part of the body: take it out of the sum and the comma count.
        let star = match stars {
            0 => None,
            1 if line.len() >= 3 && line[line.len() - 3] == b'*' => Some(line.len() - 3),
            _ => line.iter().position(|&b| b == b'*'),
        };
        let body_end = star.unwrap_or(line.len());
        for &b in &line[body_end..] {
            sum ^= b;
            commas -= usize::from(b == b',');
        }
        let body = &line[1..body_end];
        let first_comma = body.iter().position(|&b| b == b',').map(|i| i + 1);
        let text = match core::str::from_utf8(line) {
            Ok(text) => text,
            Err(err) => {
                let offset = err.valid_up_to();
                return Err(not_a_sentence(Message::NotPrintable { byte: line[offset], offset }));
            }
        };
        let address = &text[1..first_comma.unwrap_or(body_end)];
        let named = (!address.is_empty() && address.bytes().all(|b| b.is_ascii_alphanumeric())).then_some(address);
        let sent = star.map(|star| &text[star + 1..]);
        // A bare '*' leaves the checksum out, as ST's manual writes its commands.
        if let Some(sent) = sent.filter(|sent| !sent.is_empty()) {
            let b = sent.as_bytes();
            let one_case = !(b.iter().any(u8::is_ascii_uppercase) && b.iter().any(u8::is_ascii_lowercase));
            let short = !strict && b.len() == 1 && b[0].is_ascii_hexdigit() && hex_value(b[0]) == sum;
            if !short && (b.len() != 2 || !b.iter().all(u8::is_ascii_hexdigit) || !one_case) {
                return Err(Error::new(named, Message::BadChecksum { text: sent }));
            }
            if !short && hex_value(b[0]) << 4 | hex_value(b[1]) != sum {
                let message = Message::ChecksumMismatch { sent, computed: sum };
                return Err(Error::new(named, message));
            }
        }
        let Some(address) = named else {
            return Err(not_a_sentence(Message::BadAddress { text: address }));
        };
        if require_checksum && sent.is_none_or(str::is_empty) {
            return Err(Error::new(Some(address), Message::MissingChecksum));
        }
        let fields = match first_comma {
            Some(comma) => Fields::new(address, &text[comma + 1..body_end], commas),
            None => Fields::new(address, "", 0),
        };
        Ok(Self { start, address, fields, checksum: Checksum::of(sent) })
    }

    /// Checks and splits a text command (ComNav: words separated by single spaces, no `$`, no
    /// checksum): length, printable bytes; the first word is the address.
    pub fn parse_text(line: &'a [u8]) -> Result<Self, Error<'a>> {
        if line.len() > MAX_LINE {
            return Err(Error::too_long(line.len()));
        }
        if let Some(offset) = line.iter().position(|b| !(0x20..=0x7e).contains(b)) {
            return Err(Error::new(None, Message::NotPrintable { byte: line[offset], offset }));
        }
        let Ok(text) = core::str::from_utf8(line) else {
            return Err(Error::new(None, Message::NotPrintable { byte: line[0], offset: 0 }));
        };
        let (address, fields) = match text.split_once(' ') {
            Some((word, rest)) => (word, Fields::words(word, rest, text.bytes().filter(|&b| b == b' ').count())),
            None => (text, Fields::words(text, "", 0)),
        };
        Ok(Self { start: "", address, fields: fields.with_line(text), checksum: Checksum::None })
    }
}

/// The command word of a possible text command: the bytes before the first space.
pub fn first_word(line: &[u8]) -> &[u8] {
    line.split(|&b| b == b' ').next().unwrap_or(line)
}

/// Whether a line's first word, upper-cased the way Python upper-cases Latin-1 text (ASCII
/// letters, and `ß` as `SS`), is the command word `upper`.
pub fn is_command_word(word: &[u8], upper: &str) -> bool {
    let mut expected = upper.bytes();
    for &b in word {
        let fits = match b {
            0xdf => expected.next() == Some(b'S') && expected.next() == Some(b'S'),
            _ => expected.next() == Some(b.to_ascii_uppercase()),
        };
        if !fits {
            return false;
        }
    }
    expected.next().is_none()
}

/// Whether a line is a standard sentence, a talker ID and a formatter: `$` (or `!`, an
/// encapsulation sentence such as AIS VDM) and 5 characters (6 for a receiver's 4-character
/// formatter, Unicore's `GGAH`), not proprietary (`P…`).
pub fn is_standard_address(start: &str, address: &str) -> bool {
    matches!(start, "$" | "!") && matches!(address.len(), 5 | 6) && !address.starts_with('P')
}

/// What one pass over the bytes after the start finds: whether all are printable ASCII, their
/// XOR, and how many commas and stars there are. Sixteen bytes at a time, each into its own lane
/// of the counters, a loop the compiler turns into vector instructions.
struct Scan {
    printable: bool,
    sum: u8,
    commas: usize,
    stars: usize,
}

/// Per-lane accumulators of [`Scan`].
#[derive(Default)]
struct Lanes {
    unprintable: [u8; Lanes::WIDTH],
    sum: [u8; Lanes::WIDTH],
    commas: [u8; Lanes::WIDTH],
    stars: [u8; Lanes::WIDTH],
}

impl Lanes {
    const WIDTH: usize = 16;

    /// Adds one chunk, byte `i` to lane `i`: at most [`MAX_LINE`] / 16 = 64 per lane.
    #[inline(always)]
    #[allow(clippy::needless_range_loop)] // Indexing the lanes side by side is what vectorizes.
    fn add(&mut self, chunk: &[u8; Self::WIDTH]) {
        for i in 0..Self::WIDTH {
            let b = chunk[i];
            self.unprintable[i] |= u8::from(!(0x20..=0x7e).contains(&b));
            self.sum[i] ^= b;
            self.commas[i] += u8::from(b == b',');
            self.stars[i] += u8::from(b == b'*');
        }
    }
}

impl Scan {
    /// Scans at most [`MAX_LINE`] bytes.
    fn of(bytes: &[u8]) -> Self {
        debug_assert!(bytes.len() <= MAX_LINE);
        let mut lanes = Lanes::default();
        let mut chunks = bytes.chunks_exact(Lanes::WIDTH);
        for chunk in &mut chunks {
            let mut block = [0u8; Lanes::WIDTH];
            block.copy_from_slice(chunk);
            lanes.add(&block);
        }
        // The last bytes, padded with spaces: printable, neither comma nor star, and each pair
        // of them leaves the sum unchanged.
        let rest = chunks.remainder();
        let mut sum = 0;
        if !rest.is_empty() {
            let mut block = [b' '; Lanes::WIDTH];
            block[..rest.len()].copy_from_slice(rest);
            lanes.add(&block);
            if (Lanes::WIDTH - rest.len()) % 2 == 1 {
                sum = b' ';
            }
        }
        // The lanes folded as one 128-bit word each rather than byte by byte.
        let mut xor = u128::from_le_bytes(lanes.sum);
        for shift in [64, 32, 16, 8] {
            xor ^= xor >> shift;
        }
        Self {
            printable: u128::from_le_bytes(lanes.unprintable) == 0,
            sum: sum ^ xor as u8,
            commas: Self::lane_sum(lanes.commas),
            stars: Self::lane_sum(lanes.stars),
        }
    }

    /// The sum of 16 counters of at most 64 each.
    fn lane_sum(lanes: [u8; Lanes::WIDTH]) -> usize {
        const PAIRS: u128 = 0x00ff_00ff_00ff_00ff_00ff_00ff_00ff_00ff;
        const ONES: u128 = 0x0001_0001_0001_0001_0001_0001_0001_0001;
        let v = u128::from_le_bytes(lanes);
        // Byte pairs summed into 16-bit lanes, then every 16-bit lane into the top one.
        let pairs = (v & PAIRS) + ((v >> 8) & PAIRS);
        (pairs.wrapping_mul(ONES) >> 112) as usize
    }
}

pub(crate) fn hex_value(b: u8) -> u8 {
    match b {
        b'0'..=b'9' => b - b'0',
        b'a'..=b'f' => b - b'a' + 10,
        _ => b - b'A' + 10,
    }
}

/// The fields after the address: their text (joined by `,`, or by spaces in a text command
/// as received) and how many there are.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Fields<'a> {
    address: &'a str,
    text: &'a str,
    count: usize,
    separator: u8,
    line: Option<&'a str>,
    blanks: Blanks,
}

impl<'a> Fields<'a> {
    /// `count` fields joined by `,` in `text`, of the sentence at `address` (named in errors).
    pub const fn new(address: &'a str, text: &'a str, count: usize) -> Self {
        Self { address, text, count, separator: b',', line: None, blanks: Blanks::EMPTY }
    }

    /// `count` words joined by single spaces in `text`, after the command word `address`.
    pub const fn words(address: &'a str, text: &'a str, count: usize) -> Self {
        Self { address, text, count, separator: b' ', line: None, blanks: Blanks::EMPTY }
    }

    /// The same fields, belonging to the text command `line` (kept by the parsed command).
    pub const fn with_line(self, line: &'a str) -> Self {
        Self { line: Some(line), ..self }
    }

    /// The same fields with wire field `index` (1-based) read as empty (lenient parsing).
    #[must_use]
    pub fn with_blank(self, index: usize) -> Self {
        Self { blanks: self.blanks.with(index), ..self }
    }

    /// The same fields with the number of wire field `index` (1-based) kept outside its range.
    #[must_use]
    pub fn with_range_kept(self, index: usize) -> Self {
        Self { blanks: self.blanks.with(index | RANGE_KEPT), ..self }
    }

    /// The fields lenient parsing reads as empty.
    pub const fn blanks(&self) -> &Blanks {
        &self.blanks
    }

    /// The text of wire field `index` (1-based) as the readers see it: empty when it is blanked.
    pub fn get(&self, index: usize) -> Option<&'a str> {
        if self.blanks.contains(index) {
            return (index >= 1 && index <= self.count).then_some("");
        }
        self.iter().nth(index.checked_sub(1)?)
    }

    /// The whole command line, for a text command.
    pub const fn line(&self) -> Option<&'a str> {
        self.line
    }

    /// The address of the sentence.
    pub const fn address(&self) -> &'a str {
        self.address
    }

    /// The talker of a standard sentence whose talker has `len` characters (4 for the query,
    /// `$CCGPQ`: the requester's and the listener's talker IDs): the first `len` characters of
    /// its address (empty for an address too short to be one).
    pub fn talker_of(&self, len: usize) -> &'a str {
        if self.address.len() > len {
            self.address.get(..len).unwrap_or("")
        } else {
            ""
        }
    }

    /// The talker ID of a standard sentence: the first 2 characters of its address (empty for
    /// an address too short to be one).
    pub fn talker(&self) -> &'a str {
        if self.address.len() > 2 {
            self.address.get(..2).unwrap_or("")
        } else {
            ""
        }
    }

    /// The fields as received, joined by `,` (by spaces in a text command as received).
    pub const fn as_str(&self) -> &'a str {
        self.text
    }

    /// How many fields there are.
    pub const fn len(&self) -> usize {
        self.count
    }

    /// Whether there are no fields at all (not even an empty one).
    pub const fn is_empty(&self) -> bool {
        self.count == 0
    }

    /// The field texts, in order.
    pub fn iter(&self) -> FieldIter<'a> {
        FieldIter { rest: self.text, left: self.count, separator: self.separator }
    }

    /// A reader that hands out the fields in order to the typed field readers.
    pub fn reader(&self) -> Reader<'a> {
        Reader {
            address: self.address,
            rest: self.text,
            separator: self.separator,
            blanks: self.blanks,
            ignore_case: false,
            any_range: false,
            index: 0,
            group: "",
            entry: 0,
        }
    }

    /// Checks the field count against a layout: how many times its repeated group occurs and
    /// how many optional trailing wire fields follow, or `too_few_fields`/`too_many_fields`.
    pub fn shape(&self, shape: &Shape) -> Result<(usize, usize), Error<'a>> {
        let (count, fixed, optional) = (self.count, shape.fixed, shape.optional);
        let sentence = shape.sentence;
        let too_few = |need| Message::TooFew { sentence, need, found: count };
        let too_many = |limit| Message::TooMany { sentence, limit, found: count };
        let error = |message| Error::new(Some(self.address), message);
        let Some(group) = &shape.group else {
            if count < fixed {
                return Err(error(too_few(fixed)));
            }
            if count > fixed + optional {
                return Err(error(too_many(fixed + optional)));
            }
            return Ok((0, count - fixed));
        };
        let width = group.width;
        if count < fixed + group.min * width {
            return Err(error(too_few(fixed + group.min * width)));
        }
        let rest = count - fixed;
        let repeats = (rest / width).min(group.max);
        let extra = rest - repeats * width;
        if extra > optional {
            if repeats == group.max {
                return Err(error(too_many(fixed + group.max * width + optional)));
            }
            return Err(error(Message::GroupCut { sentence, group: group.id, width, left: extra }));
        }
        Ok((repeats, extra))
    }
}

impl<'a> IntoIterator for &Fields<'a> {
    type Item = &'a str;
    type IntoIter = FieldIter<'a>;

    fn into_iter(self) -> FieldIter<'a> {
        self.iter()
    }
}

/// Iterator over the field texts of [`Fields`].
#[derive(Clone, Debug)]
pub struct FieldIter<'a> {
    rest: &'a str,
    left: usize,
    separator: u8,
}

impl<'a> Iterator for FieldIter<'a> {
    type Item = &'a str;

    fn next(&mut self) -> Option<&'a str> {
        if self.left == 0 {
            return None;
        }
        self.left -= 1;
        Some(take(&mut self.rest, self.separator))
    }

    fn size_hint(&self) -> (usize, Option<usize>) {
        (self.left, Some(self.left))
    }
}

impl ExactSizeIterator for FieldIter<'_> {}

/// The first `count` fields of `text` (all of it when it has fewer), without the separator after
/// them.
pub(crate) fn fields_text(text: &str, separator: u8, count: usize) -> &str {
    if count == 0 {
        return &text[..0];
    }
    let mut left = count;
    for (at, &b) in text.as_bytes().iter().enumerate() {
        if b == separator {
            left -= 1;
            if left == 0 {
                return &text[..at];
            }
        }
    }
    text
}

/// Splits off the text before the next `separator` (all of `rest` when there is none).
#[inline(always)]
fn take<'a>(rest: &mut &'a str, separator: u8) -> &'a str {
    let bytes = rest.as_bytes();
    let mut at = 0;
    while at < bytes.len() && bytes[at] != separator {
        at += 1;
    }
    // The separator is ASCII, so both cuts fall on character boundaries.
    let (field, tail) = rest.split_at(at);
    *rest = tail.get(1..).unwrap_or("");
    field
}

/// How the fields of a layout are counted: required fields outside the repeated group, optional
/// trailing fields, and the group.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Shape {
    /// The sentence id, for messages.
    pub sentence: &'static str,
    /// Wire fields outside the group that are always present.
    pub fixed: usize,
    /// Wire fields of the optional trailing fields.
    pub optional: usize,
    /// The repeated group, if any.
    pub group: Option<GroupShape>,
}

/// The repeated group of a layout.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct GroupShape {
    /// The group id, for messages.
    pub id: &'static str,
    /// Wire fields per entry.
    pub width: usize,
    /// Fewest entries.
    pub min: usize,
    /// Most entries.
    pub max: usize,
}

/// Hands out the fields of a sentence in wire order to the typed readers below. Each reader
/// takes the next field (two for latitude and longitude): an empty field is `None`, text that
/// does not fit the type is a `bad_field` error naming the field (`id`, or `group[n].id` inside
/// [`Reader::group`]).
#[derive(Clone, Debug)]
pub struct Reader<'a> {
    address: &'a str,
    rest: &'a str,
    separator: u8,
    blanks: Blanks,
    ignore_case: bool,
    /// Numbers are not held to their range (a parsed sentence's entries, read again).
    any_range: bool,
    index: usize,
    group: &'static str,
    entry: usize,
}

impl<'a> Reader<'a> {
    /// The same reader for a text command: keywords and enum codes match ignoring case.
    pub const fn ignoring_case(self) -> Self {
        Self { ignore_case: true, ..self }
    }

    /// A reader of `text` alone: the entries of a group as a parsed sentence keeps them, with the
    /// fields lenient parsing read as empty (1-based in `text`); parsing has held each number to
    /// its range or kept it outside.
    pub(crate) const fn over(text: &'a str, separator: u8, blanks: Blanks) -> Self {
        Self {
            address: "",
            rest: text,
            separator,
            blanks,
            ignore_case: false,
            any_range: true,
            index: 0,
            group: "",
            entry: 0,
        }
    }

    /// Reads `count` entries of the repeated group `id`, each of `width` wire fields, with `read`,
    /// and keeps them as received (read again with `read` when asked for).
    #[inline(always)]
    pub fn entries<T: Copy + Default>(
        &mut self,
        id: &'static str,
        count: usize,
        width: usize,
        read: ReadEntry<'a, T>,
    ) -> Result<Entries<'a, T>, Error<'a>> {
        let (start, first) = (self.rest, self.index);
        self.group = id;
        for entry in 1..=count {
            self.entry = entry;
            read(self)?;
        }
        (self.group, self.entry) = ("", 0);
        let fields = count * width;
        let wire = Texts::joined(fields_text(start, self.separator, fields), fields, self.separator)
            .blanking(self.blanks.within(first, fields));
        Ok(Entries::on_wire(wire, count, self.ignore_case, read))
    }

    /// Reads `count` values of the repeated group `group` of one text field `id` (each at most
    /// `max_length`), kept as their wire text.
    pub fn texts(
        &mut self,
        group: &'static str,
        id: &'static str,
        count: usize,
        expected: &'static str,
        max_length: Option<usize>,
    ) -> Result<Texts<'a>, Error<'a>> {
        let start = self.rest;
        let mut end = 0;
        let mut blanked = Blanks::default();
        for entry in 1..=count {
            let offset = start.len() - self.rest.len();
            self.index += 1;
            let raw = take(&mut self.rest, self.separator);
            let text = if !self.blanks.is_empty() && self.blanks.contains(self.index) {
                blanked = blanked.with(entry);
                ""
            } else {
                raw
            };
            if max_length.is_some_and(|max| text.len() > max) {
                return Err(Error::bad_field(self.address, self.index, Name::entry(group, entry, id), expected, text));
            }
            end = offset + raw.len();
        }
        Ok(Texts::joined(&start[..end], count, self.separator).blanking(blanked))
    }

    fn name(&self, id: &'static str) -> Name {
        Name::entry(self.group, self.entry, id)
    }

    /// The `bad_field` error of field `id` at the current index: kept out of line, so that the
    /// readers' fast path stays small.
    #[cold]
    #[inline(never)]
    fn bad_field(&self, id: &'static str, expected: &'static str, text: &'a str) -> Error<'a> {
        Error::bad_field(self.address, self.index, self.name(id), expected, text)
    }

    #[inline(always)]
    fn next_text(&mut self) -> &'a str {
        self.index += 1;
        let text = take(&mut self.rest, self.separator);
        if self.blanks.is_empty() || !self.blanks.contains(self.index) {
            return text;
        }
        ""
    }

    #[inline(always)]
    fn read<T>(
        &mut self,
        id: &'static str,
        expected: &'static str,
        parse: impl FnOnce(&'a str) -> Option<T>,
    ) -> Result<Option<T>, Error<'a>> {
        let text = self.next_text();
        if text.is_empty() {
            return Ok(None);
        }
        match parse(text) {
            Some(value) => Ok(Some(value)),
            None => Err(self.bad_field(id, expected, text)),
        }
    }

    /// An integer `[+-]digits` within `range`.
    #[inline(always)]
    pub fn integer(
        &mut self,
        id: &'static str,
        expected: &'static str,
        range: Range,
    ) -> Result<Option<Number>, Error<'a>> {
        self.number(id, expected, range, true)
    }

    /// A decimal number `[+-]digits[.digits]` within `range`.
    #[inline(always)]
    pub fn decimal(
        &mut self,
        id: &'static str,
        expected: &'static str,
        range: Range,
    ) -> Result<Option<Number>, Error<'a>> {
        self.number(id, expected, range, false)
    }

    /// An integer or decimal field: the usual unsigned field in range is read in one pass over
    /// its bytes, up to the separator; anything else (a sign, a field out of range or not a
    /// number, a blanked field) is read again from its start by the general path.
    #[inline(always)]
    fn number(
        &mut self,
        id: &'static str,
        expected: &'static str,
        range: Range,
        integer: bool,
    ) -> Result<Option<Number>, Error<'a>> {
        if self.blanks.is_empty() {
            match self.unsigned_number(integer) {
                Some((0, None)) => {
                    self.skip(0);
                    return Ok(None);
                }
                Some((end, Some(number))) if range.contains(number) => {
                    self.skip(end);
                    return Ok(Some(number));
                }
                _ => {}
            }
        }
        self.any_number(id, expected, range, integer)
    }

    /// [`Reader::number`] for a field its fast path leaves: kept out of line. Outside its range,
    /// an error that says so, unless the field is one whose number is kept outside its range.
    #[cold]
    #[inline(never)]
    fn any_number(
        &mut self,
        id: &'static str,
        expected: &'static str,
        range: Range,
        integer: bool,
    ) -> Result<Option<Number>, Error<'a>> {
        let text = self.next_text();
        if text.is_empty() {
            return Ok(None);
        }
        let Some(number) = Number::parse(text, integer) else {
            return Err(self.bad_field(id, expected, text));
        };
        if range.contains(number) || self.any_range || self.blanks.contains(self.index | RANGE_KEPT) {
            return Ok(Some(number));
        }
        Err(self.bad_field(id, expected, text).outside_range())
    }

    /// The next field as `digits[.digits]` (no point for an `integer`) without taking it: where
    /// it ends and its value (`None` when empty); `None` when it is anything else.
    #[inline(always)]
    fn unsigned_number(&self, integer: bool) -> Option<(usize, Option<Number>)> {
        let bytes = self.rest.as_bytes();
        let (mut digits, mut end, mut point_at) = (0i64, 0, None);
        while let Some(&b) = bytes.get(end) {
            let digit = b.wrapping_sub(b'0');
            if digit <= 9 {
                digits = digits.wrapping_mul(10).wrapping_add(i64::from(digit));
            } else if b == self.separator {
                break;
            } else if b == b'.' && point_at.is_none() && !integer {
                point_at = Some(end);
            } else {
                return None;
            }
            end += 1;
        }
        if end == 0 {
            return Some((0, None));
        }
        let count = end - usize::from(point_at.is_some());
        if count == 0 || count > MAX_DIGITS {
            return None;
        }
        let whole = point_at.unwrap_or(end);
        let (scale, width) = ((count - whole) as u8, whole as u8);
        Some((end, Some(Number { digits, scale, width, sign: Sign::Implicit, point: point_at.is_some() })))
    }

    /// Takes the next field, `end` bytes long.
    #[inline(always)]
    fn skip(&mut self, end: usize) {
        self.index += 1;
        self.rest = self.rest.get(end + 1..).unwrap_or("");
    }

    /// Hex digits.
    #[inline(always)]
    pub fn hex(&mut self, id: &'static str) -> Result<Option<Hex>, Error<'a>> {
        self.read(id, "hex number", Hex::parse)
    }

    /// A time `hhmmss[.s…]`.
    #[inline(always)]
    pub fn time(&mut self, id: &'static str) -> Result<Option<Time>, Error<'a>> {
        self.read(id, "time hhmmss[.s]", Time::parse)
    }

    /// A date `ddmmyy`.
    #[inline(always)]
    pub fn date(&mut self, id: &'static str) -> Result<Option<Date>, Error<'a>> {
        self.read(id, "date ddmmyy", Date::parse)
    }

    /// One character.
    #[inline(always)]
    pub fn char(&mut self, id: &'static str) -> Result<Option<char>, Error<'a>> {
        self.read(id, "one character", |t| {
            let mut chars = t.chars();
            chars.next().filter(|_| chars.next().is_none())
        })
    }

    /// Exactly `value` (or nothing).
    #[inline(always)]
    pub fn literal(
        &mut self,
        id: &'static str,
        expected: &'static str,
        value: &'static str,
    ) -> Result<Option<&'a str>, Error<'a>> {
        self.read(id, expected, |t| (t == value).then_some(t))
    }

    /// Any text, at most `max_length` characters.
    #[inline(always)]
    pub fn text(
        &mut self,
        id: &'static str,
        expected: &'static str,
        max_length: Option<usize>,
    ) -> Result<Option<&'a str>, Error<'a>> {
        self.read(id, expected, |t| max_length.is_none_or(|max| t.len() <= max).then_some(t))
    }

    /// Exactly the word `keyword` (ignoring case in a text command); never empty.
    #[inline(always)]
    pub fn keyword(&mut self, id: &'static str, keyword: &'static str) -> Result<(), Error<'a>> {
        let text = self.next_text();
        if text == keyword || (self.ignore_case && upper_eq(text, keyword)) {
            return Ok(());
        }
        Err(self.bad_field(id, keyword, text))
    }

    /// A code of enum `E` (ignoring case in a text command), or an unknown one of the same form.
    #[inline(always)]
    pub fn code<E: CodeEnum>(&mut self, id: &'static str) -> Result<Option<Code<'a, E>>, Error<'a>> {
        if self.ignore_case {
            return self.read(id, E::EXPECTED, |t| Code::parse_ignoring_case(t, E::MIN_LEN, E::MAX_LEN));
        }
        self.read(id, E::EXPECTED, |t| Code::parse(t, E::MIN_LEN, E::MAX_LEN))
    }

    /// A run of one-character codes of enum `E`, at most `max_length`.
    #[inline(always)]
    pub fn code_chars<E: CodeEnum>(
        &mut self,
        id: &'static str,
        max_length: Option<usize>,
    ) -> Result<Option<CodeChars<'a, E>>, Error<'a>> {
        self.read(id, E::EXPECTED_CHARS, |t| CodeChars::parse(t, max_length))
    }

    /// A latitude: `ddmm.mmmm` and `N`/`S`, both empty or both set.
    #[inline(always)]
    pub fn latitude(&mut self, id: &'static str) -> Result<Option<Coordinate>, Error<'a>> {
        self.coordinate(id, (LATITUDE, 2, 90), (NORTH_SOUTH, ['N', 'S']))
    }

    /// A longitude: `dddmm.mmmm` and `E`/`W`, both empty or both set.
    #[inline(always)]
    pub fn longitude(&mut self, id: &'static str) -> Result<Option<Coordinate>, Error<'a>> {
        self.coordinate(id, (LONGITUDE, 3, 180), (EAST_WEST, ['E', 'W']))
    }

    #[inline(always)]
    fn coordinate(
        &mut self,
        id: &'static str,
        (expected, degree_digits, max_degrees): (&'static str, usize, u8),
        (hemisphere_expected, hemispheres): (&'static str, [char; 2]),
    ) -> Result<Option<Coordinate>, Error<'a>> {
        let text = self.next_text();
        let hemisphere = self.next_text();
        let (index, name) = (self.index - 1, self.name(id));
        if text.is_empty() {
            if !hemisphere.is_empty() {
                return Err(Error::bad_field(self.address, index, name, expected, text));
            }
            return Ok(None);
        }
        let Some(mut value) = Coordinate::parse(text, degree_digits, max_degrees) else {
            return Err(Error::bad_field(self.address, index, name, expected, text));
        };
        let mut chars = hemisphere.chars();
        match (chars.next(), chars.next()) {
            (Some(c), None) if hemispheres.contains(&c) => value.hemisphere = c,
            _ => return Err(Error::bad_field(self.address, index + 1, name, hemisphere_expected, hemisphere)),
        }
        Ok(Some(value))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn naive(bytes: &[u8]) -> (bool, u8, usize, usize) {
        let printable = bytes.iter().all(|b| (0x20..=0x7e).contains(b));
        let sum = bytes.iter().fold(0, |x, b| x ^ b);
        let count = |c| bytes.iter().filter(|&&b| b == c).count();
        (printable, sum, count(b','), count(b'*'))
    }

    #[test]
    fn scan_agrees_with_a_byte_loop() {
        let mut buf = [b'a'; 24];
        for len in [0, 1, 7, 8, 9, 16, 23, 24] {
            for at in 0..len {
                for byte in 0..=255u8 {
                    buf[at] = byte;
                    let scan = Scan::of(&buf[..len]);
                    assert_eq!((scan.printable, scan.sum, scan.commas, scan.stars), naive(&buf[..len]));
                    buf[at] = b'a';
                }
            }
        }
    }

    #[test]
    fn frames_split_address_fields_and_checksum() {
        let frame = Frame::parse(b"$GPHDT,1.0,T*34").unwrap();
        assert_eq!((frame.start, frame.address, frame.fields.len()), ("$", "GPHDT", 2));
        assert!(frame.fields.iter().eq(["1.0", "T"]));
        assert_eq!(frame.fields.talker(), "GP");
        let query = Frame::parse(b"$CCGPQ,GGA*2B").unwrap();
        assert_eq!((query.fields.talker_of(talker_length(QUERY)), talker_length("GGA")), ("CCGP", 2));
        let err = Frame::parse(b"!AB*aB").unwrap_err();
        assert_eq!(err.message(), &Message::BadChecksum { text: "aB" });
        let err = Frame::parse(b"!AB*2a").unwrap_err();
        assert_eq!(err.message(), &Message::ChecksumMismatch { sent: "2a", computed: 3 });
        let fields = Frame::parse(b"$A,*6D").unwrap().fields;
        assert_eq!((fields.as_str(), fields.len()), ("", 1));
        assert_eq!(Frame::parse(b"$A,*,*41").unwrap_err().message(), &Message::BadChecksum { text: ",*41" });
        assert!(Frame::parse(b"$PSTMSAVEPAR").unwrap().fields.is_empty());
        let frame = Frame::parse(b"$PSTMSETPAR,1121,10*").unwrap();
        assert_eq!((frame.fields.len(), frame.checksum), (2, Checksum::Empty));
        // one hex digit that is the checksum (0x01): kept, unless strict; never one that differs
        assert_eq!(Frame::parse(b"$PXYZ,0AW*1").unwrap().checksum, Checksum::ShortUpper);
        let err = Frame::parse_checked(b"$PXYZ,0AW*1", false, true).unwrap_err();
        assert_eq!(err.message(), &Message::BadChecksum { text: "1" });
        assert_eq!(Frame::parse(b"$PXYZ,0AW*2").unwrap_err().message(), &Message::BadChecksum { text: "2" });
        assert_eq!(Checksum::ShortLower.digits(0x0b), Some(([b'b', 0], 1)));
        assert_eq!(Checksum::ShortLower.digits(0x1b), Some(([b'1', b'b'], 2)));
    }

    #[test]
    fn text_commands_split_on_single_spaces() {
        let frame = Frame::parse_text(b"nmeatalker GGA,1  GP").unwrap();
        assert_eq!((frame.start, frame.address, frame.checksum), ("", "nmeatalker", Checksum::None));
        assert!(frame.fields.iter().eq(["GGA,1", "", "GP"]));
        assert_eq!(frame.fields.line(), Some("nmeatalker GGA,1  GP"));
        assert!(Frame::parse_text(b"LOG").unwrap().fields.is_empty());
        let err = Frame::parse_text(b"LOG \x01").unwrap_err();
        assert_eq!(err.message(), &Message::NotPrintable { byte: 1, offset: 4 });
        assert!(is_command_word(b"nmeaTalker", "NMEATALKER"));
        assert!(is_command_word(b"cla\xdf", "CLASS"));
        assert!(!is_command_word(b"NMEATALKERS", "NMEATALKER"));
        assert_eq!(first_word(b"log gga"), b"log");
    }
}
