//! The UBX messages (nmeaspec::ubx_messages) against generated/vectors/ubx.jsonl, which the Python
//! codec and the reference decoder decode too: every frame decodes to the same JSON as Python's
//! (each field's value, raw integer, enum id, bitfield parts, characters and bytes as sent, group
//! entries, trailing bytes) or fails with the same error kind, and encodes back to the same bytes.
//! Then every UBX frame of gpsd's logs (tests/data/ubx, tests/data/rtcm3), cut by the stream
//! framer, decodes and encodes back byte-exact.
#![cfg(feature = "binary")]

use std::fs;
use std::path::Path;

use nmeaspec::stream::{Framer, Item, Protocol};
use nmeaspec::ubx::UbxErrorKind;
use nmeaspec::ubx_messages::{AckAck, Message, NavPvt};

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
fn messages_decode_and_encode_as_the_vectors_say() {
    let path = Path::new(CRATE).join("../vectors/ubx.jsonl");
    let data = fs::read_to_string(&path).unwrap_or_else(|err| panic!("{}: {err}", path.display()));
    let (mut decoded, mut refused) = (0, 0);
    let mut buf = vec![0u8; 70_000];
    for record in data.lines() {
        let frame = unhex(member(record, "frame"));
        let message = Message::from_frame(&frame);
        if record.contains("\"error\":") && !record.contains("\"decode\":") {
            let kind = message.map(|_| "none").unwrap_or_else(|err| err.kind.as_str());
            assert_eq!(kind, member(record, "error"), "{record}");
            refused += 1;
            continue;
        }
        let message = message.unwrap_or_else(|err| panic!("{err}: {record}"));
        let mut json = String::new();
        message.write_json(&mut json).unwrap();
        let expected = &record[record.find("\"decode\":").unwrap() + 9..record.len() - 1];
        assert_eq!(json, expected, "{record}");
        assert_eq!(message.encode(&mut buf).unwrap_or_else(|err| panic!("{err}: {record}")), &frame[..], "{record}");
        decoded += 1;
    }
    assert!(decoded > 0 && refused > 0, "{decoded} decoded, {refused} refused");
}

/// Every UBX frame of the logs in `dir`: its file's name, the frame.
fn log_frames(dir: &str) -> Vec<(String, Vec<u8>)> {
    let mut frames = Vec::new();
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
            if let Item::Frame(Protocol::Ubx, frame) = item {
                frames.push((name.clone(), frame.to_vec()));
            }
        };
        framer.feed(&fs::read(&path).unwrap(), &mut take);
        framer.finish(&mut take);
    }
    frames
}

#[test]
fn every_logged_frame_decodes_and_encodes_back() {
    let mut buf = vec![0u8; 70_000];
    let (mut known, mut unknown) = (0, 0);
    for dir in ["ubx", "rtcm3"] {
        for (file, frame) in log_frames(dir) {
            let message = Message::from_frame(&frame).unwrap_or_else(|err| panic!("{file}: {err}"));
            match message {
                Message::Unknown(_) => unknown += 1,
                _ => known += 1,
            }
            let mut json = String::new();
            message.write_json(&mut json).unwrap();
            assert_eq!(message.encode(&mut buf).unwrap(), &frame[..], "{file}: {json}");
        }
    }
    // gpsd's logs hold hundreds of frames, nearly all of classes and ids the spec describes.
    assert!(known > 100 && unknown < known / 10, "{known} known, {unknown} unknown");
}

#[test]
fn a_short_payload_names_message_field_and_bytes() {
    let err = Message::decode(0x01, 0x07, &[0; 28]).unwrap_err();
    assert_eq!((err.kind, err.message, err.field), (UbxErrorKind::ShortPayload, "NAV-PVT", Some("lat")));
    assert_eq!(err.to_string(), "short_payload: UBX NAV-PVT: lat needs bytes 28-31, the payload has 28");
    assert_eq!(NavPvt::read(&[0; 28]), Err(err));
}

#[test]
fn an_undescribed_class_and_id_is_kept_with_its_payload() {
    let frame = [0xB5, 0x62, 0x7F, 0x01, 0x01, 0x00, 0xAA, 0x2B, 0x2C];
    let message = Message::from_frame(&frame).unwrap();
    let mut json = String::new();
    message.write_json(&mut json).unwrap();
    assert_eq!(json, r#"{"message":null,"class":127,"id":1,"payload":"aa"}"#);
    assert_eq!(message.encode(&mut [0u8; 9]).unwrap(), &frame[..]);
}

#[test]
fn a_message_built_in_code_encodes_to_its_frame() {
    let ack = AckAck { cls_id: 0x06, msg_id: 0x00, trailing: &[] };
    let mut buf = [0u8; 10];
    assert_eq!(ack.encode(&mut buf).unwrap(), [0xB5, 0x62, 0x05, 0x01, 0x02, 0x00, 0x06, 0x00, 0x0E, 0x37]);
    assert_eq!(ack.encode(&mut [0u8; 9]).unwrap_err().kind, UbxErrorKind::BufferTooSmall);
}
