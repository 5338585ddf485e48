//! Receivers' tables of configuration parameters (ST's CDB, read and written with
//! `$PSTMGETPAR` / `$PSTMSETPAR`) and the wire text of a parameter's value.

use core::cmp::Ordering;
use core::fmt::{self, Write};

use super::types::{Bound, CodeEnum, Number, Range, Sign};

/// How a parameter's value is written on the wire.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Encoding {
    /// Upper-case hex digits without `0x`.
    Hex,
    /// A decimal number.
    Decimal,
    /// `count` decimal numbers, one wire field each.
    DecimalList,
    /// Plain text.
    Text,
}

impl Encoding {
    /// The spec's name: `hex`, `decimal`, `decimal_list` or `text`.
    pub const fn as_str(self) -> &'static str {
        match self {
            Self::Hex => "hex",
            Self::Decimal => "decimal",
            Self::DecimalList => "decimal_list",
            Self::Text => "text",
        }
    }
}

/// One parameter of a receiver's configuration table and how its value is written.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Parameter {
    /// The parameter ID on the wire.
    pub number: u32,
    /// The spec's frozen name.
    pub id: &'static str,
    /// Display name.
    pub name: &'static str,
    /// How the value is written.
    pub encoding: Encoding,
    /// Bytes in the block (a hex value must fit them).
    pub size: Option<u8>,
    /// Values of a decimal list.
    pub count: Option<u8>,
    /// The least value allowed.
    pub min: Option<Bound>,
    /// The greatest value allowed.
    pub max: Option<Bound>,
    /// Longest text.
    pub max_length: Option<usize>,
    /// The default value as written on the wire.
    pub default: Option<&'static str>,
    /// Unit of the value.
    pub unit: Option<&'static str>,
    /// The spec id of the enum whose codes are the values (in [`crate::enums`]).
    pub enum_id: Option<&'static str>,
    /// The spec id of the bitfield that names the value's bits (in `crate::bitfields`).
    pub bitfield_id: Option<&'static str>,
}

/// A value to write into a parameter.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ParamValue<'v> {
    /// The number of a hex parameter (an enum code's or a bitfield's value too).
    Unsigned(u64),
    /// The value of a decimal parameter.
    Number(Number),
    /// The values of a decimal list.
    Numbers(&'v [Number]),
    /// The text of a text parameter.
    Text(&'v str),
}

impl ParamValue<'_> {
    /// The number an enum code stands for in a hex parameter (`None` when the code is not hex).
    pub fn from_code<E: CodeEnum>(value: E) -> Option<Self> {
        u64::from_str_radix(value.code(), 16).ok().map(Self::Unsigned)
    }
}

/// Why a value cannot be written into a parameter.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum Problem<'v> {
    /// The value is not of the kind the encoding takes.
    WrongKind,
    /// A hex value does not fit the parameter's bytes.
    DoesNotFit(u64),
    /// Below the least value.
    Below(ParamValue<'v>, Bound),
    /// Above the greatest value.
    Above(ParamValue<'v>, Bound),
    /// A decimal list of the wrong length.
    Count(usize),
    /// A text over the longest length.
    TooLong,
    /// A text holding `,`, `*`, `$`, `!` or a byte outside printable ASCII.
    BadText,
    /// The buffer cannot hold the text: it needs this many bytes.
    BufferTooSmall(usize),
}

/// Why a value cannot be written into a parameter; `Display` names the parameter.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ParameterError<'v> {
    /// The parameter.
    pub parameter: &'static Parameter,
    /// What is wrong.
    pub problem: Problem<'v>,
}

impl fmt::Display for ParameterError<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let p = self.parameter;
        write!(f, "parameter {} ({}): ", p.number, p.id)?;
        match self.problem {
            Problem::WrongKind => write!(f, "a {} parameter cannot take this value", p.encoding.as_str()),
            Problem::DoesNotFit(value) => write!(f, "{value} does not fit {} byte(s)", p.size.unwrap_or(0)),
            Problem::Below(value, bound) => write!(f, "{} is below {}", Shown(value), Plain(bound)),
            Problem::Above(value, bound) => write!(f, "{} is above {}", Shown(value), Plain(bound)),
            Problem::Count(got) => write!(f, "expected {} values, got {got}", p.count.unwrap_or(0)),
            Problem::TooLong => write!(f, "text longer than {}", p.max_length.unwrap_or(0)),
            Problem::BadText => f.write_str("text holds ',', '*', '$', '!' or a byte outside printable ASCII"),
            Problem::BufferTooSmall(needed) => write!(f, "the text needs {needed} bytes"),
        }
    }
}

