//! The fast path of `parse` and `parse_with` against the general path alone (`parse_general`,
//! `parse_with_general`): the same sentence, or the same error, with every option, on
//! - every line of every file of the real receiver logs (`../shared/corpus/real` beside the
//!   repository; the test fails without them, as the tools' agreement test does),
//! - the edge cases of tests/agreement/edge_cases.txt,
//! - every example of the manuals (generated/vectors/examples.jsonl), as printed and as corrected,
//! - and each of those with its checksum made right (or added), and variants of the examples and
//!   of log lines of every layout, with one byte replaced, removed or added and the checksum made
//!   right: those reach the fast path's field readers, where a line with a wrong checksum would
//!   not.
//!
//! The fast path must also read most of the logs' lines, or this test would prove nothing.
//!
//! Likewise the byte writer of `serialize_into` against the `fmt` writer (`Display`)
//! on every sentence read, lenient readings with problems included: the same text, or `None`
//! when the buffer is too small for it.

use std::collections::HashMap;
use std::fs;
use std::path::{Path, PathBuf};

use nmeaspec::json::Value;
use nmeaspec::paths::{parse_fast, parse_general, parse_with_general, serialize_fast};
use nmeaspec::{parse, parse_with, LayoutId, Options, Parsed, MAX_LINE};

const CRATE: &str = env!("CARGO_MANIFEST_DIR");

/// The bytes the variants put in: what number, time, coordinate, code and text readers stop
/// at, refuse, or take in another way than the usual.
const BYTES: &[u8] = b"-+.,*09AaNSEWMTV $!\t\x7f\x80\xc3\xff";

/// What one run found.
#[derive(Default)]
struct Tally {
    lines: usize,
    known: usize,
    fast: usize,
    /// Lines the general path read.
    read: usize,
    /// Sentences the byte writer wrote without its `fmt` fallback.
    written_fast: usize,
}

impl Tally {
    /// Checks one line (with or without its line ending): `parse` gives what the general path
    /// gives, and so does `parse_with` with every option when the fast path reads the line (when
    /// it does not, `parse_with` is the general path).
    fn check(&mut self, line: &[u8]) {
        let general = parse_general(line);
        assert_eq!(parse(line), general, "parse disagrees with the general path on {:?}", show(line));
        self.lines += 1;
        self.known += usize::from(general.as_ref().is_ok_and(|sentence| sentence.layout().is_some()));
        if let Ok(sentence) = &general {
            check_writing(&(*sentence).into(), line);
            self.read += 1;
            self.written_fast += usize::from(serialize_fast(sentence, &mut [0; MAX_LINE]).is_some());
        }
        if let Ok(parsed) = parse_with_general(line, Options { lenient: true, ..Options::default() }) {
            check_writing(&parsed, line);
        }
        let Some(sentence) = parse_fast(line) else {
            return;
        };
        assert_eq!(Ok(sentence), general, "the fast path read {:?} differently", show(line));
        self.fast += 1;
        for (lenient, require_checksum, strict) in
            [(false, false, false), (true, false, false), (false, true, true), (true, true, true)]
        {
            let options = Options { lenient, require_checksum, strict };
            assert_eq!(
                parse_with(line, options),
                parse_with_general(line, options),
                "parse_with ({options:?}) disagrees with the general path on {:?}",
                show(line)
            );
        }
    }

    /// Checks `line`, and the same line with its checksum made right when that changes it.
    fn check_with_checksum(&mut self, line: &[u8]) {
        self.check(line);
        if let Some(fixed) = with_checksum(line).filter(|fixed| line.trim_ascii_end() != fixed.as_slice()) {
            self.check(&fixed);
        }
    }
}

