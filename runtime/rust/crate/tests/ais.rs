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
    // The counts come from the vectors themselves (a record to refuse names its error): every
    // record was read, and the file holds some of each.
    let to_refuse = data.lines().filter(|record| record.contains("\"error\":")).count();
    let records = data.lines().count();
    assert!(to_refuse > 0 && records > to_refuse, "{}: too few vectors", path.display());
    assert_eq!((decoded, refused), (records - to_refuse, to_refuse));
}

/// A message a program builds, with its own text: a safety broadcast (text to the end) and a
/// static data report's name (a field of 20 characters, padded with `@`).
#[test]
fn messages_built_with_a_programs_text_encode() {
    use nmeaspec::ais_messages::{SafetyBroadcast, StaticDataReport};
    use nmeaspec::ais::SixBitText;

    let mut buf = [0u8; 32];
    let text = SixBitText::armor_into("ALL SHIPS: BUOY ADRIFT", &mut buf).unwrap();
    let broadcast = Message::SafetyBroadcast(SafetyBroadcast { message_type: 14, mmsi: 366_999_999, text, ..Default::default() });
    let armored = broadcast.encode().unwrap();
    let Ok(Message::SafetyBroadcast(back)) = Message::decode(armored.as_str().as_bytes(), armored.fill_bits()) else {
        panic!("{}", armored.as_str())
    };
    assert_eq!((back.mmsi, back.text.to_string()), (366_999_999, "ALL SHIPS: BUOY ADRIFT".to_string()));

    let mut name = [0u8; 20];
    let shipname = Some(SixBitText::armor_into("NORDIC STAR@@@@@@@@@", &mut name).unwrap());
    let report = StaticDataReport { message_type: 24, mmsi: 257_000_000, shipname, spare: Some(0), ..Default::default() };
    let armored = Message::StaticDataReport(report).encode().unwrap();
    let Ok(Message::StaticDataReport(back)) = Message::decode(armored.as_str().as_bytes(), armored.fill_bits()) else {
        panic!("{}", armored.as_str())
    };
    assert_eq!(back.shipname.unwrap().trimmed().collect::<String>(), "NORDIC STAR");

    // A name short of its field's 20 characters, a character six-bit text lacks, a buffer too short.
    let mut short = [0u8; 20];
    let shipname = Some(SixBitText::armor_into("NORDIC STAR", &mut short).unwrap());
    let err = Message::StaticDataReport(StaticDataReport { shipname, ..report }).encode().unwrap_err();
    assert_eq!(err.to_string(), "bad_value: AIS type 24: shipname takes 20 six-bit text characters, not 11");
    let err = SixBitText::armor_into("nordic", &mut short).unwrap_err();
    assert_eq!(err.to_string(), "bad_value: AIS: text takes six-bit text characters, not 'n'");
    assert_eq!(SixBitText::armor_into("NORDIC STAR", &mut [0u8; 4]).unwrap_err().kind.as_str(), "bad_value");
}