#[cfg(feature = "std")]
impl std::error::Error for ParameterError<'_> {}

struct Shown<'v>(ParamValue<'v>);

impl fmt::Display for Shown<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.0 {
            ParamValue::Unsigned(value) => write!(f, "{value}"),
            ParamValue::Number(number) => write_decimal(f, number),
            ParamValue::Numbers(_) | ParamValue::Text(_) => Ok(()),
        }
    }
}

struct Plain(Bound);

impl fmt::Display for Plain {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let Bound { digits, scale } = self.0;
        let number = Number {
            digits: digits.abs(),
            scale,
            width: 1,
            sign: if digits < 0 { Sign::Minus } else { Sign::Implicit },
            point: false,
        };
        write_decimal(f, number)
    }
}

/// Writes a number as Python's `str(Decimal(...))` does: no leading zeros, the decimals as
/// given, scientific notation for very small numbers (`1E-7`).
fn write_decimal<W: Write + ?Sized>(w: &mut W, number: Number) -> fmt::Result {
    let mut buf = [0u8; 20];
    let mut len = 0;
    let mut value = number.digits.unsigned_abs();
    loop {
        buf[len] = b'0' + (value % 10) as u8;
        len += 1;
        value /= 10;
        if value == 0 {
            break;
        }
    }
    buf[..len].reverse();
    let digits = core::str::from_utf8(&buf[..len]).map_err(|_| fmt::Error)?;
    let exponent = -i32::from(number.scale);
    let left = exponent + len as i32;
    let dot = if left > -6 { left } else { 1 };
    if number.is_negative() {
        w.write_char('-')?;
    }
    if dot <= 0 {
        w.write_str("0.")?;
        (0..-dot).try_for_each(|_| w.write_char('0'))?;
        w.write_str(digits)?;
    } else if dot as usize >= len {
        w.write_str(digits)?;
        (len..dot as usize).try_for_each(|_| w.write_char('0'))?;
    } else {
        let (whole, frac) = digits.split_at(dot as usize);
        write!(w, "{whole}.{frac}")?;
    }
    if left != dot {
        write!(w, "E{:+}", left - dot)?;
    }
    Ok(())
}

/// Compares a bound with a whole number exactly.
fn cmp_unsigned(bound: Bound, value: u64) -> Ordering {
    let scaled = i128::from(value) * 10i128.pow(u32::from(bound.scale));
    i128::from(bound.digits).cmp(&scaled)
}

impl Parameter {
    /// Writes the wire text of `value` into `buf` and returns it: upper-case hex without `0x`,
    /// a decimal number, decimal numbers joined by `,` (one wire field each), or the text; as
    /// the Python runtime's `Parameter.encode` does. Refuses a value of the wrong kind, out of
    /// range, too big for the parameter's bytes, a list of the wrong length, a text too long or
    /// holding `,`, `*`, `$`, `!` or a byte outside printable ASCII.
    pub fn encode<'b, 'v>(
        &'static self,
        value: ParamValue<'v>,
        buf: &'b mut [u8],
    ) -> Result<&'b str, ParameterError<'v>> {
        let fail = |problem| ParameterError { parameter: self, problem };
        let mut out = Out { buf, len: 0, needed: 0 };
        match (self.encoding, value) {
            (Encoding::Hex, ParamValue::Unsigned(number)) => {
                if let Some(min) = self.min.filter(|&min| cmp_unsigned(min, number) == Ordering::Greater) {
                    return Err(fail(Problem::Below(value, min)));
                }
                if let Some(max) = self.max.filter(|&max| cmp_unsigned(max, number) == Ordering::Less) {
                    return Err(fail(Problem::Above(value, max)));
                }
                if self.size.is_some_and(|size| u128::from(number) >> (8 * u32::from(size)) != 0) {
                    return Err(fail(Problem::DoesNotFit(number)));
                }
                let _ = write!(out, "{number:X}");
            }
            (Encoding::Decimal, ParamValue::Number(number)) => {
                self.check_range(number, value).map_err(fail)?;
                let _ = write_decimal(&mut out, number);
            }
            (Encoding::DecimalList, ParamValue::Numbers(numbers)) => {
                if self.count.is_some_and(|count| usize::from(count) != numbers.len()) {
                    return Err(fail(Problem::Count(numbers.len())));
                }
                for (i, &number) in numbers.iter().enumerate() {
                    self.check_range(number, ParamValue::Number(number)).map_err(fail)?;
                    if i > 0 {
                        let _ = out.write_char(',');
                    }
                    let _ = write_decimal(&mut out, number);
                }
            }
            (Encoding::Text, ParamValue::Text(text)) => {
                if self.max_length.is_some_and(|max| text.chars().count() > max) {
                    return Err(fail(Problem::TooLong));
                }
                if !text.bytes().all(|b| (0x20..=0x7e).contains(&b) && !b",*$!".contains(&b)) {
                    return Err(fail(Problem::BadText));
                }
                let _ = out.write_str(text);
            }
            _ => return Err(fail(Problem::WrongKind)),
        }
        if out.needed > out.buf.len() {
            return Err(fail(Problem::BufferTooSmall(out.needed)));
        }
        let Out { buf, len, .. } = out;
        core::str::from_utf8(&buf[..len]).map_err(|_| fail(Problem::BadText))
    }

