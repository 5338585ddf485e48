//! The Rust benchmark driver: reads the corpus into memory once, then times one operation of one
//! implementation over every line and prints a JSON object.
//!
//! ```text
//! bench-rs ours|nmea|nmea0183|ours-ais|nmea-parser|ours-ubx|ublox parse|serialize|roundtrip|fixes|none CORPUS [--by-type]
//! ```
//!
//! `ours` is `nmeaspec`: parse is `nmeaspec::parse`; serialize is `serialize_into` of each parsed
//! sentence (its text, what `Display` writes), the sentences being parsed chunk by chunk outside
//! the timed region and written one after another into one buffer, as a program writing a stream
//! would; `to_bytes` (text, read-back check, CR LF) is timed the same way and reported beside it;
//! roundtrip parses and writes each line and compares it with the input; fixes parses each line and
//! feeds it to a `FixAssembler` (ok: the lines parsed). `ours-ais` (over the AIS corpus) parses
//! each line and, when it is a whole message, decodes its AIS message, every field
//! (`ais_messages::Message::decode`; ok: messages decoded); its peer is `nmea-parser`'s
//! `NmeaParser::parse_sentence`, which decodes the message of a VDM/VDO line into a struct.
//! `ours-ubx` (over the UBX corpus, a frame in hex per line, turned into bytes before timing)
//! checks and decodes each frame (`ubx_messages::Message::from_frame`, then every entry of its
//! groups read: `Message::for_each_entry`; ok: frames of a class and id the spec describes). A
//! counting global allocator reports the allocations made inside every timed loop. The peers only
//! parse: `nmea::parse_str` per line, and one `nmea0183::Parser` fed every line with its CR LF
//! (built with the `peers` feature).

use std::alloc::{GlobalAlloc, Layout, System};
use std::hint::black_box;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::Instant;

/// The system allocator, counting every allocation.
struct CountingAllocator;

static ALLOCATIONS: AtomicUsize = AtomicUsize::new(0);

unsafe impl GlobalAlloc for CountingAllocator {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        ALLOCATIONS.fetch_add(1, Ordering::Relaxed);
        System.alloc(layout)
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        System.dealloc(ptr, layout)
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        ALLOCATIONS.fetch_add(1, Ordering::Relaxed);
        System.realloc(ptr, layout, new_size)
    }
}

#[global_allocator]
static GLOBAL: CountingAllocator = CountingAllocator;

fn allocations() -> usize {
    ALLOCATIONS.load(Ordering::Relaxed)
}

/// Lines are parsed this many at a time before their serialization is timed.
const CHUNK: usize = 2048;
/// Room for the longest line a parser accepts and its CR LF.
const LINE_CAPACITY: usize = nmeaspec::BUILD_CAPACITY;

#[derive(Default)]
struct Timing {
    seconds: f64,
    ok: usize,
    allocations: usize,
}

/// One corpus line: its text without, and with, its CR LF.
#[derive(Clone, Copy)]
struct Line<'a> {
    text: &'a str,
    raw: &'a [u8],
}

/// Times `work` (which returns its ok count), counting the allocations made meanwhile.
fn timed(work: impl FnOnce() -> usize) -> Timing {
    let before = allocations();
    let start = Instant::now();
    let ok = work();
    Timing {
        seconds: start.elapsed().as_secs_f64(),
        ok,
        allocations: allocations() - before,
    }
}

