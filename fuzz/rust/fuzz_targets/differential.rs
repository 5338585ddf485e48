//! The in-process differential: the generated C pair (built by build.rs) and the Rust crate are
//! given the same input, and every answer must be byte-identical:
//! - decode's JSON of the input as a line (the lossless and the values form; strict, lenient,
//!   requiring a checksum, both): accept or reject, the error kind and message, every field;
//! - encode's output for the input as a line of JSON: the re-serialized sentence or the error,
//!   and whether the line is a failure line that encode skips;
//! - the stream framer's items for the input fed whole and in chunks of sizes taken from it;
//! - AIS: the input after its first byte (which gives the fill bits) as a payload, when it is
//!   printable ASCII as in a sentence: its message's JSON or its error's, and what the message encodes back to; the assemblers' events for the
//!   input's lines (the lines and joined payload of each message, or why it was given up).
//! Python stays in the replay differential (fuzz/differential.py).
#![cfg_attr(feature = "libfuzzer", no_main)]
use nmeaspec::ais_messages::Message;
use nmeaspec::assembly::{Assembled, Assembler};
use nmeaspec::json::{Value, SKIP_CHECK_DEPTH};
use nmeaspec::stream::{FrameError, Framer, Item};
use nmeaspec::{Options, TagBlocks};
use std::fmt::Write;

extern "C" {
    fn shim_decode(
        line: *const u8,
        len: usize,
        values: i32,
        lenient: i32,
        required: i32,
        out: *mut u8,
        cap: usize,
    ) -> usize;
    fn shim_encode(json: *const u8, len: usize, out: *mut u8, cap: usize) -> usize;
    fn shim_frame(data: *const u8, len: usize, chunk: usize, out: *mut u8, cap: usize) -> usize;
    fn shim_ais(payload: *const u8, len: usize, fill_bits: u32, out: *mut u8, cap: usize) -> usize;
    fn shim_assemble(data: *const u8, len: usize, lifetime: u32, out: *mut u8, cap: usize) -> usize;
}

#[cfg(feature = "libfuzzer")]
extern "C" {
    fn nmea_fuzz_mutate(data: *mut u8, size: usize, max_size: usize, seed: u32) -> usize;
}

const INPUT_MAX: usize = 4096;
const OUT: usize = 64 * 1024;

fn c_text(f: impl FnOnce(*mut u8, usize) -> usize) -> Option<Vec<u8>> {
    let mut out = vec![0u8; OUT];
    let n = f(out.as_mut_ptr(), OUT);
    if n == usize::MAX {
        return None;
    }
    out.truncate(n);
    Some(out)
}

/// A tool's output line as the bytes it writes: each character is one byte (Latin-1).
fn latin1(text: &str) -> Vec<u8> {
    text.chars().map(|ch| ch as u32 as u8).collect()
}

fn decode(data: &[u8]) {
    for values in [false, true] {
        for (lenient, required) in [(false, false), (true, false), (false, true), (true, true)] {
            let c = c_text(|out, cap| unsafe {
                shim_decode(data.as_ptr(), data.len(), values.into(), lenient.into(), required.into(), out, cap)
            })
            .unwrap();
            let rust = nmeaspec::json::decode_json_with(
                data,
                values,
                Options { lenient, require_checksum: required, strict: false },
            );
            assert!(
                c == latin1(&rust),
                "decode (values {values}, lenient {lenient}, require_checksum {required}):\n   C: {}\nRust: {rust}",
                String::from_utf8_lossy(&c)
            );
        }
    }
}

fn encode(data: &[u8]) {
    if data.len() > INPUT_MAX || data.contains(&b'\n') {
        return; // the tools read JSON a line at a time
    }
    let c = c_text(|out, cap| unsafe { shim_encode(data.as_ptr(), data.len(), out, cap) });
    // What nmea-rs encode does with the line (runtime/rust/crate/bin/nmea-rs.rs).
    let value = Value::parse_nested(data, SKIP_CHECK_DEPTH).map(|(value, _)| value);
    let skipped = value.as_ref().and_then(|v| v.get("ok")) == Some(&Value::Bool(false));
    assert_eq!(c.is_none(), skipped, "encode: C skips the line: {}, Rust: {skipped}", c.is_none());
    if let Some(c) = c {
        let mut rust = String::new();
        nmeaspec::json::write_encoded(&mut rust, value.as_ref()).unwrap();
        let rust = latin1(&rust);
        assert!(
            c == rust,
            "encode:\n   C: {:?}\nRust: {:?}",
            String::from_utf8_lossy(&c),
            String::from_utf8_lossy(&rust)
        );
    }
}

