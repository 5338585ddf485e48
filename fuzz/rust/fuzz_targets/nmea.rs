//! Each input is tried as an NMEA line and as a line of decode's JSON. A line that parses must
//! write back to exactly its bytes and its lossless JSON must encode back to them too; nothing
//! may panic.
#![no_main]
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    if let Ok(sentence) = nmeaspec::parse(data) {
        if !data.ends_with(b"\n") {
            let text = sentence.to_string();
            assert_eq!(text.as_bytes(), data, "round trip changed the line");
            let json = sentence.to_json(false);
            let _ = sentence.to_json(true);
            assert_eq!(nmeaspec::encode_json(json.as_bytes()).as_bytes(), data, "JSON round trip changed the line");
        }
    }
    let _ = nmeaspec::decode_json(data, true);
    let _ = nmeaspec::encode_json(data);
});