fn time_ours_parse(lines: &[Line<'_>]) -> Timing {
    timed(|| {
        let mut ok = 0;
        for line in lines {
            // Looked at in place, as C's caller reads the struct nmea_parse filled: not moved out.
            if let Ok(sentence) = &nmeaspec::parse(line.text) {
                black_box(sentence);
                ok += 1;
            }
        }
        ok
    })
}

/// Times `write` over the sentences of each chunk, parsed beforehand, written one after another
/// into one buffer; counts the lines written back byte for byte (`with_line_ending`: the output
/// ends with CR LF).
fn time_ours_serialize(
    lines: &[Line<'_>],
    with_line_ending: bool,
    write: impl Fn(&nmeaspec::Sentence<'_>, &mut [u8]) -> Option<usize>,
) -> Timing {
    let mut out = vec![0u8; CHUNK * LINE_CAPACITY];
    let mut ends = Vec::with_capacity(CHUNK);
    let mut parsed = Vec::with_capacity(CHUNK);
    let mut timing = Timing::default();
    for chunk in lines.chunks(CHUNK) {
        parsed.clear();
        ends.clear();
        parsed.extend(
            chunk
                .iter()
                .filter_map(|line| nmeaspec::parse(line.text).ok().map(|s| (s, line))),
        );
        let before = allocations();
        let start = Instant::now();
        let mut used = 0;
        for (sentence, _) in &parsed {
            used += write(sentence, &mut out[used..]).unwrap_or(0);
            ends.push(used);
        }
        timing.seconds += start.elapsed().as_secs_f64();
        timing.allocations += allocations() - before;
        let mut begin = 0;
        for ((_, line), &end) in parsed.iter().zip(&ends) {
            let expected = if with_line_ending {
                line.raw
            } else {
                line.text.as_bytes()
            };
            timing.ok += usize::from(&out[begin..end] == expected);
            begin = end;
        }
    }
    timing
}

fn time_ours_roundtrip(lines: &[Line<'_>]) -> Timing {
    let mut buf = [0u8; LINE_CAPACITY];
    timed(|| {
        let mut ok = 0;
        for line in lines {
            if let Ok(sentence) = nmeaspec::parse(line.text) {
                let written = sentence.serialize_into(&mut buf);
                ok += usize::from(written.is_some_and(|n| &buf[..n] == line.text.as_bytes()));
            }
        }
        ok
    })
}

#[cfg(feature = "peers")]
fn time_nmea_parse(lines: &[Line<'_>]) -> Timing {
    timed(|| {
        lines
            .iter()
            .filter(|line| nmea::parse_str(line.text).map(black_box).is_ok())
            .count()
    })
}

#[cfg(feature = "peers")]
fn time_nmea0183_parse(lines: &[Line<'_>]) -> Timing {
    let mut parser = nmea0183::Parser::new();
    timed(|| {
        let mut ok = 0;
        for line in lines {
            for result in parser.parse_from_bytes(line.raw).flatten() {
                black_box(&result);
                ok += 1;
            }
        }
        ok
    })
}

fn time_ours_fixes(lines: &[Line<'_>]) -> Timing {
    let mut assembler = nmeaspec::FixAssembler::new();
    timed(|| {
        let mut ok = 0;
        for line in lines {
            if let Ok(sentence) = &nmeaspec::parse(line.text) {
                black_box(assembler.feed(sentence));
                ok += 1;
            }
        }
        black_box(assembler.finish());
        ok
    })
}

fn time_ours_ais_parse(lines: &[Line<'_>]) -> Timing {
    timed(|| {
        let mut ok = 0;
        for line in lines {
            let Ok(sentence) = &nmeaspec::parse(line.text) else {
                continue;
            };
            let Some(fragment) = sentence.fragment().filter(|f| f.count == 1) else {
                continue;
            };
            if let Ok(message) = &nmeaspec::ais_messages::Message::decode(
                fragment.payload.as_bytes(),
                fragment.fill_bits,
            ) {
                black_box(message);
                ok += 1;
            }
        }
        ok
    })
}

/// The UBX corpus's frames (one per line, in hex), as bytes: turned back before anything is timed.
fn ubx_frames(lines: &[Line<'_>]) -> Vec<Vec<u8>> {
    lines
        .iter()
        .map(|line| {
            (0..line.text.len() / 2)
                .map(|i| u8::from_str_radix(&line.text[2 * i..2 * i + 2], 16).expect("hex"))
                .collect()
        })
        .collect()
}

/// Each frame checked (sync, length, checksum) and decoded into the struct of its layout
/// (`ubx_messages::Message::from_frame`: every field read, a group's entries as a view), then every
/// entry of its groups read (`Message::for_each_entry`), as the C pair reads them into its struct;
/// ok: messages of a layout the spec describes.
fn time_ours_ubx_parse(frames: &[Vec<u8>]) -> Timing {
    timed(|| {
        let mut ok = 0;
        for frame in frames {
            if let Ok(message) = &nmeaspec::ubx_messages::Message::from_frame(frame) {
                if !matches!(message, nmeaspec::ubx_messages::Message::Unknown(_)) {
                    ok += 1;
                }
                message.for_each_entry(|entry| {
                    black_box(entry);
                });
                black_box(message);
            }
        }
        ok
    })
}

/// The ublox crate's peer of `ours-ubx`: one `ublox::Parser` (protocol 23, a fixed 2 KiB buffer:
/// no allocation) fed each frame with `consume_ubx`, every packet it yields read whole: its
/// `Serialize` implementation (the crate's `serde` feature) calls the getter of every field, the
/// repeated groups' entries included, and hands each value to `Sink`, which only `black_box`es it.
/// A getter that panics (ublox 0.10.0's CFG-PRT `mode` of a port that is no UART, whose data bits
/// read 5: `unimplemented!`) is caught, its packet not counted. ok: packets of a message the crate
/// knows (not `Unknown`) read whole.
#[cfg(feature = "peers")]
fn time_ublox_parse(frames: &[Vec<u8>]) -> Timing {
    use serde::Serialize;
    use std::panic::{catch_unwind, AssertUnwindSafe};
    use ublox::{proto23::PacketRef, ParserBuilder, UbxPacket};
    let mut parser = ParserBuilder::new()
        .with_protocol::<ublox::proto23::Proto23>()
        .with_fixed_buffer::<2048>();
    std::panic::set_hook(Box::new(|_| {})); // a caught panic prints nothing
    timed(|| {
        let mut ok = 0;
        for frame in frames {
            let mut packets = parser.consume_ubx(frame);
            while let Some(result) = packets.next() {
                if let Ok(UbxPacket::Proto23(packet)) = result {
                    let read = catch_unwind(AssertUnwindSafe(|| {
                        black_box(&packet).serialize(sink::Sink).is_ok()
                    }));
                    if matches!(read, Ok(true)) && !matches!(packet, PacketRef::Unknown(_)) {
                        ok += 1;
                    }
                }
            }
        }
        ok
    })
}

/// A serde serializer that reads every value it is given (`black_box`) and writes nothing: what
/// touches every field of a ublox packet without the cost of a text format.
#[cfg(feature = "peers")]
mod sink {
    use serde::ser::{self, Serialize};
    use std::hint::black_box;

    pub struct Sink;

    #[derive(Debug)]
    pub struct Never;

    impl std::fmt::Display for Never {
        fn fmt(&self, _: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
            Ok(())
        }
    }

    impl std::error::Error for Never {}

    impl ser::Error for Never {
        fn custom<T: std::fmt::Display>(_: T) -> Self {
            Never
        }
    }

    macro_rules! read {
        ($($name:ident: $type:ty),* $(,)?) => {
            $(fn $name(self, value: $type) -> Result<(), Never> {
                black_box(value);
                Ok(())
            })*
        };
    }

    impl ser::Serializer for Sink {
        type Ok = ();
        type Error = Never;
        type SerializeSeq = Sink;
        type SerializeTuple = Sink;
        type SerializeTupleStruct = Sink;
        type SerializeTupleVariant = Sink;
        type SerializeMap = Sink;
        type SerializeStruct = Sink;
        type SerializeStructVariant = Sink;

        read!(serialize_bool: bool, serialize_i8: i8, serialize_i16: i16, serialize_i32: i32,
              serialize_i64: i64, serialize_u8: u8, serialize_u16: u16, serialize_u32: u32,
              serialize_u64: u64, serialize_f32: f32, serialize_f64: f64, serialize_char: char,
              serialize_str: &str, serialize_bytes: &[u8], serialize_unit_struct: &'static str);

        fn serialize_none(self) -> Result<(), Never> {
            Ok(())
        }
        fn serialize_some<T: ?Sized + Serialize>(self, value: &T) -> Result<(), Never> {
            value.serialize(self)
        }
        fn serialize_unit(self) -> Result<(), Never> {
            Ok(())
        }
        fn serialize_unit_variant(
            self,
            _: &'static str,
            index: u32,
            _: &'static str,
        ) -> Result<(), Never> {
            black_box(index);
            Ok(())
        }
        fn serialize_newtype_struct<T: ?Sized + Serialize>(
            self,
            _: &'static str,
            value: &T,
        ) -> Result<(), Never> {
            value.serialize(self)
        }
        fn serialize_newtype_variant<T: ?Sized + Serialize>(
            self,
            _: &'static str,
            index: u32,
            _: &'static str,
            value: &T,
        ) -> Result<(), Never> {
            black_box(index);
            value.serialize(self)
        }
        fn serialize_seq(self, _: Option<usize>) -> Result<Sink, Never> {
            Ok(Sink)
        }
        fn serialize_tuple(self, _: usize) -> Result<Sink, Never> {
            Ok(Sink)
        }
        fn serialize_tuple_struct(self, _: &'static str, _: usize) -> Result<Sink, Never> {
            Ok(Sink)
        }
        fn serialize_tuple_variant(
            self,
            _: &'static str,
            _: u32,
            _: &'static str,
            _: usize,
        ) -> Result<Sink, Never> {
            Ok(Sink)
        }
        fn serialize_map(self, _: Option<usize>) -> Result<Sink, Never> {
            Ok(Sink)
        }
        fn serialize_struct(self, _: &'static str, _: usize) -> Result<Sink, Never> {
            Ok(Sink)
        }
        fn serialize_struct_variant(
            self,
            _: &'static str,
            _: u32,
            _: &'static str,
            _: usize,
        ) -> Result<Sink, Never> {
            Ok(Sink)
        }
    }

    /// Every compound: each element or field value read in turn.
    macro_rules! compound {
        ($($trait:ident :: $method:ident $(($key:ty))?),* $(,)?) => {
            $(impl ser::$trait for Sink {
                type Ok = ();
                type Error = Never;
                fn $method<T: ?Sized + Serialize>(&mut self, $(_: $key,)? value: &T) -> Result<(), Never> {
                    value.serialize(Sink)
                }
                fn end(self) -> Result<(), Never> {
                    Ok(())
                }
            })*
        };
    }

    compound!(
        SerializeSeq::serialize_element,
        SerializeTuple::serialize_element,
        SerializeTupleStruct::serialize_field,
        SerializeTupleVariant::serialize_field,
        SerializeStruct::serialize_field(&'static str),
        SerializeStructVariant::serialize_field(&'static str)
    );

    impl ser::SerializeMap for Sink {
        type Ok = ();
        type Error = Never;
        /// The keys are the fields' names, constants: not read.
        fn serialize_key<T: ?Sized + Serialize>(&mut self, _: &T) -> Result<(), Never> {
            Ok(())
        }
        fn serialize_value<T: ?Sized + Serialize>(&mut self, value: &T) -> Result<(), Never> {
            value.serialize(Sink)
        }
        fn end(self) -> Result<(), Never> {
            Ok(())
        }
    }
}

#[cfg(feature = "peers")]
fn time_nmea_parser_parse(lines: &[Line<'_>]) -> Timing {
    let mut parser = nmea_parser::NmeaParser::new();
    timed(|| {
        let mut ok = 0;
        for line in lines {
            match parser.parse_sentence(line.text) {
                Ok(nmea_parser::ParsedMessage::Incomplete) | Err(_) => {}
                Ok(message) => {
                    black_box(&message);
                    ok += 1;
                }
            }
        }
        ok
    })
}
fn run(implementation: &str, op: &str, lines: &[Line<'_>]) -> Timing {
    match (implementation, op) {
        // Reading the corpus only: the baseline bench/run.py subtracts from instruction counts.
        (_, "none") => Timing::default(),
        ("ours", "parse") => time_ours_parse(lines),
        ("ours", "serialize") => {
            time_ours_serialize(lines, false, |sentence, buf| sentence.serialize_into(buf))
        }
        ("ours", "to_bytes") => time_ours_serialize(lines, true, |sentence, buf| {
            sentence.to_bytes(buf).ok().map(<[u8]>::len)
        }),
        ("ours", "roundtrip") => time_ours_roundtrip(lines),
        ("ours", "fixes") => time_ours_fixes(lines),
        ("ours-ais", "parse") => time_ours_ais_parse(lines),
        ("ours-ubx", "parse") => time_ours_ubx_parse(&ubx_frames(lines)),
        #[cfg(feature = "peers")]
        ("ublox", "parse") => time_ublox_parse(&ubx_frames(lines)),
        #[cfg(feature = "peers")]
        ("nmea-parser", "parse") => time_nmea_parser_parse(lines),
        #[cfg(feature = "peers")]
        ("nmea", "parse") => time_nmea_parse(lines),
        #[cfg(feature = "peers")]
        ("nmea0183", "parse") => time_nmea0183_parse(lines),
        _ => {
            eprintln!("unknown implementation/operation {implementation} {op}");
            std::process::exit(2);
        }
    }
}

fn split_lines(corpus: &str) -> Vec<Line<'_>> {
    corpus
        .split_inclusive('\n')
        .map(|raw| Line {
            text: raw.trim_end_matches(['\r', '\n']),
            raw: raw.as_bytes(),
        })
        .collect()
}

fn ns_per_line(timing: &Timing, lines: usize) -> f64 {
    timing.seconds * 1e9 / lines.max(1) as f64
}

/// Times `op` over the lines of each sentence type, each group copied into a text of its own.
fn by_type(implementation: &str, op: &str, lines: &[Line<'_>]) -> String {
    let mut types: Vec<&str> = Vec::new();
    for line in lines {
        let kind = line.text.get(3..6).unwrap_or("");
        if !types.contains(&kind) {
            types.push(kind);
        }
    }
    let mut entries = Vec::new();
    for kind in types {
        let text: String = lines
            .iter()
            .filter(|l| l.text.get(3..6).unwrap_or("") == kind)
            .map(|l| std::str::from_utf8(l.raw).unwrap())
            .collect();
        let group = split_lines(&text);
        let timing = run(implementation, op, &group);
        entries.push(format!(
            "\"{kind}\": {{\"ns_per_line\": {:.2}, \"ok_lines\": {}, \"lines\": {}}}",
            ns_per_line(&timing, group.len()),
            timing.ok,
            group.len()
        ));
    }
    entries.join(", ")
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    if args.len() < 4 {
        eprintln!(
            "usage: bench-rs ours|nmea|nmea0183|ours-ais|nmea-parser|ours-ubx|ublox parse|serialize|roundtrip|fixes|none CORPUS [--by-type]"
        );
        std::process::exit(2);
    }
    let (implementation, op) = (args[1].as_str(), args[2].as_str());
    let corpus = std::fs::read_to_string(&args[3]).expect("read the corpus");
    let lines = split_lines(&corpus);
    run(implementation, op, &lines[..lines.len().min(10_000)]); // warm the caches and branch predictors
    let timing = run(implementation, op, &lines);
    let mut json = format!(
        "{{\"impl\": \"{implementation}\", \"op\": \"{op}\", \"lines\": {}, \"bytes\": {}, \"ns_per_line\": {:.2}, \"ok_lines\": {}, \"allocations\": {}",
        lines.len(),
        corpus.len(),
        ns_per_line(&timing, lines.len()),
        timing.ok,
        timing.allocations
    );
    if implementation == "ours" && op == "serialize" {
        let checked = run(implementation, "to_bytes", &lines);
        json += &format!(
            ", \"to_bytes_ns_per_line\": {:.2}, \"to_bytes_ok_lines\": {}",
            ns_per_line(&checked, lines.len()),
            checked.ok
        );
    }
    if args.get(4).map(String::as_str) == Some("--by-type") {
        json += &format!(", \"by_type\": {{{}}}", by_type(implementation, op, &lines));
    }
    println!("{json}}}");
}
