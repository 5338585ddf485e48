//! The `nmea-rs` tool: `decode` NMEA lines to JSON, `encode` that JSON back to sentences,
//! `stream` a byte stream that may hold garbage, cut lines or sentences run together, `fixes`
//! the fixes of NMEA lines (one JSON object per epoch, docs/fixes.md).
//!
//! Same behaviour, byte for byte, as nmea-c and nmea-py; see docs/json.md. Input is bytes, split
//! on LF with one CR before it dropped; a line over the limit is reported without being kept.
//! decode and stream end a line's object with the AIS message it carries (decode: a message of
//! one sentence; stream: also one joined across sentences, and an `incomplete_message` line after
//! the line that gave a message up).

use std::fmt::{self, Write as _};
use std::io::{self, BufRead, BufReader, BufWriter, Read, Write};
use std::process::ExitCode;

use nmeaspec::ais_messages::Message;
use nmeaspec::assembly::Assembler;
use nmeaspec::json::{write_encoded, Value, SKIP_CHECK_DEPTH};
use nmeaspec::stream::{FrameError, Framer, Item, Protocol, MAX_FRAME};
use nmeaspec::{parse_with, Error, Fix, FixAssembler, Options, MAX_LINE};

const USAGE: &str =
    "usage: nmea-rs decode|stream [--values] [--lenient] [--require-checksum] [--strict] [--ubx] [--rtcm3] | encode | fixes | --version\n       \
     (reads stdin, writes stdout)\n";
const BUFFER: usize = 1 << 16;

/// Writes output lines: each is formatted into a reused buffer, then written as Latin-1 bytes (as
/// the Python tool does) with its LF.
struct Output<W: Write> {
    inner: W,
    line: String,
}

impl<W: Write> Output<W> {
    fn new(inner: W) -> Self {
        Self { inner, line: String::with_capacity(4096) }
    }

    fn line(&mut self, write: impl FnOnce(&mut String) -> fmt::Result) -> io::Result<()> {
        self.line.clear();
        write(&mut self.line).map_err(|_| io::Error::other("formatting failed"))?;
        self.line.push('\n');
        if self.line.is_ascii() {
            self.inner.write_all(self.line.as_bytes())
        } else {
            let bytes: Vec<u8> = self.line.chars().map(|c| c as u32 as u8).collect();
            self.inner.write_all(&bytes)
        }
    }
}

/// Splits the input into lines and hands each to `handle`: its bytes when it has at most `keep`
/// bytes (after dropping the CR), else `Err(length)`; a longer line is counted but not kept.
fn for_each_line(
    input: &mut impl BufRead,
    keep: usize,
    mut handle: impl FnMut(Result<&[u8], usize>) -> io::Result<()>,
) -> io::Result<()> {
    // `kept` holds the first bytes of a line that spans buffer refills; `length` counts them all.
    let mut kept: Vec<u8> = Vec::with_capacity(keep + 1);
    let mut length = 0usize;
    let mut last = 0u8;
    let mut emit = |kept: &[u8], length: usize, last: u8| {
        let length = if last == b'\r' { length - 1 } else { length };
        handle(if length > keep { Err(length) } else { Ok(&kept[..length]) })
    };
    loop {
        let buf = input.fill_buf()?;
        if buf.is_empty() {
            break;
        }
        let newline = buf.iter().position(|&b| b == b'\n');
        let chunk = &buf[..newline.unwrap_or(buf.len())];
        if newline.is_some() && length == 0 {
            // The whole line is in the buffer: no copy.
            emit(chunk, chunk.len(), chunk.last().copied().unwrap_or(0))?;
        } else {
            let room = (keep + 1).saturating_sub(kept.len());
            kept.extend_from_slice(&chunk[..chunk.len().min(room)]);
            length += chunk.len();
            last = chunk.last().copied().unwrap_or(last);
            if newline.is_some() {
                emit(&kept, length, last)?;
                kept.clear();
                length = 0;
            }
        }
        let used = chunk.len() + usize::from(newline.is_some());
        input.consume(used);
    }
    if length > 0 {
        emit(&kept, length, last)?;
    }
    Ok(())
}

