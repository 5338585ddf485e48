//! The UBX messages (nmeaspec::ubx_messages) against generated/vectors/ubx.jsonl, which the Python
//! codec and the reference decoder decode too: every frame decodes to the same JSON as Python's
//! (each field's value, raw integer, enum id, bitfield parts, characters and bytes as sent, group
//! entries, trailing bytes) or fails with the same error kind, and encodes back to the same bytes.
//! Then every UBX frame of gpsd's logs (tests/data/ubx, tests/data/rtcm3), cut by the stream
//! framer, decodes and encodes back byte-exact. The same for SkyTraq, SiRF and CASIC
//! (nmeaspec::{skytraq,sirf,casic}_messages): generated/vectors/binary.jsonl, then every frame of
//! their logs (tests/data/{skytraq,sirf,casic}), and their errors.
#![cfg(feature = "binary")]

use std::fs;
use std::path::Path;

use nmeaspec::stream::{Framer, Item, Protocol};
use nmeaspec::ubx::UbxErrorKind;
use nmeaspec::ubx_messages::{AckAck, Message, MgaIniClkd, MgaIniFreq, NavPvt};
use nmeaspec::{casic_messages, sbf_messages, sirf_messages, skytraq_messages, unicore_messages};

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
    frames_of(dir, Protocol::Ubx)
}