fn frame(data: &[u8], chunk: usize) {
    let c = c_text(|out, cap| unsafe { shim_frame(data.as_ptr(), data.len(), chunk, out, cap) }).unwrap();
    let mut rust = Vec::new();
    let mut put = |item: Item<'_>| match item {
        Item::Line(line) => {
            let mut head = String::new();
            let _ = write!(head, "L{}:", line.len());
            rust.extend_from_slice(head.as_bytes());
            rust.extend_from_slice(line);
        }
        Item::TooLong(len) => rust.extend_from_slice(format!("T{len};").as_bytes()),
        // c_shim.c's numbers: nmea_protocol and nmea_frame_error
        Item::Frame(protocol, frame) => {
            rust.extend_from_slice(format!("F{}:{}:", protocol as u8 + 1, frame.len()).as_bytes());
            rust.extend_from_slice(frame);
        }
        Item::BadFrame(protocol, error, sync) => {
            let error = match error {
                FrameError::BadChecksum { .. } => 1,
                FrameError::TooLong(_) => 2,
                FrameError::NulHeader => 3,
                FrameError::Cut => 4,
                FrameError::TooShort(_) => 5,
            };
            rust.extend_from_slice(format!("B{}.{error}:{}:", protocol as u8 + 1, sync.len()).as_bytes());
            rust.extend_from_slice(sync);
        }
    };
    let mut framer = Framer::with_binary_frames();
    for piece in data.chunks(chunk.max(1)) {
        framer.feed(piece, &mut put);
    }
    framer.finish(&mut put);
    assert!(
        c == rust,
        "framing in chunks of {chunk}:\n   C: {:?}\nRust: {:?}",
        String::from_utf8_lossy(&c),
        String::from_utf8_lossy(&rust)
    );
}

fn ais(data: &[u8]) {
    let Some((&first, payload)) = data.split_first() else { return };
    if !payload.iter().all(|b| (0x20..=0x7e).contains(b)) {
        return; // a payload as a sentence carries it: printable ASCII
    }
    let fill_bits = first % 8;
    let c =
        c_text(|out, cap| unsafe { shim_ais(payload.as_ptr(), payload.len(), fill_bits.into(), out, cap) }).unwrap();
    let mut rust = String::new();
    match Message::decode(payload, fill_bits) {
        Ok(message) => {
            message.write_json(&mut rust, fill_bits).unwrap();
            match message.encode() {
                Ok(armored) => write!(rust, "|{},{}", armored.as_str(), armored.fill_bits()).unwrap(),
                Err(err) => write!(rust, "|{}", err.kind.as_str()).unwrap(),
            }
        }
        Err(err) => err.write_json(&mut rust).unwrap(),
    }
    assert!(c == latin1(&rust), "AIS payload:\n   C: {}\nRust: {rust}", String::from_utf8_lossy(&c));
}

fn assemble(data: &[u8]) {
    let lifetime = 1 + u32::from(data.last().copied().unwrap_or(0) % 8);
    let c = c_text(|out, cap| unsafe { shim_assemble(data.as_ptr(), data.len(), lifetime, out, cap) }).unwrap();
    let mut rust = String::new();
    let mut put = |done: Assembled<'_>| {
        let lines: Vec<String> = done.lines.iter().map(u32::to_string).collect();
        match done.joined {
            Some((payload, fill_bits)) => write!(rust, "{}:P{payload},{fill_bits};", lines.join(",")),
            None => write!(rust, "{}:I{};", lines.join(","), done.incomplete_message()),
        }
        .unwrap();
    };
    let mut assembler: Assembler = Assembler::new(lifetime);
    for line in data.split(|&b| b == b'\n') {
        match nmeaspec::parse_with(line, Options::default()) {
            Ok(parsed) => assembler.feed(parsed.sentence.fragment(), parsed.tag_blocks, &mut put),
            Err(_) => assembler.feed(None, TagBlocks::default(), &mut put),
        }
    }
    assembler.finish(&mut put);
    assert!(c == latin1(&rust), "AIS assembly:\n   C: {}\nRust: {rust}", String::from_utf8_lossy(&c));
}

fn check(data: &[u8]) {
    decode(data);
    encode(data);
    ais(data);
    assemble(data);
    frame(data, data.len().max(1));
    frame(data, 1 + data.first().copied().unwrap_or(0) as usize % 7);
}

#[cfg(feature = "libfuzzer")]
libfuzzer_sys::fuzz_target!(|data: &[u8]| check(data));

#[cfg(not(feature = "libfuzzer"))]
fn main() -> std::process::ExitCode {
    nmeaspec_fuzz::replay_files(check)
}

#[cfg(feature = "libfuzzer")]
libfuzzer_sys::fuzz_mutator!(|data: &mut [u8], size: usize, max_size: usize, seed: u32| {
    unsafe { nmea_fuzz_mutate(data.as_mut_ptr(), size, max_size, seed) }
});