    /// The problem when `number` (shown as `value`) is outside the parameter's range.
    fn check_range<'v>(&self, number: Number, value: ParamValue<'v>) -> Result<(), Problem<'v>> {
        if let Some(min) = self.min.filter(|&min| !Range::at_least(min).contains(number)) {
            return Err(Problem::Below(value, min));
        }
        if let Some(max) = self.max.filter(|&max| !Range::at_most(max).contains(number)) {
            return Err(Problem::Above(value, max));
        }
        Ok(())
    }
}

/// Writes ASCII text into a byte buffer and counts what does not fit.
struct Out<'b> {
    buf: &'b mut [u8],
    len: usize,
    needed: usize,
}

impl Write for Out<'_> {
    fn write_str(&mut self, s: &str) -> fmt::Result {
        self.needed += s.len();
        if let Some(room) = self.buf.get_mut(self.len..self.len + s.len()) {
            room.copy_from_slice(s.as_bytes());
            self.len += s.len();
        }
        Ok(())
    }
}

/// A table of configuration parameters.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Table {
    /// The spec id.
    pub id: &'static str,
    /// Display name.
    pub name: &'static str,
    /// Every parameter, in the spec's order.
    pub parameters: &'static [Parameter],
}

impl Table {
    /// The parameter with ID `number`.
    pub fn get(&self, number: u32) -> Option<&'static Parameter> {
        self.parameters.iter().find(|p| p.number == number)
    }

    /// The parameter named `id`.
    pub fn find(&self, id: &str) -> Option<&'static Parameter> {
        self.parameters.iter().find(|p| p.id == id)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const HEX: Parameter = Parameter {
        number: 102,
        id: "baud",
        name: "Baud",
        encoding: Encoding::Hex,
        size: Some(1),
        count: None,
        min: None,
        max: Some(Bound::int(200)),
        max_length: None,
        default: None,
        unit: None,
        enum_id: None,
        bitfield_id: None,
    };
    const LIST: Parameter = Parameter { number: 400, encoding: Encoding::DecimalList, count: Some(2), ..HEX };

    #[test]
    fn values_are_written_as_python_writes_them() {
        let mut buf = [0u8; 32];
        assert_eq!(HEX.encode(ParamValue::Unsigned(0xab), &mut buf), Ok("AB"));
        let err = HEX.encode(ParamValue::Unsigned(201), &mut buf).unwrap_err();
        assert_eq!(err.problem, Problem::Above(ParamValue::Unsigned(201), Bound::int(200)));
        let numbers = [Number::parse("007.50", false).unwrap(), Number::parse("0.0000001", false).unwrap()];
        assert_eq!(LIST.encode(ParamValue::Numbers(&numbers), &mut buf), Ok("7.50,1E-7"));
        let err = LIST.encode(ParamValue::Numbers(&numbers[..1]), &mut buf).unwrap_err();
        assert_eq!(err.problem, Problem::Count(1));
        assert_eq!(LIST.encode(ParamValue::Text("x"), &mut buf).unwrap_err().problem, Problem::WrongKind);
        let mut small = [0u8; 3];
        let err = LIST.encode(ParamValue::Numbers(&numbers), &mut small).unwrap_err();
        assert_eq!(err.problem, Problem::BufferTooSmall(9));
    }
}
