//! The AIS runtime (nmeaspec::ais) against generated/vectors/ais.jsonl, which the Python codec
//! decodes and encodes too: every payload's armor checked (refused where the vector says
//! bad_armor), the message type, MMSI and the values of the fill bits of each decoded one read,
//! and its bits written back to the same characters and fill bits. The
//! per-message types that will decode each field from the same model are yet to be generated.

use std::fs;
use std::path::Path;

use nmeaspec::ais::{AisErrorKind, BitWriter, Payload};

const CRATE: &str = env!("CARGO_MANIFEST_DIR");

/// The text of a member of a JSON record (a string's without its quotes; the members read here
/// hold no comma, quote or brace).
fn member<'r>(record: &'r str, key: &str) -> &'r str {
    let start = record.find(&format!("\"{key}\":")).unwrap_or_else(|| panic!("no {key} in {record}")) + key.len() + 3;
    let rest = &record[start..];
    rest[..rest.find([',', '}']).unwrap_or(rest.len())].trim_matches('"')
}

#[test]
fn payloads_read_and_write_back_as_the_vectors_say() {
    let path = Path::new(CRATE).join("../vectors/ais.jsonl");
    let data = fs::read_to_string(&path).unwrap_or_else(|err| panic!("{}: {err}", path.display()));
    let (mut decoded, mut refused) = (0, 0);
    for record in data.lines() {
        let (armored, fill_bits) = (member(record, "payload"), member(record, "fill_bits").parse().unwrap());
        let payload = Payload::new(armored.as_bytes(), fill_bits);
        if record.contains("\"error\":\"bad_armor\"") {
            assert_eq!(payload.map_err(|err| err.kind), Err(AisErrorKind::BadArmor), "{record}");
            refused += 1;
            continue;
        }
        // The other errors are the layouts' (a payload too short for its message, a type no
        // layout describes): its bits still read and write back.
        let payload = payload.unwrap_or_else(|err| panic!("{err}: {record}"));
        let mut writer = BitWriter::new(0);
        let bits = payload.reader().take_bits(payload.bit_len(), "message").unwrap();
        writer.put_bits(bits, "message").unwrap();
        let written = writer.finish(payload.padding()).unwrap();
        assert_eq!((written.as_str(), written.fill_bits()), (armored, fill_bits), "{record}");
        if record.contains("\"error\":") {
            continue;
        }
        let mut reader = payload.reader();
        assert_eq!(reader.take(6, "message_type").unwrap().to_string(), member(record, "message_type"), "{record}");
        assert_eq!(reader.peek(8, 30, "mmsi").unwrap().to_string(), member(record, "mmsi"), "{record}");
        let padding = u8::from_str_radix(member(record, "padding"), 2).unwrap_or(0);
        assert_eq!(payload.padding(), padding, "{record}");
        decoded += 1;
    }
    assert_eq!((decoded, refused), (44, 3));
}
