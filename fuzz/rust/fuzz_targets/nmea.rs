//! Each input is tried as an NMEA line, as a line of decode's JSON and as a byte stream:
//! - a line that parses must write back to exactly its bytes and its lossless JSON must encode
//!   back to them too; lenient parsing must give the same JSON (listing as problems only numbers
//!   kept outside their range), and requiring a checksum must refuse it exactly when it has none
//!   (text commands never need one);
//! - a line kept only by lenient parsing must still write back to exactly its bytes, and its
//!   JSON (problems included) must encode back to them;
//! - the fast path of `parse` and `parse_with` must give exactly what the general path alone gives
//!   (`parse_general`, `parse_with_general`), with every option;
//! - `serialize_into` must write those same bytes, and give `None` for a buffer a byte short;
//! - JSON that encodes to a sentence must parse again (leniently);
//! - the stream framer must cut the input into the same items as a byte-at-a-time model of the
//!   Python reference's Framer, whether it gets the input whole or in chunks of sizes derived
//!   from the input.
//! Nothing may panic.
#![no_main]
use libfuzzer_sys::fuzz_target;
use nmeaspec::stream::{Framer, Item};
use nmeaspec::{ErrorKind, Options, ProblemKind};

const LENIENT: Options = Options { lenient: true, require_checksum: false, strict: false };
const REQUIRED: Options = Options { lenient: false, require_checksum: true, strict: false };

fn as_line(data: &[u8]) {
    assert_eq!(nmeaspec::parse(data), nmeaspec::paths::parse_general(data), "the fast path disagrees with the general path");
    let strict = Options { lenient: false, require_checksum: false, strict: true };
    for options in [LENIENT, REQUIRED, strict, Options { lenient: true, require_checksum: true, strict: true }] {
        assert_eq!(
            nmeaspec::parse_with(data, options),
            nmeaspec::paths::parse_with_general(data, options),
            "the fast path disagrees with the general path ({options:?})"
        );
    }
    let _ = nmeaspec::json::decode_json(data, true);
    if data.ends_with(b"\n") {
        return; // parse() drops one line ending: the round trip is checked without it
    }
    let Ok(sentence) = nmeaspec::parse(data) else {
        if let Ok(parsed) = nmeaspec::parse_with(data, LENIENT) {
            assert!(!parsed.problems.is_empty(), "lenient parsing kept a line strict parsing refused, without problems");
            assert_eq!(parsed.to_string().as_bytes(), data, "lenient round trip changed the line");
            assert_serialized(|buf| parsed.serialize_into(buf), data);
            let _ = parsed.to_json(true);
            let json = parsed.to_json(false);
            assert_eq!(nmeaspec::json::encode_json(json.as_bytes()).as_bytes(), data, "JSON with problems changed the line");
        }
        return;
    };
    let text = sentence.to_string();
    assert_eq!(text.as_bytes(), data, "round trip changed the line");
    assert_serialized(|buf| sentence.serialize_into(buf), data);
    let json = sentence.to_json(false);
    let _ = sentence.to_json(true);
    assert_eq!(nmeaspec::json::encode_json(json.as_bytes()).as_bytes(), data, "JSON round trip changed the line");
    let lenient = nmeaspec::parse_with(data, LENIENT).expect("lenient parsing refused a valid line");
    assert!(
        lenient.problems.iter().all(|p| p.kind() == ProblemKind::OutOfRange),
        "lenient parsing left a field of a valid line empty"
    );
    assert_eq!(lenient.sentence.to_json(false), json, "lenient parsing disagrees on a valid line");
    let no_checksum = json.ends_with("\"checksum\":null}") || json.ends_with("\"checksum\":\"\"}");
    let text_command = json.starts_with("{\"ok\":true,\"start\":\"\"");
    match nmeaspec::parse_with(data, REQUIRED) {
        Ok(parsed) => {
            assert_eq!(parsed.sentence.to_json(false), json);
            assert!(!no_checksum || text_command, "a sentence without checksum passed");
        }
        Err(err) => {
            assert_eq!(err.kind(), ErrorKind::MissingChecksum);
            assert!(no_checksum && !text_command, "a checksum was asked of a sentence that has one");
        }
    }
}

