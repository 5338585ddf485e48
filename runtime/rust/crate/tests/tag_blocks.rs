//! TAG blocks against generated/vectors/tag_blocks.jsonl, which tests/agreement holds the three
//! tools to: each line decodes to its JSON and a good one encodes back to the line; then the API
//! that reads the parameters and builds a block.

use std::fs;
use std::path::Path;

use nmeaspec::json::{decode_json, encode_json, Value};
use nmeaspec::{parse_with, write_tag_block, Options, Sentence, TAG_CODES};

const CRATE: &str = env!("CARGO_MANIFEST_DIR");

fn text<'v>(record: &'v Value, key: &str) -> &'v str {
    match record.get(key) {
        Some(Value::String(text)) => text,
        _ => panic!("no {key}"),
    }
}

#[test]
fn tag_blocks_agree_with_the_vectors() {
    let path = Path::new(CRATE).join("../vectors/tag_blocks.jsonl");
    let data = fs::read_to_string(&path).unwrap_or_else(|err| panic!("{}: {err}", path.display()));
    for record in data.lines().map(|line| Value::parse(line.as_bytes()).unwrap()) {
        let (line, decode) = (text(&record, "line"), text(&record, "decode"));
        assert_eq!(decode_json(line.as_bytes(), false), decode, "{line}");
        if decode.starts_with(r#"{"ok":true"#) {
            assert_eq!(encode_json(decode.as_bytes()), line);
        }
    }
}

#[test]
fn a_line_keeps_its_tag_blocks() {
    let line = "\\g:1-2-73874,n:157036,s:r003669945,c:1241544035*4A\\!AIVDM,1,1,,B,15N4cJ`005Jrek0H@9n`DW5608EP,0*13";
    let parsed = parse_with(line, Options::default()).unwrap();
    assert!(matches!(parsed.sentence, Sentence::Vdm(_)));
    assert_eq!(parsed.tag_blocks.get("s"), Some("r003669945"));
    assert_eq!(parsed.tag_blocks.get("g"), Some("1-2-73874"));
    assert_eq!(parsed.to_string(), line);
    assert!(TAG_CODES.iter().any(|code| code.code == "c" && code.id == "time"));

    let mut buf = [0; 128];
    let len = write_tag_block(&mut buf, &[("s", "r003669945"), ("c", "1241544035")], false).unwrap();
    assert_eq!(&buf[..len], b"\\s:r003669945,c:1241544035*79\\");
    assert!(write_tag_block(&mut buf, &[("g", "1-2")], false).is_err());
}
