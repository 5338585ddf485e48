//! The value accessors against generated/vectors/values.jsonl, which tests/agreement/test_values.py
//! holds the Python and C runtimes to: every number, coordinate, time, date, and date and time of
//! the manuals' examples plus edge cases, as doubles (the same bits), degrees × 10^7,
//! milliseconds of the day, days and milliseconds since 1970. Then the sentence-level accessors.

use std::fs;
use std::path::Path;
use std::str::FromStr;

use nmeaspec::{days_from_civil, Coordinate, Date, DateTime, Number, Sentence, Time};

const CRATE: &str = env!("CARGO_MANIFEST_DIR");

/// The text of a member of a flat JSON record (a string's without its quotes; none of the
/// vectors' strings holds a comma, quote or backslash).
fn member<'r>(record: &'r str, key: &str) -> &'r str {
    let start = record.find(&format!("\"{key}\":")).unwrap_or_else(|| panic!("no {key} in {record}")) + key.len() + 3;
    let rest = &record[start..];
    rest[..rest.find([',', '}']).unwrap_or(rest.len())].trim_matches('"')
}

fn number<T: FromStr>(record: &str, key: &str) -> Option<T> {
    let text = member(record, key);
    (text != "null").then(|| text.parse().unwrap_or_else(|_| panic!("{key} of {record}")))
}

/// A double of the vectors (the shortest text that reads back as it), as bits.
fn bits(record: &str, key: &str) -> u64 {
    number::<f64>(record, key).unwrap().to_bits()
}

#[test]
fn values_agree_with_the_vectors() {
    let path = Path::new(CRATE).join("../vectors/values.jsonl");
    let data = fs::read_to_string(&path).unwrap_or_else(|err| panic!("{}: {err}", path.display()));
    for record in data.lines() {
        let text = || member(record, "text");
        match member(record, "type") {
            "number" => {
                let n = Number::parse(text(), false).unwrap();
                assert_eq!(f64::from(n).to_bits(), bits(record, "double"), "{record}");
                assert_eq!(f64::from(n.to_f32()).to_bits(), bits(record, "float"), "{record}");
                assert_eq!(Some(n.trunc()), number(record, "int"), "{record}");
            }
            kind @ ("latitude" | "longitude") => {
                let (digits, max) = if kind == "latitude" { (2, 90) } else { (3, 180) };
                let mut c = Coordinate::parse(text(), digits, max).unwrap();
                c.hemisphere = member(record, "hemisphere").chars().next().unwrap();
                assert_eq!(f64::from(c).to_bits(), bits(record, "degrees"), "{record}");
                assert_eq!(Some(c.degrees_e7()), number(record, "e7"), "{record}");
            }
            "time" => assert_eq!(Some(Time::parse(text()).unwrap().ms_of_day()), number(record, "ms"), "{record}"),
            "date" => {
                let d = Date::parse(text()).unwrap();
                assert_eq!(Some(d.full_year()), number(record, "full_year"), "{record}");
                assert_eq!(d.days_since_epoch(), number(record, "days"), "{record}");
            }
            "datetime" => {
                let (d, t) = (Date::parse(member(record, "date")), Time::parse(member(record, "time")));
                let when = DateTime::of_date(d.unwrap(), t.unwrap());
                assert_eq!(when.map(DateTime::timestamp_ms), number(record, "ms"), "{record}");
            }
            "civil" => {
                let [year, month, day] = ["year", "month", "day"].map(|k| number::<i32>(record, k).unwrap());
                let days = days_from_civil(year, month as u8, day as u8);
                assert_eq!(days, number(record, "days"), "{record}");
            }
            kind => panic!("unknown type {kind}"),
        }
    }
}

#[test]
fn sentences_give_their_position_and_date_and_time() {
    let Ok(Sentence::Rmc(rmc)) = nmeaspec::parse("$GPRMC,225446,A,4916.45,N,12311.12,W,000.5,054.7,191194,020.3,E*68")
    else {
        panic!("not RMC")
    };
    assert_eq!((rmc.latitude(), rmc.longitude()), (Some(49.274166666666666), Some(-123.18533333333333)));
    assert_eq!(rmc.datetime().map(DateTime::timestamp_ms), Some(785_285_686_000));
    let Ok(Sentence::Zda(zda)) = nmeaspec::parse("$GPZDA,181813,14,10,2003,,*4F") else { panic!("not ZDA") };
    assert_eq!(zda.datetime().map(DateTime::timestamp_ms), Some(1_066_155_493_000));
}