/// `serialize` writes exactly `data` into a buffer with room to spare, and nothing into one a
/// byte short.
fn assert_serialized(serialize: impl Fn(&mut [u8]) -> Option<usize>, data: &[u8]) {
    let mut buf = [0u8; nmeaspec::MAX_LINE + 64];
    let written = serialize(&mut buf).expect("serialize_into wrote nothing");
    assert_eq!(&buf[..written], data, "serialize_into changed the line");
    assert_eq!(serialize(&mut buf[..written - 1]), None, "serialize_into wrote into a buffer too small");
}

fn as_json(data: &[u8]) {
    let out = nmeaspec::json::encode_json(data);
    if out.starts_with("{\"ok\":false") || out.len() > nmeaspec::MAX_LINE {
        return;
    }
    assert!(nmeaspec::parse_with(out.as_bytes(), LENIENT).is_ok(), "an encoded sentence does not parse: {out:?}");
}

/// What came out of framing: each line's bytes, or the length of an overlong one.
#[derive(Debug, PartialEq, Eq)]
enum Owned {
    Line(Vec<u8>),
    TooLong(usize),
}

impl From<Item<'_>> for Owned {
    fn from(item: Item<'_>) -> Self {
        match item {
            Item::Line(line) => Owned::Line(line.to_vec()),
            Item::TooLong(length) => Owned::TooLong(length),
        }
    }
}

/// The Python reference's Framer, one byte at a time.
fn model(data: &[u8]) -> Vec<Owned> {
    let max = nmeaspec::MAX_LINE;
    let (mut out, mut line, mut length) = (Vec::new(), Vec::new(), 0usize);
    let mut finish = |line: &mut Vec<u8>, length: &mut usize| {
        if *length > 0 {
            out.push(if *length <= max { Owned::Line(line.clone()) } else { Owned::TooLong(*length) });
        }
        line.clear();
        *length = 0;
    };
    for &b in data {
        match b {
            b'\r' | b'\n' => finish(&mut line, &mut length),
            b'$' | b'!' => {
                finish(&mut line, &mut length);
                line.push(b);
                length = 1;
            }
            _ => {
                length += 1;
                if length <= max {
                    line.push(b);
                }
            }
        }
    }
    finish(&mut line, &mut length);
    out
}

fn framed<'c>(chunks: impl Iterator<Item = &'c [u8]>) -> Vec<Owned> {
    let mut framer = Framer::new();
    let mut out = Vec::new();
    for chunk in chunks {
        framer.feed(chunk, |item| out.push(item.into()));
    }
    out.extend(framer.finish().map(Owned::from));
    out
}

fn as_stream(data: &[u8]) {
    let expected = model(data);
    assert_eq!(framed([data].into_iter()), expected, "framing the whole input differs from the model");
    // chunk sizes 1..=7 cycling, as the Python target does, then sizes read from the input
    let mut chunks = Vec::new();
    let (mut rest, mut size) = (data, 1usize);
    while !rest.is_empty() {
        let (chunk, tail) = rest.split_at(size.min(rest.len()));
        chunks.push(chunk);
        rest = tail;
        size = size % 7 + 1;
    }
    assert_eq!(framed(chunks.into_iter()), expected, "framing depends on the chunking");
    let mut chunks = Vec::new();
    let (mut rest, mut at) = (data, 0usize);
    while !rest.is_empty() {
        let size = usize::from(data[at % data.len()]) % 64 + 1;
        let (chunk, tail) = rest.split_at(size.min(rest.len()));
        chunks.push(chunk);
        rest = tail;
        at += 1;
    }
    assert_eq!(framed(chunks.into_iter()), expected, "framing depends on the chunking");
}

fuzz_target!(|data: &[u8]| {
    as_line(data);
    as_json(data);
    as_stream(data);
});

extern "C" {
    /// fuzz/c/field_mutator.c: sentences mutated field by field, their checksums made right again.
    fn nmea_fuzz_mutate(data: *mut u8, size: usize, max_size: usize, seed: u32) -> usize;
}

libfuzzer_sys::fuzz_mutator!(|data: &mut [u8], size: usize, max_size: usize, seed: u32| {
    unsafe { nmea_fuzz_mutate(data.as_mut_ptr(), size, max_size, seed) }
});
