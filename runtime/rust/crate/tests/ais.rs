//! The AIS messages (nmeaspec::ais_messages) against generated/vectors/ais.jsonl, which the
//! Python codec decodes and encodes too: every payload decodes to the same JSON as Python's (each
//! field's value, raw integer, special value, enum id, text as sent, data and trailing bits, the
//! fill bits' values) or fails with the same error kind, and encodes back to the same armored
//! characters and fill bits.
#![cfg(feature = "ais")]

use std::fs;
use std::path::Path;

use nmeaspec::ais_messages::Message;

#[cfg(feature = "binary")]
mod rtcm3;

const CRATE: &str = env!("CARGO_MANIFEST_DIR");

/// The text of a member of a JSON record (a string's without its quotes; the members read here
/// hold no comma, quote or brace).
fn member<'r>(record: &'r str, key: &str) -> &'r str {
    let start = record.find(&format!("\"{key}\":")).unwrap_or_else(|| panic!("no {key} in {record}")) + key.len() + 3;
    let rest = &record[start..];
    rest[..rest.find([',', '}']).unwrap_or(rest.len())].trim_matches('"')
}

#[test]
fn messages_decode_and_encode_as_the_vectors_say() {
    let path = Path::new(CRATE).join("../vectors/ais.jsonl");
    let data = fs::read_to_string(&path).unwrap_or_else(|err| panic!("{}: {err}", path.display()));
    let (mut decoded, mut refused) = (0, 0);
    for record in data.lines() {
        let (armored, fill_bits) = (member(record, "payload"), member(record, "fill_bits").parse().unwrap());
        let message = Message::decode(armored.as_bytes(), fill_bits);
        if record.contains("\"error\":") {
            let kind = message.map(|_| "none").unwrap_or_else(|err| err.kind.as_str());
            assert_eq!(kind, member(record, "error"), "{record}");
            refused += 1;
            continue;
        }
        let message = message.unwrap_or_else(|err| panic!("{err}: {record}"));
        let mut json = String::new();
        message.write_json(&mut json, fill_bits).unwrap();
        let expected = &record[record.find("\"decode\":").unwrap() + 9..record.len() - 1];
        assert_eq!(json, expected, "{record}");
        let encoded = message.encode().unwrap_or_else(|err| panic!("{err}: {record}"));
        assert_eq!((encoded.as_str(), encoded.fill_bits()), (armored, fill_bits), "{record}");
        decoded += 1;
    }
    assert_eq!((decoded, refused), (44, 6));
}
