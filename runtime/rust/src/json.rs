//! Reading the tools' JSON back, for the `encode` verb (needs `std`).
//!
//! A small reader that accepts what Python's `json.loads` accepts, over a line taken as Latin-1
//! (each byte one character), and the helpers that turn decode's lossless `fields` back into wire
//! fields, with the `bad_json` messages of the Python runtime.

use std::fmt;

use super::error::Error;
use super::frame::{talker_length, Fields};
use super::types::Checksum;
use super::write::write_json_str;

/// A JSON value. Numbers are recognised but not kept: decode's JSON never needs them back.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Value {
    /// `null`
    Null,
    /// `true` or `false`
    Bool(bool),
    /// Any number but an integer (also `NaN`, `Infinity`, `-Infinity`, as Python reads them).
    Number,
    /// An integer: its value when it is positive and fits a `u64` (else `None`: zero, negative
    /// or huge, never the index of a field).
    Integer(Option<u64>),
    /// A string.
    String(String),
    /// An array.
    Array(Vec<Value>),
    /// An object, members in the order written (a repeated key: the last one counts).
    Object(Vec<(String, Value)>),
}

/// Most nested arrays and objects `encode` reads (counted outside strings), in every tool.
/// Deeper JSON is "not JSON".
pub const MAX_DEPTH: usize = 500;

/// Most nested arrays and objects of a line whose `"ok"` the tool checks first: the same limit.
pub const SKIP_CHECK_DEPTH: usize = MAX_DEPTH;

/// Python refuses to convert integers of more digits than this.
const MAX_INT_DIGITS: usize = 4300;

impl Value {
    /// Reads one JSON text (surrounding whitespace allowed); `None` when it is not JSON (or
    /// nests deeper than [`MAX_DEPTH`]).
    pub fn parse(text: &[u8]) -> Option<Self> {
        Self::parse_nested(text, MAX_DEPTH).map(|(value, _)| value)
    }

    /// Reads one JSON text nesting at most `max_depth` arrays and objects; the value and how
    /// deep it nests.
    pub fn parse_nested(text: &[u8], max_depth: usize) -> Option<(Self, usize)> {
        let mut reader = JsonReader { text, pos: 0, depth: 0, deepest: 0, max_depth };
        reader.skip_space();
        let value = reader.value()?;
        reader.skip_space();
        (reader.pos == text.len()).then_some((value, reader.deepest))
    }

    /// The member `key` of an object (the last one when repeated).
    pub fn get(&self, key: &str) -> Option<&Value> {
        match self {
            Self::Object(members) => members.iter().rev().find(|(k, _)| k == key).map(|(_, v)| v),
            _ => None,
        }
    }

    /// Whether this is an object.
    pub const fn is_object(&self) -> bool {
        matches!(self, Self::Object(_))
    }
}

struct JsonReader<'t> {
    text: &'t [u8],
    pos: usize,
    depth: usize,
    deepest: usize,
    max_depth: usize,
}

