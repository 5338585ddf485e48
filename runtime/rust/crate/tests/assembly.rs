//! AIS messages assembled across sentences (nmeaspec::assembly) against
//! tests/data/ais/assembly_cases.jsonl, the events Python's assembler gives of the same lines:
//! the same messages and given-up partials, in the same order, naming the same lines, with the
//! same payloads and fill bits, or the same error kinds.
#![cfg(feature = "ais")]

use std::fmt::Write;
use std::fs;
use std::path::Path;

use nmeaspec::ais_messages::Message;
use nmeaspec::assembly::{Assembled, Assembler};
use nmeaspec::{parse_with, Options};

const CRATE: &str = env!("CARGO_MANIFEST_DIR");

/// The text of a member of a JSON record, up to the end of its value (an integer, or an array
/// whose items hold no `]`).
fn member<'r>(record: &'r str, key: &str) -> &'r str {
    let start = record.find(&format!("\"{key}\":")).unwrap_or_else(|| panic!("no {key} in {record}")) + key.len() + 3;
    let rest = &record[start..];
    &rest[..rest.find([',', '}']).unwrap_or(rest.len())]
}

/// The strings of the record's `lines` array (JSON strings whose only escapes are `\\` and `\"`).
fn lines(record: &str) -> Vec<String> {
    let mut rest = &record[record.find("\"lines\":[\"").expect("lines") + 9..];
    let mut out = Vec::new();
    while let Some(body) = rest.strip_prefix('"') {
        let mut text = String::new();
        let mut chars = body.char_indices();
        let end = loop {
            match chars.next().expect("a closed string") {
                (_, '\\') => text.push(chars.next().expect("an escape").1),
                (i, '"') => break i,
                (_, c) => text.push(c),
            }
        };
        out.push(text);
        rest = body[end + 1..].trim_start_matches(',');
    }
    out
}

/// An event in the form of the file.
fn write_event(out: &mut String, after: Option<usize>, done: Assembled<'_>) {
    let after = after.map_or("null".to_string(), |i| i.to_string());
    let lines: Vec<String> = done.lines.iter().map(u32::to_string).collect();
    write!(out, "{{\"after\":{after},\"lines\":[{}]", lines.join(",")).unwrap();
    match done.joined {
        Some((payload, fill_bits)) => {
            write!(out, ",\"payload\":\"{payload}\",\"fill_bits\":{fill_bits}").unwrap();
            if let Err(err) = Message::decode(payload.as_bytes(), fill_bits) {
                write!(out, ",\"error\":\"{}\"", err.kind.as_str()).unwrap();
            }
        }
        None => out.push_str(",\"error\":\"incomplete_message\""),
    }
    out.push_str("},");
}

/// The events of an assembler of `SLOTS` fed the lines then finished, in the form of the file.
fn events<const SLOTS: usize>(lines: &[String], lifetime: u32) -> String {
    let mut assembler = Assembler::<SLOTS>::new(lifetime);
    let mut out = String::from("[");
    for (i, line) in lines.iter().enumerate() {
        let parsed = parse_with(line, Options::default()).unwrap_or_else(|err| panic!("{err}: {line}"));
        assembler.feed(parsed.sentence.fragment(), parsed.tag_blocks, |done| write_event(&mut out, Some(i), done));
    }
    assembler.finish(|done| write_event(&mut out, None, done));
    out.truncate(out.len() - usize::from(out.len() > 1));
    out + "]"
}

#[test]
fn messages_assemble_as_the_shared_cases_say() {
    let path = Path::new(CRATE).join("../../tests/data/ais/assembly_cases.jsonl");
    let data = fs::read_to_string(&path).unwrap_or_else(|err| panic!("{}: {err}", path.display()));
    let mut cases = 0;
    for record in data.lines() {
        let (lines, lifetime) = (lines(record), member(record, "lifetime").parse().unwrap());
        let events = match member(record, "slots") {
            "2" => events::<2>(&lines, lifetime),
            "16" => events::<16>(&lines, lifetime),
            slots => panic!("no assembler of {slots} slots here: {record}"),
        };
        let expected = &record[record.find("\"events\":").unwrap() + 9..record.len() - 1];
        assert_eq!(events, expected, "{record}");
        cases += 1;
    }
    assert_eq!(cases, 15);
}
