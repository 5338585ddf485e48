//! The RTCM 3 messages (nmeaspec::rtcm3_messages) against generated/vectors/rtcm3.jsonl, which
//! the Python codec and the reference decoder decode too: every frame decodes to the same JSON as
//! Python's (each field's value, raw integer, special value, characters, the cell mask's bits,
//! group entries in mask order, trailing bits) or fails with the same error kind, and encodes back
//! to the same bytes. Then every RTCM 3 frame of the logs in tests/data, cut by the stream framer,
//! decodes and encodes back byte-exact, and a payload cut at any length is refused, never read
//! past. (A module of the AIS test binary: the two share the bit layouts' reader and writer.)

use std::collections::BTreeSet;
use std::fs;
use std::path::Path;

use nmeaspec::ais::AisErrorKind;
use nmeaspec::rtcm3_messages::Message;
use nmeaspec::stream::{Framer, Item, Protocol};

const CRATE: &str = env!("CARGO_MANIFEST_DIR");

/// The text of a string member of a JSON record (the members read here hold no comma or quote).
fn member<'r>(record: &'r str, key: &str) -> &'r str {
    let start = record.find(&format!("\"{key}\":")).unwrap_or_else(|| panic!("no {key} in {record}")) + key.len() + 3;
    let rest = &record[start..];
    rest[..rest.find([',', '}']).unwrap_or(rest.len())].trim_matches('"')
}

fn unhex(text: &str) -> Vec<u8> {
    text.split(' ').map(|byte| u8::from_str_radix(byte, 16).unwrap()).collect()
}

#[test]
fn rtcm3_messages_decode_and_encode_as_the_vectors_say() {
    let path = Path::new(CRATE).join("../vectors/rtcm3.jsonl");
    let data = fs::read_to_string(&path).unwrap_or_else(|err| panic!("{}: {err}", path.display()));
    let (mut decoded, mut refused) = (0, 0);
    for record in data.lines() {
        let frame = unhex(member(record, "frame"));
        let message = Message::decode(&frame);
        if !record.contains("\"decode\":") {
            let kind = message.map(|_| "none").unwrap_or_else(|err| err.kind());
            assert_eq!(kind, member(record, "error"), "{record}");
            refused += 1;
            continue;
        }
        let message = message.unwrap_or_else(|err| panic!("{err}: {record}"));
        let mut json = String::new();
        message.write_json(&mut json).unwrap();
        let expected = &record[record.find("\"decode\":").unwrap() + 9..record.len() - 1];
        assert_eq!(json, expected, "{record}");
        assert_eq!(message.encode().unwrap_or_else(|err| panic!("{err}: {record}")).as_bytes(), &frame[..], "{record}");
        decoded += 1;
    }
    println!("rtcm3.jsonl: {decoded} decoded, {refused} refused");
    assert!(decoded > 40 && refused >= 2, "{decoded} decoded, {refused} refused");
}

/// Every RTCM 3 frame of the logs in tests/data/<dir>: its file's name, the frame.
fn rtcm3_frames(dirs: &[&str]) -> Vec<(String, Vec<u8>)> {
    let mut frames = Vec::new();
    for dir in dirs {
        let mut paths: Vec<_> = fs::read_dir(Path::new(CRATE).join("../../tests/data").join(dir))
            .unwrap()
            .map(|entry| entry.unwrap().path())
            .filter(|path| path.extension().is_some_and(|ext| ext == "log"))
            .collect();
        paths.sort();
        for path in paths {
            let name = path.file_name().unwrap().to_string_lossy().into_owned();
            let mut framer = Framer::with_binary_frames();
            let mut take = |item: Item<'_>| {
                if let Item::Frame(Protocol::Rtcm3, frame) = item {
                    frames.push((name.clone(), frame.to_vec()));
                }
            };
            framer.feed(&fs::read(&path).unwrap(), &mut take);
            framer.finish(&mut take);
        }
    }
    frames
}

#[test]
fn every_logged_rtcm3_frame_decodes_and_encodes_back() {
    let (mut known, mut unknown) = (0, 0);
    let mut cut = BTreeSet::new();
    for (file, frame) in rtcm3_frames(&["rtcm3", "ubx"]) {
        let message = Message::decode(&frame).unwrap_or_else(|err| panic!("{file}: {err}"));
        match message {
            Message::Unknown(_) => unknown += 1,
            _ => known += 1,
        }
        let mut json = String::new();
        message.write_json(&mut json).unwrap();
        assert_eq!(message.encode().unwrap().as_bytes(), &frame[..], "{file}: {json}");
        // the first frame of each number cut at every length: refused (or an Unknown), never
        // read past its end
        let payload = &frame[3..frame.len() - 3];
        if message.id().is_some() && cut.insert(message.message_number()) {
            for len in 0..payload.len() {
                match Message::from_payload(&payload[..len]) {
                    Ok(Message::Unknown(_)) => assert!(len < 2, "{file}: {len}"),
                    Ok(short) => {
                        // the fields end before the cut: what follows them is trailing bits
                        assert_eq!(short.payload().unwrap().written(), &payload[..len], "{file}: {len}");
                    }
                    Err(err) => assert!(
                        matches!(err.kind, AisErrorKind::ShortPayload | AisErrorKind::BadValue),
                        "{file}: {err}"
                    ),
                }
            }
        }
    }
    println!("RTCM 3 frames of the logs: {known} decoded, {unknown} of numbers the spec does not describe");
    assert!(known > 200 && unknown < known / 10, "{known} known, {unknown} unknown");
}

#[test]
fn an_rtcm3_error_names_message_number_and_field() {
    let frame = unhex("d3 00 03 3e d0 00 7a 79 fe");
    let err = Message::decode(&frame).unwrap_err();
    assert_eq!(err.to_string(), "short_payload: RTCM3 1005: itrf_year needs bits 24-29, the payload has 24");
    let mut json = String::new();
    let nmeaspec::rtcm3::Error::Payload(payload) = err else { panic!("{err}") };
    payload.write_json(&mut json).unwrap();
    assert_eq!(
        json,
        r#"{"kind":"short_payload","address":"RTCM3 1005","field":null,"name":"itrf_year","message":"itrf_year needs bits 24-29, the payload has 24"}"#
    );
}
