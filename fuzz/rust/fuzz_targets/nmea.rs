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
//! - the stream framer (with binary frames) must cut the input into the same items as a
//!   byte-at-a-time model of the Python reference's Framer, whether it gets the input whole or in
//!   chunks of sizes derived from the input;
//! - AIS: a payload that decodes (a VDM/VDO line's of one sentence, one the assembler joins, or the
//!   input itself after a first byte that gives the fill bits) must encode back to its characters
//!   and fill bits when it fits a message's bits; the assembler fed the input's lines must account
//!   for every fragment exactly once.
//! Nothing may panic.
#![cfg_attr(feature = "libfuzzer", no_main)]
use nmeaspec::ais_messages::Message;
use nmeaspec::assembly::Assembler;
use nmeaspec::stream::{crc24q, Framer, Item, MAX_FRAME};
use nmeaspec::{ErrorKind, Options, ProblemKind};

const LENIENT: Options = Options { lenient: true, require_checksum: false, strict: false };
const REQUIRED: Options = Options { lenient: false, require_checksum: true, strict: false };

fn as_line(data: &[u8]) {
    assert_eq!(
        nmeaspec::parse(data),
        nmeaspec::paths::parse_general(data),
        "the fast path disagrees with the general path"
    );
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
        if nmeaspec::parse_with(data, Options::default()).is_ok() {
            return; // a line behind TAG blocks: parse() takes none, parse_with reads them
        }
        if let Ok(parsed) = nmeaspec::parse_with(data, LENIENT) {
            assert!(
                !parsed.problems.is_empty(),
                "lenient parsing kept a line strict parsing refused, without problems"
            );
            assert_eq!(parsed.to_string().as_bytes(), data, "lenient round trip changed the line");
            assert_serialized(|buf| parsed.serialize_into(buf), data);
            let _ = parsed.to_json(true);
            let json = parsed.to_json(false);
            assert_eq!(
                nmeaspec::json::encode_json(json.as_bytes()).as_bytes(),
                data,
                "JSON with problems changed the line"
            );
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
    // The sentence's checksum member is the last, or the one before its TAG blocks or stray `$`.
    let no_checksum = ["\"checksum\":null", "\"checksum\":\"\""].iter().any(|member| {
        json.ends_with(&format!("{member}}}"))
            || json.contains(&format!("{member},\"tag_blocks\":"))
            || json.contains(&format!("{member},\"stray\":"))
    });
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

/// What came out of framing: each line's bytes, or the length of an overlong one; a binary
/// frame's protocol and bytes, or a rejected one's protocol, reason and sync bytes.
#[derive(Debug, PartialEq, Eq)]
enum Owned {
    Line(Vec<u8>),
    TooLong(usize),
    Frame(&'static str, Vec<u8>),
    Bad(&'static str, &'static str, Vec<u8>),
}

impl From<Item<'_>> for Owned {
    fn from(item: Item<'_>) -> Self {
        match item {
            Item::Line(line) => Owned::Line(line.to_vec()),
            Item::TooLong(length) => Owned::TooLong(length),
            Item::Frame(protocol, frame) => Owned::Frame(protocol.name(), frame.to_vec()),
            Item::BadFrame(protocol, error, sync) => Owned::Bad(protocol.name(), error.kind(), sync.to_vec()),
        }
    }
}

/// What the framer makes of a first sync byte at the start of `data`: the item, and how many bytes
/// it takes (reading goes on after them); None when it starts no frame. The frame is read ahead
/// in the whole input; a rejected one gives up its sync bytes only.
fn model_frame(data: &[u8]) -> Option<(Owned, usize)> {
    // the frames of spec/binary, from the protocols' facts: name, first two bytes (the second
    // under a mask), sync bytes, header and trailer (checksum and end bytes) sizes; a third sync byte
    const MODELS: [(&str, u8, u8, u8, usize, usize, usize, u8); 7] = [
        ("ubx", 0xB5, 0x62, 0xFF, 2, 6, 2, 0),
        ("rtcm3", 0xD3, 0x00, 0xFC, 1, 3, 3, 0),
        ("skytraq", 0xA0, 0xA1, 0xFF, 2, 4, 3, 0),
        ("sirf", 0xA0, 0xA2, 0xFF, 2, 4, 4, 0),
        ("casic", 0xBA, 0xCE, 0xFF, 2, 6, 4, 0),
        ("sbf", b'$', b'@', 0xFF, 2, 8, 0, 0), // $@ CRC(LE) id(LE) length(LE: the whole block) body
        ("unicore", 0xAA, 0x44, 0xFF, 3, 24, 4, 0xB5), // AA 44 B5 cpu id(LE) length(LE) time... body CRC-32(LE)
    ];
    let second = *data.get(1)?;
    let &(name, _, _, _, sync, header, trailer, _) =
        MODELS.iter().find(|m| m.1 == data[0] && second & m.3 == m.2 && (m.4 < 3 || data.get(2) == Some(&m.7)))?;
    let bad = |kind| Some((Owned::Bad(name, kind, data[..sync].to_vec()), sync));
    if data.len() < header {
        return bad("cut");
    }
    if data[sync..header].iter().all(|&b| b == 0) {
        return bad("nul_header");
    }
    let payload = match name {
        "sbf" => (usize::from(data[6]) | usize::from(data[7]) << 8).wrapping_sub(header),
        "ubx" => usize::from(data[4]) | usize::from(data[5]) << 8,
        "unicore" => usize::from(data[6]) | usize::from(data[7]) << 8,
        "casic" => usize::from(data[2]) | usize::from(data[3]) << 8,
        "rtcm3" => usize::from(data[1] & 3) << 8 | usize::from(data[2]),
        // SkyTraq, SiRF (whose top bit, reserved and zero, makes the frame too long when set)
        _ => usize::from(data[2]) << 8 | usize::from(data[3]),
    };
    let size = header.wrapping_add(payload).wrapping_add(trailer);
    if size > MAX_FRAME {
        return bad("too_long");
    }
    if size < header + trailer {
        return bad("too_short"); // an SBF length under its header's
    }
    if size > data.len() {
        return bad("cut");
    }
    let body = &data[..size - trailer];
    let computed = match name {
        "ubx" => {
            let (mut a, mut b) = (0u8, 0u8);
            for &byte in &body[2..] {
                a = a.wrapping_add(byte);
                b = b.wrapping_add(a);
            }
            vec![a, b]
        }
        "skytraq" => vec![body[4..].iter().fold(0u8, |x, &b| x ^ b), 0x0D, 0x0A],
        "sirf" => {
            let sum = body[4..].iter().map(|&b| u32::from(b)).sum::<u32>() & 0x7FFF;
            vec![(sum >> 8) as u8, sum as u8, 0xB0, 0xB3]
        }
        "casic" => {
            let sum = body[2..].chunks(4).fold(0u32, |sum, word| {
                let mut le = [0u8; 4];
                le[..word.len()].copy_from_slice(word);
                sum.wrapping_add(u32::from_le_bytes(le))
            });
            sum.to_le_bytes().to_vec()
        }
        "sbf" => {
            let crc = body[4..].iter().fold(0u16, |crc, &byte| {
                (0..8).fold(crc ^ u16::from(byte) << 8, |c, _| if c & 0x8000 != 0 { c << 1 ^ 0x1021 } else { c << 1 })
            });
            crc.to_le_bytes().to_vec()
        }
        "unicore" => {
            let crc = body.iter().fold(0u32, |crc, &byte| {
                (0..8).fold(crc ^ u32::from(byte), |c, _| if c & 1 != 0 { c >> 1 ^ 0xEDB8_8320 } else { c >> 1 })
            });
            crc.to_le_bytes().to_vec()
        }
        _ => crc24q(body).to_be_bytes()[1..].to_vec(),
    };
    let sent = if name == "sbf" { &data[2..4] } else { &data[size - trailer..size] };
    if computed != sent {
        return bad("bad_checksum");
    }
    Some((Owned::Frame(name, data[..size].to_vec()), size))
}

/// The Python reference's Framer, one byte at a time.
fn model(data: &[u8]) -> Vec<Owned> {
    let max = nmeaspec::MAX_LINE;
    // where the line is as to TAG blocks: outside, in one, right after one
    #[derive(PartialEq)]
    enum Tag {
        Outside,
        In,
        After,
    }
    let (mut out, mut line, mut length, mut tag) = (Vec::new(), Vec::new(), 0usize, Tag::Outside);
    let finish = |out: &mut Vec<Owned>, line: &mut Vec<u8>, length: &mut usize| {
        if *length > 0 {
            out.push(if *length <= max { Owned::Line(line.clone()) } else { Owned::TooLong(*length) });
        }
        line.clear();
        *length = 0;
    };
    let mut at = 0;
    while at < data.len() {
        let b = data[at];
        at += 1;
        if matches!(b, 0xB5 | 0xD3 | 0xA0 | 0xBA | 0xAA | b'$') && tag == Tag::Outside {
            if let Some((item, taken)) = model_frame(&data[at - 1..]) {
                finish(&mut out, &mut line, &mut length);
                out.push(item);
                at += taken - 1;
                continue;
            }
        }
        if b == b'\r' || b == b'\n' {
            finish(&mut out, &mut line, &mut length);
            tag = Tag::Outside;
            continue;
        }
        if b == b'\\' && (length == 0 || tag != Tag::Outside) {
            tag = if tag == Tag::In { Tag::After } else { Tag::In }; // opens a block, or closes it
        } else if (b == b'$' || b == b'!') && tag == Tag::Outside {
            finish(&mut out, &mut line, &mut length);
        } else if tag == Tag::After {
            tag = Tag::Outside;
        }
        length += 1;
        if length <= max {
            line.push(b);
        }
    }
    finish(&mut out, &mut line, &mut length);
    out
}

fn framed<'c>(chunks: impl Iterator<Item = &'c [u8]>) -> Vec<Owned> {
    let mut framer = Framer::with_binary_frames();
    let mut out = Vec::new();
    for chunk in chunks {
        framer.feed(chunk, |item| out.push(item.into()));
    }
    framer.finish(|item| out.push(item.into()));
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

/// A payload that decodes must encode back to it, when it fits a message's bits.
fn ais_round_trip(payload: &str, fill_bits: u8) {
    let Ok(message) = Message::decode(payload.as_bytes(), fill_bits) else {
        return;
    };
    let mut json = String::new();
    message.write_json(&mut json, fill_bits).expect("an AIS message's JSON");
    match message.encode() {
        Ok(armored) => assert_eq!((armored.as_str(), armored.fill_bits()), (payload, fill_bits), "AIS round trip"),
        Err(err) => assert!(payload.len() * 6 > nmeaspec::ais::MAX_BITS, "a payload that fits did not encode: {err}"),
    }
}

fn as_ais(data: &[u8]) {
    if let Some((&first, payload)) = data.split_first() {
        if let Ok(payload) = core::str::from_utf8(payload) {
            ais_round_trip(payload, first % 8);
        }
    }
    let mut assembler: Assembler = Assembler::new(1 + u32::from(data.last().copied().unwrap_or(0) % 8));
    let (mut fed, mut reported) = (0usize, 0usize);
    let mut done = |d: nmeaspec::assembly::Assembled<'_>| {
        assert!((1..=9).contains(&d.lines.len()) && d.lines.len() == d.numbers.len(), "an assembled message's lines");
        reported += d.lines.len();
        match d.joined {
            Some((payload, fill_bits)) => ais_round_trip(payload, fill_bits),
            None => drop(d.incomplete_message().to_string()),
        }
    };
    for line in data.split(|&b| b == b'\n') {
        let Ok(parsed) = nmeaspec::parse_with(line, Options::default()) else {
            assembler.feed(None, nmeaspec::TagBlocks::default(), &mut done);
            continue;
        };
        let fragment = parsed.sentence.fragment();
        fed += usize::from(fragment.is_some());
        assembler.feed(fragment, parsed.tag_blocks, &mut done);
    }
    assembler.finish(&mut done);
    assert_eq!(fed, reported, "the assembler lost or repeated a fragment");
}

fn check(data: &[u8]) {
    as_line(data);
    as_json(data);
    as_stream(data);
    as_ais(data);
}

#[cfg(feature = "libfuzzer")]
libfuzzer_sys::fuzz_target!(|data: &[u8]| check(data));

#[cfg(not(feature = "libfuzzer"))]
fn main() -> std::process::ExitCode {
    nmeaspec_fuzz::replay_files(check)
}

#[cfg(feature = "libfuzzer")]
extern "C" {
    /// fuzz/c/field_mutator.c: sentences mutated field by field, their checksums made right again.
    fn nmea_fuzz_mutate(data: *mut u8, size: usize, max_size: usize, seed: u32) -> usize;
}

#[cfg(feature = "libfuzzer")]
libfuzzer_sys::fuzz_mutator!(|data: &mut [u8], size: usize, max_size: usize, seed: u32| {
    unsafe { nmea_fuzz_mutate(data.as_mut_ptr(), size, max_size, seed) }
});