/// `serialize_into` writes what the `fmt` writer writes (the sentence's text with its problem
/// fields' texts put back), into a buffer of any size: all of it, or `None`.
fn check_writing(parsed: &Parsed<'_>, line: &[u8]) {
    let expected = parsed.to_string();
    let mut buf = [0u8; MAX_LINE + 64];
    let written =
        parsed.serialize_into(&mut buf).unwrap_or_else(|| panic!("serialize_into wrote nothing for {:?}", show(line)));
    assert_eq!(show(&buf[..written]), expected, "serialize_into and the fmt writer disagree on {:?}", show(line));
    if parsed.problems.is_empty() {
        // The sentence alone writes the line without its TAG blocks.
        let alone = parsed.sentence.serialize_into(&mut buf).map(|n| show(&buf[..n]));
        if parsed.tag_blocks.is_empty() {
            assert_eq!(alone.as_deref(), Some(expected.as_str()), "the sentence alone wrote {:?} differently", show(line));
        } else if let Some(alone) = &alone {
            assert!(expected.ends_with(alone.as_str()), "the sentence alone wrote {alone:?} for {:?}", show(line));
        }
        if let Some(fast) = serialize_fast(&parsed.sentence, &mut buf) {
            assert_eq!(Some(show(&buf[..fast])), alone, "the byte writer alone wrote {:?} differently", show(line));
        }
    }
    for capacity in [written - 1, written / 2, 0] {
        assert_eq!(parsed.serialize_into(&mut buf[..capacity]), None, "{capacity} bytes took {:?}", show(line));
    }
}

fn show(line: &[u8]) -> String {
    String::from_utf8_lossy(line).into_owned()
}

/// `$` and the body of `line` (up to its last `*`, or all of it without one) with the right
/// upper-case checksum; `None` for a line that does not start with `$`.
fn with_checksum(line: &[u8]) -> Option<Vec<u8>> {
    let line = line.strip_suffix(b"\n").unwrap_or(line);
    let line = line.strip_suffix(b"\r").unwrap_or(line);
    let rest = line.strip_prefix(b"$")?;
    let body = match rest.iter().rposition(|&b| b == b'*') {
        Some(star) => &rest[..star],
        None => rest,
    };
    let sum = body.iter().fold(0u8, |sum, b| sum ^ b);
    let mut out = Vec::with_capacity(body.len() + 4);
    out.push(b'$');
    out.extend_from_slice(body);
    out.extend_from_slice(format!("*{sum:02X}").as_bytes());
    Some(out)
}

/// Variants of a `$…*hh` line: at every byte of its body, one of [`BYTES`] in its place, the
/// byte removed, or a comma added before it (the byte put in is picked by position and `seed`,
/// so that every position meets every byte over the logs); each with its checksum made right.
fn variants(line: &[u8], seed: usize, mut check: impl FnMut(&[u8])) {
    let line = line.strip_suffix(b"\n").unwrap_or(line);
    let line = line.strip_suffix(b"\r").unwrap_or(line);
    let Some(body) = line.strip_prefix(b"$").and_then(|rest| rest.get(..rest.len().checked_sub(3)?)) else {
        return;
    };
    let mut variant = Vec::with_capacity(line.len() + 4);
    for at in 0..body.len() {
        for edit in 0..3 {
            variant.clear();
            variant.push(b'$');
            variant.extend_from_slice(&body[..at]);
            match edit {
                0 => variant.push(BYTES[(at + seed) % BYTES.len()]),
                1 => {}
                _ => variant.extend_from_slice(&[b',', body[at]]),
            }
            variant.extend_from_slice(&body[at + 1..]);
            if let Some(fixed) = with_checksum(&variant) {
                check(&fixed);
            }
        }
    }
}

/// Every file under `dir`, in sorted order.
fn files(dir: &Path) -> Vec<PathBuf> {
    let mut found = Vec::new();
    let mut entries: Vec<_> = fs::read_dir(dir)
        .unwrap_or_else(|err| panic!("{}: {err}", dir.display()))
        .map(|entry| entry.expect("a directory entry").path())
        .collect();
    entries.sort();
    for path in entries {
        if path.is_dir() {
            found.extend(files(&path));
        } else {
            found.push(path);
        }
    }
    found
}