impl JsonReader<'_> {
    fn peek(&self) -> Option<u8> {
        self.text.get(self.pos).copied()
    }

    fn bump(&mut self) -> Option<u8> {
        let b = self.peek()?;
        self.pos += 1;
        Some(b)
    }

    fn skip_space(&mut self) {
        while matches!(self.peek(), Some(b' ' | b'\t' | b'\n' | b'\r')) {
            self.pos += 1;
        }
    }

    fn skip_digits(&mut self) -> usize {
        let start = self.pos;
        while self.peek().is_some_and(|b| b.is_ascii_digit()) {
            self.pos += 1;
        }
        self.pos - start
    }

    fn word(&mut self, word: &str, value: Value) -> Option<Value> {
        if self.text[self.pos..].starts_with(word.as_bytes()) {
            self.pos += word.len();
            Some(value)
        } else {
            None
        }
    }

    fn value(&mut self) -> Option<Value> {
        match self.peek()? {
            b'{' => self.nested(Self::object),
            b'[' => self.nested(Self::array),
            b'"' => self.string().map(Value::String),
            b'n' => self.word("null", Value::Null),
            b't' => self.word("true", Value::Bool(true)),
            b'f' => self.word("false", Value::Bool(false)),
            b'N' => self.word("NaN", Value::Number),
            b'I' => self.word("Infinity", Value::Number),
            b'-' if self.text[self.pos + 1..].starts_with(b"Infinity") => self.word("-Infinity", Value::Number),
            b'-' | b'0'..=b'9' => self.number(),
            _ => None,
        }
    }

    fn nested(&mut self, read: fn(&mut Self) -> Option<Value>) -> Option<Value> {
        self.depth += 1;
        if self.depth > self.max_depth {
            return None;
        }
        self.deepest = self.deepest.max(self.depth);
        let value = read(self);
        self.depth -= 1;
        value
    }

    fn number(&mut self) -> Option<Value> {
        let negative = self.peek() == Some(b'-');
        if negative {
            self.pos += 1;
        }
        let first = self.pos;
        let digits = match self.peek()? {
            b'0' => {
                self.pos += 1;
                1
            }
            b'1'..=b'9' => self.skip_digits(),
            _ => return None,
        };
        let mut float = false;
        if self.peek() == Some(b'.') && self.text.get(self.pos + 1).is_some_and(u8::is_ascii_digit) {
            self.pos += 1;
            self.skip_digits();
            float = true;
        }
        if matches!(self.peek(), Some(b'e' | b'E')) {
            let mark = self.pos;
            self.pos += 1;
            if matches!(self.peek(), Some(b'+' | b'-')) {
                self.pos += 1;
            }
            if self.skip_digits() > 0 {
                float = true;
            } else {
                self.pos = mark;
            }
        }
        if float {
            return Some(Value::Number);
        }
        if digits > MAX_INT_DIGITS {
            return None;
        }
        let value = core::str::from_utf8(&self.text[first..first + digits]).ok().and_then(|t| t.parse::<u64>().ok());
        Some(Value::Integer(value.filter(|&v| v > 0 && !negative)))
    }

    fn hex4(&mut self) -> Option<u32> {
        let digits = self.text.get(self.pos..self.pos + 4)?;
        let mut value = 0;
        for &b in digits {
            value = value << 4 | char::from(b).to_digit(16)?;
        }
        self.pos += 4;
        Some(value)
    }

    fn string(&mut self) -> Option<String> {
        self.pos += 1;
        let mut out = String::new();
        loop {
            match self.bump()? {
                b'"' => return Some(out),
                b'\\' => out.push(self.escape()?),
                0x00..=0x1f => return None,
                byte => out.push(char::from(byte)),
            }
        }
    }

    fn escape(&mut self) -> Option<char> {
        Some(match self.bump()? {
            b'"' => '"',
            b'\\' => '\\',
            b'/' => '/',
            b'b' => '\u{8}',
            b'f' => '\u{c}',
            b'n' => '\n',
            b'r' => '\r',
            b't' => '\t',
            b'u' => {
                let unit = self.hex4()?;
                if (0xd800..0xdc00).contains(&unit) && self.text[self.pos..].starts_with(b"\\u") {
                    let mark = self.pos;
                    self.pos += 2;
                    let low = self.hex4()?;
                    if (0xdc00..0xe000).contains(&low) {
                        return char::from_u32(0x10000 + ((unit - 0xd800) << 10) + (low - 0xdc00));
                    }
                    self.pos = mark;
                }
                // A lone surrogate, which a Rust string cannot hold: a private-use character
                // with the same low byte stands in (all that matters of it is that low byte).
                char::from_u32(unit).unwrap_or_else(|| char::from_u32(0xe000 | (unit & 0xff)).unwrap_or('\u{e000}'))
            }
            _ => return None,
        })
    }

    fn array(&mut self) -> Option<Value> {
        self.pos += 1;
        self.skip_space();
        let mut items = Vec::new();
        if self.peek() == Some(b']') {
            self.pos += 1;
            return Some(Value::Array(items));
        }
        loop {
            items.push(self.value()?);
            self.skip_space();
            match self.bump()? {
                b',' => self.skip_space(),
                b']' => return Some(Value::Array(items)),
                _ => return None,
            }
        }
    }

    fn object(&mut self) -> Option<Value> {
        self.pos += 1;
        self.skip_space();
        let mut members = Vec::new();
        if self.peek() == Some(b'}') {
            self.pos += 1;
            return Some(Value::Object(members));
        }
        loop {
            if self.peek() != Some(b'"') {
                return None;
            }
            let key = self.string()?;
            self.skip_space();
            if self.bump()? != b':' {
                return None;
            }
            self.skip_space();
            members.push((key, self.value()?));
            self.skip_space();
            match self.bump()? {
                b',' => self.skip_space(),
                b'}' => return Some(Value::Object(members)),
                _ => return None,
            }
        }
    }
}

/// `obj[key]`, or `missing "key"`.
pub fn member<'v>(obj: &'v Value, key: &str) -> Result<&'v Value, Error<'static>> {
    obj.get(key).ok_or_else(|| Error::bad_json(format!("missing \"{key}\"")))
}

/// `obj[key]` as an array, or `"key" is not an array`.
pub fn list<'v>(obj: &'v Value, key: &str) -> Result<&'v [Value], Error<'static>> {
    match member(obj, key)? {
        Value::Array(items) => Ok(items),
        _ => Err(Error::bad_json(format!("\"{key}\" is not an array"))),
    }
}

