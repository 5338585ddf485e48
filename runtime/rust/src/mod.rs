//! The hand-written runtime under the generated sentence modules: framing and checksum, field
//! splitting, the field types, the error type, JSON writing, configuration parameter tables and
//! (with `std`) JSON reading.
//!
//! Its rules (what text each field type accepts, the error messages, the JSON form) are the
//! Python and C runtimes' rules byte for byte; see docs/json.md.
//!
//! The generated code reaches it through the names below; the crate root re-exports to users only
//! the public API (runtime/README.md lists it). The parser and the tools' JSON ([`parse`],
//! [`write_decoded`], `Rebuilt`) hold for any spec: they work through [`Layouts`], which the
//! generated `LayoutId` implements, and [`Decoded`], which the generated `Sentence` implements.

mod error;
mod fast;
mod frame;
mod framings;
mod layout;
mod parse;
mod repr;
mod table;
mod tag;
mod tools;
mod types;
mod values;
mod write;

#[cfg(feature = "serde")]
mod serialize;

pub mod ais;
pub mod assembly;
pub mod rtcm3;
pub mod stream;
pub mod ubx;

#[cfg(feature = "std")]
pub mod fixes;
#[cfg(feature = "std")]
pub mod json;

pub use error::{Error, ErrorKind, FieldProblem, Name, ProblemKind, Problems};
pub use fast::{FastReader, Read};
// Text commands compile with their receivers' features only.
#[allow(unused_imports)]
pub use frame::is_command_word;
pub use frame::{Fields, GroupShape, Reader, Shape, MAX_LINE, MAX_PROBLEMS};
pub use layout::{build, Framing, Generic, JsonMember, Kind, Layout, ReplyOutcome, BUILD_CAPACITY};
pub use parse::{
    parse, parse_fast, parse_general, parse_with, parse_with_general, read_layout, Decoded, Layouts, Options, Outcome,
    Parsed,
};
pub use table::{Encoding, ParamValue, Parameter, ParameterError, Problem, Table};
pub use tag::{write_tag_block, TagBlock, TagBlocks, TagCode, TagType};
#[cfg(feature = "std")]
pub use tools::{decode_json, decode_json_with, encode_json, write_encoded, Rebuilt};
pub use tools::{write_decoded, write_decoded_with};
pub use types::{
    Bound, Checksum, Code, CodeChars, CodeClass, CodeEnum, Coordinate, Date, Entries, EntryIter, Hex, Number, Range,
    Sign, Texts, Time,
};
pub use values::{days_from_civil, DateTime, NotWhole, PIVOT_YEAR};
pub use write::{Entry, FieldSink};
