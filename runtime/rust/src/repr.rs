//! Python's `repr` of a double, which its `json` module writes too: the one way the tools' JSON
//! prints a float in Rust (AIS, binary messages, fixes), as `runtime/c/repr.c` does in C.

use core::fmt::{self, Write};

/// Writes `value` as Python's `repr` does: the fewest significant digits that read back the
/// same; of those the closest to the value (a tie to even), `.0` on whole values, positional from
/// 1e-4 to below 1e16, else `d.ddde-XX` with two exponent digits or more; `inf`, `-inf`, `nan`.
pub fn write_repr<W: Write + ?Sized>(out: &mut W, value: f64) -> fmt::Result {
    if !value.is_finite() {
        return out.write_str(if value.is_nan() {
            "nan"
        } else if value > 0.0 {
            "inf"
        } else {
            "-inf"
        });
    }
    // The shortest digits that read back (of those, Rust picks one close to the value) ...
    let mut shortest = Digits { buf: [0; 40], len: 0 };
    write!(shortest, "{value:e}")?;
    let count = shortest.as_str()?.split('e').next().unwrap_or("").bytes().filter(u8::is_ascii_digit).count();
    // ... and as many rounded from the exact value (a tie to even), which Python takes when it
    // reads back (it may not: a power of two's lower neighbour is nearer).
    let mut rounded = Digits { buf: [0; 40], len: 0 };
    write!(rounded, "{value:.*e}", count.saturating_sub(1))?;
    let text = if rounded.as_str()?.parse::<f64>() == Ok(value) { rounded.as_str()? } else { shortest.as_str()? };
    let (mantissa, exponent) = text.split_once('e').ok_or(fmt::Error)?;
    let exponent: i32 = exponent.parse().map_err(|_| fmt::Error)?;
    let (sign, mantissa) = mantissa.strip_prefix('-').map_or(("", mantissa), |m| ("-", m));
    let (first, rest) = mantissa.split_once('.').unwrap_or((mantissa, ""));
    if !(-4..16).contains(&exponent) {
        let point = if rest.is_empty() { "" } else { "." };
        let esign = if exponent < 0 { "-" } else { "+" };
        return write!(out, "{sign}{first}{point}{rest}e{esign}{:02}", exponent.unsigned_abs());
    }
    out.write_str(sign)?;
    if exponent < 0 {
        out.write_str("0.")?;
        (1..-exponent).try_for_each(|_| out.write_char('0'))?;
        return write!(out, "{first}{rest}");
    }
    let whole = exponent.unsigned_abs() as usize; // digits after the first one before the point
    out.write_str(first)?;
    if rest.len() <= whole {
        out.write_str(rest)?;
        (rest.len()..whole).try_for_each(|_| out.write_char('0'))?;
        return out.write_str(".0");
    }
    write!(out, "{}.{}", &rest[..whole], &rest[whole..])
}

/// A number's digits on the stack.
struct Digits {
    buf: [u8; 40],
    len: usize,
}

impl Digits {
    fn as_str(&self) -> Result<&str, fmt::Error> {
        core::str::from_utf8(&self.buf[..self.len]).map_err(|_| fmt::Error)
    }
}

impl Write for Digits {
    fn write_str(&mut self, s: &str) -> fmt::Result {
        let slot = self.buf.get_mut(self.len..self.len + s.len()).ok_or(fmt::Error)?;
        slot.copy_from_slice(s.as_bytes());
        self.len += s.len();
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::write_repr;
    extern crate std;
    use std::string::String;

    #[test]
    fn doubles_are_written_as_pythons_repr() {
        let cases = [
            (0.0, "0.0"),
            (-0.0, "-0.0"),
            (1e-5, "1e-05"),
            (0.0001, "0.0001"),
            (0.000123, "0.000123"),
            (1e16, "1e+16"),
            (1.5e16, "1.5e+16"),
            (1e22, "1e+22"),
            (-2.5e-300, "-2.5e-300"),
            (100.0, "100.0"),
            (123456789.0, "123456789.0"),
            (1234567890123456.0, "1234567890123456.0"),
            (9999999999999998.0, "9999999999999998.0"),
            (12.3, "12.3"),
            (-4850729.7108, "-4850729.7108"),
            (-0.16135025024414062, "-0.16135025024414062"),
            (-1.862645149230957e-09, "-1.862645149230957e-09"),
            // A power of two whose correctly rounded 16 digits read back another double.
            (-5.960464477539063e-08, "-5.960464477539063e-08"),
            (5e-324, "5e-324"),
            (f64::MAX, "1.7976931348623157e+308"),
            // A float widened to a double, halfway between two 17-digit decimals: ties to even.
            (f64::from(3.912_788_4_f32), "3.9127883911132812"),
            (f64::NEG_INFINITY, "-inf"),
            (f64::NAN, "nan"),
        ];
        for (value, text) in cases {
            let mut out = String::new();
            write_repr(&mut out, value).unwrap();
            assert_eq!(out, text, "{value:e}");
        }
    }
}