/// Every frame of `protocol` of the logs in `dir`: its file's name, the frame.
fn frames_of(dir: &str, protocol: Protocol) -> Vec<(String, Vec<u8>)> {
    let mut frames = Vec::new();
    let mut paths: Vec<_> = fs::read_dir(Path::new(CRATE).join("../../tests/data").join(dir))
        .unwrap()
        .map(|entry| entry.unwrap().path())
        .filter(|path| path.extension().is_some_and(|ext| ext == "log" || ext == "sbf"))
        .collect();
    paths.sort();
    for path in paths {
        let name = path.file_name().unwrap().to_string_lossy().into_owned();
        let mut framer = Framer::with_binary_frames();
        let mut take = |item: Item<'_>| {
            if matches!(item, Item::Frame(p, _) if p == protocol) {
                let Item::Frame(_, frame) = item else { unreachable!() };
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

#[test]
fn a_layout_built_with_new_carries_its_type_byte() {
    // MGA-INI's CLKD (type 0x20) and FREQ (0x21) share a length: new() sets the type that picks it.
    let clkd = MgaIniClkd { clk_d: -1234, clk_d_acc: 100, ..MgaIniClkd::new() };
    let frame = unhex("b5 62 13 40 0c 00 20 00 00 00 2e fb ff ff 64 00 00 00 0a ea");
    assert_eq!(clkd.encode(&mut [0u8; 20]).unwrap(), &frame[..]);
    assert_eq!(MgaIniClkd::SELECT, Some(("type", 0, 0x20)));
    assert!(matches!(Message::from_frame(&frame), Ok(Message::MgaIniClkd(m)) if m == clkd));
    let freq = MgaIniFreq::new();
    let mut buf = [0u8; 20];
    assert!(matches!(Message::from_frame(freq.encode(&mut buf).unwrap()), Ok(Message::MgaIniFreq(_))));
}

/// A frame of SkyTraq, SiRF or CASIC decoded by its protocol's module: its JSON and the frame it
/// encodes back to, or its error.
fn other_protocol(protocol: &str, frame: &[u8]) -> Result<(String, Vec<u8>), nmeaspec::ubx::UbxError> {
    let mut json = String::new();
    let mut buf = vec![0u8; 70_000];
    let encoded = match protocol {
        "skytraq" => {
            let m = skytraq_messages::Message::from_frame(frame)?;
            m.write_json(&mut json).unwrap();
            m.encode(&mut buf)?.to_vec()
        }
        "sirf" => {
            let m = sirf_messages::Message::from_frame(frame)?;
            m.write_json(&mut json).unwrap();
            m.encode(&mut buf)?.to_vec()
        }
        "casic" => {
            let m = casic_messages::Message::from_frame(frame)?;
            m.write_json(&mut json).unwrap();
            m.encode(&mut buf)?.to_vec()
        }
        "sbf" => {
            let m = sbf_messages::Message::from_frame(frame)?;
            m.write_json(&mut json).unwrap();
            m.encode(&mut buf)?.to_vec()
        }
        "unicore" => {
            let m = unicore_messages::Message::from_frame(frame)?;
            m.write_json(&mut json).unwrap();
            m.encode(&mut buf)?.to_vec()
        }
        _ => panic!("{protocol}"),
    };
    Ok((json, encoded))
}

#[test]
fn other_protocols_decode_and_encode_as_the_vectors_say() {
    let path = Path::new(CRATE).join("../vectors/binary.jsonl");
    let data = fs::read_to_string(&path).unwrap_or_else(|err| panic!("{}: {err}", path.display()));
    let mut decoded = 0;
    for record in data.lines() {
        let frame = unhex(member(record, "frame"));
        if !record.contains("\"decode\":") {
            // a frame every decoder refuses, with this kind of error
            let err = other_protocol(member(record, "protocol"), &frame).expect_err(record);
            assert_eq!(err.kind.as_str(), member(record, "error"), "{err}: {record}");
            continue;
        }
        let (json, encoded) =
            other_protocol(member(record, "protocol"), &frame).unwrap_or_else(|err| panic!("{err}: {record}"));
        let expected = &record[record.find("\"decode\":").unwrap() + 9..record.len() - 1];
        assert_eq!(json, expected, "{record}");
        assert_eq!(encoded, frame, "{record}");
        decoded += 1;
    }
    assert!(decoded >= 20, "{decoded} decoded");
}

#[test]
fn every_logged_frame_of_other_protocols_decodes_and_encodes_back() {
    for (dir, protocol, at_least) in [
        ("skytraq", Protocol::Skytraq, 250),
        ("sirf", Protocol::Sirf, 200),
        ("casic", Protocol::Casic, 700),
        ("sbf", Protocol::Sbf, 60),
    ] {
        let frames = frames_of(dir, protocol);
        let mut known = 0;
        for (file, frame) in &frames {
            let (json, encoded) = other_protocol(dir, frame).unwrap_or_else(|err| panic!("{file}: {err}"));
            known += usize::from(!json.starts_with("{\"message\":null"));
            assert_eq!(&encoded, frame, "{file}: {json}");
        }
        assert!(known >= at_least, "{dir}: {known} of {} frames known", frames.len());
    }
}

#[test]
fn errors_of_other_protocols_name_protocol_message_and_field() {
    // SkyTraq 0xA8 (navigation data) cut to 20 bytes after its id.
    let mut payload = vec![0xA8];
    payload.extend_from_slice(&[0; 20]);
    let err = skytraq_messages::Message::decode(&[], &payload).unwrap_err();
    assert_eq!((err.kind, err.field), (UbxErrorKind::ShortPayload, Some("msl_alt")), "{err}");
    assert_eq!(err.to_string(), "short_payload: SKYTRAQ 0xA8: msl_alt needs bytes 20-23, the payload has 20");
    let ok = [0xA0, 0xA2, 0x00, 0x02, 0x12, 0x01, 0x00, 0x13, 0xB0, 0xB3]; // SiRF MID 18, OkToSend
    assert!(matches!(sirf_messages::Message::from_frame(&ok), Ok(sirf_messages::Message::OkToSend(_))));
    let mut bad = ok;
    bad[5] ^= 1;
    let err = sirf_messages::Message::from_frame(&bad).unwrap_err();
    assert_eq!(err.to_string(), "bad_checksum: SIRF: checksum and end 00 13 B0 B3, computed 00 12 B0 B3");
    let err = casic_messages::Message::from_frame(&[0xBA, 0xCF]).unwrap_err();
    assert_eq!(err.to_string(), "bad_sync: CASIC: a CASIC frame starts with BA CE, not BA CF");
    let err = skytraq_messages::Message::from_frame(&ok[..3]).unwrap_err();
    assert_eq!(err.to_string(), "bad_sync: SKYTRAQ: a SKYTRAQ frame starts with A0 A1, not A0 A2");
    let unknown = [0xA0, 0xA1, 0x00, 0x02, 0x7E, 0x01, 0x7F, 0x0D, 0x0A];
    let message = skytraq_messages::Message::from_frame(&unknown).unwrap();
    let mut json = String::new();
    message.write_json(&mut json).unwrap();
    assert_eq!(json, r#"{"message":null,"id":126,"payload":"01"}"#);
    assert_eq!(message.encode(&mut [0u8; 9]).unwrap(), &unknown[..]);
}

#[test]
fn sbf_sub_blocks_are_sblength_bytes() {
    // SatVisibility of two SatInfo sub-blocks of 10 bytes (SBLength): the 2 after the fields kept
    let frame = unhex(
        "24 40 15 cd ac 0f 24 00 e0 52 c9 1c 3f 09 02 0a 03 00 29 1a 96 21 00 02 aa bb 04 00 ab 43 c6 0c 01 01 cc dd",
    );
    let sbf_messages::Message::SatVisibility(mut sky) = sbf_messages::Message::from_frame(&frame).unwrap() else {
        panic!("not a SatVisibility");
    };
    let second = sky.sat_info.get(1).unwrap();
    assert_eq!((sky.sat_info.len(), sky.sat_info.stride(), second.svid, second.trailing), (2, 10, 4, &[0xcc, 0xdd][..]));
    let mut buf = [0u8; 64];
    assert_eq!(sky.encode(&mut buf).unwrap(), &frame[..]);
    sky.sb_length = 8; // the sub-blocks' bytes are 10: not encoded
    let err = sky.encode(&mut buf).unwrap_err();
    assert_eq!((err.kind, err.field), (UbxErrorKind::BadValue, Some("sb_length")), "{err}");
    assert!(err.to_string().ends_with("sb_length takes the bytes of each entry of sat_info (10), not 8"), "{err}");
    let mut short = frame.clone(); // SBLength 4, shorter than a SatInfo's 8 bytes of fields
    short[15] = 4;
    let err = sbf_messages::Message::decode(&short[..8], &short[8..]).unwrap_err();
    assert_eq!(err.to_string(), "bad_value: SBF 4012 rev 0: sb_length is 4, an entry of sat_info takes at least 8 bytes");
}

#[test]
fn sbf_sub_blocks_of_sub_blocks() {
    // MeasEpoch: two Type-1 of 22 bytes (SB1Length), the first followed by two Type-2 of 14
    // (SB2Length), the second by none; each one's 2 bytes after its fields kept (rule B010)
    let frame = unhex("24 40 85 fe bb 2f 5c 00 68 a2 bf 1c 3f 09 02 16 0e 01 0c 00 01 00 11 01 15 cd 5b 07 e0 b1 ff ff f4 01 fd a0 2a 00 01 02 aa bb 02 28 96 f7 ff 01 e8 fd 2c 01 39 30 cc dd 02 28 96 f7 ff 01 e8 fd 2c 01 39 30 ee ff 02 00 05 01 15 cd 5b 07 e0 b1 ff ff f4 01 fd a0 2a 00 01 00 11 22");
    let sbf_messages::Message::MeasEpoch(mut epoch) = sbf_messages::Message::from_frame(&frame).unwrap() else {
        panic!("not a MeasEpoch");
    };
    assert_eq!((epoch.type1.len(), epoch.type1.strides()), (2, (22, 14)));
    let first = epoch.type1.get(0).unwrap();
    let second = first.type2.get(1).unwrap();
    assert_eq!((first.n2, first.type2.len(), first.trailing), (2, 2, &[0xaa, 0xbb][..]));
    assert_eq!((second.code_offset_msb(), second.doppler_offset_msb(), second.trailing), (-1, -2, &[0xee, 0xff][..]));
    assert_eq!(epoch.type1.get(1).map(|t| (t.svid, t.type2.len())), Some((5, 0)));
    let mut buf = [0u8; 128];
    assert_eq!(epoch.encode(&mut buf).unwrap(), &frame[..]);
    epoch.sb2_length = 12; // the Type-2 sub-blocks' bytes are 14: not encoded
    let err = epoch.encode(&mut buf).unwrap_err();
    assert_eq!((err.kind, err.field), (UbxErrorKind::BadValue, Some("sb2_length")), "{err}");
    assert!(err.to_string().ends_with("sb2_length takes the bytes of each entry of type2 (14), not 12"), "{err}");
    let mut short = frame.clone(); // SB2Length 8, shorter than a Type-2's 12 bytes of fields
    short[16] = 8;
    let err = sbf_messages::Message::decode(&short[..8], &short[8..]).unwrap_err();
    assert_eq!(err.to_string(), "bad_value: SBF 4027 rev 1: sb2_length is 8, an entry of type2 takes at least 12 bytes");
}

#[test]
fn sbf_blocks_keep_do_not_use_values_padding_and_crc() {
    use nmeaspec::ais::Reading;
    // ReceiverTime (5914 rev 0) of pysbf2's pygpsdata_x5_time.sbf: 14 bytes of fields, 2 of padding.
    let frame = unhex("24 40 bd 13 1a 17 18 00 70 2f cb 1c 3f 09 19 05 17 0e 0b 00 12 07 00 00");
    let sbf_messages::Message::ReceiverTime(mut time) = sbf_messages::Message::from_frame(&frame).unwrap() else {
        panic!("not a ReceiverTime");
    };
    assert_eq!(
        (time.tow(), time.utc_year(), time.trailing),
        (Reading::Value(483078000), Reading::Value(25), &[0u8, 0][..])
    );
    let mut buf = [0u8; 64];
    assert_eq!(time.encode(&mut buf).unwrap(), &frame[..]);
    // do-not-use values by their id, beside the raw integer; the CRC and length written anew
    time.tow_raw = u32::MAX;
    time.utc_sec_raw = -128;
    assert_eq!((time.tow(), time.utc_sec()), (Reading::Special("do_not_use"), Reading::Special("do_not_use")));
    let again = sbf_messages::Message::from_frame(time.encode(&mut buf).unwrap()).unwrap();
    let mut json = String::new();
    again.write_json(&mut json).unwrap();
    assert!(json.contains(r#""tow":"do_not_use","tow_raw":4294967295,"#), "{json}");
    assert!(json.contains(r#""utc_sec":"do_not_use","utc_sec_raw":-128,"#), "{json}");
    // the float do-not-use value (-2e10) by its id, r4 and r8 alike, the float kept and written back as sent
    let frame = unhex(
        "24 40 71 0e a7 4f 60 00 18 a9 c7 1c 3f 09 06 00 91 82 7c 11 fe ca ed 3f 0d ec d5 a8 9a 13 a4 bf 0f 92 c3 6d \
         f3 65 60 40 4f e9 41 42 5b b9 a0 3a 0b 98 50 ba 73 8e fc 39 f9 02 95 d0 d8 21 db 51 dc c3 b1 3f 7f 8b 4a 3e \
         00 00 24 07 7b 00 16 01 01 01 22 50 01 01 00 00 37 00 66 00 8a 00 60 00",
    );
    let sbf_messages::Message::PvtGeodetic(mut pvt) = sbf_messages::Message::from_frame(&frame).unwrap() else {
        panic!("not a PVTGeodetic");
    };
    assert_eq!((pvt.cog(), pvt.cog_raw), (Reading::Special("do_not_use"), -2e10_f32));
    assert_eq!(pvt.encode(&mut [0u8; 128]).unwrap(), &frame[..]);
    pvt.height_raw = -2e10;
    assert_eq!(pvt.height(), Reading::Special("do_not_use"));
    json.clear();
    sbf_messages::Message::PvtGeodetic(pvt).write_json(&mut json).unwrap();
    assert!(json.contains(r#""height":"do_not_use","#) && json.contains(r#""cog":"do_not_use","#), "{json}");
    // a block number no layout describes: its number and revision, its body as sent
    let unknown = unhex("24 40 16 64 a0 2f 0c 00 01 02 03 04");
    let message = sbf_messages::Message::from_frame(&unknown).unwrap();
    json.clear();
    message.write_json(&mut json).unwrap();
    assert_eq!(json, r#"{"message":null,"number":4000,"revision":1,"payload":"01020304"}"#);
    assert_eq!(message.encode(&mut buf).unwrap(), &unknown[..]);
    let mut bad = frame.clone();
    bad[2] ^= 1;
    assert_eq!(sbf_messages::Message::from_frame(&bad).unwrap_err().kind, UbxErrorKind::BadChecksum);
}

#[test]
fn unicore_messages_keep_their_header_fields() {
    // a decoded message keeps the header's time and status and is encoded with them; one built by
    // hand has them 0 unless set
    let path = Path::new(CRATE).join("../../tests/data/unicore/pyunigps_built.log");
    let log = fs::read(&path).unwrap_or_else(|err| panic!("{}: {err}", path.display()));
    let at = log.windows(6).position(|w| w == [0xaa, 0x44, 0xb5, 0x26, 0x46, 0x08]).expect("BESTNAVB");
    let frame = &log[at..at + 24 + 120 + 4];
    let unicore_messages::Message::BestnavB(best) = unicore_messages::Message::from_frame(frame).unwrap() else {
        panic!("not BESTNAVB")
    };
    assert_eq!((best.header.cpu_idle, best.header.week, best.header.time_of_week), (38, 2407, 123_457_250));
    let mut buf = [0u8; 256];
    assert_eq!(best.encode(&mut buf).unwrap(), frame);
    let plain = unicore_messages::BestnavB { header: unicore_messages::Header::default(), ..best };
    let encoded = plain.encode(&mut buf).unwrap().to_vec();
    assert_eq!(encoded[8..24], [0u8; 16]);
    let dated = unicore_messages::BestnavB { header: unicore_messages::Header { week: 2407, ..plain.header }, ..plain };
    let encoded = dated.encode(&mut buf).unwrap().to_vec();
    assert_eq!(unicore_messages::Message::from_frame(&encoded).unwrap(), unicore_messages::Message::BestnavB(dated));
}