/// Adds the AIS message of a payload to a line's JSON object as its last member: `"ais"`, or
/// `"ais_error"`, why no message decodes from it.
fn add_message(json: &mut String, payload: &str, fill_bits: u8) -> fmt::Result {
    json.pop(); // its closing brace
    match Message::decode(payload.as_bytes(), fill_bits) {
        Ok(message) => {
            json.push_str(",\"ais\":");
            message.write_json(json, fill_bits)?;
        }
        Err(err) => {
            json.push_str(",\"ais_error\":");
            err.write_json(json)?;
        }
    }
    json.push('}');
    Ok(())
}

/// Writes a line's JSON with the AIS message it carries (decode: `assembler` is `None`) or
/// completes (stream); the errors of the messages it gives up go to `given_up`, a line each.
fn write_line(
    w: &mut String,
    line: &[u8],
    values: bool,
    options: Options,
    assembler: Option<&mut Assembler>,
    given_up: &mut String,
) -> fmt::Result {
    let parsed = match parse_with(line, options) {
        Ok(parsed) => parsed,
        Err(err) => return err.write_json(w),
    };
    parsed.write_json(w, values)?;
    let Some(fragment) = parsed.sentence.fragment() else {
        return Ok(());
    };
    let Some(assembler) = assembler else {
        return if fragment.count == 1 { add_message(w, fragment.payload, fragment.fill_bits) } else { Ok(()) };
    };
    let mut written = Ok(());
    assembler.feed(Some(fragment), parsed.tag_blocks, |done| {
        written = written.and(match done.joined {
            Some((payload, fill_bits)) => add_message(w, payload, fill_bits),
            None => incomplete(given_up, &done.incomplete_message()),
        });
    });
    written
}

/// The error line of a message given up (`incomplete_message`).
fn incomplete(out: &mut String, message: &dyn fmt::Display) -> fmt::Result {
    writeln!(
        out,
        "{{\"ok\":false,\"error\":{{\"kind\":\"incomplete_message\",\"address\":\"AIS\",\"field\":null,\"name\":null,\"message\":\"{message}\"}}}}"
    )
}

fn decode(values: bool, options: Options) -> io::Result<()> {
    let mut input = BufReader::with_capacity(BUFFER, io::stdin().lock());
    let mut out = Output::new(BufWriter::with_capacity(BUFFER, io::stdout().lock()));
    let mut unused = String::new();
    for_each_line(&mut input, MAX_LINE, |line| match line {
        Ok(line) => out.line(|w| write_line(w, line, values, options, None, &mut unused)),
        Err(length) => out.line(|w| Error::too_long(length).write_json(w)),
    })?;
    out.inner.flush()
}

/// A binary frame's JSON (docs/json.md, "Binary frames in stream").
fn write_frame(w: &mut String, protocol: Protocol, frame: &[u8]) -> fmt::Result {
    write!(w, "{{\"ok\":true,\"protocol\":\"{}\",", protocol.name())?;
    for (name, value) in protocol.framing().identity_of(frame) {
        match value {
            Some(value) => write!(w, "\"{name}\":{value},")?,
            None => write!(w, "\"{name}\":null,")?, // past the payload's end
        }
    }
    write!(w, "\"length\":{},\"frame\":\"", frame.len())?;
    write_hex(w, frame)
}