/// `obj[key]` as a string or null.
pub fn opt_text<'v>(obj: &'v Value, key: &str) -> Result<Option<&'v str>, Error<'static>> {
    match member(obj, key)? {
        Value::Null => Ok(None),
        Value::String(text) => Ok(Some(text)),
        _ => Err(Error::bad_json(format!("\"{key}\" is not a string or null"))),
    }
}

/// `obj[key]` as letters and digits (an address, a talker ID, a command word).
pub fn word<'v>(obj: &'v Value, key: &str) -> Result<&'v str, Error<'static>> {
    match member(obj, key)? {
        Value::String(text) if !text.is_empty() && text.bytes().all(|b| b.is_ascii_alphanumeric()) => Ok(text),
        _ => Err(Error::bad_json(format!("\"{key}\" is not letters and digits"))),
    }
}

/// The talker of standard sentence `sentence`: two letters and digits, as decode gives it (a
/// longer one would make another address); four, two talker IDs, for the query.
pub fn talker<'v>(obj: &'v Value, sentence: &str) -> Result<&'v str, Error<'static>> {
    match word(obj, "talker")? {
        talker if talker.len() == talker_length(sentence) => Ok(talker),
        _ if talker_length(sentence) == 4 => Err(Error::bad_json("\"talker\" is not four letters and digits")),
        _ => Err(Error::bad_json("\"talker\" is not two letters and digits")),
    }
}

/// `obj[key]` as a string.
pub fn str_member<'v>(obj: &'v Value, key: &str) -> Result<&'v str, Error<'static>> {
    match member(obj, key)? {
        Value::String(text) => Ok(text),
        _ => Err(Error::bad_json(format!("\"{key}\" is not a string"))),
    }
}

/// How a received checksum was written: absent, empty (a bare `*`), or lower case when it has
/// a letter from `a` to `z`, in one digit when it is one character ([`Checksum::of`]).
pub fn checksum_case(text: Option<&str>) -> Checksum {
    Checksum::of(text)
}

struct JsonStr<'t>(&'t str);

impl fmt::Display for JsonStr<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write_json_str(f, self.0)
    }
}

/// The TAG blocks of a `"tag_blocks"` array written back (each block's parameters and its
/// checksum, computed in the letter case its `"checksum"` gives); unchecked: parsing reads them.
pub fn tag_blocks(items: &Value) -> Result<String, Error<'static>> {
    let not_blocks = || Error::bad_json("\"tag_blocks\" is not an array of TAG blocks");
    let Value::Array(items) = items else {
        return Err(not_blocks());
    };
    if items.is_empty() {
        return Err(not_blocks());
    }
    let mut text = String::new();
    for item in items {
        let mut body = String::new();
        for (i, param) in list(item, "params")?.iter().enumerate() {
            let (code, value) = (tag_text(param, "code")?, tag_text(param, "value")?);
            body.extend([if i == 0 { "" } else { "," }, code, ":", value]);
        }
        let sum = super::frame::checksum(body.as_bytes());
        text += &match checksum_case(Some(str_member(item, "checksum")?)) {
            Checksum::Lower => format!("\\{body}*{sum:02x}\\"),
            _ => format!("\\{body}*{sum:02X}\\"),
        };
    }
    Ok(text)
}

/// A TAG block parameter's code or value: printable ASCII without `,`, `*`, `\`.
fn tag_text<'v>(param: &'v Value, key: &str) -> Result<&'v str, Error<'static>> {
    let text = str_member(param, key)?;
    if text.bytes().all(|b| (0x20..=0x7e).contains(&b) && b != b',' && b != b'*' && b != b'\\') {
        return Ok(text);
    }
    Err(Error::bad_json(format!(
        "TAG block text {} holds ',', '*', a backslash or a byte outside printable ASCII",
        JsonStr(text)
    )))
}

/// The wire text of a field value: a string or null (empty), printable ASCII without `,`, `*`.
pub fn text(value: &Value) -> Result<&str, Error<'static>> {
    match value {
        Value::Null => Ok(""),
        Value::String(text) => {
            if text.bytes().all(|b| (0x20..=0x7e).contains(&b) && b != b',' && b != b'*') {
                Ok(text)
            } else {
                Err(Error::bad_json(format!(
                    "field text {} holds ',', '*' or a byte outside printable ASCII",
                    JsonStr(text)
                )))
            }
        }
        _ => Err(Error::bad_json("a field value is not a string or null")),
    }
}

/// Wire fields rebuilt from JSON: their text joined by `,`, and how many there are.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct WireFields {
    text: String,
    count: usize,
}

impl WireFields {
    /// Appends one field's text.
    pub fn push(&mut self, text: &str) {
        if self.count > 0 {
            self.text.push(',');
        }
        self.text.push_str(text);
        self.count += 1;
    }

