//! The hand-written runtime under the generated sentence modules: framing and checksum, field
//! splitting, the field types, the error type, JSON writing, configuration parameter tables and
//! (with `std`) JSON reading.
//!
//! Its rules (what text each field type accepts, the error messages, the JSON form) are the
//! Python and C runtimes' rules byte for byte; see docs/json.md.

mod error;
mod fast;
mod frame;
mod layout;
mod table;
mod types;
mod write;

#[cfg(feature = "serde")]
mod serialize;

pub mod stream;

#[cfg(feature = "std")]
pub mod json;

pub use error::{Error, ErrorKind, FieldProblem, Message, Name, Problems};
pub use fast::{FastReader, Read, Unsure};
pub use frame::{
    checksum, first_word, is_command_word, is_standard_address, Blanks, FieldIter, Fields, Frame, GroupShape, Reader,
    Shape, MAX_LINE, MAX_PROBLEMS,
};
pub use layout::{build, strip_line_ending, Framing, Generic, JsonMember, Kind, Layout, ReplyOutcome, BUILD_CAPACITY};
pub use table::{Encoding, ParamValue, Parameter, ParameterError, Problem, Table};
pub use types::{
    upper_eq, Ascii, Bound, Checksum, Code, CodeChars, CodeClass, CodeEnum, Coordinate, Date, Entries, EntryIter, Hex,
    Number, Range, ReadEntry, Sign, Texts, Time, MAX_DIGITS,
};
pub use write::{
    write_json_char, write_json_display, write_json_str, write_sentence, write_sentence_with, write_words_json,
    ByteWriter, Discard, Entry, FieldSink, FieldValue, JsonEscape, JsonFields, Latin1Bytes, SameUpper, WireWriter,
};