/// `stream --ubx`: a UBX frame's JSON with the message it carries: `ubx`, its decoded JSON (that
/// of generated/vectors/ubx.jsonl), or `ubx_error` when its payload does not decode; a SkyTraq,
/// SiRF, CASIC or SBF frame's alike under its protocol's name (`sirf`, `sirf_error`); `stream
/// --rtcm3`: an RTCM 3 frame's alike (`rtcm3`, `rtcm3_error`). Other frames, and those of a
/// protocol the crate does not type, as `stream` writes them.
fn write_typed_frame(w: &mut String, protocol: Protocol, frame: &[u8]) -> fmt::Result {
    write_frame(w, protocol, frame)?;
    let mut message = String::new();
    if nmeaspec::json::write_frame_message(&mut message, protocol, frame)? {
        w.pop(); // the frame's closing brace
        write!(w, ",{message}}}")?;
    }
    Ok(())
}

/// The JSON of what began like a binary frame and is not one: its sync bytes and the reason.
fn write_bad_frame(w: &mut String, protocol: Protocol, error: FrameError, sync: &[u8]) -> fmt::Result {
    write!(
        w,
        "{{\"ok\":false,\"protocol\":\"{}\",\"error\":{{\"kind\":\"{}\",\"message\":\"",
        protocol.name(),
        error.kind()
    )?;
    match error {
        FrameError::BadChecksum { sent, computed } => {
            let width = protocol.framing().check_size + protocol.framing().end.len();
            w.push_str("checksum");
            for i in (0..width).rev() {
                write!(w, " {:02X}", sent >> (8 * i) & 0xFF)?;
            }
            w.push_str(", computed");
            for i in (0..width).rev() {
                write!(w, " {:02X}", computed >> (8 * i) & 0xFF)?;
            }
        }
        FrameError::TooLong(length) => write!(w, "frame is {length} bytes, the limit is {MAX_FRAME}")?,
        FrameError::TooShort(length) => {
            let least = protocol.framing().header + protocol.trailer_len();
            write!(w, "frame is {length} bytes, the least is {least}")?;
        }
        FrameError::NulHeader => w.push_str("the header after the sync is NUL bytes"),
        FrameError::Cut => w.push_str("the stream ends inside the frame"),
    }
    w.push_str("\"},\"bytes\":\"");
    write_hex(w, sync)
}

/// Bytes as lowercase hex, then the closing quote and brace.
fn write_hex(w: &mut String, bytes: &[u8]) -> fmt::Result {
    for byte in bytes {
        write!(w, "{byte:02x}")?;
    }
    w.push_str("\"}");
    Ok(())
}

fn stream(values: bool, options: Options, ubx: bool, rtcm3: bool) -> io::Result<()> {
    let mut input = io::stdin().lock();
    let mut out = Output::new(BufWriter::with_capacity(BUFFER, io::stdout().lock()));
    let mut framer = Framer::with_binary_frames();
    let mut chunk = vec![0u8; BUFFER];
    let mut assembler: Assembler = Assembler::new(100);
    let mut given_up = String::new();
    let mut write = |out: &mut Output<BufWriter<io::StdoutLock<'_>>>, item: Item<'_>| {
        match item {
            Item::Line(line) => {
                out.line(|w| write_line(w, line, values, options, Some(&mut assembler), &mut given_up))?
            }
            Item::TooLong(length) => out.line(|w| Error::too_long(length).write_json(w))?,
            Item::Frame(Protocol::Rtcm3, frame) if rtcm3 => out.line(|w| write_typed_frame(w, Protocol::Rtcm3, frame))?,
            Item::Frame(protocol, frame) if ubx && protocol != Protocol::Rtcm3 => {
                out.line(|w| write_typed_frame(w, protocol, frame))?
            }
            Item::Frame(protocol, frame) => out.line(|w| write_frame(w, protocol, frame))?,
            Item::BadFrame(protocol, error, sync) => out.line(|w| write_bad_frame(w, protocol, error, sync))?,
        }
        out.inner.write_all(given_up.as_bytes())?;
        given_up.clear();
        Ok::<_, io::Error>(())
    };
    loop {
        let n = match input.read(&mut chunk) {
            Ok(0) => break,
            Ok(n) => n,
            Err(err) if err.kind() == io::ErrorKind::Interrupted => continue,
            Err(err) => return Err(err),
        };
        let mut written = Ok(());
        framer.feed(&chunk[..n], |item| {
            if written.is_ok() {
                written = write(&mut out, item);
            }
        });
        written?;
    }
    let mut written = Ok(());
    framer.finish(|item| {
        if written.is_ok() {
            written = write(&mut out, item);
        }
    });
    written?;
    given_up.clear();
    let mut written = Ok(());
    assembler.finish(|done| written = written.and(incomplete(&mut given_up, &done.incomplete_message())));
    written.map_err(|_| io::Error::other("formatting failed"))?;
    out.inner.write_all(given_up.as_bytes())?;
    out.inner.flush()
}