    /// Appends the texts of one field value: a string or null, or for latitude and longitude
    /// (`width` 2) null or an array of two.
    pub fn value(&mut self, value: &Value, width: usize) -> Result<(), Error<'static>> {
        if width == 1 {
            self.push(text(value)?);
            return Ok(());
        }
        match value {
            Value::Null => (0..width).for_each(|_| self.push("")),
            Value::Array(items) if items.len() == width => {
                for item in items {
                    self.push(text(item)?);
                }
            }
            _ => return Err(Error::bad_json("a latitude or longitude is not null or an array of two")),
        }
        Ok(())
    }

    /// Appends the member `key` of `obj` (`missing "key"` when it is not there).
    pub fn member(&mut self, obj: &Value, key: &str, width: usize) -> Result<(), Error<'static>> {
        self.value(member(obj, key)?, width)
    }

    /// Appends the member `key` of `obj` if it is there (an optional trailing field).
    pub fn optional(&mut self, obj: &Value, key: &str, width: usize) -> Result<(), Error<'static>> {
        match obj.get(key) {
            Some(value) => self.value(value, width),
            None => Ok(()),
        }
    }

    /// How many fields there are.
    pub const fn len(&self) -> usize {
        self.count
    }

    /// Whether there are none.
    pub const fn is_empty(&self) -> bool {
        self.count == 0
    }

    /// Replaces the text of field `index` (0-based; ignored past the end).
    pub fn set(&mut self, index: usize, text: &str) {
        if index >= self.count {
            return;
        }
        let mut out = String::with_capacity(self.text.len() + text.len());
        for (i, field) in self.text.split(',').enumerate() {
            if i > 0 {
                out.push(',');
            }
            out.push_str(if i == index { text } else { field });
        }
        self.text = out;
    }

    /// The fields, for parsing, of the sentence at `address`.
    pub fn fields<'a>(&'a self, address: &'a str) -> Fields<'a> {
        Fields::new(address, &self.text, self.count)
    }

    /// The text command these fields make after the command word `word`: the words joined by
    /// single spaces (field texts hold no `,`).
    pub fn command_line(&self, word: &str) -> String {
        let mut line = String::from(word);
        if self.count > 0 {
            line.push(' ');
            line.extend(self.text.chars().map(|c| if c == ',' { ' ' } else { c }));
        }
        line
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reads_what_python_json_loads_reads() {
        for text in ["null", " {} ", "[1, -0.5e3, NaN, -Infinity]", r#"{"a":"\ud83d\ude00\u00e9\/"}"#, "\"\u{7f}\""] {
            assert!(Value::parse(text.as_bytes()).is_some(), "{text}");
        }
        for text in ["", "01", "1.", "-", "[1,]", "{\"a\":1,}", "\"\u{1}\"", "\"\\x\"", "\"\\u12\"", "nul", "{} x"] {
            assert!(Value::parse(text.as_bytes()).is_none(), "{text}");
        }
        let deep = |n: usize| format!("{}{}", "[".repeat(n), "]".repeat(n));
        assert!(Value::parse(deep(MAX_DEPTH).as_bytes()).is_some());
        assert!(Value::parse(deep(MAX_DEPTH + 1).as_bytes()).is_none());
        assert_eq!(Value::parse_nested(deep(3).as_bytes(), 5).map(|(_, depth)| depth), Some(3));
        let long = "1".repeat(4301);
        assert!(Value::parse(long.as_bytes()).is_none());
        assert!(Value::parse(format!("{long}.0").as_bytes()).is_some());
    }

    #[test]
    fn the_last_of_repeated_keys_counts() {
        let value = Value::parse(br#"{"ok":false,"ok":true}"#).unwrap();
        assert_eq!(value.get("ok"), Some(&Value::Bool(true)));
    }

    #[test]
    fn field_texts_are_printable_ascii_without_separators() {
        let value = Value::parse(br#"["a,b"]"#).unwrap();
        let Value::Array(items) = value else { unreachable!() };
        let err = text(&items[0]).unwrap_err();
        assert_eq!(
            err.to_string(),
            r#"bad_json: line: field text "a,b" holds ',', '*' or a byte outside printable ASCII"#
        );
        // lower case when it holds a letter from a to z, whatever else it holds
        assert_eq!(checksum_case(Some("\u{df}")), Checksum::ShortUpper);
        assert_eq!(checksum_case(Some("\u{df}x")), Checksum::Lower);
        assert_eq!(checksum_case(Some("4f")), Checksum::Lower);
        assert_eq!(checksum_case(Some("4F")), Checksum::Upper);
        assert_eq!(checksum_case(Some("")), Checksum::Empty);
    }
}