fn lines(data: &[u8]) -> impl Iterator<Item = &[u8]> {
    data.split_inclusive(|&b| b == b'\n')
}

#[test]
fn fast_path_agrees_on_the_real_logs() {
    let dir = Path::new(CRATE).join("../../../shared/corpus/real");
    let missing = "is missing: the real logs live in ../shared/corpus/real beside the repository";
    assert!(dir.is_dir(), "{} {missing}", dir.display());
    let paths = files(&dir);
    assert!(paths.len() > 50, "expected the real logs in {}", dir.display());
    let (mut tally, mut edited) = (Tally::default(), Tally::default());
    let mut varied: HashMap<LayoutId, usize> = HashMap::new();
    for path in &paths {
        let data = fs::read(path).unwrap_or_else(|err| panic!("{}: {err}", path.display()));
        for (index, line) in lines(&data).enumerate() {
            tally.check_with_checksum(line);
            // Variants of the first lines of each layout, then of one line in 32 (the lines picked
            // differ per file) up to 64 lines a layout: enough to reach every reader, and quick (the
            // few commonest sentences, a tenth of a log each, no longer take most of the time).
            let Some(layout) = parse_fast(line).and_then(|sentence| sentence.layout()) else {
                continue;
            };
            let done = varied.entry(layout).or_default();
            if *done < 4 || (*done < 64 && (index + path.as_os_str().len()) % 32 == 0) {
                *done += 1;
                variants(line, index, |variant| edited.check(variant));
            }
        }
    }
    println!(
        "real logs: {} lines, {} of known layouts, {} on the fast path; {} variants, {} of known layouts, {} on \
         the fast path",
        tally.lines, tally.known, tally.fast, edited.lines, edited.known, edited.fast
    );
    // The lines of known layouts with a lower-case checksum or none count twice, the copy with
    // its checksum made right on the fast path: it reads nearly all of them.
    assert!(tally.fast * 10 > tally.known * 9, "the fast path read only {} of {} lines", tally.fast, tally.known);
    assert!(edited.fast > 0 && edited.fast < edited.known);
    // Every sentence read from the logs is ASCII and none is a text command: the byte writer
    // writes each without falling back.
    assert_eq!(tally.written_fast, tally.read, "the byte writer left sentences to fmt");
}

#[test]
fn fast_path_agrees_on_the_edge_cases() {
    let path = Path::new(CRATE).join("../../tests/agreement/edge_cases.txt");
    let data = fs::read(&path).unwrap_or_else(|err| panic!("{}: {err}", path.display()));
    let mut tally = Tally::default();
    for line in lines(&data) {
        tally.check_with_checksum(line);
    }
    assert!(tally.fast > 0, "no edge case reached the fast path");
}

#[test]
fn fast_path_agrees_on_the_examples() {
    let path = Path::new(CRATE).join("../vectors/examples.jsonl");
    let data = fs::read(&path).unwrap_or_else(|err| panic!("{}: {err}", path.display()));
    let (mut tally, mut edited) = (Tally::default(), Tally::default());
    for (index, text) in lines(&data).enumerate() {
        let example =
            Value::parse(text).unwrap_or_else(|| panic!("{}: line {} is not JSON", path.display(), index + 1));
        for key in ["raw", "line"] {
            let Some(Value::String(line)) = example.get(key) else {
                continue;
            };
            // The JSON string holds the line's bytes as characters up to U+00FF; a manual's text
            // with a character beyond (a Unicode minus) is read as its UTF-8 bytes, as the tools do.
            let line: Vec<u8> = match line.chars().map(|c| u8::try_from(u32::from(c))).collect() {
                Ok(bytes) => bytes,
                Err(_) => line.as_bytes().to_vec(),
            };
            tally.check_with_checksum(&line);
            if key == "line" {
                variants(&line, index, |variant| edited.check(variant));
            }
        }
    }
    assert!(tally.fast > 0 && edited.fast > 0, "no example reached the fast path");
}