fn encode() -> io::Result<()> {
    let mut input = BufReader::with_capacity(BUFFER, io::stdin().lock());
    let mut out = Output::new(BufWriter::with_capacity(BUFFER, io::stdout().lock()));
    let mut line = Vec::new();
    loop {
        line.clear();
        if input.read_until(b'\n', &mut line)? == 0 {
            break;
        }
        if line.last() == Some(&b'\n') {
            line.pop();
        }
        if line.last() == Some(&b'\r') {
            line.pop();
        }
        // JSON nested deeper than the limit is "not JSON", also for this check.
        let value = Value::parse_nested(&line, SKIP_CHECK_DEPTH).map(|(value, _)| value);
        // decode's error lines have nothing to encode.
        if value.as_ref().and_then(|v| v.get("ok")) == Some(&Value::Bool(false)) {
            continue;
        }
        out.line(|w| write_encoded(w, value.as_ref()))?;
    }
    out.inner.flush()
}

fn fixes() -> io::Result<()> {
    let mut input = BufReader::with_capacity(BUFFER, io::stdin().lock());
    let mut out = Output::new(BufWriter::with_capacity(BUFFER, io::stdout().lock()));
    let mut assembler = FixAssembler::new();
    let write = |out: &mut Output<_>, fix: Option<Fix>| match fix {
        Some(fix) => out.line(|w| fix.write_json(w)),
        None => Ok(()),
    };
    for_each_line(&mut input, MAX_LINE, |line| match line {
        Ok(line) => write(&mut out, assembler.feed_line(line)),
        Err(_) => Ok(()),
    })?;
    write(&mut out, assembler.finish())?;
    out.inner.flush()
}

/// Flags of decode and stream: each known one at most once, in any order.
fn flags_ok(flags: &[&str]) -> bool {
    const FLAGS: [&str; 6] = ["--values", "--lenient", "--require-checksum", "--strict", "--ubx", "--rtcm3"];
    flags.iter().enumerate().all(|(i, flag)| FLAGS.contains(flag) && !flags[..i].contains(flag))
}

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args_os().skip(1).map(|a| a.to_string_lossy().into_owned()).collect();
    let args: Vec<&str> = args.iter().map(String::as_str).collect();
    let result = match args.as_slice() {
        ["encode"] => encode(),
        ["fixes"] => fixes(),
        ["--version"] => {
            println!("nmea-rs {}", nmeaspec::VERSION);
            return ExitCode::SUCCESS;
        }
        [verb @ ("decode" | "stream"), flags @ ..] if flags_ok(flags) => {
            let values = flags.contains(&"--values");
            let options = Options {
                lenient: flags.contains(&"--lenient"),
                require_checksum: flags.contains(&"--require-checksum"),
                strict: flags.contains(&"--strict"),
            };
            if *verb == "decode" {
                decode(values, options)
            } else {
                stream(values, options, flags.contains(&"--ubx"), flags.contains(&"--rtcm3"))
            }
        }
        _ => {
            eprint!("{USAGE}");
            return ExitCode::from(2);
        }
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(err) if err.kind() == io::ErrorKind::BrokenPipe => ExitCode::SUCCESS,
        Err(err) => {
            eprintln!("nmea-rs: {err}");
            ExitCode::from(1)
        }
    }
}
