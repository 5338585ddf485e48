//! `Serialize` for the field types (feature `serde`), in the form `decode --values` prints: a
//! number as a number, a time `hh:mm:ss.ss`, a date `yy-mm-dd`, a latitude or longitude as
//! signed decimal degrees, an enum field as its spec id (or the code the spec does not list), a
//! repeated group as a list. No allocation: it works without `std`.

use core::fmt;

use serde::ser::{Serialize, SerializeStruct, Serializer};

use super::{
    Checksum, Code, CodeChars, CodeEnum, Coordinate, Date, Entries, Fields, Generic, Hex, Number, Texts, Time,
};

impl Serialize for Number {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        if self.scale == 0 {
            serializer.serialize_i64(self.signed_digits())
        } else {
            serializer.serialize_f64(self.to_f64())
        }
    }
}

impl Serialize for Hex {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        serializer.serialize_u64(self.value)
    }
}

/// The fraction of a time as written, point included (`.05`), or nothing.
struct Fraction(Time);

impl fmt::Display for Fraction {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.0.point {
            f.write_str(".")?;
            if self.0.fraction_digits > 0 {
                super::types::write_digits(f, u64::from(self.0.fraction), usize::from(self.0.fraction_digits))?;
            }
        }
        Ok(())
    }
}

impl Serialize for Time {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        serializer.collect_str(&format_args!(
            "{:02}:{:02}:{:02}{}",
            self.hour,
            self.minute,
            self.second,
            Fraction(*self)
        ))
    }
}

impl Serialize for Date {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        serializer.collect_str(&format_args!("{:02}-{:02}-{:02}", self.year, self.month, self.day))
    }
}

impl Serialize for Coordinate {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        serializer.serialize_f64(self.to_degrees())
    }
}

impl<E: CodeEnum> Serialize for Code<'_, E> {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        serializer.serialize_str(self.id())
    }
}

impl<E: CodeEnum> Serialize for CodeChars<'_, E> {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        serializer.collect_seq(self.iter().map(|code| code.id()))
    }
}

impl Serialize for Texts<'_> {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        serializer.collect_seq(self.iter())
    }
}

impl<T: Serialize + Copy + Default> Serialize for Entries<'_, T> {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        serializer.collect_seq(self.iter())
    }
}

impl Serialize for Fields<'_> {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        serializer.collect_seq(self.iter())
    }
}

impl Serialize for Checksum {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        let (index, name) = match self {
            Self::Upper => (0, "Upper"),
            Self::Lower => (1, "Lower"),
            Self::Empty => (2, "Empty"),
            Self::None => (3, "None"),
            Self::ShortUpper => (4, "ShortUpper"),
            Self::ShortLower => (5, "ShortLower"),
        };
        serializer.serialize_unit_variant("Checksum", index, name)
    }
}

impl Serialize for Generic<'_> {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        let mut out = serializer.serialize_struct("Generic", 4)?;
        out.serialize_field("start", self.start)?;
        out.serialize_field("address", self.address)?;
        out.serialize_field("fields", &self.fields)?;
        out.serialize_field("checksum", &self.checksum)?;
        out.end()
    }
}
